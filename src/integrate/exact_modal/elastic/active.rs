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
        if self.act.iter().any(|a| !a) {
            self.passive_steps += 1;
        }
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

    /// The next grid point after the current time (free flight's, see `free_segment`): the
    /// piece's equal steps no longer than dt.
    pub(super) fn next_grid_point(&self) -> f64 {
        let (_, start, seg_end) = self.piece();
        let EqualSteps { steps, h: hh, .. } = EqualSteps::new(start, seg_end, self.dt);
        let i = ((self.t - start) / hh + 1e-9).floor() + 1.0;
        if i >= steps { seg_end } else { start + i * hh }
    }

    /// Observe the end of an accepted contact step. A row tells the observer which
    /// structures the step carried ([`Observer::observe_stepped`]): the passive ones moved in
    /// exact free flight and may be observed on the grid only, as free flight is, and every
    /// structure is seen at the first observation at or past each grid point (a recorded
    /// motion's contact steps end on its grid points; a harmonic one's may pass them).
    pub(super) fn observe_step(&mut self) {
        if !self.row {
            return self.observe();
        }
        let grid = self.t >= self.obs_grid - 1e-9 * self.dt || self.t >= self.duration;
        self.obs.observe_stepped(
            self.sys,
            &StepView {
                t: self.t,
                q: &self.q,
                v: &self.v,
                levels: &self.states,
                z: &[],
                tally: &self.tally,
            },
            &Stepped {
                active: &self.act,
                grid,
            },
        );
        if grid {
            self.obs_grid = self.next_grid_point();
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
            self.edge_redos += 1;
        }
        grown
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::scenario::Scenario;

    /// One observation: time, modal displacements and velocities, the levels' forces.
    type Seen = (f64, Vec<f64>, Vec<f64>, Vec<f64>);
    /// Every observation.
    #[derive(Default)]
    struct Log(Vec<Seen>);
    impl Observer for Log {
        fn observe(&mut self, _: &System, s: &StepView) {
            let f = s.levels.iter().map(|l| l.force).collect();
            self.0.push((s.t, s.q.to_vec(), s.v.to_vec(), f));
        }
    }

    /// A shear building of the test rows: `n` storeys of 3.5 m and 2e5 kg, storey stiffness `k`
    /// (N/m), every mode kept.
    fn b(name: &str, n: usize, k: f64) -> String {
        format!(
            "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
             storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\n\
             damping_ratio = 0.05\nmodes = {n}\n"
        )
    }

    /// A Hertz contact (2e10 N/m^1.5) between `a` and `bb` at height `h` (m) with `gap` (m).
    fn c(a: &str, bb: &str, h: f64, gap: f64) -> String {
        format!(
            "[[contact]]\nbetween = [\"{a}\", \"{bb}\"]\nlaw = \"hertz\"\n\
             stiffness = 2.0e10\nheight = {h}\ngap = {gap}\n"
        )
    }

    /// A row of four shear buildings A–B–C–D under harmonic motion: A–B at 14 m (gap 1 cm),
    /// B–C at 10.5 m with gap `middle`, C–D at 10.5 m with gap `last`.
    fn row(middle: f64, last: f64) -> System {
        let text = format!(
            "{}{}{}{}{}{}{}[ground_motion]\nkind = \"harmonic\"\npga = 0.35\nperiod = 0.8\n\
             [solver]\nmethod = \"exact-modal\"\ndt = 0.002\nduration = 6.0\n",
            b("A", 4, 3.0e8),
            b("B", 5, 1.6e8),
            b("C", 3, 1.0e8),
            b("D", 4, 2.4e8),
            c("A", "B", 14.0, 0.01),
            c("B", "C", 10.5, middle),
            c("C", "D", 10.5, last),
        );
        Scenario::from_toml(&text, "row.toml", std::path::Path::new("."))
            .unwrap_or_else(|e| panic!("{e}"))
            .system()
    }

    /// The run of `sys`, every contact step over all its structures (`all`) or over the
    /// active ones: the observations, the impulse per level, the passive steps, the redos.
    fn run(sys: &System, all: bool) -> (Log, Vec<f64>, usize, usize) {
        let settings = SolverSettings::new(Method::ExactModal, 0.002, 6.0);
        let (q0, v0) = InitialState::default().resolved(sys.len());
        let mut log = Log::default();
        let mut r = Elastic::new(sys, &settings, &mut log, None, 0.0, q0, v0, None);
        r.all_active = all;
        r.drive_here().expect("runs");
        let out = (r.tally.impulse.clone(), r.passive_steps, r.edge_redos);
        drop(r);
        (log, out.0, out.1, out.2)
    }

    /// A gap for B–C at which it first closes after A–B's first impact, if it can be while A–B
    /// touches (from the row `make(gap)` with B–C open: the run is the open one's until B–C
    /// closes).
    fn late_gap(make: &dyn Fn(f64) -> System) -> f64 {
        let open = make(10.0);
        let (log, imp, _, _) = run(&open, true);
        assert!(imp[0] > 0.0, "A–B pounds: {imp:?}");
        assert_eq!(imp[1], 0.0);
        let c = open.coupling(1);
        let approach = |q: &[f64]| -dot(c, q);
        let a_max = log
            .0
            .iter()
            .map(|(_, q, _, _)| approach(q))
            .fold(f64::NEG_INFINITY, f64::max);
        let first_impact = log
            .0
            .iter()
            .find(|(_, _, _, f)| f[0] != 0.0 || f[2] != 0.0)
            .map(|x| x.0)
            .expect("an impact");
        // (preferably the largest approach while A–B touches, when B–C's first crossing of it
        // is inside an A–B contact phase — its onset seen inside a contact step — else just
        // under the largest approach)
        let first_crossing = |gap: f64| log.0.iter().find(|(_, q, _, _)| approach(q) > gap);
        let touching = log
            .0
            .iter()
            .filter(|(_, _, _, f)| f[0] != 0.0)
            .map(|(_, q, _, _)| approach(q))
            .fold(f64::NEG_INFINITY, f64::max);
        let gap = match first_crossing(0.999 * touching) {
            Some((_, _, _, f)) if touching > 0.0 && f[0] != 0.0 => 0.999 * touching,
            _ => 0.97 * a_max,
        };
        let closes = first_crossing(gap).expect("closes").0;
        eprintln!(
            "B–C: largest approach {a_max:.5} m, gap {gap:.5} m closes at {closes:.3} s; first impact {first_impact:.3} s"
        );
        assert!(a_max > 0.0 && closes > first_impact);
        gap
    }

    /// A gap for B–C that it first reaches inside a contact step of A–B's or C–D's (from the
    /// row `make(gap)` with B–C open: the run is the open one's until B–C closes): halfway
    /// between B–C's largest approach so far and a new largest one at an observation that ends
    /// a step with that pair's force at both its ends, so that δ of B–C crosses 0 inside a
    /// step while one of its structures pounds its other neighbour.
    fn edge_gap(make: &dyn Fn(f64) -> System) -> f64 {
        let open = make(10.0);
        let (log, _, _, _) = run(&open, true);
        let c = open.coupling(1);
        let mut most = f64::NEG_INFINITY;
        for w in log.0.windows(2) {
            let (before, now) = (&w[0], &w[1]);
            let a = -dot(c, &now.1);
            let touch = |k: usize| before.3[k] != 0.0 && now.3[k] != 0.0;
            if a > most && most > 1e-5 && (touch(0) || touch(2)) {
                let gap = 0.5 * (most + a);
                eprintln!(
                    "B–C: gap {gap:.6} m first reached at {:.4} s (A–B touching: {}, C–D: {})",
                    now.0,
                    touch(0),
                    touch(2)
                );
                return gap;
            }
            most = most.max(a);
        }
        panic!("B–C never reaches a new largest approach while A–B or C–D touches");
    }

    /// A row's accepted steps under a recorded motion take one pass over the modes,
    /// structure by structure, the passive structures' modes two at a time
    /// (`row_pass::row_poly_pass`): the row of four (4, 5, 3 and 4 modes: odd structures leave
    /// a mode to the scalar tail) under the first 4 s of Loma Prieta at 0.4 g with gaps that
    /// close (A–B and C–D pound while the other pair is passive, B–C too at times) gives every
    /// observation — time, every modal coordinate and velocity, every level's force — and
    /// every tally (impulses, the ground's work, dissipation, contact work) equal to the last
    /// bit to the same run on the general loops, while hundreds of its contact steps leave
    /// structures passive.
    #[test]
    fn the_row_pass_is_the_general_accepted_step_to_the_last_bit() {
        let record = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/records/RSN753_LOMAP_CLS000.AT2");
        let text = format!(
            "{}{}{}{}{}{}{}[ground_motion]\nkind = \"record\"\nfile = \"{}\"\n\
             scale_to_pga = 0.4\n[solver]\nmethod = \"exact-modal\"\ndt = 0.005\n\
             duration = 4.0\n",
            b("A", 4, 3.0e8),
            b("B", 5, 1.6e8),
            b("C", 3, 1.0e8),
            b("D", 4, 2.4e8),
            c("A", "B", 14.0, 0.002),
            c("B", "C", 10.5, 0.004),
            c("C", "D", 10.5, 0.002),
            record.display(),
        );
        let sys = Scenario::from_toml(&text, "row.toml", std::path::Path::new("."))
            .unwrap_or_else(|e| panic!("{e}"))
            .system();
        let (g, p) = (both_ways(&sys, false), both_ways(&sys, true));
        eprintln!(
            "{} observations, {} contact steps with a passive structure, impulses {:?}",
            p.seen.len(),
            p.passive,
            p.impulses
        );
        assert!(
            p.impulses.iter().all(|&i| i > 0.0),
            "every pair pounds: {:?}",
            p.impulses
        );
        assert!(p.passive > 100 && p.passive == g.passive, "{}", p.passive);
        assert_same_bits(&g, &p);
    }

    /// A pair with several contact levels under a recorded motion takes the row's one pass
    /// over the modes too (`row_pass::row_poly_pass`: a pair is a row of two whose every
    /// mode is forced and couples to every level): two buildings of 5 and 4 storeys (odd:
    /// both structures leave a mode to the scalar tail) with Hertz contact at three floors,
    /// under the first 4 s of Loma Prieta at 0.4 g, give every observation — time, every
    /// modal coordinate and velocity, every level's force — and every tally equal to the last
    /// bit to the same run on the pair's per-mode loops (`PairLevel`'s sums), while all three
    /// levels pound.
    #[test]
    fn a_pairs_several_level_step_through_the_row_pass_is_the_pair_loops_to_the_last_bit() {
        let record = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/records/RSN753_LOMAP_CLS000.AT2");
        let level = |h: f64| format!("[[contact.level]]\nheight = {h}\ngap = 0.002\n");
        let text = format!(
            "{}{}[contact]\nlaw = \"hertz\"\nstiffness = 2.0e10\n{}{}{}\
             [ground_motion]\nkind = \"record\"\nfile = \"{}\"\nscale_to_pga = 0.4\n\
             [solver]\nmethod = \"exact-modal\"\ndt = 0.005\nduration = 4.0\n",
            b("A", 5, 1.6e8),
            b("B", 4, 3.0e8),
            level(14.0),
            level(10.5),
            level(7.0),
            record.display(),
        );
        let sys = Scenario::from_toml(&text, "pair.toml", std::path::Path::new("."))
            .unwrap_or_else(|e| panic!("{e}"))
            .system();
        assert_eq!((sys.structures.len(), sys.levels.len()), (2, 3));
        let (g, p) = (both_ways(&sys, false), both_ways(&sys, true));
        eprintln!(
            "{} observations, {} steps, impulses {:?}",
            p.seen.len(),
            p.steps,
            p.impulses
        );
        assert!(
            p.impulses.iter().all(|&i| i > 0.0),
            "every level pounds: {:?}",
            p.impulses
        );
        assert_eq!(g.steps, p.steps);
        assert_same_bits(&g, &p);
    }

    /// What a run of [`both_ways`] leaves: every observation, the tallies' bits and counts.
    struct Ran {
        seen: Vec<Seen>,
        impulses: Vec<f64>,
        flows: [u64; 3],
        passive: usize,
        steps: usize,
    }

    /// `sys` under `exact-modal` at 5 ms over 4 s, its accepted steps through the row's one
    /// pass over the modes (`pass`) or the general loops.
    fn both_ways(sys: &System, pass: bool) -> Ran {
        let settings = SolverSettings::new(Method::ExactModal, 0.005, 4.0);
        let (q0, v0) = InitialState::default().resolved(sys.len());
        let mut log = Log::default();
        let mut r = Elastic::new(sys, &settings, &mut log, None, 0.0, q0, v0, None);
        r.row_pass = pass;
        let stats = r.drive_here().expect("runs");
        let t = &r.tally;
        let (impulses, flows, passive) = (
            t.impulse.clone(),
            [t.input, t.damping, t.contact].map(f64::to_bits),
            r.passive_steps,
        );
        drop(r);
        Ran {
            seen: log.0,
            impulses,
            flows,
            passive,
            steps: stats.steps,
        }
    }

    /// Every observation (time, modal coordinates and velocities, level forces) and every
    /// tally of `a` and `b` equal to the last bit.
    fn assert_same_bits(a: &Ran, b: &Ran) {
        assert_eq!(a.seen.len(), b.seen.len());
        for (x, y) in a.seen.iter().zip(&b.seen) {
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(x.0.to_bits(), y.0.to_bits());
            assert_eq!(bits(&x.1), bits(&y.1), "q at t = {}", x.0);
            assert_eq!(bits(&x.2), bits(&y.2), "q̇ at t = {}", x.0);
            assert_eq!(bits(&x.3), bits(&y.3), "forces at t = {}", x.0);
        }
        assert_eq!(a.impulses, b.impulses);
        assert_eq!(a.flows, b.flows);
    }

    /// A row's step table filled for some active structures holds exactly what a step over
    /// them reads, and grown ([`Table::ensure`], [`Table::ensure_mid`]) it is the table filled
    /// for every structure, bit for bit: every mode's P(h), the coupled propagators of every
    /// level next to an active structure, the active modes' responses and the level tables.
    #[test]
    fn a_table_grown_from_an_active_set_is_the_full_table() {
        let sys = row(0.01, 0.01);
        let h = 1.3e-3;
        let full = Table::new(&sys, None, h);
        let ns = sys.structures.len();
        let same_mode = |t: &Table, j: usize, responses: bool, mid: bool| {
            let (a, b) = (&t.modes[j], &full.modes[j]);
            assert_eq!(a.end, b.end, "P(h) of mode {j}");
            if mid {
                assert_eq!(a.mid, b.mid, "interior nodes of mode {j}");
            }
            if responses {
                assert_eq!(a.end8, b.end8, "mode {j}");
                assert_eq!(a.mid8, b.mid8, "mode {j}");
            }
        };
        let same_cprop = |t: &Table, k: usize| {
            for i in 0..6 {
                assert_eq!(
                    t.cprop_at(&sys, k, i),
                    full.cprop_at(&sys, k, i),
                    "level {k}"
                );
            }
        };
        for act in [
            [true, true, false, false],
            [false, false, false, true],
            [false, true, false, false],
            [true, false, false, false],
        ] {
            let mut t = Table::new_for(&sys, None, h, &act);
            for s in 0..ns {
                let near = act[s] || (s > 0 && act[s - 1]) || (s + 1 < ns && act[s + 1]);
                for j in sys.modes_of(s) {
                    same_mode(&t, j, act[s], near);
                }
            }
            for k in 0..sys.levels.len() {
                let p = sys.levels[k].pair;
                if act[p] || act[p + 1] {
                    same_cprop(&t, k);
                }
            }
            // grown: first by a neighbour (the levels newly next to it), then to every
            // structure and every interior node
            let mut more = act;
            let first = (0..ns).find(|&s| !act[s]).expect("a passive structure");
            more[first] = true;
            t.ensure(&sys, &more);
            t.ensure(&sys, &[true; 4]);
            t.ensure_mid(&sys);
            for j in 0..sys.len() {
                same_mode(&t, j, true, true);
            }
            for k in 0..sys.levels.len() {
                same_cprop(&t, k);
            }
            assert_eq!(t.w8, full.w8, "{act:?}");
            assert_eq!(t.w6, full.w6, "{act:?}");
            assert_eq!(t.w86, full.w86, "{act:?}");
        }
    }

    /// The edge of the active structures (issue 29): the row of four whose B–C gap is first
    /// reached inside a contact step of C–D's ([`edge_gap`]: 0.32 mm, at 0.283 s) while B is
    /// passive — B–C is then a level at the edge, and the trial that reaches it (δ > 0 at its
    /// nodes) is redone with B active ([`Elastic::promote_edges`]). The run redoes trials
    /// (counted: 39), and every observation and impulse equals the all-active run's to the last
    /// bit: the redone trial starts from the same state as the all-active step's, and what it
    /// leaves out are products with zero forces, as in every step.
    #[test]
    fn a_trial_that_reaches_an_edge_is_redone_as_the_all_active_step() {
        let make = |gap: f64| row(gap, 0.01);
        let sys = make(edge_gap(&make));
        let (all, imp_all, _, _) = run(&sys, true);
        let (act, imp_act, passive, redos) = run(&sys, false);
        eprintln!("{passive} contact steps with a passive structure, {redos} trials redone");
        assert!(imp_all[1] > 0.0, "B–C pounds: {imp_all:?}");
        assert!(redos > 0, "a trial reached the edge and was redone");
        assert_eq!(all.0.len(), act.0.len());
        for (x, y) in all.0.iter().zip(&act.0) {
            assert_eq!(x, y, "at t = {}", x.0);
        }
        assert_eq!(imp_all, imp_act);
    }

    /// The contact step over the active structures is the all-active step with the products
    /// by zero forces left out: a row of four where A–B and C–D pound and B–C closes late
    /// (in the middle of A–B's pounding, [`late_gap`]), and the same row with C–D open (10 m),
    /// where B–C is at the edge of A–B's steps while C is passive (an onset there inside a
    /// contact step is seen in the trial, which is redone with C), give every observation — time, every modal coordinate and velocity, every
    /// level's force — and every level's impulse equal to the last bit to the all-active run,
    /// while many of their contact steps leave structures passive.
    #[test]
    fn the_active_step_is_the_all_active_step_to_the_last_bit() {
        let four = |gap: f64| row(gap, 0.01);
        let three = |gap: f64| row(gap, 10.0);
        for (name, make) in [("four", &four as &dyn Fn(f64) -> System), ("three", &three)] {
            let sys = make(late_gap(make));
            let (all, imp_all, passive_all, _) = run(&sys, true);
            let (act, imp_act, passive, redos) = run(&sys, false);
            assert_eq!(passive_all, 0);
            assert!(imp_all[1] > 0.0, "{name}: B–C pounds: {imp_all:?}");
            eprintln!(
                "{name}: {} observations; {passive} contact steps with a passive structure, {redos} trials redone",
                act.0.len()
            );
            assert_eq!(all.0.len(), act.0.len(), "{name}");
            for (x, y) in all.0.iter().zip(&act.0) {
                assert_eq!(x, y, "{name}: at t = {}", x.0);
            }
            assert_eq!(imp_all, imp_act, "{name}");
            assert!(passive > 100, "{name}: {passive}");
        }
    }
}
