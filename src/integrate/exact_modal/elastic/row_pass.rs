//! A row's accepted contact step under a recorded motion, and a pair's with several levels
//! (a row of two): the one pass over the modes of [`row_poly_pass`] (issues 29, 25), the
//! general loops' arithmetic structure by structure and two modes at a time.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::*;
use crate::integrate::collocation::ModeStep;
use crate::numerics::lanes::F2;

crate::numerics::vex::avx_copy! {
    /// The pass over the modes of a row's (or a several-level pair's) accepted step under a
    /// recorded motion without dense output ([`Elastic::accept_general`]): each mode's end state, its levels' projections of it,
    /// its ground work and its change of energy in one pass, structure by structure — a
    /// structure's modes share their levels ([`System::levels_of_mode`]) and whether a contact
    /// force reaches them, so that the passive structures' modes (most of a row's) take the
    /// propagator, the particular solution and the tallies without the contact load's terms.
    /// A structure's modes go two at a time in the lanes of [`F2`] (an odd one last, alone).
    /// Every value is the general loops' (the same operations in the same order, each sum over
    /// the modes in mode order): the same bits. `start`: (x0, y0, q0, v0) per mode; `loads`: the
    /// particular solutions' coefficients and the ground load per mode; `forces`: the nodal forces
    /// `[k·5 + p]` and each level's moments. Returns the ground's work and the change of the modal
    /// energy over the step, J.
    /// Where the processor has AVX, its copy compiled for it runs ([`crate::numerics::vex`]: the
    /// same bits).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn row_poly_pass(
        sys: &System,
        gm: &GroundModes,
        modes: &[ModeStep],
        start: (&[f64], &[f64], &[f64], &[f64]),
        loads: (&[[f64; 3]], &[[f64; 3]]),
        cpl_t: &[f64],
        mode_act: &[bool],
        forces: (&[f64], &[(f64, f64)]),
        h: f64,
        ends: (&mut [f64], &mut [f64]),
        proj: &mut [(f64, f64)],
    ) -> (f64, f64) => row_poly_pass_vex, row_poly_pass_body
}

/// [`row_poly_pass`]'s work.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn row_poly_pass_body(
    sys: &System,
    gm: &GroundModes,
    modes: &[ModeStep],
    start: (&[f64], &[f64], &[f64], &[f64]),
    loads: (&[[f64; 3]], &[[f64; 3]]),
    cpl_t: &[f64],
    mode_act: &[bool],
    (f8, moments): (&[f64], &[(f64, f64)]),
    h: f64,
    (q1s, v1s): (&mut [f64], &mut [f64]),
    proj: &mut [(f64, f64)],
) -> (f64, f64) {
    let (n, nl) = (modes.len(), proj.len());
    let (x0s, y0s) = (&start.0[..n], &start.1[..n]);
    let (q0s, v0s) = (&start.2[..n], &start.3[..n]);
    let (pcoef, cpoly) = (&loads.0[..n], &loads.1[..n]);
    let (w2s, damp, iw2) = (&gm.w2[..n], &gm.damp[..n], &gm.inv_w2[..n]);
    let (q1s, v1s, act) = (&mut q1s[..n], &mut v1s[..n], &mode_act[..n]);
    let (mut input, mut d_energy) = (0.0, 0.0);
    for s in 0..sys.structures.len() {
        let modes_s = sys.modes_of(s);
        if modes_s.is_empty() {
            continue;
        }
        let holding = sys.levels_of_mode(modes_s.start);
        let forced = act[modes_s.start];
        let f = &f8[holding.start * 5..holding.end * 5];
        let mo = &moments[holding.clone()];
        let pr = &mut proj[holding.clone()];
        // (the modes two at a time, each lane the scalar operations below on its own mode,
        // every sum over the levels in their order and the sums over the modes taken lane 0
        // then lane 1: the same bits)
        let mut modes_s = modes_s;
        let pairs = modes_s.len() / 2;
        for jj in 0..pairs {
            let j = modes_s.start + 2 * jj;
            let (ma, mb) = (&modes[j], &modes[j + 1]);
            let lanes = |f: fn(&Prop) -> f64| F2::new(f(&ma.end), f(&mb.end));
            let (x, y) = (F2::new(x0s[j], x0s[j + 1]), F2::new(y0s[j], y0s[j + 1]));
            let xe = lanes(|p| p.p11) * x + lanes(|p| p.p12) * y;
            let ye = lanes(|p| p.p21) * x + lanes(|p| p.p22) * y;
            let (pa, pb) = (pcoef[j], pcoef[j + 1]);
            let [a, b, c] = [0, 1, 2].map(|i| F2::new(pa[i], pb[i]));
            let hh = F2::splat(h);
            let mut q1 = xe + (a + hh * (b + hh * c));
            let mut v1 = ye + (b + F2::splat(2.0 * h) * c);
            let (ca, cb) = (
                &cpl_t[j * nl + holding.start..j * nl + holding.end],
                &cpl_t[(j + 1) * nl + holding.start..(j + 1) * nl + holding.end],
            );
            let (mut gi, mut gt) = (F2::zero(), F2::zero());
            if forced {
                let mut g = [F2::zero(); 5];
                for ((&c1, &c2), fk) in ca.iter().zip(cb).zip(f.chunks_exact(5)) {
                    let cc = F2::new(c1, c2);
                    for p in 0..5 {
                        g[p] = g[p] + cc * F2::splat(fk[p]);
                    }
                }
                for p in 0..5 {
                    q1 = q1 + g[p] * F2::new(ma.end8[p].0, mb.end8[p].0);
                    v1 = v1 + g[p] * F2::new(ma.end8[p].1, mb.end8[p].1);
                }
                for ((&c1, &c2), m) in ca.iter().zip(cb).zip(mo) {
                    let cc = F2::new(c1, c2);
                    gi = gi + cc * F2::splat(m.0);
                    gt = gt + cc * F2::splat(m.1);
                }
            }
            let ([qa, qb], [va, vb]) = (q1.get(), v1.get());
            (q1s[j], q1s[j + 1], v1s[j], v1s[j + 1]) = (qa, qb, va, vb);
            let (sa, sb) = (F2::new(qa, va), F2::new(qb, vb));
            for ((p, &c1), &c2) in pr.iter_mut().zip(ca).zip(cb) {
                let acc = F2::new(p.0, p.1) + F2::splat(c1) * sa + F2::splat(c2) * sb;
                let [u, w] = acc.get();
                *p = (u, w);
            }
            let q0 = F2::new(q0s[j], q0s[j + 1]);
            let v0 = F2::new(v0s[j], v0s[j + 1]);
            let (la, lb) = (&cpoly[j], &cpoly[j + 1]);
            let ground = if (la[1] == 0.0 && la[2] == 0.0) || (lb[1] == 0.0 && lb[2] == 0.0) {
                // (`poly_ground_work`'s shortcut for a constant load: lane by lane)
                let ([gia, gib], [gta, gtb]) = (gi.get(), gt.get());
                let work = |i: usize, e1: f64, w1: f64, g: (f64, f64)| {
                    let st = ((q0s[j + i], v0s[j + i]), (e1, w1));
                    let mode = (damp[j + i], iw2[j + i]);
                    poly_ground_work(mode, h, st.0, st.1, &cpoly[j + i], g.0, g.1)
                };
                [work(0, qa, va, (gia, gta)), work(1, qb, vb, (gib, gtb))]
            } else {
                let [c0, c1, c2] = [0, 1, 2].map(|i| F2::new(la[i], lb[i]));
                let mode = (F2::new(damp[j], damp[j + 1]), F2::new(iw2[j], iw2[j + 1]));
                ground_work2(mode, h, (q0, v0), (q1, v1), (c0, c1, c2), (gi, gt)).get()
            };
            let half = F2::splat(0.5);
            let w2 = F2::new(w2s[j], w2s[j + 1]);
            let de = (half * (v1 * v1 - v0 * v0) + half * w2 * (q1 * q1 - q0 * q0)).get();
            input += ground[0];
            input += ground[1];
            d_energy += de[0];
            d_energy += de[1];
        }
        modes_s.start += 2 * pairs;
        for j in modes_s {
            let cj = &cpl_t[j * nl + holding.start..j * nl + holding.end];
            let ms = &modes[j];
            let (xe, ye) = ms.end.apply(x0s[j], y0s[j]);
            // (the particular solution at the end, `particular_at`'s)
            let [pa, pb, pc] = pcoef[j];
            let (mut q1, mut v1) = (xe + (pa + h * (pb + h * pc)), ye + (pb + 2.0 * h * pc));
            let (mut gi, mut gt) = (0.0, 0.0);
            if forced {
                let mut g = [0.0; 5];
                for (c, fk) in cj.iter().zip(f.chunks_exact(5)) {
                    for p in 0..5 {
                        g[p] += c * fk[p];
                    }
                }
                for p in 0..5 {
                    q1 += g[p] * ms.end8[p].0;
                    v1 += g[p] * ms.end8[p].1;
                }
                for (c, m) in cj.iter().zip(mo) {
                    gi += c * m.0;
                    gt += c * m.1;
                }
            }
            q1s[j] = q1;
            v1s[j] = v1;
            for (c, p) in cj.iter().zip(pr.iter_mut()) {
                p.0 += c * q1;
                p.1 += c * v1;
            }
            let (q0, v0) = (q0s[j], v0s[j]);
            input += poly_ground_work((damp[j], iw2[j]), h, (q0, v0), (q1, v1), &cpoly[j], gi, gt);
            d_energy += 0.5 * (v1 * v1 - v0 * v0) + 0.5 * w2s[j] * (q1 * q1 - q0 * q0);
        }
    }
    (input, d_energy)
}

/// [`poly_ground_work`] of two modes in the lanes of [`F2`], under a load that is not constant
/// (`c1` or `c2` non-zero in both lanes): the same operations in the same order, each lane the
/// scalar function's bits. `mode`: 2ζω and 1/ω²; `(g_int, g_tint)`: the contact load's moments.
#[inline(always)]
fn ground_work2(
    (d, iw2): (F2, F2),
    h: f64,
    (e0, v0): (F2, F2),
    (e1, v1): (F2, F2),
    (c0, c1, c2): (F2, F2, F2),
    (g_int, g_tint): (F2, F2),
) -> F2 {
    const THIRD: f64 = 1.0 / 3.0;
    let hh = F2::splat(h);
    let int_f = g_int + hh * (c0 + hh * (F2::splat(0.5) * c1 + hh * c2 * F2::splat(THIRD)));
    let i0 = (int_f - (v1 - v0) - d * (e1 - e0)) * iw2;
    let int_tf = g_tint
        + F2::splat(h * h)
            * (F2::splat(0.5) * c0 + hh * (c1 * F2::splat(THIRD) + F2::splat(0.25 * h) * c2));
    let i1 = (int_tf - (hh * v1 - (e1 - e0)) - d * (hh * e1 - i0)) * iw2;
    let ph = c0 + hh * (c1 + hh * c2);
    ph * e1 - c0 * e0 - c1 * i0 - F2::splat(2.0) * c2 * i1
}
