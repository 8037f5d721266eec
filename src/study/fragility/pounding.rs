//! P(pounding | IM, gap) for every gap at once, from the runs without contact.
//!
//! Before the first impact the runs with and without contact are the same motion, so a run
//! pounds exactly when, without contact, the structures' relative displacement at some level
//! exceeds that level's gap: `max_t (w₁ − w₂)(h_k) > g_k`, the level's time-history required
//! separation r_k ([`crate::analysis::simulate::LevelReport::required_gap`]) above its gap.
//! A record at an intensity then pounds for every gap below its *critical gap*:
//!
//! - `uniform` (one gap g at every level): pounding iff g < max_k r_k;
//! - `scaled` (the scenario's gaps g_k⁰ scaled together, the axis g the gap at the highest
//!   level, g_k = g · g_k⁰ / g_top⁰): pounding iff g < max_k r_k · g_top⁰ / g_k⁰ (a level
//!   with g_k⁰ = 0 and r_k > 0 pounds at any scale: critical gap ∞).
//!
//! P(pounding | IM, g) is the fraction of records whose critical gap exceeds g.

use serde::Serialize;

use super::fit;
use crate::input::fragility::GapMode;

/// The gap below which a run pounds (see the module), m: `required` r_k and `gaps` g_k⁰ per
/// level, `top` the scenario's gap at its highest level (`scaled` only).
pub fn critical_gap(required: &[f64], gaps: &[f64], top: f64, mode: GapMode) -> f64 {
    match mode {
        GapMode::Uniform => required.iter().copied().fold(0.0, f64::max),
        GapMode::Scaled => required
            .iter()
            .zip(gaps)
            .map(|(&r, &g)| {
                if r <= 0.0 {
                    0.0
                } else if g <= 0.0 {
                    f64::INFINITY
                } else {
                    r * top / g
                }
            })
            .fold(0.0, f64::max),
    }
}

/// P(pounding) over stripes × gaps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PoundingTable {
    /// The stripes, in the study's IM units.
    pub im: Vec<f64>,
    /// The gaps, m.
    pub gaps: Vec<f64>,
    /// `p[stripe][gap]`.
    pub p: Vec<Vec<f64>>,
}

impl PoundingTable {
    /// From the critical gaps `critical[stripe][record]`.
    pub fn new(im: &[f64], gaps: &[f64], critical: &[Vec<f64>]) -> PoundingTable {
        let p = critical
            .iter()
            .map(|c| {
                let n = c.len().max(1) as f64;
                gaps.iter()
                    .map(|&g| c.iter().filter(|&&x| x > g).count() as f64 / n)
                    .collect()
            })
            .collect();
        PoundingTable {
            im: im.to_vec(),
            gaps: gaps.to_vec(),
            p,
        }
    }
}

/// The gap that keeps P(pounding) at most `probability` at one intensity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GapForTarget {
    /// The design intensity, study units.
    pub im: f64,
    /// The accepted probability.
    pub probability: f64,
    /// Records.
    pub records: usize,
    /// The smallest gap at which at most ⌊p·n⌋ of the n records pound (the
    /// (⌊p·n⌋ + 1)-th largest critical gap), m.
    pub empirical: f64,
    /// How many records pound at that gap.
    pub pounding_records: usize,
    /// The gap from a lognormal fitted to the critical gaps (the mean μ and standard
    /// deviation σ of their logarithms, n − 1): exp(μ + σ Φ⁻¹(1 − p)), m; `None` when a
    /// critical gap is 0 or ∞, or n < 3.
    pub lognormal: Option<f64>,
    /// μ and σ of the lognormal.
    pub ln_mean: Option<f64>,
    /// See `ln_mean`.
    pub ln_std: Option<f64>,
}

/// The gap for P(pounding) ≤ `probability` at the intensity `im` (study units) from the
/// records' critical gaps there.
pub fn gap_for_target(critical: &[f64], probability: f64, im: f64) -> GapForTarget {
    let n = critical.len();
    let mut c = critical.to_vec();
    c.sort_by(|a, b| b.total_cmp(a));
    let k = ((probability * n as f64).floor() as usize).min(n.saturating_sub(1));
    let empirical = c.get(k).copied().unwrap_or(0.0);
    let pounding_records = c.iter().filter(|&&x| x > empirical).count();
    let usable = n >= 3 && c.iter().all(|x| x.is_finite() && *x > 0.0);
    let (mu, sd) = if usable {
        let l: Vec<f64> = c.iter().map(|x| x.ln()).collect();
        let mu = l.iter().sum::<f64>() / n as f64;
        let var = l.iter().map(|x| (x - mu) * (x - mu)).sum::<f64>() / (n - 1) as f64;
        (Some(mu), Some(var.sqrt()))
    } else {
        (None, None)
    };
    GapForTarget {
        im,
        probability,
        records: n,
        empirical,
        pounding_records,
        lognormal: mu
            .zip(sd)
            .map(|(m, s)| (m + s * fit::normal_quantile(1.0 - probability)).exp()),
        ln_mean: mu,
        ln_std: sd,
    }
}
