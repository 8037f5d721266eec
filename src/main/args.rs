//! The command line's arguments (clap derive): one variant of [`Command`] per subcommand, its
//! doc comment the subcommand's help, its arguments a struct `…Args`; and the parsers of
//! option values. Kept apart from main.rs so that main.rs stays dispatch.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

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
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// Print only errors, warnings and what the command exists to print (the tables of
    /// `modes`, `laws`, `separation`, `convergence`): no progress, no run summary, no list of
    /// files written. Works before or after the command name.
    #[arg(short, long, global = true)]
    pub quiet: bool,
}

#[derive(Subcommand)]
pub enum Command {
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
    Run(RunArgs),
    /// List each structure's modes: period, frequency, damping ratio, φ(h) and participation.
    Modes(ModesArgs),
    /// Achieved coefficient of restitution of every contact law that takes a target e, measured
    /// on an isolated two-body impact through the solver (e = 0.3 … 0.9).
    ///
    /// Several laws are derived for idealised impacts and miss their nominal e; pick a law knowing
    /// what it does. The result does not depend on the stiffness, masses or approach speed for
    /// these laws (they are scale-free); defaults are the paper's k_h and 0.5 m/s.
    Laws(LawsArgs),
    /// Convergence study: the run with pounding for 1, 2, 3, 5, 10, 20, 50 modes and for a ladder
    /// of steps (dt × 4 … ⅛; rtol 1e-6 … 1e-12 for `adaptive`, 1e-4 … 1e-8 and 1e-10 for `exact-modal`), each with its change relative to
    /// the finest, and a recommendation (fewest modes, largest step within the tolerance) that
    /// `pounding run` accepts — or "NOT CONVERGED" and what to try, when even the two finest runs
    /// of a ladder differ by more than the tolerance.
    Convergence(ConvergenceArgs),
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
    Separation(SeparationArgs),
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
    Sweep(SweepArgs),
    /// Join the parts of a sharded sweep into one results table, checking that every case is
    /// there exactly once.
    Merge(MergeArgs),
    /// How often each separation rule is unsafe over a sweep: from a results table with the
    /// exact time-history separation (sep_time_history) and the rules (sep_abs, sep_srss,
    /// sep_ddc, and sep_asce7 … when the base scenario had a [separation] table), the fraction
    /// of cases where each rule is below the exact value, its worst shortfall and its excess
    /// when safe; draws DIR/rules.png/.svg (rule/exact against one axis: smallest, median,
    /// largest over the other axes).
    Rules(RulesArgs),
    /// Draw a sweep's pictures from its results table: heatmaps over two axes, line plots
    /// over one.
    ///
    /// Without options: heatmaps of the change % of each structure, the peak force, the
    /// number of impacts and the required separation over the first two numeric axes (one
    /// picture per value of the other axes), and line plots over the first axis.
    Plot(PlotArgs),
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
    /// A row of buildings is compared per structure and per adjacent pair.
    Crosscheck(CrosscheckArgs),
    /// What the program reads from a ground-motion record file: layout (detected from the
    /// content), component, units in the file, time step, number of points, PGA (m/s² and g)
    /// and its time, the peak the header states; `--csv` writes the series in SI (t, a).
    ///
    /// Layouts: PEER NGA .AT2, COSMOS V1/V2, CSMIP/DMG V1/V2, K-NET/KiK-net ASCII, ESM ASCII,
    /// one or two columns. Uncorrected records (V1) are refused unless processed (--baseline,
    /// --highpass, --lowpass).
    Record(RecordArgs),
    /// 5 %-damped pseudo-acceleration response spectra of records (exact for an acceleration
    /// linear between samples, Nigam–Jennings): a table of PSA in g per period and record,
    /// their mean, and the figure DIR/spectrum.png/.svg (log period axis).
    ///
    /// With --target the design spectrum is drawn and tabulated beside them, and with --t1
    /// the period range 0.2·T1 … 2·T1 is shaded. --json gives per record `periods` (s), `psa`
    /// (m/s²), `psa_g`, `sd` (m), `psv` (m/s), `sa_abs` (m/s²).
    Spectrum(SpectrumArgs),
    /// Scale a suite of records to a target spectrum by a code's rule: one factor per record so
    /// that the suite's mean 5 %-damped spectrum is at least 90 % of the target over the code's
    /// period range (0.2·T1 … 2·T1) — ASCE 7-16 §16.2.3 (≥ 11 records, target MCE_R = 1.5 × an
    /// ASCE 7 design spectrum) or EN 1998-1 §3.2.3.1.2 (≥ 3 records, and mean PGA ≥ a_g·S).
    ///
    /// Prints each record's factor, the lowest mean-to-target ratio and where, and what governs;
    /// refuses, with the reason, a suite that cannot meet the rule. Draws DIR/scaling.png/.svg.
    ///
    /// With --sa T,SA instead (no --target, --rule, --t1): each record on its own scaled to a
    /// pseudo-acceleration SA (g) at the period T (s), the factor a scenario's
    /// `scale_to_sa = { period = T, sa = SA }` applies, with the PSA and PGA before and after.
    Scale(ScaleArgs),
    /// How likely pounding is: a fragility study (multi-stripe analysis). Every record of the
    /// study's suite is scaled to each intensity level (stripe) and run with and without
    /// contact; per limit state the fraction exceeding at each stripe and a lognormal fit
    /// (maximum likelihood, bootstrap intervals over records); P(pounding | IM, gap) for every
    /// gap from the runs without contact and the gap for a target probability.
    ///
    /// With `ida = { … }` instead of stripes: an incremental dynamic analysis (each record
    /// scaled up until every limit state is exceeded, its capacity bracketed by hunt and fill)
    /// and the lognormal of the records' capacities.
    ///
    /// Writes into DIR: fragility.csv, p_pounding.csv, runs.csv (IDA: ida.csv and
    /// capacities.csv), the figures fragility.png/.svg, p-pounding.png/.svg (IDA: ida.png/.svg),
    /// and fit.json last. Every run is journaled in DIR/journal.csv as it finishes: a study
    /// stopped midway resumes where it stopped when run again. See the README, "Fragility".
    Fragility(FragilityArgs),
}

/// `pounding fragility`.
#[derive(Args)]
pub struct FragilityArgs {
    /// The study file (TOML).
    pub study: PathBuf,
    /// Output directory (created if missing) [default: out/<study file name>].
    #[arg(short, long)]
    pub out: Option<PathBuf>,
    /// Worker threads [default: the number of CPUs].
    #[arg(short, long)]
    pub jobs: Option<usize>,
    /// Do not draw the figures.
    #[arg(long)]
    pub no_plot: bool,
    /// Run only part K of N of the study (task i — a run of records × stripes, or a record's
    /// whole IDA — is in part i mod N + 1); the part journals its runs in
    /// DIR/journal-shard-K-of-N.csv; join the parts with --merge.
    #[arg(long, value_name = "K/N", conflicts_with = "merge")]
    pub shard: Option<pounding::study::sweep::Shard>,
    /// Join the parts of a sharded study (their journal-shard-K-of-N.csv files, or the
    /// directories holding them) and write the study's files into --out.
    #[arg(long, value_name = "PART", num_args = 1..)]
    pub merge: Vec<PathBuf>,
}

/// Targets of `pounding export`.
#[derive(Subcommand)]
pub enum ExportTarget {
    /// Write a self-contained OpenSeesPy script of the scenario: `python3 model.py` runs it
    /// with and without contact and prints JSON with the headline numbers of summary.json.
    ///
    /// Cantilevers become N elasticBeamColumn elements (consistent mass), shear buildings
    /// floor masses with storey springs, each contact level a zeroLength element with the
    /// law's material (hertz, linear, jankowski: exact; kelvin, hertzdamp: approximate;
    /// stereomechanical: refused). A row of buildings gives one script with every structure
    /// and every adjacent pair's contact, printing per structure and per pair. See the
    /// README, "Checking in OpenSees".
    Opensees(OpenseesArgs),
}

// `pounding run` (clap takes its help from the variant `Run`'s doc comment)
#[derive(Args)]
pub struct RunArgs {
    /// Scenario file (TOML). Without it, the bundled default runs (examples/default.toml:
    /// a 4- and an 8-storey frame under a scaled earthquake record).
    pub scenario: Option<PathBuf>,
    /// Output directory (created if missing).
    #[arg(short, long, default_value = "out")]
    pub out: PathBuf,
    /// Draw no pictures (history, envelopes, hysteresis); removes those an earlier run
    /// left in DIR.
    #[arg(long)]
    pub no_plot: bool,
    /// Skip the self-check (the second run at a 100× tighter tolerance); summary.json
    /// then says `"accuracy": {"checked": false, …}`.
    #[arg(long)]
    pub no_check: bool,
    /// Largest history.csv the run may write (estimated before the run from
    /// solver.duration / solver.output_interval), e.g. 5GB, 500MB, 2e9; a run above it is
    /// refused with the estimate and the keys that change it.
    #[arg(long, value_name = "SIZE", default_value = "1GB", value_parser = parse_size)]
    pub max_output_size: u64,
}

// `pounding modes` (clap takes its help from the variant `Modes`'s doc comment)
#[derive(Args)]
pub struct ModesArgs {
    /// Scenario file (TOML); the bundled default if omitted.
    pub scenario: Option<PathBuf>,
}

// `pounding laws` (clap takes its help from the variant `Laws`'s doc comment)
#[derive(Args)]
pub struct LawsArgs {
    /// Approach speed, m/s.
    #[arg(long, default_value_t = 0.5)]
    pub speed: f64,
}

// `pounding convergence` (clap takes its help from the variant `Convergence`'s doc comment)
#[derive(Args)]
pub struct ConvergenceArgs {
    /// Scenario file (TOML); the bundled default if omitted.
    pub scenario: Option<PathBuf>,
    /// Largest acceptable relative change of the peaks and peak force vs the finest run.
    #[arg(long, default_value_t = 0.01)]
    pub tolerance: f64,
}

// `pounding separation` (clap takes its help from the variant `Separation`'s doc comment)
#[derive(Args)]
pub struct SeparationArgs {
    /// Scenario file (TOML); the bundled default if omitted.
    pub scenario: Option<PathBuf>,
    /// Only these codes (comma-separated or repeated): asce7, is1893, nbcc, gb50011, ntc, ec8
    /// [default: every code whose factors are in the scenario].
    #[arg(long, value_delimiter = ',')]
    pub code: Vec<String>,
    /// Use this design spectrum for the rules instead of the time history (which still
    /// gives the exact separation): asce7:sds=1.0,sd1=0.6,tl=8 |
    /// ec8:ag=0.25g,ground_type=C,type=1 (a_g with its unit: 0.25g or 2.45m/s2) |
    /// table:FILE[,units=g] (T in s, S_a in m/s² unless units=g).
    #[arg(long, value_name = "SPEC")]
    pub spectrum: Option<String>,
    /// Write the report as JSON on stdout instead of the tables (SI units, full precision;
    /// keys in the README, "One report").
    #[arg(long)]
    pub json: bool,
}

// `pounding sweep` (clap takes its help from the variant `Sweep`'s doc comment)
#[derive(Args)]
pub struct SweepArgs {
    /// The sweep file (TOML).
    pub sweep: PathBuf,
    /// Output directory (created if missing) [default: out/<sweep file name>].
    #[arg(short, long)]
    pub out: Option<PathBuf>,
    /// Worker threads [default: the number of CPUs].
    #[arg(short, long)]
    pub jobs: Option<usize>,
    /// Run only part K of N of the grid (e.g. 3/8; case i is in part i mod N + 1), for
    /// spreading a study over machines, e.g. a Slurm array job with
    /// --shard $((SLURM_ARRAY_TASK_ID+1))/$SLURM_ARRAY_TASK_COUNT. Each part writes
    /// DIR/results-shard-K-of-N.csv; join them with `pounding merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<pounding::study::sweep::Shard>,
    /// Do not draw the pictures.
    #[arg(long)]
    pub no_plot: bool,
    /// Print the scenario of case N (TOML) and exit, e.g. to rerun it with `pounding run`.
    #[arg(long, value_name = "N")]
    pub case: Option<usize>,
    /// Skip the cases' self-check (faster); the rows then say converged = unchecked.
    #[arg(long)]
    pub no_check: bool,
    /// Largest output (results.csv and its journal, estimated from the number of cases)
    /// the sweep may write, e.g. 5GB; a sweep above it is refused with the estimate.
    #[arg(long, value_name = "SIZE", default_value = "1GB", value_parser = parse_size)]
    pub max_output_size: u64,
}

// `pounding merge` (clap takes its help from the variant `Merge`'s doc comment)
#[derive(Args)]
pub struct MergeArgs {
    /// The merged table to write.
    pub out: PathBuf,
    /// The parts (results-shard-K-of-N.csv files), or directories holding them.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
}

// `pounding rules` (clap takes its help from the variant `Rules`'s doc comment)
#[derive(Args)]
pub struct RulesArgs {
    /// The results table (results.csv of a sweep, or a merged table).
    pub results: PathBuf,
    /// Axis along x of the figure [default: the first axis].
    #[arg(long)]
    pub x: Option<String>,
    /// Output directory of the figure [default: plots/ beside the results table].
    #[arg(short, long)]
    pub out: Option<PathBuf>,
    /// Do not draw the figure.
    #[arg(long)]
    pub no_plot: bool,
}

// `pounding plot` (clap takes its help from the variant `Plot`'s doc comment)
#[derive(Args)]
pub struct PlotArgs {
    /// The results table (results.csv of a sweep, or a merged table).
    pub results: PathBuf,
    /// Axis along x (an axis key, e.g. period_ratio).
    #[arg(long)]
    pub x: Option<String>,
    /// Axis along y: draws heatmaps (without it, with --x: line plots over x).
    #[arg(long, requires = "x")]
    pub y: Option<String>,
    /// Field to draw: change_percent_1, change_percent_2, peak_force, impacts,
    /// contact_time, sep_time_history, sep_abs, sep_srss, sep_ddc, peak_displacement_1, …
    #[arg(long)]
    pub field: Option<String>,
    /// Output directory [default: plots/ beside the results table].
    #[arg(short, long)]
    pub out: Option<PathBuf>,
}

// `pounding crosscheck` (clap takes its help from the variant `Crosscheck`'s doc comment)
#[derive(Args)]
pub struct CrosscheckArgs {
    /// Scenario file (TOML); the bundled default if omitted.
    pub scenario: Option<PathBuf>,
    /// Beam elements per cantilever in OpenSees.
    #[arg(long, default_value_t = pounding::opensees::DEFAULT_ELEMENTS)]
    pub elements: usize,
    /// OpenSees' analysis step, s.
    #[arg(long, default_value_t = pounding::opensees::DEFAULT_DT)]
    pub dt: f64,
    /// Modes per structure in the program (default: the scenario's); an rk4 step that is
    /// then unstable switches the program to `adaptive`.
    #[arg(long)]
    pub modes: Option<usize>,
    /// Simulated time, s, for both (default: the scenario's).
    #[arg(long)]
    pub duration: Option<f64>,
    /// Keep the script (model.py), OpenSees' results (opensees.json) and log in DIR.
    #[arg(long, value_name = "DIR")]
    pub keep: Option<PathBuf>,
}

// `pounding record` (clap takes its help from the variant `Record`'s doc comment)
#[derive(Args)]
pub struct RecordArgs {
    /// The record file.
    pub file: PathBuf,
    /// The component of a multi-channel file: its number (1, 2, …) or name ("90", "EW").
    #[arg(long)]
    pub component: Option<String>,
    /// Print JSON (keys format, component, dt, points, pga, pga_time, …).
    #[arg(long)]
    pub json: bool,
    /// Write the series to OUT as CSV: t (s), a (m/s²).
    #[arg(long, value_name = "OUT")]
    pub csv: Option<PathBuf>,
    /// Units of the values, overriding the file's: g, cm/s2 (gal), m/s2.
    #[arg(long)]
    pub units: Option<String>,
    /// Time step, s (one-column files; resampling of digitised film records).
    #[arg(long)]
    pub dt: Option<f64>,
    /// Baseline correction: linear or polynomial.
    #[arg(long, value_parser = ["linear", "polynomial"])]
    pub baseline: Option<String>,
    /// High-pass corner, Hz (zero-phase Butterworth).
    #[arg(long, value_name = "HZ")]
    pub highpass: Option<f64>,
    /// Low-pass corner, Hz (zero-phase Butterworth).
    #[arg(long, value_name = "HZ")]
    pub lowpass: Option<f64>,
    /// Butterworth order.
    #[arg(long, default_value_t = pounding::model::ground_motion::processing::DEFAULT_ORDER)]
    pub order: usize,
}

// `pounding spectrum` (clap takes its help from the variant `Spectrum`'s doc comment)
#[derive(Args)]
pub struct SpectrumArgs {
    /// Record files (any layout `pounding record` reads).
    #[arg(required = true)]
    pub records: Vec<PathBuf>,
    /// The component of multi-channel files: a number (1, 2, …) or a name ("90", "EW"),
    /// the same for every file.
    #[arg(long)]
    pub component: Option<String>,
    /// Damping ratio of the oscillators, in [0, 1).
    #[arg(long, default_value_t = pounding::analysis::record_spectrum::DEFAULT_DAMPING)]
    pub damping: f64,
    /// Periods, s: a list (0,0.1,0.2,0.5,1) or FROM:TO:N (N periods equally spaced in log
    /// T). Default: 0 (the PGA) and 0.01 to 10 s, 20 a decade.
    #[arg(long)]
    pub periods: Option<String>,
    /// A design spectrum to show beside the records, as `pounding separation --spectrum`:
    /// asce7:sds=…,sd1=…,tl=… | ec8:ag=…,ground_type=…,type=… | table:FILE.
    #[arg(long, value_name = "SPEC")]
    pub target: Option<String>,
    /// First-mode periods of the structures, s (one or two): shade 0.2·min … 2·max.
    #[arg(long, value_name = "T1[,T2]")]
    pub t1: Option<String>,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Directory for the figure (created if missing).
    #[arg(short, long, default_value = "out")]
    pub out: PathBuf,
    /// Do not draw the figure.
    #[arg(long)]
    pub no_plot: bool,
    /// Units of the values, overriding the files': g, cm/s2 (gal), m/s2.
    #[arg(long)]
    pub units: Option<String>,
    /// Time step, s (one-column files).
    #[arg(long)]
    pub dt: Option<f64>,
}

// `pounding scale` (clap takes its help from the variant `Scale`'s doc comment)
#[derive(Args)]
pub struct ScaleArgs {
    /// Record files.
    #[arg(required = true)]
    pub records: Vec<PathBuf>,
    /// The target spectrum: asce7:sds=…,sd1=…,tl=… | ec8:ag=…,ground_type=…,type=… |
    /// table:FILE (as `pounding separation --spectrum`).
    #[arg(long, value_name = "SPEC", required_unless_present = "sa")]
    pub target: Option<String>,
    /// The code's rule.
    #[arg(long, value_parser = ["asce7", "ec8"], required_unless_present = "sa")]
    pub rule: Option<String>,
    /// First-mode periods of the structures, s (one or two).
    #[arg(long, value_name = "T1[,T2]", required_unless_present = "sa")]
    pub t1: Option<String>,
    /// Scale each record on its own to a pseudo-acceleration SA_G (g) at PERIOD (s), instead
    /// of a suite to a spectrum.
    #[arg(long, value_name = "PERIOD,SA_G", conflicts_with_all = ["target", "rule", "t1", "range", "factor_limits", "target_scale"])]
    pub sa: Option<String>,
    /// With --sa: the oscillator's damping ratio, in [0, 1).
    #[arg(long, requires = "sa", default_value_t = pounding::analysis::record_spectrum::DEFAULT_DAMPING)]
    pub damping: f64,
    /// A wider period range than the code's, s (e.g. to include the modes of 90 % mass
    /// participation, ASCE 7-16 §16.2.3.1).
    #[arg(long, value_name = "LO,HI")]
    pub range: Option<String>,
    /// The mean-to-target ratio to reach (at least the code's 0.9).
    #[arg(long, default_value_t = 0.9)]
    pub ratio: f64,
    /// Smallest and largest factor allowed per record.
    #[arg(long, value_name = "MIN,MAX")]
    pub factor_limits: Option<String>,
    /// Multiply the target by this instead of the rule's factor (1.5 for an ASCE 7 design
    /// spectrum under asce7, else 1).
    #[arg(long)]
    pub target_scale: Option<f64>,
    /// The component of multi-channel files, the same for every file.
    #[arg(long)]
    pub component: Option<String>,
    /// Print JSON (factors, grid, target, mean, ratios) instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Directory for the figure (created if missing).
    #[arg(short, long, default_value = "out")]
    pub out: PathBuf,
    /// Do not draw the figure.
    #[arg(long)]
    pub no_plot: bool,
    /// Units of the values, overriding the files': g, cm/s2 (gal), m/s2.
    #[arg(long)]
    pub units: Option<String>,
    /// Time step, s (one-column files).
    #[arg(long)]
    pub dt: Option<f64>,
}

// `pounding opensees` (clap takes its help from the variant `Opensees`'s doc comment)
#[derive(Args)]
pub struct OpenseesArgs {
    /// Scenario file (TOML); the bundled default if omitted.
    pub scenario: Option<PathBuf>,
    /// Write the script here (default: standard output).
    #[arg(short, long)]
    pub out: Option<PathBuf>,
    /// Beam elements per cantilever.
    #[arg(long, default_value_t = pounding::opensees::DEFAULT_ELEMENTS)]
    pub elements: usize,
    /// OpenSees' analysis step, s.
    #[arg(long, default_value_t = pounding::opensees::DEFAULT_DT)]
    pub dt: f64,
    /// Run only the case with contact or only the one without.
    #[arg(long, value_parser = ["contact", "free"])]
    pub only: Option<String>,
    /// Simulated time, s (default: the scenario's).
    #[arg(long)]
    pub duration: Option<f64>,
}

/// `--max-output-size` values.
fn parse_size(text: &str) -> Result<u64, String> {
    pounding::output::budget::parse_size(text)
}

/// Comma-separated positive numbers of an option.
pub fn parse_list(text: &str, option: &str) -> anyhow::Result<Vec<f64>> {
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
pub fn parse_pair(text: &str, option: &str) -> anyhow::Result<(f64, f64)> {
    match parse_list(text, option)?.as_slice() {
        [a, b] => Ok((*a, *b)),
        _ => anyhow::bail!("{option} {text}: expected two numbers A,B"),
    }
}
