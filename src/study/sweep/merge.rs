//! Merging the parts of a sharded sweep (`pounding merge OUT PARTS…`): the results tables
//! `results-shard-K-of-N.csv` of one sweep joined into one, checked for a part missing or given
//! twice, a case in two parts or missing from all, and parts of different sweeps.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::SweepError;
use super::results::{Table, TableRow, write_results};

/// What [`merge`] did.
#[derive(Debug, Clone)]
pub struct MergeSummary {
    /// The parts read.
    pub parts: Vec<PathBuf>,
    /// Cases in the merged table.
    pub cases: usize,
    /// Of which failed.
    pub failed: usize,
}

/// `results-shard-K-of-N.csv` → (K, N).
fn shard_of(path: &Path) -> Option<(usize, usize)> {
    let name = path.file_name()?.to_str()?;
    let rest = name.strip_prefix("results-shard-")?.strip_suffix(".csv")?;
    let (k, n) = rest.split_once("-of-")?;
    Some((k.parse().ok()?, n.parse().ok()?))
}

/// Join the parts of a sharded sweep (files, or directories holding
/// `results-shard-K-of-N.csv` files) into one table at `out`, checking that they belong to
/// one sweep (same columns, consistent axis values), that no case appears twice and that
/// none is missing (every part K of N present; cases 0 … n−1 with n the grid size).
pub fn merge(out: &Path, inputs: &[PathBuf]) -> Result<MergeSummary, SweepError> {
    let mut parts = Vec::new();
    for p in inputs {
        if p.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(p)
                .map_err(|e| SweepError::Read {
                    path: p.display().to_string(),
                    source: e,
                })?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| shard_of(f).is_some())
                .collect();
            if found.is_empty() {
                return Err(SweepError::Merge(format!(
                    "{} holds no results-shard-K-of-N.csv file",
                    p.display()
                )));
            }
            found.sort();
            parts.extend(found);
        } else {
            parts.push(p.clone());
        }
    }
    if parts.is_empty() {
        return Err(SweepError::Merge("no parts given".into()));
    }
    let tables = parts
        .iter()
        .map(|p| Table::read(p))
        .collect::<Result<Vec<_>, _>>()?;
    let first = &tables[0];
    // parts named K-of-N: all of 1..N, once each
    let named: Vec<(usize, usize)> = parts.iter().filter_map(|p| shard_of(p)).collect();
    if named.len() == parts.len() {
        let n = named[0].1;
        if let Some(p) = named.iter().position(|s| s.1 != n) {
            return Err(SweepError::Merge(format!(
                "{} is a part of {} but {} is a part of {n}",
                parts[p].display(),
                named[p].1,
                parts[0].display()
            )));
        }
        let mut seen: Vec<Option<usize>> = vec![None; n + 1];
        for (i, (k, _)) in named.iter().enumerate() {
            if let Some(j) = seen[*k] {
                return Err(SweepError::Merge(format!(
                    "part {k} of {n} is given twice: {} and {}",
                    parts[j].display(),
                    parts[i].display()
                )));
            }
            seen[*k] = Some(i);
        }
        let missing: Vec<String> = (1..=n)
            .filter(|k| seen[*k].is_none())
            .map(|k| k.to_string())
            .collect();
        if !missing.is_empty() {
            return Err(SweepError::Merge(format!(
                "part(s) {} of {n} are missing (results-shard-K-of-{n}.csv)",
                missing.join(", ")
            )));
        }
    }
    let mut rows: BTreeMap<usize, (&TableRow, usize)> = BTreeMap::new();
    for (ti, t) in tables.iter().enumerate() {
        if t.header != first.header {
            return Err(SweepError::Merge(format!(
                "{} and {} have different columns: not parts of one sweep",
                first.path.display(),
                t.path.display()
            )));
        }
        for (case, r) in &t.rows {
            if let Some((_, other)) = rows.insert(*case, (r, ti)) {
                return Err(SweepError::Merge(format!(
                    "case {case} is in both {} and {}",
                    tables[other].path.display(),
                    t.path.display()
                )));
            }
        }
    }
    // the grid: the number of distinct values of each axis; the value of every axis must
    // follow from the case number (first axis slowest)
    let na = first.axes.len();
    let mut distinct: Vec<Vec<&str>> = vec![Vec::new(); na];
    for (r, _) in rows.values() {
        for (j, v) in r.values.iter().enumerate() {
            if !distinct[j].contains(&v.as_str()) {
                distinct[j].push(v);
            }
        }
    }
    let sizes: Vec<usize> = distinct.iter().map(Vec::len).collect();
    let total: usize = sizes.iter().product();
    let mut at: Vec<Vec<Option<&str>>> = sizes.iter().map(|&n| vec![None; n]).collect();
    for (case, (r, ti)) in &rows {
        if *case >= total {
            return Err(SweepError::Merge(format!(
                "case {case} in {} is beyond the grid ({total} cases from the axis values): parts of different sweeps?",
                tables[*ti].path.display()
            )));
        }
        let mut rest = *case;
        for j in (0..na).rev() {
            let i = rest % sizes[j];
            rest /= sizes[j];
            let v = r.values[j].as_str();
            match at[j][i] {
                None => at[j][i] = Some(v),
                Some(w) if w == v => {}
                Some(w) => {
                    return Err(SweepError::Merge(format!(
                        "case {case} in {} has {} = {v} where the grid has {w}: parts of different sweeps?",
                        tables[*ti].path.display(),
                        first.axes[j]
                    )));
                }
            }
        }
    }
    let missing: Vec<usize> = (0..total).filter(|c| !rows.contains_key(c)).collect();
    if !missing.is_empty() {
        let list: Vec<String> = missing.iter().take(10).map(|c| c.to_string()).collect();
        return Err(SweepError::Merge(format!(
            "{} of {total} cases are missing (cases {}{}); rerun the parts that hold them",
            missing.len(),
            list.join(", "),
            if missing.len() > 10 { ", …" } else { "" }
        )));
    }
    write_results(
        out,
        &first.header,
        rows.values().map(|(r, _)| r.line.as_str()),
    )?;
    Ok(MergeSummary {
        parts,
        cases: total,
        failed: rows.values().filter(|(r, _)| r.status != "ok").count(),
    })
}
