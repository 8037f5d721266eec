//! What `pounding run` prints after a run of one ground motion: the scenario and its settings,
//! the peaks with and without pounding at the contact height (and at the floors), the impacts,
//! the required separation, the energy balance and the self-check.

use std::fmt::{self, Write as _};

use crate::analysis::simulate::Report;
use crate::input::scenario::Scenario;

use super::{heading, impacts};

/// The summary `pounding run` prints for `sc` (named `name` in the text) and its report `r`
/// (lengths in m and mm, forces in N, accelerations in m/s² and g, as labelled).
pub fn run_summary(sc: &Scenario, name: &str, r: &Report) -> String {
    let mut o = String::new();
    write_summary(&mut o, sc, name, r).expect("writing to a String cannot fail");
    o
}

fn write_summary(o: &mut String, sc: &Scenario, name: &str, r: &Report) -> fmt::Result {
    o.push_str(&heading(&sc.title, name));
    let levels: Vec<String> = sc
        .contact
        .levels
        .iter()
        .map(|l| format!("h = {} m (gap {} mm)", l.height, l.gap * 1e3))
        .collect();
    writeln!(
        o,
        "  {} contact at {}; {}, dt = {} s over {} s ({} steps)",
        sc.contact.law.name(),
        levels.join(", "),
        sc.solver.method.name(),
        sc.solver.dt,
        sc.solver.duration,
        r.stats.steps
    )?;
    if let Some(line) = crate::output::ground_section::scaling_line(&sc.ground_motion) {
        writeln!(o, "  {line}")?;
    }
    if !sc.defaults_applied.is_empty() {
        writeln!(
            o,
            "  defaults used (not in the file): {}",
            sc.defaults_applied.join(", ")
        )?;
    }
    writeln!(o)?;
    let [a, b] = &r.structures;
    // columns as wide as the longer name (at least 16)
    let w = 2 + a.name.chars().count().max(b.name.chars().count()).max(14);
    writeln!(o, "  {:<34}{:>w$}{:>w$}", "", a.name, b.name)?;
    writeln!(
        o,
        "  {:<34}{:>w$.4}{:>w$.4}",
        "first-mode period [s]", a.periods[0], b.periods[0]
    )?;
    writeln!(
        o,
        "  {:<34}{:>w$.4}{:>w$.4}",
        "peak w(h) without pounding [m]",
        a.peak_displacement_no_contact,
        b.peak_displacement_no_contact
    )?;
    writeln!(
        o,
        "  {:<34}{:>w$.4}{:>w$.4}",
        "peak w(h) with pounding [m]", a.peak_displacement, b.peak_displacement
    )?;
    writeln!(
        o,
        "  {:<34}{:>+w$.1}{:>+w$.1}",
        "change [%]", a.change_percent, b.change_percent
    )?;
    if !a.floors.is_empty()
        && (sc.structures[0].floor_heights().is_some()
            || sc.structures[1].floor_heights().is_some())
    {
        let peak = |s: &crate::analysis::simulate::StructureReport,
                    f: fn(&crate::analysis::simulate::FloorReport) -> f64| {
            s.floors.iter().map(f).fold(0.0, f64::max)
        };
        writeln!(
            o,
            "  {:<34}{:>w$.3}{:>w$.3}",
            "peak floor accel. without [m/s²]",
            peak(a, |f| f.peak_acceleration_no_contact),
            peak(b, |f| f.peak_acceleration_no_contact)
        )?;
        writeln!(
            o,
            "  {:<34}{:>w$.3}{:>w$.3}",
            "peak floor accel. with [m/s²]",
            peak(a, |f| f.peak_acceleration),
            peak(b, |f| f.peak_acceleration)
        )?;
        // the storey drift over the storey's height, as engineers read it (and the figure shows)
        let ratio = |s: &crate::analysis::simulate::StructureReport, k: usize| {
            s.peak_drift_ratios()
                .iter()
                .map(|r| r[k])
                .fold(0.0, f64::max)
        };
        for (label, k) in [
            ("peak drift ratio without [%]", 1),
            ("peak drift ratio with [%]", 0),
        ] {
            writeln!(o, "  {label:<34}{:>w$.3}{:>w$.3}", ratio(a, k), ratio(b, k))?;
        }
    }
    // yielding buildings (issue 16); "–" for an elastic one
    let [sa, sb] = &r.structures;
    if sa.peak_ductility.is_some() || sb.peak_ductility.is_some() {
        let cell = |v: Option<f64>, scale: f64, digits: usize| {
            v.map_or("–".to_string(), |x| format!("{:.digits$}", x * scale))
        };
        type Pick = fn(&crate::analysis::simulate::StructureReport) -> Option<f64>;
        let rows: [(&str, Pick, f64, usize); 6] = [
            (
                "peak ductility without",
                |s| s.peak_ductility_no_contact,
                1.0,
                2,
            ),
            ("peak ductility with", |s| s.peak_ductility, 1.0, 2),
            (
                "residual drift without [mm]",
                |s| s.max_residual_drift_no_contact,
                1e3,
                2,
            ),
            ("residual drift with [mm]", |s| s.max_residual_drift, 1e3, 2),
            (
                "hysteretic energy without [kJ]",
                |s| s.hysteretic_energy_no_contact,
                1e-3,
                1,
            ),
            (
                "hysteretic energy with [kJ]",
                |s| s.hysteretic_energy,
                1e-3,
                1,
            ),
        ];
        for (label, pick, scale, digits) in rows {
            writeln!(
                o,
                "  {:<34}{:>w$}{:>w$}",
                label,
                cell(pick(sa), scale, digits),
                cell(pick(sb), scale, digits)
            )?;
        }
    }
    writeln!(o)?;
    let c = &r.contact;
    if c.impacts == 0 {
        writeln!(o, "  no contact: the gap never closed")?;
    } else {
        writeln!(
            o,
            "  {}, peak force {:.4e} N, max penetration {:.3} mm, {:.3} s in contact",
            impacts(c.impacts),
            c.peak_force,
            c.max_penetration * 1e3,
            c.contact_time
        )?;
    }
    if r.levels.len() > 1 {
        for l in &r.levels {
            writeln!(
                o,
                "    level h = {} m: {}, peak force {:.4e} N, {:.3} s in contact",
                l.height,
                impacts(l.impacts),
                l.peak_force,
                l.contact_time
            )?;
        }
    }
    if c.impacts > 0 {
        write_acceleration_pulses(o, r)?;
    }
    let s = &r.separation;
    writeln!(
        o,
        "  required separation [m]: time history {:.4} | ABS {:.4}  SRSS {:.4}  DDC {:.4}  (DDC as printed in the paper {:.4})",
        s.time_history, s.abs, s.srss, s.ddc, s.ddc_paper
    )?;
    if let Some(line) = time_history_verdict(r) {
        writeln!(o, "  {line}")?;
    }
    writeln!(
        o,
        "  energy balance error: {:.1e} with contact, {:.1e} without",
        r.energy.relative_error, r.energy_no_contact.relative_error
    )?;
    writeln!(o, "  {}", self_check_line(&r.accuracy))?;
    Ok(())
}

/// Each structure's largest absolute floor acceleration with pounding, where and when, and
/// what it is: during an impact, the impact's pulse (as long as the contact), not a design
/// value (the paper case's ~55 g at the top used to stand without a word).
fn write_acceleration_pulses(o: &mut String, r: &Report) -> fmt::Result {
    const G: f64 = 9.80665;
    writeln!(
        o,
        "  largest absolute floor acceleration with pounding (inside an impact it is the \
         impact's pulse, lasting as long as the contact: not a floor acceleration to design for):"
    )?;
    for s in &r.structures {
        let Some(f) = s
            .floors
            .iter()
            .max_by(|a, b| a.peak_acceleration.total_cmp(&b.peak_acceleration))
        else {
            continue;
        };
        let what = match &f.peak_acceleration_impact {
            Some(p) => format!(
                "the pulse of an impact at h = {} m lasting {:.1} ms",
                p.height,
                p.duration * 1e3
            ),
            None => "not during an impact".into(),
        };
        let without = s
            .floors
            .iter()
            .map(|f| f.peak_acceleration_no_contact)
            .fold(0.0, f64::max);
        writeln!(
            o,
            "    {}: {:.2} m/s² ({:.2} g) at h = {} m, t = {:.3} s: {what}; {:.2} m/s² ({:.2} g) without pounding",
            s.name,
            f.peak_acceleration,
            f.peak_acceleration / G,
            f.height,
            f.peak_acceleration_time,
            without,
            without / G
        )?;
    }
    Ok(())
}

/// One line saying whether the result passed its self-check.
pub fn self_check_line(a: &crate::analysis::simulate::accuracy::AccuracyCheck) -> String {
    use crate::analysis::simulate::accuracy::percent;
    let against = a.settings.map(|s| s.describe()).unwrap_or_default();
    if !a.checked {
        return "self-check: not done (--no-check): this result was NOT self-checked".into();
    }
    if let Some(f) = &a.failure {
        return format!("self-check: NOT CONVERGED — not verified: {f} (see the warning)");
    }
    let worst = a
        .quantities
        .iter()
        .find(|q| Some(q.name) == a.max_change_quantity)
        .map_or("", |q| q.label());
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

/// Whether the gap given suffices at every contact level by the exact time-history separation
/// (summary.json `separation.levels` and `verdict`), and the level that governs: where
/// gap − required is smallest. `None` without per-level checks.
pub fn time_history_verdict(r: &Report) -> Option<String> {
    let key = "time_history";
    let g = r.separation.verdict.rules.iter().find(|g| g.key == key)?;
    let n = r.separation.levels.len();
    let short = r
        .separation
        .levels
        .iter()
        .filter(|l| l.rules.iter().any(|c| c.key == key && !c.sufficient))
        .count();
    let what = match (short, n) {
        (0, 1) => "suffices".to_string(),
        (0, n) => format!("suffices at all {n}"),
        (_, 1) => "is TOO SMALL".to_string(),
        (k, n) => format!("is TOO SMALL at {k} of {n}"),
    };
    Some(format!(
        "time-history separation at every contact level: the gap {what}; governing: h = {} m ({:.1} mm required, gap {:.1} mm)",
        g.height,
        g.required * 1e3,
        g.gap * 1e3
    ))
}
