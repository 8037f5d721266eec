//! Issue 28: incremental dynamic analysis (hunt and fill) against closed forms, and a study
//! resumed from its journal or joined from its shards equal to one run at once.
//!
//! The closed form: two *elastic* 2-storey shear buildings with a linear contact law. Without
//! contact the motion is linear in the ground motion, so a record scaled to intensity x has
//! required separations r_k(x) = r_k(x₀) · x / x₀ and peak drifts likewise. "Pounding occurs"
//! (one gap g at every level) is first exceeded at x* = x₀ · g / max_k r_k(x₀), a drift ratio θ
//! at x* = x₀ · θ / drift(x₀): each record's hunt-and-fill bracket must contain x* and be
//! within the tolerance.

mod common;

use std::path::Path;

use pounding::analysis::simulate::simulate;
use pounding::input::fragility::FragilityStudy;
use pounding::study::fragility::{self, RunOutcome};

/// A record in g (one value a line, dt 0.01 s): a sine of period `t` under a half-sine
/// envelope plus a second harmonic.
fn record_text(a: f64, t: f64, n: usize) -> String {
    (0..n)
        .map(|k| {
            let x = k as f64 * 0.01;
            let env = (std::f64::consts::PI * k as f64 / (n - 1) as f64).sin();
            let w = 2.0 * std::f64::consts::PI / t;
            format!(
                "{}\n",
                a * env * ((w * x).sin() + 0.3 * (2.7 * w * x).sin())
            )
        })
        .collect()
}

const RECORDS: [(f64, f64); 4] = [(0.30, 0.50), (0.25, 0.80), (0.35, 0.35), (0.20, 1.10)];

const GAP: f64 = 0.02;

fn setup() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (i, (a, t)) in RECORDS.iter().enumerate() {
        std::fs::write(
            dir.path().join(format!("r{}.txt", i + 1)),
            record_text(*a, *t, 500),
        )
        .unwrap();
    }
    let base = format!(
        r#"title = "IDA test: elastic pair"
[[structure]]
name = "A"
kind = "shear-building"
floor_heights = [3.0, 6.0]
floor_masses = [2.0e5, 2.0e5]
storey_stiffnesses = [3.0e8, 3.0e8]
damping_ratio = 0.05
[[structure]]
name = "B"
kind = "shear-building"
floor_heights = [3.0, 6.0]
floor_masses = [2.0e5, 2.0e5]
storey_stiffnesses = [1.0e8, 1.0e8]
damping_ratio = 0.05
[contact]
law = "linear"
stiffness = 1.0e9
[[contact.level]]
height = 6.0
gap = {GAP}
[[contact.level]]
height = 3.0
gap = {GAP}
[ground_motion]
kind = "record"
file = "r1.txt"
units = "g"
dt = 0.01
"#
    );
    std::fs::write(dir.path().join("base.toml"), base).unwrap();
    dir
}

const DRIFT: f64 = 0.004;

fn study_text(ida: &str, extra: &str) -> String {
    let recs: Vec<String> = (1..=RECORDS.len())
        .map(|i| format!("  {{ file = \"r{i}.txt\", units = \"g\", dt = 0.01 }},"))
        .collect();
    format!(
        "scenario = \"base.toml\"\n[ground_motion]\nrecords = [\n{}\n]\n[intensity]\n\
         measure = \"pga\"\n[[limit_state]]\nkind = \"pounding\"\n[[limit_state]]\n\
         kind = \"drift_ratio\"\nvalue = {DRIFT}\nstructure = 2\n[fragility]\n{ida}\n\
         bootstrap = 50\n{extra}\n",
        recs.join("\n")
    )
}

fn study(dir: &Path, text: &str) -> FragilityStudy {
    FragilityStudy::from_toml(text, &dir.join("study.toml").display().to_string(), dir)
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
}

#[test]
fn hunt_and_fill_brackets_the_closed_form_capacity() {
    let d = setup();
    // (g: the IM units; tolerance 0.004 g)
    let tol = 0.004;
    let s = study(
        d.path(),
        &study_text(
            &format!(
                "ida = {{ start = 0.05, step = 0.1, growth = 0.05, tolerance = {tol}, max_runs = 40 }}"
            ),
            "gaps = [0.0, 0.01, 0.02, 0.04]\ntarget = { im = 0.33, probability = 0.25 }",
        ),
    );
    let g = 9.80665;
    let run = fragility::run(&s, Some(2)).unwrap();
    let suite = s.scenario.suite.as_ref().unwrap();
    // the closed form, record by record, from one run without contact at x₀ = 0.1 g
    let x0 = 0.1 * g;
    let mut pound_star = Vec::new();
    let mut drift_star = Vec::new();
    for r in 0..RECORDS.len() {
        let own = fragility::im::intensity(&s.measure, &suite.records[r].record);
        let sc = suite.member_scenario(&s.scenario, r, x0 / own).unwrap();
        let rep = simulate(&sc).unwrap();
        let req = rep
            .levels
            .iter()
            .map(|l| l.required_gap)
            .fold(0.0, f64::max);
        pound_star.push(x0 * GAP / req / g);
        let drift = rep.structures[1]
            .peak_drift_ratios()
            .iter()
            .map(|d| d[1] / 100.0)
            .fold(0.0, f64::max);
        drift_star.push(x0 * DRIFT / drift / g);
    }
    let curve = |l: usize, m: usize| {
        run.curves
            .iter()
            .find(|c| c.limit_state == l && c.model == m)
            .unwrap_or_else(|| panic!("curve {l} {m}"))
    };
    for (l, star) in [(0, &pound_star), (1, &drift_star)] {
        let c = curve(l, 1);
        let caps = c.capacities.as_ref().unwrap();
        for (r, (cap, x)) in caps.iter().zip(star.iter()).enumerate() {
            let (lo, hi) = (cap.lo / g, cap.hi.unwrap() / g);
            // the bracket contains x* and is within the tolerance (1e-9 g: round-off of the
            // scaling, far below the tolerance)
            assert!(
                lo <= x * (1.0 + 1e-9) && x * (1.0 - 1e-9) < hi,
                "limit state {l}, record {r}: x* = {x} not in [{lo}, {hi}]"
            );
            assert!(hi - lo <= tol * (1.0 + 1e-12), "{lo} {hi}");
        }
        // θ is the geometric mean of the bracket midpoints, each within tol/2 of x*: so
        // |ln θ − mean ln x*| ≤ tol / (2 min x*) (to first order)
        let fit = c.fit.as_ref().unwrap();
        let mean = star.iter().map(|x| x.ln()).sum::<f64>() / star.len() as f64;
        let min = star.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            (fit.theta.ln() - mean).abs() <= 0.5 * tol / min * 1.01,
            "θ {} vs exp(mean ln x*) {}",
            fit.theta,
            mean.exp()
        );
        // β: the standard deviation (n − 1) of ln x*, within what the brackets allow
        let sd = (star.iter().map(|x| (x.ln() - mean).powi(2)).sum::<f64>()
            / (star.len() - 1) as f64)
            .sqrt();
        assert!(
            (fit.beta - sd).abs() <= tol / min * 1.01,
            "β {} vs {sd}",
            fit.beta
        );
    }
    // with contact the pounding capacity is the same event (the runs are one until the gap
    // closes): the bracket contains x* too
    for (cap, x) in curve(0, 0)
        .capacities
        .as_ref()
        .unwrap()
        .iter()
        .zip(&pound_star)
    {
        assert!(cap.lo / g <= *x * (1.0 + 1e-9) && *x * (1.0 - 1e-9) < cap.hi.unwrap() / g);
    }
    // at most max_runs a record
    for r in 0..RECORDS.len() {
        assert!(run.record_runs(r).count() <= 40);
    }
    // the target: each record's critical gap at 0.33 g is linear in x: GAP · 0.33 / x*
    let t = run.target_gap.first().unwrap();
    let mut crit: Vec<f64> = pound_star.iter().map(|x| GAP * 0.33 / x).collect();
    crit.sort_by(|a, b| b.total_cmp(a));
    // ⌊0.25 · 4⌋ = 1: the second largest
    assert!(
        (t.empirical / crit[1] - 1.0).abs() < 1e-9,
        "{} vs {}",
        t.empirical,
        crit[1]
    );
    // P(pounding) at the hunt's intensities: the fraction of records with x* below (uniform
    // gap = the scenario's gap 0.02: column 2)
    for (j, x) in run.pounding[0].im.iter().enumerate() {
        let expect = pound_star.iter().filter(|s| *s * (1.0 + 1e-9) < *x).count() as f64
            / RECORDS.len() as f64;
        assert_eq!(run.pounding[0].p[j][2], expect, "IM {x}");
    }
    // the files: ida.csv (every run), capacities.csv (2 + 1 + 2 curves × 4 records: pounding
    // with/without, drift with/without)
    let out = d.path().join("out");
    let written = fragility::write::write(&run, &out, || {
        pounding::figures::fragility::pictures(&run, &out).unwrap()
    })
    .unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.last().unwrap(), "fit.json");
    for f in [
        "ida.csv",
        "capacities.csv",
        "ida.png",
        "fragility.png",
        "p-pounding.png",
    ] {
        assert!(names.iter().any(|n| n == f), "{f} in {names:?}");
    }
    let ida = std::fs::read_to_string(out.join("ida.csv")).unwrap();
    assert_eq!(ida.lines().count(), 1 + run.outcomes.len());
    assert!(ida.starts_with("record,file,run,im,factor,"));
    let caps = std::fs::read_to_string(out.join("capacities.csv")).unwrap();
    assert_eq!(caps.lines().count(), 1 + 4 * RECORDS.len());
}

#[test]
fn ida_keys_are_checked() {
    let d = setup();
    for (ida, key) in [
        ("ida = { step = -0.1 }", "fragility.ida.step"),
        ("ida = { max_runs = 1 }", "fragility.ida.max_runs"),
        ("ida = { tolerance = 0 }", "fragility.ida.tolerance"),
        ("ida = { stepp = 0.1 }", "stepp"),
        ("stripes = [0.1]\nida = {}", "fragility.ida"),
    ] {
        let text = study_text(ida, "");
        let e = FragilityStudy::from_toml(&text, "study.toml", d.path())
            .err()
            .unwrap_or_else(|| panic!("{ida} must be refused"))
            .to_string();
        assert!(e.contains(key) && e.contains("study.toml"), "{key}: {e}");
    }
    // the defaults, documented: 0.05 g, 0.1 g, 0.05 g, 0.01 g, 20 runs, no fill
    let s = study(d.path(), &study_text("ida = {}", ""));
    let i = s.ida.unwrap();
    let g = 9.80665;
    assert_eq!(
        (i.start, i.step, i.growth, i.tolerance, i.max_runs, i.fill),
        (0.05 * g, 0.1 * g, 0.05 * g, 0.01 * g, 20, false)
    );
}

/// The outcomes of two runs of a study, compared field by field (bit for bit).
fn same(a: &[RunOutcome], b: &[RunOutcome]) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert_eq!(x, y);
    }
}

#[test]
fn shards_joined_equal_one_run_for_stripes_and_ida() {
    let d = setup();
    for method in [
        "stripes = [0.1, 0.2, 0.3]",
        "ida = { start = 0.05, step = 0.1, tolerance = 0.01, max_runs = 12 }",
    ] {
        let s = study(d.path(), &study_text(method, ""));
        let whole = fragility::run(&s, Some(2)).unwrap();
        let out = d.path().join(format!("parts-{}", &method[..3]));
        let ims = fragility::record_ims(&s).unwrap();
        for k in 1..=3 {
            let shard = pounding::study::sweep::Shard { k, n: 3 };
            let store = fragility::journal::open(&s, &out, shard).unwrap();
            let tasks = fragility::journal::part(&s, shard);
            fragility::run_tasks(&s, &ims, &tasks, Some(1), &store).unwrap();
        }
        let joined = fragility::journal::merge(&s, std::slice::from_ref(&out)).unwrap();
        same(&whole.outcomes, &joined.outcomes);
        assert_eq!(
            fragility::write::fit_json_text(&whole),
            fragility::write::fit_json_text(&joined)
        );
        // a part missing: refused, naming it
        std::fs::remove_file(out.join("journal-shard-2-of-3.csv")).unwrap();
        let e = fragility::journal::merge(&s, &[out])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("part(s) 2 of 3 are missing"), "{e}");
    }
}

const BIN: &str = env!("CARGO_BIN_EXE_pounding");

fn pounding_cli(args: &[&str]) -> String {
    let o = std::process::Command::new(BIN).args(args).output().unwrap();
    assert!(
        o.status.success(),
        "pounding {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A study of the bundled frames (8 s of motion) under three bundled records, as an IDA.
fn frames_study(dir: &Path) -> std::path::PathBuf {
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let base = std::fs::read_to_string(ex.join("fragility-frames.toml"))
        .unwrap()
        .replace("duration = 30.0", "duration = 8.0")
        .replace(
            "file = \"records/",
            &format!("file = \"{}/records/", ex.display()),
        );
    std::fs::write(dir.join("base.toml"), base).unwrap();
    let rec = ex.join("records");
    let study = format!(
        "scenario = \"base.toml\"\n[ground_motion]\nrecords = [\n\
         {{ file = \"{r}/RSN753_LOMAP_CLS000.AT2\" }},\n\
         {{ file = \"{r}/RSN786_LOMAP_PAE055.AT2\" }},\n\
         {{ file = \"{r}/INGLEWOO.V2\", component = 1 }},\n]\n\
         [intensity]\nmeasure = \"pga\"\n[[limit_state]]\nkind = \"pounding\"\n\
         [[limit_state]]\nkind = \"ductility\"\nvalue = 2.0\nstructure = 2\n\
         [fragility]\nida = {{ start = 0.05, step = 0.1, tolerance = 0.01, max_runs = 14 }}\n\
         target = {{ im = 0.25, probability = 0.4 }}\nbootstrap = 30\n",
        r = rec.display()
    );
    let p = dir.join("study.toml");
    std::fs::write(&p, study).unwrap();
    p
}

#[test]
fn a_killed_study_resumes_to_the_tables_of_an_uninterrupted_run() {
    let d = tempfile::tempdir().unwrap();
    let study = frames_study(d.path());
    let st = study.to_str().unwrap();
    let (full, cut) = (d.path().join("full"), d.path().join("cut"));
    pounding_cli(&[
        "fragility",
        st,
        "--out",
        full.to_str().unwrap(),
        "--no-plot",
        "-q",
    ]);
    // start, wait until some runs are journaled, kill -9 (one thread: runs finish one by one)
    let journal = cut.join("journal.csv");
    common::kill_after_journal_rows(
        std::process::Command::new(BIN).args([
            "fragility",
            st,
            "--out",
            cut.to_str().unwrap(),
            "--no-plot",
            "-j",
            "1",
        ]),
        &journal,
        4,
    );
    assert!(
        !cut.join("fit.json").exists(),
        "killed too late to test resuming"
    );
    // a torn last line, as a kill in the middle of a write leaves
    let mut j = std::fs::read_to_string(&journal).unwrap();
    let before = j.lines().count() - 2;
    j.push_str("3,0,3,0.25,1.2");
    std::fs::write(&journal, j).unwrap();
    let out = pounding_cli(&["fragility", st, "--out", cut.to_str().unwrap(), "--no-plot"]);
    assert!(
        out.contains(&format!("{before} runs found")) && out.contains("1 torn or damaged"),
        "expected {before} resumed: {out}"
    );
    for f in [
        "fragility.csv",
        "p_pounding.csv",
        "ida.csv",
        "capacities.csv",
        "fit.json",
    ] {
        assert_eq!(
            std::fs::read_to_string(cut.join(f)).unwrap(),
            std::fs::read_to_string(full.join(f)).unwrap(),
            "{f}: resumed differs from an uninterrupted run"
        );
    }
    // every run journaled once
    let j = std::fs::read_to_string(&journal).unwrap();
    let mut keys: Vec<usize> = j
        .lines()
        .skip(2)
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    let n = keys.len();
    keys.sort();
    keys.dedup();
    assert_eq!(keys.len(), n);
    // a rerun computes nothing
    let out = pounding_cli(&["fragility", st, "--out", cut.to_str().unwrap(), "--no-plot"]);
    assert!(
        out.contains(&format!("{n} runs found, 0 computed")),
        "{out}"
    );
    // the CLI's parts joined by --merge: the same tables
    let parts = d.path().join("parts");
    for k in 1..=2 {
        pounding_cli(&[
            "fragility",
            st,
            "--out",
            parts.to_str().unwrap(),
            "--shard",
            &format!("{k}/2"),
        ]);
    }
    let merged = d.path().join("merged");
    pounding_cli(&[
        "fragility",
        st,
        "--merge",
        parts.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
        "--no-plot",
    ]);
    for f in ["fragility.csv", "ida.csv", "capacities.csv", "fit.json"] {
        assert_eq!(
            std::fs::read_to_string(merged.join(f)).unwrap(),
            std::fs::read_to_string(full.join(f)).unwrap(),
            "{f}: merged differs"
        );
    }
    // another study into the same directory is refused
    std::fs::write(
        &study,
        std::fs::read_to_string(&study)
            .unwrap()
            .replace("tolerance = 0.01", "tolerance = 0.02"),
    )
    .unwrap();
    let o = std::process::Command::new(BIN)
        .args(["fragility", st, "--out", cut.to_str().unwrap(), "--no-plot"])
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && e.contains("different fragility"),
        "{e}"
    );
}
