//! Convergence study (issue 4; what the seed paper's §4 did by hand, docs/model.md §4): the run with
//! pounding repeated for a ladder of mode counts and a ladder of steps (or tolerances), each row
//! with its peaks, peak force, impacts and change relative to the finest row — and for yielding
//! buildings (issue 24) their peak ductility, largest residual drift and hysteretic energy
//! ([`quantities`]).
//!
//! A ladder has *converged* when its two finest runs both ran and agree within the tolerance on
//! both peaks and the peak force (and the yielding quantities); otherwise the study says "not
//! converged", recommends nothing
//! and says what to try. When both ladders converged it recommends the fewest modes and the
//! largest step (loosest tolerance) such that every finer row is within the tolerance of the
//! finest — never the finest alone, and never a row that failed — combined into settings that
//! `pounding run` accepts: a mode count other than the scenario's is run once at the chosen
//! step, and with `rk4` a combination it refuses (stability of the modes, refusal in contact) is
//! replaced by the mode ladder's own method and settings (which ran), with the reason. The
//! recommended settings are then run once more at a finer step (dt/4; `adaptive`: rtol and
//! atol/100) and must agree within the tolerance, or nothing is recommended.

pub mod quantities;

use serde::{Serialize, Serializer};

use crate::input::scenario::Scenario;
use crate::integrate::{
    InitialState, MIN_ATOL, MIN_RTOL, Method, SolveError, SolverSettings, integrate,
    rk4_max_stable_dt,
};
use crate::recording::recorder::Recorder;
use quantities::{Yielding, headline_changes, named, within, worst, yield_changes};

/// Mode counts tried (per structure), capped at [`MAX_MODES`].
pub const MODE_LADDER: [usize; 7] = [1, 2, 3, 5, 10, 20, 50];
/// Largest mode count the study will use.
pub const MAX_MODES: usize = 500;
/// Step multipliers of the scenario's dt tried for the fixed-step methods.
pub const DT_LADDER: [f64; 6] = [4.0, 2.0, 1.0, 0.5, 0.25, 0.125];
/// Relative tolerances tried for `adaptive` (each with its atol, [`SolverSettings::with_rtol`]).
pub const RTOL_LADDER: [f64; 6] = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-12];
/// Relative tolerances tried for `exact-modal`'s contact sub-steps (its eighth-order collocation
/// with a sixth-order companion). The default, 1e-8, is the ladder's second finest, so the
/// ladder's verdict (its two finest runs agree) is the default against a run 100× tighter, as
/// the self-check's; the coarser rungs show how fast the answer settles.
pub const EXACT_MODAL_RTOL_LADDER: [f64; 6] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-10];
/// Fraction of RK4's largest stable step offered when a mode count needs a smaller step.
pub const RK4_DT_MARGIN: f64 = 0.9;

/// The ladders of a study, coarsest first (the last entry is the reference of its ladder).
#[derive(Debug, Clone, PartialEq)]
pub struct Ladders {
    /// Mode counts per structure (capped at [`MAX_MODES`]).
    pub modes: Vec<usize>,
    /// Multipliers of the scenario's dt (fixed-step methods).
    pub dt_factors: Vec<f64>,
    /// Relative tolerances (`adaptive`).
    pub rtols: Vec<f64>,
    /// Relative tolerances (`exact-modal`).
    pub exact_modal_rtols: Vec<f64>,
}

impl Default for Ladders {
    /// [`MODE_LADDER`], [`DT_LADDER`], [`RTOL_LADDER`], [`EXACT_MODAL_RTOL_LADDER`].
    fn default() -> Ladders {
        Ladders {
            modes: MODE_LADDER.to_vec(),
            dt_factors: DT_LADDER.to_vec(),
            rtols: RTOL_LADDER.to_vec(),
            exact_modal_rtols: EXACT_MODAL_RTOL_LADDER.to_vec(),
        }
    }
}

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
    /// Each structure's peak |w(h)| with pounding at its highest contact level (a pair: both
    /// at the main contact height; a row: with either neighbour), m, in row order.
    pub peaks: Vec<f64>,
    /// Each adjacent pair's peak contact force over its levels, N (a pair: one).
    pub forces: Vec<f64>,
    /// Contact episodes over all levels.
    pub impacts: usize,
    /// |x − x_finest|/|x_finest| for each of `peaks` then each of `forces` (0 when
    /// x_finest = 0): a pair's w₁, w₂ and force ([`quantities::quantity_names`]).
    pub change: Vec<f64>,
    /// Yielding buildings only (issue 16), per structure: peak ductility, largest |residual
    /// drift| and hysteretic energy with pounding (`None` for an elastic structure).
    pub yielding: Vec<Option<Yielding>>,
    /// Their changes relative to the finest row, per structure: ductility relative, residual
    /// drift in units of the larger of the finest's and the smallest yield drift, hysteretic
    /// energy in units of the larger of the finest's and 0.1 % of its input energy (as the
    /// self-check measures them, [`crate::analysis::simulate::accuracy`]).
    pub yield_change: Vec<Option<[f64; 3]>>,
    /// Steps taken.
    pub steps: usize,
    /// `None`, or why the row could not be computed (beyond RK4's stability limit for the
    /// modes, refused in contact, a step `pounding run` would refuse).
    pub failure: Option<String>,
}

impl Row {
    /// Every change with its name (`peak w1`, `peak w2`, `peak force` — a row: `peak w{i}` of
    /// every structure, `peak force of pair {p}` of every pair — then `peak ductility of 2`,
    /// `residual drift of 2`, `hysteretic energy of 2` for each yielding structure).
    pub fn changes(&self) -> Vec<(String, f64)> {
        named(&self.change, &self.yield_change)
    }

    /// The largest peak contact force over every pair, N (a pair's peak force).
    pub fn peak_force(&self) -> f64 {
        self.forces.iter().copied().fold(f64::NAN, f64::max)
    }

    /// Largest of the changes (a NaN counts as the largest).
    pub fn worst_change(&self) -> f64 {
        worst(&self.changes()).map_or(0.0, |(_, c)| c)
    }

    /// The step setting in words: `dt = … s` or `rtol = …`.
    fn step_label(&self) -> String {
        match self.rtol {
            Some(r) => format!("rtol = {r:e}"),
            None => format!("dt = {} s", self.dt),
        }
    }
}

fn method_name<S: Serializer>(m: &Method, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(m.name())
}

/// Settings the study recommends: a combination that `pounding run` accepts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Recommended {
    /// Method.
    #[serde(serialize_with = "method_name")]
    pub method: Method,
    /// Modes per structure.
    pub modes: usize,
    /// Step (largest step for `adaptive`), s.
    pub dt: f64,
    /// Relative tolerance (`adaptive` only).
    pub rtol: Option<f64>,
    /// What these settings were checked against (the same at dt/4, or at rtol and atol/100)
    /// and the changes found.
    pub check: String,
    /// Largest change of the peaks and peak force (and the yielding quantities) in that check
    /// (≤ the tolerance).
    pub check_change: f64,
}

impl Recommended {
    /// The scenario with these settings (both structures' modes, method, dt, rtol).
    pub fn apply(&self, scenario: &Scenario) -> Scenario {
        let mut sc = scenario.clone();
        sc.structures[0].set_modes(self.modes);
        sc.structures[1].set_modes(self.modes);
        sc.solver.method = self.method;
        sc.solver.dt = self.dt;
        if let Some(r) = self.rtol {
            sc.solver.rtol = r;
        }
        sc
    }

    /// The settings in words, e.g. `10 modes per structure, adaptive with dt = 0.001 s,
    /// rtol = 1e-8`.
    pub fn describe(&self) -> String {
        let rtol = self
            .rtol
            .map_or(String::new(), |r| format!(", rtol = {r:e}"));
        format!(
            "{} modes per structure, {} with dt = {} s{rtol}",
            self.modes,
            self.method.name(),
            self.dt
        )
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
    /// The mode ladder's two finest runs ran and agree within the tolerance.
    pub modes_converged: bool,
    /// The step ladder's two finest runs ran and agree within the tolerance.
    pub steps_converged: bool,
    /// Both ladders converged. When false nothing is recommended.
    pub converged: bool,
    /// The recommended settings (only when converged).
    pub recommended: Option<Recommended>,
    /// Why the study did not converge and what to try, or why the recommendation differs
    /// from the scenario's method; one sentence each.
    pub notes: Vec<String>,
    /// One line for people.
    pub recommendation: String,
}

/// A row not run (yet) for `n` structures.
fn empty_row(modes: usize, settings: &SolverSettings, n: usize) -> Row {
    Row {
        modes,
        method: settings.method.name(),
        dt: settings.dt,
        rtol: settings.method.has_tolerance().then_some(settings.rtol),
        peaks: vec![f64::NAN; n],
        forces: vec![f64::NAN; n - 1],
        impacts: 0,
        change: vec![f64::NAN; 2 * n - 1],
        yielding: vec![None; n],
        yield_change: vec![None; n],
        steps: 0,
        failure: None,
    }
}

fn with_modes(scenario: &Scenario, modes: usize) -> Scenario {
    let mut sc = scenario.clone();
    for s in &mut sc.structures {
        s.set_modes(modes);
    }
    sc
}

fn one_run(scenario: &Scenario, modes: usize, settings: SolverSettings) -> Row {
    let sc = with_modes(scenario, modes);
    let n = sc.structures.len();
    let mut row = empty_row(modes, &settings, n);
    // what `pounding run` refuses before solving (scenario validation of solver.dt)
    if !(settings.dt < settings.duration && settings.duration / settings.dt <= 1e9) {
        row.failure = Some(format!(
            "dt = {} s is not a step `pounding run` accepts for a duration of {} s",
            settings.dt, settings.duration
        ));
        return row;
    }
    // every pair's levels (a pair's: its own), tracked as `simulate_row` tracks them
    let system = sc.system();
    let heights: Vec<f64> = system.levels.iter().map(|l| l.height).collect();
    let pairs: Vec<usize> = system.levels.iter().map(|l| l.pair).collect();
    let mut rec = Recorder::for_row(
        &system,
        &heights,
        &pairs,
        sc.output_interval,
        settings.duration,
    );
    let out: Result<_, SolveError> =
        integrate(&system, &settings, &InitialState::default(), &mut rec)
            .map(|s| (rec.finish(), s));
    match out {
        Ok((rec, stats)) => {
            for (i, peak) in row.peaks.iter_mut().enumerate() {
                // its highest level with either neighbour (the first on a tie, as the
                // recorder's main level: a pair's `peak`)
                let main = (0..heights.len())
                    .filter(|&k| pairs[k] == i || pairs[k] + 1 == i)
                    .fold(None, |best: Option<usize>, k| match best {
                        Some(b) if heights[k] <= heights[b] => Some(b),
                        _ => Some(k),
                    });
                *peak = main.map_or(0.0, |k| {
                    let l = &rec.levels[k];
                    if pairs[k] == i { l.peak_w1 } else { l.peak_w2 }
                });
            }
            for (p, force) in row.forces.iter_mut().enumerate() {
                *force = (rec.levels.iter().zip(&pairs))
                    .filter(|(_, q)| **q == p)
                    .map(|(l, _)| l.peak_force)
                    .fold(0.0, f64::max);
            }
            row.impacts = rec.levels.iter().map(|l| l.impacts).sum();
            row.yielding = quantities::yielding(&rec, n);
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
    for r in rows.iter_mut().filter(|r| r.failure.is_none()) {
        r.change = changes(r, &finest);
        r.yield_change = yield_changes(&r.yielding, &finest.yielding);
    }
}

/// What a ladder says: the coarsest row from which every row is within the tolerance of the
/// finest (never the finest alone), or why there is none.
struct Verdict {
    /// Index of the recommended row, when the ladder converged.
    pick: Option<usize>,
    /// Why it did not converge.
    why: Option<String>,
}

fn judge(rows: &[Row], tolerance: f64, label: impl Fn(&Row) -> String) -> Verdict {
    let n = rows.len();
    let pct = 100.0 * tolerance;
    let fail = |why: String| Verdict {
        pick: None,
        why: Some(why),
    };
    if n < 2 {
        return fail("fewer than two runs: nothing to compare".into());
    }
    let (prev, last) = (&rows[n - 2], &rows[n - 1]);
    if let Some(f) = &last.failure {
        return fail(format!("the finest run ({}) failed: {f}", label(last)));
    }
    if let Some(f) = &prev.failure {
        return fail(format!(
            "the second finest run ({}) failed, so the finest has nothing to be compared with: {f}",
            label(prev)
        ));
    }
    let all = prev.changes();
    if let Some((name, worst)) = worst(&all).filter(|(_, c)| !within(*c, tolerance)) {
        return fail(format!(
            "the two finest runs ({} and {}) differ by {:.3} % in the {name} (tolerance {pct} %)",
            label(prev),
            label(last),
            100.0 * worst,
        ));
    }
    let ok = |r: &Row| r.failure.is_none() && within(r.worst_change(), tolerance);
    Verdict {
        pick: (0..n - 1).find(|&i| rows[i..].iter().all(ok)),
        why: None,
    }
}

/// Run the study for `scenario` with `tolerance` (relative, > 0) over the default ladders.
/// `progress` is called before each run with a short description (for a CLI to show what is
/// happening).
pub fn convergence(
    scenario: &Scenario,
    tolerance: f64,
    progress: impl FnMut(&str),
) -> ConvergenceTable {
    convergence_with(scenario, tolerance, &Ladders::default(), progress)
}

/// [`convergence`] over the given ladders.
pub fn convergence_with(
    scenario: &Scenario,
    tolerance: f64,
    ladders: &Ladders,
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
    let mut modes: Vec<Row> = ladders
        .modes
        .iter()
        .map(|&m| m.clamp(1, MAX_MODES))
        .map(|m| {
            progress(&format!("{m} modes ({})", mode_settings.method.name()));
            one_run(scenario, m, mode_settings)
        })
        .collect();
    fill_changes(&mut modes);
    let n_modes = (scenario.structures.iter())
        .map(|s| s.modes())
        .max()
        .unwrap_or(1);
    let rtols = match base.method {
        Method::Adaptive => Some(&ladders.rtols),
        Method::ExactModal => Some(&ladders.exact_modal_rtols),
        Method::Rk4 => None,
    };
    let mut steps: Vec<Row> = if let Some(rtols) = rtols {
        rtols
            .iter()
            .map(|&rtol| {
                progress(&format!("rtol = {rtol:e}"));
                one_run(scenario, n_modes, base.with_rtol(rtol))
            })
            .collect()
    } else {
        ladders
            .dt_factors
            .iter()
            .map(|&f| {
                let s = SolverSettings {
                    dt: base.dt * f,
                    ..base
                };
                progress(&format!("dt = {:e} s", s.dt));
                if base.method == Method::Rk4 {
                    let (max_dt, _) = rk4_max_stable_dt(&with_modes(scenario, n_modes).system());
                    if s.dt > max_dt {
                        let mut r = empty_row(n_modes, &s, scenario.structures.len());
                        r.failure = Some(format!("beyond RK4's stability limit {max_dt:.3e} s"));
                        return r;
                    }
                }
                one_run(scenario, n_modes, s)
            })
            .collect()
    };
    fill_changes(&mut steps);

    let pct = 100.0 * tolerance;
    let modes_verdict = judge(&modes, tolerance, |r| format!("{} modes", r.modes));
    let steps_verdict = judge(&steps, tolerance, Row::step_label);
    let modes_converged = modes_verdict.pick.is_some();
    let steps_converged = steps_verdict.pick.is_some();
    let mut notes = Vec::new();
    let recommended = match (modes_verdict.pick, steps_verdict.pick) {
        (Some(im), Some(is)) => combine(
            scenario,
            tolerance,
            &modes[im],
            &steps[is],
            mode_settings,
            n_modes,
            &mut notes,
            &mut progress,
        ),
        (im, is) => {
            match (&modes_verdict.why, im) {
                (Some(why), _) => {
                    notes.push(format!("modes: {why}."));
                    notes.push(advice_modes(&modes, base.method));
                }
                (None, Some(i)) => notes.push(format!(
                    "modes: converged ({} modes and more within {pct} % of {}).",
                    modes[i].modes,
                    modes.last().map_or(0, |r| r.modes)
                )),
                (None, None) => {}
            }
            match (&steps_verdict.why, is) {
                (Some(why), _) => {
                    notes.push(format!("step: {why}."));
                    notes.push(advice_steps(&steps, &base));
                }
                (None, Some(i)) => notes.push(format!(
                    "step: converged ({} and finer within {pct} % of {}).",
                    steps[i].step_label(),
                    steps.last().map_or(String::new(), Row::step_label)
                )),
                (None, None) => {}
            }
            notes.push(format!(
                "or accept a larger difference (--tolerance above {pct} %)."
            ));
            None
        }
    };
    let recommendation = match &recommended {
        Some(r) => {
            let finest_modes = modes.last().map_or(0, |r| r.modes);
            let finest_step = steps.last().map_or(String::new(), Row::step_label);
            let yielding = if modes
                .iter()
                .chain(&steps)
                .any(|r| r.yielding.iter().any(Option::is_some))
            {
                " (and the yielding buildings' peak ductility, residual drift and hysteretic energy)"
            } else {
                ""
            };
            let what = if scenario.structures.len() == 2 {
                "both peaks and the peak force"
            } else {
                "every structure's peak and every pair's peak force"
            };
            format!(
                "{}: {what}{yielding} within {pct} % of the finest run of \
                 each ladder ({finest_modes} modes with {}; {finest_step} with {} and {n_modes} \
                 modes) and of the same settings at {}.",
                r.describe(),
                mode_settings.method.name(),
                base.method.name(),
                r.check
            )
        }
        None => {
            let mut why: Vec<String> = [
                modes_verdict.why.map(|w| format!("modes: {w}")),
                steps_verdict.why.map(|w| format!("step: {w}")),
            ]
            .into_iter()
            .flatten()
            .collect();
            if why.is_empty() {
                why.push("the recommended settings failed their check (see the notes)".into());
            }
            format!(
                "NOT CONVERGED within {pct} %: {}; nothing is recommended.",
                why.join("; ")
            )
        }
    };
    ConvergenceTable {
        tolerance,
        modes,
        steps,
        modes_converged,
        steps_converged,
        converged: recommended.is_some(),
        recommended,
        notes,
        recommendation,
    }
}

/// A finer setting of the same method for the check of a recommendation: dt/4 for `rk4`,
/// rtol and atol/100 (at least [`MIN_RTOL`] and [`MIN_ATOL`]) for the methods with a tolerance
/// (atol too: it bounds the error control from below).
fn finer(settings: SolverSettings) -> SolverSettings {
    match settings.method {
        Method::Adaptive | Method::ExactModal => SolverSettings {
            rtol: (settings.rtol / 100.0).max(MIN_RTOL),
            atol: (settings.atol / 100.0).max(MIN_ATOL),
            ..settings
        },
        Method::Rk4 => SolverSettings {
            dt: settings.dt / 4.0,
            ..settings
        },
    }
}

/// Relative changes of a row's peaks and peak forces against a reference row.
fn changes(row: &Row, reference: &Row) -> Vec<f64> {
    let q = |r: &Row| [r.peaks.as_slice(), r.forces.as_slice()].concat();
    headline_changes(&q(row), &q(reference))
}

/// The recommended settings from the chosen mode row and step row: run (so that `pounding run`
/// is known to accept them; with `rk4` a refused combination is replaced by the mode ladder's
/// own method and settings, with the reason) and checked once more at a finer step (tolerance),
/// which must agree within `tolerance`. `None`, with the reason in `notes`, if the check fails.
#[allow(clippy::too_many_arguments)]
fn combine(
    scenario: &Scenario,
    tolerance: f64,
    mode_row: &Row,
    step_row: &Row,
    mode_settings: SolverSettings,
    n_modes: usize,
    notes: &mut Vec<String>,
    progress: &mut impl FnMut(&str),
) -> Option<Recommended> {
    let base = scenario.solver;
    let m = mode_row.modes;
    let pct = 100.0 * tolerance;
    let mut settings = SolverSettings {
        dt: step_row.dt,
        rtol: step_row.rtol.unwrap_or(base.rtol),
        ..base
    };
    let label = |s: &SolverSettings| {
        Recommended {
            method: s.method,
            modes: m,
            dt: s.dt,
            rtol: s.method.has_tolerance().then_some(s.rtol),
            check: String::new(),
            check_change: 0.0,
        }
        .describe()
    };
    let mut row = if m == n_modes {
        step_row.clone()
    } else if settings == mode_settings {
        mode_row.clone()
    } else {
        let system = with_modes(scenario, m).system();
        match settings.check_stability(&system) {
            Err(e) => {
                let mut r = empty_row(m, &settings, scenario.structures.len());
                r.failure = Some(e.to_string());
                r
            }
            Ok(()) => {
                progress(&format!("check: {}", label(&settings)));
                one_run(scenario, m, settings)
            }
        }
    };
    if m != n_modes && row.failure.is_none() {
        notes.push(format!(
            "the step was chosen with the scenario's {n_modes} modes per structure and the mode \
             count with {} at dt = {} s; the combination was run and checked.",
            mode_settings.method.name(),
            mode_settings.dt
        ));
    }
    if let Some(refusal) = &row.failure {
        // only rk4 refuses a step (stability of the modes, or in contact)
        let (max_dt, _) = rk4_max_stable_dt(&with_modes(scenario, m).system());
        notes.push(format!(
            "{} cannot run {m} modes per structure at dt = {} s: {refusal}",
            settings.method.name(),
            settings.dt
        ));
        notes.push(format!(
            "recommended instead: the mode ladder's own settings for {m} modes ({}, stable for \
             any step and mode count), which ran; to keep {} with {m} modes, dt ≤ {:.3e} s \
             ({RK4_DT_MARGIN} × its stability limit for the modes, {max_dt:.3e} s; not tested \
             here, and a stiff contact may need less).",
            mode_settings.method.name(),
            settings.method.name(),
            RK4_DT_MARGIN * max_dt,
        ));
        settings = mode_settings;
        row = mode_row.clone();
    }
    // the check: the same settings at a finer step (tolerance)
    let fine = finer(settings);
    let what = match fine.method {
        Method::Adaptive | Method::ExactModal => {
            format!("rtol = {:e}, atol = {:e} m", fine.rtol, fine.atol)
        }
        _ => format!("dt = {} s", fine.dt),
    };
    progress(&format!(
        "check: {m} modes, {} with {what}",
        fine.method.name()
    ));
    let fine_row = one_run(scenario, m, fine);
    if let Some(f) = &fine_row.failure {
        notes.push(format!(
            "the check of {} at {what} failed: {f}; nothing is recommended.",
            label(&settings)
        ));
        return None;
    }
    let all = named(
        &changes(&row, &fine_row),
        &yield_changes(&row.yielding, &fine_row.yielding),
    );
    let worst = worst(&all).map_or(0.0, |(_, c)| c);
    let check = format!(
        "{what} (changes of {}: {})",
        all.iter()
            .map(|(n, _)| n.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        all.iter()
            .map(|(_, c)| format!("{c:.1e}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    if !within(worst, tolerance) {
        notes.push(format!(
            "{} is not converged: the same at {check} differs by more than the tolerance \
             ({pct} %); nothing is recommended.",
            label(&settings)
        ));
        notes.push(match settings.method {
            Method::Adaptive | Method::ExactModal => format!(
                "try: a tighter solver.rtol than {:e} (and solver.atol, if it is set), a \
                 smaller solver.dt, another method, or a larger --tolerance.",
                settings.rtol
            ),
            _ => format!(
                "try: a smaller solver.dt than {} s, another method, or a larger --tolerance.",
                settings.dt
            ),
        });
        return None;
    }
    Some(Recommended {
        method: settings.method,
        modes: m,
        dt: settings.dt,
        rtol: settings.method.has_tolerance().then_some(settings.rtol),
        check,
        check_change: worst,
    })
}

/// What to try when the mode ladder did not converge.
fn advice_modes(rows: &[Row], method: Method) -> String {
    let most = rows.last().map_or(0, |r| r.modes);
    let stable = if method == Method::Rk4 {
        " with `exact-modal` or `adaptive` (stable with any number of modes; rk4 needs \
         dt ≲ 2.8/ω of the highest mode)"
    } else {
        ""
    };
    format!(
        "try: more modes than {most} per structure (structure.modes, up to {MAX_MODES}){stable}, \
         and compare again;"
    )
}

/// What to try when the step ladder did not converge.
fn advice_steps(rows: &[Row], base: &SolverSettings) -> String {
    let finest = rows.last().map_or(base.dt, |r| r.dt);
    match base.method {
        Method::Rk4 => format!(
            "try: a smaller solver.dt than {finest} s, or another method (`exact-modal`, \
             `adaptive`: their steps follow the contact and they are stable for any number of \
             modes);"
        ),
        Method::ExactModal => {
            let rtol = rows.last().and_then(|r| r.rtol).unwrap_or(base.rtol);
            format!(
                "try: a tighter solver.rtol than {rtol:e} (its contact sub-steps), `adaptive` \
                 (sixth order: cheaper at tight tolerances), or a smaller solver.dt ({finest} s \
                 now: it sets the peaks' extraction between observations);"
            )
        }
        Method::Adaptive => {
            let rtol = rows.last().and_then(|r| r.rtol).unwrap_or(base.rtol);
            format!(
                "try: a tighter solver.rtol than {rtol:e} (and solver.atol, if it is set: it \
                 bounds the error control from below), a smaller solver.dt (the largest \
                 step, {finest} s now), or another method (`exact-modal`, `rk4` with a small \
                 dt);"
            )
        }
    }
}

#[cfg(test)]
mod tests;
