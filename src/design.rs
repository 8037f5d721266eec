//! Scenario inputs of issue 13: a design spectrum as the ground motion of `pounding separation`
//! (`[ground_motion] kind = "spectrum"`) and the building-code factors of `[separation]`.
//!
//! The raw serde structs of `[separation]` and the checks of every key live here; the checked
//! result is a [`DesignInputs`] in [`crate::scenario::Scenario::design`]. Errors are
//! [`ScenarioError`]s with file:line:col, the key and the allowed range, like the rest of a
//! scenario. The formulas are in [`crate::spectrum`] and [`crate::codes`] (docs/codes.md);
//! the conversion of the elastic displacement computed here into the displacement a code
//! multiplies is [`ToDesign`]: ASCE 7's δ_max = δ_elastic I_e/R (§12.9.1.4, needs `r`), or a
//! factor the user states (`displacement_factor`). No factor is ever assumed.

use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::codes::{
    Asce7Boundary, Asce7Params, CodeRule, Gb50011Params, GbSystem, Is1893Params, NbccParams,
    NtcMethod, NtcParams, NtcZone, PartialStep,
};
use crate::ground_motion::STANDARD_GRAVITY;
use crate::scenario::{Check, Ctx, RawGround, ScenarioError};
use crate::spectrum::{
    Asce7Spectrum, DesignSpectrum, Ec8Spectrum, Ec8Type, GroundType, SpectrumTable,
};

/// The codes of `[separation]`, in the order they are reported (keys as in the scenario, the
/// `--code` flag and the sweep columns `sep_<key>`).
pub const CODE_KEYS: [&str; 5] = ["asce7", "is1893", "nbcc", "gb50011", "ntc"];

/// Valid keys of the tables of this module, for the scenario's unknown-key suggestions.
pub const TABLES: &[(&str, &[&str])] = &[
    (
        "[separation]",
        &["asce7", "is1893", "nbcc", "gb50011", "ntc", "ec8"],
    ),
    (
        "[separation.asce7]",
        &["cd", "ie", "r", "displacement_factor", "boundary"],
    ),
    ("[separation.is1893]", &["r", "displacement_factor"]),
    (
        "[separation.nbcc]",
        &["rd", "ro", "ie", "displacement_factor"],
    ),
    (
        "[separation.gb50011]",
        &["intensity", "systems", "partial_step"],
    ),
    (
        "[separation.ntc]",
        &[
            "zone",
            "method",
            "same_height_and_levels",
            "displacement_factor",
        ],
    ),
];

/// `[separation]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSeparation {
    asce7: Option<Spanned<RawAsce7>>,
    is1893: Option<Spanned<RawIs1893>>,
    nbcc: Option<Spanned<RawNbcc>>,
    gb50011: Option<Spanned<RawGb>>,
    ntc: Option<Spanned<RawNtc>>,
    /// Refused with the reason (EN 1998-1 §4.4.2.7 could not be verified).
    ec8: Option<Spanned<toml::Value>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAsce7 {
    cd: Option<Spanned<toml::Value>>,
    ie: Option<Spanned<toml::Value>>,
    r: Option<Spanned<toml::Value>>,
    displacement_factor: Option<Spanned<toml::Value>>,
    boundary: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawIs1893 {
    r: Option<Spanned<toml::Value>>,
    displacement_factor: Option<Spanned<toml::Value>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawNbcc {
    rd: Option<Spanned<toml::Value>>,
    ro: Option<Spanned<toml::Value>>,
    ie: Option<Spanned<toml::Value>>,
    displacement_factor: Option<Spanned<toml::Value>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGb {
    intensity: Option<Spanned<toml::Value>>,
    systems: Option<Spanned<toml::Value>>,
    partial_step: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawNtc {
    zone: Option<Spanned<String>>,
    method: Option<Spanned<String>>,
    same_height_and_levels: Option<Spanned<bool>>,
    displacement_factor: Option<Spanned<toml::Value>>,
}

/// How the elastic peak displacement at the contact height computed by `pounding` (from the
/// time history without pounding, or the CQC of a design spectrum) becomes the displacement a
/// code multiplies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ToDesign {
    /// The code uses no displacement (GB 50011 §6.1.4; NTC-Sismo's simplified method).
    NotUsed,
    /// ASCE 7-16 §12.9.1.4: the elastic displacement divided by R/I_e, δ_max = δ_e I_e/R, with
    /// R (Table 12.2-1) of each structure; δ_M = C_d δ_max/I_e is then C_d/R × δ_e.
    Asce7R {
        /// R of structure 1 and 2.
        r: [f64; 2],
    },
    /// The user's factor: the code's displacement = factor × the elastic displacement.
    Factor([f64; 2]),
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
        }
    }

    /// One line for reports: how the displacement was obtained.
    pub fn describe(&self) -> String {
        match self {
            ToDesign::NotUsed => "no displacement used".into(),
            ToDesign::Asce7R { r } => {
                format!("δ_max = δ_elastic·I_e/R (§12.9.1.4), R = {}", pair_text(*r))
            }
            ToDesign::Factor(f) => format!(
                "displacement = {} × elastic (displacement_factor)",
                pair_text(*f)
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
/// [`crate::scenario`]'s validation). `kind` itself was checked before.
pub(crate) fn validate(
    c: &Check,
    ground: Option<&Spanned<RawGround>>,
    separation: Option<&Spanned<RawSeparation>>,
    base_dir: &Path,
    defaults: &mut Vec<String>,
) -> Result<DesignInputs, ScenarioError> {
    let spectrum = match ground {
        Some(g) => spectrum(c, g, base_dir, "ground_motion.")?,
        None => None,
    };
    let codes = match separation {
        Some(s) => codes(c, s, defaults)?,
        None => Vec::new(),
    };
    Ok(DesignInputs { spectrum, codes })
}

/// A spectrum given on the command line (`--spectrum`): `asce7:sds=1.0,sd1=0.6,tl=8`,
/// `ec8:ag=2.5,ground_type=C,type=1[,units=g]`, `table:FILE[,units=g]` (the file relative to
/// the working directory). Checked exactly as the scenario keys of the same names.
pub fn spectrum_from_arg(arg: &str) -> Result<DesignSpectrum, ScenarioError> {
    let bad = |reason: String| ScenarioError::Invalid {
        at: crate::scenario::Location {
            file: "--spectrum".into(),
            line_col: None,
        },
        key: "--spectrum".into(),
        value: arg.to_string(),
        reason,
    };
    let usage = "expected asce7:sds=…,sd1=…,tl=… or ec8:ag=…,ground_type=A…E,type=1|2[,units=g] \
                 or table:FILE[,units=g]";
    let (name, rest) = arg.split_once(':').unwrap_or((arg, ""));
    let mut text = format!(
        "kind = \"spectrum\"\nspectrum = {}\n",
        toml_string(name.trim())
    );
    for (i, item) in rest.split(',').filter(|s| !s.trim().is_empty()).enumerate() {
        let (k, v) = match item.split_once('=') {
            Some((k, v)) => (k.trim(), v.trim()),
            None if i == 0 && name.trim() == "table" => ("file", item.trim()),
            None => return Err(bad(format!("`{item}` is not key=value; {usage}"))),
        };
        if !k.chars().all(|ch| ch.is_ascii_alphanumeric() || ch == '_') || k.is_empty() {
            return Err(bad(format!("`{k}` is not a key; {usage}")));
        }
        let value = match k {
            "file" | "units" | "ground_type" => toml_string(v),
            _ if v.parse::<f64>().is_ok() => v.to_string(),
            _ => return Err(bad(format!("`{k}` = `{v}` is not a number"))),
        };
        text.push_str(&format!("{k} = {value}\n"));
    }
    let ctx = Ctx {
        text: &text,
        file: "--spectrum",
        name: "--spectrum".into(),
        warnings: Default::default(),
    };
    let c = Check { ctx: &ctx };
    let forget_place = |e: ScenarioError| match e {
        ScenarioError::Invalid {
            key, value, reason, ..
        } => bad(format!("`{key}` = {value}: {reason}")),
        ScenarioError::Missing { key, expected, .. } => bad(format!("missing `{key}`: {expected}")),
        ScenarioError::UnknownKey { key, hint, .. } => bad(format!("unknown key `{key}`{hint}")),
        other => bad(other.to_string()),
    };
    let raw: RawGround = toml::from_str(&text).map_err(|e| forget_place(ctx.toml_error(&e)))?;
    let spanned = Spanned::new(0..0, raw);
    match spectrum(&c, &spanned, Path::new("."), "").map_err(forget_place)? {
        Some(s) => Ok(s),
        None => Err(bad(usage.into())),
    }
}

fn toml_string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// The spectrum of `[ground_motion]` when kind = "spectrum"; with another kind, an error if a
/// spectrum key is present. `prefix` is prepended to key names in messages.
fn spectrum(
    c: &Check,
    raw: &Spanned<RawGround>,
    base_dir: &Path,
    prefix: &str,
) -> Result<Option<DesignSpectrum>, ScenarioError> {
    let near = Some(raw.span().start);
    let g = raw.get_ref();
    let kind = g.kind.as_ref().map_or("", |k| k.get_ref().as_str());
    let key = |k: &str| format!("{prefix}{k}");
    let given = |k: &str, present: bool| -> Result<(), ScenarioError> {
        if present {
            Err(ScenarioError::Invalid {
                at: c.ctx.at(near),
                key: key(k),
                value: "(given)".into(),
                reason: format!("not used with kind = \"{kind}\""),
            })
        } else {
            Ok(())
        }
    };
    let spectrum_keys = [
        ("spectrum", g.spectrum.is_some()),
        ("sds", g.sds.is_some()),
        ("sd1", g.sd1.is_some()),
        ("tl", g.tl.is_some()),
        ("ag", g.ag.is_some()),
        ("ground_type", g.ground_type.is_some()),
        ("type", g.spectrum_type.is_some()),
    ];
    if kind != "spectrum" {
        for (k, p) in spectrum_keys {
            given(k, p)?;
        }
        return Ok(None);
    }
    for (k, p) in [
        ("pga", g.pga.is_some()),
        ("period", g.period.is_some()),
        ("scale_to_pga", g.scale_to_pga.is_some()),
        ("dt", g.dt.is_some()),
    ] {
        given(k, p)?;
    }
    let name = c.required(
        &g.spectrum,
        &key("spectrum"),
        "\"asce7\" (ASCE 7-16 §11.4.6), \"ec8\" (EN 1998-1 §3.2.2.2) or \"table\" (T, S_a pairs)",
        near,
    )?;
    let kind = name.get_ref().as_str();
    let range = |v: &Spanned<f64>, k: &str, lo: f64, hi: f64, unit: &str| {
        let x = *v.get_ref();
        if x.is_finite() && x > lo && x <= hi {
            Ok(x)
        } else {
            Err(c.invalid(v, &key(k), &format!("must be in ({lo}, {hi}] {unit}")))
        }
    };
    let units = |what: &str| -> Result<f64, ScenarioError> {
        match &g.units {
            None => Ok(1.0),
            Some(u) => match u.get_ref().as_str() {
                "g" => Ok(STANDARD_GRAVITY),
                "m/s2" | "m/s^2" | "m/s²" => Ok(1.0),
                _ => Err(c.invalid(
                    u,
                    &key("units"),
                    &format!("must be \"g\" or \"m/s2\" (the unit of {what})"),
                )),
            },
        }
    };
    let spectrum = match kind {
        "asce7" => {
            for (k, p) in [
                ("ag", g.ag.is_some()),
                ("ground_type", g.ground_type.is_some()),
                ("type", g.spectrum_type.is_some()),
                ("file", g.file.is_some()),
                ("units", g.units.is_some()),
            ] {
                if p {
                    return Err(ScenarioError::Invalid {
                        at: c.ctx.at(near),
                        key: key(k),
                        value: "(given)".into(),
                        reason:
                            "not used with spectrum = \"asce7\" (S_DS and S_D1 are in g, T_L in s)"
                                .into(),
                    });
                }
            }
            let sds = c.required(&g.sds, &key("sds"), "S_DS in g (ASCE 7-16 §11.4.5)", near)?;
            let sd1 = c.required(&g.sd1, &key("sd1"), "S_D1 in g (ASCE 7-16 §11.4.5)", near)?;
            let tl = c.required(
                &g.tl,
                &key("tl"),
                "long-period transition period T_L in s (ASCE 7-16 §11.4.6)",
                near,
            )?;
            let (a, b, t) = (
                range(sds, "sds", 0.0, 5.0, "g")?,
                range(sd1, "sd1", 0.0, 5.0, "g")?,
                range(tl, "tl", 0.0, 20.0, "s")?,
            );
            let s = Asce7Spectrum::new(a, b, t)
                .map_err(|e| c.invalid(tl, &key("tl"), &e.to_string()))?;
            DesignSpectrum::Asce7(s)
        }
        "ec8" => {
            for (k, p) in [
                ("sds", g.sds.is_some()),
                ("sd1", g.sd1.is_some()),
                ("tl", g.tl.is_some()),
                ("file", g.file.is_some()),
            ] {
                if p {
                    return Err(ScenarioError::Invalid {
                        at: c.ctx.at(near),
                        key: key(k),
                        value: "(given)".into(),
                        reason:
                            "not used with spectrum = \"ec8\" (keys: ag, units, ground_type, type)"
                                .into(),
                    });
                }
            }
            let scale = units("ag")?;
            let ag = c.required(
                &g.ag,
                &key("ag"),
                "design ground acceleration a_g on type A ground, in m/s² (or in g with units = \"g\")",
                near,
            )?;
            let ag_si = if scale == 1.0 {
                range(ag, "ag", 0.0, 30.0, "m/s² (units = \"g\" to give it in g)")?
            } else {
                range(ag, "ag", 0.0, 3.0, "g (units = \"g\")")? * scale
            };
            let gt = c.required(
                &g.ground_type,
                &key("ground_type"),
                "EN 1998-1 ground type \"A\" … \"E\" (Table 3.1)",
                near,
            )?;
            let ground = match gt.get_ref().as_str() {
                "A" => GroundType::A,
                "B" => GroundType::B,
                "C" => GroundType::C,
                "D" => GroundType::D,
                "E" => GroundType::E,
                _ => {
                    return Err(c.invalid(
                        gt,
                        &key("ground_type"),
                        "must be \"A\", \"B\", \"C\", \"D\" or \"E\" (EN 1998-1 Table 3.1; S1 and S2 need special studies)",
                    ));
                }
            };
            let ty = c.required(
                &g.spectrum_type,
                &key("type"),
                "1 or 2 (EN 1998-1 §3.2.2.2(2)P: Type 1 for M_s > 5.5, Type 2 otherwise)",
                near,
            )?;
            let ty = match ty.get_ref() {
                toml::Value::Integer(1) => Ec8Type::Type1,
                toml::Value::Integer(2) => Ec8Type::Type2,
                _ => {
                    return Err(c.invalid(
                        ty,
                        &key("type"),
                        "must be 1 or 2 (EN 1998-1 §3.2.2.2(2)P, Tables 3.2 and 3.3)",
                    ));
                }
            };
            let s = Ec8Spectrum::new(ag_si, ground, ty)
                .map_err(|e| c.invalid(ag, &key("ag"), &e.to_string()))?;
            DesignSpectrum::Ec8(s)
        }
        "table" => {
            for (k, p) in [
                ("sds", g.sds.is_some()),
                ("sd1", g.sd1.is_some()),
                ("tl", g.tl.is_some()),
                ("ag", g.ag.is_some()),
                ("ground_type", g.ground_type.is_some()),
                ("type", g.spectrum_type.is_some()),
            ] {
                if p {
                    return Err(ScenarioError::Invalid {
                        at: c.ctx.at(near),
                        key: key(k),
                        value: "(given)".into(),
                        reason: "not used with spectrum = \"table\" (keys: file, units)".into(),
                    });
                }
            }
            let scale = units("S_a")?;
            let file = c.required(
                &g.file,
                &key("file"),
                "a file of (T in s, S_a) pairs, one pair a line, relative to the scenario",
                near,
            )?;
            let path = base_dir.join(file.get_ref());
            let pairs = read_table(&path, scale)
                .map_err(|reason| c.invalid(file, &key("file"), &reason))?;
            let t = SpectrumTable::new(&pairs)
                .map_err(|e| c.invalid(file, &key("file"), &format!("{}: {e}", path.display())))?;
            DesignSpectrum::Table(t)
        }
        _ => {
            return Err(c.invalid(
                name,
                &key("spectrum"),
                "must be \"asce7\", \"ec8\" or \"table\"",
            ));
        }
    };
    Ok(Some(spectrum))
}

/// Pairs (T, S_a × `scale`) of a spectrum file: two numbers a line separated by spaces, tabs or
/// a comma; blank lines and lines starting with `#` skipped; a first line that is not numeric
/// is taken as a header.
pub fn read_table(path: &Path, scale: f64) -> Result<Vec<(f64, f64)>, String> {
    let text = crate::input_file::read_text(path, crate::input_file::MAX_TEXT_BYTES)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut pairs = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = line
            .split(|ch: char| ch == ',' || ch.is_whitespace())
            .filter(|s| !s.is_empty())
            .collect();
        let nums: Option<Vec<f64>> = cols.iter().map(|s| s.parse().ok()).collect();
        match nums {
            Some(v) if v.len() == 2 => pairs.push((v[0], v[1] * scale)),
            None if pairs.is_empty() && i == 0 => continue, // header
            _ => {
                return Err(format!(
                    "{}:{}: expected two numbers `T S_a`, got `{line}`",
                    path.display(),
                    i + 1
                ));
            }
        }
    }
    Ok(pairs)
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

/// Each code table of `[separation]`, checked.
fn codes(
    c: &Check,
    raw: &Spanned<RawSeparation>,
    defaults: &mut Vec<String>,
) -> Result<Vec<CodeSpec>, ScenarioError> {
    let s = raw.get_ref();
    let mut out = Vec::new();
    if let Some(e) = &s.ec8 {
        return Err(c.invalid(
            e,
            "separation.ec8",
            "EN 1998-1 §4.4.2.7 (pounding) could not be verified against a source, so it is not \
             implemented (docs/codes.md, \"Not implemented\"); use asce7, is1893, nbcc, gb50011 \
             or ntc",
        ));
    }
    const FACTOR: (f64, f64, bool) = (0.0, 10.0, true);
    const FORCE_FACTOR: (f64, f64, bool) = (1.0, 10.0, false);
    let factor = |v: &Option<Spanned<toml::Value>>,
                  key: &str|
     -> Result<Option<[f64; 2]>, ScenarioError> {
        v.as_ref()
            .map(|v| {
                per_structure(
                    c,
                    v,
                    key,
                    FACTOR,
                    "the factor from the elastic displacement computed here to the code's displacement",
                )
            })
            .transpose()
    };
    let needs_factor = |near: usize, key: &str, code: &str| {
        c.missing(
            key,
            &format!(
                "the factor that turns the elastic peak displacement computed by pounding (time \
                 history without pounding, or the spectrum's CQC) into the displacement {code} \
                 multiplies — e.g. 1/(R/I) if the code's design forces are the elastic ones \
                 divided by R/I; pounding never assumes one"
            ),
            Some(near),
        )
    };
    if let Some(t) = &s.asce7 {
        let near = t.span().start;
        let a = t.get_ref();
        let cd = per_structure(
            c,
            c.required(
                &a.cd,
                "separation.asce7.cd",
                "deflection amplification factor C_d (ASCE 7-16 Table 12.2-1)",
                Some(near),
            )?,
            "separation.asce7.cd",
            FORCE_FACTOR,
            "C_d",
        )?;
        let ie = per_structure(
            c,
            c.required(
                &a.ie,
                "separation.asce7.ie",
                "importance factor I_e (ASCE 7-16 Table 1.5-2: 1.0, 1.25 or 1.5)",
                Some(near),
            )?,
            "separation.asce7.ie",
            (1.0, 1.5, false),
            "I_e",
        )?;
        let boundary = match &a.boundary {
            None => {
                defaults.push("separation.asce7.boundary = \"same-property\"".into());
                Asce7Boundary::SameProperty
            }
            Some(b) => match b.get_ref().as_str() {
                "same-property" => Asce7Boundary::SameProperty,
                "property-line" => Asce7Boundary::PropertyLine,
                _ => {
                    return Err(c.invalid(
                        b,
                        "separation.asce7.boundary",
                        "must be \"same-property\" (δ_MT = √(δ_M1² + δ_M2²), Eq. 12.12-2) or \
                         \"property-line\" (each set back by its δ_M: δ_M1 + δ_M2)",
                    ));
                }
            },
        };
        let r =
            a.r.as_ref()
                .map(|v| {
                    per_structure(
                        c,
                        v,
                        "separation.asce7.r",
                        FORCE_FACTOR,
                        "R (response modification coefficient, Table 12.2-1)",
                    )
                })
                .transpose()?;
        let f = factor(
            &a.displacement_factor,
            "separation.asce7.displacement_factor",
        )?;
        let to_design = match (r, f) {
            (Some(r), None) => ToDesign::Asce7R { r },
            (None, Some(f)) => ToDesign::Factor(f),
            (Some(_), Some(_)) => {
                let v = a
                    .displacement_factor
                    .as_ref()
                    .unwrap_or_else(|| unreachable!());
                return Err(c.invalid(
                    v,
                    "separation.asce7.displacement_factor",
                    "give either `r` (δ_max = δ_elastic·I_e/R, §12.9.1.4) or \
                     `displacement_factor`, not both",
                ));
            }
            (None, None) => {
                return Err(c.missing(
                    "separation.asce7.r",
                    "R of Table 12.2-1, to obtain δ_max = δ_elastic·I_e/R from the elastic \
                     displacement computed here (§12.9.1.4); or `displacement_factor` = δ_max / \
                     δ_elastic as you determine it",
                    Some(near),
                ));
            }
        };
        out.push(CodeSpec {
            rule: CodeRule::Asce7(Asce7Params { cd, ie, boundary }),
            to_design,
        });
    }
    if let Some(t) = &s.is1893 {
        let near = t.span().start;
        let a = t.get_ref();
        let r = per_structure(
            c,
            c.required(
                &a.r,
                "separation.is1893.r",
                "response reduction factor R (IS 1893 Table 9)",
                Some(near),
            )?,
            "separation.is1893.r",
            FORCE_FACTOR,
            "R",
        )?;
        if r[0] != r[1] {
            let v = a.r.as_ref().unwrap_or_else(|| unreachable!());
            return Err(c.invalid(
                v,
                "separation.is1893.r",
                "§7.11.3 names one R: give one number (the larger of the two systems' R)",
            ));
        }
        let f = factor(
            &a.displacement_factor,
            "separation.is1893.displacement_factor",
        )?
        .ok_or_else(|| {
            needs_factor(
                near,
                "separation.is1893.displacement_factor",
                "IS 1893 §7.11.3 (Δ under the design lateral force)",
            )
        })?;
        out.push(CodeSpec {
            rule: CodeRule::Is1893(Is1893Params { r: r[0] }),
            to_design: ToDesign::Factor(f),
        });
    }
    if let Some(t) = &s.nbcc {
        let near = t.span().start;
        let a = t.get_ref();
        let get = |v: &Option<Spanned<toml::Value>>, k: &str, exp: &str, lim, what| {
            per_structure(
                c,
                c.required(v, &format!("separation.nbcc.{k}"), exp, Some(near))?,
                &format!("separation.nbcc.{k}"),
                lim,
                what,
            )
        };
        let rd = get(
            &a.rd,
            "rd",
            "ductility-related force modification factor R_d",
            FORCE_FACTOR,
            "R_d",
        )?;
        let ro = get(
            &a.ro,
            "ro",
            "overstrength-related force modification factor R_o",
            FORCE_FACTOR,
            "R_o",
        )?;
        let ie = get(
            &a.ie,
            "ie",
            "earthquake importance factor I_E",
            (0.5, 2.0, false),
            "I_E",
        )?;
        let f = factor(
            &a.displacement_factor,
            "separation.nbcc.displacement_factor",
        )?
        .ok_or_else(|| {
            needs_factor(
                near,
                "separation.nbcc.displacement_factor",
                "NBCC 4.1.8.14 (the deflection under the design forces, before × R_dR_o/I_E)",
            )
        })?;
        out.push(CodeSpec {
            rule: CodeRule::Nbcc(NbccParams { rd, ro, ie }),
            to_design: ToDesign::Factor(f),
        });
    }
    if let Some(t) = &s.gb50011 {
        let near = t.span().start;
        let a = t.get_ref();
        let iv = c.required(
            &a.intensity,
            "separation.gb50011.intensity",
            "seismic fortification intensity 6, 7, 8 or 9",
            Some(near),
        )?;
        let intensity = match iv.get_ref() {
            toml::Value::Integer(i @ 6..=9) => *i as u8,
            _ => {
                return Err(c.invalid(
                    iv,
                    "separation.gb50011.intensity",
                    "must be 6, 7, 8 or 9 (GB 50011-2010 §6.1.4 item 1)",
                ));
            }
        };
        let sv = c.required(
            &a.systems,
            "separation.gb50011.systems",
            "the structural system of each side: \"frame\", \"frame-shear-wall\" or \"shear-wall\" (one for both, or [structure 1, structure 2])",
            Some(near),
        )?;
        let sys = |x: &toml::Value| match x.as_str() {
            Some("frame") => Some(GbSystem::Frame),
            Some("frame-shear-wall") => Some(GbSystem::FrameShearWall),
            Some("shear-wall") => Some(GbSystem::ShearWall),
            _ => None,
        };
        let systems = match sv.get_ref() {
            toml::Value::Array(v) if v.len() == 2 => [sys(&v[0]), sys(&v[1])],
            x => [sys(x), sys(x)],
        };
        let system = match systems {
            [Some(a), Some(b)] => [a, b],
            _ => {
                return Err(c.invalid(
                    sv,
                    "separation.gb50011.systems",
                    "must be \"frame\", \"frame-shear-wall\" or \"shear-wall\", or two of them \
                     [structure 1, structure 2] (reinforced-concrete systems of §6.1.4 item 1)",
                ));
            }
        };
        let partial_step = match &a.partial_step {
            None => {
                defaults.push("separation.gb50011.partial_step = \"round-up\"".into());
                PartialStep::RoundUp
            }
            Some(p) => match p.get_ref().as_str() {
                "round-up" => PartialStep::RoundUp,
                "linear" => PartialStep::Linear,
                _ => {
                    return Err(c.invalid(
                        p,
                        "separation.gb50011.partial_step",
                        "must be \"round-up\" (a started height step counts whole) or \"linear\"",
                    ));
                }
            },
        };
        out.push(CodeSpec {
            rule: CodeRule::Gb50011(Gb50011Params {
                intensity,
                system,
                partial_step,
            }),
            to_design: ToDesign::NotUsed,
        });
    }
    if let Some(t) = &s.ntc {
        let near = t.span().start;
        let a = t.get_ref();
        let z = c.required(
            &a.zone,
            "separation.ntc.zone",
            "Mexico City seismic zone \"I\", \"II\" or \"III\"",
            Some(near),
        )?;
        let zone = match z.get_ref().as_str() {
            "I" => NtcZone::I,
            "II" => NtcZone::II,
            "III" => NtcZone::III,
            _ => {
                return Err(c.invalid(
                    z,
                    "separation.ntc.zone",
                    "must be \"I\", \"II\" or \"III\" (NTC-Sismo 2004)",
                ));
            }
        };
        let m = c.required(
            &a.method,
            "separation.ntc.method",
            "\"analysis\" (s = max(50 mm, d + c h)) or \"simplified\" (s = max(50 mm, k h))",
            Some(near),
        )?;
        let method = match m.get_ref().as_str() {
            "analysis" => NtcMethod::Analysis,
            "simplified" => NtcMethod::Simplified,
            _ => {
                return Err(c.invalid(
                    m,
                    "separation.ntc.method",
                    "must be \"analysis\" or \"simplified\" (NTC-Sismo 2004 §1.10)",
                ));
            }
        };
        let same = match &a.same_height_and_levels {
            Some(b) => *b.get_ref(),
            None => {
                defaults.push("separation.ntc.same_height_and_levels = false".into());
                false
            }
        };
        let f = factor(&a.displacement_factor, "separation.ntc.displacement_factor")?;
        let to_design = match (method, f) {
            (NtcMethod::Analysis, Some(f)) => ToDesign::Factor(f),
            (NtcMethod::Analysis, None) => {
                return Err(needs_factor(
                    near,
                    "separation.ntc.displacement_factor",
                    "NTC-Sismo §1.10 (the displacement calculated for the level)",
                ));
            }
            (NtcMethod::Simplified, None) => ToDesign::NotUsed,
            (NtcMethod::Simplified, Some(_)) => {
                let v = a
                    .displacement_factor
                    .as_ref()
                    .unwrap_or_else(|| unreachable!());
                return Err(c.invalid(
                    v,
                    "separation.ntc.displacement_factor",
                    "not used with method = \"simplified\" (s = max(50 mm, k h) uses no displacement)",
                ));
            }
        };
        out.push(CodeSpec {
            rule: CodeRule::NtcSismo(NtcParams {
                zone,
                method,
                same_height_and_levels: same,
            }),
            to_design,
        });
    }
    Ok(out)
}
