//! The Python package's `Scenario.from_dict` on arbitrary nested data: the input is JSON (the
//! shape of Python's nested dicts, lists, strings, numbers and booleans; Python's own `json`
//! spellings `"NaN"`, `"Infinity"` and `"-Infinity"` stand for those floats, which a dict may
//! hold), turned into a `toml::Table` as `pounding._core` turns a dict, and validated by
//! `Scenario::from_table` — the library entry `from_dict` calls. It must return a scenario or an
//! error, never panic, hang or exhaust memory. `null` (Python's `None`) has no TOML form: the
//! binding refuses it by key path, so here it is dropped. Record files resolve in `examples/`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

/// Nesting deeper than this is refused by the binding (a list containing itself); the same cap
/// keeps this conversion's recursion bounded.
const MAX_DEPTH: usize = 32;

fn to_toml(v: &serde_json::Value, depth: usize) -> Option<toml::Value> {
    if depth > MAX_DEPTH {
        return None;
    }
    Some(match v {
        serde_json::Value::Null => return None,
        serde_json::Value::Bool(b) => toml::Value::Boolean(*b),
        serde_json::Value::Number(n) => match n.as_i64() {
            Some(i) => toml::Value::Integer(i),
            None => toml::Value::Float(n.as_f64()?),
        },
        serde_json::Value::String(s) => match s.as_str() {
            "NaN" => toml::Value::Float(f64::NAN),
            "Infinity" => toml::Value::Float(f64::INFINITY),
            "-Infinity" => toml::Value::Float(f64::NEG_INFINITY),
            _ => toml::Value::String(s.clone()),
        },
        serde_json::Value::Array(a) => {
            toml::Value::Array(a.iter().filter_map(|x| to_toml(x, depth + 1)).collect())
        }
        serde_json::Value::Object(o) => toml::Value::Table(
            o.iter()
                .filter_map(|(k, x)| Some((k.clone(), to_toml(x, depth + 1)?)))
                .collect(),
        ),
    })
}

fuzz_target!(|data: &[u8]| {
    let Ok(json) = serde_json::from_slice::<serde_json::Value>(data) else {
        return;
    };
    let Some(toml::Value::Table(table)) = to_toml(&json, 0) else {
        return;
    };
    let base = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples"));
    if let Ok(sc) = pounding::input::scenario::Scenario::from_table(&table, "<dict>", base) {
        // an accepted scenario must assemble its system
        let _ = sc.system();
    }
});
