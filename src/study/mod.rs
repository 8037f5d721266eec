//! Studies over many runs.

pub mod rule_study;
pub mod sweep;
pub mod suite;
