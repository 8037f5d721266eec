//! Fixed-step classical Runge–Kutta (SPEC §2.9), with the energy flows and impulses integrated
//! by the same stage weights.

use super::{
    InitialState, Observer, SolveError, SolverSettings, Stats, StepView, Tally, step_plan,
    update_onsets,
};
use crate::system::{LevelState, Powers, System};

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
/// For ζ = 0 it is `2√2/ω` (SPEC §2.9).
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
}

pub(super) fn run<O: Observer>(
    sys: &System,
    settings: &SolverSettings,
    initial: &InitialState,
    observer: &mut O,
) -> Result<Stats, SolveError> {
    let n = sys.len();
    let nl = sys.levels.len();
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
    };
    let mut tally = Tally {
        impulse: vec![0.0; nl],
        ..Tally::default()
    };
    let mut stats = Stats::default();
    let (steps, last) = step_plan(settings.dt, settings.duration);

    // k1 of the first step, and the state at t = 0. The ground is evaluated twice per step:
    // stages 2 and 3 share t + h/2, and stage 4's time is the next step's k1 time.
    let mut ground_end = sys.ground.accel_velocity(0.0);
    let mut p1 = sys.acceleration_in(ground_end, &w.q, &w.v, &w.onset, &mut w.a[0], &mut w.states);
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
            tally: &tally,
        },
    );

    for step in 0..steps {
        let t = step as f64 * settings.dt;
        let h = if step + 1 == steps { last } else { settings.dt };
        for k in 0..nl {
            w.stage_force[0][k] = w.states[k].force;
        }
        w.prev_states.copy_from_slice(&w.states);

        // stage 2: y + h/2 k1
        let [a1, a2, a3, a4] = &mut w.a;
        let [v2, v3, v4] = &mut w.vstage;
        for j in 0..n {
            w.qs[j] = w.q[j] + 0.5 * h * w.v[j];
            w.vs[j] = w.v[j] + 0.5 * h * a1[j];
            v2[j] = w.vs[j];
        }
        let ground_mid = sys.ground.accel_velocity(t + 0.5 * h);
        let p2 = sys.acceleration_in(ground_mid, &w.qs, &w.vs, &w.onset, a2, &mut w.stage_states);
        store_forces(&w.stage_states, &mut w.stage_force[1]);
        // stage 3: y + h/2 k2
        for j in 0..n {
            w.qs[j] = w.q[j] + 0.5 * h * v2[j];
            w.vs[j] = w.v[j] + 0.5 * h * a2[j];
            v3[j] = w.vs[j];
        }
        let p3 = sys.acceleration_in(ground_mid, &w.qs, &w.vs, &w.onset, a3, &mut w.stage_states);
        store_forces(&w.stage_states, &mut w.stage_force[2]);
        // stage 4: y + h k3
        for j in 0..n {
            w.qs[j] = w.q[j] + h * v3[j];
            w.vs[j] = w.v[j] + h * a3[j];
            v4[j] = w.vs[j];
        }
        let t_end = if step + 1 == steps {
            settings.duration
        } else {
            (step + 1) as f64 * settings.dt
        };
        ground_end = sys.ground.accel_velocity(t_end);
        let p4 = sys.acceleration_in(ground_end, &w.qs, &w.vs, &w.onset, a4, &mut w.stage_states);
        store_forces(&w.stage_states, &mut w.stage_force[3]);
        // combine
        let h6 = h / 6.0;
        for j in 0..n {
            w.q[j] += h6 * (w.v[j] + 2.0 * v2[j] + 2.0 * v3[j] + v4[j]);
            w.v[j] += h6 * (a1[j] + 2.0 * a2[j] + 2.0 * a3[j] + a4[j]);
        }
        accumulate(&mut tally, h6, [&p1, &p2, &p3, &p4]);
        for k in 0..nl {
            let f = &w.stage_force;
            tally.impulse[k] += h6 * (f[0][k] + 2.0 * f[1][k] + 2.0 * f[2][k] + f[3][k]);
        }

        // k1 of the next step = the state at the end of this one
        p1 = sys.acceleration_in(ground_end, &w.q, &w.v, &w.onset, a1, &mut w.states);
        if sys.apply_impulses(
            &mut w.v,
            &mut w.states,
            &mut tally.impulse,
            &mut tally.contact,
        ) {
            p1 = sys.acceleration_in(ground_end, &w.q, &w.v, &w.onset, a1, &mut w.states);
        }
        stats.evaluations += 4;
        stats.steps += 1;
        update_onsets(&mut w.onset, &w.prev_states, &w.states, h);
        for (lv, st) in sys.levels.iter().zip(&w.states) {
            if st.delta > 0.0 {
                let omega_c = (lv.force.tangent_stiffness(st.delta) / lv.effective_mass).sqrt();
                stats.max_contact_omega_dt = stats.max_contact_omega_dt.max(omega_c * h);
            }
        }
        if !(p1.input.is_finite() && p1.damping.is_finite() && w.q.iter().sum::<f64>().is_finite())
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
                tally: &tally,
            },
        );
    }
    Ok(stats)
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
}
