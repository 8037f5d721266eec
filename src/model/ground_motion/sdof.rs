//! The linear SDOF oscillator `ü + 2ζω u̇ + ω² u = −a_g(t)` under a piecewise-linear ground
//! acceleration (a [`crate::model::ground_motion::Record`]: linear between samples, zero after
//! the last), in the model layer so that a record can be scaled to a spectral acceleration when
//! it is read (`scale_to_sa`); the response spectra of `pounding spectrum` (the analysis
//! layer's `record_spectrum`) use this same oscillator. The response is solved exactly from
//! sample to sample (Nigam & Jennings 1969, "Calculation of response spectra from
//! strong-motion earthquake records", *BSSA* 59(2), 909–922): the state (u, u̇) after a step h
//! is `A(h)·(u, u̇) + B(h)·(a₀, a₁)`, A the free-vibration propagator and B the response to
//! the linear load between the two samples. The coefficients are computed once per period; the
//! loop over the samples is two 2×2 products and a few comparisons.
//!
//! The peaks are those of the continuous response, not only at the samples:
//! - each sample interval is cut into m equal sub-steps with ωh ≤ [`MAX_PHASE_PER_STEP`] (the
//!   sub-steps are exact as well: the load is linear on each);
//! - where the velocity (for the displacement) or the derivative of the total acceleration
//!   changes sign inside a sub-step near the running peak, the extremum is located on the exact
//!   solution of that sub-step (its Taylor series, exact to rounding for ωh ≤ 0.5; Newton's
//!   method) and its value taken;
//! - after the last sample the ground is still (as [`crate::model::ground_motion::Record`] has it) and
//!   the free vibration's largest excursion is found in closed form: a damped sinusoid's
//!   extrema decrease one after the other, so the first one after the end (or the end itself)
//!   is the largest.

use std::f64::consts::{FRAC_PI_2, PI};

/// The damping ratio of the codes' spectra, of `pounding spectrum` and of `scale_to_sa` by
/// default: 5 %.
pub const DEFAULT_DAMPING: f64 = 0.05;

/// Shortest positive period computed, as a fraction of the record's time step: below dt/100 the
/// oscillator follows the ground (PSA is the PGA to about 1/(ωdt) < 0.2 %) and the exact
/// sub-stepping would cost ∝ 1/T; such a period is refused with that reason.
pub const MIN_PERIOD_OVER_DT: f64 = 0.01;

/// The pseudo-acceleration PSA = ω²·max|u| (m/s²), ω = 2π/T, of the oscillator of period
/// `period` (s, > 0, at least [`MIN_PERIOD_OVER_DT`]·dt: checked by the callers) and damping
/// ratio `zeta` in [0, 1) under `accel` (m/s²) sampled every `dt` s, from rest: [`peaks`]'s
/// displacement. The one expression of PSA: `analysis::record_spectrum::spectral_point` gives
/// the same bits.
pub fn pseudo_acceleration(accel: &[f64], dt: f64, period: f64, zeta: f64) -> f64 {
    let omega = 2.0 * PI / period;
    omega * omega * peaks(accel, dt, omega, zeta).displacement
}

/// Largest phase ωh of one sub-step, rad: sample intervals longer than this are cut into equal
/// sub-steps. Over 0.5 rad a sinusoid departs from its chord by at most 1 − cos(0.25) = 3 % of
/// its amplitude, which is what the peak search below relies on to skip far-from-peak steps.
pub const MAX_PHASE_PER_STEP: f64 = 0.5;

/// An extremum inside a sub-step is located exactly when its estimate (derivative taken linear
/// over the sub-step) reaches this fraction of the running peak.
const NEAR_PEAK: f64 = 0.9;

/// Below this phase ωh the coefficients come from the power series of the exact propagator
/// instead of the closed form, whose particular-solution terms (∝ 2ζ/(ω³h)) cancel to the
/// result's O(h²) with a relative loss ≈ 4ζ/(ωh)³ (at 0.05: 1.6e3 ε ≈ 4e-13).
const SERIES_BELOW: f64 = 0.05;

/// Recurrence coefficients of one step h: `u₁ = a11 u₀ + a12 v₀ + b11 a₀ + b12 a₁`,
/// `v₁ = a21 u₀ + a22 v₀ + b21 a₀ + b22 a₁` (u in m, v in m/s, a in m/s²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// ∂u₁/∂u₀.
    pub a11: f64,
    /// ∂u₁/∂v₀, s.
    pub a12: f64,
    /// ∂v₁/∂u₀, 1/s.
    pub a21: f64,
    /// ∂v₁/∂v₀.
    pub a22: f64,
    /// ∂u₁/∂a₀, s².
    pub b11: f64,
    /// ∂u₁/∂a₁, s².
    pub b12: f64,
    /// ∂v₁/∂a₀, s.
    pub b21: f64,
    /// ∂v₁/∂a₁, s.
    pub b22: f64,
}

impl Coefficients {
    /// The exact coefficients for circular frequency `omega` (rad/s, > 0), damping ratio
    /// `zeta` in [0, 1) and step `h` (s, > 0): closed form (Nigam–Jennings) for ωh ≥ 0.05, the
    /// series of the propagator below.
    pub fn new(omega: f64, zeta: f64, h: f64) -> Coefficients {
        if omega * h < SERIES_BELOW {
            Coefficients::series(omega, zeta, h)
        } else {
            Coefficients::closed_form(omega, zeta, h)
        }
    }

    /// Closed form: free vibration `A(h)` plus the particular solution of the linear load
    /// a(τ) = a₀ + kτ, `u_p = P + Qτ` with Q = −k/ω², P = (−a₀ + 2ζk/ω)/ω²; then
    /// `B·(a₀, a₁) = p(h) − A(h)·p(0)` with p = (u_p, u̇_p) — Nigam & Jennings' coefficients.
    pub fn closed_form(omega: f64, zeta: f64, h: f64) -> Coefficients {
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let sw = zeta * omega;
        let e = (-sw * h).exp();
        let (s, c) = (wd * h).sin_cos();
        let a11 = e * (c + sw / wd * s);
        let a12 = e * s / wd;
        let a21 = -e * omega * omega / wd * s;
        let a22 = e * (c - sw / wd * s);
        let w2 = omega * omega;
        // the load's columns: unit a₀ (k = −1/h) and unit a₁ (k = 1/h)
        let column = |a0: f64, k: f64| {
            let q = -k / w2;
            let p = (-a0 + 2.0 * zeta * k / omega) / w2;
            (p + q * h - a11 * p - a12 * q, q - a21 * p - a22 * q)
        };
        let (b11, b21) = column(1.0, -1.0 / h);
        let (b12, b22) = column(0.0, 1.0 / h);
        Coefficients {
            a11,
            a12,
            a21,
            a22,
            b11,
            b12,
            b21,
            b22,
        }
    }

    /// Power series of the exact propagator of the augmented system in scaled variables
    /// U = ω²u, V = ωu̇, time s = ωt: z = (U, V, a, K) with z' = N z,
    /// N = [[0, 1, 0, 0], [−1, −2ζ, −1, 0], [0, 0, 0, 1], [0, 0, 0, 0]] (K = da/ds), and
    /// E = exp(Nθ), θ = ωh: every entry of Nθ is O(θ), so the series converges fast and
    /// nothing cancels. Accurate for θ up to about 1.
    pub fn series(omega: f64, zeta: f64, h: f64) -> Coefficients {
        let theta = omega * h;
        let n = [
            [0.0, 1.0, 0.0, 0.0],
            [-1.0, -2.0 * zeta, -1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [0.0; 4],
        ];
        let mut e = [[0.0; 4]; 4];
        let mut term = [[0.0; 4]; 4];
        for i in 0..4 {
            e[i][i] = 1.0;
            term[i][i] = 1.0;
        }
        for k in 1..60 {
            let mut next = [[0.0; 4]; 4];
            for i in 0..4 {
                for j in 0..4 {
                    next[i][j] =
                        (0..4).map(|l| term[i][l] * n[l][j]).sum::<f64>() * theta / k as f64;
                }
            }
            term = next;
            let mut largest = 0.0_f64;
            for i in 0..4 {
                for j in 0..4 {
                    e[i][j] += term[i][j];
                    largest = largest.max(term[i][j].abs());
                }
            }
            if largest < 1e-20 {
                break;
            }
        }
        let w2 = omega * omega;
        // U₁ = E00 U₀ + E01 V₀ + E02 a₀ + E03 K, K = (a₁ − a₀)/θ; V₁ likewise with row 1
        Coefficients {
            a11: e[0][0],
            a12: e[0][1] / omega,
            a21: e[1][0] * omega,
            a22: e[1][1],
            b11: (e[0][2] - e[0][3] / theta) / w2,
            b12: e[0][3] / theta / w2,
            b21: (e[1][2] - e[1][3] / theta) / omega,
            b22: e[1][3] / theta / omega,
        }
    }

    /// The state after the step from (u, v) under the load a₀ → a₁.
    #[inline]
    pub fn step(&self, u: f64, v: f64, a0: f64, a1: f64) -> (f64, f64) {
        (
            self.a11 * u + self.a12 * v + self.b11 * a0 + self.b12 * a1,
            self.a21 * u + self.a22 * v + self.b21 * a0 + self.b22 * a1,
        )
    }
}

/// Peaks of one oscillator's response to a record.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peaks {
    /// max |u|, m: the spectral displacement S_d.
    pub displacement: f64,
    /// max |ü + a_g|, m/s²: the peak total (absolute) acceleration.
    pub total_acceleration: f64,
}

/// The peaks of the oscillator (ω in rad/s > 0, ζ in [0, 1)) at rest at t = 0, under the
/// ground acceleration `accel` (m/s²) sampled every `dt` s, linear between samples, zero after
/// the last sample (the free vibration after the end is included).
pub fn peaks(accel: &[f64], dt: f64, omega: f64, zeta: f64) -> Peaks {
    let m = ((omega * dt / MAX_PHASE_PER_STEP).ceil() as usize).max(1);
    let h = dt / m as f64;
    let c = Coefficients::new(omega, zeta, h);
    let two_zw = 2.0 * zeta * omega;
    let w2 = omega * omega;
    let mut search = Search {
        omega,
        zeta,
        h,
        peak_u: 0.0,
        peak_y: 0.0,
    };
    let (mut u, mut v) = (0.0_f64, 0.0_f64);
    let mut y = 0.0_f64;
    for pair in accel.windows(2) {
        let (a0, a1) = (pair[0], pair[1]);
        let da = (a1 - a0) / m as f64;
        let mut s0 = a0;
        for j in 0..m {
            let s1 = if j + 1 == m {
                a1
            } else {
                a0 + da * (j + 1) as f64
            };
            let (u1, v1) = c.step(u, v, s0, s1);
            let y1 = -(two_zw * v1 + w2 * u1);
            let au1 = u1.abs();
            if au1 > search.peak_u {
                search.peak_u = au1;
            }
            // an extremum of u inside the sub-step that may top the running peak: locate it.
            // Estimate with the velocity taken linear over the sub-step: over ωh ≤ 0.5 that is
            // within 1.6 % of the oscillation's amplitude, so a 10 % margin misses nothing.
            if v * v1 < 0.0 {
                let est = (u + 0.5 * v * h * v / (v - v1)).abs();
                if est >= NEAR_PEAK * search.peak_u {
                    search.displacement_extremum(u, v, s0, s1);
                }
            }
            let ay1 = y1.abs();
            if ay1 > search.peak_y {
                search.peak_y = ay1;
            }
            if y.abs().max(ay1) >= 0.5 * search.peak_y {
                // y' = −2ζω ü − ω² v with ü = y − a
                let g0 = -two_zw * (y - s0) - w2 * v;
                let g1 = -two_zw * (y1 - s1) - w2 * v1;
                if g0 * g1 < 0.0 {
                    let est = (y + 0.5 * g0 * h * g0 / (g0 - g1)).abs();
                    if est >= NEAR_PEAK * search.peak_y {
                        search.acceleration_extremum(u, v, s0, s1);
                    }
                }
            }
            (u, v, y) = (u1, v1, y1);
            s0 = s1;
        }
    }
    // free vibration after the end (a_g = 0): u and ü are damped sinusoids
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    let sw = zeta * omega;
    let free_u = free_peak(u, (v + sw * u) / wd, omega, zeta);
    let udd = y; // a_g = 0 after the end
    let yd = -two_zw * udd - w2 * v;
    let free_y = free_peak(y, (yd + sw * y) / wd, omega, zeta);
    Peaks {
        displacement: search.peak_u.max(free_u),
        total_acceleration: search.peak_y.max(free_y),
    }
}

/// The running peaks and what locating an extremum inside a sub-step needs.
struct Search {
    omega: f64,
    zeta: f64,
    h: f64,
    peak_u: f64,
    peak_y: f64,
}

/// Terms of the Taylor series of u over a sub-step: with ωh ≤ 0.5 the n-th term is of order
/// (ωh)ⁿ/n! of the response's scale, below 1e-24 at n = 20.
const TERMS: usize = 21;

impl Search {
    /// The Taylor coefficients cₙ = u⁽ⁿ⁾(0)/n! of the exact solution over a sub-step from
    /// (u, v) under the load s0 → s1: u'' = −a − 2ζωu' − ω²u with a linear, so
    /// u⁽ⁿ⁾ = −2ζω u⁽ⁿ⁻¹⁾ − ω² u⁽ⁿ⁻²⁾ for n ≥ 4 (an entire function: the series is exact).
    fn taylor(&self, u: f64, v: f64, s0: f64, s1: f64) -> [f64; TERMS] {
        let (two_zw, w2) = (2.0 * self.zeta * self.omega, self.omega * self.omega);
        let k = (s1 - s0) / self.h;
        let mut d = [0.0; TERMS];
        d[0] = u;
        d[1] = v;
        d[2] = -s0 - two_zw * v - w2 * u;
        d[3] = -k - two_zw * d[2] - w2 * d[1];
        for n in 4..TERMS {
            d[n] = -two_zw * d[n - 1] - w2 * d[n - 2];
        }
        let mut fact = 1.0;
        for (n, dn) in d.iter_mut().enumerate().skip(1) {
            fact *= n as f64;
            *dn /= fact;
        }
        d
    }

    /// The extremum of u where v = 0 inside the sub-step.
    fn displacement_extremum(&mut self, u: f64, v: f64, s0: f64, s1: f64) {
        let c = self.taylor(u, v, s0, s1);
        let tau = root(|t| (derivative(&c, 1, t), derivative(&c, 2, t)), self.h);
        let ue = derivative(&c, 0, tau).abs();
        if ue > self.peak_u {
            self.peak_u = ue;
        }
    }

    /// The extremum of the total acceleration y = −(2ζωu' + ω²u) where y' = 0.
    fn acceleration_extremum(&mut self, u: f64, v: f64, s0: f64, s1: f64) {
        let (two_zw, w2) = (2.0 * self.zeta * self.omega, self.omega * self.omega);
        let c = self.taylor(u, v, s0, s1);
        let y = |n: usize, t: f64| -(two_zw * derivative(&c, n + 1, t) + w2 * derivative(&c, n, t));
        let tau = root(|t| (y(1, t), y(2, t)), self.h);
        let ye = y(0, tau).abs();
        if ye > self.peak_y {
            self.peak_y = ye;
        }
    }
}

/// The `order`-th derivative at τ of the series Σ cₙ τⁿ.
fn derivative(c: &[f64; TERMS], order: usize, tau: f64) -> f64 {
    let mut acc = 0.0;
    for n in (order..TERMS).rev() {
        let falling: f64 = (n - order + 1..=n).map(|j| j as f64).product();
        acc = acc * tau + c[n] * falling;
    }
    acc
}

/// A root of g on [0, h], where g(0) and g(h) have opposite signs: Newton's method (`g`
/// returns the value and the derivative) kept inside the bracket, bisecting when a step would
/// leave it; to 1e-14 h.
fn root(g: impl Fn(f64) -> (f64, f64), h: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, h);
    let g_lo = g(lo).0;
    let g_hi = g(hi).0;
    // start from the linear interpolation of g
    let mut t = if g_lo != g_hi {
        h * g_lo / (g_lo - g_hi)
    } else {
        0.5 * h
    };
    for _ in 0..100 {
        let (gt, dgt) = g(t);
        if gt == 0.0 {
            return t;
        }
        if (gt < 0.0) == (g_lo < 0.0) {
            lo = t;
        } else {
            hi = t;
        }
        let mut next = t - gt / dgt;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - t).abs() <= 1e-14 * h || hi - lo <= 1e-14 * h {
            return next;
        }
        t = next;
    }
    t
}

/// Largest |q(τ)| over τ ≥ 0 of q = e^{−ζωτ}(c₁ cos ω_dτ + c₂ sin ω_dτ): the extrema of q are
/// π/ω_d apart and shrink by e^{−ζπ/√(1−ζ²)} each, so it is |q(0)| or the first extremum.
fn free_peak(c1: f64, c2: f64, omega: f64, zeta: f64) -> f64 {
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    let sw = zeta * omega;
    // q' ∝ p cos φ + r sin φ = ρ cos(φ − ψ), φ = ω_d τ
    let p = -sw * c1 + wd * c2;
    let r = -sw * c2 - wd * c1;
    let psi = r.atan2(p);
    let mut phi = (psi + FRAC_PI_2).rem_euclid(PI);
    if phi <= 0.0 {
        phi = PI;
    }
    let (s, c) = phi.sin_cos();
    let q1 = (-sw * phi / wd).exp() * (c1 * c + c2 * s);
    c1.abs().max(q1.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form and the series are independent derivations of the same propagator:
    /// they agree where both are accurate (θ = ωh from 0.05 to 1), to 1e-10 of each
    /// coefficient's scale (the closed form's cancellation is ≈ 4ζ/θ³ ε ≤ 1e-12 there).
    #[test]
    fn closed_form_and_series_agree() {
        for zeta in [0.0, 0.02, 0.05, 0.2, 0.7] {
            for theta in [0.05, 0.1, 0.3, 0.6, 1.0] {
                let omega = 7.3;
                let h = theta / omega;
                let a = Coefficients::closed_form(omega, zeta, h);
                let b = Coefficients::series(omega, zeta, h);
                let pairs = [
                    (a.a11, b.a11, 1.0),
                    (a.a12, b.a12, h),
                    (a.a21, b.a21, omega * omega * h),
                    (a.a22, b.a22, 1.0),
                    (a.b11, b.b11, h * h),
                    (a.b12, b.b12, h * h),
                    (a.b21, b.b21, h),
                    (a.b22, b.b22, h),
                ];
                for (k, (x, y, scale)) in pairs.iter().enumerate() {
                    assert!(
                        (x - y).abs() <= 1e-10 * scale,
                        "ζ {zeta} θ {theta} coefficient {k}: {x} vs {y}"
                    );
                }
            }
        }
    }

    /// A constant load a from rest: u(t) = −a/ω² (1 − e^{−ζωt}(cos ω_d t + ζω/ω_d sin ω_d t)),
    /// the step response, at every step for several step sizes and both branches.
    #[test]
    fn constant_load_is_the_step_response() {
        let (omega, zeta, a) = (4.0, 0.05, 2.0);
        let wd = omega * (1.0_f64 - zeta * zeta).sqrt();
        for h in [0.001, 0.01, 0.2] {
            let c = Coefficients::new(omega, zeta, h);
            let (mut u, mut v) = (0.0, 0.0);
            for k in 1..=200 {
                (u, v) = c.step(u, v, a, a);
                let t = k as f64 * h;
                let e = (-zeta * omega * t).exp();
                let exact = -a / (omega * omega)
                    * (1.0 - e * ((wd * t).cos() + zeta * omega / wd * (wd * t).sin()));
                assert!(
                    (u - exact).abs() < 1e-12 * a / (omega * omega),
                    "h {h} t {t}: {u} vs {exact}"
                );
            }
        }
    }

    /// The free vibration's peak: undamped, the amplitude √(u² + (v/ω)²); damped, against a
    /// dense sampling of the closed form.
    #[test]
    fn free_vibration_peak() {
        let omega = 3.0_f64;
        let (u, v) = (0.2_f64, -1.1_f64);
        let amp = (u * u + (v / omega) * (v / omega)).sqrt();
        let got = free_peak(u, v / omega, omega, 0.0);
        assert!((got - amp).abs() < 1e-14, "{got} vs {amp}");
        let zeta = 0.1;
        let wd = omega * (1.0_f64 - zeta * zeta).sqrt();
        let c2 = (v + zeta * omega * u) / wd;
        let got = free_peak(u, c2, omega, zeta);
        let dense = (0..200_000)
            .map(|k| {
                let t = k as f64 * 1e-5;
                ((-zeta * omega * t).exp() * (u * (wd * t).cos() + c2 * (wd * t).sin())).abs()
            })
            .fold(0.0_f64, f64::max);
        assert!(
            (got - dense).abs() < 1e-9 && got >= dense - 1e-15,
            "{got} vs {dense}"
        );
    }
}
