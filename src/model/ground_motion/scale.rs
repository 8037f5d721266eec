//! Scaling a record as it is read (issue 27): to a peak ground acceleration (`scale_to_pga`) or
//! to a target pseudo-spectral acceleration at one period (`scale_to_sa`), and what was applied
//! ([`RecordScaling`], reported in summary.json's `ground_motion` section and by `pounding
//! run`).
//!
//! Amplitude scaling multiplies every sample by one factor f, so the response of a linear
//! oscillator, and its PSA at every period, is multiplied by f too: f = S_a,target / PSA(T, ζ) of
//! the record as read (after any processing), PSA from the exact oscillator of [`super::sdof`]
//! (Nigam & Jennings 1969), brings the record's PSA at T to the target.

use super::STANDARD_GRAVITY;
use super::error::{Location, RecordError};
use super::sdof::{DEFAULT_DAMPING, MIN_PERIOD_OVER_DT, pseudo_acceleration};

/// A target pseudo-spectral acceleration at one period: `scale_to_sa = { period, sa, damping }`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SaTarget {
    /// The oscillator's period T, s (> 0, at least dt/100 of the record).
    pub period: f64,
    /// The target PSA at T, in g (> 0; × 9.80665 m/s²), as `scale_to_pga` is in g.
    pub sa: f64,
    /// The oscillator's damping ratio ζ, in [0, 1); 5 % by default ([`SaTarget::new`]).
    pub damping: f64,
}

impl SaTarget {
    /// The target `sa` (g) at `period` (s) with the default 5 % damping.
    pub fn new(period: f64, sa: f64) -> SaTarget {
        SaTarget {
            period,
            sa,
            damping: DEFAULT_DAMPING,
        }
    }

    /// Checks what does not depend on the record: T and S_a finite and > 0, ζ in [0, 1).
    pub fn check(&self, at: impl Fn() -> Location) -> Result<(), RecordError> {
        let bad = |what: &'static str, value: f64, allowed: &'static str| {
            Err(RecordError::InvalidSaTarget {
                at: at(),
                what,
                value,
                allowed,
            })
        };
        if !(self.period.is_finite() && self.period > 0.0) {
            return bad("period", self.period, "a finite period > 0 s");
        }
        if !(self.sa.is_finite() && self.sa > 0.0) {
            return bad("sa", self.sa, "a finite spectral acceleration > 0 g");
        }
        if !(self.damping.is_finite() && (0.0..1.0).contains(&self.damping)) {
            return bad("damping", self.damping, "a damping ratio in [0, 1)");
        }
        Ok(())
    }

    /// The target in m/s².
    pub fn sa_m_s2(&self) -> f64 {
        self.sa * STANDARD_GRAVITY
    }
}

/// What a record was scaled to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ScaleTarget {
    /// A factor given as such: a suite's record at its `factor` or at the factor its scaling
    /// rule set.
    Factor,
    /// `scale_to_pga`: the record's PGA set to this, g.
    Pga {
        /// The target PGA, g.
        pga: f64,
    },
    /// `scale_to_sa`: the record's PSA at the target's period set to its S_a.
    Sa {
        /// The target.
        target: SaTarget,
        /// The record's PSA at that period and damping before scaling, m/s².
        psa_before: f64,
    },
}

/// The scaling applied to a record when it was read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RecordScaling {
    /// The factor every sample was multiplied by (for `scale_to_pga`: target/PGA, the samples
    /// being set to a/PGA·target).
    pub factor: f64,
    /// What it was scaled to.
    pub target: ScaleTarget,
}

/// The factor that brings the PSA at `target.period` of `accel` (m/s², every `dt` s) to
/// `target.sa`, and that PSA (m/s²) before scaling. `at` names the record in errors: a target
/// out of range ([`SaTarget::check`]), a period below dt/100 (where the spectrum code refuses
/// it too), or a record without response at that period (all zeros).
pub fn sa_factor(
    accel: &[f64],
    dt: f64,
    target: &SaTarget,
    at: impl Fn() -> Location,
) -> Result<(f64, f64), RecordError> {
    target.check(&at)?;
    let limit = MIN_PERIOD_OVER_DT * dt;
    if target.period < limit {
        return Err(RecordError::SaPeriodBelowStep {
            at: at(),
            period: target.period,
            dt,
            limit,
        });
    }
    let psa = pseudo_acceleration(accel, dt, target.period, target.damping);
    if !(psa.is_finite() && psa > 0.0) {
        return Err(RecordError::ZeroSa {
            at: at(),
            period: target.period,
        });
    }
    Ok((target.sa_m_s2() / psa, psa))
}

/// Scales `accel` in place to a PGA of `pga_g` (g): a/PGA·target, which cannot overflow.
pub(crate) fn to_pga(
    accel: &mut [f64],
    pga_g: f64,
    at: impl Fn() -> Location,
) -> Result<RecordScaling, RecordError> {
    let pga = accel.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
    if pga <= 0.0 {
        return Err(RecordError::ZeroPga { at: at() });
    }
    let target = pga_g * STANDARD_GRAVITY;
    for a in accel.iter_mut() {
        *a = *a / pga * target;
    }
    Ok(RecordScaling {
        factor: target / pga,
        target: ScaleTarget::Pga { pga: pga_g },
    })
}

/// Scales `accel` in place to the PSA of `target`: every sample × the factor of [`sa_factor`]
/// (so that a record scaled here and one multiplied by that factor are the same bits).
pub(crate) fn to_sa(
    accel: &mut [f64],
    dt: f64,
    target: &SaTarget,
    at: impl Fn() -> Location,
) -> Result<RecordScaling, RecordError> {
    let (factor, psa_before) = sa_factor(accel, dt, target, at)?;
    for a in accel.iter_mut() {
        *a *= factor;
    }
    Ok(RecordScaling {
        factor,
        target: ScaleTarget::Sa {
            target: *target,
            psa_before,
        },
    })
}
