//! Resuming and sharding a fragility study with the sweeps' journal
//! ([`crate::study::sweep::journal::Journal`]): every finished run is appended to
//! `DIR/journal.csv` (`journal-shard-K-of-N.csv` for part K of N) as soon as it is known, one
//! write per row; a rerun of the same study into the same directory reads it back, drops a
//! torn last line, and runs only what is missing. The first line identifies the study
//! ([`identity`]: its text, its base scenario's, the records' samples), the
//! part and the number of run keys; a journal of another study is refused.
//!
//! A row is one run, exactly ([`row`] / [`parse_row`]: numbers in the shortest form that reads
//! back to the same `f64`), so a resumed study's tables are those of an uninterrupted one. The
//! parts of a sharded study (`--shard K/N`: the tasks, [`super::tasks`], with task mod N =
//! K − 1: runs of stripes interleaved, or whole records of an IDA) are joined by [`merge`],
//! which replays the study from the parts' journals and refuses a missing run.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use super::{FragilityError, RunOutcome, RunStore};
use crate::input::fragility::FragilityStudy;
use crate::study::sweep::journal::{Journal, JournalKind};
use crate::study::sweep::results::{csv_field, file_names, parse_csv_line};
use crate::study::sweep::{Shard, SweepError};

/// A hash of what the runs of `study` depend on: its text, its base scenario's, every
/// record's samples and step (a journal of other inputs is not resumed).
pub fn identity(study: &FragilityStudy) -> u64 {
    let mut hash = crate::study::sweep::Fnv1a::new();
    hash.part(b"pounding-fragility-1");
    for t in &study.texts {
        hash.part(t.as_bytes());
    }
    if let Some(suite) = &study.scenario.suite {
        for r in &suite.records {
            let mut b = Vec::with_capacity(8 * (r.record.accel.len() + 1));
            b.extend_from_slice(&r.record.dt.to_le_bytes());
            for a in r.record.accel.iter() {
                b.extend_from_slice(&a.to_le_bytes());
            }
            hash.part(&b);
        }
    }
    hash.finish()
}

/// The journal format's version of a pair's study.
pub const VERSION: u32 = 1;

/// The journal format's version of a row's study (more than two structures: its columns per
/// pair and per structure, [`header`]), so that a journal of one kind is never read as the
/// other's.
pub const VERSION_ROW: u32 = 2;

const MAGIC: &str = "# pounding fragility journal v";

fn num(x: f64) -> String {
    if x.is_finite() {
        crate::numerics::format::fmt_f64(x)
    } else {
        format!("{x}")
    }
}

/// The layout of a study's runs: each pair's number of contact levels and the number of
/// structures; `row` for more than two structures (the columns named per pair).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Shape {
    /// Contact levels of each adjacent pair, row order.
    pub levels: Vec<usize>,
    /// Structures.
    pub structures: usize,
    /// A row of more than two structures.
    pub row: bool,
}

impl Shape {
    /// The layout of `study`'s runs.
    pub fn of(study: &FragilityStudy) -> Shape {
        Shape {
            levels: study.scenario.contacts().map(|c| c.levels.len()).collect(),
            structures: study.scenario.structures.len(),
            row: study.scenario.is_row(),
        }
    }

    /// The journal version of this layout.
    pub fn version(&self) -> u32 {
        if self.row { VERSION_ROW } else { VERSION }
    }

    /// The columns of the required separations: `level{k}_required_separation` of a pair,
    /// `pair{p}_level{k}_required_separation` of a row.
    pub fn level_columns(&self) -> Vec<String> {
        let mut v = Vec::new();
        for (p, n) in self.levels.iter().enumerate() {
            for k in 1..=*n {
                v.push(if self.row {
                    format!("pair{}_level{k}_required_separation", p + 1)
                } else {
                    format!("level{k}_required_separation")
                });
            }
        }
        v
    }

    /// Each pair's prefix of its columns: `` of a pair, `pair{p}_` of a row.
    pub fn pair_prefix(&self, p: usize) -> String {
        if self.row {
            format!("pair{}_", p + 1)
        } else {
            String::new()
        }
    }

    /// The columns per structure i (1-based): `ductility_i`, `ductility_no_contact_i`, then
    /// the same of the drift ratio and the floor acceleration.
    pub fn structure_columns(&self) -> Vec<String> {
        let mut v = Vec::new();
        for what in ["ductility", "drift_ratio", "floor_acceleration"] {
            for i in 1..=self.structures {
                v.push(format!("{what}_{i}"));
                v.push(format!("{what}_no_contact_{i}"));
            }
        }
        v
    }
}

/// The journal's header line.
pub fn header(shape: &Shape) -> String {
    let mut h = vec!["key,record,run,im,factor".to_string()];
    h.extend(shape.level_columns());
    for p in 0..shape.levels.len() {
        let pre = shape.pair_prefix(p);
        h.push(format!("{pre}impacts,{pre}peak_force"));
    }
    h.extend(shape.structure_columns());
    h.push("converged,warnings".into());
    h.join(",")
}

/// A run as a journal row under `key`.
pub fn row(key: usize, o: &RunOutcome) -> String {
    let mut f: Vec<String> = vec![
        key.to_string(),
        o.record.to_string(),
        o.stripe.to_string(),
        num(o.im),
        num(o.factor),
    ];
    f.extend(o.required.iter().flatten().map(|x| num(*x)));
    for (n, p) in o.impacts.iter().zip(&o.peak_force) {
        f.push(n.to_string());
        f.push(num(*p));
    }
    for d in &o.ductility {
        for x in d {
            f.push(x.map_or(String::new(), num));
        }
    }
    for v in [&o.drift_ratio, &o.floor_acceleration] {
        for row in v {
            for x in row {
                f.push(num(*x));
            }
        }
    }
    f.push(
        match o.converged {
            Some(true) => "true",
            Some(false) => "false",
            None => "unchecked",
        }
        .into(),
    );
    // (as JSON: a warning's line breaks escaped, the row stays one line)
    f.push(serde_json::to_string(&o.warnings).unwrap_or_else(|_| "[]".into()));
    f.iter().map(|x| csv_field(x)).collect::<Vec<_>>().join(",")
}

/// A journal row read back: its key and run, `None` if damaged.
pub fn parse_row(line: &str, shape: &Shape) -> Option<(usize, RunOutcome)> {
    let f = parse_csv_line(line)?;
    let levels: usize = shape.levels.iter().sum();
    let (np, ns) = (shape.levels.len(), shape.structures);
    if f.len() != 5 + levels + 2 * np + 6 * ns + 2 {
        return None;
    }
    let n = |s: &str| s.parse::<f64>().ok();
    let mut it = f.iter();
    let mut next = || it.next().map(String::as_str).unwrap_or("");
    let key: usize = next().parse().ok()?;
    let record: usize = next().parse().ok()?;
    let stripe: usize = next().parse().ok()?;
    let im = n(next())?;
    let factor = n(next())?;
    let mut required = Vec::with_capacity(np);
    for &k in &shape.levels {
        let mut v = Vec::with_capacity(k);
        for _ in 0..k {
            v.push(n(next())?);
        }
        required.push(v);
    }
    let (mut impacts, mut peak_force) = (Vec::new(), Vec::new());
    for _ in 0..np {
        impacts.push(next().parse().ok()?);
        peak_force.push(n(next())?);
    }
    let mut ductility = vec![[None; 2]; ns];
    for d in ductility.iter_mut() {
        for x in d.iter_mut() {
            let s = next();
            *x = if s.is_empty() { None } else { Some(n(s)?) };
        }
    }
    let mut per = || -> Option<Vec<[f64; 2]>> {
        let mut v = vec![[0.0; 2]; ns];
        for r in v.iter_mut() {
            for x in r.iter_mut() {
                *x = n(next())?;
            }
        }
        Some(v)
    };
    let drift_ratio = per()?;
    let floor_acceleration = per()?;
    let converged = match next() {
        "true" => Some(true),
        "false" => Some(false),
        "unchecked" => None,
        _ => return None,
    };
    let warnings: Vec<String> = serde_json::from_str(next()).ok()?;
    Some((
        key,
        RunOutcome {
            record,
            stripe,
            im,
            factor,
            required,
            impacts,
            peak_force,
            ductility,
            drift_ratio,
            floor_acceleration,
            converged,
            warnings,
        },
    ))
}

/// The largest run key of a study, plus one.
fn keys(study: &FragilityStudy) -> usize {
    study.record_names.len()
        * match &study.ida {
            Some(i) => i.max_runs,
            None => study.stripes.len(),
        }
}

/// A journal that is also the store of the runs: those read back are found again, new ones
/// appended.
pub struct JournalStore {
    journal: Mutex<Journal>,
    runs: BTreeMap<usize, RunOutcome>,
    /// Rows dropped on reading (torn or damaged): their runs are redone.
    pub dropped: usize,
    compute: bool,
    added: std::sync::atomic::AtomicUsize,
}

impl JournalStore {
    /// Runs read back from the journal.
    pub fn resumed(&self) -> usize {
        self.runs.len()
    }

    /// Runs computed (and journaled) since it was opened.
    pub fn computed(&self) -> usize {
        self.added.load(std::sync::atomic::Ordering::Relaxed)
    }
}

impl RunStore for JournalStore {
    fn get(&self, key: usize) -> Option<RunOutcome> {
        self.runs.get(&key).cloned()
    }

    fn put(&self, key: usize, run: &RunOutcome) -> Result<(), FragilityError> {
        let mut j = self
            .journal
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        j.append(key, row(key, run), false)?;
        self.added
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(())
    }

    fn may_compute(&self) -> bool {
        self.compute
    }
}

/// Open (or create) the journal of part `shard` of `study` in `dir` (created if missing).
pub fn open(
    study: &FragilityStudy,
    dir: &Path,
    shard: Shard,
) -> Result<JournalStore, FragilityError> {
    std::fs::create_dir_all(dir).map_err(|e| SweepError::Write {
        path: dir.display().to_string(),
        source: e,
    })?;
    let path = dir.join(file_names(shard).1);
    open_file(study, &path, shard, true)
}

fn open_file(
    study: &FragilityStudy,
    path: &Path,
    shard: Shard,
    compute: bool,
) -> Result<JournalStore, FragilityError> {
    let shape = Shape::of(study);
    let total = keys(study);
    let check = |body: &str| {
        parse_row(body, &shape)
            .filter(|(k, _)| *k < total && shard.contains(super::key_task(study, *k)))
            .map(|(k, _)| (k, false))
    };
    let kind = JournalKind {
        magic: MAGIC,
        version: shape.version(),
        ident: format!(
            "{MAGIC}{}; identity={:016x}; shard={shard}; keys={total}",
            shape.version(),
            identity(study)
        ),
        header: header(&shape),
        command: "pounding fragility",
        inputs: "the study file, its base scenario, its records or --shard",
        version_note: "its rows differ",
        check_row: &check,
    };
    let journal = Journal::open_kind(path, &kind)?;
    let runs = journal
        .rows
        .iter()
        .filter_map(|(_, (line, _))| parse_row(line, &shape))
        .collect();
    Ok(JournalStore {
        dropped: journal.dropped,
        journal: Mutex::new(journal),
        runs,
        compute,
        added: std::sync::atomic::AtomicUsize::new(0),
    })
}

/// The tasks of part `shard`.
pub fn part(study: &FragilityStudy, shard: Shard) -> Vec<usize> {
    (0..super::tasks(study))
        .filter(|&t| shard.contains(t))
        .collect()
}

/// The parts' journals in `inputs` (`journal-shard-K-of-N.csv` files, or directories holding
/// them): every part 1 … N once.
fn shard_journals(inputs: &[PathBuf]) -> Result<Vec<(PathBuf, Shard)>, FragilityError> {
    let of = |p: &Path| -> Option<Shard> {
        let name = p.file_name()?.to_str()?;
        let rest = name.strip_prefix("journal-shard-")?.strip_suffix(".csv")?;
        let (k, n) = rest.split_once("-of-")?;
        format!("{k}/{n}").parse().ok()
    };
    let mut found = Vec::new();
    for p in inputs {
        if p.is_dir() {
            let list = std::fs::read_dir(p).map_err(|e| SweepError::Read {
                path: p.display().to_string(),
                source: e,
            })?;
            let mut here: Vec<(PathBuf, Shard)> = list
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter_map(|f| of(&f).map(|s| (f, s)))
                .collect();
            if here.is_empty() {
                return Err(SweepError::Merge(format!(
                    "{} holds no journal-shard-K-of-N.csv (the journal of `pounding fragility \
                     --shard K/N`)",
                    p.display()
                ))
                .into());
            }
            here.sort_by_key(|(_, s)| s.k);
            found.extend(here);
        } else {
            let s = of(p).ok_or_else(|| {
                SweepError::Merge(format!("{} is not a journal-shard-K-of-N.csv", p.display()))
            })?;
            found.push((p.clone(), s));
        }
    }
    let Some(n) = found.first().map(|(_, s)| s.n) else {
        return Err(SweepError::Merge("no parts given".into()).into());
    };
    let mut seen = vec![None; n + 1];
    for (p, s) in &found {
        if s.n != n {
            return Err(SweepError::Merge(format!(
                "{} is a part of {} but {} is a part of {n}",
                p.display(),
                s.n,
                found[0].0.display()
            ))
            .into());
        }
        if let Some(q) = seen[s.k].replace(p.clone()) {
            return Err(SweepError::Merge(format!(
                "part {} of {n} is given twice: {} and {}",
                s.k,
                q.display(),
                p.display()
            ))
            .into());
        }
    }
    let missing: Vec<String> = (1..=n)
        .filter(|k| seen[*k].is_none())
        .map(|k| k.to_string())
        .collect();
    if !missing.is_empty() {
        return Err(SweepError::Merge(format!(
            "part(s) {} of {n} are missing (journal-shard-K-of-{n}.csv)",
            missing.join(", ")
        ))
        .into());
    }
    Ok(found)
}

/// A store of the parts' runs that computes nothing.
struct Parts(BTreeMap<usize, RunOutcome>);

impl RunStore for Parts {
    fn get(&self, key: usize) -> Option<RunOutcome> {
        self.0.get(&key).cloned()
    }
    fn put(&self, _: usize, _: &RunOutcome) -> Result<(), FragilityError> {
        Ok(())
    }
    fn may_compute(&self) -> bool {
        false
    }
}

/// The runs of task `task` ([`super::tasks`]) as journal rows ([`row`]): what one Dask task
/// computes (`pounding.distributed.fragility`).
pub fn task_rows(
    study: &FragilityStudy,
    record_im: &[f64],
    task: usize,
) -> Result<Vec<String>, FragilityError> {
    let runs = super::run_task(study, record_im, task, &super::NoStore)?;
    Ok(runs
        .iter()
        .map(|o| row(super::run_key(study, o.record, o.stripe), o))
        .collect())
}

/// The study's results from journal rows ([`row`]) holding every run, in any order (the rows
/// of all tasks, e.g. gathered from Dask); a damaged row or a missing run is refused.
pub fn assemble_rows(
    study: &FragilityStudy,
    rows: &[String],
) -> Result<super::FragilityRun, FragilityError> {
    let shape = Shape::of(study);
    let mut runs = BTreeMap::new();
    for (i, r) in rows.iter().enumerate() {
        let (k, o) = parse_row(r, &shape).ok_or_else(|| {
            SweepError::Merge(format!("row {} is not a run of this study: {r}", i + 1))
        })?;
        runs.insert(k, o);
    }
    replay(study, runs)
}

fn replay(
    study: &FragilityStudy,
    runs: BTreeMap<usize, RunOutcome>,
) -> Result<super::FragilityRun, FragilityError> {
    let record_im = super::record_ims(study)?;
    let all: Vec<usize> = (0..super::tasks(study)).collect();
    let outcomes = super::run_tasks(study, &record_im, &all, Some(1), &Parts(runs))?;
    Ok(super::assemble(study.clone(), record_im, outcomes))
}

/// Join the parts of a sharded study: the journals in `inputs` (files or directories), each
/// checked to be a part of `study` (its identity), every part present once; the study is
/// replayed from their runs (a run in no part is refused: [`FragilityError::Missing`]).
pub fn merge(
    study: &FragilityStudy,
    inputs: &[PathBuf],
) -> Result<super::FragilityRun, FragilityError> {
    let parts = shard_journals(inputs)?;
    let mut runs = BTreeMap::new();
    for (p, s) in &parts {
        let store = open_file(study, p, *s, false)?;
        runs.extend(store.runs);
    }
    replay(study, runs)
}
