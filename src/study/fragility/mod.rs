//! Fragility (issue 28): how likely pounding — and a storey's ductility, drift or a floor's
//! acceleration beyond a limit, with and without pounding — is at each shaking intensity.
//!
//! A multi-stripe analysis: every record of the suite is scaled to each stripe of the
//! intensity measure (factor = level / the record's IM, [`im`]) and run through the one
//! driver of a run ([`simulate_checked`]: with and without contact), all runs in parallel
//! (rayon). Per run the numbers the limit states need are kept ([`RunOutcome`]); per limit
//! state and model the counts of exceedance per stripe, their lognormal fit by maximum
//! likelihood and bootstrap intervals over records ([`fit`]); and from the runs without
//! contact, P(pounding | IM, gap) for every gap at once ([`pounding`]). Files: [`mod@write`];
//! text: [`report`]; pictures: `figures::fragility`.
//!
//! Or an incremental dynamic analysis ([`ida`]): each record scaled up until every limit state
//! is exceeded, each record's capacity bracketed (hunt and fill), the lognormal of the
//! capacities.
//!
//! Every run can be journaled as it finishes and found again ([`RunStore`], [`journal`]): a
//! study stopped midway resumes without rerunning finished runs, and its parts (`--shard`)
//! run on different machines and are joined by [`journal::merge`].

pub mod fit;
pub mod ida;
pub mod im;
pub mod journal;
pub mod pounding;
pub mod report;
pub mod write;

use rayon::prelude::*;

use crate::analysis::simulate::{
    Report, RowReport, StructureReport, simulate_checked, simulate_row_checked,
};
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
    /// Joining parts: a run is in none of them.
    #[error(
        "merge: run {run} of record {record} (IM = {im}) is in none of the parts: run every part \
         (--shard K/N) to its end first"
    )]
    Missing {
        /// 1-based record.
        record: usize,
        /// 1-based run of the record (its stripe).
        run: usize,
        /// Its intensity, study units.
        im: f64,
    },
    /// The journal could not be opened, read or written, or the parts do not join.
    #[error(transparent)]
    Journal(#[from] crate::study::sweep::SweepError),
}

/// With contact (index 0) or without (1).
pub const MODELS: [&str; 2] = ["with", "without"];

/// What the limit states need from one run (SI units). Per pair (row order; one for a pair of
/// structures) and per structure (row order) `[m]`: model m (0 with contact, 1 without).
#[derive(Debug, Clone, PartialEq)]
pub struct RunOutcome {
    /// 0-based record.
    pub record: usize,
    /// 0-based stripe (IDA: the record's k-th run, in the order run).
    pub stripe: usize,
    /// The intensity of the scaled record, m/s².
    pub im: f64,
    /// The factor on the record.
    pub factor: f64,
    /// Per pair, the time-history required separation at each of its contact levels (run
    /// without contact), m.
    pub required: Vec<Vec<f64>>,
    /// Per pair, contact episodes over its levels (run with contact).
    pub impacts: Vec<usize>,
    /// Per pair, the peak contact force over its levels, N.
    pub peak_force: Vec<f64>,
    /// Per structure, the peak storey ductility demand (`None`: no yielding storeys).
    pub ductility: Vec<[Option<f64>; 2]>,
    /// Per structure, the peak storey drift ratio over the floors (drift / storey height).
    pub drift_ratio: Vec<[f64; 2]>,
    /// Per structure, the peak absolute floor acceleration over the floors, m/s².
    pub floor_acceleration: Vec<[f64; 2]>,
    /// The self-check (`None`: not checked).
    pub converged: Option<bool>,
    /// The run's warnings.
    pub warnings: Vec<String>,
}

/// Per structure [with, without]: peak storey drift ratio and peak floor acceleration.
fn structure_peaks(s: &StructureReport) -> ([Option<f64>; 2], [f64; 2], [f64; 2]) {
    let drift = [0, 1].map(|m| {
        s.peak_drift_ratios()
            .iter()
            .map(|d| d[m] / 100.0)
            .fold(0.0, f64::max)
    });
    let acc = [0, 1].map(|m| {
        s.floors
            .iter()
            .map(|f| {
                if m == 0 {
                    f.peak_acceleration
                } else {
                    f.peak_acceleration_no_contact
                }
            })
            .fold(0.0, f64::max)
    });
    ([s.peak_ductility, s.peak_ductility_no_contact], drift, acc)
}

impl RunOutcome {
    /// The numbers of a pair's `report`.
    pub fn of(report: &Report, record: usize, stripe: usize, im: f64, factor: f64) -> RunOutcome {
        let (ductility, drift_ratio, floor_acceleration) = per_structure(report.structures.iter());
        RunOutcome {
            record,
            stripe,
            im,
            factor,
            required: vec![report.levels.iter().map(|l| l.required_gap).collect()],
            impacts: vec![report.contact.impacts],
            peak_force: vec![report.contact.peak_force],
            ductility,
            drift_ratio,
            floor_acceleration,
            converged: report.accuracy.converged,
            warnings: report.warnings.clone(),
        }
    }

    /// The numbers of a row's `report` (per pair and per structure).
    pub fn of_row(
        report: &RowReport,
        record: usize,
        stripe: usize,
        im: f64,
        factor: f64,
    ) -> RunOutcome {
        let (ductility, drift_ratio, floor_acceleration) = per_structure(report.structures.iter());
        let p = &report.pairs;
        RunOutcome {
            record,
            stripe,
            im,
            factor,
            required: p
                .iter()
                .map(|p| p.levels.iter().map(|l| l.required_gap).collect())
                .collect(),
            impacts: p.iter().map(|p| p.contact.impacts).collect(),
            peak_force: p.iter().map(|p| p.contact.peak_force).collect(),
            ductility,
            drift_ratio,
            floor_acceleration,
            converged: report.accuracy.converged,
            warnings: report.warnings.clone(),
        }
    }

    /// The pairs `ls` looks at: its pair, or every pair.
    fn pairs_of(&self, ls: &LimitState) -> std::ops::Range<usize> {
        match ls.pair {
            Some(p) => p..p + 1,
            None => 0..self.impacts.len(),
        }
    }

    /// The structures `ls` looks at: its structure, or every structure.
    fn structures_of(&self, ls: &LimitState) -> std::ops::Range<usize> {
        match ls.structure {
            Some(s) => s..s + 1,
            None => 0..self.drift_ratio.len(),
        }
    }

    /// The demand `ls` compares with its threshold, in model `m` (SI; for `pounding` the
    /// largest ratio of required separation to gap over the levels of its pairs, pounding
    /// beyond 1, from the run without contact only; `gaps` per pair and level, m); `None`
    /// where it does not apply.
    pub fn demand(&self, ls: &LimitState, m: usize, gaps: &[Vec<f64>]) -> Option<f64> {
        let most = |v: &[[f64; 2]]| self.structures_of(ls).map(|s| v[s][m]).fold(0.0, f64::max);
        match ls.kind {
            LimitKind::Pounding => (m == 1).then(|| {
                self.pairs_of(ls)
                    .flat_map(|p| self.required[p].iter().zip(&gaps[p]))
                    .map(|(r, g)| {
                        if *g > 0.0 {
                            r / g
                        } else if *r > 0.0 {
                            f64::INFINITY
                        } else {
                            0.0
                        }
                    })
                    .fold(0.0, f64::max)
            }),
            LimitKind::ContactForce => (m == 0).then(|| {
                self.pairs_of(ls)
                    .map(|p| self.peak_force[p])
                    .fold(0.0, f64::max)
            }),
            LimitKind::Ductility => {
                let v: Vec<f64> = self
                    .structures_of(ls)
                    .filter_map(|s| self.ductility[s][m])
                    .collect();
                (!v.is_empty()).then(|| v.iter().copied().fold(0.0, f64::max))
            }
            LimitKind::DriftRatio => Some(most(&self.drift_ratio)),
            LimitKind::FloorAcceleration => Some(most(&self.floor_acceleration)),
        }
    }

    /// Whether the run exceeds `ls` in model `m` (0 with contact, 1 without), with the
    /// scenario's gaps `gaps` (m, per pair and level); `None` where the limit state does not
    /// apply (a contact force without contact, a ductility of an elastic structure).
    pub fn exceeds(&self, ls: &LimitState, m: usize, gaps: &[Vec<f64>]) -> Option<bool> {
        let over = |v: &[[f64; 2]]| self.structures_of(ls).any(|s| v[s][m] > ls.value);
        match ls.kind {
            // with contact: the run has an impact; without: the relative displacement passes
            // the gap at some level (the same event: before the first impact the two runs are
            // one, tested); of a row, at any of its pairs (a pair's: that pair's)
            LimitKind::Pounding => Some(if m == 0 {
                self.pairs_of(ls).any(|p| self.impacts[p] > 0)
            } else {
                self.pairs_of(ls)
                    .any(|p| self.required[p].iter().zip(&gaps[p]).any(|(r, g)| r > g))
            }),
            LimitKind::ContactForce => {
                (m == 0).then(|| self.pairs_of(ls).any(|p| self.peak_force[p] > ls.value))
            }
            LimitKind::Ductility => {
                let pick: Vec<f64> = self
                    .structures_of(ls)
                    .filter_map(|s| self.ductility[s][m])
                    .collect();
                (!pick.is_empty()).then(|| pick.iter().any(|d| *d > ls.value))
            }
            LimitKind::DriftRatio => Some(over(&self.drift_ratio)),
            LimitKind::FloorAcceleration => Some(over(&self.floor_acceleration)),
        }
    }
}

/// Per structure: ductility, drift ratio and floor acceleration, [with, without].
#[allow(clippy::type_complexity)]
fn per_structure<'a>(
    structures: impl Iterator<Item = &'a StructureReport>,
) -> (Vec<[Option<f64>; 2]>, Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let mut out = (Vec::new(), Vec::new(), Vec::new());
    for s in structures {
        let (d, r, a) = structure_peaks(s);
        out.0.push(d);
        out.1.push(r);
        out.2.push(a);
    }
    out
}

/// The counts and fit of one limit state in one model.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Index into the study's limit states.
    pub limit_state: usize,
    /// 0 with contact, 1 without.
    pub model: usize,
    /// The intensities of the counts, study units: the stripes; in an IDA the records'
    /// capacities, increasing (the empirical fragility).
    pub im: Vec<f64>,
    /// Runs per stripe (where the limit state applies); IDA: the records.
    pub runs: Vec<usize>,
    /// Exceedances per stripe; IDA: the records whose capacity is at most `im`.
    pub exceedances: Vec<usize>,
    /// The lognormal fit (θ in the study's IM units).
    pub fit: Result<LognormalFit, FitError>,
    /// Bootstrap intervals (with its band at [`FragilityRun::band_im`]).
    pub intervals: Option<BootstrapIntervals>,
    /// IDA: each record's capacity (m/s²).
    pub capacities: Option<Vec<ida::Capacity>>,
}

/// A study's results.
#[derive(Debug, Clone)]
pub struct FragilityRun {
    /// The study.
    pub study: FragilityStudy,
    /// Each record's IM (unscaled), m/s².
    pub record_im: Vec<f64>,
    /// Every run, record-major (stripes: `record * stripes + stripe`; IDA: each record's runs
    /// in the order run).
    pub outcomes: Vec<RunOutcome>,
    /// One per limit state and model where it applies.
    pub curves: Vec<Curve>,
    /// P(pounding) from the runs without contact (IDA: at the hunt's intensities that every
    /// record ran), per adjacent pair in row order (one for a pair of structures): each
    /// pair's own gap against its own required separations.
    pub pounding: Vec<PoundingTable>,
    /// The gap for the target probability, when asked: per pair (empty when not asked, or in
    /// an IDA when a record did not reach the target intensity).
    pub target_gap: Vec<GapForTarget>,
    /// The IMs (study units) at which the fitted curves and bands are drawn.
    pub band_im: Vec<f64>,
}

impl FragilityRun {
    /// The stripes in the study's units (empty in an IDA).
    pub fn stripes(&self) -> Vec<f64> {
        self.study.stripes_given.clone()
    }

    /// Runs that did not pass the self-check.
    pub fn unconverged(&self) -> usize {
        self.outcomes
            .iter()
            .filter(|o| o.converged == Some(false))
            .count()
    }

    /// The runs of record `r` (IDA: in the order run).
    pub fn record_runs(&self, r: usize) -> impl Iterator<Item = &RunOutcome> {
        self.outcomes.iter().filter(move |o| o.record == r)
    }
}

/// Where finished runs are kept and found again: a journal (resume, shards) or nothing.
pub trait RunStore: Sync {
    /// The run stored under `key`, if any.
    fn get(&self, key: usize) -> Option<RunOutcome>;
    /// Keep a finished run under `key`.
    fn put(&self, key: usize, run: &RunOutcome) -> Result<(), FragilityError>;
    /// Whether a run not found may be computed (not when joining parts).
    fn may_compute(&self) -> bool {
        true
    }
}

/// Keeps nothing: every run is computed.
pub struct NoStore;

impl RunStore for NoStore {
    fn get(&self, _: usize) -> Option<RunOutcome> {
        None
    }
    fn put(&self, _: usize, _: &RunOutcome) -> Result<(), FragilityError> {
        Ok(())
    }
}

/// The number of tasks of a study, the unit of parallel work, of `--shard` and of a Dask
/// task: a run (record × stripe, task `record * stripes + stripe`), or in an IDA a record's
/// whole trace (task = record).
pub fn tasks(study: &FragilityStudy) -> usize {
    match &study.ida {
        Some(_) => study.record_names.len(),
        None => study.record_names.len() * study.stripes.len(),
    }
}

/// The record of task `task`.
pub fn task_record(study: &FragilityStudy, task: usize) -> usize {
    match &study.ida {
        Some(_) => task,
        None => task / study.stripes.len().max(1),
    }
}

/// The key of a run in a [`RunStore`]: its task (stripes), or `record * max_runs + k` for the
/// k-th run of a record's IDA.
pub fn run_key(study: &FragilityStudy, record: usize, k: usize) -> usize {
    match &study.ida {
        Some(i) => record * i.max_runs + k,
        None => record * study.stripes.len() + k,
    }
}

/// The task of the run stored under `key`.
pub fn key_task(study: &FragilityStudy, key: usize) -> usize {
    match &study.ida {
        Some(i) => key / i.max_runs,
        None => key,
    }
}

/// Each record's IM (unscaled), m/s²; refuses a record whose IM is not positive.
pub fn record_ims(study: &FragilityStudy) -> Result<Vec<f64>, FragilityError> {
    let suite = study
        .scenario
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
    Ok(record_im)
}

/// Record `r` scaled to intensity `x` (m/s²) and run with and without contact: its outcome as
/// run `k` of the record.
fn run_one(
    study: &FragilityStudy,
    record_im: &[f64],
    r: usize,
    k: usize,
    x: f64,
    store: &dyn RunStore,
) -> Result<RunOutcome, FragilityError> {
    let key = run_key(study, r, k);
    if let Some(o) = store.get(key)
        && o.record == r
        && o.stripe == k
        && o.im.to_bits() == x.to_bits()
    {
        return Ok(o);
    }
    if !store.may_compute() {
        return Err(FragilityError::Missing {
            record: r + 1,
            run: k + 1,
            im: x / study.units.factor(),
        });
    }
    let sc = &study.scenario;
    let suite = sc.suite.as_ref().expect("a checked study has a suite");
    let f = x / record_im[r];
    let member = suite.member_scenario(sc, r, f)?;
    let failed = |e| FragilityError::Solve {
        index: r + 1,
        file: study.record_names[r].clone(),
        stripe: k + 1,
        source: Box::new(e),
    };
    // (a row through the row's driver, with its self-check; a pair through the pair's)
    let o = if member.is_row() {
        let report = simulate_row_checked(&member, study.check).map_err(failed)?;
        RunOutcome::of_row(&report, r, k, x, f)
    } else {
        let report = simulate_checked(&member, study.check).map_err(failed)?;
        RunOutcome::of(&report, r, k, x, f)
    };
    store.put(key, &o)?;
    Ok(o)
}

/// The runs of task `task` ([`tasks`]): one run at a stripe, or a record's IDA trace; runs
/// found in `store` are not run again, new ones are put there.
pub fn run_task(
    study: &FragilityStudy,
    record_im: &[f64],
    task: usize,
    store: &dyn RunStore,
) -> Result<Vec<RunOutcome>, FragilityError> {
    match &study.ida {
        Some(settings) => ida::trace(study, settings, |k, x| {
            run_one(study, record_im, task, k, x, store)
        }),
        None => {
            let ns = study.stripes.len();
            let (r, j) = (task / ns, task % ns);
            Ok(vec![run_one(
                study,
                record_im,
                r,
                j,
                study.stripes[j],
                store,
            )?])
        }
    }
}

/// Run a study: every task, in parallel on `jobs` threads (default: every CPU), then the
/// counts, fits and P(pounding).
pub fn run(study: &FragilityStudy, jobs: Option<usize>) -> Result<FragilityRun, FragilityError> {
    let record_im = record_ims(study)?;
    let all: Vec<usize> = (0..tasks(study)).collect();
    let outcomes = run_tasks(study, &record_im, &all, jobs, &NoStore)?;
    Ok(assemble(study.clone(), record_im, outcomes))
}

/// The runs of `tasks` in parallel on `jobs` threads (default: every CPU), in task order.
pub fn run_tasks(
    study: &FragilityStudy,
    record_im: &[f64],
    tasks: &[usize],
    jobs: Option<usize>,
    store: &dyn RunStore,
) -> Result<Vec<RunOutcome>, FragilityError> {
    let go = || -> Result<Vec<RunOutcome>, FragilityError> {
        let parts: Vec<Vec<RunOutcome>> = tasks
            .par_iter()
            .map(|&t| run_task(study, record_im, t, store))
            .collect::<Result<_, _>>()?;
        Ok(parts.into_iter().flatten().collect())
    };
    match jobs {
        None => go(),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|_| FragilityError::Threads(n))?
            .install(go),
    }
}

/// The counts, fits and P(pounding) of a study's runs (`outcomes` record-major: stripes in
/// stripe order; IDA each record's runs in the order run).
pub fn assemble(
    study: FragilityStudy,
    record_im: Vec<f64>,
    outcomes: Vec<RunOutcome>,
) -> FragilityRun {
    if study.ida.is_some() {
        return assemble_ida(study, record_im, outcomes);
    }
    let stripes: Vec<f64> = study.stripes_given.clone();
    let ns = stripes.len();
    let nr = record_im.len();
    let gaps = scenario_gaps(&study);
    let band_im = band(stripes[0], stripes[ns - 1]);
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
                im: stripes.clone(),
                runs,
                exceedances,
                fit,
                intervals: intervals.flatten(),
                capacities: None,
            });
        }
    }
    // per pair: critical[p][stripe][record]
    let critical: Vec<Vec<Vec<f64>>> = (0..gaps.len())
        .map(|p| {
            (0..ns)
                .map(|j| {
                    (0..nr)
                        .map(|r| critical_of(&study, &outcomes[r * ns + j], p))
                        .collect()
                })
                .collect()
        })
        .collect();
    let pounding = critical
        .iter()
        .map(|c| PoundingTable::new(&stripes, &study.gaps, c))
        .collect();
    let target_gap = study.target.map_or_else(Vec::new, |t| {
        critical
            .iter()
            .map(|c| pounding::gap_for_target(&c[t.stripe], t.probability, stripes[t.stripe]))
            .collect()
    });
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

/// The scenario's gaps, m, per pair and level.
pub fn scenario_gaps(study: &FragilityStudy) -> Vec<Vec<f64>> {
    crate::input::fragility::pair_gaps(&study.scenario)
}

/// A run's critical gap (m) of pair `p` (0-based; 0 of a pair of structures) in the study's
/// gap mode: from the pair's own levels, gaps and (`scaled`) its gap at its highest level.
pub fn critical_of(study: &FragilityStudy, o: &RunOutcome, p: usize) -> f64 {
    let gaps = crate::input::fragility::pair_gaps(&study.scenario);
    let top = crate::input::fragility::pair_top_gaps(&study.scenario);
    pounding::critical_gap(&o.required[p], &gaps[p], top[p], study.gap_mode)
}

/// 121 log-spaced intensities from half of `lo` to 1.5 × `hi`.
fn band(lo: f64, hi: f64) -> Vec<f64> {
    let (lo, hi) = (lo * 0.5, hi * 1.5);
    (0..=120)
        .map(|k| lo * (hi / lo).powf(k as f64 / 120.0))
        .collect()
}

/// The hunt's intensities (m/s²) that every record ran: the common first runs of the traces
/// (each trace starts with its hunt, in increasing order; bracketing runs fall below its end).
pub fn common_hunt(outcomes: &[RunOutcome], records: usize) -> Vec<f64> {
    let mut common: Option<Vec<f64>> = None;
    for r in 0..records {
        let mut hunt: Vec<f64> = Vec::new();
        for o in outcomes.iter().filter(|o| o.record == r) {
            if hunt.last().is_some_and(|&x| o.im <= x) {
                break;
            }
            hunt.push(o.im);
        }
        common = Some(match common {
            None => hunt,
            Some(c) => c.into_iter().zip(hunt).map(|(a, _)| a).collect(),
        });
    }
    common.unwrap_or_default()
}

fn assemble_ida(
    study: FragilityStudy,
    record_im: Vec<f64>,
    outcomes: Vec<RunOutcome>,
) -> FragilityRun {
    let u = study.units.factor();
    let nr = record_im.len();
    let gaps = scenario_gaps(&study);
    let ims: Vec<f64> = outcomes.iter().map(|o| o.im / u).collect();
    let lo = ims.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = ims.iter().copied().fold(0.0, f64::max);
    let band_im = if lo.is_finite() && hi > 0.0 {
        band(lo, hi)
    } else {
        Vec::new()
    };
    let by_record: Vec<Vec<RunOutcome>> = (0..nr)
        .map(|r| outcomes.iter().filter(|o| o.record == r).cloned().collect())
        .collect();
    let mut curves = Vec::new();
    if let Some(first) = outcomes.first() {
        for (l, m) in ida::pairs(&study, first, &gaps) {
            let caps: Vec<ida::Capacity> = by_record
                .iter()
                .map(|runs| ida::bracket(&study, runs, &gaps, l, m))
                .collect();
            let mut reached: Vec<f64> = caps
                .iter()
                .filter_map(|c| c.value())
                .map(|v| v / u)
                .collect();
            reached.sort_by(f64::total_cmp);
            let exceedances = (1..=reached.len()).collect();
            let cf = ida::fit_capacities(
                caps,
                u,
                study.bootstrap,
                study.seed,
                study.confidence,
                &band_im,
            );
            curves.push(Curve {
                limit_state: l,
                model: m,
                runs: vec![nr; reached.len()],
                im: reached,
                exceedances,
                fit: cf.fit,
                intervals: cf.intervals,
                capacities: Some(cf.capacities),
            });
        }
    }
    // P(pounding) at the hunt's intensities every record ran (the same for all records)
    let levels = common_hunt(&outcomes, nr);
    let levels_u: Vec<f64> = levels.iter().map(|x| x / u).collect();
    let pounding = (0..gaps.len())
        .map(|p| {
            let critical: Vec<Vec<f64>> = (0..levels.len())
                .map(|j| {
                    by_record
                        .iter()
                        .map(|runs| critical_of(&study, &runs[j], p))
                        .collect()
                })
                .collect();
            PoundingTable::new(&levels_u, &study.gaps, &critical)
        })
        .collect();
    // the target: each record's critical gap at the target intensity, linear between its runs
    // (per pair; none when a record's runs did not reach it)
    let target_gap = study
        .target
        .and_then(|t| {
            (0..gaps.len())
                .map(|p| {
                    let at: Option<Vec<f64>> = by_record
                        .iter()
                        .map(|runs| {
                            let pts: Vec<(f64, f64)> = runs
                                .iter()
                                .map(|o| (o.im, critical_of(&study, o, p)))
                                .collect();
                            ida::critical_gap_at(&pts, t.im)
                        })
                        .collect();
                    at.map(|c| pounding::gap_for_target(&c, t.probability, t.im / u))
                })
                .collect::<Option<Vec<_>>>()
        })
        .unwrap_or_default();
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
