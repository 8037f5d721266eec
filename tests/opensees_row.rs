//! The OpenSees export and crosscheck of a row of buildings (issue 29).
//!
//! Tests that run OpenSees need python3 with openseespy (`$POUNDING_PYTHON`, else `python3`);
//! without it they fail under CI (`CI=true`) and are skipped with a printed reason elsewhere,
//! as in tests/opensees.rs. Expected values come from the pair's export (an independent path:
//! the pair's `Model` on two structures) or from the program against OpenSees at a tolerance
//! derived in the test from OpenSees' own convergence in its step; never from stored outputs.
//! Each OpenSees run is a few seconds of small shear buildings (CI time).

mod common;

use std::path::Path;
use std::process::Command;

use common::{ROW_HARMONIC, model_json, opensees_python, row_building, row_contact, row_scenario};
use pounding::input::scenario::Scenario;
use pounding::model::building::{EngineerModes, FloorDamping, Floors};
use pounding::model::structure::{FloorKind, FloorStructure, Structure};
use pounding::opensees::compare::{CrosscheckOptions, run_script};
use pounding::opensees::results::{OpenSeesResults, OsStructure};
use pounding::opensees::row::{any_script, row_script};
use pounding::opensees::row_compare::{RowOpenSeesResults, crosscheck_row, run_row_script};
use pounding::opensees::{DRIVER, ExportOptions, script};

fn run_pair(py: &str, script: &str) -> OpenSeesResults {
    let dir = tempfile::tempdir().expect("temp dir");
    run_script(py, script, dir.path(), &[]).expect("OpenSees run (pair)")
}

fn run_row(py: &str, script: &str, extra: &[&str]) -> RowOpenSeesResults {
    let dir = tempfile::tempdir().expect("temp dir");
    let extra: Vec<String> = extra.iter().map(|s| s.to_string()).collect();
    run_row_script(py, script, dir.path(), &extra).expect("OpenSees run (row)")
}

/// A row of three shear buildings A (4 storeys), B (5), C (3) under the harmonic motion:
/// A–B in Hertz contact at 14 m (gap `gap_ab`), B–C at 10.5 m (gap `gap_bc`).
fn three(gap_ab: f64, gap_bc: f64, duration: f64) -> Scenario {
    row_scenario(&format!(
        "title = \"three\"\n{}{}{}{}{}{ROW_HARMONIC}[solver]\nmethod = \"adaptive\"\n\
         dt = 0.001\nduration = {duration}\n",
        row_building("A", 4, 1.5e8),
        row_building("B", 5, 1.0e8),
        row_building("C", 3, 2.0e8),
        row_contact("A", "B", 14.0, gap_ab),
        row_contact("B", "C", 10.5, gap_bc),
    ))
}

/// |a − b| ≤ tol · max(|a|, |b|), with a message (and the difference printed).
fn close(what: &str, a: f64, b: f64, tol: f64) {
    let scale = a.abs().max(b.abs());
    eprintln!(
        "{what}: {a:e} vs {b:e}, {:.1e}",
        (a - b).abs() / scale.max(f64::MIN_POSITIVE)
    );
    assert!(
        (a - b).abs() <= tol * scale,
        "{what}: {a:e} vs {b:e} (relative {:e} > {tol:e})",
        (a - b).abs() / scale.max(f64::MIN_POSITIVE)
    );
}

/// A structure's peaks at every tracked height and its storeys, with and without contact.
fn structure_numbers(s: &OsStructure) -> Vec<(String, f64)> {
    let mut v = Vec::new();
    for h in &s.heights {
        v.push((format!("w at {} m", h.height), h.peak_displacement.unwrap()));
        v.push((
            format!("w at {} m free", h.height),
            h.peak_displacement_no_contact.unwrap(),
        ));
    }
    for (j, st) in s.storeys.iter().enumerate() {
        v.push((format!("drift {j}"), st.peak_drift.unwrap()));
        v.push((format!("drift {j} free"), st.peak_drift_no_contact.unwrap()));
        v.push((format!("storey force {j}"), st.peak_force.unwrap()));
    }
    v
}

/// A row of three whose second gap (B–C, 10 m, the largest a gap may be) never closes is, in
/// OpenSees, the pair A–B plus a building C that touches nothing: its first pair's numbers
/// (A's and B's peaks at every floor and every storey, the pair's peak force, penetration,
/// impacts, contact time, required gap) are those of the pair's own export with the same step.
/// The two models differ only in C's equations in the system (numbering, the eigen-solution
/// that assigns modal damping): the numbers agree to Newton's tolerance (1e-10 m on the
/// increment against peaks of centimetres, ~1e-8; measured: 1.4e-9 at most, the peak force
/// after 2 s of impacts); 1e-7 leaves room for that and catches any real difference (a wrong
/// node, a missing load or damping on a structure moves the peaks by percents).
#[test]
fn a_row_whose_second_gap_never_closes_gives_the_pairs_numbers() {
    let Some(py) = opensees_python() else { return };
    let row = three(0.005, 10.0, 2.0);
    let opts = ExportOptions {
        dt: 5e-4,
        ..ExportOptions::default()
    };
    let r = run_row(
        &py,
        &row_script(&row, &opts, "row").expect("row export"),
        &[],
    );
    let p = run_pair(
        &py,
        &script(&row.pair(0), &opts, "pair").expect("pair export"),
    );
    let tol = 1e-7;
    for s in 0..2 {
        let (a, b) = (
            structure_numbers(&r.structures[s]),
            structure_numbers(&p.structures[s]),
        );
        assert_eq!(a.len(), b.len());
        for ((q, x), (_, y)) in a.iter().zip(&b) {
            close(&format!("structure {s}: {q}"), *x, *y, tol);
        }
    }
    // A's headline height is the pair's main level in both
    close(
        "A's headline peak",
        r.structures[0].peak_displacement.unwrap(),
        p.structures[0].peak_displacement.unwrap(),
        tol,
    );
    let (rp, pc) = (&r.pairs[0], p.contact.as_ref().expect("contact run"));
    let rc = rp.contact.as_ref().expect("contact run");
    assert!(pc.impacts > 0, "the first pair must pound");
    assert_eq!(rc.impacts, pc.impacts);
    close("peak force", rc.peak_force, pc.peak_force, tol);
    close("penetration", rc.max_penetration, pc.max_penetration, tol);
    close("contact time", rc.contact_time, pc.contact_time, tol);
    close(
        "required gap",
        rp.separation.time_history.unwrap(),
        p.separation.time_history.unwrap(),
        tol,
    );
    assert_eq!(rp.between, ["A".to_string(), "B".to_string()]);
    // the second pair never touches
    let second = r.pairs[1].contact.as_ref().expect("contact run");
    assert_eq!((second.impacts, second.peak_force), (0, 0.0));
    assert_eq!(r.pairs[1].between, ["B".to_string(), "C".to_string()]);
}

/// A row of three small shear buildings, both pairs pounding (Hertz): OpenSees and the
/// program agree per structure (peaks at the headline height and every floor, every storey)
/// and per pair (peak force at its level, required separation).
///
/// The tolerance comes from OpenSees' convergence in its step: the shear buildings are the
/// program's own model (no discretisation in space, so nothing to converge in elements), and
/// Newmark's error is O(dt²), so the error of the run at dt = 2.5e-4 s is estimated by
/// Richardson as |Q(dt) − Q(2dt)|/3. Each quantity must agree within three times that estimate
/// plus 0.3 % (the program runs `adaptive` at its default tolerance, and both take the peak
/// force at discrete instants: OpenSees at step ends, a contact of ~10 ms sampled every
/// 0.25 ms misses its crest by ≲ (π·0.025)²/2 ≈ 0.3 %).
#[test]
fn a_row_of_three_shear_buildings_agrees_with_opensees() {
    let Some(py) = opensees_python() else { return };
    let sc = three(0.004, 0.004, 3.0);
    let coarse = row_script(
        &sc,
        &ExportOptions {
            dt: 5e-4,
            ..ExportOptions::default()
        },
        "three",
    )
    .expect("export");
    let c = crosscheck_row(&sc, "three", &CrosscheckOptions::default(), &py).expect("crosscheck");
    eprintln!("{}", c.table());
    let fine = &c.opensees;
    assert_eq!(fine.dt, 2.5e-4);
    let half = run_row(&py, &coarse, &[]);
    // the same quantities at 2·dt, in the order of the crosscheck's rows
    let again = pounding::opensees::row_compare::row_rows(&c.program, &half);
    assert_eq!(again.len(), c.rows.len());
    let mut worst: f64 = 0.0;
    for (r, h) in c.rows.iter().zip(&again) {
        let q = &r.quantity;
        if !(q.contains("peak") || q.contains(" at ") || q.contains("separation")) {
            continue;
        }
        let (o, o2) = (
            r.opensees.expect("both runs"),
            h.opensees.expect("both runs"),
        );
        let estimate = (o - o2).abs() / 3.0;
        let allowed = 3.0 * estimate + 3e-3 * r.program.abs();
        let d = (o - r.program).abs();
        worst = worst.max(d / r.program.abs());
        assert!(
            d <= allowed,
            "{q}: program {:e}, OpenSees {o:e} (at 2dt {o2:e}): {d:e} > {allowed:e}",
            r.program
        );
    }
    eprintln!("largest relative difference {worst:.2e}");
    for (p, op) in c.program.pairs.iter().zip(&c.opensees.pairs) {
        let oc = op.contact.as_ref().expect("contact run");
        assert!(p.contact.impacts > 0 && oc.impacts > 0, "both pairs pound");
        // impacts follow the sequence of impacts: within one
        assert!(p.contact.impacts.abs_diff(oc.impacts as usize) <= 1);
    }
}

/// Every bundled pair example's script is the pair's export, byte for byte: what `pounding
/// export opensees` writes (and [`any_script`]) is [`script`], whose text is the pair's header,
/// `MODEL` and the pair's driver whole — none of the row's driver or keys.
#[test]
fn a_pairs_script_is_the_pair_export_on_every_bundled_pair() {
    let mut pairs = 0;
    for entry in std::fs::read_dir("examples").expect("examples") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let Ok(sc) = Scenario::from_file(&path) else {
            continue; // a sweep file
        };
        if sc.is_row() || sc.suite.is_some() {
            continue;
        }
        let name = path.display().to_string();
        let Ok(pair) = script(&sc, &ExportOptions::default(), &name) else {
            continue; // refused alike below (modal-csv: given by modes)
        };
        pairs += 1;
        let any = any_script(&sc, &ExportOptions::default(), &name).expect("export");
        assert_eq!(any, pair, "{name}");
        let out = Command::new(env!("CARGO_BIN_EXE_pounding"))
            .args(["export", "opensees"])
            .arg(&path)
            .output()
            .expect("run");
        assert!(out.status.success(), "{name}");
        assert!(
            out.stdout == pair.as_bytes(),
            "{name}: the CLI's script differs"
        );
        assert!(pair.ends_with(DRIVER), "{name}");
        assert!(!pair.contains("RowModel") && !pair.contains("row_main"));
        let m = model_json(&pair);
        assert!(m.get("pairs").is_none() && m["levels"][0].get("pair").is_none());
    }
    assert!(pairs >= 10, "{pairs} pair examples");
}

/// The row's script: every structure once (row order), every pair's levels with their pair,
/// the pair's driver followed by the row driver; the CLI writes it for a row (no longer
/// refused), and a pair that cannot be exported is refused naming `contact[P]`, a structure
/// that cannot be (given by its modes), naming it.
#[test]
fn a_rows_export_holds_every_structure_and_pair_and_refusals_name_the_key() {
    let sc = Scenario::from_file(Path::new("examples/row-four-buildings.toml")).expect("row");
    let text = row_script(&sc, &ExportOptions::default(), "row4").expect("export");
    let m = model_json(&text);
    let names: Vec<&str> = (m["structures"].as_array().unwrap().iter())
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["A3", "B8", "C5", "D12"]);
    let pairs: Vec<u64> = (m["levels"].as_array().unwrap().iter())
        .map(|l| l["pair"].as_u64().unwrap())
        .collect();
    assert_eq!(pairs, [0, 0, 1, 1, 2, 2]);
    assert_eq!(m["pairs"][2]["between"][1], "D12");
    assert_eq!(m["levels"][0]["material"]["type"], "JankowskiImpact");
    assert!(m["structures"][1]["bouc_wen"].is_array());
    assert_eq!(text.matches("class Model:").count(), 1);
    assert!(text.contains("class RowModel(Model):"));
    assert!(text.ends_with("    row_main()\n"));
    assert!(!text.contains("\nif __name__ == \"__main__\":\n    main()\n"));
    assert!(!text.contains("UniformExcitation\","));

    let dir = tempfile::tempdir().expect("dir");
    let out_file = dir.path().join("row.py");
    let out = Command::new(env!("CARGO_BIN_EXE_pounding"))
        .args([
            "export",
            "opensees",
            "examples/row-four-buildings.toml",
            "-o",
        ])
        .arg(&out_file)
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        std::fs::read_to_string(&out_file)
            .expect("written")
            .contains("row_main()")
    );

    // the second pair's law has no OpenSees material
    let raw = std::fs::read_to_string("examples/row-four-buildings.toml").expect("read");
    let stereo = raw.replacen(
        "between = [\"B8\", \"C5\"]\nlaw = \"jankowski\"\nstiffness = 2.75e9\n",
        "between = [\"B8\", \"C5\"]\nlaw = \"stereomechanical\"\n",
        1,
    );
    assert_ne!(stereo, raw);
    let sc = Scenario::from_toml(&stereo, "s.toml", Path::new("examples")).expect("valid");
    let err = row_script(&sc, &ExportOptions::default(), "s").expect_err("refused");
    let msg = err.to_string();
    assert!(
        msg.contains("contact[2]") && msg.contains("`stereomechanical`"),
        "{msg}"
    );
    assert!(msg.contains("\"B8\" and \"C5\""), "{msg}");
    // a building given by its modes (OpenSees needs stiffnesses): refused naming it
    let mut sc = Scenario::from_file(Path::new("examples/row-four-buildings.toml")).expect("row");
    let heights = vec![3.5, 7.0, 10.5, 14.0, 17.5];
    let modal = EngineerModes {
        floors: Floors {
            masses: vec![2.2e5; heights.len()],
            heights: heights.clone(),
        },
        periods: vec![0.6],
        shapes: vec![heights.iter().map(|h| h / 17.5).collect()],
        modes: 1,
        damping: FloorDamping::Modal(vec![0.05]),
    };
    sc.structures[2] = Structure::Floors(Box::new(
        FloorStructure::new("C5 by modes".into(), FloorKind::Modal(modal)).expect("modes"),
    ));
    let msg = row_script(&sc, &ExportOptions::default(), "m")
        .expect_err("given by modes")
        .to_string();
    assert!(
        msg.contains("`C5 by modes`") && msg.contains("periods and mode shapes"),
        "{msg}"
    );
    // options out of range, as for a pair
    let sc = Scenario::from_file(Path::new("examples/row-four-buildings.toml")).expect("row");
    let bad = ExportOptions {
        elements: 0,
        ..ExportOptions::default()
    };
    assert!(
        row_script(&sc, &bad, "x")
            .unwrap_err()
            .to_string()
            .contains("--elements")
    );
}
