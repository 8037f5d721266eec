//! What can go wrong when reading a record, and where ([`Location`], the crate's one kind of
//! place in a file, here as `record "x.AT2", line 7`) and
//! [`RecordError`]. Every message starts with the file (and the line, when there is one) and
//! quotes the offending text plainly, clipped to [`MAX_QUOTED_CHARS`] characters with control
//! characters replaced (never as a Rust escape such as `"\u{1a}"`).

/// Longest piece of user text quoted in an error message, in characters.
pub const MAX_QUOTED_CHARS: usize = 60;

pub use crate::diagnostics::Location;
use crate::diagnostics::Naming;

/// A record file (or, for [`crate::model::ground_motion::Record::from_samples`], its
/// description) as messages name it: `record "x.AT2"`.
pub fn in_record(file: &str) -> Location {
    Location::file(file).named(Naming::Record)
}

/// One 1-based line of a record file: `record "x.AT2", line 7`.
pub fn record_line(file: &str, line: usize) -> Location {
    in_record(file).at_line(line)
}

/// Shortens user text for quoting in an error message: trimmed, at most [`MAX_QUOTED_CHARS`]
/// characters (then `…`), control characters shown as `�` so that a binary byte never prints
/// as an escape or moves the terminal's cursor.
pub fn clip(text: &str) -> String {
    let text = text.trim();
    let mut s: String = text
        .chars()
        .take(MAX_QUOTED_CHARS)
        .map(|c| if c.is_control() { '\u{fffd}' } else { c })
        .collect();
    if text.chars().count() > MAX_QUOTED_CHARS {
        s.push('…');
    }
    s
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
        /// The limit, bytes ([`crate::model::ground_motion::record::MAX_RECORD_BYTES`]).
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
    /// The file is not text (issue 24): NUL bytes, control characters or mostly invalid UTF-8
    /// in its first kilobytes — a binary file (miniSEED, SAC, a spreadsheet, an archive).
    #[error(
        "{at}: not a text record file ({reason}); records are read from text files \
         (PEER .AT2, COSMOS, CSMIP/DMG, K-NET/KiK-net, ESM, or one or two columns)"
    )]
    NotText {
        /// The file, and the line of the first offending byte.
        at: Location,
        /// What was found, e.g. "a NUL byte at byte 17".
        reason: String,
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
         \"NPTS=   7995, DT=   .0050 SEC,\" or \"4164    0.0100    NPTS, DT\", found \"{found}\""
    )]
    BadHeader {
        /// The file and line 4.
        at: Location,
        /// The line found (shortened).
        found: String,
    },
    /// A header line of a fixed layout (COSMOS, CSMIP/DMG, K-NET, ESM) is not what the layout
    /// has there: a damaged or truncated header.
    #[error("{at}: expected {expected} ({format} header), found \"{found}\"")]
    BadHeaderLine {
        /// The file and line.
        at: Location,
        /// The layout's name.
        format: &'static str,
        /// What the layout has on this line.
        expected: String,
        /// The line found (shortened).
        found: String,
    },
    /// The file holds velocities, displacements, spectra or raw counts, not accelerations.
    #[error("{at}: this is not an acceleration record (the header says \"{found}\")")]
    NotAcceleration {
        /// The file and the header line.
        at: Location,
        /// The header line (shortened).
        found: String,
    },
    /// The units stated in the file are not ones the program reads.
    #[error(
        "{at}: the file gives its values in \"{found}\"; accelerations in g, gal (cm/s²) or \
         m/s² are read"
    )]
    UnsupportedUnits {
        /// The file and line.
        at: Location,
        /// The units found (shortened).
        found: String,
    },
    /// The record is uncorrected (a V1 or raw record): no baseline correction or filtering was
    /// applied by the agency, so its velocity and displacement drift.
    #[error(
        "{at}: this is an uncorrected record ({what}): its baseline has not been corrected nor \
         its noise filtered, so the ground velocity and displacement drift; use the agency's \
         corrected (V2) record, or have it processed with `processing = {{ baseline = \
         \"linear\", highpass_hz = 0.1, lowpass_hz = 25 }}` in [ground_motion] (see the README, \
         \"Recorded ground motion\")"
    )]
    Uncorrected {
        /// The file.
        at: Location,
        /// The layout and level, e.g. "COSMOS V1, uncorrected acceleration".
        what: String,
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
    /// A fixed-width data line holds fewer fields than its format says.
    #[error(
        "{at}: expected {expected} value(s) of {width} characters (format {format}), the line \
         holds {found}"
    )]
    ShortLine {
        /// The file and line.
        at: Location,
        /// Values this line should hold.
        expected: usize,
        /// Field width, characters.
        width: usize,
        /// The Fortran format, e.g. "(8F10.5)".
        format: String,
        /// Values it holds.
        found: usize,
    },
    /// A field that should be a number is not one.
    #[error("{at}: \"{token}\" is not a number")]
    NotANumber {
        /// The file and line.
        at: Location,
        /// The field (shortened).
        token: String,
    },
    /// A value is NaN or infinite.
    #[error("{at}: \"{token}\" is not a finite number")]
    NonFinite {
        /// The file and line.
        at: Location,
        /// The field (shortened).
        token: String,
    },
    /// A value is finite in the file's units but overflows when converted to m/s².
    #[error("{at}: \"{token}\" is too large to convert to m/s²")]
    OutOfRange {
        /// The file and line.
        at: Location,
        /// The field (shortened).
        token: String,
    },
    /// A data value is the layout's placeholder for a missing value (COSMOS `-999`).
    #[error(
        "{at}: \"{token}\" is the file's placeholder for a missing value; a record with gaps \
         cannot be used"
    )]
    MissingValue {
        /// The file and line.
        at: Location,
        /// The placeholder as written.
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
        /// The first time step, `t[1] − t[0]`, s.
        dt: f64,
        /// The time step ending at this line, s.
        spacing: f64,
    },
    /// Two statements of the time step in one file disagree (mixed time steps).
    #[error(
        "{at}: the time step is given as {} s ({first}) and as {} s ({second}); \
         the file is inconsistent",
        short(*.dt_first),
        short(*.dt_second)
    )]
    TimeStepMismatch {
        /// The file and the line of the second statement.
        at: Location,
        /// Where the first is stated.
        first: String,
        /// The first value, s.
        dt_first: f64,
        /// Where the second is stated.
        second: String,
        /// The second value, s.
        dt_second: f64,
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
    /// The first data line of a text file has neither 1 nor 2 numbers, and the file is in no
    /// other known layout.
    #[error(
        "{at}: expected 1 number (acceleration) or 2 numbers (time, acceleration) per line, \
         found {found} (if this is a PEER .AT2 file, its 4 header lines are missing); the file \
         is in none of the layouts read: PEER .AT2, COSMOS V1/V2, CSMIP/DMG V1/V2, \
         K-NET/KiK-net, ESM, one or two columns"
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
    /// The file holds several components and none was chosen.
    #[error(
        "{at}: the file holds {} components: {}; choose one with `component` in \
         [ground_motion] (its number or its name, e.g. component = 1 or component = \"{}\")",
        .components.len(),
        .components.join("; "),
        .example
    )]
    ComponentNeeded {
        /// The file.
        at: Location,
        /// Each component: number, name and what else it answers to.
        components: Vec<String>,
        /// A name to show in the example.
        example: String,
    },
    /// The component asked for is not in the file.
    #[error(
        "{at}: no component \"{asked}\" in the file; it holds: {}",
        .components.join("; ")
    )]
    NoSuchComponent {
        /// The file.
        at: Location,
        /// The component asked for.
        asked: String,
        /// Each component: number, name and what else it answers to.
        components: Vec<String>,
    },
    /// The processing options cannot be applied to this record.
    #[error("{at}: processing: {reason}")]
    InvalidProcessing {
        /// The file.
        at: Location,
        /// Why.
        reason: String,
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
    /// `scale_to_pga` and `scale_to_sa` both given.
    #[error(
        "{at}: `scale_to_pga` and `scale_to_sa` are both given: a record is scaled to its PGA or \
         to a spectral acceleration, not both; keep one"
    )]
    ScaleConflict {
        /// The file.
        at: Location,
    },
    /// A `scale_to_sa` target out of its range.
    #[error("{at}: scale_to_sa.{what} = {value} must be {allowed}")]
    InvalidSaTarget {
        /// The file.
        at: Location,
        /// `period`, `sa` or `damping`.
        what: &'static str,
        /// The offending value.
        value: f64,
        /// What it may be.
        allowed: &'static str,
    },
    /// A `scale_to_sa` period below dt/100, where the spectrum code refuses it too.
    #[error(
        "{at}: scale_to_sa.period = {period} s is below dt/100 = {limit} s (dt = {dt} s): there \
         the oscillator follows the ground and PSA is the PGA to 0.2 %; use `scale_to_pga`"
    )]
    SaPeriodBelowStep {
        /// The file.
        at: Location,
        /// The period asked, s.
        period: f64,
        /// The record's time step, s.
        dt: f64,
        /// dt/100, s.
        limit: f64,
    },
    /// `scale_to_sa` was asked for a record with no response at that period (all zeros).
    #[error(
        "{at}: cannot scale to a spectral acceleration: the record's PSA at T = {period} s is 0 \
         (every acceleration is 0)"
    )]
    ZeroSa {
        /// The file.
        at: Location,
        /// The period, s.
        period: f64,
    },
    /// The integrated velocity overflows f64.
    #[error("{at}: the ground velocity overflows (accelerations or time step too large)")]
    VelocityOverflow {
        /// The file.
        at: Location,
    },
}

/// Rounds `x` to 12 significant digits for messages, so that a time step computed as
/// 0.035 − 0.02 prints as 0.015 rather than 0.015000000000000003.
pub(crate) fn short(x: f64) -> f64 {
    if !x.is_finite() || x == 0.0 {
        return x;
    }
    let scale = 10f64.powi(11 - x.abs().log10().floor() as i32);
    let rounded = (x * scale).round() / scale;
    if rounded.is_finite() { rounded } else { x }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_shows_control_characters_plainly() {
        assert_eq!(clip("  abc \n"), "abc");
        assert_eq!(clip("a\u{1a}b"), "a\u{fffd}b");
        let long = "x".repeat(100);
        let c = clip(&long);
        assert_eq!(c.chars().count(), MAX_QUOTED_CHARS + 1);
        assert!(c.ends_with('…'));
        let e = RecordError::NotANumber {
            at: record_line("f", 2),
            token: clip("\u{1a}"),
        };
        assert_eq!(
            e.to_string(),
            "record \"f\", line 2: \"\u{fffd}\" is not a number"
        );
        assert!(!e.to_string().contains("\\u"));
    }

    #[test]
    fn short_rounds_for_messages() {
        assert_eq!(short(0.035 - 0.02), 0.015);
        assert_eq!(short(0.0), 0.0);
        assert!(short(f64::NAN).is_nan());
    }
}
