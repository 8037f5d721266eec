//! The figures a run produces, drawn with [`crate::plot`].

use std::path::{Path, PathBuf};

use crate::plot::{
    AxisScale, Figure, LineStyle, Panel, PlotError, ProfileFigure, ProfilePanel, ProfileSeries,
    Series, write_figure, write_profile,
};
use crate::recorder::Impact;
use crate::scenario::Scenario;
use crate::simulate::Report;

/// The contact force of one level as the time-history figure draws it, N: the history's
/// samples `(t, force)` merged with every impact's located start and end (force 0) and its peak
/// force (`Impact::peak_force`, located between the integration steps).
///
/// The history is sampled at the output interval (10 ms by default) while an impact lasts
/// 14–74 ms, so the samples alone miss most peaks; with the peaks added, the drawn maximum of a
/// level is its peak force at any output interval. The impact log gives each peak's value, not
/// its time: the peak is drawn at the largest sample inside the impact (within one output
/// interval of the true time), or at the impact's midpoint when no sample falls inside it.
/// `t` must be ascending; returns the times and forces, ascending in time.
pub fn drawn_force(
    t: &[f64],
    force: &[f64],
    impacts: &[Impact],
    level: usize,
) -> (Vec<f64>, Vec<f64>) {
    let n = t.len().min(force.len());
    let mut pts: Vec<(f64, f64)> = t
        .iter()
        .copied()
        .zip(force.iter().copied())
        .take(n)
        .collect();
    for i in impacts.iter().filter(|i| i.level == level) {
        let (a, b) = (
            t[..n].partition_point(|&s| s < i.start),
            t[..n].partition_point(|&s| s <= i.end),
        );
        let inside = (a..b).max_by(|&p, &q| force[p].total_cmp(&force[q]));
        let t_peak = inside.map_or(0.5 * (i.start + i.end), |k| t[k]);
        pts.extend([(i.start, 0.0), (t_peak, i.peak_force), (i.end, 0.0)]);
    }
    pts.sort_by(|p, q| p.0.total_cmp(&q.0));
    pts.into_iter().unzip()
}

/// The pictures of a run, as `pounding run` draws them into its directory: the time-history
/// figure (`history.png/.svg`, [`time_history_figure`]) and the envelopes over height
/// (`envelopes.png/.svg`, [`envelope_figure`]) and, with yielding storeys, the hysteresis loops
/// (`hysteresis.png/.svg`, [`hysteresis_figure`]; removed after an elastic run so that no stale
/// loops sit beside its summary); for [`crate::output::RunWriter::finish`].
pub fn run_pictures<'a>(
    scenario: &'a Scenario,
    report: &'a Report,
) -> Box<crate::output::DrawPictures<'a>> {
    Box::new(move |dir: &Path| {
        let mut files = time_history_figure(scenario, report, &dir.join("history"))
            .map_err(|e| e.to_string())?;
        files.extend(envelope_figure(report, &dir.join("envelopes")).map_err(|e| e.to_string())?);
        match hysteresis_figure(report, &dir.join("hysteresis")).map_err(|e| e.to_string())? {
            Some(f) => files.extend(f),
            // an elastic run: no stale loops beside its summary
            None => {
                for ext in ["png", "svg"] {
                    let _ = std::fs::remove_file(dir.join(format!("hysteresis.{ext}")));
                }
            }
        }
        Ok(files)
    })
}

/// The time-history figure (the paper's Figs. 2–4, readable): displacement at the contact
/// height of each structure with and without pounding, and the contact force of each level in a
/// panel of its own, every impact drawn at its located peak ([`drawn_force`]). Writes
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
    let forces: Vec<(String, Vec<f64>, Vec<f64>)> = (0..h.force.len())
        .map(|k| {
            let (t, n) = drawn_force(&h.t, &h.force[k], &report.impact_log, k);
            let (count, peak) = report
                .levels
                .get(k)
                .map_or((0, 0.0), |l| (l.impacts, l.peak_force));
            let at = if h.force.len() > 1 {
                format!(" at h = {} m", scenario.contact.levels[k].height)
            } else {
                String::new()
            };
            let title = format!(
                "Contact force{at}: {count} impacts, peak {:.3} MN (each impact drawn at its peak)",
                peak / 1e6
            );
            (title, t, n.iter().map(|x| x / 1e6).collect())
        })
        .collect();
    let displacement = |title, y_label, with: &'static str, a, b| Panel {
        title,
        y_label,
        series: vec![
            Series {
                label: with,
                x: &h.t,
                y: a,
                style: LineStyle::Solid,
            },
            Series {
                label: "without pounding",
                x: &f.t,
                y: b,
                style: LineStyle::Dashed,
            },
        ],
        y_scale: AxisScale::Linear,
    };
    let mut panels = vec![
        displacement(&titles[0], "w1 [m]", "with pounding", &h.w1, &f.w1),
        displacement(&titles[1], "w2 [m]", "with pounding", &h.w2, &f.w2),
    ];
    for (title, t, y) in &forces {
        panels.push(Panel {
            title,
            y_label: "F [MN]",
            series: vec![Series {
                label: "",
                x: t,
                y,
                style: LineStyle::Solid,
            }],
            y_scale: AxisScale::Linear,
        });
    }
    let extra = forces.len().saturating_sub(1) as u32;
    let fig = Figure {
        title: &scenario.title,
        subtitle: "",
        x_label: "time t [s]",
        panels,
        legend_once: true,
        width: 1200,
        height: 900 + 220 * extra.min(8),
    };
    write_figure(&fig, stem)
}

/// The envelopes over height (the figure of the pounding literature): peak displacement,
/// storey drift, absolute floor acceleration and storey shear of each structure at every floor
/// (a cantilever's stations), with pounding (solid) and without (dashed), floors up the page.
/// Writes `<stem>.png` and `<stem>.svg`.
pub fn envelope_figure(report: &Report, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    type Pick = fn(&crate::simulate::FloorReport) -> (f64, f64);
    let quantities: [(&str, &str, Pick); 4] = [
        ("Peak displacement", "u [m]", |f| {
            (f.peak_displacement, f.peak_displacement_no_contact)
        }),
        ("Peak storey drift", "drift [m]", |f| {
            (f.peak_drift, f.peak_drift_no_contact)
        }),
        ("Peak absolute acceleration", "a [m/s²]", |f| {
            (f.peak_acceleration, f.peak_acceleration_no_contact)
        }),
        ("Peak storey shear", "V [MN]", |f| {
            (f.peak_shear / 1e6, f.peak_shear_no_contact / 1e6)
        }),
    ];
    let heights: Vec<Vec<f64>> = report
        .structures
        .iter()
        .map(|s| s.floors.iter().map(|f| f.height).collect())
        .collect();
    // values[q][structure][with/without]
    let values: Vec<Vec<[Vec<f64>; 2]>> = quantities
        .iter()
        .map(|(_, _, pick)| {
            report
                .structures
                .iter()
                .map(|s| {
                    let (a, b): (Vec<f64>, Vec<f64>) = s.floors.iter().map(pick).unzip();
                    [a, b]
                })
                .collect()
        })
        .collect();
    let labels: Vec<[String; 2]> = report
        .structures
        .iter()
        .map(|s| {
            [
                format!("{}, with pounding", s.name),
                format!("{}, without", s.name),
            ]
        })
        .collect();
    let mut panels: Vec<ProfilePanel> = quantities
        .iter()
        .zip(&values)
        .enumerate()
        .map(|(q, ((title, x_label, _), v))| ProfilePanel {
            title,
            x_label,
            // displacements start from the fixed base; storey quantities and absolute
            // accelerations have no value there to draw
            base: (q == 0).then_some(0.0),
            series: (0..report.structures.len())
                .flat_map(|i| {
                    [(0, LineStyle::Solid), (1, LineStyle::Dashed)].map(|(k, style)| {
                        ProfileSeries {
                            label: &labels[i][k],
                            values: &v[i][k],
                            heights: &heights[i],
                            style,
                            color: i,
                        }
                    })
                })
                .collect(),
        })
        .collect();
    // yielding buildings (issue 16): the peak ductility demand of every storey
    let ductility: Vec<[Vec<f64>; 2]> = report
        .structures
        .iter()
        .map(|s| {
            let (a, b): (Vec<f64>, Vec<f64>) = s
                .floors
                .iter()
                .filter_map(|f| Some((f.peak_ductility?, f.peak_ductility_no_contact?)))
                .unzip();
            [a, b]
        })
        .collect();
    if ductility.iter().any(|d| !d[0].is_empty()) {
        panels.push(ProfilePanel {
            title: "Peak ductility demand",
            x_label: "μ = |drift|/d_y",
            base: None,
            series: (0..report.structures.len())
                .filter(|&i| !ductility[i][0].is_empty())
                .flat_map(|i| {
                    [(0, LineStyle::Solid), (1, LineStyle::Dashed)].map(|(k, style)| {
                        ProfileSeries {
                            label: &labels[i][k],
                            values: &ductility[i][k],
                            heights: &heights[i],
                            style,
                            color: i,
                        }
                    })
                })
                .collect(),
        });
    }
    let width = 400 * panels.len() as u32;
    let fig = ProfileFigure {
        title: &report.title,
        subtitle: "envelopes over height: peaks at every floor (a cantilever: every tenth of its height and each contact height)",
        y_label: "height [m]",
        panels,
        width,
        height: 700,
    };
    write_profile(&fig, stem)
}

/// The hysteresis loops of a run with yielding storeys (issue 16): for each yielding building,
/// the storey force against the drift of its most demanded storey (largest peak ductility with
/// pounding), with pounding (solid) and without (dashed), sampled at the output interval.
/// `Ok(None)` when no storey yields.
pub fn hysteresis_figure(report: &Report, stem: &Path) -> Result<Option<Vec<PathBuf>>, PlotError> {
    let (with, without) = (
        &report.with_contact.storeys,
        &report.without_contact.storeys,
    );
    if with.is_empty() {
        return Ok(None);
    }
    // per building: the most demanded storey's (drift mm, force MN) with and without pounding
    let mut loops: Vec<(String, [Vec<f64>; 4])> = Vec::new();
    for i in 0..2 {
        let Some((k, r)) = with
            .iter()
            .enumerate()
            .filter(|(_, r)| r.structure == i)
            .max_by(|a, b| a.1.peak_ductility().total_cmp(&b.1.peak_ductility()))
        else {
            continue;
        };
        let free = &without[k];
        let split = |pts: &[[f64; 2]]| -> (Vec<f64>, Vec<f64>) {
            pts.iter().map(|p| (p[0] * 1e3, p[1] / 1e6)).unzip()
        };
        let (dx, vy) = split(&r.loop_points);
        let (fx, fy) = split(&free.loop_points);
        let title = format!(
            "Structure {}, {}: storey {}, μ = {:.2} with pounding, {:.2} without; residual drift {:.1} / {:.1} mm",
            i + 1,
            report.structures[i].name,
            r.storey + 1,
            r.peak_ductility(),
            free.peak_ductility(),
            r.residual_drift * 1e3,
            free.residual_drift * 1e3
        );
        loops.push((title, [dx, vy, fx, fy]));
    }
    let panels = loops
        .iter()
        .map(|(title, v)| Panel {
            title,
            y_label: "storey force V [MN]",
            series: vec![
                Series {
                    label: "with pounding",
                    x: &v[0],
                    y: &v[1],
                    style: LineStyle::Solid,
                },
                Series {
                    label: "without",
                    x: &v[2],
                    y: &v[3],
                    style: LineStyle::Dashed,
                },
            ],
            y_scale: AxisScale::Linear,
        })
        .collect::<Vec<_>>();
    let n = panels.len() as u32;
    let fig = Figure {
        title: &report.title,
        subtitle: "hysteresis loops: Bouc–Wen storey force against inter-storey drift of each building's most demanded storey",
        x_label: "inter-storey drift [mm]",
        panels,
        legend_once: false,
        width: 1100,
        height: 120 + 420 * n,
    };
    write_figure(&fig, stem).map(Some)
}
