//! Lognormal fragility functions fitted by maximum likelihood to stripe counts (Baker 2015,
//! "Efficient analytical fragility function fitting using dynamic structural analysis",
//! *Earthquake Spectra* 31(1), 579–599, eq. 11), with bootstrap intervals over records.
//!
//! P(exceed | IM = x) = Φ(ln(x/θ)/β). At stripe j, z_j of n_j runs exceed; the counts are
//! taken as binomial, and (θ, β) maximise
//!
//! ```text
//! ln L = Σ_j [ z_j ln Φ(u_j) + (n_j − z_j) ln Φ(−u_j) ],   u_j = ln(x_j/θ)/β
//! ```
//!
//! In the probit parameters a = −ln θ/β, b = 1/β (u = a + b ln x) the log-likelihood is
//! concave, so Nelder–Mead (argmin) from any start finds the one maximum. β is kept in
//! [`BETA_MIN`, `BETA_MAX`]: counts that jump from 0 to all at adjacent stripes have their
//! maximum at β → 0, reported as β = `BETA_MIN` with `at_bound`.
//!
//! The bootstrap resamples the *records* with replacement (each record keeps its outcome at
//! every stripe, so the correlation between stripes, which the binomial likelihood ignores, is
//! carried into the interval), refits, and takes the percentile interval.

use argmin::core::{CostFunction, Executor};
use argmin::solver::neldermead::NelderMead;
use rand_pcg::Pcg64;
use rand_pcg::rand_core::{Rng, SeedableRng};
use rayon::prelude::*;
use serde::Serialize;

/// Smallest dispersion fitted (below it the counts are a step: the data cannot tell).
pub const BETA_MIN: f64 = 0.01;
/// Largest dispersion fitted.
pub const BETA_MAX: f64 = 5.0;

/// Φ, the standard normal distribution function.
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// ln Φ(x), finite far in the lower tail (Φ underflows below x ≈ −38): there the
/// asymptotic ln Φ(x) ≈ −x²/2 − ln(−x √(2π)) (Abramowitz & Stegun 26.2.12, first term).
pub fn ln_normal_cdf(x: f64) -> f64 {
    if x > -30.0 {
        normal_cdf(x).ln()
    } else {
        -0.5 * x * x - (-x * (2.0 * std::f64::consts::PI).sqrt()).ln()
    }
}

/// Φ⁻¹(p) for p in (0, 1), by bisection on [`normal_cdf`] to round-off.
pub fn normal_quantile(p: f64) -> f64 {
    let (mut lo, mut hi) = (-40.0, 40.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if normal_cdf(mid) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// −ln L of (θ, β) on stripe counts: `im` the stripes (> 0), `runs` n_j, `exceed` z_j.
pub fn neg_log_likelihood(
    theta: f64,
    beta: f64,
    im: &[f64],
    runs: &[usize],
    exceed: &[usize],
) -> f64 {
    let mut s = 0.0;
    for ((&x, &n), &z) in im.iter().zip(runs).zip(exceed) {
        let u = (x / theta).ln() / beta;
        if z > 0 {
            s -= z as f64 * ln_normal_cdf(u);
        }
        if n > z {
            s -= (n - z) as f64 * ln_normal_cdf(-u);
        }
    }
    s
}

/// A fitted lognormal fragility function.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LognormalFit {
    /// The median θ, in the units of the stripes.
    pub theta: f64,
    /// The dispersion β (log standard deviation).
    pub beta: f64,
    /// ln L at the fit.
    pub log_likelihood: f64,
    /// β reached [`BETA_MIN`] or [`BETA_MAX`].
    pub at_bound: bool,
}

impl LognormalFit {
    /// P(exceed | IM = x).
    pub fn probability(&self, x: f64) -> f64 {
        normal_cdf((x / self.theta).ln() / self.beta)
    }
}

/// Why no fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FitError {
    /// No run exceeds at any stripe: θ is above the stripes, not estimable.
    #[error("no run exceeds at any stripe (the median is above the stripes)")]
    NoExceedance,
    /// Every run exceeds at every stripe.
    #[error("every run exceeds at every stripe (the median is below the stripes)")]
    AllExceed,
    /// Inputs of different lengths or a stripe ≤ 0.
    #[error("the stripes and the counts do not match, or a stripe is not positive")]
    BadInput,
    /// The optimiser failed.
    #[error("the optimiser failed")]
    Optimiser,
    /// IDA: a record did not reach the limit state within its runs (no capacity).
    #[error("a record did not reach it within ida.max_runs (raise max_runs or the step)")]
    Censored,
}

struct Probit<'a> {
    ln_im: Vec<f64>,
    runs: &'a [usize],
    exceed: &'a [usize],
}

impl Probit<'_> {
    /// (a, b) with b in [1/BETA_MAX, 1/BETA_MIN].
    fn clamp(p: &[f64]) -> (f64, f64) {
        (p[0], p[1].clamp(1.0 / BETA_MAX, 1.0 / BETA_MIN))
    }
}

impl CostFunction for Probit<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, p: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        let (a, b) = Probit::clamp(p);
        let mut s = 0.0;
        for ((&l, &n), &z) in self.ln_im.iter().zip(self.runs).zip(self.exceed) {
            let u = a + b * l;
            if z > 0 {
                s -= z as f64 * ln_normal_cdf(u);
            }
            if n > z {
                s -= (n - z) as f64 * ln_normal_cdf(-u);
            }
        }
        // a gentle pull back inside the bounds (the clamped cost is flat outside)
        let out = (p[1] - b).abs();
        Ok(s + out)
    }
}

/// The maximum-likelihood lognormal fit to stripe counts (see the module).
pub fn fit_lognormal(
    im: &[f64],
    runs: &[usize],
    exceed: &[usize],
) -> Result<LognormalFit, FitError> {
    if im.len() != runs.len()
        || im.len() != exceed.len()
        || im.is_empty()
        || im.iter().any(|x| !(x.is_finite() && *x > 0.0))
        || runs.iter().zip(exceed).any(|(n, z)| z > n)
    {
        return Err(FitError::BadInput);
    }
    let total: usize = runs.iter().sum();
    let hits: usize = exceed.iter().sum();
    if hits == 0 {
        return Err(FitError::NoExceedance);
    }
    if hits == total {
        return Err(FitError::AllExceed);
    }
    // complete separation (none exceed below some stripe, all from it on): the likelihood
    // grows without bound as β → 0 with θ anywhere between the two stripes; the fit is β at
    // its bound and θ their geometric mean
    let step = (1..im.len()).find(|&j| {
        exceed[..j].iter().all(|&z| z == 0)
            && runs[j..].iter().zip(&exceed[j..]).all(|(n, z)| n == z)
    });
    if let Some(j) = step {
        let (theta, beta) = ((im[j - 1] * im[j]).sqrt(), BETA_MIN);
        return Ok(LognormalFit {
            theta,
            beta,
            log_likelihood: -neg_log_likelihood(theta, beta, im, runs, exceed),
            at_bound: true,
        });
    }
    let ln_im: Vec<f64> = im.iter().map(|x| x.ln()).collect();
    // start: θ where the observed fraction first reaches ½ (else beyond the last stripe), β = 0.4
    let theta0 = im
        .iter()
        .zip(runs.iter().zip(exceed))
        .find(|(_, (n, z))| 2 * **z >= **n && **n > 0)
        .map_or(im[im.len() - 1] * 1.5, |(x, _)| *x);
    let b0 = 1.0 / 0.4;
    let a0 = -theta0.ln() * b0;
    let simplex = vec![vec![a0, b0], vec![a0 + 0.5, b0], vec![a0, b0 * 1.5]];
    let problem = Probit {
        ln_im,
        runs,
        exceed,
    };
    fn best<'a>(
        problem: Probit<'a>,
        simplex: Vec<Vec<f64>>,
    ) -> Result<(Vec<f64>, Probit<'a>), FitError> {
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(1e-13)
            .map_err(|_| FitError::Optimiser)?;
        let res = Executor::new(problem, solver)
            .configure(|s| s.max_iters(5000))
            .run()
            .map_err(|_| FitError::Optimiser)?;
        let p = res.state.best_param.clone().ok_or(FitError::Optimiser)?;
        let problem = res.problem.problem.ok_or(FitError::Optimiser)?;
        Ok((p, problem))
    }
    // twice: a restart from the first optimum refreshes a simplex that collapsed early
    let (p, problem) = best(problem, simplex)?;
    let simplex = vec![
        p.clone(),
        vec![p[0] + 0.05 * (1.0 + p[0].abs()), p[1]],
        vec![p[0], p[1] * 1.05],
    ];
    let (p, _) = best(problem, simplex)?;
    let (a, b) = Probit::clamp(&p);
    let (theta, beta) = ((-a / b).exp(), 1.0 / b);
    let at_bound = beta <= BETA_MIN * (1.0 + 1e-6) || beta >= BETA_MAX * (1.0 - 1e-6);
    Ok(LognormalFit {
        theta,
        beta,
        log_likelihood: -neg_log_likelihood(theta, beta, im, runs, exceed),
        at_bound,
    })
}

/// A two-sided interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Interval {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

/// The bootstrap over records.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BootstrapIntervals {
    /// Percentile interval of θ.
    pub theta: Interval,
    /// Percentile interval of β.
    pub beta: Interval,
    /// Its confidence.
    pub confidence: f64,
    /// Resamples drawn.
    pub resamples: usize,
    /// Resamples with no fit (no exceedance or all exceed in the resample): left out.
    pub failed: usize,
    /// The fitted P(exceed) at each point of `band_im`: the interval at each.
    #[serde(skip)]
    pub band: Vec<Interval>,
}

/// Sample quantile, Hyndman & Fan definition 7, of sorted `v`.
pub(crate) fn quantile(v: &[f64], p: f64) -> f64 {
    let h = (v.len() - 1) as f64 * p;
    let (i, f) = (h.floor() as usize, h - h.floor());
    if i + 1 < v.len() {
        v[i] + f * (v[i + 1] - v[i])
    } else {
        v[i]
    }
}

/// Bootstrap over records: `outcomes[r][j]` is whether record r exceeds at stripe j
/// (`None`: the limit state does not apply — counted as not run). `resamples` sets of records
/// drawn with replacement by a PCG-64 generator seeded with `seed` (the same seed, the same
/// intervals on any number of threads); each refitted; the percentile interval at
/// `confidence`, and of P(exceed) at each `band_im`.
pub fn bootstrap(
    outcomes: &[Vec<Option<bool>>],
    im: &[f64],
    resamples: usize,
    seed: u64,
    confidence: f64,
    band_im: &[f64],
) -> Option<BootstrapIntervals> {
    let n = outcomes.len();
    if n == 0 || resamples == 0 {
        return None;
    }
    let mut rng = Pcg64::seed_from_u64(seed);
    // (n ≤ millions: the modulo bias of next_u64 % n is below n / 2⁶⁴, nothing)
    let draws: Vec<Vec<usize>> = (0..resamples)
        .map(|_| {
            (0..n)
                .map(|_| (rng.next_u64() % n as u64) as usize)
                .collect()
        })
        .collect();
    let fits: Vec<Option<LognormalFit>> = draws
        .par_iter()
        .map(|pick| {
            let (runs, exceed) = counts(outcomes, im.len(), pick);
            fit_lognormal(im, &runs, &exceed).ok()
        })
        .collect();
    let ok: Vec<LognormalFit> = fits.iter().flatten().copied().collect();
    if ok.len() < 2 {
        return None;
    }
    let (lo_p, hi_p) = (0.5 * (1.0 - confidence), 0.5 * (1.0 + confidence));
    let interval = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        Interval {
            lo: quantile(&v, lo_p),
            hi: quantile(&v, hi_p),
        }
    };
    let band = band_im
        .iter()
        .map(|&x| interval(ok.iter().map(|f| f.probability(x)).collect()))
        .collect();
    Some(BootstrapIntervals {
        theta: interval(ok.iter().map(|f| f.theta).collect()),
        beta: interval(ok.iter().map(|f| f.beta).collect()),
        confidence,
        resamples,
        failed: resamples - ok.len(),
        band,
    })
}

/// Runs and exceedances per stripe over the records `pick` (with repetition).
pub fn counts(
    outcomes: &[Vec<Option<bool>>],
    stripes: usize,
    pick: &[usize],
) -> (Vec<usize>, Vec<usize>) {
    let mut runs = vec![0; stripes];
    let mut exceed = vec![0; stripes];
    for &r in pick {
        for (j, o) in outcomes[r].iter().enumerate().take(stripes) {
            if let Some(e) = o {
                runs[j] += 1;
                exceed[j] += usize::from(*e);
            }
        }
    }
    (runs, exceed)
}
