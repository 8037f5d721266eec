//! The exact ground work of a recorded motion over a free step, summed over the modes and
//! regrouped (as [`super::linear::HarmonicTally`] does for harmonic motion): a step costs a few
//! multiply–adds per mode (sums of the state carried from step to step) instead of
//! [`super::linear::poly_ground_work`]'s per-mode formula.
//!
//! Over a step of length h a mode's ground load is `c0 + c1τ + c2τ²` with
//! `c0 = la·a_g + lv·v_g`, `c1 = la·a1 + lv·a_g`, `c2 = ½lv·a1` (`a_g`, `v_g` the ground's
//! acceleration and velocity at the step's start, `a1` the acceleration's slope: the same for
//! every mode), and its work is `[cη] − c1∫η − 2c2∫τη` with the moments of η from the equation
//! of motion (`poly_ground_work` with no contact load). Expanded, that is a sum of terms each
//! the product of a ground factor (shared), a mode constant and the mode's state: the state
//! enters through six weighted sums ([`PolySums`]), the rest through six sums of mode
//! constants taken once.

/// Sums over the modes of the state `(η, η̇)`, weighted by mode constants (see the module).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PolySums {
    /// Σ la η.
    a1: f64,
    /// Σ lv η.
    a2: f64,
    /// Σ la/ω² (η̇ + 2ζω η).
    b1: f64,
    /// Σ lv/ω² (η̇ + 2ζω η).
    b2: f64,
    /// Σ lv/ω² η.
    c1: f64,
    /// Σ lv 2ζω/ω⁴ (η̇ + 2ζω η).
    c3: f64,
}

impl PolySums {
    /// Add a mode with weights `w` (la, lv, la/ω², lv/ω², lv·2ζω/ω⁴, 2ζω) and state (η, η̇).
    #[inline(always)]
    fn add(&mut self, w: &[f64; 6], e: f64, v: f64) {
        let [la, lv, lai, lvi, lvd, d] = *w;
        let u = v + d * e;
        self.a1 += la * e;
        self.a2 += lv * e;
        self.b1 += lai * u;
        self.b2 += lvi * u;
        self.c1 += lvi * e;
        self.c3 += lvd * u;
    }
}

impl PolySums {
    /// The sums from their parts in the order (Σ la η, Σ lv η, Σ la/ω² D, Σ lv/ω² D, Σ lv/ω² η,
    /// Σ lv 2ζω/ω⁴ D), D = η̇ + 2ζωη: what a pass over the modes with the weights of
    /// [`PolyTally::new`] (la, lv, la/ω², lv/ω², lv·2ζω/ω⁴, 2ζω) accumulated.
    pub fn from_parts([a1, a2, b1, b2, c1, c3]: [f64; 6]) -> PolySums {
        PolySums {
            a1,
            a2,
            b1,
            b2,
            c1,
            c3,
        }
    }
}

/// Per-mode weights and mode-constant sums of the regrouped ground work.
#[derive(Debug, Clone)]
pub struct PolyTally {
    /// Per mode: la, lv, la/ω², lv/ω², lv·2ζω/ω⁴, 2ζω.
    w: Vec<[f64; 6]>,
    /// Σ la²/ω², Σ la·lv/ω², Σ lv²/ω², and the same with the extra factor 2ζω/ω².
    s: [f64; 3],
    t: [f64; 3],
}

impl PolyTally {
    /// From each mode's `la`, `lv` (load coefficients of a_g and v_g), `damp` (2ζω) and `1/ω²`.
    pub fn new(la: &[f64], lv: &[f64], damp: &[f64], inv_w2: &[f64]) -> PolyTally {
        let mut s = [0.0; 3];
        let mut t = [0.0; 3];
        let w = (0..la.len())
            .map(|j| {
                let (a, b, d, i) = (la[j], lv[j], damp[j], inv_w2[j]);
                for (k, p) in [a * a, a * b, b * b].into_iter().enumerate() {
                    s[k] += p * i;
                    t[k] += p * i * i * d;
                }
                [a, b, a * i, b * i, b * i * i * d, d]
            })
            .collect();
        PolyTally { w, s, t }
    }

    /// Contribution of mode j with state (η, η̇) to the sums.
    #[inline(always)]
    pub fn add(&self, sums: &mut PolySums, j: usize, e: f64, v: f64) {
        sums.add(&self.w[j], e, v);
    }

    /// The sums at the modal state (q, v).
    pub fn sums(&self, q: &[f64], v: &[f64]) -> PolySums {
        let mut s = PolySums::default();
        for j in 0..self.w.len() {
            self.add(&mut s, j, q[j], v[j]);
        }
        s
    }

    /// The ground's work over a free step of length h (ground acceleration `ag`, velocity
    /// `vg` at its start, acceleration slope `a1`) from the sums at its start and end, J.
    /// (Inlined, so that the free flight's commit compiled for AVX has it in its VEX form.)
    #[inline(always)]
    pub fn input(
        &self,
        h: f64,
        (ag, vg, a1): (f64, f64, f64),
        s0: &PolySums,
        s1: &PolySums,
    ) -> f64 {
        const THIRD: f64 = 1.0 / 3.0;
        // the state's part: Σ c0Δη + h(c1 + h c2)η₁ + c1/ω² ΔD − 2c2/ω² (−h D₁ + Δη − 2ζω/ω² ΔD),
        // D = η̇ + 2ζωη
        let state = ag * (s1.a1 - s0.a1)
            + vg * (s1.a2 - s0.a2)
            + h * (a1 * s1.a1 + ag * s1.a2)
            + 0.5 * h * h * a1 * s1.a2
            + a1 * (s1.b1 - s0.b1)
            + ag * (s1.b2 - s0.b2)
            - a1 * (-h * s1.b2 + (s1.c1 - s0.c1) - (s1.c3 - s0.c3));
        // the loads' part: −Σ c1/ω² ∫f − 2Σ c2/ω² (∫τf + 2ζω/ω² ∫f), ∫f = h c0 + h²/2 c1 +
        // h³/3 c2, ∫τf = h²/2 c0 + h³/3 c1 + h⁴/4 c2; c_a = la α_a + lv β_a
        let (al, be) = ([ag, a1, 0.0], [vg, ag, 0.5 * a1]);
        let pair = |m: &[f64; 3], a: usize, b: usize| {
            al[a] * al[b] * m[0] + (al[a] * be[b] + be[a] * al[b]) * m[1] + be[a] * be[b] * m[2]
        };
        let (h2, h3) = (h * h, h * h * h);
        let int_f = |m: &[f64; 3], a: usize| {
            h * pair(m, a, 0) + 0.5 * h2 * pair(m, a, 1) + h3 * THIRD * pair(m, a, 2)
        };
        let int_tf = |m: &[f64; 3], a: usize| {
            0.5 * h2 * pair(m, a, 0) + h3 * THIRD * pair(m, a, 1) + 0.25 * h2 * h2 * pair(m, a, 2)
        };
        let loads = -int_f(&self.s, 1) - 2.0 * (int_tf(&self.s, 2) + int_f(&self.t, 2));
        state + loads
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::linear::{poly_coefficients, poly_ground_work, propagator};

    /// The regrouped work equals the per-mode formula summed over the modes, on exact free
    /// steps of modes from stiff to soft, damped and not, with every ground term present.
    #[test]
    fn regrouped_work_equals_the_per_mode_sum() {
        let omega = [2.0, 9.5, 31.0, 140.0, 800.0];
        let zeta = [0.0, 0.02, 0.05, 0.3, 0.01];
        let la = [-1200.0, 310.0, -95.0, 40.0, -7.0];
        let lv = [3.0, -0.4, 11.0, -2.5, 0.8];
        let damp: Vec<f64> = omega.iter().zip(&zeta).map(|(w, z)| 2.0 * z * w).collect();
        let inv_w2: Vec<f64> = omega.iter().map(|w| 1.0 / (w * w)).collect();
        let pt = PolyTally::new(&la, &lv, &damp, &inv_w2);
        let (q0, v0) = (
            [0.01, -0.002, 3e-4, 1e-5, -2e-7],
            [0.05, 0.03, -0.01, 2e-3, 1e-4],
        );
        for &(h, ag, vg, a1) in &[
            (0.005, 1.7, -0.3, 40.0),
            (0.02, -3.0, 0.8, -5.0),
            (1e-4, 0.2, 0.01, 900.0),
        ] {
            let (mut q1, mut v1) = ([0.0; 5], [0.0; 5]);
            let mut want = 0.0;
            let mut scale = 0.0f64;
            for j in 0..5 {
                let c = [
                    la[j] * ag + lv[j] * vg,
                    la[j] * a1 + lv[j] * ag,
                    0.5 * lv[j] * a1,
                ];
                let (pa, pb, pc) = poly_coefficients(inv_w2[j], damp[j], &c);
                let p = propagator(omega[j], damp[j], h);
                let (x, y) = p.apply(q0[j] - pa, v0[j] - pb);
                q1[j] = x + pa + h * (pb + h * pc);
                v1[j] = y + pb + 2.0 * h * pc;
                let w = poly_ground_work(
                    (damp[j], inv_w2[j]),
                    h,
                    (q0[j], v0[j]),
                    (q1[j], v1[j]),
                    &c,
                    0.0,
                    0.0,
                );
                want += w;
                let cabs = c[0].abs() + h * c[1].abs() + h * h * c[2].abs();
                scale += cabs * (q0[j].abs() + q1[j].abs());
            }
            let got = pt.input(h, (ag, vg, a1), &pt.sums(&q0, &v0), &pt.sums(&q1, &v1));
            // (the same sums in another order, with differences of sums over the step for
            // sums of differences: round-off of the ground force × displacement's size, which
            // over a short step is far above the step's work; measured 7e-13 of it at h 1e-4)
            assert!(
                (got - want).abs() <= 1e-11 * scale,
                "h {h}: {got} vs {want}"
            );
        }
    }
}
