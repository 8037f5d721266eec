//! The pictures of a fragility study: `fragility.png/.svg` (per limit state, the fitted
//! lognormal curves with and without pounding, their bootstrap bands and the observed
//! fractions at the stripes) and `p-pounding.png/.svg` (P(pounding) against the gap, one curve
//! per stripe, from the runs without contact).

use std::path::{Path, PathBuf};

use crate::input::fragility::{G, LimitKind, LimitState};
use crate::plot::curves::{BandCurve, CurveFigure, CurvePanel, Markers, write_curves};
use crate::plot::{AxisScale, LineColor, LineStyle, PlotError, XyFigure, XyLine, write_xy};
use crate::study::fragility::{FragilityRun, MODELS};

/// The palette's black, for the threshold lines.
const PALETTE_BLACK: usize = 6;

/// A record's palette colour (black left for the threshold).
fn record_color(r: usize) -> usize {
    let c = r % 7;
    if c >= PALETTE_BLACK { c + 1 } else { c }
}

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
        x: Vec<f64>,
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
                x: c.im.clone(),
                label,
            }
        })
        .collect();
    let row = s.scenario.is_row();
    let mut panels = Vec::new();
    for l in 0..n_ls {
        let ls = &s.limit_states[l];
        let row_title = row.then(|| {
            // (a row has many panels: its titles short, "with / without")
            let fit = |m: usize| {
                run.curves
                    .iter()
                    .find(|c| c.limit_state == l && c.model == m)
                    .and_then(|c| c.fit.as_ref().ok())
            };
            let pair = |f: &dyn Fn(&crate::study::fragility::LognormalFit) -> String| {
                [0, 1]
                    .map(|m| fit(m).map_or("–".to_string(), f))
                    .join(" / ")
            };
            if fit(0).is_none() && fit(1).is_none() {
                ls.name.clone()
            } else {
                format!(
                    "{}: θ = {}, β = {}",
                    ls.name,
                    pair(&|f| format!("{:.3}", f.theta)),
                    pair(&|f| format!("{:.2}", f.beta))
                )
            }
        });
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
        let title = if let Some(t) = row_title {
            t
        } else if fits.is_empty() {
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
                    x: &d.x,
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
    let subtitle = if row {
        format!(
            "{} records{}; θ, β: with / without pounding (solid / dashed); points: fractions \
             (filled: with); bands: {:.0} % bootstrap",
            s.record_names.len(),
            if s.ida.is_some() {
                " (IDA)".to_string()
            } else {
                format!(" × {} stripes", stripes.len())
            },
            100.0 * s.confidence
        )
    } else if s.ida.is_some() {
        format!(
            "IDA of {} records; points: the fraction of records whose capacity is at most IM; \
             lines: lognormal of the capacities; bands: {:.0} % bootstrap over records",
            s.record_names.len(),
            100.0 * s.confidence
        )
    } else {
        format!(
            "{} records × {} stripes; points: observed fractions; lines: lognormal fit by \
             maximum likelihood; bands: {:.0} % bootstrap over records",
            s.record_names.len(),
            stripes.len(),
            100.0 * s.confidence
        )
    };
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

/// `p-pounding.png/.svg` in `dir` (of a row: a panel per pair, `row_pounding_figure`).
pub fn pounding_figure(run: &FragilityRun, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let s = &run.study;
    if s.scenario.is_row() {
        return row_pounding_figure(run, dir);
    }
    let t = &run.pounding[0];
    let gaps_mm: Vec<f64> = t.gaps.iter().map(|g| 1e3 * g).collect();
    let labels: Vec<String> =
        t.im.iter()
            .map(|x| format!("{} = {} {}", s.measure.short(), tidy(*x), s.units.key()))
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
    if let Some(g) = run.target_gap.first() {
        target_x = vec![0.0, 1e3 * g.empirical, 1e3 * g.empirical];
        target_y = vec![g.probability, g.probability, 0.0];
        target_label = format!(
            "P = {:.0} % at {} = {} {}: gap {:.0} mm",
            100.0 * g.probability,
            s.measure.short(),
            tidy(g.im),
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

/// `p-pounding.png/.svg` of a row: one panel per adjacent pair, P(pounding) of that pair
/// against its gap (one curve per intensity), and the gap for the target probability.
fn row_pounding_figure(run: &FragilityRun, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let s = &run.study;
    let names: Vec<&str> = s.scenario.structures.iter().map(|x| x.name()).collect();
    struct Panel {
        title: String,
        gaps_mm: Vec<f64>,
        target: Option<(Vec<f64>, Vec<f64>)>,
    }
    let data: Vec<Panel> = run
        .pounding
        .iter()
        .enumerate()
        .map(|(p, t)| {
            let g = run.target_gap.get(p);
            Panel {
                title: format!(
                    "pair {}: {} – {}{}",
                    p + 1,
                    names[p],
                    names[p + 1],
                    g.map_or(String::new(), |g| format!(
                        " (P = {:.0} % at {} = {} {}: gap {:.0} mm)",
                        100.0 * g.probability,
                        s.measure.short(),
                        tidy(g.im),
                        s.units.key(),
                        1e3 * g.empirical
                    ))
                ),
                gaps_mm: t.gaps.iter().map(|g| 1e3 * g).collect(),
                target: g.map(|g| {
                    (
                        vec![0.0, 1e3 * g.empirical, 1e3 * g.empirical],
                        vec![g.probability, g.probability, 0.0],
                    )
                }),
            }
        })
        .collect();
    let labels: Vec<String> = run.pounding[0]
        .im
        .iter()
        .map(|x| format!("{} = {} {}", s.measure.short(), tidy(*x), s.units.key()))
        .collect();
    let panels: Vec<CurvePanel> = data
        .iter()
        .zip(&run.pounding)
        .map(|(d, t)| {
            let mut curves: Vec<BandCurve> =
                t.p.iter()
                    .zip(&labels)
                    .enumerate()
                    .map(|(j, (p, l))| BandCurve {
                        label: l,
                        x: &d.gaps_mm,
                        y: p,
                        band: (&[], &[]),
                        // (seven colours, in turn)
                        color: record_color(j),
                        style: LineStyle::Solid,
                    })
                    .collect();
            if let Some((x, y)) = &d.target {
                curves.push(BandCurve {
                    label: "",
                    x,
                    y,
                    band: (&[], &[]),
                    color: PALETTE_BLACK,
                    style: LineStyle::Dashed,
                });
            }
            CurvePanel {
                title: d.title.clone(),
                curves,
                markers: Vec::new(),
            }
        })
        .collect();
    let n = panels.len();
    let cols = if n <= 1 { 1 } else { 2 };
    let rows = n.div_ceil(cols);
    let subtitle = format!(
        "{}; from the runs without contact ({}); black: the gap for the target probability",
        s.measure.label(),
        match s.gap_mode {
            crate::input::fragility::GapMode::Uniform => "one gap at every level of the pair",
            crate::input::fragility::GapMode::Scaled => {
                "the pair's gaps scaled; the gap at its highest level"
            }
        }
    );
    let fig = CurveFigure {
        title: "P(pounding | IM, gap) per pair",
        subtitle: &subtitle,
        x_label: "gap [mm]",
        y_label: "P(pounding)",
        y_range: (0.0, 1.0),
        panels,
        columns: cols,
        width: if cols == 1 { 1100 } else { 1600 },
        height: 170 + 430 * rows as u32,
    };
    write_curves(&fig, &dir.join("p-pounding"))
}

/// An intensity for a legend: at most six decimals, no trailing zeros (0.06, not
/// 0.060000000000000005 from the hunt's sums).
fn tidy(x: f64) -> String {
    let t = format!("{x:.6}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The demand of a limit state as drawn (its unit: N as MN, m/s² as g when the threshold was
/// given in g) and the axis label: (scale, label).
fn demand_axis(ls: &LimitState) -> (f64, String) {
    match ls.kind {
        LimitKind::Pounding => (1.0, "required separation / gap, largest over levels".into()),
        LimitKind::ContactForce => (1e-6, "peak contact force [MN]".into()),
        LimitKind::Ductility => (1.0, "peak storey ductility".into()),
        LimitKind::DriftRatio => (100.0, "peak storey drift ratio [%]".into()),
        LimitKind::FloorAcceleration => {
            if ls.name.contains("g(") || ls.name.ends_with('g') {
                (1.0 / G, "peak floor acceleration [g]".into())
            } else {
                (1.0, "peak floor acceleration [m/s²]".into())
            }
        }
    }
}

/// A record's short name: its number and the last part of its file's stem.
fn short_name(i: usize, file: &str) -> String {
    let stem = Path::new(file)
        .file_stem()
        .map_or(file.to_string(), |s| s.to_string_lossy().into_owned());
    let last = stem.rsplit('_').next().unwrap_or(&stem).to_string();
    format!("{} {last}", i + 1)
}

/// `ida.png/.svg` in `dir` (an IDA): per limit state, each record's IDA curve — the intensity
/// against the demand, run by run (solid: with contact; dashed: without) — the threshold (grey)
/// and each record's capacity marked on it (filled: with; open: without).
pub fn ida_figure(run: &FragilityRun, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let s = &run.study;
    let u = s.units.factor();
    let gaps = crate::study::fragility::scenario_gaps(s);
    let nr = s.record_names.len();
    let names: Vec<String> = s
        .record_names
        .iter()
        .enumerate()
        .map(|(i, f)| short_name(i, f))
        .collect();
    // per record its runs by IM
    let by_record: Vec<Vec<&crate::study::fragility::RunOutcome>> = (0..nr)
        .map(|r| {
            let mut v: Vec<_> = run.record_runs(r).collect();
            v.sort_by(|a, b| a.im.total_cmp(&b.im));
            v
        })
        .collect();
    let y_max = run.outcomes.iter().map(|o| o.im / u).fold(0.0, f64::max) * 1.05;
    struct Line {
        x: Vec<f64>,
        y: Vec<f64>,
        record: usize,
        model: usize,
    }
    struct Panel {
        title: String,
        lines: Vec<Line>,
        thr: (Vec<f64>, Vec<f64>),
        caps: Vec<(usize, usize, Vec<f64>, Vec<f64>)>,
        x_label: String,
    }
    let mut panels_data = Vec::new();
    for (l, ls) in s.limit_states.iter().enumerate() {
        let (scale, x_label) = demand_axis(ls);
        let mut lines = Vec::new();
        for (r, runs) in by_record.iter().enumerate() {
            for m in 0..2 {
                let pts: Vec<(f64, f64)> = runs
                    .iter()
                    .filter_map(|o| o.demand(ls, m, &gaps).map(|d| (d * scale, o.im / u)))
                    .collect();
                if pts.is_empty() {
                    continue;
                }
                let mut x = vec![0.0];
                let mut y = vec![0.0];
                x.extend(pts.iter().map(|p| p.0));
                y.extend(pts.iter().map(|p| p.1));
                lines.push(Line {
                    x,
                    y,
                    record: r,
                    model: m,
                });
            }
        }
        if lines.is_empty() {
            continue;
        }
        let thr_x = if ls.kind == LimitKind::Pounding {
            1.0
        } else {
            ls.value * scale
        };
        let mut caps = Vec::new();
        for c in run.curves.iter().filter(|c| c.limit_state == l) {
            if let Some(k) = &c.capacities {
                for (r, cap) in k.iter().enumerate() {
                    if let Some(v) = cap.value() {
                        caps.push((r, c.model, vec![thr_x], vec![v / u]));
                    }
                }
            }
        }
        panels_data.push(Panel {
            title: ls.name.clone(),
            lines,
            thr: (vec![thr_x, thr_x], vec![0.0, y_max]),
            caps,
            x_label,
        });
    }
    if panels_data.is_empty() {
        return Err(PlotError::NoData(
            "no limit state has a demand to draw".into(),
        ));
    }
    let panels: Vec<CurvePanel> = panels_data
        .iter()
        .map(|p| {
            let mut labelled = vec![false; nr];
            let mut curves: Vec<BandCurve> = p
                .lines
                .iter()
                .map(|ln| {
                    let label = if labelled[ln.record] {
                        ""
                    } else {
                        labelled[ln.record] = true;
                        names[ln.record].as_str()
                    };
                    BandCurve {
                        label,
                        x: &ln.x,
                        y: &ln.y,
                        band: (&[], &[]),
                        color: record_color(ln.record),
                        style: if ln.model == 0 {
                            LineStyle::Solid
                        } else {
                            LineStyle::Dashed
                        },
                    }
                })
                .collect();
            curves.push(BandCurve {
                label: "",
                x: &p.thr.0,
                y: &p.thr.1,
                band: (&[], &[]),
                color: PALETTE_BLACK,
                style: LineStyle::Dashed,
            });
            CurvePanel {
                title: format!("{}: {}", p.title, p.x_label),
                curves,
                markers: p
                    .caps
                    .iter()
                    .map(|(r, m, x, y)| Markers {
                        x,
                        y,
                        color: record_color(*r),
                        filled: *m == 0,
                    })
                    .collect(),
            }
        })
        .collect();
    let n = panels.len();
    let cols = if n <= 1 { 1 } else { 2 };
    let rows = n.div_ceil(cols);
    let y_label = format!("{} [{}]", s.measure.short(), s.units.key());
    let subtitle = format!(
        "{nr} records, their runs by intensity; solid: with contact, dashed: without; black: \
         the limit; points: capacities (filled: with, open: without)"
    );
    let fig = CurveFigure {
        title: &s.title,
        subtitle: &subtitle,
        x_label: "demand (in each panel's title)",
        y_label: &y_label,
        y_range: (0.0, y_max.max(1e-12)),
        panels,
        columns: cols,
        width: if cols == 1 { 1100 } else { 1700 },
        height: 190 + 460 * rows as u32,
    };
    write_curves(&fig, &dir.join("ida"))
}

/// The figures of a study in `dir`: `fragility`, `p-pounding`, and for an IDA `ida`.
pub fn pictures(run: &FragilityRun, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let mut v = fragility_figure(run, dir)?;
    v.extend(pounding_figure(run, dir)?);
    if run.study.ida.is_some() {
        v.extend(ida_figure(run, dir)?);
    }
    Ok(v)
}
