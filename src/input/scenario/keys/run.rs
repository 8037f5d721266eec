//! The top level, `[output]`, `[contact]` and its levels, `[solver]` and the `[separation]`
//! tables (the building codes' factors, `input::scenario::design`).

use super::{KeyInfo, Kind, Table};
use crate::integrate::{MIN_ATOL, MIN_RTOL};

use Table::{
    Asce7, Contact, Ec8, Gb50011, Is1893, Level, Nbcc, Ntc, Output, Separation, Solver, Top,
};

const GAP_RANGE: (f64, f64, &str) = (0.0, 10.0, "a gap between buildings");

/// The top level and `[output]`.
pub(super) const TOP: &[KeyInfo] = &[
    KeyInfo::new(
        Top,
        "title",
        Kind::Text,
        "",
        "a title for reports and plots (default: the file name)",
    ),
    KeyInfo::new(
        Top,
        "structure",
        Kind::Table,
        "",
        "[[structure]]: two, structure 1 (left) and 2 (right); or a row of up to 100 in order \
         along the row (issue 29), each with its own `name`",
    ),
    KeyInfo::new(
        Top,
        "contact",
        Kind::Table,
        "",
        "[contact]: the contact law and where the structures meet; a row: one [[contact]] per \
         adjacent pair, each with `between`",
    ),
    KeyInfo::new(
        Top,
        "ground_motion",
        Kind::Table,
        "",
        "[ground_motion]: the base excitation",
    ),
    KeyInfo::new(
        Top,
        "solver",
        Kind::Table,
        "",
        "[solver], optional: every key has a default",
    ),
    KeyInfo::new(
        Top,
        "separation",
        Kind::Table,
        "",
        "[separation], optional: the building codes' factors",
    ),
    KeyInfo::new(
        Top,
        "output",
        Kind::Table,
        "",
        "[output], optional: what the written files hold",
    ),
    KeyInfo::new(
        Output,
        "floor_stations",
        Kind::Text,
        "",
        "floors.csv's stations: \"contact\" (default: a building's every floor, a cantilever's \
         contact heights and top) or \"all\" (a cantilever's every tenth of its height too)",
    ),
];

/// `[contact]` and `[[contact.level]]`.
pub(super) const CONTACT: &[KeyInfo] = &[
    KeyInfo::new(
        Contact,
        "between",
        Kind::Text,
        "",
        "a row's [[contact]]: the two adjacent structures it is between, by `name`, as a list \
         (`between = [\"A\", \"B\"]`, either order); every adjacent pair needs its own table \
         (neighbours that cannot touch: a gap larger than any motion)",
    ),
    KeyInfo::new(
        Contact,
        "law",
        Kind::Text,
        "",
        "\"hertz\" (default), \"linear\", \"kelvin\", \"hertzdamp\", \"jankowski\" or \
         \"stereomechanical\"",
    )
    .sweep(),
    KeyInfo::new(
        Contact,
        "stiffness",
        Kind::Number,
        "",
        "k: N/m^1.5 for the Hertz family (hertz, hertzdamp, jankowski), N/m for linear and kelvin",
    )
    .physical(1e-3, 1e20, "a contact stiffness")
    .usual(
        1e6,
        1e13,
        "contact stiffnesses between buildings in the literature are about 10⁶–10¹³ \
         (N/m or N/m^1.5)",
    )
    .sweep(),
    KeyInfo::new(
        Contact,
        "restitution",
        Kind::Number,
        "",
        "target coefficient of restitution e (kelvin, hertzdamp, jankowski, stereomechanical), \
         in [0.01, 1]; [0, 1] for stereomechanical",
    )
    .usual(
        0.3,
        1.0,
        "impacts between buildings (concrete, steel, timber) have restitution of about \
         0.4–0.8",
    )
    .sweep(),
    KeyInfo::new(
        Contact,
        "damping_model",
        Kind::Text,
        "",
        "hertzdamp's χ(e): \"lankarani-nikravesh\" (default), \"hunt-crossley\", \"ye-li-zhu\"",
    )
    .sweep(),
    KeyInfo::new(Contact, "gap", Kind::Number, "m", "the at-rest gap d")
        .physical(GAP_RANGE.0, GAP_RANGE.1, GAP_RANGE.2)
        .sweep()
        .label("gap"),
    KeyInfo::new(
        Contact,
        "height",
        Kind::Number,
        "m",
        "contact height h, in [0.001·min(L₁, L₂), min(L₁, L₂)], a floor of a building; default \
         the top of the lower structure",
    )
    .sweep(),
    KeyInfo::new(
        Contact,
        "level",
        Kind::Table,
        "",
        "[[contact.level]]: several contact levels (then no `gap`, `height` above)",
    ),
    KeyInfo::new(
        Level,
        "height",
        Kind::Number,
        "m",
        "as `contact.height`; the levels' heights distinct",
    )
    .sweep(),
    KeyInfo::new(Level, "gap", Kind::Number, "m", "as `contact.gap`")
        .physical(GAP_RANGE.0, GAP_RANGE.1, GAP_RANGE.2)
        .sweep(),
];

/// `[solver]`.
pub(super) const SOLVER: &[KeyInfo] = &[
    KeyInfo::new(
        Solver,
        "method",
        Kind::Text,
        "",
        "\"exact-modal\" (default), \"adaptive\" (default with yielding storeys), \"rk4\" (the \
         paper's)",
    )
    .sweep(),
    KeyInfo::new(
        Solver,
        "dt",
        Kind::Number,
        "s",
        "the step (rk4), base step (exact-modal) or largest step (adaptive), below `duration`",
    )
    .physical(1e-7, 100.0, "a time step")
    .usual(
        1e-6,
        0.05,
        "a step below 1 µs takes very long; above 50 ms a step spans the short periods \
         of a building and of a record",
    )
    .sweep()
    .label("dt"),
    KeyInfo::new(
        Solver,
        "duration",
        Kind::Number,
        "s",
        "the simulated time (default 20 s for harmonic motion, a record's duration)",
    )
    .physical(1e-3, 1e7, "a simulated duration")
    .usual(1.0, 3600.0, "earthquake shaking lasts seconds to minutes")
    .sweep(),
    KeyInfo::new(
        Solver,
        "output_interval",
        Kind::Number,
        "s",
        "the sampling of history.csv (default 0.01 s, or dt if larger)",
    )
    .physical(1e-7, 1e6, "a sampling interval")
    .usual(
        1e-4,
        0.1,
        "history.csv sampled more sparsely than 0.1 s does not resolve a building's \
         motion (the peaks are still exact)",
    )
    .sweep(),
    KeyInfo::new(
        Solver,
        "rtol",
        Kind::Number,
        "",
        "relative tolerance of adaptive and of exact-modal's contact steps, in [1e-12, 0.1]",
    )
    .usual(
        MIN_RTOL,
        1e-3,
        "a relative tolerance above 1e-3 gives rough results (the self-check says how rough)",
    )
    .sweep(),
    KeyInfo::new(
        Solver,
        "atol",
        Kind::Number,
        "m",
        "absolute tolerance at a structure's top, in [1e-14, 1] (default rtol × 1 cm)",
    )
    .usual(
        MIN_ATOL,
        1e-3,
        "an absolute tolerance above 1 mm is coarser than the gaps it is meant to resolve",
    )
    .sweep(),
];

/// `[separation]` and its codes' tables (README, *Code separation rules*).
pub(super) const SEPARATION: &[KeyInfo] = &[
    KeyInfo::new(Separation, "asce7", Kind::Table, "", "ASCE 7-16 §12.12.3"),
    KeyInfo::new(
        Separation,
        "is1893",
        Kind::Table,
        "",
        "IS 1893 (Part 1):2016 §7.11.3",
    ),
    KeyInfo::new(Separation, "nbcc", Kind::Table, "", "NBCC Art. 4.1.8.14"),
    KeyInfo::new(
        Separation,
        "gb50011",
        Kind::Table,
        "",
        "GB 50011-2010 §6.1.4",
    ),
    KeyInfo::new(
        Separation,
        "ntc",
        Kind::Table,
        "",
        "NTC-Sismo 2004 (Mexico City) §1.10",
    ),
    KeyInfo::new(
        Separation,
        "ec8",
        Kind::Table,
        "",
        "EN 1998-1:2004 §4.4.2.7",
    ),
    KeyInfo::new(
        Asce7,
        "cd",
        Kind::Number,
        "",
        "C_d, in [1, 10] (Table 12.2-1); one, or one per structure",
    ),
    KeyInfo::new(
        Asce7,
        "ie",
        Kind::Number,
        "",
        "I_e, in [1, 1.5] (Table 1.5-2)",
    ),
    KeyInfo::new(
        Asce7,
        "r",
        Kind::Number,
        "",
        "R, in [1, 10] (or `displacement_factor`)",
    ),
    KeyInfo::new(
        Asce7,
        "displacement_factor",
        Kind::Number,
        "",
        "δ_max/δ_elastic (instead of `r`)",
    ),
    KeyInfo::new(
        Asce7,
        "boundary",
        Kind::Text,
        "",
        "\"same-property\" (default) or \"property-line\"",
    ),
    KeyInfo::new(Is1893, "r", Kind::Number, "", "R, in [1, 10]"),
    KeyInfo::new(
        Is1893,
        "displacement_factor",
        Kind::Number,
        "",
        "the code's displacement over the elastic one (required)",
    ),
    KeyInfo::new(
        Is1893,
        "floor_reduction",
        Kind::Bool,
        "",
        "R/2 at a level that is a floor of both structures (default true)",
    ),
    KeyInfo::new(Ec8, "q", Kind::Number, "", "behaviour factor q, in [1, 10]"),
    KeyInfo::new(Ec8, "qd", Kind::Number, "", "q_d, in [1, 10] (default q)"),
    KeyInfo::new(
        Ec8,
        "boundary",
        Kind::Text,
        "",
        "\"same-property\" (default) or \"property-line\"",
    ),
    KeyInfo::new(
        Ec8,
        "floor_reduction",
        Kind::Bool,
        "",
        "× 0.7 at a level that is a floor of both structures (default true)",
    ),
    KeyInfo::new(Nbcc, "rd", Kind::Number, "", "R_d, in [1, 10]"),
    KeyInfo::new(Nbcc, "ro", Kind::Number, "", "R_o, in [1, 10]"),
    KeyInfo::new(Nbcc, "ie", Kind::Number, "", "I_E, in [0.5, 2]"),
    KeyInfo::new(
        Nbcc,
        "displacement_factor",
        Kind::Number,
        "",
        "the code's displacement over the elastic one (required)",
    ),
    KeyInfo::new(
        Gb50011,
        "intensity",
        Kind::Integer,
        "",
        "seismic intensity 6, 7, 8 or 9",
    ),
    KeyInfo::new(
        Gb50011,
        "systems",
        Kind::Text,
        "",
        "\"frame\", \"frame-shear-wall\" or \"shear-wall\": one, or one per structure",
    ),
    KeyInfo::new(
        Gb50011,
        "partial_step",
        Kind::Text,
        "",
        "\"round-up\" (default) or \"linear\"",
    ),
    KeyInfo::new(Ntc, "zone", Kind::Text, "", "\"I\", \"II\" or \"III\""),
    KeyInfo::new(
        Ntc,
        "method",
        Kind::Text,
        "",
        "\"analysis\" (needs `displacement_factor`) or \"simplified\"",
    ),
    KeyInfo::new(
        Ntc,
        "same_height_and_levels",
        Kind::Bool,
        "",
        "the two structures have the same height and floor levels (default false; README, *Code separation rules*)",
    ),
    KeyInfo::new(
        Ntc,
        "displacement_factor",
        Kind::Number,
        "",
        "the code's displacement over the elastic one (method \"analysis\")",
    ),
];
