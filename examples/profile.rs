//! Runs `simulate` on a scenario N times, for profilers and instruction counts (wall time on a
//! shared machine drifts; `valgrind --tool=callgrind` counts do not):
//!
//! ```text
//! cargo build --release --example profile
//! valgrind --tool=callgrind --callgrind-out-file=/dev/null \
//!     target/release/examples/profile examples/paper-c.toml exact-modal 0.01 10
//! ```
//!
//! Arguments: scenario file, method (replaces `method = "rk4"`), dt (replaces `dt = 0.001`),
//! repetitions, and optionally `check` (the run and its self-check, as `pounding run` does),
//! `floors` (also the responses over the structures' heights, as `pounding run` does) or
//! `check,floors`; without them the headline integration alone (`simulate_headline`, what a
//! sweep row costs). A row of buildings (more than two structures) runs `simulate_row` (its
//! two runs with the floors; `check` is refused, as `pounding run` refuses it for a row).
//! Prints the best wall time, the recorder's observations (with and without contact:
//! `RunRecord::steps`, not the solver's accepted steps) and the peaks of the last run.

use std::time::Instant;

use pounding::analysis::simulate::{simulate_checked, simulate_headline, simulate_row};
use pounding::input::scenario::Scenario;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or("examples/paper-c.toml", |s| s.as_str());
    let method = args.get(2).map_or("exact-modal", |s| s.as_str());
    let dt: f64 = args.get(3).map_or(Ok(0.01), |s| s.parse())?;
    let reps: usize = args.get(4).map_or(Ok(100), |s| s.parse())?;
    let (check, floors) = match args.get(5).map(|s| s.as_str()) {
        None => (false, false),
        Some("check") => (true, false),
        Some("floors") => (false, true),
        Some("check,floors") => (true, true),
        Some(other) => {
            return Err(format!(
                "5th argument: `check`, `floors`, `check,floors` or nothing, not `{other}`"
            )
            .into());
        }
    };
    let text = std::fs::read_to_string(path)?
        .replace("method = \"rk4\"", &format!("method = \"{method}\""))
        .replace("dt = 0.001", &format!("dt = {dt}"));
    let dir = std::path::Path::new(path)
        .parent()
        .unwrap_or(std::path::Path::new("."));
    let scenario = Scenario::from_toml(&text, path, dir)?;
    let mut best = f64::INFINITY;
    if scenario.is_row() {
        if check {
            return Err("a row has no self-check (pounding run refuses it)".into());
        }
        let mut last = None;
        for _ in 0..reps.max(1) {
            let t0 = Instant::now();
            last = Some(simulate_row(&scenario)?);
            best = best.min(t0.elapsed().as_secs_f64());
        }
        if let Some(r) = last {
            let impacts: usize = r.pairs.iter().map(|p| p.contact.impacts).sum();
            println!(
                "best {:.3} ms; observations {} + {}; {} structures, {} impacts",
                best * 1e3,
                r.with_contact.steps,
                r.without_contact.steps,
                r.structures.len(),
                impacts
            );
        }
        return Ok(());
    }
    let mut last = None;
    for _ in 0..reps.max(1) {
        let t0 = Instant::now();
        last = Some(if floors {
            simulate_checked(&scenario, check)?
        } else {
            simulate_headline(&scenario, check)?
        });
        best = best.min(t0.elapsed().as_secs_f64());
    }
    if let Some(r) = last {
        println!(
            "best {:.3} ms; observations {} + {}; peaks {:.6} {:.6} m; peak force {:.6e} N",
            best * 1e3,
            r.with_contact.steps,
            r.without_contact.steps,
            r.with_contact.peak[0],
            r.with_contact.peak[1],
            r.contact.peak_force
        );
    }
    Ok(())
}
