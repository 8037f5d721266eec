//! What `pounding separation` prints for a row of buildings: each adjacent pair's tables (a
//! pair's, [`mod@super::separation_report`]), then the row's verdict.

use std::fmt::{self, Write as _};

use crate::analysis::row_separation::RowGapReport;

/// The tables of `pounding separation` for a row (lengths in mm, heights in m).
pub fn row_separation_report(r: &RowGapReport) -> String {
    let mut o = String::new();
    write_report(&mut o, r).expect("writing to a String cannot fail");
    o
}

fn write_report(o: &mut String, r: &RowGapReport) -> fmt::Result {
    writeln!(o, "{}", r.title)?;
    let names: Vec<String> = r.structures.iter().map(|n| format!("\"{n}\"")).collect();
    writeln!(
        o,
        "  a row of {} structures, left to right: {}; each adjacent pair's required separation \
         (structure 1 = the pair's left, 2 = its right)",
        r.structures.len(),
        names.join(", ")
    )?;
    for w in &r.warnings {
        writeln!(o, "  warning: {w}")?;
    }
    for p in &r.pairs {
        writeln!(o)?;
        writeln!(
            o,
            "pair {} of {}: \"{}\" (1) – \"{}\" (2)",
            p.index + 1,
            r.pairs.len(),
            p.between[0],
            p.between[1]
        )?;
        // the pair's report without its title line (the row's is above)
        let text = super::separation_report(&p.report);
        o.push_str(text.split_once('\n').map_or("", |(_, rest)| rest));
    }
    writeln!(o)?;
    let v = &r.verdict;
    let pairs = |list: &[usize]| {
        (list.iter())
            .map(|&p| {
                format!(
                    "{} (\"{}\"–\"{}\")",
                    p + 1,
                    r.structures[p],
                    r.structures[p + 1]
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    match (&v.governing, v.pair) {
        (Some(g), Some(p)) => writeln!(
            o,
            "row verdict: pair {} governs: {} at h = {} m ({:.3} mm required, gap {:.3} mm, \
             margin {:.3} mm)",
            pairs(&[p]),
            g.label,
            g.height,
            1e3 * g.required,
            1e3 * g.gap,
            1e3 * g.margin
        )?,
        _ => writeln!(o, "row verdict: no rule was evaluated")?,
    }
    if v.insufficient_pairs.is_empty() {
        writeln!(
            o,
            "  every pair's gap suffices by every rule at every level"
        )?;
    } else {
        writeln!(
            o,
            "  gap TOO SMALL by some rule in pair(s) {}",
            pairs(&v.insufficient_pairs)
        )?;
    }
    Ok(())
}
