//! The rule study's figure (`rules.png`): the ratio of each separation rule to the exact
//! time-history separation over one axis of a sweep, from the study of
//! [`crate::study::rule_study`].

use std::path::{Path, PathBuf};

use crate::plot::PlotError;
use crate::plot::lines::{AxisScale, Figure, LineStyle, Panel, Series, write_figure};
use crate::study::rule_study::{exact_of, median, rule_columns, rule_study};
use crate::study::sweep::results::Table;

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
