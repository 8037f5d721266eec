//! The self-check of a row of buildings (issue 29): a pair's check ([`super::accuracy`]) over
//! every structure and every pair. The row is run again with [`tightened`](super::accuracy::tightened) settings (100×
//! tighter tolerance; `dt/√10` for `rk4`) and its headline numbers compared: each structure's
//! peak displacement with and without pounding (at its headline height), and for a yielding
//! one its peak ductility with and without, largest residual drift and hysteretic energy
//! (scaled as a pair's); each pair's peak contact force, number of impacts and time-history
//! required separation. The same threshold ([`CHECK_THRESHOLD`], 1 %) and the same warning
//! ("self-check NOT converged: …", naming the quantities and the setting to tighten).
//!
//! With the floors (every row run records them), each structure's floor peaks are compared as
//! a pair's are ([`super::accuracy::floor_change`]): the largest relative change at a station of
//! the displacement, drift, storey force, absolute acceleration and equilibrium shear (the
//! self-check's run with contact records the floors too).
//!
//! The quantities are named after the structures and pairs: `peak_displacement_B8`,
//! `floor_shear_B8`, `peak_force_A3_B8`, … (the names of summary.json's
//! `accuracy.quantities` of a row).

use serde::Serialize;
use serde::ser::SerializeMap;

use super::RowReport;
use super::accuracy::{
    CHECK_THRESHOLD, CheckSettings, FLOOR_QUANTITIES, count_change, floor_change,
    not_converged_warning, percent, relative_change, setting_to_tighten,
};
use crate::integrate::{SolveError, SolverSettings};

/// The floor quantities of a row's structures, in the order of a pair's
/// [`FLOOR_QUANTITIES`]: the key's stem (the structure's name follows) and what it is.
const FLOOR_NAMES: [(&str, &str); 5] = [
    ("floor_displacement", "peak floor displacement"),
    ("floor_drift", "peak drift"),
    ("floor_shear", "peak storey/section shear"),
    ("floor_acceleration", "peak absolute floor acceleration"),
    (
        "floor_shear_with_damping",
        "peak storey/section shear with damping (equilibrium)",
    ),
];

/// One checked quantity of a row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowQuantityChange {
    /// Its name (a key of `accuracy.quantities`): the quantity and the structure's name, or
    /// the pair's two names.
    #[serde(skip)]
    pub name: String,
    /// What it is, for people.
    #[serde(skip)]
    pub label: String,
    /// The run's value (SI; the number of impacts as a number).
    pub value: f64,
    /// The check run's value.
    pub tight: f64,
    /// Relative change ([`relative_change`], [`count_change`]).
    pub change: f64,
}

impl RowQuantityChange {
    /// Within [`CHECK_THRESHOLD`] (false for a NaN change).
    pub fn within(&self) -> bool {
        self.change <= CHECK_THRESHOLD
    }
}

/// The `accuracy` section of a row's summary: as a pair's
/// ([`super::accuracy::AccuracyCheck`]), its quantities per structure and per pair.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowAccuracyCheck {
    /// Whether the check was made.
    pub checked: bool,
    /// The largest relative change accepted, [`CHECK_THRESHOLD`].
    pub threshold: f64,
    /// Every change ≤ `threshold` (`None` when not checked; `Some(false)` when the check run
    /// failed).
    pub converged: Option<bool>,
    /// The largest relative change.
    pub max_change: Option<f64>,
    /// The quantity with the largest change.
    pub max_change_quantity: Option<String>,
    /// The check run's settings.
    pub settings: Option<CheckSettings>,
    /// Every quantity (a JSON object keyed by name, in row order).
    #[serde(serialize_with = "by_name")]
    pub quantities: Vec<RowQuantityChange>,
    /// Why the check run failed, or could not vouch for the run.
    pub failure: Option<String>,
}

fn by_name<S: serde::Serializer>(q: &[RowQuantityChange], s: S) -> Result<S::Ok, S::Error> {
    let mut m = s.serialize_map(Some(q.len()))?;
    for x in q {
        m.serialize_entry(&x.name, x)?;
    }
    m.end()
}

impl Default for RowAccuracyCheck {
    fn default() -> Self {
        RowAccuracyCheck::unchecked()
    }
}

impl RowAccuracyCheck {
    /// No check made.
    pub fn unchecked() -> RowAccuracyCheck {
        RowAccuracyCheck {
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

    /// The check run failed with `error`: not verified, so not converged.
    pub fn failed(settings: &SolverSettings, error: &SolveError) -> RowAccuracyCheck {
        RowAccuracyCheck {
            checked: true,
            converged: Some(false),
            settings: Some(CheckSettings::of(settings)),
            failure: Some(error.to_string()),
            ..RowAccuracyCheck::unchecked()
        }
    }

    /// Compare `report` (run with `settings`) with `tight`, the same row run with
    /// [`tightened`](super::accuracy::tightened)`(settings)`.
    pub fn compare(
        report: &RowReport,
        tight: &RowReport,
        settings: &SolverSettings,
    ) -> RowAccuracyCheck {
        let mut q = Vec::new();
        let mut real = |name: String, label: String, a: f64, b: f64| {
            q.push(RowQuantityChange {
                name,
                label,
                value: a,
                tight: b,
                change: relative_change(a, b),
            })
        };
        for (a, b) in report.structures.iter().zip(&tight.structures) {
            let n = &a.name;
            real(
                format!("peak_displacement_{n}"),
                format!("peak displacement of {n} with pounding"),
                a.peak_displacement,
                b.peak_displacement,
            );
            real(
                format!("peak_displacement_no_contact_{n}"),
                format!("peak displacement of {n} without pounding"),
                a.peak_displacement_no_contact,
                b.peak_displacement_no_contact,
            );
            if let (Some(mu), Some(mu_t), Some(mu0), Some(mu0_t)) = (
                a.peak_ductility,
                b.peak_ductility,
                a.peak_ductility_no_contact,
                b.peak_ductility_no_contact,
            ) {
                real(
                    format!("peak_ductility_{n}"),
                    format!("peak ductility demand of {n} with pounding"),
                    mu,
                    mu_t,
                );
                real(
                    format!("peak_ductility_no_contact_{n}"),
                    format!("peak ductility demand of {n} without pounding"),
                    mu0,
                    mu0_t,
                );
            }
        }
        // a yielding building's residual drift and hysteretic energy, scaled as a pair's
        // (accuracy::AccuracyCheck::compare): near zero, in units of the smallest yield drift
        // and of 0.1 % of the ground's input
        for (a, b) in report.structures.iter().zip(&tight.structures) {
            let n = &a.name;
            if let (Some(r), Some(r_t)) = (a.max_residual_drift, b.max_residual_drift) {
                let scale = r_t.abs().max(a.min_yield_drift.unwrap_or(0.0));
                q.push(RowQuantityChange {
                    name: format!("residual_drift_{n}"),
                    label: format!("largest residual drift of {n} with pounding"),
                    value: r,
                    tight: r_t,
                    change: if scale > 0.0 && r.is_finite() && r_t.is_finite() {
                        (r - r_t).abs() / scale
                    } else {
                        relative_change(r, r_t)
                    },
                });
            }
            if let (Some(e), Some(e_t)) = (a.hysteretic_energy, b.hysteretic_energy) {
                let scale = e_t.abs().max(1e-3 * tight.energy.input.abs());
                q.push(RowQuantityChange {
                    name: format!("hysteretic_energy_{n}"),
                    label: format!("hysteretic energy of {n} with pounding"),
                    value: e,
                    tight: e_t,
                    change: if scale > 0.0 && e.is_finite() && e_t.is_finite() {
                        (e - e_t).abs() / scale
                    } else {
                        relative_change(e, e_t)
                    },
                });
            }
        }
        // the responses over the heights with pounding, where both runs recorded them: per
        // structure the largest relative change at a station of each floor quantity, as a
        // pair's (`floor_displacement_B8`, …, `floor_shear_with_damping_B8`)
        let floors = report.with_contact.floors.iter();
        for ((a, b), s) in floors
            .zip(&tight.with_contact.floors)
            .zip(&report.structures)
        {
            let n = &s.name;
            for ((_, peak), (key, label)) in FLOOR_QUANTITIES[0].iter().zip(FLOOR_NAMES) {
                if let Some(c) = floor_change(key, a, b, *peak) {
                    q.push(RowQuantityChange {
                        name: format!("{key}_{n}"),
                        label: format!(
                            "{label} of {n} with pounding (largest relative change at a floor)"
                        ),
                        value: c.value,
                        tight: c.tight,
                        change: c.change,
                    });
                }
            }
        }
        for (a, b) in report.pairs.iter().zip(&tight.pairs) {
            let [l, r] = &a.between;
            let pair = format!("{l}_{r}");
            let (n, nt) = (a.contact.impacts, b.contact.impacts);
            q.push(RowQuantityChange {
                name: format!("peak_force_{pair}"),
                label: format!("peak contact force {l}–{r}"),
                value: a.contact.peak_force,
                tight: b.contact.peak_force,
                change: relative_change(a.contact.peak_force, b.contact.peak_force),
            });
            q.push(RowQuantityChange {
                name: format!("impacts_{pair}"),
                label: format!("number of impacts {l}–{r}"),
                value: n as f64,
                tight: nt as f64,
                change: count_change(n, nt),
            });
            q.push(RowQuantityChange {
                name: format!("sep_time_history_{pair}"),
                label: format!("required separation {l}–{r} (time history)"),
                value: a.separation.time_history,
                tight: b.separation.time_history,
                change: relative_change(a.separation.time_history, b.separation.time_history),
            });
        }
        let impacts: usize = report.pairs.iter().map(|p| p.contact.impacts).sum();
        // a check run that could not be tighter verifies only the floors' refinement between
        // observations (when the tolerance matters: contact steps, or yielding storeys)
        let matters = impacts > 0 || report.structures.iter().any(|s| s.peak_ductility.is_some());
        let unverified = super::accuracy::untightened(settings) && matters;
        let verified = q
            .iter()
            .filter(|x| !unverified || x.name.starts_with("floor_"));
        let worst = verified.fold(None::<&RowQuantityChange>, |m, x| match m {
            Some(m) if !(x.change.is_nan() || x.change > m.change) => Some(m),
            _ => Some(x),
        });
        // a check run identical to the run in contact tightened nothing: it cannot vouch for it
        let blind = impacts > 0 && report.with_contact == tight.with_contact;
        RowAccuracyCheck {
            checked: true,
            threshold: CHECK_THRESHOLD,
            converged: Some(!unverified && !blind && q.iter().all(RowQuantityChange::within)),
            max_change: worst.map(|x| x.change),
            max_change_quantity: worst.map(|x| x.name.clone()),
            settings: Some(CheckSettings::of(settings)),
            failure: if unverified {
                Some(super::accuracy::untightened_failure(
                    settings,
                    worst.map(|x| x.change),
                ))
            } else {
                blind.then(|| {
                    format!(
                        "the check run with contact was bit-identical to the run: `{}` has no \
                         effect on this method's contact steps here, so the result could not be \
                         checked",
                        setting_to_tighten(settings.method)
                    )
                })
            },
            quantities: q,
        }
    }

    /// Checked and converged.
    pub fn is_converged(&self) -> bool {
        self.converged == Some(true)
    }

    /// The quantities whose change exceeds the threshold.
    pub fn exceeded(&self) -> impl Iterator<Item = &RowQuantityChange> {
        self.quantities.iter().filter(|q| !q.within())
    }

    /// The warning of a row that failed its check (`None` when converged or not checked), in
    /// the words of a pair's ([`super::accuracy::AccuracyCheck::warning`]).
    pub fn warning(&self, settings: &SolverSettings) -> Option<String> {
        if !self.checked || self.is_converged() {
            return None;
        }
        let cs = self.settings.unwrap_or_else(|| CheckSettings::of(settings));
        let moved: Vec<String> = self
            .exceeded()
            .map(|q| format!("the {} changed by {}", q.label, percent(q.change)))
            .collect();
        let count_note = if self.exceeded().all(|q| q.name.starts_with("impacts_")) {
            " Only numbers of impacts moved (the peaks and the peak forces agree within the \
             limit): in a long sequence of impacts each one's timing shifts the next, so the \
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
