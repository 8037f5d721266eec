//! The bundled default scenario (paper case T1/T2 = 0.7: 3 modes per structure, 20 s at
//! dt = 0.001 s, Hertz contact), both runs (with and without contact); and with the self-check
//! (both runs again at dt/√10), as `pounding run` does.

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use pounding::analysis::simulate::{simulate, simulate_checked};
use pounding::input::scenario::Scenario;

fn default_scenario(c: &mut Criterion) {
    let text = include_str!("../examples/paper-c.toml");
    let sc = Scenario::from_toml(text, "paper-c.toml", Path::new("examples")).unwrap();
    c.bench_function("default scenario, rk4, both runs", |b| {
        b.iter(|| simulate(std::hint::black_box(&sc)).unwrap())
    });
    c.bench_function("default scenario, rk4, both runs + self-check", |b| {
        b.iter(|| simulate_checked(std::hint::black_box(&sc), true).unwrap())
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(4));
    targets = default_scenario
}
criterion_main!(benches);
