//! K-NET / KiK-net ASCII (NIED, Japan): 17 header lines `Key  value` (`Origin Time`,
//! `Station Code`, `Sampling Freq(Hz)  100Hz`, `Duration Time(s)  102`, `Dir.  N-S` — KiK-net:
//! `1`…`6`, borehole NS/EW/UD then surface —, `Scale Factor  3920(gal)/6182761`,
//! `Max. Acc. (gal)  4.954`, …, `Memo.`), then integer counts, 8 per line. The acceleration is
//! counts × 3920/6182761 gal with the mean of the whole record removed; the header's maximum
//! is of that (NIED's description of the format).

use crate::model::ground_motion::error::{RecordError, clip, record_line};
use crate::model::ground_motion::formats::text::{first_number, parse_value};
use crate::model::ground_motion::formats::{Channel, Parsed};
use crate::model::ground_motion::record::{AccelUnits, RecordFormat};

const FORMAT: &str = "K-NET";

/// Reads a K-NET or KiK-net ASCII file (one channel).
pub fn read(text: &str, file: &str) -> Result<Parsed, RecordError> {
    let lines: Vec<&str> = text.lines().collect();
    // the header ends with the `Memo.` line
    let memo = lines
        .iter()
        .take(40)
        .position(|l| l.trim_start().starts_with("Memo"))
        .ok_or_else(|| RecordError::BadHeaderLine {
            at: record_line(file, 17.min(lines.len().max(1))),
            format: FORMAT,
            expected: "the header's last line, \"Memo.\"".into(),
            found: clip(lines.get(16).copied().unwrap_or("")),
        })?;
    let field = |key: &str| -> Option<(usize, &str)> {
        lines[..memo].iter().enumerate().find_map(|(i, l)| {
            l.trim_start()
                .starts_with(key)
                .then(|| (i + 1, l.trim_start()[key.len()..].trim()))
        })
    };
    let required = |key: &str, what: &str| {
        field(key).ok_or_else(|| RecordError::BadHeaderLine {
            at: record_line(file, memo + 1),
            format: FORMAT,
            expected: format!("a \"{key}\" line ({what}) before it"),
            found: clip(lines[memo]),
        })
    };
    let bad = |line: usize, expected: &str, found: &str| RecordError::BadHeaderLine {
        at: record_line(file, line),
        format: FORMAT,
        expected: expected.into(),
        found: clip(found),
    };

    let (l, v) = required("Sampling Freq(Hz)", "e.g. 100Hz")?;
    let rate = first_number(v)
        .filter(|r| *r > 0.0)
        .ok_or_else(|| bad(l, "a sampling frequency such as \"100Hz\"", v))?;
    let dt = 1.0 / rate;
    let (l, v) = required("Scale Factor", "e.g. 3920(gal)/6182761")?;
    let scale = scale_factor(v).ok_or_else(|| {
        bad(
            l,
            "a scale factor such as \"3920(gal)/6182761\" (gal per count)",
            v,
        )
    })?;
    let (l, v) = required("Dir.", "N-S, E-W, U-D or 1 to 6")?;
    let names = direction_names(v).ok_or_else(|| bad(l, "N-S, E-W, U-D or 1 to 6", v))?;
    let duration = field("Duration Time(s)").and_then(|(_, v)| first_number(v));
    let stated = ["Max. Acc. (gal)", "Max Acc. (gal)"]
        .iter()
        .find_map(|k| field(k))
        .and_then(|(_, v)| first_number(v));

    let mut counts = Vec::new();
    for (i, line) in lines.iter().enumerate().skip(memo + 1) {
        for token in line.split_whitespace() {
            counts.push(parse_value(token, file, i + 1)?);
        }
    }
    // the duration is in whole seconds: the count must be within one second's samples of it
    if let Some(d) = duration {
        let expected = (d * rate).round();
        let n = counts.len() as f64;
        if (n - expected).abs() > rate {
            let at = record_line(file, field("Duration Time(s)").map_or(1, |(l, _)| l));
            return Err(if n < expected {
                RecordError::TooFewValues {
                    at,
                    npts: expected as usize,
                    found: counts.len(),
                }
            } else {
                RecordError::TooManyValues {
                    at,
                    npts: expected as usize,
                    found: counts.len(),
                }
            });
        }
    }
    let mean = counts.iter().sum::<f64>() / counts.len().max(1) as f64;
    let values = counts.iter().map(|c| (c - mean) * scale).collect();
    let station = field("Station Code").map_or("", |(_, v)| v);
    let origin = field("Origin Time").map_or("", |(_, v)| v);
    Ok(Parsed {
        format: RecordFormat::Knet,
        description: format!("K-NET/KiK-net {station}, origin time {origin}"),
        channels: vec![Channel {
            names,
            values,
            units: Some(AccelUnits::Gal),
            dt: Some(dt),
            stated_peak: stated.map(|p| (p, None)),
            line: 1,
            ..Channel::default()
        }],
        default_units: AccelUnits::Gal,
    })
}

/// `3920(gal)/6182761` → 3920/6182761 gal per count.
fn scale_factor(v: &str) -> Option<f64> {
    let (num, den) = v.split_once('/')?;
    let num = num.trim().to_ascii_lowercase();
    let num: f64 = num.strip_suffix("(gal)")?.trim().parse().ok()?;
    let den: f64 = den.trim().parse().ok()?;
    let s = num / den;
    (s.is_finite() && s > 0.0).then_some(s)
}

/// The names of a direction: K-NET's `N-S`, `E-W`, `U-D`; KiK-net's channel 1–6 (1–3 in the
/// borehole, 4–6 at the surface: NS, EW, UD each).
fn direction_names(v: &str) -> Option<Vec<String>> {
    let d = v.split_whitespace().next()?.to_ascii_uppercase();
    let names: &[&str] = match d.as_str() {
        "N-S" => &["N-S", "NS", "N"],
        "E-W" => &["E-W", "EW", "E"],
        "U-D" => &["U-D", "UD", "UP", "Z"],
        "1" => &["1 (borehole N-S)", "1", "NS1", "NS", "N"],
        "2" => &["2 (borehole E-W)", "2", "EW1", "EW", "E"],
        "3" => &["3 (borehole U-D)", "3", "UD1", "UD", "UP", "Z"],
        "4" => &["4 (surface N-S)", "4", "NS2", "NS", "N"],
        "5" => &["5 (surface E-W)", "5", "EW2", "EW", "E"],
        "6" => &["6 (surface U-D)", "6", "UD2", "UD", "UP", "Z"],
        _ => return None,
    };
    Some(names.iter().map(|s| s.to_string()).collect())
}
