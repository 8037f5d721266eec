//! Sweep throughput, and the speedup from 1 to 2 threads.
//!
//! CI-sized: 48 cases of the paper's case c (3 modes per structure, harmonic motion, RK4 with
//! dt = 0.001 s) over 5 s each, run through the whole sweep machinery (case building and
//! validation, both simulations, journal, results table). Throughput is reported in cases/s;
//! the speedup is the ratio of the two times. The full-size figure (10 000 cases of 20 s) is
//! measured with `pounding sweep examples/bench-10k.toml` (see README, "Parameter sweeps").
//!
//!     cargo bench --bench sweep

use std::path::Path;

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use pounding::study::sweep::run::{RunOptions, Silent, run};
use pounding::study::sweep::{Shard, Sweep};

const CASES: usize = 48;

fn setup(dir: &Path) -> Sweep {
    let base =
        include_str!("../examples/paper-c.toml").replace("duration = 20.0", "duration = 5.0");
    std::fs::write(dir.join("base.toml"), base).unwrap();
    let sweep = format!(
        "scenario = \"base.toml\"\n[[axis]]\nkey = \"period_ratio\"\nfrom = 0.3\nto = 1.0\nsteps = {}\n\
         [[axis]]\nkey = \"ground_motion.pga\"\nvalues = [0.3, 0.6]\n",
        CASES / 2
    );
    let p = dir.join("sweep.toml");
    std::fs::write(&p, sweep).unwrap();
    Sweep::from_file(&p).unwrap()
}

fn bench(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let sweep = setup(dir.path());
    assert_eq!(sweep.len(), CASES);
    let mut g = c.benchmark_group("sweep");
    g.throughput(Throughput::Elements(CASES as u64));
    g.sample_size(10);
    for jobs in [1, 2] {
        g.bench_function(format!("jobs={jobs}"), |b| {
            b.iter_batched(
                || tempfile::tempdir_in(dir.path()).unwrap(),
                |out| {
                    let opts = RunOptions {
                        out_dir: out.path().to_path_buf(),
                        jobs,
                        shard: Shard::ALL,
                        // the sweep machinery and the parallel speed-up, as before the
                        // self-check existed (which multiplies the work per case)
                        check: false,
                    };
                    let o = run(&sweep, &opts, &mut Silent).unwrap();
                    assert_eq!(o.computed, CASES);
                    out
                },
                BatchSize::PerIteration,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
