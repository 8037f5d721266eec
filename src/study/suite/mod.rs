//! A suite of records (issue 27, part 3): the scenario's `[ground_motion] kind = "suite"`
//! scaled by its code's rule ([`crate::analysis::record_spectrum::SuiteScaling`], as
//! `pounding scale`), every record run as a scenario of its own through the one driver of a
//! run ([`simulate_streaming`]: with and without contact, self-checked), in parallel (rayon);
//! then per record the headline numbers, across the records their statistics
//! ([`statistics`]), and per contact level the code's design value of the required separation
//! against the level's gap, the verdict at the level of least margin.
//!
//! The files are written by [`mod@write`] (a pair's suite and a row's); the pictures by
//! `figures::suite`.

pub mod report;
pub mod row;
pub mod statistics;
pub mod write;

use rayon::prelude::*;
use serde::Serialize;
use serde::ser::SerializeMap;

use crate::analysis::record_spectrum::{
    PeriodRange, ScaledSuite, ScalingError, ScalingOptions, ScalingRule, SuiteMember, SuiteScaling,
    Target,
};
use crate::analysis::simulate::{Report, RunCapture, simulate_headline, simulate_streaming};
use crate::input::scenario::suite::{Suite, SuiteRule};
use crate::input::scenario::{Scenario, ScenarioError};
use crate::integrate::SolveError;
pub use statistics::{DesignStatistic, Statistics};

/// Why a suite could not be run.
#[derive(Debug, thiserror::Error)]
pub enum SuiteError {
    /// The scenario has no suite.
    #[error("the scenario's ground motion is not a suite (kind = \"suite\")")]
    NotASuite,
    /// The suite cannot be scaled by its rule.
    #[error("ground_motion.scaling: {0}")]
    Scaling(#[from] ScalingError),
    /// A record's scenario could not be formed.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A suite on a row of buildings given to a pair's suite driver ([`run`],
    /// [`run_headline`]): a row's suite is run by [`row::run_row`] / [`row::run_row_headline`].
    #[error(
        "the scenario is a row of {0} structures: its suite of records is run by the row's \
         suite driver (study::suite::row::run_row), not the pair's"
    )]
    Row(usize),
    /// A record's run failed.
    #[error("record {index} ({file}): {source}")]
    Solve {
        /// 1-based position in `records`.
        index: usize,
        /// The file.
        file: String,
        /// Why.
        source: Box<SolveError>,
    },
}

/// The headline numbers of one record's run (SI units): what `suite.csv` holds per row and
/// `summary.json`'s `suite.records` per record, with the meanings of summary.json's keys of
/// the same names.
#[derive(Debug, Clone, PartialEq)]
pub struct Headline {
    /// (name, value) in the order of the columns of `suite.csv` (the names are those columns).
    pub values: Vec<(String, f64)>,
    /// The self-check: every number within 1 % of the tighter run (`None`: not checked).
    pub converged: Option<bool>,
}

impl Headline {
    /// The numbers of `report` for a record of PGA `pga` (m/s², as run).
    pub fn of(report: &Report, pga: f64) -> Headline {
        let s = &report.structures;
        let mut v: Vec<(String, f64)> = vec![
            ("pga".into(), pga),
            ("peak_displacement_1".into(), s[0].peak_displacement),
            ("peak_displacement_2".into(), s[1].peak_displacement),
            (
                "peak_displacement_no_contact_1".into(),
                s[0].peak_displacement_no_contact,
            ),
            (
                "peak_displacement_no_contact_2".into(),
                s[1].peak_displacement_no_contact,
            ),
            ("peak_force".into(), report.contact.peak_force),
            ("impacts".into(), report.contact.impacts as f64),
            ("contact_time".into(), report.contact.contact_time),
            ("max_penetration".into(), report.contact.max_penetration),
            ("required_separation".into(), report.separation.time_history),
        ];
        for (k, l) in report.levels.iter().enumerate() {
            let n = k + 1;
            v.push((format!("level{n}_required_separation"), l.required_gap));
            v.push((format!("level{n}_peak_force"), l.peak_force));
            v.push((format!("level{n}_impacts"), l.impacts as f64));
        }
        v.push((
            "check_max_change".into(),
            report.accuracy.max_change.unwrap_or(f64::NAN),
        ));
        Headline {
            values: v,
            converged: report.accuracy.converged,
        }
    }

    /// The value named `name`.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|(n, _)| n == name).map(|(_, x)| *x)
    }
}

/// One record's run of a suite: the file, its factor, its own scenario and its run by the
/// driver of the suite's structures — a pair's [`Report`] ([`RecordRun`]) or a row's
/// [`crate::analysis::simulate::RowReport`] ([`row::RowRecordRun`]): one pipeline for both
/// (`run_records`).
#[derive(Debug, Clone)]
pub struct MemberRun<R> {
    /// The file as the scenario names it.
    pub file: String,
    /// The component read.
    pub component: Option<String>,
    /// The factor applied (the rule's, or the user's with rule = "none").
    pub factor: f64,
    /// The record's own scenario (the record scaled, the solver's defaults of that record).
    pub scenario: Scenario,
    /// Its run.
    pub report: R,
    /// Its history samples (to write the representative record's files).
    pub capture: RunCapture,
    /// Its headline numbers.
    pub headline: Headline,
}

/// One record's run of a pair.
pub type RecordRun = MemberRun<Report>;

/// What the suite pipeline needs of a record's run: its headline numbers and the time-history
/// required separation at a level.
pub trait MemberReport {
    /// The headline numbers for a record of PGA `pga` (m/s², as run).
    fn headline(&self, pga: f64) -> Headline;
    /// The time-history required separation at level `level` (0-based) of pair `pair`
    /// (0-based; a pair's run has only pair 0), m.
    fn required_gap(&self, pair: usize, level: usize) -> f64;
    /// The run's warnings.
    fn warnings(&self) -> &[String];
}

impl MemberReport for Report {
    fn headline(&self, pga: f64) -> Headline {
        Headline::of(self, pga)
    }
    fn required_gap(&self, _pair: usize, level: usize) -> f64 {
        self.levels[level].required_gap
    }
    fn warnings(&self) -> &[String] {
        &self.warnings
    }
}

/// The records of a suite run ([`run_records`]): the scaling, every record's run, and across
/// them the statistic of the rule, its clause and the statistics of every headline number.
pub(crate) struct Runs<R> {
    pub(crate) scaling: Option<ScaledSuite>,
    pub(crate) records: Vec<MemberRun<R>>,
    pub(crate) statistic: DesignStatistic,
    pub(crate) basis: &'static str,
    pub(crate) statistics: NamedStatistics,
}

/// The suite of `scenario` scaled by its rule, each record's scenario run by `simulate` (in
/// parallel), and the statistics across the records: the one pipeline of a pair's suite
/// ([`run`], [`run_headline`]) and a row's ([`row::run_row`], [`row::run_row_headline`]).
pub(crate) fn run_records<R, F>(scenario: &Scenario, simulate: F) -> Result<Runs<R>, SuiteError>
where
    R: MemberReport + Send,
    F: Fn(&Scenario) -> Result<(R, RunCapture), SolveError> + Sync,
{
    let suite = scenario.suite.as_ref().ok_or(SuiteError::NotASuite)?;
    let Members {
        scaling,
        factors,
        scenarios,
    } = members(scenario)?;
    let runs = run_members(suite, &scenarios, simulate)?;
    let records: Vec<MemberRun<R>> = runs
        .into_iter()
        .zip(scenarios)
        .enumerate()
        .map(|(i, ((report, capture), sc))| {
            let m = &suite.records[i];
            MemberRun {
                file: m.file.clone(),
                component: m.component.clone(),
                factor: factors[i],
                headline: report.headline(sc.ground_motion.pga()),
                scenario: sc,
                report,
                capture,
            }
        })
        .collect();
    let (statistic, basis) = DesignStatistic::for_rule(suite.scaling.rule, records.len());
    let statistics = named_statistics(records.iter().map(|r| &r.headline), statistic);
    Ok(Runs {
        scaling,
        records,
        statistic,
        basis,
        statistics,
    })
}

/// The record with the largest required separation at level `level` of pair `pair` (0-based;
/// the first of equal values): the representative record of a suite.
pub(crate) fn representative<R: MemberReport>(
    records: &[MemberRun<R>],
    pair: usize,
    level: usize,
) -> usize {
    (0..records.len())
        .max_by(|&a, &b| {
            let g = |i: usize| records[i].report.required_gap(pair, level);
            // the first of equal values
            g(a).total_cmp(&g(b)).then(b.cmp(&a))
        })
        .unwrap_or(0)
}

/// The design value of the required separation at one contact level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelDesign {
    /// 1-based level, in the scenario's order.
    pub level: usize,
    /// Height, m.
    pub height: f64,
    /// The gap given there, m.
    pub gap: f64,
    /// The design value of the time-history required separation there, m.
    pub required: f64,
    /// gap − required, m (negative: too small).
    pub margin: f64,
    /// Whether the gap is at least the design value.
    pub sufficient: bool,
    /// The statistics of the level's required separation over the records, m.
    pub statistics: Statistics,
}

/// The answer: the design values at every level and the verdict.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Design {
    /// The statistic taken: `mean` or `max`.
    pub statistic: DesignStatistic,
    /// Why (the clause).
    pub basis: &'static str,
    /// Number of records.
    pub records: usize,
    /// Every level.
    pub levels: Vec<LevelDesign>,
    /// The gap suffices at every level.
    pub sufficient: bool,
    /// The level of least margin (1-based): what governs.
    pub governing_level: usize,
    /// How many levels are too narrow.
    pub insufficient_levels: usize,
}

/// Statistics of every headline number, in the order of [`Headline::values`].
#[derive(Debug, Clone, PartialEq)]
pub struct NamedStatistics(pub Vec<(String, Statistics)>);

impl Serialize for NamedStatistics {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        let mut m = ser.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            m.serialize_entry(k, v)?;
        }
        m.end()
    }
}

/// A suite run.
#[derive(Debug, Clone)]
pub struct SuiteRun {
    /// The rule.
    pub rule: SuiteRule,
    /// The scaling by the rule (`None` for rule = "none").
    pub scaling: Option<ScaledSuite>,
    /// Every record, in the scenario's order.
    pub records: Vec<RecordRun>,
    /// Every headline number across the records.
    pub statistics: NamedStatistics,
    /// The design values and the verdict.
    pub design: Design,
    /// The record whose run the top-level keys of summary.json (and history.csv, impacts.csv,
    /// the run's pictures) describe: the largest required separation at the governing level
    /// (0-based).
    pub representative: usize,
}

/// The code's scaling rule of a suite rule (`None`: no scaling).
pub fn scaling_rule(rule: SuiteRule) -> Option<ScalingRule> {
    match rule {
        SuiteRule::Asce7 => Some(ScalingRule::Asce7),
        SuiteRule::Ec8 => Some(ScalingRule::Ec8),
        SuiteRule::None => None,
    }
}

/// The suite of `scenario` scaled by its rule over the structures' first-mode periods
/// (`None` for rule = "none").
pub fn scale(scenario: &Scenario, suite: &Suite) -> Result<Option<ScaledSuite>, ScalingError> {
    let Some(rule) = scaling_rule(suite.scaling.rule) else {
        return Ok(None);
    };
    let spec = &suite.scaling;
    let Some(spectrum) = spec.target.clone() else {
        return Ok(None);
    };
    let target = match spec.target_scale {
        Some(f) => Target::scaled(spectrum, f),
        None => Target::for_rule(spectrum, rule),
    };
    let t1: Vec<f64> = scenario
        .structures
        .iter()
        .map(|s| s.modal().periods().first().copied().unwrap_or(f64::NAN))
        .collect();
    let mut opts = ScalingOptions::new(rule, &t1);
    opts.range = spec.range.map(|(lo, hi)| PeriodRange { lo, hi });
    if let Some(r) = spec.ratio {
        opts.required_ratio = r;
    }
    opts.factor_limits = spec.factor_limits;
    let members: Vec<SuiteMember> = suite
        .records
        .iter()
        .map(|m| SuiteMember {
            name: &m.file,
            record: &m.record,
        })
        .collect();
    SuiteScaling::compute(&members, &target, &opts).map(Some)
}

/// Scale the suite of `scenario`, run every record (self-checked with `check`) in parallel,
/// and form the statistics and the verdict. Each record's history is kept
/// ([`MemberRun::capture`]) to write the representative record's files.
pub fn run(scenario: &Scenario, check: bool) -> Result<SuiteRun, SuiteError> {
    run_with(scenario, |sc| {
        let mut capture = RunCapture::new();
        simulate_streaming(sc, check, &mut capture).map(|r| (r, capture))
    })
}

/// [`run`] without the histories and the floor responses: every record through
/// [`simulate_headline`] (the driver of a sweep's rows; the same integration, so the same
/// numbers), [`MemberRun::capture`] empty. What a case of a sweep over a suite runs
/// ([`crate::study::sweep`]).
pub fn run_headline(scenario: &Scenario, check: bool) -> Result<SuiteRun, SuiteError> {
    run_headline_by(scenario, |sc| simulate_headline(sc, check))
}

/// [`run_headline`] with every record's scenario run by `simulate`, which must give the
/// report [`simulate_headline`] gives (a sweep's runs through its cache of runs without
/// contact, [`crate::study::sweep::free_cache`]).
pub fn run_headline_by<F>(scenario: &Scenario, simulate: F) -> Result<SuiteRun, SuiteError>
where
    F: Fn(&Scenario) -> Result<Report, SolveError> + Sync,
{
    run_with(scenario, |sc| simulate(sc).map(|r| (r, RunCapture::new())))
}

/// The records of a suite, each as a scenario of its own: what every driver of a suite runs
/// (a pair's [`run`], a row's [`row::run_row`], and a fragility study's suite on a row).
#[derive(Debug, Clone)]
pub struct Members {
    /// The scaling by the rule (`None` for rule = "none").
    pub scaling: Option<ScaledSuite>,
    /// The factor on each record, in the scenario's order (the rule's, or the user's).
    pub factors: Vec<f64>,
    /// Each record's scenario ([`Suite::member_scenario`]): the suite's scenario — a pair or a
    /// row of buildings, every structure and contact unchanged — with that record scaled by its
    /// factor as its ground motion and the solver's defaults of that record alone.
    pub scenarios: Vec<Scenario>,
}

/// The suite of `scenario` scaled by its rule over the first-mode periods of all its structures
/// (a pair's two, or every building of a row: the period range defaults to 0.2 × the shortest
/// to 2 × the longest) and each record's scenario ([`Members`]). Shared by the suite drivers
/// of a pair and of a row, and by fragility on a row (a row suite member's scenario is the row
/// with that record, as for a pair).
pub fn members(scenario: &Scenario) -> Result<Members, SuiteError> {
    let suite = scenario.suite.as_ref().ok_or(SuiteError::NotASuite)?;
    let scaling = scale(scenario, suite)?;
    let factors: Vec<f64> = match &scaling {
        Some(s) => s.records.iter().map(|r| r.factor).collect(),
        None => suite
            .records
            .iter()
            .map(|m| m.factor.unwrap_or(1.0))
            .collect(),
    };
    let scenarios: Vec<Scenario> = factors
        .iter()
        .enumerate()
        .map(|(i, &f)| suite.member_scenario(scenario, i, f))
        .collect::<Result<_, _>>()?;
    Ok(Members {
        scaling,
        factors,
        scenarios,
    })
}

/// Each record's scenario of `scenarios` run by `simulate`, in parallel; the first failure
/// names its record (1-based) and file.
fn run_members<R, F>(
    suite: &Suite,
    scenarios: &[Scenario],
    simulate: F,
) -> Result<Vec<R>, SuiteError>
where
    R: Send,
    F: Fn(&Scenario) -> Result<R, SolveError> + Sync,
{
    scenarios
        .par_iter()
        .enumerate()
        .map(|(i, sc)| {
            simulate(sc).map_err(|source| SuiteError::Solve {
                index: i + 1,
                file: suite.records[i].file.clone(),
                source: Box::new(source),
            })
        })
        .collect()
}

/// Every headline number across the records' `headlines` (named as the first record's), with
/// the design value by `statistic`.
fn named_statistics<'a>(
    headlines: impl Iterator<Item = &'a Headline> + Clone,
    statistic: DesignStatistic,
) -> NamedStatistics {
    let Some(first) = headlines.clone().next() else {
        return NamedStatistics(Vec::new());
    };
    NamedStatistics(
        first
            .values
            .iter()
            .map(|(name, _)| {
                let v: Vec<f64> = headlines.clone().filter_map(|h| h.get(name)).collect();
                (name.clone(), Statistics::of(&v, statistic))
            })
            .collect(),
    )
}

/// The suite scaled by its rule, each record's scenario run by `simulate` (in parallel), the
/// statistics and the verdict: the one pipeline of [`run`] and [`run_headline`].
fn run_with<F>(scenario: &Scenario, simulate: F) -> Result<SuiteRun, SuiteError>
where
    F: Fn(&Scenario) -> Result<(Report, RunCapture), SolveError> + Sync,
{
    let suite = scenario.suite.as_ref().ok_or(SuiteError::NotASuite)?;
    if scenario.is_row() {
        return Err(SuiteError::Row(scenario.structures.len()));
    }
    let Runs {
        scaling,
        records,
        statistic,
        basis,
        statistics,
    } = run_records(scenario, simulate)?;
    let design = design(scenario, &records, statistic, basis);
    let representative = representative(&records, 0, design.governing_level - 1);
    Ok(SuiteRun {
        rule: suite.scaling.rule,
        scaling,
        records,
        statistics,
        design,
        representative,
    })
}

/// The design value of the required separation at every level, and the verdict.
pub fn design(
    scenario: &Scenario,
    records: &[RecordRun],
    statistic: DesignStatistic,
    basis: &'static str,
) -> Design {
    let (levels, governing_level) = level_designs(
        &scenario.contact.levels,
        |k| {
            records
                .iter()
                .map(|r| r.report.levels[k].required_gap)
                .collect()
        },
        statistic,
    );
    Design {
        statistic,
        basis,
        records: records.len(),
        sufficient: levels.iter().all(|l| l.sufficient),
        insufficient_levels: levels.iter().filter(|l| !l.sufficient).count(),
        governing_level,
        levels,
    }
}

/// The design value at each of one contact's `levels` of the records' required separations
/// there (`required(k)`: one value per record at level k, 0-based), and the level of least
/// margin (1-based; the first of equal margins): a pair's levels, or one pair's of a row.
pub(crate) fn level_designs(
    levels: &[crate::model::system::ContactLevel],
    required: impl Fn(usize) -> Vec<f64>,
    statistic: DesignStatistic,
) -> (Vec<LevelDesign>, usize) {
    let levels: Vec<LevelDesign> = levels
        .iter()
        .enumerate()
        .map(|(k, lv)| {
            let statistics = Statistics::of(&required(k), statistic);
            let required = statistics.design;
            LevelDesign {
                level: k + 1,
                height: lv.height,
                gap: lv.gap,
                required,
                margin: lv.gap - required,
                sufficient: lv.gap >= required,
                statistics,
            }
        })
        .collect();
    let governing = levels
        .iter()
        .fold(None::<&LevelDesign>, |m, l| match m {
            Some(m) if m.margin <= l.margin => Some(m),
            _ => Some(l),
        })
        .map_or(1, |l| l.level);
    (levels, governing)
}
