//! The history of a run: every sample to an optional [`HistorySink`] as it is taken (the CSV
//! writer streams it to disk), and in memory at most [`MAX_KEPT_SAMPLES`] rows ([`History`]:
//! every sample of an ordinary run, a min/max envelope of a long one).

/// Most history rows a [`crate::recording::recorder::Recorder`] keeps in memory. Up to this many samples (a 200 s run at
/// the default 10 ms interval) the [`History`] holds every sample; beyond, an envelope.
pub const MAX_KEPT_SAMPLES: usize = 20_000;

/// Receives every history sample of a run as the recorder takes it, at full resolution, in
/// time order: `t` (s), `w` = (w₁, w₂) at the main contact height (m), `forces` one per
/// contact level (N; empty without contact levels in the system). What a long run writes to
/// disk goes through here; the in-memory [`History`] is bounded.
pub trait HistorySink {
    /// One sample.
    fn row(&mut self, t: f64, w: [f64; 2], forces: &[f64]);
    /// One sample of the floors (see [`crate::recording::floor_response::FloorRecorder::columns`]): at
    /// every station of structure 1 then 2, the displacement and the absolute acceleration.
    fn floor_row(&mut self, t: f64, values: &[f64]) {
        let _ = (t, values);
    }
    /// Whether this sink uses [`HistorySink::floor_row`] (false: the recorder does not form
    /// the floor rows at all — the self-check's runs, whose rows nobody writes).
    fn wants_floor_rows(&self) -> bool {
        true
    }
}

/// Sampled time history: displacements at the main contact height and every level's force.
///
/// With `stride == 1` (every run of at most [`MAX_KEPT_SAMPLES`] samples) row i is the sample
/// at `t = i·output_interval`, exactly as written to history.csv. With `stride > 1` (a longer
/// run) it is an envelope for drawing: each group of `stride` consecutive samples is kept as
/// two rows, the columns' minima at the group's first time and their maxima at its last, so
/// that every extreme of the sampled series (e.g. the largest sampled force) is kept while the
/// length stays below [`MAX_KEPT_SAMPLES`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct History {
    /// Samples per envelope group: 1 = every sample kept (0 only in an empty default).
    pub stride: usize,
    /// Sample times, s (multiples of the output interval).
    pub t: Vec<f64>,
    /// w₁(h) at the main contact height, m.
    pub w1: Vec<f64>,
    /// w₂(h), m.
    pub w2: Vec<f64>,
    /// Contact force of each level (outer index: level), N.
    pub force: Vec<Vec<f64>>,
}

/// A group of samples being folded into the envelope (stride > 1).
#[derive(Debug, Clone)]
pub(crate) struct Envelope {
    pub(crate) count: usize,
    t_first: f64,
    t_last: f64,
    /// Minima then maxima of w₁, w₂, force₁ … force_k.
    min: Vec<f64>,
    max: Vec<f64>,
}

impl Envelope {
    pub(crate) fn new(columns: usize) -> Envelope {
        Envelope {
            count: 0,
            t_first: 0.0,
            t_last: 0.0,
            min: vec![f64::INFINITY; columns],
            max: vec![f64::NEG_INFINITY; columns],
        }
    }

    pub(crate) fn add(&mut self, t: f64, values: impl Iterator<Item = f64>) {
        if self.count == 0 {
            self.t_first = t;
        }
        self.t_last = t;
        self.count += 1;
        for ((lo, hi), v) in self.min.iter_mut().zip(self.max.iter_mut()).zip(values) {
            *lo = lo.min(v);
            *hi = hi.max(v);
        }
    }

    /// Append the group's two rows to `h` and start a new group.
    pub(crate) fn flush(&mut self, h: &mut History) {
        if self.count == 0 {
            return;
        }
        for (t, col) in [(self.t_first, &self.min), (self.t_last, &self.max)] {
            h.t.push(t);
            h.w1.push(col[0]);
            h.w2.push(col[1]);
            for (f, v) in h.force.iter_mut().zip(&col[2..]) {
                f.push(*v);
            }
        }
        self.count = 0;
        self.min.fill(f64::INFINITY);
        self.max.fill(f64::NEG_INFINITY);
    }
}

/// Samples of a run of `duration` s at `interval` s: `⌊duration/interval⌋ + 1` (t = 0 included).
pub fn sample_count(interval: f64, duration: f64) -> u64 {
    (duration / interval + 1e-9).floor() as u64 + 1
}
