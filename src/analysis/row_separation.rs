//! `pounding separation` of a row of buildings (issue 29): every adjacent pair's report — every
//! rule and code at every contact level of that pair, [`GapReport`] — then the row's verdict:
//! the pair, rule and level with the smallest margin (gap − required) of all.
//!
//! Each pair's report is a pair's ([`crate::analysis::gap_report`]) on the pair taken as a
//! scenario of its own ([`Scenario::pair`]: its two structures, its contact, the row's ground
//! motion and design inputs). With a time history its peaks come from one run of the whole row
//! without contact (without contact the row's equations are uncoupled: every structure is
//! computed once, and each pair reads its own levels of that run); with a design spectrum from
//! the spectral analysis of each pair's two structures. A pair (N = 2) gives one entry whose
//! report is [`crate::analysis::gap_report::gap_report`]'s.

use serde::Serialize;

use crate::analysis::gap_report::{GapError, GapReport, check_codes, pair_gap_report};
use crate::analysis::level_checks::Governing;
use crate::codes::spectrum::DesignSpectrum;
use crate::input::scenario::Scenario;
use crate::integrate::{InitialState, SolveError, integrate};
use crate::recording::recorder::Recorder;
use crate::recording::run_record::LevelRecord;

/// One adjacent pair's report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairGapReport {
    /// The left structure's index in the row (0-based); the right one is `index + 1`.
    pub index: usize,
    /// The two structures' names, left then right.
    pub between: [String; 2],
    /// The pair's report (every rule and code at every level of the pair; its `warnings` are
    /// the pair's own, the scenario's are the row's).
    pub report: GapReport,
}

/// The row's verdict: of every pair's rules at every level, the one with the smallest margin.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct RowGapVerdict {
    /// The pair that governs (its left structure's index, 0-based), `None` without rules.
    pub pair: Option<usize>,
    /// Its two structures' names.
    pub between: Option<[String; 2]>,
    /// The rule and level that govern, in that pair.
    pub governing: Option<Governing>,
    /// The pairs (left structure's index) where some rule finds the gap too small somewhere.
    pub insufficient_pairs: Vec<usize>,
}

/// What `pounding separation` prints for a row (and `--json` writes).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowGapReport {
    /// Scenario title.
    pub title: String,
    /// The structures' names, in row order.
    pub structures: Vec<String>,
    /// Every adjacent pair, in row order.
    pub pairs: Vec<PairGapReport>,
    /// The row's verdict.
    pub verdict: RowGapVerdict,
    /// The scenario's warnings.
    pub warnings: Vec<String>,
}

/// The run without contact of a row `scenario` (or a pair), at every contact level of every
/// pair, pair by pair in row order and each pair's levels in its `[[contact]]` order: one
/// integration of the whole row (uncoupled without contact). A design spectrum (no time
/// history) or a suite is refused.
pub fn row_levels_without_contact(scenario: &Scenario) -> Result<Vec<LevelRecord>, SolveError> {
    if let Some(s) = &scenario.suite {
        return Err(SolveError::Suite(s.records.len()));
    }
    if let Some(s) = &scenario.design.spectrum {
        return Err(SolveError::NoTimeHistory(s.name()));
    }
    let system = scenario.system();
    let free = system.without_contact();
    let heights: Vec<f64> = system.levels.iter().map(|l| l.height).collect();
    let pairs: Vec<usize> = system.levels.iter().map(|l| l.pair).collect();
    let settings = &scenario.solver;
    let mut rec = Recorder::for_row(
        &free,
        &heights,
        &pairs,
        scenario.output_interval,
        settings.duration,
    )
    .without_floors();
    integrate(&free, settings, &InitialState::default(), &mut rec)?;
    Ok(rec.finish().levels)
}

/// The report of every adjacent pair of `scenario` (a row or a pair) and the row's verdict:
/// rules from `spectrum` if given, else from the scenario's own spectrum, else from its time
/// history (as [`crate::analysis::gap_report::gap_report`]); `codes`: the codes to include
/// (all of the scenario's when `None`).
pub fn row_gap_report(
    scenario: &Scenario,
    spectrum: Option<&DesignSpectrum>,
    codes: Option<&[String]>,
) -> Result<RowGapReport, GapError> {
    check_codes(scenario, codes)?;
    let time_history = if scenario.design.spectrum.is_none() {
        Some(row_levels_without_contact(scenario)?)
    } else {
        None
    };
    let n = scenario.structures.len();
    let names: Vec<String> = (scenario.structures.iter())
        .map(|s| s.name().to_string())
        .collect();
    let own_warnings = scenario.warnings.len();
    let mut pairs = Vec::with_capacity(n - 1);
    let mut first = 0;
    for (p, contact) in scenario.contacts().enumerate() {
        let range = first..first + contact.levels.len();
        first = range.end;
        let pair = scenario.pair(p);
        let levels = time_history.as_ref().map(|t| &t[range]);
        let mut report = pair_gap_report(&pair, spectrum, codes, levels)?;
        // the scenario's warnings once, for the row
        report
            .warnings
            .drain(..own_warnings.min(report.warnings.len()));
        pairs.push(PairGapReport {
            index: p,
            between: [names[p].clone(), names[p + 1].clone()],
            report,
        });
    }
    Ok(RowGapReport {
        title: scenario.title.clone(),
        structures: names,
        verdict: row_gap_verdict(&pairs),
        pairs,
        warnings: scenario.warnings.clone(),
    })
}

/// The row's verdict from every pair's: the smallest margin of all (the first pair on a tie).
pub fn row_gap_verdict(pairs: &[PairGapReport]) -> RowGapVerdict {
    let mut v = RowGapVerdict::default();
    for p in pairs {
        let verdict = &p.report.verdict;
        if verdict.insufficient > 0 {
            v.insufficient_pairs.push(p.index);
        }
        if let Some(g) = &verdict.governing
            && v.governing.as_ref().is_none_or(|m| g.margin < m.margin)
        {
            v.governing = Some(g.clone());
            v.pair = Some(p.index);
            v.between = Some(p.between.clone());
        }
    }
    v
}
