//! A grid of panels, each with curves over a shaded band between a lower and an upper curve,
//! and observed points as markers: fitted probability curves with their confidence band and
//! the observed fractions (fragility curves).

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::lines::LineStyle;
use super::style::{AXIS, Fonts, GRID, PALETTE, fmt_num, font};
use super::{PlotError, Render, draw_err, draw_titles, write_both};

/// One curve, with an optional band around it (same abscissae).
#[derive(Debug, Clone)]
pub struct BandCurve<'a> {
    /// Legend text (the legend is that of the panel with the most labels; empty: none).
    pub label: &'a str,
    /// Abscissae.
    pub x: &'a [f64],
    /// Ordinates (non-finite points break the line).
    pub y: &'a [f64],
    /// Lower and upper ends of the band at each x (empty: no band).
    pub band: (&'a [f64], &'a [f64]),
    /// Palette index.
    pub color: usize,
    /// Solid or dashed.
    pub style: LineStyle,
}

/// Observed points.
#[derive(Debug, Clone)]
pub struct Markers<'a> {
    /// Abscissae.
    pub x: &'a [f64],
    /// Ordinates.
    pub y: &'a [f64],
    /// Palette index.
    pub color: usize,
    /// Filled circles (else open).
    pub filled: bool,
}

/// One panel.
#[derive(Debug, Clone)]
pub struct CurvePanel<'a> {
    /// Title above the panel.
    pub title: String,
    /// The curves.
    pub curves: Vec<BandCurve<'a>>,
    /// The markers.
    pub markers: Vec<Markers<'a>>,
}

/// A grid of panels sharing axis labels and the y range.
#[derive(Debug, Clone)]
pub struct CurveFigure<'a> {
    /// Title.
    pub title: &'a str,
    /// Subtitle (may be empty).
    pub subtitle: &'a str,
    /// X-axis label with unit.
    pub x_label: &'a str,
    /// Y-axis label with unit.
    pub y_label: &'a str,
    /// The y range of every panel.
    pub y_range: (f64, f64),
    /// Panels, row by row.
    pub panels: Vec<CurvePanel<'a>>,
    /// Panels per row.
    pub columns: usize,
    /// Picture size in pixels.
    pub width: u32,
    /// See `width`.
    pub height: u32,
}

/// Writes `<stem>.png` and `<stem>.svg`; returns the paths.
pub fn write_curves(fig: &CurveFigure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    if fig.panels.is_empty() {
        return Err(PlotError::NoData("the figure has no panels".into()));
    }
    if !(fig.y_range.0.is_finite() && fig.y_range.1.is_finite() && fig.y_range.0 < fig.y_range.1) {
        return Err(PlotError::InvalidInput("the y range is empty".into()));
    }
    write_both(fig, stem, fig.width, fig.height)
}

fn x_range(p: &CurvePanel) -> (f64, f64) {
    let xs = p
        .curves
        .iter()
        .flat_map(|c| c.x.iter())
        .chain(p.markers.iter().flat_map(|m| m.x.iter()))
        .copied()
        .filter(|v| v.is_finite());
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if lo.is_finite() && hi > lo {
        (lo.min(0.0), hi)
    } else {
        (0.0, 1.0)
    }
}

impl Render for CurveFigure<'_> {
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _bitmap: bool,
    ) -> Result<(), PlotError> {
        let f = Fonts::for_size(self.width, self.height);
        let top = draw_titles(root, self.title, self.subtitle, f)?;
        let (w, h) = (self.width as i32, self.height as i32);
        // the legend: one row under the title, from the panel with the most labelled curves
        let most = self
            .panels
            .iter()
            .max_by_key(|p| p.curves.iter().filter(|c| !c.label.is_empty()).count())
            .unwrap_or(&self.panels[0]);
        let legend: Vec<&BandCurve> = most.curves.iter().filter(|c| !c.label.is_empty()).collect();
        let line_h = (f.tick * 1.8) as i32;
        if !legend.is_empty() {
            let mut x = 20;
            let cy = top + line_h / 2;
            for c in &legend {
                let col = PALETTE[c.color % PALETTE.len()];
                root.draw(&Rectangle::new(
                    [(x, cy - 7), (x + 30, cy + 7)],
                    col.mix(0.18).filled(),
                ))
                .map_err(draw_err)?;
                root.draw(&PathElement::new(
                    vec![(x, cy), (x + 30, cy)],
                    col.stroke_width(3),
                ))
                .map_err(draw_err)?;
                root.draw(&Circle::new((x + 15, cy), 5, col.filled()))
                    .map_err(draw_err)?;
                root.draw_text(
                    c.label,
                    &font(f.tick)
                        .color(&BLACK)
                        .pos(Pos::new(HPos::Left, VPos::Center)),
                    (x + 38, cy),
                )
                .map_err(draw_err)?;
                x += 38 + super::style::text_width(c.label, f.tick) + 30;
            }
        }
        let legend_h = if legend.is_empty() { 0 } else { line_h + 4 };
        let body = root.clone().shrink(
            (0, top + legend_h),
            (w as u32, (h - top - legend_h).max(10) as u32),
        );
        let cols = self.columns.max(1);
        let rows = self.panels.len().div_ceil(cols);
        let cells = body.split_evenly((rows, cols));
        for (p, cell) in self.panels.iter().zip(cells.iter()) {
            let (xlo, xhi) = x_range(p);
            let (ylo, yhi) = self.y_range;
            let mut chart = ChartBuilder::on(cell)
                .margin(8)
                .caption(&p.title, font(f.text).color(&BLACK))
                .set_label_area_size(LabelAreaPosition::Left, (f.tick * 3.6) as u32)
                .set_label_area_size(LabelAreaPosition::Bottom, (f.tick * 2.8) as u32)
                .build_cartesian_2d(xlo..xhi * 1.02, ylo..yhi)
                .map_err(draw_err)?;
            let fmt = |v: &f64| fmt_num(*v);
            chart
                .configure_mesh()
                .bold_line_style(GRID)
                .light_line_style(TRANSPARENT)
                .axis_style(AXIS)
                .label_style(font(f.tick).color(&AXIS))
                .axis_desc_style(font(f.tick).color(&BLACK))
                .x_label_formatter(&fmt)
                .y_label_formatter(&fmt)
                .x_labels(6)
                .y_labels(6)
                .x_desc(self.x_label)
                .y_desc(self.y_label)
                .draw()
                .map_err(draw_err)?;
            for c in &p.curves {
                let col = PALETTE[c.color % PALETTE.len()];
                let (lo, hi) = c.band;
                if !lo.is_empty() && lo.len() == c.x.len() && hi.len() == c.x.len() {
                    let mut poly: Vec<(f64, f64)> =
                        c.x.iter()
                            .zip(hi)
                            .filter(|(x, y)| x.is_finite() && y.is_finite())
                            .map(|(x, y)| (*x, y.clamp(ylo, yhi)))
                            .collect();
                    poly.extend(
                        c.x.iter()
                            .zip(lo)
                            .rev()
                            .filter(|(x, y)| x.is_finite() && y.is_finite())
                            .map(|(x, y)| (*x, y.clamp(ylo, yhi))),
                    );
                    if poly.len() >= 3 {
                        chart
                            .draw_series([Polygon::new(poly, col.mix(0.18).filled())])
                            .map_err(draw_err)?;
                    }
                }
                let pts: Vec<(f64, f64)> =
                    c.x.iter()
                        .zip(c.y)
                        .filter(|(x, y)| x.is_finite() && y.is_finite())
                        .map(|(x, y)| (*x, y.clamp(ylo, yhi)))
                        .collect();
                let stroke = col.stroke_width(3);
                match c.style {
                    LineStyle::Solid => {
                        chart
                            .draw_series([PathElement::new(pts, stroke)])
                            .map_err(draw_err)?;
                    }
                    LineStyle::Dashed => {
                        // dashes of three segments on, two off (the curves are dense)
                        let dashes: Vec<Vec<(f64, f64)>> = pts
                            .windows(2)
                            .enumerate()
                            .filter(|(k, _)| k % 5 < 3)
                            .map(|(_, w)| w.to_vec())
                            .collect();
                        chart
                            .draw_series(dashes.into_iter().map(|d| PathElement::new(d, stroke)))
                            .map_err(draw_err)?;
                    }
                }
            }
            for m in &p.markers {
                let col = PALETTE[m.color % PALETTE.len()];
                let style = if m.filled {
                    col.filled()
                } else {
                    col.stroke_width(2)
                };
                chart
                    .draw_series(
                        m.x.iter()
                            .zip(m.y)
                            .filter(|(x, y)| x.is_finite() && y.is_finite())
                            .map(|(x, y)| Circle::new((*x, *y), 6, style)),
                    )
                    .map_err(draw_err)?;
            }
        }
        Ok(())
    }
}
