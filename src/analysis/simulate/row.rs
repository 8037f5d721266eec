//! A row of buildings (issue 29): N ≥ 2 structures side by side, each adjacent pair with its
//! own contact. [`simulate_row`] runs the whole row with contact once (one [`System`] of every
//! structure and every pair's levels: a middle building is struck from both sides in the same
//! integration) and once without contact (every structure once: without contact the row's
//! equations are uncoupled), then reports per structure (the quantities of a pair's
//! [`StructureReport`]) and per pair ([`PairReport`]: its contact, every level, the required
//! separation by every rule and code at every level of the pair, its verdict), and the row's
//! verdict: the pair and level that govern.
//!
//! The per-structure and per-level numbers are formed by the same functions as a pair's
//! ([`super::simulate`]); each pair's separation checks are a pair's checks on that pair taken
//! as a scenario of its own ([`Scenario::pair`]), fed with the row's run without contact.

use serde::Serialize;

use super::{
    ContactReport, LevelReport, NoSink, Phase, RunSink, StructureReport, contact_report,
    level_report, level_warnings, no_spectrum, run_phase, run_warnings, separations,
    structure_report,
};
use crate::analysis::level_checks::{Governing, Separations, complete_run_separation};
use crate::input::scenario::Scenario;
use crate::integrate::{SolveError, Stats};
use crate::recording::run_record::{EnergyBalance, RunRecord};

/// One adjacent pair of a row: structures `index` and `index + 1` (0-based, row order).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairReport {
    /// The left structure's index in the row (0-based); the right one is `index + 1`.
    pub index: usize,
    /// The two structures' names, left then right.
    pub between: [String; 2],
    /// The pair's contact law (`hertz`, …).
    pub law: &'static str,
    /// Totals and maxima over the pair's levels.
    pub contact: ContactReport,
    /// The largest approach speed δ̇ at the start of any of the pair's impacts, m/s (0
    /// without impacts).
    pub peak_approach_speed: f64,
    /// Every level of the pair, in the order of its `[[contact]]` table (`peak_displacement`:
    /// left, right).
    pub levels: Vec<LevelReport>,
    /// The required separation by every rule at the pair's main (highest) level, every rule
    /// and code at each of its levels (`levels`) and its verdict (`verdict`), from the row's
    /// run without contact.
    pub separation: Separations,
}

/// One impact of a row.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RowImpact {
    /// The pair (its left structure's index, 0-based).
    pub pair: usize,
    /// The level within the pair (0-based, in the order of its `[[contact]]` table).
    pub level: usize,
    /// The level's height, m.
    pub height: f64,
    /// Start, s.
    pub start: f64,
    /// End, s.
    pub end: f64,
    /// Peak contact force, N.
    pub peak_force: f64,
    /// Impulse ∫F dt, N·s.
    pub impulse: f64,
    /// Largest penetration, m.
    pub max_penetration: f64,
    /// Approach speed δ̇ at the start, m/s.
    pub approach_speed: f64,
}

/// The row's verdict: of every pair's rules at every level, the one with the smallest margin
/// (gap − required).
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct RowVerdict {
    /// The pair that governs (its left structure's index, 0-based), `None` without rules.
    pub pair: Option<usize>,
    /// Its two structures' names.
    pub between: Option<[String; 2]>,
    /// The rule and level that govern, in that pair.
    pub governing: Option<Governing>,
    /// The pairs (left structure's index) where some rule finds the gap too small somewhere.
    pub insufficient_pairs: Vec<usize>,
    /// The pairs that touched in the run with contact.
    pub pounding_pairs: Vec<usize>,
}

/// Everything a row's run produces (summary.json of a row).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowReport {
    /// Scenario title.
    pub title: String,
    /// Every structure, in row order. `peak_displacement` (and `_no_contact`) is at the
    /// structure's highest contact level (of either neighbour).
    pub structures: Vec<StructureReport>,
    /// Every adjacent pair, in row order.
    pub pairs: Vec<PairReport>,
    /// The row's verdict.
    pub verdict: RowVerdict,
    /// Energy balance of the run with contact (the whole row).
    pub energy: EnergyBalance,
    /// Energy balance of the run without contact.
    pub energy_no_contact: EnergyBalance,
    /// Every impact, in time order.
    pub impact_log: Vec<RowImpact>,
    /// Solver counters (with contact).
    #[serde(skip)]
    pub stats: Stats,
    /// Things the user should know.
    pub warnings: Vec<String>,
    /// The run with contact (its `levels` are every pair's, pair by pair).
    #[serde(skip)]
    pub with_contact: RunRecord,
    /// The run without contact.
    #[serde(skip)]
    pub without_contact: RunRecord,
}

/// Run a row (or a pair: the same numbers as [`super::simulate`]'s, arranged per pair) with
/// and without contact. Not self-checked.
pub fn simulate_row(scenario: &Scenario) -> Result<RowReport, SolveError> {
    simulate_row_with(scenario, &mut NoSink)
}

/// [`simulate_row`] reporting progress to `sink` (its history rows are those of the highest
/// level's pair at that level; a row's outputs do not write them).
pub fn simulate_row_with(
    scenario: &Scenario,
    sink: &mut dyn RunSink,
) -> Result<RowReport, SolveError> {
    no_spectrum(scenario)?;
    let system = scenario.system();
    let free = system.without_contact();
    let heights: Vec<f64> = system.levels.iter().map(|l| l.height).collect();
    let pair_of: Vec<usize> = system.levels.iter().map(|l| l.pair).collect();
    let interval = scenario.output_interval;
    let stations = Some(scenario.floor_stations);
    let (with, stats) = run_phase(
        &system,
        &scenario.solver,
        (&heights, &pair_of),
        interval,
        sink,
        Phase::WithContact,
        stations,
    )?;
    let (without, _) = run_phase(
        &free,
        &scenario.solver,
        (&heights, &pair_of),
        interval,
        sink,
        Phase::WithoutContact,
        stations,
    )?;
    let n = system.structures.len();
    // each structure's headline level: its highest contact level with either neighbour
    let structures: Vec<StructureReport> = (0..n)
        .map(|i| {
            let mine = |k: &usize| pair_of[*k] == i || pair_of[*k] + 1 == i;
            let main = (0..heights.len())
                .filter(mine)
                .fold(None, |best: Option<usize>, k| match best {
                    Some(b) if heights[k] <= heights[b] => Some(b),
                    _ => Some(k),
                });
            let peak = |r: &RunRecord| {
                main.map_or(0.0, |k| {
                    if pair_of[k] == i {
                        r.levels[k].peak_w1
                    } else {
                        r.levels[k].peak_w2
                    }
                })
            };
            let impacts: Vec<_> = (with.impacts.iter())
                .filter(|x| mine(&x.level))
                .copied()
                .collect();
            structure_report(
                &scenario.structures[i],
                i,
                &system.structures[i],
                (&with, &without),
                &impacts,
                &heights,
                [peak(&with), peak(&without)],
            )
        })
        .collect();
    let mut warnings = scenario.warnings.clone();
    let mut pairs = Vec::with_capacity(n - 1);
    let mut first = 0;
    for p in 0..n - 1 {
        let count = pair_of.iter().filter(|&&q| q == p).count();
        let range = first..first + count;
        first += count;
        let levels: Vec<LevelReport> = range
            .clone()
            .map(|k| level_report(&system.levels[k], &with.levels[k], &without.levels[k]))
            .collect();
        // the pair as a scenario of its own, with the row's run without contact at its levels
        let pair_scenario = scenario.pair(p);
        let models = [
            system.structures[p].clone(),
            system.structures[p + 1].clone(),
        ];
        let record = pair_record(&without, range.clone());
        let mut separation = separations(&models, &record);
        if let Err(e) = complete_run_separation(&pair_scenario, &models, &record, &mut separation) {
            warnings.push(format!(
                "pair \"{}\"–\"{}\": separation.codes and separation.levels left out: {e}",
                scenario.structures[p].name(),
                scenario.structures[p + 1].name()
            ));
        }
        let peak_approach_speed = (with.impacts.iter())
            .filter(|x| range.contains(&x.level))
            .map(|x| x.approach_speed)
            .fold(0.0, f64::max);
        pairs.push(PairReport {
            index: p,
            between: [p, p + 1].map(|i| scenario.structures[i].name().to_string()),
            law: pair_scenario.contact.law.name(),
            contact: contact_report(&levels),
            peak_approach_speed,
            levels,
            separation,
        });
    }
    for (s, i) in structures.iter().zip(0..) {
        let h = (0..heights.len())
            .filter(|&k| pair_of[k] == i || pair_of[k] + 1 == i)
            .map(|k| heights[k])
            .fold(0.0, f64::max);
        super::drift_warning(s, h, &mut warnings);
    }
    for p in &pairs {
        level_warnings(&p.levels, &mut warnings);
    }
    run_warnings(scenario, &stats, &with, &without, &mut warnings);
    let impact_log = with
        .impacts
        .iter()
        .map(|x| {
            let p = pair_of[x.level];
            let first = pair_of.iter().position(|&q| q == p).unwrap_or(0);
            RowImpact {
                pair: p,
                level: x.level - first,
                height: heights[x.level],
                start: x.start,
                end: x.end,
                peak_force: x.peak_force,
                impulse: x.impulse,
                max_penetration: x.max_penetration,
                approach_speed: x.approach_speed,
            }
        })
        .collect();
    Ok(RowReport {
        title: scenario.title.clone(),
        verdict: row_verdict(&pairs),
        structures,
        pairs,
        energy: with.energy,
        energy_no_contact: without.energy,
        impact_log,
        stats,
        warnings,
        with_contact: with,
        without_contact: without,
    })
}

/// The run without contact at the levels `range` of one pair, as a pair's run record: those
/// levels, and the peaks at the highest of them (the first on a tie, as the recorder picks
/// its main level).
fn pair_record(without: &RunRecord, range: std::ops::Range<usize>) -> RunRecord {
    let levels = without.levels[range].to_vec();
    let main = (0..levels.len()).fold(0, |best, k| {
        if levels[k].height > levels[best].height {
            k
        } else {
            best
        }
    });
    let (peak, max_closing) = levels
        .get(main)
        .map_or(([0.0; 2], 0.0), |m| ([m.peak_w1, m.peak_w2], m.max_closing));
    RunRecord {
        levels,
        peak,
        max_closing,
        impacts: Vec::new(),
        history: Default::default(),
        energy: without.energy,
        steps: without.steps,
        floors: Vec::new(),
        storeys: Vec::new(),
    }
}

/// The row's verdict from every pair's.
fn row_verdict(pairs: &[PairReport]) -> RowVerdict {
    let mut v = RowVerdict::default();
    for p in pairs {
        if p.separation.verdict.insufficient > 0 {
            v.insufficient_pairs.push(p.index);
        }
        if p.contact.impacts > 0 {
            v.pounding_pairs.push(p.index);
        }
        if let Some(g) = &p.separation.verdict.governing
            && v.governing.as_ref().is_none_or(|m| g.margin < m.margin)
        {
            v.governing = Some(g.clone());
            v.pair = Some(p.index);
            v.between = Some(p.between.clone());
        }
    }
    v
}
