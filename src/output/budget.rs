//! Guards: no run may eat the machine. The output of a run (history.csv) and of a sweep
//! (results.csv and its journal) is estimated before anything is computed and refused above a
//! limit — 1 GB unless the user raises it (`--max-output-size`) — with the estimated size and
//! the keys that change it. Memory does not depend on these sizes (the history is streamed,
//! see [`crate::output::writer::RunWriter`]); disk and time do.

use crate::input::scenario::Scenario;
use crate::recording::history::sample_count;

/// Default largest estimated output, bytes (1 GB).
pub const DEFAULT_MAX_OUTPUT: u64 = 1_000_000_000;

/// Bytes per number written to history.csv, on average: a displacement in full precision
/// takes about 22 characters, the time and a zero force a few; measured on the bundled
/// examples: 94 bytes per row of 6 numbers, 108 per row of 8.
pub const HISTORY_BYTES_PER_NUMBER: u64 = 16;

/// Bytes per sweep case, per column, of results.csv and its journal together (each row is
/// written twice: to the journal as it is computed and to the results table at the end).
pub const SWEEP_BYTES_PER_COLUMN: u64 = 2 * 16;

/// Columns of a results row besides the axes (case, status, the result fields and the
/// self-check).
pub const SWEEP_FIXED_COLUMNS: u64 = 24;

/// An estimated output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Estimate {
    /// Rows (history samples, or sweep cases).
    pub rows: u64,
    /// Bytes.
    pub bytes: u64,
}

/// Why a run or a sweep is refused before it starts.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct TooLarge(pub String);

/// The history.csv of a scenario: one row per output interval, `t,w1,w2,force,w1_free,w2_free`
/// and one force column per level when there are several.
pub fn estimate_run(scenario: &Scenario) -> Estimate {
    let rows = sample_count(scenario.output_interval, scenario.solver.duration);
    let levels = scenario.contact.levels.len() as u64;
    // history.csv, and floors.csv: t and, per floor (station) of each structure, a displacement
    // and an acceleration with and without pounding (a cantilever: the contact heights and its
    // top, or with `[output] floor_stations = "all"` its tenths and the levels)
    let contact_stations = |length: f64| {
        let mut h: Vec<f64> = (scenario.contact.levels.iter())
            .map(|l| l.height)
            .filter(|&h| h <= length)
            .chain([length])
            .collect();
        h.sort_by(f64::total_cmp);
        h.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * length);
        h.len() as u64
    };
    let stations: u64 = (scenario.structures.iter())
        .map(|s| match (s.floor_heights(), scenario.floor_stations) {
            (Some(h), _) => h.len() as u64,
            (None, crate::recording::stations::FloorStations::All) => 10 + levels,
            (None, crate::recording::stations::FloorStations::Contact) => {
                contact_stations(s.length())
            }
        })
        .sum();
    let numbers = 6 + if levels > 1 { levels } else { 0 } + 1 + 4 * stations;
    Estimate {
        rows,
        bytes: rows.saturating_mul(numbers * HISTORY_BYTES_PER_NUMBER),
    }
}

/// Refuse a run whose history would exceed `limit` bytes; otherwise its estimate.
pub fn check_run(scenario: &Scenario, limit: u64) -> Result<Estimate, TooLarge> {
    let e = estimate_run(scenario);
    if e.bytes <= limit {
        return Ok(e);
    }
    // the output interval that would fit
    let fits = scenario.solver.duration * e.bytes as f64 / limit as f64 / e.rows as f64;
    Err(TooLarge(format!(
        "this run would write about {} of history ({} rows of history.csv and floors.csv: solver.duration = {} s \
         sampled every solver.output_interval = {} s), above the limit of {}. Raise \
         `solver.output_interval` (to about {} s or more to fit) or shorten `solver.duration`, \
         or allow it explicitly with --max-output-size {} (the disk must hold it; memory does not \
         grow with it)",
        format_size(e.bytes),
        e.rows,
        scenario.solver.duration,
        scenario.output_interval,
        format_size(limit),
        round_up_1_2_5(fits),
        format_size(round_up_size(e.bytes)).replace(' ', ""),
    )))
}

/// Results of a sweep of `cases` cases over `axes` axes: one row per case in results.csv and
/// in the journal.
pub fn estimate_sweep(cases: u64, axes: usize) -> Estimate {
    let columns = SWEEP_FIXED_COLUMNS + axes as u64;
    Estimate {
        rows: cases,
        bytes: cases.saturating_mul(columns * SWEEP_BYTES_PER_COLUMN),
    }
}

/// Refuse a sweep whose results would exceed `limit` bytes.
pub fn check_sweep(cases: u64, axes: usize, limit: u64) -> Result<Estimate, TooLarge> {
    let e = estimate_sweep(cases, axes);
    if e.bytes <= limit {
        return Ok(e);
    }
    Err(TooLarge(format!(
        "this sweep has {cases} cases and would write about {} of results (results.csv and \
         journal.csv), above the limit of {}. Use fewer values per axis (`values`, or `steps` of \
         a range), or allow it explicitly with --max-output-size {}",
        format_size(e.bytes),
        format_size(limit),
        format_size(round_up_size(e.bytes)).replace(' ', ""),
    )))
}

/// A size in bytes for people: "950 kB", "12.3 GB" (decimal units).
pub fn format_size(bytes: u64) -> String {
    const UNITS: [(&str, f64); 4] = [("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)];
    let b = bytes as f64;
    for (unit, scale) in UNITS {
        if b >= scale {
            let x = b / scale;
            return if x < 10.0 {
                format!("{x:.1} {unit}")
            } else {
                format!("{x:.0} {unit}")
            };
        }
    }
    format!("{bytes} B")
}

/// A size for `--max-output-size`: a number of bytes, optionally with a decimal unit
/// (`kB`, `MB`, `GB`, `TB`, case-insensitive, `B` optional), e.g. `5GB`, `1.5 GB`, `2e9`.
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| c.is_ascii_alphabetic() && c != 'e' && c != 'E')
        .unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let scale = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" => 1e3,
        "m" | "mb" => 1e6,
        "g" | "gb" => 1e9,
        "t" | "tb" => 1e12,
        _ => {
            return Err(format!(
                "`{text}`: unknown unit `{}` (use B, kB, MB, GB or TB, e.g. 5GB)",
                unit.trim()
            ));
        }
    };
    let x: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("`{text}`: not a size (e.g. 5GB, 500MB, 2e9)"))?;
    let bytes = x * scale;
    if !(bytes.is_finite() && bytes >= 1.0) {
        return Err(format!("`{text}`: must be at least 1 byte"));
    }
    Ok(if bytes >= u64::MAX as f64 {
        u64::MAX
    } else {
        bytes.ceil() as u64
    })
}

/// `bytes` rounded up to two significant digits (a limit to suggest).
fn round_up_size(bytes: u64) -> u64 {
    let b = bytes as f64;
    let scale = 10f64.powf(b.log10().floor() - 1.0).max(1.0);
    let r = (b / scale).ceil() * scale;
    if r >= u64::MAX as f64 {
        u64::MAX
    } else {
        r as u64
    }
}

/// The smallest of 1, 2, 5 × 10ⁿ at or above `x` (an output interval to suggest).
fn round_up_1_2_5(x: f64) -> String {
    if !(x.is_finite() && x > 0.0) {
        return x.to_string();
    }
    let p = 10f64.powf(x.log10().floor());
    let m = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .find(|m| m * p >= x * (1.0 - 1e-12))
        .unwrap_or(10.0);
    format!("{}", (m * p * 1e12).round() / 1e12)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_print() {
        assert_eq!(parse_size("5GB"), Ok(5_000_000_000));
        assert_eq!(parse_size("1.5 gb"), Ok(1_500_000_000));
        assert_eq!(parse_size("2e9"), Ok(2_000_000_000));
        assert_eq!(parse_size("500MB"), Ok(500_000_000));
        assert_eq!(parse_size("12345"), Ok(12345));
        assert!(
            parse_size("5 furlongs")
                .unwrap_err()
                .contains("unknown unit")
        );
        assert!(parse_size("-1GB").is_err());
        assert!(parse_size("GB").is_err());
        assert_eq!(format_size(12_300_000_000), "12 GB");
        assert_eq!(format_size(1_230_000_000), "1.2 GB");
        assert_eq!(format_size(950_000), "950 kB");
        assert_eq!(format_size(12), "12 B");
        assert_eq!(round_up_size(12_345_678_901), 13_000_000_000);
        assert_eq!(round_up_1_2_5(0.013), "0.02");
        assert_eq!(round_up_1_2_5(3.0), "5");
        assert_eq!(round_up_1_2_5(10.0), "10");
    }

    /// 10⁹ cases over two axes: 26 columns × 32 bytes × 10⁹ = 832 GB, refused with the size,
    /// the limit and the flag that overrides it; a raised limit lets it through.
    #[test]
    fn absurd_sweep_is_refused() {
        let e = check_sweep(1_000_000_000, 2, DEFAULT_MAX_OUTPUT)
            .unwrap_err()
            .0;
        for needle in [
            "1000000000 cases",
            "832 GB",
            "1.0 GB",
            "--max-output-size 840GB",
        ] {
            assert!(e.contains(needle), "`{needle}` missing in: {e}");
        }
        assert!(check_sweep(1_000_000_000, 2, 840_000_000_000).is_ok());
        assert!(check_sweep(1000, 2, DEFAULT_MAX_OUTPUT).is_ok());
    }
}
