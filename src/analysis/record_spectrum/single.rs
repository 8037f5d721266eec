//! Records scaled one by one to a target pseudo-spectral acceleration at one period (issue 27,
//! `pounding scale --sa T,SA`): each record's factor f = S_a,target / PSA(T, ζ), the same factor
//! a scenario's `[ground_motion] scale_to_sa` applies when it reads the record
//! ([`crate::model::ground_motion::scale::sa_factor`]), with the PSA before and after (the
//! latter computed again from the scaled samples, not as f·PSA). Text and JSON:
//! `output::sa_scaling`.

use serde::Serialize;

use crate::model::ground_motion::scale::{SaTarget, sa_factor};
use crate::model::ground_motion::sdof::pseudo_acceleration;
use crate::model::ground_motion::{RecordError, STANDARD_GRAVITY};

use super::scaling::SuiteMember;

/// One record scaled to the target.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SaScaledRecord {
    /// The record as named on the command line.
    pub record: String,
    /// Its time step, s.
    pub dt: f64,
    /// The factor every sample is multiplied by.
    pub factor: f64,
    /// PSA at the target's period before scaling, m/s².
    pub psa_before: f64,
    /// PSA at the target's period of the scaled record, m/s² (the target to rounding).
    pub psa_after: f64,
    /// PGA before scaling, m/s².
    pub pga_before: f64,
    /// PGA after scaling, m/s².
    pub pga_after: f64,
}

/// Every record scaled to one target S_a at one period.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SaScaling {
    /// The oscillator's period T, s.
    pub period: f64,
    /// Its damping ratio ζ.
    pub damping: f64,
    /// The target PSA at T, g.
    pub sa_g: f64,
    /// The target PSA at T, m/s².
    pub sa: f64,
    /// Each record, in the order given.
    pub records: Vec<SaScaledRecord>,
}

impl SaScaling {
    /// Each of `members` scaled to `target` (period s, S_a g, damping): an error names the
    /// record (a target out of range, a period below its dt/100, a record of zeros).
    pub fn compute(members: &[SuiteMember], target: &SaTarget) -> Result<SaScaling, RecordError> {
        let records = members
            .iter()
            .map(|m| {
                let r = m.record;
                let at = || crate::model::ground_motion::error::in_record(m.name);
                let (factor, psa_before) = sa_factor(&r.accel, r.dt, target, at)?;
                let scaled: Vec<f64> = r.accel.iter().map(|a| a * factor).collect();
                let psa_after = pseudo_acceleration(&scaled, r.dt, target.period, target.damping);
                Ok(SaScaledRecord {
                    record: m.name.to_string(),
                    dt: r.dt,
                    factor,
                    psa_before,
                    psa_after,
                    pga_before: r.pga(),
                    pga_after: scaled.iter().fold(0.0_f64, |p, a| p.max(a.abs())),
                })
            })
            .collect::<Result<Vec<_>, RecordError>>()?;
        Ok(SaScaling {
            period: target.period,
            damping: target.damping,
            sa_g: target.sa,
            sa: target.sa * STANDARD_GRAVITY,
            records,
        })
    }
}
