//! Studies over many runs.

pub mod rule_study;
pub mod suite;
pub mod sweep;
