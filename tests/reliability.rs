//! Issue 15, README *Reliability*: what a wrong path or a killed run cannot do — the binary
//! reading a FIFO or a device as a record (refused at once, not blocking or eating memory), a
//! record over the size limit refused before it is read, and a `pounding run` killed with
//! SIGKILL mid-run leaving no summary.json and no partial history.csv under its name.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use pounding::model::ground_motion::record::{
    MAX_RECORD_BYTES, Record, RecordError, RecordOptions,
};

const BIN: &str = env!("CARGO_BIN_EXE_pounding");

/// Runs the binary with a deadline: a run that blocks (a FIFO opened for reading) is killed
/// and reported, instead of hanging the test suite.
fn run_within(args: &[&str], cwd: &Path, limit: Duration) -> Output {
    let mut child = Command::new(BIN)
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > limit {
            child.kill().unwrap();
            panic!(
                "`pounding {}` still running after {limit:?}",
                args.join(" ")
            );
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    child.wait_with_output().unwrap()
}

fn scenario_with_record(file: &str) -> String {
    include_str!("../examples/loma-prieta.toml")
        .replace("records/RSN753_LOMAP_CLS000.AT2", file)
        .replace("method = \"rk4\"", "method = \"adaptive\"")
}

/// A record over [`MAX_RECORD_BYTES`] is refused from its size alone: a sparse file of 600 MB
/// (no disk used) is refused at once, naming the size and the limit.
#[test]
fn a_record_over_the_limit_is_refused_before_it_is_read() {
    let d = tempfile::tempdir().unwrap();
    let big = d.path().join("big.txt");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len(600_000_000).unwrap();
    let t0 = Instant::now();
    let e = Record::read(&big, &RecordOptions::default()).unwrap_err();
    assert!(
        matches!(
            e,
            RecordError::TooLarge {
                size: 600_000_000,
                limit: MAX_RECORD_BYTES,
                ..
            }
        ),
        "{e}"
    );
    assert!(t0.elapsed() < Duration::from_secs(1), "{:?}", t0.elapsed());
    let msg = e.to_string();
    assert!(
        msg.contains("600000000") && msg.contains("500000000"),
        "{msg}"
    );
}

/// `/dev/zero` as the record of `pounding run`: refused as a device at once (it used to grow to
/// 2.1 GB before running out of memory).
#[cfg(unix)]
#[test]
fn a_device_as_record_is_refused_at_once() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("s.toml"), scenario_with_record("/dev/zero")).unwrap();
    let out = run_within(
        &["run", "s.toml", "--out", "out", "-q"],
        d.path(),
        Duration::from_secs(20),
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("/dev/zero") && err.contains("device"), "{err}");
    assert!(!d.path().join("out").join("summary.json").exists());
}

/// A FIFO as the record of `pounding run` and on a record axis of `pounding sweep`: refused at
/// once with what it is (opening it would block until a writer comes).
#[cfg(unix)]
#[test]
fn a_fifo_as_record_is_refused_by_run_and_sweep() {
    let d = tempfile::tempdir().unwrap();
    let fifo = d.path().join("pipe.AT2");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path; mkfifo only creates a file system entry.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    std::fs::write(d.path().join("s.toml"), scenario_with_record("pipe.AT2")).unwrap();
    let out = run_within(
        &["run", "s.toml", "--out", "out", "-q"],
        d.path(),
        Duration::from_secs(20),
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("pipe.AT2") && err.contains("FIFO"), "{err}");

    let records = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/records");
    std::fs::copy(
        records.join("RSN753_LOMAP_CLS000.AT2"),
        d.path().join("real.AT2"),
    )
    .unwrap();
    std::fs::write(d.path().join("s.toml"), scenario_with_record("real.AT2")).unwrap();
    std::fs::write(
        d.path().join("w.toml"),
        "scenario = \"s.toml\"\n[[axis]]\nkey = \"ground_motion.file\"\n\
         values = [\"real.AT2\", \"pipe.AT2\"]\n",
    )
    .unwrap();
    // (the identity hash skips what is not a regular file; the FIFO's case fails with the
    // reason and the sweep goes on, as any failing case does)
    let out = run_within(
        &[
            "sweep",
            "w.toml",
            "--out",
            "sw",
            "--no-plot",
            "--no-check",
            "-q",
        ],
        d.path(),
        Duration::from_secs(120),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let table = std::fs::read_to_string(d.path().join("sw/results.csv")).unwrap();
    let rows: Vec<&str> = table.lines().skip(1).collect();
    assert_eq!(rows.len(), 2, "{table}");
    assert!(rows[0].contains(",ok,"), "{}", rows[0]);
    assert!(
        rows[1].contains("failed") && rows[1].contains("pipe.AT2") && rows[1].contains("FIFO"),
        "{}",
        rows[1]
    );
}

/// `pounding run` killed with SIGKILL in the middle of its run: the stale summary.json of an
/// earlier run is gone (removed before anything is computed), and history.csv — streamed to a
/// temporary file and renamed at the end — is still the earlier run's complete file, never a
/// partial one; a rerun then writes the full set.
#[cfg(unix)]
#[test]
fn a_run_killed_mid_way_leaves_no_summary_and_no_partial_history() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("out");
    // an earlier run's outputs
    let short =
        include_str!("../examples/paper-c.toml").replace("duration = 20.0", "duration = 1.0");
    std::fs::write(d.path().join("short.toml"), &short).unwrap();
    let run_short = || {
        run_within(
            &[
                "run",
                "short.toml",
                "--out",
                "out",
                "--no-plot",
                "--no-check",
                "-q",
            ],
            d.path(),
            Duration::from_secs(60),
        )
    };
    let o = run_short();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stale_history = std::fs::read(out.join("history.csv")).unwrap();
    assert!(out.join("summary.json").exists());
    // a long run into the same directory, killed after a while
    // (2000 s of RK4 at 1 ms, with the self-check: many seconds; 200 000 rows, within budget)
    let long =
        include_str!("../examples/paper-c.toml").replace("duration = 20.0", "duration = 2000.0");
    std::fs::write(d.path().join("long.toml"), &long).unwrap();
    let mut child = Command::new(BIN)
        .args(["run", "long.toml", "--out", "out", "--no-plot", "-q"])
        .current_dir(d.path())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // wait until the summary of the earlier run is gone (the run has started), then some more
    let t0 = Instant::now();
    while out.join("summary.json").exists() && t0.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(5));
    }
    std::thread::sleep(Duration::from_millis(500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the long run ended too early to test a kill"
    );
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    assert!(
        !out.join("summary.json").exists(),
        "a killed run must leave no summary.json"
    );
    assert_eq!(
        std::fs::read(out.join("history.csv")).unwrap(),
        stale_history,
        "history.csv must be the earlier complete file, not a partial one"
    );
    // and a rerun completes
    let o = run_short();
    assert!(o.status.success());
    assert!(out.join("summary.json").exists());
    assert_eq!(
        std::fs::read(out.join("history.csv")).unwrap(),
        stale_history
    );
}
