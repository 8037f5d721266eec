//! The self-check beside the run ([`super::concurrent`]) against the same on one thread: the
//! report (by its `Debug` text, which writes every f64 so that it reads back exactly), the
//! streamed rows and what `beside` saw; and a check that fails on its thread gives the same
//! verdict and warning as sequentially. (Every file of the run, byte for byte:
//! tests/check_beside.rs, outside the library, which writes them.)

use super::concurrent::{Runs, streaming_beside};
use super::reuse_tests::{cantilevers, scenario, shear};
use super::*;

/// The self-check's integration as the program does it.
fn real(
    tight: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    exact: bool,
) -> Result<Runs, SolveError> {
    super::concurrent::check_runs(tight, system, sink, exact)
}

/// The self-check's integration failing after its run with contact, as a check run can
/// (e.g. `rk4` refused at a contact, an `adaptive` step that cannot meet its tolerance).
fn failing(
    tight: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    exact: bool,
) -> Result<Runs, SolveError> {
    super::concurrent::check_runs(tight, system, sink, exact)?;
    Err(SolveError::NoTimeHistory("a test's failing check"))
}

/// The report, the rows streamed before `beside` was called, the report `beside` saw and the
/// rows after, with the self-check on a second thread (`concurrent`) or not.
fn streamed(
    sc: &Scenario,
    check: bool,
    concurrent: bool,
    integrate: fn(&Scenario, &System, &mut dyn RunSink, bool) -> Result<Runs, SolveError>,
) -> String {
    let mut capture = RunCapture::new();
    let beside = |c: &mut RunCapture, r: &Report| format!("{c:?}\n{r:?}");
    match streaming_beside(sc, (check, concurrent), &mut capture, beside, integrate) {
        Ok((report, seen)) => format!("{report:?}\n{seen}\n{capture:?}"),
        Err(e) => format!("error: {e}"),
    }
}

/// Asserts two texts equal, showing where they part.
fn same(a: &str, b: &str, what: &str) {
    let at = a
        .bytes()
        .zip(b.bytes())
        .position(|(x, y)| x != y)
        .unwrap_or(a.len().min(b.len()));
    assert!(
        a == b,
        "{what}: concurrent and sequential differ at\n{}\n{}",
        &a[at.saturating_sub(300)..(at + 200).min(a.len())],
        &b[at.saturating_sub(300)..(at + 200).min(b.len())]
    );
}

/// Cases that take each of the check's orders: touching with the result's run without
/// contact taken (`exact-modal`), never touching (the result its own check), a check that
/// integrates its own run without contact (`rk4`; yielding storeys under `adaptive`).
fn cases() -> Vec<Scenario> {
    vec![
        scenario(&cantilevers("exact-modal", 0.01, 0.0127, 0.6, 2.0)),
        scenario(&cantilevers("exact-modal", 0.01, 0.5, 0.3, 2.0)),
        scenario(&cantilevers("rk4", 0.001, 0.0127, 0.6, 2.0)),
        scenario(&shear("adaptive", 0.01, true)),
    ]
}

#[test]
fn the_check_beside_the_run_is_the_check_after_it() {
    for sc in cases() {
        for check in [false, true] {
            let what = format!("{} {:?} check {check}", sc.title, sc.solver.method);
            let fast = streamed(&sc, check, true, real);
            same(&fast, &streamed(&sc, check, false, real), &what);
            // and the report is simulate_streaming's, the sequential path the suites take
            let mut capture = RunCapture::new();
            let r = simulate_streaming(&sc, check, &mut capture).expect("runs");
            assert!(
                fast.starts_with(&format!("{r:?}\n")) && fast.ends_with(&format!("\n{capture:?}")),
                "{what}: not simulate_streaming's report"
            );
        }
    }
    // the cases take the orders they are meant to (else the test above tests less)
    let checks: Vec<_> = cases()
        .iter()
        .map(|sc| {
            let r = simulate(sc).expect("runs");
            (!r.impact_log.is_empty(), free_run_is_exact(sc))
        })
        .collect();
    assert_eq!(
        checks,
        [(true, true), (false, true), (true, false), (true, false)]
    );
}

#[test]
fn a_check_failing_on_its_thread_is_reported_as_sequentially() {
    for sc in cases() {
        let fast = streamed(&sc, true, true, failing);
        same(&fast, &streamed(&sc, true, false, failing), &sc.title);
        let mut capture = RunCapture::new();
        let beside = |_: &mut RunCapture, _: &Report| ();
        let (r, ()) = streaming_beside(&sc, (true, true), &mut capture, beside, failing)
            .expect("the result's runs succeed");
        // (a result that never touched is its own check: nothing integrated can fail)
        if r.impact_log.is_empty() {
            assert!(r.accuracy.failure.is_none());
            continue;
        }
        assert_eq!(r.accuracy.converged, Some(false));
        let failure = r.accuracy.failure.as_deref().expect("the failure recorded");
        assert!(failure.contains("a test's failing check"), "{failure}");
        assert!(
            r.warnings
                .iter()
                .any(|w| w.contains("a test's failing check")),
            "{:?}",
            r.warnings
        );
    }
}

#[test]
fn a_run_failing_beside_its_check_is_the_same_error() {
    // rk4 beyond its stability limit (set past the input's validation, which refuses it):
    // the result's integration is refused, its check's at dt/√√100 too (still beyond it)
    let mut sc = scenario(&cantilevers("rk4", 0.001, 0.0127, 0.6, 2.0));
    sc.solver.dt = 0.05;
    let fast = streamed(&sc, true, true, real);
    assert!(fast.starts_with("error: "), "{fast}");
    same(&fast, &streamed(&sc, true, false, real), "rk4 refused");
    let mut capture = RunCapture::new();
    let e = simulate_streaming(&sc, true, &mut capture).expect_err("refused");
    assert_eq!(fast, format!("error: {e}"));
}
