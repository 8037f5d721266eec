//! The figures a run produces, drawn with [`crate::plot`].

use std::path::{Path, PathBuf};

use crate::plot::{Figure, LineStyle, Panel, PlotError, Series, write_figure};
use crate::scenario::Scenario;
use crate::simulate::Report;

/// The time-history figure (the paper's Figs. 2–4, readable): displacement at the contact
/// height of each structure with and without pounding, and the contact force. Writes
/// `<stem>.png` and `<stem>.svg`.
pub fn time_history_figure(
    scenario: &Scenario,
    report: &Report,
    stem: &Path,
) -> Result<Vec<PathBuf>, PlotError> {
    let h = &report.with_contact.history;
    let f = &report.without_contact.history;
    let height = scenario.main_height();
    let titles = [0, 1].map(|i| {
        let name = &report.structures[i].name;
        let label = if *name == format!("structure {}", i + 1) {
            format!("Structure {}", i + 1)
        } else {
            format!("Structure {} ({name})", i + 1)
        };
        format!(
            "{label}: displacement at h = {height} m, change {:+.1} %",
            report.structures[i].change_percent
        )
    });
    let total: Vec<f64> = (0..h.t.len())
        .map(|i| h.force.iter().map(|c| c[i]).sum())
        .collect();
    let force_mn: Vec<f64> = total.iter().map(|x| x / 1e6).collect();
    let mut force_series = vec![Series {
        label: "total",
        x: &h.t,
        y: &force_mn,
        style: LineStyle::Solid,
    }];
    let per_level: Vec<(String, Vec<f64>)> = if h.force.len() > 1 {
        h.force
            .iter()
            .enumerate()
            .map(|(k, c)| {
                (
                    format!("h = {} m", scenario.contact.levels[k].height),
                    c.iter().map(|x| x / 1e6).collect(),
                )
            })
            .collect()
    } else {
        Vec::new()
    };
    for (label, y) in &per_level {
        force_series.push(Series {
            label,
            x: &h.t,
            y,
            style: LineStyle::Dashed,
        });
    }
    let force_title = format!(
        "Contact force: {} impacts, {} {:.3} MN",
        report.contact.impacts,
        if h.force.len() > 1 {
            "largest peak at one level"
        } else {
            "peak"
        },
        report.contact.peak_force / 1e6
    );
    let fig = Figure {
        title: &scenario.title,
        x_label: "time t [s]",
        panels: vec![
            Panel {
                title: &titles[0],
                y_label: "w1 [m]",
                series: vec![
                    Series {
                        label: "with pounding",
                        x: &h.t,
                        y: &h.w1,
                        style: LineStyle::Solid,
                    },
                    Series {
                        label: "without pounding",
                        x: &f.t,
                        y: &f.w1,
                        style: LineStyle::Dashed,
                    },
                ],
            },
            Panel {
                title: &titles[1],
                y_label: "w2 [m]",
                series: vec![
                    Series {
                        label: "with pounding",
                        x: &h.t,
                        y: &h.w2,
                        style: LineStyle::Solid,
                    },
                    Series {
                        label: "without pounding",
                        x: &f.t,
                        y: &f.w2,
                        style: LineStyle::Dashed,
                    },
                ],
            },
            Panel {
                title: &force_title,
                y_label: "F [MN]",
                series: force_series,
            },
        ],
        width: 1200,
        height: 900,
    };
    write_figure(&fig, stem)
}
