//! The allowed range of every numeric key (refused outside, issue 15) and its usual band for
//! real buildings and earthquakes (accepted with a warning outside), looked up by path in the
//! one table of the keys (`keys`), so that errors, warnings and docs/scenario-keys.md state the
//! same numbers.

use super::keys::{DERIVED, lookup};
pub use super::keys::{USUAL_DAMPING_RATIO, USUAL_STRUCTURE_PERIOD};

/// The physically meaningful range of a numeric key, by its path or last component (issue 15): values
/// outside are refused, so that no accepted input overflows into a non-finite result (a period of
/// 1e300 s made the CQC correlation overflow and DDC print 0). The bounds are generous: they
/// exclude only what no structure, motion or run can be.
pub fn physical_range(key: &str) -> Option<(f64, f64, &'static str)> {
    let r = lookup(key, |k| k.physical.is_some())?.physical?;
    Some((r.lo, r.hi, r.why))
}

/// The usual band of a numeric key for real buildings, earthquakes and runs (issue 15): a value
/// inside [`physical_range`] but outside this band is accepted with a warning (in
/// `Scenario::warnings`) that gives the band and why. Keys by path, e.g. `structure[1].period`
/// or `ground_motion.period` (the ground's period has its own band).
///
/// Some quantities are warned about once, where they are known in full rather than per key:
/// the PGA (of a harmonic motion or a record, scaled or not: `ground_motion.pga`,
/// `scale_to_pga` → [`super::PLAUSIBLE_PGA`], [`PLAUSIBLE_MIN_PGA`]), a record's sample spacing
/// (`ground_motion.dt` or the file's own → [`USUAL_RECORD_DT`]), the gaps ([`super::PLAUSIBLE_GAP`]),
/// a structure's stiffness (`bending_stiffness`, `tip_stiffness`: through the first-mode period
/// it gives with the mass and height, [`USUAL_STRUCTURE_PERIOD`]) and physical damping
/// (`strain_rate_damping`, `air_damping`: through the first-mode damping ratio,
/// [`USUAL_DAMPING_RATIO`]). Those keys return `None` here.
///
/// Two entries are not keys but what Bouc–Wen keys give together (issue 16, warned about once
/// per building in `scenario::hysteresis`): `yield_drift_ratio`, a storey's yield drift
/// (`yield_drifts`, or `yield_forces` over the storey stiffness) over the storey's height, and
/// `beta_plus_gamma`, β + γ.
pub fn usual_range(key: &str) -> Option<(f64, f64, &'static str)> {
    let r = match lookup(key, |k| k.usual.is_some()) {
        Some(k) => k.usual?,
        None => DERIVED.iter().find(|(name, _)| *name == key)?.1,
    };
    Some((r.lo, r.hi, r.why))
}

/// Usual sample spacing of an accelerogram, s (50 Hz to 10 kHz).
pub const USUAL_RECORD_DT: (f64, f64) = (1e-4, 0.02);

/// PGA below which a ground motion gets a plausibility warning, g (barely felt shaking).
pub const PLAUSIBLE_MIN_PGA: f64 = 0.01;

/// The warning for `x` (of `key`, in `unit`) outside its usual band, if it is.
pub(crate) fn unusual(x: f64, key: &str, unit: &str) -> Option<String> {
    let (lo, hi, why) = usual_range(key)?;
    let unit = if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    };
    (!(lo..=hi).contains(&x)).then(|| {
        format!(
            "`{key}` = {x:?}{unit} is outside the usual [{lo:e}, {hi:e}]{unit}: {why}; \
             check the value{}",
            if unit.is_empty() { "" } else { " and its unit" }
        )
    })
}
