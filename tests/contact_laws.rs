//! Contact laws on an isolated two-body impact (issue 3): achieved restitution, energy bookkeeping.

use pounding::analysis::restitution::{TargetLaw, isolated_impact};
use pounding::model::contact::{ContactLaw, HertzDampModel};

const KH: f64 = 2.808e10;
const KL: f64 = 1.0e9;
const M1: f64 = 1.0e6;
const M2: f64 = 3.0e6;

/// Laws built to give a target restitution do so within 2 %: kelvin (c chosen for the clamped
/// impact) and stereomechanical at every e; Jankowski's and Ye–Li–Zhu's published formulas are
/// approximations that hold to 2 % only for e ≥ 0.4 and e ≥ 0.8 respectively (at e = 0.3 they
/// give 0.292 and 0.256 — see `solver_matches_independent_point_mass_impact`, which shows this is
/// the formulas, not the solver).
#[test]
fn built_laws_achieve_their_restitution() {
    let cases: [(TargetLaw, &[f64]); 4] = [
        (TargetLaw::Kelvin, &[0.1, 0.3, 0.5, 0.65, 0.8, 0.9]),
        (TargetLaw::Stereomechanical, &[0.0, 0.3, 0.5, 0.8, 1.0]),
        (TargetLaw::Jankowski, &[0.4, 0.5, 0.65, 0.8, 0.9]),
        (
            TargetLaw::HertzDamp(HertzDampModel::YeLiZhu),
            &[0.8, 0.85, 0.9, 0.95],
        ),
    ];
    for (law, targets) in cases {
        for &e in targets {
            let out = isolated_impact(&law.law(e, KH, KL), M1, M2, 0.5).unwrap();
            let err = (out.restitution - e).abs();
            assert!(
                err <= 0.02 * e.max(0.05),
                "{}: e = {e} gives {}",
                law.label(),
                out.restitution
            );
        }
    }
}

/// A contact force written out from its formula: F(δ, δ̇, m*).
type LawFormula = Box<dyn Fn(f64, f64, f64) -> f64>;

/// An independent check of the damped Hertz-family laws: a point mass m* hitting a rigid wall at
/// v, `m* δ̈ = −F(δ, δ̇)` with the law written out here from its published formula, integrated by a
/// plain RK4 at t_c/200 000. The solver's two-cantilever impact must give the same rebound
/// (to 1e-3; both are converged far below that).
#[test]
fn solver_matches_independent_point_mass_impact() {
    fn rebound(force: impl Fn(f64, f64) -> f64, m: f64, v0: f64, t_c: f64) -> f64 {
        let (mut d, mut dd, mut t) = (0.0f64, v0, 0.0);
        let h = t_c / 200_000.0;
        let acc = |d: f64, dd: f64| {
            if d > 0.0 {
                -force(d, dd).max(0.0) / m
            } else {
                0.0
            }
        };
        loop {
            let (k1x, k1v) = (dd, acc(d, dd));
            let (k2x, k2v) = (
                dd + 0.5 * h * k1v,
                acc(d + 0.5 * h * k1x, dd + 0.5 * h * k1v),
            );
            let (k3x, k3v) = (
                dd + 0.5 * h * k2v,
                acc(d + 0.5 * h * k2x, dd + 0.5 * h * k2v),
            );
            let (k4x, k4v) = (dd + h * k3v, acc(d + h * k3x, dd + h * k3v));
            d += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
            dd += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
            t += h;
            if d <= 0.0 && t > 0.1 * t_c {
                return -dd / v0;
            }
        }
    }
    let v = 0.5;
    for e in [0.3, 0.5, 0.7, 0.9] {
        let laws: [(TargetLaw, LawFormula); 4] = [
            (
                TargetLaw::HertzDamp(HertzDampModel::LankaraniNikravesh),
                Box::new(move |d: f64, dd, _| {
                    KH * d.powf(1.5) * (1.0 + 3.0 * (1.0 - e * e) / 4.0 * dd / v)
                }),
            ),
            (
                TargetLaw::HertzDamp(HertzDampModel::HuntCrossley),
                Box::new(move |d: f64, dd, _| KH * d.powf(1.5) * (1.0 + 1.5 * (1.0 - e) * dd / v)),
            ),
            (
                TargetLaw::HertzDamp(HertzDampModel::YeLiZhu),
                Box::new(move |d: f64, dd, _| {
                    KH * d.powf(1.5) * (1.0 + 8.0 * (1.0 - e) / (5.0 * e) * dd / v)
                }),
            ),
            (
                TargetLaw::Jankowski,
                Box::new(move |d: f64, dd, m: f64| {
                    let xi = 9.0 * 5f64.sqrt() * (1.0 - e * e)
                        / (2.0 * e * (e * (9.0 * std::f64::consts::PI - 16.0) + 16.0));
                    let c = 2.0 * xi * (KH * d.sqrt() * m).sqrt();
                    KH * d.powf(1.5) + if dd > 0.0 { c * dd } else { 0.0 }
                }),
            ),
        ];
        for (law, f) in laws {
            let out = isolated_impact(&law.law(e, KH, KL), M1, M2, v).unwrap();
            let m = out.effective_mass;
            let t_c = 2.9432 * (5.0 * m * v * v / (4.0 * KH)).powf(0.4) / v;
            let reference = rebound(|d, dd| f(d, dd, m), m, v, t_c);
            assert!(
                (out.restitution - reference).abs() < 1e-3,
                "{} at e = {e}: solver {} vs point mass {reference}",
                law.label(),
                out.restitution
            );
        }
    }
}

/// Lankarani–Nikravesh is derived for e near 1: at e = 0.65 it rebounds near 0.78 (issue 3).
#[test]
fn lankarani_nikravesh_overshoots_at_low_restitution() {
    let law = TargetLaw::HertzDamp(HertzDampModel::LankaraniNikravesh).law(0.65, KH, KL);
    let out = isolated_impact(&law, M1, M2, 0.5).unwrap();
    assert!((out.restitution - 0.78).abs() < 0.02, "{}", out.restitution);
}

/// The energy the contact dissipates is the drop in the structures' mechanical energy, which for
/// a rebound at e is ½(1 − e²) m* v². Pure Hertz and linear springs lose nothing.
#[test]
fn contact_energy_bookkeeping() {
    for law in TargetLaw::ALL {
        let out = isolated_impact(&law.law(0.6, KH, KL), M1, M2, 0.5).unwrap();
        let closed = 0.5 * (1.0 - out.restitution.powi(2)) * out.effective_mass * 0.25;
        assert!(
            (out.energy_drop - closed).abs() < 1e-6 * closed,
            "{}: {} vs {closed}",
            law.label(),
            out.energy_drop
        );
        assert!(
            (out.contact_dissipated - out.energy_drop).abs() < 1e-5 * out.energy_drop,
            "{}: dissipated {} vs drop {}",
            law.label(),
            out.contact_dissipated,
            out.energy_drop
        );
    }
    for law in [
        ContactLaw::Hertz { stiffness: KH },
        ContactLaw::Linear { stiffness: KL },
    ] {
        let out = isolated_impact(&law, M1, M2, 0.5).unwrap();
        let e0 = 0.5 * out.effective_mass * 0.25;
        assert!(
            (out.restitution - 1.0).abs() < 1e-6,
            "{law:?}: e = {}",
            out.restitution
        );
        assert!(
            out.energy_drop.abs() < 1e-8 * e0 && out.contact_dissipated.abs() < 1e-8 * e0,
            "{law:?}"
        );
    }
}

/// A linear spring: contact lasts π√(m*/k) (half a period of the contact oscillator) and peaks at
/// v√(k m*).
#[test]
fn linear_impact_duration_and_force() {
    let out = isolated_impact(&ContactLaw::Linear { stiffness: KL }, M1, M2, 0.5).unwrap();
    let m = out.effective_mass;
    let t = std::f64::consts::PI * (m / KL).sqrt();
    assert!(
        (out.duration - t).abs() < 1e-3 * t,
        "{} vs {t}",
        out.duration
    );
    let f = 0.5 * (KL * m).sqrt();
    assert!((out.peak_force - f).abs() < 1e-3 * f);
}

/// No law ever pulls: the force stays ≥ 0 throughout, checked on the stored impacts of a damped
/// law at low restitution, where an unclamped dashpot would pull at the end of the contact.
#[test]
fn forces_are_never_negative() {
    use pounding::integrate::{
        InitialState, Method, Observer, SolverSettings, StepView, integrate,
    };
    use pounding::model::ground_motion::GroundMotion;
    use pounding::model::structure::{Cantilever, Damping, Stiffness};
    use pounding::model::system::{ContactLevel, System};
    struct MinForce(f64);
    impl Observer for MinForce {
        fn observe(&mut self, _: &System, s: &StepView) {
            self.0 = self.0.min(s.levels[0].force);
        }
    }
    let beam = |m: f64| Cantilever {
        name: "b".into(),
        length: 10.0,
        mass: m,
        stiffness: Stiffness::Period(1000.0),
        modes: 1,
        damping: Damping::Modal(vec![0.0]),
    };
    for law in [
        ContactLaw::Kelvin {
            stiffness: KL,
            restitution: 0.3,
        },
        ContactLaw::HertzDamp {
            stiffness: KH,
            restitution: 0.3,
            model: HertzDampModel::YeLiZhu,
        },
    ] {
        let sys = System::new(
            [beam(M1).modal(), beam(M2).modal()],
            &law,
            &[ContactLevel {
                height: 10.0,
                gap: 0.0,
            }],
            GroundMotion::None,
        );
        let phi = sys.structures[0].shape(0, 10.0);
        let mut min = MinForce(0.0);
        let settings = SolverSettings::new(Method::Rk4, 1e-6, 0.1);
        integrate(
            &sys,
            &settings,
            &InitialState {
                q: vec![0.0; 2],
                v: vec![0.5 / phi, 0.0],
            },
            &mut min,
        )
        .unwrap();
        assert_eq!(min.0, 0.0, "{law:?}");
    }
}

/// The stereomechanical law through every method: two soft bodies closing a 1 cm gap at 0.5 m/s
/// rebound at exactly −e·v (the jump is exact; the springs act for 0.02 s before and after, a
/// 1e-7 effect at T = 1000 s), with impulse (1 + e) m* v and the energy balance closed.
#[test]
fn stereomechanical_impact_every_method() {
    use pounding::analysis::simulate::run_system;
    use pounding::integrate::{InitialState, Method, SolverSettings};
    use pounding::model::ground_motion::GroundMotion;
    use pounding::model::structure::{Cantilever, Damping, Stiffness};
    use pounding::model::system::{ContactLevel, System};
    let beam = |m: f64| Cantilever {
        name: "b".into(),
        length: 10.0,
        mass: m,
        stiffness: Stiffness::Period(1000.0),
        modes: 1,
        damping: Damping::Modal(vec![0.0]),
    };
    let e = 0.6;
    let sys = System::new(
        [beam(M1).modal(), beam(M2).modal()],
        &ContactLaw::Stereomechanical { restitution: e },
        &[ContactLevel {
            height: 10.0,
            gap: 0.01,
        }],
        GroundMotion::None,
    );
    let m_star = sys.levels[0].effective_mass;
    let phi1 = sys.structures[0].shape(0, 10.0);
    let v = 0.5;
    for method in [Method::Rk4, Method::ExactModal, Method::Adaptive] {
        let settings = SolverSettings::new(method, 1e-4, 0.04);
        let init = InitialState {
            q: vec![0.0, 0.0],
            v: vec![v / phi1, 0.0],
        };
        let (rec, _) = run_system(&sys, &settings, &init, &[10.0], 1e-3).unwrap();
        assert_eq!(rec.impacts.len(), 1, "{method:?}: {:?}", rec.impacts);
        let p = rec.impacts[0].impulse;
        assert!(
            (p - (1.0 + e) * m_star * v).abs() < 1e-6 * p,
            "{method:?}: impulse {p}"
        );
        // rebound from the last history sample: relative velocity via finite difference of w1 − w2
        let h = &rec.history;
        let k = h.t.len() - 1;
        let rel = ((h.w1[k] - h.w2[k]) - (h.w1[k - 1] - h.w2[k - 1])) / (h.t[k] - h.t[k - 1]);
        assert!(
            (rel + e * v).abs() < 1e-5,
            "{method:?}: rebound {rel} vs {}",
            -e * v
        );
        assert!(
            rec.energy.relative_error < 1e-6,
            "{method:?}: energy {:e}",
            rec.energy.relative_error
        );
        let lost = 0.5 * (1.0 - e * e) * m_star * v * v;
        assert!(
            (rec.energy.contact_dissipated - lost).abs() < 1e-6 * lost,
            "{method:?}"
        );
    }
}
