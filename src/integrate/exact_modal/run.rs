//! `exact-modal` for structures with yielding storeys: the run's state, its construction, and
//! the base step (free flight in closed form, contact and yielding storeys in sub-steps).

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::*;

pub(super) struct Run<'a, O: Observer> {
    pub(super) sys: &'a System,
    pub(super) tol: SubstepTolerance,
    /// Every level's force at the start of the last accepted (sub-)step, and that step's
    /// length: the third point of the force's second divided difference.
    pub(super) last_force: Vec<f64>,
    pub(super) last_h: f64,
    /// Whether the last estimate met an onset or a release (for the trace).
    pub(super) kink: bool,
    pub(super) trace: Option<&'a mut Vec<StepTrace>>,
    pub(super) gm: GroundModes,
    pub(super) obs: &'a mut O,
    pub(super) cache: StepCache,
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) qb: Vec<f64>,
    pub(super) vb: Vec<f64>,
    /// Ground load polynomial of each mode over the current step (records).
    pub(super) cpoly: Vec<[f64; 3]>,
    pub(super) states: Vec<LevelState>,
    pub(super) prev_states: Vec<LevelState>,
    pub(super) onset: Vec<f64>,
    pub(super) fpred: Vec<f64>,
    /// δ, δ̇ of every level at the end of the free flight in (qb, vb), from [`Self::contact_bound`].
    pub(super) free_end: Vec<(f64, f64)>,
    /// Per mode, how far its free flight in (qb, vb) may stray from the cubic Hermite
    /// interpolant over the step (see [`hermite_gap_factor`]), and per level the |coupling|.
    pub(super) amp: Vec<f64>,
    pub(super) cabs: Vec<Vec<f64>>,
    /// max over contact sub-steps of `k_t h²/m*` (its square root is reported).
    pub(super) max_contact_w2h2: f64,
    /// 1/m* of every level, 1/kg.
    pub(super) inv_mstar: Vec<f64>,
    /// Coupling rows transposed, mode-major: `[j·L + k]`.
    pub(super) cpl_t: Vec<f64>,
    /// Harmonic motion: Ω (rad/s); sin Ωt, cos Ωt at the current state, and at both ends of
    /// the (sub-)step whose free flight is in (qb, vb).
    pub(super) big: Option<f64>,
    pub(super) trig_now: Trig,
    pub(super) trig_start: Trig,
    pub(super) trig_end: Trig,
    /// Cache entries of the sub-steps hh/2^m of the base step length `level_hh`.
    pub(super) level_hh: f64,
    pub(super) level_idx: [usize; MAX_LEVEL as usize + 1],
    /// Harmonic motion: every mode's particular solution (η_p, η̇_p) at `trig_now` and at
    /// `trig_end` (swapped when a step is taken).
    pub(super) part_now: Vec<(f64, f64)>,
    pub(super) part_end: Vec<(f64, f64)>,
    /// Base steps since sin, cos were last evaluated directly (not by rotation).
    pub(super) since_sync: u32,
    /// Fast exact tallies for harmonic motion, and the sums at the current state.
    pub(super) htally: Option<HarmonicTally>,
    /// The harmonic contact tallies regrouped by level, and their per-step sums.
    pub(super) forms: Option<ContactForms>,
    pub(super) lsteps: Vec<LevelStep>,
    pub(super) sums: StateSums,
    pub(super) tally: Tally,
    pub(super) stats: Stats,
    /// Yielding storeys (empty without): see [`Yield`].
    pub(super) hy: Yield,
}

impl<'a, O: Observer> Run<'a, O> {
    /// The integrator at time `t0` in the modal state (q0, v0); `onset`: the approach speeds
    /// of the contact episodes in force (`None`: none, as at rest).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        sys: &'a System,
        settings: &SolverSettings,
        observer: &'a mut O,
        trace: Option<&'a mut Vec<StepTrace>>,
        t0: f64,
        q0: Vec<f64>,
        v0: Vec<f64>,
        onset: Option<&[f64]>,
    ) -> Run<'a, O> {
        let n = sys.len();
        let nl = sys.levels.len();
        let mut r = Run {
            sys,
            tol: SubstepTolerance::new(sys, settings),
            last_force: vec![0.0; nl],
            last_h: settings.base_step(),
            kink: false,
            trace,
            gm: GroundModes::new(sys),
            obs: observer,
            cache: StepCache::new(),
            q: q0,
            v: v0,
            qb: vec![0.0; n],
            vb: vec![0.0; n],
            cpoly: vec![[0.0; 3]; n],
            states: vec![LevelState::default(); nl],
            prev_states: vec![LevelState::default(); nl],
            onset: vec![0.0; nl],
            fpred: vec![0.0; nl],
            free_end: vec![(0.0, 0.0); nl],
            amp: vec![0.0; n],
            cabs: (0..nl)
                .map(|k| sys.coupling(k).iter().map(|c| c.abs()).collect())
                .collect(),
            max_contact_w2h2: 0.0,
            inv_mstar: sys.levels.iter().map(|l| 1.0 / l.effective_mass).collect(),
            cpl_t: (0..n)
                .flat_map(|j| (0..nl).map(move |k| sys.coupling(k)[j]))
                .collect(),
            big: None,
            trig_now: Trig::default(),
            trig_start: Trig::default(),
            trig_end: Trig::default(),
            since_sync: 0,
            part_now: vec![(0.0, 0.0); n],
            part_end: vec![(0.0, 0.0); n],
            level_hh: f64::NAN,
            level_idx: [usize::MAX; MAX_LEVEL as usize + 1],
            htally: None,
            forms: None,
            lsteps: vec![LevelStep::default(); nl],
            sums: StateSums::default(),
            tally: Tally {
                impulse: vec![0.0; nl],
                ..Tally::default()
            },
            stats: Stats::default(),
            hy: Yield::default(),
        };
        let ns = sys.hysteresis.len();
        if ns > 0 {
            let nr = nl + ns;
            r.hy = Yield {
                ns,
                z: vec![0.0; ns],
                now: vec![StoreyState::default(); ns],
                rows_t: (0..n)
                    .flat_map(|j| (0..ns).map(move |s| sys.hysteresis.row(s)[j]))
                    .collect(),
                held: vec![0.0; n],
                free: vec![(0.0, 0.0); ns],
                zpred: vec![0.0; ns],
                zdpred: vec![0.0; ns],
                ppred: vec![0.0; ns],
                zcorr: vec![0.0; ns],
                last_p: vec![0.0; ns],
                last_zd: vec![0.0; ns],
                l0: vec![0.0; nr],
                lpred: vec![0.0; nr],
                lcorr: vec![0.0; nr],
                level: 0,
            };
            r.tally.storey_work = vec![0.0; ns];
        }
        // (the fast harmonic tallies know only the contact loads: with yielding storeys every
        // step takes the per-mode exact tallies, which take any load linear in time)
        r.htally = if ns == 0 {
            HarmonicTally::new(&r.gm)
        } else {
            None
        };
        r.forms = r
            .htally
            .as_ref()
            .map(|ht| ContactForms::new(ht, &r.gm, &r.cpl_t, nl));
        r.big = r.gm.harmonic_omega();
        r.trig_now = r.gm.trig(t0);
        r.sync_particular();
        if let Some(ht) = &r.htally {
            for j in 0..n {
                ht.add(&mut r.sums, j, r.gm.w2[j], r.q[j], r.v[j]);
            }
        }
        if let Some(onset) = onset {
            r.onset.copy_from_slice(onset);
        }
        r.evaluate_states();
        r.evaluate_storeys();
        let s0 = r.states.clone();
        update_onsets(&mut r.onset, &s0, &r.states, 0.0);
        r
    }
}

impl<O: Observer> Run<'_, O> {
    pub(super) fn observe(&mut self, t: f64) {
        self.obs.observe(
            self.sys,
            &StepView {
                t,
                q: &self.q,
                v: &self.v,
                levels: &self.states,
                z: &self.hy.z,
                tally: &self.tally,
            },
        );
    }

    /// The harmonic particular solution (η_p, η̇_p) of every mode at `trig_now`.
    pub(super) fn sync_particular(&mut self) {
        if let Some((big, g_re, g_im)) = self.gm.harmonic_plain() {
            let (s, c) = (self.trig_now.s, self.trig_now.c);
            for ((p, gr), gi) in self.part_now.iter_mut().zip(g_re).zip(g_im) {
                *p = (gr * s + gi * c, big * (gr * c - gi * s));
            }
        }
    }

    /// δ, δ̇ and the law's force at the current state.
    pub(super) fn evaluate_states(&mut self) {
        let sys = self.sys;
        for k in 0..sys.levels.len() {
            let c = sys.coupling(k);
            self.set_state(k, dot(c, &self.q), dot(c, &self.v));
        }
    }

    /// Level k's δ, δ̇ and force from its projections `c_k·η`, `c_k·η̇`.
    #[inline]
    pub(super) fn set_state(&mut self, k: usize, cq: f64, cv: f64) {
        self.states[k] = self.sys.levels[k].state(cq, cv, self.onset[k]);
    }

    /// Ground-only free flight from the current state over [t0, t0 + h] into (qb, vb).
    pub(super) fn free_flight(&mut self, t0: f64, h: f64, piece: &Piece, idx: usize) {
        // the margin of the contact test is needed only where a level is out of force
        let margin = self.states.iter().any(|st| st.force <= 0.0);
        let gm = &self.gm;
        let data = &self.cache.entries[idx];
        // sin, cos at the step end by rotating those at its start (one ulp per step; re-synced
        // every SYNC_EVERY base steps)
        let tr0 = self.trig_now;
        let (sh, ch) = data.rot;
        let tr1 = Trig {
            t: t0 + h,
            s: tr0.s * ch + tr0.c * sh,
            c: tr0.c * ch - tr0.s * sh,
        };
        if let (Piece::Harmonic, Some((big, g_re, g_im))) = (piece, gm.harmonic_plain()) {
            // harmonic motion: the particular solution is G_re sin Ωt + G_im cos Ωt
            let (s1, c1) = (tr1.s, tr1.c);
            // (slices cut to n once: the indexing below needs no bounds checks; the particular
            // solution at the start is the one kept from the previous step's end)
            let n = self.q.len();
            let (q, v, infl) = (&self.q[..n], &self.v[..n], &data.infl[..n]);
            let (g_re, g_im) = (&g_re[..n], &g_im[..n]);
            let (p0, p1) = (&self.part_now[..n], &mut self.part_end[..n]);
            let (qb, vb, amp) = (&mut self.qb[..n], &mut self.vb[..n], &mut self.amp[..n]);
            let (herm, hp) = (&data.herm[..n], data.herm_part);
            for j in 0..n {
                let (gr, gi) = (g_re[j], g_im[j]);
                let (e0, d0) = p0[j];
                let (e1, d1) = (gr * s1 + gi * c1, big * (gr * c1 - gi * s1));
                p1[j] = (e1, d1);
                let (x0, y0) = (q[j] - e0, v[j] - d0);
                let (x, y) = infl[j].p.apply(x0, y0);
                qb[j] = x + e1;
                vb[j] = y + d1;
                if margin {
                    amp[j] =
                        herm[j].0 * x0.abs() + herm[j].1 * y0.abs() + hp * (gr.abs() + gi.abs());
                }
            }
        } else if let Piece::Poly {
            t0: start,
            a0,
            a1,
            v0,
        } = *piece
        {
            // a recorded motion: a_g linear, v_g quadratic over the piece; each mode's load is
            // c0 + c1τ + c2τ² from t0 on, its particular solution A + Bτ + Cτ² (slices cut to n
            // once: no bounds checks below)
            let tau = t0 - start;
            let (ag, vg) = (a0 + a1 * tau, v0 + tau * (a0 + 0.5 * a1 * tau));
            let n = self.q.len();
            let (la, lv) = (&gm.la[..n], &gm.lv[..n]);
            let (iw2, damp) = (&gm.inv_w2[..n], &gm.damp[..n]);
            let (q, v, infl) = (&self.q[..n], &self.v[..n], &data.infl[..n]);
            let (qb, vb, cpoly) = (&mut self.qb[..n], &mut self.vb[..n], &mut self.cpoly[..n]);
            let (amp, herm) = (&mut self.amp[..n], &data.herm[..n]);
            for j in 0..n {
                let c = [
                    la[j] * ag + lv[j] * vg,
                    la[j] * a1 + lv[j] * ag,
                    0.5 * lv[j] * a1,
                ];
                cpoly[j] = c;
                let (pa, pb, pc) = poly_coefficients(iw2[j], damp[j], &c);
                let (e1, d1) = (pa + h * (pb + h * pc), pb + 2.0 * h * pc);
                // (the particular solution is quadratic: its cubic Hermite is exact)
                let (x0, y0) = (q[j] - pa, v[j] - pb);
                let (x, y) = infl[j].p.apply(x0, y0);
                qb[j] = x + e1;
                vb[j] = y + d1;
                if margin {
                    amp[j] = herm[j].0 * x0.abs() + herm[j].1 * y0.abs();
                }
            }
        } else {
            // no ground load, or harmonic motion with a mode at undamped resonance
            for j in 0..self.q.len() {
                let c = [0.0; 3];
                self.cpoly[j] = c;
                let (e0, d0) = gm.particular(j, piece, &c, 0.0, &tr0);
                let (e1, d1) = gm.particular(j, piece, &c, h, &tr1);
                let (x0, y0) = (self.q[j] - e0, self.v[j] - d0);
                let (x, y) = data.infl[j].p.apply(x0, y0);
                self.qb[j] = x + e1;
                self.vb[j] = y + d1;
                // (resonant harmonic: the particular part's own bound is added as Ω-wide)
                let (hx, hy) = data.herm[j];
                self.amp[j] = hx * x0.abs()
                    + hy * y0.abs()
                    + data.herm_part * (e0.abs().max(e1.abs()) + d0.abs().max(d1.abs()));
            }
        }
        self.trig_start = tr0;
        self.trig_end = tr1;
    }

    /// Upper bound of the penetration over a (sub-)step of length h whose free flight is in
    /// (qb, vb) (max over the levels of the cubic Hermite bound of δ, or the current δ while in
    /// force; negative: no level can touch), and the largest `k_t·D(h)` of the levels at their
    /// bound (`D(h) = Σ_j c_j² Γ0_j(h)`, the level's displacement under a unit force held for h:
    /// h²/(2m*) for a point mass, so `k_t·D(h) ≤ α²/2` is `ω_c h ≤ α`; modes much stiffer than
    /// the contact add only their static flexibility, so the sub-step does not shrink as modes
    /// are added).
    pub(super) fn contact_bound(&mut self, h: f64, idx: usize) -> (f64, f64) {
        let sys = self.sys;
        let nl = sys.levels.len();
        let data = &self.cache.entries[idx];
        let (mut bound, mut worst) = (f64::NEG_INFINITY, 0.0f64);
        for (k, lv) in sys.levels.iter().enumerate() {
            let st = self.states[k];
            let c = sys.coupling(k);
            let (d1, dd1) = lv.penetration(dot(c, &self.qb), dot(c, &self.vb));
            self.free_end[k] = (d1, dd1);
            // while in force the sub-step is short against the impact and the larger end
            // value bounds k_t well enough (k_t ∝ √δ for Hertz); otherwise the cubic decides
            // whether the level can touch at all
            let m = if st.force > 0.0 {
                st.delta.max(d1)
            } else {
                // the cubic through the ends, plus how far the modes' free motion may stray
                // from it (fast modes oscillate within a long step: without this margin a
                // short impact between two base-step ends is missed)
                hermite_max(st.delta, st.delta_dot, d1, dd1, h).0 + dot(&self.cabs[k], &self.amp)
            };
            bound = bound.max(m);
            if m > 0.0 {
                let w = lv.force.tangent_stiffness(m) * data.m0[k * nl + k].0;
                // a sub-step in which the level may start touching: the force grows from zero
                // like (t − t_on)^{3/2} (Hertz), which a linear load over the sub-step fits
                // worst, so the rule is ω_c·h ≤ α/4 there
                let w = if st.force > 0.0 { w } else { w * ONSET_WEIGHT };
                worst = worst.max(w);
            }
        }
        (bound, worst)
    }

    /// The cache entry of the sub-step `h = hh/2^level`, remembered per level for the current
    /// base step length (no search through the cache on every sub-step).
    pub(super) fn level_index(&mut self, hh: f64, level: u32, h: f64) -> usize {
        if self.level_hh != hh {
            self.level_hh = hh;
            self.level_idx = [usize::MAX; MAX_LEVEL as usize + 1];
        }
        let i = self.level_idx[level as usize];
        if self.cache.entries.get(i).is_some_and(|e| e.h == h) {
            return i;
        }
        let i = self.cache.index(self.sys, self.big, h);
        self.level_idx[level as usize] = i;
        i
    }

    /// One base step of a system with yielding storeys ([`Self::base_step_yielding`]; elastic
    /// systems take [`elastic`]).
    pub(super) fn base_step(&mut self, t0: f64, hh: f64, piece: &Piece) -> Result<(), SolveError> {
        if self.since_sync == 0 {
            self.trig_now = self.gm.trig(t0);
            self.sync_particular();
        }
        self.since_sync = (self.since_sync + 1) % SYNC_EVERY;
        self.base_step_yielding(t0, hh, piece)
    }

    /// The predicted end force F₁* of every level (load held at F₀ over the (sub-)step whose
    /// free flight is in (qb, vb)) into `fpred`; zero without `contact`.
    pub(super) fn predict(&mut self, idx: usize, contact: bool) {
        let sys = self.sys;
        let nl = sys.levels.len();
        let data = &self.cache.entries[idx];
        if contact {
            for (k, lv) in sys.levels.iter().enumerate() {
                let (mut d, mut dd) = self.free_end[k];
                for l in 0..nl {
                    let f0 = self.states[l].force;
                    d -= f0 * data.m0[k * nl + l].0;
                    dd -= f0 * data.m0[k * nl + l].1;
                }
                let v0 = episode_v0(self.onset[k], dd);
                self.fpred[k] = lv.force.force(d, dd, v0);
            }
        } else {
            self.fpred.iter_mut().for_each(|f| *f = 0.0);
        }
    }

    /// [`Self::finish_step`], recording the (sub-)step in the trace when one is kept and
    /// `record` (copies only then: no allocation per step otherwise).
    pub(super) fn finish_traced(
        &mut self,
        t0: f64,
        h: f64,
        piece: &Piece,
        idx: usize,
        err: f64,
        record: bool,
    ) -> Result<(), SolveError> {
        let start = (self.trace.is_some() && record).then(|| {
            (
                self.q.clone(),
                self.v.clone(),
                self.onset.clone(),
                self.hy.z.clone(),
            )
        });
        self.finish_step(t0, h, piece, idx)?;
        if let (Some(trace), Some((q0, v0, onset, z0))) = (self.trace.as_mut(), start) {
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
                z0,
                z1: self.hy.z.clone(),
                companion: Vec::new(),
            });
        }
        Ok(())
    }

    /// Complete a (sub-)step whose free flight is in (qb, vb) and predicted end forces in
    /// `fpred` (zero: no contact load): the corrector for the contact load; then the state,
    /// tallies, observation.
    pub(super) fn finish_step(
        &mut self,
        t0: f64,
        h: f64,
        piece: &Piece,
        idx: usize,
    ) -> Result<(), SolveError> {
        let sys = self.sys;
        let nl = sys.levels.len();
        let data = &self.cache.entries[idx];
        let any_force = (0..nl).any(|k| self.states[k].force != 0.0 || self.fpred[k] != 0.0);
        // state update and exact tallies, mode by mode
        // (free_flight has just computed sin, cos at t0 + h into trig_end)
        let tm = match piece {
            Piece::Harmonic => self.big.map(|big| {
                let (tr0, tr1) = (self.trig_start, self.trig_end);
                TrigMoments::from_ends(big, h, (tr0.s, tr0.c), (tr1.s, tr1.c), data.half)
            }),
            _ => None,
        };
        self.trig_now = self.trig_end;
        std::mem::swap(&mut self.part_now, &mut self.part_end);
        let n = self.q.len();
        let (mut input, mut damping) = (0.0, 0.0);
        // (the modal sums of the harmonic tallies; only that branch uses them)
        let mut sums = StateSums::default();
        // the one level's projections of the new state, when the corrector formed them
        let mut projected = None;
        if let (Some(ht), Some(tm)) = (&self.htally, &tm) {
            // harmonic motion: exact tallies from linear forms
            let mut extra = 0.0;
            let mut contact = 0.0;
            if let (true, Some(forms)) = (any_force, &self.forms) {
                for (ls, (st, fp)) in self
                    .lsteps
                    .iter_mut()
                    .zip(self.states.iter().zip(&self.fpred))
                {
                    *ls = LevelStep {
                        f0: st.force,
                        df: fp - st.force,
                        ..LevelStep::default()
                    };
                }
                if nl == 1 {
                    // one level (the common case): no inner loops; the slices are cut to n
                    // once so that the indexing below needs no bounds checks
                    let (c, wts, infl) = (&self.cpl_t[..n], &forms.weights[..n], &data.infl[..n]);
                    let (qb, vb, w2) = (&self.qb[..n], &self.vb[..n], &self.gm.w2[..n]);
                    let (q, v) = (&mut self.q[..n], &mut self.v[..n]);
                    let LevelStep { f0, df, .. } = self.lsteps[0];
                    let (mut cq0, mut cq1, mut sv, mut se) = (0.0, 0.0, 0.0, 0.0);
                    let mut cv1 = 0.0;
                    for j in 0..n {
                        let (g0, g1) = (c[j] * f0, c[j] * df);
                        let f = &infl[j];
                        let (q0, v0) = (q[j], v[j]);
                        let q1 = qb[j] + g0 * f.g0.0 + g1 * f.g1.0;
                        let v1 = vb[j] + g0 * f.g0.1 + g1 * f.g1.1;
                        cq0 += c[j] * q0;
                        cq1 += c[j] * q1;
                        cv1 += c[j] * v1;
                        sv += wts[j].0 * (v1 - v0);
                        se += wts[j].1 * (q1 - q0);
                        ht.add(&mut sums, j, w2[j], q1, v1);
                        q[j] = q1;
                        v[j] = v1;
                    }
                    let ls = &mut self.lsteps[0];
                    (ls.cq0, ls.cq1, ls.sv, ls.se) = (cq0, cq1, sv, se);
                    projected = Some((cq1, cv1));
                } else {
                    let rows = self
                        .cpl_t
                        .chunks_exact(nl)
                        .zip(forms.weights.chunks_exact(nl));
                    let modes = self.q.iter_mut().zip(self.v.iter_mut());
                    let free = self.qb.iter().zip(&self.vb);
                    let consts = data.infl.iter().zip(&self.gm.w2);
                    for (j, (((row, wrow), (q, v)), (free, (f, &w2)))) in
                        rows.zip(modes).zip(free.zip(consts)).enumerate()
                    {
                        let (mut g0, mut g1) = (0.0, 0.0);
                        for (c, ls) in row.iter().zip(&self.lsteps) {
                            g0 += c * ls.f0;
                            g1 += c * ls.df;
                        }
                        let (q0, v0) = (*q, *v);
                        let q1 = free.0 + g0 * f.g0.0 + g1 * f.g1.0;
                        let v1 = free.1 + g0 * f.g0.1 + g1 * f.g1.1;
                        let per_level = row.iter().zip(wrow).zip(self.lsteps.iter_mut());
                        for ((c, (wv, wd)), ls) in per_level {
                            ls.cq0 += c * q0;
                            ls.cq1 += c * q1;
                            ls.sv += wv * (v1 - v0);
                            ls.se += wd * (q1 - q0);
                        }
                        ht.add(&mut sums, j, w2, q1, v1);
                        *q = q1;
                        *v = v1;
                    }
                }
                (extra, contact) = forms.tallies(tm, h, &self.lsteps);
            } else {
                let (qb, vb, w2) = (&self.qb[..n], &self.vb[..n], &self.gm.w2[..n]);
                let (q, v) = (&mut self.q[..n], &mut self.v[..n]);
                for j in 0..n {
                    ht.add(&mut sums, j, w2[j], qb[j], vb[j]);
                    q[j] = qb[j];
                    v[j] = vb[j];
                }
            }
            input = ht.input(tm, &self.sums, &sums) + extra;
            damping = input + contact - (sums.energy - self.sums.energy);
        } else if matches!(piece, Piece::Poly { .. }) {
            // a recorded motion: the corrector and the exact tallies in one slice-indexed pass
            let inv_h = data.inv_h;
            let (w2, damp, iw2) = (&self.gm.w2[..n], &self.gm.damp[..n], &self.gm.inv_w2[..n]);
            let (qb, vb, cpoly, infl) = (
                &self.qb[..n],
                &self.vb[..n],
                &self.cpoly[..n],
                &data.infl[..n],
            );
            let (q, v) = (&mut self.q[..n], &mut self.v[..n]);
            let cpl = &self.cpl_t[..n * nl];
            for j in 0..n {
                let (mut g0, mut g1) = (0.0, 0.0);
                if any_force {
                    for k in 0..nl {
                        let c = cpl[j * nl + k];
                        g0 += c * self.states[k].force;
                        g1 += c * (self.fpred[k] - self.states[k].force);
                    }
                }
                // yielding storeys: their held load is in (qb, vb) already, their ramp joins
                // the contact's; the tallies take the whole load
                let gh = self.hy.ramp(j, &mut g1);
                let f = &infl[j];
                let q1 = qb[j] + g0 * f.g0.0 + g1 * f.g1.0;
                let v1 = vb[j] + g0 * f.g0.1 + g1 * f.g1.1;
                let w = poly_mode_work(
                    (w2[j], damp[j], iw2[j]),
                    h,
                    inv_h,
                    (q[j], v[j]),
                    (q1, v1),
                    &cpoly[j],
                    g0 + gh,
                    g1,
                );
                input += w.input;
                damping += w.damping;
                q[j] = q1;
                v[j] = v1;
            }
        } else {
            for j in 0..n {
                let (mut g0, mut g1) = (0.0, 0.0);
                if any_force {
                    for k in 0..nl {
                        let c = self.cpl_t[j * nl + k];
                        g0 += c * self.states[k].force;
                        g1 += c * (self.fpred[k] - self.states[k].force);
                    }
                }
                let gh = self.hy.ramp(j, &mut g1);
                let f = &data.infl[j];
                let q1 = self.qb[j] + g0 * f.g0.0 + g1 * f.g1.0;
                let v1 = self.vb[j] + g0 * f.g0.1 + g1 * f.g1.1;
                let ground = match piece {
                    Piece::Harmonic => None,
                    _ => Some(&self.cpoly[j]),
                };
                let w = mode_work(
                    &self.gm,
                    j,
                    h,
                    (self.q[j], self.v[j]),
                    (q1, v1),
                    ground,
                    tm.as_ref(),
                    g0 + gh,
                    g1,
                );
                input += w.input;
                damping += w.damping;
                self.q[j] = q1;
                self.v[j] = v1;
            }
        }
        self.sums = sums;
        self.tally.input += input;
        self.tally.damping += damping;
        for ((p, lf), st) in self
            .prev_states
            .iter_mut()
            .zip(self.last_force.iter_mut())
            .zip(&self.states)
        {
            *p = *st;
            *lf = st.force;
        }
        self.last_h = h;
        match projected {
            Some((cq, cv)) => self.set_state(0, cq, cv),
            None => self.evaluate_states(),
        }
        if self.hy.ns > 0 {
            self.finish_storeys(h);
        }
        let inv_h = self.cache.entries[idx].inv_h;
        // work into the contacts with the law's force (Simpson on the Hermite interpolant of δ)
        for k in 0..nl {
            let (a, b) = (self.prev_states[k], self.states[k]);
            if a.delta > 0.0 || b.delta > 0.0 || any_force {
                let dm = 0.5 * (a.delta + b.delta) + h * (a.delta_dot - b.delta_dot) / 8.0;
                let ddm = 1.5 * (b.delta - a.delta) * inv_h - 0.25 * (a.delta_dot + b.delta_dot);
                let lv = &sys.levels[k];
                let v0 = episode_v0(self.onset[k], ddm);
                let fm = lv.force.force(dm, ddm, v0);
                self.tally.contact +=
                    h / 6.0 * (a.force * a.delta_dot + 4.0 * fm * ddm + b.force * b.delta_dot);
                self.tally.impulse[k] += 0.5 * h * (a.force + self.fpred[k]);
                if b.delta > 0.0 {
                    let kt = lv.force.tangent_stiffness(b.delta);
                    self.max_contact_w2h2 =
                        self.max_contact_w2h2.max(kt * self.inv_mstar[k] * h * h);
                }
            }
        }
        update_onsets(&mut self.onset, &self.prev_states, &self.states, h);
        // stereomechanical impacts: velocity jumps at the step end; the exact harmonic tallies
        // take the next step's start sums from the state, so re-derive them after a jump
        if sys.has_impulsive()
            && sys.apply_impulses(
                &mut self.v,
                &mut self.states,
                &mut self.tally.impulse,
                &mut self.tally.contact,
            )
        {
            self.evaluate_states();
            if self.hy.ns > 0 {
                self.evaluate_storeys();
            }
            if let Some(ht) = &self.htally {
                let mut sums = StateSums::default();
                for j in 0..n {
                    ht.add(&mut sums, j, self.gm.w2[j], self.q[j], self.v[j]);
                }
                self.sums = sums;
            }
        }
        self.stats.steps += 1;
        self.stats.evaluations += 1;
        // (the modal energy is finite exactly when every η, η̇ is)
        let finite = if self.htally.is_some() {
            self.sums.energy.is_finite()
        } else {
            self.q.iter().chain(&self.v).all(|x| x.is_finite())
        };
        if !finite {
            return Err(SolveError::Diverged {
                t: t0 + h,
                contact_omega_dt: self.max_contact_w2h2.sqrt(),
            });
        }
        self.observe(t0 + h);
        Ok(())
    }
}
