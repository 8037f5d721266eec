//! The commands on record files: `pounding record`, `spectrum`, `scale`. Each reads the
//! records, calls the library and prints the text or JSON its reports return.

use anyhow::anyhow;
use std::path::PathBuf;

use pounding::analysis::record_spectrum as rs;
use pounding::input::scenario::design::spectrum_from_arg;
use pounding::model::ground_motion::{Record, SaTarget};
use pounding::output::record_summary;

use super::args::{self, parse_list, parse_pair};
use super::{list_paths, quiet_or};

pub fn record(a: args::RecordArgs, quiet: bool) -> anyhow::Result<()> {
    let opts = record_summary::options(
        a.component.as_deref(),
        a.units.as_deref(),
        a.dt,
        a.baseline.as_deref(),
        a.highpass,
        a.lowpass,
        a.order,
    )
    .map_err(anyhow::Error::msg)?;
    let record = Record::read(&a.file, &opts)?;
    let summary = record_summary::RecordSummary::of(&record, &a.file.display().to_string());
    if let Some(out) = &a.csv {
        record_summary::write_csv(&record, out)?;
    }
    if a.json {
        println!("{}", summary.json());
        return Ok(());
    }
    print!("{}", summary.text());
    match &a.csv {
        Some(out) => quiet_or(quiet, || println!("wrote {}", out.display())),
        None => Ok(()),
    }
}

pub fn spectrum(a: args::SpectrumArgs, quiet: bool) -> anyhow::Result<()> {
    let read = read_records(&a.records, a.component.as_deref(), a.units.as_deref(), a.dt)?;
    let periods = match a.periods {
        Some(text) => rs::parse_periods(&text)?,
        None => rs::default_periods(),
    };
    let target = a.target.as_deref().map(spectrum_from_arg).transpose()?;
    let target = target.map(rs::Target::as_given);
    let t1 = a.t1.as_deref().map(|t| parse_list(t, "--t1")).transpose()?;
    let range = t1.map(|t| rs::PeriodRange::from_first_modes(&t));
    let pairs: Vec<(&str, &Record)> = read.iter().map(|(n, r)| (n.as_str(), r)).collect();
    let report = pounding::output::spectrum_report::SpectrumReport::new(
        &pairs,
        &periods,
        a.damping,
        target.as_ref(),
        range,
    )?;
    if a.json {
        println!("{}", report.json());
    } else {
        print!("{}", report.text());
    }
    if a.no_plot {
        return Ok(());
    }
    std::fs::create_dir_all(&a.out)?;
    let fig = pounding::figures::spectrum::spectrum_figure(&report, &a.out.join("spectrum"))?;
    quiet_or(quiet || a.json, || println!("wrote {}", list_paths(&fig)))
}

pub fn scale(a: args::ScaleArgs, quiet: bool) -> anyhow::Result<()> {
    if let Some(sa) = &a.sa {
        return scale_to_sa(&a, sa);
    }
    // (clap requires these without --sa)
    let (Some(rule), Some(target), Some(t1)) = (&a.rule, &a.target, &a.t1) else {
        anyhow::bail!("give --target, --rule and --t1 (a suite to a spectrum), or --sa T,SA");
    };
    let rule = rs::ScalingRule::from_name(rule)
        .ok_or_else(|| anyhow!("--rule {rule}: must be asce7 or ec8"))?;
    let spectrum = spectrum_from_arg(target)?;
    let target = match a.target_scale {
        None => rs::Target::for_rule(spectrum, rule),
        Some(f) if f.is_finite() && f > 0.0 => rs::Target::scaled(spectrum, f),
        Some(f) => anyhow::bail!("--target-scale {f}: must be a positive number"),
    };
    let mut opts = rs::ScalingOptions::new(rule, &parse_list(t1, "--t1")?);
    opts.required_ratio = a.ratio;
    if let Some(r) = a.range {
        let (lo, hi) = parse_pair(&r, "--range")?;
        opts.range = Some(rs::PeriodRange { lo, hi });
    }
    let limits = a.factor_limits.as_deref();
    opts.factor_limits = limits
        .map(|l| parse_pair(l, "--factor-limits"))
        .transpose()?;
    let read = read_records(&a.records, a.component.as_deref(), a.units.as_deref(), a.dt)?;
    let members: Vec<rs::SuiteMember> = read
        .iter()
        .map(|(name, record)| rs::SuiteMember { name, record })
        .collect();
    let suite = rs::SuiteScaling::compute(&members, &target, &opts)?;
    if a.json {
        println!("{}", suite.json());
    } else {
        print!("{}", suite.text());
    }
    if a.no_plot {
        return Ok(());
    }
    std::fs::create_dir_all(&a.out)?;
    let fig = pounding::figures::spectrum::scaling_figure(&suite, &a.out.join("scaling"))?;
    quiet_or(quiet || a.json, || println!("wrote {}", list_paths(&fig)))
}

/// `pounding scale --sa T,SA`: each record's factor to the target PSA, table or JSON.
fn scale_to_sa(a: &args::ScaleArgs, sa: &str) -> anyhow::Result<()> {
    let (period, sa_g) = parse_pair(sa, "--sa")?;
    let target = SaTarget {
        period,
        sa: sa_g,
        damping: a.damping,
    };
    let read = read_records(&a.records, a.component.as_deref(), a.units.as_deref(), a.dt)?;
    let members: Vec<rs::SuiteMember> = read
        .iter()
        .map(|(name, record)| rs::SuiteMember { name, record })
        .collect();
    let scaled = rs::single::SaScaling::compute(&members, &target)?;
    if a.json {
        println!("{}", scaled.json());
    } else {
        print!("{}", scaled.text());
    }
    Ok(())
}

/// Reads every record file with the same options; the error names the file.
fn read_records(
    files: &[PathBuf],
    component: Option<&str>,
    units: Option<&str>,
    dt: Option<f64>,
) -> anyhow::Result<Vec<(String, Record)>> {
    let opts = record_summary::options(component, units, dt, None, None, None, 4)
        .map_err(anyhow::Error::msg)?;
    files
        .iter()
        .map(|f| Ok((f.display().to_string(), Record::read(f, &opts)?)))
        .collect()
}
