//! `exact-modal` for elastic structures (no yielding storey): free flight in closed form between
//! impacts, onsets located on the exact free flight, and contact integrated by the embedded
//! Lobatto collocation pair of [`crate::integrate::collocation`] with steps chosen by its error
//! estimate.
//!
//! **Free flight.** Every mode's motion is exact over any step (propagator and particular
//! solution, [`super::super::linear`]); the free flight advances on the base grid (steps `dt`,
//! cut at a record's samples), one observation per grid point, with exact tallies. Whether a
//! level can touch within a step is decided on the cubic Hermite interpolant of δ between the
//! step's ends plus a margin for the modes that oscillate within it (each mode strays at most
//! `(|λ|h)⁴/384` of its amplitude from its own cubic).
//!
//! **Onset.** Where it can, the step is searched in dyadic sub-steps for the first one whose
//! end penetrates (or whose interpolant touches), and δ = 0 is solved inside it by safeguarded
//! Newton iterations on the exact free flight (every iterate an exact state), to 1e-12 m. The
//! state jumps there exactly: contact starts at a located instant, with the law's right limit
//! (c·δ̇ for Kelvin), so no step straddles the onset. A stereomechanical impact is applied
//! there.
//!
//! **Contact.** Steps of the 5-node collocation (order 8, kept) and its 4-node companion
//! (order 6, the estimate) from the onset on, of lengths `dt·2^(−k/4)` (tables computed once
//! per length), each held to the tolerance of [`super::SubstepTolerance`] by the distance of
//! the two solutions, the next length from `err^(−1/7)`. A level that starts touching inside
//! a contact step (another level's impact) has its onset located by shortening that step
//! (secant on the step length, to 1e-12 m). The contact phase ends when no level penetrates;
//! the free flight then resumes to the next grid point.
//!
//! **Tallies.** Free flight: exact (the ground's work from moments of the modal equations,
//! dissipation from each mode's energy equation). Contact steps: the 5-node Lobatto quadrature
//! (exact for polynomials of degree 7) of the ground's and the damping's power from the modal
//! velocities at the nodes, and of `F·δ̇` at the nodes; impulses exact for the force quartic.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

mod accept;
mod active;
mod contact;
mod free;
mod kernel;
mod node_sums;
mod onset;
mod row_pass;
mod single;

use super::super::collocation::{
    self, NODES, NODES6, NODES8, Newton, NoConvergence, THETA8, Table, WEIGHTS8,
};
use super::super::linear::{
    GroundModes, HarmonicTally, Piece, Prop, StateSums, Trig, TrigMoments, mode_work,
    poly_coefficients, poly_ground_work, propagator,
};
use super::super::plan::{DyadicWalk, EqualSteps};
use super::super::poly_tally::{PolySums, PolyTally};
use super::super::progress::Progress;
use super::super::{
    InitialState, Method, Observer, SolveError, SolverSettings, Stats, StepTrace, StepView,
    Stepped, Tally, update_onsets,
};
use super::{SubstepTolerance, hermite_gap_factor};
use crate::model::system::{LevelState, System, episode_v0};
use crate::numerics::hermite::{hermite_crossing, hermite_max};
use crate::numerics::linalg::dot;

/// Onsets are located to |δ| ≤ this, m.
pub(super) const EVENT_TOL: f64 = 1e-12;
/// Contact step lengths are `dt·2^(−k/QUANT)`.
const QUANT: f64 = 4.0;
/// The shortest contact step, `dt·2^(−MAX_K/4)` ≈ dt·1e-12: below it the tolerance is out of
/// double precision's reach.
const MAX_K: usize = 160;
/// The estimate's local order (the companion is of order 6: error ∝ h⁷).
const ORDER: f64 = 7.0;
/// Under a recorded motion contact steps are dyadic parts hh/2^m of the grid step hh, aligned
/// to their own length (so that they end on the record's samples); their tables follow the
/// quantised ones in the cache, at `DYADIC + m`.
const DYADIC: usize = MAX_K + 1;
/// Deepest dyadic level (hh·2^-48).
const MAX_LEVEL: usize = 48;
/// Free-flight step lengths kept (grid steps and their dyadic parts).
const FREE_CACHE: usize = 24;
const _: () = assert!(FREE_CACHE < u8::MAX as usize);

/// The slot of `free_slot` for a step length h: its bits' Fibonacci hash (every bit moves
/// the top six; the grid's lengths differ by ulps of the time, anywhere in the mantissa).
#[inline(always)]
fn free_key(h: f64) -> usize {
    (h.to_bits().wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 58) as usize
}
/// Located stereomechanical impacts per grid step before the rest of the step is taken whole.
const ZENO: u32 = 16;
/// Depth of the dyadic search for an onset inside a free step.
const MAX_SCAN: u32 = 24;
/// A law's kink closer than this many units in the last place of t (and of dt) to a contact
/// step's start or end is taken as at it (see [`Elastic::law_kink_inside`]).
const KINK_FLOOR_ULPS: f64 = 64.0;

/// The free flight over one step length: every mode's propagator and its Hermite margin.
struct FreeData {
    h: f64,
    props: Vec<Prop>,
    /// Per mode, how far its free flight may stray from the cubic Hermite through its ends,
    /// per unit of |η − η_p| and of |η̇ − η̇_p| ([`hermite_gap_factor`]).
    herm: Vec<(f64, f64)>,
    /// The same for the harmonic particular solution (per unit of |G_re| + |G_im|).
    herm_part: f64,
    /// Harmonic motion: (sin Ωh, cos Ωh) and (sin Ωh/2, cos Ωh/2).
    rot: (f64, f64),
    half: (f64, f64),
    /// Recorded motion: the step as one affine map per mode (built at first use, see
    /// [`kernel::PolyMap`]).
    poly: Option<kernel::PolyMap>,
}

impl FreeData {
    fn new(sys: &System, big: Option<f64>, h: f64) -> FreeData {
        let (omega, damp) = (sys.omega(), sys.damping_coefficients());
        let props = (0..sys.len())
            .map(|j| propagator(omega[j], damp[j], h))
            .collect();
        let herm = (0..sys.len())
            .map(|j| {
                // |λ| of the mode's free motion: ω when underdamped, the fast root otherwise
                let (w, zw) = (omega[j], 0.5 * damp[j]);
                let lam = if zw < w {
                    w
                } else {
                    zw + (zw * zw - w * w).sqrt()
                };
                let f = hermite_gap_factor(lam * h);
                // amplitude of the complex exponential ≤ |x| + 2|ẋ|/|λ| (ζ ≤ 0.6, overdamped)
                (f, 2.0 * f / lam)
            })
            .collect();
        let (rot, half) = big.map_or(((0.0, 1.0), (0.0, 1.0)), |b| {
            ((b * h).sin_cos(), (0.5 * b * h).sin_cos())
        });
        FreeData {
            h,
            props,
            herm,
            herm_part: big.map_or(0.0, |b| hermite_gap_factor(b * h)),
            rot,
            half,
            poly: None,
        }
    }
}

/// One trial of a contact step, as left in the work arrays.
#[derive(Debug, Clone, Copy)]
struct Trial {
    /// Scaled error estimate (≤ 1 passes).
    err: f64,
    /// Step length, s.
    h: f64,
    /// Its table: quantised index, or `None` for the scratch table (a one-off length).
    k: Option<usize>,
}

pub(super) struct Elastic<'a, O: Observer> {
    sys: &'a System,
    gm: GroundModes,
    obs: &'a mut O,
    trace: Option<&'a mut Vec<StepTrace>>,
    tol: SubstepTolerance,
    dt: f64,
    duration: f64,
    n: usize,
    nl: usize,
    /// Ω of a harmonic motion without a mode at undamped resonance (the fast paths).
    big: Option<f64>,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    states: Vec<LevelState>,
    prev_states: Vec<LevelState>,
    onset: Vec<f64>,
    tally: Tally,
    stats: Stats,
    // --- free flight
    free: Vec<FreeData>,
    free_next: usize,
    /// The cache entry found last (checked first: a run of grid steps hits it every time).
    free_hit: usize,
    /// Per hash of a step length's bits ([`free_key`]), 1 + the cache entry last found or made
    /// for a length with that hash (0: none): the grid's steps differ by an ulp or two of the
    /// time (t_{i+1} − t_i of rounded grid points), a few lengths in turn, which the last hit
    /// alone misses. Checked against the entry's length: a stale slot only falls back to the
    /// scan.
    free_slot: [u8; 64],
    scratch_free: Option<FreeData>,
    qb: Vec<f64>,
    vb: Vec<f64>,
    /// Search state of the onset scan.
    qs: Vec<f64>,
    vs: Vec<f64>,
    /// Each mode's Hermite margin over the last free step (see [`hermite_gap_factor`]).
    amp: Vec<f64>,
    /// sin Ωt, cos Ωt at the current time (harmonic), carried by rotations along the grid.
    trig_now: Trig,
    /// The last `gm.trig` evaluated (a contact step's trials and its acceptance all start at
    /// the same instant, which the previous step's end evaluated: one libm call per step).
    trig_memo: Trig,
    since_sync: u32,
    htally: Option<HarmonicTally>,
    sums: StateSums,
    /// Records: the free flight's ground work regrouped ([`PolyTally`]), its sums at the
    /// current state (when `psums_ok`) and at the free pass's end, and the pass's ground
    /// factors (a_g, v_g, a1).
    ptally: PolyTally,
    psums: PolySums,
    psums_ok: bool,
    fpsums: PolySums,
    /// `Σ η̇² + ω²η²` at the current state (when `psums_ok`) and at the free pass's end, as
    /// the pass sums it (what bounds the next step's contact-test margins).
    pe2: f64,
    fe2: f64,
    fground: (f64, f64, f64),
    /// Each mode's ground load over the current step (records), and its particular solution's
    /// coefficients.
    cpoly: Vec<[f64; 3]>,
    pcoef: Vec<[f64; 3]>,
    // --- contact
    tables: Vec<Option<Box<Table>>>,
    scratch_table: Option<Box<Table>>,
    k_step: usize,
    k_onset: Option<usize>,
    /// Recorded motion: the grid step the dyadic tables were made for, the current level and
    /// the level the last onset needed.
    dyadic_hh: f64,
    m_step: usize,
    m_onset: Option<usize>,
    /// Recorded motion: where the contact steps stand on the piece's dyadic grid.
    walk: Option<contact::GridWalk>,
    /// Free flight's (δ, δ̇) at the table's nodes: `[k·6 + node]`.
    dfree: Vec<(f64, f64)>,
    d8free: Vec<(f64, f64)>,
    d6free: Vec<(f64, f64)>,
    /// Each mode's homogeneous part at the step's start, (η − η_p, η̇ − η̇_p), kept from the
    /// trial for the accepted step's pass.
    x0: Vec<f64>,
    y0: Vec<f64>,
    /// Harmonic motion: per level `(c_k·G_re, c_k·G_im)`, the particular solutions projected.
    gk: Vec<(f64, f64)>,
    /// Nodal forces `[k·5 + p]`, `[k·4 + p]` and nodal (δ, δ̇) `[k·4 + p − 1]`, `[k·3 + p − 1]`.
    f8: Vec<f64>,
    f6: Vec<f64>,
    nodal8: Vec<(f64, f64)>,
    nodal6: Vec<(f64, f64)>,
    /// The last accepted contact step's nodal forces and length, for the next one's guess.
    last_f8: Vec<f64>,
    last_h: f64,
    newton: Newton,
    /// Relative convergence tolerance of the Newton iterations: 1e-3 of rtol (not below
    /// 4e-15), so that their error stays far below the step's.
    newton_tol: f64,
    max_contact_w2h2: f64,
    inv_mstar: Vec<f64>,
    /// Coupling rows transposed, mode-major: `[j·L + k]`.
    cpl_t: Vec<f64>,
    /// Whether the last trial met a level's onset or release inside it (for the trace).
    kink: bool,
    /// Per level (δ, δ̇) at a search point, and the end state's projections (scratch).
    at: Vec<(f64, f64)>,
    proj: Vec<(f64, f64)>,
    /// The free flight's pass (see [`Self::free_prop`]): every level's projections of the end
    /// state and margin, the harmonic sums, the records' ground-work sums and the modal energy at the end.
    fproj: Vec<(f64, f64)>,
    fmargin: Vec<f64>,
    fsums: StateSums,
    fenergy: f64,
    /// The modal energy at the current state, J.
    energy: f64,
    /// `|c_kj|`, level by level: `[k·n + j]`.
    cabs_t: Vec<f64>,
    /// Per level, the contact quartic's (∫F dτ, ∫τF dτ) over the step being accepted.
    moments: Vec<(f64, f64)>,
    /// Per level, whether any of its nodal forces over the step being accepted is non-zero.
    live: Vec<bool>,
    /// Per level, the coefficients of the ground's extra work under a load along it
    /// ([`HarmonicTally::row_extra`]; harmonic motion).
    kextra: Vec<(f64, f64)>,
    /// Dense output of a step (its interior nodes' modal states, level states, tallies).
    dense_q: Vec<f64>,
    dense_v: Vec<f64>,
    /// The accepted contact step's per-mode scratch: the particular solutions at its end and
    /// interior nodes, and the end state (swapped with `q`, `v` once the tallies are taken).
    pend: Vec<(f64, f64)>,
    pmid: Vec<[(f64, f64); 3]>,
    q1s: Vec<f64>,
    v1s: Vec<f64>,
    dense_states: Vec<LevelState>,
    dense_tally: Tally,
    /// Located stereomechanical impacts in the current grid step (see [`ZENO`]).
    zeno: u32,
    /// A level touches now with δ̇ = 0 (an onset at the current instant that is not
    /// approaching yet): the next step is a contact step.
    force_contact: bool,
    /// The guard against steps that cannot be made ([`Progress`]).
    progress: Progress,
    /// [`KINK_FLOOR_ULPS`] (a test sets 0 to bring back the defect it guards against).
    kink_floor_ulps: f64,
    /// A row's and a several-level pair's accepted steps under a recorded motion take the one
    /// pass over the modes (`row_pass::row_poly_pass`; a test sets false for the general loops
    /// it must equal).
    row_pass: bool,
    /// The quantised contact step lengths `dt·2^(−k/4)`, k = 0..=MAX_K.
    lengths: Vec<f64>,
    /// Contact steps since sin Ωt, cos Ωt were last evaluated directly.
    contact_sync: u32,
    // --- a row's contact step over the structures in (or near) contact (see `active`)
    /// A row of more than two structures (a pair's every step is all-active).
    row: bool,
    /// Every structure active in every contact step (a test's reference: the all-active step).
    all_active: bool,
    /// Per structure, whether it is active in the current contact step (and scratch).
    act: Vec<bool>,
    act_next: Vec<bool>,
    /// Per mode, whether its structure is active.
    mode_act: Vec<bool>,
    /// The levels solved for, at the edge of the active structures, and both (ascending).
    lv_solve: Vec<usize>,
    lv_edge: Vec<usize>,
    lv_seen: Vec<usize>,
    /// Per level, the time until which it is held in the step (its free flight may close).
    hold: Vec<f64>,
    /// Per level, whether the last check cleared it passive; until when that check holds; the
    /// time the last contact step ended (a free step since then voids the check).
    p_checked: Vec<bool>,
    passive_safe: f64,
    contact_t_end: f64,
    /// Contact steps with a passive structure, and trials redone for a level at the edge.
    passive_steps: usize,
    edge_redos: usize,
    /// The next grid point, at (or first past) which a row's observation sees every
    /// structure (see [`Observer::observe_stepped`]), s.
    obs_grid: f64,
    /// What a recorded motion's contact trials take from their start alone, kept over the
    /// trials of one step.
    start: TrialStart,
}

/// A recorded motion's contact trial's start (see [`Elastic::trial_general`]): every mode's
/// ground-load polynomial, particular solution and homogeneous part at the step's start
/// (`cpoly`, `pcoef`, `x0`, `y0` of [`Elastic`]) and the particular solutions projected on
/// the levels. The trials of one step (rejected, cut at an event, redone with an edge's
/// structure) start from the same state at the same instant, so these are the same numbers
/// at every trial: formed at the first, valid until the step is accepted.
#[derive(Debug, Clone)]
struct TrialStart {
    /// Whether the modes' values (and `narrow`) are this step's.
    valid: bool,
    /// Of at most eight levels: every level's projection (A, B, C), summed over every mode.
    narrow: [[f64; 3]; 8],
    /// Of more levels: each level's projection over its pair's modes, and whether it is
    /// formed for this step.
    wide: Vec<[f64; 3]>,
    wide_ok: Vec<bool>,
}

pub(super) fn run<O: Observer>(
    sys: &System,
    settings: &SolverSettings,
    initial: &InitialState,
    observer: &mut O,
    trace: Option<&mut Vec<StepTrace>>,
) -> Result<Stats, SolveError> {
    let (q0, v0) = initial.resolved(sys.len());
    Elastic::new(sys, settings, observer, trace, 0.0, q0, v0, None).drive()
}

impl<'a, O: Observer> Elastic<'a, O> {
    /// The run from the current state to the end of the duration.
    fn drive(mut self) -> Result<Stats, SolveError> {
        self.drive_here()
    }

    /// [`Self::drive`] keeping the integrator (a test reads its counters after the run).
    fn drive_here(&mut self) -> Result<Stats, SolveError> {
        self.observe();
        while self.t < self.duration {
            let t0 = self.t;
            if self.in_contact() {
                self.contact_step()?;
            } else {
                self.free_segment()?;
            }
            self.progress
                .passed(self.sys, &self.states, t0, self.t, self.dt)?;
        }
        self.stats.max_contact_omega_dt = self.max_contact_w2h2.sqrt();
        Ok(self.stats)
    }

    /// The integrator at time `t0` in the modal state (q0, v0); `onset`: the approach speeds of
    /// the contact episodes in force (`None`: none).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        sys: &'a System,
        settings: &SolverSettings,
        observer: &'a mut O,
        trace: Option<&'a mut Vec<StepTrace>>,
        t0: f64,
        q0: Vec<f64>,
        v0: Vec<f64>,
        onset: Option<&[f64]>,
    ) -> Elastic<'a, O> {
        let n = sys.len();
        let nl = sys.levels.len();
        let gm = GroundModes::new(sys);
        let big = gm.harmonic_plain().map(|h| h.0);
        let htally = HarmonicTally::new(&gm);
        let kextra = match &htally {
            Some(ht) => (0..nl).map(|k| ht.row_extra(sys.coupling(k))).collect(),
            None => vec![(0.0, 0.0); nl],
        };
        let mut r = Elastic {
            sys,
            obs: observer,
            trace,
            tol: SubstepTolerance::new(sys, settings),
            dt: settings.base_step(),
            duration: settings.duration,
            n,
            nl,
            big,
            t: t0,
            q: q0,
            v: v0,
            states: vec![LevelState::default(); nl],
            prev_states: vec![LevelState::default(); nl],
            onset: vec![0.0; nl],
            tally: Tally {
                impulse: vec![0.0; nl],
                ..Tally::default()
            },
            stats: Stats::default(),
            free: Vec::with_capacity(FREE_CACHE),
            free_next: 0,
            free_hit: 0,
            free_slot: [0; 64],
            scratch_free: None,
            qb: vec![0.0; n],
            vb: vec![0.0; n],
            qs: vec![0.0; n],
            vs: vec![0.0; n],
            amp: vec![0.0; n],
            trig_now: gm.trig(t0),
            trig_memo: Trig {
                t: f64::NAN,
                ..Trig::default()
            },
            since_sync: 0,
            htally,
            sums: StateSums::default(),
            ptally: PolyTally::new(&gm.la, &gm.lv, &gm.damp, &gm.inv_w2),
            psums: PolySums::default(),
            psums_ok: false,
            fpsums: PolySums::default(),
            pe2: 0.0,
            fe2: 0.0,
            fground: (0.0, 0.0, 0.0),
            cpoly: vec![[0.0; 3]; n],
            pcoef: vec![[0.0; 3]; n],
            tables: (0..DYADIC + MAX_LEVEL + 1).map(|_| None).collect(),
            dyadic_hh: f64::NAN,
            m_step: 2,
            m_onset: None,
            walk: None,
            scratch_table: None,
            k_step: 8,
            k_onset: None,
            dfree: vec![(0.0, 0.0); 6 * nl],
            d8free: vec![(0.0, 0.0); 4 * nl],
            d6free: vec![(0.0, 0.0); 3 * nl],
            x0: vec![0.0; n],
            y0: vec![0.0; n],
            gk: match gm.harmonic_plain() {
                Some((_, g_re, g_im)) => (0..nl)
                    .map(|k| (dot(sys.coupling(k), g_re), dot(sys.coupling(k), g_im)))
                    .collect(),
                None => vec![(0.0, 0.0); nl],
            },
            f8: vec![0.0; 5 * nl],
            f6: vec![0.0; 4 * nl],
            nodal8: vec![(0.0, 0.0); 4 * nl],
            nodal6: vec![(0.0, 0.0); 3 * nl],
            last_f8: vec![0.0; 5 * nl],
            last_h: 0.0,
            newton: Newton::default(),
            newton_tol: (1e-3 * settings.rtol).max(4e-15),
            max_contact_w2h2: 0.0,
            inv_mstar: sys.levels.iter().map(|l| 1.0 / l.effective_mass).collect(),
            cpl_t: (0..n)
                .flat_map(|j| (0..nl).map(move |k| sys.coupling(k)[j]))
                .collect(),
            kink: false,
            at: vec![(0.0, 0.0); nl],
            proj: vec![(0.0, 0.0); nl],
            force_contact: false,
            progress: Progress::new(Method::ExactModal),
            kink_floor_ulps: KINK_FLOOR_ULPS,
            row_pass: true,
            lengths: (0..=MAX_K)
                .map(|k| settings.base_step() * (-(k as f64) / QUANT).exp2())
                .collect(),
            contact_sync: 0,
            row: sys.structures.len() > 2,
            all_active: false,
            act: vec![true; sys.structures.len()],
            act_next: Vec::new(),
            mode_act: vec![true; n],
            lv_solve: (0..nl).collect(),
            lv_edge: Vec::new(),
            lv_seen: (0..nl).collect(),
            hold: vec![f64::NEG_INFINITY; nl],
            p_checked: vec![false; nl],
            passive_safe: f64::NEG_INFINITY,
            contact_t_end: f64::NAN,
            passive_steps: 0,
            edge_redos: 0,
            obs_grid: 0.0,
            start: TrialStart {
                valid: false,
                narrow: [[0.0; 3]; 8],
                wide: vec![[0.0; 3]; nl],
                wide_ok: vec![false; nl],
            },
            zeno: 0,
            fproj: vec![(0.0, 0.0); nl],
            fmargin: vec![0.0; nl],
            fsums: StateSums::default(),
            fenergy: 0.0,
            energy: 0.0,
            cabs_t: (0..nl)
                .flat_map(|k| sys.coupling(k).iter().map(|c| c.abs()))
                .collect(),
            moments: vec![(0.0, 0.0); nl],
            live: vec![false; nl],
            kextra,
            dense_q: vec![0.0; 3 * n],
            dense_v: vec![0.0; 3 * n],
            pend: vec![(0.0, 0.0); n],
            pmid: vec![[(0.0, 0.0); 3]; n],
            q1s: vec![0.0; n],
            v1s: vec![0.0; n],
            dense_states: vec![LevelState::default(); nl],
            dense_tally: Tally {
                impulse: vec![0.0; nl],
                ..Tally::default()
            },
            gm,
        };
        r.resync_sums();
        r.energy = r.modal_energy();
        if let Some(onset) = onset {
            r.onset.copy_from_slice(onset);
        }
        r.evaluate_states();
        let s0 = r.states.clone();
        update_onsets(&mut r.onset, &s0, &r.states, 0.0);
        r
    }

    /// sin Ωt, cos Ωt at t, evaluated directly (memoised: see `trig_memo`).
    #[inline]
    fn exact_trig(&mut self, t: f64) -> Trig {
        if self.trig_memo.t != t {
            self.trig_memo = self.gm.trig(t);
            self.trig_memo.t = t;
        }
        self.trig_memo
    }

    fn observe(&mut self) {
        self.obs.observe(
            self.sys,
            &StepView {
                t: self.t,
                q: &self.q,
                v: &self.v,
                levels: &self.states,
                z: &[],
                tally: &self.tally,
            },
        );
        if self.row {
            self.obs_grid = self.next_grid_point();
        }
    }

    /// The harmonic tallies' sums at the current state.
    fn resync_sums(&mut self) {
        if let Some(ht) = &self.htally {
            let mut s = StateSums::default();
            for j in 0..self.n {
                ht.add(&mut s, j, self.gm.w2[j], self.q[j], self.v[j]);
            }
            self.sums = s;
        }
    }

    /// δ, δ̇ and the law's force of every level at the current state.
    fn evaluate_states(&mut self) {
        for k in 0..self.nl {
            let c = self.sys.coupling(k);
            let (cq, cv) = if self.row {
                free::dots_within(c, &self.q, &self.v, self.sys.coupling_modes(k))
            } else {
                (dot(c, &self.q), dot(c, &self.v))
            };
            self.set_state(k, cq, cv);
        }
    }

    #[inline]
    fn set_state(&mut self, k: usize, cq: f64, cv: f64) {
        self.states[k] = self.sys.levels[k].state(cq, cv, self.onset[k]);
    }

    /// A level at a located onset (δ within [`EVENT_TOL`] below 0, approaching).
    fn at_onset(st: &LevelState) -> bool {
        st.delta <= 0.0 && st.delta >= -EVENT_TOL && st.delta_dot > 0.0
    }

    /// A level penetrating (not just released: within [`EVENT_TOL`] above 0 and separating,
    /// where the force is ~k·EVENT_TOL^{3/2}, nothing).
    fn penetrating(st: &LevelState) -> bool {
        st.delta > EVENT_TOL || (st.delta > 0.0 && st.delta_dot >= 0.0)
    }

    /// A level's δ at the start of a free step, for the contact test: a just-released level
    /// counts as at 0.
    fn free_start(st: &LevelState) -> (f64, f64) {
        if st.delta > 0.0 && !Self::penetrating(st) {
            (0.0, st.delta_dot)
        } else {
            (st.delta, st.delta_dot)
        }
    }

    /// Whether the next step is a contact step: a level penetrates, or is at a located onset
    /// of a force law.
    fn in_contact(&self) -> bool {
        let impulsive = self.sys.has_impulsive();
        (self.force_contact && !impulsive)
            || self
                .states
                .iter()
                .any(|st| Self::penetrating(st) || (!impulsive && Self::at_onset(st)))
    }

    /// The piece of ground load at the current time, its start, and the end of the span the
    /// current step may not cross (the piece's end or the duration).
    fn piece(&self) -> (Piece, f64, f64) {
        let (piece, piece_end) = self.gm.piece_at(self.t);
        let start = match piece {
            Piece::Poly { t0, .. } => t0,
            _ => 0.0,
        };
        (piece, start, piece_end.min(self.duration))
    }
}

/// Mode j's particular solution (η_p, η̇_p) at τ into a step (sin, cos at that instant in `tr`),
/// the record's polynomial one from its coefficients `pcoef`.
#[inline(always)]
fn particular_at(
    gm: &GroundModes,
    piece: &Piece,
    harmonic: Option<(f64, &[f64], &[f64])>,
    pcoef: &[f64; 3],
    j: usize,
    tau: f64,
    tr: &Trig,
) -> (f64, f64) {
    match (piece, harmonic) {
        (Piece::Harmonic, Some((big, g_re, g_im))) => {
            let (gr, gi) = (g_re[j], g_im[j]);
            (gr * tr.s + gi * tr.c, big * (gr * tr.c - gi * tr.s))
        }
        (Piece::Poly { .. }, _) => {
            let [pa, pb, pc] = *pcoef;
            (pa + tau * (pb + tau * pc), pb + 2.0 * tau * pc)
        }
        (Piece::Zero, _) => (0.0, 0.0),
        _ => gm.particular(j, piece, &[0.0; 3], tau, tr),
    }
}

/// The largest value over x ∈ [0, 1] of `H(x) + 16 m x²(1 − x)²`, H the cubic Hermite through
/// (y0, d0) at 0 and (y1, d1) at h (x = τ/h): the bound of a function whose distance from
/// its Hermite interpolant is at most Hermite's remainder `max|f⁗| τ²(h − τ)²/24`, whose
/// largest value (at the middle) is m. The quartic's maximum is at an end or a root of its
/// derivative, a cubic: each interval on which that cubic is monotone (split at the roots of
/// its own derivative) is bisected where it changes sign.
fn quartic_bound(y0: f64, d0: f64, y1: f64, d1: f64, h: f64, m: f64) -> f64 {
    let (m0, m1) = (h * d0, h * d1);
    // g(x) = c4 x⁴ + c3 x³ + c2 x² + c1 x + c0
    let c4 = 16.0 * m;
    let c3 = 2.0 * y0 + m0 - 2.0 * y1 + m1 - 32.0 * m;
    let c2 = -3.0 * y0 - 2.0 * m0 + 3.0 * y1 - m1 + 16.0 * m;
    let (c1, c0) = (m0, y0);
    let g = |x: f64| (((c4 * x + c3) * x + c2) * x + c1) * x + c0;
    let dg = |x: f64| ((4.0 * c4 * x + 3.0 * c3) * x + 2.0 * c2) * x + c1;
    // g'' = 12 c4 x² + 6 c3 x + 2 c2: its roots split [0, 1] into monotone pieces of g'
    let mut cuts = [0.0, 1.0, 1.0, 1.0];
    let mut nc = 1;
    let (a, b, c) = (12.0 * c4, 6.0 * c3, 2.0 * c2);
    if a.abs() > 1e-300 {
        let disc = b * b - 4.0 * a * c;
        if disc > 0.0 {
            let r = disc.sqrt();
            let q = -0.5 * (b + b.signum() * r);
            for x in [q / a, c / q] {
                if x > 0.0 && x < 1.0 {
                    cuts[nc] = x;
                    nc += 1;
                }
            }
        }
    } else if b != 0.0 && (-c / b) > 0.0 && (-c / b) < 1.0 {
        cuts[nc] = -c / b;
        nc += 1;
    }
    cuts[nc] = 1.0;
    cuts[..=nc].sort_by(f64::total_cmp);
    let mut best = g(0.0).max(g(1.0));
    for w in cuts[..=nc].windows(2) {
        let (mut lo, mut hi) = (w[0], w[1]);
        let (glo, ghi) = (dg(lo), dg(hi));
        if glo.signum() == ghi.signum() {
            continue;
        }
        for _ in 0..50 {
            let mid = 0.5 * (lo + hi);
            if dg(mid).signum() == glo.signum() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        best = best.max(g(0.5 * (lo + hi)));
    }
    best
}

#[cfg(test)]
mod tests;

/// The step guard, on a parsed record suite (tests/data/jankowski-kink.toml).
#[cfg(test)]
mod step_guard {
    use super::tests::Quiet;
    use super::*;
    use crate::input::scenario::Scenario;

    /// The guard: with the kink floor off (`kink_floor_ulps = 0`, the defect of
    /// tests/data/jankowski-kink.toml back: a Jankowski switch re-found at every step's start,
    /// steps that do not move time) the run stops at once with `StepFailed`, naming exact-modal,
    /// the instant (t = 9.6066 s, where the located switch sits), the level in contact (the
    /// top, level 1: the only one penetrating there) and `adaptive`; with the floor on it runs
    /// to the end.
    #[test]
    fn a_step_that_cannot_advance_time_stops_the_run() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
        let text = include_str!("../../../../tests/data/jankowski-kink.toml");
        let suite = Scenario::from_toml(text, "jankowski-kink.toml", &dir).expect("valid");
        let members = suite.suite.as_ref().expect("a suite");
        let f = members.records[0].factor.expect("factor");
        let sc = members.member_scenario(&suite, 0, f).expect("scales");
        let sys = sc.system();
        // (the self-check's tolerance, 100× tighter than the default: the run that stalled)
        let settings = sc.solver.with_rtol(1e-10);
        let run = |floor: f64| {
            let (q0, v0) = InitialState::default().resolved(sys.len());
            let mut quiet = Quiet;
            let mut r = Elastic::new(&sys, &settings, &mut quiet, None, 0.0, q0, v0, None);
            r.kink_floor_ulps = floor;
            r.drive()
        };
        let e = run(0.0).expect_err("stops");
        let SolveError::StepFailed {
            method,
            t,
            level,
            height,
            reason,
            alternative,
            h,
        } = e.clone()
        else {
            panic!("{e}");
        };
        assert_eq!(
            (method, level, height, reason, alternative),
            (
                "exact-modal",
                Some(1),
                Some(14.0),
                crate::integrate::StepFailure::NoProgress,
                "adaptive"
            ),
            "{e}"
        );
        // (the located switch, to the ms of the trace that found it; the step that did not
        // advance t there was 2.9e-25 s, below t's resolution of 1.8e-15 s)
        assert!((t - 9.6066).abs() < 1e-3, "{e}");
        assert!(h > 0.0 && t + h == t, "{e}");
        let msg = e.to_string();
        for part in [
            "exact-modal",
            "t = 9.606",
            "contact level 1",
            "\"adaptive\"",
        ] {
            assert!(msg.contains(part), "{part} in {msg}");
        }
        let stats = run(KINK_FLOOR_ULPS).expect("runs with the floor");
        assert!(stats.steps > 0);
    }
}
