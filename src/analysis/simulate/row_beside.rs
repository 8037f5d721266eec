//! `pounding run`'s self-check of a row of buildings beside its run, as a pair's
//! ([`super::concurrent`]): the check's run with contact on a second thread from the start
//! (it depends on nothing of the result's) while this one integrates the row with and without
//! contact, streams its rows and hands the finished result to the caller (who writes its
//! files and draws its pictures meanwhile). The check's run without contact is the result's
//! where the tolerance does not change it ([`free_run_is_exact`], taken once both threads are
//! done), and otherwise is integrated on a third thread beside the check's run with contact
//! (a row with yielding storeys, or `rk4`).
//!
//! The report is bit for bit [`super::simulate_row_streaming`]'s (tested both ways, with the
//! rows streamed and every file). The sweeps, suites and fragility studies, which run cases
//! in parallel already, keep to the sequential path.

use super::concurrent::{CheckIntegration, CheckProgress, beside_each_other, run_beside};
use super::row::{assemble_row, conclude_row_check, row_free, row_with, simulate_row_phases};
use super::row_history::RowHistory;
use super::{RowReport, RunSink, free_run_is_exact};
use crate::input::scenario::Scenario;
use crate::integrate::{SolveError, Stats};
use crate::model::system::System;
use crate::recording::run_record::RunRecord;

/// [`super::simulate_row_streaming`] with the self-check (`check`) integrated on a second
/// thread while this one integrates the result (`concurrent`; sequentially without it or
/// without a second core or thread), as [`super::simulate_streaming_beside`] does a pair's:
/// `beside` is called on this thread once the result's runs are done and streamed to `sink`,
/// with the result not yet checked, while the check goes on; what it returns comes back with
/// the checked report. The report is bit-identical either way, and `beside` sees the same
/// result. A check run that fails gives the same `accuracy.failure` and warning as
/// sequentially; a result's run that fails returns its error once the check's threads have
/// stopped (`beside` is then not called).
pub fn simulate_row_streaming_beside<S: RunSink, T>(
    scenario: &Scenario,
    check: bool,
    sink: &mut S,
    concurrent: bool,
    beside: impl FnOnce(&mut S, &RowReport) -> T,
) -> Result<(RowReport, T), SolveError> {
    row_streaming_beside(scenario, (check, concurrent), sink, beside, row_check_runs)
}

/// A row's self-check runs: with contact (its record, counters and empty history), and
/// without (`None`: the result's).
pub(super) type RowRuns = (
    (RunRecord, Stats, RowHistory),
    Option<(RunRecord, RowHistory)>,
);

/// The self-check's integrations of a row's `tight` (the scenario at the tightened settings,
/// its `system`), streaming progress to `sink`: with contact, and without when not `exact`
/// (on a thread of its own with `split`: the two are independent, as a pair's,
/// [`super::concurrent::check_runs`]).
pub(super) fn row_check_runs(
    tight: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    split: Option<&CheckProgress>,
    exact: bool,
) -> Result<RowRuns, SolveError> {
    let with = |sink: &mut dyn RunSink| row_with(tight, system, sink, true);
    let free = |sink: &mut dyn RunSink| row_free(tight, system, sink, true);
    beside_each_other(sink, split, exact, with, free)
}

/// [`simulate_row_streaming_beside`] with the check's integration `integrate` (the tests make
/// it fail).
pub(super) fn row_streaming_beside<S: RunSink, T>(
    scenario: &Scenario,
    (check, concurrent): (bool, bool),
    sink: &mut S,
    beside: impl FnOnce(&mut S, &RowReport) -> T,
    integrate: CheckIntegration<RowRuns>,
) -> Result<(RowReport, T), SolveError> {
    let result = |sink: &mut dyn RunSink| simulate_row_phases(scenario, sink, false, None);
    if !check {
        let report = result(sink)?;
        let t = beside(sink, &report);
        return Ok((report, t));
    }
    let mut tight = scenario.clone();
    tight.solver = super::accuracy::tightened(&scenario.solver);
    let exact = free_run_is_exact(scenario);
    let integrate = |sink: &mut dyn RunSink, split: Option<&CheckProgress>| {
        let system = tight.system();
        let runs = integrate(&tight, &system, sink, split, exact);
        (system, runs)
    };
    // (a row's check is always run: unlike a pair's, no result is its own check)
    let parts = (result, |_: &RowReport| true, integrate);
    let (mut report, t, runs) = run_beside(sink, concurrent, parts, beside)?;
    if let Some((system, runs)) = runs {
        let check = runs.map(|(with, without)| {
            // the result's run without contact where the tolerance does not change it, as
            // `simulate_row_run` takes it (without its history: the check has none)
            let without = without.unwrap_or_else(|| {
                let none = RowHistory::default();
                (report.without_contact.clone(), none)
            });
            assemble_row(&tight, &system, with, without)
        });
        conclude_row_check(scenario, &mut report, check);
    }
    Ok((report, t))
}
