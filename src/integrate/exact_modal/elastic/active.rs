//! A row's contact step over the structures in (or near) contact only (issue 29).
//!
//! Of a row of N structures, a contact step carries the **active** structures: both of every
//! pair that touches, is at an onset, carried a force over the last step, or whose free flight
//! may close within the current base step. Every level then is one of
//!
//! - **solved** (both its structures active): its nodal forces are the collocation's unknowns,
//!   as every level's are in a pair;
//! - **edge** (one structure active, one passive): its force is zero and its nodal states are
//!   evaluated from the solved forces and the free flight (`collocation::nodal_states`), so
//!   that an onset there is seen inside the step; if the trial reaches it (δ > 0 at a node of
//!   either scheme), the passive structure joins and the trial is redone
//!   ([`Elastic::promote_edges`]);
//! - **passive** (both passive): no force acts on either structure, so their free flight is
//!   exact; it is cleared once per base step by the free flight's own bound (the cubic Hermite
//!   of δ and the modes' margin, [`quartic_bound`]) over the next base step, and a level that may
//!   close joins the step ([`Elastic::update_active`]).
//!
//! The passive modes are carried to the step's end by their exact propagator and particular
//! solution (the same arithmetic as a mode no contact force reaches in the all-active step:
//! the terms left out are products with zero forces), and the step tables hold the responses
//! to the contact loads of the active structures' modes only ([`Table::fill_for`]). What is
//! solved, tabulated and estimated is then that of the structures in contact, not of the row.

use super::*;

impl<'a, O: Observer> Elastic<'a, O> {
    /// Whether level k is engaged: in contact, at an onset, carrying a force at the step's
    /// start or over the last step, or held (its free flight may close before `hold[k]`).
    fn engaged(&self, k: usize) -> bool {
        let st = &self.states[k];
        Self::penetrating(st)
            || Self::at_onset(st)
            || st.force != 0.0
            || self.hold[k] > self.t
            || self.last_f8[k * 5..k * 5 + 5].iter().any(|&f| f != 0.0)
    }

    /// The active structures at the start of a contact step (a row; a pair: both, always), and
    /// the passive levels' free flight cleared over the next base step (`piece`, `span_end`:
    /// the ground's piece and the end of the span the step may not cross).
    pub(super) fn update_active(&mut self, piece: &Piece, span_end: f64) {
        if !self.row || self.all_active {
            return;
        }
        let ns = self.sys.structures.len();
        let mut act = std::mem::take(&mut self.act_next);
        act.clear();
        act.resize(ns, false);
        for k in 0..self.nl {
            if self.engaged(k) {
                let p = self.sys.levels[k].pair;
                act[p] = true;
                act[p + 1] = true;
            }
        }
        // the passive levels: cleared by the last check while no free step came between and
        // the time is within what it cleared
        let fresh_phase = self.t != self.contact_t_end;
        let expired = self.t >= self.passive_safe || fresh_phase;
        let unchecked = (0..self.nl).any(|k| {
            let p = self.sys.levels[k].pair;
            !act[p] && !act[p + 1] && !self.p_checked[k]
        });
        if expired || unchecked {
            let h = (span_end - self.t).min(self.dt);
            if h > 0.0 {
                self.check_passive(piece, h, &mut act);
            }
        }
        if act != self.act {
            std::mem::swap(&mut self.act, &mut act);
            self.set_levels();
        }
        self.act_next = act;
    }

    /// Clear the levels passive under `act` over [t, t + h] on their exact free flight: a level
    /// whose bound reaches δ > 0 joins (both its structures active, held until t + h).
    fn check_passive(&mut self, piece: &Piece, h: f64, act: &mut [bool]) {
        let fd = self.free_index(h, h == self.dt);
        let tr0 = self.exact_trig(self.t);
        self.free_prop(fd, piece, tr0, self.t, h, false, true);
        let until = self.t + h;
        for k in 0..self.nl {
            let p = self.sys.levels[k].pair;
            let passive = !act[p] && !act[p + 1];
            self.p_checked[k] = false;
            if !passive {
                continue;
            }
            let (d0, dd0) = Self::free_start(&self.states[k]);
            let (d1, dd1) = self.level_at_end(k);
            if quartic_bound(d0, dd0, d1, dd1, h, self.fmargin[k]) > 0.0 {
                act[p] = true;
                act[p + 1] = true;
                self.hold[k] = until;
            }
        }
        // (a level passive after the joins was cleared above: its structures were passive)
        for k in 0..self.nl {
            let p = self.sys.levels[k].pair;
            self.p_checked[k] = !act[p] && !act[p + 1];
        }
        self.passive_safe = until;
        self.stats.evaluations += 1;
    }

    /// The levels solved for, at the edge and seen (solved and edge), the active modes, from
    /// `act`; the forces of the levels no longer solved for are zero (they carried none).
    pub(super) fn set_levels(&mut self) {
        let sys = self.sys;
        self.lv_solve.clear();
        self.lv_edge.clear();
        self.lv_seen.clear();
        for k in 0..self.nl {
            let p = sys.levels[k].pair;
            let (a, b) = (self.act[p], self.act[p + 1]);
            if a && b {
                self.lv_solve.push(k);
            } else if a || b {
                self.lv_edge.push(k);
            }
            if a || b {
                self.lv_seen.push(k);
            }
            if !(a && b) {
                self.f8[k * 5..k * 5 + 5].iter_mut().for_each(|f| *f = 0.0);
                self.f6[k * 4..k * 4 + 4].iter_mut().for_each(|f| *f = 0.0);
                self.last_f8[k * 5..k * 5 + 5]
                    .iter_mut()
                    .for_each(|f| *f = 0.0);
            }
        }
        for s in 0..sys.structures.len() {
            let a = self.act[s];
            self.mode_act[sys.modes_of(s)]
                .iter_mut()
                .for_each(|m| *m = a);
        }
    }

    /// After a trial: if it reaches a level at the edge of the active structures (δ > 0 at a
    /// node of either scheme; their nodal states are the trial's), that level's passive
    /// structure joins the step (true: redo the trial).
    pub(super) fn promote_edges(&mut self) -> bool {
        if self.lv_edge.is_empty() {
            return false;
        }
        let sys = self.sys;
        let mut grown = false;
        for i in 0..self.lv_edge.len() {
            let k = self.lv_edge[i];
            let reached = self.nodal8[k * 4..k * 4 + 4].iter().any(|x| x.0 > 0.0)
                || self.nodal6[k * 3..k * 3 + 3].iter().any(|x| x.0 > 0.0);
            if reached {
                let p = sys.levels[k].pair;
                self.act[p] = true;
                self.act[p + 1] = true;
                self.hold[k] = self.t + self.dt;
                grown = true;
            }
        }
        if grown {
            self.set_levels();
        }
        grown
    }
}
