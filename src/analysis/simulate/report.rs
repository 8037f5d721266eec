//! What a run of a pair reports ([`Report`]) and its parts: per structure (every floor, the
//! yielding storeys), per contact level and over all levels, formed from the records of the
//! runs with and without contact.

use serde::Serialize;

use super::accuracy::AccuracyCheck;
use crate::analysis::level_checks::Separations;
use crate::integrate::Stats;
use crate::model::modal::ModalModel;
use crate::model::structure::Structure;
use crate::model::system::Level;
use crate::recording::floor_response::FloorPeaks;
use crate::recording::run_record::{EnergyBalance, Impact, LevelRecord, RunRecord};
use crate::recording::storey_record::StoreyRecord;

/// Per-structure results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StructureReport {
    /// Name.
    pub name: String,
    /// Periods of the modes kept, s.
    pub periods: Vec<f64>,
    /// Damping ratios of the modes kept.
    pub damping_ratios: Vec<f64>,
    /// Peak |w(h)| with pounding at the main contact height, m.
    pub peak_displacement: f64,
    /// Peak |w(h)| without pounding, m.
    pub peak_displacement_no_contact: f64,
    /// 100·(with − without)/without, %.
    pub change_percent: f64,
    /// Peaks at every floor (a cantilever: every tenth of its height and each contact
    /// height), lowest first, with and without pounding (see [`crate::recording::floor_response`]).
    pub floors: Vec<FloorReport>,
    /// A yielding building only (issue 16): the largest peak ductility demand over its storeys
    /// with pounding, and without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_ductility: Option<f64>,
    /// See `peak_ductility`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_ductility_no_contact: Option<f64>,
    /// A yielding building only: the largest |residual drift| over its storeys, m, with
    /// pounding, and without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_residual_drift: Option<f64>,
    /// See `max_residual_drift`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_residual_drift_no_contact: Option<f64>,
    /// A yielding building only: the energy its storeys dissipate by hysteresis, J, with
    /// pounding, and without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_energy: Option<f64>,
    /// See `hysteretic_energy`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_energy_no_contact: Option<f64>,
    /// A yielding building only: its smallest yield drift, m (the scale of the self-check's
    /// change in residual drift; not written).
    #[serde(skip)]
    pub min_yield_drift: Option<f64>,
}

impl StructureReport {
    /// The peak storey drift ratio of every floor (station), with and without pounding, %:
    /// `100 · peak_drift / (h_j − h_{j−1})`, the storey's drift over its height (the first
    /// storey's over its height above the base) — the drift ratio engineers read (elastic
    /// buildings ≈ 0.5–2 %).
    pub fn peak_drift_ratios(&self) -> Vec<[f64; 2]> {
        let mut below = 0.0;
        self.floors
            .iter()
            .map(|f| {
                let storey = f.height - below;
                below = f.height;
                [f.peak_drift, f.peak_drift_no_contact].map(|d| 100.0 * d / storey)
            })
            .collect()
    }
}

/// Peaks at one floor (station), with and without pounding.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FloorReport {
    /// Height above the base, m.
    pub height: f64,
    /// Peak |w| (displacement) relative to the ground with pounding, m.
    pub peak_displacement: f64,
    /// The same without pounding, m.
    pub peak_displacement_no_contact: f64,
    /// Peak absolute acceleration |ü + a_g| with pounding, m/s².
    pub peak_acceleration: f64,
    /// The same without pounding, m/s².
    pub peak_acceleration_no_contact: f64,
    /// When the peak absolute acceleration with pounding occurred, s.
    pub peak_acceleration_time: f64,
    /// The impact during which it occurred (`None`, not written: at no impact). During an
    /// impact the peak is the impact's pulse — as short as the contact, set by the contact
    /// stiffness — not a floor acceleration to design contents or equipment for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_acceleration_impact: Option<ImpactPulse>,
    /// Peak inter-storey drift of the storey below with pounding (the first relative to the
    /// base), m.
    pub peak_drift: f64,
    /// The same without pounding, m.
    pub peak_drift_no_contact: f64,
    /// Peak storey shear of the storey below with pounding: the force its structure carries
    /// (k·drift, a yielding storey's Bouc–Wen force V, the modes' K u, a cantilever's −EI w‴;
    /// no damping forces; docs/model.md §2.6c), N.
    pub peak_shear: f64,
    /// The same without pounding, N.
    pub peak_shear_no_contact: f64,
    /// Peak shear of the storey below from the equilibrium of everything above (inertia and
    /// contact forces): the storey force plus the damping forces above, with pounding, N.
    pub peak_shear_with_damping: f64,
    /// The same without pounding, N.
    pub peak_shear_with_damping_no_contact: f64,
    /// Yielding storeys only (issue 16): peak |drift| / d_y of the storey below, with pounding.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_ductility: Option<f64>,
    /// The same without pounding.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_ductility_no_contact: Option<f64>,
    /// Yielding storeys only: signed drift of the storey below at the end of the run, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_drift: Option<f64>,
    /// The same without pounding, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_drift_no_contact: Option<f64>,
    /// Yielding storeys only: energy dissipated by the storey's hysteresis, J.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_energy: Option<f64>,
    /// The same without pounding, J.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteretic_energy_no_contact: Option<f64>,
    /// Yielding storeys only: the storey's yield drift d_y, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yield_drift: Option<f64>,
}

impl FloorReport {
    /// A yielding storey: the storey force, ductility, residual drift and hysteretic energy
    /// from its records with (`a`) and without (`b`) pounding.
    fn yielding(&mut self, a: &StoreyRecord, b: &StoreyRecord) {
        self.peak_shear = a.peak_force;
        self.peak_shear_no_contact = b.peak_force;
        self.peak_drift = a.peak_drift;
        self.peak_drift_no_contact = b.peak_drift;
        self.peak_ductility = Some(a.peak_ductility());
        self.peak_ductility_no_contact = Some(b.peak_ductility());
        self.residual_drift = Some(a.residual_drift);
        self.residual_drift_no_contact = Some(b.residual_drift);
        self.hysteretic_energy = Some(a.hysteretic_energy);
        self.hysteretic_energy_no_contact = Some(b.hysteretic_energy);
        self.yield_drift = Some(a.yield_drift);
    }

    fn pair(a: &FloorPeaks, b: &FloorPeaks) -> FloorReport {
        FloorReport {
            height: a.height,
            peak_displacement: a.displacement,
            peak_displacement_no_contact: b.displacement,
            peak_acceleration: a.acceleration,
            peak_acceleration_no_contact: b.acceleration,
            peak_acceleration_time: a.acceleration_time,
            peak_acceleration_impact: None,
            peak_drift: a.drift,
            peak_drift_no_contact: b.drift,
            peak_shear: a.shear,
            peak_shear_no_contact: b.shear,
            peak_shear_with_damping: a.shear_with_damping,
            peak_shear_with_damping_no_contact: b.shear_with_damping,
            peak_ductility: None,
            peak_ductility_no_contact: None,
            residual_drift: None,
            residual_drift_no_contact: None,
            hysteretic_energy: None,
            hysteretic_energy_no_contact: None,
            yield_drift: None,
        }
    }
}

/// The impact during which a floor's peak absolute acceleration occurred: the acceleration is
/// then the impact's pulse, lasting about the contact's duration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ImpactPulse {
    /// Contact level index (0-based, as in `impact_log`).
    pub level: usize,
    /// The level's height, m.
    pub height: f64,
    /// Start and end of the contact, s.
    pub start: f64,
    /// See `start`.
    pub end: f64,
    /// `end − start`, s: how long the pulse lasts.
    pub duration: f64,
    /// The impact's peak contact force, N.
    pub peak_force: f64,
}

/// The impact in progress at time `t` (start ≤ t ≤ end), the one of largest peak force when
/// impacts at several levels overlap; `heights[k]` is level k's height.
pub fn impact_at(impacts: &[Impact], heights: &[f64], t: f64) -> Option<ImpactPulse> {
    impacts
        .iter()
        .filter(|i| i.start <= t && t <= i.end)
        .max_by(|a, b| a.peak_force.total_cmp(&b.peak_force))
        .map(|i| ImpactPulse {
            level: i.level,
            height: heights.get(i.level).copied().unwrap_or(f64::NAN),
            start: i.start,
            end: i.end,
            duration: i.end - i.start,
            peak_force: i.peak_force,
        })
}

/// Contact results, totals and maxima over the levels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactReport {
    /// Largest contact force at any level, N.
    pub peak_force: f64,
    /// Largest penetration at any level, m.
    pub max_penetration: f64,
    /// Number of contact episodes over all levels.
    pub impacts: usize,
    /// Total time in contact over all levels, s.
    pub contact_time: f64,
}

/// Per-level results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelReport {
    /// Height, m.
    pub height: f64,
    /// Gap, m.
    pub gap: f64,
    /// Effective mass at the contact point, kg.
    pub effective_mass: f64,
    /// Peak force, N.
    pub peak_force: f64,
    /// Largest penetration, m.
    pub max_penetration: f64,
    /// Contact episodes.
    pub impacts: usize,
    /// Time in contact, s.
    pub contact_time: f64,
    /// Peak |w₁| and |w₂| at this height with pounding, m.
    pub peak_displacement: [f64; 2],
    /// Peak |w₁| and |w₂| at this height without pounding, m.
    pub peak_displacement_no_contact: [f64; 2],
    /// `max_t [w₁ − w₂]` at this height without pounding: the gap needed here, m.
    pub required_gap: f64,
}

/// Everything a run produces.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Scenario title.
    pub title: String,
    /// Structure 1 and 2.
    pub structures: [StructureReport; 2],
    /// Contact totals.
    pub contact: ContactReport,
    /// Per level.
    pub levels: Vec<LevelReport>,
    /// Required separations at the main contact height.
    pub separation: Separations,
    /// The self-check: the headline numbers against a run at a 100× tighter tolerance
    /// ([`super::simulate_checked`]); `checked: false` from [`super::simulate`].
    pub accuracy: AccuracyCheck,
    /// Energy balance of the run with contact.
    pub energy: EnergyBalance,
    /// Energy balance of the run without contact.
    pub energy_no_contact: EnergyBalance,
    /// Every impact.
    pub impact_log: Vec<Impact>,
    /// Solver counters (with contact).
    #[serde(skip)]
    pub stats: Stats,
    /// Things the user should know (inaccurate contact resolution, energy drift).
    pub warnings: Vec<String>,
    /// The run with contact (history, impacts).
    #[serde(skip)]
    pub with_contact: RunRecord,
    /// The run without contact.
    #[serde(skip)]
    pub without_contact: RunRecord,
}

/// `100 · (with − without) / without`, %; 0 without a peak without contact.
fn change_percent(with: f64, without: f64) -> f64 {
    if without > 0.0 {
        100.0 * (with - without) / without
    } else {
        0.0
    }
}

/// Structure `i`'s report (`structure`, its modal model `model`) from the runs (with,
/// without) contact; `impacts` those that load it (for the floor accelerations' pulses),
/// `heights` every tracked level's height, `peak` its headline peak |w| with and without
/// contact, m.
pub(super) fn structure_report(
    structure: &Structure,
    i: usize,
    model: &ModalModel,
    (with, without): (&RunRecord, &RunRecord),
    impacts: &[Impact],
    heights: &[f64],
    peak: [f64; 2],
) -> StructureReport {
    let (s, m) = (structure, model);
    let mut floors: Vec<FloorReport> = with.floors[i]
        .iter()
        .zip(&without.floors[i])
        .map(|(a, b)| FloorReport::pair(a, b))
        .collect();
    for f in &mut floors {
        f.peak_acceleration_impact = impact_at(impacts, heights, f.peak_acceleration_time);
    }
    let mine = |r: &RunRecord| -> Vec<StoreyRecord> {
        r.storeys
            .iter()
            .filter(|x| x.structure == i)
            .cloned()
            .collect()
    };
    let (ya, yb) = (mine(with), mine(without));
    for (a, b) in ya.iter().zip(&yb) {
        if let Some(f) = floors.get_mut(a.storey) {
            f.yielding(a, b);
        }
    }
    let yielding = !ya.is_empty();
    let over = |v: &[StoreyRecord], f: fn(&StoreyRecord) -> f64, sum: bool| {
        yielding.then(|| {
            if sum {
                v.iter().map(f).sum()
            } else {
                v.iter().map(f).fold(0.0, f64::max)
            }
        })
    };
    StructureReport {
        peak_ductility: over(&ya, StoreyRecord::peak_ductility, false),
        peak_ductility_no_contact: over(&yb, StoreyRecord::peak_ductility, false),
        max_residual_drift: over(&ya, |r| r.residual_drift.abs(), false),
        max_residual_drift_no_contact: over(&yb, |r| r.residual_drift.abs(), false),
        hysteretic_energy: over(&ya, |r| r.hysteretic_energy, true),
        hysteretic_energy_no_contact: over(&yb, |r| r.hysteretic_energy, true),
        min_yield_drift: yielding.then(|| {
            ya.iter()
                .map(|r| r.yield_drift)
                .fold(f64::INFINITY, f64::min)
        }),
        name: s.name().to_string(),
        periods: m.periods(),
        damping_ratios: m.zeta.clone(),
        peak_displacement: peak[0],
        peak_displacement_no_contact: peak[1],
        change_percent: change_percent(peak[0], peak[1]),
        floors,
    }
}

/// A contact level's report from its records with (`a`) and without (`b`) contact.
pub(super) fn level_report(lv: &Level, a: &LevelRecord, b: &LevelRecord) -> LevelReport {
    LevelReport {
        height: lv.height,
        gap: lv.gap,
        effective_mass: lv.effective_mass,
        peak_force: a.peak_force,
        max_penetration: a.max_penetration,
        impacts: a.impacts,
        contact_time: a.contact_time,
        peak_displacement: [a.peak_w1, a.peak_w2],
        peak_displacement_no_contact: [b.peak_w1, b.peak_w2],
        required_gap: b.max_closing.max(0.0),
    }
}

/// Totals and maxima over `levels`.
pub(super) fn contact_report(levels: &[LevelReport]) -> ContactReport {
    ContactReport {
        peak_force: levels.iter().map(|l| l.peak_force).fold(0.0, f64::max),
        max_penetration: levels.iter().map(|l| l.max_penetration).fold(0.0, f64::max),
        impacts: levels.iter().map(|l| l.impacts).sum(),
        contact_time: levels.iter().map(|l| l.contact_time).sum(),
    }
}
