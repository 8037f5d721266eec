//! The key paths an axis may set: derived ratios (`period_ratio`, `ground_period_ratio`) and
//! any scenario key by path (`structure.1.period`, `contact.level.2.gap`, and for a row of
//! buildings `structure[3].period`, `contact[2].gap`, `contact[2].level[1].gap`: the contact of
//! adjacent pair 2, structures 2 and 3), each with the
//! type of its value (`parse_key`, `valid_keys` for suggestions): which keys and their types
//! come from the scenario's key table (`input::scenario::keys`, `sweep`).

use crate::input::scenario::MAX_ROW;
pub(super) use crate::input::scenario::keys::Kind;
use crate::input::scenario::keys::{KeyInfo, Table};

/// Where in the scenario an axis writes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum Section {
    Structure(usize),
    /// A structure's `hysteresis` table (issue 16).
    Hysteresis(usize),
    Contact,
    Level(usize),
    /// `contact[P].…`: the contact of adjacent pair P (0-based here) of a row, whichever
    /// `[[contact]]` table of the base names it (issue 29).
    PairContact(usize),
    /// `contact[P].level[L].…`: level L of pair P's contact (both 0-based here).
    PairLevel(usize, usize),
    Ground,
    /// `ground_motion.scale_to_sa` (issue 27).
    ScaleToSa,
    Solver,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum Target {
    PeriodRatio,
    GroundPeriodRatio,
    /// `structure.N.stiffness_scale` (`mass = false`) or `structure.N.mass_scale`: every
    /// stiffness (mass) of structure N times the value, the periods given following.
    Scale {
        structure: usize,
        mass: bool,
    },
    Key {
        section: Section,
        field: &'static str,
        kind: Kind,
    },
}

/// The derived axes, which are not scenario keys (the module doc says what each sets).
pub(super) const DERIVED_AXES: &[&str] = &[
    "period_ratio",
    "ground_period_ratio",
    "structure.N.stiffness_scale",
    "structure.N.mass_scale",
];

/// The keys of `table` an axis may set (the key table's `sweep`).
fn fields(table: Table) -> impl Iterator<Item = &'static KeyInfo> {
    table.keys().filter(|k| k.sweep)
}

/// Every key an axis may have (for messages), with `N` for an index: the derived axes, then
/// the scenario's keys in the key table's order.
pub(super) fn valid_keys() -> Vec<String> {
    let mut v: Vec<String> = DERIVED_AXES[..2].iter().map(|k| k.to_string()).collect();
    let scenario = |t: Table| fields(t).filter_map(KeyInfo::sweep_key);
    v.extend(scenario(Table::Structure));
    v.extend(DERIVED_AXES[2..].iter().map(|k| k.to_string()));
    for t in [Table::Hysteresis, Table::Contact, Table::Level] {
        v.extend(scenario(t));
    }
    // a row's pairs (issue 29): the contact and level keys of pair P
    for t in [Table::Contact, Table::Level] {
        v.extend(scenario(t).map(|k| k.replacen("contact.", "contact.P.", 1)));
    }
    for t in [Table::Ground, Table::ScaleToSa, Table::Solver] {
        v.extend(scenario(t));
    }
    v
}

/// Parse a key path. `Err` is the reason.
pub(super) fn parse_key(raw: &str) -> Result<(String, Target), String> {
    let key = raw.trim().replace('[', ".").replace(']', "");
    let parts: Vec<&str> = key.split('.').collect();
    let field = |table: Table, f: &str| {
        fields(table)
            .find(|k| k.name == f)
            .map(|k| (k.name, k.kind))
            .ok_or(())
    };
    let index = |s: &str, what: &str, max: Option<usize>| -> Result<usize, String> {
        match s.parse::<usize>() {
            Ok(n) if n >= 1 && max.is_none_or(|m| n <= m) => Ok(n - 1),
            _ => Err(format!(
                "`{s}` is not a valid {what} index: {}",
                match max {
                    Some(m) => format!("use 1 to {m} (1-based)"),
                    None => "use 1, 2, … (1-based)".into(),
                }
            )),
        }
    };
    let is_index = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_digit());
    let target = match parts.as_slice() {
        ["period_ratio"] => Ok(Target::PeriodRatio),
        ["ground_period_ratio"] => Ok(Target::GroundPeriodRatio),
        ["structure", n, f @ ("stiffness_scale" | "mass_scale")] => {
            let i = index(n, "structure", Some(MAX_ROW))?;
            Ok(Target::Scale {
                structure: i,
                mass: *f == "mass_scale",
            })
        }
        ["structure", n, "hysteresis", f] => {
            let i = index(n, "structure", Some(MAX_ROW))?;
            field(Table::Hysteresis, f).map(|(field, kind)| Target::Key {
                section: Section::Hysteresis(i),
                field,
                kind,
            })
        }
        ["structure", n, f] => {
            let i = index(n, "structure", Some(MAX_ROW))?;
            field(Table::Structure, f).map(|(field, kind)| Target::Key {
                section: Section::Structure(i),
                field,
                kind,
            })
        }
        ["contact", "level", n, f] => {
            let i = index(n, "contact level", None)?;
            field(Table::Level, f).map(|(field, kind)| Target::Key {
                section: Section::Level(i),
                field,
                kind,
            })
        }
        ["contact", p, "level", n, f] if is_index(p) => {
            let p = index(p, "pair", Some(MAX_ROW - 1))?;
            let i = index(n, "contact level", None)?;
            field(Table::Level, f).map(|(field, kind)| Target::Key {
                section: Section::PairLevel(p, i),
                field,
                kind,
            })
        }
        ["contact", p, f] if is_index(p) => {
            let p = index(p, "pair", Some(MAX_ROW - 1))?;
            field(Table::Contact, f).map(|(field, kind)| Target::Key {
                section: Section::PairContact(p),
                field,
                kind,
            })
        }
        ["contact", f] => field(Table::Contact, f).map(|(field, kind)| Target::Key {
            section: Section::Contact,
            field,
            kind,
        }),
        ["ground_motion", "scale_to_sa", f] => {
            field(Table::ScaleToSa, f).map(|(field, kind)| Target::Key {
                section: Section::ScaleToSa,
                field,
                kind,
            })
        }
        ["ground_motion", f] => field(Table::Ground, f).map(|(field, kind)| Target::Key {
            section: Section::Ground,
            field,
            kind,
        }),
        ["solver", f] => field(Table::Solver, f).map(|(field, kind)| Target::Key {
            section: Section::Solver,
            field,
            kind,
        }),
        _ => Err(()),
    };
    match target {
        Ok(t) => Ok((key, t)),
        Err(()) => {
            let keys = valid_keys();
            let generic = key
                .split('.')
                .map(|p| {
                    if p.chars().all(|c| c.is_ascii_digit()) {
                        "N"
                    } else {
                        p
                    }
                })
                .collect::<Vec<_>>()
                .join(".");
            let best = keys
                .iter()
                .map(|k| (strsim::jaro_winkler(&generic, k), k))
                .max_by(|a, b| a.0.total_cmp(&b.0));
            let mut msg = "unknown axis key".to_string();
            if let Some((score, k)) = best
                && score > 0.8
            {
                msg.push_str(&format!("; did you mean `{k}`?"));
            }
            msg.push_str(&format!(
                " (valid keys: {}; N is 1-based; P is 1-based too: a row's adjacent pair P, between its structures P and P + 1)",
                keys.join(", ")
            ));
            Err(msg)
        }
    }
}

/// Round to 12 significant digits, so that generated grids read 0.3, not 0.30000000000000004.
pub(super) fn tidy(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    format!("{x:.11e}").parse().unwrap_or(x)
}
