//! The dispatcher: detection from the content, non-text files, components, units, robustness.

use super::*;
use crate::model::ground_motion::formats::testutil::*;
use crate::model::ground_motion::record::*;

// ---------------------------------------------------------------- robustness

fn exercise(text: &str) {
    let opts = [
        no_opts(),
        with_dt(0.01),
        RecordOptions {
            dt: Some(0.01),
            ..with_scale(0.5)
        },
        RecordOptions {
            units: Some(AccelUnits::G),
            dt: Some(1e-300),
            scale_to_pga: Some(1e300),
            ..RecordOptions::default()
        },
    ];
    for name in ["f.AT2", "f.txt", "f", ""] {
        for o in &opts {
            match Record::parse(text, Path::new(name), o) {
                Ok(r) => {
                    assert!(r.num_samples() >= 2 && r.dt > 0.0);
                    for t in [-1.0, 0.0, 0.3 * r.duration(), r.duration(), 1e9, f64::NAN] {
                        let _ = r.accel_and_velocity_at(t);
                    }
                }
                Err(e) => {
                    let msg = e.to_string();
                    assert!(msg.starts_with(&format!("record \"{name}\"")), "{msg}");
                }
            }
        }
    }
}

#[test]
fn random_bytes_never_panic() {
    let mut rng = Lcg(12345);
    for _ in 0..300 {
        let len = rng.below(200);
        let bytes: Vec<u8> = (0..len)
            .map(|_| {
                // Bias towards the characters the parsers care about.
                const BIASED: &[u8] = b"0123456789.eE+-,; \t\n\r#NPTSDTsec=";
                if rng.below(4) == 0 {
                    rng.below(256) as u8
                } else {
                    BIASED[rng.below(BIASED.len())]
                }
            })
            .collect();
        exercise(&String::from_utf8_lossy(&bytes));
    }
}

#[test]
fn random_token_lines_never_panic() {
    const TOKENS: &[&str] = &[
        "NPTS=",
        "DT=",
        "NPTS",
        "DT",
        "SEC",
        "SEC,",
        "5",
        "2",
        "1",
        "0",
        "-1",
        ".01",
        "0.01",
        "-.5E+01",
        "1e308",
        "1e-320",
        "nan",
        "inf",
        "-inf",
        "abc",
        "t,a",
        ",",
        ";",
        "#",
        " ",
        "  ",
        "\t",
        "\n",
        "\n",
        "\n",
        "\r\n",
        "99999999999999999999",
        "1.5",
        "é",
        "NPTS=2,",
    ];
    let mut rng = Lcg(987);
    for i in 0..400 {
        let mut text = String::new();
        if i % 2 == 0 {
            text.push_str(AT2_HEAD);
        }
        for _ in 0..rng.below(60) {
            text.push_str(TOKENS[rng.below(TOKENS.len())]);
            if rng.below(3) == 0 {
                text.push(' ');
            }
        }
        exercise(&text);
    }
}
