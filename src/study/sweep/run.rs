//! Running a sweep: the cases of one part, in parallel (rayon), each row journaled as soon as
//! it is finished, then `results.csv` sorted and written atomically.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::journal::Journal;
use super::results;
use super::shard::Shard;
use super::{Sweep, SweepError};

/// How to run a sweep.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// Output directory (created if missing).
    pub out_dir: PathBuf,
    /// Worker threads (≥ 1).
    pub jobs: usize,
    /// The part of the grid to run.
    pub shard: Shard,
    /// Self-check every case (`simulate_checked`: a second run at a 100× tighter tolerance,
    /// recorded in the `check_max_change` and `converged` columns). The default of
    /// `pounding sweep`; `--no-check` turns it off and the rows say `unchecked`.
    pub check: bool,
}

/// What a run did.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// The results table written (`results.csv`, or the part's file).
    pub results: PathBuf,
    /// Cases in this part.
    pub cases: usize,
    /// Cases found finished in the journal (not recomputed).
    pub resumed: usize,
    /// Cases computed now.
    pub computed: usize,
    /// Failed cases (from the journal and now).
    pub failed: usize,
    /// The first failed case and its status, if any.
    pub first_failure: Option<(usize, String)>,
    /// Journal lines dropped as torn or damaged (their cases were recomputed).
    pub dropped: usize,
    /// Cases computed now whose run gave a warning (e.g. stiff contact for the step).
    pub warned: usize,
    /// The lowest such case and its first warning.
    pub first_warning: Option<(usize, String)>,
    /// Wall-clock time of the computation, s.
    pub seconds: f64,
    /// Self-check of the part's cases that did not fail (from the journal, so resumed cases
    /// count too).
    pub check: CheckCounts,
}

/// How the cases of a sweep fared in their self-check (column `converged`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CheckCounts {
    /// Checked and converged within 1 %.
    pub converged: usize,
    /// Checked and not converged.
    pub not_converged: usize,
    /// Not self-checked (run with `--no-check`).
    pub unchecked: usize,
    /// The lowest not-converged case and its `check_max_change` (as written; empty if the
    /// check run failed).
    pub first_not_converged: Option<(usize, String)>,
}

impl CheckCounts {
    /// Count the `converged` column of finished rows (`(case, line)`, in case order) whose
    /// last `codes` columns are code columns ([`results::CODE_FIELDS`]).
    pub fn of_rows<'a>(rows: impl Iterator<Item = (usize, &'a str)>, codes: usize) -> CheckCounts {
        let mut c = CheckCounts::default();
        for (case, line) in rows {
            let Some(mut f) = results::parse_csv_line(line) else {
                continue;
            };
            f.truncate(f.len().saturating_sub(codes));
            let (Some(conv), Some(change)) = (f.last(), f.len().checked_sub(2).map(|i| &f[i]))
            else {
                continue;
            };
            match conv.as_str() {
                "true" => c.converged += 1,
                "false" => {
                    c.not_converged += 1;
                    if c.first_not_converged.is_none() {
                        c.first_not_converged = Some((case, change.clone()));
                    }
                }
                results::UNCHECKED => c.unchecked += 1,
                _ => {} // a failed case
            }
        }
        c
    }
}

/// Receives progress. Implementations must be cheap: they are called once per case.
pub trait Progress {
    /// `pending` cases are about to be computed; `resumed` were finished before.
    fn start(&mut self, pending: usize, resumed: usize);
    /// One more case finished.
    fn advance(&mut self, failed: bool);
    /// All done.
    fn finish(&mut self);
}

/// Progress that shows nothing.
pub struct Silent;

impl Progress for Silent {
    fn start(&mut self, _: usize, _: usize) {}
    fn advance(&mut self, _: bool) {}
    fn finish(&mut self) {}
}

/// Progress on standard error: a bar with rate and ETA on a terminal, plain lines (every
/// 10 s, and at the end) otherwise.
pub struct StderrProgress {
    bar: Option<indicatif::ProgressBar>,
    total: usize,
    done: usize,
    failed: usize,
    started: Instant,
    last_line: Instant,
}

impl StderrProgress {
    /// A bar when standard error is a terminal, plain lines otherwise.
    pub fn new() -> StderrProgress {
        StderrProgress {
            bar: None,
            total: 0,
            done: 0,
            failed: 0,
            started: Instant::now(),
            last_line: Instant::now(),
        }
    }

    fn line(&self) {
        let el = self.started.elapsed().as_secs_f64();
        let eta = if self.done > 0 {
            el / self.done as f64 * (self.total - self.done) as f64
        } else {
            f64::NAN
        };
        eprintln!(
            "sweep: {}/{} cases ({:.0} %), {} failed, {:.0} s elapsed{}",
            self.done,
            self.total,
            100.0 * self.done as f64 / self.total.max(1) as f64,
            self.failed,
            el,
            if eta.is_finite() && self.done < self.total {
                format!(", about {eta:.0} s left")
            } else {
                String::new()
            }
        );
    }
}

impl Default for StderrProgress {
    fn default() -> Self {
        StderrProgress::new()
    }
}

impl Progress for StderrProgress {
    fn start(&mut self, pending: usize, resumed: usize) {
        self.total = pending;
        self.started = Instant::now();
        self.last_line = Instant::now();
        if resumed > 0 {
            eprintln!("sweep: {resumed} cases already done (resuming), {pending} to run");
        }
        if std::io::stderr().is_terminal() && pending > 0 {
            let bar = indicatif::ProgressBar::new(pending as u64);
            let style = indicatif::ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {wide_bar} {pos}/{len} cases, {per_sec}, ETA {eta} {msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
            bar.set_style(style);
            bar.enable_steady_tick(Duration::from_millis(200));
            self.bar = Some(bar);
        } else if pending > 0 {
            self.line();
        }
    }

    fn advance(&mut self, failed: bool) {
        self.done += 1;
        if failed {
            self.failed += 1;
        }
        match &self.bar {
            Some(b) => {
                b.inc(1);
                if failed {
                    b.set_message(format!("({} failed)", self.failed));
                }
            }
            None => {
                if self.last_line.elapsed() >= Duration::from_secs(10) {
                    self.last_line = Instant::now();
                    self.line();
                }
            }
        }
    }

    fn finish(&mut self) {
        match self.bar.take() {
            Some(b) => b.finish_and_clear(),
            None if self.total > 0 => self.line(),
            None => {}
        }
    }
}

/// One computed case.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// The results row (without line break).
    pub line: String,
    /// Did the case fail?
    pub failed: bool,
    /// The run's first warning (inaccurate contact resolution, energy drift), if any; the
    /// self-check's warnings are not included (see the row's `converged` column).
    pub warning: Option<String>,
}

/// Compute one case, with its self-check if `check`. A panic in the library is caught and
/// recorded as a failure, so that one bad case cannot stop a sweep.
pub fn compute_case(sweep: &Sweep, case: usize, check: bool) -> CaseResult {
    let mut warning = None;
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let sc = sweep.case_scenario(case)?;
        // (every kind of case: cases that differ only in their contact share their runs
        // without contact, through the sweep's cache)
        let cache = sweep.free_runs();
        match sweep.row_kind() {
            super::RowKind::Suite { .. } => return suite_case(&sc, check, cache, &mut warning),
            super::RowKind::Row { .. } => return row_case(&sc, check, cache, &mut warning),
            super::RowKind::RowSuite { .. } => {
                return row_suite_case(&sc, check, cache, &mut warning);
            }
            super::RowKind::Single => {}
        }
        // (the floor responses only when the table has floor columns: they cost more than the
        // integration of a small model)
        let floors = !sweep.floor_columns().is_empty();
        let report = cache
            .simulate(&sc, check, floors)
            .map_err(|e| e.to_string())?;
        // the self-check's verdict is counted from the `converged` column instead
        warning = report
            .warnings
            .iter()
            .find(|w| !crate::analysis::simulate::accuracy::is_check_warning(w))
            .cloned();
        Ok(results::case_fields(sweep, &report))
    }))
    .unwrap_or_else(|p| {
        let msg = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Err(format!("internal error (please report): {msg}"))
    });
    CaseResult {
        line: results::row(sweep, case, &outcome),
        failed: outcome.is_err(),
        warning,
    }
}

/// A case of a sweep over a suite: the whole suite run ([`crate::study::suite::run_headline`]:
/// scaled by its rule for the case's structures, every record with and without contact, the
/// runs without contact through `cache`) to the fields of its row
/// ([`super::suite_rows::fields`]); `warning` receives the first warning of a record's run
/// (not the self-check's), naming the record.
fn suite_case(
    sc: &crate::input::scenario::Scenario,
    check: bool,
    cache: &super::free_cache::FreeRunCache,
    warning: &mut Option<String>,
) -> Result<Vec<String>, String> {
    let run = crate::study::suite::run_headline_by(sc, |s| cache.simulate(s, check, false))
        .map_err(|e| e.to_string())?;
    *warning = run.records.iter().enumerate().find_map(|(i, r)| {
        r.report
            .warnings
            .iter()
            .find(|w| !crate::analysis::simulate::accuracy::is_check_warning(w))
            .map(|w| format!("record {} ({}): {w}", i + 1, r.file))
    });
    Ok(super::suite_rows::fields(&run, check))
}

/// A case of a sweep over a suite on a row of buildings: the whole suite on the whole row
/// ([`crate::study::suite::row::run_row_headline`]: scaled by its rule over every building's
/// first-mode periods, every record's run of the row with and without contact, the runs
/// without contact through `cache`) to the fields of its row
/// ([`super::row_suite_rows::fields`]); `warning` receives the first warning of a record's run
/// (not the self-check's), naming the record.
fn row_suite_case(
    sc: &crate::input::scenario::Scenario,
    check: bool,
    cache: &super::free_cache::FreeRunCache,
    warning: &mut Option<String>,
) -> Result<Vec<String>, String> {
    let run = crate::study::suite::row::run_row_headline_by(sc, |s| cache.simulate_row(s, check))
        .map_err(|e| e.to_string())?;
    *warning = run.records.iter().enumerate().find_map(|(i, r)| {
        r.report
            .warnings
            .iter()
            .find(|w| !crate::analysis::simulate::accuracy::is_check_warning(w))
            .map(|w| format!("record {} ({}): {w}", i + 1, r.file))
    });
    Ok(super::row_suite_rows::fields(&run, check))
}

/// A case of a sweep over a row of buildings: the row run with and without contact and
/// self-checked unless `check` is off ([`crate::analysis::simulate::simulate_row_checked`], its
/// runs without contact through `cache`) to the fields of its row
/// ([`super::row_columns::fields`]); `warning` receives the run's first warning other than the
/// self-check's (that one is counted from `converged`).
fn row_case(
    sc: &crate::input::scenario::Scenario,
    check: bool,
    cache: &super::free_cache::FreeRunCache,
    warning: &mut Option<String>,
) -> Result<Vec<String>, String> {
    let report = cache.simulate_row(sc, check).map_err(|e| e.to_string())?;
    // the self-check's verdict is counted from the `converged` column instead
    *warning = report
        .warnings
        .iter()
        .find(|w| !crate::analysis::simulate::accuracy::is_check_warning(w))
        .cloned();
    Ok(super::row_columns::fields(&report))
}

/// Refuse a sweep none of whose `cases` is a valid scenario (a mistake in the base scenario
/// or the axes) with [`SweepError::NoValidCase`], before computing anything; usually the
/// first case settles it. No cases: nothing to refuse.
pub fn require_valid_case(sweep: &Sweep, cases: &[usize]) -> Result<(), SweepError> {
    if cases.is_empty() {
        return Ok(());
    }
    let any_valid = cases
        .par_iter()
        .with_min_len(64)
        .any(|&c| sweep.case_scenario(c).is_ok());
    if any_valid {
        return Ok(());
    }
    let c = cases[0];
    let reason = sweep.case_scenario(c).err().unwrap_or_default();
    Err(SweepError::NoValidCase {
        case: c,
        label: sweep.label(c),
        reason,
        scenario: sweep.scenario_path.display().to_string(),
        sweep: sweep.path.display().to_string(),
    })
}

/// Every case of `sweep` computed in memory on `jobs` threads ([`compute_case`], checked if
/// `check`), in case order: the rows `pounding sweep` writes to results.csv, without the
/// journal and the files (the Python package's `pounding.sweep`). A sweep none of whose cases
/// is valid is refused as by [`run`].
pub fn compute_all(sweep: &Sweep, jobs: usize, check: bool) -> Result<Vec<CaseResult>, SweepError> {
    if jobs == 0 {
        return Err(SweepError::Usage("jobs must be at least 1".into()));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| SweepError::Usage(format!("cannot start {jobs} threads: {e}")))?;
    let mut cases: Vec<usize> = (0..sweep.len()).collect();
    pool.install(|| {
        require_valid_case(sweep, &cases)?;
        // (computed in the order that shares runs without contact, returned in case order)
        sweep.free_runs().order(&mut cases, |c| sweep.indices(c));
        let mut done: Vec<(usize, CaseResult)> = cases
            .par_iter()
            .map(|&c| (c, compute_case(sweep, c, check)))
            .collect();
        done.sort_by_key(|(c, _)| *c);
        Ok(done.into_iter().map(|(_, r)| r).collect())
    })
}

/// Run (or resume) part `opts.shard` of `sweep` into `opts.out_dir`.
pub fn run(
    sweep: &Sweep,
    opts: &RunOptions,
    progress: &mut dyn Progress,
) -> Result<RunOutcome, SweepError> {
    if opts.jobs == 0 {
        return Err(SweepError::Usage("--jobs must be at least 1".into()));
    }
    std::fs::create_dir_all(&opts.out_dir).map_err(|e| SweepError::Write {
        path: opts.out_dir.display().to_string(),
        source: e,
    })?;
    let (results_name, journal_name) = results::file_names(opts.shard);
    let mut journal = Journal::open(&opts.out_dir.join(&journal_name), sweep, opts.shard)?;
    let resumed = journal.rows.len();
    let mut pending: Vec<usize> = (0..sweep.len())
        .filter(|&c| opts.shard.contains(c) && !journal.rows.contains_key(&c))
        .collect();
    // cases that share their run without contact one after another (the journal and the
    // results are by case number, so the order is free)
    sweep.free_runs().order(&mut pending, |c| sweep.indices(c));
    let cases = resumed + pending.len();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.jobs)
        .build()
        .map_err(|e| SweepError::Usage(format!("cannot start {} threads: {e}", opts.jobs)))?;

    // Refuse a sweep none of whose cases is a valid scenario (a mistake in the base scenario
    // or the axes), before computing anything.
    if journal.rows.values().all(|(_, failed)| *failed) {
        pool.install(|| require_valid_case(sweep, &pending))?;
    }

    let started = Instant::now();
    progress.start(pending.len(), resumed);
    let stop = AtomicBool::new(false);
    let mut write_error = None;
    let mut warned = 0;
    let mut first_warning: Option<(usize, String)> = None;
    std::thread::scope(|s| {
        let (tx, rx) = mpsc::sync_channel::<(usize, CaseResult)>(4096);
        let stop = &stop;
        let pending = &pending;
        let pool = &pool;
        s.spawn(move || {
            pool.install(|| {
                pending.par_iter().for_each_with(tx, |tx, &case| {
                    if stop.load(Ordering::Relaxed) {
                        return;
                    }
                    let r = compute_case(sweep, case, opts.check);
                    if tx.send((case, r)).is_err() {
                        stop.store(true, Ordering::Relaxed);
                    }
                });
            });
        });
        for (case, r) in rx {
            if let Some(w) = r.warning {
                warned += 1;
                if first_warning.as_ref().is_none_or(|(c, _)| case < *c) {
                    first_warning = Some((case, w));
                }
            }
            if write_error.is_none() {
                match journal.append(case, r.line, r.failed) {
                    Ok(()) => progress.advance(r.failed),
                    Err(e) => {
                        write_error = Some(e);
                        stop.store(true, Ordering::Relaxed);
                    }
                }
            }
        }
    });
    progress.finish();
    if let Some(e) = write_error {
        return Err(e);
    }
    journal.sync()?;
    let seconds = started.elapsed().as_secs_f64();
    let results_path = opts.out_dir.join(results_name);
    results::write_results(
        &results_path,
        &results::header(sweep),
        journal.rows.values().map(|(l, _)| l.as_str()),
    )?;
    let failed = journal.rows.values().filter(|(_, f)| *f).count();
    let first_failure = journal
        .rows
        .iter()
        .find(|(_, (_, f))| *f)
        .map(|(c, (l, _))| {
            let status = results::parse_csv_line(l)
                .and_then(|f| f.get(1 + sweep.axes.len()).cloned())
                .unwrap_or_default();
            (*c, status)
        });
    let check = CheckCounts::of_rows(
        journal.rows.iter().map(|(c, (l, _))| (*c, l.as_str())),
        sweep.extra_columns().len(),
    );
    Ok(RunOutcome {
        check,
        results: results_path,
        cases,
        resumed,
        computed: pending.len(),
        failed,
        first_failure,
        dropped: journal.dropped,
        warned,
        first_warning,
        seconds,
    })
}
