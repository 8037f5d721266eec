//! What `pounding convergence` prints: the ladders of runs (modes, steps or tolerances) with
//! each run's change against the finest, the yielding storeys of the same runs, and the
//! recommendation or NOT CONVERGED.

use std::fmt::{self, Write as _};

use crate::analysis::convergence::{ConvergenceTable, Row};

/// The table of `pounding convergence` (peaks in m, forces in N, changes in %).
pub fn convergence_table(t: &ConvergenceTable) -> String {
    let mut o = String::new();
    write_table(&mut o, t).expect("writing to a String cannot fail");
    o
}

/// One ladder of runs with each run's change against the finest.
fn write_rows(o: &mut String, title: &str, rows: &[Row]) -> fmt::Result {
    writeln!(o)?;
    writeln!(o, "  {title}")?;
    writeln!(
        o,
        "  {:>6} {:>12} {:>10} {:>8} {:>11} {:>11} {:>13} {:>8} {:>9} {:>9} {:>9}",
        "modes",
        "method",
        "dt [s]",
        "rtol",
        "peak w1 [m]",
        "peak w2 [m]",
        "peak F [N]",
        "impacts",
        "Δw1 [%]",
        "Δw2 [%]",
        "ΔF [%]"
    )?;
    for r in rows {
        let rtol = r.rtol.map_or("-".to_string(), |x| format!("{x:.0e}"));
        if let Some(f) = &r.failure {
            writeln!(
                o,
                "  {:>6} {:>12} {:>10.2e} {:>8}  FAILED: {}",
                r.modes,
                r.method,
                r.dt,
                rtol,
                first_sentence(f)
            )?;
            continue;
        }
        writeln!(
            o,
            "  {:>6} {:>12} {:>10.2e} {:>8} {:>11.5} {:>11.5} {:>13.5e} {:>8} {:>9.3} {:>9.3} {:>9.3}",
            r.modes,
            r.method,
            r.dt,
            rtol,
            r.peak_w1,
            r.peak_w2,
            r.peak_force,
            r.impacts,
            100.0 * r.change[0],
            100.0 * r.change[1],
            100.0 * r.change[2]
        )?;
    }
    Ok(())
}

/// The same runs' yielding storeys (ductility, residual drift, hysteretic energy) of the
/// structures in `yielding` (indices 0, 1); nothing when none yields.
fn write_yielding(o: &mut String, yielding: &[usize], rows: &[Row]) -> fmt::Result {
    if yielding.is_empty() {
        return Ok(());
    }
    writeln!(o, "  the yielding buildings in the same runs:")?;
    write!(
        o,
        "  {:>6} {:>12} {:>10} {:>8}",
        "modes", "method", "dt [s]", "rtol"
    )?;
    for i in yielding {
        let i = i + 1;
        write!(
            o,
            " {:>7} {:>9} {:>10} {:>8} {:>9} {:>9}",
            format!("μ{i}"),
            format!("res{i} [mm]"),
            format!("E_h{i} [kJ]"),
            format!("Δμ{i} [%]"),
            format!("Δres{i} [%]"),
            format!("ΔE_h{i} [%]")
        )?;
    }
    writeln!(o)?;
    for r in rows.iter().filter(|r| r.failure.is_none()) {
        let rtol = r.rtol.map_or("-".to_string(), |x| format!("{x:.0e}"));
        write!(
            o,
            "  {:>6} {:>12} {:>10.2e} {:>8}",
            r.modes, r.method, r.dt, rtol
        )?;
        for &i in yielding {
            match (r.yielding[i], r.yield_change[i]) {
                (Some(y), Some(c)) => write!(
                    o,
                    " {:>7.3} {:>9.2} {:>10.1} {:>8.3} {:>9.3} {:>9.3}",
                    y.ductility,
                    1e3 * y.residual_drift,
                    1e-3 * y.hysteretic_energy,
                    100.0 * c[0],
                    100.0 * c[1],
                    100.0 * c[2]
                )?,
                _ => write!(
                    o,
                    " {:>7} {:>9} {:>10} {:>8} {:>9} {:>9}",
                    "-", "-", "-", "-", "-", "-"
                )?,
            }
        }
        writeln!(o)?;
    }
    Ok(())
}

fn write_table(o: &mut String, t: &ConvergenceTable) -> fmt::Result {
    // yielding buildings (issue 24): their ductility, residual drift and hysteretic energy
    let yielding: Vec<usize> = (0..2)
        .filter(|&i| {
            t.modes
                .iter()
                .chain(&t.steps)
                .any(|r| r.yielding[i].is_some())
        })
        .collect();
    write_rows(o, "modes (change vs the most modes):", &t.modes)?;
    write_yielding(o, &yielding, &t.modes)?;
    write_rows(o, "step / tolerance (change vs the finest):", &t.steps)?;
    write_yielding(o, &yielding, &t.steps)?;
    if !yielding.is_empty() {
        writeln!(o)?;
        writeln!(
            o,
            "  μ: peak ductility; res: largest |residual drift|, its change in units of the larger \
             of it and the smallest yield drift; E_h: hysteretic energy, its change in units of the \
             larger of it and 0.1 % of the input energy"
        )?;
    }
    writeln!(o)?;
    if t.converged {
        writeln!(
            o,
            "  recommendation (tolerance {} %): {}",
            100.0 * t.tolerance,
            t.recommendation
        )?;
    } else {
        writeln!(
            o,
            "  *** NOT CONVERGED within {} %: nothing is recommended ***",
            100.0 * t.tolerance
        )?;
    }
    for n in &t.notes {
        writeln!(o, "    {n}")?;
    }
    Ok(())
}

/// A failure message up to its first sentence (the table has one line per run).
fn first_sentence(text: &str) -> String {
    match text.find(". ") {
        Some(i) => format!("{} …", &text[..=i]),
        None => text.to_string(),
    }
}
