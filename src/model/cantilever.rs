//! Modes of a uniform Euler–Bernoulli cantilever (clamped at x = 0, free at x = L), docs/model.md §2.3.
//!
//! Everything here is dimensionless or per unit of `√(mL)`: the mass-normalised shape of a beam
//! with total mass `M = m L` is `φ_n(x) = shape(λ_n, x/L) / √M`.
//!
//! The textbook form `cosh βx − cos βx − σ (sinh βx − sin βx)` cancels catastrophically for large
//! βx (useless by mode ~15) and overflows past mode ~225, so [`Mode::shape`] evaluates it with
//! decaying exponentials only (docs/model.md §2.3).

use std::f64::consts::PI;

/// One cantilever mode: the root `λ = β L` of `cosh λ cos λ + 1 = 0` and the shape constant σ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode {
    /// Dimensionless frequency parameter λ = β_n L.
    pub lambda: f64,
    /// σ_n = (sinh λ − sin λ)/(cosh λ + cos λ), computed without overflow.
    pub sigma: f64,
}

/// The n-th root (n ≥ 1) of the cantilever characteristic equation `cosh λ cos λ + 1 = 0`.
///
/// Solved by Newton's method on the well-scaled equivalent `cos λ + sech λ = 0`, starting from
/// (2n − 1)π/2; converges to machine precision in a few iterations for every n.
pub fn root(n: usize) -> f64 {
    assert!(n >= 1, "cantilever modes are numbered from 1");
    let mut x = (2.0 * n as f64 - 1.0) * PI / 2.0;
    for _ in 0..100 {
        let e1 = (-x).exp();
        let e2 = e1 * e1;
        let sech = 2.0 * e1 / (1.0 + e2);
        let tanh = (1.0 - e2) / (1.0 + e2);
        let f = x.cos() + sech;
        let df = -x.sin() - tanh * sech;
        let step = f / df;
        x -= step;
        if step.abs() <= 1e-16 * x {
            break;
        }
    }
    x
}

impl Mode {
    /// The n-th mode (n ≥ 1).
    pub fn new(n: usize) -> Mode {
        let lambda = root(n);
        let e1 = (-lambda).exp();
        let e2 = e1 * e1;
        let d = 1.0 + e2 + 2.0 * lambda.cos() * e1;
        let sigma = (1.0 - e2 - 2.0 * lambda.sin() * e1) / d;
        Mode { lambda, sigma }
    }

    /// The first `count` modes.
    pub fn first(count: usize) -> Vec<Mode> {
        (1..=count).map(Mode::new).collect()
    }

    /// `φ_n(ξL)·√(mL)`: the mass-normalised shape at relative height ξ = x/L ∈ [0, 1],
    /// evaluated with decaying exponentials only (docs/model.md §2.3).
    pub fn shape(&self, xi: f64) -> f64 {
        let l = self.lambda;
        let (s, c) = l.sin_cos();
        let e = |a: f64| (-l * a).exp();
        let d = 1.0 + e(2.0) + 2.0 * c * e(1.0);
        let a = e(1.0 - xi);
        let b = e(1.0 + xi);
        let cosh_minus_sigma_sinh = (e(xi) + e(2.0 - xi) + c * (a + b) + s * (a - b)) / d;
        let (sx, cx) = (l * xi).sin_cos();
        cosh_minus_sigma_sinh - cx + self.sigma * sx
    }

    /// `γ_n·√(mL)/L = (1/L)∫₀ᴸ φ_n dx·√(mL) = 2σ_n/λ_n` (docs/model.md §2.3): the modal participation
    /// integral per unit length, dimensionless.
    pub fn participation(&self) -> f64 {
        2.0 * self.sigma / self.lambda
    }

    /// `√(mL)/L · ∫_{ξL}^{L} φ_n dx = ∫_ξ^1 y(ξ') dξ'`, the share of the mode's participation
    /// integral above relative height ξ (dimensionless): from `y'''' = λ⁴ y` and the free end's
    /// `y'''(1) = 0`, `∫_ξ^1 y = −y'''(ξ)/λ⁴ = [σ(cosh λξ + cos λξ) − sinh λξ + sin λξ]/λ`,
    /// with `σ cosh − sinh` written in decaying exponentials as [`Mode::shape`] does. At ξ = 0
    /// it is [`Mode::participation`]; the storey shear of a cantilever is built from it.
    pub fn integral_above(&self, xi: f64) -> f64 {
        let l = self.lambda;
        let (s, c) = l.sin_cos();
        let e = |a: f64| (-l * a).exp();
        let d = 1.0 + e(2.0) + 2.0 * c * e(1.0);
        // σ cosh λξ − sinh λξ = ½[(σ−1)e^{λξ} + (σ+1)e^{−λξ}], (σ−1) = −2(e^{−2λ} + (s+c)e^{−λ})/d
        let growing = -(e(2.0 - xi) + (s + c) * e(1.0 - xi)) / d;
        let decaying = 0.5 * (self.sigma + 1.0) * e(xi);
        let (sx, cx) = (l * xi).sin_cos();
        (growing + decaying + self.sigma * cx + sx) / l
    }

    /// ω_n/ω_1 scale: `λ²`, so that `ω_n = λ_n² √(EI/(m L⁴))` (docs/model.md §2.3, paper eq. 12).
    pub fn lambda_squared(&self) -> f64 {
        self.lambda * self.lambda
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `∫_ξ^1 y` against Simpson's rule on [`Mode::shape`] (2000 intervals: error ~1e-12 for
    /// the first ten modes), and at ξ = 0 against the participation integral 2σ/λ.
    #[test]
    fn integral_above_matches_quadrature() {
        for n in [1, 2, 3, 7, 10] {
            let m = Mode::new(n);
            assert!((m.integral_above(0.0) - m.participation()).abs() < 1e-12);
            assert!(m.integral_above(1.0).abs() < 1e-12);
            for xi in [0.1, 0.35, 0.8] {
                let k = 2000;
                let h = (1.0 - xi) / k as f64;
                let mut sum = m.shape(xi) + m.shape(1.0);
                for i in 1..k {
                    sum += if i % 2 == 1 { 4.0 } else { 2.0 } * m.shape(xi + i as f64 * h);
                }
                let q = sum * h / 3.0;
                assert!(
                    (m.integral_above(xi) - q).abs() < 1e-9,
                    "mode {n} at {xi}: {} vs {q}",
                    m.integral_above(xi)
                );
            }
        }
    }

    /// Roots printed in docs/model.md §2.3 (and standard tables), to 1e-12 absolute.
    #[test]
    fn roots_match_tabulated_values() {
        let expected = [
            1.875104068711961,
            4.694091132974175,
            7.854757438237613,
            10.995540734875467,
            14.13716839104647,
        ];
        for (i, &e) in expected.iter().enumerate() {
            let r = root(i + 1);
            assert!((r - e).abs() < 1e-12, "mode {}: {r} vs {e}", i + 1);
        }
    }

    /// For large n the roots approach (2n−1)π/2 and satisfy the characteristic equation.
    #[test]
    fn high_roots_satisfy_characteristic_equation() {
        for n in [10, 50, 200, 500] {
            let r = root(n);
            let asym = (2.0 * n as f64 - 1.0) * PI / 2.0;
            assert!((r - asym).abs() < 1e-3, "mode {n}");
            // cos λ + sech λ = 0; |d/dλ| ≈ 1, and cos of an argument rounded to ulp(λ) is
            // itself uncertain by ≈ ε·λ, so that is the best attainable residual.
            let resid = r.cos() + 2.0 * (-r).exp() / (1.0 + (-2.0 * r).exp());
            assert!(
                resid.abs() < 4.0 * f64::EPSILON * r,
                "mode {n}: residual {resid}"
            );
        }
    }

    /// |φ_n(L)|·√(mL) = 2 for every mode (docs/model.md §2.3).
    #[test]
    fn tip_value_is_two() {
        for n in 1..=500 {
            let m = Mode::new(n);
            assert!(
                (m.shape(1.0).abs() - 2.0).abs() < 1e-12,
                "mode {n}: {}",
                m.shape(1.0)
            );
        }
    }

    /// Clamped end: φ(0) = 0.
    #[test]
    fn clamped_end_is_zero() {
        for n in 1..=200 {
            assert!(Mode::new(n).shape(0.0).abs() < 1e-13);
        }
    }

    /// Gauss–Legendre nodes and weights on [−1, 1] by Newton on P_n (Golub–Welsch not needed).
    fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
        let mut x = vec![0.0; n];
        let mut w = vec![0.0; n];
        for i in 0..n {
            let mut z = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, z);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
                let dz = p1 / dp;
                z -= dz;
                if dz.abs() < 1e-16 {
                    break;
                }
            }
            x[i] = z;
            w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
        }
        (x, w)
    }

    /// Composite Gauss–Legendre quadrature of f over ξ ∈ [0, 1].
    fn integrate01(f: impl Fn(f64) -> f64, panels: usize, order: usize) -> f64 {
        let (x, w) = gauss_legendre(order);
        let h = 1.0 / panels as f64;
        let mut sum = 0.0;
        for p in 0..panels {
            let a = p as f64 * h;
            for (xi, wi) in x.iter().zip(&w) {
                sum += wi * h / 2.0 * f(a + h * (xi + 1.0) / 2.0);
            }
        }
        sum
    }

    /// ∫₀ᴸ m φ_r φ_n dx = δ_rn for 200 modes, by quadrature fine enough to resolve mode 200
    /// (≈100 oscillations: 400 panels × 20 points). Error bound 1e-9 as the issue requires.
    #[test]
    fn two_hundred_modes_are_orthonormal() {
        let modes = Mode::first(200);
        let (gx, gw) = gauss_legendre(20);
        let panels = 400;
        let h = 1.0 / panels as f64;
        // Shapes tabulated once at all quadrature nodes: n_nodes × 200.
        let mut nodes = Vec::new();
        let mut weights = Vec::new();
        for p in 0..panels {
            for (xi, wi) in gx.iter().zip(&gw) {
                nodes.push(p as f64 * h + h * (xi + 1.0) / 2.0);
                weights.push(wi * h / 2.0);
            }
        }
        let table: Vec<Vec<f64>> = modes
            .iter()
            .map(|m| nodes.iter().map(|&x| m.shape(x)).collect())
            .collect();
        let mut worst = 0.0f64;
        for r in 0..200 {
            for n in r..200 {
                let s: f64 = (0..nodes.len())
                    .map(|k| weights[k] * table[r][k] * table[n][k])
                    .sum();
                let target = if r == n { 1.0 } else { 0.0 };
                worst = worst.max((s - target).abs());
            }
        }
        assert!(worst < 1e-9, "worst orthonormality error {worst:e}");
    }

    /// γ_n closed form 2σ/λ vs quadrature of the shape, 50 modes, 1e-11.
    #[test]
    fn participation_matches_quadrature() {
        for n in 1..=50 {
            let m = Mode::new(n);
            let q = integrate01(|x| m.shape(x), 200, 16);
            assert!(
                (q - m.participation()).abs() < 1e-11,
                "mode {n}: {q} vs {}",
                m.participation()
            );
        }
    }

    /// The stable shape agrees with the textbook form where the latter is still accurate
    /// (first 5 modes, relative 1e-10).
    #[test]
    fn stable_shape_matches_textbook_form_for_low_modes() {
        for n in 1..=5 {
            let m = Mode::new(n);
            let l = m.lambda;
            let sigma = (l.sinh() - l.sin()) / (l.cosh() + l.cos());
            for k in 0..=20 {
                let x = k as f64 / 20.0 * l;
                let textbook = x.cosh() - x.cos() - sigma * (x.sinh() - x.sin());
                assert!(
                    (m.shape(k as f64 / 20.0) - textbook).abs() < 1e-10 * textbook.abs().max(1.0)
                );
            }
        }
    }
}
