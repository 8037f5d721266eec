//! The run without contact taken from the run with contact that never touched
//! ([`free_run_of`]) and from another scenario's ([`FreeRunKey`]): the reports, every number
//! and every record of both runs, are bit-identical to integrating the run without contact.
//! Reports are compared by their `Debug` text, which writes every f64 so that it reads back
//! exactly and tells −0.0 from 0.0 (summary.json writes them apart too).

use std::path::Path;

use super::*;

/// A pair of uniform cantilevers (the paper's case c, 3 modes, harmonic 0.65 s) for `secs`.
pub(super) fn cantilevers(method: &str, dt: f64, gap: f64, pga: f64, secs: f64) -> String {
    format!(
        r#"
title = "reuse"
[[structure]]
name = "a"
length = 10.0
mass = 2.273e6
period = 0.4203
modes = 3
damping_ratio = 0.01
[[structure]]
name = "b"
length = 10.0
mass = 2.273e6
period = 0.6004285714285714
modes = 3
damping_ratio = 0.01
[contact]
law = "hertz"
stiffness = 2.808e10
gap = {gap}
[ground_motion]
kind = "harmonic"
pga = {pga}
period = 0.65
[solver]
method = "{method}"
dt = {dt}
duration = {secs}
output_interval = 0.01
"#
    )
}

/// Two shear buildings under the bundled Loma Prieta record, storey 2 of B yielding when
/// `yielding`, two contact levels.
pub(super) fn shear(method: &str, gap: f64, yielding: bool) -> String {
    let hysteresis = if yielding {
        "hysteresis = { model = \"bouc-wen\", yield_drifts = 0.0175, post_yield_ratio = 0.05, exponent = 2.0, beta = 0.5, gamma = 0.5 }"
    } else {
        ""
    };
    format!(
        r#"
title = "reuse shear"
[[structure]]
name = "A"
kind = "shear-building"
floor_heights = [3.5, 7.0]
floor_masses = [2.0e5, 1.5e5]
storey_stiffnesses = [4.0e8, 2.5e8]
damping_ratio = 0.05
[[structure]]
name = "B"
kind = "shear-building"
storeys = 3
storey_height = 3.5
floor_mass = 2.5e5
storey_stiffness = 1.2e8
damping_ratio = 0.05
{hysteresis}
[contact]
law = "jankowski"
stiffness = 2.75e9
restitution = 0.65
[[contact.level]]
height = 7.0
gap = {gap}
[[contact.level]]
height = 3.5
gap = {gap}
[ground_motion]
kind = "record"
file = "examples/records/RSN753_LOMAP_CLS000.AT2"
scale_to_pga = 0.6
[solver]
method = "{method}"
duration = 8.0
"#
    )
}

pub(super) fn scenario(text: &str) -> Scenario {
    Scenario::from_toml(text, "reuse.toml", Path::new(env!("CARGO_MANIFEST_DIR")))
        .expect("valid scenario")
}

/// The report with the shortcut and without, for the result and with a self-check, with and
/// without the floors; `Debug` texts equal. Returns whether the result's run with contact
/// touched (impacts) and whether the shortcut applied.
fn both_ways(sc: &Scenario) -> (bool, bool) {
    for floors in [false, true] {
        for check in [false, true] {
            let run = |shortcut| {
                let (r, c) = simulate_run_reusing(sc, check, &mut NoSink, floors, None, shortcut)
                    .expect("runs");
                format!("{r:?}\n{c:?}")
            };
            let (fast, slow) = (run(true), run(false));
            let at = fast
                .bytes()
                .zip(slow.bytes())
                .position(|(x, y)| x != y)
                .unwrap_or(fast.len().min(slow.len()));
            assert!(
                fast == slow,
                "{} {:?} (check {check}, floors {floors}): the shortcut changed the report at\n{}\n{}",
                sc.title,
                sc.solver.method,
                &fast[at.saturating_sub(300)..(at + 200).min(fast.len())],
                &slow[at.saturating_sub(300)..(at + 200).min(slow.len())]
            );
        }
    }
    let system = sc.system();
    let heights: Vec<f64> = sc.contact.levels.iter().map(|l| l.height).collect();
    let pairs = vec![0; heights.len()];
    let (with, stats) = run_phase(
        &system,
        &sc.solver,
        (&heights, &pairs),
        sc.output_interval,
        &mut NoSink,
        Phase::WithContact,
        None,
    )
    .expect("runs");
    (
        !with.impacts.is_empty(),
        free_run_of(sc, &stats, &with).is_some(),
    )
}

/// Elastic cantilevers, every method, impacts (gap 12.7 mm) and none (gap 5 m): the reports
/// match both ways; the shortcut serves exact-modal without impacts, never the other methods
/// (see [`free_run_of`]) nor a run with impacts.
#[test]
fn shortcut_is_bit_identical_on_cantilevers() {
    for (method, dt) in [("exact-modal", 0.01), ("adaptive", 0.005), ("rk4", 0.002)] {
        for (gap, touches) in [(0.0127, true), (5.0, false)] {
            let sc = scenario(&cantilevers(method, dt, gap, 0.6, 3.0));
            let (impacts, served) = both_ways(&sc);
            assert_eq!(impacts, touches, "{method} gap {gap}");
            assert_eq!(
                served,
                !touches && method == "exact-modal",
                "{method} gap {gap}"
            );
        }
    }
}

/// A gap a hair above and below the largest closing of the run without contact (1e-9 and
/// 1e-6 of it): where the sampled closing cannot say whether the contact run touches, the
/// integrator's counters do; the reports match both ways either way (with `adaptive` they
/// would not if it were served: its energy tallies differ in the last digits here).
#[test]
fn shortcut_is_bit_identical_at_near_misses() {
    for (method, dt) in [("exact-modal", 0.01), ("adaptive", 0.005)] {
        let free = scenario(&cantilevers(method, dt, 0.5, 0.3, 3.0));
        let closing = simulate(&free).expect("runs").without_contact.max_closing;
        assert!(closing > 0.0);
        for f in [1.0 + 1e-9, 1.0 + 1e-6, 1.0 - 1e-9, 1.0 - 1e-6] {
            let sc = scenario(&cantilevers(method, dt, closing * f, 0.3, 3.0));
            let (impacts, served) = both_ways(&sc);
            assert!(!(impacts && served), "{method} gap × {f}");
        }
    }
}

/// Shear buildings under a record, two levels: elastic (exact-modal, adaptive) and with
/// yielding storeys (never served: their sub-steps evaluate the contact unseen).
#[test]
fn shortcut_is_bit_identical_on_shear_buildings_and_yielding_storeys() {
    for method in ["exact-modal", "adaptive"] {
        for yielding in [false, true] {
            for (gap, touches) in [(0.005, true), (2.0, false)] {
                let sc = scenario(&shear(method, gap, yielding));
                let (impacts, served) = both_ways(&sc);
                assert_eq!(impacts, touches, "{method} yielding {yielding} gap {gap}");
                let em = method == "exact-modal";
                assert_eq!(
                    served,
                    !touches && !yielding && em,
                    "{method} {yielding} {gap}"
                );
            }
        }
    }
}

/// A scenario that differs only in its contact (gap, stiffness, law, restitution) has the
/// same [`FreeRunKey`], and its report from the other's runs without contact is bit-identical
/// to its own; a different structure, motion, solver or level height gives another key.
#[test]
fn free_runs_of_another_scenario_give_the_same_report() {
    for method in ["exact-modal", "adaptive", "rk4"] {
        for check in [false, true] {
            for floors in [false, true] {
                let dt = if method == "rk4" { 0.002 } else { 0.01 };
                let a = scenario(&cantilevers(method, dt, 0.0127, 0.6, 2.0));
                let b_text = cantilevers(method, dt, 0.02, 0.6, 2.0)
                    .replace("2.808e10", "1.0e10")
                    .replace("\"hertz\"", "\"hertzdamp\"\nrestitution = 0.7");
                let b = scenario(&b_text);
                let ka = FreeRunKey::of(&a, check, floors).expect("a pair");
                let kb = FreeRunKey::of(&b, check, floors).expect("a pair");
                assert!(ka == kb && ka.hash == kb.hash, "{method}");
                let (_, free_a) = simulate_reusing(&a, check, floors, None).expect("runs");
                let (own, free_b) = simulate_reusing(&b, check, floors, None).expect("runs");
                let (reused, again) =
                    simulate_reusing(&b, check, floors, Some(&free_a)).expect("runs");
                assert_eq!(
                    format!("{own:?}"),
                    format!("{reused:?}"),
                    "{method} {check}"
                );
                assert_eq!(format!("{free_b:?}"), format!("{again:?}"));
                assert_eq!(check && method == "rk4", free_a.check.is_some());
            }
        }
    }
    let base = cantilevers("exact-modal", 0.01, 0.0127, 0.6, 2.0);
    let key = |t: &str| FreeRunKey::of(&scenario(t), false, false).expect("a pair");
    let k0 = key(&base);
    assert!(k0 != FreeRunKey::of(&scenario(&base), true, false).expect("a pair"));
    assert!(k0 != FreeRunKey::of(&scenario(&base), false, true).expect("a pair"));
    for other in [
        base.replace("period = 0.4203", "period = 0.42"),
        base.replace("pga = 0.6", "pga = 0.61"),
        base.replace("dt = 0.01", "dt = 0.005"),
        base.replace("output_interval = 0.01", "output_interval = 0.02"),
        base.replace("gap = 0.0127", "gap = 0.0127\nheight = 9.0"),
    ] {
        assert!(k0 != key(&other), "{other}");
    }
    // a record by its samples: the same file at another scale is another motion
    let r1 = key(&shear("exact-modal", 0.02, false));
    let r2 = key(&shear("exact-modal", 0.03, false));
    let r3 =
        key(&shear("exact-modal", 0.02, false).replace("scale_to_pga = 0.6", "scale_to_pga = 0.5"));
    assert!(r1 == r2 && r1 != r3);
}

/// The self-check's run with contact of `sc` (rtol/100, or dt/√10 for `rk4`), integrated, with
/// the floors, as `simulate_run_reusing` integrates it when it does; and the result's report
/// with its own check (the shortcut on).
fn check_run_and_result(sc: &Scenario) -> (Report, Report) {
    let (result, _) = simulate_run_reusing(sc, true, &mut NoSink, true, None, true).expect("runs");
    let mut tight = sc.clone();
    tight.solver = accuracy::tightened(&sc.solver);
    let check = simulate_phases(&tight, &mut NoSink, true, true, None, false).expect("runs");
    (result, check)
}

/// A run with contact that never touched (`exact-modal`, elastic) read no tolerance, so its
/// self-check's run would repeat it: here that run is integrated anyway and its record (peaks,
/// levels, floors, history, energy) is the run's bit for bit (`Debug` texts), its numbers
/// without contact are the run's, and the check the result carries — taken from the run
/// itself — says converged with every change exactly 0. Where the check run must be
/// integrated it differs from the run: impacts (the contact steps follow rtol), `rk4` without
/// impacts (dt/√10 changes every step), and it is not taken from the run for `adaptive`
/// (a collocation step near a miss) nor for yielding storeys (their sub-steps follow rtol).
#[test]
fn the_check_of_a_run_that_never_touched_is_the_run() {
    let served = |sc: &Scenario| {
        let r = simulate(sc).expect("runs");
        reuse::untouched(sc, &r.stats, &r.with_contact)
    };
    for sc in [
        scenario(&cantilevers("exact-modal", 0.01, 5.0, 0.6, 3.0)),
        scenario(&shear("exact-modal", 2.0, false)),
    ] {
        assert!(served(&sc), "{}", sc.title);
        let (result, check) = check_run_and_result(&sc);
        assert!(result.contact.impacts == 0 && check.contact.impacts == 0);
        assert!(!result.with_contact.floors.is_empty());
        assert!(
            format!("{:?}", result.with_contact) == format!("{:?}", check.with_contact),
            "{}: the check run did not repeat the run",
            sc.title
        );
        // (the check integrated its own run without contact, which records no floors)
        let mut free = result.without_contact.clone();
        free.floors.iter_mut().for_each(Vec::clear);
        assert!(
            format!("{free:?}") == format!("{:?}", check.without_contact),
            "{}: the check's run without contact differs",
            sc.title
        );
        let a = &result.accuracy;
        assert!(a.checked && a.converged == Some(true) && a.failure.is_none());
        assert_eq!(a.max_change, Some(0.0), "{}", sc.title);
        // (the floors compared too: five quantities per structure)
        assert!(
            a.quantities
                .iter()
                .filter(|q| q.name.starts_with("floor_"))
                .count()
                == 10
        );
    }
    // must not be taken from the run: the check run differs, or may
    let touching = scenario(&cantilevers("exact-modal", 0.01, 0.0127, 0.6, 3.0));
    let rk4 = scenario(&cantilevers("rk4", 0.002, 5.0, 0.6, 3.0));
    for sc in [&touching, &rk4] {
        assert!(!served(sc), "{:?}", sc.solver.method);
        let (result, check) = check_run_and_result(sc);
        assert!(
            format!("{:?}", result.with_contact) != format!("{:?}", check.with_contact),
            "{:?}",
            sc.solver.method
        );
        assert!(result.accuracy.max_change.is_some_and(|c| c > 0.0));
    }
    assert!(!served(&scenario(&cantilevers(
        "adaptive", 0.005, 5.0, 0.6, 3.0
    ))));
    assert!(!served(&scenario(&shear("exact-modal", 2.0, true))));
}
