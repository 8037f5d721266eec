//! A record scaled to a target pseudo-spectral acceleration at one period (issue 27,
//! `[ground_motion] scale_to_sa`, `pounding scale --sa`): the scaled record's PSA from an
//! oscillator written here (RK4 on fine sub-steps of the piecewise-linear record, independent of
//! the program's exact recurrence) equals the target; the run equals the run of an explicitly
//! scaled copy bit for bit; every bad input is refused with its file:line:col and key.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Command;

use pounding::analysis::record_spectrum::{scale_to_sa, spectral_point};
use pounding::analysis::simulate::simulate;
use pounding::input::scenario::Scenario;
use pounding::model::ground_motion::scale::sa_factor;
use pounding::model::ground_motion::sdof::pseudo_acceleration;
use pounding::model::ground_motion::{
    GroundMotion, Record, RecordError, RecordOptions, STANDARD_GRAVITY, SaTarget, ScaleTarget,
};

const RECORD: &str = "examples/records/RSN753_LOMAP_CLS000.AT2";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// PSA = ω² max|u| of `ü + 2ζωu̇ + ω²u = −a(t)` from rest, a linear between the samples and 0
/// after the last, by classical RK4 with `m` sub-steps per sample interval (the load evaluated
/// on its line at the stage times), continued 3 periods into the free vibration; the peak is
/// taken over the sub-step ends. Independent of the program's closed-form recurrence.
fn psa_rk4(accel: &[f64], dt: f64, period: f64, zeta: f64, m: usize) -> f64 {
    let w = 2.0 * PI / period;
    let h = dt / m as f64;
    let f = |u: f64, v: f64, a: f64| (v, -a - 2.0 * zeta * w * v - w * w * u);
    let (mut u, mut v, mut peak) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut step = |u: &mut f64, v: &mut f64, a0: f64, am: f64, a1: f64| {
        let (k1u, k1v) = f(*u, *v, a0);
        let (k2u, k2v) = f(*u + 0.5 * h * k1u, *v + 0.5 * h * k1v, am);
        let (k3u, k3v) = f(*u + 0.5 * h * k2u, *v + 0.5 * h * k2v, am);
        let (k4u, k4v) = f(*u + h * k3u, *v + h * k3v, a1);
        *u += h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
        *v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        peak = peak.max(u.abs());
    };
    for pair in accel.windows(2) {
        let at = |s: f64| pair[0] + (pair[1] - pair[0]) * s;
        for j in 0..m {
            let s = j as f64 / m as f64;
            let ds = 1.0 / m as f64;
            step(&mut u, &mut v, at(s), at(s + 0.5 * ds), at(s + ds));
        }
    }
    let tail = (3.0 * period / h).ceil() as usize;
    for _ in 0..tail {
        step(&mut u, &mut v, 0.0, 0.0, 0.0);
    }
    w * w * peak
}

fn read(path: &Path, opts: &RecordOptions) -> Result<Record, RecordError> {
    Record::read(path, opts)
}

/// The bundled record scaled to S_a(T) = 0.4 g at T = 1 s (5 %) and to 0.25 g at T = 0.3 s
/// (2 %): the scaled record's PSA by the RK4 oscillator is the target to 1e-6.
///
/// Tolerance: with m = 40 sub-steps of 0.125 ms, ωh ≤ 2.6e-3 rad: RK4's error is O((ωh)⁴) ≈
/// 5e-11 per period, and a peak taken at the sub-step ends misses the true one by at most
/// (ωh/2)²/2 ≈ 1e-6 of it (at T = 0.3 s; 1e-7 at 1 s). The target itself is met to rounding.
#[test]
fn scaled_record_meets_target_by_an_independent_oscillator() {
    let path = root().join(RECORD);
    let raw = read(&path, &RecordOptions::default()).unwrap();
    for (period, sa, damping) in [(1.0, 0.4, 0.05), (0.3, 0.25, 0.02)] {
        let target = SaTarget {
            period,
            sa,
            damping,
        };
        let opts = RecordOptions {
            scale_to_sa: Some(target),
            ..RecordOptions::default()
        };
        let r = read(&path, &opts).unwrap();
        let psa = psa_rk4(&r.accel, r.dt, period, damping, 40);
        let want = sa * STANDARD_GRAVITY;
        assert!(
            (psa / want - 1.0).abs() < 1.5e-6,
            "T {period}: PSA {psa} vs {want}"
        );
        // what was applied is reported: the factor and the PSA as read (RK4 again, 1e-6)
        let s = r.scaling.unwrap();
        let ScaleTarget::Sa { psa_before, .. } = s.target else {
            panic!("{:?}", s.target)
        };
        let raw_psa = psa_rk4(&raw.accel, raw.dt, period, damping, 40);
        assert!((psa_before / raw_psa - 1.0).abs() < 1.5e-6);
        assert!((s.factor * raw_psa / want - 1.0).abs() < 1.5e-6);
        // every sample is the raw one times that factor, exactly
        for (a, b) in r.accel.iter().zip(&raw.accel) {
            assert_eq!(a.to_bits(), (b * s.factor).to_bits());
        }
        // one oscillator: the analysis layer's PSA and factor are the model's, bit for bit
        let p = spectral_point(&raw.accel, raw.dt, period, damping).psa;
        assert_eq!(
            p.to_bits(),
            pseudo_acceleration(&raw.accel, raw.dt, period, damping).to_bits()
        );
        let f = scale_to_sa(&raw, period, damping, want).unwrap();
        assert_eq!(f.to_bits(), s.factor.to_bits());
    }
}

/// Scaling is linear: a harmonic record at the oscillator's resonance has the steady-state PSA
/// A/(2ζ) (Chopra §3.2, r = 1), so the factor to a target S is 2ζS/A; checked on a sine ramped
/// up and down slowly (1/(ωt_r)² transients ≈ 1e-5, and the approach to the steady state over
/// the 150 s plateau against 1/(ζω) = 3.2 s: tolerance 3e-4, as tests/record_spectrum.rs).
#[test]
fn resonant_sine_factor_is_the_steady_state_one() {
    let (a, period, dt, zeta) = (2.0, 1.0, 0.002, 0.05);
    let w = 2.0 * PI / period;
    let (t_ramp, t_end) = (150.0, 350.0);
    let n = (t_end / dt) as usize + 1;
    let accel: Vec<f64> = (0..n)
        .map(|k| {
            let t = k as f64 * dt;
            let env = if t < t_ramp {
                0.5 * (1.0 - (PI * t / t_ramp).cos())
            } else if t > t_end - t_ramp {
                0.5 * (1.0 - (PI * (t_end - t) / t_ramp).cos())
            } else {
                1.0
            };
            a * env * (w * t).sin()
        })
        .collect();
    let sa_g = 1.5;
    let target = SaTarget {
        period,
        sa: sa_g,
        damping: zeta,
    };
    let (f, psa) = sa_factor(&accel, dt, &target, || {
        pounding::diagnostics::Location::file("sine")
    })
    .unwrap();
    let steady = a / (2.0 * zeta);
    assert!((psa / steady - 1.0).abs() < 3e-4, "{psa} vs {steady}");
    let want = 2.0 * zeta * sa_g * STANDARD_GRAVITY / a;
    assert!((f / want - 1.0).abs() < 3e-4, "{f} vs {want}");
}

fn scenario_text(ground: &str) -> String {
    format!(
        r#"title = "scale_to_sa"
[[structure]]
name = "a"
length = 10.0
mass = 2.273e6
period = 0.42
modes = 2
damping_ratio = 0.02
[[structure]]
name = "b"
length = 10.0
mass = 2.273e6
period = 0.6
modes = 2
damping_ratio = 0.02
[contact]
law = "hertz"
stiffness = 2.808e10
gap = 0.02
[ground_motion]
{ground}
[solver]
method = "exact-modal"
dt = 0.005
duration = 8.0
"#
    )
}

fn load(dir: &Path, ground: &str) -> Result<Scenario, String> {
    let p = dir.join("s.toml");
    std::fs::write(&p, scenario_text(ground)).unwrap();
    Scenario::from_file(&p).map_err(|e| e.to_string())
}

/// The run with `scale_to_sa` is the run of the record multiplied by the factor, written out as
/// a one-column file (shortest round-trip decimals, so the same bits): the same report, bit for
/// bit, and summary.json's `ground_motion` says what was applied.
#[test]
fn run_equals_the_explicitly_scaled_record() {
    let dir = tempfile::tempdir().unwrap();
    let rec = root().join(RECORD);
    let raw = read(&rec, &RecordOptions::default()).unwrap();
    let (period, sa) = (0.6, 0.5);
    let f = scale_to_sa(&raw, period, 0.05, sa * STANDARD_GRAVITY).unwrap();
    let copy = dir.path().join("copy.txt");
    let text: String = raw.accel.iter().map(|a| format!("{:?}\n", a * f)).collect();
    std::fs::write(&copy, text).unwrap();

    let by_key = load(
        dir.path(),
        &format!(
            "kind = \"record\"\nfile = \"{}\"\nscale_to_sa = {{ period = {period}, sa = {sa} }}",
            rec.display()
        ),
    )
    .unwrap();
    let by_copy = load(
        dir.path(),
        &format!(
            "kind = \"record\"\nfile = \"{}\"\nunits = \"m/s2\"\ndt = {}",
            copy.display(),
            raw.dt
        ),
    )
    .unwrap();
    let (GroundMotion::Record(a), GroundMotion::Record(b)) =
        (&by_key.ground_motion, &by_copy.ground_motion)
    else {
        panic!("records expected")
    };
    assert_eq!(a.accel.len(), b.accel.len());
    assert!(
        a.accel
            .iter()
            .zip(&b.accel)
            .all(|(x, y)| x.to_bits() == y.to_bits())
    );
    let ra = simulate(&by_key).unwrap();
    let rb = simulate(&by_copy).unwrap();
    assert_eq!(
        serde_json::to_string(&ra).unwrap(),
        serde_json::to_string(&rb).unwrap()
    );
    assert!(ra.contact.impacts > 0, "the case should pound");

    let json = pounding::output::run::summary_json(&by_key, &ra).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let g = &v["ground_motion"];
    assert_eq!(g["kind"], "record");
    assert_eq!(g["scale_factor"].as_f64().unwrap().to_bits(), f.to_bits());
    assert_eq!(g["scale_to_sa"]["period"], period);
    assert_eq!(g["scale_to_sa"]["sa_g"], sa);
    assert_eq!(g["scale_to_sa"]["damping"], 0.05);
    let before = g["scale_to_sa"]["psa_before"].as_f64().unwrap();
    assert!((before * f / (sa * STANDARD_GRAVITY) - 1.0).abs() < 1e-14);
    let text = pounding::output::text::run_summary(&by_key, "s.toml", &ra);
    assert!(
        text.contains(&format!(
            "scaled × {f:.4} to PSA(T = 0.6 s, ζ = 5 %) = 0.5 g"
        )),
        "{text}"
    );
    // the copy was not scaled when read
    let json = pounding::output::run::summary_json(&by_copy, &rb).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["ground_motion"]["scale_factor"], 1.0);
    assert!(v["ground_motion"].get("scale_to_sa").is_none());
}

/// Every bad `scale_to_sa` is refused with the file, line, column and key, and the reason.
#[test]
fn bad_inputs_name_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let rec = root().join(RECORD);
    let file = format!("kind = \"record\"\nfile = \"{}\"", rec.display());
    let cases: &[(&str, &str, &str)] = &[
        (
            "scale_to_sa = { period = 1.0, sa = 0.4 }\nscale_to_pga = 0.3",
            "s.toml:23:15: `ground_motion.scale_to_sa`",
            "not with `ground_motion.scale_to_pga` (line 24)",
        ),
        (
            "scale_to_sa = { period = -1.0, sa = 0.4 }",
            "s.toml:23:26: `ground_motion.scale_to_sa.period`",
            "must be a finite number > 0 (s)",
        ),
        (
            "scale_to_sa = { period = 1.0, sa = 0.0 }",
            "s.toml:23:36: `ground_motion.scale_to_sa.sa`",
            "must be a finite number > 0 (g)",
        ),
        (
            "scale_to_sa = { period = 1.0, sa = inf }",
            "`ground_motion.scale_to_sa.sa`",
            "must be a finite number > 0 (g)",
        ),
        (
            "scale_to_sa = { period = 1.0, sa = 0.4, damping = 1.0 }",
            "s.toml:23:51: `ground_motion.scale_to_sa.damping`",
            "in [0, 1)",
        ),
        (
            "scale_to_sa = { period = 1.0, sa = 0.4, damping = -0.01 }",
            "`ground_motion.scale_to_sa.damping`",
            "in [0, 1)",
        ),
        (
            "scale_to_sa = { period = 1.0 }",
            "`ground_motion.scale_to_sa.sa`",
            "the target PSA at T, in g",
        ),
        (
            "scale_to_sa = { period = 1.0, sa = 0.4, zeta = 0.1 }",
            "unknown key `zeta` in ground_motion.scale_to_sa",
            "period, sa, damping",
        ),
    ];
    for (ground, at, why) in cases {
        let e = load(dir.path(), &format!("{file}\n{ground}")).unwrap_err();
        assert!(e.contains(at) && e.contains(why), "{ground}:\n{e}");
    }
    // not with a harmonic motion
    let e = load(
        dir.path(),
        "kind = \"harmonic\"\npga = 0.3\nperiod = 0.5\nscale_to_sa = { period = 1.0, sa = 0.4 }",
    )
    .unwrap_err();
    assert!(
        e.contains("ground_motion.scale_to_sa") && e.contains("not used with kind = \"harmonic\""),
        "{e}"
    );

    // a period below the record's dt/100 (dt = 2 s: 0.02 s), known once the record is read:
    // named at the period's own key
    let coarse = dir.path().join("coarse.txt");
    std::fs::write(&coarse, "0\n0.5\n-0.3\n0.1\n0\n").unwrap();
    let e = load(
        dir.path(),
        &format!(
            "kind = \"record\"\nfile = \"{}\"\ndt = 2.0\nunits = \"m/s2\"\n\
             scale_to_sa = {{ period = 0.015, sa = 0.4 }}",
            coarse.display()
        ),
    )
    .unwrap_err();
    assert!(
        e.contains("s.toml:25:26: `ground_motion.scale_to_sa.period`")
            && e.contains("below dt/100 = 0.02 s"),
        "{e}"
    );
    // a record of zeros has no PSA to scale
    let zeros = dir.path().join("zeros.txt");
    std::fs::write(&zeros, "0\n0\n0\n0\n").unwrap();
    let e = load(
        dir.path(),
        &format!(
            "kind = \"record\"\nfile = \"{}\"\ndt = 0.01\n\
             scale_to_sa = {{ period = 1.0, sa = 0.4 }}",
            zeros.display()
        ),
    )
    .unwrap_err();
    assert!(
        e.contains("s.toml:24:15: `ground_motion.scale_to_sa`")
            && e.contains("PSA at T = 1 s is 0"),
        "{e}"
    );

    // the library refuses both scalings at once too
    let both = RecordOptions {
        scale_to_pga: Some(0.3),
        scale_to_sa: Some(SaTarget::new(1.0, 0.4)),
        ..RecordOptions::default()
    };
    assert!(matches!(
        read(&rec, &both),
        Err(RecordError::ScaleConflict { .. })
    ));
}

/// `pounding scale --sa T,SA --json`: per record the factor of the library, PSA before × factor
/// = the target (to rounding), PSA after (computed again) = the target to 1e-12, and the
/// scaled PGA = factor × PGA; with `--damping` the damping of the oscillator.
#[test]
fn cli_scale_to_sa() {
    let files = [RECORD, "examples/records/RSN786_LOMAP_PAE055.AT2"];
    let out = Command::new(env!("CARGO_BIN_EXE_pounding"))
        .current_dir(root())
        .args([
            "scale",
            files[0],
            files[1],
            "--sa",
            "0.8,0.35",
            "--damping",
            "0.03",
        ])
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["period"], 0.8);
    assert_eq!(v["damping"], 0.03);
    assert_eq!(v["sa_g"], 0.35);
    let target = 0.35 * STANDARD_GRAVITY;
    for (i, file) in files.iter().enumerate() {
        let r = &v["records"][i];
        assert_eq!(r["record"], *file);
        let raw = read(&root().join(file), &RecordOptions::default()).unwrap();
        let f = scale_to_sa(&raw, 0.8, 0.03, target).unwrap();
        assert_eq!(r["factor"].as_f64().unwrap(), f);
        let num = |k: &str| r[k].as_f64().unwrap();
        assert!((num("psa_before") * f / target - 1.0).abs() < 1e-14);
        assert!((num("psa_after") / target - 1.0).abs() < 1e-12);
        assert!((num("pga_after") / (f * raw.pga()) - 1.0).abs() < 1e-14);
        assert_eq!(num("pga_before"), raw.pga());
    }
    // the table
    let out = Command::new(env!("CARGO_BIN_EXE_pounding"))
        .current_dir(root())
        .args(["scale", files[0], "--sa", "1,0.4"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(text.contains("PSA(T = 1 s, ζ = 5 %) = 0.4 g"), "{text}");
    // refused: with the suite's options, a period below dt/100, damping out of range
    for args in [
        vec!["--sa", "1,0.4", "--rule", "asce7"],
        vec!["--sa", "0.00001,0.4"],
        vec!["--sa", "1,0.4", "--damping", "1"],
        vec!["--sa", "1"],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_pounding"))
            .current_dir(root())
            .arg("scale")
            .arg(files[0])
            .args(&args)
            .output()
            .unwrap();
        assert!(!out.status.success(), "{args:?}");
        assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
    }
}

/// A sweep over `ground_motion.scale_to_sa.sa`: each case's record is scaled to its value (the
/// scaled PSA from the RK4 oscillator, 1.5e-6 as above), and an axis of `scale_to_sa` replaces a
/// base scenario's `scale_to_pga`.
#[test]
fn sweep_axis_sets_the_target() {
    let dir = tempfile::tempdir().unwrap();
    let rec = root().join(RECORD);
    std::fs::write(
        dir.path().join("base.toml"),
        scenario_text(&format!(
            "kind = \"record\"\nfile = \"{}\"\nscale_to_pga = 0.3",
            rec.display()
        )),
    )
    .unwrap();
    let sweep = dir.path().join("sweep.toml");
    std::fs::write(
        &sweep,
        "scenario = \"base.toml\"\n\
         [[axis]]\nkey = \"ground_motion.scale_to_sa.period\"\nvalues = [0.5]\n\
         [[axis]]\nkey = \"ground_motion.scale_to_sa.sa\"\nvalues = [0.2, 0.6]\n",
    )
    .unwrap();
    let s = pounding::study::sweep::Sweep::from_file(&sweep).unwrap();
    assert_eq!(s.len(), 2);
    for (case, sa) in [(0, 0.2), (1, 0.6)] {
        let sc = s.case_scenario(case).unwrap();
        let GroundMotion::Record(r) = &sc.ground_motion else {
            panic!()
        };
        let psa = psa_rk4(&r.accel, r.dt, 0.5, 0.05, 40);
        assert!(
            (psa / (sa * STANDARD_GRAVITY) - 1.0).abs() < 1.5e-6,
            "{psa}"
        );
    }
}
