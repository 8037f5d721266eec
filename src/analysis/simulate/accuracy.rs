//! Every run checks itself (issue 9, item 4): the headline numbers of a run compared with a
//! second run of the same scenario at a 100× tighter tolerance ([`tightened`]).
//!
//! The check is a second, independent [`simulate`](crate::analysis::simulate::simulate) call with the
//! settings of [`tightened`]; it adds nothing to the integrators or to their time loop. Where
//! the run without contact does not depend on the tolerance (`exact-modal` and `adaptive` on
//! elastic structures: exact propagation on the grid of `dt`,
//! [`free_run_is_exact`](crate::analysis::simulate::free_run_is_exact)) the check takes the run's own
//! instead of integrating it again: it would be bit-identical. It
//! compares the peak displacements with and without pounding of each structure (at the main
//! contact height), the peak contact force, the number of impacts and the time-history
//! required separation ([`QUANTITIES`]). Each change is relative, `|a − b|/|b|` with `b` the
//! tight run's value (0 when both are 0, 1 when only `b` is 0); for the number of impacts
//! `|Δn|/max(n_tight, 1)`. The run is *converged* when every change is at most
//! [`CHECK_THRESHOLD`] (1 %); otherwise [`AccuracyCheck::warning`] says which numbers moved, by
//! how much, and which setting to tighten.
//!
//! With the responses over the heights (`pounding run`, [`simulate_checked`]), the check run
//! records them too (with contact: the run without contact is the run's own where it is exact,
//! or integrated again without them), and compares the floor peaks — displacement, drift,
//! storey force, absolute acceleration and the equilibrium shear (`shear_with_damping`) — per
//! structure as the largest relative change at any station ([`floor_change`],
//! [`FLOOR_QUANTITIES`]). Both runs take them between observations where the modes too fast
//! for the cubic Hermite ring, on the sub-grid of the modes' closed forms
//! ([`crate::recording::subgrid`], at [`floor_resolution`]), whose own error is bounded by
//! construction far below the check's 1 %; a run whose floors were taken at the observations
//! alone (a cantilever's high modes ringing between them after a stiff impact, a coarse grid's
//! second and third modes) is flagged. Inside an impact pulse the observations are the contact
//! sub-steps and the force is linear between them: the accelerations' peaks there converge with
//! the contact steps, and the check run's tighter tolerance measures that error (on the paper's
//! case c with `exact-modal` at dt = 10 ms: 1.1 % estimated, 1.2 % against an independent
//! integration, `tests/audit_cantilevers.rs`).
//!
//! What the check does not see: the step `dt` of `adaptive` and `exact-modal` (the largest
//! step, and the spacing of observations) is kept, so the peaks at the contact heights are
//! refined between the same observations; the number of modes is never checked (`pounding
//! convergence` varies it).
//!
//! [`simulate_checked`]: crate::analysis::simulate::simulate_checked

use serde::Serialize;
use serde::ser::SerializeMap;

use crate::analysis::simulate::Report;
use crate::integrate::{Method, SolveError, SolverSettings};
use crate::recording::floor_response::FloorPeaks;

/// Largest relative change of any checked quantity for a run to count as converged (1 %).
pub const CHECK_THRESHOLD: f64 = 0.01;

/// How much tighter the check run is: its error should be about this many times smaller.
pub const TIGHTENING: f64 = 100.0;

/// Smallest relative tolerance the check run uses (the smallest a scenario accepts); below it
/// the error estimate of `adaptive` would sink into round-off and its steps would shrink
/// without end.
pub const MIN_RTOL: f64 = crate::integrate::MIN_RTOL;

/// Smallest absolute tolerance the check run uses, m (the smallest a scenario accepts).
pub const MIN_ATOL: f64 = crate::integrate::MIN_ATOL;

/// Every warning of the self-check starts with this (see [`is_check_warning`]).
pub const WARNING_PREFIX: &str = "self-check";

/// Whether a report's warning comes from the self-check (rather than from the run itself).
pub fn is_check_warning(warning: &str) -> bool {
    warning.starts_with(WARNING_PREFIX)
}

/// The quantities checked, by the names used in `summary.json`'s `accuracy.quantities` and in
/// a sweep's results table, with what they are.
pub const QUANTITIES: [(&str, &str); 25] = [
    (
        "peak_displacement_1",
        "peak displacement of structure 1 with pounding",
    ),
    (
        "peak_displacement_2",
        "peak displacement of structure 2 with pounding",
    ),
    (
        "peak_displacement_no_contact_1",
        "peak displacement of structure 1 without pounding",
    ),
    (
        "peak_displacement_no_contact_2",
        "peak displacement of structure 2 without pounding",
    ),
    ("peak_force", "peak contact force"),
    ("impacts", "number of impacts"),
    ("sep_time_history", "required separation (time history)"),
    // yielding buildings only (issue 16)
    (
        "peak_ductility_1",
        "peak ductility demand of structure 1 with pounding",
    ),
    (
        "peak_ductility_2",
        "peak ductility demand of structure 2 with pounding",
    ),
    (
        "peak_ductility_no_contact_1",
        "peak ductility demand of structure 1 without pounding",
    ),
    (
        "peak_ductility_no_contact_2",
        "peak ductility demand of structure 2 without pounding",
    ),
    (
        "residual_drift_1",
        "largest residual drift of structure 1 with pounding (change relative to the larger of it and the smallest yield drift)",
    ),
    (
        "residual_drift_2",
        "largest residual drift of structure 2 with pounding (change relative to the larger of it and the smallest yield drift)",
    ),
    (
        "hysteretic_energy_1",
        "hysteretic energy of structure 1 with pounding (change relative to the larger of it and 0.1 % of the input energy)",
    ),
    (
        "hysteretic_energy_2",
        "hysteretic energy of structure 2 with pounding (change relative to the larger of it and 0.1 % of the input energy)",
    ),
    // the responses over the heights, with pounding (runs that record them)
    (
        "floor_displacement_1",
        "peak floor displacement of structure 1 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_drift_1",
        "peak drift of structure 1 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_shear_1",
        "peak storey/section shear of structure 1 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_acceleration_1",
        "peak absolute floor acceleration of structure 1 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_shear_with_damping_1",
        "peak storey/section shear with damping (equilibrium) of structure 1 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_displacement_2",
        "peak floor displacement of structure 2 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_drift_2",
        "peak drift of structure 2 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_shear_2",
        "peak storey/section shear of structure 2 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_acceleration_2",
        "peak absolute floor acceleration of structure 2 with pounding (largest relative change at a floor)",
    ),
    (
        "floor_shear_with_damping_2",
        "peak storey/section shear with damping (equilibrium) of structure 2 with pounding (largest relative change at a floor)",
    ),
];

/// A floor quantity of [`QUANTITIES`]: its name and the peak it compares.
pub type FloorQuantity = (&'static str, fn(&FloorPeaks) -> f64);

/// The floor quantities of [`QUANTITIES`] per structure.
pub const FLOOR_QUANTITIES: [[FloorQuantity; 5]; 2] = [
    [
        ("floor_displacement_1", |p| p.displacement),
        ("floor_drift_1", |p| p.drift),
        ("floor_shear_1", |p| p.shear),
        ("floor_acceleration_1", |p| p.acceleration),
        ("floor_shear_with_damping_1", |p| p.shear_with_damping),
    ],
    [
        ("floor_displacement_2", |p| p.displacement),
        ("floor_drift_2", |p| p.drift),
        ("floor_shear_2", |p| p.shear),
        ("floor_acceleration_2", |p| p.acceleration),
        ("floor_shear_with_damping_2", |p| p.shear_with_damping),
    ],
];

/// The resolution of the check run's floor peaks between observations
/// ([`crate::recording::subgrid::CHECK_RESOLUTION`]).
pub fn floor_resolution() -> f64 {
    crate::recording::subgrid::CHECK_RESOLUTION
}

/// A floor's peak is compared relative to itself, or to this fraction of the structure's
/// largest peak of the quantity when it is smaller (a cantilever's section shear vanishes at
/// its top: a change there relative to ~0 means nothing).
pub const FLOOR_SCALE: f64 = 0.1;

/// The change of one floor quantity `peak` between the stations of a run (`a`) and of its
/// check run (`b`): `max_f |a_f − b_f| / max(|b_f|, FLOOR_SCALE·max_g |b_g|)` (every floor
/// relative to itself, as an engineer reads it, floors below [`FLOOR_SCALE`] of the largest
/// relative to that), with the values at the station of the largest change. `None` when the
/// stations differ.
pub fn floor_change(
    name: &'static str,
    a: &[FloorPeaks],
    b: &[FloorPeaks],
    peak: fn(&FloorPeaks) -> f64,
) -> Option<QuantityChange> {
    if a.is_empty() || a.len() != b.len() {
        return None;
    }
    let top = b.iter().map(|p| peak(p).abs()).fold(0.0, f64::max);
    let (mut worst, mut at) = (f64::NEG_INFINITY, 0);
    for (f, (x, y)) in a.iter().zip(b).enumerate() {
        let scale = peak(y).abs().max(FLOOR_SCALE * top);
        let d = if scale > 0.0 {
            (peak(x) - peak(y)).abs() / scale
        } else {
            relative_change(peak(x), peak(y))
        };
        if d.is_nan() || d > worst {
            worst = d;
            at = f;
            if d.is_nan() {
                break;
            }
        }
    }
    let (value, tight) = (peak(&a[at]), peak(&b[at]));
    Some(QuantityChange {
        name,
        value,
        tight,
        change: worst,
    })
}

/// The settings of the check run, from the run's own settings — the one place that says what
/// "100× tighter" means for each method:
///
/// - `adaptive`: `rtol/100` and `atol/100`, `dt` (the largest step) unchanged;
/// - `exact-modal`: `rtol/100` and `atol/100` (the tolerance of its contact steps), `dt` (the
///   grid of the free flight) unchanged. Its contact steps are held to rtol by a sixth-order
///   estimate while the solution it keeps is of order 8, so a run's error falls at least as
///   fast as rtol (26–250× per 100× on the paper's case, `tests/integrators.rs`): the check
///   run's error is far below the run's, and the change it reports is the run's error
///   (tested against converged solutions, `tests/accuracy.rs`). It costs the contact steps
///   100^{1/7} ≈ 1.9× more (the estimate goes like h⁷), and nothing without contact;
/// - `rk4`: `dt/√10` — fourth order, so the error shrinks by about 100. The smaller step is
///   always within the stability limit if `dt` was, and any `duration` is covered (the last
///   step is shortened).
///
/// Tolerances do not go below [`MIN_RTOL`] and [`MIN_ATOL`]; [`limited_tightening`] says when
/// that bound cut the tightening short.
pub fn tightened(settings: &SolverSettings) -> SolverSettings {
    let mut s = *settings;
    match settings.method {
        Method::Rk4 => s.dt = settings.dt / TIGHTENING.sqrt().sqrt(),
        Method::Adaptive | Method::ExactModal => {
            s.rtol = (settings.rtol / TIGHTENING).max(MIN_RTOL);
            s.atol = (settings.atol / TIGHTENING).max(MIN_ATOL);
        }
    }
    s
}

/// Whether [`tightened`] could not tighten the tolerances fully (they were already within 100×
/// of [`MIN_RTOL`] / [`MIN_ATOL`]); the check then understates the error.
pub fn limited_tightening(settings: &SolverSettings) -> bool {
    match settings.method {
        Method::Rk4 => false,
        Method::Adaptive | Method::ExactModal => {
            settings.rtol / TIGHTENING < MIN_RTOL || settings.atol / TIGHTENING < MIN_ATOL
        }
    }
}

/// Whether [`tightened`] leaves the settings as they are: `adaptive` or `exact-modal` with
/// `rtol` and `atol` already at [`MIN_RTOL`] and [`MIN_ATOL`]. The check run then integrates
/// exactly as the run did, so it cannot verify the time integration; it still records the floor
/// peaks between observations at its finer resolution ([`floor_resolution`]).
pub fn untightened(settings: &SolverSettings) -> bool {
    tightened(settings) == *settings
}

/// What a check that could not tighten the run at all (`untightened`) could and could not
/// verify: the time integration not at all, the floor peaks between observations (refined more
/// finely by the check run) with their largest change `floors` when compared.
pub(crate) fn untightened_failure(settings: &SolverSettings, floors: Option<f64>) -> String {
    let what = match floors {
        Some(c) => format!(
            "; only the floor peaks between observations, refined more finely by the check run, \
             were compared (largest change {})",
            percent(c)
        ),
        None => String::new(),
    };
    format!(
        "rtol {:e} and atol {:e} m are already the smallest tolerances, so the check run \
         integrates exactly as the run did: the time integration (peaks, forces, impacts, \
         separation) is not verified{what}",
        settings.rtol, settings.atol
    )
}

/// The scenario setting to tighten when the check fails, as written in a scenario file.
pub fn setting_to_tighten(method: Method) -> &'static str {
    match method {
        Method::Rk4 => "[solver] dt",
        Method::Adaptive | Method::ExactModal => "[solver] rtol",
    }
}

/// Relative change `|value − tight|/|tight|` of a real quantity: 0 when both are 0, 1 when only
/// the tight value is 0, NaN when either is not finite.
pub fn relative_change(value: f64, tight: f64) -> f64 {
    if !(value.is_finite() && tight.is_finite()) {
        f64::NAN
    } else if tight == 0.0 {
        if value == 0.0 { 0.0 } else { 1.0 }
    } else {
        (value - tight).abs() / tight.abs()
    }
}

/// Relative change of a count: `|n − n_tight|/max(n_tight, 1)`.
pub fn count_change(value: usize, tight: usize) -> f64 {
    value.abs_diff(tight) as f64 / tight.max(1) as f64
}

/// One checked quantity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct QuantityChange {
    /// Its name (a key of `accuracy.quantities`, one of [`QUANTITIES`]).
    #[serde(skip)]
    pub name: &'static str,
    /// The run's value (SI; the number of impacts as a number).
    pub value: f64,
    /// The check run's value.
    pub tight: f64,
    /// Relative change, see [`relative_change`] and [`count_change`].
    pub change: f64,
}

impl QuantityChange {
    /// What the quantity is, for people.
    pub fn label(&self) -> &'static str {
        QUANTITIES
            .iter()
            .find(|(n, _)| *n == self.name)
            .map_or(self.name, |(_, l)| l)
    }

    /// Within [`CHECK_THRESHOLD`] (false for a NaN change).
    pub fn within(&self) -> bool {
        self.change <= CHECK_THRESHOLD
    }
}

/// The settings of the check run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CheckSettings {
    /// Method (the run's own).
    pub method: &'static str,
    /// Step of the check run, s (see `dt` in `solver`).
    pub dt: f64,
    /// Relative tolerance of the check run (`adaptive`, `exact-modal`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rtol: Option<f64>,
    /// Absolute tolerance of the check run, m (`adaptive`, `exact-modal`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub atol: Option<f64>,
    /// How the check run's settings were derived from the run's.
    pub tightening: &'static str,
}

impl CheckSettings {
    /// The check settings of a run with `settings`.
    pub fn of(settings: &SolverSettings) -> CheckSettings {
        let t = tightened(settings);
        let tol = settings.method != Method::Rk4;
        CheckSettings {
            method: settings.method.name(),
            dt: t.dt,
            rtol: tol.then_some(t.rtol),
            atol: tol.then_some(t.atol),
            tightening: match settings.method {
                Method::Rk4 => {
                    "dt / sqrt(10): fourth order, so the error is about 100 times smaller"
                }
                Method::Adaptive | Method::ExactModal => {
                    "rtol / 100 and atol / 100 (not below 1e-12 and 1e-14 m), dt unchanged"
                }
            },
        }
    }

    /// The setting of the check run that the user would tighten, for messages: `rtol 1e-10`,
    /// `dt = 3.162e-4 s`.
    pub fn describe(&self) -> String {
        match self.rtol {
            Some(r) => format!("rtol {r:.0e}"),
            None => format!("dt = {:.4} ms", self.dt * 1e3),
        }
    }
}

/// The `accuracy` section of a report: the run's headline numbers against a second run at a
/// 100× tighter tolerance.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AccuracyCheck {
    /// Whether the check was made (false: `--no-check`, or the library's plain `simulate`).
    pub checked: bool,
    /// The largest relative change accepted, [`CHECK_THRESHOLD`].
    pub threshold: f64,
    /// Every change ≤ `threshold` (`None` when not checked; `Some(false)` when the check run
    /// failed).
    pub converged: Option<bool>,
    /// The largest relative change (`None` when not checked or the check run failed).
    pub max_change: Option<f64>,
    /// The quantity with the largest change.
    pub max_change_quantity: Option<&'static str>,
    /// The check run's settings.
    pub settings: Option<CheckSettings>,
    /// Each quantity of [`QUANTITIES`] (in that order; a JSON object keyed by name).
    #[serde(serialize_with = "by_name")]
    pub quantities: Vec<QuantityChange>,
    /// Why the check run failed, if it did (the result is then not verified).
    pub failure: Option<String>,
}

fn by_name<S: serde::Serializer>(q: &[QuantityChange], s: S) -> Result<S::Ok, S::Error> {
    let mut m = s.serialize_map(Some(q.len()))?;
    for x in q {
        m.serialize_entry(x.name, x)?;
    }
    m.end()
}

impl Default for AccuracyCheck {
    fn default() -> Self {
        AccuracyCheck::unchecked()
    }
}

impl AccuracyCheck {
    /// No check made.
    pub fn unchecked() -> AccuracyCheck {
        AccuracyCheck {
            checked: false,
            threshold: CHECK_THRESHOLD,
            converged: None,
            max_change: None,
            max_change_quantity: None,
            settings: None,
            quantities: Vec::new(),
            failure: None,
        }
    }

    /// The check run (with `settings`' [`tightened`] settings) failed with `error`: the result is
    /// not verified, and so not converged.
    pub fn failed(settings: &SolverSettings, error: &SolveError) -> AccuracyCheck {
        AccuracyCheck {
            checked: true,
            converged: Some(false),
            settings: Some(CheckSettings::of(settings)),
            failure: Some(error.to_string()),
            ..AccuracyCheck::unchecked()
        }
    }

    /// Compare `report` (run with `settings`) with `tight`, the same scenario run with
    /// [`tightened`]`(settings)`.
    pub fn compare(report: &Report, tight: &Report, settings: &SolverSettings) -> AccuracyCheck {
        let real = |name, a: f64, b: f64| QuantityChange {
            name,
            value: a,
            tight: b,
            change: relative_change(a, b),
        };
        let [a1, a2] = &report.structures;
        let [b1, b2] = &tight.structures;
        let (n, nt) = (report.contact.impacts, tight.contact.impacts);
        let quantities = vec![
            real(
                "peak_displacement_1",
                a1.peak_displacement,
                b1.peak_displacement,
            ),
            real(
                "peak_displacement_2",
                a2.peak_displacement,
                b2.peak_displacement,
            ),
            real(
                "peak_displacement_no_contact_1",
                a1.peak_displacement_no_contact,
                b1.peak_displacement_no_contact,
            ),
            real(
                "peak_displacement_no_contact_2",
                a2.peak_displacement_no_contact,
                b2.peak_displacement_no_contact,
            ),
            real(
                "peak_force",
                report.contact.peak_force,
                tight.contact.peak_force,
            ),
            QuantityChange {
                name: "impacts",
                value: n as f64,
                tight: nt as f64,
                change: count_change(n, nt),
            },
            real(
                "sep_time_history",
                report.separation.time_history,
                tight.separation.time_history,
            ),
        ];
        let mut quantities = quantities;
        // yielding buildings (issue 16): ductility, residual drift, hysteretic energy
        let names = [
            (
                "peak_ductility_1",
                "peak_ductility_no_contact_1",
                "residual_drift_1",
                "hysteretic_energy_1",
            ),
            (
                "peak_ductility_2",
                "peak_ductility_no_contact_2",
                "residual_drift_2",
                "hysteretic_energy_2",
            ),
        ];
        for (i, (a, b)) in report.structures.iter().zip(&tight.structures).enumerate() {
            let (
                Some(mu),
                Some(mu_t),
                Some(mu0),
                Some(mu0_t),
                Some(r),
                Some(r_t),
                Some(e),
                Some(e_t),
            ) = (
                a.peak_ductility,
                b.peak_ductility,
                a.peak_ductility_no_contact,
                b.peak_ductility_no_contact,
                a.max_residual_drift,
                b.max_residual_drift,
                a.hysteretic_energy,
                b.hysteretic_energy,
            )
            else {
                continue;
            };
            let (n_mu, n_mu0, n_r, n_e) = names[i];
            quantities.push(real(n_mu, mu, mu_t));
            quantities.push(real(n_mu0, mu0, mu0_t));
            // a residual drift near zero: its change in units of the yield drift
            let scale = r_t.abs().max(a.min_yield_drift.unwrap_or(0.0));
            quantities.push(QuantityChange {
                name: n_r,
                value: r,
                tight: r_t,
                change: if scale > 0.0 && r.is_finite() && r_t.is_finite() {
                    (r - r_t).abs() / scale
                } else {
                    relative_change(r, r_t)
                },
            });
            // a storey that barely yields dissipates next to nothing: its change in units of
            // 0.1 % of the ground's input (with pounding) when that is larger
            let scale = e_t.abs().max(1e-3 * tight.energy.input.abs());
            quantities.push(QuantityChange {
                name: n_e,
                value: e,
                tight: e_t,
                change: if scale > 0.0 && e.is_finite() && e_t.is_finite() {
                    (e - e_t).abs() / scale
                } else {
                    relative_change(e, e_t)
                },
            });
        }
        // the responses over the heights with pounding, where both runs recorded them
        let floors = report.with_contact.floors.iter();
        for (i, (a, b)) in floors.zip(&tight.with_contact.floors).enumerate() {
            for (name, peak) in FLOOR_QUANTITIES.get(i).into_iter().flatten() {
                quantities.extend(floor_change(name, a, b, *peak));
            }
        }
        // a check run that could not be tighter verifies only the floors' refinement between
        // observations (when the tolerance matters: contact steps, or yielding storeys)
        let matters = report.contact.impacts > 0
            || report.structures.iter().any(|s| s.peak_ductility.is_some());
        let unverified = untightened(settings) && matters;
        // the largest change (of what was verified); a NaN change counts as the largest
        let verified = quantities
            .iter()
            .filter(|q| !unverified || q.name.starts_with("floor_"));
        let worst = verified.copied().reduce(|m, q| {
            if q.change.is_nan() || q.change > m.change {
                q
            } else {
                m
            }
        });
        // a check run identical to the run in contact tightened nothing: it cannot vouch for it
        // (the floors aside: the check run resolves their peaks more finely in any case)
        let (w, wt) = (&report.with_contact, &tight.with_contact);
        let blind = report.contact.impacts > 0
            && (w.peak, &w.levels, &w.impacts, &w.energy, w.steps)
                == (wt.peak, &wt.levels, &wt.impacts, &wt.energy, wt.steps);
        AccuracyCheck {
            checked: true,
            threshold: CHECK_THRESHOLD,
            converged: Some(!unverified && !blind && quantities.iter().all(QuantityChange::within)),
            max_change: worst.map(|q| q.change),
            max_change_quantity: worst.map(|q| q.name),
            settings: Some(CheckSettings::of(settings)),
            failure: if unverified {
                Some(untightened_failure(settings, worst.map(|q| q.change)))
            } else {
                blind.then(|| {
                format!(
                    "the check run with contact was bit-identical to the run: `{}` has no effect \
                     on this method's contact steps here, so the result could not be checked",
                    setting_to_tighten(settings.method)
                )
                })
            },
            quantities,
        }
    }

    /// The quantities whose change exceeds the threshold.
    pub fn exceeded(&self) -> impl Iterator<Item = &QuantityChange> {
        self.quantities.iter().filter(|q| !q.within())
    }

    /// Checked and converged.
    pub fn is_converged(&self) -> bool {
        self.converged == Some(true)
    }

    /// The change of quantity `name` ([`QUANTITIES`]), if checked.
    pub fn change_of(&self, name: &str) -> Option<f64> {
        self.quantities
            .iter()
            .find(|q| q.name == name)
            .map(|q| q.change)
    }

    /// The warning for a run that failed its check (`None` when converged or not checked),
    /// naming the quantities, their changes and the setting to tighten.
    pub fn warning(&self, settings: &SolverSettings) -> Option<String> {
        if !self.checked || self.is_converged() {
            return None;
        }
        let cs = self.settings.unwrap_or_else(|| CheckSettings::of(settings));
        let moved: Vec<String> = self
            .exceeded()
            .map(|q| format!("the {} changed by {}", q.label(), percent(q.change)))
            .collect();
        let count_note = if self.exceeded().all(|q| q.name == "impacts") {
            " Only the number of impacts moved (the peaks and the peak force agree within \
             the limit): in a long sequence of impacts each one's timing shifts the next, so the \
             count may not settle at any tolerance."
        } else {
            ""
        };
        Some(not_converged_warning(
            &cs,
            settings,
            self.failure.as_deref(),
            &moved,
            count_note,
        ))
    }
}

/// The self-check's warning, in one wording for a pair ([`AccuracyCheck::warning`]) and a row
/// ([`super::row_check::RowAccuracyCheck::warning`]): the check that could not be done
/// (`failure`), or the quantities that `moved`, the limit and the setting to tighten, then
/// `count_note` (what it means when only numbers of impacts moved).
pub(crate) fn not_converged_warning(
    cs: &CheckSettings,
    settings: &SolverSettings,
    failure: Option<&str>,
    moved: &[String],
    count_note: &str,
) -> String {
    let knob = setting_to_tighten(settings.method);
    let scope = "The check varies the time integration only, not the number of modes \
                 (see `pounding convergence`).";
    if let Some(f) = failure {
        return format!(
            "self-check NOT converged: not verified against a 100× tighter rerun ({}): \
             {f}. {scope}",
            cs.describe()
        );
    }
    format!(
        "self-check NOT converged: against a 100× tighter rerun ({}), {} (limit {} %); \
         tighten `{knob}` (e.g. to the check's {}) and rerun. {scope}{count_note}",
        cs.describe(),
        moved.join(", "),
        100.0 * CHECK_THRESHOLD,
        match cs.rtol {
            Some(r) => format!("{r:.0e}"),
            None => format!("{:.3e} s", cs.dt),
        },
    )
}

/// A relative change as a percentage for people (`24.1 %`, `0.0031 %`).
pub fn percent(change: f64) -> String {
    let p = 100.0 * change;
    if !p.is_finite() {
        "an undefined amount".into()
    } else if p >= 1.0 {
        format!("{p:.1} %")
    } else {
        format!("{p:.2} %")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tightening_by_method() {
        let s = SolverSettings::new(Method::Rk4, 1e-3, 10.0);
        let t = tightened(&s);
        assert_eq!(t.dt, 1e-3 / 10f64.sqrt());
        assert_eq!((t.rtol, t.atol, t.duration), (s.rtol, s.atol, s.duration));
        for m in [Method::Adaptive, Method::ExactModal] {
            let s = SolverSettings::new(m, 1e-3, 10.0);
            let t = tightened(&s);
            assert_eq!(t.dt, s.dt);
            assert_eq!(t.rtol, s.rtol / 100.0);
            assert_eq!(t.atol, s.atol / 100.0);
            assert!(!limited_tightening(&s));
        }
        let mut s = SolverSettings::new(Method::Adaptive, 1e-3, 10.0);
        s.rtol = 1e-11;
        assert_eq!(tightened(&s).rtol, MIN_RTOL);
        assert!(limited_tightening(&s));
    }

    #[test]
    fn changes() {
        assert_eq!(relative_change(0.0, 0.0), 0.0);
        assert_eq!(relative_change(1.0, 0.0), 1.0);
        assert_eq!(relative_change(1.1, 1.0), 0.10000000000000009);
        assert_eq!(relative_change(-1.1, -1.0), 0.10000000000000009);
        assert!(relative_change(f64::NAN, 1.0).is_nan());
        assert_eq!(count_change(0, 0), 0.0);
        assert_eq!(count_change(3, 0), 3.0);
        assert_eq!(count_change(62, 54), 8.0 / 54.0);
        let nan = QuantityChange {
            name: "peak_force",
            value: 1.0,
            tight: 1.0,
            change: f64::NAN,
        };
        assert!(!nan.within());
    }

    #[test]
    fn unchecked_serialises_as_not_checked() {
        let j = serde_json::to_value(AccuracyCheck::unchecked()).unwrap();
        assert_eq!(j["checked"], false);
        assert!(j["converged"].is_null());
        assert!(j["quantities"].as_object().unwrap().is_empty());
    }
}
