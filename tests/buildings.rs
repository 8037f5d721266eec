//! Buildings with floors (issue 11): scenario keys, errors, and the physics against an
//! independent integration in physical coordinates (written here, sharing nothing with the
//! program but the equations of motion).

use std::path::Path;

use pounding::analysis::simulate::{Report, simulate};
use pounding::input::scenario::Scenario;

mod common;
use common::{BUILDING_A as A, BUILDING_B as B, Case, Physical, integrate_physical, physical};

fn scenario(text: &str) -> Result<Scenario, String> {
    common::scenario_named(text, "b.toml")
}

fn run(text: &str) -> Report {
    common::run_named(text, "b.toml")
}

const GROUND: &str = "[ground_motion]\nkind = \"harmonic\"\npga = 0.3\nperiod = 0.5\n";

fn pair(contact: &str, solver: &str) -> String {
    format!("{A}{B}{contact}{GROUND}[solver]\n{solver}\n")
}

fn physical_pair() -> (Physical, Physical) {
    (
        physical(&[2.0e5, 2.0e5, 1.5e5], &[3.0e8, 2.5e8, 2.0e8], 0.03),
        physical(&[1.8e5, 1.8e5], &[6.0e7, 5.0e7], 0.03),
    )
}

/// With every mode kept the modal model is exact: without contact, and with Hertz contact at
/// the two common floors, the program (`adaptive` at rtol 1e-10, dt = 1e-4 s so that its
/// observations are as dense as the peaks need) agrees with RK4 in physical coordinates at
/// dt = 2e-5 s (its own error ~(ω dt)⁴, far below 1e-5; the contact ω_c·dt ≈ 0.03) at every
/// floor of both buildings: displacements, drifts and storey forces `k_j·(u_j − u_{j−1})`
/// (`peak_shear`, refined between steps like the drift) to 1e-4 (1e-5 without contact),
/// absolute accelerations and the equilibrium shear `Σ_{f ≥ j}(F_f − m_f a_f)`
/// (`peak_shear_with_damping`) to 1e-3 (both take their peaks at the steps: ~(ω h)²/8 apart),
/// the peak contact force to 1e-4.
#[test]
fn shear_buildings_match_a_physical_coordinate_integration() {
    let (pa, pb) = physical_pair();
    let contact = "[contact]\nlaw = \"hertz\"\nstiffness = 2.0e9\n\
        [[contact.level]]\nheight = 6.0\ngap = 0.01\n[[contact.level]]\nheight = 3.0\ngap = 0.01\n";
    let duration = 4.0;
    let r = run(&pair(
        contact,
        &format!("duration = {duration}\ndt = 1e-4\nrtol = 1e-10\noutput_interval = 0.01"),
    ));
    assert!(
        r.contact.impacts > 2,
        "premise: they pound ({} impacts)",
        r.contact.impacts
    );
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    let mut case = Case {
        levels: &[],
        kh: 2.0e9,
        pga: 0.3 * 9.80665,
        omega: 2.0 * std::f64::consts::PI / 0.5,
        duration,
        dt: 2e-5,
    };
    let (free, _) = integrate_physical(&pa, &pb, &case);
    case.levels = &[(1, 1, 0.01), (0, 0, 0.01)];
    let (with, force) = integrate_physical(&pa, &pb, &case);
    for i in 0..2 {
        let floors = &r.structures[i].floors;
        assert_eq!(floors.len(), with[i].disp.len());
        for (f, fl) in floors.iter().enumerate() {
            let at = |what: &str| format!("building {} floor {} {what}", i + 1, f + 1);
            let checks = [
                ("displacement", fl.peak_displacement, with[i].disp[f], 1e-4),
                (
                    "displacement free",
                    fl.peak_displacement_no_contact,
                    free[i].disp[f],
                    1e-5,
                ),
                ("drift", fl.peak_drift, with[i].drift[f], 1e-4),
                (
                    "drift free",
                    fl.peak_drift_no_contact,
                    free[i].drift[f],
                    1e-5,
                ),
                ("acceleration", fl.peak_acceleration, with[i].acc[f], 1e-3),
                (
                    "acceleration free",
                    fl.peak_acceleration_no_contact,
                    free[i].acc[f],
                    1e-4,
                ),
                ("storey force", fl.peak_shear, with[i].force[f], 1e-4),
                (
                    "storey force free",
                    fl.peak_shear_no_contact,
                    free[i].force[f],
                    1e-5,
                ),
                (
                    "shear with damping",
                    fl.peak_shear_with_damping,
                    with[i].shear[f],
                    1e-3,
                ),
                (
                    "shear with damping free",
                    fl.peak_shear_with_damping_no_contact,
                    free[i].shear[f],
                    1e-4,
                ),
            ];
            for (what, got, want, tol) in checks {
                assert!(
                    rel(got, want) < tol,
                    "{}: {got} vs physical {want} ({:.1e})",
                    at(what),
                    rel(got, want)
                );
            }
        }
    }
    assert!(
        rel(r.contact.peak_force, force) < 1e-4,
        "peak force {} vs physical {force}",
        r.contact.peak_force
    );
}

/// A `modal` structure built from a shear building's own periods and shapes (in another
/// normalisation) gives the same results as the shear building, to round-off — with every mode
/// and with the first two of three — and so the same storey forces at every floor: the modes'
/// equivalent static forces `K φ_n = ω_n² M φ_n` summed over the floors above are `k_j` times
/// the storey's drift for each mode, kept or not (to 1e-6; measured 8e-10 with three modes,
/// whose two runs' step decisions may differ in round-off, 9e-15 with two; printed).
#[test]
fn modal_kind_from_a_shear_buildings_modes_gives_the_same_results() {
    let contact = "[contact]\nlaw = \"hertz\"\nstiffness = 2.0e9\ngap = 0.01\nheight = 6.0\n";
    let solver = "duration = 3.0\ndt = 1e-3";
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(1e-300);
    for kept in [3, 2] {
        let a_kept = A.replace("rayleigh =", &format!("modes = {kept}\nrayleigh ="));
        let shear = format!("{a_kept}{B}{contact}{GROUND}[solver]\n{solver}\n");
        let sc = scenario(&shear).unwrap();
        let m = sc.structures[0].modal();
        assert_eq!(m.len(), kept);
        let modal_a = common::modal_building_a(&m);
        let modal = format!("{modal_a}{B}{contact}{GROUND}[solver]\n{solver}\n");
        let (a, b) = (run(&shear), run(&modal));
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
        // the equilibrium shear is taken at the integrator's observations, whose times may
        // differ by round-off step decisions between the two runs (not refined between them,
        // unlike the storey force): 1e-4
        let mut worst: f64 = 0.0;
        for i in 0..2 {
            for (fa, fb) in a.structures[i].floors.iter().zip(&b.structures[i].floors) {
                for (x, y, tol) in [
                    (fb.peak_shear, fa.peak_shear, 1e-6),
                    (fb.peak_shear_no_contact, fa.peak_shear_no_contact, 1e-6),
                    (fb.peak_shear_with_damping, fa.peak_shear_with_damping, 1e-4),
                ] {
                    assert!(
                        rel(x, y) < tol,
                        "{kept} modes, structure {i} floor {}: {x} vs {y}",
                        fa.height
                    );
                }
                worst = worst
                    .max(rel(fb.peak_shear, fa.peak_shear))
                    .max(rel(fb.peak_shear_no_contact, fa.peak_shear_no_contact));
            }
        }
        eprintln!("{kept} modes: storey forces of the modal kind within {worst:.1e}");
    }
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

/// A cantilever's stations are every tenth of its height and each contact height; at the top
/// nothing is above, so its equilibrium shear is the contact force there alone: 0 without
/// contact and the peak contact force with pounding at the top (`V(L) = F − m∫_L^L a`; to
/// 1e-4, the shear being taken at the integration steps and the force refined between them),
/// while the section force `−EI w‴(L)` is zero at the free end (every mode's y‴(1) = 0; to
/// round-off against the base's). The displacement peak at the contact height equals the run's
/// `peak_displacement`.
#[test]
fn cantilever_stations_and_the_shear_at_the_top() {
    // `adaptive`: its steps in contact are short, so the shear (taken at the steps, not refined
    // between them as the force is) reaches the located peak force closely
    let text = include_str!("../examples/paper-c.toml")
        .replace("duration = 20.0", "duration = 3.0")
        .replace("method = \"rk4\"", "method = \"adaptive\"");
    assert!(text.contains("adaptive"));
    let sc =
        Scenario::from_toml(&text, "paper-c.toml", Path::new(env!("CARGO_MANIFEST_DIR"))).unwrap();
    let r = simulate(&sc).unwrap();
    for (i, s) in r.structures.iter().enumerate() {
        let heights: Vec<f64> = s.floors.iter().map(|f| f.height).collect();
        let want: Vec<f64> = (1..=10).map(|k| 10.0 * k as f64 / 10.0).collect();
        assert_eq!(heights.len(), 10);
        for (a, b) in heights.iter().zip(&want) {
            assert!((a - b).abs() < 1e-12, "structure {}: {heights:?}", i + 1);
        }
        let top = s.floors.last().unwrap();
        // (zero to round-off: the modes' integrals above the top are ~1e-13 of their size)
        let base = s.floors[0].peak_shear_with_damping_no_contact;
        assert!(
            top.peak_shear_with_damping_no_contact <= 1e-9 * base,
            "{} vs base {base}",
            top.peak_shear_with_damping_no_contact
        );
        assert!(
            (top.peak_shear_with_damping - r.contact.peak_force).abs()
                <= 1e-4 * r.contact.peak_force,
            "{} vs {}",
            top.peak_shear_with_damping,
            r.contact.peak_force
        );
        for v in [top.peak_shear, top.peak_shear_no_contact] {
            assert!(v <= 1e-9 * s.floors[0].peak_shear, "{v}");
        }
        assert!((top.peak_displacement - s.peak_displacement).abs() <= 1e-12 * s.peak_displacement);
    }
}

/// Issue 13 on buildings: the spectral peak displacement at every floor. Two one-storey
/// buildings (one mode each: φ = 1/√m, Γ = √m, so u = Γφ·S_d = S_d exactly) under the ASCE 7
/// spectrum S_DS = 1 g, S_D1 = 0.6 g: building 1 (m = 1e5 kg, k = 4e7 N/m) has ω = 20 rad/s,
/// T = 0.3142 s on the plateau (T₀ = 0.12 s, T_S = 0.6 s), S_a = 1 g, S_d = 9.80665/400 m;
/// building 2 (m = 2e5 kg, k = 2e7 N/m) ω = 10 rad/s, T = 0.6283 s > T_S, S_a = S_D1/T g,
/// S_d = 0.6·9.80665/0.6283/100 m.
#[test]
fn spectral_peaks_at_every_floor_by_hand() {
    use pounding::codes::spectrum::{Asce7Spectrum, DesignSpectrum};
    let text = format!(
        "[[structure]]\nkind = \"shear-building\"\nfloor_heights = [3.0]\nfloor_masses = [1.0e5]\n\
         storey_stiffnesses = [4.0e7]\n[[structure]]\nkind = \"shear-building\"\n\
         floor_heights = [3.0]\nfloor_masses = [2.0e5]\nstorey_stiffnesses = [2.0e7]\n\
         [contact]\nstiffness = 1e9\ngap = 0.05\n{GROUND}[solver]\nduration = 2.0\n"
    );
    let sc = scenario(&text).unwrap();
    let spectrum = DesignSpectrum::Asce7(Asce7Spectrum::new(1.0, 0.6, 8.0).unwrap());
    let r = pounding::analysis::gap_report::gap_report(&sc, Some(&spectrum), None).unwrap();
    let s = r.spectral_floors.expect("spectral part");
    let g = 9.80665;
    let t2 = 2.0 * std::f64::consts::PI / 10.0;
    let want = [g / 400.0, 0.6 / t2 * g / 100.0];
    for (floors, want) in s.iter().zip(want) {
        assert_eq!(floors.len(), 1);
        let f = &floors[0];
        assert_eq!(f.height, 3.0);
        assert!((f.srss - want).abs() < 1e-12 * want, "{} vs {want}", f.srss);
        assert!((f.cqc - want).abs() < 1e-12 * want);
    }
}

/// A sweep over buildings gets the floor columns: each building's largest floor acceleration
/// (with and without pounding) and drift over its floors, equal to the maxima of
/// `structures[i].floors` of the same case run on its own.
#[test]
fn sweeps_over_buildings_report_floor_columns() {
    use pounding::study::sweep::Sweep;
    use pounding::study::sweep::results::{FIELDS, FLOOR_FIELDS, parse_csv_line};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/buildings-sweep.toml");
    let sweep = Sweep::from_file(&path).unwrap();
    assert_eq!(sweep.extra_columns(), FLOOR_FIELDS.to_vec());
    let case = 3;
    let row = pounding::study::sweep::run::compute_case(&sweep, case, false);
    assert!(!row.failed, "{}", row.line);
    let cells = parse_csv_line(&row.line).unwrap();
    let first = 2 + sweep.axes.len() + FIELDS.len();
    let r = simulate(&sweep.case_scenario(case).unwrap()).unwrap();
    let max = |i: usize, f: fn(&pounding::analysis::simulate::FloorReport) -> f64| {
        r.structures[i].floors.iter().map(f).fold(0.0, f64::max)
    };
    let want = [
        max(0, |f| f.peak_acceleration),
        max(1, |f| f.peak_acceleration),
        max(0, |f| f.peak_acceleration_no_contact),
        max(1, |f| f.peak_acceleration_no_contact),
        max(0, |f| f.peak_drift),
        max(1, |f| f.peak_drift),
    ];
    for (k, w) in want.iter().enumerate() {
        let got: f64 = cells[first + k].parse().unwrap();
        assert_eq!(got, *w, "{}", FLOOR_FIELDS[k]);
    }
    assert!(
        want[1] > 1.5 * want[3],
        "premise: pounding raises B's floor accelerations"
    );
}

/// A shear building's uniform shorthand keys are sweep axes: doubling `storey_stiffness`
/// multiplies every ω by √2 (K scales, M does not).
#[test]
fn building_keys_are_sweep_axes() {
    use pounding::study::sweep::Sweep;
    let dir = std::env::temp_dir().join(format!("pounding-bsweep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/shear-buildings.toml");
    std::fs::write(
        dir.join("s.toml"),
        format!(
            "scenario = {:?}\n[[axis]]\nkey = \"structure.2.storey_stiffness\"\nvalues = [1.2e8, 2.4e8]\n",
            base.display().to_string()
        ),
    )
    .unwrap();
    let sweep = Sweep::from_file(&dir.join("s.toml")).unwrap();
    let w: Vec<Vec<f64>> = (0..2)
        .map(|c| sweep.case_scenario(c).unwrap().structures[1].modal().omega)
        .collect();
    for (a, b) in w[0].iter().zip(&w[1]) {
        assert!((b / a - 2f64.sqrt()).abs() < 1e-12, "{a} {b}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `floors.csv`: one row per history row; the displacement at the main contact height equals
/// history.csv's (the same interpolation of the same steps); each station's acceleration column
/// reaches exactly the peak absolute acceleration of summary.json (every observation is held
/// until the next sample), with and without pounding.
#[test]
fn floors_csv_matches_the_history_and_the_peaks() {
    use pounding::output::writer::RunWriter;
    let dir = std::env::temp_dir().join(format!("pounding-floors-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/shear-buildings.toml"),
    )
    .unwrap()
    .replace("duration = 25.0", "duration = 6.0");
    let sc = Scenario::from_toml(
        &text,
        "shear-buildings.toml",
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("examples"),
    )
    .unwrap();
    let heights: Vec<f64> = sc.contact.levels.iter().map(|l| l.height).collect();
    let columns = pounding::recording::floor_response::FloorRecorder::new(
        &sc.system(),
        &heights,
        sc.output_interval,
    )
    .columns();
    let mut writer = RunWriter::create(&dir, sc.contact.levels.len())
        .unwrap()
        .with_floors(&columns)
        .unwrap();
    let report = pounding::analysis::simulate::simulate_streaming(&sc, false, &mut writer).unwrap();
    writer.finish(&sc, &report, None).unwrap();
    let read = |name: &str| -> (Vec<String>, Vec<Vec<f64>>) {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        let mut lines = text.lines();
        let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
        let rows = lines
            .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
            .collect();
        (head, rows)
    };
    let (fh, floors) = read("floors.csv");
    let (hh, history) = read("history.csv");
    assert_eq!(floors.len(), history.len());
    assert_eq!(fh.len(), 1 + 2 * columns.len());
    let col = |h: &[String], name: &str| h.iter().position(|c| c == name).unwrap();
    let (u1, w1) = (col(&fh, "w1_14"), col(&hh, "w1"));
    let scale = report.structures[0].peak_displacement;
    for (f, h) in floors.iter().zip(&history) {
        assert_eq!(f[0], h[0]);
        assert!((f[u1] - h[w1]).abs() <= 1e-12 * scale, "t = {}", f[0]);
    }
    for (i, s) in report.structures.iter().enumerate() {
        for fl in &s.floors {
            for (suffix, want) in [
                ("", fl.peak_acceleration),
                ("_free", fl.peak_acceleration_no_contact),
            ] {
                let c = col(&fh, &format!("a{}_{}{suffix}", i + 1, fl.height));
                let got = floors.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
                assert_eq!(got, want, "a{}_{}{suffix}", i + 1, fl.height);
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The modal model with every mode is the building: the static response to a uniform ground
/// acceleration, `Σ_n φ_n Γ_n / ω_n²` (the modal sum), equals `K⁻¹ M 1` solved here by the
/// tridiagonal (Thomas) algorithm for the 3-storey building A.
#[test]
fn modal_static_sum_equals_the_stiffness_solution() {
    let sc = scenario(&pair(
        "[contact]\nstiffness = 2.0e9\ngap = 0.01\nheight = 6.0\n",
        "duration = 1.0",
    ))
    .unwrap();
    let m = sc.structures[0].modal();
    let (masses, k) = ([2.0e5, 2.0e5, 1.5e5], [3.0e8, 2.5e8, 2.0e8]);
    // K u = M 1: K tridiagonal with diagonal k_j + k_{j+1}, off-diagonal −k_{j+1}
    let n = 3;
    let diag: Vec<f64> = (0..n)
        .map(|j| k[j] + if j + 1 < n { k[j + 1] } else { 0.0 })
        .collect();
    let off: Vec<f64> = (0..n - 1).map(|j| -k[j + 1]).collect();
    let (mut c, mut d) = (vec![0.0; n], vec![0.0; n]);
    c[0] = off[0] / diag[0];
    d[0] = masses[0] / diag[0];
    for j in 1..n {
        let den = diag[j] - off[j - 1] * c[j - 1];
        if j + 1 < n {
            c[j] = off[j] / den;
        }
        d[j] = (masses[j] - off[j - 1] * d[j - 1]) / den;
    }
    let mut u = vec![0.0; n];
    u[n - 1] = d[n - 1];
    for j in (0..n - 1).rev() {
        u[j] = d[j] - c[j] * u[j + 1];
    }
    for (f, h) in [3.0, 6.0, 9.0].iter().enumerate() {
        let modal: f64 = (0..m.len())
            .map(|j| m.shape(j, *h) * m.participation[j] / (m.omega[j] * m.omega[j]))
            .sum();
        assert!(
            (modal - u[f]).abs() < 1e-12 * u[n - 1],
            "floor {}: {modal} vs {}",
            f + 1,
            u[f]
        );
    }
}

/// Energy balance with floor contact: Hertz at two floors, no damping of the contact, the
/// balance input = Δ(kinetic + strain) + damping + contact closes to far below the warning's
/// 1e-3 (`adaptive`, rtol 1e-10).
#[test]
fn energy_balance_closes_with_floor_contact() {
    let contact = "[contact]\nlaw = \"hertz\"\nstiffness = 2.0e9\n\
        [[contact.level]]\nheight = 6.0\ngap = 0.01\n[[contact.level]]\nheight = 3.0\ngap = 0.01\n";
    let r = run(&pair(contact, "duration = 4.0\ndt = 1e-3"));
    assert!(r.contact.impacts > 2);
    assert!(
        r.energy.relative_error.abs() < 1e-6,
        "{}",
        r.energy.relative_error
    );
}

/// Action and reaction: the mirror image of a case — the two buildings swapped (B on the left,
/// A on the right) and the ground motion reversed (the same harmonic motion as a two-column
/// record, with and without its sign) — gives each building the same peaks at every floor, the
/// same peak force and the same impacts.
#[test]
fn mirrored_buildings_give_mirrored_results() {
    let contact = "[contact]\nlaw = \"hertz\"\nstiffness = 2.0e9\ngap = 0.01\nheight = 6.0\n";
    let solver = "[solver]\nduration = 3.0\ndt = 1e-3\nrtol = 1e-10\n";
    let dir = std::env::temp_dir().join(format!("pounding-mirror-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // the same harmonic motion as a two-column record, with and without its sign
    let (pga, tg) = (0.3 * 9.80665, 0.5);
    let w = 2.0 * std::f64::consts::PI / tg;
    let mut plus = String::from("t,a\n");
    let mut minus = String::from("t,a\n");
    for i in 0..=3000 {
        let t = i as f64 * 1e-3;
        let ag = -pga * (w * t).sin();
        plus.push_str(&format!("{t},{ag:e}\n"));
        minus.push_str(&format!("{t},{:e}\n", -ag));
    }
    std::fs::write(dir.join("plus.csv"), plus).unwrap();
    std::fs::write(dir.join("minus.csv"), minus).unwrap();
    let ground =
        |f: &str| format!("[ground_motion]\nkind = \"record\"\nfile = \"{f}\"\nunits = \"m/s2\"\n");
    let sc = |text: String| Scenario::from_toml(&text, "m.toml", &dir).unwrap();
    let ab = simulate(&sc(format!(
        "{A}{B}{contact}{}{solver}",
        ground("plus.csv")
    )))
    .unwrap();
    let ba = simulate(&sc(format!(
        "{B}{A}{contact}{}{solver}",
        ground("minus.csv")
    )))
    .unwrap();
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    assert!(ab.contact.impacts > 0);
    assert_eq!(ab.contact.impacts, ba.contact.impacts);
    assert!(rel(ab.contact.peak_force, ba.contact.peak_force) < 1e-9);
    for i in 0..2 {
        let (x, y) = (&ab.structures[i], &ba.structures[1 - i]);
        assert!(rel(x.peak_displacement, y.peak_displacement) < 1e-9);
        for (f, g) in x.floors.iter().zip(&y.floors) {
            assert!(rel(f.peak_acceleration, g.peak_acceleration) < 1e-9);
            assert!(rel(f.peak_shear, g.peak_shear) < 1e-9);
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A floor-to-floor impact between two one-storey buildings on storey springs far softer than
/// the contact (ω = 3e-3 rad/s, so the floors are free bodies during the 10 ms impact) against
/// the two-body Hertz impact (Goldsmith): m* = m₁m₂/(m₁ + m₂), δ_max = (5m*v²/(4k_h))^{2/5},
/// F_max = k_h δ_max^{3/2}, contact time 2.9432 δ_max/v, rebound at the approach speed.
#[test]
fn one_storey_floor_impact_matches_the_two_body_hertz_formulas() {
    use pounding::integrate::{InitialState, Method, SolverSettings, integrate};
    use pounding::model::building::{FloorDamping, Floors, ShearBuilding};
    use pounding::model::contact::ContactLaw;
    use pounding::model::ground_motion::GroundMotion;
    use pounding::model::system::{ContactLevel, System};
    use pounding::recording::recorder::Recorder;
    let building = |m: f64| {
        ShearBuilding {
            floors: Floors {
                heights: vec![3.0],
                masses: vec![m],
            },
            storey_stiffnesses: vec![1.0],
            modes: 1,
            damping: FloorDamping::Modal(vec![0.0]),
        }
        .modal()
        .unwrap()
    };
    let (m1, m2, kh, v) = (1.0e5, 2.0e5, 5.0e9, 0.5);
    let sys = System::new(
        [building(m1), building(m2)],
        &ContactLaw::Hertz { stiffness: kh },
        &[ContactLevel {
            height: 3.0,
            gap: 0.0,
        }],
        GroundMotion::None,
    );
    let m_star = m1 * m2 / (m1 + m2);
    assert!((sys.levels[0].effective_mass - m_star).abs() < 1e-9 * m_star);
    let d_max = (5.0 * m_star * v * v / (4.0 * kh)).powf(0.4);
    let (f_max, t_c) = (kh * d_max.powf(1.5), 2.9432 * d_max / v);
    // building 1 moves right at v (φ = 1/√m₁, so η̇ = v√m₁)
    let phi1 = sys.structures[0].shape(0, 3.0);
    let init = InitialState {
        q: vec![0.0, 0.0],
        v: vec![v / phi1, 0.0],
    };
    let settings = SolverSettings::new(Method::Adaptive, t_c / 50.0, 3.0 * t_c).with_rtol(1e-11);
    let mut rec = Recorder::new(&sys, &[3.0], settings.duration, settings.duration);
    integrate(&sys, &settings, &init, &mut rec).unwrap();
    let r = rec.finish();
    assert_eq!(r.impacts.len(), 1);
    let i = &r.impacts[0];
    let rel = |a: f64, b: f64| (a - b).abs() / b;
    // (the storey springs' force over the impact is ~1e-9 of the contact's; the constant
    // 2.9432 is given to 5 digits)
    assert!(
        rel(i.peak_force, f_max) < 1e-6,
        "{} vs {f_max}",
        i.peak_force
    );
    assert!(
        rel(i.max_penetration, d_max) < 1e-6,
        "{} vs {d_max}",
        i.max_penetration
    );
    assert!(
        rel(i.end - i.start, t_c) < 1e-4,
        "{} vs {t_c}",
        i.end - i.start
    );
    // momentum: the impulse m*·(1 + e)·v with e = 1
    assert!(
        rel(i.impulse, 2.0 * m_star * v) < 1e-6,
        "{} vs {}",
        i.impulse,
        2.0 * m_star * v
    );
}

/// Scale factors as sweep axes: `stiffness_scale` multiplies every storey stiffness (ω × √f),
/// `mass_scale` every floor mass (ω ÷ √f), for a building given by lists or the shorthand; a
/// `modal` building's periods follow the stiffness (÷ √f) and its shapes stay; the masses of a
/// `modes_file` are refused (the sweep cannot rewrite the file).
#[test]
fn scale_factor_axes() {
    use pounding::study::sweep::Sweep;
    let dir = std::env::temp_dir().join(format!("pounding-scale-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let omega = |file: &str, key: &str, s: usize| -> [Vec<f64>; 2] {
        std::fs::write(
            dir.join("s.toml"),
            format!(
                "scenario = {:?}\n[[axis]]\nkey = \"{key}\"\nvalues = [1.0, 4.0]\n",
                ex.join(file).display().to_string()
            ),
        )
        .unwrap();
        let sweep = Sweep::from_file(&dir.join("s.toml")).unwrap();
        [0, 1].map(|c| sweep.case_scenario(c).unwrap().structures[s].modal().omega)
    };
    for (file, key, s, ratio) in [
        (
            "shear-buildings.toml",
            "structure.1.stiffness_scale",
            0,
            2.0,
        ),
        ("shear-buildings.toml", "structure.1.mass_scale", 0, 0.5),
        (
            "shear-buildings.toml",
            "structure.2.stiffness_scale",
            1,
            2.0,
        ),
        ("modal-csv.toml", "structure.1.stiffness_scale", 0, 2.0),
        ("paper-c.toml", "structure.2.stiffness_scale", 1, 2.0),
    ] {
        let [a, b] = omega(file, key, s);
        for (x, y) in a.iter().zip(&b) {
            assert!((y / x - ratio).abs() < 1e-12, "{file} {key}: {x} → {y}");
        }
    }
    // the masses of a modes_file cannot be scaled by rewriting the scenario: refused
    std::fs::write(
        dir.join("s.toml"),
        format!(
            "scenario = {:?}\n[[axis]]\nkey = \"structure.1.mass_scale\"\nvalues = [2.0]\n",
            ex.join("modal-csv.toml").display().to_string()
        ),
    )
    .unwrap();
    let e = Sweep::from_file(&dir.join("s.toml"))
        .unwrap()
        .case_scenario(0)
        .unwrap_err();
    assert!(e.contains("modes_file"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `pounding plot --field` draws the floor columns of a results table (and refuses a name the
/// table does not have, listing the ones it has).
#[test]
fn plot_draws_floor_columns() {
    use pounding::figures::sweep::{PlotRequest, plot_table_of};
    use pounding::study::sweep::results::{FIELDS, FLOOR_FIELDS, Table};
    let dir = std::env::temp_dir().join(format!("pounding-plotfloors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut text = format!(
        "case,ground_motion.pga,status,{},{}\n",
        FIELDS.join(","),
        FLOOR_FIELDS.join(",")
    );
    for (c, pga) in [0.1, 0.2, 0.3].iter().enumerate() {
        let nums: Vec<String> = (0..FIELDS.len() + FLOOR_FIELDS.len())
            .map(|k| match FIELDS.get(k) {
                Some(&"converged") => "true".to_string(),
                _ => format!("{}", pga * (k + 1) as f64),
            })
            .collect();
        text.push_str(&format!("{c},{pga},ok,{}\n", nums.join(",")));
    }
    std::fs::write(dir.join("results.csv"), text).unwrap();
    let table = Table::read(&dir.join("results.csv")).unwrap();
    assert_eq!(table.codes, FLOOR_FIELDS.to_vec());
    let req = |f: &str| PlotRequest {
        x: Some("ground_motion.pga".into()),
        y: None,
        field: Some(f.into()),
    };
    let files = plot_table_of(
        &table,
        &req("peak_floor_acceleration_2"),
        &dir.join("p"),
        None,
    )
    .unwrap();
    assert!(files.iter().any(|f| f.exists()));
    let e = plot_table_of(&table, &req("sep_asce7"), &dir.join("p"), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("peak_drift_2"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A building's lists are sweep axes by path: `values = [[…], […]]` for `floor_masses`
/// (doubling every mass divides every ω by √2), written to the table as `[a b …]` and read
/// back; a number where a list is due is refused naming the key.
#[test]
fn list_keys_are_sweep_axes() {
    use pounding::study::sweep::Sweep;
    use pounding::study::sweep::results::Table;
    let dir = std::env::temp_dir().join(format!("pounding-listaxis-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/shear-buildings.toml");
    let write = |values: &str| {
        std::fs::write(
            dir.join("s.toml"),
            format!(
                "scenario = {:?}\n[[axis]]\nkey = \"structure.1.floor_masses\"\nvalues = {values}\n\
                 [[axis]]\nkey = \"solver.duration\"\nvalues = [2.0]\n",
                base.display().to_string()
            ),
        )
        .unwrap();
    };
    write("[[2.0e5, 2.0e5, 2.0e5, 1.5e5], [4.0e5, 4.0e5, 4.0e5, 3.0e5]]");
    let sweep = Sweep::from_file(&dir.join("s.toml")).unwrap();
    let w: Vec<Vec<f64>> = (0..2)
        .map(|c| sweep.case_scenario(c).unwrap().structures[0].modal().omega)
        .collect();
    for (a, b) in w[0].iter().zip(&w[1]) {
        assert!((a / b - 2f64.sqrt()).abs() < 1e-12, "{a} {b}");
    }
    // the row of case 1: the list as one cell, then `ok`
    let row = pounding::study::sweep::run::compute_case(&sweep, 1, false);
    assert!(!row.failed, "{}", row.line);
    let cells = pounding::study::sweep::results::parse_csv_line(&row.line).unwrap();
    assert_eq!(cells[1], "[400000.0 400000.0 400000.0 300000.0]");
    assert_eq!(cells[3], "ok");
    // and a results table with it reads back
    std::fs::write(
        dir.join("results.csv"),
        format!(
            "{}\n{}\n",
            pounding::study::sweep::results::header(&sweep),
            row.line
        ),
    )
    .unwrap();
    let table = Table::read(&dir.join("results.csv")).unwrap();
    assert_eq!(table.rows[&1].values[0], cells[1]);
    write("[2.0e5, 3.0e5]");
    let e = Sweep::from_file(&dir.join("s.toml"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("floor_masses") && e.contains("lists"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Without contact, after the transient has died out (ζ = 3 %, 40 s), building A's floor at
/// 6 m moves with the closed-form steady-state amplitude |U₂| of
/// `(K − Ω²M + iΩC) U = −M 1 a_g` (a_g of amplitude PGA·g; C Rayleigh, as in the scenario),
/// solved here by Gaussian elimination in complex numbers: to 1e-4 over the last 2 s, sampled
/// every 1 ms (the sampling misses the crest by at most 1 − cos(Ω·0.5 ms) ≈ 2e-5).
#[test]
// (Gaussian elimination reads best with the indices of its formulas)
#[allow(clippy::needless_range_loop)]
fn steady_state_harmonic_response_of_a_building_matches_the_closed_form() {
    let (pa, _) = physical_pair();
    let (pga, tg) = (0.3 * 9.80665, 0.5);
    let big = 2.0 * std::f64::consts::PI / tg;
    // complex matrix A = K − Ω²M + iΩC, right-hand side −M 1 (times the amplitude)
    type C = (f64, f64);
    let n = 3;
    let mut a: Vec<Vec<C>> = (0..n)
        .map(|r| {
            (0..n)
                .map(|c| {
                    let m = if r == c { pa.m[r] } else { 0.0 };
                    (pa.k[r][c] - big * big * m, big * pa.c[r][c])
                })
                .collect()
        })
        .collect();
    let mut b: Vec<C> = (0..n).map(|r| (-pa.m[r] * pga, 0.0)).collect();
    let mul = |x: C, y: C| (x.0 * y.0 - x.1 * y.1, x.0 * y.1 + x.1 * y.0);
    let div = |x: C, y: C| {
        let d = y.0 * y.0 + y.1 * y.1;
        ((x.0 * y.0 + x.1 * y.1) / d, (x.1 * y.0 - x.0 * y.1) / d)
    };
    for p in 0..n {
        for r in p + 1..n {
            let f = div(a[r][p], a[p][p]);
            for c in p..n {
                let t = mul(f, a[p][c]);
                a[r][c] = (a[r][c].0 - t.0, a[r][c].1 - t.1);
            }
            let t = mul(f, b[p]);
            b[r] = (b[r].0 - t.0, b[r].1 - t.1);
        }
    }
    let mut u = vec![(0.0, 0.0); n];
    for r in (0..n).rev() {
        let mut s = b[r];
        for c in r + 1..n {
            let t = mul(a[r][c], u[c]);
            s = (s.0 - t.0, s.1 - t.1);
        }
        u[r] = div(s, a[r][r]);
    }
    let amplitude = (u[1].0 * u[1].0 + u[1].1 * u[1].1).sqrt();
    // the program: contact far away (gap 5 m: never closes), main height 6 m
    let r = run(&pair(
        "[contact]\nstiffness = 2.0e9\ngap = 5.0\nheight = 6.0\n",
        "duration = 40.0\noutput_interval = 0.001",
    ));
    // (40 001 samples: the history kept in memory is their min/max envelope in groups, whose
    // maximum over the last 2 s is the samples' maximum there)
    let h = &r.without_contact.history;
    let late =
        h.t.iter()
            .zip(&h.w1)
            .filter(|(t, _)| **t >= 38.0)
            .map(|(_, w)| w.abs())
            .fold(0.0, f64::max);
    assert!(
        (late - amplitude).abs() < 1e-4 * amplitude,
        "{late} vs closed form {amplitude}"
    );
}
