//! `[ground_motion] kind = "suite"` (issue 27, part 3): a suite of records, each read as a
//! single record is (`file`, `component`, `units`, `dt`, `processing`, every key checked with
//! file:line:col), an optional factor per record, and the scaling of the suite by a code's rule:
//!
//! ```toml
//! [ground_motion]
//! kind = "suite"
//! records = [
//!   { file = "records/RSN753_LOMAP_CLS000.AT2" },
//!   { file = "records/RSN786_LOMAP_PAE055.AT2", component = 1 },
//! ]
//! scaling = { rule = "ec8", target = { spectrum = "ec8", ag = 2.5, ground_type = "C", type = 1 } }
//! ```
//!
//! The records are read here; the scaling itself needs the structures' periods and the
//! records' spectra and is computed by the suite driver ([`crate::study::suite`]) before any
//! run, with `SuiteScaling::compute` of `pounding scale`.
//!
//! Decisions (README, "Record suites"): records with different time steps are allowed — each
//! record's spectrum and run use its own step, and neither code asks for a common one; a
//! per-record `factor` is the user's own scaling and is taken only with `rule = "none"` (with a
//! code's rule the rule sets every factor); without `solver.duration` (`dt`,
//! `output_interval`) each record runs with the default a single-record scenario of that
//! record would get, so that a suite of one record is that record's run exactly.

use std::path::Path;
use std::sync::Arc;

use serde::Deserialize;
use toml::Spanned;

use super::diagnostics::{Check, ScenarioError};
use super::ground_keys::ground;
use super::plausibility::plausibility;
use super::{DEFAULT_DT, RawGround, RawScenario, RecordCache, record_keys};
use crate::codes::spectrum::DesignSpectrum;
use crate::model::ground_motion::{GroundMotion, Record};

/// One entry of `records = [ … ]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSuiteRecord {
    file: Option<Spanned<String>>,
    component: Option<Spanned<toml::Value>>,
    factor: Option<Spanned<f64>>,
    units: Option<Spanned<String>>,
    dt: Option<Spanned<f64>>,
    processing: Option<Spanned<record_keys::RawProcessing>>,
}

/// `scaling = { rule, target, range, ratio, factor_limits, target_scale }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSuiteScaling {
    rule: Option<Spanned<String>>,
    target: Option<Spanned<RawTarget>>,
    range: Option<Spanned<Vec<f64>>>,
    ratio: Option<Spanned<f64>>,
    factor_limits: Option<Spanned<Vec<f64>>>,
    target_scale: Option<Spanned<f64>>,
}

/// `target = { spectrum = "asce7" | "ec8" | "table", … }`: the keys of
/// `[ground_motion] kind = "spectrum"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTarget {
    spectrum: Option<Spanned<String>>,
    sds: Option<Spanned<f64>>,
    sd1: Option<Spanned<f64>>,
    tl: Option<Spanned<f64>>,
    ag: Option<Spanned<f64>>,
    units: Option<Spanned<String>>,
    ground_type: Option<Spanned<String>>,
    #[serde(rename = "type")]
    spectrum_type: Option<Spanned<toml::Value>>,
    file: Option<Spanned<String>>,
}

/// The rule a suite is scaled by and whose design value it reports, a closed set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SuiteRule {
    /// ASCE/SEI 7-16 Chapter 16 (≥ 11 records, the mean response).
    Asce7,
    /// EN 1998-1 §3.2.3.1.2 and §4.3.3.4.3 (≥ 3 records; the mean with ≥ 7, else the most
    /// unfavourable).
    Ec8,
    /// No code: the records at their own `factor` (default 1); the design value is the most
    /// unfavourable record's (no code procedure is claimed).
    None,
}

impl SuiteRule {
    /// The key as written: `asce7`, `ec8`, `none`.
    pub fn key(self) -> &'static str {
        match self {
            SuiteRule::Asce7 => "asce7",
            SuiteRule::Ec8 => "ec8",
            SuiteRule::None => "none",
        }
    }
}

/// `scaling = { … }`, checked. Ranges are checked against the structures' periods when the
/// suite is scaled.
#[derive(Debug, Clone, PartialEq)]
pub struct SuiteScalingSpec {
    /// The rule.
    pub rule: SuiteRule,
    /// The target spectrum as given (a code's rule only).
    pub target: Option<DesignSpectrum>,
    /// A factor on the target instead of the rule's own (ASCE 7: 1.5, MCE_R = 1.5 × the
    /// design spectrum, §11.4.7).
    pub target_scale: Option<f64>,
    /// A period range wider than the code's, s.
    pub range: Option<(f64, f64)>,
    /// A mean-to-target ratio above the code's 0.90.
    pub ratio: Option<f64>,
    /// Smallest and largest factor allowed per record.
    pub factor_limits: Option<(f64, f64)>,
}

/// One record of a suite, as read.
#[derive(Debug, Clone, PartialEq)]
pub struct SuiteRecord {
    /// The file as written in the scenario.
    pub file: String,
    /// The component read, as the file names it (or as the scenario gave it).
    pub component: Option<String>,
    /// The user's factor (`rule = "none"` only).
    pub factor: Option<f64>,
    /// The record as read (units, processing applied; not scaled).
    pub record: Arc<Record>,
}

/// A checked suite (`Scenario::suite`).
#[derive(Debug, Clone, PartialEq)]
pub struct Suite {
    /// The records, in the scenario's order.
    pub records: Vec<SuiteRecord>,
    /// How the suite is scaled.
    pub scaling: SuiteScalingSpec,
    /// `solver.duration`, `solver.dt`, `solver.output_interval` were not given: each record
    /// gets its own default.
    own: [bool; 3],
    /// The longest record, for the scenario's listing of defaults.
    longest: GroundMotion,
}

impl Suite {
    /// The scenario of record `i` at factor `f`: the suite's scenario with that record (scaled
    /// by `f`) as its ground motion and the solver's defaults a scenario of that record alone
    /// would get.
    pub fn member_scenario(
        &self,
        scenario: &super::Scenario,
        i: usize,
        f: f64,
    ) -> Result<super::Scenario, ScenarioError> {
        let m = &self.records[i];
        let record = if f == 1.0 {
            m.record.clone()
        } else {
            Arc::new(scaled(&m.record, f).map_err(|e| ScenarioError::Record {
                at: super::Location::file(m.file.as_str()),
                key: format!("ground_motion.records[{}].factor", i + 1),
                source: Box::new(e),
            })?)
        };
        let mut sc = scenario.clone();
        sc.suite = None;
        let [own_duration, own_dt, own_interval] = self.own;
        let s = &mut sc.solver;
        if own_duration {
            s.duration = record.duration();
        }
        if own_dt {
            s.dt = DEFAULT_DT.min(record.dt).min(s.duration / 10.0);
        }
        if own_interval {
            sc.output_interval = (0.01f64).max(s.dt).min(s.duration);
        } else {
            sc.output_interval = sc.output_interval.min(s.duration);
        }
        let (duration, dt, interval) = (s.duration, s.dt, sc.output_interval);
        for d in &mut sc.defaults_applied {
            if own_duration && d.starts_with("solver.duration = ") {
                *d = format!("solver.duration = {duration} (the record's duration)");
            } else if own_dt && d.starts_with("solver.dt = ") {
                *d = format!("solver.dt = {dt}");
            } else if own_interval && d.starts_with("solver.output_interval = ") {
                *d = format!("solver.output_interval = {interval}");
            }
        }
        sc.ground_motion = GroundMotion::Record(record);
        // what a scenario of the scaled record would be warned of (a PGA above 3 g …)
        for w in plausibility(&sc.contact, &sc.ground_motion) {
            if !sc.warnings.contains(&w) {
                sc.warnings.push(w);
            }
        }
        Ok(sc)
    }
}

/// `record` × `f` (the velocity integrated again from the scaled samples).
pub fn scaled(record: &Record, f: f64) -> Result<Record, crate::model::ground_motion::RecordError> {
    let mut r = Record::from_samples(
        record.dt,
        record.accel.iter().map(|a| a * f).collect(),
        record.description.clone(),
    )?;
    r.format = record.format;
    r.component = record.component.clone();
    r.file_units = record.file_units;
    r.stated_peak = None;
    r.processing = record.processing;
    // what was applied in all: the factor on the record as read (and its own scaling, if any)
    r.scaling = Some(crate::model::ground_motion::RecordScaling {
        factor: f * record.scaling.map_or(1.0, |s| s.factor),
        target: crate::model::ground_motion::ScaleTarget::Factor,
    });
    r.warnings = record.warnings.clone();
    Ok(r)
}

/// The suite of `[ground_motion]` when kind = "suite" (`None` for another kind, after
/// refusing `records` and `scaling` there). The hook of the scenario's validation.
pub(super) fn suite(
    c: &Check,
    raw: &RawScenario,
    base_dir: &Path,
    cache: Option<&RecordCache>,
) -> Result<Option<Suite>, ScenarioError> {
    let Some(g) = raw.ground_motion.as_ref() else {
        return Ok(None);
    };
    let near = Some(g.span().start);
    let gr = g.get_ref();
    let kind = gr.kind.as_ref().map_or("", |k| k.get_ref().as_str());
    let given = |k: &str, why: &str| ScenarioError::Invalid {
        at: c.ctx.at(near),
        key: format!("ground_motion.{k}"),
        value: "(given)".into(),
        reason: why.to_string(),
    };
    if kind != "suite" {
        for (k, p) in [
            ("records", gr.records.is_some()),
            ("scaling", gr.scaling.is_some()),
        ] {
            if p {
                return Err(given(k, &format!("not used with kind = \"{kind}\"")));
            }
        }
        return Ok(None);
    }
    for (k, p) in [
        ("file", gr.file.is_some()),
        ("component", gr.component.is_some()),
        ("units", gr.units.is_some()),
        ("dt", gr.dt.is_some()),
        ("processing", gr.processing.is_some()),
        ("scale_to_pga", gr.scale_to_pga.is_some()),
        ("scale_to_sa", gr.scale_to_sa.is_some()),
    ] {
        if p {
            return Err(given(
                k,
                "not used with kind = \"suite\": give it per record, in `records = [{ file = …, \
                 … }]`",
            ));
        }
    }
    for (k, p) in [("pga", gr.pga.is_some()), ("period", gr.period.is_some())] {
        if p {
            return Err(given(k, "not used with kind = \"suite\""));
        }
    }
    let scaling = scaling(c, gr.scaling.as_ref(), base_dir, near)?;
    let list = c.required(
        &gr.records,
        "ground_motion.records",
        "the suite's records: records = [{ file = \"…\", component = … }, …]",
        near,
    )?;
    if list.get_ref().is_empty() {
        return Err(ScenarioError::Invalid {
            at: c.ctx.at(Some(list.span().start)),
            key: "ground_motion.records".into(),
            value: "[]".into(),
            reason: "a suite needs at least one record".into(),
        });
    }
    let mut records = Vec::with_capacity(list.get_ref().len());
    for (i, entry) in list.get_ref().iter().enumerate() {
        let prefix = format!("ground_motion.records[{}]", i + 1);
        let e = entry.get_ref();
        let factor = match &e.factor {
            None => None,
            Some(_) if scaling.rule != SuiteRule::None => {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(Some(entry.span().start)),
                    key: format!("{prefix}.factor"),
                    value: "(given)".into(),
                    reason: format!(
                        "the rule \"{}\" sets every record's factor; give your own factors with \
                         scaling = {{ rule = \"none\" }}",
                        scaling.rule.key()
                    ),
                });
            }
            Some(f) => {
                let x = *f.get_ref();
                if !(x.is_finite() && x > 0.0 && x <= 100.0) {
                    return Err(c.invalid(f, &format!("{prefix}.factor"), "must be in (0, 100]"));
                }
                Some(x)
            }
        };
        // read exactly as `kind = "record"` reads its file, every key checked there
        let one = Spanned::new(
            entry.span(),
            RawGround {
                kind: Some(Spanned::new(entry.span(), "record".to_string())),
                file: e.file.clone(),
                units: e.units.clone(),
                dt: e.dt.clone(),
                component: e.component.clone(),
                processing: e.processing.clone(),
                ..RawGround::default()
            },
        );
        let rename = |err: ScenarioError| rename_key(err, &prefix);
        if e.file.is_none() {
            return Err(c.missing(
                &format!("{prefix}.file"),
                "the record file, relative to the scenario",
                Some(entry.span().start),
            ));
        }
        let GroundMotion::Record(record) =
            ground(c, Some(&one), base_dir, cache).map_err(rename)?
        else {
            unreachable!("kind = \"record\" gives a record")
        };
        let given_component = e.component.as_ref().map(|v| match v.get_ref() {
            toml::Value::String(s) => s.trim().to_string(),
            other => other.to_string(),
        });
        records.push(SuiteRecord {
            file: e
                .file
                .as_ref()
                .map_or_else(String::new, |f| f.get_ref().clone()),
            component: record.component.clone().or(given_component),
            factor,
            record,
        });
    }
    let longest = records
        .iter()
        .max_by(|a, b| a.record.duration().total_cmp(&b.record.duration()))
        .map(|m| GroundMotion::Record(m.record.clone()))
        .unwrap_or(GroundMotion::None);
    let s = raw.solver.as_ref().map(|s| s.get_ref());
    let own = [
        s.is_none_or(|s| s.duration.is_none()),
        s.is_none_or(|s| s.dt.is_none()),
        s.is_none_or(|s| s.output_interval.is_none()),
    ];
    Ok(Some(Suite {
        records,
        scaling,
        own,
        longest,
    }))
}

/// The ground motion the solver's defaults are taken from: the suite's longest record (a
/// suite's own defaults are each record's, [`Suite::member_scenario`]).
pub(super) fn defaults_ground<'a>(
    suite: Option<&'a Suite>,
    other: &'a GroundMotion,
) -> &'a GroundMotion {
    suite.map_or(other, |s| &s.longest)
}

/// The listing of a suite's defaults says that each record has its own.
pub(super) fn note_defaults(suite: Option<&Suite>, defaults: &mut [String]) {
    let Some(s) = suite else { return };
    for d in defaults.iter_mut() {
        let own = (s.own[0] && d.starts_with("solver.duration = "))
            || (s.own[1] && d.starts_with("solver.dt = "))
            || (s.own[2] && d.starts_with("solver.output_interval = "));
        if own {
            let key = d.split(" = ").next().unwrap_or_default().to_string();
            *d = format!("{key} = each record's own default (as a scenario of the record alone)");
        }
    }
}

/// The error of reading one record with its key inside `records[i]`.
fn rename_key(err: ScenarioError, prefix: &str) -> ScenarioError {
    let fix = |k: String| match k.strip_prefix("ground_motion.") {
        Some(rest) => format!("{prefix}.{rest}"),
        None => k,
    };
    match err {
        ScenarioError::Invalid {
            at,
            key,
            value,
            reason,
        } => ScenarioError::Invalid {
            at,
            key: fix(key),
            value,
            reason,
        },
        ScenarioError::Missing { at, key, expected } => ScenarioError::Missing {
            at,
            key: fix(key),
            expected,
        },
        ScenarioError::Record { at, key, source } => ScenarioError::Record {
            at,
            key: fix(key),
            source,
        },
        other => other,
    }
}

fn scaling(
    c: &Check,
    raw: Option<&Spanned<RawSuiteScaling>>,
    base_dir: &Path,
    near: Option<usize>,
) -> Result<SuiteScalingSpec, ScenarioError> {
    let Some(raw) = raw else {
        return Err(c.missing(
            "ground_motion.scaling",
            "scaling = { rule = \"asce7\" | \"ec8\" | \"none\", target = { spectrum = …, … } }",
            near,
        ));
    };
    let s = raw.get_ref();
    let near = Some(raw.span().start);
    let key = |k: &str| format!("ground_motion.scaling.{k}");
    let rule_v = c.required(
        &s.rule,
        &key("rule"),
        "\"asce7\" (ASCE 7-16 Chapter 16), \"ec8\" (EN 1998-1 §3.2.3.1.2) or \"none\" (your own \
         factors)",
        near,
    )?;
    let rule = match rule_v.get_ref().as_str() {
        "asce7" => SuiteRule::Asce7,
        "ec8" => SuiteRule::Ec8,
        "none" => SuiteRule::None,
        _ => {
            return Err(c.invalid(
                rule_v,
                &key("rule"),
                "must be \"asce7\", \"ec8\" or \"none\"",
            ));
        }
    };
    let pair =
        |v: &Spanned<Vec<f64>>, k: &str, what: &str, strict: bool| match v.get_ref().as_slice() {
            [a, b]
                if a.is_finite()
                    && b.is_finite()
                    && *a > 0.0
                    && (if strict { a < b } else { a <= b }) =>
            {
                Ok((*a, *b))
            }
            _ => Err(ScenarioError::Invalid {
                at: c.ctx.at(Some(v.span().start)),
                key: key(k),
                value: format!("{:?}", v.get_ref()),
                reason: what.to_string(),
            }),
        };
    if rule == SuiteRule::None {
        for (k, p) in [
            ("target", s.target.is_some()),
            ("range", s.range.is_some()),
            ("ratio", s.ratio.is_some()),
            ("factor_limits", s.factor_limits.is_some()),
            ("target_scale", s.target_scale.is_some()),
        ] {
            if p {
                return Err(ScenarioError::Invalid {
                    at: c.ctx.at(near),
                    key: key(k),
                    value: "(given)".into(),
                    reason: "not used with rule = \"none\" (the records at their own `factor`)"
                        .into(),
                });
            }
        }
        return Ok(SuiteScalingSpec {
            rule,
            target: None,
            target_scale: None,
            range: None,
            ratio: None,
            factor_limits: None,
        });
    }
    let t = c.required(
        &s.target,
        &key("target"),
        "the target spectrum: target = { spectrum = \"asce7\", sds = …, sd1 = …, tl = … }, \
         { spectrum = \"ec8\", ag = …, ground_type = …, type = … } or { spectrum = \"table\", \
         file = … }",
        near,
    )?;
    let tr = t.get_ref();
    let as_ground = Spanned::new(
        t.span(),
        RawGround {
            kind: Some(Spanned::new(t.span(), "spectrum".to_string())),
            spectrum: tr.spectrum.clone(),
            sds: tr.sds.clone(),
            sd1: tr.sd1.clone(),
            tl: tr.tl.clone(),
            ag: tr.ag.clone(),
            units: tr.units.clone(),
            ground_type: tr.ground_type.clone(),
            spectrum_type: tr.spectrum_type.clone(),
            file: tr.file.clone(),
            ..RawGround::default()
        },
    );
    let target = super::design::target_spectrum(c, &as_ground, base_dir, &key("target."))?;
    let range = s
        .range
        .as_ref()
        .map(|v| {
            pair(
                v,
                "range",
                "must be [shortest, longest] period in s, 0 < shortest < longest; it may only \
                 widen the code's range",
                true,
            )
        })
        .transpose()?;
    let ratio = match &s.ratio {
        None => None,
        Some(v) => {
            let x = *v.get_ref();
            if !(x.is_finite() && (0.9..=2.0).contains(&x)) {
                return Err(c.invalid(
                    v,
                    &key("ratio"),
                    "must be in [0.9, 2]: the mean-to-target ratio to reach, at least the codes' \
                     0.90",
                ));
            }
            Some(x)
        }
    };
    let factor_limits = s
        .factor_limits
        .as_ref()
        .map(|v| {
            pair(
                v,
                "factor_limits",
                "must be [smallest, largest] factor allowed per record, 0 < smallest ≤ largest",
                false,
            )
        })
        .transpose()?;
    let target_scale = match &s.target_scale {
        None => None,
        Some(v) => {
            let x = *v.get_ref();
            if !(x.is_finite() && x > 0.0 && x <= 10.0) {
                return Err(c.invalid(v, &key("target_scale"), "must be in (0, 10]"));
            }
            Some(x)
        }
    };
    Ok(SuiteScalingSpec {
        rule,
        target: Some(target),
        target_scale,
        range,
        ratio,
        factor_limits,
    })
}
