//! The study file's raw keys (serde, with their positions) and their checks, each error
//! naming the key and its file:line:col.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::Deserialize;
use toml::Spanned;

use super::{
    G, GapMode, IdaSettings, ImUnits, IntensityMeasure, LimitKind, LimitState, PoundingTarget,
    StudyError, pair_top_gaps,
};
use crate::input::scenario::{Location, Scenario};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawStudy {
    pub(super) title: Option<String>,
    pub(super) scenario: Option<Spanned<String>>,
    pub(super) ground_motion: Option<Spanned<toml::Table>>,
    pub(super) intensity: Option<Spanned<RawIntensity>>,
    pub(super) limit_state: Option<Vec<Spanned<RawLimit>>>,
    pub(super) fragility: Option<Spanned<RawFragility>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawIntensity {
    measure: Option<Spanned<String>>,
    structure: Option<Spanned<i64>>,
    periods: Option<Spanned<Vec<f64>>>,
    count: Option<Spanned<i64>>,
    units: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLimit {
    kind: Option<Spanned<String>>,
    value: Option<Spanned<f64>>,
    structure: Option<Spanned<i64>>,
    pair: Option<Spanned<i64>>,
    units: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(super) enum RawGaps {
    List(Vec<f64>),
    Range { to: f64, count: Option<i64> },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTarget {
    im: Option<Spanned<f64>>,
    probability: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFragility {
    pub(super) stripes: Option<Spanned<Vec<f64>>>,
    pub(super) gaps: Option<Spanned<RawGaps>>,
    pub(super) gap_mode: Option<Spanned<String>>,
    pub(super) target: Option<Spanned<RawTarget>>,
    pub(super) bootstrap: Option<Spanned<i64>>,
    pub(super) seed: Option<Spanned<i64>>,
    pub(super) confidence: Option<Spanned<f64>>,
    pub(super) check: Option<bool>,
    pub(super) ida: Option<Spanned<RawIda>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawIda {
    start: Option<Spanned<f64>>,
    step: Option<Spanned<f64>>,
    growth: Option<Spanned<f64>>,
    tolerance: Option<Spanned<f64>>,
    max_runs: Option<Spanned<i64>>,
    fill: Option<bool>,
}

/// Where a byte offset of the text lies: file:line:col.
pub(super) struct Here<'a> {
    pub(super) text: &'a str,
    pub(super) file: Arc<str>,
}

impl Here<'_> {
    pub(super) fn at(&self, offset: Option<usize>) -> Location {
        Location::in_text(self.file.clone(), self.text, offset)
    }

    pub(super) fn invalid<T: std::fmt::Debug>(
        &self,
        v: &Spanned<T>,
        key: &str,
        reason: &str,
    ) -> StudyError {
        StudyError::Invalid {
            at: self.at(Some(v.span().start)),
            key: key.into(),
            value: format!("{:?}", v.get_ref()).trim_matches('"').to_string(),
            reason: reason.into(),
        }
    }

    pub(super) fn missing(&self, key: &str, expected: &str, near: Option<usize>) -> StudyError {
        StudyError::Missing {
            at: self.at(near),
            key: key.into(),
            expected: expected.into(),
        }
    }
}

/// The base scenario with the study's `[ground_motion]` as its suite: record files relative
/// to the study are made absolute so that the scenario's own relative paths still work.
pub(super) fn suite_in_study(
    here: &Here,
    gm: &Spanned<toml::Table>,
    sc_text: &str,
    sc_path: &Path,
    dir: &Path,
) -> Result<(Scenario, Vec<String>), StudyError> {
    let near = Some(gm.span().start);
    let mut g = gm.get_ref().clone();
    for k in ["kind", "scaling"] {
        if let Some(v) = g.get(k)
            && !(k == "kind" && v.as_str() == Some("suite"))
        {
            return Err(StudyError::Invalid {
                at: here.at(near),
                key: format!("ground_motion.{k}"),
                value: v.to_string(),
                reason: "a study's [ground_motion] is a suite of records (records = [ … ]) \
                         scaled to each stripe by the study: no kind other than \"suite\", no \
                         scaling"
                    .into(),
            });
        }
    }
    let base = std::fs::canonicalize(dir).unwrap_or_else(|_| PathBuf::from(dir));
    let mut names = Vec::new();
    let Some(toml::Value::Array(records)) = g.get_mut("records") else {
        return Err(here.missing(
            "ground_motion.records",
            "records = [{ file = \"…\", component = … }, …]",
            near,
        ));
    };
    for (i, r) in records.iter_mut().enumerate() {
        let key = format!("ground_motion.records[{}]", i + 1);
        let Some(t) = r.as_table_mut() else {
            return Err(StudyError::Invalid {
                at: here.at(near),
                key,
                value: r.to_string(),
                reason: "each record is a table { file = \"…\", … }".into(),
            });
        };
        if t.contains_key("factor") {
            return Err(StudyError::Invalid {
                at: here.at(near),
                key: format!("{key}.factor"),
                value: "(given)".into(),
                reason: "the study scales every record to each stripe itself".into(),
            });
        }
        if let Some(toml::Value::String(f)) = t.get("file").cloned() {
            names.push(f.clone());
            let p = Path::new(&f);
            if p.is_relative() {
                t.insert(
                    "file".into(),
                    toml::Value::String(base.join(p).display().to_string()),
                );
            }
        } else {
            names.push(String::new());
        }
    }
    g.insert("kind".into(), toml::Value::String("suite".into()));
    let mut scaling = toml::Table::new();
    scaling.insert("rule".into(), toml::Value::String("none".into()));
    g.insert("scaling".into(), toml::Value::Table(scaling));
    let mut table: toml::Table = toml::from_str(sc_text).map_err(|e| StudyError::Syntax {
        at: Location::file(sc_path.display().to_string()),
        message: e.message().trim().to_string(),
    })?;
    table.insert("ground_motion".into(), toml::Value::Table(g));
    // (positions in messages are of the merged text: the key names the place)
    let origin = format!(
        "{} with the [ground_motion] of {} (merged)",
        sc_path.display(),
        here.file
    );
    let sc_dir = sc_path.parent().unwrap_or(Path::new("."));
    let sc = Scenario::from_table(&table, &origin, sc_dir)?;
    Ok((sc, names))
}

/// A 1-based `structure = N` of a scenario of `n` structures, 0-based.
fn structure_index(
    here: &Here,
    v: &Spanned<i64>,
    key: &str,
    n: usize,
) -> Result<usize, StudyError> {
    match usize::try_from(*v.get_ref()) {
        Ok(i) if (1..=n).contains(&i) => Ok(i - 1),
        _ if n == 2 => Err(here.invalid(v, key, "must be 1 or 2")),
        _ => Err(here.invalid(
            v,
            key,
            &format!("must be in 1..={n}: a structure of the row, in row order"),
        )),
    }
}

pub(super) fn intensity_measure(
    here: &Here,
    raw: &Spanned<RawIntensity>,
    scenario: &Scenario,
) -> Result<(IntensityMeasure, ImUnits), StudyError> {
    let r = raw.get_ref();
    let near = Some(raw.span().start);
    let m = r.measure.as_ref().ok_or_else(|| {
        here.missing(
            "intensity.measure",
            "\"pga\", \"sa\" (5 %-damped Sa(T1) of `structure`) or \"sa_avg\" (geometric mean \
             over `periods`)",
            near,
        )
    })?;
    let refuse = |present: bool, key: &str, why: &str| -> Result<(), StudyError> {
        if present {
            Err(StudyError::Invalid {
                at: here.at(near),
                key: format!("intensity.{key}"),
                value: "(given)".into(),
                reason: why.into(),
            })
        } else {
            Ok(())
        }
    };
    let measure = match m.get_ref().as_str() {
        "pga" => {
            refuse(
                r.structure.is_some(),
                "structure",
                "not used with measure = \"pga\"",
            )?;
            refuse(
                r.periods.is_some(),
                "periods",
                "not used with measure = \"pga\"",
            )?;
            refuse(
                r.count.is_some(),
                "count",
                "not used with measure = \"pga\"",
            )?;
            IntensityMeasure::Pga
        }
        "sa" => {
            refuse(
                r.periods.is_some(),
                "periods",
                "not used with measure = \"sa\"",
            )?;
            refuse(r.count.is_some(), "count", "not used with measure = \"sa\"")?;
            let s = r.structure.as_ref().ok_or_else(|| {
                here.missing(
                    "intensity.structure",
                    &format!(
                        "1 to {}: whose first-mode period T1 Sa is taken at",
                        scenario.structures.len()
                    ),
                    near,
                )
            })?;
            let i = structure_index(here, s, "intensity.structure", scenario.structures.len())?;
            let period = scenario.structures[i]
                .modal()
                .periods()
                .first()
                .copied()
                .unwrap_or(f64::NAN);
            IntensityMeasure::Sa {
                structure: i,
                period,
            }
        }
        "sa_avg" => {
            refuse(
                r.structure.is_some(),
                "structure",
                "not used with measure = \"sa_avg\"",
            )?;
            let p = r.periods.as_ref().ok_or_else(|| {
                here.missing(
                    "intensity.periods",
                    "[shortest, longest] period of the average, s (e.g. 0.2 T1 to 3 T1)",
                    near,
                )
            })?;
            let (lo, hi) = match p.get_ref().as_slice() {
                [a, b] if a.is_finite() && b.is_finite() && *a > 0.0 && a < b && *b <= 20.0 => {
                    (*a, *b)
                }
                _ => {
                    return Err(here.invalid(
                        p,
                        "intensity.periods",
                        "must be [shortest, longest] in s, 0 < shortest < longest ≤ 20",
                    ));
                }
            };
            let n = match &r.count {
                None => 10,
                Some(c) => usize::try_from(*c.get_ref())
                    .ok()
                    .filter(|n| (2..=100).contains(n))
                    .ok_or_else(|| here.invalid(c, "intensity.count", "must be in 2..=100"))?,
            };
            let periods = (0..n)
                .map(|k| lo * (hi / lo).powf(k as f64 / (n - 1) as f64))
                .collect();
            IntensityMeasure::SaAvg { periods }
        }
        _ => {
            return Err(here.invalid(
                m,
                "intensity.measure",
                "must be \"pga\", \"sa\" or \"sa_avg\"",
            ));
        }
    };
    let units = match r.units.as_ref() {
        None => ImUnits::G,
        Some(u) => match u.get_ref().as_str() {
            "g" => ImUnits::G,
            "m/s2" | "m/s^2" | "m/s²" => ImUnits::Ms2,
            _ => return Err(here.invalid(u, "intensity.units", "must be \"g\" or \"m/s2\"")),
        },
    };
    Ok((measure, units))
}

/// `[[limit_state]]` number `i` (0-based): for a pair, the one limit state; for a row (more
/// than two structures) a limit state that names no structure or pair stands for the row's
/// (any structure, any pair: the larger demand) and is followed by one per structure (a
/// structure's kind: each that it applies to) or per pair (`pounding`, `contact_force`).
pub(super) fn limit_state(
    here: &Here,
    i: usize,
    raw: &Spanned<RawLimit>,
    scenario: &Scenario,
) -> Result<Vec<LimitState>, StudyError> {
    let r = raw.get_ref();
    let near = Some(raw.span().start);
    let n = scenario.structures.len();
    let row = scenario.is_row();
    let key = |k: &str| format!("limit_state[{}].{k}", i + 1);
    let k = r.kind.as_ref().ok_or_else(|| {
        here.missing(
            &key("kind"),
            "\"pounding\", \"contact_force\", \"ductility\", \"drift_ratio\" or \
             \"floor_acceleration\"",
            near,
        )
    })?;
    let kind = match k.get_ref().as_str() {
        "pounding" => LimitKind::Pounding,
        "contact_force" => LimitKind::ContactForce,
        "ductility" => LimitKind::Ductility,
        "drift_ratio" => LimitKind::DriftRatio,
        "floor_acceleration" => LimitKind::FloorAcceleration,
        _ => {
            return Err(here.invalid(
                k,
                &key("kind"),
                "must be \"pounding\", \"contact_force\", \"ductility\", \"drift_ratio\" or \
                 \"floor_acceleration\"",
            ));
        }
    };
    let of_pair = matches!(kind, LimitKind::Pounding | LimitKind::ContactForce);
    // a pair's limit state names a pair, a structure's a structure: the other key would be
    // ambiguous (which of a middle building's two pairs?), so it is refused
    if let (true, Some(st)) = (of_pair, &r.structure) {
        return Err(here.invalid(
            st,
            &key("structure"),
            &if row {
                format!(
                    "not used with this kind: it is a pair's (a structure of a row has up to two \
                     neighbours); give `pair` = 1 to {} (structures P and P + 1), or neither \
                     for every pair and the row",
                    n - 1
                )
            } else {
                "not used with this kind: it concerns both structures".to_string()
            },
        ));
    }
    if let (false, Some(p)) = (of_pair, &r.pair) {
        return Err(here.invalid(
            p,
            &key("pair"),
            "not used with this kind: it is a structure's; give `structure` (1-based, row \
             order), or neither for every structure",
        ));
    }
    let structure = r
        .structure
        .as_ref()
        .map(|s| structure_index(here, s, &key("structure"), n))
        .transpose()?;
    let pair = match &r.pair {
        None => None,
        Some(p) => match usize::try_from(*p.get_ref()) {
            Ok(x) if (1..n).contains(&x) => Some(x - 1),
            _ => {
                return Err(here.invalid(
                    p,
                    &key("pair"),
                    &format!(
                        "must be in 1..={}: the adjacent pair of structures P and P + 1, in row \
                         order",
                        n - 1
                    ),
                ));
            }
        },
    };
    let (unit_factor, unit) = match (&r.units, kind) {
        (None, LimitKind::ContactForce) => (1.0, "N"),
        (None, LimitKind::FloorAcceleration) => (1.0, "m/s2"),
        (None, _) => (1.0, ""),
        (Some(u), LimitKind::FloorAcceleration) => match u.get_ref().as_str() {
            "g" => (G, "g"),
            "m/s2" | "m/s^2" | "m/s²" => (1.0, "m/s2"),
            _ => return Err(here.invalid(u, &key("units"), "must be \"g\" or \"m/s2\"")),
        },
        (Some(u), _) => {
            return Err(here.invalid(
                u,
                &key("units"),
                "only with kind = \"floor_acceleration\" (\"g\" or \"m/s2\"); the other \
                 thresholds are SI (N) or ratios",
            ));
        }
    };
    let value = if kind == LimitKind::Pounding {
        if let Some(v) = &r.value {
            return Err(here.invalid(
                v,
                &key("value"),
                "not used with kind = \"pounding\" (any contact; the gaps are the scenario's)",
            ));
        }
        0.0
    } else {
        let v = r.value.as_ref().ok_or_else(|| {
            here.missing(
                &key("value"),
                match kind {
                    LimitKind::ContactForce => "the peak contact force not to exceed, N",
                    LimitKind::Ductility => "the storey ductility demand not to exceed (> 1)",
                    LimitKind::DriftRatio => "the storey drift ratio not to exceed (0.01 = 1 %)",
                    _ => "the floor acceleration not to exceed, m/s² (or units = \"g\")",
                },
                near,
            )
        })?;
        let x = *v.get_ref();
        let ok = x.is_finite()
            && match kind {
                LimitKind::Ductility => x > 1.0 && x <= 1000.0,
                LimitKind::DriftRatio => x > 0.0 && x <= 1.0,
                _ => x > 0.0,
            };
        if !ok {
            return Err(here.invalid(
                v,
                &key("value"),
                match kind {
                    LimitKind::Ductility => "must be in (1, 1000]",
                    LimitKind::DriftRatio => "must be in (0, 1] (a ratio: 0.01 = 1 %)",
                    _ => "must be positive",
                },
            ));
        }
        x * unit_factor
    };
    let yielding: Vec<usize> = (0..n)
        .filter(|&s| scenario.structures[s].hysteresis().is_some())
        .collect();
    if kind == LimitKind::Ductility {
        let ok = match structure {
            Some(s) => yielding.contains(&s),
            None => !yielding.is_empty(),
        };
        if !ok {
            return Err(here.invalid(
                k,
                &key("kind"),
                &match structure {
                    Some(s) => format!(
                        "structure {} has no yielding storeys (a ductility needs `hysteresis`)",
                        s + 1
                    ),
                    None if n == 2 => "neither structure has yielding storeys (a ductility \
                                       needs `hysteresis`)"
                        .to_string(),
                    None => "no structure of the row has yielding storeys (a ductility needs \
                             `hysteresis`)"
                        .to_string(),
                },
            ));
        }
    }
    // the name as the user wrote the threshold: `ductility>4(2)`, `floor_acceleration>1g(1)`,
    // a pair's `pounding(1-2)` (structures 1 and 2)
    let given = format!("{}", value / unit_factor);
    let make = |structure: Option<usize>, pair: Option<usize>| {
        let who = match (structure, pair) {
            (Some(s), _) => format!("({})", s + 1),
            (None, Some(p)) => format!("({}-{})", p + 1, p + 2),
            (None, None) => String::new(),
        };
        let name = match kind {
            LimitKind::Pounding => format!("pounding{who}"),
            _ => format!("{}>{given}{unit}{who}", kind.key()),
        };
        LimitState {
            kind,
            value,
            structure,
            pair,
            name,
        }
    };
    let mut out = vec![make(structure, pair)];
    if row && structure.is_none() && pair.is_none() {
        if of_pair {
            out.extend((0..n - 1).map(|p| make(None, Some(p))));
        } else {
            out.extend(
                (0..n)
                    .filter(|s| kind != LimitKind::Ductility || yielding.contains(s))
                    .map(|s| make(Some(s), None)),
            );
        }
    }
    Ok(out)
}

pub(super) fn gap_axis(
    here: &Here,
    raw: Option<&Spanned<RawGaps>>,
    scenario: &Scenario,
    mode: GapMode,
) -> Result<Vec<f64>, StudyError> {
    let key = "fragility.gaps";
    let Some(g) = raw else {
        // 0 to twice the scenario's gap (at the highest level in "scaled" mode, else the
        // largest), 41 values
        // (of a row: the largest over its pairs)
        let g0 = match mode {
            GapMode::Scaled => pair_top_gaps(scenario).into_iter().fold(0.0, f64::max),
            GapMode::Uniform => scenario
                .contacts()
                .flat_map(|c| &c.levels)
                .map(|l| l.gap)
                .fold(0.0, f64::max),
        };
        let to = if g0 > 0.0 { 2.0 * g0 } else { 0.5 };
        return Ok((0..=40).map(|k| to * k as f64 / 40.0).collect());
    };
    let v: Vec<f64> = match g.get_ref() {
        RawGaps::List(v) => v.clone(),
        RawGaps::Range { to, count } => {
            let n = count.unwrap_or(41);
            if !(to.is_finite() && *to > 0.0 && *to <= 100.0 && (2..=10_000).contains(&n)) {
                return Err(here.invalid(
                    g,
                    key,
                    "{ to, count }: 0 < to ≤ 100 m, count in 2..=10000",
                ));
            }
            (0..n).map(|k| to * k as f64 / (n - 1) as f64).collect()
        }
    };
    if v.is_empty()
        || v.len() > 10_000
        || v.iter()
            .any(|x| !(x.is_finite() && *x >= 0.0 && *x <= 100.0))
        || v.windows(2).any(|w| w[1] <= w[0])
    {
        return Err(here.invalid(
            g,
            key,
            "must be a list of 1 to 10000 gaps in m, 0 ≤ gap ≤ 100, strictly increasing, or \
             { to = …, count = … }",
        ));
    }
    Ok(v)
}

/// `target`; `stripes` `None` in an IDA (any positive intensity: the hunt goes past it).
pub(super) fn target(
    here: &Here,
    t: &Spanned<RawTarget>,
    stripes: Option<&[f64]>,
    units: ImUnits,
) -> Result<PoundingTarget, StudyError> {
    let near = Some(t.span().start);
    let r = t.get_ref();
    let im = r.im.as_ref().ok_or_else(|| {
        here.missing(
            "fragility.target.im",
            "the design intensity, one of the stripes",
            near,
        )
    })?;
    let Some(stripes) = stripes else {
        let x = *im.get_ref();
        if !(x.is_finite() && x > 0.0) {
            return Err(here.invalid(im, "fragility.target.im", "must be a positive intensity"));
        }
        let probability = target_probability(here, r, near)?;
        return Ok(PoundingTarget {
            im: x * units.factor(),
            stripe: 0,
            probability,
        });
    };
    let stripe = stripes
        .iter()
        .position(|s| (s - im.get_ref()).abs() <= 1e-9 * s.abs())
        .ok_or_else(|| {
            here.invalid(
                im,
                "fragility.target.im",
                &format!(
                    "must be one of the stripes {:?} (the gap is read from the runs at that \
                     intensity)",
                    stripes
                ),
            )
        })?;
    Ok(PoundingTarget {
        im: stripes[stripe] * units.factor(),
        stripe,
        probability: target_probability(here, r, near)?,
    })
}

fn target_probability(here: &Here, r: &RawTarget, near: Option<usize>) -> Result<f64, StudyError> {
    let p = r.probability.as_ref().ok_or_else(|| {
        here.missing(
            "fragility.target.probability",
            "the accepted probability of pounding at that intensity, e.g. 0.1",
            near,
        )
    })?;
    let x = *p.get_ref();
    if !(x.is_finite() && x > 0.0 && x < 1.0) {
        return Err(here.invalid(p, "fragility.target.probability", "must be in (0, 1)"));
    }
    Ok(x)
}

/// `ida = { start, step, growth, tolerance, max_runs, fill }`: the hunt-and-fill settings in
/// the study's IM units (defaults: physical values in g, converted), checked.
pub(super) fn ida_settings(
    here: &Here,
    raw: &Spanned<RawIda>,
    units: ImUnits,
) -> Result<IdaSettings, StudyError> {
    let r = raw.get_ref();
    let u = units.factor();
    // (the defaults are physical: 0.05 g is 0.49 m/s² when units = "m/s2")
    let num = |v: &Option<Spanned<f64>>,
               key: &str,
               default_g: f64,
               zero_ok: bool|
     -> Result<f64, StudyError> {
        match v {
            None => Ok(default_g * G),
            Some(x) => {
                let y = *x.get_ref();
                if y.is_finite() && (y > 0.0 || (zero_ok && y == 0.0)) && y * u <= 1e4 {
                    Ok(y * u)
                } else {
                    Err(here.invalid(
                        x,
                        &format!("fragility.ida.{key}"),
                        if zero_ok {
                            "must be ≥ 0 (in intensity.units), at most 10⁴ m/s²"
                        } else {
                            "must be > 0 (in intensity.units), at most 10⁴ m/s²"
                        },
                    ))
                }
            }
        }
    };
    let start = num(&r.start, "start", 0.05, false)?;
    let step = num(&r.step, "step", 0.1, false)?;
    let growth = num(&r.growth, "growth", 0.05, true)?;
    let tolerance = num(&r.tolerance, "tolerance", 0.01, false)?;
    let max_runs = match &r.max_runs {
        None => 20,
        Some(n) => usize::try_from(*n.get_ref())
            .ok()
            .filter(|n| (2..=1000).contains(n))
            .ok_or_else(|| here.invalid(n, "fragility.ida.max_runs", "must be in 2..=1000"))?,
    };
    Ok(IdaSettings {
        start,
        step,
        growth,
        tolerance,
        max_runs,
        fill: r.fill.unwrap_or(false),
    })
}
