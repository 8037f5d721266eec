//! The files of a suite run on a row of buildings, written as a run's are (temporary file then
//! rename, the same permissions, the top-level `summary.json` last):
//!
//! - `suite.csv`: one row per record — `record` (1-based), `file`, `component`, `factor`, the
//!   row's headline numbers ([`super::Headline::of_row`]: per structure and per pair, named as
//!   a row's sweep columns) and `converged`;
//! - `records/NN/` (NN = 1-based record number, zero-padded to the count's width): each
//!   record's run of the row as `pounding run` writes a row's (history.csv, impacts.csv,
//!   floors.csv, its pictures, summary.json);
//! - the representative record's run ([`super::row::RowSuiteRun::representative`]) at the top
//!   level, as a row's run, and `summary.json`'s `suite` section ([`row_section`]): `records`,
//!   `scaling`, `statistics`, `design` (with `pairs`), `representative`,
//!   `representative_file`, `record_dirs`.

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use super::row::RowSuiteRun;
use super::write::{CSV_FILE, PICTURE_FILES, record_entries, records_csv, scaling_section};
use crate::output::atomic::{OutputError, write_atomic};
use crate::output::row::{RowWriter, write_row};
use crate::output::run::DrawPictures;

/// The folder of the records' own runs.
pub const RECORDS_DIR: &str = "records";

/// The folder of record `i` (0-based) of `n`, relative to the output directory:
/// `records/01` … (zero-padded to the width of `n`).
pub fn record_dir(i: usize, n: usize) -> String {
    let width = n.to_string().len().max(2);
    format!("{RECORDS_DIR}/{:0width$}", i + 1)
}

/// `suite.csv` of a row: a header, then one row per record in the scenario's order.
pub fn row_suite_csv(run: &RowSuiteRun) -> String {
    records_csv(run.records.iter().map(|r| {
        (
            r.file.as_str(),
            r.component.as_deref(),
            r.factor,
            &r.headline,
        )
    }))
}

/// The `suite` section of a row's summary.json: a pair suite's keys (`records`, `scaling`,
/// `statistics`, `design`, `representative`, `representative_file`) with `design` per pair
/// ([`super::row::RowDesign`]: `pairs`, `governing_pair`, `governing_level`,
/// `insufficient_pairs`), and `record_dirs` (each record's run, relative to the directory).
pub fn row_section(run: &RowSuiteRun) -> Value {
    let n = run.records.len();
    let records = record_entries(run.records.iter().map(|r| {
        (
            r.file.as_str(),
            r.component.as_deref(),
            r.factor,
            &r.headline,
            r.report.warnings.as_slice(),
        )
    }));
    json!({
        "records": records,
        "scaling": scaling_section(
            run.rule,
            run.scaling.as_ref(),
            run.records.iter().map(|r| r.factor).collect()
        ),
        "statistics": run.statistics,
        "design": run.design,
        "representative": run.representative + 1,
        "representative_file": run.records[run.representative].file,
        "record_dirs": (0..n).map(|i| record_dir(i, n)).collect::<Vec<_>>(),
    })
}

/// Write a row's suite run into `dir`: each record's run into its folder ([`record_dir`],
/// pictures by `draw_record(i)`, none where it gives `None`), `suite.csv`, then the
/// representative record's run at the top level as `pounding run` writes a row (the pictures
/// `draw` draws, or the stale ones removed) and last `summary.json` with the `suite` section.
/// Returns the files written, in order.
pub fn write_row_suite<'a>(
    dir: &Path,
    run: &'a RowSuiteRun,
    draw: Option<Box<DrawPictures<'a>>>,
    mut draw_record: impl FnMut(usize) -> Option<Box<DrawPictures<'a>>>,
) -> Result<Vec<PathBuf>, OutputError> {
    let rep = &run.records[run.representative];
    // (created first: it removes a summary.json an earlier run left)
    let mut writer = RowWriter::for_scenario(dir, &rep.scenario)?.with_suite(row_section(run));
    let n = run.records.len();
    let mut written = Vec::new();
    for (i, r) in run.records.iter().enumerate() {
        let sub = dir.join(record_dir(i, n));
        written.extend(write_row(
            &sub,
            &r.scenario,
            &r.report,
            &r.capture,
            draw_record(i),
        )?);
    }
    let csv = dir.join(CSV_FILE);
    write_atomic(&csv, row_suite_csv(run).as_bytes())?;
    written.push(csv);
    if draw.is_none() {
        for name in PICTURE_FILES {
            let p = dir.join(name);
            match std::fs::remove_file(&p) {
                Ok(()) => {}
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                Err(source) => return Err(OutputError::Io { path: p, source }),
            }
        }
    }
    rep.capture.replay(&mut writer);
    written.extend(writer.finish(&rep.scenario, &rep.report, draw)?);
    Ok(written)
}
