//! Where in an input file something is: [`Location`] (file, line, column) and [`line_col`], and
//! what serde's unknown-key message means ([`unknown_field`], [`key_hint`]): shared by every
//! reader of user files — scenarios and sweeps (`file:line:col`, the form
//! editors jump to) and ground-motion records (`record "x.AT2", line 7`, since a record's
//! message is usually quoted inside a scenario's).

use std::fmt;
use std::num::NonZeroU32;
use std::sync::Arc;

/// Where in an input file something is: the file as given, and the 1-based line and column
/// when known. Displays as `file:line:col` (`file:line`, `file`), or, for a record
/// ([`Naming::Record`]), as `record "file", line N`. (32 bytes: errors carry it by value.)
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file as given (or what stands for it, e.g. a record's description).
    pub file: Arc<str>,
    /// 1-based line, when known.
    pub line: Option<NonZeroU32>,
    /// 1-based column (in bytes of the line), when known.
    pub column: Option<NonZeroU32>,
    /// How messages name the file.
    pub naming: Naming,
}

/// How a message names the file of a [`Location`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Naming {
    /// `file:line:col`, the form editors and compilers use (scenarios, sweeps).
    Path,
    /// `record "file", line N`: a ground-motion record, whose messages are usually quoted
    /// inside a scenario's (`s.toml:5:8: `ground_motion.file`: record "x.AT2", line 7: …`).
    Record,
}

/// A 1-based number (never 0; saturating at `u32::MAX`).
fn one_based(n: usize) -> Option<NonZeroU32> {
    NonZeroU32::new(u32::try_from(n).unwrap_or(u32::MAX))
}

impl Location {
    /// The whole file.
    pub fn file(file: impl Into<Arc<str>>) -> Location {
        Location {
            file: file.into(),
            line: None,
            column: None,
            naming: Naming::Path,
        }
    }

    /// The byte `offset` of `text` (the file's contents), when known: its line and column.
    pub fn in_text(file: impl Into<Arc<str>>, text: &str, offset: Option<usize>) -> Location {
        let mut at = Location::file(file);
        if let Some(o) = offset {
            let (line, column) = line_col(text, o);
            at.line = NonZeroU32::new(line);
            at.column = NonZeroU32::new(column);
        }
        at
    }

    /// The same file at one 1-based line.
    pub fn at_line(mut self, line: usize) -> Location {
        self.line = one_based(line);
        self.column = None;
        self
    }

    /// The same place, named as `naming` says.
    pub fn named(mut self, naming: Naming) -> Location {
        self.naming = naming;
        self
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.naming {
            Naming::Record => {
                write!(f, "record \"{}\"", self.file)?;
                if let Some(line) = self.line {
                    write!(f, ", line {line}")?;
                }
                if let Some(column) = self.column {
                    write!(f, ", column {column}")?;
                }
                Ok(())
            }
            Naming::Path => {
                write!(f, "{}", self.file)?;
                if let Some(line) = self.line {
                    write!(f, ":{line}")?;
                    if let Some(column) = self.column {
                        write!(f, ":{column}")?;
                    }
                }
                Ok(())
            }
        }
    }
}

/// The 1-based line and column of byte `offset` of `text` (an offset past the end, or inside a
/// character, is taken back to the last character boundary before it).
pub fn line_col(text: &str, offset: usize) -> (u32, u32) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rfind('\n').map_or(offset, |p| offset - p - 1) + 1;
    (
        u32::try_from(line).unwrap_or(u32::MAX),
        u32::try_from(col).unwrap_or(u32::MAX),
    )
}

/// The unknown key and the keys the table accepts, from the message of serde's
/// `deny_unknown_fields`, in each of its forms: "unknown field `k`, expected one of `a`, `b`,
/// `c`", "… expected `a` or `b`", "… expected `a`" and "… there are no fields". `None` for
/// any other message.
pub fn unknown_field(msg: &str) -> Option<(String, Vec<String>)> {
    let rest = msg.strip_prefix("unknown field `")?;
    let end = rest.find('`')?;
    let key = rest[..end].to_string();
    let list = rest[end + 1..]
        .split_once("expected one of ")
        .or_else(|| rest[end + 1..].split_once("expected "))
        .map_or("", |(_, l)| l);
    let expected = list
        .split(", ")
        .flat_map(|part| part.split(" or "))
        .map(|k| k.trim().trim_matches('`'))
        .filter(|k| !k.is_empty())
        .map(str::to_string)
        .collect();
    Some((key, expected))
}

/// What follows "unknown key `key` in TABLE": the closest valid key when one is close
/// ("; did you mean `period`?") and every valid key ("(valid keys: a, b)"; "(the table takes
/// no keys)" when there are none).
pub fn key_hint<S: AsRef<str>>(key: &str, valid: &[S]) -> String {
    let best = valid
        .iter()
        .map(|v| (strsim::jaro_winkler(key, v.as_ref()), v.as_ref()))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    let mut hint = String::new();
    if let Some((score, v)) = best
        && score > 0.75
    {
        hint.push_str(&format!("; did you mean `{v}`?"));
    }
    if valid.is_empty() {
        hint.push_str(" (the table takes no keys)");
    } else {
        let names: Vec<&str> = valid.iter().map(AsRef::as_ref).collect();
        hint.push_str(&format!(" (valid keys: {})", names.join(", ")));
    }
    hint
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_of_an_offset() {
        let text = "a = 1\nbé = 2\n";
        // 'b' opens line 2; '=' is after the two bytes of 'é' and a space
        assert_eq!(line_col(text, 0), (1, 1));
        assert_eq!(line_col(text, 6), (2, 1));
        assert_eq!(line_col(text, 10), (2, 5));
        // inside 'é' (bytes 7–8): back to its start
        assert_eq!(line_col(text, 8), (2, 2));
        assert_eq!(line_col(text, 1000), (3, 1));
    }

    #[test]
    fn both_forms_of_display() {
        let at = Location::in_text("s.toml", "x\ny = 1", Some(4));
        assert_eq!(at.to_string(), "s.toml:2:3");
        assert_eq!(Location::file("s.toml").to_string(), "s.toml");
        let rec = Location::file("x.AT2").named(Naming::Record);
        assert_eq!(rec.to_string(), "record \"x.AT2\"");
        assert_eq!(rec.at_line(7).to_string(), "record \"x.AT2\", line 7");
        // errors carry a Location by value: it stays as small as a fat pointer and two lines
        assert_eq!(std::mem::size_of::<Location>(), 32);
    }
}
