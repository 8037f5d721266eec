//! # pounding
//!
//! Seismic pounding of two adjacent structures: each a continuous Euler–Bernoulli cantilever
//! reduced to its modes, shaken by a common ground motion, hitting each other through a contact
//! law at one or more heights. Library first; the `pounding` binary is a thin CLI over it.
//!
//! The model, its equations and its corrections to the seed paper are in `docs/model.md`
//! (sections cited in the code as `docs/model.md §x.y`; older comments say `docs/model.md §x.y`, the
//! same sections). Units are SI throughout (m, kg, s, N); PGA inputs are in g.
//!
//! ```no_run
//! use pounding::{input::scenario::Scenario, analysis::simulate::simulate};
//! let scenario = Scenario::from_file("examples/paper-c.toml".as_ref())?;
//! let report = simulate(&scenario)?;
//! println!("structure 1 peak: {:.3} m", report.structures[0].peak_displacement);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod analysis;
pub mod codes;
pub mod diagnostics;
pub mod figures;
pub mod input;
pub mod integrate;
pub mod model;
pub mod numerics;
pub mod opensees;
pub mod output;
pub mod plot;
pub mod recording;
pub mod study;
