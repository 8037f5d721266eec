//! Design spectra and response-spectrum analysis of a [`ModalModel`] (issue 13).
//!
//! A [`DesignSpectrum`] gives the pseudo-acceleration S_a(T, ζ) in m/s² and the spectral
//! displacement S_d = S_a/ω² = S_a (T/2π)² in m. Three forms, a closed set:
//!
//! - [`Asce7Spectrum`]: ASCE 7-16 §11.4.6, two parameters S_DS, S_D1 (in g) and T_L (s). The
//!   standard defines this spectrum for 5 % damping and gives no damping correction in §11.4.6;
//!   it is used **as given whatever ζ** (see [`DesignSpectrum::damping_corrected`]).
//! - [`Ec8Spectrum`]: EN 1998-1 §3.2.2.2 horizontal elastic spectrum, a_g in m/s², ground type
//!   A–E, Type 1 or 2 (Tables 3.2 and 3.3, recommended values), with the damping correction
//!   η = √(10/(5 + ξ)) ≥ 0.55, ξ = 100 ζ in percent (expression 3.6).
//! - [`SpectrumTable`]: user pairs (T, S_a), linear interpolation, for the damping the user
//!   states; used as given whatever ζ. Periods outside the table are an error, not extrapolated.
//!
//! Response-spectrum analysis: the peak of mode n at height x is
//! `u_n(x) = Γ_n φ_n(x) S_d(T_n, ζ_n)` (Γ_n in kg^½, φ_n in kg^-½: u in m), combined by SRSS
//! `√Σ u_n²` and by CQC `√ΣΣ ρ_ij u_i u_j` with Der Kiureghian's correlation
//! ([`cqc_correlation`], general form for different damping ratios).
//! [`relative_peak`] combines the modes of both structures at their contact heights into the
//! peak of w₁ − w₂ (the spectral form of DDC).

use crate::model::ground_motion::STANDARD_GRAVITY;
use crate::model::modal::ModalModel;
use serde::Serialize;
use std::f64::consts::PI;

/// CQC correlation of two modes with damping ratios ζ₁, ζ₂ and period ratio r = T₁/T₂:
/// `ρ = 8√(ζ₁ζ₂)(ζ₁ + rζ₂) r^{3/2} / [(1−r²)² + 4ζ₁ζ₂ r(1+r²) + 4(ζ₁² + ζ₂²) r²]`.
pub fn cqc_correlation(zeta1: f64, zeta2: f64, r: f64) -> f64 {
    let num = 8.0 * (zeta1 * zeta2).sqrt() * (zeta1 + r * zeta2) * r.powf(1.5);
    let den = (1.0 - r * r).powi(2)
        + 4.0 * zeta1 * zeta2 * r * (1.0 + r * r)
        + 4.0 * (zeta1 * zeta1 + zeta2 * zeta2) * r * r;
    num / den
}

/// What is wrong with a spectrum, its input or a response-spectrum analysis.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpectrumError {
    /// A parameter that must be positive and finite is not.
    #[error("{name} must be positive and finite, got {value}")]
    NotPositive {
        /// The parameter's name as the code writes it.
        name: &'static str,
        /// The offending value.
        value: f64,
    },
    /// ASCE 7: the long-period transition T_L lies below T_S = S_D1/S_DS.
    #[error("ASCE 7-16 spectrum: T_L = {t_l} s is below T_S = S_D1/S_DS = {t_s} s")]
    LongPeriodBeforeTs {
        /// T_L, s.
        t_l: f64,
        /// T_S, s.
        t_s: f64,
    },
    /// A user table with fewer than two points.
    #[error("spectrum table needs at least 2 (T, S_a) pairs, got {0}")]
    TooFewPoints(usize),
    /// A table period that is negative or not finite.
    #[error("spectrum table pair {row}: period T = {period} s must be finite and ≥ 0")]
    BadTablePeriod {
        /// 1-based index of the pair.
        row: usize,
        /// The period, s.
        period: f64,
    },
    /// Table periods that do not increase strictly.
    #[error(
        "spectrum table pair {row}: period T = {period} s is not greater than the previous \
         period {previous} s (periods must increase strictly)"
    )]
    PeriodsNotIncreasing {
        /// 1-based index of the pair.
        row: usize,
        /// The period, s.
        period: f64,
        /// The previous pair's period, s.
        previous: f64,
    },
    /// A table acceleration that is not positive and finite.
    #[error("spectrum table pair {row}: S_a = {value} m/s² must be positive and finite")]
    BadTableAcceleration {
        /// 1-based index of the pair.
        row: usize,
        /// The acceleration, m/s².
        value: f64,
    },
    /// A period asked of a table outside its range (no extrapolation).
    #[error("period T = {period} s is outside the spectrum table's range [{min}, {max}] s")]
    OutsideTable {
        /// The period asked, s.
        period: f64,
        /// First period of the table, s.
        min: f64,
        /// Last period of the table, s.
        max: f64,
    },
    /// A period asked that is negative or not finite.
    #[error("period T = {0} s must be finite and ≥ 0")]
    BadPeriod(f64),
    /// A damping ratio outside [0, 1).
    #[error("damping ratio ζ = {0} must be finite and in [0, 1)")]
    BadDamping(f64),
    /// A height outside the structure.
    #[error("height {x} m is outside the structure (0 to {length} m)")]
    HeightOutside {
        /// The height asked, m.
        x: f64,
        /// Height of the structure, m.
        length: f64,
    },
    /// A modal model whose arrays disagree in length or whose frequency is not positive.
    #[error("modal model: {0}")]
    BadModel(String),
}

/// ASCE 7-16 §11.4.6 design response spectrum (5 % damping).
///
/// `S_a = S_DS (0.4 + 0.6 T/T_0)` for T < T_0; `S_DS` for T_0 ≤ T ≤ T_S; `S_D1/T` for
/// T_S < T ≤ T_L; `S_D1 T_L/T²` for T > T_L; T_0 = 0.2 S_D1/S_DS, T_S = S_D1/S_DS. S_DS and S_D1
/// are in g (as the standard defines them); [`DesignSpectrum::acceleration`] returns m/s²
/// (× 9.80665).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Asce7Spectrum {
    sds: f64,
    sd1: f64,
    tl: f64,
}

impl Asce7Spectrum {
    /// Checked spectrum: S_DS > 0 and S_D1 > 0 in g, T_L > 0 in s with T_L ≥ T_S.
    pub fn new(sds: f64, sd1: f64, tl: f64) -> Result<Asce7Spectrum, SpectrumError> {
        positive("S_DS", sds)?;
        positive("S_D1", sd1)?;
        positive("T_L", tl)?;
        let t_s = sd1 / sds;
        if tl < t_s {
            return Err(SpectrumError::LongPeriodBeforeTs { t_l: tl, t_s });
        }
        Ok(Asce7Spectrum { sds, sd1, tl })
    }

    /// Design short-period spectral acceleration S_DS, g.
    pub fn sds(&self) -> f64 {
        self.sds
    }

    /// Design 1-s spectral acceleration S_D1, g.
    pub fn sd1(&self) -> f64 {
        self.sd1
    }

    /// Long-period transition period T_L, s.
    pub fn tl(&self) -> f64 {
        self.tl
    }

    /// T_0 = 0.2 S_D1/S_DS, s.
    pub fn t0(&self) -> f64 {
        0.2 * self.sd1 / self.sds
    }

    /// T_S = S_D1/S_DS, s.
    pub fn ts(&self) -> f64 {
        self.sd1 / self.sds
    }

    /// S_a(T) in g (no damping dependence: the spectrum is for 5 %).
    pub fn acceleration_g(&self, period: f64) -> f64 {
        let (t0, ts) = (self.t0(), self.ts());
        if period < t0 {
            self.sds * (0.4 + 0.6 * period / t0)
        } else if period <= ts {
            self.sds
        } else if period <= self.tl {
            self.sd1 / period
        } else {
            self.sd1 * self.tl / (period * period)
        }
    }
}

/// EN 1998-1 ground type (§3.1.2, Table 3.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum GroundType {
    /// Rock or rock-like formation.
    A,
    /// Very dense sand, gravel or very stiff clay.
    B,
    /// Deep deposits of dense or medium-dense sand, gravel or stiff clay.
    C,
    /// Loose-to-medium cohesionless soil or soft-to-firm cohesive soil.
    D,
    /// Surface alluvium of type C or D, 5–20 m thick, over stiffer material.
    E,
}

/// EN 1998-1 §3.2.2.2(2)P spectrum shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Ec8Type {
    /// Type 1 (Table 3.2): high seismicity, surface-wave magnitude M_s > 5.5.
    Type1,
    /// Type 2 (Table 3.3): M_s ≤ 5.5.
    Type2,
}

/// The parameters of an EC8 elastic spectrum shape: soil factor S and corner periods.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ec8Shape {
    /// Soil factor S.
    pub s: f64,
    /// T_B, s: start of the constant-acceleration branch.
    pub tb: f64,
    /// T_C, s: end of the constant-acceleration branch.
    pub tc: f64,
    /// T_D, s: start of the constant-displacement branch.
    pub td: f64,
}

impl Ec8Shape {
    /// Recommended values of EN 1998-1 Table 3.2 (Type 1) and Table 3.3 (Type 2). National
    /// annexes may change them: build an [`Ec8Spectrum`] with [`Ec8Spectrum::with_shape`] then.
    pub fn recommended(ground: GroundType, kind: Ec8Type) -> Ec8Shape {
        use GroundType::*;
        let (s, tb, tc, td) = match (kind, ground) {
            (Ec8Type::Type1, A) => (1.0, 0.15, 0.4, 2.0),
            (Ec8Type::Type1, B) => (1.2, 0.15, 0.5, 2.0),
            (Ec8Type::Type1, C) => (1.15, 0.20, 0.6, 2.0),
            (Ec8Type::Type1, D) => (1.35, 0.20, 0.8, 2.0),
            (Ec8Type::Type1, E) => (1.4, 0.15, 0.5, 2.0),
            (Ec8Type::Type2, A) => (1.0, 0.05, 0.25, 1.2),
            (Ec8Type::Type2, B) => (1.35, 0.05, 0.25, 1.2),
            (Ec8Type::Type2, C) => (1.5, 0.10, 0.25, 1.2),
            (Ec8Type::Type2, D) => (1.8, 0.10, 0.30, 1.2),
            (Ec8Type::Type2, E) => (1.6, 0.05, 0.25, 1.2),
        };
        Ec8Shape { s, tb, tc, td }
    }
}

/// EN 1998-1 §3.2.2.2 horizontal elastic response spectrum S_e(T), expressions (3.2)–(3.5):
///
/// - 0 ≤ T ≤ T_B: `a_g S [1 + T/T_B (2.5η − 1)]`
/// - T_B ≤ T ≤ T_C: `2.5 a_g S η`
/// - T_C ≤ T ≤ T_D: `2.5 a_g S η T_C/T`
/// - T_D ≤ T: `2.5 a_g S η T_C T_D/T²` (EN 1998-1 writes this branch up to 4 s; beyond 4 s it is
///   continued unchanged, i.e. a constant spectral displacement).
///
/// η = √(10/(5 + ξ)) ≥ 0.55 with ξ the damping ratio in percent (expression 3.6).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ec8Spectrum {
    ag: f64,
    shape: Ec8Shape,
}

impl Ec8Spectrum {
    /// Design ground acceleration on type A ground a_g (m/s², > 0) with the recommended shape
    /// of `ground` and `kind`.
    pub fn new(ag: f64, ground: GroundType, kind: Ec8Type) -> Result<Ec8Spectrum, SpectrumError> {
        Ec8Spectrum::with_shape(ag, Ec8Shape::recommended(ground, kind))
    }

    /// a_g (m/s²) with an explicit shape (e.g. from a national annex): S > 0 and
    /// 0 < T_B < T_C < T_D.
    pub fn with_shape(ag: f64, shape: Ec8Shape) -> Result<Ec8Spectrum, SpectrumError> {
        positive("a_g", ag)?;
        positive("S", shape.s)?;
        positive("T_B", shape.tb)?;
        positive("T_C", shape.tc)?;
        positive("T_D", shape.td)?;
        if shape.tc <= shape.tb {
            return Err(SpectrumError::NotPositive {
                name: "T_C − T_B",
                value: shape.tc - shape.tb,
            });
        }
        if shape.td <= shape.tc {
            return Err(SpectrumError::NotPositive {
                name: "T_D − T_C",
                value: shape.td - shape.tc,
            });
        }
        Ok(Ec8Spectrum { ag, shape })
    }

    /// a_g, m/s².
    pub fn ag(&self) -> f64 {
        self.ag
    }

    /// S, T_B, T_C, T_D.
    pub fn shape(&self) -> Ec8Shape {
        self.shape
    }

    /// Damping correction η = max(√(10/(5 + 100ζ)), 0.55) (EN 1998-1 expression 3.6).
    pub fn eta(zeta: f64) -> f64 {
        (10.0 / (5.0 + 100.0 * zeta)).sqrt().max(0.55)
    }

    /// S_e(T, ζ), m/s².
    pub fn acceleration(&self, period: f64, zeta: f64) -> f64 {
        let Ec8Shape { s, tb, tc, td } = self.shape;
        let eta = Ec8Spectrum::eta(zeta);
        let plateau = 2.5 * self.ag * s * eta;
        if period <= tb {
            self.ag * s * (1.0 + period / tb * (2.5 * eta - 1.0))
        } else if period <= tc {
            plateau
        } else if period <= td {
            plateau * tc / period
        } else {
            plateau * tc * td / (period * period)
        }
    }
}

/// A user spectrum: pairs (T in s, S_a in m/s²), linearly interpolated in T.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpectrumTable {
    periods: Vec<f64>,
    accelerations: Vec<f64>,
}

impl SpectrumTable {
    /// Checked table: at least two pairs, periods finite, ≥ 0 and strictly increasing,
    /// accelerations positive and finite. Errors name the 1-based pair.
    pub fn new(pairs: &[(f64, f64)]) -> Result<SpectrumTable, SpectrumError> {
        if pairs.len() < 2 {
            return Err(SpectrumError::TooFewPoints(pairs.len()));
        }
        for (i, &(t, a)) in pairs.iter().enumerate() {
            let row = i + 1;
            if !(t.is_finite() && t >= 0.0) {
                return Err(SpectrumError::BadTablePeriod { row, period: t });
            }
            if i > 0 && t <= pairs[i - 1].0 {
                return Err(SpectrumError::PeriodsNotIncreasing {
                    row,
                    period: t,
                    previous: pairs[i - 1].0,
                });
            }
            if !(a.is_finite() && a > 0.0) {
                return Err(SpectrumError::BadTableAcceleration { row, value: a });
            }
        }
        Ok(SpectrumTable {
            periods: pairs.iter().map(|p| p.0).collect(),
            accelerations: pairs.iter().map(|p| p.1).collect(),
        })
    }

    /// The table's periods, s.
    pub fn periods(&self) -> &[f64] {
        &self.periods
    }

    /// The table's accelerations, m/s².
    pub fn accelerations(&self) -> &[f64] {
        &self.accelerations
    }

    /// S_a(T) by linear interpolation, m/s²; an error outside [T_first, T_last].
    pub fn acceleration(&self, period: f64) -> Result<f64, SpectrumError> {
        let (t, a) = (&self.periods, &self.accelerations);
        let (min, max) = (t[0], t[t.len() - 1]);
        if !(period >= min && period <= max) {
            return Err(SpectrumError::OutsideTable { period, min, max });
        }
        // first index with t[k] ≥ period (k ≥ 1 unless period == min)
        let k = t.partition_point(|&tk| tk < period);
        if k == 0 {
            return Ok(a[0]);
        }
        let w = (period - t[k - 1]) / (t[k] - t[k - 1]);
        Ok(a[k - 1] + w * (a[k] - a[k - 1]))
    }
}

/// A design spectrum: the closed set of forms the library knows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum DesignSpectrum {
    /// ASCE 7-16 §11.4.6 (5 % damping, used as given for any ζ).
    Asce7(Asce7Spectrum),
    /// EN 1998-1 §3.2.2.2 elastic spectrum with the damping correction η.
    Ec8(Ec8Spectrum),
    /// User table (used as given for any ζ).
    Table(SpectrumTable),
}

impl DesignSpectrum {
    /// Pseudo-acceleration S_a(T, ζ), m/s². T ≥ 0 in s; ζ in [0, 1). Only the EC8 spectrum
    /// depends on ζ (through η); see [`DesignSpectrum::damping_corrected`].
    pub fn acceleration(&self, period: f64, zeta: f64) -> Result<f64, SpectrumError> {
        if !(period.is_finite() && period >= 0.0) {
            return Err(SpectrumError::BadPeriod(period));
        }
        if !(zeta.is_finite() && (0.0..1.0).contains(&zeta)) {
            return Err(SpectrumError::BadDamping(zeta));
        }
        match self {
            DesignSpectrum::Asce7(s) => Ok(s.acceleration_g(period) * STANDARD_GRAVITY),
            DesignSpectrum::Ec8(s) => Ok(s.acceleration(period, zeta)),
            DesignSpectrum::Table(s) => s.acceleration(period),
        }
    }

    /// Spectral displacement S_d = S_a/ω² = S_a (T/2π)², m.
    pub fn displacement(&self, period: f64, zeta: f64) -> Result<f64, SpectrumError> {
        let sa = self.acceleration(period, zeta)?;
        let w = period / (2.0 * PI);
        Ok(sa * w * w)
    }

    /// Whether S_a depends on the damping ratio: true for EC8 (η), false for ASCE 7 (a 5 %
    /// spectrum, no correction in §11.4.6) and for a user table (its own damping).
    pub fn damping_corrected(&self) -> bool {
        matches!(self, DesignSpectrum::Ec8(_))
    }

    /// Short name for reports: "ASCE 7-16 §11.4.6", "EN 1998-1 §3.2.2.2", "table".
    pub fn name(&self) -> &'static str {
        match self {
            DesignSpectrum::Asce7(_) => "ASCE 7-16 §11.4.6",
            DesignSpectrum::Ec8(_) => "EN 1998-1 §3.2.2.2",
            DesignSpectrum::Table(_) => "table",
        }
    }
}

/// One mode's peak response at one height.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ModalPeak {
    /// Mode index (0-based).
    pub mode: usize,
    /// Period T_n, s.
    pub period: f64,
    /// Damping ratio ζ_n.
    pub zeta: f64,
    /// S_a(T_n, ζ_n), m/s².
    pub sa: f64,
    /// S_d(T_n, ζ_n) = S_a/ω_n², m.
    pub sd: f64,
    /// Participation factor Γ_n, kg^½.
    pub gamma: f64,
    /// Mode shape φ_n(x), kg^-½.
    pub phi: f64,
    /// Signed peak u_n(x) = Γ_n φ_n(x) S_d, m (the sign matters to CQC).
    pub displacement: f64,
}

/// The combined peak displacement at one height of one structure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpectralResponse {
    /// Height x, m.
    pub height: f64,
    /// Per-mode peaks.
    pub modes: Vec<ModalPeak>,
    /// SRSS `√Σ u_n²`, m.
    pub srss: f64,
    /// CQC `√ΣΣ ρ_ij u_i u_j`, m.
    pub cqc: f64,
}

/// Peak of the relative displacement w₁(h₁) − w₂(h₂) from the modes of both structures.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RelativeResponse {
    /// Structure 1's response at h₁.
    pub structure1: SpectralResponse,
    /// Structure 2's response at h₂.
    pub structure2: SpectralResponse,
    /// SRSS of all modes of both structures, m (= √(SRSS₁² + SRSS₂²): no correlation).
    pub srss: f64,
    /// CQC over all modes of both structures with u₂ negated, m: the spectral DDC. Equals
    /// √(CQC₁² + CQC₂² − 2 Σ_ij ρ_ij u₁ᵢ u₂ⱼ).
    pub cqc: f64,
}

/// Correlation of two modes (ω in rad/s, ζ): 1 on identical modes, else Der Kiureghian's ρ
/// with r = ω_j/ω_i ([`cqc_correlation`]); two undamped modes of equal frequency count as
/// fully correlated.
pub fn modal_correlation(omega_i: f64, zeta_i: f64, omega_j: f64, zeta_j: f64) -> f64 {
    if omega_i == omega_j && zeta_i == zeta_j {
        return 1.0;
    }
    let rho = cqc_correlation(zeta_i, zeta_j, omega_j / omega_i);
    if rho.is_finite() { rho } else { 1.0 }
}

/// SRSS `√Σ u²`, m.
pub fn srss(peaks: &[f64]) -> f64 {
    peaks.iter().map(|u| u * u).sum::<f64>().sqrt()
}

/// CQC `√max(0, ΣΣ ρ_ij u_i u_j)` of signed modal peaks `u` with frequencies `omega` (rad/s)
/// and damping ratios `zeta` (all three the same length; extra entries are ignored).
pub fn cqc(peaks: &[f64], omega: &[f64], zeta: &[f64]) -> f64 {
    let n = peaks.len().min(omega.len()).min(zeta.len());
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            sum += modal_correlation(omega[i], zeta[i], omega[j], zeta[j]) * peaks[i] * peaks[j];
        }
    }
    sum.max(0.0).sqrt()
}

fn check_model(model: &ModalModel) -> Result<(), SpectrumError> {
    let n = model.omega.len();
    if n == 0 {
        return Err(SpectrumError::BadModel("no modes".into()));
    }
    let shapes = match &model.shapes {
        crate::model::modal::Shapes::Cantilever(m) => m.len(),
        crate::model::modal::Shapes::Floors { values, .. } => values.len(),
    };
    if model.zeta.len() != n || model.participation.len() != n || shapes != n {
        return Err(SpectrumError::BadModel(format!(
            "{} frequencies, {} damping ratios, {} participation factors, {} shapes",
            n,
            model.zeta.len(),
            model.participation.len(),
            shapes
        )));
    }
    if let Some((i, w)) = model
        .omega
        .iter()
        .enumerate()
        .find(|(_, w)| !(w.is_finite() && **w > 0.0))
    {
        return Err(SpectrumError::BadModel(format!(
            "mode {}: ω = {w} rad/s is not positive",
            i + 1
        )));
    }
    if !(model.length.is_finite() && model.length > 0.0 && model.mass > 0.0) {
        return Err(SpectrumError::BadModel(format!(
            "length {} m and mass {} kg must be positive",
            model.length, model.mass
        )));
    }
    Ok(())
}

/// Per-mode peaks `u_n(x) = Γ_n φ_n(x) S_d(T_n, ζ_n)` of `model` at height `x` (m, 0 ≤ x ≤ L).
pub fn modal_peaks(
    model: &ModalModel,
    spectrum: &DesignSpectrum,
    x: f64,
) -> Result<Vec<ModalPeak>, SpectrumError> {
    check_model(model)?;
    if !(x.is_finite() && (0.0..=model.length).contains(&x)) {
        return Err(SpectrumError::HeightOutside {
            x,
            length: model.length,
        });
    }
    (0..model.omega.len())
        .map(|n| {
            let w = model.omega[n];
            let period = 2.0 * PI / w;
            let zeta = model.zeta[n];
            let sa = spectrum.acceleration(period, zeta)?;
            let sd = sa / (w * w);
            let gamma = model.participation_factor(n);
            let phi = model.shape(n, x);
            Ok(ModalPeak {
                mode: n,
                period,
                zeta,
                sa,
                sd,
                gamma,
                phi,
                displacement: gamma * phi * sd,
            })
        })
        .collect()
}

/// Peak displacement of `model` at height `x` (m) under `spectrum`, by SRSS and CQC.
pub fn peak_displacement(
    model: &ModalModel,
    spectrum: &DesignSpectrum,
    x: f64,
) -> Result<SpectralResponse, SpectrumError> {
    let modes = modal_peaks(model, spectrum, x)?;
    let u: Vec<f64> = modes.iter().map(|m| m.displacement).collect();
    Ok(SpectralResponse {
        height: x,
        srss: srss(&u),
        cqc: cqc(&u, &model.omega, &model.zeta),
        modes,
    })
}

/// [`peak_displacement`] at each of `heights` (m), e.g. every floor.
pub fn peak_displacements(
    model: &ModalModel,
    spectrum: &DesignSpectrum,
    heights: &[f64],
) -> Result<Vec<SpectralResponse>, SpectrumError> {
    heights
        .iter()
        .map(|&x| peak_displacement(model, spectrum, x))
        .collect()
}

/// Peak of w₁(h₁) − w₂(h₂) with both structures under the same `spectrum`: the modes of both
/// combined by SRSS and by CQC (structure 2's peaks negated), heights in m.
pub fn relative_peak(
    model1: &ModalModel,
    h1: f64,
    model2: &ModalModel,
    h2: f64,
    spectrum: &DesignSpectrum,
) -> Result<RelativeResponse, SpectrumError> {
    let r1 = peak_displacement(model1, spectrum, h1)?;
    let r2 = peak_displacement(model2, spectrum, h2)?;
    let u: Vec<f64> = r1
        .modes
        .iter()
        .map(|m| m.displacement)
        .chain(r2.modes.iter().map(|m| -m.displacement))
        .collect();
    let omega: Vec<f64> = model1.omega.iter().chain(&model2.omega).copied().collect();
    let zeta: Vec<f64> = model1.zeta.iter().chain(&model2.zeta).copied().collect();
    Ok(RelativeResponse {
        srss: srss(&u),
        cqc: cqc(&u, &omega, &zeta),
        structure1: r1,
        structure2: r2,
    })
}

fn positive(name: &'static str, value: f64) -> Result<(), SpectrumError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(SpectrumError::NotPositive { name, value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// η at 5 % is 1; at 10 %: √(10/15) = 0.816497; floor 0.55 reached at ξ = 28.06 %.
    #[test]
    fn eta_values() {
        assert!((Ec8Spectrum::eta(0.05) - 1.0).abs() < 1e-15);
        assert!((Ec8Spectrum::eta(0.10) - (10.0f64 / 15.0).sqrt()).abs() < 1e-15);
        assert_eq!(Ec8Spectrum::eta(0.5), 0.55);
    }

    /// Interpolation halfway between two pairs; ends exact.
    #[test]
    fn table_interpolates() {
        let t = SpectrumTable::new(&[(0.0, 2.0), (0.5, 6.0), (2.0, 3.0)]).unwrap();
        assert_eq!(t.acceleration(0.0).unwrap(), 2.0);
        assert!((t.acceleration(0.25).unwrap() - 4.0).abs() < 1e-15);
        assert!((t.acceleration(1.25).unwrap() - 4.5).abs() < 1e-15);
        assert_eq!(t.acceleration(2.0).unwrap(), 3.0);
        assert!(t.acceleration(2.1).is_err());
    }
}
