//! One scenario, end to end: the run with contact, the same run without, the comparison and the
//! required separations — `simulate(&Scenario) -> Report` — and the same with its self-check,
//! `simulate_checked(&Scenario, true)` (see [`crate::accuracy`]).

use serde::Serialize;

use crate::accuracy::{AccuracyCheck, limited_tightening, tightened};
use crate::integrate::{InitialState, SolveError, SolverSettings, Stats, integrate};
use crate::recorder::{EnergyBalance, Impact, Recorder, RunRecord};
use crate::scenario::Scenario;
use crate::separation::{PeakPair, Separations};
use crate::system::System;

/// Energy-balance error above which a run is flagged (relative to the largest energy present).
pub const ENERGY_WARNING_THRESHOLD: f64 = 1e-3;

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

fn change_percent(with: f64, without: f64) -> f64 {
    if without > 0.0 {
        100.0 * (with - without) / without
    } else {
        0.0
    }
}

/// The separation rules (docs/model.md §3) from the run without contact.
fn separations(system: &System, without: &RunRecord) -> Separations {
    let [m1, m2] = &system.structures;
    let peaks = PeakPair {
        w1: without.peak[0],
        w2: without.peak[1],
        zeta1: m1.zeta[0],
        zeta2: m2.zeta[0],
        period_ratio: m2.omega[0] / m1.omega[0],
    };
    Separations::new(&peaks, without.max_closing)
}

/// What the separation rules need, from the run without contact only (half the work of
/// [`simulate`], whose `separation` and no-contact peaks it equals).
#[derive(Debug, Clone, PartialEq)]
pub struct SeparationReport {
    /// Peak |w₁|, |w₂| without contact at the main contact height, m.
    pub peaks_no_contact: [f64; 2],
    /// First-mode periods of structures 1 and 2, s.
    pub periods: [f64; 2],
    /// First-mode damping ratios of structures 1 and 2.
    pub damping_ratios: [f64; 2],
    /// The required gap by every rule.
    pub separation: Separations,
}

/// Run a scenario without contact and evaluate the separation rules (`pounding separation`).
pub fn separation(scenario: &Scenario) -> Result<SeparationReport, SolveError> {
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
    let [m1, m2] = &system.structures;
    Ok(SeparationReport {
        peaks_no_contact: without.peak,
        periods: [m1.periods()[0], m2.periods()[0]],
        damping_ratios: [m1.zeta[0], m2.zeta[0]],
        separation: separations(&system, &without),
    })
}

/// Run a scenario with and without contact and compare. The result is not self-checked
/// (`accuracy.checked` is false); [`simulate_checked`] checks it.
pub fn simulate(scenario: &Scenario) -> Result<Report, SolveError> {
    let system = scenario.system();
    let free = system.without_contact();
    let heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let init = InitialState::default();
    let (with, stats) = run_system(
        &system,
        &scenario.solver,
        &init,
        &heights,
        scenario.output_interval,
    )?;
    let (without, _) = run_system(
        &free,
        &scenario.solver,
        &init,
        &heights,
        scenario.output_interval,
    )?;

    let structures = [0, 1].map(|i| {
        let s = &scenario.structures[i];
        let m = &system.structures[i];
        StructureReport {
            name: s.name.clone(),
            periods: m.periods(),
            damping_ratios: m.zeta.clone(),
            peak_displacement: with.peak[i],
            peak_displacement_no_contact: without.peak[i],
            change_percent: change_percent(with.peak[i], without.peak[i]),
        }
    });
    let levels: Vec<LevelReport> = system
        .levels
        .iter()
        .enumerate()
        .map(|(k, lv)| {
            let (a, b) = (&with.levels[k], &without.levels[k]);
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
        })
        .collect();
    let contact = ContactReport {
        peak_force: levels.iter().map(|l| l.peak_force).fold(0.0, f64::max),
        max_penetration: levels.iter().map(|l| l.max_penetration).fold(0.0, f64::max),
        impacts: levels.iter().map(|l| l.impacts).sum(),
        contact_time: levels.iter().map(|l| l.contact_time).sum(),
    };
    let separation = separations(&system, &without);

    let mut warnings = Vec::new();
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

/// [`simulate`], and with `check` its self-check: the same scenario run again with the
/// [`tightened`] settings (100× tighter tolerance; `dt/√10` for `rk4`), both runs with and
/// without contact, and the headline numbers compared ([`AccuracyCheck::compare`]). A run
/// whose numbers move by more than 1 % gets `accuracy.converged = false` and a warning naming
/// the setting to tighten; so does a run whose check run fails (the result itself is still
/// returned). Without `check`, exactly [`simulate`].
pub fn simulate_checked(scenario: &Scenario, check: bool) -> Result<Report, SolveError> {
    let mut report = simulate(scenario)?;
    if !check {
        return Ok(report);
    }
    let mut tight = scenario.clone();
    tight.solver = tightened(&scenario.solver);
    report.accuracy = match simulate(&tight) {
        Ok(t) => AccuracyCheck::compare(&report, &t, &scenario.solver),
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
            crate::accuracy::MIN_RTOL,
            crate::accuracy::MIN_ATOL
        ));
    }
    Ok(report)
}
