//! `pounding` — command-line interface. Parses arguments, reads files, calls the library, prints.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use pounding::scenario::Scenario;
use pounding::separation::Rule;
use pounding::simulate::{Report, simulate};

/// The bundled default scenario: the seed paper's case T1/T2 = 0.7.
const DEFAULT_SCENARIO: &str = include_str!("../examples/paper-c.toml");
const DEFAULT_NAME: &str = "examples/paper-c.toml (bundled default)";

#[derive(Parser)]
#[command(
    name = "pounding",
    version,
    about = "Seismic pounding of two adjacent structures (continuous cantilevers, modal expansion, contact laws)",
    long_about = "Seismic pounding of two adjacent structures.\n\n\
        Each structure is a continuous Euler–Bernoulli cantilever reduced to its modes; both are shaken by \
        the same ground motion and hit each other through a contact law (Hertz by default) when the gap \
        closes. `pounding run` simulates a scenario with and without pounding and reports the peaks, \
        impacts, forces and the separation needed to avoid pounding.\n\n\
        Scenario files are TOML; see examples/ and the README. Units are SI (m, kg, s, N); PGA is in g."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a scenario with and without pounding; print a summary and write results.
    ///
    /// Writes DIR/summary.json (peaks, change %, impacts, forces, separations, energy balance),
    /// DIR/history.csv (t, w1, w2, force, w1_free, w2_free at the contact height), DIR/impacts.csv
    /// (one row per impact) and the time-history figure DIR/history.png/.svg.
    Run {
        /// Scenario file (TOML). Without it, the bundled default runs: the seed paper's case
        /// T1/T2 = 0.7 (examples/paper-c.toml).
        scenario: Option<PathBuf>,
        /// Output directory (created if missing).
        #[arg(short, long, default_value = "out")]
        out: PathBuf,
        /// Do not draw the figure.
        #[arg(long)]
        no_plot: bool,
        /// Print only errors.
        #[arg(short, long)]
        quiet: bool,
    },
    /// List each structure's modes: period, frequency, damping ratio, φ(h) and participation.
    Modes {
        /// Scenario file (TOML); the bundled default if omitted.
        scenario: Option<PathBuf>,
    },
    /// Convergence study: the run with pounding for 1, 2, 3, 5, 10, 20, 50 modes and for a ladder
    /// of steps (dt × 4 … ⅛; rtol 1e-4 … 1e-10 for `adaptive`), each with its change relative to
    /// the finest, and a recommendation (fewest modes, largest step within the tolerance).
    Convergence {
        /// Scenario file (TOML); the bundled default if omitted.
        scenario: Option<PathBuf>,
        /// Largest acceptable relative change of the peaks and peak force vs the finest run.
        #[arg(long, default_value_t = 0.01)]
        tolerance: f64,
    },
    /// Required separation by every rule (ABS, SRSS, DDC, DDC as printed in the paper) and the
    /// exact time-history value, side by side.
    Separation {
        /// Scenario file (TOML); the bundled default if omitted.
        scenario: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn load(path: Option<&Path>) -> anyhow::Result<(Scenario, String)> {
    match path {
        Some(p) => Ok((Scenario::from_file(p)?, p.display().to_string())),
        None => Ok((
            Scenario::from_toml(DEFAULT_SCENARIO, DEFAULT_NAME, Path::new("examples"))?,
            DEFAULT_NAME.to_string(),
        )),
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Run {
            scenario,
            out,
            no_plot,
            quiet,
        } => {
            let (sc, name) = load(scenario.as_deref())?;
            let report = simulate(&sc)?;
            let mut written = pounding::output::write_run(&out, &sc, &report)?;
            if !no_plot {
                written.extend(pounding::figures::time_history_figure(
                    &sc,
                    &report,
                    &out.join("history"),
                )?);
            }
            if !quiet {
                print_summary(&sc, &name, &report);
                println!();
                let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
                println!("wrote {}", names.join(", "));
            }
            for w in &report.warnings {
                eprintln!("warning: {w}");
            }
            Ok(())
        }
        Command::Modes { scenario } => {
            let (sc, _) = load(scenario.as_deref())?;
            print_modes(&sc);
            Ok(())
        }
        Command::Convergence {
            scenario,
            tolerance,
        } => {
            if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
                anyhow::bail!(
                    "--tolerance must be in (0, 1) (a relative change, e.g. 0.01 for 1 %)"
                );
            }
            let (sc, name) = load(scenario.as_deref())?;
            println!(
                "{}
  scenario: {name}",
                sc.title
            );
            let table = pounding::convergence::convergence(&sc, tolerance, |what| {
                eprintln!("  running {what} …")
            });
            print_convergence(&table);
            Ok(())
        }
        Command::Separation { scenario } => {
            let (sc, _) = load(scenario.as_deref())?;
            let report = simulate(&sc)?;
            print_separation(&sc, &report);
            Ok(())
        }
    }
}

fn print_summary(sc: &Scenario, name: &str, r: &Report) {
    println!("{}", sc.title);
    println!("  scenario: {name}");
    let levels: Vec<String> = sc
        .contact
        .levels
        .iter()
        .map(|l| format!("h = {} m (gap {} mm)", l.height, l.gap * 1e3))
        .collect();
    println!(
        "  {} contact at {}; {}, dt = {} s over {} s ({} steps)",
        sc.contact.law.name(),
        levels.join(", "),
        sc.solver.method.name(),
        sc.solver.dt,
        sc.solver.duration,
        r.stats.steps
    );
    println!();
    let [a, b] = &r.structures;
    println!("  {:<34}{:>16}{:>16}", "", a.name, b.name);
    println!(
        "  {:<34}{:>16.4}{:>16.4}",
        "first-mode period [s]", a.periods[0], b.periods[0]
    );
    println!(
        "  {:<34}{:>16.4}{:>16.4}",
        "peak w(h) without pounding [m]",
        a.peak_displacement_no_contact,
        b.peak_displacement_no_contact
    );
    println!(
        "  {:<34}{:>16.4}{:>16.4}",
        "peak w(h) with pounding [m]", a.peak_displacement, b.peak_displacement
    );
    println!(
        "  {:<34}{:>+16.1}{:>+16.1}",
        "change [%]", a.change_percent, b.change_percent
    );
    println!();
    let c = &r.contact;
    if c.impacts == 0 {
        println!("  no contact: the gap never closed");
    } else {
        println!(
            "  {} impacts, peak force {:.4e} N, max penetration {:.3} mm, {:.3} s in contact",
            c.impacts,
            c.peak_force,
            c.max_penetration * 1e3,
            c.contact_time
        );
    }
    if r.levels.len() > 1 {
        for l in &r.levels {
            println!(
                "    level h = {} m: {} impacts, peak force {:.4e} N, {:.3} s in contact",
                l.height, l.impacts, l.peak_force, l.contact_time
            );
        }
    }
    let s = &r.separation;
    println!(
        "  required separation [m]: time history {:.4} | ABS {:.4}  SRSS {:.4}  DDC {:.4}  (DDC as printed in the paper {:.4})",
        s.time_history, s.abs, s.srss, s.ddc, s.ddc_paper
    );
    println!(
        "  energy balance error: {:.1e} with contact, {:.1e} without",
        r.energy.relative_error, r.energy_no_contact.relative_error
    );
}

fn print_modes(sc: &Scenario) {
    let h = sc.main_height();
    for (i, s) in sc.structures.iter().enumerate() {
        let m = s.modal();
        println!(
            "structure {} \"{}\": L = {} m, M = {:.4e} kg, EI = {:.4e} N·m²",
            i + 1,
            s.name,
            s.length,
            s.mass,
            s.bending_stiffness()
        );
        println!(
            "  {:>4} {:>12} {:>12} {:>12} {:>9} {:>14} {:>14} {:>10}",
            "mode", "period [s]", "freq [Hz]", "ω [rad/s]", "ζ", "φ(h)·√M", "Γ [kg^½]", "mass [%]"
        );
        for n in 0..m.omega.len() {
            let w = m.omega[n];
            println!(
                "  {:>4} {:>12.6} {:>12.5} {:>12.4} {:>9.5} {:>14.6} {:>14.4} {:>10.3}",
                n + 1,
                2.0 * std::f64::consts::PI / w,
                w / (2.0 * std::f64::consts::PI),
                w,
                m.zeta[n],
                m.shape(n, h) * m.mass.sqrt(),
                m.participation_factor(n),
                100.0 * m.effective_mass_fraction(n)
            );
        }
        println!();
    }
    println!(
        "φ(h) at the contact height h = {h} m, times √M (dimensionless; ±2 at a free tip). Γ = m∫φ dx is the\n\
         participation factor (η̈ + … = −Γ a_g); mass % = Γ²/M, the share of the mass each mode moves."
    );
}

fn print_convergence(t: &pounding::convergence::ConvergenceTable) {
    let print_rows = |title: &str, rows: &[pounding::convergence::Row]| {
        println!();
        println!("  {title}");
        println!(
            "  {:>6} {:>12} {:>10} {:>8} {:>11} {:>11} {:>13} {:>8} {:>9} {:>9} {:>9}",
            "modes",
            "method",
            "dt [s]",
            "rtol",
            "peak w1 [m]",
            "peak w2 [m]",
            "peak F [N]",
            "impacts",
            "Δw1 [%]",
            "Δw2 [%]",
            "ΔF [%]"
        );
        for r in rows {
            let rtol = r.rtol.map_or("-".to_string(), |x| format!("{x:.0e}"));
            if let Some(f) = &r.failure {
                println!(
                    "  {:>6} {:>12} {:>10.2e} {:>8}  {f}",
                    r.modes, r.method, r.dt, rtol
                );
                continue;
            }
            println!(
                "  {:>6} {:>12} {:>10.2e} {:>8} {:>11.5} {:>11.5} {:>13.5e} {:>8} {:>9.3} {:>9.3} {:>9.3}",
                r.modes,
                r.method,
                r.dt,
                rtol,
                r.peak_w1,
                r.peak_w2,
                r.peak_force,
                r.impacts,
                100.0 * r.change[0],
                100.0 * r.change[1],
                100.0 * r.change[2]
            );
        }
    };
    print_rows("modes (change vs the most modes):", &t.modes);
    print_rows("step / tolerance (change vs the finest):", &t.steps);
    println!();
    println!(
        "  recommendation (tolerance {} %): {}",
        100.0 * t.tolerance,
        t.recommendation
    );
}

fn print_separation(sc: &Scenario, r: &Report) {
    let s = &r.separation;
    let [a, b] = &r.structures;
    println!("{}", sc.title);
    println!(
        "  peaks without pounding at h = {} m: w1 = {:.5} m, w2 = {:.5} m; T1/T2 = {:.4}, ζ1 = {}, ζ2 = {}, ρ12 (CQC) = {:.5}",
        sc.main_height(),
        a.peak_displacement_no_contact,
        b.peak_displacement_no_contact,
        a.periods[0] / b.periods[0],
        a.damping_ratios[0],
        b.damping_ratios[0],
        s.rho
    );
    println!();
    println!("  {:<44}{:>12}{:>16}", "rule", "gap [m]", "vs exact");
    let rows = [
        ("time history, max(w1 − w2) (exact)", s.time_history, None),
        ("ABS  w1 + w2", s.abs, Some(Rule::Abs)),
        ("SRSS √(w1² + w2²)", s.srss, Some(Rule::Srss)),
        ("DDC  √(w1² + w2² − 2ρ w1 w2)", s.ddc, Some(Rule::Ddc)),
        (
            "ddc-paper (eq. 22–23 as printed)",
            s.ddc_paper,
            Some(Rule::DdcPaper),
        ),
    ];
    for (label, v, rule) in rows {
        let vs = if rule.is_some() && s.time_history > 0.0 {
            format!("{:+.1} %", 100.0 * (v - s.time_history) / s.time_history)
        } else {
            String::new()
        };
        println!("  {label:<44}{v:>12.5}{vs:>16}");
    }
    println!();
    println!(
        "  the at-rest gap in the scenario is {} m: {}",
        sc.contact.levels[0].gap,
        if sc.contact.levels[0].gap >= s.time_history {
            "wide enough, no pounding"
        } else {
            "too small, the structures pound"
        }
    );
}
