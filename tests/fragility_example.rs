//! Issue 28: the bundled example `examples/fragility.toml` runs, and its outputs keep their
//! invariants: fraction = exceedances / runs; P(pounding) non-increasing in the gap and equal,
//! at the scenario's 50 mm gaps, to the fraction of runs that pound (with and without
//! contact: the same event); P(pounding) at every gap the fraction of records whose critical
//! gap in runs.csv exceeds it; the printed gap for 10 % at 0.3 g the one p_pounding.csv and
//! runs.csv give (the smallest gap at which at most ⌊0.1 · 7⌋ = 0 records pound).

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_pounding");

/// A CSV file of plain fields as rows of name → text.
fn table(path: &Path) -> Vec<BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            head.iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

fn f(r: &BTreeMap<String, String>, k: &str) -> f64 {
    r[k].parse()
        .unwrap_or_else(|_| panic!("{k} = {:?} is not a number", r[k]))
}

#[test]
fn the_bundled_example_runs_and_its_outputs_agree() {
    let d = tempfile::tempdir().unwrap();
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/fragility.toml");
    let o = Command::new(BIN)
        .args(["fragility", ex.to_str().unwrap(), "--out"])
        .arg(d.path())
        .arg("--no-plot")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report = String::from_utf8_lossy(&o.stdout).into_owned();

    // fragility.csv: 7 runs per stripe, fraction = exceedances / runs exactly
    let frag = table(&d.path().join("fragility.csv"));
    assert!(!frag.is_empty());
    for r in &frag {
        assert_eq!(f(r, "runs"), 7.0, "{r:?}");
        assert_eq!(
            f(r, "fraction"),
            f(r, "exceedances") / f(r, "runs"),
            "{r:?}"
        );
    }
    // P(pounding | IM, gap): non-increasing in the gap at every IM
    let p = table(&d.path().join("p_pounding.csv"));
    let mut by_im: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for r in &p {
        by_im
            .entry(r["im"].clone())
            .or_default()
            .push((f(r, "gap"), f(r, "p_pounding")));
    }
    assert_eq!(by_im.len(), 6);
    for (im, v) in &by_im {
        assert!(
            v.windows(2).all(|w| w[0].0 < w[1].0 && w[1].1 <= w[0].1),
            "{im}"
        );
        // at the scenario's gaps (50 mm at every level) the fraction of runs that pound, with
        // and without contact
        let at50 = v.iter().find(|(g, _)| (g - 0.05).abs() < 1e-12).unwrap().1;
        for model in ["with", "without"] {
            let row = frag
                .iter()
                .find(|r| r["limit_state"] == "pounding" && r["model"] == model && r["im"] == *im)
                .unwrap();
            assert_eq!(f(row, "fraction"), at50, "{model} at {im}");
        }
    }
    // … and at every gap the fraction of records whose critical gap (runs.csv) exceeds it
    let runs = table(&d.path().join("runs.csv"));
    assert_eq!(runs.len(), 42);
    for r in &p {
        let crit: Vec<f64> = runs
            .iter()
            .filter(|x| x["im"] == r["im"])
            .map(|x| f(x, "critical_gap"))
            .collect();
        assert_eq!(crit.len(), 7);
        let n = crit.iter().filter(|c| **c > f(r, "gap")).count();
        assert_eq!(f(r, "p_pounding"), n as f64 / 7.0, "{r:?}");
    }
    // the printed gap for P ≤ 10 % at 0.3 g: the largest critical gap at 0.3 g (⌊0.7⌋ = 0
    // records may pound), where p_pounding.csv falls to 0 and above 0.1 just below
    let line = report
        .lines()
        .find(|l| l.contains("gap for P(pounding) ≤ 10 % at IM = 0.3 g"))
        .unwrap_or_else(|| panic!("no target line in:\n{report}"));
    let mm: f64 = line
        .split(": ")
        .nth(1)
        .unwrap()
        .split(" mm")
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let largest = runs
        .iter()
        .filter(|x| x["im"] == "0.3")
        .map(|x| f(x, "critical_gap"))
        .fold(0.0, f64::max);
    // (printed to 0.1 mm)
    assert!(
        (mm - 1e3 * largest).abs() <= 0.05 + 1e-9,
        "{mm} vs {largest}"
    );
    let at = &by_im["0.3"];
    for (g, pp) in at {
        if *g >= largest {
            assert!(*pp <= 0.1, "P = {pp} at {g} ≥ the printed gap");
        } else if *g < largest - 1e-12 {
            assert!(*pp > 0.1, "P = {pp} at {g} below the printed gap");
        }
    }
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.path().join("fit.json")).unwrap()).unwrap();
    assert_eq!(fit["target_gap"]["empirical"].as_f64().unwrap(), largest);
    // the fragility of pounding and of B's ductility, with and without pounding, is fitted
    for (ls, model) in [
        ("pounding", "with"),
        ("pounding", "without"),
        ("ductility>4(2)", "with"),
        ("ductility>4(2)", "without"),
    ] {
        let c = fit["fits"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["limit_state"] == ls && c["model"] == model)
            .unwrap();
        let theta = c["theta"].as_f64().unwrap();
        let (lo, hi) = (
            c["theta_interval"][0].as_f64().unwrap(),
            c["theta_interval"][1].as_f64().unwrap(),
        );
        assert!(lo <= theta && theta <= hi, "{ls} {model}: {c}");
    }
}
