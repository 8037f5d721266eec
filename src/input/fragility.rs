//! A fragility study file (issue 28): `pounding fragility STUDY.toml`.
//!
//! ```toml
//! title = "…"                                # optional
//! scenario = "shear-buildings.toml"          # the base scenario, relative to this file
//!
//! [ground_motion]                            # the suite (else the scenario's own kind = "suite")
//! records = [{ file = "records/RSN753_LOMAP_CLS000.AT2" }, …]   # the keys of a suite's records
//!
//! [intensity]
//! measure = "sa"                             # "pga" | "sa" (Sa(T1), 5 %) | "sa_avg"
//! structure = 2                              # sa: T1 of structure 1 or 2
//! periods = [0.2, 2.0]                       # sa_avg: the period range, s
//! count = 10                                 # sa_avg: periods, log-spaced (default 10)
//! units = "g"                                # "g" (default) or "m/s2": of stripes, target, outputs
//!
//! [[limit_state]]
//! kind = "pounding"                          # | "contact_force" | "ductility" | "drift_ratio"
//! value = 4.0                                #   | "floor_acceleration": the threshold
//! structure = 2                              # optional: 1 or 2 (default: either structure)
//!
//! [fragility]
//! stripes = [0.1, 0.2, 0.4, 0.6, 0.8]        # IM levels, in `intensity.units`
//! gaps = { to = 0.4, count = 41 }            # or a list, m: the gap axis of p_pounding.csv
//! gap_mode = "uniform"                       # or "scaled" (the scenario's gaps in proportion)
//! target = { im = 0.6, probability = 0.1 }   # the gap for P(pounding) ≤ p at im (a stripe)
//! bootstrap = 200                            # resamples of the records (0: no intervals)
//! seed = 1                                   # of the bootstrap
//! confidence = 0.9                           # of the intervals
//! check = false                              # self-check every run (as `pounding run`)
//! ```
//!
//! The records of the suite are scaled to every stripe (factor = level / the record's IM):
//! a suite's own `scaling` is not used, and a per-record `factor` is refused. Every error
//! names the file, line:column and the key.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::Deserialize;
use toml::Spanned;

use crate::input::scenario::{Location, Scenario, ScenarioError};

/// Standard gravity, m/s² (the conversion of `units = "g"`).
pub const G: f64 = 9.80665;

/// Why a study file was refused.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// The file could not be read.
    #[error("cannot read study {path}: {source}")]
    Read {
        /// Path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not valid TOML, an unknown key or a value of the wrong type.
    #[error("{at}: {message}")]
    Syntax {
        /// Where.
        at: Location,
        /// What the TOML reader said.
        message: String,
    },
    /// A required key is absent.
    #[error("{at}: missing key `{key}`: {expected}")]
    Missing {
        /// Where.
        at: Location,
        /// The key.
        key: String,
        /// What is expected.
        expected: String,
    },
    /// A value outside its allowed range or an inconsistent combination.
    #[error("{at}: `{key}` = {value}: {reason}")]
    Invalid {
        /// Where.
        at: Location,
        /// The key.
        key: String,
        /// The value as given.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// The base scenario (or the suite given in the study) was refused.
    #[error("{0}")]
    Scenario(#[from] ScenarioError),
}

/// The intensity measure, a closed set.
#[derive(Debug, Clone, PartialEq)]
pub enum IntensityMeasure {
    /// Peak ground acceleration.
    Pga,
    /// 5 %-damped pseudo-spectral acceleration at the first-mode period of a structure.
    Sa {
        /// 0 or 1.
        structure: usize,
        /// Its first-mode period T₁, s.
        period: f64,
    },
    /// The geometric mean of the 5 %-damped PSA over log-spaced periods (Sa_avg).
    SaAvg {
        /// The periods, s.
        periods: Vec<f64>,
    },
}

impl IntensityMeasure {
    /// A short name for tables and axes: `PGA`, `Sa(T1 = 0.41 s)`, `Sa_avg(0.2–2 s)`.
    pub fn label(&self) -> String {
        match self {
            IntensityMeasure::Pga => "PGA".into(),
            IntensityMeasure::Sa { structure, period } => {
                format!("Sa(T1 = {period:.3} s of structure {})", structure + 1)
            }
            IntensityMeasure::SaAvg { periods } => format!(
                "Sa_avg({:.3}–{:.3} s, {} periods)",
                periods.first().copied().unwrap_or(f64::NAN),
                periods.last().copied().unwrap_or(f64::NAN),
                periods.len()
            ),
        }
    }

    /// A short name: `PGA`, `Sa(T1)`, `Sa_avg`.
    pub fn short(&self) -> &'static str {
        match self {
            IntensityMeasure::Pga => "PGA",
            IntensityMeasure::Sa { .. } => "Sa(T1)",
            IntensityMeasure::SaAvg { .. } => "Sa_avg",
        }
    }

    /// The key: `pga`, `sa`, `sa_avg`.
    pub fn key(&self) -> &'static str {
        match self {
            IntensityMeasure::Pga => "pga",
            IntensityMeasure::Sa { .. } => "sa",
            IntensityMeasure::SaAvg { .. } => "sa_avg",
        }
    }
}

/// The units of the intensity measure in the study file and the outputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImUnits {
    /// g = 9.80665 m/s².
    G,
    /// m/s².
    Ms2,
}

impl ImUnits {
    /// m/s² per unit.
    pub fn factor(self) -> f64 {
        match self {
            ImUnits::G => G,
            ImUnits::Ms2 => 1.0,
        }
    }

    /// As written: `g`, `m/s2`.
    pub fn key(self) -> &'static str {
        match self {
            ImUnits::G => "g",
            ImUnits::Ms2 => "m/s2",
        }
    }
}

/// What a limit state measures, a closed set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitKind {
    /// The structures touch at any level (the run with contact has an impact; the run
    /// without contact: the relative displacement exceeds the gap at any level).
    Pounding,
    /// The peak contact force over all levels exceeds the value, N (with contact only).
    ContactForce,
    /// The peak storey ductility demand of a yielding building exceeds the value.
    Ductility,
    /// The peak storey drift ratio (drift over storey height) exceeds the value.
    DriftRatio,
    /// The peak absolute floor acceleration exceeds the value, m/s².
    FloorAcceleration,
}

impl LimitKind {
    /// As written in the study file.
    pub fn key(self) -> &'static str {
        match self {
            LimitKind::Pounding => "pounding",
            LimitKind::ContactForce => "contact_force",
            LimitKind::Ductility => "ductility",
            LimitKind::DriftRatio => "drift_ratio",
            LimitKind::FloorAcceleration => "floor_acceleration",
        }
    }
}

/// A limit state: a kind, its threshold (SI) and the structure it looks at.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitState {
    /// The kind.
    pub kind: LimitKind,
    /// The threshold, SI (N, –, –, m/s²); 0 for `pounding`.
    pub value: f64,
    /// 0 or 1; `None`: either structure (the larger demand).
    pub structure: Option<usize>,
    /// Its name in the tables: `ductility>4(2)` …
    pub name: String,
}

/// How the gap of `p_pounding.csv` is applied to the contact levels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GapMode {
    /// The same gap at every level.
    Uniform,
    /// The scenario's gaps scaled together; the axis is the gap at the highest level.
    Scaled,
}

/// `target = { im, probability }`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoundingTarget {
    /// The design intensity, m/s² (one of the stripes).
    pub im: f64,
    /// The stripe's index.
    pub stripe: usize,
    /// The accepted probability of pounding.
    pub probability: f64,
}

/// A checked study.
#[derive(Debug, Clone)]
pub struct FragilityStudy {
    /// Title.
    pub title: String,
    /// The study file.
    pub file: String,
    /// The base scenario with its suite (`scenario.suite` is `Some`).
    pub scenario: Scenario,
    /// The base scenario's path as the study gives it.
    pub scenario_file: String,
    /// Each record's file as the study (or the scenario) spells it.
    pub record_names: Vec<String>,
    /// The intensity measure.
    pub measure: IntensityMeasure,
    /// Its units.
    pub units: ImUnits,
    /// The stripes, m/s², increasing.
    pub stripes: Vec<f64>,
    /// The limit states, in file order.
    pub limit_states: Vec<LimitState>,
    /// The gap axis of `p_pounding.csv`, m, increasing.
    pub gaps: Vec<f64>,
    /// How a gap is applied to the levels.
    pub gap_mode: GapMode,
    /// The design question, if asked.
    pub target: Option<PoundingTarget>,
    /// Bootstrap resamples.
    pub bootstrap: usize,
    /// Its seed.
    pub seed: u64,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// Self-check every run.
    pub check: bool,
    /// What the study notes (a suite's own scaling not used …).
    pub notes: Vec<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    title: Option<String>,
    scenario: Option<Spanned<String>>,
    ground_motion: Option<Spanned<toml::Table>>,
    intensity: Option<Spanned<RawIntensity>>,
    limit_state: Option<Vec<Spanned<RawLimit>>>,
    fragility: Option<Spanned<RawFragility>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawIntensity {
    measure: Option<Spanned<String>>,
    structure: Option<Spanned<i64>>,
    periods: Option<Spanned<Vec<f64>>>,
    count: Option<Spanned<i64>>,
    units: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLimit {
    kind: Option<Spanned<String>>,
    value: Option<Spanned<f64>>,
    structure: Option<Spanned<i64>>,
    units: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawGaps {
    List(Vec<f64>),
    Range { to: f64, count: Option<i64> },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTarget {
    im: Option<Spanned<f64>>,
    probability: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFragility {
    stripes: Option<Spanned<Vec<f64>>>,
    gaps: Option<Spanned<RawGaps>>,
    gap_mode: Option<Spanned<String>>,
    target: Option<Spanned<RawTarget>>,
    bootstrap: Option<Spanned<i64>>,
    seed: Option<Spanned<i64>>,
    confidence: Option<Spanned<f64>>,
    check: Option<bool>,
}

/// Where a byte offset of the text lies: file:line:col.
struct Here<'a> {
    text: &'a str,
    file: Arc<str>,
}

impl Here<'_> {
    fn at(&self, offset: Option<usize>) -> Location {
        Location {
            file: self.file.clone(),
            line_col: offset.map(|o| {
                let mut o = o.min(self.text.len());
                while !self.text.is_char_boundary(o) {
                    o -= 1;
                }
                let before = &self.text[..o];
                let line = before.matches('\n').count() + 1;
                let col = before.rfind('\n').map_or(o, |p| o - p - 1) + 1;
                (line as u32, col as u32)
            }),
        }
    }

    fn invalid<T: std::fmt::Debug>(&self, v: &Spanned<T>, key: &str, reason: &str) -> StudyError {
        StudyError::Invalid {
            at: self.at(Some(v.span().start)),
            key: key.into(),
            value: format!("{:?}", v.get_ref()).trim_matches('"').to_string(),
            reason: reason.into(),
        }
    }

    fn missing(&self, key: &str, expected: &str, near: Option<usize>) -> StudyError {
        StudyError::Missing {
            at: self.at(near),
            key: key.into(),
            expected: expected.into(),
        }
    }
}

impl FragilityStudy {
    /// Read and check a study file; the base scenario and the records are resolved relative
    /// to it.
    pub fn from_file(path: &Path) -> Result<FragilityStudy, StudyError> {
        let text = crate::input::file::read_text(path, crate::input::file::MAX_TEXT_BYTES)
            .map_err(|e| StudyError::Read {
                path: path.display().to_string(),
                source: e,
            })?;
        let dir = path.parent().unwrap_or(Path::new("."));
        FragilityStudy::from_toml(&text, &path.display().to_string(), dir)
    }

    /// Check study text; `file` names it in messages, `dir` resolves the paths it names.
    pub fn from_toml(text: &str, file: &str, dir: &Path) -> Result<FragilityStudy, StudyError> {
        let here = Here {
            text,
            file: Arc::from(file),
        };
        let raw: RawStudy = toml::from_str(text).map_err(|e| StudyError::Syntax {
            at: here.at(e.span().map(|s| s.start)),
            message: e.message().trim().to_string(),
        })?;
        let mut notes = Vec::new();
        let sc_key = raw.scenario.as_ref().ok_or_else(|| {
            here.missing(
                "scenario",
                "the base scenario file, relative to the study: scenario = \"….toml\"",
                Some(0),
            )
        })?;
        let scenario_file = sc_key.get_ref().clone();
        let sc_path = dir.join(&scenario_file);
        let sc_text = crate::input::file::read_text(&sc_path, crate::input::file::MAX_TEXT_BYTES)
            .map_err(|e| StudyError::Invalid {
            at: here.at(Some(sc_key.span().start)),
            key: "scenario".into(),
            value: scenario_file.clone(),
            reason: format!("cannot read {}: {e}", sc_path.display()),
        })?;
        let sc_dir = sc_path.parent().unwrap_or(Path::new("."));
        let (scenario, record_names) = match &raw.ground_motion {
            None => {
                let sc = Scenario::from_toml(&sc_text, &sc_path.display().to_string(), sc_dir)?;
                let Some(suite) = sc.suite.as_ref() else {
                    return Err(StudyError::Missing {
                        at: here.at(Some(sc_key.span().start)),
                        key: "ground_motion".into(),
                        expected: format!(
                            "a suite of records: the scenario {scenario_file} has no \
                             [ground_motion] kind = \"suite\", so give [ground_motion] records = \
                             [{{ file = \"…\" }}, …] in the study"
                        ),
                    });
                };
                if suite.records.iter().any(|r| r.factor.is_some()) {
                    return Err(StudyError::Invalid {
                        at: here.at(Some(sc_key.span().start)),
                        key: "scenario".into(),
                        value: scenario_file.clone(),
                        reason: "its suite gives per-record `factor`s: a fragility study scales \
                                 every record to each stripe itself; remove them"
                            .into(),
                    });
                }
                if suite.scaling.rule != crate::input::scenario::suite::SuiteRule::None {
                    notes.push(format!(
                        "the scenario's suite scaling (rule \"{}\") is not used: every record \
                         is scaled to each stripe",
                        suite.scaling.rule.key()
                    ));
                }
                let names = suite.records.iter().map(|r| r.file.clone()).collect();
                (sc, names)
            }
            Some(gm) => suite_in_study(&here, gm, &sc_text, &sc_path, dir)?,
        };
        let intensity = raw.intensity.as_ref().ok_or_else(|| {
            here.missing(
                "intensity",
                "[intensity] measure = \"pga\" | \"sa\" | \"sa_avg\"",
                None,
            )
        })?;
        let (measure, units) = intensity_measure(&here, intensity, &scenario)?;
        let limits = raw.limit_state.as_deref().unwrap_or_default();
        if limits.is_empty() {
            return Err(here.missing(
                "limit_state",
                "at least one [[limit_state]] kind = \"pounding\" | \"contact_force\" | \
                 \"ductility\" | \"drift_ratio\" | \"floor_acceleration\"",
                None,
            ));
        }
        let limit_states = limits
            .iter()
            .enumerate()
            .map(|(i, l)| limit_state(&here, i, l, &scenario))
            .collect::<Result<Vec<_>, _>>()?;
        let fr = raw
            .fragility
            .as_ref()
            .ok_or_else(|| here.missing("fragility", "[fragility] stripes = [IM levels]", None))?;
        let f = fr.get_ref();
        let near = Some(fr.span().start);
        let st = f.stripes.as_ref().ok_or_else(|| {
            here.missing(
                "fragility.stripes",
                "the intensity levels, increasing, in intensity.units",
                near,
            )
        })?;
        let s = st.get_ref();
        if s.is_empty()
            || s.len() > 200
            || s.iter().any(|x| !(x.is_finite() && *x > 0.0))
            || s.windows(2).any(|w| w[1] <= w[0])
        {
            return Err(here.invalid(
                st,
                "fragility.stripes",
                "must be 1 to 200 positive, strictly increasing intensity levels",
            ));
        }
        let stripes: Vec<f64> = s.iter().map(|x| x * units.factor()).collect();
        let gap_mode = match f.gap_mode.as_ref() {
            None => GapMode::Uniform,
            Some(m) => match m.get_ref().as_str() {
                "uniform" => GapMode::Uniform,
                "scaled" => GapMode::Scaled,
                _ => {
                    return Err(here.invalid(
                        m,
                        "fragility.gap_mode",
                        "must be \"uniform\" (one gap at every level) or \"scaled\" (the \
                         scenario's gaps scaled together)",
                    ));
                }
            },
        };
        if gap_mode == GapMode::Scaled && top_gap(&scenario) <= 0.0 {
            return Err(here.invalid(
                f.gap_mode.as_ref().expect("given"),
                "fragility.gap_mode",
                "\"scaled\" needs a positive gap at the scenario's highest contact level",
            ));
        }
        let gaps = gap_axis(&here, f.gaps.as_ref(), &scenario, gap_mode)?;
        let target = match &f.target {
            None => None,
            Some(t) => Some(target(&here, t, s, units)?),
        };
        let bootstrap = match &f.bootstrap {
            None => 200,
            Some(b) => usize::try_from(*b.get_ref())
                .ok()
                .filter(|n| *n <= 100_000)
                .ok_or_else(|| {
                    here.invalid(b, "fragility.bootstrap", "must be in 0..=100000 resamples")
                })?,
        };
        let seed = match &f.seed {
            None => 1,
            Some(v) => u64::try_from(*v.get_ref())
                .map_err(|_| here.invalid(v, "fragility.seed", "must be ≥ 0"))?,
        };
        let confidence = match &f.confidence {
            None => 0.9,
            Some(c) => {
                let x = *c.get_ref();
                if !(x.is_finite() && x > 0.0 && x < 1.0) {
                    return Err(here.invalid(c, "fragility.confidence", "must be in (0, 1)"));
                }
                x
            }
        };
        Ok(FragilityStudy {
            title: raw
                .title
                .clone()
                .unwrap_or_else(|| format!("fragility of {}", scenario.title)),
            file: file.to_string(),
            scenario,
            scenario_file,
            record_names,
            measure,
            units,
            stripes,
            limit_states,
            gaps,
            gap_mode,
            target,
            bootstrap,
            seed,
            confidence,
            check: f.check.unwrap_or(false),
            notes,
        })
    }

    /// The number of runs (records × stripes), each with and without contact.
    pub fn runs(&self) -> usize {
        self.record_names.len() * self.stripes.len()
    }
}

/// The gap at the scenario's highest contact level, m.
pub fn top_gap(scenario: &Scenario) -> f64 {
    let h = scenario.main_height();
    scenario
        .contact
        .levels
        .iter()
        .find(|l| l.height == h)
        .map_or(0.0, |l| l.gap)
}

/// The base scenario with the study's `[ground_motion]` as its suite: record files relative
/// to the study are made absolute so that the scenario's own relative paths still work.
fn suite_in_study(
    here: &Here,
    gm: &Spanned<toml::Table>,
    sc_text: &str,
    sc_path: &Path,
    dir: &Path,
) -> Result<(Scenario, Vec<String>), StudyError> {
    let near = Some(gm.span().start);
    let mut g = gm.get_ref().clone();
    for k in ["kind", "scaling"] {
        if let Some(v) = g.get(k)
            && !(k == "kind" && v.as_str() == Some("suite"))
        {
            return Err(StudyError::Invalid {
                at: here.at(near),
                key: format!("ground_motion.{k}"),
                value: v.to_string(),
                reason: "a study's [ground_motion] is a suite of records (records = [ … ]) \
                         scaled to each stripe by the study: no kind other than \"suite\", no \
                         scaling"
                    .into(),
            });
        }
    }
    let base = std::fs::canonicalize(dir).unwrap_or_else(|_| PathBuf::from(dir));
    let mut names = Vec::new();
    let Some(toml::Value::Array(records)) = g.get_mut("records") else {
        return Err(here.missing(
            "ground_motion.records",
            "records = [{ file = \"…\", component = … }, …]",
            near,
        ));
    };
    for (i, r) in records.iter_mut().enumerate() {
        let key = format!("ground_motion.records[{}]", i + 1);
        let Some(t) = r.as_table_mut() else {
            return Err(StudyError::Invalid {
                at: here.at(near),
                key,
                value: r.to_string(),
                reason: "each record is a table { file = \"…\", … }".into(),
            });
        };
        if t.contains_key("factor") {
            return Err(StudyError::Invalid {
                at: here.at(near),
                key: format!("{key}.factor"),
                value: "(given)".into(),
                reason: "the study scales every record to each stripe itself".into(),
            });
        }
        if let Some(toml::Value::String(f)) = t.get("file").cloned() {
            names.push(f.clone());
            let p = Path::new(&f);
            if p.is_relative() {
                t.insert(
                    "file".into(),
                    toml::Value::String(base.join(p).display().to_string()),
                );
            }
        } else {
            names.push(String::new());
        }
    }
    g.insert("kind".into(), toml::Value::String("suite".into()));
    let mut scaling = toml::Table::new();
    scaling.insert("rule".into(), toml::Value::String("none".into()));
    g.insert("scaling".into(), toml::Value::Table(scaling));
    let mut table: toml::Table =
        toml::from_str(sc_text).map_err(|e| StudyError::Syntax {
            at: Location {
                file: Arc::from(sc_path.display().to_string()),
                line_col: None,
            },
            message: e.message().trim().to_string(),
        })?;
    table.insert("ground_motion".into(), toml::Value::Table(g));
    let origin = format!(
        "{} with the [ground_motion] of {}",
        sc_path.display(),
        here.file
    );
    let sc_dir = sc_path.parent().unwrap_or(Path::new("."));
    let sc = Scenario::from_table(&table, &origin, sc_dir)?;
    Ok((sc, names))
}

fn structure_index(
    here: &Here,
    v: &Spanned<i64>,
    key: &str,
) -> Result<usize, StudyError> {
    match *v.get_ref() {
        1 => Ok(0),
        2 => Ok(1),
        _ => Err(here.invalid(v, key, "must be 1 or 2")),
    }
}

fn intensity_measure(
    here: &Here,
    raw: &Spanned<RawIntensity>,
    scenario: &Scenario,
) -> Result<(IntensityMeasure, ImUnits), StudyError> {
    let r = raw.get_ref();
    let near = Some(raw.span().start);
    let m = r.measure.as_ref().ok_or_else(|| {
        here.missing(
            "intensity.measure",
            "\"pga\", \"sa\" (5 %-damped Sa(T1) of `structure`) or \"sa_avg\" (geometric mean \
             over `periods`)",
            near,
        )
    })?;
    let refuse = |present: bool, key: &str, why: &str| -> Result<(), StudyError> {
        if present {
            Err(StudyError::Invalid {
                at: here.at(near),
                key: format!("intensity.{key}"),
                value: "(given)".into(),
                reason: why.into(),
            })
        } else {
            Ok(())
        }
    };
    let measure = match m.get_ref().as_str() {
        "pga" => {
            refuse(r.structure.is_some(), "structure", "not used with measure = \"pga\"")?;
            refuse(r.periods.is_some(), "periods", "not used with measure = \"pga\"")?;
            refuse(r.count.is_some(), "count", "not used with measure = \"pga\"")?;
            IntensityMeasure::Pga
        }
        "sa" => {
            refuse(r.periods.is_some(), "periods", "not used with measure = \"sa\"")?;
            refuse(r.count.is_some(), "count", "not used with measure = \"sa\"")?;
            let s = r.structure.as_ref().ok_or_else(|| {
                here.missing(
                    "intensity.structure",
                    "1 or 2: whose first-mode period T1 Sa is taken at",
                    near,
                )
            })?;
            let i = structure_index(here, s, "intensity.structure")?;
            let period = scenario.structures[i]
                .modal()
                .periods()
                .first()
                .copied()
                .unwrap_or(f64::NAN);
            IntensityMeasure::Sa {
                structure: i,
                period,
            }
        }
        "sa_avg" => {
            refuse(r.structure.is_some(), "structure", "not used with measure = \"sa_avg\"")?;
            let p = r.periods.as_ref().ok_or_else(|| {
                here.missing(
                    "intensity.periods",
                    "[shortest, longest] period of the average, s (e.g. 0.2 T1 to 3 T1)",
                    near,
                )
            })?;
            let (lo, hi) = match p.get_ref().as_slice() {
                [a, b] if a.is_finite() && b.is_finite() && *a > 0.0 && a < b && *b <= 20.0 => {
                    (*a, *b)
                }
                _ => {
                    return Err(here.invalid(
                        p,
                        "intensity.periods",
                        "must be [shortest, longest] in s, 0 < shortest < longest ≤ 20",
                    ));
                }
            };
            let n = match &r.count {
                None => 10,
                Some(c) => usize::try_from(*c.get_ref())
                    .ok()
                    .filter(|n| (2..=100).contains(n))
                    .ok_or_else(|| here.invalid(c, "intensity.count", "must be in 2..=100"))?,
            };
            let periods = (0..n)
                .map(|k| lo * (hi / lo).powf(k as f64 / (n - 1) as f64))
                .collect();
            IntensityMeasure::SaAvg { periods }
        }
        _ => {
            return Err(here.invalid(
                m,
                "intensity.measure",
                "must be \"pga\", \"sa\" or \"sa_avg\"",
            ));
        }
    };
    let units = match r.units.as_ref() {
        None => ImUnits::G,
        Some(u) => match u.get_ref().as_str() {
            "g" => ImUnits::G,
            "m/s2" | "m/s^2" | "m/s²" => ImUnits::Ms2,
            _ => return Err(here.invalid(u, "intensity.units", "must be \"g\" or \"m/s2\"")),
        },
    };
    Ok((measure, units))
}

fn limit_state(
    here: &Here,
    i: usize,
    raw: &Spanned<RawLimit>,
    scenario: &Scenario,
) -> Result<LimitState, StudyError> {
    let r = raw.get_ref();
    let near = Some(raw.span().start);
    let key = |k: &str| format!("limit_state[{}].{k}", i + 1);
    let k = r.kind.as_ref().ok_or_else(|| {
        here.missing(
            &key("kind"),
            "\"pounding\", \"contact_force\", \"ductility\", \"drift_ratio\" or \
             \"floor_acceleration\"",
            near,
        )
    })?;
    let kind = match k.get_ref().as_str() {
        "pounding" => LimitKind::Pounding,
        "contact_force" => LimitKind::ContactForce,
        "ductility" => LimitKind::Ductility,
        "drift_ratio" => LimitKind::DriftRatio,
        "floor_acceleration" => LimitKind::FloorAcceleration,
        _ => {
            return Err(here.invalid(
                k,
                &key("kind"),
                "must be \"pounding\", \"contact_force\", \"ductility\", \"drift_ratio\" or \
                 \"floor_acceleration\"",
            ));
        }
    };
    let structure = r
        .structure
        .as_ref()
        .map(|s| structure_index(here, s, &key("structure")))
        .transpose()?;
    let (unit_factor, unit) = match (&r.units, kind) {
        (None, LimitKind::ContactForce) => (1.0, "N"),
        (None, LimitKind::FloorAcceleration) => (1.0, "m/s2"),
        (None, _) => (1.0, ""),
        (Some(u), LimitKind::FloorAcceleration) => match u.get_ref().as_str() {
            "g" => (G, "g"),
            "m/s2" | "m/s^2" | "m/s²" => (1.0, "m/s2"),
            _ => return Err(here.invalid(u, &key("units"), "must be \"g\" or \"m/s2\"")),
        },
        (Some(u), _) => {
            return Err(here.invalid(
                u,
                &key("units"),
                "only with kind = \"floor_acceleration\" (\"g\" or \"m/s2\"); the other \
                 thresholds are SI (N) or ratios",
            ));
        }
    };
    if kind == LimitKind::Pounding || kind == LimitKind::ContactForce {
        if r.structure.is_some() {
            return Err(here.invalid(
                r.structure.as_ref().expect("given"),
                &key("structure"),
                "not used with this kind: it concerns both structures",
            ));
        }
    }
    let value = if kind == LimitKind::Pounding {
        if let Some(v) = &r.value {
            return Err(here.invalid(
                v,
                &key("value"),
                "not used with kind = \"pounding\" (any contact; the gaps are the scenario's)",
            ));
        }
        0.0
    } else {
        let v = r.value.as_ref().ok_or_else(|| {
            here.missing(
                &key("value"),
                match kind {
                    LimitKind::ContactForce => "the peak contact force not to exceed, N",
                    LimitKind::Ductility => "the storey ductility demand not to exceed (> 1)",
                    LimitKind::DriftRatio => "the storey drift ratio not to exceed (0.01 = 1 %)",
                    _ => "the floor acceleration not to exceed, m/s² (or units = \"g\")",
                },
                near,
            )
        })?;
        let x = *v.get_ref();
        let ok = x.is_finite()
            && match kind {
                LimitKind::Ductility => x > 1.0 && x <= 1000.0,
                LimitKind::DriftRatio => x > 0.0 && x <= 1.0,
                _ => x > 0.0,
            };
        if !ok {
            return Err(here.invalid(
                v,
                &key("value"),
                match kind {
                    LimitKind::Ductility => "must be in (1, 1000]",
                    LimitKind::DriftRatio => "must be in (0, 1] (a ratio: 0.01 = 1 %)",
                    _ => "must be positive",
                },
            ));
        }
        x * unit_factor
    };
    if kind == LimitKind::Ductility {
        let yielding: Vec<usize> = (0..2)
            .filter(|&s| scenario.structures[s].hysteresis().is_some())
            .collect();
        let ok = match structure {
            Some(s) => yielding.contains(&s),
            None => !yielding.is_empty(),
        };
        if !ok {
            return Err(here.invalid(
                k,
                &key("kind"),
                &match structure {
                    Some(s) => format!(
                        "structure {} has no yielding storeys (a ductility needs `hysteresis`)",
                        s + 1
                    ),
                    None => "neither structure has yielding storeys (a ductility needs \
                             `hysteresis`)"
                        .to_string(),
                },
            ));
        }
    }
    // the name as the user wrote the threshold: `ductility>4(2)`, `floor_acceleration>1g(1)`
    let who = structure.map_or(String::new(), |s| format!("({})", s + 1));
    let given = format!("{}", value / unit_factor);
    let name = match kind {
        LimitKind::Pounding => "pounding".to_string(),
        _ => format!("{}>{given}{unit}{who}", kind.key()),
    };
    Ok(LimitState {
        kind,
        value,
        structure,
        name,
    })
}

fn gap_axis(
    here: &Here,
    raw: Option<&Spanned<RawGaps>>,
    scenario: &Scenario,
    mode: GapMode,
) -> Result<Vec<f64>, StudyError> {
    let key = "fragility.gaps";
    let Some(g) = raw else {
        // 0 to twice the scenario's gap (at the highest level in "scaled" mode, else the
        // largest), 41 values
        let g0 = match mode {
            GapMode::Scaled => top_gap(scenario),
            GapMode::Uniform => scenario
                .contact
                .levels
                .iter()
                .map(|l| l.gap)
                .fold(0.0, f64::max),
        };
        let to = if g0 > 0.0 { 2.0 * g0 } else { 0.5 };
        return Ok((0..=40).map(|k| to * k as f64 / 40.0).collect());
    };
    let v: Vec<f64> = match g.get_ref() {
        RawGaps::List(v) => v.clone(),
        RawGaps::Range { to, count } => {
            let n = count.unwrap_or(41);
            if !(to.is_finite() && *to > 0.0 && *to <= 100.0) || !(2..=10_000).contains(&n) {
                return Err(here.invalid(
                    g,
                    key,
                    "{ to, count }: 0 < to ≤ 100 m, count in 2..=10000",
                ));
            }
            (0..n).map(|k| to * k as f64 / (n - 1) as f64).collect()
        }
    };
    if v.is_empty()
        || v.len() > 10_000
        || v.iter().any(|x| !(x.is_finite() && *x >= 0.0 && *x <= 100.0))
        || v.windows(2).any(|w| w[1] <= w[0])
    {
        return Err(here.invalid(
            g,
            key,
            "must be a list of 1 to 10000 gaps in m, 0 ≤ gap ≤ 100, strictly increasing, or \
             { to = …, count = … }",
        ));
    }
    Ok(v)
}

fn target(
    here: &Here,
    t: &Spanned<RawTarget>,
    stripes: &[f64],
    units: ImUnits,
) -> Result<PoundingTarget, StudyError> {
    let near = Some(t.span().start);
    let r = t.get_ref();
    let im = r.im.as_ref().ok_or_else(|| {
        here.missing(
            "fragility.target.im",
            "the design intensity, one of the stripes",
            near,
        )
    })?;
    let stripe = stripes
        .iter()
        .position(|s| (s - im.get_ref()).abs() <= 1e-9 * s.abs())
        .ok_or_else(|| {
            here.invalid(
                im,
                "fragility.target.im",
                &format!(
                    "must be one of the stripes {:?} (the gap is read from the runs at that \
                     intensity)",
                    stripes
                ),
            )
        })?;
    let p = r.probability.as_ref().ok_or_else(|| {
        here.missing(
            "fragility.target.probability",
            "the accepted probability of pounding at that intensity, e.g. 0.1",
            near,
        )
    })?;
    let x = *p.get_ref();
    if !(x.is_finite() && x > 0.0 && x < 1.0) {
        return Err(here.invalid(p, "fragility.target.probability", "must be in (0, 1)"));
    }
    Ok(PoundingTarget {
        im: stripes[stripe] * units.factor(),
        stripe,
        probability: x,
    })
}
