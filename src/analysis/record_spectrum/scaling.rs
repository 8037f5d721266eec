//! Amplitude scaling of a suite of records to a target spectrum by the codes' rules
//! (docs/codes.md, "Scaling records to a target spectrum"):
//!
//! - ASCE 7-16 §16.2 ([`ScalingRule::Asce7`]): at least 11 records, amplitude-scaled (one factor
//!   per record) so that the suite's mean 5 %-damped spectrum is not below 90 % of the target over
//!   the period range of §16.2.3.1, from at most 0.2 × the shortest to at least 2 × the longest
//!   first-mode period; the target is the MCE_R spectrum, 1.5 × the design spectrum (§11.4.7,
//!   applied by [`Target::for_rule`] to an ASCE 7 design spectrum).
//! - EN 1998-1 §3.2.3.1.2 with §3.2.3.1.1(4) ([`ScalingRule::Ec8`]): at least 3 records, the
//!   mean of their zero-period spectral values (PGA) not below a_g·S, and no value of the mean
//!   5 %-damped spectrum below 90 % of the elastic spectrum between 0.2 T₁ and 2 T₁.
//!
//! **The factor rule** (a choice: the codes require only the outcome). Each record i first gets
//! its *shape factor* f⁰ᵢ = exp(mean over the range of ln(S_target/PSAᵢ)), the factor that
//! matches the target in the least-squares sense of ln S_a over periods equally spaced in
//! log T; then one common factor c, the smallest that meets every condition of the rule, gives
//! fᵢ = c·f⁰ᵢ (clipped to the user's factor limits, if any). The mean therefore touches the
//! required ratio (0.90, or the user's higher one) at the governing period, or the mean PGA
//! equals a_g·S (EC8), whichever needs the larger c. A suite that cannot meet the rule (too few
//! records, or not even with every record at its largest allowed factor) is refused with the
//! reason.

use serde::Serialize;

use crate::analysis::record_spectrum::{
    DEFAULT_DAMPING, SpectrumInputError, check_input, log_periods,
};
use crate::codes::spectrum::{DesignSpectrum, SpectrumError};
use crate::model::ground_motion::{Record, STANDARD_GRAVITY};

/// The codes' scaling rules, a closed set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ScalingRule {
    /// ASCE/SEI 7-16 Chapter 16 (§16.2.2, §16.2.3.1, §16.2.3.2).
    Asce7,
    /// EN 1998-1:2004 §3.2.3.1.2 (with §3.2.3.1.1(4)).
    Ec8,
}

impl ScalingRule {
    /// The rule from its name on the command line: `asce7` or `ec8`.
    pub fn from_name(name: &str) -> Option<ScalingRule> {
        match name.trim().to_ascii_lowercase().as_str() {
            "asce7" | "asce7-16" => Some(ScalingRule::Asce7),
            "ec8" | "en1998" => Some(ScalingRule::Ec8),
            _ => None,
        }
    }

    /// The short name: `asce7`, `ec8`.
    pub fn key(self) -> &'static str {
        match self {
            ScalingRule::Asce7 => "asce7",
            ScalingRule::Ec8 => "ec8",
        }
    }

    /// The code and clause, as reports print them.
    pub fn name(self) -> &'static str {
        match self {
            ScalingRule::Asce7 => "ASCE 7-16 §16.2.3 (amplitude scaling)",
            ScalingRule::Ec8 => "EN 1998-1 §3.2.3.1.2 with §3.2.3.1.1(4)",
        }
    }

    /// The fewest records the rule accepts: 11 (ASCE 7-16 §16.2.2), 3 (EN 1998-1
    /// §3.2.3.1.1(4)a).
    pub fn min_records(self) -> usize {
        match self {
            ScalingRule::Asce7 => 11,
            ScalingRule::Ec8 => 3,
        }
    }

    /// Where the minimum number of records is written.
    fn count_clause(self) -> &'static str {
        match self {
            ScalingRule::Asce7 => "ASCE 7-16 §16.2.2",
            ScalingRule::Ec8 => "EN 1998-1 §3.2.3.1.1(4)a (by §3.2.3.1.2)",
        }
    }

    /// The lowest mean-to-target ratio the rule allows over its period range: 0.90 for both.
    pub fn min_ratio(self) -> f64 {
        0.9
    }

    /// Whether the mean PGA must reach the target's zero-period value a_g·S (EC8 only).
    pub fn requires_pga(self) -> bool {
        matches!(self, ScalingRule::Ec8)
    }

    /// The code's period range for the first-mode periods `t1` (s): [0.2 min, 2 max] for both
    /// rules (ASCE 7-16 §16.2.3.1 sets the least range, EC8 §3.2.3.1.1(4)c the range).
    pub fn period_range(self, t1: &[f64]) -> PeriodRange {
        PeriodRange::from_first_modes(t1)
    }
}

/// A period range [lo, hi], s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PeriodRange {
    /// Shortest period, s.
    pub lo: f64,
    /// Longest period, s.
    pub hi: f64,
}

impl PeriodRange {
    /// [0.2 × the shortest, 2 × the longest] of the first-mode periods `t1` (s).
    pub fn from_first_modes(t1: &[f64]) -> PeriodRange {
        let lo = t1.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = t1.iter().copied().fold(0.0, f64::max);
        PeriodRange {
            lo: 0.2 * lo,
            hi: 2.0 * hi,
        }
    }

    /// Whether this range contains `other` (to 1e-9 relative).
    pub fn covers(&self, other: &PeriodRange) -> bool {
        self.lo <= other.lo * (1.0 + 1e-9) && self.hi >= other.hi * (1.0 - 1e-9)
    }
}

/// The target spectrum: a design spectrum times a factor (1.5 for ASCE 7's MCE_R), 5 % damped.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Target {
    /// The spectrum as given.
    pub spectrum: DesignSpectrum,
    /// The factor applied to it (1.5: MCE_R = 1.5 × the design spectrum, ASCE 7-16 §11.4.7).
    pub scale: f64,
    /// What the target is, for reports.
    pub description: String,
}

impl Target {
    /// `spectrum` × `scale` (> 0), described by `description`.
    pub fn new(spectrum: DesignSpectrum, scale: f64, description: String) -> Target {
        Target {
            spectrum,
            scale,
            description,
        }
    }

    /// The code's target from a spectrum: for [`ScalingRule::Asce7`] an ASCE 7 design spectrum
    /// becomes the MCE_R spectrum, 1.5 × (ASCE 7-16 §16.2.1 scales to MCE_R; §11.4.7: "the
    /// design response spectrum multiplied by 1.5"); any other spectrum is taken as given (the
    /// user's table is then the MCE_R spectrum; EC8's elastic spectrum is its own target).
    pub fn for_rule(spectrum: DesignSpectrum, rule: ScalingRule) -> Target {
        match (rule, &spectrum) {
            (ScalingRule::Asce7, DesignSpectrum::Asce7(_)) => {
                let mut t = Target::scaled(spectrum, 1.5);
                t.description = format!("MCE_R = {} (ASCE 7-16 §11.4.7)", t.description);
                t
            }
            _ => Target::as_given(spectrum),
        }
    }

    /// `factor` (> 0) × the spectrum.
    pub fn scaled(spectrum: DesignSpectrum, factor: f64) -> Target {
        let mut t = Target::as_given(spectrum);
        t.description = format!(
            "{} × the {}",
            crate::numerics::format::fmt_num(factor),
            t.description
        );
        t.scale = factor;
        t
    }

    /// The spectrum as given.
    pub fn as_given(spectrum: DesignSpectrum) -> Target {
        let name = spectrum.name();
        let description = match &spectrum {
            DesignSpectrum::Ec8(s) => format!(
                "{name} elastic spectrum, a_g = {} m/s², S = {}, T_B = {} s, T_C = {} s, T_D = {} s",
                s.ag(),
                s.shape().s,
                s.shape().tb,
                s.shape().tc,
                s.shape().td
            ),
            DesignSpectrum::Asce7(s) => format!(
                "{name} design spectrum (S_DS = {} g, S_D1 = {} g, T_L = {} s)",
                s.sds(),
                s.sd1(),
                s.tl()
            ),
            DesignSpectrum::Table(t) => format!(
                "table spectrum ({} pairs, {} to {} s)",
                t.periods().len(),
                t.periods().first().copied().unwrap_or(0.0),
                t.periods().last().copied().unwrap_or(0.0)
            ),
        };
        Target::new(spectrum, 1.0, description)
    }

    /// S_a(T) of the target, m/s², 5 % damped.
    pub fn sa(&self, period: f64) -> Result<f64, SpectrumError> {
        Ok(self.scale * self.spectrum.acceleration(period, DEFAULT_DAMPING)?)
    }
}

/// One record of a suite: its name (the file, for reports and errors) and the record.
#[derive(Debug, Clone, Copy)]
pub struct SuiteMember<'a> {
    /// The file as given.
    pub name: &'a str,
    /// The record read from it.
    pub record: &'a Record,
}

/// How to scale a suite.
#[derive(Debug, Clone, PartialEq)]
pub struct ScalingOptions {
    /// The code's rule.
    pub rule: ScalingRule,
    /// First-mode periods of the structures, s (one or both of a pounding pair).
    pub first_mode_periods: Vec<f64>,
    /// A wider period range than the code's least one (ASCE 7-16 §16.2.3.1 asks for the modes
    /// of 90 % mass participation too); `None`: the code's range.
    pub range: Option<PeriodRange>,
    /// The mean-to-target ratio to reach, at least the rule's 0.90.
    pub required_ratio: f64,
    /// Smallest and largest factor allowed per record, if any.
    pub factor_limits: Option<(f64, f64)>,
    /// Periods per decade of the grid on which the mean is checked (≥ 10).
    pub points_per_decade: usize,
}

impl ScalingOptions {
    /// The rule's defaults for first-mode periods `t1`: the code's range, its ratio, no limits,
    /// 100 periods a decade.
    pub fn new(rule: ScalingRule, t1: &[f64]) -> ScalingOptions {
        ScalingOptions {
            rule,
            first_mode_periods: t1.to_vec(),
            range: None,
            required_ratio: rule.min_ratio(),
            factor_limits: None,
            points_per_decade: 100,
        }
    }
}

/// Why a suite could not be scaled.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScalingError {
    /// Fewer records than the rule requires.
    #[error("{clause} requires at least {required} records; {given} given")]
    TooFewRecords {
        /// Where the minimum is written.
        clause: &'static str,
        /// The minimum.
        required: usize,
        /// How many were given.
        given: usize,
    },
    /// No first-mode period, or one that is not positive.
    #[error("first-mode periods {0:?} s: give one or two, each finite and > 0")]
    BadFirstMode(Vec<f64>),
    /// A period range narrower than the code's.
    #[error(
        "period range [{lo}, {hi}] s does not cover the code's range [{code_lo}, {code_hi}] s \
         (0.2 × the shortest to 2 × the longest first-mode period); it may only be wider"
    )]
    RangeTooNarrow {
        /// Range given, s.
        lo: f64,
        /// Range given, s.
        hi: f64,
        /// The code's range, s.
        code_lo: f64,
        /// The code's range, s.
        code_hi: f64,
    },
    /// A required ratio below the code's.
    #[error("required mean-to-target ratio {given} is below the code's {code} (or not finite)")]
    BadRatio {
        /// Ratio given.
        given: f64,
        /// The code's.
        code: f64,
    },
    /// Factor limits that are not 0 < min ≤ max.
    #[error("factor limits [{0}, {1}] must satisfy 0 < min ≤ max, both finite")]
    BadLimits(f64, f64),
    /// The target spectrum cannot be evaluated where needed.
    #[error("target spectrum at T = {period} s: {source}")]
    Target {
        /// Period, s.
        period: f64,
        /// Why.
        source: SpectrumError,
    },
    /// A record that does not respond at a period (all zeros).
    #[error("record \"{record}\": no spectral response at T = {period} s (a record of zeros?)")]
    NoResponse {
        /// The record.
        record: String,
        /// Period, s.
        period: f64,
    },
    /// A target S_a that is not positive.
    #[error("target spectral acceleration {0} m/s² must be positive and finite")]
    BadTargetSa(f64),
    /// Periods or damping not accepted for a record.
    #[error(transparent)]
    Input(#[from] SpectrumInputError),
    /// The rule cannot be met.
    #[error("the suite cannot meet {rule}: {reason}")]
    Infeasible {
        /// The rule's name.
        rule: &'static str,
        /// Why, with the numbers.
        reason: String,
    },
}

/// One record of a scaled suite.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScaledRecord {
    /// The file.
    pub name: String,
    /// Time step, s.
    pub dt: f64,
    /// PGA of the record as read, m/s².
    pub pga: f64,
    /// The shape factor f⁰ (least squares of ln S_a over the range).
    pub shape_factor: f64,
    /// The factor to apply to the record.
    pub factor: f64,
    /// Its PGA after scaling, m/s².
    pub scaled_pga: f64,
    /// `"min"` or `"max"` when the factor is held at a limit.
    pub at_limit: Option<&'static str>,
    /// PSA of the record as read at the grid's periods, m/s².
    pub psa: Vec<f64>,
    /// PSA of the record as read at [`ScaledSuite::display_periods`], m/s².
    pub display_psa: Vec<f64>,
}

/// EN 1998-1's zero-period check: the mean PGA of the scaled records against a_g·S.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PgaCheck {
    /// Mean PGA of the scaled records, m/s².
    pub mean_pga: f64,
    /// The target's value at T = 0 (a_g·S for an EN 1998-1 spectrum), m/s².
    pub required: f64,
    /// mean_pga / required (≥ 1 to pass).
    pub ratio: f64,
}

/// A suite scaled by a code's rule.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScaledSuite {
    /// The rule (`asce7`, `ec8`).
    pub rule: ScalingRule,
    /// The rule's code and clause.
    pub rule_name: &'static str,
    /// The target.
    pub target_description: String,
    /// Damping ratio of the spectra: 0.05.
    pub damping: f64,
    /// First-mode periods, s.
    pub first_mode_periods: Vec<f64>,
    /// The code's range, s.
    pub code_range: PeriodRange,
    /// The range checked (the code's, or wider), s.
    pub range: PeriodRange,
    /// The grid of periods in the range, s.
    pub periods: Vec<f64>,
    /// The target at the grid, m/s².
    pub target: Vec<f64>,
    /// The scaled suite's mean PSA at the grid, m/s².
    pub mean: Vec<f64>,
    /// mean / target at the grid.
    pub ratio: Vec<f64>,
    /// The ratio to reach (0.90 or higher).
    pub required_ratio: f64,
    /// The lowest mean-to-target ratio over the range.
    pub min_ratio: f64,
    /// Where it occurs, s.
    pub min_ratio_period: f64,
    /// EC8's mean-PGA check (None for ASCE 7).
    pub pga_check: Option<PgaCheck>,
    /// The common factor c (fᵢ = c·f⁰ᵢ before limits).
    pub common_factor: f64,
    /// What set the factors.
    pub governs: String,
    /// Factor limits applied, if any.
    pub factor_limits: Option<(f64, f64)>,
    /// The records.
    pub records: Vec<ScaledRecord>,
    /// Periods for a picture around the range (from a third of its start to three times its
    /// end), s.
    pub display_periods: Vec<f64>,
    /// The target there, m/s² (`null` where a table does not reach).
    pub display_target: Vec<Option<f64>>,
    /// What the user should know about the rule's application.
    pub notes: Vec<String>,
}

/// The suite driver's entry: [`SuiteScaling::compute`].
pub struct SuiteScaling;

/// The rule's conditions at one set of factors.
struct Outcome {
    min_ratio: f64,
    min_period: f64,
    mean_pga: f64,
}

impl SuiteScaling {
    /// Scales `members` to `target` by `opts.rule` (see the module's factor rule). Errors name
    /// the record, the clause or the period concerned.
    pub fn compute(
        members: &[SuiteMember],
        target: &Target,
        opts: &ScalingOptions,
    ) -> Result<ScaledSuite, ScalingError> {
        let rule = opts.rule;
        if members.len() < rule.min_records() {
            return Err(ScalingError::TooFewRecords {
                clause: rule.count_clause(),
                required: rule.min_records(),
                given: members.len(),
            });
        }
        let t1 = &opts.first_mode_periods;
        if t1.is_empty() || t1.iter().any(|t| !(t.is_finite() && *t > 0.0)) {
            return Err(ScalingError::BadFirstMode(t1.clone()));
        }
        let code_range = rule.period_range(t1);
        let range = opts.range.unwrap_or(code_range);
        let ordered = range.lo > 0.0 && range.hi > range.lo && range.hi.is_finite();
        if !(ordered && range.covers(&code_range)) {
            return Err(ScalingError::RangeTooNarrow {
                lo: range.lo,
                hi: range.hi,
                code_lo: code_range.lo,
                code_hi: code_range.hi,
            });
        }
        let required = opts.required_ratio;
        if !(required.is_finite() && required >= rule.min_ratio()) {
            return Err(ScalingError::BadRatio {
                given: required,
                code: rule.min_ratio(),
            });
        }
        if let Some((lo, hi)) = opts.factor_limits
            && !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi)
        {
            return Err(ScalingError::BadLimits(lo, hi));
        }

        // the grid: log-spaced over the range, with the first-mode periods themselves
        let decades = (range.hi / range.lo).log10();
        let n = ((decades * opts.points_per_decade.max(10) as f64).ceil() as usize + 1).max(21);
        let mut periods = log_periods(range.lo, range.hi, n);
        periods.extend(t1.iter().copied());
        periods.sort_by(f64::total_cmp);
        periods.dedup();
        let target_at = |t: f64| {
            target
                .sa(t)
                .map_err(|source| ScalingError::Target { period: t, source })
        };
        let target_sa: Vec<f64> = periods
            .iter()
            .map(|&t| target_at(t))
            .collect::<Result<_, _>>()?;
        let zero_period = if rule.requires_pga() {
            Some(target_at(0.0)?)
        } else {
            None
        };

        // each record's spectrum and shape factor
        let mut psa = Vec::with_capacity(members.len());
        let mut shape = Vec::with_capacity(members.len());
        for m in members {
            let r = m.record;
            check_input(m.name, r.dt, &periods, DEFAULT_DAMPING)?;
            let s: Vec<f64> = periods
                .iter()
                .map(|&t| super::spectral_point(&r.accel, r.dt, t, DEFAULT_DAMPING).psa)
                .collect();
            if let Some(k) = s.iter().position(|v| v.is_nan() || *v <= 0.0) {
                return Err(ScalingError::NoResponse {
                    record: m.name.to_string(),
                    period: periods[k],
                });
            }
            let mean_log = s
                .iter()
                .zip(&target_sa)
                .map(|(sr, st)| (st / sr).ln())
                .sum::<f64>()
                / s.len() as f64;
            shape.push(mean_log.exp());
            psa.push(s);
        }
        let pga: Vec<f64> = members.iter().map(|m| m.record.pga()).collect();
        // a wider grid for pictures (records whose dt is too long for its short end are cut)
        let display_periods = log_periods(range.lo / 3.0, range.hi * 3.0, 121);
        let display_psa: Vec<Vec<f64>> = members
            .iter()
            .map(|m| {
                let r = m.record;
                display_periods
                    .iter()
                    .map(|&t| match t >= super::MIN_PERIOD_OVER_DT * r.dt {
                        true => super::spectral_point(&r.accel, r.dt, t, DEFAULT_DAMPING).psa,
                        false => f64::NAN,
                    })
                    .collect()
            })
            .collect();
        let display_target = display_periods.iter().map(|&t| target.sa(t).ok()).collect();

        let factors = |c: f64| -> Vec<f64> {
            shape
                .iter()
                .map(|f0| {
                    let f = c * f0;
                    match opts.factor_limits {
                        Some((lo, hi)) => f.clamp(lo, hi),
                        None => f,
                    }
                })
                .collect()
        };
        let outcome = |f: &[f64]| -> Outcome {
            let k = f.len() as f64;
            let mut worst = (f64::INFINITY, 0.0);
            for (j, (&t, st)) in periods.iter().zip(&target_sa).enumerate() {
                let mean = f.iter().zip(&psa).map(|(fi, s)| fi * s[j]).sum::<f64>() / k;
                let r = mean / st;
                if r < worst.0 {
                    worst = (r, t);
                }
            }
            Outcome {
                min_ratio: worst.0,
                min_period: worst.1,
                mean_pga: f.iter().zip(&pga).map(|(fi, p)| fi * p).sum::<f64>() / k,
            }
        };
        // slack ≥ 1 when every condition holds; nondecreasing in c
        let slack = |o: &Outcome| {
            let spectral = o.min_ratio / required;
            match zero_period {
                Some(z) => spectral.min(o.mean_pga / z),
                None => spectral,
            }
        };

        let c = match opts.factor_limits {
            None => {
                // every condition is linear in c: the largest of the c each one needs
                let o = outcome(&factors(1.0));
                1.0 / slack(&o)
            }
            Some((lo, hi)) => {
                let c_lo = shape.iter().map(|f0| lo / f0).fold(f64::INFINITY, f64::min);
                let c_hi = shape.iter().map(|f0| hi / f0).fold(0.0, f64::max);
                let top = outcome(&factors(c_hi));
                if slack(&top) < 1.0 {
                    return Err(ScalingError::Infeasible {
                        rule: rule.name(),
                        reason: infeasible_reason(&top, required, zero_period, hi),
                    });
                }
                if slack(&outcome(&factors(c_lo))) >= 1.0 {
                    c_lo
                } else {
                    // smallest c with slack ≥ 1, by bisection in log c
                    let (mut a, mut b) = (c_lo.ln(), c_hi.ln());
                    for _ in 0..200 {
                        if b - a < 1e-13 {
                            break;
                        }
                        let mid = 0.5 * (a + b);
                        if slack(&outcome(&factors(mid.exp()))) >= 1.0 {
                            b = mid;
                        } else {
                            a = mid;
                        }
                    }
                    b.exp()
                }
            }
        };
        if !(c.is_finite() && c > 0.0) {
            return Err(ScalingError::Infeasible {
                rule: rule.name(),
                reason: format!("the common factor would be {c}"),
            });
        }
        let f = factors(c);
        let o = outcome(&f);
        let k = f.len() as f64;
        let mean: Vec<f64> = (0..periods.len())
            .map(|j| f.iter().zip(&psa).map(|(fi, s)| fi * s[j]).sum::<f64>() / k)
            .collect();
        let ratio: Vec<f64> = mean.iter().zip(&target_sa).map(|(m, t)| m / t).collect();
        let pga_check = zero_period.map(|z| PgaCheck {
            mean_pga: o.mean_pga,
            required: z,
            ratio: o.mean_pga / z,
        });
        let all_at_lo = opts
            .factor_limits
            .is_some_and(|(lo, _)| f.iter().all(|fi| *fi == lo));
        let governs = if all_at_lo && slack(&o) > 1.0 + 1e-9 {
            "the smallest factor allowed (every record at it; the rule is exceeded)".to_string()
        } else {
            match pga_check {
                Some(p) if p.ratio / 1.0 <= o.min_ratio / required => format!(
                    "the mean PGA: {:.4} g = the target at T = 0 (a_g·S) = {:.4} g (EN 1998-1 §3.2.3.1.1(4)b)",
                    p.mean_pga / STANDARD_GRAVITY,
                    p.required / STANDARD_GRAVITY
                ),
                _ => format!(
                    "the mean spectrum at T = {:.4} s: {:.3} of the target",
                    o.min_period, o.min_ratio
                ),
            }
        };
        let records = members
            .iter()
            .zip(psa.into_iter().zip(display_psa))
            .enumerate()
            .map(|(i, (m, (s, display)))| {
                let at_limit = opts.factor_limits.and_then(|(lo, hi)| {
                    if f[i] == hi && c * shape[i] > hi {
                        Some("max")
                    } else if f[i] == lo && c * shape[i] < lo {
                        Some("min")
                    } else {
                        None
                    }
                });
                ScaledRecord {
                    name: m.name.to_string(),
                    dt: m.record.dt,
                    pga: pga[i],
                    shape_factor: shape[i],
                    factor: f[i],
                    scaled_pga: f[i] * pga[i],
                    at_limit,
                    psa: s,
                    display_psa: display,
                }
            })
            .collect();
        let mut notes = vec![
            "5 %-damped spectra of the one component read from each record (the planar model \
             takes one)"
                .to_string(),
        ];
        if rule == ScalingRule::Asce7 {
            notes.push(
                "ASCE 7-16 §16.2.3.2 checks the maximum-direction spectrum of each pair of \
                 horizontal components; for a model in one plane the component's own spectrum is \
                 used here"
                    .to_string(),
            );
        }
        if rule == ScalingRule::Asce7 {
            notes.push(
                "§16.2.3.1: the range must also include the periods of the modes needed for 90 % \
                 mass participation; widen it (--range) if they are below 0.2 T₁"
                    .to_string(),
            );
        }
        Ok(ScaledSuite {
            rule,
            rule_name: rule.name(),
            target_description: target.description.clone(),
            damping: DEFAULT_DAMPING,
            first_mode_periods: t1.clone(),
            code_range,
            range,
            periods,
            target: target_sa,
            mean,
            ratio,
            required_ratio: required,
            min_ratio: o.min_ratio,
            min_ratio_period: o.min_period,
            pga_check,
            common_factor: c,
            governs,
            factor_limits: opts.factor_limits,
            records,
            display_periods,
            display_target,
            notes,
        })
    }
}

fn infeasible_reason(top: &Outcome, required: f64, zero_period: Option<f64>, hi: f64) -> String {
    let mut parts = Vec::new();
    if top.min_ratio < required {
        parts.push(format!(
            "even with every record at the largest factor allowed ({hi}) the mean spectrum reaches \
             only {:.3} of the target at T = {:.4} s (at least {required} required)",
            top.min_ratio, top.min_period
        ));
    }
    if let Some(z) = zero_period
        && top.mean_pga < z
    {
        parts.push(format!(
            "the mean PGA reaches only {:.4} g against the target at T = 0 (a_g·S) = {:.4} g",
            top.mean_pga / STANDARD_GRAVITY,
            z / STANDARD_GRAVITY
        ));
    }
    parts.join("; ")
}
