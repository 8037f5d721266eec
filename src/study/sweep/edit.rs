//! Setting axis values into a case: the base scenario's TOML table with the values written at
//! their key paths (`set_keys`; a structure's period replacing its stiffness, …), and a sweep
//! of a scenario held in memory (`sweep_text`).

use std::path::{Path, PathBuf};

use toml::{Table, Value};

use crate::input::scenario::{Location, ScenarioError};
use crate::model::structure::{Cantilever, Damping, Stiffness};

use super::axes::AxisValue;
use super::{Sweep, SweepError, number};

/// A sweep file's text (`scenario = …` and one `[[axis]]` per entry of `axes`) for sweeping
/// a scenario given as text: each axis a table with `key` and either `values` or `from`, `to`,
/// `steps` (and `scale`), exactly as in a sweep file. `scenario` is the base scenario's file
/// name (it names it; [`Sweep::from_toml_with_base`] takes its text).
pub fn sweep_text(scenario: &str, axes: Vec<Table>) -> Result<String, SweepError> {
    let mut t = Table::new();
    t.insert("scenario".into(), Value::String(scenario.to_string()));
    t.insert(
        "axis".into(),
        Value::Array(axes.into_iter().map(Value::Table).collect()),
    );
    toml::to_string(&t)
        .map_err(|e| SweepError::Usage(format!("axes: cannot be written as TOML: {e}")))
}

/// A scenario's TOML text with keys set as a sweep sets them (the same key paths, derived
/// keys such as `period_ratio` included, and the same rules: setting a structure's `period`
/// removes its `bending_stiffness`, …): `values` = (key path, value) in any order, applied in
/// the sweep's order. `base` = the scenario's text and path (record files relative to its
/// directory). The result is not validated: read it with [`Scenario::from_toml`](crate::input::scenario::Scenario::from_toml). Used by the
/// Python package's `Scenario.replace`.
pub fn set_keys(
    base_text: &str,
    base_path: &Path,
    values: Vec<(String, Value)>,
) -> Result<String, SweepError> {
    let keys: Vec<String> = values.iter().map(|(k, _)| k.clone()).collect();
    let axes = values
        .into_iter()
        .map(|(k, v)| {
            let mut a = Table::new();
            a.insert("key".into(), Value::String(k));
            a.insert("values".into(), Value::Array(vec![v]));
            a
        })
        .collect();
    let name = base_path
        .file_name()
        .map_or_else(|| "scenario".into(), |n| n.to_string_lossy().into_owned());
    let text = sweep_text(&name, axes)?;
    let dir = base_path.parent().unwrap_or(Path::new("."));
    let at = || Location::file(base_path.display().to_string());
    // messages name the key as given, not the generated sweep's `axis[N]`
    let sweep =
        Sweep::from_toml_with_base(&text, &dir.join("replace"), Some((base_text, base_path)))
            .map_err(|e| match e {
                SweepError::Invalid { key, reason, .. } if key.starts_with("axis[") => {
                    let n: usize = key[5..]
                        .split(']')
                        .next()
                        .and_then(|n| n.parse().ok())
                        .unwrap_or(1);
                    SweepError::Invalid {
                        at: at(),
                        key: keys.get(n.saturating_sub(1)).cloned().unwrap_or(key),
                        reason,
                    }
                }
                other => other,
            })?;
    let mut table = sweep.case_table(0).map_err(|reason| SweepError::Invalid {
        at: at(),
        key: sweep.label(0),
        reason,
    })?;
    // the title says what was changed (the base's title may name the values replaced)
    if let Some(Value::String(title)) = table.get_mut("title") {
        *title = format!("{title} — with {}", sweep.label(0));
    }
    toml::to_string(&table)
        .map_err(|e| SweepError::Usage(format!("cannot encode the scenario as TOML: {e}")))
}

pub(super) fn as_f64(v: &AxisValue) -> f64 {
    match v {
        AxisValue::Number(x) => *x,
        AxisValue::Integer(i) => *i as f64,
        AxisValue::Text(_) | AxisValue::List(_) => f64::NAN,
    }
}

/// An absolute path without touching the file system (no symlink resolution).
pub(super) fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

pub(super) fn section_mut<'t>(t: &'t mut Table, name: &str) -> Result<&'t mut Table, String> {
    match t
        .entry(name.to_string())
        .or_insert_with(|| Value::Table(Table::new()))
    {
        Value::Table(s) => Ok(s),
        _ => Err(format!("`{name}` in the base scenario is not a table")),
    }
}

pub(super) fn structure_mut(t: &mut Table, i: usize) -> Result<&mut Table, String> {
    match t.get_mut("structure") {
        Some(Value::Array(a)) => match a.get_mut(i) {
            Some(Value::Table(s)) => Ok(s),
            _ => Err(format!(
                "the base scenario has no [[structure]] number {}",
                i + 1
            )),
        },
        _ => Err("the base scenario has no [[structure]] tables".into()),
    }
}

pub(super) fn level_mut(t: &mut Table, i: usize) -> Result<&mut Table, String> {
    let c = section_mut(t, "contact")?;
    match c.get_mut("level") {
        Some(Value::Array(a)) => match a.get_mut(i) {
            Some(Value::Table(s)) => Ok(s),
            _ => Err(format!(
                "the base scenario has no [[contact.level]] number {}",
                i + 1
            )),
        },
        _ => Err("the base scenario has no [[contact.level]] tables".into()),
    }
}

/// First-mode period of structure `i` (0-based) as the case table gives it: `period`, or
/// computed from length, mass and `bending_stiffness`/`tip_stiffness` (docs/model.md §2.6).
pub(super) fn first_period(t: &Table, i: usize) -> Result<f64, String> {
    let s = match t.get("structure") {
        Some(Value::Array(a)) => match a.get(i) {
            Some(Value::Table(s)) => s,
            _ => return Err(format!("the scenario has no structure {}", i + 1)),
        },
        _ => return Err("the scenario has no [[structure]] tables".into()),
    };
    let get = |k: &str| s.get(k).and_then(number);
    let positive = |k: &str| -> Result<f64, String> {
        match get(k) {
            Some(x) if x.is_finite() && x > 0.0 => Ok(x),
            _ => Err(format!(
                "structure[{}].{k} must be a number > 0 to compute the period",
                i + 1
            )),
        }
    };
    if s.contains_key("period") {
        return positive("period");
    }
    let stiffness = if s.contains_key("bending_stiffness") {
        Stiffness::Bending(positive("bending_stiffness")?)
    } else if s.contains_key("tip_stiffness") {
        Stiffness::Tip(positive("tip_stiffness")?)
    } else {
        return Err(format!(
            "structure[{}] gives none of `period`, `bending_stiffness`, `tip_stiffness`",
            i + 1
        ));
    };
    let st = Cantilever {
        name: String::new(),
        length: positive("length")?,
        mass: positive("mass")?,
        stiffness,
        modes: 1,
        damping: Damping::Modal(vec![0.0]),
    };
    Ok(st.modal().periods()[0])
}

/// A scenario error without the position in the generated case text.
pub(super) fn reason(e: &ScenarioError) -> String {
    match e {
        ScenarioError::Read { path, source } => format!("cannot read {path}: {source}"),
        ScenarioError::Syntax { message, .. } => message.clone(),
        ScenarioError::UnknownKey {
            key, section, hint, ..
        } => format!("unknown key `{key}` in {section}{hint}"),
        ScenarioError::Missing { key, expected, .. } => {
            format!("missing key `{key}`: {expected}")
        }
        ScenarioError::Invalid {
            key, value, reason, ..
        } => format!("`{key}` = {value}: {reason}"),
        ScenarioError::Record { key, source, .. } => format!("`{key}`: {source}"),
        ScenarioError::MissingMany { missing, .. } => format!(
            "missing keys: {}",
            missing
                .iter()
                .map(|(_, key, expected)| format!("`{key}` ({expected})"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        ScenarioError::SweepFile { .. } => e.to_string(),
    }
}
