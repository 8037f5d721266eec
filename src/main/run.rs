//! `pounding run`: the scenario's run (a pair, a suite of records or a row of buildings)
//! streamed into its files with a progress bar, its report printed.

use std::io::IsTerminal as _;
use std::path::Path;

use anyhow::anyhow;
use pounding::analysis::simulate;
use pounding::input::scenario::Scenario;
use pounding::output::text;
use pounding::study::suite;

use crate::{args, list_paths, load, progress};

/// `pounding run`: a pair's run streamed into its files (summary.json last), a suite of records
/// or a row of buildings by their own writers; the report printed, the warnings on stderr.
pub(super) fn run_scenario(a: args::RunArgs, quiet: bool) -> anyhow::Result<()> {
    let (sc, name) = load(a.scenario.clone())?;
    if sc.suite.is_some() {
        return run_suite(&sc, &name, &a.out, a.no_plot, a.no_check, quiet);
    }
    simulate::require_time_history(&sc)?;
    if sc.is_row() {
        return run_row(&sc, &name, &a, quiet);
    }
    pounding::output::budget::check_run(&sc, a.max_output_size)?;
    let mut writer = pounding::output::writer::RunWriter::for_scenario(&a.out, &sc)?;
    let bar = !quiet && std::io::stderr().is_terminal();
    let phases = if a.no_check { 2.0 } else { 4.0 };
    let mut sink = progress::RunProgress::new(&mut writer, bar, sc.solver.duration, phases);
    // the self-check integrates on a second thread while this one writes the result's files
    // and draws its pictures (none of which reads the check); summary.json waits for it
    let result =
        simulate::simulate_streaming_beside(&sc, !a.no_check, &mut sink, true, |sink, report| {
            let draw = (!a.no_plot).then(|| pounding::figures::run::run_pictures(&sc, report));
            sink.writer().finish_files(report, draw)
        });
    sink.finish();
    let (report, files) = result?;
    let written = writer.finish_summary(&sc, &report, files?)?;
    if !quiet {
        print!("{}", text::run_summary(&sc, &name, &report));
        println!("\nwrote {}", list_paths(&written));
    }
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// `pounding run` on a suite of records (`[ground_motion] kind = "suite"`): every record run
/// (in parallel), the files written (summary.json last), the report printed.
fn run_suite(
    sc: &Scenario,
    name: &str,
    out: &Path,
    no_plot: bool,
    no_check: bool,
    quiet: bool,
) -> anyhow::Result<()> {
    if !quiet && std::io::stderr().is_terminal() {
        eprintln!("{}", suite::report::progress_line(sc, !no_check));
    }
    if sc.is_row() {
        return run_row_suite(sc, name, out, no_plot, no_check, quiet);
    }
    let run = suite::run(sc, !no_check).map_err(|e| anyhow!("{name}: {e}"))?;
    let draw = (!no_plot).then(|| pounding::figures::suite::suite_pictures(&run));
    let written = suite::write::write(out, &run, draw, |_| None)?;
    if !quiet {
        print!("{}", suite::report::text(&run, &sc.title, name));
        println!("\nwrote {}", list_paths(&written));
    }
    for w in suite::report::warnings(sc, &run) {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// `pounding run` on a suite of records on a row of buildings: every record through the row's
/// driver (in parallel), each record's run in its folder, the representative's at the top
/// level (summary.json last), the report per pair printed.
fn run_row_suite(
    sc: &Scenario,
    name: &str,
    out: &Path,
    no_plot: bool,
    no_check: bool,
    quiet: bool,
) -> anyhow::Result<()> {
    let run = suite::row::run_row(sc, !no_check).map_err(|e| anyhow!("{name}: {e}"))?;
    let draw = (!no_plot).then(|| pounding::figures::suite::row_suite_pictures(&run));
    let written = suite::write::write(out, &run, draw, |i| {
        (!no_plot).then(|| pounding::figures::suite::row_suite_record_pictures(&run, i))
    })?;
    if !quiet {
        print!("{}", suite::report::text(&run, &sc.title, name));
        // (each record's folder once, not its every file)
        let top: Vec<_> = written
            .iter()
            .filter(|p| !p.starts_with(out.join(suite::write::RECORDS_DIR)))
            .cloned()
            .collect();
        println!(
            "\nwrote {}, and each record's run in {}",
            list_paths(&top),
            out.join(suite::write::RECORDS_DIR).display()
        );
    }
    for w in suite::report::warnings(sc, &run) {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// `pounding run` on a row of buildings (issue 29): the row with and without contact (and the
/// self-check unless `--no-check`, beside them on a second thread), streamed into history.csv
/// and floors.csv, then impacts.csv, the pictures (unless `--no-plot`) and summary.json last.
fn run_row(sc: &Scenario, name: &str, a: &args::RunArgs, quiet: bool) -> anyhow::Result<()> {
    pounding::output::budget::check_run(sc, a.max_output_size)?;
    let mut writer = pounding::output::writer::RunWriter::for_scenario(&a.out, sc)?;
    let bar = !quiet && std::io::stderr().is_terminal();
    let phases = if a.no_check { 2.0 } else { 4.0 };
    let mut sink = progress::RunProgress::new(&mut writer, bar, sc.solver.duration, phases);
    // as a pair's: the self-check on a second thread while this one writes the result's files
    // and draws its pictures (none of which reads the check); summary.json waits for it
    let result = simulate::simulate_row_streaming_beside(
        sc,
        !a.no_check,
        &mut sink,
        true,
        |sink, report| {
            let draw = (!a.no_plot).then(|| pounding::figures::row::row_pictures(sc, report));
            sink.writer().finish_files(report, draw)
        },
    );
    sink.finish();
    let (report, files) = result?;
    let written = writer.finish_summary(sc, &report, files?)?;
    if !quiet {
        print!("{}", text::row_summary(sc, name, &report));
        println!("\nwrote {}", list_paths(&written));
    }
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    Ok(())
}
