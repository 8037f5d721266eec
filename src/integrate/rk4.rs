//! Fixed-step classical Runge–Kutta (docs/model.md §2.9), with the energy flows and impulses integrated
//! by the same stage weights.

use super::{
    InitialState, Observer, SolveError, SolverSettings, Stats, StepView, Tally, step_plan,
    update_onsets,
};
use crate::model::contact::ContactForce;
use crate::model::system::{LevelState, Powers, System};

/// |R(z)| of RK4, `R(z) = 1 + z + z²/2 + z³/6 + z⁴/24`, for complex z = x + iy.
fn rk4_gain(x: f64, y: f64) -> f64 {
    // Horner in complex arithmetic: R = 1 + z(1 + z/2(1 + z/3(1 + z/4)))
    let mut re = 1.0;
    let mut im = 0.0;
    for k in [4.0, 3.0, 2.0, 1.0] {
        // (re, im) ← 1 + (x + iy)(re, im)/k
        let nr = 1.0 + (x * re - y * im) / k;
        let ni = (x * im + y * re) / k;
        re = nr;
        im = ni;
    }
    re.hypot(im)
}

/// Largest s such that RK4 is stable for z = s·u along the unit direction u = (ux, uy) from 0.
/// Scans outward, then bisects the first crossing of |R| = 1.
///
/// Memoised per thread (the last few directions): the scan costs ~50 µs, and scenarios and
/// sweeps ask for the same damping ratio over and over (every mode, every case, each run).
fn limit_along(ux: f64, uy: f64) -> f64 {
    use std::cell::RefCell;
    thread_local! {
        static MEMO: RefCell<Vec<(u64, u64, f64)>> = const { RefCell::new(Vec::new()) };
    }
    let key = (ux.to_bits(), uy.to_bits());
    if let Some(s) = MEMO.with_borrow(|m| m.iter().find(|e| (e.0, e.1) == key).map(|e| e.2)) {
        return s;
    }
    let s = scan_limit_along(ux, uy);
    MEMO.with_borrow_mut(|m| {
        if m.len() >= 16 {
            m.remove(0);
        }
        m.push((key.0, key.1, s));
    });
    s
}

fn scan_limit_along(ux: f64, uy: f64) -> f64 {
    let ds = 1e-3;
    let mut s = ds;
    while s < 4.0 {
        if rk4_gain(s * ux, s * uy) > 1.0 + 1e-13 {
            let (mut lo, mut hi) = (s - ds, s);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if rk4_gain(mid * ux, mid * uy) > 1.0 + 1e-13 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return lo;
        }
        s += ds;
    }
    4.0
}

/// Largest stable RK4 step for a linear oscillator `η̈ + 2ζωη̇ + ω²η = 0`, s.
/// For ζ = 0 it is `2√2/ω` (docs/model.md §2.9).
pub fn rk4_stability_limit(omega: f64, zeta: f64) -> f64 {
    // eigenvalues λ = ω(−ζ ± i√(1−ζ²)) or ω(−ζ ± √(ζ²−1))
    if zeta < 1.0 {
        let (ux, uy) = (-zeta, (1.0 - zeta * zeta).sqrt());
        limit_along(ux, uy) / omega
    } else {
        let fast = omega * (zeta + (zeta * zeta - 1.0).sqrt());
        limit_along(-1.0, 0.0) / fast
    }
}

/// Largest stable RK4 step over every mode of `system`, and the index of the limiting mode.
pub fn rk4_max_stable_dt(system: &System) -> (f64, usize) {
    let omega = system.omega();
    let damp = system.damping_coefficients();
    let mut best = (f64::INFINITY, 0);
    for j in 0..omega.len() {
        let dt = rk4_stability_limit(omega[j], damp[j] / (2.0 * omega[j]));
        if dt < best.0 {
            best = (dt, j);
        }
    }
    best
}

/// Safety factor of the largest stable step that a refusal in contact suggests
/// ([`SolveError::ContactUnstable`]): the estimate is for the impact met, and other impacts of
/// the same run (and of a run at the smaller step, whose impacts differ) may be harder.
const CONTACT_DT_MARGIN: f64 = 0.7;

/// `ω·dt` below which every mode whose damping ratio is at most [`PRECHECK_ZETA`] is stable:
/// RK4's limit along those directions is ≥ 2.62 (2√2 undamped, 2.62 at ζ ≈ 0.5; tested below).
const PRECHECK_OMEGA_DT: f64 = 2.6;
/// See [`PRECHECK_OMEGA_DT`].
const PRECHECK_ZETA: f64 = 0.9;

/// The stiffest mode of the system linearised about a contact state at one level.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ContactMode {
    /// Its natural frequency, rad/s.
    omega: f64,
    /// Its damping ratio (Rayleigh quotient of the damping on the undamped mode shape).
    zeta: f64,
}

/// The stiffest mode of the system linearised about a contact at level `k` with tangent
/// stiffness `kt` (N/m) and tangent damping `ct` (N·s/m): the largest eigenvalue λ of
/// `K = diag(ω_j²) + k_t c cᵀ` (unit modal masses, c the level's coupling row) among the modes
/// the contact couples, from the secular equation `1 = k_t Σ_j c_j²/(λ − ω_j²)` on
/// `(ω*², ω*² + k_t|c|²]` (ω* the stiffest coupled mode; `k_t|c|² = ω_c²`). Its shape is
/// `u_j ∝ c_j/(λ − ω_j²)` and its damping ratio `uᵀCu/(2√λ uᵀu)` with
/// `C = diag(2ζ_jω_j) + c_t c cᵀ`. So the frequency lies between `max(ω_c, ω*)` (Rayleigh quotient
/// of c) and `√(ω_c² + ω*²)` (Weyl): the contact alone (ω_c) misses the modes' own stiffness, the
/// upper bound overstates it, and as the contact vanishes the mode tends to the structural mode
/// ω*, ζ* that [`SolverSettings::check_stability`](super::SolverSettings::check_stability) has
/// already accepted. `None` when the contact is negligible (k_t|c|² ≤ 1e-12 ω*²) or couples no
/// mode: the modes are then those already checked.
fn contact_mode(sys: &System, k: usize, kt: f64, ct: f64) -> Option<ContactMode> {
    let c = sys.coupling(k);
    let omega = sys.omega();
    let damp = sys.damping_coefficients();
    let mut w2_star: f64 = 0.0;
    let mut c2 = 0.0;
    for (&cj, &wj) in c.iter().zip(omega) {
        if cj != 0.0 {
            w2_star = w2_star.max(wj * wj);
            c2 += cj * cj;
        }
    }
    let wc2 = kt * c2;
    if !wc2.is_finite() || wc2 <= 1e-12 * w2_star {
        return None;
    }
    // g(λ) = 1 − k_t Σ c_j²/(λ − ω_j²) rises from −∞ at ω*² to ≥ 0 at ω*² + k_t|c|²
    let g = |lam: f64| {
        let mut s = 0.0;
        for (&cj, &wj) in c.iter().zip(omega) {
            if cj != 0.0 {
                s += cj * cj / (lam - wj * wj);
            }
        }
        1.0 - kt * s
    };
    let (mut lo, mut hi) = (w2_star, w2_star + wc2);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let lam = hi;
    let (mut uu, mut udu, mut cu) = (0.0, 0.0, 0.0);
    for ((&cj, &wj), &dj) in c.iter().zip(omega).zip(damp) {
        if cj != 0.0 {
            let u = cj / (lam - wj * wj);
            uu += u * u;
            udu += dj * u * u;
            cu += cj * u;
        }
    }
    let omega_top = lam.sqrt();
    Some(ContactMode {
        omega: omega_top,
        zeta: (udu + ct * cu * cu) / (2.0 * omega_top * uu),
    })
}

/// Is RK4 with step `h` unstable for `mode`: |R(hλ)| > 1 at its eigenvalues λ (the same
/// tolerance as [`rk4_stability_limit`])?
fn rk4_unstable(mode: ContactMode, h: f64) -> bool {
    let (w, z) = (mode.omega * h, mode.zeta);
    let unstable = |x: f64, y: f64| rk4_gain(x, y) > 1.0 + 1e-13;
    if z < 1.0 {
        unstable(-z * w, (1.0 - z * z).sqrt() * w)
    } else {
        let s = (z * z - 1.0).sqrt();
        unstable(-(z + s) * w, 0.0) || unstable(-(z - s) * w, 0.0)
    }
}

/// Penetration at which the law's potential equals `energy` (J), m: the peak penetration of an
/// impact of two point masses m* at approach speed v₀ with `energy = ½m*v₀²` (no damping, no
/// other force; for damped laws an upper bound). At least `from`.
fn penetration_for_energy(force: &ContactForce, energy: f64, from: f64) -> f64 {
    let mut hi = from.max(1e-15);
    if !(energy.is_finite() && energy > 0.0) || force.potential(hi) >= energy {
        return from;
    }
    let mut lo = hi;
    for _ in 0..2000 {
        if force.potential(hi) >= energy {
            break;
        }
        lo = hi;
        hi *= 2.0;
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if force.potential(mid) < energy {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// Per-level bounds for the cheap test of [`check_contact`].
#[derive(Debug, Clone, Copy)]
struct LevelBounds {
    /// Largest ω² among the modes coupled to the level, 1/s².
    w2_star: f64,
    /// Largest `2ζ_jω_j` among them, 1/s.
    d_star: f64,
}

fn level_bounds(sys: &System) -> Vec<LevelBounds> {
    (0..sys.levels.len())
        .map(|k| {
            let mut b = LevelBounds {
                w2_star: 0.0,
                d_star: 0.0,
            };
            let coupled = sys.coupling(k).iter().map(|&c| c != 0.0);
            for ((on, &w), &d) in coupled.zip(sys.omega()).zip(sys.damping_coefficients()) {
                if on {
                    b.w2_star = b.w2_star.max(w * w);
                    b.d_star = b.d_star.max(d);
                }
            }
            b
        })
        .collect()
}

/// Refuse a step `h` ending at `t` in which the contact at level `k` (state `st`, onset speed
/// `v0`) makes RK4 unstable. Cheap unless the step is near the limit: the stiffest mode in
/// contact has `ω ≤ √(ω*² + ω_c²)` and `ζ ≤ (max 2ζ_jω_j + c_t/m*)/(2ω_c)`, and below
/// [`PRECHECK_OMEGA_DT`], [`PRECHECK_ZETA`] RK4 is stable; otherwise [`contact_mode`] decides.
///
/// The frequency tested is the linearised system's, not ω_c alone: with a soft contact on many
/// modes the stiffest mode is a structural one nudged up by the contact, and with a stiff one
/// it is ≈ √(ω_c² + ω̄²) (ω̄² the coupling-weighted mean of ω_j²); ω_c alone would let pass
/// steps where the two together are unstable, √(ω_c² + ω*²) would refuse stable ones.
#[allow(clippy::too_many_arguments)]
fn check_contact(
    sys: &System,
    bounds: &LevelBounds,
    k: usize,
    st: &LevelState,
    v0: f64,
    h: f64,
    t: f64,
    dt: f64,
) -> Result<(), SolveError> {
    let lv = &sys.levels[k];
    let m = lv.effective_mass;
    let kt = lv.force.tangent_stiffness(st.delta);
    if kt.is_nan() || kt <= 0.0 {
        return Ok(());
    }
    let ct = lv.force.tangent_damping(st.delta, st.delta_dot, v0);
    let wc2 = kt / m;
    let zeta_bound = (bounds.d_star + ct / m) / (2.0 * wc2.max(bounds.w2_star).sqrt());
    if (bounds.w2_star + wc2).sqrt() * h <= PRECHECK_OMEGA_DT && zeta_bound <= PRECHECK_ZETA {
        return Ok(());
    }
    let Some(mode) = contact_mode(sys, k, kt, ct) else {
        return Ok(());
    };
    if !rk4_unstable(mode, h) {
        return Ok(());
    }
    // the largest stable step, estimated at the peak penetration of this impact
    let limit_now = rk4_stability_limit(mode.omega, mode.zeta);
    let delta_est = penetration_for_energy(&lv.force, 0.5 * m * v0 * v0, st.delta);
    let kt_est = lv.force.tangent_stiffness(delta_est);
    let ct_est = lv.force.tangent_damping(delta_est, st.delta_dot, v0);
    let limit_est = contact_mode(sys, k, kt_est, ct_est)
        .map_or(limit_now, |m| rk4_stability_limit(m.omega, m.zeta));
    let omega_c = wc2.sqrt();
    Err(SolveError::ContactUnstable {
        t,
        level: k + 1,
        height: lv.height,
        delta: st.delta,
        omega_c,
        omega_c_dt: omega_c * h,
        omega_dt: mode.omega * h,
        limit: limit_now * mode.omega,
        dt,
        max_dt: CONTACT_DT_MARGIN * limit_now.min(limit_est),
        margin: CONTACT_DT_MARGIN,
        accurate_dt: 0.5 / (kt_est / m).sqrt(),
    })
}

/// Work arrays, sized once.
struct Work {
    q: Vec<f64>,
    v: Vec<f64>,
    qs: Vec<f64>,
    vs: Vec<f64>,
    a: [Vec<f64>; 4],
    vstage: [Vec<f64>; 3],
    states: Vec<LevelState>,
    stage_states: Vec<LevelState>,
    prev_states: Vec<LevelState>,
    onset: Vec<f64>,
    stage_force: [Vec<f64>; 4],
    /// Hysteretic variables (issue 16), their stage values, rates and per-storey powers (empty
    /// without yielding storeys).
    z: Vec<f64>,
    zs: Vec<f64>,
    zk: [Vec<f64>; 4],
    pw: [Vec<f64>; 4],
}

/// The right-hand side with the yielding storeys' pseudo-forces: [`System::acceleration_in`],
/// then (with hysteresis) [`crate::model::hysteresis::Hysteresis::apply`] on the same state.
#[allow(clippy::too_many_arguments)]
#[inline]
fn eval(
    sys: &System,
    ground: (f64, f64),
    (q, v, z): (&[f64], &[f64], &[f64]),
    onset: &[f64],
    a: &mut [f64],
    zdot: &mut [f64],
    pw: &mut [f64],
    states: &mut [LevelState],
) -> Powers {
    let mut p = sys.acceleration_in(ground, q, v, onset, a, states);
    if !sys.hysteresis.is_empty() {
        p.hysteretic = sys.hysteresis.apply(q, v, z, a, zdot, pw);
    }
    p
}

// (index loops over the parallel stage arrays read like the RK4 formulas)
#[allow(clippy::needless_range_loop)]
pub(super) fn run<O: Observer>(
    sys: &System,
    settings: &SolverSettings,
    initial: &InitialState,
    observer: &mut O,
) -> Result<Stats, SolveError> {
    let n = sys.len();
    let nl = sys.levels.len();
    let ns = sys.hysteresis.len();
    let zeros = || vec![0.0; n];
    let (q0, v0) = initial.resolved(n);
    let mut w = Work {
        q: q0,
        v: v0,
        qs: zeros(),
        vs: zeros(),
        a: [zeros(), zeros(), zeros(), zeros()],
        vstage: [zeros(), zeros(), zeros()],
        states: vec![LevelState::default(); nl],
        stage_states: vec![LevelState::default(); nl],
        prev_states: vec![LevelState::default(); nl],
        onset: vec![0.0; nl],
        stage_force: [vec![0.0; nl], vec![0.0; nl], vec![0.0; nl], vec![0.0; nl]],
        z: vec![0.0; ns],
        zs: vec![0.0; ns],
        zk: [vec![0.0; ns], vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]],
        pw: [vec![0.0; ns], vec![0.0; ns], vec![0.0; ns], vec![0.0; ns]],
    };
    let mut tally = Tally {
        impulse: vec![0.0; nl],
        storey_work: vec![0.0; ns],
        ..Tally::default()
    };
    let mut stats = Stats::default();
    let dt = settings.fixed_step();
    let (steps, last) = step_plan(dt, settings.duration);
    let bounds = level_bounds(sys);

    // k1 of the first step, and the state at t = 0. The ground is evaluated twice per step:
    // stages 2 and 3 share t + h/2, and stage 4's time is the next step's k1 time.
    let mut ground_end = sys.ground.accel_velocity(0.0);
    let mut p1 = eval(
        sys,
        ground_end,
        (&w.q, &w.v, &w.z),
        &w.onset,
        &mut w.a[0],
        &mut w.zk[0],
        &mut w.pw[0],
        &mut w.states,
    );
    stats.evaluations += 1;
    w.prev_states.copy_from_slice(&w.states);
    update_onsets(&mut w.onset, &w.prev_states, &w.states, 0.0);
    observer.observe(
        sys,
        &StepView {
            t: 0.0,
            q: &w.q,
            v: &w.v,
            levels: &w.states,
            z: &w.z,
            tally: &tally,
        },
    );

    for step in 0..steps {
        let t = step as f64 * dt;
        let h = if step + 1 == steps { last } else { dt };
        for k in 0..nl {
            w.stage_force[0][k] = w.states[k].force;
        }
        w.prev_states.copy_from_slice(&w.states);

        // stage 2: y + h/2 k1
        let [a1, a2, a3, a4] = &mut w.a;
        let [v2, v3, v4] = &mut w.vstage;
        let [z1, z2, z3, z4] = &mut w.zk;
        let [pw1, pw2, pw3, pw4] = &mut w.pw;
        stage(&mut w.qs, &mut w.vs, v2, (&w.q, &w.v), (&w.v, a1), 0.5 * h);
        for s in 0..ns {
            w.zs[s] = w.z[s] + 0.5 * h * z1[s];
        }
        let ground_mid = sys.ground.accel_velocity(t + 0.5 * h);
        let p2 = eval(
            sys,
            ground_mid,
            (&w.qs, &w.vs, &w.zs),
            &w.onset,
            a2,
            z2,
            pw2,
            &mut w.stage_states,
        );
        store_forces(&w.stage_states, &mut w.stage_force[1]);
        // stage 3: y + h/2 k2
        stage(&mut w.qs, &mut w.vs, v3, (&w.q, &w.v), (v2, a2), 0.5 * h);
        for s in 0..ns {
            w.zs[s] = w.z[s] + 0.5 * h * z2[s];
        }
        let p3 = eval(
            sys,
            ground_mid,
            (&w.qs, &w.vs, &w.zs),
            &w.onset,
            a3,
            z3,
            pw3,
            &mut w.stage_states,
        );
        store_forces(&w.stage_states, &mut w.stage_force[2]);
        // stage 4: y + h k3
        stage(&mut w.qs, &mut w.vs, v4, (&w.q, &w.v), (v3, a3), h);
        for s in 0..ns {
            w.zs[s] = w.z[s] + h * z3[s];
        }
        let t_end = if step + 1 == steps {
            settings.duration
        } else {
            (step + 1) as f64 * dt
        };
        ground_end = sys.ground.accel_velocity(t_end);
        let p4 = eval(
            sys,
            ground_end,
            (&w.qs, &w.vs, &w.zs),
            &w.onset,
            a4,
            z4,
            pw4,
            &mut w.stage_states,
        );
        store_forces(&w.stage_states, &mut w.stage_force[3]);
        // combine
        let h6 = h / 6.0;
        combine(&mut w.q, [&w.v, v2, v3, v4], h6);
        combine(&mut w.v, [a1, a2, a3, a4], h6);
        for s in 0..ns {
            w.z[s] += h6 * (z1[s] + 2.0 * z2[s] + 2.0 * z3[s] + z4[s]);
            tally.storey_work[s] += h6 * (pw1[s] + 2.0 * pw2[s] + 2.0 * pw3[s] + pw4[s]);
        }
        accumulate(&mut tally, h6, [&p1, &p2, &p3, &p4]);
        for k in 0..nl {
            let f = &w.stage_force;
            tally.impulse[k] += h6 * (f[0][k] + 2.0 * f[1][k] + 2.0 * f[2][k] + f[3][k]);
        }

        // k1 of the next step = the state at the end of this one
        p1 = eval(
            sys,
            ground_end,
            (&w.q, &w.v, &w.z),
            &w.onset,
            a1,
            z1,
            pw1,
            &mut w.states,
        );
        if sys.apply_impulses(
            &mut w.v,
            &mut w.states,
            &mut tally.impulse,
            &mut tally.contact,
        ) {
            p1 = eval(
                sys,
                ground_end,
                (&w.q, &w.v, &w.z),
                &w.onset,
                a1,
                z1,
                pw1,
                &mut w.states,
            );
        }
        stats.evaluations += 4;
        stats.steps += 1;
        update_onsets(&mut w.onset, &w.prev_states, &w.states, h);
        for (k, (lv, st)) in sys.levels.iter().zip(&w.states).enumerate() {
            if st.delta > 0.0 {
                let omega_c = (lv.force.tangent_stiffness(st.delta) / lv.effective_mass).sqrt();
                stats.max_contact_omega_dt = stats.max_contact_omega_dt.max(omega_c * h);
                // the onset speed as the force law sees it (System::acceleration_in)
                let v0 = if w.onset[k] > 0.0 {
                    w.onset[k]
                } else {
                    st.delta_dot
                };
                check_contact(sys, &bounds[k], k, st, v0, h, t_end, dt)?;
            }
        }
        if !(p1.input.is_finite()
            && p1.damping.is_finite()
            && w.q.iter().sum::<f64>().is_finite()
            && w.z.iter().sum::<f64>().is_finite())
        {
            return Err(SolveError::Diverged {
                t: t_end,
                contact_omega_dt: stats.max_contact_omega_dt,
            });
        }
        observer.observe(
            sys,
            &StepView {
                t: t_end,
                q: &w.q,
                v: &w.v,
                levels: &w.states,
                z: &w.z,
                tally: &tally,
            },
        );
    }
    Ok(stats)
}

/// One stage's state `y + c·k`: `qs = q + c·dq`, `vs = v + c·dv`, and `vk` a copy of `vs` (the
/// stage's velocity, the next stage's `dq`).
///
/// (Over slices zipped once, not `w.qs[j]` indexing into the work struct: indexed, each element
/// reloaded the vectors' pointers and lengths and checked bounds whenever the optimiser could
/// not keep the struct in registers — which depends on what else shares the codegen unit, so
/// unrelated changes moved the paper case's count by 16 M of 135 M, issue 25.)
#[inline(always)]
fn stage(
    qs: &mut [f64],
    vs: &mut [f64],
    vk: &mut [f64],
    (q, v): (&[f64], &[f64]),
    (dq, dv): (&[f64], &[f64]),
    c: f64,
) {
    let it = qs.iter_mut().zip(vs.iter_mut()).zip(vk.iter_mut());
    for (((qs, vs), vk), (((q, v), dq), dv)) in it.zip(q.iter().zip(v).zip(dq).zip(dv)) {
        *qs = q + c * dq;
        *vs = v + c * dv;
        *vk = *vs;
    }
}

/// `y += h6·(k₁ + 2k₂ + 2k₃ + k₄)` (the same order of operations as the formula).
#[inline(always)]
fn combine(y: &mut [f64], [k1, k2, k3, k4]: [&[f64]; 4], h6: f64) {
    for ((((y, a), b), c), d) in y.iter_mut().zip(k1).zip(k2).zip(k3).zip(k4) {
        *y += h6 * (a + 2.0 * b + 2.0 * c + d);
    }
}

#[inline]
fn store_forces(states: &[LevelState], out: &mut [f64]) {
    for (o, s) in out.iter_mut().zip(states) {
        *o = s.force;
    }
}

#[inline]
fn accumulate(tally: &mut Tally, h6: f64, p: [&Powers; 4]) {
    tally.input += h6 * (p[0].input + 2.0 * p[1].input + 2.0 * p[2].input + p[3].input);
    tally.damping += h6 * (p[0].damping + 2.0 * p[1].damping + 2.0 * p[2].damping + p[3].damping);
    tally.contact += h6 * (p[0].contact + 2.0 * p[1].contact + 2.0 * p[2].contact + p[3].contact);
    tally.hysteretic +=
        h6 * (p[0].hysteretic + 2.0 * p[1].hysteretic + 2.0 * p[2].hysteretic + p[3].hysteretic);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On the imaginary axis RK4 is stable up to |z| = 2√2 exactly: |R(iy)|² = 1 − y⁶/72 + y⁸/576.
    #[test]
    fn undamped_limit_is_two_root_two() {
        let dt = rk4_stability_limit(10.0, 0.0);
        assert!(
            (dt * 10.0 - 2.0 * 2f64.sqrt()).abs() < 1e-6,
            "{}",
            dt * 10.0
        );
    }

    /// On the negative real axis the limit is the real root of R(x) = −1... i.e. |R| = 1 at
    /// x ≈ −2.7853 (standard value).
    #[test]
    fn overdamped_limit_is_real_axis_limit() {
        let zeta: f64 = 2.0;
        let omega = 5.0;
        let dt = rk4_stability_limit(omega, zeta);
        let fast = omega * (zeta + (zeta * zeta - 1.0).sqrt());
        assert!((dt * fast - 2.785293563).abs() < 1e-6, "{}", dt * fast);
    }

    /// Light damping extends the limit slightly beyond 2√2.
    #[test]
    fn light_damping_extends_limit() {
        assert!(rk4_stability_limit(1.0, 0.05) > 2.0 * 2f64.sqrt());
    }

    /// The cheap test of `check_contact` is sound: for every damping ratio up to PRECHECK_ZETA
    /// the limit on ω·dt is at least PRECHECK_OMEGA_DT (smallest ≈ 2.62 near ζ = 0.5).
    #[test]
    fn precheck_is_below_every_limit_it_covers() {
        let mut least = f64::INFINITY;
        for i in 0..=900 {
            let zeta = i as f64 * 1e-3;
            least = least.min(rk4_stability_limit(1.0, zeta));
        }
        assert!(least >= PRECHECK_OMEGA_DT, "{least}");
        assert!(
            least < PRECHECK_OMEGA_DT + 0.05,
            "the bound is not needlessly low: {least}"
        );
    }

    /// `rk4_unstable` agrees with the scanned limit on both sides of it, under- and
    /// overdamped.
    #[test]
    fn instability_test_matches_the_limit() {
        for zeta in [0.0, 0.01, 0.3, 0.7, 1.0, 1.5, 3.0] {
            let omega = 7.0;
            let lim = rk4_stability_limit(omega, zeta);
            let mode = ContactMode { omega, zeta };
            assert!(!rk4_unstable(mode, lim * (1.0 - 1e-6)), "ζ = {zeta}");
            assert!(rk4_unstable(mode, lim * (1.0 + 1e-6)), "ζ = {zeta}");
        }
    }

    /// Two one-mode beams touching at a height: the stiffest mode in contact is the larger
    /// eigenvalue of the 2×2 matrix `diag(ω₁², ω₂²) + k_t c cᵀ` (closed form), its damping the
    /// Rayleigh quotient of `diag(2ζω) + c_t c cᵀ` on that eigenvector; it lies between
    /// max(ω_c, ω*) and √(ω_c² + ω*²).
    #[test]
    fn contact_mode_matches_the_two_by_two_eigenproblem() {
        use crate::model::contact::ContactLaw;
        use crate::model::ground_motion::GroundMotion;
        use crate::model::structure::{Cantilever, Damping, Stiffness};
        use crate::model::system::ContactLevel;
        let beam = |period: f64, zeta: f64| Cantilever {
            name: "b".into(),
            length: 10.0,
            mass: 2e6,
            stiffness: Stiffness::Period(period),
            modes: 1,
            damping: Damping::Modal(vec![zeta]),
        };
        let sys = System::new(
            [beam(0.4, 0.02).modal(), beam(0.7, 0.05).modal()],
            &ContactLaw::Hertz { stiffness: 1e10 },
            &[ContactLevel {
                height: 8.0,
                gap: 0.0,
            }],
            GroundMotion::None,
        );
        let c = sys.coupling(0).to_vec();
        let w = sys.omega().to_vec();
        let d = sys.damping_coefficients().to_vec();
        let m_star = sys.levels[0].effective_mass;
        for (kt, ct) in [(1e3, 0.0), (3e7, 1e4), (5e8, 0.0), (1e12, 3e6)] {
            let (a, b, e) = (
                w[0] * w[0] + kt * c[0] * c[0],
                kt * c[0] * c[1],
                w[1] * w[1] + kt * c[1] * c[1],
            );
            let lam = 0.5 * (a + e) + (0.25 * (a - e) * (a - e) + b * b).sqrt();
            let u = [b, lam - a];
            let uu = u[0] * u[0] + u[1] * u[1];
            let cu = c[0] * u[0] + c[1] * u[1];
            let zeta =
                (d[0] * u[0] * u[0] + d[1] * u[1] * u[1] + ct * cu * cu) / (2.0 * lam.sqrt() * uu);
            let mode = contact_mode(&sys, 0, kt, ct).unwrap();
            assert!(
                (mode.omega - lam.sqrt()).abs() < 1e-12 * lam.sqrt(),
                "k_t = {kt}"
            );
            assert!(
                (mode.zeta - zeta).abs() < 1e-9 * zeta.max(1e-3),
                "k_t = {kt}"
            );
            let wc = (kt / m_star).sqrt();
            let w_star = w[0].max(w[1]);
            assert!(mode.omega >= wc.max(w_star) * (1.0 - 1e-12));
            assert!(mode.omega <= (wc * wc + w_star * w_star).sqrt() * (1.0 + 1e-12));
        }
        // a negligible contact leaves the structural modes to check_stability
        assert_eq!(contact_mode(&sys, 0, 1e-30, 0.0), None);
    }

    /// The energy estimate of the peak penetration: ½m*v² = (2/5)kδ^{5/2} (Hertz) and ½kδ²
    /// (linear).
    #[test]
    fn penetration_for_energy_inverts_the_potential() {
        let (m, v, k) = (9.47e4, 0.96, 2.808e13);
        let e = 0.5 * m * v * v;
        let hertz = penetration_for_energy(&ContactForce::Hertz { k }, e, 0.0);
        let exact = (e / (0.4 * k)).powf(0.4);
        assert!((hertz - exact).abs() < 1e-12 * exact, "{hertz} {exact}");
        let lin = penetration_for_energy(&ContactForce::Linear { k: 1e9 }, e, 0.0);
        let exact = v * (m / 1e9).sqrt();
        assert!((lin - exact).abs() < 1e-12 * exact, "{lin} {exact}");
        // never below the penetration already met
        assert_eq!(
            penetration_for_energy(&ContactForce::Hertz { k }, e, 1.0),
            1.0
        );
    }
}
