//! docs/scenario-keys.md is generated from the key table (`input::scenario::keys`) and must be
//! current; the table's facts are the ones the checks use.

use pounding::input::scenario::keys::{self, ALL_TABLES, Table};
use pounding::input::scenario::{physical_range, usual_range};

#[test]
fn the_committed_key_reference_is_current() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scenario-keys.md");
    let generated = keys::markdown();
    let committed = std::fs::read_to_string(path).unwrap_or_default();
    if committed != generated {
        if std::env::var_os("POUNDING_WRITE_DOCS").is_some() {
            std::fs::write(path, &generated).expect("write docs/scenario-keys.md");
            return;
        }
        panic!(
            "docs/scenario-keys.md is not what the key table gives: regenerate it with\n  {}\n\
             (or POUNDING_WRITE_DOCS=1 cargo test --release --test scenario_keys)",
            keys::REGENERATE
        );
    }
}

#[test]
fn every_key_with_a_range_appears_in_the_reference_with_it() {
    let doc = keys::markdown();
    for k in keys::all() {
        assert!(doc.contains(&format!("| `{}` |", k.name)), "{}", k.path());
        if let Some(r) = k.physical {
            // the lookup the checks use finds this key's range by its path
            let path = k
                .path()
                .replace("[i]", "[1]")
                .replace("[j]", "[2]")
                .replace("[k]", "[3]");
            assert_eq!(physical_range(&path), Some((r.lo, r.hi, r.why)), "{path}");
            assert!(doc.contains(&format!("[{:e}, {:e}]", r.lo, r.hi)), "{path}");
        }
        if let Some(r) = k.usual {
            let path = k.path().replace("[i]", "[1]").replace("[j]", "[2]");
            assert_eq!(usual_range(&path), Some((r.lo, r.hi, r.why)), "{path}");
        }
    }
}

#[test]
fn sweep_axes_and_tables_come_from_the_table() {
    // the tables a sweep may set have sweep paths, the others none
    for t in ALL_TABLES {
        let sweepable = t.keys().any(|k| k.sweep);
        assert_eq!(sweepable, t.sweep_path().is_some(), "{}", t.title());
    }
    let gap = Table::Contact.keys().find(|k| k.name == "gap").unwrap();
    assert_eq!(gap.sweep_key().as_deref(), Some("contact.gap"));
    assert_eq!(gap.unit, "m");
}
