//! Contact geometry (issue 3): structures of different heights, several contact levels.

use std::path::Path;

use pounding::analysis::simulate::{run_system, simulate};
use pounding::input::scenario::Scenario;
use pounding::integrate::{InitialState, Method, Observer, SolverSettings, StepView, integrate};
use pounding::model::contact::ContactLaw;
use pounding::model::ground_motion::GroundMotion;
use pounding::model::structure::{Cantilever, Damping, Stiffness};
use pounding::model::system::{ContactLevel, System};

fn beam(length: f64, mass: f64, period: f64, zeta: f64) -> Cantilever {
    Cantilever {
        name: "b".into(),
        length,
        mass,
        stiffness: Stiffness::Period(period),
        modes: 4,
        damping: Damping::Modal(vec![zeta]),
    }
}

fn levels() -> [ContactLevel; 2] {
    [
        ContactLevel {
            height: 10.0,
            gap: 0.004,
        },
        ContactLevel {
            height: 6.0,
            gap: 0.002,
        },
    ]
}

/// Two Hertz levels on a 10 m and a 16 m cantilever, no damping, no ground motion: modal plus
/// contact energy is conserved (drift < 1e-6 over 5 s at dt = 2e-5 s) through impacts at both.
#[test]
fn two_levels_conserve_energy() {
    let sys = System::new(
        [
            beam(10.0, 1.5e6, 0.35, 0.0).modal(),
            beam(16.0, 2.5e6, 0.7, 0.0).modal(),
        ],
        &ContactLaw::Hertz {
            stiffness: 2.808e10,
        },
        &levels(),
        GroundMotion::None,
    );
    let n = sys.len();
    let mut v = vec![0.0; n];
    v[0] = 0.3 / sys.structures[0].shape(0, 10.0);
    struct E {
        e0: Option<f64>,
        worst: f64,
        hits: [usize; 2],
        was: [bool; 2],
    }
    impl Observer for E {
        fn observe(&mut self, sys: &System, s: &StepView) {
            let e = sys.modal_energy(s.q, s.v) + sys.contact_energy(s.levels);
            let e0 = *self.e0.get_or_insert(e);
            self.worst = self.worst.max((e - e0).abs() / e0);
            for k in 0..2 {
                let inside = s.levels[k].delta > 0.0;
                if inside && !self.was[k] {
                    self.hits[k] += 1;
                }
                self.was[k] = inside;
            }
        }
    }
    let mut obs = E {
        e0: None,
        worst: 0.0,
        hits: [0; 2],
        was: [false; 2],
    };
    let settings = SolverSettings::new(Method::Rk4, 2e-5, 5.0);
    integrate(
        &sys,
        &settings,
        &InitialState { q: vec![0.0; n], v },
        &mut obs,
    )
    .unwrap();
    assert!(
        obs.hits[0] >= 2 && obs.hits[1] >= 2,
        "impacts at both levels needed: {:?}",
        obs.hits
    );
    assert!(obs.worst < 1e-6, "energy drift {:e}", obs.worst);
}

/// Mirrored two-level problem (swap the structures, reverse the initial velocity): same peaks
/// per structure and the same forces at each level (action and reaction at every level).
#[test]
fn two_levels_mirror() {
    let (a, b) = (beam(10.0, 1.5e6, 0.35, 0.02), beam(16.0, 2.5e6, 0.7, 0.02));
    let law = ContactLaw::Hertz {
        stiffness: 2.808e10,
    };
    let left = System::new([a.modal(), b.modal()], &law, &levels(), GroundMotion::None);
    let right = System::new([b.modal(), a.modal()], &law, &levels(), GroundMotion::None);
    let n = left.len();
    let na = 4;
    let (mut vl, mut vr) = (vec![0.0; n], vec![0.0; n]);
    vl[0] = 0.3 / left.structures[0].shape(0, 10.0); // a moves towards b
    vr[n - na] = -0.3 / right.structures[1].shape(0, 10.0); // mirrored: a (now right) moves left
    let s = SolverSettings::new(Method::Rk4, 5e-5, 3.0);
    let (ra, _) = run_system(
        &left,
        &s,
        &InitialState {
            q: vec![0.0; n],
            v: vl,
        },
        &[10.0, 6.0],
        0.01,
    )
    .unwrap();
    let (rb, _) = run_system(
        &right,
        &s,
        &InitialState {
            q: vec![0.0; n],
            v: vr,
        },
        &[10.0, 6.0],
        0.01,
    )
    .unwrap();
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * x.abs().max(y.abs());
    for k in 0..2 {
        assert!(ra.levels[k].impacts > 0, "level {k} must be hit");
        assert!(
            close(ra.levels[k].peak_force, rb.levels[k].peak_force),
            "level {k}"
        );
        assert!(close(ra.levels[k].peak_w1, rb.levels[k].peak_w2));
        assert_eq!(ra.levels[k].impacts, rb.levels[k].impacts);
    }
}

fn scenario(text: &str) -> Scenario {
    Scenario::from_toml(text, "t.toml", Path::new(".")).unwrap()
}

/// `[contact] gap/height` and one `[[contact.level]]` are the same thing.
#[test]
fn single_level_forms_agree() {
    let base = include_str!("../examples/paper-c.toml");
    let a = simulate(&scenario(&base.replacen(
        "\ngap = 0.0127",
        "\ngap = 0.0127\nheight = 8.0",
        1,
    )))
    .unwrap();
    let b = simulate(&scenario(&base.replacen(
        "\ngap = 0.0127",
        "\n[[contact.level]]\nheight = 8.0\ngap = 0.0127",
        1,
    )))
    .unwrap();
    assert_eq!(a.structures, b.structures);
    assert_eq!(a.contact, b.contact);
}

/// The bundled two-level example: per-level results, totals over levels, outputs.
#[test]
fn two_level_example_outputs() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/two-levels.toml");
    let sc = Scenario::from_file(&path).unwrap();
    let r = simulate(&sc).unwrap();
    assert_eq!(r.levels.len(), 2);
    assert!(r.levels.iter().all(|l| l.impacts > 0));
    assert_eq!(r.contact.impacts, r.levels[0].impacts + r.levels[1].impacts);
    let max = r.levels[0].peak_force.max(r.levels[1].peak_force);
    assert_eq!(r.contact.peak_force, max);
    assert!(
        (r.contact.contact_time - r.levels[0].contact_time - r.levels[1].contact_time).abs()
            < 1e-12
    );
    // the main height is the highest level, and its displacements are the structure peaks
    assert_eq!(
        r.structures[0].peak_displacement,
        r.levels[0].peak_displacement[0]
    );
    let csv = pounding::output::run::history_csv(&r);
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,w1,w2,force,w1_free,w2_free,force_1,force_2"
    );
    for line in lines {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!(
            (v[3] - v[6] - v[7]).abs() <= 1e-9 * v[3].abs().max(1.0),
            "force is the sum: {line}"
        );
    }
    let json: serde_json::Value =
        serde_json::from_str(&pounding::output::run::summary_json(&sc, &r).unwrap()).unwrap();
    assert_eq!(json["levels"].as_array().unwrap().len(), 2);
    assert!(json["levels"][1]["peak_force"].as_f64().unwrap() > 0.0);
}
