//! Time integration of the assembled [`System`] (docs/model.md §2.9).
//!
//! An integrator advances the modal state and reports every step to an [`Observer`]; it knows
//! nothing of files or of what is kept. Alongside the state it integrates, with the same order,
//! the energy flows (input work, structural damping, work into the contacts) and each level's
//! impulse, so that energy balance and impulses are exact to the method's accuracy.
//!
//! Methods ([`Method`]): `rk4` (the paper's fixed step, module `rk4`), `exact-modal` (exact
//! modal propagation, closed-form free flight, contact by the embedded Lobatto collocation pair
//! of module `collocation`, module `exact_modal`; the default) and `adaptive` (exponential
//! Lobatto collocation with step doubling and event location, module `adaptive`: kept as an
//! independent second implementation, the tests' converged reference); the last two share the
//! exact propagator and particular solutions of [`linear`].
//!
//! Also on every `Observer`: `exact-modal` observes a contact step whose force peaks inside it
//! at its interior nodes too (dense output), so observations are not always step ends.

mod adaptive;
mod collocation;
mod exact_modal;
mod hysteretic;
pub mod linear;
mod plan;
mod poly_tally;
mod progress;
mod rk4;

pub use exact_modal::SUBSTEP_ALPHA;
pub use progress::StepFailure;
pub use rk4::{rk4_max_stable_dt, rk4_stability_limit};

pub(crate) use plan::step_plan;

use adaptive::Adaptive;
use exact_modal::ExactModal;
use hysteretic::Hysteretic;

use crate::model::system::{LevelState, System};
use crate::numerics::hermite::{Basis, hermite_crossing};

/// Integration method (`[solver] method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Classical fixed-step fourth-order Runge–Kutta: the paper's method.
    Rk4,
    /// Dormand–Prince 5(4) in the interaction picture (each mode's linear dynamics and the
    /// ground load propagated exactly, the pair integrating only the contact coupling), with
    /// error control (rtol, atol) and contact onset/release located so that no step straddles
    /// the kink of the contact law.
    Adaptive,
    /// Exact modal propagation (ground load integrated exactly, free flight in closed form
    /// between impacts, onsets located); contact by an embedded exponential Lobatto collocation
    /// pair (order 8, error estimated to order 6) with steps held to rtol. With yielding
    /// storeys, their pseudo-forces, z and the contact by a trapezoidal predictor–corrector
    /// (second order) in dyadic sub-steps.
    ExactModal,
}

impl Method {
    /// Name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Method::Rk4 => "rk4",
            Method::Adaptive => "adaptive",
            Method::ExactModal => "exact-modal",
        }
    }

    /// Every method, in the order of [`Method::name`]s offered to users.
    pub const ALL: [Method; 3] = [Method::Rk4, Method::Adaptive, Method::ExactModal];

    /// The method of a scenario with elastic structures that names none: `exact-modal`, at its
    /// default tolerance within 0.5 % of converged solutions on every contact law, stiff and
    /// chaotic cases included, and the cheapest tolerance-controlled method (README, *Solver
    /// methods and speed*). See [`Method::default_for`].
    pub const DEFAULT: Method = Method::ExactModal;

    /// The method of a scenario that names none: [`Method::DEFAULT`] (`exact-modal`) for
    /// elastic structures, `adaptive` when a structure has yielding storeys (`yielding`).
    /// With yielding storeys `exact-modal` integrates the storeys' pseudo-forces by a
    /// second-order trapezoid in dyadic sub-steps: as accurate at its default (within 1e-6 of
    /// converged on the bundled yielding frames, and with a 100× stiffer contact) but 4–6× the
    /// work of `adaptive`, whose collocation carries the Bouc–Wen z to high order.
    pub fn default_for(yielding: bool) -> Method {
        if yielding {
            Method::Adaptive
        } else {
            Method::DEFAULT
        }
    }

    /// Relative tolerance used when a scenario gives none: [`DEFAULT_RTOL`] for `adaptive`,
    /// [`EXACT_MODAL_DEFAULT_RTOL`] for `exact-modal` (its tolerance bounds a sixth-order
    /// estimate of each contact step while it keeps an eighth-order solution: the two methods'
    /// rtol are not the same measure); `rk4` has no tolerance (it reports [`DEFAULT_RTOL`]).
    pub fn default_rtol(self) -> f64 {
        match self {
            Method::Rk4 | Method::Adaptive => DEFAULT_RTOL,
            Method::ExactModal => EXACT_MODAL_DEFAULT_RTOL,
        }
    }

    /// Whether `rtol`/`atol` control the method's error (`adaptive`, `exact-modal`); `rk4`'s
    /// error is set by its step alone.
    pub fn has_tolerance(self) -> bool {
        matches!(self, Method::Adaptive | Method::ExactModal)
    }

    /// What `[solver] dt` is to this method, in words (as summary.json's `solver.dt_meaning`
    /// writes it): see [`SolverSettings::fixed_step`], [`SolverSettings::base_step`],
    /// [`SolverSettings::max_step`].
    pub fn dt_meaning(self) -> &'static str {
        match self {
            Method::Rk4 => "fixed step",
            Method::ExactModal => "base step (contact sub-steps below it)",
            Method::Adaptive => "largest step",
        }
    }

    /// The method called `name` in scenario files.
    pub fn from_name(name: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// Default relative tolerance (`adaptive`, and `exact-modal`'s contact sub-steps). 1e-10,
/// because a sequence of stiff impacts amplifies local errors: on a stiff case (k_h = 2.808e13
/// N/m^1.5, issue 9) rtol = 1e-8 leaves the peak force 2.4 % from the converged one and 1e-10
/// 0.15 %, while on the paper's case 1e-10 costs 1.25× what 1e-8 does.
pub const DEFAULT_RTOL: f64 = 1e-10;
/// Smallest relative tolerance accepted: on a stiff contact (k_h = 2.808e13 N/m^1.5) the
/// round-off of one contact step is ~1.4e-13 of the state, so below ~1e-12 an error estimate
/// measures round-off and the steps would shrink without end.
pub const MIN_RTOL: f64 = 1e-12;
/// Smallest absolute tolerance accepted, m ([`MIN_RTOL`] × [`ATOL_PER_RTOL`]).
pub const MIN_ATOL: f64 = MIN_RTOL * ATOL_PER_RTOL;
/// Default relative tolerance of `exact-modal`'s contact steps. 1e-8: on the stiff Hertz case
/// (k_h = 2.808e13 N/m^1.5, PGA 0.5 g, 6 s), whose chaotic sequence of impacts amplifies every
/// step's error, the peak force is 2.1e-4 from converged at 1e-8, 1.3e-3 at 2e-8 and 8.2e-3 at
/// 4e-8 (dt 1 ms); the paper's case costs 1.2× what 1e-7 does.
pub const EXACT_MODAL_DEFAULT_RTOL: f64 = 1e-8;
/// Absolute tolerance that goes with a relative one when `atol` is not given, m per unit of
/// rtol: `atol = rtol × 1 cm` at a structure's top. Scaling it with rtol keeps rtol the one
/// knob: with a fixed atol, rtol below ~1e-9 would change nothing (the modal amplitudes times
/// rtol fall under atol).
pub const ATOL_PER_RTOL: f64 = 0.01;
/// Default absolute tolerance, m (displacement at a structure's top; see
/// [`SolverSettings::atol`]): [`DEFAULT_RTOL`] × [`ATOL_PER_RTOL`].
pub const DEFAULT_ATOL: f64 = DEFAULT_RTOL * ATOL_PER_RTOL;

/// Solver settings, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Method.
    pub method: Method,
    /// `[solver] dt`, s: one number that each method reads in its own way, through the named
    /// accessors — [`SolverSettings::fixed_step`] (`rk4`: every step),
    /// [`SolverSettings::base_step`] (`exact-modal`: the grid of free flight and of
    /// observations, contact steps below it) and [`SolverSettings::max_step`] (`adaptive`: the
    /// largest step); [`Method::dt_meaning`] says which in words.
    pub dt: f64,
    /// Simulated duration, s.
    pub duration: f64,
    /// Relative tolerance of `adaptive` (ignored by the fixed-step methods).
    pub rtol: f64,
    /// Absolute tolerance of `adaptive`, m: an error of this size in a structure's top
    /// displacement. Turned into modal units per structure i as `atol·√M_i/2` (since
    /// |φ(L)| = 2/√(M), docs/model.md §2.3) for η, and that times ω₁ of the structure for η̇.
    pub atol: f64,
}

impl SolverSettings {
    /// Settings with the method's default tolerances ([`Method::default_rtol`]).
    pub fn new(method: Method, dt: f64, duration: f64) -> SolverSettings {
        SolverSettings {
            method,
            dt,
            duration,
            rtol: DEFAULT_RTOL,
            atol: DEFAULT_ATOL,
        }
        .with_rtol(method.default_rtol())
    }

    /// `rk4`'s step, s (`dt`): every step of the run has this length but the last, which ends
    /// on the duration (the step plan); checked against RK4's stability limit before the run
    /// ([`SolverSettings::check_stability`]) and in every contact.
    pub fn fixed_step(&self) -> f64 {
        self.dt
    }

    /// `exact-modal`'s base step, s (`dt`): each span of the ground load (the whole run, or one
    /// interval between a record's samples) is cut into equal steps no longer than this
    /// (the step plan); free flight takes them whole (exact for any length), and they are the
    /// grid of observations. Contact steps are dyadic fractions `dt·2^(−k/4)` of it (elastic
    /// structures) or `dt/2^m` sub-steps (yielding storeys), chosen by the error estimate.
    pub fn base_step(&self) -> f64 {
        self.dt
    }

    /// `adaptive`'s largest step, s (`dt`): the error control chooses steps `dt·2^(−k/4)` below
    /// it (elastic structures; no step crosses a record sample or the duration), or starts at
    /// `dt/64` and grows to at most `dt` (Dormand–Prince with yielding storeys); so `dt` is
    /// also the largest spacing of observations.
    pub fn max_step(&self) -> f64 {
        self.dt
    }

    /// The same settings at relative tolerance `rtol`, with the absolute tolerance that goes
    /// with it (`rtol ×` [`ATOL_PER_RTOL`]).
    pub fn with_rtol(self, rtol: f64) -> SolverSettings {
        SolverSettings {
            rtol,
            atol: rtol * ATOL_PER_RTOL,
            ..self
        }
    }
}

/// One accepted step (`adaptive`) or contact sub-step (`exact-modal`) that carried contact
/// forces, as its error estimate saw it: for the tests that compare the estimate with the
/// step's true local error (the step redone finely from `q0`, `v0`).
#[derive(Debug, Clone)]
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) struct StepTrace {
    /// Start time, s.
    pub t: f64,
    /// Step length, s.
    pub h: f64,
    /// Modal state at the start.
    pub q0: Vec<f64>,
    /// See `q0`.
    pub v0: Vec<f64>,
    /// Onset speeds in force at the start.
    pub onset: Vec<f64>,
    /// The accepted end state.
    pub q1: Vec<f64>,
    /// See `q1`.
    pub v1: Vec<f64>,
    /// The scaled error estimate (≤ 1 for an accepted step).
    pub err: f64,
    /// Whether a level's force starts or ends at zero inside the step (`exact-modal`, which does
    /// not locate onsets: its estimate is a bound there, not an asymptotic estimate), or (with
    /// yielding storeys) a storey's ḋz changes sign in it.
    pub kink: bool,
    /// Hysteretic variables at the start and the end (empty without hysteresis).
    pub z0: Vec<f64>,
    /// See `z0`.
    pub z1: Vec<f64>,
    /// `exact-modal`'s contact steps: every level's (δ, δ̇) at the end by the estimate's
    /// companion scheme (empty otherwise).
    pub companion: Vec<(f64, f64)>,
}

/// Initial modal state (default: at rest relative to the ground, docs/model.md §2.8).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct InitialState {
    /// Modal displacements η(0), structure 1 then 2 (empty: zeros).
    pub q: Vec<f64>,
    /// Modal velocities η̇(0) (empty: zeros).
    pub v: Vec<f64>,
}

impl InitialState {
    /// Modal displacements and velocities for a system of `n` coordinates: the given vectors,
    /// or zeros where a vector is empty (or of another length).
    pub fn resolved(&self, n: usize) -> (Vec<f64>, Vec<f64>) {
        let pick = |x: &Vec<f64>| {
            if x.len() == n {
                x.clone()
            } else {
                vec![0.0; n]
            }
        };
        (pick(&self.q), pick(&self.v))
    }
}

/// Cumulative quantities integrated alongside the state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tally {
    /// Work done by the ground loading since t = 0, J.
    pub input: f64,
    /// Energy dissipated by structural damping, J.
    pub damping: f64,
    /// Work done on the contacts, `Σ_k ∫ F_k δ̇_k dt`, J (stored + dissipated in contact).
    pub contact: f64,
    /// Impulse of each level's contact force, `∫ F_k dt`, N·s.
    pub impulse: Vec<f64>,
    /// Work given to the yielding storeys' pseudo-forces, `Σ_s ∫ ΔV_s ḋ_s dt`, J (0 without
    /// hysteresis; see [`crate::model::hysteresis`]).
    pub hysteretic: f64,
    /// The same per yielding storey (in the order of `System::hysteresis`), J.
    pub storey_work: Vec<f64>,
}

/// What an observer sees at the end of each step (and once at t = 0).
#[derive(Debug)]
pub struct StepView<'a> {
    /// Time, s.
    pub t: f64,
    /// Modal displacements.
    pub q: &'a [f64],
    /// Modal velocities.
    pub v: &'a [f64],
    /// Contact state of every level.
    pub levels: &'a [LevelState],
    /// Hysteretic variable z of every yielding storey (empty without hysteresis).
    pub z: &'a [f64],
    /// Cumulative energy flows and impulses.
    pub tally: &'a Tally,
}

/// Receives the solution as it is computed.
pub trait Observer {
    /// Called at t = 0 and after every step, in time order (and, for `exact-modal`, at the
    /// interior nodes of a contact step whose force peaks inside it: dense output of the
    /// collocation, with the tallies integrated to that instant).
    fn observe(&mut self, system: &System, step: &StepView);

    /// [`Observer::observe`] at the end of a row's contact step (or at one of its interior
    /// nodes) that carried only the structures `stepped.active` under contact forces: the
    /// others (passive) moved in exact free flight, no force acting on them, since their
    /// last observation at a grid point or in a step that carried them. An observer may
    /// leave a passive structure unobserved here and take it at its next observation
    /// (`stepped.grid`: every structure must be seen now), as free flight is observed on the
    /// grid. The default observes everything.
    fn observe_stepped(&mut self, system: &System, step: &StepView, stepped: &Stepped) {
        let _ = stepped;
        self.observe(system, step);
    }
}

/// Which structures a row's contact step carried (see [`Observer::observe_stepped`]).
#[derive(Debug, Clone, Copy)]
pub struct Stepped<'a> {
    /// Per structure (row order): whether the step carried it under contact forces.
    pub active: &'a [bool],
    /// Whether this observation is the first at or past a grid point (or the run's end):
    /// every structure is to be observed.
    pub grid: bool,
}

/// Counters of one integration.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stats {
    /// Steps accepted (summary.json's `solver.steps`; the recorder's count of observations,
    /// which can be larger, is [`crate::recording::run_record::RunRecord::steps`]).
    pub steps: usize,
    /// Right-hand-side evaluations.
    pub evaluations: usize,
    /// Largest `ω_c·dt` met in contact, where `ω_c = √(k_t/m*)` is the contact's tangent
    /// frequency: above ≈2.8 an explicit step is locally unstable, above ≈0.5 inaccurate.
    pub max_contact_omega_dt: f64,
    /// Steps rejected by error control (every method but `rk4`).
    pub rejected: usize,
    /// Contact onsets and releases located as events (every method but `rk4`).
    pub events: usize,
}

/// Why an integration could not be carried out.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// The scenario's ground motion is a design spectrum: there is no time history to
    /// integrate (`pounding separation` evaluates a spectrum).
    #[error(
        "the ground motion is a design spectrum ({0}), which has no time history to simulate: \
         use `pounding separation SCENARIO` for the spectral peaks and the required separation \
         by every rule, or give a record or a harmonic motion to simulate pounding"
    )]
    NoTimeHistory(&'static str),
    /// The step exceeds the method's stability limit for the structures' highest mode.
    #[error(
        "time step dt = {dt} s is beyond {method}'s stability limit: mode {mode} of structure {structure} \
         (ω = {omega:.4} rad/s, ζ = {zeta}) needs dt ≤ {max_dt:.6e} s; the largest stable dt for this \
         scenario is {max_dt:.6e} s (reduce dt, or keep fewer modes)"
    )]
    UnstableStep {
        /// Method name.
        method: &'static str,
        /// Requested step, s.
        dt: f64,
        /// Largest stable step, s.
        max_dt: f64,
        /// Structure (1 or 2) of the limiting mode.
        structure: usize,
        /// Limiting mode (1-based).
        mode: usize,
        /// Its ω, rad/s.
        omega: f64,
        /// Its ζ.
        zeta: f64,
    },
    /// A contact made the fixed step unstable (`rk4`, docs/model.md §2.9): in contact the system's
    /// stiffest mode, linearised about the contact state (each mode's stiffness plus the law's
    /// tangent stiffness and damping at the penetration met), lies beyond RK4's stability
    /// limit for the step. The run stops there; `max_dt` estimates the largest stable step.
    #[error(
        "rk4 refused at t = {t:.4} s: at contact level {level} (h = {height} m) the penetration \
         {delta:.3e} m gives ω_c·dt = {omega_c_dt:.3} (ω_c = √(k_t/m*) = {omega_c:.4e} rad/s); \
         with the structures' modes the stiffest mode in contact has ω·dt = {omega_dt:.3}, beyond \
         RK4's stability limit {limit:.3} at dt = {dt} s. Largest stable step, estimated: \
         dt ≈ {max_dt:.2e} s ({margin} × the stable step of the stiffest mode at the larger of the \
         penetration met and the one this impact reaches by energy, ½m*v₀² = contact potential; \
         only an estimate: at another step the impacts, and so the penetrations, change). Accurate contact forces need ω_c·dt ≲ 0.5, about dt ≲ \
         {accurate_dt:.1e} s. Reduce solver.dt, or use `exact-modal` or `adaptive`, whose steps \
         follow the contact"
    )]
    ContactUnstable {
        /// Time at the end of the refused step, s.
        t: f64,
        /// Contact level (1-based, in the order of the scenario).
        level: usize,
        /// Its height, m.
        height: f64,
        /// Penetration at the end of the step, m.
        delta: f64,
        /// The contact's tangent frequency `ω_c = √(k_t/m*)` there, rad/s.
        omega_c: f64,
        /// `ω_c·dt`.
        omega_c_dt: f64,
        /// `ω·dt` of the stiffest mode of the linearised system in contact (≥ `ω_c·dt`).
        omega_dt: f64,
        /// RK4's stability limit on `ω·dt` for that mode (2√2 when undamped).
        limit: f64,
        /// Requested step, s.
        dt: f64,
        /// Estimated largest stable step (with the safety factor `margin`), s.
        max_dt: f64,
        /// Safety factor applied to `max_dt`.
        margin: f64,
        /// Step for `ω_c·dt ≈ 0.5` at the estimated peak penetration, s.
        accurate_dt: f64,
    },
    /// The solution became non-finite.
    #[error(
        "the solution diverged at t = {t:.6} s (largest contact ω·dt met: {contact_omega_dt:.3}; \
         above ≈2.8 the contact is too stiff for this step): reduce dt"
    )]
    Diverged {
        /// Time, s.
        t: f64,
        /// Largest contact ω·dt met before.
        contact_omega_dt: f64,
    },
    /// An error-controlled method could not meet its tolerance with any step it may take (the
    /// step fell to `dt·1e-9`): the tolerance is below what double precision resolves here.
    #[error(
        "the tolerance cannot be met at t = {t:.6} s: the step fell to {h:.3e} s and the error \
         estimate still exceeds rtol = {rtol:e} (below what double precision resolves here); \
         raise solver.rtol (and solver.atol, if set)"
    )]
    ToleranceUnreachable {
        /// Time, s.
        t: f64,
        /// Last step tried, s.
        h: f64,
        /// The relative tolerance.
        rtol: f64,
    },
    /// An error-controlled method could not make a step at an instant: it stopped rather than
    /// loop without end (accepted steps that do not move time, a rejected step retried without
    /// shrinking; see [`StepFailure`]). A failure of the method on this motion, not of the
    /// scenario: the other error-controlled method integrates it.
    #[error(
        "{method} could not advance past t = {t:.9} s{}: {reason} (last step {h:.3e} s). This is \
         a failure of the method on this motion, not of the scenario: run it with \
         solver.method = \"{alternative}\"",
        at_level(*.level, *.height)
    )]
    StepFailed {
        /// Method name.
        method: &'static str,
        /// Time, s.
        t: f64,
        /// The contact level the step was resolving (1-based, in the order of the scenario):
        /// the deepest penetrating one; `None` without contact levels.
        level: Option<usize>,
        /// Its height, m.
        height: Option<f64>,
        /// Last step length tried, s.
        h: f64,
        /// What failed.
        reason: StepFailure,
        /// The method to run the scenario with instead.
        alternative: &'static str,
    },
    /// The scenario is a suite of records (`[ground_motion] kind = "suite"`): one run per record,
    /// by `pounding run` (the library's `study::suite::run`), not one simulation.
    #[error(
        "the ground motion is a suite of {0} records, which is run record by record: use \
         `pounding run SCENARIO` (or `pounding.run` in Python), or give one record (kind = \"record\") \
         for this command"
    )]
    Suite(usize),
    /// The scenario is a row of more than two buildings (issue 29), which `pounding run` (the
    /// library's `analysis::simulate::simulate_row`) runs; this door takes a pair only.
    #[error(
        "the scenario is a row of {0} structures, which `pounding run` runs (summary.json, \
         impacts.csv and its report); this command takes a pair of structures only, so far: \
         take the row apart into pairs, or run it with `pounding run`"
    )]
    Row(usize),
}

/// " at contact level k (height h m)" of [`SolveError::StepFailed`]'s message.
fn at_level(level: Option<usize>, height: Option<f64>) -> String {
    match (level, height) {
        (Some(k), Some(h)) => format!(" at contact level {k} (h = {h} m)"),
        _ => String::new(),
    }
}

impl SolverSettings {
    /// Check the step against the method's linear stability limit for every mode of `system`.
    pub fn check_stability(&self, system: &System) -> Result<(), SolveError> {
        match self.method {
            Method::Rk4 => {
                let (max_dt, j) = rk4_max_stable_dt(system);
                if self.fixed_step() > max_dt {
                    let (i, m) = system.structure_of_mode(j);
                    let (structure, mode) = (i + 1, m + 1);
                    let omega = system.omega()[j];
                    return Err(SolveError::UnstableStep {
                        method: self.method.name(),
                        dt: self.fixed_step(),
                        max_dt,
                        structure,
                        mode,
                        omega,
                        zeta: system.damping_coefficients()[j] / (2.0 * omega),
                    });
                }
                Ok(())
            }
            // both propagate every mode's linear dynamics exactly: stable for any step
            Method::Adaptive | Method::ExactModal => Ok(()),
        }
    }
}

/// Integrate `system` from `initial` over `settings.duration`, reporting to `observer`.
pub fn integrate<O: Observer>(
    system: &System,
    settings: &SolverSettings,
    initial: &InitialState,
    observer: &mut O,
) -> Result<Stats, SolveError> {
    settings.check_stability(system)?;
    let yielding = !system.hysteresis.is_empty();
    // (one match per run: the method's loop is monomorphised, nothing is dispatched per step)
    match settings.method {
        Method::Rk4 => Rk4::run(system, settings, initial, observer, None),
        Method::Adaptive if yielding => Hysteretic::run(system, settings, initial, observer, None),
        Method::Adaptive => Adaptive::run(system, settings, initial, observer, None),
        Method::ExactModal => ExactModal::run(system, settings, initial, observer, None),
    }
}

/// One integration method's run. Each method is a unit type (`Rk4`, `Adaptive`, `Hysteretic`
/// for `adaptive` where storeys yield, `ExactModal`) and [`integrate`] picks one by a match
/// outside the time loop: static dispatch, the loop generic over the [`Observer`].
pub(crate) trait Integrator {
    /// Integrate `sys` from `initial` over `settings.duration`, reporting t = 0 and every step
    /// to `observer`. With `trace`, every step that carried contact forces (or, with yielding
    /// storeys, every estimated sub-step) is recorded as its error estimate saw it
    /// ([`StepTrace`]: for the tests of the estimates; `rk4` has no estimate and records none).
    fn run<'a, O: Observer>(
        sys: &'a System,
        settings: &SolverSettings,
        initial: &InitialState,
        observer: &'a mut O,
        trace: Option<&'a mut Vec<StepTrace>>,
    ) -> Result<Stats, SolveError>;
}

/// `rk4`: see [`rk4`] (fixed steps of [`SolverSettings::fixed_step`]).
struct Rk4;

impl Integrator for Rk4 {
    fn run<'a, O: Observer>(
        sys: &'a System,
        settings: &SolverSettings,
        initial: &InitialState,
        observer: &'a mut O,
        _trace: Option<&'a mut Vec<StepTrace>>,
    ) -> Result<Stats, SolveError> {
        rk4::run(sys, settings, initial, observer)
    }
}

/// Penetration rate at the instant δ crosses 0 upwards between two observations a time `h`
/// apart, each given as (δ, δ̇): the root of the cubic Hermite interpolant through both (a
/// third-order estimate), and its slope there. A previous observation with δ ≥ 0 (a located
/// onset, or contact from the start) is the crossing itself.
pub(crate) fn onset_speed(prev: (f64, f64), now: (f64, f64), h: f64) -> f64 {
    // (written so that a NaN δ or h also takes the early return)
    let crossing = now.0 > 0.0 && h > 0.0;
    if prev.0 >= 0.0 || !crossing {
        return if prev.0 >= 0.0 { prev.1 } else { now.1 };
    }
    // the interpolant on θ ∈ [0, 1] (slopes per unit of θ: m = h·δ̇), its root by bisection
    let (y0, m0, y1, m1) = (prev.0, prev.1 * h, now.0, now.1 * h);
    let th = hermite_crossing(y0, m0, y1, m1, 1.0, 60);
    let slope = Basis::slope_at(th).combine(y0, m0, y1, m1, 1.0);
    slope / h
}

/// Start of a contact episode at a level: the approach speed v₀ = δ̇ at the crossing of δ = 0
/// between the previous and the current observation ([`onset_speed`]; a step of length `h`).
/// This is the v₀ of the damped Hertz law and the `approach_speed` of the impact record.
pub(crate) fn update_onsets(onset: &mut [f64], prev: &[LevelState], now: &[LevelState], h: f64) {
    for k in 0..onset.len() {
        if now[k].delta > 0.0 {
            if onset[k] == 0.0 {
                let (p, c) = (prev[k], now[k]);
                let v0 = onset_speed((p.delta, p.delta_dot), (c.delta, c.delta_dot), h);
                onset[k] = v0.max(1e-12);
            }
        } else {
            onset[k] = 0.0;
        }
    }
}
