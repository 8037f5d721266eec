//! Plot output for `pounding`: stacked time-history figures and parameter-study heatmaps.
//!
//! Every picture is written twice, as `<stem>.png` and `<stem>.svg`, each atomically (rendered
//! into a temporary file in the target directory, then renamed onto the final name), so a reader
//! never sees a half-written file.
//!
//! Text is drawn with an embedded DejaVu Sans font (see `assets/DejaVuSans-LICENSE.txt`), so no
//! system fonts or fontconfig are needed at run time.
//!
//! The functions never panic on data: non-finite values are skipped (lines are broken at them,
//! heatmap cells become grey "no data" cells), empty or constant data still give a valid picture
//! with padded axes, and structurally impossible input (no panels, empty heatmap grid, wrong
//! `z` length, zero picture size) is reported as a [`PlotError`].

use std::ffi::OsString;
use std::io::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::drawing::DrawingAreaErrorKind;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontStyle, FontTransform, register_font};

/// The embedded font (DejaVu Sans, Bitstream Vera / DejaVu licence, freely redistributable).
static FONT_BYTES: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Font family name under which the embedded font is registered with plotters.
const FONT: &str = "sans-serif";

/// Largest accepted picture side in pixels.
const MAX_SIDE: u32 = 16_384;

/// Largest accepted magnitude of a data value; larger finite values are clamped to it so that
/// ranges and spans stay finite.
const BIG: f64 = 1e300;

/// Errors from writing a plot.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// Reading or writing a file failed.
    #[error("I/O error on {path}: {source}")]
    Io {
        /// The file or directory involved.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The plotting library failed to draw or encode the picture.
    #[error("drawing failed: {0}")]
    Draw(String),
    /// The embedded font could not be loaded.
    #[error("the embedded font could not be registered")]
    Font,
    /// There is nothing to draw (e.g. a figure without panels, an empty heatmap grid).
    #[error("no data to plot: {0}")]
    NoData(String),
    /// The input is inconsistent (e.g. `z` has the wrong length, zero picture size, bad path).
    #[error("invalid plot input: {0}")]
    InvalidInput(String),
}

/// How a line is drawn; its colour comes from the series' position within its panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineStyle {
    /// A continuous line.
    Solid,
    /// A dashed line.
    Dashed,
}

/// One line on a panel.
///
/// Points are taken pairwise from `x` and `y` (the longer slice is truncated); the line is broken
/// at any point whose `x` or `y` is not finite.
#[derive(Debug, Clone)]
pub struct Series<'a> {
    /// Legend text (a legend is shown when the panel has more than one series).
    pub label: &'a str,
    /// Abscissae, normally increasing.
    pub x: &'a [f64],
    /// Ordinates.
    pub y: &'a [f64],
    /// Solid or dashed.
    pub style: LineStyle,
}

/// One panel (subplot) of a stacked figure, sharing the figure's x axis.
#[derive(Debug, Clone)]
pub struct Panel<'a> {
    /// Panel title, drawn above the panel on the left.
    pub title: &'a str,
    /// Y-axis label, including the unit, e.g. `"w1 [m]"`.
    pub y_label: &'a str,
    /// The lines; colours are assigned by index from a colour-blind-safe palette (Okabe–Ito).
    pub series: Vec<Series<'a>>,
}

/// Stacked panels over one x axis: e.g. the time-history figure.
#[derive(Debug, Clone)]
pub struct Figure<'a> {
    /// Figure title, drawn centred on top.
    pub title: &'a str,
    /// X-axis label, including the unit, e.g. `"t [s]"`; shown under the bottom panel.
    pub x_label: &'a str,
    /// The panels, top to bottom.
    pub panels: Vec<Panel<'a>>,
    /// Picture width in pixels (also the SVG's nominal width).
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
}

/// A heatmap of `z` over a grid `x × y`.
///
/// `z` is row-major with `x` fastest: `z[iy * x.len() + ix]`. Grid values may be unevenly
/// spaced; each cell extends to the midpoints between neighbouring grid values. A grid that is
/// (close to) geometric, positive and spans at least a factor of 10 is drawn on a logarithmic
/// axis. Non-finite `z` cells are drawn grey and explained as "no data" under the colour bar.
/// If `z` has both signs a diverging blue–white–red map is used with white at 0 (each sign
/// scaled to its own extreme); otherwise the perceptually uniform viridis map.
#[derive(Debug, Clone)]
pub struct Heatmap<'a> {
    /// Title, drawn centred on top.
    pub title: &'a str,
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
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
}

/// Writes `<stem>.png` and `<stem>.svg` for a stacked figure; returns the paths written.
///
/// The directory of `stem` must exist. Fails with [`PlotError::NoData`] if the figure has no
/// panels; panels without finite data are drawn as empty axes.
pub fn write_figure(fig: &Figure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    check_size(fig.width, fig.height)?;
    if fig.panels.is_empty() {
        return Err(PlotError::NoData("the figure has no panels".into()));
    }
    let prep = guard(|| Ok(FigurePrep::new(fig)))?;
    write_both(&prep, stem, fig.width, fig.height)
}

/// Writes `<stem>.png` and `<stem>.svg` for a heatmap with colour bar; returns the paths written.
///
/// The directory of `stem` must exist. Fails if `x` or `y` has no finite value or if
/// `z.len() != x.len() * y.len()`.
pub fn write_heatmap(h: &Heatmap, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    check_size(h.width, h.height)?;
    let prep = guard(|| HeatPrep::new(h))?;
    write_both(&prep, stem, h.width, h.height)
}

// ---------------------------------------------------------------------------------------------
// Output plumbing
// ---------------------------------------------------------------------------------------------

fn check_size(w: u32, h: u32) -> Result<(), PlotError> {
    if w < 16 || h < 16 || w > MAX_SIDE || h > MAX_SIDE {
        return Err(PlotError::InvalidInput(format!(
            "picture size {w}x{h} is outside 16..={MAX_SIDE} pixels per side"
        )));
    }
    Ok(())
}

/// Registers the embedded font once; later calls return the cached outcome.
fn ensure_font() -> Result<(), PlotError> {
    static FONT_OK: OnceLock<bool> = OnceLock::new();
    if *FONT_OK.get_or_init(|| register_font(FONT, FontStyle::Normal, FONT_BYTES).is_ok()) {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

/// Runs `f`, turning an unexpected panic inside the plotting library into an error.
fn guard<T>(f: impl FnOnce() -> Result<T, PlotError>) -> Result<T, PlotError> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|_| {
        Err(PlotError::Draw(
            "internal error (panic) in the plotting code".into(),
        ))
    })
}

fn draw_err<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> PlotError {
    PlotError::Draw(e.to_string())
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> PlotError + '_ {
    move |source| PlotError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Something that can draw itself on any plotters backend.
trait Render {
    /// Draws on `root`. `bitmap` selects line drawing without joins (plotters' thick bitmap
    /// polylines use unlimited miter joins, which shoot spikes out of sharp peaks).
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        bitmap: bool,
    ) -> Result<(), PlotError>;
}

/// A temporary file in `dir` for an atomic write (see [`crate::output::temp_file`]).
fn temp_in(
    dir: &Path,
    prefix: &OsString,
    suffix: &str,
) -> Result<tempfile::NamedTempFile, PlotError> {
    crate::output::temp_file(dir, prefix, suffix).map_err(io_err(dir))
}

/// Renders `r` to `<stem>.png` and `<stem>.svg`, each written atomically.
fn write_both<R: Render>(r: &R, stem: &Path, w: u32, h: u32) -> Result<Vec<PathBuf>, PlotError> {
    ensure_font()?;
    let name = stem
        .file_name()
        .filter(|n| !n.is_empty())
        .ok_or_else(|| PlotError::InvalidInput(format!("bad output stem {}", stem.display())))?;
    let dir = match stem.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let with_ext = |ext: &str| {
        let mut s = stem.as_os_str().to_owned();
        s.push(ext);
        PathBuf::from(s)
    };
    let mut prefix = OsString::from(".");
    prefix.push(name);
    prefix.push(".tmp-");
    let png = with_ext(".png");
    let svg = with_ext(".svg");

    // PNG: plotters encodes by file extension, so draw into a temp file ending in `.png`.
    let tmp = temp_in(dir, &prefix, ".png")?;
    guard(|| {
        let root = BitMapBackend::new(tmp.path(), (w, h)).into_drawing_area();
        r.render(&root, true)?;
        root.present().map_err(draw_err)
    })?;
    tmp.as_file().sync_all().map_err(io_err(tmp.path()))?;
    tmp.persist(&png).map_err(|e| PlotError::Io {
        path: png.clone(),
        source: e.error,
    })?;

    // SVG: render into a string, then write it atomically.
    let mut text = String::new();
    guard(|| {
        let root = SVGBackend::with_string(&mut text, (w, h)).into_drawing_area();
        r.render(&root, false)?;
        root.present().map_err(draw_err)
    })?;
    let mut tmp = temp_in(dir, &prefix, ".svg")?;
    tmp.write_all(text.as_bytes())
        .and_then(|()| tmp.as_file().sync_all())
        .map_err(io_err(tmp.path()))?;
    tmp.persist(&svg).map_err(|e| PlotError::Io {
        path: svg.clone(),
        source: e.error,
    })?;
    Ok(vec![png, svg])
}

// ---------------------------------------------------------------------------------------------
// Styling
// ---------------------------------------------------------------------------------------------

/// Okabe–Ito colour-blind-safe palette, reordered so the first colours contrast best on white
/// (yellow, the weakest on white, comes last).
const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
    RGBColor(240, 228, 66),  // yellow
];

const GRID: RGBColor = RGBColor(225, 225, 225);
const AXIS: RGBColor = RGBColor(40, 40, 40);
const NAN_GREY: RGBColor = RGBColor(150, 150, 150);

/// Viridis, 16 evenly spaced anchors (matplotlib / R `viridis(16)`).
const VIRIDIS: [(u8, u8, u8); 16] = [
    (0x44, 0x01, 0x54),
    (0x48, 0x1a, 0x6c),
    (0x47, 0x2f, 0x7d),
    (0x41, 0x44, 0x87),
    (0x39, 0x56, 0x8c),
    (0x31, 0x68, 0x8e),
    (0x2a, 0x78, 0x8e),
    (0x23, 0x88, 0x8e),
    (0x1f, 0x98, 0x8b),
    (0x22, 0xa8, 0x84),
    (0x35, 0xb7, 0x79),
    (0x54, 0xc5, 0x68),
    (0x7a, 0xd1, 0x51),
    (0xa5, 0xdb, 0x36),
    (0xd2, 0xe2, 0x1b),
    (0xfd, 0xe7, 0x25),
];

/// Diverging blue–white–red (ColorBrewer RdBu, reversed so negative is blue).
const BLUE_WHITE_RED: [(u8, u8, u8); 11] = [
    (0x05, 0x30, 0x61),
    (0x21, 0x66, 0xac),
    (0x43, 0x93, 0xc3),
    (0x92, 0xc5, 0xde),
    (0xd1, 0xe5, 0xf0),
    (0xf7, 0xf7, 0xf7),
    (0xfd, 0xdb, 0xc7),
    (0xf4, 0xa5, 0x82),
    (0xd6, 0x60, 0x4d),
    (0xb2, 0x18, 0x2b),
    (0x67, 0x00, 0x1f),
];

/// Linear interpolation in a table of evenly spaced anchors; `t` is clamped to `[0, 1]`.
fn lerp_table(table: &[(u8, u8, u8)], t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    };
    let pos = t * (table.len() - 1) as f64;
    let i = (pos.floor() as usize).min(table.len() - 2);
    let f = pos - i as f64;
    let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
    let (a, b) = (table[i], table[i + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Font sizes scaled to the picture.
#[derive(Clone, Copy)]
struct Fonts {
    title: f64,
    panel: f64,
    desc: f64,
    tick: f64,
    legend: f64,
}

impl Fonts {
    fn for_size(w: u32, h: u32) -> Fonts {
        // Constant text size for ordinary pictures; smaller ones shrink it, larger ones grow it.
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
            title: 28.0 * s,
            panel: 20.0 * s,
            desc: 19.0 * s,
            tick: 17.0 * s,
            legend: 17.0 * s,
        }
    }
}

fn font(size: f64) -> FontDesc<'static> {
    FontDesc::new(FontFamily::Name(FONT), size, FontStyle::Normal)
}

/// Text extent in pixels `(width, height)`, with a rough fallback if the font fails.
fn text_size(text: &str, size: f64) -> (i32, i32) {
    if text.is_empty() {
        return (0, size.ceil() as i32);
    }
    match font(size).box_size(text) {
        Ok((w, h)) => (w as i32, (h as i32).max(size.ceil() as i32)),
        Err(_) => (
            (text.chars().count() as f64 * size * 0.6).ceil() as i32,
            size.ceil() as i32,
        ),
    }
}

// ---------------------------------------------------------------------------------------------
// Axes: ranges, ticks, number formatting
// ---------------------------------------------------------------------------------------------

/// Finite min/max of the values (each clamped to ±[`BIG`]), or `None` if there is none.
fn finite_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .map(|v| v.clamp(-BIG, BIG))
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// Widens a range by `frac` of its span on each side; an empty range becomes `[0, 1]` and a
/// (nearly) zero-width one is opened around its centre.
fn pad_range(r: Option<(f64, f64)>, frac: f64) -> (f64, f64) {
    let Some((lo, hi)) = r else {
        return (0.0, 1.0);
    };
    let scale = lo.abs().max(hi.abs());
    if hi - lo <= scale * 1e-9 || hi - lo < 1e-250 {
        let c = 0.5 * (lo + hi);
        let half = if c.abs() < 1e-250 { 1.0 } else { c.abs() * 0.1 };
        return (c - half, c + half);
    }
    let pad = (hi - lo) * frac;
    (lo - pad, hi + pad)
}

/// How tick values are turned into text.
#[derive(Clone, Copy, Debug)]
enum TickFormat {
    /// `value / 10^exp` with fixed decimals, suffixed `e{exp}` when `exp != 0`.
    Fixed { exp: i32, decimals: usize },
    /// Up to 3 significant digits, exponent form for very large/small values.
    General,
    /// The tick is `log10(value)`: print `10^tick` in general form.
    Log10,
}

impl TickFormat {
    /// Chooses a consistent format for evenly spaced `ticks` with spacing `step`.
    fn for_ticks(ticks: &[f64], step: f64) -> TickFormat {
        if !(step > 0.0 && step.is_finite()) {
            return TickFormat::General;
        }
        let max_abs = ticks.iter().fold(0.0f64, |m, t| m.max(t.abs()));
        let exp = if max_abs >= 1e4 || (max_abs > 0.0 && max_abs < 1e-2) {
            (max_abs.log10() / 3.0).floor() as i32 * 3
        } else {
            0
        };
        let scaled_step = step / 10f64.powi(exp);
        let decimals = (-scaled_step.log10() - 1e-9).ceil().clamp(0.0, 9.0) as usize;
        TickFormat::Fixed { exp, decimals }
    }

    fn format(&self, v: f64) -> String {
        match *self {
            TickFormat::Fixed { exp, decimals } => {
                let m = v / 10f64.powi(exp);
                let s = format!("{m:.decimals$}");
                if s.trim_start_matches('-')
                    .chars()
                    .all(|c| c == '0' || c == '.')
                {
                    "0".to_string()
                } else if exp == 0 {
                    s
                } else {
                    format!("{s}e{exp}")
                }
            }
            TickFormat::General => fmt_general(v),
            TickFormat::Log10 => fmt_general(10f64.powf(v)),
        }
    }
}

/// Up to 3 significant digits without trailing zeros; exponent form outside `[1e-3, 1e5)`.
fn fmt_general(v: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    let a = v.abs();
    if a < 1e-300 {
        return "0".into();
    }
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.2e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = trim_zeros(m);
        return format!("{m}e{e}");
    }
    let decimals = (2 - a.log10().floor() as i32).clamp(0, 6) as usize;
    trim_zeros(&format!("{v:.decimals$}")).to_string()
}

fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// At most `max_n` (≥ 2) evenly spaced nice ticks inside `[lo, hi]`, and their spacing.
fn linear_ticks(lo: f64, hi: f64, max_n: usize) -> (Vec<f64>, f64) {
    let max_n = max_n.max(2);
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite()) {
        return (vec![lo], 0.0);
    }
    // The smallest 1-2-5 step that gives at most `max_n` ticks (and at least 2 if possible).
    let mag = 10f64.powf((span / (max_n as f64 * 2.0)).log10().floor());
    let mut chosen = None;
    for m in [1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0] {
        let step = mag * m;
        let k0 = (lo / step - 1e-9).ceil();
        let k1 = (hi / step + 1e-9).floor();
        if !(step > 0.0 && step.is_finite() && k0.is_finite() && k1.is_finite()) {
            break;
        }
        if k1 - k0 + 1.0 <= max_n as f64 {
            chosen = Some((step, k0, k1));
            break;
        }
    }
    let Some((step, k0, k1)) = chosen else {
        return (vec![lo, hi], span);
    };
    if k1 < k0 || k1 - k0 > 1000.0 {
        return (vec![lo, hi], span);
    }
    let ticks = (0..=(k1 - k0) as i64)
        .map(|i| {
            let v = (k0 + i as f64) * step;
            if v.abs() < step * 1e-9 { 0.0 } else { v }
        })
        .filter(|v| *v >= lo - step * 1e-6 && *v <= hi + step * 1e-6)
        .collect();
    (ticks, step)
}

/// Ticks for an axis whose coordinate is `log10(value)` over `[lo, hi]` (in log10 units).
fn log_ticks(lo: f64, hi: f64, max_n: usize) -> Vec<f64> {
    let max_n = max_n.max(2);
    let (d0, d1) = (lo.floor() as i64 - 1, hi.ceil() as i64 + 1);
    let pick = |mantissas: &[f64], every: i64| -> Vec<f64> {
        let mut out = Vec::new();
        for d in d0..=d1 {
            if d.rem_euclid(every) != 0 {
                continue;
            }
            for m in mantissas {
                let t = m.log10() + d as f64;
                if t >= lo - 1e-9 && t <= hi + 1e-9 {
                    out.push(t);
                }
            }
        }
        out
    };
    let dense = pick(&[1.0, 2.0, 5.0], 1);
    if dense.len() <= max_n && dense.len() >= 2 {
        return dense;
    }
    if dense.len() > max_n {
        for every in [1, 2, 3, 5, 10, 20, 50, 100] {
            let sparse = pick(&[1.0], every);
            if sparse.len() <= max_n {
                return sparse;
            }
        }
        return vec![lo, hi];
    }
    // Less than a decade: nice linear ticks in value space.
    let (vt, _) = linear_ticks(10f64.powf(lo), 10f64.powf(hi), max_n);
    let t: Vec<f64> = vt
        .into_iter()
        .filter(|v| *v > 0.0)
        .map(f64::log10)
        .collect();
    if t.len() >= 2 { t } else { vec![lo, hi] }
}

/// One axis: its range (in plot coordinates), tick positions and label format.
#[derive(Clone, Debug)]
struct Axis {
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
    fmt: TickFormat,
}

impl Axis {
    fn linear(lo: f64, hi: f64, max_ticks: usize) -> Axis {
        let (ticks, step) = linear_ticks(lo, hi, max_ticks);
        let fmt = TickFormat::for_ticks(&ticks, step);
        Axis { lo, hi, ticks, fmt }
    }

    fn log(lo: f64, hi: f64, max_ticks: usize) -> Axis {
        Axis {
            lo,
            hi,
            ticks: log_ticks(lo, hi, max_ticks),
            fmt: TickFormat::Log10,
        }
    }

    /// An axis over `pixels` pixels with as many ticks as fit legibly with `size` labels.
    fn fit(lo: f64, hi: f64, log: bool, pixels: i32, size: f64, horizontal: bool) -> Axis {
        let make = |n: usize| {
            if log {
                Axis::log(lo, hi, n)
            } else {
                Axis::linear(lo, hi, n)
            }
        };
        let pixels = pixels.max(1) as f64;
        if !horizontal {
            let n = (pixels / (size * 2.4)) as usize + 1;
            return make(n.clamp(2, 12));
        }
        let mut n = ((pixels / (size * 2.5)) as usize + 1).clamp(2, 15);
        loop {
            let axis = make(n);
            let w = axis.max_label_width(size) as f64 + size * 1.5;
            if n <= 2 || axis.ticks.len() as f64 * w <= pixels {
                return axis;
            }
            n -= 1;
        }
    }

    fn coord(&self) -> TickCoord {
        TickCoord {
            lo: self.lo,
            hi: self.hi,
            ticks: self.ticks.clone(),
        }
    }

    fn labels(&self) -> impl Iterator<Item = String> + '_ {
        self.ticks.iter().map(|t| self.fmt.format(*t))
    }

    /// Clamps a plot coordinate into the axis range (so nothing is drawn far outside).
    fn clamp(&self, v: f64) -> f64 {
        v.clamp(self.lo, self.hi)
    }

    fn max_label_width(&self, size: f64) -> i32 {
        self.labels()
            .map(|s| text_size(&s, size).0)
            .max()
            .unwrap_or(0)
    }
}

const TICK_MARK: i32 = 5;

/// A linear plotters coordinate whose tick marks / grid lines are exactly the given ticks.
#[derive(Clone)]
struct TickCoord {
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
}

impl Ranged for TickCoord {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let span = self.hi - self.lo;
        if span.is_nan() || span <= 0.0 || span.is_infinite() {
            return (limit.0 + limit.1) / 2;
        }
        let frac = ((*v - self.lo) / span).clamp(-1.0, 2.0);
        let frac = if frac.is_finite() { frac } else { 0.5 };
        let len = (limit.1 - limit.0) as f64;
        limit.0 + (len * frac).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
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

// ---------------------------------------------------------------------------------------------
// Stacked figure
// ---------------------------------------------------------------------------------------------

struct LegendEntry {
    label: String,
    color: RGBColor,
    dashed: bool,
    width: i32,
}

struct PanelPrep {
    title: String,
    y_label: String,
    y: Axis,
    /// Per series: colour, dashed?, finite segments (already clamped into the axes).
    lines: Vec<(RGBColor, bool, Segments)>,
    /// Rows of legend entries (empty when the panel has at most one series).
    legend_rows: Vec<Vec<LegendEntry>>,
    /// Whether the first legend row shares the line with the title.
    legend_on_title_line: bool,
    header_h: i32,
}

struct FigurePrep {
    title: String,
    x_label: String,
    fonts: Fonts,
    x: Axis,
    panels: Vec<PanelPrep>,
    title_h: i32,
    y_area_w: i32,
    x_area_h: i32,
    right_margin: i32,
    panel_h: Vec<i32>,
}

/// Runs of consecutive finite points of one series.
type Segments = Vec<Vec<(f64, f64)>>;

/// Splits a series into runs of consecutive finite points.
fn segments(s: &Series) -> Segments {
    let mut out = Vec::new();
    let mut cur = Vec::new();
    for (&x, &y) in s.x.iter().zip(s.y.iter()) {
        if x.is_finite() && y.is_finite() {
            cur.push((x.clamp(-BIG, BIG), y.clamp(-BIG, BIG)));
        } else if !cur.is_empty() {
            out.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

const LEGEND_SAMPLE: i32 = 34;
const LEGEND_GAP: i32 = 8;
const LEGEND_SEP: i32 = 22;

impl FigurePrep {
    fn new(fig: &Figure) -> FigurePrep {
        let fonts = Fonts::for_size(fig.width, fig.height);
        let (w, h) = (fig.width as i32, fig.height as i32);
        let segs: Vec<Vec<Segments>> = fig
            .panels
            .iter()
            .map(|p| p.series.iter().map(segments).collect())
            .collect();
        let all_points = || segs.iter().flatten().flatten().flatten();

        // Shared x axis: tight to the data.
        let (xlo, xhi) = pad_range(finite_range(all_points().map(|p| p.0)), 0.0);
        let right_margin = (fonts.tick * 2.0) as i32;

        let title_h = if fig.title.is_empty() {
            (fonts.tick * 0.8) as i32
        } else {
            (fonts.title * 2.0) as i32
        };
        let (_, tick_h) = text_size("0123456789", fonts.tick);
        let (_, desc_h) = text_size("Ag", fonts.desc);
        let x_area_h = 2 * TICK_MARK
            + tick_h
            + if fig.x_label.is_empty() {
                TICK_MARK
            } else {
                desc_h + 2 * TICK_MARK
            };
        let line_h = (fonts.panel.max(fonts.legend) * 1.6) as i32;

        // First pass: y axes (need plot heights for tick counts, which need header heights,
        // which need the y-label width). Estimate the plot width with a provisional label area.
        let provisional_plot_w = (w - 90 - right_margin).max(10);
        let mut panels: Vec<PanelPrep> = fig
            .panels
            .iter()
            .zip(&segs)
            .map(|(p, psegs)| {
                let (ylo, yhi) = pad_range(
                    finite_range(psegs.iter().flatten().flatten().map(|q| q.1)),
                    0.06,
                );
                let lines = p
                    .series
                    .iter()
                    .zip(psegs)
                    .enumerate()
                    .map(|(i, (s, sg))| {
                        (
                            PALETTE[i % PALETTE.len()],
                            s.style == LineStyle::Dashed,
                            sg.clone(),
                        )
                    })
                    .collect();
                let entries: Vec<LegendEntry> = if p.series.len() > 1 {
                    p.series
                        .iter()
                        .enumerate()
                        .map(|(i, s)| LegendEntry {
                            label: s.label.to_string(),
                            color: PALETTE[i % PALETTE.len()],
                            dashed: s.style == LineStyle::Dashed,
                            width: LEGEND_SAMPLE + LEGEND_GAP + text_size(s.label, fonts.legend).0,
                        })
                        .collect()
                } else {
                    Vec::new()
                };
                let (rows, on_title) = layout_legend(
                    entries,
                    text_size(p.title, fonts.panel).0,
                    provisional_plot_w,
                );
                let title_rows = i32::from(!p.title.is_empty() || on_title);
                let extra_rows = rows.len() as i32 - i32::from(on_title);
                let header_h = if title_rows + extra_rows == 0 {
                    (fonts.tick * 0.8) as i32
                } else {
                    (title_rows + extra_rows) * line_h
                };
                PanelPrep {
                    title: p.title.to_string(),
                    y_label: p.y_label.to_string(),
                    y: Axis::linear(ylo, yhi, 2),
                    lines,
                    legend_rows: rows,
                    legend_on_title_line: on_title,
                    header_h,
                }
            })
            .collect();

        // Vertical layout: equal plot heights; the bottom panel also carries the x axis.
        let n = panels.len() as i32;
        let gap = (fonts.tick * 0.6) as i32;
        let headers: i32 = panels.iter().map(|p| p.header_h).sum();
        let plot_h = ((h - title_h - headers - x_area_h - gap * (n - 1) - 4) / n).max(1);
        for (p, psegs) in panels.iter_mut().zip(&segs) {
            let (ylo, yhi) = pad_range(
                finite_range(psegs.iter().flatten().flatten().map(|q| q.1)),
                0.06,
            );
            p.y = Axis::fit(ylo, yhi, false, plot_h, fonts.tick, false);
        }
        let mut panel_h: Vec<i32> = panels.iter().map(|p| p.header_h + plot_h + gap).collect();
        if let Some(last) = panel_h.last_mut() {
            *last = *last - gap + x_area_h;
        }

        // Left label area: widest tick label over all panels (aligned plot areas) + rotated label.
        let max_tick_w = panels
            .iter()
            .map(|p| p.y.max_label_width(fonts.tick))
            .max()
            .unwrap_or(0);
        let any_y_label = panels.iter().any(|p| !p.y_label.is_empty());
        let y_area_w = 2 * TICK_MARK
            + max_tick_w
            + TICK_MARK
            + if any_y_label {
                desc_h + 2 * TICK_MARK
            } else {
                0
            };

        // Re-layout legends with the real plot width.
        let plot_w = (w - y_area_w - right_margin).max(10);
        for (p, fp) in panels.iter_mut().zip(&fig.panels) {
            let entries: Vec<LegendEntry> = p.legend_rows.drain(..).flatten().collect();
            let (rows, on_title) =
                layout_legend(entries, text_size(fp.title, fonts.panel).0, plot_w);
            p.legend_rows = rows;
            p.legend_on_title_line = on_title;
        }

        FigurePrep {
            title: fig.title.to_string(),
            x_label: fig.x_label.to_string(),
            fonts,
            x: Axis::fit(xlo, xhi, false, plot_w, fonts.tick, true),
            panels,
            title_h,
            y_area_w,
            x_area_h,
            right_margin,
            panel_h,
        }
    }
}

/// Lays legend entries out in rows no wider than `avail`. Returns the rows and whether the
/// first row fits on the title line (right of a title `title_w` wide).
fn layout_legend(
    entries: Vec<LegendEntry>,
    title_w: i32,
    avail: i32,
) -> (Vec<Vec<LegendEntry>>, bool) {
    if entries.is_empty() {
        return (Vec::new(), false);
    }
    let total: i32 =
        entries.iter().map(|e| e.width).sum::<i32>() + LEGEND_SEP * (entries.len() as i32 - 1);
    if title_w + 3 * LEGEND_SEP + total <= avail {
        return (vec![entries], true);
    }
    let mut rows: Vec<Vec<LegendEntry>> = Vec::new();
    let mut cur: Vec<LegendEntry> = Vec::new();
    let mut cur_w = 0;
    for e in entries {
        let add = if cur.is_empty() {
            e.width
        } else {
            LEGEND_SEP + e.width
        };
        if !cur.is_empty() && cur_w + add > avail {
            rows.push(std::mem::take(&mut cur));
            cur_w = e.width;
        } else {
            cur_w += add;
        }
        cur.push(e);
    }
    rows.push(cur);
    (rows, false)
}

/// White background and the centred title; returns the picture size in pixels.
fn start_picture<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    f: Fonts,
    title_h: i32,
) -> Result<(i32, i32), PlotError> {
    root.fill(&WHITE).map_err(draw_err)?;
    let (w, h) = root.dim_in_pixel();
    let (w, h) = (w as i32, h as i32);
    if !title.is_empty() {
        let style = font(f.title)
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Center));
        root.draw_text(title, &style, (w / 2, title_h / 2))
            .map_err(draw_err)?;
    }
    Ok((w, h))
}

impl Render for FigurePrep {
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        bitmap: bool,
    ) -> Result<(), PlotError> {
        let f = self.fonts;
        let (_, h) = start_picture(root, &self.title, f, self.title_h)?;

        // Panel areas.
        let mut breaks = Vec::with_capacity(self.panels.len() + 1);
        let mut y = self.title_h;
        breaks.push(y.min(h));
        for ph in &self.panel_h {
            y += ph;
            breaks.push(y.min(h));
        }
        let areas = root.split_by_breakpoints::<i32, i32, _, _>([], breaks);
        // areas[0] is the title band; the last one is whatever is left at the bottom.
        let last = self.panels.len() - 1;
        for (i, (p, area)) in self.panels.iter().zip(areas.iter().skip(1)).enumerate() {
            self.render_panel(root, p, area, i == last, bitmap)?;
        }
        Ok(())
    }
}

impl FigurePrep {
    fn render_panel<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        p: &PanelPrep,
        area: &DrawingArea<DB, Shift>,
        bottom: bool,
        bitmap: bool,
    ) -> Result<(), PlotError> {
        let f = self.fonts;
        let (aw, ah) = area.dim_in_pixel();
        let header_h = p.header_h.min(ah as i32);
        let (header, body) = area.split_vertically(header_h);
        let plot_left = self.y_area_w;
        let plot_right = aw as i32 - self.right_margin;
        let line_h = if p.legend_rows.len() + usize::from(!p.legend_on_title_line) > 1 {
            header_h / (p.legend_rows.len() as i32 + i32::from(!p.legend_on_title_line)).max(1)
        } else {
            header_h
        };

        // Header: title on the left, legend (horizontal, right-aligned) on the right.
        if !p.title.is_empty() {
            let style = font(f.panel)
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center));
            header
                .draw_text(&p.title, &style, (plot_left, line_h / 2 + 2))
                .map_err(draw_err)?;
        }
        let first_row_line = if p.legend_on_title_line { 0 } else { 1 };
        for (r, row) in p.legend_rows.iter().enumerate() {
            let cy = (first_row_line + r as i32) * line_h + line_h / 2 + 2;
            let row_w: i32 =
                row.iter().map(|e| e.width).sum::<i32>() + LEGEND_SEP * (row.len() as i32 - 1);
            let mut x = plot_right - row_w;
            for e in row {
                let (bx, by) = header.get_base_pixel();
                let pts = [
                    ((bx + x) as f64, (by + cy) as f64),
                    ((bx + x + LEGEND_SAMPLE) as f64, (by + cy) as f64),
                ];
                draw_polyline(root, &pts, e.color, e.dashed, bitmap)?;
                let ts = font(f.legend)
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Left, VPos::Center));
                header
                    .draw_text(&e.label, &ts, (x + LEGEND_SAMPLE + LEGEND_GAP, cy))
                    .map_err(draw_err)?;
                x += e.width + LEGEND_SEP;
            }
        }

        // Body: the chart.
        let x_area = if bottom { self.x_area_h } else { 0 };
        let mut cb = ChartBuilder::on(&body);
        cb.margin_right(self.right_margin as u32)
            .set_label_area_size(LabelAreaPosition::Left, self.y_area_w as u32);
        if bottom {
            cb.set_label_area_size(LabelAreaPosition::Bottom, x_area as u32);
        } else {
            cb.margin_bottom(self.fonts.tick as u32 * 6 / 10);
        }
        let mut chart = cb
            .build_cartesian_2d(self.x.coord(), p.y.coord())
            .map_err(draw_err)?;
        let xf = self.x.fmt;
        let yf = p.y.fmt;
        let x_fmt = move |v: &f64| xf.format(*v);
        let y_fmt = move |v: &f64| yf.format(*v);
        let mut mesh = chart.configure_mesh();
        mesh.bold_line_style(GRID)
            .light_line_style(TRANSPARENT)
            .axis_style(AXIS)
            .set_all_tick_mark_size(TICK_MARK)
            .label_style(font(f.tick).color(&AXIS))
            .axis_desc_style(font(f.desc).color(&BLACK))
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt);
        if bottom && !self.x_label.is_empty() {
            mesh.x_desc(self.x_label.as_str());
        }
        mesh.draw().map_err(draw_err)?;
        let (_, yr) = chart.plotting_area().get_pixel_range();
        let (_, desc_h) = text_size("Ag", f.desc);
        let x0 = body.get_base_pixel().0;
        draw_vertical_label(
            root,
            &p.y_label,
            f.desc,
            (x0 + 2 * TICK_MARK + desc_h / 2, (yr.start + yr.end) / 2),
        )?;

        // Zero line when the range spans zero (helps reading signed responses).
        if p.y.lo < 0.0 && p.y.hi > 0.0 {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(self.x.lo, 0.0), (self.x.hi, 0.0)],
                    ShapeStyle::from(&RGBColor(160, 160, 160)).stroke_width(1),
                )))
                .map_err(draw_err)?;
        }

        for (color, dashed, segs) in &p.lines {
            for seg in segs {
                let px: Vec<(f64, f64)> = seg
                    .iter()
                    .map(|&(x, y)| {
                        let (u, v) = chart.backend_coord(&(self.x.clamp(x), p.y.clamp(y)));
                        (u as f64, v as f64)
                    })
                    .collect();
                draw_polyline(root, &px, *color, *dashed, bitmap)?;
            }
        }

        frame(chart.plotting_area())?;
        Ok(())
    }
}

/// Draws `text` rotated to read bottom-to-top, centred at `center` (absolute pixels).
fn draw_vertical_label<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    text: &str,
    size: f64,
    center: (i32, i32),
) -> Result<(), PlotError> {
    if text.is_empty() {
        return Ok(());
    }
    let style = font(size)
        .transform(FontTransform::Rotate270)
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Center));
    root.draw_text(text, &style, center).map_err(draw_err)
}

const LINE_WIDTH: u32 = 2;
const DASH_ON: f64 = 9.0;
const DASH_OFF: f64 = 5.0;

/// Splits a pixel-space polyline into dashes.
fn dash_pieces(pts: &[(f64, f64)], on: f64, off: f64) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let Some(&first) = pts.first() else {
        return out;
    };
    let mut cur = vec![first];
    let mut drawing = true;
    let mut left = on;
    for w in pts.windows(2) {
        let (mut a, b) = (w[0], w[1]);
        let mut d = (b.0 - a.0).hypot(b.1 - a.1);
        while d > 0.0 {
            if d <= left {
                left -= d;
                if drawing {
                    cur.push(b);
                }
                break;
            }
            let t = left / d;
            let p = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
            if drawing {
                cur.push(p);
                out.push(std::mem::take(&mut cur));
            } else {
                cur = vec![p];
            }
            d -= left;
            a = p;
            drawing = !drawing;
            left = if drawing { on } else { off };
        }
    }
    if drawing && cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// Draws a line through pixel-space points (absolute coordinates on `root`).
///
/// For bitmaps every segment is drawn on its own: plotters renders thick bitmap polylines with
/// unlimited miter joins, which would shoot long spikes out of sharp peaks (contact forces).
fn draw_polyline<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    pts: &[(f64, f64)],
    color: RGBColor,
    dashed: bool,
    bitmap: bool,
) -> Result<(), PlotError> {
    let style = ShapeStyle::from(&color).stroke_width(LINE_WIDTH);
    if pts.len() == 1 {
        let c = (pts[0].0.round() as i32, pts[0].1.round() as i32);
        return root
            .draw(&Circle::new(c, LINE_WIDTH as i32, style.filled()))
            .map_err(draw_err);
    }
    let pieces = if dashed {
        dash_pieces(pts, DASH_ON, DASH_OFF)
    } else {
        vec![pts.to_vec()]
    };
    for piece in pieces {
        let mut ip: Vec<(i32, i32)> = piece
            .iter()
            .map(|&(x, y)| (x.round() as i32, y.round() as i32))
            .collect();
        ip.dedup();
        if ip.len() < 2 {
            continue;
        }
        if bitmap {
            for w in ip.windows(2) {
                root.draw(&PathElement::new(vec![w[0], w[1]], style))
                    .map_err(draw_err)?;
            }
        } else {
            root.draw(&PathElement::new(ip, style)).map_err(draw_err)?;
        }
    }
    Ok(())
}

/// Draws a thin frame around a chart's plotting area.
fn frame<DB: DrawingBackend, CT: CoordTranslate>(
    area: &DrawingArea<DB, CT>,
) -> Result<(), PlotError> {
    let plain = area.strip_coord_spec();
    let (w, h) = plain.dim_in_pixel();
    if w < 2 || h < 2 {
        return Ok(());
    }
    plain
        .draw(&Rectangle::new(
            [(0, 0), (w as i32 - 1, h as i32 - 1)],
            ShapeStyle::from(&AXIS).stroke_width(1),
        ))
        .map_err(draw_err)
}

// ---------------------------------------------------------------------------------------------
// Heatmap
// ---------------------------------------------------------------------------------------------

/// One heatmap axis: grid order, cell edges (plot coordinates), and the drawn axis.
struct GridAxis {
    /// Original indices of the finite grid values, sorted by value.
    order: Vec<usize>,
    /// `order.len() + 1` cell edges in plot coordinates.
    edges: Vec<f64>,
    axis: Axis,
}

impl GridAxis {
    fn new(
        values: &[f64],
        what: &str,
        pixels: i32,
        tick_font: f64,
        horizontal: bool,
    ) -> Result<GridAxis, PlotError> {
        let mut order: Vec<usize> = (0..values.len())
            .filter(|&i| values[i].is_finite())
            .collect();
        if order.is_empty() {
            return Err(PlotError::NoData(format!(
                "the {what} grid has no finite value"
            )));
        }
        order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
        let v: Vec<f64> = order.iter().map(|&i| values[i].clamp(-BIG, BIG)).collect();
        let log = is_geometric(&v);
        let t: Vec<f64> = if log {
            v.iter().map(|x| x.log10()).collect()
        } else {
            v.clone()
        };
        let n = t.len();
        let (first, last) = (t[0], t[n - 1]);
        let mut edges = Vec::with_capacity(n + 1);
        if last - first <= (first.abs().max(last.abs())) * 1e-12 {
            // One value (or all equal): a single cell width around it; repeated values get
            // zero-width cells except the last.
            let (lo, hi) = if log {
                (first - 0.5, first + 0.5)
            } else {
                pad_range(Some((first, first)), 0.0)
            };
            edges.extend(std::iter::repeat_n(lo, n));
            edges.push(hi);
        } else {
            edges.push(t[0] - 0.5 * (t[1] - t[0]));
            for i in 1..n {
                edges.push(0.5 * (t[i - 1] + t[i]));
            }
            edges.push(t[n - 1] + 0.5 * (t[n - 1] - t[n - 2]));
        }
        let (lo, hi) = (edges[0], edges[n]);
        let axis = Axis::fit(lo, hi, log, pixels, tick_font, horizontal);
        Ok(GridAxis { order, edges, axis })
    }
}

/// True if the (sorted, finite) values are positive, span at least a factor of 10 and are more
/// evenly spaced in log than in linear terms.
fn is_geometric(v: &[f64]) -> bool {
    if v.len() < 3 || v[0] <= 0.0 || v[v.len() - 1] / v[0] < 10.0 {
        return false;
    }
    fn spread(d: &[f64]) -> f64 {
        let (mn, mx) = d
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        if mn > 0.0 { mx / mn } else { f64::INFINITY }
    }
    let lin: Vec<f64> = v.windows(2).map(|w| w[1] - w[0]).collect();
    let lg: Vec<f64> = v.windows(2).map(|w| w[1].log10() - w[0].log10()).collect();
    spread(&lg) < spread(&lin)
}

/// Maps values to colours.
#[derive(Clone, Copy)]
enum ColorMap {
    /// Viridis over `[lo, hi]`.
    Sequential { lo: f64, hi: f64 },
    /// Blue–white–red with white at 0; `[lo, 0]` and `[0, hi]` are each stretched to a half.
    Diverging { lo: f64, hi: f64 },
}

impl ColorMap {
    fn color(&self, z: f64) -> RGBColor {
        if !z.is_finite() {
            return NAN_GREY;
        }
        match *self {
            ColorMap::Sequential { lo, hi } => lerp_table(&VIRIDIS, (z - lo) / (hi - lo)),
            ColorMap::Diverging { lo, hi } => {
                let t = if z < 0.0 {
                    0.5 - 0.5 * (z / lo)
                } else {
                    0.5 + 0.5 * (z / hi)
                };
                lerp_table(&BLUE_WHITE_RED, t)
            }
        }
    }
}

struct HeatPrep {
    title: String,
    x_label: String,
    y_label: String,
    z_label: String,
    fonts: Fonts,
    gx: GridAxis,
    gy: GridAxis,
    /// Cell values in sorted-grid order: `cells[j * nx + i]`.
    cells: Vec<f64>,
    any_missing: bool,
    cmap: ColorMap,
    zaxis: Axis,
    title_h: i32,
    y_area_w: i32,
    x_area_h: i32,
    cbar_w: i32,
    cbar_label_w: i32,
}

const CBAR_GAP: i32 = 24;
const CBAR_BAR: i32 = 26;
const MISSING_LABEL: &str = "no data";

impl HeatPrep {
    fn new(h: &Heatmap) -> Result<HeatPrep, PlotError> {
        if h.x.is_empty() || h.y.is_empty() {
            return Err(PlotError::NoData("the heatmap grid is empty".into()));
        }
        let expect = h.x.len().checked_mul(h.y.len());
        if expect != Some(h.z.len()) {
            return Err(PlotError::InvalidInput(format!(
                "heatmap z has {} values, expected x.len() * y.len() = {} * {}",
                h.z.len(),
                h.x.len(),
                h.y.len()
            )));
        }
        let fonts = Fonts::for_size(h.width, h.height);
        let (w, hh) = (h.width as i32, h.height as i32);
        let title_h = if h.title.is_empty() {
            (fonts.tick * 0.8) as i32
        } else {
            (fonts.title * 2.0) as i32
        };
        let (_, tick_h) = text_size("0123456789", fonts.tick);
        let (_, desc_h) = text_size("Ag", fonts.desc);
        let x_area_h = 2 * TICK_MARK + tick_h + desc_h + 3 * TICK_MARK;

        // z range and colour map.
        let zr = finite_range(h.z.iter().copied());
        let cmap_range = pad_range(zr, 0.0);
        let (cmap, (zlo, zhi)) = match zr {
            Some((lo, hi)) if lo < 0.0 && hi > 0.0 => (ColorMap::Diverging { lo, hi }, (lo, hi)),
            _ => (
                ColorMap::Sequential {
                    lo: cmap_range.0,
                    hi: cmap_range.1,
                },
                cmap_range,
            ),
        };
        let plot_h_est = (hh - title_h - x_area_h - 10).max(10);
        let zaxis = Axis::fit(zlo, zhi, false, plot_h_est, fonts.tick, false);

        // Colour bar: gap, bar, ticks, rotated label; wide enough for the "no data" swatch.
        let cbar_label_w = 2 * TICK_MARK
            + zaxis.max_label_width(fonts.tick)
            + TICK_MARK
            + if h.z_label.is_empty() {
                0
            } else {
                desc_h + 2 * TICK_MARK
            };
        let missing_w = CBAR_BAR + TICK_MARK + text_size(MISSING_LABEL, fonts.tick).0;
        let right_margin = (fonts.tick * 1.2) as i32;
        let cbar_w = CBAR_GAP + (CBAR_BAR + cbar_label_w).max(missing_w) + right_margin;

        // y axis first with an estimate of its label width, then x.
        let gy = GridAxis::new(h.y, "y", plot_h_est, fonts.tick, false)?;
        let y_area_w = 2 * TICK_MARK
            + gy.axis.max_label_width(fonts.tick)
            + TICK_MARK
            + if h.y_label.is_empty() {
                0
            } else {
                desc_h + 2 * TICK_MARK
            };
        let plot_w = (w - cbar_w - y_area_w).max(10);
        let gx = GridAxis::new(h.x, "x", plot_w, fonts.tick, true)?;

        let nx = h.x.len();
        let cells: Vec<f64> = gy
            .order
            .iter()
            .flat_map(|&iy| gx.order.iter().map(move |&ix| h.z[iy * nx + ix]))
            .collect();
        let any_missing = cells.iter().any(|z| !z.is_finite());

        Ok(HeatPrep {
            title: h.title.to_string(),
            x_label: h.x_label.to_string(),
            y_label: h.y_label.to_string(),
            z_label: h.z_label.to_string(),
            fonts,
            gx,
            gy,
            cells,
            any_missing,
            cmap,
            zaxis,
            title_h,
            y_area_w,
            x_area_h,
            cbar_w,
            cbar_label_w,
        })
    }
}

impl Render for HeatPrep {
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _bitmap: bool,
    ) -> Result<(), PlotError> {
        let f = self.fonts;
        let (w, h) = start_picture(root, &self.title, f, self.title_h)?;
        let (_, body) = root.split_vertically(self.title_h.min(h));
        let (main, bar) = body.split_horizontally((w - self.cbar_w).max(1));
        let top_margin = (f.tick * 0.6) as u32;

        // Main chart.
        let (xa, ya) = (&self.gx.axis, &self.gy.axis);
        let mut chart = ChartBuilder::on(&main)
            .margin_top(top_margin)
            .set_label_area_size(LabelAreaPosition::Left, self.y_area_w as u32)
            .set_label_area_size(LabelAreaPosition::Bottom, self.x_area_h as u32)
            .build_cartesian_2d(xa.coord(), ya.coord())
            .map_err(draw_err)?;
        let nx = self.gx.order.len();
        let rects = self.cells.iter().enumerate().map(|(k, &z)| {
            let (i, j) = (k % nx, k / nx);
            let (ex, ey) = (&self.gx.edges, &self.gy.edges);
            Rectangle::new(
                [(ex[i], ey[j]), (ex[i + 1], ey[j + 1])],
                self.cmap.color(z).filled(),
            )
        });
        chart.draw_series(rects).map_err(draw_err)?;
        let (xf, yf) = (xa.fmt, ya.fmt);
        let x_fmt = move |v: &f64| xf.format(*v);
        let y_fmt = move |v: &f64| yf.format(*v);
        let mut mesh = chart.configure_mesh();
        mesh.disable_x_mesh()
            .disable_y_mesh()
            .axis_style(AXIS)
            .set_all_tick_mark_size(TICK_MARK)
            .label_style(font(f.tick).color(&AXIS))
            .axis_desc_style(font(f.desc).color(&BLACK))
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt);
        if !self.x_label.is_empty() {
            mesh.x_desc(self.x_label.as_str());
        }
        mesh.draw().map_err(draw_err)?;
        frame(chart.plotting_area())?;
        let (_, desc_h) = text_size("Ag", f.desc);
        let (_, yr) = chart.plotting_area().get_pixel_range();
        let y_mid = (yr.start + yr.end) / 2;
        draw_vertical_label(
            root,
            &self.y_label,
            f.desc,
            (2 * TICK_MARK + desc_h / 2, y_mid),
        )?;

        // Colour bar, vertically aligned with the plot area.
        let (bw, bh) = bar.dim_in_pixel();
        let bar_right = (bw as i32 - CBAR_GAP - CBAR_BAR - self.cbar_label_w).max(0);
        let z = &self.zaxis;
        let mut cbar = ChartBuilder::on(&bar)
            .margin_top(top_margin)
            .margin_left(CBAR_GAP as u32)
            .margin_right(bar_right as u32)
            .margin_bottom(self.x_area_h as u32)
            .set_label_area_size(LabelAreaPosition::Right, self.cbar_label_w as u32)
            .build_cartesian_2d(
                TickCoord {
                    lo: 0.0,
                    hi: 1.0,
                    ticks: Vec::new(),
                },
                z.coord(),
            )
            .map_err(draw_err)?;
        let steps = 200;
        let span = z.hi - z.lo;
        cbar.draw_series((0..steps).map(|k| {
            let a = z.lo + span * k as f64 / steps as f64;
            let b = z.lo + span * (k + 1) as f64 / steps as f64;
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                self.cmap.color(0.5 * (a + b)).filled(),
            )
        }))
        .map_err(draw_err)?;
        let zf = z.fmt;
        let z_fmt = move |v: &f64| zf.format(*v);
        let mut mesh = cbar.configure_mesh();
        mesh.disable_x_mesh()
            .disable_y_mesh()
            .axis_style(AXIS)
            .set_all_tick_mark_size(TICK_MARK)
            .label_style(font(f.tick).color(&AXIS))
            .axis_desc_style(font(f.desc).color(&BLACK))
            .y_label_formatter(&z_fmt);
        mesh.draw().map_err(draw_err)?;
        frame(cbar.plotting_area())?;
        let (xr, _) = cbar.plotting_area().get_pixel_range();
        draw_vertical_label(
            root,
            &self.z_label,
            f.desc,
            (
                xr.end + self.cbar_label_w - 2 * TICK_MARK - desc_h / 2,
                y_mid,
            ),
        )?;

        // "No data" swatch under the colour bar.
        if self.any_missing {
            let y0 = bh as i32 - self.x_area_h + 2 * TICK_MARK + 4;
            let sw = (f.tick * 1.1) as i32;
            bar.draw(&Rectangle::new(
                [(CBAR_GAP, y0), (CBAR_GAP + CBAR_BAR, y0 + sw)],
                NAN_GREY.filled(),
            ))
            .map_err(draw_err)?;
            bar.draw(&Rectangle::new(
                [(CBAR_GAP, y0), (CBAR_GAP + CBAR_BAR, y0 + sw)],
                ShapeStyle::from(&AXIS).stroke_width(1),
            ))
            .map_err(draw_err)?;
            let style = font(f.tick)
                .color(&AXIS)
                .pos(Pos::new(HPos::Left, VPos::Center));
            bar.draw_text(
                MISSING_LABEL,
                &style,
                (CBAR_GAP + CBAR_BAR + TICK_MARK, y0 + sw / 2),
            )
            .map_err(draw_err)?;
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    fn temp_dir(tag: &str) -> PathBuf {
        static N: AtomicUsize = AtomicUsize::new(0);
        let d = std::env::temp_dir().join(format!(
            "pounding-plot-test-{}-{}-{}",
            std::process::id(),
            tag,
            N.fetch_add(1, Ordering::SeqCst)
        ));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn png_size(path: &Path) -> (u32, u32) {
        let b = std::fs::read(path).unwrap();
        assert_eq!(&b[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
        let w = u32::from_be_bytes(b[16..20].try_into().unwrap());
        let h = u32::from_be_bytes(b[20..24].try_into().unwrap());
        (w, h)
    }

    fn check_outputs(dir: &Path, paths: &[PathBuf], w: u32, h: u32, title: &str) {
        assert_eq!(paths.len(), 2);
        assert!(paths[0].extension().unwrap() == "png");
        assert!(paths[1].extension().unwrap() == "svg");
        assert_eq!(png_size(&paths[0]), (w, h));
        let svg = std::fs::read_to_string(&paths[1]).unwrap();
        assert!(svg.contains("<svg"));
        assert!(svg.contains(title), "SVG lacks the title");
        let leftovers: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with('.') || n.contains(".tmp"))
            .collect();
        assert!(leftovers.is_empty(), "temp files left: {leftovers:?}");
    }

    /// Realistic time-history data: damped sines for displacements, short spikes for force.
    struct Demo {
        t: Vec<f64>,
        w1p: Vec<f64>,
        w1n: Vec<f64>,
        w2p: Vec<f64>,
        w2n: Vec<f64>,
        f: Vec<f64>,
    }

    fn demo_data() -> Demo {
        let n = 2000;
        let t: Vec<f64> = (0..n).map(|i| 20.0 * i as f64 / (n - 1) as f64).collect();
        let damped = |a: f64, om: f64, z: f64, ph: f64| -> Vec<f64> {
            t.iter()
                .map(|&t| a * (-z * om * t).exp() * (om * t + ph).sin() * (1.0 - (-t).exp()))
                .collect()
        };
        let w1n = damped(0.08, 2.0 * std::f64::consts::PI * 0.8, 0.03, 0.0);
        let w2n = damped(0.05, 2.0 * std::f64::consts::PI * 1.3, 0.04, 0.5);
        let w1p: Vec<f64> = w1n.iter().map(|v| v * 0.8).collect();
        let w2p: Vec<f64> = w2n.iter().zip(&w1n).map(|(a, b)| a + 0.15 * b).collect();
        let f: Vec<f64> = t
            .iter()
            .map(|&t| {
                [1.3, 2.55, 3.8, 5.1, 7.7, 11.2]
                    .iter()
                    .zip([1.2e7, 8.0e6, 5.5e6, 3.0e6, 1.5e6, 4.0e5])
                    .map(|(c, a)| {
                        let d = (t - c) / 0.012;
                        if d.abs() < 1.0 {
                            a * (1.0 - d * d)
                        } else {
                            0.0
                        }
                    })
                    .sum()
            })
            .collect();
        Demo {
            t,
            w1p,
            w1n,
            w2p,
            w2n,
            f,
        }
    }

    fn demo_figure(d: &Demo) -> Figure<'_> {
        Figure {
            title: "Time history: El Centro 1940, gap 5 cm",
            x_label: "t [s]",
            panels: vec![
                Panel {
                    title: "Structure 1 (left)",
                    y_label: "w1 [m]",
                    series: vec![
                        Series {
                            label: "with pounding",
                            x: &d.t,
                            y: &d.w1p,
                            style: LineStyle::Solid,
                        },
                        Series {
                            label: "without pounding",
                            x: &d.t,
                            y: &d.w1n,
                            style: LineStyle::Dashed,
                        },
                    ],
                },
                Panel {
                    title: "Structure 2 (right)",
                    y_label: "w2 [m]",
                    series: vec![
                        Series {
                            label: "with pounding",
                            x: &d.t,
                            y: &d.w2p,
                            style: LineStyle::Solid,
                        },
                        Series {
                            label: "without pounding",
                            x: &d.t,
                            y: &d.w2n,
                            style: LineStyle::Dashed,
                        },
                    ],
                },
                Panel {
                    title: "Contact force",
                    y_label: "F [N]",
                    series: vec![Series {
                        label: "F",
                        x: &d.t,
                        y: &d.f,
                        style: LineStyle::Solid,
                    }],
                },
            ],
            width: 1200,
            height: 900,
        }
    }

    /// Signed smooth function over an uneven 9 × 10 grid (log-spaced x) with two NaN cells.
    fn demo_heat() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..9).map(|i| 0.005 * 2f64.powi(i)).collect(); // gap [m], 5 mm .. 1.28 m
        let y: Vec<f64> = (0..10).map(|j| 0.5 + 0.25 * j as f64).collect(); // T2/T1
        let mut z = Vec::new();
        for (j, &yy) in y.iter().enumerate() {
            for (i, &xx) in x.iter().enumerate() {
                let v = 300.0 * (-(xx / 0.05)).exp() * ((yy - 1.0) * 2.0).cos().powi(2)
                    - 100.0 * (1.0 - (-(xx / 0.3)).exp()) * (yy - 0.5) / 2.25;
                z.push(if (i, j) == (3, 4) || (i, j) == (7, 8) {
                    f64::NAN
                } else {
                    v
                });
            }
        }
        (x, y, z)
    }

    #[test]
    fn figure_and_heatmap_written() {
        let dir = temp_dir("basic");
        let d = demo_data();
        let fig = demo_figure(&d);
        let paths = write_figure(&fig, &dir.join("history")).unwrap();
        check_outputs(&dir, &paths, 1200, 900, "Time history");

        let (x, y, z) = demo_heat();
        let h = Heatmap {
            title: "Peak drift change",
            x_label: "gap [m]",
            y_label: "T2/T1 [-]",
            x: &x,
            y: &y,
            z: &z,
            z_label: "change [%]",
            width: 900,
            height: 700,
        };
        let paths = write_heatmap(&h, &dir.join("heat")).unwrap();
        check_outputs(&dir, &paths, 900, 700, "Peak drift change");
        // Overwriting works and is still atomic.
        write_heatmap(&h, &dir.join("heat")).unwrap();
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 4);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn nasty_figure_data_does_not_panic() {
        let dir = temp_dir("nasty");
        let nan = [f64::NAN; 5];
        let mixed = [1.0, f64::NAN, f64::INFINITY, 2.0, f64::NEG_INFINITY, 3.0];
        let xs = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let consts = [7.0; 6];
        let huge = [1e308, -1e308, 0.0, f64::MAX, f64::MIN_POSITIVE, 1e-320];
        fn s<'a>(y: &'a [f64], x: &'a [f64]) -> Series<'a> {
            Series {
                label: "s",
                x,
                y,
                style: LineStyle::Dashed,
            }
        }
        let fig = Figure {
            title: "Nasty <&> data",
            x_label: "",
            panels: vec![
                Panel {
                    title: "",
                    y_label: "",
                    series: vec![],
                },
                Panel {
                    title: "all NaN",
                    y_label: "a",
                    series: vec![s(&nan, &xs), s(&[], &[])],
                },
                Panel {
                    title: "mixed",
                    y_label: "b",
                    series: vec![s(&mixed, &xs), s(&consts, &xs), s(&consts[..1], &xs)],
                },
                Panel {
                    title: "huge",
                    y_label: "c",
                    series: vec![s(&huge, &xs)],
                },
            ],
            width: 640,
            height: 480,
        };
        let p = write_figure(&fig, &dir.join("nasty")).unwrap();
        check_outputs(&dir, &p, 640, 480, "Nasty &lt;&amp;&gt; data");

        // Tiny pictures and many panels: ugly but no panic.
        let many = Figure {
            panels: (0..30)
                .map(|_| Panel {
                    title: "p",
                    y_label: "y",
                    series: vec![s(&mixed, &xs), s(&consts, &xs)],
                })
                .collect(),
            width: 16,
            height: 16,
            ..fig.clone()
        };
        let _ = write_figure(&many, &dir.join("many"));

        // Errors, not panics.
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
        let leftovers = std::fs::read_dir(&dir)
            .unwrap()
            .filter(|e| {
                let n = e.as_ref().unwrap().file_name();
                let n = n.to_string_lossy();
                n.starts_with('.')
            })
            .count();
        assert_eq!(leftovers, 0);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn nasty_heatmaps() {
        let dir = temp_dir("nastyheat");
        let base = Heatmap {
            title: "H",
            x_label: "x",
            y_label: "y",
            x: &[1.0],
            y: &[2.0],
            z: &[f64::NAN],
            z_label: "z",
            width: 400,
            height: 300,
        };
        // Single all-NaN cell.
        let p = write_heatmap(&base, &dir.join("one")).unwrap();
        check_outputs(&dir, &p, 400, 300, "H");
        // Constant z, duplicated and unsorted grid, NaN coordinate.
        let x = [3.0, 1.0, 1.0, f64::NAN];
        let y = [5.0, 0.0];
        let z = [4.0; 8];
        let h = Heatmap {
            x: &x,
            y: &y,
            z: &z,
            ..base.clone()
        };
        write_heatmap(&h, &dir.join("const")).unwrap();
        // Huge / tiny values.
        let z2 = [1e308, -1e308, f64::INFINITY, 1e-320, 0.0, -0.0, 1.0, 2.0];
        let h2 = Heatmap {
            z: &z2,
            ..h.clone()
        };
        write_heatmap(&h2, &dir.join("huge")).unwrap();
        // Errors.
        let bad = Heatmap {
            z: &z[..3],
            ..h.clone()
        };
        assert!(matches!(
            write_heatmap(&bad, &dir.join("bad")),
            Err(PlotError::InvalidInput(_))
        ));
        let empty = Heatmap {
            x: &[],
            z: &[],
            ..base.clone()
        };
        assert!(matches!(
            write_heatmap(&empty, &dir.join("empty")),
            Err(PlotError::NoData(_))
        ));
        let nan_grid = Heatmap {
            x: &[f64::NAN],
            ..base.clone()
        };
        assert!(write_heatmap(&nan_grid, &dir.join("nangrid")).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn tick_formatting() {
        let (t, s) = linear_ticks(0.0, 1.2e7, 7);
        let f = TickFormat::for_ticks(&t, s);
        let l: Vec<String> = t.iter().map(|v| f.format(*v)).collect();
        assert_eq!(l, ["0", "2e6", "4e6", "6e6", "8e6", "10e6", "12e6"]);
        let (t, s) = linear_ticks(-0.083, 0.09, 6);
        let f = TickFormat::for_ticks(&t, s);
        let l: Vec<String> = t.iter().map(|v| f.format(*v)).collect();
        assert_eq!(l, ["-0.05", "0", "0.05"]);
        let (t, s) = linear_ticks(-0.083, 0.09, 9);
        let f = TickFormat::for_ticks(&t, s);
        let l: Vec<String> = t.iter().map(|v| f.format(*v)).collect();
        assert_eq!(
            l,
            [
                "-0.08", "-0.06", "-0.04", "-0.02", "0", "0.02", "0.04", "0.06", "0.08"
            ]
        );
        let (t, s) = linear_ticks(0.0, 20.0, 10);
        let f = TickFormat::for_ticks(&t, s);
        let l: Vec<String> = t.iter().map(|v| f.format(*v)).collect();
        assert_eq!(l, ["0", "5", "10", "15", "20"]);
        let (t, s) = linear_ticks(0.0, 0.0042, 5);
        let f = TickFormat::for_ticks(&t, s);
        let l: Vec<String> = t.iter().map(|v| f.format(*v)).collect();
        assert_eq!(l, ["0", "1e-3", "2e-3", "3e-3", "4e-3"]);
        assert_eq!(fmt_general(0.005), "0.005");
        assert_eq!(fmt_general(1.28), "1.28");
        assert_eq!(fmt_general(2e-4), "2e-4");
        assert_eq!(fmt_general(150000.0), "1.5e5");
    }

    /// Renders the demo pictures into `demo/` of the crate for visual inspection.
    #[test]
    #[ignore = "writes demo pictures into the source tree"]
    fn render_demo() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("demo");
        std::fs::create_dir_all(&dir).unwrap();
        let d = demo_data();
        write_figure(&demo_figure(&d), &dir.join("time_history")).unwrap();
        let (x, y, z) = demo_heat();
        let h = Heatmap {
            title: "Change of peak drift due to pounding",
            x_label: "gap [m]",
            y_label: "T2 / T1 [-]",
            x: &x,
            y: &y,
            z: &z,
            z_label: "change of peak drift [%]",
            width: 900,
            height: 700,
        };
        write_heatmap(&h, &dir.join("heatmap")).unwrap();
        let zpos: Vec<f64> = z.iter().map(|v| v.abs()).collect();
        let ylin: Vec<f64> = (0..10).map(|j| 1.0 + (j * j) as f64 * 0.1).collect();
        let h2 = Heatmap {
            title: "Peak contact force",
            z: &zpos,
            y: &ylin,
            z_label: "F max [N]",
            ..h
        };
        write_heatmap(&h2, &dir.join("heatmap_seq")).unwrap();

        // Edge cases, small pictures.
        let xs: Vec<f64> = (0..200).map(|i| i as f64 * 0.01).collect();
        let gappy: Vec<f64> = xs
            .iter()
            .map(|&x| {
                if (0.8..1.1).contains(&x) {
                    f64::NAN
                } else {
                    (3.0 * x).sin()
                }
            })
            .collect();
        let consts = vec![7.0; 200];
        let fig = Figure {
            title: "Edge cases",
            x_label: "x [-]",
            panels: vec![
                Panel {
                    title: "empty panel",
                    y_label: "y [-]",
                    series: vec![],
                },
                Panel {
                    title: "NaN gap and constant, a long panel title to force wrapping",
                    y_label: "y [-]",
                    series: vec![
                        Series {
                            label: "sin with gap",
                            x: &xs,
                            y: &gappy,
                            style: LineStyle::Solid,
                        },
                        Series {
                            label: "constant 7",
                            x: &xs,
                            y: &consts,
                            style: LineStyle::Dashed,
                        },
                    ],
                },
            ],
            width: 640,
            height: 480,
        };
        write_figure(&fig, &dir.join("edge_figure")).unwrap();
        let one = Heatmap {
            title: "One NaN cell",
            x_label: "x",
            y_label: "y",
            x: &[1.0],
            y: &[2.0],
            z: &[f64::NAN],
            z_label: "z",
            width: 400,
            height: 300,
        };
        write_heatmap(&one, &dir.join("edge_heatmap")).unwrap();
    }
}
