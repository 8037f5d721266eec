//! Required separation between the structures (docs/model.md §3, paper §3).
//!
//! The design rules combine the two structures' peak displacements at the contact height
//! without pounding; the time-history value is exact for the given motion. [`Separations`]
//! (summary.json `separation`) holds them at the main (highest) contact level, as it always
//! has, and beside them every level's checks and the verdict ([`crate::analysis::gap_report`]).

use serde::Serialize;

/// A separation rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// Absolute sum `w₁ + w₂`.
    Abs,
    /// Square root of the sum of squares `√(w₁² + w₂²)`.
    Srss,
    /// Double difference combination with the CQC correlation (docs/model.md §3).
    Ddc,
    /// DDC as printed in the seed paper (eq. 22–23: factor 2 in ρ, no 2 on the cross term).
    /// Kept only to reproduce the paper; not a correct rule.
    DdcPaper,
}

/// CQC correlation of two modes with damping ratios ζ₁, ζ₂ and period ratio r = T₁/T₂:
/// `ρ = 8√(ζ₁ζ₂)(ζ₁ + rζ₂) r^{3/2} / [(1−r²)² + 4ζ₁ζ₂ r(1+r²) + 4(ζ₁² + ζ₂²) r²]`.
pub fn cqc_correlation(zeta1: f64, zeta2: f64, r: f64) -> f64 {
    let num = 8.0 * (zeta1 * zeta2).sqrt() * (zeta1 + r * zeta2) * r.powf(1.5);
    let den = (1.0 - r * r).powi(2)
        + 4.0 * zeta1 * zeta2 * r * (1.0 + r * r)
        + 4.0 * (zeta1 * zeta1 + zeta2 * zeta2) * r * r;
    num / den
}

/// Inputs of the design rules.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PeakPair {
    /// Peak |w₁(h)| without pounding, m.
    pub w1: f64,
    /// Peak |w₂(h)| without pounding, m.
    pub w2: f64,
    /// First-mode damping ratio of structure 1.
    pub zeta1: f64,
    /// First-mode damping ratio of structure 2.
    pub zeta2: f64,
    /// First-mode period ratio r = T₁/T₂.
    pub period_ratio: f64,
}

impl PeakPair {
    /// The separation given by `rule`, m.
    pub fn separation(&self, rule: Rule) -> f64 {
        let (a, b) = (self.w1, self.w2);
        match rule {
            Rule::Abs => a + b,
            Rule::Srss => (a * a + b * b).sqrt(),
            Rule::Ddc => {
                let rho = cqc_correlation(self.zeta1, self.zeta2, self.period_ratio);
                (a * a + b * b - 2.0 * rho * a * b).max(0.0).sqrt()
            }
            Rule::DdcPaper => {
                let rho = cqc_correlation(self.zeta1, self.zeta2, self.period_ratio) / 4.0;
                (a * a + b * b - rho * a * b).max(0.0).sqrt()
            }
        }
    }
}

/// Every rule side by side, plus the exact time-history value, m: `abs` … `rho` and `codes` at
/// the main (highest) contact level; `levels` and `verdict` at every level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Separations {
    /// ABS, m.
    pub abs: f64,
    /// SRSS, m.
    pub srss: f64,
    /// DDC with the CQC correlation, m.
    pub ddc: f64,
    /// DDC as printed in the paper, m.
    pub ddc_paper: f64,
    /// `max_t [w₁(h,t) − w₂(h,t)]` without pounding (0 if they only move apart), m: the
    /// smallest gap at which the structures do not touch.
    pub time_history: f64,
    /// CQC correlation ρ₁₂ used by DDC.
    pub rho: f64,
    /// The building codes of the scenario's `[separation]` table at the main contact level
    /// (empty without it).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub codes: Vec<crate::analysis::gap_report::CodeCheck>,
    /// Where the peaks fed to the rules come from (the run without pounding: elastic, or
    /// inelastic with yielding storeys).
    pub peaks_from: crate::analysis::gap_report::PeakSource,
    /// Every rule at every contact level, in the order of the scenario's levels (as the
    /// report's `levels`); empty when not computed.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub levels: Vec<crate::analysis::gap_report::LevelCheck>,
    /// Each rule at its governing level (the smallest gap − required over the levels).
    #[serde(skip_serializing_if = "crate::analysis::gap_report::Verdict::is_empty")]
    pub verdict: crate::analysis::gap_report::Verdict,
}

impl Separations {
    /// All rules for `peaks`, with the time-history value `exact` (m).
    pub fn new(peaks: &PeakPair, exact: f64) -> Separations {
        Separations {
            abs: peaks.separation(Rule::Abs),
            srss: peaks.separation(Rule::Srss),
            ddc: peaks.separation(Rule::Ddc),
            ddc_paper: peaks.separation(Rule::DdcPaper),
            time_history: exact.max(0.0),
            rho: cqc_correlation(peaks.zeta1, peaks.zeta2, peaks.period_ratio),
            codes: Vec::new(),
            peaks_from: crate::analysis::gap_report::PeakSource::TimeHistory,
            levels: Vec::new(),
            verdict: Default::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Equal periods and damping: ρ = 1 exactly, DDC = |w₁ − w₂|.
    #[test]
    fn equal_structures_are_fully_correlated() {
        assert!((cqc_correlation(0.05, 0.05, 1.0) - 1.0).abs() < 1e-15);
        let p = PeakPair {
            w1: 0.3,
            w2: 0.1,
            zeta1: 0.05,
            zeta2: 0.05,
            period_ratio: 1.0,
        };
        assert!((p.separation(Rule::Ddc) - 0.2).abs() < 1e-12);
    }

    /// Hand computation: ζ₁ = ζ₂ = 0.05, r = 0.5.
    /// num = 8·0.05·(0.05 + 0.025)·0.5^1.5 = 0.4·0.075·0.353553 = 0.0106066
    /// den = 0.5625 + 4·0.0025·0.5·1.25 + 4·0.005·0.25 = 0.5625 + 0.00625 + 0.005 = 0.57375
    /// ρ = 0.0184864
    #[test]
    fn cqc_hand_value() {
        let rho = cqc_correlation(0.05, 0.05, 0.5);
        let expected = 0.4 * 0.075 * 0.5f64.powf(1.5) / 0.57375;
        assert!((rho - expected).abs() < 1e-15);
        assert!((rho - 0.0184864).abs() < 1e-6);
    }

    /// ABS, SRSS and DDC for w₁ = 3, w₂ = 4 (a 3-4-5 triangle), ζ = 0.02, r = 0.7.
    #[test]
    fn rules_hand_values() {
        let p = PeakPair {
            w1: 3.0,
            w2: 4.0,
            zeta1: 0.02,
            zeta2: 0.02,
            period_ratio: 0.7,
        };
        assert_eq!(p.separation(Rule::Abs), 7.0);
        assert!((p.separation(Rule::Srss) - 5.0).abs() < 1e-15);
        // ρ by hand: num = 8·0.02·(0.02+0.014)·0.7^1.5 = 0.00544·0.585662 = 0.00318600
        // den = 0.2601 + 4·0.0004·0.7·1.49 + 4·0.0008·0.49 = 0.2601 + 0.0016688 + 0.001568 = 0.2633368
        let rho = 0.00544 * 0.7f64.powf(1.5) / 0.2633368;
        let ddc = (25.0 - 2.0 * rho * 12.0).sqrt();
        assert!((p.separation(Rule::Ddc) - ddc).abs() < 1e-12);
        let ddc_paper = (25.0 - rho / 4.0 * 12.0).sqrt();
        assert!((p.separation(Rule::DdcPaper) - ddc_paper).abs() < 1e-12);
        // SRSS ≥ ABS/√2 always (docs/model.md §4)
        assert!(p.separation(Rule::Srss) >= p.separation(Rule::Abs) / 2f64.sqrt());
    }

    #[test]
    fn negative_time_history_separation_clamps_to_zero() {
        let p = PeakPair {
            w1: 1.0,
            w2: 1.0,
            zeta1: 0.01,
            zeta2: 0.01,
            period_ratio: 0.5,
        };
        assert_eq!(Separations::new(&p, -0.2).time_history, 0.0);
    }
}
