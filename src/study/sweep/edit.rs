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

/// The structures' names of a scenario table, in row order (a structure without `name` is
/// "structure i", as the scenario names it).
fn structure_names(t: &Table) -> Vec<String> {
    match t.get("structure") {
        Some(Value::Array(a)) => (a.iter().enumerate())
            .map(|(i, s)| {
                s.get("name")
                    .and_then(Value::as_str)
                    .map_or_else(|| format!("structure {}", i + 1), str::to_string)
            })
            .collect(),
        _ => Vec::new(),
    }
}

/// The contact table of adjacent pair `p` (0-based: structures p and p + 1) of a scenario
/// table: a pair's `[contact]` (p = 0), or the `[[contact]]` table whose `between` names the
/// pair (in either order), or a pair's one `[[contact]]` without `between`. `Err`: the
/// reason, naming the key `contact[p + 1]`.
pub(super) fn pair_contact_mut(t: &mut Table, p: usize) -> Result<&mut Table, String> {
    let names = structure_names(t);
    let pairs = names.len().saturating_sub(1);
    if p >= pairs {
        return Err(format!(
            "contact[{}]: the base scenario has {} structure(s), so {pairs} adjacent pair(s) \
             (contact[1] … contact[{pairs}])",
            p + 1,
            names.len()
        ));
    }
    let (a, b) = (names[p].as_str(), names[p + 1].as_str());
    let names_pair = |c: &Value| {
        c.get("between")
            .and_then(Value::as_array)
            .is_some_and(|list| {
                let l: Vec<&str> = list.iter().filter_map(Value::as_str).collect();
                l == [a, b] || l == [b, a]
            })
    };
    match t.get_mut("contact") {
        Some(Value::Table(c)) if p == 0 => Ok(c),
        Some(Value::Array(list)) => {
            let lone = list.len() == 1 && pairs == 1 && list[0].get("between").is_none();
            let at = if lone {
                Some(0)
            } else {
                list.iter().position(names_pair)
            };
            match at.and_then(|i| list.get_mut(i)) {
                Some(Value::Table(c)) => Ok(c),
                _ => Err(format!(
                    "contact[{}]: the base scenario has no [[contact]] table with between = \
                     [\"{a}\", \"{b}\"]",
                    p + 1
                )),
            }
        }
        _ => Err(format!(
            "contact[{}]: the base scenario has no contact table for \"{a}\"–\"{b}\"",
            p + 1
        )),
    }
}

/// Level `i` (0-based) of pair `p`'s contact: its `level` list (`level = [...]` or
/// `[[contact.level]]` tables).
pub(super) fn pair_level_mut(t: &mut Table, p: usize, i: usize) -> Result<&mut Table, String> {
    let c = pair_contact_mut(t, p)?;
    match c.get_mut("level") {
        Some(Value::Array(a)) => {
            let n = a.len();
            match a.get_mut(i) {
                Some(Value::Table(s)) => Ok(s),
                _ => Err(format!(
                    "contact[{}].level[{}]: the pair's contact has {n} level(s)",
                    p + 1,
                    i + 1
                )),
            }
        }
        _ => Err(format!(
            "contact[{}].level[{}]: the pair's contact has no levels (`level = [...]`); sweep \
             contact[{}].gap or contact[{}].height",
            p + 1,
            i + 1,
            p + 1,
            p + 1
        )),
    }
}

/// The number of structures and, per adjacent pair, its contact's number of levels (`None`
/// without a `level` list) of a base scenario table; a pair whose table is missing is left
/// out (the base scenario's own validation names it).
pub(super) fn row_shape(t: &Table) -> (usize, Vec<Option<Option<usize>>>) {
    let mut t = t.clone();
    let n = structure_names(&t).len();
    let pairs = (0..n.saturating_sub(1))
        .map(|p| {
            pair_contact_mut(&mut t, p)
                .ok()
                .map(|c| c.get("level").and_then(Value::as_array).map(Vec::len))
        })
        .collect();
    (n, pairs)
}
