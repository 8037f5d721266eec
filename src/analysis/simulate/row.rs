//! A row of buildings (issue 29): N ≥ 2 structures side by side, each adjacent pair with its
//! own contact. [`simulate_row`] runs the whole row with contact once (one [`System`] of every
//! structure and every pair's levels: a middle building is struck from both sides in the same
//! integration) and once without contact (every structure once: without contact the row's
//! equations are uncoupled), then reports per structure (the quantities of a pair's
//! [`StructureReport`]) and per pair ([`PairReport`]: its contact, every level, the required
//! separation by every rule and code at every level of the pair, its verdict), and the row's
//! verdict: the pair and level that govern.
//!
//! The per-structure and per-level numbers are formed by the same functions as a pair's
//! ([`super::simulate`]); each pair's separation checks are a pair's checks on that pair taken
//! as a scenario of its own ([`Scenario::pair`]), fed with the row's run without contact.

use serde::Serialize;

use std::cell::RefCell;
use std::collections::VecDeque;

use super::row_check::RowAccuracyCheck;
use super::row_history::{RowHistory, RowObserver, RowPhaseSink, RowSampler};
use super::{
    ContactReport, LevelReport, NoSink, Phase, RunSink, StructureReport, contact_report,
    free_run_is_exact, level_report, level_warnings, no_spectrum, run_warnings, separations,
    structure_report,
};
use crate::analysis::level_checks::{Governing, Separations, complete_run_separation};
use crate::input::scenario::Scenario;
use crate::integrate::{InitialState, SolveError, SolverSettings, Stats, integrate};
use crate::model::system::System;
use crate::recording::recorder::Recorder;
use crate::recording::run_record::{EnergyBalance, RunRecord};

/// One adjacent pair of a row: structures `index` and `index + 1` (0-based, row order).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairReport {
    /// The left structure's index in the row (0-based); the right one is `index + 1`.
    pub index: usize,
    /// The two structures' names, left then right.
    pub between: [String; 2],
    /// The pair's contact law (`hertz`, …).
    pub law: &'static str,
    /// Totals and maxima over the pair's levels.
    pub contact: ContactReport,
    /// The largest approach speed δ̇ at the start of any of the pair's impacts, m/s (0
    /// without impacts).
    pub peak_approach_speed: f64,
    /// Every level of the pair, in the order of its `[[contact]]` table (`peak_displacement`:
    /// left, right).
    pub levels: Vec<LevelReport>,
    /// The required separation by every rule at the pair's main (highest) level, every rule
    /// and code at each of its levels (`levels`) and its verdict (`verdict`), from the row's
    /// run without contact.
    pub separation: Separations,
}

/// One impact of a row.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RowImpact {
    /// The pair (its left structure's index, 0-based).
    pub pair: usize,
    /// The level within the pair (0-based, in the order of its `[[contact]]` table).
    pub level: usize,
    /// The level's height, m.
    pub height: f64,
    /// Start, s.
    pub start: f64,
    /// End, s.
    pub end: f64,
    /// Peak contact force, N.
    pub peak_force: f64,
    /// Impulse ∫F dt, N·s.
    pub impulse: f64,
    /// Largest penetration, m.
    pub max_penetration: f64,
    /// Approach speed δ̇ at the start, m/s.
    pub approach_speed: f64,
}

/// The row's verdict: of every pair's rules at every level, the one with the smallest margin
/// (gap − required).
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct RowVerdict {
    /// The pair that governs (its left structure's index, 0-based), `None` without rules.
    pub pair: Option<usize>,
    /// Its two structures' names.
    pub between: Option<[String; 2]>,
    /// The rule and level that govern, in that pair.
    pub governing: Option<Governing>,
    /// The pairs (left structure's index) where some rule finds the gap too small somewhere.
    pub insufficient_pairs: Vec<usize>,
    /// The pairs that touched in the run with contact.
    pub pounding_pairs: Vec<usize>,
}

/// Everything a row's run produces (summary.json of a row).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowReport {
    /// Scenario title.
    pub title: String,
    /// Every structure, in row order. `peak_displacement` (and `_no_contact`) is at the
    /// structure's highest contact level (of either neighbour).
    pub structures: Vec<StructureReport>,
    /// Every adjacent pair, in row order.
    pub pairs: Vec<PairReport>,
    /// The row's verdict.
    pub verdict: RowVerdict,
    /// Energy balance of the run with contact (the whole row).
    pub energy: EnergyBalance,
    /// Energy balance of the run without contact.
    pub energy_no_contact: EnergyBalance,
    /// Every impact, in time order.
    pub impact_log: Vec<RowImpact>,
    /// The self-check ([`simulate_row_checked`]): every structure's and every pair's headline
    /// numbers against a 100× tighter rerun; `checked: false` from [`simulate_row`].
    pub accuracy: RowAccuracyCheck,
    /// Solver counters (with contact).
    #[serde(skip)]
    pub stats: Stats,
    /// Things the user should know.
    pub warnings: Vec<String>,
    /// The run with contact (its `levels` are every pair's, pair by pair).
    #[serde(skip)]
    pub with_contact: RunRecord,
    /// The run without contact.
    #[serde(skip)]
    pub without_contact: RunRecord,
    /// The displacement histories of the run with contact: every structure at its headline
    /// height, both structures at every level (empty for the self-check's runs).
    #[serde(skip)]
    pub history: RowHistory,
    /// The same of the run without contact.
    #[serde(skip)]
    pub history_no_contact: RowHistory,
}

/// Run a row (or a pair: the same numbers as [`super::simulate`]'s, arranged per pair) with
/// and without contact. Not self-checked.
pub fn simulate_row(scenario: &Scenario) -> Result<RowReport, SolveError> {
    simulate_row_with(scenario, &mut NoSink)
}

/// [`simulate_row`] streaming to `sink`: every history sample of the two runs
/// ([`RunSink::row_contact_row`], [`RunSink::row_free_row`]: each structure's displacement at
/// its headline height and every level's force), the floor rows, and the progress. Not
/// self-checked.
pub fn simulate_row_with(
    scenario: &Scenario,
    sink: &mut dyn RunSink,
) -> Result<RowReport, SolveError> {
    simulate_row_phases(scenario, sink, false, None)
}

/// [`simulate_row`] and, with `check`, its self-check ([`RowAccuracyCheck`]): the row run again
/// with [`super::accuracy::tightened`] settings and its numbers compared; a row whose numbers
/// move by more than 1 % gets `accuracy.converged = false` and the warning "self-check NOT
/// converged: …", as a pair's ([`super::simulate_checked`]).
pub fn simulate_row_checked(scenario: &Scenario, check: bool) -> Result<RowReport, SolveError> {
    simulate_row_streaming(scenario, check, &mut NoSink)
}

/// [`simulate_row_checked`] streaming the two runs of the result to `sink` (the self-check's
/// runs report progress only); how `pounding run` writes a row
/// (`output::writer::RunWriter`).
pub fn simulate_row_streaming(
    scenario: &Scenario,
    check: bool,
    sink: &mut dyn RunSink,
) -> Result<RowReport, SolveError> {
    simulate_row_run(scenario, check, sink, None).map(|(r, _)| r)
}

/// The runs without contact of one row, to take for another that differs only in its
/// contact (same [`super::FreeRunKey::of_row`]): the result's with its history, and the
/// self-check's when it integrates its own (`None`: it reuses the result's,
/// [`free_run_is_exact`], or no check was run).
#[derive(Debug, Clone, PartialEq)]
pub struct RowFreeRuns {
    /// The run without contact of the result.
    pub run: RunRecord,
    /// Its displacement histories ([`RowReport::history_no_contact`]).
    pub history: RowHistory,
    /// The self-check's run without contact, when it has its own.
    pub check: Option<RunRecord>,
}

impl RowFreeRuns {
    /// Approximate heap size, bytes (what a cache of them bounds).
    pub fn bytes(&self) -> usize {
        let h = &self.history;
        let history = 8
            * (h.t.len()
                + h.structures.iter().map(Vec::len).sum::<usize>()
                + h.levels
                    .iter()
                    .map(|[a, b]| a.len() + b.len())
                    .sum::<usize>());
        super::FreeRuns::record_bytes(&self.run)
            + self.check.as_ref().map_or(0, super::FreeRuns::record_bytes)
            + history
    }
}

/// [`simulate_row_checked`], taking the runs without contact from `free` when given — those
/// of another row with the same [`super::FreeRunKey::of_row`], which a sweep over contact
/// keys caches — and returning them with the report, for the next such row. The report is
/// bit-identical to the one computed without `free` (tested).
pub fn simulate_row_reusing(
    scenario: &Scenario,
    check: bool,
    free: Option<&RowFreeRuns>,
) -> Result<(RowReport, RowFreeRuns), SolveError> {
    let (report, check_run) = simulate_row_run(scenario, check, &mut NoSink, free)?;
    let runs = RowFreeRuns {
        run: report.without_contact.clone(),
        history: report.history_no_contact.clone(),
        check: check_run,
    };
    Ok((report, runs))
}

/// [`simulate_row_streaming`] with the runs without contact from `free` (then not streamed
/// to `sink`); also the self-check's run without contact when it integrated its own.
fn simulate_row_run(
    scenario: &Scenario,
    check: bool,
    sink: &mut dyn RunSink,
    free: Option<&RowFreeRuns>,
) -> Result<(RowReport, Option<RunRecord>), SolveError> {
    let reuse = free.map(|f| (&f.run, &f.history));
    let mut report = simulate_row_phases(scenario, sink, false, reuse)?;
    if !check {
        return Ok((report, None));
    }
    let mut tight = scenario.clone();
    tight.solver = super::accuracy::tightened(&scenario.solver);
    // (the run without contact again only where the tolerance changes it)
    let exact = free_run_is_exact(scenario);
    let none = RowHistory::default();
    let reuse = if exact {
        Some((&report.without_contact, &none))
    } else {
        free.and_then(|f| f.check.as_ref()).map(|r| (r, &none))
    };
    let check = simulate_row_phases(&tight, sink, true, reuse);
    let check_run = conclude_row_check(scenario, &mut report, check);
    Ok((report, check_run))
}

/// The self-check's verdict on a row's `report` (of `scenario`) from the `check` report at
/// the tightened settings (`Err`: the check run failed), with its warnings; returns the
/// check's run without contact when it integrated its own (not [`free_run_is_exact`]).
pub(super) fn conclude_row_check(
    scenario: &Scenario,
    report: &mut RowReport,
    check: Result<RowReport, SolveError>,
) -> Option<RunRecord> {
    let mut check_run = None;
    report.accuracy = match check {
        Ok(t) => {
            let a = RowAccuracyCheck::compare(report, &t, &scenario.solver);
            if !free_run_is_exact(scenario) {
                check_run = Some(t.without_contact);
            }
            a
        }
        Err(e) => RowAccuracyCheck::failed(&scenario.solver, &e),
    };
    if let Some(w) = report.accuracy.warning(&scenario.solver) {
        report.warnings.push(w);
    }
    // (a check that could not tighten at all says so in its own warning)
    if super::accuracy::limited_tightening(&scenario.solver) && report.accuracy.failure.is_none() {
        report.warnings.push(format!(
            "self-check: could not tighten rtol {:e} / atol {:e} m a full 100× (the smallest \
             tolerances are {:e} and {:e} m): its changes understate the error",
            scenario.solver.rtol,
            scenario.solver.atol,
            super::accuracy::MIN_RTOL,
            super::accuracy::MIN_ATOL
        ));
    }
    check_run
}

/// One integration of a row `system` with its recorder and (unless `check`) the row's sampler
/// ([`RowSampler`]), streaming to `sink` as `phase`.
#[allow(clippy::too_many_arguments)]
fn run_row_phase(
    system: &System,
    settings: &SolverSettings,
    (heights, pairs): (&[f64], &[usize]),
    interval: f64,
    sink: &mut dyn RunSink,
    phase: Phase,
    floors: Option<crate::recording::stations::FloorStations>,
    check: bool,
) -> Result<(RunRecord, Stats, RowHistory), SolveError> {
    let pending = RefCell::new(VecDeque::new());
    let sampler = RowSampler::new(
        system,
        (heights, pairs),
        interval,
        settings.duration,
        &pending,
    );
    let width = if check { 0 } else { sampler.width() };
    let mut adapter = RowPhaseSink {
        sink,
        phase,
        pending: &pending,
        width,
        structures: system.structures.len(),
        row: Vec::with_capacity(width),
    };
    let mut rec = Recorder::for_row(system, heights, pairs, interval, settings.duration);
    rec = match floors {
        Some(stations) => rec.with_floor_stations(system, heights, stations),
        None => rec.without_floors(),
    };
    let recorder = rec.with_sink(&mut adapter);
    let initial = InitialState::default();
    if check {
        // (the self-check compares headline numbers only: no sampler)
        let mut recorder = recorder;
        let stats = integrate(system, settings, &initial, &mut recorder)?;
        return Ok((recorder.finish(), stats, RowHistory::default()));
    }
    let mut obs = RowObserver { sampler, recorder };
    let stats = integrate(system, settings, &initial, &mut obs)?;
    let RowObserver { sampler, recorder } = obs;
    Ok((recorder.finish(), stats, sampler.finish()))
}

/// The two runs of a row (with `check`: the self-check's, `reuse` the run without contact and
/// its history to take instead of integrating it again) and its report.
pub(super) fn simulate_row_phases(
    scenario: &Scenario,
    sink: &mut dyn RunSink,
    check: bool,
    reuse: Option<(&RunRecord, &RowHistory)>,
) -> Result<RowReport, SolveError> {
    no_spectrum(scenario)?;
    let system = scenario.system();
    let with = row_with(scenario, &system, sink, check)?;
    let without = match reuse {
        Some((r, h)) => (r.clone(), h.clone()),
        None => row_free(scenario, &system, sink, check)?,
    };
    Ok(assemble_row(scenario, &system, with, without))
}

/// A row's levels: every level's height (m) and its pair (the left structure's index).
fn row_levels(system: &System) -> (Vec<f64>, Vec<usize>) {
    let heights = system.levels.iter().map(|l| l.height).collect();
    let pair_of = system.levels.iter().map(|l| l.pair).collect();
    (heights, pair_of)
}

/// A row's run with contact (with `check`: the self-check's) of `scenario`'s `system`, its
/// counters and (not `check`) its history, streamed to `sink`.
pub(super) fn row_with(
    scenario: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    check: bool,
) -> Result<(RunRecord, Stats, RowHistory), SolveError> {
    let (heights, pair_of) = row_levels(system);
    let phase = if check {
        Phase::CheckWithContact
    } else {
        Phase::WithContact
    };
    // (the self-check's run with contact records the floors too: its check compares them,
    // as a pair's does)
    run_row_phase(
        system,
        &scenario.solver,
        (&heights, &pair_of),
        scenario.output_interval,
        sink,
        phase,
        Some(scenario.floor_stations),
        check,
    )
}

/// A row's run without contact (with `check`: the self-check's, without floors) of
/// `scenario`'s `system` (with contact: its structures are taken), and (not `check`) its
/// history, streamed to `sink`.
pub(super) fn row_free(
    scenario: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    check: bool,
) -> Result<(RunRecord, RowHistory), SolveError> {
    let free = system.without_contact();
    let (heights, pair_of) = row_levels(system);
    let phase = if check {
        Phase::CheckWithoutContact
    } else {
        Phase::WithoutContact
    };
    let (r, _, h) = run_row_phase(
        &free,
        &scenario.solver,
        (&heights, &pair_of),
        scenario.output_interval,
        sink,
        phase,
        (!check).then_some(scenario.floor_stations),
        check,
    )?;
    Ok((r, h))
}

/// The report of a row `scenario` (its `system`) from its run with contact (`with`: the
/// record, its counters, its history) and without (the record, its history).
pub(super) fn assemble_row(
    scenario: &Scenario,
    system: &System,
    (with, stats, history): (RunRecord, Stats, RowHistory),
    (without, history_no_contact): (RunRecord, RowHistory),
) -> RowReport {
    let (heights, pair_of) = row_levels(system);
    let n = system.structures.len();
    // each structure's headline level: its highest contact level with either neighbour
    let structures: Vec<StructureReport> = (0..n)
        .map(|i| {
            let mine = |k: &usize| pair_of[*k] == i || pair_of[*k] + 1 == i;
            let main = (0..heights.len())
                .filter(mine)
                .fold(None, |best: Option<usize>, k| match best {
                    Some(b) if heights[k] <= heights[b] => Some(b),
                    _ => Some(k),
                });
            let peak = |r: &RunRecord| {
                main.map_or(0.0, |k| {
                    if pair_of[k] == i {
                        r.levels[k].peak_w1
                    } else {
                        r.levels[k].peak_w2
                    }
                })
            };
            let impacts: Vec<_> = (with.impacts.iter())
                .filter(|x| mine(&x.level))
                .copied()
                .collect();
            structure_report(
                &scenario.structures[i],
                i,
                &system.structures[i],
                (&with, &without),
                &impacts,
                &heights,
                [peak(&with), peak(&without)],
            )
        })
        .collect();
    let mut warnings = scenario.warnings.clone();
    let mut pairs = Vec::with_capacity(n - 1);
    let mut first = 0;
    for p in 0..n - 1 {
        let count = pair_of.iter().filter(|&&q| q == p).count();
        let range = first..first + count;
        first += count;
        let levels: Vec<LevelReport> = range
            .clone()
            .map(|k| level_report(&system.levels[k], &with.levels[k], &without.levels[k]))
            .collect();
        // the pair as a scenario of its own, with the row's run without contact at its levels
        let pair_scenario = scenario.pair(p);
        let models = [
            system.structures[p].clone(),
            system.structures[p + 1].clone(),
        ];
        let record = pair_record(&without, range.clone());
        let mut separation = separations(&models, &record);
        if let Err(e) = complete_run_separation(&pair_scenario, &models, &record, &mut separation) {
            warnings.push(format!(
                "pair \"{}\"–\"{}\": separation.codes and separation.levels left out: {e}",
                scenario.structures[p].name(),
                scenario.structures[p + 1].name()
            ));
        }
        let peak_approach_speed = (with.impacts.iter())
            .filter(|x| range.contains(&x.level))
            .map(|x| x.approach_speed)
            .fold(0.0, f64::max);
        pairs.push(PairReport {
            index: p,
            between: [p, p + 1].map(|i| scenario.structures[i].name().to_string()),
            law: pair_scenario.contact.law.name(),
            contact: contact_report(&levels),
            peak_approach_speed,
            levels,
            separation,
        });
    }
    for (s, i) in structures.iter().zip(0..) {
        let h = (0..heights.len())
            .filter(|&k| pair_of[k] == i || pair_of[k] + 1 == i)
            .map(|k| heights[k])
            .fold(0.0, f64::max);
        super::drift_warning(s, h, &mut warnings);
    }
    for p in &pairs {
        level_warnings(&p.levels, &mut warnings);
    }
    run_warnings(scenario, &stats, &with, &without, &mut warnings);
    let impact_log = with
        .impacts
        .iter()
        .map(|x| {
            let p = pair_of[x.level];
            let first = pair_of.iter().position(|&q| q == p).unwrap_or(0);
            RowImpact {
                pair: p,
                level: x.level - first,
                height: heights[x.level],
                start: x.start,
                end: x.end,
                peak_force: x.peak_force,
                impulse: x.impulse,
                max_penetration: x.max_penetration,
                approach_speed: x.approach_speed,
            }
        })
        .collect();
    RowReport {
        title: scenario.title.clone(),
        verdict: row_verdict(&pairs),
        structures,
        pairs,
        energy: with.energy,
        energy_no_contact: without.energy,
        impact_log,
        accuracy: RowAccuracyCheck::unchecked(),
        stats,
        warnings,
        with_contact: with,
        without_contact: without,
        history,
        history_no_contact,
    }
}

/// The run without contact at the levels `range` of one pair, as a pair's run record: those
/// levels, and the peaks at the highest of them (the first on a tie, as the recorder picks
/// its main level).
fn pair_record(without: &RunRecord, range: std::ops::Range<usize>) -> RunRecord {
    let levels = without.levels[range].to_vec();
    let main = (0..levels.len()).fold(0, |best, k| {
        if levels[k].height > levels[best].height {
            k
        } else {
            best
        }
    });
    let (peak, max_closing) = levels
        .get(main)
        .map_or(([0.0; 2], 0.0), |m| ([m.peak_w1, m.peak_w2], m.max_closing));
    RunRecord {
        levels,
        peak,
        max_closing,
        impacts: Vec::new(),
        history: Default::default(),
        energy: without.energy,
        steps: without.steps,
        floors: Vec::new(),
        storeys: Vec::new(),
    }
}

/// The row's verdict from every pair's.
fn row_verdict(pairs: &[PairReport]) -> RowVerdict {
    let mut v = RowVerdict::default();
    for p in pairs {
        if p.separation.verdict.insufficient > 0 {
            v.insufficient_pairs.push(p.index);
        }
        if p.contact.impacts > 0 {
            v.pounding_pairs.push(p.index);
        }
        if let Some(g) = &p.separation.verdict.governing
            && v.governing.as_ref().is_none_or(|m| g.margin < m.margin)
        {
            v.governing = Some(g.clone());
            v.pair = Some(p.index);
            v.between = Some(p.between.clone());
        }
    }
    v
}
