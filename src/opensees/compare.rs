//! `pounding crosscheck`: run an exported script with a local `openseespy` and set OpenSees'
//! numbers beside the program's, with the relative differences and what explains them.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use super::results::{OpenSeesResults, ProgramNumbers, Row};
use super::{DRIVER, ExportError, ExportOptions, Mapping, TESTED_OPENSEESPY, law_mapping};
use crate::analysis::simulate::{run_system, simulate};
use crate::input::scenario::Scenario;
use crate::integrate::{InitialState, Method, SolveError, SolverSettings};
use crate::model::structure::Structure;

/// Environment variable naming the Python interpreter to run OpenSees with (default
/// `python3`).
pub const PYTHON_ENV: &str = "POUNDING_PYTHON";

/// Why a crosscheck could not be made.
#[derive(Debug, thiserror::Error)]
pub enum CrosscheckError {
    /// No usable openseespy.
    #[error(
        "openseespy is not available to `{python}`: {detail}\n  install it with `{python} -m pip install \
         openseespy=={TESTED_OPENSEESPY}` (in a virtual environment: `python3 -m venv venv && \
         venv/bin/pip install openseespy=={TESTED_OPENSEESPY}`), or set {PYTHON_ENV} to a python \
         that has it"
    )]
    Missing {
        /// The interpreter tried.
        python: String,
        /// What it said.
        detail: String,
    },
    /// The scenario cannot be exported.
    #[error(transparent)]
    Export(#[from] ExportError),
    /// The OpenSees run failed.
    #[error("the OpenSees run failed ({status}): {detail}")]
    Failed {
        /// Exit status.
        status: String,
        /// Its last words.
        detail: String,
    },
    /// Its output could not be read.
    #[error("could not read OpenSees' results {path}: {detail}")]
    Parse {
        /// The file.
        path: String,
        /// Why.
        detail: String,
    },
    /// A file could not be written.
    #[error("could not write {path}: {detail}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        detail: String,
    },
    /// The program's own run failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
}

/// The interpreter to use: `$POUNDING_PYTHON`, else `python3`.
pub fn python() -> String {
    std::env::var(PYTHON_ENV)
        .ok()
        .filter(|s| !s.trim().is_empty())
        .unwrap_or_else(|| "python3".to_string())
}

/// The driver's import function (with its imports), for [`probe`].
fn import_prelude() -> &'static str {
    let end = DRIVER.find("def node_tag").unwrap_or(DRIVER.len());
    &DRIVER[..end]
}

/// Check that `python` can import openseespy; its version (e.g. `3.7.1`).
pub fn probe(python: &str) -> Result<String, CrosscheckError> {
    let code = format!(
        "{}\nops = import_opensees()\nprint(ops.version())\n",
        import_prelude()
    );
    let out = Command::new(python)
        .arg("-c")
        .arg(code)
        .output()
        .map_err(|e| CrosscheckError::Missing {
            python: python.to_string(),
            detail: format!("could not run it ({e})"),
        })?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    let version = stdout.lines().rev().find(|l| !l.trim().is_empty());
    match (out.status.success(), version) {
        (true, Some(v)) => Ok(v.trim().to_string()),
        _ => Err(CrosscheckError::Missing {
            python: python.to_string(),
            detail: last_line(&String::from_utf8_lossy(&out.stderr))
                .unwrap_or_else(|| format!("it exited with {}", out.status)),
        }),
    }
}

fn last_line(text: &str) -> Option<String> {
    text.lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .map(|l| l.trim().to_string())
}

/// Parse a script's JSON output.
pub fn parse_results(text: &str, path: &str) -> Result<OpenSeesResults, CrosscheckError> {
    serde_json::from_str(text).map_err(|e| CrosscheckError::Parse {
        path: path.to_string(),
        detail: e.to_string(),
    })
}

/// Write `script` into `dir` as `model.py`, run it with `python` (`extra` arguments after the
/// script's own) and read its results (`opensees.json` in `dir`).
pub fn run_script(
    python: &str,
    script: &str,
    dir: &Path,
    extra: &[String],
) -> Result<OpenSeesResults, CrosscheckError> {
    let (text, json) = run_script_text(python, script, dir, extra)?;
    parse_results(&text, &json)
}

/// [`run_script`] up to the text of `opensees.json` (and its path), for a pair's or a row's
/// results.
pub fn run_script_text(
    python: &str,
    script: &str,
    dir: &Path,
    extra: &[String],
) -> Result<(String, String), CrosscheckError> {
    let model = dir.join("model.py");
    let json = dir.join("opensees.json");
    let log = dir.join("opensees.log");
    crate::output::atomic::write_atomic(&model, script.as_bytes()).map_err(|e| {
        CrosscheckError::Io {
            path: model.display().to_string(),
            detail: e.to_string(),
        }
    })?;
    let out = Command::new(python)
        .arg(&model)
        .arg("--json")
        .arg(&json)
        .arg("--log")
        .arg(&log)
        .args(extra)
        .output()
        .map_err(|e| CrosscheckError::Missing {
            python: python.to_string(),
            detail: format!("could not run it ({e})"),
        })?;
    if !out.status.success() {
        return Err(CrosscheckError::Failed {
            status: out.status.to_string(),
            detail: last_line(&String::from_utf8_lossy(&out.stderr))
                .unwrap_or_else(|| "no message".into()),
        });
    }
    let text = std::fs::read_to_string(&json).map_err(|e| CrosscheckError::Parse {
        path: json.display().to_string(),
        detail: e.to_string(),
    })?;
    Ok((text, json.display().to_string()))
}

/// The heights whose peaks are reported for structure `s` (as in the export).
pub fn tracked_heights(scenario: &Scenario, s: usize) -> Vec<f64> {
    match &scenario.structures[s] {
        Structure::Floors(f) => f
            .all_modes
            .floor_heights()
            .map(|h| h.to_vec())
            .unwrap_or_default(),
        Structure::Cantilever(_) => scenario.contact.levels.iter().map(|l| l.height).collect(),
    }
}

/// Run the program on `scenario` (both runs, no self-check) and collect the numbers compared.
pub fn program(scenario: &Scenario) -> Result<ProgramNumbers, CrosscheckError> {
    let start = Instant::now();
    let report = simulate(scenario)?;
    let seconds = start.elapsed().as_secs_f64();
    let floors = scenario
        .structures
        .iter()
        .any(|s| matches!(s, Structure::Floors(_)));
    let level_heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let mut heights: [Vec<(f64, f64, f64)>; 2] = [Vec::new(), Vec::new()];
    if floors {
        // every tracked height after the contact levels (whose records the recorder keys)
        let mut all = level_heights.clone();
        for s in 0..2 {
            all.extend(tracked_heights(scenario, s));
        }
        let system = scenario.system();
        let free = system.without_contact();
        let init = InitialState::default();
        let interval = scenario.output_interval;
        let (with, _) = run_system(&system, &scenario.solver, &init, &all, interval)?;
        let (without, _) = run_system(&free, &scenario.solver, &init, &all, interval)?;
        for (s, out) in heights.iter_mut().enumerate() {
            for h in tracked_heights(scenario, s) {
                let k = all.iter().position(|x| (x - h).abs() <= 1e-9).unwrap_or(0);
                let pick = |l: &crate::recording::run_record::LevelRecord| {
                    if s == 0 { l.peak_w1 } else { l.peak_w2 }
                };
                out.push((h, pick(&with.levels[k]), pick(&without.levels[k])));
            }
        }
    } else {
        for (s, out) in heights.iter_mut().enumerate() {
            for l in &report.levels {
                out.push((
                    l.height,
                    l.peak_displacement[s],
                    l.peak_displacement_no_contact[s],
                ));
            }
        }
    }
    Ok(ProgramNumbers {
        report,
        heights,
        seconds,
    })
}

/// `scenario` with `modes` modes per structure (a building keeps at most its floors); when
/// the scenario's `rk4` step is then beyond the stability limit, the program's method becomes
/// `adaptive` at its default tolerance (said in the returned note).
pub fn with_modes(scenario: &Scenario, modes: usize) -> (Scenario, Option<String>) {
    let mut sc = scenario.clone();
    for s in &mut sc.structures {
        s.set_modes(modes.max(1));
    }
    let mut note = None;
    if sc.solver.check_stability(&sc.system()).is_err() {
        let s = sc.solver;
        sc.solver = SolverSettings::new(Method::Adaptive, s.dt, s.duration);
        note = Some(format!(
            "with {modes} modes the scenario's rk4 step dt = {} s is unstable: the program runs \
             `adaptive` (rtol {:e}) instead",
            s.dt,
            Method::Adaptive.default_rtol()
        ));
    }
    (sc, note)
}

/// `scenario` over `duration` s instead of its own.
pub fn with_duration(scenario: &Scenario, duration: f64) -> Scenario {
    let mut sc = scenario.clone();
    sc.solver.duration = duration;
    sc.output_interval = sc.output_interval.min(duration);
    sc
}

/// The quantities compared: peaks at the main height with and without contact, per level
/// and per floor when there are several, the contact totals, the time-history separation.
pub fn rows(p: &ProgramNumbers, o: &OpenSeesResults) -> Vec<Row> {
    let mut rows = Vec::new();
    let r = &p.report;
    let row = |q: String, program: f64, opensees: Option<f64>| Row {
        quantity: q,
        program,
        opensees,
        scale: 0.0,
    };
    for s in 0..2 {
        let os = o.structures.get(s);
        rows.push(row(
            format!("peak w{}(h) with contact [m]", s + 1),
            r.structures[s].peak_displacement,
            os.and_then(|x| x.peak_displacement),
        ));
        rows.push(row(
            format!("peak w{}(h) without contact [m]", s + 1),
            r.structures[s].peak_displacement_no_contact,
            os.and_then(|x| x.peak_displacement_no_contact),
        ));
    }
    let several = r.levels.len() > 1;
    for s in 0..2 {
        let list = &p.heights[s];
        let floors = matches!(
            list.len(),
            n if n > 1 || (n == 1 && several)
        );
        if !floors {
            continue;
        }
        for (i, &(h, with, without)) in list.iter().enumerate() {
            let os = o.structures.get(s).and_then(|x| x.heights.get(i));
            rows.push(row(
                format!("  w{} at {h} m with contact [m]", s + 1),
                with,
                os.and_then(|x| x.peak_displacement),
            ));
            rows.push(row(
                format!("  w{} at {h} m without contact [m]", s + 1),
                without,
                os.and_then(|x| x.peak_displacement_no_contact),
            ));
        }
    }
    rows.extend(super::storeys::storey_rows(p, o));
    let oc = o.contact.as_ref();
    rows.push(row(
        "peak contact force [N]".into(),
        r.contact.peak_force,
        oc.map(|c| c.peak_force),
    ));
    if several {
        for (k, l) in r.levels.iter().enumerate() {
            rows.push(row(
                format!("  peak force at {} m [N]", l.height),
                l.peak_force,
                o.levels.get(k).and_then(|x| x.peak_force),
            ));
        }
    }
    rows.push(row(
        "max penetration [m]".into(),
        r.contact.max_penetration,
        oc.map(|c| c.max_penetration),
    ));
    rows.push(row(
        "impacts".into(),
        r.contact.impacts as f64,
        oc.map(|c| c.impacts as f64),
    ));
    rows.push(row(
        "contact time [s]".into(),
        r.contact.contact_time,
        oc.map(|c| c.contact_time),
    ));
    rows.push(row(
        "required separation, time history [m]".into(),
        r.separation.time_history,
        o.separation.time_history,
    ));
    rows
}

/// What explains the differences, for this scenario and these options.
pub fn notes(scenario: &Scenario, o: &OpenSeesResults) -> Vec<String> {
    notes_for(scenario, &o.elements, o.dt)
}

/// [`notes`] from OpenSees' elements per structure and its step `dt` (s): a pair's or a row's
/// (each distinct contact law of a row's pairs once).
pub(super) fn notes_for(scenario: &Scenario, elements: &[usize], dt: f64) -> Vec<String> {
    let mut notes = Vec::new();
    for (s, st) in scenario.structures.iter().enumerate() {
        let elements = elements.get(s).copied().unwrap_or(0);
        notes.push(match st {
            Structure::Cantilever(_) => format!(
                "{}: mode truncation vs discretisation — the program keeps {} modes of the \
                 continuous cantilever, OpenSees has every mode of its {elements} elements \
                 (the low modes converge fast with consistent mass; the high ones, which ring \
                 in contact, differ)",
                st.name(),
                st.modes()
            ),
            Structure::Floors(_) => format!(
                "{}: the same model in both (floor masses, storey springs); the program keeps \
                 {} of its {elements} modes, OpenSees all",
                st.name(),
                st.modes()
            ),
        });
    }
    notes.push(format!(
        "time step: OpenSees runs Newmark average acceleration at dt = {dt} s (period \
         elongation ≈ (ωdt)²/12 per mode; peaks only at step ends), the program {} at \
         dt = {} s",
        scenario.solver.method.name(),
        scenario.solver.dt
    ));
    let mut laws: Vec<&'static str> = Vec::new();
    for c in scenario.contacts() {
        if laws.contains(&c.law.name()) {
            continue;
        }
        laws.push(c.law.name());
        notes.push(match law_mapping(&c.law) {
            Mapping::Exact(t) => format!("contact law mapped exactly: {t}"),
            Mapping::Approximate(t) => format!("contact law mapped approximately: {t}"),
            Mapping::Refused(t) => t.to_string(),
        });
    }
    notes.push(
        "impacts and contact time follow the sequence of impacts, which a small difference \
         early on changes (a chaotic response): compare them loosely"
            .to_string(),
    );
    notes.extend(super::damping_notes(scenario));
    if scenario.structures.iter().any(|s| s.hysteresis().is_some()) {
        notes.push(format!(
            "yielding {}; peak storey forces and drifts are taken at OpenSees' step ends, the \
             hysteretic energy from the work of the link force over the steps (trapezoidal)",
            super::BOUC_WEN_MAPPING
        ));
    }
    notes
}

/// Options of [`crosscheck`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CrosscheckOptions {
    /// The export's options (elements, OpenSees step, duration).
    pub export: ExportOptions,
    /// Modes per structure in the program (`None`: the scenario's).
    pub modes: Option<usize>,
    /// Keep the script and OpenSees' output in this directory (`None`: a temporary one).
    pub keep: Option<std::path::PathBuf>,
}

/// A crosscheck's outcome.
#[derive(Debug, Clone)]
pub struct Crosscheck {
    /// The scenario as the program ran it (modes, method, duration).
    pub scenario: Scenario,
    /// The program's numbers.
    pub program: ProgramNumbers,
    /// OpenSees' numbers.
    pub opensees: OpenSeesResults,
    /// Quantity by quantity.
    pub rows: Vec<Row>,
    /// What explains the differences.
    pub notes: Vec<String>,
}

/// `scenario` as the program runs it in a crosscheck: over `--duration` and with `--modes`
/// when given (checked), with a note when the method had to change.
pub(super) fn prepared(
    scenario: &Scenario,
    opts: &CrosscheckOptions,
) -> Result<(Scenario, Vec<String>), CrosscheckError> {
    let mut sc = scenario.clone();
    if let Some(t) = opts.export.duration {
        if !(t.is_finite() && t > 0.0) {
            return Err(ExportError::Option(format!(
                "--duration must be a finite number > 0 (s), got {t}"
            ))
            .into());
        }
        sc = with_duration(&sc, t);
    }
    let mut notes = Vec::new();
    if let Some(n) = opts.modes {
        if n == 0 || n > crate::input::scenario::MAX_MODES as usize {
            return Err(ExportError::Option(format!(
                "--modes must be a whole number from 1 to {}, got {n}",
                crate::input::scenario::MAX_MODES
            ))
            .into());
        }
        let (s, note) = with_modes(&sc, n);
        sc = s;
        notes.extend(note);
    }
    Ok((sc, notes))
}

/// `f` in the directory `keep` (created), or in a temporary one removed afterwards.
pub(super) fn in_dir<T>(
    keep: &Option<std::path::PathBuf>,
    f: impl FnOnce(&Path) -> Result<T, CrosscheckError>,
) -> Result<T, CrosscheckError> {
    match keep {
        Some(d) => {
            std::fs::create_dir_all(d).map_err(|e| CrosscheckError::Io {
                path: d.display().to_string(),
                detail: e.to_string(),
            })?;
            f(d)
        }
        None => {
            let tmp = tempfile::tempdir().map_err(|e| CrosscheckError::Io {
                path: "a temporary directory".into(),
                detail: e.to_string(),
            })?;
            f(tmp.path())
        }
    }
}

/// Export `scenario` (named `source`), run it with `python`'s openseespy and the program, and
/// compare.
pub fn crosscheck(
    scenario: &Scenario,
    source: &str,
    opts: &CrosscheckOptions,
    python: &str,
) -> Result<Crosscheck, CrosscheckError> {
    let (sc, extra_notes) = prepared(scenario, opts)?;
    let script = super::script(&sc, &opts.export, source)?;
    probe(python)?;
    let opensees = in_dir(&opts.keep, |dir| run_script(python, &script, dir, &[]))?;
    let program = program(&sc)?;
    let rows = rows(&program, &opensees);
    let mut notes = extra_notes;
    notes.extend(self::notes(&sc, &opensees));
    Ok(Crosscheck {
        scenario: sc,
        program,
        opensees,
        rows,
        notes,
    })
}

impl Crosscheck {
    /// The largest |relative difference| over the peaks and the peak force (not impacts,
    /// contact time or penetration, which follow the sequence of impacts).
    pub fn max_peak_difference(&self) -> f64 {
        self.rows
            .iter()
            .filter(|r| r.quantity.contains("peak"))
            .filter_map(Row::relative)
            .fold(0.0, |a, b| a.max(b.abs()))
    }

    /// The printed table: quantity, program, OpenSees, relative difference; the run times;
    /// the notes.
    pub fn table(&self) -> String {
        let mut s = String::new();
        let sc = &self.scenario;
        let o = &self.opensees;
        s.push_str(&format!(
            "  program: {} and {} modes, {} at dt = {} s over {} s\n",
            sc.structures[0].modes(),
            sc.structures[1].modes(),
            sc.solver.method.name(),
            sc.solver.dt,
            sc.solver.duration
        ));
        s.push_str(&format!(
            "  OpenSees {}: {} and {} elements, Newmark (average acceleration) at dt = {} s over {} s\n\n",
            o.opensees,
            o.elements.first().copied().unwrap_or(0),
            o.elements.get(1).copied().unwrap_or(0),
            o.dt,
            o.duration
        ));
        s.push_str(&rows_table(&self.rows));
        s.push_str(&format!(
            "\n  run time (both runs): program {:.3} s, OpenSees {:.1} s ({} steps, {} needed the fallback)\n",
            self.program.seconds,
            o.seconds(),
            o.runs.values().map(|r| r.steps).sum::<u64>(),
            o.runs.values().map(|r| r.fallbacks).sum::<u64>()
        ));
        s.push_str(&notes_block(&self.notes));
        s
    }
}

/// The table of compared quantities: quantity, program, OpenSees, relative difference.
pub(super) fn rows_table(rows: &[Row]) -> String {
    let mut s = String::new();
    let width = rows
        .iter()
        .map(|r| r.quantity.chars().count())
        .fold(44, usize::max);
    s.push_str(&format!(
        "  {:<width$} {:>14} {:>14} {:>10}\n",
        "quantity", "program", "OpenSees", "diff"
    ));
    for r in rows {
        let os = r
            .opensees
            .map_or_else(|| "—".to_string(), |v| format!("{v:.6e}"));
        let diff = r
            .relative()
            .map_or_else(|| "—".to_string(), |d| format!("{:+.2} %", 100.0 * d));
        s.push_str(&format!(
            "  {:<width$} {:>14} {:>14} {:>10}\n",
            r.quantity,
            format!("{:.6e}", r.program),
            os,
            diff
        ));
    }
    s
}

/// The notes under a crosscheck's table.
pub(super) fn notes_block(notes: &[String]) -> String {
    let mut s = String::from("\n  what explains the differences:\n");
    for n in notes {
        s.push_str(&format!("  - {n}\n"));
    }
    s
}
