//! One panel of lines over an x axis that may be logarithmic, with shaded x bands: response
//! spectra (PSA against a log period axis, a code's period range shaded).

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::coord::ranged1d::Ranged;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::lines::{AxisScale, LineStyle};
use super::style::{self, AXIS, Fonts, GRID, PALETTE, Ticked, fmt_num, font, text_width};
use super::{PlotError, Render, draw_err, draw_titles, write_both};

/// Colour of a line: one of the palette's (by index) or grey (for the many lines of a suite).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineColor {
    /// The palette colour of this index (Okabe–Ito, colour-blind safe).
    Palette(usize),
    /// Light grey.
    Grey,
    /// Black.
    Black,
}

/// One line.
#[derive(Debug, Clone)]
pub struct XyLine<'a> {
    /// Legend text; empty: not in the legend.
    pub label: &'a str,
    /// Abscissae.
    pub x: &'a [f64],
    /// Ordinates (a point that is not finite, or ≤ 0 on a log axis, breaks the line).
    pub y: &'a [f64],
    /// Solid or dashed.
    pub style: LineStyle,
    /// Colour.
    pub color: LineColor,
    /// Width in pixels.
    pub width: u32,
}

/// A shaded band over an x interval.
#[derive(Debug, Clone)]
pub struct Band<'a> {
    /// Legend text.
    pub label: &'a str,
    /// From, in x units.
    pub from: f64,
    /// To, in x units.
    pub to: f64,
}

/// A one-panel figure.
#[derive(Debug, Clone)]
pub struct XyFigure<'a> {
    /// Title.
    pub title: &'a str,
    /// Subtitle (may be empty).
    pub subtitle: &'a str,
    /// X-axis label with unit.
    pub x_label: &'a str,
    /// Y-axis label with unit.
    pub y_label: &'a str,
    /// X-axis scale.
    pub x_scale: AxisScale,
    /// Y-axis scale.
    pub y_scale: AxisScale,
    /// Bands drawn under the lines.
    pub bands: Vec<Band<'a>>,
    /// Lines, drawn in order (the last on top).
    pub lines: Vec<XyLine<'a>>,
    /// Picture size in pixels.
    pub width: u32,
    /// See `width`.
    pub height: u32,
}

/// Writes `<stem>.png` and `<stem>.svg`; returns the paths.
pub fn write_xy(fig: &XyFigure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    if fig.lines.is_empty() {
        return Err(PlotError::NoData("the figure has no lines".into()));
    }
    write_both(fig, stem, fig.width, fig.height)
}

fn to_plot(v: f64, scale: AxisScale) -> Option<f64> {
    match scale {
        AxisScale::Linear if v.is_finite() => Some(v.clamp(-1e300, 1e300)),
        AxisScale::Log if v.is_finite() && v > 0.0 => Some(v.log10()),
        _ => None,
    }
}

/// Axis in plot coordinates (log10 on a log axis) with its ticks.
fn axis(r: Option<(f64, f64)>, pad: f64, scale: AxisScale, n: usize) -> Ticked {
    let (lo, hi) = style::pad(r, pad);
    let ticks = match scale {
        AxisScale::Linear => RangedCoordf64::from(lo..hi)
            .key_points(n.max(2))
            .into_iter()
            .map(|t: f64| if t.abs() < 1e-9 * (hi - lo) { 0.0 } else { t })
            .collect(),
        AxisScale::Log => style::log_ticks(10f64.powf(lo), 10f64.powf(hi), n.max(2))
            .into_iter()
            .map(f64::log10)
            .collect(),
    };
    Ticked { lo, hi, ticks }
}

fn label(v: f64, scale: AxisScale) -> String {
    match scale {
        AxisScale::Linear => fmt_num(v),
        AxisScale::Log => fmt_num(10f64.powf(v)),
    }
}

fn rgb(c: LineColor) -> RGBColor {
    match c {
        LineColor::Palette(k) => PALETTE[k % PALETTE.len()],
        LineColor::Grey => RGBColor(175, 175, 175),
        LineColor::Black => RGBColor(0, 0, 0),
    }
}

const BAND: RGBColor = RGBColor(255, 236, 179);

/// A legend entry: its text and its line (none for a band).
type Entry<'a> = (&'a str, Option<&'a XyLine<'a>>);

impl Render for XyFigure<'_> {
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _bitmap: bool,
    ) -> Result<(), PlotError> {
        let f = Fonts::for_size(self.width, self.height);
        let top = draw_titles(root, self.title, self.subtitle, f)?;
        let (w, h) = (self.width as i32, self.height as i32);
        // legend rows under the title: as many entries per row as fit
        let sample = 34;
        let entries: Vec<Entry> = (self.bands.iter().map(|b| (b.label, None)))
            .chain(
                self.lines
                    .iter()
                    .filter(|l| !l.label.is_empty())
                    .map(|l| (l.label, Some(l))),
            )
            .collect();
        let line_h = (f.tick * 1.7) as i32;
        let mut rows: Vec<Vec<(i32, &Entry)>> = vec![Vec::new()];
        let mut x = 0;
        for e in &entries {
            let ew = sample + 8 + text_width(e.0, f.tick) + 22;
            if x + ew > w - 40 && x > 0 {
                rows.push(Vec::new());
                x = 0;
            }
            if let Some(row) = rows.last_mut() {
                row.push((x, e));
            }
            x += ew;
        }
        let legend_h = if entries.is_empty() {
            0
        } else {
            rows.len() as i32 * line_h + 6
        };
        for (r, row) in rows.iter().enumerate() {
            let width: i32 = row
                .last()
                .map_or(0, |(x, e)| x + sample + 8 + text_width(e.0, f.tick));
            let x0 = (w - width) / 2;
            let cy = top + r as i32 * line_h + line_h / 2;
            for (x, (text, line)) in row {
                let lx = x0 + x;
                match line {
                    Some(l) => {
                        let pts = [(lx, cy), (lx + sample, cy)];
                        draw_polyline(root, &pts, rgb(l.color), l.style, l.width.max(2))?;
                    }
                    None => {
                        root.draw(&Rectangle::new(
                            [(lx, cy - 7), (lx + sample, cy + 7)],
                            BAND.filled(),
                        ))
                        .map_err(draw_err)?;
                    }
                }
                root.draw_text(
                    text,
                    &font(f.tick)
                        .color(&BLACK)
                        .pos(Pos::new(HPos::Left, VPos::Center)),
                    (lx + sample + 8, cy),
                )
                .map_err(draw_err)?;
            }
        }

        let body = root.clone().shrink(
            (0, top + legend_h),
            (w as u32, (h - top - legend_h).max(10) as u32),
        );
        let xs = self
            .lines
            .iter()
            .flat_map(|l| l.x.iter().filter_map(|v| to_plot(*v, self.x_scale)));
        let bx = self.bands.iter().flat_map(|b| {
            [to_plot(b.from, self.x_scale), to_plot(b.to, self.x_scale)]
                .into_iter()
                .flatten()
        });
        let x_axis = axis(style::finite_range(xs.chain(bx)), 0.0, self.x_scale, 12);
        let ys = self.lines.iter().flat_map(|l| {
            l.x.iter()
                .zip(l.y)
                .filter(|(x, _)| to_plot(**x, self.x_scale).is_some())
                .filter_map(|(_, y)| to_plot(*y, self.y_scale))
        });
        let y_pad = if self.y_scale == AxisScale::Log {
            0.04
        } else {
            0.05
        };
        let y_range = style::finite_range(ys).map(|(lo, hi)| match self.y_scale {
            AxisScale::Linear => (lo.min(0.0), hi),
            AxisScale::Log => (lo, hi),
        });
        let ybody_h = body.dim_in_pixel().1 as f64;
        let mut y_axis = axis(
            y_range,
            y_pad,
            self.y_scale,
            (ybody_h / (f.tick * 2.6)) as usize,
        );
        // a quantity that is never negative starts at 0 exactly
        if self.y_scale == AxisScale::Linear && y_range.is_some_and(|(lo, _)| lo >= 0.0) {
            y_axis.lo = 0.0;
            y_axis.ticks.retain(|t| *t >= 0.0);
        }
        let x_area = (f.tick * 1.4 + f.text * 1.6) as u32 + 10;
        let y_area = (f.tick * 3.9 + f.text * 0.9) as u32 + 14;
        let desc_room = (f.text * 0.7) as u32;
        let mut chart = ChartBuilder::on(&body)
            .margin_left(desc_room)
            .margin_right((f.tick * 1.5) as u32)
            .margin_top(4)
            .set_label_area_size(LabelAreaPosition::Left, y_area)
            .set_label_area_size(LabelAreaPosition::Bottom, x_area)
            .build_cartesian_2d(x_axis.clone(), y_axis.clone())
            .map_err(draw_err)?;
        // bands first, under the grid
        for b in &self.bands {
            if let (Some(a), Some(c)) = (to_plot(b.from, self.x_scale), to_plot(b.to, self.x_scale))
            {
                let (a, c) = (a.clamp(x_axis.lo, x_axis.hi), c.clamp(x_axis.lo, x_axis.hi));
                chart
                    .draw_series([Rectangle::new(
                        [(a, y_axis.lo), (c, y_axis.hi)],
                        BAND.filled(),
                    )])
                    .map_err(draw_err)?;
            }
        }
        let (xs_, ys_) = (self.x_scale, self.y_scale);
        let (x_fmt, y_fmt) = (|v: &f64| label(*v, xs_), |v: &f64| label(*v, ys_));
        chart
            .configure_mesh()
            .bold_line_style(GRID)
            .light_line_style(TRANSPARENT)
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
        for l in &self.lines {
            let mut run: Vec<(i32, i32)> = Vec::new();
            let pts = l.x.iter().zip(l.y).map(|(&px, &py)| {
                match (to_plot(px, self.x_scale), to_plot(py, self.y_scale)) {
                    (Some(a), Some(b)) => Some(chart.backend_coord(&(
                        a.clamp(x_axis.lo, x_axis.hi),
                        b.clamp(y_axis.lo, y_axis.hi),
                    ))),
                    _ => None,
                }
            });
            for q in pts.chain([None]) {
                match q {
                    Some(c) => run.push(c),
                    None if !run.is_empty() => {
                        draw_polyline(root, &run, rgb(l.color), l.style, l.width)?;
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
        Ok(())
    }
}

/// Draws a polyline (absolute pixels on `root`), one path per segment (no miter spikes),
/// dashed by cutting it into pieces.
fn draw_polyline<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    pts: &[(i32, i32)],
    color: RGBColor,
    style: LineStyle,
    width: u32,
) -> Result<(), PlotError> {
    let stroke = ShapeStyle::from(&color).stroke_width(width.max(1));
    let pieces = match style {
        LineStyle::Solid => vec![pts.to_vec()],
        LineStyle::Dashed => dashes(pts, 10.0, 6.0),
    };
    for piece in pieces {
        for s in piece.windows(2).filter(|s| s[0] != s[1]) {
            root.draw(&PathElement::new([s[0], s[1]], stroke))
                .map_err(draw_err)?;
        }
    }
    Ok(())
}

/// Cuts a pixel polyline into dashes `on` long, `off` apart.
fn dashes(pts: &[(i32, i32)], on: f64, off: f64) -> Vec<Vec<(i32, i32)>> {
    let p = |q: (f64, f64)| (q.0.round() as i32, q.1.round() as i32);
    let mut out = Vec::new();
    let Some(first) = pts.first() else {
        return out;
    };
    let mut cur = vec![*first];
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

    #[test]
    fn log_axes_bands_and_nasty_data() {
        let dir = temp_dir("xy");
        let t: Vec<f64> = (0..100).map(|i| 0.01 * 1.07f64.powi(i)).collect();
        let a: Vec<f64> = t.iter().map(|t| 1.0 / (1.0 + t)).collect();
        let b = [f64::NAN, 0.0, -1.0, 2.0, f64::INFINITY, 3.0];
        let fig = XyFigure {
            title: "Spectra <&>",
            subtitle: "5 % damping",
            x_label: "T [s]",
            y_label: "PSA [g]",
            x_scale: AxisScale::Log,
            y_scale: AxisScale::Linear,
            bands: vec![Band {
                label: "range",
                from: 0.1,
                to: 2.0,
            }],
            lines: vec![
                XyLine {
                    label: "a",
                    x: &t,
                    y: &a,
                    style: LineStyle::Solid,
                    color: LineColor::Grey,
                    width: 1,
                },
                XyLine {
                    label: "b",
                    x: &t[..6],
                    y: &b,
                    style: LineStyle::Dashed,
                    color: LineColor::Palette(1),
                    width: 3,
                },
            ],
            width: 900,
            height: 600,
        };
        let p = write_xy(&fig, &dir.join("s")).unwrap();
        check_outputs(&dir, &p, 900, 600, "Spectra &lt;&amp;&gt;");
        let log_y = XyFigure {
            y_scale: AxisScale::Log,
            ..fig.clone()
        };
        write_xy(&log_y, &dir.join("l")).unwrap();
        let empty = XyFigure {
            lines: vec![],
            ..fig.clone()
        };
        assert!(matches!(
            write_xy(&empty, &dir.join("e")),
            Err(PlotError::NoData(_))
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
