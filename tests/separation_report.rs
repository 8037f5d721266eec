//! Issue 13 wired into what users run: the scenario keys of a design spectrum and of the code
//! factors (values and every error), `pounding separation` on a case checked by hand (one mode:
//! u = S_d Γφ(h)), `separation.codes` of summary.json, the sweep's code columns, the rule study,
//! and `pounding run` refusing a spectrum.
//!
//! Expected numbers come from closed forms: the cantilever's first mode (λ₁ from
//! cosh λ cos λ + 1 = 0, σ₁, tip participation Γφ(L) = 4σ/λ for φ normalised to ∫φ² = L), the
//! ASCE 7 spectrum's branches, Der Kiureghian's ρ, and each code's formula (docs/codes.md).

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use pounding::codes::rules::{Asce7Boundary, CodeRule, GbSystem, NtcMethod, NtcZone, PartialStep};
use pounding::codes::spectrum::DesignSpectrum;
use pounding::input::scenario::Scenario;
use pounding::input::scenario::design::ToDesign;

mod common;
use common::pounding;

const G: f64 = 9.80665;

/// Two cantilevers of height `l`, one mode each, 5 % damping, periods 0.5 s and 1.0 s; contact
/// at the top with a 50 mm gap; then `ground` and `extra`.
fn scenario_text(l: f64, ground: &str, extra: &str) -> String {
    format!(
        r#"title = "hand case"

[[structure]]
name = "left"
length = {l}
mass = 1.0e6
period = 0.5
modes = 1
damping_ratio = 0.05

[[structure]]
name = "right"
length = {l}
mass = 1.0e6
period = 1.0
modes = 1
damping_ratio = 0.05

[contact]
stiffness = 1.0e10
gap = 0.05

[ground_motion]
{ground}
{extra}"#
    )
}

const ASCE: &str = "kind = \"spectrum\"\nspectrum = \"asce7\"\nsds = 1.0\nsd1 = 0.6\ntl = 8.0";

fn parse(text: &str) -> Result<Scenario, String> {
    Scenario::from_toml(text, "hand.toml", Path::new(".")).map_err(|e| e.to_string())
}

/// Tip participation of a uniform cantilever's first mode, Γφ(L) = 4σ₁/λ₁ (∫φ dx = 2σL/λ and
/// φ(L) = 2 for the shape cosh − cos − σ(sinh − sin) with ∫φ² = L), λ₁ by bisection.
fn tip_participation() -> f64 {
    let f = |x: f64| x.cosh() * x.cos() + 1.0;
    let (mut a, mut b) = (1.5, 2.5);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if f(a) * f(m) <= 0.0 { b = m } else { a = m }
    }
    let l = 0.5 * (a + b);
    let sigma = (l.sinh() - l.sin()) / (l.cosh() + l.cos());
    4.0 * sigma / l
}

/// The hand case's peaks at the top: S_a = S_DS = 1 g at T = 0.5 s (T₀ = 0.12 s ≤ T ≤ T_S =
/// 0.6 s) and S_D1/T = 0.6 g at T = 1 s; S_d = S_a (T/2π)²; u = S_d Γφ(L).
fn hand_peaks() -> [f64; 2] {
    let gp = tip_participation();
    let sd1 = G * (0.5 / (2.0 * PI)).powi(2);
    let sd2 = 0.6 * G * (1.0 / (2.0 * PI)).powi(2);
    [gp * sd1, gp * sd2]
}

/// ρ for ζ = 0.05 both and r = 0.5 (separation.rs's hand value).
fn hand_rho() -> f64 {
    0.4 * 0.075 * 0.5f64.powf(1.5) / 0.57375
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

#[test]
fn tip_participation_is_the_textbook_value() {
    assert!((tip_participation() - 1.566).abs() < 5e-4);
}

// ------------------------------------------------------------------------------------------
// Scenario keys

#[test]
fn spectrum_and_code_keys_are_read() {
    let extra = r#"
[separation]
asce7 = { cd = [5.5, 4.0], ie = 1.25, r = 8, boundary = "property-line" }
is1893 = { r = 5, displacement_factor = 0.2 }
nbcc = { rd = 4, ro = 1.5, ie = 1, displacement_factor = [0.1, 0.2] }
gb50011 = { intensity = 8, systems = ["frame", "shear-wall"], partial_step = "linear" }
ntc = { zone = "III", method = "simplified", same_height_and_levels = true }
"#;
    let sc = parse(&scenario_text(10.0, ASCE, extra)).unwrap();
    match &sc.design.spectrum {
        Some(DesignSpectrum::Asce7(s)) => {
            assert_eq!((s.sds(), s.sd1(), s.tl()), (1.0, 0.6, 8.0));
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        sc.ground_motion,
        pounding::model::ground_motion::GroundMotion::None
    );
    let keys: Vec<&str> = sc.design.codes.iter().map(|c| c.rule.key()).collect();
    assert_eq!(keys, ["asce7", "is1893", "nbcc", "gb50011", "ntc"]);
    match (sc.design.codes[0].rule, sc.design.codes[0].to_design) {
        (CodeRule::Asce7(p), ToDesign::Asce7R { r }) => {
            assert_eq!(p.cd, [5.5, 4.0]);
            assert_eq!(p.ie, [1.25, 1.25]);
            assert_eq!(p.boundary, Asce7Boundary::PropertyLine);
            assert_eq!(r, [8.0, 8.0]);
        }
        other => panic!("{other:?}"),
    }
    match (sc.design.codes[2].rule, sc.design.codes[2].to_design) {
        (CodeRule::Nbcc(p), ToDesign::Factor(f)) => {
            assert_eq!((p.rd, p.ro, p.ie), ([4.0; 2], [1.5; 2], [1.0; 2]));
            assert_eq!(f, [0.1, 0.2]);
        }
        other => panic!("{other:?}"),
    }
    match sc.design.codes[3].rule {
        CodeRule::Gb50011(p) => {
            assert_eq!(p.intensity, 8);
            assert_eq!(p.system, [GbSystem::Frame, GbSystem::ShearWall]);
            assert_eq!(p.partial_step, PartialStep::Linear);
        }
        other => panic!("{other:?}"),
    }
    match (sc.design.codes[4].rule, sc.design.codes[4].to_design) {
        (CodeRule::NtcSismo(p), ToDesign::NotUsed) => {
            assert_eq!(p.zone, NtcZone::III);
            assert_eq!(p.method, NtcMethod::Simplified);
            assert!(p.same_height_and_levels);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn ec8_spectrum_in_g_and_a_table_file_are_read() {
    let ec8 = "kind = \"spectrum\"\nspectrum = \"ec8\"\nag = 0.25\nunits = \"g\"\nground_type = \"C\"\ntype = 1";
    let sc = parse(&scenario_text(10.0, ec8, "")).unwrap();
    match &sc.design.spectrum {
        Some(DesignSpectrum::Ec8(s)) => {
            assert!(close(s.ag(), 0.25 * G, 1e-15));
            // Table 3.2, ground C: S = 1.15, T_B = 0.2, T_C = 0.6, T_D = 2.0
            let sh = s.shape();
            assert_eq!((sh.s, sh.tb, sh.tc, sh.td), (1.15, 0.2, 0.6, 2.0));
        }
        other => panic!("{other:?}"),
    }
    // a table in g with a header line and a comment
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("spec.txt"),
        "T Sa\n# 5 % damped\n0.0 0.4\n0.5 1.0\n2.0, 0.25\n",
    )
    .unwrap();
    let text = scenario_text(
        10.0,
        "kind = \"spectrum\"\nspectrum = \"table\"\nfile = \"spec.txt\"\nunits = \"g\"",
        "",
    );
    let sc = Scenario::from_toml(&text, "t.toml", dir.path()).unwrap();
    match &sc.design.spectrum {
        Some(DesignSpectrum::Table(t)) => {
            assert_eq!(t.periods(), [0.0, 0.5, 2.0]);
            assert_eq!(t.accelerations(), [0.4 * G, 1.0 * G, 0.25 * G]);
        }
        other => panic!("{other:?}"),
    }
    // defaults are listed: ASCE boundary, GB partial step, NTC same-height
    let extra = "[separation]\nasce7 = { cd = 5.5, ie = 1, r = 8 }\ngb50011 = { intensity = 7, systems = \"frame\" }\nntc = { zone = \"I\", method = \"analysis\", displacement_factor = 1 }\n";
    let sc = parse(&scenario_text(10.0, ASCE, extra)).unwrap();
    for d in [
        "separation.asce7.boundary = \"same-property\"",
        "separation.gb50011.partial_step = \"round-up\"",
        "separation.ntc.same_height_and_levels = false",
    ] {
        assert!(
            sc.defaults_applied.iter().any(|x| x == d),
            "{d} not in {:?}",
            sc.defaults_applied
        );
    }
}

/// Every new key with a wrong value: the message names file:line:col, the key and the range.
#[test]
fn every_new_key_is_checked_with_its_place_and_range() {
    let ok_sep = "[separation]\n";
    let cases: &[(&str, &str, &str, &str)] = &[
        // (ground, extra, expected fragments…)
        (
            "kind = \"spectrum\"\nspectrum = \"asce7\"\nsds = 0\nsd1 = 0.6\ntl = 8",
            "",
            "hand.toml:26:7: `ground_motion.sds` = 0",
            "(0, 5] g",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"asce7\"\nsds = 1\nsd1 = 9\ntl = 8",
            "",
            "hand.toml:27:7: `ground_motion.sd1` = 9",
            "(0, 5] g",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"asce7\"\nsds = 1\nsd1 = 0.6\ntl = 0.5",
            "",
            "hand.toml:28:6: `ground_motion.tl` = 0.5",
            "below T_S",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"asce8\"",
            "",
            "`ground_motion.spectrum` = asce8",
            "\"asce7\", \"ec8\" or \"table\"",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"ec8\"\nag = 40\nground_type = \"C\"\ntype = 1",
            "",
            "hand.toml:26:6: `ground_motion.ag` = 40",
            "(0, 30] m/s²",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"ec8\"\nag = 2\nground_type = \"F\"\ntype = 1",
            "",
            "`ground_motion.ground_type` = F",
            "\"A\", \"B\", \"C\", \"D\" or \"E\"",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"ec8\"\nag = 2\nground_type = \"C\"\ntype = 3",
            "",
            "`ground_motion.type` = 3",
            "must be 1 or 2",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"ec8\"\nag = 2\nunits = \"mg\"\nground_type = \"C\"\ntype = 1",
            "",
            "`ground_motion.units` = mg",
            "\"g\" or \"m/s2\"",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"table\"\nfile = \"nowhere.txt\"",
            "",
            "`ground_motion.file` = nowhere.txt",
            "cannot read",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"asce7\"\nsds = 1\nsd1 = 0.6\ntl = 8\npga = 0.3",
            "",
            "`ground_motion.pga` = (given)",
            "not used with kind = \"spectrum\"",
        ),
        (
            "kind = \"harmonic\"\npga = 0.3\nperiod = 1.0\nsds = 1.0",
            "",
            "`ground_motion.sds` = (given)",
            "not used with kind = \"harmonic\"",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"asce7\"\nsd1 = 0.6\ntl = 8",
            "",
            "missing key `ground_motion.sds`",
            "S_DS in g",
        ),
        (
            ASCE,
            "[separation]\nasce7 = { cd = 0.5, ie = 1, r = 8 }",
            "hand.toml:30:16: `separation.asce7.cd` = 0.5",
            "[1, 10]",
        ),
        (
            ASCE,
            "[separation]\nasce7 = { cd = 5.5, ie = 2, r = 8 }",
            "`separation.asce7.ie` = 2",
            "[1, 1.5]",
        ),
        (
            ASCE,
            "[separation]\nasce7 = { cd = 5.5, ie = 1, r = [8, 8, 8] }",
            "`separation.asce7.r` = [8, 8, 8]",
            "two such numbers",
        ),
        (
            ASCE,
            "[separation]\nasce7 = { cd = 5.5, ie = 1 }",
            "missing key `separation.asce7.r`",
            "§12.9.1.2",
        ),
        (
            ASCE,
            "[separation]\nasce7 = { cd = 5.5, ie = 1, r = 8, displacement_factor = 0.1 }",
            "`separation.asce7.displacement_factor` = 0.1",
            "not both",
        ),
        (
            ASCE,
            "[separation]\nasce7 = { cd = 5.5, ie = 1, r = 8, boundary = \"fence\" }",
            "`separation.asce7.boundary` = fence",
            "\"same-property\"",
        ),
        (
            ASCE,
            "[separation]\nis1893 = { r = 5 }",
            "missing key `separation.is1893.displacement_factor`",
            "never assumes",
        ),
        (
            ASCE,
            "[separation]\nis1893 = { r = [5, 3], displacement_factor = 0.2 }",
            "`separation.is1893.r` = [5, 3]",
            "one R",
        ),
        (
            ASCE,
            "[separation]\nis1893 = { r = 5, displacement_factor = 0 }",
            "`separation.is1893.displacement_factor` = 0",
            "(0, 10]",
        ),
        (
            ASCE,
            "[separation]\nnbcc = { rd = 4, ro = 1.5, ie = 3, displacement_factor = 1 }",
            "`separation.nbcc.ie` = 3",
            "[0.5, 2]",
        ),
        (
            ASCE,
            "[separation]\nnbcc = { rd = 0, ro = 1.5, ie = 1, displacement_factor = 1 }",
            "`separation.nbcc.rd` = 0",
            "[1, 10]",
        ),
        (
            ASCE,
            "[separation]\ngb50011 = { intensity = 10, systems = \"frame\" }",
            "`separation.gb50011.intensity` = 10",
            "6, 7, 8 or 9",
        ),
        (
            ASCE,
            "[separation]\ngb50011 = { intensity = 8, systems = \"steel\" }",
            "`separation.gb50011.systems` = \"steel\"",
            "\"frame-shear-wall\"",
        ),
        (
            ASCE,
            "[separation]\ngb50011 = { intensity = 8, systems = \"frame\", partial_step = \"up\" }",
            "`separation.gb50011.partial_step` = up",
            "\"round-up\"",
        ),
        (
            ASCE,
            "[separation]\nntc = { zone = \"IV\", method = \"analysis\", displacement_factor = 1 }",
            "`separation.ntc.zone` = IV",
            "\"I\", \"II\" or \"III\"",
        ),
        (
            ASCE,
            "[separation]\nntc = { zone = \"I\", method = \"static\", displacement_factor = 1 }",
            "`separation.ntc.method` = static",
            "\"analysis\" or \"simplified\"",
        ),
        (
            ASCE,
            "[separation]\nntc = { zone = \"I\", method = \"simplified\", displacement_factor = 1 }",
            "`separation.ntc.displacement_factor` = 1",
            "not used with method = \"simplified\"",
        ),
        (
            ASCE,
            "[separation]\nec8 = { qd = 4 }",
            "missing key `separation.ec8.q`",
            "behaviour factor q",
        ),
        (
            ASCE,
            "[separation]\nec8 = { q = 0.5 }",
            "`separation.ec8.q` = 0.5",
            "[1, 10]",
        ),
        (
            ASCE,
            "[separation]\nec8 = { q = 4, boundary = \"street\" }",
            "`separation.ec8.boundary` = street",
            "\"property-line\"",
        ),
        (
            ASCE,
            "[separation]\nec8 = { q = 4, floor_reduction = 1 }",
            "hand.toml:30:34: `separation.ec8.floor_reduction` = 1",
            "must be true",
        ),
        (
            ASCE,
            "[separation]\nasce7 = { cd = 5.5, ie = 1, rr = 8 }",
            "unknown key `rr` in [separation.asce7]; did you mean `r`?",
            "valid keys: cd, ie, r, displacement_factor, boundary",
        ),
        (
            ASCE,
            "[separation]\nnbc = { rd = 4 }",
            "unknown key `nbc` in [separation]; did you mean `nbcc`?",
            "valid keys: asce7",
        ),
        (
            "kind = \"spectrum\"\nspectrum = \"asce7\"\nsds = 1\nsd1 = 0.6\ntl = 8\ntll = 4",
            "",
            "unknown key `tll` in [ground_motion]; did you mean `tl`?",
            "ground_type, type",
        ),
    ];
    let _ = ok_sep;
    for (ground, extra, a, b) in cases {
        let e = parse(&scenario_text(10.0, ground, extra)).unwrap_err();
        assert!(
            e.contains(a) && e.contains(b),
            "expected `{a}` … `{b}` in:\n{e}"
        );
    }
}

// ------------------------------------------------------------------------------------------
// pounding separation on the hand case

fn hand_codes(l: f64) -> String {
    let _ = l;
    r#"
[separation]
asce7 = { cd = 5.5, ie = 1.25, r = 8 }
is1893 = { r = 5, displacement_factor = 0.2 }
nbcc = { rd = 4, ro = 1.5, ie = 1, displacement_factor = [0.1, 0.2] }
gb50011 = { intensity = 8, systems = ["frame", "shear-wall"] }
ntc = { zone = "II", method = "analysis", displacement_factor = 1 }
"#
    .into()
}

/// The required separations of the hand case at the top of 24 m cantilevers, by the formulas
/// of docs/codes.md: (label, value).
fn hand_rules(w: [f64; 2], l: f64) -> Vec<(&'static str, f64)> {
    let [a, b] = w;
    let rho = hand_rho();
    let dm = [5.5 * (a * 1.25 / 8.0) / 1.25, 5.5 * (b * 1.25 / 8.0) / 1.25];
    let nb = [a * 0.1 * 6.0, b * 0.2 * 6.0];
    // GB 50011, intensity 8: 100 mm + 20 mm per started 3 m above 15 m; the wider system
    // (frame) at the lower height
    let gb = (100.0 + 20.0 * ((l - 15.0) / 3.0f64).ceil()) / 1000.0;
    let ntc = (a + 0.003 * l).max(0.05) + (b + 0.003 * l).max(0.05);
    vec![
        ("ABS", a + b),
        ("SRSS", a.hypot(b)),
        ("DDC ", (a * a + b * b - 2.0 * rho * a * b).sqrt()),
        ("ASCE 7-16", dm[0].hypot(dm[1])),
        ("IS 1893", 5.0 * 0.2 * (a + b)),
        ("NBCC", nb[0].hypot(nb[1])),
        ("GB 50011", gb),
        ("NTC-Sismo", ntc),
    ]
}

#[test]
fn separation_report_of_a_single_mode_spectrum_case_by_hand() {
    let l = 24.0;
    let sc = parse(&scenario_text(l, ASCE, &hand_codes(l))).unwrap();
    let r = pounding::analysis::gap_report::gap_report(&sc, None, None).unwrap();
    let w = hand_peaks();
    assert_eq!(r.levels.len(), 1);
    let level = &r.levels[0];
    let s = level.spectral.as_ref().unwrap();
    // one mode: SRSS = CQC = |S_d Γφ(h)|
    for (resp, wi) in [(&s.structure1, w[0]), (&s.structure2, w[1])] {
        assert!(close(resp.srss, wi, 1e-9), "{} vs {wi}", resp.srss);
        assert!(close(resp.cqc, wi, 1e-9));
    }
    assert!(level.exact.is_none());
    // two cantilevers: no floors, so no reduction
    assert!(!level.floors_coincide);
    let expect = hand_rules(w, l);
    let by_key = |k: &str| level.rules.iter().find(|x| x.key == k).unwrap().required;
    for (key, (_, v)) in [
        "abs", "srss", "ddc", "asce7", "is1893", "nbcc", "gb50011", "ntc",
    ]
    .iter()
    .zip(&expect)
    {
        assert!(
            close(by_key(key), *v, 1e-9),
            "{key}: {} vs {v}",
            by_key(key)
        );
    }
    // DDC over both structures' modes: with one mode each it is the first-mode DDC
    assert!(close(by_key("ddc_modes"), expect[2].1, 1e-9));
    assert_eq!(expect[6].1, 0.16);
    // the gap given (50 mm) suffices for none but … none: check the flags against the values
    for row in &level.rules {
        assert_eq!(row.sufficient, 0.05 >= row.required, "{}", row.key);
        assert_eq!(row.margin, 0.05 - row.required);
        assert!(row.vs_exact_percent.is_none());
    }
    // one level: each rule's verdict is that level
    assert_eq!(r.verdict.rules.len(), level.rules.len());
    for (g, x) in r.verdict.rules.iter().zip(&level.rules) {
        assert_eq!(
            (g.height, g.required, g.sufficient),
            (l, x.required, x.sufficient)
        );
    }
    // --code selects; unknown and absent codes are refused
    let only = ["gb50011".to_string()];
    let r = pounding::analysis::gap_report::gap_report(&sc, None, Some(&only)).unwrap();
    assert_eq!(r.levels[0].codes.len(), 1);
    let e = pounding::analysis::gap_report::gap_report(&sc, None, Some(&["ec8".to_string()]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no [separation.ec8] table"), "{e}");
    let e = pounding::analysis::gap_report::gap_report(&sc, None, Some(&["ec9".to_string()]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown code") && e.contains("ec8"), "{e}");
}

#[test]
fn separation_command_prints_the_hand_values() {
    let l = 24.0;
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("hand.toml");
    std::fs::write(&f, scenario_text(l, ASCE, &hand_codes(l))).unwrap();
    let out = pounding(&["separation", "hand.toml"], dir.path());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("no time history"), "{text}");
    let w = hand_peaks();
    for (label, v) in hand_rules(w, l) {
        let line = text
            .lines()
            .find(|x| x.trim_start().starts_with(label))
            .unwrap_or_else(|| panic!("no row {label} in\n{text}"));
        // mm with 3 decimals
        let value = format!("{:.3}", 1e3 * v);
        assert!(
            line.contains(&value),
            "{label}: expected {value} in `{line}`"
        );
        let verdict = if 0.05 >= v { "suffices" } else { "TOO SMALL" };
        assert!(line.contains(verdict), "{label}: `{line}`");
    }
    // the spectral peaks of each structure
    assert!(text.contains(&format!(
        "structure 1 SRSS {:.3}, CQC {:.3}",
        1e3 * w[0],
        1e3 * w[0]
    )));
    // --spectrum on a scenario with a time history: the rules from the spectrum, the exact
    // value from the time history beside them
    let harmonic = scenario_text(
        l,
        "kind = \"harmonic\"\npga = 0.3\nperiod = 0.8",
        &hand_codes(l),
    );
    std::fs::write(dir.path().join("th.toml"), harmonic).unwrap();
    let out = pounding(
        &[
            "separation",
            "th.toml",
            "--code",
            "asce7",
            "--spectrum",
            "asce7:sds=1.0,sd1=0.6,tl=8",
        ],
        dir.path(),
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("(exact)") && text.contains("vs exact"),
        "{text}"
    );
    let asce = text.lines().find(|x| x.contains("§12.12.3")).unwrap();
    assert!(
        asce.contains(&format!("{:.3}", 1e3 * hand_rules(w, l)[3].1)),
        "{asce}"
    );
    assert!(asce.ends_with('%'), "{asce}");
    assert!(!text.contains("IS 1893"), "--code asce7 only:\n{text}");
    // a bad --spectrum is an error with the key and the range, not a panic
    let out = pounding(
        &[
            "separation",
            "th.toml",
            "--spectrum",
            "asce7:sds=-1,sd1=0.6,tl=8",
        ],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("`sds` = -1") && err.contains("(0, 5] g"),
        "{err}"
    );
}

#[test]
fn run_refuses_a_spectrum_and_points_to_separation() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), scenario_text(10.0, ASCE, "")).unwrap();
    let out = pounding(&["run", "s.toml", "--out", "res"], dir.path());
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no time history") && err.contains("pounding separation"),
        "{err}"
    );
    assert!(!dir.path().join("res").exists(), "nothing is written");
    // nor is there anything to converge
    let out = pounding(&["convergence", "s.toml"], dir.path());
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no time history"));
    // the library refuses too (sweeps, convergence)
    let sc = parse(&scenario_text(10.0, ASCE, "")).unwrap();
    let e = pounding::analysis::simulate::simulate(&sc)
        .unwrap_err()
        .to_string();
    assert!(e.contains("design spectrum"), "{e}");
}

// ------------------------------------------------------------------------------------------
// summary.json and the sweep columns

/// The code values for no-pounding peaks `w` of the study factors below, by hand.
fn th_codes(w: [f64; 2]) -> [(&'static str, f64); 3] {
    [
        ("asce7", (5.5 / 8.0 * w[0]).hypot(5.5 / 8.0 * w[1])),
        ("is1893", 5.0 * 0.2 * (w[0] + w[1])),
        ("gb50011", 0.1),
    ]
}

const TH_CODES: &str = "[separation]\nasce7 = { cd = 5.5, ie = 1, r = 8 }\nis1893 = { r = 5, displacement_factor = 0.2 }\ngb50011 = { intensity = 8, systems = \"frame\" }\n";

#[test]
fn summary_json_has_separation_codes() {
    let dir = tempfile::tempdir().unwrap();
    let text = scenario_text(
        10.0,
        "kind = \"harmonic\"\npga = 0.3\nperiod = 0.8",
        &format!("[solver]\nduration = 5.0\n{TH_CODES}"),
    );
    std::fs::write(dir.path().join("h.toml"), text).unwrap();
    let out = pounding(&["run", "h.toml", "--out", "res", "--no-plot"], dir.path());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("res/summary.json")).unwrap(),
    )
    .unwrap();
    let w = [0, 1].map(|i| {
        j["structures"][i]["peak_displacement_no_contact"]
            .as_f64()
            .unwrap()
    });
    let exact = j["separation"]["time_history"].as_f64().unwrap();
    let codes = j["separation"]["codes"].as_array().unwrap();
    assert_eq!(codes.len(), 3);
    for (c, (key, v)) in codes.iter().zip(th_codes(w)) {
        assert_eq!(c["key"], key);
        let req = c["required"].as_f64().unwrap();
        assert!(close(req, v, 1e-12), "{key}: {req} vs {v}");
        assert_eq!(c["sufficient"].as_bool().unwrap(), 0.05 >= v);
        for k in ["name", "clause", "terms", "displacements"] {
            assert!(!c[k].is_null(), "{key} lacks {k}");
        }
        let pct = c["vs_time_history_percent"].as_f64().unwrap();
        assert!(close(pct, 100.0 * (v - exact) / exact, 1e-9));
    }
    assert_eq!(codes[0]["clause"], "§12.12.3, Eqs. (12.12-1), (12.12-2)");
    // without [separation] there is no `codes` key
    let text = scenario_text(
        10.0,
        "kind = \"harmonic\"\npga = 0.3\nperiod = 0.8",
        "[solver]\nduration = 2.0\n",
    );
    std::fs::write(dir.path().join("n.toml"), text).unwrap();
    let out = pounding(&["run", "n.toml", "--out", "res2", "--no-plot"], dir.path());
    assert!(out.status.success());
    let j: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("res2/summary.json")).unwrap(),
    )
    .unwrap();
    assert!(j["separation"].get("codes").is_none());
}

fn write(path: &Path, text: &str) -> PathBuf {
    std::fs::write(path, text).unwrap();
    path.to_path_buf()
}

#[test]
fn sweep_returns_code_columns() {
    let dir = tempfile::tempdir().unwrap();
    let base = scenario_text(
        10.0,
        "kind = \"harmonic\"\npga = 0.3\nperiod = 0.8",
        &format!("[solver]\nduration = 3.0\n{TH_CODES}"),
    );
    write(&dir.path().join("base.toml"), &base);
    write(
        &dir.path().join("sw.toml"),
        "scenario = \"base.toml\"\n[[axis]]\nkey = \"ground_motion.pga\"\nvalues = [0.2, 0.4]\n",
    );
    let out = pounding(
        &[
            "sweep",
            "sw.toml",
            "-o",
            "o",
            "--no-plot",
            "--no-check",
            "-j",
            "1",
        ],
        dir.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.path().join("o/results.csv")).unwrap();
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    // the v2 columns unchanged, the code columns appended in the order asce7, is1893, gb50011
    assert_eq!(
        head[head.len() - 4..],
        ["converged", "sep_asce7", "sep_is1893", "sep_gb50011"]
    );
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let num = |name: &str| f[col(name)].parse::<f64>().unwrap();
        let w = [
            num("peak_displacement_no_contact_1"),
            num("peak_displacement_no_contact_2"),
        ];
        for (key, v) in th_codes(w) {
            let got = num(&format!("sep_{key}"));
            assert!(close(got, v, 1e-12), "{key}: {got} vs {v}");
        }
    }
    // the journal says v3 (an older pounding refuses to resume it)
    let journal = std::fs::read_to_string(dir.path().join("o/journal.csv")).unwrap();
    assert!(
        journal.starts_with("# pounding sweep journal v3;"),
        "{journal}"
    );
    // the table reads back with its code columns
    let t =
        pounding::study::sweep::results::Table::read(&dir.path().join("o/results.csv")).unwrap();
    assert_eq!(t.codes, ["sep_asce7", "sep_is1893", "sep_gb50011"]);
    let r = &t.rows[&0];
    assert_eq!(r.get(&t, "sep_gb50011"), Some(0.1));
    assert!(r.get(&t, "sep_nbcc").is_none());
    // a sweep without [separation] writes the v2 table unchanged
    let plain = scenario_text(
        10.0,
        "kind = \"harmonic\"\npga = 0.3\nperiod = 0.8",
        "[solver]\nduration = 2.0\n",
    );
    write(&dir.path().join("base.toml"), &plain);
    let out = pounding(
        &[
            "sweep",
            "sw.toml",
            "-o",
            "p",
            "--no-plot",
            "--no-check",
            "-j",
            "1",
        ],
        dir.path(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.path().join("p/results.csv")).unwrap();
    assert!(csv.lines().next().unwrap().ends_with(",converged"));
    let journal = std::fs::read_to_string(dir.path().join("p/journal.csv")).unwrap();
    assert!(journal.starts_with("# pounding sweep journal v2;"));
}

// ------------------------------------------------------------------------------------------
// the rule study

#[test]
fn rule_study_counts_unsafe_cases_and_excess_by_hand() {
    use pounding::study::sweep::results::FIELDS;
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("results.csv");
    // four ok cases with exact = 0.1, 0.2, 0.4, 0 (the last left out) and one failed case;
    // abs = 2 × exact, srss = 0.9 × exact in the first two and 1.5 × in the third,
    // ddc = exact × (0.5, 1, 1.2), sep_asce7 = 0.05 constant
    let head = format!("case,x,status,{},sep_asce7", FIELDS.join(","));
    let mut text = head + "\n";
    let rows = [
        (0.1, 0.2, 0.09, 0.05, 0.05),
        (0.2, 0.4, 0.18, 0.2, 0.05),
        (0.4, 0.8, 0.6, 0.48, 0.05),
        (0.0, 0.0, 0.0, 0.0, 0.05),
    ];
    for (i, (e, abs, srss, ddc, asce)) in rows.iter().enumerate() {
        let mut f = vec!["0".to_string(); FIELDS.len()];
        let idx = |n: &str| FIELDS.iter().position(|x| *x == n).unwrap();
        f[idx("sep_abs")] = abs.to_string();
        f[idx("sep_srss")] = srss.to_string();
        f[idx("sep_ddc")] = ddc.to_string();
        f[idx("sep_time_history")] = e.to_string();
        f[idx("check_max_change")] = String::new();
        f[idx("converged")] = "unchecked".into();
        text.push_str(&format!("{i},{},ok,{},{asce}\n", i + 1, f.join(",")));
    }
    text.push_str(&format!("4,5,failed: x{}\n", ",".repeat(FIELDS.len() + 1)));
    std::fs::write(&p, text).unwrap();
    let t = pounding::study::sweep::results::Table::read(&p).unwrap();
    let s = pounding::study::rule_study::rule_study(&t);
    assert_eq!((s.rows, s.left_out), (5, 2));
    let get = |c: &str| s.rules.iter().find(|r| r.column == c).unwrap();
    let abs = get("sep_abs");
    assert_eq!((abs.cases, abs.unsafe_cases), (3, 0));
    assert!(close(abs.median_over_percent, 100.0, 1e-12));
    let srss = get("sep_srss");
    assert_eq!(srss.unsafe_cases, 2);
    assert!(close(srss.unsafe_fraction, 2.0 / 3.0, 1e-15));
    assert!(close(srss.worst_under_percent, -10.0, 1e-9));
    assert!(close(srss.max_over_percent, 50.0, 1e-9));
    let ddc = get("sep_ddc");
    // 0.05/0.1 − 1 = −50 % unsafe; 0 % (equal: safe) and +20 %
    assert_eq!(ddc.unsafe_cases, 1);
    assert!(close(ddc.worst_under_percent, -50.0, 1e-9));
    assert!(close(ddc.mean_over_percent, 10.0, 1e-9));
    let asce = get("sep_asce7");
    // 0.05 against 0.1, 0.2, 0.4: all unsafe, worst −87.5 %
    assert_eq!(asce.unsafe_cases, 3);
    assert!(close(asce.worst_under_percent, -87.5, 1e-9));
    assert!(asce.median_over_percent.is_nan());
    // the figure is drawn
    let files =
        pounding::figures::rules::rule_figure(&t, Some("x"), &dir.path().join("plots"), "test")
            .unwrap();
    assert!(files.iter().any(|f| f.ends_with("rules.png")));
}

#[test]
fn bundled_study_and_spectrum_examples_are_valid() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let s = pounding::study::sweep::Sweep::from_file(&dir.join("separation-sweep.toml")).unwrap();
    assert_eq!(s.len(), 3 * 7 * 5);
    for c in [0, 52, 104] {
        let sc = s
            .case_scenario(c)
            .unwrap_or_else(|e| panic!("case {c}: {e}"));
        assert_eq!(sc.design.codes.len(), 5);
    }
    assert_eq!(
        s.code_columns(),
        [
            "sep_asce7",
            "sep_is1893",
            "sep_nbcc",
            "sep_gb50011",
            "sep_ntc"
        ]
    );
    let sc = Scenario::from_file(&dir.join("design-spectrum.toml")).unwrap();
    assert!(matches!(sc.design.spectrum, Some(DesignSpectrum::Asce7(_))));
    let r = pounding::analysis::gap_report::gap_report(&sc, None, None).unwrap();
    assert_eq!(r.levels[0].codes.len(), 5);
}
