//! The absolute acceleration and the equilibrium shear of one structure's stations between two
//! observations ([`Between`]: what they need; docs/model.md §2.6c): on the sub-grid of the modes'
//! closed forms where fast modes ring ([`between_on_subgrid`]), on the cubic Hermite of their
//! values and rates in a free flight where none does ([`between_on_hermite`]). Functions over
//! the slices they are given: the stations (`super::station`) call them.

// Index loops over parallel per-mode slices read like the sums they form.
#![allow(clippy::needless_range_loop)]

use super::FloorPeaks;
use super::bounds::{HERMITE_REACH, raise, reach, refine};
use crate::numerics::hermite::{hermite_bound, hermite_max};
use crate::recording::subgrid::SubGrid;

/// What the absolute acceleration and the equilibrium shear (`shear_with_damping`) of one
/// structure need between observations where fast modes ring (docs/model.md §2.6c): per
/// station `a = Σ φ_n η̈_n + a_g` and `V = C − Σ E_n η̈_n − M a_g`, with the contact forces
/// above `C` and the ground's `a_g` linear over the interval (as the modal loads have them).
#[derive(Debug, Clone)]
pub(super) struct Between {
    /// `E_n` per station, kg·kg^−½ (`Σ_{g ≥ f} m_g φ_n(g)` of floors, `m ∫_x^L φ_n dx` of a
    /// cantilever), `[n·stations + station]`, and the mass above M, kg.
    pub(super) eq_rows: Vec<f64>,
    pub(super) mass_above: Vec<f64>,
    /// `|φ_n| ω_n²` and `|E_n| ω_n²` (`[n·stations + station]`): the weights of the modes'
    /// ringing `|R̈_n| ≤ ω_n² ρ_n` ([`crate::recording::subgrid`]), and per mode their
    /// largest over the stations.
    pub(super) abs_acc: Vec<f64>,
    pub(super) abs_eq: Vec<f64>,
    pub(super) cmax: [Vec<f64>; 2],
    /// At the previous observation: per station the acceleration, the equilibrium shear and
    /// the contact forces above, and the ground's acceleration (m/s²).
    pub(super) prev_acc: Vec<f64>,
    pub(super) prev_eq: Vec<f64>,
    pub(super) prev_contact: Vec<f64>,
    pub(super) prev_ag: f64,
    /// At the current observation (scratch): the equilibrium shear and the contact forces
    /// above, per station.
    pub(super) eq_now: Vec<f64>,
    pub(super) contact_now: Vec<f64>,
    /// The fast modes' ringing of both quantities per station (`[k·stations + station]`),
    /// the stations that take the sub-grid, and the values and rates at its points (scratch).
    pub(super) rings: Vec<f64>,
    pub(super) flagged: Vec<usize>,
    pub(super) y: Vec<f64>,
    pub(super) yd: Vec<f64>,
    /// Whether a contact level of this structure carried force at the previous observation.
    pub(super) prev_loaded: bool,
    /// Per mode the largest |φ_n| and |E_n| over the stations (the bound of
    /// [`between_on_hermite`]).
    pub(super) coeff_max: [Vec<f64>; 2],
    /// Per station `1 + Σ_n φ_n l_n` then `M + Σ_n E_n l_n` (`l_n` the modes' ground loads,
    /// kg^½: the ground's jerk's weight in ȧ and V̇ beyond the modes'), filled at the first
    /// use (the ground loads are the system's).
    pub(super) ground_gain: Vec<f64>,
}

impl Between {
    /// What one structure's `ns` stations need between observations, from its `nm` modes'
    /// values at the stations `phi`, their equilibrium rows `eq_rows` and the masses above
    /// `mass_above` (see the fields), and the modes' ω (1/s).
    pub(super) fn new(
        phi: &[f64],
        (eq_rows, mass_above): (Vec<f64>, Vec<f64>),
        omega: &[f64],
        (ns, nm): (usize, usize),
    ) -> Between {
        // per mode, the largest over the stations
        let largest = |x: &[f64]| -> Vec<f64> {
            (0..nm)
                .map(|n| {
                    x.get(n * ns..(n + 1) * ns)
                        .map_or(0.0, |c| c.iter().fold(0.0, |a: f64, &b| a.max(b)))
                })
                .collect()
        };
        let weigh = |x: &[f64]| -> Vec<f64> {
            (0..nm)
                .flat_map(|n| (0..ns).map(move |f| (x[n * ns + f] * omega[n] * omega[n]).abs()))
                .collect()
        };
        let (abs_acc, abs_eq) = (weigh(phi), weigh(&eq_rows));
        let abs_of = |x: &[f64]| -> Vec<f64> { x.iter().map(|x| x.abs()).collect() };
        let coeff_max = [largest(&abs_of(phi)), largest(&abs_of(&eq_rows))];
        Between {
            cmax: [largest(&abs_acc), largest(&abs_eq)],
            abs_acc,
            abs_eq,
            eq_rows,
            mass_above,
            prev_acc: vec![0.0; ns],
            prev_eq: vec![0.0; ns],
            prev_contact: vec![0.0; ns],
            prev_ag: 0.0,
            eq_now: vec![0.0; ns],
            contact_now: vec![0.0; ns],
            rings: vec![0.0; 6 * ns],
            flagged: Vec::with_capacity(ns),
            y: Vec::new(),
            yd: Vec::new(),
            prev_loaded: false,
            coeff_max,
            ground_gain: Vec::new(),
        }
    }

    /// Fill [`Between::ground_gain`] once per run from the modes' ground loads `la` (kg^½) and
    /// the stations' values `phi` (the ground loads are the system's).
    pub(super) fn fill_ground_gain(&mut self, phi: &[f64], la: &[f64], (ns, nm): (usize, usize)) {
        if !self.ground_gain.is_empty() {
            return;
        }
        for (c, base) in [(phi, 1.0), (&self.eq_rows[..], f64::NAN)] {
            for f in 0..ns {
                let start = if base.is_nan() {
                    self.mass_above[f]
                } else {
                    base
                };
                let g = (0..nm).fold(start, |g, n| g + c[n * ns + f] * la[n]);
                self.ground_gain.push(g);
            }
        }
    }
}

/// The absolute accelerations and the equilibrium shears of the stations that need them
/// (`bt.flagged`) between the observations at `t − h` and `t`, on a sub-grid of the
/// modes' closed forms with parts `≤ theta/ω` of the fastest mode whose ringing matters
/// ([`SubGrid::resolved_omega_for`]): at its points `a = Σ φ_n η̈_n + a_g` and `V = C − Σ E_n
/// η̈_n − M a_g` with their rates (η⃛ from the modes' equations, `C` and `a_g` linear between
/// their values `(ag0, ag1)` at both ends), refined on each part's cubic Hermite. The
/// interval's largest |a| (signed) also counts towards the next floor history sample.
pub(super) fn between_on_subgrid(
    (grid, bt): (&mut SubGrid, &mut Between),
    (peaks, hold, abs_now, phi): (&mut [FloorPeaks], &mut [f64], &[f64], &[f64]),
    (t, h, theta): (f64, f64, f64),
    (q, v): (&[f64], &[f64]),
    (omega, damp): (&[f64], &[f64]),
    (ag0, ag1): (f64, f64),
) {
    let ns = peaks.len();
    let largest = |x: fn(&FloorPeaks) -> f64| -> f64 { peaks.iter().map(x).fold(0.0, f64::max) };
    let peak = [
        largest(|p| p.acceleration),
        largest(|p| p.shear_with_damping),
    ];
    let resolve = grid.resolved_omega_for(omega, &[&bt.cmax[0], &bt.cmax[1]], &peak);
    // the modes only (no station: the displacements are not needed here)
    grid.evaluate(h, theta, (q, v), omega, damp, resolve, phi, None, 0);
    grid.accelerations(h, omega, damp);
    let g = &*grid;
    let (parts, dl, t0) = (g.parts, g.delta, t - h);
    let (y, yd) = (&mut bt.y, &mut bt.yd);
    y.resize(parts + 1, 0.0);
    yd.resize(parts + 1, 0.0);
    let sg = (ag1 - ag0) / h;
    for &f in &bt.flagged {
        let p = &mut peaks[f];
        // the absolute acceleration: its signed largest over the interval, and where
        g.station_accelerations(phi, ns, f, y, yd);
        for k in 0..=parts {
            y[k] += ag0 + sg * (k as f64 * dl);
            yd[k] += sg;
        }
        let (mut top, mut when) = (abs_now[f], t);
        for k in 0..parts {
            if reach(y[k], yd[k], y[k + 1], yd[k + 1], dl) > top.abs() {
                let (hi, th_hi) = hermite_max(y[k], yd[k], y[k + 1], yd[k + 1], dl);
                let (lo, th_lo) = hermite_max(-y[k], -yd[k], -y[k + 1], -yd[k + 1], dl);
                let t_k = t0 + k as f64 * dl;
                if hi > top.abs() {
                    (top, when) = (hi, t_k + th_hi * dl);
                }
                if lo > top.abs() {
                    (top, when) = (-lo, t_k + th_lo * dl);
                }
            }
        }
        if top.abs() > p.acceleration {
            p.acceleration = top.abs();
            p.acceleration_time = when;
        }
        if top.abs() > hold[f].abs() {
            hold[f] = top;
        }
        // the equilibrium shear: the contact forces above and the ground linear, less the
        // inertia of the modes
        g.station_accelerations(&bt.eq_rows, ns, f, y, yd);
        let (c0, sc, mass) = (
            bt.prev_contact[f],
            (bt.contact_now[f] - bt.prev_contact[f]) / h,
            bt.mass_above[f],
        );
        for k in 0..=parts {
            let tau = k as f64 * dl;
            y[k] = c0 + sc * tau - y[k] - mass * (ag0 + sg * tau);
            yd[k] = sc - yd[k] - mass * sg;
        }
        for k in 0..parts {
            refine(
                &mut p.shear_with_damping,
                y[k],
                yd[k],
                y[k + 1],
                yd[k + 1],
                dl,
            );
        }
    }
}

/// The absolute accelerations and the equilibrium shears of every station between the
/// observations at `t − h` and `t` of an interval where no mode rings too fast for the cubic
/// Hermite (`ω h ≤ Θ` for every mode that rings, [`crate::recording::subgrid`]) and no contact
/// level of the structure carries force at either end: each refined on the cubic Hermite of
/// its values and rates at both ends, the rates `ȧ = Σ φ_n η⃛_n + ȧ_g` and `V̇ = Ċ − Σ E_n η⃛_n
/// − M ȧ_g` from the modes' `jerks` (η⃛ at both ends under the interval's linear forcing,
/// [`SubGrid::jerks`]) with the ground's `a_g` (its value `ag` at `t`) and the contact forces
/// above linear over the interval. The Hermite's error on a mode is `(ω h)⁴/384` of its
/// swing (≤ 1.6e-4 at Θ = 0.5), where the observations alone miss a crest by up to `1 −
/// cos(ω h/2)` (3 % at Θ). Most intervals change no peak: a station's rates are formed only
/// where a bound from the modes' largest coefficients ([`Between::coeff_max`]) can beat its
/// peak, then each sign's [`hermite_bound`] with its own rates decides; an acceleration raised
/// also counts towards the next floor history sample.
#[inline(never)]
pub(super) fn between_on_hermite(
    peaks: (&mut [FloorPeaks], &mut [f64]),
    bt: &Between,
    now: (&[f64], &[f64]),
    jerks: (&[f64], &[f64], &[f64]),
    times: (f64, f64, f64),
) {
    hermite_body(peaks, bt, now, jerks, times);
}

/// [`between_on_hermite`] compiled for AVX (the same IEEE operations in the same order).
/// Safety: the processor has AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
pub(super) unsafe fn between_on_hermite_avx(
    peaks: (&mut [FloorPeaks], &mut [f64]),
    bt: &Between,
    now: (&[f64], &[f64]),
    jerks: (&[f64], &[f64], &[f64]),
    times: (f64, f64, f64),
) {
    hermite_body(peaks, bt, now, jerks, times);
}

#[inline(always)]
fn hermite_body(
    (peaks, hold): (&mut [FloorPeaks], &mut [f64]),
    bt: &Between,
    (abs_now, phi): (&[f64], &[f64]),
    (j0, j1, la): (&[f64], &[f64], &[f64]),
    (t, h, ag): (f64, f64, f64),
) {
    let ns = peaks.len();
    let nm = j0.len();
    let sg = (ag - bt.prev_ag) / h;
    // the largest |rate| of any station's modal part at either end less the ground's jerk
    // (`η⃛_n = ĵ_n + l_n ȧ_g`, l_n the mode's ground load: a record's jerk, large, cancels
    // between the modes and ȧ_g in `ȧ`, and between them and M ȧ_g in `V̇`):
    // Σ_n max_f |c_n(f)| · max(|ĵ_n(0)|, |ĵ_n(h)|); the ground's part per station is
    // `ȧ_g (1 + Σ φ_n l_n)` and `−ȧ_g (M + Σ E_n l_n)` ([`Between::ground_gain`])
    let (mut ra, mut re) = (0.0, 0.0);
    let (cphi, ceq, la) = (&bt.coeff_max[0][..nm], &bt.coeff_max[1][..nm], &la[..nm]);
    for n in 0..nm {
        let (x, y) = ((j0[n] - la[n] * sg).abs(), (j1[n] - la[n] * sg).abs());
        let j = if x > y { x } else { y };
        ra += cphi[n] * j;
        re += ceq[n] * j;
    }
    let (gain_a, gain_v) = bt.ground_gain[..2 * ns].split_at(ns);
    // (both ends' slope terms, 4/27 each: [`reach`] with the rates bounded)
    let slack = 2.0 * HERMITE_REACH * h;
    let t0 = t - h;
    let (prev_acc, prev_eq) = (&bt.prev_acc[..ns], &bt.prev_eq[..ns]);
    let (eq_now, contact_now, prev_contact) = (
        &bt.eq_now[..ns],
        &bt.contact_now[..ns],
        &bt.prev_contact[..ns],
    );
    let (mass_above, eq_rows) = (&bt.mass_above[..ns], &bt.eq_rows[..nm * ns]);
    let rates = |c: &[f64], f: usize| -> (f64, f64) {
        let (mut d0, mut d1) = (0.0, 0.0);
        for n in 0..nm {
            let c = c[n * ns + f];
            d0 += c * j0[n];
            d1 += c * j1[n];
        }
        (d0, d1)
    };
    for f in 0..ns {
        let p = &mut peaks[f];
        let (a0, a1) = (prev_acc[f], abs_now[f]);
        let ends = if a0.abs() > a1.abs() {
            a0.abs()
        } else {
            a1.abs()
        };
        if ends + slack * (ra + (sg * gain_a[f]).abs()) > p.acceleration {
            let (d0, d1) = rates(phi, f);
            let (d0, d1) = (d0 + sg, d1 + sg);
            // each sign's Hermite only where its bound beats the peak (the ends cannot:
            // both were raised at their observations)
            let mut top = (0.0, 0.0);
            if hermite_bound(a0, d0, a1, d1, h) > p.acceleration {
                top = hermite_max(a0, d0, a1, d1, h);
            }
            if hermite_bound(-a0, -d0, -a1, -d1, h) > p.acceleration {
                let (lo, th) = hermite_max(-a0, -d0, -a1, -d1, h);
                if lo > top.0.abs() {
                    top = (-lo, th);
                }
            }
            let (top, th) = top;
            if top.abs() > p.acceleration {
                p.acceleration = top.abs();
                p.acceleration_time = t0 + th * h;
            }
            if top.abs() > hold[f].abs() {
                hold[f] = top;
            }
        }
        // V = C − Σ E_n η̈_n − M a_g, C and a_g linear
        let (v0, v1) = (prev_eq[f], eq_now[f]);
        let ends = if v0.abs() > v1.abs() {
            v0.abs()
        } else {
            v1.abs()
        };
        let sc = (contact_now[f] - prev_contact[f]) / h;
        let mass = mass_above[f];
        let lin = sc - mass * sg;
        if ends + slack * (re + (sc - sg * gain_v[f]).abs()) > p.shear_with_damping {
            let (d0, d1) = rates(eq_rows, f);
            let (d0, d1) = (lin - d0, lin - d1);
            if hermite_bound(v0, d0, v1, d1, h) > p.shear_with_damping {
                raise(&mut p.shear_with_damping, hermite_max(v0, d0, v1, d1, h).0);
            }
            if hermite_bound(-v0, -d0, -v1, -d1, h) > p.shear_with_damping {
                raise(
                    &mut p.shear_with_damping,
                    hermite_max(-v0, -d0, -v1, -d1, h).0,
                );
            }
        }
    }
}
