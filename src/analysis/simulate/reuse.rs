//! Runs without contact that need not be integrated: the one a run with contact that never
//! touched already is ([`free_run_of`]), and the one another scenario with the same
//! structures, ground motion and solver settings already computed ([`FreeRunKey`], what a
//! sweep over contact keys caches).

use std::hash::{Hash, Hasher};
use std::sync::Arc;

use crate::input::scenario::Scenario;
use crate::integrate::{Method, Stats};
use crate::model::ground_motion::GroundMotion;
use crate::model::ground_motion::record::Record;
use crate::recording::run_record::RunRecord;

/// The run without contact of a scenario whose run with contact (`with`, its solver counters
/// `stats`) never touched, or `None` when it may have.
///
/// Such a run with contact is the run without contact, step for step: the integrator took
/// exactly the steps and did exactly the arithmetic of the free system (a contact force of 0 is
/// never added where no level touches), so its record is the free run's, bit for bit, but for
/// the contact columns of its history (one per level, all zero; a free run has none) and the
/// stored contact energy, a sum over no levels there (−0.0, which summary.json writes as
/// such). Whether it touched is read from the integrator's own counters, not from the
/// recorded closing, which is sampled: for `exact-modal` with elastic structures, no contact
/// step (`evaluations == 0`) and no located onset (`events == 0`) mean that every step was
/// the closed-form free flight of the free system (a step whose onset search found nothing
/// is taken again as that free flight).
///
/// Not the other methods, whose run without contact is always integrated (the tests compare
/// both ways): `adaptive` takes a collocation step wherever its bound cannot rule a contact
/// out, and such a step with zero contact force keeps the free trajectory but tallies the
/// input and damping energy in another order (last digits apart at a near miss), which no
/// counter tells from a free step; `rk4` evaluates the contact force at its stages' predicted
/// states, which the recorder never sees (a stage can touch while no step end does); yielding
/// storeys evaluate the contact at the unobserved states of their sub-steps likewise.
pub fn free_run_of(scenario: &Scenario, stats: &Stats, with: &RunRecord) -> Option<RunRecord> {
    if !untouched(scenario, stats, with) {
        return None;
    }
    let mut free = with.clone();
    free.history.force = Vec::new();
    // the contact energy of a system without levels: an empty sum, as the recorder forms it
    free.energy.contact_stored = std::iter::empty::<f64>().sum();
    Some(free)
}

/// Whether a run with contact (`with`, its solver counters `stats`) of `scenario` never
/// touched and so did only the closed-form free flight of the free system (see
/// [`free_run_of`]): `exact-modal` on elastic structures, no contact step, no located onset.
/// Such a run reads no tolerance at all (only the contact steps and the storeys' sub-steps
/// do), so the self-check's run with contact at `rtol/100` would repeat it bit for bit
/// (tested: `the_check_of_a_run_that_never_touched_is_the_run`).
pub(super) fn untouched(scenario: &Scenario, stats: &Stats, with: &RunRecord) -> bool {
    !scenario.has_hysteresis()
        && with.impacts.is_empty()
        && scenario.solver.method == Method::ExactModal
        && stats.evaluations == 0
        && stats.events == 0
        && stats.max_contact_omega_dt == 0.0
}

/// The runs without contact of one scenario, to take for another that differs only in its
/// contact (see [`FreeRunKey`]): the result's, and the self-check's when it integrates its own
/// (`None`: it reuses the result's, [`super::free_run_is_exact`], or no check was run).
#[derive(Debug, Clone, PartialEq)]
pub struct FreeRuns {
    /// The run without contact of the result.
    pub run: RunRecord,
    /// The self-check's run without contact, when it has its own.
    pub check: Option<RunRecord>,
}

impl FreeRuns {
    /// Approximate heap size, bytes (what a cache of them bounds).
    pub fn bytes(&self) -> usize {
        FreeRuns::record_bytes(&self.run) + self.check.as_ref().map_or(0, FreeRuns::record_bytes)
    }

    /// Approximate heap size of one run record, bytes.
    pub(super) fn record_bytes(r: &RunRecord) -> usize {
        let h = &r.history;
        8 * (h.t.len() + h.w1.len() + h.w2.len())
            + 8 * h.force.iter().map(Vec::len).sum::<usize>()
            + 64 * r.levels.len()
            + 128 * r.floors.iter().map(Vec::len).sum::<usize>()
            + 64 * r.storeys.len()
            + 256
    }
}

/// What a scenario's run without contact depends on, exactly: the structures as given, the
/// ground motion (a record by its samples), the solver settings, the output interval and
/// floor stations, the contact levels' heights (the run records the closing at each) and
/// whether it is self-checked. Two scenarios with equal keys have bit-identical runs without
/// contact, whatever their contact laws, stiffnesses, gaps and restitutions. `hash` is for a
/// hash map; equality compares everything.
#[derive(Debug, Clone)]
pub struct FreeRunKey {
    /// A hash of everything below.
    pub hash: u64,
    text: String,
    record: Option<Arc<Record>>,
}

impl PartialEq for FreeRunKey {
    fn eq(&self, other: &FreeRunKey) -> bool {
        self.hash == other.hash
            && self.text == other.text
            && match (&self.record, &other.record) {
                (None, None) => true,
                (Some(a), Some(b)) => {
                    Arc::ptr_eq(a, b)
                        || (a.dt.to_bits() == b.dt.to_bits()
                            && a.accel.len() == b.accel.len()
                            && a.accel
                                .iter()
                                .zip(&b.accel)
                                .all(|(x, y)| x.to_bits() == y.to_bits()))
                }
                _ => false,
            }
    }
}

impl FreeRunKey {
    /// The key of `scenario`'s run without contact (with its self-check's if `check`; with
    /// the floor responses if `floors`, as [`super::simulate_reusing`] takes them), or `None`
    /// for what is not a single run of a pair (a row: [`FreeRunKey::of_row`]; a suite, a
    /// design spectrum).
    pub fn of(scenario: &Scenario, check: bool, floors: bool) -> Option<FreeRunKey> {
        if scenario.is_row() || scenario.suite.is_some() || scenario.design.spectrum.is_some() {
            return None;
        }
        let heights: Vec<u64> = scenario
            .contact
            .levels
            .iter()
            .map(|l| l.height.to_bits())
            .collect();
        Some(FreeRunKey::with_levels(
            scenario,
            &format!("{heights:?}"),
            check,
            floors,
        ))
    }

    /// The key of a row's run without contact (issue 29; with its self-check's if `check`,
    /// as [`super::simulate_row_reusing`] takes them: a row's result always records its
    /// floors), or `None` for a suite or a design spectrum. Besides a pair's key it holds
    /// every pair's level heights, pair by pair (the run records the closing at each, and each
    /// structure's headline height is its highest level with either neighbour).
    pub fn of_row(scenario: &Scenario, check: bool) -> Option<FreeRunKey> {
        if scenario.suite.is_some() || scenario.design.spectrum.is_some() {
            return None;
        }
        let heights: Vec<Vec<u64>> = scenario
            .contacts()
            .map(|c| c.levels.iter().map(|l| l.height.to_bits()).collect())
            .collect();
        Some(FreeRunKey::with_levels(
            scenario,
            &format!("row {heights:?}"),
            check,
            true,
        ))
    }

    /// The key of `scenario` with its contact levels described by `levels`.
    fn with_levels(scenario: &Scenario, levels: &str, check: bool, floors: bool) -> FreeRunKey {
        let (ground, record) = match &scenario.ground_motion {
            GroundMotion::Record(r) => (format!("record {:?}", r.dt.to_bits()), Some(r.clone())),
            g => (format!("{g:?}"), None),
        };
        // Debug writes every f64 so that it reads back exactly (shortest round trip)
        let text = format!(
            "{:?}|{ground}|{:?}|{:?}|{:?}|{levels}|{check}|{floors}",
            scenario.structures,
            scenario.solver,
            scenario.output_interval.to_bits(),
            scenario.floor_stations,
        );
        // (a record's samples enter the hash by their length and a few of them: equality
        // compares them all, on a hit only)
        let mut h = std::collections::hash_map::DefaultHasher::new();
        text.hash(&mut h);
        if let Some(r) = &record {
            r.accel.len().hash(&mut h);
            let n = r.accel.len();
            for i in [0, n / 4, n / 2, 3 * n / 4, n.saturating_sub(1)] {
                r.accel.get(i).map(|a| a.to_bits()).hash(&mut h);
            }
        }
        FreeRunKey {
            hash: h.finish(),
            text,
            record,
        }
    }
}
