//! The spectrum keys of `[ground_motion]` (`kind = "spectrum"`) and `--spectrum`.

use std::path::Path;

use toml::Spanned;

use crate::codes::spectrum::{
    Asce7Spectrum, DesignSpectrum, Ec8Spectrum, Ec8Type, GroundType, SpectrumTable,
};
use crate::input::scenario::RawGround;
use crate::input::scenario::diagnostics::{Check, Ctx, ScenarioError};
use crate::model::ground_motion::STANDARD_GRAVITY;

/// A spectrum given on the command line (`--spectrum`): `asce7:sds=1.0,sd1=0.6,tl=8`,
/// `ec8:ag=0.25g,ground_type=C,type=1` (a_g with its unit: `0.25g`, `2.45m/s2`, or a bare
/// number with `units=g` / `units=m/s2` — a bare a_g is refused, since 0.25 read as m/s² is
/// ten times too small), `table:FILE[,units=g]` (the file relative to the working directory).
/// Checked exactly as the scenario keys of the same names.
pub fn spectrum_from_arg(arg: &str) -> Result<DesignSpectrum, ScenarioError> {
    let bad = |reason: String| ScenarioError::Invalid {
        at: crate::input::scenario::diagnostics::Location::file("--spectrum"),
        key: "--spectrum".into(),
        value: arg.to_string(),
        reason,
    };
    let usage = "expected asce7:sds=…,sd1=…,tl=… or ec8:ag=…g|…m/s2,ground_type=A…E,type=1|2 \
                 or table:FILE[,units=g]";
    let (name, rest) = arg.split_once(':').unwrap_or((arg, ""));
    let mut text = format!(
        "kind = \"spectrum\"\nspectrum = {}\n",
        toml_string(name.trim())
    );
    // a_g's unit: from a suffix of its value or from `units`
    let (mut ag, mut ag_unit, mut units) = (None, None, false);
    for (i, item) in rest.split(',').filter(|s| !s.trim().is_empty()).enumerate() {
        let (k, mut v) = match item.split_once('=') {
            Some((k, v)) => (k.trim(), v.trim()),
            None if i == 0 && name.trim() == "table" => ("file", item.trim()),
            None => return Err(bad(format!("`{item}` is not key=value; {usage}"))),
        };
        if !k.chars().all(|ch| ch.is_ascii_alphanumeric() || ch == '_') || k.is_empty() {
            return Err(bad(format!("`{k}` is not a key; {usage}")));
        }
        units |= k == "units";
        if k == "ag" {
            ag = Some(v.to_string());
            for (suffix, unit) in [
                ("m/s2", "m/s2"),
                ("m/s^2", "m/s2"),
                ("m/s²", "m/s2"),
                ("g", "g"),
            ] {
                if let Some(x) = v.strip_suffix(suffix) {
                    v = x.trim();
                    ag_unit = Some(unit);
                    break;
                }
            }
        }
        let value = match k {
            "file" | "units" | "ground_type" => toml_string(v),
            _ if v.parse::<f64>().is_ok() => v.to_string(),
            _ => return Err(bad(format!("`{k}` = `{v}` is not a number"))),
        };
        text.push_str(&format!("{k} = {value}\n"));
    }
    match (ag, ag_unit, units) {
        (Some(v), Some(_), true) => {
            return Err(bad(format!(
                "`ag` = `{v}` has a unit and `units` is given too: give one of them"
            )));
        }
        (Some(_), Some(u), false) => text.push_str(&format!("units = {}\n", toml_string(u))),
        (Some(v), None, false) => {
            return Err(bad(format!(
                "`ag` = `{v}` needs its unit: ag={v}g if a_g is in g, ag={v}m/s2 if in m/s² (as \
                 EN 1998-1 writes it), or add units=g / units=m/s2"
            )));
        }
        _ => {}
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

/// Below this a_g (m/s², 0.15 g) without `units` the scenario warns that it is probably in g:
/// EN 1998-1 a_g values in m/s² are mostly 0.5–5 m/s², while in g they are below 1; a value
/// under 1.5 m/s² is a low-seismicity site or, more likely, a number in g.
pub const AG_PROBABLY_IN_G: f64 = 1.5;

fn toml_string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// The spectrum of `[ground_motion]` when kind = "spectrum"; with another kind, an error if a
/// spectrum key is present. `prefix` is prepended to key names in messages.
pub(super) fn spectrum(
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
        ("scale_to_sa", g.scale_to_sa.is_some()),
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
                let x = range(ag, "ag", 0.0, 30.0, "m/s² (units = \"g\" to give it in g)")?;
                if g.units.is_none() && x < AG_PROBABLY_IN_G {
                    c.ctx.warnings.borrow_mut().push(format!(
                        "`{}` = {x} is read in m/s² ({:.3} g), a low design ground acceleration: \
                         if it is in g, add {}units = \"g\"",
                        key("ag"),
                        x / STANDARD_GRAVITY,
                        prefix
                    ));
                }
                x
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
    let text = crate::input::file::read_text(path, crate::input::file::MAX_TEXT_BYTES)
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
