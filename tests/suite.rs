//! Issue 27, part 3: suites of records (`[ground_motion] kind = "suite"`). The statistics
//! against hand computation, the design value's rule by the number of records, the per-level
//! verdict where a lower level governs, a suite of one record against the single-record run
//! (bit for bit), a factor against a record file scaled by hand, the files written, and bad
//! inputs. Records are synthetic (written here), the structures small shear buildings, so
//! that every run takes milliseconds.

use std::path::Path;

use pounding::analysis::simulate::simulate_checked;
use pounding::input::scenario::Scenario;
use pounding::input::scenario::suite::SuiteRule;
use pounding::study::suite::{self, DesignStatistic, Statistics};

/// A record in g, one value a line (`dt` given in the scenario): a sine of period `t` (s)
/// and amplitude `a` (g) under a half-sine envelope over `n` samples of 0.01 s, plus a second
/// harmonic so that spectra have no zero.
fn record_text(a: f64, t: f64, n: usize, scale: f64) -> String {
    let dt = 0.01;
    let mut out = String::new();
    for k in 0..n {
        let x = k as f64 * dt;
        let env = (std::f64::consts::PI * k as f64 / (n - 1) as f64).sin();
        let v = a
            * env
            * ((2.0 * std::f64::consts::PI * x / t).sin()
                + 0.3 * (2.0 * std::f64::consts::PI * x * 2.7 / t).sin());
        // (`{}` writes the shortest text that reads back to the same f64)
        out.push_str(&format!("{}\n", v * scale));
    }
    out
}

/// Writes records r1 … r7 (different periods and amplitudes) into `dir`.
fn write_records(dir: &Path) {
    for (i, (a, t)) in [
        (0.30, 0.50),
        (0.25, 0.80),
        (0.35, 0.35),
        (0.20, 1.10),
        (0.28, 0.65),
        (0.32, 0.45),
        (0.22, 0.95),
    ]
    .iter()
    .enumerate()
    {
        std::fs::write(
            dir.join(format!("r{}.txt", i + 1)),
            record_text(*a, *t, 600, 1.0),
        )
        .unwrap();
    }
}

/// Two 2-storey shear buildings, contact at both floors: level 1 at 6 m with `gap_top`, level
/// 2 at 3 m with `gap_low`; `ground` is the `[ground_motion]` table.
fn scenario_text(gap_top: f64, gap_low: f64, ground: &str) -> String {
    format!(
        r#"title = "suite test"

[[structure]]
name = "A"
kind = "shear-building"
floor_heights = [3.0, 6.0]
floor_masses = [2.0e5, 2.0e5]
storey_stiffnesses = [3.0e8, 3.0e8]
damping_ratio = 0.05

[[structure]]
name = "B"
kind = "shear-building"
floor_heights = [3.0, 6.0]
floor_masses = [2.0e5, 2.0e5]
storey_stiffnesses = [1.0e8, 1.0e8]
damping_ratio = 0.05

[contact]
law = "linear"
stiffness = 1.0e9

[[contact.level]]
height = 6.0
gap = {gap_top}

[[contact.level]]
height = 3.0
gap = {gap_low}

{ground}
"#
    )
}

fn suite_table(files: &[&str], scaling: &str, extra: &str) -> String {
    let recs: Vec<String> = files
        .iter()
        .map(|f| format!("  {{ file = \"{f}\", units = \"g\", dt = 0.01{extra} }},"))
        .collect();
    format!(
        "[ground_motion]\nkind = \"suite\"\nrecords = [\n{}\n]\nscaling = {scaling}\n",
        recs.join("\n")
    )
}

const EC8: &str =
    r#"{ rule = "ec8", target = { spectrum = "ec8", ag = 2.5, ground_type = "C", type = 1 } }"#;
const ASCE7: &str =
    r#"{ rule = "asce7", target = { spectrum = "asce7", sds = 0.6, sd1 = 0.35, tl = 8.0 } }"#;

fn parse(text: &str, dir: &Path) -> Scenario {
    Scenario::from_toml(text, "s.toml", dir).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn error(text: &str, dir: &Path) -> String {
    match Scenario::from_toml(text, "s.toml", dir) {
        Ok(_) => panic!("must be refused:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Hand computation: 3, 1, 4, 1, 5 → mean 14/5 = 2.8; sorted 1, 1, 3, 4, 5; the median
/// (h = 4·0.5 = 2) is x₍₃₎ = 3; the 84th percentile (h = 4·0.84 = 3.36) is
/// x₍₄₎ + 0.36 (x₍₅₎ − x₍₄₎) = 4.36; max 5; and for an even count 1, 2, 3, 4 the median is 2.5.
#[test]
fn statistics_by_hand() {
    let s = Statistics::of(&[3.0, 1.0, 4.0, 1.0, 5.0], DesignStatistic::Mean);
    assert_eq!(s.mean, 2.8);
    assert_eq!(s.median, 3.0);
    // (0.36 is not exact in binary: a few ulps)
    assert!((s.p84 - 4.36).abs() < 1e-14, "{}", s.p84);
    assert_eq!((s.min, s.max, s.design), (1.0, 5.0, 2.8));
    let s = Statistics::of(&[4.0, 2.0, 1.0, 3.0], DesignStatistic::Max);
    assert_eq!((s.median, s.design), (2.5, 4.0));
    // h = 3·0.84 = 2.52: 3 + 0.52·(4 − 3)
    assert!((s.p84 - 3.52).abs() < 1e-14);
}

/// ASCE 7-16: the mean (≥ 11 records); EN 1998-1 §4.3.3.4.3: the mean from 7 records, the
/// most unfavourable below; no rule: the most unfavourable.
#[test]
fn design_statistic_by_rule_and_count() {
    use DesignStatistic::{Max, Mean};
    assert_eq!(DesignStatistic::for_rule(SuiteRule::Asce7, 11).0, Mean);
    assert_eq!(DesignStatistic::for_rule(SuiteRule::Ec8, 7).0, Mean);
    assert_eq!(DesignStatistic::for_rule(SuiteRule::Ec8, 6).0, Max);
    assert_eq!(DesignStatistic::for_rule(SuiteRule::Ec8, 3).0, Max);
    assert_eq!(DesignStatistic::for_rule(SuiteRule::None, 20).0, Max);
}

/// EC8 suites of 3 and of 7 records: each level's design value is the largest of the
/// records' required separations (3) or their mean (7), computed here from the records' own
/// runs; the scaling meets the rule (mean ≥ 0.9 × target over the range, mean PGA ≥ a_g·S).
#[test]
fn ec8_design_value_is_max_below_seven_records_and_mean_from_seven() {
    let dir = tempfile::tempdir().unwrap();
    write_records(dir.path());
    for n in [3usize, 7] {
        let files: Vec<String> = (1..=n).map(|i| format!("r{i}.txt")).collect();
        let names: Vec<&str> = files.iter().map(String::as_str).collect();
        let text = scenario_text(0.5, 0.5, &suite_table(&names, EC8, ""));
        let sc = parse(&text, dir.path());
        let run = suite::run(&sc, false).unwrap();
        let s = run.scaling.as_ref().unwrap();
        assert!(s.min_ratio >= 0.9 * (1.0 - 1e-12), "{}", s.min_ratio);
        let p = s.pga_check.unwrap();
        assert!(p.mean_pga >= p.required * (1.0 - 1e-12));
        for (k, l) in run.design.levels.iter().enumerate() {
            let v: Vec<f64> = run
                .records
                .iter()
                .map(|r| r.report.levels[k].required_gap)
                .collect();
            let expected = if n >= 7 {
                v.iter().sum::<f64>() / n as f64
            } else {
                v.iter().copied().fold(0.0, f64::max)
            };
            assert_eq!(l.required, expected, "n = {n}, level {}", k + 1);
            assert_eq!(l.margin, l.gap - expected);
        }
        // every record ran at its factor: its PGA is the factor × the PGA read
        for (r, m) in run.records.iter().zip(&sc.suite.as_ref().unwrap().records) {
            let pga = r.headline.get("pga").unwrap();
            assert!((pga - r.factor * m.record.pga()).abs() <= 1e-12 * pga);
        }
    }
}

/// Gaps of 0.5 m at the top (6 m) and 1 mm at the lower floor (3 m): the lower level is too
/// narrow, the top suffices, and the verdict names level 2 (the lower one) as governing.
#[test]
fn a_lower_level_governs() {
    let dir = tempfile::tempdir().unwrap();
    write_records(dir.path());
    let text = scenario_text(
        0.5,
        0.001,
        &suite_table(&["r1.txt", "r2.txt"], "{ rule = \"none\" }", ""),
    );
    let run = suite::run(&parse(&text, dir.path()), false).unwrap();
    let d = &run.design;
    assert_eq!(d.statistic, DesignStatistic::Max);
    let req = |k: usize| {
        run.records
            .iter()
            .map(|r| r.report.levels[k].required_gap)
            .fold(0.0, f64::max)
    };
    assert!(req(1) > 0.001 && req(0) < 0.5, "{} {}", req(0), req(1));
    assert!(d.levels[0].sufficient && !d.levels[1].sufficient);
    assert_eq!(d.governing_level, 2);
    assert!(!d.sufficient);
    assert_eq!(d.insufficient_levels, 1);
    assert_eq!(d.levels[1].required, req(1));
}

/// A suite of one record at factor 1 is that record's run: the same numbers bit for bit.
#[test]
fn one_record_suite_equals_the_single_record_run() {
    let dir = tempfile::tempdir().unwrap();
    write_records(dir.path());
    let single = scenario_text(
        0.02,
        0.02,
        "[ground_motion]\nkind = \"record\"\nfile = \"r3.txt\"\nunits = \"g\"\ndt = 0.01\n",
    );
    let mut a = simulate_checked(&parse(&single, dir.path()), true).unwrap();
    let text = scenario_text(
        0.02,
        0.02,
        &suite_table(&["r3.txt"], "{ rule = \"none\" }", ""),
    );
    let run = suite::run(&parse(&text, dir.path()), true).unwrap();
    let mut b = run.records[0].report.clone();
    assert!(a.contact.impacts > 0, "the case must pound");
    a.warnings.sort();
    b.warnings.sort();
    assert!(a == b, "the suite's run differs from the single record's");
    // its statistics are its own numbers
    assert_eq!(run.design.levels[0].required, a.levels[0].required_gap);
    assert_eq!(
        run.design.levels[0].statistics.p84,
        a.levels[0].required_gap
    );
}

/// `factor = 2` on a record gives exactly the run of a file holding the record's values × 2
/// (× 2 is exact in binary, so the two inputs are the same numbers); `factor = 1.3` the run of
/// a file × 1.3 to within the rounding of the product (relative 1e-9 on every headline
/// number, far above the 1e-16 of one rounding and far below any physical effect).
#[test]
fn a_factor_is_the_record_scaled() {
    let dir = tempfile::tempdir().unwrap();
    for (f, exact) in [(2.0, true), (1.3, false)] {
        std::fs::write(dir.path().join("base.txt"), record_text(0.3, 0.5, 600, 1.0)).unwrap();
        std::fs::write(dir.path().join("scaled.txt"), record_text(0.3, 0.5, 600, f)).unwrap();
        let single = scenario_text(
            0.02,
            0.02,
            "[ground_motion]\nkind = \"record\"\nfile = \"scaled.txt\"\nunits = \"g\"\ndt = 0.01\n",
        );
        let one = parse(&single, dir.path());
        let a = simulate_checked(&one, false).unwrap();
        let text = scenario_text(
            0.02,
            0.02,
            &suite_table(
                &["base.txt"],
                "{ rule = \"none\" }",
                &format!(", factor = {f}"),
            ),
        );
        let run = suite::run(&parse(&text, dir.path()), false).unwrap();
        assert_eq!(run.records[0].factor, f);
        let ha = suite::Headline::of(&a, one.ground_motion.pga());
        let hb = &run.records[0].headline;
        assert!(a.contact.impacts > 0);
        for ((name, x), (_, y)) in ha.values.iter().zip(&hb.values) {
            if name == "check_max_change" {
                continue;
            }
            if exact {
                assert_eq!(x, y, "{name}");
            } else {
                assert!(
                    (x - y).abs() <= 1e-9 * x.abs().max(1e-12),
                    "{name}: {x} vs {y}"
                );
            }
        }
    }
}

/// What `pounding run` writes for a suite: suite.csv (a row per record, its numbers those of
/// summary.json's `suite.records`), summary.json last with the single-record top-level keys
/// and the `suite` section, every file with the same permissions.
#[test]
fn the_files_of_a_suite_run() {
    let dir = tempfile::tempdir().unwrap();
    write_records(dir.path());
    let text = scenario_text(
        0.02,
        0.02,
        &suite_table(&["r1.txt", "r2.txt", "r3.txt"], EC8, ""),
    );
    std::fs::write(dir.path().join("s.toml"), &text).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pounding"))
        .args(["run", "s.toml", "--out", "res", "--no-check"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("verdict: the gap"), "{stdout}");
    let res = dir.path().join("res");
    let csv = std::fs::read_to_string(res.join("suite.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 4);
    assert!(rows[0].starts_with("record,file,component,factor,pga,"));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(res.join("summary.json")).unwrap()).unwrap();
    for key in [
        "structures",
        "contact",
        "levels",
        "separation",
        "accuracy",
        "solver",
    ] {
        assert!(summary.get(key).is_some(), "top-level `{key}`");
    }
    let s = &summary["suite"];
    assert_eq!(s["records"].as_array().unwrap().len(), 3);
    assert_eq!(s["scaling"]["rule"], "ec8");
    assert!(s["scaling"]["min_mean_to_target_ratio"].as_f64().unwrap() >= 0.9 - 1e-12);
    assert_eq!(s["design"]["statistic"], "max");
    // suite.csv's numbers are summary.json's
    let header: Vec<&str> = rows[0].split(',').collect();
    for (i, row) in rows[1..].iter().enumerate() {
        let cells: Vec<&str> = row.split(',').collect();
        let rec = &s["records"][i];
        for (h, c) in header.iter().zip(&cells).skip(4) {
            // (serde_json's default float parsing may be an ulp off: 1e-15 relative)
            if let Some(x) = rec[*h].as_f64() {
                let y = c.parse::<f64>().unwrap();
                assert!((y - x).abs() <= 1e-15 * x.abs(), "{h}: {y} vs {x}");
            }
        }
    }
    // the representative record is the one of largest required separation at the governing
    // level, and the top-level keys are its run
    let k = s["design"]["governing_level"].as_u64().unwrap() as usize;
    let rep = s["representative"].as_u64().unwrap() as usize - 1;
    let key = format!("level{k}_required_separation");
    let max = (0..3)
        .map(|i| s["records"][i][&key].as_f64().unwrap())
        .fold(0.0, f64::max);
    assert_eq!(s["records"][rep][&key].as_f64().unwrap(), max);
    let top = summary["levels"][k - 1]["required_gap"].as_f64().unwrap();
    assert!((top - max).abs() <= 1e-15 * max, "{top} vs {max}");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = |f: &str| std::fs::metadata(res.join(f)).unwrap().permissions().mode();
        for f in [
            "suite.csv",
            "history.csv",
            "suite-records.png",
            "suite-spectra.png",
        ] {
            assert_eq!(mode(f), mode("summary.json"), "{f}");
        }
    }
}

/// Bad inputs: each refused with the key (and the file) named.
#[test]
fn bad_suites_are_refused_with_the_key() {
    let dir = tempfile::tempdir().unwrap();
    write_records(dir.path());
    let s = |ground: &str| scenario_text(0.02, 0.02, ground);
    // a missing file: the key records[2].file and the file's name
    let e = error(
        &s(&suite_table(&["r1.txt", "nope.txt"], EC8, "")),
        dir.path(),
    );
    assert!(
        e.contains("ground_motion.records[2].file") && e.contains("nope.txt"),
        "{e}"
    );
    // a component the file does not have (a one-column file has one)
    let e = error(
        &s(&suite_table(
            &["r1.txt"],
            "{ rule = \"none\" }",
            ", component = \"EW\"",
        )),
        dir.path(),
    );
    assert!(e.contains("records[1]") && e.contains("r1.txt"), "{e}");
    // a factor with a code's rule
    let e = error(
        &s(&suite_table(&["r1.txt"; 3], EC8, ", factor = 2.0")),
        dir.path(),
    );
    assert!(
        e.contains("records[1].factor") && e.contains("rule = \"none\""),
        "{e}"
    );
    // an unknown key in a record, with the valid ones
    let e = error(
        &s(&suite_table(&["r1.txt"], EC8, ", scale = 2.0")),
        dir.path(),
    );
    assert!(
        e.contains("unknown key `scale`") && e.contains("factor"),
        "{e}"
    );
    // unknown keys in the scaling and its target name their table and its keys
    let e = error(
        &s(&suite_table(
            &["r1.txt"],
            &EC8.replace("rule =", "rul = 1, rule ="),
            "",
        )),
        dir.path(),
    );
    assert!(
        e.contains("unknown key `rul` in ground_motion.scaling") && e.contains("factor_limits"),
        "{e}"
    );
    let e = error(
        &s(&suite_table(
            &["r1.txt"],
            &EC8.replace("ag = 2.5", "ag = 2.5, a_g = 2.5"),
            "",
        )),
        dir.path(),
    );
    assert!(
        e.contains("unknown key `a_g` in ground_motion.scaling.target")
            && e.contains("ground_type"),
        "{e}"
    );
    // no scaling table; no target with a rule; a single-record key at the top
    let e = error(
        &s(
            "[ground_motion]\nkind = \"suite\"\nrecords = [{ file = \"r1.txt\", units = \"g\", dt = 0.01 }]\n",
        ),
        dir.path(),
    );
    assert!(e.contains("ground_motion.scaling"), "{e}");
    let e = error(
        &s(&suite_table(&["r1.txt"], "{ rule = \"ec8\" }", "")),
        dir.path(),
    );
    assert!(e.contains("ground_motion.scaling.target"), "{e}");
    let e = error(
        &s(&format!(
            "{}file = \"r1.txt\"\n",
            suite_table(&["r1.txt"], EC8, "")
        )),
        dir.path(),
    );
    assert!(
        e.contains("ground_motion.file") && e.contains("per record"),
        "{e}"
    );
    // a target key out of range names its full key
    let bad = EC8.replace("ag = 2.5", "ag = 50.0");
    let e = error(&s(&suite_table(&["r1.txt"], &bad, "")), dir.path());
    assert!(e.contains("ground_motion.scaling.target.ag"), "{e}");
    // `records` with another kind
    let e = error(
        &s("[ground_motion]\nkind = \"harmonic\"\npga = 0.3\nperiod = 0.5\nrecords = []\n"),
        dir.path(),
    );
    assert!(e.contains("ground_motion.records"), "{e}");
}

/// A suite that cannot meet its rule is refused before any run, naming the rule and the
/// shortfall: too few records for ASCE 7 (11), and an EC8 suite held at factor 1.
#[test]
fn suites_that_cannot_meet_the_rule() {
    let dir = tempfile::tempdir().unwrap();
    write_records(dir.path());
    let text = scenario_text(
        0.02,
        0.02,
        &suite_table(&["r1.txt", "r2.txt", "r3.txt"], ASCE7, ""),
    );
    let e = suite::run(&parse(&text, dir.path()), false)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("ASCE 7-16 §16.2.2 requires at least 11 records; 3 given"),
        "{e}"
    );
    let held = format!("{}, factor_limits = [1.0, 1.0] }}", &EC8[..EC8.len() - 2]);
    let text = scenario_text(
        0.02,
        0.02,
        &suite_table(&["r1.txt", "r2.txt", "r3.txt"], &held, ""),
    );
    let e = suite::run(&parse(&text, dir.path()), false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("EN 1998-1") && e.contains("reaches only"), "{e}");
    // and `simulate` refuses a suite rather than running it without ground motion
    let e = simulate_checked(&parse(&text, dir.path()), false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("suite of 3 records"), "{e}");
}
