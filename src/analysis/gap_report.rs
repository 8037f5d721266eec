//! What `pounding separation` prints (issue 13, "One report"): every rule at every contact
//! level ([`crate::analysis::level_checks`]) from the run without contact
//! ([`crate::analysis::simulate::separation`]) or from a design spectrum, with each rule's
//! verdict and the spectral peaks at the floors.

use serde::Serialize;

use crate::analysis::level_checks::{
    LevelCheck, LevelInput, PeakSource, RuleInputs, Verdict, floors_coincide, level_check, verdict,
};
use crate::codes::rules::CodeError;
use crate::codes::spectrum::{
    DesignSpectrum, SpectralResponse, SpectrumError, peak_displacements, relative_peak,
};
use crate::input::scenario::Scenario;
use crate::input::scenario::design::CODE_KEYS;
use crate::integrate::SolveError;
use crate::recording::run_record::LevelRecord;

/// Why the report could not be made.
#[derive(Debug, thiserror::Error)]
pub enum GapError {
    /// The run without pounding failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// The response-spectrum analysis failed (e.g. a period outside a spectrum table).
    #[error("response-spectrum analysis: {0}")]
    Spectrum(#[from] SpectrumError),
    /// A code rule refused its input.
    #[error(transparent)]
    Code(#[from] CodeError),
    /// `--code` named a code that does not exist.
    #[error("--code {0}: unknown code; the codes are {codes}", codes = CODE_KEYS.join(", "))]
    UnknownCode(String),
    /// `--code` named a code whose factors the scenario does not give.
    #[error(
        "--code {0}: the scenario has no [separation.{0}] table with the code's factors (see the \
         README, \"Code separation rules\")"
    )]
    NotInScenario(String),
}

/// Everything `pounding separation` prints (and `--json` writes).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GapReport {
    /// Scenario title.
    pub title: String,
    /// Where the peaks fed to the rules come from.
    pub peaks_from: PeakSource,
    /// One line saying so.
    pub peaks_note: &'static str,
    /// The design spectrum's name, when one feeds the rules.
    pub spectrum: Option<&'static str>,
    /// Whether each structure has yielding storeys.
    pub yielding: [bool; 2],
    /// First-mode periods, s.
    pub periods: [f64; 2],
    /// First-mode damping ratios.
    pub damping_ratios: [f64; 2],
    /// First-mode CQC correlation used by DDC.
    pub rho: f64,
    /// Every contact level, in the order of the scenario's `[contact]` levels (as
    /// summary.json's `levels`).
    pub levels: Vec<LevelCheck>,
    /// Each rule at its governing level.
    pub verdict: Verdict,
    /// With a spectrum: the spectral peaks at every floor of each structure that has floors
    /// (empty for a cantilever), lowest first.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spectral_floors: Option<[Vec<SpectralResponse>; 2]>,
    /// What the reader should know (the scenario's warnings first).
    pub warnings: Vec<String>,
}

/// The report of `scenario`: rules from `spectrum` if given, else from the scenario's own
/// spectrum, else from its time history; the exact value whenever it has a time history; every
/// check at every contact level. `codes`: the codes to include (all of the scenario's when
/// `None`).
pub fn gap_report(
    scenario: &Scenario,
    spectrum: Option<&DesignSpectrum>,
    codes: Option<&[String]>,
) -> Result<GapReport, GapError> {
    check_codes(scenario, codes)?;
    let time_history = if scenario.design.spectrum.is_none() {
        Some(crate::analysis::simulate::separation(scenario)?.levels)
    } else {
        None
    };
    pair_gap_report(scenario, spectrum, codes, time_history.as_deref())
}

/// `--code`'s names: each a code, and one the scenario gives the factors of.
pub(crate) fn check_codes(scenario: &Scenario, codes: Option<&[String]>) -> Result<(), GapError> {
    if let Some(list) = codes {
        for k in list {
            if !CODE_KEYS.contains(&k.as_str()) {
                return Err(GapError::UnknownCode(k.clone()));
            }
            if scenario.design.code(k).is_none() {
                return Err(GapError::NotInScenario(k.clone()));
            }
        }
    }
    Ok(())
}

/// [`gap_report`] of a pair `scenario` (a scenario of two structures: a pair, or one pair of a
/// row, [`Scenario::pair`]) whose run without contact at its contact levels, in their order, is
/// `time_history` (`None` when the scenario's ground motion is a design spectrum). The one
/// body of a pair's report and of each pair's in a row's
/// ([`crate::analysis::row_separation`]).
pub(crate) fn pair_gap_report(
    scenario: &Scenario,
    spectrum: Option<&DesignSpectrum>,
    codes: Option<&[String]>,
    time_history: Option<&[LevelRecord]>,
) -> Result<GapReport, GapError> {
    let spectrum = spectrum.or(scenario.design.spectrum.as_ref());
    let models = [
        scenario.structures[0].modal(),
        scenario.structures[1].modal(),
    ];
    let yielding = [0, 1].map(|i| scenario.structures[i].hysteresis().is_some());
    let mut warnings = scenario.warnings.clone();
    let peaks_from = match spectrum {
        Some(_) => {
            if yielding.iter().any(|y| *y) {
                warnings.push(
                    "the response-spectrum analysis is linear (initial stiffness): the yielding \
                     storeys are not in the spectral peaks; the exact separation (with a time \
                     history) includes them"
                        .into(),
                );
            }
            PeakSource::Spectrum
        }
        None => PeakSource::of_time_history(scenario),
    };
    let lengths = [0, 1].map(|i| scenario.structures[i].length());
    let r = RuleInputs {
        design: &scenario.design,
        codes,
        lengths,
        models: [&models[0], &models[1]],
    };
    let mut levels = Vec::new();
    for (k, lv) in scenario.contact.levels.iter().enumerate() {
        let h = lv.height;
        let spectral = match spectrum {
            Some(s) => Some(relative_peak(&models[0], h, &models[1], h, s)?),
            None => None,
        };
        let record = time_history.map(|t| &t[k]);
        let peaks = match (&spectral, record) {
            (Some(s), _) => [s.structure1.cqc, s.structure2.cqc],
            (None, Some(l)) => [l.peak_w1, l.peak_w2],
            (None, None) => unreachable!("a scenario without a time history has a spectrum"),
        };
        levels.push(level_check(
            &r,
            LevelInput {
                height: h,
                gap: lv.gap,
                peaks,
                exact: record.map(|l| l.max_closing.max(0.0)),
                spectral,
                floors_coincide: floors_coincide(&scenario.structures, h),
            },
        )?);
    }
    let spectral_floors = match spectrum {
        Some(s) => {
            let mut floors = [Vec::new(), Vec::new()];
            for (i, f) in floors.iter_mut().enumerate() {
                if let Some(heights) = scenario.structures[i].floor_heights() {
                    *f = peak_displacements(&models[i], s, heights)?;
                }
            }
            Some(floors)
        }
        None => None,
    };
    let [m1, m2] = &models;
    Ok(GapReport {
        title: scenario.title.clone(),
        peaks_from,
        peaks_note: peaks_from.describe(),
        spectrum: spectrum.map(|s| s.name()),
        yielding,
        periods: [m1.periods()[0], m2.periods()[0]],
        damping_ratios: [m1.zeta[0], m2.zeta[0]],
        rho: crate::codes::spectrum::cqc_correlation(
            m1.zeta[0],
            m2.zeta[0],
            m2.omega[0] / m1.omega[0],
        ),
        verdict: verdict(&levels),
        levels,
        spectral_floors,
        warnings,
    })
}
