//! A pair's output files (docs/model.md §6): `summary.json`, `history.csv`, `impacts.csv` —
//! their contents, by the SPEC's output contract. They are written by the one writer of a
//! run's files, a pair's or a row's (`output::writer::RunWriter`: temporary files renamed
//! into place, `summary.json` last).

use std::fmt::Write as _;

use serde::Serialize;

use crate::analysis::simulate::Report;
use crate::input::scenario::Scenario;
use crate::integrate::Method;
use crate::output::csv::{push_field, push_number};

/// Solver facts recorded in the summary.
#[derive(Debug, Serialize)]
pub(crate) struct SolverInfo {
    method: &'static str,
    dt: f64,
    duration: f64,
    output_interval: f64,
    steps: usize,
    max_contact_omega_dt: f64,
    /// Relative and absolute (m) tolerances: for the methods that read them (`adaptive`;
    /// `exact-modal`'s contact steps and yielding sub-steps), not for `rk4`.
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
    /// What shook the structures, with a record's scaling ([`super::ground_section`]).
    ground_motion: serde_json::Value,
    /// Keys the scenario left out and the defaults used for them (`key = value`).
    defaults_applied: &'a [String],
    /// A suite's own section (`output::writer::RunWriter::with_suite`); absent for one record.
    #[serde(skip_serializing_if = "Option::is_none")]
    suite: Option<&'a serde_json::Value>,
}

/// The summary as JSON text (docs/model.md §6 fields plus levels, energy, impacts, warnings,
/// solver, defaults applied).
pub fn summary_json(scenario: &Scenario, report: &Report) -> Result<String, String> {
    summary_json_with(scenario, report, None)
}

/// [`summary_json`] with a suite's section `suite` last (the top-level keys are then the
/// run of the suite's representative record, `scenario`).
pub fn summary_json_with(
    scenario: &Scenario,
    report: &Report,
    suite: Option<&serde_json::Value>,
) -> Result<String, String> {
    let s = Summary {
        report,
        contact_law: scenario.contact.law.name(),
        solver: SolverInfo::new(
            scenario,
            &report.stats,
            (&report.energy, &report.energy_no_contact),
        ),
        ground_motion: super::ground_section::ground_section(&scenario.ground_motion),
        defaults_applied: &scenario.defaults_applied,
        suite,
    };
    serde_json::to_string_pretty(&s).map_err(|e| e.to_string())
}

impl SolverInfo {
    /// The solver's facts of a run of `scenario` with its counters and energy balances
    /// (with, without contact).
    pub(crate) fn new(
        scenario: &Scenario,
        stats: &crate::integrate::Stats,
        (energy, energy_no_contact): (
            &crate::recording::run_record::EnergyBalance,
            &crate::recording::run_record::EnergyBalance,
        ),
    ) -> SolverInfo {
        let tolerant = scenario.solver.method != Method::Rk4;
        SolverInfo {
            method: scenario.solver.method.name(),
            dt: scenario.solver.dt,
            duration: scenario.solver.duration,
            output_interval: scenario.output_interval,
            steps: stats.steps,
            max_contact_omega_dt: stats.max_contact_omega_dt,
            rtol: tolerant.then_some(scenario.solver.rtol),
            atol: tolerant.then_some(scenario.solver.atol),
            dt_meaning: scenario.solver.method.dt_meaning(),
            rejected_steps: stats.rejected,
            events: stats.events,
            energy_relative_error: energy.relative_error,
            energy_relative_error_no_contact: energy_no_contact.relative_error,
        }
    }
}

/// The header line of `history.csv` for `levels` contact levels (without the newline).
pub fn history_header(levels: usize) -> String {
    let mut out = String::from("t,w1,w2,force,w1_free,w2_free");
    if levels > 1 {
        for k in 1..=levels {
            let _ = write!(out, ",force_{k}");
        }
    }
    out
}

/// One row of `history.csv` (with its newline) appended to `out`.
pub(crate) fn history_row(out: &mut Vec<u8>, t: f64, w: [f64; 2], forces: &[f64], free: [f64; 2]) {
    let total: f64 = forces.iter().sum();
    push_number(out, t);
    for v in [w[0], w[1], total, free[0], free[1]] {
        push_field(out, v);
    }
    if forces.len() > 1 {
        for &f in forces {
            push_field(out, f);
        }
    }
    out.push(b'\n');
}

/// `history.csv` from a report's in-memory history: `t,w1,w2,force,w1_free,w2_free` and, with
/// several levels, `force_1 … force_k` (`force` is then their sum). Displacements at the main
/// contact height, m; forces, N. This is exactly what `output::writer::RunWriter` streams when the history
/// holds every sample (`History::stride == 1`, runs of at most
/// [`crate::recording::history::MAX_KEPT_SAMPLES`] samples); for longer runs the in-memory history is an
/// envelope and only the streamed file has every sample.
pub fn history_csv(report: &Report) -> String {
    let h = &report.with_contact.history;
    let f = &report.without_contact.history;
    let nl = h.force.len();
    let mut out = Vec::with_capacity(h.t.len() * (60 + 20 * nl));
    out.extend_from_slice(history_header(nl).as_bytes());
    out.push(b'\n');
    let mut forces = vec![0.0; nl];
    for i in 0..h.t.len() {
        for (x, c) in forces.iter_mut().zip(&h.force) {
            *x = c[i];
        }
        let free = [
            f.w1.get(i).copied().unwrap_or(f64::NAN),
            f.w2.get(i).copied().unwrap_or(f64::NAN),
        ];
        history_row(&mut out, h.t[i], [h.w1[i], h.w2[i]], &forces, free);
    }
    // (only ASCII digits, signs, letters and commas were written)
    String::from_utf8(out).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

/// `impacts.csv`: one row per contact episode.
pub fn impacts_csv(report: &Report) -> String {
    let mut out = String::from(
        "level,height,start,end,duration,peak_force,impulse,max_penetration,approach_speed\n",
    );
    let mut row = Vec::with_capacity(200);
    for i in &report.impact_log {
        row.clear();
        row.extend_from_slice((i.level + 1).to_string().as_bytes());
        for v in [
            report.levels[i.level].height,
            i.start,
            i.end,
            i.end - i.start,
            i.peak_force,
            i.impulse,
            i.max_penetration,
            i.approach_speed,
        ] {
            push_field(&mut row, v);
        }
        row.push(b'\n');
        out.push_str(&String::from_utf8_lossy(&row));
    }
    out
}

/// The pictures `pounding run` draws into its directory (a pair's or a row's: the same
/// names): removed by the writer's `finish` when a run draws none, so that no stale picture
/// sits beside a new summary.
pub const PICTURE_FILES: [&str; 6] = [
    "history.png",
    "history.svg",
    "envelopes.png",
    "envelopes.svg",
    "hysteresis.png",
    "hysteresis.svg",
];

/// Draws a run's pictures into the directory it is given; returns the files written.
pub type DrawPictures<'a> =
    dyn FnOnce(&std::path::Path) -> Result<Vec<std::path::PathBuf>, String> + 'a;

/// Called with each file of a run once it is complete and in place.
pub type WrittenHook = dyn FnMut(&std::path::Path);

/// One column of a table handed to another program (the Python package's arrays): whole
/// numbers, numbers, or text.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// Whole numbers (a count, an index).
    Int(Vec<i64>),
    /// Numbers.
    Float(Vec<f64>),
    /// Text.
    Text(Vec<String>),
}

/// The columns of `impacts.csv` ([`impacts_csv`]), by its header names: `level` (1-based)
/// whole numbers, the rest the same numbers the file holds.
pub fn impact_columns(report: &Report) -> Vec<(&'static str, Column)> {
    let log = &report.impact_log;
    let f = |g: &dyn Fn(&crate::recording::run_record::Impact) -> f64| {
        Column::Float(log.iter().map(g).collect())
    };
    vec![
        (
            "level",
            Column::Int(log.iter().map(|i| i.level as i64 + 1).collect()),
        ),
        ("height", f(&|i| report.levels[i.level].height)),
        ("start", f(&|i| i.start)),
        ("end", f(&|i| i.end)),
        ("duration", f(&|i| i.end - i.start)),
        ("peak_force", f(&|i| i.peak_force)),
        ("impulse", f(&|i| i.impulse)),
        ("max_penetration", f(&|i| i.max_penetration)),
        ("approach_speed", f(&|i| i.approach_speed)),
    ]
}

/// The floor columns of a run of `scenario` (`floors.csv` without `t` and the `_free`
/// copies): the displacement and absolute acceleration at each station that
/// `scenario.floor_stations` keeps ([`FloorStations`](crate::recording::stations::FloorStations); names of
/// [`crate::recording::floor_response::FloorRecorder::columns`]).
pub fn floor_columns(scenario: &Scenario) -> Vec<String> {
    let heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let system = scenario.system();
    let floors = crate::recording::floor_response::FloorRecorder::new(
        &system,
        &heights,
        scenario.output_interval,
    );
    let all = floors.columns();
    match scenario
        .floor_stations
        .selection(&system, &floors, &heights)
    {
        None => all,
        Some(keep) => keep.iter().filter_map(|&i| all.get(i).cloned()).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every finite `f64` written by [`push_number`] reads back bit for bit (the text is
    /// the shortest that does: zmij's guarantee, checked here on the corners — subnormals,
    /// the extremes, powers of ten at the switch to exponent notation, −0 — and on 10⁵
    /// values spread over every exponent by a fixed xorshift sequence); NaN and the infinities
    /// are written as Rust writes them, which `str::parse` reads.
    #[test]
    fn numbers_read_back_exactly() {
        let mut values = vec![
            0.0,
            -0.0,
            1.0,
            0.1,
            1e-5,
            9.99e-6,
            1e16,
            9.999_999_999_999_998e15,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            0.1 + 0.2,
            2.808e10,
        ];
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = f64::from_bits(x);
            if v.is_finite() {
                values.push(v);
            }
        }
        let mut out = Vec::new();
        for v in values {
            out.clear();
            push_number(&mut out, v);
            let text = std::str::from_utf8(&out).unwrap();
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                v.to_bits(),
                "{text}"
            );
        }
        for (v, text) in [
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
            (-f64::INFINITY, "-inf"),
        ] {
            out.clear();
            push_number(&mut out, v);
            assert_eq!(std::str::from_utf8(&out).unwrap(), text);
            let back: f64 = text.parse().unwrap();
            assert!(back.is_nan() == v.is_nan() && (v.is_nan() || back == v));
        }
    }
}
