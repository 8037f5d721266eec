//! What a run records of its yielding storeys (issue 16): per Bouc–Wen storey the peak drift
//! and ductility, the storey force, the residual drift and the dissipated (hysteretic) energy,
//! and the storey force against the drift sampled for the hysteresis-loop figure.
//!
//! The dissipated energy is `E_h = W + ½(1 − α)k(d² − d_y² z²) − (the same at the start)`, W the
//! pseudo-force's work the integrator tallies per storey with its own stage weights (see
//! [`crate::model::hysteresis`] for the definition and its source): the energy balance and E_h come
//! from the same integral.

use serde::Serialize;

use crate::integrate::StepView;
use crate::model::system::System;
use crate::recording::floor_response::refine;

/// Most (drift, force) pairs kept per storey for the loop figure; beyond, every other one is
/// dropped and the sampling interval doubled.
pub const MAX_LOOP_POINTS: usize = 8_000;

/// The record of one yielding storey over a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StoreyRecord {
    /// Structure (0 or 1).
    pub structure: usize,
    /// Storey, 0 = the lowest.
    pub storey: usize,
    /// Yield drift d_y, m.
    pub yield_drift: f64,
    /// Peak |drift|, m (refined between observations on the cubic Hermite interpolant).
    pub peak_drift: f64,
    /// Peak |V| of the Bouc–Wen storey force, N (refined between observations on the cubic
    /// Hermite interpolant of V and dV/dt).
    pub peak_force: f64,
    /// Signed drift at the end of the run, m.
    pub residual_drift: f64,
    /// Energy dissipated by the storey's hysteresis, J.
    pub hysteretic_energy: f64,
    /// (drift m, storey force N) pairs, for the loop figure.
    #[serde(skip)]
    pub loop_points: Vec<[f64; 2]>,
}

impl StoreyRecord {
    /// Peak ductility demand, peak |drift| / d_y.
    pub fn peak_ductility(&self) -> f64 {
        self.peak_drift / self.yield_drift
    }
}

/// Tracks every yielding storey of a system through a run.
#[derive(Debug, Clone)]
pub struct StoreyTracker {
    records: Vec<StoreyRecord>,
    /// (d, ḋ) at the previous observation.
    prev: Vec<(f64, f64)>,
    /// (V, dV/dt) at the previous observation.
    prev_force: Vec<(f64, f64)>,
    /// `½(1 − α)k(d² − d_y²z²)` at t = 0.
    excess0: Vec<f64>,
    last_t: Option<f64>,
    interval: f64,
    next_loop_t: f64,
}

impl StoreyTracker {
    /// For the yielding storeys of `system` (None when it has none); loop points every
    /// `interval` s at most over a run of `duration` s (their storage reserved here: the time
    /// loop does not allocate).
    pub fn new(system: &System, interval: f64, duration: f64) -> Option<StoreyTracker> {
        let h = &system.hysteresis;
        if h.is_empty() {
            return None;
        }
        let points = ((duration / interval).ceil() as usize + 2).min(MAX_LOOP_POINTS + 1);
        let records = h
            .storeys()
            .iter()
            .map(|s| StoreyRecord {
                structure: s.structure,
                storey: s.storey,
                yield_drift: s.dy,
                peak_drift: 0.0,
                peak_force: 0.0,
                residual_drift: 0.0,
                hysteretic_energy: 0.0,
                loop_points: Vec::with_capacity(points),
            })
            .collect();
        Some(StoreyTracker {
            records,
            prev: vec![(0.0, 0.0); h.len()],
            prev_force: vec![(0.0, 0.0); h.len()],
            excess0: vec![0.0; h.len()],
            last_t: None,
            interval,
            next_loop_t: 0.0,
        })
    }

    /// Record one observation.
    pub fn observe(&mut self, system: &System, s: &StepView) {
        let hy = &system.hysteresis;
        let h = self.last_t.map(|t0| s.t - t0).filter(|h| *h > 0.0);
        let take_loop = s.t >= self.next_loop_t;
        if take_loop {
            self.next_loop_t = s.t + self.interval;
        }
        for (k, st) in hy.storeys().iter().enumerate() {
            let (d, dd) = hy.drift(k, s.q, s.v);
            let z = s.z.get(k).copied().unwrap_or(0.0);
            let r = &mut self.records[k];
            let (force, rate) = (st.force(d, z), st.force_rate(dd, z));
            r.peak_drift = r.peak_drift.max(d.abs());
            r.peak_force = r.peak_force.max(force.abs());
            if let Some(h) = h {
                // on the cubic Hermite interpolants, where they could beat the peaks
                let (d0, dd0) = self.prev[k];
                refine(&mut r.peak_drift, d0, dd0, d, dd, h);
                let (v0, vd0) = self.prev_force[k];
                refine(&mut r.peak_force, v0, vd0, force, rate, h);
            }
            self.prev_force[k] = (force, rate);
            let excess = st.excess(d, z);
            if self.last_t.is_none() {
                self.excess0[k] = excess;
            }
            let work = s.tally.storey_work.get(k).copied().unwrap_or(0.0);
            r.hysteretic_energy = work + excess - self.excess0[k];
            r.residual_drift = d;
            self.prev[k] = (d, dd);
            if take_loop {
                if r.loop_points.len() >= MAX_LOOP_POINTS {
                    // keep every other point, in place
                    let mut i = 0;
                    r.loop_points.retain(|_| {
                        i += 1;
                        i % 2 == 1
                    });
                    if k + 1 == hy.len() {
                        self.interval *= 2.0;
                    }
                }
                r.loop_points.push([d, force]);
            }
        }
        self.last_t = Some(s.t);
    }

    /// The records, in the order of the system's storeys.
    pub fn finish(self) -> Vec<StoreyRecord> {
        self.records
    }
}
