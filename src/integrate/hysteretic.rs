//! `adaptive` for systems with yielding storeys (issue 16): the embedded Dormand–Prince 5(4)
//! pair on the whole state — modal displacements η, velocities η̇ **and the hysteretic variables
//! z** — with error control over all three.
//!
//! Why not the exponential Lobatto collocation of [`super::adaptive`]: that method is exact
//! without contact and spends effort only on steps that carry contact forces, finding the nodal
//! forces by fixed-point iteration. A yielding storey's pseudo-force acts at every instant, and
//! its dependence on the drift through the quasi-static response of the stiff modes has a gain
//! close to (1 − α)·|z|ⁿ(β + γ) ≈ 1 − α when the storey yields, so that iteration would barely
//! converge. An explicit pair with the full state in its error norm is simple, robust and
//! error-controlled everywhere; its step is limited by the highest mode kept (ω_max·h ≲ 3.3,
//! which error control enforces on its own), an acceptable cost for shear buildings with tens
//! of floors.
//!
//! Non-smoothness: ż has a kink where ḋ z changes sign (unloading), and the contact laws have
//! one at δ = 0. Neither is located as an event here; the estimate, which includes every z,
//! sees the lower smoothness of a step across a kink and shrinks it (tested against the true
//! local error of each step in `tests`). Stereomechanical impulses are applied at step ends, as
//! with `rk4`.
//!
//! Norm: max over coordinates of |error| / (atol_j + rtol·max(|y₀|, |y₁|)); η and η̇ with the
//! tolerances of [`super::adaptive`] (atol in metres at a structure's top), z with
//! `atol / d_y` (an error of atol in the storey's drift). Tallies (input, damping, contact,
//! hysteretic work per storey, impulses) are integrated with the pair's fifth-order weights.

// Index loops over parallel per-coordinate arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::linear::GroundModes;
use super::{
    InitialState, Observer, SolveError, SolverSettings, Stats, StepTrace, StepView, Tally,
    update_onsets,
};
use crate::system::{LevelState, Powers, System};

/// Dormand–Prince nodes.
const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
/// Dormand–Prince coefficients (row i: stage i + 1 from stages 0..i).
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order weights (= the last row of A: first same as last).
const B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
/// Fifth- minus fourth-order weights: the local error estimate.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// Smallest step relative to `dt` before the tolerance is declared out of reach.
const MIN_STEP: f64 = 1e-12;

/// Work arrays, sized once (no allocation in the time loop).
struct Work {
    n: usize,
    ns: usize,
    /// State y = [η, η̇, z] and the trial end state.
    y: Vec<f64>,
    y1: Vec<f64>,
    ys: Vec<f64>,
    /// Stage derivatives `[stage][…]`, same layout as y.
    k: [Vec<f64>; 7],
    /// Stage powers per storey `[stage][s]`, stage forces `[stage][level]`.
    pw: [Vec<f64>; 7],
    force: [Vec<f64>; 7],
    powers: [Powers; 7],
    /// Tolerance scales of η, η̇ and z.
    aq: Vec<f64>,
    av: Vec<f64>,
    az: Vec<f64>,
    states: Vec<LevelState>,
    stage_states: Vec<LevelState>,
}

/// The derivative of y = [η, η̇, z] at time t into `k`, the powers, per-storey powers and level
/// states.
#[allow(clippy::too_many_arguments)]
#[inline]
fn deriv(
    sys: &System,
    t: f64,
    (n, ns): (usize, usize),
    y: &[f64],
    onset: &[f64],
    k: &mut [f64],
    pw: &mut [f64],
    states: &mut [LevelState],
) -> Powers {
    let (q, rest) = y.split_at(n);
    let (v, z) = rest.split_at(n);
    let (kq, rest) = k.split_at_mut(n);
    let (ka, kz) = rest.split_at_mut(n);
    kq.copy_from_slice(v);
    let mut p = sys.acceleration(t, q, v, onset, ka, states);
    if ns > 0 {
        p.hysteretic = sys.hysteresis.apply(q, v, z, ka, kz, pw);
    }
    p
}

pub(super) fn run<O: Observer>(
    sys: &System,
    settings: &SolverSettings,
    initial: &InitialState,
    observer: &mut O,
) -> Result<Stats, SolveError> {
    run_traced(sys, settings, initial, observer, None)
}

pub(crate) fn run_traced<O: Observer>(
    sys: &System,
    settings: &SolverSettings,
    initial: &InitialState,
    observer: &mut O,
    mut trace: Option<&mut Vec<StepTrace>>,
) -> Result<Stats, SolveError> {
    let n = sys.len();
    let ns = sys.hysteresis.len();
    let nl = sys.levels.len();
    let m = 2 * n + ns;
    let (q0, v0) = initial.resolved(n);
    let (aq, av) = super::adaptive::modal_tolerances(sys, settings.atol);
    let az = sys
        .hysteresis
        .storeys()
        .iter()
        .map(|s| settings.atol / s.dy)
        .collect();
    let mut y = vec![0.0; m];
    y[..n].copy_from_slice(&q0);
    y[n..2 * n].copy_from_slice(&v0);
    let mut w = Work {
        n,
        ns,
        y,
        y1: vec![0.0; m],
        ys: vec![0.0; m],
        k: std::array::from_fn(|_| vec![0.0; m]),
        pw: std::array::from_fn(|_| vec![0.0; ns]),
        force: std::array::from_fn(|_| vec![0.0; nl]),
        powers: [Powers::default(); 7],
        aq,
        av,
        az,
        states: vec![LevelState::default(); nl],
        stage_states: vec![LevelState::default(); nl],
    };
    let mut prev_states = vec![LevelState::default(); nl];
    let mut onset = vec![0.0; nl];
    let mut tally = Tally {
        impulse: vec![0.0; nl],
        storey_work: vec![0.0; ns],
        ..Tally::default()
    };
    let mut stats = Stats::default();
    let gm = GroundModes::new(sys);
    let dims = (n, ns);

    w.powers[0] = deriv(
        sys,
        0.0,
        dims,
        &w.y,
        &onset,
        &mut w.k[0],
        &mut w.pw[0],
        &mut w.states,
    );
    stats.evaluations += 1;
    for k in 0..nl {
        w.force[0][k] = w.states[k].force;
    }
    prev_states.copy_from_slice(&w.states);
    update_onsets(&mut onset, &prev_states, &w.states, 0.0);
    observe(sys, observer, 0.0, &w, &tally);

    let hmax = settings.dt;
    let rtol = settings.rtol;
    let duration = settings.duration;
    let mut h = hmax / 64.0;
    let mut t = 0.0;
    let mut rejected_last = false;
    while t < duration {
        let (_, piece_end) = gm.piece_at(t);
        let limit = piece_end.min(duration) - t;
        let to_limit = h >= limit * (1.0 - 1e-9);
        let hs = if to_limit { limit } else { h };
        // stages 2..7
        for i in 1..7 {
            for j in 0..m {
                let mut acc = 0.0;
                for (l, a) in A[i][..i].iter().enumerate() {
                    acc += a * w.k[l][j];
                }
                w.ys[j] = w.y[j] + hs * acc;
            }
            let (ki, pwi) = (&mut w.k[i], &mut w.pw[i]);
            w.powers[i] = deriv(
                sys,
                t + C[i] * hs,
                dims,
                &w.ys,
                &onset,
                ki,
                pwi,
                &mut w.stage_states,
            );
            for k in 0..nl {
                w.force[i][k] = w.stage_states[k].force;
            }
        }
        stats.evaluations += 6;
        // the stage-7 state is the fifth-order solution (FSAL)
        w.y1.copy_from_slice(&w.ys);
        let err = error_norm(&w, hs, rtol);
        if !(err <= 1.0) {
            stats.rejected += 1;
            let fac = if err.is_finite() {
                (0.9 * err.powf(-0.2)).clamp(0.2, 0.9)
            } else {
                0.25
            };
            h = hs * fac;
            rejected_last = true;
            if h < MIN_STEP * hmax {
                return Err(if err.is_finite() {
                    SolveError::ToleranceUnreachable { t, h: hs, rtol }
                } else {
                    SolveError::Diverged {
                        t,
                        contact_omega_dt: stats.max_contact_omega_dt,
                    }
                });
            }
            continue;
        }
        if let Some(log) = trace.as_deref_mut() {
            log.push(StepTrace {
                t,
                h: hs,
                q0: w.y[..n].to_vec(),
                v0: w.y[n..2 * n].to_vec(),
                onset: onset.clone(),
                q1: w.y1[..n].to_vec(),
                v1: w.y1[n..2 * n].to_vec(),
                err,
                kink: false,
                z0: w.y[2 * n..].to_vec(),
                z1: w.y1[2 * n..].to_vec(),
            });
        }
        // accept: tallies with the fifth-order weights
        for i in 0..7 {
            let b = hs * B[i];
            if b == 0.0 {
                continue;
            }
            let p = &w.powers[i];
            tally.input += b * p.input;
            tally.damping += b * p.damping;
            tally.contact += b * p.contact;
            tally.hysteretic += b * p.hysteretic;
            for s in 0..ns {
                tally.storey_work[s] += b * w.pw[i][s];
            }
            for k in 0..nl {
                tally.impulse[k] += b * w.force[i][k];
            }
        }
        std::mem::swap(&mut w.y, &mut w.y1);
        t = if to_limit { t + limit } else { t + hs };
        if to_limit && piece_end >= duration {
            t = duration;
        }
        // the last stage is the derivative at the new state (FSAL)
        w.k.swap(0, 6);
        w.pw.swap(0, 6);
        w.force.swap(0, 6);
        w.powers[0] = w.powers[6];
        prev_states.copy_from_slice(&w.states);
        w.states.copy_from_slice(&w.stage_states);
        if sys.has_impulsive() {
            let (_, rest) = w.y.split_at_mut(n);
            let v = &mut rest[..n];
            if sys.apply_impulses(v, &mut w.states, &mut tally.impulse, &mut tally.contact) {
                w.powers[0] = deriv(
                    sys,
                    t,
                    dims,
                    &w.y,
                    &onset,
                    &mut w.k[0],
                    &mut w.pw[0],
                    &mut w.states,
                );
                stats.evaluations += 1;
                for k in 0..nl {
                    w.force[0][k] = w.states[k].force;
                }
            }
        }
        update_onsets(&mut onset, &prev_states, &w.states, hs);
        for (lv, st) in sys.levels.iter().zip(&w.states) {
            if st.delta > 0.0 {
                let omega_c = (lv.force.tangent_stiffness(st.delta) / lv.effective_mass).sqrt();
                stats.max_contact_omega_dt = stats.max_contact_omega_dt.max(omega_c * hs);
            }
        }
        stats.steps += 1;
        observe(sys, observer, t, &w, &tally);
        // next step: elementary controller (no growth right after a rejection)
        let grow = if err > 0.0 {
            (0.9 * err.powf(-0.2)).clamp(0.2, 5.0)
        } else {
            5.0
        };
        let grow = if rejected_last { grow.min(1.0) } else { grow };
        rejected_last = false;
        h = (hs * grow).min(hmax);
    }
    Ok(stats)
}

/// The scaled max-norm of the embedded error estimate `h Σ E_i k_i` of the step just taken
/// (start `w.y`, end `w.y1`).
fn error_norm(w: &Work, h: f64, rtol: f64) -> f64 {
    let (n, ns) = (w.n, w.ns);
    let mut err: f64 = 0.0;
    for j in 0..2 * n + ns {
        let mut e = 0.0;
        for i in 0..7 {
            e += E[i] * w.k[i][j];
        }
        let e = (h * e).abs();
        let atol = if j < n {
            w.aq[j]
        } else if j < 2 * n {
            w.av[j - n]
        } else {
            w.az[j - 2 * n]
        };
        let scale = atol + rtol * w.y[j].abs().max(w.y1[j].abs());
        let r = e / scale;
        if r.is_nan() {
            return f64::INFINITY;
        }
        err = err.max(r);
    }
    err
}

fn observe<O: Observer>(sys: &System, observer: &mut O, t: f64, w: &Work, tally: &Tally) {
    let n = w.n;
    observer.observe(
        sys,
        &StepView {
            t,
            q: &w.y[..n],
            v: &w.y[n..2 * n],
            levels: &w.states,
            z: &w.y[2 * n..],
            tally,
        },
    );
}
