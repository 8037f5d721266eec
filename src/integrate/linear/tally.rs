//! Exact energy flows over a step of the modal equations (docs/model.md §2.4): the work of the
//! ground load and of a polynomial contact load, and the damping's dissipation, from moments of
//! η obtained from the equation of motion itself, so that the tallies of [`crate::integrate::Tally`]
//! need no quadrature of fast oscillations.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::*;

/// Integrals over one step [t0, t0 + h] of the harmonic functions, shared by all modes.
#[derive(Debug, Clone, Copy, Default)]
pub struct TrigMoments {
    ss: f64,
    sc: f64,
    cc: f64,
    s: f64,
    c: f64,
    ts: f64,
    tc: f64,
    /// sin, cos at both ends.
    s0: f64,
    c0: f64,
    s1: f64,
    c1: f64,
}

impl TrigMoments {
    /// For Ω (rad/s) over [t0, t0 + h].
    pub fn new(big: f64, t0: f64, h: f64) -> TrigMoments {
        let e0 = (big * t0).sin_cos();
        let e1 = (big * (t0 + h)).sin_cos();
        TrigMoments::from_ends(big, h, e0, e1, (0.5 * big * h).sin_cos())
    }

    /// The same from (sin, cos) of Ωt₀, Ω(t₀ + h) and Ωh/2 (no further trigonometric calls).
    pub fn from_ends(
        big: f64,
        h: f64,
        (s0, c0): (f64, f64),
        (s1, c1): (f64, f64),
        (sh, ch): (f64, f64),
    ) -> TrigMoments {
        let sin_h = 2.0 * sh * ch;
        let ib = 1.0 / big;
        // sin 2Ωt₁ − sin 2Ωt₀ = 2 cos(Ω(t₀+t₁)) sin(Ωh)
        let d2 = 0.5 * (c0 * c1 - s0 * s1) * sin_h * ib;
        let ss = 0.5 * h - d2;
        let cc = 0.5 * h + d2;
        // sin²Ωt₁ − sin²Ωt₀ = sin(Ω(t₁+t₀)) sin(Ωh)
        let sc = 0.5 * (s0 * c1 + c0 * s1) * sin_h * ib;
        // cos Ωt₀ − cos Ωt₁ = 2 sin(Ω(t₀+t₁)/2) sin(Ωh/2)
        let half = (s0 * ch + c0 * sh, c0 * ch - s0 * sh);
        let s = 2.0 * half.0 * sh * ib;
        let c = 2.0 * half.1 * sh * ib;
        let ts = (c - h * c1) * ib;
        let tc = (h * s1 - s) * ib;
        TrigMoments {
            ss,
            sc,
            cc,
            s,
            c,
            ts,
            tc,
            s0,
            c0,
            s1,
            c1,
        }
    }
}

/// Energy flows of one mode over one step, J (mass-normalised modes).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ModeWork {
    /// Work of the ground load, `∫ f_g η̇ dt`.
    pub input: f64,
    /// Work of the contact load, `∫ g η̇ dt`.
    pub contact: f64,
    /// Dissipated by damping, `∫ 2ζω η̇² dt` (from the mode's energy equation, exact for the
    /// solution with these loads).
    pub damping: f64,
}

/// [`mode_work`] under a recorded motion: the ground load `c0 + c1τ + c2τ²`; the mode's ω², 2ζω
/// and 1/ω² in `mode`; `inv_h` = 1/h.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn poly_mode_work(
    (w2, d, iw2): (f64, f64, f64),
    h: f64,
    inv_h: f64,
    (e0, v0): (f64, f64),
    (e1, v1): (f64, f64),
    c: &[f64; 3],
    g0: f64,
    g1: f64,
) -> ModeWork {
    const THIRD: f64 = 1.0 / 3.0;
    let slope = g1 * inv_h;
    let de = 0.5 * (v1 * v1 - v0 * v0) + 0.5 * w2 * (e1 * e1 - e0 * e0);
    // ∫ f dt of the total load, and ∫η dt from the equation of motion
    let int_f = h * (g0 + 0.5 * slope * h) + h * (c[0] + h * (0.5 * c[1] + h * c[2] * THIRD));
    let i0 = (int_f - (v1 - v0) - d * (e1 - e0)) * iw2;
    let input = if c[1] != 0.0 || c[2] != 0.0 || slope != 0.0 {
        let int_tf = h * h * (0.5 * (g0 + c[0]) + h * ((slope + c[1]) * THIRD + 0.25 * h * c[2]));
        let i1 = (int_tf - (h * v1 - (e1 - e0)) - d * (h * e1 - i0)) * iw2;
        let ph = c[0] + h * (c[1] + h * c[2]);
        ph * e1 - c[0] * e0 - c[1] * i0 - 2.0 * c[2] * i1
    } else {
        c[0] * (e1 - e0)
    };
    let contact = (g0 + g1) * e1 - g0 * e0 - slope * i0;
    ModeWork {
        input,
        contact,
        damping: input + contact - de,
    }
}

/// Exact work of a recorded motion's ground load `c0 + c1τ + c2τ²` on one mode over a step of
/// length h (its 2ζω and 1/ω² in `mode`) whose other load `g(τ)` (any shape) enters only
/// through its moments `∫g dτ` (`g_int`) and `∫τ g dτ` (`g_tint`), from the exact end states:
/// `[cη] − c1∫η − 2c2∫τη`, the moments of η from the equation of motion.
#[inline(always)]
pub fn poly_ground_work(
    (d, iw2): (f64, f64),
    h: f64,
    (e0, v0): (f64, f64),
    (e1, v1): (f64, f64),
    c: &[f64; 3],
    g_int: f64,
    g_tint: f64,
) -> f64 {
    const THIRD: f64 = 1.0 / 3.0;
    if c[1] == 0.0 && c[2] == 0.0 {
        return c[0] * (e1 - e0);
    }
    let int_f = g_int + h * (c[0] + h * (0.5 * c[1] + h * c[2] * THIRD));
    let i0 = (int_f - (v1 - v0) - d * (e1 - e0)) * iw2;
    let int_tf = g_tint + h * h * (0.5 * c[0] + h * (c[1] * THIRD + 0.25 * h * c[2]));
    let i1 = (int_tf - (h * v1 - (e1 - e0)) - d * (h * e1 - i0)) * iw2;
    let ph = c[0] + h * (c[1] + h * c[2]);
    ph * e1 - c[0] * e0 - c[1] * i0 - 2.0 * c[2] * i1
}

/// Exact work over a step of length h of one mode whose load is the ground load plus a contact
/// load linear in τ (`g0 + g1 τ/h`), given the exact end states y0 = (η0, v0), y1 = (η1, v1).
/// `ground` is the polynomial ground load (records) or `None` for harmonic (then `tm` is used).
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn mode_work(
    gm: &GroundModes,
    j: usize,
    h: f64,
    y0: (f64, f64),
    y1: (f64, f64),
    ground: Option<&[f64; 3]>,
    tm: Option<&TrigMoments>,
    g0: f64,
    g1: f64,
) -> ModeWork {
    let (w2, d, iw2) = (gm.w2[j], gm.damp[j], gm.inv_w2[j]);
    if let Some(c) = ground {
        return poly_mode_work((w2, d, iw2), h, 1.0 / h, y0, y1, c, g0, g1);
    }
    let (e0, v0) = y0;
    let (e1, v1) = y1;
    let slope = g1 / h;
    let de = 0.5 * (v1 * v1 - v0 * v0) + 0.5 * w2 * (e1 * e1 - e0 * e0);
    let mut input = 0.0;
    // ∫ f dt of the total load
    let mut int_f = h * (g0 + 0.5 * slope * h);
    let i0;
    if let Some(tm) = tm {
        let [al, be, m, n, inv] = gm.hcoef[j];
        let big = gm.harmonic.map_or(0.0, |x| x.0);
        int_f += al * tm.s + be * tm.c;
        i0 = (int_f - (v1 - v0) - d * (e1 - e0)) * iw2;
        // S = ∫ sin Ωt η, C = ∫ cos Ωt η from the equation of motion times sin, cos
        let int_sf = al * tm.ss + be * tm.sc + g0 * tm.s + slope * tm.ts;
        let int_cf = al * tm.sc + be * tm.cc + g0 * tm.c + slope * tm.tc;
        let dsv = tm.s1 * v1 - tm.s0 * v0;
        let dcv = tm.c1 * v1 - tm.c0 * v0;
        let dse = tm.s1 * e1 - tm.s0 * e0;
        let dce = tm.c1 * e1 - tm.c0 * e0;
        if inv > 0.0 {
            let r1 = int_sf - dsv + big * dce - d * dse;
            let r2 = int_cf - dcv - big * dse - d * dce;
            let s = (m * r1 + n * r2) * inv;
            let c = (m * r2 - n * r1) * inv;
            input = al * (dse - big * c) + be * (dce + big * s);
        } else {
            // undamped resonance: trapezoid (rare; the balance check will show its error)
            input = 0.5 * h * ((al * tm.s0 + be * tm.c0) * v0 + (al * tm.s1 + be * tm.c1) * v1);
        }
    } else {
        i0 = (int_f - (v1 - v0) - d * (e1 - e0)) * iw2;
    }
    let contact = (g0 + g1) * e1 - g0 * e0 - slope * i0;
    ModeWork {
        input,
        contact,
        damping: input + contact - de,
    }
}

/// The exact ground work of all modes over a step without contact load, for harmonic motion, as
/// linear forms in the modal state: [`mode_work`]'s per-mode formula summed over the modes with
/// the per-mode constants gathered, so a step costs four dot products instead of a 2×2 solve per
/// mode. `input = K_ss·∫sin² + K_sc·∫sin cos + K_cc·∫cos² + [sin·U + cos·V]_{t₀}^{t₁}` with
/// `U = Σ κ1 η + κ3 η̇`, `V = Σ κ2 η + κ4 η̇`.
#[derive(Debug, Clone)]
pub struct HarmonicTally {
    kappa: Vec<[f64; 6]>,
    k: [f64; 3],
}

/// Sums of the modal state carried from step to step by [`HarmonicTally`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StateSums {
    /// Σ κ1 η + κ3 η̇.
    pub u: f64,
    /// Σ κ2 η + κ4 η̇.
    pub v: f64,
    /// Modal energy Σ ½(η̇² + ω²η²), J.
    pub energy: f64,
}

impl HarmonicTally {
    /// For harmonic motion without an undamped resonant mode (else `None`: use [`mode_work`]).
    pub fn new(gm: &GroundModes) -> Option<HarmonicTally> {
        let big = gm.harmonic_omega()?;
        let mut kappa = Vec::with_capacity(gm.len());
        let mut k = [0.0; 3];
        for j in 0..gm.len() {
            let [a, b, m, n, q] = gm.hcoef[j];
            if q == 0.0 {
                return None;
            }
            let d = gm.damp[j];
            let p1 = q * (b * m + a * n);
            let p2 = q * (b * n - a * m);
            k[0] += big * p1 * a;
            k[1] += big * (p1 * b + p2 * a);
            k[2] += big * p2 * b;
            kappa.push([
                a - big * (d * p1 + big * p2),
                b + big * (big * p1 - d * p2),
                -big * p1,
                -big * p2,
                big * p1,
                big * p2,
            ]);
        }
        Some(HarmonicTally { kappa, k })
    }

    /// Contribution of mode j with state (η, η̇) and ω² to the sums.
    #[inline(always)]
    pub fn add(&self, sums: &mut StateSums, j: usize, w2: f64, e: f64, v: f64) {
        let k = &self.kappa[j];
        sums.u += k[0] * e + k[2] * v;
        sums.v += k[1] * e + k[3] * v;
        sums.energy += 0.5 * (v * v + w2 * e * e);
    }

    /// Extra ground work of mode j over the step when it also carries the contact load
    /// `g0 + slope·τ` (the load changes the mode's motion, hence the ground's work), and the
    /// exact work of that contact load; `y0`, `y1` are the mode's end states. The per-mode form:
    /// `exact-modal` uses its sum regrouped by level, [`ContactForms`], tested against it.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn with_contact(
        &self,
        gm: &GroundModes,
        j: usize,
        tm: &TrigMoments,
        h: f64,
        y0: (f64, f64),
        y1: (f64, f64),
        g0: f64,
        slope: f64,
    ) -> (f64, f64) {
        let k = &self.kappa[j];
        let extra = k[4] * (g0 * tm.s + slope * tm.ts) + k[5] * (g0 * tm.c + slope * tm.tc);
        let [a, b, ..] = gm.hcoef[j];
        let int_f = a * tm.s + b * tm.c + h * (g0 + 0.5 * slope * h);
        let i0 = (int_f - (y1.1 - y0.1) - gm.damp[j] * (y1.0 - y0.0)) * gm.inv_w2[j];
        let contact = (g0 + slope * h) * y1.0 - g0 * y0.0 - slope * i0;
        (extra, contact)
    }

    /// The coefficients of the extra ground work that a load along `row` (one contact level's
    /// coupling) causes: `(Σ_j row_j κ4_j, Σ_j row_j κ5_j)`. A load `f(τ)` along the row adds
    /// `K4·∫f sin Ωt dt + K5·∫f cos Ωt dt` to the ground's work over a step (the sum over the
    /// modes of [`Self::with_contact`]'s extra term, for any load shape).
    pub fn row_extra(&self, row: &[f64]) -> (f64, f64) {
        self.kappa
            .iter()
            .zip(row)
            .fold((0.0, 0.0), |(a, b), (k, r)| (a + r * k[4], b + r * k[5]))
    }

    /// Ground work over the step [t₀, t₁] from the sums at both ends.
    #[inline]
    pub fn input(&self, tm: &TrigMoments, s0: &StateSums, s1: &StateSums) -> f64 {
        self.k[0] * tm.ss + self.k[1] * tm.sc + self.k[2] * tm.cc + tm.s1 * s1.u + tm.c1 * s1.v
            - tm.s0 * s0.u
            - tm.c0 * s0.v
    }
}

/// Per-level sums of one (sub-)step for [`ContactForms::tallies`].
#[derive(Debug, Clone, Copy, Default)]
pub struct LevelStep {
    /// Contact force at the step start F₀, N.
    pub f0: f64,
    /// Change of the (linearly varying) contact force over the step, N.
    pub df: f64,
    /// `c_k·η` at the start and at the end.
    pub cq0: f64,
    /// See `cq0`.
    pub cq1: f64,
    /// `Σ_j (c_kj/ω_j²) Δη̇_j` over the step.
    pub sv: f64,
    /// `Σ_j (c_kj 2ζ_jω_j/ω_j²) Δη_j` over the step.
    pub se: f64,
}

/// [`HarmonicTally::with_contact`] summed over the modes and regrouped by contact level: the
/// mode sums of the constants are taken once, so a step with contact costs two multiply–adds
/// per mode and level (the `sv`, `se` sums of [`LevelStep`]) instead of the per-mode formula.
#[derive(Debug, Clone)]
pub struct ContactForms {
    nl: usize,
    /// Per level: `Σ_j c_kj κ4_j`, `Σ_j c_kj κ5_j`, `Σ_j c_kj α_j/ω_j²`, `Σ_j c_kj β_j/ω_j²`.
    level: Vec<[f64; 4]>,
    /// `W_kl = Σ_j c_kj c_lj/ω_j²`.
    w: Vec<f64>,
    /// `(c_kj/ω_j², c_kj 2ζ_jω_j/ω_j²)` at `[j·L + k]`.
    pub weights: Vec<(f64, f64)>,
}

impl ContactForms {
    /// From the coupling rows transposed, mode-major (`cpl_t[j·L + k] = c_kj`), L levels.
    pub fn new(ht: &HarmonicTally, gm: &GroundModes, cpl_t: &[f64], nl: usize) -> ContactForms {
        let n = gm.len();
        let mut level = vec![[0.0; 4]; nl];
        let mut w = vec![0.0; nl * nl];
        let mut weights = vec![(0.0, 0.0); n * nl];
        for j in 0..n {
            let (k4, k5) = (ht.kappa[j][4], ht.kappa[j][5]);
            let [a, b, ..] = gm.hcoef[j];
            let iw2 = gm.inv_w2[j];
            for k in 0..nl {
                let c = cpl_t[j * nl + k];
                level[k][0] += c * k4;
                level[k][1] += c * k5;
                level[k][2] += c * a * iw2;
                level[k][3] += c * b * iw2;
                for l in 0..nl {
                    w[k * nl + l] += c * cpl_t[j * nl + l] * iw2;
                }
                weights[j * nl + k] = (c * iw2, c * gm.damp[j] * iw2);
            }
        }
        ContactForms {
            nl,
            level,
            w,
            weights,
        }
    }

    /// The extra ground work and the work of the contact load over the step (the sums over
    /// the modes of [`HarmonicTally::with_contact`]), J.
    #[inline]
    pub fn tallies(&self, tm: &TrigMoments, h: f64, steps: &[LevelStep]) -> (f64, f64) {
        let nl = self.nl;
        let (mut extra, mut contact) = (0.0, 0.0);
        for k in 0..nl {
            let st = &steps[k];
            let [k4, k5, a, b] = self.level[k];
            let r = st.df / h;
            extra += st.f0 * (k4 * tm.s + k5 * tm.c) + r * (k4 * tm.ts + k5 * tm.tc);
            // Σ_j c_kj ∫η dt over the step, from the equation of motion
            let mut load = 0.0;
            for l in 0..nl {
                load += (st_f(steps, l) * h) * self.w[k * nl + l];
            }
            let i0 = a * tm.s + b * tm.c + load - st.sv - st.se;
            contact += (st.f0 + st.df) * st.cq1 - st.f0 * st.cq0 - r * i0;
        }
        (extra, contact)
    }
}

/// `F₀ + ΔF/2` of level l: the mean of its linearly varying force over the step.
#[inline(always)]
fn st_f(steps: &[LevelStep], l: usize) -> f64 {
    steps[l].f0 + 0.5 * steps[l].df
}
