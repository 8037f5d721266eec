//! The text report of a fragility study (what `pounding fragility` prints).

use std::fmt::Write as _;

use super::{FragilityRun, MODELS};

/// The report: the study, the fit of every limit state with and without pounding, the
/// P(pounding) at the stripes for a few gaps, the gap for the target probability.
pub fn report(run: &FragilityRun) -> String {
    let s = &run.study;
    let u = s.units.key();
    let mut o = String::new();
    let stripes = run.stripes();
    let _ = writeln!(o, "{}", s.title);
    match &s.ida {
        None => {
            let _ = writeln!(
                o,
                "  {} records × {} stripes = {} runs (each with and without contact{}), scenario {}",
                s.record_names.len(),
                stripes.len(),
                run.outcomes.len(),
                if s.check { ", self-checked" } else { "" },
                s.scenario_file
            );
            let _ = writeln!(
                o,
                "  intensity measure {} [{u}]; stripes {}",
                s.measure.label(),
                stripes
                    .iter()
                    .map(|x| format!("{x}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        Some(i) => {
            let per: Vec<usize> = (0..s.record_names.len())
                .map(|r| run.record_runs(r).count())
                .collect();
            let f = s.units.factor();
            let _ = writeln!(
                o,
                "  IDA (hunt and fill) of {} records: {} runs ({}–{} a record, at most {}; each \
                 with and without contact{}), scenario {}",
                s.record_names.len(),
                run.outcomes.len(),
                per.iter().min().copied().unwrap_or(0),
                per.iter().max().copied().unwrap_or(0),
                i.max_runs,
                if s.check { ", self-checked" } else { "" },
                s.scenario_file
            );
            let _ = writeln!(
                o,
                "  intensity measure {} [{u}]; start {}, step {} growing by {}, capacities \
                 bracketed to {}{}",
                s.measure.label(),
                fmt(i.start / f),
                fmt(i.step / f),
                fmt(i.growth / f),
                fmt(i.tolerance / f),
                if i.fill { "; gaps filled" } else { "" }
            );
        }
    }
    let f: Vec<f64> = run.outcomes.iter().map(|r| r.factor).collect();
    let (lo, hi) = f
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    let _ = writeln!(o, "  scale factors {lo:.3}–{hi:.3}");
    for n in &s.notes {
        let _ = writeln!(o, "  note: {n}");
    }
    let _ = writeln!(o);
    let _ = writeln!(
        o,
        "  {:<34} {:<8} {:>26}   {:>10} {:>22} {:>7} {:>16}",
        "limit state",
        "model",
        if s.ida.is_some() {
            "records"
        } else {
            "exceedances per stripe"
        },
        format!("θ [{u}]"),
        format!("{:.0} % interval", 100.0 * s.confidence),
        "β",
        "interval"
    );
    for c in &run.curves {
        let ls = &s.limit_states[c.limit_state];
        let counts = match &c.capacities {
            None => {
                let counts: Vec<String> = c.exceedances.iter().map(|z| z.to_string()).collect();
                format!(
                    "{}/{}",
                    counts.join(" "),
                    c.runs.first().copied().unwrap_or(0)
                )
            }
            Some(caps) => format!(
                "capacity in {} of {}",
                caps.iter().filter(|k| k.hi.is_some()).count(),
                caps.len()
            ),
        };
        let (theta, ti, beta, bi) = match &c.fit {
            Ok(fit) => {
                let (ti, bi) = c.intervals.as_ref().map_or(("–".into(), "–".into()), |b| {
                    (
                        format!("{:.3}–{:.3}", b.theta.lo, b.theta.hi),
                        format!("{:.2}–{:.2}", b.beta.lo, b.beta.hi),
                    )
                });
                let beta = if fit.at_bound {
                    format!("{:.2}*", fit.beta)
                } else {
                    format!("{:.2}", fit.beta)
                };
                (format!("{:.3}", fit.theta), ti, beta, bi)
            }
            Err(e) => (
                format!("({e})"),
                String::new(),
                String::new(),
                String::new(),
            ),
        };
        let _ = writeln!(
            o,
            "  {:<34} {:<8} {:>26}   {:>10} {:>22} {:>7} {:>16}",
            ls.name, MODELS[c.model], counts, theta, ti, beta, bi
        );
    }
    if run
        .curves
        .iter()
        .any(|c| c.fit.as_ref().is_ok_and(|f| f.at_bound))
    {
        let _ = writeln!(
            o,
            "  (* β at its bound: the counts jump from none to all between two stripes; add \
             stripes there)"
        );
    }
    if let Some(i) = &s.ida {
        let caps: Vec<&super::ida::Capacity> = run
            .curves
            .iter()
            .filter_map(|c| c.capacities.as_ref())
            .flatten()
            .collect();
        let wide = caps
            .iter()
            .filter(|k| k.hi.is_some_and(|h| h - k.lo > i.tolerance * (1.0 + 1e-9)))
            .count();
        let f = s.units.factor();
        let _ = writeln!(
            o,
            "  capacity: the midpoint of the bracket of the IM at which the limit state is first \
             exceeded; {} of {} bracketed within {} {u}{}",
            caps.len() - wide,
            caps.len(),
            fmt(i.tolerance / f),
            if wide > 0 {
                format!(
                    " ({wide} wider: the {} runs a record were spent; capacities.csv gives each \
                     bracket; raise ida.max_runs)",
                    i.max_runs
                )
            } else {
                String::new()
            }
        );
    }
    let _ = writeln!(
        o,
        "  model: with = the run with contact, without = the run without; for `pounding`, \
         without = the relative displacement passes the gap at some level"
    );
    // P(pounding) at a few gaps, per pair (a pair of structures: its one table)
    let row = s.scenario.is_row();
    let names: Vec<&str> = s.scenario.structures.iter().map(|x| x.name()).collect();
    for (p, t) in run.pounding.iter().enumerate() {
        let picks: Vec<usize> = {
            let n = t.gaps.len();
            let mut v: Vec<usize> = (0..5).map(|k| k * (n - 1) / 4).collect();
            v.dedup();
            v
        };
        let _ = writeln!(o);
        let _ = writeln!(
            o,
            "  P(pounding | IM, gap){} from the runs without contact{} ({} gap at every level{}):",
            if row {
                format!(" of pair {} ({}–{})", p + 1, names[p], names[p + 1])
            } else {
                String::new()
            },
            if s.ida.is_some() {
                " at the hunt's intensities that every record ran"
            } else {
                ""
            },
            match (s.gap_mode, row) {
                (crate::input::fragility::GapMode::Uniform, _) => "the same",
                (crate::input::fragility::GapMode::Scaled, false) => {
                    "the scenario's gaps scaled; the"
                }
                (crate::input::fragility::GapMode::Scaled, true) => "the pair's gaps scaled; the",
            },
            match (s.gap_mode, row) {
                (crate::input::fragility::GapMode::Uniform, false) => "",
                (crate::input::fragility::GapMode::Uniform, true) => " of the pair",
                (crate::input::fragility::GapMode::Scaled, _) => " at the highest level",
            }
        );
        let mut head = format!("  {:>12}", format!("IM [{u}]"));
        for &k in &picks {
            let _ = write!(head, " {:>12}", format!("{:.0} mm", 1e3 * t.gaps[k]));
        }
        let _ = writeln!(o, "{head}");
        for (j, x) in t.im.iter().enumerate() {
            let mut line = if s.ida.is_some() {
                format!("  {x:>12.4}")
            } else {
                format!("  {x:>12}")
            };
            for &k in &picks {
                let _ = write!(line, " {:>12.2}", t.p[j][k]);
            }
            let _ = writeln!(o, "{line}");
        }
    }
    if !run.target_gap.is_empty() {
        let _ = writeln!(o);
    }
    for (p, g) in run.target_gap.iter().enumerate() {
        let _ = writeln!(
            o,
            "  gap{} for P(pounding) ≤ {:.0} % at IM = {} {u}: {:.1} mm ({} of {} records pound \
             at it; the records' critical gaps ranked){}",
            if row {
                format!(" of pair {} ({}–{})", p + 1, names[p], names[p + 1])
            } else {
                String::new()
            },
            100.0 * g.probability,
            g.im,
            1e3 * g.empirical,
            g.pounding_records,
            g.records,
            match g.lognormal {
                Some(l) => format!(
                    "; {:.1} mm from a lognormal fitted to the critical gaps",
                    1e3 * l
                ),
                None => String::new(),
            }
        );
    }
    if let (Some(t), true) = (&s.target, run.target_gap.is_empty()) {
        let _ = writeln!(
            o,
            "  gap for P(pounding) ≤ {:.0} % at IM = {} {u}: not known — a record's runs did not \
             reach that intensity within ida.max_runs",
            100.0 * t.probability,
            fmt(t.im / s.units.factor())
        );
    }
    let bad = run.unconverged();
    if bad > 0 {
        let _ = writeln!(
            o,
            "  warning: {bad} of {} runs did not pass the self-check (runs.csv, converged)",
            run.outcomes.len()
        );
    }
    o
}

fn fmt(x: f64) -> String {
    crate::numerics::format::fmt_f64(x)
}

/// The runs' warnings, each once, with the first record and stripe that gave it.
pub fn warnings(run: &FragilityRun) -> Vec<String> {
    let mut seen = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for w in &run.study.scenario.warnings {
        if seen.insert(w.clone()) {
            out.push(w.clone());
        }
    }
    let mut more = 0;
    for o in &run.outcomes {
        for w in &o.warnings {
            // (a warning's numbers differ from run to run: ten are enough to see what is wrong)
            if out.len() >= 10 {
                more += usize::from(seen.insert(w.clone()));
                continue;
            }
            if seen.insert(w.clone()) {
                out.push(format!(
                    "{w} (record {}, IM = {} {}; and maybe others)",
                    run.study.record_names[o.record],
                    fmt(o.im / run.study.units.factor()),
                    run.study.units.key()
                ));
            }
        }
    }
    if more > 0 {
        out.push(format!("… and {more} more warnings of other runs"));
    }
    out
}
