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
//! use pounding::{scenario::Scenario, simulate::simulate};
//! let scenario = Scenario::from_file("examples/paper-c.toml".as_ref())?;
//! let report = simulate(&scenario)?;
//! println!("structure 1 peak: {:.3} m", report.structures[0].peak_displacement);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod accuracy;
pub mod budget;
pub mod building;
pub mod cantilever;
pub mod codes;
pub mod contact;
pub mod convergence;
pub mod design;
pub mod figures;
pub mod floor_response;
pub mod floors_csv;
pub mod gap_report;
pub mod ground_motion;
pub mod hysteresis;
pub mod input_file;
pub mod integrate;
pub mod modal;
pub mod opensees;
pub mod output;
pub mod plot;
pub mod record_spectrum;
pub mod recorder;
pub mod restitution;
pub mod row_spool;
pub mod rule_study;
pub mod scenario;
pub mod separation;
pub mod simulate;
pub mod spectrum;
pub mod storey_record;
pub mod sweep;
pub mod sweep_plots;
pub mod system;
