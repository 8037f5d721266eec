//! The scenario parser and validator on arbitrary text: `Scenario::from_toml` must return a
//! scenario or an error, never panic, hang or exhaust memory. Files a scenario names (records,
//! mode tables, spectrum tables) resolve in `examples/`, so the seeds' own files are found.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let base = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples"));
    if let Ok(sc) = pounding::input::scenario::Scenario::from_toml(text, "fuzz.toml", base) {
        // an accepted scenario must assemble its system
        let _ = sc.system();
    }
});
