//! What the user gives.

pub mod file;
pub mod scenario;
