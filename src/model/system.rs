//! The structures of a pair or a row, their contact levels and the ground motion assembled into
//! one system of modal equations, stored as flat arrays for the integrators' hot loops
//! (docs/model.md §2.4, §2.4a).
//!
//! The modal coordinates of the N ≥ 1 structures are concatenated in row order: structure i
//! owns indices `offset_i..offset_{i+1}` ([`System::modes_of`]). Every contact level belongs to
//! one adjacent pair (left structure i, right i + 1, [`Level::pair`]); its *coupling* row is
//! `c_kj = s φ_j(h_k)` over the modes of its two structures (s = −1 for the left one's modes,
//! +1 for the right one's, 0 for every other structure's), so that
//!
//! - penetration `δ_k = w_left(h_k) − w_right(h_k) − d_k = −Σ_j c_kj η_j − d_k`,
//! - generalised contact load on mode j: `c_kj F_k` (action and reaction, docs/model.md §2.4),
//!
//! which makes the contact force exactly `−∂U/∂η` of the contact potential U(δ): the discrete
//! system conserves energy with an elastic law. A middle structure of a row receives the forces
//! of both neighbours through the rows of both its pairs; the integrators do not know how many
//! structures there are. For a pair (N = 2) every row spans all modes, as it always did.

use crate::model::contact::{ContactForce, ContactLaw};
use crate::model::ground_motion::GroundMotion;
use crate::model::modal::ModalModel;
use crate::numerics::linalg::dot;

/// Penetration (m) from which an impulsive contact counts as touching: integrators that locate
/// the onset of contact land on δ = 0 only to round-off.
pub const IMPACT_TOUCH_TOLERANCE: f64 = 1e-12;

/// One contact level: where, at which gap, and with what law.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactLevel {
    /// Height above ground, m (0 < h ≤ min(L₁, L₂)).
    pub height: f64,
    /// At-rest gap d, m (≥ 0).
    pub gap: f64,
}

/// The contact of one adjacent pair of a row: the law and its levels.
#[derive(Debug, Clone, PartialEq)]
pub struct PairContact {
    /// The force law of every level of the pair.
    pub law: ContactLaw,
    /// The pair's levels (heights within the lower of its two structures).
    pub levels: Vec<ContactLevel>,
}

/// An assembled contact level.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    /// The adjacent pair it belongs to: its left structure's index (0-based; the right one is
    /// `pair + 1`). Always 0 for a two-structure system.
    pub pair: usize,
    /// Height, m.
    pub height: f64,
    /// Gap, m.
    pub gap: f64,
    /// Effective mass at the contact point, kg: `1/m* = Σ_n φ_Ln(h)² + Σ_n φ_Rn(h)²` over the
    /// pair's left and right structures, i.e. their point masses `1/Σφ²` in series.
    pub effective_mass: f64,
    /// The force law resolved for that mass.
    pub force: ContactForce,
}

/// The approach speed v₀ (m/s) a rate-dependent law is evaluated with: the episode's `onset`
/// speed while one is in force (> 0), else the current penetration rate `delta_dot`.
#[inline(always)]
pub fn episode_v0(onset: f64, delta_dot: f64) -> f64 {
    if onset > 0.0 { onset } else { delta_dot }
}

impl Level {
    /// Penetration `δ = −c·η − d` (m) from the level's projection `cq = c·η` (module docs;
    /// docs/model.md §2.4): the one place the sign convention and the gap enter.
    #[inline(always)]
    pub fn delta(&self, cq: f64) -> f64 {
        -cq - self.gap
    }

    /// Penetration and its rate `(δ, δ̇) = (−c·η − d, −c·η̇)` (m, m/s) from the projections
    /// `cq = c·η`, `cv = c·η̇`.
    #[inline(always)]
    pub fn penetration(&self, cq: f64, cv: f64) -> (f64, f64) {
        (self.delta(cq), -cv)
    }

    /// The law's force (N) at (δ, δ̇) in a contact episode whose approach speed is `onset`
    /// (m/s; 0 when no episode is in force, and the damped Hertz law then takes δ̇ as v₀).
    #[inline(always)]
    pub fn episode_force(&self, delta: f64, delta_dot: f64, onset: f64) -> f64 {
        self.force
            .force(delta, delta_dot, episode_v0(onset, delta_dot))
    }

    /// The level's state (δ, δ̇ and the law's force) from the projections `cq = c·η`,
    /// `cv = c·η̇` in an episode of approach speed `onset` ([`Level::episode_force`]).
    #[inline(always)]
    pub fn state(&self, cq: f64, cv: f64, onset: f64) -> LevelState {
        let (delta, delta_dot) = self.penetration(cq, cv);
        LevelState {
            delta,
            delta_dot,
            force: self.episode_force(delta, delta_dot, onset),
        }
    }
}

/// Contact state of one level at one instant.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LevelState {
    /// Penetration δ, m (negative: open gap).
    pub delta: f64,
    /// Penetration rate δ̇, m/s.
    pub delta_dot: f64,
    /// Contact force F ≥ 0, N.
    pub force: f64,
}

/// Instantaneous powers, W.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Powers {
    /// Power of the ground loading on the structures, `Σ_j f_j(t) η̇_j`.
    pub input: f64,
    /// Power dissipated by structural damping, `Σ_j 2ζ_jω_j η̇_j²`.
    pub damping: f64,
    /// Power flowing into the contacts, `Σ_k F_k δ̇_k`.
    pub contact: f64,
    /// Power given to the yielding storeys' pseudo-forces, `Σ_s ΔV_s ḋ_s` (0 without
    /// hysteresis; see [`crate::model::hysteresis`]).
    pub hysteretic: f64,
}

/// The assembled system.
#[derive(Debug, Clone)]
pub struct System {
    /// The structures in modal form, in row order (two for a pair).
    pub structures: Vec<ModalModel>,
    /// Contact levels (empty: no contact), pair by pair in row order.
    pub levels: Vec<Level>,
    /// The ground motion.
    pub ground: GroundMotion,
    /// `offsets[i]..offsets[i + 1]` are structure i's modal coordinates (N + 1 entries).
    offsets: Vec<usize>,
    omega: Vec<f64>,
    omega_sq: Vec<f64>,
    damp: Vec<f64>,
    load_a: Vec<f64>,
    load_v: Vec<f64>,
    coupling: Vec<f64>,
    /// Whether any level's law is impulsive (stereomechanical): the step-end hook is skipped
    /// otherwise.
    impulsive: bool,
    /// The contact steps' banded level tables: see [`Bands`].
    bands: Bands,
    /// Yielding storeys (issue 16): their pseudo-forces enter through drift rows as contact
    /// forces do, with one hysteretic variable z per storey as extra state. Empty when both
    /// structures are elastic.
    pub hysteresis: crate::model::hysteresis::Hysteresis,
}

impl System {
    /// Assemble a pair: structure 1 (left) and 2 (right), one law at every level. `levels`
    /// may be empty (the no-contact run).
    pub fn new(
        structures: [ModalModel; 2],
        law: &ContactLaw,
        levels: &[ContactLevel],
        ground: GroundMotion,
    ) -> System {
        System::row(
            structures.into(),
            &[PairContact {
                law: *law,
                levels: levels.to_vec(),
            }],
            ground,
        )
    }

    /// Assemble a row of N ≥ 1 structures (row order, left to right) with the contact of
    /// each adjacent pair: `pairs[p]` is between structures p and p + 1 (at most N − 1 of
    /// them; a pair without levels never touches). A pair is the row of two.
    pub fn row(structures: Vec<ModalModel>, pairs: &[PairContact], ground: GroundMotion) -> System {
        assert!(
            pairs.len() < structures.len().max(1),
            "a row of {} structures has {} adjacent pairs, not {}",
            structures.len(),
            structures.len().saturating_sub(1),
            pairs.len()
        );
        let mut offsets = Vec::with_capacity(structures.len() + 1);
        offsets.push(0);
        for s in &structures {
            offsets.push(offsets.last().copied().unwrap_or(0) + s.omega.len());
        }
        let n = offsets.last().copied().unwrap_or(0);
        let mut omega = Vec::with_capacity(n);
        let mut damp = Vec::with_capacity(n);
        let mut load_a = Vec::with_capacity(n);
        let mut load_v = Vec::with_capacity(n);
        for s in &structures {
            for j in 0..s.omega.len() {
                omega.push(s.omega[j]);
                damp.push(2.0 * s.zeta[j] * s.omega[j]);
                // docs/model.md §2.4: −Γ_n a_g − c_a γ_n v_g
                load_a.push(-s.participation[j]);
                load_v.push(-s.air_load[j]);
            }
        }
        let omega_sq = omega.iter().map(|w| w * w).collect();
        let count: usize = pairs.iter().map(|p| p.levels.len()).sum();
        let mut coupling = Vec::with_capacity(count * n);
        let mut assembled = Vec::with_capacity(count);
        for (p, pc) in pairs.iter().enumerate() {
            for lv in &pc.levels {
                // the row is zero outside the pair's two structures
                coupling.extend(std::iter::repeat_n(0.0, offsets[p]));
                let mut sum_sq = 0.0;
                for (sign, s) in [(-1.0, &structures[p]), (1.0, &structures[p + 1])] {
                    for j in 0..s.omega.len() {
                        let phi = s.shape(j, lv.height);
                        coupling.push(sign * phi);
                        sum_sq += phi * phi;
                    }
                }
                coupling.extend(std::iter::repeat_n(0.0, n - offsets[p + 2]));
                let m_star = 1.0 / sum_sq;
                assembled.push(Level {
                    pair: p,
                    height: lv.height,
                    gap: lv.gap,
                    effective_mass: m_star,
                    force: pc.law.resolve(m_star),
                });
            }
        }
        let impulsive = assembled.iter().any(|l| l.force.impulsive().is_some());
        let bands = Bands::new(&assembled, &offsets);
        System {
            structures,
            impulsive,
            bands,
            levels: assembled,
            ground,
            offsets,
            omega,
            omega_sq,
            damp,
            load_a,
            load_v,
            coupling,
            hysteresis: crate::model::hysteresis::Hysteresis::none(),
        }
    }

    /// The same system with yielding storeys (`h` built for these structures' modes).
    pub fn with_hysteresis(mut self, h: crate::model::hysteresis::Hysteresis) -> System {
        self.hysteresis = h;
        self
    }

    /// The same system with contact switched off.
    pub fn without_contact(&self) -> System {
        let mut s = self.clone();
        s.levels.clear();
        s.coupling.clear();
        s.impulsive = false;
        s.bands = Bands::new(&s.levels, &s.offsets);
        s
    }

    /// Number of modes of structure 1.
    pub fn n1(&self) -> usize {
        self.offsets.get(1).copied().unwrap_or(0)
    }

    /// The modal coordinates of structure `i` (0-based, row order): a range of indices into
    /// the concatenated state.
    #[inline]
    pub fn modes_of(&self, i: usize) -> std::ops::Range<usize> {
        self.offsets[i]..self.offsets[i + 1]
    }

    /// The structure (0-based) and its mode (0-based) of modal coordinate `j`.
    pub fn structure_of_mode(&self, j: usize) -> (usize, usize) {
        let i = self.offsets[1..].partition_point(|&end| end <= j);
        (i, j - self.offsets[i.min(self.offsets.len() - 1)])
    }

    /// Total number of modal coordinates.
    pub fn len(&self) -> usize {
        self.omega.len()
    }

    /// True if there are no modes (never, for a checked scenario).
    pub fn is_empty(&self) -> bool {
        self.omega.is_empty()
    }

    /// Natural frequencies of all modes (structure 1 then 2), rad/s.
    pub fn omega(&self) -> &[f64] {
        &self.omega
    }

    /// `2ζ_jω_j` of all modes, 1/s.
    pub fn damping_coefficients(&self) -> &[f64] {
        &self.damp
    }

    /// Coefficients of a_g in the modal loads, `−γ_j m`, kg^(1/2).
    pub fn ground_load(&self) -> &[f64] {
        &self.load_a
    }

    /// Coefficients of v_g in the modal loads, `−γ_j c_a`, kg^(1/2)/s.
    pub fn air_load(&self) -> &[f64] {
        &self.load_v
    }

    /// Coupling row of level k: `s_i φ_ij(h_k)`, kg^(−1/2).
    #[inline]
    pub fn coupling(&self, k: usize) -> &[f64] {
        let n = self.len();
        &self.coupling[k * n..(k + 1) * n]
    }

    /// The modal coordinates level k's coupling row can be non-zero on: its pair's two
    /// structures' (`modes_of(pair)` then `modes_of(pair + 1)`); zero elsewhere, so that a sum
    /// over the row may skip the rest (a pair: every mode). Of a row of N structures, a level
    /// then costs its pair's modes, not all N structures'.
    #[inline]
    pub fn coupling_modes(&self, k: usize) -> std::ops::Range<usize> {
        let p = self.levels[k].pair;
        self.offsets[p]..self.offsets[p + 2]
    }

    /// The levels whose coupling rows can be non-zero at mode j: those of the (at most two)
    /// pairs that hold mode j's structure, a contiguous range since the levels are assembled
    /// pair by pair in row order (a pair: every level). Elsewhere `c_kj = 0`.
    #[inline]
    pub fn levels_of_mode(&self, j: usize) -> std::ops::Range<usize> {
        let (lo, hi) = self.bands.mode_levels[j];
        lo as usize..hi as usize
    }

    /// The levels that share a structure with level k (k's own pair and the two neighbouring
    /// pairs), a contiguous range: outside it `Σ_j c_kj c_lj (…)` vanishes, every term being
    /// zero (a pair: every level).
    #[inline]
    pub fn sharing_levels(&self, k: usize) -> std::ops::Range<usize> {
        let (lo, hi) = self.bands.sharing[k];
        lo as usize..hi as usize
    }

    /// Where the level pair (k, l), l in [`Self::sharing_levels`]`(k)`, stands in the banded
    /// storage of a level-to-level table: the bands of the levels one after the other
    /// (`k·L + l` for a pair, whose band is every level: the dense layout).
    #[inline]
    pub fn band_slot(&self, k: usize, l: usize) -> usize {
        let lo = self.bands.sharing[k].0 as usize;
        debug_assert!(
            self.sharing_levels(k).contains(&l),
            "level {l} outside {k}'s band"
        );
        self.bands.start[k] + (l - lo)
    }

    /// The number of level pairs (k, l) with l in k's band: the slots of a banded table.
    #[inline]
    pub fn band_slots(&self) -> usize {
        self.bands.start.last().copied().unwrap_or(0)
    }

    /// Displacements (w_left, w_right) of level k's pair at its height for modal coordinates
    /// `q`, m.
    #[inline]
    pub fn displacements_at_level(&self, k: usize, q: &[f64]) -> (f64, f64) {
        let c = self.coupling(k);
        let p = self.levels[k].pair;
        let (l, r) = (self.modes_of(p), self.modes_of(p + 1));
        let w1 = -dot(&c[l.clone()], &q[l]);
        let w2 = dot(&c[r.clone()], &q[r]);
        (w1, w2)
    }

    /// Modal energy `Σ ½(η̇² + ω²η²)`, J (mass-normalised modes: modal mass 1 kg).
    pub fn modal_energy(&self, q: &[f64], v: &[f64]) -> f64 {
        let mut e = 0.0;
        for j in 0..q.len() {
            e += 0.5 * (v[j] * v[j] + self.omega_sq[j] * q[j] * q[j]);
        }
        e
    }

    /// Energy stored in the contacts for states `levels`, J.
    pub fn contact_energy(&self, states: &[LevelState]) -> f64 {
        self.levels
            .iter()
            .zip(states)
            .map(|(l, s)| l.force.potential(s.delta))
            .sum()
    }

    /// Penetration and its rate at every level (no forces).
    #[inline]
    pub fn kinematics(&self, q: &[f64], v: &[f64], states: &mut [LevelState]) {
        for (k, (lv, st)) in self.levels.iter().zip(states.iter_mut()).enumerate() {
            let c = self.coupling(k);
            (st.delta, st.delta_dot) = lv.penetration(dot(c, q), dot(c, v));
        }
    }

    /// The right-hand side: modal accelerations `a` at time t for state (q, v), the contact
    /// state of every level and the powers. `onset_speed[k]` is v₀ of an active contact
    /// episode at level k, or 0 when none is active (the damped Hertz law then takes the
    /// current δ̇ as v₀).
    #[inline]
    pub fn acceleration(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        onset_speed: &[f64],
        a: &mut [f64],
        states: &mut [LevelState],
    ) -> Powers {
        let ground = self.ground.accel_velocity(t);
        self.acceleration_in(ground, q, v, onset_speed, a, states)
    }

    /// [`System::acceleration`] with the ground acceleration and velocity (m/s², m/s) already
    /// evaluated, for integrators that reuse them across stages at the same time.
    #[inline]
    pub fn acceleration_in(
        &self,
        (ag, vg): (f64, f64),
        q: &[f64],
        v: &[f64],
        onset_speed: &[f64],
        a: &mut [f64],
        states: &mut [LevelState],
    ) -> Powers {
        let mut p = Powers::default();
        let n = self.len();
        let (q, v, a) = (&q[..n], &v[..n], &mut a[..n]);
        for j in 0..n {
            let f = self.load_a[j] * ag + self.load_v[j] * vg;
            let d = self.damp[j] * v[j];
            a[j] = f - d - self.omega_sq[j] * q[j];
            p.input += f * v[j];
            p.damping += d * v[j];
        }
        for (k, (lv, st)) in self.levels.iter().zip(states.iter_mut()).enumerate() {
            let c = &self.coupling[k * n..(k + 1) * n];
            let (delta, delta_dot) = lv.penetration(dot(c, q), dot(c, v));
            let force = lv.episode_force(delta, delta_dot, onset_speed[k]);
            if force != 0.0 {
                for j in 0..n {
                    a[j] += c[j] * force;
                }
            }
            p.contact += force * delta_dot;
            *st = LevelState {
                delta,
                delta_dot,
                force,
            };
        }
        p
    }
}

/// The band structure of a row's contact levels, computed once: of each mode the levels whose
/// coupling can be non-zero there, of each level those sharing a structure with it, and where
/// each level's band starts in a banded table (the contact step's hot loops read these at
/// every step; a pair: every level everywhere).
#[derive(Debug, Clone, Default)]
struct Bands {
    /// Per mode, `levels_of_mode` as (start, end).
    mode_levels: Vec<(u32, u32)>,
    /// Per level, `sharing_levels` as (start, end).
    sharing: Vec<(u32, u32)>,
    /// Per level, its band's first slot; then the total (L + 1 entries).
    start: Vec<usize>,
}

impl Bands {
    fn new(levels: &[Level], offsets: &[usize]) -> Bands {
        let nl = levels.len() as u32;
        let n = offsets.last().copied().unwrap_or(0);
        let pair = offsets.len() <= 3;
        // (the levels are assembled pair by pair in row order: a set of pairs is a range)
        let pairs = |lo: usize, hi: usize| {
            let a = levels.partition_point(|l| l.pair < lo) as u32;
            let b = levels.partition_point(|l| l.pair <= hi) as u32;
            (a, b)
        };
        let mode_levels = (0..n)
            .map(|j| {
                if pair {
                    return (0, nl);
                }
                // structure s holds j: pairs s − 1 (s its right structure) and s (its left one)
                let s = offsets[1..].partition_point(|&end| end <= j);
                pairs(s.saturating_sub(1), s)
            })
            .collect();
        let sharing: Vec<(u32, u32)> = levels
            .iter()
            .map(|l| {
                if pair {
                    (0, nl)
                } else {
                    pairs(l.pair.saturating_sub(1), l.pair + 1)
                }
            })
            .collect();
        let mut start = Vec::with_capacity(sharing.len() + 1);
        start.push(0);
        for &(a, b) in &sharing {
            start.push(start.last().copied().unwrap_or(0) + (b - a) as usize);
        }
        Bands {
            mode_levels,
            sharing,
            start,
        }
    }
}

impl System {
    /// Whether any level's law is impulsive (stereomechanical).
    #[inline(always)]
    pub fn has_impulsive(&self) -> bool {
        self.impulsive
    }

    /// Stereomechanical impacts (docs/model.md §2.7, issue 3): at every level with an impulsive law where
    /// the structures touch or overlap (δ ≥ −1e-12 m) and still approach (δ̇ > 0), apply the impulse
    /// `P = (1 + e) m* δ̇` as the velocity jump `v += c_k P`, which turns δ̇ into −e δ̇. Adds P to
    /// `impulse[k]` and the kinetic energy lost, `½(1 − e²) m* δ̇²`, to `dissipated`. Returns
    /// whether any impulse was applied (the caller then re-evaluates the state).
    #[inline]
    pub fn apply_impulses(
        &self,
        v: &mut [f64],
        states: &mut [LevelState],
        impulse: &mut [f64],
        dissipated: &mut f64,
    ) -> bool {
        if !self.impulsive {
            return false;
        }
        let mut any = false;
        let n = self.len();
        for (k, lv) in self.levels.iter().enumerate() {
            let Some(e) = lv.force.impulsive() else {
                continue;
            };
            let st = &mut states[k];
            // δ ≥ −1e-12 m: methods that locate the contact onset land on δ = 0 to round-off
            if st.delta >= -IMPACT_TOUCH_TOLERANCE && st.delta_dot > 0.0 {
                let c = &self.coupling[k * n..(k + 1) * n];
                let p = (1.0 + e) * lv.effective_mass * st.delta_dot;
                for j in 0..n {
                    v[j] += c[j] * p;
                }
                *dissipated +=
                    0.5 * (1.0 - e * e) * lv.effective_mass * st.delta_dot * st.delta_dot;
                impulse[k] += p;
                st.delta_dot = -dot(c, v);
                any = true;
            }
        }
        any
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::structure::{Cantilever, Damping, Stiffness};

    fn pair(modes: usize) -> [ModalModel; 2] {
        let s = |t: f64, l: f64| Cantilever {
            name: "s".into(),
            length: l,
            mass: 2e6,
            stiffness: Stiffness::Period(t),
            modes,
            damping: Damping::Modal(vec![0.02]),
        };
        [s(0.5, 10.0).modal(), s(0.8, 14.0).modal()]
    }

    /// Contact load is −∂U/∂η: check by finite differences of the Hertz potential.
    #[test]
    fn contact_load_is_gradient_of_potential() {
        let sys = System::new(
            pair(4),
            &ContactLaw::Hertz { stiffness: 1e10 },
            &[ContactLevel {
                height: 9.0,
                gap: 0.001,
            }],
            GroundMotion::None,
        );
        let n = sys.len();
        let q: Vec<f64> = (0..n)
            .map(|j| if j < 4 { 10.0 } else { -5.0 } / (j as f64 + 1.0))
            .collect();
        let v = vec![0.0; n];
        let mut a = vec![0.0; n];
        let mut st = [LevelState::default()];
        sys.acceleration(0.0, &q, &v, &[0.0], &mut a, &mut st);
        assert!(
            st[0].delta > 0.0,
            "the test needs penetration: {}",
            st[0].delta
        );
        let energy = |q: &[f64]| {
            let mut s = [LevelState::default()];
            sys.kinematics(q, &v, &mut s);
            sys.contact_energy(&s)
        };
        for j in 0..n {
            let contact_load = a[j] + sys.omega_sq[j] * q[j];
            // central difference: truncation ~e², round-off ~ε·U/e, both < 1e-8 relative here
            let e = 1e-5;
            let mut qp = q.clone();
            qp[j] += e;
            let mut qm = q.clone();
            qm[j] -= e;
            let grad = (energy(&qp) - energy(&qm)) / (2.0 * e);
            assert!(
                (contact_load + grad).abs() < 1e-7 * contact_load.abs().max(1.0),
                "mode {j}: {contact_load} vs {}",
                -grad
            );
        }
    }

    /// Action and reaction: the force pushes structure 1 left (w₁ decreases) and 2 right.
    #[test]
    fn contact_pushes_structures_apart() {
        let sys = System::new(
            pair(1),
            &ContactLaw::Linear { stiffness: 1e8 },
            &[ContactLevel {
                height: 10.0,
                gap: 0.0,
            }],
            GroundMotion::None,
        );
        // structure 1 displaced right by 1 cm at the top, structure 2 at rest
        let phi1 = sys.structures[0].shape(0, 10.0);
        let q = [0.01 / phi1, 0.0];
        let mut a = [0.0; 2];
        let mut st = [LevelState::default()];
        sys.acceleration(0.0, &q, &[0.0; 2], &[0.0], &mut a, &mut st);
        assert!((st[0].delta - 0.01).abs() < 1e-15);
        let contact_a1 = a[0] + sys.omega_sq[0] * q[0];
        // w₁ acceleration from contact: φ₁ · a₁ < 0; w₂: φ₂ · a₂ > 0
        assert!(phi1 * contact_a1 < 0.0);
        assert!(sys.structures[1].shape(0, 10.0) * a[1] > 0.0);
        assert!((st[0].force - 1e6).abs() < 1e-6);
    }

    /// m* = 1/(Σφ₁² + Σφ₂²); at the tip of one-mode beams φ² = 4/M.
    #[test]
    fn effective_mass_at_tips() {
        let sys = System::new(
            pair(1),
            &ContactLaw::Hertz { stiffness: 1e10 },
            &[ContactLevel {
                height: 10.0,
                gap: 0.0,
            }],
            GroundMotion::None,
        );
        // structure 2 is 14 m tall; at 10 m its shape is not the tip value
        let phi2 = sys.structures[1].shape(0, 10.0);
        let expected = 1.0 / (4.0 / 2e6 + phi2 * phi2);
        assert!((sys.levels[0].effective_mass - expected).abs() < 1e-9 * expected);
    }
}
