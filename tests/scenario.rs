//! Scenario validation: every bad input is refused with a message that names the file, the
//! line, the key and the allowed range — never a panic.

use std::path::Path;

use pounding::input::scenario::{Scenario, ScenarioError};

const BASE: &str = include_str!("../examples/paper-c.toml");

fn parse(text: &str) -> Result<Scenario, ScenarioError> {
    Scenario::from_toml(text, "case.toml", Path::new("examples"))
}

/// Replace the first line that starts with `from` (comments mention some values too).
fn edit(from: &str, to: &str) -> String {
    let at = BASE
        .find(&format!("\n{from}"))
        .unwrap_or_else(|| panic!("test edit `{from}` does not apply"))
        + 1;
    format!("{}{}{}", &BASE[..at], to, &BASE[at + from.len()..])
}

/// Apply a textual edit to the bundled paper case, expect an error containing every `needle`.
fn refused(from: &str, to: &str, needles: &[&str]) {
    let text = edit(from, to);
    let err = parse(&text)
        .expect_err(&format!("`{to}` must be refused"))
        .to_string();
    for n in needles {
        assert!(err.contains(n), "message for `{to}` lacks `{n}`: {err}");
    }
    assert!(
        err.starts_with("case.toml:"),
        "message must start with the file: {err}"
    );
}

#[test]
fn bundled_examples_parse() {
    for f in ["paper-a.toml", "paper-b.toml", "paper-c.toml"] {
        let p = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples")
            .join(f);
        let sc = Scenario::from_file(&p).unwrap_or_else(|e| panic!("{f}: {e}"));
        assert_eq!(sc.structures[0].modes(), 3);
        assert_eq!(sc.contact.levels.len(), 1);
        assert_eq!(
            sc.contact.levels[0].height, 10.0,
            "height defaults to min(L1, L2)"
        );
    }
}

#[test]
fn parsed_values_are_si() {
    let sc = parse(BASE).unwrap();
    assert_eq!(sc.structures[0].length(), 10.0);
    assert_eq!(sc.structures[0].mass(), 2.273e6);
    assert_eq!(sc.contact.levels[0].gap, 0.0127);
    // PGA in g → m/s² with standard gravity
    assert!((sc.ground_motion.pga() - 0.6 * 9.80665).abs() < 1e-12);
    assert_eq!(sc.solver.dt, 0.001);
    assert_eq!(sc.output_interval, 0.01);
    // integers are accepted where floats are expected
    let sc = parse(&edit("length = 10.0", "length = 10")).unwrap();
    assert_eq!(sc.structures[0].length(), 10.0);
}

#[test]
fn unknown_keys_are_named_with_a_suggestion() {
    refused(
        "period = 0.4203",
        "perod = 0.4203",
        &[
            "unknown key `perod`",
            "[[structure]]",
            "did you mean `period`?",
            ":18:",
        ],
    );
    refused(
        "stiffness = 2.808e10",
        "stifness = 2.808e10",
        &["`stifness`", "[contact]", "did you mean `stiffness`?"],
    );
    refused(
        "[solver]",
        "[solvr]",
        &["`solvr`", "did you mean `solver`?"],
    );
    refused(
        "dt = 0.001",
        "dt = 0.001\nsteps = 5",
        &["unknown key `steps`", "[solver]", "valid keys"],
    );
}

#[test]
fn missing_keys_are_named() {
    refused(
        "length = 10.0\n",
        "",
        &["missing key `structure[1].length`"],
    );
    refused("mass = 2.273e6\n", "", &["missing key `structure[1].mass`"]);
    // `modes` has a default (20), too many for rk4 at the paper's 1 ms: the stability error
    // says that the default was used
    refused(
        "modes = 3\n",
        "",
        &[
            "`solver.dt`",
            "mode 20 of structure 1",
            "default of 20 modes",
        ],
    );
    refused(
        "period = 0.4203\n",
        "",
        &[
            "`structure[1].period`",
            "bending_stiffness",
            "tip_stiffness",
        ],
    );
    // damping and the duration have defaults (0.05; 20 s for harmonic motion)
    let sc = parse(&edit("damping_ratio = 0.01\n", "")).unwrap();
    assert_eq!(sc.structures[0].modal().zeta[0], 0.05);
    let sc = parse(&edit("duration = 20.0\n", "")).unwrap();
    assert_eq!(sc.solver.duration, 20.0);
    refused("gap = 0.0127\n", "", &["missing key `contact.gap`"]);
    refused(
        "stiffness = 2.808e10\n",
        "",
        &["missing key `contact.stiffness`"],
    );
    refused("pga = 0.6\n", "", &["missing key `ground_motion.pga`"]);
    refused(
        "dt = 0.001\n",
        "",
        &["missing key `solver.dt`", "rk4", "adaptive default"],
    );
}

#[test]
fn out_of_range_values_are_refused_with_the_range() {
    refused(
        "mass = 2.273e6",
        "mass = -5.0",
        &["`structure[1].mass` = -5", "> 0", "kg"],
    );
    refused(
        "mass = 2.273e6",
        "mass = 0.0",
        &["structure[1].mass", "> 0"],
    );
    refused(
        "length = 10.0",
        "length = -1.0",
        &["structure[1].length", "> 0", "m"],
    );
    refused(
        "period = 0.4203",
        "period = 0.0",
        &["structure[1].period", "> 0", "s"],
    );
    refused(
        "period = 0.4203",
        "bending_stiffness = -1e9",
        &["structure[1].bending_stiffness", "> 0"],
    );
    refused(
        "period = 0.4203",
        "tip_stiffness = 0.0",
        &["structure[1].tip_stiffness", "> 0"],
    );
    refused(
        "period = 0.4203",
        "period = 0.4203\ntip_stiffness = 1e9",
        &["exactly one of"],
    );
    refused(
        "modes = 3",
        "modes = 0",
        &["structure[1].modes", "1 to 500"],
    );
    refused(
        "modes = 3",
        "modes = 501",
        &["structure[1].modes", "1 to 500"],
    );
    refused(
        "damping_ratio = 0.01",
        "damping_ratio = 1.5",
        &["damping_ratio", "[0, 1)"],
    );
    refused(
        "damping_ratio = 0.01",
        "damping_ratio = [0.01, 0.02]",
        &["damping_ratio", "exactly 3"],
    );
    refused(
        "damping_ratio = 0.01",
        "damping_ratio = 0.01\nair_damping = 10.0",
        &["not both"],
    );
    refused(
        "damping_ratio = 0.01",
        "air_damping = -3.0",
        &["air_damping", "≥ 0"],
    );
    refused(
        "gap = 0.0127",
        "gap = -0.01",
        &["`contact.gap` = -0.01", "≥ 0"],
    );
    refused(
        "gap = 0.0127",
        "gap = 0.0127\nheight = 11.0",
        &["contact.height", "[0.01, 10]"],
    );
    refused(
        "gap = 0.0127",
        "gap = 0.0127\nheight = 0.0",
        &["contact.height", "[0.01, 10]"],
    );
    // (issue 15: at 1e-3 of the height and below a contact's effective mass runs to infinity)
    refused(
        "gap = 0.0127",
        "gap = 0.0127\nheight = 0.009",
        &["contact.height", "[0.01, 10]", "at the base"],
    );
    // (issue 15: a damped law's damping grows as 1/e)
    refused(
        "law = \"hertz\"",
        "law = \"jankowski\"\nrestitution = 0.001",
        &["contact.restitution", "[0.01, 1]"],
    );
    refused(
        "stiffness = 2.808e10",
        "stiffness = 0.0",
        &["contact.stiffness", "> 0"],
    );
    refused(
        "law = \"hertz\"",
        "law = \"hurtz\"",
        &["contact.law", "\"hertz\""],
    );
    refused(
        "law = \"hertz\"",
        "law = \"hertz\"\nrestitution = 0.5",
        &["contact.restitution", "no restitution"],
    );
    refused(
        "pga = 0.6",
        "pga = -0.6",
        &["ground_motion.pga", "> 0", "g"],
    );
    refused(
        "kind = \"harmonic\"",
        "kind = \"harmonik\"",
        &["ground_motion.kind", "\"record\""],
    );
    refused("dt = 0.001", "dt = 0.0", &["`solver.dt` = 0", "> 0"]);
    refused("dt = 0.001", "dt = -0.001", &["solver.dt", "> 0"]);
    refused(
        "dt = 0.001",
        "dt = 30.0",
        &["solver.dt", "smaller than solver.duration"],
    );
    refused(
        "output_interval = 0.01",
        "output_interval = 0.0",
        &["solver.output_interval"],
    );
    refused("method = \"rk4\"", "method = \"euler\"", &["solver.method"]);
    refused(
        "[[structure]]\nname = \"structure 2\"",
        "[[structur]]\nname = \"structure 2\"",
        &["unknown key `structur`"],
    );
}

#[test]
fn non_finite_numbers_are_refused() {
    refused(
        "pga = 0.6",
        "pga = nan",
        &["ground_motion.pga", "NaN", "finite"],
    );
    refused(
        "mass = 2.273e6",
        "mass = inf",
        &["structure[1].mass", "finite"],
    );
    refused("gap = 0.0127", "gap = +inf", &["contact.gap", "finite"]);
    refused(
        "duration = 20.0",
        "duration = nan",
        &["solver.duration", "finite"],
    );
}

#[test]
fn type_errors_name_the_key() {
    refused("mass = 2.273e6", "mass = \"heavy\"", &["`mass`", ":17:"]);
    refused(
        "modes = 3",
        "modes = 3.5",
        &["`structure[1].modes` = 3.5", "whole number", ":19:9"],
    );
}

#[test]
fn rk4_step_beyond_stability_gives_the_largest_stable_step() {
    // mode 3 of structure 1: ω₃ = (7.8548/1.8751)² · 2π/0.4203 = 262.32 rad/s; with ζ = 0.01 the
    // limit is a little above 2√2/ω₃ = 0.010782 s.
    let text = edit("dt = 0.001", "dt = 0.02");
    let err = parse(&text).unwrap_err().to_string();
    assert!(
        err.contains("solver.dt") && err.contains("stability"),
        "{err}"
    );
    let largest: f64 = err
        .split("largest stable dt for this scenario is ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no largest dt in: {err}"));
    let w3 =
        (7.854757438237613f64 / 1.875104068711961).powi(2) * 2.0 * std::f64::consts::PI / 0.4203;
    assert!(
        largest > 2.0 * 2f64.sqrt() / w3 && largest < 1.01 * 2.0 * 2f64.sqrt() / w3,
        "{largest}"
    );
    // and a step just inside it is accepted
    let ok = edit("dt = 0.001", &format!("dt = {}", 0.999 * largest));
    parse(&ok).unwrap();
}

#[test]
fn structure_count_must_be_two() {
    let one = BASE
        .split("[[structure]]\nname = \"structure 2\"")
        .next()
        .unwrap()
        .to_string()
        + &BASE[BASE.find("[contact]").unwrap()..];
    let err = parse(&one).unwrap_err().to_string();
    // (a row of more than two is a scenario of its own, issue 29: tests/rows.rs)
    assert!(
        err.contains("`structure` = 1 table(s)") && err.contains("one structure alone"),
        "{err}"
    );
}

#[test]
fn contact_levels() {
    let multi = BASE.replacen(
        "gap = 0.0127\n",
        "[[contact.level]]\nheight = 10.0\ngap = 0.0127\n[[contact.level]]\nheight = 6.0\ngap = 0.02\n",
        1,
    );
    let sc = parse(&multi).unwrap();
    assert_eq!(sc.contact.levels.len(), 2);
    assert_eq!(sc.contact.levels[1].height, 6.0);
    let both = BASE.replacen(
        "gap = 0.0127\n",
        "gap = 0.0127\n[[contact.level]]\nheight = 10.0\ngap = 0.0127\n",
        1,
    );
    assert!(
        parse(&both)
            .unwrap_err()
            .to_string()
            .contains("in each level")
    );
    let dup = BASE.replacen(
        "gap = 0.0127\n",
        "[[contact.level]]\nheight = 10.0\ngap = 0.0127\n[[contact.level]]\nheight = 10.0\ngap = 0.02\n",
        1,
    );
    assert!(parse(&dup).unwrap_err().to_string().contains("same height"));
}

#[test]
fn garbage_never_panics() {
    // a tiny LCG mutating the base text: no input may panic
    let mut seed: u64 = 0x2545F4914F6CDD1D;
    let bytes = BASE.as_bytes();
    for _ in 0..2000 {
        let mut b = bytes.to_vec();
        for _ in 0..4 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let i = (seed >> 33) as usize % b.len();
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let table = b"=[]\"0.-e\n#x9 ";
            b[i] = table[(seed >> 40) as usize % table.len()];
        }
        if let Ok(text) = String::from_utf8(b) {
            let _ = parse(&text);
        }
    }
}

/// A table or a key given twice names itself and both lines (issue 15).
#[test]
fn duplicates_name_the_table_or_key_and_both_lines() {
    let base = include_str!("../examples/paper-c.toml");
    let dup_table = format!("{base}\n[contact]\nstiffness = 1e9\n");
    let first = base.lines().position(|l| l.trim() == "[contact]").unwrap() + 1;
    let again = dup_table
        .lines()
        .enumerate()
        .filter(|(_, l)| l.trim() == "[contact]")
        .last()
        .unwrap()
        .0
        + 1;
    let e = Scenario::from_toml(&dup_table, "d.toml", std::path::Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`contact`")
            && e.contains(&format!("first at line {first}"))
            && e.contains(&format!("again at line {again}")),
        "{e}"
    );
    let dup_key = base.replacen("gap = 0.0127", "gap = 0.0127\ngap = 0.02", 1);
    let e = Scenario::from_toml(&dup_key, "d.toml", std::path::Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(e.contains("`gap`") && e.contains("given twice"), "{e}");
}

/// Issue 15: every numeric key has a physical range; at both ends of each range (the others as
/// in the paper's case, 1 s of `adaptive`) a scenario is either refused with the key named, or
/// runs, or stops with an error — and when it runs, every number of its summary.json is finite.
/// Outside the ranges the scenario is refused naming the range.
#[test]
fn range_corners_give_finite_summaries_or_clear_errors() {
    use pounding::input::scenario::physical_range;
    let base = include_str!("../examples/paper-c.toml")
        .replace("method = \"rk4\"", "method = \"adaptive\"")
        .replace("duration = 20.0", "duration = 1.0");
    // (key as written in the file, the line to replace, a template with {v})
    let keys = [
        ("length", "length = 10.0", "length = {v}"),
        ("mass", "mass = 2.273e6", "mass = {v}"),
        ("period", "period = 0.4203", "period = {v}"),
        ("stiffness", "stiffness = 2.808e10", "stiffness = {v}"),
        ("gap", "gap = 0.0127", "gap = {v}"),
        ("pga", "pga = 0.6", "pga = {v}"),
    ];
    let mut ran = 0;
    for (key, line, template) in keys {
        assert!(base.contains(line), "{line}");
        let (lo, hi, _) = physical_range(key).unwrap();
        let lo = if lo == 0.0 { 0.0 } else { lo };
        for v in [lo, hi] {
            let text = base.replacen(line, &template.replace("{v}", &format!("{v:e}")), 1);
            let sc = match Scenario::from_toml(&text, "c.toml", std::path::Path::new(".")) {
                Ok(sc) => sc,
                Err(e) => {
                    let e = e.to_string();
                    assert!(e.contains('`'), "{key} = {v}: an error without a key: {e}");
                    continue;
                }
            };
            let Ok(report) = pounding::analysis::simulate::simulate(&sc) else {
                continue;
            };
            ran += 1;
            let json = pounding::output::run::summary_json(&sc, &report).unwrap();
            let value: serde_json::Value = serde_json::from_str(&json).unwrap();
            let mut stack = vec![&value];
            while let Some(x) = stack.pop() {
                match x {
                    // (`accuracy` is skipped: unchecked, its nulls say "not checked")
                    serde_json::Value::Null => panic!("{key} = {v}: a null in summary.json"),
                    serde_json::Value::Number(n) => {
                        assert!(n.as_f64().unwrap().is_finite(), "{key} = {v}: {n}");
                    }
                    serde_json::Value::Array(a) => stack.extend(a),
                    serde_json::Value::Object(o) => {
                        for (k, v2) in o {
                            if k != "accuracy" {
                                stack.push(v2);
                            }
                        }
                    }
                    _ => {}
                }
            }
        }
        // just outside: refused, naming the range
        let (lo, hi, _) = physical_range(key).unwrap();
        for v in [hi * 10.0, if lo > 0.0 { lo / 10.0 } else { -1.0 }] {
            let text = base.replacen(line, &template.replace("{v}", &format!("{v:e}")), 1);
            let e = Scenario::from_toml(&text, "c.toml", std::path::Path::new("."))
                .unwrap_err()
                .to_string();
            assert!(e.contains(key), "{key} = {v}: {e}");
        }
    }
    assert!(ran >= 6, "only {ran} corner runs ran");
}
