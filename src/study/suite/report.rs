//! The text report of `pounding run` on a suite: the scaling, one line per record, the
//! statistics of the required separation at every level, the design values and the verdict.

use std::fmt::Write as _;

use super::SuiteRun;
use crate::model::ground_motion::STANDARD_GRAVITY;

fn mm(x: f64) -> String {
    format!("{:.1}", x * 1e3)
}

/// The report (lengths in mm, forces in kN).
pub fn text(run: &SuiteRun, title: &str, name: &str) -> String {
    let mut o = String::new();
    let n = run.records.len();
    let _ = writeln!(o, "{title}");
    let _ = writeln!(o, "  scenario: {name}");
    o.push_str(&scaling_lines(run.scaling.as_ref(), n));
    let levels = &run.design.levels;
    let _ = writeln!(
        o,
        "  required separation by the time history at each level (h = {} m), mm; peak force kN",
        levels
            .iter()
            .map(|l| l.height.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(o);
    let (width, cw) = record_widths(
        run.records
            .iter()
            .map(|r| (r.file.as_str(), r.component.as_deref())),
    );
    let mut head = format!(
        "  {:>3}  {:<width$}  {:<cw$}  {:>7}  {:>6}",
        "#", "file", "comp.", "factor", "PGA g"
    );
    for l in levels {
        let _ = write!(head, "  {:>9}", format!("sep L{}", l.level));
    }
    let _ = write!(head, "  {:>10}  {:>7}  {:>9}", "force", "impacts", "check");
    let _ = writeln!(o, "{head}");
    for (i, r) in run.records.iter().enumerate() {
        let h = &r.headline;
        let mark = if i == run.representative { "*" } else { " " };
        let mut line = format!(
            "{mark} {:>3}  {:<width$}  {:<cw$}  {:>7.3}  {:>6.3}",
            i + 1,
            r.file,
            r.component.as_deref().unwrap_or("-"),
            r.factor,
            h.get("pga").unwrap_or(f64::NAN) / STANDARD_GRAVITY
        );
        for l in &r.report.levels {
            let _ = write!(line, "  {:>9}", mm(l.required_gap));
        }
        let check = match (h.converged, r.report.accuracy.max_change) {
            (Some(true), Some(c)) => format!("{:.2} %", 100.0 * c),
            (Some(false), _) => "NOT CONV.".into(),
            _ => "unchecked".into(),
        };
        let _ = write!(
            line,
            "  {:>10.1}  {:>7}  {:>9}",
            r.report.contact.peak_force / 1e3,
            r.report.contact.impacts,
            check
        );
        let _ = writeln!(o, "{line}");
    }
    let _ = writeln!(o);
    for (label, f) in [
        (
            "mean",
            (|s: &super::Statistics| s.mean) as fn(&super::Statistics) -> f64,
        ),
        ("median", |s| s.median),
        ("84th percentile", |s| s.p84),
        ("max", |s| s.max),
    ] {
        let mut line = format!("  {:<width$}", label, width = width + cw + 25);
        for l in levels {
            let _ = write!(line, "  {:>9}", mm(f(&l.statistics)));
        }
        if let Some((_, force)) = run.statistics.0.iter().find(|(k, _)| k == "peak_force") {
            let _ = write!(line, "  {:>10.1}", f(force) / 1e3);
        }
        let _ = writeln!(o, "{line}");
    }
    let d = &run.design;
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "  design value = the {} of the {} records ({})",
        d.statistic.key(),
        d.records,
        d.basis
    );
    for l in levels {
        let _ = writeln!(
            o,
            "    level {} (h = {} m): required {} mm, gap {} mm: {} (margin {:+.1} mm)",
            l.level,
            l.height,
            mm(l.required),
            mm(l.gap),
            if l.sufficient {
                "suffices"
            } else {
                "TOO SMALL"
            },
            l.margin * 1e3
        );
    }
    let g = &levels[d.governing_level - 1];
    let _ = writeln!(
        o,
        "  verdict: the gap {} by this procedure; governing level {} (h = {} m): required {} mm, \
         gap {} mm{}",
        if d.sufficient {
            "suffices at every level"
        } else {
            "is TOO SMALL"
        },
        g.level,
        g.height,
        mm(g.required),
        mm(g.gap),
        if d.insufficient_levels > 0 {
            format!(
                " ({} of {} levels too small)",
                d.insufficient_levels,
                levels.len()
            )
        } else {
            String::new()
        }
    );
    let rep = &run.records[run.representative];
    let _ = writeln!(
        o,
        "  * record {} ({}): the largest required separation at the governing level; its run is \
         the top level of summary.json, history.csv and the run's pictures",
        run.representative + 1,
        rep.file
    );
    o
}

/// The lines on the scaling of a suite of `n` records (`None`: rule "none"), each starting
/// with two spaces and ending with a newline.
pub(crate) fn scaling_lines(
    scaling: Option<&crate::analysis::record_spectrum::ScaledSuite>,
    n: usize,
) -> String {
    let mut o = String::new();
    match scaling {
        Some(s) => {
            let _ = writeln!(
                o,
                "  suite of {n} records scaled by {} to {}",
                s.rule_name, s.target_description
            );
            let _ = writeln!(
                o,
                "  period range {:.3}–{:.3} s (first-mode periods {}); lowest mean/target {:.3} \
                 at T = {:.3} s (≥ {} required){}",
                s.range.lo,
                s.range.hi,
                s.first_mode_periods
                    .iter()
                    .map(|t| format!("{t:.3}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                s.min_ratio,
                s.min_ratio_period,
                s.required_ratio,
                s.pga_check.map_or(String::new(), |p| format!(
                    "; mean PGA {:.3} g ≥ a_g·S {:.3} g",
                    p.mean_pga / STANDARD_GRAVITY,
                    p.required / STANDARD_GRAVITY
                ))
            );
        }
        None => {
            let _ = writeln!(
                o,
                "  suite of {n} records at their own factors (rule \"none\")"
            );
        }
    }
    o
}

/// The line `pounding run` shows on a terminal before it runs the suite of `sc` (`check`: with
/// the self-check).
pub fn progress_line(sc: &crate::input::scenario::Scenario, check: bool) -> String {
    let n = sc.suite.as_ref().map_or(0, |s| s.records.len());
    format!(
        "  running {n} records (with and without pounding{}) …",
        if check { ", self-checked" } else { "" }
    )
}

/// The warnings of a suite's run: the scenario's own (`sc`'s) once, then each warning a
/// record's run adds, named with the first record that gave it.
pub fn warnings(sc: &crate::input::scenario::Scenario, run: &SuiteRun) -> Vec<String> {
    merge_warnings(
        sc,
        run.records
            .iter()
            .map(|r| (r.file.as_str(), r.report.warnings.as_slice())),
    )
}

/// The scenario's warnings once, then each record's (file, warnings) new ones, named with the
/// first record that gave it.
pub(crate) fn merge_warnings<'a>(
    sc: &crate::input::scenario::Scenario,
    records: impl Iterator<Item = (&'a str, &'a [String])>,
) -> Vec<String> {
    let mut seen: std::collections::BTreeSet<&str> =
        sc.warnings.iter().map(String::as_str).collect();
    let mut out = sc.warnings.clone();
    for (file, warnings) in records {
        for w in warnings {
            if seen.insert(w) {
                out.push(format!("{w} (record {file})"));
            }
        }
    }
    out
}

/// The widths of the record table's file and component columns (characters), each within
/// its bounds: `(file, component)` of every record.
pub(super) fn record_widths<'a>(
    records: impl Iterator<Item = (&'a str, Option<&'a str>)>,
) -> (usize, usize) {
    let (mut file, mut component) = (None, None);
    for (f, c) in records {
        file = file.max(Some(f.chars().count()));
        component = component.max(Some(c.map_or(1, |c| c.chars().count())));
    }
    (
        file.unwrap_or(4).clamp(4, 48),
        component.unwrap_or(1).clamp(5, 24),
    )
}
