//! Statistics across the records of a suite and the codes' design value (docs/codes.md,
//! "Design values of a suite").
//!
//! - mean: the arithmetic mean;
//! - median and 84th percentile: sample quantiles by definition 7 of Hyndman & Fan (1996,
//!   "Sample quantiles in statistical packages", *The American Statistician* 50(4), 361–365;
//!   the default of R's `quantile` and NumPy's `percentile`): with the n values sorted,
//!   x₍₁₎ ≤ … ≤ x₍ₙ₎, h = (n − 1)p and Q(p) = x₍⌊h⌋+1₎ + (h − ⌊h⌋)(x₍⌊h⌋+2₎ − x₍⌊h⌋+1₎) —
//!   the median of an even count is the average of the middle two, and Q(p) lies between
//!   the smallest and the largest value. It needs no distribution: a lognormal 84th
//!   percentile (median × e^β) is undefined for the zeros a suite has (no impact);
//! - max: the largest value (the most unfavourable);
//! - design: the code's design value ([`DesignStatistic`]).

use serde::Serialize;

use crate::input::scenario::suite::SuiteRule;

/// Which statistic of the suite is the code's design value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DesignStatistic {
    /// The mean over the records.
    Mean,
    /// The largest value over the records (the most unfavourable).
    Max,
}

impl DesignStatistic {
    /// The statistic `rule` takes as the design value of a suite of `n` records, with the
    /// clause that says so:
    /// - ASCE 7-16 Chapter 16 (§16.4: the mean of the suite's response; the suite has ≥ 11
    ///   records, §16.2.2): the mean;
    /// - EN 1998-1 §4.3.3.4.3(3): with at least 7 analyses the average response, otherwise
    ///   the most unfavourable value;
    /// - no rule: the most unfavourable value (no code procedure is claimed).
    pub fn for_rule(rule: SuiteRule, n: usize) -> (DesignStatistic, &'static str) {
        match rule {
            SuiteRule::Asce7 => (
                DesignStatistic::Mean,
                "ASCE 7-16 §16.4: the mean over the suite (≥ 11 records, §16.2.2)",
            ),
            SuiteRule::Ec8 if n >= 7 => (
                DesignStatistic::Mean,
                "EN 1998-1 §4.3.3.4.3(3): at least 7 analyses, the average response",
            ),
            SuiteRule::Ec8 => (
                DesignStatistic::Max,
                "EN 1998-1 §4.3.3.4.3(3): fewer than 7 analyses, the most unfavourable value",
            ),
            SuiteRule::None => (
                DesignStatistic::Max,
                "no code rule: the most unfavourable record",
            ),
        }
    }

    /// The key as summary.json writes it: `mean`, `max`.
    pub fn key(self) -> &'static str {
        match self {
            DesignStatistic::Mean => "mean",
            DesignStatistic::Max => "max",
        }
    }
}

/// One quantity across the records.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Statistics {
    /// Arithmetic mean.
    pub mean: f64,
    /// Median (Hyndman & Fan definition 7, p = 0.5).
    pub median: f64,
    /// 84th percentile (Hyndman & Fan definition 7, p = 0.84).
    pub p84: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// The design value: `mean` or `max` as the rule says.
    pub design: f64,
}

impl Statistics {
    /// The statistics of `values` (at least one, all finite) with the design value by
    /// `design`. NaN everywhere for no values or a non-finite one.
    pub fn of(values: &[f64], design: DesignStatistic) -> Statistics {
        if values.is_empty() || values.iter().any(|v| !v.is_finite()) {
            return Statistics {
                mean: f64::NAN,
                median: f64::NAN,
                p84: f64::NAN,
                min: f64::NAN,
                max: f64::NAN,
                design: f64::NAN,
            };
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let max = sorted[sorted.len() - 1];
        Statistics {
            mean,
            median: quantile(&sorted, 0.5),
            p84: quantile(&sorted, 0.84),
            min: sorted[0],
            max,
            design: match design {
                DesignStatistic::Mean => mean,
                DesignStatistic::Max => max,
            },
        }
    }
}

/// The sample quantile of Hyndman & Fan's definition 7 at `p` ∈ [0, 1] of `sorted` (ascending,
/// not empty): h = (n − 1)p, linear between the order statistics around h.
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    let n = sorted.len();
    if n == 0 {
        return f64::NAN;
    }
    let h = (n - 1) as f64 * p.clamp(0.0, 1.0);
    let lo = h.floor() as usize;
    let hi = (lo + 1).min(n - 1);
    sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand computation: 1, 2, 3, 4 → h(0.5) = 1.5 → 2.5; h(0.84) = 2.52 → 3 + 0.52 = 3.52.
    #[test]
    fn quantiles_by_hand() {
        let s = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(quantile(&s, 0.5), 2.5);
        assert!((quantile(&s, 0.84) - 3.52).abs() < 1e-15);
        assert_eq!(quantile(&s, 0.0), 1.0);
        assert_eq!(quantile(&s, 1.0), 4.0);
        assert_eq!(quantile(&[7.0], 0.84), 7.0);
    }
}
