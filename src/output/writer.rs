//! One writer of a run's files, a pair's or a row of buildings' (docs/model.md §6): every file
//! is written to a temporary file in the target directory and renamed into place (the same
//! permissions for all), so a reader never sees a half-written file, and `summary.json` comes
//! last: its presence means every file of the run is complete and from the same run.
//!
//! [`RunWriter`] is created before the run (it removes a previous `summary.json` from the
//! directory at once), streams `history.csv` and `floors.csv` while the run goes (memory does
//! not grow with the duration) and [`RunWriter::finish`] renames them into place, writes
//! `impacts.csv`, the pictures (or removes stale ones) and, last, `summary.json`.
//!
//! What differs between a pair and a row is data: the layout of `history.csv` ([`Layout`]:
//! its columns and how a line is formed from a sample of each run) and what the report gives
//! ([`RunOutput`]: `impacts.csv` and `summary.json`, a pair's by the SPEC's output contract, a
//! row's with `structures` and `pairs`). The sequence of files, the temporary files, the
//! spooling and the failure handling are this one code path.

use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};

use crate::analysis::simulate::{Report, RowReport, RunCapture, RunSink};
use crate::input::scenario::Scenario;
use crate::output::atomic::{OutputError, temp_file, write_atomic};
use crate::output::csv::{push_field, push_number};
use crate::output::floors_csv::{FILE_NAME as FLOORS_FILE, FloorsCsv};
use crate::output::row_spool::RowSpool;
pub use crate::output::run::{DrawPictures, PICTURE_FILES, WrittenHook};

/// The layout of `history.csv`: what a spooled sample of the run with contact holds and how a
/// line is formed from it and the run without contact's sample at the same time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// A pair: `t,w1,w2,force,w1_free,w2_free` and, with several levels, `force_1 … force_k`
    /// (`force` is their sum) — the SPEC's contract
    /// ([`crate::output::run::history_header`]).
    Pair {
        /// Contact levels.
        levels: usize,
    },
    /// A row of buildings: `t`, `w_<name>` per structure, `force_<left>_<right>_<k>` per
    /// level, `w_<name>_free` per structure ([`crate::output::row::row_history_columns`]).
    Row {
        /// Structures.
        structures: usize,
        /// Contact levels of every pair.
        levels: usize,
    },
}

impl Layout {
    /// The layout of `scenario`'s history.csv.
    pub fn of(scenario: &Scenario) -> Layout {
        if scenario.is_row() {
            Layout::Row {
                structures: scenario.structures.len(),
                levels: scenario.system().levels.len(),
            }
        } else {
            Layout::Pair {
                levels: scenario.contact.levels.len(),
            }
        }
    }

    /// Displacements per sample of one run (2 for a pair).
    fn structures(self) -> usize {
        match self {
            Layout::Pair { .. } => 2,
            Layout::Row { structures, .. } => structures,
        }
    }

    /// Numbers of a spooled sample of the run with contact: t, every displacement, every
    /// level's force.
    fn width(self) -> usize {
        match self {
            Layout::Pair { levels } | Layout::Row { levels, .. } => 1 + self.structures() + levels,
        }
    }

    /// The line of history.csv (with its newline) into `out` from a spooled sample `row`
    /// ([`Layout::width`] numbers) and the run without contact's displacements `free` (NaN
    /// where missing: the run without contact did not reach that time).
    fn line(self, out: &mut Vec<u8>, row: &[f64], free: Option<&[f64]>) {
        let free = |j: usize| free.and_then(|f| f.get(j).copied()).unwrap_or(f64::NAN);
        match self {
            Layout::Pair { .. } => crate::output::run::history_row(
                out,
                row[0],
                [row[1], row[2]],
                &row[3..],
                [free(0), free(1)],
            ),
            Layout::Row { structures, .. } => {
                push_number(out, row[0]);
                for &v in &row[1..] {
                    push_field(out, v);
                }
                for j in 0..structures {
                    push_field(out, free(j));
                }
                out.push(b'\n');
            }
        }
    }
}

/// What [`RunWriter::finish`] takes from a run's report: its `impacts.csv` and its
/// `summary.json` (a pair's [`Report`], a row's [`RowReport`]).
pub trait RunOutput {
    /// `impacts.csv`: one row per contact episode.
    fn impacts_csv(&self) -> String;
    /// `summary.json` of this report of `scenario`, with a suite's section `suite` last.
    fn summary_json(
        &self,
        scenario: &Scenario,
        suite: Option<&serde_json::Value>,
    ) -> Result<String, String>;
}

impl RunOutput for Report {
    fn impacts_csv(&self) -> String {
        crate::output::run::impacts_csv(self)
    }
    fn summary_json(
        &self,
        scenario: &Scenario,
        suite: Option<&serde_json::Value>,
    ) -> Result<String, String> {
        crate::output::run::summary_json_with(scenario, self, suite)
    }
}

impl RunOutput for RowReport {
    fn impacts_csv(&self) -> String {
        crate::output::row::row_impacts_csv(self)
    }
    fn summary_json(
        &self,
        scenario: &Scenario,
        suite: Option<&serde_json::Value>,
    ) -> Result<String, String> {
        crate::output::row::row_summary_json_with(scenario, self, suite)
    }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Remove `dir/name` if it is there.
pub(crate) fn remove_stale(dir: &Path, name: &str) -> Result<(), OutputError> {
    let p = dir.join(name);
    match std::fs::remove_file(&p) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(io(&p)(e)),
    }
}

/// Writes one run — a pair's or a row's ([`Layout`]) — into a directory: streams
/// `history.csv` (and `floors.csv`) during the run (it is the run's [`RunSink`]) and writes
/// the rest in [`RunWriter::finish`], `summary.json` last.
///
/// The run with contact comes first ([`crate::analysis::simulate::simulate_streaming`],
/// [`crate::analysis::simulate::simulate_row_streaming`]); its samples are spooled in binary
/// to an anonymous temporary file (8 bytes per number), and each sample of the run without
/// contact completes one line of the CSV. Memory holds one line.
pub struct RunWriter {
    dir: PathBuf,
    layout: Layout,
    /// history.csv being written (temporary name until `finish`).
    csv: Option<BufWriter<tempfile::NamedTempFile>>,
    /// The samples with contact: t, every displacement, every level's force.
    spool: RowSpool,
    /// Reused text buffer of one CSV line.
    line: Vec<u8>,
    /// Reused spooled sample.
    row: Vec<f64>,
    /// The first I/O error met while streaming (reported by `finish`).
    error: Option<OutputError>,
    /// Called with each file once it is complete and in place, in order.
    on_written: Option<Box<WrittenHook>>,
    /// The directory did not exist before: a run that fails removes it again (if empty).
    created_dir: bool,
    /// floors.csv being written, when asked for ([`RunWriter::with_floors`]).
    floors: Option<FloorsCsv>,
    /// A suite's section of summary.json ([`RunWriter::with_suite`]).
    suite: Option<serde_json::Value>,
}

impl Drop for RunWriter {
    /// A writer dropped before [`RunWriter::finish`] completes (the run failed) deletes its
    /// temporary files and the directory it created, if nothing else is in it.
    fn drop(&mut self) {
        self.csv.take();
        self.floors.take();
        if self.created_dir {
            let _ = std::fs::remove_dir(&self.dir);
        }
    }
}

impl std::fmt::Debug for RunWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RunWriter")
            .field("dir", &self.dir)
            .field("layout", &self.layout)
            .finish_non_exhaustive()
    }
}

impl RunWriter {
    /// Prepare `dir` (created if needed) for a pair's run with `levels` contact levels, without
    /// `floors.csv` ([`RunWriter::with_floors`] adds it): remove a `summary.json` left there by
    /// an earlier run (a summary must never describe other files than its own run's) and open
    /// the temporary history files.
    pub fn create(dir: &Path, levels: usize) -> Result<RunWriter, OutputError> {
        RunWriter::with_layout(
            dir,
            Layout::Pair { levels },
            &crate::output::run::history_header(levels),
        )
    }

    /// The writer of a run of `scenario` into `dir`, as `pounding run` creates it: a pair's
    /// history.csv (one force column per contact level) or a row's ([`Layout::of`]), and
    /// `floors.csv` with the run's floor columns ([`crate::output::run::floor_columns`],
    /// [`crate::output::row::row_floor_columns`]).
    pub fn for_scenario(dir: &Path, scenario: &Scenario) -> Result<RunWriter, OutputError> {
        let layout = Layout::of(scenario);
        let (header, floors) = match layout {
            Layout::Pair { levels } => (
                crate::output::run::history_header(levels),
                crate::output::run::floor_columns(scenario),
            ),
            Layout::Row { .. } => (
                crate::output::row::row_history_header(scenario),
                crate::output::row::row_floor_columns(scenario),
            ),
        };
        RunWriter::with_layout(dir, layout, &header)?.with_floors(&floors)
    }

    /// Prepare `dir` for a run whose history.csv has `layout` and the header line `header`
    /// (without its newline).
    fn with_layout(dir: &Path, layout: Layout, header: &str) -> Result<RunWriter, OutputError> {
        let created_dir = !dir.exists();
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        remove_stale(dir, "summary.json")?;
        let history = dir.join("history.csv");
        let tmp = temp_file(dir, ".pounding-history-", ".tmp").map_err(io(&history))?;
        let mut csv = BufWriter::with_capacity(1 << 16, tmp);
        writeln!(csv, "{header}").map_err(io(&history))?;
        let width = layout.width();
        let spool = RowSpool::new(dir, width).map_err(io(&history))?;
        Ok(RunWriter {
            dir: dir.to_path_buf(),
            layout,
            csv: Some(csv),
            spool,
            line: Vec::with_capacity(24 * (width + layout.structures())),
            row: vec![0.0; width],
            error: None,
            on_written: None,
            created_dir,
            floors: None,
            suite: None,
        })
    }

    /// Also write `floors.csv`, the floor histories with the names `columns` (a pair's
    /// [`crate::recording::floor_response::FloorRecorder::columns`], a row's
    /// [`crate::output::row::row_floor_columns`]; written after impacts.csv).
    pub fn with_floors(mut self, columns: &[String]) -> Result<RunWriter, OutputError> {
        let path = self.dir.join(FLOORS_FILE);
        self.floors = Some(FloorsCsv::create(&self.dir, columns).map_err(io(&path))?);
        Ok(self)
    }

    /// Add `section` as the key `suite` of summary.json (a suite of records, written by the
    /// suite driver of the study layer).
    pub fn with_suite(mut self, section: serde_json::Value) -> RunWriter {
        self.suite = Some(section);
        self
    }

    /// Call `hook` with the path of every file once it is complete and in place, in the order
    /// they are written (tests use it to check that `summary.json` comes last).
    pub fn on_written(mut self, hook: impl FnMut(&Path) + 'static) -> RunWriter {
        self.on_written = Some(Box::new(hook));
        self
    }

    fn fail(&mut self, source: std::io::Error) {
        if self.error.is_none() {
            self.error = Some(OutputError::Io {
                path: self.dir.join("history.csv"),
                source,
            });
        }
    }

    /// The spooled sample in `self.row` with `free` (the run without contact's) as a line of
    /// history.csv.
    fn write_line(&mut self, free: Option<&[f64]>) {
        self.line.clear();
        self.layout.line(&mut self.line, &self.row, free);
        if let Some(csv) = self.csv.as_mut()
            && let Err(e) = csv.write_all(&self.line)
        {
            self.fail(e);
        }
    }

    /// A sample of the run with contact: `t`, the displacements `w` and the levels' forces.
    fn push(&mut self, t: f64, w: &[f64], forces: &[f64]) {
        let n = self.layout.structures();
        self.spool.push(
            std::iter::once(t)
                .chain(w.iter().copied().chain(std::iter::repeat(f64::NAN)).take(n))
                .chain(forces.iter().copied()),
        );
    }

    /// A sample of the run without contact completes the next spooled line.
    fn complete(&mut self, w: &[f64]) {
        self.spool.rewind();
        if self.spool.next(&mut self.row) {
            self.write_line(Some(w));
        }
    }

    /// Rename the history into place, write `impacts.csv` and `floors.csv`, then the pictures
    /// (`draw`, e.g. `figures::run::run_pictures`, `figures::row::row_pictures`)
    /// — or, without `draw`, remove the pictures ([`PICTURE_FILES`]) an earlier run left — and
    /// last `summary.json`. Returns the files written, in the order written (`summary.json`
    /// last). A failure at any point leaves no summary.
    pub fn finish<R: RunOutput + ?Sized>(
        mut self,
        scenario: &Scenario,
        report: &R,
        draw: Option<Box<DrawPictures<'_>>>,
    ) -> Result<Vec<PathBuf>, OutputError> {
        let written = self.finish_files(report, draw)?;
        self.finish_summary(scenario, report, written)
    }

    /// [`RunWriter::finish`] but for `summary.json`: the history renamed into place,
    /// `impacts.csv`, `floors.csv` and the pictures (`draw`) or the stale ones removed. For a
    /// caller that writes them before the report is complete (`pounding run` while its
    /// self-check goes on, [`crate::analysis::simulate::simulate_streaming_beside`]): none of
    /// them reads the self-check. Returns the files written, in order;
    /// [`RunWriter::finish_summary`] completes the run.
    pub fn finish_files<R: RunOutput + ?Sized>(
        &mut self,
        report: &R,
        draw: Option<Box<DrawPictures<'_>>>,
    ) -> Result<Vec<PathBuf>, OutputError> {
        // samples with contact the run without contact did not match (none, normally)
        self.spool.rewind();
        while self.spool.next(&mut self.row) {
            self.write_line(None);
        }
        if let Some(e) = self.spool.take_error() {
            self.fail(e);
        }
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let mut written = Vec::new();
        let history = self.dir.join("history.csv");
        if let Some(csv) = self.csv.take() {
            let tmp = csv.into_inner().map_err(|e| io(&history)(e.into_error()))?;
            crate::output::atomic::persist(tmp, &history).map_err(io(&history))?;
        }
        self.written(&history, &mut written);
        let impacts = self.dir.join("impacts.csv");
        write_atomic(&impacts, report.impacts_csv().as_bytes())?;
        self.written(&impacts, &mut written);
        if let Some(f) = self.floors.take() {
            let path = self.dir.join(FLOORS_FILE);
            let done = f.finish().map_err(io(&path))?;
            self.written(&done, &mut written);
        }
        match draw {
            Some(draw) => {
                let files = draw(&self.dir).map_err(|message| OutputError::Encode {
                    path: self.dir.join(PICTURE_FILES[0]),
                    message: format!(
                        "{message} (history.csv and impacts.csv are written; summary.json is not)"
                    ),
                })?;
                for f in files {
                    self.written(&f, &mut written);
                }
            }
            None => {
                for name in PICTURE_FILES {
                    remove_stale(&self.dir, name)?;
                }
            }
        }
        Ok(written)
    }

    /// `summary.json` of the complete `report`, last, after [`RunWriter::finish_files`]
    /// (which wrote the files `written`); returns them with it.
    pub fn finish_summary<R: RunOutput + ?Sized>(
        mut self,
        scenario: &Scenario,
        report: &R,
        mut written: Vec<PathBuf>,
    ) -> Result<Vec<PathBuf>, OutputError> {
        let summary = self.dir.join("summary.json");
        let json = report
            .summary_json(scenario, self.suite.as_ref())
            .map_err(|message| OutputError::Encode {
                path: summary.clone(),
                message,
            })?;
        write_atomic(&summary, json.as_bytes())?;
        self.written(&summary, &mut written);
        self.created_dir = false;
        Ok(written)
    }

    fn written(&mut self, path: &Path, list: &mut Vec<PathBuf>) {
        if let Some(h) = self.on_written.as_mut() {
            h(path);
        }
        list.push(path.to_path_buf());
    }
}

impl RunSink for RunWriter {
    fn contact_floor_row(&mut self, t: f64, values: &[f64]) {
        if let Some(f) = self.floors.as_mut() {
            f.contact_row(t, values);
        }
    }

    fn free_floor_row(&mut self, t: f64, values: &[f64]) {
        if let Some(f) = self.floors.as_mut() {
            f.free_row(t, values);
        }
    }

    fn contact_row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
        self.push(t, &w, forces);
    }

    fn free_row(&mut self, _t: f64, w: [f64; 2]) {
        self.complete(&w);
    }

    fn row_contact_row(&mut self, t: f64, w: &[f64], forces: &[f64]) {
        self.push(t, w, forces);
    }

    fn row_free_row(&mut self, _t: f64, w: &[f64]) {
        self.complete(w);
    }
}

/// Write a run already done into `dir` exactly as `pounding run --out dir` does while it
/// runs: the samples in `capture` are replayed into the [`RunWriter`] of the scenario
/// ([`RunWriter::for_scenario`]: a pair's or a row's), then [`RunWriter::finish`] (pictures by
/// `draw`; without, stale pictures are removed; `summary.json` last). Returns the files
/// written, in order.
pub fn write_run<R: RunOutput + ?Sized>(
    dir: &Path,
    scenario: &Scenario,
    report: &R,
    capture: &RunCapture,
    draw: Option<Box<DrawPictures<'_>>>,
) -> Result<Vec<PathBuf>, OutputError> {
    let mut writer = RunWriter::for_scenario(dir, scenario)?;
    capture.replay(&mut writer);
    writer.finish(scenario, report, draw)
}
