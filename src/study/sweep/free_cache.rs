//! The runs without contact of a sweep's cases, cached across cases that differ only in
//! their contact (gap, stiffness, law, restitution, the levels' gaps; of a row, any pair's):
//! such cases share their structures, ground motion and solver settings, hence their runs
//! without contact, bit for bit ([`FreeRunKey`]: a pair's, [`FreeRunKey::of_row`]: a row's).
//! Enabled only for a sweep with an axis on a contact key; its cases are then computed in an
//! order where the contact axes vary fastest ([`FreeRunCache::order`]), so that the cases
//! sharing a run follow one another and a small cache serves them all. Every kind of case
//! uses it: a single run of a pair ([`FreeRunCache::simulate`]) or of a row
//! ([`FreeRunCache::simulate_row`]), and each record's run of a suite on either (the records
//! of a case are keyed one by one: a record's run without contact is shared by the cases
//! that differ only in contact, whose suites are scaled alike — the scaling reads the
//! first-mode periods, not the contact).

use std::collections::{HashMap, VecDeque};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use super::axes::Axis;
use super::keys::{Section, Target};
use crate::analysis::simulate::{
    FreeRunKey, FreeRuns, Report, RowFreeRuns, RowReport, simulate_reusing, simulate_row_reusing,
};
use crate::input::scenario::Scenario;
use crate::integrate::SolveError;

/// The memory a cache holds at most, bytes (≈ 1300 runs without contact of the paper's case:
/// 2001 history samples each, no floors).
pub const FREE_RUN_CACHE_BYTES: usize = 64 << 20;

/// The runs without contact of a pair's case or of a row's.
#[derive(Clone)]
enum Runs {
    Pair(Arc<FreeRuns>),
    Row(Arc<RowFreeRuns>),
}

impl Runs {
    fn bytes(&self) -> usize {
        match self {
            Runs::Pair(r) => r.bytes(),
            Runs::Row(r) => r.bytes(),
        }
    }
}

#[derive(Default)]
struct Entries {
    map: HashMap<u64, Vec<(FreeRunKey, Runs)>>,
    /// Insertion order (hash, key), oldest first: what is evicted first.
    order: VecDeque<(u64, usize)>,
    bytes: usize,
}

/// A bounded cache of runs without contact ([`FREE_RUN_CACHE_BYTES`]), shared by the
/// sweep's worker threads. Disabled (every case integrated as before) when no axis sets a
/// contact key.
pub struct FreeRunCache {
    /// Per axis: whether it sets a contact key (the cases it separates share their runs
    /// without contact); empty when disabled.
    contact_axes: Vec<bool>,
    entries: Mutex<Entries>,
    hits: AtomicUsize,
    budget: usize,
}

impl std::fmt::Debug for FreeRunCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FreeRunCache")
            .field("contact_axes", &self.contact_axes)
            .field("hits", &self.hits.load(Ordering::Relaxed))
            .finish_non_exhaustive()
    }
}

impl FreeRunCache {
    /// The cache of a sweep with `axes` (enabled if any sets a contact key).
    pub fn new(axes: &[Axis]) -> FreeRunCache {
        let contact: Vec<bool> = axes.iter().map(sets_contact).collect();
        FreeRunCache {
            contact_axes: if contact.iter().any(|&c| c) {
                contact
            } else {
                Vec::new()
            },
            entries: Mutex::new(Entries::default()),
            hits: AtomicUsize::new(0),
            budget: FREE_RUN_CACHE_BYTES,
        }
    }

    /// Whether the cache is in use.
    pub fn enabled(&self) -> bool {
        !self.contact_axes.is_empty()
    }

    /// Cases whose runs without contact came from the cache so far.
    pub fn hits(&self) -> usize {
        self.hits.load(Ordering::Relaxed)
    }

    /// Reorder `cases` (case numbers, with each case's axis indices from `indices`) so that
    /// the contact axes vary fastest: the order in which to compute them. Unchanged when the
    /// cache is disabled.
    pub fn order(&self, cases: &mut [usize], indices: impl Fn(usize) -> Vec<usize>) {
        if !self.enabled() {
            return;
        }
        let c = &self.contact_axes;
        cases.sort_by_cached_key(|&case| {
            let idx = indices(case);
            // the other axes first (slowest), then the contact axes, each in axis order
            let (mut other, mut contact): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
            for (j, &i) in idx.iter().enumerate() {
                if c[j] { &mut contact } else { &mut other }.push(i);
            }
            other.extend(contact);
            other
        });
    }

    /// [`simulate_reusing`] of `scenario` (the report of `simulate_checked(scenario, check)`
    /// if `floors`, else of `simulate_headline`), its runs without contact taken from the
    /// cache when a case with the same [`FreeRunKey`] has computed them, and stored for the
    /// next one otherwise. The report is bit-identical either way.
    pub fn simulate(
        &self,
        scenario: &Scenario,
        check: bool,
        floors: bool,
    ) -> Result<Report, SolveError> {
        let key = self
            .enabled()
            .then(|| FreeRunKey::of(scenario, check, floors))
            .flatten();
        let Some(key) = key else {
            return if floors {
                crate::analysis::simulate::simulate_checked(scenario, check)
            } else {
                crate::analysis::simulate::simulate_headline(scenario, check)
            };
        };
        let cached = match self.get(&key) {
            Some(Runs::Pair(r)) => Some(r),
            _ => None,
        };
        if cached.is_some() {
            self.hits.fetch_add(1, Ordering::Relaxed);
        }
        let (report, runs) = simulate_reusing(scenario, check, floors, cached.as_deref())?;
        if cached.is_none() {
            self.put(key, Runs::Pair(Arc::new(runs)));
        }
        Ok(report)
    }

    /// [`simulate_row_reusing`] of the row `scenario` (the report of
    /// `simulate_row_checked(scenario, check)`), its runs without contact taken from the cache
    /// when a case with the same [`FreeRunKey::of_row`] has computed them, and stored for the
    /// next one otherwise. The report is bit-identical either way.
    pub fn simulate_row(&self, scenario: &Scenario, check: bool) -> Result<RowReport, SolveError> {
        let key = self
            .enabled()
            .then(|| FreeRunKey::of_row(scenario, check))
            .flatten();
        let Some(key) = key else {
            return crate::analysis::simulate::simulate_row_checked(scenario, check);
        };
        let cached = match self.get(&key) {
            Some(Runs::Row(r)) => Some(r),
            _ => None,
        };
        if cached.is_some() {
            self.hits.fetch_add(1, Ordering::Relaxed);
        }
        let (report, runs) = simulate_row_reusing(scenario, check, cached.as_deref())?;
        if cached.is_none() {
            self.put(key, Runs::Row(Arc::new(runs)));
        }
        Ok(report)
    }

    fn get(&self, key: &FreeRunKey) -> Option<Runs> {
        let e = self.entries.lock().unwrap_or_else(|p| p.into_inner());
        e.map
            .get(&key.hash)?
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, r)| r.clone())
    }

    fn put(&self, key: FreeRunKey, runs: Runs) {
        let size = runs.bytes();
        if size > self.budget {
            return;
        }
        let mut e = self.entries.lock().unwrap_or_else(|p| p.into_inner());
        let hash = key.hash;
        let bucket = e.map.entry(hash).or_default();
        if bucket.iter().any(|(k, _)| *k == key) {
            return; // another thread computed it meanwhile
        }
        bucket.push((key, runs));
        e.order.push_back((hash, size));
        e.bytes += size;
        while e.bytes > self.budget {
            let Some((h, s)) = e.order.pop_front() else {
                break;
            };
            e.bytes -= s;
            // the oldest entry of that hash (entries of a hash are in insertion order)
            if let Some(b) = e.map.get_mut(&h) {
                if !b.is_empty() {
                    b.remove(0);
                }
                if b.is_empty() {
                    e.map.remove(&h);
                }
            }
        }
    }
}

/// Whether an axis sets a key of the contact (the contact table or a level; of a row, any
/// pair's): cases apart only along such axes have the same run without contact. (A level's
/// height is a contact key that the run without contact does record: [`FreeRunKey`] tells
/// those apart.)
fn sets_contact(a: &Axis) -> bool {
    matches!(
        a.target,
        Target::Key {
            section: Section::Contact
                | Section::Level(_)
                | Section::PairContact(_)
                | Section::PairLevel(..),
            ..
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cache holds at most its budget: with room for three runs, ten stored leave the
    /// last three, and the bytes counted never exceed the budget.
    #[test]
    fn cache_is_bounded_and_evicts_the_oldest() {
        let text = |pga: f64| {
            format!(
                "[[structure]]\nlength = 10.0\nmass = 2.0e6\nperiod = 0.5\nmodes = 2\n\
                 damping_ratio = 0.02\n[[structure]]\nlength = 10.0\nmass = 2.0e6\n\
                 period = 0.7\nmodes = 2\ndamping_ratio = 0.02\n[contact]\ngap = 0.01\nstiffness = 1.0e10\n\
                 [ground_motion]\nkind = \"harmonic\"\npga = {pga}\nperiod = 0.6\n\
                 [solver]\nduration = 0.5\n"
            )
        };
        let scenario = |pga| {
            Scenario::from_toml(&text(pga), "c.toml", std::path::Path::new(".")).expect("valid")
        };
        let runs = |pga| {
            simulate_reusing(&scenario(pga), false, false, None)
                .expect("runs")
                .1
        };
        let size = runs(0.1).bytes();
        let mut cache = FreeRunCache::new(&[]);
        cache.budget = 3 * size + size / 2;
        let pgas: Vec<f64> = (1..=10).map(|i| 0.1 * f64::from(i)).collect();
        for &pga in &pgas {
            let key = FreeRunKey::of(&scenario(pga), false, false).expect("a pair");
            cache.put(key, Runs::Pair(Arc::new(runs(pga))));
            assert!(cache.entries.lock().expect("lock").bytes <= cache.budget);
        }
        let held: Vec<bool> = pgas
            .iter()
            .map(|&pga| {
                let key = FreeRunKey::of(&scenario(pga), false, false).expect("a pair");
                cache.get(&key).is_some()
            })
            .collect();
        let mut expected = vec![false; 7];
        expected.extend([true; 3]);
        assert_eq!(held, expected);
    }
}
