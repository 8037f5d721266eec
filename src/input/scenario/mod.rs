//! Scenario files (README, *Scenario files*): TOML → raw serde structs with spans → `validate` → a checked
//! [`Scenario`] in SI units.
//!
//! Every error names the file, the line and column, the key and the allowed range.

use std::path::Path;
use std::sync::Arc;

use serde::Deserialize;
use toml::Spanned;

use crate::integrate::SolverSettings;
use crate::model::contact::ContactLaw;
use crate::model::ground_motion::{GroundMotion, Record, RecordOptions};
use crate::model::structure::Structure;
use crate::model::system::{ContactLevel, System};

use diagnostics::Ctx;
use validate::{missing_keys, validate};

mod contact_keys;
pub mod design;
pub(crate) mod diagnostics;
mod floors;
mod ground_keys;
mod hysteresis;
pub mod keys;
mod plausibility;
mod ranges;
mod record_keys;
mod row_keys;
mod solver_keys;
mod structure_keys;
pub mod suite;
mod validate;

pub use diagnostics::{Location, ScenarioError};
pub use ranges::{
    PLAUSIBLE_MIN_PGA, USUAL_DAMPING_RATIO, USUAL_RECORD_DT, USUAL_STRUCTURE_PERIOD,
    physical_range, usual_range,
};

/// Most structures of a row (`[[structure]]` tables).
pub const MAX_ROW: usize = 100;

/// Most modes a structure may keep.
pub const MAX_MODES: i64 = 500;

/// Modes kept when `structure.modes` is not given. Measured with `pounding convergence` on the
/// paper's three cases (adaptive, against 50 modes): the peak contact force is off by 11–43 %
/// with 3 modes, 1.5–8.8 % with 5, 0.2–3.4 % with 10 and 0.02–0.31 % with 20 (README,
/// *Defaults and guards*).
pub const DEFAULT_MODES: usize = 20;

/// Damping ratio of every mode when no damping is given: 5 %, the design codes' convention.
pub const DEFAULT_DAMPING_RATIO: f64 = 0.05;

/// Simulated time of a harmonic ground motion when `solver.duration` is not given, s (the
/// paper's examples' duration; with 5 % damping the transient has long decayed).
pub const DEFAULT_HARMONIC_DURATION: f64 = 20.0;

/// Largest step of the default `adaptive` method when `solver.dt` is not given, s (a record's
/// own sample spacing when smaller).
pub const DEFAULT_DT: f64 = 0.001;

/// Lowest coefficient of restitution of the laws with a stiffness (kelvin, hertzdamp,
/// jankowski): their damping grows as 1/e (Jankowski's ξ ≈ 9√5/(32 e)), and at e = 1e-308 one
/// second of the paper's case took a minute before it diverged (issue 15's corner test).
pub const MIN_RESTITUTION: f64 = 0.01;

/// Lowest contact height, as a fraction of the lower structure's height.
pub const MIN_CONTACT_HEIGHT_FRACTION: f64 = 1e-3;

/// PGA above which a ground motion gets a plausibility warning, g.
pub const PLAUSIBLE_PGA: f64 = 3.0;

/// At-rest gap from which a contact level gets a plausibility warning, m.
pub const PLAUSIBLE_GAP: f64 = 1.0;

/// Contact law names accepted by `[contact] law`.
pub const CONTACT_LAWS: &[&str] = &[
    "hertz",
    "linear",
    "kelvin",
    "hertzdamp",
    "jankowski",
    "stereomechanical",
];

// ---------------------------------------------------------------------------------------------
// Raw schema: what the TOML may contain. All optional so that missing keys get our messages.

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    title: Option<String>,
    structure: Option<Spanned<Vec<RawStructure>>>,
    contact: Option<Spanned<row_keys::RawContacts>>,
    ground_motion: Option<Spanned<RawGround>>,
    solver: Option<Spanned<RawSolver>>,
    separation: Option<Spanned<crate::input::scenario::design::RawSeparation>>,
    output: Option<Spanned<RawOutput>>,
}

/// `[output]`: what the written files hold.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOutput {
    floor_stations: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStructure {
    /// `"cantilever"` (default), `"shear-building"` or `"modal"`.
    kind: Option<Spanned<String>>,
    name: Option<String>,
    length: Option<Spanned<f64>>,
    mass: Option<Spanned<f64>>,
    period: Option<Spanned<f64>>,
    bending_stiffness: Option<Spanned<f64>>,
    tip_stiffness: Option<Spanned<f64>>,
    /// A whole number; taken as a TOML value so that `3.0` gets our message, not serde's.
    modes: Option<Spanned<toml::Value>>,
    damping_ratio: Option<Spanned<RawZeta>>,
    strain_rate_damping: Option<Spanned<f64>>,
    air_damping: Option<Spanned<f64>>,
    // buildings with floors (see `floors`)
    floor_heights: Option<Spanned<Vec<f64>>>,
    floor_masses: Option<Spanned<Vec<f64>>>,
    storey_stiffnesses: Option<Spanned<Vec<f64>>>,
    storeys: Option<Spanned<toml::Value>>,
    storey_height: Option<Spanned<f64>>,
    floor_mass: Option<Spanned<f64>>,
    storey_stiffness: Option<Spanned<f64>>,
    rayleigh: Option<Spanned<RawRayleigh>>,
    periods: Option<Spanned<Vec<f64>>>,
    mode_shapes: Option<Spanned<Vec<Vec<f64>>>>,
    modes_file: Option<Spanned<String>>,
    /// Yielding storeys of a shear building (issue 16, see `floors`).
    hysteresis: Option<Spanned<RawHysteresis>>,
}

/// `hysteresis = { model = "bouc-wen", yield_drifts = …, post_yield_ratio = …, … }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHysteresis {
    model: Option<Spanned<String>>,
    yield_drifts: Option<Spanned<RawZeta>>,
    yield_forces: Option<Spanned<RawZeta>>,
    post_yield_ratio: Option<Spanned<f64>>,
    exponent: Option<Spanned<f64>>,
    beta: Option<Spanned<f64>>,
    gamma: Option<Spanned<f64>>,
}

/// `rayleigh = { damping_ratio = 0.05, modes = [1, 3] }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRayleigh {
    damping_ratio: Option<Spanned<f64>>,
    modes: Option<Spanned<Vec<i64>>>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawZeta {
    One(f64),
    Many(Vec<f64>),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    /// A row's `[[contact]]`: the pair's two structures by name.
    between: Option<Spanned<Vec<Spanned<String>>>>,
    law: Option<Spanned<String>>,
    stiffness: Option<Spanned<f64>>,
    restitution: Option<Spanned<f64>>,
    damping_model: Option<Spanned<String>>,
    gap: Option<Spanned<f64>>,
    height: Option<Spanned<f64>>,
    level: Option<Vec<Spanned<RawLevel>>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLevel {
    height: Option<Spanned<f64>>,
    gap: Option<Spanned<f64>>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawGround {
    pub(crate) kind: Option<Spanned<String>>,
    pub(crate) pga: Option<Spanned<f64>>,
    pub(crate) period: Option<Spanned<f64>>,
    pub(crate) file: Option<Spanned<String>>,
    pub(crate) units: Option<Spanned<String>>,
    pub(crate) scale_to_pga: Option<Spanned<f64>>,
    /// kind = "record": checked in `ground_keys`.
    pub(crate) scale_to_sa: Option<Spanned<ground_keys::RawScaleToSa>>,
    pub(crate) dt: Option<Spanned<f64>>,
    /// kind = "record": checked in `record_keys`.
    pub(crate) component: Option<Spanned<toml::Value>>,
    pub(crate) processing: Option<Spanned<record_keys::RawProcessing>>,
    // kind = "spectrum": checked in crate::input::scenario::design
    pub(crate) spectrum: Option<Spanned<String>>,
    pub(crate) sds: Option<Spanned<f64>>,
    pub(crate) sd1: Option<Spanned<f64>>,
    pub(crate) tl: Option<Spanned<f64>>,
    pub(crate) ag: Option<Spanned<f64>>,
    pub(crate) ground_type: Option<Spanned<String>>,
    #[serde(rename = "type")]
    pub(crate) spectrum_type: Option<Spanned<toml::Value>>,
    // kind = "suite": checked in `suite`
    pub(crate) records: Option<Spanned<Vec<Spanned<suite::RawSuiteRecord>>>>,
    pub(crate) scaling: Option<Spanned<suite::RawSuiteScaling>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSolver {
    method: Option<Spanned<String>>,
    dt: Option<Spanned<f64>>,
    duration: Option<Spanned<f64>>,
    output_interval: Option<Spanned<f64>>,
    rtol: Option<Spanned<f64>>,
    atol: Option<Spanned<f64>>,
}

// ---------------------------------------------------------------------------------------------
// The checked scenario.

/// Contact definition: one law, one or more levels.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactSpec {
    /// The force law.
    pub law: ContactLaw,
    /// Contact levels (at least one).
    pub levels: Vec<ContactLevel>,
}

/// A checked scenario, SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    /// Title.
    pub title: String,
    /// The structures in row order, left to right: structure 1 and 2 of a pair, N ≥ 2 of a
    /// row of buildings (issue 29).
    pub structures: Vec<Structure>,
    /// The contact of the first adjacent pair (structures 1 and 2): a pair's only contact.
    pub contact: ContactSpec,
    /// A row (more than two structures): the contacts of the following adjacent pairs,
    /// structures 2–3, 3–4, … in row order; empty for a pair. [`Scenario::contacts`] gives
    /// every pair's.
    pub row_contacts: Vec<ContactSpec>,
    /// Ground motion.
    pub ground_motion: GroundMotion,
    /// Solver.
    pub solver: SolverSettings,
    /// Sampling interval of the written history, s.
    pub output_interval: f64,
    /// Which stations' histories floors.csv holds (`[output] floor_stations`).
    pub floor_stations: crate::recording::stations::FloorStations,
    /// Keys the file left out and the defaults used for them, as `key = value`, in file
    /// order (printed in the run summary, `defaults_applied` in summary.json).
    pub defaults_applied: Vec<String>,
    /// Implausible values, each with why (a PGA above 3 g, a gap of metres); the run adds
    /// them to its warnings.
    pub warnings: Vec<String>,
    /// A design spectrum (`[ground_motion] kind = "spectrum"`, then `ground_motion` is
    /// [`GroundMotion::None`]) and the code factors of `[separation]` ([`crate::input::scenario::design`]).
    pub design: crate::input::scenario::design::DesignInputs,
    /// A suite of records (`[ground_motion] kind = "suite"`, then `ground_motion` is
    /// [`GroundMotion::None`]): run by [`crate::study::suite`].
    pub suite: Option<suite::Suite>,
}

impl Scenario {
    /// Read and validate a scenario file. Record files are resolved relative to it.
    pub fn from_file(path: &Path) -> Result<Scenario, ScenarioError> {
        Scenario::read_file(path).map(|(s, _)| s)
    }

    /// As [`Scenario::from_file`], also returning the file's text (what was validated).
    pub fn read_file(path: &Path) -> Result<(Scenario, String), ScenarioError> {
        let text = crate::input::file::read_text(path, crate::input::file::MAX_TEXT_BYTES)
            .map_err(|e| ScenarioError::Read {
                path: path.display().to_string(),
                source: e,
            })?;
        let base = path.parent().unwrap_or(Path::new("."));
        let sc = Scenario::from_toml(&text, &path.display().to_string(), base)?;
        Ok((sc, text))
    }

    /// Validate scenario text. `file` names it in messages; `base_dir` resolves record files.
    pub fn from_toml(text: &str, file: &str, base_dir: &Path) -> Result<Scenario, ScenarioError> {
        Scenario::from_toml_cached(text, file, base_dir, None)
    }

    /// As [`Scenario::from_toml`], but record files are taken from (and added to) `records`,
    /// so that many scenarios naming the same record (a sweep) read it once and share it.
    pub fn from_toml_cached(
        text: &str,
        file: &str,
        base_dir: &Path,
        records: Option<&RecordCache>,
    ) -> Result<Scenario, ScenarioError> {
        let ctx = Ctx {
            text,
            file,
            name: Arc::from(file),
            warnings: Default::default(),
        };
        let raw: RawScenario = toml::from_str(text).map_err(|e| {
            sweep_file(text, file)
                .or_else(|| row_keys::both_contact_forms(&ctx))
                .unwrap_or_else(|| ctx.toml_error(&e))
        })?;
        let missing = missing_keys(&raw, &ctx);
        if missing.len() > 1 {
            return Err(ScenarioError::MissingMany {
                file: file.to_string(),
                missing,
            });
        }
        validate(raw, &ctx, base_dir, records)
    }

    /// Validate a scenario given as a TOML table (the structure of a scenario file, e.g. built
    /// from nested dicts by the Python package's `Scenario.from_dict`). The table is written
    /// as TOML text ([`table_to_toml`]) and validated by [`Scenario::from_toml`], so that the
    /// checks, defaults and messages are exactly those of a file; `origin` names it in
    /// messages (its positions are line:col of that text) and `base_dir` resolves record
    /// files. Any table is accepted as input: a wrong one is a [`ScenarioError`], never a
    /// panic.
    pub fn from_table(
        table: &toml::Table,
        origin: &str,
        base_dir: &Path,
    ) -> Result<Scenario, ScenarioError> {
        let text = table_to_toml(table, origin)?;
        Scenario::from_toml(&text, origin, base_dir)
    }

    /// The assembled system with contact (of a row: every structure, every pair's levels).
    pub fn system(&self) -> System {
        let models: Vec<_> = self.structures.iter().map(Structure::modal).collect();
        let hysteresis = crate::model::hysteresis::Hysteresis::new(&self.structures, &models);
        let pairs: Vec<crate::model::system::PairContact> = self
            .contacts()
            .map(|c| crate::model::system::PairContact {
                law: c.law,
                levels: c.levels.clone(),
            })
            .collect();
        System::row(models, &pairs, self.ground_motion.clone()).with_hysteresis(hysteresis)
    }

    /// Every adjacent pair's contact, in row order (one for a pair).
    pub fn contacts(&self) -> impl Iterator<Item = &ContactSpec> {
        std::iter::once(&self.contact).chain(&self.row_contacts)
    }

    /// Whether this is a row of more than two structures (issue 29): what only a pair
    /// supports (`pounding separation`, sweeps, suites, OpenSees, …) refuses it.
    pub fn is_row(&self) -> bool {
        self.structures.len() > 2
    }

    /// The pair of structures `p` and `p + 1` (0-based) of a row as a scenario of its own:
    /// those two structures, their contact, the same ground motion, solver and design inputs
    /// (for a pair, `pair(0)` is the scenario itself). What the row's per-pair separation
    /// checks read, and the row taken apart into pairs.
    pub fn pair(&self, p: usize) -> Scenario {
        let mut sc = self.clone();
        sc.structures = vec![self.structures[p].clone(), self.structures[p + 1].clone()];
        sc.contact = self
            .contacts()
            .nth(p)
            .cloned()
            .unwrap_or_else(|| self.contact.clone());
        sc.row_contacts = Vec::new();
        sc
    }

    /// Whether either structure has yielding storeys (issue 16).
    pub fn has_hysteresis(&self) -> bool {
        self.structures.iter().any(|s| s.hysteresis().is_some())
    }

    /// Height whose displacements are reported as "the" contact height: the highest level of
    /// the first pair, m.
    pub fn main_height(&self) -> f64 {
        self.contact
            .levels
            .iter()
            .map(|l| l.height)
            .fold(f64::NEG_INFINITY, f64::max)
    }
}

/// A scenario table as TOML text (what [`Scenario::from_table`] validates); `origin` names
/// the table in the error when it cannot be written as TOML.
pub fn table_to_toml(table: &toml::Table, origin: &str) -> Result<String, ScenarioError> {
    toml::to_string(table).map_err(|e| ScenarioError::Syntax {
        at: Location::file(origin),
        message: format!("cannot be written as TOML: {e}"),
    })
}

/// A sweep file given where a scenario is expected: it has `[[axis]]` tables or a base
/// `scenario` and no `[[structure]]`.
fn sweep_file(text: &str, file: &str) -> Option<ScenarioError> {
    let t: toml::Table = toml::from_str(text).ok()?;
    if t.contains_key("structure") {
        return None;
    }
    let why = match (t.contains_key("axis"), t.contains_key("scenario")) {
        (true, true) => "it has [[axis]] tables and a base `scenario`",
        (true, false) => "it has [[axis]] tables",
        (false, true) => "it names a base `scenario`",
        (false, false) => return None,
    };
    Some(ScenarioError::SweepFile {
        file: file.to_string(),
        why: why.into(),
    })
}

/// Records already read, shared between scenarios: keyed by the path and the reading options
/// (units, dt, scale to PGA, component, processing), so a record read differently is read
/// separately.
#[derive(Debug, Default)]
pub struct RecordCache {
    map: std::sync::Mutex<std::collections::HashMap<String, Arc<Record>>>,
}

impl RecordCache {
    /// An empty cache.
    pub fn new() -> RecordCache {
        RecordCache::default()
    }

    fn get_or_read<E>(
        &self,
        path: &Path,
        opts: &RecordOptions,
        read: impl FnOnce() -> Result<Arc<Record>, E>,
    ) -> Result<Arc<Record>, E> {
        let key = format!(
            "{}\u{0}{:?}\u{0}{:?}\u{0}{:?}\u{0}{:?}\u{0}{:?}\u{0}{:?}",
            path.display(),
            opts.units,
            opts.dt.map(f64::to_bits),
            opts.scale_to_pga.map(f64::to_bits),
            opts.scale_to_sa
                .map(|t| [t.period, t.sa, t.damping].map(f64::to_bits)),
            opts.component,
            opts.processing
        );
        if let Some(r) = self.lock().get(&key) {
            return Ok(r.clone());
        }
        // read outside the lock: other threads may read other records meanwhile
        let r = read()?;
        Ok(self.lock().entry(key).or_insert(r).clone())
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, std::collections::HashMap<String, Arc<Record>>> {
        self.map.lock().unwrap_or_else(|p| p.into_inner())
    }
}
