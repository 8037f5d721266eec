use super::bounds::reach;
use super::station::StoreyForce;
use super::*;
use crate::model::building::{FloorDamping, Floors, ShearBuilding};
use crate::model::modal::{ModalModel, Shapes};

fn shear_building(modes: usize) -> ModalModel {
    ShearBuilding {
        floors: Floors {
            heights: vec![3.0, 6.0, 9.0, 12.0],
            masses: vec![2.0e5, 2.0e5, 1.8e5, 1.5e5],
        },
        storey_stiffnesses: vec![4.0e8, 3.5e8, 3.0e8, 2.0e8],
        modes,
        damping: FloorDamping::Modal(vec![0.05]),
    }
    .modal()
    .expect("building")
    .truncated(modes)
}

/// The bound of the stations' skip ([`reach`]) against the largest |y| of the cubic
/// Hermite interpolant over [0, h], computed in the test from its own closed form: the
/// cubic `y(θ) = y0 + m0 θ + (3Δ − 2m0 − m1) θ² + (m0 + m1 − 2Δ) θ³` (Δ = y1 − y0,
/// m = h·d: the power form of the basis), at 2 001 points and at the roots of its
/// derivative (a quadratic solved here), for random data over many orders of magnitude.
#[test]
fn the_skip_bound_holds_for_every_hermite_cubic() {
    use proptest::prelude::*;
    let mag = || (-6.0f64..2.0, -1.0f64..1.0).prop_map(|(e, s)| s * 10f64.powf(e));
    let data = (mag(), mag(), mag(), mag(), -4.0f64..0.0)
        .prop_map(|(y0, d0, y1, d1, e)| (y0, d0 * 1e2, y1, d1 * 1e2, 10f64.powf(e)));
    proptest!(ProptestConfig::with_cases(4000), |((y0, d0, y1, d1, h) in data)| {
        let (m0, m1, dy) = (h * d0, h * d1, y1 - y0);
        let (c2, c3) = (3.0 * dy - 2.0 * m0 - m1, m0 + m1 - 2.0 * dy);
        let y = |t: f64| y0 + t * (m0 + t * (c2 + t * c3));
        let mut top = y0.abs().max(y1.abs());
        for i in 0..=2000 {
            top = top.max(y(i as f64 / 2000.0).abs());
        }
        // y' = m0 + 2c2 θ + 3c3 θ²: its roots in [0, 1]
        let (a, b, c) = (3.0 * c3, 2.0 * c2, m0);
        let disc = b * b - 4.0 * a * c;
        if a != 0.0 && disc >= 0.0 {
            for r in [(-b + disc.sqrt()) / (2.0 * a), (-b - disc.sqrt()) / (2.0 * a)] {
                if (0.0..=1.0).contains(&r) {
                    top = top.max(y(r).abs());
                }
            }
        }
        let bound = reach(y0, d0, y1, d1, h);
        // (the power form rounds differently from the bound's terms: a few ulps of the
        // largest term, |y| + |m0| + |c2| + |c3|, are allowed)
        let scale = y0.abs() + m0.abs() + c2.abs() + c3.abs();
        prop_assert!(
            top <= bound + 1e-14 * scale,
            "max |y| {top:e} above the bound {bound:e}"
        );
    });
}

/// The stations' skip changes no peak: two floor recorders observe the same runs, one
/// with the skip and one with the full update of every station at every observation
/// ([`FloorRecorder::full`]), and their peaks are equal to the last bit — two cantilevers
/// pounding under a harmonic motion, and two shear buildings (storey springs) under it
/// too, with `exact-modal` (contact sub-steps and free steps) and `rk4`.
/// The pairs both pass tests run: two cantilevers of `modes` modes (T 0.4 and 0.7 s) touching
/// at `top`, and shear buildings of 4 and `storeys` storeys touching at 12 m; Hertz contact
/// at 1 cm, harmonic 0.5 g at 0.5 s. Each with its contact height.
fn touching_pairs(modes: usize, top: f64, storeys: usize) -> Vec<(System, f64)> {
    use crate::model::contact::ContactLaw;
    use crate::model::ground_motion::{GroundMotion, Harmonic};
    use crate::model::structure::{Cantilever, Damping, Stiffness};
    use crate::model::system::ContactLevel;
    let cantilever = |period: f64| {
        Cantilever {
            name: "c".into(),
            length: 10.0,
            mass: 2.0e6,
            stiffness: Stiffness::Period(period),
            modes,
            damping: Damping::Modal(vec![0.05]),
        }
        .modal()
    };
    let law = ContactLaw::Hertz { stiffness: 2.8e10 };
    let ground = GroundMotion::Harmonic(Harmonic::from_pga_g(0.5, 0.5));
    let level = |height: f64| ContactLevel { height, gap: 0.01 };
    [
        ([cantilever(0.4), cantilever(0.7)], top),
        ([shear_building(4), shear_building(storeys)], 12.0),
    ]
    .into_iter()
    .map(|([a, b], height)| {
        (
            System::new([a, b], &law, &[level(height)], ground.clone()),
            height,
        )
    })
    .collect()
}

#[test]
fn the_skip_changes_no_peak() {
    use crate::integrate::{InitialState, Method, Observer, SolverSettings, integrate};
    struct Both(FloorRecorder, FloorRecorder);
    impl Observer for Both {
        fn observe(&mut self, system: &System, s: &StepView) {
            self.0.observe(system, s, None);
            self.1.observe(system, s, None);
        }
    }
    for (sys, height) in touching_pairs(3, 10.0, 2) {
        for (method, dt) in [(Method::ExactModal, 0.01), (Method::Rk4, 0.001)] {
            let mut both = Both(
                FloorRecorder::new(&sys, &[height], 0.01),
                FloorRecorder::new(&sys, &[height], 0.01),
            );
            both.1.full = true;
            let settings = SolverSettings::new(method, dt, 6.0);
            integrate(&sys, &settings, &InitialState::default(), &mut both).unwrap();
            let (skip, full) = (both.0.finish(), both.1.finish());
            assert!(skip[0][0].displacement > 0.0, "the run moved");
            assert_eq!(skip, full, "{method:?}, pair at {height} m");
        }
    }
}

/// The AVX pass of the stations ([`Stations::observe`] compiled for AVX, four stations to a
/// sum's operation) changes no peak and no floor history value: two floor recorders observe
/// the same runs, one with the pass the processor takes and one with the SSE2 pass, and
/// their peaks and rows are equal to the last bit — two cantilevers (ten stations and the
/// contact height: groups of four and the rest) and two shear buildings pounding under a
/// harmonic motion, with `exact-modal` (contact sub-steps, the free flight's Hermite of the
/// accelerations and the jerks) and `rk4`. (Without AVX both take the SSE2 pass.)
#[test]
fn the_avx_pass_changes_no_peak() {
    use crate::integrate::{InitialState, Method, Observer, SolverSettings, integrate};
    #[derive(Default)]
    struct Rows(Vec<(u64, Vec<u64>)>);
    impl crate::recording::history::HistorySink for Rows {
        fn row(&mut self, _: f64, _: [f64; 2], _: &[f64]) {}
        fn floor_row(&mut self, t: f64, values: &[f64]) {
            self.0
                .push((t.to_bits(), values.iter().map(|x| x.to_bits()).collect()));
        }
    }
    struct Both(FloorRecorder, FloorRecorder, Rows, Rows);
    impl Observer for Both {
        fn observe(&mut self, system: &System, s: &StepView) {
            self.0.observe(system, s, Some(&mut self.2));
            self.1.observe(system, s, Some(&mut self.3));
        }
    }
    for (sys, height) in touching_pairs(5, 9.5, 3) {
        for (method, dt) in [(Method::ExactModal, 0.01), (Method::Rk4, 0.001)] {
            let mut both = Both(
                FloorRecorder::new(&sys, &[height], 0.01),
                FloorRecorder::new(&sys, &[height], 0.01),
                Rows::default(),
                Rows::default(),
            );
            for st in &mut both.1.stations {
                st.wide = false;
            }
            let settings = SolverSettings::new(method, dt, 6.0);
            integrate(&sys, &settings, &InitialState::default(), &mut both).unwrap();
            let (rows, narrow_rows) = (std::mem::take(&mut both.2), std::mem::take(&mut both.3));
            let (wide, narrow) = (both.0.finish(), both.1.finish());
            assert!(wide[0][0].displacement > 0.0, "the run moved");
            assert!(rows.0.len() > 500, "{} rows", rows.0.len());
            assert_eq!(wide, narrow, "{method:?}, pair at {height} m");
            assert!(
                rows.0 == narrow_rows.0,
                "{method:?}, pair at {height} m: rows"
            );
        }
    }
}

/// A shear building's modes, all of them or the first two, are recognised as storey
/// springs with its own stiffnesses (to 1e-9), and the modes' equivalent static forces
/// `Σ_{g ≥ j} m_g φ_n(g) ω_n²` are `k_j (φ_n(j) − φ_n(j−1))` mode by mode; a structure whose
/// modes are not a chain's (the second mode's shape altered, so K φ ≠ ω² M φ for a chain)
/// keeps the modal rows.
#[test]
fn a_shear_buildings_modes_are_its_storey_springs() {
    for modes in [4, 2] {
        let m = shear_building(modes);
        let st = Stations::new(&m, &[], &[], 0);
        let StoreyForce::Springs(k) = &st.force else {
            panic!("{modes} modes: not recognised as springs");
        };
        for (got, want) in k.iter().zip([4.0e8, 3.5e8, 3.0e8, 2.0e8]) {
            assert!((got - want).abs() <= 1e-9 * want, "{got} vs {want}");
        }
    }
    let mut m = shear_building(4);
    if let Shapes::Floors { values, .. } = &mut m.shapes {
        values[1][2] *= 1.01;
    }
    let st = Stations::new(&m, &[], &[], 0);
    assert!(matches!(st.force, StoreyForce::Rows(_)));
}
