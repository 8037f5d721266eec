//! The code tables of `[separation]`: raw serde structs and every key's check.

use serde::Deserialize;
use toml::Spanned;

use super::{CodeSpec, ToDesign, per_structure};
use crate::codes::rules::{
    Asce7Boundary, Asce7Params, CodeRule, Ec8Boundary, Ec8Params, Gb50011Params, GbSystem,
    Is1893Params, NbccParams, NtcMethod, NtcParams, NtcZone, PartialStep,
};
use crate::input::scenario::diagnostics::{Check, ScenarioError};

/// `[separation]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSeparation {
    asce7: Option<Spanned<RawAsce7>>,
    is1893: Option<Spanned<RawIs1893>>,
    nbcc: Option<Spanned<RawNbcc>>,
    gb50011: Option<Spanned<RawGb>>,
    ntc: Option<Spanned<RawNtc>>,
    ec8: Option<Spanned<RawEc8>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEc8 {
    q: Option<Spanned<toml::Value>>,
    qd: Option<Spanned<toml::Value>>,
    boundary: Option<Spanned<String>>,
    floor_reduction: Option<Spanned<toml::Value>>,
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
    floor_reduction: Option<Spanned<toml::Value>>,
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

/// Each code table of `[separation]`, checked.
pub(super) fn codes(
    c: &Check,
    raw: &Spanned<RawSeparation>,
    defaults: &mut Vec<String>,
) -> Result<Vec<CodeSpec>, ScenarioError> {
    let s = raw.get_ref();
    let mut out = Vec::new();
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
                    "give either `r` (δ_max = δ_elastic·I_e/R, §12.9.1.2) or \
                     `displacement_factor`, not both",
                ));
            }
            (None, None) => {
                return Err(c.missing(
                    "separation.asce7.r",
                    "R of Table 12.2-1, to obtain δ_max = δ_elastic·I_e/R from the elastic \
                     displacement computed here (§12.9.1.2); or `displacement_factor` = δ_max / \
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
        let floor_reduction = floor_reduction(
            c,
            &a.floor_reduction,
            "separation.is1893.floor_reduction",
            "R/2",
            defaults,
        )?;
        out.push(CodeSpec {
            rule: CodeRule::Is1893(Is1893Params {
                r: r[0],
                floor_reduction,
            }),
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
    if let Some(t) = &s.ec8 {
        let near = t.span().start;
        let a = t.get_ref();
        let q = per_structure(
            c,
            c.required(
                &a.q,
                "separation.ec8.q",
                "behaviour factor q of each structure (EN 1998-1 §3.2.2.5): d_e, the displacement \
                 on the design spectrum, is taken as the elastic displacement computed here \
                 divided by q",
                Some(near),
            )?,
            "separation.ec8.q",
            FORCE_FACTOR,
            "q (behaviour factor)",
        )?;
        let qd = match &a.qd {
            Some(v) => per_structure(
                c,
                v,
                "separation.ec8.qd",
                FORCE_FACTOR,
                "q_d (displacement behaviour factor, §4.3.4)",
            )?,
            None => {
                defaults.push("separation.ec8.qd = q (§4.3.4)".into());
                q
            }
        };
        let boundary = match &a.boundary {
            None => {
                defaults.push("separation.ec8.boundary = \"same-property\"".into());
                Ec8Boundary::SameProperty
            }
            Some(b) => match b.get_ref().as_str() {
                "same-property" => Ec8Boundary::SameProperty,
                "property-line" => Ec8Boundary::PropertyLine,
                _ => {
                    return Err(c.invalid(
                        b,
                        "separation.ec8.boundary",
                        "must be \"same-property\" (√(d_s1² + d_s2²), §4.4.2.7(2)b) or \
                         \"property-line\" (each building its own d_s from the line: d_s1 + d_s2, \
                         §4.4.2.7(2)a)",
                    ));
                }
            },
        };
        let floor_reduction = floor_reduction(
            c,
            &a.floor_reduction,
            "separation.ec8.floor_reduction",
            "× 0.7",
            defaults,
        )?;
        out.push(CodeSpec {
            rule: CodeRule::Ec8(Ec8Params {
                qd,
                boundary,
                floor_reduction,
            }),
            to_design: ToDesign::Ec8 { q },
        });
    }
    Ok(out)
}

/// `floor_reduction` of EC8 / IS 1893 (`what` the reduction): on unless the scenario turns it
/// off (recorded as a default when left out).
fn floor_reduction(
    c: &Check,
    v: &Option<Spanned<toml::Value>>,
    key: &str,
    what: &str,
    defaults: &mut Vec<String>,
) -> Result<bool, ScenarioError> {
    match v {
        Some(b) => b.get_ref().as_bool().ok_or_else(|| {
            c.invalid(
                b,
                key,
                &format!(
                    "must be true (the {what} where a contact level is a floor of both \
                     structures) or false (never)"
                ),
            )
        }),
        None => {
            defaults.push(format!(
                "{key} = true (the {what} where a contact level is a floor of both structures)"
            ));
            Ok(true)
        }
    }
}
