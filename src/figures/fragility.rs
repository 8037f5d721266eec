//! The pictures of a fragility study: `fragility.png/.svg` (per limit state, the fitted
//! lognormal curves with and without pounding, their bootstrap bands and the observed
//! fractions at the stripes) and `p-pounding.png/.svg` (P(pounding) against the gap, one curve
//! per stripe, from the runs without contact).

use std::path::{Path, PathBuf};

use crate::plot::curves::{BandCurve, CurveFigure, CurvePanel, Markers, write_curves};
use crate::plot::{AxisScale, LineColor, LineStyle, PlotError, XyFigure, XyLine, write_xy};
use crate::study::fragility::{FragilityRun, MODELS};

/// Palette index of the model (with contact: vermillion; without: blue).
fn color(model: usize) -> usize {
    if model == 0 { 1 } else { 0 }
}

/// `fragility.png/.svg` in `dir`.
pub fn fragility_figure(run: &FragilityRun, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let s = &run.study;
    let stripes = run.stripes();
    let n_ls = s.limit_states.len();
    // (per curve: the fitted P, the band, the observed fractions)
    struct Data {
        ls: usize,
        model: usize,
        fitted: Vec<f64>,
        lo: Vec<f64>,
        hi: Vec<f64>,
        frac: Vec<f64>,
        label: String,
    }
    let data: Vec<Data> = run
        .curves
        .iter()
        .map(|c| {
            let fitted = match &c.fit {
                Ok(f) => run.band_im.iter().map(|&x| f.probability(x)).collect(),
                Err(_) => vec![f64::NAN; run.band_im.len()],
            };
            let (lo, hi) = match &c.intervals {
                Some(b) => (
                    b.band.iter().map(|i| i.lo).collect(),
                    b.band.iter().map(|i| i.hi).collect(),
                ),
                None => (Vec::new(), Vec::new()),
            };
            let frac = c
                .runs
                .iter()
                .zip(&c.exceedances)
                .map(|(n, z)| {
                    if *n > 0 {
                        *z as f64 / *n as f64
                    } else {
                        f64::NAN
                    }
                })
                .collect();
            let label = match c.model {
                0 => "with pounding (runs with contact)".to_string(),
                _ => "without pounding (runs without contact)".to_string(),
            };
            Data {
                ls: c.limit_state,
                model: c.model,
                fitted,
                lo,
                hi,
                frac,
                label,
            }
        })
        .collect();
    let mut panels = Vec::new();
    for l in 0..n_ls {
        let ls = &s.limit_states[l];
        let mut fits = Vec::new();
        for d in data.iter().filter(|d| d.ls == l) {
            let c = run
                .curves
                .iter()
                .find(|c| c.limit_state == l && c.model == d.model);
            if let Some(Ok(f)) = c.map(|c| &c.fit) {
                fits.push(format!(
                    "{}: θ = {:.3}, β = {:.2}",
                    MODELS[d.model], f.theta, f.beta
                ));
            }
        }
        let title = if fits.is_empty() {
            ls.name.clone()
        } else {
            format!("{} ({})", ls.name, fits.join("; "))
        };
        panels.push(CurvePanel {
            title,
            curves: data
                .iter()
                .filter(|d| d.ls == l)
                .map(|d| BandCurve {
                    label: &d.label,
                    x: &run.band_im,
                    y: &d.fitted,
                    band: (&d.lo, &d.hi),
                    color: color(d.model),
                    style: if d.model == 0 {
                        LineStyle::Solid
                    } else {
                        LineStyle::Dashed
                    },
                })
                .collect(),
            markers: data
                .iter()
                .filter(|d| d.ls == l)
                .map(|d| Markers {
                    x: &stripes,
                    y: &d.frac,
                    color: color(d.model),
                    filled: d.model == 0,
                })
                .collect(),
        });
    }
    let cols = if n_ls <= 1 { 1 } else { 2 };
    let rows = n_ls.div_ceil(cols);
    let x_label = format!("{} [{}]", s.measure.label(), s.units.key());
    let subtitle = format!(
        "{} records × {} stripes; points: observed fractions; lines: lognormal fit by maximum \
         likelihood; bands: {:.0} % bootstrap over records",
        s.record_names.len(),
        stripes.len(),
        100.0 * s.confidence
    );
    let fig = CurveFigure {
        title: &s.title,
        subtitle: &subtitle,
        x_label: &x_label,
        y_label: "P(exceed)",
        y_range: (0.0, 1.0),
        panels,
        columns: cols,
        width: if cols == 1 { 1000 } else { 1600 },
        height: 170 + 430 * rows as u32,
    };
    write_curves(&fig, &dir.join("fragility"))
}

/// `p-pounding.png/.svg` in `dir`.
pub fn pounding_figure(run: &FragilityRun, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let s = &run.study;
    let t = &run.pounding;
    let gaps_mm: Vec<f64> = t.gaps.iter().map(|g| 1e3 * g).collect();
    let labels: Vec<String> =
        t.im.iter()
            .map(|x| format!("{} = {x} {}", s.measure.short(), s.units.key()))
            .collect();
    let mut lines: Vec<XyLine> =
        t.p.iter()
            .zip(&labels)
            .enumerate()
            .map(|(j, (p, l))| XyLine {
                label: l,
                x: &gaps_mm,
                y: p,
                style: LineStyle::Solid,
                color: LineColor::Palette(j),
                width: 3,
            })
            .collect();
    let target_x;
    let target_y;
    let target_label;
    if let Some(g) = &run.target_gap {
        target_x = vec![0.0, 1e3 * g.empirical, 1e3 * g.empirical];
        target_y = vec![g.probability, g.probability, 0.0];
        target_label = format!(
            "P = {:.0} % at {} = {} {}: gap {:.0} mm",
            100.0 * g.probability,
            s.measure.short(),
            g.im,
            s.units.key(),
            1e3 * g.empirical
        );
        lines.push(XyLine {
            label: &target_label,
            x: &target_x,
            y: &target_y,
            style: LineStyle::Dashed,
            color: LineColor::Black,
            width: 2,
        });
    }
    let subtitle = format!(
        "{}; from the runs without contact: a record pounds for every gap below its critical gap ({})",
        s.measure.label(),
        match s.gap_mode {
            crate::input::fragility::GapMode::Uniform => "the same gap at every level",
            crate::input::fragility::GapMode::Scaled => {
                "the scenario's gaps scaled together; the gap at the highest level"
            }
        }
    );
    let fig = XyFigure {
        title: "P(pounding | IM, gap)",
        subtitle: &subtitle,
        x_label: "gap [mm]",
        y_label: "P(pounding)",
        x_scale: AxisScale::Linear,
        y_scale: AxisScale::Linear,
        bands: Vec::new(),
        lines,
        width: 1200,
        height: 700,
    };
    write_xy(&fig, &dir.join("p-pounding"))
}

/// Both figures in `dir`.
pub fn pictures(run: &FragilityRun, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let mut v = fragility_figure(run, dir)?;
    v.extend(pounding_figure(run, dir)?);
    Ok(v)
}
