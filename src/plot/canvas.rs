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
    fn blend(&mut self, x: usize, y: usize, rgb: (u8, u8, u8), alpha: f64) {
        let i = 3 * (y * self.w as usize + x);
        let Some(px) = self.buf.get_mut(i..i + 3) else {
            return;
        };
        let new = [rgb.0, rgb.1, rgb.2];
        if alpha >= 1.0 - 1.0 / 256.0 {
            px.copy_from_slice(&new);
        } else if alpha > 0.0 {
            // (truncation is the floor here: 0 < alpha < 1; `floor` is a libm call)
            let a = (alpha * 256.0) as u64;
            for (old, new) in px.iter_mut().zip(new) {
                if new > *old {
                    *old += (u64::from(new - *old) * a / 256) as u8;
                } else {
                    *old -= (u64::from(*old - new) * a / 256) as u8;
                }
            }
        }
    }

    /// Paints, in pixel column `x` (`column`) or row `x` (else), the interval `[lo, hi]` of
    /// that column (row) with pixel `k` covering `[k − ½, k + ½]`: the pixels inside it
    /// opaque, the one at each end by the fraction of it the interval covers.
    fn span(&mut self, column: bool, x: i64, lo: f64, hi: f64, rgb: (u8, u8, u8)) {
        let (along, across) = if column {
            (self.h as i64, self.w as i64)
        } else {
            (self.w as i64, self.h as i64)
        };
        if !(0..across).contains(&x) || !(lo <= hi) {
            return;
        }
        // the end pixels (clamped before the conversion: a span far off the canvas stays off)
        let pixel = |v: f64| floor((v + 0.5).clamp(-1.0, along as f64));
        let (first, last) = (pixel(lo), pixel(hi));
        let put = |s: &mut Self, k: i64, alpha: f64| {
            if (0..along).contains(&k) {
                let (px, py) = if column { (x, k) } else { (k, x) };
                s.blend(px as usize, py as usize, rgb, alpha);
            }
        };
        if first == last {
            put(self, first, hi - lo);
            return;
        }
        put(self, first, first as f64 + 0.5 - lo);
        put(self, last, hi - (last as f64 - 0.5));
        let (a, b) = ((first + 1).max(0), (last - 1).min(along - 1));
        if a > b {
            return;
        }
        let colour = [rgb.0, rgb.1, rgb.2];
        let w = self.w as usize;
        if column {
            for k in a..=b {
                let i = 3 * (k as usize * w + x as usize);
                self.buf[i..i + 3].copy_from_slice(&colour);
            }
        } else {
            let row = 3 * (x as usize * w);
            let run = &mut self.buf[row + 3 * a as usize..row + 3 * b as usize + 3];
            for px in run.chunks_exact_mut(3) {
                px.copy_from_slice(&colour);
            }
        }
    }

    /// A straight segment `a`–`b` of width `width` pixels (see the module's documentation).
    fn segment(&mut self, a: BackendCoord, b: BackendCoord, width: f64, rgb: (u8, u8, u8)) {
        let (dx, dy) = (
            (i64::from(b.0) - i64::from(a.0)) as f64,
            (i64::from(b.1) - i64::from(a.1)) as f64,
        );
        let len = dx.hypot(dy);
        if len == 0.0 {
            return;
        }
        // scan along the longer extent; `run` the major coordinate, `rise` the minor one
        let column = dx.abs() >= dy.abs();
        let run = |p: BackendCoord| if column { p } else { (p.1, p.0) };
        let (p, q) = if run(a).0 <= run(b).0 {
            (run(a), run(b))
        } else {
            (run(b), run(a))
        };
        let slope = (f64::from(q.1) - f64::from(p.1)) / (f64::from(q.0) - f64::from(p.0));
        let half = 0.5 * (width + WIDEN) * len / if column { dx.abs() } else { dy.abs() };
        let limit = if column { self.w } else { self.h } as i64;
        let (first, last) = (i64::from(p.0).max(0), i64::from(q.0).min(limit - 1));
        for x in first..=last {
            let c = f64::from(p.1) + (x - i64::from(p.0)) as f64 * slope;
            self.span(column, x, c - half, c + half, rgb);
        }
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
            self.blend(point.0 as usize, point.1 as usize, color.rgb, color.alpha);
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
                self.segment(a, b, width, color.rgb);
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
                        let alpha = color.alpha * f64::from(cover);
                        self.blend(x as usize, y as usize, color.rgb, alpha);
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
    /// The covered pixels of its box: `(x, y, coverage)`, coverage in (0, 1].
    cover: Box<[(u32, u32, f32)]>,
}

impl Glyph {
    fn rasterise<F: Font>(font: &impl ScaleFont<F>, c: char) -> Glyph {
        let glyph = font.scaled_glyph(c);
        let id = glyph.id;
        let mut cover = Vec::new();
        let top = font.outline_glyph(glyph).map(|q| {
            // (uncovered pixels are left out: plotters draws them at opacity 0, a no-op)
            q.draw(|x, y, a| {
                if a > 0.0 {
                    cover.push((x, y, a));
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
