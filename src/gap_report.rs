//! The required separation by every rule, side by side (issue 13, "One report"): the paper's
//! rules (ABS, SRSS, DDC), the building codes of the scenario's `[separation]` table, the gap
//! given and whether each suffices, and — when the scenario has a time history — the exact
//! time-history separation with each rule's over- or under-estimate of it.
//!
//! The rules are fed the elastic peak displacement at the contact height (the highest contact
//! level) of each structure without pounding: from the time history, or, with a design
//! spectrum, the CQC of the modal peaks `Γ_n φ_n(h) S_d(T_n, ζ_n)` ([`crate::spectrum`]). The
//! codes multiply their own displacements, obtained from that elastic displacement as the
//! scenario states ([`crate::design::ToDesign`]).

use serde::Serialize;

use crate::codes::{CodeError, PairInput};
use crate::design::{CODE_KEYS, DesignInputs};
use crate::integrate::SolveError;
use crate::scenario::Scenario;
use crate::separation::{PeakPair, Rule, Separations};
use crate::spectrum::{
    DesignSpectrum, RelativeResponse, SpectralResponse, SpectrumError, peak_displacements,
    relative_peak,
};

/// One code's required separation for a scenario (`separation.codes` of summary.json).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CodeCheck {
    /// Short key: "asce7", "is1893", "nbcc", "gb50011", "ntc".
    pub key: &'static str,
    /// The code's name.
    pub name: &'static str,
    /// The clause.
    pub clause: &'static str,
    /// Required separation, m.
    pub required: f64,
    /// Per-structure terms, m (see [`crate::codes::CodeSeparation::terms`]).
    pub terms: [f64; 2],
    /// The displacements the code multiplied, m (0 when it uses none).
    pub displacements: [f64; 2],
    /// How they were obtained from the elastic displacements.
    pub conversion: String,
    /// Whether the gap given at the contact height is at least `required`.
    pub sufficient: bool,
    /// 100 (required − exact)/exact, % (when there is a time history and its separation is
    /// positive): negative means the code asks for less than the exact separation (unsafe).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vs_time_history_percent: Option<f64>,
}

/// 100 (value − exact)/exact, or `None` when there is no positive exact value.
pub fn vs_exact(value: f64, exact: Option<f64>) -> Option<f64> {
    exact.filter(|e| *e > 0.0).map(|e| 100.0 * (value - e) / e)
}

/// The gap at the contact height the rules are evaluated at (the highest level), m.
pub fn main_gap(scenario: &Scenario) -> f64 {
    let h = scenario.main_height();
    scenario
        .contact
        .levels
        .iter()
        .find(|l| l.height == h)
        .map_or(scenario.contact.levels[0].gap, |l| l.gap)
}

/// Every code of `design` whose key is in `keys` (all when `None`) for the elastic peak
/// displacements `elastic` (m) at the contact height `level` (m) of structures `heights` (m);
/// `gap` the gap given (m), `exact` the time-history separation when there is one (m).
pub fn code_checks(
    design: &DesignInputs,
    keys: Option<&[String]>,
    elastic: [f64; 2],
    heights: [f64; 2],
    level: f64,
    gap: f64,
    exact: Option<f64>,
) -> Result<Vec<CodeCheck>, CodeError> {
    let mut out = Vec::new();
    for spec in &design.codes {
        if keys.is_some_and(|k| !k.iter().any(|k| k == spec.rule.key())) {
            continue;
        }
        let displacements = spec.to_design.apply(&spec.rule, elastic);
        let input = PairInput {
            displacement: displacements,
            height: heights,
            level: [level; 2],
        };
        let s = spec.rule.required_separation(&input)?;
        out.push(CodeCheck {
            key: s.key,
            name: s.name,
            clause: s.clause,
            required: s.required,
            terms: s.terms,
            displacements,
            conversion: spec.to_design.describe(),
            sufficient: gap >= s.required,
            vs_time_history_percent: vs_exact(s.required, exact),
        });
    }
    Ok(out)
}

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
    #[error("--code {0}: {reason}", reason = unknown_code_reason(.0))]
    UnknownCode(String),
    /// `--code` named a code whose factors the scenario does not give.
    #[error(
        "--code {0}: the scenario has no [separation.{0}] table with the code's factors (see the \
         README, \"Code separation rules\")"
    )]
    NotInScenario(String),
}

fn unknown_code_reason(code: &str) -> String {
    if code == "ec8" {
        "EN 1998-1 §4.4.2.7 could not be verified, so it is not implemented (docs/codes.md)".into()
    } else {
        format!("unknown code; the codes are {}", CODE_KEYS.join(", "))
    }
}

/// One row of the report: a rule and its value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RuleRow {
    /// Short key: "abs", "srss", "ddc", "ddc_modes", "ddc_paper", or a code's key.
    pub key: String,
    /// What the rule is, for the table.
    pub label: String,
    /// Clause (codes only).
    pub clause: Option<String>,
    /// Required separation, m.
    pub value: f64,
    /// Whether the gap given is at least `value`.
    pub sufficient: bool,
    /// Over (+) or under (−) estimate of the exact time-history separation, %.
    pub vs_exact_percent: Option<f64>,
}

/// The spectral side of the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpectralPart {
    /// The spectrum's name, e.g. "ASCE 7-16 §11.4.6".
    pub name: &'static str,
    /// Peaks at the contact height of each structure (per mode, SRSS, CQC) and of w₁ − w₂.
    pub response: RelativeResponse,
    /// Peaks at every floor of each structure that has floors (empty for a cantilever),
    /// lowest first.
    pub floors: [Vec<SpectralResponse>; 2],
}

/// Everything `pounding separation` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GapReport {
    /// Contact height the rules are evaluated at, m.
    pub height: f64,
    /// Gap given there, m.
    pub gap: f64,
    /// The elastic peak displacements feeding the rules, m (CQC with a spectrum).
    pub elastic: [f64; 2],
    /// Peak |w₁|, |w₂| of the time history without pounding, m (when there is one).
    pub time_history_peaks: Option<[f64; 2]>,
    /// First-mode periods, s.
    pub periods: [f64; 2],
    /// First-mode damping ratios.
    pub damping_ratios: [f64; 2],
    /// First-mode CQC correlation used by DDC.
    pub rho: f64,
    /// The response-spectrum analysis, when a spectrum is used.
    pub spectrum: Option<SpectralPart>,
    /// The exact time-history separation `max_t (w₁ − w₂)`, m, when there is a time history.
    pub exact: Option<f64>,
    /// Every rule: ABS, SRSS, DDC (+ DDC over all modes with a spectrum), DDC as printed in
    /// the paper, then the codes.
    pub rules: Vec<RuleRow>,
    /// The codes in detail.
    pub codes: Vec<CodeCheck>,
}

/// The report of `scenario`: rules from `spectrum` if given, else from the scenario's own
/// spectrum, else from its time history; the exact value whenever it has a time history.
/// `codes`: the codes to include (all of the scenario's when `None`).
pub fn gap_report(
    scenario: &Scenario,
    spectrum: Option<&DesignSpectrum>,
    codes: Option<&[String]>,
) -> Result<GapReport, GapError> {
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
    let spectrum = spectrum.or(scenario.design.spectrum.as_ref());
    let h = scenario.main_height();
    let gap = main_gap(scenario);
    let models = [
        scenario.structures[0].modal(),
        scenario.structures[1].modal(),
    ];
    let time_history = if scenario.design.spectrum.is_none() {
        Some(crate::simulate::separation(scenario)?)
    } else {
        None
    };
    let exact = time_history.as_ref().map(|t| t.separation.time_history);
    let spectral = match spectrum {
        Some(s) => {
            let mut floors = [Vec::new(), Vec::new()];
            for (i, f) in floors.iter_mut().enumerate() {
                if let Some(heights) = scenario.structures[i].floor_heights() {
                    *f = peak_displacements(&models[i], s, heights)?;
                }
            }
            Some(SpectralPart {
                name: s.name(),
                response: relative_peak(&models[0], h, &models[1], h, s)?,
                floors,
            })
        }
        None => None,
    };
    let elastic = match (&spectral, &time_history) {
        (Some(s), _) => [s.response.structure1.cqc, s.response.structure2.cqc],
        (None, Some(t)) => t.peaks_no_contact,
        (None, None) => unreachable!("a scenario without a time history has a spectrum"),
    };
    let [m1, m2] = &models;
    let peaks = PeakPair {
        w1: elastic[0],
        w2: elastic[1],
        zeta1: m1.zeta[0],
        zeta2: m2.zeta[0],
        period_ratio: m2.omega[0] / m1.omega[0],
    };
    let rules_of = Separations::new(&peaks, exact.unwrap_or(0.0));
    let row = |key: &str, label: &str, value: f64| RuleRow {
        key: key.into(),
        label: label.into(),
        clause: None,
        value,
        sufficient: gap >= value,
        vs_exact_percent: vs_exact(value, exact),
    };
    let mut rules = vec![
        row("abs", "ABS  w1 + w2", peaks.separation(Rule::Abs)),
        row("srss", "SRSS √(w1² + w2²)", peaks.separation(Rule::Srss)),
        row(
            "ddc",
            "DDC  √(w1² + w2² − 2ρ w1 w2)",
            peaks.separation(Rule::Ddc),
        ),
    ];
    if let Some(s) = &spectral {
        rules.push(row(
            "ddc_modes",
            "DDC, all modes: CQC of w1(h) − w2(h)",
            s.response.cqc,
        ));
    }
    rules.push(row(
        "ddc_paper",
        "ddc-paper (eq. 22–23 as printed)",
        peaks.separation(Rule::DdcPaper),
    ));
    let lengths = [
        scenario.structures[0].length(),
        scenario.structures[1].length(),
    ];
    let code_rows = code_checks(&scenario.design, codes, elastic, lengths, h, gap, exact)?;
    for c in &code_rows {
        rules.push(RuleRow {
            key: c.key.into(),
            label: c.name.into(),
            clause: Some(c.clause.into()),
            value: c.required,
            sufficient: c.sufficient,
            vs_exact_percent: c.vs_time_history_percent,
        });
    }
    Ok(GapReport {
        height: h,
        gap,
        elastic,
        time_history_peaks: time_history.as_ref().map(|t| t.peaks_no_contact),
        periods: [m1.periods()[0], m2.periods()[0]],
        damping_ratios: [m1.zeta[0], m2.zeta[0]],
        rho: rules_of.rho,
        spectrum: spectral,
        exact,
        rules,
        codes: code_rows,
    })
}
