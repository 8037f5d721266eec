//! Helpers shared by the integration tests (each file of `tests/` is a crate of its own and
//! includes them with `mod common;`):
//!
//! - running the `pounding` binary ([`pounding`]), a scenario from TOML text
//!   ([`scenario_named`], [`run_named`]);
//! - rows of buildings from TOML pieces ([`row_scenario`], [`row_building`], [`row_contact`],
//!   [`ROW_HARMONIC`]) and the rows of three that several test files share
//!   ([`row_flexible_end`], [`row_both_pounding`]): used by the `tests/row*.rs` files,
//!   `tests/fragility_row.rs` and `tests/opensees_row.rs`;
//! - an integration of buildings in physical coordinates, `M ü + C u̇ + K u = −M 1 a_g + F`, by
//!   RK4 at a small fixed step: the independent reference of the floor-response tests (it
//!   shares nothing with the program but the equations of motion). Used by
//!   `tests/buildings.rs` and `tests/storey_force.rs`.

// (each test file uses part of it)
#![allow(dead_code)]

pub mod audit_line;
pub mod physical_laws;

use std::path::Path;
use std::process::{Command, Output};

use pounding::analysis::simulate::{Report, simulate};
use pounding::input::scenario::Scenario;

/// M, K, C (Rayleigh through modes i, j of the generalised problem, computed here by the
/// characteristic polynomial's roots) of a shear building, for the independent integration.
pub struct Physical {
    /// Floor masses, kg.
    pub m: Vec<f64>,
    /// Stiffness matrix, N/m.
    pub k: Vec<Vec<f64>>,
    /// Damping matrix, N·s/m.
    pub c: Vec<Vec<f64>>,
    /// Storey springs k_j (a shear building): the storey force is `k_j (u_j − u_{j−1})`;
    /// otherwise it is `Σ_{g ≥ j} (K u)_g`, the equivalent static forces of the floors above.
    pub springs: Option<Vec<f64>>,
}

pub fn physical(masses: &[f64], ks: &[f64], zeta: f64) -> Physical {
    let n = masses.len();
    let mut k = vec![vec![0.0; n]; n];
    for j in 0..n {
        k[j][j] = ks[j] + ks.get(j + 1).copied().unwrap_or(0.0);
        if j + 1 < n {
            k[j][j + 1] = -ks[j + 1];
            k[j + 1][j] = -ks[j + 1];
        }
    }
    // Rayleigh through the two lowest modes, found on K and M alone
    let mut p = Physical {
        m: masses.to_vec(),
        k,
        c: Vec::new(),
        springs: Some(ks.to_vec()),
    };
    let (wi, wj) = lowest_two(&p);
    let a0 = 2.0 * zeta * wi * wj / (wi + wj);
    let a1 = 2.0 * zeta / (wi + wj);
    let c = (0..n)
        .map(|r| {
            (0..n)
                .map(|s| a1 * p.k[r][s] + if r == s { a0 * masses[r] } else { 0.0 })
                .collect()
        })
        .collect();
    p.c = c;
    p
}

/// The two lowest ω of `K φ = ω² M φ` for a 2- or 3-DOF shear building by bisection on
/// det(K − ω²M) (a tridiagonal determinant by recurrence): independent of the program's
/// eigen-solver.
pub fn lowest_two(p: &Physical) -> (f64, f64) {
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

/// Peaks at every floor of one building in the physical integration.
#[derive(Debug, Default, Clone)]
pub struct FloorPeaks {
    /// |u|, m.
    pub disp: Vec<f64>,
    /// |ü + a_g|, m/s².
    pub acc: Vec<f64>,
    /// |u_j − u_{j−1}|, m.
    pub drift: Vec<f64>,
    /// The storey force of the storey below (restoring, no damping): see [`Physical::springs`], N.
    pub force: Vec<f64>,
    /// The storey shear from the equilibrium of the floors above, `Σ_{f ≥ j} (F_f − m_f a_f)`
    /// (the storey force plus the damping forces above), N.
    pub shear: Vec<f64>,
}

/// What the physical integration runs: Hertz contact `kh` at common floors (`levels`: floor
/// index in A and in B, gap) under a_g = −`pga`·sin(Ω t) (the program's harmonic motion is the
/// displacement y = A sin Ωt, docs/model.md §2.8), over `duration` at step `dt`.
pub struct Case<'a> {
    /// (floor index in the first building, in the second, gap m).
    pub levels: &'a [(usize, usize, f64)],
    /// Hertz k_h, N/m^1.5.
    pub kh: f64,
    /// m/s².
    pub pga: f64,
    /// rad/s.
    pub omega: f64,
    /// s.
    pub duration: f64,
    /// s.
    pub dt: f64,
}

/// RK4 in physical coordinates of both buildings, `M ü + C u̇ + K u = −M 1 a_g + F`; returns
/// every floor's peaks (displacement, absolute acceleration ü + a_g, storey drift, storey force
/// — `k_j d_j` of a storey spring, else `Σ_{g ≥ j} (K u)_g` — and the storey shear from the
/// equilibrium of the floors above, `V_j = Σ_{f ≥ j} (F_f − m_f a_f)`) of both buildings and
/// the largest contact force of any level, sampled at every step.
pub fn integrate_physical(a: &Physical, b: &Physical, case: &Case) -> ([FloorPeaks; 2], f64) {
    let (na, nb) = (a.m.len(), b.m.len());
    let n = na + nb;
    // state derivative and the contact forces on every dof
    let deriv = |t: f64, y: &[f64], out: &mut [f64], fext: &mut [f64]| -> f64 {
        let a_g = -case.pga * (case.omega * t).sin();
        let (u, v) = y.split_at(n);
        fext.iter_mut().for_each(|x| *x = 0.0);
        let mut fmax = 0.0f64;
        for &(fa, fb, gap) in case.levels {
            let delta = u[fa] - u[na + fb] - gap;
            if delta > 0.0 {
                let fc = case.kh * delta.powf(1.5);
                fext[fa] -= fc;
                fext[na + fb] += fc;
                fmax = fmax.max(fc);
            }
        }
        for (off, p, nn) in [(0, a, na), (na, b, nb)] {
            for r in 0..nn {
                let mut s = fext[off + r] - p.m[r] * a_g;
                for c in 0..nn {
                    s -= p.k[r][c] * u[off + c] + p.c[r][c] * v[off + c];
                }
                out[off + r] = v[off + r];
                out[n + off + r] = s / p.m[r];
            }
        }
        fmax
    };
    let mut y = vec![0.0; 2 * n];
    let mut k = [
        vec![0.0; 2 * n],
        vec![0.0; 2 * n],
        vec![0.0; 2 * n],
        vec![0.0; 2 * n],
    ];
    let mut tmp = vec![0.0; 2 * n];
    let mut fext = vec![0.0; n];
    let mut peaks = [FloorPeaks::default(), FloorPeaks::default()];
    for (p, nn) in peaks.iter_mut().zip([na, nb]) {
        *p = FloorPeaks {
            disp: vec![0.0; nn],
            acc: vec![0.0; nn],
            drift: vec![0.0; nn],
            force: vec![0.0; nn],
            shear: vec![0.0; nn],
        };
    }
    let mut pf = 0.0f64;
    let steps = (case.duration / case.dt).round() as usize;
    let dt = case.dt;
    for s in 0..=steps {
        let t = s as f64 * dt;
        // the state at t: its accelerations and forces, and the peaks
        let f0 = deriv(t, &y, &mut k[0], &mut fext);
        pf = pf.max(f0);
        let a_g = -case.pga * (case.omega * t).sin();
        for (bi, (off, p, nn)) in [(0, a, na), (na, b, nb)].into_iter().enumerate() {
            let pk = &mut peaks[bi];
            let mut v_above = 0.0;
            for f in (0..nn).rev() {
                let acc = k[0][n + off + f] + a_g;
                v_above += fext[off + f] - p.m[f] * acc;
                let below = if f == 0 { 0.0 } else { y[off + f - 1] };
                pk.disp[f] = pk.disp[f].max(y[off + f].abs());
                pk.acc[f] = pk.acc[f].max(acc.abs());
                pk.drift[f] = pk.drift[f].max((y[off + f] - below).abs());
                pk.shear[f] = pk.shear[f].max(v_above.abs());
                let force = match &p.springs {
                    Some(ks) => ks[f] * (y[off + f] - below),
                    None => (f..nn)
                        .map(|g| (0..nn).map(|c| p.k[g][c] * y[off + c]).sum::<f64>())
                        .sum(),
                };
                pk.force[f] = pk.force[f].max(force.abs());
            }
        }
        if s == steps {
            break;
        }
        for i in 0..2 * n {
            tmp[i] = y[i] + 0.5 * dt * k[0][i];
        }
        let (k0, rest) = k.split_at_mut(1);
        let _ = k0;
        deriv(t + 0.5 * dt, &tmp, &mut rest[0], &mut fext);
        for i in 0..2 * n {
            tmp[i] = y[i] + 0.5 * dt * rest[0][i];
        }
        deriv(t + 0.5 * dt, &tmp, &mut rest[1], &mut fext);
        for i in 0..2 * n {
            tmp[i] = y[i] + dt * rest[1][i];
        }
        deriv(t + dt, &tmp, &mut rest[2], &mut fext);
        for i in 0..2 * n {
            y[i] += dt / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
        }
    }
    (peaks, pf)
}

/// The `pounding` binary run with `args` in the directory `cwd`.
pub fn pounding(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pounding"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("the binary runs")
}

/// The `pounding` binary run with `args` in the tests' working directory (the repository's
/// root).
pub fn pounding_here(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pounding"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The standard output of a run that must have succeeded (else its stdout and stderr in the
/// failure's message).
pub fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "failed: {}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The sweep `sweep` run as `shards` shards (`--shard k/shards`, `extra` arguments each) into
/// `dir/parts`, then joined by `pounding merge` into `dir/merged.csv`: the merged table's text.
pub fn sharded_and_merged(sweep: &Path, dir: &Path, shards: usize, extra: &[&str]) -> String {
    let parts = dir.join("parts");
    for k in 1..=shards {
        let shard = format!("{k}/{shards}");
        let mut args = vec![
            "sweep",
            s(sweep),
            "--out",
            s(&parts),
            "--shard",
            &shard,
            "-q",
        ];
        args.extend_from_slice(extra);
        ok(&pounding_here(&args));
    }
    let merged = dir.join("merged.csv");
    ok(&pounding_here(&["merge", s(&merged), s(&parts), "-q"]));
    std::fs::read_to_string(&merged).unwrap()
}

/// A path as a command line's argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A scenario from TOML `text`, named `file` in its messages, its paths relative to the
/// repository's root; the error as its message.
pub fn scenario_named(text: &str, file: &str) -> Result<Scenario, String> {
    Scenario::from_toml(text, file, Path::new(env!("CARGO_MANIFEST_DIR")))
        .map_err(|e| e.to_string())
}

/// `simulate` of the scenario `text` (named `file`), which must be valid and run.
pub fn run_named(text: &str, file: &str) -> Report {
    simulate(&scenario_named(text, file).expect("valid scenario")).expect("runs")
}

/// Start `cmd` (its output discarded), wait until its journal at `journal` holds at least
/// `rows` rows after the two header lines (at most 60 s), then kill it with SIGKILL: how the
/// resume tests of sweeps and studies interrupt a run mid-way.
pub fn kill_after_journal_rows(cmd: &mut Command, journal: &Path, rows: usize) {
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let mut child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    loop {
        let done = std::fs::read_to_string(journal)
            .map(|t| t.lines().count().saturating_sub(2))
            .unwrap_or(0);
        if done >= rows || t0.elapsed() > Duration::from_secs(60) {
            break;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
}

/// A row's scenario from its TOML text (named `row.toml`, read from `.`); panics with the
/// scenario's error.
pub fn row_scenario(text: &str) -> Scenario {
    Scenario::from_toml(text, "row.toml", Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// A shear building of `n` storeys of 3.5 m named `name`, floor mass 2e5 kg, storey stiffness
/// `k` (N/m), 5 % damping, all its modes kept.
pub fn row_building(name: &str, n: usize, k: f64) -> String {
    format!(
        "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
         storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\ndamping_ratio = 0.05\n\
         modes = {n}\n"
    )
}

/// A `[[contact]]` between `a` and `b` at height `h` (m) with gap `gap` (m), Hertz 2e10.
pub fn row_contact(a: &str, b: &str, h: f64, gap: f64) -> String {
    format!(
        "[[contact]]\nbetween = [\"{a}\", \"{b}\"]\nlaw = \"hertz\"\nstiffness = 2.0e10\n\
         height = {h}\ngap = {gap}\n"
    )
}

/// The row of three whose last building is the most flexible: A (4 storeys, storey stiffness
/// 3e8 N/m), B (5, 1.6e8), C (3, 1e8), every mode kept; A–B at 14 m with gap `gap_ab`, B–C at
/// 10.5 m with gap `gap_bc` (m), Hertz 2e10 (structures and contacts only: a test adds its
/// ground motion and solver). With a gap B–C that never closes it is the pair A–B to the last
/// digit: exact-modal's tolerance on δ̇ scales with the largest first-mode ω of the system's
/// structures, which the more flexible C does not change.
pub fn row_flexible_end(gap_ab: f64, gap_bc: f64) -> String {
    [
        row_building("A", 4, 3.0e8),
        row_building("B", 5, 1.6e8),
        row_building("C", 3, 1.0e8),
        row_contact("A", "B", 14.0, gap_ab),
        row_contact("B", "C", 10.5, gap_bc),
    ]
    .concat()
}

/// The row of three with both gaps small, so that under [`ROW_HARMONIC`] both pairs pound: A (3
/// storeys, storey stiffness 3e8 N/m), B (5, 1.6e8), C (4, 2.2e8), every mode kept; A–B at
/// 10.5 m with a 4 mm gap, B–C at 14 m with 6 mm, Hertz 2e10 (structures and contacts only).
pub fn row_both_pounding() -> String {
    [
        row_building("A", 3, 3.0e8),
        row_building("B", 5, 1.6e8),
        row_building("C", 4, 2.2e8),
        row_contact("A", "B", 10.5, 0.004),
        row_contact("B", "C", 14.0, 0.006),
    ]
    .concat()
}

/// A harmonic ground motion of 0.35 g at 0.8 s.
pub const ROW_HARMONIC: &str = "[ground_motion]\nkind = \"harmonic\"\npga = 0.35\nperiod = 0.8\n";

/// The interpreter with openseespy for the OpenSees tests (`$POUNDING_PYTHON`, else
/// `python3`), or `None` (skip) — a failure under CI.
pub fn opensees_python() -> Option<String> {
    let py = pounding::opensees::compare::python();
    match pounding::opensees::compare::probe(&py) {
        Ok(_) => Some(py),
        Err(e) => {
            let ci = std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
            assert!(!ci, "CI must have openseespy (see .ci/run): {e}");
            eprintln!("skipping an OpenSees test: {e}");
            None
        }
    }
}

/// The `MODEL` JSON of an exported OpenSeesPy script.
pub fn model_json(script: &str) -> serde_json::Value {
    let start = script.find("MODEL = json.loads(r'''").expect("MODEL") + 23;
    let end = script[start..].find("''')").expect("end of MODEL") + start;
    serde_json::from_str(&script[start..end]).expect("MODEL is JSON")
}

/// Building A ([`BUILDING_A`]: floors at 3, 6, 9 m, masses 2e5, 2e5, 1.5e5 kg) as the
/// engineer's modes (`kind = "modal"`) given the modes `m` (its periods, ζ and shapes read at
/// the floors, scaled by −3e3 to show the normalisation does not matter, printed to full
/// precision): the same structure through the other door.
pub fn modal_building_a(m: &pounding::model::modal::ModalModel) -> String {
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

/// Building A of the floor-response tests (`tests/buildings.rs`, `tests/floors_between.rs`):
/// 3 storeys, Rayleigh-damped (classical damping C = a₀M + a₁K, so that the physical-coordinate
/// integration [`physical`] has exactly the modal model's damping).
pub const BUILDING_A: &str = "[[structure]]\nname = \"A\"\nkind = \"shear-building\"\n\
floor_heights = [3.0, 6.0, 9.0]\nfloor_masses = [2.0e5, 2.0e5, 1.5e5]\n\
storey_stiffnesses = [3.0e8, 2.5e8, 2.0e8]\nrayleigh = { damping_ratio = 0.03, modes = [1, 2] }\n";

/// Building B of the same tests: 2 storeys at A's lower floor heights, more flexible.
pub const BUILDING_B: &str = "[[structure]]\nname = \"B\"\nkind = \"shear-building\"\n\
floor_heights = [3.0, 6.0]\nfloor_masses = [1.8e5, 1.8e5]\n\
storey_stiffnesses = [6.0e7, 5.0e7]\nrayleigh = { damping_ratio = 0.03, modes = [1, 2] }\n";
