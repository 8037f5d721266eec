//! Numerical helpers that know nothing of pounding: [`linalg`] (dot products for the hot
//! loops) and [`format`] (numbers as short labels).

pub mod format;
pub mod linalg;
