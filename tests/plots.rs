//! The pictures tell the truth: the time-history figure draws every impact at its peak force,
//! and the heatmap colour scales follow their formulas.

use std::path::Path;

use pounding::figures::{drawn_force, time_history_figure};
use pounding::plot::ColorScale;
use pounding::plot::style::{
    NO_DATA, RATIO_HIGH, RATIO_LOW, RATIO_NEUTRAL, ratio_color, ratio_position, viridis,
};
use pounding::scenario::Scenario;
use pounding::simulate::{Report, simulate};
use pounding::sweep_plots::{RATIO_LIMIT, axis_label, field_scale};

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
