//! What `pounding separation` prints: every rule and code at every contact level against its
//! gap (with the exact time-history separation and each rule's over/under-estimate of it), then
//! each rule's verdict at its governing level.

use std::fmt::{self, Write as _};

use crate::analysis::gap_report::GapReport;
use crate::analysis::level_checks::LevelCheck;

/// The tables of `pounding separation` (lengths in mm, heights in m).
pub fn separation_report(r: &GapReport) -> String {
    let mut o = String::new();
    write_report(&mut o, r).expect("writing to a String cannot fail");
    o
}

/// A length in mm with 3 decimals (1 µm: enough to check a code's value by hand).
fn mm(x: f64) -> String {
    format!("{:.3}", 1e3 * x)
}

fn write_report(o: &mut String, r: &GapReport) -> fmt::Result {
    writeln!(o, "{}", r.title)?;
    let exact = r.levels.iter().any(|l| l.exact.is_some());
    let source = match (r.spectrum, exact) {
        (Some(s), true) => format!(
            "rules from the design spectrum {s} (--spectrum); exact separation from the scenario's time history"
        ),
        (Some(s), false) => format!("design spectrum {s}: no time history, so no exact separation"),
        (None, _) => "time history of the scenario (the run without pounding)".to_string(),
    };
    writeln!(o, "  ground motion: {source}")?;
    writeln!(o, "  the rules take, at each level, {}", r.peaks_note)?;
    writeln!(
        o,
        "  T1 = {:.4} s, T2 = {:.4} s, ζ1 = {}, ζ2 = {}, ρ12 (CQC, first modes) = {:.5}; lengths in mm",
        r.periods[0], r.periods[1], r.damping_ratios[0], r.damping_ratios[1], r.rho
    )?;
    for w in &r.warnings {
        writeln!(o, "  warning: {w}")?;
    }
    // top level first, as a building is read
    let mut order: Vec<&LevelCheck> = r.levels.iter().collect();
    order.sort_by(|a, b| b.height.total_cmp(&a.height));
    for l in &order {
        writeln!(o)?;
        let floors = if l.floors_coincide {
            "; a floor of both structures"
        } else {
            ""
        };
        writeln!(
            o,
            "  contact level h = {} m: gap {} mm{floors}; the rules take w1 = {} mm, w2 = {} mm",
            l.height,
            mm(l.gap),
            mm(l.peaks[0]),
            mm(l.peaks[1])
        )?;
        if let Some(s) = &l.spectral {
            let (a, b) = (&s.structure1, &s.structure2);
            writeln!(
                o,
                "    spectral peaks [mm]: structure 1 SRSS {}, CQC {} ({} modes); structure 2 SRSS {}, CQC {} ({} modes)",
                mm(a.srss),
                mm(a.cqc),
                a.modes.len(),
                mm(b.srss),
                mm(b.cqc),
                b.modes.len()
            )?;
        }
        let gap_col = format!("gap {} mm", mm(l.gap));
        let vs_col = if l.exact.is_some() { "vs exact" } else { "" };
        let head = format!(
            "    {:<40}{:<42}{:>14}{:>16}{:>12}",
            "rule", "clause", "required [mm]", gap_col, vs_col
        );
        writeln!(o, "{}", head.trim_end())?;
        for row in &l.rules {
            let ok = if row.sufficient {
                "suffices"
            } else {
                "TOO SMALL"
            };
            let vs = row
                .vs_exact_percent
                .map_or(String::new(), |p| format!("{p:+.1} %"));
            let line = format!(
                "    {:<40}{:<42}{:>14}{:>16}{:>12}",
                row.label,
                row.clause.as_deref().unwrap_or(""),
                mm(row.required),
                ok,
                vs
            );
            writeln!(o, "{}", line.trim_end())?;
        }
        for c in &l.codes {
            let reduced = c.reduction.map_or(String::new(), |x| format!("; {x}"));
            writeln!(
                o,
                "      {}: {}; displacements [{}, {}] mm, terms [{}, {}] mm{reduced}",
                c.key,
                c.conversion,
                mm(c.displacements[0]),
                mm(c.displacements[1]),
                mm(c.terms[0]),
                mm(c.terms[1])
            )?;
        }
    }
    writeln!(o)?;
    let v = &r.verdict;
    if r.levels.len() > 1 {
        writeln!(
            o,
            "  verdict: each rule at its governing level (the smallest gap − required):"
        )?;
        let head = format!(
            "    {:<40}{:>10}{:>12}{:>16}{:>14}",
            "rule", "level [m]", "gap [mm]", "required [mm]", "margin [mm]"
        );
        writeln!(o, "{head}")?;
        for g in &v.rules {
            let ok = if g.sufficient {
                "suffices"
            } else {
                "TOO SMALL"
            };
            writeln!(
                o,
                "    {:<40}{:>10}{:>12}{:>16}{:>14}  {ok}",
                g.label,
                g.height,
                mm(g.gap),
                mm(g.required),
                mm(g.margin)
            )?;
        }
    }
    let n = v.rules.len();
    let summary = match v.insufficient {
        0 => format!("  the gap suffices at every level by all {n} rules"),
        k => format!("  the gap is TOO SMALL by {k} of {n} rules"),
    };
    match &v.governing {
        Some(g) => writeln!(
            o,
            "{summary}; the most demanding: {} at h = {} m ({} mm required, gap {} mm)",
            g.label,
            g.height,
            mm(g.required),
            mm(g.gap)
        )?,
        None => writeln!(o, "{summary}")?,
    }
    if let Some(floors) = &r.spectral_floors {
        for (i, f) in floors.iter().enumerate() {
            if f.is_empty() {
                continue;
            }
            writeln!(
                o,
                "  spectral peak displacement at every floor of structure {} [mm]:",
                i + 1
            )?;
            writeln!(o, "    {:>10} {:>12} {:>12}", "height [m]", "SRSS", "CQC")?;
            for x in f.iter().rev() {
                writeln!(
                    o,
                    "    {:>10.3} {:>12} {:>12}",
                    x.height,
                    mm(x.srss),
                    mm(x.cqc)
                )?;
            }
        }
    }
    if exact {
        writeln!(
            o,
            "  vs exact: 100 (rule − exact)/exact at the same level; a negative value is a rule below the exact separation (unsafe)"
        )?;
    }
    Ok(())
}
