//! The files of a fragility study (a contract for scripts), each written atomically
//! (temporary file then rename), `fit.json` last:
//!
//! - `fragility.csv`: `limit_state`, `model` (`with` / `without` contact), `im` (the stripe,
//!   in the study's IM units), `runs`, `exceedances`, `fraction`;
//! - `p_pounding.csv`: `im`, `gap` (m), `p_pounding`, from the runs without contact;
//! - `runs.csv`: one row per record and stripe: `record`, `file`, `stripe`, `im`, `factor`,
//!   `record_im` (the record's own IM, study units), `critical_gap` (m), per level
//!   `levelk_required_separation` (m), `impacts`, `peak_force` (N), per structure i
//!   `ductility_i`, `ductility_no_contact_i`, `drift_ratio_i`, `drift_ratio_no_contact_i`,
//!   `floor_acceleration_i`, `floor_acceleration_no_contact_i` (m/s²), `converged`;
//! - IDA: `ida.csv` (the IDA curves: `runs.csv`'s columns with `run`, the record's k-th run,
//!   for `stripe`, rows by record and increasing `im`) instead of `runs.csv`, and
//!   `capacities.csv`: `record`, `file`, `limit_state`, `model`, `im_lo`, `im_hi` (the bracket
//!   of the IM at which the limit state is first exceeded; `im_hi` empty: not reached),
//!   `capacity` (their midpoint); `fragility.csv` then holds the empirical fragility, one row
//!   per record reaching the limit state at its capacity (`exceedances` = records with a
//!   capacity at most `im`, `runs` = records);
//! - `fit.json`: the study (measure, units, stripes, records), per limit state and model the
//!   fit (`theta` in IM units, `beta`, `theta_interval`, `beta_interval`, …), the gap for the
//!   target probability.
//!
//! A row of buildings (more than two structures; a pair's files are unchanged): per pair
//! `p_pounding.csv` rows (a first column `pair`, 1-based), `runs.csv` columns
//! `pair{p}_critical_gap`, `pair{p}_level{k}_required_separation`, `pair{p}_impacts`,
//! `pair{p}_peak_force` and the structures' for i = 1 … N; `fit.json` with `structures`,
//! `pairs`, `pair` in every fit and `target_gap` a list (one per pair, with `pair` and
//! `between`).

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use super::{FragilityRun, MODELS, pounding};
use crate::input::fragility::{GapMode, IntensityMeasure};
use crate::output::atomic::{OutputError, write_atomic};

/// The files, in the order written.
pub const FILES: [&str; 4] = ["fragility.csv", "p_pounding.csv", "runs.csv", "fit.json"];

/// The files of an IDA, in the order written.
pub const IDA_FILES: [&str; 5] = [
    "fragility.csv",
    "p_pounding.csv",
    "ida.csv",
    "capacities.csv",
    "fit.json",
];

fn num(out: &mut String, x: f64) {
    if x.is_finite() {
        out.push_str(&crate::numerics::format::fmt_f64(x));
    } else if x == f64::INFINITY {
        out.push_str("inf");
    }
}

fn text(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// `fragility.csv`.
pub fn fragility_csv(run: &FragilityRun) -> String {
    let mut out = String::from("limit_state,model,im,runs,exceedances,fraction\n");
    for c in &run.curves {
        let name = &run.study.limit_states[c.limit_state].name;
        for (j, x) in c.im.iter().enumerate() {
            out.push_str(&format!("{},{},", text(name), MODELS[c.model]));
            num(&mut out, *x);
            out.push_str(&format!(",{},{},", c.runs[j], c.exceedances[j]));
            if c.runs[j] > 0 {
                num(&mut out, c.exceedances[j] as f64 / c.runs[j] as f64);
            }
            out.push('\n');
        }
    }
    out
}

/// `p_pounding.csv` (of a row: `pair` first, each pair's rows in row order).
pub fn p_pounding_csv(run: &FragilityRun) -> String {
    let row = run.study.scenario.is_row();
    let mut out = String::from(if row {
        "pair,im,gap,p_pounding\n"
    } else {
        "im,gap,p_pounding\n"
    });
    for (p, t) in run.pounding.iter().enumerate() {
        p_pounding_rows(&mut out, t, row.then_some(p));
    }
    out
}

fn p_pounding_rows(out: &mut String, t: &pounding::PoundingTable, pair: Option<usize>) {
    for (j, x) in t.im.iter().enumerate() {
        for (k, g) in t.gaps.iter().enumerate() {
            if let Some(p) = pair {
                out.push_str(&format!("{},", p + 1));
            }
            num(out, *x);
            out.push(',');
            num(out, *g);
            out.push(',');
            num(out, t.p[j][k]);
            out.push('\n');
        }
    }
}

/// `runs.csv` (stripes) or `ida.csv` (IDA: `run` for `stripe`, rows by record and IM). Of a
/// row: `pair{p}_critical_gap` for every pair, then `pair{p}_level{k}_required_separation`,
/// `pair{p}_impacts`, `pair{p}_peak_force`, and the structures' columns for i = 1 … N.
pub fn runs_csv(run: &FragilityRun) -> String {
    let shape = super::journal::Shape::of(&run.study);
    let ida = run.study.ida.is_some();
    let mut out = String::from(if ida {
        "record,file,run,im,factor,record_im"
    } else {
        "record,file,stripe,im,factor,record_im"
    });
    for p in 0..shape.levels.len() {
        out.push_str(&format!(",{}critical_gap", shape.pair_prefix(p)));
    }
    for c in shape.level_columns() {
        out.push_str(&format!(",{c}"));
    }
    for p in 0..shape.levels.len() {
        let pre = shape.pair_prefix(p);
        out.push_str(&format!(",{pre}impacts,{pre}peak_force"));
    }
    for c in shape.structure_columns() {
        out.push_str(&format!(",{c}"));
    }
    out.push_str(",converged\n");
    let u = run.study.units.factor();
    let mut order: Vec<&super::RunOutcome> = run.outcomes.iter().collect();
    if ida {
        order.sort_by(|a, b| a.record.cmp(&b.record).then(a.im.total_cmp(&b.im)));
    }
    for o in order {
        out.push_str(&format!(
            "{},{},{},",
            o.record + 1,
            text(&run.study.record_names[o.record]),
            o.stripe + 1
        ));
        num(
            &mut out,
            if ida {
                o.im / u
            } else {
                run.study.stripes_given[o.stripe]
            },
        );
        out.push(',');
        num(&mut out, o.factor);
        out.push(',');
        num(&mut out, run.record_im[o.record] / u);
        for p in 0..o.required.len() {
            out.push(',');
            num(&mut out, super::critical_of(&run.study, o, p));
        }
        for r in o.required.iter().flatten() {
            out.push(',');
            num(&mut out, *r);
        }
        for (n, f) in o.impacts.iter().zip(&o.peak_force) {
            out.push_str(&format!(",{n},"));
            num(&mut out, *f);
        }
        for d in &o.ductility {
            for x in d {
                out.push(',');
                if let Some(d) = x {
                    num(&mut out, *d);
                }
            }
        }
        for v in [&o.drift_ratio, &o.floor_acceleration] {
            for row in v {
                for x in row {
                    out.push(',');
                    num(&mut out, *x);
                }
            }
        }
        out.push(',');
        out.push_str(match o.converged {
            Some(true) => "true",
            Some(false) => "false",
            None => "unchecked",
        });
        out.push('\n');
    }
    out
}

/// `capacities.csv` (IDA; empty otherwise).
pub fn capacities_csv(run: &FragilityRun) -> String {
    let mut out = String::from("record,file,limit_state,model,im_lo,im_hi,capacity\n");
    let u = run.study.units.factor();
    for c in &run.curves {
        let Some(caps) = &c.capacities else { continue };
        let name = &run.study.limit_states[c.limit_state].name;
        for (r, cap) in caps.iter().enumerate() {
            out.push_str(&format!(
                "{},{},{},{},",
                r + 1,
                text(&run.study.record_names[r]),
                text(name),
                MODELS[c.model]
            ));
            num(&mut out, cap.lo / u);
            out.push(',');
            if let Some(h) = cap.hi {
                num(&mut out, h / u);
            }
            out.push(',');
            if let Some(v) = cap.value() {
                num(&mut out, v / u);
            }
            out.push('\n');
        }
    }
    out
}

fn finite(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

/// `fit.json`.
pub fn fit_json(run: &FragilityRun) -> Value {
    let s = &run.study;
    let measure = match &s.measure {
        IntensityMeasure::Pga => json!({ "kind": "pga" }),
        IntensityMeasure::Sa { structure, period } => {
            json!({ "kind": "sa", "structure": structure + 1, "period": period, "damping": super::im::DAMPING })
        }
        IntensityMeasure::SaAvg { periods } => {
            json!({ "kind": "sa_avg", "periods": periods, "damping": super::im::DAMPING })
        }
    };
    let u = s.units.factor();
    let row = s.scenario.is_row();
    let fits: Vec<Value> = run
        .curves
        .iter()
        .map(|c| {
            let ls = &s.limit_states[c.limit_state];
            let mut v = json!({
                "limit_state": ls.name,
                "kind": ls.kind.key(),
                "value": ls.value,
                "structure": ls.structure.map(|i| i + 1),
                "model": MODELS[c.model],
                "runs": c.runs,
                "exceedances": c.exceedances,
            });
            if row {
                v["pair"] = json!(ls.pair.map(|p| p + 1));
            }
            if let Some(caps) = &c.capacities {
                v["capacities"] = caps
                    .iter()
                    .map(|k| {
                        json!({
                            "im_lo": finite(k.lo / u),
                            "im_hi": k.hi.map(|h| finite(h / u)),
                            "capacity": k.value().map(|h| finite(h / u)),
                        })
                    })
                    .collect();
            }
            match &c.fit {
                Ok(f) => {
                    v["theta"] = finite(f.theta);
                    v["beta"] = finite(f.beta);
                    v["log_likelihood"] = finite(f.log_likelihood);
                    v["at_bound"] = json!(f.at_bound);
                    if let Some(b) = &c.intervals {
                        v["theta_interval"] = json!([finite(b.theta.lo), finite(b.theta.hi)]);
                        v["beta_interval"] = json!([finite(b.beta.lo), finite(b.beta.hi)]);
                        v["confidence"] = json!(b.confidence);
                        v["resamples"] = json!(b.resamples);
                        v["failed_resamples"] = json!(b.failed);
                    }
                }
                Err(e) => {
                    v["theta"] = Value::Null;
                    v["beta"] = Value::Null;
                    v["error"] = json!(e.to_string());
                }
            }
            v
        })
        .collect();
    let names: Vec<&str> = s.scenario.structures.iter().map(|x| x.name()).collect();
    // a pair's: its one gap (or null); a row's: one per pair, with the pair
    let target_gap = if row {
        json!(
            run.target_gap
                .iter()
                .enumerate()
                .map(|(p, g)| {
                    let mut v = json!({ "pair": p + 1, "between": [names[p], names[p + 1]] });
                    if let (Value::Object(o), Ok(Value::Object(g))) =
                        (&mut v, serde_json::to_value(g))
                    {
                        o.extend(g);
                    }
                    v
                })
                .collect::<Vec<_>>()
        )
    } else {
        json!(run.target_gap.first())
    };
    let mut out = json!({
        "title": s.title,
        "scenario": s.scenario_file,
        "measure": measure,
        "im_label": s.measure.label(),
        "im_units": s.units.key(),
        "stripes": run.stripes(),
        "ida": s.ida.map(|i| json!({
            "start": i.start / u, "step": i.step / u, "growth": i.growth / u,
            "tolerance": i.tolerance / u, "max_runs": i.max_runs, "fill": i.fill,
        })),
        "records": s.record_names.iter().zip(&run.record_im).map(|(f, x)| json!({ "file": f, "im": x / u })).collect::<Vec<_>>(),
        "runs": run.outcomes.len(),
        "checked": s.check,
        "unconverged_runs": run.unconverged(),
        "gap_mode": match s.gap_mode { GapMode::Uniform => "uniform", GapMode::Scaled => "scaled" },
        "method": if s.ida.is_some() {
            "IDA (hunt and fill, Vamvatsikos & Cornell 2002); lognormal of the records' capacities: geometric mean and standard deviation of ln (n - 1) (Baker 2015, eqs. 3-4), percentile bootstrap over records"
        } else {
            "multi-stripe; lognormal by maximum likelihood on the stripe counts (Baker 2015), percentile bootstrap over records"
        },
        "fits": fits,
        "target_gap": target_gap,
        "notes": s.notes,
    });
    if row {
        out["structures"] = json!(names);
        out["pairs"] = (0..names.len() - 1)
            .map(|p| json!({ "pair": p + 1, "between": [names[p], names[p + 1]] }))
            .collect();
    }
    out
}

/// `fit.json`'s text (pretty-printed, a final newline).
pub fn fit_json_text(run: &FragilityRun) -> String {
    // (a `Value` of finite numbers and strings always serialises)
    serde_json::to_string_pretty(&fit_json(run)).unwrap_or_default() + "\n"
}

/// Write every file into `dir` (created if missing), `fit.json` last, after `pictures` (the
/// figures, drawn by the caller into `dir`: this layer knows no pictures); returns the paths.
pub fn write(
    run: &FragilityRun,
    dir: &Path,
    pictures: impl FnOnce() -> Vec<PathBuf>,
) -> Result<Vec<PathBuf>, OutputError> {
    std::fs::create_dir_all(dir).map_err(|source| OutputError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let (names, texts): (&[&str], Vec<String>) = if run.study.ida.is_some() {
        (
            &IDA_FILES,
            vec![
                fragility_csv(run),
                p_pounding_csv(run),
                runs_csv(run),
                capacities_csv(run),
                fit_json_text(run),
            ],
        )
    } else {
        (
            &FILES,
            vec![
                fragility_csv(run),
                p_pounding_csv(run),
                runs_csv(run),
                fit_json_text(run),
            ],
        )
    };
    let mut written = Vec::new();
    let mut pictures = Some(pictures);
    for (name, t) in names.iter().zip(texts) {
        let p = dir.join(name);
        if *name == "fit.json"
            && let Some(draw) = pictures.take()
        {
            written.extend(draw());
        }
        write_atomic(&p, t.as_bytes())?;
        written.push(p);
    }
    Ok(written)
}
