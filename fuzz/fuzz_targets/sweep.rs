//! The sweep-file parser on arbitrary text: `Sweep::from_toml` (axes, values, key paths, the
//! base scenario read relative to the sweep file, the first case validated) must return a sweep
//! or an error, never panic, hang or exhaust memory. When it accepts, the first and last cases'
//! scenario text is built and validated too. The sweep is placed in `examples/`, so that the
//! seeds' base scenarios (`scenario = "paper-c.toml"`) are found.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/fuzz-sweep.toml"
    ));
    if let Ok(sweep) = pounding::study::sweep::Sweep::from_toml(text, path) {
        assert!(!sweep.is_empty());
        for case in [0, sweep.len() - 1] {
            let _ = sweep.case_toml(case);
            let _ = sweep.case_scenario(case);
            let _ = sweep.label(case);
        }
    }
});
