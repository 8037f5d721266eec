//! `pounding separation` of a pair: the run without contact only and the separation rules
//! from it ([`separation`]), half the work of [`super::simulate`].

use super::{no_spectrum, refuse_row, run_system};
use crate::analysis::level_checks::Separations;
use crate::analysis::separation::PeakPair;
use crate::input::scenario::Scenario;
use crate::integrate::{InitialState, SolveError};
use crate::model::modal::ModalModel;
use crate::recording::run_record::RunRecord;

/// The separation rules (docs/model.md §3) from the run without contact of a pair of
/// structures whose modal models are `models` (the first two).
pub(super) fn separations(models: &[ModalModel], without: &RunRecord) -> Separations {
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

/// What the separation rules need, from the run without contact only (half the work of
/// [`super::simulate`], whose `separation` and no-contact peaks it equals).
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
