//! exact-modal's yielding storeys (issue 16, docs/model.md §2.6b): their state ([`Yield`]), the
//! base step walked in sub-steps when a building yields, the pseudo-forces held and ramped like
//! the contact forces, z by the trapezoidal rule, and the error estimate over z, the drifts and
//! the kinks of ż. The elastic path of [`Run`] lives in the parent module.

use super::*;
use crate::integrate::plan::DyadicWalk;

/// One yielding storey's drift d (m), drift rate ḋ (m/s), pseudo-force P = (1 − α)k(d_y z − d)
/// (N) and ż (1/s) at a state.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct StoreyState {
    pub(super) d: f64,
    pub(super) dd: f64,
    pub(super) p: f64,
    pub(super) zd: f64,
}

impl Yield {
    /// Mode j's share of the storeys' load over the (sub-)step: adds the ramp
    /// `−Σ_s e_sj (P₁* − P₀)` to `g1` and returns the held part `−Σ_s e_sj P₀` (0 without
    /// yielding storeys).
    #[inline(always)]
    pub(super) fn ramp(&self, j: usize, g1: &mut f64) -> f64 {
        if self.ns == 0 {
            return 0.0;
        }
        let row = &self.rows_t[j * self.ns..(j + 1) * self.ns];
        for ((e, st), p1) in row.iter().zip(&self.now).zip(&self.ppred) {
            *g1 -= e * (p1 - st.p);
        }
        self.held[j]
    }
}

/// The state and scratch of the yielding storeys (docs/model.md §2.6b): their pseudo-forces
/// are loads along the drift rows, treated like the contact forces (linear in time over a
/// sub-step, trapezoidal predictor–corrector), and z is integrated by the trapezoidal rule with
/// the same predictor–corrector (see [`Run::base_step_yielding`]).
#[derive(Default)]
pub(super) struct Yield {
    /// Number of storeys S.
    pub(super) ns: usize,
    /// z of every storey.
    pub(super) z: Vec<f64>,
    /// At the current state.
    pub(super) now: Vec<StoreyState>,
    /// Drift rows transposed, mode-major: `[j·S + s]`.
    pub(super) rows_t: Vec<f64>,
    /// Per mode, the storeys' load `−Σ_s e_sj P_s` held over the (sub-)step (folded into the
    /// free flight (qb, vb)).
    pub(super) held: Vec<f64>,
    /// Per storey, (d, ḋ) of the free flight with the held pseudo-forces.
    pub(super) free: Vec<(f64, f64)>,
    /// Predictor: z₁* = z₀ + h ż₀, ż₁* at the predicted end, P₁*.
    pub(super) zpred: Vec<f64>,
    pub(super) zdpred: Vec<f64>,
    pub(super) ppred: Vec<f64>,
    /// Corrector: z₁ = z₀ + h/2 (ż₀ + ż₁*).
    pub(super) zcorr: Vec<f64>,
    /// P and ż at the start of the last accepted (sub-)step (third point of the curvature).
    pub(super) last_p: Vec<f64>,
    pub(super) last_zd: Vec<f64>,
    /// Scratch over the load rows (levels, then storeys): the generalised load L (F for a
    /// level, −P for a storey) at the start, predicted and corrected end, and the corrected
    /// end's projections.
    pub(super) l0: Vec<f64>,
    pub(super) lpred: Vec<f64>,
    pub(super) lcorr: Vec<f64>,
    /// Level of the last accepted sub-step (where the next base step starts its walk).
    pub(super) level: u32,
}

impl<O: Observer> Run<'_, O> {
    /// Yielding storeys (issue 16): the base step walked in dyadic sub-steps hh/2^m whose
    /// length the error estimate [`Self::estimate_yielding`] chooses (z, every storey's drift
    /// and rate, every level's δ and δ̇ held to the tolerance), m ≥ 0 (m ≥ [`MIN_LEVEL`] when a
    /// level may touch within the base step, and the contact stability rule as in
    /// [`Self::base_step`]). The pseudo-forces act at every instant, so every sub-step is
    /// estimated; the walk starts at the level the last base step ended with.
    pub(super) fn base_step_yielding(
        &mut self,
        t0: f64,
        hh: f64,
        piece: &Piece,
    ) -> Result<(), SolveError> {
        let sys = self.sys;
        let nl = sys.levels.len();
        let idx = self.cache.index(sys, self.big, hh);
        self.free_flight(t0, hh, piece, idx);
        self.hold_storeys(idx);
        let floor = if nl > 0 && self.contact_bound(hh, idx).0 >= 0.0 {
            MIN_LEVEL
        } else {
            0
        };
        let limit = 0.5 * SUBSTEP_ALPHA * SUBSTEP_ALPHA;
        let mut walk = DyadicWalk::new(self.hy.level.max(floor), MAX_LEVEL);
        while !walk.done() {
            let h = walk.length(hh);
            let ts = t0 + walk.offset(hh);
            let idx = self.level_index(hh, walk.level, h);
            self.free_flight(ts, h, piece, idx);
            self.hold_storeys(idx);
            let (bound, worst) = if nl > 0 {
                self.contact_bound(h, idx)
            } else {
                (f64::NEG_INFINITY, 0.0)
            };
            if worst > limit && !walk.finest() {
                walk.refine(1);
                continue;
            }
            let contact = bound >= 0.0;
            self.predict(idx, contact);
            self.predict_storeys(idx, h);
            let err = self.estimate_yielding(h, idx);
            // (a NaN estimate is refined as well)
            if err.is_nan() || err > 1.0 {
                if !walk.finest() {
                    let more = if err.is_finite() {
                        (err.log2() / 3.0).ceil().clamp(1.0, 8.0) as u32
                    } else {
                        1
                    };
                    walk.refine(more);
                    self.stats.rejected += 1;
                    continue;
                }
                return Err(SolveError::ToleranceUnreachable {
                    t: ts,
                    h,
                    rtol: self.tol.rtol,
                });
            }
            self.finish_traced(ts, h, piece, idx, err, true)?;
            walk.advance();
            if 4.0 * worst <= 0.5 * limit && 8.0 * err <= 0.5 && walk.can_coarsen(floor) {
                walk.coarsen();
            }
        }
        self.hy.level = walk.level;
        Ok(())
    }

    /// After the modal state of a (sub-)step of length h is updated: z to its corrected end
    /// value, the storeys at the new state, and each storey's work `∫ P ḋ dt` by Simpson's rule
    /// on the cubic Hermite interpolants of d and z (as the contact work is taken: with the
    /// law's force along the computed motion, so that the energy balance measures the error of
    /// the linearly interpolated load).
    pub(super) fn finish_storeys(&mut self, h: f64) {
        let hyst = &self.sys.hysteresis;
        let hy = &mut self.hy;
        let mut total = 0.0;
        for (s, st) in hyst.storeys().iter().enumerate() {
            let a = hy.now[s];
            let (z0, z1) = (hy.z[s], hy.zcorr[s]);
            let (d, dd) = hyst.drift(s, &self.q, &self.v);
            let b = StoreyState {
                d,
                dd,
                p: st.pseudo_force(d, z1),
                zd: st.z_rate(dd, z1),
            };
            let dm = 0.5 * (a.d + b.d) + h * (a.dd - b.dd) / 8.0;
            let ddm = 1.5 * (b.d - a.d) / h - 0.25 * (a.dd + b.dd);
            let zm = 0.5 * (z0 + z1) + h * (a.zd - b.zd) / 8.0;
            let pm = st.pseudo_force(dm, zm);
            let w = h / 6.0 * (a.p * a.dd + 4.0 * pm * ddm + b.p * b.dd);
            self.tally.storey_work[s] += w;
            total += w;
            hy.last_p[s] = a.p;
            hy.last_zd[s] = a.zd;
            hy.now[s] = b;
            hy.z[s] = z1;
        }
        self.tally.hysteretic += total;
    }

    /// d, ḋ, P and ż of every yielding storey at the current state.
    pub(super) fn evaluate_storeys(&mut self) {
        let hy = &self.sys.hysteresis;
        for (s, st) in hy.storeys().iter().enumerate() {
            let (d, dd) = hy.drift(s, &self.q, &self.v);
            let z = self.hy.z[s];
            self.hy.now[s] = StoreyState {
                d,
                dd,
                p: st.pseudo_force(d, z),
                zd: st.z_rate(dd, z),
            };
        }
    }

    /// Fold the storeys' pseudo-forces, held at their start values over the (sub-)step, into
    /// the free flight (qb, vb) (exact per mode: `g·Γ0`), and widen the contact test's margin by
    /// the oscillation that load starts in each mode (amplitude |g|/ω²).
    pub(super) fn hold_storeys(&mut self, idx: usize) {
        let ns = self.hy.ns;
        let n = self.q.len();
        let data = &self.cache.entries[idx];
        let margin = !self.sys.levels.is_empty() && self.states.iter().any(|st| st.force <= 0.0);
        for j in 0..n {
            let row = &self.hy.rows_t[j * ns..(j + 1) * ns];
            let mut g = 0.0;
            for (e, st) in row.iter().zip(&self.hy.now) {
                g -= e * st.p;
            }
            self.hy.held[j] = g;
            let f = &data.infl[j];
            self.qb[j] += g * f.g0.0;
            self.vb[j] += g * f.g0.1;
            if margin {
                self.amp[j] += data.herm[j].0 * g.abs() * self.gm.inv_w2[j];
            }
        }
    }

    /// The storeys' predictor over a (sub-)step of length h (free flight with the held
    /// pseudo-forces in (qb, vb), predicted level forces in `fpred`): the end drift and rate
    /// with every load held, z₁* = z₀ + h ż₀, ż₁* and P₁* there; and the corrector's
    /// z₁ = z₀ + h/2 (ż₀ + ż₁*) (trapezoidal, as the loads are).
    pub(super) fn predict_storeys(&mut self, idx: usize, h: f64) {
        let sys = self.sys;
        let nl = sys.levels.len();
        let ns = self.hy.ns;
        let nr = nl + ns;
        let data = &self.cache.entries[idx];
        let hyst = &sys.hysteresis;
        for (s, st) in hyst.storeys().iter().enumerate() {
            let (mut d, mut dd) = hyst.drift(s, &self.qb, &self.vb);
            self.hy.free[s] = (d, dd);
            let r = nl + s;
            for l in 0..nl {
                let f0 = self.states[l].force;
                let y = data.y0[r * nr + l];
                d += f0 * y.0;
                dd += f0 * y.1;
            }
            let now = self.hy.now[s];
            let z0 = self.hy.z[s];
            let z1 = z0 + h * now.zd;
            let zd1 = st.z_rate(dd, z1);
            self.hy.zpred[s] = z1;
            self.hy.zdpred[s] = zd1;
            self.hy.ppred[s] = st.pseudo_force(d, z1);
            self.hy.zcorr[s] = z0 + 0.5 * h * (now.zd + zd1);
        }
    }

    /// Scaled local error estimate of the sub-step about to be completed, with yielding
    /// storeys: [`Self::estimate`]'s two parts over every load row (levels and storeys), each
    /// row's load correction acting on every row through the tables [`StepData::y1`],
    /// [`StepData::y2`] (and the onset/release bound of a level through [`StepData::y0`]), plus
    /// z's own: the trapezoidal rule's end-rate correction `h/2·(ż₁ − ż₁*)` and its curvature
    /// term `h³/6·f`, f the second divided difference of ż through the previous step's start,
    /// this one's start and its corrected end (the rule leaves out `f·τ(τ − h)` of ż, which
    /// integrates to `−f h³/6`). Scales: a level's δ and δ̇ as in [`Self::estimate`]; a
    /// storey's drift `atol + rtol·|d|`, its rate `atol·ω₁ + rtol·|ḋ|`, z `atol/d_y + rtol·|z|`
    /// (an error of atol in the drift, as `adaptive` does).
    pub(super) fn estimate_yielding(&mut self, h: f64, idx: usize) -> f64 {
        let sys = self.sys;
        let nl = sys.levels.len();
        let ns = self.hy.ns;
        let nr = nl + ns;
        let data = &self.cache.entries[idx];
        let hp = self.last_h;
        let hy = &mut self.hy;
        for l in 0..nl {
            hy.l0[l] = self.states[l].force;
            hy.lpred[l] = self.fpred[l];
        }
        for s in 0..ns {
            hy.l0[nl + s] = -hy.now[s].p;
            hy.lpred[nl + s] = -hy.ppred[s];
        }
        // the corrected end's projections along every row, and the loads there
        let project = |r: usize, base: (f64, f64), l0: &[f64], lp: &[f64]| {
            let (mut y, mut yd) = base;
            for b in 0..nr {
                let (a0, a1) = (data.y0[r * nr + b], data.y1[r * nr + b]);
                // (the storeys' held loads are in the free flight already)
                let held = if b < nl { l0[b] } else { 0.0 };
                let dl = lp[b] - l0[b];
                y += held * a0.0 + dl * a1.0;
                yd += held * a0.1 + dl * a1.1;
            }
            (y, yd)
        };
        for (k, lv) in sys.levels.iter().enumerate() {
            let (fd, fdd) = self.free_end[k];
            let (y, yd) = project(k, (-fd - lv.gap, -fdd), &hy.l0, &hy.lpred);
            let (d, dd) = lv.penetration(y, yd);
            let v0 = episode_v0(self.onset[k], dd);
            hy.lcorr[k] = lv.force.force(d, dd, v0);
        }
        let storeys = sys.hysteresis.storeys();
        let tol = self.tol;
        let h2 = h * h;
        let mut err = 0.0f64;
        self.kink = false;
        for (s, st) in storeys.iter().enumerate() {
            let (d, dd) = project(nl + s, hy.free[s], &hy.l0, &hy.lpred);
            let z1 = hy.zcorr[s];
            let zd1 = st.z_rate(dd, z1);
            hy.lcorr[nl + s] = -st.pseudo_force(d, z1);
            // z's own error: end-rate correction and curvature of ż
            let zd0 = hy.now[s].zd;
            let f = ((zd1 - zd0) / h - (zd0 - hy.last_zd[s]) / hp) / (h + hp);
            // a kink of ż inside the sub-step (ḋ or z changes sign: ż's slope jumps by Δs
            // there): the rule's error is then h²θ(1 − θ)|Δs|/2 (θ the kink's place in the
            // sub-step, ż linear on either side) while the divided difference gives
            // h³|f|/6 = h³(1 − θ)|Δs|/(6(h + h_p)), so the curvature term is taken
            // 3(h + h_p)/h times (the worst θ → 1)
            let now = hy.now[s];
            let kink = (now.dd * hy.z[s] > 0.0) != (dd * z1 > 0.0);
            self.kink |= kink;
            let weight = if kink { 3.0 * (h + hp) / h } else { 1.0 };
            let mut ez = 0.5 * h * (zd1 - hy.zdpred[s]).abs() + weight * h * h2 * f.abs() / 6.0;
            if (hy.z[s] > 0.0) != (z1 > 0.0) {
                // z crosses 0: the term −(ḋ/d_y)|z|ⁿ(β sign(ḋz) + γ) of ż behaves like
                // |t − t₀|ⁿ there (n ≥ 1 may be 1 or 1.5: no curvature to estimate), so it is
                // bounded instead: it stays within T = max|ḋ|/d_y·max|z|ⁿ(β + |γ|) over the
                // sub-step (z is monotone through its zero), and the rule's error from it
                // within h·T
                let zmax = hy.z[s].abs().max(z1.abs());
                let t = now.dd.abs().max(dd.abs()) / st.dy
                    * zmax.powf(st.n)
                    * (st.beta + st.gamma.abs());
                ez += h * t;
            }
            let z0 = hy.z[s];
            err = err.max(ez / (tol.atol / st.dy + tol.rtol * z0.abs().max(z1.abs())));
        }
        // the loads' corrections and curvatures, seen along every row
        for r in 0..nr {
            let (mut ed, mut ev) = (0.0, 0.0);
            for b in 0..nr {
                let (a0, a1, a2) = (
                    data.y0[r * nr + b],
                    data.y1[r * nr + b],
                    data.y2[r * nr + b],
                );
                let (l0, l1) = (hy.l0[b], hy.lcorr[b]);
                let dl = l1 - hy.lpred[b];
                ed += (dl * a1.0).abs();
                ev += (dl * a1.1).abs();
                if b < nl && (l0 == 0.0) != (l1 == 0.0) {
                    // a level's onset or release inside the sub-step: bounded as in
                    // `estimate`
                    let f = l0.max(l1);
                    self.kink = true;
                    ed += f * a0.0.abs() / 3.0;
                    ev += f * a0.1.abs() / 2.0;
                } else {
                    let lm = if b < nl {
                        self.last_force[b]
                    } else {
                        -hy.last_p[b - nl]
                    };
                    let c = ((l1 - l0) / h - (l0 - lm) / hp) / (h + hp);
                    ed += (h2 * c * a2.0).abs();
                    ev += (h2 * c * a2.1).abs();
                }
            }
            if ed == 0.0 && ev == 0.0 {
                continue;
            }
            let (sd, sv) = if r < nl {
                let st = &self.states[r];
                (
                    (st.delta + sys.levels[r].gap).abs(),
                    st.delta_dot.abs().max(self.onset[r]),
                )
            } else {
                let now = hy.now[r - nl];
                (now.d.abs(), now.dd.abs())
            };
            err = err
                .max(ed / (tol.atol + tol.rtol * sd))
                .max(ev / (tol.atol_rate + tol.rtol * sv));
        }
        err
    }
}
