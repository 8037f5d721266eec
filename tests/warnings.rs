//! Issue 15: values inside their allowed range but unusual for real buildings, earthquakes or
//! runs are accepted with a warning that names the key, the usual band and why; the bundled
//! examples (scenarios and every case of every sweep) give none.

use std::path::Path;

use pounding::input::scenario::{Scenario, usual_range};
use pounding::study::sweep::Sweep;

const BASE: &str = include_str!("../examples/paper-c.toml");

/// Validates `text`, run by `adaptive` (rk4 at 1 ms would refuse the stiffer edits).
fn parse(text: &str) -> Scenario {
    let text = text.replace("method = \"rk4\"", "method = \"adaptive\"");
    Scenario::from_toml(&text, "w.toml", Path::new("examples"))
        .unwrap_or_else(|e| panic!("must be accepted: {e}\n{text}"))
}

/// `BASE` with its first line starting with `from` replaced by `to`.
fn edit(from: &str, to: &str) -> String {
    let at = BASE
        .find(&format!("\n{from}"))
        .unwrap_or_else(|| panic!("test edit `{from}` does not apply"))
        + 1;
    let end = at + BASE[at..].find('\n').unwrap();
    format!("{}{}{}", &BASE[..at], to, &BASE[end..])
}

/// The warnings of the paper's case with one line edited.
fn warnings_with(from: &str, to: &str) -> Vec<String> {
    parse(&edit(from, to)).warnings
}

#[test]
fn the_base_case_has_no_warning() {
    assert!(
        parse(BASE).warnings.is_empty(),
        "{:?}",
        parse(BASE).warnings
    );
}

/// A representative value outside each usual band warns, naming the key and the band; a value
/// just inside does not.
#[test]
fn unusual_values_warn_with_key_and_band() {
    // (line to replace, unusual value line, usual value line, key named, band text)
    let cases = [
        (
            "length = 10.0",
            "length = 1.0",
            "length = 3.0",
            "`structure[1].length`",
            "[2.5e0, 8.5e2] m",
        ),
        (
            "length = 10.0",
            "length = 1500.0",
            "length = 800.0",
            "`structure[1].length`",
            "[2.5e0, 8.5e2] m",
        ),
        (
            "mass = 2.273e6",
            "mass = 100.0",
            "mass = 2e4",
            "`structure[1].mass`",
            "[1e4, 1e10] kg",
        ),
        (
            "period = 0.4203",
            "period = 0.015",
            "period = 0.03",
            "`structure[1].period`",
            "[2e-2, 1.2e1] s",
        ),
        (
            "period = 0.4203",
            "period = 50.0",
            "period = 11.0",
            "`structure[1].period`",
            "[2e-2, 1.2e1] s",
        ),
        (
            "damping_ratio = 0.01",
            "damping_ratio = 0.0",
            "damping_ratio = 0.006",
            "`structure[1].damping_ratio`",
            "[5e-3, 2e-1]",
        ),
        (
            "damping_ratio = 0.01",
            "damping_ratio = 0.5",
            "damping_ratio = 0.15",
            "`structure[1].damping_ratio`",
            "[5e-3, 2e-1]",
        ),
        (
            "stiffness = 2.808e10",
            "stiffness = 10.0",
            "stiffness = 2e6",
            "`contact.stiffness`",
            "[1e6, 1e13]",
        ),
        (
            "stiffness = 2.808e10",
            "stiffness = 1e16",
            "stiffness = 5e12",
            "`contact.stiffness`",
            "[1e6, 1e13]",
        ),
        (
            "period = 0.65",
            "period = 60.0",
            "period = 15.0",
            "`ground_motion.period`",
            "[2e-2, 2e1] s",
        ),
        (
            "dt = 0.001",
            "dt = 0.1",
            "dt = 0.01",
            "`solver.dt`",
            "[1e-6, 5e-2] s",
        ),
        (
            "duration = 20.0",
            "duration = 0.5",
            "duration = 2.0",
            "`solver.duration`",
            "[1e0, 3.6e3] s",
        ),
        (
            "duration = 20.0",
            "duration = 5000.0",
            "duration = 3000.0",
            "`solver.duration`",
            "[1e0, 3.6e3] s",
        ),
    ];
    for (from, unusual, usual, key, band) in cases {
        // the ground motion's period line comes after the structures'
        let text = if from == "period = 0.65" {
            BASE.replacen("period = 0.65", unusual, 1)
        } else {
            edit(from, unusual)
        };
        let text = text.replace("method = \"rk4\"", "method = \"adaptive\"");
        let w = parse(&text).warnings;
        assert!(
            w.iter().any(|w| w.contains(key) && w.contains(band)),
            "`{unusual}` must warn naming {key} and {band}: {w:?}"
        );
        let text = if from == "period = 0.65" {
            BASE.replacen("period = 0.65", usual, 1)
        } else {
            edit(from, usual)
        };
        let text = text.replace("method = \"rk4\"", "method = \"adaptive\"");
        let w = parse(&text).warnings;
        assert!(
            !w.iter().any(|w| w.contains(key)),
            "`{usual}` must not warn about {key}: {w:?}"
        );
    }
}

/// Quantities warned about once from what several keys give: the PGA (low too), the first
/// period of a structure given by its stiffness, the damping of physical coefficients, the
/// restitution, the tolerances, a shear building's storeys.
#[test]
fn derived_and_other_keys_warn() {
    let w = warnings_with("pga = 0.6", "pga = 0.001");
    assert!(w.iter().any(|w| w.contains("below 0.01 g")), "{w:?}");
    // EI of 1e6 N·m² on 10 m and 2273 t: T1 = 2π/(3.516² √(EI/(m L⁴))) ≈ 24 s
    let w = warnings_with("period = 0.4203", "bending_stiffness = 1e6");
    assert!(
        w.iter()
            .any(|w| w.contains("structure 1") && w.contains("first-mode period")),
        "{w:?}"
    );
    // ζ₁ = c_s ω₁ / 2 = 1 · 15 / 2 ≫ 0.2 (ω₁ = 2π/0.42 s)
    let w = warnings_with("damping_ratio = 0.01", "strain_rate_damping = 1.0");
    assert!(
        w.iter()
            .any(|w| w.contains("structure 1") && w.contains("damping ratio")),
        "{w:?}"
    );
    let text = edit("law = \"hertz\"", "law = \"kelvin\"\nrestitution = 0.1");
    let w = parse(&text).warnings;
    assert!(
        w.iter().any(|w| w.contains("`contact.restitution`")),
        "{w:?}"
    );
    let text = edit("method = \"rk4\"", "method = \"adaptive\"\nrtol = 0.05");
    let w = parse(&text).warnings;
    assert!(w.iter().any(|w| w.contains("`solver.rtol`")), "{w:?}");
    let text = edit("method = \"rk4\"", "method = \"adaptive\"\natol = 0.01");
    let w = parse(&text).warnings;
    assert!(w.iter().any(|w| w.contains("`solver.atol`")), "{w:?}");
    let text = edit("output_interval = 0.01", "output_interval = 0.5");
    let w = parse(&text).warnings;
    assert!(
        w.iter().any(|w| w.contains("`solver.output_interval`")),
        "{w:?}"
    );
    // a 3-storey shear building with 20 m storeys and 10 kg floors
    let text = BASE.replacen(
        "length = 10.0\nmass = 2.273e6\nperiod = 0.4203",
        "kind = \"shear-building\"\nstoreys = 3\nstorey_height = 20.0\nfloor_mass = 10.0\n\
         storey_stiffness = 1e3",
        1,
    );
    let text = text
        .replace("method = \"rk4\"", "method = \"adaptive\"")
        .replace("modes = 3\n", "");
    let sc = Scenario::from_toml(&text, "w.toml", Path::new("examples"));
    // (the contact height of 10 m is not a floor of 20 m storeys: only the warnings matter,
    // which are collected before; use a height at a floor)
    let text = if sc.is_err() {
        text.replace("[contact]", "[contact]\nheight = 20.0")
            .replace("length = 10.0", "length = 60.0")
    } else {
        text
    };
    let w = parse(&text).warnings;
    for key in ["storey_height", "floor_mass", "storey_stiffness"] {
        assert!(
            w.iter()
                .any(|w| w.contains(&format!("`structure[1].{key}`"))),
            "{key}: {w:?}"
        );
    }
    // a list warns once
    let damp = edit("damping_ratio = 0.01", "damping_ratio = [0.5, 0.5, 0.5]");
    let w = parse(&damp).warnings;
    assert_eq!(
        w.iter().filter(|w| w.contains("damping_ratio")).count(),
        1,
        "{w:?}"
    );
}

/// Every band lies inside its key's allowed range.
#[test]
fn bands_are_inside_the_ranges() {
    use pounding::input::scenario::physical_range;
    for key in [
        "length",
        "mass",
        "structure[1].period",
        "ground_motion.period",
        "stiffness",
        "solver.dt",
        "duration",
        "output_interval",
        "storey_height",
        "floor_mass",
        "storey_stiffness",
        "floor_heights",
        "periods",
    ] {
        let (ulo, uhi, _) = usual_range(key).unwrap();
        let (lo, hi, _) = physical_range(key).unwrap();
        assert!(lo <= ulo && ulo < uhi && uhi <= hi, "{key}");
    }
}

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples")
}

/// No bundled scenario, and no case of any bundled sweep, gets a warning at validation.
#[test]
fn bundled_examples_give_no_warnings() {
    let mut scenarios = 0;
    let mut cases = 0;
    let mut names: Vec<_> = std::fs::read_dir(examples())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    for p in names {
        let text = std::fs::read_to_string(&p).unwrap();
        // a fragility study file (`[fragility]`) names its base scenario too: it is not a
        // sweep; its base scenario with the study's suite must read without warnings
        if text.lines().any(|l| l.trim() == "[fragility]") {
            let st = pounding::input::fragility::FragilityStudy::from_file(&p)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert!(
                st.scenario.warnings.is_empty(),
                "{}: {:?}",
                p.display(),
                st.scenario.warnings
            );
            scenarios += 1;
            continue;
        }
        if text
            .lines()
            .any(|l| l.trim_start().starts_with("scenario ="))
        {
            let sweep = Sweep::from_file(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            for case in 0..sweep.len() {
                let sc = sweep.case_scenario(case).unwrap();
                assert!(
                    sc.warnings.is_empty(),
                    "{} case {case}: {:?}",
                    p.display(),
                    sc.warnings
                );
                cases += 1;
            }
        } else {
            let sc = Scenario::from_file(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert!(sc.warnings.is_empty(), "{}: {:?}", p.display(), sc.warnings);
            scenarios += 1;
        }
    }
    assert!(
        scenarios >= 10 && cases >= 1000,
        "{scenarios} scenarios, {cases} cases"
    );
}

/// Issue 16's Bouc–Wen keys: an unusual post-yield ratio, exponent, yield drift (over the storey
/// height, given as a drift or as a force) or β + γ warns naming the key and the band; the
/// values of `examples/yielding-frames.toml` and nearby usual ones do not.
#[test]
fn unusual_bouc_wen_values_warn_with_key_and_band() {
    let base = std::fs::read_to_string(examples().join("yielding-frames.toml")).unwrap();
    let line = "hysteresis = { model = \"bouc-wen\", yield_drifts = 0.0175, post_yield_ratio = 0.05, \
                exponent = 2.0, beta = 0.5, gamma = 0.5 }";
    assert!(base.contains(line));
    let warnings = |keys: &str| {
        let text = base.replace(
            line,
            &format!("hysteresis = {{ model = \"bouc-wen\", {keys} }}"),
        );
        Scenario::from_toml(&text, "y.toml", &examples())
            .unwrap_or_else(|e| panic!("{keys}: must be accepted: {e}"))
            .warnings
    };
    let key = |k: &str| format!("`structure[2].hysteresis.{k}`");
    // (keys, the key named, its band; or no warning)
    let cases: [(&str, Option<(&str, &str)>); 14] = [
        ("yield_drifts = 0.0175, post_yield_ratio = 0.05", None),
        (
            "yield_drifts = 0.0175, post_yield_ratio = 0.5",
            Some(("post_yield_ratio", "[0e0, 3e-1]")),
        ),
        ("yield_drifts = 0.0175, post_yield_ratio = 0.25", None),
        ("yield_drifts = 0.0175, post_yield_ratio = 0.0", None),
        (
            "yield_drifts = 0.0175, post_yield_ratio = 0.05, exponent = 50.0",
            Some(("exponent", "[1e0, 2e1]")),
        ),
        (
            "yield_drifts = 0.0175, post_yield_ratio = 0.05, exponent = 15.0",
            None,
        ),
        // 2 mm and 20 cm of 3.5 m storeys: 0.06 % and 5.7 %
        (
            "yield_drifts = 0.002, post_yield_ratio = 0.05",
            Some(("yield_drifts", "[1e-3, 5e-2]")),
        ),
        (
            "yield_drifts = 0.2, post_yield_ratio = 0.05",
            Some(("yield_drifts", "[1e-3, 5e-2]")),
        ),
        ("yield_drifts = 0.1, post_yield_ratio = 0.05", None),
        // 1e5 N on 1.2e8 N/m storeys: 0.83 mm, 0.024 % of 3.5 m
        (
            "yield_forces = 1e5, post_yield_ratio = 0.05",
            Some(("yield_forces", "[1e-3, 5e-2]")),
        ),
        ("yield_forces = 2.1e6, post_yield_ratio = 0.05", None),
        (
            "yield_drifts = 0.0175, post_yield_ratio = 0.05, beta = 2.0, gamma = 1.5",
            Some(("beta", "[5e-1, 2e0]")),
        ),
        (
            "yield_drifts = 0.0175, post_yield_ratio = 0.05, beta = 0.2, gamma = 0.1",
            Some(("gamma", "[5e-1, 2e0]")),
        ),
        (
            "yield_drifts = 0.0175, post_yield_ratio = 0.05, beta = 0.9, gamma = -0.1",
            None,
        ),
    ];
    for (keys, want) in cases {
        let w = warnings(keys);
        match want {
            None => assert!(w.is_empty(), "{keys}: must not warn: {w:?}"),
            Some((k, band)) => {
                assert!(
                    w.len() == 1 && w[0].contains(&key(k)) && w[0].contains(band),
                    "{keys}: must warn once naming {} and {band}: {w:?}",
                    key(k)
                );
                eprintln!("{}", w[0]);
            }
        }
    }
    // a list of drifts warns once, for its first unusual storey
    let w = warnings(
        "yield_drifts = [0.0175, 0.0175, 0.001, 0.001, 0.0175, 0.0175, 0.0175, 0.0175], \
         post_yield_ratio = 0.05",
    );
    assert!(w.len() == 1 && w[0].contains("storey 3"), "{w:?}");
    for k in [
        "post_yield_ratio",
        "exponent",
        "yield_drift_ratio",
        "beta_plus_gamma",
    ] {
        assert!(usual_range(k).is_some(), "{k}");
    }
}

/// The kind of a run's warning, as an example's `# expect-warning:` header names it (README,
/// "Warnings on implausible values"): `drift`, `penetration`, `self-check`, `energy`,
/// `contact-step`, `usual` (a value outside its usual band), or `other`, which no header may
/// declare.
fn warning_kind(w: &str) -> &'static str {
    if w.contains("is a drift of") {
        "drift"
    } else if w.contains("the structures overlap by") {
        "penetration"
    } else if w.starts_with("self-check") {
        "self-check"
    } else if w.starts_with("energy balance") {
        "energy"
    } else if w.starts_with("the contact is stiff for this step") {
        "contact-step"
    } else if w.contains("outside the usual") {
        "usual"
    } else {
        "other"
    }
}

/// The kinds an example's header comment declares: `# expect-warning: a, b — why`.
fn expected_kinds(text: &str) -> Vec<String> {
    text.lines()
        .take_while(|l| l.trim_start().starts_with('#') || l.trim().is_empty())
        .filter_map(|l| {
            l.trim_start_matches('#')
                .trim()
                .strip_prefix("expect-warning:")
        })
        .flat_map(|rest| {
            let kinds = rest.split(" — ").next().unwrap_or("");
            kinds
                .split(',')
                .map(|k| k.trim().to_string())
                .collect::<Vec<_>>()
        })
        .filter(|k| !k.is_empty())
        .collect()
}

#[test]
fn expect_warning_headers_are_read() {
    let text = "# A case.\n# expect-warning: drift, self-check — the paper's case\ntitle = \"x\"\n# expect-warning: energy\n";
    assert_eq!(expected_kinds(text), ["drift", "self-check"]);
    assert!(expected_kinds("title = \"x\"\n").is_empty());
    assert_eq!(warning_kind("self-check NOT converged: …"), "self-check");
    assert_eq!(warning_kind("something new"), "other");
}

/// Every bundled scenario runs as `pounding run` runs it — with its
/// self-check — without a run-time warning and converged, unless its header declares the
/// warnings it exists to show (`# expect-warning: drift, penetration, self-check — why`);
/// a declared kind must then occur, so that no header outlives its reason. Sweeps are covered
/// through their base scenarios, which are bundled examples themselves. A design-spectrum
/// scenario has no time history to run. About 9 s in all (release build, loaded 2-core
/// machine): the longest are yielding-frames (45 s of record, 1.9 s), twenty-storeys (1.8 s)
/// and two-levels (1.5 s).
#[test]
fn bundled_examples_run_without_warnings() {
    let mut names: Vec<_> = std::fs::read_dir(examples())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    let mut ran = 0;
    let mut bases = Vec::new();
    for p in &names {
        let text = std::fs::read_to_string(p).unwrap();
        // a fragility study file (`[fragility]`) names its base scenario too: it is not a
        // sweep (no test runs the bundled study yet: it is `pounding fragility`'s example)
        if text.lines().any(|l| l.trim() == "[fragility]") {
            continue;
        }
        if text
            .lines()
            .any(|l| l.trim_start().starts_with("scenario ="))
        {
            let sweep = Sweep::from_file(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            bases.push((p.clone(), sweep));
            continue;
        }
        let sc = Scenario::from_file(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        if pounding::analysis::simulate::require_time_history(&sc).is_err() {
            continue;
        }
        // a suite of records on a row: every record's run of the row, self-checked
        if sc.is_row() && sc.suite.is_some() {
            let run = pounding::study::suite::row::run_row(&sc, true)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            for r in &run.records {
                assert!(
                    r.report.warnings.is_empty(),
                    "{}: {:?}",
                    r.file,
                    r.report.warnings
                );
                assert_eq!(r.report.accuracy.converged, Some(true), "{}", r.file);
            }
            ran += 1;
            continue;
        }
        // a row of buildings (issue 29): its warnings, none expected of the bundled row
        if sc.is_row() {
            let r = pounding::analysis::simulate::simulate_row(&sc)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert!(r.warnings.is_empty(), "{}: {:?}", p.display(), r.warnings);
            ran += 1;
            continue;
        }
        // a suite of records: every record's run (issue 27)
        let reports = match sc.suite {
            Some(_) => pounding::study::suite::run(&sc, true)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
                .records
                .into_iter()
                .map(|r| r.report)
                .collect(),
            None => vec![
                pounding::analysis::simulate::simulate_checked(&sc, true)
                    .unwrap_or_else(|e| panic!("{}: {e}", p.display())),
            ],
        };
        ran += 1;
        let expected = expected_kinds(&text);
        for report in &reports {
            for k in &expected {
                assert!(
                    k != "other" && report.warnings.iter().any(|w| warning_kind(w) == k),
                    "{}: the header expects a `{k}` warning, which the run does not give (remove \
                     it from the header): {:?}",
                    p.display(),
                    report.warnings
                );
            }
            for w in &report.warnings {
                assert!(
                    expected.iter().any(|k| k == warning_kind(w)),
                    "{}: warning of kind `{}` not declared by an `# expect-warning:` header: {w}",
                    p.display(),
                    warning_kind(w)
                );
            }
            assert!(
                report.accuracy.is_converged() || expected.iter().any(|k| k == "self-check"),
                "{}: not converged: {:?}",
                p.display(),
                report.accuracy
            );
        }
    }
    // every sweep's base scenario is one of the examples just run
    for (p, _) in &bases {
        let text = std::fs::read_to_string(p).unwrap();
        let base = text
            .lines()
            .find_map(|l| l.trim().strip_prefix("scenario ="))
            .map(|v| {
                v.split('#')
                    .next()
                    .unwrap()
                    .trim()
                    .trim_matches('"')
                    .to_string()
            })
            .unwrap();
        assert!(
            names
                .iter()
                .any(|n| n.file_name().unwrap() == base.as_str()),
            "{}: base scenario {base} is not a bundled example",
            p.display()
        );
    }
    assert!(ran >= 10, "{ran} scenarios run");
}
