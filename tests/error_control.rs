//! Issue 9: the default answer is right, or says that it is not. Every reference here is a
//! converged run (the same case at rtol = 1e-12, the tightest accepted, whose own error is shown
//! to be far below the tolerances asserted) or a number from an independent implementation —
//! never the program's output at the settings under test.

use std::path::Path;

use pounding::analysis::simulate::{Report, simulate};
use pounding::input::scenario::Scenario;

/// The stiff case of issue 9: T1 = 0.3 s, T2 = 0.6 s, equal masses 2.273e6 kg, L = 10 m,
/// 3 modes, ζ = 0.01, Hertz k_h = 2.808e13 N/m^1.5 (1000× the paper's), gap 12.7 mm, harmonic
/// `pga` (g) at Tg = 0.8 s. `solver` is appended to the [solver] table.
fn stiff(pga: f64, duration: f64, method: &str, dt: f64, solver: &str) -> Scenario {
    stiff_with(
        "law = \"hertz\"\nstiffness = 2.808e13",
        pga,
        duration,
        method,
        dt,
        solver,
    )
}

fn stiff_with(
    contact: &str,
    pga: f64,
    duration: f64,
    method: &str,
    dt: f64,
    solver: &str,
) -> Scenario {
    let text = format!(
        "[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.3\nmodes = 3\n\
         damping_ratio = 0.01\n[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.6\n\
         modes = 3\ndamping_ratio = 0.01\n[contact]\n{contact}\ngap = 0.0127\n\
         [ground_motion]\nkind = \"harmonic\"\npga = {pga}\nperiod = 0.8\n[solver]\n\
         method = \"{method}\"\ndt = {dt}\nduration = {duration}\n{solver}\n"
    );
    Scenario::from_toml(&text, "stiff.toml", Path::new(".")).expect("valid scenario")
}

fn run(s: &Scenario) -> Report {
    simulate(s).expect("runs")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The headline numbers the issue names: peaks with pounding, peak force, required separation
/// (time history), as (name, value).
fn headline(r: &Report) -> [(&'static str, f64); 4] {
    [
        ("peak 1", r.structures[0].peak_displacement),
        ("peak 2", r.structures[1].peak_displacement),
        ("peak force", r.contact.peak_force),
        ("separation", r.separation.time_history),
    ]
}

/// The largest relative error of the headline numbers of `r` against `reference` (printed by
/// the tests below, so that the README's tables are reproduced by `--nocapture`).
fn largest_error(r: &Report, reference: &Report) -> f64 {
    headline(r)
        .iter()
        .zip(headline(reference))
        .map(|((_, a), (_, b))| rel(*a, b))
        .fold(0.0f64, f64::max)
}

/// The stiff case over 6 s at the default tolerance is within 0.5 % of the converged run, at
/// the issue's dt = 1e-4 s and at 1e-3 s. The case is chaotic (a 1e-6 relative change of the
/// gap moves its peak force by 36 %: the largest of 54 impacts comes at 5.3 s), so this asks
/// for ~1e-10 relative accuracy of every contact step. Measured: peak force +0.15 % (dt 1e-4),
/// +0.22 % (dt 1e-3); at rtol 1e-8 it would be −2.4 %.
#[test]
fn stiff_case_at_default_tolerance_is_within_half_a_percent_of_converged() {
    let reference = run(&stiff(0.5, 6.0, "adaptive", 1e-4, "rtol = 1e-12"));
    // the reference itself: rtol 3e-12 agrees to 5e-5 (its error is far below 0.5 %)
    let check = run(&stiff(0.5, 6.0, "adaptive", 1e-4, "rtol = 3e-12"));
    for ((name, a), (_, b)) in headline(&check).iter().zip(headline(&reference)) {
        assert!(
            rel(*a, b) < 5e-5,
            "reference not converged: {name} {a} vs {b}"
        );
    }
    eprintln!(
        "stiff case 0.5 g: reference rtol 3e-12 against 1e-12 {:.2e}",
        largest_error(&check, &reference)
    );
    assert_eq!(reference.contact.impacts, 54);
    for dt in [1e-4, 1e-3] {
        let r = run(&stiff(0.5, 6.0, "adaptive", dt, ""));
        eprintln!(
            "stiff case 0.5 g: adaptive default dt {dt}: largest headline error {:.2e}, impacts {}",
            largest_error(&r, &reference),
            r.contact.impacts
        );
        for ((name, a), (_, b)) in headline(&r).iter().zip(headline(&reference)) {
            assert!(rel(*a, b) < 5e-3, "dt {dt}: {name} {a} vs converged {b}");
        }
        assert_eq!(r.contact.impacts, reference.contact.impacts, "dt {dt}");
    }
}

/// Against an independent implementation: issue 9's converged solution of this case (54
/// impacts, peak force 5.4461e8 N) was computed with g = 9.81 m/s² (docs/model.md says 9.80665), i.e.
/// PGA = 0.5 × 9.81 / 9.80665 g in the program's units. At the default tolerance the peak force is
/// within 0.5 % of it, and the converged run within 1e-4 (its five printed digits).
#[test]
fn stiff_case_matches_the_independent_converged_peak_force() {
    let pga = 0.5 * 9.81 / 9.80665;
    let independent = 5.4461e8;
    let converged = run(&stiff(pga, 6.0, "adaptive", 1e-4, "rtol = 1e-12"));
    assert_eq!(converged.contact.impacts, 54);
    assert!(
        rel(converged.contact.peak_force, independent) < 1e-4,
        "{}",
        converged.contact.peak_force
    );
    let default = run(&stiff(pga, 6.0, "adaptive", 1e-4, ""));
    assert_eq!(default.contact.impacts, 54);
    assert!(
        rel(default.contact.peak_force, independent) < 5e-3,
        "{}",
        default.contact.peak_force
    );
}

/// rtol acts down to 1e-12: on the first second of the stiff case (ten impacts, before the
/// sequence turns sensitive) the located onset and release times at rtol 1e-8 and 1e-10 differ
/// from those at 1e-12, by less at 1e-10 (at least 10× less per factor 100 of rtol). Before
/// issue 9 a fixed atol made 1e-10 … 1e-13 bit-identical. (Event times, not peaks: a peak is
/// refined between observations, whose spacing also changes with rtol, to ~1e-6.)
#[test]
fn rtol_acts_down_to_1e_12() {
    let events = |r: &str| -> Vec<f64> {
        let rep = run(&stiff(0.5, 1.0, "adaptive", 1e-3, &format!("rtol = {r}")));
        rep.impact_log
            .iter()
            .flat_map(|i| [i.start, i.end])
            .collect()
    };
    let (e8, e10, e12) = (events("1e-8"), events("1e-10"), events("1e-12"));
    assert_eq!((e8.len(), e10.len()), (e12.len(), e12.len()));
    assert!(e12.len() >= 10, "{e12:?}");
    let dist = |a: &[f64]| {
        a.iter()
            .zip(&e12)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    let (d8, d10) = (dist(&e8), dist(&e10));
    assert!(d10 > 0.0, "rtol 1e-10 and 1e-12 gave the same events");
    assert!(
        d10 * 10.0 < d8,
        "event time error {d8:e} s at 1e-8, {d10:e} s at 1e-10"
    );
}

/// `approach_speed` (impacts.csv) is δ̇ at the located onset. Against the converged run's:
/// `adaptive` at its default on the first five impacts of the stiff case to 1e-6 (it locates
/// each onset; measured ≤ 3e-7); `rk4` at dt = 1e-4 s and `exact-modal` at dt = 1e-3 s on the
/// first impact to 1e-3 (the recorder takes the root of the cubic Hermite interpolant of δ
/// between observations: error O(dt³) in δ̇; measured 5.8e-4 and 1.5e-5 — later impacts carry
/// the methods' own trajectory error). Before issue 9 the recorder took δ̇ at the first
/// observation with δ > 0: −3.6 % at dt = 1e-4, −36 % at 1e-3.
#[test]
fn approach_speed_is_the_speed_at_the_located_onset() {
    let reference = run(&stiff(0.5, 0.6, "adaptive", 1e-4, "rtol = 1e-12"));
    let speeds = |r: &Report| -> Vec<f64> {
        r.impact_log
            .iter()
            .take(5)
            .map(|i| i.approach_speed)
            .collect()
    };
    let want = speeds(&reference);
    assert_eq!(want.len(), 5);
    assert!(want.iter().all(|&v| v > 0.1), "{want:?}");
    for (method, dt, tol, count) in [
        ("adaptive", 1e-3, 1e-6, 5),
        ("rk4", 1e-4, 1e-3, 1),
        ("exact-modal", 1e-3, 1e-3, 1),
    ] {
        let got = speeds(&run(&stiff(0.5, 0.6, method, dt, "")));
        assert_eq!(got.len(), 5, "{method}");
        for (g, w) in got.iter().zip(&want).take(count) {
            assert!(rel(*g, *w) < tol, "{method} dt {dt}: {g} vs converged {w}");
        }
    }
}

/// The damped Hertz law's v₀ is the approach speed at the onset, not `max(v₀, δ̇)` (which
/// overestimated it by the free acceleration times a step: a first-order error). The first
/// impact of the stiff case with the default damped Hertz law (Lankarani–Nikravesh, k_h =
/// 2.808e11 N/m^1.5, e = 0.6) by `rk4` at dt = 1e-4, 5e-5, 2.5e-5 s: the error of its impulse
/// (the rebound momentum) against the converged run falls faster than first order (by more
/// than 2.8 per halving, order > 1.5; measured 9.9e-7, 8.0e-8, 4.2e-9).
#[test]
fn damped_hertz_rebound_error_falls_faster_than_first_order() {
    let contact = "law = \"hertzdamp\"\nstiffness = 2.808e11\nrestitution = 0.6";
    let impulse = |method: &str, dt: f64, solver: &str| {
        let r = run(&stiff_with(contact, 0.5, 0.55, method, dt, solver));
        assert_eq!(r.impact_log.len(), 1);
        r.impact_log[0].impulse
    };
    let reference = impulse("adaptive", 1e-4, "rtol = 1e-12");
    let errors: Vec<f64> = [1e-4, 5e-5, 2.5e-5]
        .iter()
        .map(|&dt| rel(impulse("rk4", dt, ""), reference))
        .collect();
    for w in errors.windows(2) {
        assert!(
            w[0] > 2.8 * w[1],
            "errors {errors:?} do not fall faster than first order"
        );
    }
}

/// A damped law's peak force comes while δ still grows (δ̇ > 0), between observations: it is
/// searched on the step's Hermite interpolant of (δ, δ̇), not taken as the elastic force at the
/// largest penetration (a lower bound). The first impact of the stiff case with the default
/// damped Hertz law (k_h = 2.808e11 N/m^1.5, e = 0.6) against the converged run: `adaptive` at
/// its default (dt = 1 ms) and `rk4` at dt = 1e-4 s within 2e-5 (measured 2.6e-6 and 8.4e-6;
/// before: 2.4e-4 whatever the step, the elastic bound).
#[test]
fn damped_law_peak_force_is_found_between_observations() {
    let contact = "law = \"hertzdamp\"\nstiffness = 2.808e11\nrestitution = 0.6";
    let peak = |method: &str, dt: f64, solver: &str| {
        let r = run(&stiff_with(contact, 0.5, 0.55, method, dt, solver));
        assert_eq!(r.impact_log.len(), 1);
        r.impact_log[0].peak_force
    };
    let reference = peak("adaptive", 1e-4, "rtol = 1e-12");
    for (method, dt) in [("adaptive", 1e-3), ("rk4", 1e-4)] {
        let f = peak(method, dt, "");
        assert!(
            rel(f, reference) < 2e-5,
            "{method} dt {dt}: {f} vs {reference}"
        );
    }
}

/// A bundled example with `replace` applied to its text (scenario directory `examples/`, so a
/// record resolves as it does for the user).
fn example(file: &str, replace: &[(&str, &str)]) -> Scenario {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut text = std::fs::read_to_string(dir.join(file)).expect("bundled example");
    for (a, b) in replace {
        assert!(text.contains(a), "{file} has no `{a}`");
        text = text.replace(a, b);
    }
    Scenario::from_toml(&text, file, &dir).expect("valid scenario")
}

/// The cases of issue 9, item 3, beyond the stiff Hertz one: a record, a damped law at two
/// levels of structures of different heights (5 modes each), many modes (20 per structure),
/// and every damped law on a 100× stiffer-than-the-paper contact. Each as (name, scenario
/// with `method`, `dt` and `solver` lines).
fn cases(method: &str, dt_scale: f64, solver: &str) -> Vec<(&'static str, Scenario)> {
    let m = format!("method = \"{method}\"\n{solver}");
    let dt = |d: f64| format!("dt = {}", d * dt_scale);
    let stiff_law = |law: &str| stiff_with(law, 0.5, 3.0, method, 1e-3 * dt_scale, solver);
    vec![
        (
            "Loma Prieta record",
            example(
                "loma-prieta.toml",
                &[("method = \"rk4\"", &m), ("dt = 0.001", &dt(5e-3))],
            ),
        ),
        (
            "two levels, hertzdamp, unequal heights",
            example(
                "two-levels.toml",
                &[("method = \"rk4\"", &m), ("dt = 0.0002", &dt(1e-3))],
            ),
        ),
        (
            "paper case c, 20 modes",
            example(
                "paper-c.toml",
                &[
                    ("method = \"rk4\"", &m),
                    ("dt = 0.001", &dt(1e-3)),
                    ("modes = 3", "modes = 20"),
                    ("duration = 20.0", "duration = 10.0"),
                ],
            ),
        ),
        (
            "stiff hertzdamp",
            stiff_law("law = \"hertzdamp\"\nstiffness = 2.808e11\nrestitution = 0.6"),
        ),
        (
            "stiff kelvin",
            stiff_law("law = \"kelvin\"\nstiffness = 1e10\nrestitution = 0.6"),
        ),
        (
            "stiff jankowski",
            stiff_law("law = \"jankowski\"\nstiffness = 2.808e11\nrestitution = 0.6"),
        ),
    ]
}

/// Every headline number of `r` within `tol` of `reference` (and, with `same_impacts`, the
/// same number of impacts: at 0.5 % a long sequence may gain or lose one).
fn assert_close(what: &str, r: &Report, reference: &Report, tol: f64, same_impacts: bool) {
    for ((name, a), (_, b)) in headline(r).iter().zip(headline(reference)) {
        assert!(
            rel(*a, b) < tol,
            "{what}: {name} {a} vs converged {b} ({:.2e})",
            rel(*a, b)
        );
    }
    if same_impacts {
        assert_eq!(
            r.contact.impacts, reference.contact.impacts,
            "{what}: impacts"
        );
    }
}

/// Issue 9, item 3: at default settings every result is within 0.5 % of the converged
/// solution, on a record, damped laws, many modes and unequal heights (the stiff Hertz case has
/// its own test above); at rtol = 1e-10 both accurate methods are within 0.1 %. The converged
/// solution is `adaptive` at rtol 1e-12 and a tenth of the step, confirmed by the other
/// method, `exact-modal` at rtol 1e-11, within 1e-5 (two schemes that share only the exact
/// modal propagators). Measured (printed): defaults within 5.9e-6 (`adaptive`) and 1.5e-6
/// (`exact-modal`, whose count of impacts may differ by one or two), rtol 1e-10 within 5.9e-6
/// and 5.0e-7; the reference confirmed within 7.3e-7.
#[test]
fn defaults_and_rtol_1e_10_are_within_their_bounds_across_cases() {
    let reference = cases("adaptive", 0.1, "rtol = 1e-12");
    let confirm = cases("exact-modal", 1.0, "rtol = 1e-11");
    for (method, solver, tol) in [
        ("adaptive", "", 5e-3),
        ("exact-modal", "", 5e-3),
        ("adaptive", "rtol = 1e-10", 1e-3),
        ("exact-modal", "rtol = 1e-10", 1e-3),
    ] {
        for ((name, s), ((_, r), (_, c))) in cases(method, 1.0, solver)
            .iter()
            .zip(reference.iter().zip(&confirm))
        {
            let reference = run(r);
            if method == "adaptive" && solver.is_empty() {
                let c = run(c);
                eprintln!(
                    "{name}: reference confirmed by exact-modal rtol 1e-11 within {:.2e}",
                    largest_error(&c, &reference)
                );
                assert_close(&format!("{name}: reference"), &c, &reference, 1e-5, true);
            }
            let what = format!("{name}: {method} {solver}");
            let r = run(s);
            eprintln!(
                "{what}: largest headline error {:.2e}, impacts {} (converged {})",
                largest_error(&r, &reference),
                r.contact.impacts,
                reference.contact.impacts
            );
            assert_close(&what, &r, &reference, tol, tol < 5e-3);
        }
    }
}

/// The stiff Hertz case of issue 9 (6 s, 54 impacts, at the PGA of its independent solution)
/// at rtol = 1e-10 with either accurate method is within 0.1 % of the converged run (measured
/// 4.7e-6 `adaptive`, 2.4e-7 `exact-modal`, printed). This is not a bound for every case: at
/// PGA 0.5 g exactly the same case is so sensitive that `adaptive` at 1e-10 is 0.22 % off (and
/// `exact-modal` 5.0e-5, see below).
#[test]
fn stiff_case_at_rtol_1e_10_is_within_a_tenth_of_a_percent_with_both_methods() {
    let pga = 0.5 * 9.81 / 9.80665;
    let reference = run(&stiff(pga, 6.0, "adaptive", 1e-4, "rtol = 1e-12"));
    for method in ["adaptive", "exact-modal"] {
        let r = run(&stiff(pga, 6.0, method, 1e-3, "rtol = 1e-10"));
        eprintln!(
            "stiff case {pga:.5} g: {method} rtol 1e-10: largest headline error {:.2e}, peak force {:.2e}",
            largest_error(&r, &reference),
            rel(r.contact.peak_force, reference.contact.peak_force)
        );
        assert_close(method, &r, &reference, 1e-3, true);
    }
}

/// `exact-modal`'s rtol controls its contact sub-steps: on the first impacts of the stiff case
/// (before the sequence turns sensitive: from the fourth on, each impact inherits the earlier
/// ones' errors amplified) the peak-force error against the converged run falls at least 5×
/// for every 100× of rtol (rtol 1e-4, 1e-6, 1e-8: measured 1.1e-4, 1.3e-6, 2.0e-7),
/// while the sub-steps grow in number.
///
/// The converged run is `adaptive` at rtol 1e-12 and dt 0.01 ms. At dt 0.1 ms (this test's
/// reference until issue 25) its first three peak forces were 5.3e-8, 7.9e-8 and 2.8e-8 below
/// it: the recorder takes an impact's peak force from the cubic Hermite of δ between
/// observations, and `adaptive`'s observations inside an impact are at most dt apart however
/// small rtol is — a floor of the reference that does not follow rtol, as large as half of
/// `exact-modal`'s error at rtol 1e-8. At dt 0.01 ms the reference agrees with `exact-modal`
/// at rtol 1e-12 (another scheme, whose peaks come from its own sub-steps' dense output) to
/// 2e-9, asserted below within 1e-8: 20× below the smallest error this test compares.
#[test]
fn exact_modal_rtol_controls_its_error() {
    let reference = run(&stiff(0.5, 1.0, "adaptive", 1e-5, "rtol = 1e-12"));
    assert_eq!(reference.contact.impacts, 10);
    let confirm = run(&stiff(0.5, 1.0, "exact-modal", 1e-3, "rtol = 1e-12"));
    for (a, b) in confirm.impact_log.iter().zip(&reference.impact_log).take(3) {
        let d = rel(a.peak_force, b.peak_force);
        assert!(d < 1e-8, "reference not converged: {d:.3e}");
    }
    let mut last = (f64::INFINITY, 0);
    for rtol in [1e-4, 1e-6, 1e-8] {
        let r = run(&stiff(
            0.5,
            1.0,
            "exact-modal",
            1e-3,
            &format!("rtol = {rtol}"),
        ));
        assert_eq!(r.contact.impacts, 10, "rtol {rtol}");
        let err = r
            .impact_log
            .iter()
            .zip(&reference.impact_log)
            .take(3)
            .map(|(a, b)| rel(a.peak_force, b.peak_force))
            .fold(0.0f64, f64::max);
        eprintln!(
            "exact-modal rtol {rtol}: first three impacts' peak force within {err:.2e}, {} steps",
            r.with_contact.steps
        );
        assert!(
            err < last.0 / 5.0,
            "rtol {rtol}: {err:.3e} after {:.3e}",
            last.0
        );
        assert!(
            r.with_contact.steps > last.1,
            "rtol {rtol}: no more sub-steps"
        );
        last = (err, r.with_contact.steps);
    }
    assert!(last.0 < 5e-6, "rtol 1e-8: {:.3e}", last.0);
}

/// The free flight of a long base step is tested for contact with a margin for the modes that
/// oscillate within it (ω₃·dt = 3.7 here): at dt = 10 ms `exact-modal` meets the same ten
/// impacts as the converged run in the stiff case's first second, at the same times. Without
/// the margin the cubic through the step's ends missed the fifth (a 1.8 ms, 22 MN impact at
/// t = 0.573 s) and merged its neighbours.
#[test]
fn exact_modal_does_not_miss_short_impacts_inside_a_long_step() {
    let reference = run(&stiff(0.5, 1.0, "adaptive", 1e-4, "rtol = 1e-12"));
    let r = run(&stiff(0.5, 1.0, "exact-modal", 1e-2, "rtol = 1e-8"));
    assert_eq!(r.contact.impacts, reference.contact.impacts);
    for (a, b) in r.impact_log.iter().zip(&reference.impact_log) {
        assert!(
            (a.start - b.start).abs() < 1e-5,
            "{} vs {}",
            a.start,
            b.start
        );
        assert!(
            rel(a.peak_force, b.peak_force) < 1e-3,
            "{} vs {}",
            a.peak_force,
            b.peak_force
        );
    }
}

/// A result that failed its check is never presented as converged, and one that passed it is
/// right: on the stiff Hertz case (PGA 0.5 g, where it is most sensitive: a chaotic sequence of
/// impacts amplifies every impact's error) `exact-modal` at rtol 5e-5 (its default while its
/// contact steps were second order) is 10 % and 4.8 % off in peak force at dt 1 ms and 10 ms,
/// and its self-check says NOT converged each time; at its default (1e-8) it is within 0.5 %
/// (measured 2.1e-4, 5.9e-4) and the check says converged; at 1e-10 within 0.1 % (5.0e-5). (Before its sub-steps followed rtol, the check
/// run was bit-identical and could see nothing; before they were a collocation, the default
/// was 1.6 % and 20 % off, flagged.)
#[test]
fn exact_modal_on_the_stiff_case_is_flagged_when_off() {
    use pounding::analysis::simulate::simulate_checked;
    let reference = run(&stiff(0.5, 6.0, "adaptive", 1e-4, "rtol = 1e-12"));
    for (dt, solver, bound) in [
        (1e-3, "rtol = 5e-5", None),
        (1e-2, "rtol = 5e-5", None),
        (1e-3, "", Some(5e-3)),
        (1e-2, "", Some(5e-3)),
        (1e-3, "rtol = 1e-10", Some(1e-3)),
    ] {
        let s = stiff(0.5, 6.0, "exact-modal", dt, solver);
        let r = simulate_checked(&s, true).expect("runs");
        let err = rel(r.contact.peak_force, reference.contact.peak_force);
        let converged = r.accuracy.converged;
        eprintln!(
            "exact-modal dt {dt} {solver}: peak force error {err:.2e}, converged {converged:?}, \
             largest headline error {:.2e}, impacts {} (converged {})",
            largest_error(&r, &reference),
            r.contact.impacts,
            reference.contact.impacts
        );
        match bound {
            // the former default: off, and flagged
            None => {
                assert!(err > 0.01, "premise: dt {dt} {solver}: error {err:.3e}");
                assert_eq!(converged, Some(false), "dt {dt} {solver}: error {err:.3e}");
            }
            Some(b) => {
                assert!(err < b, "dt {dt} {solver}: error {err:.3e}");
                assert_eq!(converged, Some(true), "dt {dt} {solver}: error {err:.3e}");
            }
        }
    }
}

/// Yielding storeys pounding on a stiff contact: the bundled yielding frames (Bouc–Wen,
/// Loma Prieta 0.6 g, four contact levels) with Jankowski's law 100× stiffer (2.75e11 N/m^1.5),
/// 15 s. The method a scenario gets when it names none (`adaptive` for yielding storeys) at its
/// default tolerance is within 0.5 % of the converged run (`adaptive` at rtol 1e-12), which
/// `exact-modal` at its default — a different scheme for the storeys (trapezoidal sub-steps) —
/// confirms within 1e-5. Measured: default 1.1e-7, confirmation 6.1e-7 (peak force).
#[test]
fn yielding_storeys_on_a_stiff_contact_at_the_default() {
    let with = |solver: &str| {
        example(
            "yielding-frames.toml",
            &[
                ("stiffness = 2.75e9", "stiffness = 2.75e11"),
                ("duration = 45.0", &format!("{solver}\nduration = 15.0")),
            ],
        )
    };
    let default = with("");
    assert_eq!(default.solver.method.name(), "adaptive", "the default");
    let reference = run(&with("method = \"adaptive\"\nrtol = 1e-12"));
    assert!(reference.contact.impacts >= 5, "premise: it pounds");
    let confirm = run(&with("method = \"exact-modal\""));
    let r = run(&default);
    eprintln!(
        "yielding frames, stiff Jankowski: exact-modal default {:.2e} (peak force {:.2e}), \
         adaptive default {:.2e} (peak force {:.2e})",
        largest_error(&confirm, &reference),
        rel(confirm.contact.peak_force, reference.contact.peak_force),
        largest_error(&r, &reference),
        rel(r.contact.peak_force, reference.contact.peak_force)
    );
    assert_close("reference", &confirm, &reference, 1e-5, true);
    assert_close("default", &r, &reference, 5e-3, true);
}

/// The stiff Hertz case (1000× the paper's) with 40 modes per structure: `exact-modal`, the
/// default for elastic structures, at its default tolerance and dt is within 0.5 % of the
/// converged run (`adaptive`, rtol 1e-12, dt 0.1 ms) on every headline number, with the same
/// impacts. Measured: peak force 1.7e-9, peak 1 5.4e-6 (the 40th mode's peaks between
/// observations), 105 impacts.
#[test]
fn stiff_hertz_with_40_modes_at_the_default() {
    let with_modes = |solver: &str| {
        let text = format!(
            "[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.3\nmodes = 40\n\
             damping_ratio = 0.01\n[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.6\n\
             modes = 40\ndamping_ratio = 0.01\n[contact]\nlaw = \"hertz\"\nstiffness = 2.808e13\n\
             gap = 0.0127\n[ground_motion]\nkind = \"harmonic\"\npga = 0.5\nperiod = 0.8\n\
             [solver]\nduration = 6.0\n{solver}"
        );
        Scenario::from_toml(&text, "stiff40.toml", Path::new(".")).expect("valid scenario")
    };
    let default = with_modes("");
    assert_eq!(default.solver.method.name(), "exact-modal", "the default");
    let reference = run(&with_modes(
        "method = \"adaptive\"\nrtol = 1e-12\ndt = 1e-4\n",
    ));
    assert!(reference.contact.impacts > 50, "premise: a long sequence");
    let r = run(&default);
    eprintln!(
        "stiff Hertz, 40 modes: exact-modal default largest headline error {:.2e} \
         (peak force {:.2e}), impacts {} (converged {})",
        largest_error(&r, &reference),
        rel(r.contact.peak_force, reference.contact.peak_force),
        r.contact.impacts,
        reference.contact.impacts
    );
    assert_close("40 modes", &r, &reference, 5e-3, true);
}

/// The bundled shear buildings at 0.6 g over 15 s with `law` at `stiffness` and `solver` lines.
fn shear(law: &str, stiffness: &str, solver: &str) -> Scenario {
    example(
        "shear-buildings.toml",
        &[
            ("law = \"jankowski\"", &format!("law = \"{law}\"")),
            ("stiffness = 2.75e9", &format!("stiffness = {stiffness}")),
            ("scale_to_pga = 0.4", "scale_to_pga = 0.6"),
            ("duration = 25.0", &format!("{solver}\nduration = 15.0")),
        ],
    )
}

/// Shear buildings pounding at four floors (the bundled 4- and 8-storey buildings, Loma Prieta
/// at 0.6 g, 15 s) on stiff contacts of every damped law: at the default (`exact-modal`) within
/// 0.5 % of the converged run (`adaptive`, rtol 1e-12). Measured: Jankowski (2.75e11, 100× the
/// example's) 1.7e-8, damped Hertz (2.75e12) 7.8e-7, Kelvin (1e10) 1.9e-5 on the peak force —
/// the last not set by the tolerance but by how finely a damped law's peak between
/// observations is found.
#[test]
fn shear_building_floors_on_stiff_contacts_at_the_default() {
    for (law, k) in [
        ("jankowski", "2.75e11"),
        ("hertzdamp", "2.75e12"),
        ("kelvin", "1e10"),
    ] {
        let default = shear(law, k, "");
        assert_eq!(default.solver.method.name(), "exact-modal", "the default");
        let reference = run(&shear(law, k, "method = \"adaptive\"\nrtol = 1e-12"));
        assert!(reference.contact.impacts > 20, "premise: {law} pounds");
        let r = run(&default);
        eprintln!(
            "shear floors, {law}: exact-modal default largest headline error {:.2e} \
             (peak force {:.2e})",
            largest_error(&r, &reference),
            rel(r.contact.peak_force, reference.contact.peak_force)
        );
        assert_close(law, &r, &reference, 5e-3, true);
    }
}

/// `exact-modal` converges monotonically as rtol shrinks, on whole runs: the shear buildings on
/// the stiff Jankowski contact (44 impacts at four floors) at rtol 1e-4 … 1e-7, the largest
/// error of the headline numbers against the converged run falls at least 5× per decade of
/// rtol (measured 2.6e-5, 2.1e-6, 1.8e-7, 2.3e-8: one order per order, as a tolerance should
/// act) — so the self-check's rerun at rtol/100 and `pounding convergence` see the error they
/// report.
///
/// The converged run is `adaptive` at rtol 1e-12 and dt 0.01 ms. At the record's step (this
/// test's reference until issue 25) its peak force was 1.3e-8 below it (the damped law's peak
/// is searched between observations, which `adaptive` takes at most dt apart: at dt 0.5 ms it is
/// 4.0e-8 below, at 0.05 ms 0.9e-8 above, at 2 µs 0.03e-8 above), as large as `exact-modal`'s
/// error at rtol 1e-7. At dt 0.01 ms it agrees with `exact-modal` at rtol 1e-12 (another
/// scheme) to 2.6e-9, asserted below within 1e-8.
#[test]
fn exact_modal_converges_monotonically_in_rtol() {
    let reference = run(&shear(
        "jankowski",
        "2.75e11",
        "method = \"adaptive\"\nrtol = 1e-12\ndt = 1e-5",
    ));
    let confirm = run(&shear("jankowski", "2.75e11", "rtol = 1e-12"));
    for ((name, a), (_, b)) in headline(&confirm).iter().zip(headline(&reference)) {
        let d = rel(*a, b);
        assert!(d < 1e-8, "reference not converged: {name} {d:.3e}");
    }
    let mut last = f64::INFINITY;
    for rtol in ["1e-4", "1e-5", "1e-6", "1e-7"] {
        let r = run(&shear("jankowski", "2.75e11", &format!("rtol = {rtol}")));
        assert_eq!(r.contact.impacts, reference.contact.impacts, "rtol {rtol}");
        let err = headline(&r)
            .iter()
            .zip(headline(&reference))
            .map(|((_, a), (_, b))| rel(*a, b))
            .fold(0.0f64, f64::max);
        eprintln!("exact-modal rtol {rtol}: largest headline error {err:.2e}");
        assert!(err < last / 5.0, "rtol {rtol}: {err:.3e} after {last:.3e}");
        last = err;
    }
}

/// Issue 25's list of stiff contacts beyond those above, each at `exact-modal`'s default
/// (rtol 1e-8, dt 1 ms) against the converged run (`adaptive`, rtol 1e-12, a tenth of the
/// step; the shear buildings at the record's own step, as above): the stiff case of issue 9
/// (3 modes, PGA 0.5 g, 6 s) with every damped law: damped Hertz and Jankowski at k_h =
/// 2.808e13 N/m^1.5 (1000× the paper's Hertz stiffness), Kelvin at k = 1e11 N/m (10× the
/// Kelvin case above); the
/// damped Hertz and Kelvin ones with 40 modes, the undamped Hertz law with 10 and 20 modes,
/// and the shear buildings' floors on the undamped Hertz law at 2.808e13. Within 0.5 % (the
/// issue's bar) on both peaks, the peak force and the separation. Measured (largest of the
/// four): damped Hertz 1.4e-7, Kelvin 1.7e-6, Jankowski 3.2e-6, damped Hertz 40 modes 7.1e-7,
/// Kelvin 40 modes 9.3e-7, Hertz 10 modes 9.7e-6, Hertz 20 modes 3.4e-7, shear floors Hertz
/// 7.5e-9. The count of impacts is not asserted: it may differ by one grazing impact (damped
/// Hertz 74 against 73, Hertz 20 modes 106 against 105). (The undamped Hertz law with 3 modes
/// is chaotic at 0.4 and 0.6 g as at 0.5 g: see the next test.)
#[test]
fn stiff_contacts_of_issue_25_at_the_default() {
    let stiff3 = |law: &str, modes: usize, solver: &str| {
        let text = format!(
            "[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.3\nmodes = {modes}\n\
             damping_ratio = 0.01\n[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.6\n\
             modes = {modes}\ndamping_ratio = 0.01\n[contact]\n{law}\ngap = 0.0127\n\
             [ground_motion]\nkind = \"harmonic\"\npga = 0.5\nperiod = 0.8\n[solver]\n\
             duration = 6.0\n{solver}"
        );
        Scenario::from_toml(&text, "stiff.toml", Path::new(".")).expect("valid scenario")
    };
    let hertzdamp = "law = \"hertzdamp\"\nstiffness = 2.808e13\nrestitution = 0.6";
    let kelvin = "law = \"kelvin\"\nstiffness = 1e11\nrestitution = 0.6";
    let jankowski = "law = \"jankowski\"\nstiffness = 2.808e13\nrestitution = 0.6";
    let hertz = "law = \"hertz\"\nstiffness = 2.808e13";
    let reference = "method = \"adaptive\"\nrtol = 1e-12\ndt = 1e-4\n";
    let cases = [
        ("damped Hertz", hertzdamp, 3),
        ("Kelvin", kelvin, 3),
        ("Jankowski", jankowski, 3),
        ("damped Hertz, 40 modes", hertzdamp, 40),
        ("Kelvin, 40 modes", kelvin, 40),
        ("Hertz, 10 modes", hertz, 10),
        ("Hertz, 20 modes", hertz, 20),
    ];
    for (name, law, modes) in cases {
        let default = stiff3(law, modes, "");
        assert_eq!(default.solver.method.name(), "exact-modal", "the default");
        let r = run(&default);
        let c = run(&stiff3(law, modes, reference));
        assert!(c.contact.impacts >= 20, "premise: {name} pounds");
        report_and_assert(name, &r, &c);
    }
    // (the bundled shear buildings as `shear` makes them, on the undamped law: no restitution)
    let shear_hertz = |solver: &str| {
        example(
            "shear-buildings.toml",
            &[
                ("law = \"jankowski\"", "law = \"hertz\""),
                ("stiffness = 2.75e9", "stiffness = 2.808e13"),
                ("restitution = 0.65\n", ""),
                ("scale_to_pga = 0.4", "scale_to_pga = 0.6"),
                ("duration = 25.0", &format!("{solver}\nduration = 15.0")),
            ],
        )
    };
    let r = run(&shear_hertz(""));
    let c = run(&shear_hertz("method = \"adaptive\"\nrtol = 1e-12"));
    assert!(c.contact.impacts >= 20, "premise: the floors pound");
    report_and_assert("shear floors, Hertz", &r, &c);
}

/// The largest relative error of the headline numbers of `r` against `reference`, printed,
/// and asserted below 0.5 %.
fn report_and_assert(what: &str, r: &Report, reference: &Report) {
    let err = largest_error(r, reference);
    eprintln!(
        "{what}: largest headline error {err:.2e}, impacts {} (converged {})",
        r.contact.impacts, reference.contact.impacts
    );
    assert_close(what, r, reference, 5e-3, false);
}

/// The undamped Hertz law 1000× the paper's with 3 modes is chaotic at other intensities too:
/// at PGA 0.4 g and 0.6 g (6 s) `exact-modal` at its default (dt 1 ms) is 48 % and 3.6 % off
/// the converged peak force (and `adaptive` at its default 15 % and 6.5 %; at 0.6 g `adaptive`
/// at rtol 1e-12 and 3e-12 still differ by 0.7 %: no tolerance bounds such a case). What holds
/// is the self-check: every such run off by more than 1 % says NOT converged (here the peak
/// force moved by 27 % against the check's rerun at 0.4 g, the count of impacts by 3.4 % at
/// 0.6 g). The premise — at least one run off by more than 1 % — keeps the test from passing
/// without checking anything.
#[test]
fn exact_modal_off_on_chaotic_stiff_cases_is_flagged() {
    use pounding::analysis::simulate::simulate_checked;
    let mut off = 0;
    for pga in [0.4, 0.6] {
        let reference = run(&stiff(pga, 6.0, "adaptive", 1e-4, "rtol = 1e-12"));
        let r = simulate_checked(&stiff(pga, 6.0, "exact-modal", 1e-3, ""), true).expect("runs");
        let err = rel(r.contact.peak_force, reference.contact.peak_force);
        eprintln!(
            "PGA {pga} g: exact-modal default peak force error {err:.2e}, converged {:?}",
            r.accuracy.converged
        );
        if err > 0.01 {
            off += 1;
            assert_eq!(r.accuracy.converged, Some(false), "PGA {pga} g: {err:.3e}");
        }
    }
    assert!(off > 0, "premise: a chaotic case off by more than 1 %");
}
