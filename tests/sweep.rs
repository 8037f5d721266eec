//! `pounding sweep`, `merge` and `plot` driven as a user would: through the binary.

mod common;

use std::path::{Path, PathBuf};

use common::pounding_here as pounding;
use common::{ok, s};

const BIN: &str = env!("CARGO_BIN_EXE_pounding");
const PAPER_C: &str = include_str!("../examples/paper-c.toml");

fn base(duration: f64) -> String {
    PAPER_C.replace("duration = 20.0", &format!("duration = {duration:?}"))
}

fn write(path: &Path, text: &str) -> PathBuf {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).unwrap();
    }
    std::fs::write(path, text).unwrap();
    path.to_path_buf()
}

/// A sweep of `n1 × 3` cases over period ratio and PGA.
fn study(dir: &Path, n1: usize, duration: f64) -> PathBuf {
    write(&dir.join("base.toml"), &base(duration));
    write(
        &dir.join("study.toml"),
        &format!(
            "scenario = \"base.toml\"\n\
             [[axis]]\nkey = \"period_ratio\"\nfrom = 0.4\nto = 1.0\nsteps = {n1}\n\
             [[axis]]\nkey = \"ground_motion.pga\"\nvalues = [0.2, 0.5, 0.8]\n"
        ),
    )
}

fn data_rows(csv: &str) -> Vec<&str> {
    csv.lines().skip(1).collect()
}

#[test]
fn killed_sweep_resumes_without_losing_or_repeating_rows() {
    let d = tempfile::tempdir().unwrap();
    let sweep = study(d.path(), 20, 20.0);
    let (full, cut) = (d.path().join("full"), d.path().join("cut"));
    ok(&pounding(&[
        "sweep",
        s(&sweep),
        "--out",
        s(&full),
        "--no-plot",
        "-q",
    ]));
    let reference = std::fs::read_to_string(full.join("results.csv")).unwrap();
    assert_eq!(data_rows(&reference).len(), 60);

    // start, wait until some rows are journaled, kill -9
    let journal = cut.join("journal.csv");
    common::kill_after_journal_rows(
        std::process::Command::new(BIN).args([
            "sweep",
            s(&sweep),
            "--out",
            s(&cut),
            "--no-plot",
            "--jobs",
            "1",
        ]),
        &journal,
        5,
    );
    assert!(
        !cut.join("results.csv").exists(),
        "killed too late to test resuming"
    );
    // a torn last line, as a kill in the middle of a write leaves
    let mut j = std::fs::read_to_string(&journal).unwrap();
    let before = j.lines().count() - 2;
    assert!((5..60).contains(&before), "{before} rows before the kill");
    j.push_str("59,1.0,0.8,ok,0.12");
    std::fs::write(&journal, j).unwrap();

    let out = ok(&pounding(&[
        "sweep",
        s(&sweep),
        "--out",
        s(&cut),
        "--no-plot",
    ]));
    assert!(
        out.contains(&format!("{} resumed", before)),
        "expected {before} resumed: {out}"
    );
    let resumed = std::fs::read_to_string(cut.join("results.csv")).unwrap();
    assert_eq!(
        resumed, reference,
        "resumed results differ from an uninterrupted run"
    );
    // the journal holds every case exactly once
    let j = std::fs::read_to_string(&journal).unwrap();
    let mut cases: Vec<usize> = j
        .lines()
        .skip(2)
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    cases.sort();
    assert_eq!(cases, (0..60).collect::<Vec<_>>());

    // a rerun of a finished sweep computes nothing and rewrites the same table
    let out = ok(&pounding(&[
        "sweep",
        s(&sweep),
        "--out",
        s(&cut),
        "--no-plot",
    ]));
    assert!(
        out.contains("0 computed") && out.contains("60 resumed"),
        "{out}"
    );
    assert_eq!(
        std::fs::read_to_string(cut.join("results.csv")).unwrap(),
        reference
    );

    // a different sweep into the same directory is refused
    let other = std::fs::read_to_string(&sweep)
        .unwrap()
        .replace("0.8]", "0.9]");
    write(&sweep, &other);
    let out = pounding(&["sweep", s(&sweep), "--out", s(&cut), "--no-plot"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("different sweep") && err.contains("journal.csv"),
        "{err}"
    );
}

#[test]
fn rows_are_identical_to_pounding_run() {
    let d = tempfile::tempdir().unwrap();
    let sweep = study(d.path(), 4, 6.0);
    let out = d.path().join("o");
    ok(&pounding(&[
        "sweep",
        s(&sweep),
        "--out",
        s(&out),
        "--no-plot",
        "-q",
    ]));
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for case in [0usize, 7, 11] {
        let row: Vec<&str> = data_rows(&csv)[case].split(',').collect();
        assert_eq!(row[0], case.to_string());
        let text = ok(&pounding(&[
            "sweep",
            s(&sweep),
            "--case",
            &case.to_string(),
        ]));
        let sc = write(&d.path().join(format!("case{case}.toml")), &text);
        let run_dir = d.path().join(format!("run{case}"));
        ok(&pounding(&[
            "run",
            s(&sc),
            "--out",
            s(&run_dir),
            "--no-plot",
            "-q",
        ]));
        // the numbers as summary.json writes them (raw text: serde_json's default parser is
        // not correctly rounded, so going through f64 could hide or invent differences)
        let json = std::fs::read_to_string(run_dir.join("summary.json")).unwrap();
        // (without the per-floor arrays, whose keys repeat the structures')
        let json = {
            let mut out = String::new();
            let mut rest = json.as_str();
            while let Some(i) = rest.find("\"floors\": [") {
                out.push_str(&rest[..i]);
                let mut depth = 0;
                let mut end = i;
                for (j, ch) in rest[i..].char_indices() {
                    match ch {
                        '[' => depth += 1,
                        ']' => {
                            depth -= 1;
                            if depth == 0 {
                                end = i + j + 1;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                rest = &rest[end..];
            }
            out.push_str(rest);
            out
        };
        let raw = |key: &str, nth: usize| -> String {
            let pat = format!("\"{key}\": ");
            let start = json.match_indices(&pat).nth(nth).unwrap().0 + pat.len();
            json[start..]
                .split([',', '\n', '}'])
                .next()
                .unwrap()
                .trim()
                .to_string()
        };
        let expect = [
            ("peak_displacement_1", raw("peak_displacement", 0)),
            ("peak_displacement_2", raw("peak_displacement", 1)),
            (
                "peak_displacement_no_contact_1",
                raw("peak_displacement_no_contact", 0),
            ),
            (
                "peak_displacement_no_contact_2",
                raw("peak_displacement_no_contact", 1),
            ),
            ("change_percent_1", raw("change_percent", 0)),
            ("change_percent_2", raw("change_percent", 1)),
            ("peak_force", raw("peak_force", 0)),
            ("impacts", raw("impacts", 0)),
            ("contact_time", raw("contact_time", 0)),
            ("sep_abs", raw("abs", 0)),
            ("sep_srss", raw("srss", 0)),
            ("sep_ddc", raw("ddc", 0)),
            ("sep_time_history", raw("time_history", 0)),
        ];
        for (col, v) in expect {
            let i = header.iter().position(|h| *h == col).unwrap();
            // byte-identical to the JSON text, hence the same f64
            assert_eq!(row[i], v, "case {case}, {col}");
        }
        // the self-check of the headline numbers, as `pounding run` reports them (its check
        // also compares the floors, which a sweep row does not record: those are left out)
        let full = std::fs::read_to_string(run_dir.join("summary.json")).unwrap();
        let value: serde_json::Value = serde_json::from_str(&full).unwrap();
        let headline = value["accuracy"]["quantities"]
            .as_object()
            .unwrap()
            .keys()
            .filter(|q| !q.starts_with("floor_"))
            .map(|q| {
                let at = json.find(&format!("\"{q}\": {{")).unwrap();
                let key = "\"change\": ";
                let from = at + json[at..].find(key).unwrap() + key.len();
                json[from..]
                    .split([',', '\n', '}'])
                    .next()
                    .unwrap()
                    .trim()
                    .parse::<f64>()
                    .unwrap()
            })
            .fold(0.0, f64::max);
        let col = |c: &str| header.iter().position(|h| *h == c).unwrap();
        assert_eq!(
            row[col("check_max_change")].parse::<f64>().unwrap(),
            headline,
            "case {case}"
        );
        assert_eq!(
            row[col("converged")],
            (headline <= 0.01).to_string(),
            "case {case}"
        );
        assert_eq!(row[3], "ok");
    }
}

#[test]
fn shards_merge_into_the_full_table() {
    let d = tempfile::tempdir().unwrap();
    let sweep = study(d.path(), 5, 3.0);
    let (full, parts) = (d.path().join("full"), d.path().join("parts"));
    ok(&pounding(&[
        "sweep",
        s(&sweep),
        "--out",
        s(&full),
        "--no-plot",
        "-q",
    ]));
    for k in 1..=3 {
        let shard = format!("{k}/3");
        ok(&pounding(&[
            "sweep",
            s(&sweep),
            "--out",
            s(&parts),
            "--shard",
            &shard,
            "-q",
        ]));
    }
    let merged = d.path().join("merged.csv");
    let out = ok(&pounding(&["merge", s(&merged), s(&parts)]));
    assert!(out.contains("15 cases"), "{out}");
    assert_eq!(
        std::fs::read_to_string(&merged).unwrap(),
        std::fs::read_to_string(full.join("results.csv")).unwrap()
    );
    // a part missing
    let p1 = parts.join("results-shard-1-of-3.csv");
    let p3 = parts.join("results-shard-3-of-3.csv");
    let out = pounding(&["merge", s(&merged), s(&p1), s(&p3)]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("part(s) 2 of 3 are missing"));
    // a part given twice
    let out = pounding(&["merge", s(&merged), s(&p1), s(&p1)]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("given twice"));
    // rows lost from a part (renamed so that names do not tell)
    let t = std::fs::read_to_string(&p3).unwrap();
    let cut: Vec<&str> = t.lines().take(3).collect();
    let a = write(&d.path().join("a.csv"), &(cut.join("\n") + "\n"));
    let b = d.path().join("b.csv");
    std::fs::copy(&p1, &b).unwrap();
    let c = d.path().join("c.csv");
    std::fs::copy(parts.join("results-shard-2-of-3.csv"), &c).unwrap();
    let out = pounding(&["merge", s(&merged), s(&a), s(&b), s(&c)]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("cases are missing"),
        "{err}"
    );
    // duplicates across parts
    let out = pounding(&["merge", s(&merged), s(&b), s(&b)]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("is in both"));
    // plot from the merged table
    let plots = d.path().join("plots");
    let out = ok(&pounding(&[
        "plot",
        s(&merged),
        "--x",
        "period_ratio",
        "--y",
        "ground_motion.pga",
        "--field",
        "peak_force",
        "--out",
        s(&plots),
    ]));
    assert!(out.contains("wrote 1 pictures"), "{out}");
    assert!(plots.join("heatmap_peak_force_T1T2-PGA.png").exists());
}

#[test]
fn failed_cases_are_recorded_and_the_sweep_goes_on() {
    let d = tempfile::tempdir().unwrap();
    write(&d.path().join("base.toml"), &base(2.0));
    let sweep = write(
        &d.path().join("s.toml"),
        "scenario = \"base.toml\"\n[[axis]]\nkey = \"solver.dt\"\nvalues = [0.001, 0.05, 0.002]\n",
    );
    let out = d.path().join("o");
    let r = pounding(&["sweep", s(&sweep), "--out", s(&out), "--no-plot"]);
    ok(&r);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(err.contains("1 of 3 cases failed"), "{err}");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let rows = data_rows(&csv);
    assert!(rows[0].contains(",ok,"));
    assert!(
        rows[1].starts_with("1,0.05,\"failed: `solver.dt` = 0.05:")
            && rows[1].contains("stability limit"),
        "{}",
        rows[1]
    );
    assert!(rows[1].ends_with(&",".repeat(pounding::study::sweep::results::FIELDS.len())));
    assert!(rows[2].contains(",ok,"));
}

#[test]
fn record_files_resolve_relative_to_the_sweep_file() {
    let d = tempfile::tempdir().unwrap();
    // base scenario and records in different directories from the sweep file
    write(&d.path().join("base/base.toml"), &base(3.0));
    let rec = |f: f64| {
        (0..300)
            .map(|i| {
                let t = i as f64 * 0.01;
                format!("{t} {}\n", (2.0 * std::f64::consts::PI * f * t).sin())
            })
            .collect::<String>()
    };
    write(&d.path().join("records/a.txt"), &rec(1.5));
    write(&d.path().join("records/b.txt"), &rec(2.5));
    let sweep = write(
        &d.path().join("sweeps/s.toml"),
        "scenario = \"../base/base.toml\"\n\
         [[axis]]\nkey = \"ground_motion.file\"\nvalues = [\"../records/a.txt\", \"../records/b.txt\"]\n\
         [[axis]]\nkey = \"ground_motion.pga\"\nvalues = [0.3, 0.6]\n",
    );
    let out = d.path().join("o");
    ok(&pounding(&["sweep", s(&sweep), "--out", s(&out), "-q"]));
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let rows = data_rows(&csv);
    assert_eq!(rows.len(), 4);
    assert!(
        rows[0].starts_with("0,../records/a.txt,0.3,ok,"),
        "{}",
        rows[0]
    );
    assert!(rows.iter().all(|r| r.contains(",ok,")), "{csv}");
    // the PGA axis scales the record: the case scenario says so
    let text = ok(&pounding(&["sweep", s(&sweep), "--case", "3"]));
    assert!(text.contains("scale_to_pga = 0.6") && text.contains("kind = \"record\""));
    assert!(!text.contains("\nperiod = 0.65"), "{text}");
    // lines over the PGA, one line per record
    assert!(out.join("plots/lines_PGA.png").exists());
    // an edited record is a different sweep: its results must not resume into the old rows
    write(&d.path().join("records/b.txt"), &rec(3.0));
    let again = pounding(&["sweep", s(&sweep), "--out", s(&out), "-q"]);
    assert!(!again.status.success());
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(err.contains("different sweep"), "{err}");
}

#[test]
fn mistakes_are_reported_with_file_key_and_range() {
    let d = tempfile::tempdir().unwrap();
    write(&d.path().join("base.toml"), &base(2.0));
    let sweep = write(
        &d.path().join("s.toml"),
        "scenario = \"base.toml\"\n[[axis]]\nkey = \"ground_motion.pga\"\nfrom = 0.1\nto = 0.5\nsteps = 0\n",
    );
    let out = pounding(&["sweep", s(&sweep)]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("s.toml:6:9") && err.contains("axis[1].steps") && err.contains("from 1 to"),
        "{err}"
    );
    // every case invalid: refused before anything is computed
    write(
        &d.path().join("base.toml"),
        &base(2.0).replace("gap = 0.0127", "gap = -1.0"),
    );
    let sweep = write(
        &d.path().join("s.toml"),
        "scenario = \"base.toml\"\n[[axis]]\nkey = \"ground_motion.pga\"\nvalues = [0.1, 0.2]\n",
    );
    let o = d.path().join("o");
    let out = pounding(&["sweep", s(&sweep), "--out", s(&o)]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no case of the sweep is a valid scenario")
            && err.contains("`contact.gap` = -1"),
        "{err}"
    );
    assert!(!o.join("results.csv").exists());
    let out = pounding(&["sweep", s(&sweep), "--shard", "4/3"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("1 ≤ K ≤ N"));
}

#[test]
fn example_sweeps_are_valid() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    for (name, cases) in [
        ("quick-sweep.toml", 21),
        ("paper-study.toml", 4551),
        ("bench-10k.toml", 10_000),
        ("record-sweep.toml", 36),
    ] {
        let s = pounding::study::sweep::Sweep::from_file(&dir.join(name)).unwrap();
        assert_eq!(s.len(), cases, "{name}");
        for c in [0, cases / 2, cases - 1] {
            s.case_scenario(c)
                .unwrap_or_else(|e| panic!("{name} case {c}: {e}"));
        }
    }
    // a scenario given where a sweep is expected
    let out = pounding(&["sweep", s(&dir.join("paper-c.toml"))]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("looks like a scenario file"));
}

/// A case that RK4 refuses in contact (issue 9's stiff case at dt = 1 ms, whose first impact at
/// t ≈ 0.51 s has ω_c·dt ≈ 3.0 > 2√2: see `tests/integrators.rs`) is recorded as failed with
/// the refusal and its suggested step, and the case at a stable step (0.5 ms, ω_c·dt ≈ 1.6 at
/// the first impact) is computed.
#[test]
fn a_case_refused_in_contact_is_recorded_with_its_reason() {
    let d = tempfile::tempdir().unwrap();
    let stiff = base(1.0)
        .replacen("period = 0.4203", "period = 0.3", 1)
        .replacen("period = 0.6004285714285714", "period = 0.6", 1)
        .replacen("\nstiffness = 2.808e10", "\nstiffness = 2.808e13", 1)
        .replacen("pga = 0.6\nperiod = 0.65", "pga = 0.5\nperiod = 0.8", 1);
    write(&d.path().join("base.toml"), &stiff);
    let sweep = write(
        &d.path().join("s.toml"),
        "scenario = \"base.toml\"\n[[axis]]\nkey = \"solver.dt\"\nvalues = [0.001, 0.0005]\n",
    );
    let out = d.path().join("o");
    let r = pounding(&["sweep", s(&sweep), "--out", s(&out), "--no-plot"]);
    ok(&r);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(err.contains("1 of 2 cases failed"), "{err}");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let rows = data_rows(&csv);
    assert!(
        rows[0].starts_with("0,0.001,\"failed: rk4 refused at t = 0.5")
            && rows[0].contains("contact level 1")
            && rows[0].contains("Largest stable step, estimated: dt ≈ "),
        "{}",
        rows[0]
    );
    assert!(rows[0].ends_with(",,,,,,,,,,,,,"), "{}", rows[0]);
    assert!(rows[1].starts_with("1,0.0005,ok,"), "{}", rows[1]);
}

/// Every case checks itself by default: the columns `check_max_change` and `converged` say how
/// it fared; `--no-check` writes `unchecked` and says so; a journal of the format before these
/// columns is refused with a message that says why.
#[test]
fn sweep_records_the_self_check_and_no_check_says_so() {
    let d = tempfile::tempdir().unwrap();
    write(&d.path().join("base.toml"), &base(3.0));
    // RK4 at 1 ms is accurate on these 3 s; at 8 ms (near its stability limit) it is not
    let sweep = write(
        &d.path().join("s.toml"),
        "scenario = \"base.toml\"\n[[axis]]\nkey = \"solver.dt\"\nvalues = [0.001, 0.008]\n",
    );
    let out = d.path().join("o");
    let r = pounding(&["sweep", s(&sweep), "--out", s(&out), "--no-plot"]);
    let stdout = ok(&r);
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert!(
        stdout.contains("1 case(s) converged within 1 %, 1 NOT converged"),
        "{stdout}"
    );
    assert!(
        stderr.contains("1 of 2 cases are NOT converged") && stderr.contains("case 1"),
        "{stderr}"
    );
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (change, conv) = (col("check_max_change"), col("converged"));
    let rows: Vec<Vec<&str>> = data_rows(&csv)
        .iter()
        .map(|r| r.split(',').collect())
        .collect();
    assert_eq!(rows[0][conv], "true");
    assert!(rows[0][change].parse::<f64>().unwrap() < 0.01);
    assert_eq!(rows[1][conv], "false");
    assert!(rows[1][change].parse::<f64>().unwrap() > 0.01);
    // the table reads back, `converged` as 1/0
    let t = pounding::study::sweep::results::Table::read(&out.join("results.csv")).unwrap();
    let k = pounding::study::sweep::results::Table::field_index("converged").unwrap();
    assert_eq!((t.rows[&0].fields[k], t.rows[&1].fields[k]), (1.0, 0.0));

    // --no-check: the rows and the summary say the cases were not self-checked
    let plain = d.path().join("plain");
    let stdout = ok(&pounding(&[
        "sweep",
        s(&sweep),
        "--out",
        s(&plain),
        "--no-plot",
        "--no-check",
    ]));
    assert!(stdout.contains("NOT self-checked"), "{stdout}");
    let csv = std::fs::read_to_string(plain.join("results.csv")).unwrap();
    for r in data_rows(&csv) {
        assert!(r.ends_with(",,unchecked"), "{r}");
    }
    // the numbers themselves are those of the checked sweep
    let strip = |t: &str| -> Vec<String> {
        data_rows(t)
            .iter()
            .map(|r| r.rsplitn(3, ',').nth(2).unwrap().to_string())
            .collect()
    };
    assert_eq!(
        strip(&csv),
        strip(&std::fs::read_to_string(out.join("results.csv")).unwrap())
    );

    // a journal of the previous format (v1, without the check columns) is not resumed
    let journal = plain.join("journal.csv");
    let j = std::fs::read_to_string(&journal).unwrap();
    write(&journal, &j.replacen("journal v2;", "journal v1;", 1));
    let r = pounding(&["sweep", s(&sweep), "--out", s(&plain), "--no-plot"]);
    assert!(!r.status.success());
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(
        err.contains("another version of pounding") && err.contains("journal v1"),
        "{err}"
    );
}

/// `solver.rtol` and `solver.atol` are axis keys (a study's speed/accuracy dial, README
/// "What a default tolerance can promise"): each case runs at the axis's tolerance, exactly as
/// a scenario file giving that tolerance does, and the default's value reproduces a sweep
/// without the axis.
#[test]
fn tolerances_are_axis_keys() {
    let d = tempfile::tempdir().unwrap();
    let exact = |text: &str| {
        text.replace("method = \"rk4\"", "method = \"exact-modal\"")
            .replace("dt = 0.001\n", "dt = 0.01\n")
            .replace("duration = 20.0", "duration = 5.0")
    };
    write(&d.path().join("base.toml"), &exact(PAPER_C));
    let sweep = |name: &str, axis: &str| {
        let file = write(
            &d.path().join(format!("{name}.toml")),
            &format!("scenario = \"base.toml\"\n{axis}"),
        );
        let out = d.path().join(name);
        ok(&pounding(&[
            "sweep",
            s(&file),
            "--out",
            s(&out),
            "--no-plot",
            "--no-check",
            "-q",
        ]));
        std::fs::read_to_string(out.join("results.csv")).unwrap()
    };
    // the result columns of a row (after case, the axis columns and status)
    let results = |csv: &str, row: usize, axes: usize| -> Vec<String> {
        let line = data_rows(csv)[row];
        line.split(',').skip(2 + axes).map(String::from).collect()
    };
    let column = |csv: &str, row: usize, col: &str| -> String {
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let i = header.iter().position(|h| *h == col).unwrap();
        data_rows(csv)[row].split(',').nth(i).unwrap().to_string()
    };
    // what `pounding run` gives for the base with `line` added under [solver]
    let run = |name: &str, line: &str| -> String {
        let text = exact(PAPER_C).replace("[solver]\n", &format!("[solver]\n{line}\n"));
        let sc = write(&d.path().join(format!("{name}-case.toml")), &text);
        let dir = d.path().join(format!("{name}-run"));
        ok(&pounding(&[
            "run",
            s(&sc),
            "--out",
            s(&dir),
            "--no-plot",
            "--no-check",
            "-q",
        ]));
        // (the raw text of `contact.peak_force`, as the row writes it: the first one after
        // the `"contact": {` object opens; the floors' pulses name theirs earlier)
        let json = std::fs::read_to_string(dir.join("summary.json")).unwrap();
        let contact = json.find("\"contact\": {").unwrap();
        let pat = "\"peak_force\": ";
        let start = contact + json[contact..].find(pat).unwrap() + pat.len();
        json[start..]
            .split([',', '\n'])
            .next()
            .unwrap()
            .trim()
            .to_string()
    };

    let rtol = sweep(
        "rtol",
        "[[axis]]\nkey = \"solver.rtol\"\nvalues = [1e-4, 1e-8]\n",
    );
    let plain = sweep(
        "plain",
        "[[axis]]\nkey = \"contact.gap\"\nvalues = [0.0127]\n",
    );
    // 1e-8 is the default: the same numbers as the sweep that does not set it
    assert_eq!(results(&rtol, 1, 1), results(&plain, 0, 1));
    // 1e-4 took effect (paper-c's peak force moves by ~2e-5 between the two: a changed digit)
    assert_ne!(
        column(&rtol, 0, "peak_force"),
        column(&rtol, 1, "peak_force")
    );
    // and is what a scenario file saying `rtol = 1e-4` gives, bit for bit
    assert_eq!(column(&rtol, 0, "peak_force"), run("r4", "rtol = 1e-4"));

    let atol = sweep("atol", "[[axis]]\nkey = \"solver.atol\"\nvalues = [1e-5]\n");
    assert_eq!(column(&atol, 0, "peak_force"), run("a5", "atol = 1e-5"));
    assert_ne!(
        column(&atol, 0, "peak_force"),
        column(&plain, 0, "peak_force")
    );
}
