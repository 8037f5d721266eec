//! Numerical helpers that know nothing of pounding: [`linalg`] (dot products for the hot
//! loops) and [`format`](mod@format) (numbers as text).

pub mod format;
pub mod linalg;
