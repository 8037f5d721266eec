//! What the building codes define.

pub mod rules;
pub mod spectrum;
