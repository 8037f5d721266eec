//! Plot output for `pounding`: stacked line figures (time histories, sweep lines) and heatmaps
//! (parameter studies), drawn with plotters.
//!
//! - [`lines`]: [`Figure`]s of stacked [`Panel`]s over one x axis, linear or logarithmic y;
//! - [`heatmap`]: a [`Heatmap`] of a grid with its colour bar, ticked at the grid values;
//! - [`profile`]: envelopes over height, panels side by side ([`ProfileFigure`]);
//! - [`xy`]: one panel over a linear or logarithmic x axis with shaded bands ([`XyFigure`]);
//! - [`style`]: the font, palette, number labels and the colour scales ([`ColorScale`]).
//!
//! Every picture is written twice, as `<stem>.png` and `<stem>.svg`, on two backends of our own
//! behind plotters' drawing API: `canvas` (the PNG's RGB bitmap: thick lines drawn as spans,
//! each glyph rasterised once) and `svg` (plotters' SVG markup written straight into the
//! document). Each is written atomically (rendered into a temporary file in the target
//! directory, then renamed onto the final name), so a reader never sees a half-written file. Text uses an embedded DejaVu Sans font (see
//! `assets/DejaVuSans-LICENSE.txt`): no system fonts or fontconfig are needed.
//!
//! The functions never panic on data: non-finite values are skipped (lines break at them,
//! heatmap cells become grey "no data" cells), empty or constant data still give a valid picture,
//! and structurally impossible input (no panels, empty grid, wrong `z` length, picture size out
//! of range) is a [`PlotError`].

use std::ffi::OsString;
use std::io::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::drawing::DrawingAreaErrorKind;
use plotters::prelude::*;

mod canvas;
pub mod curves;
pub mod heatmap;
pub mod lines;
mod png;
pub mod profile;
pub mod style;
mod svg;
pub mod xy;

pub use heatmap::{Heatmap, write_heatmap};
pub use lines::{AxisScale, Figure, LineStyle, Panel, Series, write_figure};
pub use profile::{ProfileFigure, ProfilePanel, ProfileSeries, write_profile};
pub use style::ColorScale;
pub use xy::{Band, LineColor, XyFigure, XyLine, write_xy};

/// Largest accepted picture side in pixels.
const MAX_SIDE: u32 = 16_384;

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

fn check_size(w: u32, h: u32) -> Result<(), PlotError> {
    if w < 16 || h < 16 || w > MAX_SIDE || h > MAX_SIDE {
        return Err(PlotError::InvalidInput(format!(
            "picture size {w}x{h} is outside 16..={MAX_SIDE} pixels per side"
        )));
    }
    Ok(())
}

/// Runs `f`, turning an unexpected panic inside the plotting library into an error.
fn guard<T>(f: impl FnOnce() -> Result<T, PlotError>) -> Result<T, PlotError> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|_| {
        Err(PlotError::Draw(
            "internal error (panic) in the plotting code".into(),
        ))
    })
}

/// A plotters drawing error as a [`PlotError`].
fn draw_err<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> PlotError {
    PlotError::Draw(e.to_string())
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> PlotError + '_ {
    move |source| PlotError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Something that draws itself on any plotters backend.
trait Render {
    /// Draws on `root`. `bitmap`: `root` is the PNG's `canvas::Canvas` (lines may be thinned
    /// to what its pixels show; it draws thick polylines segment by segment, without the miter
    /// spikes plotters' bitmap would draw above sharp peaks).
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        bitmap: bool,
    ) -> Result<(), PlotError>;
}

/// Renders `r` to `<stem>.png` and `<stem>.svg`, each written atomically.
fn write_both<R: Render + Sync>(
    r: &R,
    stem: &Path,
    w: u32,
    h: u32,
) -> Result<Vec<PathBuf>, PlotError> {
    check_size(w, h)?;
    style::ensure_font()?;
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
    let temp =
        |suffix: &str| crate::output::atomic::temp_file(dir, &prefix, suffix).map_err(io_err(dir));
    // not synced, an earlier run's file removed first (crate::output::atomic says why)
    let persist = |tmp: tempfile::NamedTempFile, to: &Path| {
        crate::output::atomic::persist(tmp, to).map_err(|source| PlotError::Io {
            path: to.to_path_buf(),
            source,
        })
    };
    let (png, svg) = (with_ext(".png"), with_ext(".svg"));

    // The two encodings are independent: the SVG is rendered on a second thread while the
    // PNG is drawn and encoded here (on the paper case's run ~40 % of the pictures' work is
    // the SVG side; a user's `pounding run` waits for the longer of the two, not their sum).
    let svg_text = || -> Result<String, PlotError> {
        let mut text = String::new();
        guard(|| {
            let root = svg::Svg::new(&mut text, (w, h)).into_drawing_area();
            r.render(&root, false)?;
            root.present().map_err(draw_err)
        })?;
        Ok(text)
    };
    let png_file = || -> Result<tempfile::NamedTempFile, PlotError> {
        // PNG: drawn into an RGB buffer, encoded here with fast settings (plotters' own
        // encoder tries all five row filters on every row, which cost more than the drawing)
        let mut rgb = vec![0u8; 3 * w as usize * h as usize];
        guard(|| {
            let canvas = canvas::Canvas::new(&mut rgb, (w, h))
                .ok_or_else(|| PlotError::Draw("bitmap buffer of the wrong size".into()))?;
            let root = canvas.into_drawing_area();
            r.render(&root, true)?;
            root.present().map_err(draw_err)
        })?;
        let tmp = temp(".png")?;
        encode_png(tmp.as_file(), &rgb, w, h)
            .map_err(|e| PlotError::Draw(format!("PNG encoding: {e}")))?;
        Ok(tmp)
    };
    let (png_tmp, text) = std::thread::scope(|scope| {
        let svg = std::thread::Builder::new()
            .name("svg".into())
            .spawn_scoped(scope, svg_text);
        let png_tmp = png_file();
        let text = match svg {
            Ok(handle) => handle.join().unwrap_or_else(|_| {
                Err(PlotError::Draw(
                    "internal error (panic) in the plotting code".into(),
                ))
            }),
            // no thread to be had: the SVG after the PNG, on this one
            Err(_) => svg_text(),
        };
        (png_tmp, text)
    });
    // (the PNG is persisted first, as before: a failed SVG leaves no stale SVG either way)
    persist(png_tmp?, &png)?;
    let text = text?;
    let mut tmp = temp(".svg")?;
    tmp.write_all(text.as_bytes()).map_err(io_err(tmp.path()))?;
    persist(tmp, &svg)?;
    Ok(vec![png, svg])
}

/// White background, the centred title and an optional subtitle under it; returns the height
/// they take.
/// `rgb` (8-bit RGB rows of `w` pixels, `h` rows) encoded as PNG into `file`: fast deflate
/// and one fixed row filter, `Up` ([`png::write_png`], which says why: against Paeth 30 %
/// fewer instructions for files ~40 % larger).
fn encode_png(file: &std::fs::File, rgb: &[u8], w: u32, h: u32) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::with_capacity(1 << 16, file);
    png::write_png(&mut out, rgb, w, h)
}

fn draw_titles<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    subtitle: &str,
    f: style::Fonts,
) -> Result<i32, PlotError> {
    use plotters::style::text_anchor::{HPos, Pos, VPos};
    root.fill(&WHITE).map_err(draw_err)?;
    let w = root.dim_in_pixel().0 as i32;
    let centred = |size: f64| {
        style::font(size)
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Center))
    };
    let mut y = (f.tick * 0.8) as i32;
    if !title.is_empty() {
        let h = (f.title * 1.7) as i32;
        root.draw_text(title, &centred(f.title), (w / 2, y + h / 2))
            .map_err(draw_err)?;
        y += h;
    }
    if !subtitle.is_empty() {
        let h = (f.text * 1.5) as i32;
        root.draw_text(subtitle, &centred(f.text), (w / 2, y + h / 2 - 4))
            .map_err(draw_err)?;
        y += h;
    }
    Ok(y)
}

#[cfg(test)]
pub(crate) mod test_util {
    use std::path::{Path, PathBuf};
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A fresh temporary directory.
    pub fn temp_dir(tag: &str) -> PathBuf {
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

    /// PNG of the given size and an SVG containing `title`; no temporary files left in `dir`.
    pub fn check_outputs(dir: &Path, paths: &[PathBuf], w: u32, h: u32, title: &str) {
        assert_eq!(paths.len(), 2);
        assert!(paths[0].extension().unwrap() == "png");
        assert!(paths[1].extension().unwrap() == "svg");
        let b = std::fs::read(&paths[0]).unwrap();
        assert_eq!(&b[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
        let size = (
            u32::from_be_bytes(b[16..20].try_into().unwrap()),
            u32::from_be_bytes(b[20..24].try_into().unwrap()),
        );
        assert_eq!(size, (w, h));
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
}
