//! One scenario, end to end: the run with contact, the same run without, the comparison and the
//! required separations — `simulate(&Scenario) -> Report` — and the same with its self-check,
//! `simulate_checked(&Scenario, true)` (see [`accuracy`]).

pub mod accuracy;
mod reuse;
#[cfg(test)]
mod reuse_tests;
mod row;
pub mod row_check;
pub mod row_history;
mod sink;

pub use reuse::{FreeRunKey, FreeRuns, free_run_of};
use sink::PhaseSink;
pub use sink::{NoSink, Phase, RunCapture, RunSink};

pub use row::{
    PairReport, RowImpact, RowReport, RowVerdict, simulate_row, simulate_row_checked,
    simulate_row_streaming, simulate_row_with,
};

use serde::Serialize;

use self::accuracy::{AccuracyCheck, limited_tightening, tightened};
use crate::analysis::level_checks::Separations;
use crate::analysis::separation::PeakPair;
use crate::input::scenario::Scenario;
use crate::integrate::{InitialState, SolveError, SolverSettings, Stats, integrate};
use crate::model::modal::ModalModel;
use crate::model::structure::Structure;
use crate::model::system::{Level, System};
use crate::recording::floor_response::FloorPeaks;
use crate::recording::recorder::Recorder;
use crate::recording::run_record::{EnergyBalance, Impact, LevelRecord, RunRecord};
use crate::recording::storey_record::StoreyRecord;

/// Energy-balance error above which a run is flagged (relative to the largest energy present).
pub const ENERGY_WARNING_THRESHOLD: f64 = 1e-3;

/// Peak drift (displacement at the contact height over that height) above which a run warns
/// that a linear model no longer means much: 5 %, several times the elastic range of
/// buildings (≈ 0.5–2 %).
pub const PLAUSIBLE_DRIFT: f64 = 0.05;

/// Penetration above which a run warns, m ("a few centimetres"), besides any penetration
/// larger than the gap.
pub const PLAUSIBLE_PENETRATION: f64 = 0.05;

/// Per-structure results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StructureReport {
    /// Name.
    pub name: String,
    /// Periods of the modes kept, s.
    pub periods: Vec<f64>,
    /// Damping ratios of the modes kept.
    pub damping_ratios: Vec<f64>,
    /// Peak |w(h)| with pounding at the main contact height, m.
    pub peak_displacement: f64,
    /// Peak |w(h)| without pounding, m.
    pub peak_displacement_no_contact: f64,
    /// 100·(with − without)/without, %.
    pub change_percent: f64,
    /// Peaks at every floor (a cantilever: every tenth of its height and each contact
    /// height), lowest first, with and without pounding (see [`crate::recording::floor_response`]).
    pub floors: Vec<FloorReport>,
    /// A yielding building only (issue 16): the largest peak ductility demand over its storeys
    /// with pounding, and without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_ductility: Option<f64>,
    /// See `peak_ductility`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_ductility_no_contact: Option<f64>,
    /// A yielding building only: the largest |residual drift| over its storeys, m, with
    /// pounding, and without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_residual_drift: Option<f64>,
    /// See `max_residual_drift`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_residual_drift_no_contact: Option<f64>,
    /// A yielding building only: the energy its storeys dissipate by hysteresis, J, with
    /// pounding, and without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_energy: Option<f64>,
    /// See `hysteretic_energy`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_energy_no_contact: Option<f64>,
    /// A yielding building only: its smallest yield drift, m (the scale of the self-check's
    /// change in residual drift; not written).
    #[serde(skip)]
    pub min_yield_drift: Option<f64>,
}

impl StructureReport {
    /// The peak storey drift ratio of every floor (station), with and without pounding, %:
    /// `100 · peak_drift / (h_j − h_{j−1})`, the storey's drift over its height (the first
    /// storey's over its height above the base) — the drift ratio engineers read (elastic
    /// buildings ≈ 0.5–2 %).
    pub fn peak_drift_ratios(&self) -> Vec<[f64; 2]> {
        let mut below = 0.0;
        self.floors
            .iter()
            .map(|f| {
                let storey = f.height - below;
                below = f.height;
                [f.peak_drift, f.peak_drift_no_contact].map(|d| 100.0 * d / storey)
            })
            .collect()
    }
}

/// Peaks at one floor (station), with and without pounding.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FloorReport {
    /// Height above the base, m.
    pub height: f64,
    /// Peak |w| (displacement) relative to the ground with pounding, m.
    pub peak_displacement: f64,
    /// The same without pounding, m.
    pub peak_displacement_no_contact: f64,
    /// Peak absolute acceleration |ü + a_g| with pounding, m/s².
    pub peak_acceleration: f64,
    /// The same without pounding, m/s².
    pub peak_acceleration_no_contact: f64,
    /// When the peak absolute acceleration with pounding occurred, s.
    pub peak_acceleration_time: f64,
    /// The impact during which it occurred (`None`, not written: at no impact). During an
    /// impact the peak is the impact's pulse — as short as the contact, set by the contact
    /// stiffness — not a floor acceleration to design contents or equipment for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_acceleration_impact: Option<ImpactPulse>,
    /// Peak inter-storey drift of the storey below with pounding (the first relative to the
    /// base), m.
    pub peak_drift: f64,
    /// The same without pounding, m.
    pub peak_drift_no_contact: f64,
    /// Peak storey shear of the storey below with pounding: the force its structure carries
    /// (k·drift, a yielding storey's Bouc–Wen force V, the modes' K u, a cantilever's −EI w‴;
    /// no damping forces; docs/model.md §2.6c), N.
    pub peak_shear: f64,
    /// The same without pounding, N.
    pub peak_shear_no_contact: f64,
    /// Peak shear of the storey below from the equilibrium of everything above (inertia and
    /// contact forces): the storey force plus the damping forces above, with pounding, N.
    pub peak_shear_with_damping: f64,
    /// The same without pounding, N.
    pub peak_shear_with_damping_no_contact: f64,
    /// Yielding storeys only (issue 16): peak |drift| / d_y of the storey below, with pounding.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_ductility: Option<f64>,
    /// The same without pounding.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_ductility_no_contact: Option<f64>,
    /// Yielding storeys only: signed drift of the storey below at the end of the run, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_drift: Option<f64>,
    /// The same without pounding, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_drift_no_contact: Option<f64>,
    /// Yielding storeys only: energy dissipated by the storey's hysteresis, J.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_energy: Option<f64>,
    /// The same without pounding, J.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_energy_no_contact: Option<f64>,
    /// Yielding storeys only: the storey's yield drift d_y, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yield_drift: Option<f64>,
}

impl FloorReport {
    /// A yielding storey: the storey force, ductility, residual drift and hysteretic energy
    /// from its records with (`a`) and without (`b`) pounding.
    fn yielding(&mut self, a: &StoreyRecord, b: &StoreyRecord) {
        self.peak_shear = a.peak_force;
        self.peak_shear_no_contact = b.peak_force;
        self.peak_drift = a.peak_drift;
        self.peak_drift_no_contact = b.peak_drift;
        self.peak_ductility = Some(a.peak_ductility());
        self.peak_ductility_no_contact = Some(b.peak_ductility());
        self.residual_drift = Some(a.residual_drift);
        self.residual_drift_no_contact = Some(b.residual_drift);
        self.hysteretic_energy = Some(a.hysteretic_energy);
        self.hysteretic_energy_no_contact = Some(b.hysteretic_energy);
        self.yield_drift = Some(a.yield_drift);
    }

    fn pair(a: &FloorPeaks, b: &FloorPeaks) -> FloorReport {
        FloorReport {
            height: a.height,
            peak_displacement: a.displacement,
            peak_displacement_no_contact: b.displacement,
            peak_acceleration: a.acceleration,
            peak_acceleration_no_contact: b.acceleration,
            peak_acceleration_time: a.acceleration_time,
            peak_acceleration_impact: None,
            peak_drift: a.drift,
            peak_drift_no_contact: b.drift,
            peak_shear: a.shear,
            peak_shear_no_contact: b.shear,
            peak_shear_with_damping: a.shear_with_damping,
            peak_shear_with_damping_no_contact: b.shear_with_damping,
            peak_ductility: None,
            peak_ductility_no_contact: None,
            residual_drift: None,
            residual_drift_no_contact: None,
            hysteretic_energy: None,
            hysteretic_energy_no_contact: None,
            yield_drift: None,
        }
    }
}

/// The impact during which a floor's peak absolute acceleration occurred: the acceleration is
/// then the impact's pulse, lasting about the contact's duration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ImpactPulse {
    /// Contact level index (0-based, as in `impact_log`).
    pub level: usize,
    /// The level's height, m.
    pub height: f64,
    /// Start and end of the contact, s.
    pub start: f64,
    /// See `start`.
    pub end: f64,
    /// `end − start`, s: how long the pulse lasts.
    pub duration: f64,
    /// The impact's peak contact force, N.
    pub peak_force: f64,
}

/// The impact in progress at time `t` (start ≤ t ≤ end), the one of largest peak force when
/// impacts at several levels overlap; `heights[k]` is level k's height.
pub fn impact_at(impacts: &[Impact], heights: &[f64], t: f64) -> Option<ImpactPulse> {
    impacts
        .iter()
        .filter(|i| i.start <= t && t <= i.end)
        .max_by(|a, b| a.peak_force.total_cmp(&b.peak_force))
        .map(|i| ImpactPulse {
            level: i.level,
            height: heights.get(i.level).copied().unwrap_or(f64::NAN),
            start: i.start,
            end: i.end,
            duration: i.end - i.start,
            peak_force: i.peak_force,
        })
}

/// Contact results, totals and maxima over the levels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactReport {
    /// Largest contact force at any level, N.
    pub peak_force: f64,
    /// Largest penetration at any level, m.
    pub max_penetration: f64,
    /// Number of contact episodes over all levels.
    pub impacts: usize,
    /// Total time in contact over all levels, s.
    pub contact_time: f64,
}

/// Per-level results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelReport {
    /// Height, m.
    pub height: f64,
    /// Gap, m.
    pub gap: f64,
    /// Effective mass at the contact point, kg.
    pub effective_mass: f64,
    /// Peak force, N.
    pub peak_force: f64,
    /// Largest penetration, m.
    pub max_penetration: f64,
    /// Contact episodes.
    pub impacts: usize,
    /// Time in contact, s.
    pub contact_time: f64,
    /// Peak |w₁| and |w₂| at this height with pounding, m.
    pub peak_displacement: [f64; 2],
    /// Peak |w₁| and |w₂| at this height without pounding, m.
    pub peak_displacement_no_contact: [f64; 2],
    /// `max_t [w₁ − w₂]` at this height without pounding: the gap needed here, m.
    pub required_gap: f64,
}

/// Everything a run produces.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Scenario title.
    pub title: String,
    /// Structure 1 and 2.
    pub structures: [StructureReport; 2],
    /// Contact totals.
    pub contact: ContactReport,
    /// Per level.
    pub levels: Vec<LevelReport>,
    /// Required separations at the main contact height.
    pub separation: Separations,
    /// The self-check: the headline numbers against a run at a 100× tighter tolerance
    /// ([`simulate_checked`]); `checked: false` from [`simulate`].
    pub accuracy: AccuracyCheck,
    /// Energy balance of the run with contact.
    pub energy: EnergyBalance,
    /// Energy balance of the run without contact.
    pub energy_no_contact: EnergyBalance,
    /// Every impact.
    pub impact_log: Vec<Impact>,
    /// Solver counters (with contact).
    #[serde(skip)]
    pub stats: Stats,
    /// Things the user should know (inaccurate contact resolution, energy drift).
    pub warnings: Vec<String>,
    /// The run with contact (history, impacts).
    #[serde(skip)]
    pub with_contact: RunRecord,
    /// The run without contact.
    #[serde(skip)]
    pub without_contact: RunRecord,
}

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
    let mut adapter = PhaseSink { sink, phase };
    let mut rec = Recorder::for_row(system, heights, pairs, interval, settings.duration);
    rec = match floors {
        Some(stations) => rec.with_floor_stations(system, heights, stations),
        None => rec.without_floors(),
    };
    let mut rec = rec.with_sink(&mut adapter);
    let stats = integrate(system, settings, &InitialState::default(), &mut rec)?;
    Ok((rec.finish(), stats))
}

fn change_percent(with: f64, without: f64) -> f64 {
    if without > 0.0 {
        100.0 * (with - without) / without
    } else {
        0.0
    }
}

/// The separation rules (docs/model.md §3) from the run without contact of a pair of
/// structures whose modal models are `models` (the first two).
fn separations(models: &[ModalModel], without: &RunRecord) -> Separations {
    let (m1, m2) = (&models[0], &models[1]);
    let peaks = PeakPair {
        w1: without.peak[0],
        w2: without.peak[1],
        zeta1: m1.zeta[0],
        zeta2: m2.zeta[0],
        period_ratio: m2.omega[0] / m1.omega[0],
    };
    Separations::new(&peaks, without.max_closing)
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

/// What the separation rules need, from the run without contact only (half the work of
/// [`simulate`], whose `separation` and no-contact peaks it equals).
#[derive(Debug, Clone, PartialEq)]
pub struct SeparationReport {
    /// Peak |w₁|, |w₂| without contact at the main contact height, m.
    pub peaks_no_contact: [f64; 2],
    /// Every contact level of the run without contact (peaks, `max_closing`), in the order of
    /// the scenario's levels.
    pub levels: Vec<crate::recording::run_record::LevelRecord>,
    /// First-mode periods of structures 1 and 2, s.
    pub periods: [f64; 2],
    /// First-mode damping ratios of structures 1 and 2.
    pub damping_ratios: [f64; 2],
    /// The required gap by every rule.
    pub separation: Separations,
}

/// Run a scenario without contact and evaluate the separation rules (`pounding separation`).
pub fn separation(scenario: &Scenario) -> Result<SeparationReport, SolveError> {
    refuse_row(scenario)?;
    no_spectrum(scenario)?;
    let system = scenario.system();
    let free = system.without_contact();
    let heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let (without, _) = run_system(
        &free,
        &scenario.solver,
        &InitialState::default(),
        &heights,
        scenario.output_interval,
    )?;
    let (m1, m2) = (&system.structures[0], &system.structures[1]);
    let mut separation = separations(&system.structures, &without);
    // as in `simulate`; a code that refuses its input is reported by `gap_report`, which
    // evaluates the codes again
    let _ = crate::analysis::level_checks::complete_run_separation(
        scenario,
        &system.structures,
        &without,
        &mut separation,
    );
    Ok(SeparationReport {
        peaks_no_contact: without.peak,
        levels: without.levels.clone(),
        periods: [m1.periods()[0], m2.periods()[0]],
        damping_ratios: [m1.zeta[0], m2.zeta[0]],
        separation,
    })
}

/// Run a scenario with and without contact and compare. The result is not self-checked
/// (`accuracy.checked` is false); [`simulate_checked`] checks it.
pub fn simulate(scenario: &Scenario) -> Result<Report, SolveError> {
    simulate_phases(scenario, &mut NoSink, false, true, None, true)
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
    let free = system.without_contact();
    let heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let pairs = vec![0; heights.len()];
    let (p1, p2) = if check {
        (Phase::CheckWithContact, Phase::CheckWithoutContact)
    } else {
        (Phase::WithContact, Phase::WithoutContact)
    };
    let interval = scenario.output_interval;
    // (the self-check compares headline numbers only: its runs skip the floors)
    let floors = (floors && !check).then_some(scenario.floor_stations);
    let (with, stats) = run_phase(
        &system,
        &scenario.solver,
        (&heights, &pairs),
        interval,
        sink,
        p1,
        floors,
    )?;
    // a run with contact that never touched is the run without contact (bit for bit)
    let derived = (shortcut && reuse.is_none() && (check || !sink.wants_rows()))
        .then(|| free_run_of(scenario, &stats, &with))
        .flatten();
    let without = match (reuse, derived) {
        (Some(r), _) => r.clone(),
        (None, Some(r)) => r,
        (None, None) => {
            run_phase(
                &free,
                &scenario.solver,
                (&heights, &pairs),
                interval,
                sink,
                p2,
                floors,
            )?
            .0
        }
    };

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
    Ok(Report {
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
    })
}

/// Structure `i`'s report (`structure`, its modal model `model`) from the runs (with,
/// without) contact; `impacts` those that load it (for the floor accelerations' pulses),
/// `heights` every tracked level's height, `peak` its headline peak |w| with and without
/// contact, m.
fn structure_report(
    structure: &Structure,
    i: usize,
    model: &ModalModel,
    (with, without): (&RunRecord, &RunRecord),
    impacts: &[Impact],
    heights: &[f64],
    peak: [f64; 2],
) -> StructureReport {
    let (s, m) = (structure, model);
    let mut floors: Vec<FloorReport> = with.floors[i]
        .iter()
        .zip(&without.floors[i])
        .map(|(a, b)| FloorReport::pair(a, b))
        .collect();
    for f in &mut floors {
        f.peak_acceleration_impact = impact_at(impacts, heights, f.peak_acceleration_time);
    }
    let mine = |r: &RunRecord| -> Vec<StoreyRecord> {
        r.storeys
            .iter()
            .filter(|x| x.structure == i)
            .cloned()
            .collect()
    };
    let (ya, yb) = (mine(with), mine(without));
    for (a, b) in ya.iter().zip(&yb) {
        if let Some(f) = floors.get_mut(a.storey) {
            f.yielding(a, b);
        }
    }
    let yielding = !ya.is_empty();
    let over = |v: &[StoreyRecord], f: fn(&StoreyRecord) -> f64, sum: bool| {
        yielding.then(|| {
            if sum {
                v.iter().map(f).sum()
            } else {
                v.iter().map(f).fold(0.0, f64::max)
            }
        })
    };
    StructureReport {
        peak_ductility: over(&ya, StoreyRecord::peak_ductility, false),
        peak_ductility_no_contact: over(&yb, StoreyRecord::peak_ductility, false),
        max_residual_drift: over(&ya, |r| r.residual_drift.abs(), false),
        max_residual_drift_no_contact: over(&yb, |r| r.residual_drift.abs(), false),
        hysteretic_energy: over(&ya, |r| r.hysteretic_energy, true),
        hysteretic_energy_no_contact: over(&yb, |r| r.hysteretic_energy, true),
        min_yield_drift: yielding.then(|| {
            ya.iter()
                .map(|r| r.yield_drift)
                .fold(f64::INFINITY, f64::min)
        }),
        name: s.name().to_string(),
        periods: m.periods(),
        damping_ratios: m.zeta.clone(),
        peak_displacement: peak[0],
        peak_displacement_no_contact: peak[1],
        change_percent: change_percent(peak[0], peak[1]),
        floors,
    }
}

/// A contact level's report from its records with (`a`) and without (`b`) contact.
fn level_report(lv: &Level, a: &LevelRecord, b: &LevelRecord) -> LevelReport {
    LevelReport {
        height: lv.height,
        gap: lv.gap,
        effective_mass: lv.effective_mass,
        peak_force: a.peak_force,
        max_penetration: a.max_penetration,
        impacts: a.impacts,
        contact_time: a.contact_time,
        peak_displacement: [a.peak_w1, a.peak_w2],
        peak_displacement_no_contact: [b.peak_w1, b.peak_w2],
        required_gap: b.max_closing.max(0.0),
    }
}

/// Totals and maxima over `levels`.
fn contact_report(levels: &[LevelReport]) -> ContactReport {
    ContactReport {
        peak_force: levels.iter().map(|l| l.peak_force).fold(0.0, f64::max),
        max_penetration: levels.iter().map(|l| l.max_penetration).fold(0.0, f64::max),
        impacts: levels.iter().map(|l| l.impacts).sum(),
        contact_time: levels.iter().map(|l| l.contact_time).sum(),
    }
}

/// A structure whose headline peak (at height `h`, m) is a drift beyond [`PLAUSIBLE_DRIFT`].
fn drift_warning(s: &StructureReport, h: f64, warnings: &mut Vec<String>) {
    let peak = s.peak_displacement.max(s.peak_displacement_no_contact);
    if peak > PLAUSIBLE_DRIFT * h {
        warnings.push(format!(
            "{}: peak displacement {peak:.3} m at h = {h} m is a drift of {:.1} %, beyond {} %: \
             a building would long have yielded (elastic drifts are ≈ 0.5–2 %), so a linear \
             elastic model means little here; check the PGA and the stiffness",
            s.name,
            100.0 * peak / h,
            100.0 * PLAUSIBLE_DRIFT
        ));
    }
}

/// Levels whose penetration is implausible.
fn level_warnings(levels: &[LevelReport], warnings: &mut Vec<String>) {
    for l in levels {
        let p = l.max_penetration;
        if p > PLAUSIBLE_PENETRATION || (l.gap > 0.0 && p > l.gap) {
            let what = if l.gap > 0.0 && p > l.gap {
                format!("larger than the gap ({:.1} mm)", l.gap * 1e3)
            } else {
                format!("more than {:.0} cm", PLAUSIBLE_PENETRATION * 1e2)
            };
            warnings.push(format!(
                "contact at h = {} m: the structures overlap by up to {:.1} mm, {what}: the \
                 contact stiffness is too low for a contact between buildings (a real collision \
                 crushes millimetres); check `contact.stiffness`",
                l.height,
                p * 1e3
            ));
        }
    }
}

/// The step's and the energy balance's warnings of a run.
fn run_warnings(
    scenario: &Scenario,
    stats: &Stats,
    with: &RunRecord,
    without: &RunRecord,
    warnings: &mut Vec<String>,
) {
    if scenario.solver.method == crate::integrate::Method::Rk4 && stats.max_contact_omega_dt > 0.5 {
        warnings.push(format!(
            "the contact is stiff for this step: ω_c·dt reached {:.2} (accurate below ≈0.5, unstable above ≈2.8); \
             peak forces may be inaccurate — reduce solver.dt",
            stats.max_contact_omega_dt
        ));
    }
    for (label, e) in [("with", &with.energy), ("without", &without.energy)] {
        if e.relative_error > ENERGY_WARNING_THRESHOLD {
            warnings.push(format!(
                "energy balance of the run {label} contact is off by {:.2e} (relative): the step is too large for an accurate answer",
                e.relative_error
            ));
        }
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
/// [`crate::output::run::RunWriter`]).
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
    let mut check_run = None;
    report.accuracy = match simulate_phases(&tight, sink, true, false, reuse, shortcut) {
        Ok(t) => {
            let a = AccuracyCheck::compare(&report, &t, &scenario.solver);
            if !exact {
                check_run = Some(t.without_contact);
            }
            a
        }
        Err(e) => AccuracyCheck::failed(&scenario.solver, &e),
    };
    if let Some(w) = report.accuracy.warning(&scenario.solver) {
        report.warnings.push(w);
    }
    if limited_tightening(&scenario.solver) {
        report.warnings.push(format!(
            "self-check: could not tighten rtol {:e} / atol {:e} m a full 100× (the smallest \
             tolerances are {:e} and {:e} m): its changes understate the error",
            scenario.solver.rtol,
            scenario.solver.atol,
            crate::analysis::simulate::accuracy::MIN_RTOL,
            crate::analysis::simulate::accuracy::MIN_ATOL
        ));
    }
    Ok((report, check_run))
}
