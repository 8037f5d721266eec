//! `pounding run`'s self-check beside the run (`simulate_streaming_beside`, a row's
//! `simulate_row_streaming_beside`): every file of the run — the CSVs and pictures written
//! while the check goes on, summary.json after it — is byte for byte the file the same run
//! writes with the check after it, on one thread.

use std::path::Path;

use pounding::analysis::simulate::{
    Report, RowReport, simulate_row_streaming_beside, simulate_streaming_beside,
};
use pounding::input::scenario::Scenario;
use pounding::output::writer::RunWriter;

/// The paper's two cantilevers (3 modes each) under harmonic motion, 2 s.
fn cantilevers(method: &str, dt: f64, gap: f64, pga: f64) -> Scenario {
    let text = format!(
        "title = \"beside\"\n\
         [[structure]]\nname = \"a\"\nlength = 10.0\nmass = 2.273e6\nperiod = 0.4203\nmodes = 3\ndamping_ratio = 0.01\n\
         [[structure]]\nname = \"b\"\nlength = 10.0\nmass = 2.273e6\nperiod = 0.6004285714285714\nmodes = 3\ndamping_ratio = 0.01\n\
         [contact]\nlaw = \"hertz\"\nstiffness = 2.808e10\ngap = {gap}\n\
         [ground_motion]\nkind = \"harmonic\"\npga = {pga}\nperiod = 0.65\n\
         [solver]\nmethod = \"{method}\"\ndt = {dt}\nduration = 2.0\noutput_interval = 0.01\n"
    );
    Scenario::from_toml(&text, "beside.toml", Path::new(env!("CARGO_MANIFEST_DIR")))
        .expect("valid scenario")
}

/// Every file of a run written as `pounding run` writes it (the files beside the check,
/// summary.json last), into a fresh directory; their names and bytes.
fn files(sc: &Scenario, concurrent: bool, dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut writer = RunWriter::for_scenario(dir, sc).expect("a writer");
    let beside = |w: &mut RunWriter, r: &Report| {
        let draw = pounding::figures::run::run_pictures(sc, r);
        w.finish_files(r, Some(draw))
    };
    let (report, written) =
        simulate_streaming_beside(sc, true, &mut writer, concurrent, beside).expect("runs");
    let written = writer
        .finish_summary(sc, &report, written.expect("files"))
        .expect("summary");
    assert!(written.last().is_some_and(|p| p.ends_with("summary.json")));
    listed(dir)
}

/// Every file of a row's run written as `pounding run` writes it, into a fresh directory.
fn row_files(sc: &Scenario, concurrent: bool, dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut writer = RunWriter::for_scenario(dir, sc).expect("a writer");
    let beside = |w: &mut RunWriter, r: &RowReport| {
        let draw = pounding::figures::row::row_pictures(sc, r);
        w.finish_files(r, Some(draw))
    };
    let (report, written) =
        simulate_row_streaming_beside(sc, true, &mut writer, concurrent, beside).expect("runs");
    let written = writer
        .finish_summary(sc, &report, written.expect("files"))
        .expect("summary");
    assert!(written.last().is_some_and(|p| p.ends_with("summary.json")));
    listed(dir)
}

/// The names and bytes of the files in `dir`, by name.
fn listed(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out: Vec<_> = std::fs::read_dir(dir)
        .expect("the run's directory")
        .map(|e| {
            let p = e.expect("an entry").path();
            let name = p
                .file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned();
            (name, std::fs::read(&p).expect("a file"))
        })
        .collect();
    out.sort();
    out
}

/// Asserts two runs' files the same, byte for byte, pictures among them.
fn assert_same(a: &[(String, Vec<u8>)], b: &[(String, Vec<u8>)], what: &str) {
    let names = |f: &[(String, Vec<u8>)]| f.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(a), names(b));
    assert!(
        names(a).iter().any(|n| n == "history.png"),
        "{:?}",
        names(a)
    );
    for ((name, x), (_, y)) in a.iter().zip(b) {
        // (summary.json holds no timing: the whole file is compared)
        assert!(x == y, "{what}: {name} differs");
    }
}

/// Touching with the result's run without contact taken (`exact-modal`), never touching (the
/// result its own check), and a check that integrates its own run without contact (`rk4`: on
/// a third thread beside its run with contact).
#[test]
fn every_file_is_byte_identical_with_the_check_beside_the_run() {
    let tmp = tempfile::tempdir().expect("a temporary directory");
    let cases = [
        cantilevers("exact-modal", 0.01, 0.0127, 0.6),
        cantilevers("exact-modal", 0.01, 0.5, 0.3),
        cantilevers("rk4", 0.001, 0.0127, 0.6),
    ];
    for (i, sc) in cases.iter().enumerate() {
        let a = files(sc, true, &tmp.path().join(format!("concurrent-{i}")));
        let b = files(sc, false, &tmp.path().join(format!("sequential-{i}")));
        assert_same(&a, &b, &sc.title);
    }
}

/// A row of three shear buildings (the middle one yielding when `yielding`), 2 s of harmonic
/// motion, both gaps closing.
fn row(method: &str, dt: f64, yielding: bool) -> Scenario {
    let building = |name: &str, n: usize, k: f64, extra: &str| {
        format!(
            "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
             storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\n\
             damping_ratio = 0.05\n{extra}\n"
        )
    };
    let contact = |a: &str, b: &str| {
        format!(
            "[[contact]]\nbetween = [\"{a}\", \"{b}\"]\nlaw = \"hertz\"\nstiffness = 2.0e10\n\
             height = 7.0\ngap = 0.01\n"
        )
    };
    let hysteresis = if yielding {
        "hysteresis = { model = \"bouc-wen\", yield_drifts = 0.0175, post_yield_ratio = 0.05 }"
    } else {
        ""
    };
    let text = format!(
        "title = \"row beside\"\n{}{}{}{}{}\
         [ground_motion]\nkind = \"harmonic\"\npga = 0.35\nperiod = 0.8\n\
         [solver]\nmethod = \"{method}\"\ndt = {dt}\nduration = 2.0\noutput_interval = 0.01\n",
        building("A", 3, 3.0e8, ""),
        building("B", 4, 1.2e8, hysteresis),
        building("C", 2, 2.0e8, ""),
        contact("A", "B"),
        contact("B", "C"),
    );
    Scenario::from_toml(&text, "row.toml", Path::new(env!("CARGO_MANIFEST_DIR")))
        .expect("valid scenario")
}

/// A row: the check's run without contact the result's (`exact-modal`), or its own on a third
/// thread beside its run with contact (`rk4`, yielding storeys under `adaptive`).
#[test]
fn every_file_of_a_row_is_byte_identical_with_the_check_beside_the_run() {
    let tmp = tempfile::tempdir().expect("a temporary directory");
    let cases = [
        row("exact-modal", 0.01, false),
        row("rk4", 0.002, false),
        row("adaptive", 0.01, true),
    ];
    for (i, sc) in cases.iter().enumerate() {
        let a = row_files(sc, true, &tmp.path().join(format!("concurrent-{i}")));
        let b = row_files(sc, false, &tmp.path().join(format!("sequential-{i}")));
        assert_same(&a, &b, &format!("row {i}"));
    }
}
