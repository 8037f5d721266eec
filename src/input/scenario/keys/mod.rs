//! The one table of a scenario file's keys (issue 26): every key once, with its table, the type
//! of its value, its unit, its physical range (refused outside), its usual band (warned
//! outside), its axis label and a line of documentation. From it come the valid keys of each
//! table (unknown-key suggestions, `diagnostics::Ctx`), the ranges ([`super::physical_range`],
//! [`super::usual_range`]), the keys a sweep axis may set and their types
//! (`study::sweep`), the sweep pictures' axis labels (`figures::sweep::axis_label`) and
//! docs/scenario-keys.md ([`markdown`], tested to be current).
//!
//! The entries are in `structure` (`[[structure]]` and its sub-tables), `motion`
//! (`[ground_motion]` and its sub-tables) and `run` (the top level, `[contact]`, `[solver]`,
//! `[output]`, `[separation]`). Within a table, the entries are in the order in which messages
//! list the table's valid keys.

mod doc;
mod motion;
mod run;
mod structure;

pub use doc::{REGENERATE, markdown};

/// A table of a scenario file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Table {
    /// The top level.
    Top,
    /// `[output]`.
    Output,
    /// `[[structure]]`.
    Structure,
    /// `[structure.rayleigh]`.
    Rayleigh,
    /// `[structure.hysteresis]`.
    Hysteresis,
    /// `[contact]`.
    Contact,
    /// `[[contact.level]]`.
    Level,
    /// `ground_motion.processing` (also of each record of a suite).
    Processing,
    /// `[ground_motion]`.
    Ground,
    /// `[solver]`.
    Solver,
    /// `[separation]`.
    Separation,
    /// `[separation.asce7]`.
    Asce7,
    /// `[separation.is1893]`.
    Is1893,
    /// `[separation.ec8]`.
    Ec8,
    /// `[separation.nbcc]`.
    Nbcc,
    /// `[separation.gb50011]`.
    Gb50011,
    /// `[separation.ntc]`.
    Ntc,
    /// `ground_motion.records` (each record of a suite).
    Records,
    /// `ground_motion.scaling` (a suite's scaling).
    Scaling,
    /// `ground_motion.scaling.target`.
    Target,
    /// `ground_motion.scale_to_sa` (a record scaled to a spectral acceleration).
    ScaleToSa,
}

/// Every table, in the order of the documentation.
pub const ALL_TABLES: [Table; 21] = [
    Table::Top,
    Table::Output,
    Table::Structure,
    Table::Rayleigh,
    Table::Hysteresis,
    Table::Contact,
    Table::Level,
    Table::Processing,
    Table::Ground,
    Table::Solver,
    Table::Separation,
    Table::Asce7,
    Table::Is1893,
    Table::Ec8,
    Table::Nbcc,
    Table::Gb50011,
    Table::Ntc,
    Table::Records,
    Table::Scaling,
    Table::Target,
    Table::ScaleToSa,
];

impl Table {
    /// The table as messages name it ("unknown key `x` in `[contact]`").
    pub const fn title(self) -> &'static str {
        match self {
            Table::Top => "the top level",
            Table::Output => "[output]",
            Table::Structure => "[[structure]]",
            Table::Rayleigh => "[structure.rayleigh]",
            Table::Hysteresis => "[structure.hysteresis]",
            Table::Contact => "[contact]",
            Table::Level => "[[contact.level]]",
            Table::Processing => "ground_motion.processing",
            Table::Ground => "[ground_motion]",
            Table::Solver => "[solver]",
            Table::Separation => "[separation]",
            Table::Asce7 => "[separation.asce7]",
            Table::Is1893 => "[separation.is1893]",
            Table::Ec8 => "[separation.ec8]",
            Table::Nbcc => "[separation.nbcc]",
            Table::Gb50011 => "[separation.gb50011]",
            Table::Ntc => "[separation.ntc]",
            Table::Records => "ground_motion.records",
            Table::Scaling => "ground_motion.scaling",
            Table::Target => "ground_motion.scaling.target",
            Table::ScaleToSa => "ground_motion.scale_to_sa",
        }
    }

    /// The path of a key of this table as messages write it, before the key's name
    /// (`structure[i].`; empty at the top level).
    pub const fn path(self) -> &'static str {
        match self {
            Table::Top => "",
            Table::Output => "output.",
            Table::Structure => "structure[i].",
            Table::Rayleigh => "structure[i].rayleigh.",
            Table::Hysteresis => "structure[i].hysteresis.",
            Table::Contact => "contact.",
            Table::Level => "contact.level[j].",
            Table::Processing => "ground_motion.processing.",
            Table::Ground => "ground_motion.",
            Table::Solver => "solver.",
            Table::Separation => "separation.",
            Table::Asce7 => "separation.asce7.",
            Table::Is1893 => "separation.is1893.",
            Table::Ec8 => "separation.ec8.",
            Table::Nbcc => "separation.nbcc.",
            Table::Gb50011 => "separation.gb50011.",
            Table::Ntc => "separation.ntc.",
            Table::Records => "ground_motion.records[k].",
            Table::Scaling => "ground_motion.scaling.",
            Table::Target => "ground_motion.scaling.target.",
            Table::ScaleToSa => "ground_motion.scale_to_sa.",
        }
    }

    /// How a sweep axis names a key of this table, before the key's name (`N` the 1-based
    /// index): `None` for the tables no axis may set.
    pub const fn sweep_path(self) -> Option<&'static str> {
        match self {
            Table::Structure => Some("structure.N."),
            Table::Hysteresis => Some("structure.N.hysteresis."),
            Table::Contact => Some("contact."),
            Table::Level => Some("contact.level.N."),
            Table::Ground => Some("ground_motion."),
            Table::ScaleToSa => Some("ground_motion.scale_to_sa."),
            Table::Solver => Some("solver."),
            _ => None,
        }
    }

    /// `[ground_motion]` and the tables inside it.
    pub const fn in_ground_motion(self) -> bool {
        matches!(
            self,
            Table::Ground
                | Table::Processing
                | Table::Records
                | Table::Scaling
                | Table::Target
                | Table::ScaleToSa
        )
    }

    /// The table's keys, in the order messages list them.
    pub fn keys(self) -> impl Iterator<Item = &'static KeyInfo> {
        all().filter(move |k| k.table == self)
    }

    /// The table's key names, in the order messages list them.
    pub fn names(self) -> Vec<&'static str> {
        self.keys().map(|k| k.name).collect()
    }
}

/// The type of a key's value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A number.
    Number,
    /// A whole number.
    Integer,
    /// A name (one of a set, or free text).
    Text,
    /// A file path, relative to the scenario file.
    File,
    /// A list of numbers.
    List,
    /// `true` or `false`.
    Bool,
    /// A table (or an inline table, or an array of tables).
    Table,
}

impl Kind {
    /// As the documentation names it.
    pub const fn name(self) -> &'static str {
        match self {
            Kind::Number => "number",
            Kind::Integer => "whole number",
            Kind::Text => "text",
            Kind::File => "file",
            Kind::List => "list",
            Kind::Bool => "true/false",
            Kind::Table => "table",
        }
    }
}

/// A closed range of values and why it is that range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lowest value.
    pub lo: f64,
    /// Highest value.
    pub hi: f64,
    /// What the range is of (a physical range: "a structure's height") or why it is usual.
    pub why: &'static str,
}

/// One key of a scenario file: everything the program and its documentation say about it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeyInfo {
    /// The table it is in.
    pub table: Table,
    /// Its name in the table.
    pub name: &'static str,
    /// The type of its value.
    pub kind: Kind,
    /// Its SI unit as messages write it (empty: none, or depends on other keys: see `doc`).
    pub unit: &'static str,
    /// Values outside are refused (issue 15): only what no structure, motion or run can be.
    pub physical: Option<Range>,
    /// Values inside `physical` but outside this band are accepted with a warning.
    pub usual: Option<Range>,
    /// A sweep axis may set it (as `Table::sweep_path` + name).
    pub sweep: bool,
    /// A sweep picture's axis label (with the unit added in brackets; `{i}` is the structure's
    /// number): `None` draws the key itself.
    pub label: Option<&'static str>,
    /// What it is, and what else is allowed or assumed.
    pub doc: &'static str,
}

impl KeyInfo {
    /// A key without ranges, label or sweep.
    pub(crate) const fn new(
        table: Table,
        name: &'static str,
        kind: Kind,
        unit: &'static str,
        doc: &'static str,
    ) -> KeyInfo {
        KeyInfo {
            table,
            name,
            kind,
            unit,
            physical: None,
            usual: None,
            sweep: false,
            label: None,
            doc,
        }
    }

    pub(crate) const fn physical(mut self, lo: f64, hi: f64, why: &'static str) -> KeyInfo {
        self.physical = Some(Range { lo, hi, why });
        self
    }

    pub(crate) const fn usual(mut self, lo: f64, hi: f64, why: &'static str) -> KeyInfo {
        self.usual = Some(Range { lo, hi, why });
        self
    }

    pub(crate) const fn sweep(mut self) -> KeyInfo {
        self.sweep = true;
        self
    }

    pub(crate) const fn label(mut self, label: &'static str) -> KeyInfo {
        self.label = Some(label);
        self
    }

    /// The key as messages write it (`structure[i].length`).
    pub fn path(&self) -> String {
        format!("{}{}", self.table.path(), self.name)
    }

    /// The key as a sweep axis names it (`structure.N.length`), if an axis may set it.
    pub fn sweep_key(&self) -> Option<String> {
        let prefix = self.table.sweep_path()?;
        self.sweep.then(|| format!("{prefix}{}", self.name))
    }
}

/// Every key of a scenario file.
pub fn all() -> impl Iterator<Item = &'static KeyInfo> {
    run::TOP
        .iter()
        .chain(structure::KEYS)
        .chain(run::CONTACT)
        .chain(motion::KEYS)
        .chain(run::SOLVER)
        .chain(run::SEPARATION)
}

/// Usual first-mode period of a building, s ([`super::usual_range`]): from a one-storey stiff frame to
/// the tallest towers (Burj Khalifa: about 11 s).
pub const USUAL_STRUCTURE_PERIOD: (f64, f64) = (0.02, 12.0);

/// Usual damping ratio of a building's first mode ([`super::usual_range`]).
pub const USUAL_DAMPING_RATIO: (f64, f64) = (0.005, 0.2);

/// Quantities that are not keys but what keys give together, with their usual bands (warned
/// about once per building, `scenario::hysteresis`).
pub const DERIVED: &[(&str, Range)] = &[
    // a storey's yield drift (`yield_drifts`, or `yield_forces`/k) over its height. Frames and
    // walls yield at drift ratios of about 0.1 % (stiff shear walls, masonry) to 3 % (flexible
    // steel or timber frames); 0.5–1 % is usual for frames.
    (
        "yield_drift_ratio",
        Range {
            lo: 1e-3,
            hi: 0.05,
            why: "storeys yield at drifts of about 0.1 % (shear walls) to 3 % (flexible frames) of \
                  their height, 0.5–1 % for most frames",
        },
    ),
    // β + γ. The plateau of the storey force is (1 − α) k d_y (β + γ)^(−1/n): with β + γ = 1
    // (β = γ = 0.5, the standard choice) d_y is the yield drift; outside [0.5, 2] the plateau
    // moves by more than a factor of 2^(1/n) (41 % at n = 2) from k d_y, and `yield_drifts` no
    // longer says where the storey yields.
    (
        "beta_plus_gamma",
        Range {
            lo: 0.5,
            hi: 2.0,
            why: "β + γ = 1 (β = γ = 0.5 is the standard choice) puts the plateau of the storey \
                  force at (1 − α)k·d_y; far from 1 the plateau moves as (β + γ)^(−1/n) and \
                  `yield_drifts` no longer says where the storey yields",
        },
    ),
];

/// The entry of `key`, given by path (`structure[1].period`, `ground_motion.processing.lowpass_hz`,
/// `ground_motion.records[2].dt`, or only its last component) that has `what`: the key's own
/// name names it, and the table decides between keys of the same name — a key under
/// `ground_motion` is one of `[ground_motion]`'s tables when they have a key of that name (so
/// `ground_motion.period` is the ground's, `period` or `structure[1].period` a structure's).
pub(crate) fn lookup(key: &str, what: impl Fn(&KeyInfo) -> bool) -> Option<&'static KeyInfo> {
    // a key given by its full path is that entry (`ground_motion.scale_to_sa.period` is not the
    // ground's `period`), whether or not it has `what`. Compared character by character with
    // the indices left out, without building strings: this runs for every key a scenario
    // validates, and so for every case of a sweep.
    if let Some(k) =
        all().find(|k| unindexed(key).eq(unindexed(k.table.path()).chain(k.name.chars())))
    {
        return what(k).then_some(k);
    }
    let last = key.rsplit('.').next().unwrap_or(key);
    let named = || all().filter(move |k| k.name == last);
    if key.starts_with("ground_motion") && named().any(|k| k.table.in_ground_motion()) {
        return named().find(|k| k.table.in_ground_motion() && what(k));
    }
    named()
        .find(|k| !k.table.in_ground_motion() && what(k))
        .or_else(|| named().find(|k| what(k)))
}

/// The characters of `p` outside brackets (`structure[1].period` → `structure.period`).
fn unindexed(p: &str) -> impl Iterator<Item = char> + '_ {
    let mut depth = 0u32;
    p.chars().filter(move |&ch| match ch {
        '[' => {
            depth += 1;
            false
        }
        ']' => {
            depth = depth.saturating_sub(1);
            false
        }
        _ => depth == 0,
    })
}

/// The table whose key set is exactly `keys` (serde's list of a table's fields): every table's
/// key set is distinct (tested in `tests/unknown_keys.rs`).
pub(crate) fn table_with_keys(keys: &[String]) -> Option<Table> {
    ALL_TABLES.into_iter().find(|t| {
        let names = t.names();
        names.len() == keys.len() && keys.iter().all(|k| names.contains(&k.as_str()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_of_one_name_have_one_physical_range() {
        // `physical_range` finds a key by its last component: keys of the same name in
        // several tables (`period`, `dt`, `gap`, the processing keys) must agree
        for a in all() {
            for b in all().filter(|b| b.name == a.name) {
                if let (Some(x), Some(y)) = (a.physical, b.physical) {
                    assert_eq!((x.lo, x.hi), (y.lo, y.hi), "{} / {}", a.path(), b.path());
                }
            }
        }
    }

    #[test]
    fn every_key_is_in_its_table_once_and_ranges_are_ordered() {
        for t in ALL_TABLES {
            let names = t.names();
            let mut sorted = names.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), names.len(), "{}", t.title());
        }
        for k in all() {
            for r in [k.physical, k.usual].into_iter().flatten() {
                assert!(
                    r.lo <= r.hi && r.lo.is_finite() && r.hi.is_finite(),
                    "{}",
                    k.path()
                );
            }
            if let (Some(p), Some(u)) = (k.physical, k.usual) {
                // a usual band outside the physical range would warn about refused values
                assert!(p.lo <= u.lo && u.hi <= p.hi, "{}", k.path());
            }
            assert!(!k.doc.is_empty(), "{}", k.path());
            assert!(!k.sweep || k.table.sweep_path().is_some(), "{}", k.path());
            assert!(
                !k.sweep || !matches!(k.kind, Kind::Table | Kind::Bool),
                "{}",
                k.path()
            );
        }
    }

    #[test]
    fn lookup_tells_the_ground_from_a_structure() {
        let usual = |k: &str| lookup(k, |e| e.usual.is_some()).map(|e| e.path());
        assert_eq!(
            usual("ground_motion.period").as_deref(),
            Some("ground_motion.period")
        );
        assert_eq!(
            usual("structure[2].period").as_deref(),
            Some("structure[i].period")
        );
        assert_eq!(usual("period").as_deref(), Some("structure[i].period"));
        // a record's sample spacing has no band of its own; the solver's step has one
        assert_eq!(usual("ground_motion.dt"), None);
        assert_eq!(usual("ground_motion.records[3].dt"), None);
        assert_eq!(usual("dt").as_deref(), Some("solver.dt"));
        assert_eq!(
            usual("ground_motion.records[1].processing.lowpass_hz").as_deref(),
            Some("ground_motion.processing.lowpass_hz")
        );
    }
}
