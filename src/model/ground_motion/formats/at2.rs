//! PEER NGA `.AT2` (NGA-West1, NGA-West2 and older): four header lines, the 4th giving the
//! number of points and the time step in any of the forms `NPTS=   7995, DT=   .0050 SEC,`
//! (NGA-West2), `NPTS=  2000, DT= .02000 SEC` (older files) or `4164    0.0100    NPTS, DT`
//! (NGA-West1), case-insensitive and with flexible spacing; then the values, several per line,
//! in g (line 3: `ACCELERATION TIME SERIES IN UNITS OF G`). Files whose 3rd line says VELOCITY
//! or DISPLACEMENT are refused.

use crate::model::ground_motion::error::{RecordError, clip, in_record, record_line};
use crate::model::ground_motion::formats::text::parse_value;
use crate::model::ground_motion::formats::{Channel, Parsed};
use crate::model::ground_motion::record::{AccelUnits, RecordFormat};

/// The units line 3 states (`… IN UNITS OF G`, `… UNITS: CM/S/S`), if it states them.
fn stated_units(line3: &str) -> Option<AccelUnits> {
    let upper = line3.to_ascii_uppercase();
    let at = upper
        .find("UNITS OF")
        .map(|i| i + 8)
        .or_else(|| upper.find("UNITS:").map(|i| i + 6))?;
    let name = upper[at..].split_whitespace().next()?;
    AccelUnits::from_name(name.trim_end_matches([',', '.', ';']))
}

/// If `token` (upper case) is a number, possibly with a glued `SEC`/`SECS`/`S` unit,
/// returns the number part.
fn number_part(token: &str) -> Option<&str> {
    let s = ["SECS", "SEC", "S"]
        .iter()
        .find_map(|unit| token.strip_suffix(unit))
        .filter(|s| !s.is_empty())
        .unwrap_or(token);
    s.parse::<f64>().is_ok().then_some(s)
}

/// If `line` is the 4th line of a PEER AT2 file, returns its NPTS and DT fields (text).
///
/// Accepted, case-insensitive and with any spacing: `NPTS= 7995, DT= .0050 SEC,`,
/// `NPTS= 2000, DT= .02000 SEC` and `4164 0.0100 NPTS, DT`.
pub fn header_fields(line: &str) -> Option<(String, String)> {
    let upper: String = line
        .chars()
        .map(|c| match c {
            ',' | '=' | ':' | ';' => ' ',
            c => c.to_ascii_uppercase(),
        })
        .collect();
    let tokens: Vec<&str> = upper.split_whitespace().collect();
    let npts_pos = tokens.iter().position(|t| *t == "NPTS")?;
    let dt_pos = tokens.iter().position(|t| *t == "DT")?;
    let number_after = |pos: usize| tokens.get(pos + 1).and_then(|t| number_part(t));
    if let (Some(n), Some(d)) = (number_after(npts_pos), number_after(dt_pos)) {
        return Some((n.to_string(), d.to_string()));
    }
    // NGA-West1: the two numbers first, then the keywords in the same order.
    if npts_pos < dt_pos {
        let n = tokens.first().and_then(|t| number_part(t))?;
        let d = tokens.get(1).and_then(|t| number_part(t))?;
        if npts_pos >= 2 {
            return Some((n.to_string(), d.to_string()));
        }
    }
    None
}

/// Parses NPTS: a non-negative integer (written `7995`, or `7995.` / `7.995E3`).
fn parse_npts(token: &str) -> Option<usize> {
    if let Ok(n) = token.parse::<usize>() {
        return Some(n);
    }
    let x = token.parse::<f64>().ok()?;
    // Below 2^53, so the conversion is exact.
    (x.is_finite() && x >= 0.0 && x.fract() == 0.0 && x < 9.0e15).then_some(x as usize)
}

/// The blank- or comma-separated tokens of a data line. An ASCII line (every line of a PEER
/// file) is cut on its bytes — the ASCII characters `char::is_whitespace` takes (tab, line
/// feed, vertical tab, form feed, carriage return, space) and the comma — without decoding
/// characters; any other line by characters. The same tokens either way.
fn value_tokens(line: &str) -> impl Iterator<Item = &str> {
    let ascii = line.is_ascii();
    let by_char = (!ascii).then(|| {
        line.split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
    });
    let bytes = line.as_bytes();
    let mut at = 0;
    let by_byte = std::iter::from_fn(move || {
        if !ascii {
            return None;
        }
        let sep = |b: u8| matches!(b, b'\t' | b'\n' | 0x0b | 0x0c | b'\r' | b' ' | b',');
        while at < bytes.len() && sep(bytes[at]) {
            at += 1;
        }
        let start = at;
        while at < bytes.len() && !sep(bytes[at]) {
            at += 1;
        }
        (at > start).then(|| &line[start..at])
    });
    by_char.into_iter().flatten().chain(by_byte)
}

/// Reads a PEER NGA `.AT2` file: one channel, units from line 3 (`… IN UNITS OF G`), g when
/// it does not say.
pub fn read(text: &str, file: &str) -> Result<Parsed, RecordError> {
    let header: Vec<&str> = text.lines().take(4).collect();
    let [_, line2, line3, line4] = *header.as_slice() else {
        return Err(RecordError::MissingHeader {
            at: in_record(file),
            lines: header.len(),
        });
    };

    let bad_header = || RecordError::BadHeader {
        at: record_line(file, 4),
        found: clip(line4),
    };
    let (npts_text, dt_text) = header_fields(line4).ok_or_else(bad_header)?;
    let npts = parse_npts(&npts_text).ok_or_else(bad_header)?;
    let dt = dt_text.parse::<f64>().map_err(|_| bad_header())?;
    if !(dt.is_finite() && dt > 0.0) {
        return Err(RecordError::InvalidDt {
            at: record_line(file, 4),
            dt,
        });
    }
    let line3_upper = line3.to_ascii_uppercase();
    if line3_upper.contains("VELOCITY") || line3_upper.contains("DISPLACEMENT") {
        return Err(RecordError::NotAcceleration {
            at: record_line(file, 3),
            found: clip(line3),
        });
    }

    let units = stated_units(line3);
    // Do not trust NPTS for the allocation: each value takes at least 2 bytes.
    let mut accel = Vec::with_capacity(npts.min(text.len() / 2 + 1));
    let mut found = 0_usize;
    let mut first_extra_line = None;
    for (i, line) in text.lines().enumerate().skip(4) {
        let line_no = i + 1;
        for token in value_tokens(line) {
            let a = parse_value(token, file, line_no)?;
            found += 1;
            if found <= npts {
                accel.push(a);
            } else if first_extra_line.is_none() {
                first_extra_line = Some(line_no);
            }
        }
    }
    if let Some(line_no) = first_extra_line {
        return Err(RecordError::TooManyValues {
            at: record_line(file, line_no),
            npts,
            found,
        });
    }
    if found < npts {
        return Err(RecordError::TooFewValues {
            at: record_line(file, 4),
            npts,
            found,
        });
    }

    let description = [line2.trim(), line3.trim()]
        .into_iter()
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    Ok(Parsed {
        format: RecordFormat::PeerAt2,
        description: if description.is_empty() {
            file.to_string()
        } else {
            description
        },
        channels: vec![Channel {
            values: accel,
            units,
            dt: Some(dt),
            line: 1,
            ..Channel::default()
        }],
        default_units: AccelUnits::G,
    })
}

#[cfg(test)]
mod tests {
    use crate::model::ground_motion::formats::testutil::*;
    use crate::model::ground_motion::record::*;
    use std::path::{Path, PathBuf};

    /// Directory of the real PEER records bundled with the tests (`tests/data/records/`, with
    /// their source in its README).
    const GROUND_MOTIONS_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/records");

    const G: f64 = STANDARD_GRAVITY;

    /// (file, NPTS, DT in s, PGA in g) from `tests/data/records/README.md` (the data set's own description).
    const README_FACTS: [(&str, usize, f64, f64); 5] = [
        ("RSN753_LOMAP_CLS000.AT2", 7995, 0.005, 0.645),
        ("RSN786_LOMAP_PAE055.AT2", 11999, 0.005, 0.215),
        ("RSN753_LOMAP_CLS090.AT2", 7999, 0.005, 0.483),
        ("RSN808_LOMAP_TRI000.AT2", 7999, 0.005, 0.100),
        ("RSN813_LOMAP_YBI090.AT2", 7999, 0.005, 0.068),
    ];

    fn data_file(name: &str) -> PathBuf {
        Path::new(GROUND_MOTIONS_DIR).join(name)
    }

    /// A data line's tokens cut on bytes are those of the character split they replace, on
    /// lines of digits, signs, points, letters, commas and every kind of blank — ASCII
    /// (tab, vertical tab, form feed, carriage return, space) and not (U+0085, U+00A0, which
    /// is no blank, U+2003, U+3000), which send a line to the character split.
    #[test]
    fn tokens_cut_on_bytes_are_the_character_split() {
        use proptest::prelude::*;
        let chars = prop::sample::select(vec![
            '1', '2', '9', '0', '.', '-', '+', 'E', 'e', 'D', 'x', ',', ' ', ' ', ' ', '\t',
            '\u{b}', '\u{c}', '\r', '\u{85}', '\u{a0}', '\u{2003}', '\u{3000}', 'é',
        ]);
        proptest!(ProptestConfig::with_cases(5000), |(line in prop::collection::vec(chars, 0..40))| {
            let line: String = line.into_iter().collect();
            let want: Vec<&str> = line
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|t| !t.is_empty())
                .collect();
            let got: Vec<&str> = super::value_tokens(&line).collect();
            prop_assert_eq!(got, want, "{:?}", line);
        });
    }

    // ---------------------------------------------------------------- real records

    #[test]
    fn real_records_match_readme() {
        for (name, npts, dt, pga_g) in README_FACTS {
            let path = data_file(name);
            let r = Record::read(&path, &no_opts())
                .unwrap_or_else(|e| panic!("{name}: {e} (is GROUND_MOTIONS_DIR right?)"));
            assert_eq!(r.format, RecordFormat::PeerAt2, "{name}");
            assert_eq!(r.num_samples(), npts, "{name}");
            assert_eq!(r.velocity_samples().len(), npts, "{name}");
            assert!((r.dt - dt).abs() < 1e-12, "{name}: dt {}", r.dt);
            assert!(rel_close(r.duration(), (npts - 1) as f64 * dt, 1e-12));
            assert!(
                (r.pga() / G - pga_g).abs() < 0.0005,
                "{name}: PGA {} g, README {pga_g} g",
                r.pga() / G
            );
            assert!(r.description.contains("Loma Prieta"), "{}", r.description);
            // A dt option that agrees with the file is accepted; one that does not fails.
            assert!(Record::read(&path, &with_dt(0.005)).is_ok());
            let e = Record::read(&path, &with_dt(0.01)).unwrap_err();
            assert!(matches!(e, RecordError::DtMismatch { .. }), "{e}");
            assert!(e.to_string().contains(name));
        }
    }

    #[test]
    fn real_record_first_value_is_in_g() {
        // First value of RSN753_LOMAP_CLS000.AT2 is .1394908E-02 g.
        let r = Record::read(&data_file("RSN753_LOMAP_CLS000.AT2"), &no_opts()).unwrap();
        assert!(rel_close(r.accel[0], 0.1394908e-2 * G, 1e-15));
        assert_eq!(r.accel_at(0.0), r.accel[0]);
        assert_eq!(r.velocity_at(0.0), 0.0);
    }

    #[test]
    fn real_record_scaled_to_pga() {
        let path = data_file("RSN753_LOMAP_CLS000.AT2");
        let plain = Record::read(&path, &no_opts()).unwrap();
        let scaled = Record::read(&path, &with_scale(0.3)).unwrap();
        assert!(rel_close(scaled.pga(), 0.3 * G, 1e-12), "{}", scaled.pga());
        // The shape is kept: each sample scaled by the same factor.
        let factor = 0.3 * G / plain.pga();
        for k in [0, 1, 1000, 5000, 7994] {
            assert!(rel_close(scaled.accel[k], plain.accel[k] * factor, 1e-12));
        }
        assert!(rel_close(
            scaled.velocity_at(20.0),
            plain.velocity_at(20.0) * factor,
            1e-9
        ));
    }

    #[test]
    fn read_missing_file_is_io_error_naming_it() {
        let path = temp_path("does-not-exist.AT2");
        let e = Record::read(&path, &no_opts()).unwrap_err();
        assert!(matches!(e, RecordError::Io { .. }));
        assert!(e.to_string().contains("does-not-exist.AT2"), "{e}");
    }

    #[test]
    fn read_from_temp_files() {
        let path = temp_path("motion.csv");
        std::fs::write(&path, "t,a\n0,0.5\n0.02,1.5\n0.04,-1\n").unwrap();
        let r = Record::read(&path, &no_opts()).unwrap();
        assert_eq!(r.format, RecordFormat::TwoColumn);
        assert_eq!(r.accel, vec![0.5, 1.5, -1.0]);
        assert!(rel_close(r.dt, 0.02, 1e-12));
        assert_eq!(r.description, "motion.csv");

        // Non-UTF-8 bytes in a header (Latin-1 "é") are tolerated.
        let path = temp_path("latin1.AT2");
        let mut bytes = b"PEER NGA STRONG MOTION DATABASE RECORD\nSan Jos\xe9\n".to_vec();
        bytes.extend_from_slice(b"ACCELERATION TIME SERIES IN UNITS OF G\n");
        bytes.extend_from_slice(b"NPTS=   3, DT=   .0100 SEC,\n .1 .2 .3\n");
        std::fs::write(&path, bytes).unwrap();
        let r = Record::read(&path, &no_opts()).unwrap();
        assert_eq!(r.num_samples(), 3);
        assert!(rel_close(r.accel[2], 0.3 * G, 1e-15));
    }

    // ---------------------------------------------------------------- numbers

    #[test]
    fn fortran_style_numbers_parse() {
        assert_eq!(".1394908E-02".parse::<f64>().unwrap(), 0.001394908);
        assert_eq!("-.123E+01".parse::<f64>().unwrap(), -1.23);
        assert_eq!("+.5".parse::<f64>().unwrap(), 0.5);
        assert_eq!("1.E+00".parse::<f64>().unwrap(), 1.0);
        assert_eq!("-.8478295e-05".parse::<f64>().unwrap(), -8.478295e-6);
    }

    // ---------------------------------------------------------------- AT2 headers

    /// Five values 0.01, 0.02, ... 0.05 (g) after the given 4th header line.
    fn at2_with(line4: &str) -> String {
        format!(
            "{AT2_HEAD}{line4}\n   .1000000E-01   .2000000E-01   .3000000E-01\n .4E-01 .5E-01\n"
        )
    }

    fn check_five(r: &Record, dt: f64, factor: f64) {
        assert_eq!(r.format, RecordFormat::PeerAt2);
        assert_eq!(r.num_samples(), 5);
        assert!(rel_close(r.dt, dt, 1e-15), "dt {}", r.dt);
        for (k, a) in r.accel.iter().enumerate() {
            assert!(
                rel_close(*a, (k + 1) as f64 * 0.01 * factor, 1e-14),
                "{k}: {a}"
            );
        }
    }

    #[test]
    fn at2_header_variants() {
        let lines = [
            ("NPTS=      5, DT=   .0100 SEC,                     ", 0.01), // NGA-West2
            ("NPTS=  5, DT= .02000 SEC", 0.02),                            // older PEER
            ("5    0.0100    NPTS, DT", 0.01),                             // NGA-West1
            ("npts=5,dt=.005sec", 0.005),
            ("  Npts =  5 ,  Dt = 0.01 Sec", 0.01),
            ("NPTS= 5, DT= 1.0E-02 SEC,", 0.01),
            ("NPTS= 5., DT= .01", 0.01),
        ];
        for (line4, dt) in lines {
            let text = at2_with(line4);
            // By extension (any case) ...
            for name in ["r.AT2", "r.at2", "dir/r.At2"] {
                check_five(&ok(&text, name, &no_opts()), dt, G);
            }
            // ... and by the 4th line alone.
            for name in ["r.txt", "r"] {
                check_five(&ok(&text, name, &no_opts()), dt, G);
            }
        }
    }

    #[test]
    fn at2_description_units_and_crlf() {
        let text = at2_with("NPTS=   5, DT=   .0100 SEC,").replace('\n', "\r\n");
        let r = ok(&text, "x.AT2", &no_opts());
        check_five(&r, 0.01, G);
        assert_eq!(
            r.description,
            "Test event, 1/1/2000, Station, 0; ACCELERATION TIME SERIES IN UNITS OF G"
        );
        let opts = RecordOptions {
            units: Some(AccelUnits::MetersPerSecond2),
            ..RecordOptions::default()
        };
        check_five(&ok(&text, "x.AT2", &opts), 0.01, 1.0);
        // A byte-order mark does not hide the header.
        check_five(&ok(&format!("\u{feff}{text}"), "x", &no_opts()), 0.01, G);
    }

    // ---------------------------------------------------------------- AT2 errors

    #[test]
    fn at2_truncated_data() {
        let text = format!("{AT2_HEAD}NPTS=   10, DT=   .0100 SEC,\n .1 .2 .3 .4 .5\n .6 .7\n");
        let (e, msg) = fails(&text, "x.AT2", &no_opts(), Some(4));
        assert!(matches!(
            e,
            RecordError::TooFewValues {
                npts: 10,
                found: 7,
                ..
            }
        ));
        assert!(
            msg.contains("NPTS = 10") && msg.contains("only 7 values"),
            "{msg}"
        );
        // Header only: no data at all.
        let text = format!("{AT2_HEAD}NPTS=   10, DT=   .0100 SEC,\n");
        let (e, _) = fails(&text, "x.AT2", &no_opts(), Some(4));
        assert!(matches!(
            e,
            RecordError::TooFewValues {
                npts: 10,
                found: 0,
                ..
            }
        ));
        // An absurd NPTS is reported, not allocated.
        let text = format!("{AT2_HEAD}NPTS= 999999999999999, DT= .01\n .1 .2\n");
        let (e, _) = fails(&text, "x.AT2", &no_opts(), Some(4));
        assert!(matches!(e, RecordError::TooFewValues { found: 2, .. }));
    }

    #[test]
    fn at2_more_values_than_npts() {
        let text = format!("{AT2_HEAD}NPTS=   3, DT=   .0100 SEC,\n .1 .2\n .3\n .4 .5\n");
        let (e, msg) = fails(&text, "x.AT2", &no_opts(), Some(7));
        assert!(matches!(
            e,
            RecordError::TooManyValues {
                npts: 3,
                found: 5,
                ..
            }
        ));
        assert!(msg.contains("NPTS = 3") && msg.contains("has 5"), "{msg}");
    }

    #[test]
    fn at2_non_numeric_value() {
        let text = format!("{AT2_HEAD}NPTS=   4, DT=   .0100 SEC,\n .1 .2\n abc .3\n");
        let (e, msg) = fails(&text, "x.AT2", &no_opts(), Some(6));
        assert!(matches!(e, RecordError::NotANumber { .. }));
        assert_eq!(msg, "record \"x.AT2\", line 6: \"abc\" is not a number");
    }

    #[test]
    fn at2_non_finite_values() {
        for bad in ["NaN", "nan", "inf", "-inf", "infinity", "1e999", "-1E+400"] {
            let text = format!("{AT2_HEAD}NPTS=   3, DT=   .0100 SEC,\n .1\n .2 {bad}\n");
            let (e, msg) = fails(&text, "x.AT2", &no_opts(), Some(6));
            assert!(matches!(e, RecordError::NonFinite { .. }), "{bad}: {msg}");
            assert!(msg.contains(bad), "{msg}");
        }
        // Finite in g but not in m/s².
        let text = format!("{AT2_HEAD}NPTS=   2, DT=   .0100 SEC,\n .1 1.7e308\n");
        let (e, _) = fails(&text, "x.AT2", &no_opts(), Some(5));
        assert!(matches!(e, RecordError::OutOfRange { .. }));
    }

    #[test]
    fn at2_missing_or_bad_header() {
        // Too short to have a header.
        let (e, msg) = fails(" .1 .2 .3\n .4\n", "x.AT2", &no_opts(), None);
        assert!(matches!(e, RecordError::MissingHeader { lines: 2, .. }));
        assert!(msg.contains("NPTS and DT"), "{msg}");
        // Data without a header: line 4 is data.
        let text = " .1 .2\n .3 .4\n .5 .6\n .7 .8\n .9\n";
        let (e, msg) = fails(text, "x.AT2", &no_opts(), Some(4));
        assert!(matches!(e, RecordError::BadHeader { .. }));
        assert!(
            msg.contains("4th line") && msg.contains("NPTS and DT"),
            "{msg}"
        );
        // Keywords without numbers, or a mangled NPTS.
        for line4 in [
            "NPTS, DT",
            "NPTS= abc, DT= .01",
            "NPTS= 5",
            "NPTS= -5, DT= .01",
        ] {
            let (e, _) = fails(&at2_with(line4), "x.AT2", &no_opts(), Some(4));
            assert!(matches!(e, RecordError::BadHeader { .. }), "{line4}: {e}");
        }
    }

    #[test]
    fn at2_bad_dt() {
        for line4 in [
            "NPTS= 5, DT= 0.0 SEC",
            "NPTS= 5, DT= -.01 SEC",
            "NPTS= 5, DT= nan",
        ] {
            let (e, _) = fails(&at2_with(line4), "x.AT2", &no_opts(), Some(4));
            assert!(matches!(e, RecordError::InvalidDt { .. }), "{line4}: {e}");
        }
    }

    #[test]
    fn at2_too_few_samples() {
        let text = format!("{AT2_HEAD}NPTS=   1, DT=   .0100 SEC,\n .1\n");
        let (e, _) = fails(&text, "x.AT2", &no_opts(), None);
        assert!(matches!(e, RecordError::TooFewSamples { found: 1, .. }));
    }

    #[test]
    fn at2_velocity_file_refused() {
        let text = "PEER NGA STRONG MOTION DATABASE RECORD\nx\n\
                    VELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS=   2, DT=   .0100 SEC,\n 1 2\n";
        let (e, _) = fails(text, "x.VT2", &no_opts(), Some(3));
        assert!(matches!(e, RecordError::NotAcceleration { .. }));
    }

    #[test]
    fn empty_files() {
        for text in ["", "   \n\n\t\n", "\u{feff}"] {
            for name in ["x.AT2", "x.txt"] {
                let (e, msg) = fails(text, name, &no_opts(), None);
                assert!(matches!(e, RecordError::Empty { .. }));
                assert_eq!(msg, format!("record \"{name}\": the file is empty"));
            }
        }
    }
}
