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
//! structure = 2                              # sa: T1 of structure 1 or 2 (a row: 1 to N)
//! periods = [0.2, 2.0]                       # sa_avg: the period range, s
//! count = 10                                 # sa_avg: periods, log-spaced (default 10)
//! units = "g"                                # "g" (default) or "m/s2": of stripes, target, outputs
//!
//! [[limit_state]]
//! kind = "pounding"                          # | "contact_force" | "ductility" | "drift_ratio"
//! value = 4.0                                #   | "floor_acceleration": the threshold
//! structure = 2                              # optional: 1 or 2 (a row: 1 to N; default: each)
//! # pair = 1                                 # pounding, contact_force of a row: structures 1–2
//!
//! [fragility]
//! stripes = [0.1, 0.2, 0.4, 0.6, 0.8]        # IM levels, in `intensity.units`; or
//! # ida = { start = 0.05, step = 0.1, growth = 0.05, tolerance = 0.01, max_runs = 20 }
//! #                                          # incremental dynamic analysis (hunt and fill)
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

use std::path::Path;
use std::sync::Arc;

mod keys;

use keys::{
    Here, RawStudy, gap_axis, ida_settings, intensity_measure, limit_state, suite_in_study, target,
};

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
        /// 0-based, row order.
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
    /// The structure (0-based, row order) of a structure's limit state (ductility, drift,
    /// floor acceleration); `None`: every structure (the larger demand).
    pub structure: Option<usize>,
    /// The adjacent pair (0-based: structures `pair` and `pair + 1`) of a pair's limit state
    /// (pounding, contact force); `None`: every pair (any pounds; the larger force).
    pub pair: Option<usize>,
    /// Its name in the tables: `ductility>4(2)` (structure 2), `pounding(1-2)` (the pair of
    /// structures 1 and 2) …
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

/// Incremental dynamic analysis: each record scaled up run by run until every limit state is
/// exceeded, then each limit state's capacity bracketed by bisection (hunt and fill,
/// Vamvatsikos & Cornell 2002; docs/fragility.md). Intensities in m/s².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IdaSettings {
    /// The first intensity, m/s² (default 0.05 g).
    pub start: f64,
    /// The first step of the hunt, m/s² (default 0.1 g).
    pub step: f64,
    /// What each further step adds, m/s² (default 0.05 g): steps `step`, `step + growth`, …
    pub growth: f64,
    /// The width to which every capacity is bracketed, m/s² (default 0.01 g).
    pub tolerance: f64,
    /// Most runs per record (hunt, bracketing and fill; default 20).
    pub max_runs: usize,
    /// Spend the runs left after bracketing on the widest gaps between runs (default false).
    pub fill: bool,
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
    /// The stripes, m/s², increasing (empty in an IDA).
    pub stripes: Vec<f64>,
    /// The stripes as written, in the study's IM units (the tables' `im`).
    pub stripes_given: Vec<f64>,
    /// Incremental dynamic analysis instead of stripes.
    pub ida: Option<IdaSettings>,
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
    /// The study's text and the base scenario's, as read (with the records' samples, what a
    /// journal's identity covers: `study::fragility::journal::identity`).
    pub texts: [String; 2],
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
            .collect::<Result<Vec<_>, _>>()?
            .into_iter()
            .flatten()
            .collect();
        let fr = raw
            .fragility
            .as_ref()
            .ok_or_else(|| here.missing("fragility", "[fragility] stripes = [IM levels]", None))?;
        let f = fr.get_ref();
        let near = Some(fr.span().start);
        let (stripes, ida) = match (&f.stripes, &f.ida) {
            (Some(_), Some(i)) => {
                return Err(here.invalid(
                    i,
                    "fragility.ida",
                    "give either `stripes` (multi-stripe analysis) or `ida` (incremental \
                     dynamic analysis), not both",
                ));
            }
            (None, None) => {
                return Err(here.missing(
                    "fragility.stripes",
                    "the intensity levels, increasing, in intensity.units (or `ida = { … }` \
                     for an incremental dynamic analysis)",
                    near,
                ));
            }
            (None, Some(i)) => (Vec::new(), Some(ida_settings(&here, i, units)?)),
            (Some(st), None) => {
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
                (s.iter().map(|x| x * units.factor()).collect(), None)
            }
        };
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
        if gap_mode == GapMode::Scaled && pair_top_gaps(&scenario).iter().any(|g| *g <= 0.0) {
            return Err(here.invalid(
                f.gap_mode.as_ref().expect("given"),
                "fragility.gap_mode",
                if scenario.is_row() {
                    "\"scaled\" needs a positive gap at every pair's highest contact level"
                } else {
                    "\"scaled\" needs a positive gap at the scenario's highest contact level"
                },
            ));
        }
        let gaps = gap_axis(&here, f.gaps.as_ref(), &scenario, gap_mode)?;
        let target = match &f.target {
            None => None,
            Some(t) => Some(target(
                &here,
                t,
                f.stripes.as_ref().map(|s| s.get_ref().as_slice()),
                units,
            )?),
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
            texts: [text.to_string(), sc_text.clone()],
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
            stripes_given: f
                .stripes
                .as_ref()
                .map_or_else(Vec::new, |s| s.get_ref().clone()),
            stripes,
            ida,
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

    /// The number of runs (records × stripes; in an IDA at most records × `max_runs`), each
    /// with and without contact.
    pub fn runs(&self) -> usize {
        self.record_names.len()
            * match &self.ida {
                Some(i) => i.max_runs,
                None => self.stripes.len(),
            }
    }
}

/// Each adjacent pair's gaps (m), per level in the order of its contact table (one pair for
/// a pair of structures).
pub fn pair_gaps(scenario: &Scenario) -> Vec<Vec<f64>> {
    scenario
        .contacts()
        .map(|c| c.levels.iter().map(|l| l.gap).collect())
        .collect()
}

/// Each adjacent pair's gap at its highest contact level, m (the axis of `gap_mode =
/// "scaled"`; for a pair, [`top_gap`]).
pub fn pair_top_gaps(scenario: &Scenario) -> Vec<f64> {
    scenario
        .contacts()
        .map(|c| {
            let h = c
                .levels
                .iter()
                .map(|l| l.height)
                .fold(f64::NEG_INFINITY, f64::max);
            c.levels
                .iter()
                .find(|l| l.height == h)
                .map_or(0.0, |l| l.gap)
        })
        .collect()
}

/// The gap at the scenario's highest contact level (of its first pair), m.
pub fn top_gap(scenario: &Scenario) -> f64 {
    let h = scenario.main_height();
    scenario
        .contact
        .levels
        .iter()
        .find(|l| l.height == h)
        .map_or(0.0, |l| l.gap)
}
