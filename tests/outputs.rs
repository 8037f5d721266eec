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

/// `pounding run SCENARIO --out OUT -q --no-check --no-plot`, which must succeed.
fn run_quietly(scenario: &Path, out: &Path) {
    let run = Command::new(env!("CARGO_BIN_EXE_pounding"))
        .args(["run", scenario.to_str().unwrap(), "--out"])
        .arg(out)
        .args(["-q", "--no-check", "--no-plot"])
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
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
            .output()
            .unwrap();
        assert!(
            status.status.success(),
            "{}",
            String::from_utf8_lossy(&status.stderr)
        );
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
    use pounding::input::scenario::Scenario;
    let dir = tempfile::tempdir().unwrap();
    let path = scenario(dir.path());
    let (sc, _) = Scenario::read_file(&path).unwrap();
    let report = pounding::analysis::simulate::simulate_checked(&sc, false).unwrap();
    let out = dir.path().join("out");
    let status = Command::new(env!("CARGO_BIN_EXE_pounding"))
        .args(["run", path.to_str().unwrap(), "--out"])
        .arg(&out)
        .args(["-q", "--no-check", "--no-plot"])
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
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

/// `floors.csv` of a cantilever holds by default the stations at the contact heights and at
/// its top (`[output] floor_stations = "contact"`), with the names and numbers of the full
/// file (`floor_stations = "all"`: every tenth of the height too), while summary.json's
/// envelopes cover every station either way. The displacement at the contact height equals
/// history.csv's w1/w2 (the same interpolation of the same steps, to 1e-12 of the peak: two
/// projections of the modal state, summed in another order), and each acceleration column
/// reaches the peak absolute acceleration of summary.json at that height.
#[test]
fn floors_csv_keeps_the_contact_stations_by_default() {
    use pounding::input::scenario::Scenario;
    let dir = tempfile::tempdir().unwrap();
    let path = scenario(dir.path());
    let all_path = dir.path().join("all.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(
        &all_path,
        format!("{text}\n[output]\nfloor_stations = \"all\"\n"),
    )
    .unwrap();
    let run = |p: &Path, out: &str| {
        let out = dir.path().join(out);
        run_quietly(p, &out);
        let read = |name: &str| -> (Vec<String>, Vec<Vec<f64>>) {
            let text = std::fs::read_to_string(out.join(name)).unwrap();
            let mut lines = text.lines();
            let head = lines.next().unwrap().split(',').map(String::from).collect();
            let rows = lines
                .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
                .collect();
            (head, rows)
        };
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        (read("floors.csv"), read("history.csv"), summary)
    };
    let ((head, rows), (hh, history), summary) = run(&path, "contact");
    let names = ["w1_10", "a1_10", "w2_10", "a2_10"];
    let mut want = vec!["t".to_string()];
    want.extend(names.iter().map(|n| n.to_string()));
    want.extend(names.iter().map(|n| format!("{n}_free")));
    assert_eq!(head, want);
    let ((all_head, all_rows), _, all_summary) = run(&all_path, "all");
    assert_eq!(
        all_head.len(),
        1 + 2 * 2 * 2 * 10,
        "10 stations a structure"
    );
    // the same numbers under the same names
    assert_eq!(rows.len(), all_rows.len());
    for (j, name) in head.iter().enumerate() {
        let k = all_head.iter().position(|c| c == name).unwrap();
        for (r, a) in rows.iter().zip(&all_rows) {
            assert_eq!(r[j].to_bits(), a[k].to_bits(), "{name}");
        }
    }
    // every station's envelope in summary.json either way
    for s in 0..2 {
        let floors = |v: &serde_json::Value| v["structures"][s]["floors"].clone();
        assert_eq!(floors(&summary).as_array().unwrap().len(), 10);
        assert_eq!(floors(&summary), floors(&all_summary));
    }
    // the contact height's displacement is history.csv's, its acceleration peaks as reported
    let col = |h: &[String], n: &str| h.iter().position(|c| c == n).unwrap();
    for (i, (u, w)) in [("w1_10", "w1"), ("w2_10", "w2")].into_iter().enumerate() {
        let scale = summary["structures"][i]["peak_displacement"]
            .as_f64()
            .unwrap();
        let (u, w) = (col(&head, u), col(&hh, w));
        for (f, h) in rows.iter().zip(&history) {
            assert_eq!(f[0], h[0]);
            assert!((f[u] - h[w]).abs() <= 1e-12 * scale, "t = {}", f[0]);
        }
        let top = &summary["structures"][i]["floors"][9];
        assert_eq!(top["height"].as_f64(), Some(10.0));
        let a = col(&head, &format!("a{}_10", i + 1));
        let peak = rows.iter().map(|r| r[a].abs()).fold(0.0, f64::max);
        assert_eq!(Some(peak), top["peak_acceleration"].as_f64());
    }
    // two contact levels, structures of 10 m and 16 m: the levels and each top
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let (sc, _) = Scenario::read_file(&examples.join("two-levels.toml")).unwrap();
    let cols = pounding::output::run::floor_columns(&sc);
    let want: Vec<&str> = vec![
        "w1_6", "a1_6", "w1_10", "a1_10", "w2_6", "a2_6", "w2_10", "a2_10", "w2_16", "a2_16",
    ];
    assert_eq!(cols, want);
    // a building with floors: every floor, whatever the choice
    let (sc, _) = Scenario::read_file(&examples.join("shear-buildings.toml")).unwrap();
    let floors: usize = sc
        .structures
        .iter()
        .map(|s| s.floor_heights().unwrap().len())
        .sum();
    assert_eq!(pounding::output::run::floor_columns(&sc).len(), 2 * floors);
}

/// summary.json's `solver` section records the tolerances a run read: `rtol` and `atol` for
/// `exact-modal` (its contact steps) and `adaptive`, as the scenario gave them (or their
/// defaults), and none for `rk4`, which reads none.
#[test]
fn summary_records_the_tolerances_of_the_methods_that_read_them() {
    let dir = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(scenario(dir.path())).unwrap();
    for (method, dt, tols) in [
        ("exact-modal", "0.01", Some((3e-7, 2e-9))),
        ("adaptive", "0.01", Some((4e-9, 5e-11))),
        ("rk4", "0.001", None),
    ] {
        let mut text = base
            .replace(
                "method = \"exact-modal\"",
                &format!("method = \"{method}\""),
            )
            .replace("dt = 0.01", &format!("dt = {dt}"))
            .replace("duration = 2.0", "duration = 0.3");
        if let Some((r, a)) = tols {
            text = text.replace("[solver]", &format!("[solver]\nrtol = {r:e}\natol = {a:e}"));
        }
        let path = dir.path().join(format!("{method}.toml"));
        std::fs::write(&path, text).unwrap();
        let out = dir.path().join(method);
        run_quietly(&path, &out);
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let solver = &summary["solver"];
        assert_eq!(solver["method"], method);
        match tols {
            Some((r, a)) => {
                assert_eq!(solver["rtol"].as_f64(), Some(r), "{method}: {solver}");
                assert_eq!(solver["atol"].as_f64(), Some(a), "{method}: {solver}");
            }
            None => {
                assert!(solver.get("rtol").is_none(), "{method}: {solver}");
                assert!(solver.get("atol").is_none(), "{method}: {solver}");
            }
        }
    }
}
