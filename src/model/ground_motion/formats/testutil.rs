//! Helpers of the readers' unit tests.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::model::ground_motion::record::{Record, RecordError, RecordOptions, STANDARD_GRAVITY};

pub(crate) const G: f64 = STANDARD_GRAVITY;

pub(crate) fn parse(text: &str, name: &str, opts: &RecordOptions) -> Result<Record, RecordError> {
    Record::parse(text, Path::new(name), opts)
}

pub(crate) fn ok(text: &str, name: &str, opts: &RecordOptions) -> Record {
    match parse(text, name, opts) {
        Ok(r) => r,
        Err(e) => panic!("expected {name} to parse, got: {e}"),
    }
}

/// Parses text that must fail; checks that the message names the file and, if
/// `line` is given, the line. Returns the error and its message.
pub(crate) fn fails(
    text: &str,
    name: &str,
    opts: &RecordOptions,
    line: Option<usize>,
) -> (RecordError, String) {
    let e = match parse(text, name, opts) {
        Ok(r) => panic!("expected {name} to fail, got {} samples", r.num_samples()),
        Err(e) => e,
    };
    let msg = e.to_string();
    let head = match line {
        Some(l) => format!("record \"{name}\", line {l}: "),
        None => format!("record \"{name}\": "),
    };
    assert!(
        msg.starts_with(&head),
        "message {msg:?} should start with {head:?}"
    );
    (e, msg)
}

pub(crate) fn no_opts() -> RecordOptions {
    RecordOptions::default()
}

pub(crate) fn with_dt(dt: f64) -> RecordOptions {
    RecordOptions {
        dt: Some(dt),
        ..RecordOptions::default()
    }
}

pub(crate) fn with_scale(pga_g: f64) -> RecordOptions {
    RecordOptions {
        scale_to_pga: Some(pga_g),
        ..RecordOptions::default()
    }
}

pub(crate) fn rel_close(actual: f64, expected: f64, tol: f64) -> bool {
    (actual - expected).abs() <= tol * expected.abs().max(f64::MIN_POSITIVE)
}

/// Tiny deterministic generator (Knuth's MMIX LCG).
pub(crate) struct Lcg(pub u64);
impl Lcg {
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 11
    }
    pub(crate) fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 42) as f64
    }
}

pub(crate) fn temp_path(name: &str) -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let dir = std::env::temp_dir().join(format!(
        "pounding-record-test-{}-{nanos}-{n}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("create temp dir");
    dir.join(name)
}

pub(crate) const AT2_HEAD: &str = "PEER NGA STRONG MOTION DATABASE RECORD\n\
                            Test event, 1/1/2000, Station, 0\n\
                            ACCELERATION TIME SERIES IN UNITS OF G\n";
