use super::*;
use crate::input::scenario::Scenario;
use crate::integrate::hysteretic::tests::redo;
use crate::integrate::{Method, SolverSettings};

struct Quiet;
impl Observer for Quiet {
    fn observe(&mut self, _: &System, _: &StepView) {}
}

/// Two cantilevers (T1 = 0.3 s, T2 = 0.6 s, `modes` modes), contact `contact` at the top,
/// harmonic motion 0.5 g at Tg = 0.8 s.
fn system(contact: &str, modes: usize) -> System {
    let text = format!(
        "[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.3\nmodes = {modes}\n\
         damping_ratio = 0.01\n[[structure]]\nlength = 10.0\nmass = 2.273e6\n\
         period = 0.6\nmodes = {modes}\ndamping_ratio = 0.01\n[contact]\n{contact}\n\
         gap = 0.0127\n[ground_motion]\nkind = \"harmonic\"\npga = 0.5\nperiod = 0.8\n\
         [solver]\nmethod = \"exact-modal\"\ndt = 1e-3\nduration = 1.0\n"
    );
    Scenario::from_toml(&text, "case.toml", std::path::Path::new("."))
        .expect("valid scenario")
        .system()
}

fn trace(sys: &System, rtol: f64, dt: f64, duration: f64) -> Vec<StepTrace> {
    let settings = SolverSettings::new(Method::ExactModal, dt, duration).with_rtol(rtol);
    let mut trace = Vec::new();
    super::run(
        sys,
        &settings,
        &InitialState::default(),
        &mut Quiet,
        Some(&mut trace),
    )
    .expect("runs");
    trace
}

/// One step of length h of both schemes from the start of `tr`: every level's (δ, δ̇) at
/// the end by the propagated scheme and by the companion.
fn one_step(sys: &System, tr: &StepTrace, h: f64) -> Vec<((f64, f64), (f64, f64))> {
    let settings = SolverSettings::new(Method::ExactModal, 1e-3, 10.0);
    let mut quiet = Quiet;
    let mut r = Elastic::new(
        sys,
        &settings,
        &mut quiet,
        None,
        tr.t,
        tr.q0.clone(),
        tr.v0.clone(),
        Some(&tr.onset),
    );
    // (a contiguous previous step is not needed: the first guess only speeds Newton up)
    let (piece, _, _) = r.piece();
    r.trial(None, h, &piece).expect("converges");
    (0..sys.levels.len())
        .map(|k| (r.nodal8[k * 4 + 3], r.nodal6[k * 3 + 2]))
        .collect()
}

/// Every level's (δ, δ̇) at the end of `tr`'s interval (length h) by `m` RK4 sub-steps of
/// the full right-hand side from its start (independent of the collocation).
fn reference(sys: &System, tr: &StepTrace, h: f64, m: usize) -> Vec<(f64, f64)> {
    let t = StepTrace { h, ..tr.clone() };
    let y = redo(sys, &t, m);
    let n = sys.len();
    (0..sys.levels.len())
        .map(|k| {
            let c = sys.coupling(k);
            (-dot(c, &y[..n]) - sys.levels[k].gap, -dot(c, &y[n..2 * n]))
        })
        .collect()
}

/// The contact step that starts closest to an impact's deepest point (δ̇ = 0) without an
/// event inside, from a run at rtol 1e-10: a start inside a long stretch of contact.
fn deepest(sys: &System) -> StepTrace {
    let c = sys.coupling(0);
    trace(sys, 1e-10, 1e-3, 1.0)
        .into_iter()
        .filter(|s| !s.kink)
        .min_by(|a, b| dot(c, &a.v0).abs().total_cmp(&dot(c, &b.v0).abs()))
        .expect("contact steps")
}

/// The observed order of the local error of both schemes: one step of ω_c·h = 1, ½, ¼
/// (⅛ for the companion) from the same state inside an impact, against 4000 RK4 steps of
/// the full right-hand side over the same interval (its own error < 1e-15 of δ here). The
/// propagated scheme's local error goes like h⁹ (order 8; Lobatto IIIA, 5 nodes) and the
/// companion's like h⁷ (order 6): mean observed exponents in [8, 10] and [6, 8.5] on
/// linear, Kelvin, Hertz (the paper's stiffness) and damped Hertz contact (measured 8.4,
/// 8.8, 9.4, 9.3 and 7.1, 8.1, 7.4, 6.6: the Hertz law's δ^{3/2} and the damped laws' rate
/// terms are not polynomials, so the asymptotic exponents come later than on the linear
/// law's 7.0–7.2), and the propagated error at least 10× below the companion's from ω_c·h
/// = ½ on (measured 30–800×). Without this gap the estimate would not bound the kept
/// solution's error.
/// Every level's (δ, δ̇) at the end of `tr` by `m` equal steps of the propagated scheme.
fn substepped(sys: &System, tr: &StepTrace, m: usize) -> Vec<(f64, f64)> {
    let settings = SolverSettings::new(Method::ExactModal, 1e-3, 10.0);
    let mut quiet = Quiet;
    let mut r = Elastic::new(
        sys,
        &settings,
        &mut quiet,
        None,
        tr.t,
        tr.q0.clone(),
        tr.v0.clone(),
        Some(&tr.onset),
    );
    let h = tr.h / m as f64;
    for _ in 0..m {
        let (piece, _, _) = r.piece();
        let trial = r.trial(None, h, &piece).expect("converges");
        let t_end = r.t + h;
        r.accept(&piece, trial, t_end);
    }
    (0..sys.levels.len())
        .map(|k| (r.states[k].delta, r.states[k].delta_dot))
        .collect()
}

/// The guard: with the kink floor off (`kink_floor_ulps = 0`, the defect of
/// tests/data/jankowski-kink.toml back: a Jankowski switch re-found at every step's start,
/// steps that do not move time) the run stops at once with `StepFailed`, naming exact-modal,
/// the instant (t = 9.6066 s, where the located switch sits), the level in contact (the
/// top, level 1: the only one penetrating there) and `adaptive`; with the floor on it runs
/// to the end.
#[test]
fn a_step_that_cannot_advance_time_stops_the_run() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let text = include_str!("../../../../tests/data/jankowski-kink.toml");
    let suite = Scenario::from_toml(text, "jankowski-kink.toml", &dir).expect("valid");
    let members = suite.suite.as_ref().expect("a suite");
    let f = members.records[0].factor.expect("factor");
    let sc = members.member_scenario(&suite, 0, f).expect("scales");
    let sys = sc.system();
    // (the self-check's tolerance, 100× tighter than the default: the run that stalled)
    let settings = sc.solver.with_rtol(1e-10);
    let run = |floor: f64| {
        let (q0, v0) = InitialState::default().resolved(sys.len());
        let mut quiet = Quiet;
        let mut r = Elastic::new(&sys, &settings, &mut quiet, None, 0.0, q0, v0, None);
        r.kink_floor_ulps = floor;
        r.drive()
    };
    let e = run(0.0).expect_err("stops");
    let SolveError::StepFailed {
        method,
        t,
        level,
        height,
        reason,
        alternative,
        h,
    } = e.clone()
    else {
        panic!("{e}");
    };
    assert_eq!(
        (method, level, height, reason, alternative),
        (
            "exact-modal",
            Some(1),
            Some(14.0),
            crate::integrate::StepFailure::NoProgress,
            "adaptive"
        ),
        "{e}"
    );
    // (the located switch, to the ms of the trace that found it; the step that did not
    // advance t there was 2.9e-25 s, below t's resolution of 1.8e-15 s)
    assert!((t - 9.6066).abs() < 1e-3, "{e}");
    assert!(h > 0.0 && t + h == t, "{e}");
    let msg = e.to_string();
    for part in [
        "exact-modal",
        "t = 9.606",
        "contact level 1",
        "\"adaptive\"",
    ] {
        assert!(msg.contains(part), "{part} in {msg}");
    }
    let stats = run(KINK_FLOOR_ULPS).expect("runs with the floor");
    assert!(stats.steps > 0);
}

#[test]
fn local_errors_are_of_orders_eight_and_six() {
    for (name, contact) in [
        ("linear", "law = \"linear\"\nstiffness = 1e9"),
        (
            "kelvin",
            "law = \"kelvin\"\nstiffness = 1e9\nrestitution = 0.8",
        ),
        ("hertz", "law = \"hertz\"\nstiffness = 2.808e10"),
        (
            "hertzdamp",
            "law = \"hertzdamp\"\nstiffness = 2.808e11\nrestitution = 0.6",
        ),
    ] {
        let sys = system(contact, 3);
        let start = deepest(&sys);
        let lv = &sys.levels[0];
        let d0 = -dot(sys.coupling(0), &start.q0) - lv.gap;
        let wc = (lv.force.tangent_stiffness(d0) / lv.effective_mass).sqrt();
        let errors: Vec<(f64, f64)> = [1.0, 0.5, 0.25, 0.125]
            .iter()
            .map(|x| {
                let h = x / wc;
                let r = reference(&sys, &start, h, 4000);
                let s = one_step(&sys, &start, h);
                ((s[0].0.0 - r[0].0).abs(), (s[0].1.0 - r[0].0).abs())
            })
            .collect();
        let order = |a: f64, b: f64| (a / b).log2();
        let p8 = 0.5 * (order(errors[0].0, errors[1].0) + order(errors[1].0, errors[2].0));
        let p6 = 0.5 * (order(errors[1].1, errors[2].1) + order(errors[2].1, errors[3].1));
        eprintln!(
            "{name}: local error exponents: propagated {p8:.2}, companion {p6:.2}; errors {errors:?}"
        );
        assert!(
            (8.0..=10.0).contains(&p8),
            "{name}: propagated {p8} ({errors:?})"
        );
        assert!(
            (6.0..=8.5).contains(&p6),
            "{name}: companion {p6} ({errors:?})"
        );
        for e in &errors[1..3] {
            assert!(e.0 * 10.0 <= e.1, "{name}: {errors:?}");
        }
    }
}

/// Every accepted contact step's estimate against its true local error (the step redone
/// from its start by 2000 RK4 steps of the full right-hand side, its own error < 1e-4 of
/// the tolerance here), both measured in the estimate's scaled norm on every level's δ and
/// δ̇: on a stiff (1000× the paper's), the paper's, a damped Hertz and a Kelvin contact at
/// rtol 1e-4, 1e-6 and 1e-8,
/// - the kept (8th-order) solution's true error is never above the estimate on a step
///   where the force is smooth (the estimate is an upper bound there, by local
///   extrapolation; measured ≤ 0.36), and never more than 3× above it on a step that
///   straddles a release or an onset, which steps are not ended at unless they fail
///   (measured ≤ 1.50: there both schemes err on the same kink);
/// - the estimate is the companion's (6th-order) true error: never more than 3× below it
///   (measured ≤ 2.50) and on a median within 3× of it (measured 0.74–1.0 where at least
///   ten steps are above the floor);
///
/// every accepted step's estimate ≤ 1. Errors below 1 % of the tolerance are not judged
/// (no step length depends on them). Before the kinks of Kelvin's clamp (kδ + cδ̇ = 0
/// inside contact) were located, both schemes erred on them alike and the true error
/// reached 6× the estimate.
#[test]
fn estimate_bounds_the_true_local_error_of_contact_steps() {
    let cases = [
        ("stiff hertz", "law = \"hertz\"\nstiffness = 2.808e13"),
        ("paper hertz", "law = \"hertz\"\nstiffness = 2.808e10"),
        (
            "hertzdamp",
            "law = \"hertzdamp\"\nstiffness = 2.808e11\nrestitution = 0.6",
        ),
        (
            "kelvin",
            "law = \"kelvin\"\nstiffness = 1e10\nrestitution = 0.6",
        ),
    ];
    for (name, contact) in cases {
        let sys = system(contact, 3);
        for rtol in [1e-4, 1e-6, 1e-8] {
            let settings = SolverSettings::new(Method::ExactModal, 1e-3, 1.0).with_rtol(rtol);
            let tol = SubstepTolerance::new(&sys, &settings);
            let steps = trace(&sys, rtol, 1e-3, 1.0);
            assert!(
                steps.len() > 20,
                "{name}: only {} contact steps",
                steps.len()
            );
            let (mut kept_over, mut kink_over, mut comp_under) = (0.0f64, 0.0f64, 0.0f64);
            let mut ratios = Vec::new();
            let floor = 0.01;
            for tr in &steps {
                assert!(
                    tr.err <= 1.0,
                    "{name} rtol {rtol}: accepted step at {}: {}",
                    tr.t,
                    tr.err
                );
                // (RK4 cannot start on the jump of Kelvin's force at a located onset, c·δ̇
                // from δ = 0⁺: its first stage sees δ ≤ 0 and no force, an error of the
                // reference, not of the step; there the step is redone in 64 steps of the
                // same collocation, error 64⁻⁹ of its own)
                let at_onset = (0..sys.levels.len()).any(|k| {
                    let c = sys.coupling(k);
                    let d = -dot(c, &tr.q0) - sys.levels[k].gap;
                    (-EVENT_TOL..=0.0).contains(&d) && -dot(c, &tr.v0) > 0.0
                });
                let r = if at_onset && sys.levels[0].force.kink(1.0, 0.0, 1.0).is_some() {
                    substepped(&sys, tr, 64)
                } else {
                    reference(&sys, tr, tr.h, 2000)
                };
                let (mut kept, mut comp) = (0.0f64, 0.0f64);
                for k in 0..sys.levels.len() {
                    let c = sys.coupling(k);
                    let lv = &sys.levels[k];
                    let (d0, dd0) = (-dot(c, &tr.q0) - lv.gap, -dot(c, &tr.v0));
                    let sd = tol.atol + tol.rtol * (d0 + lv.gap).abs();
                    let sv = tol.atol_rate + tol.rtol * dd0.abs().max(tr.onset[k]);
                    let (d1, dd1) = (-dot(c, &tr.q1) - lv.gap, -dot(c, &tr.v1));
                    kept = kept
                        .max((d1 - r[k].0).abs() / sd)
                        .max((dd1 - r[k].1).abs() / sv);
                    let (c0, c1) = tr.companion[k];
                    comp = comp
                        .max((c0 - r[k].0).abs() / sd)
                        .max((c1 - r[k].1).abs() / sv);
                }
                if tr.err.max(kept).max(comp) <= floor {
                    continue;
                }
                let est = tr.err.max(floor);
                // a level's δ changing sign inside: a kink the two schemes err on alike
                let straddles = (0..sys.levels.len()).any(|k| {
                    let c = sys.coupling(k);
                    let gap = sys.levels[k].gap;
                    let (a, b) = (-dot(c, &tr.q0) - gap, -dot(c, &tr.q1) - gap);
                    (a > 0.0) != (b > 0.0)
                });
                if straddles {
                    kink_over = kink_over.max(kept / est);
                } else {
                    kept_over = kept_over.max(kept / est);
                }
                comp_under = comp_under.max(comp / est);
                if comp > floor && tr.err > floor {
                    ratios.push(tr.err / comp);
                }
            }
            ratios.sort_by(f64::total_cmp);
            let median = ratios.get(ratios.len() / 2).copied().unwrap_or(f64::NAN);
            eprintln!(
                "{name} rtol {rtol}: {} steps; kept true/est ≤ {kept_over:.3} (≤ {kink_over:.2} straddling a release or an onset); companion true/est ≤ {comp_under:.2}, est/true median {median:.2} over {}",
                steps.len(),
                ratios.len()
            );
            assert!(kept_over <= 1.0, "{name} rtol {rtol}: kept {kept_over}");
            assert!(
                kink_over <= 3.0,
                "{name} rtol {rtol}: kept at a kink {kink_over}"
            );
            assert!(
                comp_under <= 3.0,
                "{name} rtol {rtol}: companion {comp_under}"
            );
            // (a median needs steps whose errors are not all far below the tolerance: at
            // rtol 1e-4 the smooth laws' steps mostly are)
            assert!(
                ratios.len() < 10 || (1.0 / 3.0..=3.0).contains(&median),
                "{name} rtol {rtol}: median {median}"
            );
        }
    }
}
