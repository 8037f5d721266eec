//! Scenario inputs of issue 13: a design spectrum as the ground motion of `pounding separation`
//! (`[ground_motion] kind = "spectrum"`) and the building-code factors of `[separation]`.
//!
//! The raw serde structs of `[separation]` and the checks of every key live here; the checked
//! result is a [`DesignInputs`] in [`crate::input::scenario::Scenario::design`]. Errors are
//! [`ScenarioError`]s with file:line:col, the key and the allowed range, like the rest of a
//! scenario. The formulas are in [`crate::codes::spectrum`] and [`crate::codes::rules`] (docs/codes.md);
//! the conversion of the elastic displacement computed here into the displacement a code
//! multiplies is [`ToDesign`]: ASCE 7's δ_max = δ_elastic I_e/R (§12.9.1.2, needs `r`), or a
//! factor the user states (`displacement_factor`). No factor is ever assumed.

mod code_tables;
mod spectrum_keys;

use std::path::Path;

use toml::Spanned;

use crate::codes::rules::CodeRule;
use crate::codes::spectrum::DesignSpectrum;
use crate::input::scenario::RawGround;
use crate::input::scenario::diagnostics::{Check, ScenarioError};

pub(crate) use code_tables::RawSeparation;
pub use spectrum_keys::{read_table, spectrum_from_arg};

/// The codes of `[separation]`, in the order they are reported (keys as in the scenario, the
/// `--code` flag and the sweep columns `sep_<key>`).
/// (`ec8` is last so that the five older keys keep their sweep columns, see
/// [`crate::study::sweep::results::CODE_FIELDS`].)
pub const CODE_KEYS: [&str; 6] = ["asce7", "is1893", "nbcc", "gb50011", "ntc", "ec8"];

/// How the peak displacement at a contact level computed by `pounding` (from the time history
/// without pounding — elastic, or inelastic where storeys yield — or the CQC of a design
/// spectrum) becomes the displacement a code multiplies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ToDesign {
    /// The code uses no displacement (GB 50011 §6.1.4; NTC-Sismo's simplified method).
    NotUsed,
    /// ASCE 7-16 §12.9.1.2: the elastic displacement divided by R/I_e, δ_max = δ_e I_e/R, with
    /// R (Table 12.2-1) of each structure; δ_M = C_d δ_max/I_e is then C_d/R × δ_e.
    Asce7R {
        /// R of structure 1 and 2.
        r: [f64; 2],
    },
    /// The user's factor: the code's displacement = factor × the elastic displacement.
    Factor([f64; 2]),
    /// EN 1998-1: d_e, the displacement on the design spectrum of §3.2.2.5, taken as the
    /// elastic displacement divided by the behaviour factor q of each structure (the design
    /// spectrum is the elastic one divided by q on its plateau and descending branch at 5 %
    /// damping; docs/codes.md says where it is not). The rule then forms d_s = q_d d_e.
    Ec8 {
        /// q of structure 1 and 2.
        q: [f64; 2],
    },
}

impl ToDesign {
    /// The code's displacements of both structures from their elastic ones (m).
    pub fn apply(&self, rule: &CodeRule, elastic: [f64; 2]) -> [f64; 2] {
        match (self, rule) {
            (ToDesign::NotUsed, _) => [0.0; 2],
            (ToDesign::Asce7R { r }, CodeRule::Asce7(p)) => {
                [0, 1].map(|i| elastic[i] * p.ie[i] / r[i])
            }
            // R without I_e is not a rule of any other code
            (ToDesign::Asce7R { r }, _) => [0, 1].map(|i| elastic[i] / r[i]),
            (ToDesign::Factor(f), _) => [0, 1].map(|i| elastic[i] * f[i]),
            (ToDesign::Ec8 { q }, _) => [0, 1].map(|i| elastic[i] / q[i]),
        }
    }

    /// One line for reports: how the displacement was obtained.
    pub fn describe(&self) -> String {
        match self {
            ToDesign::NotUsed => "no displacement used".into(),
            ToDesign::Asce7R { r } => {
                format!("δ_max = δ_elastic·I_e/R (§12.9.1.2), R = {}", pair_text(*r))
            }
            ToDesign::Factor(f) => format!(
                "displacement = {} × elastic (displacement_factor)",
                pair_text(*f)
            ),
            ToDesign::Ec8 { q } => format!(
                "d_e = d_elastic/q (design spectrum §3.2.2.5 = elastic/q), q = {}",
                pair_text(*q)
            ),
        }
    }
}

fn pair_text(v: [f64; 2]) -> String {
    // at most 6 decimals, trailing zeros dropped
    let t = |x: f64| {
        let s = format!("{x:.6}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    if v[0] == v[1] {
        t(v[0])
    } else {
        format!("[{}, {}]", t(v[0]), t(v[1]))
    }
}

/// One code of `[separation]`, checked: the rule and how its displacements are obtained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CodeSpec {
    /// The rule with its factors.
    pub rule: CodeRule,
    /// Elastic → code displacement.
    pub to_design: ToDesign,
}

/// The issue-13 inputs of a scenario: a design spectrum and the code factors (both optional).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DesignInputs {
    /// `[ground_motion] kind = "spectrum"`: the spectrum (the scenario then has no time
    /// history: `pounding run` refuses it, `pounding separation` uses it).
    pub spectrum: Option<DesignSpectrum>,
    /// The codes of `[separation]`, in the order of [`CODE_KEYS`].
    pub codes: Vec<CodeSpec>,
}

impl DesignInputs {
    /// The code with short key `key` ("asce7", …), if the scenario gives its factors.
    pub fn code(&self, key: &str) -> Option<&CodeSpec> {
        self.codes.iter().find(|c| c.rule.key() == key)
    }
}

/// Check the spectrum keys of `[ground_motion]` and the `[separation]` table (the hook of
/// [`crate::input::scenario`]'s validation). `kind` itself was checked before.
pub(crate) fn validate(
    c: &Check,
    ground: Option<&Spanned<RawGround>>,
    separation: Option<&Spanned<RawSeparation>>,
    base_dir: &Path,
    defaults: &mut Vec<String>,
) -> Result<DesignInputs, ScenarioError> {
    let spectrum = match ground {
        Some(g) => spectrum_keys::spectrum(c, g, base_dir, "ground_motion.")?,
        None => None,
    };
    let codes = match separation {
        Some(s) => code_tables::codes(c, s, defaults)?,
        None => Vec::new(),
    };
    Ok(DesignInputs { spectrum, codes })
}

/// The spectrum of a table of spectrum keys (`kind` set to "spectrum"): the target of a
/// suite's scaling ([`crate::input::scenario::suite`]); `prefix` names its keys in messages.
pub(crate) fn target_spectrum(
    c: &Check,
    raw: &Spanned<RawGround>,
    base_dir: &Path,
    prefix: &str,
) -> Result<DesignSpectrum, ScenarioError> {
    spectrum_keys::spectrum(c, raw, base_dir, prefix)?.ok_or_else(|| {
        c.missing(
            &format!("{prefix}spectrum"),
            "\"asce7\", \"ec8\" or \"table\"",
            Some(raw.span().start),
        )
    })
}

/// A number or two numbers `[structure 1, structure 2]` in `[lo, hi]` (`open_lo`: `(lo, hi]`).
fn per_structure(
    c: &Check,
    v: &Spanned<toml::Value>,
    key: &str,
    (lo, hi, open_lo): (f64, f64, bool),
    what: &str,
) -> Result<[f64; 2], ScenarioError> {
    let num = |x: &toml::Value| match x {
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::Float(f) => Some(*f),
        _ => None,
    };
    let ok = |x: f64| x.is_finite() && x <= hi && if open_lo { x > lo } else { x >= lo };
    let range = if open_lo {
        format!("({lo}, {hi}]")
    } else {
        format!("[{lo}, {hi}]")
    };
    let reason = format!(
        "{what} must be a number in {range}, or two such numbers [structure 1, structure 2]"
    );
    let vals = match v.get_ref() {
        toml::Value::Array(a) if a.len() == 2 => [num(&a[0]), num(&a[1])],
        x => [num(x), num(x)],
    };
    match vals {
        [Some(a), Some(b)] if ok(a) && ok(b) => Ok([a, b]),
        _ => Err(c.invalid(v, key, &reason)),
    }
}
