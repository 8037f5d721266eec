//! The rows of a sweep over a suite of records (a base scenario with `[ground_motion]
//! kind = "suite"`): each case is a whole suite — scaled by its rule for the case's structures
//! (the scaling depends on their first-mode periods, so it is recomputed per case), every
//! record run with and without contact ([`crate::study::suite::run_headline`], the pipeline of
//! `pounding run` on a suite) — and its row carries the suite's answer ([`columns`]):
//!
//! | column | meaning |
//! |---|---|
//! | `records` | number of records run |
//! | `statistic` | the design statistic: `mean` or `max` (the rule's, by the number of records) |
//! | `min_mean_to_target_ratio` | the lowest mean-to-target ratio over the code's period range (NaN for rule `none`) |
//! | `sufficient` | `true` if the gap is at least the design value at every level |
//! | `governing_level` | the level of least margin (1-based, the scenario's order) |
//! | `governing_margin` | gap − design required separation there, m (negative: too small) |
//! | `levelK_gap` | the gap at level K, m |
//! | `levelK_required_separation` | the design value of the required separation by the time history at level K, m |
//! | `levelK_peak_force` | the design value of the peak contact force at level K, N |
//! | `levelK_sufficient` | `true` if level K's gap is at least its design value |
//! | `check_max_change` | the largest self-check change over the records (empty: unchecked, or a check run failed) |
//! | `converged` | `true` if every record converged within 1 %, `false` if one did not, `unchecked` |
//!
//! A suite's rows have none of a single run's [`super::results::FIELDS`] nor its code, floor
//! and ductility columns. Its journal is version [`JOURNAL_VERSION_SUITE`], so that a journal
//! of one row kind is never resumed as the other.

use std::path::{Path, PathBuf};

use toml::{Table, Value};

use super::edit::absolute;
use crate::numerics::format::fmt_f64;
use crate::study::suite::SuiteRun;

/// The `converged` value of a row not self-checked (as a single run's row writes it,
/// `results::UNCHECKED`: `results` reads these rows, so this file does not import it).
const UNCHECKED: &str = "unchecked";

/// What one row of a sweep holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RowKind {
    /// One run (with and without contact): [`super::results::FIELDS`] and the extra columns.
    Single,
    /// A suite of records: [`columns`] for `levels` contact levels.
    Suite {
        /// Number of contact levels of the base scenario (the axes cannot change it).
        levels: usize,
    },
    /// A row of buildings (issue 29): [`super::row_columns::columns`] for `structures`
    /// structures.
    Row {
        /// Number of structures of the base scenario (the axes cannot change it).
        structures: usize,
    },
    /// A suite of records on a row of buildings:
    /// [`super::row_suite_rows::columns`] of `pair_levels`.
    RowSuite {
        /// Each adjacent pair's number of contact levels in the base scenario (N − 1 pairs;
        /// the axes cannot change them).
        pair_levels: Vec<usize>,
    },
}

impl RowKind {
    /// Is `name` a column of text of this kind's rows (after [`super::results::FIELDS`]
    /// for a single run, which has none)?
    pub fn is_text(&self, name: &str) -> bool {
        match self {
            RowKind::Single => false,
            // (a row suite's text columns are a pair suite's: `statistic`, `sufficient`,
            // `converged` and every `…_sufficient`, with the same values)
            RowKind::Suite { .. } | RowKind::RowSuite { .. } => is_text(name),
            RowKind::Row { .. } => super::row_columns::is_text(name),
        }
    }

    /// A field of this kind's own columns read back (a suite's [`parse`], a row's
    /// [`super::row_columns::parse`]; a single run's extra columns are numbers).
    pub fn parse(&self, name: &str, x: &str) -> Option<f64> {
        match self {
            RowKind::Single => x.parse().ok(),
            RowKind::Suite { .. } | RowKind::RowSuite { .. } => parse(name, x),
            RowKind::Row { .. } => super::row_columns::parse(name, x),
        }
    }

    /// What a row of this kind holds, in messages ("one run per case", …).
    pub fn describe(&self) -> &'static str {
        match self {
            RowKind::Single => "one run per case",
            RowKind::Suite { .. } => "a suite of records per case",
            RowKind::Row { .. } => "a row of buildings per case",
            RowKind::RowSuite { .. } => "a suite of records on a row of buildings per case",
        }
    }

    /// What the rows of a sweep journal of format `version` hold, in messages (`None`: a
    /// version this program does not write).
    pub fn describe_version(version: u32) -> Option<&'static str> {
        match version {
            1..=3 => Some(RowKind::Single.describe()),
            JOURNAL_VERSION_SUITE => Some(RowKind::Suite { levels: 1 }.describe()),
            super::row_columns::JOURNAL_VERSION_ROW => {
                Some(RowKind::Row { structures: 3 }.describe())
            }
            super::row_suite_rows::JOURNAL_VERSION_ROW_SUITE => Some(
                RowKind::RowSuite {
                    pair_levels: Vec::new(),
                }
                .describe(),
            ),
            _ => None,
        }
    }
}

/// Version of the journal format of a sweep over a suite (its first line).
pub const JOURNAL_VERSION_SUITE: u32 = 4;

/// The columns before the levels' columns.
pub const HEAD: [&str; 6] = [
    "records",
    "statistic",
    "min_mean_to_target_ratio",
    "sufficient",
    "governing_level",
    "governing_margin",
];

/// Each level's columns, as `level{K}_` + the name.
pub const PER_LEVEL: [&str; 4] = ["gap", "required_separation", "peak_force", "sufficient"];

/// The last columns: the self-check (as in a single run's row).
pub const TAIL: [&str; 2] = ["check_max_change", "converged"];

/// The columns of a suite's row after `status`, for `levels` contact levels.
pub fn columns(levels: usize) -> Vec<String> {
    let mut v: Vec<String> = HEAD.iter().map(|s| s.to_string()).collect();
    for k in 1..=levels {
        v.extend(PER_LEVEL.iter().map(|c| format!("level{k}_{c}")));
    }
    v.extend(TAIL.iter().map(|s| s.to_string()));
    v
}

/// Is `name` a column of text (not a number) of a suite's row?
pub fn is_text(name: &str) -> bool {
    matches!(name, "statistic" | "sufficient" | "converged") || name.ends_with("_sufficient")
}

/// A field of a suite's row read back: `true`/`false` columns as 1/0, `converged` as 1, 0 or
/// NaN (`unchecked`), `statistic` as NaN (it is text), `check_max_change` empty as NaN, every
/// other field a number. `None`: not a valid value of the column.
pub fn parse(name: &str, x: &str) -> Option<f64> {
    match name {
        "statistic" => matches!(x, "mean" | "max").then_some(f64::NAN),
        "converged" => match x {
            "true" => Some(1.0),
            "false" => Some(0.0),
            UNCHECKED => Some(f64::NAN),
            _ => None,
        },
        "check_max_change" if x.is_empty() => Some(f64::NAN),
        n if is_text(n) => match x {
            "true" => Some(1.0),
            "false" => Some(0.0),
            _ => None,
        },
        _ => x.parse().ok(),
    }
}

/// The fields of a suite's row ([`columns`]), formatted as the results table writes numbers.
pub fn fields(run: &SuiteRun, check: bool) -> Vec<String> {
    let d = &run.design;
    let governing = &d.levels[d.governing_level - 1];
    let mut out = vec![
        d.records.to_string(),
        d.statistic.key().to_string(),
        fmt_f64(run.scaling.as_ref().map_or(f64::NAN, |s| s.min_ratio)),
        d.sufficient.to_string(),
        d.governing_level.to_string(),
        fmt_f64(governing.margin),
    ];
    for l in &d.levels {
        let force = run
            .statistics
            .0
            .iter()
            .find(|(n, _)| *n == format!("level{}_peak_force", l.level))
            .map_or(f64::NAN, |(_, s)| s.design);
        out.push(fmt_f64(l.gap));
        out.push(fmt_f64(l.required));
        out.push(fmt_f64(force));
        out.push(l.sufficient.to_string());
    }
    let acc = run.records.iter().map(|r| &r.report.accuracy);
    out.extend(super::suite_check::worst_check(
        acc.map(|a| (a.checked, a.max_change, a.converged)),
        check,
    ));
    out
}

/// The row kind of a base scenario (as a TOML table) and, for a suite, its record files and
/// target table made absolute (relative to `base_dir`, the base scenario's directory), so that
/// a case's TOML is self-contained as a single-record case's is.
pub(super) fn absolute_suite_files(base: &mut Table, base_dir: &Path) -> RowKind {
    let levels = base
        .get("contact")
        .and_then(|c| c.get("level"))
        .and_then(Value::as_array)
        .map_or(1, Vec::len);
    let Some(Value::Table(g)) = base.get_mut("ground_motion") else {
        return RowKind::Single;
    };
    if g.get("kind").and_then(Value::as_str) != Some("suite") {
        return RowKind::Single;
    }
    let fix = |v: Option<&mut Value>| {
        if let Some(Value::String(f)) = v {
            *f = absolute(&base_dir.join(&*f)).display().to_string();
        }
    };
    if let Some(Value::Array(list)) = g.get_mut("records") {
        for r in list.iter_mut() {
            fix(r.get_mut("file"));
        }
    }
    if let Some(t) = g.get_mut("scaling").and_then(|s| s.get_mut("target")) {
        fix(t.get_mut("file"));
    }
    RowKind::Suite { levels }
}

/// The files a suite in the base scenario reads (after [`absolute_suite_files`]): its records
/// and its target table, for the sweep's identity.
pub(super) fn suite_files(base: &Table) -> Vec<PathBuf> {
    let Some(g) = base.get("ground_motion").and_then(Value::as_table) else {
        return Vec::new();
    };
    if g.get("kind").and_then(Value::as_str) != Some("suite") {
        return Vec::new();
    }
    let mut out: Vec<PathBuf> = g
        .get("records")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(|r| r.get("file").and_then(Value::as_str))
        .map(PathBuf::from)
        .collect();
    if let Some(f) = g
        .get("scaling")
        .and_then(|s| s.get("target"))
        .and_then(|t| t.get("file"))
        .and_then(Value::as_str)
    {
        out.push(PathBuf::from(f));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unchecked_is_the_single_rows_value() {
        assert_eq!(UNCHECKED, super::super::results::UNCHECKED);
    }

    /// The columns of two levels, in order, and each column's kind read back.
    #[test]
    fn columns_and_their_values() {
        let c = columns(2);
        assert_eq!(c.len(), HEAD.len() + 2 * PER_LEVEL.len() + TAIL.len());
        assert_eq!(c[6], "level1_gap");
        assert_eq!(c[13], "level2_sufficient");
        assert_eq!(c.last().map(String::as_str), Some("converged"));
        assert_eq!(parse("sufficient", "true"), Some(1.0));
        assert_eq!(parse("level2_sufficient", "false"), Some(0.0));
        assert!(parse("statistic", "mean").is_some_and(f64::is_nan));
        assert_eq!(parse("statistic", "median"), None);
        assert!(parse("check_max_change", "").is_some_and(f64::is_nan));
        assert_eq!(parse("governing_margin", "-0.5"), Some(-0.5));
        assert_eq!(parse("records", "x"), None);
    }
}
