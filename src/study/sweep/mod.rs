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

mod axes;
mod edit;
pub mod free_cache;
mod hash;
pub mod journal;
mod keys;
pub mod merge;
pub mod report;
pub mod results;
pub mod row_columns;
pub mod row_suite_rows;
pub mod run;
mod shard;
mod suite_check;
pub mod suite_rows;

pub use axes::{Axis, AxisValue};
pub use edit::{set_keys, sweep_text};
pub use hash::{Fnv1a, fnv1a};
pub use shard::Shard;
pub use suite_rows::RowKind;

use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::{Spanned, Table, Value};

use crate::input::scenario::{Location, RecordCache, Scenario};

use axes::{check_axes, parse_axis};
use edit::{absolute, as_f64, first_period, level_mut, reason, section_mut, structure_mut};
use keys::{Kind, Section, Target};

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
    kind: RowKind,
    /// The runs without contact shared by cases that differ only in their contact.
    free_runs: free_cache::FreeRunCache,
}

struct Ctx<'a> {
    text: &'a str,
    file: &'a str,
}

impl Ctx<'_> {
    fn at(&self, offset: Option<usize>) -> Location {
        Location::in_text(self.file, self.text, offset)
    }
    fn invalid(&self, offset: Option<usize>, key: &str, reason: impl Into<String>) -> SweepError {
        SweepError::Invalid {
            at: self.at(offset),
            key: key.to_string(),
            reason: reason.into(),
        }
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
        // and a suite's record files and target table, likewise
        let mut kind = suite_rows::absolute_suite_files(&mut base, &base_dir);
        // a row of buildings (issue 29): its own columns
        let shape = edit::row_shape(&base);
        let structures = shape.0;
        if kind == RowKind::Single && structures > 2 {
            kind = RowKind::Row { structures };
        }
        // a suite on a row of buildings: per pair and level (each pair's levels as the base
        // scenario gives them; a pair without its contact table counts one, and every case
        // of that base fails validation naming it)
        if matches!(kind, RowKind::Suite { .. }) && structures > 2 {
            kind = RowKind::RowSuite {
                pair_levels: shape.1.iter().map(|l| l.flatten().unwrap_or(1)).collect(),
            };
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
        check_axes(&ctx, &axes, &spans, &base, &shape)?;
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
        files.extend(suite_rows::suite_files(&base));
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
        let free_runs = free_cache::FreeRunCache::new(&axes);
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
            kind,
            free_runs,
        })
    }

    /// What a row of this sweep holds: one run ([`RowKind::Single`]), a suite of records
    /// ([`RowKind::Suite`], when the base scenario's ground motion is `kind = "suite"`), a row
    /// of buildings ([`RowKind::Row`], more than two structures) or a suite on a row
    /// ([`RowKind::RowSuite`]).
    pub fn row_kind(&self) -> &RowKind {
        &self.kind
    }

    /// The columns of a row after `status`: [`results::FIELDS`] and [`Sweep::extra_columns`]
    /// for single runs, [`suite_rows::columns`] for a suite, [`row_columns::columns`] for a row,
    /// [`row_suite_rows::columns`] for a suite on a row.
    pub fn result_columns(&self) -> Vec<String> {
        match &self.kind {
            RowKind::Single => results::FIELDS
                .iter()
                .chain(self.extra_columns().iter())
                .map(|f| f.to_string())
                .collect(),
            RowKind::Suite { levels } => suite_rows::columns(*levels),
            RowKind::Row { structures } => row_columns::columns(*structures),
            RowKind::RowSuite { pair_levels } => row_suite_rows::columns(pair_levels),
        }
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
    /// the ductility columns (none for a sweep over a suite, whose rows are
    /// [`suite_rows::columns`]).
    pub fn extra_columns(&self) -> Vec<&'static str> {
        if self.kind != RowKind::Single {
            // a suite's rows have their own columns (`suite_rows::columns`)
            return Vec::new();
        }
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

    /// The runs without contact this sweep's cases share (see [`free_cache`]).
    pub fn free_runs(&self) -> &free_cache::FreeRunCache {
        &self.free_runs
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
                    Section::PairContact(p) => edit::pair_contact_mut(t, *p)?,
                    Section::PairLevel(p, i) => edit::pair_level_mut(t, *p, *i)?,
                    Section::Ground => section_mut(t, "ground_motion")?,
                    Section::ScaleToSa => {
                        // a record is scaled one way: the axis's `scale_to_sa` replaces PGA scaling
                        let g = section_mut(t, "ground_motion")?;
                        g.remove("scale_to_pga");
                        section_mut(g, "scale_to_sa")?
                    }
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
                        table.remove("scale_to_sa");
                    }
                    (Section::Ground, "scale_to_pga") => {
                        table.remove("scale_to_sa");
                    }
                    _ => {}
                }
                table.insert(field.into(), value);
                Ok(())
            }
        }
    }
}

#[cfg(test)]
mod tests;
