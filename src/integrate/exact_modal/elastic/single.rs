//! The contact step of a pair with one contact level (the paper's cases, every sweep row of a
//! pair with one level, the bundled pair examples): the trial of [`Elastic::trial_general`]
//! specialised to a scalar law, every per-level table a fixed-size array on the stack, the
//! coupled propagators read as one contiguous block, no per-level indirection.
//!
//! The arithmetic is the general path's, term for term and in the same order, so the results
//! are the same bit for bit (tested below against the general path on the same states); what
//! goes is the work around it: the level loops and their slices, the six calls for the nodes'
//! propagator rows, the per-level work arrays of the free flight to the nodes.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::*;
use crate::numerics::lanes::F2;

impl<'a, O: Observer> Elastic<'a, O> {
    /// Whether the contact steps take the one-level path: a pair (two structures) with a single
    /// contact level.
    #[inline]
    pub(super) fn single_level(&self) -> bool {
        self.nl == 1 && self.sys.structures.len() == 2
    }

    crate::numerics::vex::avx_copy! {
        /// [`Elastic::trial_general`] for one contact level of a pair ([`Self::single_level`]):
        /// the same trial (free flight to the six nodes, both collocations, the estimate) with the
        /// same arithmetic, on stack arrays. Harmonic motion with a mode at undamped resonance (its
        /// particular solutions at every node: rare) takes the general path.
        pub(super) fn trial_one(
            &mut self,
            k: Option<usize>,
            h: f64,
            piece: &Piece,
        ) -> Result<Trial, NoConvergence> => trial_one_vex, trial_one_body
    }

    /// [`Self::trial_one`]'s work.
    #[inline(always)]
    fn trial_one_body(
        &mut self,
        k: Option<usize>,
        h: f64,
        piece: &Piece,
    ) -> Result<Trial, NoConvergence> {
        debug_assert!(self.single_level());
        let n = self.n;
        let sys = self.sys;
        let t0 = self.t;
        let tr0 = self.exact_trig(t0);
        // (the table first: a trial that takes the general path asks for it again and finds it
        // made)
        self.table(k, h);
        // (whether a harmonic motion has a mode at resonance: asked once a trial)
        let plain = self.gm.harmonic_plain();
        if matches!((piece, plain), (Piece::Harmonic, None)) {
            return self.trial_general(k, h, piece);
        }
        let tab: &Table = match k {
            Some(k) => self.tables[k].as_deref().expect("table"),
            None => self.scratch_table.as_deref().expect("table"),
        };
        debug_assert_eq!(tab.modes(), n);
        self.stats.evaluations += 1;
        // the free flight's particular solution projected on the level at the six nodes
        let mut df = [(0.0, 0.0); 6];
        let (q, v) = (&self.q[..n], &self.v[..n]);
        let (x0s, y0s) = (&mut self.x0[..n], &mut self.y0[..n]);
        let gm = &self.gm;
        match (piece, plain) {
            (Piece::Harmonic, Some((big, g_re, g_im))) => {
                harmonic_start(x0s, y0s, q, v, g_re, g_im, big, &tr0);
                let (gre, gim) = self.gk[0];
                for i in 0..6 {
                    let (sh, ch) = tab.rot[i];
                    let (sn, cn) = (tr0.s * ch + tr0.c * sh, tr0.c * ch - tr0.s * sh);
                    df[i] = (-(sn * gre + cn * gim), -big * (cn * gre - sn * gim));
                }
            }
            (Piece::Poly { .. }, _) => {
                // particular solution A + Bτ + Cτ² per mode, projected on the level
                let ck = &self.cpl_t[..n];
                let (cpoly, pcoef) = (&mut self.cpoly[..n], &mut self.pcoef[..n]);
                let mut proj = [0.0; 3];
                for j in 0..n {
                    let c = gm.poly_load(j, piece, t0);
                    cpoly[j] = c;
                    let (pa, pb, pc) = poly_coefficients(gm.inv_w2[j], gm.damp[j], &c);
                    pcoef[j] = [pa, pb, pc];
                    x0s[j] = q[j] - pa;
                    y0s[j] = v[j] - pb;
                    proj[0] += ck[j] * pa;
                    proj[1] += ck[j] * pb;
                    proj[2] += ck[j] * pc;
                }
                let [a, b, c] = proj;
                for i in 0..6 {
                    let tau = NODES[i] * h;
                    df[i] = (-(a + tau * (b + tau * c)), -(b + 2.0 * tau * c));
                }
            }
            _ => {
                x0s.copy_from_slice(q);
                y0s.copy_from_slice(v);
            }
        }
        // the homogeneous parts Σ_j c_j P(θh)(x0, y0): one pass over the modes for the six
        // nodes, the level's block of coupled propagators node by node (a pair: every mode),
        // δ and δ̇ in the two lanes of one vector operation ([`F2`]: each lane the scalar
        // `s += a·x + b·y`, the modes added in the same order: the same bits)
        let block = tab.cprop_single(n);
        let rows: [&[[f64; 4]]; 6] = std::array::from_fn(|i| &block[i * n..(i + 1) * n]);
        let mut acc = [F2::zero(); 6];
        for (jj, (&x, &y)) in self.x0[..n].iter().zip(&self.y0[..n]).enumerate() {
            let (x, y) = (F2::splat(x), F2::splat(y));
            for (s, row) in acc.iter_mut().zip(&rows) {
                let [a, c, b, e] = row[jj];
                *s = *s + (F2::new(a, c) * x + F2::new(b, e) * y);
            }
        }
        let lv = &sys.levels[0];
        for (d, s) in df.iter_mut().zip(acc) {
            let [s0, s1] = s.get();
            d.0 = lv.delta(-(d.0 - s0));
            d.1 -= s1;
        }
        self.dfree[..6].copy_from_slice(&df);
        let d8free = NODES8.map(|node| df[node]);
        let d6free = NODES6.map(|node| df[node]);
        self.d8free[..4].copy_from_slice(&d8free);
        self.d6free[..3].copy_from_slice(&d6free);
        // the propagated scheme: the start force, a first guess from the last step's quartic
        let bases = collocation::bases();
        let onset = self.onset[0];
        let f0 = collocation::start_force(sys, 0, &self.states[0], onset, EVENT_TOL);
        let mut f8 = [f0; 5];
        if self.last_h > 0.0 {
            let ratio = h / self.last_h;
            let prev: [f64; 5] = std::array::from_fn(|p| self.last_f8[p]);
            for p in 1..5 {
                f8[p] = bases.quartic_at(&prev, 1.0 + THETA8[p] * ratio).max(0.0);
            }
        }
        let tol = self.newton_tol;
        let mut nodal8 = [(0.0, 0.0); 4];
        let solved = collocation::solve_single::<5>(
            sys,
            &tab.w8,
            &d8free,
            &self.onset,
            &mut f8,
            &mut nodal8,
            tol,
        );
        // (the work arrays hold what the general path leaves there, also on a failure)
        self.f8[..5].copy_from_slice(&f8);
        self.nodal8[..4].copy_from_slice(&nodal8);
        solved?;
        // the companion, from the propagated quartic at its nodes
        let at = |i: usize| (0..5).map(|p| bases.at6[i][p] * f8[p]).sum::<f64>();
        let mut f6 = [f8[0], at(0), at(1), f8[4]];
        let mut nodal6 = [(0.0, 0.0); 3];
        let solved = collocation::solve_single::<4>(
            sys,
            &tab.w6,
            &d6free,
            &self.onset,
            &mut f6,
            &mut nodal6,
            tol,
        );
        self.f6[..4].copy_from_slice(&f6);
        self.nodal6[..3].copy_from_slice(&nodal6);
        solved?;
        // the estimate: the two ends' distance on δ and δ̇
        let st = &self.states[0];
        let (a, b) = (nodal8[3], nodal6[2]);
        let w = (st.delta + lv.gap).abs();
        let rate = st.delta_dot.abs().max(onset);
        let err = 0.0f64
            .max((a.0 - b.0).abs() / (self.tol.atol + self.tol.rtol * w))
            .max((a.1 - b.1).abs() / (self.tol.atol_rate + self.tol.rtol * rate));
        if !err.is_finite() {
            return Err(NoConvergence);
        }
        Ok(Trial { err, h, k })
    }

    crate::numerics::vex::avx_copy! {
        /// [`Elastic::accept_general`] for one contact level of a pair ([`Self::single_level`]):
        /// the same commit (end state, dense output, tallies, the law's work, level state) with the
        /// same arithmetic, the per-mode loops split per kind of ground motion and the level loops
        /// gone. Harmonic motion with a mode at undamped resonance takes the general path.
        pub(super) fn accept_one(&mut self, piece: &Piece, trial: Trial, t_end: f64) => accept_one_vex, accept_one_body
    }

    /// [`Self::accept_one`]'s work.
    #[inline(always)]
    fn accept_one_body(&mut self, piece: &Piece, trial: Trial, t_end: f64) {
        debug_assert!(self.single_level());
        let t0 = self.t;
        let tr0 = self.exact_trig(t0);
        // (whether a harmonic motion has a mode at resonance: asked once a step)
        let plain = self.gm.harmonic_plain();
        let harmonic_piece = match (piece, &self.htally, plain.is_some()) {
            (Piece::Harmonic, Some(_), true) => true,
            (Piece::Poly { .. }, _, _) | (Piece::Zero, _, _) => false,
            _ => return self.accept_general(piece, trial, t_end),
        };
        let n = self.n;
        let h = trial.h;
        let bases = collocation::bases();
        let tab: &Table = match trial.k {
            Some(k) => self.tables[k].as_deref().expect("table"),
            None => self.scratch_table.as_deref().expect("table"),
        };
        let start = self.trace_start();
        let f: [f64; 5] = std::array::from_fn(|p| self.f8[p]);
        // dense output where the nodal forces peak inside the step
        let inner = f[1].max(f[2]).max(f[3]);
        let dense = inner > 0.0 && inner > f[0].max(f[4]);
        // sin, cos at the end, and at the interior nodes only for dense output (`trs[1..4]`
        // is read only then)
        let end_trig = self.node_trig(tab, tr0, h, 4);
        let trs: [Trig; 5] = if dense {
            self.node_trigs(tab, tr0, h)
        } else {
            [tr0, end_trig, end_trig, end_trig, end_trig]
        };
        // the contact quartic's integral and first moment
        let moment = {
            let (mut a, mut b) = (0.0, 0.0);
            for p in 0..5 {
                a += WEIGHTS8[p] * f[p];
                b += bases.first[p] * f[p];
            }
            (h * a, h * h * b)
        };
        self.moments[0] = moment;
        let gm = &self.gm;
        let (x0s, y0s) = (&self.x0[..n], &self.y0[..n]);
        let (w2s, damp, iw2) = (&gm.w2[..n], &gm.damp[..n], &gm.inv_w2[..n]);
        let modes = &tab.modes[..n];
        let cs = &self.cpl_t[..n];
        // the particular solutions at the end (and at the interior nodes for dense output)
        let (pend, pmid) = (&mut self.pend[..n], &mut self.pmid[..n]);
        match plain {
            Some((big, g_re, g_im)) if harmonic_piece => {
                let at = |j: usize, tr: &Trig| {
                    let (gr, gi) = (g_re[j], g_im[j]);
                    (gr * tr.s + gi * tr.c, big * (gr * tr.c - gi * tr.s))
                };
                for j in 0..n {
                    pend[j] = at(j, &trs[4]);
                }
                if dense {
                    for j in 0..n {
                        pmid[j] = std::array::from_fn(|i| at(j, &trs[i + 1]));
                    }
                }
            }
            harmonic => {
                for j in 0..n {
                    let pcoef = &self.pcoef[j];
                    pend[j] = particular_at(gm, piece, harmonic, pcoef, j, h, &trs[4]);
                    if dense {
                        pmid[j] = std::array::from_fn(|i| {
                            let tau = THETA8[i + 1] * h;
                            particular_at(gm, piece, harmonic, pcoef, j, tau, &trs[i + 1])
                        });
                    }
                }
            }
        }
        // the end state (and the dense output's), the level's projections of it
        let (q1s, v1s) = (&mut self.q1s[..n], &mut self.v1s[..n]);
        let (dq, dv) = (&mut self.dense_q[..3 * n], &mut self.dense_v[..3 * n]);
        // (η, η̇) in the two lanes of one vector operation ([`F2`]: each lane the scalar
        // arithmetic, term for term in the same order: the same bits)
        let lanes =
            |p: &Prop, x0: F2, y0: F2| F2::new(p.p11, p.p21) * x0 + F2::new(p.p12, p.p22) * y0;
        let pair = |x: (f64, f64)| F2::new(x.0, x.1);
        let mut proj = F2::zero();
        for j in 0..n {
            let c = cs[j];
            let g = f.map(|x| F2::splat(c * x));
            let ms = &modes[j];
            let (x0, y0) = (F2::splat(x0s[j]), F2::splat(y0s[j]));
            let mut qv = lanes(&ms.end, x0, y0) + pair(pend[j]);
            for p in 0..5 {
                qv = qv + g[p] * pair(ms.end8[p]);
            }
            if dense {
                for i in 0..3 {
                    let mut ed = lanes(&ms.mid[i], x0, y0) + pair(pmid[j][i]);
                    for p in 0..5 {
                        ed = ed + g[p] * pair(ms.mid8[i][p]);
                    }
                    [dq[i * n + j], dv[i * n + j]] = ed.get();
                }
            }
            [q1s[j], v1s[j]] = qv.get();
            proj = proj + F2::splat(c) * qv;
        }
        let proj = {
            let [a, b] = proj.get();
            (a, b)
        };
        self.proj[0] = proj;
        // the tallies, per kind of piece
        let mut sums = StateSums::default();
        let (mut input, mut d_energy) = (0.0, 0.0);
        let (q0s, v0s) = (&self.q[..n], &self.v[..n]);
        let (q1s, v1s) = (&self.q1s[..n], &self.v1s[..n]);
        match (piece, &self.htally) {
            (Piece::Harmonic, Some(ht)) => {
                for j in 0..n {
                    ht.add(&mut sums, j, w2s[j], q1s[j], v1s[j]);
                }
            }
            (Piece::Poly { .. }, _) => {
                for j in 0..n {
                    let c = cs[j];
                    let (mut gi, mut gt) = (0.0, 0.0);
                    gi += c * moment.0;
                    gt += c * moment.1;
                    input += poly_ground_work(
                        (damp[j], iw2[j]),
                        h,
                        (q0s[j], v0s[j]),
                        (q1s[j], v1s[j]),
                        &self.cpoly[j],
                        gi,
                        gt,
                    );
                }
            }
            _ => {}
        }
        let harmonic_sums = harmonic_piece && self.big.is_some();
        if !harmonic_sums {
            for j in 0..n {
                let (q0, v0, q1, v1) = (q0s[j], v0s[j], q1s[j], v1s[j]);
                d_energy += 0.5 * (v1 * v1 - v0 * v0) + 0.5 * w2s[j] * (q1 * q1 - q0 * q0);
            }
        }
        std::mem::swap(&mut self.q, &mut self.q1s);
        std::mem::swap(&mut self.v, &mut self.v1s);
        if let (true, Some(ht), Some(big)) = (harmonic_sums, &self.htally, self.big) {
            // the ground's work: the state sums at both ends, and the contact quartic's extra
            let tm =
                TrigMoments::from_ends(big, h, (tr0.s, tr0.c), (trs[4].s, trs[4].c), tab.rot[3]);
            input = ht.input(&tm, &self.sums, &sums);
            let (k4, k5) = self.kextra[0];
            for p in 0..5 {
                let (a, b) = tab.hmom[p];
                let (sp, cp) = (tr0.s * a + tr0.c * b, tr0.c * a - tr0.s * b);
                input += f[p] * (k4 * sp + k5 * cp);
            }
            d_energy = sums.energy - self.sums.energy;
        }
        self.sums = sums;
        self.psums_ok = false;
        // the contact load's work on the modes (Lobatto, 5 nodes), and the work into the
        // contact with the law along the motion (the 7-point rule)
        let st0 = self.states[0];
        let nodal8: [(f64, f64); 4] = std::array::from_fn(|i| self.nodal8[i]);
        let mut pw = WEIGHTS8[0] * f[0] * st0.delta_dot;
        for p in 1..5 {
            pw += WEIGHTS8[p] * f[p] * nodal8[p - 1].1;
        }
        let modal = 0.0 - h * pw;
        let sys = self.sys;
        let lv = &sys.levels[0];
        let onset = self.onset[0];
        let power = |(d, dd): (f64, f64)| lv.force.force(d, dd, episode_v0(onset, dd)) * dd;
        let w7 = &bases.seven;
        let mut lw = w7[0] * f[0] * st0.delta_dot;
        for (i, node) in [(1, 0), (3, 1), (5, 2), (6, 3)] {
            lw += w7[i] * power(nodal8[node]);
        }
        for (i, slot) in [(2, 0), (4, 1)] {
            let (mut d, mut dd) = self.dfree[slot];
            let w86 = &tab.w86[slot * 5..slot * 5 + 5];
            for p in 0..5 {
                let (a, b) = w86[p];
                d -= a * f[p];
                dd -= b * f[p];
            }
            lw += w7[i] * power((d, dd));
        }
        let law = 0.0 + h * lw;
        let damping = input + modal - d_energy;
        self.energy += d_energy;
        if dense {
            self.observe_dense(h, t0, (input, damping, law));
        }
        self.tally.input += input;
        self.tally.damping += damping;
        self.tally.contact += law;
        self.tally.impulse[0] += moment.0;
        self.last_f8[..5].copy_from_slice(&f);
        self.t = t_end;
        self.prev_states[0] = st0;
        let (cq, cv) = proj;
        self.set_state(0, cq, cv);
        update_onsets(&mut self.onset, &self.prev_states, &self.states, h);
        let st = self.states[0];
        if self.onset[0] == 0.0 && Self::at_onset(&st) {
            self.onset[0] = st.delta_dot;
        }
        if st.delta > 0.0 {
            let kt = lv.force.tangent_stiffness(st.delta);
            self.max_contact_w2h2 = self.max_contact_w2h2.max(kt * self.inv_mstar[0] * h * h);
        }
        self.close_contact_step(t0, h, t_end, trs[4], start, trial.err);
    }
}

/// The free flight's start without its harmonic particular solution, per mode:
/// `x0 = q − (g_re sin Ωt + g_im cos Ωt)`, `y0 = v − Ω(g_re cos Ωt − g_im sin Ωt)`. A function
/// of its own so that the slices are known not to overlap (no run-time overlap tests before
/// the vector loop).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn harmonic_start(
    x0s: &mut [f64],
    y0s: &mut [f64],
    q: &[f64],
    v: &[f64],
    g_re: &[f64],
    g_im: &[f64],
    big: f64,
    tr0: &Trig,
) {
    let n = x0s.len();
    let (y0s, q, v, g_re, g_im) = (&mut y0s[..n], &q[..n], &v[..n], &g_re[..n], &g_im[..n]);
    for j in 0..n {
        let (gr, gi) = (g_re[j], g_im[j]);
        x0s[j] = q[j] - (gr * tr0.s + gi * tr0.c);
        y0s[j] = v[j] - big * (gr * tr0.c - gi * tr0.s);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::scenario::Scenario;
    use crate::integrate::{Method, SolverSettings};

    struct Quiet;
    impl Observer for Quiet {
        fn observe(&mut self, _: &System, _: &StepView) {}
    }

    /// Two cantilevers (T1 = 0.3 s, T2 = 0.6 s, 3 modes each) with one contact level at the
    /// top (`contact`), under `ground`.
    fn system(contact: &str, ground: &str) -> System {
        let text = format!(
            "[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.3\nmodes = 3\n\
             damping_ratio = 0.01\n[[structure]]\nlength = 10.0\nmass = 2.273e6\n\
             period = 0.6\nmodes = 3\ndamping_ratio = 0.01\n[contact]\n{contact}\n\
             gap = 0.0127\n[ground_motion]\n{ground}\n\
             [solver]\nmethod = \"exact-modal\"\ndt = 1e-3\nduration = 1.0\n"
        );
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
        Scenario::from_toml(&text, "case.toml", &dir)
            .expect("valid scenario")
            .system()
    }

    /// The contact steps of a run (rtol 1e-8, `duration` s), as traced.
    fn steps(sys: &System, duration: f64) -> Vec<StepTrace> {
        let settings = SolverSettings::new(Method::ExactModal, 1e-3, duration).with_rtol(1e-8);
        let mut trace = Vec::new();
        super::super::run(
            sys,
            &settings,
            &InitialState::default(),
            &mut Quiet,
            Some(&mut trace),
        )
        .expect("runs");
        trace
    }

    /// Every observation, as its `Debug` text (which tells every bit of an f64 apart).
    #[derive(Default)]
    struct Seen(Vec<String>);
    impl Observer for Seen {
        fn observe(&mut self, _: &System, v: &StepView) {
            self.0.push(format!(
                "{} {:?} {:?} {:?} {:?}",
                v.t, v.q, v.v, v.levels, v.tally
            ));
        }
    }

    /// Three contact steps of length h from `tr`'s start state, trial and acceptance each by
    /// the one-level path or the general one (the second and third start from a previous
    /// step's quartic, as inside an impact): everything a trial leaves (estimate, both
    /// schemes' forces and nodal states, the free flight to the nodes) and an acceptance
    /// leaves (state, level state, onset speed, tallies, energy, the next first guess, every
    /// observation, dense ones included), as `Debug` text.
    fn steps_from(sys: &System, tr: &StepTrace, h: f64, single: bool) -> Vec<String> {
        let settings = SolverSettings::new(Method::ExactModal, 1e-3, 10.0);
        let mut seen = Seen::default();
        let mut out = Vec::new();
        {
            let mut r = Elastic::new(
                sys,
                &settings,
                &mut seen,
                None,
                tr.t,
                tr.q0.clone(),
                tr.v0.clone(),
                Some(&tr.onset),
            );
            for _ in 0..3 {
                let (piece, _, _) = r.piece();
                let t = if single {
                    r.trial_one(None, h, &piece)
                } else {
                    r.trial_general(None, h, &piece)
                }
                .expect("converges");
                out.push(format!(
                    "{:?} {:?} {:?} {:?} {:?} {:?}",
                    t.err, r.f8, r.f6, r.nodal8, r.nodal6, r.dfree
                ));
                let t_end = r.t + h;
                if single {
                    r.accept_one(&piece, t, t_end);
                } else {
                    r.accept_general(&piece, t, t_end);
                }
                out.push(format!(
                    "{} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?}",
                    r.t, r.q, r.v, r.states, r.onset, r.tally, r.energy, r.last_f8, r.last_h
                ));
            }
        }
        out.extend(seen.0);
        out
    }

    /// The one-level contact step equals the general path's on the same state, under harmonic
    /// motion and a record (their particular solutions take different branches), on the
    /// elastic and the damped laws, from states inside impacts, at their onsets and releases:
    /// the same arithmetic in the same order, so equal bit for bit (every f64 compared by its
    /// shortest round-trip text: 0 ulp; the general path is itself tested against closed forms
    /// and an independent integration in `elastic::tests`).
    #[test]
    fn the_one_level_step_equals_the_general_one() {
        // (the bundled Loma Prieta record scaled to 1 g: its strong motion pounds within 8 s)
        let record = "kind = \"record\"\nfile = \"records/RSN753_LOMAP_CLS000.AT2\"\n\
                      scale_to_pga = 1.0";
        let harmonic = "kind = \"harmonic\"\npga = 0.5\nperiod = 0.8";
        let (mut compared, mut dense) = (0, 0);
        for (ground, duration) in [(harmonic, 1.0), (record, 8.0)] {
            for law in [
                "law = \"hertz\"\nstiffness = 2.808e10",
                "law = \"kelvin\"\nstiffness = 1e9\nrestitution = 0.6",
                "law = \"hertzdamp\"\nstiffness = 2.808e10\nrestitution = 0.6",
            ] {
                let sys = system(law, ground);
                let trace = steps(&sys, duration);
                assert!(trace.len() > 20, "{law} / {ground}: contact steps");
                for tr in trace.iter().step_by(7) {
                    let a = steps_from(&sys, tr, tr.h, true);
                    let b = steps_from(&sys, tr, tr.h, false);
                    // (six entries for three steps, one observation each, three more for each
                    // step observed densely: the force peaks inside it)
                    assert!(a.len() >= 9, "three steps and their observations");
                    dense += a.len() - 9;
                    assert_eq!(a, b, "{law} / {ground} at t = {}", tr.t);
                    compared += 1;
                }
            }
        }
        assert!(compared > 50, "{compared} states compared");
        assert!(dense > 0, "dense output compared");
    }
}
