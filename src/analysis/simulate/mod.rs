//! One scenario, end to end: the run with contact, the same run without, the comparison and the
//! required separations — `simulate(&Scenario) -> Report` — and the same with its self-check,
//! `simulate_checked(&Scenario, true)` (see [`accuracy`]).

pub mod accuracy;
mod concurrent;
#[cfg(test)]
mod concurrent_tests;
mod report;
mod reuse;
#[cfg(test)]
mod reuse_tests;
mod row;
mod row_beside;
pub mod row_check;
pub mod row_history;
mod separation_only;
mod sink;
mod warnings;

pub use concurrent::simulate_streaming_beside;
pub use report::{
    ContactReport, FloorReport, ImpactPulse, LevelReport, Report, StructureReport, impact_at,
};
use report::{contact_report, level_report, structure_report};
pub use reuse::{FreeRunKey, FreeRuns, free_run_of};
pub use row_beside::simulate_row_streaming_beside;
use separation_only::separations;
pub use separation_only::{SeparationReport, separation};
use sink::PhaseSink;
pub use sink::{NoSink, Phase, RunCapture, RunSink};
pub use warnings::{ENERGY_WARNING_THRESHOLD, PLAUSIBLE_DRIFT, PLAUSIBLE_PENETRATION};
use warnings::{drift_warning, level_warnings, run_warnings};

pub use row::{
    PairReport, RowFreeRuns, RowImpact, RowReport, RowVerdict, simulate_row, simulate_row_checked,
    simulate_row_reusing, simulate_row_streaming, simulate_row_with,
};

use self::accuracy::{AccuracyCheck, limited_tightening, tightened};
use crate::input::scenario::Scenario;
use crate::integrate::{InitialState, SolveError, SolverSettings, Stats, integrate};
use crate::model::system::System;
use crate::recording::recorder::Recorder;
use crate::recording::run_record::RunRecord;

/// Refuse a scenario without a time history to simulate (its ground motion is a design
/// spectrum, which only `pounding separation` uses), as `pounding run` does before running.
pub fn require_time_history(scenario: &Scenario) -> Result<(), SolveError> {
    match &scenario.design.spectrum {
        Some(s) => Err(SolveError::NoTimeHistory(s.name())),
        None => Ok(()),
    }
}

/// Integrate `system` and record displacements at `heights` (m), sampling every `interval` s.
pub fn run_system(
    system: &System,
    settings: &SolverSettings,
    initial: &InitialState,
    heights: &[f64],
    interval: f64,
) -> Result<(RunRecord, Stats), SolveError> {
    let mut rec = Recorder::new(system, heights, interval, settings.duration);
    let stats = integrate(system, settings, initial, &mut rec)?;
    Ok((rec.finish(), stats))
}

/// [`run_system`], streaming every history sample to `sink` as `phase`; `heights` and the
/// pair of each (its left structure's index: all 0 for a pair) are the tracked levels.
fn run_phase(
    system: &System,
    settings: &SolverSettings,
    (heights, pairs): (&[f64], &[usize]),
    interval: f64,
    sink: &mut dyn RunSink,
    phase: Phase,
    floors: Option<crate::recording::stations::FloorStations>,
) -> Result<(RunRecord, Stats), SolveError> {
    let resolution = match phase {
        Phase::CheckWithContact | Phase::CheckWithoutContact => accuracy::floor_resolution(),
        _ => crate::recording::subgrid::DEFAULT_RESOLUTION,
    };
    let what = (system, settings, (heights, pairs), interval);
    run_phase_at(what, sink, phase, floors, Some(resolution))
}

/// [`run_phase`] with the floor peaks' `resolution` between observations
/// ([`Recorder::with_floor_resolution`]).
#[allow(clippy::type_complexity)]
fn run_phase_at(
    (system, settings, (heights, pairs), interval): (
        &System,
        &SolverSettings,
        (&[f64], &[usize]),
        f64,
    ),
    sink: &mut dyn RunSink,
    phase: Phase,
    floors: Option<crate::recording::stations::FloorStations>,
    resolution: Option<f64>,
) -> Result<(RunRecord, Stats), SolveError> {
    let mut adapter = PhaseSink { sink, phase };
    let mut rec = Recorder::for_row(system, heights, pairs, interval, settings.duration)
        .with_floor_resolution(resolution);
    rec = match floors {
        Some(stations) => rec.with_floor_stations(system, heights, stations),
        None => rec.without_floors(),
    };
    let mut rec = rec.with_sink(&mut adapter);
    let stats = integrate(system, settings, &InitialState::default(), &mut rec)?;
    Ok((rec.finish(), stats))
}

/// What only a pair supports refuses a row (issue 29: `simulate_row` runs it).
fn refuse_row(scenario: &Scenario) -> Result<(), SolveError> {
    if scenario.is_row() {
        return Err(SolveError::Row(scenario.structures.len()));
    }
    Ok(())
}

/// A design spectrum has no time history: refuse it before integrating nothing.
fn no_spectrum(scenario: &Scenario) -> Result<(), SolveError> {
    if let Some(s) = &scenario.suite {
        return Err(SolveError::Suite(s.records.len()));
    }
    match &scenario.design.spectrum {
        Some(s) => Err(SolveError::NoTimeHistory(s.name())),
        None => Ok(()),
    }
}

/// Run a scenario with and without contact and compare. The result is not self-checked
/// (`accuracy.checked` is false); [`simulate_checked`] checks it.
pub fn simulate(scenario: &Scenario) -> Result<Report, SolveError> {
    simulate_phases(scenario, &mut NoSink, false, true, None, true)
}

/// [`simulate`] with the floor peaks between observations taken at `resolution` (the largest
/// `ω h` the cubic Hermite follows and the sub-grid's, [`crate::recording::subgrid`]; `None`:
/// the cubic Hermite alone) in the run with contact: for the tests of the floor peaks and of
/// the self-check, which takes
/// [`floor_resolution`](accuracy::floor_resolution).
pub fn simulate_with_floor_resolution(
    scenario: &Scenario,
    resolution: Option<f64>,
) -> Result<Report, SolveError> {
    refuse_row(scenario)?;
    no_spectrum(scenario)?;
    let mut report = simulate(scenario)?;
    let system = scenario.system();
    let heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let pairs = vec![0; heights.len()];
    let what = (
        &system,
        &scenario.solver,
        (&heights[..], &pairs[..]),
        scenario.output_interval,
    );
    let (with, _) = run_phase_at(
        what,
        &mut NoSink,
        Phase::WithContact,
        Some(scenario.floor_stations),
        resolution,
    )?;
    for (i, s) in report.structures.iter_mut().enumerate() {
        for (f, p) in s.floors.iter_mut().zip(&with.floors[i]) {
            f.peak_displacement = p.displacement;
            f.peak_drift = p.drift;
            f.peak_shear = p.shear;
            f.peak_acceleration = p.acceleration;
            f.peak_acceleration_time = p.acceleration_time;
            f.peak_shear_with_damping = p.shear_with_damping;
        }
    }
    report.with_contact.floors = with.floors;
    Ok(report)
}

/// Whether the scenario's run without contact is the same at any tolerance, so that the
/// self-check need not run it again: `exact-modal` and `adaptive` propagate every mode exactly
/// and take no step the tolerance decides where nothing touches (the free flight follows the
/// grid of `dt`), unless storeys yield (their hysteresis is integrated to the tolerance). The
/// run at `rtol/100` is then bit-identical (tested), and the check compares the result's own
/// numbers without contact with themselves: a change of exactly 0, which is the truth.
pub fn free_run_is_exact(scenario: &Scenario) -> bool {
    scenario.solver.method.has_tolerance() && !scenario.has_hysteresis()
}

/// [`simulate_checked`] without the responses over the structures' heights
/// (`structures[i].floors` empty): the headline numbers only, at the cost of the integration
/// alone (what a sweep row needs).
pub fn simulate_headline(scenario: &Scenario, check: bool) -> Result<Report, SolveError> {
    simulate_run(scenario, check, &mut NoSink, false)
}

/// The two runs of [`simulate`], streamed to `sink` as the phases of the result or (`check`)
/// of the self-check.
/// `reuse`: the run without contact to take as this one's instead of integrating it again
/// (the self-check of a run whose run without contact does not depend on the tolerance, see
/// [`free_run_is_exact`], or another scenario's with the same [`FreeRunKey`]).
/// `shortcut`: take the run without contact from the run with contact when that never
/// touched ([`free_run_of`]; only where the sink does not stream the result's rows).
fn simulate_phases(
    scenario: &Scenario,
    sink: &mut dyn RunSink,
    check: bool,
    floors: bool,
    reuse: Option<&RunRecord>,
    shortcut: bool,
) -> Result<Report, SolveError> {
    refuse_row(scenario)?;
    no_spectrum(scenario)?;
    let system = scenario.system();
    let (with, stats) = integrate_with(scenario, &system, sink, check, floors)?;
    let without = match reuse {
        Some(r) => r.clone(),
        None => {
            let w = (&with, &stats);
            integrate_without(scenario, &system, sink, check, floors, w, shortcut)?
        }
    };
    Ok(assemble(scenario, &system, with, stats, without))
}

/// The levels' heights (m) of a pair and the pair of each (all 0), as the recorder tracks them.
fn tracked(scenario: &Scenario) -> (Vec<f64>, Vec<usize>) {
    let heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let pairs = vec![0; heights.len()];
    (heights, pairs)
}

/// The run with contact of [`simulate_phases`] (of the result, or with `check` of the
/// self-check) on `scenario`'s `system`, and its solver counters.
fn integrate_with(
    scenario: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    check: bool,
    floors: bool,
) -> Result<(RunRecord, Stats), SolveError> {
    let (heights, pairs) = tracked(scenario);
    let phase = if check {
        Phase::CheckWithContact
    } else {
        Phase::WithContact
    };
    run_phase(
        system,
        &scenario.solver,
        (&heights, &pairs),
        scenario.output_interval,
        sink,
        phase,
        floors.then_some(scenario.floor_stations),
    )
}

/// The run without contact of [`simulate_phases`] after its run with contact `with` (and
/// its counters): integrated, or taken from `with` when that never touched (`shortcut`).
fn integrate_without(
    scenario: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    check: bool,
    floors: bool,
    (with, stats): (&RunRecord, &Stats),
    shortcut: bool,
) -> Result<RunRecord, SolveError> {
    // a run with contact that never touched is the run without contact (bit for bit)
    if shortcut
        && (check || !sink.wants_rows())
        && let Some(r) = free_run_of(scenario, stats, with)
    {
        return Ok(r);
    }
    integrate_free(scenario, system, sink, check, floors)
}

/// The run without contact of [`simulate_phases`], integrated (what [`integrate_without`]
/// does without its shortcut; the self-check's beside its run with contact,
/// `concurrent::check_runs`).
fn integrate_free(
    scenario: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    check: bool,
    floors: bool,
) -> Result<RunRecord, SolveError> {
    let (heights, pairs) = tracked(scenario);
    let phase = if check {
        Phase::CheckWithoutContact
    } else {
        Phase::WithoutContact
    };
    // (the self-check compares the floors with contact of a run that has them: its run
    // without contact skips them)
    let floors = (floors && !check).then_some(scenario.floor_stations);
    let what = (&scenario.solver, (&heights[..], &pairs[..]));
    let free = system.without_contact();
    run_phase(
        &free,
        what.0,
        what.1,
        scenario.output_interval,
        sink,
        phase,
        floors,
    )
    .map(|r| r.0)
}

/// The report of `scenario` (its `system`) from its runs with contact (`with`, its counters
/// `stats`) and without.
fn assemble(
    scenario: &Scenario,
    system: &System,
    with: RunRecord,
    stats: Stats,
    without: RunRecord,
) -> Report {
    let heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let structures = [0, 1].map(|i| {
        structure_report(
            &scenario.structures[i],
            i,
            &system.structures[i],
            (&with, &without),
            &with.impacts,
            &heights,
            [with.peak[i], without.peak[i]],
        )
    });
    let levels: Vec<LevelReport> = system
        .levels
        .iter()
        .enumerate()
        .map(|(k, lv)| level_report(lv, &with.levels[k], &without.levels[k]))
        .collect();
    let contact = contact_report(&levels);
    let mut separation = separations(&system.structures, &without);

    let mut warnings = scenario.warnings.clone();
    // the building codes of `[separation]` and every rule at every level, from the peaks
    // without pounding
    if let Err(e) = crate::analysis::level_checks::complete_run_separation(
        scenario,
        &system.structures,
        &without,
        &mut separation,
    ) {
        warnings.push(format!(
            "separation.codes and separation.levels left out: {e}"
        ));
    }
    let h = scenario.main_height();
    for s in &structures {
        drift_warning(s, h, &mut warnings);
    }
    level_warnings(&levels, &mut warnings);
    run_warnings(scenario, &stats, &with, &without, &mut warnings);
    Report {
        title: scenario.title.clone(),
        structures,
        contact,
        levels,
        separation,
        accuracy: AccuracyCheck::unchecked(),
        energy: with.energy,
        energy_no_contact: without.energy,
        impact_log: with.impacts.clone(),
        stats,
        warnings,
        with_contact: with,
        without_contact: without,
    }
}

/// [`simulate`], and with `check` its self-check: the same scenario run again with the
/// [`tightened`] settings (100× tighter tolerance; `dt/√10` for `rk4`), both runs with and
/// without contact, and the headline numbers compared ([`AccuracyCheck::compare`]). A run
/// whose numbers move by more than 1 % gets `accuracy.converged = false` and a warning naming
/// the setting to tighten; so does a run whose check run fails (the result itself is still
/// returned). Without `check`, exactly [`simulate`].
pub fn simulate_checked(scenario: &Scenario, check: bool) -> Result<Report, SolveError> {
    simulate_streaming(scenario, check, &mut NoSink)
}

/// [`simulate_checked`], streaming the history of both runs and the progress of every run to
/// `sink` as they are computed (the self-check's runs report progress only). This is how a
/// long run is written without holding its history in memory (see
/// `output::writer::RunWriter`).
pub fn simulate_streaming(
    scenario: &Scenario,
    check: bool,
    sink: &mut dyn RunSink,
) -> Result<Report, SolveError> {
    simulate_run(scenario, check, sink, true)
}

fn simulate_run(
    scenario: &Scenario,
    check: bool,
    sink: &mut dyn RunSink,
    floors: bool,
) -> Result<Report, SolveError> {
    simulate_run_reusing(scenario, check, sink, floors, None, true).map(|(r, _)| r)
}

/// [`simulate_checked`] (`floors`) or [`simulate_headline`] (not `floors`), taking the runs
/// without contact from `free` when given — those of another scenario with the same
/// [`FreeRunKey`] (`FreeRunKey::of(scenario, check, floors)`), which a sweep over contact
/// keys caches — and returning them with the report, for the next such scenario. The report
/// is bit-identical to the one computed without `free` (tested).
pub fn simulate_reusing(
    scenario: &Scenario,
    check: bool,
    floors: bool,
    free: Option<&FreeRuns>,
) -> Result<(Report, FreeRuns), SolveError> {
    let (report, check_run) =
        simulate_run_reusing(scenario, check, &mut NoSink, floors, free, true)?;
    let runs = FreeRuns {
        run: report.without_contact.clone(),
        check: check_run,
    };
    Ok((report, runs))
}

/// [`simulate_run`], with the runs without contact from `free`; also the self-check's run
/// without contact when it integrated its own. `shortcut`: see [`simulate_phases`] (false
/// only in the tests that compare both ways).
fn simulate_run_reusing(
    scenario: &Scenario,
    check: bool,
    sink: &mut dyn RunSink,
    floors: bool,
    free: Option<&FreeRuns>,
    shortcut: bool,
) -> Result<(Report, Option<RunRecord>), SolveError> {
    let f = free.map(|f| &f.run);
    let mut report = simulate_phases(scenario, sink, false, floors, f, shortcut)?;
    if !check {
        return Ok((report, None));
    }
    let mut tight = scenario.clone();
    tight.solver = tightened(&scenario.solver);
    // (the run without contact again only where the tolerance changes it)
    let exact = free_run_is_exact(scenario);
    let reuse = if exact {
        Some(&report.without_contact)
    } else {
        free.and_then(|f| f.check.as_ref())
    };
    // a run with contact that never touched read no tolerance: the check run would repeat it
    // bit for bit (and the run without contact is the run's own), so it is compared with
    // itself — every change exactly 0, which is the truth (`shortcut`: see `simulate_phases`)
    let repeats =
        shortcut && exact && reuse::untouched(scenario, &report.stats, &report.with_contact);
    let check = if repeats {
        Ok(None)
    } else {
        simulate_phases(&tight, sink, true, floors, reuse, shortcut).map(Some)
    };
    let check_run = conclude_check(scenario, &mut report, check);
    Ok((report, check_run))
}

/// The self-check's verdict on `report` (of `scenario`) from the `check` report at the
/// tightened settings (`Ok(None)`: the run is its own check, it never touched; `Err`: the
/// check run failed), with its warnings; returns the check's run without contact when it
/// integrated its own (not [`free_run_is_exact`]).
fn conclude_check(
    scenario: &Scenario,
    report: &mut Report,
    check: Result<Option<Report>, SolveError>,
) -> Option<RunRecord> {
    let mut check_run = None;
    report.accuracy = match check {
        Ok(None) => AccuracyCheck::compare(report, report, &scenario.solver),
        Ok(Some(t)) => {
            let a = AccuracyCheck::compare(report, &t, &scenario.solver);
            if !free_run_is_exact(scenario) {
                check_run = Some(t.without_contact);
            }
            a
        }
        Err(e) => AccuracyCheck::failed(&scenario.solver, &e),
    };
    if let Some(w) = report.accuracy.warning(&scenario.solver) {
        report.warnings.push(w);
    }
    // (a check that could not tighten at all says so in its own warning)
    if limited_tightening(&scenario.solver) && report.accuracy.failure.is_none() {
        report.warnings.push(format!(
            "self-check: could not tighten rtol {:e} / atol {:e} m a full 100× (the smallest \
             tolerances are {:e} and {:e} m): its changes understate the error",
            scenario.solver.rtol,
            scenario.solver.atol,
            crate::analysis::simulate::accuracy::MIN_RTOL,
            crate::analysis::simulate::accuracy::MIN_ATOL
        ));
    }
    check_run
}
