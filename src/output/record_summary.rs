//! What `pounding record FILE` prints: what the program read from a record file — layout,
//! component, units in the file, time step, number of points, PGA (m/s² and g) and its time,
//! the peak the header states — as text or as JSON (a contract for scripts), and the series in
//! SI as `t,a` CSV.

use std::path::Path;

use serde::Serialize;

use crate::model::ground_motion::processing::{Baseline, Processing};
use crate::model::ground_motion::record::{
    AccelUnits, Component, Record, RecordOptions, STANDARD_GRAVITY,
};
use crate::output::atomic::{OutputError, write_atomic};

/// What was read from a record file. The JSON keys `format`, `component`, `dt` (s), `points`,
/// `pga` (m/s²) and `pga_time` (s) are a contract for scripts; the others may grow.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordSummary {
    /// The file as given.
    pub file: String,
    /// The layout's identifier ([`crate::model::ground_motion::RecordFormat::key`]), e.g. `cosmos-v2`.
    pub format: String,
    /// The layout's name, e.g. `COSMOS V2 (corrected)`.
    pub format_name: String,
    /// The component read, as the file names it (`null` when the layout names none).
    pub component: Option<String>,
    /// The units the file states (`g`, `cm/s2`, `m/s2`), `null` when it states none.
    pub units_in_file: Option<String>,
    /// Time step, s.
    pub dt: f64,
    /// Number of samples.
    pub points: usize,
    /// Duration, s: (points − 1)·dt.
    pub duration: f64,
    /// Peak ground acceleration, m/s².
    pub pga: f64,
    /// Peak ground acceleration, g.
    pub pga_g: f64,
    /// Time of the PGA, s from the first sample.
    pub pga_time: f64,
    /// The peak the file's header states, m/s² (`null` when it states none).
    pub stated_pga: Option<f64>,
    /// Its time, s, when stated.
    pub stated_pga_time: Option<f64>,
    /// The processing applied, `null` for none.
    pub processing: Option<String>,
    /// Event and station.
    pub description: String,
    /// What the reader noticed but accepted.
    pub warnings: Vec<String>,
}

impl RecordSummary {
    /// The summary of `record`, read from `file`.
    pub fn of(record: &Record, file: &str) -> RecordSummary {
        let pga = record.pga();
        RecordSummary {
            file: file.to_string(),
            format: record.format.key().to_string(),
            format_name: record.format.name().to_string(),
            component: record.component.clone(),
            units_in_file: record.file_units.map(|u| u.name().to_string()),
            dt: record.dt,
            points: record.num_samples(),
            duration: record.duration(),
            pga,
            pga_g: pga / STANDARD_GRAVITY,
            pga_time: record.pga_time(),
            stated_pga: record.stated_peak.map(|p| p.accel),
            stated_pga_time: record.stated_peak.and_then(|p| p.time),
            processing: record.processing.map(|p| {
                let pad = p.pad_seconds(record.dt);
                if pad > 0.0 {
                    format!(
                        "{}; zero pads of {pad} s kept at both ends (t = 0 is the start of the \
                         first pad)",
                        p.describe()
                    )
                } else {
                    p.describe()
                }
            }),
            description: record.description.clone(),
            warnings: record.warnings.clone(),
        }
    }

    /// The summary as aligned lines of text.
    pub fn text(&self) -> String {
        let mut rows: Vec<(&str, String)> = vec![
            ("file", self.file.clone()),
            ("format", self.format_name.clone()),
            ("record", self.description.clone()),
            (
                "component",
                self.component
                    .clone()
                    .unwrap_or_else(|| "(the only one)".into()),
            ),
            (
                "units in the file",
                self.units_in_file
                    .clone()
                    .unwrap_or_else(|| "not stated".into()),
            ),
            ("time step", format!("{} s", self.dt)),
            ("points", self.points.to_string()),
            ("duration", format!("{:.3} s", self.duration)),
            (
                "PGA",
                format!(
                    "{} m/s² = {} g at t = {:.3} s",
                    sig(self.pga),
                    sig(self.pga_g),
                    self.pga_time
                ),
            ),
        ];
        if let Some(p) = self.stated_pga {
            let time = self
                .stated_pga_time
                .map_or(String::new(), |t| format!(" at t = {t:.3} s"));
            rows.push((
                "PGA stated in the file",
                format!(
                    "{} m/s² = {} g{time}",
                    sig(p.abs()),
                    sig(p.abs() / STANDARD_GRAVITY)
                ),
            ));
        }
        if let Some(p) = &self.processing {
            rows.push(("processing", p.clone()));
        }
        let width = rows
            .iter()
            .map(|(k, _)| k.chars().count())
            .max()
            .unwrap_or(0);
        let mut out = String::new();
        for (k, v) in rows {
            out.push_str(&format!("  {k:<width$}  {v}\n"));
        }
        for w in &self.warnings {
            out.push_str(&format!("warning: {w}\n"));
        }
        out
    }

    /// The summary as pretty JSON.
    pub fn json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|_| "{}".into())
    }
}

/// `x` to 5 significant digits, without an exponent for ordinary magnitudes.
fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = 4 - x.abs().log10().floor() as i32;
    if (0..=12).contains(&digits) {
        format!("{x:.prec$}", prec = digits as usize)
    } else {
        format!("{x:.4e}")
    }
}

/// The series in SI as CSV, `t,a` (s, m/s²), one row per sample, every digit kept.
pub fn csv(record: &Record) -> String {
    let mut out = String::with_capacity(24 * record.num_samples() + 16);
    out.push_str("t,a\n");
    for (k, a) in record.accel.iter().enumerate() {
        out.push_str(&format!("{},{a}\n", k as f64 * record.dt));
    }
    out
}

/// Writes [`csv()`] to `path` atomically (a temporary file, then renamed into place).
pub fn write_csv(record: &Record, path: &Path) -> Result<(), OutputError> {
    write_atomic(path, csv(record).as_bytes())
}

/// The reading options of `pounding record`'s arguments: a component (a number or a name),
/// units by name, a time step, and processing when a baseline or a corner is given.
pub fn options(
    component: Option<&str>,
    units: Option<&str>,
    dt: Option<f64>,
    baseline: Option<&str>,
    highpass_hz: Option<f64>,
    lowpass_hz: Option<f64>,
    order: usize,
) -> Result<RecordOptions, String> {
    let component = component.map(|c| match c.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Component::Index(n),
        _ => Component::Name(c.trim().to_string()),
    });
    let units = match units {
        None => None,
        Some(u) => Some(
            AccelUnits::from_name(u)
                .ok_or_else(|| format!("--units {u}: must be g, cm/s2 (gal) or m/s2"))?,
        ),
    };
    let baseline = match baseline {
        None => None,
        Some("linear") => Some(Baseline::Linear),
        Some("polynomial") => Some(Baseline::Polynomial),
        Some(b) => return Err(format!("--baseline {b}: must be linear or polynomial")),
    };
    let processing = (baseline.is_some() || highpass_hz.is_some() || lowpass_hz.is_some())
        .then_some(Processing {
            baseline,
            highpass_hz,
            lowpass_hz,
            order,
        });
    Ok(RecordOptions {
        units,
        dt,
        component,
        processing,
        ..RecordOptions::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_of_a_sampled_sine() {
        // a = A sin(2π f t), sampled so that a sample falls on the first crest
        let (a0, f, dt) = (2.5, 1.25, 0.01);
        let accel: Vec<f64> = (0..801)
            .map(|k| a0 * (2.0 * std::f64::consts::PI * f * k as f64 * dt).sin())
            .collect();
        let r = Record::from_samples(dt, accel, "sine".into()).unwrap();
        let s = RecordSummary::of(&r, "sine.txt");
        assert_eq!(s.points, 801);
        assert_eq!(s.dt, dt);
        assert!((s.pga - a0).abs() < 1e-12);
        assert!((s.pga_g - a0 / STANDARD_GRAVITY).abs() < 1e-12);
        // the first crest: t = 1/(4f) = 0.2 s
        assert!((s.pga_time - 0.2).abs() < 1e-12, "{}", s.pga_time);
        let j: serde_json::Value = serde_json::from_str(&s.json()).unwrap();
        for key in ["format", "component", "dt", "points", "pga", "pga_time"] {
            assert!(j.get(key).is_some(), "{key}");
        }
        assert_eq!(j["format"], "one-column");
        assert!(s.text().contains("801"));
        let c = csv(&r);
        let mut lines = c.lines();
        assert_eq!(lines.next(), Some("t,a"));
        assert_eq!(lines.next(), Some("0,0"));
        assert_eq!(c.lines().count(), 802);
    }
}
