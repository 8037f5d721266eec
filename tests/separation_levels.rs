//! Issue 24, items 1, 2 and 4b: the required separation at every contact level (the lower level
//! governing), EN 1998-1 §4.4.2.7 and IS 1893 §7.11.3 with and without coinciding floors, the
//! `--json` report, the unit of a_g, and a yielding run through `pounding separation`.
//!
//! The spectral case is computed here by hand: two 2-storey shear buildings with equal floor
//! masses m and storey stiffnesses k have ω² = (k/m)(3 ∓ √5)/2 and mode shapes
//! φ₂/φ₁ = 2 − ω²m/k (from det(K − ω²M) = 0 with K = k[[2, −1], [−1, 1]]), mass-normalised
//! m(φ₁² + φ₂²) = 1, Γ = m(φ₁ + φ₂); the peak at floor j is u_n = Γ_n φ_n(j) S_d(T_n) with
//! the ASCE 7-16 §11.4.6 branches, combined by CQC with Der Kiureghian's ρ — all written
//! below from the formulas, none read from the program.

use std::f64::consts::PI;
use std::path::Path;

use pounding::analysis::gap_report::{GapReport, gap_report};
use pounding::input::scenario::Scenario;

mod common;
use common::pounding;

const G: f64 = 9.80665;

fn parse(text: &str) -> Scenario {
    Scenario::from_toml(text, "levels.toml", Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

/// The issue's case: two 2-storey shear buildings with floors at 3.2 and 6.4 m, touching at
/// both floors: 10 mm at 3.2 m, 200 mm at 6.4 m. Building A: m = 2e5 kg, k = 2e8 N/m;
/// building B: m = 2e5 kg, k = 8e7 N/m; 5 % damping in every mode.
fn buildings(ground: &str, separation: &str) -> String {
    format!(
        r#"title = "two 2-storey buildings, gaps 10 mm at 3.2 m and 200 mm at 6.4 m"

[[structure]]
name = "A"
kind = "shear-building"
floor_heights = [3.2, 6.4]
floor_masses = [2.0e5, 2.0e5]
storey_stiffnesses = [2.0e8, 2.0e8]
damping_ratio = 0.05

[[structure]]
name = "B"
kind = "shear-building"
floor_heights = [3.2, 6.4]
floor_masses = [2.0e5, 2.0e5]
storey_stiffnesses = [8.0e7, 8.0e7]
damping_ratio = 0.05

[contact]
stiffness = 1.0e9

[[contact.level]]
height = 6.4
gap = 0.2

[[contact.level]]
height = 3.2
gap = 0.01

[ground_motion]
{ground}

{separation}
"#
    )
}

const ASCE: &str = "kind = \"spectrum\"\nspectrum = \"asce7\"\nsds = 1.0\nsd1 = 0.6\ntl = 8.0";

const CODES: &str = r#"[separation]
asce7 = { cd = 5.5, ie = 1.0, r = 8 }
is1893 = { r = 5, displacement_factor = 0.2 }
nbcc = { rd = 4, ro = 1.5, ie = 1, displacement_factor = 0.25 }
gb50011 = { intensity = 8, systems = "frame" }
ntc = { zone = "II", method = "analysis", displacement_factor = 1.0 }
ec8 = { q = 4, qd = 3 }"#;

/// ASCE 7-16 §11.4.6 S_a in m/s² (S_DS = 1, S_D1 = 0.6, T_L = 8).
fn asce_sa(t: f64) -> f64 {
    let (sds, sd1, tl) = (1.0, 0.6, 8.0);
    let (t0, ts) = (0.2 * sd1 / sds, sd1 / sds);
    G * if t < t0 {
        sds * (0.4 + 0.6 * t / t0)
    } else if t <= ts {
        sds
    } else if t <= tl {
        sd1 / t
    } else {
        sd1 * tl / (t * t)
    }
}

/// Der Kiureghian's correlation for modes i, j (equal damping here), r = ω_j/ω_i.
fn rho(zi: f64, zj: f64, wi: f64, wj: f64) -> f64 {
    let r = wj / wi;
    8.0 * (zi * zj).sqrt() * (zi + r * zj) * r.powf(1.5)
        / ((1.0 - r * r).powi(2)
            + 4.0 * zi * zj * r * (1.0 + r * r)
            + 4.0 * (zi * zi + zj * zj) * r * r)
}

/// One building's two modes: (ω_n, [Γ_n φ_n(floor 1), Γ_n φ_n(floor 2)] S_d(T_n)).
fn modal_peaks(m: f64, k: f64) -> [(f64, [f64; 2]); 2] {
    let s5 = 5f64.sqrt();
    [(3.0 - s5) / 2.0, (3.0 + s5) / 2.0].map(|lambda| {
        let w = (lambda * k / m).sqrt();
        let ratio = 2.0 - lambda; // φ₂/φ₁
        let phi1 = 1.0 / (m * (1.0 + ratio * ratio)).sqrt();
        let phi = [phi1, ratio * phi1];
        let gamma = m * (phi[0] + phi[1]);
        let sd = asce_sa(2.0 * PI / w) / (w * w);
        (w, phi.map(|p| gamma * p * sd))
    })
}

/// CQC of signed modal peaks `u` with frequencies `w`, all at ζ = 0.05.
fn cqc(u: &[f64], w: &[f64]) -> f64 {
    let mut s = 0.0;
    for i in 0..u.len() {
        for j in 0..u.len() {
            let r = if i == j {
                1.0
            } else {
                rho(0.05, 0.05, w[i], w[j])
            };
            s += r * u[i] * u[j];
        }
    }
    s.sqrt()
}

/// The hand values at floor `j` (0: 3.2 m, 1: 6.4 m): the two CQC peaks, the all-mode DDC,
/// and every rule by its formula (docs/codes.md), with the floors coinciding.
struct Hand {
    peaks: [f64; 2],
    rules: Vec<(&'static str, f64)>,
}

fn hand(j: usize, height: f64) -> Hand {
    let (a, b) = (modal_peaks(2e5, 2e8), modal_peaks(2e5, 8e7));
    let w: Vec<f64> = a.iter().chain(&b).map(|x| x.0).collect();
    let ua: Vec<f64> = a.iter().map(|x| x.1[j]).collect();
    let ub: Vec<f64> = b.iter().map(|x| x.1[j]).collect();
    let (w1, w2) = (cqc(&ua, &w[..2]), cqc(&ub, &w[2..]));
    let rel: Vec<f64> = ua.iter().copied().chain(ub.iter().map(|u| -u)).collect();
    let ddc_modes = cqc(&rel, &w);
    let r1 = rho(0.05, 0.05, w[0], w[2]);
    let ntc = |d: f64| (d + 0.003 * height).max(0.05);
    let rules = vec![
        ("abs", w1 + w2),
        ("srss", w1.hypot(w2)),
        ("ddc", (w1 * w1 + w2 * w2 - 2.0 * r1 * w1 * w2).sqrt()),
        ("ddc_modes", ddc_modes),
        ("ddc_paper", (w1 * w1 + w2 * w2 - r1 / 4.0 * w1 * w2).sqrt()),
        // δ_M = C_d (δ I_e/R)/I_e
        ("asce7", (5.5 / 8.0 * w1).hypot(5.5 / 8.0 * w2)),
        // the floor levels coincide: R/2
        ("is1893", 2.5 * 0.2 * (w1 + w2)),
        ("nbcc", (0.25 * 6.0 * w1).hypot(0.25 * 6.0 * w2)),
        // below 15 m: 100 mm
        ("gb50011", 0.1),
        ("ntc", ntc(w1) + ntc(w2)),
        // d_s = q_d d_e = 3 (w/4); the floor elevations coincide: × 0.7
        ("ec8", 0.7 * (0.75 * w1).hypot(0.75 * w2)),
    ];
    Hand {
        peaks: [w1, w2],
        rules,
    }
}

fn level(r: &GapReport, h: f64) -> &pounding::analysis::level_checks::LevelCheck {
    r.levels.iter().find(|l| l.height == h).unwrap()
}

/// Every rule at both levels by hand; the lower level governs every rule, which the old
/// report (the highest level only) called sufficient.
#[test]
fn every_rule_at_every_level_by_hand_and_the_lower_level_governs() {
    let sc = parse(&buildings(ASCE, CODES));
    let r = gap_report(&sc, None, None).unwrap();
    assert_eq!(r.levels.len(), 2);
    // in the scenario's order
    assert_eq!((r.levels[0].height, r.levels[1].height), (6.4, 3.2));
    for (j, h, gap) in [(0, 3.2, 0.01), (1, 6.4, 0.2)] {
        let want = hand(j, h);
        let l = level(&r, h);
        assert_eq!(l.gap, gap);
        assert!(l.floors_coincide, "{h} m is a floor of both");
        assert!(l.exact.is_none());
        // the spectral peaks at h (2 modes each); 1e-9: the program's eigen-solver against
        // the closed form
        for i in 0..2 {
            assert!(
                close(l.peaks[i], want.peaks[i], 1e-9),
                "{h}: {:?} vs {:?}",
                l.peaks,
                want.peaks
            );
        }
        let s = l.spectral.as_ref().unwrap();
        assert_eq!((s.structure1.modes.len(), s.structure2.modes.len()), (2, 2));
        for (key, v) in &want.rules {
            let row = l.rules.iter().find(|x| x.key == *key).unwrap();
            assert!(
                close(row.required, *v, 1e-9),
                "{h} m {key}: {} vs {v}",
                row.required
            );
            assert_eq!(row.sufficient, gap >= *v, "{h} m {key}");
            assert_eq!(row.margin, gap - row.required);
        }
        // the reductions are said
        let said = |k: &str| l.codes.iter().find(|c| c.key == k).unwrap().reduction;
        assert!(said("is1893").unwrap().contains("R/2"));
        assert!(said("ec8").unwrap().contains("0.7"));
        assert_eq!(said("asce7"), None);
    }
    // the case: everything suffices at 6.4 m, nothing at 3.2 m
    assert!(level(&r, 6.4).rules.iter().all(|x| x.sufficient));
    assert!(level(&r, 3.2).rules.iter().all(|x| !x.sufficient));
    // every rule's verdict: 3.2 m, too small, with the hand value there
    let low = hand(0, 3.2);
    assert_eq!(r.verdict.rules.len(), low.rules.len());
    assert_eq!(r.verdict.insufficient, low.rules.len());
    for g in &r.verdict.rules {
        let v = low.rules.iter().find(|x| x.0 == g.key).unwrap().1;
        assert_eq!(
            (g.height, g.gap, g.sufficient),
            (3.2, 0.01, false),
            "{}",
            g.key
        );
        assert!(close(g.required, v, 1e-9));
    }
    // the most demanding: the largest requirement at 3.2 m (NTC-Sismo's s₁ + s₂ here)
    let most = low
        .rules
        .iter()
        .fold(("", 0.0), |m, x| if x.1 > m.1 { *x } else { m });
    let gov = r.verdict.governing.as_ref().unwrap();
    assert_eq!((gov.key.as_str(), gov.height), (most.0, 3.2));
}

/// The same case through the command line: tables in mm with 3 decimals, the verdict naming
/// 3.2 m, and `--json` carrying the same numbers.
#[test]
fn separation_command_and_json_report_every_level() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("b.toml"), buildings(ASCE, CODES)).unwrap();
    let out = pounding(&["separation", "b.toml"], dir.path());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let low = hand(0, 3.2);
    // the level's table: each rule's hand value in mm to 3 decimals
    let at = text
        .find("contact level h = 3.2 m")
        .expect("the 3.2 m level");
    let table = &text[at..];
    for (key, v) in &low.rules {
        let want = format!("{:.3}", 1e3 * v);
        assert!(table.contains(&want), "{key}: {want} not in\n{table}");
    }
    assert!(text.contains("a floor of both structures"), "{text}");
    assert!(text.contains("R/2") && text.contains("× 0.7"), "{text}");
    let verdict = &text[text.find("verdict").expect("a verdict table")..];
    let abs = verdict
        .lines()
        .find(|l| l.trim_start().starts_with("ABS"))
        .unwrap();
    assert!(abs.contains("3.2") && abs.contains("TOO SMALL"), "{abs}");
    assert!(text.contains("TOO SMALL by 11 of 11 rules"), "{text}");

    let out = pounding(&["separation", "b.toml", "--json"], dir.path());
    assert!(out.status.success());
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["peaks_from"], "spectrum");
    let levels = j["levels"].as_array().unwrap();
    assert_eq!(levels.len(), 2);
    let l = &levels[1];
    assert_eq!(l["height"], 3.2);
    assert_eq!(l["gap"], 0.01);
    assert_eq!(l["floors_coincide"], true);
    for (i, p) in low.peaks.iter().enumerate() {
        assert!(close(l["peaks"][i].as_f64().unwrap(), *p, 1e-9));
    }
    // the modal terms of the spectral analysis
    let m = &l["spectral"]["structure1"]["modes"][0];
    for k in ["period", "zeta", "sa", "sd", "gamma", "phi", "displacement"] {
        assert!(m[k].is_number(), "{k} in {m}");
    }
    for row in l["rules"].as_array().unwrap() {
        let key = row["key"].as_str().unwrap();
        let v = low.rules.iter().find(|x| x.0 == key).unwrap().1;
        assert!(close(row["required"].as_f64().unwrap(), v, 1e-9), "{key}");
        assert_eq!(row["sufficient"], false);
    }
    let asce = l["codes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["key"] == "asce7")
        .unwrap();
    assert!(asce["conversion"].as_str().unwrap().contains("§12.9.1.2"));
    assert_eq!(j["verdict"]["rules"][0]["height"], 3.2);
    assert_eq!(j["verdict"]["insufficient"], 11);
}

/// EN 1998-1 and IS 1893 where the floors do not coincide: two cantilevers (no floors) touching
/// at their tops, one mode each; the peaks are S_d Γφ(L) with Γφ(L) = 4σ₁/λ₁ (a uniform
/// cantilever's first mode); no reduction. And on the buildings, `floor_reduction = false`
/// turns the reductions off.
#[test]
fn no_reduction_without_coinciding_floors_or_when_turned_off() {
    let f = |x: f64| x.cosh() * x.cos() + 1.0;
    let (mut lo, mut hi) = (1.5, 2.5);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if f(lo) * f(m) <= 0.0 { hi = m } else { lo = m }
    }
    let l1 = 0.5 * (lo + hi);
    let gp = 4.0 * (l1.sinh() - l1.sin()) / (l1.cosh() + l1.cos()) / l1;
    let w = [0.5, 1.0].map(|t: f64| gp * asce_sa(t) * (t / (2.0 * PI)).powi(2));
    let text = format!(
        r#"[[structure]]
length = 10.0
mass = 1.0e6
period = 0.5
modes = 1
damping_ratio = 0.05
[[structure]]
length = 10.0
mass = 1.0e6
period = 1.0
modes = 1
damping_ratio = 0.05
[contact]
stiffness = 1.0e10
gap = 0.05
[ground_motion]
{ASCE}
[separation]
is1893 = {{ r = 5, displacement_factor = 0.2 }}
ec8 = {{ q = 4, boundary = "property-line" }}
"#
    );
    let r = gap_report(&parse(&text), None, None).unwrap();
    let l = &r.levels[0];
    assert!(!l.floors_coincide);
    let req = |k: &str| l.codes.iter().find(|c| c.key == k).unwrap();
    // R (Δ₁ + Δ₂), Δ = 0.2 w
    assert!(close(
        req("is1893").required,
        5.0 * 0.2 * (w[0] + w[1]),
        1e-9
    ));
    // q_d = q: d_s = q (w/q) = w; property line: d_s1 + d_s2
    assert!(close(req("ec8").required, w[0] + w[1], 1e-9));
    assert!(req("is1893").reduction.is_none() && req("ec8").reduction.is_none());

    let off = CODES
        .replace(
            "displacement_factor = 0.2 }",
            "displacement_factor = 0.2, floor_reduction = false }",
        )
        .replace("qd = 3 }", "qd = 3, floor_reduction = false }");
    let r = gap_report(&parse(&buildings(ASCE, &off)), None, None).unwrap();
    let want = hand(0, 3.2);
    let l = level(&r, 3.2);
    let get = |k: &str| l.codes.iter().find(|c| c.key == k).unwrap();
    let hand_of = |k: &str| want.rules.iter().find(|x| x.0 == k).unwrap().1;
    assert!(close(get("is1893").required, 2.0 * hand_of("is1893"), 1e-9));
    assert!(close(get("ec8").required, hand_of("ec8") / 0.7, 1e-9));
    assert!(get("ec8").reduction.is_none());
    // a floor of both structures, whatever the switch
    assert!(l.floors_coincide);
}

/// A time history: every level's peaks and exact separation are those of the run without
/// pounding at that level (summary.json `levels`), the main-level keys keep their meaning, and
/// `pounding separation` reports the same numbers as `pounding run`.
#[test]
fn time_history_levels_match_the_run_and_keep_the_old_keys() {
    let dir = tempfile::tempdir().unwrap();
    let ground = "kind = \"harmonic\"\npga = 0.3\nperiod = 0.45\n\n[solver]\nduration = 4.0";
    std::fs::write(dir.path().join("t.toml"), buildings(ground, CODES)).unwrap();
    let out = pounding(
        &["run", "t.toml", "--out", "res", "--no-plot", "--no-check"],
        dir.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("res/summary.json")).unwrap(),
    )
    .unwrap();
    let sep = &j["separation"];
    assert_eq!(sep["peaks_from"], "time_history");
    let levels = j["levels"].as_array().unwrap();
    let checks = sep["levels"].as_array().unwrap();
    assert_eq!(checks.len(), levels.len());
    for (lv, c) in levels.iter().zip(checks) {
        assert_eq!(lv["height"], c["height"]);
        let p = [0, 1].map(|i| lv["peak_displacement_no_contact"][i].as_f64().unwrap());
        assert_eq!(c["peaks"][0].as_f64().unwrap(), p[0]);
        assert_eq!(c["peaks"][1].as_f64().unwrap(), p[1]);
        assert_eq!(c["exact"], lv["required_gap"]);
        let rule = |k: &str| {
            c["rules"]
                .as_array()
                .unwrap()
                .iter()
                .find(|x| x["key"] == k)
                .unwrap()["required"]
                .as_f64()
                .unwrap()
        };
        assert_eq!(rule("time_history"), lv["required_gap"].as_f64().unwrap());
        assert!(close(rule("abs"), p[0] + p[1], 1e-15));
        assert!(close(rule("srss"), p[0].hypot(p[1]), 1e-15));
        // IS 1893 with R/2 at these coinciding floors
        assert!(close(rule("is1893"), 2.5 * 0.2 * (p[0] + p[1]), 1e-15));
    }
    // the old keys: the main (highest) level, unchanged in meaning
    let top = checks.iter().find(|c| c["height"] == 6.4).unwrap();
    let top_rule = |k: &str| {
        top["rules"]
            .as_array()
            .unwrap()
            .iter()
            .find(|x| x["key"] == k)
            .unwrap()["required"]
            .as_f64()
            .unwrap()
    };
    assert_eq!(sep["abs"].as_f64().unwrap(), top_rule("abs"));
    assert_eq!(
        sep["time_history"].as_f64().unwrap(),
        top_rule("time_history")
    );
    assert_eq!(sep["codes"][0]["key"], "asce7");
    assert_eq!(
        sep["codes"][0]["required"].as_f64().unwrap(),
        top_rule("asce7")
    );
    // the verdict names a level for each rule, the worst by margin
    for g in sep["verdict"]["rules"].as_array().unwrap() {
        let key = g["key"].as_str().unwrap();
        let margins: Vec<(f64, f64)> = checks
            .iter()
            .map(|c| {
                let row = c["rules"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .find(|x| x["key"] == key)
                    .unwrap();
                (
                    c["height"].as_f64().unwrap(),
                    row["margin"].as_f64().unwrap(),
                )
            })
            .collect();
        let worst = margins
            .iter()
            .fold(margins[0], |m, x| if x.1 < m.1 { *x } else { m });
        assert_eq!(g["height"].as_f64().unwrap(), worst.0, "{key}");
        assert_eq!(g["margin"].as_f64().unwrap(), worst.1, "{key}");
    }
    // the same numbers from `pounding separation --json` (the run without pounding only)
    let out = pounding(&["separation", "t.toml", "--json"], dir.path());
    assert!(out.status.success());
    let s: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(s["levels"], sep["levels"]);
    assert_eq!(s["verdict"], sep["verdict"]);
}

/// A yielding run through `pounding separation`: the report says the peaks are inelastic, and
/// they are those of the yielding run without pounding (`pounding run`), not of the elastic
/// building.
#[test]
fn a_yielding_run_feeds_its_inelastic_peaks_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let ground = "kind = \"harmonic\"\npga = 0.5\nperiod = 0.6\n\n[solver]\nduration = 4.0";
    let elastic = buildings(ground, "");
    // building B yields at 2 mm storey drift (its elastic drifts are several times that)
    let yielding = elastic.replacen(
        "storey_stiffnesses = [8.0e7, 8.0e7]\ndamping_ratio = 0.05",
        "storey_stiffnesses = [8.0e7, 8.0e7]\ndamping_ratio = 0.05\nhysteresis = { model = \"bouc-wen\", yield_drifts = 0.002, post_yield_ratio = 0.05, exponent = 2.0, beta = 0.5, gamma = 0.5 }",
        1,
    );
    assert_ne!(yielding, elastic);
    std::fs::write(dir.path().join("y.toml"), &yielding).unwrap();
    std::fs::write(dir.path().join("e.toml"), &elastic).unwrap();
    let out = pounding(&["separation", "y.toml"], dir.path());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("INELASTIC"), "{text}");
    let json = |f: &str| -> serde_json::Value {
        let out = pounding(&["separation", f, "--json"], dir.path());
        assert!(out.status.success());
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let (y, e) = (json("y.toml"), json("e.toml"));
    assert_eq!(y["peaks_from"], "time_history_yielding");
    assert_eq!(y["yielding"], serde_json::json!([false, true]));
    assert_eq!(e["peaks_from"], "time_history");
    let peak = |v: &serde_json::Value| v["levels"][0]["peaks"][1].as_f64().unwrap();
    // yielding changes B's peak (by more than 1 %: it yields well past 2 mm)
    assert!(
        !close(peak(&y), peak(&e), 0.01),
        "{} vs {}",
        peak(&y),
        peak(&e)
    );
    // and the peaks are those of the yielding run without pounding
    let out = pounding(
        &["run", "y.toml", "--out", "res", "--no-plot", "--no-check"],
        dir.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("res/summary.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(j["separation"]["peaks_from"], "time_history_yielding");
    assert_eq!(j["separation"]["levels"], y["levels"]);
    assert_eq!(
        j["levels"][0]["peak_displacement_no_contact"],
        y["levels"][0]["peaks"]
    );
}

/// a_g of `--spectrum ec8` needs its unit; `0.25g`, `2.4516625m/s2` and `units=g` agree; the
/// scenario key warns when a bare a_g below 1.5 m/s² is probably in g.
#[test]
fn the_unit_of_ag() {
    use pounding::input::scenario::design::spectrum_from_arg;
    let e = spectrum_from_arg("ec8:ag=2.5,ground_type=C,type=1")
        .unwrap_err()
        .to_string();
    assert!(e.contains("needs its unit") && e.contains("ag=2.5g"), "{e}");
    let e = spectrum_from_arg("ec8:ag=0.25g,ground_type=C,type=1,units=g")
        .unwrap_err()
        .to_string();
    assert!(e.contains("give one of them"), "{e}");
    let ag = |arg: &str| match spectrum_from_arg(arg).unwrap() {
        pounding::codes::spectrum::DesignSpectrum::Ec8(s) => s.ag(),
        other => panic!("{other:?}"),
    };
    let in_g = ag("ec8:ag=0.25g,ground_type=C,type=1");
    assert!(close(in_g, 0.25 * G, 1e-15));
    assert_eq!(ag("ec8:ag=0.25,units=g,ground_type=C,type=1"), in_g);
    assert!(close(
        ag("ec8:ag=2.4516625m/s2,ground_type=C,type=1"),
        in_g,
        1e-15
    ));
    assert_eq!(ag("ec8:ag=2.5,units=m/s2,ground_type=C,type=1"), 2.5);
    // the scenario: a bare 0.25 is read in m/s² with a warning; 2.5 or units = "m/s2" without
    let ec8 = |v: &str| {
        format!(
            "[[structure]]\nlength = 10.0\nmass = 1e6\nperiod = 0.5\n[[structure]]\nlength = 10.0\n\
             mass = 1e6\nperiod = 1.0\n[contact]\nstiffness = 1e10\ngap = 0.05\n[ground_motion]\n\
             kind = \"spectrum\"\nspectrum = \"ec8\"\nground_type = \"C\"\ntype = 1\n{v}\n"
        )
    };
    let warned = |v: &str| {
        parse(&ec8(v))
            .warnings
            .iter()
            .any(|w| w.contains("units = \"g\""))
    };
    assert!(warned("ag = 0.25"));
    assert!(!warned("ag = 2.5"));
    assert!(!warned("ag = 0.25\nunits = \"m/s2\""));
    assert!(!warned("ag = 0.25\nunits = \"g\""));
    // and `pounding separation` prints it
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), ec8("ag = 0.25")).unwrap();
    let out = pounding(&["separation", "s.toml"], dir.path());
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("warning: `ground_motion.ag` = 0.25"));
}

/// The EN 1998-1 keys are read, with their defaults listed.
#[test]
fn ec8_keys_and_defaults() {
    let sc = parse(&buildings(ASCE, "[separation]\nec8 = { q = [4, 1.5] }"));
    let c = sc.design.code("ec8").unwrap();
    match (c.rule, c.to_design) {
        (
            pounding::codes::rules::CodeRule::Ec8(p),
            pounding::input::scenario::design::ToDesign::Ec8 { q },
        ) => {
            assert_eq!(q, [4.0, 1.5]);
            assert_eq!(p.qd, q, "q_d = q unless given");
            assert_eq!(
                p.boundary,
                pounding::codes::rules::Ec8Boundary::SameProperty
            );
            assert!(p.floor_reduction);
        }
        other => panic!("{other:?}"),
    }
    for d in [
        "separation.ec8.qd = q (§4.3.4)",
        "separation.ec8.boundary = \"same-property\"",
    ] {
        assert!(
            sc.defaults_applied.iter().any(|x| x == d),
            "{d}: {:?}",
            sc.defaults_applied
        );
    }
    assert!(
        sc.defaults_applied
            .iter()
            .any(|x| x.starts_with("separation.ec8.floor_reduction = true"))
    );
}
