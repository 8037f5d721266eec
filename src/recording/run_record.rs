//! What one integration produced ([`RunRecord`]): peaks at the tracked heights, every impact
//! episode ([`Impact`]), per-level results ([`LevelRecord`]), the sampled history, the energy
//! balance ([`EnergyBalance`]), the peaks over the height and the yielding storeys.

use serde::Serialize;

use crate::recording::floor_response::FloorPeaks;
use crate::recording::history::History;
use crate::recording::storey_record::StoreyRecord;

/// One contact episode at one level: from the first instant of penetration to separation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Impact {
    /// Contact level index (0-based).
    pub level: usize,
    /// Start time (δ crosses 0 upwards, interpolated between steps), s.
    pub start: f64,
    /// End time (δ crosses 0 downwards), s; the run's end if still in contact.
    pub end: f64,
    /// Peak contact force, N.
    pub peak_force: f64,
    /// Impulse `∫F dt`, N·s.
    pub impulse: f64,
    /// Largest penetration, m.
    pub max_penetration: f64,
    /// Approach speed δ̇ at the start, m/s.
    pub approach_speed: f64,
}

/// Per-level results of one run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelRecord {
    /// Height, m.
    pub height: f64,
    /// Peak |w₁(h)|, m (of a row: the left structure of the level's pair).
    pub peak_w1: f64,
    /// Peak |w₂(h)|, m (of a row: the right structure of the level's pair).
    pub peak_w2: f64,
    /// `max_t [w₁(h) − w₂(h)]`, m: without contact, the gap needed to avoid touching here.
    pub max_closing: f64,
    /// Peak contact force, N.
    pub peak_force: f64,
    /// Largest penetration, m.
    pub max_penetration: f64,
    /// Number of contact episodes.
    pub impacts: usize,
    /// Total time in contact, s.
    pub contact_time: f64,
}

/// The energy balance of a run: `input = modal + contact_stored + damping + contact_dissipated`
/// up to the integration error, which `relative_error` measures.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct EnergyBalance {
    /// Work done by the ground loading, J.
    pub input: f64,
    /// Kinetic + strain energy of the structures at the end, minus at the start, J.
    pub modal_change: f64,
    /// Energy stored in the contacts at the end, J.
    pub contact_stored: f64,
    /// Energy dissipated by structural damping, J.
    pub damping_dissipated: f64,
    /// Energy dissipated in the contacts, J (0 for elastic laws, up to integration error).
    pub contact_dissipated: f64,
    /// Energy dissipated by the yielding storeys' hysteresis, J (only with yielding storeys;
    /// see [`crate::model::hysteresis`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_dissipated: Option<f64>,
    /// Strain energy the Bouc–Wen storeys hold at the end beyond the linear strain energy of
    /// the initial stiffness counted in `modal_change`, `Σ ½(1 − α)k(d_y²z² − d²)`, minus that at
    /// the start, J (only with yielding storeys).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_stored: Option<f64>,
    /// |input − modal_change − contact_stored − damping − contact_dissipated
    /// − hysteretic_dissipated − hysteretic_stored| over the largest
    /// energy present in the run (peak modal + contact energy at the history samples, or
    /// |input| if larger).
    pub relative_error: f64,
}

/// Everything one integration produced.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRecord {
    /// Per-level results (empty without contact... except displacements: see `main_level`).
    pub levels: Vec<LevelRecord>,
    /// Peak |w₁|, |w₂| at the main contact height (of a row: of the highest level's pair), m.
    pub peak: [f64; 2],
    /// `max_t [w₁ − w₂]` at the main contact height, m.
    pub max_closing: f64,
    /// Every impact, in time order per level.
    pub impacts: Vec<Impact>,
    /// Sampled history.
    pub history: History,
    /// Energy balance.
    pub energy: EnergyBalance,
    /// Observations the recorder took after the one at t = 0: one at every accepted step's
    /// end and, with `exact-modal`, three more (the interior nodes) for each contact step whose
    /// force peaks inside it. This is the recorder's count, not the solver's: the accepted and
    /// rejected steps are [`crate::integrate::Stats`] (summary.json's `solver.steps` and
    /// `solver.rejected`).
    pub steps: usize,
    /// Peaks over the height of every structure, in row order (floors, or a cantilever's
    /// stations; empty lists when not tracked).
    pub floors: Vec<Vec<FloorPeaks>>,
    /// Every yielding storey (issue 16; empty when both structures are elastic).
    pub storeys: Vec<StoreyRecord>,
}
