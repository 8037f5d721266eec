//! `pounding` — command-line interface. Parses arguments, reads files, calls the library, prints.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use std::io::IsTerminal as _;

use pounding::analysis::simulate::{Phase, Report, simulate_streaming};
use pounding::input::scenario::Scenario;
use pounding::output::run::RunWriter;

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

#[derive(Parser)]
#[command(
    name = "pounding",
    version,
    about = "Seismic pounding of two adjacent structures — cantilevers, shear buildings (elastic or \
             with yielding storeys) or buildings given by their modes — under harmonic or recorded \
             ground motion",
    long_about = "Seismic pounding of two adjacent structures.\n\n\
        Each structure is one of: a continuous Euler–Bernoulli cantilever (kind = \"cantilever\", \
        the default); a shear building with floors (kind = \"shear-building\": floor masses and \
        storey stiffnesses, elastic or with yielding Bouc–Wen storeys); or a building given by its \
        own modes (kind = \"modal\": periods and mode shapes, e.g. exported from ETABS, SAP2000 or \
        OpenSees). Each is reduced to its modes; both are shaken by the same ground motion \
        (harmonic, or a recorded accelerogram) and hit each other through a contact law (Hertz by \
        default) at one or more heights — floor against floor — when the gap closes.\n\n\
        `pounding run` simulates a scenario with and without pounding and reports the peaks at the \
        contact height and at every floor (displacement, storey drift, absolute acceleration, \
        storey shear; ductility, residual drift and hysteretic energy of yielding storeys), every \
        impact, and the separation needed to avoid pounding; every run checks itself against a \
        100× tighter run. `pounding separation` sets the separation rules and the building codes \
        side by side.\n\n\
        Without a scenario file the bundled default runs (examples/default.toml: a 4- and an \
        8-storey frame 25 mm apart under the Loma Prieta 1989 record scaled to 0.4 g). Scenario \
        files are TOML; see examples/ and the README. Units are SI (m, kg, s, N); PGA is in g."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Print only errors, warnings and what the command exists to print (the tables of
    /// `modes`, `laws`, `separation`, `convergence`): no progress, no run summary, no list of
    /// files written. Works before or after the command name.
    #[arg(short, long, global = true)]
    quiet: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a scenario with and without pounding; print a summary and write results.
    ///
    /// Writes into DIR (w is a displacement relative to the ground, at the highest contact
    /// level unless a floor is named):
    ///
    ///   history.csv          t, w1, w2, force, w1_free, w2_free (force_1 … with several
    ///                        contact levels), one row per output interval
    ///   impacts.csv          one row per impact: level, height, start, end, duration,
    ///                        peak_force, impulse, max_penetration, approach_speed
    ///   floors.csv           every floor's (a cantilever's stations') displacement w{i}_{h} and
    ///                        absolute acceleration a{i}_{h} over time, with and without (_free)
    ///   history.png/.svg     the displacements with and without pounding, the contact force
    ///   envelopes.png/.svg   peaks over height: displacement, storey drift ratio, absolute
    ///                        acceleration (impact pulses marked), storey shear (+ ductility)
    ///   hysteresis.png/.svg  with yielding storeys: storey force against drift
    ///   summary.json         written last: peaks, change %, every floor, impacts, forces,
    ///                        separations, energy balance, self-check, warnings
    ///
    /// Every run checks itself: the scenario is run a second time at a 100× tighter tolerance
    /// (rtol/100 and atol/100; dt/√10 for rk4) and the peaks, peak force, impacts and required
    /// separation are compared. A change above 1 % is a warning naming the setting to tighten,
    /// and the result is reported as NOT converged (summary.json: accuracy).
    #[command(verbatim_doc_comment)]
    Run {
        /// Scenario file (TOML). Without it, the bundled default runs (examples/default.toml:
        /// a 4- and an 8-storey frame under a scaled earthquake record).
        scenario: Option<PathBuf>,
        /// Output directory (created if missing).
        #[arg(short, long, default_value = "out")]
        out: PathBuf,
        /// Draw no pictures (history, envelopes, hysteresis); removes those an earlier run
        /// left in DIR.
        #[arg(long)]
        no_plot: bool,
        /// Skip the self-check (the second run at a 100× tighter tolerance); summary.json
        /// then says `"accuracy": {"checked": false, …}`.
        #[arg(long)]
        no_check: bool,
        /// Largest history.csv the run may write (estimated before the run from
        /// solver.duration / solver.output_interval), e.g. 5GB, 500MB, 2e9; a run above it is
        /// refused with the estimate and the keys that change it.
        #[arg(long, value_name = "SIZE", default_value = "1GB", value_parser = parse_size)]
        max_output_size: u64,
    },
    /// List each structure's modes: period, frequency, damping ratio, φ(h) and participation.
    Modes {
        /// Scenario file (TOML); the bundled default if omitted.
        scenario: Option<PathBuf>,
    },
    /// Achieved coefficient of restitution of every contact law that takes a target e, measured
    /// on an isolated two-body impact through the solver (e = 0.3 … 0.9).
    ///
    /// Several laws are derived for idealised impacts and miss their nominal e; pick a law knowing
    /// what it does. The result does not depend on the stiffness, masses or approach speed for
    /// these laws (they are scale-free); defaults are the paper's k_h and 0.5 m/s.
    Laws {
        /// Approach speed, m/s.
        #[arg(long, default_value_t = 0.5)]
        speed: f64,
    },
    /// Convergence study: the run with pounding for 1, 2, 3, 5, 10, 20, 50 modes and for a ladder
    /// of steps (dt × 4 … ⅛; rtol 1e-4 … 1e-10 for `adaptive`), each with its change relative to
    /// the finest, and a recommendation (fewest modes, largest step within the tolerance) that
    /// `pounding run` accepts — or "NOT CONVERGED" and what to try, when even the two finest runs
    /// of a ladder differ by more than the tolerance.
    Convergence {
        /// Scenario file (TOML); the bundled default if omitted.
        scenario: Option<PathBuf>,
        /// Largest acceptable relative change of the peaks and peak force vs the finest run.
        #[arg(long, default_value_t = 0.01)]
        tolerance: f64,
    },
    /// Required separation by every rule at every contact level, side by side: ABS, SRSS, DDC,
    /// DDC as printed in the paper, and the building codes whose factors the scenario's
    /// [separation] table gives (ASCE 7-16 §12.12.3, IS 1893 §7.11.3, NBCC 4.1.8.14, GB 50011
    /// §6.1.4, NTC-Sismo §1.10, EN 1998-1 §4.4.2.7), each against the gap given at that level;
    /// with a time history, the exact time-history separation beside them and each rule's
    /// over/under-estimate of it (%). The verdict of each rule is its worst level, named.
    ///
    /// At each level the rules take each structure's own peak there without pounding: from the
    /// time history (inelastic where storeys yield), or with a design spectrum ([ground_motion]
    /// kind = "spectrum", or --spectrum) the CQC of Γ_n φ_n(h) S_d(T_n, ζ_n). Lengths in mm.
    Separation {
        /// Scenario file (TOML); the bundled default if omitted.
        scenario: Option<PathBuf>,
        /// Only these codes (comma-separated or repeated): asce7, is1893, nbcc, gb50011, ntc, ec8
        /// [default: every code whose factors are in the scenario].
        #[arg(long, value_delimiter = ',')]
        code: Vec<String>,
        /// Use this design spectrum for the rules instead of the time history (which still
        /// gives the exact separation): asce7:sds=1.0,sd1=0.6,tl=8 |
        /// ec8:ag=0.25g,ground_type=C,type=1 (a_g with its unit: 0.25g or 2.45m/s2) |
        /// table:FILE[,units=g] (T in s, S_a in m/s² unless units=g).
        #[arg(long, value_name = "SPEC")]
        spectrum: Option<String>,
        /// Write the report as JSON on stdout instead of the tables (SI units, full precision;
        /// keys in the README, "One report").
        #[arg(long)]
        json: bool,
    },
    /// Run a parameter study: every case of a grid over scenario keys, in parallel, resumable.
    ///
    /// SWEEP.toml names a base scenario and one or more axes, e.g.
    ///
    ///   scenario = "paper-c.toml"            # relative to the sweep file
    ///   [[axis]]
    ///   key = "period_ratio"                 # T1/T2: varies structure 2's period
    ///   values = [0.3, 0.5, 0.7]
    ///   [[axis]]
    ///   key = "ground_motion.pga"            # any scenario key by path
    ///   from = 0.1
    ///   to = 0.9
    ///   steps = 9                            # add scale = "log" for log spacing
    ///
    /// Derived keys: period_ratio (T1/T2) and ground_period_ratio (T2/Tg, harmonic motion).
    /// Scenario keys: structure.1.period, structure.2.mass, contact.gap, contact.stiffness,
    /// ground_motion.pga, ground_motion.file (values = record files), solver.dt, … The grid is
    /// the full product, first axis slowest.
    ///
    /// Writes DIR/results.csv (one row per case, in case order: case, the axis values,
    /// status, peaks, change %, peak force, impacts, contact time, required separations, and
    /// the self-check: check_max_change, converged) and pictures in DIR/plots.
    ///
    /// Every case checks itself as `pounding run` does (a second run at a 100× tighter
    /// tolerance; converged = every headline number within 1 %), which costs about one to four
    /// more runs per case; --no-check skips it and the rows say converged = unchecked. Every finished case is journaled at once in DIR/journal.csv:
    /// if the sweep is stopped (Ctrl-C, kill, a crash), run the same command again and only
    /// the missing cases are computed. A case that fails (e.g. an unstable step) is recorded
    /// with its reason and the sweep goes on.
    #[command(verbatim_doc_comment)]
    Sweep {
        /// The sweep file (TOML).
        sweep: PathBuf,
        /// Output directory (created if missing) [default: out/<sweep file name>].
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Worker threads [default: the number of CPUs].
        #[arg(short, long)]
        jobs: Option<usize>,
        /// Run only part K of N of the grid (e.g. 3/8; case i is in part i mod N + 1), for
        /// spreading a study over machines, e.g. a Slurm array job with
        /// --shard $((SLURM_ARRAY_TASK_ID+1))/$SLURM_ARRAY_TASK_COUNT. Each part writes
        /// DIR/results-shard-K-of-N.csv; join them with `pounding merge`.
        #[arg(long, value_name = "K/N")]
        shard: Option<pounding::study::sweep::Shard>,
        /// Do not draw the pictures.
        #[arg(long)]
        no_plot: bool,
        /// Print the scenario of case N (TOML) and exit, e.g. to rerun it with `pounding run`.
        #[arg(long, value_name = "N")]
        case: Option<usize>,
        /// Skip the cases' self-check (faster); the rows then say converged = unchecked.
        #[arg(long)]
        no_check: bool,
        /// Largest output (results.csv and its journal, estimated from the number of cases)
        /// the sweep may write, e.g. 5GB; a sweep above it is refused with the estimate.
        #[arg(long, value_name = "SIZE", default_value = "1GB", value_parser = parse_size)]
        max_output_size: u64,
    },
    /// Join the parts of a sharded sweep into one results table, checking that every case is
    /// there exactly once.
    Merge {
        /// The merged table to write.
        out: PathBuf,
        /// The parts (results-shard-K-of-N.csv files), or directories holding them.
        #[arg(required = true)]
        parts: Vec<PathBuf>,
    },
    /// How often each separation rule is unsafe over a sweep: from a results table with the
    /// exact time-history separation (sep_time_history) and the rules (sep_abs, sep_srss,
    /// sep_ddc, and sep_asce7 … when the base scenario had a [separation] table), the fraction
    /// of cases where each rule is below the exact value, its worst shortfall and its excess
    /// when safe; draws DIR/rules.png/.svg (rule/exact against one axis: smallest, median,
    /// largest over the other axes).
    Rules {
        /// The results table (results.csv of a sweep, or a merged table).
        results: PathBuf,
        /// Axis along x of the figure [default: the first axis].
        #[arg(long)]
        x: Option<String>,
        /// Output directory of the figure [default: plots/ beside the results table].
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Do not draw the figure.
        #[arg(long)]
        no_plot: bool,
    },
    /// Draw a sweep's pictures from its results table: heatmaps over two axes, line plots
    /// over one.
    ///
    /// Without options: heatmaps of the change % of each structure, the peak force, the
    /// number of impacts and the required separation over the first two numeric axes (one
    /// picture per value of the other axes), and line plots over the first axis.
    Plot {
        /// The results table (results.csv of a sweep, or a merged table).
        results: PathBuf,
        /// Axis along x (an axis key, e.g. period_ratio).
        #[arg(long)]
        x: Option<String>,
        /// Axis along y: draws heatmaps (without it, with --x: line plots over x).
        #[arg(long, requires = "x")]
        y: Option<String>,
        /// Field to draw: change_percent_1, change_percent_2, peak_force, impacts,
        /// contact_time, sep_time_history, sep_abs, sep_srss, sep_ddc, peak_displacement_1, …
        #[arg(long)]
        field: Option<String>,
        /// Output directory [default: plots/ beside the results table].
        #[arg(short, long)]
        out: Option<PathBuf>,
    },
    /// Export a scenario to another program (`export opensees`).
    Export {
        #[command(subcommand)]
        target: ExportTarget,
    },
    /// Run the scenario in OpenSees (a local openseespy) and in the program, and print the
    /// numbers side by side with their relative differences and what explains them.
    ///
    /// Needs python3 with openseespy (`pip install openseespy==3.7.1.2`); the interpreter is
    /// $POUNDING_PYTHON, else python3. Without openseespy: an error saying how to install it.
    Crosscheck {
        /// Scenario file (TOML); the bundled default if omitted.
        scenario: Option<PathBuf>,
        /// Beam elements per cantilever in OpenSees.
        #[arg(long, default_value_t = pounding::opensees::DEFAULT_ELEMENTS)]
        elements: usize,
        /// OpenSees' analysis step, s.
        #[arg(long, default_value_t = pounding::opensees::DEFAULT_DT)]
        dt: f64,
        /// Modes per structure in the program (default: the scenario's); an rk4 step that is
        /// then unstable switches the program to `adaptive`.
        #[arg(long)]
        modes: Option<usize>,
        /// Simulated time, s, for both (default: the scenario's).
        #[arg(long)]
        duration: Option<f64>,
        /// Keep the script (model.py), OpenSees' results (opensees.json) and log in DIR.
        #[arg(long, value_name = "DIR")]
        keep: Option<PathBuf>,
    },
    /// What the program reads from a ground-motion record file: layout (detected from the
    /// content), component, units in the file, time step, number of points, PGA (m/s² and g)
    /// and its time, the peak the header states; `--csv` writes the series in SI (t, a).
    ///
    /// Layouts: PEER NGA .AT2, COSMOS V1/V2, CSMIP/DMG V1/V2, K-NET/KiK-net ASCII, ESM ASCII,
    /// one or two columns. Uncorrected records (V1) are refused unless processed (--baseline,
    /// --highpass, --lowpass).
    Record {
        /// The record file.
        file: PathBuf,
        /// The component of a multi-channel file: its number (1, 2, …) or name ("90", "EW").
        #[arg(long)]
        component: Option<String>,
        /// Print JSON (keys format, component, dt, points, pga, pga_time, …).
        #[arg(long)]
        json: bool,
        /// Write the series to OUT as CSV: t (s), a (m/s²).
        #[arg(long, value_name = "OUT")]
        csv: Option<PathBuf>,
        /// Units of the values, overriding the file's: g, cm/s2 (gal), m/s2.
        #[arg(long)]
        units: Option<String>,
        /// Time step, s (one-column files; resampling of digitised film records).
        #[arg(long)]
        dt: Option<f64>,
        /// Baseline correction: linear or polynomial.
        #[arg(long, value_parser = ["linear", "polynomial"])]
        baseline: Option<String>,
        /// High-pass corner, Hz (zero-phase Butterworth).
        #[arg(long, value_name = "HZ")]
        highpass: Option<f64>,
        /// Low-pass corner, Hz (zero-phase Butterworth).
        #[arg(long, value_name = "HZ")]
        lowpass: Option<f64>,
        /// Butterworth order.
        #[arg(long, default_value_t = pounding::model::ground_motion::processing::DEFAULT_ORDER)]
        order: usize,
    },
    /// 5 %-damped pseudo-acceleration response spectra of records (exact for an acceleration
    /// linear between samples, Nigam–Jennings): a table of PSA in g per period and record,
    /// their mean, and the figure DIR/spectrum.png/.svg (log period axis).
    ///
    /// With --target the design spectrum is drawn and tabulated beside them, and with --t1
    /// the period range 0.2·T1 … 2·T1 is shaded. --json gives per record `periods` (s), `psa`
    /// (m/s²), `psa_g`, `sd` (m), `psv` (m/s), `sa_abs` (m/s²).
    Spectrum {
        /// Record files (any layout `pounding record` reads).
        #[arg(required = true)]
        records: Vec<PathBuf>,
        /// The component of multi-channel files: a number (1, 2, …) or a name ("90", "EW"),
        /// the same for every file.
        #[arg(long)]
        component: Option<String>,
        /// Damping ratio of the oscillators, in [0, 1).
        #[arg(long, default_value_t = pounding::analysis::record_spectrum::DEFAULT_DAMPING)]
        damping: f64,
        /// Periods, s: a list (0,0.1,0.2,0.5,1) or FROM:TO:N (N periods equally spaced in log
        /// T). Default: 0 (the PGA) and 0.01 to 10 s, 20 a decade.
        #[arg(long)]
        periods: Option<String>,
        /// A design spectrum to show beside the records, as `pounding separation --spectrum`:
        /// asce7:sds=…,sd1=…,tl=… | ec8:ag=…,ground_type=…,type=… | table:FILE.
        #[arg(long, value_name = "SPEC")]
        target: Option<String>,
        /// First-mode periods of the structures, s (one or two): shade 0.2·min … 2·max.
        #[arg(long, value_name = "T1[,T2]")]
        t1: Option<String>,
        /// Print JSON instead of the table.
        #[arg(long)]
        json: bool,
        /// Directory for the figure (created if missing).
        #[arg(short, long, default_value = "out")]
        out: PathBuf,
        /// Do not draw the figure.
        #[arg(long)]
        no_plot: bool,
        /// Units of the values, overriding the files': g, cm/s2 (gal), m/s2.
        #[arg(long)]
        units: Option<String>,
        /// Time step, s (one-column files).
        #[arg(long)]
        dt: Option<f64>,
    },
    /// Scale a suite of records to a target spectrum by a code's rule: one factor per record so
    /// that the suite's mean 5 %-damped spectrum is at least 90 % of the target over the code's
    /// period range (0.2·T1 … 2·T1) — ASCE 7-16 §16.2.3 (≥ 11 records, target MCE_R = 1.5 × an
    /// ASCE 7 design spectrum) or EN 1998-1 §3.2.3.1.2 (≥ 3 records, and mean PGA ≥ a_g·S).
    ///
    /// Prints each record's factor, the lowest mean-to-target ratio and where, and what governs;
    /// refuses, with the reason, a suite that cannot meet the rule. Draws DIR/scaling.png/.svg.
    Scale {
        /// Record files.
        #[arg(required = true)]
        records: Vec<PathBuf>,
        /// The target spectrum: asce7:sds=…,sd1=…,tl=… | ec8:ag=…,ground_type=…,type=… |
        /// table:FILE (as `pounding separation --spectrum`).
        #[arg(long, value_name = "SPEC")]
        target: String,
        /// The code's rule.
        #[arg(long, value_parser = ["asce7", "ec8"])]
        rule: String,
        /// First-mode periods of the structures, s (one or two).
        #[arg(long, value_name = "T1[,T2]")]
        t1: String,
        /// A wider period range than the code's, s (e.g. to include the modes of 90 % mass
        /// participation, ASCE 7-16 §16.2.3.1).
        #[arg(long, value_name = "LO,HI")]
        range: Option<String>,
        /// The mean-to-target ratio to reach (at least the code's 0.9).
        #[arg(long, default_value_t = 0.9)]
        ratio: f64,
        /// Smallest and largest factor allowed per record.
        #[arg(long, value_name = "MIN,MAX")]
        factor_limits: Option<String>,
        /// Multiply the target by this instead of the rule's factor (1.5 for an ASCE 7 design
        /// spectrum under asce7, else 1).
        #[arg(long)]
        target_scale: Option<f64>,
        /// The component of multi-channel files, the same for every file.
        #[arg(long)]
        component: Option<String>,
        /// Print JSON (factors, grid, target, mean, ratios) instead of the table.
        #[arg(long)]
        json: bool,
        /// Directory for the figure (created if missing).
        #[arg(short, long, default_value = "out")]
        out: PathBuf,
        /// Do not draw the figure.
        #[arg(long)]
        no_plot: bool,
        /// Units of the values, overriding the files': g, cm/s2 (gal), m/s2.
        #[arg(long)]
        units: Option<String>,
        /// Time step, s (one-column files).
        #[arg(long)]
        dt: Option<f64>,
    },
    /// How likely pounding is: a fragility study (multi-stripe analysis). Every record of the
    /// study's suite is scaled to each intensity level (stripe) and run with and without
    /// contact; per limit state the fraction exceeding at each stripe and a lognormal fit
    /// (maximum likelihood, bootstrap intervals over records); P(pounding | IM, gap) for every
    /// gap from the runs without contact and the gap for a target probability.
    ///
    /// Writes into DIR: fragility.csv, p_pounding.csv, runs.csv, the figures fragility.png/.svg
    /// and p-pounding.png/.svg, and fit.json last. See the README, "Fragility".
    Fragility {
        /// The study file (TOML).
        study: PathBuf,
        /// Output directory (created if missing) [default: out/<study file name>].
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Worker threads [default: the number of CPUs].
        #[arg(short, long)]
        jobs: Option<usize>,
        /// Do not draw the figures.
        #[arg(long)]
        no_plot: bool,
    },
}

/// Targets of `pounding export`.
#[derive(Subcommand)]
enum ExportTarget {
    /// Write a self-contained OpenSeesPy script of the scenario: `python3 model.py` runs it
    /// with and without contact and prints JSON with the headline numbers of summary.json.
    ///
    /// Cantilevers become N elasticBeamColumn elements (consistent mass), shear buildings
    /// floor masses with storey springs, each contact level a zeroLength element with the
    /// law's material (hertz, linear, jankowski: exact; kelvin, hertzdamp: approximate;
    /// stereomechanical: refused). See the README, "Checking in OpenSees".
    Opensees {
        /// Scenario file (TOML); the bundled default if omitted.
        scenario: Option<PathBuf>,
        /// Write the script here (default: standard output).
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Beam elements per cantilever.
        #[arg(long, default_value_t = pounding::opensees::DEFAULT_ELEMENTS)]
        elements: usize,
        /// OpenSees' analysis step, s.
        #[arg(long, default_value_t = pounding::opensees::DEFAULT_DT)]
        dt: f64,
        /// Run only the case with contact or only the one without.
        #[arg(long, value_parser = ["contact", "free"])]
        only: Option<String>,
        /// Simulated time, s (default: the scenario's).
        #[arg(long)]
        duration: Option<f64>,
    },
}

/// `--max-output-size` values.
fn parse_size(text: &str) -> Result<u64, String> {
    pounding::output::budget::parse_size(text)
}

fn main() -> ExitCode {
    restore_sigpipe();
    let cli = Cli::parse();
    match run(cli) {
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

fn load(path: Option<&Path>) -> anyhow::Result<(Scenario, String)> {
    match path {
        Some(p) => Ok((Scenario::from_file(p)?, p.display().to_string())),
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

/// Streams a run into its [`RunWriter`] and shows a progress bar on a terminal when the run
/// takes more than a second.
struct RunProgress<'a> {
    writer: &'a mut RunWriter,
    enabled: bool,
    bar: Option<indicatif::ProgressBar>,
    started: std::time::Instant,
    duration: f64,
    phases: f64,
    ticks: u32,
}

impl RunProgress<'_> {
    fn finish(&mut self) {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
    }
}

impl pounding::analysis::simulate::RunSink for RunProgress<'_> {
    fn contact_row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
        self.writer.contact_row(t, w, forces);
    }

    fn free_row(&mut self, t: f64, w: [f64; 2]) {
        self.writer.free_row(t, w);
    }

    fn contact_floor_row(&mut self, t: f64, values: &[f64]) {
        self.writer.contact_floor_row(t, values);
    }

    fn free_floor_row(&mut self, t: f64, values: &[f64]) {
        self.writer.free_floor_row(t, values);
    }

    fn progress(&mut self, phase: Phase, t: f64) {
        if !self.enabled {
            return;
        }
        self.ticks = self.ticks.wrapping_add(1);
        if self.bar.is_none() {
            if !self.ticks.is_multiple_of(64) || self.started.elapsed().as_secs_f64() < 1.0 {
                return;
            }
            let bar = indicatif::ProgressBar::new(1000);
            let style = indicatif::ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {wide_bar} {percent:>3} %, ETA {eta} {msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
            bar.set_style(style);
            bar.enable_steady_tick(std::time::Duration::from_millis(200));
            self.bar = Some(bar);
        }
        let index = match phase {
            Phase::WithContact => 0.0,
            Phase::WithoutContact => 1.0,
            Phase::CheckWithContact => 2.0,
            Phase::CheckWithoutContact => 3.0,
        };
        if let Some(b) = &self.bar {
            let done = (index + t / self.duration) / self.phases;
            b.set_position((1000.0 * done).clamp(0.0, 1000.0) as u64);
            if self.ticks.is_multiple_of(256) {
                b.set_message(format!(
                    "{} at t = {t:.0} s of {} s",
                    phase.label(),
                    self.duration
                ));
            }
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    let quiet = cli.quiet;
    match cli.command {
        Command::Run {
            scenario,
            out,
            no_plot,
            no_check,
            max_output_size,
        } => {
            let (sc, name) = load(scenario.as_deref())?;
            if sc.suite.is_some() {
                return run_suite(&sc, &name, &out, no_plot, no_check, quiet);
            }
            pounding::analysis::simulate::require_time_history(&sc)?;
            pounding::output::budget::check_run(&sc, max_output_size)?;
            let mut writer = RunWriter::for_scenario(&out, &sc)?;
            let mut sink = RunProgress {
                writer: &mut writer,
                enabled: !quiet && std::io::stderr().is_terminal(),
                bar: None,
                started: std::time::Instant::now(),
                duration: sc.solver.duration,
                phases: if no_check { 2.0 } else { 4.0 },
                ticks: 0,
            };
            let result = simulate_streaming(&sc, !no_check, &mut sink);
            sink.finish();
            let report = result?;
            let draw = (!no_plot).then(|| pounding::figures::run::run_pictures(&sc, &report));
            let written = writer.finish(&sc, &report, draw)?;
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
        Command::Sweep {
            sweep,
            out,
            jobs,
            shard,
            no_plot,
            case,
            no_check,
            max_output_size,
        } => run_sweep(
            &sweep,
            out,
            jobs,
            shard,
            SweepFlags {
                no_plot,
                case,
                check: !no_check,
                quiet,
                max_output_size,
            },
        ),
        Command::Merge { out, parts } => {
            let m = pounding::study::sweep::results::merge(&out, &parts)?;
            if quiet {
                return Ok(());
            }
            println!(
                "merged {} part(s): {} cases ({} failed) into {}",
                m.parts.len(),
                m.cases,
                m.failed,
                out.display()
            );
            Ok(())
        }
        Command::Plot {
            results,
            x,
            y,
            field,
            out,
        } => {
            let table = pounding::study::sweep::results::Table::read(&results)?;
            let dir =
                out.unwrap_or_else(|| results.parent().unwrap_or(Path::new(".")).join("plots"));
            let req = pounding::figures::sweep::PlotRequest { x, y, field };
            let files = pounding::figures::sweep::plot_table(&table, &req, &dir)?;
            if quiet {
                return Ok(());
            }
            println!(
                "wrote {} pictures (PNG and SVG) in {}",
                pounding::figures::sweep::count_pictures(&files),
                dir.display()
            );
            Ok(())
        }
        Command::Rules {
            results,
            x,
            out,
            no_plot,
        } => {
            let table = pounding::study::sweep::results::Table::read(&results)?;
            let study = pounding::study::rule_study::rule_study(&table);
            print!("{}", pounding::study::rule_study::format_study(&study));
            if !no_plot {
                let dir =
                    out.unwrap_or_else(|| results.parent().unwrap_or(Path::new(".")).join("plots"));
                let sub = format!("{} ({} cases)", results.display(), study.rows);
                let files =
                    pounding::figures::rules::rule_figure(&table, x.as_deref(), &dir, &sub)?;
                if !quiet {
                    let names: Vec<String> =
                        files.iter().map(|p| p.display().to_string()).collect();
                    println!("wrote {}", names.join(", "));
                }
            }
            Ok(())
        }
        Command::Laws { speed } => {
            if !(speed.is_finite() && speed > 0.0) {
                anyhow::bail!("--speed must be a finite number > 0 (m/s), got {speed}");
            }
            print_laws(speed)
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
            refuse_suite(&sc)?;
            pounding::analysis::simulate::require_time_history(&sc)?;
            if !quiet {
                println!(
                    "{}
  scenario: {name}",
                    sc.title
                );
            }
            let table = pounding::analysis::convergence::convergence(&sc, tolerance, |what| {
                if !quiet {
                    eprintln!("  running {what} …")
                }
            });
            print_convergence(&table);
            Ok(())
        }
        Command::Separation {
            scenario,
            code,
            spectrum,
            json,
        } => {
            let (sc, _) = load(scenario.as_deref())?;
            let spectrum = spectrum
                .as_deref()
                .map(pounding::input::scenario::design::spectrum_from_arg)
                .transpose()?;
            let codes = (!code.is_empty()).then_some(code.as_slice());
            let report = pounding::analysis::gap_report::gap_report(&sc, spectrum.as_ref(), codes)?;
            if json {
                println!("{}", serde_json::to_string_pretty(&report)?);
            } else {
                print_separation(&report);
            }
            Ok(())
        }
        Command::Export {
            target:
                ExportTarget::Opensees {
                    scenario,
                    out,
                    elements,
                    dt,
                    only,
                    duration,
                },
        } => {
            let (sc, name) = load(scenario.as_deref())?;
            refuse_suite(&sc)?;
            let opts = pounding::opensees::ExportOptions {
                elements,
                dt,
                duration,
                only: only
                    .as_deref()
                    .and_then(pounding::opensees::Only::from_name),
            };
            let script = pounding::opensees::script(&sc, &opts, &name)?;
            match out {
                None => print!("{script}"),
                Some(path) => {
                    pounding::output::atomic::write_atomic(&path, script.as_bytes())?;
                    if !quiet {
                        println!(
                            "wrote {} (run it: python3 {} [--json results.json])",
                            path.display(),
                            path.display()
                        );
                    }
                }
            }
            Ok(())
        }
        Command::Record {
            file,
            component,
            json,
            csv,
            units,
            dt,
            baseline,
            highpass,
            lowpass,
            order,
        } => {
            let opts = pounding::output::record_summary::options(
                component.as_deref(),
                units.as_deref(),
                dt,
                baseline.as_deref(),
                highpass,
                lowpass,
                order,
            )
            .map_err(anyhow::Error::msg)?;
            let record = pounding::model::ground_motion::Record::read(&file, &opts)?;
            let name = file.display().to_string();
            let summary = pounding::output::record_summary::RecordSummary::of(&record, &name);
            if let Some(out) = &csv {
                pounding::output::record_summary::write_csv(&record, out)?;
            }
            if json {
                println!("{}", summary.json());
            } else {
                print!("{}", summary.text());
                if let Some(out) = &csv
                    && !quiet
                {
                    println!("wrote {}", out.display());
                }
            }
            Ok(())
        }
        Command::Spectrum {
            records,
            component,
            damping,
            periods,
            target,
            t1,
            json,
            out,
            no_plot,
            units,
            dt,
        } => {
            use pounding::analysis::record_spectrum as rs;
            let read = read_records(&records, component.as_deref(), units.as_deref(), dt)?;
            let periods = match periods {
                Some(text) => rs::parse_periods(&text)?,
                None => rs::default_periods(),
            };
            let target = target
                .as_deref()
                .map(pounding::input::scenario::design::spectrum_from_arg)
                .transpose()?
                .map(rs::Target::as_given);
            let range = t1
                .as_deref()
                .map(|t| parse_list(t, "--t1"))
                .transpose()?
                .map(|t| rs::PeriodRange::from_first_modes(&t));
            let pairs: Vec<(&str, &pounding::model::ground_motion::Record)> =
                read.iter().map(|(n, r)| (n.as_str(), r)).collect();
            let report = pounding::output::spectrum_report::SpectrumReport::new(
                &pairs,
                &periods,
                damping,
                target.as_ref(),
                range,
            )?;
            if json {
                println!("{}", report.json());
            } else {
                print!("{}", report.text());
            }
            if !no_plot {
                std::fs::create_dir_all(&out)?;
                let written =
                    pounding::figures::spectrum::spectrum_figure(&report, &out.join("spectrum"))?;
                if !quiet && !json {
                    println!("wrote {}", list_paths(&written));
                }
            }
            Ok(())
        }
        Command::Scale {
            records,
            target,
            rule,
            t1,
            range,
            ratio,
            factor_limits,
            target_scale,
            component,
            json,
            out,
            no_plot,
            units,
            dt,
        } => {
            use pounding::analysis::record_spectrum as rs;
            let rule = rs::ScalingRule::from_name(&rule)
                .ok_or_else(|| anyhow::anyhow!("--rule {rule}: must be asce7 or ec8"))?;
            let spectrum = pounding::input::scenario::design::spectrum_from_arg(&target)?;
            let target = match target_scale {
                None => rs::Target::for_rule(spectrum, rule),
                Some(f) if f.is_finite() && f > 0.0 => rs::Target::scaled(spectrum, f),
                Some(f) => anyhow::bail!("--target-scale {f}: must be a positive number"),
            };
            let mut opts = rs::ScalingOptions::new(rule, &parse_list(&t1, "--t1")?);
            opts.required_ratio = ratio;
            if let Some(r) = range {
                let (lo, hi) = parse_pair(&r, "--range")?;
                opts.range = Some(rs::PeriodRange { lo, hi });
            }
            opts.factor_limits = factor_limits
                .as_deref()
                .map(|l| parse_pair(l, "--factor-limits"))
                .transpose()?;
            let read = read_records(&records, component.as_deref(), units.as_deref(), dt)?;
            let members: Vec<rs::SuiteMember> = read
                .iter()
                .map(|(name, record)| rs::SuiteMember { name, record })
                .collect();
            let suite = rs::SuiteScaling::compute(&members, &target, &opts)?;
            if json {
                println!("{}", suite.json());
            } else {
                print!("{}", suite.text());
            }
            if !no_plot {
                std::fs::create_dir_all(&out)?;
                let written =
                    pounding::figures::spectrum::scaling_figure(&suite, &out.join("scaling"))?;
                if !quiet && !json {
                    println!("wrote {}", list_paths(&written));
                }
            }
            Ok(())
        }
        Command::Crosscheck {
            scenario,
            elements,
            dt,
            modes,
            duration,
            keep,
        } => {
            let (sc, name) = load(scenario.as_deref())?;
            refuse_suite(&sc)?;
            let opts = pounding::opensees::compare::CrosscheckOptions {
                export: pounding::opensees::ExportOptions {
                    elements,
                    dt,
                    duration,
                    only: None,
                },
                modes,
                keep,
            };
            let python = pounding::opensees::compare::python();
            if !quiet {
                eprintln!("  running OpenSees ({python}) and the program …");
            }
            let c = pounding::opensees::compare::crosscheck(&sc, &name, &opts, &python)?;
            println!("{}\n  scenario: {name}", sc.title);
            print!("{}", c.table());
            Ok(())
        }
        Command::Fragility {
            study,
            out,
            jobs,
            no_plot,
        } => run_fragility(&study, out, jobs, no_plot, quiet),
    }
}

/// `pounding fragility`: the study run, its files and figures written (fit.json last), its
/// report printed (`study::fragility::report`).
fn run_fragility(
    path: &Path,
    out: Option<PathBuf>,
    jobs: Option<usize>,
    no_plot: bool,
    quiet: bool,
) -> anyhow::Result<()> {
    use pounding::study::fragility;
    let study = pounding::input::fragility::FragilityStudy::from_file(path)?;
    let out = out.unwrap_or_else(|| {
        let stem = path.file_stem().unwrap_or_default();
        Path::new("out").join(stem)
    });
    if !quiet && std::io::stderr().is_terminal() {
        eprintln!(
            "  running {} runs (with and without contact) …",
            study.runs()
        );
    }
    let run =
        fragility::run(&study, jobs).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let mut failed = None;
    let written = fragility::write::write(&run, &out, || {
        if no_plot {
            return Vec::new();
        }
        pounding::figures::fragility::pictures(&run, &out).unwrap_or_else(|e| {
            failed = Some(e);
            Vec::new()
        })
    })?;
    if !quiet {
        print!("{}", fragility::report::report(&run));
        println!();
        println!("wrote {}", list_paths(&written));
    }
    for w in fragility::report::warnings(&run) {
        eprintln!("warning: {w}");
    }
    if let Some(e) = failed {
        anyhow::bail!("the figures could not be drawn: {e}");
    }
    Ok(())
}

/// `pounding run` on a suite of records (`[ground_motion] kind = "suite"`): every record run
/// (in parallel), the files written (suite.csv, the representative record's run, summary.json
/// with its `suite` section, last), the report printed.
fn run_suite(
    sc: &Scenario,
    name: &str,
    out: &Path,
    no_plot: bool,
    no_check: bool,
    quiet: bool,
) -> anyhow::Result<()> {
    use pounding::study::suite;
    if !quiet && std::io::stderr().is_terminal() {
        let n = sc.suite.as_ref().map_or(0, |s| s.records.len());
        eprintln!(
            "  running {n} records (with and without pounding{}) …",
            if no_check { "" } else { ", self-checked" }
        );
    }
    let run = suite::run(sc, !no_check).map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    let draw = (!no_plot).then(|| pounding::figures::suite::suite_pictures(&run));
    let written = suite::write::write(out, &run, draw)?;
    if !quiet {
        print!("{}", suite::report::text(&run, &sc.title, name));
        println!();
        println!("wrote {}", list_paths(&written));
    }
    // the scenario's own warnings once; then what a record's run adds
    let mut seen: std::collections::BTreeSet<String> = sc.warnings.iter().cloned().collect();
    for w in &sc.warnings {
        eprintln!("warning: {w}");
    }
    for r in &run.records {
        for w in &r.report.warnings {
            if seen.insert(w.clone()) {
                eprintln!("warning: {} (record {})", w, r.file);
            }
        }
    }
    Ok(())
}

/// Commands of one ground motion refuse a suite of records (which `pounding run` runs).
fn refuse_suite(sc: &Scenario) -> anyhow::Result<()> {
    match &sc.suite {
        Some(s) => Err(pounding::integrate::SolveError::Suite(s.records.len()).into()),
        None => Ok(()),
    }
}

/// Reads every record file with the same options; the error names the file.
fn read_records(
    files: &[PathBuf],
    component: Option<&str>,
    units: Option<&str>,
    dt: Option<f64>,
) -> anyhow::Result<Vec<(String, pounding::model::ground_motion::Record)>> {
    let opts = pounding::output::record_summary::options(component, units, dt, None, None, None, 4)
        .map_err(anyhow::Error::msg)?;
    files
        .iter()
        .map(|f| {
            let r = pounding::model::ground_motion::Record::read(f, &opts)?;
            Ok((f.display().to_string(), r))
        })
        .collect()
}

/// Comma-separated positive numbers of an option.
fn parse_list(text: &str, option: &str) -> anyhow::Result<Vec<f64>> {
    let values: Vec<f64> = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v > 0.0)
                .ok_or_else(|| {
                    anyhow::anyhow!("{option} {text}: `{}` is not a positive number", s.trim())
                })
        })
        .collect::<anyhow::Result<_>>()?;
    Ok(values)
}

/// Two positive numbers `A,B` of an option.
fn parse_pair(text: &str, option: &str) -> anyhow::Result<(f64, f64)> {
    match parse_list(text, option)?.as_slice() {
        [a, b] => Ok((*a, *b)),
        _ => anyhow::bail!("{option} {text}: expected two numbers A,B"),
    }
}

fn list_paths(paths: &[PathBuf]) -> String {
    paths
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
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
    if !sc.defaults_applied.is_empty() {
        println!(
            "  defaults used (not in the file): {}",
            sc.defaults_applied.join(", ")
        );
    }
    println!();
    let [a, b] = &r.structures;
    // columns as wide as the longer name (at least 16)
    let w = 2 + a.name.chars().count().max(b.name.chars().count()).max(14);
    println!("  {:<34}{:>w$}{:>w$}", "", a.name, b.name);
    println!(
        "  {:<34}{:>w$.4}{:>w$.4}",
        "first-mode period [s]", a.periods[0], b.periods[0]
    );
    println!(
        "  {:<34}{:>w$.4}{:>w$.4}",
        "peak w(h) without pounding [m]",
        a.peak_displacement_no_contact,
        b.peak_displacement_no_contact
    );
    println!(
        "  {:<34}{:>w$.4}{:>w$.4}",
        "peak w(h) with pounding [m]", a.peak_displacement, b.peak_displacement
    );
    println!(
        "  {:<34}{:>+w$.1}{:>+w$.1}",
        "change [%]", a.change_percent, b.change_percent
    );
    if !a.floors.is_empty()
        && (sc.structures[0].floor_heights().is_some()
            || sc.structures[1].floor_heights().is_some())
    {
        let peak = |s: &pounding::analysis::simulate::StructureReport,
                    f: fn(&pounding::analysis::simulate::FloorReport) -> f64| {
            s.floors.iter().map(f).fold(0.0, f64::max)
        };
        println!(
            "  {:<34}{:>w$.3}{:>w$.3}",
            "peak floor accel. without [m/s²]",
            peak(a, |f| f.peak_acceleration_no_contact),
            peak(b, |f| f.peak_acceleration_no_contact)
        );
        println!(
            "  {:<34}{:>w$.3}{:>w$.3}",
            "peak floor accel. with [m/s²]",
            peak(a, |f| f.peak_acceleration),
            peak(b, |f| f.peak_acceleration)
        );
        // the storey drift over the storey's height, as engineers read it (and the figure shows)
        let ratio = |s: &pounding::analysis::simulate::StructureReport, k: usize| {
            s.peak_drift_ratios()
                .iter()
                .map(|r| r[k])
                .fold(0.0, f64::max)
        };
        for (label, k) in [
            ("peak drift ratio without [%]", 1),
            ("peak drift ratio with [%]", 0),
        ] {
            println!("  {label:<34}{:>w$.3}{:>w$.3}", ratio(a, k), ratio(b, k));
        }
    }
    // yielding buildings (issue 16); "–" for an elastic one
    let [sa, sb] = &r.structures;
    if sa.peak_ductility.is_some() || sb.peak_ductility.is_some() {
        let cell = |v: Option<f64>, scale: f64, digits: usize| {
            v.map_or("–".to_string(), |x| format!("{:.digits$}", x * scale))
        };
        type Pick = fn(&pounding::analysis::simulate::StructureReport) -> Option<f64>;
        let rows: [(&str, Pick, f64, usize); 6] = [
            (
                "peak ductility without",
                |s| s.peak_ductility_no_contact,
                1.0,
                2,
            ),
            ("peak ductility with", |s| s.peak_ductility, 1.0, 2),
            (
                "residual drift without [mm]",
                |s| s.max_residual_drift_no_contact,
                1e3,
                2,
            ),
            ("residual drift with [mm]", |s| s.max_residual_drift, 1e3, 2),
            (
                "hysteretic energy without [kJ]",
                |s| s.hysteretic_energy_no_contact,
                1e-3,
                1,
            ),
            (
                "hysteretic energy with [kJ]",
                |s| s.hysteretic_energy,
                1e-3,
                1,
            ),
        ];
        for (label, pick, scale, digits) in rows {
            println!(
                "  {:<34}{:>w$}{:>w$}",
                label,
                cell(pick(sa), scale, digits),
                cell(pick(sb), scale, digits)
            );
        }
    }
    println!();
    let c = &r.contact;
    if c.impacts == 0 {
        println!("  no contact: the gap never closed");
    } else {
        println!(
            "  {}, peak force {:.4e} N, max penetration {:.3} mm, {:.3} s in contact",
            impacts(c.impacts),
            c.peak_force,
            c.max_penetration * 1e3,
            c.contact_time
        );
    }
    if r.levels.len() > 1 {
        for l in &r.levels {
            println!(
                "    level h = {} m: {}, peak force {:.4e} N, {:.3} s in contact",
                l.height,
                impacts(l.impacts),
                l.peak_force,
                l.contact_time
            );
        }
    }
    if c.impacts > 0 {
        print_acceleration_pulses(r);
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
    println!("  {}", self_check_line(&r.accuracy));
}

/// "1 impact", "15 impacts".
fn impacts(n: usize) -> String {
    if n == 1 {
        "1 impact".into()
    } else {
        format!("{n} impacts")
    }
}

/// Each structure's largest absolute floor acceleration with pounding, where and when, and
/// what it is: during an impact, the impact's pulse (as long as the contact), not a design
/// value (the paper case's ~55 g at the top used to stand without a word).
fn print_acceleration_pulses(r: &Report) {
    const G: f64 = 9.80665;
    println!(
        "  largest absolute floor acceleration with pounding (inside an impact it is the \
         impact's pulse, lasting as long as the contact: not a floor acceleration to design for):"
    );
    for s in &r.structures {
        let Some(f) = s
            .floors
            .iter()
            .max_by(|a, b| a.peak_acceleration.total_cmp(&b.peak_acceleration))
        else {
            continue;
        };
        let what = match &f.peak_acceleration_impact {
            Some(p) => format!(
                "the pulse of an impact at h = {} m lasting {:.1} ms",
                p.height,
                p.duration * 1e3
            ),
            None => "not during an impact".into(),
        };
        let without = s
            .floors
            .iter()
            .map(|f| f.peak_acceleration_no_contact)
            .fold(0.0, f64::max);
        println!(
            "    {}: {:.2} m/s² ({:.2} g) at h = {} m, t = {:.3} s: {what}; {:.2} m/s² ({:.2} g) without pounding",
            s.name,
            f.peak_acceleration,
            f.peak_acceleration / G,
            f.height,
            f.peak_acceleration_time,
            without,
            without / G
        );
    }
}

/// One line saying whether the result passed its self-check.
fn self_check_line(a: &pounding::analysis::simulate::accuracy::AccuracyCheck) -> String {
    use pounding::analysis::simulate::accuracy::percent;
    let against = a.settings.map(|s| s.describe()).unwrap_or_default();
    if !a.checked {
        return "self-check: not done (--no-check): this result was NOT self-checked".into();
    }
    if let Some(f) = &a.failure {
        return format!("self-check: NOT CONVERGED — not verified: {f} (see the warning)");
    }
    let worst = a
        .quantities
        .iter()
        .find(|q| Some(q.name) == a.max_change_quantity)
        .map_or("", |q| q.label());
    let change = percent(a.max_change.unwrap_or(f64::NAN));
    if a.is_converged() {
        format!(
            "self-check: converged within {} % (largest change {change}, {worst}, against a run at {against})",
            100.0 * a.threshold
        )
    } else {
        format!(
            "self-check: NOT CONVERGED — {worst} changed by {change} against a run at {against} \
             (more than {} %); see the warning",
            100.0 * a.threshold
        )
    }
}

fn print_modes(sc: &Scenario) {
    let h = sc.main_height();
    for (i, s) in sc.structures.iter().enumerate() {
        let m = s.modal();
        let stiffness = match s {
            pounding::model::structure::Structure::Cantilever(c) => {
                format!("cantilever, EI = {:.4e} N·m²", c.bending_stiffness())
            }
            pounding::model::structure::Structure::Floors(f) => format!(
                "{} floors, {} of {} modes kept",
                f.all_modes.floor_heights().map_or(0, |h| h.len()),
                f.modes,
                f.all_modes.len()
            ),
        };
        println!(
            "structure {} \"{}\": L = {} m, M = {:.4e} kg, {stiffness}",
            i + 1,
            s.name(),
            s.length(),
            s.mass(),
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
        if let Some(heights) = s.floor_heights() {
            // the floors' mode shapes, each normalised to 1 at the top (as engineers read them)
            let shown = m.len().min(8);
            print!("  {:>10}", "floor [m]");
            for n in 0..shown {
                print!(" {:>9}", format!("φ{}", n + 1));
            }
            println!();
            for &fh in heights.iter().rev() {
                print!("  {fh:>10.3}");
                for n in 0..shown {
                    let top = m.shape(n, heights[heights.len() - 1]);
                    print!(" {:>9.4}", m.shape(n, fh) / top);
                }
                println!();
            }
            if shown < m.len() {
                println!("  (the first {shown} of {} modes)", m.len());
            }
        }
        println!();
    }
    println!(
        "φ(h) at the contact height h = {h} m, times √M (dimensionless; ±2 at a cantilever's free tip). Γ (m∫φ dx,\n\
         or φᵀM1 for floors) is the participation factor (η̈ + … = −Γ a_g); mass % = Γ²/M, the share of the mass\n\
         each mode moves."
    );
}

fn print_convergence(t: &pounding::analysis::convergence::ConvergenceTable) {
    let print_rows = |title: &str, rows: &[pounding::analysis::convergence::Row]| {
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
                    "  {:>6} {:>12} {:>10.2e} {:>8}  FAILED: {}",
                    r.modes,
                    r.method,
                    r.dt,
                    rtol,
                    first_sentence(f)
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
    // yielding buildings (issue 24): their ductility, residual drift and hysteretic energy
    let yielding: Vec<usize> = (0..2)
        .filter(|&i| {
            t.modes
                .iter()
                .chain(&t.steps)
                .any(|r| r.yielding[i].is_some())
        })
        .collect();
    let print_yielding = |rows: &[pounding::analysis::convergence::Row]| {
        if yielding.is_empty() {
            return;
        }
        println!("  the yielding buildings in the same runs:");
        print!(
            "  {:>6} {:>12} {:>10} {:>8}",
            "modes", "method", "dt [s]", "rtol"
        );
        for i in &yielding {
            let i = i + 1;
            print!(
                " {:>7} {:>9} {:>10} {:>8} {:>9} {:>9}",
                format!("μ{i}"),
                format!("res{i} [mm]"),
                format!("E_h{i} [kJ]"),
                format!("Δμ{i} [%]"),
                format!("Δres{i} [%]"),
                format!("ΔE_h{i} [%]")
            );
        }
        println!();
        for r in rows.iter().filter(|r| r.failure.is_none()) {
            let rtol = r.rtol.map_or("-".to_string(), |x| format!("{x:.0e}"));
            print!(
                "  {:>6} {:>12} {:>10.2e} {:>8}",
                r.modes, r.method, r.dt, rtol
            );
            for &i in &yielding {
                match (r.yielding[i], r.yield_change[i]) {
                    (Some(y), Some(c)) => print!(
                        " {:>7.3} {:>9.2} {:>10.1} {:>8.3} {:>9.3} {:>9.3}",
                        y.ductility,
                        1e3 * y.residual_drift,
                        1e-3 * y.hysteretic_energy,
                        100.0 * c[0],
                        100.0 * c[1],
                        100.0 * c[2]
                    ),
                    _ => print!(
                        " {:>7} {:>9} {:>10} {:>8} {:>9} {:>9}",
                        "-", "-", "-", "-", "-", "-"
                    ),
                }
            }
            println!();
        }
    };
    print_rows("modes (change vs the most modes):", &t.modes);
    print_yielding(&t.modes);
    print_rows("step / tolerance (change vs the finest):", &t.steps);
    print_yielding(&t.steps);
    if !yielding.is_empty() {
        println!();
        println!(
            "  μ: peak ductility; res: largest |residual drift|, its change in units of the larger \
             of it and the smallest yield drift; E_h: hysteretic energy, its change in units of the \
             larger of it and 0.1 % of the input energy"
        );
    }
    println!();
    if t.converged {
        println!(
            "  recommendation (tolerance {} %): {}",
            100.0 * t.tolerance,
            t.recommendation
        );
    } else {
        println!(
            "  *** NOT CONVERGED within {} %: nothing is recommended ***",
            100.0 * t.tolerance
        );
    }
    for n in &t.notes {
        println!("    {n}");
    }
}

/// A failure message up to its first sentence (the table has one line per run).
fn first_sentence(text: &str) -> String {
    match text.find(". ") {
        Some(i) => format!("{} …", &text[..=i]),
        None => text.to_string(),
    }
}

/// A length in mm with 3 decimals (1 µm: enough to check a code's value by hand).
fn mm(x: f64) -> String {
    format!("{:.3}", 1e3 * x)
}

fn print_separation(r: &pounding::analysis::gap_report::GapReport) {
    println!("{}", r.title);
    let exact = r.levels.iter().any(|l| l.exact.is_some());
    let source = match (r.spectrum, exact) {
        (Some(s), true) => format!(
            "rules from the design spectrum {s} (--spectrum); exact separation from the scenario's time history"
        ),
        (Some(s), false) => format!("design spectrum {s}: no time history, so no exact separation"),
        (None, _) => "time history of the scenario (the run without pounding)".to_string(),
    };
    println!("  ground motion: {source}");
    println!("  the rules take, at each level, {}", r.peaks_note);
    println!(
        "  T1 = {:.4} s, T2 = {:.4} s, ζ1 = {}, ζ2 = {}, ρ12 (CQC, first modes) = {:.5}; lengths in mm",
        r.periods[0], r.periods[1], r.damping_ratios[0], r.damping_ratios[1], r.rho
    );
    for w in &r.warnings {
        println!("  warning: {w}");
    }
    // top level first, as a building is read
    let mut order: Vec<&pounding::analysis::level_checks::LevelCheck> = r.levels.iter().collect();
    order.sort_by(|a, b| b.height.total_cmp(&a.height));
    for l in &order {
        println!();
        let floors = if l.floors_coincide {
            "; a floor of both structures"
        } else {
            ""
        };
        println!(
            "  contact level h = {} m: gap {} mm{floors}; the rules take w1 = {} mm, w2 = {} mm",
            l.height,
            mm(l.gap),
            mm(l.peaks[0]),
            mm(l.peaks[1])
        );
        if let Some(s) = &l.spectral {
            let (a, b) = (&s.structure1, &s.structure2);
            println!(
                "    spectral peaks [mm]: structure 1 SRSS {}, CQC {} ({} modes); structure 2 SRSS {}, CQC {} ({} modes)",
                mm(a.srss),
                mm(a.cqc),
                a.modes.len(),
                mm(b.srss),
                mm(b.cqc),
                b.modes.len()
            );
        }
        let gap_col = format!("gap {} mm", mm(l.gap));
        let vs_col = if l.exact.is_some() { "vs exact" } else { "" };
        let head = format!(
            "    {:<40}{:<42}{:>14}{:>16}{:>12}",
            "rule", "clause", "required [mm]", gap_col, vs_col
        );
        println!("{}", head.trim_end());
        for row in &l.rules {
            let ok = if row.sufficient {
                "suffices"
            } else {
                "TOO SMALL"
            };
            let vs = row
                .vs_exact_percent
                .map_or(String::new(), |p| format!("{p:+.1} %"));
            let line = format!(
                "    {:<40}{:<42}{:>14}{:>16}{:>12}",
                row.label,
                row.clause.as_deref().unwrap_or(""),
                mm(row.required),
                ok,
                vs
            );
            println!("{}", line.trim_end());
        }
        for c in &l.codes {
            let reduced = c.reduction.map_or(String::new(), |x| format!("; {x}"));
            println!(
                "      {}: {}; displacements [{}, {}] mm, terms [{}, {}] mm{reduced}",
                c.key,
                c.conversion,
                mm(c.displacements[0]),
                mm(c.displacements[1]),
                mm(c.terms[0]),
                mm(c.terms[1])
            );
        }
    }
    println!();
    let v = &r.verdict;
    if r.levels.len() > 1 {
        println!("  verdict: each rule at its governing level (the smallest gap − required):");
        let head = format!(
            "    {:<40}{:>10}{:>12}{:>16}{:>14}",
            "rule", "level [m]", "gap [mm]", "required [mm]", "margin [mm]"
        );
        println!("{head}");
        for g in &v.rules {
            let ok = if g.sufficient {
                "suffices"
            } else {
                "TOO SMALL"
            };
            println!(
                "    {:<40}{:>10}{:>12}{:>16}{:>14}  {ok}",
                g.label,
                g.height,
                mm(g.gap),
                mm(g.required),
                mm(g.margin)
            );
        }
    }
    let n = v.rules.len();
    let summary = match v.insufficient {
        0 => format!("  the gap suffices at every level by all {n} rules"),
        k => format!("  the gap is TOO SMALL by {k} of {n} rules"),
    };
    match &v.governing {
        Some(g) => println!(
            "{summary}; the most demanding: {} at h = {} m ({} mm required, gap {} mm)",
            g.label,
            g.height,
            mm(g.required),
            mm(g.gap)
        ),
        None => println!("{summary}"),
    }
    if let Some(floors) = &r.spectral_floors {
        for (i, f) in floors.iter().enumerate() {
            if f.is_empty() {
                continue;
            }
            println!(
                "  spectral peak displacement at every floor of structure {} [mm]:",
                i + 1
            );
            println!("    {:>10} {:>12} {:>12}", "height [m]", "SRSS", "CQC");
            for x in f.iter().rev() {
                println!(
                    "    {:>10.3} {:>12} {:>12}",
                    x.height,
                    mm(x.srss),
                    mm(x.cqc)
                );
            }
        }
    }
    if exact {
        println!(
            "  vs exact: 100 (rule − exact)/exact at the same level; a negative value is a rule below the exact separation (unsafe)"
        );
    }
}

/// The switches of `pounding sweep`.
struct SweepFlags {
    no_plot: bool,
    case: Option<usize>,
    check: bool,
    quiet: bool,
    max_output_size: u64,
}

fn run_sweep(
    path: &Path,
    out: Option<PathBuf>,
    jobs: Option<usize>,
    shard: Option<pounding::study::sweep::Shard>,
    flags: SweepFlags,
) -> anyhow::Result<()> {
    use pounding::study::sweep::{Shard, Sweep, run};
    let SweepFlags {
        no_plot,
        case,
        check,
        quiet,
        max_output_size,
    } = flags;
    let sweep = Sweep::from_file(path)?;
    if let Some(c) = case {
        if c >= sweep.len() {
            anyhow::bail!(
                "--case {c}: the sweep has {} cases, numbered 0 to {}",
                sweep.len(),
                sweep.len() - 1
            );
        }
        let text = sweep
            .case_toml(c)
            .map_err(|e| anyhow::anyhow!("case {c}: {e}"))?;
        print!(
            "# case {c} of {}: {}\n{text}",
            path.display(),
            sweep.label(c)
        );
        return Ok(());
    }
    let out = out.unwrap_or_else(|| {
        Path::new("out").join(path.file_stem().unwrap_or(std::ffi::OsStr::new("sweep")))
    });
    let jobs = jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let shard = shard.unwrap_or(Shard::ALL);
    let in_shard = (0..sweep.len()).filter(|&c| shard.contains(c)).count();
    pounding::output::budget::check_sweep(in_shard as u64, sweep.axes.len(), max_output_size)?;
    let opts = run::RunOptions {
        out_dir: out.clone(),
        jobs,
        shard,
        check,
    };
    let o = if quiet {
        run::run(&sweep, &opts, &mut run::Silent)?
    } else {
        run::run(&sweep, &opts, &mut run::StderrProgress::new())?
    };
    if o.dropped > 0 {
        eprintln!(
            "warning: {} damaged line(s) in the journal were dropped (a kill during a write); their cases were recomputed",
            o.dropped
        );
    }
    if !quiet {
        let part = if shard.is_all() {
            String::new()
        } else {
            format!(" (part {shard} of the grid's {} cases)", sweep.len())
        };
        println!(
            "{}: {} cases{part}: {} computed in {:.1} s with {jobs} thread(s){}, {} resumed, {} failed",
            path.display(),
            o.cases,
            o.computed,
            o.seconds,
            if o.computed > 0 {
                format!(
                    " ({:.2} ms per case per thread)",
                    o.seconds * 1e3 * jobs as f64 / o.computed as f64
                )
            } else {
                String::new()
            },
            o.resumed,
            o.failed
        );
        println!("wrote {}", o.results.display());
        if !sweep.code_columns().is_empty() {
            println!(
                "how often each rule is below the exact separation: pounding rules {}",
                o.results.display()
            );
        }
        let c = &o.check;
        let ok = o.cases - o.failed;
        if ok == 0 {
            // nothing ran to the end: nothing to check
        } else if c.unchecked == ok {
            println!(
                "self-check: not done (--no-check): the cases were NOT self-checked (column converged = unchecked)"
            );
        } else if c.converged == ok {
            println!(
                "self-check: every case converged within 1 % against a 100× tighter run (column check_max_change)"
            );
        } else {
            println!(
                "self-check: {} case(s) converged within 1 %, {} NOT converged, {} not checked (columns converged, check_max_change)",
                c.converged, c.not_converged, c.unchecked
            );
        }
    }
    if let Some((c, change)) = &o.check.first_not_converged {
        let change = match change.parse::<f64>() {
            Ok(x) if x > pounding::analysis::simulate::accuracy::CHECK_THRESHOLD => {
                format!(
                    "largest change {}",
                    pounding::analysis::simulate::accuracy::percent(x)
                )
            }
            _ => "not verified: the check run failed or changed nothing".into(),
        };
        eprintln!(
            "warning: self-check: {} of {} cases are NOT converged within 1 % (column converged = false); the first, case {c} ({}): {change}\n\
             (see it with: pounding sweep {} --case {c} > case.toml && pounding run case.toml)",
            o.check.not_converged,
            o.cases - o.failed,
            sweep.label(*c),
            path.display()
        );
    }
    if let Some((c, w)) = &o.first_warning {
        eprintln!(
            "warning: {} of the {} cases computed now ran with warnings; the first, case {c} ({}): {w}\n\
             (see it with: pounding sweep {} --case {c} > case.toml && pounding run case.toml)",
            o.warned,
            o.computed,
            sweep.label(*c),
            path.display()
        );
    }
    if let Some((c, status)) = &o.first_failure {
        eprintln!(
            "warning: {} of {} cases failed; the first, case {c} ({}): {status}",
            o.failed,
            o.cases,
            sweep.label(*c)
        );
    }
    if o.failed == o.cases && o.cases > 0 {
        anyhow::bail!(
            "every case failed (see the status column of {})",
            o.results.display()
        );
    }
    if !no_plot && shard.is_all() {
        let table = pounding::study::sweep::results::Table::read(&o.results)?;
        let dir = out.join("plots");
        // the pictures name the base scenario as what the keys not swept were held at
        let base = sweep
            .scenario_path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned());
        match pounding::figures::sweep::plot_table_of(
            &table,
            &Default::default(),
            &dir,
            base.as_deref(),
        ) {
            Ok(files) => {
                if !quiet {
                    println!(
                        "wrote {} pictures (PNG and SVG) in {}",
                        pounding::figures::sweep::count_pictures(&files),
                        dir.display()
                    );
                }
            }
            Err(e) => eprintln!("warning: no pictures: {e}"),
        }
    } else if !shard.is_all() && !quiet {
        println!(
            "when every part is done: pounding merge {}/results.csv {} (then pounding plot)",
            out.display(),
            out.display()
        );
    }
    Ok(())
}

fn print_laws(speed: f64) -> anyhow::Result<()> {
    use pounding::analysis::restitution::{TargetLaw, isolated_impact};
    let targets = [0.3, 0.4, 0.5, 0.6, 0.65, 0.7, 0.8, 0.9];
    print!("  {:<36}", "law \\ target e");
    for e in targets {
        print!("{e:>7}");
    }
    println!();
    for law in TargetLaw::ALL {
        print!("  {:<36}", law.label());
        for e in targets {
            let out = isolated_impact(&law.law(e, 2.808e10, 1.0e9), 1.0e6, 3.0e6, speed)?;
            print!("{:>7.3}", out.restitution);
        }
        println!();
    }
    println!();
    println!(
        "  achieved e = separation speed / approach speed ({speed} m/s) of an isolated impact of two bodies, through the solver"
    );
    Ok(())
}
