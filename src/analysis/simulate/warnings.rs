//! What a run warns of beyond the scenario's own warnings: a drift at which a linear model
//! means little, an implausible penetration, a contact too stiff for `rk4`'s step, an energy
//! balance that does not close.

use super::{LevelReport, StructureReport};
use crate::input::scenario::Scenario;
use crate::integrate::Stats;
use crate::recording::run_record::RunRecord;

/// Energy-balance error above which a run is flagged (relative to the largest energy present).
pub const ENERGY_WARNING_THRESHOLD: f64 = 1e-3;

/// Peak drift (displacement at the contact height over that height) above which a run warns
/// that a linear model no longer means much: 5 %, several times the elastic range of
/// buildings (≈ 0.5–2 %).
pub const PLAUSIBLE_DRIFT: f64 = 0.05;

/// Penetration above which a run warns, m ("a few centimetres"), besides any penetration
/// larger than the gap.
pub const PLAUSIBLE_PENETRATION: f64 = 0.05;

/// A structure whose headline peak (at height `h`, m) is a drift beyond [`PLAUSIBLE_DRIFT`].
pub(super) fn drift_warning(s: &StructureReport, h: f64, warnings: &mut Vec<String>) {
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
pub(super) fn level_warnings(levels: &[LevelReport], warnings: &mut Vec<String>) {
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
pub(super) fn run_warnings(
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
