//! The figures a run produces, drawn with [`crate::plot`].

use std::path::{Path, PathBuf};

use crate::analysis::simulate::Report;
use crate::input::scenario::Scenario;
use crate::plot::{
    AxisScale, Figure, LineStyle, Panel, PlotError, ProfileFigure, ProfilePanel, ProfileSeries,
    Series, write_figure, write_profile,
};
use crate::recording::run_record::Impact;

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

/// Draws `here` on this thread while `other` (an independent figure) is drawn on a second
/// one, named `envelopes`; a panic there is an error, and without a thread to be had `other`
/// is drawn after `here`, on this one. For [`run_pictures`] and
/// [`super::row::row_pictures`]: a user's run waits for the longer figure, not the sum.
pub(crate) fn beside_each_other<T: Send>(
    here: impl FnOnce() -> Result<T, PlotError>,
    other: impl FnOnce() -> Result<T, PlotError> + Send + Copy,
) -> (Result<T, PlotError>, Result<T, PlotError>) {
    std::thread::scope(|scope| {
        let spawned = std::thread::Builder::new()
            .name("envelopes".into())
            .spawn_scoped(scope, other);
        let first = here();
        let second = match spawned {
            Ok(handle) => handle.join().unwrap_or_else(|_| {
                Err(PlotError::Draw(
                    "internal error (panic) in the plotting code".into(),
                ))
            }),
            Err(_) => other(),
        };
        (first, second)
    })
}

/// The pictures of a run, as `pounding run` draws them into its directory: the time-history
/// figure (`history.png/.svg`, [`time_history_figure`]) and the envelopes over height
/// (`envelopes.png/.svg`, [`envelope_figure`]) and, with yielding storeys, the hysteresis loops
/// (`hysteresis.png/.svg`, [`hysteresis_figure`]; removed after an elastic run so that no stale
/// loops sit beside its summary); for [`crate::output::writer::RunWriter::finish`].
pub fn run_pictures<'a>(
    scenario: &'a Scenario,
    report: &'a Report,
) -> Box<crate::output::run::DrawPictures<'a>> {
    Box::new(move |dir: &Path| {
        // the two figures are independent: the envelopes are drawn on a second thread while
        // the time histories are drawn here (a user's run waits for the longer, not the sum)
        let envelopes = || envelope_figure(report, &dir.join("envelopes"));
        let (history, envelopes) = beside_each_other(
            || time_history_figure(scenario, report, &dir.join("history")),
            envelopes,
        );
        let mut files = history.map_err(|e| e.to_string())?;
        files.extend(envelopes.map_err(|e| e.to_string())?);
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

/// Palette index of structure 1 and 2 in every figure of a run (blue, vermillion): a colour
/// means a structure; with pounding is solid, without dashed.
pub const STRUCTURE_COLORS: [usize; 2] = [0, 1];

/// Palette index of the contact force (black): it acts on both structures.
pub const FORCE_COLOR: usize = 6;

/// "Structure 1" or "Structure 1, A (4 storeys)" for a named structure.
fn structure_label(report: &Report, i: usize) -> String {
    let name = &report.structures[i].name;
    if *name == format!("structure {}", i + 1) {
        format!("Structure {}", i + 1)
    } else {
        format!("Structure {}, {name}", i + 1)
    }
}

/// The time-history figure (the paper's Figs. 2–4, readable): the displacement `w` at the
/// (highest) contact height of each structure with pounding (solid) and without (dashed), in
/// the structure's colour ([`STRUCTURE_COLORS`]), and the contact force of each level where
/// impacts occurred in a panel of its own ([`FORCE_COLOR`]), every impact drawn at its located
/// peak ([`drawn_force`]). Writes `<stem>.png` and `<stem>.svg`.
pub fn time_history_figure(
    scenario: &Scenario,
    report: &Report,
    stem: &Path,
) -> Result<Vec<PathBuf>, PlotError> {
    let h = &report.with_contact.history;
    let f = &report.without_contact.history;
    let height = scenario.main_height();
    let titles = [0, 1].map(|i| {
        format!(
            "{}: displacement w{} at h = {height} m, change of the peak {:+.1} %",
            structure_label(report, i),
            i + 1,
            report.structures[i].change_percent
        )
    });
    let impacts = |k: usize| report.levels.get(k).map_or(0, |l| l.impacts);
    let several = h.force.len() > 1;
    // levels without an impact get no panel (named in the subtitle), unless none had one
    let drawn: Vec<usize> = (0..h.force.len())
        .filter(|&k| impacts(k) > 0 || (0..h.force.len()).all(|j| impacts(j) == 0) && k == 0)
        .collect();
    let quiet: Vec<String> = (0..h.force.len())
        .filter(|k| !drawn.contains(k))
        .map(|k| format!("{} m", scenario.contact.levels[k].height))
        .collect();
    let subtitle = if quiet.is_empty() {
        String::new()
    } else {
        format!("no impact at h = {}", quiet.join(", "))
    };
    let forces: Vec<(String, Vec<f64>, Vec<f64>)> = drawn
        .iter()
        .map(|&k| {
            let (t, n) = drawn_force(&h.t, &h.force[k], &report.impact_log, k);
            let peak = report.levels.get(k).map_or(0.0, |l| l.peak_force);
            let at = if several {
                format!(" at h = {} m", scenario.contact.levels[k].height)
            } else {
                String::new()
            };
            let count = match impacts(k) {
                1 => "1 impact".to_string(),
                n => format!("{n} impacts"),
            };
            let title = format!(
                "Contact force{at}: {count}, peak {:.3} MN (each impact drawn at its peak)",
                peak / 1e6
            );
            (title, t, n.iter().map(|x| x / 1e6).collect())
        })
        .collect();
    let y_labels = ["w1 [m]", "w2 [m]"];
    let displacement = |i: usize, a, b| Panel {
        title: &titles[i],
        y_label: y_labels[i],
        series: vec![
            Series {
                label: "with pounding",
                x: &h.t,
                y: a,
                style: LineStyle::Solid,
                color: Some(STRUCTURE_COLORS[i]),
            },
            Series {
                label: "without pounding",
                x: &f.t,
                y: b,
                style: LineStyle::Dashed,
                color: Some(STRUCTURE_COLORS[i]),
            },
        ],
        y_scale: AxisScale::Linear,
    };
    let mut panels = vec![displacement(0, &h.w1, &f.w1), displacement(1, &h.w2, &f.w2)];
    for (title, t, y) in &forces {
        panels.push(Panel {
            title,
            y_label: "F [MN]",
            series: vec![Series {
                label: "",
                x: t,
                y,
                style: LineStyle::Solid,
                color: Some(FORCE_COLOR),
            }],
            y_scale: AxisScale::Linear,
        });
    }
    let extra = forces.len().saturating_sub(1) as u32;
    let fig = Figure {
        title: &scenario.title,
        subtitle: &subtitle,
        x_label: "time t [s]",
        panels,
        // each displacement panel's legend in its structure's colour
        legend_once: false,
        width: 1200,
        height: 900 + 220 * extra.min(8),
    };
    write_figure(&fig, stem)
}

/// The envelopes over height (the figure of the pounding literature): peak displacement `w`,
/// storey drift ratio (%, [`crate::analysis::simulate::StructureReport::peak_drift_ratios`]), absolute
/// floor acceleration and storey shear of each structure at every floor (a cantilever's
/// stations), in the structure's colour ([`STRUCTURE_COLORS`]), with pounding (solid) and
/// without (dashed), floors up the page. A floor whose peak acceleration with pounding came
/// during an impact is drawn as a ring and the subtitle says what it is: the impact's pulse,
/// lasting as long as the contact (`FloorReport::peak_acceleration_impact`). Writes
/// `<stem>.png` and `<stem>.svg`.
pub fn envelope_figure(report: &Report, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    type Pick = fn(&crate::analysis::simulate::StructureReport) -> Vec<[f64; 2]>;
    let quantities: [(&str, &str, Pick); 4] = [
        ("Peak displacement w", "w [m]", |s| {
            (s.floors.iter())
                .map(|f| [f.peak_displacement, f.peak_displacement_no_contact])
                .collect()
        }),
        (
            "Peak storey drift ratio",
            "drift / storey height [%]",
            |s| s.peak_drift_ratios(),
        ),
        ("Peak absolute acceleration", "a [m/s²]", |s| {
            (s.floors.iter())
                .map(|f| [f.peak_acceleration, f.peak_acceleration_no_contact])
                .collect()
        }),
        ("Peak storey shear", "V [MN]", |s| {
            (s.floors.iter())
                .map(|f| [f.peak_shear / 1e6, f.peak_shear_no_contact / 1e6])
                .collect()
        }),
    ];
    const ACCELERATION: usize = 2;
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
                    let (a, b): (Vec<f64>, Vec<f64>) =
                        pick(s).into_iter().map(|[a, b]| (a, b)).unzip();
                    [a, b]
                })
                .collect()
        })
        .collect();
    // the floors whose peak acceleration with pounding is an impact's pulse
    let pulses: Vec<Vec<bool>> = report
        .structures
        .iter()
        .map(|s| {
            (s.floors.iter())
                .map(|f| f.peak_acceleration_impact.is_some())
                .collect()
        })
        .collect();
    let durations: Vec<f64> = (report.structures.iter())
        .flat_map(|s| s.floors.iter())
        .filter_map(|f| f.peak_acceleration_impact.map(|p| p.duration))
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
    let no_rings: &[bool] = &[];
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
                            color: STRUCTURE_COLORS[i],
                            rings: if q == ACCELERATION && k == 0 {
                                &pulses[i]
                            } else {
                                no_rings
                            },
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
                            color: STRUCTURE_COLORS[i],
                            rings: no_rings,
                        }
                    })
                })
                .collect(),
        });
    }
    let stations = if durations.is_empty() {
        "peaks at every floor (a cantilever: every tenth of its height and each contact height)"
            .to_string()
    } else {
        let (lo, hi) = durations
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &d| {
                (lo.min(d), hi.max(d))
            });
        let lasting = if hi - lo < 0.05e-3 {
            format!("{:.1} ms", hi * 1e3)
        } else {
            format!("{:.1}–{:.1} ms", lo * 1e3, hi * 1e3)
        };
        format!(
            "peaks at every floor; ○ an acceleration with pounding that peaks during an impact: \
             the impact's pulse ({lasting}), not a design floor acceleration"
        )
    };
    let width = 400 * panels.len() as u32;
    let fig = ProfileFigure {
        title: &report.title,
        subtitle: &stations,
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
    let mut loops: Vec<(usize, String, [Vec<f64>; 4])> = Vec::new();
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
            "{}: storey {}, μ = {:.2} with pounding, {:.2} without; residual drift {:.1} / {:.1} mm",
            structure_label(report, i),
            r.storey + 1,
            r.peak_ductility(),
            free.peak_ductility(),
            r.residual_drift * 1e3,
            free.residual_drift * 1e3
        );
        loops.push((i, title, [dx, vy, fx, fy]));
    }
    let panels = loops
        .iter()
        .map(|(i, title, v)| Panel {
            title,
            y_label: "storey force V [MN]",
            series: vec![
                Series {
                    label: "with pounding",
                    x: &v[0],
                    y: &v[1],
                    style: LineStyle::Solid,
                    color: Some(STRUCTURE_COLORS[*i]),
                },
                Series {
                    label: "without",
                    x: &v[2],
                    y: &v[3],
                    style: LineStyle::Dashed,
                    color: Some(STRUCTURE_COLORS[*i]),
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
