//! The binary end to end: outputs per docs/model.md §6, exit codes, and no partial output on failure.

use std::process::Command;

mod common;
use common::pounding;

fn example(name: &str) -> String {
    format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn run_default_writes_the_contract() {
    let dir = tempfile::tempdir().unwrap();
    let out = pounding(&["run", "--out", "res"], dir.path());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    for needle in [
        "examples/default.toml (bundled default)",
        "change [%]",
        "impacts",
        "required separation",
        "SRSS",
    ] {
        assert!(stdout.contains(needle), "summary lacks {needle}:\n{stdout}");
    }
    let res = dir.path().join("res");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(res.join("summary.json")).unwrap()).unwrap();
    for i in 0..2 {
        let s = &summary["structures"][i];
        for key in [
            "name",
            "periods",
            "peak_displacement",
            "peak_displacement_no_contact",
            "change_percent",
        ] {
            assert!(!s[key].is_null(), "structures[{i}].{key} missing");
        }
        let (w, w0) = (
            s["peak_displacement"].as_f64().unwrap(),
            s["peak_displacement_no_contact"].as_f64().unwrap(),
        );
        let change = s["change_percent"].as_f64().unwrap();
        assert!((change - 100.0 * (w - w0) / w0).abs() < 1e-9 * change.abs().max(1.0));
    }
    for key in ["peak_force", "max_penetration", "impacts", "contact_time"] {
        assert!(!summary["contact"][key].is_null(), "contact.{key} missing");
    }
    for key in ["abs", "srss", "ddc", "time_history"] {
        assert!(
            summary["separation"][key].as_f64().unwrap() > 0.0,
            "separation.{key}"
        );
    }
    let history = std::fs::read_to_string(res.join("history.csv")).unwrap();
    let mut lines = history.lines();
    assert!(lines.next().unwrap().starts_with("t,w1,w2,force"));
    // the default's 25 s every 0.01 s, both ends included
    assert_eq!(lines.clone().count(), 2501);
    let last: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert!((last[0] - 25.0).abs() < 1e-9);
    for f in [
        "history.png",
        "history.svg",
        "impacts.csv",
        "floors.csv",
        "envelopes.png",
        "envelopes.svg",
    ] {
        assert!(res.join(f).exists(), "{f} missing");
    }
    // no temporary files left behind
    for e in std::fs::read_dir(&res).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().to_string();
        assert!(!name.starts_with('.'), "leftover {name}");
    }
}

#[test]
fn bad_scenario_fails_cleanly_without_output() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("paper-c.toml"))
        .unwrap()
        .replacen("\nmass = 2.273e6", "\nmass = -1.0", 1);
    std::fs::write(dir.path().join("bad.toml"), text).unwrap();
    let out = pounding(&["run", "bad.toml", "--out", "res"], dir.path());
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml:") && err.contains("structure[1].mass") && err.contains("> 0"),
        "{err}"
    );
    assert!(
        !dir.path().join("res").exists(),
        "no output directory for a refused scenario"
    );
}

/// Issue 9's stiff case (k_h = 2.808e13 N/m^1.5, T1 = 0.3 s, T2 = 0.6 s, 0.5 g at Tg = 0.8 s) as
/// a scenario file.
fn stiff_scenario(method: &str, dt: f64) -> String {
    std::fs::read_to_string(example("paper-c.toml"))
        .unwrap()
        .replacen("period = 0.4203", "period = 0.3", 1)
        .replacen("period = 0.6004285714285714", "period = 0.6", 1)
        .replacen("\nstiffness = 2.808e10", "\nstiffness = 2.808e13", 1)
        .replacen("pga = 0.6\nperiod = 0.65", "pga = 0.5\nperiod = 0.8", 1)
        .replacen("method = \"rk4\"", &format!("method = \"{method}\""), 1)
        .replacen("dt = 0.001", &format!("dt = {dt:?}"), 1)
        .replacen("duration = 20.0", "duration = 6.0", 1)
}

/// A contact that makes RK4's step unstable (its first impact has ω_c·dt ≈ 3.0 > 2√2 at 1 ms:
/// see `tests/integrators.rs`) is refused: exit status non-zero, the reason and a smaller step
/// on stderr, and no output written — not even the directory. The same contact is also too
/// stiff for the step once the paper's case pounds with k_h = 1e17 (formerly a divergence).
#[test]
fn too_stiff_contact_is_refused_without_output() {
    let dir = tempfile::tempdir().unwrap();
    let paper = std::fs::read_to_string(example("paper-c.toml"))
        .unwrap()
        .replacen("\nstiffness = 2.808e10", "\nstiffness = 1e17", 1);
    for (name, text) in [
        ("stiff.toml", stiff_scenario("rk4", 1e-3)),
        ("very-stiff.toml", paper),
    ] {
        std::fs::write(dir.path().join(name), text).unwrap();
        let out = pounding(&["run", name, "--out", "res"], dir.path());
        assert_eq!(out.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("rk4 refused at t = ")
                && err.contains("contact level 1")
                && err.contains("stability limit 2.8")
                && err.contains("Largest stable step, estimated: dt ≈ ")
                && err.contains("Reduce solver.dt"),
            "{name}: {err}"
        );
        assert!(out.stdout.is_empty(), "{name}: no summary printed");
        assert!(
            !dir.path().join("res").exists(),
            "{name}: no output directory for a refused run"
        );
    }
    // the methods whose steps follow the contact run the same case and write the contract
    std::fs::write(
        dir.path().join("em.toml"),
        stiff_scenario("exact-modal", 1e-3),
    )
    .unwrap();
    let out = pounding(&["run", "em.toml", "--out", "res", "--no-plot"], dir.path());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.path().join("res").join("summary.json").exists());
}

#[test]
fn missing_file_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = pounding(&["run", "nope.toml"], dir.path());
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("nope.toml"));
}

#[test]
fn modes_lists_periods() {
    let dir = tempfile::tempdir().unwrap();
    let out = pounding(&["modes", &example("paper-c.toml")], dir.path());
    assert!(out.status.success());
    let s = String::from_utf8_lossy(&out.stdout);
    assert!(s.contains("0.420300") && s.contains("0.600429"), "{s}");
    // first-mode effective mass of a cantilever: 4σ₁²/λ₁² = 61.3 %
    assert!(s.contains("61.3"), "{s}");
}

#[test]
fn separation_lists_every_rule() {
    let dir = tempfile::tempdir().unwrap();
    let out = pounding(&["separation", &example("paper-c.toml")], dir.path());
    assert!(out.status.success());
    let s = String::from_utf8_lossy(&out.stdout);
    for rule in ["time history", "ABS", "SRSS", "DDC", "ddc-paper"] {
        assert!(s.contains(rule), "{rule} missing:\n{s}");
    }
}

#[test]
fn help_explains_each_command() {
    let dir = tempfile::tempdir().unwrap();
    for cmd in ["run", "modes", "separation"] {
        let out = pounding(&[cmd, "--help"], dir.path());
        assert!(out.status.success());
        assert!(String::from_utf8_lossy(&out.stdout).contains("SCENARIO"));
    }
}

/// Output piped into a reader that stops early (`pounding laws | head -1`) ends the program
/// quietly instead of panicking on the closed pipe.
#[test]
fn closed_stdout_does_not_panic() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_pounding"))
        .arg("laws")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(first.contains("target e"));
    // the reader is dropped here: later writes hit a closed pipe
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
}

/// `pounding convergence` on the stiff case says prominently that it did not converge, shows
/// the refused RK4 steps as failed, and recommends nothing. (The finest RK4 step of the ladder,
/// 0.125 ms, gives a peak force ~20 % above the converged 4.36e8 N: see tests/convergence.rs.)
#[test]
fn convergence_says_not_converged() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("stiff.toml"), stiff_scenario("rk4", 1e-3)).unwrap();
    let out = pounding(&["convergence", "stiff.toml"], dir.path());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("*** NOT CONVERGED within 1 %: nothing is recommended ***"),
        "{stdout}"
    );
    assert!(stdout.contains("FAILED: rk4 refused at t = "), "{stdout}");
    assert!(stdout.contains("try: a smaller solver.dt"), "{stdout}");
    assert!(!stdout.contains("recommendation ("), "{stdout}");
}
