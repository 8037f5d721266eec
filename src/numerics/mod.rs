//! Numerical helpers that know nothing of pounding: [`linalg`] (dot products for the hot
//! loops), [`hermite`] (the cubic Hermite interpolant: basis, roots, maxima) and
//! [`format`](mod@format) (numbers as text); `vex`, whether the hot passes run their copies
//! compiled for AVX.

pub mod format;
pub mod hermite;
pub(crate) mod lanes;
pub mod linalg;
pub(crate) mod vex;
