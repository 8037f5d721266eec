//! A row's displacement histories (issue 29): every structure's displacement at its headline
//! height (its highest contact level with either neighbour, where `structures[i].
//! peak_displacement` is), and both structures' at every contact level, sampled at the output
//! interval as a pair's history is.
//!
//! The recorder samples a pair's two displacements at the main contact height; a row has N
//! structures and several heights. `RowObserver` runs a `RowSampler` beside the
//! [`Recorder`] on the recorder's public interface: at every observation the sampler keeps the
//! state (q, q̇) of the previous observation, and at each sample time it projects both onto
//! the mode shapes (`w = Σ φ_n(h) q_n`, summed in mode order from 0) and takes the cubic
//! Hermite interpolant between them at θ = (τ − t₀)/h — the recorder's arithmetic, so that a
//! row whose other gaps never close gives a pair's `w1`, `w2` to the last digit (tested). The
//! projections happen at the samples only (a copy of the state per observation otherwise).
//! Each sample goes to a queue that the recorder's history sink (`RowPhaseSink`) empties
//! when it emits the same sample with every level's force, so that one [`RunSink`] receives
//! one row of a row's history at a time (the CSV writer streams it; nothing grows with the
//! duration except the bounded in-memory [`RowHistory`]).

use std::cell::RefCell;
use std::collections::VecDeque;

use super::{Phase, RunSink};
use crate::integrate::{Observer, StepView, Stepped};
use crate::model::system::System;
use crate::numerics::hermite::Basis;
use crate::recording::history::{HistorySink, MAX_KEPT_SAMPLES, sample_count};
use crate::recording::recorder::Recorder;

/// A row's sampled displacements in memory (for the pictures and the library): every sample
/// of an ordinary run; beyond [`MAX_KEPT_SAMPLES`] samples, as a pair's
/// [`crate::recording::history::History`], a min/max envelope (each group of `stride` samples
/// kept as two rows: the minima at the group's first time, the maxima at its last).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RowHistory {
    /// Samples per envelope group (1: every sample kept).
    pub stride: usize,
    /// Sample times, s.
    pub t: Vec<f64>,
    /// Each structure's headline height (its highest contact level with either neighbour), m.
    pub heights: Vec<f64>,
    /// Per structure (row order): w at its headline height, m.
    pub structures: Vec<Vec<f64>>,
    /// Per contact level (the system's order: pair by pair): w of the pair's left and right
    /// structure at the level's height, m.
    pub levels: Vec<[Vec<f64>; 2]>,
}

/// One tracked displacement: structure `i`'s w at a height.
#[derive(Debug, Clone)]
struct Track {
    /// φ_n at the height, every mode of the structure.
    phi: Vec<f64>,
    /// Where the structure's modes are in the state.
    span: std::ops::Range<usize>,
}

/// `Σ φ_n q_n` and `Σ φ_n q̇_n` summed from mode 0 up (the recorder's order).
#[inline(always)]
fn project(phi: &[f64], q: &[f64], v: &[f64]) -> (f64, f64) {
    let n = phi.len().min(q.len()).min(v.len());
    let (phi, q, v) = (&phi[..n], &q[..n], &v[..n]);
    let (mut w, mut wd) = (0.0, 0.0);
    for j in 0..n {
        w += phi[j] * q[j];
        wd += phi[j] * v[j];
    }
    (w, wd)
}

/// Each of `structures` structures' headline height in a row whose contact levels are at
/// `heights` between the pairs `pairs` (left structure's index): its highest contact level
/// with either neighbour (0 for a structure without levels, which a validated row does not
/// have).
pub fn headline_heights(structures: usize, heights: &[f64], pairs: &[usize]) -> Vec<f64> {
    (0..structures)
        .map(|i| {
            (heights.iter().zip(pairs))
                .filter(|(_, p)| **p == i || **p + 1 == i)
                .map(|(h, _)| *h)
                .fold(0.0, f64::max)
        })
        .collect()
}

/// Samples every structure's w at its headline height and both structures' w at every level
/// (see the module); the samples go to `pending` and into the bounded [`RowHistory`].
pub(super) struct RowSampler<'p> {
    tracks: Vec<Track>,
    structures: usize,
    interval: f64,
    next_sample: usize,
    /// The previous observation: t, q, q̇ (copied), and whether there was one.
    prev_t: Option<f64>,
    prev_q: Vec<f64>,
    prev_v: Vec<f64>,
    /// Whether `before` already holds the previous observation's projections (it was
    /// projected: a sample fell at or before it), so that `prev_q`, `prev_v` are not read.
    before_kept: bool,
    /// Scratch: (w, ẇ) of every track at the previous and at this observation, and a sample
    /// (`at`: per track; `row`: per column, see `slot`).
    before: Vec<(f64, f64)>,
    now: Vec<(f64, f64)>,
    at: Vec<f64>,
    row: Vec<f64>,
    /// Per column of a sample (every structure's headline, then both structures at every
    /// level), its track (distinct (structure, height) pairs only).
    slot: Vec<usize>,
    pending: &'p RefCell<VecDeque<f64>>,
    history: RowHistory,
    /// Envelope group being filled (stride > 1): count, first and last time, minima, maxima.
    group: (usize, f64, f64, Vec<f64>, Vec<f64>),
}

impl<'p> RowSampler<'p> {
    /// A sampler for `system` over `duration` s every `interval` s, queueing into `pending`;
    /// the row's contact levels are at `levels.0` (m) between the pairs `levels.1` (those of
    /// the run with contact, also for the run without, whose system has no levels).
    pub(super) fn new(
        system: &System,
        (level_heights, pairs): (&[f64], &[usize]),
        interval: f64,
        duration: f64,
        pending: &'p RefCell<VecDeque<f64>>,
    ) -> RowSampler<'p> {
        let st = &system.structures;
        let heights = headline_heights(st.len(), level_heights, pairs);
        let track = |i: usize, h: f64| Track {
            phi: st[i].shapes_at(h),
            span: system.modes_of(i),
        };
        // the columns: every structure at its headline height, then both structures at every
        // level; a (structure, height) met again (a headline height is one of its levels', and
        // a building of a row is often at the same heights with both neighbours) is one track,
        // projected once: the same φ and the same sums, so the same bits in every column
        let mut columns: Vec<(usize, f64)> = (0..st.len()).map(|i| (i, heights[i])).collect();
        for (&h, &p) in level_heights.iter().zip(pairs) {
            columns.push((p, h));
            columns.push((p + 1, h));
        }
        let mut distinct: Vec<(usize, f64)> = Vec::new();
        let slot: Vec<usize> = columns
            .iter()
            .map(|&(i, h)| {
                let same = |&(j, x): &(usize, f64)| j == i && x.to_bits() == h.to_bits();
                distinct.iter().position(same).unwrap_or_else(|| {
                    distinct.push((i, h));
                    distinct.len() - 1
                })
            })
            .collect();
        let tracks: Vec<Track> = distinct.iter().map(|&(i, h)| track(i, h)).collect();
        let samples = usize::try_from(sample_count(interval, duration)).unwrap_or(usize::MAX);
        let stride = if samples <= MAX_KEPT_SAMPLES {
            1
        } else {
            samples.div_ceil(MAX_KEPT_SAMPLES / 2)
        };
        let kept = if stride == 1 {
            samples
        } else {
            2 * samples.div_ceil(stride)
        };
        let n = system.len();
        let nt = tracks.len();
        let width = slot.len();
        RowSampler {
            structures: st.len(),
            interval,
            next_sample: 0,
            prev_t: None,
            prev_q: vec![0.0; n],
            prev_v: vec![0.0; n],
            before_kept: false,
            before: vec![(0.0, 0.0); nt],
            now: vec![(0.0, 0.0); nt],
            at: vec![0.0; nt],
            row: vec![0.0; width],
            slot,
            pending,
            history: RowHistory {
                stride,
                t: Vec::with_capacity(kept),
                heights,
                structures: vec![Vec::with_capacity(kept); st.len()],
                levels: (0..pairs.len())
                    .map(|_| [Vec::with_capacity(kept), Vec::with_capacity(kept)])
                    .collect(),
            },
            group: (
                0,
                0.0,
                0.0,
                vec![f64::INFINITY; width],
                vec![f64::NEG_INFINITY; width],
            ),
            tracks,
        }
    }

    /// Values per queued sample: every track's w.
    pub(super) fn width(&self) -> usize {
        self.slot.len()
    }

    fn observe(&mut self, s: &StepView) {
        let eps = 1e-9 * self.interval;
        let mut projected = false;
        loop {
            let tau = self.next_sample as f64 * self.interval;
            if tau > s.t + eps {
                break;
            }
            if !projected {
                for (k, tr) in self.tracks.iter().enumerate() {
                    let r = tr.span.clone();
                    self.now[k] = project(&tr.phi, &s.q[r.clone()], &s.v[r]);
                }
                projected = true;
            }
            match self.prev_t {
                Some(t0) if s.t > t0 => {
                    let h = s.t - t0;
                    let th = ((tau - t0) / h).clamp(0.0, 1.0);
                    // (at θ = 1 the weights are 0, 0, 1, 0 exactly: the interpolant is the
                    // observation's w bit for bit whatever (finite) values the previous one
                    // holds, unless w = 0, where the zeros' signs could matter; the previous
                    // observation is projected only where it is read)
                    let end = th == 1.0 && self.now.iter().all(|n| n.0 != 0.0);
                    if end {
                        for (w, n) in self.at.iter_mut().zip(&self.now) {
                            *w = n.0;
                        }
                    } else {
                        if !self.before_kept {
                            for (k, tr) in self.tracks.iter().enumerate() {
                                let r = tr.span.clone();
                                self.before[k] =
                                    project(&tr.phi, &self.prev_q[r.clone()], &self.prev_v[r]);
                            }
                            self.before_kept = true;
                        }
                        let b = Basis::at(th);
                        for (k, w) in self.at.iter_mut().enumerate() {
                            let ((a, ad), (c, cd)) = (self.before[k], self.now[k]);
                            *w = b.combine(a, ad, c, cd, h);
                        }
                    }
                }
                _ => {
                    for (w, n) in self.at.iter_mut().zip(&self.now) {
                        *w = n.0;
                    }
                }
            }
            for (w, &k) in self.row.iter_mut().zip(&self.slot) {
                *w = self.at[k];
            }
            self.pending.borrow_mut().extend(self.row.iter().copied());
            self.keep(tau);
            self.next_sample += 1;
        }
        self.prev_t = Some(s.t);
        // (an observation that was projected is the next one's `before` as it stands, the
        // same sums of the same state: no copy of the state needed then)
        self.before_kept = projected;
        if projected {
            std::mem::swap(&mut self.before, &mut self.now);
        } else {
            let n = self.prev_q.len();
            self.prev_q.copy_from_slice(&s.q[..n]);
            self.prev_v.copy_from_slice(&s.v[..n]);
        }
    }

    /// The sample in `row` into the in-memory history.
    fn keep(&mut self, t: f64) {
        if self.history.stride <= 1 {
            self.history.t.push(t);
            self.push_row(None);
            return;
        }
        let (count, first, last, lo, hi) = &mut self.group;
        if *count == 0 {
            *first = t;
        }
        *last = t;
        *count += 1;
        for ((l, h), &v) in lo.iter_mut().zip(hi.iter_mut()).zip(&self.row) {
            *l = l.min(v);
            *h = h.max(v);
        }
        if *count == self.history.stride {
            self.flush();
        }
    }

    /// Append `row` (or the group's minima, `Some(false)`, or maxima, `Some(true)`).
    fn push_row(&mut self, group: Option<bool>) {
        let values = match group {
            None => &self.row,
            Some(false) => &self.group.3,
            Some(true) => &self.group.4,
        };
        let n = self.structures;
        for (c, &v) in self.history.structures.iter_mut().zip(&values[..n]) {
            c.push(v);
        }
        for (k, c) in self.history.levels.iter_mut().enumerate() {
            c[0].push(values[n + 2 * k]);
            c[1].push(values[n + 2 * k + 1]);
        }
    }

    fn flush(&mut self) {
        if self.group.0 == 0 {
            return;
        }
        self.history.t.push(self.group.1);
        self.push_row(Some(false));
        self.history.t.push(self.group.2);
        self.push_row(Some(true));
        self.group.0 = 0;
        self.group.3.fill(f64::INFINITY);
        self.group.4.fill(f64::NEG_INFINITY);
    }

    /// The in-memory history.
    pub(super) fn finish(mut self) -> RowHistory {
        self.flush();
        self.history
    }
}

/// The recorder and the row's sampler as one observer (the sampler first: its samples are
/// queued before the recorder emits the same ones).
pub(super) struct RowObserver<'p, 's> {
    pub(super) sampler: RowSampler<'p>,
    pub(super) recorder: Recorder<'s>,
}

impl Observer for RowObserver<'_, '_> {
    fn observe(&mut self, system: &System, step: &StepView) {
        self.sampler.observe(step);
        self.recorder.observe(system, step);
    }

    /// (the sampler's states are exact at every observation, passive structures' included:
    /// it samples as at every observation; the recorder observes the passive structures'
    /// floors on the grid)
    fn observe_stepped(&mut self, system: &System, step: &StepView, stepped: &Stepped) {
        self.sampler.observe(step);
        self.recorder.observe_stepped(system, step, stepped);
    }
}

/// The recorder's history sink of a row's run: each history sample with the sampler's queued
/// displacements to [`RunSink::row_contact_row`] / [`RunSink::row_free_row`], the floor rows
/// as a pair's, and the progress.
pub(super) struct RowPhaseSink<'a> {
    pub(super) sink: &'a mut dyn RunSink,
    pub(super) phase: Phase,
    pub(super) pending: &'a RefCell<VecDeque<f64>>,
    /// Values per queued sample, and how many of them (the structures') go to the sink.
    pub(super) width: usize,
    pub(super) structures: usize,
    pub(super) row: Vec<f64>,
}

impl HistorySink for RowPhaseSink<'_> {
    fn row(&mut self, t: f64, _w: [f64; 2], forces: &[f64]) {
        {
            let mut q = self.pending.borrow_mut();
            self.row.clear();
            // (the sampler queued this sample first; NaN should it ever not have)
            for _ in 0..self.width {
                self.row.push(q.pop_front().unwrap_or(f64::NAN));
            }
        }
        let w = &self.row[..self.structures.min(self.row.len())];
        match self.phase {
            Phase::WithContact => self.sink.row_contact_row(t, w, forces),
            Phase::WithoutContact => self.sink.row_free_row(t, w),
            Phase::CheckWithContact | Phase::CheckWithoutContact => {}
        }
        self.sink.progress(self.phase, t);
    }

    fn floor_row(&mut self, t: f64, values: &[f64]) {
        self.phase.floor_row(self.sink, t, values);
    }

    /// The self-check's floor rows are never written: not formed.
    fn wants_floor_rows(&self) -> bool {
        !self.phase.is_check()
    }
}
