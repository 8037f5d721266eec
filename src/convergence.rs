//! Convergence study (issue 4; what the seed paper's §4 did by hand, SPEC §4): the run with
//! pounding repeated for a ladder of mode counts and a ladder of steps (or tolerances), each row
//! with its peaks, peak force, impacts and change relative to the finest row, and a
//! recommendation: the fewest modes and the largest step (loosest tolerance) whose peaks and peak
//! force are within a tolerance of the finest.

use serde::Serialize;

use crate::integrate::{InitialState, Method, SolveError, SolverSettings, rk4_max_stable_dt};
use crate::scenario::Scenario;
use crate::simulate::run_system;

/// Mode counts tried (per structure), capped at [`MAX_MODES`].
pub const MODE_LADDER: [usize; 7] = [1, 2, 3, 5, 10, 20, 50];
/// Largest mode count the study will use.
pub const MAX_MODES: usize = 500;
/// Step multipliers of the scenario's dt tried for the fixed-step methods.
pub const DT_LADDER: [f64; 6] = [4.0, 2.0, 1.0, 0.5, 0.25, 0.125];
/// Relative tolerances tried for `adaptive`.
pub const RTOL_LADDER: [f64; 6] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-10];

/// One run of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Modes per structure.
    pub modes: usize,
    /// Method used.
    pub method: &'static str,
    /// Step (fixed-step methods) or largest step (`adaptive`), s.
    pub dt: f64,
    /// Relative tolerance (`adaptive` only).
    pub rtol: Option<f64>,
    /// Peak |w₁(h)| and |w₂(h)| with pounding at the main contact height, m.
    pub peak_w1: f64,
    /// See `peak_w1`.
    pub peak_w2: f64,
    /// Peak contact force over all levels, N.
    pub peak_force: f64,
    /// Contact episodes over all levels.
    pub impacts: usize,
    /// |x − x_finest|/|x_finest| for w₁, w₂ and the force (0 when x_finest = 0).
    pub change: [f64; 3],
    /// Steps taken.
    pub steps: usize,
    /// `None`, or why the row could not be computed (e.g. beyond RK4's stability limit).
    pub failure: Option<String>,
}

impl Row {
    /// Largest of the three relative changes.
    pub fn worst_change(&self) -> f64 {
        self.change.iter().fold(0.0, |m, &c| m.max(c))
    }
}

/// The whole study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConvergenceTable {
    /// Tolerance on the relative change vs the finest row (e.g. 0.01 = 1 %).
    pub tolerance: f64,
    /// Mode ladder (at the scenario's step settings; `adaptive` if the scenario uses `rk4`,
    /// whose stability limit shrinks like 1/n²).
    pub modes: Vec<Row>,
    /// Step/tolerance ladder (at the scenario's modes and method).
    pub steps: Vec<Row>,
    /// Fewest modes within tolerance of the finest (`None`: none but the finest).
    pub recommended_modes: Option<usize>,
    /// Largest step within tolerance, s (fixed-step methods).
    pub recommended_dt: Option<f64>,
    /// Loosest rtol within tolerance (`adaptive`).
    pub recommended_rtol: Option<f64>,
    /// One line for people.
    pub recommendation: String,
}

fn empty_row(modes: usize, settings: &SolverSettings) -> Row {
    Row {
        modes,
        method: settings.method.name(),
        dt: settings.dt,
        rtol: (settings.method == Method::Adaptive).then_some(settings.rtol),
        peak_w1: f64::NAN,
        peak_w2: f64::NAN,
        peak_force: f64::NAN,
        impacts: 0,
        change: [f64::NAN; 3],
        steps: 0,
        failure: None,
    }
}

fn one_run(scenario: &Scenario, modes: usize, settings: SolverSettings) -> Row {
    let mut sc = scenario.clone();
    sc.structures[0].modes = modes;
    sc.structures[1].modes = modes;
    let system = sc.system();
    let heights: Vec<f64> = sc.contact.levels.iter().map(|l| l.height).collect();
    let mut row = empty_row(modes, &settings);
    let out: Result<_, SolveError> = run_system(
        &system,
        &settings,
        &InitialState::default(),
        &heights,
        sc.output_interval,
    );
    match out {
        Ok((rec, stats)) => {
            row.peak_w1 = rec.peak[0];
            row.peak_w2 = rec.peak[1];
            row.peak_force = rec.levels.iter().map(|l| l.peak_force).fold(0.0, f64::max);
            row.impacts = rec.levels.iter().map(|l| l.impacts).sum();
            row.steps = stats.steps;
        }
        Err(e) => row.failure = Some(e.to_string()),
    }
    row
}

fn fill_changes(rows: &mut [Row]) {
    let Some(finest) = rows.iter().rev().find(|r| r.failure.is_none()).cloned() else {
        return;
    };
    let ch = |x: f64, f: f64| {
        if f == 0.0 {
            if x == 0.0 { 0.0 } else { f64::INFINITY }
        } else {
            (x - f).abs() / f.abs()
        }
    };
    for r in rows.iter_mut().filter(|r| r.failure.is_none()) {
        r.change = [
            ch(r.peak_w1, finest.peak_w1),
            ch(r.peak_w2, finest.peak_w2),
            ch(r.peak_force, finest.peak_force),
        ];
    }
}

/// Run the study for `scenario` with `tolerance` (relative, > 0). `progress` is called before
/// each run with a short description (for a CLI to show what is happening).
pub fn convergence(
    scenario: &Scenario,
    tolerance: f64,
    mut progress: impl FnMut(&str),
) -> ConvergenceTable {
    let base = scenario.solver;
    // modes: a method stable for any number of modes
    let mode_settings = if base.method == Method::Rk4 {
        SolverSettings {
            method: Method::Adaptive,
            ..base
        }
    } else {
        base
    };
    let mut modes: Vec<Row> = MODE_LADDER
        .iter()
        .map(|&m| m.min(MAX_MODES))
        .map(|m| {
            progress(&format!("{m} modes ({})", mode_settings.method.name()));
            one_run(scenario, m, mode_settings)
        })
        .collect();
    fill_changes(&mut modes);
    let n_modes = scenario.structures[0]
        .modes
        .max(scenario.structures[1].modes);
    let mut steps: Vec<Row> = if base.method == Method::Adaptive {
        RTOL_LADDER
            .iter()
            .map(|&rtol| {
                progress(&format!("rtol = {rtol:e}"));
                one_run(scenario, n_modes, SolverSettings { rtol, ..base })
            })
            .collect()
    } else {
        DT_LADDER
            .iter()
            .map(|&f| {
                let s = SolverSettings {
                    dt: base.dt * f,
                    ..base
                };
                progress(&format!("dt = {:e} s", s.dt));
                if base.method == Method::Rk4 {
                    let mut sc = scenario.clone();
                    sc.structures[0].modes = n_modes;
                    sc.structures[1].modes = n_modes;
                    let (max_dt, _) = rk4_max_stable_dt(&sc.system());
                    if s.dt > max_dt {
                        let mut r = empty_row(n_modes, &s);
                        r.failure = Some(format!("beyond RK4's stability limit {max_dt:.3e} s"));
                        return r;
                    }
                }
                one_run(scenario, n_modes, s)
            })
            .collect()
    };
    fill_changes(&mut steps);
    let ok = |r: &&Row| r.failure.is_none() && r.worst_change() <= tolerance;
    // the fewest modes such that it and every larger count are within tolerance
    let recommended_modes = {
        let n = modes.len();
        (0..n)
            .find(|&i| modes[i..].iter().all(|r| ok(&r)))
            .map(|i| modes[i].modes)
    };
    let first_ok = (0..steps.len()).find(|&i| steps[i..].iter().all(|r| ok(&r)));
    let (recommended_dt, recommended_rtol) = match first_ok {
        Some(i) if base.method == Method::Adaptive => (None, steps[i].rtol),
        Some(i) => (Some(steps[i].dt), None),
        None => (None, None),
    };
    let pct = 100.0 * tolerance;
    let recommendation = match (recommended_modes, first_ok) {
        (Some(m), Some(i)) => {
            let step = match steps[i].rtol {
                Some(r) => format!("rtol = {r:e}"),
                None => format!("dt = {} s", steps[i].dt),
            };
            let finest_modes = modes.last().map_or(0, |r| r.modes);
            format!(
                "{m} modes per structure and {step} ({}) keep both peaks and the peak force within {pct} % \
                 of the finest runs ({finest_modes} modes; the finest step).",
                base.method.name()
            )
        }
        (None, _) => format!(
            "no mode count below {} keeps the peaks and peak force within {pct} % of it: use more modes \
             (or a larger tolerance).",
            modes.last().map_or(0, |r| r.modes)
        ),
        (_, None) => format!(
            "no step/tolerance in the ladder keeps the peaks and peak force within {pct} % of the finest: \
             refine further."
        ),
    };
    ConvergenceTable {
        tolerance,
        modes,
        steps,
        recommended_modes,
        recommended_dt,
        recommended_rtol,
        recommendation,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cheap scenario: 2 s of the paper's case.
    #[test]
    fn study_of_a_short_case_recommends_within_tolerance() {
        let text = include_str!("../examples/paper-c.toml")
            .replace("duration = 20.0", "duration = 2.0")
            .replace("method = \"rk4\"", "method = \"exact-modal\"");
        let sc = Scenario::from_toml(&text, "t", ".".as_ref()).unwrap();
        let t = convergence(&sc, 0.05, |_| {});
        assert_eq!(t.modes.len(), MODE_LADDER.len());
        assert_eq!(t.steps.len(), DT_LADDER.len());
        let last = t.steps.last().unwrap();
        assert_eq!(last.change, [0.0; 3]);
        if let Some(m) = t.recommended_modes {
            let row = t.modes.iter().find(|r| r.modes == m).unwrap();
            assert!(row.worst_change() <= 0.05);
        }
        assert!(!t.recommendation.is_empty());
    }
}
