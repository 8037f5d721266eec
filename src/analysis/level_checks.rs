//! Every separation rule at every contact level (issue 13, "One report"; issue 24: every
//! level): the paper's rules (ABS, SRSS, DDC), the building codes of the scenario's
//! `[separation]` table, the gap given there and whether each suffices, and — when the
//! scenario has a time history — the exact time-history separation with each rule's over- or
//! under-estimate of it. The verdict of each rule is its worst level (the smallest margin
//! gap − required), and names that level. [`Separations`] (summary.json `separation`) holds
//! the rules at the main (highest) contact level, as it always has, and beside them every
//! level's checks and the verdict.
//!
//! At contact level h the rules are fed each structure's own peak at h without pounding: from
//! the time history (`max_t |w_i(h, t)|` of the run without contact — elastic, or inelastic
//! when storeys yield), or, with a design spectrum, the CQC of the modal peaks
//! `Γ_n φ_n(h) S_d(T_n, ζ_n)` ([`crate::codes::spectrum`]). The exact separation at h is
//! `max_t [w₁(h, t) − w₂(h, t)]` of the run without contact. The codes multiply their own
//! displacements, obtained from those peaks as the scenario states
//! ([`crate::input::scenario::design::ToDesign`]); EN 1998-1 and IS 1893 reduce theirs where the level is a floor
//! of both structures ([`floors_coincide`]).

use serde::Serialize;

use crate::analysis::separation::{PeakPair, Rule, cqc_correlation};
use crate::codes::rules::{CodeError, PairInput};
use crate::codes::spectrum::RelativeResponse;
use crate::input::scenario::Scenario;
use crate::input::scenario::design::DesignInputs;
use crate::model::modal::ModalModel;
use crate::model::structure::Structure;
use crate::recording::run_record::RunRecord;

/// One code's required separation at one contact level (`separation.codes` of summary.json at
/// the main level; `levels[].codes` at each).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CodeCheck {
    /// Short key: "asce7", "is1893", "nbcc", "gb50011", "ntc", "ec8".
    pub key: &'static str,
    /// The code's name.
    pub name: &'static str,
    /// The clause.
    pub clause: &'static str,
    /// Required separation, m.
    pub required: f64,
    /// Per-structure terms, m (see [`crate::codes::rules::CodeSeparation::terms`]).
    pub terms: [f64; 2],
    /// The displacements the code multiplied, m (0 when it uses none).
    pub displacements: [f64; 2],
    /// How they were obtained from the peak displacements computed here.
    pub conversion: String,
    /// The reduction applied because the level is a floor of both structures (EN 1998-1
    /// × 0.7, IS 1893 R/2), in words; absent when none was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reduction: Option<&'static str>,
    /// Whether the gap given at this level is at least `required`.
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

/// The gap at the main contact height (the highest level), m: what `separation.codes` of
/// summary.json is compared with.
pub fn main_gap(scenario: &Scenario) -> f64 {
    let h = scenario.main_height();
    scenario
        .contact
        .levels
        .iter()
        .find(|l| l.height == h)
        .map_or(scenario.contact.levels[0].gap, |l| l.gap)
}

/// Whether contact height `h` (m) is a floor of both structures — their floor elevations
/// coincide there, which EN 1998-1 §4.4.2.7(3) and IS 1893 §7.11.3 reward. A cantilever has
/// no floors, so a level on it never qualifies. Heights are compared with
/// [`crate::model::building::same_height`] (1e-9 of the height), the rule by which a scenario's
/// contact height is accepted as a floor at all: the numbers are the scenario's own, so only
/// round-off can separate them.
pub fn floors_coincide(structures: &[Structure], h: f64) -> bool {
    structures.iter().all(|s| {
        s.floor_heights()
            .is_some_and(|f| f.iter().any(|&x| crate::model::building::same_height(x, h)))
    })
}

/// Every code of `design` whose key is in `keys` (all when `None`) for the peak displacements
/// `peaks` (m) at contact level `level` (m) of structures of heights `heights` (m); `gap` the
/// gap given there (m), `exact` the time-history separation there when there is one (m),
/// `floors_coincide` whether the level is a floor of both ([`floors_coincide`]).
#[allow(clippy::too_many_arguments)]
pub fn code_checks(
    design: &DesignInputs,
    keys: Option<&[String]>,
    peaks: [f64; 2],
    heights: [f64; 2],
    level: f64,
    gap: f64,
    exact: Option<f64>,
    floors_coincide: bool,
) -> Result<Vec<CodeCheck>, CodeError> {
    let mut out = Vec::new();
    for spec in &design.codes {
        if keys.is_some_and(|k| !k.iter().any(|k| k == spec.rule.key())) {
            continue;
        }
        let displacements = spec.to_design.apply(&spec.rule, peaks);
        let input = PairInput {
            displacement: displacements,
            height: heights,
            level: [level; 2],
            floors_coincide,
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
            reduction: s.reduction,
            sufficient: gap >= s.required,
            vs_time_history_percent: vs_exact(s.required, exact),
        });
    }
    Ok(out)
}

/// Where the peaks fed to the rules come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PeakSource {
    /// The time history without pounding, both structures elastic.
    TimeHistory,
    /// The time history without pounding, with yielding storeys: inelastic peaks.
    TimeHistoryYielding,
    /// The CQC of a design spectrum (a linear analysis on the initial stiffness).
    Spectrum,
}

impl PeakSource {
    /// The source of a run of `scenario` (no spectrum): yielding when a structure has
    /// hysteresis.
    pub fn of_time_history(scenario: &Scenario) -> PeakSource {
        if scenario.structures.iter().any(|s| s.hysteresis().is_some()) {
            PeakSource::TimeHistoryYielding
        } else {
            PeakSource::TimeHistory
        }
    }

    /// One line for reports.
    pub fn describe(self) -> &'static str {
        match self {
            PeakSource::TimeHistory => {
                "the elastic peaks |w1(h)|, |w2(h)| of the time history without pounding"
            }
            PeakSource::TimeHistoryYielding => {
                "the INELASTIC peaks |w1(h)|, |w2(h)| of the time history without pounding \
                 (yielding storeys, Bouc–Wen): the rules and codes take these as their \
                 displacements"
            }
            PeakSource::Spectrum => {
                "the spectral peaks at h (CQC of Γ_n φ_n(h) S_d(T_n, ζ_n), linear, initial \
                 stiffness)"
            }
        }
    }
}

/// One rule at one contact level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RuleCheck {
    /// Short key: "time_history" (the exact value), "abs", "srss", "ddc", "ddc_modes",
    /// "ddc_paper", or a code's key.
    pub key: String,
    /// What the rule is, for tables.
    pub label: String,
    /// Clause (codes only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub clause: Option<String>,
    /// Required separation, m.
    pub required: f64,
    /// Gap given − required, m (negative: too small).
    pub margin: f64,
    /// Whether the gap given at this level is at least `required`.
    pub sufficient: bool,
    /// Over (+) or under (−) estimate of the exact time-history separation at this level, %.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vs_exact_percent: Option<f64>,
}

/// Every rule at one contact level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelCheck {
    /// Height of the level, m.
    pub height: f64,
    /// Gap given there, m.
    pub gap: f64,
    /// The level is a floor of both structures ([`floors_coincide`]).
    pub floors_coincide: bool,
    /// The peaks fed to the rules at this level, m ([`PeakSource`]).
    pub peaks: [f64; 2],
    /// `max_t [w₁(h) − w₂(h)]` without pounding (≥ 0), m, when there is a time history.
    pub exact: Option<f64>,
    /// The response-spectrum analysis at this level (per mode, SRSS, CQC of each structure;
    /// SRSS and CQC of w₁ − w₂ over both structures' modes), with a spectrum.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spectral: Option<RelativeResponse>,
    /// Every rule: the exact value (with a time history), ABS, SRSS, DDC (+ DDC over all modes
    /// with a spectrum), DDC as printed in the paper, then the codes.
    pub rules: Vec<RuleCheck>,
    /// The codes in detail.
    pub codes: Vec<CodeCheck>,
}

/// A rule at its governing level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Governing {
    /// The rule's key (see [`RuleCheck::key`]).
    pub key: String,
    /// The rule, for tables.
    pub label: String,
    /// The level that governs: where gap − required is smallest, m.
    pub height: f64,
    /// Gap given there, m.
    pub gap: f64,
    /// Required there, m.
    pub required: f64,
    /// Gap − required there, m.
    pub margin: f64,
    /// Whether the gap suffices at every level.
    pub sufficient: bool,
}

/// The verdict over all levels.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Verdict {
    /// Each rule at its governing level, in the order of [`LevelCheck::rules`].
    pub rules: Vec<Governing>,
    /// The rule and level with the smallest margin of all (the widest gap asked for where it
    /// is shortest): what governs the joint if every rule is to be met.
    pub governing: Option<Governing>,
    /// How many rules find the gap too small somewhere.
    pub insufficient: usize,
}

/// The inputs of the rules that do not change with the level.
#[derive(Debug, Clone, Copy)]
pub struct RuleInputs<'a> {
    /// The scenario's code factors.
    pub design: &'a DesignInputs,
    /// The codes to include (all of `design`'s when `None`).
    pub codes: Option<&'a [String]>,
    /// Heights of the structures (their tops), m: GB 50011 uses them.
    pub lengths: [f64; 2],
    /// The two structures' modal models (first-mode ζ and ω feed DDC's ρ).
    pub models: [&'a ModalModel; 2],
}

/// What varies with the level.
#[derive(Debug, Clone, PartialEq)]
pub struct LevelInput {
    /// Height, m.
    pub height: f64,
    /// Gap given, m.
    pub gap: f64,
    /// Peaks fed to the rules, m.
    pub peaks: [f64; 2],
    /// The exact separation (≥ 0), m, with a time history.
    pub exact: Option<f64>,
    /// The spectral analysis at this height, with a spectrum.
    pub spectral: Option<RelativeResponse>,
    /// The level is a floor of both structures.
    pub floors_coincide: bool,
}

/// Every rule at one level.
pub fn level_check(r: &RuleInputs, input: LevelInput) -> Result<LevelCheck, CodeError> {
    let [m1, m2] = r.models;
    let (gap, exact) = (input.gap, input.exact);
    let pair = PeakPair {
        w1: input.peaks[0],
        w2: input.peaks[1],
        zeta1: m1.zeta[0],
        zeta2: m2.zeta[0],
        period_ratio: m2.omega[0] / m1.omega[0],
    };
    let row = |key: &str, label: &str, clause: Option<String>, required: f64| RuleCheck {
        key: key.into(),
        label: label.into(),
        clause,
        required,
        margin: gap - required,
        sufficient: gap >= required,
        vs_exact_percent: vs_exact(required, exact),
    };
    let mut rules = Vec::new();
    if let Some(e) = exact {
        rules.push(RuleCheck {
            vs_exact_percent: None,
            ..row(
                "time_history",
                "time history, max(w1 − w2) (exact)",
                None,
                e,
            )
        });
    }
    rules.push(row("abs", "ABS  w1 + w2", None, pair.separation(Rule::Abs)));
    rules.push(row(
        "srss",
        "SRSS √(w1² + w2²)",
        None,
        pair.separation(Rule::Srss),
    ));
    rules.push(row(
        "ddc",
        "DDC  √(w1² + w2² − 2ρ w1 w2)",
        None,
        pair.separation(Rule::Ddc),
    ));
    if let Some(s) = &input.spectral {
        rules.push(row(
            "ddc_modes",
            "DDC, all modes: CQC of w1(h) − w2(h)",
            None,
            s.cqc,
        ));
    }
    rules.push(row(
        "ddc_paper",
        "ddc-paper (eq. 22–23 as printed)",
        None,
        pair.separation(Rule::DdcPaper),
    ));
    let codes = code_checks(
        r.design,
        r.codes,
        input.peaks,
        r.lengths,
        input.height,
        gap,
        exact,
        input.floors_coincide,
    )?;
    for c in &codes {
        rules.push(row(c.key, c.name, Some(c.clause.into()), c.required));
    }
    Ok(LevelCheck {
        height: input.height,
        gap,
        floors_coincide: input.floors_coincide,
        peaks: input.peaks,
        exact,
        spectral: input.spectral,
        rules,
        codes,
    })
}

impl Verdict {
    /// No rule (nothing was computed).
    pub fn is_empty(&self) -> bool {
        self.rules.is_empty()
    }
}

/// Each rule at its governing level (smallest gap − required; the first such level in the
/// order given on a tie) and the rule with the smallest margin of all.
pub fn verdict(levels: &[LevelCheck]) -> Verdict {
    let Some(first) = levels.first() else {
        return Verdict::default();
    };
    let mut rules = Vec::new();
    for (i, rule) in first.rules.iter().enumerate() {
        let mut worst: Option<(&LevelCheck, &RuleCheck)> = None;
        let mut all = true;
        for l in levels {
            let Some(x) = l.rules.get(i).filter(|x| x.key == rule.key) else {
                continue;
            };
            all &= x.sufficient;
            if worst.is_none_or(|(_, w)| x.margin < w.margin) {
                worst = Some((l, x));
            }
        }
        if let Some((l, x)) = worst {
            rules.push(Governing {
                key: x.key.clone(),
                label: x.label.clone(),
                height: l.height,
                gap: l.gap,
                required: x.required,
                margin: x.margin,
                sufficient: all,
            });
        }
    }
    let governing = rules
        .iter()
        .fold(None::<&Governing>, |m, g| match m {
            Some(m) if m.margin <= g.margin => Some(m),
            _ => Some(g),
        })
        .cloned();
    Verdict {
        insufficient: rules.iter().filter(|g| !g.sufficient).count(),
        rules,
        governing,
    }
}

/// The per-level checks of a run (summary.json `separation.levels` and `verdict`, and the
/// codes at the main level, `separation.codes`) from its run without contact `without`, whose
/// levels are the scenario's contact levels in order; `models` the modal models the run used.
pub fn complete_run_separation(
    scenario: &Scenario,
    models: &[ModalModel],
    without: &RunRecord,
    separation: &mut Separations,
) -> Result<(), CodeError> {
    separation.peaks_from = PeakSource::of_time_history(scenario);
    let lengths = [0, 1].map(|i| scenario.structures[i].length());
    separation.codes = code_checks(
        &scenario.design,
        None,
        without.peak,
        lengths,
        scenario.main_height(),
        main_gap(scenario),
        Some(separation.time_history),
        floors_coincide(&scenario.structures, scenario.main_height()),
    )?;
    let r = RuleInputs {
        design: &scenario.design,
        codes: None,
        lengths,
        models: [&models[0], &models[1]],
    };
    let levels = scenario
        .contact
        .levels
        .iter()
        .zip(&without.levels)
        .map(|(lv, rec)| {
            level_check(
                &r,
                LevelInput {
                    height: lv.height,
                    gap: lv.gap,
                    peaks: [rec.peak_w1, rec.peak_w2],
                    exact: Some(rec.max_closing.max(0.0)),
                    spectral: None,
                    floors_coincide: floors_coincide(&scenario.structures, lv.height),
                },
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    separation.verdict = verdict(&levels);
    separation.levels = levels;
    Ok(())
}

/// Every rule side by side, plus the exact time-history value, m: `abs` … `rho` and `codes` at
/// the main (highest) contact level; `levels` and `verdict` at every level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Separations {
    /// ABS, m.
    pub abs: f64,
    /// SRSS, m.
    pub srss: f64,
    /// DDC with the CQC correlation, m.
    pub ddc: f64,
    /// DDC as printed in the paper, m.
    pub ddc_paper: f64,
    /// `max_t [w₁(h,t) − w₂(h,t)]` without pounding (0 if they only move apart), m: the
    /// smallest gap at which the structures do not touch.
    pub time_history: f64,
    /// CQC correlation ρ₁₂ used by DDC.
    pub rho: f64,
    /// The building codes of the scenario's `[separation]` table at the main contact level
    /// (empty without it).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub codes: Vec<CodeCheck>,
    /// Where the peaks fed to the rules come from (the run without pounding: elastic, or
    /// inelastic with yielding storeys).
    pub peaks_from: PeakSource,
    /// Every rule at every contact level, in the order of the scenario's levels (as the
    /// report's `levels`); empty when not computed.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub levels: Vec<LevelCheck>,
    /// Each rule at its governing level (the smallest gap − required over the levels).
    #[serde(skip_serializing_if = "Verdict::is_empty")]
    pub verdict: Verdict,
}

impl Separations {
    /// All rules for `peaks`, with the time-history value `exact` (m).
    pub fn new(peaks: &PeakPair, exact: f64) -> Separations {
        Separations {
            abs: peaks.separation(Rule::Abs),
            srss: peaks.separation(Rule::Srss),
            ddc: peaks.separation(Rule::Ddc),
            ddc_paper: peaks.separation(Rule::DdcPaper),
            time_history: exact.max(0.0),
            rho: cqc_correlation(peaks.zeta1, peaks.zeta2, peaks.period_ratio),
            codes: Vec::new(),
            peaks_from: PeakSource::TimeHistory,
            levels: Vec::new(),
            verdict: Default::default(),
        }
    }
}
