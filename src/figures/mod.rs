//! The project's pictures, drawn with [`crate::plot`].

pub mod fragility;
pub mod row;
pub mod rules;
pub mod run;
pub mod spectrum;
pub mod suite;
pub mod sweep;
