//! The files of a row of buildings' run (issue 29): `summary.json` (the row's
//! [`RowReport`]: `structures`, `pairs`, `verdict`, …, with the solver's facts and the defaults
//! applied) and `impacts.csv` (one row per contact episode, naming its pair). A row's run
//! writes no `history.csv`, `floors.csv` or pictures yet: [`write_row`] removes those an
//! earlier run left in the directory, so that nothing there describes another run.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::analysis::simulate::RowReport;
use crate::input::scenario::Scenario;
use crate::output::atomic::{OutputError, write_atomic};
use crate::output::csv::push_field;

/// The files of a pair's run that a row's run does not write (removed when stale).
const NOT_WRITTEN: [&str; 2] = ["history.csv", crate::output::floors_csv::FILE_NAME];

#[derive(Debug, Serialize)]
struct RowSummary<'a> {
    #[serde(flatten)]
    report: &'a RowReport,
    solver: super::run::SolverInfo,
    defaults_applied: &'a [String],
}

/// A row's summary as JSON text.
pub fn row_summary_json(scenario: &Scenario, report: &RowReport) -> Result<String, String> {
    let s = RowSummary {
        report,
        solver: super::run::SolverInfo::new(
            scenario,
            &report.stats,
            (&report.energy, &report.energy_no_contact),
        ),
        defaults_applied: &scenario.defaults_applied,
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

/// Write a row's run into `dir` (created if needed): `summary.json` of an earlier run removed
/// first, then `impacts.csv`, the stale files of a pair's run removed, `summary.json` last.
/// Returns the files written.
pub fn write_row(
    dir: &Path,
    scenario: &Scenario,
    report: &RowReport,
) -> Result<Vec<PathBuf>, OutputError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| OutputError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let summary = dir.join("summary.json");
    let stale = NOT_WRITTEN
        .iter()
        .chain(&crate::output::run::PICTURE_FILES)
        .copied();
    for name in std::iter::once("summary.json").chain(stale) {
        let p = dir.join(name);
        match std::fs::remove_file(&p) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(io(&p)(e)),
        }
    }
    let impacts = dir.join("impacts.csv");
    write_atomic(&impacts, row_impacts_csv(report).as_bytes())?;
    let json = row_summary_json(scenario, report).map_err(|message| OutputError::Encode {
        path: summary.clone(),
        message,
    })?;
    write_atomic(&summary, json.as_bytes())?;
    Ok(vec![impacts, summary])
}
