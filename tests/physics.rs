//! Physics checks against closed-form results, through the public library API.
//! Expected values come from formulas written here, never from the program's own output.

use std::f64::consts::PI;
use std::sync::Arc;

use pounding::analysis::simulate::run_system;
use pounding::integrate::{InitialState, Method, Observer, SolverSettings, StepView, integrate};
use pounding::model::contact::ContactLaw;
use pounding::model::ground_motion::{GroundMotion, Harmonic, Record};
use pounding::model::modal::ModalModel;
use pounding::model::structure::{Cantilever, Damping, Stiffness};
use pounding::model::system::{ContactLevel, System};

fn structure(length: f64, mass: f64, period: f64, modes: usize, damping: Damping) -> Cantilever {
    Cantilever {
        name: "s".into(),
        length,
        mass,
        stiffness: Stiffness::Period(period),
        modes,
        damping,
    }
}

fn rk4(dt: f64, duration: f64) -> SolverSettings {
    SolverSettings::new(Method::Rk4, dt, duration)
}

/// Collects a closure's view of every step.
struct Watch<F: FnMut(&System, &StepView)>(F);
impl<F: FnMut(&System, &StepView)> Observer for Watch<F> {
    fn observe(&mut self, system: &System, step: &StepView) {
        (self.0)(system, step)
    }
}

/// Complex steady-state amplitude W of w(h) under a_g = −P sin Ωt, so that w(t) = Im[W e^{iΩt}]:
/// the load −γ(m a_g + c_a v_g) = Im[F e^{iΩt}] with F_n = γ_n P (m − i c_a/Ω) (docs/model.md §2.4), and
/// W = Σ φ_n(h) F_n/(ω_n² − Ω² + 2iζ_nω_nΩ).
fn steady_amplitude(m: &ModalModel, h: f64, pga: f64, big_omega: f64) -> (f64, f64) {
    let (mut re, mut im) = (0.0, 0.0);
    for n in 0..m.omega.len() {
        let (w, z) = (m.omega[n], m.zeta[n]);
        let (fr, fi) = (m.participation[n] * pga, -m.air_load[n] * pga / big_omega);
        let (dr, di) = (w * w - big_omega * big_omega, 2.0 * z * w * big_omega);
        let d2 = dr * dr + di * di;
        let phi = m.shape(n, h);
        re += phi * (fr * dr + fi * di) / d2;
        im += phi * (fi * dr - fr * di) / d2;
    }
    (re, im)
}

/// No contact, harmonic ground motion: after the transients have decayed (e^{−ζωt} < 1e-10),
/// w(h, t) equals the closed-form steady state Im[W e^{iΩt}] (amplitude and phase, so the sign
/// of the air-damping load is checked too), and the peak of |w| equals |W|. Tolerance 1e-4 of
/// |W|: the peak of a sinusoid sampled every dt is low by at most (Ω dt)²/8 ≈ 5e-6 here, and
/// RK4's phase/amplitude error at ω dt ≤ 0.2 over 60 s is far smaller.
#[test]
fn steady_state_amplitude_matches_modal_sum() {
    for damping in [
        Damping::Modal(vec![0.05]),
        // ζ₁ = 0.036 and 0.055 for the two structures: transients e^{−ζωt} < 1e-11 by t = 60 s
        Damping::Physical {
            strain_rate: 2e-3,
            air: 1.0e5,
        },
    ] {
        let s1 = structure(12.0, 2e6, 0.5, 4, damping.clone());
        let s2 = structure(20.0, 3e6, 0.9, 4, damping.clone());
        let h = 12.0;
        let ground = Harmonic::from_pga_g(0.3, 0.7);
        let sys = System::new(
            [s1.modal(), s2.modal()],
            &ContactLaw::Hertz { stiffness: 1e10 },
            &[],
            GroundMotion::Harmonic(ground),
        );
        let expected = [
            steady_amplitude(&sys.structures[0], h, ground.pga, ground.omega),
            steady_amplitude(&sys.structures[1], h, ground.pga, ground.omega),
        ];
        let size = expected.map(|(re, im): (f64, f64)| re.hypot(im));
        let phi: Vec<Vec<f64>> = sys.structures.iter().map(|m| m.shapes_at(h)).collect();
        let n1 = sys.n1();
        let mut peak = [0.0f64; 2];
        let mut worst = [0.0f64; 2];
        let mut watch = Watch(|_: &System, s: &StepView| {
            if s.t > 60.0 {
                let w = [
                    phi[0]
                        .iter()
                        .zip(&s.q[..n1])
                        .map(|(a, b)| a * b)
                        .sum::<f64>(),
                    phi[1]
                        .iter()
                        .zip(&s.q[n1..])
                        .map(|(a, b)| a * b)
                        .sum::<f64>(),
                ];
                let (sn, cs) = (ground.omega * s.t).sin_cos();
                for i in 0..2 {
                    peak[i] = peak[i].max(w[i].abs());
                    let exact = expected[i].0 * sn + expected[i].1 * cs; // Im[(re + i im)(cos + i sin)]
                    worst[i] = worst[i].max((w[i] - exact).abs());
                }
            }
        });
        integrate(&sys, &rk4(5e-4, 63.0), &InitialState::default(), &mut watch).unwrap();
        for i in 0..2 {
            let rel = (peak[i] - size[i]).abs() / size[i];
            assert!(
                rel < 1e-4,
                "{damping:?} structure {}: peak {} vs {} ({rel:e})",
                i + 1,
                peak[i],
                size[i]
            );
            assert!(
                worst[i] < 1e-4 * size[i],
                "{damping:?} structure {}: waveform off by {:e}",
                i + 1,
                worst[i] / size[i]
            );
        }
    }
}

/// Free decay of the first mode from an initial displacement:
/// η(t) = η₀ e^{−ζωt}(cos ω_d t + ζ/√(1−ζ²) sin ω_d t). RK4 at ω dt = 0.0126 is accurate to
/// ~1e-10 of η₀ over 10 s; tolerance 1e-8·η₀.
#[test]
fn free_decay_matches_damping_ratio() {
    let zeta = 0.03;
    let s = structure(10.0, 1e6, 0.5, 3, Damping::Modal(vec![zeta]));
    let sys = System::new(
        [s.modal(), s.modal()],
        &ContactLaw::Hertz { stiffness: 1e10 },
        &[],
        GroundMotion::None,
    );
    let w = sys.omega()[0];
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let eta0 = 0.2;
    let n = sys.len();
    let mut q = vec![0.0; n];
    q[0] = eta0;
    let mut worst = 0.0f64;
    let mut watch = Watch(|_: &System, s: &StepView| {
        let t = s.t;
        let exact = eta0
            * (-zeta * w * t).exp()
            * ((wd * t).cos() + zeta / (1.0 - zeta * zeta).sqrt() * (wd * t).sin());
        worst = worst.max((s.q[0] - exact).abs());
        // the other modes stay at rest: modes are uncoupled without contact
        assert!(s.q[1..].iter().all(|x| *x == 0.0));
    });
    integrate(
        &sys,
        &rk4(1e-3, 10.0),
        &InitialState { q, v: vec![0.0; n] },
        &mut watch,
    )
    .unwrap();
    assert!(worst < 1e-8 * eta0, "worst error {worst:e}");
}

/// Hertz contact, no damping, no ground motion: modal + contact energy is conserved.
/// Relative drift < 1e-6 over 10 s with many impacts at dt = 2e-5 s.
#[test]
fn hertz_contact_conserves_energy() {
    let undamped = Damping::Modal(vec![0.0]);
    let s1 = structure(10.0, 2e6, 0.5, 3, undamped.clone());
    let s2 = structure(14.0, 3e6, 0.8, 3, undamped);
    let sys = System::new(
        [s1.modal(), s2.modal()],
        &ContactLaw::Hertz {
            stiffness: 2.808e10,
        },
        &[ContactLevel {
            height: 10.0,
            gap: 0.005,
        }],
        GroundMotion::None,
    );
    let n = sys.len();
    let mut v = vec![0.0; n];
    // structure 1's tip moving right at 0.4 m/s in mode 1, structure 2 at rest
    v[0] = 0.4 / sys.structures[0].shape(0, 10.0);
    let mut e0 = None;
    let mut worst = 0.0f64;
    let mut impacts = 0;
    let mut was_in = false;
    let mut watch = Watch(|sys: &System, s: &StepView| {
        let e = sys.modal_energy(s.q, s.v) + sys.contact_energy(s.levels);
        let e0 = *e0.get_or_insert(e);
        worst = worst.max((e - e0).abs() / e0);
        let inside = s.levels[0].delta > 0.0;
        if inside && !was_in {
            impacts += 1;
        }
        was_in = inside;
    });
    integrate(
        &sys,
        &rk4(2e-5, 10.0),
        &InitialState { q: vec![0.0; n], v },
        &mut watch,
    )
    .unwrap();
    assert!(
        impacts >= 5,
        "the test needs repeated impacts, got {impacts}"
    );
    assert!(worst < 1e-6, "energy drift {worst:e}");
}

/// An isolated Hertz impact of two bodies (one mode each, springs so soft they do nothing in
/// the contact time): with m* the reduced mass at the contact point and v the approach speed,
/// δ_max = (5 m* v²/(4 k))^{2/5}, F_max = k δ_max^{3/2}, t_c = 2.9432 δ_max/v, rebound speed v.
/// Each within 0.5 %.
#[test]
fn hertz_impact_matches_analytic_solution() {
    let (m1, m2, k, v) = (1.0e6, 3.0e6, 2.808e10, 0.5);
    let free = Damping::Modal(vec![0.0]);
    // T = 1000 s: the spring force during a 30 ms contact is ~1e-10 of the contact force
    let s1 = structure(10.0, m1, 1000.0, 1, free.clone());
    let s2 = structure(10.0, m2, 1000.0, 1, free);
    let sys = System::new(
        [s1.modal(), s2.modal()],
        &ContactLaw::Hertz { stiffness: k },
        &[ContactLevel {
            height: 10.0,
            gap: 0.0,
        }],
        GroundMotion::None,
    );
    // |φ(L)| = 2/√M, so the mass seen at each tip is M/4
    let m_star = (m1 / 4.0) * (m2 / 4.0) / (m1 / 4.0 + m2 / 4.0);
    let d_max = (5.0 * m_star * v * v / (4.0 * k)).powf(0.4);
    let f_max = k * d_max.powf(1.5);
    let t_c = 2.9432 * d_max / v;
    let phi1 = sys.structures[0].shape(0, 10.0);
    let phi2 = sys.structures[1].shape(0, 10.0);
    let init = InitialState {
        q: vec![0.0, 0.0],
        v: vec![v / phi1, 0.0],
    };
    let (rec, _) = run_system(&sys, &rk4(t_c / 4000.0, 2.0 * t_c), &init, &[10.0], 1e-3).unwrap();
    assert_eq!(rec.impacts.len(), 1, "one impact: {:?}", rec.impacts);
    let imp = rec.impacts[0];
    // the bodies touch at t = 0 (gap 0, δ(0) = 0): the episode starts there, not a step later
    assert!(imp.start.abs() < 1e-12, "start {}", imp.start);
    let rel = |a: f64, b: f64| (a - b).abs() / b;
    assert!(
        rel(imp.end - imp.start, t_c) < 5e-3,
        "t_c {} vs {t_c}",
        imp.end - imp.start
    );
    assert!(
        rel(imp.peak_force, f_max) < 5e-3,
        "F_max {} vs {f_max}",
        imp.peak_force
    );
    assert!(
        rel(imp.max_penetration, d_max) < 5e-3,
        "δ_max {} vs {d_max}",
        imp.max_penetration
    );
    // impulse = change of momentum of body 1 at the contact point: m1*(v − v1_after) = 2 m* v
    assert!(
        rel(imp.impulse, 2.0 * m_star * v) < 5e-3,
        "impulse {}",
        imp.impulse
    );
    // rebound: relative tip velocity after the impact
    let mut rebound = 0.0;
    let mut watch = Watch(|_: &System, s: &StepView| {
        rebound = phi1 * s.v[0] - phi2 * s.v[1];
    });
    integrate(&sys, &rk4(t_c / 4000.0, 2.0 * t_c), &init, &mut watch).unwrap();
    assert!(rel(-rebound, v) < 5e-3, "rebound {rebound} vs −{v}");
}

/// Action and reaction: mirroring the problem (swap the structures and reverse the ground
/// motion) must give the same peaks for each structure and the same contact force. With the
/// paper's sign misprint (+φF on both) this fails.
#[test]
fn mirrored_problem_gives_same_peaks() {
    let a = structure(10.0, 2e6, 0.45, 3, Damping::Modal(vec![0.02]));
    let b = structure(15.0, 3e6, 0.9, 3, Damping::Modal(vec![0.02]));
    let dt = 0.005;
    let accel: Vec<f64> = (0..2001)
        .map(|i| {
            let t = i as f64 * dt;
            4.0 * (2.0 * PI * t / 0.8).sin() * (-0.2 * t).exp()
        })
        .collect();
    let neg: Vec<f64> = accel.iter().map(|x| -x).collect();
    let rec = |s: Vec<f64>| {
        GroundMotion::Record(Arc::new(
            Record::from_samples(dt, s, "test".into()).unwrap(),
        ))
    };
    let law = ContactLaw::Hertz {
        stiffness: 2.808e10,
    };
    let level = [ContactLevel {
        height: 10.0,
        gap: 0.01,
    }];
    let left = System::new([a.modal(), b.modal()], &law, &level, rec(accel));
    let right = System::new([b.modal(), a.modal()], &law, &level, rec(neg));
    let settings = rk4(5e-4, 10.0);
    let (ra, _) = run_system(&left, &settings, &InitialState::default(), &[10.0], 0.01).unwrap();
    let (rb, _) = run_system(&right, &settings, &InitialState::default(), &[10.0], 0.01).unwrap();
    assert!(ra.impacts.len() > 2, "the test needs pounding");
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * x.abs().max(y.abs());
    assert!(
        close(ra.peak[0], rb.peak[1]),
        "{} vs {}",
        ra.peak[0],
        rb.peak[1]
    );
    assert!(
        close(ra.peak[1], rb.peak[0]),
        "{} vs {}",
        ra.peak[1],
        rb.peak[0]
    );
    assert!(close(ra.levels[0].peak_force, rb.levels[0].peak_force));
    assert_eq!(ra.impacts.len(), rb.impacts.len());
}

/// Pounding changes the response at all, and in the direction the paper reports for its
/// T1/T2 = 0.7 case (docs/model.md §4): the stiffer structure 1 is amplified, structure 2 reduced.
#[test]
fn paper_case_c_qualitative() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/paper-c.toml"
    ))
    .unwrap();
    let sc = pounding::input::scenario::Scenario::from_toml(
        &text,
        "paper-c.toml",
        std::path::Path::new("examples"),
    )
    .unwrap();
    let r = pounding::analysis::simulate::simulate(&sc).unwrap();
    assert!(r.structures[0].change_percent > 20.0);
    assert!(r.structures[1].change_percent < -20.0);
    assert!(r.contact.impacts > 0);
    // the peak force never exceeds k_h δ_max^1.5
    assert!(r.contact.peak_force <= 2.808e10 * r.contact.max_penetration.powf(1.5) * (1.0 + 1e-12));
    // `pounding separation` runs only the case without contact: the same gaps and peaks
    let s = pounding::analysis::simulate::separation(&sc).unwrap();
    assert_eq!(s.separation, r.separation);
    assert_eq!(
        s.peaks_no_contact,
        [
            r.structures[0].peak_displacement_no_contact,
            r.structures[1].peak_displacement_no_contact
        ]
    );
    assert_eq!(s.periods[0], r.structures[0].periods[0]);
}
