//! Issue 10, a newcomer's first hour: outputs written summary-last and nothing stale beside a
//! summary, guards against runs that would eat the machine, defaults of a minimal scenario,
//! messages.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use pounding::analysis::simulate::{NoSink, simulate_streaming};
use pounding::input::scenario::{DEFAULT_DAMPING_RATIO, DEFAULT_MODES, Scenario};
use pounding::output::run::history_csv;
use pounding::output::writer::RunWriter;

mod common;
use common::pounding;

fn text(o: &[u8]) -> String {
    String::from_utf8_lossy(o).into_owned()
}

/// Two structures (length, mass, period), a gap and a contact stiffness, a harmonic motion:
/// nothing else.
const MINIMAL: &str = r#"
[[structure]]
length = 10.0
mass = 2.273e6
period = 0.42

[[structure]]
length = 10.0
mass = 2.273e6
period = 0.6

[contact]
stiffness = 2.808e10
gap = 0.0127

[ground_motion]
kind = "harmonic"
pga = 0.3
period = 0.65
"#;

fn parse(text: &str) -> Result<Scenario, String> {
    Scenario::from_toml(text, "min.toml", Path::new(".")).map_err(|e| e.to_string())
}

fn short(text: &str, duration: f64) -> Scenario {
    parse(&format!("{text}\n[solver]\nduration = {duration}\n")).unwrap()
}

/// The writer renames every file into place before it writes summary.json, which comes last;
/// an earlier summary.json is removed as soon as the writer is created (before the run), and
/// the streamed history.csv is the same text as the one formed from the in-memory history
/// (two code paths, one format).
#[test]
fn summary_is_written_last_and_a_stale_summary_goes_first() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("summary.json"), "{\"stale\": true}").unwrap();
    let order: Rc<RefCell<Vec<PathBuf>>> = Rc::default();
    let seen = order.clone();
    let mut writer = RunWriter::create(dir.path(), 1)
        .unwrap()
        .on_written(move |p| seen.borrow_mut().push(p.to_path_buf()));
    assert!(
        !dir.path().join("summary.json").exists(),
        "a summary of an earlier run must not survive the start of a new one"
    );
    let sc = short(MINIMAL, 3.0);
    let report = simulate_streaming(&sc, false, &mut writer).unwrap();
    let draw = |d: &Path| -> Result<Vec<PathBuf>, String> {
        let p = d.join("history.png");
        std::fs::write(&p, b"picture").map_err(|e| e.to_string())?;
        Ok(vec![p])
    };
    let written = writer.finish(&sc, &report, Some(Box::new(draw))).unwrap();
    let names: Vec<String> = order
        .borrow()
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        ["history.csv", "impacts.csv", "history.png", "summary.json"]
    );
    assert_eq!(written, *order.borrow());
    let streamed = std::fs::read_to_string(dir.path().join("history.csv")).unwrap();
    assert_eq!(streamed, history_csv(&report));
    // 3 s at 10 ms: 301 samples and the header
    assert_eq!(streamed.lines().count(), 302);
    // no temporary file is left behind
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// `--no-plot` into a directory holding pictures of an earlier run removes them: nothing stale
/// beside the new summary; a plain run writes them again.
#[test]
fn no_plot_removes_stale_pictures() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("min.toml"),
        format!("{MINIMAL}\n[solver]\nduration = 2.0\n"),
    )
    .unwrap();
    let out = pounding(
        &["run", "min.toml", "--out", "res", "--no-check", "-q"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let res = dir.path().join("res");
    assert!(res.join("history.png").exists() && res.join("history.svg").exists());
    let out = pounding(
        &[
            "run",
            "min.toml",
            "--out",
            "res",
            "--no-check",
            "--no-plot",
            "-q",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(res.join("summary.json").exists());
    assert!(!res.join("history.png").exists(), "stale history.png left");
    assert!(!res.join("history.svg").exists(), "stale history.svg left");
    assert!(
        out.stdout.is_empty(),
        "--quiet printed: {}",
        text(&out.stdout)
    );
}

/// A run of 10⁶ s at the default 10 ms interval would write 10⁸ rows of history.csv and
/// floors.csv (6 numbers, and 1 + 4 per station of the two cantilevers, by default the contact
/// height at their top: 15 numbers of 16 bytes, ≈ 24 GB): refused before it starts,
/// with the size, the keys that change it and the flag that allows it; nothing is written.
#[test]
fn a_run_too_large_is_refused_with_the_size_and_the_keys() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("long.toml"),
        format!("{MINIMAL}\n[solver]\nduration = 1e6\n"),
    )
    .unwrap();
    let out = pounding(&["run", "long.toml", "--out", "res"], dir.path());
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    for needle in [
        "24 GB",
        "100000001 rows",
        "solver.output_interval",
        "solver.duration",
        "--max-output-size",
        "limit of 1.0 GB",
    ] {
        assert!(err.contains(needle), "`{needle}` missing in: {err}");
    }
    assert!(
        !dir.path().join("res").exists(),
        "a refused run wrote something"
    );
    // the library's estimate, from the formula: rows = duration/interval + 1, 15 numbers a row
    let sc = short(MINIMAL, 1e6);
    let e = pounding::output::budget::estimate_run(&sc);
    assert_eq!(e.rows, 100_000_001);
    assert_eq!(
        e.bytes,
        100_000_001 * (6 + 1 + 4 * 2) * pounding::output::budget::HISTORY_BYTES_PER_NUMBER
    );
    assert!(pounding::output::budget::check_run(&sc, 200_000_000_000).is_ok());
}

/// A minimal scenario runs, with every default documented and listed: in the printed summary
/// and in summary.json (`defaults_applied`).
#[test]
fn minimal_scenario_runs_with_listed_defaults() {
    let sc = parse(MINIMAL).unwrap();
    assert_eq!(sc.structures[0].modes(), DEFAULT_MODES);
    assert_eq!(sc.structures[1].modes(), DEFAULT_MODES);
    let m = sc.structures[0].modal();
    assert!(m.zeta.iter().all(|&z| z == DEFAULT_DAMPING_RATIO));
    assert_eq!(sc.solver.method, pounding::integrate::Method::DEFAULT);
    assert_eq!(
        sc.solver.duration,
        pounding::input::scenario::DEFAULT_HARMONIC_DURATION
    );
    for key in [
        "structure[1].modes = 20",
        "structure[2].damping_ratio = 0.05",
        "solver.method = \"exact-modal\"",
        "solver.duration = 20",
        "solver.dt = 0.001",
        "solver.output_interval = 0.01",
    ] {
        assert!(
            sc.defaults_applied.iter().any(|d| d.starts_with(key)),
            "`{key}` not in {:?}",
            sc.defaults_applied
        );
    }
    // a full scenario applies none of these
    let full =
        Scenario::from_file(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/paper-c.toml"))
            .unwrap();
    assert!(
        !full
            .defaults_applied
            .iter()
            .any(|d| d.contains("modes") || d.contains("solver.dt")),
        "{:?}",
        full.defaults_applied
    );

    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("min.toml"),
        format!("{MINIMAL}\n[solver]\nduration = 2.0\n"),
    )
    .unwrap();
    let out = pounding(
        &["run", "min.toml", "--out", "res", "--no-plot"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains("defaults used") && stdout.contains("structure[1].modes = 20"),
        "{stdout}"
    );
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("res/summary.json")).unwrap(),
    )
    .unwrap();
    let applied = summary["defaults_applied"].as_array().unwrap();
    assert!(applied.iter().any(|d| {
        d.as_str()
            .unwrap()
            .starts_with("structure[1].damping_ratio = 0.05")
    }));
}

/// A record's duration is the default simulated time: (NPTS − 1)·DT of the bundled record,
/// 7994 × 0.005 s; the default largest step is the record's own spacing when smaller than 1 ms
/// (it is not: 5 ms), so 1 ms.
#[test]
fn record_duration_is_the_default_duration() {
    let text = MINIMAL.replace(
        "kind = \"harmonic\"\npga = 0.3\nperiod = 0.65",
        "kind = \"record\"\nfile = \"RSN753_LOMAP_CLS000.AT2\"",
    );
    let sc = Scenario::from_toml(
        &text,
        "rec.toml",
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/records"),
    )
    .unwrap();
    assert!(
        (sc.solver.duration - 7994.0 * 0.005).abs() < 1e-9,
        "{}",
        sc.solver.duration
    );
    assert_eq!(sc.solver.dt, 0.001);
    assert!(
        sc.defaults_applied
            .iter()
            .any(|d| d.contains("the record's duration"))
    );
}

/// Several missing keys: one message naming every one, each with file:line:col.
#[test]
fn every_missing_key_in_one_message() {
    let text = MINIMAL
        .replacen("mass = 2.273e6\n", "", 1)
        .replace("gap = 0.0127\n", "")
        .replace("pga = 0.3\n", "");
    let err = parse(&text).unwrap_err();
    assert!(
        err.starts_with("min.toml: 3 required keys are missing:"),
        "{err}"
    );
    for needle in [
        "min.toml:2:1: `structure[1].mass`",
        "`contact.gap`",
        "`ground_motion.pga`",
    ] {
        assert!(err.contains(needle), "`{needle}` missing in: {err}");
    }
    // one missing key keeps the one-line message
    let err = parse(&MINIMAL.replace("gap = 0.0127\n", "")).unwrap_err();
    assert!(err.contains("missing key `contact.gap`"), "{err}");
}

/// `modes = 3.0` says "whole number", with the place and the range; strings too.
#[test]
fn modes_must_be_a_whole_number() {
    let with = |v: &str| {
        parse(&MINIMAL.replacen("period = 0.42", &format!("period = 0.42\nmodes = {v}"), 1))
    };
    let err = with("3.0").unwrap_err();
    for needle in [
        "min.toml:6:9",
        "`structure[1].modes` = 3.0",
        "whole number",
        "write 3",
        "1 to 500",
    ] {
        assert!(err.contains(needle), "`{needle}` missing in: {err}");
    }
    let err = with("2.5").unwrap_err();
    assert!(
        err.contains("must be a whole number from 1 to 500"),
        "{err}"
    );
    let err = with("\"three\"").unwrap_err();
    assert!(
        err.contains("must be a whole number from 1 to 500"),
        "{err}"
    );
    assert_eq!(with("7").unwrap().structures[0].modes(), 7);
    assert!(with("0").unwrap_err().contains("1 to 500"));
}

/// Implausible values warn, saying why: PGA above 3 g, a gap of metres (at validation); a
/// drift beyond 5 % and a penetration larger than the gap (after the run: 0.6 g on these
/// structures gives 0.55 m at 10 m on structure 2 without pounding, and a Hertz contact of
/// 2.808e10 N/m^1.5 overlaps by more than the 12.7 mm gap).
#[test]
fn implausible_values_warn_with_the_reason() {
    let sc = parse(
        &MINIMAL
            .replace("pga = 0.3", "pga = 9.81")
            .replace("gap = 0.0127", "gap = 2.5"),
    )
    .unwrap();
    assert_eq!(sc.warnings.len(), 2, "{:?}", sc.warnings);
    assert!(sc.warnings[0].contains("9.810 g") && sc.warnings[0].contains("m/s²"));
    assert!(
        sc.warnings[1].contains("`contact.gap` = 2.5 m") && sc.warnings[1].contains("mm or cm")
    );
    assert!(parse(MINIMAL).unwrap().warnings.is_empty());

    let strong = short(&MINIMAL.replace("pga = 0.3", "pga = 0.6"), 6.0);
    let r = simulate_streaming(&strong, false, &mut NoSink).unwrap();
    let drift = r
        .warnings
        .iter()
        .find(|w| w.contains("drift"))
        .expect("a drift warning");
    assert!(drift.contains("beyond 5 %"), "{drift}");
    let peak = r.structures[1].peak_displacement_no_contact;
    assert!(peak > 0.05 * 10.0, "the test's premise: {peak}");
    let pen = r
        .warnings
        .iter()
        .find(|w| w.contains("overlap"))
        .expect("a penetration warning");
    assert!(pen.contains("larger than the gap (12.7 mm)"), "{pen}");
    assert!(r.contact.max_penetration > 0.0127);
    // the scenario's own warnings reach the report (summary.json `warnings`)
    let loud = short(&MINIMAL.replace("pga = 0.3", "pga = 3.5"), 0.5);
    let r = simulate_streaming(&loud, false, &mut NoSink).unwrap();
    assert!(r.warnings.iter().any(|w| w.contains("3.500 g")));
}

/// `pounding run` given a sweep file says so and how to run it.
#[test]
fn run_given_a_sweep_file_says_how_to_run_it() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = format!("{}/examples/quick-sweep.toml", env!("CARGO_MANIFEST_DIR"));
    let out = pounding(&["run", &sweep, "--out", "res"], dir.path());
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    for needle in ["is a sweep file", "pounding sweep", "--case N"] {
        assert!(err.contains(needle), "`{needle}` missing in: {err}");
    }
    assert!(!dir.path().join("res").exists());
}

/// A case printed with `--case N` has its own title naming its values, not the base
/// scenario's (whose title names the values of the base).
#[test]
fn sweep_case_has_its_own_title() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = format!("{}/examples/quick-sweep.toml", env!("CARGO_MANIFEST_DIR"));
    let out = pounding(&["sweep", &sweep, "--case", "1"], dir.path());
    assert!(out.status.success(), "{}", text(&out.stderr));
    let case = text(&out.stdout);
    let title = case
        .lines()
        .find(|l| l.starts_with("title"))
        .expect("a title line");
    assert!(
        title.contains("case 1 of sweep quick-sweep.toml"),
        "{title}"
    );
    let sw = pounding::study::sweep::Sweep::from_file(Path::new(&sweep)).unwrap();
    assert!(
        title.contains(&sw.label(1)),
        "{title} lacks {}",
        sw.label(1)
    );
    assert!(!title.contains("Paper case"), "{title}");
}

/// `-q` works for every command: nothing on stdout for the commands whose output is files
/// (merge, plot, run); convergence prints no progress.
#[test]
fn quiet_works_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("min.toml"),
        format!("{MINIMAL}\n[solver]\nduration = 1.0\n"),
    )
    .unwrap();
    let out = pounding(
        &[
            "-q",
            "run",
            "min.toml",
            "--out",
            "res",
            "--no-plot",
            "--no-check",
        ],
        dir.path(),
    );
    assert!(
        out.status.success() && out.stdout.is_empty(),
        "{}",
        text(&out.stdout)
    );
    let out = pounding(&["convergence", "min.toml", "-q"], dir.path());
    assert!(out.status.code().is_some());
    assert!(
        !text(&out.stderr).contains("running"),
        "{}",
        text(&out.stderr)
    );
    assert!(
        text(&out.stdout).contains("modes"),
        "the table is still printed"
    );
    for args in [
        &["modes", "min.toml", "-q"][..],
        &["separation", "min.toml", "--quiet"][..],
    ] {
        let out = pounding(args, dir.path());
        assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
    }
}

/// A sweep of 10⁹ cases is refused before anything runs, saying how large it is and how to
/// proceed.
#[test]
fn an_absurd_sweep_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("min.toml"), MINIMAL).unwrap();
    std::fs::write(
        dir.path().join("big.toml"),
        "scenario = \"min.toml\"\n[[axis]]\nkey = \"ground_motion.pga\"\nfrom = 0.1\nto = 0.9\nsteps = 1000\n\
         [[axis]]\nkey = \"contact.gap\"\nfrom = 0.0\nto = 0.1\nsteps = 1000\n\
         [[axis]]\nkey = \"period_ratio\"\nfrom = 0.2\nto = 1.0\nsteps = 1000\n",
    )
    .unwrap();
    let out = pounding(&["sweep", "big.toml", "--out", "res"], dir.path());
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(err.contains("1000000000") && err.contains("cases"), "{err}");
    assert!(
        !dir.path().join("res").exists(),
        "an absurd sweep wrote something"
    );
    // 10⁴ cases over two axes: 26 columns × 32 bytes × 10⁴ ≈ 8.3 MB, within the limit;
    // at --max-output-size 1MB it is refused, naming the flag
    std::fs::write(
        dir.path().join("mid.toml"),
        "scenario = \"min.toml\"\n[[axis]]\nkey = \"ground_motion.pga\"\nfrom = 0.1\nto = 0.9\nsteps = 100\n\
         [[axis]]\nkey = \"contact.gap\"\nfrom = 0.0\nto = 0.1\nsteps = 100\n",
    )
    .unwrap();
    let out = pounding(
        &[
            "sweep",
            "mid.toml",
            "--out",
            "res",
            "--max-output-size",
            "1MB",
        ],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    for needle in ["10000 cases", "8.3 MB", "--max-output-size 8.4MB"] {
        assert!(err.contains(needle), "`{needle}` missing in: {err}");
    }
}

/// The README's Quick start shows what `pounding run` (no arguments: the bundled default)
/// prints today, line for line, and the bundled default is a clean, converged result: nothing
/// on standard error (no warning), the self-check converged. It runs from any directory (the
/// default's record is embedded). If this fails after a change of the solver or of the
/// summary, run the command and paste its output into the README.
#[test]
fn readme_quick_start_is_what_the_default_prints() {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let after = readme
        .split("The first prints:\n\n```\n")
        .nth(1)
        .expect("the README's Quick start shows the first command's output");
    let shown = &after[..after.find("```").unwrap()];
    let dir = tempfile::tempdir().unwrap();
    let out = pounding(&["run"], dir.path());
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        out.stderr.is_empty(),
        "the bundled default warns:\n{}",
        text(&out.stderr)
    );
    let printed = text(&out.stdout);
    assert!(printed.contains("self-check: converged"), "{printed}");
    for (k, (a, b)) in shown.lines().zip(printed.lines()).enumerate() {
        // The energy balance's residual is round-off (~1e-14): its digits move with any change
        // of the order of floating-point operations anywhere in the run, so the README shows
        // it and the test checks that both shown and printed values are round-off, not equal.
        if let (Some(x), Some(y)) = (energy_errors(a), energy_errors(b)) {
            for v in x.into_iter().chain(y) {
                assert!(v < 1e-11, "README Quick start, line {}: {b}", k + 1);
            }
            continue;
        }
        assert_eq!(a, b, "README Quick start, line {} of the output", k + 1);
    }
    assert_eq!(shown.lines().count(), printed.lines().count(), "{printed}");
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(summary["accuracy"]["converged"], true);
    assert_eq!(summary["warnings"].as_array().unwrap().len(), 0);
}

/// `pounding --help` names every kind of structure; `run --help` names every file a run writes
/// (taken from what runs actually write: an elastic and a yielding one) and `--no-plot` speaks
/// of the pictures, not "the figure".
#[test]
fn help_covers_every_kind_and_every_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = pounding(&["--help"], dir.path());
    let help = text(&out.stdout);
    for needle in [
        "cantilever",
        "shear-building",
        "modal",
        "yielding",
        "Bouc–Wen",
        "record",
        "harmonic",
        "floor",
    ] {
        assert!(
            help.contains(needle),
            "`pounding --help` lacks {needle}:\n{help}"
        );
    }
    let run_help = text(&pounding(&["run", "--help"], dir.path()).stdout);
    assert!(run_help.contains("--no-plot"), "{run_help}");
    assert!(!run_help.contains("the figure"), "{run_help}");
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let yielding = std::fs::read_to_string(examples.join("yielding-frames.toml"))
        .unwrap()
        .replace("duration = 45.0", "duration = 3.0")
        .replace("records/", &format!("{}/records/", examples.display()));
    std::fs::write(dir.path().join("y.toml"), yielding).unwrap();
    let mut files = std::collections::BTreeSet::new();
    for args in [
        &["run", "--out", "a", "--no-check"][..],
        &["run", "y.toml", "--out", "b", "--no-check"][..],
    ] {
        let out = pounding(args, dir.path());
        assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
        let wrote = text(&out.stdout);
        let list = wrote
            .lines()
            .find_map(|l| l.strip_prefix("wrote "))
            .unwrap_or_else(|| panic!("{wrote}"));
        for f in list.split(", ") {
            files.insert(
                Path::new(f)
                    .file_name()
                    .unwrap()
                    .to_string_lossy()
                    .to_string(),
            );
        }
    }
    assert!(
        files.contains("hysteresis.png") && files.contains("floors.csv"),
        "{files:?}"
    );
    for f in &files {
        // "history.png/.svg" names both pictures
        let (stem, ext) = f.rsplit_once('.').unwrap();
        let named = run_help.contains(f.as_str())
            || (ext == "svg" && run_help.contains(&format!("{stem}.png/.svg")));
        assert!(
            named,
            "`pounding run --help` does not list {f}:\n{run_help}"
        );
    }
}

/// The peak absolute floor acceleration of the paper's case c (≈ 55 g at the top, during
/// impacts) is printed with what it is: the line of each structure gives the value of
/// summary.json, in g too, where and when, and the duration of the impact it fell in.
#[test]
fn the_acceleration_pulse_is_named_in_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let paper = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/paper-c.toml");
    let out = pounding(
        &[
            "run",
            paper.to_str().unwrap(),
            "--out",
            "res",
            "--no-check",
            "--no-plot",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let printed = text(&out.stdout);
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("res/summary.json")).unwrap(),
    )
    .unwrap();
    assert!(printed.contains("the impact's pulse"), "{printed}");
    for (i, s) in summary["structures"].as_array().unwrap().iter().enumerate() {
        let floors = s["floors"].as_array().unwrap();
        let top = floors
            .iter()
            .max_by(|a, b| {
                let f = |x: &serde_json::Value| x["peak_acceleration"].as_f64().unwrap();
                f(a).total_cmp(&f(b))
            })
            .unwrap();
        let a = top["peak_acceleration"].as_f64().unwrap();
        // the paper's case: tens of g at the top, inside an impact of some milliseconds
        assert!(a > 20.0 * 9.80665, "structure {}: {a} m/s²", i + 1);
        let pulse = &top["peak_acceleration_impact"];
        let duration = pulse["duration"].as_f64().expect("inside an impact");
        assert!(duration > 1e-3 && duration < 0.2, "{duration} s");
        let line = format!(
            "    structure {}: {a:.2} m/s² ({:.2} g) at h = {} m, t = {:.3} s: the pulse of an impact at h = {} m lasting {:.1} ms",
            i + 1,
            a / 9.80665,
            top["height"].as_f64().unwrap(),
            top["peak_acceleration_time"].as_f64().unwrap(),
            pulse["height"].as_f64().unwrap(),
            duration * 1e3,
        );
        assert!(printed.contains(&line), "{line}\n{printed}");
    }
}

/// The two numbers of the summary's "energy balance error: A with contact, B without" line.
fn energy_errors(line: &str) -> Option<[f64; 2]> {
    let rest = line.trim().strip_prefix("energy balance error: ")?;
    let (a, rest) = rest.split_once(" with contact, ")?;
    let b = rest.strip_suffix(" without")?;
    Some([a.parse().ok()?, b.parse().ok()?])
}
