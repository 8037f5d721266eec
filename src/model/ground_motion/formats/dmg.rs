//! CSMIP/DMG (California Geological Survey, formerly the Division of Mines and Geology)
//! Volume 1 and Volume 2 files, both today's mixed-case layout and the 1980s upper-case one.
//! Each channel is a block ending with a `/&` line:
//!
//! * **V2** (corrected): 25 text lines (1st `Corrected accelerogram … Chan  1: 360 Deg`, 2nd
//!   `Uncorrected Accelerogram Data …`; the 16th `12000 points of instrument- and
//!   baseline-corrected accel, veloc and displ data`, the 17th `At equally-spaced intervals of
//!   .005 sec.`, the 18th `Peak acceleration = 77.280 cm/sec/sec at 30.585 sec.`), 100 integers
//!   (7 lines of 16I5), 100 reals (13 lines of 8F10), then three series each after its own line,
//!   `12000 points of accel data equally spaced at .005 sec, in cm/sec2. (8f10.6)` (1980s:
//!   `3251 POINTS OF ACCEL DATA EQUALLY SPACED AT .020 SEC. (UNITS: CM/SEC/SEC)`, 8F10.3).
//! * **V1** (uncorrected): 13 text lines (1st `Uncorrected Accelerogram Data`, the 11th
//!   `No. of Points = 13200 Record Length = 66.000 sec at 200 Samples/sec`, the 12th the units
//!   and `Max = .079 g , at 30.590 sec.`), 100 integers (7 lines), 50 reals (7 lines), then
//!   `13200 Accelerogram points at 200 pts/sec in units of g . Format: (8f9.6)` and the values;
//!   in the 1980s layout no such line but (t, a) pairs of the digitised film in 10F7.3, in g/10.

use crate::model::ground_motion::error::{RecordError, clip, record_line};
use crate::model::ground_motion::formats::text::{
    EditKind, FortranFormat, first_number, number_after, read_fixed,
};
use crate::model::ground_motion::formats::{Channel, Parsed, orientation_names};
use crate::model::ground_motion::record::{AccelUnits, RecordFormat};

const FORMAT: &str = "CSMIP/DMG";
const V2_TEXT: usize = 25;
const V1_TEXT: usize = 13;
const INT_LINES: usize = 7;
const V2_REAL_LINES: usize = 13;
const V1_REAL_LINES: usize = 7;

/// Reads every channel of a CSMIP/DMG V1 or V2 file.
pub fn read(text: &str, file: &str) -> Result<Parsed, RecordError> {
    let lines: Vec<&str> = text.lines().collect();
    let first = lines
        .first()
        .map_or(String::new(), |l| l.to_ascii_uppercase());
    if first.contains("RESPONSE AND FOURIER AMPLITUDE SPECTRA") {
        return Err(RecordError::NotAcceleration {
            at: record_line(file, 1),
            found: clip(lines[0]),
        });
    }
    let v1 = first.contains("UNCORRECTED ACCELEROGRAM");
    let mut channels = Vec::new();
    let mut description = String::new();
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim().is_empty() {
            i += 1;
            continue;
        }
        let (channel, desc) = if v1 {
            read_v1(&lines, i, file)?
        } else {
            read_v2(&lines, i, file)?
        };
        if description.is_empty() {
            description = desc;
        }
        channels.push(channel);
        // the block ends with its `/&` line
        i = match lines[i..].iter().position(|l| l.starts_with("/&")) {
            Some(k) => i + k + 1,
            None => lines.len(),
        };
    }
    Ok(Parsed {
        format: if v1 {
            RecordFormat::CsmipV1
        } else {
            RecordFormat::CsmipV2
        },
        description,
        channels,
        default_units: AccelUnits::Gal,
    })
}

fn bad_line(lines: &[&str], i: usize, file: &str, expected: &str) -> RecordError {
    RecordError::BadHeaderLine {
        at: record_line(file, (i + 1).min(lines.len().max(1))),
        format: FORMAT,
        expected: expected.into(),
        found: lines
            .get(i)
            .map_or_else(|| "the end of the file".into(), |l| clip(l)),
    }
}

/// The channel's names from `Chan  1: 360 Deg` / `CHAN  2: UP` on a text line.
fn names_from(line: &str) -> Vec<String> {
    let upper = line.to_ascii_uppercase();
    let Some(at) = upper.find("CHAN") else {
        return vec![String::new()];
    };
    let rest = &line[at + 4..];
    let Some((num, orient)) = rest.split_once(':') else {
        return vec![String::new()];
    };
    let num = num.trim();
    let orient = orient
        .trim()
        .split("  ")
        .next()
        .unwrap_or("")
        .trim()
        .to_string();
    let mut names = vec![format!("Chan {num}: {orient}"), num.to_string()];
    let ou = orient.to_ascii_uppercase();
    if ou.starts_with("UP") || ou.starts_with("DOWN") {
        names.extend(orientation_names(None));
    } else if let Some(a) = first_number(&orient) {
        names.extend(orientation_names(Some(a)));
    }
    names.dedup();
    names
}

/// The units of a data line: `in cm/sec2.`, `in units of g .`, `(UNITS: CM/SEC/SEC)`.
fn units_of(line: &str) -> Option<AccelUnits> {
    let upper = line.to_ascii_uppercase();
    let name = if let Some(at) = upper.find("UNITS:") {
        upper[at + 6..].split(')').next()?.trim().to_string()
    } else if let Some(at) = upper.find("UNITS OF") {
        upper[at + 8..].split_whitespace().next()?.to_string()
    } else {
        let at = upper.rfind(" IN ")?;
        upper[at + 4..].split_whitespace().next()?.to_string()
    };
    AccelUnits::from_name(name.trim_end_matches(['.', ',']))
}

/// The Fortran format in parentheses at the end of a data line, if any.
fn format_in(line: &str) -> Option<FortranFormat> {
    let open = line.rfind('(')?;
    let close = line[open..].find(')')? + open;
    FortranFormat::parse(&line[open..=close])
}

/// The format of a data line that states none (1980s files): 8 values a line, as wide as the
/// first data line is long over 8 (8F9 and 8F10 both occur), else 8F10.3.
fn unstated_format(first_data: Option<&&str>) -> FortranFormat {
    let len = first_data.map_or(0, |l| l.trim_end().chars().count());
    let width = if len > 0 && len.is_multiple_of(8) {
        len / 8
    } else {
        10
    };
    FortranFormat::fixed(8, width, 3, EditKind::Real)
}

fn read_v2(lines: &[&str], s: usize, file: &str) -> Result<(Channel, String), RecordError> {
    let text = lines
        .get(s..s + V2_TEXT)
        .ok_or_else(|| bad_line(lines, lines.len(), file, "25 text header lines"))?;
    let l1 = text[0].to_ascii_uppercase();
    if !l1.contains("CORRECTED ACCELEROGRAM") {
        return Err(bad_line(
            lines,
            s,
            file,
            "the first line of a channel, \"Corrected accelerogram …\"",
        ));
    }
    let ints = FortranFormat::fixed(16, 5, 0, EditKind::Integer);
    let reals = FortranFormat::fixed(8, 10, 3, EditKind::Real);
    let (_, next) = read_fixed(lines, s + V2_TEXT, 100, &ints, file)?;
    let (_, next) = read_fixed(lines, next, 100, &reals, file)?;
    debug_assert_eq!(next, s + V2_TEXT + INT_LINES + V2_REAL_LINES);
    let data_line = lines.get(next).copied().unwrap_or("");
    let du = data_line.to_ascii_uppercase();
    if !du.contains("POINTS OF ACCEL") {
        return Err(bad_line(
            lines,
            next,
            file,
            "\"12000 points of accel data equally spaced at .005 sec, in cm/sec2. (8f10.6)\"",
        ));
    }
    let count = first_number(data_line)
        .filter(|n| *n >= 0.0 && n.fract() == 0.0)
        .ok_or_else(|| bad_line(lines, next, file, "the number of points first"))?
        as usize;
    let dt = number_after(data_line, "spaced at")
        .filter(|d| *d > 0.0)
        .ok_or_else(|| bad_line(lines, next, file, "\"equally spaced at <dt> sec\""))?;
    let units = units_of(data_line).ok_or_else(|| RecordError::UnsupportedUnits {
        at: record_line(file, next + 1),
        found: clip(data_line),
    })?;
    let fmt = format_in(data_line).unwrap_or_else(|| unstated_format(lines.get(next + 1)));
    // the text header states the count and the time step too
    if let Some(n) = first_number(text[15])
        && text[15].to_ascii_uppercase().contains("POINTS")
        && n as usize != count
    {
        return Err(RecordError::TooFewValues {
            at: record_line(file, next + 1),
            npts: n as usize,
            found: count,
        });
    }
    if let Some(d) = number_after(text[16], "intervals of")
        && (d - dt).abs() > 1e-6 * dt
    {
        return Err(RecordError::TimeStepMismatch {
            at: record_line(file, next + 1),
            first: format!("text line 17 (line {})", s + 17),
            dt_first: d,
            second: "the data line".into(),
            dt_second: dt,
        });
    }
    let (values, _) = read_fixed(lines, next + 1, count, &fmt, file)?;
    let stated = number_after(text[17], "acceleration =").map(|p| {
        let time = number_after(text[17], " at ");
        (p, time)
    });
    let description = format!("{}; {}", text[5].trim(), text[6].trim());
    Ok((
        Channel {
            names: names_from(text[7]),
            values,
            units: Some(units),
            dt: Some(dt),
            stated_peak: stated,
            line: s + 1,
            ..Channel::default()
        },
        description,
    ))
}

fn read_v1(lines: &[&str], s: usize, file: &str) -> Result<(Channel, String), RecordError> {
    let text = lines
        .get(s..s + V1_TEXT)
        .ok_or_else(|| bad_line(lines, lines.len(), file, "13 text header lines"))?;
    if !text[0]
        .to_ascii_uppercase()
        .contains("UNCORRECTED ACCELEROGRAM")
    {
        return Err(bad_line(
            lines,
            s,
            file,
            "the first line of a channel, \"Uncorrected Accelerogram Data\"",
        ));
    }
    let ints = FortranFormat::fixed(16, 5, 0, EditKind::Integer);
    let reals = FortranFormat::fixed(8, 10, 3, EditKind::Real);
    let (_, next) = read_fixed(lines, s + V1_TEXT, 100, &ints, file)?;
    let (_, next) = read_fixed(lines, next, 50, &reals, file)?;
    debug_assert_eq!(next, s + V1_TEXT + INT_LINES + V1_REAL_LINES);
    let l11 = text[10];
    let stated_count = number_after(l11, "points =")
        .filter(|n| *n >= 0.0 && n.fract() == 0.0)
        .ok_or_else(|| bad_line(lines, s + 10, file, "\"No. of Points = 13200 …\""))?
        as usize;
    let l12 = text[11];
    let max = number_after(l12, "max  =").or_else(|| number_after(l12, "max ="));
    let max_time = number_after(l12, " at ");
    let names = names_from(text[6]);
    let description = format!("{}; {}", text[4].trim(), text[5].trim());
    let data_line = lines.get(next).copied().unwrap_or("");
    let uncorrected = Some("CSMIP/DMG V1, uncorrected acceleration".to_string());
    if data_line.to_ascii_uppercase().contains("POINTS") {
        // today's layout: `13200 Accelerogram points at 200 pts/sec in units of g . Format: (8f9.6)`
        let count = first_number(data_line)
            .filter(|n| *n >= 0.0 && n.fract() == 0.0)
            .ok_or_else(|| bad_line(lines, next, file, "the number of points first"))?
            as usize;
        // `… points at 200 pts/sec …`, or (1980s) `… EQUALLY SPACED AT .005 SEC.`
        let rate = number_after(data_line, "points at")
            .or_else(|| number_after(data_line, "spaced at").map(|dt| 1.0 / dt))
            .filter(|r| r.is_finite() && *r > 0.0)
            .ok_or_else(|| {
                bad_line(
                    lines,
                    next,
                    file,
                    "\"… points at <rate> pts/sec …\" or \"… equally spaced at <dt> sec\"",
                )
            })?;
        if count != stated_count {
            return Err(RecordError::TooFewValues {
                at: record_line(file, next + 1),
                npts: stated_count,
                found: count,
            });
        }
        if let Some(r) = number_after(l11, "sec   at")
            .or_else(|| number_after(l11, "sec at"))
            .filter(|_| l11.to_ascii_uppercase().contains("SAMPLES/SEC"))
            && (r - rate).abs() > 1e-6 * rate
        {
            return Err(RecordError::TimeStepMismatch {
                at: record_line(file, next + 1),
                first: format!("text line 11 (line {}), {r} samples/s", s + 11),
                dt_first: 1.0 / r,
                second: format!("the data line, {rate} pts/s"),
                dt_second: 1.0 / rate,
            });
        }
        let units = units_of(data_line).ok_or_else(|| RecordError::UnsupportedUnits {
            at: record_line(file, next + 1),
            found: clip(data_line),
        })?;
        let fmt = format_in(data_line).unwrap_or_else(|| unstated_format(lines.get(next + 1)));
        let (values, _) = read_fixed(lines, next + 1, count, &fmt, file)?;
        return Ok((
            Channel {
                names,
                values,
                units: Some(units),
                dt: Some(1.0 / rate),
                uncorrected,
                stated_peak: max.map(|m| (m, max_time)),
                line: s + 1,
                ..Channel::default()
            },
            description,
        ));
    }
    // the 1980s layout: (t, a) pairs of the digitised film, 10F7.3, in g/10
    let g10 = l12.to_ascii_uppercase().contains("G/10");
    let fmt = FortranFormat::fixed(10, 7, 3, EditKind::Real);
    let (pairs, _) = read_fixed(lines, next, 2 * stated_count, &fmt, file)?;
    let scale = if g10 { 0.1 } else { 1.0 };
    let times: Vec<f64> = pairs.iter().step_by(2).copied().collect();
    let values: Vec<f64> = pairs.iter().skip(1).step_by(2).map(|a| a * scale).collect();
    if let Some(k) = times.windows(2).position(|w| w[1] < w[0]) {
        return Err(RecordError::TimeNotIncreasing {
            at: record_line(file, next + 1 + (2 * (k + 1)) / 10),
            previous: times[k],
            time: times[k + 1],
        });
    }
    Ok((
        Channel {
            names,
            values,
            units: Some(AccelUnits::G),
            times: Some(times),
            uncorrected,
            stated_peak: max.map(|m| (m, max_time)),
            line: s + 1,
            ..Channel::default()
        },
        description,
    ))
}
