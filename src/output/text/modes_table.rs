//! What `pounding modes` prints: each structure's modes (period, frequency, ω, damping ratio,
//! φ(h)·√M at the contact height, participation factor, effective mass share) and, for
//! buildings with floors, the mode shapes at the floors.

use std::fmt::{self, Write as _};

use crate::input::scenario::Scenario;

/// The table of `pounding modes` for `sc` (periods in s, frequencies in Hz, ω in rad/s).
pub fn modes_table(sc: &Scenario) -> String {
    let mut o = String::new();
    write_modes(&mut o, sc).expect("writing to a String cannot fail");
    o
}

fn write_modes(o: &mut String, sc: &Scenario) -> fmt::Result {
    let h = sc.main_height();
    for (i, s) in sc.structures.iter().enumerate() {
        let m = s.modal();
        let stiffness = match s {
            crate::model::structure::Structure::Cantilever(c) => {
                format!("cantilever, EI = {:.4e} N·m²", c.bending_stiffness())
            }
            crate::model::structure::Structure::Floors(f) => format!(
                "{} floors, {} of {} modes kept",
                f.all_modes.floor_heights().map_or(0, |h| h.len()),
                f.modes,
                f.all_modes.len()
            ),
        };
        writeln!(
            o,
            "structure {} \"{}\": L = {} m, M = {:.4e} kg, {stiffness}",
            i + 1,
            s.name(),
            s.length(),
            s.mass(),
        )?;
        writeln!(
            o,
            "  {:>4} {:>12} {:>12} {:>12} {:>9} {:>14} {:>14} {:>10}",
            "mode", "period [s]", "freq [Hz]", "ω [rad/s]", "ζ", "φ(h)·√M", "Γ [kg^½]", "mass [%]"
        )?;
        for n in 0..m.omega.len() {
            let w = m.omega[n];
            writeln!(
                o,
                "  {:>4} {:>12.6} {:>12.5} {:>12.4} {:>9.5} {:>14.6} {:>14.4} {:>10.3}",
                n + 1,
                2.0 * std::f64::consts::PI / w,
                w / (2.0 * std::f64::consts::PI),
                w,
                m.zeta[n],
                m.shape(n, h) * m.mass.sqrt(),
                m.participation_factor(n),
                100.0 * m.effective_mass_fraction(n)
            )?;
        }
        if let Some(heights) = s.floor_heights() {
            // the floors' mode shapes, each normalised to 1 at the top (as engineers read them)
            let shown = m.len().min(8);
            write!(o, "  {:>10}", "floor [m]")?;
            for n in 0..shown {
                write!(o, " {:>9}", format!("φ{}", n + 1))?;
            }
            writeln!(o)?;
            for &fh in heights.iter().rev() {
                write!(o, "  {fh:>10.3}")?;
                for n in 0..shown {
                    let top = m.shape(n, heights[heights.len() - 1]);
                    write!(o, " {:>9.4}", m.shape(n, fh) / top)?;
                }
                writeln!(o)?;
            }
            if shown < m.len() {
                writeln!(o, "  (the first {shown} of {} modes)", m.len())?;
            }
        }
        writeln!(o)?;
    }
    writeln!(
        o,
        "φ(h) at the contact height h = {h} m, times √M (dimensionless; ±2 at a cantilever's free tip). Γ (m∫φ dx,\n\
         or φᵀM1 for floors) is the participation factor (η̈ + … = −Γ a_g); mass % = Γ²/M, the share of the mass\n\
         each mode moves."
    )?;
    Ok(())
}
