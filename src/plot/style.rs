//! What every picture shares: the embedded font, text sizes, the line palette, number labels,
//! tick positions plotters does not choose for us (log axes, grid values), and the colour scales
//! of heatmaps.
//!
//! The colour scales are pure functions so that they can be tested from their formulas:
//! [`ColorScale::Ratio`] maps a ratio `r` to the position `½ + ½·log10(r)/log10(limit)` of a
//! blue–white–red map (white at `r = 1`, symmetric in `log r`, saturated beyond `×limit` and
//! `×1/limit`); [`ColorScale::Log`] maps `log10 z` linearly onto viridis; [`ColorScale::Linear`]
//! maps `z` linearly onto viridis.

use std::sync::OnceLock;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use super::PlotError;

/// The tick labels of every figure (re-exported: the style of a figure's numbers).
pub use crate::numerics::format::fmt_num;

/// The embedded font (DejaVu Sans, Bitstream Vera / DejaVu licence, freely redistributable).
pub(super) static FONT_BYTES: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Font family name under which the embedded font is registered with plotters.
pub(super) const FONT: &str = "sans-serif";

/// Registers the embedded font once; later calls return the cached outcome.
pub(super) fn ensure_font() -> Result<(), PlotError> {
    static FONT_OK: OnceLock<bool> = OnceLock::new();
    if *FONT_OK.get_or_init(|| register_font(FONT, FontStyle::Normal, FONT_BYTES).is_ok()) {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

/// The embedded font at `size` pixels.
pub(super) fn font(size: f64) -> FontDesc<'static> {
    FontDesc::new(FontFamily::Name(FONT), size, FontStyle::Normal)
}

/// Text width in pixels (a rough estimate if the font cannot measure it).
pub(super) fn text_width(text: &str, size: f64) -> i32 {
    match font(size).box_size(text) {
        Ok((w, _)) => w as i32,
        Err(_) => (text.chars().count() as f64 * size * 0.6).ceil() as i32,
    }
}

/// Text sizes in pixels, scaled to the picture: constant for ordinary sizes, smaller for small
/// pictures, larger for big ones.
#[derive(Clone, Copy, Debug)]
pub(super) struct Fonts {
    pub title: f64,
    pub text: f64,
    pub tick: f64,
}

impl Fonts {
    pub fn for_size(w: u32, h: u32) -> Fonts {
        let m = w.min(h) as f64;
        let s = if m < 600.0 {
            m / 600.0
        } else if m > 1000.0 {
            m / 1000.0
        } else {
            1.0
        }
        .clamp(0.75, 3.0);
        Fonts {
            title: 26.0 * s,
            text: 19.0 * s,
            tick: 16.0 * s,
        }
    }
}

/// Okabe–Ito colour-blind-safe palette, ordered so the first colours contrast best on white.
pub(super) const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
    RGBColor(240, 228, 66),  // yellow
];

/// Axis lines and tick labels.
pub(super) const AXIS: RGBColor = RGBColor(40, 40, 40);
/// Grid lines of line plots.
pub(super) const GRID: RGBColor = RGBColor(225, 225, 225);
/// Heatmap cells without data (failed cases).
pub const NO_DATA: RGBColor = RGBColor(150, 150, 150);
/// Heatmap cells whose value is zero on a logarithmic scale (e.g. no impact at all).
pub const ZERO: RGBColor = RGBColor(255, 255, 255);

/// ColorBrewer RdBu (11 classes), from blue (below the centre) through white to red (above).
const BLUE_WHITE_RED: [RGBColor; 11] = [
    RGBColor(0x05, 0x30, 0x61),
    RGBColor(0x21, 0x66, 0xac),
    RGBColor(0x43, 0x93, 0xc3),
    RGBColor(0x92, 0xc5, 0xde),
    RGBColor(0xd1, 0xe5, 0xf0),
    RGBColor(0xf7, 0xf7, 0xf7),
    RGBColor(0xfd, 0xdb, 0xc7),
    RGBColor(0xf4, 0xa5, 0x82),
    RGBColor(0xd6, 0x60, 0x4d),
    RGBColor(0xb2, 0x18, 0x2b),
    RGBColor(0x67, 0x00, 0x1f),
];

/// The neutral colour of [`ColorScale::Ratio`] (ratio 1).
pub const RATIO_NEUTRAL: RGBColor = BLUE_WHITE_RED[5];
/// The colour of [`ColorScale::Ratio`] at and below `×1/limit`.
pub const RATIO_LOW: RGBColor = BLUE_WHITE_RED[0];
/// The colour of [`ColorScale::Ratio`] at and above `×limit`.
pub const RATIO_HIGH: RGBColor = BLUE_WHITE_RED[10];

/// How heatmap values become colours.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ColorScale {
    /// Viridis, linear in the value over the data's range.
    Linear,
    /// Viridis, linear in `log10` of the value over the positive data's range; values ≤ 0 are
    /// drawn white ([`ZERO`]) and explained under the colour bar.
    Log,
    /// A ratio (e.g. peak with / peak without pounding): blue–white–red, linear in `log10` of
    /// the ratio, white at 1, saturated at `×1/limit` and `×limit` (the colour bar says so).
    Ratio {
        /// Saturation factor, > 1 (10: the scale runs ×0.1 … ×10).
        limit: f64,
    },
}

impl ColorScale {
    /// [`ColorScale::Log`] when the positive finite values span more than a factor of 100,
    /// else [`ColorScale::Linear`].
    pub fn auto(z: &[f64]) -> ColorScale {
        match positive_range(z) {
            Some((lo, hi)) if hi > 100.0 * lo => ColorScale::Log,
            _ => ColorScale::Linear,
        }
    }
}

/// Where `r` falls on a [`ColorScale::Ratio`] map of saturation `limit`, from 0 (`≤ 1/limit`)
/// through ½ (`r = 1`) to 1 (`≥ limit`): `½ + ½·log10(r)/log10(limit)`, clamped. `None` for a
/// NaN, negative ratio or a `limit` not above 1.
pub fn ratio_position(r: f64, limit: f64) -> Option<f64> {
    if r.is_nan() || r < 0.0 || limit.is_nan() || limit <= 1.0 {
        return None;
    }
    // log10(0) = −∞ and log10(∞) = ∞ saturate like any ratio beyond the limit
    Some((0.5 + 0.5 * r.log10() / limit.log10()).clamp(0.0, 1.0))
}

/// The colour of ratio `r` on a [`ColorScale::Ratio`] map of saturation `limit` ([`NO_DATA`]
/// where [`ratio_position`] gives none).
pub fn ratio_color(r: f64, limit: f64) -> RGBColor {
    ratio_position(r, limit).map_or(NO_DATA, |t| {
        DerivedColorMap::new(&BLUE_WHITE_RED).get_color(t)
    })
}

/// Viridis at `t` in `[0, 1]` (clamped; NaN gives [`NO_DATA`]).
pub fn viridis(t: f64) -> RGBColor {
    if t.is_nan() {
        return NO_DATA;
    }
    ViridisRGB::get_color(t.clamp(0.0, 1.0))
}

/// Smallest and largest finite value, or `None` if there is none.
pub(super) fn finite_range(z: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    z.into_iter()
        .filter(|v| v.is_finite())
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// Smallest and largest finite positive value.
pub(super) fn positive_range(z: &[f64]) -> Option<(f64, f64)> {
    finite_range(z.iter().copied().filter(|&v| v > 0.0))
}

/// Widens `[lo, hi]` by `frac` of its span on each side; a (nearly) zero-width range is opened
/// around its centre, a missing one becomes `[0, 1]`.
pub(super) fn pad(r: Option<(f64, f64)>, frac: f64) -> (f64, f64) {
    let Some((lo, hi)) = r else {
        return (0.0, 1.0);
    };
    let (lo, hi) = (lo.clamp(-1e300, 1e300), hi.clamp(-1e300, 1e300));
    let scale = lo.abs().max(hi.abs()).min(1e300);
    if hi - lo <= scale * 1e-9 {
        let half = if scale < 1e-250 { 1.0 } else { scale * 0.1 };
        return (lo - half, hi + half);
    }
    let p = (hi - lo) * frac;
    (lo - p, hi + p)
}

/// Ticks of a logarithmic axis over `[lo, hi]` (values, not logs; `0 < lo < hi`): 1-2-5 per
/// decade when that gives at most `max_n`, else the powers of ten (every second, third … decade
/// if needed), else the two ends.
pub(super) fn log_ticks(lo: f64, hi: f64, max_n: usize) -> Vec<f64> {
    let (d0, d1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let pick = |mantissas: &[f64], every: i32| -> Vec<f64> {
        (d0..=d1)
            .filter(|d| d.rem_euclid(every) == 0)
            .flat_map(|d| mantissas.iter().map(move |m| m * 10f64.powi(d)))
            .filter(|&t| t >= lo * (1.0 - 1e-9) && t <= hi * (1.0 + 1e-9))
            .collect()
    };
    let dense = pick(&[1.0, 2.0, 5.0], 1);
    if dense.len() < 4 {
        // about a decade or less: plotters' linear ticks read better (1, 1.5, 2, 2.5 …)
        let lin: Vec<f64> = RangedCoordf64::from(lo..hi).key_points(max_n.max(2));
        let lin: Vec<f64> = lin.into_iter().filter(|&t| t > 0.0).collect();
        if lin.len() > dense.len() {
            return lin;
        }
    }
    if (2..=max_n).contains(&dense.len()) {
        return dense;
    }
    if dense.len() > max_n {
        for every in [1, 2, 3, 5, 10, 20, 50] {
            let t = pick(&[1.0], every);
            if t.len() <= max_n && t.len() >= 2 {
                return t;
            }
        }
    }
    vec![lo, hi]
}

/// Which of `n` sorted grid values to label so that at most `fit` labels are shown: every
/// k-th value from some offset, with the smallest stride that fits (or up to twice that) and,
/// among those, the shortest labels — so a grid 0.2, 0.22, … 1.0 is labelled 0.2, 0.3, … 1.
pub(super) fn grid_ticks(values: &[f64], fit: usize) -> Vec<f64> {
    let n = values.len();
    if n <= fit.max(1) {
        return values.to_vec();
    }
    let fit = fit.max(2);
    let kmin = n.div_ceil(fit);
    let mut best: Option<(usize, usize, usize)> = None; // (longest label, k, offset)
    for k in kmin..=(2 * kmin).min(n) {
        for o in 0..k {
            let chosen: Vec<f64> = values.iter().skip(o).step_by(k).copied().collect();
            if chosen.len() > fit || chosen.len() < 2.min(n) {
                continue;
            }
            let longest = chosen
                .iter()
                .map(|v| fmt_num(*v).chars().count())
                .max()
                .unwrap_or(0);
            if best.is_none_or(|b| (longest, k) < (b.0, b.1)) {
                best = Some((longest, k, o));
            }
        }
    }
    let (_, k, o) = best.unwrap_or((0, kmin, 0));
    values.iter().skip(o).step_by(k).copied().collect()
}

/// A linear plotters coordinate over `[lo, hi]` whose ticks (and grid lines) are exactly
/// `ticks`. (plotters' `with_key_points` does the same but cannot take a label formatter.)
#[derive(Clone, Debug)]
pub(super) struct Ticked {
    pub lo: f64,
    pub hi: f64,
    pub ticks: Vec<f64>,
}

impl Ranged for Ticked {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let frac = ((*v - self.lo) / (self.hi - self.lo)).clamp(-1.0, 2.0);
        let frac = if frac.is_finite() { frac } else { 0.5 };
        limit.0 + round((limit.1 - limit.0) as f64 * frac)
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            Vec::new()
        } else {
            self.ticks.clone()
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.lo..self.hi
    }
}

/// `v.round() as i32` for `|v| < 2³¹` (`f64::round` is a libm call on the baseline x86-64
/// target, and every point of every line is mapped): the truncation, moved one away from zero
/// when the part cut off is a half or more (that part, `v − trunc(v)`, is exact).
#[inline]
pub(super) fn round(v: f64) -> i32 {
    let t = v as i32;
    let cut = v - f64::from(t);
    t + i32::from(cut >= 0.5) - i32::from(cut <= -0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_ticks() {
        assert_eq!(fmt_num(0.30000000000000004), "0.3");
        assert_eq!(fmt_num(0.4203), "0.4203");
        assert_eq!(fmt_num(-0.05), "−0.05");
        assert_eq!(fmt_num(2e-4), "2e-4");
        assert_eq!(fmt_num(1.5e9), "1.5e9");
        assert_eq!(fmt_num(20.0), "20");
        assert_eq!(
            log_ticks(0.1, 10.0, 10),
            [0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0]
        );
        assert_eq!(log_ticks(1e3, 1e9, 5), [1e4, 1e6, 1e8]);
        // a 41-value grid 0.2 … 1.0 in steps of 0.02, room for 12 labels: steps of 0.1
        let g: Vec<f64> = (0..41).map(|i| 0.2 + 0.02 * i as f64).collect();
        let t: Vec<String> = grid_ticks(&g, 12).iter().map(|v| fmt_num(*v)).collect();
        assert_eq!(
            t,
            ["0.2", "0.3", "0.4", "0.5", "0.6", "0.7", "0.8", "0.9", "1"]
        );
        assert_eq!(grid_ticks(&[0.2, 0.5, 0.8], 10), [0.2, 0.5, 0.8]);
    }

    /// [`round`] is `f64::round` (half away from zero) wherever a pixel can be: every
    /// quarter and near-half from −20 000 to 20 000 and the halves' neighbours in `f64`.
    #[test]
    fn rounding_is_the_standard_libraries() {
        for i in -80_000..=80_000 {
            let v = f64::from(i) * 0.25;
            for w in [
                v,
                v.next_up(),
                v.next_down(),
                v + 0.4999999999,
                v - 0.4999999999,
            ] {
                assert_eq!(round(w), w.round() as i32, "{w}");
            }
        }
    }
}
