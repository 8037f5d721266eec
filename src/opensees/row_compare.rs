//! `pounding crosscheck` of a row of buildings (issue 29): the row's script
//! ([`super::row::row_script`]) run with a local `openseespy`, the program's row run
//! ([`simulate_row`]), and their numbers side by side per structure and per pair, with the
//! relative differences and what explains them — as a pair's crosscheck
//! ([`super::compare::crosscheck`]) does.

use std::collections::BTreeMap;
use std::time::Instant;

use serde::Deserialize;

use super::compare::{
    CrosscheckError, CrosscheckOptions, in_dir, notes_block, notes_for, prepared, probe,
    rows_table, run_script_text,
};
use super::results::{OsContact, OsLevel, OsSeparation, OsStructure, Row, RunInfo};
use super::storeys::storey_rows_of;
use crate::analysis::simulate::{RowReport, simulate_row};
use crate::input::scenario::Scenario;

/// A pair's numbers in a row's OpenSees results.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct OsPair {
    /// Its left structure's index (0-based).
    pub index: usize,
    /// The two names, left then right.
    pub between: [String; 2],
    /// Its levels, in the order of its `[[contact]]` table (`peak_displacement`: left,
    /// right).
    pub levels: Vec<OsLevel>,
    /// Totals over its levels (with contact).
    #[serde(default)]
    pub contact: Option<OsContact>,
    /// Its time-history separation at its highest level.
    pub separation: OsSeparation,
}

/// What a row's script prints.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct RowOpenSeesResults {
    /// OpenSees' version.
    pub opensees: String,
    /// Step, s.
    pub dt: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Elements per structure (floors for a shear building).
    pub elements: Vec<usize>,
    /// `contact` and/or `free`.
    pub runs: BTreeMap<String, RunInfo>,
    /// Every structure, in row order (`peak_displacement` at its highest contact level with
    /// either neighbour, as a row's summary.json has it).
    pub structures: Vec<OsStructure>,
    /// Every adjacent pair, in row order.
    pub pairs: Vec<OsPair>,
}

impl RowOpenSeesResults {
    /// Wall time of both runs, s.
    pub fn seconds(&self) -> f64 {
        self.runs.values().map(|r| r.seconds).sum()
    }
}

/// Parse a row script's JSON output (`path` names it in the error).
pub fn parse_row_results(text: &str, path: &str) -> Result<RowOpenSeesResults, CrosscheckError> {
    serde_json::from_str(text).map_err(|e| CrosscheckError::Parse {
        path: path.to_string(),
        detail: e.to_string(),
    })
}

/// Write a row's `script` into `dir`, run it with `python` (`extra` arguments after the
/// script's own) and read its results.
pub fn run_row_script(
    python: &str,
    script: &str,
    dir: &std::path::Path,
    extra: &[String],
) -> Result<RowOpenSeesResults, CrosscheckError> {
    let (text, path) = run_script_text(python, script, dir, extra)?;
    parse_row_results(&text, &path)
}

/// A row crosscheck's outcome.
#[derive(Debug, Clone)]
pub struct RowCrosscheck {
    /// The scenario as the program ran it (modes, method, duration).
    pub scenario: Scenario,
    /// The program's row run (both runs, not self-checked).
    pub program: RowReport,
    /// Wall time of the program's two runs, s.
    pub program_seconds: f64,
    /// OpenSees' numbers.
    pub opensees: RowOpenSeesResults,
    /// Quantity by quantity: per structure, then per pair.
    pub rows: Vec<Row>,
    /// What explains the differences.
    pub notes: Vec<String>,
}

/// The quantities compared, per structure (named) — the peaks at its headline height with and
/// without contact, at every tracked height (a building's floors, a cantilever's contact
/// heights) when there are several, every storey's — and per pair (`A–B`): the peak contact
/// force (and per level when it has several), penetration, impacts, contact time and the
/// time-history separation.
pub fn row_rows(r: &RowReport, o: &RowOpenSeesResults) -> Vec<Row> {
    let mut rows = Vec::new();
    let row = |q: String, program: f64, opensees: Option<f64>| Row {
        quantity: q,
        program,
        opensees,
        scale: 0.0,
    };
    for (s, st) in r.structures.iter().enumerate() {
        let os = o.structures.get(s);
        let name = &st.name;
        rows.push(row(
            format!("{name}: peak w(h) with contact [m]"),
            st.peak_displacement,
            os.and_then(|x| x.peak_displacement),
        ));
        rows.push(row(
            format!("{name}: peak w(h) without contact [m]"),
            st.peak_displacement_no_contact,
            os.and_then(|x| x.peak_displacement_no_contact),
        ));
        let Some(os) = os.filter(|x| x.heights.len() > 1) else {
            continue;
        };
        // the program's peaks at OpenSees' tracked heights (its floors and stations)
        for x in &os.heights {
            let Some(f) = (st.floors.iter()).find(|f| (f.height - x.height).abs() <= 1e-9) else {
                continue;
            };
            rows.push(row(
                format!("  {name}: w at {} m with contact [m]", x.height),
                f.peak_displacement,
                x.peak_displacement,
            ));
            rows.push(row(
                format!("  {name}: w at {} m without contact [m]", x.height),
                f.peak_displacement_no_contact,
                x.peak_displacement_no_contact,
            ));
        }
    }
    let names: Vec<String> = r.structures.iter().map(|s| s.name.clone()).collect();
    rows.extend(storey_rows_of(
        &r.structures,
        r.energy.input,
        &o.structures,
        &|s| names[s].clone(),
    ));
    for (p, pr) in r.pairs.iter().enumerate() {
        let op = o.pairs.get(p);
        let oc = op.and_then(|x| x.contact.as_ref());
        let pair = format!("{}–{}", pr.between[0], pr.between[1]);
        rows.push(row(
            format!("{pair}: peak contact force [N]"),
            pr.contact.peak_force,
            oc.map(|c| c.peak_force),
        ));
        if pr.levels.len() > 1 {
            for (k, l) in pr.levels.iter().enumerate() {
                rows.push(row(
                    format!("  {pair}: peak force at {} m [N]", l.height),
                    l.peak_force,
                    op.and_then(|x| x.levels.get(k)).and_then(|x| x.peak_force),
                ));
            }
        }
        rows.push(row(
            format!("{pair}: max penetration [m]"),
            pr.contact.max_penetration,
            oc.map(|c| c.max_penetration),
        ));
        rows.push(row(
            format!("{pair}: impacts"),
            pr.contact.impacts as f64,
            oc.map(|c| c.impacts as f64),
        ));
        rows.push(row(
            format!("{pair}: contact time [s]"),
            pr.contact.contact_time,
            oc.map(|c| c.contact_time),
        ));
        rows.push(row(
            format!("{pair}: required separation, time history [m]"),
            pr.separation.time_history,
            op.and_then(|x| x.separation.time_history),
        ));
    }
    rows
}

/// Export a row `scenario` (named `source`), run it with `python`'s openseespy and the
/// program's row run, and compare.
pub fn crosscheck_row(
    scenario: &Scenario,
    source: &str,
    opts: &CrosscheckOptions,
    python: &str,
) -> Result<RowCrosscheck, CrosscheckError> {
    let (sc, mut notes) = prepared(scenario, opts)?;
    let script = super::row::row_script(&sc, &opts.export, source)?;
    probe(python)?;
    let opensees = in_dir(&opts.keep, |dir| run_row_script(python, &script, dir, &[]))?;
    let start = Instant::now();
    let program = simulate_row(&sc)?;
    let program_seconds = start.elapsed().as_secs_f64();
    let rows = row_rows(&program, &opensees);
    notes.extend(notes_for(&sc, &opensees.elements, opensees.dt));
    Ok(RowCrosscheck {
        scenario: sc,
        program,
        program_seconds,
        opensees,
        rows,
        notes,
    })
}

impl RowCrosscheck {
    /// The largest |relative difference| over the peaks and peak forces (not impacts, contact
    /// time or penetration, which follow the sequence of impacts).
    pub fn max_peak_difference(&self) -> f64 {
        self.rows
            .iter()
            .filter(|r| r.quantity.contains("peak"))
            .filter_map(Row::relative)
            .fold(0.0, |a, b| a.max(b.abs()))
    }

    /// The printed table: the two models, quantity, program, OpenSees, relative difference;
    /// the run times; the notes.
    pub fn table(&self) -> String {
        let sc = &self.scenario;
        let o = &self.opensees;
        let list = |v: Vec<String>| v.join(", ");
        let mut s = format!(
            "  program: {} modes ({}), {} at dt = {} s over {} s\n",
            list(
                sc.structures
                    .iter()
                    .map(|x| x.modes().to_string())
                    .collect()
            ),
            list(sc.structures.iter().map(|x| x.name().to_string()).collect()),
            sc.solver.method.name(),
            sc.solver.dt,
            sc.solver.duration
        );
        s.push_str(&format!(
            "  OpenSees {}: {} elements, Newmark (average acceleration) at dt = {} s over {} s\n\n",
            o.opensees,
            list(o.elements.iter().map(usize::to_string).collect()),
            o.dt,
            o.duration
        ));
        s.push_str(&rows_table(&self.rows));
        s.push_str(&format!(
            "\n  run time (both runs): program {:.3} s, OpenSees {:.1} s ({} steps, {} needed the fallback)\n",
            self.program_seconds,
            o.seconds(),
            o.runs.values().map(|r| r.steps).sum::<u64>(),
            o.runs.values().map(|r| r.fallbacks).sum::<u64>()
        ));
        s.push_str(&notes_block(&self.notes));
        s
    }
}
