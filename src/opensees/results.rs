//! The numbers a crosscheck sets side by side: what the OpenSees script writes
//! (`opensees.json`, [`OpenSeesResults`]), the program's side ([`ProgramNumbers`]) and one
//! compared quantity ([`Row`]).

use std::collections::BTreeMap;

use serde::Deserialize;

use crate::analysis::simulate::Report;

/// One run of the OpenSees script.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct RunInfo {
    /// Wall time of the analysis, s.
    pub seconds: f64,
    /// Steps.
    pub steps: u64,
    /// Steps that needed the fallback.
    pub fallbacks: u64,
}

/// Peaks at one height.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct HeightPeaks {
    /// Height, m.
    pub height: f64,
    /// Peak |w| with contact, m.
    pub peak_displacement: Option<f64>,
    /// Peak |w| without contact, m.
    pub peak_displacement_no_contact: Option<f64>,
}

/// A structure's numbers.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct OsStructure {
    /// Name.
    pub name: String,
    /// Peak |w| at the main contact height with contact, m.
    pub peak_displacement: Option<f64>,
    /// The same without contact, m.
    pub peak_displacement_no_contact: Option<f64>,
    /// Peaks at every tracked height (contact heights, or floors).
    pub heights: Vec<HeightPeaks>,
    /// Every storey of a shear building, lowest first (empty for a cantilever).
    #[serde(default)]
    pub storeys: Vec<OsStorey>,
    /// Periods of the FE model's modes that belong to this structure, s (when it is modally
    /// damped).
    #[serde(default)]
    pub fe_periods: Vec<f64>,
}

/// A contact level's numbers.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct OsLevel {
    /// Height, m.
    pub height: f64,
    /// Peak force, N.
    pub peak_force: Option<f64>,
    /// Largest penetration, m.
    pub max_penetration: Option<f64>,
    /// Contact episodes.
    pub impacts: Option<u64>,
    /// Time in contact, s.
    pub contact_time: Option<f64>,
    /// Peak |w₁|, |w₂| with contact, m.
    pub peak_displacement: Option<[f64; 2]>,
    /// The same without, m.
    pub peak_displacement_no_contact: Option<[f64; 2]>,
    /// max (w₁ − w₂) without contact, m.
    pub required_gap: Option<f64>,
}

/// Contact totals.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct OsContact {
    /// N.
    pub peak_force: f64,
    /// m.
    pub max_penetration: f64,
    /// Episodes.
    pub impacts: u64,
    /// s.
    pub contact_time: f64,
}

/// Separation.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct OsSeparation {
    /// max_t (w₁ − w₂) at the main height without contact, m.
    pub time_history: Option<f64>,
}

/// What an exported script prints.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct OpenSeesResults {
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
    /// Structures 1 and 2.
    pub structures: Vec<OsStructure>,
    /// Levels.
    pub levels: Vec<OsLevel>,
    /// Totals (with contact).
    #[serde(default)]
    pub contact: Option<OsContact>,
    /// Separation.
    pub separation: OsSeparation,
}

impl OpenSeesResults {
    /// Wall time of both runs, s.
    pub fn seconds(&self) -> f64 {
        self.runs.values().map(|r| r.seconds).sum()
    }
}

/// A storey of a shear building: its link's numbers.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct OsStorey {
    /// Peak |u_j − u_{j−1}| with contact, m.
    pub peak_drift: Option<f64>,
    /// The same without contact, m.
    pub peak_drift_no_contact: Option<f64>,
    /// Peak |V| of the storey link with contact (its material's force: k·drift, or Bouc–Wen),
    /// N.
    pub peak_force: Option<f64>,
    /// The same without contact, N.
    pub peak_force_no_contact: Option<f64>,
    /// Signed drift at the end with contact, m.
    pub residual_drift: Option<f64>,
    /// The same without contact, m.
    pub residual_drift_no_contact: Option<f64>,
    /// Energy dissipated by the Bouc–Wen link with contact, J (`None`: elastic).
    pub hysteretic_energy: Option<f64>,
    /// The same without contact, J.
    pub hysteretic_energy_no_contact: Option<f64>,
}

/// The program's side of a crosscheck.
#[derive(Debug, Clone)]
pub struct ProgramNumbers {
    /// Its report (both runs).
    pub report: Report,
    /// Peaks at every tracked height per structure: (height, with, without), m — the contact
    /// heights of a cantilever, every floor of a building.
    pub heights: [Vec<(f64, f64, f64)>; 2],
    /// Wall time of the two runs, s.
    pub seconds: f64,
}

/// One compared quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// What it is (with its unit).
    pub quantity: String,
    /// The program's value.
    pub program: f64,
    /// OpenSees' value (`None`: that run was not made).
    pub opensees: Option<f64>,
    /// The size below which a difference is measured against this scale instead of the
    /// program's value (0: plain relative difference): a residual drift near zero against
    /// the yield drift, a storey's small hysteretic energy against 0.1 % of the input energy.
    pub scale: f64,
}

impl Row {
    /// (OpenSees − program)/max(|program|, scale) (`None` without an OpenSees value, or with
    /// a zero program value and scale).
    pub fn relative(&self) -> Option<f64> {
        let o = self.opensees?;
        let by = self.program.abs().max(self.scale);
        if by == 0.0 {
            return (o == 0.0).then_some(0.0);
        }
        Some((o - self.program) / by)
    }
}
