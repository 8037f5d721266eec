//! How a sweep's pictures name things: a field's title, unit and colour scale, an axis key as a
//! person reads it (from the scenario's key table), and the short forms used in titles and file
//! names.

use std::path::Path;

use crate::plot::ColorScale;

use super::RATIO_LIMIT;

/// A field's title (with unit), short axis / colour-bar label and the factor from SI to the
/// unit shown. `change_percent_i` is drawn as the ratio peak with / without pounding.
pub fn field_label(field: &str) -> (String, String, f64) {
    let s = |t: &str| t.to_string();
    let (title, short, scale) = match field {
        "peak_displacement_1" | "peak_displacement_2" => (
            format!(
                "Peak displacement of structure {} with pounding",
                &field[18..]
            ),
            s("peak w [m]"),
            1.0,
        ),
        "peak_displacement_no_contact_1" | "peak_displacement_no_contact_2" => (
            format!(
                "Peak displacement of structure {} without pounding",
                &field[29..]
            ),
            s("peak w [m]"),
            1.0,
        ),
        "change_percent_1" | "change_percent_2" => (
            format!(
                "Structure {}: peak displacement with / without pounding",
                &field[15..]
            ),
            s("with / without"),
            1.0,
        ),
        "peak_force" => (s("Peak contact force"), s("peak force [MN]"), 1e-6),
        "impacts" => (s("Number of impacts"), s("impacts"), 1.0),
        "contact_time" => (s("Time in contact"), s("time in contact [s]"), 1.0),
        "sep_abs" => (s("Required separation, ABS rule"), s("separation [m]"), 1.0),
        "sep_srss" => (
            s("Required separation, SRSS rule"),
            s("separation [m]"),
            1.0,
        ),
        "sep_ddc" => (s("Required separation, DDC rule"), s("separation [m]"), 1.0),
        "sep_time_history" => (
            s("Required separation from the time history"),
            s("separation [m]"),
            1.0,
        ),
        "check_max_change" => (
            s("Self-check: largest change against a 100× tighter run"),
            s("largest change [%]"),
            100.0,
        ),
        "converged" => (
            s("Self-check converged within 1 % (1 = yes, 0 = no)"),
            s("converged"),
            1.0,
        ),
        "peak_floor_acceleration_1" | "peak_floor_acceleration_2" => (
            format!(
                "Structure {}: largest floor acceleration with pounding",
                &field[24..]
            ),
            s("acceleration [m/s²]"),
            1.0,
        ),
        "peak_floor_acceleration_no_contact_1" | "peak_floor_acceleration_no_contact_2" => (
            format!(
                "Structure {}: largest floor acceleration without pounding",
                &field[35..]
            ),
            s("acceleration [m/s²]"),
            1.0,
        ),
        "peak_drift_1" | "peak_drift_2" => (
            format!(
                "Structure {}: largest storey drift with pounding",
                &field[11..]
            ),
            s("drift [m]"),
            1.0,
        ),
        other => {
            return suite_field_label(other)
                .or_else(|| row_field_label(other))
                .unwrap_or((s(other), s(other), 1.0));
        }
    };
    (title, short, scale)
}

/// The labels of a suite's columns (`crate::study::sweep::suite_rows`).
fn suite_field_label(field: &str) -> Option<(String, String, f64)> {
    let s = |t: &str| t.to_string();
    if let Some(rest) = field.strip_prefix("level")
        && let Some((k, what)) = rest.split_once('_')
    {
        return Some(match what {
            "required_separation" => (
                format!("Level {k}: design value of the required separation (suite)"),
                s("separation [m]"),
                1.0,
            ),
            "peak_force" => (
                format!("Level {k}: design value of the peak contact force (suite)"),
                s("peak force [MN]"),
                1e-6,
            ),
            "gap" => (format!("Level {k}: gap"), s("gap [m]"), 1.0),
            "sufficient" => (
                format!("Level {k}: gap suffices by the code's procedure (1 = yes, 0 = no)"),
                s("suffices"),
                1.0,
            ),
            _ => return None,
        });
    }
    Some(match field {
        "sufficient" => (
            // (the same words for a suite's verdict by the code's procedure and a row's by
            // every rule of every pair: both are "at every level checked")
            s("Gap suffices at every level checked (1 = yes, 0 = no)"),
            s("suffices"),
            1.0,
        ),
        "governing_margin" => (
            s("Gap − required separation where the margin is smallest"),
            s("margin [m]"),
            1.0,
        ),
        "governing_level" => (s("Governing contact level"), s("level"), 1.0),
        "min_mean_to_target_ratio" => (
            s("Lowest mean-to-target ratio of the scaled suite"),
            s("mean / target"),
            1.0,
        ),
        "records" => (s("Number of records"), s("count"), 1.0),
        _ => return None,
    })
}

/// The labels of a row sweep's columns (`crate::study::sweep::row_columns`, and those of a
/// suite on a row, `crate::study::sweep::row_suite_rows`): each structure's `structure{i}_…`
/// and each pair's `pair{p}_…` (pair p: structures p and p + 1; a suite's
/// `pair{p}_level{K}_required_separation`), and the row's governing pair and count of
/// pounding pairs.
fn row_field_label(field: &str) -> Option<(String, String, f64)> {
    let s = |t: &str| t.to_string();
    let numbered = |prefix: &str| -> Option<(usize, &str)> {
        let rest = field.strip_prefix(prefix)?;
        let (k, what) = rest.split_once('_')?;
        Some((k.parse().ok()?, what))
    };
    if let Some((i, what)) = numbered("structure") {
        return Some(match what {
            "peak_displacement" => (
                format!("Structure {i}: peak displacement with pounding"),
                s("peak w [m]"),
                1.0,
            ),
            "peak_displacement_no_contact" => (
                format!("Structure {i}: peak displacement without pounding"),
                s("peak w [m]"),
                1.0,
            ),
            "change_percent" => (
                format!("Structure {i}: change of the peak displacement by pounding"),
                s("change [%]"),
                1.0,
            ),
            _ => return None,
        });
    }
    if let Some((p, what)) = numbered("pair") {
        let pair = format!("Pair {p} (structures {p}–{})", p + 1);
        // a suite on a row: the design value at each level of the pair
        if let Some(k) = what
            .strip_prefix("level")
            .and_then(|r| r.strip_suffix("_required_separation"))
        {
            return Some((
                format!("{pair}, level {k}: design value of the required separation (suite)"),
                s("separation [m]"),
                1.0,
            ));
        }
        return Some(match what {
            "impacts" => (format!("{pair}: number of impacts"), s("impacts"), 1.0),
            "peak_force" => (
                format!("{pair}: peak contact force"),
                s("peak force [MN]"),
                1e-6,
            ),
            "max_penetration" => (
                format!("{pair}: largest penetration"),
                s("penetration [m]"),
                1.0,
            ),
            "contact_time" => (
                format!("{pair}: time in contact"),
                s("time in contact [s]"),
                1.0,
            ),
            "sep_time_history" => (
                format!("{pair}: required separation from the time history"),
                s("separation [m]"),
                1.0,
            ),
            "governing_height" => (
                format!("{pair}: height where its margin is smallest"),
                s("height [m]"),
                1.0,
            ),
            "required" => (
                format!("{pair}: required separation where its margin is smallest"),
                s("separation [m]"),
                1.0,
            ),
            "margin" => (
                format!("{pair}: gap − required separation where the margin is smallest"),
                s("margin [m]"),
                1.0,
            ),
            "sufficient" => (
                format!("{pair}: gap suffices by every rule at every level (1 = yes, 0 = no)"),
                s("suffices"),
                1.0,
            ),
            _ => return None,
        });
    }
    Some(match field {
        "governing_pair" => (s("Pair of least margin"), s("pair"), 1.0),
        "governing_height" => (
            s("Height where the margin is smallest"),
            s("height [m]"),
            1.0,
        ),
        "governing_required" => (
            s("Required separation where the margin is smallest"),
            s("separation [m]"),
            1.0,
        ),
        "pounding_pairs" => (s("Number of pairs that pound"), s("pairs"), 1.0),
        "structures" => (s("Number of structures in the row"), s("count"), 1.0),
        _ => return None,
    })
}

/// How a field is coloured (and whether its line-plot axis is logarithmic), given its values:
/// the amplification ratio on the diverging log scale, else [`ColorScale::auto`].
pub fn field_scale(field: &str, values: &[f64]) -> ColorScale {
    if field.starts_with("change_percent_") {
        ColorScale::Ratio { limit: RATIO_LIMIT }
    } else if field.ends_with("sufficient") || field.ends_with("margin") {
        // a verdict (0/1) and a signed margin: linear, whatever their spread
        ColorScale::Linear
    } else {
        ColorScale::auto(values)
    }
}

/// An axis key as a person reads it, with the name the command line uses: the derived ratios'
/// symbols, else the scenario key's label and unit from its table
/// ([`crate::input::scenario::keys`]), else the key itself.
pub fn axis_label(key: &str) -> String {
    let readable = match key {
        "period_ratio" => "T1/T2".to_string(),
        "ground_period_ratio" => "T2/Tg".to_string(),
        _ => match scenario_label(key) {
            Some(l) => l,
            None => return key.to_string(),
        },
    };
    format!("{readable} ({key})")
}

/// A sweep key's label from the key table: `label [unit]`, `{i}` replaced by the structure's
/// number (`structure.2.period` → `T2 [s]`).
fn scenario_label(key: &str) -> Option<String> {
    let parts: Vec<&str> = key.split('.').collect();
    let index = parts.iter().find(|p| p.chars().all(|c| c.is_ascii_digit()));
    let generic: Vec<&str> = parts
        .iter()
        .map(|p| if Some(p) == index { "N" } else { p })
        .collect();
    let generic = generic.join(".");
    let info = crate::input::scenario::keys::all()
        .find(|k| k.sweep_key().as_deref() == Some(generic.as_str()))?;
    let label = info.label?.replace("{i}", index.copied().unwrap_or(""));
    Some(if info.unit.is_empty() {
        label
    } else {
        format!("{label} [{}]", info.unit)
    })
}

/// A short name for titles and legends.
pub(super) fn axis_name_short(key: &str) -> &str {
    match key {
        "period_ratio" => "T1/T2",
        "ground_period_ratio" => "T2/Tg",
        "ground_motion.pga" | "ground_motion.scale_to_pga" => "PGA",
        k => k,
    }
}

/// A value for a title: numbers as written, record files by their file name.
pub(super) fn show_value(key: &str, v: &str) -> String {
    match key {
        "ground_motion.file" => Path::new(v)
            .file_name()
            .map_or_else(|| v.to_string(), |f| f.to_string_lossy().into_owned()),
        "ground_motion.pga" | "ground_motion.scale_to_pga" => format!("{v} g"),
        _ => v.to_string(),
    }
}

/// An axis key as written in file names.
pub(super) fn file_key(key: &str) -> String {
    match key {
        "period_ratio" => "T1T2".into(),
        "ground_period_ratio" => "T2Tg".into(),
        "ground_motion.pga" => "PGA".into(),
        k => sanitize(k),
    }
}

pub(super) fn sanitize(s: &str) -> String {
    let ok = |c: char| c.is_ascii_alphanumeric() || c == '.' || c == '-' || c == '=';
    s.chars().map(|c| if ok(c) { c } else { '_' }).collect()
}
