//! `[ground_motion]`: harmonic, record (read through the `RecordCache`) or design spectrum,
//! checked into a [`GroundMotion`].

use std::path::Path;
use std::sync::Arc;

use toml::Spanned;

use crate::model::ground_motion::{GroundMotion, Harmonic, Record, RecordOptions};

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
            let opts = RecordOptions {
                units,
                dt,
                scale_to_pga,
                component,
                processing,
            };
            let read = || {
                Record::read(&path, &opts)
                    .map(Arc::new)
                    .map_err(|e| ScenarioError::Record {
                        at: c.ctx.at(Some(file.span().start)),
                        key: "ground_motion.file".into(),
                        source: Box::new(e),
                    })
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
                             with `scale_to_pga`"
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
