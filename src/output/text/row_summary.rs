//! What `pounding run` prints after a row of buildings' run (issue 29): every structure's
//! peaks with and without pounding, every pair's impacts and required separation, the row's
//! verdict naming the pair and level that govern, the energy balance.

use std::fmt::{self, Write as _};

use crate::analysis::simulate::RowReport;
use crate::input::scenario::Scenario;

use super::{heading, impacts};

/// The summary `pounding run` prints for the row `sc` (named `name`) and its report `r`.
pub fn row_summary(sc: &Scenario, name: &str, r: &RowReport) -> String {
    let mut o = String::new();
    write_row(&mut o, sc, name, r).expect("writing to a String cannot fail");
    o
}

fn write_row(o: &mut String, sc: &Scenario, name: &str, r: &RowReport) -> fmt::Result {
    o.push_str(&heading(&sc.title, name));
    writeln!(
        o,
        "  a row of {} structures, {} adjacent pairs; {}, dt = {} s over {} s ({} steps)",
        r.structures.len(),
        r.pairs.len(),
        sc.solver.method.name(),
        sc.solver.dt,
        sc.solver.duration,
        r.stats.steps
    )?;
    if !sc.defaults_applied.is_empty() {
        writeln!(
            o,
            "  defaults used (not in the file): {}",
            sc.defaults_applied.join(", ")
        )?;
    }
    writeln!(o)?;
    let w = 2
        + (r.structures.iter())
            .map(|s| s.name.chars().count())
            .max()
            .unwrap_or(0)
            .max(10);
    write!(o, "  {:<34}", "")?;
    for s in &r.structures {
        write!(o, "{:>w$}", s.name)?;
    }
    writeln!(o)?;
    type Pick = fn(&crate::analysis::simulate::StructureReport) -> f64;
    let rows: [(&str, Pick, usize); 4] = [
        ("first-mode period [s]", |s| s.periods[0], 4),
        (
            "peak w(h) without pounding [m]",
            |s| s.peak_displacement_no_contact,
            4,
        ),
        ("peak w(h) with pounding [m]", |s| s.peak_displacement, 4),
        ("change [%]", |s| s.change_percent, 1),
    ];
    for (label, f, d) in rows {
        write!(o, "  {label:<34}")?;
        for s in &r.structures {
            write!(o, "{:>w$.d$}", f(s))?;
        }
        writeln!(o)?;
    }
    if r.structures.iter().any(|s| s.peak_ductility.is_some()) {
        write!(o, "  {:<34}", "peak ductility without / with")?;
        for s in &r.structures {
            let cell = match (s.peak_ductility_no_contact, s.peak_ductility) {
                (Some(a), Some(b)) => format!("{a:.2}/{b:.2}"),
                _ => "–".into(),
            };
            write!(o, "{cell:>w$}")?;
        }
        writeln!(o)?;
    }
    writeln!(
        o,
        "  (w(h): at each structure's highest contact level with either neighbour)"
    )?;
    writeln!(o)?;
    for p in &r.pairs {
        let c = &p.contact;
        let what = if c.impacts == 0 {
            "no contact: the gaps never closed".to_string()
        } else {
            format!(
                "{}, peak force {:.4e} N, max penetration {:.3} mm, fastest approach {:.3} m/s",
                impacts(c.impacts),
                c.peak_force,
                c.max_penetration * 1e3,
                p.peak_approach_speed
            )
        };
        writeln!(
            o,
            "  pair {} \"{}\"–\"{}\" ({}): {what}",
            p.index + 1,
            p.between[0],
            p.between[1],
            p.law
        )?;
        let s = &p.separation;
        writeln!(
            o,
            "    required separation [m]: time history {:.4} | ABS {:.4}  SRSS {:.4}  DDC {:.4}",
            s.time_history, s.abs, s.srss, s.ddc
        )?;
        if let Some(g) = &s.verdict.governing {
            writeln!(
                o,
                "    governs: {} at h = {} m: gap {:.4} m, required {:.4} m ({})",
                g.label,
                g.height,
                g.gap,
                g.required,
                if g.sufficient {
                    "sufficient"
                } else {
                    "too small"
                }
            )?;
        }
    }
    let v = &r.verdict;
    if let (Some(g), Some(b)) = (&v.governing, &v.between) {
        writeln!(
            o,
            "  row: the pair \"{}\"–\"{}\" governs ({} at h = {} m, margin {:.4} m); {} of {} pairs \
             have a gap too small by some rule; {} pounded",
            b[0],
            b[1],
            g.label,
            g.height,
            g.margin,
            v.insufficient_pairs.len(),
            r.pairs.len(),
            v.pounding_pairs.len()
        )?;
    }
    writeln!(
        o,
        "  energy balance error: {:.1e} with contact, {:.1e} without",
        r.energy.relative_error, r.energy_no_contact.relative_error
    )?;
    writeln!(o, "  {}", row_self_check_line(&r.accuracy))?;
    Ok(())
}

/// The self-check's line of a row's summary, in the words of a pair's
/// ([`super::run_summary::self_check_line`]).
pub fn row_self_check_line(a: &crate::analysis::simulate::row_check::RowAccuracyCheck) -> String {
    use crate::analysis::simulate::accuracy::percent;
    let against = a.settings.map(|s| s.describe()).unwrap_or_default();
    if !a.checked {
        return "self-check: not done (--no-check): this result was NOT self-checked".into();
    }
    if let Some(f) = &a.failure {
        return format!("self-check: NOT CONVERGED — not verified: {f} (see the warning)");
    }
    let worst = (a.quantities.iter())
        .find(|q| Some(&q.name) == a.max_change_quantity.as_ref())
        .map_or("", |q| q.label.as_str());
    let change = percent(a.max_change.unwrap_or(f64::NAN));
    if a.is_converged() {
        format!(
            "self-check: converged within {} % (largest change {change}, {worst}, against a run at {against})",
            100.0 * a.threshold
        )
    } else {
        format!(
            "self-check: NOT CONVERGED — {worst} changed by {change} against a run at {against} \
             (more than {} %); see the warning",
            100.0 * a.threshold
        )
    }
}
