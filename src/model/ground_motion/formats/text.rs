//! What the readers share: numbers as Fortran writes them, Fortran edit descriptors such as
//! `(8F10.5)` and the fixed-width fields they describe (which may touch: `-12.34567-23.45678`).

use crate::model::ground_motion::STANDARD_GRAVITY;
use crate::model::ground_motion::error::{RecordError, clip, record_line};

/// Largest magnitude of a value in a file, in the file's units: beyond it the conversion to
/// m/s² (at most ×9.80665, from g) could overflow.
const MAX_VALUE: f64 = f64::MAX / STANDARD_GRAVITY;

/// Parses one finite number as Fortran writes it: `.1394908E-02`, `1.5D+03`, `-.123-100`
/// (an exponent without its letter), `+.5`.
pub(crate) fn parse_number(token: &str, file: &str, line: usize) -> Result<f64, RecordError> {
    // (a token whose first and last bytes are ASCII and not whitespace has nothing to trim:
    // the readers' tokens, split at ASCII separators, are such; `trim` costs ~50 instructions)
    let b = token.as_bytes();
    let t = match (b.first(), b.last()) {
        (Some(f), Some(l)) if f.is_ascii_graphic() && l.is_ascii_graphic() => token,
        _ => token.trim(),
    };
    let x = match t.parse::<f64>() {
        Ok(x) => Some(x),
        Err(_) => fortran_number(t),
    };
    match x {
        Some(x) if x.is_finite() => Ok(x),
        Some(_) => Err(RecordError::NonFinite {
            at: record_line(file, line),
            token: clip(token),
        }),
        None => Err(RecordError::NotANumber {
            at: record_line(file, line),
            token: clip(token),
        }),
    }
}

/// A value of a data series: a finite number small enough to convert to m/s².
pub(crate) fn parse_value(token: &str, file: &str, line: usize) -> Result<f64, RecordError> {
    let x = parse_number(token, file, line)?;
    if x.abs() > MAX_VALUE {
        return Err(RecordError::OutOfRange {
            at: record_line(file, line),
            token: clip(token),
        });
    }
    Ok(x)
}

/// The Fortran forms Rust's parser does not take: `D` exponents and exponents without a letter.
fn fortran_number(t: &str) -> Option<f64> {
    if t.is_empty() || !t.is_ascii() {
        return None;
    }
    let s = t.replace(['D', 'd'], "E");
    if let Ok(x) = s.parse::<f64>() {
        return Some(x);
    }
    // `1.5-03` is 1.5E-03: a sign after the mantissa starts the exponent
    let bytes = s.as_bytes();
    let at = (1..bytes.len()).find(|&i| {
        matches!(bytes[i], b'+' | b'-') && (bytes[i - 1].is_ascii_digit() || bytes[i - 1] == b'.')
    })?;
    format!("{}E{}", &s[..at], &s[at..]).parse().ok()
}

/// The kind of a Fortran edit descriptor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum EditKind {
    /// `F`, `E`, `D`, `G`: a real.
    Real,
    /// `I`: an integer.
    Integer,
}

/// A Fortran format of one repeated edit descriptor, e.g. `(8F10.5)`: `per_line` fields of
/// `width` characters on each line (the last line may hold fewer).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FortranFormat {
    /// Fields per line.
    pub per_line: usize,
    /// Characters per field.
    pub width: usize,
    /// Digits after the implied decimal point (`F10.5`: 5), used only for fields written
    /// without a point.
    pub decimals: usize,
    /// Real or integer.
    pub kind: EditKind,
    /// The scale factor `kP` (only for fields without an exponent).
    pub scale: i32,
    /// The format as written, for messages.
    pub text: String,
}

impl FortranFormat {
    /// Parses `(8F10.5)`, `8f9.6`, `(1E15.6)`, `(10I8)`, `(1P5E15.6)`, case-insensitive, with or
    /// without the parentheses. `None` for anything else.
    pub fn parse(text: &str) -> Option<FortranFormat> {
        let t = text.trim();
        let inner = t
            .strip_prefix('(')
            .and_then(|s| s.strip_suffix(')'))
            .unwrap_or(t)
            .trim()
            .to_ascii_uppercase();
        let (digits, rest) = split_digits(&inner);
        let mut per_line = if digits.is_empty() {
            1
        } else {
            digits.parse().ok()?
        };
        let mut rest = rest.trim_start_matches(',');
        let mut scale = 0;
        // a scale factor: `1P` then the repeat count
        if let Some(r) = rest.strip_prefix('P') {
            scale = per_line as i32;
            let r = r.trim_start_matches(',');
            let (d, r2) = split_digits(r);
            per_line = if d.is_empty() { 1 } else { d.parse().ok()? };
            rest = r2;
        }
        let mut chars = rest.chars();
        let kind = match chars.next()? {
            'F' | 'E' | 'D' | 'G' => EditKind::Real,
            'I' => EditKind::Integer,
            _ => return None,
        };
        let (w, after) = split_digits(chars.as_str());
        let width: usize = w.parse().ok()?;
        let decimals = match after.strip_prefix('.') {
            Some(d) => {
                let (d, tail) = split_digits(d);
                if !tail.is_empty() {
                    return None;
                }
                d.parse().ok()?
            }
            None if after.is_empty() => 0,
            None => return None,
        };
        (per_line > 0 && per_line <= 1000 && width > 0 && width <= 100).then(|| FortranFormat {
            per_line,
            width,
            decimals,
            kind,
            scale,
            text: format!("({})", inner),
        })
    }

    /// The format of `per_line` fields of `width` characters (a layout's fixed default).
    pub fn fixed(per_line: usize, width: usize, decimals: usize, kind: EditKind) -> FortranFormat {
        let letter = if kind == EditKind::Integer { 'I' } else { 'F' };
        let text = if kind == EditKind::Integer {
            format!("({per_line}{letter}{width})")
        } else {
            format!("({per_line}{letter}{width}.{decimals})")
        };
        FortranFormat {
            per_line,
            width,
            decimals,
            kind,
            scale: 0,
            text,
        }
    }

    /// Reads one field as Fortran would: blanks around the number; a real without a decimal
    /// point has `decimals` implied digits after it (`12345` in F10.3 is 12.345).
    fn field(&self, field: &str, file: &str, line: usize) -> Result<f64, RecordError> {
        let t = field.trim();
        if self.kind == EditKind::Real
            && !t.contains('.')
            && !t.contains(['E', 'e', 'D', 'd'])
            && !t.is_empty()
            && t.bytes().skip(1).all(|b| b.is_ascii_digit())
        {
            let n = parse_number(t, file, line)?;
            let shift = self.decimals as i32 + self.scale;
            return check_size(n / 10f64.powi(shift), field, file, line);
        }
        let x = parse_value(t, file, line)?;
        if self.scale != 0 && self.kind == EditKind::Real && !t.contains(['E', 'e', 'D', 'd']) {
            return check_size(x / 10f64.powi(self.scale), field, file, line);
        }
        Ok(x)
    }
}

fn check_size(x: f64, token: &str, file: &str, line: usize) -> Result<f64, RecordError> {
    if x.is_finite() && x.abs() <= MAX_VALUE {
        Ok(x)
    } else {
        Err(RecordError::OutOfRange {
            at: record_line(file, line),
            token: clip(token),
        })
    }
}

fn split_digits(s: &str) -> (&str, &str) {
    let end = s.find(|c: char| !c.is_ascii_digit()).unwrap_or(s.len());
    s.split_at(end)
}

/// Reads `count` values in the fixed-width `format` from `lines`, starting at index `start`
/// (0-based; messages give 1-based line numbers). Fields are cut by width, so values that touch
/// (`-12.34567-23.45678`) are read correctly; a line whose fields do not parse but which holds
/// exactly the expected number of blank-separated numbers is read by those (a file re-saved
/// with other spacing). Returns the values and the index of the line after the last one read.
pub(crate) fn read_fixed(
    lines: &[&str],
    start: usize,
    count: usize,
    format: &FortranFormat,
    file: &str,
) -> Result<(Vec<f64>, usize), RecordError> {
    // do not trust a header's count for the allocation
    let mut values = Vec::with_capacity(count.min(lines.len().saturating_mul(format.per_line)));
    let mut i = start;
    while values.len() < count {
        let line_no = i + 1;
        let Some(line) = lines.get(i) else {
            return Err(RecordError::TooFewValues {
                at: record_line(file, start.max(1)),
                npts: count,
                found: values.len(),
            });
        };
        let expected = format.per_line.min(count - values.len());
        fixed_fields(line, expected, format, file, line_no)?;
        let parsed = cut(line, expected, format.width).and_then(|fields| {
            fields
                .iter()
                .map(|f| format.field(f, file, line_no))
                .collect::<Result<Vec<f64>, RecordError>>()
                .ok()
        });
        match parsed {
            Some(v) => values.extend(v),
            None => {
                let tokens: Vec<&str> = line.split_whitespace().collect();
                if tokens.len() == expected {
                    for t in tokens {
                        values.push(format.field(t, file, line_no)?);
                    }
                } else {
                    return Err(bad_field(line, expected, format, file, line_no));
                }
            }
        }
        i += 1;
    }
    Ok((values, i))
}

/// Checks that a data line is long enough for `expected` fields (blank-separated numbers of the
/// right count are accepted too).
fn fixed_fields(
    line: &str,
    expected: usize,
    format: &FortranFormat,
    file: &str,
    line_no: usize,
) -> Result<(), RecordError> {
    let body = line.trim_end();
    let need = (expected - 1) * format.width + 1;
    if body.chars().count() >= need || body.split_whitespace().count() == expected {
        return Ok(());
    }
    let found = if format.width > 0 {
        body.chars().count().div_ceil(format.width)
    } else {
        0
    };
    Err(RecordError::ShortLine {
        at: record_line(file, line_no),
        expected,
        width: format.width,
        format: format.text.clone(),
        found: found.min(expected.saturating_sub(1)),
    })
}

/// The `expected` fields of `width` characters of `line` (the last one may be cut short by
/// trailing blanks removed); `None` for a non-ASCII line, which cannot be cut by width.
fn cut(line: &str, expected: usize, width: usize) -> Option<Vec<&str>> {
    let body = line.trim_end();
    if !body.is_ascii() {
        return None;
    }
    let fields: Vec<&str> = (0..expected)
        .map(|k| {
            let a = (k * width).min(body.len());
            let b = ((k + 1) * width).min(body.len());
            &body[a..b]
        })
        .collect();
    fields
        .iter()
        .all(|f| !f.trim().is_empty())
        .then_some(fields)
}

/// The error of a data line whose fields do not parse: the first bad field, by width.
fn bad_field(
    line: &str,
    expected: usize,
    format: &FortranFormat,
    file: &str,
    line_no: usize,
) -> RecordError {
    let chars: Vec<char> = line.trim_end().chars().collect();
    for k in 0..expected {
        let a = (k * format.width).min(chars.len());
        let b = ((k + 1) * format.width).min(chars.len());
        let field: String = chars[a..b].iter().collect();
        if field.trim().is_empty() {
            return RecordError::ShortLine {
                at: record_line(file, line_no),
                expected,
                width: format.width,
                format: format.text.clone(),
                found: k,
            };
        }
        if let Err(e) = format.field(&field, file, line_no) {
            return e;
        }
    }
    // every field parses when cut by characters: a non-ASCII line of numbers
    RecordError::NotANumber {
        at: record_line(file, line_no),
        token: clip(line),
    }
}

/// The first number in `text` after `key` (case-insensitive), e.g. the 12000 of
/// `"No. of Points =  12000"` after `"points ="`.
pub(crate) fn number_after(text: &str, key: &str) -> Option<f64> {
    let upper = text.to_ascii_uppercase();
    let at = upper.find(&key.to_ascii_uppercase())? + key.len();
    first_number(text.get(at..)?)
}

/// The first number in `text` (a run of digits, signs, points and exponents).
pub(crate) fn first_number(text: &str) -> Option<f64> {
    let start = text.find(|c: char| c.is_ascii_digit() || c == '.' || c == '-' || c == '+')?;
    let rest = &text[start..];
    let end = rest
        .char_indices()
        .find(|&(i, c)| {
            !(c.is_ascii_digit()
                || c == '.'
                || (i == 0 && (c == '-' || c == '+'))
                || ((c == 'E' || c == 'e') && i > 0)
                || ((c == '-' || c == '+')
                    && i > 0
                    && matches!(rest.as_bytes()[i - 1], b'E' | b'e')))
        })
        .map_or(rest.len(), |(i, _)| i);
    let token = rest[..end].trim_end_matches(['E', 'e']);
    let x: f64 = token.parse().ok()?;
    x.is_finite().then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_numbers() {
        let p = |t: &str| parse_number(t, "f", 1).unwrap();
        assert_eq!(p(".1394908E-02"), 0.001394908);
        assert_eq!(p("-.123E+01"), -1.23);
        assert_eq!(p("+.5"), 0.5);
        assert_eq!(p("1.E+00"), 1.0);
        assert_eq!(p("1.5D+03"), 1500.0);
        assert_eq!(p("-.123-100"), -0.123e-100);
        assert_eq!(p("2.5+02"), 250.0);
        assert!(matches!(
            parse_number("abc", "f", 3),
            Err(RecordError::NotANumber { .. })
        ));
        assert!(matches!(
            parse_number("inf", "f", 3),
            Err(RecordError::NonFinite { .. })
        ));
        assert!(matches!(
            parse_value("1.7e308", "f", 3),
            Err(RecordError::OutOfRange { .. })
        ));
    }

    #[test]
    fn formats_parse() {
        let f = FortranFormat::parse("(8f10.6)").unwrap();
        assert_eq!((f.per_line, f.width, f.decimals), (8, 10, 6));
        assert_eq!(f.kind, EditKind::Real);
        let f = FortranFormat::parse("(1E15.6)").unwrap();
        assert_eq!((f.per_line, f.width), (1, 15));
        let f = FortranFormat::parse(" (10I8) ").unwrap();
        assert_eq!((f.per_line, f.width, f.kind), (10, 8, EditKind::Integer));
        let f = FortranFormat::parse("(1P5E15.6)").unwrap();
        assert_eq!((f.per_line, f.width, f.scale), (5, 15, 1));
        let f = FortranFormat::parse("E15.6").unwrap();
        assert_eq!(f.per_line, 1);
        for bad in [
            "",
            "()",
            "(8X10)",
            "(8F)",
            "(8F10.x)",
            "(0F10.3)",
            "(8F10.3,2X)",
        ] {
            assert!(FortranFormat::parse(bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn touching_fields_are_cut_by_width() {
        let f = FortranFormat::parse("(4F10.5)").unwrap();
        let lines = [
            "-123.45678-234.56789 345.67891   1.00000",
            "    .50000  -1.00000",
        ];
        let (v, next) = read_fixed(&lines, 0, 6, &f, "x").unwrap();
        assert_eq!(v, vec![-123.45678, -234.56789, 345.67891, 1.0, 0.5, -1.0]);
        assert_eq!(next, 2);
    }

    #[test]
    fn implied_decimal_point() {
        let f = FortranFormat::parse("(3F8.3)").unwrap();
        let (v, _) = read_fixed(&["   12345  -2000    1.5"], 0, 3, &f, "x").unwrap();
        assert_eq!(v, vec![12.345, -2.0, 1.5]);
        let f = FortranFormat::parse("(3I5)").unwrap();
        let (v, _) = read_fixed(&["   12  -20  300"], 0, 3, &f, "x").unwrap();
        assert_eq!(v, vec![12.0, -20.0, 300.0]);
    }

    #[test]
    fn respaced_lines_are_read_by_blanks() {
        let f = FortranFormat::parse("(3F10.3)").unwrap();
        let (v, _) = read_fixed(&["1.5 2.5 3.5"], 0, 3, &f, "x").unwrap();
        assert_eq!(v, vec![1.5, 2.5, 3.5]);
    }

    #[test]
    fn damaged_data_lines_name_the_line() {
        let f = FortranFormat::parse("(4F10.5)").unwrap();
        let lines = ["   1.00000   2.00000   3.00000   4.00000", "   5.00000"];
        let e = read_fixed(&lines, 0, 8, &f, "x").unwrap_err();
        assert!(matches!(e, RecordError::ShortLine { .. }), "{e}");
        assert!(e.to_string().starts_with("record \"x\", line 2: "), "{e}");
        let lines = ["   1.00000   2.0x000   3.00000   4.00000"];
        let e = read_fixed(&lines, 0, 4, &f, "x").unwrap_err();
        assert!(e.to_string().contains("\"2.0x000\" is not a number"), "{e}");
        let e = read_fixed(&lines, 0, 9, &f, "x").unwrap_err();
        assert!(matches!(
            e,
            RecordError::ShortLine { .. } | RecordError::NotANumber { .. }
        ));
        let lines = ["   1.00000   2.00000   3.00000   4.00000"];
        let e = read_fixed(&lines, 0, 9, &f, "x").unwrap_err();
        assert!(
            matches!(
                e,
                RecordError::TooFewValues {
                    npts: 9,
                    found: 4,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn numbers_in_text() {
        assert_eq!(
            number_after("No. of Points =  13200  Record", "points ="),
            Some(13200.0)
        );
        assert_eq!(first_number("at    .005  sec"), Some(0.005));
        assert_eq!(first_number("= -1.5E-3 g"), Some(-1.5e-3));
        assert_eq!(first_number("no number"), None);
    }
}
