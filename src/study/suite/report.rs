//! The text report of `pounding run` on a suite of records, a pair's or a row of buildings'
//! ([`text`], [`SuiteText`]): the scaling, one line per record, the statistics of the
//! required separation at every level, the design values and the verdict — for a row, every
//! structure's peaks across the records, then per pair one line per record, the statistics,
//! the design value at each of its levels and its verdict, last the row's verdict (the
//! governing pair and level). The blocks both share (the record's check, a level's cells,
//! the statistics lines, the design values and the verdict of a set of levels, the warnings)
//! are one code path.

use std::fmt::Write as _;

use super::row::RowSuiteRun;
use super::write::SuiteOutput;
use super::{LevelDesign, Statistics, SuiteRun};
use crate::model::ground_motion::STANDARD_GRAVITY;

fn mm(x: f64) -> String {
    format!("{:.1}", x * 1e3)
}

/// One statistic of [`Statistics`].
type Statistic = fn(&Statistics) -> f64;

/// (label, statistic) of the report's statistics lines.
const STATS: [(&str, Statistic); 4] = [
    ("mean", |s| s.mean),
    ("median", |s| s.median),
    ("84th percentile", |s| s.p84),
    ("max", |s| s.max),
];

/// A suite run whose report `pounding run` prints: a pair's [`SuiteRun`] or a row's
/// [`RowSuiteRun`].
pub trait SuiteText: SuiteOutput {
    /// The report (lengths in mm, forces in kN) of the scenario `name` titled `title`.
    fn text(&self, title: &str, name: &str) -> String;
}

impl SuiteText for SuiteRun {
    fn text(&self, title: &str, name: &str) -> String {
        pair_text(self, title, name)
    }
}

impl SuiteText for RowSuiteRun {
    fn text(&self, title: &str, name: &str) -> String {
        row_text(self, title, name)
    }
}

/// The report of `run` (lengths in mm, forces in kN): a pair's suite or a row's.
pub fn text<S: SuiteText>(run: &S, title: &str, name: &str) -> String {
    run.text(title, name)
}

/// A record's self-check as its table shows it: the largest change (%), `NOT CONV.` or
/// `unchecked`.
fn check_cell(converged: Option<bool>, max_change: Option<f64>) -> String {
    match (converged, max_change) {
        (Some(true), Some(c)) => format!("{:.2} %", 100.0 * c),
        (Some(false), _) => "NOT CONV.".into(),
        _ => "unchecked".into(),
    }
}

/// The levels' heights, m, as the table's title lists them.
fn heights(levels: &[LevelDesign]) -> String {
    levels
        .iter()
        .map(|l| l.height.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A record's cells of a set of levels: the required separation at each (mm), the peak force
/// (kN) and the impacts.
fn level_cells(
    line: &mut String,
    required: impl Iterator<Item = f64>,
    peak_force: f64,
    impacts: usize,
) {
    for r in required {
        let _ = write!(line, "  {:>9}", mm(r));
    }
    let _ = write!(line, "  {:>10.1}  {:>7}", peak_force / 1e3, impacts);
}

/// The statistics lines of a set of levels: per statistic its label (padded to `label`
/// characters), the required separation at each level and the peak force's (`force`).
fn statistics_lines(
    o: &mut String,
    label: usize,
    levels: &[LevelDesign],
    force: Option<&Statistics>,
) {
    for (name, f) in STATS {
        let mut line = format!("  {name:<label$}");
        for l in levels {
            let _ = write!(line, "  {:>9}", mm(f(&l.statistics)));
        }
        if let Some(s) = force {
            let _ = write!(line, "  {:>10.1}", f(s) / 1e3);
        }
        let _ = writeln!(o, "{line}");
    }
}

/// The line naming the design statistic over the records and its clause.
fn design_line(o: &mut String, statistic: super::DesignStatistic, records: usize, basis: &str) {
    let _ = writeln!(
        o,
        "  design value = the {} of the {} records ({})",
        statistic.key(),
        records,
        basis
    );
}

/// Each level's design value against its gap.
fn level_lines(o: &mut String, levels: &[LevelDesign]) {
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
}

/// The verdict of a set of levels: "the gap suffices at every level" or "is TOO SMALL" (with
/// `by`, e.g. " by this procedure"), then the governing level `g` and how many of the
/// `levels` are too small.
fn verdict(
    sufficient: bool,
    by: &str,
    g: &LevelDesign,
    insufficient: usize,
    levels: usize,
) -> String {
    format!(
        "the gap {}{by}; governing level {} (h = {} m): required {} mm, gap {} mm{}",
        if sufficient {
            "suffices at every level"
        } else {
            "is TOO SMALL"
        },
        g.level,
        g.height,
        mm(g.required),
        mm(g.gap),
        if insufficient > 0 {
            format!(" ({insufficient} of {levels} levels too small)")
        } else {
            String::new()
        }
    )
}

/// The statistics of the headline number `name` of `run`.
fn stat<'a, S: SuiteOutput>(run: &'a S, name: &str) -> Option<&'a Statistics> {
    run.statistics()
        .0
        .iter()
        .find(|(k, _)| k == name)
        .map(|(_, s)| s)
}

/// A pair's suite report.
fn pair_text(run: &SuiteRun, title: &str, name: &str) -> String {
    let mut o = String::new();
    let n = run.records.len();
    let _ = writeln!(o, "{title}");
    let _ = writeln!(o, "  scenario: {name}");
    o.push_str(&scaling_lines(run.scaling.as_ref(), n));
    let levels = &run.design.levels;
    let _ = writeln!(
        o,
        "  required separation by the time history at each level (h = {} m), mm; peak force kN",
        heights(levels)
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
        let c = &r.report.contact;
        level_cells(
            &mut line,
            r.report.levels.iter().map(|l| l.required_gap),
            c.peak_force,
            c.impacts,
        );
        let check = check_cell(h.converged, r.report.accuracy.max_change);
        let _ = write!(line, "  {check:>9}");
        let _ = writeln!(o, "{line}");
    }
    let _ = writeln!(o);
    statistics_lines(&mut o, width + cw + 25, levels, stat(run, "peak_force"));
    let d = &run.design;
    let _ = writeln!(o);
    design_line(&mut o, d.statistic, d.records, d.basis);
    level_lines(&mut o, levels);
    let g = &levels[d.governing_level - 1];
    let _ = writeln!(
        o,
        "  verdict: {}",
        verdict(
            d.sufficient,
            " by this procedure",
            g,
            d.insufficient_levels,
            levels.len()
        )
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

/// A row's suite report.
fn row_text(run: &RowSuiteRun, title: &str, name: &str) -> String {
    let mut o = String::new();
    let n = run.records.len();
    let _ = writeln!(o, "{title}");
    let _ = writeln!(o, "  scenario: {name}");
    let structures = run.records.first().map_or(0, |r| r.report.structures.len());
    let _ = write!(
        o,
        "  a row of {structures} buildings; {}",
        scaling_lines(run.scaling.as_ref(), n).trim_start()
    );
    let (width, cw) = record_widths(
        run.records
            .iter()
            .map(|r| (r.file.as_str(), r.component.as_deref())),
    );
    // the records
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "  {:>3}  {:<width$}  {:<cw$}  {:>7}  {:>6}  {:>9}",
        "#", "file", "comp.", "factor", "PGA g", "check"
    );
    for (i, r) in run.records.iter().enumerate() {
        let mark = if i == run.representative { "*" } else { " " };
        let check = check_cell(r.headline.converged, r.report.accuracy.max_change);
        let _ = writeln!(
            o,
            "{mark} {:>3}  {:<width$}  {:<cw$}  {:>7.3}  {:>6.3}  {:>9}",
            i + 1,
            r.file,
            r.component.as_deref().unwrap_or("-"),
            r.factor,
            r.headline.get("pga").unwrap_or(f64::NAN) / STANDARD_GRAVITY,
            check
        );
    }
    // every structure's peaks across the records
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "  peak displacement at each building's highest contact level across the records, mm \
         (with / without pounding)"
    );
    let names: Vec<&str> = run.records.first().map_or(Vec::new(), |r| {
        r.report
            .structures
            .iter()
            .map(|s| s.name.as_str())
            .collect()
    });
    let nw = names
        .iter()
        .map(|s| s.chars().count())
        .max()
        .unwrap_or(4)
        .clamp(4, 24);
    let mut head = format!("  {:<nw$}", "");
    for (label, _) in STATS {
        let _ = write!(head, "  {label:>19}");
    }
    let _ = writeln!(o, "{head}");
    for (i, s) in names.iter().enumerate() {
        let mut line = format!("  {s:<nw$}");
        let with = stat(run, &format!("structure{}_peak_displacement", i + 1));
        let without = stat(
            run,
            &format!("structure{}_peak_displacement_no_contact", i + 1),
        );
        for (_, f) in STATS {
            let cell = format!(
                "{} / {}",
                with.map_or("-".into(), |s| mm(f(s))),
                without.map_or("-".into(), |s| mm(f(s)))
            );
            let _ = write!(line, "  {cell:>19}");
        }
        let _ = writeln!(o, "{line}");
    }
    let d = &run.design;
    let _ = writeln!(o);
    design_line(&mut o, d.statistic, d.records, d.basis);
    // per pair
    for q in &d.pairs {
        let p = q.pair;
        let _ = writeln!(o);
        let _ = writeln!(
            o,
            "  pair {p} of {}: \"{}\" – \"{}\": required separation by the time history at each \
             level (h = {} m), mm; peak force kN",
            d.pairs.len(),
            q.between[0],
            q.between[1],
            heights(&q.levels)
        );
        let mut head = format!("  {:>3}  {:<width$}", "#", "file");
        for l in &q.levels {
            let _ = write!(head, "  {:>9}", format!("sep L{}", l.level));
        }
        let _ = write!(head, "  {:>10}  {:>7}", "force", "impacts");
        let _ = writeln!(o, "{head}");
        for (i, r) in run.records.iter().enumerate() {
            let pr = &r.report.pairs[p - 1];
            let mark = if i == run.representative { "*" } else { " " };
            let mut line = format!("{mark} {:>3}  {:<width$}", i + 1, r.file);
            level_cells(
                &mut line,
                pr.levels.iter().map(|l| l.required_gap),
                pr.contact.peak_force,
                pr.contact.impacts,
            );
            let _ = writeln!(o, "{line}");
        }
        let force = stat(run, &format!("pair{p}_peak_force"));
        statistics_lines(&mut o, width + 5, &q.levels, force);
        level_lines(&mut o, &q.levels);
        let g = &q.levels[q.governing_level - 1];
        let _ = writeln!(
            o,
            "    pair {p}: {}",
            verdict(q.sufficient, "", g, q.insufficient_levels, q.levels.len())
        );
    }
    let g = d.governing();
    let q = &d.pairs[d.governing_pair - 1];
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "  verdict for the row: {} by this procedure; governing pair {} (\"{}\" – \"{}\") level {} \
         (h = {} m): required {} mm, gap {} mm (margin {:+.1} mm){}",
        if d.sufficient {
            "every gap suffices"
        } else {
            "a gap is TOO SMALL"
        },
        q.pair,
        q.between[0],
        q.between[1],
        g.level,
        g.height,
        mm(g.required),
        mm(g.gap),
        g.margin * 1e3,
        if d.insufficient_pairs.is_empty() {
            String::new()
        } else {
            format!(
                "; pairs too small: {}",
                d.insufficient_pairs
                    .iter()
                    .map(|p| p.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    );
    let rep = &run.records[run.representative];
    let _ = writeln!(
        o,
        "  * record {} ({}): the largest required separation at the governing pair and level; \
         its run is the top level of summary.json, history.csv and the run's pictures; every \
         record's run is in {}/",
        run.representative + 1,
        rep.file,
        super::write::RECORDS_DIR
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

/// The warnings of a suite's run (a pair's or a row's): the scenario's own (`sc`'s) once, then
/// each warning a record's run adds, named with the first record that gave it.
pub fn warnings<S: SuiteOutput>(sc: &crate::input::scenario::Scenario, run: &S) -> Vec<String> {
    merge_warnings(
        sc,
        run.records()
            .iter()
            .map(|r| (r.file.as_str(), super::MemberReport::warnings(&r.report))),
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
