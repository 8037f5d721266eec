//! ESM / ITACA ASCII (Engineering Strong-Motion database, Italian accelerometric archive): a
//! header of `KEY: value` lines (`NETWORK`, `STATION_CODE`, `STREAM: HNE`,
//! `SAMPLING_INTERVAL_S: 0.005000`, `NDATA: 19128`, `DURATION_S`, `UNITS: cm/s^2`,
//! `DATA_TYPE: ACCELERATION`, `PROCESSING: manual (…)` or `none`, `PGA_CM/S^2`, `TIME_PGA_S`,
//! …, `USER5:`), then one value per line. Files whose `PROCESSING` is `none` (the database's
//! unprocessed "U" files) are uncorrected.

use crate::model::ground_motion::error::{RecordError, clip, record_line};
use crate::model::ground_motion::formats::text::{first_number, parse_value};
use crate::model::ground_motion::formats::{Channel, Parsed};
use crate::model::ground_motion::record::{AccelUnits, RecordFormat};

const FORMAT: &str = "ESM";

/// Whether `line` is a header line `KEY: value` (upper-case key).
fn header_line(line: &str) -> Option<(&str, &str)> {
    let (k, v) = line.split_once(':')?;
    let key_chars = |c: char| c.is_ascii_uppercase() || c.is_ascii_digit() || "_/^.-".contains(c);
    (!k.is_empty() && k.chars().all(key_chars)).then(|| (k, v.trim()))
}

/// Reads an ESM ASCII file (one channel).
pub fn read(text: &str, file: &str) -> Result<Parsed, RecordError> {
    let lines: Vec<&str> = text.lines().collect();
    let header_end = lines
        .iter()
        .position(|l| !l.trim().is_empty() && header_line(l).is_none())
        .unwrap_or(lines.len());
    let header: Vec<(usize, &str, &str)> = lines[..header_end]
        .iter()
        .enumerate()
        .filter_map(|(i, l)| header_line(l).map(|(k, v)| (i + 1, k, v)))
        .collect();
    let field = |key: &str| {
        header
            .iter()
            .find(|(_, k, _)| *k == key)
            .map(|(l, _, v)| (*l, *v))
    };
    let missing = |key: &str, what: &str| RecordError::BadHeaderLine {
        at: record_line(file, header_end.max(1)),
        format: FORMAT,
        expected: format!("a \"{key}:\" line ({what}) in the header"),
        found: clip(
            lines
                .get(header_end.saturating_sub(1))
                .copied()
                .unwrap_or(""),
        ),
    };
    let bad = |line: usize, expected: &str, found: &str| RecordError::BadHeaderLine {
        at: record_line(file, line),
        format: FORMAT,
        expected: expected.into(),
        found: clip(found),
    };

    if let Some((l, v)) = field("DATA_TYPE") {
        let u = v.to_ascii_uppercase();
        if !u.contains("ACCELERATION") || u.contains("SPECTRUM") {
            return Err(RecordError::NotAcceleration {
                at: record_line(file, l),
                found: clip(&format!("DATA_TYPE: {v}")),
            });
        }
    }
    let (l, v) = field("SAMPLING_INTERVAL_S").ok_or_else(|| missing("SAMPLING_INTERVAL_S", "s"))?;
    let dt = first_number(v)
        .filter(|d| *d > 0.0)
        .ok_or_else(|| bad(l, "a time step in s", v))?;
    let dt_line = l;
    let (l, v) = field("NDATA").ok_or_else(|| missing("NDATA", "the number of values"))?;
    let ndata = first_number(v)
        .filter(|n| *n >= 0.0 && n.fract() == 0.0 && *n < 1e12)
        .ok_or_else(|| bad(l, "the number of values", v))? as usize;
    let ndata_line = l;
    let (l, v) = field("UNITS").ok_or_else(|| missing("UNITS", "e.g. cm/s^2"))?;
    let units = AccelUnits::from_name(v).ok_or_else(|| RecordError::UnsupportedUnits {
        at: record_line(file, l),
        found: clip(v),
    })?;
    // the duration is NDATA·dt, written to 3 decimals: a larger difference is a second time step
    if let Some((l, v)) = field("DURATION_S")
        && let Some(d) = first_number(v)
        && ndata > 0
        && (d - ndata as f64 * dt).abs() > 1.5e-3 + 1e-6 * d
    {
        return Err(RecordError::TimeStepMismatch {
            at: record_line(file, l),
            first: format!("SAMPLING_INTERVAL_S, line {dt_line}"),
            dt_first: dt,
            second: format!("DURATION_S/NDATA, lines {l} and {ndata_line}"),
            dt_second: d / ndata as f64,
        });
    }
    let processing = field("PROCESSING")
        .map_or("", |(_, v)| v)
        .to_ascii_lowercase();
    let baseline = field("BASELINE_CORRECTION")
        .map_or("", |(_, v)| v)
        .to_ascii_uppercase();
    let uncorrected = (processing.trim() == "none" || baseline.contains("NOT REMOVED"))
        .then(|| "ESM, PROCESSING: none".to_string());

    let mut values = Vec::with_capacity(ndata.min(lines.len()));
    let mut extra_line = None;
    let mut found = 0;
    for (i, line) in lines.iter().enumerate().skip(header_end) {
        for token in line.split_whitespace() {
            let x = parse_value(token, file, i + 1)?;
            found += 1;
            if found <= ndata {
                values.push(x);
            } else if extra_line.is_none() {
                extra_line = Some(i + 1);
            }
        }
    }
    if let Some(l) = extra_line {
        return Err(RecordError::TooManyValues {
            at: record_line(file, l),
            npts: ndata,
            found,
        });
    }
    if found < ndata {
        return Err(RecordError::TooFewValues {
            at: record_line(file, ndata_line),
            npts: ndata,
            found,
        });
    }
    // the header's PGA is in cm/s² whatever UNITS says
    let stated = field("PGA_CM/S^2")
        .and_then(|(_, v)| first_number(v))
        .map(|p| p * AccelUnits::Gal.to_m_s2() / units.to_m_s2());
    let time = field("TIME_PGA_S").and_then(|(_, v)| first_number(v));
    let stream = field("STREAM").map_or("", |(_, v)| v).to_string();
    let mut names = vec![stream.clone()];
    names.extend(
        match stream.chars().last().map(|c| c.to_ascii_uppercase()) {
            Some('E') => vec!["EW".to_string(), "E".into()],
            Some('N') => vec!["NS".to_string(), "N".into()],
            Some('Z') => vec!["UD".to_string(), "UP".into(), "Z".into()],
            _ => Vec::new(),
        },
    );
    let get = |k: &str| field(k).map_or("", |(_, v)| v);
    Ok(Parsed {
        format: RecordFormat::Esm,
        description: format!(
            "ESM {}.{} {}, {} ({})",
            get("NETWORK"),
            get("STATION_CODE"),
            stream,
            get("EVENT_NAME"),
            get("EVENT_ID")
        ),
        channels: vec![Channel {
            names,
            values,
            units: Some(units),
            dt: Some(dt),
            uncorrected,
            stated_peak: stated.map(|p| (p, time)),
            line: 1,
            ..Channel::default()
        }],
        default_units: units,
    })
}
