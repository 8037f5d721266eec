//! The files of a suite run, a pair's or a row of buildings' ([`SuiteOutput`]), written as a
//! run's are (temporary file then rename, the same permissions, the top-level `summary.json`
//! last):
//!
//! - `suite.csv`: one row per record — `record` (1-based), `file`, `component`, `factor`, the
//!   headline numbers ([`super::Headline`]; a row's per structure and per pair,
//!   [`super::Headline::of_row`]) and `converged`;
//! - a row's suite only: `records/NN/` (NN = 1-based record number, zero-padded to the count's
//!   width, [`record_dir`]): each record's run of the row as `pounding run` writes a row's
//!   (history.csv, impacts.csv, floors.csv, its pictures, summary.json);
//! - the representative record's run ([`super::SuiteRun::representative`]) at the top level as
//!   `pounding run` writes one run: `history.csv`, `impacts.csv`, `floors.csv`, its pictures
//!   and `summary.json`, whose top-level keys are that record's run, plus
//! - `summary.json`'s `suite` section ([`section`]): `records`, `scaling`, `statistics`,
//!   `design` (a row's per pair, [`super::row::RowDesign`]), `representative`,
//!   `representative_file` and, for a row, `record_dirs`.
//!
//! What differs between a pair's suite and a row's is data ([`SuiteOutput`]: the report of a
//! record's run, the design, whether each record's run has its own folder); the files are
//! written by this one code path.

use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::{Value, json};

use super::row::RowSuiteRun;
use super::{MemberReport, MemberRun, NamedStatistics, SuiteRun};
use crate::analysis::record_spectrum::ScaledSuite;
use crate::input::scenario::suite::SuiteRule;
use crate::output::atomic::{OutputError, write_atomic};
use crate::output::run::DrawPictures;
use crate::output::writer::{RunOutput, RunWriter, remove_stale, write_run};

/// What the files of a suite run take from it: a pair's [`SuiteRun`] or a row's
/// [`RowSuiteRun`].
pub trait SuiteOutput {
    /// The report of a record's run (a pair's or a row's).
    type Report: MemberReport + RunOutput;
    /// Whether each record's run is written in its own folder ([`record_dir`]): a row's suite,
    /// whose per-pair answers an engineer reads record by record.
    const RECORD_DIRS: bool;
    /// The rule.
    fn rule(&self) -> SuiteRule;
    /// The scaling by the rule (`None` for rule = "none").
    fn scaling(&self) -> Option<&ScaledSuite>;
    /// Every record's run, in the scenario's order.
    fn records(&self) -> &[MemberRun<Self::Report>];
    /// Every headline number across the records.
    fn statistics(&self) -> &NamedStatistics;
    /// The design values and the verdict, as summary.json's `suite.design`.
    fn design(&self) -> Value;
    /// The representative record (0-based).
    fn representative(&self) -> usize;
}

impl SuiteOutput for SuiteRun {
    type Report = crate::analysis::simulate::Report;
    const RECORD_DIRS: bool = false;
    fn rule(&self) -> SuiteRule {
        self.rule
    }
    fn scaling(&self) -> Option<&ScaledSuite> {
        self.scaling.as_ref()
    }
    fn records(&self) -> &[MemberRun<Self::Report>] {
        &self.records
    }
    fn statistics(&self) -> &NamedStatistics {
        &self.statistics
    }
    fn design(&self) -> Value {
        json!(self.design)
    }
    fn representative(&self) -> usize {
        self.representative
    }
}

impl SuiteOutput for RowSuiteRun {
    type Report = crate::analysis::simulate::RowReport;
    const RECORD_DIRS: bool = true;
    fn rule(&self) -> SuiteRule {
        self.rule
    }
    fn scaling(&self) -> Option<&ScaledSuite> {
        self.scaling.as_ref()
    }
    fn records(&self) -> &[MemberRun<Self::Report>] {
        &self.records
    }
    fn statistics(&self) -> &NamedStatistics {
        &self.statistics
    }
    fn design(&self) -> Value {
        json!(self.design)
    }
    fn representative(&self) -> usize {
        self.representative
    }
}

/// The folder of the records' own runs (a row's suite).
pub const RECORDS_DIR: &str = "records";

/// The folder of record `i` (0-based) of `n`, relative to the output directory:
/// `records/01` … (zero-padded to the width of `n`).
pub fn record_dir(i: usize, n: usize) -> String {
    let width = n.to_string().len().max(2);
    format!("{RECORDS_DIR}/{:0width$}", i + 1)
}

/// The table of the records.
pub const CSV_FILE: &str = "suite.csv";

/// The suite's pictures (removed when a run draws none).
pub const PICTURE_FILES: [&str; 4] = [
    "suite-spectra.png",
    "suite-spectra.svg",
    "suite-records.png",
    "suite-records.svg",
];

fn csv_text(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn number(out: &mut String, x: f64) {
    // the shortest form that reads back to the same f64, as summary.json; empty for NaN
    if x.is_finite() {
        out.push_str(&serde_json::to_string(&x).unwrap_or_default());
    }
}

/// `suite.csv`: a header — `record,file,component,factor,` the headline's names,
/// `converged` — then one row per record in the scenario's order.
pub fn suite_csv<S: SuiteOutput>(run: &S) -> String {
    let records = run.records();
    let mut out = String::from("record,file,component,factor");
    if let Some(r) = records.first() {
        for (name, _) in &r.headline.values {
            out.push(',');
            out.push_str(name);
        }
    }
    out.push_str(",converged\n");
    for (i, r) in records.iter().enumerate() {
        let h = &r.headline;
        out.push_str(&format!(
            "{},{},{},",
            i + 1,
            csv_text(&r.file),
            csv_text(r.component.as_deref().unwrap_or(""))
        ));
        number(&mut out, r.factor);
        for (_, x) in &h.values {
            out.push(',');
            number(&mut out, *x);
        }
        out.push(',');
        out.push_str(match h.converged {
            Some(true) => "true",
            Some(false) => "false",
            None => "unchecked",
        });
        out.push('\n');
    }
    out
}

#[derive(Serialize)]
struct ScalingSection<'a> {
    rule: &'static str,
    clause: Option<&'static str>,
    target: Option<&'a str>,
    period_range: Option<[f64; 2]>,
    code_period_range: Option<[f64; 2]>,
    first_mode_periods: Option<&'a [f64]>,
    required_ratio: Option<f64>,
    min_mean_to_target_ratio: Option<f64>,
    min_ratio_period: Option<f64>,
    pga_check: Option<crate::analysis::record_spectrum::scaling::PgaCheck>,
    governs: Option<&'a str>,
    factors: Vec<f64>,
    notes: &'a [String],
}

/// The `suite` section of summary.json: `records` (per record its file, component, factor,
/// headline numbers, `converged` and `warnings`), `scaling`, `statistics`, `design`,
/// `representative`, `representative_file` and, for a suite whose records have their own
/// folders ([`SuiteOutput::RECORD_DIRS`]), `record_dirs` (relative to the directory).
pub fn section<S: SuiteOutput>(run: &S) -> Value {
    let records = run.records();
    let entries: Vec<Value> = records
        .iter()
        .map(|r| {
            let mut m = serde_json::Map::new();
            m.insert("file".into(), json!(r.file));
            m.insert("component".into(), json!(r.component));
            m.insert("factor".into(), json!(r.factor));
            for (k, x) in &r.headline.values {
                m.insert(k.clone(), json!(x));
            }
            m.insert("converged".into(), json!(r.headline.converged));
            m.insert("warnings".into(), json!(r.report.warnings()));
            Value::Object(m)
        })
        .collect();
    let factors = records.iter().map(|r| r.factor).collect();
    let mut out = json!({
        "records": entries,
        "scaling": scaling_section(run.rule(), run.scaling(), factors),
        "statistics": run.statistics(),
        "design": run.design(),
        "representative": run.representative() + 1,
        "representative_file": records[run.representative()].file,
    });
    if S::RECORD_DIRS
        && let Value::Object(m) = &mut out
    {
        let n = records.len();
        let dirs: Vec<String> = (0..n).map(|i| record_dir(i, n)).collect();
        m.insert("record_dirs".into(), json!(dirs));
    }
    out
}

/// `suite.scaling`: the rule, its clause, target and period ranges, the factors.
fn scaling_section(
    rule: crate::input::scenario::suite::SuiteRule,
    s: Option<&crate::analysis::record_spectrum::ScaledSuite>,
    factors: Vec<f64>,
) -> Value {
    let scaling = ScalingSection {
        rule: rule.key(),
        clause: s.map(|s| s.rule_name),
        target: s.map(|s| s.target_description.as_str()),
        period_range: s.map(|s| [s.range.lo, s.range.hi]),
        code_period_range: s.map(|s| [s.code_range.lo, s.code_range.hi]),
        first_mode_periods: s.map(|s| s.first_mode_periods.as_slice()),
        required_ratio: s.map(|s| s.required_ratio),
        min_mean_to_target_ratio: s.map(|s| s.min_ratio),
        min_ratio_period: s.map(|s| s.min_ratio_period),
        pga_check: s.and_then(|s| s.pga_check),
        governs: s.map(|s| s.governs.as_str()),
        factors,
        notes: s.map_or(&[], |s| s.notes.as_slice()),
    };
    json!(scaling)
}

/// Write a suite run into `dir`: for a row's suite each record's run into its folder
/// ([`record_dir`], pictures by `draw_record(i)`, none where it gives `None`; not called for a
/// pair's), `suite.csv`, then the representative record's run at the top level as `pounding
/// run` writes one (history.csv, impacts.csv, floors.csv, the pictures `draw` draws — the
/// run's and the suite's — or, without, the stale ones removed) and last `summary.json` with
/// the `suite` section. Returns the files written, in order.
pub fn write<'a, S: SuiteOutput>(
    dir: &Path,
    run: &'a S,
    draw: Option<Box<DrawPictures<'a>>>,
    mut draw_record: impl FnMut(usize) -> Option<Box<DrawPictures<'a>>>,
) -> Result<Vec<PathBuf>, OutputError> {
    let records = run.records();
    let rep = &records[run.representative()];
    // (created first: it removes a summary.json an earlier run left)
    let mut writer = RunWriter::for_scenario(dir, &rep.scenario)?.with_suite(section(run));
    let mut written = Vec::new();
    if S::RECORD_DIRS {
        let n = records.len();
        for (i, r) in records.iter().enumerate() {
            let sub = dir.join(record_dir(i, n));
            written.extend(write_run(
                &sub,
                &r.scenario,
                &r.report,
                &r.capture,
                draw_record(i),
            )?);
        }
    }
    let csv = dir.join(CSV_FILE);
    write_atomic(&csv, suite_csv(run).as_bytes())?;
    written.push(csv);
    if draw.is_none() {
        for name in PICTURE_FILES {
            remove_stale(dir, name)?;
        }
    }
    rep.capture.replay(&mut writer);
    written.extend(writer.finish(&rep.scenario, &rep.report, draw)?);
    Ok(written)
}
