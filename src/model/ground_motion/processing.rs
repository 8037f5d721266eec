//! The standard processing of an uncorrected accelerogram (Boore & Bommer 2005, "Processing
//! of strong-motion accelerograms: needs, options and consequences", *Soil Dyn. Earthq. Eng.*
//! 25, 93–115): baseline removal and a zero-phase (acausal) Butterworth band-pass, in this
//! order:
//!
//! 1. **Baseline.** `linear`: the least-squares straight line `c₀ + c₁t` fitted to the
//!    acceleration is removed (a constant offset and a linear drift of the zero line: the
//!    simplest baseline correction, Boore & Bommer §4). Otherwise the mean is removed, so that
//!    the filter does not ring on a step at the ends.
//! 2. **Band-pass.** Zero pads of total length `1.5·n/f_c` (n the order, f_c the high-pass
//!    corner; Converse & Brady 1992, USGS OFR 92-296A) are added, half at each end, and **kept**
//!    in the record (Boore 2005, "On pads and filters", *BSSA* 95(2), 745–750: the filtered
//!    pads belong to the filtered record, or its velocity and displacement are inconsistent).
//!    The high-pass and low-pass Butterworth filters of order n, designed by the bilinear
//!    transform with prewarped corners as cascades of second-order sections, are run forward
//!    then backward: the phase cancels, the magnitude is squared, `|H(f)|² = 1/(1 + (f/f_c)^{2n})`
//!    for the analog prototype, so at the corner the response is 1/2 (−6 dB), not 1/√2.
//! 3. **Polynomial baseline** (`polynomial`), after filtering: a polynomial of degree 6
//!    without constant and linear terms (the record starts at rest) is fitted by least squares
//!    to the displacement (the exact double integral of the piecewise-linear acceleration) and
//!    its second derivative removed from the acceleration, as in PEER's processing (Boore &
//!    Bommer §4.2): the displacement no longer drifts.

use nalgebra::{DMatrix, DVector};

/// Degree of the polynomial fitted to the displacement by [`Baseline::Polynomial`].
pub const POLYNOMIAL_DEGREE: usize = 6;

/// Default order of the Butterworth filters.
pub const DEFAULT_ORDER: usize = 4;

/// Highest Butterworth order accepted.
pub const MAX_ORDER: usize = 8;

/// The baseline correction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Baseline {
    /// The least-squares line fitted to the acceleration is removed (before filtering).
    Linear,
    /// The mean is removed before filtering; after it, the least-squares polynomial of degree
    /// [`POLYNOMIAL_DEGREE`] (terms t² … t⁶) fitted to the displacement, differentiated twice.
    Polynomial,
}

impl Baseline {
    /// `linear` or `polynomial`.
    pub fn name(self) -> &'static str {
        match self {
            Baseline::Linear => "linear",
            Baseline::Polynomial => "polynomial",
        }
    }
}

/// What processing to apply (`processing = { … }` in `[ground_motion]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Processing {
    /// The baseline correction (`None`: only the mean is removed).
    pub baseline: Option<Baseline>,
    /// High-pass (low-cut) corner, Hz.
    pub highpass_hz: Option<f64>,
    /// Low-pass (high-cut) corner, Hz; below the Nyquist frequency 1/(2 dt).
    pub lowpass_hz: Option<f64>,
    /// Order of each Butterworth filter (before the forward–backward pass doubles it).
    pub order: usize,
}

impl Default for Processing {
    fn default() -> Processing {
        Processing {
            baseline: None,
            highpass_hz: None,
            lowpass_hz: None,
            order: DEFAULT_ORDER,
        }
    }
}

impl Processing {
    /// One line for reports, e.g. `baseline linear, band-pass 0.1–25 Hz (order 4, zero-phase)`.
    pub fn describe(&self) -> String {
        let mut parts = vec![format!(
            "baseline {}",
            self.baseline.map_or("mean", Baseline::name)
        )];
        let band = match (self.highpass_hz, self.lowpass_hz) {
            (Some(h), Some(l)) => Some(format!("band-pass {h}–{l} Hz")),
            (Some(h), None) => Some(format!("high-pass {h} Hz")),
            (None, Some(l)) => Some(format!("low-pass {l} Hz")),
            (None, None) => None,
        };
        if let Some(b) = band {
            parts.push(format!(
                "{b} (Butterworth order {}, zero-phase)",
                self.order
            ));
        }
        parts.join(", ")
    }

    /// The zero pad added at each end by the high-pass filter, s (0 without one): half of
    /// 1.5·n/f_c, rounded up to whole samples of `dt`.
    pub fn pad_seconds(&self, dt: f64) -> f64 {
        self.highpass_hz.map_or(0.0, |fc| {
            (0.5 * 1.5 * self.order as f64 / fc / dt).ceil() * dt
        })
    }

    /// Why these settings cannot be applied to a record sampled every `dt` s, if they cannot.
    pub fn check(&self, dt: f64) -> Result<(), String> {
        let nyquist = 0.5 / dt;
        if !(1..=MAX_ORDER).contains(&self.order) {
            return Err(format!("order = {} must be 1 to {MAX_ORDER}", self.order));
        }
        for (name, f) in [
            ("highpass_hz", self.highpass_hz),
            ("lowpass_hz", self.lowpass_hz),
        ] {
            if let Some(f) = f
                && !(f.is_finite() && f > 0.0 && f < nyquist)
            {
                return Err(format!(
                    "{name} = {f} Hz must be above 0 and below the Nyquist frequency \
                     {nyquist} Hz of the record (dt = {dt} s)"
                ));
            }
        }
        if let (Some(h), Some(l)) = (self.highpass_hz, self.lowpass_hz)
            && h >= l
        {
            return Err(format!(
                "highpass_hz = {h} Hz must be below lowpass_hz = {l} Hz"
            ));
        }
        Ok(())
    }

    /// Processes the acceleration `accel` (m/s², sampled every `dt` s) as the module says.
    /// The result is longer by the filter's zero pads when there is a high-pass.
    pub fn apply(&self, accel: &[f64], dt: f64) -> Result<Vec<f64>, String> {
        self.check(dt)?;
        let mut a = accel.to_vec();
        match self.baseline {
            Some(Baseline::Linear) => remove_line(&mut a, dt),
            _ => {
                let mean = a.iter().sum::<f64>() / a.len().max(1) as f64;
                a.iter_mut().for_each(|x| *x -= mean);
            }
        }
        if self.highpass_hz.is_some() {
            let half = (self.pad_seconds(dt) / dt).round() as usize;
            let mut padded = vec![0.0; a.len() + 2 * half];
            padded[half..half + a.len()].copy_from_slice(&a);
            a = padded;
        }
        let mut sections = Vec::new();
        if let Some(fc) = self.highpass_hz {
            sections.extend(butterworth(self.order, fc, dt, Pass::High));
        }
        if let Some(fc) = self.lowpass_hz {
            sections.extend(butterworth(self.order, fc, dt, Pass::Low));
        }
        if !sections.is_empty() {
            filtfilt(&sections, &mut a);
        }
        if self.baseline == Some(Baseline::Polynomial) {
            remove_displacement_polynomial(&mut a, dt);
        }
        Ok(a)
    }
}

/// Which side a Butterworth filter passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    /// Frequencies below the corner.
    Low,
    /// Frequencies above the corner.
    High,
}

/// A second-order section `(b₀ + b₁z⁻¹ + b₂z⁻²)/(1 + a₁z⁻¹ + a₂z⁻²)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Numerator b₀, b₁, b₂.
    pub b: [f64; 3],
    /// Denominator a₁, a₂ (a₀ = 1).
    pub a: [f64; 2],
}

impl Section {
    /// |H| at frequency `f` (Hz) for sampling step `dt` (s).
    pub fn magnitude(&self, f: f64, dt: f64) -> f64 {
        let w = 2.0 * std::f64::consts::PI * f * dt;
        // z⁻¹ = e^{−iw}
        let (c1, s1) = (w.cos(), -w.sin());
        let (c2, s2) = ((2.0 * w).cos(), -(2.0 * w).sin());
        let num = (
            self.b[0] + self.b[1] * c1 + self.b[2] * c2,
            self.b[1] * s1 + self.b[2] * s2,
        );
        let den = (
            1.0 + self.a[0] * c1 + self.a[1] * c2,
            self.a[0] * s1 + self.a[1] * s2,
        );
        (num.0.hypot(num.1)) / (den.0.hypot(den.1))
    }
}

/// The Butterworth filter of order `order` with corner `fc` (Hz) for step `dt` (s), as
/// second-order sections: the analog prototype's poles `e^{iθ_k}`,
/// θ_k = π/2 + π(2k + 1)/(2n), paired into `s² − 2cos θ_k s + 1` (and `s + 1` for odd n),
/// mapped by the bilinear transform with the corner prewarped, K = tan(π f_c dt), so that the
/// digital magnitude at f equals the prototype's at tan(π f dt)/K exactly:
/// `|H|² = 1/(1 + (tan(π f dt)/K)^{±2n})`.
pub fn butterworth(order: usize, fc: f64, dt: f64, pass: Pass) -> Vec<Section> {
    let n = order.max(1);
    let k = (std::f64::consts::PI * fc * dt).tan();
    let mut out = Vec::with_capacity(n.div_ceil(2));
    for j in 0..n / 2 {
        let theta = std::f64::consts::FRAC_PI_2
            + std::f64::consts::PI * (2 * j + 1) as f64 / (2 * n) as f64;
        let q = -2.0 * theta.cos(); // 1/Q > 0
        let a0 = 1.0 + q * k + k * k;
        let a = [(2.0 * k * k - 2.0) / a0, (1.0 - q * k + k * k) / a0];
        let b = match pass {
            Pass::Low => [k * k / a0, 2.0 * k * k / a0, k * k / a0],
            Pass::High => [1.0 / a0, -2.0 / a0, 1.0 / a0],
        };
        out.push(Section { b, a });
    }
    if n % 2 == 1 {
        let a0 = 1.0 + k;
        let a = [(k - 1.0) / a0, 0.0];
        let b = match pass {
            Pass::Low => [k / a0, k / a0, 0.0],
            Pass::High => [1.0 / a0, -1.0 / a0, 0.0],
        };
        out.push(Section { b, a });
    }
    out
}

/// Runs the cascade forward, then backward (zero phase, magnitude squared), in place, from
/// rest at both ends (the caller pads).
pub fn filtfilt(sections: &[Section], x: &mut [f64]) {
    for s in sections {
        run(s, x.iter_mut());
    }
    for s in sections {
        run(s, x.iter_mut().rev());
    }
}

/// One section in transposed direct form II.
fn run<'a>(s: &Section, xs: impl Iterator<Item = &'a mut f64>) {
    let (mut z1, mut z2) = (0.0, 0.0);
    for x in xs {
        let y = s.b[0] * *x + z1;
        z1 = s.b[1] * *x - s.a[0] * y + z2;
        z2 = s.b[2] * *x - s.a[1] * y;
        *x = y;
    }
}

/// Removes the least-squares line c₀ + c₁t from `a`.
fn remove_line(a: &mut [f64], dt: f64) {
    let n = a.len();
    if n < 2 {
        return;
    }
    // centred time keeps the 2×2 system diagonal
    let tm = 0.5 * (n - 1) as f64 * dt;
    let (mut sy, mut sty, mut stt) = (0.0, 0.0, 0.0);
    for (k, y) in a.iter().enumerate() {
        let t = k as f64 * dt - tm;
        sy += y;
        sty += t * y;
        stt += t * t;
    }
    let c0 = sy / n as f64;
    let c1 = if stt > 0.0 { sty / stt } else { 0.0 };
    for (k, y) in a.iter_mut().enumerate() {
        *y -= c0 + c1 * (k as f64 * dt - tm);
    }
}

/// Displacement of the piecewise-linear acceleration from rest: exact (cubic) per step.
pub fn displacement(a: &[f64], dt: f64) -> Vec<f64> {
    let mut d = Vec::with_capacity(a.len());
    let (mut v, mut x) = (0.0, 0.0);
    d.push(0.0);
    for w in a.windows(2) {
        x += v * dt + dt * dt * (2.0 * w[0] + w[1]) / 6.0;
        v += 0.5 * dt * (w[0] + w[1]);
        d.push(x);
    }
    d
}

/// Fits Σ_{j=2..6} c_j τ^j (τ = t/T) to the displacement by least squares (QR) and removes its
/// second derivative from the acceleration.
fn remove_displacement_polynomial(a: &mut [f64], dt: f64) {
    let n = a.len();
    if n < POLYNOMIAL_DEGREE + 1 {
        return;
    }
    let d = displacement(a, dt);
    let span = (n - 1) as f64 * dt;
    let m = POLYNOMIAL_DEGREE - 1;
    let design = DMatrix::from_fn(n, m, |k, j| {
        let tau = k as f64 * dt / span;
        tau.powi(j as i32 + 2)
    });
    let rhs = DVector::from_column_slice(&d);
    let qr = design.qr();
    let qtb = qr.q().transpose() * rhs;
    let Some(c) = qr.r().solve_upper_triangular(&qtb) else {
        return;
    };
    for (k, y) in a.iter_mut().enumerate() {
        let tau = k as f64 * dt / span;
        // d²/dt² of c_j τ^j = c_j j (j − 1) τ^{j−2} / T²
        let second: f64 = (0..m)
            .map(|j| {
                let p = j + 2;
                c[j] * (p * (p - 1)) as f64 * tau.powi(p as i32 - 2)
            })
            .sum();
        *y -= second / (span * span);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The digital filter's magnitude is the analog prototype's at the prewarped frequency,
    /// exactly (bilinear transform): |H|² = 1/(1 + (tan(πf dt)/tan(πf_c dt))^{±2n}). Tolerance
    /// 1e-7 relative: evaluating a section at z = e^{iw} cancels as 1 − 2cos w + cos 2w ~ w²,
    /// and w = 2π·0.01 Hz·dt = 3e-4 loses about 7 of the 16 digits (1e-12 above 1 Hz).
    #[test]
    fn magnitude_matches_the_analog_prototype() {
        let dt = 0.005;
        for order in 1..=MAX_ORDER {
            for (pass, fc) in [(Pass::Low, 25.0), (Pass::High, 0.1), (Pass::High, 2.0)] {
                let s = butterworth(order, fc, dt, pass);
                assert_eq!(s.len(), order.div_ceil(2));
                for f in [0.01, 0.05, 0.1, 0.5, 1.0, 5.0, 20.0, 25.0, 40.0, 90.0] {
                    let h: f64 = s.iter().map(|x| x.magnitude(f, dt)).product();
                    let r = (PI * f * dt).tan() / (PI * fc * dt).tan();
                    let e = match pass {
                        Pass::Low => 2.0 * order as f64,
                        Pass::High => -2.0 * order as f64,
                    };
                    let exact = 1.0 / (1.0 + r.powf(e)).sqrt();
                    let tol = if f < 1.0 { 1e-7 } else { 1e-12 };
                    assert!(
                        (h - exact).abs() < tol * exact + 1e-15,
                        "order {order} {pass:?} fc {fc} f {f}: {h} vs {exact}"
                    );
                }
                // −3 dB at the corner for one pass
                let h: f64 = s.iter().map(|x| x.magnitude(fc, dt)).product();
                let tol = if fc < 1.0 { 1e-7 } else { 1e-12 };
                assert!((h - 0.5f64.sqrt()).abs() < tol, "{h}");
            }
        }
    }

    /// Forward–backward: a steady sine comes out scaled by |H(f)|² and not shifted (zero phase).
    /// Measured on the middle half, away from the start-up transients; tolerance 2e-3 of the
    /// amplitude covers what is left of them (the slowest pole decays as e^{−2π f_c t sin θ}).
    #[test]
    fn filtfilt_squares_the_magnitude_and_keeps_the_phase() {
        let dt = 0.01;
        let n = 20_000;
        for (pass, fc, f) in [
            (Pass::Low, 5.0, 5.0),
            (Pass::Low, 5.0, 3.0),
            (Pass::High, 0.5, 0.5),
            (Pass::High, 0.5, 1.0),
        ] {
            let s = butterworth(4, fc, dt, pass);
            let mut x: Vec<f64> = (0..n)
                .map(|k| (2.0 * PI * f * k as f64 * dt).sin())
                .collect();
            filtfilt(&s, &mut x);
            let h2: f64 = s
                .iter()
                .map(|x| x.magnitude(f, dt))
                .product::<f64>()
                .powi(2);
            for (k, xk) in x.iter().enumerate().take(3 * n / 4).skip(n / 4) {
                let want = h2 * (2.0 * PI * f * k as f64 * dt).sin();
                assert!((xk - want).abs() < 2e-3, "{pass:?} f {f}: {xk} vs {want}");
            }
        }
    }

    /// The linear baseline leaves a residual orthogonal to 1 and t (the normal equations).
    #[test]
    fn linear_baseline_is_the_least_squares_line() {
        let dt = 0.01;
        let a: Vec<f64> = (0..1001)
            .map(|k| {
                let t = k as f64 * dt;
                0.3 + 0.02 * t + (2.0 * PI * 1.3 * t).sin()
            })
            .collect();
        let mut r = a.clone();
        remove_line(&mut r, dt);
        let s0: f64 = r.iter().sum();
        let s1: f64 = r.iter().enumerate().map(|(k, y)| k as f64 * dt * y).sum();
        assert!(s0.abs() < 1e-9 && s1.abs() < 1e-8, "{s0} {s1}");
        // a pure line is removed entirely
        let mut line: Vec<f64> = (0..50).map(|k| 2.0 - 0.5 * k as f64).collect();
        remove_line(&mut line, 0.1);
        assert!(line.iter().all(|y| y.abs() < 1e-12));
    }

    /// An acceleration whose displacement is exactly Σ c_j τ^j (j = 2..6) is removed entirely
    /// by the polynomial baseline. Sampled finely: the piecewise-linear displacement of the
    /// sampled second derivative differs from the polynomial by O(dt²) (here < 1e-7 of it).
    #[test]
    fn polynomial_baseline_removes_a_displacement_polynomial() {
        let dt = 0.001;
        let n = 10_001;
        let span = (n - 1) as f64 * dt;
        let c = [0.5, -1.0, 0.8, 0.2, -0.3];
        let a: Vec<f64> = (0..n)
            .map(|k| {
                let tau = k as f64 * dt / span;
                (0..5)
                    .map(|j| {
                        let p = j + 2;
                        c[j] * (p * (p - 1)) as f64 * tau.powi(p as i32 - 2)
                    })
                    .sum::<f64>()
                    / (span * span)
            })
            .collect();
        let peak = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let mut r = a.clone();
        remove_displacement_polynomial(&mut r, dt);
        let left = r.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        assert!(left < 1e-6 * peak, "{left} of {peak}");
    }

    /// The whole chain: a sine in the pass band plus an offset and a drift comes out as the
    /// sine scaled by |H|² (pads added), with velocity and displacement ending near rest.
    #[test]
    fn processing_a_drifting_record() {
        let dt = 0.005;
        let n = 8000;
        let f = 2.0;
        let a: Vec<f64> = (0..n)
            .map(|k| {
                let t = k as f64 * dt;
                (2.0 * PI * f * t).sin() * (-((t - 20.0) / 6.0).powi(2)).exp() + 0.05 + 0.002 * t
            })
            .collect();
        let p = Processing {
            baseline: Some(Baseline::Polynomial),
            highpass_hz: Some(0.1),
            lowpass_hz: Some(25.0),
            order: 4,
        };
        let out = p.apply(&a, dt).unwrap();
        let half = (0.5 * 1.5 * 4.0 / 0.1 / dt).ceil() as usize;
        assert_eq!(out.len(), n + 2 * half);
        // the displacement no longer drifts: it ends within 1 % of its peak
        let d = displacement(&out, dt);
        let peak = d.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        assert!(
            d.last().unwrap().abs() < 0.01 * peak,
            "{} of {peak}",
            d.last().unwrap()
        );
        // the pulse itself is kept: its peak within 2 % (|H(2 Hz)|² ≈ 1 for both corners)
        let pk = out.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        assert!((pk - 1.0).abs() < 0.02, "{pk}");
    }

    #[test]
    fn settings_are_checked() {
        let dt = 0.01;
        let p = |h: Option<f64>, l: Option<f64>, order| Processing {
            baseline: None,
            highpass_hz: h,
            lowpass_hz: l,
            order,
        };
        assert!(p(Some(0.1), Some(25.0), 4).check(dt).is_ok());
        assert!(
            p(None, Some(50.0), 4)
                .check(dt)
                .unwrap_err()
                .contains("Nyquist")
        );
        assert!(
            p(Some(5.0), Some(1.0), 4)
                .check(dt)
                .unwrap_err()
                .contains("below")
        );
        assert!(
            p(Some(0.1), None, 0)
                .check(dt)
                .unwrap_err()
                .contains("order")
        );
        assert!(p(Some(-1.0), None, 4).check(dt).is_err());
        assert_eq!(
            p(Some(0.1), Some(25.0), 4).describe(),
            "baseline mean, band-pass 0.1–25 Hz (Butterworth order 4, zero-phase)"
        );
    }
}
