//! `adaptive`: Dormand–Prince 5(4) in the interaction picture (a Lawson Runge–Kutta method).
//!
//! Each mode's linear dynamics and the ground load are propagated exactly (see
//! [`super::linear`]): the free flight `Φ(τ)y` is exact for any τ. The Runge–Kutta pair only
//! integrates the contact coupling: with `N(y) = (0, Σ_k c_k F_k)` the stages are
//!
//! `Y_i = Φ(c_i h) y_n + h Σ_{j<i} a_ij P((c_i − c_j)h) N(Y_j)`,
//!
//! so a step without contact forces has zero error and is as long as allowed (`dt`, the largest
//! step), for any number of modes: the step size is set by the contact, not by the highest
//! mode. Error control: the embedded 4th-order solution's difference, in the max norm over every
//! modal coordinate scaled by `atol_j + rtol·|y_j|` (atol per structure from the user's metres,
//! see [`super::SolverSettings::atol`]), Hairer's PI controller; step sizes are quantised to
//! `dt·2^(−k/4)` so that the stage propagators are computed once per size and reused.
//!
//! Events: when a level's penetration δ changes sign over an accepted step, the step is
//! replaced by one that ends where δ = 0 (root of δ at the end of a step of length s, found by
//! the Illinois method starting from the cubic Hermite estimate; |δ| ≤ 1e-12 m), so no step
//! straddles the kink of the contact law, and the observation falls on the event.
//!
//! Tallies: over steps without contact forces the exact work and dissipation of
//! [`super::linear::mode_work`]; over steps with contact the stage powers combined with the
//! 5th-order weights.
//!
//! Steps split at the samples of a recorded motion.

use super::linear::{GroundModes, Piece, Prop, hermite_max, mode_work, propagator};
use super::{
    InitialState, Observer, SolveError, SolverSettings, Stats, StepView, Tally, update_onsets,
};
use crate::system::{LevelState, System, dot};

const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
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
const B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
const BHAT: [f64; 7] = [
    5179.0 / 57600.0,
    0.0,
    7571.0 / 16695.0,
    393.0 / 640.0,
    -92097.0 / 339200.0,
    187.0 / 2100.0,
    1.0 / 40.0,
];
/// Event tolerance on δ, m.
const EVENT_TOL: f64 = 1e-12;
/// Quantisation of step sizes: h = dt·2^(−k/QUANT).
const QUANT: f64 = 4.0;
const MAX_K: usize = 240;

/// The distinct stage fractions c_i − c_j (j < i) and the index of each pair.
struct Fractions {
    values: Vec<f64>,
    index: [[usize; 7]; 7],
}

impl Fractions {
    fn new() -> Fractions {
        let mut values: Vec<f64> = Vec::new();
        let mut index = [[0; 7]; 7];
        for i in 1..7 {
            for j in 0..i {
                let f = C[i] - C[j];
                let k = match values.iter().position(|&x| (x - f).abs() < 1e-15) {
                    Some(k) => k,
                    None => {
                        values.push(f);
                        values.len() - 1
                    }
                };
                index[i][j] = k;
            }
        }
        Fractions { values, index }
    }
}

/// Propagators of every mode for every stage fraction of one step size: `[f·n + j]`.
fn stage_props(sys: &System, fr: &Fractions, h: f64, out: &mut Vec<Prop>) {
    let (omega, damp) = (sys.omega(), sys.damping_coefficients());
    let n = sys.len();
    out.clear();
    for &f in &fr.values {
        for j in 0..n {
            out.push(propagator(omega[j], damp[j], f * h));
        }
    }
}

/// Result of one Lawson step (into the work arrays).
#[derive(Debug, Clone, Copy)]
struct Trial {
    err: f64,
    /// Weighted stage powers: input, damping, contact (already × h).
    input: f64,
    damping: f64,
    contact: f64,
}

struct Work {
    n: usize,
    nl: usize,
    q: Vec<f64>,
    v: Vec<f64>,
    qn: Vec<f64>,
    vn: Vec<f64>,
    /// Ground particular at the step start.
    p0: Vec<(f64, f64)>,
    cpoly: Vec<[f64; 3]>,
    /// Stage contact loads g_l[j] (7·n) and forces F_lk (7·nl).
    g: Vec<f64>,
    f: Vec<f64>,
    /// Per-level impulse weights of the trial.
    imp: Vec<f64>,
    aq: Vec<f64>,
    av: Vec<f64>,
    dots: Vec<(f64, f64)>,
}

#[allow(clippy::too_many_arguments)]
fn lawson(
    sys: &System,
    gm: &GroundModes,
    fr: &Fractions,
    props: &[Prop],
    w: &mut Work,
    onset: &[f64],
    f_start: &[LevelState],
    t: f64,
    h: f64,
    piece: &Piece,
    rtol: f64,
) -> Trial {
    let (n, nl) = (w.n, w.nl);
    let tr0 = gm.trig(t);
    let poly = matches!(piece, Piece::Poly { .. });
    for j in 0..n {
        let c = if poly {
            gm.poly_load(j, piece, t)
        } else {
            [0.0; 3]
        };
        w.cpoly[j] = c;
        w.p0[j] = gm.particular(j, piece, &c, 0.0, &tr0);
    }
    // stage 1: the start state (FSAL forces)
    for k in 0..nl {
        w.f[k] = f_start[k].force;
    }
    fill_g(sys, w, 0);
    let damp = sys.damping_coefficients();
    let mut pw = [[0.0; 3]; 7];
    {
        let (ag, vg) = sys.ground.accel_velocity(t);
        let (mut pi, mut pd) = (0.0, 0.0);
        let (la, lv) = (sys.ground_load(), sys.air_load());
        for j in 0..n {
            pi += (la[j] * ag + lv[j] * vg) * w.v[j];
            pd += damp[j] * w.v[j] * w.v[j];
        }
        let mut pc = 0.0;
        for k in 0..nl {
            pc += f_start[k].force * f_start[k].delta_dot;
        }
        pw[0] = [pi, pd, pc];
    }
    for s in 1..7 {
        let ts = t + C[s] * h;
        let tr = gm.trig(ts);
        let tau = C[s] * h;
        let ff = fr.index[s][0];
        let (mut pi, mut pd) = (0.0, 0.0);
        for d in w.dots.iter_mut() {
            *d = (0.0, 0.0);
        }
        for j in 0..n {
            let p = &props[ff * n + j];
            let (e0, d0) = w.p0[j];
            let (x0, y0) = p.apply(w.q[j] - e0, w.v[j] - d0);
            let (e1, d1) = gm.particular(j, piece, &w.cpoly[j], tau, &tr);
            let (mut x, mut y) = (x0 + e1, y0 + d1);
            for l in 0..s {
                let a = A[s][l];
                let gl = w.g[l * n + j];
                if a != 0.0 && gl != 0.0 {
                    let pl = &props[fr.index[s][l] * n + j];
                    let coef = h * a * gl;
                    x += pl.p12 * coef;
                    y += pl.p22 * coef;
                }
            }
            for k in 0..nl {
                let c = sys.coupling(k)[j];
                w.dots[k].0 += c * x;
                w.dots[k].1 += c * y;
            }
            pi += gm.load(j, piece, &w.cpoly[j], tau, &tr) * y;
            pd += damp[j] * y * y;
            if s == 6 {
                w.qn[j] = x;
                w.vn[j] = y;
            }
        }
        let mut pc = 0.0;
        for (k, lv) in sys.levels.iter().enumerate() {
            let delta = -w.dots[k].0 - lv.gap;
            let dd = -w.dots[k].1;
            let v0 = if onset[k] > 0.0 { onset[k] } else { dd };
            let f = lv.force.force(delta, dd, v0);
            w.f[s * nl + k] = f;
            pc += f * dd;
        }
        fill_g(sys, w, s);
        pw[s] = [pi, pd, pc];
    }
    // error of the embedded pair: h Σ (b − b̂)_l P((1 − c_l)h) N_l, max norm
    let mut err: f64 = 0.0;
    let any = w.g.iter().any(|&x| x != 0.0);
    if any {
        for j in 0..n {
            let (mut eq, mut ev) = (0.0, 0.0);
            for l in 0..7 {
                let e = B[l] - BHAT[l];
                let gl = w.g[l * n + j];
                if e != 0.0 && gl != 0.0 {
                    let p = if l == 6 {
                        Prop::IDENTITY
                    } else {
                        props[fr.index[6][l] * n + j]
                    };
                    eq += e * p.p12 * gl;
                    ev += e * p.p22 * gl;
                }
            }
            let sq = w.aq[j] + rtol * w.q[j].abs().max(w.qn[j].abs());
            let sv = w.av[j] + rtol * w.v[j].abs().max(w.vn[j].abs());
            err = err.max((h * eq).abs() / sq).max((h * ev).abs() / sv);
        }
    }
    let mut t_out = Trial {
        err,
        input: 0.0,
        damping: 0.0,
        contact: 0.0,
    };
    for l in 0..7 {
        t_out.input += h * B[l] * pw[l][0];
        t_out.damping += h * B[l] * pw[l][1];
        t_out.contact += h * B[l] * pw[l][2];
    }
    for k in 0..nl {
        w.imp[k] = (0..7).map(|l| h * B[l] * w.f[l * nl + k]).sum();
    }
    t_out
}

fn fill_g(sys: &System, w: &mut Work, s: usize) {
    let (n, nl) = (w.n, w.nl);
    let g = &mut w.g[s * n..(s + 1) * n];
    g.iter_mut().for_each(|x| *x = 0.0);
    for k in 0..nl {
        let f = w.f[s * nl + k];
        if f != 0.0 {
            for (gj, c) in g.iter_mut().zip(sys.coupling(k)) {
                *gj += c * f;
            }
        }
    }
}

pub(super) fn run<O: Observer>(
    sys: &System,
    settings: &SolverSettings,
    initial: &InitialState,
    observer: &mut O,
) -> Result<Stats, SolveError> {
    let n = sys.len();
    let nl = sys.levels.len();
    let gm = GroundModes::new(sys);
    let fr = Fractions::new();
    let pick = |x: &Vec<f64>| {
        if x.len() == n {
            x.clone()
        } else {
            vec![0.0; n]
        }
    };
    // absolute tolerances in modal units (SolverSettings::atol)
    let mut aq = vec![0.0; n];
    let mut av = vec![0.0; n];
    let n1 = sys.n1();
    for (i, s) in sys.structures.iter().enumerate() {
        let scale = settings.atol * (s.mass_per_length * s.length).sqrt() / 2.0;
        let w1 = s.omega.first().copied().unwrap_or(1.0);
        let range = if i == 0 { 0..n1 } else { n1..n };
        for j in range {
            aq[j] = scale;
            av[j] = scale * w1;
        }
    }
    let mut w = Work {
        n,
        nl,
        q: pick(&initial.q),
        v: pick(&initial.v),
        qn: vec![0.0; n],
        vn: vec![0.0; n],
        p0: vec![(0.0, 0.0); n],
        cpoly: vec![[0.0; 3]; n],
        g: vec![0.0; 7 * n],
        f: vec![0.0; 7 * nl],
        imp: vec![0.0; nl],
        aq,
        av,
        dots: vec![(0.0, 0.0); nl],
    };
    let mut states = vec![LevelState::default(); nl];
    let mut prev_states = states.clone();
    let mut onset = vec![0.0; nl];
    let mut tally = Tally {
        impulse: vec![0.0; nl],
        ..Tally::default()
    };
    let mut stats = Stats::default();
    let eval_states = |q: &[f64], v: &[f64], onset: &[f64], states: &mut [LevelState]| {
        for (k, lv) in sys.levels.iter().enumerate() {
            let c = sys.coupling(k);
            let delta = -dot(c, q) - lv.gap;
            let dd = -dot(c, v);
            let v0 = if onset[k] > 0.0 { onset[k] } else { dd };
            states[k] = LevelState {
                delta,
                delta_dot: dd,
                force: lv.force.force(delta, dd, v0),
            };
        }
    };
    eval_states(&w.q, &w.v, &onset, &mut states);
    let s0 = states.clone();
    update_onsets(&mut onset, &s0, &states);
    observer.observe(
        sys,
        &StepView {
            t: 0.0,
            q: &w.q,
            v: &w.v,
            levels: &states,
            tally: &tally,
        },
    );

    let duration = settings.duration;
    let hmax = settings.dt;
    let rtol = settings.rtol;
    let mut cache: Vec<Option<Vec<Prop>>> = (0..=MAX_K).map(|_| None).collect();
    let mut scratch: Vec<Prop> = Vec::with_capacity(fr.values.len() * n);
    let mut scratch_h = f64::NAN;
    let mut k_step: usize = 0; // proposed h = hmax·2^(−k/4)
    let mut err_old: f64 = 1e-4;
    let mut t = 0.0;
    let mut rejected_last = false;
    while t < duration {
        let (piece, piece_end) = gm.piece_at(t);
        let limit = piece_end.min(duration) - t;
        let hq = hmax * (-(k_step as f64) / QUANT).exp2();
        // clip at a breakpoint (snap when within a hair)
        let (h, quantised) = if hq >= limit * (1.0 - 1e-9) {
            (limit, false)
        } else {
            (hq, true)
        };
        let props: &[Prop] = if quantised {
            if cache[k_step].is_none() {
                let mut v = Vec::with_capacity(fr.values.len() * n);
                stage_props(sys, &fr, h, &mut v);
                cache[k_step] = Some(v);
            }
            cache[k_step].as_deref().unwrap_or(&[])
        } else {
            if scratch_h != h {
                stage_props(sys, &fr, h, &mut scratch);
                scratch_h = h;
            }
            &scratch
        };
        // a step without contact forces (now, at the end, or on the cubic between) is exact
        let free = if nl == 0 {
            free_step(&gm, &fr, props, &mut w, t, h, &piece);
            true
        } else {
            free_step_possible(sys, &gm, &fr, props, &mut w, &states, t, h, &piece)
        };
        let (trial, h_taken) = if free {
            free_step(&gm, &fr, props, &mut w, t, h, &piece);
            (
                Trial {
                    err: 0.0,
                    input: f64::NAN,
                    damping: 0.0,
                    contact: 0.0,
                },
                h,
            )
        } else {
            let tr = lawson(
                sys, &gm, &fr, props, &mut w, &onset, &states, t, h, &piece, rtol,
            );
            stats.evaluations += 6;
            if tr.err > 1.0 || !tr.err.is_finite() {
                // reject: shrink, and do not grow on the next try
                stats.rejected += 1;
                let fac = if tr.err.is_finite() {
                    (0.9 * tr.err.powf(-0.2)).clamp(0.2, 0.9)
                } else {
                    0.2
                };
                k_step = quantise_down(hq * fac, hmax).max(k_step + 1).min(MAX_K);
                rejected_last = true;
                if k_step == MAX_K && !tr.err.is_finite() {
                    return Err(SolveError::Diverged {
                        t,
                        contact_omega_dt: stats.max_contact_omega_dt,
                    });
                }
                continue;
            }
            // a sign change of δ over the step: end the step at the event instead
            match first_crossing(sys, &states, &w) {
                Some((k, s_guess)) => {
                    let (tr2, s) = locate_event(
                        sys,
                        &gm,
                        &fr,
                        &mut w,
                        &onset,
                        &states,
                        t,
                        h,
                        &piece,
                        rtol,
                        k,
                        s_guess,
                        &mut scratch,
                        &mut scratch_h,
                        &mut stats,
                    );
                    stats.events += 1;
                    (tr2, s)
                }
                None => (tr, h),
            }
        };
        // accept
        if trial.input.is_nan() {
            // exact tallies of a step without contact
            let tm = match piece {
                Piece::Harmonic => gm
                    .harmonic_omega()
                    .map(|big| super::linear::TrigMoments::new(big, t, h_taken)),
                _ => None,
            };
            let (mut input, mut damping) = (0.0, 0.0);
            for j in 0..n {
                let ground = match piece {
                    Piece::Harmonic => None,
                    _ => Some(&w.cpoly[j]),
                };
                let m = mode_work(
                    &gm,
                    j,
                    h_taken,
                    (w.q[j], w.v[j]),
                    (w.qn[j], w.vn[j]),
                    ground,
                    tm.as_ref(),
                    0.0,
                    0.0,
                );
                input += m.input;
                damping += m.damping;
            }
            tally.input += input;
            tally.damping += damping;
        } else {
            tally.input += trial.input;
            tally.damping += trial.damping;
            tally.contact += trial.contact;
            for k in 0..nl {
                tally.impulse[k] += w.imp[k];
            }
        }
        std::mem::swap(&mut w.q, &mut w.qn);
        std::mem::swap(&mut w.v, &mut w.vn);
        t = if h_taken == limit {
            t + limit
        } else {
            t + h_taken
        };
        prev_states.copy_from_slice(&states);
        eval_states(&w.q, &w.v, &onset, &mut states);
        update_onsets(&mut onset, &prev_states, &states);
        for (lv, st) in sys.levels.iter().zip(&states) {
            if st.delta > 0.0 {
                let wc = (lv.force.tangent_stiffness(st.delta) / lv.effective_mass).sqrt();
                stats.max_contact_omega_dt = stats.max_contact_omega_dt.max(wc * h_taken);
            }
        }
        stats.steps += 1;
        if !(w.q.iter().sum::<f64>().is_finite() && w.v.iter().sum::<f64>().is_finite()) {
            return Err(SolveError::Diverged {
                t,
                contact_omega_dt: stats.max_contact_omega_dt,
            });
        }
        observer.observe(
            sys,
            &StepView {
                t,
                q: &w.q,
                v: &w.v,
                levels: &states,
                tally: &tally,
            },
        );
        // next step size (PI controller, Hairer & Wanner II.4)
        let err = trial.err.max(1e-10);
        let mut fac = 0.9 * err.powf(-0.17) * err_old.powf(0.04);
        fac = fac.clamp(0.2, 5.0);
        if rejected_last {
            fac = fac.min(1.0);
        }
        err_old = err.max(1e-4);
        rejected_last = false;
        if quantised || h_taken == hq {
            k_step = quantise_down(hq * fac, hmax);
        }
    }
    Ok(stats)
}

/// Smallest k with hmax·2^(−k/4) ≤ h.
fn quantise_down(h: f64, hmax: f64) -> usize {
    if h >= hmax {
        return 0;
    }
    let k = (QUANT * (hmax / h).log2()).ceil();
    if k.is_finite() {
        (k as usize).min(MAX_K)
    } else {
        MAX_K
    }
}

/// Free flight over h into (qn, vn).
fn free_step(
    gm: &GroundModes,
    fr: &Fractions,
    props: &[Prop],
    w: &mut Work,
    t: f64,
    h: f64,
    piece: &Piece,
) {
    let n = w.n;
    let ff = fr.index[6][0];
    let (tr0, tr1) = (gm.trig(t), gm.trig(t + h));
    let poly = matches!(piece, Piece::Poly { .. });
    for j in 0..n {
        let c = if poly {
            gm.poly_load(j, piece, t)
        } else {
            [0.0; 3]
        };
        w.cpoly[j] = c;
        let (e0, d0) = gm.particular(j, piece, &c, 0.0, &tr0);
        let (e1, d1) = gm.particular(j, piece, &c, h, &tr1);
        let (x, y) = props[ff * n + j].apply(w.q[j] - e0, w.v[j] - d0);
        w.qn[j] = x + e1;
        w.vn[j] = y + d1;
    }
}

/// True if no level is in contact at the start and the free flight keeps every δ negative
/// (ends and cubic Hermite maximum); then (qn, vn) holds the free flight.
#[allow(clippy::too_many_arguments)]
fn free_step_possible(
    sys: &System,
    gm: &GroundModes,
    fr: &Fractions,
    props: &[Prop],
    w: &mut Work,
    states: &[LevelState],
    t: f64,
    h: f64,
    piece: &Piece,
) -> bool {
    if states.iter().any(|s| s.force != 0.0 || s.delta > 0.0) {
        return false;
    }
    free_step(gm, fr, props, w, t, h, piece);
    for (k, lv) in sys.levels.iter().enumerate() {
        let c = sys.coupling(k);
        let d1 = -dot(c, &w.qn) - lv.gap;
        let dd1 = -dot(c, &w.vn);
        let (m, _) = hermite_max(states[k].delta, states[k].delta_dot, d1, dd1, h);
        if m >= 0.0 {
            return false;
        }
    }
    true
}

/// The level whose δ changes sign first over the step (start: `states`, end: (qn, vn)) and the
/// fraction of the step where the cubic Hermite of δ crosses 0.
fn first_crossing(sys: &System, states: &[LevelState], w: &Work) -> Option<(usize, f64)> {
    let mut best: Option<(usize, f64)> = None;
    for (k, lv) in sys.levels.iter().enumerate() {
        let c = sys.coupling(k);
        let d0 = states[k].delta;
        let d1 = -dot(c, &w.qn) - lv.gap;
        let crossing = (d0 < -EVENT_TOL && d1 > 0.0) || (d0 > EVENT_TOL && d1 <= 0.0);
        if !crossing {
            continue;
        }
        let dd0 = states[k].delta_dot;
        let dd1 = -dot(c, &w.vn);
        // root of the Hermite cubic by bisection on θ (bracket [0, 1])
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            let y = super::linear::hermite(d0, dd0, d1, dd1, 1.0, mid);
            if (y > 0.0) == (d0 > 0.0) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let th = 0.5 * (lo + hi);
        if best.is_none_or(|b| th < b.1) {
            best = Some((k, th));
        }
    }
    best
}

/// Find s ∈ (0, h) with δ_k = 0 at the end of a Lawson step of length s (Illinois), and leave
/// that step's result in (qn, vn). Returns the trial and s.
#[allow(clippy::too_many_arguments)]
fn locate_event(
    sys: &System,
    gm: &GroundModes,
    fr: &Fractions,
    w: &mut Work,
    onset: &[f64],
    states: &[LevelState],
    t: f64,
    h: f64,
    piece: &Piece,
    rtol: f64,
    k: usize,
    theta: f64,
    scratch: &mut Vec<Prop>,
    scratch_h: &mut f64,
    stats: &mut Stats,
) -> (Trial, f64) {
    let lv = &sys.levels[k];
    let d_at = |w: &Work| -dot(sys.coupling(k), &w.qn) - lv.gap;
    let (mut a, mut fa) = (0.0, states[k].delta);
    let (mut b, mut fb) = (h, d_at(w));
    let mut s = (theta * h).clamp(1e-6 * h, h * (1.0 - 1e-6));
    let mut side = 0;
    let mut last = None;
    for _ in 0..40 {
        stage_props(sys, fr, s, scratch);
        *scratch_h = s;
        let tr = lawson(sys, gm, fr, scratch, w, onset, states, t, s, piece, rtol);
        stats.evaluations += 6;
        let fs = d_at(w);
        last = Some((tr, s));
        if fs.abs() <= EVENT_TOL || (b - a) <= 1e-15 * (t + h) {
            break;
        }
        if (fs > 0.0) == (fa > 0.0) {
            a = s;
            fa = fs;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = s;
            fb = fs;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
        s = (a * fb - b * fa) / (fb - fa);
        if !(s > a && s < b) {
            s = 0.5 * (a + b);
        }
    }
    last.unwrap_or((
        Trial {
            err: 0.0,
            input: 0.0,
            damping: 0.0,
            contact: 0.0,
        },
        h,
    ))
}
