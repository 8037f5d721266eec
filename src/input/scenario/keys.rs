//! The valid keys of every table of a scenario file, for the suggestions of unknown-key errors
//! (`diagnostics::Ctx`): each table's key set is distinct (tested in `tests/unknown_keys.rs`).

/// Valid keys of each table, for suggestions.
pub(super) const TABLES: &[(&str, &[&str])] = &[
    (
        "the top level",
        &[
            "title",
            "structure",
            "contact",
            "ground_motion",
            "solver",
            "separation",
            "output",
        ],
    ),
    ("[output]", &["floor_stations"]),
    (
        "[[structure]]",
        &[
            "kind",
            "name",
            "length",
            "mass",
            "period",
            "bending_stiffness",
            "tip_stiffness",
            "modes",
            "damping_ratio",
            "strain_rate_damping",
            "air_damping",
            "floor_heights",
            "floor_masses",
            "storey_stiffnesses",
            "storeys",
            "storey_height",
            "floor_mass",
            "storey_stiffness",
            "rayleigh",
            "periods",
            "mode_shapes",
            "modes_file",
            "hysteresis",
        ],
    ),
    ("[structure.rayleigh]", &["damping_ratio", "modes"]),
    (
        "[structure.hysteresis]",
        &[
            "model",
            "yield_drifts",
            "yield_forces",
            "post_yield_ratio",
            "exponent",
            "beta",
            "gamma",
        ],
    ),
    (
        "[contact]",
        &[
            "law",
            "stiffness",
            "restitution",
            "damping_model",
            "gap",
            "height",
            "level",
        ],
    ),
    ("[[contact.level]]", &["height", "gap"]),
    ("ground_motion.processing", PROCESSING_KEYS),
    (
        "[ground_motion]",
        &[
            "kind",
            "pga",
            "period",
            "file",
            "units",
            "scale_to_pga",
            "dt",
            "component",
            "processing",
            "spectrum",
            "sds",
            "sd1",
            "tl",
            "ag",
            "ground_type",
            "type",
            "records",
            "scaling",
        ],
    ),
    (
        "[solver]",
        &[
            "method",
            "dt",
            "duration",
            "output_interval",
            "rtol",
            "atol",
        ],
    ),
];

/// Valid keys of the `[separation]` tables (re-exported as `design::TABLES`).
pub const SEPARATION_TABLES: &[(&str, &[&str])] = &[
    (
        "[separation]",
        &["asce7", "is1893", "nbcc", "gb50011", "ntc", "ec8"],
    ),
    (
        "[separation.asce7]",
        &["cd", "ie", "r", "displacement_factor", "boundary"],
    ),
    (
        "[separation.is1893]",
        &["r", "displacement_factor", "floor_reduction"],
    ),
    (
        "[separation.ec8]",
        &["q", "qd", "boundary", "floor_reduction"],
    ),
    (
        "[separation.nbcc]",
        &["rd", "ro", "ie", "displacement_factor"],
    ),
    (
        "[separation.gb50011]",
        &["intensity", "systems", "partial_step"],
    ),
    (
        "[separation.ntc]",
        &[
            "zone",
            "method",
            "same_height_and_levels",
            "displacement_factor",
        ],
    ),
];

/// Valid keys of `ground_motion.processing`, for suggestions.
pub(crate) const PROCESSING_KEYS: &[&str] = &["baseline", "highpass_hz", "lowpass_hz", "order"];

/// Valid keys of the tables of `[ground_motion] kind = "suite"` (module `suite`), for the unknown-key suggestions.
pub(super) const SUITE_TABLES: &[(&str, &[&str])] = &[
    (
        "ground_motion.records",
        &["file", "component", "factor", "units", "dt", "processing"],
    ),
    (
        "ground_motion.scaling",
        &[
            "rule",
            "target",
            "range",
            "ratio",
            "factor_limits",
            "target_scale",
        ],
    ),
    (
        "ground_motion.scaling.target",
        &[
            "spectrum",
            "sds",
            "sd1",
            "tl",
            "ag",
            "units",
            "ground_type",
            "type",
            "file",
        ],
    ),
];
