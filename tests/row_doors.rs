//! Every door for a row of buildings (issue 29, part 2b): `pounding separation`, convergence,
//! sweeps, suites and fragility on a row. Each checked against invariances: a row whose second
//! gap never closes answers, pair by pair, as the pair scenarios do; the mirror row under the
//! negated ground motion gives the same per-pair answers; bad inputs name their key.

mod common;
use common::{
    ROW_HARMONIC as HARMONIC, row_both_pounding, row_building as building, row_contact as contact,
    row_flexible_end, row_scenario as scenario,
};

use std::path::Path;

use pounding::analysis::gap_report::gap_report;
use pounding::analysis::row_separation::row_gap_report;
use pounding::model::ground_motion::{GroundMotion, Harmonic};

/// The same pair as one `[contact]` table.
fn pair_contact(h: f64, gap: f64) -> String {
    format!("[contact]\nlaw = \"hertz\"\nstiffness = 2.0e10\nheight = {h}\ngap = {gap}\n")
}

const SOLVER: &str = "[solver]\nmethod = \"exact-modal\"\ndt = 0.002\nduration = 6.0\n";
/// Every code of the scenario format, so that the codes are checked per pair too.
const CODES: &str = "[separation]\nasce7 = { cd = 5.5, ie = 1.0, r = 8, boundary = \"same-property\" }\n\
    ec8 = { q = 4, boundary = \"same-property\" }\n";

fn row_abc(gap_bc: f64) -> String {
    format!(
        "{}{HARMONIC}{SOLVER}{CODES}",
        row_flexible_end(0.01, gap_bc),
    )
}

/// `pounding separation` of a row of three is each pair's report, pair by pair, equal to the
/// report of the pair scenario written on its own (the same two buildings, contact, ground
/// motion and codes): the row's run without contact is uncoupled, so each building's response is
/// the same arithmetic as in the pair's run, to the last digit.
#[test]
fn a_rows_separation_is_each_pairs_separation() {
    for gap_bc in [10.0, 0.005] {
        let row = scenario(&row_abc(gap_bc));
        let r = row_gap_report(&row, None, None).expect("row report");
        assert_eq!(r.pairs.len(), 2);
        let ab = scenario(&format!(
            "{}{}{}{HARMONIC}{SOLVER}{CODES}",
            building("A", 4, 3.0e8),
            building("B", 5, 1.6e8),
            pair_contact(14.0, 0.01)
        ));
        let bc = scenario(&format!(
            "{}{}{}{HARMONIC}{SOLVER}{CODES}",
            building("B", 5, 1.6e8),
            building("C", 3, 1.0e8),
            pair_contact(10.5, gap_bc)
        ));
        for (p, pair) in [ab, bc].iter().enumerate() {
            let alone = gap_report(pair, None, None).expect("pair report");
            let got = &r.pairs[p].report;
            assert_eq!(
                got.levels, alone.levels,
                "pair {p}: every rule at every level"
            );
            assert_eq!(got.verdict, alone.verdict, "pair {p}: verdict");
            assert_eq!(got.periods, alone.periods);
            assert!(!got.levels[0].codes.is_empty(), "the codes are checked");
        }
        // the row's verdict is the pair verdict with the smaller margin
        let m: Vec<f64> = (r.pairs.iter())
            .map(|p| p.report.verdict.governing.as_ref().unwrap().margin)
            .collect();
        let want = if m[1] < m[0] { 1 } else { 0 };
        assert_eq!(r.verdict.pair, Some(want), "margins {m:?}");
        assert_eq!(
            r.verdict.governing.as_ref().unwrap().margin,
            m[want],
            "the governing margin"
        );
        // a 10 m gap suffices by every rule; a 5 mm one is smaller than ABS of any motion
        let insufficient_bc = r.verdict.insufficient_pairs.contains(&1);
        assert_eq!(insufficient_bc, gap_bc < 1.0, "{:?}", r.verdict);
    }
}

/// With a design spectrum as the ground motion (no time history): each pair's SRSS, CQC and
/// codes are the pair scenario's.
#[test]
fn a_rows_spectral_separation_is_each_pairs() {
    let spectrum = "[ground_motion]\nkind = \"spectrum\"\nspectrum = \"asce7\"\nsds = 1.0\nsd1 = 0.6\ntl = 8.0\n";
    let row = scenario(&format!(
        "{}{spectrum}{CODES}",
        row_flexible_end(0.01, 0.02),
    ));
    let r = row_gap_report(&row, None, None).expect("row report");
    let bc = scenario(&format!(
        "{}{}{}{spectrum}{CODES}",
        building("B", 5, 1.6e8),
        building("C", 3, 1.0e8),
        pair_contact(10.5, 0.02)
    ));
    let alone = gap_report(&bc, None, None).expect("pair report");
    let got = &r.pairs[1].report;
    assert!(got.levels[0].spectral.is_some() && got.levels[0].exact.is_none());
    assert_eq!(got.levels, alone.levels);
    assert_eq!(got.spectral_floors, alone.spectral_floors);
}

/// The mirror image: the row reversed (C–B–A) under the negated ground motion moves as the
/// mirror of the row (every displacement negated, left and right swapped), so each pair's
/// required separation by every rule is the same: the exact one is max(w_left − w_right) of
/// the same motion, and the rules are symmetric in the two structures.
#[test]
fn the_mirror_row_has_the_same_separations() {
    let row = scenario(&row_abc(0.006));
    let mut mirror = scenario(&format!(
        "{}{}{}{}{}{HARMONIC}{SOLVER}{CODES}",
        building("C", 3, 1.0e8),
        building("B", 5, 1.6e8),
        building("A", 4, 3.0e8),
        contact("C", "B", 10.5, 0.006),
        contact("B", "A", 14.0, 0.01),
    ));
    let GroundMotion::Harmonic(h) = row.ground_motion.clone() else {
        panic!("harmonic")
    };
    mirror.ground_motion = GroundMotion::Harmonic(Harmonic { pga: -h.pga, ..h });
    let (r, m) = (
        row_gap_report(&row, None, None).unwrap(),
        row_gap_report(&mirror, None, None).unwrap(),
    );
    for p in 0..2 {
        let (a, b) = (&r.pairs[p].report, &m.pairs[1 - p].report);
        assert_eq!(
            r.pairs[p].between,
            [
                m.pairs[1 - p].between[1].clone(),
                m.pairs[1 - p].between[0].clone()
            ]
        );
        for (x, y) in a.levels.iter().zip(&b.levels) {
            assert_eq!(x.rules.len(), y.rules.len());
            for (u, v) in x.rules.iter().zip(&y.rules) {
                assert_eq!(u.key, v.key);
                // the same arithmetic on negated numbers, the modal sums in another order
                // (1e-9: round-off, far below any modelling difference)
                assert!(
                    (u.required - v.required).abs() <= 1e-9 * u.required.abs().max(1e-12),
                    "pair {p} {}: {} vs {}",
                    u.key,
                    u.required,
                    v.required
                );
            }
        }
    }
    assert_eq!(r.verdict.pair.map(|p| 1 - p), m.verdict.pair);
}

/// `--code` naming a code the scenario does not give is refused for a row as for a pair.
#[test]
fn a_rows_separation_refuses_an_unknown_code() {
    let row = scenario(&row_abc(0.01));
    let e = row_gap_report(&row, None, Some(&["nbcc".to_string()]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("--code nbcc"), "{e}");
}

use pounding::analysis::simulate::simulate;
use pounding::output::run::Column;
use pounding::study::sweep::Sweep;
use pounding::study::sweep::run::compute_all;

/// A sweep over `base` (a scenario's text) with the axes `axes` (TOML of `[[axis]]` tables).
fn sweep(base: &str, axes: &str) -> Result<Sweep, String> {
    let text = format!("scenario = \"row.toml\"\n{axes}");
    Sweep::from_toml_with_base(
        &text,
        Path::new("sweep.toml"),
        Some((base, Path::new("row.toml"))),
    )
    .map_err(|e| e.to_string())
}

/// The table of every case of `sw`, by column name.
fn table(sw: &Sweep) -> Vec<(String, Column)> {
    let rows = compute_all(sw, 2, false).expect("sweep");
    let lines: Vec<&str> = rows.iter().map(|r| r.line.as_str()).collect();
    pounding::study::sweep::results::columns(sw, &lines).expect("columns")
}

fn floats<'a>(t: &'a [(String, Column)], name: &str) -> &'a [f64] {
    match t.iter().find(|(k, _)| k == name).map(|(_, c)| c) {
        Some(Column::Float(v)) => v,
        other => panic!("{name}: {other:?}"),
    }
}

fn texts<'a>(t: &'a [(String, Column)], name: &str) -> &'a [String] {
    match t.iter().find(|(k, _)| k == name).map(|(_, c)| c) {
        Some(Column::Text(v)) => v,
        other => panic!("{name}: {other:?}"),
    }
}

/// A sweep over `contact[2].gap` flips pair 2's verdict exactly at its required separation:
/// the rules' required separations come from the run without contact, which no gap changes,
/// so pair 2's gap suffices by every rule iff it is at least the largest of them, R (the
/// governing rule's at its one level), taken here from `pounding separation`'s report of the
/// row. Just below R the verdict is `false` with margin −1e-9 R, at R `true` with margin 0.
#[test]
fn a_sweep_over_a_pairs_gap_flips_its_verdict_at_its_required_separation() {
    let base = row_abc(0.02);
    let report = row_gap_report(&scenario(&base), None, None).unwrap();
    let g = report.pairs[1].report.verdict.governing.clone().unwrap();
    let r = g.required;
    let below = r * (1.0 - 1e-9);
    let sw = sweep(
        &base,
        &format!(
            "[[axis]]\nkey = \"contact[2].gap\"\nvalues = [{below:e}, {r:e}, {:e}]\n",
            2.0 * r
        ),
    )
    .unwrap();
    let t = table(&sw);
    assert_eq!(texts(&t, "status"), ["ok", "ok", "ok"]);
    assert_eq!(texts(&t, "pair2_sufficient"), ["false", "true", "true"]);
    assert_eq!(texts(&t, "pair2_governing_rule")[1], g.key);
    for (c, gap) in [below, r, 2.0 * r].into_iter().enumerate() {
        assert_eq!(
            floats(&t, "pair2_required")[c],
            r,
            "case {c}: gap-independent"
        );
        assert_eq!(floats(&t, "pair2_margin")[c], gap - r, "case {c}");
    }
    // the first pair is not touched by the second pair's gap: its required separation and
    // verdict are the same in every case, and the row is sufficient only if both pairs are
    let p1: Vec<bool> = texts(&t, "pair1_sufficient")
        .iter()
        .map(|s| s == "true")
        .collect();
    assert!(p1.iter().all(|&x| x == p1[0]));
    let row: Vec<bool> = texts(&t, "sufficient")
        .iter()
        .map(|s| s == "true")
        .collect();
    let p2: Vec<bool> = texts(&t, "pair2_sufficient")
        .iter()
        .map(|s| s == "true")
        .collect();
    for c in 0..3 {
        assert_eq!(row[c], p1[c] && p2[c], "case {c}");
    }
}

/// A sweep's case of a row whose second gap never closes: its pair 1 and structure columns
/// are those of the pair scenario of the first two buildings run alone (the same arithmetic,
/// `a_row_whose_second_gap_never_closes_is_the_pair_and_the_third_alone` in tests/rows.rs),
/// and varying the third building's stiffness (`structure[3].…`) changes neither.
#[test]
fn a_rows_sweep_row_is_the_pairs_numbers_where_the_second_gap_never_closes() {
    let base = row_abc(10.0);
    let sw = sweep(
        &base,
        "[[axis]]\nkey = \"structure[3].storey_stiffness\"\nvalues = [1.0e8, 1.4e8]\n",
    )
    .unwrap();
    let t = table(&sw);
    let ab = scenario(&format!(
        "{}{}{}{HARMONIC}{SOLVER}{CODES}",
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        pair_contact(14.0, 0.01)
    ));
    let p = simulate(&ab).unwrap();
    assert!(p.contact.impacts > 0, "the test needs pounding in the pair");
    for c in 0..2 {
        assert_eq!(floats(&t, "pair1_peak_force")[c], p.contact.peak_force);
        assert_eq!(
            floats(&t, "pair1_sep_time_history")[c],
            p.separation.time_history
        );
        assert_eq!(
            floats(&t, "structure1_peak_displacement")[c],
            p.structures[0].peak_displacement
        );
        assert_eq!(floats(&t, "pair2_impacts")[c], 0.0);
    }
    match t.iter().find(|(k, _)| k == "pair1_impacts").map(|(_, c)| c) {
        Some(Column::Float(v)) => assert!(v.iter().all(|&x| x == p.contact.impacts as f64)),
        other => panic!("{other:?}"),
    }
    // the third building's stiffness changes its own peak
    let c3 = floats(&t, "structure3_peak_displacement_no_contact");
    assert_ne!(c3[0], c3[1]);
}

/// Bad axes of a row name the axis's key and say why: a pair out of range, a structure out
/// of range, `contact.…` without its pair (ambiguous in a row), a level the pair has not.
#[test]
fn a_rows_bad_axes_name_the_key() {
    let base = row_abc(0.02);
    for (key, expect) in [
        ("contact[3].gap", "out of range"),
        ("contact[0].gap", "not a valid pair index"),
        ("structure[4].period", "3 structures"),
        ("contact.gap", "ambiguous"),
        ("contact.level[1].gap", "ambiguous"),
        ("contact[1].level[1].gap", "level"),
    ] {
        let e = sweep(
            &base,
            &format!("[[axis]]\nkey = \"{key}\"\nvalues = [0.01]\n"),
        )
        .err()
        .unwrap_or_else(|| panic!("{key} accepted"));
        assert!(e.contains("axis[1].key"), "{key}: {e}");
        assert!(e.contains(expect), "{key}: {e}");
    }
    // a pair's own scenario takes contact[1] (its one pair) and refuses contact[2]
    let pair = format!(
        "{}{}{}{HARMONIC}{SOLVER}",
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        pair_contact(14.0, 0.01)
    );
    let sw = sweep(
        &pair,
        "[[axis]]\nkey = \"contact[1].gap\"\nvalues = [0.02]\n",
    )
    .unwrap();
    assert!(sw.case_toml(0).unwrap().contains("gap = 0.02"));
    let e = sweep(
        &pair,
        "[[axis]]\nkey = \"contact[2].gap\"\nvalues = [0.02]\n",
    )
    .err()
    .unwrap();
    assert!(
        e.contains("axis[1].key") && e.contains("out of range"),
        "{e}"
    );
}

/// `pounding convergence` of a row whose second gap never closes: every run of both ladders
/// gives the first pair's peaks and force of the pair scenario's run with the same settings
/// (the same arithmetic, as `a_row_whose_second_gap_never_closes_is_the_pair_and_the_third_alone`
/// in tests/rows.rs shows for one run), the second pair's force is 0, and the row's verdict is
/// the pair's when the third building's peak converges as fast as the pair's quantities.
#[test]
fn a_rows_convergence_is_the_pairs_where_the_second_gap_never_closes() {
    use pounding::analysis::convergence::{Ladders, convergence_with};
    let row = scenario(&row_abc(10.0));
    let pair = scenario(&format!(
        "{}{}{}{HARMONIC}{SOLVER}",
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        pair_contact(14.0, 0.01)
    ));
    // short ladders: the comparison is per run
    let ladders = Ladders {
        modes: vec![2, 3, 5],
        dt_factors: vec![2.0, 1.0],
        rtols: vec![1e-7, 1e-8],
        exact_modal_rtols: vec![1e-4, 1e-6],
    };
    let r = convergence_with(&row, 0.01, &ladders, |_| {});
    let p = convergence_with(&pair, 0.01, &ladders, |_| {});
    for (a, b) in r
        .modes
        .iter()
        .chain(&r.steps)
        .zip(p.modes.iter().chain(&p.steps))
    {
        assert!(a.failure.is_none() && b.failure.is_none());
        assert_eq!(a.peaks.len(), 3);
        assert_eq!(a.forces.len(), 2);
        // not to the last digit here: with few modes the row's coupling rows are summed in
        // another order than the pair's (the dot product's partial sums), and exact-modal's
        // contact sub-steps are accepted on an error estimate over the whole row's state, so
        // the steps in contact may differ within the solver's tolerance (rtol ≤ 1e-4 in these
        // ladders); the peak force is the most sensitive (5e-7 relative seen at rtol 1e-8):
        // peaks within 1e-6 and forces within 1e-5, far below any modelling difference
        let close = |x: f64, y: f64, rel: f64| (x - y).abs() <= rel * x.abs().max(y.abs());
        let what = format!("{} modes, rtol {:?}", a.modes, a.rtol);
        assert!(
            close(a.peaks[0], b.peaks[0], 1e-6) && close(a.peaks[1], b.peaks[1], 1e-6),
            "{what}: {:?} vs {:?}, forces {:?} vs {:?}",
            a.peaks,
            b.peaks,
            a.forces,
            b.forces
        );
        assert!(
            close(a.forces[0], b.forces[0], 1e-5),
            "{what}: {:?} vs {:?}",
            a.forces,
            b.forces
        );
        assert_eq!(a.forces[1], 0.0, "the second gap never closes");
        // the changes: the pair's w1, w2, F at their places (each within the above)
        for (x, y) in [
            (a.change[0], b.change[0]),
            (a.change[1], b.change[1]),
            (a.change[3], b.change[2]),
        ] {
            assert!((x - y).abs() <= 3e-5, "{what}: change {x} vs {y}");
        }
    }
    assert!(r.modes[0].impacts > 0, "the test needs pounding");
}

/// A sweep over a row is self-checked as `pounding run` checks a row: the case's `converged`
/// and `check_max_change` are those of `simulate_row_checked` on the same scenario (an `rk4`
/// row at dt = 6 ms, which its self-check flags — its forces move by more than 1 % — and at
/// 1 ms, which passes), and `unchecked` without the check.
#[test]
fn a_rows_sweep_is_self_checked() {
    let base = format!(
        "{}{HARMONIC}[solver]\nmethod = \"rk4\"\ndt = 0.001\nduration = 5.0\n",
        row_both_pounding(),
    );
    let sw = sweep(
        &base,
        "[[axis]]\nkey = \"solver.dt\"\nvalues = [0.006, 0.001]\n",
    )
    .unwrap();
    let rows = compute_all(&sw, 2, true).expect("sweep");
    let lines: Vec<&str> = rows.iter().map(|r| r.line.as_str()).collect();
    let t = pounding::study::sweep::results::columns(&sw, &lines).expect("columns");
    assert_eq!(texts(&t, "converged"), ["false", "true"]);
    for (c, dt) in [0.006, 0.001].into_iter().enumerate() {
        let sc = scenario(&base.replace("dt = 0.001", &format!("dt = {dt}")));
        let r = pounding::analysis::simulate::simulate_row_checked(&sc, true).unwrap();
        assert_eq!(
            floats(&t, "check_max_change")[c],
            r.accuracy.max_change.unwrap(),
            "case {c}"
        );
    }
    let t = table(&sw);
    assert_eq!(texts(&t, "converged"), ["unchecked", "unchecked"]);
}
