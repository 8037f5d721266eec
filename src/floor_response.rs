//! Responses over a structure's height (issue 11): at every floor of a building (at stations
//! of a cantilever: every tenth of its height and each contact height), the peaks of the
//! displacement relative to the ground, the **absolute** acceleration, the storey drift and the
//! storey shear.
//!
//! At every observation the modal accelerations come from the equations of motion
//! (docs/model.md §2.4), `η̈ = −Γ a_g − a v_g − 2ζω η̇ − ω² η + Σ_k c_k F_k`, so that the
//! absolute acceleration `ü + a_g = Σ φ η̈ + a_g` includes each impact's spike (the integrators
//! observe every contact step). The storey shear is what the storey carries (spring and
//! damper together), from the equilibrium of everything above it: `V_j = Σ_{f ≥ j} (F_f − m_f
//! a_f)`, with F the contact forces on the floors above (for a cantilever, `V(x) = Σ_{h_k ≥ x}
//! F_k − m ∫_x^L a dx`, with the modes' integrals in closed form,
//! [`crate::cantilever::Mode::integral_above`]). Displacements and drifts are refined between
//! observations on the cubic Hermite interpolant, as the contact-height peaks are;
//! accelerations and shears are taken at the observations.

// Index loops over parallel per-mode slices read like the sums they form.
#![allow(clippy::needless_range_loop)]

use serde::Serialize;

use crate::integrate::StepView;
use crate::integrate::linear::hermite_abs_max;
use crate::modal::{ModalModel, Shapes};
use crate::system::System;

/// The largest of the cubic Hermite slope basis functions θ(1−θ)², θ²(1−θ) on [0, 1].
const HERMITE_REACH: f64 = 4.0 / 27.0;

/// `peak = max(peak, x)` as a plain comparison (no NaN handling: a NaN state has already
/// stopped the run as diverged).
#[inline(always)]
fn raise(peak: &mut f64, x: f64) {
    if x > *peak {
        *peak = x;
    }
}

/// Peaks at one floor (station) of one run.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct FloorPeaks {
    /// Height above the base, m.
    pub height: f64,
    /// Peak |u| relative to the ground, m.
    pub displacement: f64,
    /// Peak |ü + a_g|, absolute, m/s².
    pub acceleration: f64,
    /// The time of that peak, s (the observation it was taken at).
    pub acceleration_time: f64,
    /// Peak |u_j − u_{j−1}| of the storey below (the first relative to the base), m.
    pub drift: f64,
    /// Peak |V| of the storey below, N.
    pub shear: f64,
}

/// How the shear of one structure is formed.
#[derive(Debug, Clone)]
enum Shear {
    /// Lumped floor masses, kg.
    Lumped(Vec<f64>),
    /// A continuous cantilever: mass per length (kg/m) and, per station, `∫_x^L φ_n dx` of
    /// every mode (m·kg^−½) and `L − x` (m).
    Continuous {
        m: f64,
        /// `[station·modes + n]`.
        integral: Vec<f64>,
        above: Vec<f64>,
    },
}

/// The stations of one structure.
#[derive(Debug, Clone)]
struct Stations {
    heights: Vec<f64>,
    /// Modes of the structure.
    modes: usize,
    /// φ_n at every station: `[station·modes + n]`.
    phi: Vec<f64>,
    shear: Shear,
    /// Which contact levels load the part above each station: `[station·levels + k]` (for
    /// floors: the level acts at that very floor).
    above: Vec<bool>,
    levels: usize,
    /// Offset of this structure's modes in the system, and the sign of the contact force on it.
    offset: usize,
    sign: f64,
    /// (u, u̇) at every station at the previous observation, and at the one before (for
    /// the samples between them).
    prev: Vec<(f64, f64)>,
    before: Vec<(f64, f64)>,
    /// Absolute acceleration at the current observation, and the one of largest size since
    /// the last sample (signed).
    abs_now: Vec<f64>,
    hold: Vec<f64>,
    peaks: Vec<FloorPeaks>,
}

impl Stations {
    fn new(m: &ModalModel, contact_heights: &[f64], offset: usize, sign: f64) -> Stations {
        let (heights, shear) = match &m.shapes {
            Shapes::Floors {
                heights, masses, ..
            } => (heights.clone(), Shear::Lumped(masses.clone())),
            Shapes::Cantilever(modes) => {
                let l = m.length;
                let mut h: Vec<f64> = (1..=10).map(|k| l * k as f64 / 10.0).collect();
                h.extend(
                    contact_heights
                        .iter()
                        .copied()
                        .filter(|&x| x > 0.0 && x <= l),
                );
                h.sort_by(f64::total_cmp);
                h.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * l);
                let scale = l / m.mass.sqrt(); // ∫ φ dx = L ∫ y dξ / √(mL)
                let integral = h
                    .iter()
                    .flat_map(|&x| modes.iter().map(move |md| scale * md.integral_above(x / l)))
                    .collect();
                let above = h.iter().map(|&x| l - x).collect();
                (
                    h,
                    Shear::Continuous {
                        m: m.mass / l,
                        integral,
                        above,
                    },
                )
            }
        };
        let phi = heights.iter().flat_map(|&x| m.shapes_at(x)).collect();
        let lumped = matches!(shear, Shear::Lumped(_));
        let above = heights
            .iter()
            .flat_map(|&x| {
                contact_heights.iter().map(move |&hk| {
                    if lumped {
                        crate::building::same_height(hk, x)
                    } else {
                        hk >= x || crate::building::same_height(hk, x)
                    }
                })
            })
            .collect();
        let n = heights.len();
        Stations {
            peaks: heights
                .iter()
                .map(|&height| FloorPeaks {
                    height,
                    ..FloorPeaks::default()
                })
                .collect(),
            heights,
            modes: m.len(),
            phi,
            shear,
            above,
            levels: contact_heights.len(),
            offset,
            sign,
            prev: vec![(0.0, 0.0); n],
            before: vec![(0.0, 0.0); n],
            abs_now: vec![0.0; n],
            hold: vec![0.0; n],
        }
    }
}

/// Tracks [`FloorPeaks`] of both structures through a run (an addition to the recorder).
#[derive(Debug, Clone)]
pub struct FloorRecorder {
    stations: [Stations; 2],
    /// Sampling of the floor history (s) and the next sample's index.
    interval: f64,
    next_sample: usize,
    /// One row of the floor history (scratch).
    row: Vec<f64>,
    /// Modal accelerations at the current observation (scratch).
    accel: Vec<f64>,
    /// Absolute accelerations at the stations of the structure being processed (scratch).
    abs: Vec<f64>,
    last_t: Option<f64>,
}

impl FloorRecorder {
    /// Stations for both structures of `system`; `contact_heights` are the contact levels'
    /// heights (the levels of `system`, or for a run without contact those of the run with).
    pub fn new(system: &System, contact_heights: &[f64], interval: f64) -> FloorRecorder {
        let [s1, s2] = &system.structures;
        let n1 = system.n1();
        let stations = [
            Stations::new(s1, contact_heights, 0, -1.0),
            Stations::new(s2, contact_heights, n1, 1.0),
        ];
        let most = stations.iter().map(|s| s.heights.len()).max().unwrap_or(0);
        let cols = 2 * stations.iter().map(|s| s.heights.len()).sum::<usize>();
        FloorRecorder {
            stations,
            interval,
            next_sample: 0,
            row: vec![0.0; cols],
            accel: vec![0.0; system.len()],
            abs: vec![0.0; most],
            last_t: None,
        }
    }

    /// The heights of the stations of structure 1 and 2 (m, lowest first), in the order of
    /// [`FloorRecorder::columns`].
    pub fn station_heights(&self) -> [&[f64]; 2] {
        [&self.stations[0].heights, &self.stations[1].heights]
    }

    /// The names of a floor history row's values: for structure i and every station (height
    /// h, m), `w{i}_{h}` (displacement, m) and `a{i}_{h}` (absolute acceleration, m/s²).
    pub fn columns(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (i, st) in self.stations.iter().enumerate() {
            for h in &st.heights {
                out.push(format!("w{}_{h}", i + 1));
                out.push(format!("a{}_{h}", i + 1));
            }
        }
        out
    }

    /// Record one observation; with a `sink`, every floor history sample due by then (times
    /// `k·interval`, as history.csv): displacements on the cubic Hermite interpolant between
    /// observations, and for the acceleration the value of largest size since the previous
    /// sample (so that an impact's spike shows at the sample after it, at its true size).
    pub fn observe(
        &mut self,
        system: &System,
        s: &StepView,
        sink: Option<&mut (dyn crate::recorder::HistorySink + '_)>,
    ) {
        let n = system.len();
        let (ag, vg) = system.ground.accel_velocity(s.t);
        {
            let (la, lv) = (system.ground_load(), system.air_load());
            let (damp, w) = (system.damping_coefficients(), system.omega());
            for j in 0..n {
                self.accel[j] = la[j] * ag + lv[j] * vg - damp[j] * s.v[j] - w[j] * w[j] * s.q[j];
            }
            for (k, st) in s.levels.iter().enumerate() {
                if st.force != 0.0 {
                    for (a, c) in self.accel.iter_mut().zip(system.coupling(k)) {
                        *a += c * st.force;
                    }
                }
            }
            // yielding storeys: the pseudo-forces −e_s ΔV_s (crate::hysteresis)
            let hy = &system.hysteresis;
            for (k, st) in hy.storeys().iter().enumerate() {
                let (d, _) = hy.drift(k, s.q, s.v);
                let f = st.pseudo_force(d, s.z.get(k).copied().unwrap_or(0.0));
                if f != 0.0 {
                    for (a, e) in self.accel.iter_mut().zip(hy.row(k)) {
                        *a -= e * f;
                    }
                }
            }
        }
        let h = self.last_t.map(|t0| s.t - t0);
        for st in &mut self.stations {
            let nm = st.modes;
            let ns = st.heights.len();
            let (q, v, a) = (
                &s.q[st.offset..st.offset + nm],
                &s.v[st.offset..st.offset + nm],
                &self.accel[st.offset..st.offset + nm],
            );
            let (phi, abs) = (&st.phi[..ns * nm], &mut self.abs[..ns]);
            let (mut below, mut below_rate, mut below_prev, mut below_prev_rate) =
                (0.0, 0.0, 0.0, 0.0);
            for f in 0..ns {
                let row = &phi[f * nm..(f + 1) * nm];
                let (mut u, mut ud, mut ua) = (0.0, 0.0, 0.0);
                for j in 0..nm {
                    u += row[j] * q[j];
                    ud += row[j] * v[j];
                    ua += row[j] * a[j];
                }
                let (up, udp) = st.prev[f];
                let p = &mut st.peaks[f];
                let (d, dd, dp, ddp) = (
                    u - below,
                    ud - below_rate,
                    up - below_prev,
                    udp - below_prev_rate,
                );
                raise(&mut p.displacement, u.abs());
                raise(&mut p.drift, d.abs());
                if let Some(h) = h.filter(|h| *h > 0.0) {
                    // refine between observations on the cubic Hermite interpolant (both
                    // signs), only where it could beat the peak: the interpolant lies within
                    // (4/27)·h·(|ẏ₀| + |ẏ₁|) of the larger end value (its slope basis
                    // functions are at most 4/27 in size)
                    if up.abs().max(u.abs()) + HERMITE_REACH * h * (udp.abs() + ud.abs())
                        > p.displacement
                    {
                        p.displacement = p.displacement.max(hermite_abs_max(up, udp, u, ud, h));
                    }
                    if dp.abs().max(d.abs()) + HERMITE_REACH * h * (ddp.abs() + dd.abs()) > p.drift
                    {
                        p.drift = p.drift.max(hermite_abs_max(dp, ddp, d, dd, h));
                    }
                }
                abs[f] = ua + ag;
                if abs[f].abs() > p.acceleration {
                    p.acceleration = abs[f].abs();
                    p.acceleration_time = s.t;
                }
                st.abs_now[f] = abs[f];
                st.before[f] = st.prev[f];
                st.prev[f] = (u, ud);
                (below, below_rate, below_prev, below_prev_rate) = (u, ud, up, udp);
            }
            // storey shear from the equilibrium of what is above
            let nl = st.levels.min(s.levels.len());
            match &st.shear {
                Shear::Lumped(masses) => {
                    let mut v_above = 0.0;
                    for f in (0..ns).rev() {
                        v_above -= masses[f] * abs[f];
                        // contact forces acting at this floor
                        for k in 0..nl {
                            if st.above[f * st.levels + k] {
                                v_above += st.sign * s.levels[k].force;
                            }
                        }
                        raise(&mut st.peaks[f].shear, v_above.abs());
                    }
                }
                Shear::Continuous { m, integral, above } => {
                    let integral = &integral[..ns * nm];
                    for f in 0..ns {
                        let row = &integral[f * nm..(f + 1) * nm];
                        let mut inertia = ag * above[f];
                        for j in 0..nm {
                            inertia += row[j] * a[j];
                        }
                        let mut v_sec = -m * inertia;
                        for k in 0..nl {
                            if st.above[f * st.levels + k] {
                                v_sec += st.sign * s.levels[k].force;
                            }
                        }
                        raise(&mut st.peaks[f].shear, v_sec.abs());
                    }
                }
            }
        }
        if let Some(sink) = sink {
            self.emit(s.t, h, sink);
        }
        self.last_t = Some(s.t);
    }

    /// The floor history samples due by time `t` (the current observation; `h` since the
    /// previous one).
    fn emit(&mut self, t: f64, h: Option<f64>, sink: &mut (dyn crate::recorder::HistorySink + '_)) {
        let eps = 1e-9 * self.interval;
        let mut consumed = false;
        loop {
            let tau = self.next_sample as f64 * self.interval;
            if tau > t + eps {
                break;
            }
            // a sample strictly before this observation holds the accelerations up to the
            // previous one; one at this observation includes it
            let here = tau >= t - eps;
            let th = match h {
                Some(h) if h > 0.0 && !here => ((tau - (t - h)) / h).clamp(0.0, 1.0),
                _ => 1.0,
            };
            let hh = h.unwrap_or(0.0);
            let (t2, t3) = (th * th, th * th * th);
            let (h00, h10, h01, h11) = (
                2.0 * t3 - 3.0 * t2 + 1.0,
                t3 - 2.0 * t2 + th,
                -2.0 * t3 + 3.0 * t2,
                t3 - t2,
            );
            let mut k = 0;
            for st in &mut self.stations {
                for f in 0..st.heights.len() {
                    let ((u0, d0), (u1, d1)) = (st.before[f], st.prev[f]);
                    self.row[k] = h00 * u0 + h10 * hh * d0 + h01 * u1 + h11 * hh * d1;
                    if here && st.abs_now[f].abs() > st.hold[f].abs() {
                        st.hold[f] = st.abs_now[f];
                    }
                    self.row[k + 1] = st.hold[f];
                    st.hold[f] = 0.0;
                    k += 2;
                }
            }
            sink.floor_row(tau, &self.row);
            self.next_sample += 1;
            consumed |= here;
        }
        if consumed {
            return;
        }
        // this observation's accelerations count towards the next sample
        for st in &mut self.stations {
            for f in 0..st.heights.len() {
                if st.abs_now[f].abs() > st.hold[f].abs() {
                    st.hold[f] = st.abs_now[f];
                }
            }
        }
    }

    /// The peaks of structure 1 and 2, lowest station first.
    pub fn finish(self) -> [Vec<FloorPeaks>; 2] {
        let [a, b] = self.stations;
        [a.peaks, b.peaks]
    }
}
