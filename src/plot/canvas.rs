//! The bitmap every PNG is drawn on: an RGB buffer behind plotters' [`DrawingBackend`] that
//! draws the two things the pictures spend most of their time on itself, and hands everything
//! else (axis lines, rectangles, circles, polygons) to plotters' own bitmap backend over the
//! same buffer, so those pixels are exactly as before.
//!
//! - **Thick lines** (stroke width ≥ 2, opaque): each segment is scanned along its major axis,
//!   one short span per pixel column (or row) written straight into the buffer, instead of
//!   plotters' polygon fill (a polygon per segment, sorted edges and a vector per scan line:
//!   ~12 000 instructions per segment of a time history, now a few hundred). The span of a
//!   segment of width `w` at a column is `y_c ± (w/2)·L/|Δx|` around the centre line `y_c`
//!   (`L` the segment's length: the same perpendicular width at every slope), filled like
//!   plotters fills its polygons (every pixel whose centre lies in the span, and the pixels
//!   just outside by the part of them it covers), so a line looks as before. Segments are
//!   drawn one by one, each ending on its end point's column (row): no miter spikes above a
//!   sharp peak, and consecutive segments overlap at their shared point, so joins have no gap.
//! - **Text**: each glyph of each size is rasterised once per process ([`draw_text`] of the
//!   trait re-rasterised every glyph of every label); the cached coverage is placed and
//!   blended exactly as plotters places and blends it, so text pixels are unchanged.
//!
//! [`draw_text`]: DrawingBackend::draw_text

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use ab_glyph::{Font, FontRef, GlyphId, ScaleFont};
use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};

use super::style::{FONT, FONT_BYTES};

/// The error type of plotters' bitmap backend, which this one shares.
type BitmapError = <BitMapBackend<'static> as DrawingBackend>::ErrorType;
type DrawResult = Result<(), DrawingErrorKind<BitmapError>>;

const WIDEN: f64 = 0.5;

/// An RGB bitmap (`3·w·h` bytes, rows top to bottom) drawn through plotters.
pub(super) struct Canvas<'a> {
    buf: &'a mut [u8],
    w: u32,
    h: u32,
}

impl<'a> Canvas<'a> {
    /// A canvas over `buf`; `None` when `buf` is not `3·w·h` bytes.
    pub fn new(buf: &'a mut [u8], (w, h): (u32, u32)) -> Option<Canvas<'a>> {
        (buf.len() == 3 * w as usize * h as usize).then_some(Canvas { buf, w, h })
    }

    /// plotters' bitmap backend over the same buffer (a borrow, no copy: nothing to set up).
    fn plotters(&mut self) -> BitMapBackend<'_> {
        BitMapBackend::with_buffer(self.buf, (self.w, self.h))
    }

    /// Paints pixel `(x, y)` (inside the canvas) with `rgb` at opacity `alpha`, as plotters'
    /// RGB bitmap does: opaque from 255/256 up, else each channel moved towards the colour by
    /// `⌊256·alpha⌋/256` of the difference, rounded towards the old value.
    #[inline]
    fn blend(&mut self, x: usize, y: usize, rgb: [u8; 3], alpha: f64) {
        self.blend_at(3 * (y * self.w as usize + x), rgb, weight(alpha));
    }

    /// Paints the pixel at byte offset `i` with `rgb` at weight `a` of 256 ([`weight`]).
    #[inline]
    fn blend_at(&mut self, i: usize, rgb: [u8; 3], a: u32) {
        let Some(px) = self.buf.get_mut(i..i + 3) else {
            return;
        };
        if a >= 256 {
            px.copy_from_slice(&rgb);
        } else if a > 0 {
            for (old, new) in px.iter_mut().zip(rgb) {
                if new > *old {
                    *old += (u32::from(new - *old) * a / 256) as u8;
                } else {
                    *old -= (u32::from(*old - new) * a / 256) as u8;
                }
            }
        }
    }

    /// Paints the pixels `k` of a line of pixels (a column: byte offsets `base + 3·w·k`; a row:
    /// `base + 3·k`; `0 ≤ k < n`) over `[lo, hi]` of it, pixel `k` covering `[k − ½, k + ½]`:
    /// the pixels inside opaque, the one at each end by the fraction of it that is covered.
    fn span(&mut self, (base, stride, n): (usize, usize, i64), lo: f64, hi: f64, rgb: [u8; 3]) {
        // (NaN ends: nothing to draw)
        if lo.partial_cmp(&hi).is_none_or(|o| o.is_gt()) {
            return;
        }
        // the end pixels (clamped before the conversion: a span far off the canvas stays off)
        let pixel = |v: f64| floor((v + 0.5).clamp(-1.0, n as f64));
        let (first, last) = (pixel(lo), pixel(hi));
        let mut put = |k: i64, alpha: f64| {
            if (0..n).contains(&k) {
                self.blend_at(base + k as usize * stride, rgb, weight(alpha));
            }
        };
        if first == last {
            put(first, hi - lo);
            return;
        }
        put(first, first as f64 + 0.5 - lo);
        put(last, hi - (last as f64 - 0.5));
        let (a, b) = ((first + 1).max(0), (last - 1).min(n - 1));
        for k in a..=b {
            let i = base + k as usize * stride;
            if let Some(px) = self.buf.get_mut(i..i + 3) {
                px.copy_from_slice(&rgb);
            }
        }
    }

    /// A straight segment `a`–`b` of width `width` pixels (see the module's documentation).
    fn segment(&mut self, a: BackendCoord, b: BackendCoord, width: f64, rgb: [u8; 3]) {
        let (dx, dy) = (
            (i64::from(b.0) - i64::from(a.0)) as f64,
            (i64::from(b.1) - i64::from(a.1)) as f64,
        );
        let len = dx.hypot(dy);
        if len == 0.0 {
            return;
        }
        // scan along the longer extent: `run` is (major, minor) coordinate of a point
        let column = dx.abs() >= dy.abs();
        let run = |p: BackendCoord| if column { p } else { (p.1, p.0) };
        let (p, q) = if run(a).0 <= run(b).0 {
            (run(a), run(b))
        } else {
            (run(b), run(a))
        };
        let slope = (f64::from(q.1) - f64::from(p.1)) / (f64::from(q.0) - f64::from(p.0));
        let half = 0.5 * (width + WIDEN) * len / if column { dx.abs() } else { dy.abs() };
        let (w, h) = (self.w as usize, self.h as usize);
        // (major extent, minor extent, bytes between pixels along the minor axis)
        let (major, minor, stride) = if column { (w, h, 3 * w) } else { (h, w, 3) };
        let (first, last) = (i64::from(p.0).max(0), i64::from(q.0).min(major as i64 - 1));
        for x in first..=last {
            let c = f64::from(p.1) + (x - i64::from(p.0)) as f64 * slope;
            // where pixel (major x, minor 0) starts
            let base = if column {
                3 * x as usize
            } else {
                3 * w * x as usize
            };
            self.span((base, stride, minor as i64), c - half, c + half, rgb);
        }
    }
}

/// The weight of opacity `alpha` out of 256 as plotters' RGB bitmap applies it: 256 (opaque)
/// from 255/256 up, else `⌊256·alpha⌋` (0 for `alpha ≤ 0`).
#[inline]
fn weight(alpha: f64) -> u32 {
    if alpha >= 1.0 - 1.0 / 256.0 {
        256
    } else if alpha > 0.0 {
        // (truncation is the floor here: 0 < alpha < 1; `floor` is a libm call)
        (alpha * 256.0) as u32
    } else {
        0
    }
}

impl DrawingBackend for Canvas<'_> {
    type ErrorType = BitmapError;

    fn get_size(&self) -> (u32, u32) {
        (self.w, self.h)
    }

    fn ensure_prepared(&mut self) -> DrawResult {
        Ok(())
    }

    fn present(&mut self) -> DrawResult {
        Ok(())
    }

    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> DrawResult {
        if point.0 >= 0 && point.1 >= 0 && (point.0 as u32) < self.w && (point.1 as u32) < self.h {
            let rgb = [color.rgb.0, color.rgb.1, color.rgb.2];
            self.blend(point.0 as usize, point.1 as usize, rgb, color.alpha);
        }
        Ok(())
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> DrawResult {
        self.plotters().draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> DrawResult {
        self.plotters()
            .draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> DrawResult {
        let color = style.color();
        if style.stroke_width() < 2 || color.alpha < 1.0 {
            // thin lines (plotters' own line drawing, fast) and translucent ones (drawn once
            // as one polygon: overlapping segments would darken their joins)
            return self.plotters().draw_path(path, style);
        }
        let width = f64::from(style.stroke_width());
        let mut path = path.into_iter();
        let Some(mut a) = path.next() else {
            return Ok(());
        };
        for b in path {
            if b != a {
                self.segment(a, b, width, [color.rgb.0, color.rgb.1, color.rgb.2]);
                a = b;
            }
        }
        Ok(())
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> DrawResult {
        self.plotters().draw_circle(center, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> DrawResult {
        self.plotters().fill_polygon(vert, style)
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
        // another font than ours (not drawn by the figures): plotters draws it
        let (Some(font), FONT) = (embedded_font(), style.family().as_str()) else {
            return self.plotters().draw_text(text, style, pos);
        };
        // placed as plotters places text: the anchor on the layout box, then the rotation
        let ((min_x, min_y), (max_x, max_y)) = style
            .layout_box(text)
            .map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
        let (width, height) = (max_x - min_x, max_y - min_y);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Right => -width,
            HPos::Center => -width / 2,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let trans = style.transform();
        let size = style.size();
        let rgb = [color.rgb.0, color.rgb.1, color.rgb.2];
        let opaque = color.alpha == 1.0;
        let scaled = font.as_scaled(size as f32);
        let mut cache = glyph_cache().lock().unwrap_or_else(|e| e.into_inner());
        if cache.len() > MAX_CACHED_GLYPHS {
            cache.clear();
        }
        // glyph by glyph, as ab_glyph lays them out for plotters: advance plus kerning, each
        // glyph's pixel box hung from half the size above the text's top
        let mut advance = 0f32;
        let mut prev: Option<GlyphId> = None;
        for c in text.chars() {
            let g = cache
                .entry((c, size.to_bits()))
                .or_insert_with(|| Glyph::rasterise(&scaled, c));
            if let Some(p) = prev {
                advance += scaled.kern(p, g.id);
            }
            prev = Some(g.id);
            if let Some(top) = g.top {
                let gx = advance as i32 + dx - min_x;
                let gy = ((size as f32) / 2.0 + top) as i32 + dy - min_y;
                for &(x, y, cover) in g.cover.iter() {
                    let (x, y) = trans.transform(x as i32 + gx, y as i32 + gy);
                    let (x, y) = (pos.0 + x, pos.1 + y);
                    if x >= 0 && y >= 0 && (x as u32) < self.w && (y as u32) < self.h {
                        // (opaque text: the weight of the coverage alone, kept with the glyph)
                        let a = if opaque {
                            cover.1
                        } else {
                            weight(color.alpha * f64::from(cover.0))
                        };
                        let i = 3 * (y as usize * self.w as usize + x as usize);
                        self.blend_at(i, rgb, a);
                    }
                }
            }
            advance += g.advance;
        }
        Ok(())
    }

    fn blit_bitmap(&mut self, pos: BackendCoord, size: (u32, u32), src: &[u8]) -> DrawResult {
        self.plotters().blit_bitmap(pos, size, src)
    }
}

/// The glyph cache is cleared when it holds more than this many glyphs (each a few hundred
/// bytes; the figures of a run use ~100 glyph–size pairs).
const MAX_CACHED_GLYPHS: usize = 4096;

/// One glyph at one size, as ab_glyph rasterises it for plotters.
struct Glyph {
    id: GlyphId,
    /// Horizontal advance, pixels.
    advance: f32,
    /// Top of the glyph's pixel box relative to the baseline (`None`: no outline, e.g. a
    /// space).
    top: Option<f32>,
    /// The covered pixels of its box.
    cover: Box<[Covered]>,
}

/// A pixel of a glyph's box: `(x, y, (coverage, its weight out of 256))`, coverage in (0, 1].
type Covered = (u32, u32, (f32, u32));

impl Glyph {
    fn rasterise<F: Font>(font: &impl ScaleFont<F>, c: char) -> Glyph {
        let glyph = font.scaled_glyph(c);
        let id = glyph.id;
        let mut cover = Vec::new();
        let top = font.outline_glyph(glyph).map(|q| {
            // (uncovered pixels are left out: plotters draws them at opacity 0, a no-op)
            q.draw(|x, y, a| {
                if a > 0.0 {
                    cover.push((x, y, (a, weight(f64::from(a)))));
                }
            });
            q.px_bounds().min.y
        });
        Glyph {
            id,
            advance: font.h_advance(id),
            top,
            cover: cover.into_boxed_slice(),
        }
    }
}

/// The rasterised glyphs, by character and size (the bits of the size in pixels), shared by
/// every figure of the process.
fn glyph_cache() -> &'static Mutex<HashMap<(char, u64), Glyph>> {
    static CACHE: OnceLock<Mutex<HashMap<(char, u64), Glyph>>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// The embedded font, parsed once (`None` if it cannot be: then plotters draws the text).
fn embedded_font() -> Option<&'static FontRef<'static>> {
    static PARSED: OnceLock<Option<FontRef<'static>>> = OnceLock::new();
    PARSED
        .get_or_init(|| FontRef::try_from_slice(FONT_BYTES).ok())
        .as_ref()
}

/// `⌊v⌋` for a finite `v` well inside the range of `i64` (`f64::floor` is a libm call on the
/// baseline x86-64 target, ~25 instructions).
#[inline]
fn floor(v: f64) -> i64 {
    let t = v as i64;
    t - i64::from((t as f64) > v)
}

#[cfg(test)]
mod tests {
    use plotters::style::FontTransform;
    use plotters::style::text_anchor::Pos;

    use super::super::style::{ensure_font, font};
    use super::*;

    const W: u32 = 300;
    const H: u32 = 200;

    fn white() -> Vec<u8> {
        vec![255u8; 3 * W as usize * H as usize]
    }

    /// Darkness of pixel `(x, y)` of a black drawing on white, 0 (white) … 1 (black).
    fn ink(buf: &[u8], x: i64, y: i64) -> f64 {
        if !(0..W as i64).contains(&x) || !(0..H as i64).contains(&y) {
            return 0.0;
        }
        1.0 - f64::from(buf[3 * (y as usize * W as usize + x as usize)]) / 255.0
    }

    /// Text drawn from the glyph cache has exactly the pixels plotters' own bitmap backend
    /// gives it: every anchor, both sizes of the figures, rotated (the y-axis labels),
    /// translucent, cut by the picture's edge, and each text drawn twice (the second time
    /// from the cache, onto the first).
    #[test]
    fn cached_text_is_plotters_text_pixel_for_pixel() {
        ensure_font().unwrap();
        let texts = [
            "Peak storey drift ratio",
            "−0.05 ±1e-4 [m/s²]",
            "Tg = 0.65 s, AV",
        ];
        let (mut ours, mut theirs) = (white(), white());
        for round in 0..2 {
            let mut canvas = Canvas::new(&mut ours, (W, H)).unwrap();
            let mut plain = BitMapBackend::with_buffer(&mut theirs, (W, H));
            for (i, text) in texts.iter().enumerate() {
                for (j, (h, v)) in [
                    (HPos::Left, VPos::Top),
                    (HPos::Center, VPos::Center),
                    (HPos::Right, VPos::Bottom),
                ]
                .into_iter()
                .enumerate()
                {
                    for (k, transform) in [
                        FontTransform::None,
                        FontTransform::Rotate270,
                        FontTransform::Rotate90,
                    ]
                    .into_iter()
                    .enumerate()
                    {
                        let size = [16.0, 26.0, 19.0][(i + j + round) % 3];
                        let color = if k == 2 { RED.mix(0.4) } else { BLACK.mix(1.0) };
                        let style = font(size)
                            .transform(transform)
                            .color(&color)
                            .pos(Pos::new(h, v));
                        // (some texts run off the left, right or bottom edge)
                        let at = (40 * j as i32 + 100 * k as i32 - 30, 60 * i as i32 + 20);
                        canvas.draw_text(text, &style, at).unwrap();
                        plain.draw_text(text, &style, at).unwrap();
                    }
                }
            }
        }
        assert!(ours.iter().any(|&v| v < 128), "no text drawn");
        assert!(
            ours == theirs,
            "the cached glyphs differ from plotters' text"
        );
    }

    /// A straight 2-pixel line is drawn where its formula puts it: in every pixel column
    /// of a shallow line (and every row of a steep one) the ink's centroid lies on the
    /// line `y = y0 + (x − x0)·dy/dx` and its total is the line's width across that column,
    /// `(2 + ½)·L/|dx|` (the 2-pixel stroke is drawn ½ pixel wider, with the ink of plotters'
    /// lines). Tolerances: each partly covered pixel is quantised to 1/256 of its colour and
    /// 1/255 of white, ≤ 2/255 per pixel, two such pixels per column (0.02 on the total); the
    /// centroid counts a partly covered end pixel's ink at the pixel's centre, not at the
    /// centre of its covered part, which moves it by at most `c(1 − c)/2 ≤ 1/8` pixel-ink
    /// per end over a total of ≥ 2.5 (0.05), plus the quantisation (0.06 in all).
    #[test]
    fn a_straight_line_lies_where_its_formula_puts_it() {
        for (a, b) in [((20, 30), (220, 130)), ((40, 190), (90, 10))] {
            let mut buf = white();
            let mut canvas = Canvas::new(&mut buf, (W, H)).unwrap();
            let style = ShapeStyle::from(&BLACK).stroke_width(2);
            canvas.draw_path([a, b], &style).unwrap();
            let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
            let len = dx.hypot(dy);
            let column = dx.abs() >= dy.abs();
            let (major, across) = if column { (dx.abs(), W) } else { (dy.abs(), H) };
            let width = 2.5 * len / major;
            let (p, q) = if column { (a.0, b.0) } else { (a.1, b.1) };
            for m in p.min(q) + 1..p.max(q) {
                let centre = if column {
                    f64::from(a.1) + f64::from(m - a.0) * dy / dx
                } else {
                    f64::from(a.0) + f64::from(m - a.1) * dx / dy
                };
                let pix = |k: i64| {
                    if column {
                        ink(&buf, i64::from(m), k)
                    } else {
                        ink(&buf, k, i64::from(m))
                    }
                };
                let total: f64 = (0..i64::from(across)).map(pix).sum();
                let moment: f64 = (0..i64::from(across)).map(|k| k as f64 * pix(k)).sum();
                assert!(
                    (total - width).abs() < 0.02,
                    "{m}: ink {total}, width {width}"
                );
                assert!(
                    (moment / total - centre).abs() < 0.06,
                    "{m}: centroid {} for a line at {centre}",
                    moment / total
                );
            }
        }
    }

    /// A spike (an impact's force: up and straight down again) ends at its peak: no ink above
    /// the peak's pixel row (plotters' mitred thick polylines drew a spike far above it), and
    /// the peak's own row is inked; the joins leave no gap (every row between the base and
    /// the peak holds ink on both flanks).
    #[test]
    fn a_spike_is_drawn_to_its_peak_and_no_higher() {
        let mut buf = white();
        let mut canvas = Canvas::new(&mut buf, (W, H)).unwrap();
        let style = ShapeStyle::from(&BLACK).stroke_width(2);
        let spike = [(50, 180), (100, 180), (103, 20), (106, 180), (200, 180)];
        canvas.draw_path(spike, &style).unwrap();
        let row_ink = |y: i64| (0..i64::from(W)).map(|x| ink(&buf, x, y)).sum::<f64>();
        assert_eq!(row_ink(19), 0.0);
        assert!(row_ink(20) > 1.0, "the peak row holds {}", row_ink(20));
        for y in 21..180 {
            // each flank at this row: x from the formula of its segment
            for (x0, x1) in [(100.0, 103.0), (106.0, 103.0)] {
                let x = x0 + (x1 - x0) * (180.0 - y as f64) / 160.0;
                let near: f64 = (-2..=2).map(|d| ink(&buf, x.round() as i64 + d, y)).sum();
                assert!(near > 1.5, "row {y}: {near} ink near the flank at {x}");
            }
        }
    }

    /// The thick-line fast path keeps to the canvas: lines far outside it, through it from
    /// far away, degenerate ones and a zero-length path draw nothing outside and do not panic.
    #[test]
    fn lines_far_off_the_canvas_are_clipped() {
        let mut buf = white();
        let mut canvas = Canvas::new(&mut buf, (W, H)).unwrap();
        let style = ShapeStyle::from(&BLACK).stroke_width(3);
        for path in [
            vec![(-100_000, -5), (100_000, 7)],
            vec![(i32::MIN / 2, i32::MIN / 2), (i32::MAX / 2, i32::MAX / 2)],
            vec![(10, 10), (10, 10)],
            vec![(5, 5)],
            vec![],
            vec![(-50, 100), (-10, 400)],
        ] {
            canvas.draw_path(path, &style).unwrap();
        }
        // the first line crosses the whole width near y = 1
        assert!((0..i64::from(W)).all(|x| ink(&buf, x, 1) > 0.5));
        assert!(Canvas::new(&mut [0u8; 10], (2, 2)).is_none());
    }
}
