//! How often each separation rule is unsafe over a sweep (issue 13, "A study that users will
//! cite"): from a results table with `sep_time_history` (the exact separation) and the rules'
//! columns (`sep_abs`, `sep_srss`, `sep_ddc` and the code columns `sep_asce7`, …), the fraction
//! of cases where a rule is below the exact value and by how much it exceeds it when it is not;
//! and a figure of the ratio rule/exact over one axis of the sweep.
//!
//! Cases that failed, and cases whose exact separation is 0 (the structures never approach:
//! identical structures), are left out: a ratio to 0 means nothing.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::plot::PlotError;
use crate::plot::lines::{AxisScale, Figure, LineStyle, Panel, Series, write_figure};
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

fn exact_of(table: &Table, r: &TableRow) -> Option<f64> {
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

fn median(v: &mut [f64]) -> f64 {
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

/// Draws `<dir>/rules.png/.svg`: one panel per rule, the ratio rule/exact against the axis
/// `x` of the table (its first axis when `None`): the smallest, the median and the largest
/// over the other axes' values at each x, and the line 1 (below it the rule is unsafe).
pub fn rule_figure(
    table: &Table,
    x: Option<&str>,
    dir: &Path,
    subtitle: &str,
) -> Result<Vec<PathBuf>, PlotError> {
    let j = match x {
        Some(k) => table
            .axes
            .iter()
            .position(|a| a == k)
            .ok_or_else(|| PlotError::NoData(format!("the table has no axis `{k}`")))?,
        None => 0,
    };
    let axis = table
        .axes
        .get(j)
        .ok_or_else(|| PlotError::NoData("the table has no axis".into()))?;
    // the distinct numeric values of the axis, increasing
    let mut xs: Vec<f64> = table
        .rows
        .values()
        .filter_map(|r| r.values.get(j)?.parse::<f64>().ok())
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    if xs.is_empty() {
        return Err(PlotError::NoData(format!(
            "axis `{axis}` does not hold numbers"
        )));
    }
    let study = rule_study(table);
    let cols = rule_columns(table);
    let mut data: Vec<[Vec<f64>; 3]> = Vec::new();
    for col in &cols {
        let mut lines = [Vec::new(), Vec::new(), Vec::new()];
        for &xv in &xs {
            let mut ratios: Vec<f64> = table
                .rows
                .values()
                .filter(|r| {
                    r.values
                        .get(j)
                        .and_then(|v| v.parse::<f64>().ok())
                        .is_some_and(|v| v == xv)
                })
                .filter_map(|r| {
                    let e = exact_of(table, r)?;
                    let v = r.get(table, col)?;
                    v.is_finite().then_some(v / e)
                })
                .collect();
            let lo = ratios.iter().copied().fold(f64::NAN, f64::min);
            let hi = ratios.iter().copied().fold(f64::NAN, f64::max);
            lines[0].push(lo);
            lines[1].push(median(&mut ratios));
            lines[2].push(hi);
        }
        data.push(lines);
    }
    let ones = vec![1.0; xs.len()];
    let titles: Vec<String> = cols
        .iter()
        .zip(&study.rules)
        .map(|(c, s)| {
            format!(
                "{c}: below the exact separation in {:.0} % of {} cases",
                100.0 * s.unsafe_fraction,
                s.cases
            )
        })
        .collect();
    let panels: Vec<Panel> = data
        .iter()
        .zip(&titles)
        .map(|(d, title)| Panel {
            title,
            y_label: "rule / exact",
            series: vec![
                Series {
                    label: "smallest",
                    x: &xs,
                    y: &d[0],
                    style: LineStyle::Solid,
                    color: None,
                },
                Series {
                    label: "median",
                    x: &xs,
                    y: &d[1],
                    style: LineStyle::Solid,
                    color: None,
                },
                Series {
                    label: "largest",
                    x: &xs,
                    y: &d[2],
                    style: LineStyle::Solid,
                    color: None,
                },
                Series {
                    label: "exact (below: unsafe)",
                    x: &xs,
                    y: &ones,
                    style: LineStyle::Dashed,
                    color: None,
                },
            ],
            y_scale: AxisScale::Log,
        })
        .collect();
    let height = 120 + 190 * panels.len() as u32;
    let fig = Figure {
        title: "Required separation by each rule / the exact time-history separation",
        subtitle,
        x_label: axis,
        panels,
        legend_once: true,
        width: 1000,
        height,
    };
    std::fs::create_dir_all(dir).map_err(|e| PlotError::Io {
        path: dir.to_path_buf(),
        source: e,
    })?;
    write_figure(&fig, &dir.join("rules"))
}
