//! The record/signal model: an equally spaced ground acceleration `a_g(t)` (m/s²) with its
//! exact velocity integral `v_g(t)` (m/s), scaling, and what was read with it (format,
//! component, units stated in the file, the header's own peak, warnings).
//!
//! Files are read by [`crate::model::ground_motion::formats`]: the layout is detected from the content
//! (PEER NGA `.AT2`, COSMOS V1/V2, CSMIP/DMG V1/V2, K-NET/KiK-net ASCII, ESM ASCII, one or two
//! columns), one reader per layout, and the chosen component converted to m/s² (processed when
//! asked, [`crate::model::ground_motion::processing`]).
//!
//! Acceleration is linear between samples and zero after the end of the record (free
//! vibration, as OpenSees' `Path` time series); the velocity is its exact integral with
//! `v_g(0) = 0`, piecewise quadratic between samples and constant after the end.

use std::path::Path;

use crate::model::ground_motion::error::in_record;
pub use crate::model::ground_motion::error::{Location, RecordError};
use crate::model::ground_motion::processing::Processing;
use crate::model::ground_motion::scale::{RecordScaling, SaTarget};

/// Standard gravity, m/s², used to convert accelerations given in g.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Relative tolerance on time steps: the spacing of a two-column file must be uniform
/// to this fraction of `dt`, and a `dt` option must agree with the file's to it.
pub const DT_REL_TOLERANCE: f64 = 1e-6;

/// Units of the acceleration values in a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AccelUnits {
    /// Multiples of standard gravity, [`STANDARD_GRAVITY`] = 9.80665 m/s².
    G,
    /// Centimetres per second squared (gal), 0.01 m/s².
    Gal,
    /// Metres per second squared, m/s².
    MetersPerSecond2,
}

impl AccelUnits {
    /// Factor that converts a value in these units to m/s² (9.80665 for g, 0.01 for gal, 1 for
    /// m/s²).
    pub fn to_m_s2(self) -> f64 {
        match self {
            AccelUnits::G => STANDARD_GRAVITY,
            AccelUnits::Gal => 0.01,
            AccelUnits::MetersPerSecond2 => 1.0,
        }
    }

    /// The name used in scenario files and reports: `g`, `cm/s2`, `m/s2`.
    pub fn name(self) -> &'static str {
        match self {
            AccelUnits::G => "g",
            AccelUnits::Gal => "cm/s2",
            AccelUnits::MetersPerSecond2 => "m/s2",
        }
    }

    /// Units from their name: `g`; `gal`, `cm/s2`, `cm/s^2`, `cm/s²`, `cm/sec2`, `cm/sec/sec`;
    /// `m/s2`, `m/s^2`, `m/s²` (case-insensitive, blanks ignored).
    pub fn from_name(name: &str) -> Option<AccelUnits> {
        let n: String = name
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect::<String>()
            .to_ascii_lowercase()
            .replace('²', "2")
            .replace("^2", "2")
            .replace("**2", "2")
            .replace("sec", "s");
        match n.as_str() {
            "g" => Some(AccelUnits::G),
            "gal" | "cm/s2" | "cm/s/s" | "cms-2" | "cm/s2." => Some(AccelUnits::Gal),
            "m/s2" | "m/s/s" | "ms-2" => Some(AccelUnits::MetersPerSecond2),
            _ => None,
        }
    }
}

/// Which component of a multi-channel file to read: its number (1-based, in the order of the
/// file) or a name it answers to (`"90"`, `"EW"`, `"HNE"`, `"Up"`, case-insensitive).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Component {
    /// The n-th acceleration component of the file, from 1.
    Index(usize),
    /// A name of the component.
    Name(String),
}

impl std::fmt::Display for Component {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Component::Index(i) => write!(f, "{i}"),
            Component::Name(n) => write!(f, "{n}"),
        }
    }
}

/// How to read a record file.
#[derive(Debug, Clone, Default)]
pub struct RecordOptions {
    /// Units of the values in the file. `None`: the units the file states (AT2, COSMOS,
    /// CSMIP/DMG, K-NET, ESM); g for an AT2 file that does not say; m/s² for the two-column and
    /// single-column formats. When given and the file states others, these win and the record
    /// carries a warning.
    pub units: Option<AccelUnits>,
    /// Time step, s. Required for single-column files. For the formats that carry their
    /// own time step it may be given only if it agrees with the file's to
    /// [`DT_REL_TOLERANCE`] (relative); otherwise reading fails.
    pub dt: Option<f64>,
    /// Target peak ground acceleration, in g: when set, the whole record is scaled so
    /// that max |a| equals `scale_to_pga · 9.80665` m/s². Must be positive and finite.
    pub scale_to_pga: Option<f64>,
    /// Target pseudo-spectral acceleration at one period: when set, the whole record is
    /// multiplied by the factor that brings its PSA at `period` (damping `damping`) to `sa` g
    /// ([`crate::model::ground_motion::scale::sa_factor`]). Not with `scale_to_pga`.
    pub scale_to_sa: Option<SaTarget>,
    /// The component to read from a file with several; `None` for a file with one.
    pub component: Option<Component>,
    /// Baseline correction and band-pass filtering, required for uncorrected records (V1,
    /// raw), applied to any record when given.
    pub processing: Option<Processing>,
}

/// The layout a record was read from (detected from the content, not the file name).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RecordFormat {
    /// PEER NGA `.AT2`: four header lines with NPTS and DT, then the values.
    PeerAt2,
    /// COSMOS strong-motion format, uncorrected (V1) acceleration.
    CosmosV1,
    /// COSMOS strong-motion format, corrected (V2) acceleration.
    CosmosV2,
    /// CSMIP/DMG (California Geological Survey) Volume 1: uncorrected acceleration.
    CsmipV1,
    /// CSMIP/DMG Volume 2: corrected acceleration, velocity and displacement.
    CsmipV2,
    /// K-NET / KiK-net ASCII (NIED): counts with a scale factor, mean removed.
    Knet,
    /// ESM / ITACA ASCII: one value per line after a `KEY: value` header.
    Esm,
    /// Two columns: time (s) and acceleration.
    TwoColumn,
    /// One acceleration value per line; the time step comes from [`RecordOptions::dt`].
    /// Also used for records built with [`Record::from_samples`].
    SingleColumn,
}

impl RecordFormat {
    /// The layout's name, as reports print it.
    pub fn name(self) -> &'static str {
        match self {
            RecordFormat::PeerAt2 => "PEER NGA AT2",
            RecordFormat::CosmosV1 => "COSMOS V1 (uncorrected)",
            RecordFormat::CosmosV2 => "COSMOS V2 (corrected)",
            RecordFormat::CsmipV1 => "CSMIP/DMG V1 (uncorrected)",
            RecordFormat::CsmipV2 => "CSMIP/DMG V2 (corrected)",
            RecordFormat::Knet => "K-NET/KiK-net ASCII",
            RecordFormat::Esm => "ESM ASCII",
            RecordFormat::TwoColumn => "two columns (t, a)",
            RecordFormat::SingleColumn => "one column (a)",
        }
    }

    /// A short identifier for scripts (the `format` of `pounding record --json`).
    pub fn key(self) -> &'static str {
        match self {
            RecordFormat::PeerAt2 => "peer-at2",
            RecordFormat::CosmosV1 => "cosmos-v1",
            RecordFormat::CosmosV2 => "cosmos-v2",
            RecordFormat::CsmipV1 => "csmip-v1",
            RecordFormat::CsmipV2 => "csmip-v2",
            RecordFormat::Knet => "knet",
            RecordFormat::Esm => "esm",
            RecordFormat::TwoColumn => "two-column",
            RecordFormat::SingleColumn => "one-column",
        }
    }
}

/// The peak acceleration a file's header states for the component read (before any processing
/// or scaling): to check what was read against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StatedPeak {
    /// The peak as stated, converted to m/s² (with its sign when the header gives one).
    pub accel: f64,
    /// Its time, s from the first sample, when the header gives it.
    pub time: Option<f64>,
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
    /// Human-readable description: the header's event and station, or the file name.
    pub description: String,
    /// The component read, as the file names it (`None` for single-component layouts that do
    /// not name it).
    pub component: Option<String>,
    /// The units the file states for its values (`None` when it states none).
    pub file_units: Option<AccelUnits>,
    /// The peak acceleration the header states, when it does.
    pub stated_peak: Option<StatedPeak>,
    /// The processing applied ([`RecordOptions::processing`]).
    pub processing: Option<Processing>,
    /// The scaling applied when read ([`RecordOptions::scale_to_pga`],
    /// [`RecordOptions::scale_to_sa`]): its factor and target.
    pub scaling: Option<RecordScaling>,
    /// What the reader noticed but accepted (a `units` option overriding the file's units).
    pub warnings: Vec<String>,
}

/// Largest record file read, bytes (500 MB: about 10⁸ samples of a one-column file), so that a
/// wrong path (a disk image, `/dev/zero`) is refused before it takes the memory.
pub const MAX_RECORD_BYTES: u64 = 500_000_000;

/// Opens a record file for reading after checking, without opening it, that it is a regular
/// file no larger than [`MAX_RECORD_BYTES`] (opening a FIFO blocks until a writer comes).
pub fn open_record_file(path: &Path) -> Result<std::fs::File, RecordError> {
    let at = || in_record(&path.display().to_string());
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
                at: in_record(&file),
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

    /// Time of the peak ground acceleration, s: k·dt of the first sample where |a| is largest.
    pub fn pga_time(&self) -> f64 {
        let mut best = (0, 0.0_f64);
        for (k, a) in self.accel.iter().enumerate() {
            if a.abs() > best.1 {
                best = (k, a.abs());
            }
        }
        best.0 as f64 * self.dt
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

/// Validates and builds a record, integrating the velocity; what was read with it is set
/// by the caller.
pub(crate) fn build(
    dt: f64,
    accel: Vec<f64>,
    description: String,
    format: RecordFormat,
    file: &str,
) -> Result<Record, RecordError> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(RecordError::InvalidDt {
            at: in_record(file),
            dt,
        });
    }
    if accel.len() < 2 {
        return Err(RecordError::TooFewSamples {
            at: in_record(file),
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
            at: in_record(file),
        });
    }
    Ok(Record {
        dt,
        accel,
        velocity,
        format,
        description,
        component: None,
        file_units: None,
        stated_peak: None,
        processing: None,
        scaling: None,
        warnings: Vec::new(),
    })
}

pub(crate) fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0_f64, |m, a| m.max(a.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ground_motion::formats::testutil::*;

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
}
