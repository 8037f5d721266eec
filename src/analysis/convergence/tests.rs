//! Unit tests of the convergence study: its verdicts on rows built by hand, and a short study.

use super::*;

/// A cheap scenario: 2 s of the paper's case. Whatever the study concludes, it is
/// consistent: a recommendation only with both ladders converged, made of rows that are,
/// with every finer row, within the tolerance of the finest, and never the finest alone.
#[test]
fn study_of_a_short_case_recommends_within_tolerance() {
    let text = include_str!("../../../examples/paper-c.toml")
        .replace("duration = 20.0", "duration = 2.0")
        .replace("method = \"rk4\"", "method = \"exact-modal\"");
    let sc = Scenario::from_toml(&text, "t", ".".as_ref()).unwrap();
    let tol = 0.05;
    let t = convergence(&sc, tol, |_| {});
    assert_eq!(t.modes.len(), MODE_LADDER.len());
    assert_eq!(t.steps.len(), DT_LADDER.len());
    let last = t.steps.last().unwrap();
    assert_eq!(last.change, [0.0; 3]);
    assert_eq!(t.converged, t.modes_converged && t.steps_converged);
    assert_eq!(t.converged, t.recommended.is_some());
    match t.recommended {
        Some(r) => {
            let i = t.modes.iter().position(|x| x.modes == r.modes).unwrap();
            assert!(i + 1 < t.modes.len(), "never the most modes alone");
            assert!(t.modes[i..].iter().all(|x| x.worst_change() <= tol));
            let j = t.steps.iter().position(|x| x.dt == r.dt).unwrap();
            assert!(j + 1 < t.steps.len(), "never the finest step alone");
            assert!(t.steps[j..].iter().all(|x| x.worst_change() <= tol));
            assert_eq!(r.method, Method::ExactModal);
        }
        None => assert!(!t.notes.is_empty()),
    }
    assert!(!t.recommendation.is_empty());
}

fn row(modes: usize, change: f64, failure: Option<&str>) -> Row {
    let mut r = empty_row(
        modes,
        &SolverSettings::new(Method::ExactModal, 1e-3, 1.0),
        2,
    );
    r.change = vec![0.0, change, 0.0];
    r.failure = failure.map(str::to_string);
    r
}

/// The verdict of a ladder, on rows built by hand.
#[test]
fn a_ladder_converges_only_when_its_two_finest_runs_agree() {
    let label = |r: &Row| format!("{} modes", r.modes);
    // the two finest differ by 2 % > 1 %: not converged, even though the finest agrees
    // with itself and a coarse row happens to agree with it
    let rows = [row(1, 0.001, None), row(2, 0.02, None), row(3, 0.0, None)];
    let v = judge(&rows, 0.01, label);
    assert_eq!(v.pick, None);
    let why = v.why.unwrap();
    assert!(
        why.contains("2 modes and 3 modes") && why.contains("2.000 %"),
        "{why}"
    );
    assert!(why.contains("peak w2"), "{why}");
    // the coarsest row from which all are within: index 1, not 0 (row 0 is 5 % off)
    let rows = [row(1, 0.05, None), row(2, 0.004, None), row(3, 0.0, None)];
    assert_eq!(judge(&rows, 0.01, label).pick, Some(1));
    // a row that agrees but has a failed row after it is not picked
    let rows = [
        row(1, 0.001, None),
        row(2, f64::NAN, Some("refused")),
        row(3, 0.0, None),
    ];
    let v = judge(&rows, 0.01, label);
    assert_eq!(v.pick, None);
    assert!(
        v.why
            .unwrap()
            .contains("second finest run (2 modes) failed")
    );
    // a failed finest run
    let rows = [row(1, 0.0, None), row(2, f64::NAN, Some("refused"))];
    assert!(
        judge(&rows, 0.01, label)
            .why
            .unwrap()
            .contains("finest run (2 modes) failed")
    );
    // one run: nothing to compare
    assert_eq!(judge(&rows[..1], 0.01, label).pick, None);
}

/// A yielding building's quantities count in the verdict: headline peaks that agree do
/// not make a ladder converged when the hysteretic energy of the two finest runs differs by
/// 2 % (named in the reason), and the coarsest row picked must be within on them too.
#[test]
fn a_ladder_judges_the_yielding_quantities_too() {
    let label = |r: &Row| format!("{} modes", r.modes);
    let yielding = |change: [f64; 3]| {
        let mut r = row(0, 0.0, None);
        r.yield_change = vec![None, Some(change)];
        r
    };
    let mut rows = [
        yielding([0.0; 3]),
        yielding([0.0, 0.0, 0.02]),
        yielding([0.0; 3]),
    ];
    for (i, r) in rows.iter_mut().enumerate() {
        r.modes = i + 1;
    }
    let v = judge(&rows, 0.01, label);
    assert_eq!(v.pick, None);
    let why = v.why.unwrap();
    assert!(
        why.contains("2.000 % in the hysteretic energy of 2"),
        "{why}"
    );
    rows[0].yield_change[1] = Some([0.05, 0.0, 0.0]);
    rows[1].yield_change[1] = Some([0.004, 0.003, 0.002]);
    assert_eq!(judge(&rows, 0.01, label).pick, Some(1));
    assert_eq!(rows[0].worst_change(), 0.05);
    let names: Vec<String> = rows[0].changes().into_iter().map(|(n, _)| n).collect();
    assert_eq!(
        names,
        [
            "peak w1",
            "peak w2",
            "peak force",
            "peak ductility of 2",
            "residual drift of 2",
            "hysteretic energy of 2"
        ]
    );
}
