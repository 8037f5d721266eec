//! What `pounding scale --sa T,SA` prints: each record's factor to a target pseudo-spectral
//! acceleration at one period, with its PSA and PGA before and after
//! ([`crate::analysis::record_spectrum::single::SaScaling`]).
//!
//! The JSON (`--json`) is a contract for scripts: `period` (s), `damping`, `sa_g` (g), `sa`
//! (m/s²), and `records`, each with `record` (the file as given), `dt` (s), `factor`,
//! `psa_before` and `psa_after` (m/s²), `pga_before` and `pga_after` (m/s²).

use crate::analysis::record_spectrum::single::SaScaling;
use crate::model::ground_motion::STANDARD_GRAVITY;

impl SaScaling {
    /// The table `pounding scale --sa` prints (accelerations in g).
    pub fn text(&self) -> String {
        let g = STANDARD_GRAVITY;
        let mut out = format!(
            "  target            PSA(T = {} s, ζ = {} %) = {} g ({:.4} m/s²)\n",
            fmt(self.period),
            fmt(100.0 * self.damping),
            fmt(self.sa_g),
            self.sa
        );
        let width = self
            .records
            .iter()
            .map(|r| r.record.chars().count())
            .max()
            .unwrap_or(6)
            .max(6);
        out.push_str(&format!(
            "\n  {:<width$}  {:>8}  {:>9}  {:>10}  {:>9}  {:>10}  {:>10}\n",
            "record", "dt [s]", "PGA [g]", "PSA [g]", "factor", "scaled PSA", "scaled PGA"
        ));
        for r in &self.records {
            out.push_str(&format!(
                "  {:<width$}  {:>8}  {:>9.4}  {:>10.4}  {:>9.4}  {:>10.4}  {:>10.4}\n",
                r.record,
                fmt(r.dt),
                r.pga_before / g,
                r.psa_before / g,
                r.factor,
                r.psa_after / g,
                r.pga_after / g
            ));
        }
        out.push_str(
            "\n  factor = target / PSA(T) of the record as read; scaled PSA computed again from \
             the scaled record\n",
        );
        out
    }

    /// Pretty JSON (the contract in the module's documentation).
    pub fn json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|_| "{}".into())
    }
}

/// A number with up to 4 significant decimals and no trailing zeros.
fn fmt(x: f64) -> String {
    crate::numerics::format::fmt_num(x).replace('−', "-")
}
