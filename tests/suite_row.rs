//! A suite of records on a row of buildings (issue 29 with issue 27's suites): the row's pair
//! against the pair suite where the second gap never closes (to the last digit), the design
//! value per pair and level against the code's rule applied here to suite.csv's per-record
//! values, the row's verdict against the least margin computed here, the files, and bad
//! inputs. The records are the bundled ones (examples/records), cut to a few seconds.

use std::path::{Path, PathBuf};

use pounding::input::scenario::Scenario;
use pounding::study::suite::{self, SuiteError};
use serde_json::Value;

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples")
}

/// A shear building of `n` storeys of 3.5 m.
fn building(name: &str, n: usize, k: f64) -> String {
    format!(
        "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
         storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\ndamping_ratio = 0.05\n"
    )
}

/// A `[[contact]]` between `a` and `b` with levels (height, gap) (m).
fn contact(a: &str, b: &str, levels: &[(f64, f64)]) -> String {
    let l: Vec<String> = levels
        .iter()
        .map(|(h, g)| format!("{{ height = {h}, gap = {g} }}"))
        .collect();
    format!(
        "[[contact]]\nbetween = [\"{a}\", \"{b}\"]\nlaw = \"jankowski\"\nstiffness = 2.75e9\n\
         restitution = 0.65\nlevel = [{}]\n",
        l.join(", ")
    )
}

const EC8: &str =
    r#"{ rule = "ec8", target = { spectrum = "ec8", ag = 2.0, ground_type = "C", type = 1 } }"#;
const ASCE7: &str = r#"{ rule = "asce7", target = { spectrum = "asce7", sds = 0.6, sd1 = 0.35, tl = 8.0 }, factor_limits = [0.25, 10.0] }"#;

/// The three Loma Prieta records of examples/suite-row.toml.
const THREE: [&str; 3] = [
    "{ file = \"records/RSN753_LOMAP_CLS000.AT2\" }",
    "{ file = \"records/RSN786_LOMAP_PAE055.AT2\" }",
    "{ file = \"records/RSN808_LOMAP_TRI000.AT2\" }",
];

/// The eleven records of examples/suite-asce7.toml.
const ELEVEN: [&str; 11] = [
    "{ file = \"records/RSN753_LOMAP_CLS000.AT2\" }",
    "{ file = \"records/RSN753_LOMAP_CLS090.AT2\" }",
    "{ file = \"records/RSN786_LOMAP_PAE055.AT2\" }",
    "{ file = \"records/RSN808_LOMAP_TRI000.AT2\" }",
    "{ file = \"records/RSN813_LOMAP_YBI090.AT2\" }",
    "{ file = \"records/ce36456p_CE36456.V2\", component = 1 }",
    "{ file = \"records/INGLEWOO.V2\", component = 1 }",
    "{ file = \"records/MTWILSON.V2\", component = 1 }",
    "{ file = \"records/SYLMOVFF.V2\", component = 1 }",
    "{ file = \"records/CE58667.V2\", component = 1 }",
    "{ file = \"records/CE89146.V2\", component = 1 }",
];

fn ground(records: &[&str], scaling: &str) -> String {
    format!(
        "[ground_motion]\nkind = \"suite\"\nrecords = [\n  {}\n]\nscaling = {scaling}\n",
        records.join(",\n  ")
    )
}

fn parse(text: &str) -> Scenario {
    Scenario::from_toml(text, "row-suite.toml", &examples())
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn refused(text: &str) -> String {
    match Scenario::from_toml(text, "row-suite.toml", &examples()) {
        Ok(_) => panic!("must be refused:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// A row of three (A 4 storeys, B 5, C a copy of A) where the second gap never closes: pair
/// 1's per-record numbers, its structures' peaks and its design values are the pair suite's of
/// A and B. C is a copy of A so that the row's first-mode periods are the pair's (the
/// scaling's period range and grid, hence the factors, are the same) and the system's largest
/// first-mode ω is the pair's (exact-modal's tolerance on δ̇ scales with it); with the second
/// pair's force exactly 0, the first pair's arithmetic is the pair's
/// (`a_row_whose_second_gap_never_closes_is_the_pair_and_the_third_alone`, tests/rows.rs).
///
/// With one level A–B every number is the pair's to the last digit. With two levels A–B (the
/// second at the height of the B–C level) the numbers of the runs without contact (required
/// separations, their design values, the peaks without contact) and the forces and impacts
/// are still the same bits, but a peak with contact and the contact time move at round-off
/// (measured: 1.7e-13 and 2.3e-12 relative on one record of three): the row's contact step
/// carries the B–C level in its band (zero force) beside the two A–B levels, which changes the
/// floating-point path of an episode's end; 1e-10 relative bounds that with a margin and is
/// far below anything an engineer reads.
#[test]
fn a_row_suite_whose_second_gap_never_closes_is_the_pair_suite() {
    let (a, b, c) = (
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        building("C", 4, 3.0e8),
    );
    let solver = "[solver]\nmethod = \"exact-modal\"\ndt = 0.005\nduration = 6.0\n";
    for (ab, tol) in [
        (&[(14.0, 0.01)][..], 0.0),
        (&[(14.0, 0.01), (10.5, 0.01)][..], 1e-10),
    ] {
        let row = parse(&format!(
            "{a}{b}{c}{}{}{}{solver}",
            contact("A", "B", ab),
            contact("B", "C", &[(10.5, 10.0)]),
            ground(&THREE, EC8)
        ));
        let pair = row.pair(0);
        assert!(row.is_row() && !pair.is_row() && pair.suite.is_some());
        let r = suite::row::run_row(&row, false).expect("row suite");
        let p = suite::run(&pair, false).expect("pair suite");
        assert_eq!(r.records.len(), 3);
        let mut pounded = 0;
        for (x, y) in r.records.iter().zip(&p.records) {
            assert_eq!(x.factor, y.factor, "{}", x.file);
            let (hx, hy) = (&x.headline, &y.headline);
            let same = |row_key: &str, pair_key: &str, tol: f64| {
                let (u, v) = (hx.get(row_key), hy.get(pair_key));
                let (Some(u), Some(v)) = (u, v) else {
                    panic!("{row_key} / {pair_key}")
                };
                assert!(
                    u == v || (u - v).abs() <= tol * v.abs(),
                    "{} ({} levels): {row_key} {u} vs the pair's {pair_key} {v}",
                    x.file,
                    ab.len()
                );
            };
            same("pga", "pga", 0.0);
            for i in 1..=2 {
                same(
                    &format!("structure{i}_peak_displacement"),
                    &format!("peak_displacement_{i}"),
                    tol,
                );
                same(
                    &format!("structure{i}_peak_displacement_no_contact"),
                    &format!("peak_displacement_no_contact_{i}"),
                    0.0,
                );
            }
            for k in ["impacts", "peak_force"] {
                same(&format!("pair1_{k}"), k, 0.0);
            }
            for k in ["max_penetration", "contact_time"] {
                same(&format!("pair1_{k}"), k, tol);
            }
            same("pair1_sep_time_history", "required_separation", 0.0);
            for k in 1..=ab.len() {
                for q in ["required_separation", "peak_force", "impacts"] {
                    same(
                        &format!("pair1_level{k}_{q}"),
                        &format!("level{k}_{q}"),
                        0.0,
                    );
                }
            }
            assert_eq!(
                hx.get("pair2_impacts"),
                Some(0.0),
                "the second gap never closes"
            );
            pounded += (hy.get("impacts").unwrap_or(0.0) > 0.0) as usize;
        }
        assert!(pounded > 0, "the test needs pounding in the pair");
        // the design values of pair 1 are the pair suite's, to the last digit
        let d = &r.design.pairs[0];
        assert_eq!(d.levels, p.design.levels);
        assert_eq!(d.governing_level, p.design.governing_level);
        assert_eq!(d.sufficient, p.design.sufficient);
        assert_eq!(r.design.statistic, p.design.statistic);
        // and the statistics of its numbers
        for (name, s) in &p.statistics.0 {
            let row_name = match name.as_str() {
                "peak_force" => "pair1_peak_force",
                "required_separation" => "pair1_sep_time_history",
                "level1_required_separation" => "pair1_level1_required_separation",
                _ => continue,
            };
            let t = r.statistics.0.iter().find(|(k, _)| k == row_name).unwrap();
            assert_eq!(&t.1, s, "{name}");
        }
    }
}

/// A CSV file as (header, rows of cells).
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    // (no field of these tables holds a comma: the files are plain paths)
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (head, rows)
}

fn column(head: &[String], rows: &[Vec<String>], name: &str) -> Vec<f64> {
    let c = head
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {head:?}"));
    rows.iter().map(|r| r[c].parse::<f64>().unwrap()).collect()
}

/// `pounding run` on a row suite in a fresh directory; (the output directory, summary.json,
/// stdout).
fn run_cli(text: &str) -> (tempfile::TempDir, Value, String) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("row-suite.toml");
    // (the bundled records by their absolute paths: the scenario is in the temporary folder)
    let records = format!("{}/records/", examples().display());
    std::fs::write(&file, text.replace("records/", &records)).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pounding"))
        .args([
            "run",
            "row-suite.toml",
            "--out",
            "out",
            "--no-check",
            "--no-plot",
        ])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("out").join("summary.json")).unwrap(),
    )
    .unwrap();
    (dir, summary, stdout)
}

/// A row of three that pounds at both pairs, two levels each.
fn row_text(records: &[&str], scaling: &str, gaps: [f64; 2]) -> String {
    format!(
        "{}{}{}{}{}{}[solver]\nmethod = \"exact-modal\"\nduration = 5.0\n",
        building("B8", 8, 1.2e8),
        building("A4", 4, 3.0e8),
        building("C5", 5, 2.2e8),
        contact("B8", "A4", &[(14.0, gaps[0]), (10.5, gaps[0])]),
        contact("A4", "C5", &[(14.0, gaps[1]), (10.5, gaps[1])]),
        ground(records, scaling)
    )
}

/// The design value at every level of every pair is the code's rule applied here to
/// suite.csv's per-record values (EC8 with 3 records: the largest; ASCE 7 with 11: the
/// mean), the margin gap − design and each pair's verdict follow, and the row's verdict names
/// the pair and level of least margin of all (computed here from those numbers).
#[test]
fn design_values_per_pair_and_the_row_verdict_by_hand() {
    for (records, scaling, gaps, mean) in [
        (&THREE[..], EC8, [0.05, 0.04], false),
        (&ELEVEN[..], ASCE7, [0.05, 0.04], true),
    ] {
        let (dir, summary, stdout) = run_cli(&row_text(records, scaling, gaps));
        let out = dir.path().join("out");
        let (head, rows) = read_csv(&out.join("suite.csv"));
        assert_eq!(rows.len(), records.len());
        assert_eq!(head[..5], ["record", "file", "component", "factor", "pga"]);
        let design = &summary["suite"]["design"];
        assert_eq!(design["statistic"], if mean { "mean" } else { "max" });
        let mut least: Option<(f64, usize, usize)> = None;
        let mut insufficient = Vec::new();
        for p in 1..=2 {
            let dp = &design["pairs"][p - 1];
            assert_eq!(dp["pair"], p);
            let mut pair_least: Option<(f64, usize)> = None;
            for k in 1..=2 {
                let v = column(
                    &head,
                    &rows,
                    &format!("pair{p}_level{k}_required_separation"),
                );
                let by_hand = if mean {
                    v.iter().sum::<f64>() / v.len() as f64
                } else {
                    v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                };
                let dl = &dp["levels"][k - 1];
                let got = dl["required"].as_f64().unwrap();
                // the max is one of the values; summary.json is read by serde_json's default
                // float parser, which may be an ulp off (1e-15 relative); the mean's sum may be
                // taken in another order than here: a few ulps (1e-14 relative)
                let tol = if mean { 1e-14 } else { 1e-15 } * by_hand;
                assert!(
                    (got - by_hand).abs() <= tol,
                    "pair {p} level {k}: {got} vs {by_hand}"
                );
                let gap = gaps[p - 1];
                assert_eq!(dl["gap"].as_f64().unwrap(), gap);
                let margin = gap - by_hand;
                assert!((dl["margin"].as_f64().unwrap() - margin).abs() <= 1e-14);
                assert_eq!(dl["sufficient"], gap >= got);
                if pair_least.is_none_or(|(m, _)| margin < m) {
                    pair_least = Some((margin, k));
                }
                if least.is_none_or(|(m, _, _)| margin < m) {
                    least = Some((margin, p, k));
                }
            }
            let (m, k) = pair_least.unwrap();
            assert_eq!(dp["governing_level"], k, "pair {p}");
            assert_eq!(dp["sufficient"], m >= 0.0, "pair {p}");
            if m < 0.0 {
                insufficient.push(p);
            }
        }
        let (m, p, k) = least.unwrap();
        assert_eq!(design["governing_pair"], p);
        assert_eq!(design["governing_level"], k);
        assert_eq!(design["sufficient"], m >= 0.0);
        assert_eq!(
            design["insufficient_pairs"],
            serde_json::json!(insufficient)
        );
        assert!(
            stdout.contains(&format!("governing pair {p} (")),
            "the report names the governing pair: {stdout}"
        );
        assert!(stdout.contains("pair 1 of 2") && stdout.contains("pair 2 of 2"));
        // the representative record: the largest required separation there, its run the top
        // level, every record's run in its folder as a row's run writes it
        let s = &summary["suite"];
        let rep = s["representative"].as_u64().unwrap() as usize - 1;
        let v = column(
            &head,
            &rows,
            &format!("pair{p}_level{k}_required_separation"),
        );
        let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(v[rep], max);
        let dirs = s["record_dirs"].as_array().unwrap();
        assert_eq!(dirs.len(), records.len());
        let mut top = summary.clone();
        top.as_object_mut().unwrap().remove("suite");
        let own: Value = serde_json::from_str(
            &std::fs::read_to_string(out.join(dirs[rep].as_str().unwrap()).join("summary.json"))
                .unwrap(),
        )
        .unwrap();
        assert_eq!(top, own, "the top level is the representative record's run");
        for d in dirs {
            for f in ["history.csv", "impacts.csv", "floors.csv", "summary.json"] {
                assert!(out.join(d.as_str().unwrap()).join(f).is_file(), "{d} {f}");
            }
        }
        assert_eq!(
            std::fs::read_to_string(out.join("history.csv")).unwrap(),
            std::fs::read_to_string(out.join(dirs[rep].as_str().unwrap()).join("history.csv"))
                .unwrap()
        );
    }
}

/// The period range of a row's suite is from every building's first-mode period: a range that
/// covers the first two buildings' but not the third's is refused (naming the key and the
/// code's range), and one that covers all three is taken.
#[test]
fn a_rows_period_range_covers_every_building() {
    let text = |range: &str| {
        format!(
            "{}{}{}{}{}{}",
            building("A", 4, 3.0e8),
            building("B", 5, 1.6e8),
            building("C", 12, 1.0e8),
            contact("A", "B", &[(14.0, 0.01)]),
            contact("B", "C", &[(17.5, 0.01)]),
            ground(
                &THREE,
                &format!(
                    "{{ rule = \"ec8\", target = {{ spectrum = \"ec8\", ag = 2.0, ground_type = \
                     \"C\", type = 1 }}, range = {range} }}"
                )
            )
        )
    };
    let row = parse(&text("[0.05, 3.0]"));
    let t1: Vec<f64> = row
        .structures
        .iter()
        .map(|s| s.modal().periods()[0])
        .collect();
    // (the test's premise: C's first period is the longest, and 2 T_C is beyond 3 s)
    assert!(t1[2] > t1[0].max(t1[1]) && 2.0 * t1[2] > 3.0 && 2.0 * t1[1] < 3.0);
    match suite::row::run_row(&row, false) {
        Err(SuiteError::Scaling(e)) => {
            let e = format!("{}", SuiteError::Scaling(e));
            assert!(e.contains("ground_motion.scaling"), "{e}");
            assert!(
                e.contains(&format!("{}", 2.0 * t1[2])),
                "the code's range: {e}"
            );
        }
        other => panic!("must be refused: {:?}", other.map(|r| r.records.len())),
    }
    // the pair of the first two is content with it
    assert!(suite::members(&row.pair(0)).is_ok());
    let wide = parse(&text(&format!("[0.05, {}]", 2.0 * t1[2] + 0.1)));
    let m = suite::members(&wide).expect("covers every building");
    let s = m.scaling.expect("ec8 scales");
    assert_eq!(s.first_mode_periods, t1);
    assert_eq!(s.code_range.hi, 2.0 * t1[2]);
    assert_eq!(s.code_range.lo, 0.2 * t1[0].min(t1[1]));
}

/// Bad inputs are refused with the key named: a record's factor with a code's rule, a row
/// missing a pair's contact (as any row), a pair's suite driver given a row (a sweep over a
/// row suite: tests/suite_row_sweep.rs).
#[test]
fn bad_row_suites_are_refused_naming_the_key() {
    let (a, b, c) = (
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        building("C", 4, 3.0e8),
    );
    let ab = contact("A", "B", &[(14.0, 0.01)]);
    let bc = contact("B", "C", &[(14.0, 0.01)]);
    let e = refused(&format!(
        "{a}{b}{c}{ab}{bc}{}",
        ground(
            &["{ file = \"records/RSN753_LOMAP_CLS000.AT2\", factor = 2.0 }"; 3],
            EC8
        )
    ));
    assert!(e.contains("ground_motion.records[1].factor"), "{e}");
    let e = refused(&format!("{a}{b}{c}{ab}{}", ground(&THREE, EC8)));
    assert!(
        e.contains("B") && e.contains("C") && e.contains("contact"),
        "{e}"
    );
    let e = refused(&format!(
        "{a}{b}{c}{ab}{bc}{}",
        ground(&["{ file = \"records/nope.AT2\" }"], EC8)
    ));
    assert!(e.contains("ground_motion.records[1].file"), "{e}");
    // EC8 needs three records, on a row as on a pair
    let row = parse(&format!("{a}{b}{c}{ab}{bc}{}", ground(&THREE[..2], EC8)));
    let e = suite::row::run_row(&row, false)
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("ground_motion.scaling"), "{e}");
    // the pair's driver does not take a row
    let row = parse(&format!("{a}{b}{c}{ab}{bc}{}", ground(&THREE, EC8)));
    let e = suite::run_headline(&row, false).map(|_| ()).unwrap_err();
    assert!(matches!(e, SuiteError::Row(3)), "{e}");
}

/// A pair's suite keeps its contract (README "Record suites"; byte-identical outputs of
/// examples/suite-asce7.toml and suite-ec8.toml were compared before and after the row suite):
/// summary.json's `suite` has exactly the pair suite's keys (no `record_dirs`), its `design`
/// per level (no `pairs`), no top-level `pairs`, suite.csv the pair's columns, no `records/`.
#[test]
fn a_pair_suites_contract_is_unchanged() {
    let text = format!(
        "{}{}[contact]\nlaw = \"jankowski\"\nstiffness = 2.75e9\nrestitution = 0.65\n\
         level = [{{ height = 14.0, gap = 0.05 }}, {{ height = 10.5, gap = 0.05 }}]\n{}\
         [solver]\nmethod = \"exact-modal\"\nduration = 5.0\n",
        building("B8", 8, 1.2e8),
        building("A4", 4, 3.0e8),
        ground(&THREE, EC8)
    );
    let (dir, summary, _) = run_cli(&text);
    let out = dir.path().join("out");
    let keys = |v: &Value| -> Vec<String> { v.as_object().unwrap().keys().cloned().collect() };
    let mut want = vec![
        "design",
        "records",
        "representative",
        "representative_file",
        "scaling",
        "statistics",
    ];
    want.sort();
    assert_eq!(keys(&summary["suite"]), want);
    let mut want = vec![
        "basis",
        "governing_level",
        "insufficient_levels",
        "levels",
        "records",
        "statistic",
        "sufficient",
    ];
    want.sort();
    assert_eq!(keys(&summary["suite"]["design"]), want);
    assert!(summary.get("pairs").is_none());
    let (head, _) = read_csv(&out.join("suite.csv"));
    let mut cols = vec![
        "record",
        "file",
        "component",
        "factor",
        "pga",
        "peak_displacement_1",
        "peak_displacement_2",
        "peak_displacement_no_contact_1",
        "peak_displacement_no_contact_2",
        "peak_force",
        "impacts",
        "contact_time",
        "max_penetration",
        "required_separation",
    ];
    for k in 1..=2 {
        cols.extend(
            [
                format!("level{k}_required_separation"),
                format!("level{k}_peak_force"),
                format!("level{k}_impacts"),
            ]
            .map(|s| &*s.leak()),
        );
    }
    cols.extend(["check_max_change", "converged"]);
    assert_eq!(head, cols);
    assert!(!out.join("records").exists());
}
