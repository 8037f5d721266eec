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

impl<'a, O: Observer> Elastic<'a, O> {
    /// Whether the contact steps take the one-level path: a pair (two structures) with a single
    /// contact level.
    #[inline]
    pub(super) fn single_level(&self) -> bool {
        self.nl == 1 && self.sys.structures.len() == 2
    }

    /// [`Elastic::trial_general`] for one contact level of a pair ([`Self::single_level`]):
    /// the same trial (free flight to the six nodes, both collocations, the estimate) with the
    /// same arithmetic, on stack arrays. Harmonic motion with a mode at undamped resonance (its
    /// particular solutions at every node: rare) takes the general path.
    pub(super) fn trial_one(
        &mut self,
        k: Option<usize>,
        h: f64,
        piece: &Piece,
    ) -> Result<Trial, NoConvergence> {
        debug_assert!(self.single_level());
        let plain = self.gm.harmonic_plain().is_some();
        match (piece, plain) {
            (Piece::Harmonic, true) | (Piece::Poly { .. }, _) | (Piece::Zero, _) => {}
            _ => return self.trial_general(k, h, piece),
        }
        let n = self.n;
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
        // the free flight's particular solution projected on the level at the six nodes
        let mut df = [(0.0, 0.0); 6];
        let (q, v) = (&self.q[..n], &self.v[..n]);
        let (x0s, y0s) = (&mut self.x0[..n], &mut self.y0[..n]);
        let gm = &self.gm;
        match (piece, gm.harmonic_plain()) {
            (Piece::Harmonic, Some((big, g_re, g_im))) => {
                let (g_re, g_im) = (&g_re[..n], &g_im[..n]);
                for j in 0..n {
                    let (gr, gi) = (g_re[j], g_im[j]);
                    x0s[j] = q[j] - (gr * tr0.s + gi * tr0.c);
                    y0s[j] = v[j] - big * (gr * tr0.c - gi * tr0.s);
                }
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
        // nodes, the level's block of coupled propagators node by node (a pair: every mode)
        let block = tab.cprop_single(n);
        let rows: [&[[f64; 4]]; 6] = std::array::from_fn(|i| &block[i * n..(i + 1) * n]);
        let mut acc = [(0.0, 0.0); 6];
        for (jj, (&x, &y)) in self.x0[..n].iter().zip(&self.y0[..n]).enumerate() {
            for (s, row) in acc.iter_mut().zip(&rows) {
                let [a, c, b, e] = row[jj];
                s.0 += a * x + b * y;
                s.1 += c * x + e * y;
            }
        }
        let lv = &sys.levels[0];
        for (x, s) in df.iter_mut().zip(acc) {
            x.0 = lv.delta(-(x.0 - s.0));
            x.1 -= s.1;
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

    /// What a trial leaves: the estimate, the forces and nodal states of both schemes, the
    /// free flight to the six nodes.
    type Left = (
        f64,
        Vec<f64>,
        Vec<f64>,
        Vec<(f64, f64)>,
        Vec<(f64, f64)>,
        Vec<(f64, f64)>,
    );

    /// One trial of length h from `tr`'s start state, by the one-level path or the general
    /// one, after a first step of length h (so that the first guess comes from a previous
    /// step's quartic, as inside an impact).
    fn trial(sys: &System, tr: &StepTrace, h: f64, single: bool) -> Left {
        let settings = SolverSettings::new(Method::ExactModal, 1e-3, 10.0);
        let mut quiet = Quiet;
        let mut r = Elastic::new(
            sys,
            &settings,
            &mut quiet,
            None,
            tr.t,
            tr.q0.clone(),
            tr.v0.clone(),
            Some(&tr.onset),
        );
        let mut last = None;
        for _ in 0..2 {
            let (piece, _, _) = r.piece();
            let t = if single {
                r.trial_one(None, h, &piece)
            } else {
                r.trial_general(None, h, &piece)
            }
            .expect("converges");
            if last.is_none() {
                let t_end = r.t + h;
                r.accept(&piece, t, t_end);
            }
            last = Some(t);
        }
        (
            last.expect("trial").err,
            r.f8.clone(),
            r.f6.clone(),
            r.nodal8.clone(),
            r.nodal6.clone(),
            r.dfree.clone(),
        )
    }

    /// The one-level trial equals the general path's on the same state, under harmonic motion
    /// and a record (their particular solutions take different branches), on the elastic and
    /// the damped laws, at steps from inside an impact and at its onset: the same arithmetic in
    /// the same order, so equal bit for bit (compared to 0 ulp; the general path is itself
    /// tested against closed forms and an independent integration in `elastic::tests`).
    #[test]
    fn the_one_level_trial_equals_the_general_one() {
        // (the bundled Loma Prieta record scaled to 1 g: its strong motion pounds within 8 s)
        let record = "kind = \"record\"\nfile = \"records/RSN753_LOMAP_CLS000.AT2\"\n\
                      scale_to_pga = 1.0";
        let harmonic = "kind = \"harmonic\"\npga = 0.5\nperiod = 0.8";
        let mut compared = 0;
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
                    let h = tr.h;
                    let a = trial(&sys, tr, h, true);
                    let b = trial(&sys, tr, h, false);
                    assert_eq!(a.0.to_bits(), b.0.to_bits(), "estimate at t = {}", tr.t);
                    assert_eq!(a, b, "{law} / {ground} at t = {}", tr.t);
                    compared += 1;
                }
            }
        }
        assert!(compared > 50, "{compared} trials compared");
    }
}
