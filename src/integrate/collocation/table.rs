//! [`Table`]: everything of a step of length h that does not depend on the state (every
//! mode's propagators to the nodes and responses to the Lagrange loads, the level tables).

use super::nodes::{Bases, END, NODES, NODES6, NODES8, bases};
use crate::integrate::linear::{Prop, propagator};
use crate::model::system::System;

/// 1/k for k < 70 (the series' factorials without divisions).
fn reciprocals() -> &'static [f64; 70] {
    static R: std::sync::OnceLock<[f64; 70]> = std::sync::OnceLock::new();
    R.get_or_init(|| std::array::from_fn(|k| if k == 0 { 0.0 } else { 1.0 / k as f64 }))
}

/// One mode's propagators `P(θ_i h)` to every node of [`NODES`] (ω rad/s, damp = 2ζω 1/s).
#[inline]
fn node_props(omega: f64, damp: f64, h: f64) -> [Prop; 6] {
    let mut out = [Prop::default(); 6];
    for (o, &x) in out.iter_mut().zip(&NODES) {
        *o = propagator(omega, damp, x * h);
    }
    out
}

/// Exact response (η, η̇) at times `s_i = θ_i h` from rest of one mode (ω rad/s, damp = 2ζω
/// 1/s) to the loads (τ/h)^m, m = 0..4, with the propagators `props[i] = P(s_i)`: into
/// `out[i][m]`. A series in `sA` (shared by the five loads) where `s(ω + damp)` is small, the
/// polynomial particular solution otherwise (no cancellation either way).
pub(super) fn monomial_responses(
    omega: f64,
    damp: f64,
    h: f64,
    props: &[Prop; 6],
    out: &mut [[(f64, f64); 5]; 6],
) {
    let w2 = omega * omega;
    for (i, &th) in NODES.iter().enumerate() {
        let s = th * h;
        let o = &mut out[i];
        if s * (omega + damp) < 1.0 {
            // Σ_r (m!/h^m) s^{r+m+1}/(r+m+1)! A^r e₂, A = [[0, 1], [−ω², −damp]]
            let inv = reciprocals();
            let mut coef = [0.0; 5];
            let mut fact = 1.0; // m!/h^m
            for (m, c) in coef.iter_mut().enumerate() {
                if m > 0 {
                    fact *= m as f64 / h;
                }
                let mut x = fact;
                for q in 1..=(m + 1) {
                    x *= s / q as f64;
                }
                *c = x;
            }
            let (mut x, mut y) = (0.0, 1.0);
            let mut acc = [(0.0, 0.0); 5];
            for r in 0..60 {
                for m in 0..5 {
                    acc[m].0 += coef[m] * x;
                    acc[m].1 += coef[m] * y;
                    coef[m] *= s * inv[r + m + 2];
                }
                let (nx, ny) = (y, -w2 * x - damp * y);
                x = nx;
                y = ny;
                // (the m = 0 series converges slowest)
                if coef[0] * (x.abs() + y.abs())
                    < 1e-17 * (acc[0].0.abs() * w2.max(1.0) + acc[0].1.abs())
                {
                    break;
                }
            }
            *o = acc;
        } else {
            for m in 0..5 {
                // particular polynomial Σ u_r τ^r of the load τ^m/h^m
                let mut u = [0.0; 7];
                let cm = 1.0 / h.powi(m as i32);
                for r in (0..=m).rev() {
                    let c = if r == m { cm } else { 0.0 };
                    u[r] = (c
                        - damp * (r + 1) as f64 * u[r + 1]
                        - ((r + 2) * (r + 1)) as f64 * u[r + 2])
                        / w2;
                }
                let (mut e, mut d) = (0.0, 0.0);
                for r in (0..=m).rev() {
                    e = e * s + u[r];
                }
                for r in (1..=m).rev() {
                    d = d * s + r as f64 * u[r];
                }
                let (a, b) = props[i].apply(u[0], u[1]);
                o[m] = (e - a, d - b);
            }
        }
    }
}

/// One mode's part of a [`Table`]: what an accepted step needs of it, in one place.
#[derive(Debug, Clone, Copy, Default)]
pub(in crate::integrate) struct ModeStep {
    /// `P(h)`.
    pub end: Prop,
    /// (η, η̇) at the step's end from rest under the 5-node scheme's Lagrange load ℓ_p.
    pub end8: [(f64, f64); 5],
    /// `P(θh)` at the 5-node scheme's interior nodes (B1, ½, B3), for dense output.
    pub mid: [Prop; 3],
    /// (η, η̇) there under ℓ_p.
    pub mid8: [[(f64, f64); 5]; 3],
}

/// One mode's Γ_j of the level tables `W_kl = Σ_j c_kj c_lj Γ_j` (see [`Table::w8`]), or
/// one slot's sum of them: the 5-node scheme's at its 4 nodes, the companion's at its 3, the
/// 5-node scheme's at the companion's 2 interior nodes.
#[derive(Debug, Clone, Copy)]
struct Gammas {
    g8: [(f64, f64); 20],
    g6: [(f64, f64); 12],
    g86: [(f64, f64); 10],
}

impl Default for Gammas {
    fn default() -> Gammas {
        Gammas {
            g8: [(0.0, 0.0); 20],
            g6: [(0.0, 0.0); 12],
            g86: [(0.0, 0.0); 10],
        }
    }
}

/// Everything of a step of length h that does not depend on the state.
pub(in crate::integrate) struct Table {
    /// Step length, s.
    pub h: f64,
    /// Modes.
    n: usize,
    /// `c_kj·(p11, p21, p12, p22)` of `P(θh)` at every node of [`NODES`] (the columns in
    /// pairs: (η, η̇) from η₀, then from η̇₀), level by level over the level's pair's modes
    /// only (`System::coupling_modes`; c_kj = 0 elsewhere): level k's block starts at
    /// `cstart[k]`, node i's row of it at `i·n_k` (see [`Table::cprop_at`]). The free
    /// flight's δ, δ̇ at the nodes are two dot products per node and level.
    cprop: Vec<[f64; 4]>,
    /// `cprop` with two nodes side by side, for the four lanes of an AVX register: node pair
    /// i/2 (nodes i, i + 1 of even i) of level k's mode j at `cstart[k]/2 + (i/2)·n_k + j`,
    /// `[[a_i, c_i, a_{i+1}, c_{i+1}], [b_i, e_i, b_{i+1}, e_{i+1}]]` of `cprop`'s
    /// `[a, c, b, e]` (see [`Table::cprop_pairs`]).
    cprop2: Vec<[[f64; 4]; 2]>,
    /// Where each level's block of `cprop` starts (L + 1 entries).
    cstart: Vec<usize>,
    /// Per mode, see [`ModeStep`].
    pub modes: Vec<ModeStep>,
    /// Per mode, its responses to the Lagrange loads in the level tables' layout (scratch of
    /// [`Table::fill_for`]).
    gammas: Vec<Gammas>,
    /// Level tables of the 5-node scheme: the response of `c_k·η` (and `c_k·η̇`) at its node i
    /// (B1, ½, B3, end) to a unit force at level l shaped as ℓ_p,
    /// `Σ_j c_kj c_lj Γ_j(i, p)`: `[(kl·4 + i)·5 + p]`, kl = `System::band_slot(k, l)`. Banded:
    /// only the levels l sharing a structure with k are stored (`System::sharing_levels`; the
    /// others' weights are sums of zeros); a pair's band is every level (kl = k·L + l).
    pub w8: Vec<(f64, f64)>,
    /// The same for the 4-node companion at its nodes (A1, A2, end): `[(kl·3 + i)·4 + p]`.
    pub w6: Vec<(f64, f64)>,
    /// The 5-node scheme's response at the companion's interior nodes (A1, A2), for the work
    /// of the contacts along the computed motion: `[(kl·2 + i)·5 + p]`.
    pub w86: Vec<(f64, f64)>,
    /// Harmonic motion: (sin Ωθh, cos Ωθh) at every node of [`NODES`].
    pub rot: [(f64, f64); 6],
    /// Harmonic motion: `(∫₀ʰ ℓ_p(τ/h) cos Ωτ dτ, ∫₀ʰ ℓ_p(τ/h) sin Ωτ dτ)` of the 5-node
    /// scheme's Lagrange loads (s), for the ground's exact work under a contact load.
    pub hmom: [(f64, f64); 5],
    /// Per structure, whether its modes' responses to the Lagrange loads are filled (a row's
    /// structures out of contact are not: see [`Table::fill_for`]), and which were filled by
    /// the last fill (scratch).
    done: Vec<bool>,
    fresh: Vec<bool>,
    /// Per level, whether its coupled propagators (`cprop`) are filled: a row's level both of
    /// whose structures are passive is not (no step reads its free flight to the nodes).
    seen: Vec<bool>,
    /// Per structure, whether its modes' interior-node propagators ([`ModeStep::mid`]) are
    /// filled: a row's passive structure without a filled level is given `P(h)` only, the
    /// others on demand ([`Table::ensure_mid`]: a step observed at its interior nodes).
    mid_ok: Vec<bool>,
    /// Whether every level, structure and interior node is filled (a pair's table, always):
    /// [`Table::ensure`] has nothing to do.
    complete: bool,
}

impl Table {
    /// The table of step length `h` for `sys` (Ω of a harmonic motion in `big`), every
    /// structure's modes filled.
    #[cfg(test)]
    pub(in crate::integrate) fn new(sys: &System, big: Option<f64>, h: f64) -> Table {
        Table::new_for(sys, big, h, &vec![true; sys.structures.len()])
    }

    /// The table of step length `h` with the responses to the Lagrange loads of the
    /// structures `active` marks only (see [`Table::fill_for`]).
    pub(in crate::integrate) fn new_for(
        sys: &System,
        big: Option<f64>,
        h: f64,
        active: &[bool],
    ) -> Table {
        let mut t = Table {
            h: f64::NAN,
            n: 0,
            cprop: Vec::new(),
            cprop2: Vec::new(),
            cstart: Vec::new(),
            modes: Vec::new(),
            gammas: Vec::new(),
            w8: Vec::new(),
            w6: Vec::new(),
            w86: Vec::new(),
            rot: [(0.0, 1.0); 6],
            hmom: [(0.0, 0.0); 5],
            done: Vec::new(),
            fresh: Vec::new(),
            seen: Vec::new(),
            mid_ok: Vec::new(),
            complete: false,
        };
        t.fill_for(sys, big, h, active);
        t
    }

    /// Whether the structures `active` marks are all filled (see [`Table::ensure`]).
    #[inline]
    pub(in crate::integrate) fn covers(&self, active: &[bool]) -> bool {
        active.iter().zip(&self.done).all(|(&a, &d)| d || !a)
    }

    /// Whether level k's coupled propagators are needed under `active`: one of its pair's
    /// structures is active (the step's free flight to the nodes is projected on it).
    #[inline]
    fn level_needed(sys: &System, active: &[bool], k: usize) -> bool {
        let p = sys.levels[k].pair;
        active[p] || active[p + 1]
    }

    /// Level k's coupled propagators from mode j's propagators to the nodes.
    #[inline]
    fn put_cprop(&mut self, sys: &System, k: usize, j: usize, props: &[Prop; 6]) {
        let c = sys.coupling(k)[j];
        let modes = sys.coupling_modes(k);
        let (w, at) = (modes.len(), self.cstart[k] + j - modes.start);
        for (i, p) in props.iter().enumerate() {
            let [a, cc, b, e] = [c * p.p11, c * p.p21, c * p.p12, c * p.p22];
            self.cprop[at + i * w] = [a, cc, b, e];
            let pair = &mut self.cprop2[self.cstart[k] / 2 + (i / 2) * w + j - modes.start];
            let lanes = 2 * (i % 2);
            pair[0][lanes..lanes + 2].copy_from_slice(&[a, cc]);
            pair[1][lanes..lanes + 2].copy_from_slice(&[b, e]);
        }
    }

    /// Mode j's interior-node propagators from its propagators to the nodes.
    #[inline]
    fn put_mid(&mut self, j: usize, props: &[Prop; 6]) {
        self.modes[j].mid = [props[NODES8[0]], props[NODES8[1]], props[NODES8[2]]];
    }

    /// Fill the interior-node propagators ([`ModeStep::mid`]) of every structure's modes: a
    /// step about to be observed at its interior nodes (the same values a full fill gives).
    pub(in crate::integrate) fn ensure_mid(&mut self, sys: &System) {
        if self.mid_ok.iter().all(|&m| m) {
            return;
        }
        let (omega, damp) = (sys.omega(), sys.damping_coefficients());
        let h = self.h;
        for s in 0..sys.structures.len() {
            if self.mid_ok[s] {
                continue;
            }
            for j in sys.modes_of(s) {
                let props = node_props(omega[j], damp[j], h);
                self.put_mid(j, &props);
            }
            self.mid_ok[s] = true;
        }
        self.set_complete();
    }

    /// Fill the structures `active` marks that are not filled yet (their responses to the
    /// Lagrange loads, and the level-table slots that sum over them): a row's contact step
    /// that grows its set of active structures ([`Table::fill_for`]).
    #[inline]
    pub(in crate::integrate) fn ensure(&mut self, sys: &System, active: &[bool]) {
        if !self.complete {
            self.ensure_parts(sys, active);
        }
    }

    /// [`Table::ensure`] of a table not complete.
    fn ensure_parts(&mut self, sys: &System, active: &[bool]) {
        let (omega, damp) = (sys.omega(), sys.damping_coefficients());
        let h = self.h;
        // (the levels newly next to an active structure: their coupled propagators, and the
        // interior-node propagators of both their structures, from the same propagators)
        for k in 0..sys.levels.len() {
            if self.seen[k] || !Self::level_needed(sys, active, k) {
                continue;
            }
            for j in sys.coupling_modes(k) {
                let props = node_props(omega[j], damp[j], h);
                self.put_cprop(sys, k, j, &props);
                self.put_mid(j, &props);
            }
            let p = sys.levels[k].pair;
            self.mid_ok[p] = true;
            self.mid_ok[p + 1] = true;
            self.seen[k] = true;
        }
        if self.covers(active) {
            self.set_complete();
            return;
        }
        self.fresh.clear();
        self.fresh
            .extend(active.iter().zip(&self.done).map(|(&a, &d)| a && !d));
        for s in 0..sys.structures.len() {
            if self.fresh[s] {
                for j in sys.modes_of(s) {
                    let props = node_props(omega[j], damp[j], h);
                    self.fill_mode(omega[j], damp[j], h, j, &props);
                }
                self.done[s] = true;
                self.mid_ok[s] = true;
            }
        }
        self.fill_slots(sys);
        self.set_complete();
    }

    /// Whether every part is filled (`complete`).
    fn set_complete(&mut self) {
        self.complete = self
            .seen
            .iter()
            .chain(&self.done)
            .chain(&self.mid_ok)
            .all(|&x| x);
    }

    crate::numerics::vex::avx_copy! {
        /// Recompute for step length `h` (the buffers are reused): every mode's propagators to the
        /// nodes (the free flight to them, and the state of a mode no contact force acts on), and
        /// the responses to the Lagrange loads of the structures `active` marks only — of a row,
        /// the structures of the pairs in (or near) contact: a mode of any other structure carries
        /// no contact force over the step (its responses would multiply zeros), and a level-table
        /// slot is summed only when every structure it sums over is filled. A pair: both.
        pub(in crate::integrate) fn fill_for(
            &mut self,
            sys: &System,
            big: Option<f64>,
            h: f64,
            active: &[bool],
        ) => fill_for_vex, fill_for_body
    }

    /// [`Self::fill_for`]'s work.
    #[inline(always)]
    fn fill_for_body(&mut self, sys: &System, big: Option<f64>, h: f64, active: &[bool]) {
        let (omega, damp) = (sys.omega(), sys.damping_coefficients());
        let n = sys.len();
        let nl = sys.levels.len();
        self.h = h;
        self.n = n;
        let Bases { l8, .. } = bases();
        if let Some(big) = big {
            self.rot = NODES.map(|x| (big * x * h).sin_cos());
            let moments = trig_moments(big * h);
            self.hmom = std::array::from_fn(|p| {
                let (mut a, mut b) = (0.0, 0.0);
                for m in 0..5 {
                    a += l8[m][p] * moments[m].0;
                    b += l8[m][p] * moments[m].1;
                }
                (h * a, h * b)
            });
        }
        // (every entry of `cprop`, `modes`, `gammas` and the level tables is written below:
        // nothing is cleared)
        self.cstart.clear();
        self.cstart.push(0);
        for k in 0..nl {
            let w = sys.coupling_modes(k).len();
            self.cstart.push(self.cstart[k] + 6 * w);
        }
        self.cprop.resize(self.cstart[nl], [0.0; 4]);
        self.cprop2.resize(self.cstart[nl] / 2, [[0.0; 4]; 2]);
        self.modes.resize(n, ModeStep::default());
        self.gammas.resize(n, Gammas::default());
        let slots = sys.band_slots();
        for (t, per) in [(&mut self.w8, 20), (&mut self.w6, 12), (&mut self.w86, 10)] {
            t.resize(slots * per, (0.0, 0.0));
        }
        self.done.clear();
        self.done.extend_from_slice(active);
        self.fresh.clear();
        self.fresh.extend_from_slice(active);
        // (of a row, the coupled propagators of the levels next to an active structure only:
        // a level between two passive structures is cleared on its exact free flight, see
        // `exact_modal::elastic::active`; the others on demand, [`Table::ensure`])
        self.seen.clear();
        self.seen
            .extend((0..nl).map(|k| Self::level_needed(sys, active, k)));
        self.mid_ok.clear();
        self.mid_ok.resize(sys.structures.len(), false);
        for s in 0..sys.structures.len() {
            // (a structure with a level next to an active one: every node's propagators)
            let full = active[s]
                || (s > 0 && active[s - 1])
                || (s + 1 < sys.structures.len() && active[s + 1]);
            self.mid_ok[s] = full;
            if !full {
                // (a passive mode no filled level holds: its free flight to the end only, the
                // interior nodes on demand)
                for j in sys.modes_of(s) {
                    self.modes[j].end = propagator(omega[j], damp[j], NODES[END] * h);
                }
                continue;
            }
            for j in sys.modes_of(s) {
                let props = node_props(omega[j], damp[j], h);
                // (of a row, only the levels whose pair holds mode j: c_kj = 0 for the others)
                for k in sys.levels_of_mode(j) {
                    if self.seen[k] {
                        self.put_cprop(sys, k, j, &props);
                    }
                }
                if self.done[s] {
                    self.fill_mode(omega[j], damp[j], h, j, &props);
                } else {
                    // (a passive mode: its free flight to the end and the interior nodes only)
                    self.modes[j].end = props[END];
                    self.put_mid(j, &props);
                }
            }
        }
        self.fill_slots(sys);
        self.set_complete();
    }

    /// Mode j's responses to the Lagrange loads (its [`ModeStep`] and Γ_j), from its
    /// propagators to the nodes.
    #[inline(always)]
    fn fill_mode(&mut self, omega: f64, damp: f64, h: f64, j: usize, props: &[Prop; 6]) {
        let Bases { l8, l6, .. } = bases();
        {
            let mut mono = [[(0.0, 0.0); 5]; 6];
            monomial_responses(omega, damp, h, props, &mut mono);
            // this mode's responses to the Lagrange loads: the 5-node scheme's at its 4 nodes
            // and at the companion's 2 interior ones, the companion's at its 3
            let lagrange8 = |node: usize| -> [(f64, f64); 5] {
                std::array::from_fn(|p| {
                    let (mut a, mut b) = (0.0, 0.0);
                    for m in 0..5 {
                        a += l8[m][p] * mono[node][m].0;
                        b += l8[m][p] * mono[node][m].1;
                    }
                    (a, b)
                })
            };
            let g8: [[(f64, f64); 5]; 4] = NODES8.map(lagrange8);
            let g86: [[(f64, f64); 5]; 2] = [lagrange8(0), lagrange8(1)];
            let g6: [[(f64, f64); 4]; 3] = NODES6.map(|node| {
                std::array::from_fn(|p| {
                    let (mut a, mut b) = (0.0, 0.0);
                    for m in 0..4 {
                        a += l6[m][p] * mono[node][m].0;
                        b += l6[m][p] * mono[node][m].1;
                    }
                    (a, b)
                })
            });
            self.modes[j] = ModeStep {
                end: props[END],
                end8: g8[3],
                mid: [props[NODES8[0]], props[NODES8[1]], props[NODES8[2]]],
                mid8: [g8[0], g8[1], g8[2]],
            };
            let g = &mut self.gammas[j];
            g.g8.copy_from_slice(g8.as_flattened());
            g.g6.copy_from_slice(g6.as_flattened());
            g.g86.copy_from_slice(g86.as_flattened());
        }
    }

    /// The level tables, slot by slot over each level's band: the sum over the modes both
    /// levels couple to (c_kj c_lj = 0 on every other mode), in mode order from 0 — the slots
    /// whose structures are all filled and one of them just now (`fresh`). The tables are
    /// symmetric, (k, l) the same bits as (l, k) (`c_kj c_lj` = `c_lj c_kj` exactly, the same
    /// terms in the same order): each pair of slots is summed once, for l ≥ k.
    fn fill_slots(&mut self, sys: &System) {
        let nl = sys.levels.len();
        for k in 0..nl {
            let (ck, mk) = (sys.coupling(k), sys.coupling_modes(k));
            let pk = sys.levels[k].pair;
            for l in sys.sharing_levels(k).filter(|&l| l >= k) {
                let (cl, ml) = (sys.coupling(l), sys.coupling_modes(l));
                // (the structures both pairs hold)
                let pl = sys.levels[l].pair;
                let shared = pk.max(pl)..(pk.min(pl) + 2);
                if !shared.clone().all(|s| self.done[s]) || !shared.clone().any(|s| self.fresh[s]) {
                    continue;
                }
                let mut sum = Gammas::default();
                for j in mk.start.max(ml.start)..mk.end.min(ml.end) {
                    let w = ck[j] * cl[j];
                    if w == 0.0 {
                        continue;
                    }
                    let g = &self.gammas[j];
                    let add = |t: &mut [(f64, f64)], g: &[(f64, f64)]| {
                        for (e, g) in t.iter_mut().zip(g) {
                            e.0 += w * g.0;
                            e.1 += w * g.1;
                        }
                    };
                    add(&mut sum.g8, &g.g8);
                    add(&mut sum.g6, &g.g6);
                    add(&mut sum.g86, &g.g86);
                }
                let kl = sys.band_slot(k, l);
                self.w8[kl * 20..(kl + 1) * 20].copy_from_slice(&sum.g8);
                self.w6[kl * 12..(kl + 1) * 12].copy_from_slice(&sum.g6);
                self.w86[kl * 10..(kl + 1) * 10].copy_from_slice(&sum.g86);
                if l != k {
                    let lk = sys.band_slot(l, k);
                    self.w8[lk * 20..(lk + 1) * 20].copy_from_slice(&sum.g8);
                    self.w6[lk * 12..(lk + 1) * 12].copy_from_slice(&sum.g6);
                    self.w86[lk * 10..(lk + 1) * 10].copy_from_slice(&sum.g86);
                }
            }
        }
    }

    /// Modes the table was made for.
    pub(in crate::integrate) fn modes(&self) -> usize {
        self.n
    }

    /// Level k's coupled propagators at node i of [`NODES`], over `sys.coupling_modes(k)`
    /// (the same system the table was filled for; the steps take all six at once,
    /// [`Table::cprop_rows`]).
    #[cfg(test)]
    pub(in crate::integrate) fn cprop_at(&self, sys: &System, k: usize, i: usize) -> &[[f64; 4]] {
        let w = sys.coupling_modes(k).len();
        let at = self.cstart[k] + i * w;
        &self.cprop[at..at + w]
    }

    /// Level k's coupled propagators at the six nodes of [`NODES`] (see [`Table::cprop_at`]),
    /// in one call.
    #[inline]
    pub(in crate::integrate) fn cprop_rows(&self, sys: &System, k: usize) -> [&[[f64; 4]]; 6] {
        let w = sys.coupling_modes(k).len();
        let block = &self.cprop[self.cstart[k]..self.cstart[k] + 6 * w];
        std::array::from_fn(|i| &block[i * w..(i + 1) * w])
    }

    /// Level k's coupled propagators as [`Table::cprop_rows`] has them, two nodes side by side
    /// (nodes 0–1, 2–3, 4–5): each mode's `[[a_i, c_i, a_{i+1}, c_{i+1}], [b_i, e_i, b_{i+1},
    /// e_{i+1}]]`.
    #[inline]
    pub(in crate::integrate) fn cprop_pairs(
        &self,
        sys: &System,
        k: usize,
    ) -> [&[[[f64; 4]; 2]]; 3] {
        let w = sys.coupling_modes(k).len();
        let start = self.cstart[k] / 2;
        let block = &self.cprop2[start..start + 3 * w];
        std::array::from_fn(|i| &block[i * w..(i + 1) * w])
    }

    /// The coupled propagators of a pair's single contact level (`n` modes, all coupled):
    /// node i's row at `[i·n..(i + 1)·n]`, as [`Table::cprop_at`] gives them one by one.
    #[inline]
    pub(in crate::integrate) fn cprop_single(&self, n: usize) -> &[[f64; 4]] {
        &self.cprop[..6 * n]
    }
}

/// `(∫₀¹ x^m cos ax dx, ∫₀¹ x^m sin ax dx)` for m = 0..4: a series for |a| < 2, else the
/// recursion `I_m = (e^{ia} − m I_{m−1})/(ia)` (each step divides the error by |a|/m).
pub(super) fn trig_moments(a: f64) -> [(f64, f64); 5] {
    let mut out = [(0.0, 0.0); 5];
    if a.abs() < 2.0 {
        // Σ_r (ia)^r/(r!·(m + r + 1)): real parts from even r, imaginary from odd
        for (m, o) in out.iter_mut().enumerate() {
            let (mut re, mut im) = (0.0, 0.0);
            let mut term = 1.0; // a^r/r!
            for r in 0..40 {
                let x = term / (m + r + 1) as f64;
                match r % 4 {
                    0 => re += x,
                    1 => im += x,
                    2 => re -= x,
                    _ => im -= x,
                }
                term *= a / (r + 1) as f64;
                if term.abs() < 1e-18 {
                    break;
                }
            }
            *o = (re, im);
        }
    } else {
        let (s, c) = a.sin_cos();
        // I_0 = (e^{ia} − 1)/(ia) = (sin a + i(1 − cos a))/a
        let mut prev = (s / a, (1.0 - c) / a);
        out[0] = prev;
        for (m, o) in out.iter_mut().enumerate().skip(1) {
            // (e^{ia} − m·I)/(ia) = (Im(e^{ia} − mI) − i Re(e^{ia} − mI))/a
            let (re, im) = (c - m as f64 * prev.0, s - m as f64 * prev.1);
            prev = (im / a, -re / a);
            *o = prev;
        }
    }
    out
}
