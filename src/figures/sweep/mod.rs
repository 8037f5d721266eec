//! Pictures of a sweep's results table, drawn with [`crate::plot`]: heatmaps of a field over
//! two numeric axes and line plots over one, one picture per combination of the other axes'
//! values (e.g. one heatmap per PGA level). Failed cases are grey cells / gaps in lines.
//!
//! Each quantity has one colour scale everywhere ([`field_scale`]): the change of a peak
//! displacement is drawn as the amplification ratio peak with / peak without pounding on a
//! logarithmic diverging scale centred on 1 (×0.1 … ×10, saturating), quantities spanning more
//! than a factor of 100 (peak force, required separation) on a logarithmic scale. Axes are
//! named as on the command line, e.g. "T1/T2 (period_ratio)".

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::plot::{
    AxisScale, ColorScale, Figure, Heatmap, LineStyle, Panel, PlotError, Series, write_figure,
    write_heatmap,
};
use crate::study::sweep::SweepError;
use crate::study::sweep::results::{FIELDS, Table, TableRow};

mod labels;

pub use labels::{axis_label, field_label, field_scale};
use labels::{axis_name_short, file_key, sanitize, show_value};

/// The fields drawn when none is asked for.
pub const DEFAULT_FIELDS: [&str; 5] = [
    "change_percent_1",
    "change_percent_2",
    "peak_force",
    "impacts",
    "sep_time_history",
];

/// The fields drawn for a sweep over a suite of records when none is asked for: the design
/// required separation at every level (`levelK_required_separation`, at most
/// [`MAX_SUITE_LEVELS`] levels: the first ones, the top of the scenario's list), the margin at
/// the governing level and the verdict.
pub fn suite_default_fields(table: &Table) -> Vec<&str> {
    let mut v: Vec<&str> = table
        .codes
        .iter()
        .map(String::as_str)
        .filter(|c| c.starts_with("level") && c.ends_with("_required_separation"))
        .take(MAX_SUITE_LEVELS)
        .collect();
    v.extend(["governing_margin", "sufficient"]);
    v
}

/// Most levels drawn by default for a suite.
pub const MAX_SUITE_LEVELS: usize = 4;

/// Most lines on one line-plot panel (evenly chosen among the series axis' values).
const MAX_SERIES: usize = 6;

/// Saturation of the amplification colour scale: ×0.1 … ×10.
pub const RATIO_LIMIT: f64 = 10.0;

/// What to draw. Empty: the defaults (the first two numeric axes, [`DEFAULT_FIELDS`]).
#[derive(Debug, Clone, Default)]
pub struct PlotRequest {
    /// Axis along x (must be numeric).
    pub x: Option<String>,
    /// Axis along y for heatmaps (numeric); without it, line plots over `x` only.
    pub y: Option<String>,
    /// One field of [`FIELDS`]; without it, [`DEFAULT_FIELDS`].
    pub field: Option<String>,
}

/// The value drawn for `field` in row `r`, in the unit shown: for `change_percent_i` the ratio
/// `peak_displacement_i / peak_displacement_no_contact_i`.
fn value(table: &Table, r: &TableRow, field: &str) -> f64 {
    let get = |name: &str| r.get(table, name).unwrap_or(f64::NAN);
    match field.strip_prefix("change_percent_") {
        Some(i) => {
            get(&format!("peak_displacement_{i}"))
                / get(&format!("peak_displacement_no_contact_{i}"))
        }
        None => get(field) * field_label(field).2,
    }
}

/// Distinct values of column `j` in case order, and whether all are numbers.
fn distinct(table: &Table, j: usize) -> (Vec<String>, bool) {
    let mut out: Vec<String> = Vec::new();
    for r in table.rows.values() {
        if !out.contains(&r.values[j]) {
            out.push(r.values[j].clone());
        }
    }
    let numeric = out
        .iter()
        .all(|v| v.parse::<f64>().is_ok_and(f64::is_finite));
    (out, numeric)
}

fn sorted_numbers(vals: &[String]) -> Vec<f64> {
    let mut v: Vec<f64> = vals.iter().filter_map(|s| s.parse().ok()).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// Slices: the combinations of the values of the axes `other`, in case order.
fn slices(table: &Table, other: &[usize]) -> Vec<Vec<String>> {
    let mut out: Vec<Vec<String>> = Vec::new();
    for r in table.rows.values() {
        let s: Vec<String> = other.iter().map(|&j| r.values[j].clone()).collect();
        if !out.contains(&s) {
            out.push(s);
        }
    }
    out
}

/// What a slice holds fixed ("PGA = 0.5 g") and its file-name suffix ("_PGA=0.5").
fn slice_text(table: &Table, other: &[usize], s: &[String]) -> (String, String) {
    let fixed = other
        .iter()
        .zip(s)
        .map(|(&j, v)| {
            format!(
                "{} = {}",
                axis_name_short(&table.axes[j]),
                show_value(&table.axes[j], v)
            )
        })
        .collect::<Vec<_>>()
        .join(", ");
    let stem = other
        .iter()
        .zip(s)
        .map(|(&j, v)| {
            let v = if table.axes[j] == "ground_motion.file" {
                show_value(&table.axes[j], v)
            } else {
                v.clone()
            };
            format!("_{}={}", file_key(&table.axes[j]), sanitize(&v))
        })
        .collect();
    (fixed, stem)
}

/// The subtitle: the slice's fixed values and the base scenario the other keys come from.
fn held_fixed(fixed: &str, base: Option<&str>) -> String {
    let rest = match base {
        Some(b) => format!("other keys as in {b}"),
        None => "other keys as in the base scenario".to_string(),
    };
    if fixed.is_empty() {
        rest
    } else {
        format!("{fixed}; {rest}")
    }
}

fn find_axis(table: &Table, key: &str) -> Result<usize, SweepError> {
    let norm = key.replace('[', ".").replace(']', "");
    table.axes.iter().position(|a| *a == norm).ok_or_else(|| {
        SweepError::Usage(format!(
            "`{key}` is not an axis of {} (its axes: {})",
            table.path.display(),
            table.axes.join(", ")
        ))
    })
}

/// Draw the requested pictures of `table` into `out_dir` (created if missing). Returns the
/// files written (PNG and SVG of each picture). Titles say that the keys not swept are the
/// base scenario's; [`plot_table_of`] names it.
pub fn plot_table(
    table: &Table,
    req: &PlotRequest,
    out_dir: &Path,
) -> Result<Vec<PathBuf>, SweepError> {
    plot_table_of(table, req, out_dir, None)
}

/// [`plot_table`], naming the base scenario (e.g. `"paper-c.toml (Paper case T1/T2 = 0.7)"`)
/// in every picture's subtitle as what the keys not swept were held at.
pub fn plot_table_of(
    table: &Table,
    req: &PlotRequest,
    out_dir: &Path,
    base: Option<&str>,
) -> Result<Vec<PathBuf>, SweepError> {
    let fields: Vec<&str> = match &req.field {
        Some(f) => match Table::field_index(f).filter(|_| !table.suite) {
            Some(i) => vec![FIELDS[i]],
            // a column after the standard ones (codes, floors) that this table has
            None => match table.codes.iter().find(|c| *c == f) {
                Some(c) => vec![c.as_str()],
                None => {
                    return Err(SweepError::Usage(format!(
                        "--field `{f}` is not a result field of this table; choose one of {}",
                        FIELDS
                            .iter()
                            .copied()
                            .filter(|_| !table.suite)
                            .chain(table.codes.iter().map(String::as_str))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )));
                }
            },
        },
        None if table.suite => suite_default_fields(table),
        None => DEFAULT_FIELDS.to_vec(),
    };
    let info: Vec<(Vec<String>, bool)> =
        (0..table.axes.len()).map(|j| distinct(table, j)).collect();
    let numeric_axes: Vec<usize> = (0..table.axes.len())
        .filter(|&j| info[j].1 && info[j].0.len() > 1)
        .collect();
    let need_numeric = |j: usize| -> Result<usize, SweepError> {
        if info[j].1 {
            Ok(j)
        } else {
            Err(SweepError::Usage(format!(
                "axis `{}` does not hold numbers: it can only be a series or a slice, not an x or y axis",
                table.axes[j]
            )))
        }
    };
    let x = match &req.x {
        Some(k) => Some(need_numeric(find_axis(table, k)?)?),
        None => numeric_axes.first().copied(),
    };
    let Some(x) = x else {
        return Err(SweepError::Usage(format!(
            "{} has no numeric axis with more than one value: nothing to plot",
            table.path.display()
        )));
    };
    let y = match &req.y {
        Some(k) => {
            let y = need_numeric(find_axis(table, k)?)?;
            if y == x {
                return Err(SweepError::Usage(
                    "--x and --y must be different axes".into(),
                ));
            }
            Some(y)
        }
        None if req.x.is_none() => numeric_axes.iter().copied().find(|&j| j != x),
        None => None,
    };
    std::fs::create_dir_all(out_dir).map_err(|e| SweepError::Write {
        path: out_dir.display().to_string(),
        source: e,
    })?;
    let perr = |e: PlotError| SweepError::Usage(format!("plot: {e}"));
    let in_slice = |r: &TableRow, other: &[usize], s: &[String]| {
        other.iter().zip(s).all(|(&j, v)| r.values[j] == *v)
    };
    let xs = sorted_numbers(&info[x].0);
    let xl = axis_label(&table.axes[x]);
    let mut written = Vec::new();

    if let Some(y) = y {
        let other: Vec<usize> = (0..table.axes.len())
            .filter(|&j| j != x && j != y)
            .collect();
        let ys = sorted_numbers(&info[y].0);
        let yl = axis_label(&table.axes[y]);
        for s in slices(table, &other) {
            let (fixed, sstem) = slice_text(table, &other, &s);
            let subtitle = held_fixed(&fixed, base);
            for &field in &fields {
                let (title, short, _) = field_label(field);
                let mut z = vec![f64::NAN; xs.len() * ys.len()];
                for r in table.rows.values().filter(|r| in_slice(r, &other, &s)) {
                    let (Ok(vx), Ok(vy)) = (r.values[x].parse::<f64>(), r.values[y].parse::<f64>())
                    else {
                        continue;
                    };
                    let ix = xs.iter().position(|&a| a == vx);
                    let iy = ys.iter().position(|&a| a == vy);
                    if let (Some(ix), Some(iy)) = (ix, iy) {
                        z[iy * xs.len() + ix] = value(table, r, field);
                    }
                }
                let stem = out_dir.join(format!(
                    "heatmap_{field}_{}-{}{sstem}",
                    file_key(&table.axes[x]),
                    file_key(&table.axes[y])
                ));
                let h = Heatmap {
                    title: &title,
                    subtitle: &subtitle,
                    x_label: &xl,
                    y_label: &yl,
                    x: &xs,
                    y: &ys,
                    z: &z,
                    z_label: &short,
                    scale: field_scale(field, &z),
                    zero_label: if field.ends_with("peak_force") {
                        "0: no impact"
                    } else {
                        "0"
                    },
                    width: 1000,
                    height: 820,
                };
                written.extend(write_heatmap(&h, &stem).map_err(perr)?);
            }
        }
        if req.y.is_some() {
            return Ok(written);
        }
    }

    // line plots over x: one line per value of a series axis, one figure per slice of the rest
    let series_axis = y.or_else(|| (0..table.axes.len()).find(|&j| j != x && info[j].0.len() > 1));
    let other: Vec<usize> = (0..table.axes.len())
        .filter(|&j| j != x && Some(j) != series_axis)
        .collect();
    let (series_vals, subset) = match series_axis {
        Some(j) => {
            let mut v = info[j].0.clone();
            if info[j].1 {
                v.sort_by(|a, b| {
                    let num = |s: &String| s.parse::<f64>().unwrap_or(0.0);
                    num(a).total_cmp(&num(b))
                });
            }
            let n = v.len();
            if n > MAX_SERIES {
                v = (0..MAX_SERIES)
                    .map(|i| v[i * (n - 1) / (MAX_SERIES - 1)].clone())
                    .collect();
            }
            let subset = (n > MAX_SERIES).then(|| {
                format!(
                    "lines at {MAX_SERIES} of the {n} values of {}",
                    axis_name_short(&table.axes[j])
                )
            });
            (v, subset)
        }
        None => (vec![String::new()], None),
    };
    let labels: Vec<String> = series_vals
        .iter()
        .map(|v| match series_axis {
            Some(j) => format!(
                "{} = {}",
                axis_name_short(&table.axes[j]),
                show_value(&table.axes[j], v)
            ),
            None => String::new(),
        })
        .collect();
    let titles: Vec<(String, String, f64)> = fields.iter().map(|f| field_label(f)).collect();
    for s in slices(table, &other) {
        let (fixed, sstem) = slice_text(table, &other, &s);
        // data[field][series] = y over xs
        let mut data = vec![vec![vec![f64::NAN; xs.len()]; series_vals.len()]; fields.len()];
        for r in table.rows.values().filter(|r| in_slice(r, &other, &s)) {
            let k = match series_axis {
                Some(j) => match series_vals.iter().position(|v| *v == r.values[j]) {
                    Some(k) => k,
                    None => continue,
                },
                None => 0,
            };
            let Some(ix) = r.values[x]
                .parse::<f64>()
                .ok()
                .and_then(|vx| xs.iter().position(|&a| a == vx))
            else {
                continue;
            };
            for (fi, field) in fields.iter().enumerate() {
                data[fi][k][ix] = value(table, r, field);
            }
        }
        let panel_titles: Vec<String> = (0..fields.len())
            .map(|fi| {
                let all: Vec<f64> = data[fi].iter().flatten().copied().collect();
                let log = field_scale(fields[fi], &all) != ColorScale::Linear;
                let note = match (log, all.iter().any(|&v| v <= 0.0)) {
                    (true, true) => " (log scale; zero values not drawn)",
                    (true, false) => " (log scale)",
                    _ => "",
                };
                format!("{}{note}", titles[fi].0)
            })
            .collect();
        let panels: Vec<Panel> = (0..fields.len())
            .map(|fi| {
                let all: Vec<f64> = data[fi].iter().flatten().copied().collect();
                Panel {
                    title: &panel_titles[fi],
                    y_label: &titles[fi].1,
                    series: (0..series_vals.len())
                        .map(|k| Series {
                            label: &labels[k],
                            x: &xs,
                            y: &data[fi][k],
                            style: LineStyle::Solid,
                            color: None,
                        })
                        .collect(),
                    y_scale: match field_scale(fields[fi], &all) {
                        ColorScale::Linear => AxisScale::Linear,
                        _ => AxisScale::Log,
                    },
                }
            })
            .collect();
        let title = format!("Sweep over {}", axis_name_short(&table.axes[x]));
        let parts: Vec<String> = subset
            .iter()
            .cloned()
            .chain([held_fixed(&fixed, base)])
            .collect();
        let subtitle = parts.join("; ");
        let fig = Figure {
            title: &title,
            subtitle: &subtitle,
            x_label: &xl,
            panels,
            legend_once: true,
            width: 1100,
            height: (260 * fields.len() as u32 + 150).min(4000),
        };
        let stem = out_dir.join(format!(
            "lines_{}{sstem}{}",
            file_key(&table.axes[x]),
            if fields.len() == 1 {
                format!("_{}", fields[0])
            } else {
                String::new()
            }
        ));
        written.extend(write_figure(&fig, &stem).map_err(perr)?);
    }
    Ok(written)
}

/// Group written files by picture stem, for messages ("wrote 15 heatmaps").
pub fn count_pictures(files: &[PathBuf]) -> usize {
    let mut stems = BTreeMap::new();
    for f in files {
        stems.insert(f.with_extension(""), ());
    }
    stems.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::sweep::row_columns;

    /// Every numeric column of a row sweep has a title of its own naming its structure or pair
    /// and a unit, not its raw column name (the text columns are not drawn).
    #[test]
    fn a_row_sweeps_columns_are_titled_by_structure_and_pair() {
        // (a row's columns, then a suite on a row's)
        let suite_row = crate::study::sweep::row_suite_rows::columns(&[2, 1, 3]);
        for name in row_columns::columns(4).into_iter().chain(suite_row) {
            if row_columns::is_text(&name) || name == "statistic" {
                continue;
            }
            let (title, short, _) = field_label(&name);
            assert_ne!(title, name, "{name} has no title");
            assert_ne!(short, name, "{name} has no axis label");
            if let Some(rest) = name.strip_prefix("pair") {
                let p: usize = rest.split('_').next().unwrap().parse().unwrap();
                assert!(
                    title.starts_with(&format!("Pair {p} (structures {p}–{})", p + 1)),
                    "{name}: {title}"
                );
            }
            if let Some(rest) = name.strip_prefix("structure")
                && let Some(i) = rest.split('_').next().and_then(|i| i.parse::<usize>().ok())
            {
                assert!(
                    title.starts_with(&format!("Structure {i}:")),
                    "{name}: {title}"
                );
            }
        }
        assert_eq!(
            field_label("pair3_level2_required_separation").0,
            "Pair 3 (structures 3–4), level 2: design value of the required separation (suite)"
        );
        // a pair's force is drawn in MN, as a pair sweep's
        assert_eq!(field_label("pair2_peak_force").2, 1e-6);
        // a pair's margin and verdict on a linear colour scale, as the row's
        assert!(matches!(
            field_scale("pair3_margin", &[1e-4, 1.0]),
            ColorScale::Linear
        ));
    }
}
