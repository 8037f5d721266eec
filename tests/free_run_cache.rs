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

/// The rows of `text`'s sweep (a sweep file's text, its paths relative to `dir`) computed
/// each alone, in a sweep of its own whose cache starts empty (so nothing is shared), and
/// written as results.csv: the table without the cache.
fn results_alone(text: &str, file: &Path, out: &Path, check: bool) -> Vec<u8> {
    let first = Sweep::from_toml(text, file).unwrap();
    let lines: Vec<String> = (0..first.len())
        .map(|c| {
            let alone = Sweep::from_toml(text, file).unwrap();
            let row = compute_case(&alone, c, check);
            assert_eq!(alone.free_runs().hits(), 0);
            assert!(!row.failed, "{}", row.line);
            row.line
        })
        .collect();
    let path = out.join("alone.csv");
    pounding::study::sweep::results::write_results(
        &path,
        &pounding::study::sweep::results::header(&first),
        lines.iter().map(String::as_str),
    )
    .unwrap();
    std::fs::read(path).unwrap()
}

/// results.csv of `text`'s sweep run as `pounding sweep` runs it (one thread, the cache in
/// use), and the cache's hits.
fn results_shared(text: &str, file: &Path, out: &Path, check: bool) -> (Vec<u8>, usize) {
    use pounding::study::sweep::run::{RunOptions, Silent, run};
    let sw = Sweep::from_toml(text, file).unwrap();
    assert!(sw.free_runs().enabled());
    let opts = RunOptions {
        out_dir: out.join(format!("shared-{check}")),
        jobs: 1,
        shard: pounding::study::sweep::Shard::ALL,
        check,
    };
    let o = run(&sw, &opts, &mut Silent).unwrap();
    assert_eq!(o.failed, 0);
    (std::fs::read(o.results).unwrap(), sw.free_runs().hits())
}

/// A sweep over a suite of records on a row of buildings (examples/suite-row-sweep.toml: 3
/// stiffnesses of the middle building × 3 gaps of its second pair, 3 records): the cases that
/// differ only in the gap share each record's run without contact — one thread computes the 3
/// cases of a stiffness one after another, so all but the first case of each of the 3 groups
/// are served, 3 records each — and results.csv is byte-identical to the table of the cases
/// computed alone, with the self-check and without.
#[test]
fn a_row_suite_sweep_shares_runs_without_contact_and_gives_the_same_table() {
    let d = tempfile::tempdir().unwrap();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/suite-row-sweep.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    for check in [false, true] {
        let (shared, hits) = results_shared(&text, &file, d.path(), check);
        assert_eq!(hits, (9 - 3) * 3, "check {check}");
        assert_eq!(
            String::from_utf8(shared).unwrap(),
            String::from_utf8(results_alone(&text, &file, d.path(), check)).unwrap(),
            "check {check}"
        );
    }
}

/// A sweep over a row of three buildings (one run per case) along both pairs' gaps and the
/// ground motion's period: cases apart only in their gaps share the row's run without contact
/// (2 groups of 4 cases: 6 served), and results.csv is byte-identical to the table of the
/// cases computed alone (exact-modal and adaptive, whose self-check integrates its own run
/// without contact only where storeys yield — here never; rk4, whose check has its own).
#[test]
fn a_row_sweep_shares_runs_without_contact_and_gives_the_same_table() {
    let d = tempfile::tempdir().unwrap();
    let building = |name: &str, n: usize, k: f64| {
        format!(
            "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
             storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\n\
             damping_ratio = 0.05\n"
        )
    };
    let contact = |a: &str, b: &str, h: f64| {
        format!(
            "[[contact]]\nbetween = [\"{a}\", \"{b}\"]\nstiffness = 2.0e10\nheight = {h:?}\n\
             gap = 0.004\n"
        )
    };
    for (method, dt) in [("exact-modal", 0.01), ("adaptive", 0.005), ("rk4", 0.002)] {
        let base = [
            building("A", 3, 3.0e8),
            building("B", 5, 1.6e8),
            building("C", 4, 2.2e8),
            contact("A", "B", 10.5),
            contact("B", "C", 14.0),
            "[ground_motion]\nkind = \"harmonic\"\npga = 0.35\nperiod = 0.8\n".into(),
            format!("[solver]\nmethod = \"{method}\"\ndt = {dt}\nduration = 3.0\n"),
        ]
        .concat();
        std::fs::write(d.path().join("row.toml"), base).unwrap();
        let text = "scenario = \"row.toml\"\n\
             [[axis]]\nkey = \"ground_motion.period\"\nvalues = [0.6, 0.8]\n\
             [[axis]]\nkey = \"contact[1].gap\"\nvalues = [0.004, 0.5]\n\
             [[axis]]\nkey = \"contact[2].gap\"\nvalues = [0.006, 0.5]\n";
        let file = d.path().join("s.toml");
        let out = d.path().join(method);
        std::fs::create_dir_all(&out).unwrap();
        for check in [false, true] {
            let (shared, hits) = results_shared(text, &file, &out, check);
            assert_eq!(hits, 8 - 2, "{method} check {check}");
            assert_eq!(
                String::from_utf8(shared).unwrap(),
                String::from_utf8(results_alone(text, &file, &out, check)).unwrap(),
                "{method} check {check}"
            );
        }
    }
}

/// A row's report from another row's runs without contact (the same structures, motion and
/// solver; other gaps, stiffness and law) is the report computed from scratch, every field
/// (histories included, `Debug` text: bit for bit, NaN too), with and without the self-check,
/// for every method; and the two rows have the same key, a row with another level height not.
#[test]
fn a_rows_report_from_another_rows_runs_without_contact_is_its_own() {
    use pounding::analysis::simulate::{FreeRunKey, simulate_row_checked, simulate_row_reusing};
    use pounding::input::scenario::Scenario;
    let row = |method: &str, dt: f64, contact: &str, h: f64| {
        let b = |name: &str, n: usize, k: f64| {
            format!(
                "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
                 storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\n\
                 damping_ratio = 0.05\n"
            )
        };
        let text = [
            b("A", 3, 3.0e8),
            b("B", 5, 1.6e8),
            b("C", 4, 2.2e8),
            format!("[[contact]]\nbetween = [\"A\", \"B\"]\n{contact}height = 10.5\n"),
            format!("[[contact]]\nbetween = [\"B\", \"C\"]\n{contact}height = {h:?}\n"),
            "[ground_motion]\nkind = \"harmonic\"\npga = 0.35\nperiod = 0.8\n".into(),
            format!("[solver]\nmethod = \"{method}\"\ndt = {dt}\nduration = 3.0\n"),
        ]
        .concat();
        Scenario::from_toml(&text, "row.toml", Path::new(".")).unwrap()
    };
    for (method, dt) in [("exact-modal", 0.01), ("adaptive", 0.005), ("rk4", 0.002)] {
        let a = row(method, dt, "stiffness = 2.0e10\ngap = 0.004\n", 14.0);
        let b = row(
            method,
            dt,
            "law = \"jankowski\"\nstiffness = 2.75e9\nrestitution = 0.65\ngap = 0.5\n",
            14.0,
        );
        for check in [false, true] {
            let (ka, kb) = (FreeRunKey::of_row(&a, check), FreeRunKey::of_row(&b, check));
            assert!(ka.is_some() && ka == kb);
            let other = FreeRunKey::of_row(
                &row(method, dt, "stiffness = 2.0e10\ngap = 0.004\n", 10.5),
                check,
            );
            assert!(other != ka);
            let (_, runs) = simulate_row_reusing(&b, check, None).unwrap();
            let (reused, _) = simulate_row_reusing(&a, check, Some(&runs)).unwrap();
            let own = simulate_row_checked(&a, check).unwrap();
            assert!(own.pairs.iter().all(|p| p.contact.impacts > 0), "a pounds");
            assert_eq!(
                format!("{reused:?}"),
                format!("{own:?}"),
                "{method} check {check}"
            );
        }
    }
}
