//! The free flight of [`Elastic`]: exact propagation over the base grid, its cached step data,
//! the exact tallies of a free step, and the segment loop between contact phases.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::kernel::{
    HarmonicWave, ModeLoads, PolyMap, dots, harmonic_pass, poly_margins, poly_pass, start_energy2,
};
use super::*;
use crate::numerics::hermite::hermite_bound;

impl<'a, O: Observer> Elastic<'a, O> {
    // ---------------------------------------------------------------- free flight

    /// The cached free-flight data of step length h (or, when `keep` is false and h is not
    /// cached, freshly computed into the scratch slot): returns `Some(index)` or `None` for
    /// the scratch slot.
    pub(super) fn free_index(&mut self, h: f64, keep: bool) -> Option<usize> {
        // (a length is cached at most once: the last hit is the same entry the scan finds)
        if self.free.get(self.free_hit).is_some_and(|e| e.h == h) {
            return Some(self.free_hit);
        }
        let key = free_key(h);
        let slot = usize::from(self.free_slot[key]).wrapping_sub(1);
        if self.free.get(slot).is_some_and(|e| e.h == h) {
            self.free_hit = slot;
            return Some(slot);
        }
        if let Some(i) = self.free.iter().position(|e| e.h == h) {
            self.free_hit = i;
            self.free_slot[key] = (i + 1) as u8;
            return Some(i);
        }
        if !keep {
            if self.scratch_free.as_ref().is_none_or(|e| e.h != h) {
                self.scratch_free = Some(FreeData::new(self.sys, self.big, h));
            }
            return None;
        }
        let d = FreeData::new(self.sys, self.big, h);
        let i = if self.free.len() < FREE_CACHE {
            self.free.push(d);
            self.free.len() - 1
        } else {
            let i = self.free_next;
            self.free[i] = d;
            self.free_next = (i + 1) % FREE_CACHE;
            i
        };
        self.free_slot[key] = (i + 1) as u8;
        Some(i)
    }

    crate::numerics::vex::avx_copy! {
        /// The free flight over [t0, t0 + h] from the state (`from_search`: the search state
        /// (qs, vs), else (q, v)) into (qb, vb), in one pass over the modes that also gives every
        /// level's projections of the end state (`fproj`), with `margin` each mode's Hermite margin
        /// (`amp`) and every level's (`fmargin`; without `margin`, under a recorded motion an upper
        /// bound of them, [`PolyMap::margin_bounds`], else 0), and what the step's exact tallies
        /// need (`fsums`, `fpsums`, `fenergy`). `tr0`: sin, cos at t0 (harmonic). Returns sin, cos
        /// at the end.
        ///
        /// Where the processor has AVX, its copy compiled for it runs ([`crate::numerics::vex`]:
        /// the same bits).
        #[allow(clippy::too_many_arguments)]
        pub(super) fn free_prop(
            &mut self,
            fd: Option<usize>,
            piece: &Piece,
            tr0: Trig,
            t0: f64,
            h: f64,
            from_search: bool,
            margin: bool,
        ) -> Trig => free_prop_vex, free_prop_body
    }

    /// [`Self::free_prop`]'s work.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn free_prop_body(
        &mut self,
        fd: Option<usize>,
        piece: &Piece,
        tr0: Trig,
        t0: f64,
        h: f64,
        from_search: bool,
        margin: bool,
    ) -> Trig {
        let (n, nl) = (self.n, self.nl);
        if matches!(piece, Piece::Poly { .. }) {
            let slot = match fd {
                Some(i) => &mut self.free[i],
                None => self.scratch_free.as_mut().expect("scratch free flight"),
            };
            if slot.poly.is_none() {
                let gm = &self.gm;
                let modes = ModeLoads {
                    la: &gm.la,
                    lv: &gm.lv,
                    damp: &gm.damp,
                    w2: &gm.w2,
                    inv_w2: &gm.inv_w2,
                };
                let mut map = PolyMap::new(modes, &slot.props, &slot.herm, slot.h);
                map.set_gains((0..self.nl).map(|k| self.sys.coupling(k)));
                slot.poly = Some(map);
            }
        }
        let fd = match fd {
            Some(i) => &self.free[i],
            None => self.scratch_free.as_ref().expect("scratch free flight"),
        };
        debug_assert_eq!(fd.h, h);
        let (sh, ch) = fd.rot;
        let tr1 = match self.big {
            // sin, cos at the end by rotating those at the start (one ulp per step; re-synced
            // on the grid every 16 steps and after every contact step)
            Some(_) => Trig {
                t: t0 + h,
                s: tr0.s * ch + tr0.c * sh,
                c: tr0.c * ch - tr0.s * sh,
            },
            None => Trig::default(),
        };
        let (q, v) = if from_search {
            (&self.qs[..n], &self.vs[..n])
        } else {
            (&self.q[..n], &self.v[..n])
        };
        let (qb, vb, amp) = (&mut self.qb[..n], &mut self.vb[..n], &mut self.amp[..n]);
        let (props, herm) = (&fd.props[..n], &fd.herm[..n]);
        let gm = &self.gm;
        let w2 = &gm.w2[..n];
        let mut sums = StateSums::default();
        let mut energy = None;
        let mut bounded = false;
        match (piece, gm.harmonic_plain(), &self.htally) {
            (Piece::Harmonic, Some((big, g_re, g_im)), ht) => {
                let hw = HarmonicWave {
                    big,
                    g_re: &g_re[..n],
                    g_im: &g_im[..n],
                    tr0,
                    tr1,
                };
                let (out, hp) = ((qb, vb, amp), (herm, fd.herm_part));
                let s = &mut sums;
                // (the per-mode branches hoisted: one loop per case)
                match (margin, ht) {
                    (true, Some(ht)) => {
                        harmonic_pass::<true>(&hw, props, hp, q, v, out, |j, x, y| {
                            ht.add(s, j, w2[j], x, y)
                        })
                    }
                    (false, Some(ht)) => {
                        harmonic_pass::<false>(&hw, props, hp, q, v, out, |j, x, y| {
                            ht.add(s, j, w2[j], x, y)
                        })
                    }
                    (true, None) => harmonic_pass::<true>(&hw, props, hp, q, v, out, |_, _, _| {}),
                    (false, None) => {
                        harmonic_pass::<false>(&hw, props, hp, q, v, out, |_, _, _| {})
                    }
                }
            }
            (
                Piece::Poly {
                    t0: start,
                    a0,
                    a1,
                    v0,
                },
                _,
                _,
            ) => {
                // a recorded motion: the ground's acceleration a_g, velocity v_g at the step's
                // start and the acceleration's slope a1 load every mode (c0 + c1τ + c2τ²), and
                // the step is one affine map of (η, η̇, a_g, v_g, a1) per mode ([`PolyMap`]);
                // the same pass sums what the ground's exact work needs (PolyTally)
                let tau = t0 - start;
                let g = (a0 + a1 * tau, v0 + tau * (a0 + 0.5 * a1 * tau), *a1);
                let map = fd.poly.as_ref().expect("the map is built before the pass");
                let out = (qb, vb, amp);
                let (ps, e) = if margin {
                    poly_pass::<true>(map, g, q, v, out)
                } else {
                    let (ps, e) = poly_pass::<false>(map, g, q, v, out);
                    if nl > 0 {
                        // the start state's Σ η̇² + ω²η²: the previous pass's end sum where the
                        // current state is that pass's end (`psums_ok`: nothing moved it since)
                        let s0 = if !from_search && self.psums_ok {
                            self.pe2
                        } else {
                            start_energy2(map, q, v)
                        };
                        debug_assert_eq!(s0.to_bits(), start_energy2(map, q, v).to_bits());
                        map.margin_bounds(g, s0, &mut self.fmargin);
                    }
                    bounded = true;
                    (ps, e)
                };
                self.fpsums = ps;
                self.fe2 = e;
                self.fground = g;
                energy = Some(0.5 * e);
            }
            _ => {
                // no ground load, or harmonic motion with a mode at undamped resonance (its
                // tallies mode by mode in commit_free)
                let (tr_start, tr_end) = (gm.trig(t0), gm.trig(t0 + h));
                for j in 0..n {
                    let c = [0.0; 3];
                    self.cpoly[j] = c;
                    let (e0, d0) = gm.particular(j, piece, &c, 0.0, &tr_start);
                    let (e1, d1) = gm.particular(j, piece, &c, h, &tr_end);
                    let (x0, y0) = (q[j] - e0, v[j] - d0);
                    let (x, y) = props[j].apply(x0, y0);
                    let (x, y) = (x + e1, y + d1);
                    qb[j] = x;
                    vb[j] = y;
                    let a = if margin {
                        herm[j].0 * x0.abs()
                            + herm[j].1 * y0.abs()
                            + fd.herm_part * (e0.abs().max(e1.abs()) + d0.abs().max(d1.abs()))
                    } else {
                        0.0
                    };
                    amp[j] = a;
                }
            }
        }
        // every level's projections and margin, and the modal energy, at the end (of a row,
        // over the level's pair's modes only: the same bits, see `dots_within`)
        if self.row {
            for k in 0..nl {
                let (c, r) = (self.sys.coupling(k), self.sys.coupling_modes(k));
                self.fproj[k] = dots_within(c, &self.qb, &self.vb, r.clone());
                if margin {
                    self.fmargin[k] = dot_within(&self.cabs_t[k * n..(k + 1) * n], &self.amp, r);
                } else if !bounded {
                    self.fmargin[k] = 0.0;
                }
            }
        } else {
            for k in 0..nl {
                let c = self.sys.coupling(k);
                self.fproj[k] = dots(c, &self.qb, &self.vb);
                if margin {
                    self.fmargin[k] = dot(&self.cabs_t[k * n..(k + 1) * n], &self.amp);
                } else if !bounded {
                    self.fmargin[k] = 0.0;
                }
            }
        }
        self.fenergy = match (&self.htally, energy) {
            (_, Some(e)) => e,
            (Some(_), _) if matches!(piece, Piece::Harmonic) => sums.energy,
            _ => {
                let (qb, vb) = (&self.qb[..n], &self.vb[..n]);
                let mut e = 0.0;
                for j in 0..n {
                    e += vb[j] * vb[j] + w2[j] * qb[j] * qb[j];
                }
                0.5 * e
            }
        };
        self.fsums = sums;
        tr1
    }

    /// The contact test's margins of the free step just passed without them under a recorded
    /// motion (its data `fd`, its ground factors in `fground`, from (q, v)): each mode's in
    /// `amp` and every level's in `fmargin`, the same bits a pass with margins gives.
    fn exact_margins(&mut self, fd: Option<usize>) {
        let n = self.n;
        let g = self.fground;
        let fd = match fd {
            Some(i) => &self.free[i],
            None => self.scratch_free.as_ref().expect("scratch free flight"),
        };
        let map = fd.poly.as_ref().expect("the map is built before the pass");
        poly_margins(map, g, &self.q[..n], &self.v[..n], &mut self.amp[..n]);
        for k in 0..self.nl {
            let ca = &self.cabs_t[k * n..(k + 1) * n];
            self.fmargin[k] = if self.row {
                dot_within(ca, &self.amp, self.sys.coupling_modes(k))
            } else {
                dot(ca, &self.amp)
            };
        }
    }

    /// (δ, δ̇) of level k at the state (qb, vb) (from the free flight's projections).
    pub(super) fn level_at_end(&self, k: usize) -> (f64, f64) {
        let (cq, cv) = self.fproj[k];
        self.sys.levels[k].penetration(cq, cv)
    }

    /// The largest penetration any level can reach over a free step of length h from the
    /// levels' (δ, δ̇) in `at` to the state in (qb, vb) (margins in `fmargin`): the cubic
    /// Hermite's maximum plus the modes' margin. Negative: no level can touch.
    ///
    /// `sharp`: the margin weighted as Hermite's remainder is, `16 x²(1 − x)²` of its value at
    /// the middle (x = τ/h: zero at both ends, where the cubic is exact), instead of added at
    /// its largest everywhere — what lets the search clear a level that has just separated.
    #[inline(always)]
    pub(super) fn free_bound(&self, h: f64, sharp: bool) -> f64 {
        let mut bound = f64::NEG_INFINITY;
        for k in 0..self.nl {
            let (d1, dd1) = self.level_at_end(k);
            let (d0, dd0) = self.at[k];
            let margin = self.fmargin[k];
            let m = if sharp {
                quartic_bound(d0, dd0, d1, dd1, h, margin)
            } else {
                // the root solve only where the bound without it, with a slack for the
                // solve's rounding, lets the level reach 0: elsewhere the solve's value too
                // stays ≤ 0 (numerics::hermite's proptest), so the decision is the same
                let slack = 1e-12 * (d0.abs() + d1.abs() + h * (dd0.abs() + dd1.abs()));
                let reach = hermite_bound(d0, dd0, d1, dd1, h) + slack + margin;
                if reach <= 0.0 {
                    reach
                } else {
                    hermite_max(d0, dd0, d1, dd1, h).0 + margin
                }
            };
            bound = bound.max(m);
        }
        bound
    }

    /// The free-flight data `fd` names (a cache entry, or the scratch slot).
    pub(super) fn free_data(&self, fd: Option<usize>) -> &FreeData {
        match fd {
            Some(i) => &self.free[i],
            None => self.scratch_free.as_ref().expect("scratch free flight"),
        }
    }

    crate::numerics::vex::avx_copy! {
        /// Commit the free flight in (qb, vb) over [t, t_end] (h = t_end − t, end trig `tr1`,
        /// free data `fd`, the pass's sums in `fsums`, `fpsums`, `fenergy`, `fproj`): exact
        /// tallies (the ground's work; the dissipation from the modal energy balance), the new
        /// state (no observation).
        ///
        /// Where the processor has AVX, its copy compiled for it runs ([`crate::numerics::vex`]:
        /// the same bits).
        pub(super) fn commit_free(
            &mut self,
            fd: Option<usize>,
            piece: &Piece,
            h: f64,
            t_end: f64,
            tr1: Trig,
        ) => commit_free_vex, commit_free_body
    }

    /// [`Self::commit_free`]'s work.
    #[inline(always)]
    fn commit_free_body(
        &mut self,
        fd: Option<usize>,
        piece: &Piece,
        h: f64,
        t_end: f64,
        tr1: Trig,
    ) {
        let n = self.n;
        let tr0 = self.trig_now;
        let input = match (piece, &self.htally, self.big) {
            (Piece::Harmonic, Some(ht), Some(big)) => {
                let half = self.free_data(fd).half;
                let tm = TrigMoments::from_ends(big, h, (tr0.s, tr0.c), (tr1.s, tr1.c), half);
                let input = ht.input(&tm, &self.sums, &self.fsums);
                self.sums = self.fsums;
                input
            }
            (Piece::Poly { .. }, _, _) => {
                if !self.psums_ok {
                    self.psums = self.ptally.sums(&self.q[..n], &self.v[..n]);
                }
                let w = self
                    .ptally
                    .input(h, self.fground, &self.psums, &self.fpsums);
                self.psums = self.fpsums;
                self.pe2 = self.fe2;
                w
            }
            (Piece::Zero, _, _) => 0.0,
            _ => {
                // harmonic motion with a mode at undamped resonance
                let tm = self
                    .gm
                    .harmonic_omega()
                    .map(|big| TrigMoments::new(big, self.t, h));
                (0..n)
                    .map(|j| {
                        mode_work(
                            &self.gm,
                            j,
                            h,
                            (self.q[j], self.v[j]),
                            (self.qb[j], self.vb[j]),
                            None,
                            tm.as_ref(),
                            0.0,
                            0.0,
                        )
                        .input
                    })
                    .sum()
            }
        };
        self.psums_ok = matches!(piece, Piece::Poly { .. });
        self.tally.input += input;
        self.tally.damping += input - (self.fenergy - self.energy);
        self.energy = self.fenergy;
        std::mem::swap(&mut self.q, &mut self.qb);
        std::mem::swap(&mut self.v, &mut self.vb);
        self.t = t_end;
        self.trig_now = Trig { t: t_end, ..tr1 };
        self.prev_states.copy_from_slice(&self.states);
        for k in 0..self.nl {
            let (cq, cv) = self.fproj[k];
            self.set_state(k, cq, cv);
        }
        update_onsets(&mut self.onset, &self.prev_states, &self.states, h);
        for k in 0..self.nl {
            if self.onset[k] == 0.0 && Self::at_onset(&self.states[k]) {
                self.onset[k] = self.states[k].delta_dot;
            }
        }
        self.impulses();
        self.stats.steps += 1;
    }

    /// Stereomechanical impacts at the current state (a located onset): velocity jumps.
    pub(super) fn impulses(&mut self) {
        if self.sys.has_impulsive()
            && self.sys.apply_impulses(
                &mut self.v,
                &mut self.states,
                &mut self.tally.impulse,
                &mut self.tally.contact,
            )
        {
            self.psums_ok = false;
            self.evaluate_states();
            self.resync_sums();
            self.energy = self.modal_energy();
        }
    }

    /// The modal energy `Σ ½(η̇² + ω²η²)` at the current state, J.
    pub(super) fn modal_energy(&self) -> f64 {
        let w2 = &self.gm.w2;
        (0..self.n)
            .map(|j| 0.5 * (self.v[j] * self.v[j] + w2[j] * self.q[j] * self.q[j]))
            .sum()
    }

    crate::numerics::vex::avx_copy! {
        /// The free flight from the current time to the next grid point, or to the first onset
        /// before it (located on the exact free flight).
        #[inline(never)]
        pub(super) fn free_segment(&mut self) -> Result<(), SolveError> => free_segment_vex, free_segment_body
    }

    /// [`Self::free_segment`]'s work.
    #[inline(always)]
    fn free_segment_body(&mut self) -> Result<(), SolveError> {
        let (piece, start, seg_end) = self.piece();
        let EqualSteps { steps, h: hh, .. } = EqualSteps::new(start, seg_end, self.dt);
        let x = (self.t - start) / hh;
        let i = floor(x + 1e-9) + 1.0;
        let mut target = if i >= steps { seg_end } else { start + i * hh };
        if target - self.t <= 1e-12 * hh && target < seg_end {
            target = if i + 1.0 >= steps {
                seg_end
            } else {
                start + (i + 1.0) * hh
            };
        }
        let h = target - self.t;
        // a grid step keeps its data (its length recurs); a one-off length does not
        let on_grid = (x - round(x)).abs() < 1e-9;
        if self.since_sync == 0 || !on_grid {
            self.trig_now = self.exact_trig(self.t);
        }
        self.since_sync = (self.since_sync + 1) % 16;
        let fd = self.free_index(h, on_grid);
        let check = self.nl > 0;
        // under a recorded motion the pass gives the margins' upper bound (no per-mode work), and
        // the margins themselves are formed only where that bound lets a level touch: the
        // decision is the one the margins give (the bound is at least the margin, and the test
        // grows with it), so nothing else changes
        let lean = check && matches!(piece, Piece::Poly { .. });
        let tr1 = self.free_prop(fd, &piece, self.trig_now, self.t, h, false, check && !lean);
        if check {
            for k in 0..self.nl {
                self.at[k] = Self::free_start(&self.states[k]);
            }
            let mut touch = self.free_bound(h, false) > 0.0;
            if touch && lean {
                self.exact_margins(fd);
                touch = self.free_bound(h, false) > 0.0;
            }
            // (stereomechanical impacts pressed together by the ground chatter without end — a
            // Zeno sequence, bounces 1e-9 s apart: after ZENO located impacts within one grid
            // step, or one at the current instant, the rest of the step is taken whole and its
            // impulse applied at the end, as a fixed-step method does)
            let impulsive = self.sys.has_impulsive();
            if touch && !(impulsive && self.zeno >= ZENO) {
                if let Some(tau) = self
                    .find_onset(&piece, h, on_grid)
                    .filter(|&tau| !(impulsive && tau <= 1e-12 * h))
                {
                    if impulsive {
                        self.zeno += 1;
                    }
                    // under a recorded motion contact steps are dyadic parts of the grid step
                    // (see DYADIC): the free flight ends on that grid just before the onset,
                    // and the first contact step holds it (an onset inside a step is seen by
                    // the estimate); no step of a one-off length is needed to realign
                    let tau = match piece {
                        Piece::Poly { .. } => {
                            let m = self.m_onset.unwrap_or(self.m_step).min(MAX_LEVEL);
                            let unit = hh / (1u64 << m) as f64;
                            let x = (self.t + tau - start) / unit;
                            (start + x.floor() * unit - self.t).max(0.0)
                        }
                        _ => tau,
                    };
                    if tau <= 1e-12 * h {
                        // the onset is within reach now: contact starts here
                        self.force_contact = true;
                        return Ok(());
                    }
                    if matches!(piece, Piece::Poly { .. }) {
                        self.force_contact = true;
                    }
                    // jump to the onset: the exact free flight from the segment's start
                    let fd1 = self.free_index(tau, false);
                    let tr = self.free_prop(fd1, &piece, self.trig_now, self.t, tau, false, false);
                    let t_on = self.t + tau;
                    self.commit_free(fd1, &piece, tau, t_on, tr);
                    self.trig_now = self.exact_trig(self.t);
                    self.since_sync = 1;
                    self.observe();
                    return self.check_finite_free();
                }
                // no onset after all (the search overwrote the end state): the step again
                let fd = self.free_index(h, on_grid);
                let tr1 = self.free_prop(fd, &piece, self.trig_now, self.t, h, false, false);
                self.commit_free(fd, &piece, h, target, tr1);
                return self.finish_segment(on_grid);
            }
        }
        self.commit_free(fd, &piece, h, target, tr1);
        self.finish_segment(on_grid)
    }

    pub(super) fn finish_segment(&mut self, on_grid: bool) -> Result<(), SolveError> {
        self.zeno = 0;
        if !on_grid {
            self.trig_now = self.exact_trig(self.t);
        }
        self.observe();
        self.check_finite_free()
    }

    /// [`Self::check_finite`] after a committed free step, whose modal energy `energy` is
    /// `Σ ½(η̇² + ω²η²)` of the current state: finite only if every value is (ω² > 0; a
    /// NaN or an infinity makes it NaN or ∞), so one comparison clears the usual step and the
    /// scan decides only when it is not (the same error at the same instant as before).
    fn check_finite_free(&self) -> Result<(), SolveError> {
        if self.energy.is_finite() {
            Ok(())
        } else {
            self.check_finite()
        }
    }

    pub(super) fn check_finite(&self) -> Result<(), SolveError> {
        let finite = self.q.iter().chain(&self.v).all(|x| x.is_finite());
        if finite {
            Ok(())
        } else {
            Err(SolveError::Diverged {
                t: self.t,
                contact_omega_dt: self.max_contact_w2h2.sqrt(),
            })
        }
    }
}

/// `x.floor()` without a call into the maths library (the baseline x86-64 target has no
/// rounding instruction): a truncation for 0 ≤ x < 2⁵², where it is the floor exactly.
#[inline(always)]
fn floor(x: f64) -> f64 {
    if (0.0..4.503_599_627_370_496e15).contains(&x) {
        x as u64 as f64
    } else {
        x.floor()
    }
}

/// `x.round()` (half away from zero) as [`floor`] does it: for 0 ≤ x < 2⁵², the floor of
/// x + ½ — equal to the round but where x + ½ rounds up to the next integer (x just below a
/// half), which the grid test of `free_segment` cannot tell apart: both are ½ away from x.
#[inline(always)]
fn round(x: f64) -> f64 {
    if (0.0..4.503_599_627_370_496e15).contains(&x) {
        (x + 0.5) as u64 as f64
    } else {
        x.round()
    }
}

/// [`dot`]`(a, b)` when `a` is zero outside `r` (a row's coupling row outside its level's
/// pair's modes), the same bits from the terms in `r` only. `dot` adds term j to partial sum
/// j mod 4 (for 8 terms and more; below, one chain) and adds the sums as (0 + 2) + (1 + 3);
/// each partial sum here takes the same terms in the same order, less the products 0·b_j,
/// which change none: a sum starts at +0, to which ±0 adds +0, and adding ±0 to a non-zero
/// sum leaves it (for finite b; a NaN or an infinity there is a diverged run either way).
#[inline]
pub(super) fn dot_within(a: &[f64], b: &[f64], r: std::ops::Range<usize>) -> f64 {
    let n = a.len().min(b.len());
    let r = r.start.min(n)..r.end.min(n);
    if n < 8 {
        let mut s = 0.0;
        for j in r {
            s += a[j] * b[j];
        }
        return s;
    }
    let mut acc = [0.0; 4];
    for j in r {
        acc[j & 3] += a[j] * b[j];
    }
    (acc[0] + acc[2]) + (acc[1] + acc[3])
}

/// [`dots`]`(c, x, y)` when `c` is zero outside `r`, the same bits from the terms in `r` only
/// (as [`dot_within`]: `dots` has `dot`'s arithmetic for each).
#[inline]
pub(super) fn dots_within(
    c: &[f64],
    x: &[f64],
    y: &[f64],
    r: std::ops::Range<usize>,
) -> (f64, f64) {
    let n = c.len().min(x.len()).min(y.len());
    let r = r.start.min(n)..r.end.min(n);
    if n < 8 {
        let (mut sx, mut sy) = (0.0, 0.0);
        for j in r {
            sx += c[j] * x[j];
            sy += c[j] * y[j];
        }
        return (sx, sy);
    }
    let (mut ax, mut ay) = ([0.0; 4], [0.0; 4]);
    for j in r {
        ax[j & 3] += c[j] * x[j];
        ay[j & 3] += c[j] * y[j];
    }
    (
        (ax[0] + ax[2]) + (ax[1] + ax[3]),
        (ay[0] + ay[2]) + (ay[1] + ay[3]),
    )
}

#[cfg(test)]
mod tests {
    use super::{dot_within, dots_within, floor, round};
    use crate::integrate::exact_modal::elastic::kernel::dots;
    use crate::numerics::linalg::dot;

    /// `dot_within`/`dots_within` over a range give the bits of `dot`/`dots` over the whole
    /// vector when the first factor is zero (of either sign) outside the range: every length
    /// from 1 to 40 (below and above the four-lane threshold of 8, every remainder), every
    /// range, factors of mixed signs and magnitudes (so that the partial sums round).
    #[test]
    fn sums_within_a_range_are_the_whole_sums_bit_for_bit() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
            (u - 0.5) * 10f64.powi((seed % 7) as i32 - 3)
        };
        for n in 1..=40 {
            for lo in 0..n {
                for hi in lo..=n {
                    let c: Vec<f64> = (0..n)
                        .map(|j| {
                            let x = next();
                            if (lo..hi).contains(&j) {
                                x
                            } else if j % 2 == 0 {
                                0.0
                            } else {
                                -0.0
                            }
                        })
                        .collect();
                    let x: Vec<f64> = (0..n).map(|_| next()).collect();
                    let y: Vec<f64> = (0..n).map(|_| next()).collect();
                    let (a, b) = (dot(&c, &x), dot_within(&c, &x, lo..hi));
                    assert_eq!(a.to_bits(), b.to_bits(), "n {n} range {lo}..{hi}: {a} {b}");
                    let (p, q) = (dots(&c, &x, &y), dots_within(&c, &x, &y, lo..hi));
                    assert_eq!(p.0.to_bits(), q.0.to_bits(), "n {n} range {lo}..{hi}");
                    assert_eq!(p.1.to_bits(), q.1.to_bits(), "n {n} range {lo}..{hi}");
                }
            }
        }
    }

    /// The call-free floor and round equal the standard library's for every value the grid
    /// test meets (grid indices 0…10⁶ and their neighbours by an ulp and by 1e-9, halves and
    /// just below them) and outside the fast range (negative, ≥ 2⁵², infinite); the grid
    /// test's one departure, x just below a half, is ½ away from both candidates.
    #[test]
    fn floor_and_round_without_calls() {
        let mut xs = vec![
            -2.5,
            -1.0,
            -0.3,
            4.6e15,
            1e300,
            f64::INFINITY,
            0.5,
            1.5,
            2.5,
        ];
        for i in (0..1_000_000u64)
            .step_by(997)
            .chain([0, 1, 2, 3, 2000, 8000])
        {
            let x = i as f64;
            xs.extend([x, x.next_up(), x.next_down().max(0.0), x + 1e-9, x - 1e-9]);
            xs.extend([x + 0.5, (x + 0.5).next_down(), (x + 0.5).next_up()]);
        }
        for x in xs {
            assert_eq!(floor(x), x.floor(), "floor {x:e}");
            let (r, want) = (round(x), x.round());
            if r != want {
                assert_eq!(x, 0.5f64.next_down() + x.floor(), "round {x:e}");
                assert!(
                    ((x - r).abs() - 0.5).abs() < 1e-12 && ((x - want).abs() - 0.5).abs() < 1e-12
                );
            }
        }
    }
}
