//! Responses over a structure's height (issue 11): at every floor of a building (at stations
//! of a cantilever: every tenth of its height and each contact height), the peaks of the
//! displacement relative to the ground, the **absolute** acceleration, the storey drift and the
//! storey force.
//!
//! At every observation the modal accelerations come from the equations of motion
//! (docs/model.md §2.4), `η̈ = −Γ a_g − a v_g − 2ζω η̇ − ω² η + Σ_k c_k F_k`, so that the
//! absolute acceleration `ü + a_g = Σ φ η̈ + a_g` includes each impact's spike (the integrators
//! observe every contact step).
//!
//! The **storey shear** (`shear`) is the force the storey's structure carries, its restoring
//! force without damping forces, the same quantity for every kind (docs/model.md §2.6c): `k_j
//! d_j` of a shear building's storey spring, the Bouc–Wen force `V_j` of a yielding storey, the
//! modes' equivalent static forces `K u = M Φ Ω² η` summed over the floors above for a building
//! given by its modes, and the section shear `−EI w‴ = m Σ_n ω_n² η_n ∫_x^L φ_n dx` of a
//! cantilever. Floors whose modes are those of a chain of storey springs (every shear
//! building, and a `modal` structure built from one) are recognised once, and their storey
//! force is `k_j` times the drift's peak: nothing is added to the time loop. The equilibrium
//! of everything above, `V_j = Σ_{f ≥ j} (F_f − m_f a_f)` (a cantilever's `Σ_{h_k ≥ x} F_k −
//! m ∫_x^L a dx`, [`crate::model::cantilever::Mode::integral_above`]), is the storey force plus the
//! damping forces above: `shear_with_damping`.
//!
//! Displacements, drifts and storey forces (elastic or Bouc–Wen) are refined between
//! observations on the cubic Hermite interpolant, as the contact-height peaks are, and where
//! modes too fast for it (`ω h > 0.5`) ring enough to matter (after a stiff impact), on a
//! sub-grid of each mode's closed form ([`crate::recording::subgrid`]). The absolute
//! accelerations and the equilibrium value are taken at the observations and, where the fast
//! modes ring enough to lift their peaks, on the same sub-grid (each mode's η̈ from its closed
//! form and its equation with the interval's linear load, `Between`); where no mode is too
//! fast for the cubic Hermite, on the Hermite of their values and rates between the
//! observations of a free flight (`between_on_hermite`); inside an impact pulse
//! the observations are the contact sub-steps, and the accelerations and the equilibrium value
//! are also evaluated at the quarters of each sub-step where a level carries force (`pulse`;
//! a law whose force jumps at the onset, Kelvin's, from the acceleration just after the jump).

// Index loops over parallel per-mode slices read like the sums they form.
#![allow(clippy::needless_range_loop)]

mod between;
mod bounds;
mod pulse;
mod station;
#[cfg(test)]
mod tests;

use serde::Serialize;

pub(crate) use bounds::refine;
use station::{At, Saved, Stations, copy_into};

use crate::integrate::StepView;
use crate::model::system::System;
use crate::numerics::hermite::Basis;
use crate::recording::subgrid::DEFAULT_RESOLUTION;
/// Peaks at one floor (station) of one run.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct FloorPeaks {
    /// Height above the base, m.
    pub height: f64,
    /// Peak |u| relative to the ground, m.
    pub displacement: f64,
    /// Peak |ü + a_g|, absolute, m/s².
    pub acceleration: f64,
    /// The time of that peak, s (the observation it was taken at, or the point between two
    /// where the sub-grid found it).
    pub acceleration_time: f64,
    /// Peak |u_j − u_{j−1}| of the storey below (the first relative to the base), m.
    pub drift: f64,
    /// Peak |V| of the storey below: the force its structure carries (its restoring force,
    /// without damping forces; see the module documentation), N.
    pub shear: f64,
    /// Peak |V| of the storey below from the equilibrium of everything above it (inertia and
    /// contact forces): the storey force plus the damping forces above, N.
    pub shear_with_damping: f64,
}

/// Tracks [`FloorPeaks`] of both structures through a run (an addition to the recorder).
#[derive(Debug, Clone)]
pub struct FloorRecorder {
    /// One per structure, in row order.
    stations: Vec<Stations>,
    /// Sampling of the floor history (s) and the next sample's index.
    interval: f64,
    next_sample: usize,
    /// One row of the floor history (scratch).
    row: Vec<f64>,
    /// Modal accelerations at the current observation (scratch).
    accel: Vec<f64>,
    /// The last observation that left structures unobserved (a row's passive ones).
    saved: Saved,
    /// The previous observation, for the accelerations inside an impact pulse.
    last: pulse::Last,
    /// Every station takes the full update at every observation (tests: the skip changes
    /// nothing).
    full: bool,
    /// The resolution Θ of the sub-grid ([`crate::recording::subgrid`]; `None`: the cubic
    /// Hermite between observations only).
    resolution: Option<f64>,
}

impl FloorRecorder {
    /// Stations for both structures of a pair `system`; `contact_heights` are the contact
    /// levels' heights (the levels of `system`, or for a run without contact those of the run
    /// with).
    pub fn new(system: &System, contact_heights: &[f64], interval: f64) -> FloorRecorder {
        FloorRecorder::for_row(
            system,
            contact_heights,
            &vec![0; contact_heights.len()],
            interval,
        )
    }

    /// Stations for every structure of a row `system`: contact level k is at
    /// `contact_heights[k]` between structures `pairs[k]` and `pairs[k] + 1`.
    pub fn for_row(
        system: &System,
        contact_heights: &[f64],
        pairs: &[usize],
        interval: f64,
    ) -> FloorRecorder {
        let mut stations: Vec<Stations> = (system.structures.iter().enumerate())
            .map(|(i, m)| {
                let signs: Vec<f64> = pairs
                    .iter()
                    .map(|&p| match i {
                        _ if i == p => -1.0,
                        _ if i == p + 1 => 1.0,
                        _ => 0.0,
                    })
                    .collect();
                Stations::new(m, contact_heights, &signs, system.modes_of(i).start)
            })
            .collect();
        for (k, st) in system.hysteresis.storeys().iter().enumerate() {
            if let Some(y) = stations[st.structure].yields.get_mut(st.storey) {
                *y = Some(k);
            }
        }
        let cols = 2 * stations.iter().map(|s| s.heights.len()).sum::<usize>();
        FloorRecorder {
            stations,
            interval,
            next_sample: 0,
            row: vec![0.0; cols],
            accel: vec![0.0; system.len()],
            saved: Saved::default(),
            last: pulse::Last::default(),
            full: false,
            resolution: Some(DEFAULT_RESOLUTION),
        }
    }

    /// The resolution Θ of the peaks between observations: modes with `ω h > Θ` are followed
    /// on a sub-grid of their closed forms with parts `≤ Θ/ω_max`
    /// ([`crate::recording::subgrid`]); `None`: the cubic Hermite only.
    pub fn with_resolution(mut self, resolution: Option<f64>) -> FloorRecorder {
        self.resolution = resolution;
        self
    }

    /// The heights of the stations of every structure (m, lowest first), in the order of
    /// [`FloorRecorder::columns`].
    pub fn station_heights(&self) -> Vec<&[f64]> {
        self.stations.iter().map(|s| s.heights.as_slice()).collect()
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
        sink: Option<&mut (dyn crate::recording::history::HistorySink + '_)>,
    ) {
        self.observe_part(system, s, sink, None);
    }

    /// [`FloorRecorder::observe`] of a row's contact step that carried the structures
    /// `stepped.active` only (`None`: every structure). A passive structure moved in exact
    /// free flight: it is observed at the grid points (`stepped.grid`) and wherever a history
    /// sample is due, so that its peaks between them come from the cubic Hermite interpolant
    /// over the free flight, as a pair's free flight has them; one that a step carries again,
    /// or whose history sample falls inside the interval since the last observation, is first
    /// observed at the last observation it skipped ([`Saved`]: the samples are then
    /// interpolated over the same interval as every structure's). Its peak accelerations are
    /// sampled where it is observed.
    pub(crate) fn observe_part(
        &mut self,
        system: &System,
        s: &StepView,
        sink: Option<&mut (dyn crate::recording::history::HistorySink + '_)>,
        stepped: Option<&crate::integrate::Stepped>,
    ) {
        let n = system.len();
        let (tau, eps) = (
            self.next_sample as f64 * self.interval,
            1e-9 * self.interval,
        );
        let due = sink.is_some() && tau <= s.t + eps;
        // (a sample inside the interval since the last observation: every structure is
        // interpolated over that interval, as history.csv's sampler does)
        let inside = due && tau < s.t - eps;
        let active = stepped.filter(|p| !p.grid && !due).map(|p| p.active);
        let (full, resolution) = (self.full, self.resolution);
        if self.saved.valid {
            let sv = &self.saved;
            let at = At {
                t: sv.t,
                q: &sv.q,
                v: &sv.v,
                accel: &sv.accel,
                ag: sv.ag,
                levels: &sv.levels,
                z: &sv.z,
            };
            for (i, st) in self.stations.iter_mut().enumerate() {
                let carried = stepped.is_some_and(|p| p.active[i]);
                if (carried || inside) && st.last_t.is_some_and(|t| t < sv.t) {
                    st.observe(system, &at, full, resolution);
                    st.hold_now();
                }
            }
        }
        let (ag, vg) = system.ground.accel_velocity(s.t);
        {
            // (every slice cut to the modes once: no bounds check per mode)
            let (la, lv) = (&system.ground_load()[..n], &system.air_load()[..n]);
            let (damp, w) = (&system.damping_coefficients()[..n], &system.omega()[..n]);
            let (q, v, accel) = (&s.q[..n], &s.v[..n], &mut self.accel[..n]);
            for j in 0..n {
                accel[j] = la[j] * ag + lv[j] * vg - damp[j] * v[j] - w[j] * w[j] * q[j];
            }
            for (k, st) in s.levels.iter().enumerate() {
                if st.force != 0.0 {
                    for (a, c) in accel.iter_mut().zip(system.coupling(k)) {
                        *a += c * st.force;
                    }
                }
            }
            // yielding storeys: the pseudo-forces −e_s ΔV_s (crate::model::hysteresis)
            let hy = &system.hysteresis;
            for (k, st) in hy.storeys().iter().enumerate() {
                let (d, _) = hy.drift(k, s.q, s.v);
                let z = s.z.get(k).copied().unwrap_or(0.0);
                let f = st.pseudo_force(d, z);
                if f != 0.0 {
                    for (a, e) in self.accel.iter_mut().zip(hy.row(k)) {
                        *a -= e * f;
                    }
                }
            }
        }
        // the accelerations inside an impact pulse since the previous observation (of the
        // stations last observed there)
        // (with the sub-grid's resolution: `None` keeps the observations alone)
        if self.resolution.is_some() {
            self.last.pulse(system, s, &self.accel, &mut self.stations);
        }
        let at = At {
            t: s.t,
            q: s.q,
            v: s.v,
            accel: &self.accel,
            ag,
            levels: s.levels,
            z: s.z,
        };
        for (i, st) in self.stations.iter_mut().enumerate() {
            st.fresh = active.is_none_or(|a| a[i]);
            if st.fresh {
                st.observe(system, &at, full, resolution);
            }
        }
        match active {
            // (a copy of this observation for the structures it skipped)
            Some(_) => {
                let sv = &mut self.saved;
                sv.valid = true;
                (sv.t, sv.ag) = (s.t, ag);
                copy_into(&mut sv.q, s.q);
                copy_into(&mut sv.v, s.v);
                copy_into(&mut sv.accel, &self.accel);
                sv.levels.clear();
                sv.levels.extend_from_slice(s.levels);
                copy_into(&mut sv.z, s.z);
            }
            None => self.saved.valid = false,
        }
        // (a partial observation of a row too: every mode is carried to each step's end, and
        // only the stations observed at both ends are raised)
        self.last.keep(s, &self.accel);
        if let Some(sink) = sink {
            self.emit(s.t, sink);
        }
    }

    /// The floor history samples due by time `t` (the current observation; `h` since the
    /// previous one).
    fn emit(&mut self, t: f64, sink: &mut (dyn crate::recording::history::HistorySink + '_)) {
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
            let mut k = 0;
            // (every structure was observed now, a sample being due; each over its own
            // interval: a row's passive ones since their last observation)
            let mut last: Option<(Option<f64>, f64, Basis)> = None;
            for st in &mut self.stations {
                let h = st.h;
                let (hh, basis) = match last {
                    Some((lh, hh, b)) if lh == h => (hh, b),
                    _ => {
                        let th = match h {
                            Some(h) if h > 0.0 && !here => ((tau - (t - h)) / h).clamp(0.0, 1.0),
                            _ => 1.0,
                        };
                        // h01 = 3θ² − 2θ³ was written −2θ³ + 3θ² here: the same sum (addition
                        // commutes exactly), so the rows are unchanged bit for bit
                        let b = Basis::at(th);
                        let hh = h.unwrap_or(0.0);
                        last = Some((h, hh, b));
                        (hh, b)
                    }
                };
                for f in 0..st.heights.len() {
                    let ((u0, d0), (u1, d1)) = (st.before[f], st.prev[f]);
                    self.row[k] = basis.combine(u0, d0, u1, d1, hh);
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
        // this observation's accelerations count towards the next sample (of the structures
        // it saw)
        for st in &mut self.stations {
            if st.fresh {
                st.hold_now();
            }
        }
    }

    /// The peaks of every structure (row order), lowest station first.
    pub fn finish(self) -> Vec<Vec<FloorPeaks>> {
        self.stations.into_iter().map(Stations::finish).collect()
    }
}
