//! Heatmaps of a value over a grid of runs, with a colour bar.
//!
//! Each cell is centred on the grid value that was run and extends to the midpoints between
//! neighbouring values; the axes are ticked at the grid values themselves (every k-th when they
//! do not all fit, chosen so that the labels are short). A grid that is geometric, positive and
//! spans at least a factor of 10 is drawn on a logarithmic axis. The colours follow the
//! heatmap's [`ColorScale`]; the colour bar says where the scale saturates, and swatches under
//! it explain grey "no data" cells and, on a log scale, white zero cells.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::coord::ranged1d::Ranged;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::style::{
    self, AXIS, ColorScale, Fonts, NO_DATA, Ticked, ZERO, fmt_num, font, grid_ticks, ratio_color,
    text_width, viridis,
};
use super::{PlotError, Render, draw_err, draw_titles, write_both};

/// A heatmap of `z` over a grid `x × y`.
///
/// `z` is row-major with `x` fastest: `z[iy * x.len() + ix]`. Grid values may be unevenly spaced
/// or unsorted; non-finite grid values and their cells are left out. Non-finite `z` cells are
/// drawn grey and explained as "no data" under the colour bar.
#[derive(Debug, Clone)]
pub struct Heatmap<'a> {
    /// Title, drawn centred on top.
    pub title: &'a str,
    /// A second line under the title: what was held fixed. May be empty.
    pub subtitle: &'a str,
    /// X-axis label with unit.
    pub x_label: &'a str,
    /// Y-axis label with unit.
    pub y_label: &'a str,
    /// Grid values along x (columns).
    pub x: &'a [f64],
    /// Grid values along y (rows).
    pub y: &'a [f64],
    /// Cell values, `z[iy * x.len() + ix]`; length must be `x.len() * y.len()`.
    pub z: &'a [f64],
    /// Colour-bar label with unit.
    pub z_label: &'a str,
    /// How values become colours.
    pub scale: ColorScale,
    /// On a [`ColorScale::Log`] scale: what a cell ≤ 0 means (e.g. "0: no impact").
    pub zero_label: &'a str,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
}

/// Writes `<stem>.png` and `<stem>.svg` for a heatmap with colour bar; returns the paths written.
///
/// The directory of `stem` must exist. Fails if `x` or `y` has no finite value or if
/// `z.len() != x.len() * y.len()`.
pub fn write_heatmap(h: &Heatmap, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    if h.x.is_empty() || h.y.is_empty() {
        return Err(PlotError::NoData("the heatmap grid is empty".into()));
    }
    if h.x.len().checked_mul(h.y.len()) != Some(h.z.len()) {
        return Err(PlotError::InvalidInput(format!(
            "heatmap z has {} values, expected x.len() * y.len() = {} * {}",
            h.z.len(),
            h.x.len(),
            h.y.len()
        )));
    }
    for (v, what) in [(h.x, "x"), (h.y, "y")] {
        if !v.iter().any(|v| v.is_finite()) {
            return Err(PlotError::NoData(format!(
                "the {what} grid has no finite value"
            )));
        }
    }
    write_both(h, stem, h.width, h.height)
}

/// One grid axis: the finite values' original indices in ascending order, the cell edges and
/// the ticks, in plot coordinates (the value, or its `log10` on a log axis).
struct Grid {
    order: Vec<usize>,
    edges: Vec<f64>,
    ticks: Vec<f64>,
    log: bool,
}

impl Grid {
    /// The axis of `values` over `pixels` with labels `label_px` apart at the least.
    fn new(values: &[f64], pixels: i32, label_px: f64) -> Grid {
        let mut order: Vec<usize> = (0..values.len())
            .filter(|&i| values[i].is_finite())
            .collect();
        order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
        let v: Vec<f64> = order
            .iter()
            .map(|&i| values[i].clamp(-1e300, 1e300))
            .collect();
        let log = is_geometric(&v);
        let t: Vec<f64> = v.iter().map(|&x| if log { x.log10() } else { x }).collect();
        let n = t.len();
        let (first, last) = (t[0], t[n - 1]);
        let edges: Vec<f64> = if last - first <= first.abs().max(last.abs()) * 1e-12 {
            // one value (or all equal): one cell around it
            let (lo, hi) = style::pad(Some((first, first)), 0.0);
            std::iter::repeat_n(lo, n).chain([hi]).collect()
        } else {
            let mut e = vec![t[0] - 0.5 * (t[1] - t[0])];
            e.extend(t.windows(2).map(|w| 0.5 * (w[0] + w[1])));
            e.push(t[n - 1] + 0.5 * (t[n - 1] - t[n - 2]));
            e
        };
        let mut distinct = v.clone();
        distinct.dedup();
        let fit = (pixels as f64 / label_px).floor().max(1.0) as usize;
        let ticks = grid_ticks(&distinct, fit)
            .into_iter()
            .map(|x| if log { x.log10() } else { x })
            .collect();
        Grid {
            order,
            edges,
            ticks,
            log,
        }
    }

    fn coord(&self) -> Ticked {
        Ticked {
            lo: self.edges[0],
            hi: self.edges[self.edges.len() - 1],
            ticks: self.ticks.clone(),
        }
    }

    fn label(&self, v: f64) -> String {
        fmt_num(if self.log { 10f64.powf(v) } else { v })
    }
}

/// True if the (sorted, finite) values are positive, span at least a factor of 10 and are more
/// evenly spaced in log than in linear terms.
fn is_geometric(v: &[f64]) -> bool {
    if v.len() < 3 || v[0] <= 0.0 || v[v.len() - 1] / v[0] < 10.0 {
        return false;
    }
    let spread = |d: Vec<f64>| {
        let (mn, mx) = style::finite_range(d).unwrap_or((0.0, 0.0));
        if mn > 0.0 { mx / mn } else { f64::INFINITY }
    };
    spread(v.windows(2).map(|w| (w[1] / w[0]).log10()).collect())
        < spread(v.windows(2).map(|w| w[1] - w[0]).collect())
}

/// The colour bar: its range and ticks in bar units, and how a bar unit and a value map to
/// colours.
struct Bar {
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
    scale: ColorScale,
}

impl Bar {
    fn new(scale: ColorScale, z: &[f64], n: usize) -> Bar {
        let (lo, hi, ticks) = match scale {
            ColorScale::Linear => {
                let (lo, hi) = style::pad(style::finite_range(z.iter().copied()), 0.0);
                let t = RangedCoordf64::from(lo..hi).key_points(n);
                let t = t
                    .into_iter()
                    .map(|t: f64| if t.abs() < 1e-9 * (hi - lo) { 0.0 } else { t });
                (lo, hi, t.collect())
            }
            ColorScale::Log => {
                let r = style::positive_range(z).map(|(a, b)| (a.log10(), b.log10()));
                let (lo, hi) = style::pad(r, 0.0);
                let t = style::log_ticks(10f64.powf(lo), 10f64.powf(hi), n);
                (lo, hi, t.into_iter().map(f64::log10).collect())
            }
            ColorScale::Ratio { limit } => {
                let l = limit.log10();
                let t = style::log_ticks(1.0 / limit, limit, n);
                (-l, l, t.into_iter().map(f64::log10).collect())
            }
        };
        Bar {
            lo,
            hi,
            ticks,
            scale,
        }
    }

    /// Colour at bar unit `u`.
    fn color_at(&self, u: f64) -> RGBColor {
        match self.scale {
            ColorScale::Ratio { limit } => ratio_color(10f64.powf(u), limit),
            _ => viridis((u - self.lo) / (self.hi - self.lo)),
        }
    }

    /// Colour of a cell value.
    fn color(&self, z: f64) -> RGBColor {
        match self.scale {
            _ if z.is_nan() => NO_DATA,
            ColorScale::Linear if z.is_finite() => self.color_at(z),
            ColorScale::Log if z <= 0.0 => ZERO,
            ColorScale::Log if z.is_finite() => self.color_at(z.log10()),
            ColorScale::Ratio { limit } => ratio_color(z, limit),
            _ => NO_DATA,
        }
    }

    fn label(&self, u: f64) -> String {
        let end = |v: f64| (u - v).abs() < 1e-9 * (self.hi - self.lo);
        match self.scale {
            ColorScale::Linear => fmt_num(u),
            ColorScale::Log => fmt_num(10f64.powf(u)),
            ColorScale::Ratio { .. } => {
                let sign = if end(self.lo) {
                    "≤ "
                } else if end(self.hi) {
                    "≥ "
                } else {
                    ""
                };
                format!("{sign}×{}", fmt_num(10f64.powf(u)))
            }
        }
    }
}

const BAR: i32 = 26;

impl Render for Heatmap<'_> {
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _bitmap: bool,
    ) -> Result<(), PlotError> {
        let f = Fonts::for_size(self.width, self.height);
        let top = draw_titles(root, self.title, self.subtitle, f)?;
        let (w, h) = (self.width as i32, self.height as i32);
        let x_area_h = (f.tick * 1.4 + f.text * 1.6) as i32 + 12;
        let plot_h = (h - top - x_area_h - 10).max(10);
        let bar = Bar::new(
            self.scale,
            self.z,
            (plot_h as f64 / (f.tick * 2.8)) as usize,
        );
        let missing = self.z.iter().any(|z| z.is_nan());
        let zeros = self.scale == ColorScale::Log && self.z.iter().any(|&z| z <= 0.0);
        let swatches: Vec<(RGBColor, &str)> = [
            (missing, NO_DATA, "no data"),
            (zeros, ZERO, self.zero_label),
        ]
        .into_iter()
        .filter(|s| s.0)
        .map(|s| (s.1, s.2))
        .collect();

        // widths: y tick labels, colour-bar tick labels and label, swatch texts
        let gy = Grid::new(self.y, plot_h, f.tick * 2.2);
        let widest = |labels: Vec<String>| labels.iter().map(|s| text_width(s, f.tick)).max();
        let y_area_w = widest(gy.ticks.iter().map(|&t| gy.label(t)).collect()).unwrap_or(0)
            + (f.text * 1.6) as i32
            + 16;
        let bar_labels_w = widest(bar.ticks.iter().map(|&t| bar.label(t)).collect()).unwrap_or(0)
            + (f.text * 1.6) as i32
            + 16;
        let swatch_w = widest(swatches.iter().map(|s| s.1.to_string()).collect()).unwrap_or(0);
        let bar_w = 28 + (BAR + bar_labels_w).max(BAR + 8 + swatch_w) + 12;
        let plot_w = (w - y_area_w - bar_w).max(10);
        let x_label_px = |g: &Grid| {
            widest(g.ticks.iter().map(|&t| g.label(t)).collect()).unwrap_or(0) as f64 + f.tick * 1.5
        };
        let mut gx = Grid::new(self.x, plot_w, f.tick * 3.0);
        let px = x_label_px(&gx);
        if gx.ticks.len() as f64 * px > plot_w as f64 {
            gx = Grid::new(self.x, plot_w, px);
        }

        let area = root
            .clone()
            .shrink((0, top), (w as u32, (h - top).max(1) as u32));
        let (main, side) = area.split_horizontally(w - bar_w);
        let mut chart = ChartBuilder::on(&main)
            .margin_top(8)
            .margin_left((f.text * 0.7) as u32)
            .set_label_area_size(LabelAreaPosition::Left, y_area_w as u32)
            .set_label_area_size(LabelAreaPosition::Bottom, x_area_h as u32)
            .build_cartesian_2d(gx.coord(), gy.coord())
            .map_err(draw_err)?;
        let nx = self.x.len();
        let cells = gy.order.iter().enumerate().flat_map(|(j, &iy)| {
            let (gx, bar, ey) = (&gx, &bar, &gy.edges);
            gx.order.iter().enumerate().map(move |(i, &ix)| {
                let c = bar.color(self.z[iy * nx + ix]);
                let ex = &gx.edges;
                Rectangle::new([(ex[i], ey[j]), (ex[i + 1], ey[j + 1])], c.filled())
            })
        });
        chart.draw_series(cells).map_err(draw_err)?;
        let (x_fmt, y_fmt) = (|v: &f64| gx.label(*v), |v: &f64| gy.label(*v));
        chart
            .configure_mesh()
            .disable_mesh()
            .axis_style(AXIS)
            .set_all_tick_mark_size(5)
            .label_style(font(f.tick).color(&AXIS))
            .axis_desc_style(font(f.text).color(&BLACK))
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .draw()
            .map_err(draw_err)?;

        // colour bar, level with the plot area
        let mut cbar = ChartBuilder::on(&side)
            .margin_top(8)
            .margin_left(28)
            .margin_bottom(x_area_h as u32)
            .margin_right((bar_w - 28 - BAR - bar_labels_w).max(0) as u32)
            .set_label_area_size(LabelAreaPosition::Right, bar_labels_w as u32)
            .build_cartesian_2d(
                0.0..1.0,
                Ticked {
                    lo: bar.lo,
                    hi: bar.hi,
                    ticks: bar.ticks.clone(),
                },
            )
            .map_err(draw_err)?;
        let steps = 240;
        let du = (bar.hi - bar.lo) / steps as f64;
        cbar.draw_series((0..steps).map(|k| {
            let u = bar.lo + du * k as f64;
            Rectangle::new(
                [(0.0, u), (1.0, u + du)],
                bar.color_at(u + 0.5 * du).filled(),
            )
        }))
        .map_err(draw_err)?;
        // the bar's labels are drawn below, left-aligned (plotters aligns right-side labels
        // by a width heuristic that leaves "≥ ×10" and "×5" ragged)
        let z_fmt = |_: &f64| String::new();
        cbar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .axis_style(AXIS)
            .set_all_tick_mark_size(5)
            .label_style(font(f.tick).color(&AXIS))
            .axis_desc_style(font(f.text).color(&BLACK))
            .y_label_formatter(&z_fmt)
            .y_desc(self.z_label)
            .draw()
            .map_err(draw_err)?;
        let style = font(f.tick)
            .color(&AXIS)
            .pos(Pos::new(HPos::Left, VPos::Center));
        for &t in &bar.ticks {
            let (bx, by) = cbar.backend_coord(&(1.0, t));
            root.draw_text(&bar.label(t), &style, (bx + 10, by))
                .map_err(draw_err)?;
        }
        for area in [
            chart.plotting_area().strip_coord_spec(),
            cbar.plotting_area().strip_coord_spec(),
        ] {
            let (pw, ph) = area.dim_in_pixel();
            area.draw(&Rectangle::new(
                [(0, 0), (pw as i32 - 1, ph as i32 - 1)],
                AXIS,
            ))
            .map_err(draw_err)?;
        }

        // swatches under the colour bar
        let (_, sh) = side.dim_in_pixel();
        let row = (f.tick * 1.6) as i32;
        let mut y = sh as i32 - x_area_h + 12;
        for (c, text) in swatches {
            let r = [(28, y), (28 + BAR, y + row - 6)];
            side.draw(&Rectangle::new(r, c.filled()))
                .map_err(draw_err)?;
            side.draw(&Rectangle::new(r, AXIS)).map_err(draw_err)?;
            let style = font(f.tick)
                .color(&AXIS)
                .pos(Pos::new(HPos::Left, VPos::Center));
            side.draw_text(text, &style, (28 + BAR + 8, y + (row - 6) / 2))
                .map_err(draw_err)?;
            y += row;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{check_outputs, temp_dir};
    use super::*;

    fn base<'a>(x: &'a [f64], y: &'a [f64], z: &'a [f64], scale: ColorScale) -> Heatmap<'a> {
        Heatmap {
            title: "H",
            subtitle: "",
            x_label: "x",
            y_label: "y",
            x,
            y,
            z,
            z_label: "z",
            scale,
            zero_label: "0",
            width: 500,
            height: 400,
        }
    }

    #[test]
    fn heatmaps_with_nasty_data_are_written() {
        let dir = temp_dir("heat");
        let x: Vec<f64> = (0..9).map(|i| 0.005 * 2f64.powi(i)).collect();
        let y: Vec<f64> = (0..10).map(|j| 0.5 + 0.25 * j as f64).collect();
        let z: Vec<f64> = (0..90)
            .map(|k| {
                if k == 31 {
                    f64::NAN
                } else {
                    10f64.powf((k as f64 - 45.0) / 20.0)
                }
            })
            .collect();
        for (i, scale) in [
            ColorScale::Linear,
            ColorScale::Log,
            ColorScale::Ratio { limit: 10.0 },
        ]
        .into_iter()
        .enumerate()
        {
            let p = write_heatmap(&base(&x, &y, &z, scale), &dir.join(format!("h{i}"))).unwrap();
            check_outputs(&dir, &p, 500, 400, "H");
        }
        // one NaN cell; constant z on a duplicated, unsorted grid with a NaN coordinate; huge
        // and zero values on a log scale
        write_heatmap(
            &base(&[1.0], &[2.0], &[f64::NAN], ColorScale::Log),
            &dir.join("one"),
        )
        .unwrap();
        let (gx, gy) = ([3.0, 1.0, 1.0, f64::NAN], [5.0, 0.0]);
        write_heatmap(
            &base(&gx, &gy, &[4.0; 8], ColorScale::Linear),
            &dir.join("c"),
        )
        .unwrap();
        let z2 = [1e308, -1e308, f64::INFINITY, 1e-320, 0.0, -0.0, 1.0, 2.0];
        for scale in [
            ColorScale::Linear,
            ColorScale::Log,
            ColorScale::Ratio { limit: 10.0 },
        ] {
            write_heatmap(&base(&gx, &gy, &z2, scale), &dir.join("huge")).unwrap();
        }
        let bad = base(&gx, &gy, &z2[..3], ColorScale::Linear);
        assert!(matches!(
            write_heatmap(&bad, &dir.join("bad")),
            Err(PlotError::InvalidInput(_))
        ));
        let empty = base(&[], &gy, &[], ColorScale::Linear);
        assert!(matches!(
            write_heatmap(&empty, &dir.join("e")),
            Err(PlotError::NoData(_))
        ));
        assert!(
            write_heatmap(
                &base(&[f64::NAN], &[1.0], &[1.0], ColorScale::Log),
                &dir.join("n")
            )
            .is_err()
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn grid_ticks_are_the_values_run() {
        // 0.2, 0.5, 0.8 on a wide axis: exactly these three, at the cells' centres
        let g = Grid::new(&[0.8, 0.2, 0.5], 800, 40.0);
        assert_eq!(g.ticks, [0.2, 0.5, 0.8]);
        assert!(!g.log);
        for (k, t) in g.ticks.iter().enumerate() {
            assert!((0.5 * (g.edges[k] + g.edges[k + 1]) - t).abs() < 1e-12);
        }
        // a geometric grid is drawn in log10 and ticked at its own values
        let v = [0.01, 0.1, 1.0, 10.0];
        let g = Grid::new(&v, 800, 40.0);
        assert!(g.log);
        assert_eq!(
            g.ticks.iter().map(|&t| g.label(t)).collect::<Vec<_>>(),
            ["0.01", "0.1", "1", "10"]
        );
    }

    #[test]
    fn ratio_bar_saturation_is_stated() {
        let bar = Bar::new(ColorScale::Ratio { limit: 10.0 }, &[], 10);
        let labels: Vec<String> = bar.ticks.iter().map(|&t| bar.label(t)).collect();
        assert_eq!(
            labels,
            ["≤ ×0.1", "×0.2", "×0.5", "×1", "×2", "×5", "≥ ×10"]
        );
    }
}
