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

/// One ladder of runs with each run's change against the finest: each structure's peak (a
/// pair: w1, w2 at the main contact height; a row: w_i at structure i's highest contact level)
/// and each adjacent pair's peak force (a pair: F; a row: F_p of pair p, between structures p
/// and p + 1).
fn write_rows(o: &mut String, title: &str, rows: &[Row]) -> fmt::Result {
    let n = rows.first().map_or(2, |r| r.peaks.len());
    let force = |p: usize| if n == 2 { String::new() } else { p.to_string() };
    writeln!(o)?;
    writeln!(o, "  {title}")?;
    write!(
        o,
        "  {:>6} {:>12} {:>10} {:>8}",
        "modes", "method", "dt [s]", "rtol"
    )?;
    for i in 1..=n {
        write!(o, " {:>11}", format!("peak w{i} [m]"))?;
    }
    for p in 1..n {
        write!(o, " {:>13}", format!("peak F{} [N]", force(p)))?;
    }
    write!(o, " {:>8}", "impacts")?;
    for i in 1..=n {
        write!(o, " {:>9}", format!("Δw{i} [%]"))?;
    }
    for p in 1..n {
        write!(o, " {:>9}", format!("ΔF{} [%]", force(p)))?;
    }
    writeln!(o)?;
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
        write!(
            o,
            "  {:>6} {:>12} {:>10.2e} {:>8}",
            r.modes, r.method, r.dt, rtol
        )?;
        for w in &r.peaks {
            write!(o, " {w:>11.5}")?;
        }
        for f in &r.forces {
            write!(o, " {f:>13.5e}")?;
        }
        write!(o, " {:>8}", r.impacts)?;
        for c in &r.change {
            write!(o, " {:>9.3}", 100.0 * c)?;
        }
        writeln!(o)?;
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
    let structures = t.modes.first().map_or(2, |r| r.peaks.len());
    let yielding: Vec<usize> = (0..structures)
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
