//! What a scenario file's errors say and where: [`Location`] (file, line, column: the crate's
//! `diagnostics` kit, shared with sweeps and record readers),
//! [`ScenarioError`], the parse context `Ctx` (TOML errors with the key and a suggestion, the
//! usual-band warnings) and `Check`, the validator of one key against its range.

use std::fmt;
use std::sync::Arc;

use toml::Spanned;

use super::MIN_RESTITUTION;
use super::keys::table_with_keys;
use super::ranges::{physical_range, unusual};

pub use crate::diagnostics::Location;
pub(crate) use crate::diagnostics::{key_hint, unknown_field};

/// Why a scenario was refused.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("cannot read scenario {path}: {source}")]
    Read {
        /// Path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not valid TOML, or a value of the wrong type.
    #[error("{at}: {message}")]
    Syntax {
        /// Where.
        at: Location,
        /// What the TOML parser said.
        message: String,
    },
    /// A key that the format does not have.
    #[error("{at}: unknown key `{key}` in {section}{hint}")]
    UnknownKey {
        /// Where.
        at: Location,
        /// The key.
        key: String,
        /// The table it is in.
        section: String,
        /// "; did you mean …? valid keys: …"
        hint: String,
    },
    /// Several required keys are absent: every one, in file order.
    #[error("{file}: {} required keys are missing:{}", .missing.len(), list_missing(.missing))]
    MissingMany {
        /// The scenario file.
        file: String,
        /// (where, key, what is expected) of each.
        missing: Vec<(Location, String, String)>,
    },
    /// The file is a sweep file, not a scenario.
    #[error(
        "{file}: this is a sweep file ({why}), not a scenario: run it with `pounding sweep {file}`, or print one of its cases as a scenario with `pounding sweep {file} --case N`"
    )]
    SweepFile {
        /// The file.
        file: String,
        /// What gave it away.
        why: String,
    },
    /// A required key is absent.
    #[error("{at}: missing key `{key}`: {expected}")]
    Missing {
        /// Where (the file, or the table).
        at: Location,
        /// Full key path, e.g. `structure[1].mass`.
        key: String,
        /// What is expected.
        expected: String,
    },
    /// A value outside its allowed range or an inconsistent combination.
    #[error("{at}: `{key}` = {value}: {reason}")]
    Invalid {
        /// Where.
        at: Location,
        /// Full key path.
        key: String,
        /// The value as given.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// The ground-motion record could not be read.
    #[error("{at}: `{key}`: {source}")]
    Record {
        /// Where the file is named.
        at: Location,
        /// The key.
        key: String,
        /// The reader's error.
        source: Box<crate::model::ground_motion::RecordError>,
    },
}

pub(super) fn list_missing(missing: &[(Location, String, String)]) -> String {
    missing
        .iter()
        .map(|(at, key, expected)| format!("\n  {at}: `{key}`: {expected}"))
        .collect()
}

pub(crate) struct Ctx<'a> {
    pub(crate) text: &'a str,
    pub(crate) file: &'a str,
    pub(crate) name: Arc<str>,
    /// Values inside their range but outside the usual band ([`usual_range`]), as warnings.
    pub(crate) warnings: std::cell::RefCell<Vec<String>>,
}

impl Ctx<'_> {
    pub(crate) fn at(&self, offset: Option<usize>) -> Location {
        Location::in_text(self.name.clone(), self.text, offset)
    }

    pub(crate) fn toml_error(&self, e: &toml::de::Error) -> ScenarioError {
        let at = self.at(e.span().map(|s| s.start));
        let msg = e.message().trim().to_string();
        if let Some((key, expected)) = unknown_field(&msg) {
            let (section, valid) = self.section_for(&expected);
            return ScenarioError::UnknownKey {
                at,
                hint: key_hint(&key, &valid),
                key,
                section,
            };
        }
        // a duplicate: name the table or key and both lines
        if msg.starts_with("duplicate key")
            && let Some(message) = e.span().and_then(|sp| self.duplicate(sp.start))
        {
            return ScenarioError::Syntax { at, message };
        }
        // name the key when the offending line is a `key = value` line
        let message = match e.span().and_then(|sp| self.key_on_line(sp.start)) {
            Some(key) => format!("`{key}`: {msg}"),
            None => msg,
        };
        ScenarioError::Syntax { at, message }
    }

    /// What a "duplicate key" at byte `offset` repeats, with the line where it first stood:
    /// a table header (`[contact]` given twice) or a key within the same table.
    pub(super) fn duplicate(&self, offset: usize) -> Option<String> {
        let offset = offset.min(self.text.len());
        let start = self.text.get(..offset)?.rfind('\n').map_or(0, |p| p + 1);
        let line_no = self.text[..start].matches('\n').count() + 1;
        let line = self.text.get(start..)?.lines().next()?.trim();
        let lines: Vec<&str> = self.text.lines().collect();
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            let name = name.trim();
            let first = lines[..line_no - 1].iter().position(|l| {
                l.trim()
                    .strip_prefix('[')
                    .and_then(|l| l.strip_suffix(']'))
                    .is_some_and(|n| n.trim() == name)
            })?;
            return Some(format!(
                "`{name}`: the table [{name}] is given twice (first at line {}, again at line \
                 {line_no}); merge the two",
                first + 1
            ));
        }
        let key = self.key_on_line(offset)?;
        // the earlier line with the same key in the same table (back to the table's header)
        let first = lines[..line_no - 1]
            .iter()
            .enumerate()
            .rev()
            .take_while(|(_, l)| !l.trim_start().starts_with('['))
            .find(|(_, l)| l.split_once('=').is_some_and(|(k, _)| k.trim() == key))
            .map(|(i, _)| i + 1)?;
        Some(format!(
            "`{key}`: given twice in the same table (first at line {first}, again at line \
             {line_no}); keep one"
        ))
    }

    /// The key of a `key = value` line containing byte `offset`.
    pub(super) fn key_on_line(&self, offset: usize) -> Option<String> {
        let offset = offset.min(self.text.len());
        let start = self.text.get(..offset)?.rfind('\n').map_or(0, |p| p + 1);
        let line = self.text.get(start..)?.lines().next()?;
        let (key, _) = line.split_once('=')?;
        let key = key.trim();
        let ok = !key.is_empty()
            && key
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.');
        ok.then(|| key.to_string())
    }

    /// The table an unknown key sits in, and its valid keys: the table whose keys are exactly
    /// serde's list of expected keys (every table's key set is distinct, tested in
    /// `tests/unknown_keys.rs`).
    pub(super) fn section_for(&self, expected: &[String]) -> (String, Vec<String>) {
        if let Some(t) = table_with_keys(expected) {
            return (
                t.title().to_string(),
                t.names().iter().map(|k| k.to_string()).collect(),
            );
        }
        // (not reached for the tables of a scenario; a table added without its entry in
        // TABLES still gets its keys listed)
        ("this table".to_string(), expected.to_vec())
    }
}

/// A validator for one key: checks the value against a range and reports with its location.
pub(crate) struct Check<'a, 'c> {
    pub(crate) ctx: &'c Ctx<'a>,
}

impl Check<'_, '_> {
    pub(crate) fn invalid<T: fmt::Display>(
        &self,
        v: &Spanned<T>,
        key: &str,
        reason: &str,
    ) -> ScenarioError {
        ScenarioError::Invalid {
            at: self.ctx.at(Some(v.span().start)),
            key: key.to_string(),
            value: v.get_ref().to_string(),
            reason: reason.to_string(),
        }
    }

    pub(crate) fn missing(&self, key: &str, expected: &str, near: Option<usize>) -> ScenarioError {
        ScenarioError::Missing {
            at: self.ctx.at(near),
            key: key.to_string(),
            expected: expected.to_string(),
        }
    }

    /// A finite number > 0 (unit in the message).
    pub(crate) fn positive(
        &self,
        v: &Spanned<f64>,
        key: &str,
        unit: &str,
    ) -> Result<f64, ScenarioError> {
        let x = *v.get_ref();
        if x.is_finite() && x > 0.0 {
            self.in_range(v, key, unit)
        } else {
            Err(self.invalid(v, key, &format!("must be a finite number > 0 ({unit})")))
        }
    }

    /// A finite number ≥ 0.
    pub(super) fn non_negative(
        &self,
        v: &Spanned<f64>,
        key: &str,
        unit: &str,
    ) -> Result<f64, ScenarioError> {
        let x = *v.get_ref();
        if x.is_finite() && x >= 0.0 {
            self.in_range(v, key, unit)
        } else {
            Err(self.invalid(v, key, &format!("must be a finite number ≥ 0 ({unit})")))
        }
    }

    /// `v` within the physical range of `key` ([`physical_range`]), if it has one.
    pub(super) fn in_range(
        &self,
        v: &Spanned<f64>,
        key: &str,
        unit: &str,
    ) -> Result<f64, ScenarioError> {
        let x = *v.get_ref();
        match physical_range(key) {
            Some((lo, hi, what)) if !(lo..=hi).contains(&x) => Err(ScenarioError::Invalid {
                at: self.ctx.at(Some(v.span().start)),
                key: key.to_string(),
                // (shortest form: 1e300, not three hundred digits)
                value: format!("{x:?}"),
                reason: format!("must be in [{lo:e}, {hi:e}] {unit} ({what})"),
            }),
            _ => {
                self.usual(x, key, unit);
                Ok(x)
            }
        }
    }

    /// Records a warning when `x` is outside the usual band of `key` ([`usual_range`]).
    /// A list warns once, for its first unusual value.
    pub(crate) fn usual(&self, x: f64, key: &str, unit: &str) {
        if let Some(w) = unusual(x, key, unit) {
            let mut list = self.ctx.warnings.borrow_mut();
            let named = format!("`{key}` = ");
            if !list.iter().any(|o| o.starts_with(&named)) {
                list.push(w);
            }
        }
    }

    pub(crate) fn required<'v, T>(
        &self,
        v: &'v Option<Spanned<T>>,
        key: &str,
        expected: &str,
        near: Option<usize>,
    ) -> Result<&'v Spanned<T>, ScenarioError> {
        v.as_ref().ok_or_else(|| self.missing(key, expected, near))
    }

    pub(super) fn restitution(&self, v: &Spanned<f64>, key: &str) -> Result<f64, ScenarioError> {
        let e = *v.get_ref();
        if e.is_finite() && (MIN_RESTITUTION..=1.0).contains(&e) {
            Ok(e)
        } else {
            Err(self.invalid(
                v,
                key,
                &format!(
                    "coefficient of restitution must be in [{MIN_RESTITUTION}, 1] (the damping of \
                     the jankowski and hunt-crossley laws grows as 1/e: below {MIN_RESTITUTION} \
                     it stalls the solver; for a plastic impact use law = \"stereomechanical\" \
                     with restitution = 0)"
                ),
            ))
        }
    }
}

pub(super) fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A list value that is wrong as a whole (its length, an element): the error quotes the list,
/// cut to 60 characters.
pub(super) fn list_error<T: std::fmt::Debug>(
    c: &Check,
    v: &Spanned<T>,
    key: &str,
    reason: String,
) -> ScenarioError {
    let value = format!("{:?}", v.get_ref());
    ScenarioError::Invalid {
        at: c.ctx.at(Some(v.span().start)),
        key: key.to_string(),
        value: if value.len() > 60 {
            format!("{}…", &value[..value.floor_char_boundary(57)])
        } else {
            value
        },
        reason,
    }
}
