//! Incremental dynamic analysis (IDA): each record scaled up run by run until every limit state
//! is exceeded, and the intensity at which each is first exceeded — the record's *capacity* —
//! bracketed by bisection: the hunt-and-fill tracing of Vamvatsikos & Cornell (2002),
//! "Incremental dynamic analysis", *Earthquake Engineering & Structural Dynamics* 31(3),
//! 491–514.
//!
//! For one record ([`trace`]), with the settings of [`IdaSettings`]:
//!
//! 1. **Hunt**: run at x₁ = `start`, then x_{k+1} = x_k + `step` + (k − 1) `growth` (steps that
//!    grow linearly), until every limit state that applies has been exceeded (in each model,
//!    with and without contact) and, when a `target` is asked, x has passed the target
//!    intensity — or `max_runs` runs are spent.
//! 2. **Bracket**: for each limit state and model, the capacity lies between `lo`, the
//!    highest run below the lowest exceeding run, and `hi`, that lowest exceeding run (`lo` = 0
//!    when the first run already exceeds). The widest bracket above `tolerance` is halved by a
//!    run at its midpoint (every run narrows every bracket it falls in), until all are within
//!    `tolerance` or the runs are spent.
//! 3. **Fill** (`fill = true`): runs left in the budget are spent at the midpoints of the
//!    widest gaps between consecutive runs below the highest, which smooths the curve.
//!
//! The capacity is the IM at which the limit state is *first* exceeded going up (a record that
//! exceeds and then stops exceeding at a higher intensity, V&C's "resurrection", keeps the
//! first). A limit state not exceeded within `max_runs` has no capacity (`hi` = `None`).
//!
//! The fit ([`fit_capacities`]): ln θ = mean of ln c_r, β = the standard deviation of ln c_r
//! with n − 1 (Baker 2015, *Earthquake Spectra* 31(1), eqs. 3–4: the capacities' lognormal by
//! the method of moments on their logarithms), c_r the midpoint of each record's bracket; no
//! fit when a record has no capacity. Intervals: the same bootstrap over records as the
//! stripes ([`super::fit`]).

use rand_pcg::Pcg64;
use rand_pcg::rand_core::{Rng, SeedableRng};
use serde::Serialize;

use super::RunOutcome;
use super::fit::{BootstrapIntervals, FitError, Interval, LognormalFit, normal_cdf};
use crate::input::fragility::{FragilityStudy, IdaSettings};

/// A limit state's capacity for one record, m/s².
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Capacity {
    /// The highest run below `hi` (0 when none), m/s².
    pub lo: f64,
    /// The lowest run exceeding, m/s² (`None`: not exceeded in any run).
    pub hi: Option<f64>,
}

impl Capacity {
    /// The capacity, the bracket's midpoint, m/s² (`None`: not reached).
    pub fn value(&self) -> Option<f64> {
        self.hi.map(|h| 0.5 * (self.lo + h))
    }
}

/// The (limit state, model) pairs that apply to the study: `exceeds` is `Some`.
pub fn pairs(study: &FragilityStudy, run: &RunOutcome, gaps: &[Vec<f64>]) -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    for (l, ls) in study.limit_states.iter().enumerate() {
        for m in 0..2 {
            if run.exceeds(ls, m, gaps).is_some() {
                v.push((l, m));
            }
        }
    }
    v
}

/// The bracket of limit state `l` in model `m` from a record's runs (any order).
pub fn bracket(
    study: &FragilityStudy,
    runs: &[RunOutcome],
    gaps: &[Vec<f64>],
    l: usize,
    m: usize,
) -> Capacity {
    let ls = &study.limit_states[l];
    let hi = runs
        .iter()
        .filter(|o| o.exceeds(ls, m, gaps) == Some(true))
        .map(|o| o.im)
        .fold(None, |a: Option<f64>, x| Some(a.map_or(x, |a| a.min(x))));
    let below = |o: &&RunOutcome| hi.is_none_or(|h| o.im < h);
    let lo = runs.iter().filter(below).map(|o| o.im).fold(0.0, f64::max);
    Capacity { lo, hi }
}

/// Hunt and fill for one record (see the module): `run_at(k, im)` gives the record's k-th run
/// (0-based) at intensity `im` (m/s²). Returns the runs in the order run.
pub fn trace<E>(
    study: &FragilityStudy,
    settings: &IdaSettings,
    mut run_at: impl FnMut(usize, f64) -> Result<RunOutcome, E>,
) -> Result<Vec<RunOutcome>, E> {
    let gaps = super::scenario_gaps(study);
    let target = study.target.map_or(0.0, |t| t.im);
    let n = settings.max_runs;
    let mut runs: Vec<RunOutcome> = Vec::new();
    // 1. hunt
    let mut x = settings.start;
    let mut k = 0;
    while runs.len() < n {
        runs.push(run_at(runs.len(), x)?);
        let all = pairs(study, &runs[0], &gaps).iter().all(|&(l, m)| {
            let ls = &study.limit_states[l];
            runs.iter().any(|o| o.exceeds(ls, m, &gaps) == Some(true))
        });
        if all && x >= target {
            break;
        }
        x += settings.step + k as f64 * settings.growth;
        k += 1;
    }
    // 2. bracket: the widest first
    let pairs = pairs(study, &runs[0], &gaps);
    while runs.len() < n {
        let widest = pairs
            .iter()
            .map(|&(l, m)| bracket(study, &runs, &gaps, l, m))
            .filter_map(|c| c.hi.map(|h| (c.lo, h)))
            .filter(|(lo, hi)| hi - lo > settings.tolerance)
            .max_by(|a, b| (a.1 - a.0).total_cmp(&(b.1 - b.0)));
        let Some((lo, hi)) = widest else { break };
        runs.push(run_at(runs.len(), 0.5 * (lo + hi))?);
    }
    // 3. fill the widest gaps between consecutive runs
    if settings.fill {
        while runs.len() < n {
            let mut at: Vec<f64> = runs.iter().map(|o| o.im).collect();
            at.push(0.0);
            at.sort_by(f64::total_cmp);
            let Some(w) = at
                .windows(2)
                .max_by(|a, b| (a[1] - a[0]).total_cmp(&(b[1] - b[0])))
            else {
                break;
            };
            if w[1] - w[0] <= settings.tolerance {
                break;
            }
            runs.push(run_at(runs.len(), 0.5 * (w[0] + w[1]))?);
        }
    }
    Ok(runs)
}

/// The IDA of one limit state in one model: every record's capacity and their fit.
#[derive(Debug, Clone, PartialEq)]
pub struct CapacityFit {
    /// Each record's capacity, m/s².
    pub capacities: Vec<Capacity>,
    /// The lognormal of the capacities (θ in the study's IM units).
    pub fit: Result<LognormalFit, FitError>,
    /// Bootstrap intervals over records.
    pub intervals: Option<BootstrapIntervals>,
}

/// θ and β of capacities `c` (> 0): the geometric mean and the standard deviation of ln c
/// with n − 1 (Baker 2015, eqs. 3–4); ln L the log-likelihood of the lognormal density there.
pub fn lognormal_of(c: &[f64]) -> Result<LognormalFit, FitError> {
    let n = c.len();
    if n < 2 || c.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
        return Err(FitError::BadInput);
    }
    let l: Vec<f64> = c.iter().map(|x| x.ln()).collect();
    let mu = l.iter().sum::<f64>() / n as f64;
    let var = l.iter().map(|x| (x - mu).powi(2)).sum::<f64>() / (n - 1) as f64;
    let beta = var.sqrt();
    if beta.is_nan() || beta <= 0.0 {
        // every record at the same capacity: a step, as complete separation of stripes
        return Ok(LognormalFit {
            theta: mu.exp(),
            beta: super::fit::BETA_MIN,
            log_likelihood: f64::NAN,
            at_bound: true,
        });
    }
    let ll = l
        .iter()
        .map(|x| {
            -x - beta.ln()
                - 0.5 * (2.0 * std::f64::consts::PI).ln()
                - 0.5 * ((x - mu) / beta).powi(2)
        })
        .sum();
    Ok(LognormalFit {
        theta: mu.exp(),
        beta,
        log_likelihood: ll,
        at_bound: false,
    })
}

/// The fit of the records' capacities in the study's IM units (`units` m/s² per unit), with
/// the percentile bootstrap over records (as [`super::fit::bootstrap`]: `resamples` draws by
/// PCG-64 seeded with `seed`, the interval at `confidence`, the band at `band_im`).
pub fn fit_capacities(
    capacities: Vec<Capacity>,
    units: f64,
    resamples: usize,
    seed: u64,
    confidence: f64,
    band_im: &[f64],
) -> CapacityFit {
    let values: Option<Vec<f64>> = capacities
        .iter()
        .map(|c| c.value().map(|v| v / units))
        .collect();
    let Some(c) = values else {
        return CapacityFit {
            capacities,
            fit: Err(FitError::Censored),
            intervals: None,
        };
    };
    let fit = lognormal_of(&c);
    let intervals = if fit.is_ok() && resamples > 0 {
        let n = c.len();
        let mut rng = Pcg64::seed_from_u64(seed);
        let fits: Vec<LognormalFit> = (0..resamples)
            .filter_map(|_| {
                let pick: Vec<f64> = (0..n)
                    .map(|_| c[(rng.next_u64() % n as u64) as usize])
                    .collect();
                lognormal_of(&pick).ok()
            })
            .collect();
        (fits.len() >= 2).then(|| {
            let (lo_p, hi_p) = (0.5 * (1.0 - confidence), 0.5 * (1.0 + confidence));
            let interval = |mut v: Vec<f64>| {
                v.sort_by(f64::total_cmp);
                Interval {
                    lo: super::fit::quantile(&v, lo_p),
                    hi: super::fit::quantile(&v, hi_p),
                }
            };
            BootstrapIntervals {
                theta: interval(fits.iter().map(|f| f.theta).collect()),
                beta: interval(fits.iter().map(|f| f.beta).collect()),
                confidence,
                resamples,
                failed: resamples - fits.len(),
                band: band_im
                    .iter()
                    .map(|&x| {
                        interval(
                            fits.iter()
                                .map(|f| normal_cdf((x / f.theta).ln() / f.beta))
                                .collect(),
                        )
                    })
                    .collect(),
            }
        })
    } else {
        None
    };
    CapacityFit {
        capacities,
        fit,
        intervals,
    }
}

/// A record's critical gap at intensity `x` (m/s²), linear between its runs sorted by IM
/// (`runs` as (im, critical gap)); `None` above its highest run. Exact where the required
/// separation is linear in the intensity (an elastic pair).
pub fn critical_gap_at(runs: &[(f64, f64)], x: f64) -> Option<f64> {
    let mut v: Vec<(f64, f64)> = runs.to_vec();
    v.push((0.0, 0.0));
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    if x > v.last()?.0 {
        return None;
    }
    let i = v.partition_point(|p| p.0 < x);
    if i == 0 {
        return Some(v[0].1);
    }
    let (a, b) = (v[i - 1], v[i]);
    if b.0 == a.0 {
        return Some(b.1);
    }
    Some(a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0))
}
