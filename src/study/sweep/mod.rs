//! Parameter sweeps (docs/model.md §1.3): a sweep file names a base scenario and axes; every point of
//! the full grid is a *case*, i.e. the base scenario's TOML with the axis values set, validated
//! exactly like a scenario file and run with [`crate::analysis::simulate::simulate`].
//!
//! ```toml
//! scenario = "paper-c.toml"        # base scenario, relative to this file
//! [[axis]]
//! key = "period_ratio"             # derived axis T1/T2 (varies structure 2's period)
//! values = [0.3, 0.5, 0.7]
//! [[axis]]
//! key = "ground_motion.pga"        # any scenario key by path
//! from = 0.1
//! to = 0.9
//! steps = 9                        # linear; `scale = "log"` for logarithmic
//! ```
//!
//! Axis keys:
//! - `period_ratio` = T1/T2: sets structure 2's `period` to T2 = T1/r (replacing a
//!   `bending_stiffness` or `tip_stiffness` given for it). T1 is structure 1's `period` if
//!   given; otherwise it is computed from its length, mass and stiffness by the modal model
//!   (docs/model.md §2.6: T1 = 2π/ω₁, ω₁ = (β₁L)²√(EI/(mL⁴))).
//! - `ground_period_ratio` = T2/Tg: sets the harmonic ground motion's `period` to Tg = T2/r,
//!   with T2 as above (after `period_ratio` is applied, when both are swept).
//! - any scenario key by path: `structure.1.period` (1-based structure index; also written
//!   `structure[1].period`), `contact.gap`, `contact.level.2.gap`, `ground_motion.pga`,
//!   `solver.dt`, … Setting one of a structure's `period`, `bending_stiffness`,
//!   `tip_stiffness` removes the other two; `damping_ratio` replaces the physical damping
//!   coefficients and vice versa.
//! - `ground_motion.file` with `values = ["a.AT2", "b.AT2"]`: record files, relative to the
//!   sweep file; the ground motion becomes a record (a harmonic base's `pga` and `period` are
//!   dropped). With a record, a `ground_motion.pga` axis sets `scale_to_pga`.
//!
//! The grid is the full product of the axes, first axis slowest; case `i` is numbered from 0.

pub mod results;
pub mod run;

use std::fmt;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::{Spanned, Table, Value};

use crate::input::scenario::{Location, RecordCache, Scenario, ScenarioError};
use crate::model::structure::{Cantilever, Damping, Stiffness};

/// Most cases a sweep may have.
pub const MAX_CASES: usize = 10_000_000;

/// Most values on one axis.
pub const MAX_STEPS: i64 = 1_000_000;

/// Why a sweep could not be set up, run or merged.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// A file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// Path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// A file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// Path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not valid TOML, a value of the wrong type, or an unknown key.
    #[error("{at}: {message}")]
    Syntax {
        /// Where.
        at: Location,
        /// What the TOML parser said.
        message: String,
    },
    /// A key is missing, out of range or inconsistent.
    #[error("{at}: `{key}`: {reason}")]
    Invalid {
        /// Where.
        at: Location,
        /// The key concerned.
        key: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// Not one case of the sweep is a valid scenario: the base scenario or the axes are wrong.
    #[error(
        "no case of the sweep is a valid scenario; case {case} ({label}): {reason}\n\
         (fix the base scenario {scenario} or the axes in {sweep})"
    )]
    NoValidCase {
        /// The first case.
        case: usize,
        /// Its axis values.
        label: String,
        /// Why it is invalid.
        reason: String,
        /// The base scenario file.
        scenario: String,
        /// The sweep file.
        sweep: String,
    },
    /// The output directory holds results of another sweep, or a damaged journal.
    #[error("{path}: {message}")]
    Journal {
        /// The journal or results file.
        path: String,
        /// What is wrong and what to do.
        message: String,
    },
    /// Merging shard results failed.
    #[error("merge: {0}")]
    Merge(String),
    /// Bad command-line value (shard, jobs, plot selection).
    #[error("{0}")]
    Usage(String),
}

// ---------------------------------------------------------------------------------------------
// Raw schema

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSweep {
    scenario: Option<Spanned<String>>,
    axis: Option<Spanned<Vec<Spanned<RawAxis>>>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxis {
    key: Option<Spanned<String>>,
    values: Option<Spanned<Vec<Spanned<RawValue>>>>,
    from: Option<Spanned<f64>>,
    to: Option<Spanned<f64>>,
    steps: Option<Spanned<i64>>,
    scale: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawValue {
    Int(i64),
    Num(f64),
    Text(String),
    List(Vec<f64>),
}

// ---------------------------------------------------------------------------------------------
// Axes

/// One value on an axis.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValue {
    /// A number.
    Number(f64),
    /// An integer (e.g. `structure.1.modes`).
    Integer(i64),
    /// Text: a record file as listed in the sweep file, a contact law name, …
    Text(String),
    /// A list of numbers (a building's `floor_masses`, `storey_stiffnesses`, …).
    List(Vec<f64>),
}

impl AxisValue {
    /// The value as written in the results table (numbers in shortest round-trip form).
    pub fn to_csv(&self) -> String {
        match self {
            AxisValue::Number(x) => results::fmt_f64(*x),
            AxisValue::Integer(i) => i.to_string(),
            AxisValue::Text(s) => s.clone(),
            AxisValue::List(v) => format!(
                "[{}]",
                v.iter()
                    .map(|x| results::fmt_f64(*x))
                    .collect::<Vec<_>>()
                    .join(" ")
            ),
        }
    }
}

impl fmt::Display for AxisValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AxisValue::Text(s) => write!(f, "\"{s}\""),
            other => f.write_str(&other.to_csv()),
        }
    }
}

/// The type of value a scenario key takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Number,
    Integer,
    Text,
    File,
    List,
}

/// Where in the scenario an axis writes.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Section {
    Structure(usize),
    /// A structure's `hysteresis` table (issue 16).
    Hysteresis(usize),
    Contact,
    Level(usize),
    Ground,
    Solver,
}

#[derive(Debug, Clone, PartialEq, Eq)]
enum Target {
    PeriodRatio,
    GroundPeriodRatio,
    /// `structure.N.stiffness_scale` (`mass = false`) or `structure.N.mass_scale`: every
    /// stiffness (mass) of structure N times the value, the periods given following.
    Scale {
        structure: usize,
        mass: bool,
    },
    Key {
        section: Section,
        field: &'static str,
        kind: Kind,
    },
}

/// One axis of the grid.
#[derive(Debug, Clone)]
pub struct Axis {
    /// The key as written (normalised: `structure[2].period` → `structure.2.period`); also
    /// the column name in the results.
    pub key: String,
    /// The values, in grid order.
    pub values: Vec<AxisValue>,
    target: Target,
}

const STRUCTURE_FIELDS: &[(&str, Kind)] = &[
    ("length", Kind::Number),
    ("mass", Kind::Number),
    ("period", Kind::Number),
    ("bending_stiffness", Kind::Number),
    ("tip_stiffness", Kind::Number),
    ("modes", Kind::Integer),
    ("damping_ratio", Kind::Number),
    ("strain_rate_damping", Kind::Number),
    ("air_damping", Kind::Number),
    ("name", Kind::Text),
    // a shear building's uniform shorthand (kind = "shear-building")
    ("storeys", Kind::Integer),
    ("storey_height", Kind::Number),
    ("floor_mass", Kind::Number),
    ("storey_stiffness", Kind::Number),
    // a building's lists, one value per floor (or per mode for `periods`)
    ("floor_heights", Kind::List),
    ("floor_masses", Kind::List),
    ("storey_stiffnesses", Kind::List),
    ("periods", Kind::List),
];
/// A yielding building's Bouc–Wen keys (`structure.N.hysteresis.KEY`; one value for every
/// storey).
const HYSTERESIS_FIELDS: &[(&str, Kind)] = &[
    ("yield_drifts", Kind::Number),
    ("yield_forces", Kind::Number),
    ("post_yield_ratio", Kind::Number),
    ("exponent", Kind::Number),
    ("beta", Kind::Number),
    ("gamma", Kind::Number),
];
const CONTACT_FIELDS: &[(&str, Kind)] = &[
    ("stiffness", Kind::Number),
    ("restitution", Kind::Number),
    ("gap", Kind::Number),
    ("height", Kind::Number),
    ("law", Kind::Text),
    ("damping_model", Kind::Text),
];
const LEVEL_FIELDS: &[(&str, Kind)] = &[("height", Kind::Number), ("gap", Kind::Number)];
const GROUND_FIELDS: &[(&str, Kind)] = &[
    ("pga", Kind::Number),
    ("period", Kind::Number),
    ("scale_to_pga", Kind::Number),
    ("dt", Kind::Number),
    ("file", Kind::File),
    ("units", Kind::Text),
    ("kind", Kind::Text),
];
const SOLVER_FIELDS: &[(&str, Kind)] = &[
    ("dt", Kind::Number),
    ("duration", Kind::Number),
    ("output_interval", Kind::Number),
    ("method", Kind::Text),
];

/// Every key an axis may have (for messages), with `N` for an index.
fn valid_keys() -> Vec<String> {
    let mut v = vec![
        "period_ratio".to_string(),
        "ground_period_ratio".to_string(),
    ];
    for (f, _) in STRUCTURE_FIELDS {
        v.push(format!("structure.N.{f}"));
    }
    v.push("structure.N.stiffness_scale".into());
    v.push("structure.N.mass_scale".into());
    for (f, _) in HYSTERESIS_FIELDS {
        v.push(format!("structure.N.hysteresis.{f}"));
    }
    for (f, _) in CONTACT_FIELDS {
        v.push(format!("contact.{f}"));
    }
    for (f, _) in LEVEL_FIELDS {
        v.push(format!("contact.level.N.{f}"));
    }
    for (f, _) in GROUND_FIELDS {
        v.push(format!("ground_motion.{f}"));
    }
    for (f, _) in SOLVER_FIELDS {
        v.push(format!("solver.{f}"));
    }
    v
}

/// Parse a key path. `Err` is the reason.
fn parse_key(raw: &str) -> Result<(String, Target), String> {
    let key = raw.trim().replace('[', ".").replace(']', "");
    let parts: Vec<&str> = key.split('.').collect();
    let field = |list: &[(&'static str, Kind)], f: &str| {
        list.iter()
            .find(|(n, _)| *n == f)
            .map(|(n, k)| (*n, *k))
            .ok_or(())
    };
    let index = |s: &str, what: &str, max: Option<usize>| -> Result<usize, String> {
        match s.parse::<usize>() {
            Ok(n) if n >= 1 && max.is_none_or(|m| n <= m) => Ok(n - 1),
            _ => Err(format!(
                "`{s}` is not a valid {what} index: {}",
                match max {
                    Some(m) => format!("use 1 to {m} (1-based)"),
                    None => "use 1, 2, … (1-based)".into(),
                }
            )),
        }
    };
    let target = match parts.as_slice() {
        ["period_ratio"] => Ok(Target::PeriodRatio),
        ["ground_period_ratio"] => Ok(Target::GroundPeriodRatio),
        ["structure", n, f @ ("stiffness_scale" | "mass_scale")] => {
            let i = index(n, "structure", Some(2))?;
            Ok(Target::Scale {
                structure: i,
                mass: *f == "mass_scale",
            })
        }
        ["structure", n, "hysteresis", f] => {
            let i = index(n, "structure", Some(2))?;
            field(HYSTERESIS_FIELDS, f).map(|(field, kind)| Target::Key {
                section: Section::Hysteresis(i),
                field,
                kind,
            })
        }
        ["structure", n, f] => {
            let i = index(n, "structure", Some(2))?;
            field(STRUCTURE_FIELDS, f).map(|(field, kind)| Target::Key {
                section: Section::Structure(i),
                field,
                kind,
            })
        }
        ["contact", "level", n, f] => {
            let i = index(n, "contact level", None)?;
            field(LEVEL_FIELDS, f).map(|(field, kind)| Target::Key {
                section: Section::Level(i),
                field,
                kind,
            })
        }
        ["contact", f] => field(CONTACT_FIELDS, f).map(|(field, kind)| Target::Key {
            section: Section::Contact,
            field,
            kind,
        }),
        ["ground_motion", f] => field(GROUND_FIELDS, f).map(|(field, kind)| Target::Key {
            section: Section::Ground,
            field,
            kind,
        }),
        ["solver", f] => field(SOLVER_FIELDS, f).map(|(field, kind)| Target::Key {
            section: Section::Solver,
            field,
            kind,
        }),
        _ => Err(()),
    };
    match target {
        Ok(t) => Ok((key, t)),
        Err(()) => {
            let keys = valid_keys();
            let generic = key
                .split('.')
                .map(|p| {
                    if p.chars().all(|c| c.is_ascii_digit()) {
                        "N"
                    } else {
                        p
                    }
                })
                .collect::<Vec<_>>()
                .join(".");
            let best = keys
                .iter()
                .map(|k| (strsim::jaro_winkler(&generic, k), k))
                .max_by(|a, b| a.0.total_cmp(&b.0));
            let mut msg = "unknown axis key".to_string();
            if let Some((score, k)) = best
                && score > 0.8
            {
                msg.push_str(&format!("; did you mean `{k}`?"));
            }
            msg.push_str(&format!(" (valid keys: {}; N is 1-based)", keys.join(", ")));
            Err(msg)
        }
    }
}

/// Round to 12 significant digits, so that generated grids read 0.3, not 0.30000000000000004.
fn tidy(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    format!("{x:.11e}").parse().unwrap_or(x)
}

// ---------------------------------------------------------------------------------------------
// The sweep

/// A checked sweep: the base scenario as a TOML table and the axes.
#[derive(Debug)]
pub struct Sweep {
    /// The sweep file, as given.
    pub path: PathBuf,
    /// The base scenario file (resolved relative to the sweep file).
    pub scenario_path: PathBuf,
    /// The axes, first (slowest) first.
    pub axes: Vec<Axis>,
    base: Table,
    base_dir: PathBuf,
    sweep_dir: PathBuf,
    identity: u64,
    /// The sweep file's text and the base scenario's text, as read.
    text: String,
    base_text: String,
    records: RecordCache,
}

struct Ctx<'a> {
    text: &'a str,
    file: &'a str,
}

impl Ctx<'_> {
    fn at(&self, offset: Option<usize>) -> Location {
        Location {
            file: std::sync::Arc::from(self.file),
            line_col: offset.map(|o| line_col(self.text, o)),
        }
    }
    fn invalid(&self, offset: Option<usize>, key: &str, reason: impl Into<String>) -> SweepError {
        SweepError::Invalid {
            at: self.at(offset),
            key: key.to_string(),
            reason: reason.into(),
        }
    }
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

/// FNV-1a, 64 bit: the sweep's identity in its journal (not cryptographic; it only tells
/// sweeps apart).
pub fn fnv1a(parts: &[&[u8]]) -> u64 {
    let mut h = Fnv1a::new();
    for p in parts {
        h.part(p);
    }
    h.finish()
}

/// [`fnv1a`] fed piece by piece, files streamed in blocks (no file is held in memory).
#[derive(Debug, Clone, Copy)]
pub struct Fnv1a(u64);

impl Fnv1a {
    /// The empty hash.
    pub fn new() -> Fnv1a {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }

    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// Ends a part (a separator, so that ("ab", "c") and ("a", "bc") differ).
    pub fn end_part(&mut self) {
        self.0 ^= 0xff;
        self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
    }

    /// One whole part.
    pub fn part(&mut self, b: &[u8]) {
        self.bytes(b);
        self.end_part();
    }

    /// A file's bytes, read in 64 KiB blocks (up to [`crate::model::ground_motion::record::MAX_RECORD_BYTES`]);
    /// a read error ends the stream (the case's own validation reports it).
    pub fn stream(&mut self, mut r: impl std::io::Read) {
        let mut buf = vec![0u8; 1 << 16];
        let mut left = crate::model::ground_motion::record::MAX_RECORD_BYTES;
        while left > 0 {
            match r.read(&mut buf) {
                Ok(0) | Err(_) => break,
                Ok(n) => {
                    self.bytes(&buf[..n]);
                    left = left.saturating_sub(n as u64);
                }
            }
        }
    }

    /// The hash.
    pub fn finish(self) -> u64 {
        self.0
    }
}

impl Default for Fnv1a {
    fn default() -> Fnv1a {
        Fnv1a::new()
    }
}

fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Float(x) => Some(*x),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

impl Sweep {
    /// Read and check a sweep file and its base scenario.
    pub fn from_file(path: &Path) -> Result<Sweep, SweepError> {
        let text = crate::input::file::read_text(path, crate::input::file::MAX_TEXT_BYTES)
            .map_err(|e| SweepError::Read {
                path: path.display().to_string(),
                source: e,
            })?;
        Sweep::from_toml(&text, path)
    }

    /// Check sweep text; `path` names it in messages and resolves the base scenario and
    /// record files (relative to its directory).
    pub fn from_toml(text: &str, path: &Path) -> Result<Sweep, SweepError> {
        Sweep::from_toml_with_base(text, path, None)
    }

    /// As [`Sweep::from_toml`], with the base scenario's text given instead of read from the
    /// file the sweep names: `base` = (its TOML text, its path — which names it in messages,
    /// and whose directory resolves its record files). The sweep text's `scenario` key must
    /// still be there (it is not read). This is how the Python package sweeps a scenario built
    /// in memory (`pounding.sweep(scenario, axes=…)`), and how a sweep travels to other
    /// processes ([`Sweep::sources`]).
    pub fn from_toml_with_base(
        text: &str,
        path: &Path,
        base: Option<(&str, &Path)>,
    ) -> Result<Sweep, SweepError> {
        let file = path.display().to_string();
        let ctx = Ctx { text, file: &file };
        let raw: RawSweep = toml::from_str(text).map_err(|e| {
            let mut message = e.message().trim().to_string();
            // an unknown key: name the table and list its keys, as a scenario's message does
            if let Some((key, valid)) = crate::input::scenario::diagnostics::unknown_field(&message) {
                let table = if valid.iter().any(|k| k == "scenario") {
                    "the top level of the sweep file"
                } else {
                    "[[axis]]"
                };
                message = format!(
                    "unknown key `{key}` in {table}{}",
                    crate::input::scenario::diagnostics::key_hint(&key, &valid)
                );
            }
            if message.starts_with("unknown key") && text.contains("[[structure]]") {
                message.push_str(
                    " — this looks like a scenario file: `pounding run` runs it; a sweep file names one \
                     with `scenario = \"…\"` and adds [[axis]] tables",
                );
            }
            SweepError::Syntax {
                at: ctx.at(e.span().map(|s| s.start)),
                message,
            }
        })?;
        let sweep_dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
            .to_path_buf();
        let sc = raw.scenario.as_ref().ok_or_else(|| {
            ctx.invalid(
                None,
                "scenario",
                "missing: name the base scenario file, e.g. scenario = \"paper-c.toml\" (relative to the sweep file)",
            )
        })?;
        let (scenario_path, base_text) = match base {
            Some((text, p)) => (p.to_path_buf(), text.to_string()),
            None => {
                let scenario_path = sweep_dir.join(sc.get_ref());
                let base_text = crate::input::file::read_text(
                    &scenario_path,
                    crate::input::file::MAX_TEXT_BYTES,
                )
                .map_err(|e| {
                    ctx.invalid(
                        Some(sc.span().start),
                        "scenario",
                        format!(
                            "cannot read the base scenario {}: {e}",
                            scenario_path.display()
                        ),
                    )
                })?;
                (scenario_path, base_text)
            }
        };
        let base_name = scenario_path.display().to_string();
        let bctx = Ctx {
            text: &base_text,
            file: &base_name,
        };
        let mut base: Table = toml::from_str(&base_text).map_err(|e| SweepError::Syntax {
            at: bctx.at(e.span().map(|s| s.start)),
            message: e.message().trim().to_string(),
        })?;
        let base_dir = scenario_path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
            .to_path_buf();
        // make the base's own record file independent of the directory of the case text
        if let Some(Value::Table(g)) = base.get_mut("ground_motion")
            && let Some(Value::String(f)) = g.get_mut("file")
        {
            *f = absolute(&base_dir.join(&*f)).display().to_string();
        }

        let list = raw.axis.as_ref().ok_or_else(|| {
            ctx.invalid(
                None,
                "axis",
                "missing: give at least one [[axis]] table with `key` and `values` (or `from`, `to`, `steps`)",
            )
        })?;
        if list.get_ref().is_empty() {
            return Err(ctx.invalid(
                Some(list.span().start),
                "axis",
                "give at least one [[axis]]",
            ));
        }
        let mut axes: Vec<Axis> = Vec::new();
        let mut spans: Vec<usize> = Vec::new();
        for (n, a) in list.get_ref().iter().enumerate() {
            let axis = parse_axis(&ctx, n, a)?;
            if let Some(j) = axes.iter().position(|b| b.key == axis.key) {
                return Err(ctx.invalid(
                    Some(a.span().start),
                    &format!("axis[{}].key", n + 1),
                    format!("`{}` is already axis {}", axis.key, j + 1),
                ));
            }
            axes.push(axis);
            spans.push(a.span().start);
        }
        check_axes(&ctx, &axes, &spans, &base)?;
        let mut cases: usize = 1;
        for a in &axes {
            cases = cases.saturating_mul(a.values.len());
        }
        if cases > MAX_CASES {
            return Err(ctx.invalid(
                Some(list.span().start),
                "axis",
                format!(
                    "the grid has {cases} cases (results of about {}); a sweep may have at most \
                     {MAX_CASES} cases: use fewer values per axis (`values`, or `steps` of a range), \
                     or split the study into several sweep files",
                    crate::output::budget::format_size(
                        crate::output::budget::estimate_sweep(cases as u64, axes.len()).bytes
                    )
                ),
            ));
        }
        // the identity covers what the cases read: the sweep file, the base scenario and the
        // bytes of every record file (an edited record must not resume into old rows)
        let mut files: Vec<PathBuf> = Vec::new();
        if let Some(Value::Table(g)) = base.get("ground_motion")
            && let Some(Value::String(f)) = g.get("file")
        {
            files.push(PathBuf::from(f));
        }
        for a in &axes {
            if let Target::Key {
                kind: Kind::File, ..
            } = a.target
            {
                for v in &a.values {
                    if let AxisValue::Text(f) = v {
                        files.push(absolute(&sweep_dir.join(f)));
                    }
                }
            }
        }
        // the record files streamed through the hash (a file that is missing, not regular or
        // too large counts as empty here: its cases fail validation with the reason)
        let mut hash = Fnv1a::new();
        for p in [
            b"pounding-sweep-2".as_slice(),
            text.as_bytes(),
            base_text.as_bytes(),
        ] {
            hash.part(p);
        }
        for f in &files {
            if let Ok(file) = crate::model::ground_motion::record::open_record_file(f) {
                hash.stream(file);
            }
            hash.end_part();
        }
        let identity = hash.finish();
        Ok(Sweep {
            text: text.to_string(),
            base_text,
            path: path.to_path_buf(),
            scenario_path,
            axes,
            base,
            base_dir,
            sweep_dir,
            identity,
            records: RecordCache::new(),
        })
    }

    /// What the sweep was made of: its text, its path, the base scenario's text and path —
    /// [`Sweep::from_toml_with_base`] of them gives the same sweep (the same cases, the same
    /// [`Sweep::identity`]) without reading the files again, e.g. in another process. Record
    /// files are still read from their (absolute) paths.
    pub fn sources(&self) -> (&str, &Path, &str, &Path) {
        (&self.text, &self.path, &self.base_text, &self.scenario_path)
    }

    /// The code columns of the results (`sep_asce7`, …, in the order of
    /// [`crate::input::scenario::design::CODE_KEYS`]): one per code table in the base scenario's `[separation]`
    /// (the axes cannot change them), after the [`results::FIELDS`].
    pub fn code_columns(&self) -> Vec<&'static str> {
        let Some(Value::Table(sep)) = self.base.get("separation") else {
            return Vec::new();
        };
        crate::input::scenario::design::CODE_KEYS
            .iter()
            .zip(results::CODE_FIELDS)
            .filter(|(k, _)| sep.contains_key(**k))
            .map(|(_, f)| f)
            .collect()
    }

    /// The floor columns ([`results::FLOOR_FIELDS`]) when the base scenario has a building
    /// with floors (`kind = "shear-building"` or `"modal"`).
    pub fn floor_columns(&self) -> Vec<&'static str> {
        let buildings = match self.base.get("structure") {
            Some(Value::Array(list)) => list.iter().any(|s| {
                s.get("kind")
                    .and_then(Value::as_str)
                    .is_some_and(|k| k != "cantilever")
            }),
            _ => false,
        };
        if buildings {
            results::FLOOR_FIELDS.to_vec()
        } else {
            Vec::new()
        }
    }

    /// The ductility columns ([`results::DUCTILITY_FIELDS`]) when the base scenario has a
    /// yielding building (a `hysteresis` table in a `[[structure]]`).
    pub fn ductility_columns(&self) -> Vec<&'static str> {
        let yielding = match self.base.get("structure") {
            Some(Value::Array(list)) => list.iter().any(|s| s.get("hysteresis").is_some()),
            _ => false,
        };
        if yielding {
            results::DUCTILITY_FIELDS.to_vec()
        } else {
            Vec::new()
        }
    }

    /// Every column after [`results::FIELDS`]: the code columns, then the floor columns, then
    /// the ductility columns.
    pub fn extra_columns(&self) -> Vec<&'static str> {
        let mut v = self.code_columns();
        v.extend(self.floor_columns());
        v.extend(self.ductility_columns());
        v
    }

    /// Number of cases (the product of the axis lengths).
    pub fn len(&self) -> usize {
        self.axes.iter().map(|a| a.values.len()).product()
    }

    /// Always false: a sweep has at least one case.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Hash of the sweep file's and the base scenario's text and of every record file's bytes.
    pub fn identity(&self) -> u64 {
        self.identity
    }

    /// The index along each axis of case `case` (first axis slowest).
    pub fn indices(&self, case: usize) -> Vec<usize> {
        let mut rest = case;
        let mut idx = vec![0; self.axes.len()];
        for (j, a) in self.axes.iter().enumerate().rev() {
            idx[j] = rest % a.values.len();
            rest /= a.values.len();
        }
        idx
    }

    /// The axis values of case `case`.
    pub fn values(&self, case: usize) -> Vec<&AxisValue> {
        self.indices(case)
            .iter()
            .zip(&self.axes)
            .map(|(&i, a)| &a.values[i])
            .collect()
    }

    /// `key = value, …` for messages.
    pub fn label(&self, case: usize) -> String {
        self.values(case)
            .iter()
            .zip(&self.axes)
            .map(|(v, a)| format!("{} = {v}", a.key))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The scenario TOML of case `case`: the base with the axis values set. Self-contained
    /// (record files are absolute paths): save it and `pounding run` it to reproduce the case.
    pub fn case_toml(&self, case: usize) -> Result<String, String> {
        let mut t = self.case_table(case)?;
        // the case's own title: its values, not the base scenario's title (which may name
        // values this case changes, e.g. "T1/T2 = 0.7" on a period_ratio = 0.9 case)
        let name = |p: &Path| {
            p.file_name()
                .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into())
        };
        let title = format!(
            "{} — case {case} of sweep {} (base scenario {})",
            self.label(case),
            name(&self.path),
            name(&self.scenario_path)
        );
        t.insert("title".into(), Value::String(title));
        toml::to_string(&t).map_err(|e| format!("cannot encode the case as TOML: {e}"))
    }

    /// The scenario table of case `case`: the base with the axis values set (its title
    /// unchanged), not yet validated.
    pub fn case_table(&self, case: usize) -> Result<Table, String> {
        let mut t = self.base.clone();
        let values = self.values(case);
        // files first (they change the kind of ground motion), then plain keys, then the
        // derived ratios (which read the periods the other axes set)
        let order = |a: &Axis| match a.target {
            Target::Key {
                kind: Kind::File, ..
            } => 0,
            Target::Key { .. } => 1,
            Target::Scale { .. } => 2,
            Target::PeriodRatio => 3,
            Target::GroundPeriodRatio => 4,
        };
        let mut idx: Vec<usize> = (0..self.axes.len()).collect();
        idx.sort_by_key(|&j| order(&self.axes[j]));
        for j in idx {
            self.apply(&mut t, &self.axes[j], values[j])?;
        }
        Ok(t)
    }

    /// The validated scenario of case `case`, or why it is not valid (without file positions,
    /// which would point into the generated text).
    pub fn case_scenario(&self, case: usize) -> Result<Scenario, String> {
        let text = self.case_toml(case)?;
        let name = format!("{} [case {case}]", self.scenario_path.display());
        Scenario::from_toml_cached(&text, &name, &self.base_dir, Some(&self.records))
            .map_err(|e| reason(&e))
    }

    fn apply(&self, t: &mut Table, axis: &Axis, v: &AxisValue) -> Result<(), String> {
        match &axis.target {
            Target::PeriodRatio => {
                let r = as_f64(v);
                let t1 = first_period(t, 0).map_err(|e| format!("period_ratio: {e}"))?;
                let s2 = structure_mut(t, 1)?;
                s2.remove("bending_stiffness");
                s2.remove("tip_stiffness");
                s2.insert("period".into(), Value::Float(t1 / r));
                Ok(())
            }
            Target::Scale { structure, mass } => {
                let f = as_f64(v);
                let st = structure_mut(t, *structure)?;
                if *mass && st.contains_key("modes_file") {
                    return Err(format!(
                        "structure.{}.mass_scale: the floor masses are in the modes_file, which a \
                         sweep does not rewrite; give floor_heights, floor_masses and mode_shapes \
                         inline to scale them",
                        structure + 1
                    ));
                }
                let times = |x: &mut Value, by: f64| match x {
                    Value::Float(y) => *y *= by,
                    Value::Integer(y) => *x = Value::Float(*y as f64 * by),
                    Value::Array(list) => {
                        for y in list.iter_mut() {
                            match y {
                                Value::Float(z) => *z *= by,
                                Value::Integer(z) => *y = Value::Float(*z as f64 * by),
                                _ => {}
                            }
                        }
                    }
                    _ => {}
                };
                // K × f: ω × √f, periods ÷ √f; M × f: ω ÷ √f, periods × √f (a cantilever given
                // by `period` keeps it: its stiffness follows its mass)
                let (scaled, period): (&[&str], f64) = if *mass {
                    (&["mass", "floor_mass", "floor_masses"], f.sqrt())
                } else {
                    (
                        &[
                            "bending_stiffness",
                            "tip_stiffness",
                            "storey_stiffness",
                            "storey_stiffnesses",
                        ],
                        1.0 / f.sqrt(),
                    )
                };
                for k in scaled {
                    if let Some(x) = st.get_mut(*k) {
                        times(x, f);
                    }
                }
                if let Some(x) = st.get_mut("periods") {
                    times(x, period);
                }
                if !*mass && let Some(x) = st.get_mut("period") {
                    times(x, period);
                }
                Ok(())
            }
            Target::GroundPeriodRatio => {
                let r = as_f64(v);
                let t2 = first_period(t, 1).map_err(|e| format!("ground_period_ratio: {e}"))?;
                let g = section_mut(t, "ground_motion")?;
                g.insert("period".into(), Value::Float(t2 / r));
                Ok(())
            }
            Target::Key {
                section,
                field,
                kind,
            } => {
                let value = match (v, kind) {
                    (AxisValue::Text(s), Kind::File) => {
                        Value::String(absolute(&self.sweep_dir.join(s)).display().to_string())
                    }
                    (AxisValue::Text(s), _) => Value::String(s.clone()),
                    (AxisValue::Integer(i), _) => Value::Integer(*i),
                    (AxisValue::Number(x), _) => Value::Float(*x),
                    (AxisValue::List(v), _) => {
                        Value::Array(v.iter().map(|x| Value::Float(*x)).collect())
                    }
                };
                let table = match section {
                    Section::Structure(i) => structure_mut(t, *i)?,
                    Section::Hysteresis(i) => section_mut(structure_mut(t, *i)?, "hysteresis")?,
                    Section::Contact => section_mut(t, "contact")?,
                    Section::Level(i) => level_mut(t, *i)?,
                    Section::Ground => section_mut(t, "ground_motion")?,
                    Section::Solver => section_mut(t, "solver")?,
                };
                let mut field = *field;
                match (section, field) {
                    (Section::Structure(_), "period" | "bending_stiffness" | "tip_stiffness") => {
                        for k in ["period", "bending_stiffness", "tip_stiffness"] {
                            table.remove(k);
                        }
                    }
                    (Section::Structure(_), "damping_ratio") => {
                        table.remove("strain_rate_damping");
                        table.remove("air_damping");
                        table.remove("rayleigh");
                    }
                    (Section::Structure(_), "strain_rate_damping" | "air_damping") => {
                        table.remove("damping_ratio");
                    }
                    (Section::Hysteresis(_), "yield_drifts") => {
                        table.remove("yield_forces");
                    }
                    (Section::Hysteresis(_), "yield_forces") => {
                        table.remove("yield_drifts");
                    }
                    (Section::Ground, "file") => {
                        table.insert("kind".into(), Value::String("record".into()));
                        table.remove("pga");
                        table.remove("period");
                    }
                    (Section::Ground, "pga")
                        if table.get("kind").and_then(Value::as_str) == Some("record") =>
                    {
                        field = "scale_to_pga";
                    }
                    _ => {}
                }
                table.insert(field.into(), value);
                Ok(())
            }
        }
    }
}

/// A sweep file's text (`scenario = …` and one `[[axis]]` per entry of `axes`) for sweeping
/// a scenario given as text: each axis a table with `key` and either `values` or `from`, `to`,
/// `steps` (and `scale`), exactly as in a sweep file. `scenario` is the base scenario's file
/// name (it names it; [`Sweep::from_toml_with_base`] takes its text).
pub fn sweep_text(scenario: &str, axes: Vec<Table>) -> Result<String, SweepError> {
    let mut t = Table::new();
    t.insert("scenario".into(), Value::String(scenario.to_string()));
    t.insert(
        "axis".into(),
        Value::Array(axes.into_iter().map(Value::Table).collect()),
    );
    toml::to_string(&t)
        .map_err(|e| SweepError::Usage(format!("axes: cannot be written as TOML: {e}")))
}

/// A scenario's TOML text with keys set as a sweep sets them (the same key paths, derived
/// keys such as `period_ratio` included, and the same rules: setting a structure's `period`
/// removes its `bending_stiffness`, …): `values` = (key path, value) in any order, applied in
/// the sweep's order. `base` = the scenario's text and path (record files relative to its
/// directory). The result is not validated: read it with [`Scenario::from_toml`]. Used by the
/// Python package's `Scenario.replace`.
pub fn set_keys(
    base_text: &str,
    base_path: &Path,
    values: Vec<(String, Value)>,
) -> Result<String, SweepError> {
    let keys: Vec<String> = values.iter().map(|(k, _)| k.clone()).collect();
    let axes = values
        .into_iter()
        .map(|(k, v)| {
            let mut a = Table::new();
            a.insert("key".into(), Value::String(k));
            a.insert("values".into(), Value::Array(vec![v]));
            a
        })
        .collect();
    let name = base_path
        .file_name()
        .map_or_else(|| "scenario".into(), |n| n.to_string_lossy().into_owned());
    let text = sweep_text(&name, axes)?;
    let dir = base_path.parent().unwrap_or(Path::new("."));
    let at = || Location {
        file: std::sync::Arc::from(base_path.display().to_string()),
        line_col: None,
    };
    // messages name the key as given, not the generated sweep's `axis[N]`
    let sweep =
        Sweep::from_toml_with_base(&text, &dir.join("replace"), Some((base_text, base_path)))
            .map_err(|e| match e {
                SweepError::Invalid { key, reason, .. } if key.starts_with("axis[") => {
                    let n: usize = key[5..]
                        .split(']')
                        .next()
                        .and_then(|n| n.parse().ok())
                        .unwrap_or(1);
                    SweepError::Invalid {
                        at: at(),
                        key: keys.get(n.saturating_sub(1)).cloned().unwrap_or(key),
                        reason,
                    }
                }
                other => other,
            })?;
    let mut table = sweep.case_table(0).map_err(|reason| SweepError::Invalid {
        at: at(),
        key: sweep.label(0),
        reason,
    })?;
    // the title says what was changed (the base's title may name the values replaced)
    if let Some(Value::String(title)) = table.get_mut("title") {
        *title = format!("{title} — with {}", sweep.label(0));
    }
    toml::to_string(&table)
        .map_err(|e| SweepError::Usage(format!("cannot encode the scenario as TOML: {e}")))
}

fn as_f64(v: &AxisValue) -> f64 {
    match v {
        AxisValue::Number(x) => *x,
        AxisValue::Integer(i) => *i as f64,
        AxisValue::Text(_) | AxisValue::List(_) => f64::NAN,
    }
}

/// An absolute path without touching the file system (no symlink resolution).
fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

fn section_mut<'t>(t: &'t mut Table, name: &str) -> Result<&'t mut Table, String> {
    match t
        .entry(name.to_string())
        .or_insert_with(|| Value::Table(Table::new()))
    {
        Value::Table(s) => Ok(s),
        _ => Err(format!("`{name}` in the base scenario is not a table")),
    }
}

fn structure_mut(t: &mut Table, i: usize) -> Result<&mut Table, String> {
    match t.get_mut("structure") {
        Some(Value::Array(a)) => match a.get_mut(i) {
            Some(Value::Table(s)) => Ok(s),
            _ => Err(format!(
                "the base scenario has no [[structure]] number {}",
                i + 1
            )),
        },
        _ => Err("the base scenario has no [[structure]] tables".into()),
    }
}

fn level_mut(t: &mut Table, i: usize) -> Result<&mut Table, String> {
    let c = section_mut(t, "contact")?;
    match c.get_mut("level") {
        Some(Value::Array(a)) => match a.get_mut(i) {
            Some(Value::Table(s)) => Ok(s),
            _ => Err(format!(
                "the base scenario has no [[contact.level]] number {}",
                i + 1
            )),
        },
        _ => Err("the base scenario has no [[contact.level]] tables".into()),
    }
}

/// First-mode period of structure `i` (0-based) as the case table gives it: `period`, or
/// computed from length, mass and `bending_stiffness`/`tip_stiffness` (docs/model.md §2.6).
fn first_period(t: &Table, i: usize) -> Result<f64, String> {
    let s = match t.get("structure") {
        Some(Value::Array(a)) => match a.get(i) {
            Some(Value::Table(s)) => s,
            _ => return Err(format!("the scenario has no structure {}", i + 1)),
        },
        _ => return Err("the scenario has no [[structure]] tables".into()),
    };
    let get = |k: &str| s.get(k).and_then(number);
    let positive = |k: &str| -> Result<f64, String> {
        match get(k) {
            Some(x) if x.is_finite() && x > 0.0 => Ok(x),
            _ => Err(format!(
                "structure[{}].{k} must be a number > 0 to compute the period",
                i + 1
            )),
        }
    };
    if s.contains_key("period") {
        return positive("period");
    }
    let stiffness = if s.contains_key("bending_stiffness") {
        Stiffness::Bending(positive("bending_stiffness")?)
    } else if s.contains_key("tip_stiffness") {
        Stiffness::Tip(positive("tip_stiffness")?)
    } else {
        return Err(format!(
            "structure[{}] gives none of `period`, `bending_stiffness`, `tip_stiffness`",
            i + 1
        ));
    };
    let st = Cantilever {
        name: String::new(),
        length: positive("length")?,
        mass: positive("mass")?,
        stiffness,
        modes: 1,
        damping: Damping::Modal(vec![0.0]),
    };
    Ok(st.modal().periods()[0])
}

/// A scenario error without the position in the generated case text.
fn reason(e: &ScenarioError) -> String {
    match e {
        ScenarioError::Read { path, source } => format!("cannot read {path}: {source}"),
        ScenarioError::Syntax { message, .. } => message.clone(),
        ScenarioError::UnknownKey {
            key, section, hint, ..
        } => format!("unknown key `{key}` in {section}{hint}"),
        ScenarioError::Missing { key, expected, .. } => {
            format!("missing key `{key}`: {expected}")
        }
        ScenarioError::Invalid {
            key, value, reason, ..
        } => format!("`{key}` = {value}: {reason}"),
        ScenarioError::Record { key, source, .. } => format!("`{key}`: {source}"),
        ScenarioError::MissingMany { missing, .. } => format!(
            "missing keys: {}",
            missing
                .iter()
                .map(|(_, key, expected)| format!("`{key}` ({expected})"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        ScenarioError::SweepFile { .. } => e.to_string(),
    }
}

fn parse_axis(ctx: &Ctx, n: usize, a: &Spanned<RawAxis>) -> Result<Axis, SweepError> {
    let name = |k: &str| format!("axis[{}].{k}", n + 1);
    let r = a.get_ref();
    let start = Some(a.span().start);
    let key_v = r.key.as_ref().ok_or_else(|| {
        ctx.invalid(
            start,
            &name("key"),
            "missing: e.g. key = \"period_ratio\", \"ground_period_ratio\" or a scenario key such as \"ground_motion.pga\"",
        )
    })?;
    let (key, target) = parse_key(key_v.get_ref())
        .map_err(|m| ctx.invalid(Some(key_v.span().start), &name("key"), m))?;
    let kind = match &target {
        Target::Key { kind, .. } => *kind,
        _ => Kind::Number,
    };
    let ratio = matches!(
        target,
        Target::PeriodRatio | Target::GroundPeriodRatio | Target::Scale { .. }
    );
    let values = match (&r.values, &r.from, &r.to, &r.steps) {
        (Some(list), None, None, None) => {
            if let Some(s) = &r.scale {
                return Err(ctx.invalid(
                    Some(s.span().start),
                    &name("scale"),
                    "`scale` goes with `from`, `to`, `steps`, not with `values`",
                ));
            }
            if list.get_ref().is_empty() {
                return Err(ctx.invalid(
                    Some(list.span().start),
                    &name("values"),
                    "give at least one value",
                ));
            }
            let mut out = Vec::new();
            let mut seen = std::collections::HashSet::new();
            for v in list.get_ref() {
                let at = Some(v.span().start);
                let value = match (v.get_ref(), kind) {
                    (RawValue::Text(s), Kind::Text | Kind::File) => {
                        if s.contains(['\n', '\r']) {
                            return Err(ctx.invalid(
                                at,
                                &name("values"),
                                "no line breaks in values",
                            ));
                        }
                        AxisValue::Text(s.clone())
                    }
                    (RawValue::Int(i), Kind::Integer) => AxisValue::Integer(*i),
                    (RawValue::Num(x), Kind::Integer) if x.fract() == 0.0 && x.abs() < 1e15 => {
                        AxisValue::Integer(*x as i64)
                    }
                    (RawValue::Int(i), Kind::Number) => AxisValue::Number(*i as f64),
                    (RawValue::Num(x), Kind::Number) => AxisValue::Number(*x),
                    (_, Kind::Text | Kind::File) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` takes text values (in quotes)"),
                        ));
                    }
                    (_, Kind::Integer) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` takes whole numbers"),
                        ));
                    }
                    (RawValue::List(v), Kind::List) => {
                        if v.is_empty() || v.iter().any(|x| !x.is_finite()) {
                            return Err(ctx.invalid(
                                at,
                                &name("values"),
                                format!("`{key}` takes lists of finite numbers, not empty ones"),
                            ));
                        }
                        AxisValue::List(v.clone())
                    }
                    (_, Kind::List) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` takes lists of numbers, e.g. values = [[2e5, 2e5], [3e5, 3e5]]"),
                        ));
                    }
                    (RawValue::Text(_) | RawValue::List(_), Kind::Number) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` takes numbers"),
                        ));
                    }
                };
                check_value(ctx, at, &name("values"), &value, ratio)?;
                if !seen.insert(value.to_csv()) {
                    return Err(ctx.invalid(
                        at,
                        &name("values"),
                        format!("{value} is listed twice"),
                    ));
                }
                out.push(value);
            }
            out
        }
        (None, Some(from), Some(to), Some(steps)) => {
            if kind == Kind::List {
                return Err(ctx.invalid(
                    start,
                    &name("from"),
                    format!("`{key}` takes lists: give them with `values = [[…], […]]`"),
                ));
            }
            if kind == Kind::Text || kind == Kind::File {
                return Err(ctx.invalid(
                    start,
                    &name("from"),
                    format!("`{key}` takes text: list them with `values = [\"…\", …]`"),
                ));
            }
            let s = *steps.get_ref();
            if !(1..=MAX_STEPS).contains(&s) {
                return Err(ctx.invalid(
                    Some(steps.span().start),
                    &name("steps"),
                    format!("= {s}: must be a whole number from 1 to {MAX_STEPS}"),
                ));
            }
            let (a, b) = (*from.get_ref(), *to.get_ref());
            for (v, k) in [(from, "from"), (to, "to")] {
                if !v.get_ref().is_finite() {
                    return Err(ctx.invalid(Some(v.span().start), &name(k), "must be finite"));
                }
            }
            let log = match r.scale.as_ref().map(|s| (s, s.get_ref().as_str())) {
                None | Some((_, "linear")) => false,
                Some((_, "log")) => true,
                Some((s, other)) => {
                    return Err(ctx.invalid(
                        Some(s.span().start),
                        &name("scale"),
                        format!("= \"{other}\": must be \"linear\" or \"log\""),
                    ));
                }
            };
            if log && !(a > 0.0 && b > 0.0) {
                return Err(ctx.invalid(
                    Some(from.span().start),
                    &name("from"),
                    "a logarithmic axis needs `from` and `to` > 0",
                ));
            }
            if s == 1 && a != b {
                return Err(ctx.invalid(
                    Some(steps.span().start),
                    &name("steps"),
                    "= 1 needs `from` = `to` (or use `values`)",
                ));
            }
            if s > 1 && a == b {
                return Err(ctx.invalid(
                    Some(to.span().start),
                    &name("to"),
                    "equals `from`: the values would repeat",
                ));
            }
            let s = s as usize;
            let mut out = Vec::with_capacity(s);
            for i in 0..s {
                let f = if s == 1 {
                    0.0
                } else {
                    i as f64 / (s - 1) as f64
                };
                let x = if i + 1 == s {
                    b
                } else if log {
                    tidy(a * (b / a).powf(f))
                } else {
                    tidy(a + (b - a) * f)
                };
                let value = if kind == Kind::Integer {
                    if x.fract() != 0.0 {
                        return Err(ctx.invalid(
                            start,
                            &name("steps"),
                            format!("`{key}` takes whole numbers, but the grid has {x}"),
                        ));
                    }
                    AxisValue::Integer(x as i64)
                } else {
                    AxisValue::Number(x)
                };
                check_value(ctx, Some(from.span().start), &name("from"), &value, ratio)?;
                // generated values are monotonic: a repeat can only be the previous value
                if out.last() == Some(&value) {
                    return Err(ctx.invalid(
                        Some(steps.span().start),
                        &name("steps"),
                        format!("{value} would appear twice: use fewer steps"),
                    ));
                }
                out.push(value);
            }
            out
        }
        (None, None, None, None) => {
            return Err(ctx.invalid(
                start,
                &name("values"),
                "missing: give `values = [...]`, or `from`, `to` and `steps`",
            ));
        }
        (Some(v), ..) => {
            return Err(ctx.invalid(
                Some(v.span().start),
                &name("values"),
                "give either `values` or `from`/`to`/`steps`, not both",
            ));
        }
        _ => {
            let missing: Vec<&str> = [
                ("from", r.from.is_none()),
                ("to", r.to.is_none()),
                ("steps", r.steps.is_none()),
            ]
            .into_iter()
            .filter(|(_, m)| *m)
            .map(|(k, _)| k)
            .collect();
            return Err(ctx.invalid(
                start,
                &name(missing[0]),
                format!(
                    "missing: a generated axis needs `from`, `to` and `steps` (missing: {})",
                    missing.join(", ")
                ),
            ));
        }
    };
    Ok(Axis {
        key,
        values,
        target,
    })
}

fn check_value(
    ctx: &Ctx,
    at: Option<usize>,
    key: &str,
    v: &AxisValue,
    ratio: bool,
) -> Result<(), SweepError> {
    if let AxisValue::Number(x) = v {
        if !x.is_finite() {
            return Err(ctx.invalid(at, key, "values must be finite numbers"));
        }
        if ratio && *x <= 0.0 {
            return Err(ctx.invalid(at, key, format!("{x}: a period ratio must be > 0")));
        }
    }
    Ok(())
}

fn check_axes(ctx: &Ctx, axes: &[Axis], spans: &[usize], base: &Table) -> Result<(), SweepError> {
    let find = |pred: &dyn Fn(&Target) -> bool| axes.iter().position(|a| pred(&a.target));
    let is_key = |t: &Target, s: &Section, f: &[&str]| matches!(t, Target::Key { section, field, .. } if section == s && f.contains(field));
    let file_axis = find(&|t| is_key(t, &Section::Ground, &["file"]));
    let conflicts: [(Target, &[&str], Section, &str); 2] = [
        (
            Target::PeriodRatio,
            &["period", "bending_stiffness", "tip_stiffness"],
            Section::Structure(1),
            "period_ratio sets structure 2's period",
        ),
        (
            Target::GroundPeriodRatio,
            &["period"],
            Section::Ground,
            "ground_period_ratio sets the ground motion's period",
        ),
    ];
    for (derived, fields, section, why) in conflicts {
        if let Some(d) = find(&|t| *t == derived)
            && let Some(j) = find(&|t| is_key(t, &section, fields))
        {
            return Err(ctx.invalid(
                Some(spans[j.max(d)]),
                &axes[j].key,
                format!("cannot be an axis together with `{}`: {why}", axes[d].key),
            ));
        }
    }
    let base_ground = base.get("ground_motion").and_then(Value::as_table);
    let base_kind = base_ground
        .and_then(|g| g.get("kind"))
        .and_then(Value::as_str);
    if let Some(d) = find(&|t| *t == Target::GroundPeriodRatio) {
        if let Some(f) = file_axis {
            return Err(ctx.invalid(
                Some(spans[f.max(d)]),
                "ground_period_ratio",
                "needs a harmonic ground motion; it cannot be swept with record files (`ground_motion.file`)",
            ));
        }
        if base_kind != Some("harmonic") {
            return Err(ctx.invalid(
                Some(spans[d]),
                "ground_period_ratio",
                "needs a harmonic ground motion (kind = \"harmonic\") in the base scenario",
            ));
        }
    }
    let base_contact = base.get("contact").and_then(Value::as_table);
    let levels = base_contact
        .and_then(|c| c.get("level"))
        .and_then(Value::as_array)
        .map(Vec::len);
    for (j, a) in axes.iter().enumerate() {
        match &a.target {
            Target::Key {
                section: Section::Contact,
                field: f @ ("gap" | "height"),
                ..
            } if levels.is_some() => {
                return Err(ctx.invalid(
                    Some(spans[j]),
                    &a.key,
                    format!(
                        "the base scenario has [[contact.level]] tables: sweep `contact.level.N.{f}` instead"
                    ),
                ));
            }
            Target::Key {
                section: Section::Level(i),
                ..
            } if levels.is_none_or(|n| *i >= n) => {
                return Err(ctx.invalid(
                    Some(spans[j]),
                    &a.key,
                    format!(
                        "the base scenario has {} [[contact.level]] table(s)",
                        levels.unwrap_or(0)
                    ),
                ));
            }
            _ => {}
        }
    }
    Ok(())
}

/// `K/N`: the K-th (1-based) of N disjoint parts of the grid. Case `i` belongs to part
/// `i mod N + 1` (interleaved, so that every part gets a similar mix of cheap and costly cases).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 1-based part number.
    pub k: usize,
    /// Number of parts.
    pub n: usize,
}

impl Shard {
    /// The whole grid.
    pub const ALL: Shard = Shard { k: 1, n: 1 };

    /// Does case `case` belong to this part?
    pub fn contains(&self, case: usize) -> bool {
        case % self.n + 1 == self.k
    }

    /// Is this the whole grid?
    pub fn is_all(&self) -> bool {
        self.n == 1
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad =
            || format!("--shard `{s}`: expected K/N with 1 ≤ K ≤ N, e.g. 3/8 (the 3rd of 8 parts)");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if k == 0 || n == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    const BASE: &str = include_str!("../../../examples/paper-c.toml");

    fn sweep(axes: &str) -> Result<Sweep, SweepError> {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "base.toml", BASE);
        let p = write(
            dir.path(),
            "s.toml",
            &format!("scenario = \"base.toml\"\n{axes}"),
        );
        Sweep::from_file(&p)
    }

    #[test]
    fn grid_order_first_axis_slowest() {
        let s = sweep(
            "[[axis]]\nkey = \"period_ratio\"\nvalues = [0.3, 0.5]\n\
             [[axis]]\nkey = \"ground_motion.pga\"\nfrom = 0.1\nto = 0.3\nsteps = 3\n",
        )
        .unwrap();
        assert_eq!(s.len(), 6);
        assert_eq!(s.label(0), "period_ratio = 0.3, ground_motion.pga = 0.1");
        assert_eq!(s.label(4), "period_ratio = 0.5, ground_motion.pga = 0.2");
        assert_eq!(s.axes[1].values[1], AxisValue::Number(0.2));
    }

    #[test]
    fn derived_axes_set_periods() {
        let s = sweep(
            "[[axis]]\nkey = \"period_ratio\"\nvalues = [0.7]\n\
             [[axis]]\nkey = \"ground_period_ratio\"\nvalues = [2.0]\n",
        )
        .unwrap();
        let sc = s.case_scenario(0).unwrap();
        let t2 = 0.4203 / 0.7;
        assert_eq!(
            sc.structures[1].as_cantilever().unwrap().stiffness,
            Stiffness::Period(t2)
        );
        let h = match &sc.ground_motion {
            crate::model::ground_motion::GroundMotion::Harmonic(h) => *h,
            _ => panic!(),
        };
        assert!((h.period() - t2 / 2.0).abs() < 1e-12);
    }

    #[test]
    fn period_ratio_from_stiffness() {
        // structure 1 given by tip stiffness: T1 from the modal model
        let base = BASE.replacen("period = 0.4203", "tip_stiffness = 5.0e8", 1);
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "base.toml", &base);
        let p = write(
            dir.path(),
            "s.toml",
            "scenario = \"base.toml\"\n[[axis]]\nkey = \"period_ratio\"\nvalues = [0.5]\n",
        );
        let s = Sweep::from_file(&p).unwrap();
        let sc = s.case_scenario(0).unwrap();
        let t1 = sc.structures[0].modal().periods()[0];
        let t2 = sc.structures[1].modal().periods()[0];
        assert!((t1 / t2 - 0.5).abs() < 1e-12, "{t1} {t2}");
    }

    #[test]
    fn errors_name_file_key_and_range() {
        let e = sweep("[[axis]]\nkey = \"ground_motion.pgaa\"\nvalues = [1]\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("s.toml:3:7"), "{e}");
        assert!(e.contains("did you mean `ground_motion.pga`"), "{e}");
        let e = sweep("[[axis]]\nkey = \"period_ratio\"\nvalues = [0.5, -1]\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("s.toml:4:16") && e.contains("must be > 0"),
            "{e}"
        );
        let e = sweep("[[axis]]\nkey = \"structure.3.mass\"\nvalues = [1]\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("use 1 to 2"), "{e}");
        let e = sweep("[[axis]]\nkey = \"contact.gap\"\nfrom = 0\nto = 1\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("axis[1].steps") && e.contains("missing"), "{e}");
        let e = sweep("[[axis]]\nkey = \"contact.gap\"\nvalues = [0.1]\nfoo = 1\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("s.toml:5:1")
                && e.contains("unknown key `foo` in [[axis]]")
                && e.contains("(valid keys: key, values, from, to, steps, scale)"),
            "{e}"
        );
        let e = sweep(
            "[[axis]]\nkey = \"period_ratio\"\nvalues = [0.5]\n[[axis]]\nkey = \"structure[2].period\"\nvalues = [1.0]\n",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("cannot be an axis together"), "{e}");
    }

    #[test]
    fn log_axis_and_tidy_values() {
        let s = sweep("[[axis]]\nkey = \"contact.stiffness\"\nfrom = 1e8\nto = 1e11\nsteps = 4\nscale = \"log\"\n").unwrap();
        let v: Vec<String> = s.axes[0].values.iter().map(|v| v.to_csv()).collect();
        assert_eq!(
            v,
            [
                "100000000.0",
                "1000000000.0",
                "10000000000.0",
                "100000000000.0"
            ]
        );
    }

    #[test]
    fn case_toml_round_trips_floats() {
        let s = sweep(
            "[[axis]]\nkey = \"contact.gap\"\nvalues = [0.30000000000000004, 1e-20, 7.123456789012345]\n",
        )
        .unwrap();
        for i in 0..3 {
            let sc = s.case_scenario(i).unwrap();
            assert_eq!(
                sc.contact.levels[0].gap,
                as_f64(&s.axes[0].values[i]),
                "case {i}"
            );
        }
    }

    #[test]
    fn integer_and_replacing_keys() {
        let s = sweep(
            "[[axis]]\nkey = \"structure.2.modes\"\nfrom = 1\nto = 5\nsteps = 3\n\
             [[axis]]\nkey = \"structure[2].tip_stiffness\"\nvalues = [3e8]\n\
             [[axis]]\nkey = \"structure.1.strain_rate_damping\"\nvalues = [0.001]\n",
        )
        .unwrap();
        assert_eq!(s.axes[0].values[1], AxisValue::Integer(3));
        assert_eq!(s.axes[1].key, "structure.2.tip_stiffness");
        let sc = s.case_scenario(2).unwrap();
        assert_eq!(sc.structures[1].modes(), 5);
        assert_eq!(
            sc.structures[1].as_cantilever().unwrap().stiffness,
            Stiffness::Tip(3e8)
        );
        assert!(matches!(
            sc.structures[0].as_cantilever().unwrap().damping,
            Damping::Physical { strain_rate, air } if strain_rate == 0.001 && air == 0.0
        ));
        let e = sweep("[[axis]]\nkey = \"structure.2.modes\"\nvalues = [2.5]\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("whole numbers"), "{e}");
    }

    /// The identity hash of a file streamed in blocks (of any size the reader gives) is the
    /// hash of its bytes as one part: streaming changes nothing but the memory it takes.
    #[test]
    fn streamed_identity_equals_the_whole_file_hash() {
        /// A reader giving at most 7 777 bytes a call, as a pipe or a slow disk might.
        struct Trickle<'a>(&'a [u8]);
        impl std::io::Read for Trickle<'_> {
            fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
                let n = self.0.len().min(buf.len()).min(7777);
                buf[..n].copy_from_slice(&self.0[..n]);
                self.0 = &self.0[n..];
                Ok(n)
            }
        }
        let bytes: Vec<u8> = (0..300_000u32)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
            .collect();
        let mut streamed = Fnv1a::new();
        streamed.part(b"head");
        streamed.stream(Trickle(&bytes));
        streamed.end_part();
        assert_eq!(streamed.finish(), fnv1a(&[b"head", &bytes]));
        // and a different byte changes it
        let mut other = bytes.clone();
        other[123_456] ^= 1;
        assert_ne!(fnv1a(&[b"head", &bytes]), fnv1a(&[b"head", &other]));
    }

    #[test]
    fn shard_parse() {
        assert_eq!("2/5".parse::<Shard>(), Ok(Shard { k: 2, n: 5 }));
        assert!("0/5".parse::<Shard>().is_err());
        assert!("6/5".parse::<Shard>().is_err());
        assert!("x".parse::<Shard>().is_err());
    }
}
