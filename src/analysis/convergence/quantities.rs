//! What the convergence study compares between runs: each structure's peak at its highest
//! contact level and each adjacent pair's peak contact force (a pair: the peaks at the main
//! contact height and the peak force; a row of buildings, issue 29: per structure and per pair), and for yielding buildings (issue 16) the peak ductility, the largest
//! residual drift and the hysteretic energy, each change measured as the self-check measures
//! it ([`crate::analysis::simulate::accuracy`]).

use serde::Serialize;

use crate::recording::run_record::RunRecord;

/// A yielding building's numbers in one run with pounding.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Yielding {
    /// Largest peak ductility demand over its storeys (peak |drift| / d_y).
    pub ductility: f64,
    /// Largest |residual drift| over its storeys, m.
    pub residual_drift: f64,
    /// Energy dissipated by all its storeys' hysteresis, J.
    pub hysteretic_energy: f64,
    /// Its smallest yield drift, m: the scale of a residual drift's change.
    #[serde(skip)]
    pub min_yield_drift: f64,
    /// 0.1 % of the run's input energy, J: the scale of a small hysteretic energy's change.
    #[serde(skip)]
    pub energy_floor: f64,
}

/// Each of the `structures` structures' [`Yielding`] numbers from a run (`None` for an
/// elastic structure).
pub fn yielding(rec: &RunRecord, structures: usize) -> Vec<Option<Yielding>> {
    (0..structures)
        .map(|i| {
            let mut it = rec.storeys.iter().filter(|s| s.structure == i).peekable();
            it.peek()?;
            let mut y = Yielding {
                ductility: 0.0,
                residual_drift: 0.0,
                hysteretic_energy: 0.0,
                min_yield_drift: f64::INFINITY,
                energy_floor: 1e-3 * rec.energy.input.abs(),
            };
            for s in it {
                y.ductility = y.ductility.max(s.peak_ductility());
                y.residual_drift = y.residual_drift.max(s.residual_drift.abs());
                y.hysteretic_energy += s.hysteretic_energy;
                y.min_yield_drift = y.min_yield_drift.min(s.yield_drift);
            }
            Some(y)
        })
        .collect()
}

/// |x − reference| / max(|reference|, `floor`); 0 when both are 0, infinite when only the
/// reference is.
fn change(x: f64, reference: f64, floor: f64) -> f64 {
    let by = reference.abs().max(floor);
    if by == 0.0 {
        if x == 0.0 { 0.0 } else { f64::INFINITY }
    } else {
        (x - reference).abs() / by
    }
}

/// Relative changes of each quantity against a reference (peaks, forces, …).
pub fn headline_changes(x: &[f64], reference: &[f64]) -> Vec<f64> {
    x.iter()
        .zip(reference)
        .map(|(a, r)| change(*a, *r, 0.0))
        .collect()
}

/// Changes of each structure's ductility (relative), residual drift (in units of the larger
/// of the reference's and the smallest yield drift) and hysteretic energy (in units of the
/// larger of the reference's and 0.1 % of the reference run's input energy): a residual drift
/// near zero and a storey that barely yields are not judged by their own tiny size.
pub fn yield_changes(
    x: &[Option<Yielding>],
    reference: &[Option<Yielding>],
) -> Vec<Option<[f64; 3]>> {
    x.iter()
        .zip(reference)
        .map(|(a, r)| {
            let (a, r) = ((*a)?, (*r)?);
            Some([
                change(a.ductility, r.ductility, 0.0),
                change(a.residual_drift, r.residual_drift, r.min_yield_drift),
                change(a.hysteretic_energy, r.hysteretic_energy, r.energy_floor),
            ])
        })
        .collect()
}

/// The names of a pair's headline changes (the N = 2 case of [`quantity_names`]).
pub const HEADLINE: [&str; 3] = ["peak w1", "peak w2", "peak force"];

/// The names of a yielding structure's changes.
pub const YIELDING: [&str; 3] = ["peak ductility", "residual drift", "hysteretic energy"];

/// The names of the compared quantities of `structures` structures in a row (a pair: N = 2):
/// each structure's peak `peak w{i}` (at its highest contact level), then each adjacent pair's
/// peak force (`peak force` for a pair, `peak force of pair {p}` in a row; 1-based).
pub fn quantity_names(structures: usize) -> Vec<String> {
    let mut v: Vec<String> = (1..=structures).map(|i| format!("peak w{i}")).collect();
    if structures == 2 {
        v.push(HEADLINE[2].to_string());
    } else {
        v.extend((1..structures).map(|p| format!("peak force of pair {p}")));
    }
    v
}

/// Every change with its name (`peak w1`, …, `peak force…`, then `peak ductility of 2`, …),
/// quantities first ([`quantity_names`]).
pub fn named(quantities: &[f64], yielding: &[Option<[f64; 3]>]) -> Vec<(String, f64)> {
    let mut out: Vec<(String, f64)> = quantity_names(yielding.len())
        .into_iter()
        .zip(quantities)
        .map(|(n, c)| (n, *c))
        .collect();
    for (i, y) in yielding.iter().enumerate() {
        if let Some(y) = y {
            out.extend(
                YIELDING
                    .iter()
                    .zip(y)
                    .map(|(n, c)| (format!("{n} of {}", i + 1), *c)),
            );
        }
    }
    out
}

/// `change ≤ tolerance`, false if either is NaN.
pub fn within(change: f64, tolerance: f64) -> bool {
    matches!(
        change.partial_cmp(&tolerance),
        Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
    )
}

/// The largest of the changes and its name; a NaN counts as the largest.
pub fn worst(changes: &[(String, f64)]) -> Option<(&str, f64)> {
    changes
        .iter()
        .map(|(n, c)| (n.as_str(), *c))
        .reduce(|m, q| if q.1.is_nan() || q.1 > m.1 { q } else { m })
}
