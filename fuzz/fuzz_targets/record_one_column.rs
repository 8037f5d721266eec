//! The record reader on arbitrary bytes, as `Record::read` sees a file (lossy UTF-8, then
//! `Record::parse`), named `fuzz.txt` with `dt = 0.01` given (the one-column form): a record or an error, never a panic, a hang or
//! unbounded memory.
#![no_main]

use libfuzzer_sys::fuzz_target;
use pounding::model::ground_motion::record::{Record, RecordOptions};
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let opts = RecordOptions {
        dt: Some(0.01),
        ..RecordOptions::default()
    };
    if let Ok(r) = Record::from_bytes(data, Path::new("fuzz.txt"), &opts) {
        assert!(r.num_samples() >= 2 && r.dt > 0.0 && r.dt.is_finite());
        assert!(r.pga().is_finite() && r.duration().is_finite());
    }
});
