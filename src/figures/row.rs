//! The pictures of a row of buildings' run (issue 29), drawn with [`crate::plot`]:
//! `envelopes.png/.svg` — every building's peak displacement over its height with and without
//! pounding, side by side in row order on one height axis and one displacement axis — and
//! `history.png/.svg` — for each adjacent pair, the two buildings' displacement histories at
//! the pair's governing level and the pair's contact forces.

use std::path::{Path, PathBuf};

use crate::analysis::simulate::row_history::RowHistory;
use crate::analysis::simulate::{RowReport, StructureReport};
use crate::input::scenario::Scenario;
use crate::plot::{
    AxisScale, Figure, LineStyle, Panel, PlotError, ProfileFigure, ProfilePanel, ProfileSeries,
    Series, write_figure, write_profile,
};

/// Palette indices a building's colour cycles through (the palette without black, which is
/// the contact force's, yellow, too pale on white, and sky blue, too close to blue): five
/// colours in turn, so that neighbours — also across the wrap, orange then blue — contrast.
const BUILDING_COLORS: [usize; 5] = [0, 1, 2, 3, 4];

/// Building `i`'s palette index.
pub fn building_color(i: usize) -> usize {
    BUILDING_COLORS[i % BUILDING_COLORS.len()]
}

/// The pictures of a row, as `pounding run` draws them into its directory (the envelopes on
/// a second thread while the histories are drawn here); removes a pair's `hysteresis.png/.svg`
/// an earlier run left. For [`crate::output::writer::RunWriter::finish`].
pub fn row_pictures<'a>(
    scenario: &'a Scenario,
    report: &'a RowReport,
) -> Box<crate::output::run::DrawPictures<'a>> {
    Box::new(move |dir: &Path| {
        let envelopes = || row_envelope_figure(report, &dir.join("envelopes"));
        let (history, envelopes) = super::run::beside_each_other(
            || row_history_figure(scenario, report, &dir.join("history")),
            envelopes,
        );
        let mut files = history.map_err(|e| e.to_string())?;
        files.extend(envelopes.map_err(|e| e.to_string())?);
        for ext in ["png", "svg"] {
            let _ = std::fs::remove_file(dir.join(format!("hysteresis.{ext}")));
        }
        Ok(files)
    })
}

/// "B8 (28 m)": the name and the height of the top station.
fn building_title(s: &StructureReport) -> String {
    match s.floors.last() {
        Some(top) => format!("{} ({} m)", s.name, top.height),
        None => s.name.clone(),
    }
}

/// The row's envelopes: one panel per building in row order, its peak displacement at every
/// floor (a cantilever's stations) with pounding (solid) and without (dashed), all panels on
/// the same height and displacement scales so that the buildings compare at a glance; each
/// panel's title gives the change of the building's headline peak. Writes `<stem>.png` and
/// `<stem>.svg`.
pub fn row_envelope_figure(report: &RowReport, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let n = report.structures.len();
    let heights: Vec<Vec<f64>> = (report.structures.iter())
        .map(|s| s.floors.iter().map(|f| f.height).collect())
        .collect();
    let values: Vec<[Vec<f64>; 2]> = (report.structures.iter())
        .map(|s| {
            let (a, b) = (s.floors.iter())
                .map(|f| (f.peak_displacement, f.peak_displacement_no_contact))
                .unzip();
            [a, b]
        })
        .collect();
    let x_max = values
        .iter()
        .flat_map(|v| v.iter().flatten().copied())
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    // the same displacement scale in every panel: an undrawn point at the largest peak
    let scale = [x_max];
    let nowhere = [f64::NAN];
    let titles: Vec<String> = (report.structures.iter())
        .map(|s| format!("{}: {:+.0} %", building_title(s), s.change_percent))
        .collect();
    let panels: Vec<ProfilePanel> = (0..n)
        .map(|i| ProfilePanel {
            title: &titles[i],
            x_label: "peak w [m]",
            base: Some(0.0),
            series: vec![
                ProfileSeries {
                    label: "with pounding",
                    values: &values[i][0],
                    heights: &heights[i],
                    style: LineStyle::Solid,
                    color: building_color(i),
                    rings: &[],
                },
                ProfileSeries {
                    label: "without pounding",
                    values: &values[i][1],
                    heights: &heights[i],
                    style: LineStyle::Dashed,
                    color: building_color(i),
                    rings: &[],
                },
                ProfileSeries {
                    label: "",
                    values: &scale,
                    heights: &nowhere,
                    style: LineStyle::Solid,
                    color: building_color(i),
                    rings: &[],
                },
            ],
        })
        .collect();
    let subtitle = "peak displacement at every floor, buildings in row order (left to right); \
                    in each title the change of its peak at its highest contact level";
    let fig = ProfileFigure {
        title: &report.title,
        subtitle,
        y_label: "height [m]",
        panels,
        width: (300 * n as u32).max(1000),
        height: 700,
    };
    write_profile(&fig, stem)
}

/// The contact level of pair `p` whose displacements the history figure draws: the level of
/// the pair's governing rule (smallest margin), else its highest level; an index into the
/// system's levels (pair by pair).
pub fn drawn_level(report: &RowReport, p: usize) -> Option<usize> {
    let first: usize = report.pairs[..p].iter().map(|q| q.levels.len()).sum();
    let pair = &report.pairs[p];
    let highest = (0..pair.levels.len()).fold(None, |b: Option<usize>, k| match b {
        Some(b) if pair.levels[k].height <= pair.levels[b].height => Some(b),
        _ => Some(k),
    })?;
    let governing = pair.separation.verdict.governing.as_ref().and_then(|g| {
        (0..pair.levels.len()).find(|&k| (pair.levels[k].height - g.height).abs() <= 1e-9)
    });
    Some(first + governing.unwrap_or(highest))
}

/// The row's time histories: for each adjacent pair (row order), a panel of the two
/// buildings' displacements at the pair's governing level ([`drawn_level`]) with pounding
/// (solid) and without (dashed), each building in its colour ([`building_color`]), and a panel
/// of the pair's contact force at each of its levels, every impact drawn at its located peak
/// ([`crate::figures::run::drawn_force`]). Writes `<stem>.png` and `<stem>.svg`.
pub fn row_history_figure(
    scenario: &Scenario,
    report: &RowReport,
    stem: &Path,
) -> Result<Vec<PathBuf>, PlotError> {
    let (h, f) = (&report.history, &report.history_no_contact);
    let forces = &report.with_contact.history;
    let mut first = 0;
    // per pair: (title, labels, [left with, left without, right with, right without])
    struct PairLines {
        title: String,
        labels: [String; 4],
        k: usize,
        force_title: String,
        force_labels: Vec<String>,
        force: Vec<(Vec<f64>, Vec<f64>)>,
    }
    let mut pairs = Vec::new();
    for (p, pair) in report.pairs.iter().enumerate() {
        let range = first..first + pair.levels.len();
        first = range.end;
        let Some(k) = drawn_level(report, p) else {
            continue;
        };
        let lv = &pair.levels[k - range.start];
        let [l, r] = &pair.between;
        let why = if pair.separation.verdict.governing.is_some() {
            "its governing level"
        } else {
            "its highest level"
        };
        let title = format!(
            "{l}–{r}: displacement at h = {} m ({why}; gap {:.0} mm)",
            lv.height,
            lv.gap * 1e3
        );
        let labels = [
            format!("{l}, with pounding"),
            format!("{l}, without"),
            format!("{r}, with pounding"),
            format!("{r}, without"),
        ];
        let count = match pair.contact.impacts {
            1 => "1 impact".to_string(),
            n => format!("{n} impacts"),
        };
        let force_title = format!(
            "{l}–{r}: contact force, {count}, peak {:.3} MN (each impact drawn at its peak)",
            pair.contact.peak_force / 1e6
        );
        let several = pair.levels.len() > 1;
        let force_labels = (range.clone())
            .map(|j| {
                if several {
                    format!("h = {} m", report.pairs[p].levels[j - range.start].height)
                } else {
                    String::new()
                }
            })
            .collect();
        let force = (range.clone())
            .map(|j| {
                let empty = Vec::new();
                let series = forces.force.get(j).unwrap_or(&empty);
                let (t, y) = crate::figures::run::drawn_force(
                    &forces.t,
                    series,
                    &report.with_contact.impacts,
                    j,
                );
                (t, y.iter().map(|x| x / 1e6).collect())
            })
            .collect();
        pairs.push(PairLines {
            title,
            labels,
            k,
            force_title,
            force_labels,
            force,
        });
    }
    fn col(hist: &RowHistory, k: usize, side: usize) -> &[f64] {
        hist.levels.get(k).map_or(&[], |c| &c[side])
    }
    let mut panels = Vec::new();
    for (p, lines) in pairs.iter().enumerate() {
        let colors = [building_color(p), building_color(p + 1)];
        let mut series = Vec::new();
        for (side, &color) in colors.iter().enumerate() {
            series.push(Series {
                label: &lines.labels[2 * side],
                x: &h.t,
                y: col(h, lines.k, side),
                style: LineStyle::Solid,
                color: Some(color),
            });
            series.push(Series {
                label: &lines.labels[2 * side + 1],
                x: &f.t,
                y: col(f, lines.k, side),
                style: LineStyle::Dashed,
                color: Some(color),
            });
        }
        panels.push(Panel {
            title: &lines.title,
            y_label: "w [m]",
            series,
            y_scale: AxisScale::Linear,
        });
        panels.push(Panel {
            title: &lines.force_title,
            y_label: "F [MN]",
            series: (lines.force.iter().zip(&lines.force_labels))
                .enumerate()
                .map(|(j, ((t, y), label))| Series {
                    label,
                    x: t,
                    y,
                    style: LineStyle::Solid,
                    // the first level in black, as a pair's force; further ones in sky blue,
                    // orange, purple
                    color: Some([6, 5, 4, 3][j % 4]),
                })
                .collect(),
            y_scale: AxisScale::Linear,
        });
    }
    if panels.is_empty() {
        return Err(PlotError::NoData("a row without contact levels".into()));
    }
    let subtitle =
        "each adjacent pair: the displacements where its gap governs, its contact forces";
    let n = panels.len() as u32;
    let fig = Figure {
        title: &scenario.title,
        subtitle,
        x_label: "time t [s]",
        panels,
        legend_once: false,
        width: 1400,
        height: (160 + 340 * n).min(16_000),
    };
    write_figure(&fig, stem)
}
