//! The absolute accelerations inside an impact pulse between two observations (docs/model.md
//! §2.6c). An observation samples `η̈ = … + Σ_k c_k F_k` where it falls; the contact force of
//! a pulse peaks between them, and a floor's acceleration with it (at the contact height of
//! paper case c at the default settings of `exact-modal` the observations alone missed the
//! peak by 1 %). Over an interval where a level carries force at either end, the accelerations
//! are also evaluated at [`PARTS`]` − 1` interior points: the modes' (η, η̇) from the quintic
//! Hermite through (η, η̇, η̈) at both ends, each loaded level's force from its law at the
//! (δ, δ̇) those give, and the ground's motion where it is; the equilibrium shear
//! `V = C − Σ E_n η̈_n − M a_g` is raised at the same points, with those forces in `C`. Laws
//! whose force is a function of (δ, δ̇) alone (Hertz, linear, Kelvin, Jankowski) and structures
//! without yielding storeys take it (the damped Hertz law needs its episode's approach speed, a
//! Bouc–Wen storey its z). Where a law's force jumps at δ = 0 (Kelvin's `c δ̇`), the quintic
//! starts from the acceleration just after the jump at an onset (an observation there has the
//! force before it), and that limit is raised too.

use std::ops::Range;

use crate::integrate::StepView;
use crate::model::system::{LevelState, System};

use super::bounds::raise;
use super::station::{Equilibrium, Stations, copy_into};
use crate::numerics::lanes::F2;

/// The interval is cut into this many parts (its interior points `j/PARTS`): a pulse's peak
/// sampled this finely is off by `O((h/PARTS)²)` of its curvature, 1/16 of the ends' error
/// (paper case c: 1.03 % at the observations, 3e-6 measured at the contact height).
pub(super) const PARTS: usize = 4;

/// The largest `ω_max h` of an interval the quintic is trusted over: its error in a mode
/// followed over `ω h` is `O((ω h)⁶)` of the mode's swing.
const MAX_OMEGA_H: f64 = 2.0;

/// The quintic Hermite basis at `θ ∈ [0, 1]` — the weights of `(y₀, h y₀′, h² y₀″, y₁, h y₁′,
/// h² y₁″)` — and their θ-derivatives (the slope's weights times h).
fn quintic(th: f64) -> ([f64; 6], [f64; 6]) {
    let (t2, t3) = (th * th, th * th * th);
    let (t4, t5) = (t3 * th, t3 * t2);
    let h0 = 1.0 - 10.0 * t3 + 15.0 * t4 - 6.0 * t5;
    let d0 = -30.0 * t2 + 60.0 * t3 - 30.0 * t4;
    (
        [
            h0,
            th - 6.0 * t3 + 8.0 * t4 - 3.0 * t5,
            0.5 * t2 - 1.5 * t3 + 1.5 * t4 - 0.5 * t5,
            1.0 - h0,
            -4.0 * t3 + 7.0 * t4 - 3.0 * t5,
            0.5 * t3 - t4 + 0.5 * t5,
        ],
        [
            d0,
            1.0 - 18.0 * t2 + 32.0 * t3 - 15.0 * t4,
            th - 4.5 * t2 + 6.0 * t3 - 2.5 * t4,
            -d0,
            -12.0 * t2 + 28.0 * t3 - 15.0 * t4,
            1.5 * t2 - 4.0 * t3 + 2.5 * t4,
        ],
    )
}

/// The previous observation (of the stations observed there: `Stations::last_t`).
#[derive(Debug, Clone, Default)]
pub(super) struct Last {
    pub(super) valid: bool,
    pub(super) t: f64,
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) accel: Vec<f64>,
    pub(super) levels: Vec<LevelState>,
    /// Scratch: the modal accelerations at an interior point, the loaded levels' forces there.
    pub(super) inner: Vec<f64>,
    /// Scratch: every level's force at an interior point (0 where it carries none), N.
    forces: Vec<f64>,
    /// Scratch: the modal accelerations at both ends as limits from inside the interval.
    a0: Vec<f64>,
    a1: Vec<f64>,
    /// Scratch: every level's force in those limits, at the start then at the end, N.
    limits: Vec<f64>,
    /// Scratch: the modes' (η, η̇) at an interior point.
    pub(super) qi: Vec<f64>,
    pub(super) vi: Vec<f64>,
    /// Scratch: the mode ranges of the loaded levels' pairs sampled and left out.
    usable: Vec<Range<usize>>,
    excluded: Vec<Range<usize>>,
}

impl Last {
    /// Keep observation `s` (with its modal accelerations `accel`).
    pub(super) fn keep(&mut self, s: &StepView, accel: &[f64]) {
        self.valid = true;
        self.t = s.t;
        copy_into(&mut self.q, s.q);
        copy_into(&mut self.v, s.v);
        copy_into(&mut self.accel, accel);
        self.levels.clear();
        self.levels.extend_from_slice(s.levels);
    }

    /// Raise the stations' peak accelerations and equilibrium shears with those inside the
    /// interval from the kept observation to `s` (modal accelerations `accel`) where a level
    /// carries force.
    pub(super) fn pulse(
        &mut self,
        system: &System,
        s: &StepView,
        accel: &[f64],
        stations: &mut [Stations],
    ) {
        let h = s.t - self.t;
        let n = system.len();
        if !self.valid
            || h <= 0.0
            || self.levels.len() != s.levels.len()
            || !system.hysteresis.storeys().is_empty()
        {
            return;
        }
        let loaded = |k: usize| self.levels[k].force != 0.0 || s.levels[k].force != 0.0;
        if !(0..s.levels.len()).any(loaded) {
            return;
        }
        if (0..s.levels.len()).any(|k| loaded(k) && system.levels[k].force.needs_approach_speed()) {
            return;
        }
        let (la, lv) = (&system.ground_load()[..n], &system.air_load()[..n]);
        let (damp, w) = (&system.damping_coefficients()[..n], &system.omega()[..n]);
        // The stations raised: those of the structures of a loaded level's pair, unless a
        // loaded level's pair that holds them has a mode the quintic cannot follow (it follows
        // a mode with `ω h ≤ MAX_OMEGA_H` closely; a longer interval, a grid step of free
        // flight, is left to the observations and the sub-grid). Decided per pair, so that a
        // row's pair is sampled exactly as the same pair alone (tests/fragility_row.rs).
        let (mut usable, mut excluded) = (
            std::mem::take(&mut self.usable),
            std::mem::take(&mut self.excluded),
        );
        usable.clear();
        excluded.clear();
        for k in (0..s.levels.len()).filter(|&k| loaded(k)) {
            let r = system.coupling_modes(k);
            let fast = w[r.clone()].iter().fold(0.0f64, |m, &x| m.max(x)) * h > MAX_OMEGA_H;
            if fast { &mut excluded } else { &mut usable }.push(r);
        }
        if usable.is_empty() {
            (self.usable, self.excluded) = (usable, excluded);
            return;
        }
        // The modes the interior points need: the loaded levels' pairs' (their forces read
        // them, the stations raised are theirs); in a row, not the other structures' (zero
        // coupling: the sums below skip only products with zeros).
        let span = (0..s.levels.len())
            .filter(|&k| loaded(k))
            .map(|k| system.coupling_modes(k))
            .fold(n..0, |acc, r| acc.start.min(r.start)..acc.end.max(r.end));
        let within = |rs: &[Range<usize>], st: &Stations| {
            rs.iter()
                .any(|r| r.start <= st.offset && st.offset + st.modes <= r.end)
        };
        self.inner.resize(n, 0.0);
        self.qi.resize(n, 0.0);
        self.vi.resize(n, 0.0);
        let nl = s.levels.len();
        self.forces.clear();
        self.forces.resize(nl, 0.0);
        // The ends' accelerations as limits from inside the interval: a law whose force jumps
        // where contact begins (Kelvin: `c δ̇` at δ = 0⁺) is observed at an onset with the force
        // before the jump, and at a release (were its force to jump there) with the force
        // after it. The quintic starts from the right-hand limit at an onset and ends at the
        // left-hand one at a release, and those limits are values of the pulse itself.
        copy_into(&mut self.a0, &self.accel[..n]);
        copy_into(&mut self.a1, &accel[..n]);
        self.limits.clear();
        for k in 0..nl {
            self.limits.push(self.levels[k].force);
        }
        for k in 0..nl {
            self.limits.push(s.levels[k].force);
        }
        let mut jumps = [false; 2];
        for k in (0..nl).filter(|&k| loaded(k)) {
            let law = &system.levels[k].force;
            let scale = self.levels[k].force.abs().max(s.levels[k].force.abs());
            for (end, lv, a) in [
                (0, &self.levels[k], &mut self.a0),
                (1, &s.levels[k], &mut self.a1),
            ] {
                // an onset (approaching) at the start, a release (separating) at the end
                let moving_in = if end == 0 {
                    lv.delta_dot > 0.0
                } else {
                    lv.delta_dot < 0.0
                };
                if lv.delta > 0.0 || !moving_in {
                    continue;
                }
                // the law's force just inside contact: `δ = 0⁺` as the smallest positive δ
                // (the continuous laws give ~1e-297 N there, their round-off, left out
                // below 1e-12 of the interval's force)
                let inside = law.force(f64::MIN_POSITIVE, lv.delta_dot, lv.delta_dot);
                let jump = inside - lv.force;
                if jump.abs() > 1e-12 * scale {
                    let r = system.coupling_modes(k);
                    for (x, c) in a[r.clone()].iter_mut().zip(&system.coupling(k)[r]) {
                        *x += c * jump;
                    }
                    self.limits[end * nl + k] = inside;
                    jumps[end] = true;
                }
            }
        }
        let (q0, v0, a0) = (&self.q[..n], &self.v[..n], &self.a0[..n]);
        let (q1, v1, a1) = (&s.q[..n], &s.v[..n], &self.a1[..n]);
        let raise_at = |stations: &mut [Stations], t: f64, accel: &[f64], ag: f64, f: &[f64]| {
            for st in stations.iter_mut() {
                if st.last_t == Some(self.t) && within(&usable, st) && !within(&excluded, st) {
                    st.raise_at(t, accel, ag, f);
                }
            }
        };
        // the ends' limits where they differ from the observations
        for (end, (on, t, a)) in [(jumps[0], self.t, a0), (jumps[1], s.t, a1)]
            .into_iter()
            .enumerate()
        {
            if on {
                let ag = system.ground.accel_velocity(t).0;
                raise_at(stations, t, a, ag, &self.limits[end * nl..(end + 1) * nl]);
            }
        }
        for j in 1..PARTS {
            let th = j as f64 / PARTS as f64;
            let t = self.t + th * h;
            let (hv, hd) = quintic(th);
            let (ag, vg) = system.ground.accel_velocity(t);
            // the modes' (η, η̇) on the quintic (kept in `qi`, `vi`), their equations' terms
            let (qi, vi) = (&mut self.qi[..n], &mut self.vi[..n]);
            let inner = &mut self.inner[..n];
            for m in span.clone() {
                let q = hv[0] * q0[m]
                    + hv[3] * q1[m]
                    + (hv[1] * v0[m] + hv[4] * v1[m]) * h
                    + (hv[2] * a0[m] + hv[5] * a1[m]) * h * h;
                let v = (hd[0] * q0[m] + hd[3] * q1[m]) / h
                    + (hd[1] * v0[m] + hd[4] * v1[m])
                    + (hd[2] * a0[m] + hd[5] * a1[m]) * h;
                (qi[m], vi[m]) = (q, v);
                inner[m] = la[m] * ag + lv[m] * vg - damp[m] * v - w[m] * w[m] * q;
            }
            // each loaded level's force from its law at the interpolated state (the others
            // carry none)
            for k in 0..nl {
                if !loaded(k) {
                    self.forces[k] = 0.0;
                    continue;
                }
                let c = system.coupling(k);
                let (mut cq, mut cv) = (0.0, 0.0);
                for m in system.coupling_modes(k) {
                    cq += c[m] * qi[m];
                    cv += c[m] * vi[m];
                }
                self.forces[k] = system.levels[k].state(cq, cv, 0.0).force;
            }
            for k in 0..nl {
                let f = self.forces[k];
                if !loaded(k) {
                    continue;
                }
                let r = system.coupling_modes(k);
                for (a, c) in inner[r.clone()].iter_mut().zip(&system.coupling(k)[r]) {
                    *a += c * f;
                }
            }
            raise_at(stations, t, inner, ag, &self.forces);
        }
        (self.usable, self.excluded) = (usable, excluded);
    }
}

/// `x_f = Σ_n φ_n(f) a_n` and `v_f −= Σ_n E_n(f) a_n` at every station f (`phi`, `eq`:
/// `[n·stations + station]`), each sum in the modes' order: the scalar loop's, bit for bit,
/// two stations per operation ([`F2`]: each lane the scalar operation), station pair by
/// station pair with both sums held in registers over the modes. (`x` starts from the first
/// mode's term, not from `0 +` it: the same value but for the sign of an exact zero, which no
/// |x| compared with a peak sees.)
#[inline(always)]
fn accelerations_and_inertia((phi, eq): (&[f64], &[f64]), a: &[f64], x: &mut [f64], v: &mut [f64]) {
    let (ns, nm) = (x.len(), a.len());
    if ns == 0 || nm == 0 {
        x.fill(0.0);
        return;
    }
    let (phi, eq, v) = (&phi[..nm * ns], &eq[..nm * ns], &mut v[..ns]);
    for p in 0..ns / 2 {
        let i = 2 * p;
        let s = F2::splat(a[0]);
        let mut xs = F2::new(phi[i], phi[i + 1]) * s;
        let mut vs = F2::new(v[i], v[i + 1]) - F2::new(eq[i], eq[i + 1]) * s;
        for n in 1..nm {
            let (j, s) = (n * ns + i, F2::splat(a[n]));
            xs = xs + F2::new(phi[j], phi[j + 1]) * s;
            vs = vs - F2::new(eq[j], eq[j + 1]) * s;
        }
        [x[i], x[i + 1]] = xs.get();
        [v[i], v[i + 1]] = vs.get();
    }
    if ns % 2 == 1 {
        let i = ns - 1;
        let (mut xs, mut vs) = (phi[i] * a[0], v[i] - eq[i] * a[0]);
        for n in 1..nm {
            xs += phi[n * ns + i] * a[n];
            vs -= eq[n * ns + i] * a[n];
        }
        (x[i], v[i]) = (xs, vs);
    }
}

impl Stations {
    /// Raise the peak absolute accelerations and equilibrium shears (`shear_with_damping`, N)
    /// with those at time `t` (s) between two observations, from the system's modal
    /// accelerations `accel`, the ground's `ag` (m/s²) and every contact level's force there
    /// `forces` (N, in the system's level order): `a = Σ φ_n η̈_n + a_g` (which counts towards
    /// the next floor history sample too) and `V = C − Σ E_n η̈_n − M a_g`, as
    /// [`Stations::observe`] forms them at an observation.
    pub(super) fn raise_at(&mut self, t: f64, accel: &[f64], ag: f64, forces: &[f64]) {
        let (nm, ns) = (self.modes, self.heights.len());
        if ns == 0 {
            return;
        }
        let a = &accel[self.offset..self.offset + nm];
        let nl = self.levels.min(forces.len());
        let (signs, forces) = (&self.signs[..nl], &forces[..nl]);
        // the levels that carry force on this structure, `sign_k F_k ≠ 0`, once per call (the
        // others add an exact zero to a sum that is never −0: leaving them out changes no bit)
        self.loaded.clear();
        for k in 0..nl {
            let sf = signs[k] * forces[k];
            if sf != 0.0 {
                self.loaded.push((k, sf));
            }
        }
        let loaded = &self.loaded[..];
        let (x, c) = self.point[..2 * ns].split_at_mut(ns);
        // `C − M a_g` per station, `C` the contact forces above it, a sum from 0 in the levels'
        // order (floors: a level acts at its floor, and what is above a storey sums from the
        // top; a cantilever's `above` already marks every level above the section)
        c.fill(0.0);
        for &(k, sf) in loaded {
            for &f in &self.level_stations[self.level_at[k]..self.level_at[k + 1]] {
                c[f] += sf;
            }
        }
        let mass_above = &self.between.mass_above[..ns];
        if matches!(self.equilibrium, Equilibrium::Lumped(_)) {
            let mut c_above = 0.0;
            for f in (0..ns).rev() {
                c_above += c[f];
                c[f] = c_above - mass_above[f] * ag;
            }
        } else {
            for f in 0..ns {
                c[f] -= mass_above[f] * ag;
            }
        }
        // `Σ φ_n η̈_n` and `C − M a_g − Σ E_n η̈_n`, mode by mode over the stations (each
        // station's sums in the modes' order, as a loop per station forms them)
        let (phi, eq_rows) = (&self.phi[..nm * ns], &self.between.eq_rows[..nm * ns]);
        accelerations_and_inertia((phi, eq_rows), a, x, c);
        let (peaks, hold) = (&mut self.peaks[..ns], &mut self.hold[..ns]);
        for f in 0..ns {
            let x = x[f] + ag;
            let p = &mut peaks[f];
            if x.abs() > p.acceleration {
                p.acceleration = x.abs();
                p.acceleration_time = t;
            }
            // (and towards the next floor history sample, as the sub-grid's values)
            if x.abs() > hold[f].abs() {
                hold[f] = x;
            }
            raise(&mut p.shear_with_damping, c[f].abs());
        }
    }
}
