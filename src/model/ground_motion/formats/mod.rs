//! Record files in every common layout, detected from the content (the first lines), not the
//! file name: one reader per layout, one dispatcher (`read`) in front.
//!
//! | layout | recognised by | reader |
//! |---|---|---|
//! | PEER NGA `.AT2` | 4th line `NPTS=…, DT=…` (or `… NPTS, DT`), or a 1st line starting `PEER` | [`at2`] |
//! | COSMOS V1/V2 (`.V1`, `.V2`, `.v2c`) | 1st line `… (Format v01.20 with 13 text lines)` | [`cosmos`] |
//! | CSMIP/DMG V1/V2 | 1st line `UNCORRECTED ACCELEROGRAM DATA`, or `CORRECTED ACCELEROGRAM` over it | [`dmg`] |
//! | K-NET / KiK-net ASCII | `Origin Time`, `Sampling Freq(Hz)`, `Scale Factor` header lines | [`knet`] |
//! | ESM / ITACA ASCII | `KEY: value` header with `SAMPLING_INTERVAL_S` and `NDATA` | [`esm`] |
//! | one or two columns | anything else | [`columns`] |
//!
//! Each reader returns the file's acceleration channels in the file's units ([`Parsed`]); the
//! dispatcher chooses the component, settles units and time step against the options, refuses
//! an uncorrected record unless it is to be processed, converts to m/s², processes, scales and
//! builds the [`Record`]. Binary files are refused first ([`check_text`], issue 24).

pub mod at2;
pub mod columns;
pub mod cosmos;
pub mod dmg;
pub mod esm;
pub mod knet;
#[cfg(test)]
pub(crate) mod testutil;
pub(crate) mod text;

use std::path::Path;

use crate::model::ground_motion::error::{RecordError, in_record, record_line};
use crate::model::ground_motion::record::{
    AccelUnits, Component, DT_REL_TOLERANCE, Record, RecordFormat, RecordOptions, StatedPeak, build,
};
use crate::model::ground_motion::record::{MAX_RECORD_BYTES, open_record_file};
use crate::model::ground_motion::scale;

/// Bytes at the start of a file checked for control characters and invalid UTF-8.
pub const SNIFF_BYTES: usize = 8192;

/// One acceleration channel of a file, in the file's units.
#[derive(Debug, Clone, Default)]
pub struct Channel {
    /// The names it answers to (case-insensitive), the first as it is shown: `"Chan 3: 90 Deg"`,
    /// then e.g. `"3"`, `"90"`, `"EW"`.
    pub names: Vec<String>,
    /// The samples, in `units` (or the layout's default).
    pub values: Vec<f64>,
    /// The units the file states.
    pub units: Option<AccelUnits>,
    /// The time step the file states, s.
    pub dt: Option<f64>,
    /// The times of unequally spaced samples (digitised film records), s; `values` are at them.
    pub times: Option<Vec<f64>>,
    /// `Some(what)` when the channel is uncorrected (V1, raw): e.g. "CSMIP V1".
    pub uncorrected: Option<String>,
    /// The peak the header states (in `units`) and its time (s), when it does.
    pub stated_peak: Option<(f64, Option<f64>)>,
    /// The 1-based line of the channel's first header line (for messages).
    pub line: usize,
}

/// What a reader found in a file.
#[derive(Debug, Clone)]
pub struct Parsed {
    /// The layout (and level) read.
    pub format: RecordFormat,
    /// Event and station, for the record's description.
    pub description: String,
    /// The acceleration channels, in the order of the file (at least one).
    pub channels: Vec<Channel>,
    /// The units when neither the file nor the options give them.
    pub default_units: AccelUnits,
}

/// Reading a record: the file, its bytes, its text (here rather than in
/// [`crate::model::ground_motion::record`], which the readers below build on).
impl Record {
    /// Reads a record file; see [`Record::parse`] for the formats and options. A binary file
    /// is refused ("not a text record file"); a few bytes that are not UTF-8 (e.g. Latin-1
    /// station names in a header) are replaced, not refused.
    pub fn read(path: &Path, opts: &RecordOptions) -> Result<Record, RecordError> {
        let at = || in_record(&path.display().to_string());
        let mut file = open_record_file(path)?;
        // (at most the limit and one byte more: a file that grows while it is read is caught)
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(&mut file, MAX_RECORD_BYTES + 1),
            &mut bytes,
        )
        .map_err(|source| RecordError::Io { at: at(), source })?;
        if bytes.len() as u64 > MAX_RECORD_BYTES {
            return Err(RecordError::TooLarge {
                at: at(),
                size: bytes.len() as u64,
                limit: MAX_RECORD_BYTES,
            });
        }
        Record::from_bytes(&bytes, path, opts)
    }

    /// Parses the bytes of a record file, as [`Record::read`] does after reading them: a
    /// binary file is refused ([`crate::model::ground_motion::formats::check_text`]), bytes that are
    /// not UTF-8 are replaced, then [`Record::parse`]. `path` is used only in error messages,
    /// for the description and as [`Record::parse`] says (the fuzz targets of `fuzz/` call
    /// this).
    pub fn from_bytes(
        bytes: &[u8],
        path: &Path,
        opts: &RecordOptions,
    ) -> Result<Record, RecordError> {
        crate::model::ground_motion::formats::check_text(bytes, &path.display().to_string())?;
        // (valid UTF-8, every bundled record, is checked by the standard library's fast scan,
        // where the lossy conversion decodes character by character)
        let text = match std::str::from_utf8(bytes) {
            Ok(text) => std::borrow::Cow::Borrowed(text),
            Err(_) => String::from_utf8_lossy(bytes),
        };
        Record::parse(&text, path, opts)
    }

    /// Parses the text of a record file: the layout is detected from the content
    /// ([`crate::model::ground_motion::formats::detect`]), the component chosen, converted to m/s²,
    /// processed and scaled as `opts` say. `path` is used only in error messages, for the
    /// description of records without one, and, when the content matches no layout, to pick
    /// which layout's error to report (`.AT2`).
    ///
    /// Two-column files take dt = `t[1] − t[0]` and treat the first sample as t = 0: a
    /// nonzero `t[0]` is an offset that is ignored.
    pub fn parse(text: &str, path: &Path, opts: &RecordOptions) -> Result<Record, RecordError> {
        crate::model::ground_motion::formats::read(text, path, opts)
    }
}

/// Refuses a file that is not text (issue 24): a NUL byte anywhere, a control character
/// other than tab, line feed, carriage return and form feed in the first [`SNIFF_BYTES`] (DOS
/// end-of-file marks, Ctrl-Z, at the very end are allowed), or more than 1 % invalid UTF-8
/// there (a few Latin-1 letters in a station name are fine).
pub fn check_text(bytes: &[u8], file: &str) -> Result<(), RecordError> {
    let line_of = |at: usize| bytes[..at].iter().filter(|&&b| b == b'\n').count() + 1;
    let not_text = |at: usize, reason: String| RecordError::NotText {
        at: record_line(file, line_of(at)),
        reason,
    };
    // (`contains` scans a word at a time; the position only for the message)
    if bytes.contains(&0)
        && let Some(at) = bytes.iter().position(|&b| b == 0)
    {
        return Err(not_text(at, format!("a NUL byte at byte {}", at + 1)));
    }
    let body = &bytes[..bytes.len() - bytes.iter().rev().take_while(|&&b| b == 0x1a).count()];
    let head = &body[..body.len().min(SNIFF_BYTES)];
    if let Some(at) = head
        .iter()
        .position(|&b| (b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r' | 0x0c)) || b == 0x7f)
    {
        return Err(not_text(
            at,
            format!("control character 0x{:02X} at byte {}", head[at], at + 1),
        ));
    }
    let mut invalid = 0;
    let mut rest = head;
    let mut first_bad = None;
    while !rest.is_empty() {
        match std::str::from_utf8(rest) {
            Ok(_) => break,
            Err(e) => {
                let good = e.valid_up_to();
                let bad = e.error_len().unwrap_or(rest.len() - good);
                if e.error_len().is_some() {
                    first_bad.get_or_insert(head.len() - rest.len() + good);
                    invalid += bad;
                }
                rest = &rest[good + bad..];
            }
        }
    }
    if invalid > 8 && invalid * 100 > head.len() {
        return Err(not_text(
            first_bad.unwrap_or(0),
            format!(
                "{invalid} of its first {} bytes are not UTF-8 text",
                head.len()
            ),
        ));
    }
    Ok(())
}

/// The layout of a record file, from its first lines ([`RecordFormat::TwoColumn`] when it is
/// none of the others: the column reader then says one or two columns, or why not).
pub fn detect(text: &str) -> RecordFormat {
    let head: Vec<&str> = text.lines().take(80).collect();
    let upper = |i: usize| {
        head.get(i)
            .map_or(String::new(), |l| l.to_ascii_uppercase())
    };
    let (l1, l2) = (upper(0), upper(1));
    if l1.contains("(FORMAT V") && l1.contains("TEXT LINES") {
        return if l1.contains("UNCORRECTED") || l1.contains("RAW") {
            RecordFormat::CosmosV1
        } else {
            RecordFormat::CosmosV2
        };
    }
    if l1.contains("UNCORRECTED ACCELEROGRAM") {
        return RecordFormat::CsmipV1;
    }
    if (l1.contains("CORRECTED ACCELEROGRAM") && l2.contains("UNCORRECTED ACCELEROGRAM"))
        || l1.contains("RESPONSE AND FOURIER AMPLITUDE SPECTRA")
    {
        return RecordFormat::CsmipV2;
    }
    let starts = |p: &str| head.iter().any(|l| l.trim_start().starts_with(p));
    let first = head.first().map_or("", |l| l.trim_start());
    if first.starts_with("Origin Time") && starts("Sampling Freq") && starts("Scale Factor") {
        return RecordFormat::Knet;
    }
    if starts("SAMPLING_INTERVAL_S:") && starts("NDATA:") {
        return RecordFormat::Esm;
    }
    if head.get(3).is_some_and(|l| at2::header_fields(l).is_some()) || l1.starts_with("PEER") {
        return RecordFormat::PeerAt2;
    }
    RecordFormat::TwoColumn
}

/// Reads a record from the text of a file, as [`Record::parse`] documents.
pub(crate) fn read(text: &str, path: &Path, opts: &RecordOptions) -> Result<Record, RecordError> {
    let file = path.display().to_string();
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    // DOS end-of-file marks (Ctrl-Z) after the last line
    let text = text.trim_end_matches('\u{1a}');
    let at = || in_record(&file);
    if text.trim().is_empty() {
        return Err(RecordError::Empty { at: at() });
    }
    if let Some(dt) = opts.dt
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(RecordError::InvalidDt { at: at(), dt });
    }
    if let Some(value) = opts.scale_to_pga
        && !(value.is_finite() && value > 0.0)
    {
        return Err(RecordError::InvalidScale { at: at(), value });
    }
    if let Some(target) = &opts.scale_to_sa {
        if opts.scale_to_pga.is_some() {
            return Err(RecordError::ScaleConflict { at: at() });
        }
        target.check(at)?;
    }
    let has_at2_extension = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("at2"));
    let parsed = match detect(text) {
        RecordFormat::PeerAt2 => at2::read(text, &file)?,
        RecordFormat::CosmosV1 | RecordFormat::CosmosV2 => cosmos::read(text, &file)?,
        RecordFormat::CsmipV1 | RecordFormat::CsmipV2 => dmg::read(text, &file)?,
        RecordFormat::Knet => knet::read(text, &file)?,
        RecordFormat::Esm => esm::read(text, &file)?,
        // in no layout by its content: an .AT2 name says which layout's error to give
        _ if has_at2_extension => at2::read(text, &file)?,
        _ => columns::read(text, &file, path)?,
    };
    finish(parsed, &file, opts)
}

/// The component asked for, its units, time step, correction, processing and scale.
fn finish(parsed: Parsed, file: &str, opts: &RecordOptions) -> Result<Record, RecordError> {
    let at = || in_record(file);
    let Parsed {
        format,
        description,
        channels,
        default_units,
    } = parsed;
    let ch = select(channels, opts.component.as_ref(), file)?;
    let mut warnings = Vec::new();
    let units = match (opts.units, ch.units) {
        (Some(given), Some(stated)) if given != stated => {
            warnings.push(format!(
                "record \"{file}\": `units` = \"{}\" overrides the file's own units \"{}\" \
                 (values × {} instead of × {} to m/s²)",
                given.name(),
                stated.name(),
                given.to_m_s2(),
                stated.to_m_s2()
            ));
            given
        }
        (Some(given), _) => given,
        (None, Some(stated)) => stated,
        (None, None) => default_units,
    };
    if let Some(what) = &ch.uncorrected
        && opts.processing.is_none()
    {
        return Err(RecordError::Uncorrected {
            at: at(),
            what: what.clone(),
        });
    }
    let factor = units.to_m_s2();
    let (dt, mut accel) = match &ch.times {
        Some(times) => {
            // digitised film: resampled at the `dt` asked for (linear interpolation)
            let Some(dt) = opts.dt else {
                return Err(RecordError::InvalidProcessing {
                    at: at(),
                    reason: "the samples of this record are unequally spaced (a digitised \
                             film record): give `dt` to resample it at"
                        .into(),
                });
            };
            (dt, resample(times, &ch.values, dt, factor))
        }
        None => {
            let dt = match (ch.dt, opts.dt) {
                (Some(in_file), Some(given)) => {
                    if (given - in_file).abs() > DT_REL_TOLERANCE * in_file {
                        return Err(RecordError::DtMismatch {
                            at: at(),
                            given,
                            in_file,
                        });
                    }
                    in_file
                }
                (Some(in_file), None) => in_file,
                (None, Some(given)) => given,
                (None, None) => return Err(RecordError::MissingDt { at: at() }),
            };
            (dt, ch.values.iter().map(|v| v * factor).collect())
        }
    };
    if !(dt.is_finite() && dt > 0.0) {
        return Err(RecordError::InvalidDt { at: at(), dt });
    }
    if let Some(p) = &opts.processing {
        if accel.len() < 2 {
            return Err(RecordError::TooFewSamples {
                at: at(),
                found: accel.len(),
            });
        }
        accel = p
            .apply(&accel, dt)
            .map_err(|reason| RecordError::InvalidProcessing { at: at(), reason })?;
    }
    let scaling = match (opts.scale_to_pga, &opts.scale_to_sa) {
        (Some(_), Some(_)) => return Err(RecordError::ScaleConflict { at: at() }),
        (Some(pga_g), None) => Some(scale::to_pga(&mut accel, pga_g, at)?),
        (None, Some(target)) => Some(scale::to_sa(&mut accel, dt, target, at)?),
        (None, None) => None,
    };
    let mut record = build(dt, accel, description, format, file)?;
    record.component = ch.names.first().cloned().filter(|n| !n.is_empty());
    record.file_units = ch.units;
    record.stated_peak = ch.stated_peak.map(|(p, time)| StatedPeak {
        accel: p * ch.units.unwrap_or(default_units).to_m_s2(),
        time,
    });
    record.processing = opts.processing;
    record.scaling = scaling;
    record.warnings = warnings;
    Ok(record)
}

/// Linear interpolation of (t, a) pairs onto t = k·dt from the first time, in m/s².
fn resample(times: &[f64], values: &[f64], dt: f64, factor: f64) -> Vec<f64> {
    let (Some(&t0), Some(&t1)) = (times.first(), times.last()) else {
        return Vec::new();
    };
    let n = ((t1 - t0) / dt).floor() as usize + 1;
    let mut out = Vec::with_capacity(n.min(100_000_000));
    let mut j = 0;
    for k in 0..n {
        let t = t0 + k as f64 * dt;
        while j + 2 < times.len() && times[j + 1] <= t {
            j += 1;
        }
        let (ta, tb) = (times[j], times[(j + 1).min(times.len() - 1)]);
        let (va, vb) = (values[j], values[(j + 1).min(values.len() - 1)]);
        let a = if tb > ta {
            va + (vb - va) * (t - ta) / (tb - ta)
        } else {
            va
        };
        out.push(a * factor);
    }
    out
}

/// A name reduced for matching: upper case, no blanks, no trailing `DEG`.
fn normalise(name: &str) -> String {
    let n: String = name
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    n.strip_suffix("DEG")
        .or_else(|| n.strip_suffix('°'))
        .map_or(n.clone(), str::to_string)
}

/// The components of a file as an error lists them: `1: Chan 1: 360 Deg ("1", "360", "NS")`.
pub fn component_list(channels: &[Channel]) -> Vec<String> {
    channels
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let label = c.names.first().map_or("", String::as_str);
            let also: Vec<String> = c.names.iter().skip(1).map(|n| format!("\"{n}\"")).collect();
            if also.is_empty() {
                format!("{}: {label}", i + 1)
            } else {
                format!("{}: {label} (or {})", i + 1, also.join(", "))
            }
        })
        .collect()
}

fn select(
    mut channels: Vec<Channel>,
    want: Option<&Component>,
    file: &str,
) -> Result<Channel, RecordError> {
    let at = || in_record(file);
    let n = channels.len();
    let index = match want {
        None if n == 1 => 0,
        None => {
            // a name that is not a number, to show that names work
            let example = channels
                .get(1)
                .and_then(|c| {
                    c.names
                        .iter()
                        .skip(1)
                        .find(|n| n.parse::<f64>().is_err())
                        .or(c.names.first())
                })
                .cloned()
                .unwrap_or_else(|| "2".into());
            return Err(RecordError::ComponentNeeded {
                at: at(),
                components: component_list(&channels),
                example,
            });
        }
        Some(Component::Index(i)) if (1..=n).contains(i) => i - 1,
        Some(Component::Name(name)) => {
            let key = normalise(name);
            let by_name = channels
                .iter()
                .position(|c| c.names.iter().any(|n| normalise(n) == key));
            match by_name.or_else(|| {
                key.parse::<usize>()
                    .ok()
                    .filter(|i| (1..=n).contains(i))
                    .map(|i| i - 1)
            }) {
                Some(i) => i,
                None => {
                    return Err(RecordError::NoSuchComponent {
                        at: at(),
                        asked: name.clone(),
                        components: component_list(&channels),
                    });
                }
            }
        }
        Some(c) => {
            return Err(RecordError::NoSuchComponent {
                at: at(),
                asked: c.to_string(),
                components: component_list(&channels),
            });
        }
    };
    Ok(channels.swap_remove(index))
}

/// The names a horizontal or vertical component answers to, from its azimuth in degrees
/// (clockwise from north) or `None` for a vertical one: the angle, and `NS`/`EW`/`UP` where
/// it is one of those.
pub(crate) fn orientation_names(azimuth: Option<f64>) -> Vec<String> {
    match azimuth {
        None => vec!["UP".into(), "UD".into(), "Z".into()],
        Some(az) => {
            let a = az.rem_euclid(360.0);
            let mut out = vec![format!("{}", az)];
            if a == 0.0 || a == 180.0 {
                out.push("NS".into());
                out.push("N".into());
            } else if a == 90.0 || a == 270.0 {
                out.push("EW".into());
                out.push("E".into());
            }
            out
        }
    }
}

#[cfg(test)]
mod tests;
