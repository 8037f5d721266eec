//! `[ground_motion]`: harmonic, record (read through the `RecordCache`) or design spectrum,
//! checked into a [`GroundMotion`].

use std::path::Path;
use std::sync::Arc;

use serde::Deserialize;
use toml::Spanned;

use crate::model::ground_motion::sdof::DEFAULT_DAMPING;
use crate::model::ground_motion::{
    GroundMotion, Harmonic, Record, RecordError, RecordOptions, SaTarget,
};

use super::RawGround;
use super::RecordCache;
use super::diagnostics::{Check, ScenarioError};
use super::ranges::physical_range;
use super::record_keys;

pub(super) fn ground(
    c: &Check,
    raw: Option<&Spanned<RawGround>>,
    base_dir: &Path,
    records: Option<&RecordCache>,
) -> Result<GroundMotion, ScenarioError> {
    let raw = raw.ok_or_else(|| {
        c.missing(
            "ground_motion",
            "a [ground_motion] table (kind = \"harmonic\" with `pga` and `period`, or kind = \"record\" with `file`)",
            None,
        )
    })?;
    let near = Some(raw.span().start);
    let g = raw.get_ref();
    let kind = c.required(
        &g.kind,
        "ground_motion.kind",
        "\"harmonic\", \"record\" or \"spectrum\"",
        near,
    )?;
    let forbid = |present: &[(&str, bool)], kind: &str| -> Result<(), ScenarioError> {
        for (k, p) in present {
            if *p {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(near),
                    key: format!("ground_motion.{k}"),
                    value: "(given)".into(),
                    reason: format!("not used with kind = \"{kind}\""),
                });
            }
        }
        Ok(())
    };
    match kind.get_ref().as_str() {
        "harmonic" => {
            forbid(
                &[
                    ("file", g.file.is_some()),
                    ("units", g.units.is_some()),
                    ("scale_to_pga", g.scale_to_pga.is_some()),
                    ("scale_to_sa", g.scale_to_sa.is_some()),
                    ("dt", g.dt.is_some()),
                    ("component", g.component.is_some()),
                    ("processing", g.processing.is_some()),
                ],
                "harmonic",
            )?;
            let pga = c.positive(
                c.required(
                    &g.pga,
                    "ground_motion.pga",
                    "peak ground acceleration in g",
                    near,
                )?,
                "ground_motion.pga",
                "g",
            )?;
            let period = c.positive(
                c.required(
                    &g.period,
                    "ground_motion.period",
                    "ground period T_g in s",
                    near,
                )?,
                "ground_motion.period",
                "s",
            )?;
            Ok(GroundMotion::Harmonic(Harmonic::from_pga_g(pga, period)))
        }
        "record" => {
            forbid(
                &[("pga", g.pga.is_some()), ("period", g.period.is_some())],
                "record",
            )?;
            let file = c.required(
                &g.file,
                "ground_motion.file",
                "the record file (PEER .AT2, COSMOS, CSMIP/DMG, K-NET/KiK-net, ESM, two columns `t a`, or one column with `dt`), relative to the scenario",
                near,
            )?;
            let units = record_keys::units(c, g.units.as_ref())?;
            let component = record_keys::component(c, g.component.as_ref())?;
            let processing = record_keys::processing(c, g.processing.as_ref())?;
            let scale_to_pga = match &g.scale_to_pga {
                Some(v) => Some(c.positive(v, "ground_motion.scale_to_pga", "g")?),
                None => None,
            };
            let dt = match &g.dt {
                Some(v) => Some(c.positive(v, "ground_motion.dt", "s")?),
                None => None,
            };
            let path = base_dir.join(file.get_ref());
            let scale_to_sa = scale_to_sa(c, g)?;
            let opts = RecordOptions {
                units,
                dt,
                scale_to_pga,
                scale_to_sa,
                component,
                processing,
            };
            let read = || {
                Record::read(&path, &opts)
                    .map(Arc::new)
                    .map_err(|e| record_error(c, g, file, e))
            };
            let record = match records {
                None => read()?,
                Some(cache) => cache.get_or_read(&path, &opts, read)?,
            };
            // what the reader noticed but accepted (a `units` key overriding the file's)
            c.ctx
                .warnings
                .borrow_mut()
                .extend(record.warnings.iter().cloned());
            // what the file gives is held to the ranges of the keys that could give it
            let g = crate::model::ground_motion::STANDARD_GRAVITY;
            for (what, x, key, unit) in [
                ("PGA", record.pga() / g, "pga", "g"),
                ("sample spacing", record.dt, "dt", "s"),
                ("duration", record.duration(), "duration", "s"),
            ] {
                if let Some((lo, hi, range_of)) = physical_range(key)
                    && !(lo..=hi).contains(&x)
                {
                    return Err(c.invalid(
                        file,
                        "ground_motion.file",
                        &format!(
                            "the record's {what} is {x:e} {unit}, outside [{lo:e}, {hi:e}] {unit} \
                             ({range_of}): check the file's units (`units`, `dt`) or scale it \
                             with `scale_to_pga` or `scale_to_sa`"
                        ),
                    ));
                }
            }
            Ok(GroundMotion::Record(record))
        }
        // a design spectrum has no time history: crate::input::scenario::design checks its keys
        "spectrum" => Ok(GroundMotion::None),
        _ => Err(c.invalid(
            kind,
            "ground_motion.kind",
            "must be \"harmonic\", \"record\", \"spectrum\" or \"suite\"",
        )),
    }
}

/// `scale_to_sa = { period = 1.0, sa = 0.4, damping = 0.05 }`: a record scaled so that its
/// pseudo-acceleration at `period` (s) is `sa` (g), damping ratio `damping` (default 5 %).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawScaleToSa {
    period: Option<Spanned<f64>>,
    sa: Option<Spanned<f64>>,
    damping: Option<Spanned<f64>>,
}

/// `ground_motion.scale_to_sa`, checked: not with `scale_to_pga`; T and S_a finite, > 0 and in
/// their ranges (the key table's); ζ in [0, 1). That T is at least dt/100 of the record is
/// checked when it is read ([`record_error`] names the key).
fn scale_to_sa(c: &Check, g: &super::RawGround) -> Result<Option<SaTarget>, ScenarioError> {
    let Some(t) = &g.scale_to_sa else {
        return Ok(None);
    };
    let near = Some(t.span().start);
    if let Some(p) = &g.scale_to_pga {
        let (line, _) = crate::diagnostics::line_col(c.ctx.text, p.span().start);
        return Err(ScenarioError::Invalid {
            at: c.ctx.at(near),
            key: "ground_motion.scale_to_sa".into(),
            value: "(given)".into(),
            reason: format!(
                "not with `ground_motion.scale_to_pga` (line {line}): a record is scaled to its \
                 PGA or to a spectral acceleration at one period; keep one"
            ),
        });
    }
    let r = t.get_ref();
    let key = |k: &str| format!("ground_motion.scale_to_sa.{k}");
    let period = c.required(
        &r.period,
        &key("period"),
        "the oscillator's period T in s",
        near,
    )?;
    let period = c.positive(period, &key("period"), "s")?;
    let sa = c.required(&r.sa, &key("sa"), "the target PSA at T, in g", near)?;
    let sa = c.positive(sa, &key("sa"), "g")?;
    let damping = match &r.damping {
        None => DEFAULT_DAMPING,
        Some(z) => {
            let x = *z.get_ref();
            if !(x.is_finite() && (0.0..1.0).contains(&x)) {
                return Err(c.invalid(
                    z,
                    &key("damping"),
                    "must be a damping ratio in [0, 1) (0.05 = 5 %, the codes' spectra)",
                ));
            }
            x
        }
    };
    Ok(Some(SaTarget {
        period,
        sa,
        damping,
    }))
}

/// A reading error as the scenario reports it: at the `scale_to_sa` key it is about (a period
/// below the record's dt/100, a record without response), else at `file`.
fn record_error(
    c: &Check,
    g: &super::RawGround,
    file: &Spanned<String>,
    e: RecordError,
) -> ScenarioError {
    let (key, offset) = match (&e, &g.scale_to_sa) {
        (RecordError::SaPeriodBelowStep { .. }, Some(t)) => (
            "ground_motion.scale_to_sa.period",
            t.get_ref()
                .period
                .as_ref()
                .map_or(t.span().start, |p| p.span().start),
        ),
        (RecordError::ZeroSa { .. }, Some(t)) => ("ground_motion.scale_to_sa", t.span().start),
        _ => ("ground_motion.file", file.span().start),
    };
    ScenarioError::Record {
        at: c.ctx.at(Some(offset)),
        key: key.into(),
        source: Box::new(e),
    }
}
