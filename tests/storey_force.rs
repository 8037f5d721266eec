//! The storey force (`floors[].peak_shear`) means one thing for every kind of structure
//! (docs/model.md §2.6c): the force the storey's structure carries, without damping forces.
//! Each kind is checked here against a reference written in the test from the equations alone:
//! a building given by its modes (not a shear building's) against an integration in physical
//! coordinates with `Σ_{g ≥ j} (K u)_g`, and a cantilever's section shear against `−EI w‴`
//! of the closed-form harmonic response. (Shear buildings: `tests/buildings.rs`, k·drift
//! against the physical integration; yielding storeys: `tests/hysteresis.rs`.)

use std::f64::consts::PI;

use pounding::analysis::simulate::Report;

mod common;
use common::{Case, Physical, integrate_physical, physical};

fn run(text: &str) -> Report {
    common::run_named(text, "s.toml")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// A 3-floor structure given by its modes, chosen so that its stiffness is *not* a chain of
/// storey springs (K = M Φ Ω² Φᵀ M couples floors 1 and 3, as a frame's flexure does): shapes
/// M-orthonormalised by Gram–Schmidt from three vectors, periods 0.30, 0.11, 0.07 s, ζ = 3 %
/// in every mode (C = M Φ 2ZΩ Φᵀ M). Returns its modes (columns of Φ, per mode) and the
/// physical matrices.
fn frame() -> (Vec<Vec<f64>>, [f64; 3], Physical) {
    let m = [2.0e5, 2.0e5, 1.5e5];
    let periods = [0.30, 0.11, 0.07];
    let zeta = 0.03;
    let mdot = |a: &[f64], b: &[f64]| (0..3).map(|i| a[i] * m[i] * b[i]).sum::<f64>();
    let mut phi: Vec<Vec<f64>> = Vec::new();
    for v in [[0.35, 0.75, 1.0], [1.0, 0.6, -0.9], [0.8, -1.0, 0.5]] {
        let mut w = v.to_vec();
        for p in &phi {
            let c = mdot(&w, p);
            for i in 0..3 {
                w[i] -= c * p[i];
            }
        }
        let norm = mdot(&w, &w).sqrt();
        phi.push(w.iter().map(|x| x / norm).collect());
    }
    let omega = periods.map(|t| 2.0 * PI / t);
    let mat = |f: &dyn Fn(usize) -> f64| -> Vec<Vec<f64>> {
        (0..3)
            .map(|r| {
                (0..3)
                    .map(|c| {
                        (0..3)
                            .map(|n| m[r] * phi[n][r] * f(n) * phi[n][c] * m[c])
                            .sum()
                    })
                    .collect()
            })
            .collect()
    };
    let k = mat(&|n| omega[n] * omega[n]);
    let c = mat(&|n| 2.0 * zeta * omega[n]);
    (
        phi,
        periods,
        Physical {
            m: m.to_vec(),
            k,
            c,
            springs: None,
        },
    )
}

/// A building given by its modes whose stiffness is not a shear building's: its storey force
/// comes from the modes' equivalent static forces, `Σ_{g ≥ j} m_g Σ_n φ_n(g) ω_n² η_n` (the
/// program, every mode kept, `adaptive` at rtol 1e-10 with observations every ≤ 0.1 ms) against
/// `Σ_{g ≥ j} (K u)_g` of RK4 in physical coordinates at dt = 2e-5 s, pounding a 2-storey shear
/// building at two floors under a harmonic motion: every floor's storey force and displacement
/// to 1e-6 (refined between the program's steps, sampled every 2e-5 s in the reference, whose
/// RK4 error (ω dt)⁴ is far below; measured 5e-8), the equilibrium shear (storey force plus the
/// damping forces above) to 1e-5 (taken at the program's observations, not refined: ~(ω h)²/8
/// with h ≤ 0.1 ms; measured 1e-6).
#[test]
fn a_building_given_by_its_modes_carries_k_u_of_the_floors_above() {
    let (phi, periods, pa) = frame();
    // premise: not a chain of storey springs (floor 1 and floor 3 coupled)
    let kmax = pa.k.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(pa.k[0][2].abs() > 1e-2 * kmax, "{:?}", pa.k);
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let shapes: Vec<String> = phi.iter().map(|p| format!("[{}]", list(p))).collect();
    let text = format!(
        "[[structure]]\nname = \"frame\"\nkind = \"modal\"\nfloor_heights = [3.0, 6.0, 9.0]\n\
         floor_masses = [2.0e5, 2.0e5, 1.5e5]\nperiods = [{}]\nmode_shapes = [{}]\n\
         damping_ratio = 0.03\n\
         [[structure]]\nname = \"B\"\nkind = \"shear-building\"\nfloor_heights = [3.0, 6.0]\n\
         floor_masses = [1.8e5, 1.8e5]\nstorey_stiffnesses = [6.0e7, 5.0e7]\n\
         rayleigh = {{ damping_ratio = 0.03, modes = [1, 2] }}\n\
         [contact]\nlaw = \"hertz\"\nstiffness = 2.0e9\n\
         [[contact.level]]\nheight = 6.0\ngap = 0.01\n[[contact.level]]\nheight = 3.0\ngap = 0.01\n\
         [ground_motion]\nkind = \"harmonic\"\npga = 0.3\nperiod = 0.5\n\
         [solver]\nduration = 4.0\ndt = 1e-4\nrtol = 1e-10\noutput_interval = 0.01\n",
        list(&periods),
        shapes.join(", ")
    );
    let r = run(&text);
    assert!(r.contact.impacts > 2, "premise: they pound");
    let pb = physical(&[1.8e5, 1.8e5], &[6.0e7, 5.0e7], 0.03);
    let mut case = Case {
        levels: &[],
        kh: 2.0e9,
        pga: 0.3 * 9.80665,
        omega: 2.0 * PI / 0.5,
        duration: 4.0,
        dt: 2e-5,
    };
    let (free, _) = integrate_physical(&pa, &pb, &case);
    case.levels = &[(1, 1, 0.01), (0, 0, 0.01)];
    let (with, _) = integrate_physical(&pa, &pb, &case);
    let mut worst = [0.0f64; 3];
    for (f, fl) in r.structures[0].floors.iter().enumerate() {
        let checks = [
            ("storey force", fl.peak_shear, with[0].force[f], 1e-6, 0),
            (
                "storey force free",
                fl.peak_shear_no_contact,
                free[0].force[f],
                1e-6,
                0,
            ),
            (
                "equilibrium",
                fl.peak_shear_with_damping,
                with[0].shear[f],
                1e-5,
                1,
            ),
            (
                "equilibrium free",
                fl.peak_shear_with_damping_no_contact,
                free[0].shear[f],
                1e-5,
                1,
            ),
            (
                "displacement",
                fl.peak_displacement,
                with[0].disp[f],
                1e-6,
                2,
            ),
        ];
        for (what, got, want, tol, k) in checks {
            let e = rel(got, want);
            worst[k] = worst[k].max(e);
            assert!(
                e < tol,
                "floor {}: {what} {got} vs physical {want} ({e:.1e})",
                f + 1
            );
        }
    }
    eprintln!(
        "frame given by its modes vs physical: storey force {:.1e}, equilibrium {:.1e}, \
         displacement {:.1e}",
        worst[0], worst[1], worst[2]
    );
}

/// `η̈ + 2ζωη̇ + ω²η = a sin Ωt` from rest: the steady state plus the transient that starts it
/// at rest.
fn harmonic_mode(a: f64, w: f64, z: f64, om: f64, t: f64) -> f64 {
    let (k, c) = (w * w - om * om, 2.0 * z * w * om);
    let del = k * k + c * c;
    let (cs, cc) = (a * k / del, -a * c / del);
    let wd = w * (1.0 - z * z).sqrt();
    let h0 = -cc;
    let h1 = (z * w * h0 - cs * om) / wd;
    cs * (om * t).sin()
        + cc * (om * t).cos()
        + (-z * w * t).exp() * (h0 * (wd * t).cos() + h1 * (wd * t).sin())
}

/// A cantilever's storey force at a station is its section shear `−EI w‴(x)`: the paper's
/// structure 1 (L = 10 m, M = 2.273e6 kg, T₁ = 0.4203 s, ζ = 1 %, 4 modes) without contact
/// under a_g = −0.6 g sin(2πt/0.65), against the closed form written here from the textbook
/// mode shapes: `y_n(ξ) = cosh λξ − cos λξ − σ(sinh λξ − sin λξ)`,
/// `σ = (sinh λ − sin λ)/(cosh λ + cos λ)`, φ_n = y_n/√(mL),
/// `y‴ = λ³[sinh λξ − sin λξ − σ(cosh λξ + cos λξ)]`, EI = m L⁴ (ω₁/λ₁²)², ω_n = ω₁(λ_n/λ₁)²,
/// Γ_n = √(mL)·2σ_n/λ_n, each mode's harmonic response from rest; `V = −EI Σ φ_n‴ η_n` sampled every 2e-5 s over 3 s. At every station below the top to
/// 1e-6 (the program: `adaptive` at rtol 1e-10, steps ≤ 0.2 ms, the peak refined on the
/// Hermite cubic, whose error (ω₄h)⁴/384 ≈ 3e-7 of the fourth mode's small share; the sampled
/// reference misses a crest by ~(ω₁·1e-5)²/2 ≈ 1e-8; measured 1e-8); at the free top it is
/// zero.
#[test]
fn a_cantilevers_storey_force_is_minus_ei_w_triple_prime() {
    let text = include_str!("../examples/paper-c.toml")
        .replace("modes = 3", "modes = 4")
        .replace("method = \"rk4\"", "method = \"adaptive\"\nrtol = 1e-10")
        .replace("dt = 0.001", "dt = 2e-4")
        .replace("duration = 20.0", "duration = 3.0");
    let r = run(&text);
    let (l, mass, t1, zeta): (f64, f64, f64, f64) = (10.0, 2.273e6, 0.4203, 0.01);
    let mpl = mass / l;
    let lambda = [
        1.875104068711961,
        4.694091132974175,
        7.854757438237613,
        10.995540734875467,
    ];
    let w1 = 2.0 * PI / t1;
    let ei = mpl * l.powi(4) * (w1 / (lambda[0] * lambda[0])).powi(2);
    let sigma = lambda.map(|x: f64| (x.sinh() - x.sin()) / (x.cosh() + x.cos()));
    let omega = lambda.map(|x| w1 * (x / lambda[0]).powi(2));
    let gamma: Vec<f64> = (0..4)
        .map(|n| (mpl * l).sqrt() * 2.0 * sigma[n] / lambda[n])
        .collect();
    let floors = &r.structures[0].floors;
    // −EI φ_n‴(x) per station and mode
    let coef: Vec<Vec<f64>> = floors
        .iter()
        .map(|f| {
            let xi = f.height / l;
            (0..4)
                .map(|n| {
                    let (x, s) = (lambda[n] * xi, sigma[n]);
                    let y3 = lambda[n].powi(3) * (x.sinh() - x.sin() - s * (x.cosh() + x.cos()));
                    -ei * y3 / ((mpl * l).sqrt() * l.powi(3))
                })
                .collect()
        })
        .collect();
    let (p, om) = (0.6 * 9.80665, 2.0 * PI / 0.65);
    let mut peak = vec![0.0f64; floors.len()];
    let mut t = 0.0;
    while t <= 3.0 {
        let eta: Vec<f64> = (0..4)
            .map(|n| harmonic_mode(gamma[n] * p, omega[n], zeta, om, t))
            .collect();
        for (pk, c) in peak.iter_mut().zip(&coef) {
            let v: f64 = (0..4).map(|n| c[n] * eta[n]).sum();
            *pk = pk.max(v.abs());
        }
        t += 2e-5;
    }
    let mut worst: f64 = 0.0;
    for (f, (fl, want)) in floors.iter().zip(&peak).enumerate() {
        if f + 1 == floors.len() {
            assert!(fl.peak_shear_no_contact <= 1e-9 * floors[0].peak_shear_no_contact);
            continue;
        }
        let e = rel(fl.peak_shear_no_contact, *want);
        worst = worst.max(e);
        assert!(
            e < 1e-6,
            "{} m: {} vs −EI w‴ {want} ({e:.1e})",
            fl.height,
            fl.peak_shear_no_contact
        );
    }
    eprintln!("cantilever section shear vs −EI w‴: {worst:.1e}");
}
