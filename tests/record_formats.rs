//! Issue 27 (records in every common layout) and issue 24 (binary files): each reader against
//! the synthetic fixtures of `tests/data/records/formats/` (written from each layout's
//! documentation by `make_fixtures.py` there), whose signal is known by construction:
//!
//! a_k = A sin(2π f k dt) for every sample k but one, a_ks = S (the peak, |S| > A),
//!
//! with A = 150 cm/s² (60 cm/s² on a second channel), f = 1.5 Hz and S = −456.78901 cm/s².
//! Each test checks the count, time step, units, the peak and its time against those numbers
//! and the header's own statement, then the layout's corner cases and damaged variants.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use pounding::input::scenario::Scenario;
use pounding::model::ground_motion::{
    AccelUnits, Baseline, Component, Processing, Record, RecordError, RecordFormat, RecordOptions,
    STANDARD_GRAVITY,
};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/records/formats");
const A: f64 = 150.0;
const F: f64 = 1.5;
const S: f64 = -456.78901;
const GAL: f64 = 0.01;

fn path(name: &str) -> PathBuf {
    Path::new(DIR).join(name)
}

fn opts(component: Option<Component>) -> RecordOptions {
    RecordOptions {
        component,
        ..RecordOptions::default()
    }
}

fn read(name: &str, o: &RecordOptions) -> Record {
    Record::read(&path(name), o).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn fails(name: &str, o: &RecordOptions) -> RecordError {
    match Record::read(&path(name), o) {
        Ok(r) => panic!(
            "{name}: expected an error, read {} samples",
            r.num_samples()
        ),
        Err(e) => e,
    }
}

/// Checks a record against the construction: `n` samples at `dt`, amplitude `amp` and the
/// spike `spike` at `ks` (file units × `to_si`). `tol` is half a unit of the last digit the
/// layout writes, in m/s² (the rounding of the file), plus any stated reason.
#[allow(clippy::too_many_arguments)]
fn check_signal(
    r: &Record,
    n: usize,
    dt: f64,
    amp: f64,
    ks: usize,
    spike: f64,
    to_si: f64,
    tol: f64,
) {
    assert_eq!(r.num_samples(), n);
    assert!((r.dt - dt).abs() < 1e-12 * dt, "dt {}", r.dt);
    for (k, a) in r.accel.iter().enumerate() {
        let want = if k == ks {
            spike
        } else {
            amp * (2.0 * PI * F * k as f64 * dt).sin()
        } * to_si;
        assert!((a - want).abs() <= tol, "sample {k}: {a} vs {want}");
    }
    assert!(
        (r.pga() - spike.abs() * to_si).abs() <= tol,
        "PGA {}",
        r.pga()
    );
    assert!(
        (r.pga_time() - ks as f64 * dt).abs() < 1e-9,
        "{}",
        r.pga_time()
    );
}

// ---------------------------------------------------------------------------- COSMOS

#[test]
fn cosmos_v2_channels_by_number_and_name() {
    // (8F10.5): last digit 1e-5 cm/s² → half a unit 5e-6 cm/s² = 5e-8 m/s²
    for c in [
        Component::Index(1),
        Component::Name("EW".into()),
        Component::Name("90".into()),
    ] {
        let r = read("cosmos_v2.v2c", &opts(Some(c)));
        assert_eq!(r.format, RecordFormat::CosmosV2);
        assert_eq!(r.file_units, Some(AccelUnits::Gal));
        assert_eq!(r.component.as_deref(), Some("Chan 1: 90 Deg"));
        check_signal(&r, 1000, 0.01, A, 321, S, GAL, 5e-8);
        // the header's own peak (Real(64), Real(65)), to the 6 decimals it is written with
        let p = r.stated_peak.unwrap();
        assert!((p.accel - (-456.789) * GAL).abs() < 1e-8);
        assert_eq!(p.time, Some(3.21));
    }
    // the second channel is shorter (997 points) and written as (5E15.6): 7 significant digits
    for c in [
        Component::Index(2),
        Component::Name("up".into()),
        Component::Name("HNZ".into()),
    ] {
        let r = read("cosmos_v2.v2c", &opts(Some(c)));
        assert_eq!(r.component.as_deref(), Some("Chan 2: Up"));
        check_signal(
            &r,
            997,
            0.01,
            0.4 * A,
            500,
            234.56789,
            GAL,
            5e-7 * 60.0 * GAL + 5e-9,
        );
    }
}

#[test]
fn component_errors_list_the_components() {
    let e = fails("cosmos_v2.v2c", &opts(None)).to_string();
    assert!(e.contains("cosmos_v2.v2c"), "{e}");
    assert!(
        e.contains("2 components") && e.contains("1: Chan 1: 90 Deg"),
        "{e}"
    );
    assert!(
        e.contains("2: Chan 2: Up") && e.contains("`component`"),
        "{e}"
    );
    for bad in [Component::Index(3), Component::Name("NS".into())] {
        let e = fails("cosmos_v2.v2c", &opts(Some(bad)));
        assert!(matches!(e, RecordError::NoSuchComponent { .. }), "{e}");
        assert!(e.to_string().contains("Chan 2: Up"), "{e}");
    }
}

#[test]
fn uncorrected_records_are_refused_unless_processed() {
    for (name, what) in [
        ("cosmos_v1.v1c", "COSMOS V1"),
        ("csmip.V1", "CSMIP/DMG V1"),
        ("esm_uncorrected.ASC", "ESM, PROCESSING: none"),
    ] {
        let e = fails(name, &opts(None));
        assert!(matches!(e, RecordError::Uncorrected { .. }), "{name}: {e}");
        let msg = e.to_string();
        assert!(msg.contains(name) && msg.contains(what), "{msg}");
        assert!(
            msg.contains("uncorrected") && msg.contains("processing"),
            "{msg}"
        );
        // processed when asked: the mean removed, band-passed, pads kept
        let p = Processing {
            baseline: Some(Baseline::Linear),
            highpass_hz: Some(0.1),
            lowpass_hz: Some(25.0),
            order: 4,
        };
        let o = RecordOptions {
            processing: Some(p),
            ..RecordOptions::default()
        };
        let r = read(name, &o);
        assert_eq!(r.processing, Some(p));
        let pad = p.pad_seconds(r.dt);
        assert!(pad > 0.0);
        // the peak survives the band-pass (the spike is one sample: its energy is spread over
        // the band, so the peak drops; the sine's 1.5 Hz is in the pass band, |H|² > 0.999)
        assert!(
            r.pga() > 0.9 * A * GAL && r.pga() < 1.05 * S.abs() * GAL,
            "{}",
            r.pga()
        );
    }
}

#[test]
fn cosmos_v1_in_g_converts_to_si() {
    let o = RecordOptions {
        processing: Some(Processing {
            baseline: Some(Baseline::Linear),
            ..Processing::default()
        }),
        ..RecordOptions::default()
    };
    let r = read("cosmos_v1.v1c", &o);
    assert_eq!(r.format, RecordFormat::CosmosV1);
    assert_eq!(r.file_units, Some(AccelUnits::G));
    // the construction in g, less its least-squares line (normal equations in centred time)
    let n = 600;
    let a: Vec<f64> = (0..n)
        .map(|k| {
            let x = if k == 100 {
                S
            } else {
                A * (2.0 * PI * F * k as f64 * 0.01).sin()
            };
            x / 980.665 * STANDARD_GRAVITY
        })
        .collect();
    let tm = 0.5 * (n - 1) as f64 * 0.01;
    let t = |k: usize| k as f64 * 0.01 - tm;
    let c0 = a.iter().sum::<f64>() / n as f64;
    let c1 = (0..n).map(|k| t(k) * a[k]).sum::<f64>() / (0..n).map(|k| t(k) * t(k)).sum::<f64>();
    // written in g to 6 decimals, ε = 5e-7 g each; the fitted line inherits at most ε in c₀ and
    // ε·Σ|t|/Σt² ≤ 1.5ε/|t|max in c₁, so each sample is within 4ε (ε + ε + 1.5ε)
    for (k, (ak, rk)) in a.iter().zip(&r.accel).enumerate() {
        let want = ak - c0 - c1 * t(k);
        let err = (rk - want).abs();
        assert!(err < 4.0 * 5e-7 * STANDARD_GRAVITY, "{k}: {err}");
    }
}

#[test]
fn cosmos_missing_value_and_damaged_header() {
    let text = std::fs::read_to_string(path("cosmos_v2.v2c")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    // a -999.0 placeholder among the data: a gap, refused with its line
    let lines: Vec<&str> = text.lines().collect();
    let data = lines
        .iter()
        .position(|l| l.contains("acceleration pts"))
        .unwrap();
    let mut gap: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
    gap[data + 3] = format!("{:>10}{}", "-999.00000", &gap[data + 3][10..]);
    let f = dir.path().join("gap.v2c");
    std::fs::write(&f, gap.join("\n")).unwrap();
    let e = Record::read(&f, &opts(Some(Component::Index(1)))).unwrap_err();
    assert!(matches!(e, RecordError::MissingValue { .. }), "{e}");
    assert!(
        e.to_string()
            .starts_with(&format!("record \"{}\", line {}: ", f.display(), data + 4)),
        "{e}"
    );
    // the integer-header line damaged: named with its line
    let mut bad: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
    bad[13] = " 100 Integer values".into();
    let f = dir.path().join("bad.v2c");
    std::fs::write(&f, bad.join("\n")).unwrap();
    let e = Record::read(&f, &opts(None)).unwrap_err().to_string();
    assert!(
        e.contains("bad.v2c\", line 14:") && e.contains("COSMOS header"),
        "{e}"
    );
    // truncated data: the count the header gives
    let cut = lines[..data + 50].join("\n");
    let f = dir.path().join("cut.v2c");
    std::fs::write(&f, cut).unwrap();
    let e = Record::read(&f, &opts(None)).unwrap_err();
    assert!(
        matches!(
            e,
            RecordError::TooFewValues {
                npts: 1000,
                found: 392,
                ..
            }
        ),
        "{e}"
    );
}

// ---------------------------------------------------------------------------- CSMIP/DMG

#[test]
fn csmip_v2_channels_of_different_lengths() {
    let r = read("csmip.V2", &opts(Some(Component::Name("360".into()))));
    assert_eq!(r.format, RecordFormat::CsmipV2);
    assert_eq!(r.component.as_deref(), Some("Chan 1: 360 Deg"));
    check_signal(&r, 1000, 0.01, A, 321, S, GAL, 5e-8);
    let p = r.stated_peak.unwrap();
    assert!((p.accel - (-456.789) * GAL).abs() < 1e-9 && p.time == Some(3.21));
    let r = read("csmip.V2", &opts(Some(Component::Name("UP".into()))));
    check_signal(&r, 997, 0.01, 0.4 * A, 500, 234.56789, GAL, 5e-8);
}

#[test]
fn csmip_1980s_layout() {
    // upper case, CR LF, no format on the data line (8F10.3: half a unit 5e-4 cm/s²)
    let r = read("csmip_1980s.V2", &opts(None));
    assert_eq!(r.format, RecordFormat::CsmipV2);
    assert_eq!(r.component.as_deref(), Some("Chan 1: 90 DEG"));
    check_signal(&r, 800, 0.02, A, 123, -456.789, GAL, 5e-6);
}

#[test]
fn csmip_v1_processed() {
    let o = RecordOptions {
        processing: Some(Processing {
            baseline: Some(Baseline::Linear),
            ..Processing::default()
        }),
        ..RecordOptions::default()
    };
    let r = read("csmip.V1", &o);
    assert_eq!(r.format, RecordFormat::CsmipV1);
    assert_eq!(r.num_samples(), 1200);
    assert!((r.dt - 0.005).abs() < 1e-15);
    let p = r.stated_peak.unwrap();
    assert!((p.accel + 0.466 * STANDARD_GRAVITY).abs() < 1e-12);
}

#[test]
fn csmip_mixed_time_steps_and_counts() {
    let text = std::fs::read_to_string(path("csmip.V2")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    // the text header says .005 s, the data line .010 s
    let mixed = text.replacen(
        "At equally-spaced intervals of    .010",
        "At equally-spaced intervals of    .005",
        1,
    );
    assert_ne!(mixed, text);
    let f = dir.path().join("mixed.V2");
    std::fs::write(&f, mixed).unwrap();
    let e = Record::read(&f, &opts(Some(Component::Index(1)))).unwrap_err();
    assert!(matches!(e, RecordError::TimeStepMismatch { .. }), "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("mixed.V2") && msg.contains("0.005") && msg.contains("0.01"),
        "{msg}"
    );
    // the data line damaged: named with its line
    let broken = text.replacen(" 1000 points of accel data", " 1000 pts of accel", 1);
    let f = dir.path().join("broken.V2");
    std::fs::write(&f, broken).unwrap();
    let e = Record::read(&f, &opts(Some(Component::Index(1))))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("broken.V2\", line 46:") && e.contains("CSMIP/DMG header"),
        "{e}"
    );
}

// ---------------------------------------------------------------------------- K-NET, ESM

#[test]
fn knet_counts_scaled_and_mean_removed() {
    let r = read("knet.EW", &opts(Some(Component::Name("EW".into()))));
    assert_eq!(r.format, RecordFormat::Knet);
    assert_eq!(r.component.as_deref(), Some("E-W"));
    // the counts are round(a/s) + 12345 with s = 3920/6182761 gal: after the mean is removed
    // each sample is a − mean(a) to half a count (s/2 gal)
    let s = 3920.0 / 6_182_761.0;
    let a: Vec<f64> = (0..3000)
        .map(|k| {
            if k == 777 {
                S
            } else {
                A * (2.0 * PI * F * k as f64 * 0.01).sin()
            }
        })
        .collect();
    let mean = a.iter().sum::<f64>() / 3000.0;
    for (k, x) in r.accel.iter().enumerate() {
        let want = (a[k] - mean) * GAL;
        assert!(
            (x - want).abs() <= 0.5 * s * GAL + 0.5 * s * GAL,
            "{k}: {x} vs {want}"
        );
    }
    let p = r.stated_peak.unwrap();
    // the header's maximum, written to 3 decimals of a gal
    assert!(
        (p.accel - r.pga()).abs() < 0.0005 * GAL + 1e-12,
        "{} vs {}",
        p.accel,
        r.pga()
    );
}

#[test]
fn esm_units_and_stated_peak() {
    let r = read("esm.ASC", &opts(None));
    assert_eq!(r.format, RecordFormat::Esm);
    assert_eq!(r.file_units, Some(AccelUnits::Gal));
    assert_eq!(r.component.as_deref(), Some("HNE"));
    // written with 6 decimals: half a unit 5e-7 cm/s²
    check_signal(&r, 2500, 0.005, A, 900, S, GAL, 5e-9);
    let p = r.stated_peak.unwrap();
    assert!((p.accel - S.abs() * GAL).abs() < 1e-12 && p.time == Some(4.5));
}

#[test]
fn units_key_overrides_with_a_warning() {
    let o = RecordOptions {
        units: Some(AccelUnits::MetersPerSecond2),
        ..RecordOptions::default()
    };
    let r = read("esm.ASC", &o);
    assert!((r.pga() - S.abs()).abs() < 1e-9);
    assert_eq!(r.warnings.len(), 1);
    assert!(
        r.warnings[0].contains("overrides the file's own units \"cm/s2\""),
        "{:?}",
        r.warnings
    );
    // agreeing with the file: no warning
    let o = RecordOptions {
        units: Some(AccelUnits::Gal),
        ..RecordOptions::default()
    };
    assert!(read("esm.ASC", &o).warnings.is_empty());
}

// ---------------------------------------------------------------------------- issue 24

#[test]
fn binary_files_are_not_text_records() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, Vec<u8>); 3] = [
        ("nul.AT2", b"PEER\n\x00\x01\x02binary".to_vec()),
        ("sub.txt", b"0 1\n0.01 \x1a\x05\n".to_vec()),
        (
            "latin.bin",
            (0..400).map(|i| 0x80 + (i % 100) as u8).collect(),
        ),
    ];
    for (name, bytes) in cases {
        let f = dir.path().join(name);
        std::fs::write(&f, &bytes).unwrap();
        let e = Record::read(&f, &RecordOptions::default()).unwrap_err();
        assert!(matches!(e, RecordError::NotText { .. }), "{name}: {e}");
        let msg = e.to_string();
        assert!(
            msg.contains("not a text record file") && msg.contains(name),
            "{msg}"
        );
        assert!(!msg.contains("\\u{") && !msg.contains("\\x"), "{msg}");
    }
    // a DOS end-of-file mark (Ctrl-Z) after the last line is fine
    let f = dir.path().join("dos.txt");
    std::fs::write(&f, b"0 1\r\n0.01 2\r\n\x1a\x1a").unwrap();
    let r = Record::read(&f, &RecordOptions::default()).unwrap();
    assert_eq!(r.accel, vec![1.0, 2.0]);
}

#[test]
fn a_file_in_no_layout_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("table.csv");
    std::fs::write(&f, "name,x,y,z\n1,2,3,4\n").unwrap();
    let e = Record::read(&f, &RecordOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("table.csv\", line 2:") && e.contains("none of the layouts"),
        "{e}"
    );
}

// ---------------------------------------------------------------------------- scenario keys

fn with_ground(ground: &str) -> String {
    let base = include_str!("../examples/paper-c.toml");
    let start = base.find("[ground_motion]").unwrap();
    let end = base.find("[solver]").unwrap();
    format!("{}{ground}\n\n{}", &base[..start], &base[end..])
}

#[test]
fn scenario_component_and_processing_keys() {
    let dir = Path::new(DIR);
    let sc = |g: &str| Scenario::from_toml(&with_ground(g), "s.toml", dir);
    let ok =
        sc("[ground_motion]\nkind = \"record\"\nfile = \"csmip.V2\"\ncomponent = \"Up\"").unwrap();
    assert!((ok.ground_motion.pga() - 234.56789 * GAL).abs() < 1e-9);
    let ok = sc("[ground_motion]\nkind = \"record\"\nfile = \"csmip.V2\"\ncomponent = 1").unwrap();
    assert!((ok.ground_motion.pga() - S.abs() * GAL).abs() < 1e-9);
    let ok = sc(
        "[ground_motion]\nkind = \"record\"\nfile = \"esm.ASC\"\nunits = \"m/s2\"\n\
                 scale_to_pga = 0.3",
    )
    .unwrap();
    assert!(
        ok.warnings.iter().any(|w| w.contains("overrides")),
        "{:?}",
        ok.warnings
    );
    let ok = sc("[ground_motion]\nkind = \"record\"\nfile = \"csmip.V1\"\n\
                 processing = { baseline = \"polynomial\", highpass_hz = 0.2, lowpass_hz = 30 }")
    .unwrap();
    assert!(ok.ground_motion.pga() > 0.0);
    let cases: &[(&str, &[&str])] = &[
        (
            "file = \"csmip.V2\"",
            &[
                "s.toml:",
                "ground_motion.file",
                "2 components",
                "`component`",
            ],
        ),
        (
            "file = \"csmip.V2\"\ncomponent = 0",
            &["ground_motion.component", "number"],
        ),
        (
            "file = \"csmip.V2\"\ncomponent = \"NS2\"",
            &["no component \"NS2\"", "Chan 2: Up"],
        ),
        ("file = \"csmip.V1\"", &["uncorrected", "processing"]),
        (
            "file = \"csmip.V1\"\nprocessing = { baseline = \"cubic\" }",
            &["ground_motion.processing.baseline", "linear"],
        ),
        (
            "file = \"csmip.V1\"\nprocessing = { highpass_hz = 5.0, lowpass_hz = 1.0 }",
            &["ground_motion.processing.lowpass_hz", "above highpass_hz"],
        ),
        (
            "file = \"csmip.V1\"\nprocessing = { lowpass_hz = 150.0 }",
            &["Nyquist", "100 Hz"],
        ),
        (
            "file = \"csmip.V1\"\nprocessing = { order = 4 }",
            &["at least one of"],
        ),
        (
            "file = \"csmip.V1\"\nprocessing = { baseline = \"linear\", order = 4.0 }",
            &["ground_motion.processing.order", "whole number"],
        ),
        (
            "file = \"csmip.V1\"\nprocessing = { basline = \"linear\" }",
            &["basline", "baseline"],
        ),
    ];
    for (keys, needles) in cases {
        let e = sc(&format!("[ground_motion]\nkind = \"record\"\n{keys}"))
            .expect_err(keys)
            .to_string();
        for n in *needles {
            assert!(e.contains(n), "{keys}: `{n}` missing in: {e}");
        }
    }
}

// ---------------------------------------------------------------------------- the CLI

#[test]
fn pounding_record_prints_text_json_and_csv() {
    let bin = env!("CARGO_BIN_EXE_pounding");
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("a.csv");
    let out = std::process::Command::new(bin)
        .args(["record", "--json", "--component", "2", "--csv"])
        .arg(&csv)
        .arg(path("csmip.V2"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["format"], "csmip-v2");
    assert_eq!(j["component"], "Chan 2: Up");
    assert_eq!(j["points"], 997);
    assert!((j["dt"].as_f64().unwrap() - 0.01).abs() < 1e-15);
    assert!((j["pga"].as_f64().unwrap() - 234.56789 * GAL).abs() < 1e-9);
    assert!((j["pga_time"].as_f64().unwrap() - 5.0).abs() < 1e-12);
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows[0], "t,a");
    assert_eq!(rows.len(), 998);
    let last: Vec<f64> = rows[997].split(',').map(|x| x.parse().unwrap()).collect();
    assert!((last[0] - 9.96).abs() < 1e-12);
    // text, and a clear error for a binary file
    let out = std::process::Command::new(bin)
        .args(["record"])
        .arg(path("knet.EW"))
        .output()
        .unwrap();
    let s = String::from_utf8_lossy(&out.stdout);
    assert!(
        s.contains("K-NET") && s.contains("3000") && s.contains("PGA stated"),
        "{s}"
    );
    let bin_file = dir.path().join("x.AT2");
    std::fs::write(&bin_file, [0u8, 1, 2, 0x1a]).unwrap();
    let out = std::process::Command::new(bin)
        .args(["record"])
        .arg(&bin_file)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(
        e.contains("not a text record file") && !e.contains("\\u{"),
        "{e}"
    );
}
