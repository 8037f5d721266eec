//! The pictures of a suite run: `suite-spectra` (the scaled records' spectra, their mean, the
//! target and the code's period range shaded: [`crate::figures::spectrum::scaling_figure`]) and
//! `suite-records` (per record the required separation at the contact levels and the peak
//! force, each record a stem, with the design values dashed and the gaps).

use std::path::{Path, PathBuf};

use crate::figures::run::run_pictures;
use crate::figures::spectrum::scaling_figure;
use crate::plot::{AxisScale, Figure, LineStyle, Panel, Series, write_figure};
use crate::study::suite::SuiteRun;

/// At most this many levels get their own stems (else the governing and the highest level).
const MAX_LEVELS_DRAWN: usize = 4;

/// Palette indices of the levels (not black, kept for the gap; not the pale yellow).
const LEVEL_COLOURS: [usize; 4] = [0, 1, 2, 3];

/// The stems of `values` (one per record, record i at x = i + 1 + `offset`) as one series:
/// a vertical line from 0 to the value with a short cap, broken between records.
fn stems(values: &[f64], offset: f64) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for (i, &v) in values.iter().enumerate() {
        let xi = i as f64 + 1.0 + offset;
        for (a, b) in [(xi, 0.0), (xi, v), (xi - 0.08, v), (xi + 0.08, v)] {
            x.push(a);
            y.push(b);
        }
        x.push(f64::NAN);
        y.push(f64::NAN);
    }
    (x, y)
}

/// Writes `suite-records.png/.svg` into `dir`.
pub fn records_figure(run: &SuiteRun, dir: &Path) -> Result<Vec<PathBuf>, String> {
    let n = run.records.len();
    let d = &run.design;
    let levels: Vec<usize> = if d.levels.len() <= MAX_LEVELS_DRAWN {
        (0..d.levels.len()).collect()
    } else {
        let top = (0..d.levels.len())
            .max_by(|&a, &b| d.levels[a].height.total_cmp(&d.levels[b].height))
            .unwrap_or(0);
        let mut v = vec![d.governing_level - 1, top];
        v.dedup();
        v
    };
    let span = [0.5, n as f64 + 0.5];
    let width = 0.5 / levels.len().max(1) as f64;
    struct LevelLines {
        label: String,
        gap_label: String,
        stems: (Vec<f64>, Vec<f64>),
        design: [f64; 2],
        gap: [f64; 2],
        colour: usize,
    }
    let lines: Vec<LevelLines> = levels
        .iter()
        .enumerate()
        .map(|(j, &k)| {
            let l = &d.levels[k];
            let offset = (j as f64 - (levels.len() as f64 - 1.0) / 2.0) * width;
            let v: Vec<f64> = run
                .records
                .iter()
                .map(|r| r.report.levels[k].required_gap * 1e3)
                .collect();
            LevelLines {
                label: format!("L{}, h = {} m", l.level, l.height),
                gap_label: format!("gap L{}", l.level),
                stems: stems(&v, offset),
                design: [l.required * 1e3; 2],
                gap: [l.gap * 1e3; 2],
                colour: LEVEL_COLOURS[j % LEVEL_COLOURS.len()],
            }
        })
        .collect();
    let all_gaps_equal = levels
        .iter()
        .all(|&k| d.levels[k].gap == d.levels[levels[0]].gap);
    let mut sep = Vec::new();
    for l in &lines {
        sep.push(Series {
            label: &l.label,
            x: &l.stems.0,
            y: &l.stems.1,
            style: LineStyle::Solid,
            color: Some(l.colour),
        });
    }
    for l in &lines {
        sep.push(Series {
            label: "",
            x: &span,
            y: &l.design,
            style: LineStyle::Dashed,
            color: Some(l.colour),
        });
    }
    let one_gap;
    if all_gaps_equal {
        one_gap = format!("gap {:.0} mm", lines.first().map_or(0.0, |l| l.gap[0]));
        if let Some(l) = lines.first() {
            sep.push(Series {
                label: &one_gap,
                x: &span,
                y: &l.gap,
                style: LineStyle::Solid,
                color: Some(6),
            });
        }
    } else {
        for l in &lines {
            sep.push(Series {
                label: &l.gap_label,
                x: &span,
                y: &l.gap,
                style: LineStyle::Solid,
                color: Some(l.colour),
            });
        }
    }
    let forces: Vec<f64> = run
        .records
        .iter()
        .map(|r| r.report.contact.peak_force / 1e3)
        .collect();
    let force_stems = stems(&forces, 0.0);
    let force_design = run
        .statistics
        .0
        .iter()
        .find(|(k, _)| k == "peak_force")
        .map_or(f64::NAN, |(_, s)| s.design / 1e3);
    let force_line = [force_design; 2];
    let force_label = format!("{} = {:.0} kN", d.statistic.key(), force_design);
    let sep_title = format!(
        "required separation by the time history; dashed: the design value ({}) per level",
        d.statistic.key()
    );
    let panels = vec![
        Panel {
            title: &sep_title,
            y_label: "separation [mm]",
            series: sep,
            y_scale: AxisScale::Linear,
        },
        Panel {
            title: "peak contact force, largest over the levels",
            y_label: "force [kN]",
            series: vec![
                Series {
                    label: "per record",
                    x: &force_stems.0,
                    y: &force_stems.1,
                    style: LineStyle::Solid,
                    color: Some(4),
                },
                Series {
                    label: &force_label,
                    x: &span,
                    y: &force_line,
                    style: LineStyle::Dashed,
                    color: Some(4),
                },
            ],
            y_scale: AxisScale::Linear,
        },
    ];
    let g = &d.levels[d.governing_level - 1];
    let subtitle = format!(
        "{} records, design value = the {}; {} (governing level {}, h = {} m)",
        n,
        d.statistic.key(),
        if d.sufficient {
            "the gap suffices"
        } else {
            "the gap is too small"
        },
        g.level,
        g.height
    );
    let fig = Figure {
        title: "Record suite: required separation and peak force per record",
        subtitle: &subtitle,
        x_label: "record (as listed in the scenario)",
        panels,
        legend_once: false,
        width: 1100,
        height: 800,
    };
    write_figure(&fig, &dir.join("suite-records")).map_err(|e| e.to_string())
}

/// Every picture of a suite run, drawn into the directory given: the representative record's
/// run pictures ([`run_pictures`]), `suite-spectra` (with a scaling rule) and `suite-records`.
pub fn suite_pictures(run: &SuiteRun) -> Box<crate::output::run::DrawPictures<'_>> {
    Box::new(move |dir: &Path| {
        let rep = &run.records[run.representative];
        let mut files = run_pictures(&rep.scenario, &rep.report)(dir)?;
        match &run.scaling {
            Some(s) => {
                files.extend(
                    scaling_figure(s, &dir.join("suite-spectra")).map_err(|e| e.to_string())?,
                );
            }
            None => {
                for ext in ["png", "svg"] {
                    let _ = std::fs::remove_file(dir.join(format!("suite-spectra.{ext}")));
                }
            }
        }
        files.extend(records_figure(run, dir)?);
        Ok(files)
    })
}

/// Every picture of a suite run on a row of buildings, drawn into the directory given: the
/// representative record's row pictures ([`crate::figures::row::row_pictures`]) and
/// `suite-spectra` (with a scaling rule). No `suite-records` for a row yet (one left by an
/// earlier run is removed); each record's own row pictures are drawn in its folder by
/// [`row_suite_record_pictures`].
pub fn row_suite_pictures(
    run: &crate::study::suite::row::RowSuiteRun,
) -> Box<crate::output::run::DrawPictures<'_>> {
    Box::new(move |dir: &Path| {
        let rep = &run.records[run.representative];
        let mut files = crate::figures::row::row_pictures(&rep.scenario, &rep.report)(dir)?;
        match &run.scaling {
            Some(s) => {
                files.extend(
                    scaling_figure(s, &dir.join("suite-spectra")).map_err(|e| e.to_string())?,
                );
            }
            None => {
                for ext in ["png", "svg"] {
                    let _ = std::fs::remove_file(dir.join(format!("suite-spectra.{ext}")));
                }
            }
        }
        for ext in ["png", "svg"] {
            let _ = std::fs::remove_file(dir.join(format!("suite-records.{ext}")));
        }
        Ok(files)
    })
}

/// The row pictures of record `i` (0-based) of a row's suite run, for its own folder.
pub fn row_suite_record_pictures(
    run: &crate::study::suite::row::RowSuiteRun,
    i: usize,
) -> Box<crate::output::run::DrawPictures<'_>> {
    let r = &run.records[i];
    crate::figures::row::row_pictures(&r.scenario, &r.report)
}
