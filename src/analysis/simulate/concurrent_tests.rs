//! The self-check beside the run ([`super::concurrent`]) against the same on one thread: the
//! report (by its `Debug` text, which writes every f64 so that it reads back exactly), the
//! streamed rows and what `beside` saw; and a check that fails on its thread gives the same
//! verdict and warning as sequentially. (Every file of the run, byte for byte:
//! tests/check_beside.rs, outside the library, which writes them.)

use super::concurrent::{CheckIntegration, CheckProgress, Runs, check_runs, streaming_beside};
use super::reuse_tests::{cantilevers, scenario, shear};
use super::row_beside::{RowRuns, row_check_runs, row_streaming_beside};
use super::*;

/// The self-check's integration failing after its run with contact, as a check run can
/// (e.g. `rk4` refused at a contact, an `adaptive` step that cannot meet its tolerance).
fn failing(
    tight: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    split: Option<&CheckProgress>,
    exact: bool,
) -> Result<Runs, SolveError> {
    check_runs(tight, system, sink, split, exact)?;
    Err(SolveError::NoTimeHistory("a test's failing check"))
}

/// The report, the rows streamed before `beside` was called, the report `beside` saw and the
/// rows after, with the self-check on a second thread (`concurrent`) or not.
fn streamed(sc: &Scenario, check: bool, concurrent: bool, integrate: CheckIntegration) -> String {
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
            let fast = streamed(&sc, check, true, check_runs);
            same(&fast, &streamed(&sc, check, false, check_runs), &what);
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
    let fast = streamed(&sc, true, true, check_runs);
    assert!(fast.starts_with("error: "), "{fast}");
    same(
        &fast,
        &streamed(&sc, true, false, check_runs),
        "rk4 refused",
    );
    let mut capture = RunCapture::new();
    let e = simulate_streaming(&sc, true, &mut capture).expect_err("refused");
    assert_eq!(fast, format!("error: {e}"));
}

/// The check's two runs beside each other (`split`) are the two in a row: each value, and
/// the error the sequential order meets first (the run with contact's), whichever fails; the
/// run without contact on another thread than the run with contact.
#[test]
fn the_checks_two_runs_beside_each_other_are_the_two_in_a_row() {
    use super::concurrent::beside_each_other;
    let progress = CheckProgress::new();
    let err = |what: &'static str| SolveError::NoTimeHistory(what);
    for (w_fails, f_fails) in [(false, false), (false, true), (true, false), (true, true)] {
        let outcome = |split: Option<&CheckProgress>, exact: bool| {
            let here = std::thread::current().id();
            let with = |_: &mut dyn RunSink| if w_fails { Err(err("with")) } else { Ok(1) };
            let free = |_: &mut dyn RunSink| {
                let away = std::thread::current().id() != here;
                if f_fails { Err(err("free")) } else { Ok(away) }
            };
            format!(
                "{:?}",
                beside_each_other(&mut NoSink, split, exact, with, free)
            )
        };
        let split = outcome(Some(&progress), false);
        let want = match (w_fails, f_fails) {
            (true, _) => "Err(NoTimeHistory(\"with\"))",
            (false, true) => "Err(NoTimeHistory(\"free\"))",
            // (integrated on another thread beside the run with contact)
            (false, false) => "Ok((1, Some(true)))",
        };
        assert_eq!(split, want);
        // in a row: the same but for the thread
        let in_a_row = outcome(None, false);
        assert_eq!(in_a_row, want.replace("Some(true)", "Some(false)"));
        // a check that takes the result's run without contact integrates none
        let exact = if w_fails { want } else { "Ok((1, None))" };
        assert_eq!(outcome(Some(&progress), true), exact);
        assert_eq!(outcome(None, true), exact);
    }
}

/// A row of three shear buildings (the middle one yielding when `yielding`) under harmonic
/// motion for 2 s, both gaps `gap` (m) at 7 m.
fn row(method: &str, dt: f64, gap: f64, yielding: bool) -> Scenario {
    let building = |name: &str, n: usize, k: f64, extra: &str| {
        format!(
            "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
             storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\n\
             damping_ratio = 0.05\n{extra}\n"
        )
    };
    let contact = |a: &str, b: &str| {
        format!(
            "[[contact]]\nbetween = [\"{a}\", \"{b}\"]\nlaw = \"hertz\"\nstiffness = 2.0e10\n\
             height = 7.0\ngap = {gap}\n"
        )
    };
    let hysteresis = if yielding {
        "hysteresis = { model = \"bouc-wen\", yield_drifts = 0.0175, post_yield_ratio = 0.05 }"
    } else {
        ""
    };
    scenario(&format!(
        "title = \"row beside\"\n{}{}{}{}{}\
         [ground_motion]\nkind = \"harmonic\"\npga = 0.35\nperiod = 0.8\n\
         [solver]\nmethod = \"{method}\"\ndt = {dt}\nduration = 2.0\noutput_interval = 0.01\n",
        building("A", 3, 3.0e8, ""),
        building("B", 4, 1.2e8, hysteresis),
        building("C", 2, 2.0e8, ""),
        contact("A", "B"),
        contact("B", "C"),
    ))
}

/// Rows that take each of the check's orders: the result's run without contact taken
/// (`exact-modal`), touching or not; the check's own run without contact beside its run with
/// contact (`rk4`; yielding storeys under `adaptive`).
fn rows() -> Vec<Scenario> {
    vec![
        row("exact-modal", 0.01, 0.01, false),
        row("exact-modal", 0.01, 0.5, false),
        row("rk4", 0.002, 0.01, false),
        row("adaptive", 0.01, 0.01, true),
    ]
}

/// The self-check of a row's run failing after its runs, as a check run can.
fn row_failing(
    tight: &Scenario,
    system: &System,
    sink: &mut dyn RunSink,
    split: Option<&CheckProgress>,
    exact: bool,
) -> Result<RowRuns, SolveError> {
    row_check_runs(tight, system, sink, split, exact)?;
    Err(SolveError::NoTimeHistory("a test's failing check"))
}

/// [`streamed`] of a row.
fn row_streamed(
    sc: &Scenario,
    check: bool,
    concurrent: bool,
    integrate: CheckIntegration<RowRuns>,
) -> String {
    let mut capture = RunCapture::new();
    let beside = |c: &mut RunCapture, r: &RowReport| format!("{c:?}\n{r:?}");
    match row_streaming_beside(sc, (check, concurrent), &mut capture, beside, integrate) {
        Ok((report, seen)) => format!("{report:?}\n{seen}\n{capture:?}"),
        Err(e) => format!("error: {e}"),
    }
}

#[test]
fn a_rows_check_beside_its_run_is_the_check_after_it() {
    for (i, sc) in rows().iter().enumerate() {
        for check in [false, true] {
            let what = format!("row {i} check {check}");
            let fast = row_streamed(sc, check, true, row_check_runs);
            same(
                &fast,
                &row_streamed(sc, check, false, row_check_runs),
                &what,
            );
            // and the report is simulate_row_streaming's, the sequential path the suites take
            let mut capture = RunCapture::new();
            let r = simulate_row_streaming(sc, check, &mut capture).expect("runs");
            assert!(
                fast.starts_with(&format!("{r:?}\n")) && fast.ends_with(&format!("\n{capture:?}")),
                "{what}: not simulate_row_streaming's report"
            );
        }
    }
    // the rows take the orders they are meant to (else the test above tests less)
    let orders: Vec<_> = rows()
        .iter()
        .map(|sc| {
            let r = simulate_row(sc).expect("runs");
            (!r.impact_log.is_empty(), free_run_is_exact(sc))
        })
        .collect();
    assert_eq!(
        orders,
        [(true, true), (false, true), (true, false), (true, false)]
    );
}

#[test]
fn a_rows_check_failing_on_its_thread_is_reported_as_sequentially() {
    for (i, sc) in rows().iter().enumerate() {
        let fast = row_streamed(sc, true, true, row_failing);
        same(
            &fast,
            &row_streamed(sc, true, false, row_failing),
            &format!("row {i}"),
        );
        let mut capture = RunCapture::new();
        let beside = |_: &mut RunCapture, _: &RowReport| ();
        let (r, ()) = row_streaming_beside(sc, (true, true), &mut capture, beside, row_failing)
            .expect("the result's runs succeed");
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
fn a_rows_run_failing_beside_its_check_is_the_same_error() {
    // rk4 beyond its stability limit (set past the input's validation, which refuses it):
    // the result's integration is refused, its check's at dt/√10 too (still beyond it)
    let mut sc = row("rk4", 0.002, 0.01, false);
    sc.solver.dt = 0.05;
    let fast = row_streamed(&sc, true, true, row_check_runs);
    assert!(fast.starts_with("error: "), "{fast}");
    same(
        &fast,
        &row_streamed(&sc, true, false, row_check_runs),
        "rk4 refused",
    );
    let mut capture = RunCapture::new();
    let e = simulate_row_streaming(&sc, true, &mut capture).expect_err("refused");
    assert_eq!(fast, format!("error: {e}"));
}
