//! Export a scenario as an OpenSeesPy model, and compare OpenSees' numbers with the program's
//! (issue 14).
//!
//! [`script`] writes a self-contained Python script: the model's data as one JSON literal
//! (`MODEL`, built by [`model`]) followed by a fixed driver (`driver.py`, embedded) that builds
//! the OpenSees model, runs it with and without contact and prints the headline numbers of
//! `summary.json` as JSON. [`compare`] runs such a script with a local `openseespy` and sets
//! its numbers beside the program's.
//!
//! How the scenario maps onto OpenSees (what is exact and what is not: [`law_mapping`],
//! [`damping_notes`]):
//!
//! - a cantilever: `elements` 2-D `elasticBeamColumn` elements with its EI and a consistent
//!   mass (`-mass m -cMass`), axial DOFs fixed, a node at every contact height ([`mesh`]);
//! - a shear building: a node per floor with its mass, rotations fixed (rigid floors), storey
//!   springs as `twoNodeLink` elements in shear — `Elastic`, or for yielding storeys OpenSees'
//!   `BoucWen` material with the program's law mapped onto it ([`bouc_wen_material`]); a
//!   building given by its modes cannot be exported (OpenSees needs stiffnesses);
//! - the ground motion as nodal loads `−M r a_g(t)` through a `Plain` pattern with a `Path`
//!   series (never `UniformExcitation`: in OpenSees 3.7.1 a 2-D `elasticBeamColumn` with element
//!   mass under `UniformExcitation` receives the ground inertia load twice);
//! - damping: modal (`modalDampingQ` on every FE mode, each with its structure's ratio for its
//!   mode number) or Rayleigh (`region … -rayleigh` with the *initial* stiffness, as the program's
//!   damping stays that of the initial stiffness; never on the contact elements), as the
//!   scenario has it;
//! - contact at every level: a `zeroLength` element between the two structures' nodes at that
//!   height, with the law's material ([`contact_material`]);
//! - Newmark average acceleration (γ = ½, β = ¼), Newton iterations, and on a failed step:
//!   sub-steps halved down to dt/64, then the same with ModifiedNewton, then KrylovNewton.

pub mod compare;
mod contact;
mod export_model;
pub mod results;
pub mod row;
pub mod row_compare;
mod script_text;
mod storeys;
mod yielding;

use contact::mapping_text;
pub use contact::{
    ContactMaterial, HERTZ_MAX_PENETRATION, HERTZ_MIN_PENETRATION, HERTZ_RATIO, Mapping, ZERO_GAP,
    contact_material, hertz_curve, law_mapping,
};
pub use export_model::{
    ExportDamping, ExportGround, ExportLevel, ExportModel, ExportStructure, damping_notes, mesh,
    model,
};
use export_model::{checked_duration, export_ground, export_levels, export_structure, exported_by};
pub use script_text::script;
use script_text::{ScriptParts, one_line, script_text};
pub use yielding::{BOUC_WEN_MAPPING, BoucWenMaterial, bouc_wen_material};

use serde::Serialize;

/// The driver appended to every exported script (Python, OpenSeesPy).
pub const DRIVER: &str = include_str!("driver.py");

/// The OpenSeesPy release the export was written and tested against (`pip install
/// openseespy==3.7.1.2`).
pub const TESTED_OPENSEESPY: &str = "3.7.1.2";

/// Default number of beam elements per cantilever.
pub const DEFAULT_ELEMENTS: usize = 20;

/// Default OpenSees analysis step, s: the step at which the agreement (≤ 2 % with
/// Hertz contact) was measured.
pub const DEFAULT_DT: f64 = 2.5e-4;

/// Newton's convergence tolerance on the norm of the displacement increment (m, rad).
pub const NEWTON_TOLERANCE: f64 = 1e-10;

/// Which runs the script does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Only {
    /// Only the run with contact.
    Contact,
    /// Only the run without contact.
    Free,
}

impl Only {
    /// Parse `contact` or `free`.
    pub fn from_name(name: &str) -> Option<Only> {
        match name {
            "contact" => Some(Only::Contact),
            "free" => Some(Only::Free),
            _ => None,
        }
    }
}

/// Options of the export.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExportOptions {
    /// Beam elements per cantilever (at least one per segment between contact heights).
    pub elements: usize,
    /// OpenSees analysis step, s.
    pub dt: f64,
    /// Simulated time, s (`None`: the scenario's).
    pub duration: Option<f64>,
    /// Run only one of the two cases.
    pub only: Option<Only>,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            elements: DEFAULT_ELEMENTS,
            dt: DEFAULT_DT,
            duration: None,
            only: None,
        }
    }
}

/// Why a scenario cannot be exported.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// The contact law has no OpenSees counterpart.
    #[error("contact law `{law}` cannot be exported to OpenSees: {reason}")]
    Law {
        /// The law's scenario name.
        law: &'static str,
        /// Why.
        reason: &'static str,
    },
    /// A structure of a kind OpenSees cannot be given.
    #[error("structure `{name}` cannot be exported to OpenSees: {reason}")]
    Structure {
        /// The structure's name.
        name: String,
        /// Why.
        reason: String,
    },
    /// An option out of range.
    #[error("{0}")]
    Option(String),
    /// A row's pair that cannot be exported (issue 29): which pair, and why.
    #[error("contact[{pair}] (between \"{left}\" and \"{right}\"): {source}")]
    Pair {
        /// The pair's place in the row, 1-based (`contact[P]`, as a sweep names it).
        pair: usize,
        /// Its left structure's name.
        left: String,
        /// Its right structure's name.
        right: String,
        /// Why.
        source: Box<ExportError>,
    },
}
