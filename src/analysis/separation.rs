//! Required separation between the structures (docs/model.md §3, paper §3).
//!
//! The design rules combine the two structures' peak displacements at the contact height
//! without pounding; the time-history value is exact for the given motion. The CQC correlation
//! of DDC is the one of the response-spectrum analysis ([`cqc_correlation`], from
//! [`crate::codes::spectrum`]); the rules at every contact level, with the codes, are in
//! [`crate::analysis::level_checks`].

pub use crate::codes::spectrum::cqc_correlation;

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::level_checks::Separations;

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
