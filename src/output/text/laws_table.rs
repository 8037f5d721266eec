//! What `pounding laws` prints: the restitution each contact law that takes a target e
//! achieves on an isolated two-body impact, per target.

use std::fmt::{self, Write as _};

use crate::analysis::restitution::RestitutionTable;

/// The table of `pounding laws` (one row per law, one column per target e).
pub fn laws_table(t: &RestitutionTable) -> String {
    let mut o = String::new();
    write_table(&mut o, t).expect("writing to a String cannot fail");
    o
}

fn write_table(o: &mut String, t: &RestitutionTable) -> fmt::Result {
    write!(o, "  {:<36}", "law \\ target e")?;
    for e in &t.targets {
        write!(o, "{e:>7}")?;
    }
    writeln!(o)?;
    for (law, achieved) in &t.rows {
        write!(o, "  {:<36}", law.label())?;
        for e in achieved {
            write!(o, "{e:>7.3}")?;
        }
        writeln!(o)?;
    }
    writeln!(o)?;
    writeln!(
        o,
        "  achieved e = separation speed / approach speed ({} m/s) of an isolated impact of two bodies, through the solver",
        t.speed
    )
}
