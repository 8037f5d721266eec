//! The pictures tell the truth: the time-history figure draws every impact at its peak force,
//! and the heatmap colour scales follow their formulas.

use std::path::Path;

use pounding::analysis::simulate::{Report, simulate};
use pounding::figures::run::{
    drawn_force, envelope_figure, hysteresis_figure, time_history_figure,
};
use pounding::figures::sweep::{RATIO_LIMIT, axis_label, field_scale};
use pounding::input::scenario::Scenario;
use pounding::plot::ColorScale;
use pounding::plot::style::{
    NO_DATA, RATIO_HIGH, RATIO_LOW, RATIO_NEUTRAL, ratio_color, ratio_position, viridis,
};

fn run(file: &str, output_interval: Option<f64>) -> (Scenario, Report) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let mut scenario = Scenario::from_file(&path).unwrap();
    if let Some(dt) = output_interval {
        scenario.output_interval = dt;
    }
    let report = simulate(&scenario).unwrap();
    (scenario, report)
}

/// The largest value of a series (NaN-free by construction).
fn max(y: &[f64]) -> f64 {
    y.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// Every impact of `level` appears at its peak force inside its own interval, and the level's
/// drawn maximum is the level's reported peak force.
fn check_level(report: &Report, level: usize) -> f64 {
    let h = &report.with_contact.history;
    let (t, f) = drawn_force(&h.t, &h.force[level], &report.impact_log, level);
    assert!(t.windows(2).all(|w| w[0] <= w[1]), "times not ascending");
    for i in report.impact_log.iter().filter(|i| i.level == level) {
        assert!(
            t.iter()
                .zip(&f)
                .any(|(&tk, &fk)| fk == i.peak_force && tk >= i.start && tk <= i.end),
            "impact at {} s (peak {} N) is not drawn at its peak",
            i.start,
            i.peak_force
        );
    }
    assert_eq!(max(&f), report.levels[level].peak_force);
    max(&f)
}

#[test]
fn the_force_panel_shows_every_impact_at_its_peak() {
    // the default scenario (paper case c, 81 impacts of 14–74 ms) at the default 10 ms output
    // interval, a coarser 50 ms and a finer 2 ms one
    for dt in [None, Some(0.05), Some(0.002)] {
        let (_, report) = run("examples/paper-c.toml", dt);
        assert!(report.contact.impacts > 50);
        let h = &report.with_contact.history;
        // the samples alone understate the peak (what the figure used to draw)
        if dt != Some(0.002) {
            assert!(max(&h.force[0]) < 0.95 * report.contact.peak_force);
        }
        assert_eq!(check_level(&report, 0), report.contact.peak_force);
    }
}

#[test]
fn two_levels_each_drawn_to_its_own_peak() {
    let (scenario, report) = run("examples/two-levels.toml", None);
    assert_eq!(report.levels.len(), 2);
    let peaks: Vec<f64> = (0..2).map(|k| check_level(&report, k)).collect();
    assert_eq!(max(&peaks), report.contact.peak_force);
    // and the figure is written (one force panel per level)
    let dir = tempfile::tempdir().unwrap();
    let files = time_history_figure(&scenario, &report, &dir.path().join("history")).unwrap();
    assert_eq!(files.len(), 2);
    let svg = std::fs::read_to_string(&files[1]).unwrap();
    assert!(svg.contains("Contact force at h = 10 m") && svg.contains("Contact force at h = 6 m"));
}

#[test]
fn amplification_colours_follow_the_log_ratio() {
    let l = RATIO_LIMIT;
    assert_eq!(l, 10.0);
    // centre, ends, saturation beyond them
    assert_eq!(ratio_position(1.0, l), Some(0.5));
    assert_eq!(ratio_position(10.0, l), Some(1.0));
    assert_eq!(ratio_position(0.1, l), Some(0.0));
    assert_eq!(ratio_position(1e3, l), Some(1.0));
    assert_eq!(ratio_position(1e-3, l), Some(0.0));
    assert_eq!(ratio_position(f64::INFINITY, l), Some(1.0));
    assert_eq!(ratio_position(0.0, l), Some(0.0));
    // ½ + ½·log10(r)/log10(limit): √10 is three quarters up, and r, 1/r are mirror images
    assert!((ratio_position(10f64.sqrt(), l).unwrap() - 0.75).abs() < 1e-15);
    for r in [1.1, 1.5, 2.0, 3.0, 5.0, 9.9] {
        let (up, down) = (
            ratio_position(r, l).unwrap(),
            ratio_position(1.0 / r, l).unwrap(),
        );
        assert!((up + down - 1.0).abs() < 1e-12, "r = {r}");
        assert!(up > 0.5 && up < 1.0);
    }
    // another limit: ×0.01 … ×100
    assert_eq!(ratio_position(100.0, 100.0), Some(1.0));
    assert_eq!(ratio_position(10.0, 100.0), Some(0.75));
    // no colour for what is not a ratio
    assert_eq!(ratio_position(f64::NAN, l), None);
    assert_eq!(ratio_position(-1.0, l), None);
    // the colours at the centre and the ends
    assert_eq!(ratio_color(1.0, l), RATIO_NEUTRAL);
    assert_eq!(ratio_color(10.0, l), RATIO_HIGH);
    assert_eq!(ratio_color(50.0, l), RATIO_HIGH);
    assert_eq!(ratio_color(0.1, l), RATIO_LOW);
    assert_eq!(ratio_color(0.02, l), RATIO_LOW);
    assert_eq!(ratio_color(f64::NAN, l), NO_DATA);
    // amplification is red (more red than blue), reduction blue
    let (a, r) = (ratio_color(2.0, l), ratio_color(0.5, l));
    assert!(a.0 > a.2 && r.2 > r.0, "{a:?} {r:?}");
}

#[test]
fn one_scale_per_quantity() {
    // the change of either structure's peak is always the ratio scale, whatever the data
    for f in ["change_percent_1", "change_percent_2"] {
        assert_eq!(
            field_scale(f, &[1.0, 1.01]),
            ColorScale::Ratio { limit: 10.0 }
        );
    }
    // more than a factor of 100 between the positive values: logarithmic; zeros do not count
    assert_eq!(field_scale("peak_force", &[1.0, 101.0]), ColorScale::Log);
    assert_eq!(
        field_scale("peak_force", &[0.0, 2.0, 300.0, f64::NAN]),
        ColorScale::Log
    );
    assert_eq!(
        field_scale("sep_time_history", &[1.0, 99.0]),
        ColorScale::Linear
    );
    assert_eq!(
        field_scale("impacts", &[0.0, 10.0, 97.0]),
        ColorScale::Linear
    );
    // viridis' documented ends
    assert_eq!(viridis(0.0), plotters::style::RGBColor(68, 1, 84));
    assert_eq!(viridis(1.0), plotters::style::RGBColor(254, 232, 37));
}

#[test]
fn axes_are_named_as_on_the_command_line() {
    assert_eq!(axis_label("period_ratio"), "T1/T2 (period_ratio)");
    assert_eq!(
        axis_label("ground_period_ratio"),
        "T2/Tg (ground_period_ratio)"
    );
    assert_eq!(
        axis_label("ground_motion.pga"),
        "PGA [g] (ground_motion.pga)"
    );
    assert_eq!(
        axis_label("structure.2.period"),
        "T2 [s] (structure.2.period)"
    );
    assert_eq!(axis_label("contact.stiffness"), "contact.stiffness");
}

/// Colours of the lines drawn 2 px wide (data and legend samples) in drawing order, each with
/// the legend text that follows it: `(stroke, Some(label))` for a legend sample.
fn strokes(svg: &str) -> Vec<(String, Option<String>)> {
    let mut out: Vec<(String, Option<String>)> = Vec::new();
    for part in svg.split('<').skip(1) {
        if part.starts_with("polyline") && part.contains("stroke-width=\"2\"") {
            let c = part.split("stroke=\"").nth(1).unwrap();
            out.push((c[..7].to_string(), None));
        } else if part.starts_with("text") {
            let label = part.split('>').nth(1).unwrap_or("").trim().to_string();
            if let Some(last) = out.last_mut().filter(|l| l.1.is_none()) {
                last.1 = Some(label);
            }
        }
    }
    out
}

const BLUE: &str = "#0072B2";
const VERMILLION: &str = "#D55E00";
const BLACK: &str = "#000000";

/// One meaning per colour in every figure of a run: structure 1 blue, structure 2 vermillion
/// (with pounding solid, without dashed), the contact force black; the history figure's
/// panels are drawn in that order, and each legend sample has its structure's colour.
#[test]
fn a_colour_means_a_structure_in_every_figure() {
    let (scenario, report) = run("examples/default.toml", None);
    let dir = tempfile::tempdir().unwrap();
    let svg = |files: Vec<std::path::PathBuf>| std::fs::read_to_string(&files[1]).unwrap();
    // history: w1 panel (blue), w2 panel (vermillion), then the force panels (black)
    let history = svg(time_history_figure(&scenario, &report, &dir.path().join("h")).unwrap());
    let lines = strokes(&history);
    let mut runs: Vec<&str> = lines.iter().map(|l| l.0.as_str()).collect();
    runs.dedup();
    assert_eq!(runs, [BLUE, VERMILLION, BLACK], "colours in drawing order");
    let legends: Vec<(&str, &str)> = (lines.iter())
        .filter_map(|(c, l)| Some((c.as_str(), l.as_deref()?)))
        .filter(|(_, l)| l.contains("pounding"))
        .collect();
    assert_eq!(
        legends,
        [
            (BLUE, "with pounding"),
            (BLUE, "without pounding"),
            (VERMILLION, "with pounding"),
            (VERMILLION, "without pounding"),
        ]
    );
    // envelopes: every line blue or vermillion, and the legend's colour is its structure's
    let envelopes = svg(envelope_figure(&report, &dir.path().join("e")).unwrap());
    let lines = strokes(&envelopes);
    assert!(lines.iter().all(|l| l.0 == BLUE || l.0 == VERMILLION));
    for (i, colour) in [BLUE, VERMILLION].iter().enumerate() {
        let name = &report.structures[i].name;
        for label in [format!("{name}, with pounding"), format!("{name}, without")] {
            assert!(
                lines
                    .iter()
                    .any(|l| l.0 == *colour && l.1.as_deref() == Some(&label)),
                "legend {label} not in {colour}"
            );
        }
    }
    // the hysteresis loops of yielding-frames.toml: only its structure 2 yields — vermillion
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/yielding-frames.toml");
    let mut sc = Scenario::from_file(&path).unwrap();
    sc.solver.duration = 4.0;
    let r = simulate(&sc).unwrap();
    let loops = svg(hysteresis_figure(&r, &dir.path().join("y"))
        .unwrap()
        .unwrap());
    let lines = strokes(&loops);
    assert!(!lines.is_empty() && lines.iter().all(|l| l.0 == VERMILLION));
}

/// The envelope figure speaks the engineer's units: displacement w (as in history.csv),
/// storey drift as a ratio in %, rings on the floors whose acceleration peak is an impact's
/// pulse, and the pulse's duration in the subtitle.
#[test]
fn envelopes_show_drift_ratios_and_impact_pulses() {
    let (_, report) = run("examples/paper-c.toml", None);
    let dir = tempfile::tempdir().unwrap();
    let files = envelope_figure(&report, &dir.path().join("e")).unwrap();
    let svg = std::fs::read_to_string(&files[1]).unwrap();
    // (the SVG escapes the apostrophe)
    for needle in [
        "w [m]",
        "drift / storey height [%]",
        "impact&apos;s pulse",
        " ms)",
    ] {
        assert!(svg.contains(needle), "{needle}");
    }
    for stale in ["u [m]", "drift [m]"] {
        assert!(!svg.contains(stale), "{stale}");
    }
    // a ring (r = 6, not filled) for each floor whose peak with pounding is an impact's pulse
    let ringed = svg
        .split("<circle")
        .skip(1)
        .filter(|c| c.contains("r=\"6\"") && c.contains("fill=\"none\""))
        .count();
    let pulses: usize = (report.structures.iter())
        .map(|s| {
            (s.floors.iter())
                .filter(|f| f.peak_acceleration_impact.is_some())
                .count()
        })
        .sum();
    assert!(pulses > 0);
    assert_eq!(ringed, pulses);
}

/// The storey drift ratio is the peak drift over the storey's height: a first storey of 4 m
/// and storeys of 3.5 m above it (examples/modal-csv.toml's shear building), and a
/// cantilever's stations every tenth of its 10 m height (the paper's case).
#[test]
fn drift_ratio_is_the_drift_over_the_storey_height() {
    let (_, report) = run("examples/modal-csv.toml", None);
    let s = &report.structures[1];
    let heights: Vec<f64> = s.floors.iter().map(|f| f.height).collect();
    assert_eq!(heights, [4.0, 7.5, 11.0, 14.5]);
    for (f, r) in s.floors.iter().zip(s.peak_drift_ratios()) {
        let storey = if f.height == 4.0 { 4.0 } else { 3.5 };
        assert!((r[0] - 100.0 * f.peak_drift / storey).abs() < 1e-12 * r[0]);
        assert!((r[1] - 100.0 * f.peak_drift_no_contact / storey).abs() < 1e-12 * r[1]);
    }
    let (_, report) = run("examples/paper-c.toml", None);
    for s in &report.structures {
        assert_eq!(s.floors.len(), 10);
        for (f, r) in s.floors.iter().zip(s.peak_drift_ratios()) {
            // stations 1 m apart: the ratio in % is 100 × the drift in m
            assert!((r[0] - 100.0 * f.peak_drift).abs() < 1e-12 * r[0].max(1e-300));
        }
    }
}

/// A figure's PNG has the curve where the formula puts it: a straight line `y = 2t − 3` over
/// `t` ∈ [0, 10] s drawn as a time history (the x axis spans the data exactly, the y axis
/// the data's range padded by 6 % on each side, so [−4.2, 18.2]). The plotting area is found
/// from its frame (the columns and rows of the frame colour, rgb(40, 40, 40), that run through
/// most of the picture); in every pixel column inside it the centroid of the line's ink lies
/// within 1.5 pixels of `bottom − (y(t) − y_lo)/(y_hi − y_lo)·(bottom − top)`, `t` from the
/// column by the same linear map. The 1.5 pixels: the points are rounded to whole pixels
/// (½), the bitmap's line is thinned to the points off a chord by more than ½ pixel (½), and
/// plotters maps values onto the area's half-open pixel range, so the frame and the map may
/// differ by up to a pixel at one end (½ on average). The drawing itself puts the line's
/// centre within a twentieth of a pixel of its end points' line (`src/plot/canvas.rs`).
#[test]
fn a_straight_line_is_drawn_where_its_formula_puts_it() {
    use pounding::plot::{AxisScale, Figure, LineStyle, Panel, Series, write_figure};
    let t: Vec<f64> = (0..=200).map(|i| i as f64 * 0.05).collect();
    let y: Vec<f64> = t.iter().map(|t| 2.0 * t - 3.0).collect();
    let fig = Figure {
        title: "A straight line",
        subtitle: "",
        x_label: "t [s]",
        panels: vec![Panel {
            title: "y = 2t − 3",
            y_label: "y [m]",
            series: vec![Series {
                label: "",
                x: &t,
                y: &y,
                style: LineStyle::Solid,
                color: Some(0), // blue
            }],
            y_scale: AxisScale::Linear,
        }],
        legend_once: false,
        width: 900,
        height: 600,
    };
    let dir = std::env::temp_dir().join(format!("pounding-line-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    write_figure(&fig, &dir.join("line")).unwrap();
    let img = image::open(dir.join("line.png")).unwrap().to_rgb8();
    std::fs::remove_dir_all(&dir).unwrap();
    let (w, h) = img.dimensions();
    let frame = |x: u32, y: u32| img.get_pixel(x, y).0 == [40, 40, 40];
    let cols: Vec<u32> = (0..w)
        .filter(|&x| (0..h).filter(|&y| frame(x, y)).count() > h as usize / 2)
        .collect();
    let rows: Vec<u32> = (0..h)
        .filter(|&y| (0..w).filter(|&x| frame(x, y)).count() > w as usize / 2)
        .collect();
    let (left, right) = (cols[0], *cols.last().unwrap());
    let (top, bottom) = (rows[0], *rows.last().unwrap());
    assert!(
        right > left + 500 && bottom > top + 300,
        "frame {left}..{right} × {top}..{bottom}"
    );
    let (y_lo, y_hi) = (-3.0 - 0.06 * 20.0, 17.0 + 0.06 * 20.0);
    // the line's ink: it is blue, rgb(0, 114, 178), on white or grey (r = g = b) grid lines,
    // so blue minus red is 178 × its opacity whatever lies beneath
    let ink = |x: u32, yy: u32| {
        let p = img.get_pixel(x, yy).0;
        f64::from(i32::from(p[2]) - i32::from(p[0])).max(0.0) / 178.0
    };
    for x in left + 3..right - 2 {
        let tt = 10.0 * f64::from(x - left) / f64::from(right - left);
        let expected =
            f64::from(bottom) - (2.0 * tt - 3.0 - y_lo) / (y_hi - y_lo) * f64::from(bottom - top);
        let (mut total, mut moment) = (0.0, 0.0);
        for yy in top + 2..bottom - 1 {
            let d = ink(x, yy);
            total += d;
            moment += d * f64::from(yy);
        }
        assert!(total > 1.0, "column {x}: no line");
        let centroid = moment / total;
        assert!(
            (centroid - expected).abs() <= 1.5,
            "column {x}: the line at {centroid}, the formula at {expected}"
        );
    }
}
