//! The free flight's per-mode passes ([`super::Elastic::free_prop`]): the harmonic motion's,
//! and a recorded motion's as one precomputed affine map per mode and step length
//! ([`PolyMap`]) done two modes at a time.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::*;
use crate::numerics::lanes::F2;

/// The harmonic particular solution `Im[G e^{iΩt}]` of every mode at a free step's ends.
pub(super) struct HarmonicWave<'g> {
    pub(super) big: f64,
    pub(super) g_re: &'g [f64],
    pub(super) g_im: &'g [f64],
    pub(super) tr0: Trig,
    pub(super) tr1: Trig,
}

/// The free flight of every mode under harmonic motion: (q, v) → `out` = (qb, vb, amp), the
/// Hermite margin in `amp` when `MARGIN` (else 0), `tally(j, η, η̇)` at each mode's end state.
#[inline(always)]
pub(super) fn harmonic_pass<const MARGIN: bool>(
    hw: &HarmonicWave,
    props: &[Prop],
    (herm, hp): (&[(f64, f64)], f64),
    q: &[f64],
    v: &[f64],
    (qb, vb, amp): (&mut [f64], &mut [f64], &mut [f64]),
    mut tally: impl FnMut(usize, f64, f64),
) {
    let n = qb.len();
    let (props, herm, q, v) = (&props[..n], &herm[..n], &q[..n], &v[..n]);
    let (g_re, g_im, vb, amp) = (&hw.g_re[..n], &hw.g_im[..n], &mut vb[..n], &mut amp[..n]);
    let (big, tr0, tr1) = (hw.big, hw.tr0, hw.tr1);
    for j in 0..n {
        let (gr, gi) = (g_re[j], g_im[j]);
        let (e0, d0) = (gr * tr0.s + gi * tr0.c, big * (gr * tr0.c - gi * tr0.s));
        let (e1, d1) = (gr * tr1.s + gi * tr1.c, big * (gr * tr1.c - gi * tr1.s));
        let (x0, y0) = (q[j] - e0, v[j] - d0);
        let (x, y) = props[j].apply(x0, y0);
        let (x, y) = (x + e1, y + d1);
        qb[j] = x;
        vb[j] = y;
        amp[j] = if MARGIN {
            herm[j].0 * x0.abs() + herm[j].1 * y0.abs() + hp * (gr.abs() + gi.abs())
        } else {
            0.0
        };
        tally(j, x, y);
    }
}

/// A free step of length h under a recorded motion as one affine map per mode. The mode's
/// load over the step is `c0 + c1τ + c2τ²` with `c0 = la·a_g + lv·v_g`, `c1 = la·a1 + lv·a_g`,
/// `c2 = ½lv·a1` (a_g, v_g the ground's acceleration and velocity at the step's start, a1 the
/// acceleration's slope), its particular solution `A + Bτ + Cτ²` ([`poly_coefficients`], linear
/// in (a_g, v_g, a1)), and the exact step `(η', η̇') = P(h)·(η − A, η̇ − B) + (A + Bh + Ch²,
/// B + 2Ch)` regrouped as
///
/// `η' = p11 η + p12 η̇ + qa a_g + qv v_g + q1 a1`, `η̇' = p21 η + p22 η̇ + va a_g + vv v_g + v1 a1`:
///
/// ten multiply–adds per mode instead of the particular solution's coefficients, the
/// subtraction and the propagator at every step (the same algebra: only the rounding moves).
/// The particular solution's start values `A = aa a_g + av v_g + a1 a1`, `B = ba a_g + b1 a1`
/// give the Hermite margin, which needs the homogeneous part's size.
///
/// Stored two modes at a time, every coefficient of both side by side (`pairs[i][c]` = the
/// coefficient c of modes 2i and 2i + 1; a missing last odd mode has zeros): one pass reads a
/// single array and does both modes as one vector operation.
///
/// It also keeps what bounds the contact test's margins without a pass over the modes
/// ([`PolyMap::margin_bounds`]): every level's gain over the margins' factors and the
/// particular solution's size per unit of each ground factor.
#[derive(Debug, Clone)]
pub(super) struct PolyMap {
    /// (as [`F2`], 16-byte aligned: each coefficient pair is an operand of its vector
    /// multiplication straight from memory, without a load of its own)
    pairs: Vec<[F2; COEFS]>,
    /// The same coefficients four modes at a time (`quads[i].0[c]` = the coefficient c of
    /// modes 4i … 4i + 3), for the pass in 256-bit registers where the processor has AVX
    /// ([`poly_pass`]); empty without AVX, off x86-64 and below four modes.
    quads: Vec<Quad>,
    /// Per contact level k, `G_k = √(Σ_j c_kj² (H0_j²/ω_j² + H1_j²))` (∞ where a mode with
    /// ω = 0 has a margin): empty until [`PolyMap::set_gains`].
    gain: Vec<f64>,
    /// The particular solution's start `(ωA, B)` in the norm `√Σ_j (ω_j² x_j² + y_j²)`, per
    /// unit of |a_g|, |v_g| and |a1|.
    part: [f64; 3],
}

/// The coefficients of a mode in [`PolyMap`]: the map, the ground-work weights of
/// [`PolyTally`] (la, lv, la/ω², lv/ω², lv·2ζω/ω⁴, 2ζω), ω², the particular solution's start
/// and the Hermite margin's factors ([`FreeData::herm`]).
const P11: usize = 0;
const P12: usize = 1;
const P21: usize = 2;
const P22: usize = 3;
const QA: usize = 4;
const QV: usize = 5;
const Q1: usize = 6;
const VA: usize = 7;
const VV: usize = 8;
const V1: usize = 9;
const LA: usize = 10;
const LV: usize = 11;
const LAI: usize = 12;
const LVI: usize = 13;
const LVD: usize = 14;
const DD: usize = 15;
const W2: usize = 16;
const AA: usize = 17;
const AV: usize = 18;
const A1: usize = 19;
const BA: usize = 20;
const B1: usize = 21;
const H0: usize = 22;
const H1: usize = 23;
const COEFS: usize = 24;

/// Every coefficient of four modes side by side (32-byte aligned: each is one AVX operand
/// straight from memory).
#[derive(Debug, Clone)]
#[repr(align(32))]
struct Quad([[f64; 4]; COEFS]);

/// Every mode's load coefficients `la` (of a_g, kg^½) and `lv` (of v_g, kg^½/s), `damp` (2ζω,
/// 1/s), `w2` (ω², 1/s²) and `inv_w2` (1/ω², s²), as [`GroundModes`] has them.
#[derive(Debug, Clone, Copy)]
pub(super) struct ModeLoads<'a> {
    pub(super) la: &'a [f64],
    pub(super) lv: &'a [f64],
    pub(super) damp: &'a [f64],
    pub(super) w2: &'a [f64],
    pub(super) inv_w2: &'a [f64],
}

impl PolyMap {
    /// From the modes' load coefficients `la` (of a_g, kg^½) and `lv` (of v_g, kg^½/s), `damp`
    /// (2ζω, 1/s), `w2` (ω², 1/s²), `inv_w2` (1/ω², s²), their propagators over the step h (s)
    /// and Hermite margin factors `herm`.
    pub(super) fn new(
        ModeLoads {
            la,
            lv,
            damp,
            w2,
            inv_w2,
        }: ModeLoads,
        props: &[Prop],
        herm: &[(f64, f64)],
        h: f64,
    ) -> PolyMap {
        let n = props.len();
        let mut cols = vec![[[0.0; 2]; COEFS]; n.div_ceil(2)];
        let mut part = [0.0; 3];
        for j in 0..n {
            let (la, lv, d, i) = (la[j], lv[j], damp[j], inv_w2[j]);
            // poly_coefficients with c = (la a_g + lv v_g, la a1 + lv a_g, ½lv a1), per factor
            let cc = 0.5 * lv * i;
            let (ba, b1) = (lv * i, (la - 2.0 * d * cc) * i);
            let (aa, av, a1) = ((la - d * ba) * i, lv * i, (-d * b1 - 2.0 * cc) * i);
            let p = &props[j];
            let (p11, p12, p21, p22) = (p.p11, p.p12, p.p21, p.p22);
            // η' − Pη = (1 − p11)A + (h − p12)B + h²C, η̇' − Pη̇ = −p21 A + (1 − p22)B + 2hC
            let (u, w, z) = (1.0 - p11, h - p12, 1.0 - p22);
            let mut c = [0.0; COEFS];
            c[P11] = p11;
            c[P12] = p12;
            c[P21] = p21;
            c[P22] = p22;
            c[QA] = u * aa + w * ba;
            c[QV] = u * av;
            c[Q1] = u * a1 + w * b1 + h * h * cc;
            c[VA] = -p21 * aa + z * ba;
            c[VV] = -p21 * av;
            c[V1] = -p21 * a1 + z * b1 + 2.0 * h * cc;
            // (PolyTally's weights, in its order)
            c[LA] = la;
            c[LV] = lv;
            c[LAI] = la * i;
            c[LVI] = lv * i;
            c[LVD] = lv * i * i * d;
            c[DD] = d;
            c[W2] = w2[j];
            c[AA] = aa;
            c[AV] = av;
            c[A1] = a1;
            c[BA] = ba;
            c[B1] = b1;
            c[H0] = herm[j].0;
            c[H1] = herm[j].1;
            // A = aa a_g + av v_g + a1 a1, B = ba a_g + b1 a1
            part[0] += w2[j] * aa * aa + ba * ba;
            part[1] += w2[j] * av * av;
            part[2] += w2[j] * a1 * a1 + b1 * b1;
            for (k, x) in c.into_iter().enumerate() {
                cols[j / 2][k][j % 2] = x;
            }
        }
        let pairs = cols.iter().map(|c| c.map(|x| F2::load(&x))).collect();
        let quads = if crate::numerics::vex::available() {
            (0..n / 4)
                .map(|i| {
                    Quad(std::array::from_fn(|k| {
                        std::array::from_fn(|l| cols[2 * i + l / 2][k][l % 2])
                    }))
                })
                .collect()
        } else {
            Vec::new()
        };
        PolyMap {
            pairs,
            quads,
            gain: Vec::new(),
            part: part.map(f64::sqrt),
        }
    }

    /// Every contact level's gain `G_k` from its coupling row `c_k` (`rows`, one per level).
    pub(super) fn set_gains<'c>(&mut self, rows: impl Iterator<Item = &'c [f64]>) {
        let gain = rows.map(|c| {
            let mut s = 0.0;
            for (j, &ckj) in c.iter().enumerate() {
                let m = &self.pairs[j / 2];
                let c = |i: usize| m[i].get()[j % 2];
                let (h0, h1, w2) = (c(H0), c(H1), c(W2));
                if ckj == 0.0 || (h0 == 0.0 && h1 == 0.0) {
                    continue;
                }
                let x = if h0 == 0.0 { 0.0 } else { h0 * h0 / w2 };
                s += ckj * ckj * (x + h1 * h1);
            }
            // (NaN, from ω² ≤ 0, is no bound either)
            if s.is_finite() {
                s.sqrt()
            } else {
                f64::INFINITY
            }
        });
        self.gain = gain.collect();
    }

    /// An upper bound of every level's contact-test margin `Σ_j |c_kj| (H0_j |η_j − A_j| +
    /// H1_j |η̇_j − B_j|)` (what a pass with margins gives, [`poly_pass`] `MARGIN`) into `out`,
    /// from the start state's `s0 = Σ_j η̇_j² + ω_j² η_j²` and the ground factors `g` alone,
    /// without a pass over the modes: with x = η − A, y = η̇ − B, Cauchy–Schwarz gives
    /// `Σ_j (|c_kj| H0_j/ω_j)(ω_j|x_j|) + (|c_kj| H1_j)|y_j| ≤ G_k ‖(x, y)‖`, and Minkowski
    /// `‖(x, y)‖ ≤ √s0 + ‖(A, B)‖ ≤ √s0 + |a_g|‖·‖_a + |v_g|‖·‖_v + |a1|‖·‖_1` (the particular
    /// solution is linear in the factors). The rounding of both sides is a few ulps of sums of
    /// positive terms (the margin's |η − A| too is at most |η| + |A| rounded): the factor
    /// 1 + 1e-9 covers it. ∞ where [`PolyMap::set_gains`] has not run.
    pub(super) fn margin_bounds(&self, (ag, vg, a1): (f64, f64, f64), s0: f64, out: &mut [f64]) {
        let [na, nv, n1] = self.part;
        let r = (s0.sqrt() + (na * ag.abs() + nv * vg.abs() + n1 * a1.abs())) * (1.0 + 1e-9);
        for (k, o) in out.iter_mut().enumerate() {
            // (∞ · 0 is no bound: NaN reads as "may touch", which the margins then decide)
            let b = self.gain.get(k).map_or(f64::INFINITY, |g| g * r);
            *o = if b.is_nan() { f64::INFINITY } else { b };
        }
    }

    /// Mode j's end state from (η, η̇) under the ground factors `g` = (a_g, v_g, a1).
    #[cfg(test)]
    pub(super) fn step(
        &self,
        j: usize,
        (ag, vg, a1): (f64, f64, f64),
        e: f64,
        v: f64,
    ) -> (f64, f64) {
        let c = |k: usize| self.pairs[j / 2][k].get()[j % 2];
        (
            c(P11) * e + c(P12) * v + (c(QA) * ag + c(QV) * vg + c(Q1) * a1),
            c(P21) * e + c(P22) * v + (c(VA) * ag + c(VV) * vg + c(V1) * a1),
        )
    }
}

/// The free flight of every mode under a recorded motion's piece (ground factors `g`):
/// (q, v) → (qb, vb) in `out`, and each mode's Hermite margin in its `amp` when `MARGIN`
/// (untouched without: nothing reads it before a pass with margins or [`poly_margins`]
/// writes it). Returns the end state's ground-work sums and `Σ η̇² + ω²η²` (twice the modal
/// energy), each summed in two lanes (even and odd modes, added at the end). The start
/// state's same sum, which [`PolyMap::margin_bounds`] needs, is the previous pass's end sum
/// (or [`start_energy2`]): not formed again here.
pub(super) fn poly_pass<const MARGIN: bool>(
    m: &PolyMap,
    g: (f64, f64, f64),
    q: &[f64],
    v: &[f64],
    out: (&mut [f64], &mut [f64], &mut [f64]),
) -> (PolySums, f64) {
    #[cfg(target_arch = "x86_64")]
    if !m.quads.is_empty() {
        // SAFETY: `quads` is formed only where the processor has AVX (`PolyMap::new`)
        return unsafe { wide::poly_pass_avx::<MARGIN>(m, g, q, v, out) };
    }
    pass_pairs::<MARGIN>(m, g, q, v, out, 0, [F2::zero(); 7])
}

/// [`poly_pass`] two modes at a time from the pair `from` on (modes 2·from …), onto the
/// partial sums `acc` of the modes before it (even modes in lane 0, odd in lane 1).
#[inline(always)]
fn pass_pairs<const MARGIN: bool>(
    m: &PolyMap,
    (ag, vg, a1): (f64, f64, f64),
    q: &[f64],
    v: &[f64],
    (qb, vb, amp): (&mut [f64], &mut [f64], &mut [f64]),
    from: usize,
    mut acc: [F2; 7],
) -> (PolySums, f64) {
    let n = qb.len();
    // per lane: Σ la η, Σ lv η, Σ la/ω² D, Σ lv/ω² D, Σ lv/ω² η, Σ lv 2ζω/ω⁴ D (D = η̇ + 2ζωη),
    // Σ η̇² + ω²η² at the end
    let g = (F2::splat(ag), F2::splat(vg), F2::splat(a1));
    let (qp, _) = q[..n].as_chunks::<2>();
    let (vp, _) = v[..n].as_chunks::<2>();
    let (xp, _) = qb.as_chunks_mut::<2>();
    let (yp, _) = vb[..n].as_chunks_mut::<2>();
    let full = qp.len();
    let from = from.min(full);
    let rows = m.pairs[from..full]
        .iter()
        .zip(qp[from..].iter().zip(&vp[from..]));
    let (xp, yp) = (&mut xp[from..], &mut yp[from..]);
    if MARGIN {
        let (ap, _) = amp[..n].as_chunks_mut::<2>();
        let ap = &mut ap[from..];
        for ((c, (qj, vj)), (xb, (yb, ab))) in rows.zip(xp.iter_mut().zip(yp.iter_mut().zip(ap))) {
            let (x, y, a) = pair::<true>(c, g, F2::load(qj), F2::load(vj), &mut acc);
            (*xb, *yb, *ab) = (x.get(), y.get(), a.get());
        }
    } else {
        for ((c, (qj, vj)), (xb, yb)) in rows.zip(xp.iter_mut().zip(yp.iter_mut())) {
            let (x, y, _) = pair::<false>(c, g, F2::load(qj), F2::load(vj), &mut acc);
            (*xb, *yb) = (x.get(), y.get());
        }
    }
    if n % 2 == 1 {
        // the last odd mode in lane 0 (lane 1's coefficients are zeros: it adds nothing)
        let j = n - 1;
        let (x, y, a) = pair::<MARGIN>(
            &m.pairs[full],
            g,
            F2::new(q[j], 0.0),
            F2::new(v[j], 0.0),
            &mut acc,
        );
        (qb[j], vb[j]) = (x.get()[0], y.get()[0]);
        if MARGIN {
            amp[j] = a.get()[0];
        }
    }
    let acc = acc.map(F2::get);
    let sum = |k: usize| acc[k][0] + acc[k][1];
    let ps = PolySums::from_parts([sum(0), sum(1), sum(2), sum(3), sum(4), sum(5)]);
    (ps, sum(6))
}

/// [`poly_pass`] four modes at a time in AVX's 256-bit registers: every lane does its mode's
/// operations of [`pair`] in the same order, and each sum takes the quad's two pairs one
/// after the other (its low half, then its high half, onto the two-lane partial sums), in
/// the order of the two-lane pass: the same bits. The modes past the last full quad go on
/// two at a time ([`pass_pairs`]).
#[cfg(target_arch = "x86_64")]
mod wide {
    use super::*;
    use std::arch::x86_64::{
        __m128d, _mm_add_pd, _mm_setzero_pd, _mm_storeu_pd, _mm256_add_pd, _mm256_andnot_pd,
        _mm256_castpd256_pd128, _mm256_extractf128_pd, _mm256_load_pd, _mm256_loadu_pd,
        _mm256_mul_pd, _mm256_set1_pd, _mm256_setzero_pd, _mm256_storeu_pd, _mm256_sub_pd,
    };

    /// See the module. Safety: the processor has AVX.
    #[target_feature(enable = "avx")]
    pub(super) unsafe fn poly_pass_avx<const MARGIN: bool>(
        m: &PolyMap,
        g: (f64, f64, f64),
        q: &[f64],
        v: &[f64],
        (qb, vb, amp): (&mut [f64], &mut [f64], &mut [f64]),
    ) -> (PolySums, f64) {
        let n = qb.len();
        let (ga, gv, g1) = (
            _mm256_set1_pd(g.0),
            _mm256_set1_pd(g.1),
            _mm256_set1_pd(g.2),
        );
        let sign = _mm256_set1_pd(-0.0);
        let mut acc: [__m128d; 7] = [_mm_setzero_pd(); 7];
        let (qc, _) = q[..n].as_chunks::<4>();
        let (vc, _) = v[..n].as_chunks::<4>();
        let (xc, _) = qb.as_chunks_mut::<4>();
        let (yc, _) = vb[..n].as_chunks_mut::<4>();
        let nq = qc.len().min(m.quads.len());
        // (macros, not closures: every operation inlined in this function, with its AVX)
        macro_rules! mul {
            ($a:expr, $b:expr) => {
                _mm256_mul_pd($a, $b)
            };
        }
        macro_rules! add {
            ($a:expr, $b:expr) => {
                _mm256_add_pd($a, $b)
            };
        }
        macro_rules! abs {
            ($a:expr) => {
                _mm256_andnot_pd(sign, $a)
            };
        }
        for i in 0..nq {
            let c = &m.quads[i].0;
            // SAFETY: AVX (the caller); `Quad` is 32-byte aligned and every chunk holds four
            // values
            macro_rules! k {
                ($j:expr) => {
                    unsafe { _mm256_load_pd(c[$j].as_ptr()) }
                };
            }
            let (qj, vj) = unsafe {
                (
                    _mm256_loadu_pd(qc[i].as_ptr()),
                    _mm256_loadu_pd(vc[i].as_ptr()),
                )
            };
            let x = add!(
                add!(mul!(k!(P11), qj), mul!(k!(P12), vj)),
                add!(add!(mul!(k!(QA), ga), mul!(k!(QV), gv)), mul!(k!(Q1), g1))
            );
            let y = add!(
                add!(mul!(k!(P21), qj), mul!(k!(P22), vj)),
                add!(add!(mul!(k!(VA), ga), mul!(k!(VV), gv)), mul!(k!(V1), g1))
            );
            if MARGIN {
                let pa = add!(add!(mul!(k!(AA), ga), mul!(k!(AV), gv)), mul!(k!(A1), g1));
                let pb = add!(mul!(k!(BA), ga), mul!(k!(B1), g1));
                let a = add!(
                    mul!(k!(H0), abs!(_mm256_sub_pd(qj, pa))),
                    mul!(k!(H1), abs!(_mm256_sub_pd(vj, pb)))
                );
                let (ac, _) = amp[..n].as_chunks_mut::<4>();
                // SAFETY: a chunk of four values
                unsafe { _mm256_storeu_pd(ac[i].as_mut_ptr(), a) };
            }
            let u = add!(y, mul!(k!(DD), x));
            let terms = [
                mul!(k!(LA), x),
                mul!(k!(LV), x),
                mul!(k!(LAI), u),
                mul!(k!(LVI), u),
                mul!(k!(LVI), x),
                mul!(k!(LVD), u),
                add!(mul!(y, y), mul!(mul!(k!(W2), x), x)),
            ];
            for l in 0..7 {
                // modes 4i, 4i + 1, then 4i + 2, 4i + 3: the two-lane pass's order
                acc[l] = _mm_add_pd(acc[l], _mm256_castpd256_pd128(terms[l]));
                acc[l] = _mm_add_pd(acc[l], _mm256_extractf128_pd::<1>(terms[l]));
            }
            // SAFETY: chunks of four values
            unsafe {
                _mm256_storeu_pd(xc[i].as_mut_ptr(), x);
                _mm256_storeu_pd(yc[i].as_mut_ptr(), y);
            }
        }
        let mut lanes = [F2::zero(); 7];
        for l in 0..7 {
            let mut two = [0.0; 2];
            // SAFETY: two values
            unsafe { _mm_storeu_pd(two.as_mut_ptr(), acc[l]) };
            lanes[l] = F2::new(two[0], two[1]);
        }
        let acc = lanes;
        pass_pairs::<MARGIN>(m, g, q, v, (qb, vb, amp), 2 * nq, acc)
    }

    /// [`dots`]' four partial sums over the whole chunks of four (lane l: the terms j ≡ l
    /// mod 4, in order), for `c·x` and `c·y`. Safety: the processor has AVX.
    #[target_feature(enable = "avx")]
    pub(super) unsafe fn partial_dots(c: &[f64], x: &[f64], y: &[f64]) -> ([f64; 4], [f64; 4]) {
        let (cc, _) = c.as_chunks::<4>();
        let (xc, _) = x.as_chunks::<4>();
        let (yc, _) = y.as_chunks::<4>();
        let (mut sx, mut sy) = (_mm256_setzero_pd(), _mm256_setzero_pd());
        for ((c, x), y) in cc.iter().zip(xc).zip(yc) {
            // SAFETY: AVX (the caller); chunks of four values
            let (c, x, y) = unsafe {
                (
                    _mm256_loadu_pd(c.as_ptr()),
                    _mm256_loadu_pd(x.as_ptr()),
                    _mm256_loadu_pd(y.as_ptr()),
                )
            };
            sx = _mm256_add_pd(sx, _mm256_mul_pd(c, x));
            sy = _mm256_add_pd(sy, _mm256_mul_pd(c, y));
        }
        let (mut ax, mut ay) = ([0.0; 4], [0.0; 4]);
        // SAFETY: four values each
        unsafe {
            _mm256_storeu_pd(ax.as_mut_ptr(), sx);
            _mm256_storeu_pd(ay.as_mut_ptr(), sy);
        }
        (ax, ay)
    }
}

/// `Σ η̇² + ω²η²` of the state (q, v) with the arithmetic of [`poly_pass`]'s end sum (two
/// lanes, even and odd modes, added at the end): the same bits that sum gives for the state
/// a pass ends in.
pub(super) fn start_energy2(m: &PolyMap, q: &[f64], v: &[f64]) -> f64 {
    let n = q.len().min(v.len()).min(2 * m.pairs.len());
    let mut acc = F2::zero();
    for j in (0..n).step_by(2) {
        let two = j + 1 < n;
        let qj = F2::new(q[j], if two { q[j + 1] } else { 0.0 });
        let vj = F2::new(v[j], if two { v[j + 1] } else { 0.0 });
        acc = acc + (vj * vj + m.pairs[j / 2][W2] * qj * qj);
    }
    let [a, b] = acc.get();
    a + b
}

/// The contact test's margins of [`poly_pass`] alone (the same arithmetic, so the same bits):
/// `amp` from the start state (q, v) under the ground factors `g`.
pub(super) fn poly_margins(
    m: &PolyMap,
    (ag, vg, a1): (f64, f64, f64),
    q: &[f64],
    v: &[f64],
    amp: &mut [f64],
) {
    let n = amp.len().min(q.len()).min(v.len());
    let (g_a, g_v, g_1) = (F2::splat(ag), F2::splat(vg), F2::splat(a1));
    for j in (0..n).step_by(2) {
        let c = &m.pairs[j / 2];
        let k = |i: usize| c[i];
        let two = j + 1 < n;
        let qj = F2::new(q[j], if two { q[j + 1] } else { 0.0 });
        let vj = F2::new(v[j], if two { v[j + 1] } else { 0.0 });
        let pa = k(AA) * g_a + k(AV) * g_v + k(A1) * g_1;
        let pb = k(BA) * g_a + k(B1) * g_1;
        let a = k(H0) * (qj - pa).abs() + k(H1) * (vj - pb).abs();
        let a = a.get();
        amp[j] = a[0];
        if two {
            amp[j + 1] = a[1];
        }
    }
}

/// `(c·x, c·y)` with the very arithmetic of [`crate::numerics::linalg::dot`] for each (a chain
/// below 8 terms, else four partial sums, lanes 0 + 2 and 1 + 3 added last: the same bits),
/// both in one pass that reads c once, the partial sums as two pairs of lanes (or, where the
/// processor has AVX, as the four lanes of one register: each partial sum takes the same
/// terms in the same order either way).
#[inline(always)]
pub(super) fn dots(c: &[f64], x: &[f64], y: &[f64]) -> (f64, f64) {
    let n = c.len().min(x.len()).min(y.len());
    let (c, x, y) = (&c[..n], &x[..n], &y[..n]);
    if n < 8 {
        let (mut sx, mut sy) = (0.0, 0.0);
        for i in 0..n {
            sx += c[i] * x[i];
            sy += c[i] * y[i];
        }
        return (sx, sy);
    }
    #[cfg(target_arch = "x86_64")]
    if crate::numerics::vex::available() {
        // SAFETY: the processor has AVX
        let (ax, ay) = unsafe { wide::partial_dots(c, x, y) };
        return dots_tail(c, x, y, ax, ay);
    }
    let z = F2::zero();
    let (mut x01, mut x23, mut y01, mut y23) = (z, z, z, z);
    let (cc, _) = c.as_chunks::<4>();
    let (xc, _) = x.as_chunks::<4>();
    let (yc, _) = y.as_chunks::<4>();
    for ((c, x), y) in cc.iter().zip(xc).zip(yc) {
        let (c01, c23) = (F2::new(c[0], c[1]), F2::new(c[2], c[3]));
        x01 = x01 + c01 * F2::new(x[0], x[1]);
        x23 = x23 + c23 * F2::new(x[2], x[3]);
        y01 = y01 + c01 * F2::new(y[0], y[1]);
        y23 = y23 + c23 * F2::new(y[2], y[3]);
    }
    let ([x0, x1], [x2, x3]) = (x01.get(), x23.get());
    let ([y0, y1], [y2, y3]) = (y01.get(), y23.get());
    dots_tail(c, x, y, [x0, x1, x2, x3], [y0, y1, y2, y3])
}

/// [`dots`] from the four partial sums of its whole chunks of four: the last terms onto them,
/// then lanes 0 + 2 and 1 + 3 added.
#[inline(always)]
fn dots_tail(c: &[f64], x: &[f64], y: &[f64], mut ax: [f64; 4], mut ay: [f64; 4]) -> (f64, f64) {
    let n = c.len().min(x.len()).min(y.len());
    let r = n / 4 * 4;
    for i in 0..n - r {
        ax[i] += c[r + i] * x[r + i];
        ay[i] += c[r + i] * y[r + i];
    }
    (
        (ax[0] + ax[2]) + (ax[1] + ax[3]),
        (ay[0] + ay[2]) + (ay[1] + ay[3]),
    )
}

/// A pair of modes of [`poly_pass`] (coefficients `c`, ground factors `g` in both lanes) from
/// (η, η̇): (η', η̇', margin; zero without `MARGIN`), the sums added to `acc`.
#[inline(always)]
fn pair<const MARGIN: bool>(
    c: &[F2; COEFS],
    (g_a, g_v, g_1): (F2, F2, F2),
    qj: F2,
    vj: F2,
    acc: &mut [F2; 7],
) -> (F2, F2, F2) {
    let k = |i: usize| c[i];
    let x = k(P11) * qj + k(P12) * vj + (k(QA) * g_a + k(QV) * g_v + k(Q1) * g_1);
    let y = k(P21) * qj + k(P22) * vj + (k(VA) * g_a + k(VV) * g_v + k(V1) * g_1);
    let a = if MARGIN {
        let pa = k(AA) * g_a + k(AV) * g_v + k(A1) * g_1;
        let pb = k(BA) * g_a + k(B1) * g_1;
        k(H0) * (qj - pa).abs() + k(H1) * (vj - pb).abs()
    } else {
        F2::zero()
    };
    let u = y + k(DD) * x;
    acc[0] = acc[0] + k(LA) * x;
    acc[1] = acc[1] + k(LV) * x;
    acc[2] = acc[2] + k(LAI) * u;
    acc[3] = acc[3] + k(LVI) * u;
    acc[4] = acc[4] + k(LVI) * x;
    acc[5] = acc[5] + k(LVD) * u;
    acc[6] = acc[6] + (y * y + k(W2) * x * x);
    (x, y, a)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The affine map of a free step under a recorded motion's piece against the closed form
    /// of a damped oscillator `η̈ + 2ζωη̇ + ω²η = c0 + c1τ + c2τ²` (the load of a_g, v_g, a1
    /// through la, lv), written here: the particular solution `A + Bτ + Cτ²` from matching
    /// powers of τ, and the homogeneous part `e^{−ζωτ}(x0 cos ω_d τ + (y0 + ζωx0)/ω_d sin ω_d τ)`
    /// with its derivative. Modes from soft to stiff (ωh from 2e-4 to 16), damped and not, at
    /// three step lengths and three load sets.
    #[test]
    fn poly_map_is_the_exact_step_of_a_damped_oscillator_under_a_quadratic_load() {
        let omega = [2.0, 9.5, 31.0, 140.0, 800.0];
        let zeta = [0.0, 0.02, 0.05, 0.3, 0.01];
        let la = [-1200.0, 310.0, -95.0, 40.0, -7.0];
        let lv = [3.0, -0.4, 11.0, -2.5, 0.8];
        let damp: Vec<f64> = omega.iter().zip(&zeta).map(|(w, z)| 2.0 * z * w).collect();
        let inv_w2: Vec<f64> = omega.iter().map(|w| 1.0 / (w * w)).collect();
        let (q0, v0) = (
            [0.01, -0.002, 3e-4, 1e-5, -2e-7],
            [0.05, 0.03, -0.01, 2e-3, 1e-4],
        );
        let mut worst = 0.0f64;
        for h in [0.005, 0.02, 1e-4] {
            let props: Vec<Prop> = (0..5).map(|j| propagator(omega[j], damp[j], h)).collect();
            let w2: Vec<f64> = omega.iter().map(|w| w * w).collect();
            let modes = ModeLoads {
                la: &la,
                lv: &lv,
                damp: &damp,
                w2: &w2,
                inv_w2: &inv_w2,
            };
            let map = PolyMap::new(modes, &props, &[(0.0, 0.0); 5], h);
            for (ag, vg, a1) in [(1.7, -0.3, 40.0), (-3.0, 0.8, -5.0), (0.2, 0.01, 900.0)] {
                for j in 0..5 {
                    let (w, zw) = (omega[j], zeta[j] * omega[j]);
                    let c = [
                        la[j] * ag + lv[j] * vg,
                        la[j] * a1 + lv[j] * ag,
                        0.5 * lv[j] * a1,
                    ];
                    // ω²C = c2, ω²B + 2·2ζω·C = c1, ω²A + 2ζω·B + 2C = c0
                    let cc = c[2] / (w * w);
                    let b = (c[1] - 4.0 * zw * cc) / (w * w);
                    let a = (c[0] - 2.0 * zw * b - 2.0 * cc) / (w * w);
                    let (x0, y0) = (q0[j] - a, v0[j] - b);
                    let wd = w * (1.0 - zeta[j] * zeta[j]).sqrt();
                    let (sn, cs, ex) = ((wd * h).sin(), (wd * h).cos(), (-zw * h).exp());
                    let x = ex * (x0 * cs + (y0 + zw * x0) / wd * sn);
                    let y = ex * (y0 * cs - (w * w * x0 + zw * y0) / wd * sn);
                    let want = (x + a + b * h + cc * h * h, y + b + 2.0 * cc * h);
                    let got = map.step(j, (ag, vg, a1), q0[j], v0[j]);
                    // (both sides round the particular solution and the homogeneous part at
                    // their own size: the scale is the largest of them, in displacement and,
                    // times ω, in velocity; measured ≤ 8e-16 of it: 1e-13 leaves room for other
                    // compilers' contraction into fused multiply–adds)
                    let sq = q0[j].abs()
                        + a.abs()
                        + (b * h).abs()
                        + (cc * h * h).abs()
                        + (v0[j].abs() + b.abs()) / w;
                    let sv = w * sq + 2.0 * (cc * h).abs();
                    let err = ((got.0 - want.0).abs() / sq).max((got.1 - want.1).abs() / sv);
                    worst = worst.max(err);
                    assert!(
                        err <= 1e-13,
                        "mode {j}, h {h}: {got:?} vs {want:?} ({err:e})"
                    );
                }
            }
        }
        eprintln!("poly map vs closed form: worst relative error {worst:e}");
    }

    /// The margins' bound holds: for random modes (ω from 0.3 to 3000 rad/s, ζ up to 0.4, so
    /// that (ωh)⁴/384 runs from ~0 to its cap of 2), loads, steps, coupling rows (zeros among
    /// them, as a row's are), states and ground factors over many orders of magnitude, every
    /// level's [`PolyMap::margin_bounds`] is at least its margin `Σ_j |c_kj| amp_j` as the pass
    /// with margins forms it. The same draws check that the margins alone
    /// ([`poly_margins`]) are the pass's bit for bit, that the pass without margins gives the
    /// same end state and sums bit for bit, and its start sum of squares against a plain sum.
    #[test]
    fn the_margin_bound_holds_and_the_lean_pass_is_the_same_step() {
        use proptest::prelude::*;
        let mag = |lo: f64, hi: f64| {
            (lo..hi, prop::bool::ANY)
                .prop_map(|(e, s)| if s { 10f64.powf(e) } else { -10f64.powf(e) })
        };
        let mode = (-0.5f64..3.5, 0.0f64..0.4, mag(-2.0, 4.0), mag(-3.0, 2.0));
        let levels = prop::collection::vec(
            prop::collection::vec(prop_oneof![Just(0.0), mag(-4.0, 0.0)], 13),
            1..4,
        );
        let state = prop::collection::vec((mag(-9.0, 0.0), mag(-7.0, 1.0)), 13);
        let data = (
            prop::collection::vec(mode, 1..13),
            levels,
            state,
            -4.0f64..-1.5,
            (mag(-3.0, 1.5), mag(-4.0, 0.5), mag(-2.0, 3.0)),
        );
        proptest!(ProptestConfig::with_cases(3000), |((modes, rows, st, eh, g) in data)| {
            let n = modes.len();
            let h = 10f64.powf(eh);
            let omega: Vec<f64> = modes.iter().map(|m| 10f64.powf(m.0)).collect();
            let damp: Vec<f64> = modes.iter().zip(&omega).map(|(m, w)| 2.0 * m.1 * w).collect();
            let w2: Vec<f64> = omega.iter().map(|w| w * w).collect();
            let inv_w2: Vec<f64> = w2.iter().map(|x| 1.0 / x).collect();
            let la: Vec<f64> = modes.iter().map(|m| m.2).collect();
            let lv: Vec<f64> = modes.iter().map(|m| m.3).collect();
            let props: Vec<Prop> = (0..n).map(|j| propagator(omega[j], damp[j], h)).collect();
            // (FreeData::herm's factors)
            let herm: Vec<(f64, f64)> = (0..n)
                .map(|j| {
                    let (w, zw) = (omega[j], 0.5 * damp[j]);
                    let lam = if zw < w { w } else { zw + (zw * zw - w * w).sqrt() };
                    let f = hermite_gap_factor(lam * h);
                    (f, 2.0 * f / lam)
                })
                .collect();
            let loads = ModeLoads { la: &la, lv: &lv, damp: &damp, w2: &w2, inv_w2: &inv_w2 };
            let mut map = PolyMap::new(loads, &props, &herm, h);
            let rows: Vec<Vec<f64>> = rows.into_iter().map(|r| r[..n].to_vec()).collect();
            map.set_gains(rows.iter().map(|r| r.as_slice()));
            let q: Vec<f64> = st[..n].iter().map(|s| s.0).collect();
            let v: Vec<f64> = st[..n].iter().map(|s| s.1).collect();
            let (mut qa, mut va, mut aa) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            let (mut qb, mut vb, mut ab) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            let (sa, ea) = poly_pass::<true>(&map, g, &q, &v, (&mut qa, &mut va, &mut aa));
            let (sb, eb) = poly_pass::<false>(&map, g, &q, &v, (&mut qb, &mut vb, &mut ab));
            let s0 = start_energy2(&map, &q, &v);
            // (the start sum is the end sum of a pass that ended in (q, v): the same bits)
            prop_assert_eq!(start_energy2(&map, &qa, &va).to_bits(), ea.to_bits());
            let bits = |x: &[f64]| x.iter().map(|y| y.to_bits()).collect::<Vec<_>>();
            prop_assert_eq!(bits(&qa), bits(&qb));
            prop_assert_eq!(bits(&va), bits(&vb));
            prop_assert_eq!(ea.to_bits(), eb.to_bits());
            prop_assert_eq!(format!("{sa:?}"), format!("{sb:?}"));
            let plain: f64 = (0..n).map(|j| v[j] * v[j] + w2[j] * q[j] * q[j]).sum();
            // (two lanes against one chain: sums of positive terms, a few ulps apart)
            prop_assert!((s0 - plain).abs() <= 1e-14 * plain, "{s0:e} vs {plain:e}");
            let mut alone = vec![0.0; n];
            poly_margins(&map, g, &q, &v, &mut alone);
            prop_assert_eq!(bits(&alone), bits(&aa));
            let mut bound = vec![0.0; rows.len()];
            map.margin_bounds(g, s0, &mut bound);
            for (k, r) in rows.iter().enumerate() {
                let cabs: Vec<f64> = r.iter().map(|c| c.abs()).collect();
                let margin = dot(&cabs, &aa);
                prop_assert!(
                    margin <= bound[k],
                    "level {k}: margin {margin:e} above its bound {:e}", bound[k]
                );
            }
        });
    }

    /// The pass four modes at a time (AVX, where this processor has it) is the two-lane pass
    /// bit for bit: end states, margins, ground-work sums and energy sum, with and without
    /// margins, for every mode count from 1 to 21 (no whole quad, whole quads, and each
    /// remainder of pairs and odd modes after them), on modes, states and ground factors
    /// that round. Without AVX there is nothing to compare (`poly_pass` is the two-lane pass):
    /// the test says so.
    #[test]
    fn the_four_lane_pass_is_the_two_lane_pass_bit_for_bit() {
        if !crate::numerics::vex::available() {
            eprintln!(
                "no AVX on this processor: the four-lane pass is not taken, nothing to compare"
            );
            return;
        }
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = |lo: f64, hi: f64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
            let x = 10f64.powf(lo + (hi - lo) * u);
            if seed & 1 == 0 { x } else { -x }
        };
        let bits = |x: &[f64]| x.iter().map(|y| y.to_bits()).collect::<Vec<_>>();
        for n in 1..=21 {
            let h = 0.005;
            let omega: Vec<f64> = (0..n).map(|_| next(-0.5, 3.0).abs()).collect();
            let damp: Vec<f64> = omega
                .iter()
                .map(|w| 0.1 * w * next(-2.0, 0.0).abs())
                .collect();
            let w2: Vec<f64> = omega.iter().map(|w| w * w).collect();
            let inv_w2: Vec<f64> = w2.iter().map(|x| 1.0 / x).collect();
            let la: Vec<f64> = (0..n).map(|_| next(-2.0, 3.0)).collect();
            let lv: Vec<f64> = (0..n).map(|_| next(-3.0, 1.0)).collect();
            let props: Vec<Prop> = (0..n).map(|j| propagator(omega[j], damp[j], h)).collect();
            let herm: Vec<(f64, f64)> = (0..n)
                .map(|_| (next(-8.0, 0.0).abs(), next(-9.0, -2.0).abs()))
                .collect();
            let loads = ModeLoads {
                la: &la,
                lv: &lv,
                damp: &damp,
                w2: &w2,
                inv_w2: &inv_w2,
            };
            let map = PolyMap::new(loads, &props, &herm, h);
            assert_eq!(map.quads.len(), n / 4, "n {n}: the quads are formed");
            let q: Vec<f64> = (0..n).map(|_| next(-9.0, -1.0)).collect();
            let v: Vec<f64> = (0..n).map(|_| next(-7.0, 0.0)).collect();
            let g = (next(-2.0, 1.0), next(-3.0, 0.0), next(-1.0, 2.5));
            for margin in [false, true] {
                let (mut qa, mut va, mut aa) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
                let (mut qb, mut vb, mut ab) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
                let out_a = (&mut qa[..], &mut va[..], &mut aa[..]);
                let out_b = (&mut qb[..], &mut vb[..], &mut ab[..]);
                let ((sa, ea), (sb, eb)) = if margin {
                    (
                        poly_pass::<true>(&map, g, &q, &v, out_a),
                        pass_pairs::<true>(&map, g, &q, &v, out_b, 0, [F2::zero(); 7]),
                    )
                } else {
                    (
                        poly_pass::<false>(&map, g, &q, &v, out_a),
                        pass_pairs::<false>(&map, g, &q, &v, out_b, 0, [F2::zero(); 7]),
                    )
                };
                assert_eq!(bits(&qa), bits(&qb), "n {n} margin {margin}: η");
                assert_eq!(bits(&va), bits(&vb), "n {n} margin {margin}: η̇");
                assert_eq!(bits(&aa), bits(&ab), "n {n} margin {margin}: margins");
                assert_eq!(ea.to_bits(), eb.to_bits(), "n {n} margin {margin}: energy");
                assert_eq!(
                    format!("{sa:?}"),
                    format!("{sb:?}"),
                    "n {n} margin {margin}"
                );
                // (the states moved: a pass that wrote nothing would compare equal too)
                assert!(qa.iter().zip(&q).all(|(a, b)| a != b), "n {n}");
            }
        }
    }

    /// [`dots`] is [`dot`] twice, bit for bit, at every length from 0 to 41 (the chain below
    /// 8 terms, the partial sums and every remainder above), on values that round.
    #[test]
    fn dots_are_dot_bit_for_bit() {
        for n in 0..42 {
            let c: Vec<f64> = (0..n).map(|i| ((i * 7 + 3) as f64).sqrt() - 2.5).collect();
            let x: Vec<f64> = (0..n).map(|i| 1.0 / (i as f64 + 0.3)).collect();
            let y: Vec<f64> = (0..n).map(|i| ((i as f64) * 0.37).sin() * 1e-3).collect();
            let (a, b) = dots(&c, &x, &y);
            assert_eq!(a.to_bits(), dot(&c, &x).to_bits(), "n = {n}");
            assert_eq!(b.to_bits(), dot(&c, &y).to_bits(), "n = {n}");
        }
    }
}
