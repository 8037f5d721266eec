//! The SVG every picture is written as: plotters' SVG markup (the same elements, attributes
//! and order, so the same document), written straight into one string.
//!
//! plotters' own SVG backend builds each attribute value as a `String` of its own through
//! `format!` (every coordinate of a polyline through the formatting machinery): ~5 000
//! instructions per element and ~700 per point, a fifth of a run's pictures. Here the
//! integers are written with `itoa` and the colours as hex digits into the document itself;
//! what is written is unchanged (checked against plotters' backend in the tests).

use std::fmt::Write as _;

use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontStyle,
    FontTransform,
};

type DrawResult = Result<(), DrawingErrorKind<std::io::Error>>;

/// An SVG document of `w × h` pixels being written into a string; [`DrawingBackend::present`]
/// closes it.
pub(super) struct Svg<'a> {
    out: &'a mut String,
    size: (u32, u32),
    closed: bool,
}

impl<'a> Svg<'a> {
    /// Starts the document in `out`.
    pub fn new(out: &'a mut String, (w, h): (u32, u32)) -> Svg<'a> {
        let mut s = Svg {
            out,
            size: (w, h),
            closed: false,
        };
        s.out.push_str("<svg width=\"");
        s.int(w);
        s.out.push_str("\" height=\"");
        s.int(h);
        s.out.push_str("\" viewBox=\"0 0 ");
        s.int(w);
        s.out.push(' ');
        s.int(h);
        s.out.push_str("\" xmlns=\"http://www.w3.org/2000/svg\">\n");
        s
    }

    fn int(&mut self, v: impl itoa::Integer) {
        self.out.push_str(itoa::Buffer::new().format(v));
    }

    /// ` key="` … the value … `"`: `attr` opens, the caller writes the value, `end` closes.
    fn attr(&mut self, key: &str) {
        self.out.push(' ');
        self.out.push_str(key);
        self.out.push_str("=\"");
    }

    fn end(&mut self) {
        self.out.push('"');
    }

    fn int_attr(&mut self, key: &str, v: impl itoa::Integer) {
        self.attr(key);
        self.int(v);
        self.end();
    }

    fn str_attr(&mut self, key: &str, v: &str) {
        self.attr(key);
        escape(self.out, v);
        self.end();
    }

    /// `#RRGGBB`, upper-case hex.
    fn color_attr(&mut self, key: &str, c: BackendColor) {
        const HEX: &[u8; 16] = b"0123456789ABCDEF";
        self.attr(key);
        self.out.push('#');
        for v in [c.rgb.0, c.rgb.1, c.rgb.2] {
            self.out.push(HEX[usize::from(v >> 4)] as char);
            self.out.push(HEX[usize::from(v & 15)] as char);
        }
        self.end();
    }

    /// The opacity as Rust displays an `f64` (`1`, `0.18`).
    /// A shape's paint: filled in `color` without an outline, or outlined in it and empty.
    fn paint_attrs(&mut self, color: BackendColor, fill: bool) {
        if fill {
            self.color_attr("fill", color);
            self.str_attr("stroke", "none");
        } else {
            self.str_attr("fill", "none");
            self.color_attr("stroke", color);
        }
    }

    fn opacity_attr(&mut self, c: BackendColor) {
        self.attr("opacity");
        if c.alpha == 1.0 {
            self.out.push('1');
        } else {
            let _ = write!(self.out, "{}", c.alpha);
        }
        self.end();
    }

    /// `x,y x,y … ` (each point followed by a space).
    fn points_attr(&mut self, path: impl IntoIterator<Item = BackendCoord>) {
        self.attr("points");
        for (x, y) in path {
            self.int(x);
            self.out.push(',');
            self.int(y);
            self.out.push(' ');
        }
        self.end();
    }

    fn open(&mut self, tag: &str) {
        self.out.push('<');
        self.out.push_str(tag);
    }

    fn close(&mut self) {
        self.out.push_str("/>\n");
    }
}

/// `value` with XML's five special characters escaped.
fn escape(out: &mut String, value: &str) {
    for c in value.chars() {
        match c {
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '&' => out.push_str("&amp;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            other => out.push(other),
        }
    }
}

impl DrawingBackend for Svg<'_> {
    type ErrorType = std::io::Error;

    fn get_size(&self) -> (u32, u32) {
        self.size
    }

    fn ensure_prepared(&mut self) -> DrawResult {
        Ok(())
    }

    fn present(&mut self) -> DrawResult {
        if !self.closed {
            self.out.push_str("</svg>\n");
            self.closed = true;
        }
        Ok(())
    }

    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> DrawResult {
        if color.alpha == 0.0 {
            return Ok(());
        }
        self.open("rect");
        self.int_attr("x", point.0);
        self.int_attr("y", point.1);
        self.str_attr("width", "1");
        self.str_attr("height", "1");
        self.str_attr("stroke", "none");
        self.opacity_attr(color);
        self.color_attr("fill", color);
        self.close();
        Ok(())
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> DrawResult {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        self.open("line");
        self.opacity_attr(color);
        self.color_attr("stroke", color);
        self.int_attr("stroke-width", style.stroke_width());
        self.int_attr("x1", from.0);
        self.int_attr("y1", from.1);
        self.int_attr("x2", to.0);
        self.int_attr("y2", to.1);
        self.close();
        Ok(())
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> DrawResult {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        self.open("rect");
        self.int_attr("x", upper_left.0);
        self.int_attr("y", upper_left.1);
        self.int_attr("width", bottom_right.0 - upper_left.0);
        self.int_attr("height", bottom_right.1 - upper_left.1);
        self.opacity_attr(color);
        self.paint_attrs(color, fill);
        self.close();
        Ok(())
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> DrawResult {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        self.open("polyline");
        self.str_attr("fill", "none");
        self.opacity_attr(color);
        self.color_attr("stroke", color);
        self.int_attr("stroke-width", style.stroke_width());
        self.points_attr(path);
        self.close();
        Ok(())
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> DrawResult {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        self.open("polygon");
        self.opacity_attr(color);
        self.color_attr("fill", color);
        self.points_attr(vert);
        self.close();
        Ok(())
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> DrawResult {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        self.open("circle");
        self.int_attr("cx", center.0);
        self.int_attr("cy", center.1);
        self.int_attr("r", radius);
        self.opacity_attr(color);
        self.paint_attrs(color, fill);
        self.int_attr("stroke-width", style.stroke_width());
        self.close();
        Ok(())
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> DrawResult {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let anchor = match style.anchor().h_pos {
            HPos::Left => "start",
            HPos::Right => "end",
            HPos::Center => "middle",
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => "0.76em",
            VPos::Center => "0.5ex",
            VPos::Bottom => "-0.5ex",
        };
        self.open("text");
        self.int_attr("x", pos.0);
        self.int_attr("y", pos.1);
        self.str_attr("dy", dy);
        self.str_attr("text-anchor", anchor);
        self.str_attr("font-family", style.family().as_str());
        // (the font size in the units plotters gives SVG text: its pixel size / 1.24)
        self.attr("font-size");
        let _ = write!(self.out, "{}", style.size() / 1.24);
        self.end();
        self.opacity_attr(color);
        self.color_attr("fill", color);
        match style.style() {
            FontStyle::Normal => {}
            FontStyle::Bold => self.str_attr("font-weight", "bold"),
            other => self.str_attr("font-style", other.as_str()),
        }
        let angle = match style.transform() {
            FontTransform::None => None,
            FontTransform::Rotate90 => Some(90),
            FontTransform::Rotate180 => Some(180),
            FontTransform::Rotate270 => Some(270),
        };
        if let Some(angle) = angle {
            self.attr("transform");
            let _ = write!(self.out, "rotate({angle}, {}, {})", pos.0, pos.1);
            self.end();
        }
        self.out.push_str(">\n");
        escape(self.out, text);
        self.out.push_str("\n</text>\n");
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::curves::{BandCurve, CurveFigure, CurvePanel, Markers};
    use super::super::{
        AxisScale, Band, ColorScale, Figure, Heatmap, LineColor, LineStyle, Panel, ProfileFigure,
        ProfilePanel, ProfileSeries, Render, Series, XyFigure, XyLine,
    };
    use super::*;

    /// The figure as this backend writes it, and as plotters' SVG backend does.
    fn both(r: &impl Render, w: u32, h: u32) -> (String, String) {
        super::super::style::ensure_font().unwrap();
        let mut ours = String::new();
        let root = Svg::new(&mut ours, (w, h)).into_drawing_area();
        r.render(&root, false).unwrap();
        root.present().unwrap();
        drop(root);
        let mut theirs = String::new();
        let root = SVGBackend::with_string(&mut theirs, (w, h)).into_drawing_area();
        r.render(&root, false).unwrap();
        root.present().unwrap();
        drop(root);
        (ours, theirs)
    }

    /// Every kind of figure (stacked lines with legends, dashes, a log axis and broken lines;
    /// envelopes with rings; fragility curves with bands and markers; a heatmap with its colour
    /// bar and no-data cells; spectra with shaded bands) is written as the same document,
    /// byte for byte, as plotters' SVG backend writes it — titles with XML's special
    /// characters, rotated axis labels and translucent fills included.
    #[test]
    fn every_figure_is_the_document_plotters_writes() {
        let t: Vec<f64> = (0..400).map(|i| i as f64 * 0.05).collect();
        let a: Vec<f64> = t.iter().map(|t| (1.3 * t).sin() * 0.1).collect();
        let b: Vec<f64> = t
            .iter()
            .map(|t| {
                if *t > 7.0 {
                    10f64.powf(t.cos())
                } else {
                    f64::NAN
                }
            })
            .collect();
        let series = |label, y, style| Series {
            label,
            x: &t,
            y,
            style,
            color: None,
        };
        let lines = Figure {
            title: "Lines <&> \"quotes\" 'too'",
            subtitle: "held fixed: nothing",
            x_label: "t [s]",
            panels: vec![
                Panel {
                    title: "two lines",
                    y_label: "w [m]",
                    series: vec![
                        series("with", &a, LineStyle::Solid),
                        series("without", &b, LineStyle::Dashed),
                    ],
                    y_scale: AxisScale::Linear,
                },
                Panel {
                    title: "log",
                    y_label: "r",
                    series: vec![series("r", &b, LineStyle::Solid)],
                    y_scale: AxisScale::Log,
                },
            ],
            legend_once: false,
            width: 900,
            height: 700,
        };
        let (ours, theirs) = both(&lines, 900, 700);
        assert!(ours.contains("<polyline") && ours.contains("&lt;&amp;&gt; &quot;quotes&quot;"));
        assert_eq!(ours, theirs);

        let (v, z) = ([0.1, 0.25, 0.3], [1.0, 2.0, 3.0]);
        let profile = ProfileFigure {
            title: "Envelopes",
            subtitle: "",
            y_label: "height [m]",
            panels: vec![ProfilePanel {
                title: "w",
                x_label: "w [m]",
                base: Some(0.0),
                series: vec![
                    ProfileSeries {
                        label: "with",
                        values: &v,
                        heights: &z,
                        style: LineStyle::Solid,
                        color: 0,
                        rings: &[false, true, false],
                    },
                    ProfileSeries {
                        label: "without",
                        values: &z,
                        heights: &z,
                        style: LineStyle::Dashed,
                        color: 1,
                        rings: &[],
                    },
                ],
            }],
            width: 700,
            height: 500,
        };
        let (ours, theirs) = both(&profile, 700, 500);
        assert!(ours.contains("<circle"));
        assert_eq!(ours, theirs);

        let (x, p) = ([0.1, 0.5, 1.0, 1.5], [0.0, 0.3, 0.7, 0.9]);
        let (lo, hi) = ([0.0, 0.2, 0.6, 0.8], [0.1, 0.4, 0.8, 1.0]);
        let curves = CurveFigure {
            title: "Fragility",
            subtitle: "",
            x_label: "Sa [g]",
            y_label: "P",
            y_range: (0.0, 1.0),
            panels: vec![CurvePanel {
                title: "gap 10 mm".into(),
                curves: vec![BandCurve {
                    label: "fit",
                    x: &x,
                    y: &p,
                    band: (&lo, &hi),
                    color: 0,
                    style: LineStyle::Dashed,
                }],
                markers: vec![Markers {
                    x: &x,
                    y: &p,
                    color: 1,
                    filled: false,
                }],
            }],
            columns: 1,
            width: 600,
            height: 500,
        };
        let (ours, theirs) = both(&curves, 600, 500);
        assert!(ours.contains("<polygon") && ours.contains("opacity=\"0.18\""));
        assert_eq!(ours, theirs);

        let zs = [0.5, 1.0, f64::NAN, 4.0, 0.1, 2.0];
        let heat = Heatmap {
            title: "Ratio",
            subtitle: "",
            x_label: "gap [m]",
            y_label: "T1/T2",
            x: &[0.01, 0.02, 0.03],
            y: &[0.5, 0.7],
            z: &zs,
            z_label: "ratio",
            scale: ColorScale::Ratio { limit: 10.0 },
            zero_label: "",
            width: 700,
            height: 500,
        };
        let (ours, theirs) = both(&heat, 700, 500);
        assert_eq!(ours, theirs);

        let xy = XyFigure {
            title: "Spectra",
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
            lines: vec![XyLine {
                label: "a",
                x: &t[1..],
                y: &a[1..],
                style: LineStyle::Dashed,
                color: LineColor::Palette(1),
                width: 3,
            }],
            width: 800,
            height: 500,
        };
        let (ours, theirs) = both(&xy, 800, 500);
        assert_eq!(ours, theirs);
    }
}
