//! A suite of records on a row of buildings (issue 29): the suite scaled by its code's rule as
//! a pair's ([`super::members`]: the period range from every building's first-mode period, 0.2
//! × the shortest to 2 × the longest), every record run with and without contact through the
//! row's driver ([`simulate_row_streaming`], self-checked), in parallel; then per record the
//! headline numbers of every structure and every pair ([`Headline::of_row`]), across the
//! records their statistics, and **per pair and per contact level of that pair** the code's
//! design value of the required separation against the level's gap — the verdict per pair
//! (its governing level) and for the row (the pair and level of least margin).
//!
//! The design value at a level is the pair suite's (`level_designs`): the statistic
//! of the rule ([`DesignStatistic::for_rule`]) over the records' time-history required
//! separations at that level of that pair (`RowReport::pairs[p].levels[k].required_gap`, from
//! the row's run without contact, which is each pair's own: without contact a row is
//! uncoupled).

use serde::Serialize;

use super::{
    DesignStatistic, Headline, LevelDesign, MemberReport, MemberRun, NamedStatistics, Runs,
    SuiteError, level_designs, representative, run_records,
};
use crate::analysis::record_spectrum::ScaledSuite;
use crate::analysis::simulate::{
    RowReport, RunCapture, simulate_row_checked, simulate_row_streaming,
};
use crate::input::scenario::Scenario;
use crate::input::scenario::suite::SuiteRule;

impl Headline {
    /// The numbers of a row's `report` for a record of PGA `pga` (m/s², as run), named as a
    /// row's sweep columns are ([`crate::study::sweep::row_columns`]): `pga`; for every
    /// structure i (1-based, row order) `structure{i}_peak_displacement` and
    /// `structure{i}_peak_displacement_no_contact` (m, at its highest contact level); for every
    /// pair p (structures p and p + 1) `pair{p}_impacts`, `pair{p}_peak_force` (N),
    /// `pair{p}_max_penetration` (m), `pair{p}_contact_time` (s), `pair{p}_sep_time_history`
    /// (m, the time-history required separation at its highest level), and per level k of the
    /// pair `pair{p}_level{k}_required_separation` (m), `pair{p}_level{k}_peak_force` (N),
    /// `pair{p}_level{k}_impacts`; last `check_max_change` (the row's self-check).
    pub fn of_row(report: &RowReport, pga: f64) -> Headline {
        let mut v: Vec<(String, f64)> = vec![("pga".into(), pga)];
        for (s, i) in report.structures.iter().zip(1..) {
            v.push((
                format!("structure{i}_peak_displacement"),
                s.peak_displacement,
            ));
            v.push((
                format!("structure{i}_peak_displacement_no_contact"),
                s.peak_displacement_no_contact,
            ));
        }
        for (pr, p) in report.pairs.iter().zip(1..) {
            let c = &pr.contact;
            v.push((format!("pair{p}_impacts"), c.impacts as f64));
            v.push((format!("pair{p}_peak_force"), c.peak_force));
            v.push((format!("pair{p}_max_penetration"), c.max_penetration));
            v.push((format!("pair{p}_contact_time"), c.contact_time));
            v.push((
                format!("pair{p}_sep_time_history"),
                pr.separation.time_history,
            ));
            for (l, k) in pr.levels.iter().zip(1..) {
                v.push((
                    format!("pair{p}_level{k}_required_separation"),
                    l.required_gap,
                ));
                v.push((format!("pair{p}_level{k}_peak_force"), l.peak_force));
                v.push((format!("pair{p}_level{k}_impacts"), l.impacts as f64));
            }
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
}

/// One record's run of a row (its `headline`: [`Headline::of_row`]).
pub type RowRecordRun = MemberRun<RowReport>;

impl MemberReport for RowReport {
    fn headline(&self, pga: f64) -> Headline {
        Headline::of_row(self, pga)
    }
    fn required_gap(&self, pair: usize, level: usize) -> f64 {
        self.pairs[pair].levels[level].required_gap
    }
    fn warnings(&self) -> &[String] {
        &self.warnings
    }
}

/// The design values of one adjacent pair of the row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairDesign {
    /// The pair, 1-based: structures `pair` and `pair + 1` in row order.
    pub pair: usize,
    /// The two structures' names, left then right.
    pub between: [String; 2],
    /// Every level of the pair (1-based within the pair's `[[contact]]` table), as a pair
    /// suite's `design.levels`.
    pub levels: Vec<LevelDesign>,
    /// The pair's gap suffices at every one of its levels.
    pub sufficient: bool,
    /// The pair's level of least margin (1-based within the pair).
    pub governing_level: usize,
    /// How many of the pair's levels are too narrow.
    pub insufficient_levels: usize,
}

/// The answer of a row's suite: every pair's design values and the row's verdict.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowDesign {
    /// The statistic taken: `mean` or `max`.
    pub statistic: DesignStatistic,
    /// Why (the clause).
    pub basis: &'static str,
    /// Number of records.
    pub records: usize,
    /// Every adjacent pair, in row order.
    pub pairs: Vec<PairDesign>,
    /// Every pair's gap suffices at every level.
    pub sufficient: bool,
    /// The pair (1-based) whose governing level has the least margin of the row (the first of
    /// equal margins): what governs the row.
    pub governing_pair: usize,
    /// That pair's governing level (1-based within the pair).
    pub governing_level: usize,
    /// The pairs (1-based) with a level too narrow.
    pub insufficient_pairs: Vec<usize>,
}

impl RowDesign {
    /// The level that governs the row (of [`RowDesign::governing_pair`]).
    pub fn governing(&self) -> &LevelDesign {
        &self.pairs[self.governing_pair - 1].levels[self.governing_level - 1]
    }
}

/// A suite run on a row of buildings.
#[derive(Debug, Clone)]
pub struct RowSuiteRun {
    /// The rule.
    pub rule: SuiteRule,
    /// The scaling by the rule (`None` for rule = "none").
    pub scaling: Option<ScaledSuite>,
    /// Every record, in the scenario's order.
    pub records: Vec<RowRecordRun>,
    /// Every headline number across the records.
    pub statistics: NamedStatistics,
    /// The design values per pair and level, and the verdicts.
    pub design: RowDesign,
    /// The record whose run the top level of the output directory describes (summary.json's
    /// keys but `suite`, history.csv, …): the largest required separation at the row's
    /// governing pair and level (0-based; the first of equal values).
    pub representative: usize,
}

/// Scale the suite of the row `scenario`, run every record through the row's driver
/// (self-checked with `check`) in parallel, keeping each record's history
/// ([`MemberRun::capture`]), and form the statistics and the verdicts.
pub fn run_row(scenario: &Scenario, check: bool) -> Result<RowSuiteRun, SuiteError> {
    run_row_with(scenario, |sc| {
        let mut capture = RunCapture::new();
        simulate_row_streaming(sc, check, &mut capture).map(|r| (r, capture))
    })
}

/// [`run_row`] without the histories: every record through [`simulate_row_checked`] (the
/// driver of a row sweep's cases; the same integrations, so the same numbers, bit for bit),
/// [`MemberRun::capture`] empty. What a case of a sweep over a suite on a row runs
/// ([`crate::study::sweep`]).
pub fn run_row_headline(scenario: &Scenario, check: bool) -> Result<RowSuiteRun, SuiteError> {
    run_row_headline_by(scenario, |sc| simulate_row_checked(sc, check))
}

/// [`run_row_headline`] with every record's scenario run by `simulate`, which must give the
/// report [`simulate_row_checked`] gives (a sweep's runs through its cache of runs without
/// contact, [`crate::study::sweep::free_cache`]).
pub fn run_row_headline_by<F>(scenario: &Scenario, simulate: F) -> Result<RowSuiteRun, SuiteError>
where
    F: Fn(&Scenario) -> Result<RowReport, crate::integrate::SolveError> + Sync,
{
    run_row_with(scenario, |sc| simulate(sc).map(|r| (r, RunCapture::new())))
}

/// The suite of the row `scenario` scaled by its rule, each record's scenario run by
/// `simulate` (in parallel), the statistics and the verdicts: the one pipeline of [`run_row`]
/// and [`run_row_headline`].
fn run_row_with<F>(scenario: &Scenario, simulate: F) -> Result<RowSuiteRun, SuiteError>
where
    F: Fn(&Scenario) -> Result<(RowReport, RunCapture), crate::integrate::SolveError> + Sync,
{
    let suite = scenario.suite.as_ref().ok_or(SuiteError::NotASuite)?;
    let Runs {
        scaling,
        records,
        statistic,
        basis,
        statistics,
    } = run_records(scenario, simulate)?;
    let design = row_design(scenario, &records, statistic, basis);
    let (p, k) = (design.governing_pair - 1, design.governing_level - 1);
    let representative = representative(&records, p, k);
    Ok(RowSuiteRun {
        rule: suite.scaling.rule,
        scaling,
        records,
        statistics,
        design,
        representative,
    })
}

/// The design value of the required separation at every level of every pair of the row
/// `scenario` from the records' runs, each pair's verdict and the row's: the pair whose
/// governing level has the least margin gap − design value.
pub fn row_design(
    scenario: &Scenario,
    records: &[RowRecordRun],
    statistic: DesignStatistic,
    basis: &'static str,
) -> RowDesign {
    let names: Vec<&str> = scenario.structures.iter().map(|s| s.name()).collect();
    let pairs: Vec<PairDesign> = scenario
        .contacts()
        .enumerate()
        .map(|(p, contact)| {
            let (levels, governing_level) = level_designs(
                &contact.levels,
                |k| {
                    records
                        .iter()
                        .map(|r| r.report.pairs[p].levels[k].required_gap)
                        .collect()
                },
                statistic,
            );
            PairDesign {
                pair: p + 1,
                between: [names[p].to_string(), names[p + 1].to_string()],
                sufficient: levels.iter().all(|l| l.sufficient),
                insufficient_levels: levels.iter().filter(|l| !l.sufficient).count(),
                governing_level,
                levels,
            }
        })
        .collect();
    // the least margin over the pairs' governing levels, the first pair of equal margins
    let governing = pairs
        .iter()
        .fold(None::<&PairDesign>, |m, q| {
            let margin = |d: &PairDesign| d.levels[d.governing_level - 1].margin;
            match m {
                Some(m) if margin(m) <= margin(q) => Some(m),
                _ => Some(q),
            }
        })
        .map_or((1, 1), |q| (q.pair, q.governing_level));
    RowDesign {
        statistic,
        basis,
        records: records.len(),
        sufficient: pairs.iter().all(|q| q.sufficient),
        insufficient_pairs: pairs
            .iter()
            .filter(|q| !q.sufficient)
            .map(|q| q.pair)
            .collect(),
        governing_pair: governing.0,
        governing_level: governing.1,
        pairs,
    }
}
