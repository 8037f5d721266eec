//! Envelopes over height: panels side by side, each a quantity on the horizontal axis against
//! the height on the vertical axis (floors up the page), the figure pounding papers show for
//! peak floor displacement, drift, acceleration and storey shear.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::lines::LineStyle;
use super::style::{self, AXIS, Fonts, GRID, PALETTE, fmt_num};
use super::{PlotError, Render, draw_err, draw_titles, write_both};

/// One line of an envelope: a value at each height, drawn with a marker at every point.
#[derive(Debug, Clone)]
pub struct ProfileSeries<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Values (the horizontal axis).
    pub values: &'a [f64],
    /// Heights, m (the vertical axis), as many as `values`.
    pub heights: &'a [f64],
    /// Solid or dashed.
    pub style: LineStyle,
    /// Palette index (the same index, the same colour in every panel).
    pub color: usize,
    /// Points drawn as open rings instead of dots, one flag per value (e.g. a peak that is an
    /// impact's pulse); empty: every point a dot.
    pub rings: &'a [bool],
}

/// One panel: a quantity over height.
#[derive(Debug, Clone)]
pub struct ProfilePanel<'a> {
    /// Title above the panel.
    pub title: &'a str,
    /// Label of the horizontal axis (quantity and unit).
    pub x_label: &'a str,
    /// The value every line starts from at height 0 (`Some(0.0)` for a displacement relative
    /// to the base); `None`: the lines start at the lowest floor.
    pub base: Option<f64>,
    /// The lines.
    pub series: Vec<ProfileSeries<'a>>,
}

/// A figure of envelope panels side by side, one legend under the title.
#[derive(Debug, Clone)]
pub struct ProfileFigure<'a> {
    /// Figure title.
    pub title: &'a str,
    /// Subtitle (may be empty).
    pub subtitle: &'a str,
    /// Label of the shared vertical axis.
    pub y_label: &'a str,
    /// The panels, left to right.
    pub panels: Vec<ProfilePanel<'a>>,
    /// Size in pixels.
    pub width: u32,
    /// See `width`.
    pub height: u32,
}

/// Writes `<stem>.png` and `<stem>.svg`; panels without finite data are drawn as empty axes.
pub fn write_profile(fig: &ProfileFigure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    if fig.panels.is_empty() {
        return Err(PlotError::NoData("the figure has no panels".into()));
    }
    write_both(fig, stem, fig.width, fig.height)
}

impl Render for ProfileFigure<'_> {
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _bitmap: bool,
    ) -> Result<(), PlotError> {
        let f = Fonts::for_size(self.width, self.height);
        let mut top = draw_titles(root, self.title, self.subtitle, f)?;
        // one legend for the whole figure (the first panel's series), centred under the title
        if let Some(p) = self.panels.first() {
            let sample = 30;
            // (a series without a label is not in the legend)
            let items: Vec<(i32, &ProfileSeries)> = p
                .series
                .iter()
                .filter(|s| !s.label.is_empty())
                .map(|s| (sample + 8 + style::text_width(s.label, f.tick) + 24, s))
                .collect();
            let total: i32 = items.iter().map(|(w, _)| w).sum();
            let mut x = (self.width as i32 - total) / 2;
            let y = top + (f.tick * 0.9) as i32;
            for (w, s) in &items {
                let color = PALETTE[s.color % PALETTE.len()];
                let stroke = ShapeStyle::from(&color).stroke_width(2);
                let pts: Vec<(i32, i32)> = match s.style {
                    LineStyle::Solid => vec![(x, y), (x + sample, y)],
                    LineStyle::Dashed => vec![(x, y), (x + sample / 3, y)],
                };
                root.draw(&PathElement::new(pts, stroke))
                    .map_err(draw_err)?;
                if s.style == LineStyle::Dashed {
                    root.draw(&PathElement::new(
                        [(x + 2 * sample / 3, y), (x + sample, y)],
                        stroke,
                    ))
                    .map_err(draw_err)?;
                }
                root.draw(&Text::new(
                    s.label.to_string(),
                    (x + sample + 8, y - (f.tick * 0.55) as i32),
                    style::font(f.tick).color(&BLACK),
                ))
                .map_err(draw_err)?;
                x += w;
            }
            top += (f.tick * 2.0) as i32;
        }
        let (w, h) = root.dim_in_pixel();
        let area = root.margin(top as u32, 0, 0, 0);
        let panels = area.split_evenly((1, self.panels.len()));
        let y_max = self
            .panels
            .iter()
            .flat_map(|p| p.series.iter().flat_map(|s| s.heights.iter().copied()))
            .filter(|v| v.is_finite())
            .fold(0.0f64, f64::max);
        let y_hi = if y_max > 0.0 { y_max * 1.05 } else { 1.0 };
        for (panel, p) in panels.iter().zip(&self.panels) {
            let x_hi = p
                .series
                .iter()
                .flat_map(|s| s.values.iter().copied())
                .filter(|v| v.is_finite())
                .fold(0.0f64, f64::max);
            let x_hi = if x_hi > 0.0 { x_hi * 1.08 } else { 1.0 };
            let mut chart = ChartBuilder::on(panel)
                .caption(p.title, style::font(f.text).color(&BLACK))
                .margin(8)
                .x_label_area_size((f.tick * 1.4 + f.text * 1.8) as u32 + 6)
                .y_label_area_size((f.tick * 3.0 + f.text * 1.2) as u32 + 8)
                .build_cartesian_2d(0.0..x_hi, 0.0..y_hi)
                .map_err(draw_err)?;
            chart
                .configure_mesh()
                .x_desc(p.x_label)
                .y_desc(self.y_label)
                .axis_desc_style(style::font(f.text).color(&BLACK))
                .label_style(style::font(f.tick).color(&AXIS))
                .axis_style(AXIS)
                .light_line_style(WHITE)
                .bold_line_style(GRID)
                .x_labels(5)
                .y_labels(8)
                .x_label_formatter(&|v| fmt_num(*v))
                .y_label_formatter(&|v| fmt_num(*v))
                .draw()
                .map_err(draw_err)?;
            for s in &p.series {
                let color = PALETTE[s.color % PALETTE.len()];
                let pts: Vec<(f64, f64)> = s
                    .values
                    .iter()
                    .zip(s.heights)
                    .filter(|(v, h)| v.is_finite() && h.is_finite())
                    .map(|(v, h)| (*v, *h))
                    .collect();
                // from the base (when it has a value) up the floors
                let mut line: Vec<(f64, f64)> = p.base.map(|b| (b, 0.0)).into_iter().collect();
                line.extend(pts.iter().copied());
                let stroke = ShapeStyle::from(&color).stroke_width(2);
                let pieces: Vec<Vec<(f64, f64)>> = match s.style {
                    LineStyle::Solid => vec![line],
                    // dashes cut in data space: each segment in 11 pieces, every other drawn
                    LineStyle::Dashed => line
                        .windows(2)
                        .flat_map(|w| {
                            let (a, b) = (w[0], w[1]);
                            (0..11).step_by(2).map(move |i| {
                                let at = |t: f64| (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
                                vec![at(i as f64 / 11.0), at((i + 1) as f64 / 11.0)]
                            })
                        })
                        .collect(),
                };
                chart
                    .draw_series(pieces.into_iter().map(|p| PathElement::new(p, stroke)))
                    .map_err(draw_err)?;
                let ring = |k: usize| s.rings.get(k).copied().unwrap_or(false);
                let marks = s
                    .values
                    .iter()
                    .zip(s.heights)
                    .enumerate()
                    .filter(|(_, (v, h))| v.is_finite() && h.is_finite())
                    .map(|(k, (&v, &h))| {
                        if ring(k) {
                            Circle::new((v, h), 6, ShapeStyle::from(&color).stroke_width(2))
                        } else {
                            Circle::new((v, h), 3, ShapeStyle::from(&color).filled())
                        }
                    });
                chart.draw_series(marks).map_err(draw_err)?;
            }
        }
        let _ = (w, h);
        Ok(())
    }
}
