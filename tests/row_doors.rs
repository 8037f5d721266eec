//! Every door for a row of buildings (issue 29, part 2b): `pounding separation`, convergence,
//! sweeps, suites and fragility on a row. Each checked against invariances: a row whose second
//! gap never closes answers, pair by pair, as the pair scenarios do; the mirror row under the
//! negated ground motion gives the same per-pair answers; bad inputs name their key.

use std::path::Path;

use pounding::analysis::gap_report::gap_report;
use pounding::analysis::row_separation::row_gap_report;
use pounding::input::scenario::Scenario;
use pounding::model::ground_motion::{GroundMotion, Harmonic};

fn scenario(text: &str) -> Scenario {
    Scenario::from_toml(text, "row.toml", Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// A shear building of `n` storeys of 3.5 m named `name`, all its modes kept.
fn building(name: &str, n: usize, k: f64) -> String {
    format!(
        "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
         storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\ndamping_ratio = 0.05\n\
         modes = {n}\n"
    )
}

/// A `[[contact]]` between `a` and `b` at `h` with gap `gap` (m), Hertz.
fn contact(a: &str, b: &str, h: f64, gap: f64) -> String {
    format!(
        "[[contact]]\nbetween = [\"{a}\", \"{b}\"]\nlaw = \"hertz\"\nstiffness = 2.0e10\n\
         height = {h}\ngap = {gap}\n"
    )
}

/// The same pair as one `[contact]` table.
fn pair_contact(h: f64, gap: f64) -> String {
    format!("[contact]\nlaw = \"hertz\"\nstiffness = 2.0e10\nheight = {h}\ngap = {gap}\n")
}

const HARMONIC: &str = "[ground_motion]\nkind = \"harmonic\"\npga = 0.35\nperiod = 0.8\n";
const SOLVER: &str = "[solver]\nmethod = \"exact-modal\"\ndt = 0.002\nduration = 6.0\n";
/// Every code of the scenario format, so that the codes are checked per pair too.
const CODES: &str = "[separation]\nasce7 = { cd = 5.5, ie = 1.0, r = 8, boundary = \"same-property\" }\n\
    ec8 = { q = 4, boundary = \"same-property\" }\n";

fn row_abc(gap_bc: f64) -> String {
    format!(
        "{}{}{}{}{}{HARMONIC}{SOLVER}{CODES}",
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        building("C", 3, 1.0e8),
        contact("A", "B", 14.0, 0.01),
        contact("B", "C", 10.5, gap_bc),
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
        "{}{}{}{}{}{spectrum}{CODES}",
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        building("C", 3, 1.0e8),
        contact("A", "B", 14.0, 0.01),
        contact("B", "C", 10.5, 0.02),
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
