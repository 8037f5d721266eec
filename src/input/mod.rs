//! What the user gives.

pub mod file;
pub mod fragility;
pub mod scenario;
