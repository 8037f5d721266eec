//! `[[structure]]`, `[structure.rayleigh]` and `[structure.hysteresis]`.

use super::{KeyInfo, Kind, Table, USUAL_DAMPING_RATIO, USUAL_STRUCTURE_PERIOD};

const S: Table = Table::Structure;
const R: Table = Table::Rayleigh;
const H: Table = Table::Hysteresis;

/// The keys of a structure and its sub-tables.
pub(super) const KEYS: &[KeyInfo] = &[
    KeyInfo::new(
        S,
        "kind",
        Kind::Text,
        "",
        "\"cantilever\" (default: the paper's continuous cantilever), \"shear-building\" \
         (floors joined by storey springs) or \"modal\" (the engineer's own modes)",
    ),
    KeyInfo::new(
        S,
        "name",
        Kind::Text,
        "",
        "a name for messages and plots (default \"structure i\")",
    )
    .sweep(),
    KeyInfo::new(S, "length", Kind::Number, "m", "cantilever: height L")
        .physical(0.1, 2000.0, "a structure's height")
        .usual(
            2.5,
            850.0,
            "buildings are about 3 m (one storey) to 830 m (the tallest) high",
        )
        .sweep(),
    KeyInfo::new(
        S,
        "mass",
        Kind::Number,
        "kg",
        "cantilever: total mass M = m·L",
    )
    .physical(1.0, 1e12, "a structure's mass")
    .usual(
        1e4,
        1e10,
        "a building weighs about 10 t (a house) to 10⁹ kg (the tallest towers)",
    )
    .sweep(),
    KeyInfo::new(
        S,
        "period",
        Kind::Number,
        "s",
        "cantilever: first-mode period T₁ (exactly one of `period`, `bending_stiffness`, \
         `tip_stiffness`)",
    )
    .physical(0.01, 100.0, "a structural or ground period")
    .usual(
        USUAL_STRUCTURE_PERIOD.0,
        USUAL_STRUCTURE_PERIOD.1,
        "buildings have first-mode periods of about 0.02 s to 12 s (the tallest)",
    )
    .sweep()
    .label("T{i}"),
    KeyInfo::new(
        S,
        "bending_stiffness",
        Kind::Number,
        "N·m²",
        "cantilever: EI",
    )
    .physical(1.0, 1e22, "a structure's EI")
    .sweep(),
    KeyInfo::new(
        S,
        "tip_stiffness",
        Kind::Number,
        "N/m",
        "cantilever: 3EI/L³",
    )
    .physical(1e-3, 1e16, "a lateral stiffness")
    .sweep(),
    KeyInfo::new(
        S,
        "modes",
        Kind::Integer,
        "",
        "modes kept, 1 to 500 (a building: to its number of floors or of modes given); default \
         20 for a cantilever, all for a building",
    )
    .sweep(),
    KeyInfo::new(
        S,
        "damping_ratio",
        Kind::Number,
        "",
        "ζ of every mode, or a list of one per mode kept, each in [0, 1); default 0.05 when no \
         damping is given",
    )
    .usual(
        USUAL_DAMPING_RATIO.0,
        USUAL_DAMPING_RATIO.1,
        "buildings have damping ratios of about 0.5–20 % (5 % by convention)",
    )
    .sweep(),
    KeyInfo::new(
        S,
        "strain_rate_damping",
        Kind::Number,
        "s",
        "cantilever: c_s/E (instead of `damping_ratio`; its first-mode ratio is warned about)",
    )
    .physical(0.0, 10.0, "c_s/E")
    .sweep(),
    KeyInfo::new(
        S,
        "air_damping",
        Kind::Number,
        "N·s/m²",
        "cantilever: c_a (instead of `damping_ratio`; also loads the structure with −γ c_a v_g)",
    )
    .physical(0.0, 1e10, "c_a")
    .sweep(),
    KeyInfo::new(
        S,
        "floor_heights",
        Kind::List,
        "m",
        "building: floor heights above the base, strictly increasing, 1 to 500 floors",
    )
    .physical(0.1, 10000.0, "a floor's height")
    .usual(1.0, 850.0, "floors are 1 m to 830 m above the ground")
    .sweep(),
    KeyInfo::new(
        S,
        "floor_masses",
        Kind::List,
        "kg",
        "building: one mass per floor",
    )
    .physical(1.0, 1e10, "a floor's mass")
    .usual(
        1e3,
        1e8,
        "a floor weighs about 1 t (a light timber floor) to 10⁸ kg (a tower's)",
    )
    .sweep(),
    KeyInfo::new(
        S,
        "storey_stiffnesses",
        Kind::List,
        "N/m",
        "shear building: one lateral stiffness per storey (storey j joins floor j − 1 to floor j)",
    )
    .physical(1.0, 1e16, "a storey's stiffness")
    .usual(
        1e5,
        1e12,
        "a storey's lateral stiffness is about 10⁵ N/m (light timber) to 10¹² N/m (shear \
         walls)",
    )
    .sweep(),
    KeyInfo::new(
        S,
        "storeys",
        Kind::Integer,
        "",
        "shear building, uniform shorthand: the number of storeys, 1 to 500",
    )
    .usual(1.0, 170.0, "the tallest buildings have about 160 storeys")
    .sweep(),
    KeyInfo::new(
        S,
        "storey_height",
        Kind::Number,
        "m",
        "shear building, uniform shorthand",
    )
    .physical(0.1, 100.0, "a storey's height")
    .usual(
        2.0,
        10.0,
        "storeys are about 2.5–6 m high (10 m: industrial)",
    )
    .sweep(),
    KeyInfo::new(
        S,
        "floor_mass",
        Kind::Number,
        "kg",
        "shear building, uniform shorthand",
    )
    .physical(1.0, 1e10, "a floor's mass")
    .usual(
        1e3,
        1e8,
        "a floor weighs about 1 t (a light timber floor) to 10⁸ kg (a tower's)",
    )
    .sweep(),
    KeyInfo::new(
        S,
        "storey_stiffness",
        Kind::Number,
        "N/m",
        "shear building, uniform shorthand",
    )
    .physical(1.0, 1e16, "a storey's stiffness")
    .usual(
        1e5,
        1e12,
        "a storey's lateral stiffness is about 10⁵ N/m (light timber) to 10¹² N/m (shear \
             walls)",
    )
    .sweep(),
    KeyInfo::new(
        S,
        "rayleigh",
        Kind::Table,
        "",
        "building: Rayleigh damping `{ damping_ratio, modes = [i, j] }` instead of `damping_ratio`",
    ),
    KeyInfo::new(S, "periods", Kind::List, "s", "modal: one period per mode")
        .physical(1e-3, 1e3, "a mode's period")
        .usual(
            0.005,
            USUAL_STRUCTURE_PERIOD.1,
            "a building's modes have periods of about 0.005 s (high modes) to 12 s (the tallest)",
        )
        .sweep(),
    KeyInfo::new(
        S,
        "mode_shapes",
        Kind::List,
        "",
        "modal: one list per mode, a value per floor, any normalisation (mass-orthogonality checked)",
    ),
    KeyInfo::new(
        S,
        "modes_file",
        Kind::File,
        "",
        "modal: a CSV of `height, mass, mode_1, mode_2, …` instead of the lists",
    ),
    KeyInfo::new(
        S,
        "hysteresis",
        Kind::Table,
        "",
        "shear building: yielding (Bouc–Wen) storeys, see [structure.hysteresis]",
    ),
    KeyInfo::new(
        R,
        "damping_ratio",
        Kind::Number,
        "",
        "ζ at the two modes, ζ_n = a₀/(2ω_n) + a₁ω_n/2",
    )
    .usual(
        USUAL_DAMPING_RATIO.0,
        USUAL_DAMPING_RATIO.1,
        "buildings have damping ratios of about 0.5–20 % (5 % by convention)",
    ),
    KeyInfo::new(
        R,
        "modes",
        Kind::List,
        "",
        "the two (different) modes [i, j] where ζ is given",
    ),
    KeyInfo::new(
        H,
        "model",
        Kind::Text,
        "",
        "the hysteretic law: \"bouc-wen\" (default, the one model)",
    ),
    KeyInfo::new(
        H,
        "yield_drifts",
        Kind::Number,
        "m",
        "yield drift d_y: one value for every storey or a list of one per storey, lowest first \
         (exactly one of `yield_drifts`, `yield_forces`)",
    )
    .physical(1e-6, 10.0, "a storey's yield drift")
    .sweep(),
    KeyInfo::new(
        H,
        "yield_forces",
        Kind::Number,
        "N",
        "yield force F_y = k d_y: one value for every storey or a list of one per storey (F_y/k \
         is held to the range of `yield_drifts`)",
    )
    .physical(1e-3, 1e14, "a storey's yield force")
    .sweep(),
    // α: steel and concrete frames harden by 0–10 % after yield (2–5 % typical), lead-rubber
    // and friction isolators by up to about 20 %; above 30 % a storey hardly yields at all.
    KeyInfo::new(
        H,
        "post_yield_ratio",
        Kind::Number,
        "",
        "α, post-yield over initial stiffness, in [0, 1); required",
    )
    .usual(
        0.0,
        0.3,
        "storeys harden after yield by about 0–10 % of their initial stiffness (2–5 % \
         typical; isolators up to about 20 %)",
    )
    .sweep(),
    // n: 1–2 for a smooth, rounded yield (Wen 1976), about 10–25 for a nearly bilinear one;
    // beyond 20 the loop is bilinear to plotting accuracy and only stiffens the solver.
    KeyInfo::new(
        H,
        "exponent",
        Kind::Number,
        "",
        "n, sharpness of yielding (1 smooth, ≥ 10 nearly bilinear), in [1, 100]; default 2",
    )
    .usual(
        1.0,
        20.0,
        "the Bouc–Wen literature uses n = 1–2 for a smooth yield and up to about 10–20 for a \
         sharp, nearly bilinear one",
    )
    .sweep(),
    KeyInfo::new(
        H,
        "beta",
        Kind::Number,
        "",
        "β, the shape of unloading, 0 < β ≤ 100; default 0.5",
    )
    .sweep(),
    KeyInfo::new(
        H,
        "gamma",
        Kind::Number,
        "",
        "γ, the shape of unloading, |γ| ≤ β; default 0.5 (β + γ = 1 puts the plateau at \
         (1 − α)k d_y)",
    )
    .sweep(),
];
