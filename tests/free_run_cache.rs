//! A sweep over contact keys shares the runs without contact of its cases
//! (`study::sweep::free_cache`): every row is byte-identical to the row of the same case
//! computed alone (a sweep of its own, whose cache starts empty), and the cache serves every
//! case but the first of each group that shares structures, motion and solver settings.

use std::path::Path;

use pounding::study::sweep::Sweep;
use pounding::study::sweep::run::{compute_all, compute_case};

/// A sweep over `axes` on the paper's case c with `method` at `dt`, 3 s.
fn sweep(dir: &Path, method: &str, dt: f64, axes: &str) -> (Sweep, String) {
    let base = include_str!("../examples/paper-c.toml")
        .replace("duration = 20.0", "duration = 3.0")
        .replace("method = \"rk4\"", &format!("method = \"{method}\""))
        .replace("dt = 0.001", &format!("dt = {dt}"));
    std::fs::write(dir.join("base.toml"), base).unwrap();
    let text = format!("scenario = \"base.toml\"\n{axes}");
    (Sweep::from_toml(&text, &dir.join("s.toml")).unwrap(), text)
}

const CONTACT_AXES: &str = "[[axis]]\nkey = \"period_ratio\"\nvalues = [0.7, 0.9]\n\
     [[axis]]\nkey = \"contact.gap\"\nvalues = [0.0127, 0.05, 5.0]\n\
     [[axis]]\nkey = \"contact.stiffness\"\nvalues = [2.808e10, 1.0e10]\n";

#[test]
fn rows_with_shared_runs_without_contact_equal_rows_computed_alone() {
    let d = tempfile::tempdir().unwrap();
    for (method, dt) in [("exact-modal", 0.01), ("adaptive", 0.005), ("rk4", 0.002)] {
        for check in [false, true] {
            let (sw, text) = sweep(d.path(), method, dt, CONTACT_AXES);
            assert!(sw.free_runs().enabled());
            let n = sw.len();
            assert_eq!(n, 12);
            // one thread: the cases of one period ratio follow one another, so all but the
            // first of each of the 2 groups are served
            let shared = compute_all(&sw, 1, check).unwrap();
            assert_eq!(sw.free_runs().hits(), n - 2, "{method} check {check}");
            for (c, row) in shared.iter().enumerate() {
                let alone = Sweep::from_toml(&text, &d.path().join("s.toml")).unwrap();
                let own = compute_case(&alone, c, check);
                assert_eq!(alone.free_runs().hits(), 0);
                assert!(!row.failed && !own.failed, "{}", own.line);
                assert_eq!(row.line, own.line, "{method} check {check} case {c}");
            }
            // two threads: the same rows
            let (sw2, _) = sweep(d.path(), method, dt, CONTACT_AXES);
            let two: Vec<String> = compute_all(&sw2, 2, check)
                .unwrap()
                .into_iter()
                .map(|r| r.line)
                .collect();
            let one: Vec<String> = shared.into_iter().map(|r| r.line).collect();
            assert_eq!(one, two, "{method} check {check}");
        }
    }
}

/// Without an axis on a contact key no two cases share a run without contact: the cache is
/// off (nothing hashed or held).
#[test]
fn cache_is_off_without_contact_axes() {
    let d = tempfile::tempdir().unwrap();
    let (sw, _) = sweep(
        d.path(),
        "exact-modal",
        0.01,
        "[[axis]]\nkey = \"period_ratio\"\nvalues = [0.7, 0.9]\n",
    );
    assert!(!sw.free_runs().enabled());
    compute_all(&sw, 1, false).unwrap();
    assert_eq!(sw.free_runs().hits(), 0);
}
