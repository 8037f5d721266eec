//! Exponential Lobatto collocation of the contact forces over a step: the embedded pair that
//! `exact-modal` integrates contact with (docs/model.md §2.9; README, *Solver methods and speed*).
//!
//! Over a step of length h every level's contact force is the polynomial through its values at
//! the Lobatto nodes; each mode's response to a polynomial load is exact (the tables below,
//! per mode and step length), so the penetrations at the nodes are an affine function of the
//! nodal forces through small level×level tables, and the nodal forces solve the contact law at
//! the nodal states (Newton's method in those few unknowns, with the law's exact Jacobian).
//! Two such schemes on one step:
//!
//! - **the propagated one**: 5 Lobatto nodes θ = 0, ½ ∓ √(3/7)/2, ½, 1, the force a quartic —
//!   order 8 at the step's end (Lobatto IIIA, s = 5: 2s − 2; exact without contact);
//! - **its companion**: 4 nodes θ = 0, ½ ∓ 1/(2√5), 1, the force a cubic — order 6.
//!
//! The distance between the two ends is the companion's local error to within the propagated
//! one's (O(h⁹) against O(h⁷)), and it is what the step size is chosen by: an estimate that,
//! unlike a formula on one solution, solves the contact law itself, so it sees the contact's
//! stiffness, its onset and release and any kink of the law. The state kept is the eighth-order
//! one (local extrapolation, as in the Dormand–Prince pair): its error is the estimate's at
//! most and far below it on a smooth stretch — an upper bound, tested against the true local
//! error of both solutions (`exact_modal::elastic` tests).
//!
//! Everything that depends on the step length only is in [`Table`] (propagators to the nodes,
//! every mode's response to the Lagrange loads, the level tables); steps take lengths from a
//! quantised set so that the tables are computed once per length.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

mod newton;
mod nodes;
mod table;
#[cfg(test)]
mod tests;

pub(super) use newton::{Newton, NoConvergence, nodal_states, solve, solve_single, start_force};
pub(super) use nodes::{NODES, NODES6, NODES8, THETA8, WEIGHTS8, bases};
pub(super) use table::{ModeStep, Table};
