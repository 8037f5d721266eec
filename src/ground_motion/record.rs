//! Ground-motion records: reading equally spaced ground-acceleration files and
//! evaluating the ground acceleration `a_g(t)` (m/s²) and velocity `v_g(t)` (m/s).
//!
//! Supported formats (see [`RecordFormat`]):
//!
//! * **PEER NGA `.AT2`** — four header lines, then the values (in g unless told
//!   otherwise), several per line. The 4th header line gives the number of points and
//!   the time step in any of the forms `NPTS=   7995, DT=   .0050 SEC,` (NGA-West2),
//!   `NPTS=  2000, DT= .02000 SEC` (older files) or `4164    0.0100    NPTS, DT`
//!   (NGA-West1), case-insensitive and with flexible spacing. A file is read as AT2 when
//!   its extension is `.AT2` (any case) or when its 4th line has one of these forms.
//! * **Two columns** `t a`, separated by whitespace, commas or semicolons.
//! * **Single column** `a`, one value per line; the time step must be given.
//!
//! In the two text formats, blank lines and lines whose first non-blank character is `#`
//! are skipped, and the first remaining line may be a non-numeric header such as `t,a`
//! or `time (s), accel (g)` (it is recognised by its first field not being a number).
//!
//! Acceleration is linear between samples and zero after the end of the record (free
//! vibration, as OpenSees' `Path` time series); the velocity is its exact integral with
//! `v_g(0) = 0`, piecewise quadratic between samples and constant after the end.

use std::fmt;
use std::path::Path;

/// Standard gravity, m/s², used to convert accelerations given in g.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Relative tolerance on time steps: the spacing of a two-column file must be uniform
/// to this fraction of `dt`, and a `dt` option must agree with the file's to it.
pub const DT_REL_TOLERANCE: f64 = 1e-6;

/// Longest piece of user text quoted in an error message, in characters.
const MAX_QUOTED_CHARS: usize = 60;

/// Units of the acceleration values in a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccelUnits {
    /// Multiples of standard gravity, [`STANDARD_GRAVITY`] = 9.80665 m/s².
    G,
    /// Metres per second squared, m/s².
    MetersPerSecond2,
}

impl AccelUnits {
    /// Factor that converts a value in these units to m/s² (9.80665 for g, 1 for m/s²).
    pub fn to_m_s2(self) -> f64 {
        match self {
            AccelUnits::G => STANDARD_GRAVITY,
            AccelUnits::MetersPerSecond2 => 1.0,
        }
    }
}

/// How to read a record file.
#[derive(Debug, Clone, Default)]
pub struct RecordOptions {
    /// Units of the values in the file. `None`: g for PEER `.AT2` files, m/s² for the
    /// two-column and single-column formats.
    pub units: Option<AccelUnits>,
    /// Time step, s. Required for single-column files. For the formats that carry their
    /// own time step (AT2, two-column) it may be given only if it agrees with the file's
    /// to [`DT_REL_TOLERANCE`] (relative); otherwise reading fails.
    pub dt: Option<f64>,
    /// Target peak ground acceleration, in g: when set, the whole record is scaled so
    /// that max |a| equals `scale_to_pga · 9.80665` m/s². Must be positive and finite.
    pub scale_to_pga: Option<f64>,
}

/// The layout a record was read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RecordFormat {
    /// PEER NGA `.AT2`: four header lines with NPTS and DT, then the values.
    PeerAt2,
    /// Two columns: time (s) and acceleration.
    TwoColumn,
    /// One acceleration value per line; the time step comes from [`RecordOptions::dt`].
    /// Also used for records built with [`Record::from_samples`].
    SingleColumn,
}

/// Where a problem is: the file (or, for [`Record::from_samples`], the description) and
/// the 1-based line number when there is one. Displays as `record "x.AT2", line 7`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file as given (or the record's description).
    pub file: String,
    /// 1-based line number, if the problem is on one line.
    pub line: Option<usize>,
}

impl Location {
    fn file(file: &str) -> Location {
        Location {
            file: file.to_string(),
            line: None,
        }
    }

    fn line(file: &str, line: usize) -> Location {
        Location {
            file: file.to_string(),
            line: Some(line),
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "record \"{}\"", self.file)?;
        if let Some(line) = self.line {
            write!(f, ", line {line}")?;
        }
        Ok(())
    }
}

/// Everything that can go wrong when reading or building a record. Every message starts
/// with the file (and the line, when there is one), e.g.
/// `record "x.AT2", line 7: "abc" is not a number`.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The path is not a regular file (a FIFO, a device, a directory): refused before it is
    /// opened, since reading a FIFO would block for ever and a device may never end.
    #[error("{at}: not a regular file ({kind}): a record must be a file on disk")]
    NotAFile {
        /// The file.
        at: Location,
        /// What it is instead.
        kind: &'static str,
    },
    /// The file is larger than a record can be.
    #[error(
        "{at}: the file is {size} bytes, more than the {limit} bytes a record may have \
         (about 10⁸ samples); is it the right file?"
    )]
    TooLarge {
        /// The file.
        at: Location,
        /// Its size, bytes.
        size: u64,
        /// The limit, bytes ([`MAX_RECORD_BYTES`]).
        limit: u64,
    },
    /// The file could not be read.
    #[error("{at}: cannot read the file: {source}")]
    Io {
        /// The file.
        at: Location,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// The file has nothing but white space.
    #[error("{at}: the file is empty")]
    Empty {
        /// The file.
        at: Location,
    },
    /// An `.AT2` file with fewer than the four header lines.
    #[error(
        "{at}: the file has only {lines} line(s); a PEER .AT2 file needs 4 header lines, \
         the 4th containing NPTS and DT (e.g. \"NPTS=   7995, DT=   .0050 SEC,\")"
    )]
    MissingHeader {
        /// The file.
        at: Location,
        /// Number of lines in the file.
        lines: usize,
    },
    /// The 4th line of an `.AT2` file does not give NPTS and DT.
    #[error(
        "{at}: expected the 4th line of a PEER .AT2 file to contain NPTS and DT, as \
         \"NPTS=   7995, DT=   .0050 SEC,\" or \"4164    0.0100    NPTS, DT\", found {found:?}"
    )]
    BadHeader {
        /// The file and line 4.
        at: Location,
        /// The line found (shortened).
        found: String,
    },
    /// The AT2 header says the file holds velocities or displacements.
    #[error("{at}: this is not an acceleration record (the header says {found:?})")]
    NotAcceleration {
        /// The file and line 3.
        at: Location,
        /// The header line (shortened).
        found: String,
    },
    /// The AT2 header announces more values than the file holds.
    #[error("{at}: the header gives NPTS = {npts} but only {found} values follow")]
    TooFewValues {
        /// The file and the header line.
        at: Location,
        /// NPTS from the header.
        npts: usize,
        /// Number of values found.
        found: usize,
    },
    /// The AT2 file holds more values than its header announces.
    #[error("{at}: more values than NPTS = {npts} given in the header (the file has {found})")]
    TooManyValues {
        /// The file and the line of the first value beyond NPTS.
        at: Location,
        /// NPTS from the header.
        npts: usize,
        /// Number of values found.
        found: usize,
    },
    /// A field that should be a number is not one.
    #[error("{at}: {token:?} is not a number")]
    NotANumber {
        /// The file and line.
        at: Location,
        /// The field (shortened).
        token: String,
    },
    /// A value is NaN or infinite.
    #[error("{at}: {token:?} is not a finite number")]
    NonFinite {
        /// The file and line.
        at: Location,
        /// The field (shortened).
        token: String,
    },
    /// A value is finite in the file's units but overflows when converted to m/s².
    #[error("{at}: {token:?} is too large to convert to m/s²")]
    OutOfRange {
        /// The file and line.
        at: Location,
        /// The field (shortened).
        token: String,
    },
    /// The times of a two-column file are not equally spaced.
    #[error(
        "{at}: time step {} s differs from the first time step {} s; \
         the spacing must be uniform (to 1e-6 relative)",
        short(*.spacing),
        short(*.dt)
    )]
    NonUniformSpacing {
        /// The file and the line of the later of the two samples.
        at: Location,
        /// The first time step, t[1] − t[0], s.
        dt: f64,
        /// The time step ending at this line, s.
        spacing: f64,
    },
    /// The times of a two-column file do not increase.
    #[error("{at}: time {time} s does not increase (the previous time is {previous} s)")]
    TimeNotIncreasing {
        /// The file and line.
        at: Location,
        /// The previous time, s.
        previous: f64,
        /// The time on this line, s.
        time: f64,
    },
    /// A single-column file was read without a time step.
    #[error(
        "{at}: a single-column file has no times, so its time step is needed: \
         give `dt` in [ground_motion]"
    )]
    MissingDt {
        /// The file.
        at: Location,
    },
    /// A time step (from the file or the options) is not positive and finite.
    #[error("{at}: the time step dt = {dt} s must be positive and finite")]
    InvalidDt {
        /// The file, and the header line if the value is from there.
        at: Location,
        /// The offending value, s.
        dt: f64,
    },
    /// The `dt` option disagrees with the time step in the file.
    #[error(
        "{at}: `dt` = {given} s was given but the file's time step is {in_file} s; \
         leave `dt` out for this file"
    )]
    DtMismatch {
        /// The file.
        at: Location,
        /// The `dt` option, s.
        given: f64,
        /// The time step in the file, s.
        in_file: f64,
    },
    /// The first data line of a text file has neither 1 nor 2 numbers.
    #[error(
        "{at}: expected 1 number (acceleration) or 2 numbers (time, acceleration) per line, \
         found {found} (if this is a PEER .AT2 file, its 4 header lines are missing)"
    )]
    UnrecognisedLayout {
        /// The file and the first data line.
        at: Location,
        /// Number of fields found.
        found: usize,
    },
    /// A data line has a different number of fields from the first one.
    #[error("{at}: {found} field(s) on this line, expected {expected}")]
    FieldCount {
        /// The file and line.
        at: Location,
        /// Fields per line, from the first data line.
        expected: usize,
        /// Fields on this line.
        found: usize,
    },
    /// The record has fewer than 2 samples.
    #[error("{at}: {found} sample(s) found; a record needs at least 2")]
    TooFewSamples {
        /// The file.
        at: Location,
        /// Number of samples.
        found: usize,
    },
    /// `scale_to_pga` is not positive and finite.
    #[error("{at}: scale_to_pga = {value} g must be positive and finite")]
    InvalidScale {
        /// The file.
        at: Location,
        /// The offending value, g.
        value: f64,
    },
    /// `scale_to_pga` was asked for a record whose accelerations are all zero.
    #[error("{at}: cannot scale to a PGA: every acceleration in the record is 0")]
    ZeroPga {
        /// The file.
        at: Location,
    },
    /// The integrated velocity overflows f64.
    #[error("{at}: the ground velocity overflows (accelerations or time step too large)")]
    VelocityOverflow {
        /// The file.
        at: Location,
    },
}

/// An equally spaced ground-acceleration record with its integrated velocity.
///
/// The `pub` fields are for reading; changing `accel` or `dt` in place leaves the
/// stored velocity stale (build a new record with [`Record::from_samples`] instead).
/// The evaluation methods never panic, even then.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Sample spacing, s.
    pub dt: f64,
    /// Ground acceleration, m/s²; sample k is at t = k·dt (the first sample at t = 0).
    pub accel: Vec<f64>,
    /// Ground velocity at the samples, m/s: the exact integral of the piecewise-linear
    /// acceleration, with v(0) = 0.
    velocity: Vec<f64>,
    /// The layout the record was read from.
    pub format: RecordFormat,
    /// Human-readable description: the AT2 header lines 2–3, or the file name.
    pub description: String,
}

/// Largest record file read, bytes (500 MB: about 10⁸ samples of a one-column file), so that a
/// wrong path (a disk image, `/dev/zero`) is refused before it takes the memory.
pub const MAX_RECORD_BYTES: u64 = 500_000_000;

/// Opens a record file for reading after checking, without opening it, that it is a regular
/// file no larger than [`MAX_RECORD_BYTES`] (opening a FIFO blocks until a writer comes).
pub fn open_record_file(path: &Path) -> Result<std::fs::File, RecordError> {
    let at = || Location::file(&path.display().to_string());
    let meta = std::fs::metadata(path).map_err(|source| RecordError::Io { at: at(), source })?;
    let ft = meta.file_type();
    if !ft.is_file() {
        let kind = if ft.is_dir() {
            "a directory"
        } else {
            special_kind(&ft)
        };
        return Err(RecordError::NotAFile { at: at(), kind });
    }
    if meta.len() > MAX_RECORD_BYTES {
        return Err(RecordError::TooLarge {
            at: at(),
            size: meta.len(),
            limit: MAX_RECORD_BYTES,
        });
    }
    std::fs::File::open(path).map_err(|source| RecordError::Io { at: at(), source })
}

#[cfg(unix)]
fn special_kind(ft: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if ft.is_fifo() {
        "a FIFO"
    } else if ft.is_char_device() || ft.is_block_device() {
        "a device"
    } else if ft.is_socket() {
        "a socket"
    } else {
        "not a regular file"
    }
}

#[cfg(not(unix))]
fn special_kind(_: &std::fs::FileType) -> &'static str {
    "not a regular file"
}

impl Record {
    /// Builds a record from accelerations `accel_m_s2` (m/s²) sampled every `dt` seconds,
    /// the first at t = 0. Fails unless `dt` is positive and finite, there are at least
    /// 2 samples and all are finite. The format is set to [`RecordFormat::SingleColumn`];
    /// error messages name the record by `description`.
    pub fn from_samples(
        dt: f64,
        accel_m_s2: Vec<f64>,
        description: String,
    ) -> Result<Record, RecordError> {
        let file = description.clone();
        if let Some(k) = accel_m_s2.iter().position(|a| !a.is_finite()) {
            let token = accel_m_s2
                .get(k)
                .map_or_else(String::new, |a| format!("{a} (sample {k})"));
            return Err(RecordError::NonFinite {
                at: Location::file(&file),
                token,
            });
        }
        build(
            dt,
            accel_m_s2,
            description,
            RecordFormat::SingleColumn,
            &file,
        )
    }

    /// Reads a record file; see [`Record::parse`] for the formats and options. Bytes that
    /// are not UTF-8 (e.g. Latin-1 station names in a header) are replaced, not refused.
    pub fn read(path: &Path, opts: &RecordOptions) -> Result<Record, RecordError> {
        let at = || Location::file(&path.display().to_string());
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

    /// Parses the bytes of a record file, as [`Record::read`] does after reading them: bytes
    /// that are not UTF-8 are replaced, then [`Record::parse`]. `path` is used only in error
    /// messages, for the description and to detect the `.AT2` extension (the fuzz targets of
    /// `fuzz/` call this).
    pub fn from_bytes(
        bytes: &[u8],
        path: &Path,
        opts: &RecordOptions,
    ) -> Result<Record, RecordError> {
        let text = String::from_utf8_lossy(bytes);
        Record::parse(&text, path, opts)
    }

    /// Parses the text of a record file. `path` is used only in error messages, for the
    /// description of non-AT2 records, and to detect the `.AT2` extension.
    ///
    /// Two-column files take dt = t[1] − t[0] and treat the first sample as t = 0: a
    /// nonzero t[0] is an offset that is ignored.
    pub fn parse(text: &str, path: &Path, opts: &RecordOptions) -> Result<Record, RecordError> {
        let file = path.display().to_string();
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        if text.trim().is_empty() {
            return Err(RecordError::Empty {
                at: Location::file(&file),
            });
        }
        if let Some(dt) = opts.dt
            && !(dt.is_finite() && dt > 0.0)
        {
            return Err(RecordError::InvalidDt {
                at: Location::file(&file),
                dt,
            });
        }
        if let Some(value) = opts.scale_to_pga
            && !(value.is_finite() && value > 0.0)
        {
            return Err(RecordError::InvalidScale {
                at: Location::file(&file),
                value,
            });
        }

        let has_at2_extension = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("at2"));
        let fourth_line_is_header = text.lines().nth(3).and_then(at2_header_fields).is_some();

        let parsed = if has_at2_extension || fourth_line_is_header {
            parse_at2(text, &file, opts)?
        } else {
            parse_columns(text, &file, path, opts)?
        };

        let dt = match (parsed.dt, opts.dt) {
            (Some(in_file), Some(given)) => {
                if (given - in_file).abs() > DT_REL_TOLERANCE * in_file {
                    return Err(RecordError::DtMismatch {
                        at: Location::file(&file),
                        given,
                        in_file,
                    });
                }
                in_file
            }
            (Some(in_file), None) => in_file,
            (None, Some(given)) => given,
            (None, None) => {
                return Err(RecordError::MissingDt {
                    at: Location::file(&file),
                });
            }
        };

        let mut accel = parsed.accel;
        if let Some(target_g) = opts.scale_to_pga {
            let pga = max_abs(&accel);
            if pga <= 0.0 {
                return Err(RecordError::ZeroPga {
                    at: Location::file(&file),
                });
            }
            // a / pga is within [-1, 1], so this cannot overflow.
            let target = target_g * STANDARD_GRAVITY;
            for a in &mut accel {
                *a = *a / pga * target;
            }
        }
        build(dt, accel, parsed.description, parsed.format, &file)
    }

    /// Number of samples.
    pub fn num_samples(&self) -> usize {
        self.accel.len()
    }

    /// Ground velocity at the samples, m/s (v at t = k·dt; v(0) = 0).
    pub fn velocity_samples(&self) -> &[f64] {
        &self.velocity
    }

    /// Duration of the record, s: (n − 1)·dt, the time of the last sample.
    pub fn duration(&self) -> f64 {
        self.accel.len().saturating_sub(1) as f64 * self.dt
    }

    /// Peak ground acceleration, m/s²: max |a| over the samples.
    pub fn pga(&self) -> f64 {
        max_abs(&self.accel)
    }

    /// Ground acceleration at time `t` (s), m/s²: linear between samples, 0 before t = 0
    /// and after the end of the record (free vibration); NaN for a NaN `t`.
    pub fn accel_at(&self, t: f64) -> f64 {
        self.accel_and_velocity_at(t).0
    }

    /// Ground velocity at time `t` (s), m/s: the exact integral of [`Record::accel_at`]
    /// from 0 to `t` (piecewise quadratic between samples), 0 for t ≤ 0 and constant after
    /// the end of the record; NaN for a NaN `t`.
    pub fn velocity_at(&self, t: f64) -> f64 {
        self.accel_and_velocity_at(t).1
    }

    /// Ground acceleration (m/s²) and velocity (m/s) at time `t` (s), as
    /// [`Record::accel_at`] and [`Record::velocity_at`], with one index computation:
    /// O(1), no allocation.
    #[inline]
    pub fn accel_and_velocity_at(&self, t: f64) -> (f64, f64) {
        if t.is_nan() {
            return (f64::NAN, f64::NAN);
        }
        if t < 0.0 {
            return (0.0, 0.0);
        }
        let n = self.accel.len().min(self.velocity.len());
        if n < 2 {
            return (0.0, 0.0);
        }
        let last = n - 1;
        let dt = self.dt;
        let end = last as f64 * dt;
        if t >= end {
            let v_end = self.velocity.get(last).copied().unwrap_or(0.0);
            // Exactly at the last sample: its value; after it: free vibration.
            let a_end = if t == end {
                self.accel.get(last).copied().unwrap_or(0.0)
            } else {
                0.0
            };
            return (a_end, v_end);
        }
        // t / dt ≥ 0 here; `as` saturates (and maps NaN to 0), so k is in 0..last.
        let mut k = ((t / dt) as usize).min(last - 1);
        // t / dt may round just below an integer: at t = j·dt use sample j exactly.
        if k + 1 < last && (k + 1) as f64 * dt <= t {
            k += 1;
        }
        let (Some(&a0), Some(&a1), Some(&v0)) = (
            self.accel.get(k),
            self.accel.get(k + 1),
            self.velocity.get(k),
        ) else {
            return (0.0, 0.0);
        };
        let tau = t - k as f64 * dt;
        let slope = (a1 - a0) / dt;
        let a = a0 + slope * tau;
        let v = v0 + tau * (a0 + 0.5 * slope * tau);
        (a, v)
    }
}

/// Result of parsing a file, before the time step is settled and the velocity computed.
struct Parsed {
    /// Time step from the file, if the format has one, s.
    dt: Option<f64>,
    /// Accelerations, m/s².
    accel: Vec<f64>,
    format: RecordFormat,
    description: String,
}

/// Validates and builds a record, integrating the velocity.
fn build(
    dt: f64,
    accel: Vec<f64>,
    description: String,
    format: RecordFormat,
    file: &str,
) -> Result<Record, RecordError> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(RecordError::InvalidDt {
            at: Location::file(file),
            dt,
        });
    }
    if accel.len() < 2 {
        return Err(RecordError::TooFewSamples {
            at: Location::file(file),
            found: accel.len(),
        });
    }
    let mut velocity = Vec::with_capacity(accel.len());
    let mut v = 0.0;
    velocity.push(v);
    for pair in accel.windows(2) {
        if let [a0, a1] = pair {
            v += 0.5 * dt * (a0 + a1);
        }
        velocity.push(v);
    }
    if !velocity.iter().all(|v| v.is_finite()) {
        return Err(RecordError::VelocityOverflow {
            at: Location::file(file),
        });
    }
    Ok(Record {
        dt,
        accel,
        velocity,
        format,
        description,
    })
}

/// Rounds `x` to 12 significant digits for messages, so that a time step computed as
/// 0.035 − 0.02 prints as 0.015 rather than 0.015000000000000003.
fn short(x: f64) -> f64 {
    if !x.is_finite() || x == 0.0 {
        return x;
    }
    let scale = 10f64.powi(11 - x.abs().log10().floor() as i32);
    let rounded = (x * scale).round() / scale;
    if rounded.is_finite() { rounded } else { x }
}

fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0_f64, |m, a| m.max(a.abs()))
}

/// Shortens user text for quoting in an error message.
fn clip(text: &str) -> String {
    let text = text.trim();
    if text.chars().count() > MAX_QUOTED_CHARS {
        let mut s: String = text.chars().take(MAX_QUOTED_CHARS).collect();
        s.push('…');
        s
    } else {
        text.to_string()
    }
}

/// Parses one value and converts it to m/s² with `factor`.
fn parse_value(token: &str, factor: f64, file: &str, line: usize) -> Result<f64, RecordError> {
    let x = parse_number(token, file, line)?;
    let a = x * factor;
    if a.is_finite() {
        Ok(a)
    } else {
        Err(RecordError::OutOfRange {
            at: Location::line(file, line),
            token: clip(token),
        })
    }
}

/// Parses one finite number (Fortran forms like `.1394908E-02` included).
fn parse_number(token: &str, file: &str, line: usize) -> Result<f64, RecordError> {
    match token.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(RecordError::NonFinite {
            at: Location::line(file, line),
            token: clip(token),
        }),
        Err(_) => Err(RecordError::NotANumber {
            at: Location::line(file, line),
            token: clip(token),
        }),
    }
}

/// If `token` (upper case) is a number, possibly with a glued `SEC`/`SECS`/`S` unit,
/// returns the number part.
fn number_part(token: &str) -> Option<&str> {
    let s = ["SECS", "SEC", "S"]
        .iter()
        .find_map(|unit| token.strip_suffix(unit))
        .filter(|s| !s.is_empty())
        .unwrap_or(token);
    s.parse::<f64>().is_ok().then_some(s)
}

/// If `line` is the 4th line of a PEER AT2 file, returns its NPTS and DT fields (text).
///
/// Accepted, case-insensitive and with any spacing: `NPTS= 7995, DT= .0050 SEC,`,
/// `NPTS= 2000, DT= .02000 SEC` and `4164 0.0100 NPTS, DT`.
fn at2_header_fields(line: &str) -> Option<(String, String)> {
    let upper: String = line
        .chars()
        .map(|c| match c {
            ',' | '=' | ':' | ';' => ' ',
            c => c.to_ascii_uppercase(),
        })
        .collect();
    let tokens: Vec<&str> = upper.split_whitespace().collect();
    let npts_pos = tokens.iter().position(|t| *t == "NPTS")?;
    let dt_pos = tokens.iter().position(|t| *t == "DT")?;
    let number_after = |pos: usize| tokens.get(pos + 1).and_then(|t| number_part(t));
    if let (Some(n), Some(d)) = (number_after(npts_pos), number_after(dt_pos)) {
        return Some((n.to_string(), d.to_string()));
    }
    // NGA-West1: the two numbers first, then the keywords in the same order.
    if npts_pos < dt_pos {
        let n = tokens.first().and_then(|t| number_part(t))?;
        let d = tokens.get(1).and_then(|t| number_part(t))?;
        if npts_pos >= 2 {
            return Some((n.to_string(), d.to_string()));
        }
    }
    None
}

/// Parses NPTS: a non-negative integer (written `7995`, or `7995.` / `7.995E3`).
fn parse_npts(token: &str) -> Option<usize> {
    if let Ok(n) = token.parse::<usize>() {
        return Some(n);
    }
    let x = token.parse::<f64>().ok()?;
    // Below 2^53, so the conversion is exact.
    (x.is_finite() && x >= 0.0 && x.fract() == 0.0 && x < 9.0e15).then_some(x as usize)
}

fn parse_at2(text: &str, file: &str, opts: &RecordOptions) -> Result<Parsed, RecordError> {
    let header: Vec<&str> = text.lines().take(4).collect();
    let [_, line2, line3, line4] = *header.as_slice() else {
        return Err(RecordError::MissingHeader {
            at: Location::file(file),
            lines: header.len(),
        });
    };

    let bad_header = || RecordError::BadHeader {
        at: Location::line(file, 4),
        found: clip(line4),
    };
    let (npts_text, dt_text) = at2_header_fields(line4).ok_or_else(bad_header)?;
    let npts = parse_npts(&npts_text).ok_or_else(bad_header)?;
    let dt = dt_text.parse::<f64>().map_err(|_| bad_header())?;
    if !(dt.is_finite() && dt > 0.0) {
        return Err(RecordError::InvalidDt {
            at: Location::line(file, 4),
            dt,
        });
    }
    let line3_upper = line3.to_ascii_uppercase();
    if line3_upper.contains("VELOCITY") || line3_upper.contains("DISPLACEMENT") {
        return Err(RecordError::NotAcceleration {
            at: Location::line(file, 3),
            found: clip(line3),
        });
    }

    let factor = opts.units.unwrap_or(AccelUnits::G).to_m_s2();
    // Do not trust NPTS for the allocation: each value takes at least 2 bytes.
    let mut accel = Vec::with_capacity(npts.min(text.len() / 2 + 1));
    let mut found = 0_usize;
    let mut first_extra_line = None;
    for (i, line) in text.lines().enumerate().skip(4) {
        let line_no = i + 1;
        for token in line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
        {
            let a = parse_value(token, factor, file, line_no)?;
            found += 1;
            if found <= npts {
                accel.push(a);
            } else if first_extra_line.is_none() {
                first_extra_line = Some(line_no);
            }
        }
    }
    if let Some(line_no) = first_extra_line {
        return Err(RecordError::TooManyValues {
            at: Location::line(file, line_no),
            npts,
            found,
        });
    }
    if found < npts {
        return Err(RecordError::TooFewValues {
            at: Location::line(file, 4),
            npts,
            found,
        });
    }

    let description = [line2.trim(), line3.trim()]
        .into_iter()
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    Ok(Parsed {
        dt: Some(dt),
        accel,
        format: RecordFormat::PeerAt2,
        description: if description.is_empty() {
            file.to_string()
        } else {
            description
        },
    })
}

fn parse_columns(
    text: &str,
    file: &str,
    path: &Path,
    opts: &RecordOptions,
) -> Result<Parsed, RecordError> {
    let factor = opts.units.unwrap_or(AccelUnits::MetersPerSecond2).to_m_s2();
    let mut columns: Option<usize> = None;
    let mut header_allowed = true;
    let mut accel = Vec::new();
    // Time of the first sample, the first time step, and the time of the previous sample.
    let mut t_first: Option<f64> = None;
    let mut dt: Option<f64> = None;
    let mut t_prev = 0.0;

    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut fields = line
            .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .filter(|t| !t.is_empty());
        let count = fields.clone().count();
        let first = fields.next().unwrap_or("");
        if header_allowed {
            header_allowed = false;
            if first.parse::<f64>().is_err() {
                continue; // the optional header line
            }
        }
        let expected = match columns {
            Some(c) => c,
            None if count == 1 || count == 2 => {
                columns = Some(count);
                count
            }
            None => {
                return Err(RecordError::UnrecognisedLayout {
                    at: Location::line(file, line_no),
                    found: count,
                });
            }
        };
        if count != expected {
            return Err(RecordError::FieldCount {
                at: Location::line(file, line_no),
                expected,
                found: count,
            });
        }
        if expected == 1 {
            accel.push(parse_value(first, factor, file, line_no)?);
            continue;
        }

        let t = parse_number(first, file, line_no)?;
        let a = parse_value(fields.next().unwrap_or(""), factor, file, line_no)?;
        match (t_first, dt) {
            (None, _) => t_first = Some(t),
            (Some(t0), None) => {
                // Times are finite, so the step is never NaN (it may overflow to ∞).
                let step = t - t0;
                if step <= 0.0 {
                    return Err(RecordError::TimeNotIncreasing {
                        at: Location::line(file, line_no),
                        previous: t0,
                        time: t,
                    });
                }
                if !step.is_finite() {
                    return Err(RecordError::InvalidDt {
                        at: Location::line(file, line_no),
                        dt: step,
                    });
                }
                dt = Some(step);
            }
            (Some(_), Some(dt)) => {
                let step = t - t_prev;
                if step <= 0.0 {
                    return Err(RecordError::TimeNotIncreasing {
                        at: Location::line(file, line_no),
                        previous: t_prev,
                        time: t,
                    });
                }
                if (step - dt).abs() > DT_REL_TOLERANCE * dt {
                    return Err(RecordError::NonUniformSpacing {
                        at: Location::line(file, line_no),
                        dt,
                        spacing: step,
                    });
                }
            }
        }
        t_prev = t;
        accel.push(a);
    }

    let (format, dt) = match columns {
        Some(2) => {
            if accel.len() < 2 {
                return Err(RecordError::TooFewSamples {
                    at: Location::file(file),
                    found: accel.len(),
                });
            }
            (RecordFormat::TwoColumn, dt)
        }
        Some(_) => (RecordFormat::SingleColumn, None),
        None => {
            return Err(RecordError::TooFewSamples {
                at: Location::file(file),
                found: 0,
            });
        }
    };
    let description = path
        .file_name()
        .map_or_else(|| file.to_string(), |n| n.to_string_lossy().into_owned());
    Ok(Parsed {
        dt,
        accel,
        format,
        description,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Directory of the real PEER records bundled with the tests (`tests/data/records/`, with
    /// their source in its README).
    const GROUND_MOTIONS_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/records");

    const G: f64 = STANDARD_GRAVITY;

    /// (file, NPTS, DT in s, PGA in g) from `tests/data/records/README.md` (the data set's own description).
    const README_FACTS: [(&str, usize, f64, f64); 5] = [
        ("RSN753_LOMAP_CLS000.AT2", 7995, 0.005, 0.645),
        ("RSN786_LOMAP_PAE055.AT2", 11999, 0.005, 0.215),
        ("RSN753_LOMAP_CLS090.AT2", 7999, 0.005, 0.483),
        ("RSN808_LOMAP_TRI000.AT2", 7999, 0.005, 0.100),
        ("RSN813_LOMAP_YBI090.AT2", 7999, 0.005, 0.068),
    ];

    fn data_file(name: &str) -> PathBuf {
        Path::new(GROUND_MOTIONS_DIR).join(name)
    }

    fn parse(text: &str, name: &str, opts: &RecordOptions) -> Result<Record, RecordError> {
        Record::parse(text, Path::new(name), opts)
    }

    fn ok(text: &str, name: &str, opts: &RecordOptions) -> Record {
        match parse(text, name, opts) {
            Ok(r) => r,
            Err(e) => panic!("expected {name} to parse, got: {e}"),
        }
    }

    /// Parses text that must fail; checks that the message names the file and, if
    /// `line` is given, the line. Returns the error and its message.
    fn fails(
        text: &str,
        name: &str,
        opts: &RecordOptions,
        line: Option<usize>,
    ) -> (RecordError, String) {
        let e = match parse(text, name, opts) {
            Ok(r) => panic!("expected {name} to fail, got {} samples", r.num_samples()),
            Err(e) => e,
        };
        let msg = e.to_string();
        let head = match line {
            Some(l) => format!("record \"{name}\", line {l}: "),
            None => format!("record \"{name}\": "),
        };
        assert!(
            msg.starts_with(&head),
            "message {msg:?} should start with {head:?}"
        );
        (e, msg)
    }

    fn no_opts() -> RecordOptions {
        RecordOptions::default()
    }

    fn with_dt(dt: f64) -> RecordOptions {
        RecordOptions {
            dt: Some(dt),
            ..RecordOptions::default()
        }
    }

    fn with_scale(pga_g: f64) -> RecordOptions {
        RecordOptions {
            scale_to_pga: Some(pga_g),
            ..RecordOptions::default()
        }
    }

    fn rel_close(actual: f64, expected: f64, tol: f64) -> bool {
        (actual - expected).abs() <= tol * expected.abs().max(f64::MIN_POSITIVE)
    }

    /// Tiny deterministic generator (Knuth's MMIX LCG).
    struct Lcg(u64);
    impl Lcg {
        fn next_u64(&mut self) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            self.0 >> 11
        }
        fn below(&mut self, n: usize) -> usize {
            (self.next_u64() % n as u64) as usize
        }
        fn unit(&mut self) -> f64 {
            (self.next_u64() >> 11) as f64 / (1u64 << 42) as f64
        }
    }

    fn temp_path(name: &str) -> PathBuf {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let dir = std::env::temp_dir().join(format!(
            "pounding-record-test-{}-{nanos}-{n}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).expect("create temp dir");
        dir.join(name)
    }

    const AT2_HEAD: &str = "PEER NGA STRONG MOTION DATABASE RECORD\n\
                            Test event, 1/1/2000, Station, 0\n\
                            ACCELERATION TIME SERIES IN UNITS OF G\n";

    // ---------------------------------------------------------------- real records

    #[test]
    fn real_records_match_readme() {
        for (name, npts, dt, pga_g) in README_FACTS {
            let path = data_file(name);
            let r = Record::read(&path, &no_opts())
                .unwrap_or_else(|e| panic!("{name}: {e} (is GROUND_MOTIONS_DIR right?)"));
            assert_eq!(r.format, RecordFormat::PeerAt2, "{name}");
            assert_eq!(r.num_samples(), npts, "{name}");
            assert_eq!(r.velocity_samples().len(), npts, "{name}");
            assert!((r.dt - dt).abs() < 1e-12, "{name}: dt {}", r.dt);
            assert!(rel_close(r.duration(), (npts - 1) as f64 * dt, 1e-12));
            assert!(
                (r.pga() / G - pga_g).abs() < 0.0005,
                "{name}: PGA {} g, README {pga_g} g",
                r.pga() / G
            );
            assert!(r.description.contains("Loma Prieta"), "{}", r.description);
            // A dt option that agrees with the file is accepted; one that does not fails.
            assert!(Record::read(&path, &with_dt(0.005)).is_ok());
            let e = Record::read(&path, &with_dt(0.01)).unwrap_err();
            assert!(matches!(e, RecordError::DtMismatch { .. }), "{e}");
            assert!(e.to_string().contains(name));
        }
    }

    #[test]
    fn real_record_first_value_is_in_g() {
        // First value of RSN753_LOMAP_CLS000.AT2 is .1394908E-02 g.
        let r = Record::read(&data_file("RSN753_LOMAP_CLS000.AT2"), &no_opts()).unwrap();
        assert!(rel_close(r.accel[0], 0.1394908e-2 * G, 1e-15));
        assert_eq!(r.accel_at(0.0), r.accel[0]);
        assert_eq!(r.velocity_at(0.0), 0.0);
    }

    #[test]
    fn real_record_scaled_to_pga() {
        let path = data_file("RSN753_LOMAP_CLS000.AT2");
        let plain = Record::read(&path, &no_opts()).unwrap();
        let scaled = Record::read(&path, &with_scale(0.3)).unwrap();
        assert!(rel_close(scaled.pga(), 0.3 * G, 1e-12), "{}", scaled.pga());
        // The shape is kept: each sample scaled by the same factor.
        let factor = 0.3 * G / plain.pga();
        for k in [0, 1, 1000, 5000, 7994] {
            assert!(rel_close(scaled.accel[k], plain.accel[k] * factor, 1e-12));
        }
        assert!(rel_close(
            scaled.velocity_at(20.0),
            plain.velocity_at(20.0) * factor,
            1e-9
        ));
    }

    #[test]
    fn read_missing_file_is_io_error_naming_it() {
        let path = temp_path("does-not-exist.AT2");
        let e = Record::read(&path, &no_opts()).unwrap_err();
        assert!(matches!(e, RecordError::Io { .. }));
        assert!(e.to_string().contains("does-not-exist.AT2"), "{e}");
    }

    #[test]
    fn read_from_temp_files() {
        let path = temp_path("motion.csv");
        std::fs::write(&path, "t,a\n0,0.5\n0.02,1.5\n0.04,-1\n").unwrap();
        let r = Record::read(&path, &no_opts()).unwrap();
        assert_eq!(r.format, RecordFormat::TwoColumn);
        assert_eq!(r.accel, vec![0.5, 1.5, -1.0]);
        assert!(rel_close(r.dt, 0.02, 1e-12));
        assert_eq!(r.description, "motion.csv");

        // Non-UTF-8 bytes in a header (Latin-1 "é") are tolerated.
        let path = temp_path("latin1.AT2");
        let mut bytes = b"PEER NGA STRONG MOTION DATABASE RECORD\nSan Jos\xe9\n".to_vec();
        bytes.extend_from_slice(b"ACCELERATION TIME SERIES IN UNITS OF G\n");
        bytes.extend_from_slice(b"NPTS=   3, DT=   .0100 SEC,\n .1 .2 .3\n");
        std::fs::write(&path, bytes).unwrap();
        let r = Record::read(&path, &no_opts()).unwrap();
        assert_eq!(r.num_samples(), 3);
        assert!(rel_close(r.accel[2], 0.3 * G, 1e-15));
    }

    // ---------------------------------------------------------------- numbers

    #[test]
    fn fortran_style_numbers_parse() {
        assert_eq!(".1394908E-02".parse::<f64>().unwrap(), 0.001394908);
        assert_eq!("-.123E+01".parse::<f64>().unwrap(), -1.23);
        assert_eq!("+.5".parse::<f64>().unwrap(), 0.5);
        assert_eq!("1.E+00".parse::<f64>().unwrap(), 1.0);
        assert_eq!("-.8478295e-05".parse::<f64>().unwrap(), -8.478295e-6);
    }

    // ---------------------------------------------------------------- AT2 headers

    /// Five values 0.01, 0.02, ... 0.05 (g) after the given 4th header line.
    fn at2_with(line4: &str) -> String {
        format!(
            "{AT2_HEAD}{line4}\n   .1000000E-01   .2000000E-01   .3000000E-01\n .4E-01 .5E-01\n"
        )
    }

    fn check_five(r: &Record, dt: f64, factor: f64) {
        assert_eq!(r.format, RecordFormat::PeerAt2);
        assert_eq!(r.num_samples(), 5);
        assert!(rel_close(r.dt, dt, 1e-15), "dt {}", r.dt);
        for (k, a) in r.accel.iter().enumerate() {
            assert!(
                rel_close(*a, (k + 1) as f64 * 0.01 * factor, 1e-14),
                "{k}: {a}"
            );
        }
    }

    #[test]
    fn at2_header_variants() {
        let lines = [
            ("NPTS=      5, DT=   .0100 SEC,                     ", 0.01), // NGA-West2
            ("NPTS=  5, DT= .02000 SEC", 0.02),                            // older PEER
            ("5    0.0100    NPTS, DT", 0.01),                             // NGA-West1
            ("npts=5,dt=.005sec", 0.005),
            ("  Npts =  5 ,  Dt = 0.01 Sec", 0.01),
            ("NPTS= 5, DT= 1.0E-02 SEC,", 0.01),
            ("NPTS= 5., DT= .01", 0.01),
        ];
        for (line4, dt) in lines {
            let text = at2_with(line4);
            // By extension (any case) ...
            for name in ["r.AT2", "r.at2", "dir/r.At2"] {
                check_five(&ok(&text, name, &no_opts()), dt, G);
            }
            // ... and by the 4th line alone.
            for name in ["r.txt", "r"] {
                check_five(&ok(&text, name, &no_opts()), dt, G);
            }
        }
    }

    #[test]
    fn at2_description_units_and_crlf() {
        let text = at2_with("NPTS=   5, DT=   .0100 SEC,").replace('\n', "\r\n");
        let r = ok(&text, "x.AT2", &no_opts());
        check_five(&r, 0.01, G);
        assert_eq!(
            r.description,
            "Test event, 1/1/2000, Station, 0; ACCELERATION TIME SERIES IN UNITS OF G"
        );
        let opts = RecordOptions {
            units: Some(AccelUnits::MetersPerSecond2),
            ..RecordOptions::default()
        };
        check_five(&ok(&text, "x.AT2", &opts), 0.01, 1.0);
        // A byte-order mark does not hide the header.
        check_five(&ok(&format!("\u{feff}{text}"), "x", &no_opts()), 0.01, G);
    }

    // ---------------------------------------------------------------- AT2 errors

    #[test]
    fn at2_truncated_data() {
        let text = format!("{AT2_HEAD}NPTS=   10, DT=   .0100 SEC,\n .1 .2 .3 .4 .5\n .6 .7\n");
        let (e, msg) = fails(&text, "x.AT2", &no_opts(), Some(4));
        assert!(matches!(
            e,
            RecordError::TooFewValues {
                npts: 10,
                found: 7,
                ..
            }
        ));
        assert!(
            msg.contains("NPTS = 10") && msg.contains("only 7 values"),
            "{msg}"
        );
        // Header only: no data at all.
        let text = format!("{AT2_HEAD}NPTS=   10, DT=   .0100 SEC,\n");
        let (e, _) = fails(&text, "x.AT2", &no_opts(), Some(4));
        assert!(matches!(
            e,
            RecordError::TooFewValues {
                npts: 10,
                found: 0,
                ..
            }
        ));
        // An absurd NPTS is reported, not allocated.
        let text = format!("{AT2_HEAD}NPTS= 999999999999999, DT= .01\n .1 .2\n");
        let (e, _) = fails(&text, "x.AT2", &no_opts(), Some(4));
        assert!(matches!(e, RecordError::TooFewValues { found: 2, .. }));
    }

    #[test]
    fn at2_more_values_than_npts() {
        let text = format!("{AT2_HEAD}NPTS=   3, DT=   .0100 SEC,\n .1 .2\n .3\n .4 .5\n");
        let (e, msg) = fails(&text, "x.AT2", &no_opts(), Some(7));
        assert!(matches!(
            e,
            RecordError::TooManyValues {
                npts: 3,
                found: 5,
                ..
            }
        ));
        assert!(msg.contains("NPTS = 3") && msg.contains("has 5"), "{msg}");
    }

    #[test]
    fn at2_non_numeric_value() {
        let text = format!("{AT2_HEAD}NPTS=   4, DT=   .0100 SEC,\n .1 .2\n abc .3\n");
        let (e, msg) = fails(&text, "x.AT2", &no_opts(), Some(6));
        assert!(matches!(e, RecordError::NotANumber { .. }));
        assert_eq!(msg, "record \"x.AT2\", line 6: \"abc\" is not a number");
    }

    #[test]
    fn at2_non_finite_values() {
        for bad in ["NaN", "nan", "inf", "-inf", "infinity", "1e999", "-1E+400"] {
            let text = format!("{AT2_HEAD}NPTS=   3, DT=   .0100 SEC,\n .1\n .2 {bad}\n");
            let (e, msg) = fails(&text, "x.AT2", &no_opts(), Some(6));
            assert!(matches!(e, RecordError::NonFinite { .. }), "{bad}: {msg}");
            assert!(msg.contains(bad), "{msg}");
        }
        // Finite in g but not in m/s².
        let text = format!("{AT2_HEAD}NPTS=   2, DT=   .0100 SEC,\n .1 1.7e308\n");
        let (e, _) = fails(&text, "x.AT2", &no_opts(), Some(5));
        assert!(matches!(e, RecordError::OutOfRange { .. }));
    }

    #[test]
    fn at2_missing_or_bad_header() {
        // Too short to have a header.
        let (e, msg) = fails(" .1 .2 .3\n .4\n", "x.AT2", &no_opts(), None);
        assert!(matches!(e, RecordError::MissingHeader { lines: 2, .. }));
        assert!(msg.contains("NPTS and DT"), "{msg}");
        // Data without a header: line 4 is data.
        let text = " .1 .2\n .3 .4\n .5 .6\n .7 .8\n .9\n";
        let (e, msg) = fails(text, "x.AT2", &no_opts(), Some(4));
        assert!(matches!(e, RecordError::BadHeader { .. }));
        assert!(
            msg.contains("4th line") && msg.contains("NPTS and DT"),
            "{msg}"
        );
        // Keywords without numbers, or a mangled NPTS.
        for line4 in [
            "NPTS, DT",
            "NPTS= abc, DT= .01",
            "NPTS= 5",
            "NPTS= -5, DT= .01",
        ] {
            let (e, _) = fails(&at2_with(line4), "x.AT2", &no_opts(), Some(4));
            assert!(matches!(e, RecordError::BadHeader { .. }), "{line4}: {e}");
        }
    }

    #[test]
    fn at2_bad_dt() {
        for line4 in [
            "NPTS= 5, DT= 0.0 SEC",
            "NPTS= 5, DT= -.01 SEC",
            "NPTS= 5, DT= nan",
        ] {
            let (e, _) = fails(&at2_with(line4), "x.AT2", &no_opts(), Some(4));
            assert!(matches!(e, RecordError::InvalidDt { .. }), "{line4}: {e}");
        }
    }

    #[test]
    fn at2_too_few_samples() {
        let text = format!("{AT2_HEAD}NPTS=   1, DT=   .0100 SEC,\n .1\n");
        let (e, _) = fails(&text, "x.AT2", &no_opts(), None);
        assert!(matches!(e, RecordError::TooFewSamples { found: 1, .. }));
    }

    #[test]
    fn at2_velocity_file_refused() {
        let text = "PEER NGA STRONG MOTION DATABASE RECORD\nx\n\
                    VELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS=   2, DT=   .0100 SEC,\n 1 2\n";
        let (e, _) = fails(text, "x.VT2", &no_opts(), Some(3));
        assert!(matches!(e, RecordError::NotAcceleration { .. }));
    }

    #[test]
    fn empty_files() {
        for text in ["", "   \n\n\t\n", "\u{feff}"] {
            for name in ["x.AT2", "x.txt"] {
                let (e, msg) = fails(text, name, &no_opts(), None);
                assert!(matches!(e, RecordError::Empty { .. }));
                assert_eq!(msg, format!("record \"{name}\": the file is empty"));
            }
        }
    }

    // ---------------------------------------------------------------- two columns

    #[test]
    fn two_column_with_header_comments_and_separators() {
        let text = "# exported by hand\n\
                    time (s), accel (g)\n\
                    \n\
                    5.00, 0.10\n\
                    5.01; -0.20\n\
                    # a comment in the middle\n\
                    5.02\t0.30\n\
                    5.03 ,  0.40\n";
        let opts = RecordOptions {
            units: Some(AccelUnits::G),
            ..RecordOptions::default()
        };
        let r = ok(text, "dir/motion.csv", &opts);
        assert_eq!(r.format, RecordFormat::TwoColumn);
        assert!(rel_close(r.dt, 0.01, 1e-9), "{}", r.dt);
        let expected = [0.1, -0.2, 0.3, 0.4].map(|a| a * G);
        assert_eq!(r.accel, expected);
        // The time offset of 5 s is ignored: the first sample is at t = 0.
        assert_eq!(r.accel_at(0.0), 0.1 * G);
        assert_eq!(r.accel_at(r.duration() + 1e-9), 0.0);
        assert_eq!(r.description, "motion.csv");
        // Default units are m/s².
        let r = ok("t,a\n0 1\n0.5 2\n", "m.txt", &no_opts());
        assert_eq!(r.accel, vec![1.0, 2.0]);
        assert_eq!(r.dt, 0.5);
    }

    #[test]
    fn two_column_non_uniform_spacing() {
        let text = "t a\n0 1\n0.01 2\n0.02 3\n0.035 4\n0.04 5\n";
        let (e, msg) = fails(text, "m.txt", &no_opts(), Some(5));
        match e {
            RecordError::NonUniformSpacing { dt, spacing, .. } => {
                assert!(rel_close(dt, 0.01, 1e-12));
                assert!(rel_close(spacing, 0.015, 1e-9));
            }
            other => panic!("{other}"),
        }
        assert!(msg.contains(" 0.015 s") && msg.contains(" 0.01 s"), "{msg}");
        // Rounding far below 1e-6 of dt is accepted.
        let mut text = String::new();
        for k in 0..2000 {
            text.push_str(&format!("{} {}\n", k as f64 * 0.005, k % 7));
        }
        let r = ok(&text, "m.txt", &no_opts());
        assert_eq!(r.num_samples(), 2000);
    }

    #[test]
    fn two_column_time_not_increasing() {
        let (e, _) = fails("0 1\n0.01 2\n0.01 3\n", "m.txt", &no_opts(), Some(3));
        assert!(matches!(e, RecordError::TimeNotIncreasing { .. }));
        let (e, msg) = fails("0 1\n-0.01 2\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::TimeNotIncreasing { .. }));
        assert!(msg.contains("-0.01"), "{msg}");
    }

    #[test]
    fn two_column_non_finite_and_non_numeric() {
        let (e, _) = fails("0 1\n0.01 inf\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::NonFinite { .. }));
        let (e, _) = fails("0 1\nNaN 2\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::NonFinite { .. }));
        let (e, msg) = fails("0 1\n0.01 x2\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::NotANumber { .. }));
        assert!(msg.ends_with("\"x2\" is not a number"), "{msg}");
        // A second header line is not allowed.
        let (e, _) = fails("t a\nt a\n0 1\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::NotANumber { .. }));
    }

    #[test]
    fn layout_errors() {
        let (e, msg) = fails("# c\n\n1 2 3\n", "m.txt", &no_opts(), Some(3));
        assert!(matches!(
            e,
            RecordError::UnrecognisedLayout { found: 3, .. }
        ));
        assert!(msg.contains("found 3"), "{msg}");
        let (e, _) = fails("0 1\n0.01\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(
            e,
            RecordError::FieldCount {
                expected: 2,
                found: 1,
                ..
            }
        ));
        let (e, _) = fails("1\n2 3\n", "m.txt", &with_dt(0.1), Some(2));
        assert!(matches!(
            e,
            RecordError::FieldCount {
                expected: 1,
                found: 2,
                ..
            }
        ));
    }

    #[test]
    fn dt_option_against_file() {
        let text = "0 1\n0.01 2\n0.02 3\n";
        let (e, msg) = fails(text, "m.txt", &with_dt(0.02), None);
        assert!(matches!(e, RecordError::DtMismatch { .. }));
        assert!(msg.contains("0.02") && msg.contains("0.01"), "{msg}");
        let r = ok(text, "m.txt", &with_dt(0.01 * (1.0 + 1e-7)));
        assert!(rel_close(r.dt, 0.01, 1e-12));
        for bad in [0.0, -0.01, f64::NAN, f64::INFINITY] {
            let (e, _) = fails(text, "m.txt", &with_dt(bad), None);
            assert!(matches!(e, RecordError::InvalidDt { .. }), "{bad}");
        }
    }

    #[test]
    fn too_few_samples_in_text_files() {
        let (e, _) = fails("0 1\n", "m.txt", &no_opts(), None);
        assert!(matches!(e, RecordError::TooFewSamples { found: 1, .. }));
        let (e, _) = fails("t,a\n# nothing\n", "m.txt", &no_opts(), None);
        assert!(matches!(e, RecordError::TooFewSamples { found: 0, .. }));
        let (e, _) = fails("1\n", "m.txt", &with_dt(0.1), None);
        assert!(matches!(e, RecordError::TooFewSamples { found: 1, .. }));
    }

    // ---------------------------------------------------------------- single column

    #[test]
    fn single_column() {
        let text = "# accel\naccel (m/s2)\n1.5\n\n-2.5\n# end\n3.0\n";
        let r = ok(text, "a.dat", &with_dt(0.02));
        assert_eq!(r.format, RecordFormat::SingleColumn);
        assert_eq!(r.accel, vec![1.5, -2.5, 3.0]);
        assert_eq!(r.dt, 0.02);
        let opts = RecordOptions {
            units: Some(AccelUnits::G),
            dt: Some(0.02),
            scale_to_pga: None,
        };
        assert_eq!(
            ok(text, "a.dat", &opts).accel,
            vec![1.5 * G, -2.5 * G, 3.0 * G]
        );
    }

    #[test]
    fn single_column_without_dt() {
        let (e, msg) = fails("1\n2\n3\n", "a.dat", &no_opts(), None);
        assert!(matches!(e, RecordError::MissingDt { .. }));
        assert!(msg.contains("give `dt` in [ground_motion]"), "{msg}");
    }

    #[test]
    fn single_column_non_finite() {
        for bad in ["nan", "-inf", "1e999"] {
            let (e, _) = fails(&format!("1\n{bad}\n"), "a.dat", &with_dt(0.1), Some(2));
            assert!(matches!(e, RecordError::NonFinite { .. }), "{bad}");
        }
    }

    // ---------------------------------------------------------------- scaling

    #[test]
    fn scale_to_pga_hits_target() {
        let text = "0.3\n-1.7\n0.9\n1.2\n";
        for target in [0.05, 0.3, 1.0, 2.5] {
            let r = ok(
                text,
                "a.dat",
                &RecordOptions {
                    dt: Some(0.01),
                    ..with_scale(target)
                },
            );
            assert!(
                rel_close(r.pga(), target * G, 1e-12),
                "{target}: {}",
                r.pga()
            );
            assert!(rel_close(r.accel[0], 0.3 / 1.7 * target * G, 1e-12));
        }
    }

    #[test]
    fn scale_to_pga_errors() {
        for bad in [0.0, -0.5, f64::NAN, f64::INFINITY] {
            let opts = RecordOptions {
                dt: Some(0.01),
                ..with_scale(bad)
            };
            let (e, _) = fails("1\n2\n", "a.dat", &opts, None);
            assert!(matches!(e, RecordError::InvalidScale { .. }), "{bad}");
        }
        let opts = RecordOptions {
            dt: Some(0.01),
            ..with_scale(0.3)
        };
        let (e, msg) = fails("0\n0\n-0\n", "a.dat", &opts, None);
        assert!(matches!(e, RecordError::ZeroPga { .. }));
        assert!(msg.contains("0"), "{msg}");
    }

    // ---------------------------------------------------------------- from_samples

    #[test]
    fn from_samples_validation() {
        let d = || "test record".to_string();
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = Record::from_samples(dt, vec![1.0, 2.0], d()).unwrap_err();
            assert!(matches!(e, RecordError::InvalidDt { .. }), "{dt}");
            assert!(e.to_string().starts_with("record \"test record\": "), "{e}");
        }
        for n in [0, 1] {
            let e = Record::from_samples(0.01, vec![1.0; n], d()).unwrap_err();
            assert!(matches!(e, RecordError::TooFewSamples { .. }));
        }
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let e = Record::from_samples(0.01, vec![1.0, bad, 2.0], d()).unwrap_err();
            assert!(matches!(e, RecordError::NonFinite { .. }));
        }
        let e = Record::from_samples(1e300, vec![1e300, 1e300], d()).unwrap_err();
        assert!(matches!(e, RecordError::VelocityOverflow { .. }));
        let r = Record::from_samples(0.01, vec![1.0, 2.0], d()).unwrap();
        assert_eq!(r.description, "test record");
        assert_eq!(r.format, RecordFormat::SingleColumn);
    }

    // ---------------------------------------------------------------- evaluation

    #[test]
    fn constant_accel_gives_linear_velocity() {
        let a0 = 2.5;
        let dt = 0.02;
        let r = Record::from_samples(dt, vec![a0; 101], "c".into()).unwrap();
        let end = 100.0 * dt;
        assert!(rel_close(r.duration(), end, 1e-15));
        let mut rng = Lcg(7);
        for k in 0..=300 {
            let t = if k <= 100 {
                k as f64 * dt
            } else {
                rng.unit() * end
            };
            let (a, v) = r.accel_and_velocity_at(t);
            assert!(rel_close(a, a0, 1e-12), "t {t}: a {a}");
            assert!(
                rel_close(v, a0 * t, 1e-12) || t == 0.0 && v == 0.0,
                "t {t}: v {v}"
            );
        }
    }

    #[test]
    fn ramp_accel_gives_quadratic_velocity() {
        let c = 3.7; // m/s³
        let dt = 0.01;
        let n = 1001;
        let accel: Vec<f64> = (0..n).map(|k| c * (k as f64 * dt)).collect();
        let r = Record::from_samples(dt, accel, "ramp".into()).unwrap();
        let end = r.duration();
        let mut rng = Lcg(42);
        for i in 0..500 {
            let t = match i {
                0 => end,
                1 => 1e-9,
                2 => 0.5 * dt,
                _ => rng.unit() * end,
            };
            let (a, v) = r.accel_and_velocity_at(t);
            assert!(rel_close(a, c * t, 1e-12), "t {t}: a {a} vs {}", c * t);
            assert!(rel_close(v, 0.5 * c * t * t, 1e-12), "t {t}: v {v}");
            assert_eq!(r.accel_at(t), a);
            assert_eq!(r.velocity_at(t), v);
        }
        // After the end: no acceleration, constant velocity.
        let v_end = 0.5 * c * end * end;
        for t in [end + 1e-9, end + dt, end + 1.0, 1e9, f64::INFINITY] {
            assert_eq!(r.accel_at(t), 0.0, "t {t}");
            assert!(rel_close(r.velocity_at(t), v_end, 1e-12), "t {t}");
        }
        // Before the start: nothing.
        for t in [-1e-12, -1.0, f64::NEG_INFINITY] {
            assert_eq!(r.accel_and_velocity_at(t), (0.0, 0.0));
        }
        let (a, v) = r.accel_and_velocity_at(f64::NAN);
        assert!(a.is_nan() && v.is_nan());
    }

    #[test]
    fn velocity_matches_simpson_integration_of_accel() {
        // Simpson's rule is exact on each linear piece of accel_at.
        let mut rng = Lcg(3);
        let dt = 0.005;
        let accel: Vec<f64> = (0..400).map(|_| 20.0 * rng.unit() - 10.0).collect();
        let r = Record::from_samples(dt, accel.clone(), "rand".into()).unwrap();
        for (k, a) in accel.iter().enumerate() {
            assert_eq!(r.accel_at(k as f64 * dt), *a);
        }
        for _ in 0..50 {
            let t = rng.unit() * r.duration();
            let mut v = 0.0;
            let mut p = 0.0;
            while p < t {
                let q = (p + dt).min(t);
                let q = if t - q < 1e-12 { t } else { q };
                v += (q - p) / 6.0
                    * (r.accel_at(p) + 4.0 * r.accel_at(0.5 * (p + q)) + r.accel_at(q));
                p = q;
            }
            assert!(
                (r.velocity_at(t) - v).abs() < 1e-10,
                "t {t}: {} vs {v}",
                r.velocity_at(t)
            );
        }
        for (k, v) in r.velocity_samples().iter().enumerate() {
            assert!((r.velocity_at(k as f64 * dt) - v).abs() < 1e-12);
        }
    }

    #[test]
    fn mutated_public_fields_do_not_panic() {
        let base = Record::from_samples(0.01, vec![1.0, 2.0, 3.0], "m".into()).unwrap();
        let ts = [-1.0, 0.0, 0.005, 0.02, 0.03, 1.0, f64::NAN, f64::INFINITY];
        let mut r = base.clone();
        r.accel.clear();
        assert_eq!(r.duration(), 0.0);
        assert_eq!(r.pga(), 0.0);
        for t in ts {
            let _ = r.accel_and_velocity_at(t);
        }
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-320] {
            let mut r = base.clone();
            r.dt = dt;
            for t in ts {
                let _ = r.accel_and_velocity_at(t);
                let _ = r.duration();
            }
        }
        let mut r = base;
        r.accel.push(4.0);
        for t in ts {
            let _ = r.accel_and_velocity_at(t);
        }
    }

    // ---------------------------------------------------------------- robustness

    fn exercise(text: &str) {
        let opts = [
            no_opts(),
            with_dt(0.01),
            RecordOptions {
                dt: Some(0.01),
                ..with_scale(0.5)
            },
            RecordOptions {
                units: Some(AccelUnits::G),
                dt: Some(1e-300),
                scale_to_pga: Some(1e300),
            },
        ];
        for name in ["f.AT2", "f.txt", "f", ""] {
            for o in &opts {
                match Record::parse(text, Path::new(name), o) {
                    Ok(r) => {
                        assert!(r.num_samples() >= 2 && r.dt > 0.0);
                        for t in [-1.0, 0.0, 0.3 * r.duration(), r.duration(), 1e9, f64::NAN] {
                            let _ = r.accel_and_velocity_at(t);
                        }
                    }
                    Err(e) => {
                        let msg = e.to_string();
                        assert!(msg.starts_with(&format!("record \"{name}\"")), "{msg}");
                    }
                }
            }
        }
    }

    #[test]
    fn random_bytes_never_panic() {
        let mut rng = Lcg(12345);
        for _ in 0..300 {
            let len = rng.below(200);
            let bytes: Vec<u8> = (0..len)
                .map(|_| {
                    // Bias towards the characters the parsers care about.
                    const BIASED: &[u8] = b"0123456789.eE+-,; \t\n\r#NPTSDTsec=";
                    if rng.below(4) == 0 {
                        rng.below(256) as u8
                    } else {
                        BIASED[rng.below(BIASED.len())]
                    }
                })
                .collect();
            exercise(&String::from_utf8_lossy(&bytes));
        }
    }

    #[test]
    fn random_token_lines_never_panic() {
        const TOKENS: &[&str] = &[
            "NPTS=",
            "DT=",
            "NPTS",
            "DT",
            "SEC",
            "SEC,",
            "5",
            "2",
            "1",
            "0",
            "-1",
            ".01",
            "0.01",
            "-.5E+01",
            "1e308",
            "1e-320",
            "nan",
            "inf",
            "-inf",
            "abc",
            "t,a",
            ",",
            ";",
            "#",
            " ",
            "  ",
            "\t",
            "\n",
            "\n",
            "\n",
            "\r\n",
            "99999999999999999999",
            "1.5",
            "é",
            "NPTS=2,",
        ];
        let mut rng = Lcg(987);
        for i in 0..400 {
            let mut text = String::new();
            if i % 2 == 0 {
                text.push_str(AT2_HEAD);
            }
            for _ in 0..rng.below(60) {
                text.push_str(TOKENS[rng.below(TOKENS.len())]);
                if rng.below(3) == 0 {
                    text.push(' ');
                }
            }
            exercise(&text);
        }
    }
}
