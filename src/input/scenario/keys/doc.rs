//! docs/scenario-keys.md, generated from the key table.

use std::fmt::Write as _;

use super::{ALL_TABLES, DERIVED, KeyInfo, Range};

/// The command that writes docs/scenario-keys.md (the test `scenario_keys` fails, naming it,
/// when the committed file differs from [`markdown`]).
pub const REGENERATE: &str = "cargo run --release --example scenario-keys > docs/scenario-keys.md";

/// A range as the messages write it: `[1e-1, 2e3]` (the shortest exponent form).
fn range(r: &Range, unit: &str) -> String {
    let unit = if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    };
    format!("[{:e}, {:e}]{unit}", r.lo, r.hi)
}

/// Markdown table cells cannot hold a `|`.
fn cell(s: &str) -> String {
    s.replace('|', "\\|")
}

fn row(out: &mut String, k: &KeyInfo) {
    let physical = k.physical.map_or_else(String::new, |r| {
        format!("{} ({})", range(&r, k.unit), cell(r.why))
    });
    let usual = k.usual.map_or_else(String::new, |r| range(&r, k.unit));
    let axis = k.sweep_key().map_or_else(String::new, |a| format!("`{a}`"));
    let _ = writeln!(
        out,
        "| `{}` | {} | {} | {} | {} | {} | {} |",
        k.name,
        k.kind.name(),
        k.unit,
        cell(k.doc),
        physical,
        usual,
        axis
    );
}

/// docs/scenario-keys.md: every key of a scenario file, table by table, with its type, unit,
/// meaning, physical range (refused outside), usual band (warned outside, with why) and the
/// sweep axis that sets it.
pub fn markdown() -> String {
    let mut out = String::new();
    out.push_str(
        "# Scenario keys\n\n\
         <!-- Generated from src/input/scenario/keys (the one table of the keys); do not edit. -->\n\n",
    );
    let _ = writeln!(
        out,
        "Every key of a scenario file, generated from the program's own table of keys, from which \
         its checks, messages, sweep axes and plot labels come. Regenerate with\n`{REGENERATE}`; \
         the test `scenario_keys` fails when this file is not current.\n"
    );
    out.push_str(
        "- **physical**: a value outside is refused, naming the file, line, key and range;\n\
         - **usual**: a value inside the physical range but outside this band is accepted with a \
         warning that gives the band and why (below);\n\
         - **sweep axis**: the key as a sweep's `[[axis]] key` names it (`N`: 1-based index).\n\n\
         Units are SI; an empty unit is a ratio, a name, or given in the meaning.\n",
    );
    for t in ALL_TABLES {
        let _ = writeln!(out, "\n## {}\n", t.title());
        out.push_str(
            "| key | type | unit | meaning | physical | usual | sweep axis |\n\
             |---|---|---|---|---|---|---|\n",
        );
        for k in t.keys() {
            row(&mut out, k);
        }
    }
    out.push_str("\n## Why the usual bands\n\n");
    for k in super::all() {
        if let Some(r) = k.usual {
            let _ = writeln!(out, "- `{}` {}: {}.", k.path(), range(&r, k.unit), r.why);
        }
    }
    out.push_str(
        "\nTwo quantities that are not keys but what keys give together are warned about once \
         per building:\n\n",
    );
    for (name, r) in DERIVED {
        let _ = writeln!(out, "- `{name}` {}: {}.", range(r, ""), r.why);
    }
    out
}
