//! What `pounding spectrum` and `pounding scale` print: a table of text and JSON for scripts.
//! The JSON keys of `pounding spectrum` — per record `periods` (s), `psa` (m/s²) and `psa_g` —
//! are a contract; the others may grow.

use serde::Serialize;

use crate::analysis::record_spectrum::scaling::{PeriodRange, ScaledSuite, Target};
use crate::analysis::record_spectrum::{ResponseSpectrum, SpectrumInputError};
use crate::model::ground_motion::{Record, STANDARD_GRAVITY};

/// One record's spectrum, as `pounding spectrum --json` gives it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordEntry {
    /// The file as given.
    pub file: String,
    /// The component read, as the file names it.
    pub component: Option<String>,
    /// Time step, s.
    pub dt: f64,
    /// PGA, m/s².
    pub pga: f64,
    /// Periods, s.
    pub periods: Vec<f64>,
    /// Pseudo-acceleration, m/s².
    pub psa: Vec<f64>,
    /// Pseudo-acceleration, g.
    pub psa_g: Vec<f64>,
    /// Spectral displacement, m.
    pub sd: Vec<f64>,
    /// Pseudo-velocity, m/s.
    pub psv: Vec<f64>,
    /// Peak total acceleration, m/s².
    pub sa_abs: Vec<f64>,
}

/// A spectrum over the same periods: the records' mean or a target.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Curve {
    /// What it is.
    pub description: String,
    /// Pseudo-acceleration, m/s² (`null` where a target table does not reach).
    pub psa: Vec<Option<f64>>,
    /// Pseudo-acceleration, g.
    pub psa_g: Vec<Option<f64>>,
}

/// The spectra of `pounding spectrum`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpectrumReport {
    /// Damping ratio.
    pub damping: f64,
    /// Periods, s.
    pub periods: Vec<f64>,
    /// One entry per record, in the order given.
    pub records: Vec<RecordEntry>,
    /// The arithmetic mean of the records' PSA (with two records or more).
    pub mean: Option<Curve>,
    /// The target spectrum, when one is given.
    pub target: Option<Curve>,
    /// The code's period range, when first-mode periods are given, s.
    pub range: Option<PeriodRange>,
}

impl SpectrumReport {
    /// The spectra of `records` (file name, record) at `periods` with `damping`, with an
    /// optional target and period range to show beside them.
    pub fn new(
        records: &[(&str, &Record)],
        periods: &[f64],
        damping: f64,
        target: Option<&Target>,
        range: Option<PeriodRange>,
    ) -> Result<SpectrumReport, SpectrumInputError> {
        let mut entries = Vec::with_capacity(records.len());
        for (file, r) in records {
            let s = ResponseSpectrum::of_record(r, periods, damping).map_err(|e| match e {
                SpectrumInputError::PeriodBelowStep {
                    period, dt, limit, ..
                } => SpectrumInputError::PeriodBelowStep {
                    file: file.to_string(),
                    period,
                    dt,
                    limit,
                },
                other => other,
            })?;
            entries.push(RecordEntry {
                file: file.to_string(),
                component: r.component.clone(),
                dt: r.dt,
                pga: s.pga,
                psa_g: s.psa.iter().map(|a| a / STANDARD_GRAVITY).collect(),
                periods: s.periods,
                psa: s.psa,
                sd: s.sd,
                psv: s.psv,
                sa_abs: s.sa_abs,
            });
        }
        let curve = |description: String, psa: Vec<Option<f64>>| Curve {
            description,
            psa_g: psa
                .iter()
                .map(|a| a.map(|a| a / STANDARD_GRAVITY))
                .collect(),
            psa,
        };
        let mean = (entries.len() > 1).then(|| {
            let n = entries.len() as f64;
            let psa = (0..periods.len())
                .map(|j| Some(entries.iter().map(|e| e.psa[j]).sum::<f64>() / n))
                .collect();
            curve(format!("mean of {} records", entries.len()), psa)
        });
        let target = target.map(|t| {
            let psa = periods.iter().map(|&p| t.sa(p).ok()).collect();
            curve(t.description.clone(), psa)
        });
        Ok(SpectrumReport {
            damping,
            periods: periods.to_vec(),
            records: entries,
            mean,
            target,
            range,
        })
    }

    /// The table: the records numbered, then a row per period with each record's PSA in g,
    /// the mean and the target.
    pub fn text(&self) -> String {
        let mut out = format!(
            "  pseudo-acceleration PSA = ω²·S_d, {} % damping, in g (g = {STANDARD_GRAVITY} m/s²)\n",
            fmt(100.0 * self.damping)
        );
        for (i, r) in self.records.iter().enumerate() {
            let comp = r
                .component
                .as_deref()
                .map_or(String::new(), |c| format!(", {c}"));
            out.push_str(&format!(
                "  [{}] {}{comp}: dt = {} s, PGA = {:.4} g\n",
                i + 1,
                r.file,
                r.dt,
                r.pga / STANDARD_GRAVITY
            ));
        }
        if let Some(t) = &self.target {
            out.push_str(&format!("  target: {}\n", t.description));
        }
        if let Some(r) = &self.range {
            out.push_str(&format!(
                "  period range: {} to {} s (0.2 × the shortest, 2 × the longest first-mode period)\n",
                fmt(r.lo),
                fmt(r.hi)
            ));
        }
        let mut header = format!("  {:>8}", "T [s]");
        for i in 0..self.records.len() {
            header.push_str(&format!(" {:>9}", format!("[{}]", i + 1)));
        }
        if self.mean.is_some() {
            header.push_str(&format!(" {:>9}", "mean"));
        }
        if self.target.is_some() {
            header.push_str(&format!(" {:>9}", "target"));
        }
        out.push_str(&header);
        out.push('\n');
        for (j, &t) in self.periods.iter().enumerate() {
            let mark = match &self.range {
                Some(r) if t >= r.lo && t <= r.hi => "*",
                _ => " ",
            };
            let mut row = format!(" {mark}{:>8}", fmt(t));
            for r in &self.records {
                row.push_str(&format!(" {:>9.4}", r.psa_g[j]));
            }
            for c in [&self.mean, &self.target].into_iter().flatten() {
                match c.psa_g[j] {
                    Some(v) => row.push_str(&format!(" {v:>9.4}")),
                    None => row.push_str(&format!(" {:>9}", "—")),
                }
            }
            out.push_str(&row);
            out.push('\n');
        }
        if self.range.is_some() {
            out.push_str("  * inside the period range\n");
        }
        out
    }

    /// Pretty JSON.
    pub fn json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|_| "{}".into())
    }
}

impl ScaledSuite {
    /// The scaling report as text: the rule, target and range, a row per record (shape
    /// factor, factor, PGA before and after), the lowest mean-to-target ratio and where, EC8's
    /// PGA check, what governs and the notes.
    pub fn text(&self) -> String {
        let g = STANDARD_GRAVITY;
        let mut out = String::new();
        let t1: Vec<String> = self.first_mode_periods.iter().map(|t| fmt(*t)).collect();
        out.push_str(&format!("  rule              {}\n", self.rule_name));
        out.push_str(&format!(
            "  target            {}\n",
            self.target_description
        ));
        out.push_str(&format!(
            "  first-mode T       {} s → code range {} to {} s",
            t1.join(", "),
            fmt(self.code_range.lo),
            fmt(self.code_range.hi)
        ));
        if self.range != self.code_range {
            out.push_str(&format!(
                "; checked over {} to {} s",
                fmt(self.range.lo),
                fmt(self.range.hi)
            ));
        }
        out.push_str(&format!(" ({} periods)\n", self.periods.len()));
        if let Some((lo, hi)) = self.factor_limits {
            out.push_str(&format!("  factor limits     {} to {}\n", fmt(lo), fmt(hi)));
        }
        let width = self
            .records
            .iter()
            .map(|r| r.name.chars().count())
            .max()
            .unwrap_or(4)
            .max(6);
        out.push_str(&format!(
            "\n  {:<width$}  {:>8}  {:>9}  {:>9}  {:>9}  {:>14}\n",
            "record", "dt [s]", "PGA [g]", "shape f⁰", "factor", "scaled PGA [g]"
        ));
        for r in &self.records {
            let limit = r.at_limit.map_or(String::new(), |l| format!(" ({l})"));
            out.push_str(&format!(
                "  {:<width$}  {:>8}  {:>9.4}  {:>9.4}  {:>9.4}  {:>14.4}{limit}\n",
                r.name,
                fmt(r.dt),
                r.pga / g,
                r.shape_factor,
                r.factor,
                r.scaled_pga / g
            ));
        }
        out.push_str(&format!(
            "\n  mean / target     lowest {:.4} at T = {} s (required ≥ {})\n",
            self.min_ratio,
            fmt(self.min_ratio_period),
            fmt(self.required_ratio)
        ));
        if let Some(p) = &self.pga_check {
            out.push_str(&format!(
                "  mean PGA          {:.4} g against a_g·S = {:.4} g (ratio {:.4}, required ≥ 1)\n",
                p.mean_pga / g,
                p.required / g,
                p.ratio
            ));
        }
        out.push_str(&format!("  governs           {}\n", self.governs));
        for n in &self.notes {
            out.push_str(&format!("  note: {n}\n"));
        }
        out
    }

    /// Pretty JSON of the whole result (factors, grid, target, mean, ratios).
    pub fn json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|_| "{}".into())
    }
}

/// A number with up to 4 significant decimals and no trailing zeros.
fn fmt(x: f64) -> String {
    crate::numerics::format::fmt_num(x).replace('−', "-")
}
