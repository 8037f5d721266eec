//! A row of buildings (issue 29): invariances of the engine for N structures, an independent
//! integration in physical coordinates, and the scenario's refusals.

// Index loops over the dofs of a small physical model read like the equations they form.
#![allow(clippy::needless_range_loop)]

mod common;

use std::path::Path;

use pounding::analysis::simulate::{RowReport, simulate, simulate_row};
use pounding::input::scenario::Scenario;
use pounding::model::ground_motion::{GroundMotion, Harmonic};
use pounding::model::structure::Structure;
use pounding::model::system::System;
use pounding::recording::recorder::Recorder;

fn scenario(text: &str) -> Scenario {
    Scenario::from_toml(text, "row.toml", Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

fn refused(text: &str) -> String {
    match Scenario::from_toml(text, "row.toml", Path::new(".")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// A shear building of `n` storeys of 3.5 m named `name`, all its modes kept.
fn building(name: &str, n: usize, k: f64, extra: &str) -> String {
    format!(
        "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
         storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\ndamping_ratio = 0.05\n\
         modes = {n}\n{extra}\n"
    )
}

/// A `[[contact]]` between `a` and `b` at `h` with gap `gap` (m), Hertz.
fn contact(a: &str, b: &str, h: f64, gap: f64) -> String {
    format!(
        "[[contact]]\nbetween = [\"{a}\", \"{b}\"]\nlaw = \"hertz\"\nstiffness = 2.0e10\n\
         height = {h}\ngap = {gap}\n"
    )
}

const HARMONIC: &str = "[ground_motion]\nkind = \"harmonic\"\npga = 0.35\nperiod = 0.8\n";

fn solver(method: &str, duration: f64) -> String {
    format!("[solver]\nmethod = \"{method}\"\ndt = 0.002\nduration = {duration}\n")
}

/// A row of three where the second gap never closes is the pair of the first two and the
/// third alone: the first pair's numbers to the last digit (the second pair's coupling rows
/// are zero over the first pair's modes and its force is exactly 0, so every operation on
/// them is the pair's own), and the third building as it moves alone.
#[test]
fn a_row_whose_second_gap_never_closes_is_the_pair_and_the_third_alone() {
    // 4 + 5 modes: the pair's rows are long enough for the same summation path as the row's;
    // C the most flexible of the three: exact-modal's tolerance on δ̇ is atol times the
    // largest first-mode ω of the system's structures, which a stiffer third building would
    // change for the first pair too — within its tolerance, not to the last digit
    let row = scenario(&format!(
        "{}{HARMONIC}{}",
        common::row_flexible_end(0.01, 10.0),
        solver("exact-modal", 6.0)
    ));
    let pair = row.pair(0);
    let r = simulate_row(&row).expect("row");
    let p = simulate(&pair).expect("pair");
    assert!(p.contact.impacts > 0, "the test needs pounding in the pair");
    assert_eq!(r.pairs[1].contact.impacts, 0);
    // the first pair, to the last digit
    assert_eq!(r.pairs[0].contact, p.contact);
    assert_eq!(r.pairs[0].levels, p.levels);
    assert_eq!(r.pairs[0].separation, p.separation);
    for i in 0..2 {
        assert_eq!(r.structures[i], p.structures[i], "structure {}", i + 1);
    }
    assert_eq!(r.impact_log.len(), p.impact_log.len());
    for (x, y) in r.impact_log.iter().zip(&p.impact_log) {
        assert_eq!((x.pair, x.level), (0, y.level));
        assert_eq!(
            (x.start, x.end, x.peak_force, x.impulse, x.approach_speed),
            (y.start, y.end, y.peak_force, y.impulse, y.approach_speed)
        );
    }
    // the third alone: a system of that building only, no contact
    let Structure::Floors(_) = &row.structures[2] else {
        panic!("a building")
    };
    let alone = System::row(
        vec![row.structures[2].modal()],
        &[],
        row.ground_motion.clone(),
    );
    let mut rec = Recorder::for_row(&alone, &[], &[], row.output_interval, row.solver.duration);
    pounding::integrate::integrate(&alone, &row.solver, &Default::default(), &mut rec)
        .expect("alone");
    let alone = rec.finish();
    let third = &r.structures[2];
    assert_eq!(third.floors.len(), alone.floors[0].len());
    for (f, g) in third.floors.iter().zip(&alone.floors[0]) {
        // without contact: the same steps, the same numbers
        assert_eq!(f.peak_displacement_no_contact, g.displacement);
        assert_eq!(f.peak_acceleration_no_contact, g.acceleration);
        assert_eq!(f.peak_drift_no_contact, g.drift);
        // with contact the row's steps are cut at the first pair's impacts, where the third's
        // modes are propagated exactly over the pieces of a step: equal to round-off of the
        // propagators, accumulated over the run (1e-9 of the peak)
        for (x, y) in [
            (f.peak_displacement, g.displacement),
            (f.peak_drift, g.drift),
        ] {
            // (measured: 4e-11 after ~3000 steps of which hundreds are cut)
            assert!((x - y).abs() <= 1e-9 * y, "{x} vs {y}");
        }
        // the acceleration is taken at the observations (not refined between them): the
        // row's extra ones, at the first pair's sub-steps, can only find a larger sample
        assert!(f.peak_acceleration >= g.acceleration * (1.0 - 1e-9));
    }
}

fn assert_close(x: f64, y: f64, rel: f64, what: &str) {
    if std::env::var_os("ROWS_DEBUG").is_some() {
        eprintln!(
            "{what}: {:e}",
            (x - y).abs() / x.abs().max(y.abs()).max(1e-300)
        );
        return;
    }
    assert!(
        (x - y).abs() <= rel * x.abs().max(y.abs()).max(1e-300),
        "{what}: {x} vs {y} (relative {:e})",
        (x - y).abs() / x.abs().max(y.abs())
    );
}

/// The mirror image: the row reversed (C–B–A) under the negated ground motion moves as the
/// mirror of the row, so every structure's and every pair's numbers are the same (the pairs in
/// reverse order, left and right swapped).
#[test]
fn the_mirror_image_of_a_row_gives_the_same_numbers() {
    let (a, b, c) = (
        building("A", 3, 3.0e8, ""),
        building("B", 5, 1.6e8, ""),
        building("C", 4, 2.2e8, ""),
    );
    for method in ["exact-modal", "adaptive", "rk4"] {
        let dt = if method == "rk4" { 2e-4 } else { 2e-3 };
        let text = |order: [&String; 3], pairs: [String; 2]| {
            format!(
                "{}{}{}{}{}{HARMONIC}[solver]\nmethod = \"{method}\"\ndt = {dt}\nduration = 5.0\n",
                order[0], order[1], order[2], pairs[0], pairs[1]
            )
        };
        let row = scenario(&text(
            [&a, &b, &c],
            [
                contact("A", "B", 10.5, 0.004),
                contact("B", "C", 14.0, 0.006),
            ],
        ));
        let mut mirror = scenario(&text(
            [&c, &b, &a],
            [
                contact("C", "B", 14.0, 0.006),
                contact("B", "A", 10.5, 0.004),
            ],
        ));
        let GroundMotion::Harmonic(h) = row.ground_motion.clone() else {
            panic!("harmonic")
        };
        mirror.ground_motion = GroundMotion::Harmonic(Harmonic { pga: -h.pga, ..h });
        let (r, m) = (simulate_row(&row).unwrap(), simulate_row(&mirror).unwrap());
        assert!(
            r.pairs.iter().all(|p| p.contact.impacts > 0),
            "{method}: both pairs pound"
        );
        // the same arithmetic in another order (the coordinates and the sums over them
        // reversed): round-off, grown over the impacts; 1e-6 is far below any modelling
        // difference and far above the round-off seen (≈1e-12)
        let rel = 1e-6;
        for (i, s) in r.structures.iter().enumerate() {
            let t = &m.structures[2 - i];
            assert_eq!(s.name, t.name);
            assert_close(
                s.peak_displacement,
                t.peak_displacement,
                rel,
                &format!("{method} {}", s.name),
            );
            assert_close(
                s.peak_displacement_no_contact,
                t.peak_displacement_no_contact,
                rel,
                "free",
            );
            for (f, g) in s.floors.iter().zip(&t.floors) {
                // (the absolute acceleration is taken at the observations, not refined
                // between them: inside an impact's pulse a step end moved by round-off
                // samples it elsewhere — 2e-5 seen with adaptive)
                assert_close(
                    f.peak_acceleration,
                    g.peak_acceleration,
                    1e-3,
                    "acceleration",
                );
                assert_close(f.peak_shear, g.peak_shear, rel, "shear");
            }
        }
        for (p, pr) in r.pairs.iter().enumerate() {
            let q = &m.pairs[1 - p];
            assert_eq!(pr.between, [q.between[1].clone(), q.between[0].clone()]);
            assert_eq!(
                pr.contact.impacts, q.contact.impacts,
                "{method}: impacts of pair {p}"
            );
            assert_close(
                pr.contact.peak_force,
                q.contact.peak_force,
                rel,
                "peak force",
            );
            assert_close(
                pr.contact.max_penetration,
                q.contact.max_penetration,
                rel,
                "penetration",
            );
            assert_close(
                pr.peak_approach_speed,
                q.peak_approach_speed,
                rel,
                "approach",
            );
            assert_close(
                pr.separation.time_history,
                q.separation.time_history,
                rel,
                "exact gap",
            );
            assert_close(pr.separation.ddc, q.separation.ddc, rel, "DDC");
            let (l, k) = (&pr.levels[0], &q.levels[0]);
            assert_close(
                l.peak_displacement[0],
                k.peak_displacement[1],
                rel,
                "left is right",
            );
        }
    }
}

/// Identical buildings moving in phase keep their gaps: a row of them never pounds, however
/// strong the shaking (a wrong sign or a wrong structure in a coupling row would close them).
#[test]
fn identical_buildings_in_phase_never_pound() {
    let b: String = ["A", "B", "C", "D"]
        .iter()
        .map(|n| building(n, 6, 2.0e8, ""))
        .collect();
    let c = [("A", "B"), ("B", "C"), ("C", "D")]
        .iter()
        .map(|(x, y)| contact(x, y, 21.0, 0.001))
        .collect::<String>();
    for method in ["exact-modal", "adaptive"] {
        let row = scenario(&format!("{b}{c}{HARMONIC}{}", solver(method, 8.0)));
        let r = simulate_row(&row).unwrap();
        assert!(r.structures[0].peak_displacement > 0.05, "strong shaking");
        for p in &r.pairs {
            assert_eq!(p.contact.impacts, 0, "{method}");
            assert_eq!(
                p.separation.time_history, 0.0,
                "{method}: they never approach"
            );
        }
        for s in &r.structures {
            assert_eq!(s.peak_displacement, r.structures[0].peak_displacement);
        }
    }
}

/// Energy closes for a pounding row of five (the contact powers of both sides of each middle
/// building included), with every method; the impulses each pair exchanges are equal and
/// opposite by construction, so the balance is the check that the row's coupling is right.
#[test]
fn the_energy_balance_closes_for_a_row_of_five() {
    let names = ["A", "B", "C", "D", "E"];
    let storeys = [3, 6, 4, 5, 3];
    let body: String = names
        .iter()
        .zip(storeys)
        .map(|(n, s)| building(n, s, 1.0e8 + 3.0e7 * s as f64, ""))
        .collect();
    let contacts: String = (0..4)
        .map(|p| {
            let h = 3.5 * storeys[p].min(storeys[p + 1]) as f64;
            contact(names[p], names[p + 1], h, 0.003)
        })
        .collect();
    for (method, dt, bound) in [
        // exact-modal's and adaptive's balance is their tolerance's; rk4 at 0.2 ms its O(dt⁴)
        ("exact-modal", 2e-3, 1e-5),
        ("adaptive", 2e-3, 1e-5),
        ("rk4", 2e-4, 1e-5),
    ] {
        let row = scenario(&format!(
            "{body}{contacts}{HARMONIC}[solver]\nmethod = \"{method}\"\ndt = {dt}\nduration = 6.0\n"
        ));
        let r: RowReport = simulate_row(&row).unwrap();
        let pounding = r.pairs.iter().filter(|p| p.contact.impacts > 0).count();
        assert!(pounding >= 3, "{method}: {pounding} pairs pound");
        assert!(r.energy.relative_error < bound, "{method}: {:?}", r.energy);
        assert!(r.energy_no_contact.relative_error < bound);
        // every pair's force was seen by the row's energy: the contact's work is not zero
        assert!(r.energy.input > 0.0);
    }
}

/// A yielding middle building (Bouc–Wen storeys, the hysteretic method) in a row: the
/// structure's storeys are found at its offset and the energy balance closes.
#[test]
fn a_yielding_building_in_the_middle_of_a_row() {
    let hyst =
        "hysteresis = { model = \"bouc-wen\", yield_drifts = 0.01, post_yield_ratio = 0.05 }";
    let text = format!(
        "{}{}{}{}{}{HARMONIC}[solver]\nduration = 4.0\n",
        building("A", 3, 3.0e8, ""),
        building("B", 5, 1.2e8, hyst),
        building("C", 4, 2.5e8, ""),
        contact("A", "B", 10.5, 0.004),
        contact("B", "C", 14.0, 0.004),
    );
    let r = simulate_row(&scenario(&text)).unwrap();
    assert!(r.structures[1].peak_ductility.unwrap() > 1.0, "it yields");
    assert!(r.structures[0].peak_ductility.is_none());
    assert!(r.structures[2].peak_ductility.is_none());
    assert!(r.energy.relative_error < 1e-3, "{:?}", r.energy);
}

// ---------------------------------------------------------------------------------------------
// An independent integration in physical coordinates.

/// A two-storey shear building: floor masses, storey stiffnesses, Rayleigh a₀, a₁.
struct Frame {
    m: [f64; 2],
    k: [f64; 2],
}

/// Three two-storey shear buildings with Hertz contacts at the top floors (pair 1) and the
/// first floors (pair 2), integrated here as `M ü + C u̇ + K u = −M 1 a_g + contact forces` in
/// floor displacements by the classical RK4 at a step of 20 µs (C = a₀M + a₁K, the Rayleigh
/// damping the scenarios give): the row's peaks within 1e-6 of it.
#[test]
fn a_row_agrees_with_an_integration_in_physical_coordinates() {
    let frames = [
        Frame {
            m: [2.0e5, 1.5e5],
            k: [3.0e8, 2.0e8],
        },
        Frame {
            m: [2.5e5, 2.0e5],
            k: [1.0e8, 0.8e8],
        },
        Frame {
            m: [1.8e5, 1.8e5],
            k: [2.0e8, 1.6e8],
        },
    ];
    let (zeta, kh, gaps) = (0.05, 5.0e9, [0.005, 0.003]);
    let (pga_g, tg, duration): (f64, f64, f64) = (0.4, 0.9, 4.0);
    let mut text = String::new();
    for (i, f) in frames.iter().enumerate() {
        text += &format!(
            "[[structure]]\nname = \"{i}\"\nkind = \"shear-building\"\nfloor_heights = [3.5, 7.0]\n\
             floor_masses = [{:e}, {:e}]\nstorey_stiffnesses = [{:e}, {:e}]\nmodes = 2\n\
             rayleigh = {{ damping_ratio = {zeta}, modes = [1, 2] }}\n",
            f.m[0], f.m[1], f.k[0], f.k[1]
        );
    }
    text += &format!(
        "[[contact]]\nbetween = [\"0\", \"1\"]\nlaw = \"hertz\"\nstiffness = {kh:e}\nheight = 7.0\ngap = {}\n\
         [[contact]]\nbetween = [\"1\", \"2\"]\nlaw = \"hertz\"\nstiffness = {kh:e}\nheight = 3.5\ngap = {}\n\
         [ground_motion]\nkind = \"harmonic\"\npga = {pga_g}\nperiod = {tg}\n\
         [solver]\nmethod = \"adaptive\"\nrtol = 1e-9\natol = 1e-10\nduration = {duration}\n",
        gaps[0], gaps[1]
    );
    let sc = scenario(&text);
    let r = simulate_row(&sc).unwrap();

    // physical model: u = [u0_1, u0_2, u1_1, u1_2, u2_1, u2_2]
    let mut mass = [0.0; 6];
    let mut kmat = [[0.0; 6]; 6];
    let mut ray = [(0.0, 0.0); 3];
    for (i, f) in frames.iter().enumerate() {
        let o = 2 * i;
        mass[o] = f.m[0];
        mass[o + 1] = f.m[1];
        kmat[o][o] = f.k[0] + f.k[1];
        kmat[o][o + 1] = -f.k[1];
        kmat[o + 1][o] = -f.k[1];
        kmat[o + 1][o + 1] = f.k[1];
        // Rayleigh coefficients for ζ at both modes: ω from the 2×2 eigenproblem
        let (a, b, c) = (
            (f.k[0] + f.k[1]) / f.m[0],
            -f.k[1] / (f.m[0] * f.m[1]).sqrt(),
            f.k[1] / f.m[1],
        );
        let (mean, half) = ((a + c) / 2.0, (((a - c) / 2.0).powi(2) + b * b).sqrt());
        let (w1, w2) = ((mean - half).sqrt(), (mean + half).sqrt());
        ray[i] = (2.0 * zeta * w1 * w2 / (w1 + w2), 2.0 * zeta / (w1 + w2));
    }
    let omega_g = 2.0 * std::f64::consts::PI / tg;
    let pga = pga_g * 9.80665;
    // contacts: (left dof, right dof, gap)
    let contacts = [(1usize, 3usize, gaps[0]), (2usize, 4usize, gaps[1])];
    let accel = |t: f64, u: &[f64; 6], v: &[f64; 6], f_out: &mut [f64; 2]| -> [f64; 6] {
        let ag = -pga * (omega_g * t).sin();
        let mut force = [0.0; 6];
        for i in 0..6 {
            let (a0, a1) = ray[i / 2];
            let mut ku = 0.0;
            let mut kv = 0.0;
            for j in 0..6 {
                ku += kmat[i][j] * u[j];
                kv += kmat[i][j] * v[j];
            }
            force[i] = -mass[i] * ag - ku - a0 * mass[i] * v[i] - a1 * kv;
        }
        for (c, &(l, rr, gap)) in contacts.iter().enumerate() {
            let delta = u[l] - u[rr] - gap;
            let f = if delta > 0.0 {
                kh * delta.powf(1.5)
            } else {
                0.0
            };
            f_out[c] = f;
            force[l] -= f;
            force[rr] += f;
        }
        std::array::from_fn(|i| force[i] / mass[i])
    };
    let dt: f64 = 2e-5;
    let steps = (duration / dt).round() as usize;
    let (mut u, mut v) = ([0.0f64; 6], [0.0f64; 6]);
    let mut peak_u = [0.0f64; 6];
    let mut peak_f = [0.0f64; 2];
    let mut f = [0.0; 2];
    for s in 0..steps {
        let t = s as f64 * dt;
        let add = |x: &[f64; 6], k: &[f64; 6], h: f64| -> [f64; 6] {
            std::array::from_fn(|i| x[i] + h * k[i])
        };
        let a1 = accel(t, &u, &v, &mut f);
        let (u2, v2) = (add(&u, &v, dt / 2.0), add(&v, &a1, dt / 2.0));
        let a2 = accel(t + dt / 2.0, &u2, &v2, &mut f);
        let (u3, v3) = (add(&u, &v2, dt / 2.0), add(&v, &a2, dt / 2.0));
        let a3 = accel(t + dt / 2.0, &u3, &v3, &mut f);
        let (u4, v4) = (add(&u, &v3, dt), add(&v, &a3, dt));
        let a4 = accel(t + dt, &u4, &v4, &mut f);
        for i in 0..6 {
            u[i] += dt / 6.0 * (v[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
            v[i] += dt / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i]);
        }
        accel(t + dt, &u, &v, &mut f);
        for i in 0..6 {
            peak_u[i] = peak_u[i].max(u[i].abs());
        }
        for c in 0..2 {
            peak_f[c] = peak_f[c].max(f[c]);
        }
    }
    assert!(
        peak_f.iter().all(|&x| x > 0.0),
        "both pairs pound: {peak_f:?}"
    );
    // 1e-6, far inside the 0.5 % asked for: the reference's error at 20 µs (RK4, O(dt⁴)), the
    // sampling of its peaks at that step and the row's rtol 1e-9 are all below it (measured:
    // ≤ 4e-8)
    for i in 0..3 {
        let floors = &r.structures[i].floors;
        for j in 0..2 {
            assert_close(
                floors[j].peak_displacement,
                peak_u[2 * i + j],
                1e-6,
                &format!("building {i} floor {}", j + 1),
            );
        }
    }
    for c in 0..2 {
        assert_close(r.pairs[c].contact.peak_force, peak_f[c], 1e-6, "peak force");
    }
}

// ---------------------------------------------------------------------------------------------
// The scenario.

#[test]
fn a_single_contact_table_still_means_the_pair() {
    let a = building("A", 3, 3.0e8, "");
    let b = building("B", 4, 2.0e8, "");
    let one = scenario(&format!(
        "{a}{b}[contact]\nstiffness = 2.0e10\ngap = 0.01\n{HARMONIC}"
    ));
    let many = scenario(&format!(
        "{a}{b}[[contact]]\nbetween = [\"B\", \"A\"]\nstiffness = 2.0e10\ngap = 0.01\n{HARMONIC}"
    ));
    assert!(!one.is_row() && one.row_contacts.is_empty());
    assert_eq!(one.contact, many.contact);
    assert_eq!(one.system().levels, many.system().levels);
}

#[test]
fn bad_rows_are_refused_naming_the_key() {
    let (a, b, c) = (
        building("A", 3, 3.0e8, ""),
        building("B", 4, 2.0e8, ""),
        building("C", 5, 2.0e8, ""),
    );
    let ab = contact("A", "B", 10.5, 0.01);
    let bc = contact("B", "C", 14.0, 0.01);
    let cases = [
        // a name that is not a structure
        (
            format!("{a}{b}{c}{ab}{}{HARMONIC}", contact("B", "D", 14.0, 0.01)),
            ["contact[2].between", "\"D\" is not the name of a structure"],
        ),
        // a pair given twice
        (
            format!(
                "{a}{b}{c}{ab}{bc}{}{HARMONIC}",
                contact("C", "B", 14.0, 0.02)
            ),
            ["contact[3].between", "given twice (also by contact[2])"],
        ),
        // not adjacent
        (
            format!("{a}{b}{c}{ab}{}{HARMONIC}", contact("A", "C", 10.5, 0.01)),
            ["contact[2].between", "only adjacent structures"],
        ),
        // a pair without a contact
        (
            format!("{a}{b}{c}{ab}{HARMONIC}"),
            ["`contact`", "none for \"B\"–\"C\""],
        ),
        // a row of one
        (
            format!("{a}[contact]\nstiffness = 1e9\ngap = 0.01\n{HARMONIC}"),
            ["`structure`", "one structure alone"],
        ),
        // one [contact] for a row
        (
            format!("{a}{b}{c}[contact]\nstiffness = 1e9\ngap = 0.01\n{HARMONIC}"),
            ["`contact`", "one [[contact]] table per adjacent pair"],
        ),
        // no `between` in a row
        (
            format!("{a}{b}{c}{ab}[[contact]]\nstiffness = 1e9\ngap = 0.01\n{HARMONIC}"),
            ["contact[2].between", "by name"],
        ),
        // `between` of three
        (
            format!(
                "{a}{b}{c}{ab}[[contact]]\nbetween = [\"A\", \"B\", \"C\"]\nstiffness = 1e9\ngap = 0.01\n{HARMONIC}"
            ),
            ["contact[2].between", "exactly two"],
        ),
        // two structures of one name
        (
            format!("{a}{}{c}{ab}{bc}{HARMONIC}", building("A", 4, 2.0e8, "")),
            [
                "contact[1].between",
                "give every structure of a row its own",
            ],
        ),
        // a key of a row's table named with its index
        (
            format!(
                "{a}{b}{c}{ab}[[contact]]\nbetween = [\"B\", \"C\"]\nstiffness = -1\ngap = 0.01\n{HARMONIC}"
            ),
            ["contact[2].stiffness", ""],
        ),
        // a height above the lower building of the pair (A: 10.5 m)
        (
            format!("{a}{b}{c}{}{bc}{HARMONIC}", contact("A", "B", 14.0, 0.01)),
            ["contact[1].height", "min(L1, L2)"],
        ),
    ];
    for (text, [key, why]) in cases {
        let e = refused(&text);
        assert!(
            e.contains(key) && e.contains(why),
            "expected {key} / {why}, got: {e}"
        );
        assert!(e.contains("row.toml"), "names the file: {e}");
    }
    // [contact] and [[contact]] both: the TOML itself cannot hold both
    let e = refused(&format!(
        "{a}{b}[contact]\nstiffness = 1e9\ngap = 0.01\n{ab}{HARMONIC}"
    ));
    assert!(
        e.contains("[contact] and [[contact]]") && e.contains("not both"),
        "{e}"
    );
}

/// What only a pair supports refuses a row with a message saying so.
#[test]
fn pair_only_doors_refuse_a_row() {
    let row = scenario(&format!(
        "{}{}{}{}{}{HARMONIC}",
        building("A", 3, 3.0e8, ""),
        building("B", 4, 2.0e8, ""),
        building("C", 5, 2.0e8, ""),
        contact("A", "B", 10.5, 0.01),
        contact("B", "C", 14.0, 0.01),
    ));
    let e = simulate(&row).unwrap_err().to_string();
    assert!(e.contains("row of 3 structures"), "{e}");
    let e = pounding::analysis::simulate::separation(&row)
        .unwrap_err()
        .to_string();
    assert!(e.contains("row of 3 structures"), "{e}");
}
