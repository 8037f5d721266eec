//! The onset's force shape: the first contact step of a Hertz-family impact with the onset's
//! θ^{3/2} factored out of the force (issue 25; `scripts/contact-step-model/NOTES.md`).
//!
//! From an onset (δ = 0, δ̇₀ > 0) a Hertz force goes as `k(δ̇₀θh)^{3/2}(1 + O(θ))`: the
//! polynomial through its nodal values converges slowly (its derivatives are singular at
//! θ = 0), which is what makes today's first steps of an impact short. Here the force over that
//! step is `F(θ) = θ^{3/2} g(θ)` with g the polynomial through the scheme's nodes (the quartic
//! of the 5 nodes, the companion's cubic of its 4), so both schemes are exact for the leading
//! term and the estimate measures the error of the smooth part. g(0) = F(δ̇₀h, δ̇₀, v₀) (the law
//! is homogeneous of degree 3/2 in δ: the limit of F/θ^{3/2}) is known; the unknowns stay the
//! nodal forces `F_p = θ_p^{3/2} g_p` (p ≥ 1), so the Newton solve is unchanged: the basis of
//! F_p is `(θ/θ_p)^{3/2} ℓ_p(θ)`, and the start's slot holds g(0) with the basis `θ^{3/2}ℓ₀`.
//! The tables of such a step hold every mode's exact response to these loads
//! ([`half_responses`]) and depend on the step's length only, so they are cached per quantised
//! length as the polynomial ones are.

use super::nodes::{A1, A2, Bases, THETA8, bases};
use crate::integrate::linear::propagator;
use crate::numerics::linalg::power;

/// Per-node scales and weights of the onset's shape (computed once, see [`onset_shape`]).
pub(in crate::integrate) struct OnsetShape {
    /// `θ_p^{−3/2}` at the 5-node scheme's nodes after the start (1 at the start: its slot is
    /// g(0)).
    pub s8: [f64; 5],
    /// The same at the companion's nodes.
    pub s6: [f64; 4],
    /// `θ_p^{3/2}` at the 5-node scheme's nodes (0 at the start): a first guess of the
    /// nodal forces from g(0).
    pub lift8: [f64; 5],
    /// The 5-node shape at the companion's interior nodes A1, A2 (its first guess there).
    pub at6: [[f64; 5]; 2],
    /// `∫₀¹ ψ_p`, `∫₀¹ θψ_p` of the 5-node basis: the step's impulse and first moment.
    pub mean: [f64; 5],
    /// See [`OnsetShape::mean`].
    pub first: [f64; 5],
    /// `∫₀^{θ_{i+1}} ψ_p` at the interior nodes B1, ½, B3 (dense output's impulses).
    pub partial: [[f64; 5]; 3],
}

/// See [`OnsetShape`].
pub(in crate::integrate) fn onset_shape() -> &'static OnsetShape {
    static S: std::sync::OnceLock<OnsetShape> = std::sync::OnceLock::new();
    S.get_or_init(|| {
        let Bases { l8, .. } = bases();
        let s8 = std::array::from_fn(|p| if p == 0 { 1.0 } else { THETA8[p].powf(-1.5) });
        let th6 = [0.0, A1, A2, 1.0];
        let s6 = std::array::from_fn(|p| if p == 0 { 1.0 } else { th6[p].powf(-1.5) });
        let lift8 = std::array::from_fn(|p| THETA8[p].powf(1.5));
        let ell = |p: usize, x: f64| (0..5).map(|m| l8[m][p] * power(x, m as u32)).sum::<f64>();
        let at6 = [A1, A2].map(|x| std::array::from_fn(|p| x.powf(1.5) * ell(p, x) * s8[p]));
        let integral = |p: usize, upper: f64, extra: f64| {
            (0..5)
                .map(|m| {
                    let a = m as f64 + 2.5 + extra;
                    l8[m][p] * upper.powf(a) / a
                })
                .sum::<f64>()
                * s8[p]
        };
        OnsetShape {
            s8,
            s6,
            lift8,
            at6,
            mean: std::array::from_fn(|p| integral(p, 1.0, 0.0)),
            first: std::array::from_fn(|p| integral(p, 1.0, 1.0)),
            partial: std::array::from_fn(|i| {
                std::array::from_fn(|p| integral(p, THETA8[i + 1], 0.0))
            }),
        }
    })
}

/// Gauss–Legendre nodes and weights on [0, 1], 16 points (exact to degree 31), by Newton's
/// method on P₁₆ (computed once).
fn gauss16() -> &'static ([f64; 16], [f64; 16]) {
    static G: std::sync::OnceLock<([f64; 16], [f64; 16])> = std::sync::OnceLock::new();
    G.get_or_init(|| {
        const N: usize = 16;
        let (mut x, mut w) = ([0.0; N], [0.0; N]);
        for i in 0..N {
            let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, z);
                for k in 2..=N {
                    let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = N as f64 * (z * p1 - p0) / (z * z - 1.0);
                let dz = p1 / dp;
                z -= dz;
                if dz.abs() < 1e-16 {
                    break;
                }
            }
            x[i] = 0.5 * (1.0 - z);
            w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
        }
        (x, w)
    })
}

/// `Σ` over a composite 16-point Gauss rule of `panels` equal panels of [0, 1] of `f(u)·w`.
fn composite(panels: usize, mut f: impl FnMut(f64, f64)) {
    let (x, w) = gauss16();
    let width = 1.0 / panels as f64;
    for k in 0..panels {
        for i in 0..16 {
            f((k as f64 + x[i]) * width, w[i] * width);
        }
    }
}

/// Exact response (η, η̇) from rest at times `s_i = θ_i h` (`nodes`) of one mode (ω rad/s,
/// damp = 2ζω 1/s) to the loads (τ/h)^{m + 3/2}, m = 0..4: into `out[i][m]`. The series
/// `Σ_r s^{α+r+1}Γ(α+1)/(h^α Γ(α+r+2)) A^r e₂` (α = m + 3/2; the convolution of τ^α with the
/// impulse response's Taylor terms) where `s(ω + damp)` is small; else the convolution with the
/// impulse response by a composite Gauss rule after τ = s u² (which makes the integrand
/// smooth: u^{2m+4} times the propagator), its panels following the mode's oscillation.
pub(in crate::integrate) fn half_responses(
    omega: f64,
    damp: f64,
    h: f64,
    nodes: &[f64; 6],
    out: &mut [[(f64, f64); 5]; 6],
) {
    let w2 = omega * omega;
    for (i, &th) in nodes.iter().enumerate() {
        let s = th * h;
        let o = &mut out[i];
        if s * (omega + damp) < 1.0 {
            let mut coef = [0.0; 5];
            for (m, c) in coef.iter_mut().enumerate() {
                let a = m as f64 + 1.5;
                *c = th.powf(a) * s / (a + 1.0);
            }
            let (mut x, mut y) = (0.0, 1.0);
            let mut acc = [(0.0, 0.0); 5];
            for r in 0..60 {
                for m in 0..5 {
                    acc[m].0 += coef[m] * x;
                    acc[m].1 += coef[m] * y;
                    coef[m] *= s / (r as f64 + m as f64 + 3.5);
                }
                let (nx, ny) = (y, -w2 * x - damp * y);
                x = nx;
                y = ny;
                if coef[0] * (x.abs() + y.abs())
                    < 1e-17 * (acc[0].0.abs() * w2.max(1.0) + acc[0].1.abs())
                {
                    break;
                }
            }
            *o = acc;
        } else {
            let panels = ((2.0 * s * (omega + damp) / 3.0).ceil() as usize).clamp(1, 4096);
            let mut acc = [(0.0, 0.0); 5];
            let scale = 2.0 * s * th.powf(1.5);
            composite(panels, |u, w| {
                let p = propagator(omega, damp, s * (1.0 - u * u));
                let u2 = u * u;
                // u^{2m+4}·2s·θ^{m+3/2}
                let mut load = w * scale * u2 * u2;
                for a in acc.iter_mut() {
                    a.0 += load * p.p12;
                    a.1 += load * p.p22;
                    load *= u2 * th;
                }
            });
            *o = acc;
        }
    }
}

/// `(∫₀¹ x^{m+3/2} cos ax dx, ∫₀¹ x^{m+3/2} sin ax dx)` for m = 0..4: the series
/// `Σ_r (ia)^r/(r!(m + r + 5/2))` for |a| < 2, else a composite Gauss rule after x = u².
pub(in crate::integrate) fn half_trig_moments(a: f64) -> [(f64, f64); 5] {
    let mut out = [(0.0, 0.0); 5];
    if a.abs() < 2.0 {
        for (m, o) in out.iter_mut().enumerate() {
            let (mut re, mut im) = (0.0, 0.0);
            let mut term = 1.0;
            for r in 0..40 {
                let x = term / (m as f64 + r as f64 + 2.5);
                match r % 4 {
                    0 => re += x,
                    1 => im += x,
                    2 => re -= x,
                    _ => im -= x,
                }
                term *= a / (r + 1) as f64;
                if term.abs() < 1e-18 {
                    break;
                }
            }
            *o = (re, im);
        }
    } else {
        let panels = ((a.abs() / 3.0).ceil() as usize).clamp(1, 4096);
        composite(panels, |u, w| {
            let u2 = u * u;
            let (sn, cs) = (a * u2).sin_cos();
            // x^{m+3/2} dx = u^{2m+3}·2u du
            let mut load = 2.0 * w * u2 * u2;
            for o in out.iter_mut() {
                o.0 += load * cs;
                o.1 += load * sn;
                load *= u2;
            }
        });
    }
    out
}
