//! `[[structure]]`: a cantilever's keys (the kinds with floors are in `floors`), checked into
//! a [`Structure`].

use toml::Spanned;

use crate::model::structure::{Cantilever, Damping, Stiffness, Structure};

use super::diagnostics::{Check, ScenarioError};
use super::{DEFAULT_DAMPING_RATIO, DEFAULT_MODES, MAX_MODES};
use super::{RawStructure, RawZeta};

pub(super) fn structure(
    c: &Check,
    i: usize,
    s: &RawStructure,
    table_start: usize,
    defaults: &mut Vec<String>,
) -> Result<Structure, ScenarioError> {
    let key = |k: &str| format!("structure[{}].{k}", i + 1);
    let near = Some(table_start);
    let length = c.positive(
        c.required(&s.length, &key("length"), "height L in m", near)?,
        &key("length"),
        "m",
    )?;
    let mass = c.positive(
        c.required(&s.mass, &key("mass"), "total mass M in kg", near)?,
        &key("mass"),
        "kg",
    )?;
    let given: Vec<(&str, &Spanned<f64>)> = [
        ("period", &s.period),
        ("bending_stiffness", &s.bending_stiffness),
        ("tip_stiffness", &s.tip_stiffness),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.as_ref().map(|v| (k, v)))
    .collect();
    let stiffness = match given.as_slice() {
        [] => {
            return Err(c.missing(
                &key("period"),
                "one of `period` (s), `bending_stiffness` (N·m²) or `tip_stiffness` (N/m)",
                near,
            ))
        }
        [(k, v)] => {
            let (unit, make): (&str, fn(f64) -> Stiffness) = match *k {
                "period" => ("s", Stiffness::Period),
                "bending_stiffness" => ("N·m²", Stiffness::Bending),
                _ => ("N/m", Stiffness::Tip),
            };
            make(c.positive(v, &key(k), unit)?)
        }
        [(k1, _), (k2, v2), ..] => {
            return Err(c.invalid(
                v2,
                &key(k2),
                &format!(
                    "give exactly one of `period`, `bending_stiffness`, `tip_stiffness` (also `{k1}` is given)"
                ),
            ))
        }
    };
    let modes = match &s.modes {
        None => {
            defaults.push(format!("{} = {DEFAULT_MODES}", key("modes")));
            DEFAULT_MODES
        }
        Some(v) => {
            let range = format!("must be a whole number from 1 to {MAX_MODES}");
            let bad = |reason: String| ScenarioError::Invalid {
                at: c.ctx.at(Some(v.span().start)),
                key: key("modes"),
                value: v.get_ref().to_string(),
                reason,
            };
            match v.get_ref() {
                toml::Value::Integer(n) if (1..=MAX_MODES).contains(n) => *n as usize,
                toml::Value::Integer(_) => return Err(bad(range)),
                toml::Value::Float(x)
                    if x.fract() == 0.0 && (1.0..=MAX_MODES as f64).contains(x) =>
                {
                    return Err(bad(format!(
                        "must be a whole number (write {}, without a decimal point), from 1 to {MAX_MODES}",
                        *x as i64
                    )));
                }
                _ => return Err(bad(range)),
            }
        }
    };
    let damping = match (&s.damping_ratio, &s.strain_rate_damping, &s.air_damping) {
        (Some(z), None, None) => {
            let values = match z.get_ref() {
                RawZeta::One(v) => vec![*v],
                RawZeta::Many(v) => v.clone(),
            };
            if values.len() != 1 && values.len() != modes {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(z.span().start)),
                    key: key("damping_ratio"),
                    value: format!("a list of {}", values.len()),
                    reason: format!("give one ratio, or a list of exactly {modes} (one per mode)"),
                });
            }
            if let Some(bad) = values
                .iter()
                .find(|v| !(v.is_finite() && **v >= 0.0 && **v < 1.0))
            {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(z.span().start)),
                    key: key("damping_ratio"),
                    value: bad.to_string(),
                    reason: "damping ratios must be in [0, 1)".into(),
                });
            }
            for v in &values {
                c.usual(*v, &key("damping_ratio"), "");
            }
            Damping::Modal(values)
        }
        (None, None, None) => {
            defaults.push(format!(
                "{} = {DEFAULT_DAMPING_RATIO}",
                key("damping_ratio")
            ));
            Damping::Modal(vec![DEFAULT_DAMPING_RATIO])
        }
        (Some(z), _, _) => {
            return Err(ScenarioError::Invalid {
                at: c.ctx.at(Some(z.span().start)),
                key: key("damping_ratio"),
                value: "given with strain_rate_damping/air_damping".into(),
                reason: "give either `damping_ratio` or the physical coefficients, not both".into(),
            });
        }
        (None, sr, air) => {
            let strain_rate = match sr {
                Some(v) => c.non_negative(v, &key("strain_rate_damping"), "s")?,
                None => 0.0,
            };
            let air = match air {
                Some(v) => c.non_negative(v, &key("air_damping"), "N·s/m²")?,
                None => 0.0,
            };
            Damping::Physical { strain_rate, air }
        }
    };
    Ok(Structure::Cantilever(Cantilever {
        name: s
            .name
            .clone()
            .unwrap_or_else(|| format!("structure {}", i + 1)),
        length,
        mass,
        stiffness,
        modes,
        damping,
    }))
}
