//! `[ground_motion]` and its tables: a record's `processing`, a suite's `records`, `scaling`
//! and `scaling.target`.

use super::{KeyInfo, Kind, Table};

const P: Table = Table::Processing;
const G: Table = Table::Ground;
const REC: Table = Table::Records;
const SC: Table = Table::Scaling;
const T: Table = Table::Target;
const SA: Table = Table::ScaleToSa;

const HIGHPASS_WHY: &str = "strong-motion records are high-pass filtered at about 0.02–0.5 Hz; \
                            above 1 Hz the filter removes motion that buildings respond to";
const LOWPASS_WHY: &str = "strong-motion records are low-pass filtered at about 20–50 Hz; below \
                           5 Hz the filter removes motion that stiff buildings respond to";

/// The keys of `[ground_motion]` and the tables in it.
pub(super) const KEYS: &[KeyInfo] = &[
    KeyInfo::new(
        P,
        "baseline",
        Kind::Text,
        "",
        "\"linear\" (a least-squares line removed from the acceleration) or \"polynomial\" \
         (PEER's displacement baseline); default: the mean removed",
    ),
    KeyInfo::new(
        P,
        "highpass_hz",
        Kind::Number,
        "Hz",
        "corner of the zero-phase Butterworth high-pass filter",
    )
    .physical(1e-4, 100.0, "a high-pass corner of a record's filter")
    .usual(0.01, 1.0, HIGHPASS_WHY),
    KeyInfo::new(
        P,
        "lowpass_hz",
        Kind::Number,
        "Hz",
        "corner of the zero-phase Butterworth low-pass filter, above the high-pass one",
    )
    .physical(1e-2, 1e5, "a low-pass corner of a record's filter")
    .usual(5.0, 100.0, LOWPASS_WHY),
    KeyInfo::new(
        P,
        "order",
        Kind::Integer,
        "",
        "order of each Butterworth filter, 1 to 8; default 4",
    ),
    KeyInfo::new(
        G,
        "kind",
        Kind::Text,
        "",
        "\"harmonic\", \"record\", \"suite\" (records scaled by a code's rule) or \"spectrum\" \
         (a design spectrum, for `pounding separation`; no time history)",
    )
    .sweep(),
    KeyInfo::new(
        G,
        "pga",
        Kind::Number,
        "g",
        "harmonic: peak ground acceleration (as an axis with a record: sets `scale_to_pga`)",
    )
    .physical(1e-6, 20.0, "a peak ground acceleration")
    .sweep()
    .label("PGA"),
    KeyInfo::new(
        G,
        "period",
        Kind::Number,
        "s",
        "harmonic: the ground's period T_g, y = A sin(2πt/T_g)",
    )
    .physical(0.01, 100.0, "a structural or ground period")
    .usual(
        0.02,
        20.0,
        "earthquake ground motion has its energy at periods of about 0.05–10 s (long-period \
             pulses up to about 20 s)",
    )
    .sweep()
    .label("Tg"),
    KeyInfo::new(
        G,
        "file",
        Kind::File,
        "",
        "record: the accelerogram, relative to the scenario file (layout detected from the \
         content); spectrum \"table\": the (T, S_a) pairs",
    )
    .sweep()
    .label("record"),
    KeyInfo::new(
        G,
        "units",
        Kind::Text,
        "",
        "record: \"g\", \"cm/s2\" (gal) or \"m/s2\" (default: the file's own); spectrum: the \
         unit of `ag` or of the table's S_a",
    )
    .sweep(),
    KeyInfo::new(
        G,
        "scale_to_pga",
        Kind::Number,
        "g",
        "record: scale it so that its PGA is this",
    )
    .physical(1e-6, 20.0, "a peak ground acceleration")
    .sweep()
    .label("PGA"),
    KeyInfo::new(
        G,
        "scale_to_sa",
        Kind::Table,
        "",
        "record: scale it so that its pseudo-acceleration at a period is this, see \
         ground_motion.scale_to_sa; not with `scale_to_pga`",
    ),
    KeyInfo::new(
        G,
        "dt",
        Kind::Number,
        "s",
        "record: the sample spacing of a one-column file",
    )
    .physical(1e-7, 100.0, "a time step")
    .sweep(),
    KeyInfo::new(
        G,
        "component",
        Kind::Text,
        "",
        "record: which channel of a file with several, by number (1, 2, …) or name (\"90\", \
         \"EW\", \"Up\", \"HNE\")",
    ),
    KeyInfo::new(
        G,
        "processing",
        Kind::Table,
        "",
        "record: baseline correction and filtering, see ground_motion.processing",
    ),
    KeyInfo::new(
        G,
        "spectrum",
        Kind::Text,
        "",
        "spectrum: \"asce7\", \"ec8\" or \"table\"",
    ),
    KeyInfo::new(
        G,
        "sds",
        Kind::Number,
        "g",
        "spectrum \"asce7\": S_DS, in (0, 5]",
    ),
    KeyInfo::new(
        G,
        "sd1",
        Kind::Number,
        "g",
        "spectrum \"asce7\": S_D1, in (0, 5]",
    ),
    KeyInfo::new(
        G,
        "tl",
        Kind::Number,
        "s",
        "spectrum \"asce7\": T_L, in (0, 20], at least S_D1/S_DS",
    ),
    KeyInfo::new(
        G,
        "ag",
        Kind::Number,
        "m/s²",
        "spectrum \"ec8\": a_g on type A ground, (0, 30] m/s², or in g (0, 3] with units = \"g\"",
    ),
    KeyInfo::new(
        G,
        "ground_type",
        Kind::Text,
        "",
        "spectrum \"ec8\": \"A\" … \"E\" (EN 1998-1 Table 3.1)",
    ),
    KeyInfo::new(
        G,
        "type",
        Kind::Integer,
        "",
        "spectrum \"ec8\": 1 or 2 (Tables 3.2, 3.3)",
    ),
    KeyInfo::new(
        G,
        "records",
        Kind::Table,
        "",
        "suite: one table per record, see ground_motion.records",
    ),
    KeyInfo::new(
        G,
        "scaling",
        Kind::Table,
        "",
        "suite: the code's scaling rule and target, see ground_motion.scaling",
    ),
    KeyInfo::new(
        REC,
        "file",
        Kind::File,
        "",
        "the record file, relative to the scenario file",
    ),
    KeyInfo::new(
        REC,
        "component",
        Kind::Text,
        "",
        "as `ground_motion.component`",
    ),
    KeyInfo::new(
        REC,
        "factor",
        Kind::Number,
        "",
        "the record's scale factor, in (0, 100], only with rule = \"none\" (default 1)",
    ),
    KeyInfo::new(REC, "units", Kind::Text, "", "as `ground_motion.units`"),
    KeyInfo::new(REC, "dt", Kind::Number, "s", "as `ground_motion.dt`").physical(
        1e-7,
        100.0,
        "a time step",
    ),
    KeyInfo::new(
        REC,
        "processing",
        Kind::Table,
        "",
        "as `ground_motion.processing`",
    ),
    KeyInfo::new(
        SC,
        "rule",
        Kind::Text,
        "",
        "\"asce7\" (ASCE 7-16 Chapter 16, ≥ 11 records), \"ec8\" (EN 1998-1 §3.2.3.1.2, ≥ 3 \
         records) or \"none\" (each record at its `factor`)",
    ),
    KeyInfo::new(
        SC,
        "target",
        Kind::Table,
        "",
        "the target spectrum, see ground_motion.scaling.target",
    ),
    KeyInfo::new(
        SC,
        "range",
        Kind::List,
        "s",
        "[lo, hi], a period range wider than the code's (default 0.2 × the shorter to 2 × the \
         longer first-mode period)",
    ),
    KeyInfo::new(
        SC,
        "ratio",
        Kind::Number,
        "",
        "the mean-to-target ratio to reach, ≥ 0.9",
    ),
    KeyInfo::new(
        SC,
        "factor_limits",
        Kind::List,
        "",
        "[min, max] scale factor of each record",
    ),
    KeyInfo::new(
        SC,
        "target_scale",
        Kind::Number,
        "",
        "a factor on the target instead of the rule's",
    ),
    KeyInfo::new(T, "spectrum", Kind::Text, "", "as `ground_motion.spectrum`"),
    KeyInfo::new(T, "sds", Kind::Number, "g", "as `ground_motion.sds`"),
    KeyInfo::new(T, "sd1", Kind::Number, "g", "as `ground_motion.sd1`"),
    KeyInfo::new(T, "tl", Kind::Number, "s", "as `ground_motion.tl`"),
    KeyInfo::new(T, "ag", Kind::Number, "m/s²", "as `ground_motion.ag`"),
    KeyInfo::new(T, "units", Kind::Text, "", "as `ground_motion.units`"),
    KeyInfo::new(
        T,
        "ground_type",
        Kind::Text,
        "",
        "as `ground_motion.ground_type`",
    ),
    KeyInfo::new(T, "type", Kind::Integer, "", "as `ground_motion.type`"),
    KeyInfo::new(
        T,
        "file",
        Kind::File,
        "",
        "spectrum \"table\": as `ground_motion.file`",
    ),
    KeyInfo::new(
        SA,
        "period",
        Kind::Number,
        "s",
        "the period T of the oscillator whose PSA is set, at least dt/100 of the record",
    )
    .physical(0.01, 100.0, "a structural or ground period")
    .usual(
        0.01,
        10.0,
        "design spectra and ground-motion models give S_a from about 0.01 s to 10 s",
    )
    .sweep()
    .label("T of S_a"),
    KeyInfo::new(
        SA,
        "sa",
        Kind::Number,
        "g",
        "the target pseudo-acceleration PSA(T) = ω²·max|u|; the record is multiplied by \
         sa / PSA(T) of the record as read",
    )
    .physical(1e-6, 50.0, "a spectral acceleration")
    .sweep()
    .label("S_a"),
    KeyInfo::new(
        SA,
        "damping",
        Kind::Number,
        "",
        "the oscillator's damping ratio, in [0, 1); default 0.05",
    ),
];
