//! `exact-modal`: every mode's linear dynamics and the ground load propagated exactly over each
//! step (docs/model.md §2.4; see [`super::linear`]), with two ways of adding the contact load
//! `Σ_k c_kj F_k(t)` and the storeys' pseudo-forces:
//!
//! - **elastic structures** ([`elastic`], the default method's path): free flight in closed form
//!   between impacts, onsets located on it, and contact integrated by the embedded Lobatto
//!   collocation pair of [`super::collocation`] (the force a quartic over a step, order 8 kept,
//!   its order-6 companion the error estimate), step lengths chosen by that estimate against
//!   `rtol` ([`SubstepTolerance`]). See `elastic`'s own documentation.
//! - **yielding storeys** ([`Run::base_step_yielding`], below): the second-order
//!   predictor–corrector this file describes from here on.
//!
//! The predictor–corrector (yielding storeys): over a sub-step each load is linear in time, from
//! its value at the sub-step start to a predicted value at its end (PECE):
//!
//! 1. predict the end state with the loads held at their start values, evaluate them there;
//! 2. correct: the end state under the loads varying linearly (exact for such a load);
//! 3. evaluate the laws at the corrected state: they start the next sub-step.
//!
//! The scheme is second order in the sub-step; with no contact and no yielding it is exact for
//! any step and any number of modes. While a level is in contact, or may come into contact
//! within the base step, the base step `dt` is walked in dyadic sub-steps dt/2^m. Whether a
//! level may touch is decided on the cubic Hermite bound of δ over the step's free flight plus a
//! margin for the modes that oscillate within it (each mode's distance from its own cubic is at
//! most `(|λ|h)⁴/384` of its amplitude, capped at 2: without it a 1.8 ms impact inside a 10 ms
//! base step was missed). Each sub-step meets two rules:
//!
//! - **stability of the predictor:** `k_t·D(h_sub) ≤ α²/2` (α = [`SUBSTEP_ALPHA`]), k_t the
//!   tangent stiffness at the penetration bound of the sub-step's own free flight and D(h) the
//!   level's displacement under a unit force held for h (for a point mass `ω_c·h_sub ≤ α`).
//! - **accuracy:** its local error estimate ([`Run::estimate_yielding`]) within the tolerance
//!   `rtol` ([`SubstepTolerance`]).
//!
//! The walk refines when a rule fails and coarsens by one level when aligned and both rules
//! have room.

//! Steps split at the samples of a recorded motion (its load is a different polynomial on each
//! interval): each record interval is cut into equal steps ≤ dt.
//!
//! Yielding storeys (issue 16, [`Run::base_step_yielding`]): each storey's pseudo-force
//! P = (1 − α)k(d_y z − d) is a load `−e_s P` along its drift row, treated as a contact force is
//! (held at P₀ in the predictor, folded into the free flight; linear from P₀ to the predicted
//! P₁* in the corrector), and z is integrated by the trapezoidal rule in the same
//! predictor–corrector (z₁* = z₀ + h ż₀, z₁ = z₀ + h/2 (ż₀ + ż₁*), ż₁* at the predicted end),
//! second order. The pseudo-forces act at every instant, so every sub-step is estimated
//! ([`Run::estimate_yielding`]: the same two terms over all load rows, and z's own; the kinks of
//! ż — ḋz changing sign, z = 0 — are not located but covered by the estimate) and the walk
//! may use the base step itself (m ≥ 0) where no level may touch. Why not locate the kinks as
//! `adaptive`'s Dormand–Prince path does: a second-order rule's error across a kink of ż is
//! bounded by its curvature term enlarged by a known factor (see the estimate), which the test
//! `estimate_sees_the_true_local_error_with_yielding_storeys` confirms against the true local
//! error; the walk then refines around the kink on its own.
//!
//! Tallies of the predictor–corrector (the collocation's are in [`elastic`]): the work of the
//! ground load and the dissipation are computed exactly for the propagated solution (moments of η from the equation of motion, see
//! [`super::linear::mode_work`]); the work into the contacts, `∫F(δ)δ̇ dt` with the law's force,
//! by Simpson's rule on the cubic Hermite interpolant of δ, so that the energy balance measures
//! the error of the contact scheme (the mismatch between the linearly interpolated load and the
//! law along the computed motion); each yielding storey's work `∫ P ḋ dt` likewise by Simpson's
//! rule on the Hermite interpolants of d and z.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::linear::{
    ContactForms, GroundModes, HarmonicTally, Influence, LevelStep, Piece, StateSums, Trig,
    TrigMoments, influence, mode_work, monomial_influence, poly_coefficients, poly_mode_work,
};
use super::plan::EqualSteps;
use super::{
    InitialState, Integrator, Observer, SolveError, SolverSettings, Stats, StepTrace, StepView,
    Tally, update_onsets,
};
use crate::model::system::{LevelState, System, episode_v0};
use crate::numerics::hermite::hermite_max;
use crate::numerics::linalg::dot;

mod elastic;
mod run;
mod storeys;
use run::Run;
use storeys::{StoreyState, Yield};

/// Largest `ω_c·h_sub` of a contact sub-step of `exact-modal` (ω_c = √(k_t/m*), rad/s).
pub const SUBSTEP_ALPHA: f64 = 0.08;
/// `(α/α_onset)²`: sub-steps in which a level may come into contact keep `ω_c·h ≤ α/4`.
const ONSET_WEIGHT: f64 = 16.0;
/// Every base step in (or near) contact is cut into at least 2^2 sub-steps.
const MIN_LEVEL: u32 = 2;
/// At most 2^48 sub-steps per base step (the walk is logarithmic in the depth: a force that
/// jumps at an onset, as Kelvin's c·δ̇ does, is resolved in a few dozen sub-steps however
/// tight the tolerance; below dt/2^48 the estimate would measure round-off).
const MAX_LEVEL: u32 = 48;
const CACHE: usize = 16;
/// sin Ωt, cos Ωt are evaluated directly every this many base steps and advanced by rotations
/// in between (the rotations' rounding errors, about one ulp each, cannot accumulate).
const SYNC_EVERY: u32 = 16;

/// Everything that depends on the step length only.
struct StepData {
    h: f64,
    infl: Vec<Influence>,
    /// `M0[k·L + l] = Σ_j c_kj c_lj Γ0_j` (η and η̇ components): the response of level k's
    /// displacement to a unit constant force at level l, for the predictor.
    m0: Vec<(f64, f64)>,
    /// With yielding storeys, the same three tables over every *load row* r of the system:
    /// the contact levels' coupling rows c_k (r < L) and then the storeys' drift rows e_s
    /// (r = L + s), `[r·N + r']`, N = L + S: the response of `row_r · η` (and `row_r · η̇`) to
    /// a unit load along row r' held (`y0`), ramped (`y1`) or quadratic as `(τ/h)² − τ/h` (`y2`).
    y0: Vec<(f64, f64)>,
    y1: Vec<(f64, f64)>,
    y2: Vec<(f64, f64)>,
    /// Per mode, the bound of the free flight's distance from its cubic Hermite interpolant
    /// over the step per unit of |η − η_p| and of |η̇ − η̇_p| ([`hermite_gap_factor`]).
    herm: Vec<(f64, f64)>,
    /// The same for the harmonic particular solution (per unit of |η_p| + |η̇_p|/Ω).
    herm_part: f64,
    /// 1/h, 1/s.
    inv_h: f64,
    /// Harmonic motion: (sin Ωh, cos Ωh), to advance sin Ωt, cos Ωt over the step by a
    /// rotation instead of a libm call, and (sin Ωh/2, cos Ωh/2) for [`TrigMoments`].
    rot: (f64, f64),
    half: (f64, f64),
}

impl StepData {
    fn new(sys: &System, big: Option<f64>, h: f64) -> StepData {
        let (omega, damp) = (sys.omega(), sys.damping_coefficients());
        let infl: Vec<Influence> = (0..sys.len())
            .map(|j| influence(omega[j], damp[j], h))
            .collect();
        let nl = sys.levels.len();
        let ns = sys.hysteresis.len();
        // (Γ2 − Γ1) of every mode, only when there is contact or yielding to estimate
        let quad: Vec<(f64, f64)> = if nl + ns == 0 {
            Vec::new()
        } else {
            (0..sys.len())
                .map(|j| {
                    let g = monomial_influence(omega[j], damp[j], h, h, &infl[j].p);
                    (g[2].0 - g[1].0, g[2].1 - g[1].1)
                })
                .collect()
        };
        let [m0, _, _] = load_tables(nl, |k| sys.coupling(k), &infl, &quad);
        // the tables over every load row, with yielding storeys only
        let nr = if ns == 0 { 0 } else { nl + ns };
        let row = |r: usize| {
            if r < nl {
                sys.coupling(r)
            } else {
                sys.hysteresis.row(r - nl)
            }
        };
        let [y0, y1, y2] = load_tables(nr, row, &infl, &quad);
        let (rot, half) = big.map_or(((0.0, 1.0), (0.0, 1.0)), |big| {
            ((big * h).sin_cos(), (0.5 * big * h).sin_cos())
        });
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
                // amplitude of the complex exponential ≤ |x| + |ẋ|/|λ|·(1 + ζ)/√(1 − ζ²)
                // loosely: |x| + 2|ẋ|/|λ| covers ζ ≤ 0.6 and the overdamped roots
                (f, 2.0 * f / lam)
            })
            .collect();
        let herm_part = big.map_or(0.0, |b| hermite_gap_factor(b * h));
        StepData {
            h,
            herm,
            herm_part,
            infl,
            m0,
            y0,
            y1,
            y2,
            inv_h: 1.0 / h,
            rot,
            half,
        }
    }
}

/// The response tables of `n` load rows over a step: for rows a, b, `[a·n + b]` is the
/// response of `row_a · η` (and `row_a · η̇`) to a unit load along row b held over the step
/// (`Σ_j r_aj r_bj Γ0_j`), ramped as τ/h (`Γ1`) and quadratic as `(τ/h)² − τ/h` (`Γ2 − Γ1`,
/// given per mode in `quad`): `[held, ramped, quadratic]`.
fn load_tables<'r>(
    n: usize,
    row: impl Fn(usize) -> &'r [f64],
    infl: &[Influence],
    quad: &[(f64, f64)],
) -> [Vec<(f64, f64)>; 3] {
    let mut tables = [
        vec![(0.0, 0.0); n * n],
        vec![(0.0, 0.0); n * n],
        vec![(0.0, 0.0); n * n],
    ];
    for a in 0..n {
        for b in 0..n {
            let (ra, rb) = (row(a), row(b));
            let (mut s, mut r, mut e) = ((0.0, 0.0), (0.0, 0.0), (0.0, 0.0));
            for (j, (f, g)) in infl.iter().zip(quad).enumerate() {
                let w = ra[j] * rb[j];
                s.0 += w * f.g0.0;
                s.1 += w * f.g0.1;
                r.0 += w * f.g1.0;
                r.1 += w * f.g1.1;
                e.0 += w * g.0;
                e.1 += w * g.1;
            }
            tables[0][a * n + b] = s;
            tables[1][a * n + b] = r;
            tables[2][a * n + b] = e;
        }
    }
    tables
}

/// How far a free motion `Re(a e^{λt})` (|λ| = `lam_h`/h) can stray from the cubic Hermite
/// interpolant of its end values and slopes over a step h, per unit of |a|: the interpolation
/// error bound `max|x⁗| h⁴/384 = (|λ|h)⁴/384` (Hermite's remainder), capped at 2 (an
/// oscillation of amplitude |a| against a cubic through points on it).
fn hermite_gap_factor(lam_h: f64) -> f64 {
    (lam_h.powi(4) / 384.0).min(2.0)
}

/// A few step lengths' data, replaced round-robin.
pub(super) struct StepCache {
    entries: Vec<StepData>,
    next: usize,
}

impl StepCache {
    fn new() -> StepCache {
        StepCache {
            entries: Vec::with_capacity(CACHE),
            next: 0,
        }
    }

    fn index(&mut self, sys: &System, big: Option<f64>, h: f64) -> usize {
        if let Some(i) = self.entries.iter().position(|e| e.h == h) {
            return i;
        }
        let d = StepData::new(sys, big, h);
        if self.entries.len() < CACHE {
            self.entries.push(d);
            self.entries.len() - 1
        } else {
            let i = self.next;
            self.entries[i] = d;
            self.next = (i + 1) % CACHE;
            i
        }
    }
}

/// What the contact sub-steps are held to: per level, an error of the penetration δ of
/// `atol + rtol·|w₁(h) − w₂(h)|` (m) and of its rate δ̇ of `atol·ω₁ + rtol·v` (m/s, ω₁ the
/// larger first-mode frequency, v the larger of |δ̇| and the episode's approach speed).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SubstepTolerance {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance on δ, m.
    pub atol: f64,
    /// Absolute tolerance on δ̇, m/s.
    pub atol_rate: f64,
}

impl SubstepTolerance {
    pub(crate) fn new(sys: &System, settings: &SolverSettings) -> SubstepTolerance {
        let w1 = sys
            .structures
            .iter()
            .filter_map(|s| s.omega.first().copied())
            .fold(0.0f64, f64::max);
        SubstepTolerance {
            rtol: settings.rtol,
            atol: settings.atol,
            atol_rate: settings.atol * w1,
        }
    }
}

/// `exact-modal`: see the module.
pub(super) struct ExactModal;

impl Integrator for ExactModal {
    fn run<'a, O: Observer>(
        sys: &'a System,
        settings: &SolverSettings,
        initial: &InitialState,
        observer: &'a mut O,
        trace: Option<&'a mut Vec<StepTrace>>,
    ) -> Result<Stats, SolveError> {
        if sys.hysteresis.is_empty() {
            return elastic::run(sys, settings, initial, observer, trace);
        }
        let (q0, v0) = initial.resolved(sys.len());
        let mut r = Run::new(sys, settings, observer, trace, 0.0, q0, v0, None);
        r.observe(0.0);

        let duration = settings.duration;
        let mut t = 0.0;
        while t < duration {
            let (piece, piece_end) = r.gm.piece_at(t);
            let plan = EqualSteps::new(t, piece_end.min(duration), settings.base_step());
            for i in 0..plan.steps as usize {
                let (ts, te) = plan.bounds(i);
                r.base_step(ts, te - ts, &piece)?;
            }
            t = plan.end;
        }
        r.stats.max_contact_omega_dt = r.max_contact_w2h2.sqrt();
        Ok(r.stats)
    }
}

#[cfg(test)]
mod tests;
