//! summary.json's `ground_motion` section and the line `pounding run` prints about it: what
//! shook the structures, and for a record the scaling applied when it was read (`scale_factor`,
//! and the target of `scale_to_pga` or `scale_to_sa`).
//!
//! Keys (SI): `kind` (`"harmonic"`, `"record"`, `"none"`); harmonic: `pga` (m/s²), `pga_g`,
//! `period` (s); record: `record` (its description), `component` (only when the file names it:
//! summary.json has no nulls), `dt` (s), `points`, `duration` (s), `pga` (m/s²) and `pga_g` of
//! the record as run, `scale_factor` (1 when not scaled), and when scaled `scale_to_pga` = { `pga` (m/s²), `pga_g` } or `scale_to_sa` =
//! { `period` (s), `damping`, `sa` (m/s²), `sa_g`, `psa_before` (m/s², the record's PSA at
//! `period` as read) }.

use serde_json::{Value, json};

use crate::model::ground_motion::{GroundMotion, STANDARD_GRAVITY, ScaleTarget};
use crate::numerics::format::fmt_num;

/// The `ground_motion` section of summary.json for `g`.
pub fn ground_section(g: &GroundMotion) -> Value {
    let gr = STANDARD_GRAVITY;
    match g {
        GroundMotion::None => json!({ "kind": "none" }),
        GroundMotion::Harmonic(h) => json!({
            "kind": "harmonic",
            "pga": h.pga,
            "pga_g": h.pga / gr,
            "period": h.period(),
        }),
        GroundMotion::Record(r) => {
            let mut s = json!({
                "kind": "record",
                "record": r.description,
                "dt": r.dt,
                "points": r.num_samples(),
                "duration": r.duration(),
                "pga": r.pga(),
                "pga_g": r.pga() / gr,
                "scale_factor": r.scaling.map_or(1.0, |s| s.factor),
            });
            if let Some(c) = &r.component {
                s["component"] = json!(c);
            }
            match r.scaling.map(|s| s.target) {
                Some(ScaleTarget::Pga { pga }) => {
                    s["scale_to_pga"] = json!({ "pga": pga * gr, "pga_g": pga });
                }
                Some(ScaleTarget::Sa { target, psa_before }) => {
                    s["scale_to_sa"] = json!({
                        "period": target.period,
                        "damping": target.damping,
                        "sa": target.sa_m_s2(),
                        "sa_g": target.sa,
                        "psa_before": psa_before,
                    });
                }
                Some(ScaleTarget::Factor) | None => {}
            }
            s
        }
    }
}

/// The line `pounding run` prints about a scaled record (`None` for any other motion):
/// `record "x" scaled × 1.53 to PSA(T = 1 s, ζ = 5 %) = 0.4 g (as read 0.2614 g)`.
pub fn scaling_line(g: &GroundMotion) -> Option<String> {
    let GroundMotion::Record(r) = g else {
        return None;
    };
    let s = r.scaling?;
    let to = match s.target {
        ScaleTarget::Factor => {
            return Some(format!(
                "record \"{}\" scaled × {:.4}",
                r.description, s.factor
            ));
        }
        ScaleTarget::Pga { pga } => format!(
            "PGA = {} g (as read {:.4} g)",
            fmt_num(pga),
            r.pga() / s.factor / STANDARD_GRAVITY
        ),
        ScaleTarget::Sa { target, psa_before } => format!(
            "PSA(T = {} s, ζ = {} %) = {} g (as read {:.4} g)",
            fmt_num(target.period),
            fmt_num(100.0 * target.damping),
            fmt_num(target.sa),
            psa_before / STANDARD_GRAVITY
        ),
    };
    Some(format!(
        "record \"{}\" scaled × {:.4} to {to}",
        r.description, s.factor
    ))
}
