//! The files of `pounding run`: every output with the permissions an ordinary new file gets
//! under the user's umask, and the CSV numbers written back exactly.

use std::path::Path;
use std::process::Command;

/// A short paper-case scenario (exact-modal, 2 s): impacts, two figures, every file.
fn scenario(dir: &Path) -> std::path::PathBuf {
    let text = std::fs::read_to_string(format!(
        "{}/examples/paper-c.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .replace("method = \"rk4\"", "method = \"exact-modal\"")
    .replace("dt = 0.001", "dt = 0.01")
    .replace("duration = 20.0", "duration = 2.0");
    let path = dir.join("short.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// Under umask 027 and then 002, every file `pounding run` writes (CSV files, pictures,
/// summary.json) has exactly the mode of a file the shell creates under the same umask
/// (`: > ref`, i.e. 0666 & !umask, what `File::create` gives): no output is owner-only (the
/// temporary files they are renamed from are 0600 by default) and none ignores the umask.
#[cfg(unix)]
#[test]
fn every_output_has_the_permissions_of_an_ordinary_new_file() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let path = scenario(dir.path());
    for umask in ["027", "002"] {
        let out = dir.path().join(format!("out-{umask}"));
        let reference = dir.path().join(format!("ref-{umask}"));
        let status = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "umask {umask} && : > \"$3\" && exec \"$0\" run \"$1\" --out \"$2\" -q --no-check"
            ))
            .arg(env!("CARGO_BIN_EXE_pounding"))
            .arg(&path)
            .arg(&out)
            .arg(&reference)
            .status()
            .unwrap();
        assert!(status.success());
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        let want = mode(&reference);
        let expected = 0o666 & !u32::from_str_radix(umask, 8).unwrap();
        assert_eq!(want, expected, "the shell's new file under umask {umask}");
        let mut names: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        for f in [
            "envelopes.png",
            "envelopes.svg",
            "floors.csv",
            "history.csv",
            "history.png",
            "history.svg",
            "impacts.csv",
            "summary.json",
        ] {
            assert!(names.iter().any(|n| n == f), "{f} missing: {names:?}");
        }
        for n in &names {
            assert_eq!(
                mode(&out.join(n)),
                want,
                "{n} under umask {umask}: {:o}, a new file gets {want:o}",
                mode(&out.join(n))
            );
        }
    }
}

/// Every number of history.csv and floors.csv reads back as the very `f64` the library holds:
/// history.csv against `output::history_csv`'s source (the report's in-memory history, every
/// sample of this short run), parsed as numbers, bit for bit.
#[test]
fn csv_numbers_read_back_exactly() {
    use pounding::scenario::Scenario;
    let dir = tempfile::tempdir().unwrap();
    let path = scenario(dir.path());
    let (sc, _) = Scenario::read_file(&path).unwrap();
    let report = pounding::simulate::simulate_checked(&sc, false).unwrap();
    let out = dir.path().join("out");
    let status = Command::new(env!("CARGO_BIN_EXE_pounding"))
        .args(["run", path.to_str().unwrap(), "--out"])
        .arg(&out)
        .args(["-q", "--no-check", "--no-plot"])
        .status()
        .unwrap();
    assert!(status.success());
    let text = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let h = &report.with_contact.history;
    let f = &report.without_contact.history;
    assert_eq!(h.stride, 1);
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), h.t.len());
    for (i, r) in rows.iter().enumerate() {
        let want = [h.t[i], h.w1[i], h.w2[i], h.force[0][i], f.w1[i], f.w2[i]];
        for (got, want) in r.iter().zip(want) {
            assert_eq!(got.to_bits(), want.to_bits(), "row {i}: {r:?}");
        }
    }
    // floors.csv: every field a number, the same count on every line
    let floors = std::fs::read_to_string(out.join("floors.csv")).unwrap();
    let width = floors.lines().next().unwrap().split(',').count();
    for l in floors.lines().skip(1) {
        let fields: Vec<&str> = l.split(',').collect();
        assert_eq!(fields.len(), width);
        assert!(fields.iter().all(|x| x.parse::<f64>().is_ok()), "{l}");
    }
}
