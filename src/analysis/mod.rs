//! Drivers of the solver and what is computed from runs.

pub mod convergence;
pub mod gap_report;
pub mod level_checks;
pub mod record_spectrum;
pub mod restitution;
pub mod row_separation;
pub mod separation;
pub mod simulate;
