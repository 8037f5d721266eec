//! One or two columns: `t a` separated by whitespace, commas or semicolons, or one
//! acceleration per line (the time step then comes from the options). Blank lines and lines
//! whose first non-blank character is `#` are skipped, and the first remaining line may be a
//! non-numeric header such as `t,a` or `time (s), accel (g)` (recognised by its first field not
//! being a number). Two-column files take dt = `t[1] − t[0]`, uniform to [`DT_REL_TOLERANCE`], and
//! treat the first sample as t = 0. Units: m/s² unless the options say otherwise.

use std::path::Path;

use crate::model::ground_motion::error::{RecordError, in_record, record_line};
use crate::model::ground_motion::formats::text::{parse_number, parse_value};
use crate::model::ground_motion::formats::{Channel, Parsed};
use crate::model::ground_motion::record::{AccelUnits, DT_REL_TOLERANCE, RecordFormat};

/// Reads one or two columns (see the module).
pub fn read(text: &str, file: &str, path: &Path) -> Result<Parsed, RecordError> {
    let mut columns: Option<usize> = None;
    let mut header_allowed = true;
    let mut accel = Vec::new();
    // Time of the first sample, the first time step, and the time of the previous sample.
    let mut t_first: Option<f64> = None;
    let mut dt: Option<f64> = None;
    let mut t_prev = 0.0;

    for (i, raw) in text.lines().enumerate() {
        let line_no = i + 1;
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut fields = line
            .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .filter(|t| !t.is_empty());
        let count = fields.clone().count();
        let first = fields.next().unwrap_or("");
        if header_allowed {
            header_allowed = false;
            if first.parse::<f64>().is_err() {
                continue; // the optional header line
            }
        }
        let expected = match columns {
            Some(c) => c,
            None if count == 1 || count == 2 => {
                columns = Some(count);
                count
            }
            None => {
                return Err(RecordError::UnrecognisedLayout {
                    at: record_line(file, line_no),
                    found: count,
                });
            }
        };
        if count != expected {
            return Err(RecordError::FieldCount {
                at: record_line(file, line_no),
                expected,
                found: count,
            });
        }
        if expected == 1 {
            accel.push(parse_value(first, file, line_no)?);
            continue;
        }

        let t = parse_number(first, file, line_no)?;
        let a = parse_value(fields.next().unwrap_or(""), file, line_no)?;
        match (t_first, dt) {
            (None, _) => t_first = Some(t),
            (Some(t0), None) => {
                // Times are finite, so the step is never NaN (it may overflow to ∞).
                let step = t - t0;
                if step <= 0.0 {
                    return Err(RecordError::TimeNotIncreasing {
                        at: record_line(file, line_no),
                        previous: t0,
                        time: t,
                    });
                }
                if !step.is_finite() {
                    return Err(RecordError::InvalidDt {
                        at: record_line(file, line_no),
                        dt: step,
                    });
                }
                dt = Some(step);
            }
            (Some(_), Some(dt)) => {
                let step = t - t_prev;
                if step <= 0.0 {
                    return Err(RecordError::TimeNotIncreasing {
                        at: record_line(file, line_no),
                        previous: t_prev,
                        time: t,
                    });
                }
                if (step - dt).abs() > DT_REL_TOLERANCE * dt {
                    return Err(RecordError::NonUniformSpacing {
                        at: record_line(file, line_no),
                        dt,
                        spacing: step,
                    });
                }
            }
        }
        t_prev = t;
        accel.push(a);
    }

    let (format, dt) = match columns {
        Some(2) => {
            if accel.len() < 2 {
                return Err(RecordError::TooFewSamples {
                    at: in_record(file),
                    found: accel.len(),
                });
            }
            (RecordFormat::TwoColumn, dt)
        }
        Some(_) => (RecordFormat::SingleColumn, None),
        None => {
            return Err(RecordError::TooFewSamples {
                at: in_record(file),
                found: 0,
            });
        }
    };
    let description = path
        .file_name()
        .map_or_else(|| file.to_string(), |n| n.to_string_lossy().into_owned());
    Ok(Parsed {
        format,
        description,
        channels: vec![Channel {
            values: accel,
            dt,
            line: 1,
            ..Channel::default()
        }],
        default_units: AccelUnits::MetersPerSecond2,
    })
}

#[cfg(test)]
mod tests {
    use crate::model::ground_motion::formats::testutil::*;
    use crate::model::ground_motion::record::*;

    // ---------------------------------------------------------------- two columns

    #[test]
    fn two_column_with_header_comments_and_separators() {
        let text = "# exported by hand\n\
                    time (s), accel (g)\n\
                    \n\
                    5.00, 0.10\n\
                    5.01; -0.20\n\
                    # a comment in the middle\n\
                    5.02\t0.30\n\
                    5.03 ,  0.40\n";
        let opts = RecordOptions {
            units: Some(AccelUnits::G),
            ..RecordOptions::default()
        };
        let r = ok(text, "dir/motion.csv", &opts);
        assert_eq!(r.format, RecordFormat::TwoColumn);
        assert!(rel_close(r.dt, 0.01, 1e-9), "{}", r.dt);
        let expected = [0.1, -0.2, 0.3, 0.4].map(|a| a * G);
        assert_eq!(r.accel, expected);
        // The time offset of 5 s is ignored: the first sample is at t = 0.
        assert_eq!(r.accel_at(0.0), 0.1 * G);
        assert_eq!(r.accel_at(r.duration() + 1e-9), 0.0);
        assert_eq!(r.description, "motion.csv");
        // Default units are m/s².
        let r = ok("t,a\n0 1\n0.5 2\n", "m.txt", &no_opts());
        assert_eq!(r.accel, vec![1.0, 2.0]);
        assert_eq!(r.dt, 0.5);
    }

    #[test]
    fn two_column_non_uniform_spacing() {
        let text = "t a\n0 1\n0.01 2\n0.02 3\n0.035 4\n0.04 5\n";
        let (e, msg) = fails(text, "m.txt", &no_opts(), Some(5));
        match e {
            RecordError::NonUniformSpacing { dt, spacing, .. } => {
                assert!(rel_close(dt, 0.01, 1e-12));
                assert!(rel_close(spacing, 0.015, 1e-9));
            }
            other => panic!("{other}"),
        }
        assert!(msg.contains(" 0.015 s") && msg.contains(" 0.01 s"), "{msg}");
        // Rounding far below 1e-6 of dt is accepted.
        let mut text = String::new();
        for k in 0..2000 {
            text.push_str(&format!("{} {}\n", k as f64 * 0.005, k % 7));
        }
        let r = ok(&text, "m.txt", &no_opts());
        assert_eq!(r.num_samples(), 2000);
    }

    #[test]
    fn two_column_time_not_increasing() {
        let (e, _) = fails("0 1\n0.01 2\n0.01 3\n", "m.txt", &no_opts(), Some(3));
        assert!(matches!(e, RecordError::TimeNotIncreasing { .. }));
        let (e, msg) = fails("0 1\n-0.01 2\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::TimeNotIncreasing { .. }));
        assert!(msg.contains("-0.01"), "{msg}");
    }

    #[test]
    fn two_column_non_finite_and_non_numeric() {
        let (e, _) = fails("0 1\n0.01 inf\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::NonFinite { .. }));
        let (e, _) = fails("0 1\nNaN 2\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::NonFinite { .. }));
        let (e, msg) = fails("0 1\n0.01 x2\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::NotANumber { .. }));
        assert!(msg.ends_with("\"x2\" is not a number"), "{msg}");
        // A second header line is not allowed.
        let (e, _) = fails("t a\nt a\n0 1\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(e, RecordError::NotANumber { .. }));
    }

    #[test]
    fn layout_errors() {
        let (e, msg) = fails("# c\n\n1 2 3\n", "m.txt", &no_opts(), Some(3));
        assert!(matches!(
            e,
            RecordError::UnrecognisedLayout { found: 3, .. }
        ));
        assert!(msg.contains("found 3"), "{msg}");
        let (e, _) = fails("0 1\n0.01\n", "m.txt", &no_opts(), Some(2));
        assert!(matches!(
            e,
            RecordError::FieldCount {
                expected: 2,
                found: 1,
                ..
            }
        ));
        let (e, _) = fails("1\n2 3\n", "m.txt", &with_dt(0.1), Some(2));
        assert!(matches!(
            e,
            RecordError::FieldCount {
                expected: 1,
                found: 2,
                ..
            }
        ));
    }

    #[test]
    fn dt_option_against_file() {
        let text = "0 1\n0.01 2\n0.02 3\n";
        let (e, msg) = fails(text, "m.txt", &with_dt(0.02), None);
        assert!(matches!(e, RecordError::DtMismatch { .. }));
        assert!(msg.contains("0.02") && msg.contains("0.01"), "{msg}");
        let r = ok(text, "m.txt", &with_dt(0.01 * (1.0 + 1e-7)));
        assert!(rel_close(r.dt, 0.01, 1e-12));
        for bad in [0.0, -0.01, f64::NAN, f64::INFINITY] {
            let (e, _) = fails(text, "m.txt", &with_dt(bad), None);
            assert!(matches!(e, RecordError::InvalidDt { .. }), "{bad}");
        }
    }

    #[test]
    fn too_few_samples_in_text_files() {
        let (e, _) = fails("0 1\n", "m.txt", &no_opts(), None);
        assert!(matches!(e, RecordError::TooFewSamples { found: 1, .. }));
        let (e, _) = fails("t,a\n# nothing\n", "m.txt", &no_opts(), None);
        assert!(matches!(e, RecordError::TooFewSamples { found: 0, .. }));
        let (e, _) = fails("1\n", "m.txt", &with_dt(0.1), None);
        assert!(matches!(e, RecordError::TooFewSamples { found: 1, .. }));
    }

    // ---------------------------------------------------------------- single column

    #[test]
    fn single_column() {
        let text = "# accel\naccel (m/s2)\n1.5\n\n-2.5\n# end\n3.0\n";
        let r = ok(text, "a.dat", &with_dt(0.02));
        assert_eq!(r.format, RecordFormat::SingleColumn);
        assert_eq!(r.accel, vec![1.5, -2.5, 3.0]);
        assert_eq!(r.dt, 0.02);
        let opts = RecordOptions {
            units: Some(AccelUnits::G),
            dt: Some(0.02),
            scale_to_pga: None,
            ..RecordOptions::default()
        };
        assert_eq!(
            ok(text, "a.dat", &opts).accel,
            vec![1.5 * G, -2.5 * G, 3.0 * G]
        );
    }

    #[test]
    fn single_column_without_dt() {
        let (e, msg) = fails("1\n2\n3\n", "a.dat", &no_opts(), None);
        assert!(matches!(e, RecordError::MissingDt { .. }));
        assert!(msg.contains("give `dt` in [ground_motion]"), "{msg}");
    }

    #[test]
    fn single_column_non_finite() {
        for bad in ["nan", "-inf", "1e999"] {
            let (e, _) = fails(&format!("1\n{bad}\n"), "a.dat", &with_dt(0.1), Some(2));
            assert!(matches!(e, RecordError::NonFinite { .. }), "{bad}");
        }
    }
}
