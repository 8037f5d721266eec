//! `pounding run`'s self-check beside the run (`simulate_streaming_beside`): every file of the
//! run — the CSVs and pictures written while the check goes on, summary.json after it — is byte
//! for byte the file the same run writes with the check after it, on one thread.

use std::path::Path;

use pounding::analysis::simulate::{Report, simulate_streaming_beside};
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

/// Touching with the result's run without contact taken (`exact-modal`), never touching (the
/// result its own check), and a check that integrates its own run without contact (`rk4`).
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
        let names = |f: &[(String, Vec<u8>)]| f.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
        assert_eq!(names(&a), names(&b));
        assert!(
            names(&a).iter().any(|n| n == "history.png"),
            "{:?}",
            names(&a)
        );
        for ((name, x), (_, y)) in a.iter().zip(&b) {
            // (summary.json holds no timing: the whole file is compared)
            assert!(x == y, "{}: {name} differs", sc.title);
        }
    }
}
