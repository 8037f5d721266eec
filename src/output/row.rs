//! The files of a row of buildings' run (issue 29), as a pair's are written: `history.csv`
//! and `floors.csv` streamed during the run (temporary files, renamed when complete; memory
//! holds one row), then `impacts.csv` (one row per contact episode, naming its pair), the
//! pictures ([`crate::figures::row`]) and `summary.json` last (the row's [`RowReport`]:
//! `structures`, `pairs`, `verdict`, `accuracy`, …, with the solver's facts and the defaults
//! applied).
//!
//! A row's `history.csv` is a layout of its own (a pair's is unchanged): `t`, then `w_<name>`
//! for every structure (its displacement at its headline height — its highest contact level
//! with either neighbour, where summary.json's `peak_displacement` is — m), `force_<left>_
//! <right>_<k>` for every pair and level k (1-based, in the order of the pair's `[[contact]]`
//! table; N), then `w_<name>_free` (without contact). A row's `floors.csv`: `t`, `w_<name>_<h>`
//! and `a_<name>_<h>` (displacement, m; absolute acceleration, m/s²) for every structure and
//! station (height h, m), then the same with `_free`.

use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::analysis::simulate::{RowReport, RunCapture, RunSink};
use crate::input::scenario::Scenario;
use crate::output::atomic::{OutputError, temp_file, write_atomic};
use crate::output::csv::{push_field, push_number};
use crate::output::row_spool::RowSpool;
use crate::output::run::{DrawPictures, PICTURE_FILES};

#[derive(Debug, Serialize)]
struct RowSummary<'a> {
    #[serde(flatten)]
    report: &'a RowReport,
    solver: super::run::SolverInfo,
    defaults_applied: &'a [String],
    /// A suite's own section ([`RowWriter::with_suite`]); absent for one record.
    #[serde(skip_serializing_if = "Option::is_none")]
    suite: Option<&'a serde_json::Value>,
}

/// A row's summary as JSON text.
pub fn row_summary_json(scenario: &Scenario, report: &RowReport) -> Result<String, String> {
    row_summary_json_with(scenario, report, None)
}

/// [`row_summary_json`] with a suite's section `suite` last (the other keys are then the run
/// of the suite's representative record, `scenario`).
pub fn row_summary_json_with(
    scenario: &Scenario,
    report: &RowReport,
    suite: Option<&serde_json::Value>,
) -> Result<String, String> {
    let s = RowSummary {
        report,
        solver: super::run::SolverInfo::new(
            scenario,
            &report.stats,
            (&report.energy, &report.energy_no_contact),
        ),
        defaults_applied: &scenario.defaults_applied,
        suite,
    };
    serde_json::to_string_pretty(&s).map_err(|e| e.to_string())
}

/// `impacts.csv` of a row: `pair,left,right,level,height,start,end,duration,peak_force,
/// impulse,max_penetration,approach_speed` (`pair` 1-based: structures `pair` and `pair + 1`;
/// `level` 1-based within the pair's `[[contact]]` table).
pub fn row_impacts_csv(report: &RowReport) -> String {
    let mut out = String::from(
        "pair,left,right,level,height,start,end,duration,peak_force,impulse,max_penetration,\
         approach_speed\n",
    );
    let mut row = Vec::with_capacity(200);
    for i in &report.impact_log {
        row.clear();
        row.extend_from_slice((i.pair + 1).to_string().as_bytes());
        for name in &report.pairs[i.pair].between {
            row.push(b',');
            row.extend_from_slice(csv_text(name).as_bytes());
        }
        row.push(b',');
        row.extend_from_slice((i.level + 1).to_string().as_bytes());
        for v in [
            i.height,
            i.start,
            i.end,
            i.end - i.start,
            i.peak_force,
            i.impulse,
            i.max_penetration,
            i.approach_speed,
        ] {
            push_field(&mut row, v);
        }
        row.push(b'\n');
        out.push_str(&String::from_utf8_lossy(&row));
    }
    out
}

/// A name as a CSV field (quoted when it holds a comma, a quote or a line break).
fn csv_text(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The header of a row's `history.csv` (without the newline): `t`, `w_<name>` per structure,
/// `force_<left>_<right>_<k>` per pair and level, `w_<name>_free` per structure (see the
/// module).
pub fn row_history_header(scenario: &Scenario) -> String {
    row_history_columns(scenario)
        .iter()
        .map(|c| csv_text(c))
        .collect::<Vec<_>>()
        .join(",")
}

/// The names of a row's `history.csv` columns, in order (unquoted).
pub fn row_history_columns(scenario: &Scenario) -> Vec<String> {
    let names: Vec<&str> = scenario.structures.iter().map(|s| s.name()).collect();
    let system = scenario.system();
    let mut out = vec!["t".to_string()];
    out.extend(names.iter().map(|n| format!("w_{n}")));
    let mut k = 0;
    for (j, l) in system.levels.iter().enumerate() {
        k = if j > 0 && system.levels[j - 1].pair == l.pair {
            k + 1
        } else {
            1
        };
        out.push(format!("force_{}_{}_{k}", names[l.pair], names[l.pair + 1]));
    }
    out.extend(names.iter().map(|n| format!("w_{n}_free")));
    out
}

/// The floor columns of a row's run (`floors.csv` without `t` and the `_free` copies):
/// `w_<name>_<h>`, `a_<name>_<h>` for every station that `scenario.floor_stations` keeps.
pub fn row_floor_columns(scenario: &Scenario) -> Vec<String> {
    let system = scenario.system();
    let heights: Vec<f64> = system.levels.iter().map(|l| l.height).collect();
    let pairs: Vec<usize> = system.levels.iter().map(|l| l.pair).collect();
    let floors = crate::recording::floor_response::FloorRecorder::for_row(
        &system,
        &heights,
        &pairs,
        scenario.output_interval,
    );
    let mut all = Vec::new();
    for (s, st) in scenario.structures.iter().zip(floors.station_heights()) {
        for h in st {
            all.push(format!("w_{}_{h}", s.name()));
            all.push(format!("a_{}_{h}", s.name()));
        }
    }
    match scenario
        .floor_stations
        .selection(&system, &floors, &heights)
    {
        None => all,
        Some(keep) => keep.iter().filter_map(|&i| all.get(i).cloned()).collect(),
    }
}

/// Writes a row's run into a directory: streams `history.csv` and `floors.csv` during the run
/// (it is the run's [`RunSink`]: the rows of the run with contact spooled in binary, each row
/// of the run without contact completing one line) and writes the rest in
/// [`RowWriter::finish`], `summary.json` last.
pub struct RowWriter {
    dir: PathBuf,
    /// Structures and contact levels of the row.
    structures: usize,
    levels: usize,
    csv: Option<BufWriter<tempfile::NamedTempFile>>,
    /// The rows with contact: t, every structure's w, every level's force.
    spool: RowSpool,
    line: Vec<u8>,
    row: Vec<f64>,
    error: Option<OutputError>,
    created_dir: bool,
    floors: Option<crate::output::floors_csv::FloorsCsv>,
    /// A suite's section of summary.json ([`RowWriter::with_suite`]).
    suite: Option<serde_json::Value>,
}

impl std::fmt::Debug for RowWriter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RowWriter")
            .field("dir", &self.dir)
            .field("structures", &self.structures)
            .field("levels", &self.levels)
            .finish_non_exhaustive()
    }
}

impl Drop for RowWriter {
    /// A writer dropped before [`RowWriter::finish`] completes (the run failed) deletes its
    /// temporary files and the directory it created, if nothing else is in it.
    fn drop(&mut self) {
        self.csv.take();
        self.floors.take();
        if self.created_dir {
            let _ = std::fs::remove_dir(&self.dir);
        }
    }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Remove `dir/name` if it is there.
fn remove_stale(dir: &Path, name: &str) -> Result<(), OutputError> {
    let p = dir.join(name);
    match std::fs::remove_file(&p) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(io(&p)(e)),
    }
}

impl RowWriter {
    /// Prepare `dir` (created if needed) for a run of the row `scenario`: remove a
    /// `summary.json` an earlier run left (a summary must never describe other files than its
    /// own run's) and open the temporary `history.csv` and `floors.csv`.
    pub fn for_scenario(dir: &Path, scenario: &Scenario) -> Result<RowWriter, OutputError> {
        let created_dir = !dir.exists();
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        remove_stale(dir, "summary.json")?;
        let history = dir.join("history.csv");
        let tmp = temp_file(dir, ".pounding-history-", ".tmp").map_err(io(&history))?;
        let mut csv = BufWriter::with_capacity(1 << 16, tmp);
        writeln!(csv, "{}", row_history_header(scenario)).map_err(io(&history))?;
        let structures = scenario.structures.len();
        let levels = scenario.system().levels.len();
        let width = 1 + structures + levels;
        let spool = RowSpool::new(dir, width).map_err(io(&history))?;
        let floors_path = dir.join(crate::output::floors_csv::FILE_NAME);
        let floors =
            crate::output::floors_csv::FloorsCsv::create(dir, &row_floor_columns(scenario))
                .map_err(io(&floors_path))?;
        Ok(RowWriter {
            dir: dir.to_path_buf(),
            structures,
            levels,
            csv: Some(csv),
            spool,
            line: Vec::with_capacity(24 * (1 + 2 * structures + levels)),
            row: vec![0.0; width],
            error: None,
            created_dir,
            floors: Some(floors),
            suite: None,
        })
    }

    /// Add `section` as the key `suite` of summary.json (a suite of records on a row, written
    /// by the suite driver of the study layer).
    pub fn with_suite(mut self, section: serde_json::Value) -> RowWriter {
        self.suite = Some(section);
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

    /// The spooled row with contact, then `free` (NaN: the run without contact did not
    /// reach it), as a line of history.csv.
    fn write_line(&mut self, free: Option<&[f64]>) {
        self.line.clear();
        push_number(&mut self.line, self.row[0]);
        for &v in &self.row[1..] {
            push_field(&mut self.line, v);
        }
        for j in 0..self.structures {
            push_field(
                &mut self.line,
                free.and_then(|f| f.get(j).copied()).unwrap_or(f64::NAN),
            );
        }
        self.line.push(b'\n');
        if let Some(csv) = self.csv.as_mut()
            && let Err(e) = csv.write_all(&self.line)
        {
            self.fail(e);
        }
    }

    /// Rename `history.csv` and `floors.csv` into place, write `impacts.csv`, the pictures
    /// (`draw`, e.g. [`crate::figures::row::row_pictures`]) — or, without, remove those an
    /// earlier run left — and last `summary.json`. Returns the files written, in order.
    pub fn finish(
        mut self,
        scenario: &Scenario,
        report: &RowReport,
        draw: Option<Box<DrawPictures<'_>>>,
    ) -> Result<Vec<PathBuf>, OutputError> {
        // rows with contact the run without contact did not match (none, normally)
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
            tmp.as_file().sync_all().map_err(io(&history))?;
            tmp.persist(&history).map_err(|e| io(&history)(e.error))?;
        }
        written.push(history);
        let impacts = self.dir.join("impacts.csv");
        write_atomic(&impacts, row_impacts_csv(report).as_bytes())?;
        written.push(impacts);
        if let Some(f) = self.floors.take() {
            let path = self.dir.join(crate::output::floors_csv::FILE_NAME);
            written.push(f.finish().map_err(io(&path))?);
        }
        match draw {
            Some(draw) => {
                let files = draw(&self.dir).map_err(|message| OutputError::Encode {
                    path: self.dir.join(PICTURE_FILES[0]),
                    message: format!(
                        "{message} (history.csv and impacts.csv are written; summary.json is not)"
                    ),
                })?;
                written.extend(files);
            }
            None => {
                for name in PICTURE_FILES {
                    remove_stale(&self.dir, name)?;
                }
            }
        }
        let summary = self.dir.join("summary.json");
        let json =
            row_summary_json_with(scenario, report, self.suite.as_ref()).map_err(|message| {
                OutputError::Encode {
                    path: summary.clone(),
                    message,
                }
            })?;
        write_atomic(&summary, json.as_bytes())?;
        written.push(summary);
        self.created_dir = false;
        Ok(written)
    }
}

impl RunSink for RowWriter {
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

    fn row_contact_row(&mut self, t: f64, w: &[f64], forces: &[f64]) {
        let (n, l) = (self.structures, self.levels);
        self.spool.push(
            std::iter::once(t)
                .chain(w.iter().copied().chain(std::iter::repeat(f64::NAN)).take(n))
                .chain(forces.iter().copied().take(l)),
        );
    }

    fn row_free_row(&mut self, _t: f64, w: &[f64]) {
        self.spool.rewind();
        if self.spool.next(&mut self.row) {
            self.write_line(Some(w));
        }
    }
}

/// Write a row's run already done into `dir` exactly as `pounding run --out dir` does while it
/// runs: the samples in `capture` replayed into a [`RowWriter`], then [`RowWriter::finish`]
/// (pictures by `draw`; `summary.json` last). Returns the files written, in order.
pub fn write_row(
    dir: &Path,
    scenario: &Scenario,
    report: &RowReport,
    capture: &RunCapture,
    draw: Option<Box<DrawPictures<'_>>>,
) -> Result<Vec<PathBuf>, OutputError> {
    let mut writer = RowWriter::for_scenario(dir, scenario)?;
    capture.replay(&mut writer);
    writer.finish(scenario, report, draw)
}

/// Columns of numbers by name, in order.
pub type NamedColumns = Vec<(String, Vec<f64>)>;

/// The columns of a row's `history.csv` ([`row_history_columns`]) from a captured run
/// (`capture`, [`RunCapture`]): the same numbers the file holds (a row the run without contact
/// did not reach is NaN there, as in the file). Empty when the capture holds no row.
pub fn row_history_table(scenario: &Scenario, capture: &RunCapture) -> Vec<(String, Vec<f64>)> {
    let n = capture.row_structures;
    let width = capture.row_contact_width;
    if n == 0 || width <= n {
        return Vec::new();
    }
    let rows = capture.row_contact.len() / width;
    let free = |i: usize, j: usize| {
        capture
            .row_free
            .get(i * (1 + n) + 1 + j)
            .copied()
            .unwrap_or(f64::NAN)
    };
    let names = row_history_columns(scenario);
    let mut out = Vec::with_capacity(names.len());
    for (c, name) in names.into_iter().enumerate() {
        let col: Vec<f64> = if c < width {
            (0..rows)
                .map(|i| capture.row_contact[i * width + c])
                .collect()
        } else {
            (0..rows).map(|i| free(i, c - width)).collect()
        };
        out.push((name, col));
    }
    out
}

/// A row's arrays per structure, from a captured run: for each structure (row order) its name
/// and `t` (s), `w` (with pounding) and `w_free` (without; m) at its headline height — the
/// `t`, `w_<name>` and `w_<name>_free` columns of history.csv.
pub fn row_structure_series(
    scenario: &Scenario,
    capture: &RunCapture,
) -> Vec<(String, NamedColumns)> {
    let table = row_history_table(scenario, capture);
    let Some((_, t)) = table.first() else {
        return Vec::new();
    };
    let find = |name: &str| {
        (table.iter())
            .find(|(c, _)| c == name)
            .map_or_else(Vec::new, |(_, v)| v.clone())
    };
    (scenario.structures.iter())
        .map(|s| {
            let n = s.name();
            (
                n.to_string(),
                vec![
                    ("t".to_string(), t.clone()),
                    ("w".to_string(), find(&format!("w_{n}"))),
                    ("w_free".to_string(), find(&format!("w_{n}_free"))),
                ],
            )
        })
        .collect()
}

/// A row's arrays per adjacent pair, from a captured run: for each pair (row order) its two
/// names and `t` (s), `force` (the sum over its levels, N, summed as a pair's history.csv sums
/// them) and, with several levels, `force_1 … force_k` — a pair's history.csv force columns.
pub fn row_pair_series(
    scenario: &Scenario,
    capture: &RunCapture,
) -> Vec<([String; 2], NamedColumns)> {
    let n = capture.row_structures;
    let width = capture.row_contact_width;
    if n == 0 || width <= n {
        return Vec::new();
    }
    let system = scenario.system();
    let rows: Vec<&[f64]> = capture.row_contact.chunks_exact(width).collect();
    let t: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let mut out = Vec::new();
    let mut first = 0;
    for p in 0..scenario.structures.len().saturating_sub(1) {
        let count = system.levels.iter().filter(|l| l.pair == p).count();
        let range = 1 + n + first..1 + n + first + count;
        first += count;
        let mut cols = vec![
            ("t".to_string(), t.clone()),
            (
                "force".to_string(),
                rows.iter().map(|r| r[range.clone()].iter().sum()).collect(),
            ),
        ];
        if count > 1 {
            for (k, j) in range.enumerate() {
                cols.push((
                    format!("force_{}", k + 1),
                    rows.iter().map(|r| r[j]).collect(),
                ));
            }
        }
        let between = [p, p + 1].map(|i| scenario.structures[i].name().to_string());
        out.push((between, cols));
    }
    out
}

/// The columns of a row's `impacts.csv` ([`row_impacts_csv`]), by its header names: `pair`
/// and `level` (1-based) whole numbers, `left` and `right` the names, the rest the numbers
/// the file holds.
pub fn row_impact_columns(report: &RowReport) -> Vec<(&'static str, crate::output::run::Column)> {
    use crate::output::run::Column;
    let log = &report.impact_log;
    let f = |g: &dyn Fn(&crate::analysis::simulate::RowImpact) -> f64| {
        Column::Float(log.iter().map(g).collect())
    };
    let name = |side: usize| {
        Column::Text(
            log.iter()
                .map(|i| report.pairs[i.pair].between[side].clone())
                .collect(),
        )
    };
    vec![
        (
            "pair",
            Column::Int(log.iter().map(|i| i.pair as i64 + 1).collect()),
        ),
        ("left", name(0)),
        ("right", name(1)),
        (
            "level",
            Column::Int(log.iter().map(|i| i.level as i64 + 1).collect()),
        ),
        ("height", f(&|i| i.height)),
        ("start", f(&|i| i.start)),
        ("end", f(&|i| i.end)),
        ("duration", f(&|i| i.end - i.start)),
        ("peak_force", f(&|i| i.peak_force)),
        ("impulse", f(&|i| i.impulse)),
        ("max_penetration", f(&|i| i.max_penetration)),
        ("approach_speed", f(&|i| i.approach_speed)),
    ]
}
