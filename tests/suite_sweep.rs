//! Sweeps over suite scenarios (issue 27: "sweeps may vary suite scenarios like any other"):
//! a case is a whole suite and its row the suite's answer. Checked by invariances and against
//! other code paths, not against numbers the program printed before:
//!
//! - a one-case sweep over a suite gives the design values, verdict, governing level, ratio
//!   and self-check of `pounding run` on that suite scenario (the suite driver and its
//!   summary.json against the sweep's row: two paths over one engine), bit for bit;
//! - a suite of one record with rule "none" gives, case by case, the numbers of the
//!   single-record sweep over the same axis (its `sep_time_history`, `peak_force`, self-check);
//! - over a gap axis the design value does not move (the runs without contact give it) and the
//!   verdict flips exactly where the gap crosses it;
//! - a sweep killed mid-way resumes to the uninterrupted table; shards merge into it; the
//!   journal of one row kind is never resumed as the other; single-record keys are refused
//!   naming the axis; the pictures are drawn.
//!
//! Records are synthetic (written here), the structures small shear buildings, so that a case
//! takes milliseconds.

mod common;

use std::path::{Path, PathBuf};

use common::pounding_here as pounding;
use common::{ok, s};

use pounding::study::sweep::Sweep;
use pounding::study::sweep::results::parse_csv_line;
use pounding::study::sweep::run::compute_case;

const BIN: &str = env!("CARGO_BIN_EXE_pounding");

/// A record in g, one value a line (dt = 0.01 s given per record): a sine of period `t` (s)
/// and amplitude `a` (g) under a half-sine envelope over `n` samples, plus a second harmonic
/// so that its spectrum has no zero.
fn record_text(a: f64, t: f64, n: usize) -> String {
    let mut out = String::new();
    for k in 0..n {
        let x = k as f64 * 0.01;
        let env = (std::f64::consts::PI * k as f64 / (n - 1) as f64).sin();
        let w = 2.0 * std::f64::consts::PI / t;
        let v = a * env * ((w * x).sin() + 0.3 * (2.7 * w * x).sin());
        out.push_str(&format!("{v}\n"));
    }
    out
}

fn write(path: &Path, text: &str) -> PathBuf {
    std::fs::write(path, text).unwrap();
    path.to_path_buf()
}

/// Records r1 … r4 in `dir`.
fn write_records(dir: &Path) {
    for (i, (a, t)) in [(0.30, 0.50), (0.25, 0.80), (0.35, 0.35), (0.20, 1.10)]
        .iter()
        .enumerate()
    {
        write(
            &dir.join(format!("r{}.txt", i + 1)),
            &record_text(*a, *t, 600),
        );
    }
}

/// Two 2-storey shear buildings; `levels` = [(height, gap)] contact levels; `ground` the
/// `[ground_motion]` table.
fn scenario(levels: &[(f64, f64)], ground: &str) -> String {
    let mut s = String::from(
        r#"title = "suite sweep test"

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
"#,
    );
    for (h, g) in levels {
        s.push_str(&format!(
            "\n[[contact.level]]\nheight = {h:?}\ngap = {g:?}\n"
        ));
    }
    s.push('\n');
    s.push_str(ground);
    s
}

fn suite(files: &[&str], scaling: &str) -> String {
    let recs: Vec<String> = files
        .iter()
        .map(|f| format!("  {{ file = \"{f}\", units = \"g\", dt = 0.01 }},"))
        .collect();
    format!(
        "[ground_motion]\nkind = \"suite\"\nrecords = [\n{}\n]\nscaling = {scaling}\n",
        recs.join("\n")
    )
}

const EC8: &str =
    r#"{ rule = "ec8", target = { spectrum = "ec8", ag = 2.5, ground_type = "C", type = 1 } }"#;
const NONE: &str = r#"{ rule = "none" }"#;

/// The rows of a results table as maps column → field.
fn table(csv: &str) -> Vec<std::collections::BTreeMap<String, String>> {
    let mut lines = csv.lines();
    let head = parse_csv_line(lines.next().unwrap()).unwrap();
    lines
        .map(|l| {
            let f = parse_csv_line(l).unwrap();
            assert_eq!(f.len(), head.len(), "{l}");
            head.iter().cloned().zip(f).collect()
        })
        .collect()
}

fn num(row: &std::collections::BTreeMap<String, String>, k: &str) -> f64 {
    row.get(k)
        .unwrap_or_else(|| panic!("no column {k}"))
        .parse()
        .unwrap_or_else(|_| panic!("{k} = {:?}", row[k]))
}

fn sweep_file(dir: &Path, name: &str, base: &str, axes: &str) -> PathBuf {
    write(&dir.join(name), &format!("scenario = \"{base}\"\n{axes}"))
}

/// A one-case sweep over an EC8 suite of 3 records on two contact levels gives, bit for bit,
/// what `pounding run` computes for the same scenario (`study::suite::run`, the driver the
/// command calls, which keeps every record's history; the sweep's row goes through the
/// binary, results.csv and `run_headline`): every level's gap, design value of the required
/// separation and of the peak force and verdict, the statistic, the verdict, the governing
/// level and its margin, the number of records, the lowest mean-to-target ratio, and the
/// worst self-check over the records. (summary.json is not read back here: serde_json's
/// default parser may round the last bit of a number.)
#[test]
fn one_case_sweep_equals_pounding_run_on_the_suite() {
    let d = tempfile::tempdir().unwrap();
    write_records(d.path());
    let base = write(
        &d.path().join("suite.toml"),
        &scenario(
            &[(6.0, 0.05), (3.0, 0.02)],
            &suite(&["r1.txt", "r2.txt", "r3.txt"], EC8),
        ),
    );
    // the axis sets the base's own value: the case is the base scenario
    let sw = sweep_file(
        d.path(),
        "s.toml",
        "suite.toml",
        "[[axis]]\nkey = \"contact.level.2.gap\"\nvalues = [0.02]\n",
    );
    let sc = pounding::input::scenario::Scenario::from_file(&base).unwrap();
    let run = pounding::study::suite::run(&sc, true).unwrap();
    ok(&pounding(&[
        "sweep",
        s(&sw),
        "--out",
        s(&d.path().join("sw")),
        "-q",
        "--no-plot",
    ]));
    let rows = table(&std::fs::read_to_string(d.path().join("sw/results.csv")).unwrap());
    assert_eq!(rows.len(), 1);
    let r = &rows[0];
    assert_eq!(r["status"], "ok");
    let design = &run.design;
    assert_eq!(num(r, "records"), 3.0);
    assert_eq!(design.records, 3);
    // EC8 with fewer than 7 records: the most unfavourable (EN 1998-1 §4.3.3.4.3)
    assert_eq!(r["statistic"], "max");
    assert_eq!(design.statistic.key(), "max");
    assert_eq!(r["sufficient"], design.sufficient.to_string());
    assert_eq!(num(r, "governing_level"), design.governing_level as f64);
    assert_eq!(design.levels.len(), 2);
    for l in &design.levels {
        let k = l.level;
        let col = |c: &str| format!("level{k}_{c}");
        assert_eq!(num(r, &col("gap")), l.gap);
        assert_eq!(num(r, &col("required_separation")), l.required, "level {k}");
        assert_eq!(r[&col("sufficient")], l.sufficient.to_string());
        // the design value of the level's peak force: the largest over the records here
        let force = run
            .records
            .iter()
            .map(|x| x.report.levels[k - 1].peak_force)
            .fold(0.0, f64::max);
        assert_eq!(num(r, &col("peak_force")), force, "level {k} peak force");
        if k == design.governing_level {
            assert_eq!(num(r, "governing_margin"), l.margin);
        }
    }
    assert_eq!(
        num(r, "min_mean_to_target_ratio"),
        run.scaling.as_ref().unwrap().min_ratio
    );
    // the worst self-check: the largest change over the records, converged only if all are
    // (of the headline numbers: the suite's runs also compare their floors, a sweep row has none)
    let worst = run
        .records
        .iter()
        .flat_map(|x| x.report.accuracy.quantities.iter())
        .filter(|q| !q.name.starts_with("floor_"))
        .map(|q| q.change)
        .fold(0.0, f64::max);
    assert_eq!(num(r, "check_max_change"), worst);
    let all = run
        .records
        .iter()
        .all(|x| x.headline.converged == Some(true));
    assert_eq!(r["converged"], all.to_string());
    // the case pounds somewhere: a test of the design force, not of zeros
    assert!(num(r, "level1_peak_force") > 0.0 || num(r, "level2_peak_force") > 0.0);
}

/// A suite of one record with rule "none" (factor 1; the design value is that record's) swept
/// over the gap gives, case by case, the single-record sweep's numbers over the same axis:
/// one contact level, so `level1_required_separation` is `sep_time_history`, and
/// `level1_peak_force` the `peak_force`; the self-check too (both rows checked).
#[test]
fn one_record_suite_rows_equal_the_single_record_rows() {
    let d = tempfile::tempdir().unwrap();
    write_records(d.path());
    let lv = [(6.0, 0.01)];
    write(
        &d.path().join("suite.toml"),
        &scenario(&lv, &suite(&["r3.txt"], NONE)),
    );
    write(
        &d.path().join("single.toml"),
        &scenario(
            &lv,
            "[ground_motion]\nkind = \"record\"\nfile = \"r3.txt\"\nunits = \"g\"\ndt = 0.01\n",
        ),
    );
    let axes = "[[axis]]\nkey = \"contact.level.1.gap\"\nvalues = [0.001, 0.01, 0.03]\n\
                [[axis]]\nkey = \"structure.2.stiffness_scale\"\nvalues = [0.7, 1.0]\n";
    let a = Sweep::from_file(&sweep_file(d.path(), "a.toml", "suite.toml", axes)).unwrap();
    let b = Sweep::from_file(&sweep_file(d.path(), "b.toml", "single.toml", axes)).unwrap();
    assert_eq!(a.len(), 6);
    let mut pounded = 0;
    for case in 0..a.len() {
        let ra = table(&format!(
            "{}\n{}",
            pounding::study::sweep::results::header(&a),
            compute_case(&a, case, true).line
        ))
        .remove(0);
        let rb = table(&format!(
            "{}\n{}",
            pounding::study::sweep::results::header(&b),
            compute_case(&b, case, true).line
        ))
        .remove(0);
        assert_eq!((ra["status"].as_str(), rb["status"].as_str()), ("ok", "ok"));
        assert_eq!(
            num(&ra, "level1_required_separation"),
            num(&rb, "sep_time_history"),
            "case {case}"
        );
        assert_eq!(
            num(&ra, "level1_peak_force"),
            num(&rb, "peak_force"),
            "case {case}"
        );
        // the single-record row records the floors (its floor columns) and its check compares
        // them too; the suite's row compares the same runs' headline numbers: a subset of the
        // same changes, so never larger
        assert!(
            num(&ra, "check_max_change") <= num(&rb, "check_max_change"),
            "case {case}"
        );
        if rb["converged"] == "true" {
            assert_eq!(ra["converged"], "true", "case {case}");
        }
        // the verdict is gap ≥ the record's time-history separation
        let gap = num(&ra, "contact.level.1.gap");
        let sufficient = gap >= num(&rb, "sep_time_history");
        assert_eq!(ra["sufficient"], sufficient.to_string(), "case {case}");
        assert_eq!(ra["statistic"], "max");
        assert_eq!(ra["min_mean_to_target_ratio"], "NaN");
        if num(&rb, "impacts") > 0.0 {
            pounded += 1;
        }
    }
    assert!(pounded >= 2, "the test must include pounding cases");
}

/// Over a gap axis the design value of the required separation does not move (the runs
/// without contact give it, and the scaling depends on the periods only), and the verdict
/// flips exactly where the gap crosses it: gaps one part in 10⁹ below, at and above the
/// design value D of the first sweep give too small / suffices / suffices (the rule is
/// gap ≥ D), with margin gap − D.
#[test]
fn verdict_flips_exactly_at_the_design_value() {
    let d = tempfile::tempdir().unwrap();
    write_records(d.path());
    write(
        &d.path().join("suite.toml"),
        &scenario(&[(6.0, 0.05)], &suite(&["r1.txt", "r2.txt", "r4.txt"], EC8)),
    );
    let coarse = Sweep::from_file(&sweep_file(
        d.path(),
        "a.toml",
        "suite.toml",
        "[[axis]]\nkey = \"contact.level.1.gap\"\nvalues = [0.0005, 0.005, 0.05, 0.5]\n",
    ))
    .unwrap();
    let head = pounding::study::sweep::results::header(&coarse);
    let rows: Vec<_> = (0..coarse.len())
        .map(|c| table(&format!("{head}\n{}", compute_case(&coarse, c, false).line)).remove(0))
        .collect();
    let design = num(&rows[0], "level1_required_separation");
    assert!(design > 0.0005 && design < 0.5, "{design}");
    for r in &rows {
        assert_eq!(
            num(r, "level1_required_separation"),
            design,
            "the design value moved"
        );
        assert_eq!(r["converged"], "unchecked");
    }
    let below = design * (1.0 - 1e-9);
    let above = design * (1.0 + 1e-9);
    let fine = Sweep::from_file(&sweep_file(
        d.path(),
        "b.toml",
        "suite.toml",
        &format!(
            "[[axis]]\nkey = \"contact.level.1.gap\"\nvalues = [{below:?}, {design:?}, {above:?}]\n"
        ),
    ))
    .unwrap();
    let head = pounding::study::sweep::results::header(&fine);
    for (case, (gap, expected)) in [(below, false), (design, true), (above, true)]
        .into_iter()
        .enumerate()
    {
        let r = table(&format!(
            "{head}\n{}",
            compute_case(&fine, case, false).line
        ))
        .remove(0);
        assert_eq!(num(&r, "level1_gap"), gap);
        assert_eq!(num(&r, "level1_required_separation"), design, "case {case}");
        assert_eq!(r["sufficient"], expected.to_string(), "case {case}");
        assert_eq!(r["level1_sufficient"], expected.to_string(), "case {case}");
        assert_eq!(num(&r, "governing_margin"), gap - design, "case {case}");
    }
}

/// A suite sweep killed with SIGKILL mid-way (and a torn journal line) resumes to the table
/// of an uninterrupted run, byte for byte; three shards merge into it; `pounding plot` draws
/// the design separation and the verdict; a single-record sweep into the suite sweep's
/// directory is refused (the journal never mixes row kinds).
#[test]
fn killed_suite_sweep_resumes_and_shards_merge() {
    let d = tempfile::tempdir().unwrap();
    write_records(d.path());
    write(
        &d.path().join("suite.toml"),
        &scenario(
            &[(6.0, 0.03), (3.0, 0.02)],
            &suite(&["r1.txt", "r2.txt", "r3.txt", "r4.txt"], NONE),
        ),
    );
    let sw = sweep_file(
        d.path(),
        "s.toml",
        "suite.toml",
        "[[axis]]\nkey = \"structure.2.stiffness_scale\"\nfrom = 0.5\nto = 2.0\nsteps = 12\n\
         [[axis]]\nkey = \"contact.level.1.gap\"\nvalues = [0.01, 0.03, 0.1]\n",
    );
    let (full, cut) = (d.path().join("full"), d.path().join("cut"));
    ok(&pounding(&["sweep", s(&sw), "--out", s(&full), "-q"]));
    let reference = std::fs::read_to_string(full.join("results.csv")).unwrap();
    assert_eq!(reference.lines().count(), 37);
    assert!(reference.lines().nth(1).unwrap().contains(",ok,4,max,NaN,"));

    let journal = cut.join("journal.csv");
    common::kill_after_journal_rows(
        std::process::Command::new(BIN).args([
            "sweep",
            s(&sw),
            "--out",
            s(&cut),
            "--no-plot",
            "--jobs",
            "1",
        ]),
        &journal,
        3,
    );
    assert!(
        !cut.join("results.csv").exists(),
        "killed too late to test resuming"
    );
    let mut j = std::fs::read_to_string(&journal).unwrap();
    assert!(j.starts_with("# pounding sweep journal v4;"), "{j}");
    let before = j.lines().count() - 2;
    assert!((3..36).contains(&before), "{before} rows before the kill");
    j.push_str("35,2.0,0.1,ok,4,ma");
    std::fs::write(&journal, j).unwrap();
    let out = ok(&pounding(&["sweep", s(&sw), "--out", s(&cut), "--no-plot"]));
    assert!(out.contains(&format!("{before} resumed")), "{out}");
    assert_eq!(
        std::fs::read_to_string(cut.join("results.csv")).unwrap(),
        reference,
        "resumed results differ from an uninterrupted run"
    );

    // shards
    let merged = common::sharded_and_merged(&sw, d.path(), 3, &[]);
    assert_eq!(merged, reference);

    // the pictures: per level the design separation, the margin and the verdict
    let plots = full.join("plots");
    for f in [
        "heatmap_level1_required_separation_structure.2.stiffness_scale-contact.level.1.gap.png",
        "heatmap_level2_required_separation_structure.2.stiffness_scale-contact.level.1.gap.png",
        "heatmap_sufficient_structure.2.stiffness_scale-contact.level.1.gap.png",
        "heatmap_governing_margin_structure.2.stiffness_scale-contact.level.1.gap.png",
        "lines_structure.2.stiffness_scale.png",
    ] {
        assert!(plots.join(f).is_file(), "{f} missing");
    }
    let one = d.path().join("one");
    ok(&pounding(&[
        "plot",
        s(&full.join("results.csv")),
        "--x",
        "contact.level.1.gap",
        "--field",
        "level2_peak_force",
        "--out",
        s(&one),
        "-q",
    ]));
    assert!(std::fs::read_dir(&one).unwrap().count() >= 2);
    let out = pounding(&["plot", s(&full.join("results.csv")), "--field", "sep_abs"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("level1_required_separation"),
        "{err}"
    );

    // a single-record sweep into the same directory: refused, saying why
    write(
        &d.path().join("single.toml"),
        &scenario(
            &[(6.0, 0.03), (3.0, 0.02)],
            "[ground_motion]\nkind = \"record\"\nfile = \"r1.txt\"\nunits = \"g\"\ndt = 0.01\n",
        ),
    );
    let other = sweep_file(
        d.path(),
        "t.toml",
        "single.toml",
        "[[axis]]\nkey = \"contact.level.1.gap\"\nvalues = [0.01]\n",
    );
    let out = pounding(&["sweep", s(&other), "--out", s(&cut), "--no-plot"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success()
            && err.contains("a suite of records per case")
            && err.contains("never mixed"),
        "{err}"
    );
}

/// The keys of one ground motion cannot be axes of a sweep over a suite: the error names the
/// axis, its line and the reason; so does `ground_period_ratio`. A suite that cannot meet its
/// rule for a case's structures fails that case with the rule's reason.
#[test]
fn single_record_keys_are_refused_naming_the_axis() {
    let d = tempfile::tempdir().unwrap();
    write_records(d.path());
    write(
        &d.path().join("suite.toml"),
        &scenario(&[(6.0, 0.05)], &suite(&["r1.txt", "r2.txt", "r3.txt"], EC8)),
    );
    for key in [
        "ground_motion.scale_to_pga",
        "ground_motion.pga",
        "ground_motion.file",
        "ground_motion.dt",
    ] {
        let value = if key.ends_with("file") {
            "\"r1.txt\""
        } else {
            "0.3"
        };
        let p = sweep_file(
            d.path(),
            "bad.toml",
            "suite.toml",
            &format!(
                "[[axis]]\nkey = \"contact.level.1.gap\"\nvalues = [0.1]\n\
                 [[axis]]\nkey = \"{key}\"\nvalues = [{value}]\n"
            ),
        );
        let e = Sweep::from_file(&p).unwrap_err().to_string();
        assert!(
            e.contains("bad.toml:5:1")
                && e.contains("`axis[2].key`")
                && e.contains(&format!("`{key}`"))
                && e.contains("suite of records"),
            "{key}: {e}"
        );
    }
    let p = sweep_file(
        d.path(),
        "bad.toml",
        "suite.toml",
        "[[axis]]\nkey = \"ground_period_ratio\"\nvalues = [1.0]\n",
    );
    let e = Sweep::from_file(&p).unwrap_err().to_string();
    assert!(
        e.contains("ground_period_ratio") && e.contains("harmonic"),
        "{e}"
    );

    // EC8 needs ≥ 3 records: a 2-record suite fails every case with that reason
    write(
        &d.path().join("two.toml"),
        &scenario(&[(6.0, 0.05)], &suite(&["r1.txt", "r2.txt"], EC8)),
    );
    let sw = Sweep::from_file(&sweep_file(
        d.path(),
        "two-sweep.toml",
        "two.toml",
        "[[axis]]\nkey = \"contact.level.1.gap\"\nvalues = [0.1]\n",
    ))
    .unwrap();
    let row = compute_case(&sw, 0, false);
    assert!(row.failed);
    assert!(
        row.line.contains("failed: ground_motion.scaling:") && row.line.contains("at least 3"),
        "{}",
        row.line
    );
}
