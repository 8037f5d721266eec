use super::*;
use crate::input::scenario::Scenario;
use crate::integrate::{Method, SolverSettings};

struct Quiet;
impl Observer for Quiet {
    fn observe(&mut self, _: &System, _: &StepView) {}
}

/// Two cantilevers, Hertz contact at the top, harmonic motion (`law` and its keys in
/// `contact`; `extra` is appended to the scenario).
fn system(contact: &str, period2: f64, extra: &str) -> System {
    let text = format!(
        "[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.3\nmodes = 3\n\
         damping_ratio = 0.01\n[[structure]]\nlength = 10.0\nmass = 2.273e6\n\
         period = {period2}\nmodes = 3\ndamping_ratio = 0.01\n[contact]\n{contact}\n\
         gap = 0.0127\n[ground_motion]\nkind = \"harmonic\"\npga = 0.5\nperiod = 0.8\n\
         [solver]\nmethod = \"adaptive\"\ndt = 1e-3\nduration = 1.0\n{extra}"
    );
    Scenario::from_toml(&text, "case.toml", std::path::Path::new("."))
        .expect("valid scenario")
        .system()
}

/// The step `tr` redone in `m` equal sub-steps of the same collocation.
fn redo(sys: &System, tr: &StepTrace, m: usize) -> (Vec<f64>, Vec<f64>) {
    let gm = GroundModes::new(sys);
    let (aq, av) = modal_tolerances(sys, 1.0);
    let mut w = Work::new(sys, tr.q0.clone(), tr.v0.clone(), aq, av);
    let mut tab = Table::new();
    tab.fill(sys, tr.h / m as f64);
    let mut states = vec![LevelState::default(); sys.levels.len()];
    let mut imp = vec![0.0; sys.levels.len()];
    let (piece, _) = gm.piece_at(tr.t);
    for i in 0..m {
        level_states(sys, &w.q, &w.v, &tr.onset, &mut states);
        let t = tr.t + i as f64 * tab.h;
        let r = step(
            sys, &gm, &tab, &mut w, &tr.onset, &states, t, &piece, &mut imp,
        );
        assert!(r.err.is_finite());
        std::mem::swap(&mut w.q, &mut w.qn);
        std::mem::swap(&mut w.v, &mut w.vn);
    }
    (w.q, w.v)
}

/// Ratios true/estimated local error over every accepted contact step of a run.
fn error_ratios(sys: &System, rtol: f64, dt: f64, duration: f64) -> Vec<(f64, f64, f64)> {
    let mut settings = SolverSettings::new(Method::Adaptive, dt, duration);
    settings.rtol = rtol;
    settings.atol = rtol * crate::integrate::ATOL_PER_RTOL;
    let mut trace = Vec::new();
    Adaptive::run(
        sys,
        &settings,
        &InitialState::default(),
        &mut Quiet,
        Some(&mut trace),
    )
    .expect("runs");
    let (aq, av) = modal_tolerances(sys, settings.atol);
    trace
        .iter()
        .map(|tr| {
            let (q, v) = redo(sys, tr, 256);
            let mut e: f64 = 0.0;
            for j in 0..sys.len() {
                let sq = aq[j] + rtol * tr.q0[j].abs().max(tr.q1[j].abs());
                let sv = av[j] + rtol * tr.v0[j].abs().max(tr.v1[j].abs());
                e = e
                    .max((tr.q1[j] - q[j]).abs() / sq)
                    .max((tr.v1[j] - v[j]).abs() / sv);
            }
            (tr.t, tr.err, e)
        })
        .collect()
}

/// Every accepted contact step's estimate against its true local error (the step redone in
/// 256 sub-steps, whose own error is 256⁻⁴ or less of the step's): within a factor 10 each
/// way. Errors below 1 % of the tolerance are not judged (no step size depends on them), nor
/// below what double precision resolves in a stiff contact step (~1e-13 relative: at
/// rtol = 1e-12 the stiff case's worst steps differ from their redone selves by 1.4e-13,
/// which is why rtol = 1e-12 is not part of this test).
fn assert_estimates_honest(name: &str, sys: &System, rtol: f64, dt: f64, duration: f64) {
    let r = error_ratios(sys, rtol, dt, duration);
    assert!(r.len() > 5, "{name}: only {} contact steps", r.len());
    let floor = 0.01 + 1e-13 / rtol;
    let mut worst_under: f64 = 0.0;
    let mut worst_over: f64 = 0.0;
    for &(t, est, tru) in &r {
        assert!(
            est <= 1.0,
            "{name} rtol {rtol}: accepted step at {t} has error {est}"
        );
        assert!(
            tru <= 10.0 * est + floor,
            "{name} rtol {rtol}: step at t = {t} s: true error {tru:.3e} > 10 × estimate {est:.3e}"
        );
        assert!(
            est <= 10.0 * tru + floor,
            "{name} rtol {rtol}: step at t = {t} s: estimate {est:.3e} > 10 × true error {tru:.3e}"
        );
        if est > floor {
            worst_under = worst_under.max(tru / est);
            worst_over = worst_over.max(est / tru);
        }
    }
    eprintln!(
        "{name} rtol {rtol}: {} contact steps; worst true/est {worst_under:.2}, est/true {worst_over:.2}",
        r.len()
    );
}

#[test]
fn estimate_sees_the_true_local_error_of_contact_steps_stiff() {
    let stiff = system("law = \"hertz\"\nstiffness = 2.808e13", 0.6, "");
    for rtol in [1e-6, 1e-8, 1e-10] {
        assert_estimates_honest("stiff hertz", &stiff, rtol, 1e-3, 1.0);
    }
}

#[test]
fn estimate_sees_the_true_local_error_of_contact_steps_damped() {
    let hd = system(
        "law = \"hertzdamp\"\nstiffness = 2.808e11\nrestitution = 0.6",
        0.6,
        "",
    );
    let kv = system(
        "law = \"kelvin\"\nstiffness = 1e10\nrestitution = 0.6",
        0.6,
        "",
    );
    for rtol in [1e-6, 1e-8, 1e-10] {
        assert_estimates_honest("hertzdamp", &hd, rtol, 1e-3, 1.0);
        assert_estimates_honest("kelvin", &kv, rtol, 1e-3, 1.0);
    }
}

#[test]
fn estimate_sees_the_true_local_error_of_contact_steps_paper() {
    let text = include_str!("../../../examples/paper-c.toml")
        .replace("method = \"rk4\"", "method = \"adaptive\"")
        .replace("duration = 20.0", "duration = 3.0");
    let paper = Scenario::from_toml(&text, "paper-c.toml", std::path::Path::new("."))
        .expect("valid scenario")
        .system();
    for rtol in [1e-6, 1e-8, 1e-10] {
        assert_estimates_honest("paper", &paper, rtol, 1e-3, 3.0);
    }
}
