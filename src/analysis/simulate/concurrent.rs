//! `pounding run`'s self-check beside its run (issue 25): the check's integration on a second
//! thread while this one integrates the result, streams its rows and hands the finished
//! result to the caller (who writes its files and draws its pictures meanwhile).
//!
//! The order keeps the report bit for bit what [`super::simulate_streaming`] gives (tested
//! both ways): the check's run with contact starts at once, as it depends on nothing of the
//! result's; its run without contact is integrated on the check's thread where the tolerance
//! changes it, and otherwise ([`free_run_is_exact`]) is the result's, taken once both threads
//! are done. A result that never touched is its own check, as sequentially; the check's run
//! with contact was then integrated in vain on the second core (one run with contact of the
//! free system: about the result's own run with contact in instructions, and no wall time, as
//! the result's two runs take longer). A check that integrates its own run without contact
//! (`rk4`, yielding storeys) does so on a third thread beside its run with contact
//! ([`beside_each_other`]). [`run_beside`] is the machinery, a row's too
//! ([`super::simulate_row_streaming_beside`]). The sweeps, suites and fragility studies,
//! which run cases in parallel already, keep to the sequential path.

use std::sync::atomic::{AtomicU64, Ordering};

use super::accuracy::tightened;
use super::{
    Phase, Report, RunSink, assemble, conclude_check, free_run_is_exact, integrate_free,
    integrate_with, no_spectrum, refuse_row, reuse, simulate_phases,
};
use crate::input::scenario::Scenario;
use crate::integrate::{SolveError, Stats};
use crate::model::system::System;
use crate::recording::run_record::RunRecord;

/// [`super::simulate_streaming`] with the self-check (`check`) integrated on a second thread
/// while this one integrates the result (`concurrent`; sequentially, as
/// `simulate_streaming` does, without it or without a second core or thread). `beside` is
/// called on this thread once the result's runs are done and streamed to `sink`, with `sink`
/// and the result not yet checked (`accuracy` unchecked, without the check's warnings), while
/// the check goes on: what it returns comes back with the checked report. The report is
/// bit-identical either way, and `beside` sees the same result.
///
/// A check that integrates its own run without contact (`rk4`, yielding storeys) integrates
/// it on a third thread beside its run with contact (the two are independent: see
/// `check_runs`).
///
/// The check's progress reaches `sink` as its phases' [`RunSink::progress`] from this thread
/// (while it integrates and while it waits for the check). A check run that fails gives the
/// same `accuracy.failure` and warning as sequentially; a result's run that fails returns
/// its error once the check's threads have stopped (`beside` is then not called).
pub fn simulate_streaming_beside<S: RunSink, T>(
    scenario: &Scenario,
    check: bool,
    sink: &mut S,
    concurrent: bool,
    beside: impl FnOnce(&mut S, &Report) -> T,
) -> Result<(Report, T), SolveError> {
    streaming_beside(scenario, (check, concurrent), sink, beside, check_runs)
}

/// What the self-check integrates, on whichever thread: the runs of `tight` (its `system`)
/// with contact and, unless the result's is taken (`exact`), without; beside each other
/// when given their progress (`split`: see [`check_runs`]). `R` is a pair's [`Runs`] or a
/// row's `RowRuns`.
pub(super) type CheckIntegration<R = Runs> =
    fn(&Scenario, &System, &mut dyn RunSink, Option<&CheckProgress>, bool) -> Result<R, SolveError>;

/// The self-check's runs: with contact, its counters, and without (`None`: the result's).
pub(super) struct Runs {
    with: RunRecord,
    stats: Stats,
    without: Option<RunRecord>,
}

/// The self-check's integrations of `tight` (the scenario at the [`tightened`] settings, its
/// `system`), streaming progress to `sink`; without contact only when not `exact`, and then
/// on a thread of its own beside the run with contact when `split` takes its progress.
///
/// Where the check integrates its own run without contact (not [`free_run_is_exact`]: `rk4`,
/// yielding storeys) that run does not depend on its run with contact: the shortcut of
/// [`super::free_run_of`] from a run with contact that never touched holds for `exact-modal`
/// on elastic structures only, whose check takes the result's run without contact. So the
/// two runs beside each other give the records of the two in a row, bit for bit; a failure
/// is the one the sequential order meets first (the run with contact's, then the other's).
pub(super) fn check_runs(
    tight: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    split: Option<&CheckProgress>,
    exact: bool,
) -> Result<Runs, SolveError> {
    let with = |sink: &mut dyn RunSink| integrate_with(tight, system, sink, true, true);
    let free = |sink: &mut dyn RunSink| integrate_free(tight, system, sink, true, true);
    let ((with, stats), without) = beside_each_other(sink, split, exact, with, free)?;
    Ok(Runs {
        with,
        stats,
        without,
    })
}

/// A self-check's run with contact (`with`) and, unless `exact`, its run without (`free`):
/// on this thread one after the other, or with `split` the run without contact on a thread
/// of its own (streaming its progress to `split`) while this one integrates the run with
/// contact; its failure first, as one after the other (where the run without contact would
/// not have been integrated). A panic on the other thread is this thread's.
pub(super) fn beside_each_other<W: Send, F: Send>(
    sink: &mut dyn RunSink,
    split: Option<&CheckProgress>,
    exact: bool,
    with: impl FnOnce(&mut dyn RunSink) -> Result<W, SolveError>,
    free: impl Fn(&mut dyn RunSink) -> Result<F, SolveError> + Sync,
) -> Result<(W, Option<F>), SolveError> {
    if exact {
        return Ok((with(sink)?, None));
    }
    let Some(progress) = split else {
        let w = with(sink)?;
        return Ok((w, Some(free(sink)?)));
    };
    std::thread::scope(|scope| {
        let free = &free;
        let spawned = std::thread::Builder::new()
            .name("self-check, without pounding".into())
            .spawn_scoped(scope, move || free(&mut { progress }));
        let w = with(sink);
        let f = match spawned {
            Ok(h) => Some(h.join().unwrap_or_else(|p| std::panic::resume_unwind(p))),
            Err(_) => None,
        };
        let w = w?;
        // (no thread to be had: after it, as sequentially)
        let f = match f {
            Some(f) => f?,
            None => free(sink)?,
        };
        Ok((w, Some(f)))
    })
}

/// [`simulate_streaming_beside`] with the check's integration `integrate` (the tests make it
/// fail).
pub(super) fn streaming_beside<S: RunSink, T>(
    scenario: &Scenario,
    (check, concurrent): (bool, bool),
    sink: &mut S,
    beside: impl FnOnce(&mut S, &Report) -> T,
    integrate: CheckIntegration,
) -> Result<(Report, T), SolveError> {
    refuse_row(scenario)?;
    no_spectrum(scenario)?;
    let result = |sink: &mut dyn RunSink| simulate_phases(scenario, sink, false, true, None, true);
    if !check {
        let report = result(sink)?;
        let t = beside(sink, &report);
        return Ok((report, t));
    }
    let mut tight = scenario.clone();
    tight.solver = tightened(&scenario.solver);
    let exact = free_run_is_exact(scenario);
    // a result that never touched is its own check (a check run on another thread in vain)
    let needed = |r: &Report| !(exact && reuse::untouched(scenario, &r.stats, &r.with_contact));
    let integrate = |sink: &mut dyn RunSink, split: Option<&CheckProgress>| {
        let system = tight.system();
        let runs = integrate(&tight, &system, sink, split, exact);
        (system, runs)
    };
    let parts = (result, needed, integrate);
    let (mut report, t, runs) = run_beside(sink, concurrent, parts, beside)?;
    let check = match runs {
        None => Ok(None),
        Some((system, runs)) => runs.map(|r| {
            let without = r.without.unwrap_or_else(|| report.without_contact.clone());
            Some(assemble(&tight, &system, r.with, r.stats, without))
        }),
    };
    conclude_check(scenario, &mut report, check);
    Ok((report, t))
}

/// The result (`result`, streamed to `sink`), `beside` once it is done, and its self-check
/// (`check`) where `needed` by the result: with `concurrent` (and a second core and thread
/// to be had) the check on a thread of its own from the start, its progress passed on to
/// `sink` from this thread, and (`split`) its progress for a thread of its own of the check's
/// run without contact; else on this thread after `beside`, as sequentially. Returns the
/// result, what `beside` returned and the check's outcome (`None`: not needed); the
/// result's error once the check's threads have stopped. A panic in the check is this
/// thread's.
#[allow(clippy::type_complexity)]
pub(super) fn run_beside<S: RunSink, R, T, C: Send>(
    sink: &mut S,
    concurrent: bool,
    (result, needed, check): (
        impl FnOnce(&mut dyn RunSink) -> Result<R, SolveError>,
        impl Fn(&R) -> bool,
        impl Fn(&mut dyn RunSink, Option<&CheckProgress>) -> C + Sync,
    ),
    beside: impl FnOnce(&mut S, &R) -> T,
) -> Result<(R, T, Option<C>), SolveError> {
    let two_cores = std::thread::available_parallelism().is_ok_and(|n| n.get() > 1);
    if !(concurrent && two_cores) {
        return sequential(sink, (result, needed, check), beside);
    }
    let progress = CheckProgress::new();
    std::thread::scope(|scope| {
        let waiting = std::thread::current();
        let (check, progress) = (&check, &progress);
        let spawned = std::thread::Builder::new()
            .name("self-check".into())
            .spawn_scoped(scope, move || {
                // (wakes this thread when the check ends, however it ends)
                let _wake = Wake(waiting);
                check(&mut { progress }, Some(progress))
            });
        let Ok(handle) = spawned else {
            return sequential(sink, (result, needed, check), beside);
        };
        let mut forward = Forward {
            sink: &mut *sink,
            progress,
            seen: [u64::MAX; 2],
        };
        // the result's runs exactly as sequentially: the check's progress interleaved
        let r = result(&mut forward);
        let seen = forward.seen;
        let r = match r {
            Ok(r) => r,
            // (the check's outcome, a panic too, is moot: the result failed)
            Err(e) => {
                let _ = handle.join();
                return Err(e);
            }
        };
        let t = beside(sink, &r);
        let mut forward = Forward {
            sink: &mut *sink,
            progress,
            seen,
        };
        while !handle.is_finished() {
            forward.check_progress();
            std::thread::park_timeout(std::time::Duration::from_millis(100));
        }
        let c = match handle.join() {
            Ok(c) => c,
            // a panic in the check is this thread's, as sequentially
            Err(p) => std::panic::resume_unwind(p),
        };
        let c = needed(&r).then_some(c);
        Ok((r, t, c))
    })
}

/// [`run_beside`] on this thread alone: the result, `beside`, then the check where needed
/// (as [`super::simulate_streaming`] and [`super::simulate_row_streaming`] run them).
#[allow(clippy::type_complexity)]
fn sequential<S: RunSink, R, T, C>(
    sink: &mut S,
    (result, needed, check): (
        impl FnOnce(&mut dyn RunSink) -> Result<R, SolveError>,
        impl Fn(&R) -> bool,
        impl Fn(&mut dyn RunSink, Option<&CheckProgress>) -> C,
    ),
    beside: impl FnOnce(&mut S, &R) -> T,
) -> Result<(R, T, Option<C>), SolveError> {
    let r = result(sink)?;
    let t = beside(sink, &r);
    let c = needed(&r).then(|| check(sink, None));
    Ok((r, t, c))
}

/// Unparks a thread when dropped: the check's thread wakes the one waiting for it as it ends.
struct Wake(std::thread::Thread);

impl Drop for Wake {
    fn drop(&mut self) {
        self.0.unpark();
    }
}

/// How far the check's two runs have come: each one's simulated time, s (as `f64` bits;
/// `u64::MAX`: not started), written by the check's thread, read by the result's.
pub(super) struct CheckProgress {
    t: [AtomicU64; 2],
}

impl CheckProgress {
    pub(super) fn new() -> CheckProgress {
        CheckProgress {
            t: [AtomicU64::new(u64::MAX), AtomicU64::new(u64::MAX)],
        }
    }
}

/// The check's thread streams its progress (and nothing else: its phases have no rows) here.
impl RunSink for &CheckProgress {
    fn progress(&mut self, phase: Phase, t: f64) {
        let k = usize::from(phase == Phase::CheckWithoutContact);
        // (a display's: no ordering with anything else)
        self.t[k].store(t.to_bits(), Ordering::Relaxed);
    }

    fn wants_rows(&self) -> bool {
        false
    }
}

/// The result's sink, with the check's progress passed on to it at every progress of the
/// result (what it last passed on: `seen`).
struct Forward<'a> {
    sink: &'a mut dyn RunSink,
    progress: &'a CheckProgress,
    seen: [u64; 2],
}

impl Forward<'_> {
    /// The check's progress since last passed on to the sink.
    fn check_progress(&mut self) {
        let phases = [Phase::CheckWithContact, Phase::CheckWithoutContact];
        for (k, phase) in phases.into_iter().enumerate() {
            let bits = self.progress.t[k].load(Ordering::Relaxed);
            if bits != self.seen[k] {
                self.seen[k] = bits;
                self.sink.progress(phase, f64::from_bits(bits));
            }
        }
    }
}

impl RunSink for Forward<'_> {
    fn contact_row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
        self.sink.contact_row(t, w, forces);
    }
    fn free_row(&mut self, t: f64, w: [f64; 2]) {
        self.sink.free_row(t, w);
    }
    fn contact_floor_row(&mut self, t: f64, values: &[f64]) {
        self.sink.contact_floor_row(t, values);
    }
    fn free_floor_row(&mut self, t: f64, values: &[f64]) {
        self.sink.free_floor_row(t, values);
    }
    fn row_contact_row(&mut self, t: f64, w: &[f64], forces: &[f64]) {
        self.sink.row_contact_row(t, w, forces);
    }
    fn row_free_row(&mut self, t: f64, w: &[f64]) {
        self.sink.row_free_row(t, w);
    }
    fn progress(&mut self, phase: Phase, t: f64) {
        self.sink.progress(phase, t);
        self.check_progress();
    }
    fn wants_rows(&self) -> bool {
        self.sink.wants_rows()
    }
}
