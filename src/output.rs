//! Output files (docs/model.md §6): `summary.json`, `history.csv`, `impacts.csv`. Every file is written
//! to a temporary file in the target directory and renamed into place, so a reader never sees a
//! half-written file; `summary.json` is written last, so its presence means the run completed.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::integrate::Method;
use crate::scenario::Scenario;
use crate::simulate::Report;

/// Why an output could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// File-system error, with the path concerned.
    #[error("cannot write {path}: {source}")]
    Io {
        /// Path.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// Serialisation failure.
    #[error("cannot encode {path}: {message}")]
    Encode {
        /// Path.
        path: PathBuf,
        /// Cause.
        message: String,
    },
}

/// A temporary file in `dir` named `<prefix>XXXXXX<suffix>`, for writing and then renaming into
/// place, with the permissions an ordinary new file would get (tempfile's default is
/// owner-only, which the rename would carry over).
pub fn temp_file(
    dir: &Path,
    prefix: impl AsRef<std::ffi::OsStr>,
    suffix: &str,
) -> std::io::Result<tempfile::NamedTempFile> {
    let mut b = tempfile::Builder::new();
    b.prefix(prefix.as_ref()).suffix(suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o666));
    }
    b.tempfile_in(dir)
}

/// Write `bytes` to `path` atomically (temporary file in the same directory, then rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let io = |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    };
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut tmp = temp_file(dir, ".pounding-", ".tmp").map_err(io)?;
    tmp.write_all(bytes).map_err(io)?;
    tmp.as_file().sync_all().map_err(io)?;
    tmp.persist(path).map_err(|e| io(e.error))?;
    Ok(())
}

/// Solver facts recorded in the summary.
#[derive(Debug, Serialize)]
struct SolverInfo {
    method: &'static str,
    dt: f64,
    duration: f64,
    output_interval: f64,
    steps: usize,
    max_contact_omega_dt: f64,
    /// Relative and absolute (m) tolerances: only for `adaptive`.
    #[serde(skip_serializing_if = "Option::is_none")]
    rtol: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    atol: Option<f64>,
    /// What `dt` means for this method.
    dt_meaning: &'static str,
    /// Steps rejected by error control, and contact events located (`adaptive`).
    rejected_steps: usize,
    events: usize,
    /// Relative energy-balance errors of the runs with and without contact.
    energy_relative_error: f64,
    energy_relative_error_no_contact: f64,
}

#[derive(Debug, Serialize)]
struct Summary<'a> {
    #[serde(flatten)]
    report: &'a Report,
    contact_law: &'static str,
    solver: SolverInfo,
}

/// The summary as JSON text (docs/model.md §6 fields plus levels, energy, impacts, warnings, solver).
pub fn summary_json(scenario: &Scenario, report: &Report) -> Result<String, String> {
    let adaptive = scenario.solver.method == Method::Adaptive;
    let s = Summary {
        report,
        contact_law: scenario.contact.law.name(),
        solver: SolverInfo {
            method: scenario.solver.method.name(),
            dt: scenario.solver.dt,
            duration: scenario.solver.duration,
            output_interval: scenario.output_interval,
            steps: report.stats.steps,
            max_contact_omega_dt: report.stats.max_contact_omega_dt,
            rtol: adaptive.then_some(scenario.solver.rtol),
            atol: adaptive.then_some(scenario.solver.atol),
            dt_meaning: match scenario.solver.method {
                Method::Rk4 => "fixed step",
                Method::ExactModal => "base step (contact sub-steps below it)",
                Method::Adaptive => "largest step",
            },
            rejected_steps: report.stats.rejected,
            events: report.stats.events,
            energy_relative_error: report.energy.relative_error,
            energy_relative_error_no_contact: report.energy_no_contact.relative_error,
        },
    };
    serde_json::to_string_pretty(&s).map_err(|e| e.to_string())
}

/// `history.csv`: `t,w1,w2,force,w1_free,w2_free` and, with several levels, `force_1 … force_k`
/// (`force` is then their sum). Displacements at the main contact height, m; forces, N.
pub fn history_csv(report: &Report) -> String {
    let h = &report.with_contact.history;
    let f = &report.without_contact.history;
    let nl = h.force.len();
    let mut out = String::with_capacity(h.t.len() * (60 + 20 * nl));
    out.push_str("t,w1,w2,force,w1_free,w2_free");
    if nl > 1 {
        for k in 1..=nl {
            let _ = write!(out, ",force_{k}");
        }
    }
    out.push('\n');
    for i in 0..h.t.len() {
        let total: f64 = h.force.iter().map(|c| c[i]).sum();
        let _ = write!(
            out,
            "{},{},{},{},{},{}",
            h.t[i],
            h.w1[i],
            h.w2[i],
            total,
            f.w1.get(i).copied().unwrap_or(f64::NAN),
            f.w2.get(i).copied().unwrap_or(f64::NAN)
        );
        if nl > 1 {
            for c in &h.force {
                let _ = write!(out, ",{}", c[i]);
            }
        }
        out.push('\n');
    }
    out
}

/// `impacts.csv`: one row per contact episode.
pub fn impacts_csv(report: &Report) -> String {
    let mut out = String::from(
        "level,height,start,end,duration,peak_force,impulse,max_penetration,approach_speed\n",
    );
    for i in &report.impact_log {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{}",
            i.level + 1,
            report.levels[i.level].height,
            i.start,
            i.end,
            i.end - i.start,
            i.peak_force,
            i.impulse,
            i.max_penetration,
            i.approach_speed
        );
    }
    out
}

/// Write `history.csv`, `impacts.csv` and, last, `summary.json` into `dir` (created if needed).
/// Returns the paths written.
pub fn write_run(
    dir: &Path,
    scenario: &Scenario,
    report: &Report,
) -> Result<Vec<PathBuf>, OutputError> {
    std::fs::create_dir_all(dir).map_err(|e| OutputError::Io {
        path: dir.to_path_buf(),
        source: e,
    })?;
    let history = dir.join("history.csv");
    write_atomic(&history, history_csv(report).as_bytes())?;
    let impacts = dir.join("impacts.csv");
    write_atomic(&impacts, impacts_csv(report).as_bytes())?;
    let summary = dir.join("summary.json");
    let json = summary_json(scenario, report).map_err(|message| OutputError::Encode {
        path: summary.clone(),
        message,
    })?;
    write_atomic(&summary, json.as_bytes())?;
    Ok(vec![summary, history, impacts])
}
