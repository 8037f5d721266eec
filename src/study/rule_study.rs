//! How often each separation rule is unsafe over a sweep (issue 13, "A study that users will
//! cite"): from a results table with `sep_time_history` (the exact separation) and the rules'
//! columns (`sep_abs`, `sep_srss`, `sep_ddc` and the code columns `sep_asce7`, …), the fraction
//! of cases where a rule is below the exact value and by how much it exceeds it when it is not;
//! the figure of the ratio rule/exact over one axis is `figures::rules`.
//!
//! Cases that failed, and cases whose exact separation is 0 (the structures never approach:
//! identical structures), are left out: a ratio to 0 means nothing.

use serde::Serialize;

use crate::study::sweep::results::{Table, TableRow};

/// The paper's rules among the table's fields, in report order.
pub const PAPER_RULES: [&str; 3] = ["sep_abs", "sep_srss", "sep_ddc"];

/// One rule over the cases of a table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RuleStat {
    /// The column, e.g. `sep_srss`.
    pub column: String,
    /// Cases counted (ok, exact separation > 0, the rule's value present).
    pub cases: usize,
    /// Cases with the rule below the exact separation.
    pub unsafe_cases: usize,
    /// `unsafe_cases / cases`.
    pub unsafe_fraction: f64,
    /// Largest shortfall, % of the exact value (< 0; NaN when never unsafe).
    pub worst_under_percent: f64,
    /// Median excess over the exact value in the safe cases, % (NaN when none).
    pub median_over_percent: f64,
    /// Mean excess in the safe cases, %.
    pub mean_over_percent: f64,
    /// Largest excess, %.
    pub max_over_percent: f64,
}

/// Every rule of a table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RuleStudy {
    /// Rows of the table.
    pub rows: usize,
    /// Left out: failed, or an exact separation of 0.
    pub left_out: usize,
    /// Per rule.
    pub rules: Vec<RuleStat>,
}

pub(crate) fn exact_of(table: &Table, r: &TableRow) -> Option<f64> {
    let e = r.get(table, "sep_time_history")?;
    (r.status == "ok" && e.is_finite() && e > 0.0).then_some(e)
}

/// The rule columns of `table`: the paper's rules, then its code columns.
pub fn rule_columns(table: &Table) -> Vec<String> {
    PAPER_RULES
        .iter()
        .map(|s| s.to_string())
        .chain(
            table
                .codes
                .iter()
                .filter(|c| c.starts_with("sep_"))
                .cloned(),
        )
        .collect()
}

pub(crate) fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// The study of `table`.
pub fn rule_study(table: &Table) -> RuleStudy {
    let counted: Vec<(&TableRow, f64)> = table
        .rows
        .values()
        .filter_map(|r| exact_of(table, r).map(|e| (r, e)))
        .collect();
    let rules = rule_columns(table)
        .into_iter()
        .map(|column| {
            let mut over = Vec::new();
            let mut worst = f64::NAN;
            let mut unsafe_cases = 0;
            let mut cases = 0;
            for (r, e) in &counted {
                let Some(v) = r.get(table, &column).filter(|v| v.is_finite()) else {
                    continue;
                };
                cases += 1;
                let pct = 100.0 * (v - e) / e;
                if v < *e {
                    unsafe_cases += 1;
                    worst = if worst.is_nan() { pct } else { worst.min(pct) };
                } else {
                    over.push(pct);
                }
            }
            let mean = if over.is_empty() {
                f64::NAN
            } else {
                over.iter().sum::<f64>() / over.len() as f64
            };
            let max = over.iter().copied().fold(f64::NAN, f64::max);
            RuleStat {
                column,
                cases,
                unsafe_cases,
                unsafe_fraction: if cases > 0 {
                    unsafe_cases as f64 / cases as f64
                } else {
                    f64::NAN
                },
                worst_under_percent: worst,
                median_over_percent: median(&mut over),
                mean_over_percent: mean,
                max_over_percent: max,
            }
        })
        .collect();
    RuleStudy {
        rows: table.rows.len(),
        left_out: table.rows.len() - counted.len(),
        rules,
    }
}

/// The study as a text table.
pub fn format_study(s: &RuleStudy) -> String {
    let mut out = format!(
        "rule vs the exact time-history separation over {} cases ({} left out: failed, or exact separation 0)\n",
        s.rows - s.left_out,
        s.left_out
    );
    out.push_str(&format!(
        "  {:<14}{:>8}{:>10}{:>14}{:>16}{:>14}{:>14}\n",
        "rule", "cases", "unsafe", "worst under", "median over*", "mean over*", "max over*"
    ));
    let pct = |x: f64| {
        if x.is_finite() {
            format!("{x:+.1} %")
        } else {
            "–".into()
        }
    };
    for r in &s.rules {
        out.push_str(&format!(
            "  {:<14}{:>8}{:>10}{:>14}{:>16}{:>14}{:>14}\n",
            r.column,
            r.cases,
            format!("{:.1} %", 100.0 * r.unsafe_fraction),
            pct(r.worst_under_percent),
            pct(r.median_over_percent),
            pct(r.mean_over_percent),
            pct(r.max_over_percent)
        ));
    }
    out.push_str(
        "  unsafe: the rule is below the exact separation; worst under: its largest shortfall; \
         * over the safe cases, 100 (rule − exact)/exact\n",
    );
    out
}
