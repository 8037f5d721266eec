//! Stacked line figures: panels one above the other over one shared x axis (the time-history
//! figure, a sweep's line plots). plotters draws the axes, ticks, grid and axis labels; this
//! module lays the panels out, puts each panel's legend beside its title (outside the data,
//! which fills time histories edge to edge), and draws the lines themselves (see
//! `draw_line` for why).

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::coord::ranged1d::Ranged;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::style::{self, AXIS, Fonts, GRID, PALETTE, Ticked, fmt_num, font, text_width};
use super::{PlotError, Render, draw_err, draw_titles, write_both};

/// How a line is drawn; its colour comes from the series' position within its panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineStyle {
    /// A continuous line.
    Solid,
    /// A dashed line.
    Dashed,
}

/// Scale of a panel's y axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AxisScale {
    /// Linear.
    #[default]
    Linear,
    /// Logarithmic; values ≤ 0 are not drawn (the line breaks there).
    Log,
}

/// One line on a panel.
///
/// Points are taken pairwise from `x` and `y` (the longer slice is truncated); the line is broken
/// at any point whose `x` or `y` is not finite.
#[derive(Debug, Clone)]
pub struct Series<'a> {
    /// Legend text (a legend is shown when the panel has more than one series); empty: not in
    /// the legend.
    pub label: &'a str,
    /// Abscissae, normally increasing.
    pub x: &'a [f64],
    /// Ordinates.
    pub y: &'a [f64],
    /// Solid or dashed.
    pub style: LineStyle,
    /// Palette index, so that a colour can mean the same thing in every panel and figure
    /// (e.g. a structure); `None`: by the series' position within its panel.
    pub color: Option<usize>,
}

/// One panel (subplot) of a stacked figure, sharing the figure's x axis.
#[derive(Debug, Clone)]
pub struct Panel<'a> {
    /// Panel title, drawn above the panel on the left.
    pub title: &'a str,
    /// Y-axis label, including the unit, e.g. `"w1 [m]"`.
    pub y_label: &'a str,
    /// The lines; colours are each series' `color`, or assigned by index, from a
    /// colour-blind-safe palette (Okabe–Ito), and the lines are drawn last to first, so the
    /// first lies on top.
    pub series: Vec<Series<'a>>,
    /// Linear or logarithmic y axis.
    pub y_scale: AxisScale,
}

/// Stacked panels over one x axis: e.g. the time-history figure.
#[derive(Debug, Clone)]
pub struct Figure<'a> {
    /// Figure title, drawn centred on top.
    pub title: &'a str,
    /// A second line under the title (what was held fixed, what is shown); may be empty.
    pub subtitle: &'a str,
    /// X-axis label, including the unit, e.g. `"t [s]"`; shown under the bottom panel.
    pub x_label: &'a str,
    /// The panels, top to bottom.
    pub panels: Vec<Panel<'a>>,
    /// Show the legend on the first panel only (every panel has the same series).
    pub legend_once: bool,
    /// Picture width in pixels (also the SVG's nominal width).
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
}

/// Writes `<stem>.png` and `<stem>.svg` for a stacked figure; returns the paths written.
///
/// The directory of `stem` must exist. Fails with [`PlotError::NoData`] if the figure has no
/// panels; panels without finite data are drawn as empty axes.
pub fn write_figure(fig: &Figure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    if fig.panels.is_empty() {
        return Err(PlotError::NoData("the figure has no panels".into()));
    }
    write_both(fig, stem, fig.width, fig.height)
}

/// Plot coordinate of a value: itself, or its `log10` on a log axis (`None` if not drawable).
fn to_plot(v: f64, scale: AxisScale) -> Option<f64> {
    match scale {
        AxisScale::Linear if v.is_finite() => Some(v.clamp(-1e300, 1e300)),
        AxisScale::Log if v.is_finite() && v > 0.0 => Some(v.log10()),
        _ => None,
    }
}

/// An axis in plot coordinates with its ticks (in plot coordinates) and labels.
struct Axis {
    lo: f64,
    hi: f64,
    scale: AxisScale,
    ticks: Vec<f64>,
}

impl Axis {
    /// The axis over finite plot-coordinate range `r`, padded by `pad`, with about `n` ticks
    /// (plotters' own choice on a linear axis).
    fn new(r: Option<(f64, f64)>, pad: f64, scale: AxisScale, n: usize) -> Axis {
        let (lo, hi) = style::pad(r, pad);
        let ticks = match scale {
            // (plotters' ticks may put −2.8e-17 for 0; on a short panel its coarse choice can
            // leave a lone tick, e.g. only 0 on ±0.045: then a finer one, so the axis has a
            // scale)
            AxisScale::Linear => {
                let pick = |k: usize| -> Vec<f64> {
                    (RangedCoordf64::from(lo..hi).key_points(k).into_iter())
                        .map(|t: f64| if t.abs() < 1e-9 * (hi - lo) { 0.0 } else { t })
                        .collect()
                };
                let first = pick(n.max(2));
                if first.len() < 2 {
                    pick(2 * n.max(2))
                } else {
                    first
                }
            }
            AxisScale::Log => style::log_ticks(10f64.powf(lo), 10f64.powf(hi), n.max(2))
                .into_iter()
                .map(f64::log10)
                .collect(),
        };
        Axis {
            lo,
            hi,
            scale,
            ticks,
        }
    }

    fn label(&self, v: f64) -> String {
        match self.scale {
            AxisScale::Linear => fmt_num(v),
            AxisScale::Log => fmt_num(10f64.powf(v)),
        }
    }

    fn coord(&self) -> Ticked {
        Ticked {
            lo: self.lo,
            hi: self.hi,
            ticks: self.ticks.clone(),
        }
    }
}

const LEGEND_SAMPLE: i32 = 34;
const LINE_WIDTH: u32 = 2;

impl Render for Figure<'_> {
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        bitmap: bool,
    ) -> Result<(), PlotError> {
        let f = Fonts::for_size(self.width, self.height);
        let top = draw_titles(root, self.title, self.subtitle, f)?;
        let (w, h) = (self.width as i32, self.height as i32);
        let n = self.panels.len() as i32;

        // layout: a header line per panel (two when its legend does not fit beside its title)
        let line_h = (f.text * 1.6) as i32;
        let x_area_h = (f.tick * 1.4 + f.text * 1.6) as i32 + 10;
        // plotters centres the rotated y label on the label area's left edge: leave room
        let desc_room = (f.text * 0.7) as u32;
        let y_area_w = (f.tick * 3.9 + f.text * 0.9) as i32 + 14;
        let right = (f.tick * 1.5) as i32;
        let plot_w = (w - y_area_w - desc_room as i32 - right).max(10);
        let legend_w = |p: &Panel| -> i32 {
            p.series
                .iter()
                .filter(|s| !s.label.is_empty())
                .map(|s| LEGEND_SAMPLE + 8 + text_width(s.label, f.tick) + 22)
                .sum()
        };
        let shows_legend =
            |i: usize, p: &Panel| p.series.len() > 1 && (i == 0 || !self.legend_once);
        let header_rows: Vec<i32> = (self.panels.iter().enumerate())
            .map(|(i, p)| {
                let title_w = text_width(p.title, f.text) + 30;
                match shows_legend(i, p) {
                    true if title_w + legend_w(p) > plot_w => 2,
                    _ => 1,
                }
            })
            .collect();
        let gap = (f.tick * 0.5) as i32;
        let headers: i32 = header_rows.iter().sum::<i32>() * line_h;
        let plot_h = ((h - top - headers - x_area_h - gap * n) / n).max(10);

        let x_range = style::finite_range(self.panels.iter().flat_map(|p| {
            p.series
                .iter()
                .flat_map(|s| s.x.iter().zip(s.y).filter(|(_, y)| y.is_finite()))
                .map(|(x, _)| *x)
        }));
        let x = Axis::new(x_range, 0.0, AxisScale::Linear, (plot_w / 90) as usize);

        let mut y0 = top;
        for (i, p) in self.panels.iter().enumerate() {
            let bottom = i + 1 == self.panels.len();
            let header_h = header_rows[i] * line_h;
            let panel_h = header_h + plot_h + if bottom { x_area_h } else { gap };
            let area = root
                .clone()
                .shrink((0, y0), (w as u32, panel_h.max(1) as u32));
            y0 += panel_h;
            let (header, body) = area.split_vertically(header_h);

            // header: title on the left, legend on the right (on the title line if it fits)
            let left = |size: f64| {
                font(size)
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Left, VPos::Center))
            };
            header
                .draw_text(
                    p.title,
                    &left(f.text),
                    (y_area_w + desc_room as i32, line_h / 2),
                )
                .map_err(draw_err)?;
            if shows_legend(i, p) {
                let cy = header_h - line_h / 2;
                let mut lx = w - right - legend_w(p) + 22;
                for (k, s) in p.series.iter().enumerate() {
                    if s.label.is_empty() {
                        continue;
                    }
                    let (bx, by) = header.get_base_pixel();
                    let pts = [(bx + lx, by + cy), (bx + lx + LEGEND_SAMPLE, by + cy)];
                    draw_line(root, &pts, color(s.color.unwrap_or(k)), s.style, bitmap)?;
                    lx += LEGEND_SAMPLE + 8;
                    header
                        .draw_text(s.label, &left(f.tick), (lx, cy))
                        .map_err(draw_err)?;
                    lx += text_width(s.label, f.tick) + 22;
                }
            }

            // the chart: plotters' mesh, ticks and axis labels
            let ys: Vec<f64> = (p.series.iter())
                .flat_map(|s| s.y.iter().zip(s.x).filter(|(_, x)| x.is_finite()))
                .filter_map(|(y, _)| to_plot(*y, p.y_scale))
                .collect();
            let y_pad = if p.y_scale == AxisScale::Log {
                0.04
            } else {
                0.06
            };
            let ya = Axis::new(
                style::finite_range(ys),
                y_pad,
                p.y_scale,
                (plot_h as f64 / (f.tick * 2.6)) as usize,
            );
            let mut chart = ChartBuilder::on(&body)
                .margin_left(desc_room)
                .margin_right(right as u32)
                .margin_bottom(if bottom { 0 } else { gap as u32 })
                .set_label_area_size(LabelAreaPosition::Left, y_area_w as u32)
                .set_label_area_size(
                    LabelAreaPosition::Bottom,
                    if bottom { x_area_h } else { 0 } as u32,
                )
                .build_cartesian_2d(x.coord(), ya.coord())
                .map_err(draw_err)?;
            let (x_fmt, y_fmt) = (|v: &f64| x.label(*v), |v: &f64| ya.label(*v));
            let mut mesh = chart.configure_mesh();
            mesh.bold_line_style(GRID)
                .light_line_style(TRANSPARENT)
                .axis_style(AXIS)
                .set_all_tick_mark_size(5)
                .label_style(font(f.tick).color(&AXIS))
                .axis_desc_style(font(f.text).color(&BLACK))
                .x_label_formatter(&x_fmt)
                .y_label_formatter(&y_fmt)
                .y_desc(p.y_label);
            if bottom {
                mesh.x_desc(self.x_label);
            }
            mesh.draw().map_err(draw_err)?;
            if p.y_scale == AxisScale::Linear && ya.lo < 0.0 && ya.hi > 0.0 {
                let zero = [(x.lo, 0.0), (x.hi, 0.0)];
                chart
                    .draw_series([PathElement::new(zero, RGBColor(160, 160, 160))])
                    .map_err(draw_err)?;
            }

            // the lines, last first, so that the first series lies on top
            for (k, s) in p.series.iter().enumerate().rev() {
                let mut run: Vec<(i32, i32)> = Vec::new();
                let pts = s.x.iter().zip(s.y).map(|(&px, &py)| {
                    let q = to_plot(py, p.y_scale).filter(|_| px.is_finite());
                    q.map(|q| chart.backend_coord(&(px.clamp(x.lo, x.hi), q.clamp(ya.lo, ya.hi))))
                });
                for q in pts.chain([None]) {
                    match q {
                        Some(c) => run.push(c),
                        None if !run.is_empty() => {
                            draw_line(root, &run, color(s.color.unwrap_or(k)), s.style, bitmap)?;
                            run.clear();
                        }
                        None => {}
                    }
                }
            }
            let plain = chart.plotting_area().strip_coord_spec();
            let (pw, ph) = plain.dim_in_pixel();
            plain
                .draw(&Rectangle::new(
                    [(0, 0), (pw as i32 - 1, ph as i32 - 1)],
                    AXIS,
                ))
                .map_err(draw_err)?;
        }
        Ok(())
    }
}

fn color(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// Draws a line through pixel points (absolute coordinates on `root`), solid or dashed.
///
/// On a bitmap the line is first thinned to the points that change what is drawn ([`thin`]);
/// the bitmap draws a thick polyline segment by segment, without miter joins, which would
/// shoot spikes above sharp peaks (an impact drawn higher than its force; see
/// `super::canvas`). Dashes are cut along the whole line, so the pattern runs on over short
/// segments.
fn draw_line<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    pts: &[(i32, i32)],
    color: RGBColor,
    style: LineStyle,
    bitmap: bool,
) -> Result<(), PlotError> {
    let stroke = ShapeStyle::from(&color).stroke_width(LINE_WIDTH);
    if let [c] = pts {
        return root
            .draw(&Circle::new(*c, LINE_WIDTH as i32, stroke.filled()))
            .map_err(draw_err);
    }
    let pts = &if bitmap {
        thin(&simplify(pts), 0.5)
    } else {
        simplify(pts)
    };
    let pieces = match style {
        LineStyle::Solid => vec![pts.clone()],
        LineStyle::Dashed => dashes(pts, 9.0, 5.0),
    };
    for piece in pieces {
        root.draw(&PathElement::new(piece, stroke))
            .map_err(draw_err)?;
    }
    Ok(())
}

/// The same pixel polyline with fewer points, drawing the same pixels: of a run of points in
/// one pixel column only the first, the lowest, the highest and the last are kept, in their
/// order (the segments between them cover the same vertical span, so every peak stays drawn),
/// and a point on the straight segment between its neighbours is dropped (a flat stretch, such
/// as the force between impacts, becomes one segment; the path's length, and so the dashes
/// along it, do not change). A history of 20 000 samples drawn 1 000 pixels wide becomes ~4
/// points per column instead of 20.
fn simplify(pts: &[(i32, i32)]) -> Vec<(i32, i32)> {
    let mut cols: Vec<(i32, i32)> = Vec::with_capacity(pts.len());
    let mut i = 0;
    while i < pts.len() {
        let x = pts[i].0;
        let mut j = i + 1;
        while j < pts.len() && pts[j].0 == x {
            j += 1;
        }
        let run = &pts[i..j];
        if run.len() <= 4 {
            cols.extend_from_slice(run);
        } else {
            let lo = (0..run.len()).min_by_key(|&k| run[k].1).unwrap_or(0);
            let hi = (0..run.len()).max_by_key(|&k| run[k].1).unwrap_or(0);
            let (a, b) = (lo.min(hi), lo.max(hi));
            for k in [0, a, b, run.len() - 1] {
                if cols.last() != Some(&run[k]) {
                    cols.push(run[k]);
                }
            }
        }
        i = j;
    }
    let mut out: Vec<(i32, i32)> = Vec::with_capacity(cols.len());
    for &p in &cols {
        if out.last() == Some(&p) {
            continue;
        }
        if let [.., a, b] = out[..] {
            let (u, v) = ((b.0 - a.0) as i64, (b.1 - a.1) as i64);
            let (s, t) = ((p.0 - b.0) as i64, (p.1 - b.1) as i64);
            // b on the segment a–p: collinear and not turning back
            if u * t == v * s && u * s + v * t >= 0 {
                out.pop();
            }
        }
        out.push(p);
    }
    out
}

/// For the bitmap: the polyline with the points dropped that lie within `tol` pixels of the
/// chord that replaces them (Douglas–Peucker), between points where x or y turns back, which
/// are all kept — so every peak and trough is drawn exactly where it is, and a stretch between
/// them moves by less than `tol` (half a pixel: the same pixels up to the rasteriser's
/// rounding). A smooth history of 2 000 samples needs a few hundred segments, and each
/// segment has a fixed cost besides its pixels.
fn thin(pts: &[(i32, i32)], tol: f64) -> Vec<(i32, i32)> {
    let n = pts.len();
    if n < 3 {
        return pts.to_vec();
    }
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let turns = |a: i32, b: i32, c: i32| (b - a).signum() * (c - b).signum() < 0;
    let mut last_dir = [0i32; 2];
    for i in 1..n - 1 {
        // a turn in x or y, also across a flat run (the last non-zero direction)
        for (k, (a, b)) in [(pts[i - 1].0, pts[i].0), (pts[i - 1].1, pts[i].1)]
            .into_iter()
            .enumerate()
        {
            if b != a {
                last_dir[k] = (b - a).signum();
            }
        }
        let next = [
            (pts[i + 1].0 - pts[i].0).signum(),
            (pts[i + 1].1 - pts[i].1).signum(),
        ];
        if (0..2).any(|k| last_dir[k] * next[k] < 0)
            || turns(pts[i - 1].0, pts[i].0, pts[i + 1].0)
            || turns(pts[i - 1].1, pts[i].1, pts[i + 1].1)
        {
            keep[i] = true;
        }
    }
    // Douglas–Peucker between consecutive kept points (an explicit stack)
    let anchors: Vec<usize> = (0..n).filter(|&i| keep[i]).collect();
    let mut stack: Vec<(usize, usize)> = anchors.windows(2).map(|w| (w[0], w[1])).collect();
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (p, q) = (pts[a], pts[b]);
        let (dx, dy) = (f64::from(q.0 - p.0), f64::from(q.1 - p.1));
        let len = dx.hypot(dy);
        let (mut worst, mut at) = (0.0, a);
        for (i, r) in pts.iter().enumerate().take(b).skip(a + 1) {
            let (rx, ry) = (f64::from(r.0 - p.0), f64::from(r.1 - p.1));
            let d = if len > 0.0 {
                (dx * ry - dy * rx).abs() / len
            } else {
                rx.hypot(ry)
            };
            if d > worst {
                (worst, at) = (d, i);
            }
        }
        if worst > tol {
            keep[at] = true;
            stack.push((a, at));
            stack.push((at, b));
        }
    }
    (0..n).filter(|&i| keep[i]).map(|i| pts[i]).collect()
}

/// Cuts a pixel polyline into dashes `on` long, `off` apart.
fn dashes(pts: &[(i32, i32)], on: f64, off: f64) -> Vec<Vec<(i32, i32)>> {
    let p = |q: (f64, f64)| (q.0.round() as i32, q.1.round() as i32);
    let mut out = Vec::new();
    let mut cur = vec![pts[0]];
    let (mut drawing, mut left) = (true, on);
    for s in pts.windows(2) {
        let (mut a, b) = (
            (s[0].0 as f64, s[0].1 as f64),
            (s[1].0 as f64, s[1].1 as f64),
        );
        let mut d = (b.0 - a.0).hypot(b.1 - a.1);
        while d > left {
            let t = left / d;
            a = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
            if drawing {
                cur.push(p(a));
                out.push(std::mem::take(&mut cur));
            } else {
                cur = vec![p(a)];
            }
            d -= left;
            drawing = !drawing;
            left = if drawing { on } else { off };
        }
        left -= d;
        if drawing {
            cur.push(s[1]);
        }
    }
    if drawing && cur.len() > 1 {
        out.push(cur);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::test_util::{check_outputs, temp_dir};
    use super::*;

    fn s<'a>(label: &'a str, x: &'a [f64], y: &'a [f64], style: LineStyle) -> Series<'a> {
        Series {
            label,
            x,
            y,
            style,
            color: None,
        }
    }

    #[test]
    fn figures_with_nasty_data_are_written() {
        let dir = temp_dir("lines");
        let t: Vec<f64> = (0..2000).map(|i| i as f64 * 0.01).collect();
        let a: Vec<f64> = t.iter().map(|t| (2.0 * t).sin() * 0.08).collect();
        let b: Vec<f64> = t.iter().map(|t| (2.3 * t).cos() * 0.05).collect();
        let pos: Vec<f64> = t
            .iter()
            .map(|t| 10f64.powf(3.0 * (t * 0.3).sin()))
            .collect();
        let nan = [f64::NAN; 5];
        let mixed = [1.0, f64::NAN, f64::INFINITY, 2.0, f64::NEG_INFINITY, -3.0];
        let xs = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let huge = [1e308, -1e308, 0.0, f64::MAX, f64::MIN_POSITIVE, 1e-320];
        let fig = Figure {
            title: "Nasty <&> data",
            subtitle: "held fixed: nothing",
            x_label: "t [s]",
            panels: vec![
                Panel {
                    title: "two lines",
                    y_label: "w [m]",
                    series: vec![
                        s("with", &t, &a, LineStyle::Solid),
                        s("without", &t, &b, LineStyle::Dashed),
                    ],
                    y_scale: AxisScale::Linear,
                },
                Panel {
                    title: "log",
                    y_label: "r",
                    series: vec![
                        s("r", &t, &pos, LineStyle::Solid),
                        s("m", &xs, &mixed, LineStyle::Dashed),
                    ],
                    y_scale: AxisScale::Log,
                },
                Panel {
                    title: "",
                    y_label: "",
                    series: vec![
                        s("nan", &xs, &nan, LineStyle::Solid),
                        s("huge", &xs, &huge, LineStyle::Solid),
                    ],
                    y_scale: AxisScale::Linear,
                },
                Panel {
                    title: "empty",
                    y_label: "e",
                    series: vec![],
                    y_scale: AxisScale::Log,
                },
            ],
            legend_once: false,
            width: 900,
            height: 800,
        };
        let p = write_figure(&fig, &dir.join("nasty")).unwrap();
        check_outputs(&dir, &p, 900, 800, "Nasty &lt;&amp;&gt; data");
        // tiny pictures with many panels: ugly, but no panic
        let many = Figure {
            panels: vec![fig.panels[0].clone(); 30],
            width: 16,
            height: 16,
            ..fig.clone()
        };
        let _ = write_figure(&many, &dir.join("many"));
        let empty = Figure {
            panels: vec![],
            ..fig.clone()
        };
        assert!(matches!(
            write_figure(&empty, &dir.join("e")),
            Err(PlotError::NoData(_))
        ));
        let zero = Figure {
            width: 0,
            ..fig.clone()
        };
        assert!(matches!(
            write_figure(&zero, &dir.join("z")),
            Err(PlotError::InvalidInput(_))
        ));
        assert!(matches!(
            write_figure(&fig, &dir.join("no/such/dir/x")),
            Err(PlotError::Io { .. })
        ));
        check_outputs(&dir, &p, 900, 800, "Nasty");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// [`simplify`] keeps what is drawn: the first and last points, every point of the input
    /// on a segment of the output (so every peak), only points of the input in their order; a
    /// flat stretch becomes one segment; where no column holds more than 4 points, the path
    /// length (along which the dashes are laid) is unchanged. Checked on a fixed xorshift
    /// sequence of noisy polylines, dense (20 points per column) and sparse.
    #[test]
    fn simplified_lines_keep_every_peak() {
        let flat: Vec<(i32, i32)> = (0..100).map(|x| (x, 7)).collect();
        assert_eq!(simplify(&flat), vec![(0, 7), (99, 7)]);
        let mut seed: u64 = 0x2545_F491_4F6C_DD1D;
        let mut rnd = |m: i64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % m as u64) as i32
        };
        let length = |p: &[(i32, i32)]| -> f64 {
            p.windows(2)
                .map(|s| f64::from(s[1].0 - s[0].0).hypot(f64::from(s[1].1 - s[0].1)))
                .sum()
        };
        for per_column in [20, 1] {
            for _ in 0..50 {
                let n = 2000;
                let pts: Vec<(i32, i32)> = (0..n)
                    .map(|i| (i / per_column, 300 + rnd(7) - 3 + i % 97))
                    .collect();
                let out = simplify(&pts);
                assert_eq!(out.first(), pts.first());
                assert_eq!(out.last(), pts.last());
                // a subsequence of the input
                let mut it = pts.iter();
                assert!(out.iter().all(|p| it.any(|q| q == p)));
                // every input point (so every peak) lies on a segment of the output
                let on = |p: (i32, i32), a: (i32, i32), b: (i32, i32)| {
                    let (u, v) = (i64::from(b.0 - a.0), i64::from(b.1 - a.1));
                    let (s, t) = (i64::from(p.0 - a.0), i64::from(p.1 - a.1));
                    u * t == v * s && (0..=u * u + v * v).contains(&(u * s + v * t))
                };
                for &p in &pts {
                    assert!(
                        out.windows(2).any(|w| on(p, w[0], w[1])),
                        "{p:?} is not drawn"
                    );
                }
                if per_column == 1 {
                    assert!((length(&out) - length(&pts)).abs() < 1e-9 * length(&pts));
                } else {
                    assert!(out.len() <= pts.len() / 4);
                }
            }
        }
    }

    /// [`thin`]: every input point within half a pixel of the output polyline, every point
    /// where y turns (a peak or a trough) kept exactly, the ends kept, far fewer points on a
    /// smooth curve (a sine of 40 px amplitude sampled twice per pixel column).
    #[test]
    fn thinned_lines_stay_within_half_a_pixel_and_keep_the_peaks() {
        let dist = |p: (i32, i32), a: (i32, i32), b: (i32, i32)| {
            let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
            let (px, py) = (f64::from(p.0 - a.0), f64::from(p.1 - a.1));
            let l2 = dx * dx + dy * dy;
            let t = if l2 > 0.0 {
                ((px * dx + py * dy) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (px - t * dx).hypot(py - t * dy)
        };
        let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut noise = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % 3) as i32 - 1
        };
        for noisy in [false, true] {
            let pts: Vec<(i32, i32)> = (0..2000)
                .map(|i| {
                    let y = 300.0 + 40.0 * (i as f64 * 0.02).sin();
                    (i / 2, y.round() as i32 + if noisy { noise() } else { 0 })
                })
                .collect();
            let out = thin(&pts, 0.5);
            assert_eq!(out.first(), pts.first());
            assert_eq!(out.last(), pts.last());
            for &p in &pts {
                let d = out
                    .windows(2)
                    .map(|w| dist(p, w[0], w[1]))
                    .fold(f64::INFINITY, f64::min);
                assert!(d <= 0.5 + 1e-9, "{p:?} is {d} px off");
            }
            for w in pts.windows(3) {
                if (w[1].1 - w[0].1) * (w[2].1 - w[1].1) < 0 {
                    assert!(out.contains(&w[1]), "turn {:?} dropped", w[1]);
                }
            }
            if !noisy {
                assert!(out.len() * 3 < pts.len(), "{} of {}", out.len(), pts.len());
            }
        }
    }

    #[test]
    fn dashes_follow_the_line() {
        // a straight 100-pixel line: dashes of 9 every 14 pixels, none longer than 9
        let d = dashes(&[(0, 0), (50, 0), (100, 0)], 9.0, 5.0);
        assert_eq!(d.len(), 8);
        for piece in &d {
            let len = piece.last().unwrap().0 - piece[0].0;
            assert!(len <= 9, "{piece:?}");
        }
        assert_eq!(d[1][0], (14, 0));
    }
}
