//! The contact phase of [`Elastic`]: the step controller (quantised lengths, dyadic alignment,
//! tables) and one trial of the collocation pair with its error estimate; the accepted step is
//! `accept`'s, a pair's single contact level takes `single`'s path.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::*;
use crate::numerics::lanes::F2;

impl<'a, O: Observer> Elastic<'a, O> {
    // ---------------------------------------------------------------- contact

    /// The contact steps' position on the piece's dyadic grid at the current time: the walk the
    /// last contact step left (while the time is still where that step ended, in the same
    /// piece), else the time located on the grid of the current level or of one up to 20 finer
    /// (to 1e-9 of a point: the time comes from a free flight that ended on the grid by float
    /// arithmetic, or from the piece's start), else none (off the grid: an onset located
    /// between its points, or the end of an event).
    pub(super) fn walk_here(&self, pstart: f64, hh: f64) -> Option<GridWalk> {
        if let Some(w) = self.walk
            && w.t == self.t
            && w.start == pstart
        {
            return Some(w);
        }
        let top = MAX_LEVEL.min(self.m_step + 20);
        let mut m = self.m_step.min(MAX_LEVEL);
        loop {
            let x = (self.t - pstart) / (hh / (1u64 << m) as f64);
            if (x - x.round()).abs() <= 1e-9 * x.abs().max(1.0) {
                return Some(GridWalk::at(pstart, self.t, x.round() as u128, m));
            }
            if m >= top {
                return None;
            }
            m += 1;
        }
    }

    /// A recorded motion's next contact step from the walk `here` (see [`Self::walk_here`]):
    /// hh/2^m at the current level, or at a finer one where only that is a grid point (cached
    /// table `DYADIC + m`), else a one-off length to the next point of the current level's
    /// grid (after an onset or an event: the entry step back onto the grid), with the walk at
    /// that point. `steps`: the piece's number of grid steps hh.
    pub(super) fn dyadic_length(
        &self,
        here: Option<GridWalk>,
        (pstart, hh, steps): (f64, f64, u64),
        span_end: f64,
    ) -> (Option<usize>, f64, Option<GridWalk>) {
        let m = self.m_step.min(MAX_LEVEL);
        let next = match here {
            Some(w) if w.base >= steps => return (None, span_end - self.t, None),
            Some(w) => {
                let top = MAX_LEVEL.min(self.m_step + 20);
                let mut lm = m;
                while !w.walk.aligned(lm as u32) && lm < top {
                    lm += 1;
                }
                if w.walk.aligned(lm as u32) {
                    return (Some(DYADIC + lm), hh / (1u64 << lm) as f64, None);
                }
                w.next_point(m)
            }
            None => ((self.t - pstart) / (hh / (1u64 << m) as f64)).floor() as u128 + 1,
        };
        let end = GridWalk::at(pstart, f64::NAN, next, m);
        if next >= (steps as u128) << m {
            return (None, span_end - self.t, Some(end));
        }
        let t_next = pstart + next as f64 * (hh / (1u64 << m) as f64);
        (None, t_next - self.t, Some(end))
    }

    /// Quantised step length `dt·2^(−k/4)` (from the table of them: no libm call per step).
    #[inline]
    pub(super) fn length(&self, k: usize) -> f64 {
        self.lengths[k.min(MAX_K)]
    }

    /// Smallest k whose length is ≤ h.
    pub(super) fn quantise(&self, h: f64) -> usize {
        if h >= self.dt {
            return 0;
        }
        let k = (QUANT * (self.dt / h).log2()).ceil();
        if k.is_finite() {
            (k.max(0.0) as usize).min(MAX_K)
        } else {
            MAX_K
        }
    }

    /// The table of step length h (`k`: its quantised index, or `None` for a one-off length),
    /// with the active structures' responses to the contact loads (see [`Table::fill_for`]).
    pub(super) fn table(&mut self, k: Option<usize>, h: f64) -> &Table {
        let (sys, big, act) = (self.sys, self.big, &self.act);
        // (a cached length's table is kept as made: a record's sample intervals are equal to
        // rounding, and so are their tables)
        let (slot, keep) = match k {
            Some(k) => (&mut self.tables[k], true),
            None => (&mut self.scratch_table, false),
        };
        match slot {
            Some(t) if keep || t.h == h => t.ensure(sys, act),
            Some(t) => t.fill_for(sys, big, h, act),
            None => *slot = Some(Box::new(Table::new_for(sys, big, h, act))),
        }
        slot.as_deref().expect("table")
    }

    /// One trial of a contact step of length h from the current state (`k`: its quantised
    /// index): the free flight to the nodes, both collocations, the estimate. Of a row, a trial
    /// that reaches a level at the edge of the active structures is redone with that level's
    /// other structure active ([`Self::promote_edges`]).
    pub(super) fn trial(
        &mut self,
        k: Option<usize>,
        h: f64,
        piece: &Piece,
    ) -> Result<Trial, NoConvergence> {
        loop {
            let trial = self.trial_once(k, h, piece)?;
            if !self.promote_edges() {
                return Ok(trial);
            }
        }
    }

    /// One trial without the edges' promotion: a pair with one contact level takes its own
    /// path (`single`, the same arithmetic on stack arrays), anything else the general one.
    #[inline]
    fn trial_once(
        &mut self,
        k: Option<usize>,
        h: f64,
        piece: &Piece,
    ) -> Result<Trial, NoConvergence> {
        if self.single_level() {
            return self.trial_one(k, h, piece);
        }
        self.trial_general(k, h, piece)
    }

    crate::numerics::vex::avx_copy! {
        /// [`Self::trial`] for any number of contact levels (its copy compiled for AVX where the
        /// processor has it: [`crate::numerics::vex`], the same bits).
        pub(super) fn trial_general(
            &mut self,
            k: Option<usize>,
            h: f64,
            piece: &Piece,
        ) -> Result<Trial, NoConvergence> => trial_general_vex, trial_general_body
    }

    /// [`Self::trial_general`]'s work.
    #[inline(always)]
    fn trial_general_body(
        &mut self,
        k: Option<usize>,
        h: f64,
        piece: &Piece,
    ) -> Result<Trial, NoConvergence> {
        let (n, nl) = (self.n, self.nl);
        let sys = self.sys;
        let t0 = self.t;
        let tr0 = self.exact_trig(t0);
        self.table(k, h);
        let tab: &Table = match k {
            Some(k) => self.tables[k].as_deref().expect("table"),
            None => self.scratch_table.as_deref().expect("table"),
        };
        debug_assert_eq!(tab.modes(), n);
        self.stats.evaluations += 1;
        // free flight to the nodes projected on the levels: per mode its homogeneous part at
        // the start, then two dot products per node and level with the coupled propagators;
        // the particular solutions' projections come per level
        self.dfree.iter_mut().for_each(|d| *d = (0.0, 0.0));
        let (q, v) = (&self.q[..n], &self.v[..n]);
        let (x0s, y0s) = (&mut self.x0[..n], &mut self.y0[..n]);
        let gm = &self.gm;
        match (piece, gm.harmonic_plain()) {
            (Piece::Harmonic, Some((big, g_re, g_im))) => {
                for j in 0..n {
                    let (gr, gi) = (g_re[j], g_im[j]);
                    x0s[j] = q[j] - (gr * tr0.s + gi * tr0.c);
                    y0s[j] = v[j] - big * (gr * tr0.c - gi * tr0.s);
                }
                let (gk, dfree) = (&self.gk[..nl], &mut self.dfree[..6 * nl]);
                for i in 0..6 {
                    let (sh, ch) = tab.rot[i];
                    let (sn, cn) = (tr0.s * ch + tr0.c * sh, tr0.c * ch - tr0.s * sh);
                    for (&(gre, gim), df) in gk.iter().zip(dfree.chunks_exact_mut(6)) {
                        df[i] = (-(sn * gre + cn * gim), -big * (cn * gre - sn * gim));
                    }
                }
            }
            (Piece::Poly { .. }, _) => {
                // particular solution A + Bτ + Cτ² per mode, projected per level (the trials
                // of one step start from the same state at the same instant: what depends on
                // the start alone is formed at its first trial and kept, see `start`)
                let wide = nl > self.start.narrow.len();
                if !self.start.valid {
                    let (cpoly, pcoef) = (&mut self.cpoly[..n], &mut self.pcoef[..n]);
                    let (iw2, damp) = (&gm.inv_w2[..n], &gm.damp[..n]);
                    let cpl = &self.cpl_t[..n * nl];
                    self.start.narrow = start_poly_pass(
                        (gm, piece, t0),
                        (iw2, damp),
                        (q, v),
                        (cpl, if wide { 0 } else { nl }),
                        (cpoly, pcoef),
                        (x0s, y0s),
                    );
                    self.start.wide_ok.iter_mut().for_each(|ok| *ok = false);
                    self.start.valid = true;
                }
                for ki in 0..self.lv_seen.len() {
                    let k = self.lv_seen[ki];
                    let [a, b, c] = if wide {
                        if !self.start.wide_ok[k] {
                            // (over the level's pair's modes: c_kj = 0 elsewhere)
                            let ck = sys.coupling(k);
                            let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
                            for j in sys.coupling_modes(k) {
                                a += ck[j] * self.pcoef[j][0];
                                b += ck[j] * self.pcoef[j][1];
                                c += ck[j] * self.pcoef[j][2];
                            }
                            self.start.wide[k] = [a, b, c];
                            self.start.wide_ok[k] = true;
                        }
                        self.start.wide[k]
                    } else {
                        self.start.narrow[k]
                    };
                    for i in 0..6 {
                        let tau = NODES[i] * h;
                        self.dfree[k * 6 + i] = (-(a + tau * (b + tau * c)), -(b + 2.0 * tau * c));
                    }
                }
            }
            (Piece::Zero, _) => {
                x0s.copy_from_slice(q);
                y0s.copy_from_slice(v);
            }
            _ => {
                // harmonic motion with a mode at undamped resonance: every particular solution
                // at every node
                let zero = [0.0; 3];
                let tr_start = gm.trig(t0);
                for j in 0..n {
                    let (e0, d0) = gm.particular(j, piece, &zero, 0.0, &tr_start);
                    x0s[j] = q[j] - e0;
                    y0s[j] = v[j] - d0;
                }
                for i in 0..6 {
                    let tr = gm.trig(t0 + NODES[i] * h);
                    for j in 0..n {
                        let (e, d) = gm.particular(j, piece, &zero, NODES[i] * h, &tr);
                        for k in 0..nl {
                            let ck = self.cpl_t[j * nl + k];
                            self.dfree[k * 6 + i].0 -= ck * e;
                            self.dfree[k * 6 + i].1 -= ck * d;
                        }
                    }
                }
            }
        }
        // the homogeneous parts: Σ_j c_kj P(θh)(x0, y0)
        let (x0s, y0s) = (&self.x0[..n], &self.y0[..n]);
        for &k in &self.lv_seen {
            // one pass over the modes for all six nodes (each mode's start read once; every
            // node's sum still runs over the modes in order, so the sums are the same bit
            // for bit); over the level's pair's modes only: the row's others have c_kj = 0
            // (each node's (δ, δ̇) sums in the two lanes of one register: lane 0 adds
            // a·x + b·y, lane 1 c·x + e·y, the very operations of the scalar sums)
            let r = sys.coupling_modes(k);
            let (xs, ys) = (&x0s[r.clone()], &y0s[r]);
            #[cfg(target_arch = "x86_64")]
            let acc = if crate::numerics::vex::available() {
                // SAFETY: the processor has AVX
                unsafe { node_sums::node_sums_avx(tab.cprop_pairs(sys, k), xs, ys) }
            } else {
                node_sums::node_sums(tab.cprop_rows(sys, k), xs, ys)
            };
            #[cfg(not(target_arch = "x86_64"))]
            let acc = node_sums::node_sums(tab.cprop_rows(sys, k), xs, ys);
            // the sums hold −c·η; δ = −c·η − d through the one penetration (−(−s) is s
            // exactly, so this is the former `s − d` bit for bit)
            let lv = &sys.levels[k];
            let df: &mut [(f64, f64); 6] = (&mut self.dfree[k * 6..k * 6 + 6])
                .try_into()
                .expect("six nodes");
            for (x, s) in df.iter_mut().zip(acc) {
                x.0 = lv.delta(-(x.0 - s.0));
                x.1 -= s.1;
            }
            let d8: &mut [(f64, f64); 4] = (&mut self.d8free[k * 4..k * 4 + 4])
                .try_into()
                .expect("four nodes");
            *d8 = NODES8.map(|node| df[node]);
            let d6: &mut [(f64, f64); 3] = (&mut self.d6free[k * 3..k * 3 + 3])
                .try_into()
                .expect("three nodes");
            *d6 = NODES6.map(|node| df[node]);
        }
        // the propagated scheme: start forces, a first guess from the last step's quartic
        let bases = collocation::bases();
        let contiguous = self.last_h > 0.0;
        let ratio = h / self.last_h;
        for &k in &self.lv_solve {
            let f0 = collocation::start_force(sys, k, &self.states[k], self.onset[k], EVENT_TOL);
            let prev: [f64; 5] = std::array::from_fn(|p| self.last_f8[k * 5 + p]);
            self.f8[k * 5] = f0;
            for p in 1..5 {
                self.f8[k * 5 + p] = if contiguous {
                    bases.quartic_at(&prev, 1.0 + THETA8[p] * ratio).max(0.0)
                } else {
                    f0
                };
            }
        }
        collocation::solve::<5>(
            sys,
            &tab.w8,
            &self.d8free,
            &self.onset,
            &mut self.f8,
            &mut self.nodal8,
            &mut self.newton,
            self.newton_tol,
            &self.lv_solve,
        )?;
        // the companion, from the propagated quartic at its nodes
        for &k in &self.lv_solve {
            let vals: [f64; 5] = std::array::from_fn(|p| self.f8[k * 5 + p]);
            let at = |i: usize| (0..5).map(|p| bases.at6[i][p] * vals[p]).sum::<f64>();
            self.f6[k * 4] = vals[0];
            self.f6[k * 4 + 1] = at(0);
            self.f6[k * 4 + 2] = at(1);
            self.f6[k * 4 + 3] = vals[4];
        }
        collocation::solve::<4>(
            sys,
            &tab.w6,
            &self.d6free,
            &self.onset,
            &mut self.f6,
            &mut self.nodal6,
            &mut self.newton,
            self.newton_tol,
            &self.lv_solve,
        )?;
        // the estimate: the two ends' distance on every level's δ and δ̇
        let tol = self.tol;
        let mut err = 0.0f64;
        if self.row {
            // (the edge levels' nodal states: their estimate, and whether the step reaches them)
            collocation::nodal_states::<5>(
                sys,
                &tab.w8,
                &self.d8free,
                &self.f8,
                &mut self.nodal8,
                &self.lv_edge,
            );
            collocation::nodal_states::<4>(
                sys,
                &tab.w6,
                &self.d6free,
                &self.f6,
                &mut self.nodal6,
                &self.lv_edge,
            );
        }
        for &k in &self.lv_seen {
            let st = &self.states[k];
            let (a, b) = (self.nodal8[k * 4 + 3], self.nodal6[k * 3 + 2]);
            let w = (st.delta + sys.levels[k].gap).abs();
            let rate = st.delta_dot.abs().max(self.onset[k]);
            err = err
                .max((a.0 - b.0).abs() / (tol.atol + tol.rtol * w))
                .max((a.1 - b.1).abs() / (tol.atol_rate + tol.rtol * rate));
        }
        if !err.is_finite() {
            return Err(NoConvergence);
        }
        Ok(Trial { err, h, k })
    }

    /// The failure of the contact steps at the shortest length.
    pub(super) fn unreachable(&self, err: f64, h: f64) -> SolveError {
        if err.is_finite() {
            SolveError::ToleranceUnreachable {
                t: self.t,
                h,
                rtol: self.tol.rtol,
            }
        } else {
            SolveError::Diverged {
                t: self.t,
                contact_omega_dt: self.max_contact_w2h2.sqrt(),
            }
        }
    }

    crate::numerics::vex::avx_copy! {
        /// One accepted contact step from the current state, retried shorter until its estimate
        /// passes; a step in which a level's δ changes sign (an onset, a release) ends there.
        #[inline(never)]
        pub(super) fn contact_step(&mut self) -> Result<(), SolveError> => contact_step_vex, contact_step_body
    }

    /// [`Self::contact_step`]'s work.
    #[inline(always)]
    fn contact_step_body(&mut self) -> Result<(), SolveError> {
        let (piece, pstart, span_end) = self.piece();
        let limit = span_end - self.t;
        if limit <= 0.0 {
            self.t = span_end;
            return Ok(());
        }
        // (a row: the structures this step carries, see `active`)
        self.update_active(&piece, span_end);
        // (this step's trials all start here: their common start is formed once)
        self.start.valid = false;
        // a recorded motion: dyadic parts of the piece's grid step (see DYADIC)
        let dyadic = matches!(piece, Piece::Poly { .. });
        let plan = EqualSteps::new(pstart, span_end, self.dt);
        let (hh, steps) = (plan.h, plan.steps as u64);
        // (a record's sample intervals are equal to rounding: their tables are the same)
        if dyadic && (hh - self.dyadic_hh).abs() > 1e-12 * hh || self.dyadic_hh.is_nan() {
            self.dyadic_hh = hh;
            for t in &mut self.tables[DYADIC..] {
                *t = None;
            }
        }
        // the first step of an episode starts near the size the last onset needed
        let starting = self.last_h == 0.0;
        if starting && let Some(k) = self.k_onset {
            self.k_step = k.saturating_sub(1);
        }
        if starting && let Some(m) = self.m_onset {
            self.m_step = m.saturating_sub(1);
        }
        let mut rejected = false;
        loop {
            // (a recorded motion: where the walk stands, and where a one-off step takes it)
            let (mut here, mut entry) = (None, None);
            let (k, h) = if dyadic {
                here = self.walk_here(pstart, hh);
                let (id, h, end) = self.dyadic_length(here, (pstart, hh, steps), span_end);
                if let Some(id) = id {
                    self.m_step = id - DYADIC;
                }
                entry = end;
                (id, h)
            } else {
                let hq = self.length(self.k_step);
                if hq >= limit * (1.0 - 1e-9) {
                    (None, limit)
                } else {
                    (Some(self.k_step), hq)
                }
            };
            let mut trial = self.trial(k, h, &piece).unwrap_or(Trial {
                err: f64::INFINITY,
                h,
                k,
            });
            // a level's δ changes sign inside (an onset, a release): the estimate sees the
            // kink of the law there, so a step that passes is kept; one that fails is redone
            // once to end at the event as the failed trial's nodes place it (a step that ends
            // a little short or past it straddles a kink too small to fail the estimate)
            self.kink = false;
            // a kink of the law inside contact is one the two schemes err on alike (the
            // estimate can miss it by several times): such a step always ends there
            if trial.err.is_finite()
                && let Some((lev, th, scale)) = self.law_kink_inside(h)
            {
                trial = self.locate_kink(&piece, h, lev, th, scale);
                self.kink = true;
            } else if trial.err > 1.0
                && trial.err.is_finite()
                && let Some(th) = self.event_inside(h)
                && th > 1e-6
            {
                // (the largest cached length short of it: no table to compute, and the next
                // step straddles the event by at most a fifth (dyadic: a half) of this one)
                let (kq, s) = if dyadic && k.is_some() {
                    let more = (1.0 / th).log2().ceil().max(1.0) as usize;
                    let m = (self.m_step + more).min(MAX_LEVEL);
                    (DYADIC + m, hh / (1u64 << m) as f64)
                } else {
                    let kq = self.quantise(th * h);
                    (kq, self.length(kq))
                };
                trial = self.trial(Some(kq), s, &piece).unwrap_or(Trial {
                    err: f64::INFINITY,
                    h: s,
                    k: Some(kq),
                });
                self.stats.events += 1;
                self.kink = true;
            }
            if trial.err > 1.0 {
                self.stats.rejected += 1;
                rejected = true;
                self.progress
                    .rejected(self.sys, &self.states, self.t, trial.h)?;
                // (a step over an onset or a release, or near one, errs like h^{3/2 + 2}: a
                // failed step is cut as if the order were 4, not 7)
                let fac = if trial.err.is_finite() {
                    (0.9 * trial.err.powf(-0.25)).clamp(0.1, 0.9)
                } else {
                    0.5
                };
                if dyadic {
                    // (halvings as many as the factor asks for, at least one)
                    let more = (1.0 / fac).log2().ceil().max(1.0) as usize;
                    let m = match trial.k {
                        Some(id) if id >= DYADIC => id - DYADIC,
                        _ => self.m_step,
                    };
                    self.m_step = (m.max(self.m_step) + more).min(MAX_LEVEL + 1);
                    if self.m_step > MAX_LEVEL {
                        return Err(self.unreachable(trial.err, trial.h));
                    }
                    continue;
                }
                let next = self.quantise(trial.h * fac).max(self.k_step + 1);
                if next >= MAX_K {
                    return Err(self.unreachable(trial.err, trial.h));
                }
                self.k_step = next;
                continue;
            }
            if starting {
                self.k_onset = Some(self.quantise(trial.h));
                self.m_onset = Some(self.m_step);
            }
            // where the step leaves the walk: a dyadic step advances it, the planned one-off
            // step enters the grid at its next point; one cut short at an event leaves it
            let after = match (trial.k, here) {
                (Some(id), Some(w)) if dyadic && id >= DYADIC => Some(w.advance(id - DYADIC)),
                (None, _) if dyadic && !self.kink && trial.h == h => entry,
                _ => None,
            };
            let t_end = if trial.h == limit {
                span_end
            } else if dyadic && let Some(id) = trial.k.filter(|&id| id >= DYADIC) {
                // (on the dyadic grid: the end's time from the walk's integer position, not
                // by accumulation)
                let m = id - DYADIC;
                let end = after.map_or(u128::MAX, |w| w.point(m));
                if end >= (steps as u128) << m {
                    span_end
                } else {
                    pstart + end as f64 * (hh / (1u64 << m) as f64)
                }
            } else {
                self.t + trial.h
            };
            self.progress
                .accepting(self.sys, &self.states, self.t, t_end, trial.h)?;
            self.force_contact = false;
            self.accept(&piece, trial, t_end);
            self.walk = after.map(|w| GridWalk { t: self.t, ..w });
            // next length from the estimate (err ∝ h⁷); no growth right after a rejection.
            // (A PI controller's damped factors, mostly below 2^(1/4), would be rounded away
            // by the quantised lengths.)
            if trial.k.is_some() {
                let mut fac = (0.9 * trial.err.max(1e-12).powf(-1.0 / ORDER)).clamp(0.2, 3.0);
                if rejected {
                    fac = fac.min(1.0);
                }
                if dyadic {
                    // the level for the new length, coarser only where the end is aligned
                    let want = (hh / (trial.h * fac)).log2().ceil().max(0.0) as usize;
                    let mut m = self.m_step;
                    if want > m {
                        m = want.min(MAX_LEVEL);
                    } else {
                        while m > want && self.walk.is_some_and(|w| w.walk.aligned(m as u32 - 1)) {
                            m -= 1;
                        }
                    }
                    self.m_step = m;
                } else {
                    self.k_step = self.quantise(trial.h * fac);
                }
            }
            return self.check_finite();
        }
    }
}

/// What a recorded motion's contact step formed from its start alone, at its first trial:
/// each mode's ground load `c` (`cpoly`), its particular solution's coefficients (A, B, C)
/// (`pcoef`) and its homogeneous start (x0, y0) = (η − A, η̇ − B), and the first `narrow`
/// levels' projections Σ_j c_kj (A, B, C)_j (returned; `cpl`: the transposed couplings, `nl`
/// levels a mode; `narrow` ≤ 8, 0 when the levels' sums are formed level by level instead).
/// The modes two at a time in the lanes of [`F2`] (an odd one last, alone): each lane the
/// scalar operations of `poly_coefficients`, each level's sums over the modes in mode order
/// (lane 0's mode, then lane 1's), from zero: the same bits as one mode at a time.
#[inline(always)]
fn start_poly_pass(
    (gm, piece, t0): (&GroundModes, &Piece, f64),
    (iw2, damp): (&[f64], &[f64]),
    (q, v): (&[f64], &[f64]),
    (cpl, narrow): (&[f64], usize),
    (cpoly, pcoef): (&mut [[f64; 3]], &mut [[f64; 3]]),
    (x0s, y0s): (&mut [f64], &mut [f64]),
) -> [[f64; 3]; 8] {
    let n = cpoly.len();
    let nl = cpl.len().checked_div(n).unwrap_or(0);
    let narrow = narrow.min(8);
    // (A and B of each level's sums in the two lanes of one register, C alone)
    let mut ab = [F2::zero(); 8];
    let mut cs = [0.0f64; 8];
    let pairs = n / 2;
    for jj in 0..pairs {
        let j = 2 * jj;
        let (ca, cb) = (gm.poly_load(j, piece, t0), gm.poly_load(j + 1, piece, t0));
        (cpoly[j], cpoly[j + 1]) = (ca, cb);
        let [c0, c1, c2] = [0, 1, 2].map(|i| F2::new(ca[i], cb[i]));
        let (iw, d) = (F2::new(iw2[j], iw2[j + 1]), F2::new(damp[j], damp[j + 1]));
        // (`poly_coefficients`, lane by lane)
        let cc = c2 * iw;
        let b = (c1 - F2::splat(2.0) * d * cc) * iw;
        let a = (c0 - d * b - F2::splat(2.0) * cc) * iw;
        let ([pa, qa], [pb, qb], [pc, qc]) = (a.get(), b.get(), cc.get());
        pcoef[j] = [pa, pb, pc];
        pcoef[j + 1] = [qa, qb, qc];
        let x0 = F2::new(q[j], q[j + 1]) - a;
        let y0 = F2::new(v[j], v[j + 1]) - b;
        [x0s[j], x0s[j + 1]] = x0.get();
        [y0s[j], y0s[j + 1]] = y0.get();
        let (sa, sb) = (F2::new(pa, pb), F2::new(qa, qb));
        let (ka, kb) = (
            &cpl[j * nl..j * nl + narrow],
            &cpl[(j + 1) * nl..(j + 1) * nl + narrow],
        );
        for (((s, c), &k1), &k2) in ab.iter_mut().zip(cs.iter_mut()).zip(ka).zip(kb) {
            *s = *s + F2::splat(k1) * sa;
            *s = *s + F2::splat(k2) * sb;
            *c += k1 * pc;
            *c += k2 * qc;
        }
    }
    for j in 2 * pairs..n {
        let c = gm.poly_load(j, piece, t0);
        cpoly[j] = c;
        let (pa, pb, pc) = poly_coefficients(iw2[j], damp[j], &c);
        pcoef[j] = [pa, pb, pc];
        x0s[j] = q[j] - pa;
        y0s[j] = v[j] - pb;
        let sa = F2::new(pa, pb);
        for ((s, c), &k) in ab
            .iter_mut()
            .zip(cs.iter_mut())
            .zip(&cpl[j * nl..j * nl + narrow])
        {
            *s = *s + F2::splat(k) * sa;
            *c += k * pc;
        }
    }
    std::array::from_fn(|k| {
        let [a, b] = ab[k].get();
        [a, b, cs[k]]
    })
}

/// Where a recorded motion's contact steps stand on the piece's dyadic grid: grid step `base`
/// (of the piece's grid steps hh, from its start `start`) and the [`DyadicWalk`] inside it at
/// [`MAX_LEVEL`], at the time `t` (the walk holds while the time is still that).
#[derive(Debug, Clone, Copy)]
pub(super) struct GridWalk {
    start: f64,
    t: f64,
    base: u64,
    walk: DyadicWalk,
}

impl GridWalk {
    /// At the piece's grid point number `k` of level `m` (k·hh/2^m from its start).
    fn at(start: f64, t: f64, k: u128, m: usize) -> GridWalk {
        let pos = ((k & ((1u128 << m) - 1)) as u64) << (MAX_LEVEL - m);
        GridWalk {
            start,
            t,
            base: (k >> m) as u64,
            walk: DyadicWalk::at(pos, m as u32, MAX_LEVEL as u32),
        }
    }

    /// The number of the last grid point of level `m` at or before the position.
    fn point(&self, m: usize) -> u128 {
        ((self.base as u128) << m) + self.walk.index(m as u32) as u128
    }

    /// The number of the next grid point of level `m` after the position.
    fn next_point(&self, m: usize) -> u128 {
        let end = self.walk.pos() + self.walk.until_next(m as u32);
        ((self.base as u128) << m) + (end >> (MAX_LEVEL - m)) as u128
    }

    /// Past one sub-step hh/2^m (from a point of that level's grid), into the next grid step
    /// at the end of this one.
    fn advance(mut self, m: usize) -> GridWalk {
        self.walk.level = m as u32;
        self.walk.advance();
        if self.walk.done() {
            self.base += 1;
            self.walk = DyadicWalk::at(0, m as u32, MAX_LEVEL as u32);
        }
        self
    }
}
