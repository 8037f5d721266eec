//! Event location of [`Elastic`]: onsets on the exact free flight (dyadic search, Newton on
//! δ = 0, grazes), and inside a contact step the sign changes of δ and the kinks of a law.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::free::dots_within;
use super::*;

impl<'a, O: Observer> Elastic<'a, O> {
    /// The first instant (as an offset from the current time, s) within the next `h` at which a
    /// level's free-flight δ reaches 0, or `None`. Dyadic sub-steps of the free flight are tested
    /// (cubic Hermite plus margin); the first that penetrates at its end brackets the onset,
    /// which Newton iterations on the exact free flight then solve to [`EVENT_TOL`]. A sub-step
    /// whose interpolant touches without its ends doing so (a graze) is checked at the
    /// interpolant's maximum on the exact free flight.
    pub(super) fn find_onset(&mut self, piece: &Piece, h: f64, keep: bool) -> Option<f64> {
        let nl = self.nl;
        self.qs.copy_from_slice(&self.q);
        self.vs.copy_from_slice(&self.v);
        for k in 0..nl {
            self.at[k] = Self::free_start(&self.states[k]);
        }
        let mut tr_a = self.trig_now;
        let mut walk = DyadicWalk::new(0, MAX_SCAN);
        while !walk.done() {
            let len = walk.length(h);
            let a = walk.offset(h);
            let fd = self.free_index(len, keep);
            let tr1 = self.free_prop(fd, piece, tr_a, self.t + a, len, true, true);
            // a level penetrating at the sub-step's end: the onset is inside
            let mut first: Option<(usize, f64)> = None;
            for k in 0..nl {
                let (d1, dd1) = self.level_at_end(k);
                let (d0, dd0) = self.at[k];
                if d0 <= 0.0 && d1 > 0.0 {
                    let th = hermite_crossing(d0, dd0, d1, dd1, len, 60);
                    if first.is_none_or(|f| th < f.1) {
                        first = Some((k, th));
                    }
                }
            }
            if let Some((k, th)) = first {
                let start = self.at[k];
                return Some(self.solve_onset(piece, tr_a, a, len, k, th, start));
            }
            if self.free_bound(len, true) > 0.0 {
                if walk.level < MAX_SCAN - 1 {
                    walk.refine(1);
                    continue;
                }
                // the finest sub-step still may touch: check the interpolant's maximum exactly
                if let Some(tau) = self.graze(piece, tr_a, a, len) {
                    return Some(tau);
                }
            }
            // clear: advance the search state
            std::mem::swap(&mut self.qs, &mut self.qb);
            std::mem::swap(&mut self.vs, &mut self.vb);
            for k in 0..nl {
                let c = self.sys.coupling(k);
                let (cq, cv) = if self.row {
                    dots_within(c, &self.qs, &self.vs, self.sys.coupling_modes(k))
                } else {
                    (dot(c, &self.qs), dot(c, &self.vs))
                };
                self.at[k] = self.sys.levels[k].penetration(cq, cv);
            }
            tr_a = tr1;
            walk.advance();
            while walk.can_coarsen(0) {
                walk.coarsen();
            }
        }
        None
    }

    /// The exact free flight's (δ, δ̇) of level k at offset `s` after the search point a (whose
    /// state is in (qs, vs), trig `tr_a`), the state left in (qb, vb).
    pub(super) fn probe(
        &mut self,
        piece: &Piece,
        tr_a: Trig,
        a: f64,
        s: f64,
        k: usize,
    ) -> (f64, f64) {
        let fd = self.free_index(s, false);
        self.free_prop(fd, piece, tr_a, self.t + a, s, true, false);
        self.level_at_end(k)
    }

    /// Newton iterations on the exact free flight for δ_k = 0 inside the sub-step [a, a + len]
    /// (δ ≤ 0 at a, > 0 at its end), from the Hermite root at fraction `th`; returns the onset's
    /// offset from the current time, the state there in (qb, vb).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn solve_onset(
        &mut self,
        piece: &Piece,
        tr_a: Trig,
        a: f64,
        len: f64,
        k: usize,
        th: f64,
        start: (f64, f64),
    ) -> f64 {
        let (mut lo, mut hi) = (0.0, len);
        if start.0 >= -EVENT_TOL && start.1 >= 0.0 {
            // already at δ = 0, not separating: the onset is the search point itself
            self.qb.copy_from_slice(&self.qs);
            self.vb.copy_from_slice(&self.vs);
            return a;
        }
        let mut s = (th * len).clamp(1e-6 * len, len);
        for _ in 0..60 {
            let (d, dd) = self.probe(piece, tr_a, a, s, k);
            if d.abs() <= EVENT_TOL {
                break;
            }
            if d > 0.0 {
                hi = s;
            } else {
                lo = s;
            }
            let next = if dd > 0.0 { s - d / dd } else { f64::NAN };
            s = if next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            if hi - lo <= 1e-15 * (self.t + a + len).max(len) {
                self.probe(piece, tr_a, a, hi, k);
                s = hi;
                break;
            }
        }
        self.stats.events += 1;
        a + s
    }

    /// A possible graze inside [a, a + len] (ends not penetrating): the exact δ at the
    /// interpolant's maximum, and if it penetrates, the onset before it.
    pub(super) fn graze(&mut self, piece: &Piece, tr_a: Trig, a: f64, len: f64) -> Option<f64> {
        for k in 0..self.nl {
            let (d1, dd1) = self.level_at_end(k);
            let (d0, dd0) = self.at[k];
            let (m, th) = hermite_max(d0, dd0, d1, dd1, len);
            if m + self.fmargin[k] < 0.0 || th <= 0.0 || th >= 1.0 {
                continue;
            }
            let (d, dd) = self.probe(piece, tr_a, a, th * len, k);
            if d > 0.0 {
                let r = hermite_crossing(d0, dd0, d, dd, th * len, 60);
                return Some(self.solve_onset(piece, tr_a, a, th * len, k, r, (d0, dd0)));
            }
            // (the end state of the probe is not the sub-step's: restore it)
            let fd = self.free_index(len, false);
            self.free_prop(fd, piece, tr_a, self.t + a, len, true, true);
        }
        None
    }

    /// The first instant inside the trial just made (length h) at which a level's δ changes
    /// sign — an onset of a level not in contact, or the release of one that is — as a fraction
    /// of the step: the cubic Hermite root between the nodes on both sides.
    pub(super) fn event_inside(&self, h: f64) -> Option<f64> {
        let mut best: Option<f64> = None;
        // (a row: the levels the step sees; the others' nodal states are not evaluated)
        for &k in &self.lv_seen {
            let st = &self.states[k];
            let inside = Self::penetrating(st);
            if !inside && Self::at_onset(st) {
                continue;
            }
            let mut prev = (st.delta, st.delta_dot, 0.0);
            for p in 0..4 {
                let (d, dd) = self.nodal8[k * 4 + p];
                let th = THETA8[p + 1];
                let crossing = if inside {
                    prev.0 > 0.0 && d <= 0.0
                } else {
                    prev.0 <= 0.0 && d > 0.0
                };
                if crossing {
                    let span = (th - prev.2) * h;
                    let x = if inside {
                        hermite_crossing(-prev.0, -prev.1, -d, -dd, span, 60)
                    } else {
                        hermite_crossing(prev.0, prev.1, d, dd, span, 60)
                    };
                    let theta = prev.2 + (th - prev.2) * x;
                    if best.is_none_or(|b| theta < b) {
                        best = Some(theta);
                    }
                    break;
                }
                prev = (d, dd, th);
            }
        }
        best
    }

    /// The first kink of a level's law inside the trial just made (Kelvin's and the damped
    /// Hertz law's no-tension clamp, Jankowski's switch at δ̇ = 0: [`ContactForce::kink`]
    /// changing sign), as a fraction of the step: the root of the quartic through the kink
    /// function's values at the nodes (it is smooth across the kink, the force is not). Kinks
    /// within 1e-9 of the step (length h) of its ends, or within time's resolution of them
    /// ([`KINK_FLOOR_ULPS`] units in the last place of t), are left where they are: a step
    /// that ends there cannot be told from the step's start in time, and after a kink located
    /// a round-off short of it (the kink function, e.g. Jankowski's δ̇, at a round-off of 0 on
    /// its side) its roots would be re-found at the next step's start without end, each
    /// located step shorter and none advancing time. Straddled, a kink that close errs by the
    /// jump of the force's slope times that offset: nothing.
    ///
    /// [`ContactForce::kink`]: crate::model::contact::ContactForce::kink
    pub(super) fn law_kink_inside(&self, h: f64) -> Option<(usize, f64, f64)> {
        let bases = collocation::bases();
        let floor = self.kink_floor_ulps * f64::EPSILON * (self.t.abs() + self.dt) / h;
        let (first, last) = (floor.max(1e-9), 1.0 - floor.max(1e-9));
        let mut best: Option<(usize, f64, f64)> = None;
        for &k in &self.lv_seen {
            let st = &self.states[k];
            if !(Self::penetrating(st) || Self::at_onset(st)) {
                continue;
            }
            let law = &self.sys.levels[k].force;
            let v0 = |dd: f64| episode_v0(self.onset[k], dd);
            let Some(g0) = law.kink(st.delta.max(0.0), st.delta_dot, v0(st.delta_dot)) else {
                continue;
            };
            let mut g = [g0; 5];
            for p in 1..5 {
                let (d, dd) = self.nodal8[k * 4 + p - 1];
                g[p] = law.kink(d, dd, v0(dd)).unwrap_or(g0);
            }
            let Some(p) = (1..5).find(|&p| (g[p] > 0.0) != (g[p - 1] > 0.0)) else {
                continue;
            };
            let (mut lo, mut hi) = (THETA8[p - 1], THETA8[p]);
            let side = g[p - 1] > 0.0;
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if (bases.quartic_at(&g, mid) > 0.0) == side {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let theta = 0.5 * (lo + hi);
            let scale = g.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            if theta > first && theta < last && best.is_none_or(|b| theta < b.1) {
                best = Some((k, theta, scale));
            }
        }
        best
    }

    /// The trial ending at the kink of level `lev`'s law (first guess: fraction `th` of h):
    /// Illinois iterations on the step length, each step redone by the collocation, until the
    /// kink function at the end is within 1e-10 of its scale on the step (a step ending short
    /// of the kink leaves a sliver of force to the next step, which spreads it over its whole
    /// length).
    pub(super) fn locate_kink(
        &mut self,
        piece: &Piece,
        h: f64,
        lev: usize,
        th: f64,
        scale: f64,
    ) -> Trial {
        let law = self.sys.levels[lev].force;
        let g_end = |r: &Self| {
            let (d, dd) = r.nodal8[lev * 4 + 3];
            let v0 = episode_v0(r.onset[lev], dd);
            law.kink(d, dd, v0).unwrap_or(0.0)
        };
        let st = self.states[lev];
        let v0 = episode_v0(self.onset[lev], st.delta_dot);
        let (mut a, mut fa) = (
            0.0,
            law.kink(st.delta.max(0.0), st.delta_dot, v0).unwrap_or(0.0),
        );
        let (mut b, mut fb) = (h, g_end(self));
        let mut s = th * h;
        let mut side = 0;
        let mut last = Trial {
            err: f64::INFINITY,
            h: s,
            k: None,
        };
        for _ in 0..8 {
            last = self.trial(None, s, piece).unwrap_or(Trial {
                err: f64::INFINITY,
                h: s,
                k: None,
            });
            let fs = g_end(self);
            if !last.err.is_finite()
                || fs.abs() <= 1e-10 * scale
                || (fs > 0.0) == (fb > 0.0) && (fs > 0.0) == (fa > 0.0)
            {
                break;
            }
            if (fs > 0.0) == (fa > 0.0) {
                (a, fa) = (s, fs);
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            } else {
                (b, fb) = (s, fs);
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            }
            s = if fb == fa {
                0.5 * (a + b)
            } else {
                (a * fb - b * fa) / (fb - fa)
            };
            if !(s > a && s < b) {
                s = 0.5 * (a + b);
            }
        }
        self.stats.events += 1;
        last
    }
}
