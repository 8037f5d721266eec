//! Pictures of a sweep's results table, drawn with [`crate::plot`]: heatmaps of a field over
//! two numeric axes and line plots over one, one picture per combination of the other axes'
//! values (e.g. one heatmap per PGA level). Failed cases are grey cells / gaps in lines.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::plot::{Figure, Heatmap, LineStyle, Panel, Series, write_figure, write_heatmap};
use crate::sweep::SweepError;
use crate::sweep::results::{FIELDS, Table};

/// The fields drawn when none is asked for.
pub const DEFAULT_FIELDS: [&str; 5] = [
    "change_percent_1",
    "change_percent_2",
    "peak_force",
    "impacts",
    "sep_time_history",
];

/// Most lines on one line-plot panel (evenly chosen among the series axis' values).
const MAX_SERIES: usize = 6;

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

/// A field's label (with unit) and the factor from SI to the unit shown.
pub fn field_label(field: &str) -> (String, f64) {
    let s = |t: &str| t.to_string();
    match field {
        "peak_displacement_1" => (s("Peak displacement of structure 1 with pounding [m]"), 1.0),
        "peak_displacement_2" => (s("Peak displacement of structure 2 with pounding [m]"), 1.0),
        "peak_displacement_no_contact_1" => (
            s("Peak displacement of structure 1 without pounding [m]"),
            1.0,
        ),
        "peak_displacement_no_contact_2" => (
            s("Peak displacement of structure 2 without pounding [m]"),
            1.0,
        ),
        "change_percent_1" => (
            s("Change of peak displacement due to pounding, structure 1 [%]"),
            1.0,
        ),
        "change_percent_2" => (
            s("Change of peak displacement due to pounding, structure 2 [%]"),
            1.0,
        ),
        "peak_force" => (s("Peak contact force [MN]"), 1e-6),
        "impacts" => (s("Number of impacts"), 1.0),
        "contact_time" => (s("Time in contact [s]"), 1.0),
        "sep_abs" => (s("Required separation, ABS rule [m]"), 1.0),
        "sep_srss" => (s("Required separation, SRSS rule [m]"), 1.0),
        "sep_ddc" => (s("Required separation, DDC rule [m]"), 1.0),
        "sep_time_history" => (s("Required separation from the time history [m]"), 1.0),
        "check_max_change" => (
            s("Self-check: largest change against a 100× tighter run [%]"),
            100.0,
        ),
        "converged" => (s("Self-check converged within 1 % (1 = yes, 0 = no)"), 1.0),
        other => (other.to_string(), 1.0),
    }
}

/// A short panel/colour-bar label for a field.
fn short_label(field: &str) -> String {
    match field {
        "change_percent_1" => "change 1 [%]".into(),
        "change_percent_2" => "change 2 [%]".into(),
        "peak_force" => "F max [MN]".into(),
        "impacts" => "impacts".into(),
        "contact_time" => "contact [s]".into(),
        "sep_time_history" => "gap needed [m]".into(),
        other => field_label(other).0,
    }
}

/// An axis key as a person reads it.
pub fn axis_label(key: &str) -> String {
    match key {
        "period_ratio" => "T1/T2".into(),
        "ground_period_ratio" => "T2/Tg".into(),
        "ground_motion.pga" => "PGA [g]".into(),
        "ground_motion.period" => "Tg [s]".into(),
        "ground_motion.scale_to_pga" => "PGA [g]".into(),
        "ground_motion.file" => "record".into(),
        "contact.gap" => "gap [m]".into(),
        "contact.stiffness" => "contact stiffness".into(),
        "solver.dt" => "dt [s]".into(),
        k if k.starts_with("structure.") && k.ends_with(".period") => {
            format!("T{} [s]", &k[10..k.len() - 7])
        }
        k => k.to_string(),
    }
}

fn axis_name_short(key: &str) -> String {
    match key {
        "period_ratio" => "T1/T2".into(),
        "ground_period_ratio" => "T2/Tg".into(),
        "ground_motion.pga" | "ground_motion.scale_to_pga" => "PGA".into(),
        k => k.to_string(),
    }
}

/// A value for a title: numbers as written, record files by their file name.
fn show_value(key: &str, v: &str) -> String {
    let mut s = if key == "ground_motion.file" {
        Path::new(v)
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_else(|| v.to_string())
    } else {
        v.to_string()
    };
    if key == "ground_motion.pga" || key == "ground_motion.scale_to_pga" {
        s.push_str(" g");
    }
    s
}

/// An axis key as written in file names.
fn file_key(key: &str) -> String {
    match key {
        "period_ratio" => "T1T2".into(),
        "ground_period_ratio" => "T2Tg".into(),
        "ground_motion.pga" => "PGA".into(),
        k => sanitize(k),
    }
}

fn sanitize(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' || c == '=' {
                c
            } else {
                '_'
            }
        })
        .collect()
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

fn slice_text(table: &Table, other: &[usize], s: &[String]) -> (String, String) {
    let title = other
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
        .collect::<String>();
    (title, stem)
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
/// files written (PNG and SVG of each picture).
pub fn plot_table(
    table: &Table,
    req: &PlotRequest,
    out_dir: &Path,
) -> Result<Vec<PathBuf>, SweepError> {
    let fields: Vec<&str> = match &req.field {
        Some(f) => {
            let i = Table::field_index(f).ok_or_else(|| {
                SweepError::Usage(format!(
                    "--field `{f}` is not a result field; choose one of {}",
                    FIELDS.join(", ")
                ))
            })?;
            vec![FIELDS[i]]
        }
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
    let mut written = Vec::new();
    let perr = |e: crate::plot::PlotError| SweepError::Usage(format!("plot: {e}"));
    if let Some(y) = y {
        let other: Vec<usize> = (0..table.axes.len())
            .filter(|&j| j != x && j != y)
            .collect();
        let xs = sorted_numbers(&info[x].0);
        let ys = sorted_numbers(&info[y].0);
        for s in slices(table, &other) {
            let (stitle, sstem) = slice_text(table, &other, &s);
            for &field in &fields {
                let fi = Table::field_index(field).unwrap_or(0);
                let (label, scale) = field_label(field);
                let mut z = vec![f64::NAN; xs.len() * ys.len()];
                for r in table.rows.values() {
                    if other.iter().zip(&s).any(|(&j, v)| r.values[j] != *v) {
                        continue;
                    }
                    let (Ok(vx), Ok(vy)) = (r.values[x].parse::<f64>(), r.values[y].parse::<f64>())
                    else {
                        continue;
                    };
                    let ix = xs.iter().position(|&a| a == vx);
                    let iy = ys.iter().position(|&a| a == vy);
                    if let (Some(ix), Some(iy)) = (ix, iy) {
                        z[iy * xs.len() + ix] = r.fields[fi] * scale;
                    }
                }
                let title = if stitle.is_empty() {
                    label.clone()
                } else {
                    format!("{label} — {stitle}")
                };
                let (xl, yl) = (axis_label(&table.axes[x]), axis_label(&table.axes[y]));
                let stem = out_dir.join(format!(
                    "heatmap_{field}_{}-{}{sstem}",
                    file_key(&table.axes[x]),
                    file_key(&table.axes[y])
                ));
                let h = Heatmap {
                    title: &title,
                    x_label: &xl,
                    y_label: &yl,
                    x: &xs,
                    y: &ys,
                    z: &z,
                    z_label: &short_label(field),
                    width: 1000,
                    height: 800,
                };
                written.extend(write_heatmap(&h, &stem).map_err(perr)?);
            }
        }
    }
    // line plots over x: one line per value of a series axis, one figure per slice of the rest
    let series_axis = match (y, req.y.is_some()) {
        (Some(y), _) => Some(y),
        (None, _) => (0..table.axes.len()).find(|&j| j != x && info[j].0.len() > 1),
    };
    if req.y.is_none() {
        let other: Vec<usize> = (0..table.axes.len())
            .filter(|&j| j != x && Some(j) != series_axis)
            .collect();
        let xs = sorted_numbers(&info[x].0);
        let series_vals: Vec<String> = match series_axis {
            Some(j) => {
                let mut v = info[j].0.clone();
                if info[j].1 {
                    v.sort_by(|a, b| {
                        a.parse::<f64>()
                            .unwrap_or(0.0)
                            .total_cmp(&b.parse::<f64>().unwrap_or(0.0))
                    });
                }
                if v.len() > MAX_SERIES {
                    let n = v.len();
                    v = (0..MAX_SERIES)
                        .map(|i| v[i * (n - 1) / (MAX_SERIES - 1)].clone())
                        .collect();
                }
                v
            }
            None => vec![String::new()],
        };
        for s in slices(table, &other) {
            let (stitle, sstem) = slice_text(table, &other, &s);
            // data[field][series] = y over xs
            let mut data: Vec<Vec<Vec<f64>>> =
                vec![vec![vec![f64::NAN; xs.len()]; series_vals.len()]; fields.len()];
            for r in table.rows.values() {
                if other.iter().zip(&s).any(|(&j, v)| r.values[j] != *v) {
                    continue;
                }
                let k = match series_axis {
                    Some(j) => match series_vals.iter().position(|v| *v == r.values[j]) {
                        Some(k) => k,
                        None => continue,
                    },
                    None => 0,
                };
                let Ok(vx) = r.values[x].parse::<f64>() else {
                    continue;
                };
                let Some(ix) = xs.iter().position(|&a| a == vx) else {
                    continue;
                };
                for (fi, field) in fields.iter().enumerate() {
                    let c = Table::field_index(field).unwrap_or(0);
                    data[fi][k][ix] = r.fields[c] * field_label(field).1;
                }
            }
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
            let titles: Vec<String> = fields.iter().map(|f| field_label(f).0).collect();
            let ylabels: Vec<String> = fields.iter().map(|f| short_label(f)).collect();
            let panels: Vec<Panel> = fields
                .iter()
                .enumerate()
                .map(|(fi, _)| Panel {
                    title: &titles[fi],
                    y_label: &ylabels[fi],
                    series: (0..series_vals.len())
                        .map(|k| Series {
                            label: &labels[k],
                            x: &xs,
                            y: &data[fi][k],
                            style: LineStyle::Solid,
                        })
                        .collect(),
                })
                .collect();
            let title = if stitle.is_empty() {
                format!("Sweep over {}", axis_label(&table.axes[x]))
            } else {
                format!("Sweep over {} — {stitle}", axis_label(&table.axes[x]))
            };
            let xl = axis_label(&table.axes[x]);
            let fig = Figure {
                title: &title,
                x_label: &xl,
                panels,
                width: 1100,
                height: (260 * fields.len() as u32 + 120).min(4000),
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
