//! The collocation tables, bases and Newton solve checked against their definitions.

use super::newton::{lu_solve, solve_touching};
use super::nodes::{A1, A2, B1, END, SEVEN, lagrange};
use super::table::{monomial_responses, trig_moments};
use super::*;
use crate::integrate::linear::{Prop, monomial_influence, propagator};
use crate::model::system::System;

/// The Lagrange coefficients reproduce the nodes' cardinal property, and the weights
/// integrate x⁷ exactly (5-node Lobatto: degree 2·5 − 3).
#[test]
fn nodes_and_weights() {
    let l = lagrange(&THETA8);
    for p in 0..5 {
        for (i, &x) in THETA8.iter().enumerate() {
            let v: f64 = (0..5).map(|m| l[m][p] * x.powi(m as i32)).sum();
            let want = if i == p { 1.0 } else { 0.0 };
            assert!((v - want).abs() < 1e-13, "ℓ_{p}({x}) = {v}");
        }
    }
    for deg in 0..=7 {
        let q: f64 = WEIGHTS8
            .iter()
            .zip(THETA8)
            .map(|(w, x)| w * x.powi(deg))
            .sum();
        assert!(
            (q - 1.0 / (deg + 1) as f64).abs() < 1e-15,
            "degree {deg}: {q}"
        );
    }
    assert!((A1 - 0.5 * (1.0 - 1.0 / 5f64.sqrt())).abs() < 1e-16);
    assert!((B1 - 0.5 * (1.0 - (3.0f64 / 7.0).sqrt())).abs() < 1e-16);
    assert!((bases().quartic_at(&[1.0, 2.0, 3.0, 4.0, 5.0], 0.5) - 3.0).abs() < 1e-14);
    let v = [0.3, -1.0, 2.0, 0.7, 1.1];
    for (i, x) in [A1, A2].iter().enumerate() {
        let direct = bases().quartic_at(&v, *x);
        let weights: f64 = (0..5).map(|p| bases().at6[i][p] * v[p]).sum();
        assert!((direct - weights).abs() < 1e-13);
    }
}

/// The shared series and the closed form agree with the linear module's per-load
/// influences (m ≤ 3) on both sides of the switch, and the quartic load's response solves
/// the equation of motion (checked by the response's own second derivative, from a finer
/// pair of evaluations).
#[test]
fn monomial_responses_match_the_single_load_influences() {
    for &(omega, zeta, h) in &[(3.0, 0.02, 0.1), (40.0, 0.05, 0.02), (900.0, 0.01, 0.01)] {
        let damp = 2.0 * zeta * omega;
        let props = NODES.map(|x| propagator(omega, damp, x * h));
        let mut out = [[(0.0, 0.0); 5]; 6];
        monomial_responses(omega, damp, h, &props, &mut out);
        for (i, &x) in NODES.iter().enumerate() {
            let want = monomial_influence(omega, damp, x * h, h, &props[i]);
            for m in 0..4 {
                let (a, b) = (out[i][m], want[m]);
                let tol = 1e-11 * (a.0.abs() * omega + a.1.abs()).max(1e-300);
                assert!(
                    (a.0 - b.0).abs() * omega + (a.1 - b.1).abs() <= tol,
                    "ω {omega} node {x} m {m}: {a:?} vs {b:?}"
                );
            }
        }
        // the m = 4 response: η̈ = (τ/h)⁴ − damp·η̇ − ω²η at the end, by differences of η̇
        let e = 1e-4 * h;
        let at = |s: f64| {
            let p: [Prop; 6] = [propagator(omega, damp, s); 6];
            let mut o = [[(0.0, 0.0); 5]; 6];
            monomial_responses(omega, damp, s, &p, &mut o);
            // (node END is s itself; rescale the load (τ/s)⁴ to (τ/h)⁴)
            let r = (s / h).powi(4);
            (o[END][4].0 * r, o[END][4].1 * r)
        };
        let (y, yd) = at(h);
        let acc = (at(h + e).1 - at(h - e).1) / (2.0 * e);
        let lhs = acc + damp * yd + omega * omega * y;
        assert!((lhs - 1.0).abs() < 1e-5, "ω {omega}: {lhs}");
    }
}

/// The Lagrange loads' trigonometric moments against a fine midpoint rule, on both sides
/// of the switch between series and recursion.
#[test]
fn trig_moments_match_quadrature() {
    for a in [1e-3, 0.7, 1.99, 2.01, 5.0, 40.0] {
        let m = trig_moments(a);
        let n = 200_000;
        for (k, &(c, s)) in m.iter().enumerate() {
            let (mut qc, mut qs) = (0.0, 0.0);
            for i in 0..n {
                let x = (i as f64 + 0.5) / n as f64;
                qc += x.powi(k as i32) * (a * x).cos() / n as f64;
                qs += x.powi(k as i32) * (a * x).sin() / n as f64;
            }
            // (midpoint rule: error ~ a²/(24 n²) of the integrand's scale)
            let tol = 1e-10 * (1.0 + a * a);
            assert!(
                (c - qc).abs() < tol && (s - qs).abs() < tol,
                "a {a} m {k}: {c} {s} vs {qc} {qs}"
            );
        }
    }
    let w = bases().first;
    let q: f64 = w.iter().zip(THETA8).map(|(w, x)| w * x * x * x).sum();
    assert!((q - 0.2).abs() < 1e-14, "∫x·x³ = 1/5: {q}");
    for deg in 0..=7 {
        let q: f64 = bases()
            .seven
            .iter()
            .zip(SEVEN)
            .map(|(w, x)| w * x.powi(deg))
            .sum();
        // The weights come from inverting a 7×7 Vandermonde matrix on [0, 1] (condition
        // ~1e5): ~1e-13 of round-off (measured 1.8e-13 on degree 0), far below any effect.
        assert!(
            (q - 1.0 / (deg + 1) as f64).abs() < 1e-12,
            "seven, degree {deg}: {q}"
        );
    }
}

/// A row of five cantilevers of different heights, periods and mode counts, with one to
/// four levels per pair (10 levels): every level's pair and neighbours differ.
fn random_row() -> System {
    use crate::model::contact::ContactLaw;
    use crate::model::ground_motion::GroundMotion;
    use crate::model::structure::{Cantilever, Damping, Stiffness};
    use crate::model::system::{ContactLevel, PairContact};
    let spec = [
        (0.5, 12.0, 3),
        (0.8, 15.0, 4),
        (0.35, 9.0, 2),
        (1.1, 20.0, 5),
        (0.6, 11.0, 3),
    ];
    let models = spec
        .iter()
        .map(|&(t, l, modes)| {
            Cantilever {
                name: "s".into(),
                length: l,
                mass: 2e6,
                stiffness: Stiffness::Period(t),
                modes,
                damping: Damping::Modal(vec![0.03]),
            }
            .modal()
        })
        .collect();
    let levels = [
        vec![11.0],
        vec![4.0, 8.5],
        vec![3.0, 6.0, 8.9],
        vec![2.5, 7.0, 10.5, 5.0],
    ];
    let pairs: Vec<PairContact> = levels
        .iter()
        .map(|hs| PairContact {
            law: ContactLaw::Hertz { stiffness: 1e10 },
            levels: hs
                .iter()
                .map(|&height| ContactLevel { height, gap: 0.01 })
                .collect(),
        })
        .collect();
    System::row(models, &pairs, GroundMotion::None)
}

/// The level tables, assembled over the levels that hold each mode only and stored over
/// each level's band, are the dense definition `W_kl = Σ_j c_kj c_lj Γ_j` over every mode
/// of the row (Γ_j: the mode's responses to the Lagrange loads, kept in `modes[j]`),
/// exactly: the terms skipped are products with a zero coupling, and adding zeros changes
/// no sum. `sharing_levels` holds every level pair with a non-zero weight (the pairs left
/// out of the storage weigh exactly 0), and the banded propagator rows are the dense
/// `c_kj P_j(θh)` over every mode (zero outside the level's pair's modes).
#[test]
fn banded_level_tables_equal_the_dense_definition() {
    let sys = random_row();
    let (n, nl) = (sys.len(), sys.levels.len());
    assert_eq!(nl, 10);
    let t = Table::new(&sys, None, 0.013);
    assert_eq!(
        t.w8.len(),
        20 * (0..nl).map(|k| sys.sharing_levels(k).len()).sum::<usize>()
    );
    for k in 0..nl {
        for i in 0..6 {
            let cp = t.cprop_at(&sys, k, i);
            let modes = sys.coupling_modes(k);
            for j in 0..n {
                let p = propagator(
                    sys.omega()[j],
                    sys.damping_coefficients()[j],
                    NODES[i] * 0.013,
                );
                let c = sys.coupling(k)[j];
                let want = [c * p.p11, c * p.p21, c * p.p12, c * p.p22];
                if modes.contains(&j) {
                    assert_eq!(cp[j - modes.start], want, "cprop {k} {i} {j}");
                } else {
                    assert_eq!(c, 0.0, "level {k} mode {j} outside its pair");
                }
            }
        }
    }
    let mut nonzero = 0;
    let mut slots = std::collections::BTreeSet::new();
    for k in 0..nl {
        for l in 0..nl {
            let share = sys.sharing_levels(k).contains(&l);
            assert_eq!(share, sys.sharing_levels(l).contains(&k));
            let kl = share.then(|| sys.band_slot(k, l));
            if let Some(kl) = kl {
                assert!(slots.insert(kl), "slot {kl} twice");
            }
            for i in 0..4 {
                for p in 0..5 {
                    let (mut a, mut b) = (0.0, 0.0);
                    for j in 0..n {
                        let c = sys.coupling(k)[j] * sys.coupling(l)[j];
                        let g = if i < 3 {
                            t.modes[j].mid8[i][p]
                        } else {
                            t.modes[j].end8[p]
                        };
                        a += c * g.0;
                        b += c * g.1;
                    }
                    match kl {
                        Some(kl) => {
                            assert_eq!(t.w8[(kl * 4 + i) * 5 + p], (a, b), "w8 {k} {l} {i} {p}");
                            nonzero += usize::from(a != 0.0);
                        }
                        None => assert_eq!((a, b), (0.0, 0.0), "levels {k}, {l} share none"),
                    }
                }
            }
            // the companion's and the mid-node tables: stored over the band, non-zero there
            let zero = |t: &[(f64, f64)]| t.iter().all(|&x| x == (0.0, 0.0));
            if let Some(kl) = kl {
                assert!(!zero(&t.w6[kl * 12..(kl + 1) * 12]), "w6 {k} {l}");
                assert!(!zero(&t.w86[kl * 10..(kl + 1) * 10]), "w86 {k} {l}");
            }
        }
    }
    // (the slots tile the storage)
    assert_eq!(slots.len(), sys.band_slots());
    assert_eq!(slots.last().copied(), Some(sys.band_slots() - 1));
    // (the band is not the whole: levels 0 and 9 are three pairs apart)
    assert!(nonzero > 0 && !sys.sharing_levels(0).contains(&9));
    // and the levels holding each mode are those with a non-zero coupling there
    for j in 0..n {
        for k in 0..nl {
            if sys.coupling(k)[j] != 0.0 {
                assert!(sys.levels_of_mode(j).contains(&k), "mode {j} level {k}");
            }
        }
    }
}

/// The Newton update with the out-of-contact unknowns eliminated and the contact rows
/// assembled over the sharing levels only solves the dense system `(I + kd·w.0 + kv·w.1)x
/// = rhs` written from the definition over every level pair (the free rows: identity),
/// checked against `lu_solve` on the whole and by the dense residual. Tolerance: the
/// system is scaled to O(1) entries and well conditioned (identity plus a perturbation of
/// norm < 1), so both solutions agree to a few ulps of O(1) values.
#[test]
fn banded_newton_update_solves_the_dense_system() {
    let sys = random_row();
    let nl = sys.levels.len();
    let t = Table::new(&sys, None, 0.013);
    const S: usize = 5;
    let m = S - 1;
    let dim = nl * m;
    // scale the slopes so that kd·w is O(0.1)
    let wmax = t.w8.iter().fold(0.0f64, |a, x| a.max(x.0.abs()));
    let vmax = t.w8.iter().fold(0.0f64, |a, x| a.max(x.1.abs()));
    for pattern in 0..3 {
        let mut s = Newton::default();
        s.rhs = (0..dim)
            .map(|r| ((r * 37 + 11) % 17) as f64 / 8.0 - 1.0)
            .collect();
        s.free = (0..dim)
            .map(|r| match pattern {
                0 => r % 3 == 1 || (r / m) % 4 == 2,
                1 => false,
                _ => true,
            })
            .collect();
        s.slopes = (0..dim)
            .map(|r| {
                if s.free[r] {
                    (0.0, 0.0)
                } else {
                    let x = ((r * 13 + 5) % 7) as f64 / 7.0;
                    (
                        0.02 * (1.0 + x) / wmax / nl as f64,
                        0.01 * x / vmax / nl as f64,
                    )
                }
            })
            .collect();
        let mut dense = vec![0.0; dim * dim];
        for r in 0..dim {
            let (k, p) = (r / m, r % m);
            let (kd, kv) = s.slopes[r];
            for c in 0..dim {
                let (l, q) = (c / m, c % m);
                // (outside k's band the weight is zero: see the test above)
                let x = if sys.sharing_levels(k).contains(&l) {
                    t.w8[(sys.band_slot(k, l) * m + p) * S + q + 1]
                } else {
                    (0.0, 0.0)
                };
                dense[r * dim + c] = kd * x.0 + kv * x.1 + if r == c { 1.0 } else { 0.0 };
            }
        }
        let b = s.rhs.clone();
        let (mut a_full, mut x_full) = (dense.clone(), b.clone());
        assert!(lu_solve(&mut a_full, &mut x_full, dim));
        assert!(solve_touching::<S>(&sys, &t.w8, &mut s, dim));
        for r in 0..dim {
            assert!(
                (s.rhs[r] - x_full[r]).abs() < 1e-13,
                "pattern {pattern}, {r}"
            );
            let ax: f64 = (0..dim).map(|c| dense[r * dim + c] * s.rhs[c]).sum();
            assert!((ax - b[r]).abs() < 1e-13, "pattern {pattern}, row {r}");
        }
        if pattern == 2 {
            // every node free: the updates are the residuals
            assert_eq!(s.rhs, b);
        }
    }
}

/// `solve` on a row where three of ten levels penetrate in free flight (pair 0's and
/// both of pair 1's) and the rest are 10 mm short: the nodal forces it returns satisfy
/// the collocation equations `F_kp = φ_k(δ_kp)` with δ written from the dense definition
/// `δ_kp = δfree_kp − Σ_l Σ_q Σ_j c_kj c_lj Γ_j(p, q) F_lq` over every level pair and every
/// mode (so the skipped zero weights and zero forces change nothing), the levels out of
/// contact carry exactly zero force, and a level whose whole band is out of contact has its
/// free flight's states, to the bit. Tolerance: Newton stops when an update moves no force
/// by more than 1e-10 of the largest; the residual after it is of that order or below
/// (1e-8 of the largest force allows for the law's δ^{3/2} and the weights' round-off).
#[test]
fn newton_over_a_row_solves_the_dense_collocation_equations() {
    let sys = random_row();
    let (n, nl) = (sys.len(), sys.levels.len());
    let t = Table::new(&sys, None, 0.013);
    const S: usize = 5;
    let m = S - 1;
    // penetrating: level 0 (pair 0), levels 1 and 2 (pair 1); pair 3's band (pairs 2, 3)
    // holds none of them
    let touching = [0usize, 1, 2];
    let dfree: Vec<(f64, f64)> = (0..nl * m)
        .map(|r| {
            let (k, p) = (r / m, r % m);
            if touching.contains(&k) {
                (2e-4 * (1.0 + 0.3 * p as f64), 0.05)
            } else {
                (-0.01, 0.02)
            }
        })
        .collect();
    let onset = vec![0.0; nl];
    let mut force = vec![0.0; nl * S];
    let mut nodal = vec![(0.0, 0.0); nl * m];
    let mut scratch = Newton::default();
    solve::<S>(
        &sys,
        &t.w8,
        &dfree,
        &onset,
        &mut force,
        &mut nodal,
        &mut scratch,
        1e-10,
        &(0..nl).collect::<Vec<_>>(),
    )
    .expect("converges");
    let fmax = force.iter().fold(0.0f64, |a, f| a.max(f.abs()));
    assert!(fmax > 0.0);
    let mut calm_levels = 0;
    for k in 0..nl {
        let law = &sys.levels[k].force;
        for p in 0..m {
            let (mut d, mut dd) = dfree[k * m + p];
            for l in 0..nl {
                for q in 0..S {
                    let (mut a, mut b) = (0.0, 0.0);
                    for j in 0..n {
                        let c = sys.coupling(k)[j] * sys.coupling(l)[j];
                        let g = if p < 3 {
                            t.modes[j].mid8[p][q]
                        } else {
                            t.modes[j].end8[q]
                        };
                        a += c * g.0;
                        b += c * g.1;
                    }
                    d -= a * force[l * S + q];
                    dd -= b * force[l * S + q];
                }
            }
            let (phi, _, _) = law.force_jacobian(d, dd, 0.0);
            let f = force[k * S + p + 1];
            assert!(
                (phi - f).abs() <= 1e-8 * fmax,
                "level {k} node {p}: φ {phi} F {f}"
            );
            if d <= 0.0 {
                assert_eq!(f, 0.0, "level {k} node {p} out of contact");
            }
            let calm = sys
                .sharing_levels(k)
                .all(|l| force[l * S..(l + 1) * S].iter().all(|&x| x == 0.0));
            if calm {
                assert_eq!(nodal[k * m + p], dfree[k * m + p], "level {k} node {p}");
                calm_levels += 1;
            } else {
                // (elsewhere the returned states are those of the forces before Newton's
                // last update, below 1e-10 of the largest force: far below 1e-9 m here)
                let (a, b) = nodal[k * m + p];
                assert!(
                    (a - d).abs() < 1e-9 && (b - dd).abs() < 1e-6,
                    "level {k} node {p}"
                );
            }
        }
    }
    // pair 3's four levels, at four nodes each
    assert_eq!(calm_levels, 16);
    for &k in &touching {
        assert!(force[k * S + m] > 0.0, "level {k} touches");
    }
}

/// `lu_solve` solves a pivoting-needing system.
#[test]
fn lu_solves() {
    let mut a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
    let mut b = vec![5.0, 3.0, 7.0];
    assert!(lu_solve(&mut a, &mut b, 3));
    // (the first pivot is zero without the row exchange)
    let a0 = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
    let b0 = [5.0, 3.0, 7.0];
    for r in 0..3 {
        let s: f64 = (0..3).map(|c| a0[r * 3 + c] * b[c]).sum();
        assert!((s - b0[r]).abs() < 1e-12, "row {r}: {s}");
    }
}

/// The fixed-size eliminations of `lu_solve` (1 to 12 unknowns) are `lu_any`'s, bit for bit:
/// on matrices whose rows need exchanges (a small diagonal), with zero entries (the skipped
/// zero factors) and values that round, at every size from 1 to 13 (13: `lu_any` itself),
/// and a singular one is refused alike. Each solution is also checked by its residual.
#[test]
fn fixed_size_lu_is_the_general_one_bit_for_bit() {
    use super::newton::lu_any;
    for n in 1..=13usize {
        for seed in 0..4u64 {
            let entry = |r: usize, c: usize| {
                let x = ((r * 31 + c * 17 + seed as usize * 7) % 23) as f64;
                if (r + 2 * c + seed as usize).is_multiple_of(5) && r != c {
                    0.0
                } else if r == c {
                    1e-3 * (x + 1.0).sqrt()
                } else {
                    (x + 0.5).sqrt() - 2.2
                }
            };
            let a0: Vec<f64> = (0..n * n).map(|i| entry(i / n, i % n)).collect();
            let b0: Vec<f64> = (0..n).map(|r| 1.0 / (r as f64 + 0.7) - 0.4).collect();
            let (mut a1, mut b1) = (a0.clone(), b0.clone());
            let (mut a2, mut b2) = (a0.clone(), b0.clone());
            let ok1 = lu_solve(&mut a1, &mut b1, n);
            let ok2 = lu_any(&mut a2, &mut b2, n);
            assert_eq!(ok1, ok2, "n = {n}, seed {seed}");
            let bits = |x: &[f64]| x.iter().map(|y| y.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&b1), bits(&b2), "n = {n}, seed {seed}");
            if ok1 {
                // (a residual of round-off size against the row's terms: 1e-10 of them
                // allows the pivots' growth on these small systems many times over)
                for r in 0..n {
                    let s: f64 = (0..n).map(|c| a0[r * n + c] * b1[c]).sum();
                    let size: f64 = (0..n).map(|c| (a0[r * n + c] * b1[c]).abs()).sum();
                    let err = (s - b0[r]).abs();
                    assert!(
                        err <= 1e-10 * (size + b0[r].abs()),
                        "n = {n}, row {r}: {err:e}"
                    );
                }
            }
        }
        let mut z = vec![0.0; n * n];
        let mut y = vec![1.0; n];
        assert!(!lu_solve(&mut z, &mut y, n), "singular, n = {n}");
    }
}
