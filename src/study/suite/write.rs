//! The files of a suite run, written as a run's are (temporary file then rename, the same
//! permissions, `summary.json` last):
//!
//! - `suite.csv`: one row per record — `record` (1-based), `file`, `component`, `factor`, the
//!   headline numbers ([`super::Headline`]) and `converged`;
//! - the representative record's run ([`super::SuiteRun::representative`]) as `pounding run`
//!   writes one run: `history.csv`, `impacts.csv`, `floors.csv`, its pictures and
//!   `summary.json`, whose top-level keys are that record's run, plus
//! - `summary.json`'s `suite` section ([`section`]): `records`, `scaling`, `statistics`,
//!   `design`, `representative`.

use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::{Value, json};

use super::SuiteRun;
use crate::output::atomic::{OutputError, write_atomic};
use crate::output::run::{DrawPictures, RunWriter};

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

/// `suite.csv`: a header, then one row per record in the scenario's order.
pub fn suite_csv(run: &SuiteRun) -> String {
    records_csv(run.records.iter().map(|r| {
        (
            r.file.as_str(),
            r.component.as_deref(),
            r.factor,
            &r.headline,
        )
    }))
}

/// The table of the records (file, component, factor, headline numbers), a pair's or a
/// row's: `record,file,component,factor,` the headline's names, `converged`.
pub(crate) fn records_csv<'a>(
    rows: impl Iterator<Item = (&'a str, Option<&'a str>, f64, &'a super::Headline)> + Clone,
) -> String {
    let mut out = String::from("record,file,component,factor");
    if let Some((_, _, _, h)) = rows.clone().next() {
        for (name, _) in &h.values {
            out.push(',');
            out.push_str(name);
        }
    }
    out.push_str(",converged\n");
    for (i, (file, component, factor, h)) in rows.enumerate() {
        out.push_str(&format!(
            "{},{},{},",
            i + 1,
            csv_text(file),
            csv_text(component.unwrap_or(""))
        ));
        number(&mut out, factor);
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

/// The `suite` section of summary.json.
pub fn section(run: &SuiteRun) -> Value {
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
        "scaling": scaling_section(run.rule, run.scaling.as_ref(), run.records.iter().map(|r| r.factor).collect()),
        "statistics": run.statistics,
        "design": run.design,
        "representative": run.representative + 1,
        "representative_file": run.records[run.representative].file,
    })
}

/// One record's entry of the section (`suite.records`), a pair's or a row's.
type RecordEntry<'a> = (
    &'a str,
    Option<&'a str>,
    f64,
    &'a super::Headline,
    &'a [String],
);

/// `suite.records`: per record its file, component, factor, headline numbers, `converged` and
/// `warnings`.
pub(crate) fn record_entries<'a>(rows: impl Iterator<Item = RecordEntry<'a>>) -> Vec<Value> {
    rows.map(|(file, component, factor, h, warnings)| {
        let mut m = serde_json::Map::new();
        m.insert("file".into(), json!(file));
        m.insert("component".into(), json!(component));
        m.insert("factor".into(), json!(factor));
        for (k, x) in &h.values {
            m.insert(k.clone(), json!(x));
        }
        m.insert("converged".into(), json!(h.converged));
        m.insert("warnings".into(), json!(warnings));
        Value::Object(m)
    })
    .collect()
}

/// `suite.scaling`: the rule, its clause, target and period ranges, the factors.
pub(crate) fn scaling_section(
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

/// Write a suite run into `dir`: `suite.csv`, then the representative record's run as
/// `pounding run` writes one (history.csv, impacts.csv, floors.csv, the pictures `draw`
/// draws — the run's and the suite's — or, without, the stale ones removed) and last
/// `summary.json` with the `suite` section. Returns the files written, in order.
pub fn write(
    dir: &Path,
    run: &SuiteRun,
    draw: Option<Box<DrawPictures<'_>>>,
) -> Result<Vec<PathBuf>, OutputError> {
    let rep = &run.records[run.representative];
    // (created first: it removes a summary.json an earlier run left)
    let mut writer = RunWriter::for_scenario(dir, &rep.scenario)?.with_suite(section(run));
    let csv = dir.join(CSV_FILE);
    write_atomic(&csv, suite_csv(run).as_bytes())?;
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
    let mut written = vec![csv];
    written.extend(writer.finish(&rep.scenario, &rep.report, draw)?);
    Ok(written)
}
