//! The audit of the contact laws on the paper's cantilevers at 1000× its Hertz stiffness, 3 and
//! 40 modes, both error-controlled methods at their defaults with their self-checks, against an
//! independent RK4 in the cantilevers' modal coordinates (tests/common/physical_laws.rs: shapes,
//! Γ and section integrals written from docs/model.md, every law from its README formula, each
//! onset located by bisecting the step). The table's lines: tests/common/audit_line.rs.

// Index loops over the stations read like the formulas they check.
#![allow(clippy::needless_range_loop)]

mod common;

use pounding::analysis::simulate::simulate_checked;

use common::audit_line::Line;
use common::physical_laws::{
    Law, Level, cantilever, cantilever_shear, integrate_dofs, jankowski_xi, kelvin_xi,
    lankarani_chi,
};

const G: f64 = 9.80665;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
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

/// The Kelvin law (k = 1e11 N/m, e = 0.6) with 40 modes per cantilever, 0.6 s (the first
/// impacts): its force jumps to `c δ̇₀` at each onset and the top's absolute acceleration peaks
/// 4.4 µs later (the reference, RK4 at 1 µs: 1002.7 m/s² at 0.509456 s, the first onset at
/// 0.5094516 s), while the highest modes ring. `exact-modal` at its default is within the bar
/// on the top peaks, the force, the section shears and the top accelerations (measured 5.2e-4,
/// check 3.6e-4).
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

/// The same case with `adaptive` at its default. The top's peak absolute acceleration falls
/// 4.4 µs after an onset, inside the first adaptive step of the impact (≈ 13 µs), where the
/// recorder has no observation. Before the accelerations inside an impact pulse
/// (floor_response/pulse.rs) were evaluated for Kelvin and Jankowski too (their force needs δ
/// and δ̇ only, not an onset speed), this run was 5.7 % low (945.9 m/s² against 1002.7; its
/// check flagged it). With the quintic through the interval's ends starting from the
/// acceleration before the Kelvin force's jump `c δ̇` at the onset, it read 3.7e-3 high
/// (1006.4 m/s², the check's estimate 4.1e-3). Starting from the right-hand limit (the force
/// just after the jump): measured 1.64e-3 (1001.06 m/s²), the check's estimate 1.45e-3. Bound
/// 2.5e-3: 1.5× the measured, below the 3.7e-3 of the left-hand start.
#[test]
fn kelvin_on_stiff_cantilevers_with_40_modes_adaptive() {
    for (what, line) in cantilever_lines(40, 0.6, 1e-6, &kelvin_law(), true, &["adaptive"]) {
        assert!(line.impacts_ref >= 3, "premise: they pound");
        line.assert_within(2.5e-3, &what, "");
    }
}
