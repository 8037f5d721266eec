//! Where a run's samples go: the [`Phase`]s of a checked run, the [`RunSink`] that receives the
//! streamed rows (the CLI's writer, [`NoSink`], the in-memory [`RunCapture`] of the Python
//! package) and the adapter from the recorder's [`HistorySink`] to a sink for one phase.

use crate::recording::history::HistorySink;

/// The integrations a checked run does, in this order: the run with contact, the run without,
/// then (with the self-check) the same two at the tightened settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// The run with contact.
    WithContact,
    /// The run without contact.
    WithoutContact,
    /// The self-check's run with contact.
    CheckWithContact,
    /// The self-check's run without contact.
    CheckWithoutContact,
}

impl Phase {
    /// A short description for progress displays.
    pub fn label(self) -> &'static str {
        match self {
            Phase::WithContact => "with pounding",
            Phase::WithoutContact => "without pounding",
            Phase::CheckWithContact => "self-check, with pounding",
            Phase::CheckWithoutContact => "self-check, without pounding",
        }
    }

    /// Whether this is one of the self-check's runs (whose samples are not written).
    pub fn is_check(self) -> bool {
        matches!(self, Phase::CheckWithContact | Phase::CheckWithoutContact)
    }

    /// A floor history sample of this phase to `sink` (a pair's or a row's: the same files);
    /// the self-check's samples are not written.
    pub(super) fn floor_row(self, sink: &mut dyn RunSink, t: f64, values: &[f64]) {
        match self {
            Phase::WithContact => sink.contact_floor_row(t, values),
            Phase::WithoutContact => sink.free_floor_row(t, values),
            Phase::CheckWithContact | Phase::CheckWithoutContact => {}
        }
    }
}

/// What a run streams out while it goes, so that nothing of it needs to be held in memory:
/// every history sample of the two runs of the result (not of the self-check), and progress.
/// All methods default to doing nothing.
pub trait RunSink {
    /// A history sample of the run with contact: `t` (s), (w₁, w₂) at the main contact height
    /// (m), one force per level (N). Every one of them comes before any sample of the run
    /// without contact.
    fn contact_row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
        let _ = (t, w, forces);
    }
    /// A history sample of the run without contact (same times as the run with contact).
    fn free_row(&mut self, t: f64, w: [f64; 2]) {
        let _ = (t, w);
    }
    /// A floor sample of the run with contact (every station's displacement and absolute
    /// acceleration, [`crate::recording::floor_response::FloorRecorder::columns`]); all come before any
    /// of the run without contact.
    fn contact_floor_row(&mut self, t: f64, values: &[f64]) {
        let _ = (t, values);
    }
    /// A floor sample of the run without contact (same times).
    fn free_floor_row(&mut self, t: f64, values: &[f64]) {
        let _ = (t, values);
    }
    /// A history sample of a row's run with contact (issue 29, [`super::simulate_row_streaming`]):
    /// `t` (s), every structure's displacement at its headline height (its highest contact
    /// level with either neighbour; m, row order), every level's force (N, pair by pair). All
    /// come before any of the run without contact. A row sends these instead of
    /// [`RunSink::contact_row`].
    fn row_contact_row(&mut self, t: f64, w: &[f64], forces: &[f64]) {
        let _ = (t, w, forces);
    }
    /// A history sample of a row's run without contact (same times).
    fn row_free_row(&mut self, t: f64, w: &[f64]) {
        let _ = (t, w);
    }
    /// `phase` has reached simulated time `t` (s); called at every history sample.
    fn progress(&mut self, phase: Phase, t: f64) {
        let _ = (phase, t);
    }
    /// Whether the sink uses the rows of the result's runs (false: progress at most), so
    /// that a run without contact the run with contact already is need not be integrated
    /// to stream it (`free_run_of`).
    fn wants_rows(&self) -> bool {
        true
    }
}

/// A [`RunSink`] that ignores everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoSink;

impl RunSink for NoSink {
    fn wants_rows(&self) -> bool {
        false
    }
}

/// A [`RunSink`] that keeps every streamed sample of the two runs in memory, in the order
/// they came, so that a run can be looked at as arrays and written later, exactly as if it
/// had been streamed ([`RunCapture::replay`] into an `output::writer::RunWriter`). Used by
/// the Python package (`pounding.run`); memory grows with the duration (the CLI streams
/// instead).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunCapture {
    /// Numbers per row of `contact`: t, w₁, w₂ and one force per level.
    pub contact_width: usize,
    /// The rows of the run with contact, flattened.
    pub contact: Vec<f64>,
    /// The rows of the run without contact, flattened: t, w₁, w₂.
    pub free: Vec<f64>,
    /// Numbers per floor row: t and the values.
    pub floor_width: usize,
    /// The floor rows of the run with contact, flattened.
    pub contact_floors: Vec<f64>,
    /// The floor rows of the run without contact, flattened.
    pub free_floors: Vec<f64>,
    /// A row of buildings (issue 29): its number of structures N (0 for a pair).
    pub row_structures: usize,
    /// A row: numbers per row of `row_contact` (t, N displacements, one force per level).
    pub row_contact_width: usize,
    /// A row's history rows of the run with contact, flattened
    /// ([`RunSink::row_contact_row`]).
    pub row_contact: Vec<f64>,
    /// A row's history rows of the run without contact, flattened: t and N displacements.
    pub row_free: Vec<f64>,
}

impl RunCapture {
    /// An empty capture.
    pub fn new() -> RunCapture {
        RunCapture::default()
    }

    /// Hand every captured sample to `sink`, in the order [`super::simulate_streaming`] gives them:
    /// the run with contact (history and floor rows), then the run without.
    pub fn replay(&self, sink: &mut dyn RunSink) {
        let n = self.row_structures;
        if n > 0 && self.row_contact_width > n {
            for r in self.row_contact.chunks_exact(self.row_contact_width) {
                sink.row_contact_row(r[0], &r[1..1 + n], &r[1 + n..]);
            }
        }
        if self.contact_width >= 3 {
            for r in self.contact.chunks_exact(self.contact_width) {
                sink.contact_row(r[0], [r[1], r[2]], &r[3..]);
            }
        }
        if self.floor_width >= 1 {
            for r in self.contact_floors.chunks_exact(self.floor_width) {
                sink.contact_floor_row(r[0], &r[1..]);
            }
        }
        if n > 0 {
            for r in self.row_free.chunks_exact(1 + n) {
                sink.row_free_row(r[0], &r[1..]);
            }
        }
        for r in self.free.chunks_exact(3) {
            sink.free_row(r[0], [r[1], r[2]]);
        }
        if self.floor_width >= 1 {
            for r in self.free_floors.chunks_exact(self.floor_width) {
                sink.free_floor_row(r[0], &r[1..]);
            }
        }
    }

    /// The columns of `history.csv` (`output::run::history_header`): `t, w1, w2, force,
    /// w1_free, w2_free` and, with several levels, `force_1 … force_k`; the same numbers the
    /// file holds (`force` summed as the file sums it; a row the run without contact did not
    /// reach is NaN there, as in the file).
    pub fn history_columns(&self) -> Vec<(String, Vec<f64>)> {
        let width = self.contact_width.max(3);
        let levels = width - 3;
        let rows: Vec<&[f64]> = self.contact.chunks_exact(width).collect();
        let n = rows.len();
        let col = |f: &dyn Fn(usize, &[f64]) -> f64| -> Vec<f64> {
            rows.iter().enumerate().map(|(i, r)| f(i, r)).collect()
        };
        let free = |i: usize, k: usize| self.free.get(3 * i + k).copied().unwrap_or(f64::NAN);
        let mut out = vec![
            ("t".to_string(), col(&|_, r| r[0])),
            ("w1".to_string(), col(&|_, r| r[1])),
            ("w2".to_string(), col(&|_, r| r[2])),
            ("force".to_string(), col(&|_, r| r[3..].iter().sum())),
            ("w1_free".to_string(), (0..n).map(|i| free(i, 1)).collect()),
            ("w2_free".to_string(), (0..n).map(|i| free(i, 2)).collect()),
        ];
        if levels > 1 {
            for k in 0..levels {
                out.push((format!("force_{}", k + 1), col(&|_, r| r[3 + k])));
            }
        }
        out
    }

    /// The columns of `floors.csv` for the floor `columns` of the run
    /// (`output::run::floor_columns`): `t`, each column with pounding, then each with
    /// `_free` (without); empty when the run recorded no floor rows.
    pub fn floor_columns(&self, columns: &[String]) -> Vec<(String, Vec<f64>)> {
        let width = self.floor_width;
        if width == 0 || width != columns.len() + 1 {
            return Vec::new();
        }
        let n = self.contact_floors.len() / width;
        let mut out = Vec::with_capacity(2 * columns.len() + 1);
        let pick = |rows: &[f64], j: usize| -> Vec<f64> {
            (0..n)
                .map(|i| rows.get(i * width + j).copied().unwrap_or(f64::NAN))
                .collect()
        };
        out.push(("t".to_string(), pick(&self.contact_floors, 0)));
        for (j, c) in columns.iter().enumerate() {
            out.push((c.clone(), pick(&self.contact_floors, j + 1)));
        }
        for (j, c) in columns.iter().enumerate() {
            out.push((format!("{c}_free"), pick(&self.free_floors, j + 1)));
        }
        out
    }
}

impl RunSink for RunCapture {
    fn row_contact_row(&mut self, t: f64, w: &[f64], forces: &[f64]) {
        self.row_structures = w.len();
        self.row_contact_width = 1 + w.len() + forces.len();
        self.row_contact.push(t);
        self.row_contact.extend_from_slice(w);
        self.row_contact.extend_from_slice(forces);
    }

    fn row_free_row(&mut self, t: f64, w: &[f64]) {
        self.row_free.push(t);
        self.row_free.extend_from_slice(w);
    }

    fn contact_row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
        self.contact_width = 3 + forces.len();
        self.contact.extend_from_slice(&[t, w[0], w[1]]);
        self.contact.extend_from_slice(forces);
    }

    fn free_row(&mut self, t: f64, w: [f64; 2]) {
        self.free.extend_from_slice(&[t, w[0], w[1]]);
    }

    fn contact_floor_row(&mut self, t: f64, values: &[f64]) {
        self.floor_width = 1 + values.len();
        self.contact_floors.push(t);
        self.contact_floors.extend_from_slice(values);
    }

    fn free_floor_row(&mut self, t: f64, values: &[f64]) {
        self.free_floors.push(t);
        self.free_floors.extend_from_slice(values);
    }
}

/// Adapts a [`RunSink`] to the recorder's [`HistorySink`] for one phase.
pub(super) struct PhaseSink<'a> {
    pub(super) sink: &'a mut dyn RunSink,
    pub(super) phase: Phase,
}

impl HistorySink for PhaseSink<'_> {
    fn row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
        match self.phase {
            Phase::WithContact => self.sink.contact_row(t, w, forces),
            Phase::WithoutContact => self.sink.free_row(t, w),
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
