//! The allowed range of every numeric key (refused outside, issue 15) and its usual band for
//! real buildings and earthquakes (accepted with a warning outside): one table each, by the
//! key's last component, so that errors and warnings state the same numbers as the README.

/// The physically meaningful range of a numeric key, by its last component (issue 15): values
/// outside are refused, so that no accepted input overflows into a non-finite result (a period of
/// 1e300 s made the CQC correlation overflow and DDC print 0). The bounds are generous: they
/// exclude only what no structure, motion or run can be.
pub fn physical_range(key: &str) -> Option<(f64, f64, &'static str)> {
    let last = key.rsplit('.').next().unwrap_or(key);
    Some(match last {
        "length" => (0.1, 2000.0, "a structure's height"),
        "mass" => (1.0, 1e12, "a structure's mass"),
        "period" => (0.01, 100.0, "a structural or ground period"),
        "bending_stiffness" => (1.0, 1e22, "a structure's EI"),
        "tip_stiffness" => (1e-3, 1e16, "a lateral stiffness"),
        "strain_rate_damping" => (0.0, 10.0, "c_s/E"),
        "air_damping" => (0.0, 1e10, "c_a"),
        "stiffness" => (1e-3, 1e20, "a contact stiffness"),
        "gap" => (0.0, 10.0, "a gap between buildings"),
        "pga" | "scale_to_pga" => (1e-6, 20.0, "a peak ground acceleration"),
        "dt" => (1e-7, 100.0, "a time step"),
        "duration" => (1e-3, 1e7, "a simulated duration"),
        "output_interval" => (1e-7, 1e6, "a sampling interval"),
        "storey_height" => (0.1, 100.0, "a storey's height"),
        "floor_mass" | "floor_masses" => (1.0, 1e10, "a floor's mass"),
        "storey_stiffness" | "storey_stiffnesses" => (1.0, 1e16, "a storey's stiffness"),
        "floor_heights" => (0.1, 10000.0, "a floor's height"),
        "periods" => (1e-3, 1e3, "a mode's period"),
        "yield_drifts" => (1e-6, 10.0, "a storey's yield drift"),
        "yield_forces" => (1e-3, 1e14, "a storey's yield force"),
        "highpass_hz" => (1e-4, 100.0, "a high-pass corner of a record's filter"),
        "lowpass_hz" => (1e-2, 1e5, "a low-pass corner of a record's filter"),
        _ => return None,
    })
}

/// The usual band of a numeric key for real buildings, earthquakes and runs (issue 15): a value
/// inside [`physical_range`] but outside this band is accepted with a warning (in
/// `Scenario::warnings`) that gives the band and why. Keys by path, e.g. `structure[1].period`
/// or `ground_motion.period` (the ground's period has its own band).
///
/// Some quantities are warned about once, where they are known in full rather than per key:
/// the PGA (of a harmonic motion or a record, scaled or not: `ground_motion.pga`,
/// `scale_to_pga` → [`PLAUSIBLE_PGA`], [`PLAUSIBLE_MIN_PGA`]), a record's sample spacing
/// (`ground_motion.dt` or the file's own → [`USUAL_RECORD_DT`]), the gaps ([`PLAUSIBLE_GAP`]),
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
    let last = key.rsplit('.').next().unwrap_or(key);
    let ground = key.starts_with("ground_motion");
    Some(match last {
        "length" => (
            2.5,
            850.0,
            "buildings are about 3 m (one storey) to 830 m (the tallest) high",
        ),
        "mass" => (
            1e4,
            1e10,
            "a building weighs about 10 t (a house) to 10⁹ kg (the tallest towers)",
        ),
        "period" if ground => (
            0.02,
            20.0,
            "earthquake ground motion has its energy at periods of about 0.05–10 s (long-period \
             pulses up to about 20 s)",
        ),
        "period" => (
            USUAL_STRUCTURE_PERIOD.0,
            USUAL_STRUCTURE_PERIOD.1,
            "buildings have first-mode periods of about 0.02 s to 12 s (the tallest)",
        ),
        "damping_ratio" => (
            USUAL_DAMPING_RATIO.0,
            USUAL_DAMPING_RATIO.1,
            "buildings have damping ratios of about 0.5–20 % (5 % by convention)",
        ),
        "stiffness" => (
            1e6,
            1e13,
            "contact stiffnesses between buildings in the literature are about 10⁶–10¹³ \
             (N/m or N/m^1.5)",
        ),
        "restitution" => (
            0.3,
            1.0,
            "impacts between buildings (concrete, steel, timber) have restitution of about \
             0.4–0.8",
        ),
        "dt" if !ground => (
            1e-6,
            0.05,
            "a step below 1 µs takes very long; above 50 ms a step spans the short periods \
             of a building and of a record",
        ),
        "duration" => (1.0, 3600.0, "earthquake shaking lasts seconds to minutes"),
        "highpass_hz" => (
            0.01,
            1.0,
            "strong-motion records are high-pass filtered at about 0.02–0.5 Hz; above 1 Hz the \
             filter removes motion that buildings respond to",
        ),
        "lowpass_hz" => (
            5.0,
            100.0,
            "strong-motion records are low-pass filtered at about 20–50 Hz; below 5 Hz the \
             filter removes motion that stiff buildings respond to",
        ),
        "output_interval" => (
            1e-4,
            0.1,
            "history.csv sampled more sparsely than 0.1 s does not resolve a building's \
             motion (the peaks are still exact)",
        ),
        "rtol" => (
            crate::integrate::MIN_RTOL,
            1e-3,
            "a relative tolerance above 1e-3 gives rough results (the self-check says how rough)",
        ),
        "atol" => (
            crate::integrate::MIN_ATOL,
            1e-3,
            "an absolute tolerance above 1 mm is coarser than the gaps it is meant to resolve",
        ),
        "storeys" => (1.0, 170.0, "the tallest buildings have about 160 storeys"),
        "storey_height" => (
            2.0,
            10.0,
            "storeys are about 2.5–6 m high (10 m: industrial)",
        ),
        "floor_mass" | "floor_masses" => (
            1e3,
            1e8,
            "a floor weighs about 1 t (a light timber floor) to 10⁸ kg (a tower's)",
        ),
        "storey_stiffness" | "storey_stiffnesses" => (
            1e5,
            1e12,
            "a storey's lateral stiffness is about 10⁵ N/m (light timber) to 10¹² N/m (shear \
             walls)",
        ),
        "floor_heights" => (1.0, 850.0, "floors are 1 m to 830 m above the ground"),
        "periods" => (
            0.005,
            USUAL_STRUCTURE_PERIOD.1,
            "a building's modes have periods of about 0.005 s (high modes) to 12 s (the tallest)",
        ),
        // Bouc–Wen storeys (issue 16). α: steel and concrete frames harden by 0–10 % after
        // yield (2–5 % typical), lead-rubber and friction isolators by up to about 20 %; above
        // 30 % a storey hardly yields at all.
        "post_yield_ratio" => (
            0.0,
            0.3,
            "storeys harden after yield by about 0–10 % of their initial stiffness (2–5 % \
             typical; isolators up to about 20 %)",
        ),
        // n: 1–2 for a smooth, rounded yield (Wen 1976), about 10–25 for a nearly bilinear
        // one; beyond 20 the loop is bilinear to plotting accuracy and only stiffens the solver.
        "exponent" => (
            1.0,
            20.0,
            "the Bouc–Wen literature uses n = 1–2 for a smooth yield and up to about 10–20 for a \
             sharp, nearly bilinear one",
        ),
        // not a key: a storey's yield drift (`yield_drifts`, or `yield_forces`/k) over its
        // height. Frames and walls yield at drift ratios of about 0.1 % (stiff shear walls,
        // masonry) to 3 % (flexible steel or timber frames); 0.5–1 % is usual for frames.
        "yield_drift_ratio" => (
            1e-3,
            0.05,
            "storeys yield at drifts of about 0.1 % (shear walls) to 3 % (flexible frames) of \
             their height, 0.5–1 % for most frames",
        ),
        // not a key: β + γ. The plateau of the storey force is (1 − α) k d_y (β + γ)^(−1/n):
        // with β + γ = 1 (β = γ = 0.5, the standard choice) d_y is the yield drift; outside
        // [0.5, 2] the plateau moves by more than a factor of 2^(1/n) (41 % at n = 2) from
        // k d_y, and `yield_drifts` no longer says where the storey yields.
        "beta_plus_gamma" => (
            0.5,
            2.0,
            "β + γ = 1 (β = γ = 0.5 is the standard choice) puts the plateau of the storey force \
             at (1 − α)k·d_y; far from 1 the plateau moves as (β + γ)^(−1/n) and `yield_drifts` \
             no longer says where the storey yields",
        ),
        _ => return None,
    })
}

/// Usual first-mode period of a building, s ([`usual_range`]): from a one-storey stiff frame to
/// the tallest towers (Burj Khalifa: about 11 s).
pub const USUAL_STRUCTURE_PERIOD: (f64, f64) = (0.02, 12.0);

/// Usual damping ratio of a building's first mode ([`usual_range`]).
pub const USUAL_DAMPING_RATIO: (f64, f64) = (0.005, 0.2);

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
