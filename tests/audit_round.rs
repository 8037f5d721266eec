//! The audit of every contact law, structure kind and method at its default against an
//! independent integration in physical coordinates (tests/common/physical_laws.rs: RK4 at a
//! small step with located onsets, every law written from its README formula, sharing nothing
//! with the program but the equations of motion): shear buildings (every law on two levels,
//! the engineer's modes, a row of three, Bouc–Wen storeys); the cantilevers are in
//! tests/audit_cantilever_laws.rs. For each case and method: the largest error
//! over every floor quantity the README defines (displacement, absolute acceleration, drift,
//! storey force, equilibrium shear) and the peak contact force, the self-check's estimate and
//! its verdict — honest when a true error above the check's threshold (1 %) is flagged NOT
//! CONVERGED.

// Index loops over the dofs of a small physical model read like the equations they form.
#![allow(clippy::needless_range_loop)]

mod common;

use pounding::analysis::simulate::{Report, simulate_checked, simulate_row_checked};

use common::audit_line::Line;
use common::physical_laws::{
    BoucWen, Dofs, Law, Level, Peaks, floor, integrate, integrate_dofs, jankowski_xi, kelvin_xi,
    lankarani_chi,
};
use common::{BUILDING_A as A, BUILDING_B as B, FloorPeaks, Physical, physical};

const G: f64 = 9.80665;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// A pair run with its self-check, as a line of the table against `want`.
fn pair_line(text: &str, want: &Peaks) -> Line {
    let s = common::scenario_named(text, "audit.toml").expect("valid scenario");
    let r: Report = simulate_checked(&s, true).expect("runs");
    let forces: Vec<f64> = r.levels.iter().map(|l| l.peak_force).collect();
    Line::of(
        &r.structures,
        &forces,
        r.contact.impacts,
        want,
        r.accuracy.max_change,
        r.accuracy.converged,
    )
}

/// Buildings A (3 storeys) and B (2) of tests/common, in physical coordinates.
fn physical_pair() -> Vec<Physical> {
    vec![
        physical(&[2.0e5, 2.0e5, 1.5e5], &[3.0e8, 2.5e8, 2.0e8], 0.03),
        physical(&[1.8e5, 1.8e5], &[6.0e7, 5.0e7], 0.03),
    ]
}

/// The effective mass of two floors (kg): every mode of a shear building kept, `Σ_n φ_n(f)²`
/// is `(M⁻¹)_ff = 1/m_f` (README, Contact laws: `1/m* = Σ φ₁ₙ² + Σ φ₂ₙ²`).
fn m_star(ma: f64, mb: f64) -> f64 {
    1.0 / (1.0 / ma + 1.0 / mb)
}

/// The laws of the audit on the shear buildings at 1000× tests/buildings.rs's Hertz stiffness:
/// (name, TOML lines, the law at each of the two levels 6 m and 3 m).
fn stiff_laws() -> Vec<(&'static str, String, [Law; 2])> {
    let e = 0.6;
    let (kh, k) = (2.0e12, 1.0e11);
    let ms = [m_star(2.0e5, 1.8e5), m_star(2.0e5, 1.8e5)];
    let kx = kelvin_xi(e);
    let jx = jankowski_xi(e);
    vec![
        (
            "hertz",
            format!("law = \"hertz\"\nstiffness = {kh:e}\n"),
            [Law::Hertz { kh }; 2],
        ),
        (
            "linear",
            format!("law = \"linear\"\nstiffness = {k:e}\n"),
            [Law::Linear { k }; 2],
        ),
        (
            "kelvin",
            format!("law = \"kelvin\"\nstiffness = {k:e}\nrestitution = {e}\n"),
            ms.map(|m| Law::Kelvin {
                k,
                c: 2.0 * kx * (k * m).sqrt(),
            }),
        ),
        (
            "hertzdamp",
            format!("law = \"hertzdamp\"\nstiffness = {kh:e}\nrestitution = {e}\n"),
            [Law::HertzDamp {
                kh,
                chi: lankarani_chi(e),
            }; 2],
        ),
        (
            "jankowski",
            format!("law = \"jankowski\"\nstiffness = {kh:e}\nrestitution = {e}\n"),
            ms.map(|m| Law::Jankowski {
                kh,
                c0: 2.0 * jx * (m * kh).sqrt(),
            }),
        ),
    ]
}

const PGA_G: f64 = 0.3;
const TG: f64 = 0.5;
const DURATION: f64 = 4.0;

/// Buildings A and B pounding at both common floors (6 m and 3 m, gaps 1 cm) with the contact
/// `law` lines, harmonic `PGA_G` at `TG` over `DURATION`, and the `[solver]` lines `solver`.
fn two_level_pair(law: &str, solver: &str) -> String {
    format!(
        "{A}{B}[contact]\n{law}\
         [[contact.level]]\nheight = 6.0\ngap = 0.01\n[[contact.level]]\nheight = 3.0\ngap = 0.01\n\
         [ground_motion]\nkind = \"harmonic\"\npga = {PGA_G}\nperiod = {TG}\n\
         [solver]\nduration = {DURATION}\n{solver}"
    )
}

/// The two contact levels of [`two_level_pair`] in the reference: `laws` at 6 m and 3 m
/// (building A's floors 2 and 1 against B's 2 and 1), gap 10 mm.
fn pair_levels(laws: [Law; 2]) -> [Level; 2] {
    let sizes = [3, 2];
    [
        Level {
            left: floor(&sizes, 0, 1),
            right: floor(&sizes, 1, 1),
            gap: 0.01,
            law: laws[0],
        },
        Level {
            left: floor(&sizes, 0, 0),
            right: floor(&sizes, 1, 0),
            gap: 0.01,
            law: laws[1],
        },
    ]
}

/// The independent reference of [`two_level_pair`] with `laws` at 6 m and 3 m, RK4 at `dt`.
fn reference_pair(laws: [Law; 2], dt: f64) -> Peaks {
    let levels = pair_levels(laws);
    integrate(
        &physical_pair(),
        &levels,
        PGA_G * G,
        2.0 * std::f64::consts::PI / TG,
        DURATION,
        dt,
    )
}

/// The largest relative difference of two references (every floor quantity, the forces).
fn reference_spread(a: &Peaks, b: &Peaks) -> f64 {
    let mut d = 0.0f64;
    for (x, y) in a.floors.iter().zip(&b.floors) {
        for (p, q) in [
            (&x.disp, &y.disp),
            (&x.acc, &y.acc),
            (&x.drift, &y.drift),
            (&x.force, &y.force),
            (&x.shear, &y.shear),
        ] {
            for (u, v) in p.iter().zip(q.iter()) {
                d = d.max(rel(*u, *v));
            }
        }
    }
    for (u, v) in a.force.iter().zip(&b.force) {
        d = d.max(rel(*u, *v));
    }
    d
}

/// Every contact law on two levels of shear buildings (A, 3 storeys, and B, 2, at 6 m and 3 m,
/// 1000× tests/buildings.rs's Hertz stiffness: k_h = 2e12 N/m^1.5, k = 1e11 N/m, e = 0.6),
/// `exact-modal` and `adaptive` at their defaults with their self-checks, against the
/// physical-coordinate reference: every floor's displacement, absolute acceleration, drift,
/// storey force and equilibrium shear, and each level's peak force, within the 0.5 % bar, and
/// the check's verdict honest. Measured (largest over all of them; the check's estimate):
/// hertz 9.7e-5 / 1.4e-4 (2.1e-5, 5.8e-5), linear 3.6e-5 / 1.2e-4, kelvin 5.5e-5 / 8.0e-4,
/// hertzdamp 8.2e-4 / 8.3e-4 (7.4e-4, 8.3e-4), jankowski 2.0e-4 / 7.7e-4 (exact-modal /
/// adaptive), the same impacts; the largest are accelerations in the impact pulses.
/// The reference's own error: RK4 at 4 µs against 8 µs differs by ≤ 6.7e-5 (Jankowski, whose
/// `c ∝ δ^{1/4}` is not smooth at the onset; the others ≤ 1.3e-5), asserted below 2e-4.
#[test]
fn every_law_on_two_levels_of_shear_buildings_at_the_default() {
    for (name, toml, laws) in stiff_laws() {
        let want = reference_pair(laws, 4e-6);
        let spread = reference_spread(&want, &reference_pair(laws, 8e-6));
        eprintln!(
            "{name}: reference spread {spread:.2e}, impacts {:?}",
            want.impacts
        );
        assert!(spread < 2e-4, "{name}: reference {spread:.2e}");
        assert!(
            want.impacts.iter().all(|&n| n >= 5),
            "premise: both levels pound"
        );
        for method in ["exact-modal", "adaptive"] {
            let line = pair_line(
                &two_level_pair(&toml, &format!("method = \"{method}\"\n")),
                &want,
            );
            line.print(name, method);
            line.assert_within(5e-3, name, method);
        }
    }
}

/// The engineer's modes (`kind = "modal"`) given building A's own periods, shapes (another
/// normalisation) and ζ.
fn modal_a() -> String {
    let sc = common::scenario_named(&two_level_pair(&stiff_laws()[0].1, ""), "a.toml").unwrap();
    common::modal_building_a(&sc.structures[0].modal())
}

/// A report's floor peaks and level forces in the reference's form.
fn as_peaks(r: &Report) -> Peaks {
    Peaks {
        floors: r
            .structures
            .iter()
            .map(|s| FloorPeaks {
                disp: s.floors.iter().map(|f| f.peak_displacement).collect(),
                acc: s.floors.iter().map(|f| f.peak_acceleration).collect(),
                drift: s.floors.iter().map(|f| f.peak_drift).collect(),
                force: s.floors.iter().map(|f| f.peak_shear).collect(),
                shear: s.floors.iter().map(|f| f.peak_shear_with_damping).collect(),
            })
            .collect(),
        force: r.levels.iter().map(|l| l.peak_force).collect(),
        impacts: vec![r.contact.impacts],
        watched: vec![],
        watched_acc: vec![],
        watched_acc_time: vec![],
    }
}

/// One meaning for every kind: building A given as the engineer's modes (`kind = "modal"`,
/// its own periods, shapes in another normalisation and ζ) pounding B on the stiff Hertz law at
/// two levels gives the shear building's floors — the storey force from the modes' equivalent
/// static forces is k·drift, the equilibrium shear and accelerations the same — at both
/// methods' defaults: against the physical reference within the bar (measured 9.7e-5 and
/// 1.4e-4, as the shear building), and against the shear building's run to 1e-9 with
/// `exact-modal` (measured 2.4e-14: the same arithmetic) and 1e-4 with `adaptive` (measured
/// 3.8e-5, an acceleration at floor 1: the two runs' step decisions differ in round-off and
/// the accelerations are taken at the steps, each within its 1.4e-4 of the reference).
#[test]
fn the_engineers_modes_give_the_shear_buildings_floors() {
    let (name, toml, laws) = stiff_laws().swap_remove(0);
    let want = reference_pair(laws, 4e-6);
    let modal = modal_a();
    for (method, same) in [("exact-modal", 1e-9), ("adaptive", 1e-4)] {
        let shear_text = two_level_pair(&toml, &format!("method = \"{method}\"\n"));
        let modal_text = shear_text.replacen(A, &modal, 1);
        assert_ne!(shear_text, modal_text, "premise: A is replaced");
        let line = pair_line(&modal_text, &want);
        line.print(&format!("modal A, {name}"), method);
        line.assert_within(5e-3, "modal A", method);
        let run = |t: &str| {
            simulate_checked(&common::scenario_named(t, "m.toml").unwrap(), false).unwrap()
        };
        let (a, b) = (run(&shear_text), run(&modal_text));
        let pa = as_peaks(&a);
        let l = Line::of(
            &b.structures,
            &as_peaks(&b).force,
            b.contact.impacts,
            &pa,
            None,
            None,
        );
        l.print("modal A against shear A", method);
        assert!(l.error < same, "{method}: {} {:.2e}", l.what, l.error);
        assert_eq!(a.contact.impacts, b.contact.impacts);
    }
}

/// A row of three two-storey shear buildings (tests/rows.rs's) on Hertz contacts 1000× that
/// test's (k_h = 5e12 N/m^1.5) at the top floors (pair 1) and the first floors (pair 2), 0.4 g at
/// 0.9 s, 4 s: both methods at their defaults (`simulate_row_checked`) against the physical
/// reference, every floor quantity of the three buildings and each pair's peak force within
/// the bar, the check honest. Measured: exact-modal 1.4e-4 (check 1.4e-4), adaptive 8.3e-5
/// (9.4e-5), 71 impacts as the reference; the reference at 4 µs against 8 µs: 8.7e-6.
#[test]
fn a_row_of_three_on_stiff_hertz_contacts_at_the_default() {
    let m = [[2.0e5, 1.5e5], [2.5e5, 2.0e5], [1.8e5, 1.8e5]];
    let k = [[3.0e8, 2.0e8], [1.0e8, 0.8e8], [2.0e8, 1.6e8]];
    let (zeta, kh, gaps) = (0.05, 5.0e12, [0.005, 0.003]);
    let (pga_g, tg, duration): (f64, f64, f64) = (0.4, 0.9, 4.0);
    let text = |solver: &str| {
        let mut text = String::new();
        for i in 0..3 {
            text += &format!(
                "[[structure]]\nname = \"{i}\"\nkind = \"shear-building\"\nfloor_heights = [3.5, 7.0]\n\
                 floor_masses = [{:e}, {:e}]\nstorey_stiffnesses = [{:e}, {:e}]\n\
                 rayleigh = {{ damping_ratio = {zeta}, modes = [1, 2] }}\n",
                m[i][0], m[i][1], k[i][0], k[i][1]
            );
        }
        text += &format!(
            "[[contact]]\nbetween = [\"0\", \"1\"]\nlaw = \"hertz\"\nstiffness = {kh:e}\nheight = 7.0\ngap = {}\n\
             [[contact]]\nbetween = [\"1\", \"2\"]\nlaw = \"hertz\"\nstiffness = {kh:e}\nheight = 3.5\ngap = {}\n\
             [ground_motion]\nkind = \"harmonic\"\npga = {pga_g}\nperiod = {tg}\n\
             [solver]\nduration = {duration}\n{solver}",
            gaps[0], gaps[1]
        );
        text
    };
    let phys: Vec<Physical> = (0..3).map(|i| physical(&m[i], &k[i], zeta)).collect();
    let sizes = [2, 2, 2];
    let law = Law::Hertz { kh };
    let levels = [
        Level {
            left: floor(&sizes, 0, 1),
            right: floor(&sizes, 1, 1),
            gap: gaps[0],
            law,
        },
        Level {
            left: floor(&sizes, 1, 0),
            right: floor(&sizes, 2, 0),
            gap: gaps[1],
            law,
        },
    ];
    let om = 2.0 * std::f64::consts::PI / tg;
    let want = integrate(&phys, &levels, pga_g * G, om, duration, 4e-6);
    let spread = reference_spread(
        &want,
        &integrate(&phys, &levels, pga_g * G, om, duration, 8e-6),
    );
    eprintln!(
        "row: reference spread {spread:.2e}, impacts {:?}",
        want.impacts
    );
    assert!(spread < 1e-4, "reference {spread:.2e}");
    assert!(
        want.impacts.iter().all(|&n| n >= 5),
        "premise: both pairs pound"
    );
    for method in ["exact-modal", "adaptive"] {
        let sc =
            common::scenario_named(&text(&format!("method = \"{method}\"\n")), "row.toml").unwrap();
        let r = simulate_row_checked(&sc, true).unwrap();
        let forces: Vec<f64> = r.pairs.iter().map(|p| p.contact.peak_force).collect();
        let impacts = r.pairs.iter().map(|p| p.contact.impacts).sum();
        let line = Line::of(
            &r.structures,
            &forces,
            impacts,
            &want,
            r.accuracy.max_change,
            r.accuracy.converged,
        );
        line.print("row of three, Hertz", method);
        line.assert_within(5e-3, "row", method);
    }
}

/// Yielding storeys (Bouc–Wen, tests/hysteresis.rs's buildings: A yields at 4 mm, α 0.05, n 2,
/// β = γ = 0.5; B at 6 mm, α 0.1, n 1.5, β 0.6, γ 0.3) pounding on the stiff Hertz law
/// (2e12 N/m^1.5) at two levels, 0.3 g at 0.5 s, 4 s: the default method (`adaptive` for
/// yielding storeys) and `exact-modal` at their defaults with their checks against the
/// physical-coordinate reference with the Bouc–Wen storeys as states (every floor quantity —
/// the storey force is the Bouc–Wen force — and each level's peak force), and the same with
/// yield drifts 20× smaller (0.2 and 0.3 mm: a yield force a few % of the elastic one, peak
/// ductility ≈ 210–220). Measured: adaptive 1.3e-4 (check 1.1e-4), exact-modal 1.2e-6
/// (1.1e-6), ductility 6.2 and 7.3; tiny yield drifts adaptive 2.1e-4 (1.5e-4), exact-modal
/// 3.1e-6 (3.3e-6). The reference at 4 µs against 8 µs: ≤ 4.6e-6.
#[test]
fn yielding_storeys_on_stiff_contacts_at_the_default() {
    yielding_case(
        "yielding storeys",
        (0.004, 0.05, 2.0, 0.5, 0.5),
        (0.006, 0.1, 1.5, 0.6, 0.3),
    );
    yielding_case(
        "tiny yield drifts",
        (2e-4, 0.05, 2.0, 0.5, 0.5),
        (3e-4, 0.1, 1.5, 0.6, 0.3),
    );
}

type BoucWenKeys = (f64, f64, f64, f64, f64);

/// Buildings A and B with the Bouc–Wen keys (d_y, α, n, β, γ) `bw_a`, `bw_b` on the stiff Hertz
/// law at two levels: both methods' defaults against the reference.
fn yielding_case(case: &str, bw_a: BoucWenKeys, bw_b: BoucWenKeys) {
    let hyst = |(dy, a, n, b, g): BoucWenKeys| {
        format!(
            "hysteresis = {{ model = \"bouc-wen\", yield_drifts = {dy:e}, post_yield_ratio = {a}, \
             exponent = {n}, beta = {b}, gamma = {g} }}\n"
        )
    };
    let (ya, yb) = (format!("{A}{}", hyst(bw_a)), format!("{B}{}", hyst(bw_b)));
    let (name, toml, laws) = stiff_laws().swap_remove(0);
    let phys = physical_pair();
    let dofs: Vec<Dofs> = phys
        .iter()
        .zip([bw_a, bw_b])
        .map(|(p, (dy, alpha, n, beta, gamma))| {
            let k = p.springs.clone().unwrap();
            Dofs::yielding(
                p,
                BoucWen {
                    k,
                    dy,
                    alpha,
                    n,
                    beta,
                    gamma,
                },
            )
        })
        .collect();
    let levels = pair_levels(laws);
    let om = 2.0 * std::f64::consts::PI / TG;
    let reference = |h| integrate_dofs(&dofs, &phys, &levels, &[], &[], PGA_G * G, om, DURATION, h);
    let want = reference(4e-6);
    let spread = reference_spread(&want, &reference(8e-6));
    let mu: Vec<f64> = want
        .floors
        .iter()
        .zip([bw_a.0, bw_b.0])
        .map(|(f, dy)| f.drift.iter().fold(0.0f64, |m, d| m.max(*d)) / dy)
        .collect();
    eprintln!(
        "{case}: reference spread {spread:.2e}, impacts {:?}, ductility {mu:?}",
        want.impacts
    );
    assert!(spread < 1e-4, "reference {spread:.2e}");
    assert!(
        want.impacts.iter().sum::<usize>() >= 3,
        "premise: they pound"
    );
    assert!(mu.iter().all(|&m| m > 1.5), "premise: both yield");
    for method in ["", "method = \"exact-modal\"\n"] {
        let text = two_level_pair(&toml, method)
            .replacen(A, &ya, 1)
            .replacen(B, &yb, 1);
        let s = common::scenario_named(&text, "y.toml").unwrap();
        let m = s.solver.method.name();
        let line = pair_line(&text, &want);
        line.print(&format!("{case}, {name}"), m);
        line.assert_within(5e-3, case, m);
    }
}
