//! Buildings with floors (issue 11): scenario keys, errors, and the physics against an
//! independent integration in physical coordinates (written here, sharing nothing with the
//! program but the equations of motion).

use std::path::Path;

use pounding::scenario::Scenario;
use pounding::simulate::{Report, simulate};

fn scenario(text: &str) -> Result<Scenario, String> {
    Scenario::from_toml(text, "b.toml", Path::new(env!("CARGO_MANIFEST_DIR")))
        .map_err(|e| e.to_string())
}

fn run(text: &str) -> Report {
    simulate(&scenario(text).expect("valid scenario")).expect("runs")
}

const GROUND: &str = "[ground_motion]\nkind = \"harmonic\"\npga = 0.3\nperiod = 0.5\n";

/// Building A: 3 storeys, Rayleigh-damped (classical damping C = a₀M + a₁K, so that the
/// physical-coordinate integration below has exactly the modal model's damping).
const A: &str = "[[structure]]\nname = \"A\"\nkind = \"shear-building\"\n\
floor_heights = [3.0, 6.0, 9.0]\nfloor_masses = [2.0e5, 2.0e5, 1.5e5]\n\
storey_stiffnesses = [3.0e8, 2.5e8, 2.0e8]\nrayleigh = { damping_ratio = 0.03, modes = [1, 2] }\n";

/// Building B: 2 storeys at the same floor heights, more flexible.
const B: &str = "[[structure]]\nname = \"B\"\nkind = \"shear-building\"\n\
floor_heights = [3.0, 6.0]\nfloor_masses = [1.8e5, 1.8e5]\n\
storey_stiffnesses = [6.0e7, 5.0e7]\nrayleigh = { damping_ratio = 0.03, modes = [1, 2] }\n";

fn pair(contact: &str, solver: &str) -> String {
    format!("{A}{B}{contact}{GROUND}[solver]\n{solver}\n")
}

/// M, K, C (Rayleigh through modes i, j of the generalised problem, computed here by the
/// characteristic polynomial's roots) of a shear building, for the independent integration.
struct Physical {
    m: Vec<f64>,
    k: Vec<Vec<f64>>,
    c: Vec<Vec<f64>>,
}

fn physical(masses: &[f64], ks: &[f64], zeta: f64, w: (f64, f64)) -> Physical {
    let n = masses.len();
    let mut k = vec![vec![0.0; n]; n];
    for j in 0..n {
        k[j][j] = ks[j] + ks.get(j + 1).copied().unwrap_or(0.0);
        if j + 1 < n {
            k[j][j + 1] = -ks[j + 1];
            k[j + 1][j] = -ks[j + 1];
        }
    }
    let (wi, wj) = w;
    let a0 = 2.0 * zeta * wi * wj / (wi + wj);
    let a1 = 2.0 * zeta / (wi + wj);
    let c = (0..n)
        .map(|r| {
            (0..n)
                .map(|s| a1 * k[r][s] + if r == s { a0 * masses[r] } else { 0.0 })
                .collect()
        })
        .collect();
    Physical {
        m: masses.to_vec(),
        k,
        c,
    }
}

/// The two lowest ω of `K φ = ω² M φ` for a 2- or 3-DOF shear building by bisection on
/// det(K − ω²M) (a tridiagonal determinant by recurrence): independent of the program's
/// eigen-solver.
fn lowest_two(p: &Physical) -> (f64, f64) {
    let det = |l: f64| {
        let n = p.m.len();
        let (mut d0, mut d1) = (1.0, p.k[0][0] - l * p.m[0]);
        for j in 1..n {
            let d2 = (p.k[j][j] - l * p.m[j]) * d1 - p.k[j][j - 1] * p.k[j - 1][j] * d0;
            (d0, d1) = (d1, d2);
        }
        d1
    };
    let mut roots = Vec::new();
    let (mut l, step) = (1e-6, 0.05);
    let mut f = det(l);
    while roots.len() < 2 {
        let l2 = l * (1.0 + step);
        let f2 = det(l2);
        if f.signum() != f2.signum() {
            let (mut a, mut b) = (l, l2);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                if det(mid).signum() == det(a).signum() {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            roots.push((0.5 * (a + b)).sqrt());
        }
        (l, f) = (l2, f2);
    }
    (roots[0], roots[1])
}

/// RK4 in physical coordinates of both buildings with Hertz contact at common floors
/// (`levels`: floor index in A and in B, gap) under a_g = −A_g sin(Ω t); returns the peak
/// displacements of floor `watch.0` of A and `watch.1` of B, and the peak contact force, sampled every step (dt small enough that a step's
/// peak misses the true one by far less than the tolerance asserted).
fn integrate_physical(
    a: &Physical,
    b: &Physical,
    levels: &[(usize, usize, f64)],
    kh: f64,
    ag: (f64, f64),
    duration: f64,
    dt: f64,
    watch: (usize, usize),
) -> (f64, f64, f64) {
    let (na, nb) = (a.m.len(), b.m.len());
    let n = na + nb;
    let accel = |t: f64, y: &[f64], out: &mut [f64], force_out: &mut f64| {
        // the program's harmonic motion is the displacement y = A sin Ωt (docs/model.md §2.8):
        // a_g = ÿ = −PGA·g·sin Ωt
        let a_g = -ag.0 * (ag.1 * t).sin();
        let (u, v) = y.split_at(n);
        let mut f = vec![0.0; n];
        let mut total = 0.0;
        for &(fa, fb, gap) in levels {
            let delta = u[fa] - u[na + fb] - gap;
            if delta > 0.0 {
                let fc = kh * delta.powf(1.5);
                f[fa] -= fc;
                f[na + fb] += fc;
                // (the program's peak force is the largest of the levels' peaks)
                total = f64::max(total, fc);
            }
        }
        *force_out = total;
        for (off, p, nn) in [(0, a, na), (na, b, nb)] {
            for r in 0..nn {
                let mut s = f[off + r] - p.m[r] * a_g;
                for c in 0..nn {
                    s -= p.k[r][c] * u[off + c] + p.c[r][c] * v[off + c];
                }
                out[off + r] = v[off + r];
                out[n + off + r] = s / p.m[r];
            }
        }
    };
    let mut y = vec![0.0; 2 * n];
    let (mut k1, mut k2, mut k3, mut k4) = (
        vec![0.0; 2 * n],
        vec![0.0; 2 * n],
        vec![0.0; 2 * n],
        vec![0.0; 2 * n],
    );
    let mut tmp = vec![0.0; 2 * n];
    let (mut p1, mut p2, mut pf) = (0.0f64, 0.0f64, 0.0f64);
    let steps = (duration / dt).round() as usize;
    let mut fdummy = 0.0;
    for s in 0..steps {
        let t = s as f64 * dt;
        let mut f0 = 0.0;
        accel(t, &y, &mut k1, &mut f0);
        pf = pf.max(f0);
        for i in 0..2 * n {
            tmp[i] = y[i] + 0.5 * dt * k1[i];
        }
        accel(t + 0.5 * dt, &tmp, &mut k2, &mut fdummy);
        for i in 0..2 * n {
            tmp[i] = y[i] + 0.5 * dt * k2[i];
        }
        accel(t + 0.5 * dt, &tmp, &mut k3, &mut fdummy);
        for i in 0..2 * n {
            tmp[i] = y[i] + dt * k3[i];
        }
        accel(t + dt, &tmp, &mut k4, &mut fdummy);
        for i in 0..2 * n {
            y[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        p1 = p1.max(y[watch.0].abs());
        p2 = p2.max(y[na + watch.1].abs());
    }
    (p1, p2, pf)
}

fn physical_pair() -> (Physical, Physical) {
    let pa0 = physical(
        &[2.0e5, 2.0e5, 1.5e5],
        &[3.0e8, 2.5e8, 2.0e8],
        0.03,
        (1.0, 2.0),
    );
    let pb0 = physical(&[1.8e5, 1.8e5], &[6.0e7, 5.0e7], 0.03, (1.0, 2.0));
    let (wa, wb) = (lowest_two(&pa0), lowest_two(&pb0));
    (
        physical(&[2.0e5, 2.0e5, 1.5e5], &[3.0e8, 2.5e8, 2.0e8], 0.03, wa),
        physical(&[1.8e5, 1.8e5], &[6.0e7, 5.0e7], 0.03, wb),
    )
}

/// With every mode kept the modal model is exact: without contact, and with Hertz contact at
/// the two common floors, the program (`adaptive` at rtol 1e-10) agrees with RK4 in physical
/// coordinates at dt = 2e-5 s (its own error ~(ω dt)⁴, far below 1e-5 here; the contact
/// ω_c·dt ≈ 0.03) on both top peaks and the peak force to 1e-4 (the physical RK4 samples the
/// peak force at its steps: ~1e-5 low).
#[test]
fn shear_buildings_match_a_physical_coordinate_integration() {
    let (pa, pb) = physical_pair();
    let (pga, tg) = (0.3 * 9.80665, 0.5);
    let omega = 2.0 * std::f64::consts::PI / tg;
    let duration = 4.0;
    let contact = "[contact]\nlaw = \"hertz\"\nstiffness = 2.0e9\n\
        [[contact.level]]\nheight = 6.0\ngap = 0.01\n[[contact.level]]\nheight = 3.0\ngap = 0.01\n";
    let r = run(&pair(
        contact,
        &format!("duration = {duration}\ndt = 1e-3\nrtol = 1e-10\noutput_interval = 0.001"),
    ));
    // the program's peaks are at the main contact height, 6 m: floor 2 of A, the top of B
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    let (f1, f2, _) =
        integrate_physical(&pa, &pb, &[], 2.0e9, (pga, omega), duration, 2e-5, (1, 1));
    assert!(
        rel(r.structures[0].peak_displacement_no_contact, f1) < 1e-6,
        "A free: {} vs {f1}",
        r.structures[0].peak_displacement_no_contact
    );
    assert!(
        rel(r.structures[1].peak_displacement_no_contact, f2) < 1e-6,
        "B free: {} vs {f2}",
        r.structures[1].peak_displacement_no_contact
    );
    let (c1, c2, cf) = integrate_physical(
        &pa,
        &pb,
        &[(1, 1, 0.01), (0, 0, 0.01)],
        2.0e9,
        (pga, omega),
        duration,
        2e-5,
        (1, 1),
    );
    assert!(
        r.contact.impacts > 2,
        "premise: they pound ({} impacts)",
        r.contact.impacts
    );
    assert!(
        rel(r.structures[0].peak_displacement, c1) < 1e-4,
        "A with contact: {} vs physical {c1}",
        r.structures[0].peak_displacement
    );
    assert!(
        rel(r.structures[1].peak_displacement, c2) < 1e-4,
        "B with contact: {} vs physical {c2}",
        r.structures[1].peak_displacement
    );
    assert!(
        rel(r.contact.peak_force, cf) < 1e-4,
        "peak force {} vs physical {cf}",
        r.contact.peak_force
    );
}

/// A `modal` structure built from a shear building's own periods and shapes (in another
/// normalisation) gives the same results as the shear building, to round-off.
#[test]
fn modal_kind_from_a_shear_buildings_modes_gives_the_same_results() {
    let contact = "[contact]\nlaw = \"hertz\"\nstiffness = 2.0e9\ngap = 0.01\nheight = 6.0\n";
    let solver = "duration = 3.0\ndt = 1e-3";
    let shear = pair(contact, solver);
    let sc = scenario(&shear).unwrap();
    let m = sc.structures[0].modal();
    let heights = [3.0, 6.0, 9.0];
    let periods: Vec<String> = m.periods().iter().map(|t| format!("{t:?}")).collect();
    let shapes: Vec<String> = (0..3)
        .map(|n| {
            let v: Vec<String> = heights
                .iter()
                .map(|&h| format!("{:?}", -3.0 * m.shape(n, h) * 1e3))
                .collect();
            format!("[{}]", v.join(", "))
        })
        .collect();
    let zeta: Vec<String> = m.zeta.iter().map(|z| format!("{z:?}")).collect();
    let modal_a = format!(
        "[[structure]]\nname = \"A\"\nkind = \"modal\"\nfloor_heights = [3.0, 6.0, 9.0]\n\
         floor_masses = [2.0e5, 2.0e5, 1.5e5]\nperiods = [{}]\nmode_shapes = [{}]\n\
         damping_ratio = [{}]\n",
        periods.join(", "),
        shapes.join(", "),
        zeta.join(", ")
    );
    let modal = format!("{modal_a}{B}{contact}{GROUND}[solver]\n{solver}\n");
    let (a, b) = (run(&shear), run(&modal));
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(1e-300);
    for i in 0..2 {
        assert!(
            rel(
                b.structures[i].peak_displacement,
                a.structures[i].peak_displacement
            ) < 1e-9
        );
    }
    assert!(rel(b.contact.peak_force, a.contact.peak_force) < 1e-9);
    assert_eq!(a.contact.impacts, b.contact.impacts);
}

/// The same modes from a CSV file (`height, mass, mode_1, …`) as inline.
#[test]
fn modes_file_reads_the_engineers_table() {
    let dir = std::env::temp_dir().join(format!("pounding-modes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("modes.csv"),
        "height, mass, mode_1, mode_2\n3.0, 1.0e5, 0.5, -1.0\n6.0, 0.5e5, 1.0, 1.0\n",
    )
    .unwrap();
    // 2 storeys, m₁ = 2m, m₂ = m: φ₁ ∝ (½, 1), φ₂ ∝ (−1, 1) are M-orthogonal (2m·½·(−1) + m = 0)
    let text = format!(
        "[[structure]]\nkind = \"modal\"\nmodes_file = \"modes.csv\"\nperiods = [0.5, 0.25]\n{B}\
         [contact]\nstiffness = 2.0e9\ngap = 0.01\nheight = 6.0\n{GROUND}"
    );
    let sc = Scenario::from_toml(&text, "m.toml", &dir).unwrap();
    let m = sc.structures[0].modal();
    // φ₁ = (½, 1)/√(2m/4 + m) with m = 0.5e5
    let s = (1.5 * 0.5e5f64).sqrt();
    assert!((m.shape(0, 6.0) - 1.0 / s).abs() < 1e-12);
    assert!((m.participation[0] - 2.0 * 0.5e5 / s).abs() < 1e-6);
    std::fs::write(dir.join("modes.csv"), "h, m, a\n3, 1, 1\n").unwrap();
    let e = Scenario::from_toml(&text, "m.toml", &dir)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("modes_file") && e.contains("height, mass"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Errors name the file, the key and what is allowed.
#[test]
fn building_errors_name_the_key() {
    let contact = "[contact]\nstiffness = 2.0e9\ngap = 0.01\nheight = 4.5\n";
    let e = scenario(&pair(contact, "duration = 1.0")).unwrap_err();
    assert!(
        e.contains("contact.height") && e.contains("3, 6, 9") && e.contains("floor"),
        "{e}"
    );
    let bad_kind = A.replace("shear-building", "shear");
    let e = scenario(&format!(
        "{bad_kind}{B}[contact]\nstiffness = 1e9\ngap = 0.01\n{GROUND}"
    ))
    .unwrap_err();
    assert!(
        e.contains("structure[1].kind") && e.contains("shear-building"),
        "{e}"
    );
    let mixed = A.replace("name = \"A\"", "name = \"A\"\nperiod = 0.5");
    let e = scenario(&format!(
        "{mixed}{B}[contact]\nstiffness = 1e9\ngap = 0.01\n{GROUND}"
    ))
    .unwrap_err();
    assert!(
        e.contains("structure[1].period") && e.contains("not a key of kind"),
        "{e}"
    );
    let down = A.replace("[3.0, 6.0, 9.0]", "[3.0, 9.0, 6.0]");
    let e = scenario(&format!(
        "{down}{B}[contact]\nstiffness = 1e9\ngap = 0.01\n{GROUND}"
    ))
    .unwrap_err();
    assert!(e.contains("floor_heights") && e.contains("increase"), "{e}");
    let short = A.replace("[2.0e5, 2.0e5, 1.5e5]", "[2.0e5, 2.0e5]");
    let e = scenario(&format!(
        "{short}{B}[contact]\nstiffness = 1e9\ngap = 0.01\n{GROUND}"
    ))
    .unwrap_err();
    assert!(
        e.contains("floor_masses") && e.contains("one mass per floor"),
        "{e}"
    );
}

/// A shear building pounds a cantilever (any two kinds): the uniform shorthand, the default
/// contact height (the top of the lower one, a floor of the building), both runs.
#[test]
fn a_shear_building_pounds_a_cantilever() {
    let text = format!(
        "[[structure]]\nkind = \"shear-building\"\nstoreys = 3\nstorey_height = 3.0\n\
         floor_mass = 2.0e5\nstorey_stiffness = 2.0e8\n\
         [[structure]]\nlength = 12.0\nmass = 1.0e6\nperiod = 0.9\nmodes = 5\n\
         [contact]\nstiffness = 2.0e9\ngap = 0.005\n{GROUND}[solver]\nduration = 3.0\n"
    );
    let sc = scenario(&text).unwrap();
    assert_eq!(sc.contact.levels[0].height, 9.0);
    assert_eq!(sc.structures[0].modes(), 3);
    let r = simulate(&sc).unwrap();
    assert!(r.contact.impacts > 0);
}
