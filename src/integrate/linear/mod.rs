//! The shared core of the `exact-modal` and `adaptive` methods: each mode's linear dynamics
//! `η̈ + 2ζωη̇ + ω²η = f(t)` (docs/model.md §2.4) propagated exactly over a step.
//!
//! - [`propagator`]: the 2×2 matrix `P(h) = exp(hA)`, `A = [[0, 1], [−ω², −2ζω]]`, for any ζ ≥ 0
//!   (under-, critically and over-damped) and any ωh (for large ζωh it tends to 0 without
//!   overflowing).
//! - [`Influence`]: the exact response from rest to a constant and to a linearly growing load over
//!   a step (`h φ₁(hA) e₂`, `h φ₂(hA) e₂`), by series for small ‖hA‖ (no cancellation), else from
//!   `P(h)`.
//! - [`GroundModes`]: exact particular solutions of every mode under the ground load:
//!   `η_p = Im[F e^{iΩt}/(ω² − Ω² + 2iζωΩ)]` for harmonic motion (resonant form `Im[F t e^{iΩt}/(2iω)]`
//!   at undamped resonance), and the polynomial `A + Bτ + Cτ²` within one interval of a recorded
//!   motion (a_g linear, v_g quadratic in τ). With them, `y(t₁) = P(h)(y(t₀) − y_p(t₀)) + y_p(t₁)`
//!   is exact for any step.
//! - Exact energy flows over a step (`tally`: work of the ground load and of a polynomial contact load,
//!   from moments of η obtained from the equation of motion itself), so that the tallies of
//!   [`super::Tally`] need no quadrature of fast oscillations.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

mod tally;

pub use tally::{
    ContactForms, HarmonicTally, LevelStep, ModeWork, StateSums, TrigMoments, mode_work,
    poly_ground_work, poly_mode_work,
};

use std::sync::Arc;

use crate::model::ground_motion::{GroundMotion, Record};
use crate::model::system::System;

/// The exact homogeneous propagator of one mode over a step: `[η; η̇](t+h) = P [η; η̇](t)`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Prop {
    /// ∂η(h)/∂η(0).
    pub p11: f64,
    /// ∂η(h)/∂η̇(0), s.
    pub p12: f64,
    /// ∂η̇(h)/∂η(0), 1/s.
    pub p21: f64,
    /// ∂η̇(h)/∂η̇(0).
    pub p22: f64,
}

impl Prop {
    /// The identity (h = 0).
    pub const IDENTITY: Prop = Prop {
        p11: 1.0,
        p12: 0.0,
        p21: 0.0,
        p22: 1.0,
    };

    /// `P·(x, y)`.
    #[inline(always)]
    pub fn apply(&self, x: f64, y: f64) -> (f64, f64) {
        (self.p11 * x + self.p12 * y, self.p21 * x + self.p22 * y)
    }
}

/// `P(h)` for `η̈ + damp·η̇ + ω²η = 0` (ω in rad/s, damp = 2ζω in 1/s, h in s; docs/model.md §2.4, §2.5).
///
/// Written as `P = [[C + ζωS, S], [−ω²S, C − ζωS]]` with `C = e^{−ζωh} cos ω_d h`,
/// `S = e^{−ζωh} sin(ω_d h)/ω_d` for ζ < 1 and, for ζ ≥ 1, the hyperbolic forms evaluated with
/// the slow eigenvalue `λ₁ = −ω²/(ζω + μ)` (μ = ω√(ζ²−1), no cancellation) and `e^{−2μh}`, so
/// that nothing overflows and ζ → 1 from either side is continuous.
pub fn propagator(omega: f64, damp: f64, h: f64) -> Prop {
    let zw = 0.5 * damp; // ζω
    let zeta = zw / omega;
    let (c, s) = if zeta < 1.0 {
        let wd = omega * ((1.0 - zeta) * (1.0 + zeta)).sqrt();
        let e = (-zw * h).exp();
        let x = wd * h;
        let sinc = if x == 0.0 { 1.0 } else { x.sin() / x };
        (e * x.cos(), e * h * sinc)
    } else {
        let mu = omega * ((zeta - 1.0) * (zeta + 1.0)).sqrt();
        let l1 = -omega * omega / (zw + mu);
        let e1 = (l1 * h).exp();
        let x = 2.0 * mu * h;
        let r = (-x).exp();
        let ratio = if x == 0.0 { 1.0 } else { -(-x).exp_m1() / x };
        (e1 * 0.5 * (1.0 + r), e1 * h * ratio)
    };
    Prop {
        p11: c + zw * s,
        p12: s,
        p21: -omega * omega * s,
        p22: c - zw * s,
    }
}

/// Exact response from rest of one mode over a step h to a unit load: `g0` to the constant
/// load 1, `g1` to the ramp τ/h (0 at the start, 1 at the end). Units: (s², s) per m/s² of load.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Influence {
    /// Propagator P(h).
    pub p: Prop,
    /// (η, η̇) at h from rest under load 1.
    pub g0: (f64, f64),
    /// (η, η̇) at h from rest under load τ/h.
    pub g1: (f64, f64),
}

/// P(h) and the load influences for one mode (ω rad/s, damp = 2ζω 1/s, h s).
pub fn influence(omega: f64, damp: f64, h: f64) -> Influence {
    let p = propagator(omega, damp, h);
    let w2 = omega * omega;
    let size = h * (omega + damp);
    if size < 0.5 {
        // Series: h φ_k(hA) e₂ = Σ_m h^{m+k} A^m e₂ / (m+k)!, A = [[0,1],[−ω²,−damp]].
        let (mut x, mut y) = (0.0, 1.0); // A^m e₂
        let mut g0 = (0.0, 0.0);
        let mut g1 = (0.0, 0.0);
        let mut hp = h; // h^{m+1}/(m+1)!
        for m in 0..30 {
            let m = m as f64;
            g0.0 += hp * x;
            g0.1 += hp * y;
            let hq = hp * h / (m + 2.0); // h^{m+2}/(m+2)!
            g1.0 += hq * x / h;
            g1.1 += hq * y / h;
            hp = hq;
            let (nx, ny) = (y, -w2 * x - damp * y);
            x = nx;
            y = ny;
            if hp * (x.abs() + y.abs()) < 1e-18 * (g0.0.abs() + g0.1.abs()) {
                break;
            }
        }
        Influence { p, g0, g1 }
    } else {
        // particular of load 1: η = 1/ω²; of τ/h: η = (τ − damp/ω²)/(hω²)
        let inv = 1.0 / w2;
        let (a, b) = p.apply(inv, 0.0);
        let g0 = (inv - a, -b);
        let bb = inv / h;
        let aa = -damp * bb * inv;
        let (a, b) = p.apply(aa, bb);
        let g1 = (aa + bb * h - a, bb - b);
        Influence { p, g0, g1 }
    }
}

/// Exact response (η, η̇) at time s from rest of one mode (ω rad/s, damp = 2ζω 1/s) under the
/// loads (τ/h)^m, m = 0..3 (used by `adaptive`'s collocation and `exact-modal`'s error estimate).
pub fn monomial_influence(omega: f64, damp: f64, s: f64, h: f64, p: &Prop) -> [(f64, f64); 4] {
    let w2 = omega * omega;
    let mut out = [(0.0, 0.0); 4];
    if s == 0.0 {
        return out;
    }
    if s * (omega + damp) < 1.0 {
        // Σ_r (m!/h^m) s^{r+m+1}/(r+m+1)! A^r e₂
        for (m, o) in out.iter_mut().enumerate() {
            let mut fact = 1.0; // m!/h^m · s^{m+1}/(m+1)!
            for q in 1..=m {
                fact *= q as f64 / h;
            }
            let mut c = fact;
            for q in 1..=(m + 1) {
                c *= s / q as f64;
            }
            let (mut x, mut y) = (0.0, 1.0);
            let mut acc = (0.0, 0.0);
            for r in 0..60 {
                acc.0 += c * x;
                acc.1 += c * y;
                c *= s / (r + m + 2) as f64;
                let (nx, ny) = (y, -w2 * x - damp * y);
                x = nx;
                y = ny;
                if c * (x.abs() + y.abs()) < 1e-17 * (acc.0.abs() * w2.max(1.0) + acc.1.abs()) {
                    break;
                }
            }
            *o = acc;
        }
    } else {
        for (m, o) in out.iter_mut().enumerate() {
            // particular polynomial Σ u_r τ^r of the load τ^m/h^m
            let mut u = [0.0; 6];
            let cm = 1.0 / h.powi(m as i32);
            for r in (0..=m).rev() {
                let c = if r == m { cm } else { 0.0 };
                u[r] =
                    (c - damp * (r + 1) as f64 * u[r + 1] - ((r + 2) * (r + 1)) as f64 * u[r + 2])
                        / w2;
            }
            let (mut e, mut d) = (0.0, 0.0);
            for r in (0..=m).rev() {
                e = e * s + u[r];
            }
            for r in (1..=m).rev() {
                d = d * s + r as f64 * u[r];
            }
            let (a, b) = p.apply(u[0], u[1]);
            *o = (e - a, d - b);
        }
    }
    out
}

/// The ground load over a span of time where it is smooth: the mode loads are
/// `la_j a_g + lv_j v_g` with a_g, v_g given here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Piece {
    /// No ground load.
    Zero,
    /// `a_g = a0 + a1 τ`, `v_g = v0 + a0 τ + a1 τ²/2`, τ = t − t0 (records; constant v_g after
    /// a record's end).
    Poly {
        /// Start of the piece, s.
        t0: f64,
        /// a_g at t0, m/s².
        a0: f64,
        /// Slope of a_g, m/s³.
        a1: f64,
        /// v_g at t0, m/s.
        v0: f64,
    },
    /// Harmonic motion (see [`GroundModes`]).
    Harmonic,
}

/// Per-mode ground data: exact particular solutions (docs/model.md §2.4, §2.8).
#[derive(Debug, Clone)]
pub struct GroundModes {
    /// ω², 1/s².
    pub w2: Vec<f64>,
    /// ω, rad/s.
    pub omega: Vec<f64>,
    /// 2ζω, 1/s.
    pub damp: Vec<f64>,
    /// Coefficient of a_g in the load, kg^½.
    pub la: Vec<f64>,
    /// Coefficient of v_g, kg^½/s.
    pub lv: Vec<f64>,
    /// Harmonic: Ω (rad/s) and PGA (m/s²).
    harmonic: Option<(f64, f64)>,
    /// Harmonic particular: η_p = Im[G e^{iΩt}] (or t·Im[G e^{iΩt}] if resonant).
    g_re: Vec<f64>,
    g_im: Vec<f64>,
    resonant: Vec<bool>,
    record: Option<Arc<Record>>,
    /// 1/ω², s².
    pub(crate) inv_w2: Vec<f64>,
    /// Harmonic load coefficients α, β (load = α sin Ωt + β cos Ωt), ω² − Ω², 2ζωΩ and
    /// 1/((ω² − Ω²)² + (2ζωΩ)²) (0 at undamped resonance).
    hcoef: Vec<[f64; 5]>,
}

/// Trigonometric values of the harmonic motion at one instant.
#[derive(Debug, Clone, Copy, Default)]
pub struct Trig {
    /// Time, s.
    pub t: f64,
    /// sin Ωt.
    pub s: f64,
    /// cos Ωt.
    pub c: f64,
}

impl GroundModes {
    /// Precompute from an assembled system.
    pub fn new(sys: &System) -> GroundModes {
        let omega = sys.omega().to_vec();
        let w2: Vec<f64> = omega.iter().map(|w| w * w).collect();
        let damp = sys.damping_coefficients().to_vec();
        let la = sys.ground_load().to_vec();
        let lv = sys.air_load().to_vec();
        let n = omega.len();
        let mut g_re = vec![0.0; n];
        let mut g_im = vec![0.0; n];
        let mut resonant = vec![false; n];
        let mut harmonic = None;
        let mut record = None;
        match &sys.ground {
            GroundMotion::None => {}
            GroundMotion::Record(r) => record = Some(r.clone()),
            GroundMotion::Harmonic(hm) => {
                let big = hm.omega;
                harmonic = Some((big, hm.pga));
                for j in 0..n {
                    // load = Im[F e^{iΩt}], F = (−la·pga) + i(lv·pga/Ω)
                    let (fr, fi) = (-la[j] * hm.pga, lv[j] * hm.pga / big);
                    let hr = w2[j] - big * big;
                    let hi = damp[j] * big;
                    let den = hr * hr + hi * hi;
                    if den <= 1e-24 * w2[j] * w2[j] {
                        // undamped resonance: η_p = Im[F t e^{iΩt}/(2iΩ)]
                        resonant[j] = true;
                        g_re[j] = fi / (2.0 * big);
                        g_im[j] = -fr / (2.0 * big);
                    } else {
                        g_re[j] = (fr * hr + fi * hi) / den;
                        g_im[j] = (fi * hr - fr * hi) / den;
                    }
                }
            }
        }
        let inv_w2: Vec<f64> = w2.iter().map(|x| 1.0 / x).collect();
        let hcoef = (0..n)
            .map(|j| match harmonic {
                Some((big, pga)) => {
                    let m = w2[j] - big * big;
                    let nn = damp[j] * big;
                    let det = m * m + nn * nn;
                    let inv = if det > 1e-24 * w2[j] * w2[j] {
                        1.0 / det
                    } else {
                        0.0
                    };
                    [-la[j] * pga, lv[j] * pga / big, m, nn, inv]
                }
                None => [0.0; 5],
            })
            .collect();
        GroundModes {
            inv_w2,
            hcoef,
            w2,
            omega,
            damp,
            la,
            lv,
            harmonic,
            g_re,
            g_im,
            resonant,
            record,
        }
    }

    /// Number of modes.
    pub fn len(&self) -> usize {
        self.w2.len()
    }

    /// True without modes.
    pub fn is_empty(&self) -> bool {
        self.w2.is_empty()
    }

    /// The piece of ground load in force at time t (s) and the time it ends (s; ∞ if never).
    /// At a record sample time the piece starting there is returned.
    pub fn piece_at(&self, t: f64) -> (Piece, f64) {
        if self.harmonic.is_some() {
            return (Piece::Harmonic, f64::INFINITY);
        }
        let Some(r) = &self.record else {
            return (Piece::Zero, f64::INFINITY);
        };
        let n = r.accel.len();
        let v = r.velocity_samples();
        if n < 2 || v.len() < n {
            return (Piece::Zero, f64::INFINITY);
        }
        let dt = r.dt;
        let end = (n - 1) as f64 * dt;
        if t >= end - 1e-9 * dt {
            return (
                Piece::Poly {
                    t0: end,
                    a0: 0.0,
                    a1: 0.0,
                    v0: v[n - 1],
                },
                f64::INFINITY,
            );
        }
        let x = (t / dt).max(0.0);
        let mut k = (x as usize).min(n - 2);
        // at (or a rounding error below) a sample time, take the piece starting there
        if k + 1 < n - 1 && ((k + 1) as f64 * dt - t) <= 1e-9 * dt {
            k += 1;
        }
        let t0 = k as f64 * dt;
        let a0 = r.accel[k];
        let a1 = (r.accel[k + 1] - a0) / dt;
        (
            Piece::Poly {
                t0,
                a0,
                a1,
                v0: v[k],
            },
            (k + 1) as f64 * dt,
        )
    }

    /// Trigonometric values at t for harmonic motion (zeros otherwise).
    #[inline]
    pub fn trig(&self, t: f64) -> Trig {
        match self.harmonic {
            Some((big, _)) => {
                let (s, c) = (big * t).sin_cos();
                Trig { t, s, c }
            }
            None => Trig::default(),
        }
    }

    /// Polynomial load coefficients (c0, c1, c2) of mode j in τ = t − ts for a poly piece,
    /// starting at ts (s).
    #[inline(always)]
    pub fn poly_load(&self, j: usize, piece: &Piece, ts: f64) -> [f64; 3] {
        match *piece {
            Piece::Poly { t0, a0, a1, v0 } => {
                let tau = ts - t0;
                let a = a0 + a1 * tau;
                let v = v0 + tau * (a0 + 0.5 * a1 * tau);
                [
                    self.la[j] * a + self.lv[j] * v,
                    self.la[j] * a1 + self.lv[j] * a,
                    0.5 * self.lv[j] * a1,
                ]
            }
            _ => [0.0; 3],
        }
    }

    /// Particular solution (η_p, η̇_p) of mode j for the ground load at time `trig.t` (harmonic)
    /// or at τ after `ts` for a polynomial load `c` in τ (zero piece: (0, 0)).
    #[inline(always)]
    pub fn particular(
        &self,
        j: usize,
        piece: &Piece,
        c: &[f64; 3],
        tau: f64,
        tr: &Trig,
    ) -> (f64, f64) {
        match piece {
            Piece::Zero => (0.0, 0.0),
            Piece::Poly { .. } => poly_particular(self.w2[j], self.damp[j], c, tau),
            Piece::Harmonic => {
                let big = self.harmonic.map_or(0.0, |h| h.0);
                let (gr, gi) = (self.g_re[j], self.g_im[j]);
                let im = gr * tr.s + gi * tr.c; // Im[G e^{iΩt}]
                let imd = big * (gr * tr.c - gi * tr.s); // Im[iΩ G e^{iΩt}]
                if self.resonant[j] {
                    (tr.t * im, im + tr.t * imd)
                } else {
                    (im, imd)
                }
            }
        }
    }

    /// Harmonic motion without a mode at undamped resonance: Ω (rad/s) and the particular
    /// solutions' coefficients (η_p = G_re sin Ωt + G_im cos Ωt); `None` otherwise.
    #[inline]
    pub fn harmonic_plain(&self) -> Option<(f64, &[f64], &[f64])> {
        let (big, _) = self.harmonic?;
        if self.resonant.iter().any(|&r| r) {
            return None;
        }
        Some((big, &self.g_re, &self.g_im))
    }

    /// Ω of a harmonic motion, rad/s.
    pub fn harmonic_omega(&self) -> Option<f64> {
        self.harmonic.map(|h| h.0)
    }

    /// Ground load of mode j at the instant of `tr` (harmonic) or τ into a polynomial piece
    /// with load coefficients `c`, m/s²·kg^½.
    #[inline(always)]
    pub fn load(&self, j: usize, piece: &Piece, c: &[f64; 3], tau: f64, tr: &Trig) -> f64 {
        match piece {
            Piece::Zero => 0.0,
            Piece::Poly { .. } => c[0] + tau * (c[1] + tau * c[2]),
            Piece::Harmonic => {
                let (al, be, _) = self.harmonic_load(j);
                al * tr.s + be * tr.c
            }
        }
    }

    /// Harmonic load coefficients (α, β) of mode j: load = α sin Ωt + β cos Ωt; and Ω.
    #[inline(always)]
    fn harmonic_load(&self, j: usize) -> (f64, f64, f64) {
        match self.harmonic {
            Some((big, pga)) => (-self.la[j] * pga, self.lv[j] * pga / big, big),
            None => (0.0, 0.0, 1.0),
        }
    }
}

/// Particular solution `A + Bτ + Cτ²` of `η̈ + dη̇ + ω²η = c0 + c1τ + c2τ²` and its derivative at τ.
#[inline(always)]
pub fn poly_particular(w2: f64, d: f64, c: &[f64; 3], tau: f64) -> (f64, f64) {
    let (a, b, cc) = poly_coefficients(1.0 / w2, d, c);
    (a + tau * (b + tau * cc), b + 2.0 * tau * cc)
}

/// The coefficients (A, B, C) of [`poly_particular`] from 1/ω² (s²), d and the load `c`.
#[inline(always)]
pub fn poly_coefficients(inv_w2: f64, d: f64, c: &[f64; 3]) -> (f64, f64, f64) {
    let cc = c[2] * inv_w2;
    let b = (c[1] - 2.0 * d * cc) * inv_w2;
    let a = (c[0] - d * b - 2.0 * cc) * inv_w2;
    (a, b, cc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`ContactForms::tallies`] is the sum over the modes of [`HarmonicTally::with_contact`]
    /// (an algebraic regrouping: it must hold for any states and loads), with two levels so that
    /// the level cross terms count.
    #[test]
    fn contact_forms_regroup_the_per_mode_tallies() {
        use crate::model::contact::ContactLaw;
        use crate::model::ground_motion::Harmonic;
        use crate::model::structure::{Cantilever, Damping, Stiffness};
        use crate::model::system::ContactLevel;
        let st = |period: f64, zeta: f64| Cantilever {
            name: "s".into(),
            length: 10.0,
            mass: 2.0e6,
            stiffness: Stiffness::Period(period),
            modes: 4,
            damping: Damping::Modal(vec![zeta]),
        };
        let sys = System::new(
            [st(0.42, 0.02).modal(), st(0.6, 0.05).modal()],
            &ContactLaw::Hertz { stiffness: 2.8e10 },
            &[
                ContactLevel {
                    height: 6.0,
                    gap: 0.01,
                },
                ContactLevel {
                    height: 10.0,
                    gap: 0.02,
                },
            ],
            GroundMotion::Harmonic(Harmonic::from_pga_g(0.5, 0.7)),
        );
        let gm = GroundModes::new(&sys);
        let ht = HarmonicTally::new(&gm).expect("damped");
        let (n, nl) = (sys.len(), 2);
        let cpl_t: Vec<f64> = (0..n)
            .flat_map(|j| (0..nl).map(move |k| (j, k)))
            .map(|(j, k)| sys.coupling(k)[j])
            .collect();
        let forms = ContactForms::new(&ht, &gm, &cpl_t, nl);
        let (t0, h) = (1.234, 3.0e-4);
        let big = gm.harmonic_omega().unwrap();
        let tm = TrigMoments::new(big, t0, h);
        let f0 = [3.0e6, 1.0e7];
        let f1 = [5.0e6, 4.0e6];
        let mut steps = [LevelStep::default(); 2];
        let (mut extra, mut contact) = (0.0, 0.0);
        for k in 0..nl {
            steps[k].f0 = f0[k];
            steps[k].df = f1[k] - f0[k];
        }
        for j in 0..n {
            let x = j as f64;
            let y0 = (1e-3 * (x + 1.0).sin(), 2e-2 * (x * 0.7).cos());
            let y1 = (1e-3 * (x + 1.3).sin(), 2e-2 * (x * 0.9).cos());
            let (mut g0, mut g1) = (0.0, 0.0);
            for k in 0..nl {
                let c = cpl_t[j * nl + k];
                g0 += c * f0[k];
                g1 += c * (f1[k] - f0[k]);
                let (wv, wd) = forms.weights[j * nl + k];
                steps[k].cq0 += c * y0.0;
                steps[k].cq1 += c * y1.0;
                steps[k].sv += wv * (y1.1 - y0.1);
                steps[k].se += wd * (y1.0 - y0.0);
            }
            let (e, c) = ht.with_contact(&gm, j, &tm, h, y0, y1, g0, g1 / h);
            extra += e;
            contact += c;
        }
        let (e, c) = forms.tallies(&tm, h, &steps);
        assert!((e - extra).abs() <= 1e-11 * extra.abs(), "{e} vs {extra}");
        assert!(
            (c - contact).abs() <= 1e-11 * contact.abs(),
            "{c} vs {contact}"
        );
        assert!(extra != 0.0 && contact != 0.0);
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (a.abs().max(b.abs()).max(1e-300))
    }

    /// Free decay from (η0, v0) in closed form for ζ < 1, = 1, > 1.
    fn free(omega: f64, zeta: f64, t: f64, e0: f64, v0: f64) -> (f64, f64) {
        if zeta < 1.0 {
            let wd = omega * (1.0 - zeta * zeta).sqrt();
            let a = e0;
            let b = (v0 + zeta * omega * e0) / wd;
            let ex = (-zeta * omega * t).exp();
            let (s, c) = (wd * t).sin_cos();
            let e = ex * (a * c + b * s);
            let v = -zeta * omega * e + ex * (-a * wd * s + b * wd * c);
            (e, v)
        } else if zeta == 1.0 {
            let ex = (-omega * t).exp();
            let b = v0 + omega * e0;
            (ex * (e0 + b * t), ex * (b - omega * (e0 + b * t)))
        } else {
            let mu = omega * (zeta * zeta - 1.0).sqrt();
            let (l1, l2) = (-zeta * omega + mu, -zeta * omega - mu);
            // e0 = A + B, v0 = l1 A + l2 B
            let b = (v0 - l1 * e0) / (l2 - l1);
            let a = e0 - b;
            let (x1, x2) = ((l1 * t).exp(), (l2 * t).exp());
            (a * x1 + b * x2, a * l1 * x1 + b * l2 * x2)
        }
    }

    #[test]
    fn propagator_matches_free_decay() {
        for &zeta in &[0.0, 0.01, 0.5, 0.999999, 1.0, 1.000001, 1.5, 40.0] {
            for &h in &[1e-6, 0.013, 0.7, 3.0] {
                let omega = 7.3;
                let p = propagator(omega, 2.0 * zeta * omega, h);
                let (e, v) = p.apply(0.3, -1.1);
                let (ee, vv) = free(omega, zeta, h, 0.3, -1.1);
                // near ζ = 1 the closed forms themselves lose ~1e-7 (division by ω_d or μ)
                let tol = if (zeta - 1.0f64).abs() < 1e-3 && zeta != 1.0 {
                    1e-6
                } else {
                    1e-12
                };
                assert!(
                    (e - ee).abs() < tol * (1.0 + ee.abs()),
                    "ζ={zeta} h={h}: {e} vs {ee}"
                );
                assert!(
                    (v - vv).abs() < tol * (7.3 + vv.abs()),
                    "ζ={zeta} h={h}: {v} vs {vv}"
                );
            }
        }
    }

    #[test]
    fn propagator_composes() {
        for &zeta in &[0.0, 0.05, 1.0, 3.0] {
            let omega = 12.0;
            let d = 2.0 * zeta * omega;
            let (a, b) = (0.031, 0.17);
            let p1 = propagator(omega, d, a);
            let p2 = propagator(omega, d, b);
            let p = propagator(omega, d, a + b);
            let q = Prop {
                p11: p2.p11 * p1.p11 + p2.p12 * p1.p21,
                p12: p2.p11 * p1.p12 + p2.p12 * p1.p22,
                p21: p2.p21 * p1.p11 + p2.p22 * p1.p21,
                p22: p2.p21 * p1.p12 + p2.p22 * p1.p22,
            };
            for (x, y) in [
                (p.p11, q.p11),
                (p.p12, q.p12),
                (p.p21, q.p21),
                (p.p22, q.p22),
            ] {
                assert!(
                    (x - y).abs() < 1e-13 * (1.0 + omega * omega),
                    "ζ={zeta}: {x} vs {y}"
                );
            }
        }
    }

    /// Huge ωh and huge damping: finite, and → 0; a hugely overdamped mode creeps with its
    /// slow eigenvalue λ₁ = −ω/(ζ + √(ζ²−1)) ≈ −ω/(2ζ).
    #[test]
    fn propagator_never_overflows() {
        for &(omega, zeta, h) in &[(1e7, 0.01, 10.0), (1e7, 1e4, 10.0), (1e5, 3.0, 1.0)] {
            let p = propagator(omega, 2.0 * zeta * omega, h);
            for x in [p.p11, p.p12, p.p21, p.p22] {
                assert!(x.is_finite() && x.abs() < 1e-3, "{p:?}");
            }
        }
        let (omega, zeta, h) = (1e3, 1e6, 1.0);
        let p = propagator(omega, 2.0 * zeta * omega, h);
        let l1 = -omega / (zeta + (zeta * zeta - 1.0f64).sqrt());
        assert!(close(p.p11, (l1 * h).exp(), 1e-9), "{p:?}");
        assert!(p.p22.abs() < 1e-6 && p.p12.is_finite() && p.p21.is_finite());
    }

    /// Influence vectors: series and closed form agree where both are valid, and the closed form
    /// solves the ODE (checked against the particular solution route).
    #[test]
    fn influence_series_and_closed_form_agree() {
        for &zeta in &[0.0, 0.02, 2.0] {
            let omega = 3.0;
            let d = 2.0 * zeta * omega;
            let h = 0.49 / (omega + d) * 0.999;
            let a = influence(omega, d, h);
            // closed form by hand
            let p = propagator(omega, d, h);
            let inv = 1.0 / (omega * omega);
            let (x, y) = p.apply(inv, 0.0);
            let g0 = (inv - x, -y);
            let bb = inv / h;
            let aa = -d * bb * inv;
            let (x, y) = p.apply(aa, bb);
            let g1 = (aa + bb * h - x, bb - y);
            assert!(
                close(a.g0.0, g0.0, 1e-9) && close(a.g0.1, g0.1, 1e-9),
                "{:?} {:?}",
                a.g0,
                g0
            );
            assert!(
                close(a.g1.0, g1.0, 1e-8) && close(a.g1.1, g1.1, 1e-8),
                "{:?} {:?}",
                a.g1,
                g1
            );
        }
        // tiny step: g0 ≈ (h²/2, h), g1 ≈ (h²/6, h/2)
        let a = influence(10.0, 0.4, 1e-7);
        assert!(close(a.g0.0, 0.5e-14, 1e-6) && close(a.g0.1, 1e-7, 1e-6));
        assert!(close(a.g1.0, 1e-14 / 6.0, 1e-6) && close(a.g1.1, 0.5e-7, 1e-6));
    }

    /// The polynomial particular solution satisfies the ODE.
    #[test]
    fn poly_particular_solves_ode() {
        let (w2, d) = (40.0, 0.3);
        let c = [1.5, -2.0, 0.7];
        let tau = 0.37;
        let (e, v) = poly_particular(w2, d, &c, tau);
        // η̈ of A + Bτ + Cτ² is 2C = 2 c2/ω²
        let acc = 2.0 * c[2] / w2;
        let lhs = acc + d * v + w2 * e;
        let rhs = c[0] + c[1] * tau + c[2] * tau * tau;
        assert!(close(lhs, rhs, 1e-14));
    }
}
