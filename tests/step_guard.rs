//! Every run returns: `exact-modal`'s contact steps never stall (the case of
//! `tests/data/jankowski-kink.toml`, which ran without end before the fix: a Jankowski
//! loading/unloading switch located a round-off short was re-found at every next step's start,
//! steps of 3e-25 s that did not move time, in the self-check's run at rtol 1e-10), and the
//! run is as accurate there as the independent `adaptive` at the same tolerance.

use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

use pounding::analysis::simulate::accuracy::tightened;
use pounding::analysis::simulate::{Report, simulate, simulate_checked};
use pounding::input::scenario::Scenario;
use pounding::integrate::{Method, SolveError};

const CASE: &str = include_str!("data/jankowski-kink.toml");

/// The case's one record at `factor` (`None`: the case's own), solved by `method` (`None`: the
/// default, `exact-modal` at rtol 1e-8) at relative tolerance `rtol`.
fn case(factor: Option<f64>, method: Option<Method>, rtol: Option<f64>) -> Scenario {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let suite = Scenario::from_toml(CASE, "jankowski-kink.toml", &dir).expect("valid scenario");
    let members = suite.suite.as_ref().expect("a suite");
    let f = factor.unwrap_or_else(|| members.records[0].factor.expect("the case's factor"));
    let mut sc = members
        .member_scenario(&suite, 0, f)
        .expect("the record scales");
    if let Some(m) = method {
        sc.solver.method = m;
    }
    if let Some(r) = rtol {
        sc.solver = sc.solver.with_rtol(r);
    }
    sc
}

/// `run` on another thread, failing the test if it has not returned within `secs` (a run that
/// does not return fails instead of hanging the test suite).
fn within(secs: u64, run: impl FnOnce() -> Result<Report, SolveError> + Send + 'static) -> Report {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(run());
    });
    rx.recv_timeout(Duration::from_secs(secs))
        .unwrap_or_else(|e| panic!("the run did not return within {secs} s ({e})"))
        .unwrap_or_else(|e| panic!("the run failed: {e}"))
}

/// The case's self-check run (exact-modal at the check's rtol 1e-10) returns — it ran without
/// end before the fix — in a bounded number of steps, and agrees with `adaptive` at the same
/// tolerance on every level's peak force, penetration and impacts and on both structures' peak
/// displacements; the whole checked run (`pounding run`'s) passes its self-check.
#[test]
fn jankowski_switch_at_a_round_off_is_not_found_again() {
    let default = case(None, None, None);
    let tight = tightened(&default.solver);
    assert_eq!(tight.rtol, 1e-10, "the self-check's tolerance");
    let mut sc = default.clone();
    sc.solver = tight;
    // (0.3 s in a release build; 60 s leaves room for a loaded machine)
    let exact = within(60, move || simulate(&sc));
    // The record's 65 s on the 1 ms grid are ~6.6e4 free-flight steps, and its contact
    // episodes a few thousand contact steps: 2e5 bounds the run with room (the stall took
    // millions of steps a second without end).
    assert!(
        exact.stats.steps < 200_000,
        "{} steps ({} rejected)",
        exact.stats.steps,
        exact.stats.rejected
    );
    let mut sc = default.clone();
    sc.solver.method = Method::Adaptive;
    sc.solver = sc.solver.with_rtol(1e-10);
    let reference = within(600, move || simulate(&sc));
    // Two independent methods at rtol 1e-10: the states they reach differ by their errors
    // (penetrations and displacements measured within 6e-11 of each other); 1e-8 leaves room
    // and catches a kink straddled wrongly (an error of the force's slope jump over a step,
    // ~1e-3 of the force). The peak force is compared looser: `adaptive` reports the largest
    // force at its step ends, which lies below the peak by up to ~F''h²/8 (measured 2.7e-6
    // below at 1e-10, 5e-7 at 1e-12, converging on exact-modal's, whose dense output finds
    // the peak inside the step): within 1e-5, and never above exact-modal's by more than the
    // states' 1e-8.
    let close = |a: f64, b: f64, tol: f64, what: &str| {
        assert!(
            (a - b).abs() <= tol * a.abs().max(b.abs()),
            "{what}: exact-modal {a} vs adaptive {b}"
        );
    };
    for (k, (a, b)) in exact.levels.iter().zip(&reference.levels).enumerate() {
        let level = k + 1;
        close(
            a.peak_force,
            b.peak_force,
            1e-5,
            &format!("level {level} force"),
        );
        assert!(
            b.peak_force <= a.peak_force * (1.0 + 1e-8),
            "level {level}: adaptive's sampled peak {} above exact-modal's {}",
            b.peak_force,
            a.peak_force
        );
        close(
            a.max_penetration,
            b.max_penetration,
            1e-8,
            &format!("level {level} penetration"),
        );
        assert_eq!(a.impacts, b.impacts, "level {level} impacts");
    }
    for s in 0..2 {
        close(
            exact.structures[s].peak_displacement,
            reference.structures[s].peak_displacement,
            1e-8,
            &format!("structure {} peak displacement", s + 1),
        );
    }
    assert!(exact.contact.impacts > 0, "the case pounds");
    // the run as `pounding run` makes it: the default, then the self-check
    let checked = within(60, move || simulate_checked(&default, true));
    let acc = &checked.accuracy;
    assert!(
        acc.checked && acc.failure.is_none() && acc.converged == Some(true),
        "{acc:?}"
    );
}

/// Factors around the case's (the record scaled by 2.38 returned before the fix, 2.5688 did
/// not), at the default and the self-check's tolerance, all run in a bounded number of steps:
/// the stall was not one factor's accident.
#[test]
fn neighbouring_factors_run() {
    for f in [2.379860103065582, 2.5, 2.55, 2.5688420687494453, 2.6, 2.7] {
        for rtol in [1e-8, 1e-10] {
            let sc = case(Some(f), None, Some(rtol));
            let r = within(60, move || simulate(&sc));
            assert!(
                r.stats.steps < 200_000,
                "factor {f} rtol {rtol}: {} steps",
                r.stats.steps
            );
        }
    }
}
