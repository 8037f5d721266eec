//! Floor peaks between observations where the cubic Hermite cannot follow the modes.
//!
//! The floor recorder refines its peaks between two observations on the cubic Hermite
//! interpolant of (y, ẏ) at both ends, which follows a mode only while `ω h` is small (its
//! error on a sinusoid is about `(ωh)⁴/384` of the amplitude). A cantilever's section shear is
//! weighted by ω_n², and a stiff impact sets its highest modes ringing for a few ms after each
//! release (40 modes: ω₄₀ = 65 000 rad/s against 1 ms observations): the Hermite neither
//! follows nor bounds that ringing.
//!
//! Per structure and interval `[t₀, t₀ + h]`, every mode is modelled in closed form: the exact
//! solution of `η̈ + 2σ η̇ + ω² η = f(τ)` from (η, η̇) at t₀ with its forcing `f` (ground, air,
//! contact and hysteretic loads: everything but the mode's own stiffness and damping) linear
//! between its values at both ends,
//!
//! `η(τ) = α + βτ + e^{−στ}(A cos ω_d τ + B sin ω_d τ)`, `β = s/ω²`, `α = (f₀ − 2σβ)/ω²`,
//! `s = (f₁ − f₀)/h`, `A = η₀ − α`, `B = (η̇₀ − β + σA)/ω_d`, `ω_d = ω√(1 − ζ²)`
//!
//! (exact for the free flight of `exact-modal` and `adaptive` wherever the forcing is linear,
//! as it is between a record's samples), plus the cubic Hermite of its mismatch with the state
//! observed at the end, so that the model meets both observations exactly. The homogeneous
//! part `R_n(τ) = e^{−στ}(A cos + B sin)` is the mode's ringing, of size at most
//! `ρ_n = √(A² + B²)` and rate at most `ω_n ρ_n`.
//!
//! A mode is *fast* when `ω_n h >` the resolution Θ ([`DEFAULT_RESOLUTION`]). For a station
//! quantity `Q = Σ c_n η_n` the Hermite of Q's ends is off by at most `Σ_fast |c_n| ρ_n (2 +
//! (8/27) ω_n h)` (the ringing itself, and its Hermite: the slope weights are at most 4/27).
//! Where that is negligible (below [`NEGLIGIBLE`] of the peak) the Hermite stands. Otherwise
//! Q over the interval is bounded by the Hermite bound of its slow part (Q less the fast
//! modes' ends) plus the fast modes' linear part at its larger end plus `Σ_fast |c_n| ρ_n`
//! (`SubGrid::station_sums`); where that cannot reach the peak nothing changes, and where it
//! can the station's displacement, drift and storey force are evaluated from the model on a
//! sub-grid of `m` equal parts with `ω_max h/m ≤ Θ` and refined on each part's cubic Hermite
//! (as accurate there as the Hermite is for a slow mode).

// Index loops over parallel per-mode slices read like the sums they form.
#![allow(clippy::needless_range_loop)]

use crate::numerics::hermite::Basis;
use crate::numerics::lanes::F2;

/// The default resolution Θ: a mode is followed by the cubic Hermite while `ω h ≤ Θ`, and the
/// sub-grid's parts are at most `Θ/ω_max` long. At 0.5 the Hermite's error on a sinusoid is
/// `Θ⁴/384 ≈ 1.6e-4` of its amplitude.
pub const DEFAULT_RESOLUTION: f64 = 0.5;

/// The self-check's resolution: the run's. The sub-grid's own error is bounded by
/// construction (about `Θ⁴/384 ≈ 1.6e-4` of a mode's ringing, tested against independent
/// integrations), far below the check's 1 %; what the check must vary is the integration. A
/// run whose floors were taken without the sub-grid is still flagged by it.
pub const CHECK_RESOLUTION: f64 = DEFAULT_RESOLUTION;

/// A station's ringing bound below this fraction of its peak leaves the Hermite's result
/// within that fraction of the truth: no sub-grid.
pub const NEGLIGIBLE: f64 = 1e-4;

/// Most parts of one interval's sub-grid (a bound on the work of one interval; reached only
/// for `ω h > 256 Θ` of a mode whose ringing matters, see [`SubGrid::resolved_omega`]).
const MAX_PARTS: usize = 256;

/// The 4/27 of the Hermite's slope weights, doubled (both ends).
const TWO_REACH: f64 = 8.0 / 27.0;

/// One mode's closed form over an interval (see the module documentation).
#[derive(Debug, Clone, Copy, Default)]
struct Model {
    alpha: f64,
    beta: f64,
    a: f64,
    b: f64,
    sigma: f64,
    wd: f64,
    /// Overdamped (ζ ≥ 0.999) or without stiffness: the mode does not ring; it is taken on its
    /// own cubic Hermite.
    plain: bool,
}

impl Model {
    #[inline]
    fn new(q0: f64, v0: f64, f0: f64, f1: f64, h: f64, w: f64, c: f64) -> Model {
        let sigma = 0.5 * c;
        if !(w > 0.0 && sigma < 0.999 * w) {
            return Model {
                plain: true,
                ..Model::default()
            };
        }
        let wd = w * (1.0 - (sigma / w) * (sigma / w)).sqrt();
        let beta = (f1 - f0) / h / (w * w);
        let alpha = (f0 - 2.0 * sigma * beta) / (w * w);
        let a = q0 - alpha;
        let b = (v0 - beta + sigma * a) / wd;
        Model {
            alpha,
            beta,
            a,
            b,
            sigma,
            wd,
            plain: false,
        }
    }

    /// The size of the ringing, `√(A² + B²)`.
    #[inline]
    fn rho(&self) -> f64 {
        if self.plain {
            0.0
        } else {
            self.a.hypot(self.b)
        }
    }
}

/// The sub-grid of one structure: its modes' state at the previous observation, the ringing
/// weights of the current interval and the scratch of the sub-grid's values.
#[derive(Debug, Clone)]
pub(crate) struct SubGrid {
    /// η, η̇ and the forcing f of every mode at the previous observation.
    prev_q: Vec<f64>,
    prev_v: Vec<f64>,
    prev_f: Vec<f64>,
    /// The forcing at the current observation (scratch).
    now_f: Vec<f64>,
    have_prev: bool,
    /// Per mode, `ρ_n` for the fast modes of the current interval, else 0.
    weight: Vec<f64>,
    /// Per fast mode `[η₀, η̇₀, η₁, η̇₁, α, β]` of the current interval: `[n·6 + j]`.
    lin: Vec<f64>,
    /// The fast modes of the current interval with a ringing, and the same by decreasing ω
    /// (scratch).
    fast: Vec<usize>,
    order: Vec<usize>,
    /// `2 + (8/27) ω h` of the fastest of them: the Hermite's error on a ringing of size ρ is
    /// at most that times ρ.
    pub hermite_factor: f64,
    /// Per station, the sums over the fast modes of [`SubGrid::lin`] weighted by φ
    /// (`[station·6 + j]`), and of |c| ρ for the displacement, the drift and the storey force
    /// (`[station·3 + k]`, k = 0, 1, 2); with rows, the same six sums weighted by the
    /// storey-force rows.
    pub sums_u: Vec<f64>,
    pub sums_v: Vec<f64>,
    pub rings: Vec<f64>,
    /// Parts of the sub-grid and their length, s (set by [`SubGrid::evaluate`]).
    pub parts: usize,
    pub delta: f64,
    /// η, η̇ of every mode at the sub-grid's points: `[k·modes + n]`.
    eta: Vec<f64>,
    etad: Vec<f64>,
    /// The cubic Hermite's basis and slope basis at the points (scratch).
    basis: Vec<(Basis, Basis)>,
    /// Per point `[k·stations + station]`: u, u̇, V, V̇.
    pub u: Vec<f64>,
    pub ud: Vec<f64>,
    pub v: Vec<f64>,
    pub vd: Vec<f64>,
    /// `ns` zeros: the start of the sub-grid's sums ([`combine`]).
    zeros: Vec<f64>,
    /// η̈ and its rate of every mode at the sub-grid's points, `[k·modes + n]` (set by
    /// [`SubGrid::accelerations`]).
    etadd: Vec<f64>,
    etaddd: Vec<f64>,
    /// η⃛ of every mode at both ends of the interval under its linear forcing (set by
    /// [`SubGrid::jerks`]).
    jerk0: Vec<f64>,
    jerk1: Vec<f64>,
}

impl SubGrid {
    pub(crate) fn new(modes: usize) -> SubGrid {
        SubGrid {
            prev_q: vec![0.0; modes],
            prev_v: vec![0.0; modes],
            prev_f: vec![0.0; modes],
            now_f: vec![0.0; modes],
            have_prev: false,
            weight: vec![0.0; modes],
            lin: vec![0.0; 6 * modes],
            fast: Vec::with_capacity(modes),
            order: Vec::with_capacity(modes),
            hermite_factor: 0.0,
            sums_u: Vec::new(),
            sums_v: Vec::new(),
            rings: Vec::new(),
            parts: 0,
            delta: 0.0,
            eta: Vec::new(),
            etad: Vec::new(),
            basis: Vec::new(),
            u: Vec::new(),
            ud: Vec::new(),
            v: Vec::new(),
            vd: Vec::new(),
            zeros: Vec::new(),
            etadd: Vec::new(),
            etaddd: Vec::new(),
            jerk0: vec![0.0; modes],
            jerk1: vec![0.0; modes],
        }
    }

    /// The interval ending at this observation (`q`, `v`, modal accelerations `a`; the
    /// structure's `omega` and damping coefficients `c = 2σ`): the forcing now, and for the
    /// fast modes (`ω h > theta`) their ringing weights. Returns whether any fast mode rings.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn prepare(
        &mut self,
        h: Option<f64>,
        theta: f64,
        (q, v, a): (&[f64], &[f64], &[f64]),
        omega: &[f64],
        c: &[f64],
        omega_max: f64,
    ) -> bool {
        let nm = self.prev_q.len();
        for n in 0..nm {
            self.now_f[n] = a[n] + c[n] * v[n] + omega[n] * omega[n] * q[n];
        }
        self.fast.clear();
        let h = match h {
            Some(h) if self.have_prev && omega_max * h > theta => h,
            _ => return false,
        };
        let mut fastest: f64 = 0.0;
        for n in 0..nm {
            self.weight[n] = 0.0;
            let w = omega[n];
            if w * h > theta {
                let m = Model::new(
                    self.prev_q[n],
                    self.prev_v[n],
                    self.prev_f[n],
                    self.now_f[n],
                    h,
                    w,
                    c[n],
                );
                let r = m.rho();
                if r > 0.0 {
                    self.weight[n] = r;
                    self.lin[6 * n..6 * n + 6].copy_from_slice(&[
                        self.prev_q[n],
                        self.prev_v[n],
                        q[n],
                        v[n],
                        m.alpha,
                        m.beta,
                    ]);
                    self.fast.push(n);
                    fastest = fastest.max(w);
                }
            }
        }
        self.hermite_factor = 2.0 + TWO_REACH * fastest * h;
        !self.fast.is_empty()
    }

    /// Per station, the fast modes' sums of the quantities' bounds: with `phi` (and its
    /// absolute values `abs_phi`, and those of the drift rows `abs_drift`) and, with `rows`,
    /// the storey-force rows (`[n·stations + station]`), see [`SubGrid::sums_u`]. Each
    /// station's sums are contiguous (the per-station decision reads them together); every
    /// sum is accumulated from 0 over the fast modes in their order, as a plain loop would.
    pub(crate) fn station_sums(
        &mut self,
        (phi, abs_phi, abs_drift): (&[f64], &[f64], &[f64]),
        rows: Option<(&[f64], &[f64])>,
        ns: usize,
    ) {
        // (resized once: the lengths only change with the structure, i.e. never)
        self.sums_u.resize(6 * ns, 0.0);
        self.rings.resize(3 * ns, 0.0);
        self.sums_v
            .resize(if rows.is_some() { 6 * ns } else { 0 }, 0.0);
        self.sums_u.fill(0.0);
        self.rings.fill(0.0);
        self.sums_v.fill(0.0);
        let (su, rings) = (&mut self.sums_u[..6 * ns], &mut self.rings[..3 * ns]);
        for &n in &self.fast {
            let lin: [F2; 3] = std::array::from_fn(|i| {
                F2::new(self.lin[6 * n + 2 * i], self.lin[6 * n + 2 * i + 1])
            });
            let r = self.weight[n];
            let at = n * ns..(n + 1) * ns;
            let (c, au, ad) = (
                &phi[at.clone()],
                &abs_phi[at.clone()],
                &abs_drift[at.clone()],
            );
            for ((s, ring), ((&c, &au), &ad)) in (su.as_chunks_mut::<6>().0.iter_mut())
                .zip(rings.as_chunks_mut::<3>().0.iter_mut())
                .zip(c.iter().zip(au).zip(ad))
            {
                add_six(s, c, &lin);
                ring[0] += au * r;
                ring[1] += ad * r;
            }
            if let Some((rows, abs_rows)) = rows {
                let (c, av) = (&rows[at.clone()], &abs_rows[at]);
                for ((s, ring), (&c, &av)) in (self.sums_v.as_chunks_mut::<6>().0.iter_mut())
                    .zip(rings.as_chunks_mut::<3>().0.iter_mut())
                    .zip(c.iter().zip(av))
                {
                    add_six(s, c, &lin);
                    ring[2] += av * r;
                }
            }
        }
    }

    /// The ω the sub-grid must resolve: that of the fastest mode left once the fastest modes
    /// whose ringing together stays below [`NEGLIGIBLE`] of the structure's largest peak of
    /// every quantity are set aside (their values are still in the sub-grid's points; only
    /// their swings between the points are not followed). `cmax[k][n]`: the largest |c| of
    /// quantity k (displacement, drift, storey force) over the stations for mode n; `peak[k]`:
    /// the structure's largest peak of quantity k.
    pub(crate) fn resolved_omega(
        &mut self,
        omega: &[f64],
        cmax: [&[f64]; 3],
        peak: [f64; 3],
    ) -> f64 {
        self.order.clear();
        self.order.extend_from_slice(&self.fast);
        self.order.sort_by(|&a, &b| omega[b].total_cmp(&omega[a]));
        let mut dropped = [0.0; 3];
        for &n in &self.order {
            for k in 0..3 {
                if let Some(&c) = cmax[k].get(n) {
                    dropped[k] += c * self.weight[n];
                    if dropped[k] > NEGLIGIBLE * peak[k] {
                        // this mode and every slower one are followed
                        return omega[n];
                    }
                }
            }
        }
        // every fast mode's ringing negligible: one part (the model's ends)
        0.0
    }

    /// Fill the sub-grid of the interval of length `h` ending at (`q`, `v`): every mode's
    /// model at the points, then u, u̇ at every station from `phi` and, with `rows`, V, V̇
    /// (both `[n·stations + station]`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn evaluate(
        &mut self,
        h: f64,
        theta: f64,
        (q, v): (&[f64], &[f64]),
        omega: &[f64],
        c: &[f64],
        omega_max: f64,
        phi: &[f64],
        rows: Option<&[f64]>,
        ns: usize,
    ) {
        let nm = self.prev_q.len();
        let parts = ((omega_max * h / theta).ceil() as usize).clamp(1, MAX_PARTS);
        let delta = h / parts as f64;
        self.parts = parts;
        self.delta = delta;
        let pts = parts + 1;
        self.eta.resize(pts * nm, 0.0);
        self.etad.resize(pts * nm, 0.0);
        self.basis.clear();
        self.basis.extend((0..pts).map(|k| {
            let th = k as f64 / parts as f64;
            (Basis::at(th), Basis::slope_at(th))
        }));
        for n in 0..nm {
            let (q0, v0) = (self.prev_q[n], self.prev_v[n]);
            let m = Model::new(q0, v0, self.prev_f[n], self.now_f[n], h, omega[n], c[n]);
            if m.plain {
                // no ringing: the mode's own cubic Hermite
                for k in 0..pts {
                    let (b, s) = &self.basis[k];
                    self.eta[k * nm + n] = b.combine(q0, v0, q[n], v[n], h);
                    self.etad[k * nm + n] = s.combine(q0, v0, q[n], v[n], h) / h;
                }
                continue;
            }
            // e^{(−σ + iω_d) kδ} by one complex product per point
            let (sn, cs) = (m.wd * delta).sin_cos();
            let e = (-m.sigma * delta).exp();
            let (rc, rs) = (e * cs, e * sn);
            let (mut cr, mut ci) = (1.0, 0.0);
            let (ya, yb) = (m.wd * m.b - m.sigma * m.a, -(m.wd * m.a + m.sigma * m.b));
            for k in 0..pts {
                let tau = k as f64 * delta;
                self.eta[k * nm + n] = m.alpha + m.beta * tau + m.a * cr + m.b * ci;
                self.etad[k * nm + n] = m.beta + ya * cr + yb * ci;
                (cr, ci) = (cr * rc - ci * rs, ci * rc + cr * rs);
            }
            // the mismatch with the observed end, spread by its cubic Hermite
            let (eq, ev) = (
                q[n] - self.eta[parts * nm + n],
                v[n] - self.etad[parts * nm + n],
            );
            if eq != 0.0 || ev != 0.0 {
                for k in 1..pts {
                    let (b, s) = &self.basis[k];
                    self.eta[k * nm + n] += b.combine(0.0, 0.0, eq, ev, h);
                    self.etad[k * nm + n] += s.combine(0.0, 0.0, eq, ev, h) / h;
                }
            }
        }
        let stations = |x: &mut Vec<f64>| x.resize(pts * ns, 0.0);
        stations(&mut self.u);
        stations(&mut self.ud);
        self.zeros.resize(ns, 0.0);
        let dims = (nm, ns, pts);
        let etas = (&self.eta[..], &self.etad[..]);
        combine(etas, phi, dims, &self.zeros, &mut self.u, &mut self.ud);
        if let Some(rows) = rows {
            stations(&mut self.v);
            stations(&mut self.vd);
            combine(etas, rows, dims, &self.zeros, &mut self.v, &mut self.vd);
        }
    }

    /// Per station, for a quantity `Q = Σ_n c_n η̈_n` (+ parts linear over the interval) with
    /// per-mode weights `coeff` (`[n·stations + station]`) and `abs_weight` (≥ 0, e.g. `|φ_n|
    /// ω_n²`: the ringing part of a fast mode's η̈ is `R̈_n`, `|R̈_n| ≤ ω_n² ρ_n`): the fast
    /// modes' ringing `Σ_fast abs_weight ρ_n` into `ring`, and their part of Q at both ends of
    /// the interval, `Σ_fast c_n η̈_n(0)` and `Σ_fast c_n η̈_n(h)` (η̈ from the mode's equation
    /// at the observed states), into `ends` (`[0..ns]` and `[ns..2ns]`).
    pub(crate) fn fast_parts(
        &self,
        (coeff, abs_weight): (&[f64], &[f64]),
        (omega, c): (&[f64], &[f64]),
        ns: usize,
        ring: &mut [f64],
        ends: &mut [f64],
    ) {
        ring[..ns].fill(0.0);
        ends[..2 * ns].fill(0.0);
        let (e0, e1) = ends[..2 * ns].split_at_mut(ns);
        for &n in &self.fast {
            let (w2, r, l) = (
                omega[n] * omega[n],
                self.weight[n],
                &self.lin[6 * n..6 * n + 6],
            );
            let a0 = self.prev_f[n] - c[n] * l[1] - w2 * l[0];
            let a1 = self.now_f[n] - c[n] * l[3] - w2 * l[2];
            let (cf, aw) = (
                &coeff[n * ns..(n + 1) * ns],
                &abs_weight[n * ns..(n + 1) * ns],
            );
            for f in 0..ns {
                ring[f] += aw[f] * r;
                e0[f] += cf[f] * a0;
                e1[f] += cf[f] * a1;
            }
        }
    }

    /// [`SubGrid::resolved_omega`] for any number of quantities: `cmax[k][n]` the largest
    /// |c| of quantity k over the stations for mode n, `peak[k]` the structure's largest peak
    /// of quantity k.
    pub(crate) fn resolved_omega_for(
        &mut self,
        omega: &[f64],
        cmax: &[&[f64]],
        peak: &[f64],
    ) -> f64 {
        self.order.clear();
        self.order.extend_from_slice(&self.fast);
        self.order.sort_by(|&a, &b| omega[b].total_cmp(&omega[a]));
        let mut dropped = [0.0; 8];
        for &n in &self.order {
            for (k, (c, p)) in cmax.iter().zip(peak).enumerate() {
                if let Some(&c) = c.get(n) {
                    dropped[k] += c * self.weight[n];
                    if dropped[k] > NEGLIGIBLE * p {
                        return omega[n];
                    }
                }
            }
        }
        0.0
    }

    /// After [`SubGrid::evaluate`] over an interval of length `h`: every mode's acceleration
    /// and its rate at the sub-grid's points from its equation of motion with the interval's
    /// linear load, `η̈ = f(τ) − 2σ η̇ − ω² η` and `η⃛ = ḟ − 2σ η̈ − ω² η̇` (exact for the closed
    /// form; at both ends, where the model meets the observed (η, η̇), η̈ is the observed
    /// modal acceleration).
    pub(crate) fn accelerations(&mut self, h: f64, omega: &[f64], c: &[f64]) {
        let nm = self.prev_q.len();
        let pts = self.parts + 1;
        self.etadd.resize(pts * nm, 0.0);
        self.etaddd.resize(pts * nm, 0.0);
        for n in 0..nm {
            let (w2, cn) = (omega[n] * omega[n], c[n]);
            let slope = (self.now_f[n] - self.prev_f[n]) / h;
            for k in 0..pts {
                let i = k * nm + n;
                let tau = k as f64 * self.delta;
                let a = self.prev_f[n] + slope * tau - cn * self.etad[i] - w2 * self.eta[i];
                self.etadd[i] = a;
                self.etaddd[i] = slope - cn * a - w2 * self.etad[i];
            }
        }
    }

    /// At every sub-grid point k, `y[k] = Σ_n coeff[n·ns + f] η̈_n` and its rate (station
    /// `f` of `ns`) after [`SubGrid::accelerations`], into `y` and `yd` (`parts + 1` each).
    pub(crate) fn station_accelerations(
        &self,
        coeff: &[f64],
        ns: usize,
        f: usize,
        y: &mut [f64],
        yd: &mut [f64],
    ) {
        let nm = self.prev_q.len();
        for k in 0..=self.parts {
            let (a, j) = (
                &self.etadd[k * nm..(k + 1) * nm],
                &self.etaddd[k * nm..(k + 1) * nm],
            );
            let (mut s, mut sd) = (0.0, 0.0);
            for n in 0..nm {
                let c = coeff[n * ns + f];
                s += c * a[n];
                sd += c * j[n];
            }
            y[k] = s;
            yd[k] = sd;
        }
    }

    /// Before [`SubGrid::advance`], over the interval of length `h` ending at this observation
    /// (modal velocities `v` and accelerations `a`, the structure's `omega` and damping
    /// coefficients `c`): every mode's rate of acceleration at both ends under the interval's
    /// linear forcing, `η⃛ = ḟ − 2σ η̈ − ω² η̇` with `ḟ = (f₁ − f₀)/h` (the closed form's, as
    /// [`SubGrid::accelerations`]), returned as (start, end). `None` before the first interval.
    #[inline(never)]
    pub(crate) fn jerks(
        &mut self,
        h: f64,
        va: (&[f64], &[f64]),
        omega: &[f64],
        c: &[f64],
    ) -> Option<(&[f64], &[f64])> {
        self.jerks_body(h, va, omega, c)
    }

    /// [`SubGrid::jerks`] compiled for AVX (four modes to an operation, the same IEEE
    /// operations lane by lane). Safety: the processor has AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    pub(crate) unsafe fn jerks_avx(
        &mut self,
        h: f64,
        va: (&[f64], &[f64]),
        omega: &[f64],
        c: &[f64],
    ) -> Option<(&[f64], &[f64])> {
        self.jerks_body(h, va, omega, c)
    }

    #[inline(always)]
    fn jerks_body(
        &mut self,
        h: f64,
        (v, a): (&[f64], &[f64]),
        omega: &[f64],
        c: &[f64],
    ) -> Option<(&[f64], &[f64])> {
        if !self.have_prev {
            return None;
        }
        let nm = self.prev_q.len();
        jerk_pass(
            h,
            (&mut self.jerk0[..nm], &mut self.jerk1[..nm]),
            (&v[..nm], &a[..nm], &omega[..nm], &c[..nm]),
            (
                &self.prev_q[..nm],
                &self.prev_v[..nm],
                &self.prev_f[..nm],
                &self.now_f[..nm],
            ),
        );
        Some((&self.jerk0[..nm], &self.jerk1[..nm]))
    }

    /// Keep this observation's state for the next interval.
    pub(crate) fn advance(&mut self, q: &[f64], v: &[f64]) {
        let nm = self.prev_q.len();
        self.prev_q.copy_from_slice(&q[..nm]);
        self.prev_v.copy_from_slice(&v[..nm]);
        std::mem::swap(&mut self.prev_f, &mut self.now_f);
        self.have_prev = true;
    }
}

/// [`SubGrid::jerks`]' pass over the modes (its slices as arguments: the compiler knows the
/// outputs alias none of the inputs, and vectorises without run-time overlap checks).
#[inline(always)]
fn jerk_pass(
    h: f64,
    (j0, j1): (&mut [f64], &mut [f64]),
    (v, a, omega, c): (&[f64], &[f64], &[f64], &[f64]),
    (q0, v0, f0, f1): (&[f64], &[f64], &[f64], &[f64]),
) {
    let nm = j0.len();
    let (j1, v, a, omega, c) = (&mut j1[..nm], &v[..nm], &a[..nm], &omega[..nm], &c[..nm]);
    let (q0, v0, f0, f1) = (&q0[..nm], &v0[..nm], &f0[..nm], &f1[..nm]);
    for n in 0..nm {
        let w2 = omega[n] * omega[n];
        let slope = (f1[n] - f0[n]) / h;
        // η̈ at the start from the mode's equation (the previous observation's)
        let a0 = f0[n] - c[n] * v0[n] - w2 * q0[n];
        j0[n] = slope - c[n] * a0 - w2 * v0[n];
        j1[n] = slope - c[n] * a[n] - w2 * v[n];
    }
}

/// `s[j] += c · lin[j]` for the six sums (in pairs: [`F2`], each lane the scalar operation).
#[inline(always)]
fn add_six(s: &mut [f64; 6], c: f64, lin: &[F2; 3]) {
    let c = F2::splat(c);
    for i in 0..3 {
        let [a, b] = (F2::new(s[2 * i], s[2 * i + 1]) + c * lin[i]).get();
        (s[2 * i], s[2 * i + 1]) = (a, b);
    }
}

/// `out[k][f] = s_f + Σ_n c[n·ns + f] x[k][n]` for every station f (`c`: `[mode·stations +
/// station]`), summed in the modes' order from `s_f = start.0 · start.1[f]` (`start`) or from
/// the first mode's term: the same operations in the same order as the plain loops, two
/// stations per operation ([`F2`]: each lane is the scalar operation, bit for bit). Station
/// pair by station pair, the `K` sums held in registers over the modes (each coefficient
/// pair read once for all `K`, no sum stored and reloaded per mode).
#[inline(always)]
pub(crate) fn modal_sums<const K: usize>(
    c: &[f64],
    ns: usize,
    x: [&[f64]; K],
    out: [&mut [f64]; K],
    start: Option<(f64, &[f64])>,
) {
    modal_sums_from(c, ns, x, out, start, 0);
}

/// [`modal_sums`] of the stations from `first` on (the ones before it formed elsewhere:
/// [`modal_sums_avx`]).
#[inline(always)]
fn modal_sums_from<const K: usize>(
    c: &[f64],
    ns: usize,
    x: [&[f64]; K],
    out: [&mut [f64]; K],
    start: Option<(f64, &[f64])>,
    first: usize,
) {
    if ns == 0 {
        return;
    }
    let nm = c.len() / ns;
    let c = &c[..nm * ns];
    // (every input cut to the modes once: no bounds check per term)
    let x: [&[f64]; K] = std::array::from_fn(|k| &x[k][..nm]);
    let m0 = usize::from(start.is_none());
    let pairs = (ns - first) / 2;
    for p in 0..pairs {
        let i = first + 2 * p;
        // the first term: `s·w_f`, or the first mode's
        let mut acc: [F2; K] = match start {
            Some((s, w)) => [F2::splat(s) * F2::new(w[i], w[i + 1]); K],
            None => std::array::from_fn(|k| F2::splat(x[k][0]) * F2::new(c[i], c[i + 1])),
        };
        for j in m0..nm {
            let cj = F2::new(c[j * ns + i], c[j * ns + i + 1]);
            for k in 0..K {
                acc[k] = acc[k] + cj * F2::splat(x[k][j]);
            }
        }
        for k in 0..K {
            let [a, b] = acc[k].get();
            (out[k][i], out[k][i + 1]) = (a, b);
        }
    }
    if (ns - first) % 2 == 1 {
        let i = ns - 1;
        for k in 0..K {
            let mut o = match start {
                Some((s, w)) => s * w[i],
                None => x[k][0] * c[i],
            };
            for j in m0..nm {
                o += c[j * ns + i] * x[k][j];
            }
            out[k][i] = o;
        }
    }
}

/// [`modal_sums`] four stations to an AVX operation (each lane the scalar operation of its
/// station, in the modes' order: the same bits), the stations after the last group of four
/// as [`modal_sums`] has them. Safety: the processor has AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
pub(crate) unsafe fn modal_sums_avx<const K: usize>(
    c: &[f64],
    ns: usize,
    x: [&[f64]; K],
    out: [&mut [f64]; K],
    start: Option<(f64, &[f64])>,
) {
    use std::arch::x86_64::{
        _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_setzero_pd,
        _mm256_storeu_pd,
    };
    if ns == 0 {
        return;
    }
    let nm = c.len() / ns;
    let c = &c[..nm * ns];
    let mut xs = x;
    for k in 0..K {
        xs[k] = &x[k][..nm];
    }
    let x = xs;
    let m0 = usize::from(start.is_none());
    let quads = ns / 4;
    for p in 0..quads {
        let i = 4 * p;
        // (a macro, not a closure: every operation inlined here, with its AVX)
        macro_rules! load {
            ($a:expr) => {
                // SAFETY: AVX (the caller); four values in bounds (the slice is cut to them)
                unsafe { _mm256_loadu_pd($a[..4].as_ptr()) }
            };
        }
        // the first term: `s·w_f`, or the first mode's
        let mut acc = [_mm256_setzero_pd(); K];
        match start {
            Some((s, w)) => acc = [_mm256_mul_pd(_mm256_set1_pd(s), load!(&w[i..])); K],
            None => {
                let c0 = load!(&c[i..]);
                for k in 0..K {
                    acc[k] = _mm256_mul_pd(_mm256_set1_pd(x[k][0]), c0);
                }
            }
        }
        for j in m0..nm {
            let cj = load!(&c[j * ns + i..]);
            for k in 0..K {
                acc[k] = _mm256_add_pd(acc[k], _mm256_mul_pd(cj, _mm256_set1_pd(x[k][j])));
            }
        }
        for k in 0..K {
            let o = &mut out[k][i..i + 4];
            // SAFETY: AVX (the caller); four values in bounds
            unsafe { _mm256_storeu_pd(o.as_mut_ptr(), acc[k]) };
        }
    }
    modal_sums_from(c, ns, x, out, start, 4 * quads);
}

/// `y[k·ns + f] = Σ_n coeff[n·ns + f] η[k·nm + n]` (and ẏ from η̇) at every point k, each sum
/// from 0 in the modes' order ([`modal_sums`] from `0·zeros`, the same operations as a loop
/// adding to zeroed values).
fn combine(
    (eta, etad): (&[f64], &[f64]),
    coeff: &[f64],
    (nm, ns, pts): (usize, usize, usize),
    zeros: &[f64],
    y: &mut [f64],
    yd: &mut [f64],
) {
    for k in 0..pts {
        let (e, ed) = (&eta[k * nm..(k + 1) * nm], &etad[k * nm..(k + 1) * nm]);
        let (y, yd) = (&mut y[k * ns..(k + 1) * ns], &mut yd[k * ns..(k + 1) * ns]);
        modal_sums(coeff, ns, [e, ed], [y, yd], Some((0.0, zeros)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stations' sums four stations to an AVX operation ([`modal_sums_avx`]) are
    /// [`modal_sums`]' bit for bit: every station count 0–13 (groups of four, a pair and a
    /// single one left), 1–9 modes, one to three sums, from the first mode's term and from a
    /// start `s·w`, on values that round. (Skipped without AVX.)
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn avx_sums_are_the_pairs_bit_for_bit() {
        if !crate::numerics::vex::available() {
            return;
        }
        let vals = |n: usize, a: f64, b: f64| -> Vec<f64> {
            (0..n)
                .map(|j| ((j as f64) * a + b).sin() / (j as f64 + b))
                .collect()
        };
        for ns in 0..14 {
            for nm in 1..10 {
                let c = vals(ns * nm, 1.3, 0.7);
                let x = [vals(nm, 0.9, 1.1), vals(nm, 2.1, 0.4), vals(nm, 0.3, 2.5)];
                let w = vals(ns, 1.7, 0.2);
                for start in [None, Some((-0.37, &w[..]))] {
                    let (mut a, mut b) = (
                        [vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]],
                        [vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]],
                    );
                    let [a0, a1, a2] = &mut a;
                    modal_sums(&c, ns, [&x[0], &x[1], &x[2]], [a0, a1, a2], start);
                    let [b0, b1, b2] = &mut b;
                    // SAFETY: the processor has AVX (tested above)
                    unsafe { modal_sums_avx(&c, ns, [&x[0], &x[1], &x[2]], [b0, b1, b2], start) };
                    let (mut a1s, mut b1s) = (vec![0.0; ns], vec![0.0; ns]);
                    modal_sums(&c, ns, [&x[1]], [&mut a1s], start);
                    // SAFETY: as above
                    unsafe { modal_sums_avx(&c, ns, [&x[1]], [&mut b1s], start) };
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    for k in 0..3 {
                        assert_eq!(bits(&a[k]), bits(&b[k]), "{ns} stations, {nm} modes");
                    }
                    assert_eq!(bits(&a1s), bits(&b1s), "{ns} stations, {nm} modes, one sum");
                    assert_eq!(bits(&a1s), bits(&a[1]), "one sum as three");
                }
            }
        }
    }

    /// [`SubGrid::jerks`] compiled for AVX (four modes to an operation) gives the scalar
    /// formula's bits, `η⃛ = ḟ − 2σ η̈ − ω² η̇` with ḟ = (f₁ − f₀)/h, at both ends, for 1–11
    /// modes. (Skipped without AVX.)
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn avx_jerks_are_the_scalar_formula() {
        if !crate::numerics::vex::available() {
            return;
        }
        for nm in 1..12 {
            let vals = |a: f64, b: f64| -> Vec<f64> {
                (0..nm)
                    .map(|j| ((j as f64) * a + b).sin() * (1.0 + j as f64))
                    .collect()
            };
            let (omega, c) = (
                vals(0.0, 1.0)
                    .iter()
                    .map(|x| 3.0 + x.abs() * 40.0)
                    .collect::<Vec<_>>(),
                vals(0.7, 0.3).iter().map(|x| x.abs()).collect::<Vec<_>>(),
            );
            let (q0, v0, a0) = (vals(1.1, 0.2), vals(0.3, 1.7), vals(2.2, 0.9));
            let (q1, v1, a1) = (vals(0.5, 2.2), vals(1.9, 0.1), vals(0.8, 1.4));
            let h = 0.013;
            let mut g = SubGrid::new(nm);
            g.prepare(None, 0.5, (&q0, &v0, &a0), &omega, &c, 0.0);
            g.advance(&q0, &v0);
            g.prepare(Some(h), 0.5, (&q1, &v1, &a1), &omega, &c, 0.0);
            // SAFETY: the processor has AVX (tested above)
            let (j0, j1) = unsafe { g.jerks_avx(h, (&v1, &a1), &omega, &c) }.expect("an interval");
            for n in 0..nm {
                let w2 = omega[n] * omega[n];
                let f0 = a0[n] + c[n] * v0[n] + w2 * q0[n];
                let f1 = a1[n] + c[n] * v1[n] + w2 * q1[n];
                let slope = (f1 - f0) / h;
                let s0 = f0 - c[n] * v0[n] - w2 * q0[n];
                assert_eq!(
                    j0[n].to_bits(),
                    (slope - c[n] * s0 - w2 * v0[n]).to_bits(),
                    "{nm}: {n}"
                );
                assert_eq!(
                    j1[n].to_bits(),
                    (slope - c[n] * a1[n] - w2 * v1[n]).to_bits(),
                    "{nm}: {n}"
                );
            }
        }
    }

    /// The closed form of one mode against the damped oscillator's own solution under a
    /// linear load, written here (RK4 at 1e-6 of the interval): ζ = 0.02, ω = 300 rad/s over
    /// 10 ms (ωh = 3, far beyond the Hermite), values and rates at every point to 1e-9 of
    /// the amplitude (RK4's error at ωh/10⁴ per step is ~1e-17 per step).
    #[test]
    fn one_mode_matches_the_oscillator() {
        let (w, z, h) = (300.0f64, 0.02, 0.01);
        let c = 2.0 * z * w;
        let (q0, v0, f0, f1) = (1e-3, 0.4, 50.0, -20.0);
        // the reference: RK4 on η̈ = f(τ) − cη̇ − ω²η
        let rhs = |t: f64, y: [f64; 2]| [y[1], f0 + (f1 - f0) * t / h - c * y[1] - w * w * y[0]];
        let steps = 120_000;
        let dt = h / steps as f64;
        let mut y = [q0, v0];
        let mut reference = vec![y];
        for i in 0..steps {
            let t = i as f64 * dt;
            let k1 = rhs(t, y);
            let k2 = rhs(
                t + dt / 2.0,
                [y[0] + dt / 2.0 * k1[0], y[1] + dt / 2.0 * k1[1]],
            );
            let k3 = rhs(
                t + dt / 2.0,
                [y[0] + dt / 2.0 * k2[0], y[1] + dt / 2.0 * k2[1]],
            );
            let k4 = rhs(t + dt, [y[0] + dt * k3[0], y[1] + dt * k3[1]]);
            for j in 0..2 {
                y[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
            }
            reference.push(y);
        }
        let mut g = SubGrid::new(1);
        let a0 = f0 - c * v0 - w * w * q0;
        g.prepare(None, 0.5, (&[q0], &[v0], &[a0]), &[w], &[c], w);
        g.advance(&[q0], &[v0]);
        let [q1, v1] = y;
        let a1 = f1 - c * v1 - w * w * q1;
        assert!(g.prepare(Some(h), 0.5, (&[q1], &[v1], &[a1]), &[w], &[c], w));
        g.evaluate(h, 0.5, (&[q1], &[v1]), &[w], &[c], w, &[1.0], None, 1);
        assert_eq!(g.parts, 6, "ωh/Θ = 6");
        let amp = q0.hypot(v0 / w);
        for k in 0..=g.parts {
            let r = reference[k * steps / g.parts];
            assert!((g.u[k] - r[0]).abs() < 1e-9 * amp, "η at point {k}");
            assert!((g.ud[k] - r[1]).abs() < 1e-9 * amp * w, "η̇ at point {k}");
        }
    }
}
