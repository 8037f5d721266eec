//! The audit of every contact law, structure kind and method at its default against an
//! independent integration in physical coordinates (tests/common/physical_laws.rs: RK4 at a
//! small step with located onsets, every law written from its README formula, sharing nothing
//! with the program but the equations of motion). For each case and method: the largest error
//! over every floor quantity the README defines (displacement, absolute acceleration, drift,
//! storey force, equilibrium shear) and the peak contact force, the self-check's estimate and
//! its verdict — honest when a true error above the check's threshold (1 %) is flagged NOT
//! CONVERGED.

// Index loops over the dofs of a small physical model read like the equations they form.
#![allow(clippy::needless_range_loop)]

mod common;

use pounding::analysis::simulate::{
    Report, StructureReport, simulate_checked, simulate_row_checked,
};

use common::physical_laws::{
    BoucWen, Dofs, Law, Level, Peaks, cantilever, cantilever_shear, floor, integrate,
    integrate_dofs, jankowski_xi, kelvin_xi, lankarani_chi,
};
use common::{BUILDING_A as A, BUILDING_B as B, FloorPeaks, Physical, physical};

const G: f64 = 9.80665;

/// The largest error of a structure's floors against the reference `want`, each quantity
/// relative to its own reference peak or to 10 % of that quantity's largest over the floors
/// when below it (how the self-check measures a floor quantity), with the quantity's name.
fn floor_error(s: &StructureReport, want: &FloorPeaks) -> (f64, String) {
    let mut worst = (0.0f64, String::new());
    let got: [(&str, Vec<f64>, &Vec<f64>); 5] = [
        (
            "displacement",
            s.floors.iter().map(|f| f.peak_displacement).collect(),
            &want.disp,
        ),
        (
            "acceleration",
            s.floors.iter().map(|f| f.peak_acceleration).collect(),
            &want.acc,
        ),
        (
            "drift",
            s.floors.iter().map(|f| f.peak_drift).collect(),
            &want.drift,
        ),
        (
            "storey force",
            s.floors.iter().map(|f| f.peak_shear).collect(),
            &want.force,
        ),
        (
            "equilibrium shear",
            s.floors.iter().map(|f| f.peak_shear_with_damping).collect(),
            &want.shear,
        ),
    ];
    for (name, x, w) in got {
        assert_eq!(x.len(), w.len(), "{name}: one peak per floor");
        let big = w.iter().fold(0.0f64, |m, v| m.max(*v));
        for (f, (a, b)) in x.iter().zip(w.iter()).enumerate() {
            let e = (a - b).abs() / b.max(0.1 * big);
            if e > worst.0 {
                worst = (e, format!("{name} floor {}", f + 1));
            }
        }
    }
    worst
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// One line of the audit's table: the largest error over `structures`' floors and the peak
/// forces, the check's estimate and verdict.
struct Line {
    error: f64,
    what: String,
    estimate: Option<f64>,
    converged: Option<bool>,
    impacts: usize,
    impacts_ref: usize,
}

impl Line {
    fn of(
        structures: &[StructureReport],
        forces: &[f64],
        impacts: usize,
        want: &Peaks,
        estimate: Option<f64>,
        converged: Option<bool>,
    ) -> Line {
        let mut worst = (0.0f64, String::new());
        for (i, (s, w)) in structures.iter().zip(&want.floors).enumerate() {
            let (e, what) = floor_error(s, w);
            if e > worst.0 {
                worst = (e, format!("structure {} {what}", i + 1));
            }
        }
        let fmax = want.force.iter().fold(0.0f64, |m, v| m.max(*v));
        for (k, (a, b)) in forces.iter().zip(&want.force).enumerate() {
            let e = (a - b).abs() / b.max(0.1 * fmax);
            if e > worst.0 {
                worst = (e, format!("peak force {}", k + 1));
            }
        }
        Line {
            error: worst.0,
            what: worst.1,
            estimate,
            converged,
            impacts,
            impacts_ref: want.impacts.iter().sum(),
        }
    }

    fn print(&self, case: &str, method: &str) {
        eprintln!(
            "| {case} | {method} | {:.2e} ({}) | {} | {} | {} / {} |",
            self.error,
            self.what,
            self.estimate.map_or("-".into(), |e| format!("{e:.2e}")),
            match self.converged {
                Some(true) => "converged",
                Some(false) => "NOT CONVERGED",
                None => "-",
            },
            self.impacts,
            self.impacts_ref,
        );
    }

    /// Honest: a true error above the check's 1 % threshold is flagged.
    fn honest(&self) -> bool {
        self.error <= 0.01 || self.converged == Some(false)
    }

    /// The error within `tol` and the verdict honest.
    fn assert_within(&self, tol: f64, case: &str, method: &str) {
        assert!(
            self.honest(),
            "{case} {method}: a dishonest check ({:.2e} {})",
            self.error,
            self.what
        );
        assert!(
            self.error < tol,
            "{case} {method}: {:.2e} ({})",
            self.error,
            self.what
        );
    }
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

/// The independent reference of [`two_level_pair`] with `laws` at 6 m and 3 m, RK4 at `dt`.
fn reference_pair(laws: [Law; 2], dt: f64) -> Peaks {
    let sizes = [3, 2];
    let levels = [
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
    ];
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
    let m = sc.structures[0].modal();
    let heights = [3.0, 6.0, 9.0];
    let periods: Vec<String> = m.periods().iter().map(|t| format!("{t:?}")).collect();
    let shapes: Vec<String> = (0..m.len())
        .map(|n| {
            let v: Vec<String> = heights
                .iter()
                .map(|&h| format!("{:?}", -3.0 * m.shape(n, h) * 1e3))
                .collect();
            format!("[{}]", v.join(", "))
        })
        .collect();
    let zeta: Vec<String> = m.zeta.iter().map(|z| format!("{z:?}")).collect();
    format!(
        "[[structure]]\nname = \"A\"\nkind = \"modal\"\nfloor_heights = [3.0, 6.0, 9.0]\n\
         floor_masses = [2.0e5, 2.0e5, 1.5e5]\nperiods = [{}]\nmode_shapes = [{}]\n\
         damping_ratio = [{}]\n",
        periods.join(", "),
        shapes.join(", "),
        zeta.join(", ")
    )
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

/// The paper's two cantilevers (2.273e6 kg, 10 m, T = 0.3 and 0.6 s, ζ = 0.01, `modes` modes)
/// with the contact `toml` at the top (gap 12.7 mm) under 0.5 g at 0.8 s, against the
/// reference by RK4 at `h` in modal coordinates (tests/common/physical_laws.rs: shapes, Γ and
/// section integrals written from docs/model.md, the law from the README): `(name, method) →
/// line` of the top peaks, the peak force and (`shears`) the section shear (storey force) at
/// 1…9 m of both structures.
fn cantilever_lines(
    modes: usize,
    duration: f64,
    h: f64,
    laws: &[NamedLaw],
    shears: bool,
    methods: &[&str],
) -> Vec<(String, Line)> {
    let (mass, length, periods, zeta, gap) = (2.273e6, 10.0, [0.3, 0.6], 0.01, 0.0127);
    let (pga_g, tg) = (0.5, 0.8);
    let cs: Vec<_> = periods
        .iter()
        .map(|&t| cantilever(mass, length, t, modes, zeta))
        .collect();
    // 1/m* = Σ φ₁ₙ(L)² + Σ φ₂ₙ(L)² over the modes kept (README, Contact laws)
    let mstar = 1.0 / (cs[0].1.iter().chain(&cs[1].1).map(|p| p * p).sum::<f64>());
    let dofs: Vec<_> = cs.iter().map(|c| c.0.clone()).collect();
    let left: Vec<(usize, f64)> = cs[0].1.iter().copied().enumerate().collect();
    let right: Vec<(usize, f64)> = cs[1]
        .1
        .iter()
        .copied()
        .enumerate()
        .map(|(i, p)| (i + modes, p))
        .collect();
    let mut watch = vec![left.clone(), right.clone()];
    if shears {
        for (s, &t) in periods.iter().enumerate() {
            for j in 1..=9 {
                let w = cantilever_shear(mass, length, t, modes, j as f64);
                watch.push(
                    w.into_iter()
                        .enumerate()
                        .map(|(i, x)| (i + s * modes, x))
                        .collect(),
                );
            }
        }
    }
    let mut out = Vec::new();
    for (name, toml, law) in laws {
        let level = [Level {
            left: left.clone(),
            right: right.clone(),
            gap,
            law: law(mstar),
        }];
        let om = 2.0 * std::f64::consts::PI / tg;
        let want = integrate_dofs(
            &dofs,
            &[],
            &level,
            &watch,
            &watch[..2],
            pga_g * G,
            om,
            duration,
            h,
        );
        for method in methods {
            let text = format!(
                "[[structure]]\nlength = {length}\nmass = {mass}\nperiod = {}\nmodes = {modes}\n\
                 damping_ratio = {zeta}\n[[structure]]\nlength = {length}\nmass = {mass}\n\
                 period = {}\nmodes = {modes}\ndamping_ratio = {zeta}\n[contact]\n{toml}gap = {gap}\n\
                 [ground_motion]\nkind = \"harmonic\"\npga = {pga_g}\nperiod = {tg}\n\
                 [solver]\nmethod = \"{method}\"\nduration = {duration}\n",
                periods[0], periods[1]
            );
            let r =
                simulate_checked(&common::scenario_named(&text, "c.toml").unwrap(), true).unwrap();
            let mut errs = vec![
                (
                    rel(r.structures[0].peak_displacement, want.watched[0]),
                    "peak 1".to_string(),
                ),
                (
                    rel(r.structures[1].peak_displacement, want.watched[1]),
                    "peak 2".to_string(),
                ),
                (
                    rel(r.contact.peak_force, want.force[0]),
                    "peak force".to_string(),
                ),
            ];
            // the absolute acceleration at the top (the contact point)
            for s in 0..2 {
                let top = r.structures[s].floors.last().expect("stations");
                assert_eq!(top.height, length, "the top station");
                errs.push((
                    rel(top.peak_acceleration, want.watched_acc[s]),
                    format!("structure {} acceleration at the top", s + 1),
                ));
            }
            if shears {
                for s in 0..2 {
                    let ws = &want.watched[2 + 9 * s..2 + 9 * (s + 1)];
                    let big = ws.iter().fold(0.0f64, |m, v| m.max(*v));
                    for j in 0..9 {
                        let fl = r.structures[s]
                            .floors
                            .iter()
                            .find(|f| (f.height - (j + 1) as f64).abs() < 1e-9)
                            .expect("a station every metre");
                        errs.push((
                            (fl.peak_shear - ws[j]).abs() / ws[j].max(0.1 * big),
                            format!("structure {} shear at {} m", s + 1, j + 1),
                        ));
                    }
                }
            }
            let (error, what) = errs
                .into_iter()
                .fold((0.0, String::new()), |a, b| if b.0 > a.0 { b } else { a });
            let line = Line {
                error,
                what,
                estimate: r.accuracy.max_change,
                converged: r.accuracy.converged,
                impacts: r.contact.impacts,
                impacts_ref: want.impacts[0],
            };
            line.print(&format!("cantilevers, {modes} modes, {name}"), method);
            let top = r.structures[0].floors.last().expect("stations");
            eprintln!(
                "  top acceleration {} at {:?} s (reference {} at {} s); first impact at {:?} s",
                top.peak_acceleration,
                top.peak_acceleration_time,
                want.watched_acc[0],
                want.watched_acc_time[0],
                r.impact_log.first().map(|i| i.start)
            );
            out.push((format!("{name} {method}"), line));
        }
    }
    out
}

/// A law's name, its TOML lines and the law given m* (kg).
type NamedLaw = (&'static str, String, fn(f64) -> Law);

/// Both error-controlled methods.
const BOTH: &[&str] = &["exact-modal", "adaptive"];

const E: f64 = 0.6;
const KH: f64 = 2.808e13;
const KL: f64 = 1.0e11;

fn kelvin(mstar: f64) -> Law {
    Law::Kelvin {
        k: KL,
        c: 2.0 * kelvin_xi(E) * (KL * mstar).sqrt(),
    }
}

fn jankowski(mstar: f64) -> Law {
    Law::Jankowski {
        kh: KH,
        c0: 2.0 * jankowski_xi(E) * (mstar * KH).sqrt(),
    }
}

fn hertzdamp(_: f64) -> Law {
    Law::HertzDamp {
        kh: KH,
        chi: lankarani_chi(E),
    }
}

/// The damped laws on the paper's cantilevers with 3 modes, 1000× the paper's Hertz stiffness
/// (k_h = 2.808e13 N/m^1.5; Kelvin k = 1e11 N/m; e = 0.6), 6 s, both methods at their defaults
/// with their self-checks: the top peaks, the peak force and the top's absolute acceleration
/// within the bar, and for Kelvin and Jankowski the section shear at 1…9 m too (measured:
/// Kelvin 4.2e-4 / 1.0e-3, Jankowski 6.1e-4 / 6.0e-4, damped Hertz 1.5e-4 / 7.5e-4, exact-modal
/// / adaptive; 74, 84 and 74 impacts as the reference). The reference
/// (RK4 at 10 µs, ω_c h ≈ 0.03) agrees with itself at 5 and 2.5 µs to ≤ 2.7e-4.
/// Not asserted here (reported): the damped Hertz law's section shears are ill-conditioned —
/// a grazing onset with a tiny v₀ makes `1 + χ δ̇/v₀` large, so the reference's own shears move
/// by up to 5 % between 2.5 and 1.25 µs while its peaks agree to 1e-7 — and the check says NOT
/// CONVERGED (floor_shear_2 5.2 %): honest. The undamped Hertz and linear laws with 3 modes are
/// chaotic here (tests/error_control.rs): the reference moves by 2.5 % (peak force) between
/// 2.5 and 1.25 µs and cannot judge them.
#[test]
fn damped_laws_on_stiff_cantilevers_with_3_modes_at_the_default() {
    let laws: Vec<NamedLaw> = vec![
        (
            "kelvin",
            format!("law = \"kelvin\"\nstiffness = {KL:e}\nrestitution = {E}\n"),
            kelvin,
        ),
        (
            "jankowski",
            format!("law = \"jankowski\"\nstiffness = {KH:e}\nrestitution = {E}\n"),
            jankowski,
        ),
    ];
    for (what, line) in cantilever_lines(3, 6.0, 1e-5, &laws, true, BOTH) {
        line.assert_within(5e-3, &what, "");
    }
    let damped: Vec<NamedLaw> = vec![(
        "hertzdamp",
        format!("law = \"hertzdamp\"\nstiffness = {KH:e}\nrestitution = {E}\n"),
        hertzdamp,
    )];
    for (what, line) in cantilever_lines(3, 6.0, 1e-5, &damped, false, BOTH) {
        line.assert_within(5e-3, &what, "");
    }
}

/// The damped Hertz law with 40 modes per cantilever (mode 40: ω ≈ 9.2e4 rad/s), 1000× the
/// paper's stiffness, over 1.2 s: both methods at their defaults within the bar on the top
/// peaks, the peak force, the section shear at 1…9 m and the top acceleration, the check
/// honest. The reference: RK4 at 2 µs (ω₄₀ h ≈ 0.18; over 2 s the same case at 0.5 and 1 µs
/// agreed to 1.7e-6 on peaks and force). Measured: exact-modal 2.3e-3 (check 2.3e-3),
/// adaptive 5.4e-4 (check 4.3e-4), both the top's acceleration (the rest within 6.4e-6), 17
/// impacts as the reference. (Over 2 s at 0.5 µs, measured once on peaks and force: undamped
/// Hertz, linear (k = 1e11 N/m), Kelvin, Jankowski and damped Hertz all within 8.7e-6 with
/// both methods; over 0.6 s at 1 µs with the section shears and top accelerations too:
/// undamped Hertz 6.1e-4 / 2.5e-5, linear 2.0e-3 / 1.2e-3, Jankowski 1.0e-3 / 4.4e-4,
/// exact-modal / adaptive, each check's estimate of the same size and converged; for Kelvin
/// see the two tests below.)
#[test]
fn damped_hertz_on_stiff_cantilevers_with_40_modes_at_the_default() {
    let damped: Vec<NamedLaw> = vec![(
        "hertzdamp",
        format!("law = \"hertzdamp\"\nstiffness = {KH:e}\nrestitution = {E}\n"),
        hertzdamp,
    )];
    for (what, line) in cantilever_lines(40, 1.2, 2e-6, &damped, true, BOTH) {
        assert!(line.impacts_ref >= 5, "premise: they pound");
        line.assert_within(5e-3, &what, "");
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
    let sizes = [3, 2];
    let levels = [
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
    ];
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

/// The Kelvin law (k = 1e11 N/m, e = 0.6) with 40 modes per cantilever, 0.6 s (the first
/// impacts): its force jumps to `c δ̇₀` at each onset and the top's absolute acceleration peaks
/// 4.4 µs later (the reference, RK4 at 1 µs: 1002.7 m/s² at 0.509456 s, the first onset at
/// 0.5094516 s), while the highest modes ring. `exact-modal` at its default is within the bar
/// on the top peaks, the force, the section shears and the top accelerations (measured 5.2e-4,
/// check 3.4e-4).
#[test]
fn kelvin_on_stiff_cantilevers_with_40_modes_exact_modal() {
    for (what, line) in cantilever_lines(40, 0.6, 1e-6, &kelvin_law(), true, &["exact-modal"]) {
        assert!(line.impacts_ref >= 3, "premise: they pound");
        line.assert_within(5e-3, &what, "");
    }
}

fn kelvin_law() -> Vec<NamedLaw> {
    vec![(
        "kelvin",
        format!("law = \"kelvin\"\nstiffness = {KL:e}\nrestitution = {E}\n"),
        kelvin,
    )]
}

/// FINDING (src/recording/floor_response/, not this audit's code): the same case with
/// `adaptive` at its default reports the top's peak absolute acceleration 5.7 % low (945.9
/// m/s² at 0.5094647 s against 1002.7 at 0.509456 s; its check run at rtol 1e-12 gets 1002.2).
/// The check flags it (NOT CONVERGED, floor_acceleration_1 changed by 5.6 %): honest, but above
/// the 0.5 % bar. The peak falls inside the first adaptive step after the onset (≈ 13 µs), where
/// the recorder has no observation: the accelerations inside an impact pulse
/// (floor_response/pulse.rs) are skipped for rate-dependent laws, Kelvin among them (its force
/// needs δ and δ̇ only, not an onset speed). Everything else of this run is within 1.5e-5.
#[test]
#[ignore = "finding: adaptive misses the top's peak acceleration right after a Kelvin onset with 40 modes (5.7 % low; pulse sampling skips rate-dependent laws)"]
fn kelvin_on_stiff_cantilevers_with_40_modes_adaptive() {
    for (what, line) in cantilever_lines(40, 0.6, 1e-6, &kelvin_law(), true, &["adaptive"]) {
        assert!(line.impacts_ref >= 3, "premise: they pound");
        line.assert_within(5e-3, &what, "");
    }
}
