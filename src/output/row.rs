//! The files of a row of buildings' run (issue 29), written by the one writer of a run's files
//! (`output::writer::RunWriter`, as a pair's): `history.csv` and `floors.csv` streamed
//! during the run, then `impacts.csv` (one row per contact episode, naming its pair), the
//! pictures (`figures::row`) and `summary.json` last (the row's [`RowReport`]:
//! `structures`, `pairs`, `verdict`, `accuracy`, …, with the solver's facts and the defaults
//! applied). This module gives their contents.
//!
//! A row's `history.csv` is a layout of its own (a pair's is unchanged): `t`, then `w_<name>`
//! for every structure (its displacement at its headline height — its highest contact level
//! with either neighbour, where summary.json's `peak_displacement` is — m), `force_<left>_
//! <right>_<k>` for every pair and level k (1-based, in the order of the pair's `[[contact]]`
//! table; N), then `w_<name>_free` (without contact). A row's `floors.csv`: `t`, `w_<name>_<h>`
//! and `a_<name>_<h>` (displacement, m; absolute acceleration, m/s²) for every structure and
//! station (height h, m), then the same with `_free`.

use serde::Serialize;

use crate::analysis::simulate::{RowReport, RunCapture};
use crate::input::scenario::Scenario;
use crate::output::csv::push_field;

#[derive(Debug, Serialize)]
struct RowSummary<'a> {
    #[serde(flatten)]
    report: &'a RowReport,
    solver: super::run::SolverInfo,
    defaults_applied: &'a [String],
    /// A suite's own section (`output::writer::RunWriter::with_suite`); absent for one
    /// record.
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
