//! Warnings about values that are valid but implausible (a PGA given in the wrong unit, a gap
//! of metres, an unusual sample spacing), for a scenario and for each record of a suite.

use crate::model::ground_motion::GroundMotion;

use super::ranges::{PLAUSIBLE_MIN_PGA, USUAL_RECORD_DT};
use super::{ContactSpec, PLAUSIBLE_GAP, PLAUSIBLE_PGA};

/// Warnings about values that are valid but implausible, each saying why.
pub(super) fn plausibility(contact: &ContactSpec, ground: &GroundMotion) -> Vec<String> {
    let mut out = Vec::new();
    let pga_g = ground.pga() / crate::model::ground_motion::STANDARD_GRAVITY;
    if matches!(ground, GroundMotion::Harmonic(_) | GroundMotion::Record(_))
        && pga_g < PLAUSIBLE_MIN_PGA
    {
        out.push(format!(
            "the ground motion's PGA is {pga_g:.3e} g, below {PLAUSIBLE_MIN_PGA} g: shaking that \
             people barely feel, far below any that makes buildings pound; PGA is in g — was it \
             given in cm/s² or scaled twice?"
        ));
    }
    if let GroundMotion::Record(r) = ground {
        let (lo, hi) = USUAL_RECORD_DT;
        if !(lo..=hi).contains(&r.dt) {
            out.push(format!(
                "the record is sampled every {} s, outside the usual [{lo}, {hi}] s of \
                 accelerograms (50 Hz to 10 kHz); check `ground_motion.dt` or the file's time \
                 column (in s)",
                r.dt
            ));
        }
    }
    if pga_g > PLAUSIBLE_PGA {
        out.push(format!(
            "the ground motion's PGA is {pga_g:.3} g, above {PLAUSIBLE_PGA} g: beyond the strongest \
             shaking ever recorded (about 3–4 g) and far beyond design levels (≤ 1–1.5 g); \
             PGA is in g — was it given in m/s²?"
        ));
    }
    let key = |k: usize| {
        if contact.levels.len() > 1 {
            format!("contact.level[{}].gap", k + 1)
        } else {
            "contact.gap".into()
        }
    };
    for (k, l) in contact.levels.iter().enumerate() {
        if l.gap >= PLAUSIBLE_GAP {
            out.push(format!(
                "`{}` = {} m: a gap of metres between adjacent buildings (usual gaps are \
                 centimetres); the unit is m — was it given in mm or cm?",
                key(k),
                l.gap
            ));
        }
    }
    out
}
