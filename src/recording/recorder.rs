//! The recorder: what a run keeps ([`RunRecord`]) taken from every integration step — peaks
//! over every step, impact events, a history sampled at the output interval, and the energy
//! balance. The recorder is an [`Observer`]: the integrators do not know it exists.
//!
//! Memory does not grow with the duration: every history sample goes, as it is taken, to an
//! optional [`HistorySink`] (the CSV writer streams it to disk), while the in-memory
//! [`History`] (for figures and the library) keeps at most [`MAX_KEPT_SAMPLES`] rows — every
//! sample of an ordinary run, a min/max envelope of a long one ([`History::stride`]).

use crate::integrate::{Observer, StepView, Stepped, onset_speed};
use crate::model::contact::ContactForce;
use crate::model::system::System;
use crate::numerics::hermite::{
    Basis, HERMITE_REACH, big, hermite, hermite_abs_max, hermite_bound, hermite_max, hermite_slope,
    small,
};
use crate::recording::floor_response::FloorRecorder;
use crate::recording::history::{Envelope, History, HistorySink, MAX_KEPT_SAMPLES, sample_count};
use crate::recording::run_record::{EnergyBalance, Impact, LevelRecord, RunRecord};
use crate::recording::storey_record::StoreyTracker;

mod project;
#[cfg(test)]
use project::{LANES_FROM, project};
use project::{Tracks, modal_energy};

#[derive(Debug, Clone, Copy)]
struct Open {
    start: f64,
    impulse_at_start: f64,
    peak_force: f64,
    max_penetration: f64,
    approach_speed: f64,
}

/// The recorder. Build with [`Recorder::new`] (and [`Recorder::with_sink`] to stream the
/// history), pass to an integrator, then [`Recorder::finish`].
pub struct Recorder<'s> {
    /// Index of the main (highest) tracked height. Heights tracked: the contact levels' (for the
    /// no-contact run the same heights are passed in, so that both runs report the same places).
    main: usize,
    /// The tracked heights' displacements and velocities at an observation, formed structure
    /// by structure ([`Tracks`]).
    tracks: Tracks,
    /// Number of structures (the length of `RunRecord::floors`).
    structures: usize,
    levels: Vec<LevelRecord>,
    open: Vec<Option<Open>>,
    impacts: Vec<Impact>,
    prev: Option<Sample>,
    prev_delta: Vec<f64>,
    prev_delta_dot: Vec<f64>,
    /// (w₁, ẇ₁, w₂, ẇ₂) at every tracked height at the previous observation.
    prev_w: Vec<[f64; 4]>,
    interval: f64,
    next_sample: usize,
    /// `next_sample · interval`, s.
    next_time: f64,
    history: History,
    /// The envelope group being filled (stride > 1).
    envelope: Envelope,
    /// Where every sample goes as it is taken.
    sink: Option<&'s mut dyn HistorySink>,
    /// Whether the sink takes the floor rows ([`HistorySink::wants_floor_rows`]).
    floor_rows: bool,
    /// Forces of the levels at the sample being taken (scratch, no allocation per sample).
    row_forces: Vec<f64>,
    last_impulse: Vec<f64>,
    prev_force: Vec<f64>,
    modal_initial: f64,
    stored_initial: f64,
    energy_peak: f64,
    last_t: f64,
    steps: usize,
    /// Modal and contact energy and the tallies (input, damping, contact, hysteretic work) at
    /// the last observation, J.
    last_energy: [f64; 6],
    /// End of the run, s.
    end: f64,
    /// Responses over the structures' heights (`None`: not tracked, or not built yet).
    floors: Option<FloorRecorder>,
    /// The tracked heights' pairs while the floor recorder is still to be built, at the first
    /// observation (its stations' tables cost ~0.1 M instructions per structure: nothing for
    /// a run [`Recorder::without_floors`]); `None` once built or switched off.
    floors_pending: Option<Vec<usize>>,
    /// The values of the floor rows that go to the sink (`None`: all; see
    /// [`Recorder::with_floor_stations`]), and a scratch row for them.
    floor_keep: Option<Vec<usize>>,
    floor_row: Vec<f64>,
    /// The floor peaks' resolution between observations
    /// ([`FloorRecorder::with_resolution`]).
    floor_resolution: Option<f64>,
    /// Yielding storeys (`None`: none).
    storeys: Option<StoreyTracker>,
    /// ω² of every mode of the system, 1/s².
    w2: Vec<f64>,
}

#[derive(Debug, Clone, Copy)]
struct Sample {
    t: f64,
    w: [f64; 2],
    wdot: [f64; 2],
}

impl std::fmt::Debug for Recorder<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Recorder")
            .field("steps", &self.steps)
            .field("kept_samples", &self.history.t.len())
            .field("streams", &self.sink.is_some())
            .finish_non_exhaustive()
    }
}

impl<'s> Recorder<'s> {
    /// A recorder tracking displacements at `heights` (m; the main one is the highest) for
    /// a pair `system`, sampling the history every `interval` s over `duration` s.
    pub fn new(system: &System, heights: &[f64], interval: f64, duration: f64) -> Recorder<'s> {
        Recorder::for_row(system, heights, &vec![0; heights.len()], interval, duration)
    }

    /// [`Recorder::new`] for a row `system`: tracked height k (a contact level's) is between
    /// structures `pairs[k]` and `pairs[k] + 1` ([`crate::model::system::Level::pair`]); its
    /// `peak_w1`, `peak_w2` are those of the pair's left and right structure.
    pub fn for_row(
        system: &System,
        heights: &[f64],
        pairs: &[usize],
        interval: f64,
        duration: f64,
    ) -> Recorder<'s> {
        let main = heights
            .iter()
            .enumerate()
            .fold(0, |best, (i, &h)| if h > heights[best] { i } else { best });
        let st = &system.structures;
        let samples = usize::try_from(sample_count(interval, duration)).unwrap_or(usize::MAX);
        let stride = if samples <= MAX_KEPT_SAMPLES {
            1
        } else {
            // two rows per group
            samples.div_ceil(MAX_KEPT_SAMPLES / 2)
        };
        let kept = if stride == 1 {
            samples
        } else {
            2 * samples.div_ceil(stride)
        };
        let nl = system.levels.len();
        Recorder {
            main,
            tracks: Tracks::new(system, heights, pairs),
            structures: st.len(),
            levels: heights
                .iter()
                .map(|&h| LevelRecord {
                    height: h,
                    peak_w1: 0.0,
                    peak_w2: 0.0,
                    max_closing: f64::NEG_INFINITY,
                    peak_force: 0.0,
                    max_penetration: 0.0,
                    impacts: 0,
                    contact_time: 0.0,
                })
                .collect(),
            open: vec![None; nl],
            impacts: Vec::with_capacity(64),
            prev: None,
            prev_delta: vec![f64::NEG_INFINITY; nl],
            prev_delta_dot: vec![0.0; nl],
            prev_w: vec![[0.0; 4]; heights.len()],
            interval,
            next_sample: 0,
            next_time: 0.0,
            history: History {
                stride,
                t: Vec::with_capacity(kept),
                w1: Vec::with_capacity(kept),
                w2: Vec::with_capacity(kept),
                force: vec![Vec::with_capacity(kept); nl],
            },
            envelope: Envelope::new(2 + nl),
            sink: None,
            floor_rows: false,
            row_forces: vec![0.0; nl],
            last_impulse: vec![0.0; nl],
            prev_force: vec![0.0; nl],
            modal_initial: 0.0,
            stored_initial: 0.0,
            energy_peak: 0.0,
            last_t: 0.0,
            steps: 0,
            last_energy: [0.0; 6],
            end: duration,
            floors: None,
            floors_pending: Some(pairs.to_vec()),
            floor_keep: None,
            floor_row: Vec::new(),
            floor_resolution: Some(crate::recording::subgrid::DEFAULT_RESOLUTION),
            storeys: StoreyTracker::new(system, interval, duration),
            w2: system.omega().iter().map(|w| w * w).collect(),
        }
    }

    /// Do not track the responses over the structures' heights (`RunRecord::floors` empty):
    /// for runs that need only the contact-height numbers.
    pub fn without_floors(mut self) -> Recorder<'s> {
        self.floors = None;
        self.floors_pending = None;
        self
    }

    /// Build the floor recorder if it is still pending (see `floors_pending`).
    #[cold]
    fn build_floors(&mut self, system: &System) {
        if let Some(pairs) = self.floors_pending.take() {
            let heights: Vec<f64> = self.levels.iter().map(|l| l.height).collect();
            self.floors = Some(
                FloorRecorder::for_row(system, &heights, &pairs, self.interval)
                    .with_resolution(self.floor_resolution),
            );
        }
    }

    /// The resolution of the floor peaks between observations (see
    /// [`FloorRecorder::with_resolution`]; the self-check's run takes a finer one).
    pub fn with_floor_resolution(mut self, resolution: Option<f64>) -> Recorder<'s> {
        self.floor_resolution = resolution;
        if let Some(f) = self.floors.take() {
            self.floors = Some(f.with_resolution(resolution));
        }
        self
    }

    /// Send to the sink the floor history of the stations `stations` keeps (the peaks over
    /// the height still cover every station): the rows of `floors.csv`.
    pub fn with_floor_stations(
        mut self,
        system: &System,
        heights: &[f64],
        stations: crate::recording::stations::FloorStations,
    ) -> Recorder<'s> {
        self.build_floors(system);
        if let Some(f) = &self.floors {
            self.floor_keep = stations.selection(system, f, heights);
            self.floor_row = Vec::with_capacity(self.floor_keep.as_ref().map_or(0, Vec::len));
        }
        self
    }

    /// Send every history sample to `sink` as it is taken (the in-memory history is kept as
    /// well, bounded: see [`History`]).
    pub fn with_sink(mut self, sink: &'s mut dyn HistorySink) -> Recorder<'s> {
        self.floor_rows = sink.wants_floor_rows();
        self.sink = Some(sink);
        self
    }

    /// Close open contact episodes and return the record.
    pub fn finish(mut self) -> RunRecord {
        let mut envelope = std::mem::replace(&mut self.envelope, Envelope::new(0));
        envelope.flush(&mut self.history);
        for k in 0..self.open.len() {
            if let Some(o) = self.open[k].take() {
                self.close(k, o, self.last_t, self.last_impulse[k]);
            }
        }
        for l in &mut self.levels {
            if !l.max_closing.is_finite() {
                l.max_closing = 0.0;
            }
        }
        self.impacts
            .sort_by(|a, b| a.start.total_cmp(&b.start).then(a.level.cmp(&b.level)));
        let [modal, stored, input, damping, contact, hysteretic] = self.last_energy;
        let modal_change = modal - self.modal_initial;
        let residual = input - modal_change - damping - contact - hysteretic;
        let storeys = self
            .storeys
            .take()
            .map_or(Vec::new(), StoreyTracker::finish);
        let (hysteretic_dissipated, hysteretic_stored) = if storeys.is_empty() {
            (None, None)
        } else {
            let e: f64 = storeys.iter().map(|r| r.hysteretic_energy).sum();
            (Some(e), Some(hysteretic - e))
        };
        let scale = self.energy_peak.max(input.abs()).max(f64::MIN_POSITIVE);
        let energy = EnergyBalance {
            input,
            modal_change,
            contact_stored: stored,
            damping_dissipated: damping,
            contact_dissipated: contact - (stored - self.stored_initial),
            hysteretic_dissipated,
            hysteretic_stored,
            relative_error: residual.abs() / scale,
        };
        let (peak, max_closing) = self
            .levels
            .get(self.main)
            .map_or(([0.0; 2], 0.0), |m| ([m.peak_w1, m.peak_w2], m.max_closing));
        RunRecord {
            peak,
            max_closing,
            levels: self.levels,
            impacts: self.impacts,
            history: self.history,
            energy,
            steps: self.steps,
            floors: self
                .floors
                .map_or_else(|| vec![Vec::new(); self.structures], FloorRecorder::finish),
            storeys,
        }
    }

    fn close(&mut self, k: usize, o: Open, end: f64, impulse_now: f64) {
        self.impacts.push(Impact {
            level: k,
            start: o.start,
            end,
            peak_force: o.peak_force,
            impulse: impulse_now - o.impulse_at_start,
            max_penetration: o.max_penetration,
            approach_speed: o.approach_speed,
        });
        let l = &mut self.levels[k];
        l.impacts += 1;
        l.contact_time += end - o.start;
    }

    /// One history sample (forces in `row_forces`): to the sink, and into the bounded
    /// in-memory history.
    #[inline(always)]
    fn keep(&mut self, t: f64, w: [f64; 2]) {
        if let Some(sink) = self.sink.as_deref_mut() {
            sink.row(t, w, &self.row_forces);
        }
        let h = &mut self.history;
        if h.stride <= 1 {
            h.t.push(t);
            h.w1.push(w[0]);
            h.w2.push(w[1]);
            for (c, f) in h.force.iter_mut().zip(&self.row_forces) {
                c.push(*f);
            }
        } else {
            let forces = &self.row_forces;
            self.envelope
                .add(t, w.into_iter().chain(forces.iter().copied()));
            if self.envelope.count == h.stride {
                self.envelope.flush(h);
            }
        }
    }

    /// History samples at multiples of the interval in (previous step, this step]: cubic
    /// Hermite in the displacements (4th-order accurate like the step), linear in the forces.
    /// Returns whether a sample was taken.
    #[inline(always)]
    fn sample(&mut self, s: &StepView, now: &Sample) -> bool {
        if self.next_time > s.t + 1e-9 * self.interval {
            // (most observations of a run in contact: no sample due)
            for (k, st) in s.levels.iter().enumerate() {
                self.prev_force[k] = st.force;
            }
            return false;
        }
        let first = self.next_sample;
        loop {
            let tau = self.next_sample as f64 * self.interval;
            if tau > s.t + 1e-9 * self.interval {
                break;
            }
            let w = match self.prev {
                Some(p) if s.t > p.t => {
                    let h = s.t - p.t;
                    let th = ((tau - p.t) / h).clamp(0.0, 1.0);
                    let b = Basis::at(th);
                    let w = |i: usize| b.combine(p.w[i], p.wdot[i], now.w[i], now.wdot[i], h);
                    for (k, st) in s.levels.iter().enumerate() {
                        self.row_forces[k] =
                            self.prev_force[k] + th * (st.force - self.prev_force[k]);
                    }
                    [w(0), w(1)]
                }
                _ => {
                    for (k, st) in s.levels.iter().enumerate() {
                        self.row_forces[k] = st.force;
                    }
                    now.w
                }
            };
            self.keep(tau, w);
            self.next_sample += 1;
        }
        self.next_time = self.next_sample as f64 * self.interval;
        for (k, st) in s.levels.iter().enumerate() {
            self.prev_force[k] = st.force;
        }
        self.next_sample > first
    }
}

/// `peak = max(peak, x)` as a plain comparison (no NaN handling, which `f64::max` spends
/// instructions on: a NaN state has already stopped the run as diverged).
#[inline(always)]
fn raise(peak: &mut f64, x: f64) {
    if x > *peak {
        *peak = x;
    }
}

/// An upper bound of the interpolant's absolute value (see [`hermite_bound`], for y and −y).
#[inline(always)]
fn hermite_abs_bound(y0: f64, d0: f64, y1: f64, d1: f64, h: f64) -> f64 {
    let up = big(d0, 0.0) - small(d1, 0.0);
    let down = big(d1, 0.0) - small(d0, 0.0);
    big(y0.abs(), y1.abs()) + HERMITE_REACH * h * big(up, down)
}

/// An upper bound of [`hermite_abs_bound`] (`reach` = [`HERMITE_REACH`]·h): the end slopes'
/// term `max(d0⁺ + d1⁻, d1⁺ + d0⁻)` is at most `|d0| + |d1|`, and rounding is monotone, so
/// each rounded sum and product here is at least the tighter one's (`reach` is the same
/// product `HERMITE_REACH · h` it forms first): where this bound does not beat a peak, the
/// tighter one does not either, and the decision is the same.
#[inline(always)]
fn loose_abs_bound(y0: f64, d0: f64, y1: f64, d1: f64, reach: f64) -> f64 {
    big(y0.abs(), y1.abs()) + reach * (d0.abs() + d1.abs())
}

/// A sink that passes on the floor rows' values at `keep` only.
struct Picked<'a, 'b> {
    sink: &'a mut (dyn HistorySink + 'b),
    keep: &'a [usize],
    row: &'a mut Vec<f64>,
}

impl HistorySink for Picked<'_, '_> {
    fn row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
        self.sink.row(t, w, forces);
    }

    fn floor_row(&mut self, t: f64, values: &[f64]) {
        self.row.clear();
        self.row
            .extend(self.keep.iter().filter_map(|&i| values.get(i).copied()));
        self.sink.floor_row(t, self.row);
    }
}

impl Observer for Recorder<'_> {
    fn observe(&mut self, system: &System, s: &StepView) {
        self.observe_part(system, s, None);
    }

    /// A row's passive structures' floors are observed on the grid only
    /// (`FloorRecorder::observe_part`); the rest as at every observation.
    fn observe_stepped(&mut self, system: &System, s: &StepView, stepped: &Stepped) {
        self.observe_part(system, s, Some(stepped));
    }
}

impl Recorder<'_> {
    /// [`Observer::observe`], the floors of the structures `stepped.active` only where a row's
    /// contact step left the others in free flight (see [`Observer::observe_stepped`]).
    #[inline(always)]
    fn observe_part(&mut self, system: &System, s: &StepView, stepped: Option<&Stepped>) {
        #[cfg(target_arch = "x86_64")]
        if self.tracks.wide() {
            // SAFETY: `wide` only where the processor has AVX
            unsafe { self.observe_avx(system, s, stepped) };
            return;
        }
        self.observe_body(system, s, stepped);
    }

    /// [`Recorder::observe_part`] compiled for AVX: the same operations, encoded with three
    /// operands (no register copies before each) and the projections inlined. Safety: the
    /// processor has AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn observe_avx(&mut self, system: &System, s: &StepView, stepped: Option<&Stepped>) {
        self.observe_body(system, s, stepped);
    }

    #[inline(always)]
    fn observe_body(&mut self, system: &System, s: &StepView, stepped: Option<&Stepped>) {
        if self.floors_pending.is_some() {
            self.build_floors(system);
        }
        if let Some(f) = &mut self.floors {
            // (no floor rows formed for a sink that drops them)
            let sink = self.sink.as_deref_mut().filter(|_| self.floor_rows);
            match (&self.floor_keep, sink) {
                (Some(keep), Some(sink)) => {
                    let mut picked = Picked {
                        sink,
                        keep,
                        row: &mut self.floor_row,
                    };
                    f.observe_part(system, s, Some(&mut picked), stepped);
                }
                (_, sink) => f.observe_part(system, s, sink, stepped),
            }
        }
        if let Some(st) = &mut self.storeys {
            st.observe(system, s);
        }
        let q = s.q;
        // displacements and velocities at every tracked height
        let mut main_sample = Sample {
            t: s.t,
            w: [0.0; 2],
            wdot: [0.0; 2],
        };
        // Peaks: at the observation, and inside the interval since the previous one from the
        // cubic Hermite interpolant of (w, ẇ) at both ends (O(h⁴), so peaks do not depend on
        // where the steps happen to fall).
        let h = s.t - self.last_t;
        let refine = self.prev.is_some() && h > 0.0;
        let reach = HERMITE_REACH * h;
        self.tracks.project(q, s.v);
        for k in 0..self.levels.len() {
            let ((w1, w1d), (w2, w2d)) = self.tracks.at(k);
            let (prev_w, l) = (&mut self.prev_w[k], &mut self.levels[k]);
            raise(&mut l.peak_w1, w1.abs());
            raise(&mut l.peak_w2, w2.abs());
            raise(&mut l.max_closing, w1 - w2);
            if refine {
                // (every step: an interior extremum does not need the slope to change sign;
                // the root solve only where the interpolant's bound could beat the peak)
                let [a1, a1d, a2, a2d] = *prev_w;
                // (first a looser bound, with |ẇ₀| + |ẇ₁| ≥ either end-slope term: most steps
                // stay below the peak by it and skip the tighter one)
                if loose_abs_bound(a1, a1d, w1, w1d, reach) > l.peak_w1
                    && hermite_abs_bound(a1, a1d, w1, w1d, h) > l.peak_w1
                {
                    raise(&mut l.peak_w1, hermite_abs_max(a1, a1d, w1, w1d, h));
                }
                if loose_abs_bound(a2, a2d, w2, w2d, reach) > l.peak_w2
                    && hermite_abs_bound(a2, a2d, w2, w2d, h) > l.peak_w2
                {
                    raise(&mut l.peak_w2, hermite_abs_max(a2, a2d, w2, w2d, h));
                }
                let (c0, c0d, c1, c1d) = (a1 - a2, a1d - a2d, w1 - w2, w1d - w2d);
                if hermite_bound(c0, c0d, c1, c1d, h) > l.max_closing {
                    raise(&mut l.max_closing, hermite_max(c0, c0d, c1, c1d, h).0);
                }
            }
            *prev_w = [w1, w1d, w2, w2d];
            if k == self.main {
                main_sample.w = [w1, w2];
                main_sample.wdot = [w1d, w2d];
            }
        }
        // contact episodes
        for (k, st) in s.levels.iter().enumerate() {
            let prev = self.prev_delta[k];
            // largest penetration inside the interval (Hermite), and the force there: at an
            // interior maximum δ̇ = 0, so every law gives its elastic force — the peak force for
            // elastic laws, a lower bound for damped ones.
            let (mut inner_delta, mut inner_force) = (f64::NEG_INFINITY, 0.0);
            // (an interior maximum does not need δ̇ to change sign: after a velocity jump, or
            // over a step long against the motion, the cubic overshoots with end slopes of one
            // sign, as the displacements' do; δ may be negative at both ends and positive in
            // between: a grazing contact. The root solve only where the interpolant's bound
            // rises above both ends, above 0 and above the open episode's largest
            // penetration: below it, an interior maximum changes neither the episode's nor
            // the level's penetration, nor its peak force — an elastic law's force grows
            // with δ, and a damped law's peak is searched below.)
            let prev_dot = self.prev_delta_dot[k];
            let above = self.open[k].map_or(0.0, |o| o.max_penetration);
            if refine
                && hermite_bound(prev, prev_dot, st.delta, st.delta_dot, h)
                    > prev.max(st.delta).max(above)
            {
                let (m, th) = hermite_max(prev, prev_dot, st.delta, st.delta_dot, h);
                if th > 0.0 && th < 1.0 && m > 0.0 {
                    inner_delta = m;
                    inner_force = system.levels[k].force.force(m, 0.0, 1.0);
                }
            }
            // a damped law peaks while δ still grows (δ̇ > 0): search the interval's Hermite
            // interpolant of (δ, δ̇) for the force's own maximum
            let law = &system.levels[k].force;
            if refine && law.rate_dependent() && (prev > 0.0 || st.delta > 0.0 || inner_delta > 0.0)
            {
                let ends = ((prev, self.prev_delta_dot[k]), (st.delta, st.delta_dot));
                let v0 = match &self.open[k] {
                    Some(o) => o.approach_speed,
                    None => onset_speed(ends.0, ends.1, h),
                };
                inner_force = inner_force.max(rate_law_peak(law, ends.0, ends.1, h, v0));
            }
            if st.delta > 0.0 {
                let o = self.open[k].get_or_insert_with(|| {
                    // δ crossed 0 between the previous observation and this one (δ_prev = 0
                    // exactly puts the start at the previous observation)
                    let theta = if prev.is_finite() && prev <= 0.0 {
                        prev / (prev - st.delta)
                    } else {
                        1.0
                    };
                    let t0 = self.last_t + theta * (s.t - self.last_t);
                    Open {
                        start: if self.prev.is_none() { s.t } else { t0 },
                        // the tally at the previous observation: the onset step's impulse
                        // (and a stereomechanical jump at its end) belongs to this episode
                        impulse_at_start: self.last_impulse[k],
                        peak_force: 0.0,
                        max_penetration: 0.0,
                        // δ̇ where δ crosses 0 (at a located onset: the previous
                        // observation), the same v₀ the integrators give the damped laws
                        approach_speed: if prev.is_finite() {
                            onset_speed(
                                (prev, self.prev_delta_dot[k]),
                                (st.delta, st.delta_dot),
                                s.t - self.last_t,
                            )
                        } else {
                            st.delta_dot
                        },
                    }
                });
                raise(&mut o.peak_force, st.force.max(inner_force));
                raise(&mut o.max_penetration, st.delta.max(inner_delta));
            } else if let Some(mut o) = self.open[k].take() {
                o.peak_force = o.peak_force.max(inner_force);
                o.max_penetration = o.max_penetration.max(inner_delta);
                let theta = if prev > 0.0 {
                    prev / (prev - st.delta)
                } else {
                    1.0
                };
                let end = self.last_t + theta * (s.t - self.last_t);
                self.close(k, o, end, s.tally.impulse[k]);
            } else if s.tally.impulse[k] > self.last_impulse[k]
                && (system.levels[k].force.impulsive().is_some() || inner_delta > 0.0)
            {
                // an impulse without observed penetration: an instantaneous (stereomechanical)
                // impact located exactly at δ = 0, or a grazing contact between observations
                // (δ > 0 inside the interval). A force law's impulse over an interval where δ
                // stays ≤ 0 is round-off (a step ending on a located onset), not an impact.
                let o = Open {
                    start: s.t,
                    impulse_at_start: self.last_impulse[k],
                    peak_force: st.force.max(inner_force),
                    max_penetration: st.delta.max(inner_delta).max(0.0),
                    approach_speed: self.prev_delta_dot[k],
                };
                self.close(k, o, s.t, s.tally.impulse[k]);
            }
            let l = &mut self.levels[k];
            raise(&mut l.peak_force, st.force.max(inner_force));
            raise(&mut l.max_penetration, st.delta.max(inner_delta));
            self.prev_delta[k] = st.delta;
            self.prev_delta_dot[k] = st.delta_dot;
        }
        let n = self.last_impulse.len().min(s.tally.impulse.len());
        self.last_impulse[..n].copy_from_slice(&s.tally.impulse[..n]);
        let sampled = self.sample(s, &main_sample);
        // energy (docs/model.md §2.7; balance: input = Δmodal + damping + work into contacts): at the
        // start, at every observation that gave a history sample (for the peak energy, the
        // balance's scale) and at the end (the balance itself is formed in `finish`)
        if sampled || self.prev.is_none() || s.t >= self.end * (1.0 - 1e-12) {
            let modal = modal_energy(&self.w2, s.q, s.v);
            let stored = system.contact_energy(s.levels);
            if self.prev.is_none() {
                self.modal_initial = modal;
                self.stored_initial = stored;
            }
            self.energy_peak = self.energy_peak.max(modal + stored);
            self.last_energy = [
                modal,
                stored,
                s.tally.input,
                s.tally.damping,
                s.tally.contact,
                s.tally.hysteretic,
            ];
        }
        if self.prev.is_some() {
            self.steps += 1;
        }
        self.last_t = s.t;
        self.prev = Some(main_sample);
    }
}

/// Largest force of a rate-dependent law over an interval of length `h` (s) whose penetration
/// is the cubic Hermite interpolant of (δ, δ̇) at its ends (m, m/s), with approach speed `v0`:
/// golden-section search on θ ∈ [0, 1] (the force is unimodal over one step of an impact),
/// 40 iterations (θ to 1e-8). Endpoints are included.
fn rate_law_peak(law: &ContactForce, a: (f64, f64), b: (f64, f64), h: f64, v0: f64) -> f64 {
    let f = |th: f64| {
        let d = hermite(a.0, a.1, b.0, b.1, h, th);
        let dd = hermite_slope(a.0, a.1, b.0, b.1, h, th);
        law.force(d, dd, v0)
    };
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut x1 = hi - INV_PHI * (hi - lo);
    let mut x2 = lo + INV_PHI * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..40 {
        if f1 < f2 {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + INV_PHI * (hi - lo);
            f2 = f(x2);
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - INV_PHI * (hi - lo);
            f1 = f(x1);
        }
    }
    f(0.0).max(f(1.0)).max(f1).max(f2)
}
#[cfg(test)]
mod tests;
