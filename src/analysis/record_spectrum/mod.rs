//! Response spectra of recorded ground motions (issue 27) and the scaling of records and suites
//! to a target spectrum by the codes' rules.
//!
//! - [`sdof`] (in the model layer, [`crate::model::ground_motion::sdof`], where the record
//!   reader's `scale_to_sa` uses it too): the exact response of a linear oscillator to a
//!   piecewise-linear ground acceleration (Nigam & Jennings 1969), with the peaks of the
//!   continuous response;
//! - [`ResponseSpectrum`]: per period T (s) the spectral displacement S_d = max|u| (m), the
//!   pseudo-velocity PSV = ωS_d (m/s), the pseudo-acceleration PSA = ω²S_d (m/s²) and the peak
//!   total acceleration max|ü + a_g| (m/s²), ω = 2π/T; at T = 0 (a rigid oscillator) S_d = PSV = 0
//!   and PSA = the total acceleration = PGA;
//! - [`scaling`]: one factor per record so that the suite's mean spectrum meets ASCE 7-16 §16.2.3
//!   or EN 1998-1 §3.2.3.1.2 over the code's period range ([`scaling::SuiteScaling`]), and the
//!   factor that brings a record to a target S_a at one period ([`scale_to_sa`]);
//! - the tables and JSON of `pounding spectrum` and `pounding scale` are
//!   `output::spectrum_report`, their pictures `figures::spectrum`.
//!
//! The record is the program's ground-motion model ([`crate::model::ground_motion::Record`]): linear
//! between samples, zero after the last one; the oscillator starts at rest at t = 0 and its
//! free vibration after the record's end counts (it matters at long periods).

pub mod scaling;
pub mod single;

pub use crate::model::ground_motion::sdof;
pub use crate::model::ground_motion::sdof::{DEFAULT_DAMPING, MIN_PERIOD_OVER_DT};

use std::f64::consts::PI;

use serde::Serialize;

use crate::model::ground_motion::Record;

pub use scaling::{
    PeriodRange, ScaledRecord, ScaledSuite, ScalingError, ScalingOptions, ScalingRule, SuiteMember,
    SuiteScaling, Target,
};

/// What is wrong with a spectrum's input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpectrumInputError {
    /// No periods asked.
    #[error("no periods given")]
    NoPeriods,
    /// A period that is negative or not finite.
    #[error("period T = {0} s must be finite and ≥ 0")]
    BadPeriod(f64),
    /// A positive period far below the record's time step.
    #[error(
        "record \"{file}\": period T = {period} s is below dt/100 = {limit} s (dt = {dt} s): \
         there the oscillator follows the ground and PSA is the PGA to 0.2 %; ask for T = 0"
    )]
    PeriodBelowStep {
        /// The record.
        file: String,
        /// The period asked, s.
        period: f64,
        /// The record's time step, s.
        dt: f64,
        /// dt/100, s.
        limit: f64,
    },
    /// A damping ratio outside [0, 1).
    #[error("damping ratio ζ = {0} must be finite and in [0, 1)")]
    BadDamping(f64),
    /// A period list that does not parse.
    #[error("--periods `{text}`: {reason}")]
    BadPeriodList {
        /// The text given.
        text: String,
        /// What is wrong.
        reason: String,
    },
}

/// The peaks of one oscillator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpectralPoint {
    /// Period T, s.
    pub period: f64,
    /// Spectral displacement S_d = max|u|, m.
    pub sd: f64,
    /// Pseudo-velocity PSV = ωS_d, m/s.
    pub psv: f64,
    /// Pseudo-acceleration PSA = ω²S_d, m/s².
    pub psa: f64,
    /// Peak total acceleration max|ü + a_g|, m/s².
    pub sa_abs: f64,
}

/// The peaks of the oscillator of period `period` (s, ≥ 0) and damping ratio `damping` under
/// the ground acceleration `accel` (m/s²) sampled every `dt` s (see the module's conventions).
/// T = 0 gives S_d = 0 and PSA = the total acceleration = max|a|. Checked by the callers.
pub fn spectral_point(accel: &[f64], dt: f64, period: f64, damping: f64) -> SpectralPoint {
    if period == 0.0 {
        let pga = accel.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
        return SpectralPoint {
            period,
            sd: 0.0,
            psv: 0.0,
            psa: pga,
            sa_abs: pga,
        };
    }
    let omega = 2.0 * PI / period;
    let p = sdof::peaks(accel, dt, omega, damping);
    SpectralPoint {
        period,
        sd: p.displacement,
        psv: omega * p.displacement,
        psa: omega * omega * p.displacement,
        sa_abs: p.total_acceleration,
    }
}

/// A record's response spectrum at a list of periods.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResponseSpectrum {
    /// Damping ratio ζ of the oscillators.
    pub damping: f64,
    /// Periods, s, as asked.
    pub periods: Vec<f64>,
    /// Spectral displacement per period, m.
    pub sd: Vec<f64>,
    /// Pseudo-velocity per period, m/s.
    pub psv: Vec<f64>,
    /// Pseudo-acceleration per period, m/s².
    pub psa: Vec<f64>,
    /// Peak total acceleration per period, m/s².
    pub sa_abs: Vec<f64>,
    /// The record's PGA, m/s² (PSA at T = 0).
    pub pga: f64,
}

impl ResponseSpectrum {
    /// The spectrum of `record` at `periods` (s, each finite, ≥ 0 and, when positive, at least
    /// dt/100) with damping ratio `damping` in [0, 1).
    pub fn of_record(
        record: &Record,
        periods: &[f64],
        damping: f64,
    ) -> Result<ResponseSpectrum, SpectrumInputError> {
        check_input(&record.description, record.dt, periods, damping)?;
        let points: Vec<SpectralPoint> = periods
            .iter()
            .map(|&t| spectral_point(&record.accel, record.dt, t, damping))
            .collect();
        Ok(ResponseSpectrum {
            damping,
            periods: periods.to_vec(),
            sd: points.iter().map(|p| p.sd).collect(),
            psv: points.iter().map(|p| p.psv).collect(),
            psa: points.iter().map(|p| p.psa).collect(),
            sa_abs: points.iter().map(|p| p.sa_abs).collect(),
            pga: record.pga(),
        })
    }
}

/// Checks periods and damping for a record of time step `dt`.
pub fn check_input(
    file: &str,
    dt: f64,
    periods: &[f64],
    damping: f64,
) -> Result<(), SpectrumInputError> {
    if !(damping.is_finite() && (0.0..1.0).contains(&damping)) {
        return Err(SpectrumInputError::BadDamping(damping));
    }
    if periods.is_empty() {
        return Err(SpectrumInputError::NoPeriods);
    }
    for &t in periods {
        if !(t.is_finite() && t >= 0.0) {
            return Err(SpectrumInputError::BadPeriod(t));
        }
        if t > 0.0 && t < MIN_PERIOD_OVER_DT * dt {
            return Err(SpectrumInputError::PeriodBelowStep {
                file: file.to_string(),
                period: t,
                dt,
                limit: MIN_PERIOD_OVER_DT * dt,
            });
        }
    }
    Ok(())
}

/// The factor that brings `record`'s pseudo-acceleration at `period` (s, > 0) and `damping` to
/// `target_sa` (m/s², > 0): target / PSA(T). An error when PSA(T) is 0 (a record of zeros).
pub fn scale_to_sa(
    record: &Record,
    period: f64,
    damping: f64,
    target_sa: f64,
) -> Result<f64, ScalingError> {
    if !(target_sa.is_finite() && target_sa > 0.0) {
        return Err(ScalingError::BadTargetSa(target_sa));
    }
    if !(period.is_finite() && period > 0.0) {
        return Err(ScalingError::Input(SpectrumInputError::BadPeriod(period)));
    }
    check_input(&record.description, record.dt, &[period], damping)?;
    let psa = spectral_point(&record.accel, record.dt, period, damping).psa;
    if psa.is_nan() || psa <= 0.0 {
        return Err(ScalingError::NoResponse {
            record: record.description.clone(),
            period,
        });
    }
    Ok(target_sa / psa)
}

/// `n` periods from `lo` to `hi` (s, 0 < lo < hi), equally spaced in log T, both ends included.
pub fn log_periods(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n < 2 || !(lo > 0.0 && hi > lo) {
        return vec![lo];
    }
    let (a, b) = (lo.ln(), hi.ln());
    (0..n)
        .map(|k| match k {
            0 => lo,
            _ if k + 1 == n => hi,
            _ => (a + (b - a) * k as f64 / (n - 1) as f64).exp(),
        })
        .collect()
}

/// The periods of `pounding spectrum` by default: T = 0 (the PGA) and 0.01 to 10 s, 20 a
/// decade (61 periods).
pub fn default_periods() -> Vec<f64> {
    let mut p = vec![0.0];
    p.extend(log_periods(0.01, 10.0, 61));
    p
}

/// Periods from text: a comma-separated list (`0,0.1,0.2,0.5,1`) or `FROM:TO:N`, N periods
/// equally spaced in log T from FROM to TO (> 0). Sorted, duplicates removed; every period
/// finite and ≥ 0.
pub fn parse_periods(text: &str) -> Result<Vec<f64>, SpectrumInputError> {
    let bad = |reason: String| SpectrumInputError::BadPeriodList {
        text: text.to_string(),
        reason,
    };
    let num = |s: &str| -> Result<f64, SpectrumInputError> {
        let v: f64 = s
            .trim()
            .parse()
            .map_err(|_| bad(format!("`{}` is not a number", s.trim())))?;
        if !(v.is_finite() && v >= 0.0) {
            return Err(bad(format!("{v} is not a finite period ≥ 0 s")));
        }
        Ok(v)
    };
    let mut periods = if text.contains(':') {
        let parts: Vec<&str> = text.split(':').collect();
        let [from, to, n] = parts.as_slice() else {
            return Err(bad("expected FROM:TO:N, e.g. 0.02:5:100".into()));
        };
        let (from, to) = (num(from)?, num(to)?);
        let n: usize = n
            .trim()
            .parse()
            .map_err(|_| bad(format!("N = `{}` is not a whole number", n.trim())))?;
        if !(from > 0.0 && to > from) {
            return Err(bad("FROM:TO:N needs 0 < FROM < TO".into()));
        }
        if !(2..=10_000).contains(&n) {
            return Err(bad(format!("N = {n} must be in [2, 10000]")));
        }
        log_periods(from, to, n)
    } else {
        let list = text
            .split(',')
            .filter(|s| !s.trim().is_empty())
            .map(num)
            .collect::<Result<Vec<f64>, _>>()?;
        if list.is_empty() {
            return Err(bad("no periods".into()));
        }
        list
    };
    periods.sort_by(f64::total_cmp);
    periods.dedup();
    Ok(periods)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn period_lists() {
        assert_eq!(parse_periods("1, 0.5,0,0.5").unwrap(), vec![0.0, 0.5, 1.0]);
        let p = parse_periods("0.1:10:3").unwrap();
        assert_eq!(p.len(), 3);
        assert!((p[1] - 1.0).abs() < 1e-12 && p[0] == 0.1 && p[2] == 10.0);
        for bad in ["", "a", "-1", "1:0.5:3", "0:1:3", "0.1:1", "0.1:1:1", "inf"] {
            assert!(parse_periods(bad).is_err(), "{bad}");
        }
        let d = default_periods();
        assert_eq!(d.len(), 62);
        assert_eq!(d[0], 0.0);
        assert!((d[1] - 0.01).abs() < 1e-15 && (d[61] - 10.0).abs() < 1e-12);
    }
}
