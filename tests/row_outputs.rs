//! The files of a row of buildings' run (issue 29): history.csv against the pair's, the force
//! columns against the impact log, the in-memory history's bound, the self-check, and what
//! `pounding run` writes for a row.

mod common;
use common::{
    ROW_HARMONIC as HARMONIC, row_both_pounding, row_flexible_end, row_scenario as scenario,
};

use std::path::{Path, PathBuf};

use pounding::analysis::simulate::{
    RunCapture, simulate_row_checked, simulate_row_streaming, simulate_streaming,
};
use pounding::input::scenario::Scenario;
use pounding::output::writer::RunWriter;
use pounding::recording::history::{MAX_KEPT_SAMPLES, sample_count};

fn tmp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("pounding-row-outputs-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// A CSV file as its header and its rows of fields (text, as written).
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (head, rows)
}

fn column<'a>(head: &[String], rows: &'a [Vec<String>], name: &str) -> Vec<&'a str> {
    let j = head
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {head:?}"));
    rows.iter().map(|r| r[j].as_str()).collect()
}

fn numbers(col: &[&str]) -> Vec<f64> {
    col.iter().map(|x| x.parse().unwrap()).collect()
}

/// Write a row's run as `pounding run` does (no pictures, no self-check).
fn write_row_run(dir: &Path, sc: &Scenario) -> pounding::analysis::simulate::RowReport {
    let mut w = RunWriter::for_scenario(dir, sc).unwrap();
    let r = simulate_row_streaming(sc, false, &mut w).unwrap();
    w.finish(sc, &r, None).unwrap();
    r
}

/// A row of three (A 4 storeys, B 5, C 3) whose second gap (B–C, 10 m) never closes: B's
/// highest contact level is the pair A–B's (14 m), so B's headline height is the pair's main
/// height and history.csv's `w_A`, `w_B`, `force_A_B_1` and their `_free` columns are the
/// pair's `w1`, `w2`, `force`, `w1_free`, `w2_free` to the last digit (the same arithmetic:
/// the row's states of A and B are the pair's bit for bit, tests/rows.rs, and the sampler
/// interpolates as the recorder does). The third building's column is checked against its own
/// floor history in floors.csv at the same height (the same state and Hermite sampling,
/// formed by another code path: equal to round-off).
#[test]
fn history_csv_of_a_row_whose_second_gap_never_closes_is_the_pairs() {
    let row = scenario(&format!(
        "{}{HARMONIC}[solver]\nmethod = \"exact-modal\"\ndt = 0.002\nduration = 6.0\n",
        row_flexible_end(0.01, 10.0),
    ));
    let pair = row.pair(0);
    let (dr, dp) = (tmp("row3"), tmp("pair"));
    let r = write_row_run(&dr, &row);
    let mut w = RunWriter::for_scenario(&dp, &pair).unwrap();
    let p = simulate_streaming(&pair, false, &mut w).unwrap();
    w.finish(&pair, &p, None).unwrap();
    assert!(p.contact.impacts > 0, "the test needs pounding in the pair");
    assert_eq!(r.pairs[1].contact.impacts, 0);

    let (hr, rr) = read_csv(&dr.join("history.csv"));
    let (hp, rp) = read_csv(&dp.join("history.csv"));
    assert_eq!(
        hr,
        [
            "t",
            "w_A",
            "w_B",
            "w_C",
            "force_A_B_1",
            "force_B_C_1",
            "w_A_free",
            "w_B_free",
            "w_C_free"
        ]
    );
    assert_eq!(rr.len(), rp.len());
    assert_eq!(
        rr.len() as u64,
        sample_count(row.output_interval, row.solver.duration)
    );
    for (a, b) in [
        ("t", "t"),
        ("w_A", "w1"),
        ("w_B", "w2"),
        ("force_A_B_1", "force"),
        ("w_A_free", "w1_free"),
        ("w_B_free", "w2_free"),
    ] {
        assert_eq!(
            column(&hr, &rr, a),
            column(&hp, &rp, b),
            "{a} vs the pair's {b}"
        );
    }
    assert!(column(&hr, &rr, "force_B_C_1").iter().all(|f| *f == "0.0"));
    // C at its headline height 10.5 m (its top floor) against floors.csv's w_C_10.5
    let (hf, rf) = read_csv(&dr.join("floors.csv"));
    assert_eq!(rf.len(), rr.len());
    for (a, b) in [("w_C", "w_C_10.5"), ("w_C_free", "w_C_10.5_free")] {
        let (x, y) = (numbers(&column(&hr, &rr, a)), numbers(&column(&hf, &rf, b)));
        let peak = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(peak > 1e-3, "C moves");
        for (x, y) in x.iter().zip(&y) {
            // (mode shapes at a floor from two code paths: a few ulps of the peak)
            assert!((x - y).abs() <= 1e-12 * peak, "{a}: {x} vs {y}");
        }
    }
    // a row's floors.csv names each building's stations
    assert!(hf.iter().any(|h| h == "a_B_17.5_free"));
    let _ = std::fs::remove_dir_all(&dr);
    let _ = std::fs::remove_dir_all(&dp);
}

/// The force columns against the impact log, pair by pair: with the history sampled every
/// 0.1 ms, the trapezoid rule over the written rows gives each pair's total impulse Σ ∫F dt of
/// impacts.csv (the tallies' exact integral of the force). The written force is linear between
/// the integrator's observations and the samples are 0.1 ms apart, while these Hertz impacts
/// last 25 ms and more: the trapezoid's error on a smooth pulse is of order (Δt/T)² ≈ 2e-5,
/// and the interpolation between contact steps and the onset and release kinks
/// (F ∝ δ^{3/2}) add O(h/T) per impact; 1 % bounds it (measured: 0.12 % on both pairs). The
/// gaps differ (4 mm, 6 mm) and so do the pairs' impulses (5.9 and 3.2 MN·s): a column under
/// the wrong pair's name would fail. The largest sampled force of each level cannot exceed
/// the level's located peak (the samples interpolate linearly between observed forces, each
/// at most the peak) and, sampled this finely, comes within 2 % of it (a pulse of T ≥ 25 ms
/// around its peak, F ≈ F_max(1 − c(t − t*)²) with c ≈ 10/T²: 0.05 ms off the peak is
/// < 0.01 %; 2 % leaves room for the linear interpolation between contact steps; measured
/// 0.05 %).
#[test]
fn force_columns_integrate_to_the_impulses_of_each_pair() {
    let row = scenario(&format!(
        "{}{HARMONIC}[solver]\nmethod = \"exact-modal\"\ndt = 0.002\nduration = 5.0\n\
         output_interval = 1e-4\n",
        row_both_pounding(),
    ));
    let d = tmp("impulse");
    let r = write_row_run(&d, &row);
    let (h, rows) = read_csv(&d.join("history.csv"));
    let t = numbers(&column(&h, &rows, "t"));
    let (hi, ri) = read_csv(&d.join("impacts.csv"));
    assert_eq!(
        hi,
        [
            "pair",
            "left",
            "right",
            "level",
            "height",
            "start",
            "end",
            "duration",
            "peak_force",
            "impulse",
            "max_penetration",
            "approach_speed"
        ]
    );
    let mut totals = Vec::new();
    for (p, name) in [(1, "force_A_B_1"), (2, "force_B_C_1")] {
        let f = numbers(&column(&h, &rows, name));
        let trapezoid: f64 = (1..t.len())
            .map(|i| 0.5 * (f[i] + f[i - 1]) * (t[i] - t[i - 1]))
            .sum();
        let log: Vec<&Vec<String>> = ri.iter().filter(|x| x[0] == p.to_string()).collect();
        assert!(!log.is_empty(), "pair {p} pounds");
        let impulse: f64 = log.iter().map(|x| x[9].parse::<f64>().unwrap()).sum();
        let peak = log
            .iter()
            .map(|x| x[8].parse::<f64>().unwrap())
            .fold(0.0, f64::max);
        let rel = (trapezoid - impulse).abs() / impulse;
        assert!(
            rel < 0.01,
            "{name}: ∫F dt {trapezoid} vs Σ impulses {impulse} ({rel:e})"
        );
        let sampled = f.iter().copied().fold(0.0, f64::max);
        assert!(
            sampled <= peak * (1.0 + 1e-12) && sampled >= 0.98 * peak,
            "{name}: largest sample {sampled} vs located peak {peak}"
        );
        assert_eq!(peak, r.pairs[p - 1].contact.peak_force);
        totals.push(impulse);
    }
    assert!(
        (totals[0] - totals[1]).abs() > 0.1 * totals[0].max(totals[1]),
        "the two pairs' impulses differ: {totals:?}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Memory does not grow with the duration: a row run of more samples than the in-memory
/// bound keeps at most [`MAX_KEPT_SAMPLES`] rows (a min/max envelope) while history.csv has
/// every sample; the envelope keeps every column's extremes exactly (the largest and smallest
/// sample of each column in the file are in memory), and the captured rows (the Python
/// package's) are the file's.
#[test]
fn a_long_row_history_is_streamed_and_bounded_in_memory() {
    let row = scenario(&format!(
        "{}{HARMONIC}[solver]\nmethod = \"exact-modal\"\ndt = 0.002\nduration = 3.0\n\
         output_interval = 1e-4\n",
        row_both_pounding(),
    ));
    let n = sample_count(row.output_interval, row.solver.duration) as usize;
    assert!(n > MAX_KEPT_SAMPLES);
    let d = tmp("long");
    let r = write_row_run(&d, &row);
    assert!(r.history.stride > 1);
    assert!(r.history.t.len() <= MAX_KEPT_SAMPLES);
    let (h, rows) = read_csv(&d.join("history.csv"));
    assert_eq!(rows.len(), n);
    for (i, name) in ["w_A", "w_B", "w_C"].iter().enumerate() {
        let file = numbers(&column(&h, &rows, name));
        let kept = &r.history.structures[i];
        let max = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!(max(&file), max(kept), "{name}");
        assert_eq!(min(&file), min(kept), "{name}");
        // the headline peak is at least every sample (it is refined between observations)
        let peak = r.structures[i].peak_displacement;
        assert!(max(&file).max(-min(&file)) <= peak, "{name}");
    }
    // the same run captured and replayed into a writer gives the same file, byte for byte
    let mut cap = RunCapture::new();
    let again = simulate_row_streaming(&row, false, &mut cap).unwrap();
    let d2 = tmp("long-replay");
    pounding::output::writer::write_run(&d2, &row, &again, &cap, None).unwrap();
    for f in ["history.csv", "floors.csv", "impacts.csv", "summary.json"] {
        assert_eq!(
            std::fs::read(d.join(f)).unwrap(),
            std::fs::read(d2.join(f)).unwrap(),
            "{f}"
        );
    }
    let _ = std::fs::remove_dir_all(&d);
    let _ = std::fs::remove_dir_all(&d2);
}

/// The self-check of a row flags a deliberately under-resolved run: `rk4` at dt = 6 ms (within
/// its stability limit, but coarse against these ~5 ms Hertz impacts) against its rerun at
/// dt/√10 moves both pairs' peak forces by more than 1 % (measured 1.4 % and 1.8 %); the
/// warning is a pair's ("self-check NOT converged", the quantities named after their pair,
/// the setting to tighten). The same row at dt = 1 ms converges (largest change 0.01 %).
#[test]
fn the_self_check_flags_an_under_resolved_row() {
    let text = |dt: f64| {
        format!(
            "{}{HARMONIC}[solver]\nmethod = \"rk4\"\ndt = {dt}\nduration = 5.0\n",
            row_both_pounding(),
        )
    };
    let coarse = scenario(&text(0.006));
    let r = simulate_row_checked(&coarse, true).unwrap();
    assert!(r.accuracy.checked);
    assert_eq!(r.accuracy.converged, Some(false), "{:#?}", r.accuracy);
    let moved: Vec<&str> = r.accuracy.exceeded().map(|q| q.name.as_str()).collect();
    assert!(moved.contains(&"peak_force_A_B"), "{moved:?}");
    let w = r
        .warnings
        .iter()
        .find(|w| w.starts_with("self-check NOT converged"))
        .expect("the warning");
    assert!(w.contains("[solver] dt"), "{w}");
    let first = r.accuracy.exceeded().next().unwrap();
    assert!(w.contains(&first.label), "{w}");
    // every structure and every pair is checked
    for name in [
        "peak_displacement_A",
        "peak_displacement_no_contact_C",
        "peak_force_A_B",
        "impacts_B_C",
        "sep_time_history_B_C",
    ] {
        assert!(
            r.accuracy.quantities.iter().any(|q| q.name == name),
            "{name}"
        );
    }
    let fine = simulate_row_checked(&scenario(&text(0.001)), true).unwrap();
    assert_eq!(fine.accuracy.converged, Some(true), "{:#?}", fine.accuracy);
    assert!(
        !fine.warnings.iter().any(|w| w.starts_with("self-check")),
        "{:?}",
        fine.warnings
    );
    // not checked: said so
    let plain = simulate_row_checked(&coarse, false).unwrap();
    assert!(!plain.accuracy.checked);
}

/// The bundled row (examples/row-four-buildings.toml) passes its self-check, as its README
/// section says.
#[test]
fn the_bundled_row_example_is_converged() {
    let sc = Scenario::from_file(Path::new("examples/row-four-buildings.toml")).unwrap();
    let r = simulate_row_checked(&sc, true).unwrap();
    assert_eq!(r.accuracy.converged, Some(true), "{:#?}", r.accuracy);
    assert!(r.accuracy.max_change.unwrap() < 0.01);
}

/// `pounding run` on a row: every file of a pair's run (history.csv, floors.csv, impacts.csv,
/// the pictures, summary.json last, with the self-check's `accuracy`); `--no-plot` removes the
/// pictures an earlier run left.
#[test]
fn pounding_run_writes_a_rows_files() {
    let d = tmp("cli");
    std::fs::create_dir_all(&d).unwrap();
    let file = d.join("row.toml");
    std::fs::write(
        &file,
        format!(
            "title = \"three\"\n{}{HARMONIC}[solver]\nduration = 3.0\n",
            row_both_pounding(),
        ),
    )
    .unwrap();
    let out = d.join("out");
    let run = |extra: &[&str]| {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_pounding"))
            .arg("run")
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let text = run(&[]);
    assert!(text.contains("self-check: converged"), "{text}");
    for f in [
        "history.csv",
        "floors.csv",
        "impacts.csv",
        "history.png",
        "history.svg",
        "envelopes.png",
        "envelopes.svg",
        "summary.json",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let wrote = text.lines().find(|l| l.starts_with("wrote ")).unwrap();
    assert!(wrote.trim_end().ends_with("summary.json"), "{wrote}");
    let j: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(j["accuracy"]["checked"], true);
    assert_eq!(j["accuracy"]["converged"], true);
    assert!(j["accuracy"]["quantities"]["peak_force_A_B"]["change"].is_number());
    let text = run(&["--no-plot", "--no-check"]);
    assert!(text.contains("NOT self-checked"), "{text}");
    assert!(!out.join("history.png").exists());
    assert!(!out.join("envelopes.svg").exists());
    let _ = std::fs::remove_dir_all(&d);
}
