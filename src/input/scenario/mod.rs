//! Scenario files (README, *Scenario files*): TOML → raw serde structs with spans → [`validate`] → a checked
//! [`Scenario`] in SI units.
//!
//! Every error names the file, the line and column, the key and the allowed range.

use std::fmt;
use std::path::Path;
use std::sync::Arc;

use serde::Deserialize;
use toml::Spanned;

use crate::integrate::{ATOL_PER_RTOL, MIN_ATOL, MIN_RTOL, Method, SolverSettings};
use crate::model::contact::{ContactLaw, HertzDampModel};
use crate::model::ground_motion::{GroundMotion, Harmonic, Record, RecordOptions};
use crate::model::structure::{Cantilever, Damping, Stiffness, Structure};
use crate::model::system::{ContactLevel, System};

pub mod design;
mod floors;
mod hysteresis;
mod ranges;
mod record_keys;
pub mod suite;

pub(crate) use ranges::unusual;
pub use ranges::{
    PLAUSIBLE_MIN_PGA, USUAL_DAMPING_RATIO, USUAL_RECORD_DT, USUAL_STRUCTURE_PERIOD,
    physical_range, usual_range,
};

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

/// Where in a scenario file something is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// File name as given.
    pub file: Arc<str>,
    /// 1-based line and column, when known.
    pub line_col: Option<(u32, u32)>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line_col {
            Some((l, c)) => write!(f, "{}:{}:{}", self.file, l, c),
            None => write!(f, "{}", self.file),
        }
    }
}

/// Why a scenario was refused.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("cannot read scenario {path}: {source}")]
    Read {
        /// Path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not valid TOML, or a value of the wrong type.
    #[error("{at}: {message}")]
    Syntax {
        /// Where.
        at: Location,
        /// What the TOML parser said.
        message: String,
    },
    /// A key that the format does not have.
    #[error("{at}: unknown key `{key}` in {section}{hint}")]
    UnknownKey {
        /// Where.
        at: Location,
        /// The key.
        key: String,
        /// The table it is in.
        section: String,
        /// "; did you mean …? valid keys: …"
        hint: String,
    },
    /// Several required keys are absent: every one, in file order.
    #[error("{file}: {} required keys are missing:{}", .missing.len(), list_missing(.missing))]
    MissingMany {
        /// The scenario file.
        file: String,
        /// (where, key, what is expected) of each.
        missing: Vec<(Location, String, String)>,
    },
    /// The file is a sweep file, not a scenario.
    #[error(
        "{file}: this is a sweep file ({why}), not a scenario: run it with `pounding sweep {file}`, or print one of its cases as a scenario with `pounding sweep {file} --case N`"
    )]
    SweepFile {
        /// The file.
        file: String,
        /// What gave it away.
        why: String,
    },
    /// A required key is absent.
    #[error("{at}: missing key `{key}`: {expected}")]
    Missing {
        /// Where (the file, or the table).
        at: Location,
        /// Full key path, e.g. `structure[1].mass`.
        key: String,
        /// What is expected.
        expected: String,
    },
    /// A value outside its allowed range or an inconsistent combination.
    #[error("{at}: `{key}` = {value}: {reason}")]
    Invalid {
        /// Where.
        at: Location,
        /// Full key path.
        key: String,
        /// The value as given.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// The ground-motion record could not be read.
    #[error("{at}: `{key}`: {source}")]
    Record {
        /// Where the file is named.
        at: Location,
        /// The key.
        key: String,
        /// The reader's error.
        source: Box<crate::model::ground_motion::RecordError>,
    },
}

fn list_missing(missing: &[(Location, String, String)]) -> String {
    missing
        .iter()
        .map(|(at, key, expected)| format!("\n  {at}: `{key}`: {expected}"))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Raw schema: what the TOML may contain. All optional so that missing keys get our messages.

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    title: Option<String>,
    structure: Option<Spanned<Vec<RawStructure>>>,
    contact: Option<Spanned<RawContact>>,
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

/// Valid keys of each table, for suggestions.
const TABLES: &[(&str, &[&str])] = &[
    (
        "the top level",
        &[
            "title",
            "structure",
            "contact",
            "ground_motion",
            "solver",
            "separation",
            "output",
        ],
    ),
    ("[output]", &["floor_stations"]),
    (
        "[[structure]]",
        &[
            "kind",
            "name",
            "length",
            "mass",
            "period",
            "bending_stiffness",
            "tip_stiffness",
            "modes",
            "damping_ratio",
            "strain_rate_damping",
            "air_damping",
            "floor_heights",
            "floor_masses",
            "storey_stiffnesses",
            "storeys",
            "storey_height",
            "floor_mass",
            "storey_stiffness",
            "rayleigh",
            "periods",
            "mode_shapes",
            "modes_file",
            "hysteresis",
        ],
    ),
    ("[structure.rayleigh]", &["damping_ratio", "modes"]),
    (
        "[structure.hysteresis]",
        &[
            "model",
            "yield_drifts",
            "yield_forces",
            "post_yield_ratio",
            "exponent",
            "beta",
            "gamma",
        ],
    ),
    (
        "[contact]",
        &[
            "law",
            "stiffness",
            "restitution",
            "damping_model",
            "gap",
            "height",
            "level",
        ],
    ),
    ("[[contact.level]]", &["height", "gap"]),
    ("ground_motion.processing", record_keys::PROCESSING_KEYS),
    (
        "[ground_motion]",
        &[
            "kind",
            "pga",
            "period",
            "file",
            "units",
            "scale_to_pga",
            "dt",
            "component",
            "processing",
            "spectrum",
            "sds",
            "sd1",
            "tl",
            "ag",
            "ground_type",
            "type",
            "records",
            "scaling",
        ],
    ),
    (
        "[solver]",
        &[
            "method",
            "dt",
            "duration",
            "output_interval",
            "rtol",
            "atol",
        ],
    ),
];

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
    /// Structure 1 (left) and 2 (right).
    pub structures: [Structure; 2],
    /// Contact.
    pub contact: ContactSpec,
    /// Ground motion.
    pub ground_motion: GroundMotion,
    /// Solver.
    pub solver: SolverSettings,
    /// Sampling interval of the written history, s.
    pub output_interval: f64,
    /// Which stations' histories floors.csv holds (`[output] floor_stations`).
    pub floor_stations: crate::output::run::FloorStations,
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
        let raw: RawScenario = toml::from_str(text)
            .map_err(|e| sweep_file(text, file).unwrap_or_else(|| ctx.toml_error(&e)))?;
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

    /// The assembled system with contact.
    pub fn system(&self) -> System {
        let models = [self.structures[0].modal(), self.structures[1].modal()];
        let hysteresis = crate::model::hysteresis::Hysteresis::new(&self.structures, &models);
        System::new(
            models,
            &self.contact.law,
            &self.contact.levels,
            self.ground_motion.clone(),
        )
        .with_hysteresis(hysteresis)
    }

    /// Whether either structure has yielding storeys (issue 16).
    pub fn has_hysteresis(&self) -> bool {
        self.structures.iter().any(|s| s.hysteresis().is_some())
    }

    /// Height whose displacements are reported as "the" contact height: the highest level, m.
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
        at: Location {
            file: Arc::from(origin),
            line_col: None,
        },
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

/// Every required key the file lacks (with its place and what is expected), before any value
/// is checked: so that one message lists them all.
fn missing_keys(raw: &RawScenario, ctx: &Ctx) -> Vec<(Location, String, String)> {
    let mut out = Vec::new();
    let mut miss = |near: Option<usize>, key: String, expected: &str| {
        out.push((ctx.at(near), key, expected.to_string()));
    };
    match &raw.structure {
        None => miss(
            None,
            "structure".into(),
            "two [[structure]] tables (structure 1 on the left, 2 on the right)",
        ),
        Some(list) => {
            let near = Some(list.span().start);
            for (i, s) in list.get_ref().iter().enumerate().take(2) {
                let key = |k: &str| format!("structure[{}].{k}", i + 1);
                if s.kind.as_ref().is_some_and(|k| k.get_ref() != "cantilever") {
                    // a building with floors: its keys are checked by `floors`
                    continue;
                }
                if s.length.is_none() {
                    miss(near, key("length"), "height L in m");
                }
                if s.mass.is_none() {
                    miss(near, key("mass"), "total mass M in kg");
                }
                if s.period.is_none() && s.bending_stiffness.is_none() && s.tip_stiffness.is_none()
                {
                    miss(
                        near,
                        key("period"),
                        "one of `period` (s), `bending_stiffness` (N·m²) or `tip_stiffness` (N/m)",
                    );
                }
            }
        }
    }
    match &raw.contact {
        None => miss(
            None,
            "contact".into(),
            "a [contact] table with at least `stiffness` and `gap`",
        ),
        Some(c) => {
            let near = Some(c.span().start);
            let r = c.get_ref();
            let law = r.law.as_ref().map_or("hertz", |l| l.get_ref().as_str());
            if r.stiffness.is_none() && law != "stereomechanical" {
                miss(near, "contact.stiffness".into(), "contact stiffness");
            }
            if r.restitution.is_none()
                && matches!(
                    law,
                    "kelvin" | "hertzdamp" | "jankowski" | "stereomechanical"
                )
            {
                miss(
                    near,
                    "contact.restitution".into(),
                    "a coefficient of restitution for this law",
                );
            }
            match &r.level {
                None if r.gap.is_none() => {
                    miss(near, "contact.gap".into(), "at-rest gap in m (≥ 0)")
                }
                None => {}
                Some(levels) => {
                    for (i, l) in levels.iter().enumerate() {
                        let near = Some(l.span().start);
                        if l.get_ref().height.is_none() {
                            miss(
                                near,
                                format!("contact.level[{}].height", i + 1),
                                "contact height in m",
                            );
                        }
                        if l.get_ref().gap.is_none() {
                            miss(
                                near,
                                format!("contact.level[{}].gap", i + 1),
                                "at-rest gap in m (≥ 0)",
                            );
                        }
                    }
                }
            }
        }
    }
    match &raw.ground_motion {
        None => miss(
            None,
            "ground_motion".into(),
            "a [ground_motion] table (kind = \"harmonic\" with `pga` and `period`, or kind = \"record\" with `file`)",
        ),
        Some(g) => {
            let near = Some(g.span().start);
            let r = g.get_ref();
            match r.kind.as_ref().map(|k| k.get_ref().as_str()) {
                None => miss(
                    near,
                    "ground_motion.kind".into(),
                    "\"harmonic\", \"record\" or \"spectrum\"",
                ),
                Some("harmonic") => {
                    if r.pga.is_none() {
                        miss(
                            near,
                            "ground_motion.pga".into(),
                            "peak ground acceleration in g",
                        );
                    }
                    if r.period.is_none() {
                        miss(
                            near,
                            "ground_motion.period".into(),
                            "ground period T_g in s",
                        );
                    }
                }
                Some("record") if r.file.is_none() => {
                    miss(near, "ground_motion.file".into(), "the record file")
                }
                Some(_) => {}
            }
        }
    }
    out
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
            "{}\u{0}{:?}\u{0}{:?}\u{0}{:?}\u{0}{:?}\u{0}{:?}",
            path.display(),
            opts.units,
            opts.dt.map(f64::to_bits),
            opts.scale_to_pga.map(f64::to_bits),
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

pub(crate) struct Ctx<'a> {
    pub(crate) text: &'a str,
    pub(crate) file: &'a str,
    pub(crate) name: Arc<str>,
    /// Values inside their range but outside the usual band ([`usual_range`]), as warnings.
    pub(crate) warnings: std::cell::RefCell<Vec<String>>,
}

impl Ctx<'_> {
    pub(crate) fn at(&self, offset: Option<usize>) -> Location {
        Location {
            file: self.name.clone(),
            line_col: offset.map(|o| line_col(self.text, o)),
        }
    }

    pub(crate) fn toml_error(&self, e: &toml::de::Error) -> ScenarioError {
        let at = self.at(e.span().map(|s| s.start));
        let msg = e.message().trim().to_string();
        if let Some((key, expected)) = unknown_field(&msg) {
            let (section, valid) = self.section_for(&expected);
            return ScenarioError::UnknownKey {
                at,
                hint: key_hint(&key, &valid),
                key,
                section,
            };
        }
        // a duplicate: name the table or key and both lines
        if msg.starts_with("duplicate key")
            && let Some(message) = e.span().and_then(|sp| self.duplicate(sp.start))
        {
            return ScenarioError::Syntax { at, message };
        }
        // name the key when the offending line is a `key = value` line
        let message = match e.span().and_then(|sp| self.key_on_line(sp.start)) {
            Some(key) => format!("`{key}`: {msg}"),
            None => msg,
        };
        ScenarioError::Syntax { at, message }
    }

    /// What a "duplicate key" at byte `offset` repeats, with the line where it first stood:
    /// a table header (`[contact]` given twice) or a key within the same table.
    fn duplicate(&self, offset: usize) -> Option<String> {
        let offset = offset.min(self.text.len());
        let start = self.text.get(..offset)?.rfind('\n').map_or(0, |p| p + 1);
        let line_no = self.text[..start].matches('\n').count() + 1;
        let line = self.text.get(start..)?.lines().next()?.trim();
        let lines: Vec<&str> = self.text.lines().collect();
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            let name = name.trim();
            let first = lines[..line_no - 1].iter().position(|l| {
                l.trim()
                    .strip_prefix('[')
                    .and_then(|l| l.strip_suffix(']'))
                    .is_some_and(|n| n.trim() == name)
            })?;
            return Some(format!(
                "`{name}`: the table [{name}] is given twice (first at line {}, again at line \
                 {line_no}); merge the two",
                first + 1
            ));
        }
        let key = self.key_on_line(offset)?;
        // the earlier line with the same key in the same table (back to the table's header)
        let first = lines[..line_no - 1]
            .iter()
            .enumerate()
            .rev()
            .take_while(|(_, l)| !l.trim_start().starts_with('['))
            .find(|(_, l)| l.split_once('=').is_some_and(|(k, _)| k.trim() == key))
            .map(|(i, _)| i + 1)?;
        Some(format!(
            "`{key}`: given twice in the same table (first at line {first}, again at line \
             {line_no}); keep one"
        ))
    }

    /// The key of a `key = value` line containing byte `offset`.
    fn key_on_line(&self, offset: usize) -> Option<String> {
        let offset = offset.min(self.text.len());
        let start = self.text.get(..offset)?.rfind('\n').map_or(0, |p| p + 1);
        let line = self.text.get(start..)?.lines().next()?;
        let (key, _) = line.split_once('=')?;
        let key = key.trim();
        let ok = !key.is_empty()
            && key
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.');
        ok.then(|| key.to_string())
    }

    /// The table an unknown key sits in, and its valid keys: the table whose keys are exactly
    /// serde's list of expected keys (every table's key set is distinct, tested in
    /// `tests/unknown_keys.rs`).
    fn section_for(&self, expected: &[String]) -> (String, Vec<String>) {
        let tables = TABLES.iter().chain(crate::input::scenario::design::TABLES);
        for (name, keys) in tables.chain(suite::TABLES) {
            if keys.len() == expected.len() && expected.iter().all(|k| keys.contains(&k.as_str())) {
                return (
                    name.to_string(),
                    keys.iter().map(|k| k.to_string()).collect(),
                );
            }
        }
        // (not reached for the tables of a scenario; a table added without its entry in
        // TABLES still gets its keys listed)
        ("this table".to_string(), expected.to_vec())
    }
}

/// The unknown key and the keys the table accepts, from the message of serde's
/// `deny_unknown_fields`, in each of its forms: "unknown field `k`, expected one of `a`, `b`,
/// `c`", "… expected `a` or `b`", "… expected `a`" and "… there are no fields". `None` for
/// any other message.
pub(crate) fn unknown_field(msg: &str) -> Option<(String, Vec<String>)> {
    let rest = msg.strip_prefix("unknown field `")?;
    let end = rest.find('`')?;
    let key = rest[..end].to_string();
    let list = rest[end + 1..]
        .split_once("expected one of ")
        .or_else(|| rest[end + 1..].split_once("expected "))
        .map_or("", |(_, l)| l);
    let expected = list
        .split(", ")
        .flat_map(|part| part.split(" or "))
        .map(|k| k.trim().trim_matches('`'))
        .filter(|k| !k.is_empty())
        .map(str::to_string)
        .collect();
    Some((key, expected))
}

/// What follows "unknown key `key` in TABLE": the closest valid key when one is close
/// ("; did you mean `period`?") and every valid key ("(valid keys: a, b)"; "(the table takes
/// no keys)" when there are none).
pub(crate) fn key_hint<S: AsRef<str>>(key: &str, valid: &[S]) -> String {
    let best = valid
        .iter()
        .map(|v| (strsim::jaro_winkler(key, v.as_ref()), v.as_ref()))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    let mut hint = String::new();
    if let Some((score, v)) = best
        && score > 0.75
    {
        hint.push_str(&format!("; did you mean `{v}`?"));
    }
    if valid.is_empty() {
        hint.push_str(" (the table takes no keys)");
    } else {
        let names: Vec<&str> = valid.iter().map(AsRef::as_ref).collect();
        hint.push_str(&format!(" (valid keys: {})", names.join(", ")));
    }
    hint
}

fn line_col(text: &str, offset: usize) -> (u32, u32) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rfind('\n').map_or(offset, |p| offset - p - 1) + 1;
    (
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(col).unwrap_or(u32::MAX),
    )
}

/// A validator for one key: checks the value against a range and reports with its location.
pub(crate) struct Check<'a, 'c> {
    pub(crate) ctx: &'c Ctx<'a>,
}

impl Check<'_, '_> {
    pub(crate) fn invalid<T: fmt::Display>(
        &self,
        v: &Spanned<T>,
        key: &str,
        reason: &str,
    ) -> ScenarioError {
        ScenarioError::Invalid {
            at: self.ctx.at(Some(v.span().start)),
            key: key.to_string(),
            value: v.get_ref().to_string(),
            reason: reason.to_string(),
        }
    }

    pub(crate) fn missing(&self, key: &str, expected: &str, near: Option<usize>) -> ScenarioError {
        ScenarioError::Missing {
            at: self.ctx.at(near),
            key: key.to_string(),
            expected: expected.to_string(),
        }
    }

    /// A finite number > 0 (unit in the message).
    pub(crate) fn positive(
        &self,
        v: &Spanned<f64>,
        key: &str,
        unit: &str,
    ) -> Result<f64, ScenarioError> {
        let x = *v.get_ref();
        if x.is_finite() && x > 0.0 {
            self.in_range(v, key, unit)
        } else {
            Err(self.invalid(v, key, &format!("must be a finite number > 0 ({unit})")))
        }
    }

    /// A finite number ≥ 0.
    fn non_negative(&self, v: &Spanned<f64>, key: &str, unit: &str) -> Result<f64, ScenarioError> {
        let x = *v.get_ref();
        if x.is_finite() && x >= 0.0 {
            self.in_range(v, key, unit)
        } else {
            Err(self.invalid(v, key, &format!("must be a finite number ≥ 0 ({unit})")))
        }
    }

    /// `v` within the physical range of `key` ([`physical_range`]), if it has one.
    fn in_range(&self, v: &Spanned<f64>, key: &str, unit: &str) -> Result<f64, ScenarioError> {
        let x = *v.get_ref();
        match physical_range(key) {
            Some((lo, hi, what)) if !(lo..=hi).contains(&x) => Err(ScenarioError::Invalid {
                at: self.ctx.at(Some(v.span().start)),
                key: key.to_string(),
                // (shortest form: 1e300, not three hundred digits)
                value: format!("{x:?}"),
                reason: format!("must be in [{lo:e}, {hi:e}] {unit} ({what})"),
            }),
            _ => {
                self.usual(x, key, unit);
                Ok(x)
            }
        }
    }

    /// Records a warning when `x` is outside the usual band of `key` ([`usual_range`]).
    /// A list warns once, for its first unusual value.
    pub(crate) fn usual(&self, x: f64, key: &str, unit: &str) {
        if let Some(w) = unusual(x, key, unit) {
            let mut list = self.ctx.warnings.borrow_mut();
            let named = format!("`{key}` = ");
            if !list.iter().any(|o| o.starts_with(&named)) {
                list.push(w);
            }
        }
    }

    pub(crate) fn required<'v, T>(
        &self,
        v: &'v Option<Spanned<T>>,
        key: &str,
        expected: &str,
        near: Option<usize>,
    ) -> Result<&'v Spanned<T>, ScenarioError> {
        v.as_ref().ok_or_else(|| self.missing(key, expected, near))
    }

    fn restitution(&self, v: &Spanned<f64>, key: &str) -> Result<f64, ScenarioError> {
        let e = *v.get_ref();
        if e.is_finite() && (MIN_RESTITUTION..=1.0).contains(&e) {
            Ok(e)
        } else {
            Err(self.invalid(
                v,
                key,
                &format!(
                    "coefficient of restitution must be in [{MIN_RESTITUTION}, 1] (the damping of \
                     the jankowski and hunt-crossley laws grows as 1/e: below {MIN_RESTITUTION} \
                     it stalls the solver; for a plastic impact use law = \"stereomechanical\" \
                     with restitution = 0)"
                ),
            ))
        }
    }
}

/// A building with floors touches only at its floors: every contact height must be one of
/// them (a cantilever may touch at any height up to its top).
fn floors_at_contact(
    c: &Check,
    raw: &RawScenario,
    structures: &[Structure; 2],
    contact: &ContactSpec,
) -> Result<(), ScenarioError> {
    let Some(rc) = raw.contact.as_ref() else {
        return Ok(());
    };
    let levels = rc.get_ref().level.as_ref();
    for (k, lv) in contact.levels.iter().enumerate() {
        for (i, s) in structures.iter().enumerate() {
            let Some(heights) = s.floor_heights() else {
                continue;
            };
            if heights
                .iter()
                .any(|&h| crate::model::building::same_height(h, lv.height))
            {
                continue;
            }
            let (key, at) = match levels.and_then(|l| l.get(k)) {
                Some(l) => (
                    format!("contact.level[{}].height", k + 1),
                    l.get_ref()
                        .height
                        .as_ref()
                        .map_or(l.span().start, |h| h.span().start),
                ),
                None => (
                    "contact.height".to_string(),
                    rc.get_ref()
                        .height
                        .as_ref()
                        .map_or(rc.span().start, |h| h.span().start),
                ),
            };
            let floors: Vec<String> = heights.iter().map(|h| format!("{h}")).collect();
            return Err(ScenarioError::Invalid {
                at: c.ctx.at(Some(at)),
                key,
                value: format!("{} m", lv.height),
                reason: format!(
                    "structure {} (\"{}\") has floors at {} m: a building with floors touches its \
                     neighbour only at a floor, so a contact height must be one of them",
                    i + 1,
                    s.name(),
                    floors.join(", ")
                ),
            });
        }
    }
    Ok(())
}

fn validate(
    raw: RawScenario,
    ctx: &Ctx,
    base_dir: &Path,
    records: Option<&RecordCache>,
) -> Result<Scenario, ScenarioError> {
    let c = Check { ctx };
    let mut defaults = Vec::new();
    let mut structure_warnings = Vec::new();
    let structures = {
        let list = c.required(
            &raw.structure,
            "structure",
            "two [[structure]] tables (structure 1 on the left, 2 on the right)",
            None,
        )?;
        if list.get_ref().len() != 2 {
            return Err(ScenarioError::Invalid {
                at: ctx.at(Some(list.span().start)),
                key: "structure".into(),
                value: format!("{} table(s)", list.get_ref().len()),
                reason: "exactly two [[structure]] tables are needed".into(),
            });
        }
        let start = list.span().start;
        let mut it =
            list.get_ref()
                .iter()
                .enumerate()
                .map(|(i, s)| match floors::kind(&c, i, s)? {
                    floors::Kind::Cantilever => structure(&c, i, s, start, &mut defaults),
                    kind => floors::floor_structure(
                        &c,
                        i,
                        s,
                        kind,
                        start,
                        base_dir,
                        &mut defaults,
                        &mut structure_warnings,
                    ),
                });
        let a = it.next().unwrap_or_else(|| unreachable!())?;
        let b = it.next().unwrap_or_else(|| unreachable!())?;
        [a, b]
    };
    let min_length = structures[0].length().min(structures[1].length());
    let contact = contact(&c, raw.contact.as_ref(), min_length, &mut defaults)?;
    let suite = suite::suite(&c, &raw, base_dir, records)?;
    let ground_motion = match suite {
        Some(_) => GroundMotion::None,
        None => ground(&c, raw.ground_motion.as_ref(), base_dir, records)?,
    };
    let from = suite::defaults_ground(suite.as_ref(), &ground_motion);
    let (solver, output_interval) = solver(&c, raw.solver.as_ref(), from, &mut defaults)?;
    suite::note_defaults(suite.as_ref(), &mut defaults);
    floors_at_contact(&c, &raw, &structures, &contact)?;
    // each key within its range can still combine into a structure no run can mean (a huge
    // mass on a thread-like EI): its first period must be within [1e-3, 1e4] s
    for (i, st) in structures.iter().enumerate() {
        let t1 = st.modal().periods().first().copied().unwrap_or(f64::NAN);
        if !(1e-3..=1e4).contains(&t1) {
            return Err(ScenarioError::Invalid {
                at: c.ctx.at(raw.structure.as_ref().map(|l| l.span().start)),
                key: format!("structure[{}]", i + 1),
                value: format!("first-mode period {t1:e} s"),
                reason: "the mass, height and stiffness give a first-mode period outside \
                         [1e-3, 1e4] s: check their units"
                    .into(),
            });
        }
    }
    let mut warnings = structure_warnings;
    warnings.extend(plausibility(&contact, &ground_motion));
    warnings.extend(derived_warnings(&structures));
    let design = crate::input::scenario::design::validate(
        &c,
        raw.ground_motion.as_ref(),
        raw.separation.as_ref(),
        base_dir,
        &mut defaults,
    )?;
    let floor_stations = match raw
        .output
        .as_ref()
        .and_then(|o| o.get_ref().floor_stations.as_ref())
    {
        None => crate::output::run::FloorStations::default(),
        Some(v) => crate::output::run::FloorStations::from_name(v.get_ref()).ok_or_else(|| {
            c.invalid(
                v,
                "output.floor_stations",
                &format!(
                    "must be one of {}",
                    quoted(&crate::output::run::FloorStations::NAMES)
                ),
            )
        })?,
    };
    // (after `design`, which may warn too: a_g probably in g)
    warnings.extend(ctx.warnings.take());
    let scenario = Scenario {
        floor_stations,
        title: raw.title.unwrap_or_else(|| ctx.file.to_string()),
        structures,
        contact,
        ground_motion,
        solver,
        output_interval,
        defaults_applied: defaults,
        warnings,
        design,
        suite,
    };
    // stability: needs the modal model (docs/model.md §2.9)
    if let Err(e) = solver.check_stability(&scenario.system().without_contact()) {
        let dt = raw
            .solver
            .as_ref()
            .and_then(|s| s.get_ref().dt.as_ref())
            .map(|d| d.span().start);
        return Err(ScenarioError::Invalid {
            at: ctx.at(dt),
            key: "solver.dt".into(),
            value: solver.dt.to_string(),
            reason: if scenario
                .defaults_applied
                .iter()
                .any(|d| d.contains(".modes = "))
            {
                format!(
                    "{e}. `modes` was not given for every structure: the default of {DEFAULT_MODES} \
                     modes was used; give `modes` to keep fewer, or omit `method` for the \
                     adaptive default, stable with any number of modes"
                )
            } else {
                e.to_string()
            },
        });
    }
    Ok(scenario)
}

/// Warnings about what several keys give together: the first-mode period of a structure given
/// by its stiffness (not by `period`), the first-mode damping ratio of physical damping
/// (`strain_rate_damping`, `air_damping`), each outside its usual band ([`usual_range`]).
fn derived_warnings(structures: &[Structure; 2]) -> Vec<String> {
    let mut out = Vec::new();
    for (i, st) in structures.iter().enumerate() {
        let (by_period, physical) = match st {
            Structure::Cantilever(c) => (
                matches!(c.stiffness, Stiffness::Period(_)),
                matches!(c.damping, Damping::Physical { .. }),
            ),
            Structure::Floors(f) => (
                matches!(f.kind, crate::model::structure::FloorKind::Modal(_)),
                false,
            ),
        };
        let modal = st.modal();
        let (lo, hi) = USUAL_STRUCTURE_PERIOD;
        if let Some(&t1) = modal.periods().first()
            && !by_period
            && !(lo..=hi).contains(&t1)
        {
            out.push(format!(
                "structure {} (\"{}\"): its stiffness, mass and height give a first-mode period of \
                 {t1:.4e} s, outside the usual [{lo}, {hi}] s of buildings; check their units",
                i + 1,
                st.name()
            ));
        }
        let (lo, hi) = USUAL_DAMPING_RATIO;
        if let Some(&z1) = modal.zeta.first()
            && physical
            && !(lo..=hi).contains(&z1)
        {
            out.push(format!(
                "structure {} (\"{}\"): strain_rate_damping and air_damping give a first-mode \
                 damping ratio of {z1:.4}, outside the usual [{lo}, {hi}] of buildings; check \
                 their units (c_s/E in s, c_a in N·s/m²)",
                i + 1,
                st.name()
            ));
        }
    }
    out
}

/// Warnings about values that are valid but implausible, each saying why.
fn plausibility(contact: &ContactSpec, ground: &GroundMotion) -> Vec<String> {
    let mut out = Vec::new();
    let pga_g = ground.pga() / crate::model::ground_motion::STANDARD_GRAVITY;
    if matches!(ground, GroundMotion::Harmonic(_) | GroundMotion::Record(_))
        && pga_g < PLAUSIBLE_MIN_PGA
    {
        out.push(format!(
            "the ground motion's PGA is {pga_g:.3e} g, below {PLAUSIBLE_MIN_PGA} g: shaking that \
             people barely feel, far below any that makes buildings pound; PGA is in g — was it \
             given in cm/s² or scaled twice?"
        ));
    }
    if let GroundMotion::Record(r) = ground {
        let (lo, hi) = USUAL_RECORD_DT;
        if !(lo..=hi).contains(&r.dt) {
            out.push(format!(
                "the record is sampled every {} s, outside the usual [{lo}, {hi}] s of \
                 accelerograms (50 Hz to 10 kHz); check `ground_motion.dt` or the file's time \
                 column (in s)",
                r.dt
            ));
        }
    }
    if pga_g > PLAUSIBLE_PGA {
        out.push(format!(
            "the ground motion's PGA is {pga_g:.3} g, above {PLAUSIBLE_PGA} g: beyond the strongest \
             shaking ever recorded (about 3–4 g) and far beyond design levels (≤ 1–1.5 g); \
             PGA is in g — was it given in m/s²?"
        ));
    }
    let key = |k: usize| {
        if contact.levels.len() > 1 {
            format!("contact.level[{}].gap", k + 1)
        } else {
            "contact.gap".into()
        }
    };
    for (k, l) in contact.levels.iter().enumerate() {
        if l.gap >= PLAUSIBLE_GAP {
            out.push(format!(
                "`{}` = {} m: a gap of metres between adjacent buildings (usual gaps are \
                 centimetres); the unit is m — was it given in mm or cm?",
                key(k),
                l.gap
            ));
        }
    }
    out
}

fn structure(
    c: &Check,
    i: usize,
    s: &RawStructure,
    table_start: usize,
    defaults: &mut Vec<String>,
) -> Result<Structure, ScenarioError> {
    let key = |k: &str| format!("structure[{}].{k}", i + 1);
    let near = Some(table_start);
    let length = c.positive(
        c.required(&s.length, &key("length"), "height L in m", near)?,
        &key("length"),
        "m",
    )?;
    let mass = c.positive(
        c.required(&s.mass, &key("mass"), "total mass M in kg", near)?,
        &key("mass"),
        "kg",
    )?;
    let given: Vec<(&str, &Spanned<f64>)> = [
        ("period", &s.period),
        ("bending_stiffness", &s.bending_stiffness),
        ("tip_stiffness", &s.tip_stiffness),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.as_ref().map(|v| (k, v)))
    .collect();
    let stiffness = match given.as_slice() {
        [] => {
            return Err(c.missing(
                &key("period"),
                "one of `period` (s), `bending_stiffness` (N·m²) or `tip_stiffness` (N/m)",
                near,
            ))
        }
        [(k, v)] => {
            let (unit, make): (&str, fn(f64) -> Stiffness) = match *k {
                "period" => ("s", Stiffness::Period),
                "bending_stiffness" => ("N·m²", Stiffness::Bending),
                _ => ("N/m", Stiffness::Tip),
            };
            make(c.positive(v, &key(k), unit)?)
        }
        [(k1, _), (k2, v2), ..] => {
            return Err(c.invalid(
                v2,
                &key(k2),
                &format!(
                    "give exactly one of `period`, `bending_stiffness`, `tip_stiffness` (also `{k1}` is given)"
                ),
            ))
        }
    };
    let modes = match &s.modes {
        None => {
            defaults.push(format!("{} = {DEFAULT_MODES}", key("modes")));
            DEFAULT_MODES
        }
        Some(v) => {
            let range = format!("must be a whole number from 1 to {MAX_MODES}");
            let bad = |reason: String| ScenarioError::Invalid {
                at: c.ctx.at(Some(v.span().start)),
                key: key("modes"),
                value: v.get_ref().to_string(),
                reason,
            };
            match v.get_ref() {
                toml::Value::Integer(n) if (1..=MAX_MODES).contains(n) => *n as usize,
                toml::Value::Integer(_) => return Err(bad(range)),
                toml::Value::Float(x)
                    if x.fract() == 0.0 && (1.0..=MAX_MODES as f64).contains(x) =>
                {
                    return Err(bad(format!(
                        "must be a whole number (write {}, without a decimal point), from 1 to {MAX_MODES}",
                        *x as i64
                    )));
                }
                _ => return Err(bad(range)),
            }
        }
    };
    let damping = match (&s.damping_ratio, &s.strain_rate_damping, &s.air_damping) {
        (Some(z), None, None) => {
            let values = match z.get_ref() {
                RawZeta::One(v) => vec![*v],
                RawZeta::Many(v) => v.clone(),
            };
            if values.len() != 1 && values.len() != modes {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(z.span().start)),
                    key: key("damping_ratio"),
                    value: format!("a list of {}", values.len()),
                    reason: format!("give one ratio, or a list of exactly {modes} (one per mode)"),
                });
            }
            if let Some(bad) = values
                .iter()
                .find(|v| !(v.is_finite() && **v >= 0.0 && **v < 1.0))
            {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(z.span().start)),
                    key: key("damping_ratio"),
                    value: bad.to_string(),
                    reason: "damping ratios must be in [0, 1)".into(),
                });
            }
            for v in &values {
                c.usual(*v, &key("damping_ratio"), "");
            }
            Damping::Modal(values)
        }
        (None, None, None) => {
            defaults.push(format!(
                "{} = {DEFAULT_DAMPING_RATIO}",
                key("damping_ratio")
            ));
            Damping::Modal(vec![DEFAULT_DAMPING_RATIO])
        }
        (Some(z), _, _) => {
            return Err(ScenarioError::Invalid {
                at: c.ctx.at(Some(z.span().start)),
                key: key("damping_ratio"),
                value: "given with strain_rate_damping/air_damping".into(),
                reason: "give either `damping_ratio` or the physical coefficients, not both".into(),
            });
        }
        (None, sr, air) => {
            let strain_rate = match sr {
                Some(v) => c.non_negative(v, &key("strain_rate_damping"), "s")?,
                None => 0.0,
            };
            let air = match air {
                Some(v) => c.non_negative(v, &key("air_damping"), "N·s/m²")?,
                None => 0.0,
            };
            Damping::Physical { strain_rate, air }
        }
    };
    Ok(Structure::Cantilever(Cantilever {
        name: s
            .name
            .clone()
            .unwrap_or_else(|| format!("structure {}", i + 1)),
        length,
        mass,
        stiffness,
        modes,
        damping,
    }))
}

fn contact(
    c: &Check,
    raw: Option<&Spanned<RawContact>>,
    min_length: f64,
    defaults: &mut Vec<String>,
) -> Result<ContactSpec, ScenarioError> {
    let raw = raw.ok_or_else(|| {
        c.missing(
            "contact",
            "a [contact] table with at least `stiffness` and `gap`",
            None,
        )
    })?;
    let near = Some(raw.span().start);
    let r = raw.get_ref();
    let law_name = r.law.as_ref().map_or("hertz", |l| l.get_ref().as_str());
    if r.law.is_none() {
        defaults.push("contact.law = \"hertz\"".into());
    }
    let stiffness_unit = match law_name {
        "linear" | "kelvin" => "N/m",
        _ => "N/m^1.5",
    };
    let impulsive = law_name == "stereomechanical";
    let stiffness = match (&r.stiffness, impulsive) {
        (Some(k), true) => {
            return Err(c.invalid(
                k,
                "contact.stiffness",
                "law `stereomechanical` is instantaneous and has no stiffness",
            ));
        }
        (None, true) => 0.0,
        (k, false) => c.positive(
            c.required(
                k,
                "contact.stiffness",
                &format!("contact stiffness in {stiffness_unit}"),
                near,
            )?,
            "contact.stiffness",
            stiffness_unit,
        )?,
    };
    let needs_e = matches!(
        law_name,
        "kelvin" | "hertzdamp" | "jankowski" | "stereomechanical"
    );
    let restitution = match (&r.restitution, needs_e) {
        (Some(e), true) if impulsive => {
            let x = *e.get_ref();
            if x.is_finite() && (0.0..=1.0).contains(&x) {
                x
            } else {
                return Err(c.invalid(
                    e,
                    "contact.restitution",
                    "coefficient of restitution must be in [0, 1]",
                ));
            }
        }
        (Some(e), true) => c.restitution(e, "contact.restitution")?,
        (None, true) => {
            return Err(c.missing(
                "contact.restitution",
                &format!("law `{law_name}` needs a coefficient of restitution"),
                near,
            ));
        }
        (Some(e), false) => {
            return Err(c.invalid(
                e,
                "contact.restitution",
                &format!(
                    "law `{law_name}` has no restitution parameter (it is used by kelvin, hertzdamp, jankowski, stereomechanical)"
                ),
            ));
        }
        (None, false) => 1.0,
    };
    if r.restitution.is_some() {
        c.usual(restitution, "contact.restitution", "");
    }
    if let (Some(m), false) = (&r.damping_model, law_name == "hertzdamp") {
        return Err(c.invalid(
            m,
            "contact.damping_model",
            "only law `hertzdamp` takes a damping model",
        ));
    }
    let law = match law_name {
        "hertz" => ContactLaw::Hertz { stiffness },
        "linear" => ContactLaw::Linear { stiffness },
        "kelvin" => ContactLaw::Kelvin {
            stiffness,
            restitution,
        },
        "jankowski" => ContactLaw::Jankowski {
            stiffness,
            restitution,
        },
        "stereomechanical" => ContactLaw::Stereomechanical { restitution },
        "hertzdamp" => {
            let model = match r.damping_model.as_ref().map(|m| m.get_ref().as_str()) {
                None | Some("lankarani-nikravesh") => HertzDampModel::LankaraniNikravesh,
                Some("hunt-crossley") => HertzDampModel::HuntCrossley,
                Some("ye-li-zhu") => HertzDampModel::YeLiZhu,
                Some(_) => {
                    let m = r.damping_model.as_ref().unwrap_or_else(|| unreachable!());
                    return Err(c.invalid(
                        m,
                        "contact.damping_model",
                        "must be one of \"lankarani-nikravesh\", \"hunt-crossley\", \"ye-li-zhu\"",
                    ));
                }
            };
            ContactLaw::HertzDamp {
                stiffness,
                restitution,
                model,
            }
        }
        _ => {
            let l = r.law.as_ref().unwrap_or_else(|| unreachable!());
            return Err(c.invalid(
                l,
                "contact.law",
                &format!("must be one of {}", quoted(CONTACT_LAWS)),
            ));
        }
    };
    // (near the base the structures barely move: the effective mass of a contact there grows
    // without bound, 1/φ(h)², and is infinite at h = 0)
    let lowest = min_length * MIN_CONTACT_HEIGHT_FRACTION;
    let height_reason = format!(
        "contact height must be in [{lowest}, {min_length}] m, i.e. [{MIN_CONTACT_HEIGHT_FRACTION} \
         min(L1, L2), min(L1, L2)] (no contact transfers anything at the base)"
    );
    let check_height = |h: &Spanned<f64>, key: &str| -> Result<f64, ScenarioError> {
        let x = *h.get_ref();
        if x.is_finite() && x >= lowest && x <= min_length * (1.0 + 1e-12) {
            Ok(x.min(min_length))
        } else {
            Err(c.invalid(h, key, &height_reason))
        }
    };
    let levels = match &r.level {
        None => {
            let gap = c.non_negative(
                c.required(&r.gap, "contact.gap", "at-rest gap in m (≥ 0)", near)?,
                "contact.gap",
                "m",
            )?;
            let height = match &r.height {
                Some(h) => check_height(h, "contact.height")?,
                None => {
                    defaults.push(format!("contact.height = {min_length} (min(L1, L2))"));
                    min_length
                }
            };
            vec![ContactLevel { height, gap }]
        }
        Some(levels) => {
            for (k, v) in [("contact.gap", &r.gap), ("contact.height", &r.height)] {
                if let Some(v) = v {
                    return Err(c.invalid(
                        v,
                        k,
                        "with [[contact.level]] tables, give `height` and `gap` in each level instead",
                    ));
                }
            }
            if levels.is_empty() {
                return Err(c.missing("contact.level", "at least one [[contact.level]]", near));
            }
            let mut out = Vec::with_capacity(levels.len());
            for (i, lv) in levels.iter().enumerate() {
                let key = |k: &str| format!("contact.level[{}].{k}", i + 1);
                let lnear = Some(lv.span().start);
                let l = lv.get_ref();
                let height = check_height(
                    c.required(&l.height, &key("height"), "contact height in m", lnear)?,
                    &key("height"),
                )?;
                let gap = c.non_negative(
                    c.required(&l.gap, &key("gap"), "at-rest gap in m (≥ 0)", lnear)?,
                    &key("gap"),
                    "m",
                )?;
                if out.iter().any(|o: &ContactLevel| o.height == height) {
                    return Err(c.invalid(
                        l.height.as_ref().unwrap_or_else(|| unreachable!()),
                        &key("height"),
                        "two contact levels at the same height",
                    ));
                }
                out.push(ContactLevel { height, gap });
            }
            out
        }
    };
    Ok(ContactSpec { law, levels })
}

fn ground(
    c: &Check,
    raw: Option<&Spanned<RawGround>>,
    base_dir: &Path,
    records: Option<&RecordCache>,
) -> Result<GroundMotion, ScenarioError> {
    let raw = raw.ok_or_else(|| {
        c.missing(
            "ground_motion",
            "a [ground_motion] table (kind = \"harmonic\" with `pga` and `period`, or kind = \"record\" with `file`)",
            None,
        )
    })?;
    let near = Some(raw.span().start);
    let g = raw.get_ref();
    let kind = c.required(
        &g.kind,
        "ground_motion.kind",
        "\"harmonic\", \"record\" or \"spectrum\"",
        near,
    )?;
    let forbid = |present: &[(&str, bool)], kind: &str| -> Result<(), ScenarioError> {
        for (k, p) in present {
            if *p {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(near),
                    key: format!("ground_motion.{k}"),
                    value: "(given)".into(),
                    reason: format!("not used with kind = \"{kind}\""),
                });
            }
        }
        Ok(())
    };
    match kind.get_ref().as_str() {
        "harmonic" => {
            forbid(
                &[
                    ("file", g.file.is_some()),
                    ("units", g.units.is_some()),
                    ("scale_to_pga", g.scale_to_pga.is_some()),
                    ("dt", g.dt.is_some()),
                    ("component", g.component.is_some()),
                    ("processing", g.processing.is_some()),
                ],
                "harmonic",
            )?;
            let pga = c.positive(
                c.required(
                    &g.pga,
                    "ground_motion.pga",
                    "peak ground acceleration in g",
                    near,
                )?,
                "ground_motion.pga",
                "g",
            )?;
            let period = c.positive(
                c.required(
                    &g.period,
                    "ground_motion.period",
                    "ground period T_g in s",
                    near,
                )?,
                "ground_motion.period",
                "s",
            )?;
            Ok(GroundMotion::Harmonic(Harmonic::from_pga_g(pga, period)))
        }
        "record" => {
            forbid(
                &[("pga", g.pga.is_some()), ("period", g.period.is_some())],
                "record",
            )?;
            let file = c.required(
                &g.file,
                "ground_motion.file",
                "the record file (PEER .AT2, COSMOS, CSMIP/DMG, K-NET/KiK-net, ESM, two columns `t a`, or one column with `dt`), relative to the scenario",
                near,
            )?;
            let units = record_keys::units(c, g.units.as_ref())?;
            let component = record_keys::component(c, g.component.as_ref())?;
            let processing = record_keys::processing(c, g.processing.as_ref())?;
            let scale_to_pga = match &g.scale_to_pga {
                Some(v) => Some(c.positive(v, "ground_motion.scale_to_pga", "g")?),
                None => None,
            };
            let dt = match &g.dt {
                Some(v) => Some(c.positive(v, "ground_motion.dt", "s")?),
                None => None,
            };
            let path = base_dir.join(file.get_ref());
            let opts = RecordOptions {
                units,
                dt,
                scale_to_pga,
                component,
                processing,
            };
            let read = || {
                Record::read(&path, &opts)
                    .map(Arc::new)
                    .map_err(|e| ScenarioError::Record {
                        at: c.ctx.at(Some(file.span().start)),
                        key: "ground_motion.file".into(),
                        source: Box::new(e),
                    })
            };
            let record = match records {
                None => read()?,
                Some(cache) => cache.get_or_read(&path, &opts, read)?,
            };
            // what the reader noticed but accepted (a `units` key overriding the file's)
            c.ctx
                .warnings
                .borrow_mut()
                .extend(record.warnings.iter().cloned());
            // what the file gives is held to the ranges of the keys that could give it
            let g = crate::model::ground_motion::STANDARD_GRAVITY;
            for (what, x, key, unit) in [
                ("PGA", record.pga() / g, "pga", "g"),
                ("sample spacing", record.dt, "dt", "s"),
                ("duration", record.duration(), "duration", "s"),
            ] {
                if let Some((lo, hi, range_of)) = physical_range(key)
                    && !(lo..=hi).contains(&x)
                {
                    return Err(c.invalid(
                        file,
                        "ground_motion.file",
                        &format!(
                            "the record's {what} is {x:e} {unit}, outside [{lo:e}, {hi:e}] {unit} \
                             ({range_of}): check the file's units (`units`, `dt`) or scale it \
                             with `scale_to_pga`"
                        ),
                    ));
                }
            }
            Ok(GroundMotion::Record(record))
        }
        // a design spectrum has no time history: crate::input::scenario::design checks its keys
        "spectrum" => Ok(GroundMotion::None),
        _ => Err(c.invalid(
            kind,
            "ground_motion.kind",
            "must be \"harmonic\", \"record\", \"spectrum\" or \"suite\"",
        )),
    }
}

fn solver(
    c: &Check,
    raw: Option<&Spanned<RawSolver>>,
    ground: &GroundMotion,
    defaults: &mut Vec<String>,
) -> Result<(SolverSettings, f64), ScenarioError> {
    let empty = RawSolver {
        method: None,
        dt: None,
        duration: None,
        output_interval: None,
        rtol: None,
        atol: None,
    };
    let s = raw.map_or(&empty, |r| r.get_ref());
    let method = match s.method.as_ref() {
        None => {
            defaults.push("solver.method = \"adaptive\"".into());
            Method::Adaptive
        }
        Some(m) => match Method::from_name(m.get_ref()) {
            Some(method) => method,
            None => {
                let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
                return Err(c.invalid(
                    m,
                    "solver.method",
                    &format!("must be one of {}", quoted(&names)),
                ));
            }
        },
    };
    let rtol = match &s.rtol {
        None => {
            if method == Method::Adaptive {
                defaults.push(format!("solver.rtol = {:e}", method.default_rtol()));
            }
            method.default_rtol()
        }
        Some(v) => {
            let x = *v.get_ref();
            if !(x.is_finite() && (MIN_RTOL..=0.1).contains(&x)) {
                return Err(c.invalid(
                    v,
                    "solver.rtol",
                    "must be in [1e-12, 0.1] (below 1e-12 double precision cannot resolve the \
                     error estimate)",
                ));
            }
            c.usual(x, "solver.rtol", "");
            x
        }
    };
    let atol = match &s.atol {
        None => rtol * ATOL_PER_RTOL,
        Some(v) => {
            let x = *v.get_ref();
            if !(x.is_finite() && (MIN_ATOL..=1.0).contains(&x)) {
                return Err(c.invalid(
                    v,
                    "solver.atol",
                    "must be in [1e-14, 1] m (an error in a structure's top displacement)",
                ));
            }
            c.usual(x, "solver.atol", "m");
            x
        }
    };
    let duration = match &s.duration {
        Some(v) => c.positive(v, "solver.duration", "s")?,
        None => {
            let (d, why) = match ground {
                GroundMotion::Record(r) => (r.duration(), "the record's duration"),
                _ => (DEFAULT_HARMONIC_DURATION, "harmonic motion"),
            };
            defaults.push(format!("solver.duration = {d} ({why})"));
            d
        }
    };
    let dt = match &s.dt {
        Some(dt_v) => {
            let dt = c.positive(dt_v, "solver.dt", "s")?;
            if dt >= duration {
                return Err(c.invalid(
                    dt_v,
                    "solver.dt",
                    &format!("must be smaller than solver.duration = {duration} s"),
                ));
            }
            if duration / dt > 1e9 {
                return Err(c.invalid(
                    dt_v,
                    "solver.dt",
                    &format!("more than 10⁹ steps over {duration} s: use a larger step"),
                ));
            }
            dt
        }
        None if method == Method::Rk4 => {
            return Err(c.missing(
                "solver.dt",
                "the fixed step of method \"rk4\" in s (within its stability limit for the highest mode); or omit `method` for the adaptive default",
                raw.map(|r| r.span().start),
            ));
        }
        None => {
            let record_dt = match ground {
                GroundMotion::Record(r) => r.dt,
                _ => f64::INFINITY,
            };
            let dt = DEFAULT_DT.min(record_dt).min(duration / 10.0);
            defaults.push(format!("solver.dt = {dt}"));
            dt
        }
    };
    let output_interval = match &s.output_interval {
        None => {
            let x = (0.01f64).max(dt).min(duration);
            defaults.push(format!("solver.output_interval = {x}"));
            x
        }
        Some(v) => {
            let x = c.positive(v, "solver.output_interval", "s")?;
            if x > duration {
                return Err(c.invalid(
                    v,
                    "solver.output_interval",
                    &format!("must be in (0, {duration}] s (at most solver.duration)"),
                ));
            }
            x
        }
    };
    Ok((
        SolverSettings {
            method,
            dt,
            duration,
            rtol,
            atol,
        },
        output_interval,
    ))
}

fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}
