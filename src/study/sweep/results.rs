//! The results table of a sweep (`results.csv`) and the format of its rows (which the journal
//! of [`super::journal`] holds, as it finishes them); merging the parts of a sharded sweep is
//! [`super::merge`]'s.
//!
//! Columns: `case` (0-based grid index), one column per axis named by its key, `status`
//! (`ok` or `failed: reason`), then [`FIELDS`] (docs/model.md §6 meanings, SI units), the last two of
//! which are the case's self-check ([`crate::analysis::simulate::accuracy`]): `check_max_change`, the largest
//! relative change of the checked quantities against the 100× tighter rerun (empty when not
//! checked), and `converged` (`true`, `false`, or `unchecked` for a sweep run with
//! `--no-check`). Rows are in `case` order. Numbers are written exactly as `summary.json` writes them (shortest form
//! that reads back to the same `f64`), so a case's numbers are byte-identical to those of
//! `pounding run` on the same scenario.
//!
//! When the base scenario has a `[separation]` table, one column per code follows the
//! [`FIELDS`]: [`CODE_FIELDS`] (`sep_asce7`, `sep_is1893`, `sep_nbcc`, `sep_gb50011`,
//! `sep_ntc`, the codes' required separations in m, `separation.codes` of summary.json), in
//! that order, only those whose factors the scenario gives. A table without them is the v2
//! table unchanged; a journal with them is version 3 ([`JOURNAL_VERSION_CODES`]), so that an
//! older `pounding` refuses to resume it with a message instead of misreading it.
//!
//! The journal `journal.csv` (`journal-shard-K-of-N.csv` for a part, [`super::journal`]) receives every finished
//! row as soon as it is known, one `write` per row, in completion order. Its first line
//! identifies the sweep (a hash of the sweep file and the base scenario, the part, the number
//! of cases) and the format version (`v2`: with the self-check columns; a journal of another
//! version is refused with a message saying so). A rerun reads it, drops a torn last line (a kill in the middle of a write) and
//! runs only the cases not in it. `results.csv` is written from it, sorted, atomically.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

pub use crate::numerics::format::fmt_f64;

use super::shard::Shard;
use super::{Sweep, SweepError};
use crate::analysis::simulate::Report;

/// The result columns after `status`.
pub const FIELDS: [&str; NFIELDS] = [
    "peak_displacement_1",
    "peak_displacement_2",
    "peak_displacement_no_contact_1",
    "peak_displacement_no_contact_2",
    "change_percent_1",
    "change_percent_2",
    "peak_force",
    "impacts",
    "contact_time",
    "sep_abs",
    "sep_srss",
    "sep_ddc",
    "sep_time_history",
    "check_max_change",
    "converged",
];

/// Number of [`FIELDS`].
pub const NFIELDS: usize = 15;

/// The fields of the tables written before the self-check (journal v1): [`FIELDS`] without the
/// last two. [`Table::read`] still reads such tables (the check columns are then NaN).
pub const V1_FIELDS: usize = 13;

/// Version of the journal format, in its first line.
pub const JOURNAL_VERSION: u32 = 2;

/// Version of the journal format of a sweep with code columns ([`CODE_FIELDS`]).
pub const JOURNAL_VERSION_CODES: u32 = 3;

/// The code columns that may follow [`FIELDS`], in this order (`sep_` + the key of
/// [`crate::input::scenario::design::CODE_KEYS`]).
pub const CODE_FIELDS: [&str; 5] = [
    "sep_asce7",
    "sep_is1893",
    "sep_nbcc",
    "sep_gb50011",
    "sep_ntc",
];

/// The floor columns that may follow the code columns (a sweep whose base scenario has a
/// building with floors): each building's largest peak absolute floor acceleration with and
/// without pounding (m/s²) and its largest peak storey drift with pounding (m), over its floors
/// (a cantilever's stations).
pub const FLOOR_FIELDS: [&str; 6] = [
    "peak_floor_acceleration_1",
    "peak_floor_acceleration_2",
    "peak_floor_acceleration_no_contact_1",
    "peak_floor_acceleration_no_contact_2",
    "peak_drift_1",
    "peak_drift_2",
];

/// The ductility columns that follow the floor columns when the base scenario has a yielding
/// building (`hysteresis` in a `[[structure]]`, issue 16): each building's largest peak
/// ductility demand over its storeys (peak |drift|/d_y) with and without pounding; NaN for an
/// elastic building.
pub const DUCTILITY_FIELDS: [&str; 4] = [
    "peak_ductility_1",
    "peak_ductility_2",
    "peak_ductility_no_contact_1",
    "peak_ductility_no_contact_2",
];

/// The journal version of `sweep`: its row kind's (a suite's, a row's, a suite on a row's), for
/// single runs [`JOURNAL_VERSION_CODES`] with columns after [`FIELDS`] (codes, floors), else
/// [`JOURNAL_VERSION`].
pub fn journal_version(sweep: &Sweep) -> u32 {
    use super::RowKind;
    match sweep.row_kind() {
        RowKind::Single if sweep.extra_columns().is_empty() => JOURNAL_VERSION,
        RowKind::Single => JOURNAL_VERSION_CODES,
        RowKind::Suite { .. } => super::suite_rows::JOURNAL_VERSION_SUITE,
        RowKind::Row { .. } => super::row_columns::JOURNAL_VERSION_ROW,
        RowKind::RowSuite { .. } => super::row_suite_rows::JOURNAL_VERSION_ROW_SUITE,
    }
}

/// The [`FIELDS`] of a report followed by its code columns for `sweep`
/// ([`Sweep::code_columns`]): each code's required separation, or NaN if the report lacks it.
pub fn case_fields(sweep: &Sweep, r: &Report) -> Vec<String> {
    let mut out: Vec<String> = report_fields(r).into();
    for col in sweep.extra_columns() {
        if let Some(i) = DUCTILITY_FIELDS.iter().position(|f| *f == col) {
            let s = &r.structures[i % 2];
            let v = if i < 2 {
                s.peak_ductility
            } else {
                s.peak_ductility_no_contact
            };
            out.push(fmt_f64(v.unwrap_or(f64::NAN)));
            continue;
        }
        if let Some(i) = FLOOR_FIELDS.iter().position(|f| *f == col) {
            let s = &r.structures[i % 2];
            let pick = |f: &crate::analysis::simulate::FloorReport| match i / 2 {
                0 => f.peak_acceleration,
                1 => f.peak_acceleration_no_contact,
                _ => f.peak_drift,
            };
            let v = s.floors.iter().map(pick).fold(f64::NAN, f64::max);
            out.push(fmt_f64(v));
            continue;
        }
        let key = col.trim_start_matches("sep_");
        let v = r
            .separation
            .codes
            .iter()
            .find(|c| c.key == key)
            .map_or(f64::NAN, |c| c.required);
        out.push(fmt_f64(v));
    }
    out
}

/// The value of the `converged` column of a case run without its self-check.
pub const UNCHECKED: &str = "unchecked";

/// A field read back as a number: the `converged` column as 1 (`true`), 0 (`false`) or NaN
/// (`unchecked`); `check_max_change` empty as NaN; every other field must be a number.
fn parse_field(k: usize, x: &str) -> Option<f64> {
    match FIELDS[k] {
        "converged" => match x {
            "true" => Some(1.0),
            "false" => Some(0.0),
            UNCHECKED => Some(f64::NAN),
            _ => None,
        },
        "check_max_change" if x.is_empty() => Some(f64::NAN),
        _ => x.parse().ok(),
    }
}

/// The [`FIELDS`] of a report, formatted.
pub fn report_fields(r: &Report) -> [String; NFIELDS] {
    let [a, b] = &r.structures;
    let s = &r.separation;
    let acc = &r.accuracy;
    [
        fmt_f64(a.peak_displacement),
        fmt_f64(b.peak_displacement),
        fmt_f64(a.peak_displacement_no_contact),
        fmt_f64(b.peak_displacement_no_contact),
        fmt_f64(a.change_percent),
        fmt_f64(b.change_percent),
        fmt_f64(r.contact.peak_force),
        r.contact.impacts.to_string(),
        fmt_f64(r.contact.contact_time),
        fmt_f64(s.abs),
        fmt_f64(s.srss),
        fmt_f64(s.ddc),
        fmt_f64(s.time_history),
        acc.max_change.map(fmt_f64).unwrap_or_default(),
        match acc.converged {
            _ if !acc.checked => UNCHECKED.to_string(),
            Some(c) => c.to_string(),
            None => "false".to_string(),
        },
    ]
}

/// A CSV field, quoted when needed (RFC 4180).
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Split one CSV line (no line breaks inside fields) into fields; `None` if the quoting is
/// broken.
pub fn parse_csv_line(line: &str) -> Option<Vec<String>> {
    let mut out = Vec::new();
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    let mut at_start = true;
    while let Some(c) = chars.next() {
        if quoted {
            if c == '"' {
                if chars.peek() == Some(&'"') {
                    chars.next();
                    field.push('"');
                } else {
                    quoted = false;
                }
            } else {
                field.push(c);
            }
        } else if c == '"' && at_start {
            quoted = true;
            at_start = false;
        } else if c == ',' {
            out.push(std::mem::take(&mut field));
            at_start = true;
        } else {
            field.push(c);
            at_start = false;
        }
    }
    if quoted {
        return None;
    }
    out.push(field);
    Some(out)
}

/// The header line of a sweep's results.
pub fn header(sweep: &Sweep) -> String {
    let mut cols = vec!["case".to_string()];
    cols.extend(sweep.axes.iter().map(|a| csv_field(&a.key)));
    cols.push("status".into());
    cols.extend(sweep.result_columns());
    cols.join(",")
}

/// One results row (without the line break). `outcome` is the fields, or the failure reason.
/// `outcome` is [`case_fields`] (the [`FIELDS`] and the code columns), or the failure reason.
pub fn row(sweep: &Sweep, case: usize, outcome: &Result<Vec<String>, String>) -> String {
    let mut line = case.to_string();
    for v in sweep.values(case) {
        line.push(',');
        line.push_str(&csv_field(&v.to_csv()));
    }
    match outcome {
        Ok(fields) => {
            line.push_str(",ok");
            for f in fields {
                line.push(',');
                line.push_str(f);
            }
        }
        Err(reason) => {
            let reason: String = reason
                .chars()
                .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
                .collect();
            line.push(',');
            line.push_str(&csv_field(&format!("failed: {reason}")));
            line.push_str(&",".repeat(sweep.result_columns().len()));
        }
    }
    line
}

/// A results table as typed columns, named as in [`header`] and in its order, from rows in
/// the format of [`row`] (e.g. [`super::run::CaseResult::line`]): `case` whole numbers; an
/// axis of numbers (whole numbers) as numbers (whole numbers), of text or lists as text (as
/// written in the table); `status` and `converged` text; every other column numbers, the same
/// `f64` the table holds (an empty field — a failed case, `check_max_change` unchecked — is
/// NaN; `impacts` too, as a number). A row that is not of the sweep's format is an error.
pub fn columns(
    sweep: &Sweep,
    rows: &[impl AsRef<str>],
) -> Result<Vec<(String, crate::output::run::Column)>, SweepError> {
    use crate::output::run::Column;
    let names: Vec<String> = std::iter::once("case".to_string())
        .chain(sweep.axes.iter().map(|a| a.key.clone()))
        .chain(std::iter::once("status".to_string()))
        .chain(sweep.result_columns())
        .collect();
    let kind = sweep.row_kind();
    let mut cols: Vec<Column> = names
        .iter()
        .enumerate()
        .map(|(j, name)| {
            let axis = j.checked_sub(1).and_then(|a| sweep.axes.get(a));
            match axis.and_then(|a| a.values.first()) {
                Some(super::axes::AxisValue::Number(_)) => Column::Float(Vec::new()),
                Some(super::axes::AxisValue::Integer(_)) => Column::Int(Vec::new()),
                Some(_) => Column::Text(Vec::new()),
                None if j == 0 => Column::Int(Vec::new()),
                None if name == "status" || name == "converged" => Column::Text(Vec::new()),
                None if kind.is_text(name) => Column::Text(Vec::new()),
                None => Column::Float(Vec::new()),
            }
        })
        .collect();
    let bad = |i: usize, why: &str| SweepError::Usage(format!("results row {i}: {why}"));
    for (i, line) in rows.iter().enumerate() {
        let fields = parse_csv_line(line.as_ref()).ok_or_else(|| bad(i, "broken quoting"))?;
        if fields.len() != names.len() {
            return Err(bad(
                i,
                &format!(
                    "{} fields, the table has {} columns",
                    fields.len(),
                    names.len()
                ),
            ));
        }
        for (col, f) in cols.iter_mut().zip(fields) {
            match col {
                Column::Int(v) => v.push(
                    f.parse()
                        .map_err(|_| bad(i, &format!("`{f}` is not a whole number")))?,
                ),
                Column::Float(v) => v.push(if f.is_empty() {
                    f64::NAN
                } else {
                    f.parse()
                        .map_err(|_| bad(i, &format!("`{f}` is not a number")))?
                }),
                Column::Text(v) => v.push(f),
            }
        }
    }
    Ok(names.into_iter().zip(cols).collect())
}

/// Checks a row read back: right number of fields, case in range, a known status, values
/// of each result column's kind (`names`, after `status`; `kind`: the sweep's row kind) where the
/// status is `ok`. Returns the case and whether it failed.
pub(super) fn check_row(
    line: &str,
    names: &[String],
    kind: &super::RowKind,
    cases: usize,
) -> Option<(usize, bool)> {
    let f = parse_csv_line(line)?;
    let columns = f.len();
    if columns < names.len() + 2 {
        return None;
    }
    let case: usize = f[0].parse().ok()?;
    if case >= cases {
        return None;
    }
    let status = &f[columns - names.len() - 1];
    let nums = &f[columns - names.len()..];
    if status == "ok" {
        if nums.iter().zip(names).enumerate().all(|(k, (x, name))| {
            if *kind != super::RowKind::Single {
                kind.parse(name, x).is_some()
            } else if k < NFIELDS {
                parse_field(k, x).is_some()
            } else {
                x.parse::<f64>().is_ok()
            }
        }) {
            Some((case, false))
        } else {
            None
        }
    } else if status.starts_with("failed: ") && nums.iter().all(String::is_empty) {
        Some((case, true))
    } else {
        None
    }
}

/// File names of a run's outputs in its directory.
pub fn file_names(shard: Shard) -> (String, String) {
    if shard.is_all() {
        ("results.csv".into(), "journal.csv".into())
    } else {
        (
            format!("results-shard-{}-of-{}.csv", shard.k, shard.n),
            format!("journal-shard-{}-of-{}.csv", shard.k, shard.n),
        )
    }
}

/// Write a results table: `header`, then the rows in case order, atomically.
pub fn write_results<'a>(
    path: &Path,
    header: &str,
    rows: impl Iterator<Item = &'a str>,
) -> Result<(), SweepError> {
    let mut out = String::with_capacity(1 << 16);
    out.push_str(header);
    out.push('\n');
    for r in rows {
        out.push_str(r);
        out.push('\n');
    }
    crate::output::atomic::write_atomic(path, out.as_bytes()).map_err(|e| SweepError::Write {
        path: path.display().to_string(),
        source: std::io::Error::other(e.to_string()),
    })
}

/// A results table read from a CSV file.
#[derive(Debug, Clone)]
pub struct Table {
    /// Where it was read from.
    pub path: PathBuf,
    /// The header line.
    pub header: String,
    /// Axis keys (the columns between `case` and `status`).
    pub axes: Vec<String>,
    /// Rows by case.
    pub rows: BTreeMap<usize, TableRow>,
    /// The columns after [`FIELDS`] ([`CODE_FIELDS`], then [`FLOOR_FIELDS`], then
    /// [`DUCTILITY_FIELDS`]: those the table has); for a sweep over a suite, every column
    /// after `status` ([`super::suite_rows::columns`]).
    pub codes: Vec<String>,
    /// The rows are suites of records ([`super::suite_rows`]), rows of buildings
    /// ([`super::row_columns`]) or suites on a row ([`super::row_suite_rows`]):
    /// [`TableRow::fields`] are NaN and the values are in [`TableRow::codes`].
    pub suite: bool,
}

/// One row of a [`Table`].
#[derive(Debug, Clone)]
pub struct TableRow {
    /// The line as read.
    pub line: String,
    /// Axis values as written.
    pub values: Vec<String>,
    /// `ok` or `failed: …`.
    pub status: String,
    /// [`FIELDS`] values (NaN for a failed case; `converged` as 1, 0 or NaN when unchecked;
    /// the check columns NaN in a table written before them).
    pub fields: [f64; NFIELDS],
    /// Values of the table's code columns ([`Table::codes`]), NaN when empty.
    pub codes: Vec<f64>,
}

impl TableRow {
    /// The value of column `name` of `table` (a [`FIELDS`] or code column), if it has it.
    pub fn get(&self, table: &Table, name: &str) -> Option<f64> {
        match Table::field_index(name).filter(|_| !table.suite) {
            Some(i) => Some(self.fields[i]),
            None => table
                .codes
                .iter()
                .position(|c| c == name)
                .map(|i| self.codes[i]),
        }
    }
}

impl Table {
    /// Read a results CSV (`results.csv`, a part, or a merged table). Refuses duplicate cases.
    pub fn read(path: &Path) -> Result<Table, SweepError> {
        let text = std::fs::read_to_string(path).map_err(|e| SweepError::Read {
            path: path.display().to_string(),
            source: e,
        })?;
        let bad = |line: usize, msg: String| SweepError::Journal {
            path: format!("{}:{line}", path.display()),
            message: msg,
        };
        let mut lines = text.lines();
        let header = lines
            .next()
            .ok_or_else(|| bad(1, "empty file: not a sweep results table".into()))?
            .to_string();
        let all = parse_csv_line(&header).unwrap_or_default();
        if let Some(t) = Table::read_suite(path, &header, &all, &text)? {
            return Ok(t);
        }
        // trailing code columns, then the layout before them
        let ncodes = all
            .iter()
            .rev()
            .take_while(|c| {
                CODE_FIELDS.contains(&c.as_str())
                    || FLOOR_FIELDS.contains(&c.as_str())
                    || DUCTILITY_FIELDS.contains(&c.as_str())
            })
            .count();
        let codes: Vec<String> = all[all.len() - ncodes..].to_vec();
        let cols = &all[..all.len() - ncodes];
        let n = cols.len();
        // the current layout, or that of tables written before the self-check columns
        let shape = |nf: usize| {
            n >= 2 + nf
                && cols[0] == "case"
                && cols[n - nf - 1] == "status"
                && cols[n - nf..].iter().zip(FIELDS).all(|(a, b)| a == b)
        };
        let nf = if shape(NFIELDS) {
            NFIELDS
        } else if shape(V1_FIELDS) {
            V1_FIELDS
        } else {
            return Err(bad(
                1,
                format!(
                    "not a sweep results table: expected columns case, <axis keys>, status, {} \
                     (then any of {})",
                    FIELDS.join(", "),
                    CODE_FIELDS.join(", ")
                ),
            ));
        };
        let axes = cols[1..n - nf - 1].to_vec();
        let mut rows = BTreeMap::new();
        for (i, line) in lines.enumerate() {
            let lineno = i + 2;
            if line.trim().is_empty() {
                continue;
            }
            let f = parse_csv_line(line)
                .filter(|f| f.len() == n + ncodes)
                .ok_or_else(|| {
                    bad(
                        lineno,
                        format!("expected {} comma-separated fields", n + ncodes),
                    )
                })?;
            let case: usize = f[0]
                .parse()
                .map_err(|_| bad(lineno, format!("case `{}` is not a whole number", f[0])))?;
            let mut fields = [f64::NAN; NFIELDS];
            for (k, x) in f[n - nf..n].iter().enumerate() {
                if !x.is_empty() {
                    fields[k] = parse_field(k, x).ok_or_else(|| {
                        let what = if FIELDS[k] == "converged" {
                            "true, false or unchecked"
                        } else {
                            "a number"
                        };
                        bad(lineno, format!("`{}` = `{x}` is not {what}", FIELDS[k]))
                    })?;
                }
            }
            let mut code_values = vec![f64::NAN; ncodes];
            for (k, x) in f[n..].iter().enumerate() {
                if !x.is_empty() {
                    code_values[k] = x.parse().map_err(|_| {
                        bad(lineno, format!("`{}` = `{x}` is not a number", codes[k]))
                    })?;
                }
            }
            let r = TableRow {
                line: line.to_string(),
                values: f[1..n - nf - 1].to_vec(),
                status: f[n - nf - 1].clone(),
                fields,
                codes: code_values,
            };
            if rows.insert(case, r).is_some() {
                return Err(bad(lineno, format!("case {case} appears twice")));
            }
        }
        Ok(Table {
            path: path.to_path_buf(),
            header,
            axes,
            rows,
            codes,
            suite: false,
        })
    }

    /// A table of a sweep over a suite (columns `case`, the axes, `status`,
    /// [`super::suite_rows::columns`]), over a row of buildings
    /// ([`super::row_columns::columns`]) or over a suite on a row
    /// ([`super::row_suite_rows::columns`]), or `None` when `all` (the header's columns) is
    /// none of them.
    fn read_suite(
        path: &Path,
        header: &str,
        all: &[String],
        text: &str,
    ) -> Result<Option<Table>, SweepError> {
        use super::row_columns as row;
        use super::row_suite_rows as row_suite;
        use super::suite_rows::{HEAD, PER_LEVEL, TAIL, columns};
        let bad = |line: usize, msg: String| SweepError::Journal {
            path: format!("{}:{line}", path.display()),
            message: msg,
        };
        let after_status = |first: &str| {
            all.iter()
                .position(|c| c == "status")
                .filter(|&st| all.get(st + 1).map(String::as_str) == Some(first))
        };
        let (st, kind, names, expected) = if let Some(st) = after_status(HEAD[0]) {
            let rest = all.len() - st - 1;
            let levels = rest.saturating_sub(HEAD.len() + TAIL.len()) / PER_LEVEL.len();
            let expected = format!(
                "a suite: expected columns case, <axis keys>, status, {}",
                columns(1).join(", ").replace("level1_", "levelK_")
            );
            (
                st,
                super::RowKind::Suite { levels },
                columns(levels),
                expected,
            )
        } else if let Some(st) = after_status(row::HEAD[0])
            .filter(|&st| all.get(st + 2).map(String::as_str) == Some(row_suite::HEAD[1]))
        {
            // a suite on a row of buildings: each pair's columns and its levels'
            let names = &all[st + 1..];
            let pair_levels = row_suite::pair_levels_of(names).unwrap_or_default();
            let expected = format!(
                "a suite on a row of buildings: expected columns case, <axis keys>, status, {}",
                row_suite::columns(&[1])
                    .join(", ")
                    .replace("pair1_level1_", "pairP_levelK_")
                    .replace("pair1_", "pairP_")
            );
            (
                st,
                super::RowKind::RowSuite {
                    pair_levels: pair_levels.clone(),
                },
                row_suite::columns(&pair_levels),
                expected,
            )
        } else if let Some(st) = after_status(row::HEAD[0]) {
            // a row of buildings (issue 29): N structures' and N − 1 pairs' columns
            let rest = all.len() - st - 1;
            let (per_s, per_p) = (row::PER_STRUCTURE.len(), row::PER_PAIR.len());
            let body = rest.saturating_sub(row::HEAD.len() + row::TAIL.len()) + per_p;
            let structures = body / (per_s + per_p);
            let expected = format!(
                "a row of buildings: expected columns case, <axis keys>, status, {}",
                row::columns(2)
                    .join(", ")
                    .replace("structure2_", "structureI_")
                    .replace("structure1_", "structureI_")
                    .replace("pair1_", "pairP_")
            );
            (
                st,
                super::RowKind::Row { structures },
                row::columns(structures),
                expected,
            )
        } else {
            return Ok(None);
        };
        if all[0] != "case" || all[st + 1..] != names[..] {
            return Err(bad(1, format!("not a sweep results table of {expected}")));
        }
        let mut rows = BTreeMap::new();
        for (i, line) in text.lines().enumerate().skip(1) {
            let lineno = i + 1;
            if line.trim().is_empty() {
                continue;
            }
            let f = parse_csv_line(line)
                .filter(|f| f.len() == all.len())
                .ok_or_else(|| {
                    bad(
                        lineno,
                        format!("expected {} comma-separated fields", all.len()),
                    )
                })?;
            let case: usize = f[0]
                .parse()
                .map_err(|_| bad(lineno, format!("case `{}` is not a whole number", f[0])))?;
            let mut values = vec![f64::NAN; names.len()];
            for (k, x) in f[st + 1..].iter().enumerate() {
                if !x.is_empty() {
                    values[k] = kind.parse(&names[k], x).ok_or_else(|| {
                        bad(lineno, format!("`{}` = `{x}` is not valid", names[k]))
                    })?;
                }
            }
            let r = TableRow {
                line: line.to_string(),
                values: f[1..st].to_vec(),
                status: f[st].clone(),
                fields: [f64::NAN; NFIELDS],
                codes: values,
            };
            if rows.insert(case, r).is_some() {
                return Err(bad(lineno, format!("case {case} appears twice")));
            }
        }
        Ok(Some(Table {
            path: path.to_path_buf(),
            header: header.to_string(),
            axes: all[1..st].to_vec(),
            rows,
            codes: names,
            suite: true,
        }))
    }

    /// Index of a field in [`FIELDS`].
    pub fn field_index(name: &str) -> Option<usize> {
        FIELDS.iter().position(|f| *f == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_round_trip() {
        let fields = ["a", "b,c", "say \"hi\"", ""];
        let line: Vec<String> = fields.iter().map(|f| csv_field(f)).collect();
        let parsed = parse_csv_line(&line.join(",")).unwrap();
        assert_eq!(parsed, fields);
        assert!(parse_csv_line("\"open").is_none());
    }

    #[test]
    fn tables_before_the_check_columns_still_read() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("old.csv");
        let head = format!("case,pga,status,{}", FIELDS[..V1_FIELDS].join(","));
        let row = format!("0,0.2,ok,{}", vec!["1.5"; V1_FIELDS].join(","));
        std::fs::write(&p, format!("{head}\n{row}\n")).unwrap();
        let t = Table::read(&p).unwrap();
        assert_eq!(t.axes, ["pga"]);
        let f = &t.rows[&0].fields;
        assert!(f[..V1_FIELDS].iter().all(|&x| x == 1.5));
        assert!(f[V1_FIELDS..].iter().all(|x| x.is_nan()));
        // the current layout: `converged` is true/false/unchecked, the change may be empty
        let head = format!("case,pga,status,{}", FIELDS.join(","));
        let nums = vec!["1.5"; V1_FIELDS].join(",");
        let text = format!("{head}\n0,0.2,ok,{nums},0.5,false\n1,0.3,ok,{nums},,unchecked\n");
        std::fs::write(&p, text).unwrap();
        let t = Table::read(&p).unwrap();
        assert_eq!(t.rows[&0].fields[V1_FIELDS..], [0.5, 0.0]);
        assert!(t.rows[&1].fields[V1_FIELDS..].iter().all(|x| x.is_nan()));
        std::fs::write(&p, format!("{head}\n0,0.2,ok,{nums},0.5,maybe\n")).unwrap();
        let e = Table::read(&p).unwrap_err().to_string();
        assert!(e.contains("true, false or unchecked"), "{e}");
    }

    #[test]
    fn numbers_as_json_writes_them() {
        assert_eq!(fmt_f64(91490009.5168547), "91490009.5168547");
        assert_eq!(fmt_f64(0.0), "0.0");
        assert_eq!(fmt_f64(1e-7), "1e-7");
        assert_eq!(fmt_f64(f64::NAN), "NaN");
        for x in [0.1, 1.0 / 3.0, 2.808e10, 5e-324, 1.7976931348623157e308] {
            assert_eq!(fmt_f64(x).parse::<f64>().unwrap(), x);
        }
    }
}
