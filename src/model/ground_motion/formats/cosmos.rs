//! COSMOS strong-motion data format (COSMOS Strong Motion Programs Board, version 1.20, 2001;
//! `.V1`, `.V2`, `.v1c`, `.v2c`): one or more channels, each a complete block of
//!
//! 1. text header, its 1st line `Corrected acceleration    (Format v01.20 with 13 text
//!    lines)` giving the number of text lines; the 9th names the channel (`Sta Chan   1: 90
//!    Deg`); the last gives the placeholders of unknown values (`-999, -999.00`);
//! 2. ` 100 Integer-header values follow on  10 lines, Format= (10I8)` and the integers:
//!    Int(1) the processing stage (0 raw counts, 1 uncorrected V1, 2 corrected V2, 3 spectra),
//!    Int(2) the quantity (1 acceleration, 2 velocity, 3 displacement), Int(3) the units
//!    (2 g, 4 cm/s², 10 gal, 11 mg, 7 in/s², 50 counts), Int(54)/Int(55) the sensor azimuth;
//! 3. ` 100 Real-header values follow on  20 lines, Format= (5F15.6)` and the reals:
//!    Real(62) the time step in ms, Real(63) the series length n·dt in s, Real(64) the peak and
//!    Real(65) its time;
//! 4. `   6 Comment line(s) follow, each starting with a "|":` and the comments (`<SCNL>` gives
//!    the channel code);
//! 5. `   42000 acceleration pts, approx  210 secs, units=cm/sec2(04),Format=(1E15.6)` and the
//!    data in that Fortran format (fixed-width fields, which may touch);
//! 6. an end line (`End-of-data for …`, `/&`).
//!
//! Each count and format is the header's own; velocity and displacement blocks are skipped.

use crate::model::ground_motion::error::{RecordError, clip, record_line};
use crate::model::ground_motion::formats::text::{
    EditKind, FortranFormat, first_number, number_after, read_fixed,
};
use crate::model::ground_motion::formats::{Channel, Parsed, orientation_names};
use crate::model::ground_motion::record::{AccelUnits, RecordFormat};

const FORMAT: &str = "COSMOS";

/// Reads every acceleration channel of a COSMOS file.
pub fn read(text: &str, file: &str) -> Result<Parsed, RecordError> {
    let lines: Vec<&str> = text.lines().collect();
    let mut channels = Vec::new();
    let mut skipped = Vec::new();
    let mut description = String::new();
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let upper = line.to_ascii_uppercase();
        if line.trim().is_empty() || upper.contains("END-OF-DATA") || line.starts_with("/&") {
            i += 1;
            continue;
        }
        if !(upper.contains("(FORMAT V") && upper.contains("TEXT LINES")) {
            return Err(RecordError::BadHeaderLine {
                at: record_line(file, i + 1),
                format: FORMAT,
                expected: "the first line of a channel, \"… (Format v01.20 with 13 text lines)\""
                    .into(),
                found: clip(line),
            });
        }
        let block = read_block(&lines, i, file)?;
        if description.is_empty() {
            description = block.description.clone();
        }
        i = block.next;
        match block.channel {
            Ok(c) => channels.push(c),
            Err(what) => skipped.push((block.start, what)),
        }
    }
    if channels.is_empty() {
        let (line, what) = skipped
            .into_iter()
            .next()
            .unwrap_or((1, "no data".to_string()));
        return Err(RecordError::NotAcceleration {
            at: record_line(file, line),
            found: clip(&what),
        });
    }
    let all_v1 = channels.iter().all(|c| c.uncorrected.is_some());
    Ok(Parsed {
        format: if all_v1 {
            RecordFormat::CosmosV1
        } else {
            RecordFormat::CosmosV2
        },
        description,
        channels,
        default_units: AccelUnits::Gal,
    })
}

struct Block {
    /// The channel, or why it is not one (velocity, raw counts, …).
    channel: Result<Channel, String>,
    description: String,
    start: usize,
    /// Index of the line after the block's data.
    next: usize,
}

/// The count, format and text of a section header such as
/// ` 100 Integer-header values follow on  10 lines, Format= (10I8)`.
fn section(
    lines: &[&str],
    i: usize,
    file: &str,
    expected: &str,
) -> Result<(usize, FortranFormat), RecordError> {
    let line = lines.get(i).copied().unwrap_or("");
    let bad = || RecordError::BadHeaderLine {
        at: record_line(file, i + 1),
        format: FORMAT,
        expected: expected.into(),
        found: clip(line),
    };
    let count = leading_count(line).ok_or_else(bad)?;
    let fmt = format_of(line).ok_or_else(bad)?;
    Ok((count, fmt))
}

/// The integer a header line starts with.
fn leading_count(line: &str) -> Option<usize> {
    line.split_whitespace().next()?.parse().ok()
}

/// The Fortran format after `Format` on a line: `Format= (10I8)`, `Format =(5F15.6)`.
fn format_of(line: &str) -> Option<FortranFormat> {
    let upper = line.to_ascii_uppercase();
    let at = upper.rfind("FORMAT")?;
    let rest = &line[at..];
    let open = rest.find('(')?;
    let close = rest[open..].find(')')? + open;
    FortranFormat::parse(&rest[open..=close])
}

fn read_block(lines: &[&str], start: usize, file: &str) -> Result<Block, RecordError> {
    let first = lines[start];
    let n_text = number_after(first, "with")
        .map_or(13, |n| n as usize)
        .max(1);
    let text_end = start + n_text;
    if text_end > lines.len() {
        return Err(RecordError::BadHeaderLine {
            at: record_line(file, lines.len()),
            format: FORMAT,
            expected: format!("{n_text} text header lines"),
            found: "the end of the file".into(),
        });
    }
    let text = &lines[start..text_end];
    // the placeholders of unknown values, from the last text line
    let last = text[n_text - 1];
    let nulls: Vec<f64> = last
        .split_once(':')
        .map(|(_, v)| {
            v.split([',', ' '])
                .filter_map(|t| t.trim().parse::<f64>().ok())
                .collect()
        })
        .unwrap_or_default();
    let int_null = nulls.first().copied().unwrap_or(-999.0);
    let real_null = nulls.get(1).copied().unwrap_or(int_null);

    let (n_int, int_fmt) = section(
        lines,
        text_end,
        file,
        "\" 100 Integer-header values follow on  10 lines, Format= (10I8)\"",
    )?;
    if int_fmt.kind != EditKind::Integer {
        return Err(RecordError::BadHeaderLine {
            at: record_line(file, text_end + 1),
            format: FORMAT,
            expected: "an integer format such as (10I8)".into(),
            found: clip(lines[text_end]),
        });
    }
    let (ints, next) = read_fixed(lines, text_end + 1, n_int, &int_fmt, file)?;
    let (n_real, real_fmt) = section(
        lines,
        next,
        file,
        "\" 100 Real-header values follow on  20 lines, Format= (5F15.6)\"",
    )?;
    let (reals, next) = read_fixed(lines, next + 1, n_real, &real_fmt, file)?;
    let comment_line = lines.get(next).copied().unwrap_or("");
    let n_comments = leading_count(comment_line)
        .filter(|_| comment_line.to_ascii_uppercase().contains("COMMENT"))
        .ok_or_else(|| RecordError::BadHeaderLine {
            at: record_line(file, next + 1),
            format: FORMAT,
            expected: "\"   2 Comment line(s) follow, each starting with a \"|\":\"".into(),
            found: clip(comment_line),
        })?;
    let comments = lines.get(next + 1..next + 1 + n_comments).unwrap_or(&[]);
    let data_at = next + 1 + n_comments;
    let data_line = lines.get(data_at).copied().unwrap_or("");
    let bad_data_line = || RecordError::BadHeaderLine {
        at: record_line(file, data_at + 1),
        format: FORMAT,
        expected: "the data line, e.g. \"   42000 acceleration pts, approx  210 secs, \
                   units=cm/sec2(04),Format=(1E15.6)\""
            .into(),
        found: clip(data_line),
    };
    let count = leading_count(data_line).ok_or_else(bad_data_line)?;
    let data_fmt = format_of(data_line).ok_or_else(bad_data_line)?;
    let (raw, after) = read_fixed(lines, data_at + 1, count, &data_fmt, file)?;

    let int = |k: usize| ints.get(k - 1).copied().filter(|v| *v != int_null);
    let real = |k: usize| reals.get(k - 1).copied().filter(|v| *v != real_null);
    let line1 = first.to_ascii_uppercase();
    let data_upper = data_line.to_ascii_uppercase();
    let description = format!(
        "{}; {}",
        text.get(1).map_or("", |s| s.trim()),
        text.get(4).map_or("", |s| s.trim())
    );
    let done = |channel| Block {
        channel,
        description: description.clone(),
        start: start + 1,
        next: after,
    };

    // what the block holds
    let stage = int(1)
        .map(|v| v as i64)
        .unwrap_or(if line1.contains("UNCORRECTED") {
            1
        } else if line1.contains("RAW") {
            0
        } else {
            2
        });
    let quantity = int(2)
        .map(|v| v as i64)
        .unwrap_or(if data_upper.contains("VELOC") {
            2
        } else if data_upper.contains("DISPL") {
            3
        } else {
            1
        });
    if stage == 3 || quantity != 1 {
        return Ok(done(Err(first.trim().to_string())));
    }
    if stage == 0 || data_upper.contains("COUNTS") {
        return Ok(done(Err(format!(
            "raw counts (V0), not in physical units: {}",
            first.trim()
        ))));
    }
    // units: Int(3), else the data line's `units=…(code)`
    // (the data line's own code first: it sits with the data)
    let code = units_code(data_line).or_else(|| int(3).map(|v| v as i64));
    let (units, factor) = match code {
        Some(2) => (AccelUnits::G, 1.0),
        Some(4) | Some(10) => (AccelUnits::Gal, 1.0),
        Some(11) => (AccelUnits::G, 1e-3),
        Some(7) => (AccelUnits::Gal, 2.54),
        _ => match units_name(data_line).and_then(|n| AccelUnits::from_name(&n)) {
            Some(u) if code.is_none() => (u, 1.0),
            _ => {
                return Err(RecordError::UnsupportedUnits {
                    at: record_line(file, data_at + 1),
                    found: clip(
                        &units_name(data_line)
                            .unwrap_or_else(|| format!("units code {}", code.unwrap_or(-999))),
                    ),
                });
            }
        },
    };
    // the time step: Real(62) in ms
    let dt = real(62)
        .filter(|v| *v > 0.0)
        .map(|ms| ms / 1000.0)
        .ok_or_else(|| RecordError::BadHeaderLine {
            at: record_line(file, text_end + 2),
            format: FORMAT,
            expected: "the time step in ms as real-header value 62".into(),
            found: format!("{}", reals.get(61).copied().unwrap_or(real_null)),
        })?;
    // the length Real(63) is n·dt (or (n − 1)·dt in some files); "approx … secs" is rounded
    let length_checks = [
        (real(63), 1.5 * dt, "real-header value 63 (series length)"),
        (
            number_after(data_line, "approx"),
            1.0 + 0.02 * count as f64 * dt,
            "the data line's \"approx … secs\"",
        ),
    ];
    for (length, tol, what) in length_checks {
        if let Some(len) = length
            && count > 1
            && (len - count as f64 * dt).abs() > tol
        {
            return Err(RecordError::TimeStepMismatch {
                at: record_line(file, data_at + 1),
                first: "real-header value 62".into(),
                dt_first: dt,
                second: format!("{what} over {count} points"),
                dt_second: len / count as f64,
            });
        }
    }
    let mut values = Vec::with_capacity(raw.len());
    for (k, v) in raw.iter().enumerate() {
        if *v == real_null || *v == int_null {
            let line = data_at + 2 + k / data_fmt.per_line;
            return Err(RecordError::MissingValue {
                at: record_line(file, line),
                token: format!("{v}"),
            });
        }
        values.push(v * factor);
    }
    let names = channel_names(text, comments, int(54).or(int(55)));
    let uncorrected = (stage == 1).then(|| format!("COSMOS V1: {}", first.trim()));
    let stated = real(64).map(|p| (p * factor, real(65)));
    Ok(done(Ok(Channel {
        names,
        values,
        units: Some(units),
        dt: Some(dt),
        uncorrected,
        stated_peak: stated,
        line: start + 1,
        ..Channel::default()
    })))
}

/// The code in `units=cm/sec2(04)`.
fn units_code(line: &str) -> Option<i64> {
    let upper = line.to_ascii_uppercase();
    let at = upper.find("UNITS")?;
    let rest = &line[at..];
    let open = rest.find('(')?;
    let close = rest[open..].find(')')? + open;
    rest[open + 1..close].trim().parse().ok()
}

/// The name in `units=cm/sec2(04)`.
fn units_name(line: &str) -> Option<String> {
    let upper = line.to_ascii_uppercase();
    let at = upper.find("UNITS")? + 5;
    let rest = line[at..].trim_start_matches([' ', '=', ':']);
    let end = rest.find(['(', ',']).unwrap_or(rest.len());
    let name = rest[..end].trim();
    (!name.is_empty()).then(|| name.to_string())
}

/// A channel's names: from the text header's 9th line (`Sta Chan   1: 90 Deg`), the `<SCNL>`
/// comment (`BMR.BNZ.AK.--`) and the integer header's azimuth.
fn channel_names(text: &[&str], comments: &[&str], azimuth: Option<f64>) -> Vec<String> {
    let mut names = Vec::new();
    let mut orientation: Option<Option<f64>> = None;
    if let Some(l9) = text.get(8) {
        let upper = l9.to_ascii_uppercase();
        if let Some(at) = upper.find("CHA") {
            // `Chan   1: 90 Deg (Rcrdr …`, `Cha:  1: 340 deg (…`, `Chan   ?:Other (…`
            let rest = &l9[at..];
            let from = rest
                .find(|c: char| c.is_ascii_digit() || c == '?')
                .unwrap_or(rest.len());
            let (num_text, tail) = rest[from..].split_once(':').unwrap_or(("", ""));
            let number = num_text.trim().parse::<u32>().ok();
            let orient_text = tail.split('(').next().unwrap_or("").trim();
            let label = match number {
                Some(n) => format!("Chan {n}: {orient_text}"),
                None => orient_text.to_string(),
            };
            if !orient_text.is_empty() && !orient_text.eq_ignore_ascii_case("other") {
                names.push(label.trim().to_string());
                if let Some(n) = number {
                    names.push(n.to_string());
                }
                let ou = orient_text.to_ascii_uppercase();
                if ou.starts_with("UP") || ou.starts_with("DOWN") || ou.starts_with("VERT") {
                    orientation = Some(None);
                } else if let Some(a) = first_number(orient_text) {
                    orientation = Some(Some(a));
                }
            } else if let Some(n) = number {
                names.push(format!("Chan {n}"));
                names.push(n.to_string());
            }
        }
    }
    let scnl = comments.iter().find_map(|c| {
        let at = c.find("<SCNL>")? + 6;
        c[at..]
            .split_whitespace()
            .next()?
            .split('.')
            .nth(1)
            .map(str::to_string)
    });
    if let Some(code) = scnl {
        if orientation.is_none() {
            orientation = match code.chars().last().map(|c| c.to_ascii_uppercase()) {
                Some('Z') => Some(None),
                Some('N') => Some(Some(0.0)),
                Some('E') => Some(Some(90.0)),
                _ => None,
            };
        }
        if names.is_empty() {
            names.push(code.clone());
        } else {
            names.push(code);
        }
    }
    if orientation.is_none()
        && let Some(az) = azimuth
    {
        orientation = match az as i64 {
            0..=360 => Some(Some(az)),
            400..=402 => Some(None),
            _ => None,
        };
    }
    if let Some(o) = orientation {
        names.extend(orientation_names(o));
    }
    if names.is_empty() {
        names.push(String::new());
    }
    names.dedup();
    names
}
