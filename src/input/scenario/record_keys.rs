//! The record keys of `[ground_motion] kind = "record"` beyond the file and its scaling:
//! `units`, `component` (a number or a name) and `processing = { baseline, highpass_hz,
//! lowpass_hz, order }`, each checked with its file:line:col.

use serde::Deserialize;
use toml::Spanned;

use super::diagnostics::{Check, ScenarioError};
use crate::model::ground_motion::processing::{Baseline, DEFAULT_ORDER, MAX_ORDER, Processing};
use crate::model::ground_motion::{AccelUnits, Component};

/// `processing = { baseline = "linear", highpass_hz = 0.1, lowpass_hz = 25, order = 4 }`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawProcessing {
    baseline: Option<Spanned<String>>,
    highpass_hz: Option<Spanned<f64>>,
    lowpass_hz: Option<Spanned<f64>>,
    /// A whole number; taken as a TOML value so that `4.0` gets our message.
    order: Option<Spanned<toml::Value>>,
}

/// `units`: g, gal / cm/s², m/s² (several spellings, [`AccelUnits::from_name`]).
pub(crate) fn units(
    c: &Check,
    v: Option<&Spanned<String>>,
) -> Result<Option<AccelUnits>, ScenarioError> {
    let Some(u) = v else { return Ok(None) };
    AccelUnits::from_name(u.get_ref()).map(Some).ok_or_else(|| {
        c.invalid(
            u,
            "ground_motion.units",
            "must be \"g\", \"cm/s2\" (gal) or \"m/s2\"",
        )
    })
}

/// `component`: a number from 1 (the position in the file) or a name (`"90"`, `"EW"`, `"HNE"`).
pub(crate) fn component(
    c: &Check,
    v: Option<&Spanned<toml::Value>>,
) -> Result<Option<Component>, ScenarioError> {
    let Some(v) = v else { return Ok(None) };
    let key = "ground_motion.component";
    let reason = "must be a component's number in the file (1, 2, …) or its name \
                  (e.g. \"90\", \"EW\", \"HNE\", \"Up\")";
    match v.get_ref() {
        toml::Value::Integer(n) if *n >= 1 => Ok(Some(Component::Index(*n as usize))),
        toml::Value::String(s) if !s.trim().is_empty() => {
            Ok(Some(Component::Name(s.trim().to_string())))
        }
        _ => Err(c.invalid(v, key, reason)),
    }
}

/// `processing = { … }`: at least one step; the corners in their ranges
/// ([`crate::input::scenario::ranges`]), high-pass below low-pass; the order a whole number 1 to 8.
/// The Nyquist limit is checked against the record's time step when it is read.
pub(crate) fn processing(
    c: &Check,
    v: Option<&Spanned<RawProcessing>>,
) -> Result<Option<Processing>, ScenarioError> {
    let Some(v) = v else { return Ok(None) };
    let p = v.get_ref();
    let key = |k: &str| format!("ground_motion.processing.{k}");
    let baseline = match &p.baseline {
        None => None,
        Some(b) => Some(match b.get_ref().as_str() {
            "linear" => Baseline::Linear,
            "polynomial" => Baseline::Polynomial,
            _ => {
                return Err(c.invalid(
                    b,
                    &key("baseline"),
                    "must be \"linear\" (a straight line fitted to the acceleration) or \
                     \"polynomial\" (a polynomial fitted to the displacement)",
                ));
            }
        }),
    };
    let highpass_hz = match &p.highpass_hz {
        Some(f) => Some(c.positive(f, &key("highpass_hz"), "Hz")?),
        None => None,
    };
    let lowpass_hz = match &p.lowpass_hz {
        Some(f) => Some(c.positive(f, &key("lowpass_hz"), "Hz")?),
        None => None,
    };
    if let (Some(h), Some(l), Some(lv)) = (highpass_hz, lowpass_hz, &p.lowpass_hz)
        && h >= l
    {
        return Err(c.invalid(
            lv,
            &key("lowpass_hz"),
            &format!("must be above highpass_hz = {h} Hz (the band-pass keeps f_h < f < f_l)"),
        ));
    }
    let order = match &p.order {
        None => DEFAULT_ORDER,
        Some(o) => match o.get_ref() {
            toml::Value::Integer(n) if (1..=MAX_ORDER as i64).contains(n) => *n as usize,
            _ => {
                return Err(c.invalid(
                    o,
                    &key("order"),
                    &format!(
                        "must be a whole number from 1 to {MAX_ORDER} (the Butterworth order)"
                    ),
                ));
            }
        },
    };
    if baseline.is_none() && highpass_hz.is_none() && lowpass_hz.is_none() {
        return Err(c.missing(
            &key("baseline"),
            "at least one of `baseline`, `highpass_hz`, `lowpass_hz`",
            Some(v.span().start),
        ));
    }
    Ok(Some(Processing {
        baseline,
        highpass_hz,
        lowpass_hz,
        order,
    }))
}
