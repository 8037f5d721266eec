//! Fragility (issue 28): how likely pounding — and a storey's ductility, drift or a floor's
//! acceleration beyond a limit, with and without pounding — is at each shaking intensity.
//!
//! A multi-stripe analysis: every record of the suite is scaled to each stripe of the
//! intensity measure (factor = level / the record's IM, [`im`]) and run through the one
//! driver of a run ([`simulate_checked`]: with and without contact), all runs in parallel
//! (rayon). Per run the numbers the limit states need are kept ([`RunOutcome`]); per limit
//! state and model the counts of exceedance per stripe, their lognormal fit by maximum
//! likelihood and bootstrap intervals over records ([`fit`]); and from the runs without
//! contact, P(pounding | IM, gap) for every gap at once ([`pounding`]). Files: [`write`];
//! text: [`report`]; pictures: `crate::figures::fragility`.
//!
//! Not done: incremental dynamic analysis (hunt-and-fill), and resuming or sharding a study as
//! sweeps do (a study runs at once; README, "Fragility").

pub mod fit;
pub mod im;
pub mod pounding;
pub mod report;
pub mod write;

use rayon::prelude::*;

use crate::analysis::simulate::{Report, simulate_checked};
use crate::input::fragility::{FragilityStudy, LimitKind, LimitState};
use crate::input::scenario::ScenarioError;
use crate::integrate::SolveError;
pub use fit::{BootstrapIntervals, FitError, Interval, LognormalFit};
pub use pounding::{GapForTarget, PoundingTable};

/// Why a study could not be run.
#[derive(Debug, thiserror::Error)]
pub enum FragilityError {
    /// A record's IM is not positive (a record of zeros): it cannot be scaled to a stripe.
    #[error(
        "record {index} ({file}): its {measure} is {value} m/s²: it cannot be scaled to a stripe"
    )]
    ZeroIntensity {
        /// 1-based.
        index: usize,
        /// File.
        file: String,
        /// The measure.
        measure: String,
        /// Its value.
        value: f64,
    },
    /// A record's scenario could not be formed.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A run failed.
    #[error("record {index} ({file}) at stripe {stripe}: {source}")]
    Solve {
        /// 1-based record.
        index: usize,
        /// File.
        file: String,
        /// 1-based stripe.
        stripe: usize,
        /// Why.
        source: Box<SolveError>,
    },
    /// The thread pool could not be built.
    #[error("cannot start {0} worker threads")]
    Threads(usize),
}

/// With contact (index 0) or without (1).
pub const MODELS: [&str; 2] = ["with", "without"];

/// What the limit states need from one run (SI units). `[s][m]`: structure s (0, 1), model
/// m (0 with contact, 1 without).
#[derive(Debug, Clone, PartialEq)]
pub struct RunOutcome {
    /// 0-based record.
    pub record: usize,
    /// 0-based stripe.
    pub stripe: usize,
    /// The factor on the record.
    pub factor: f64,
    /// The time-history required separation at each contact level (run without contact), m.
    pub required: Vec<f64>,
    /// Contact episodes over all levels (run with contact).
    pub impacts: usize,
    /// Peak contact force over all levels, N.
    pub peak_force: f64,
    /// Peak storey ductility demand (`None`: no yielding storeys).
    pub ductility: [[Option<f64>; 2]; 2],
    /// Peak storey drift ratio over the floors (drift / storey height).
    pub drift_ratio: [[f64; 2]; 2],
    /// Peak absolute floor acceleration over the floors, m/s².
    pub floor_acceleration: [[f64; 2]; 2],
    /// The self-check (`None`: not checked).
    pub converged: Option<bool>,
    /// The run's warnings.
    pub warnings: Vec<String>,
}

impl RunOutcome {
    /// The numbers of `report`.
    pub fn of(report: &Report, record: usize, stripe: usize, factor: f64) -> RunOutcome {
        let s = &report.structures;
        let per = |f: &dyn Fn(usize, usize) -> f64| [0, 1].map(|i| [0, 1].map(|m| f(i, m)));
        RunOutcome {
            record,
            stripe,
            factor,
            required: report.levels.iter().map(|l| l.required_gap).collect(),
            impacts: report.contact.impacts,
            peak_force: report.contact.peak_force,
            ductility: [0, 1].map(|i| [s[i].peak_ductility, s[i].peak_ductility_no_contact]),
            drift_ratio: per(&|i, m| {
                s[i].peak_drift_ratios()
                    .iter()
                    .map(|d| d[m] / 100.0)
                    .fold(0.0, f64::max)
            }),
            floor_acceleration: per(&|i, m| {
                s[i].floors
                    .iter()
                    .map(|f| {
                        if m == 0 {
                            f.peak_acceleration
                        } else {
                            f.peak_acceleration_no_contact
                        }
                    })
                    .fold(0.0, f64::max)
            }),
            converged: report.accuracy.converged,
            warnings: report.warnings.clone(),
        }
    }

    /// Whether the run exceeds `ls` in model `m` (0 with contact, 1 without), with the
    /// scenario's gaps `gaps` (m, per level); `None` where the limit state does not apply
    /// (a contact force without contact, a ductility of an elastic structure).
    pub fn exceeds(&self, ls: &LimitState, m: usize, gaps: &[f64]) -> Option<bool> {
        let over = |v: [[f64; 2]; 2]| {
            let d = match ls.structure {
                Some(s) => v[s][m],
                None => v[0][m].max(v[1][m]),
            };
            d > ls.value
        };
        match ls.kind {
            // with contact: the run has an impact; without: the relative displacement passes
            // the gap at some level (the same event: before the first impact the two runs are
            // one, tested)
            LimitKind::Pounding => Some(if m == 0 {
                self.impacts > 0
            } else {
                self.required.iter().zip(gaps).any(|(r, g)| r > g)
            }),
            LimitKind::ContactForce => (m == 0).then_some(self.peak_force > ls.value),
            LimitKind::Ductility => {
                let pick: Vec<f64> = match ls.structure {
                    Some(s) => self.ductility[s][m].into_iter().collect(),
                    None => (0..2).filter_map(|s| self.ductility[s][m]).collect(),
                };
                (!pick.is_empty()).then(|| pick.iter().any(|d| *d > ls.value))
            }
            LimitKind::DriftRatio => Some(over(self.drift_ratio)),
            LimitKind::FloorAcceleration => Some(over(self.floor_acceleration)),
        }
    }
}

/// The counts and fit of one limit state in one model.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Index into the study's limit states.
    pub limit_state: usize,
    /// 0 with contact, 1 without.
    pub model: usize,
    /// Runs per stripe (where the limit state applies).
    pub runs: Vec<usize>,
    /// Exceedances per stripe.
    pub exceedances: Vec<usize>,
    /// The lognormal fit (θ in the study's IM units).
    pub fit: Result<LognormalFit, FitError>,
    /// Bootstrap intervals (with its band at [`FragilityRun::band_im`]).
    pub intervals: Option<BootstrapIntervals>,
}

/// A study's results.
#[derive(Debug, Clone)]
pub struct FragilityRun {
    /// The study.
    pub study: FragilityStudy,
    /// Each record's IM (unscaled), m/s².
    pub record_im: Vec<f64>,
    /// Every run, record-major (`record * stripes + stripe`).
    pub outcomes: Vec<RunOutcome>,
    /// One per limit state and model where it applies.
    pub curves: Vec<Curve>,
    /// P(pounding | IM, gap) from the runs without contact.
    pub pounding: PoundingTable,
    /// The gap for the target probability, when asked.
    pub target_gap: Option<GapForTarget>,
    /// The IMs (study units) at which the fitted curves and bands are drawn.
    pub band_im: Vec<f64>,
}

impl FragilityRun {
    /// The stripes in the study's units.
    pub fn stripes(&self) -> Vec<f64> {
        let u = self.study.units.factor();
        self.study.stripes.iter().map(|s| s / u).collect()
    }

    /// Runs that did not pass the self-check.
    pub fn unconverged(&self) -> usize {
        self.outcomes
            .iter()
            .filter(|o| o.converged == Some(false))
            .count()
    }
}

/// Run a study: every record at every stripe, in parallel on `jobs` threads (default: every
/// CPU), then the counts, fits and P(pounding).
pub fn run(study: &FragilityStudy, jobs: Option<usize>) -> Result<FragilityRun, FragilityError> {
    match jobs {
        None => run_all(study),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|_| FragilityError::Threads(n))?
            .install(|| run_all(study)),
    }
}

fn run_all(study: &FragilityStudy) -> Result<FragilityRun, FragilityError> {
    let sc = &study.scenario;
    let suite = sc
        .suite
        .as_ref()
        .expect("a checked study has a suite (input::fragility)");
    let record_im: Vec<f64> = suite
        .records
        .iter()
        .map(|r| im::intensity(&study.measure, &r.record))
        .collect();
    for (i, v) in record_im.iter().enumerate() {
        if !(v.is_finite() && *v > 0.0) {
            return Err(FragilityError::ZeroIntensity {
                index: i + 1,
                file: study.record_names[i].clone(),
                measure: study.measure.label(),
                value: *v,
            });
        }
    }
    let ns = study.stripes.len();
    let jobs: Vec<(usize, usize)> = (0..record_im.len())
        .flat_map(|r| (0..ns).map(move |j| (r, j)))
        .collect();
    let outcomes: Vec<RunOutcome> = jobs
        .par_iter()
        .map(|&(r, j)| {
            let f = study.stripes[j] / record_im[r];
            let member = suite.member_scenario(sc, r, f)?;
            let report =
                simulate_checked(&member, study.check).map_err(|e| FragilityError::Solve {
                    index: r + 1,
                    file: study.record_names[r].clone(),
                    stripe: j + 1,
                    source: Box::new(e),
                })?;
            Ok(RunOutcome::of(&report, r, j, f))
        })
        .collect::<Result<_, FragilityError>>()?;
    Ok(assemble(study.clone(), record_im, outcomes))
}

/// The counts, fits and P(pounding) of a study's runs (`outcomes` record-major).
pub fn assemble(
    study: FragilityStudy,
    record_im: Vec<f64>,
    outcomes: Vec<RunOutcome>,
) -> FragilityRun {
    let u = study.units.factor();
    let stripes: Vec<f64> = study.stripes.iter().map(|s| s / u).collect();
    let ns = stripes.len();
    let nr = record_im.len();
    let gaps: Vec<f64> = study
        .scenario
        .contact
        .levels
        .iter()
        .map(|l| l.gap)
        .collect();
    let (lo, hi) = (stripes[0], stripes[ns - 1]);
    let (lo, hi) = (lo * 0.5, hi * 1.5);
    let band_im: Vec<f64> = (0..=120)
        .map(|k| lo * (hi / lo).powf(k as f64 / 120.0))
        .collect();
    let mut curves = Vec::new();
    for (l, ls) in study.limit_states.iter().enumerate() {
        for m in 0..2 {
            let table: Vec<Vec<Option<bool>>> = (0..nr)
                .map(|r| {
                    (0..ns)
                        .map(|j| outcomes[r * ns + j].exceeds(ls, m, &gaps))
                        .collect()
                })
                .collect();
            if table.iter().flatten().all(Option::is_none) {
                continue;
            }
            let all: Vec<usize> = (0..nr).collect();
            let (runs, exceedances) = fit::counts(&table, ns, &all);
            let fit = fit::fit_lognormal(&stripes, &runs, &exceedances);
            let intervals = fit.is_ok().then(|| {
                fit::bootstrap(
                    &table,
                    &stripes,
                    study.bootstrap,
                    study.seed,
                    study.confidence,
                    &band_im,
                )
            });
            curves.push(Curve {
                limit_state: l,
                model: m,
                runs,
                exceedances,
                fit,
                intervals: intervals.flatten(),
            });
        }
    }
    let top = crate::input::fragility::top_gap(&study.scenario);
    let critical: Vec<Vec<f64>> = (0..ns)
        .map(|j| {
            (0..nr)
                .map(|r| {
                    pounding::critical_gap(
                        &outcomes[r * ns + j].required,
                        &gaps,
                        top,
                        study.gap_mode,
                    )
                })
                .collect()
        })
        .collect();
    let pounding = PoundingTable::new(&stripes, &study.gaps, &critical);
    let target_gap = study
        .target
        .map(|t| pounding::gap_for_target(&critical[t.stripe], t.probability, t.im / u));
    FragilityRun {
        study,
        record_im,
        outcomes,
        curves,
        pounding,
        target_gap,
        band_im,
    }
}
