//! The rows of a sweep over a suite of records on a row of buildings (a base scenario with
//! more than two `[[structure]]` tables and `[ground_motion] kind = "suite"`): each case is the
//! whole suite on the whole row — scaled by its rule over every building's first-mode periods
//! (recomputed per case), every record run with and without contact through the row's driver
//! ([`crate::study::suite::row::run_row_headline`], the pipeline of `pounding run` on a row
//! suite) — and its row carries the suite's answer per pair ([`columns`]):
//!
//! | column | meaning |
//! |---|---|
//! | `structures` | number of structures N |
//! | `records` | number of records run |
//! | `statistic` | the design statistic: `mean` or `max` (the rule's, by the number of records) |
//! | `min_mean_to_target_ratio` | the lowest mean-to-target ratio over the code's period range (NaN for rule `none`) |
//! | `sufficient` | `true` if every pair's gap is at least its design value at every level |
//! | `governing_pair` | the pair (1-based: structures P and P + 1) of least margin gap − design value |
//! | `governing_height` | its governing level's height, m |
//! | `governing_margin` | gap − design value there, m (negative: too small) |
//! | `pair{p}_sufficient` | `true` if pair p's gap is at least its design value at each of its levels |
//! | `pair{p}_governing_height` | the height of pair p's level of least margin, m |
//! | `pair{p}_required` | the design value of the required separation there, m |
//! | `pair{p}_margin` | gap − design value there, m |
//! | `pair{p}_peak_force` | the design value over the records of pair p's peak contact force (over its levels), N |
//! | `pair{p}_level{K}_required_separation` | the design value of the time-history required separation at level K of pair p, m |
//! | `check_max_change` | the largest self-check change over the records (empty: unchecked, or a check run failed) |
//! | `converged` | `true` if every record's run of the row converged within 1 %, `false` if one did not, `unchecked` |
//!
//! Every pair's columns (p = 1 … N − 1, its levels K = 1 … in the order of its `[[contact]]`
//! table) come in row order. The values are summary.json's `suite.design` of `pounding run` on
//! the case's scenario (`pairs[p − 1].levels[K − 1].required`, …) and
//! `suite.statistics.pair{p}_peak_force.design`. Its journal is version
//! [`JOURNAL_VERSION_ROW_SUITE`], so that a journal of one row kind is never resumed as
//! another.

use crate::numerics::format::fmt_f64;
use crate::study::suite::row::RowSuiteRun;

/// Version of the journal format of a sweep over a suite on a row (its first line).
pub const JOURNAL_VERSION_ROW_SUITE: u32 = 6;

/// The columns before the pairs' columns.
pub const HEAD: [&str; 8] = [
    "structures",
    "records",
    "statistic",
    "min_mean_to_target_ratio",
    "sufficient",
    "governing_pair",
    "governing_height",
    "governing_margin",
];

/// Each pair's columns before its levels', as `pair{p}_` + the name.
pub const PER_PAIR: [&str; 5] = [
    "sufficient",
    "governing_height",
    "required",
    "margin",
    "peak_force",
];

/// Each level's column of a pair, as `pair{p}_level{K}_` + the name.
pub const PER_LEVEL: [&str; 1] = ["required_separation"];

/// The last columns: the self-check (as in a single run's row).
pub const TAIL: [&str; 2] = ["check_max_change", "converged"];

/// The columns of a row suite's results row after `status`, for a row whose pair p (0-based)
/// has `pair_levels[p]` contact levels (N − 1 pairs).
pub fn columns(pair_levels: &[usize]) -> Vec<String> {
    let mut v: Vec<String> = HEAD.iter().map(|s| s.to_string()).collect();
    for (p, &levels) in (1..).zip(pair_levels) {
        v.extend(PER_PAIR.iter().map(|c| format!("pair{p}_{c}")));
        for k in 1..=levels {
            v.extend(PER_LEVEL.iter().map(|c| format!("pair{p}_level{k}_{c}")));
        }
    }
    v.extend(TAIL.iter().map(|s| s.to_string()));
    v
}

/// Each pair's number of levels from a table's columns after `status` (`names`), if they are
/// a row suite's ([`columns`] of them gives `names` back).
pub fn pair_levels_of(names: &[String]) -> Option<Vec<usize>> {
    let mut levels: Vec<usize> = Vec::new();
    for n in names {
        let Some(rest) = n.strip_prefix("pair") else {
            continue;
        };
        let (p, what) = rest.split_once('_')?;
        let p: usize = p.parse().ok()?;
        if p == 0 || p > levels.len() + 1 {
            return None;
        }
        if p == levels.len() + 1 {
            levels.push(0);
        }
        if what.starts_with("level") && what.ends_with("_required_separation") {
            levels[p - 1] += 1;
        }
    }
    (columns(&levels) == names).then_some(levels)
}

/// The fields of a row suite's row ([`columns`]), formatted as the results table writes
/// numbers: the design values and verdicts of `run.design`, the design value of each pair's
/// peak force from `run.statistics`, and the worst self-check over the records (`check`:
/// whether the records were self-checked).
pub fn fields(run: &RowSuiteRun, check: bool) -> Vec<String> {
    let d = &run.design;
    let governing = d.governing();
    let mut out = vec![
        (d.pairs.len() + 1).to_string(),
        d.records.to_string(),
        d.statistic.key().to_string(),
        fmt_f64(run.scaling.as_ref().map_or(f64::NAN, |s| s.min_ratio)),
        d.sufficient.to_string(),
        d.governing_pair.to_string(),
        fmt_f64(governing.height),
        fmt_f64(governing.margin),
    ];
    for q in &d.pairs {
        let g = &q.levels[q.governing_level - 1];
        let name = format!("pair{}_peak_force", q.pair);
        let force = run
            .statistics
            .0
            .iter()
            .find(|(n, _)| *n == name)
            .map_or(f64::NAN, |(_, s)| s.design);
        out.push(q.sufficient.to_string());
        out.push(fmt_f64(g.height));
        out.push(fmt_f64(g.required));
        out.push(fmt_f64(g.margin));
        out.push(fmt_f64(force));
        for l in &q.levels {
            out.push(fmt_f64(l.required));
        }
    }
    let acc = run.records.iter().map(|r| &r.report.accuracy);
    out.extend(super::suite_check::worst_check(
        acc.map(|a| (a.checked, a.max_change, a.converged)),
        check,
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::super::suite_rows::parse;
    use super::*;

    /// The columns of a row of three whose pairs have 2 and 1 levels, in order, read back to
    /// the levels, and each column's kind read back.
    #[test]
    fn columns_and_their_values() {
        let c = columns(&[2, 1]);
        assert_eq!(
            c.len(),
            HEAD.len() + 2 * PER_PAIR.len() + 3 * PER_LEVEL.len() + TAIL.len()
        );
        assert_eq!(c[8], "pair1_sufficient");
        assert_eq!(c[13], "pair1_level1_required_separation");
        assert_eq!(c[14], "pair1_level2_required_separation");
        assert_eq!(c[15], "pair2_sufficient");
        assert_eq!(c[20], "pair2_level1_required_separation");
        assert_eq!(c.last().map(String::as_str), Some("converged"));
        assert_eq!(pair_levels_of(&c), Some(vec![2, 1]));
        assert_eq!(pair_levels_of(&c[1..]), None);
        assert_eq!(parse("pair2_sufficient", "false"), Some(0.0));
        assert_eq!(parse("sufficient", "true"), Some(1.0));
        assert!(parse("statistic", "max").is_some_and(f64::is_nan));
        assert!(parse("check_max_change", "").is_some_and(f64::is_nan));
        assert_eq!(parse("pair1_margin", "-0.5"), Some(-0.5));
        assert_eq!(parse("governing_pair", "x"), None);
    }
}
