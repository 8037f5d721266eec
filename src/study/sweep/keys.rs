//! The key paths an axis may set: derived ratios (`period_ratio`, `ground_period_ratio`) and
//! any scenario key by path (`structure.1.period`, `contact.level.2.gap`, …), each with the
//! type of its value (`parse_key`, `valid_keys` for suggestions).

/// The type of value a scenario key takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Number,
    Integer,
    Text,
    File,
    List,
}

/// Where in the scenario an axis writes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum Section {
    Structure(usize),
    /// A structure's `hysteresis` table (issue 16).
    Hysteresis(usize),
    Contact,
    Level(usize),
    Ground,
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

pub(super) const STRUCTURE_FIELDS: &[(&str, Kind)] = &[
    ("length", Kind::Number),
    ("mass", Kind::Number),
    ("period", Kind::Number),
    ("bending_stiffness", Kind::Number),
    ("tip_stiffness", Kind::Number),
    ("modes", Kind::Integer),
    ("damping_ratio", Kind::Number),
    ("strain_rate_damping", Kind::Number),
    ("air_damping", Kind::Number),
    ("name", Kind::Text),
    // a shear building's uniform shorthand (kind = "shear-building")
    ("storeys", Kind::Integer),
    ("storey_height", Kind::Number),
    ("floor_mass", Kind::Number),
    ("storey_stiffness", Kind::Number),
    // a building's lists, one value per floor (or per mode for `periods`)
    ("floor_heights", Kind::List),
    ("floor_masses", Kind::List),
    ("storey_stiffnesses", Kind::List),
    ("periods", Kind::List),
];
/// A yielding building's Bouc–Wen keys (`structure.N.hysteresis.KEY`; one value for every
/// storey).
pub(super) const HYSTERESIS_FIELDS: &[(&str, Kind)] = &[
    ("yield_drifts", Kind::Number),
    ("yield_forces", Kind::Number),
    ("post_yield_ratio", Kind::Number),
    ("exponent", Kind::Number),
    ("beta", Kind::Number),
    ("gamma", Kind::Number),
];
pub(super) const CONTACT_FIELDS: &[(&str, Kind)] = &[
    ("stiffness", Kind::Number),
    ("restitution", Kind::Number),
    ("gap", Kind::Number),
    ("height", Kind::Number),
    ("law", Kind::Text),
    ("damping_model", Kind::Text),
];
pub(super) const LEVEL_FIELDS: &[(&str, Kind)] = &[("height", Kind::Number), ("gap", Kind::Number)];
pub(super) const GROUND_FIELDS: &[(&str, Kind)] = &[
    ("pga", Kind::Number),
    ("period", Kind::Number),
    ("scale_to_pga", Kind::Number),
    ("dt", Kind::Number),
    ("file", Kind::File),
    ("units", Kind::Text),
    ("kind", Kind::Text),
];
pub(super) const SOLVER_FIELDS: &[(&str, Kind)] = &[
    ("dt", Kind::Number),
    ("duration", Kind::Number),
    ("output_interval", Kind::Number),
    ("method", Kind::Text),
];

/// Every key an axis may have (for messages), with `N` for an index.
pub(super) fn valid_keys() -> Vec<String> {
    let mut v = vec![
        "period_ratio".to_string(),
        "ground_period_ratio".to_string(),
    ];
    for (f, _) in STRUCTURE_FIELDS {
        v.push(format!("structure.N.{f}"));
    }
    v.push("structure.N.stiffness_scale".into());
    v.push("structure.N.mass_scale".into());
    for (f, _) in HYSTERESIS_FIELDS {
        v.push(format!("structure.N.hysteresis.{f}"));
    }
    for (f, _) in CONTACT_FIELDS {
        v.push(format!("contact.{f}"));
    }
    for (f, _) in LEVEL_FIELDS {
        v.push(format!("contact.level.N.{f}"));
    }
    for (f, _) in GROUND_FIELDS {
        v.push(format!("ground_motion.{f}"));
    }
    for (f, _) in SOLVER_FIELDS {
        v.push(format!("solver.{f}"));
    }
    v
}

/// Parse a key path. `Err` is the reason.
pub(super) fn parse_key(raw: &str) -> Result<(String, Target), String> {
    let key = raw.trim().replace('[', ".").replace(']', "");
    let parts: Vec<&str> = key.split('.').collect();
    let field = |list: &[(&'static str, Kind)], f: &str| {
        list.iter()
            .find(|(n, _)| *n == f)
            .map(|(n, k)| (*n, *k))
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
    let target = match parts.as_slice() {
        ["period_ratio"] => Ok(Target::PeriodRatio),
        ["ground_period_ratio"] => Ok(Target::GroundPeriodRatio),
        ["structure", n, f @ ("stiffness_scale" | "mass_scale")] => {
            let i = index(n, "structure", Some(2))?;
            Ok(Target::Scale {
                structure: i,
                mass: *f == "mass_scale",
            })
        }
        ["structure", n, "hysteresis", f] => {
            let i = index(n, "structure", Some(2))?;
            field(HYSTERESIS_FIELDS, f).map(|(field, kind)| Target::Key {
                section: Section::Hysteresis(i),
                field,
                kind,
            })
        }
        ["structure", n, f] => {
            let i = index(n, "structure", Some(2))?;
            field(STRUCTURE_FIELDS, f).map(|(field, kind)| Target::Key {
                section: Section::Structure(i),
                field,
                kind,
            })
        }
        ["contact", "level", n, f] => {
            let i = index(n, "contact level", None)?;
            field(LEVEL_FIELDS, f).map(|(field, kind)| Target::Key {
                section: Section::Level(i),
                field,
                kind,
            })
        }
        ["contact", f] => field(CONTACT_FIELDS, f).map(|(field, kind)| Target::Key {
            section: Section::Contact,
            field,
            kind,
        }),
        ["ground_motion", f] => field(GROUND_FIELDS, f).map(|(field, kind)| Target::Key {
            section: Section::Ground,
            field,
            kind,
        }),
        ["solver", f] => field(SOLVER_FIELDS, f).map(|(field, kind)| Target::Key {
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
            msg.push_str(&format!(" (valid keys: {}; N is 1-based)", keys.join(", ")));
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
