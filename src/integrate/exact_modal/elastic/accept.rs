//! The accepted contact step of [`Elastic`]: its end state and dense output, the exact
//! tallies and the law's work, the observations at its interior nodes, and what every
//! accepted step does last (the clock of sin Ωt, cos Ωt, the trace, the observation).

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::row_pass::row_poly_pass;
use super::*;
use crate::numerics::lanes::F2;

impl<'a, O: Observer> Elastic<'a, O> {
    /// Observe the step being accepted (start `t0`, length h) at its three interior nodes, from
    /// the states the accepted pass left in `dense_q`, `dense_v` and the nodal (δ, δ̇); the
    /// impulses integrated exactly up to each node (the force quartic), the energy flows
    /// (`flows`: the step's ground work, dissipation and contact work) in proportion.
    pub(super) fn observe_dense(&mut self, h: f64, t0: f64, flows: (f64, f64, f64)) {
        let (n, nl) = (self.n, self.nl);
        let bases = collocation::bases();
        for i in 0..3 {
            let x = THETA8[i + 1];
            self.dense_tally.input = self.tally.input + x * flows.0;
            self.dense_tally.damping = self.tally.damping + x * flows.1;
            self.dense_tally.contact = self.tally.contact + x * flows.2;
            for k in 0..nl {
                let w = &bases.partial[i];
                let imp: f64 = (0..5).map(|p| w[p] * self.f8[k * 5 + p]).sum();
                self.dense_tally.impulse[k] = self.tally.impulse[k] + h * imp;
                let p = self.sys.levels[k].pair;
                if !(self.act[p] || self.act[p + 1]) {
                    // (a row's passive level: its free flight at the node, from the modes)
                    let c = self.sys.coupling(k);
                    let (q, v) = (&self.dense_q[i * n..(i + 1) * n], &self.dense_v[i * n..]);
                    let (mut cq, mut cv) = (0.0, 0.0);
                    for j in self.sys.coupling_modes(k) {
                        cq += c[j] * q[j];
                        cv += c[j] * v[j];
                    }
                    self.dense_states[k] = self.sys.levels[k].state(cq, cv, self.onset[k]);
                    continue;
                }
                let (delta, delta_dot) = self.nodal8[k * 4 + i];
                let v0 = episode_v0(self.onset[k], delta_dot);
                self.dense_states[k] = LevelState {
                    delta,
                    delta_dot,
                    force: self.sys.levels[k].force.force(delta, delta_dot, v0),
                };
            }
            let view = StepView {
                t: t0 + x * h,
                q: &self.dense_q[i * n..(i + 1) * n],
                v: &self.dense_v[i * n..(i + 1) * n],
                levels: &self.dense_states,
                z: &[],
                tally: &self.dense_tally,
            };
            // (a row's passive structures: seen at the step's end, see `active`)
            if self.row {
                let active = &self.act;
                let st = Stepped {
                    active,
                    grid: false,
                };
                self.obs.observe_stepped(self.sys, &view, &st);
            } else {
                self.obs.observe(self.sys, &view);
            }
        }
    }

    /// Commit the trial in the work arrays (table of its length): the end state, the tallies,
    /// the level states, the observation (and dense output when the force peaks inside).
    ///
    /// Tallies: the ground's work exact for the computed motion (harmonic: the closed forms
    /// of [`HarmonicTally`] with the contact quartic's extra term; records: the moments of
    /// each mode's equation of motion), the work of the contact load on the modes by the
    /// 5-node Lobatto rule on the nodal values (exact to degree 7), the dissipation from the
    /// modal energy balance; the work into the contacts with the law itself along the computed
    /// motion at the companion's Lobatto nodes, so that the energy balance measures the
    /// collocation's residual (the law against the force quartic between the nodes).
    ///
    /// A pair with one contact level takes its own path (`single`), the same arithmetic.
    #[inline(never)]
    pub(super) fn accept(&mut self, piece: &Piece, trial: Trial, t_end: f64) {
        // (the next trial starts from the new state, whichever path accepts this one)
        self.start.valid = false;
        if self.single_level() {
            return self.accept_one(piece, trial, t_end);
        }
        self.accept_general(piece, trial, t_end)
    }

    crate::numerics::vex::avx_copy! {
        /// [`Self::accept`] for any number of contact levels (its copy compiled for AVX where the
        /// processor has it: [`crate::numerics::vex`], the same bits).
        #[inline(never)]
        pub(super) fn accept_general(&mut self, piece: &Piece, trial: Trial, t_end: f64) => accept_general_vex, accept_general_body
    }

    /// [`Self::accept_general`]'s work.
    #[inline(always)]
    fn accept_general_body(&mut self, piece: &Piece, trial: Trial, t_end: f64) {
        // (the next trial starts from the new state: its start is formed again)
        self.start.valid = false;
        let (n, nl) = (self.n, self.nl);
        let h = trial.h;
        let bases = collocation::bases();
        let t0 = self.t;
        let tr0 = self.exact_trig(t0);
        // dense output: a step whose nodal forces peak inside it is also observed at its
        // interior nodes, so that the recorder's interpolant around the peak is 4× denser
        let dense = (0..nl).any(|kk| {
            let f = &self.f8[kk * 5..kk * 5 + 5];
            let inner = f[1].max(f[2]).max(f[3]);
            inner > 0.0 && inner > f[0].max(f[4])
        });
        if dense && self.row {
            // (a row's table holds its passive modes' interior-node propagators on demand)
            let slot = match trial.k {
                Some(k) => &mut self.tables[k],
                None => &mut self.scratch_table,
            };
            slot.as_deref_mut().expect("table").ensure_mid(self.sys);
        }
        let tab: &Table = match trial.k {
            Some(k) => self.tables[k].as_deref().expect("table"),
            None => self.scratch_table.as_deref().expect("table"),
        };
        let start = self.trace_start();
        let trs = self.node_trigs(tab, tr0, h);
        // per level, the contact quartic's integral and first moment (records' ground work)
        for kk in 0..nl {
            let f = &self.f8[kk * 5..kk * 5 + 5];
            let (mut a, mut b) = (0.0, 0.0);
            for p in 0..5 {
                a += WEIGHTS8[p] * f[p];
                b += bases.first[p] * f[p];
            }
            self.moments[kk] = (h * a, h * h * b);
        }
        // (a pair with several levels: every mode's weights g and moments summed level by
        // level, see `pair_loads`; the very sums of the per-mode loops below)
        let pair = self.sys.structures.len() == 2 && nl > 1 && nl <= MAX_PAIR_LEVELS;
        let mut lanes = [PairLevel::default(); MAX_PAIR_LEVELS];
        if pair {
            for (k, l) in lanes.iter_mut().enumerate().take(nl) {
                *l = PairLevel::new(&self.f8[k * 5..k * 5 + 5], self.moments[k]);
            }
        }
        let lanes = &lanes[..if pair { nl } else { 0 }];
        let gm = &self.gm;
        let harmonic = gm.harmonic_plain();
        let mut sums = StateSums::default();
        let (mut input, mut d_energy) = (0.0, 0.0);
        let (x0s, y0s) = (&self.x0[..n], &self.y0[..n]);
        let (w2s, damp, iw2) = (&gm.w2[..n], &gm.damp[..n], &gm.inv_w2[..n]);
        let modes = &tab.modes[..n];
        // (a row's levels couple to few modes and levels: see `levels_of_mode`)
        let row = self.sys.structures.len() > 2;
        // (a row, or a pair with several levels, under a recorded motion without dense
        // output: one pass over the modes, structure by structure, see `row_poly_pass`; a
        // pair's every mode is forced and couples to every level, its projections summed in
        // mode order as the pair's per-level sums below: the same bits)
        if self.row_pass && !dense && matches!(piece, Piece::Poly { .. }) {
            self.proj.iter_mut().for_each(|p| *p = (0.0, 0.0));
            (input, d_energy) = row_poly_pass(
                self.sys,
                gm,
                modes,
                (x0s, y0s, &self.q[..n], &self.v[..n]),
                (&self.pcoef[..n], &self.cpoly[..n]),
                &self.cpl_t,
                &self.mode_act,
                (&self.f8, &self.moments),
                h,
                (&mut self.q1s[..n], &mut self.v1s[..n]),
                &mut self.proj,
            );
        } else {
            // the particular solutions at the end (and at the interior nodes for dense output),
            // in a loop of their own: the piece's kind is the same for every mode
            let (pend, pmid) = (&mut self.pend[..n], &mut self.pmid[..n]);
            for j in 0..n {
                let pcoef = &self.pcoef[j];
                pend[j] = particular_at(gm, piece, harmonic, pcoef, j, h, &trs[4]);
                if dense {
                    pmid[j] = std::array::from_fn(|i| {
                        particular_at(
                            gm,
                            piece,
                            harmonic,
                            pcoef,
                            j,
                            THETA8[i + 1] * h,
                            &trs[i + 1],
                        )
                    });
                }
            }
            // the end state (and the dense output's), each level's projections of it
            let (q1s, v1s) = (&mut self.q1s[..n], &mut self.v1s[..n]);
            let proj = &mut self.proj;
            proj.iter_mut().for_each(|p| *p = (0.0, 0.0));
            let dense_out = (&mut self.dense_q[..3 * n], &mut self.dense_v[..3 * n]);
            let one = nl == 1;
            let f1: [f64; 5] = std::array::from_fn(|p| self.f8[p]);
            for j in 0..n {
                // mode j's contact load's Lagrange weights g, Σ_k c_kj F_k (one level: c_j·F)
                // (the levels whose coupling can be non-zero at mode j: of a row, its structure's
                // pairs; the others' terms are exact zeros)
                let (holding, cj) = mode_couplings(self.sys, &self.cpl_t, nl, row, j);
                // (a passive mode of a row: no contact force reaches it, its free flight is exact;
                // the terms left out are products with zeros)
                let forced = self.mode_act[j];
                let g = if !forced {
                    [0.0; 5]
                } else if pair {
                    PairLevel::weights(lanes, cj)
                } else if one {
                    let c = cj[0];
                    f1.map(|x| c * x)
                } else {
                    let mut g = [0.0; 5];
                    for (c, f) in cj.iter().zip(self.f8[holding.start * 5..].chunks_exact(5)) {
                        for p in 0..5 {
                            g[p] += c * f[p];
                        }
                    }
                    g
                };
                let ms = &modes[j];
                let (x0, y0) = (x0s[j], y0s[j]);
                let (xe, ye) = ms.end.apply(x0, y0);
                let pe = pend[j];
                let (mut q1, mut v1) = (xe + pe.0, ye + pe.1);
                if forced {
                    for p in 0..5 {
                        q1 += g[p] * ms.end8[p].0;
                        v1 += g[p] * ms.end8[p].1;
                    }
                }
                if dense {
                    for i in 0..3 {
                        let (x, y) = ms.mid[i].apply(x0, y0);
                        let pi = pmid[j][i];
                        let (mut e, mut d) = (x + pi.0, y + pi.1);
                        if forced {
                            for p in 0..5 {
                                e += g[p] * ms.mid8[i][p].0;
                                d += g[p] * ms.mid8[i][p].1;
                            }
                        }
                        dense_out.0[i * n + j] = e;
                        dense_out.1[i * n + j] = d;
                    }
                }
                q1s[j] = q1;
                v1s[j] = v1;
                if row {
                    for (c, pr) in cj.iter().zip(&mut proj[holding]) {
                        pr.0 += c * q1;
                        pr.1 += c * v1;
                    }
                }
            }
            if !row {
                // (a pair: each level's projections as one sum over the modes, in the same order
                // as the per-mode accumulation of a row above, so the same bits)
                for (k, pr) in proj.iter_mut().enumerate() {
                    let c = &self.sys.coupling(k)[..n];
                    let (mut a, mut b) = (0.0, 0.0);
                    for j in 0..n {
                        a += c[j] * q1s[j];
                        b += c[j] * v1s[j];
                    }
                    *pr = (a, b);
                }
            }
            // the tallies, one loop per kind of piece
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
                        let (gi, gt) = if pair {
                            PairLevel::moments(lanes, &self.cpl_t[j * nl..(j + 1) * nl])
                        } else if !self.mode_act[j] {
                            // (a row's passive mode: its levels carry no force over the step, so
                            // every moment is 0 and the sums below are +0 exactly)
                            (0.0, 0.0)
                        } else {
                            let (holding, cj) = mode_couplings(self.sys, &self.cpl_t, nl, row, j);
                            let (mut gi, mut gt) = (0.0, 0.0);
                            for (c, mo) in cj.iter().zip(&self.moments[holding.start..]) {
                                gi += c * mo.0;
                                gt += c * mo.1;
                            }
                            (gi, gt)
                        };
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
                (Piece::Zero, _) => {}
                _ => {
                    // harmonic motion with a mode at undamped resonance: its exact work for the
                    // contact load's chord (rare; mode_work's own trapezoid at resonance)
                    let tm = gm.harmonic_omega().map(|big| TrigMoments::new(big, t0, h));
                    for j in 0..n {
                        let (holding, cj) = mode_couplings(self.sys, &self.cpl_t, nl, row, j);
                        let mut g = [0.0; 5];
                        for (c, f) in cj.iter().zip(self.f8[holding.start * 5..].chunks_exact(5)) {
                            for p in 0..5 {
                                g[p] += c * f[p];
                            }
                        }
                        input += mode_work(
                            gm,
                            j,
                            h,
                            (q0s[j], v0s[j]),
                            (q1s[j], v1s[j]),
                            None,
                            tm.as_ref(),
                            g[0],
                            g[4] - g[0],
                        )
                        .input;
                    }
                }
            }
            // (harmonic motion: the change of energy from the harmonic sums, below)
            let harmonic_sums =
                matches!(piece, Piece::Harmonic) && self.htally.is_some() && self.big.is_some();
            if !harmonic_sums {
                for j in 0..n {
                    let (q0, v0, q1, v1) = (q0s[j], v0s[j], q1s[j], v1s[j]);
                    d_energy += 0.5 * (v1 * v1 - v0 * v0) + 0.5 * w2s[j] * (q1 * q1 - q0 * q0);
                }
            }
        }
        std::mem::swap(&mut self.q, &mut self.q1s);
        std::mem::swap(&mut self.v, &mut self.v1s);
        if let (Piece::Harmonic, Some(ht), Some(big)) = (piece, &self.htally, self.big) {
            // the ground's work: the state sums at both ends, and the contact quartic's extra
            let tm =
                TrigMoments::from_ends(big, h, (tr0.s, tr0.c), (trs[4].s, trs[4].c), tab.rot[3]);
            input = ht.input(&tm, &self.sums, &sums);
            for kk in 0..nl {
                let (k4, k5) = self.kextra[kk];
                for p in 0..5 {
                    let (a, b) = tab.hmom[p];
                    let (sp, cp) = (tr0.s * a + tr0.c * b, tr0.c * a - tr0.s * b);
                    input += self.f8[kk * 5 + p] * (k4 * sp + k5 * cp);
                }
            }
            d_energy = sums.energy - self.sums.energy;
        }
        self.sums = sums;
        self.psums_ok = false;
        // the contact load's work on the modes (Lobatto, 5 nodes), and the work into the
        // contacts with the law along the motion (the 7-point rule on every point of the step
        // whose state is known: the law against the force quartic between the nodes)
        let mut modal = 0.0;
        let mut law = 0.0;
        // (the levels whose five nodal forces are all zero: a row's edge and passive levels,
        // and solved ones out of contact over the step; their terms below subtract products
        // with zeros, which leave the sums as they are)
        for (l, live) in self.live.iter_mut().enumerate() {
            *live = self.f8[l * 5..l * 5 + 5].iter().any(|&f| f != 0.0);
        }
        // (a row's passive levels: no force, δ ≤ 0 along the step, no work)
        for &kk in &self.lv_seen {
            let f = &self.f8[kk * 5..kk * 5 + 5];
            let mut pw = WEIGHTS8[0] * f[0] * self.states[kk].delta_dot;
            for p in 1..5 {
                pw += WEIGHTS8[p] * f[p] * self.nodal8[kk * 4 + p - 1].1;
            }
            modal -= h * pw;
            let lv = &self.sys.levels[kk];
            let v0 = |dd: f64| episode_v0(self.onset[kk], dd);
            let power = |(d, dd): (f64, f64)| lv.force.force(d, dd, v0(dd)) * dd;
            // (the start: the law's right limit at a located onset, as the step used)
            let w7 = &bases.seven;
            let mut lw = w7[0] * f[0] * self.states[kk].delta_dot;
            for (i, node) in [(1, 0), (3, 1), (5, 2), (6, 3)] {
                lw += w7[i] * power(self.nodal8[kk * 4 + node]);
            }
            for (i, slot) in [(2, 0), (4, 1)] {
                let (mut d, mut dd) = self.dfree[kk * 6 + slot];
                // (the levels sharing no structure with kk weigh exactly 0)
                let band = if row {
                    self.sys.sharing_levels(kk)
                } else {
                    0..nl
                };
                for l in band {
                    if !self.live[l] {
                        continue;
                    }
                    let base = (self.sys.band_slot(kk, l) * 2 + slot) * 5;
                    for p in 0..5 {
                        let (a, b) = tab.w86[base + p];
                        d -= a * self.f8[l * 5 + p];
                        dd -= b * self.f8[l * 5 + p];
                    }
                }
                lw += w7[i] * power((d, dd));
            }
            law += h * lw;
        }
        let damping = input + modal - d_energy;
        self.energy += d_energy;
        if dense {
            self.observe_dense(h, t0, (input, damping, law));
        }
        self.tally.input += input;
        self.tally.damping += damping;
        self.tally.contact += law;
        // (the impulse: the force quartic's integral, exact)
        for kk in 0..nl {
            self.tally.impulse[kk] += self.moments[kk].0;
        }
        self.last_f8.copy_from_slice(&self.f8);
        self.t = t_end;
        self.contact_t_end = t_end;
        self.prev_states.copy_from_slice(&self.states);
        for kk in 0..nl {
            let (cq, cv) = self.proj[kk];
            self.set_state(kk, cq, cv);
        }
        update_onsets(&mut self.onset, &self.prev_states, &self.states, h);
        for kk in 0..nl {
            if self.onset[kk] == 0.0 && Self::at_onset(&self.states[kk]) {
                self.onset[kk] = self.states[kk].delta_dot;
            }
            let st = &self.states[kk];
            if st.delta > 0.0 {
                let kt = self.sys.levels[kk].force.tangent_stiffness(st.delta);
                self.max_contact_w2h2 = self.max_contact_w2h2.max(kt * self.inv_mstar[kk] * h * h);
            }
        }
        self.close_contact_step(t0, h, t_end, trs[4], start, trial.err);
    }

    /// The state at a step's start, kept only when the steps are traced (tests).
    pub(super) fn trace_start(&self) -> Option<(Vec<f64>, Vec<f64>, Vec<f64>)> {
        self.trace
            .is_some()
            .then(|| (self.q.clone(), self.v.clone(), self.onset.clone()))
    }

    /// sin, cos of the harmonic ground motion at the 5-node scheme's nodes (start, B1, ½, B3,
    /// end) of a step of length h from `tr0`: rotations by the table's angles when the motion
    /// is harmonic, else direct.
    pub(super) fn node_trigs(&self, tab: &Table, tr0: Trig, h: f64) -> [Trig; 5] {
        std::array::from_fn(|p| self.node_trig(tab, tr0, h, p))
    }

    /// [`Self::node_trigs`] at node p (0: start … 4: end) only.
    #[inline(always)]
    pub(super) fn node_trig(&self, tab: &Table, tr0: Trig, h: f64, p: usize) -> Trig {
        let t0 = tr0.t;
        if p == 0 {
            tr0
        } else if self.big.is_some() {
            let (sh, ch) = tab.rot[NODES8[p - 1]];
            Trig {
                t: t0 + THETA8[p] * h,
                s: tr0.s * ch + tr0.c * sh,
                c: tr0.c * ch - tr0.s * sh,
            }
        } else {
            self.gm.trig(t0 + THETA8[p] * h)
        }
    }

    /// What every accepted contact step does last, whatever its path: the step's length kept
    /// for the next while in contact, the clock of sin Ωt, cos Ωt, the trace (tests) and the
    /// observation.
    pub(super) fn close_contact_step(
        &mut self,
        t0: f64,
        h: f64,
        t_end: f64,
        end_trig: Trig,
        start: Option<(Vec<f64>, Vec<f64>, Vec<f64>)>,
        err: f64,
    ) {
        self.last_h = if self.in_contact() { h } else { 0.0 };
        self.stats.steps += 1;
        // sin, cos at the end: the rotation to the end node (trs[4]), evaluated directly
        // every SYNC_CONTACT steps and where the end was snapped to a span's end (the
        // rotations' rounding, about an ulp each, cannot accumulate)
        self.contact_sync += 1;
        if self.big.is_some() && self.contact_sync < SYNC_CONTACT && t_end == t0 + h {
            self.trig_memo = Trig {
                t: t_end,
                ..end_trig
            };
        } else {
            self.contact_sync = 0;
        }
        self.trig_now = self.exact_trig(self.t);
        self.since_sync = 1;
        if let (Some(trace), Some((q0, v0, onset))) = (self.trace.as_mut(), start) {
            // (a row's passive levels: their free flight's end, both schemes')
            let companion = (0..self.nl)
                .map(|kk| {
                    let p = self.sys.levels[kk].pair;
                    if self.act[p] || self.act[p + 1] {
                        self.nodal6[kk * 3 + 2]
                    } else {
                        (self.states[kk].delta, self.states[kk].delta_dot)
                    }
                })
                .collect();
            trace.push(StepTrace {
                t: t0,
                h,
                q0,
                v0,
                onset,
                q1: self.q.clone(),
                v1: self.v.clone(),
                err,
                kink: self.kink,
                z0: Vec::new(),
                z1: Vec::new(),
                companion,
            });
        }
        self.observe_step();
    }
}

/// Contact steps between direct evaluations of sin Ωt, cos Ωt (rotations in between).
const SYNC_CONTACT: u32 = 16;

/// The most contact levels of a pair whose accepted steps take [`PairLevel`]'s sums (more
/// take the per-mode loops over the levels; the same sums).
const MAX_PAIR_LEVELS: usize = 8;

/// One contact level of a pair in the accepted step, its forces and moments laid out for the
/// sums over the levels of a mode's contact load weights `g_p = Σ_k c_kj F_kp` and moments
/// `Σ_k c_kj (∫F_k, ∫τF_k)`: two weights (or both moments) to a vector operation, each sum
/// starting at 0 and adding the levels in order, as the per-mode loops of
/// [`Elastic::accept_general`] do — the same bits.
#[derive(Clone, Copy)]
struct PairLevel {
    f01: F2,
    f23: F2,
    f4: f64,
    mo: F2,
}

impl Default for PairLevel {
    fn default() -> PairLevel {
        PairLevel {
            f01: F2::zero(),
            f23: F2::zero(),
            f4: 0.0,
            mo: F2::zero(),
        }
    }
}

impl PairLevel {
    /// From the level's five nodal forces and its moments.
    #[inline(always)]
    fn new(f: &[f64], (m0, m1): (f64, f64)) -> PairLevel {
        PairLevel {
            f01: F2::new(f[0], f[1]),
            f23: F2::new(f[2], f[3]),
            f4: f[4],
            mo: F2::new(m0, m1),
        }
    }

    /// `g_p = Σ_k c_kj F_kp` of a mode whose couplings to the levels are `cj`.
    #[inline(always)]
    fn weights(levels: &[PairLevel], cj: &[f64]) -> [f64; 5] {
        let (mut a, mut b, mut e) = (F2::zero(), F2::zero(), 0.0);
        for (l, &c) in levels.iter().zip(cj) {
            let cc = F2::splat(c);
            a = a + cc * l.f01;
            b = b + cc * l.f23;
            e += c * l.f4;
        }
        let ([g0, g1], [g2, g3]) = (a.get(), b.get());
        [g0, g1, g2, g3, e]
    }

    /// `Σ_k c_kj (∫F_k, ∫τF_k)` of a mode whose couplings to the levels are `cj`.
    #[inline(always)]
    fn moments(levels: &[PairLevel], cj: &[f64]) -> (f64, f64) {
        let mut m = F2::zero();
        for (l, &c) in levels.iter().zip(cj) {
            m = m + F2::splat(c) * l.mo;
        }
        let [gi, gt] = m.get();
        (gi, gt)
    }
}

/// Mode j's levels whose coupling can be non-zero (of a row, its structure's pairs, see
/// [`System::levels_of_mode`]; otherwise every level) and those couplings, from the transposed
/// coupling table `cpl_t` (`nl` levels per mode). The other levels' terms are exact zeros.
#[inline]
fn mode_couplings<'c>(
    sys: &System,
    cpl_t: &'c [f64],
    nl: usize,
    row: bool,
    j: usize,
) -> (std::ops::Range<usize>, &'c [f64]) {
    let holding = if row { sys.levels_of_mode(j) } else { 0..nl };
    let cj = &cpl_t[j * nl + holding.start..j * nl + holding.end];
    (holding, cj)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`PairLevel`]'s sums are the per-mode loops' over the levels bit for bit (each weight and
    /// moment from 0, the levels in order): one to eight levels, couplings of both signs and
    /// zeros, forces and moments that round, a zero level among them.
    #[test]
    fn pair_level_sums_are_the_per_mode_loops() {
        for nl in 1..=MAX_PAIR_LEVELS {
            for j in 0..40usize {
                let cj: Vec<f64> = (0..nl)
                    .map(|k| match (j + 3 * k) % 7 {
                        0 => 0.0,
                        r => {
                            ((r * 13 + j) as f64).sqrt()
                                * if (j + k) % 2 == 0 { 1.0 } else { -1e-3 }
                        }
                    })
                    .collect();
                let f8: Vec<f64> = (0..5 * nl)
                    .map(|i| {
                        if i / 5 == 1 {
                            0.0
                        } else {
                            1e6 / (i as f64 + 0.37)
                        }
                    })
                    .collect();
                let moments: Vec<(f64, f64)> = (0..nl)
                    .map(|k| (1.0 / (k as f64 + 1.3), -1e-3 / (k as f64 + 2.9)))
                    .collect();
                let lanes: Vec<PairLevel> = (0..nl)
                    .map(|k| PairLevel::new(&f8[k * 5..k * 5 + 5], moments[k]))
                    .collect();
                let mut g = [0.0; 5];
                let (mut gi, mut gt) = (0.0, 0.0);
                for (c, f) in cj.iter().zip(f8.chunks_exact(5)) {
                    for p in 0..5 {
                        g[p] += c * f[p];
                    }
                }
                for (c, mo) in cj.iter().zip(&moments) {
                    gi += c * mo.0;
                    gt += c * mo.1;
                }
                let got = PairLevel::weights(&lanes, &cj);
                assert_eq!(
                    got.map(f64::to_bits),
                    g.map(f64::to_bits),
                    "nl {nl}, mode {j}"
                );
                let (a, b) = PairLevel::moments(&lanes, &cj);
                assert_eq!((a.to_bits(), b.to_bits()), (gi.to_bits(), gt.to_bits()));
            }
        }
    }
}
