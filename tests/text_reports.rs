//! The run summary's per-level separation line (issue 26): whether the gap given suffices at
//! every contact level by the exact time-history separation, and which level governs —
//! checked against the per-level numbers of the report (each level's `max(w1 − w2)` without
//! pounding and its gap), not against the verdict the line is formed from.

use std::path::Path;

use pounding::analysis::simulate::simulate;
use pounding::input::scenario::Scenario;
use pounding::output::text::{run_summary, time_history_verdict};

/// The bundled example with two contact levels, and the same with gaps so wide that the
/// structures never touch.
#[test]
fn separation_line_names_every_level_and_the_governing_one() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/two-levels.toml");
    let sc = Scenario::from_file(&path).unwrap();
    let r = simulate(&sc).unwrap();
    assert!(
        r.separation.levels.len() >= 2,
        "the example has several levels"
    );
    // by hand from each level's exact separation and gap
    let mut short = 0;
    let mut governing: Option<(f64, f64, f64)> = None; // (margin, height, required)
    for (lv, rec) in sc.contact.levels.iter().zip(&r.separation.levels) {
        let exact = rec
            .exact
            .expect("a time history gives the exact separation");
        assert_eq!(lv.height, rec.height);
        if lv.gap < exact {
            short += 1;
        }
        let margin = lv.gap - exact;
        if governing.is_none_or(|(m, _, _)| margin < m) {
            governing = Some((margin, lv.height, exact));
        }
    }
    let (_, h, required) = governing.unwrap();
    let n = sc.contact.levels.len();
    let verdict = if short == 0 {
        format!("the gap suffices at all {n}")
    } else {
        format!("the gap is TOO SMALL at {short} of {n}")
    };
    let line = time_history_verdict(&r).unwrap();
    assert!(line.contains(&verdict), "{line} — expected `{verdict}`");
    assert!(
        line.contains(&format!(
            "governing: h = {h} m ({:.1} mm required",
            required * 1e3
        )),
        "{line}"
    );
    // and the summary prints it right after the separation of the highest level
    let text = run_summary(&sc, "two-levels.toml", &r);
    let lines: Vec<&str> = text.lines().collect();
    let k = lines
        .iter()
        .position(|l| l.starts_with("  required separation [m]:"))
        .unwrap();
    assert_eq!(lines[k + 1], format!("  {line}"));

    // gaps wider than any separation: suffices everywhere
    let wide = std::fs::read_to_string(&path)
        .unwrap()
        .replace("gap = 0.", "gap = 5.");
    let sc = Scenario::from_toml(&wide, "wide.toml", path.parent().unwrap()).unwrap();
    let r = simulate(&sc).unwrap();
    assert_eq!(r.contact.impacts, 0, "5 m gaps are never closed");
    let line = time_history_verdict(&r).unwrap();
    assert!(
        line.contains(&format!("the gap suffices at all {n}")),
        "{line}"
    );
}
