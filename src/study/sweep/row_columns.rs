//! The rows of a sweep whose base scenario is a row of buildings (issue 29: more than two
//! `[[structure]]` tables): each case is the row run with and without contact
//! ([`crate::analysis::simulate::simulate_row`]), and its results row carries, in this order
//! ([`columns`]):
//!
//! | column | meaning |
//! |---|---|
//! | `structures` | number of structures N |
//! | `sufficient` | `true` if every pair's gap suffices by every rule at every level |
//! | `governing_pair` | the pair (1-based: structures P and P + 1) of least margin over all pairs, rules and levels |
//! | `governing_rule` | its rule (`time_history`, `abs`, `srss`, `ddc`, `ddc_paper` or a code's key) |
//! | `governing_height` | its level, m |
//! | `governing_required` | the required separation there, m |
//! | `governing_margin` | gap − required there, m (negative: too small) |
//! | `pounding_pairs` | number of pairs that touched |
//! | `structure{i}_peak_displacement` | structure i's peak \|w\| with contact at its highest contact level, m |
//! | `structure{i}_peak_displacement_no_contact` | the same without contact, m |
//! | `structure{i}_change_percent` | 100 (with − without)/without, % |
//! | `pair{p}_impacts` | impacts of pair p over its levels |
//! | `pair{p}_peak_force` | its largest contact force, N |
//! | `pair{p}_max_penetration` | its largest penetration, m |
//! | `pair{p}_contact_time` | its total time in contact, s |
//! | `pair{p}_sep_time_history` | its exact required separation at its main (highest) level, m |
//! | `pair{p}_governing_rule` | the pair's rule of least margin (over its rules and levels) |
//! | `pair{p}_governing_height` | the level where it governs, m |
//! | `pair{p}_required` | that rule's required separation there, m |
//! | `pair{p}_margin` | gap − required there, m |
//! | `pair{p}_sufficient` | `true` if the pair's gap suffices by every rule at every level |
//! | `check_max_change`, `converged` | the row's self-check ([`crate::analysis::simulate::row_check`]), as a single run's row: the largest relative change, `true`/`false` (`unchecked` with `--no-check`) |
//!
//! The structures' columns for i = 1 … N come before the pairs' for p = 1 … N − 1. The pair's
//! numbers are summary.json's `pairs[p − 1]` (`contact`, `separation.time_history`,
//! `separation.verdict.governing`), the row's its `verdict`. A row's journal is version
//! [`JOURNAL_VERSION_ROW`], so that a journal of one row kind is never resumed as another.

use crate::analysis::simulate::RowReport;
use crate::numerics::format::fmt_f64;

/// Version of the journal format of a sweep over a row of buildings (its first line).
pub const JOURNAL_VERSION_ROW: u32 = 5;

/// The columns before the structures' columns.
pub const HEAD: [&str; 8] = [
    "structures",
    "sufficient",
    "governing_pair",
    "governing_rule",
    "governing_height",
    "governing_required",
    "governing_margin",
    "pounding_pairs",
];

/// Each structure's columns, as `structure{i}_` + the name.
pub const PER_STRUCTURE: [&str; 3] = [
    "peak_displacement",
    "peak_displacement_no_contact",
    "change_percent",
];

/// Each pair's columns, as `pair{p}_` + the name.
pub const PER_PAIR: [&str; 10] = [
    "impacts",
    "peak_force",
    "max_penetration",
    "contact_time",
    "sep_time_history",
    "governing_rule",
    "governing_height",
    "required",
    "margin",
    "sufficient",
];

/// The last columns: the self-check (as in a single run's row).
pub const TAIL: [&str; 2] = ["check_max_change", "converged"];

/// The `converged` value of a row run without its self-check (`--no-check`).
const UNCHECKED: &str = "unchecked";

/// The columns of a row's results row after `status`, for `structures` structures.
pub fn columns(structures: usize) -> Vec<String> {
    let mut v: Vec<String> = HEAD.iter().map(|s| s.to_string()).collect();
    for i in 1..=structures {
        v.extend(PER_STRUCTURE.iter().map(|c| format!("structure{i}_{c}")));
    }
    for p in 1..structures {
        v.extend(PER_PAIR.iter().map(|c| format!("pair{p}_{c}")));
    }
    v.extend(TAIL.iter().map(|s| s.to_string()));
    v
}

/// Is `name` a column of text (not a number) of a row's results row?
pub fn is_text(name: &str) -> bool {
    matches!(name, "sufficient" | "converged" | "governing_rule")
        || name.ends_with("_sufficient")
        || name.ends_with("_governing_rule")
}

/// A field read back: `true`/`false` as 1/0, `converged` as 1, 0 or NaN (`unchecked`), a rule
/// as NaN (it is text), an empty number (`check_max_change`, a missing rule's) as NaN, every
/// other field a number.
/// `None`: not a valid value of the column.
pub fn parse(name: &str, x: &str) -> Option<f64> {
    match name {
        "converged" => match x {
            "true" => Some(1.0),
            "false" => Some(0.0),
            UNCHECKED => Some(f64::NAN),
            _ => None,
        },
        // (no rule evaluated: an empty rule, empty numbers)
        n if n.ends_with("governing_rule") => Some(f64::NAN),
        n if !is_text(n) && x.is_empty() => Some(f64::NAN),
        n if is_text(n) => match x {
            "true" => Some(1.0),
            "false" => Some(0.0),
            _ => None,
        },
        _ => x.parse().ok(),
    }
}

/// The fields of a row's results row ([`columns`]), formatted as the results table writes
/// numbers (a rule missing, e.g. no rule evaluated: an empty rule and NaN numbers).
pub fn fields(r: &RowReport) -> Vec<String> {
    let v = &r.verdict;
    let g = v.governing.as_ref();
    let num = |x: Option<f64>| fmt_f64(x.unwrap_or(f64::NAN));
    let mut out = vec![
        r.structures.len().to_string(),
        v.insufficient_pairs.is_empty().to_string(),
        v.pair.map_or_else(String::new, |p| (p + 1).to_string()),
        g.map_or_else(String::new, |g| g.key.clone()),
        num(g.map(|g| g.height)),
        num(g.map(|g| g.required)),
        num(g.map(|g| g.margin)),
        v.pounding_pairs.len().to_string(),
    ];
    for s in &r.structures {
        out.push(fmt_f64(s.peak_displacement));
        out.push(fmt_f64(s.peak_displacement_no_contact));
        out.push(fmt_f64(s.change_percent));
    }
    for p in &r.pairs {
        let g = p.separation.verdict.governing.as_ref();
        out.push(p.contact.impacts.to_string());
        out.push(fmt_f64(p.contact.peak_force));
        out.push(fmt_f64(p.contact.max_penetration));
        out.push(fmt_f64(p.contact.contact_time));
        out.push(fmt_f64(p.separation.time_history));
        out.push(g.map_or_else(String::new, |g| g.key.clone()));
        out.push(num(g.map(|g| g.height)));
        out.push(num(g.map(|g| g.required)));
        out.push(num(g.map(|g| g.margin)));
        out.push((p.separation.verdict.insufficient == 0).to_string());
    }
    // (the self-check, as a single run's row: `converged` false where it could not decide)
    let acc = &r.accuracy;
    out.push(acc.max_change.map(fmt_f64).unwrap_or_default());
    out.push(match acc.converged {
        _ if !acc.checked => UNCHECKED.to_string(),
        Some(c) => c.to_string(),
        None => "false".to_string(),
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unchecked_is_the_single_rows_value() {
        assert_eq!(UNCHECKED, super::super::results::UNCHECKED);
    }

    /// The columns of a row of three, in order, and each column's kind read back.
    #[test]
    fn columns_and_their_values() {
        let c = columns(3);
        assert_eq!(
            c.len(),
            HEAD.len() + 3 * PER_STRUCTURE.len() + 2 * PER_PAIR.len() + TAIL.len()
        );
        assert_eq!(c[8], "structure1_peak_displacement");
        assert_eq!(c[17], "pair1_impacts");
        assert_eq!(c[27 + 9], "pair2_sufficient");
        assert_eq!(c.last().map(String::as_str), Some("converged"));
        assert_eq!(parse("pair2_sufficient", "false"), Some(0.0));
        assert!(parse("pair1_governing_rule", "abs").is_some_and(f64::is_nan));
        assert!(parse("governing_pair", "").is_some_and(f64::is_nan));
        assert_eq!(parse("pair1_impacts", "x"), None);
        assert_eq!(parse("sufficient", ""), None);
        assert_eq!(parse("governing_margin", "-0.5"), Some(-0.5));
    }
}
