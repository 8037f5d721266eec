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
//! the result's two runs take longer). The sweeps and suites, which run cases in parallel
//! already, keep to the sequential path.

use std::sync::atomic::{AtomicU64, Ordering};

use super::accuracy::tightened;
use super::{
    Phase, Report, RunSink, assemble, conclude_check, free_run_is_exact, integrate_with,
    integrate_without, no_spectrum, refuse_row, reuse, simulate_phases,
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
/// The check's progress reaches `sink` as its phases' [`RunSink::progress`] from this thread
/// (while it integrates and while it waits for the check). A check run that fails gives the
/// same `accuracy.failure` and warning as sequentially; a result's run that fails returns
/// its error once the check's thread has stopped (`beside` is then not called).
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
/// with contact and, unless the result's is taken (`exact`), without.
type CheckIntegration = fn(&Scenario, &System, &mut dyn RunSink, bool) -> Result<Runs, SolveError>;

/// The self-check's runs: with contact, its counters, and without (`None`: the result's).
pub(super) struct Runs {
    with: RunRecord,
    stats: Stats,
    without: Option<RunRecord>,
}

/// The self-check's integrations of `tight` (the scenario at the [`tightened`] settings, its
/// `system`), streaming progress to `sink`; without contact only when not `exact`.
pub(super) fn check_runs(
    tight: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    exact: bool,
) -> Result<Runs, SolveError> {
    let (with, stats) = integrate_with(tight, system, sink, true, true)?;
    let without = if exact {
        None
    } else {
        let w = (&with, &stats);
        Some(integrate_without(tight, system, sink, true, true, w, true)?)
    };
    Ok(Runs {
        with,
        stats,
        without,
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
    if !check {
        let report = simulate_phases(scenario, sink, false, true, None, true)?;
        let t = beside(sink, &report);
        return Ok((report, t));
    }
    let mut tight = scenario.clone();
    tight.solver = tightened(&scenario.solver);
    let two_cores = std::thread::available_parallelism().is_ok_and(|n| n.get() > 1);
    if !(concurrent && two_cores) {
        return sequential(scenario, &tight, sink, beside, integrate);
    }
    let progress = CheckProgress::new();
    let exact = free_run_is_exact(scenario);
    std::thread::scope(|scope| {
        let waiting = std::thread::current();
        let spawned = std::thread::Builder::new()
            .name("self-check".into())
            .spawn_scoped(scope, || {
                // (wakes this thread when the check ends, however it ends)
                let _wake = Wake(waiting);
                let system = tight.system();
                let runs = integrate(&tight, &system, &mut &progress, exact);
                (system, runs)
            });
        let Ok(handle) = spawned else {
            return sequential(scenario, &tight, sink, beside, integrate);
        };
        let mut forward = Forward {
            sink: &mut *sink,
            progress: &progress,
            seen: [u64::MAX; 2],
        };
        // the result's runs exactly as sequentially: the check's progress interleaved
        let result = simulate_phases(scenario, &mut forward, false, true, None, true);
        let seen = forward.seen;
        let mut report = match result {
            Ok(r) => r,
            // (the check's outcome, a panic too, is moot: the result failed)
            Err(e) => {
                let _ = handle.join();
                return Err(e);
            }
        };
        let t = beside(sink, &report);
        let mut forward = Forward {
            sink: &mut *sink,
            progress: &progress,
            seen,
        };
        while !handle.is_finished() {
            forward.check_progress();
            std::thread::park_timeout(std::time::Duration::from_millis(100));
        }
        let (system, runs) = match handle.join() {
            Ok(r) => r,
            // a panic in the check is this thread's, as sequentially
            Err(p) => std::panic::resume_unwind(p),
        };
        // a result that never touched is its own check (the check's run was in vain)
        let repeats = exact && reuse::untouched(scenario, &report.stats, &report.with_contact);
        let check = match runs {
            _ if repeats => Ok(None),
            Ok(Runs {
                with,
                stats,
                without,
            }) => {
                let without = without.unwrap_or_else(|| report.without_contact.clone());
                Ok(Some(assemble(&tight, &system, with, stats, without)))
            }
            Err(e) => Err(e),
        };
        conclude_check(scenario, &mut report, check);
        Ok((report, t))
    })
}

/// [`streaming_beside`] on this thread alone: the result, `beside`, then the check (as
/// [`super::simulate_streaming`] runs it).
fn sequential<S: RunSink, T>(
    scenario: &Scenario,
    tight: &Scenario,
    sink: &mut S,
    beside: impl FnOnce(&mut S, &Report) -> T,
    integrate: CheckIntegration,
) -> Result<(Report, T), SolveError> {
    let mut report = simulate_phases(scenario, sink, false, true, None, true)?;
    let t = beside(sink, &report);
    let exact = free_run_is_exact(scenario);
    let check = if exact && reuse::untouched(scenario, &report.stats, &report.with_contact) {
        Ok(None)
    } else {
        let system = tight.system();
        integrate(tight, &system, sink, exact).map(|r| {
            let without = r.without.unwrap_or_else(|| report.without_contact.clone());
            Some(assemble(tight, &system, r.with, r.stats, without))
        })
    };
    conclude_check(scenario, &mut report, check);
    Ok((report, t))
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
struct CheckProgress {
    t: [AtomicU64; 2],
}

impl CheckProgress {
    fn new() -> CheckProgress {
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
