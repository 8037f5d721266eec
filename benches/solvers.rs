//! Solver benchmarks (`cargo bench --bench solvers`): the default scenario (paper case
//! T1/T2 = 0.7: 3 modes per structure, 20 s, runs with and without contact) with each method;
//! 50 and 200 modes per structure with Hertz contact; a recorded motion. Criterion measures each
//! case; a summary table (runs per second, ns per step per mode, steps) is printed at the end.

use std::hint::black_box;
use std::sync::Arc;
use std::time::{Duration, Instant};

use criterion::Criterion;
use pounding::analysis::simulate::simulate_headline;
use pounding::input::scenario::Scenario;
use pounding::model::ground_motion::{GroundMotion, Record};

const PAPER_C: &str = include_str!("../examples/paper-c.toml");

/// The bundled default scenario with another method, dt and number of modes.
fn scenario(method: &str, dt: f64, modes: usize) -> Scenario {
    let text = PAPER_C
        .replace("method = \"rk4\"", &format!("method = \"{method}\""))
        .replace("dt = 0.001", &format!("dt = {dt}"))
        .replace("modes = 3", &format!("modes = {modes}"));
    Scenario::from_toml(&text, "bench", ".".as_ref()).expect("bench scenario is valid")
}

/// A synthetic 20 s accelerogram (dt = 0.01 s): a deterministic sum of decaying sinusoids,
/// scaled to 0.5 g, standing in for a recorded motion.
fn recorded(method: &str, dt: f64) -> Scenario {
    let mut s = scenario(method, dt, 3);
    let n = 2001;
    let acc: Vec<f64> = (0..n)
        .map(|i| {
            let t = i as f64 * 0.01;
            let env = (t / 2.0).min(1.0) * (-(t - 8.0).max(0.0) / 4.0).exp();
            env * ((9.7 * t).sin() + 0.6 * (15.1 * t + 1.0).sin() + 0.4 * (23.3 * t + 2.0).sin())
        })
        .collect();
    let pga = acc.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    let acc = acc.iter().map(|a| a / pga * 0.5 * 9.80665).collect();
    s.ground_motion = GroundMotion::Record(Arc::new(
        Record::from_samples(0.01, acc, "synthetic".into()).expect("valid record"),
    ));
    s
}

struct Case {
    name: String,
    scenario: Scenario,
    modes: usize,
}

fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    let mut add = |name: &str, scenario: Scenario, modes: usize| {
        v.push(Case {
            name: name.into(),
            scenario,
            modes,
        })
    };
    add("default/rk4 dt=1ms", scenario("rk4", 0.001, 3), 3);
    add(
        "default/exact-modal dt=1ms",
        scenario("exact-modal", 0.001, 3),
        3,
    );
    add(
        "default/exact-modal dt=5ms",
        scenario("exact-modal", 0.005, 3),
        3,
    );
    add(
        "default/exact-modal dt=10ms",
        scenario("exact-modal", 0.01, 3),
        3,
    );
    add("default/adaptive", scenario("adaptive", 0.001, 3), 3);
    add("default/adaptive dt=10ms", scenario("adaptive", 0.01, 3), 3);
    for modes in [50, 200] {
        add(
            &format!("{modes} modes/exact-modal dt=1ms"),
            scenario("exact-modal", 0.001, modes),
            modes,
        );
        add(
            &format!("{modes} modes/exact-modal dt=5ms"),
            scenario("exact-modal", 0.005, modes),
            modes,
        );
        add(
            &format!("{modes} modes/adaptive"),
            scenario("adaptive", 0.001, modes),
            modes,
        );
        add(
            &format!("{modes} modes/adaptive dt=10ms"),
            scenario("adaptive", 0.01, modes),
            modes,
        );
    }
    add("record/rk4 dt=1ms", recorded("rk4", 0.001), 3);
    add(
        "record/exact-modal dt=1ms",
        recorded("exact-modal", 0.001),
        3,
    );
    add("record/adaptive", recorded("adaptive", 0.001), 3);
    v
}

fn main() {
    let mut c = Criterion::default()
        .configure_from_args()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
    let cases = cases();
    for case in &cases {
        c.bench_function(&case.name, |b| {
            b.iter(|| simulate_headline(black_box(&case.scenario), false).expect("runs"))
        });
    }
    c.final_summary();
    // summary table: best of 20 runs (both runs: with and without contact)
    println!();
    println!(
        "{:<32} {:>10} {:>10} {:>10} {:>14}",
        "case", "ms/run", "runs/s", "steps", "ns/step/mode"
    );
    // the table follows criterion's name filter (the first argument that is not an option)
    let filter = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .unwrap_or_default();
    for case in cases.iter().filter(|c| c.name.contains(&filter)) {
        let mut best = f64::INFINITY;
        let mut steps = 0;
        for _ in 0..20 {
            let t0 = Instant::now();
            let r = simulate_headline(black_box(&case.scenario), false).expect("runs");
            best = best.min(t0.elapsed().as_secs_f64());
            steps = r.with_contact.steps + r.without_contact.steps;
        }
        let modes = 2 * case.modes;
        println!(
            "{:<32} {:>10.3} {:>10.0} {:>10} {:>14.2}",
            case.name,
            best * 1e3,
            1.0 / best,
            steps,
            best * 1e9 / (steps as f64 * modes as f64)
        );
    }
}
