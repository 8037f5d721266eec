//! The pictures of `pounding spectrum` (the records' PSA against a log period axis, their mean
//! dashed, the target and the period range shaded) and of `pounding scale` (the scaled
//! records in grey, their mean, the target and the required fraction of it over the range).

use std::path::{Path, PathBuf};

use crate::analysis::record_spectrum::scaling::ScaledSuite;
use crate::model::ground_motion::STANDARD_GRAVITY;
use crate::output::spectrum_report::SpectrumReport;
use crate::plot::{AxisScale, Band, LineColor, LineStyle, PlotError, XyFigure, XyLine, write_xy};

/// Palette colours of the records, up to five (not the target's vermillion, not black, not the
/// pale yellow); more records are drawn in grey (the mean carries the message).
const RECORD_COLOURS: [usize; 5] = [0, 2, 3, 5, 4];
const COLOURED: usize = RECORD_COLOURS.len();

fn in_g(v: &[f64]) -> Vec<f64> {
    v.iter().map(|a| a / STANDARD_GRAVITY).collect()
}

fn opt_in_g(v: &[Option<f64>]) -> Vec<f64> {
    v.iter()
        .map(|a| a.map_or(f64::NAN, |a| a / STANDARD_GRAVITY))
        .collect()
}

/// Writes `<stem>.png/.svg` of a [`SpectrumReport`].
pub fn spectrum_figure(report: &SpectrumReport, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let n = report.records.len();
    let ys: Vec<Vec<f64>> = report.records.iter().map(|r| in_g(&r.psa)).collect();
    let labels: Vec<String> = report
        .records
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let name = Path::new(&r.file)
                .file_name()
                .map_or(r.file.clone(), |f| f.to_string_lossy().into_owned());
            format!("[{}] {name}", i + 1)
        })
        .collect();
    let mean = report.mean.as_ref().map(|m| opt_in_g(&m.psa));
    let target = report.target.as_ref().map(|t| opt_in_g(&t.psa));
    let t = &report.periods;
    let mut lines: Vec<XyLine> = ys
        .iter()
        .enumerate()
        .map(|(i, y)| XyLine {
            label: if n <= COLOURED { &labels[i] } else { "" },
            x: t,
            y,
            style: LineStyle::Solid,
            color: if n <= COLOURED {
                LineColor::Palette(RECORD_COLOURS[i % COLOURED])
            } else {
                LineColor::Grey
            },
            width: if n <= COLOURED { 2 } else { 1 },
        })
        .collect();
    if let Some(y) = &target {
        lines.push(XyLine {
            label: "target",
            x: t,
            y,
            style: LineStyle::Solid,
            color: LineColor::Palette(1),
            width: 3,
        });
    }
    if let Some(y) = &mean {
        lines.push(XyLine {
            label: "mean",
            x: t,
            y,
            style: LineStyle::Dashed,
            color: LineColor::Black,
            width: 3,
        });
    }
    let bands = report
        .range
        .iter()
        .map(|r| Band {
            label: "period range",
            from: r.lo,
            to: r.hi,
        })
        .collect();
    let subtitle = format!(
        "{} record{}, {} % damping{}",
        n,
        if n == 1 { "" } else { "s" },
        crate::numerics::format::fmt_num(100.0 * report.damping),
        if n > COLOURED {
            " (records in grey)"
        } else {
            ""
        }
    );
    let fig = XyFigure {
        title: "Pseudo-acceleration response spectra",
        subtitle: &subtitle,
        x_label: "period T [s]",
        y_label: "PSA [g]",
        x_scale: AxisScale::Log,
        y_scale: AxisScale::Linear,
        bands,
        lines,
        width: 1000,
        height: 650,
    };
    write_xy(&fig, stem)
}

/// Writes `<stem>.png/.svg` of a [`ScaledSuite`].
pub fn scaling_figure(suite: &ScaledSuite, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let t = &suite.display_periods;
    let scaled: Vec<Vec<f64>> = suite
        .records
        .iter()
        .map(|r| {
            r.display_psa
                .iter()
                .map(|a| r.factor * a / STANDARD_GRAVITY)
                .collect()
        })
        .collect();
    let target = opt_in_g(&suite.display_target);
    let required: Vec<f64> = target.iter().map(|a| a * suite.required_ratio).collect();
    let k = scaled.len().max(1) as f64;
    let mean: Vec<f64> = (0..t.len())
        .map(|j| scaled.iter().map(|s| s[j]).sum::<f64>() / k)
        .collect();
    let required_label = format!(
        "{} × target",
        crate::numerics::format::fmt_num(suite.required_ratio)
    );
    let mut lines: Vec<XyLine> = scaled
        .iter()
        .enumerate()
        .map(|(i, y)| XyLine {
            label: if i == 0 { "scaled records" } else { "" },
            x: t,
            y,
            style: LineStyle::Solid,
            color: LineColor::Grey,
            width: 1,
        })
        .collect();
    lines.push(XyLine {
        label: "target",
        x: t,
        y: &target,
        style: LineStyle::Solid,
        color: LineColor::Palette(1),
        width: 3,
    });
    lines.push(XyLine {
        label: &required_label,
        x: t,
        y: &required,
        style: LineStyle::Dashed,
        color: LineColor::Palette(1),
        width: 2,
    });
    lines.push(XyLine {
        label: "mean of the scaled records",
        x: t,
        y: &mean,
        style: LineStyle::Solid,
        color: LineColor::Black,
        width: 3,
    });
    let title = format!("Suite scaled by {}", suite.rule_name);
    let subtitle = format!(
        "{} records, 5 % damping; governs: {}",
        suite.records.len(),
        suite.governs
    );
    let fig = XyFigure {
        title: &title,
        subtitle: &subtitle,
        x_label: "period T [s]",
        y_label: "PSA [g]",
        x_scale: AxisScale::Log,
        y_scale: AxisScale::Linear,
        bands: vec![Band {
            label: "code's period range",
            from: suite.code_range.lo,
            to: suite.code_range.hi,
        }],
        lines,
        width: 1100,
        height: 700,
    };
    write_xy(&fig, stem)
}
