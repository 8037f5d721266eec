//! One axis of a sweep: its values ([`AxisValue`]), where it writes (`keys`), and the checks of
//! an `[[axis]]` table (`parse_axis`) and of the axes together against the base scenario
//! (`check_axes`).

use std::fmt;

use toml::{Spanned, Table, Value};

use crate::numerics::format::fmt_f64;

use super::keys::{Kind, Section, Target, parse_key, tidy};
use super::{Ctx, MAX_STEPS, RawAxis, RawValue, SweepError};

// ---------------------------------------------------------------------------------------------
// Axes

/// One value on an axis.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValue {
    /// A number.
    Number(f64),
    /// An integer (e.g. `structure.1.modes`).
    Integer(i64),
    /// Text: a record file as listed in the sweep file, a contact law name, …
    Text(String),
    /// A list of numbers (a building's `floor_masses`, `storey_stiffnesses`, …).
    List(Vec<f64>),
}

impl AxisValue {
    /// The value as written in the results table (numbers in shortest round-trip form).
    pub fn to_csv(&self) -> String {
        match self {
            AxisValue::Number(x) => fmt_f64(*x),
            AxisValue::Integer(i) => i.to_string(),
            AxisValue::Text(s) => s.clone(),
            AxisValue::List(v) => format!(
                "[{}]",
                v.iter().map(|x| fmt_f64(*x)).collect::<Vec<_>>().join(" ")
            ),
        }
    }
}

impl fmt::Display for AxisValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AxisValue::Text(s) => write!(f, "\"{s}\""),
            other => f.write_str(&other.to_csv()),
        }
    }
}

/// One axis of the grid.
#[derive(Debug, Clone)]
pub struct Axis {
    /// The key as written (normalised: `structure[2].period` → `structure.2.period`); also
    /// the column name in the results.
    pub key: String,
    /// The values, in grid order.
    pub values: Vec<AxisValue>,
    pub(super) target: Target,
}

pub(super) fn parse_axis(ctx: &Ctx, n: usize, a: &Spanned<RawAxis>) -> Result<Axis, SweepError> {
    let name = |k: &str| format!("axis[{}].{k}", n + 1);
    let r = a.get_ref();
    let start = Some(a.span().start);
    let key_v = r.key.as_ref().ok_or_else(|| {
        ctx.invalid(
            start,
            &name("key"),
            "missing: e.g. key = \"period_ratio\", \"ground_period_ratio\" or a scenario key such as \"ground_motion.pga\"",
        )
    })?;
    let (key, target) = parse_key(key_v.get_ref())
        .map_err(|m| ctx.invalid(Some(key_v.span().start), &name("key"), m))?;
    let kind = match &target {
        Target::Key { kind, .. } => *kind,
        _ => Kind::Number,
    };
    let ratio = matches!(
        target,
        Target::PeriodRatio | Target::GroundPeriodRatio | Target::Scale { .. }
    );
    let values = match (&r.values, &r.from, &r.to, &r.steps) {
        (Some(list), None, None, None) => {
            if let Some(s) = &r.scale {
                return Err(ctx.invalid(
                    Some(s.span().start),
                    &name("scale"),
                    "`scale` goes with `from`, `to`, `steps`, not with `values`",
                ));
            }
            if list.get_ref().is_empty() {
                return Err(ctx.invalid(
                    Some(list.span().start),
                    &name("values"),
                    "give at least one value",
                ));
            }
            let mut out = Vec::new();
            let mut seen = std::collections::HashSet::new();
            for v in list.get_ref() {
                let at = Some(v.span().start);
                let value = match (v.get_ref(), kind) {
                    (RawValue::Text(s), Kind::Text | Kind::File) => {
                        if s.contains(['\n', '\r']) {
                            return Err(ctx.invalid(
                                at,
                                &name("values"),
                                "no line breaks in values",
                            ));
                        }
                        AxisValue::Text(s.clone())
                    }
                    (RawValue::Int(i), Kind::Integer) => AxisValue::Integer(*i),
                    (RawValue::Num(x), Kind::Integer) if x.fract() == 0.0 && x.abs() < 1e15 => {
                        AxisValue::Integer(*x as i64)
                    }
                    (RawValue::Int(i), Kind::Number) => AxisValue::Number(*i as f64),
                    (RawValue::Num(x), Kind::Number) => AxisValue::Number(*x),
                    (_, Kind::Text | Kind::File) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` takes text values (in quotes)"),
                        ));
                    }
                    (_, Kind::Integer) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` takes whole numbers"),
                        ));
                    }
                    (RawValue::List(v), Kind::List) => {
                        if v.is_empty() || v.iter().any(|x| !x.is_finite()) {
                            return Err(ctx.invalid(
                                at,
                                &name("values"),
                                format!("`{key}` takes lists of finite numbers, not empty ones"),
                            ));
                        }
                        AxisValue::List(v.clone())
                    }
                    (_, Kind::List) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` takes lists of numbers, e.g. values = [[2e5, 2e5], [3e5, 3e5]]"),
                        ));
                    }
                    // (no key an axis may set is a table or a boolean: tested in
                    // input::scenario::keys)
                    (_, Kind::Table | Kind::Bool) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` cannot be set by an axis"),
                        ));
                    }
                    (RawValue::Text(_) | RawValue::List(_), Kind::Number) => {
                        return Err(ctx.invalid(
                            at,
                            &name("values"),
                            format!("`{key}` takes numbers"),
                        ));
                    }
                };
                check_value(ctx, at, &name("values"), &value, ratio)?;
                if !seen.insert(value.to_csv()) {
                    return Err(ctx.invalid(
                        at,
                        &name("values"),
                        format!("{value} is listed twice"),
                    ));
                }
                out.push(value);
            }
            out
        }
        (None, Some(from), Some(to), Some(steps)) => {
            if kind == Kind::List {
                return Err(ctx.invalid(
                    start,
                    &name("from"),
                    format!("`{key}` takes lists: give them with `values = [[…], […]]`"),
                ));
            }
            if kind == Kind::Text || kind == Kind::File {
                return Err(ctx.invalid(
                    start,
                    &name("from"),
                    format!("`{key}` takes text: list them with `values = [\"…\", …]`"),
                ));
            }
            let s = *steps.get_ref();
            if !(1..=MAX_STEPS).contains(&s) {
                return Err(ctx.invalid(
                    Some(steps.span().start),
                    &name("steps"),
                    format!("= {s}: must be a whole number from 1 to {MAX_STEPS}"),
                ));
            }
            let (a, b) = (*from.get_ref(), *to.get_ref());
            for (v, k) in [(from, "from"), (to, "to")] {
                if !v.get_ref().is_finite() {
                    return Err(ctx.invalid(Some(v.span().start), &name(k), "must be finite"));
                }
            }
            let log = match r.scale.as_ref().map(|s| (s, s.get_ref().as_str())) {
                None | Some((_, "linear")) => false,
                Some((_, "log")) => true,
                Some((s, other)) => {
                    return Err(ctx.invalid(
                        Some(s.span().start),
                        &name("scale"),
                        format!("= \"{other}\": must be \"linear\" or \"log\""),
                    ));
                }
            };
            if log && !(a > 0.0 && b > 0.0) {
                return Err(ctx.invalid(
                    Some(from.span().start),
                    &name("from"),
                    "a logarithmic axis needs `from` and `to` > 0",
                ));
            }
            if s == 1 && a != b {
                return Err(ctx.invalid(
                    Some(steps.span().start),
                    &name("steps"),
                    "= 1 needs `from` = `to` (or use `values`)",
                ));
            }
            if s > 1 && a == b {
                return Err(ctx.invalid(
                    Some(to.span().start),
                    &name("to"),
                    "equals `from`: the values would repeat",
                ));
            }
            let s = s as usize;
            let mut out = Vec::with_capacity(s);
            for i in 0..s {
                let f = if s == 1 {
                    0.0
                } else {
                    i as f64 / (s - 1) as f64
                };
                let x = if i + 1 == s {
                    b
                } else if log {
                    tidy(a * (b / a).powf(f))
                } else {
                    tidy(a + (b - a) * f)
                };
                let value = if kind == Kind::Integer {
                    if x.fract() != 0.0 {
                        return Err(ctx.invalid(
                            start,
                            &name("steps"),
                            format!("`{key}` takes whole numbers, but the grid has {x}"),
                        ));
                    }
                    AxisValue::Integer(x as i64)
                } else {
                    AxisValue::Number(x)
                };
                check_value(ctx, Some(from.span().start), &name("from"), &value, ratio)?;
                // generated values are monotonic: a repeat can only be the previous value
                if out.last() == Some(&value) {
                    return Err(ctx.invalid(
                        Some(steps.span().start),
                        &name("steps"),
                        format!("{value} would appear twice: use fewer steps"),
                    ));
                }
                out.push(value);
            }
            out
        }
        (None, None, None, None) => {
            return Err(ctx.invalid(
                start,
                &name("values"),
                "missing: give `values = [...]`, or `from`, `to` and `steps`",
            ));
        }
        (Some(v), ..) => {
            return Err(ctx.invalid(
                Some(v.span().start),
                &name("values"),
                "give either `values` or `from`/`to`/`steps`, not both",
            ));
        }
        _ => {
            let missing: Vec<&str> = [
                ("from", r.from.is_none()),
                ("to", r.to.is_none()),
                ("steps", r.steps.is_none()),
            ]
            .into_iter()
            .filter(|(_, m)| *m)
            .map(|(k, _)| k)
            .collect();
            return Err(ctx.invalid(
                start,
                &name(missing[0]),
                format!(
                    "missing: a generated axis needs `from`, `to` and `steps` (missing: {})",
                    missing.join(", ")
                ),
            ));
        }
    };
    Ok(Axis {
        key,
        values,
        target,
    })
}

pub(super) fn check_value(
    ctx: &Ctx,
    at: Option<usize>,
    key: &str,
    v: &AxisValue,
    ratio: bool,
) -> Result<(), SweepError> {
    if let AxisValue::Number(x) = v {
        if !x.is_finite() {
            return Err(ctx.invalid(at, key, "values must be finite numbers"));
        }
        if ratio && *x <= 0.0 {
            return Err(ctx.invalid(at, key, format!("{x}: a period ratio must be > 0")));
        }
    }
    Ok(())
}

/// `row_shape`: the base's number of structures and each adjacent pair's number of contact
/// levels (`edit::row_shape`).
pub(super) fn check_axes(
    ctx: &Ctx,
    axes: &[Axis],
    spans: &[usize],
    base: &Table,
    row_shape: &RowShape,
) -> Result<(), SweepError> {
    let find = |pred: &dyn Fn(&Target) -> bool| axes.iter().position(|a| pred(&a.target));
    let is_key = |t: &Target, s: &Section, f: &[&str]| matches!(t, Target::Key { section, field, .. } if section == s && f.contains(field));
    let file_axis = find(&|t| is_key(t, &Section::Ground, &["file"]));
    let conflicts: [(Target, &[&str], Section, &str); 2] = [
        (
            Target::PeriodRatio,
            &["period", "bending_stiffness", "tip_stiffness"],
            Section::Structure(1),
            "period_ratio sets structure 2's period",
        ),
        (
            Target::GroundPeriodRatio,
            &["period"],
            Section::Ground,
            "ground_period_ratio sets the ground motion's period",
        ),
    ];
    for (derived, fields, section, why) in conflicts {
        if let Some(d) = find(&|t| *t == derived)
            && let Some(j) = find(&|t| is_key(t, &section, fields))
        {
            return Err(ctx.invalid(
                Some(spans[j.max(d)]),
                &axes[j].key,
                format!("cannot be an axis together with `{}`: {why}", axes[d].key),
            ));
        }
    }
    let base_ground = base.get("ground_motion").and_then(Value::as_table);
    let base_kind = base_ground
        .and_then(|g| g.get("kind"))
        .and_then(Value::as_str);
    if let Some(d) = find(&|t| *t == Target::GroundPeriodRatio) {
        if let Some(f) = file_axis {
            return Err(ctx.invalid(
                Some(spans[f.max(d)]),
                "ground_period_ratio",
                "needs a harmonic ground motion; it cannot be swept with record files (`ground_motion.file`)",
            ));
        }
        if base_kind != Some("harmonic") {
            return Err(ctx.invalid(
                Some(spans[d]),
                "ground_period_ratio",
                "needs a harmonic ground motion (kind = \"harmonic\") in the base scenario",
            ));
        }
    }
    if base_kind == Some("suite")
        && let Some(j) = find(&|t| {
            matches!(
                t,
                Target::Key {
                    section: Section::Ground,
                    ..
                }
            )
        })
    {
        return Err(ctx.invalid(
            Some(spans[j]),
            &format!("axis[{}].key", j + 1),
            format!(
                "`{}` is a key of one ground motion, but the base scenario's ground motion is a \
                 suite of records (kind = \"suite\"): each case runs every record, scaled by the \
                 suite's rule for that case's structures. A sweep over a suite may vary the \
                 structures, the contact and the solver; to vary the records, write one suite \
                 scenario per set and sweep each",
                axes[j].key
            ),
        ));
    }
    check_row_axes(ctx, axes, spans, row_shape)?;
    let base_contact = base.get("contact").and_then(Value::as_table);
    let levels = base_contact
        .and_then(|c| c.get("level"))
        .and_then(Value::as_array)
        .map(Vec::len);
    for (j, a) in axes.iter().enumerate() {
        match &a.target {
            Target::Key {
                section: Section::Contact,
                field: f @ ("gap" | "height"),
                ..
            } if levels.is_some() => {
                return Err(ctx.invalid(
                    Some(spans[j]),
                    &a.key,
                    format!(
                        "the base scenario has [[contact.level]] tables: sweep `contact.level.N.{f}` instead"
                    ),
                ));
            }
            Target::Key {
                section: Section::Level(i),
                ..
            } if levels.is_none_or(|n| *i >= n) => {
                return Err(ctx.invalid(
                    Some(spans[j]),
                    &a.key,
                    format!(
                        "the base scenario has {} [[contact.level]] table(s)",
                        levels.unwrap_or(0)
                    ),
                ));
            }
            _ => {}
        }
    }
    Ok(())
}

/// A base scenario's number of structures and, per adjacent pair, its contact's number of
/// levels (`None` without a `level` list; the outer `None`: no table for the pair).
pub(super) type RowShape = (usize, Vec<Option<Option<usize>>>);

/// The axes of a row of buildings (issue 29), or of a pair written with the row's paths:
/// `structure[N]` within the base's structures, `contact[P]` within its adjacent pairs (and
/// `contact[P].level[L]` within the pair's levels), and `contact.…` without a pair refused for
/// a row, where it would be ambiguous; each error names the axis's key.
fn check_row_axes(
    ctx: &Ctx,
    axes: &[Axis],
    spans: &[usize],
    (n, pairs): &RowShape,
) -> Result<(), SweepError> {
    let (n, pairs) = (*n, pairs);
    for (j, a) in axes.iter().enumerate() {
        let refuse = |why: String| {
            Err(ctx.invalid(
                Some(spans[j]),
                &format!("axis[{}].key", j + 1),
                format!("`{}`: {why}", a.key),
            ))
        };
        let section = match &a.target {
            Target::Scale { structure, .. } => Some(Section::Structure(*structure)),
            Target::Key { section, .. } => Some(section.clone()),
            _ => None,
        };
        let field = match &a.target {
            Target::Key { field, .. } => *field,
            _ => "",
        };
        match section {
            Some(Section::Structure(i) | Section::Hysteresis(i)) if i >= n => {
                return refuse(format!(
                    "the base scenario has {n} structures (structure[1] … structure[{n}])"
                ));
            }
            Some(Section::Contact | Section::Level(_)) if n > 2 => {
                let list = (0..n - 1)
                    .map(|p| {
                        format!(
                            "contact[{}] the pair of structures {} and {}",
                            p + 1,
                            p + 1,
                            p + 2
                        )
                    })
                    .take(3)
                    .collect::<Vec<_>>()
                    .join(", ");
                let rest = a.key.strip_prefix("contact.").unwrap_or(&a.key);
                return refuse(format!(
                    "ambiguous: the base scenario is a row of {n} structures with one contact per \
                     adjacent pair; name the pair, `contact[P].{rest}` ({list}{})",
                    if n > 4 { ", …" } else { "" }
                ));
            }
            Some(Section::PairContact(p) | Section::PairLevel(p, _)) if p >= pairs.len() => {
                return refuse(format!(
                    "pair {} is out of range: the base scenario has {n} structures, so {} \
                     adjacent pair(s) (contact[1] … contact[{}])",
                    p + 1,
                    pairs.len(),
                    pairs.len()
                ));
            }
            Some(Section::PairContact(p)) if matches!(field, "gap" | "height") => {
                if let Some(Some(levels)) = pairs[p] {
                    return refuse(format!(
                        "pair {}'s contact has {levels} level(s) (`level = [...]`): sweep \
                         `contact[{}].level[L].{field}` instead",
                        p + 1,
                        p + 1
                    ));
                }
            }
            Some(Section::PairLevel(p, i)) => {
                let levels = pairs[p].flatten().unwrap_or(0);
                if i >= levels {
                    return refuse(format!(
                        "pair {}'s contact has {levels} level(s) in a `level` list",
                        p + 1
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(())
}
