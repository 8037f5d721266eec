//! `pounding` — command-line interface: parses arguments, reads files, calls the library,
//! prints the text its reports return (`pounding::output::text`, `study::*::report`), sets the
//! exit code. No logic: what a command computes or how it words its report is a library
//! function, which the Python package calls too.
//!
//! The binary's files: this one (entry, dispatch, the scenario and sweep commands),
//! src/main/args.rs (the clap definitions with their help texts, and option parsers),
//! src/main/records.rs (`record`, `spectrum`, `scale`), src/main/opensees.rs (`export`,
//! `crosscheck`), src/main/progress.rs (the progress bar of `run`). They are modules of the
//! binary (`#[path]`), not of the library; tests/architecture.rs leaves them out.
//!
//! A new subcommand: a variant of `args::Command` (its doc comment is the help) holding an
//! `…Args` struct in src/main/args.rs; one arm in [`run`]; one function here (or in a file of
//! src/main/ for a family of commands) that loads, calls the library and prints the strings
//! its reports return.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;

use pounding::analysis::simulate;
use pounding::input::scenario::{Scenario, design::spectrum_from_arg};
use pounding::output::text;
use pounding::study::{rule_study, sweep};

#[path = "main/args.rs"]
mod args;
#[path = "main/fragility.rs"]
mod fragility;
#[path = "main/opensees.rs"]
mod opensees;
#[path = "main/progress.rs"]
mod progress;
#[path = "main/records.rs"]
mod records;
#[path = "main/run.rs"]
mod run;

use args::{Cli, Command, ExportTarget};

/// The bundled default scenario: a 4- and an 8-storey frame under a scaled record, converged
/// at the default settings (the seed paper's case is examples/paper-c.toml).
const DEFAULT_SCENARIO: &str = include_str!("../examples/default.toml");
const DEFAULT_NAME: &str = "examples/default.toml (bundled default)";
/// The record the default scenario reads (its `ground_motion.file`), embedded with it so that
/// the default runs from any directory.
const DEFAULT_RECORD: (&str, &[u8]) = (
    "records/RSN753_LOMAP_CLS000.AT2",
    include_bytes!("../examples/records/RSN753_LOMAP_CLS000.AT2"),
);

fn main() -> ExitCode {
    restore_sigpipe();
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // every error message of the library already embeds its cause
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// Rust ignores SIGPIPE, so printing to a closed pipe (`pounding laws | head`) makes `println!`
/// panic. A command-line tool should instead end quietly, as Unix tools do.
fn restore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any thread starts or any I/O is done.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    let q = cli.quiet;
    match cli.command {
        Command::Run(a) => run::run_scenario(a, q),
        Command::Modes(a) => {
            print!("{}", text::modes_table(&load(a.scenario)?.0));
            Ok(())
        }
        Command::Laws(a) => laws(a.speed),
        Command::Convergence(a) => convergence(a, q),
        Command::Separation(a) => separation(a),
        Command::Sweep(a) => run_sweep(a, q),
        Command::Merge(a) => {
            let m = sweep::merge::merge(&a.out, &a.parts)?;
            quiet_or(q, || print!("{}", sweep::report::merge_summary(&m, &a.out)))
        }
        Command::Plot(a) => {
            let table = sweep::results::Table::read(&a.results)?;
            let dir = a.out.unwrap_or_else(|| beside(&a.results, "plots"));
            let req = pounding::figures::sweep::PlotRequest {
                x: a.x,
                y: a.y,
                field: a.field,
            };
            let files = pounding::figures::sweep::plot_table(&table, &req, &dir)?;
            quiet_or(q, || wrote_pictures(&files, &dir))
        }
        Command::Rules(a) => {
            let table = sweep::results::Table::read(&a.results)?;
            let study = rule_study::rule_study(&table);
            print!("{}", rule_study::format_study(&study));
            if a.no_plot {
                return Ok(());
            }
            let dir = a.out.unwrap_or_else(|| beside(&a.results, "plots"));
            let sub = format!("{} ({} cases)", a.results.display(), study.rows);
            let fig = pounding::figures::rules::rule_figure(&table, a.x.as_deref(), &dir, &sub)?;
            quiet_or(q, || println!("wrote {}", list_paths(&fig)))
        }
        Command::Export {
            target: ExportTarget::Opensees(a),
        } => opensees::export(a, q),
        Command::Crosscheck(a) => opensees::crosscheck(a, q),
        Command::Record(a) => records::record(a, q),
        Command::Spectrum(a) => records::spectrum(a, q),
        Command::Scale(a) => records::scale(a, q),
        Command::Fragility(a) => fragility::fragility(a, q),
    }
}

/// Runs `f` (printing) unless --quiet.
fn quiet_or(quiet: bool, f: impl FnOnce()) -> anyhow::Result<()> {
    if !quiet {
        f();
    }
    Ok(())
}

/// The scenario file, or the bundled default; with its name for reports.
fn load(path: Option<PathBuf>) -> anyhow::Result<(Scenario, String)> {
    match path {
        Some(p) => Ok((Scenario::from_file(&p)?, p.display().to_string())),
        None => {
            // the embedded record in a directory of its own, where the scenario looks for it
            let dir = tempfile::tempdir()?;
            let (file, bytes) = DEFAULT_RECORD;
            let path = dir.path().join(file);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent)?;
            }
            std::fs::write(&path, bytes)?;
            let sc = Scenario::from_toml(DEFAULT_SCENARIO, DEFAULT_NAME, dir.path())?;
            Ok((sc, DEFAULT_NAME.to_string()))
        }
    }
}

/// Commands of one ground motion refuse a suite of records (which `pounding run` runs); the
/// OpenSees commands, its users, take a pair or a row of buildings (issue 29).
fn refuse_suite(sc: &Scenario) -> anyhow::Result<()> {
    match &sc.suite {
        Some(s) => Err(pounding::integrate::SolveError::Suite(s.records.len()).into()),
        None => Ok(()),
    }
}

fn laws(speed: f64) -> anyhow::Result<()> {
    if !(speed.is_finite() && speed > 0.0) {
        anyhow::bail!("--speed must be a finite number > 0 (m/s), got {speed}");
    }
    let table = pounding::analysis::restitution::restitution_table(speed)?;
    print!("{}", text::laws_table(&table));
    Ok(())
}

fn convergence(a: args::ConvergenceArgs, quiet: bool) -> anyhow::Result<()> {
    let tolerance = a.tolerance;
    if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
        anyhow::bail!("--tolerance must be in (0, 1) (a relative change, e.g. 0.01 for 1 %)");
    }
    let (sc, name) = load(a.scenario)?;
    // (a row of buildings is studied as a pair is: per structure and per pair, issue 29)
    if let Some(s) = &sc.suite {
        return Err(pounding::integrate::SolveError::Suite(s.records.len()).into());
    }
    simulate::require_time_history(&sc)?;
    if !quiet {
        print!("{}", text::heading(&sc.title, &name));
    }
    let table = pounding::analysis::convergence::convergence(&sc, tolerance, |what| {
        if !quiet {
            eprintln!("  running {what} …")
        }
    });
    print!("{}", text::convergence_table(&table));
    Ok(())
}

fn separation(a: args::SeparationArgs) -> anyhow::Result<()> {
    let (sc, _) = load(a.scenario)?;
    let spectrum = a.spectrum.as_deref().map(spectrum_from_arg).transpose()?;
    let codes = (!a.code.is_empty()).then_some(a.code.as_slice());
    if sc.is_row() {
        // each adjacent pair's report, then the row's verdict (issue 29)
        let report =
            pounding::analysis::row_separation::row_gap_report(&sc, spectrum.as_ref(), codes)?;
        if a.json {
            println!("{}", serde_json::to_string_pretty(&report)?);
        } else {
            print!("{}", text::row_separation_report(&report));
        }
        return Ok(());
    }
    let report = pounding::analysis::gap_report::gap_report(&sc, spectrum.as_ref(), codes)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", text::separation_report(&report));
    }
    Ok(())
}

fn run_sweep(a: args::SweepArgs, quiet: bool) -> anyhow::Result<()> {
    use sweep::{Shard, Sweep, report, run};
    let path = &a.sweep;
    let sw = Sweep::from_file(path)?;
    if let Some(c) = a.case {
        print!(
            "{}",
            report::case_file(&sw, path, c).map_err(anyhow::Error::msg)?
        );
        return Ok(());
    }
    let stem = path.file_stem().unwrap_or(std::ffi::OsStr::new("sweep"));
    let out = a.out.unwrap_or_else(|| Path::new("out").join(stem));
    let jobs =
        (a.jobs).unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let shard = a.shard.unwrap_or(Shard::ALL);
    let in_shard = (0..sw.len()).filter(|&c| shard.contains(c)).count();
    pounding::output::budget::check_sweep(in_shard as u64, sw.axes.len(), a.max_output_size)?;
    let opts = run::RunOptions {
        out_dir: out.clone(),
        jobs,
        shard,
        check: !a.no_check,
    };
    let o = if quiet {
        run::run(&sw, &opts, &mut run::Silent)?
    } else {
        run::run(&sw, &opts, &mut run::StderrProgress::new())?
    };
    if let Some(w) = report::journal_warning(&o) {
        eprintln!("warning: {w}");
    }
    if !quiet {
        print!("{}", report::summary(&sw, path, &o, jobs, shard));
    }
    for w in report::warnings(&sw, path, &o) {
        eprintln!("warning: {w}");
    }
    if let Some(e) = report::every_case_failed(&o) {
        anyhow::bail!(e);
    }
    if !a.no_plot && shard.is_all() {
        let table = sweep::results::Table::read(&o.results)?;
        let dir = out.join("plots");
        // the pictures name the base scenario as what the keys not swept were held at
        let base = sw.scenario_path.file_name().map(|n| n.to_string_lossy());
        let req = Default::default();
        match pounding::figures::sweep::plot_table_of(&table, &req, &dir, base.as_deref()) {
            Ok(files) => quiet_or(quiet, || wrote_pictures(&files, &dir))?,
            Err(e) => eprintln!("warning: no pictures: {e}"),
        }
    } else if !shard.is_all() && !quiet {
        print!("{}", report::merge_hint(&out));
    }
    Ok(())
}

/// `name` in the directory of the file `file`.
fn beside(file: &Path, name: &str) -> PathBuf {
    file.parent().unwrap_or(Path::new(".")).join(name)
}

fn list_paths(paths: &[PathBuf]) -> String {
    let names: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
    names.join(", ")
}

fn wrote_pictures(files: &[PathBuf], dir: &Path) {
    let n = pounding::figures::sweep::count_pictures(files);
    println!("wrote {n} pictures (PNG and SVG) in {}", dir.display());
}
