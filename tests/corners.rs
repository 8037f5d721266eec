//! Issue 15: at both ends of the allowed range of every numeric key — cantilever, building with
//! floors, contact law, ground motion (harmonic and record), solver — a scenario is either
//! refused with a message naming a key, or its run stops with an error, or it runs; and when it
//! runs, every number of its summary.json is finite (no `null`, no overflow). Just outside each
//! range the scenario is refused, naming the key.
//!
//! The other values are a small version of the paper's case (1 s of `adaptive`, 3 modes), so
//! that each corner runs in well under a second; corners whose run would be long at those
//! settings (the finest step, the longest duration) are run on a scenario that makes them short
//! (`short` and `long` below).

use std::path::{Path, PathBuf};

use pounding::input::scenario::{Scenario, physical_range};

const CANTILEVERS: &str = r#"
[[structure]]
length = 10.0
mass = 2.273e6
period = 0.4203
modes = 3
damping_ratio = 0.01

[[structure]]
length = 10.0
mass = 2.273e6
period = 0.6
modes = 3
damping_ratio = 0.01

[contact]
law = "hertz"
stiffness = 2.808e10
gap = 0.0127

[ground_motion]
kind = "harmonic"
pga = 0.6
period = 0.65

[solver]
duration = 1.0
"#;

/// Two buildings of two floors each, touching at the top floor (the default contact height:
/// the top of the lower, a floor of both as long as both are changed alike).
const SHEAR: &str = r#"
[[structure]]
kind = "shear-building"
storeys = 2
storey_height = 3.5
floor_mass = 2.5e5
storey_stiffness = 1.2e8
damping_ratio = 0.05

[[structure]]
kind = "shear-building"
storeys = 2
storey_height = 3.5
floor_mass = 2.5e5
storey_stiffness = 3e8
damping_ratio = 0.05

[contact]
law = "jankowski"
stiffness = 2.75e9
restitution = 0.65
gap = 0.005

[ground_motion]
kind = "harmonic"
pga = 0.5
period = 0.6

[solver]
duration = 1.0
"#;

/// The same with lists, the second building given by its modes (one floor each).
const LISTS: &str = r#"
[[structure]]
kind = "shear-building"
floor_heights = [3.5, 7.0]
floor_masses = [2.5e5, 2.5e5]
storey_stiffnesses = [1.2e8, 1.2e8]
rayleigh = { damping_ratio = 0.05, modes = [1, 2] }

[[structure]]
kind = "modal"
floor_heights = [3.5, 7.0]
floor_masses = [2.5e5, 2.5e5]
periods = [0.5, 0.2]
mode_shapes = [[0.618, 1.0], [1.0, -0.618]]
damping_ratio = 0.05

[contact]
law = "kelvin"
stiffness = 1e9
restitution = 0.65
gap = 0.005

[ground_motion]
kind = "harmonic"
pga = 0.5
period = 0.6

[solver]
duration = 1.0
"#;

/// A record by file: [`CANTILEVERS`] shaken by a one-column record; `{file}` is set to a record
/// written by the test.
static RECORD: std::sync::LazyLock<String> =
    std::sync::LazyLock::new(|| CANTILEVERS.replace(HARMONIC_MOTION, RECORD_MOTION));

const HARMONIC_MOTION: &str = r#"[ground_motion]
kind = "harmonic"
pga = 0.6
period = 0.65

"#;

const RECORD_MOTION: &str = r#"[ground_motion]
kind = "record"
file = "{file}"
dt = 0.01
scale_to_pga = 0.5

"#;

/// What a corner did.
enum Outcome {
    Refused,
    Failed,
    Ran,
}

/// Validates and runs `text`; panics on a refusal without a key, or a non-finite number or a
/// null anywhere in summary.json.
fn corner(label: &str, text: &str, dir: &Path) -> Outcome {
    let sc = match Scenario::from_toml(text, "c.toml", dir) {
        Ok(sc) => sc,
        Err(e) => {
            let e = e.to_string();
            eprintln!("{label}: refused: {e}");
            assert!(e.contains('`'), "{label}: an error without a key: {e}");
            return Outcome::Refused;
        }
    };
    let report = match pounding::analysis::simulate::simulate(&sc) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("{label}: stopped: {e}");
            return Outcome::Failed;
        }
    };
    let json = pounding::output::run::summary_json(&sc, &report).unwrap();
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    let mut stack = vec![("".to_string(), &value)];
    while let Some((path, x)) = stack.pop() {
        match x {
            // (`accuracy` is skipped: not checked by `simulate`, its nulls say "not checked")
            serde_json::Value::Null => panic!("{label}: null at {path} in summary.json"),
            serde_json::Value::Number(n) => {
                assert!(n.as_f64().unwrap().is_finite(), "{label}: {path} = {n}");
            }
            serde_json::Value::Array(a) => stack.extend(
                a.iter()
                    .enumerate()
                    .map(|(i, v)| (format!("{path}[{i}]"), v)),
            ),
            serde_json::Value::Object(o) => {
                for (k, v) in o {
                    if k != "accuracy" {
                        stack.push((format!("{path}.{k}"), v));
                    }
                }
            }
            _ => {}
        }
    }
    Outcome::Ran
}

/// `text` with every line `line` replaced by `to` (`all`) or the first only.
fn set(text: &str, line: &str, to: &str, all: bool) -> String {
    assert!(text.contains(line), "`{line}` is not in the base");
    if all {
        text.replace(line, to)
    } else {
        text.replacen(line, to, 1)
    }
}

fn temp_dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("pounding-corners-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A numeric key: its name for [`physical_range`] (or explicit bounds), the base, the line to
/// replace, the template (`{v}`: the value), every line or the first.
struct Key {
    key: &'static str,
    bounds: Option<(f64, f64)>,
    base: &'static str,
    line: &'static str,
    template: &'static str,
    all: bool,
    /// A whole-number key (written without a decimal point).
    int: bool,
}

const fn k(
    key: &'static str,
    base: &'static str,
    line: &'static str,
    template: &'static str,
) -> Key {
    Key {
        key,
        bounds: None,
        base,
        line,
        template,
        all: false,
        int: false,
    }
}

fn keys() -> Vec<Key> {
    let c = CANTILEVERS;
    let s = SHEAR;
    let l = LISTS;
    let r: &'static str = RECORD.as_str();
    let mut v = vec![
        // cantilever
        k("length", c, "length = 10.0", "length = {v}"),
        k("mass", c, "mass = 2.273e6", "mass = {v}"),
        k("period", c, "period = 0.4203", "period = {v}"),
        k(
            "bending_stiffness",
            c,
            "period = 0.4203",
            "bending_stiffness = {v}",
        ),
        k("tip_stiffness", c, "period = 0.4203", "tip_stiffness = {v}"),
        k(
            "strain_rate_damping",
            c,
            "damping_ratio = 0.01",
            "strain_rate_damping = {v}",
        ),
        k(
            "air_damping",
            c,
            "damping_ratio = 0.01",
            "air_damping = {v}",
        ),
        Key {
            bounds: Some((0.0, 1.0 - f64::EPSILON)),
            ..k(
                "damping_ratio",
                c,
                "damping_ratio = 0.01",
                "damping_ratio = {v}",
            )
        },
        Key {
            bounds: Some((1.0, 500.0)),
            int: true,
            ..k("modes", c, "modes = 3", "modes = {v}")
        },
        // contact
        k("stiffness", c, "stiffness = 2.808e10", "stiffness = {v}"),
        k("gap", c, "gap = 0.0127", "gap = {v}"),
        Key {
            // (the lowest contact height is 1e-3 of the lower structure's)
            bounds: Some((1e-2, 10.0)),
            ..k("height", c, "gap = 0.0127", "gap = 0.0127\nheight = {v}")
        },
        Key {
            bounds: Some((0.01, 1.0)),
            ..k("restitution", s, "restitution = 0.65", "restitution = {v}")
        },
        Key {
            bounds: Some((0.01, 1.0)),
            ..k("restitution", l, "restitution = 0.65", "restitution = {v}")
        },
        Key {
            bounds: Some((0.0, 1.0)),
            ..k(
                "restitution",
                c,
                "law = \"hertz\"\nstiffness = 2.808e10",
                "law = \"stereomechanical\"\nrestitution = {v}",
            )
        },
        Key {
            bounds: Some((0.01, 1.0)),
            ..k(
                "restitution",
                c,
                "law = \"hertz\"",
                "law = \"hertzdamp\"\nrestitution = {v}",
            )
        },
        Key {
            bounds: Some((0.01, 1.0)),
            ..k(
                "restitution",
                c,
                "law = \"hertz\"",
                "law = \"hertzdamp\"\ndamping_model = \"hunt-crossley\"\nrestitution = {v}",
            )
        },
        // ground motion
        k("pga", c, "pga = 0.6", "pga = {v}"),
        k("period", c, "period = 0.65", "period = {v}"),
        k(
            "scale_to_pga",
            r,
            "scale_to_pga = 0.5",
            "scale_to_pga = {v}",
        ),
        // a one-column record's spacing (101 samples: at 1e-7 s the record lasts 1e-5 s, below
        // the shortest duration, and is refused naming `ground_motion.file`)
        k("dt", r, "dt = 0.01", "dt = {v}"),
        // solver
        Key {
            bounds: Some((1e-12, 0.1)),
            ..k("rtol", c, "duration = 1.0", "duration = 1.0\nrtol = {v}")
        },
        Key {
            bounds: Some((1e-14, 1.0)),
            ..k("atol", c, "duration = 1.0", "duration = 1.0\natol = {v}")
        },
        // shear building (both buildings alike, so the top floors stay at the same height)
        Key {
            bounds: Some((1.0, 500.0)),
            all: true,
            int: true,
            ..k("storeys", s, "storeys = 2", "storeys = {v}")
        },
        Key {
            all: true,
            ..k(
                "storey_height",
                s,
                "storey_height = 3.5",
                "storey_height = {v}",
            )
        },
        k("floor_mass", s, "floor_mass = 2.5e5", "floor_mass = {v}"),
        k(
            "storey_stiffness",
            s,
            "storey_stiffness = 1.2e8",
            "storey_stiffness = {v}",
        ),
        Key {
            bounds: Some((f64::MIN_POSITIVE, 1.0 - f64::EPSILON)),
            ..k(
                "rayleigh.damping_ratio",
                l,
                "rayleigh = { damping_ratio = 0.05,",
                "rayleigh = { damping_ratio = {v},",
            )
        },
        // lists: every value at the corner (heights: the corner and half of it, increasing)
        Key {
            all: true,
            ..k(
                "floor_heights",
                l,
                "floor_heights = [3.5, 7.0]",
                "floor_heights = [{small}, {big}]",
            )
        },
        k(
            "floor_masses",
            l,
            "floor_masses = [2.5e5, 2.5e5]",
            "floor_masses = [{v}, {v}]",
        ),
        k(
            "storey_stiffnesses",
            l,
            "storey_stiffnesses = [1.2e8, 1.2e8]",
            "storey_stiffnesses = [{v}, {v}]",
        ),
        k(
            "periods",
            l,
            "periods = [0.5, 0.2]",
            "periods = [{big}, {small}]",
        ),
    ];
    // duration, step and output interval at their small ends together (1e4 steps and rows),
    // at their large ends on the `long` scenario below
    v.push(Key {
        bounds: Some((1e-7, 1e-7)),
        ..k(
            "dt",
            c,
            "duration = 1.0",
            "duration = 1e-3\ndt = {v}\noutput_interval = {v}",
        )
    });
    v.push(Key {
        bounds: Some((1e-3, 1e-3)),
        ..k("duration", c, "duration = 1.0", "duration = {v}")
    });
    v
}

/// The template with the value `v`; a pair of list values `{big}`, `{small}` has `v` as the
/// larger at the upper end (`v`, `v`/2) and as the smaller at the lower end (2`v`, `v`).
fn fill(template: &str, v: f64, upper: bool, int: bool) -> String {
    let (big, small) = if upper { (v, v / 2.0) } else { (2.0 * v, v) };
    let v = if int {
        format!("{}", v as i64)
    } else {
        format!("{v:e}")
    };
    template
        .replace("{v}", &v)
        .replace("{big}", &format!("{big:e}"))
        .replace("{small}", &format!("{small:e}"))
}

/// Every numeric key's corners run or are refused cleanly; every key is refused just outside.
#[test]
fn every_key_at_both_ends_of_its_range() {
    let dir = temp_dir();
    // a one-column record: 1 s of a 2 Hz sine at 0.5 m/s² peak, every 10 ms
    let samples: Vec<String> = (0..=100)
        .map(|i| {
            format!(
                "{}",
                0.5 * (2.0 * std::f64::consts::PI * 2.0 * i as f64 * 0.01).sin()
            )
        })
        .collect();
    std::fs::write(dir.join("one.txt"), samples.join("\n")).unwrap();
    let (mut ran, mut refused, mut failed) = (Vec::new(), 0, 0);
    for key in keys() {
        let (lo, hi) = key
            .bounds
            .unwrap_or_else(|| physical_range(key.key).map(|(a, b, _)| (a, b)).unwrap());
        let base = key
            .base
            .replace("{file}", &dir.join("one.txt").display().to_string());
        for v in [lo, hi] {
            let line = fill(key.template, v, v == hi, key.int);
            let text = set(&base, key.line, &line, key.all);
            let label = format!("{} = {v:e}", key.key);
            let t0 = std::time::Instant::now();
            let outcome = corner(&label, &text, &dir);
            eprintln!("{label}: {:.2} s", t0.elapsed().as_secs_f64());
            match outcome {
                Outcome::Ran => ran.push(label),
                Outcome::Refused => refused += 1,
                Outcome::Failed => failed += 1,
            }
        }
        // just outside the range (physical ranges only: explicit bounds are the tests' own)
        if key.bounds.is_none() {
            for v in [hi * 10.0, if lo > 0.0 { lo / 10.0 } else { -1.0 }] {
                let line = fill(key.template, v, v > hi, key.int);
                let text = set(&base, key.line, &line, key.all);
                let e = Scenario::from_toml(&text, "c.toml", &dir)
                    .err()
                    .unwrap_or_else(|| panic!("{} = {v:e} (outside) was accepted", key.key))
                    .to_string();
                assert!(e.contains(key.key), "{} = {v:e}: {e}", key.key);
            }
        }
    }
    eprintln!(
        "{} corners ran, {refused} refused, {failed} stopped: {ran:?}",
        ran.len()
    );
    // most corners are runs, not refusals (a refusal is no test of the outputs)
    assert!(ran.len() >= 40, "only {} corners ran: {ran:?}", ran.len());
    std::fs::remove_dir_all(&dir).ok();
}

/// The large ends of the solver's duration, step and output interval (and a record's smallest
/// spacing) together: 10⁷ s after a short record, by `exact-modal` with 100 s steps — exact
/// between steps without contact, so 10⁵ steps — sampled every 10⁶ s.
#[test]
fn longest_duration_largest_step_and_interval() {
    let dir = temp_dir().join("long");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("pulse.txt"), "0\n0.1\n0\n0\n").unwrap();
    let (_, dmax, _) = physical_range("duration").unwrap();
    let (_, dtmax, _) = physical_range("dt").unwrap();
    let (_, omax, _) = physical_range("output_interval").unwrap();
    let text = RECORD
        .replace("{file}", "pulse.txt")
        .replace("scale_to_pga = 0.5\n", "")
        .replace(
            "duration = 1.0",
            &format!(
                "method = \"exact-modal\"\nduration = {dmax:e}\ndt = {dtmax:e}\noutput_interval = {omax:e}"
            ),
        );
    assert!(matches!(corner("long", &text, &dir), Outcome::Ran));
    std::fs::remove_dir_all(&dir).ok();
}

/// The stiffness keys at their ends are refused with the default masses (the first-period
/// check); with masses and heights at the matching ends they make plausible-period structures,
/// which must run with finite outputs.
#[test]
fn stiffness_ends_with_matching_masses_run() {
    let dir = temp_dir().join("stiff");
    std::fs::create_dir_all(&dir).unwrap();
    let cantilever = "length = 10.0\nmass = 2.273e6\nperiod = 0.4203";
    // (T₁ = 2π/λ₁² √(m L⁴/EI), λ₁ = 1.8751, m = M/L; tip stiffness k = 3EI/L³)
    let cases = [
        // EI = 1, M = 1 kg, L = 0.1 m: T₁ = 0.056 s
        "length = 0.1\nmass = 1.0\nbending_stiffness = 1.0",
        // EI = 1e22, M = 1e12 kg, L = 2000 m: T₁ = 1.6 s
        "length = 2000.0\nmass = 1e12\nbending_stiffness = 1e22",
        // k = 1e-3 N/m, M = 1 kg, L = 0.1 m: T₁ ≈ 2π √(0.24 M/k) ≈ 100 s
        "length = 0.1\nmass = 1.0\ntip_stiffness = 1e-3",
        // k = 1e16 N/m, M = 1e12 kg: T₁ ≈ 0.1 s
        "length = 10.0\nmass = 1e12\ntip_stiffness = 1e16",
    ];
    for case in cases {
        let text = set(CANTILEVERS, cantilever, case, false);
        assert!(
            matches!(corner(case, &text, &dir), Outcome::Ran),
            "{case} must run"
        );
    }
    // a shear building of 1 kg floors on 1 N/m storeys (T₁ ≈ 10 s), and of 1e10 kg floors on
    // 1e16 N/m storeys (T₁ ≈ 0.01 s)
    for (m, k) in [("1.0", "1.0"), ("1e10", "1e16")] {
        let text = SHEAR
            .replace("floor_mass = 2.5e5", &format!("floor_mass = {m}"))
            .replacen(
                "storey_stiffness = 1.2e8",
                &format!("storey_stiffness = {k}"),
                1,
            )
            .replacen(
                "storey_stiffness = 3e8",
                &format!("storey_stiffness = {k}"),
                1,
            );
        let label = format!("floor_mass = {m}, storey_stiffness = {k}");
        assert!(
            matches!(corner(&label, &text, &dir), Outcome::Ran),
            "{label} must run"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The Bouc–Wen keys of a yielding storey (issue 16) at both ends of their allowed ranges, each
/// with the others at ordinary values (structure 1 of `SHEAR` yielding): every corner runs with
/// finite outputs or is refused naming its key; just outside each range it is refused.
#[test]
fn bouc_wen_keys_at_both_ends_of_their_ranges() {
    let dir = temp_dir().join("bouc-wen");
    std::fs::create_dir_all(&dir).unwrap();
    let ordinary = "yield_drifts = 0.0175, post_yield_ratio = 0.05, exponent = 2.0, beta = 0.5, \
                    gamma = 0.5";
    // the hysteresis of structure 1, with `key = value` put in place of the ordinary one
    let with = |key: &str, value: &str| {
        let mut parts: Vec<String> = ordinary.split(", ").map(str::to_string).collect();
        for (k, v) in key.split(',').zip(value.split(',')) {
            let p = parts.iter().position(|p| {
                p.starts_with(&format!("{k} ="))
                    || p.starts_with("yield_") && k.starts_with("yield_")
            });
            let line = format!("{k} = {v}");
            match p {
                Some(p) => parts[p] = line,
                None => parts.push(line),
            }
        }
        set(
            SHEAR,
            "damping_ratio = 0.05",
            &format!(
                "damping_ratio = 0.05\nhysteresis = {{ model = \"bouc-wen\", {} }}",
                parts.join(", ")
            ),
            false,
        )
    };
    // the ordinary storeys yield in the 1 s of 0.5 g (so the corners exercise the law)
    let sc = Scenario::from_toml(&with("exponent", "2.0"), "c.toml", &dir).unwrap();
    assert!(sc.warnings.is_empty(), "{:?}", sc.warnings);
    let mu = pounding::analysis::simulate::simulate(&sc)
        .unwrap()
        .structures[0]
        .peak_ductility
        .unwrap();
    assert!(mu > 1.0, "peak ductility {mu}");
    let (dlo, dhi, _) = physical_range("yield_drifts").unwrap();
    // (key(s), lower end, upper end, just below, just above); β, γ at their ends with the other
    // one inside: γ ∈ (−β, β] (β + γ > 0), β ∈ (0, 100] with γ = 0
    let tiny = f64::MIN_POSITIVE;
    let cases: Vec<(&str, String, String, String, String)> = vec![
        (
            "yield_drifts",
            format!("{dlo:e}"),
            format!("{dhi:e}"),
            format!("{:e}", dlo / 10.0),
            format!("{:e}", dhi * 10.0),
        ),
        (
            "post_yield_ratio",
            "0.0".into(),
            format!("{:e}", 1.0 - f64::EPSILON),
            "-0.01".into(),
            "1.0".into(),
        ),
        (
            "exponent",
            "1.0".into(),
            "100.0".into(),
            "0.99".into(),
            "100.1".into(),
        ),
        (
            "beta,gamma",
            format!("{tiny:e},0.0"),
            "100.0,0.0".into(),
            "0.0,0.0".into(),
            "100.1,0.0".into(),
        ),
        (
            "gamma",
            format!("{:e}", -0.5 + 1e-12),
            "0.5".into(),
            "-0.5".into(),
            "0.51".into(),
        ),
        (
            "beta,gamma",
            format!("100.0,{:e}", -100.0 + 1e-9),
            "100.0,100.0".into(),
            "100.0,-100.0".into(),
            "100.0,100.1".into(),
        ),
    ];
    let mut ran = Vec::new();
    for (key, lo, hi, below, above) in &cases {
        for v in [lo, hi] {
            let label = format!("{key} = {v}");
            let t0 = std::time::Instant::now();
            let outcome = corner(&label, &with(key, v), &dir);
            eprintln!("{label}: {:.2} s", t0.elapsed().as_secs_f64());
            if matches!(outcome, Outcome::Ran) {
                ran.push(label);
            }
        }
        for v in [below, above] {
            let e = Scenario::from_toml(&with(key, v), "c.toml", &dir)
                .err()
                .unwrap_or_else(|| panic!("{key} = {v} (outside) was accepted"))
                .to_string();
            let name = key.rsplit(',').next().unwrap();
            let named = |k: &str| e.contains(&format!("structure[1].hysteresis.{k}"));
            assert!(
                named(name) || key.contains(',') && key.split(',').any(named),
                "{key} = {v}: {e}"
            );
            assert!(
                e.contains("c.toml:") && e.contains('['),
                "{key} = {v}: no place or range: {e}"
            );
        }
    }
    // yield forces at their ends, on storeys whose stiffness makes F_y/k a yield drift: 1e-3 N on
    // 1 N/m storeys (1 kg floors, T₁ ≈ 10 s) yield at 1 mm, 1e14 N on 1e16 N/m storeys (1e10 kg
    // floors, T₁ ≈ 0.01 s) at 1 cm; the ordinary storeys refuse both (F_y/k outside the drifts')
    let (flo, fhi, _) = physical_range("yield_forces").unwrap();
    for (f, m, k) in [(flo, "1.0", "1.0"), (fhi, "1e10", "1e16")] {
        let text = with("yield_forces", &format!("{f:e}"))
            .replace("floor_mass = 2.5e5", &format!("floor_mass = {m}"))
            .replace(
                "storey_stiffness = 1.2e8",
                &format!("storey_stiffness = {k}"),
            )
            .replace("storey_stiffness = 3e8", &format!("storey_stiffness = {k}"));
        let label = format!("yield_forces = {f:e} on {k} N/m");
        assert!(
            matches!(corner(&label, &text, &dir), Outcome::Ran),
            "{label} must run"
        );
        ran.push(label);
        let e = Scenario::from_toml(&with("yield_forces", &format!("{f:e}")), "c.toml", &dir)
            .err()
            .unwrap_or_else(|| panic!("yield_forces = {f:e} on 1.2e8 N/m was accepted"))
            .to_string();
        assert!(
            e.contains("yield_forces") && e.contains("[1e-6, 1e1] m"),
            "{e}"
        );
        for v in [flo / 10.0, fhi * 10.0] {
            let e = Scenario::from_toml(&with("yield_forces", &format!("{v:e}")), "c.toml", &dir)
                .err()
                .unwrap_or_else(|| panic!("yield_forces = {v:e} (outside) was accepted"))
                .to_string();
            assert!(
                e.contains("yield_forces") && e.contains("[1e-3, 1e14] N"),
                "{e}"
            );
        }
    }
    eprintln!("{} Bouc–Wen corners ran: {ran:?}", ran.len());
    assert!(ran.len() >= 12, "only {} corners ran: {ran:?}", ran.len());
    std::fs::remove_dir_all(&dir).ok();
}
