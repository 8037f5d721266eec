//! The text report of `pounding run` on a suite of records on a row of buildings: the scaling,
//! the records, every structure's peaks across the records, then **per pair** one line per
//! record (the required separation at each of the pair's levels, its peak force and impacts),
//! the statistics, the design value at each level against its gap and the pair's verdict;
//! last the row's verdict (the governing pair and level).

use std::fmt::Write as _;

use super::Statistics;
use super::row::RowSuiteRun;
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

/// The report (lengths in mm, forces in kN).
pub fn text(run: &RowSuiteRun, title: &str, name: &str) -> String {
    let mut o = String::new();
    let n = run.records.len();
    let _ = writeln!(o, "{title}");
    let _ = writeln!(o, "  scenario: {name}");
    let structures = run.records.first().map_or(0, |r| r.report.structures.len());
    let _ = write!(
        o,
        "  a row of {structures} buildings; {}",
        super::report::scaling_lines(run.scaling.as_ref(), n).trim_start()
    );
    let (width, cw) = super::report::record_widths(
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
        let check = match (r.headline.converged, r.report.accuracy.max_change) {
            (Some(true), Some(c)) => format!("{:.2} %", 100.0 * c),
            (Some(false), _) => "NOT CONV.".into(),
            _ => "unchecked".into(),
        };
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
    let _ = writeln!(
        o,
        "  design value = the {} of the {} records ({})",
        d.statistic.key(),
        d.records,
        d.basis
    );
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
            q.levels
                .iter()
                .map(|l| l.height.to_string())
                .collect::<Vec<_>>()
                .join(", ")
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
            for l in &pr.levels {
                let _ = write!(line, "  {:>9}", mm(l.required_gap));
            }
            let _ = write!(
                line,
                "  {:>10.1}  {:>7}",
                pr.contact.peak_force / 1e3,
                pr.contact.impacts
            );
            let _ = writeln!(o, "{line}");
        }
        let force = stat(run, &format!("pair{p}_peak_force"));
        for (label, f) in STATS {
            let mut line = format!("  {:<w$}", label, w = width + 5);
            for l in &q.levels {
                let _ = write!(line, "  {:>9}", mm(f(&l.statistics)));
            }
            if let Some(s) = force {
                let _ = write!(line, "  {:>10.1}", f(s) / 1e3);
            }
            let _ = writeln!(o, "{line}");
        }
        for l in &q.levels {
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
        let g = &q.levels[q.governing_level - 1];
        let _ = writeln!(
            o,
            "    pair {p}: the gap {}; governing level {} (h = {} m): required {} mm, gap {} mm{}",
            if q.sufficient {
                "suffices at every level"
            } else {
                "is TOO SMALL"
            },
            g.level,
            g.height,
            mm(g.required),
            mm(g.gap),
            if q.insufficient_levels > 0 {
                format!(
                    " ({} of {} levels too small)",
                    q.insufficient_levels,
                    q.levels.len()
                )
            } else {
                String::new()
            }
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

/// The statistics of the headline number `name`.
fn stat<'a>(run: &'a RowSuiteRun, name: &str) -> Option<&'a Statistics> {
    run.statistics
        .0
        .iter()
        .find(|(k, _)| k == name)
        .map(|(_, s)| s)
}

/// The warnings of a row suite's run: the scenario's own (`sc`'s) once, then each warning a
/// record's run adds, named with the first record that gave it.
pub fn warnings(sc: &crate::input::scenario::Scenario, run: &RowSuiteRun) -> Vec<String> {
    super::report::merge_warnings(
        sc,
        run.records
            .iter()
            .map(|r| (r.file.as_str(), r.report.warnings.as_slice())),
    )
}
