//! Studies over many runs.

pub mod fragility;
pub mod rule_study;
pub mod suite;
pub mod sweep;
