//! Newton's method on the nodal forces over the contact levels, its banded and reduced LU
//! update, and the law's force at a step's start.

use crate::model::contact::ContactForce;
use crate::model::system::{LevelState, System, episode_v0};

/// Scratch of the Newton iterations on the nodal forces.
#[derive(Default)]
pub(in crate::integrate) struct Newton {
    pub(super) rhs: Vec<f64>,
    /// Per unknown, the law's derivatives (∂φ/∂δ, ∂φ/∂δ̇) at its node: its Jacobian row is
    /// `e_r + kd·w.0 + kv·w.1`, assembled only for the unknowns in contact, over the levels
    /// sharing a structure with its own (the rest of the row is exactly zero).
    pub(super) slopes: Vec<(f64, f64)>,
    /// Per unknown, whether its node is out of contact (the law's force and derivatives 0:
    /// its row of the Jacobian is the identity's).
    pub(super) free: Vec<bool>,
    /// Per level, whether its forces are all zero (start and nodes): out of contact over the
    /// step as far as the iterate goes, it weighs on no level's state (its products with the
    /// weights are zeros, skipped).
    quiet: Vec<bool>,
    /// The unknowns of the nodes in contact, each one's place among them, and their reduced
    /// system.
    act: Vec<usize>,
    pos: Vec<usize>,
    red: Vec<f64>,
    red_rhs: Vec<f64>,
    /// Of the level a pass is at, the levels of its band that carry force: their places in
    /// the band (their weights' block in the level table follows from the level's first
    /// slot), and the levels themselves.
    loaded: Vec<(usize, usize)>,
}

/// The larger of a running maximum `s` (never NaN) and `x`, as `s.max(x)` gives it (a NaN `x`
/// leaves `s`), in one comparison instead of `f64::max`'s NaN handling.
#[inline(always)]
fn fmax(s: f64, x: f64) -> f64 {
    if x > s { x } else { s }
}

/// Why a collocation solve failed (the step is then retried shorter).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::integrate) struct NoConvergence;

/// The nodal forces of an S-node scheme (S = 5: the propagated one, S = 4: the companion) over
/// one step: Newton's method on `F_kp = φ_k(δ_kp, δ̇_kp)` at the nodes p = 1..S−1 with
/// `δ_kp = dfree[k·(S−1) + p − 1] − Σ_l Σ_q w[((k·L + l)·(S−1) + p − 1)·S + q] F_lq`.
///
/// `force[k·S + p]`: on entry `p = 0` the start force (fixed) and `p ≥ 1` the first guess; on
/// return the solution. `nodal[k·(S−1) + p − 1]` receives (δ, δ̇) at the nodes. `onset`: the
/// approach speed of each level's episode (the damped laws' v₀; 0 when none). Converged when a
/// Newton update moves no force by more than `tol` of the largest (the caller ties `tol` to its
/// tolerance, far below it: an error ΔF of the forces moves the state by the response to ΔF);
/// the nodal states are then those of the forces before that last, negligible update. Returns
/// the number of law evaluations.
///
/// `levels`: the levels solved for (ascending; a pair: every level). Of a row, the levels
/// whose two structures are both active in the contact step: every other level's forces are
/// zero on entry and stay so (their nodal states are left as they are; see [`nodal_states`]).
#[allow(clippy::too_many_arguments)]
pub(in crate::integrate) fn solve<const S: usize>(
    sys: &System,
    w: &[(f64, f64)],
    dfree: &[(f64, f64)],
    onset: &[f64],
    force: &mut [f64],
    nodal: &mut [(f64, f64)],
    scratch: &mut Newton,
    tol: f64,
    levels: &[usize],
) -> Result<usize, NoConvergence> {
    let nl = sys.levels.len();
    if nl == 1 {
        return solve_one::<S>(sys, w, dfree, onset, force, nodal, tol);
    }
    #[cfg(target_arch = "x86_64")]
    if crate::numerics::vex::available() {
        // SAFETY: the processor has AVX
        return unsafe {
            solve_levels_vex::<S>(sys, w, dfree, onset, force, nodal, scratch, tol, levels)
        };
    }
    solve_levels::<S>(sys, w, dfree, onset, force, nodal, scratch, tol, levels)
}

/// [`solve_levels`] compiled for AVX ([`crate::numerics::vex`]: the same operations, the
/// same bits). Safety: the processor has AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[allow(clippy::too_many_arguments)]
unsafe fn solve_levels_vex<const S: usize>(
    sys: &System,
    w: &[(f64, f64)],
    dfree: &[(f64, f64)],
    onset: &[f64],
    force: &mut [f64],
    nodal: &mut [(f64, f64)],
    scratch: &mut Newton,
    tol: f64,
    levels: &[usize],
) -> Result<usize, NoConvergence> {
    solve_levels::<S>(sys, w, dfree, onset, force, nodal, scratch, tol, levels)
}

/// [`solve`] over several levels.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn solve_levels<const S: usize>(
    sys: &System,
    w: &[(f64, f64)],
    dfree: &[(f64, f64)],
    onset: &[f64],
    force: &mut [f64],
    nodal: &mut [(f64, f64)],
    scratch: &mut Newton,
    tol: f64,
    levels: &[usize],
) -> Result<usize, NoConvergence> {
    let nl = sys.levels.len();
    let m = S - 1;
    let dim = nl * m;
    scratch.rhs.resize(dim, 0.0);
    scratch.slopes.resize(dim, (0.0, 0.0));
    scratch.free.resize(dim, false);
    scratch.quiet.resize(nl, false);
    if levels.len() < nl {
        // (the levels not solved for: identity rows with a zero residual, out of the update)
        scratch.rhs.iter_mut().for_each(|r| *r = 0.0);
        scratch.free.iter_mut().for_each(|f| *f = true);
    }
    let w = &w[..sys.band_slots() * m * S];
    let mut last = f64::INFINITY;
    for iter in 1..=30 {
        // nodal states from the current forces, the residual and the law's derivatives (the
        // weights of levels sharing no structure are zero, and so are the forces of a level
        // out of contact throughout: both skipped, so that a row's level far from contact
        // costs its free flight and the law's test only)
        for (l, q) in scratch.quiet.iter_mut().enumerate() {
            *q = force[l * S..(l + 1) * S].iter().all(|&f| f == 0.0);
        }
        let mut scale: f64 = 0.0;
        // (the band whose loaded levels `loaded` holds: a pair's levels all share one band,
        // listed once a pass)
        let mut listed = usize::MAX..usize::MAX;
        for &k in levels {
            let law = &sys.levels[k].force;
            let band = sys.sharing_levels(k);
            let first = sys.band_slot(k, band.start);
            // (the band's levels in order, those out of contact throughout skipped: the same
            // sums as over every level of the band, term for term; `loaded` holds each one's
            // place in the band and the level)
            let Newton {
                rhs,
                slopes,
                free,
                quiet,
                loaded,
                ..
            } = &mut *scratch;
            if band != listed {
                loaded.clear();
                for l in band.clone() {
                    if !quiet[l] {
                        loaded.push((l - band.start, l));
                    }
                }
                listed = band.clone();
            }
            let rows = k * m..(k + 1) * m;
            let (rhs, slopes, free) = (
                &mut rhs[rows.clone()],
                &mut slopes[rows.clone()],
                &mut free[rows.clone()],
            );
            let (df, nd) = (&dfree[rows.clone()], &mut nodal[rows]);
            let fk = &force[k * S + 1..(k + 1) * S];
            let ok = onset[k];
            // (the weights' rows of S and the levels' forces as arrays: one bounds check each)
            let (wrows, _) = w.as_chunks::<S>();
            let (frows, _) = force.as_chunks::<S>();
            for p in 0..m {
                let (mut d, mut dd) = df[p];
                for &(rel, l) in loaded.iter() {
                    let row = &wrows[(first + rel) * m + p];
                    let fl = &frows[l];
                    for q in 0..S {
                        d -= row[q].0 * fl[q];
                        dd -= row[q].1 * fl[q];
                    }
                }
                nd[p] = (d, dd);
                let v0 = episode_v0(ok, dd);
                let (phi, kd, kv) = law.force_jacobian(d, dd, v0);
                let f = fk[p];
                rhs[p] = phi - f;
                slopes[p] = (kd, kv);
                free[p] = kd == 0.0 && kv == 0.0;
                scale = fmax(fmax(scale, phi.abs()), f.abs());
            }
        }
        let residual = scratch.rhs.iter().fold(0.0f64, |a, x| fmax(a, x.abs()));
        if !residual.is_finite() {
            return Err(NoConvergence);
        }
        if residual <= tol * scale || residual <= 1e-300 {
            return Ok(iter);
        }
        if !solve_touching::<S>(sys, w, scratch, dim) {
            return Err(NoConvergence);
        }
        let mut change: f64 = 0.0;
        for &k in levels {
            for p in 0..m {
                let d = scratch.rhs[k * m + p];
                force[k * S + p + 1] += d;
                change = fmax(change, d.abs());
            }
        }
        // converged: the update is below the tolerance (the residual after it is of the order
        // of its square), or it stalls at round-off
        if change <= tol * scale || (change <= 1e-11 * scale && change >= 0.5 * last) {
            return Ok(iter);
        }
        last = change;
    }
    Err(NoConvergence)
}

/// The nodal (δ, δ̇) of an S-node scheme at the levels `levels` that are not solved for
/// (their forces zero), from the solved forces of the others: `δ_kp = dfree[k·(S−1) + p − 1]
/// − Σ_l Σ_q w[…] F_lq` over the levels sharing a structure with k whose forces are not all
/// zero — of a row, the levels between a structure in the contact step and one out of it,
/// whose nodal states tell whether the step reaches them (an onset there).
pub(in crate::integrate) fn nodal_states<const S: usize>(
    sys: &System,
    w: &[(f64, f64)],
    dfree: &[(f64, f64)],
    force: &[f64],
    nodal: &mut [(f64, f64)],
    levels: &[usize],
) {
    let m = S - 1;
    for &k in levels {
        let band = sys.sharing_levels(k);
        for p in 0..m {
            let (mut d, mut dd) = dfree[k * m + p];
            for l in band.clone() {
                let fl = &force[l * S..(l + 1) * S];
                if fl.iter().all(|&f| f == 0.0) {
                    continue;
                }
                let base = (sys.band_slot(k, l) * m + p) * S;
                let row = &w[base..base + S];
                for q in 0..S {
                    d -= row[q].0 * fl[q];
                    dd -= row[q].1 * fl[q];
                }
            }
            nodal[k * m + p] = (d, dd);
        }
    }
}

crate::numerics::vex::avx_copy! {
    /// [`solve`] for a single contact level (the common case): the same iterations on stack
    /// arrays, the elimination unrolled by the compiler for the scheme's S − 1 unknowns. The law's
    /// kind is matched once per solve, not once per node and pass: [`solve_law`] is compiled per
    /// kind, each calling [`ContactForce::force_jacobian`] of a value of that kind (the same
    /// function on the same arguments: the same bits).
    fn solve_one<const S: usize>(
        sys: &System,
        w: &[(f64, f64)],
        dfree: &[(f64, f64)],
        onset: &[f64],
        force: &mut [f64],
        nodal: &mut [(f64, f64)],
        tol: f64,
    ) -> Result<usize, NoConvergence> => solve_one_vex, solve_one_body
}

/// [`solve_one`]'s work.
#[inline(always)]
fn solve_one_body<const S: usize>(
    sys: &System,
    w: &[(f64, f64)],
    dfree: &[(f64, f64)],
    onset: &[f64],
    force: &mut [f64],
    nodal: &mut [(f64, f64)],
    tol: f64,
) -> Result<usize, NoConvergence> {
    let onset = onset[0];
    match sys.levels[0].force {
        ContactForce::Hertz { k } => {
            solve_law::<S, _>(w, dfree, onset, force, nodal, tol, |d, dd, v0| {
                ContactForce::Hertz { k }.force_jacobian(d, dd, v0)
            })
        }
        ContactForce::HertzDamp { k, chi } => {
            solve_law::<S, _>(w, dfree, onset, force, nodal, tol, |d, dd, v0| {
                ContactForce::HertzDamp { k, chi }.force_jacobian(d, dd, v0)
            })
        }
        ContactForce::Kelvin { k, c } => {
            solve_law::<S, _>(w, dfree, onset, force, nodal, tol, |d, dd, v0| {
                ContactForce::Kelvin { k, c }.force_jacobian(d, dd, v0)
            })
        }
        ContactForce::Linear { k } => {
            solve_law::<S, _>(w, dfree, onset, force, nodal, tol, |d, dd, v0| {
                ContactForce::Linear { k }.force_jacobian(d, dd, v0)
            })
        }
        ContactForce::Jankowski { k, c0 } => {
            solve_law::<S, _>(w, dfree, onset, force, nodal, tol, |d, dd, v0| {
                ContactForce::Jankowski { k, c0 }.force_jacobian(d, dd, v0)
            })
        }
        law @ ContactForce::Impulsive { .. } => {
            solve_law::<S, _>(w, dfree, onset, force, nodal, tol, |d, dd, v0| {
                law.force_jacobian(d, dd, v0)
            })
        }
    }
}

/// Whether a pivot's magnitude (≥ 0, or NaN) can be divided by: not 0, NaN or infinite (two
/// comparisons: `x == 0.0 || !x.is_finite()` negated, the same answer for every such x).
#[inline(always)]
fn usable_pivot(x: f64) -> bool {
    x > 0.0 && x < f64::INFINITY
}

/// The iterations of [`solve_one`] with the law `jac` (δ, δ̇, v₀ ↦ (φ, ∂φ/∂δ, ∂φ/∂δ̇)).
#[inline(always)]
fn solve_law<const S: usize, J: Fn(f64, f64, f64) -> (f64, f64, f64)>(
    w: &[(f64, f64)],
    dfree: &[(f64, f64)],
    onset: f64,
    force: &mut [f64],
    nodal: &mut [(f64, f64)],
    tol: f64,
    jac_of: J,
) -> Result<usize, NoConvergence> {
    const MAX: usize = 4;
    let m = S - 1;
    let w = &w[..m * S];
    let (dfree, nodal, force) = (&dfree[..m], &mut nodal[..m], &mut force[..S]);
    // (each node's sum starts with the start force's term, which no iteration changes: formed
    // once, the first operation of every pass's sum as before)
    let mut base = [(0.0, 0.0); MAX];
    for p in 0..m {
        let row = &w[p * S..(p + 1) * S];
        let (mut d, mut dd) = dfree[p];
        d -= row[0].0 * force[0];
        dd -= row[0].1 * force[0];
        base[p] = (d, dd);
    }
    let mut last = f64::INFINITY;
    for iter in 1..=30 {
        let mut rhs = [0.0; MAX];
        let mut slopes = [(0.0, 0.0); MAX];
        let mut scale: f64 = 0.0;
        for p in 0..m {
            let row = &w[p * S..(p + 1) * S];
            let (mut d, mut dd) = base[p];
            for q in 1..S {
                d -= row[q].0 * force[q];
                dd -= row[q].1 * force[q];
            }
            nodal[p] = (d, dd);
            let v0 = episode_v0(onset, dd);
            let (phi, kd, kv) = jac_of(d, dd, v0);
            let f = force[p + 1];
            rhs[p] = phi - f;
            slopes[p] = (kd, kv);
            scale = fmax(fmax(scale, phi.abs()), f.abs());
        }
        let residual = rhs[..m].iter().fold(0.0f64, |a, x| fmax(a, x.abs()));
        // (`residual` is ≥ 0 or infinite, never NaN: `fmax` keeps the running maximum; so
        // "not finite" is one comparison)
        if residual == f64::INFINITY {
            return Err(NoConvergence);
        }
        if residual <= tol * scale || residual <= 1e-300 {
            return Ok(iter);
        }
        // the Jacobian (only when an update follows: most solves end on the residual test)
        let mut jac = [[0.0; MAX]; MAX];
        for p in 0..m {
            let row = &w[p * S..(p + 1) * S];
            let (kd, kv) = slopes[p];
            for q in 0..m {
                jac[p][q] = kd * row[q + 1].0 + kv * row[q + 1].1;
            }
            jac[p][p] += 1.0;
        }
        // elimination with partial pivoting
        for col in 0..m {
            // (the pivot's magnitude kept as it is found: the same choice and the same test
            // as comparing and testing the entries themselves, a NaN included)
            let (mut piv, mut best) = (col, jac[col][col].abs());
            for r in col + 1..m {
                let x = jac[r][col].abs();
                if x > best {
                    (piv, best) = (r, x);
                }
            }
            if !usable_pivot(best) {
                return Err(NoConvergence);
            }
            if piv != col {
                jac.swap(col, piv);
                rhs.swap(col, piv);
            }
            let inv = 1.0 / jac[col][col];
            for r in col + 1..m {
                let f = jac[r][col] * inv;
                for c in col + 1..m {
                    jac[r][c] -= f * jac[col][c];
                }
                rhs[r] -= f * rhs[col];
            }
        }
        let mut change: f64 = 0.0;
        for r in (0..m).rev() {
            let mut x = rhs[r];
            for c in r + 1..m {
                x -= jac[r][c] * rhs[c];
            }
            rhs[r] = x / jac[r][r];
            force[r + 1] += rhs[r];
            change = fmax(change, rhs[r].abs());
        }
        if change <= tol * scale || (change <= 1e-11 * scale && change >= 0.5 * last) {
            return Ok(iter);
        }
        last = change;
    }
    Err(NoConvergence)
}

/// [`solve`] for a pair's single contact level, called directly (no dispatch on the number of
/// levels): the one-level contact step's (`exact_modal::elastic::single`).
#[inline]
pub(in crate::integrate) fn solve_single<const S: usize>(
    sys: &System,
    w: &[(f64, f64)],
    dfree: &[(f64, f64)],
    onset: &[f64],
    force: &mut [f64],
    nodal: &mut [(f64, f64)],
    tol: f64,
) -> Result<usize, NoConvergence> {
    solve_one::<S>(sys, w, dfree, onset, force, nodal, tol)
}

/// The Newton update of [`solve`]: `J·x = rhs` in place (rhs becomes x), with the Jacobian
/// `J = I + kd·w.0 + kv·w.1` (δ falls as F grows) from the scratch's slopes. An unknown whose
/// node is out of contact has the identity's row (F = φ = 0 there, ∂φ = 0), so its update is
/// its residual: those are eliminated first and only the nodes in contact are solved for by
/// LU (block elimination, the same solution: with one level of three touching, a 4×4 system
/// instead of 12×12). The reduced rows are assembled from the weights over the levels sharing
/// a structure with the row's own only (the others' entries are exact zeros). False if
/// singular.
#[inline(always)]
pub(super) fn solve_touching<const S: usize>(
    sys: &System,
    w: &[(f64, f64)],
    s: &mut Newton,
    dim: usize,
) -> bool {
    let m = S - 1;
    let Newton {
        rhs,
        slopes,
        free,
        act,
        pos,
        red,
        red_rhs,
        ..
    } = s;
    act.clear();
    pos.clear();
    pos.resize(dim, 0);
    for r in 0..dim {
        if !free[r] {
            pos[r] = act.len();
            act.push(r);
        }
    }
    let na = act.len();
    if na == 0 {
        return true;
    }
    red.clear();
    red.resize(na * na, 0.0);
    red_rhs.resize(na, 0.0);
    // (the weights' rows of S: one bounds check a row)
    let (wrows, _) = w.as_chunks::<S>();
    for (i, &r) in act.iter().enumerate() {
        let (k, p) = (r / m, r % m);
        let (kd, kv) = slopes[r];
        let band = sys.sharing_levels(k);
        let first = sys.band_slot(k, band.start);
        // one pass over the row's unknowns c = l·m + q of its band, in order: a node out of
        // contact moves the right-hand side by its entry times its (known) update, a node in
        // contact takes its entry into the reduced row
        let mut b = rhs[r];
        let row = &mut red[i * na..(i + 1) * na];
        for (slot, l) in (first..).zip(band) {
            let ws = &wrows[slot * m + p][1..];
            let cols = l * m..(l + 1) * m;
            let (fl, rl, pl) = (&free[cols.clone()], &rhs[cols.clone()], &pos[cols]);
            for (q, x) in ws.iter().enumerate() {
                let e = kd * x.0 + kv * x.1;
                let e = if l * m + q == r { e + 1.0 } else { e };
                if fl[q] {
                    b -= e * rl[q];
                } else {
                    row[pl[q]] = e;
                }
            }
        }
        red_rhs[i] = b;
    }
    if !lu_solve(red, red_rhs, na) {
        return false;
    }
    for (i, &r) in act.iter().enumerate() {
        rhs[r] = red_rhs[i];
    }
    true
}

crate::numerics::vex::avx_copy! {
    /// Solve `a·x = b` in place (b becomes x; `a` is destroyed) by Gaussian elimination with
    /// partial pivoting; false if singular. The systems of up to three levels in contact (n ≤ 12:
    /// four unknowns a level) take [`lu_fixed`], the same operations in the same order on arrays
    /// of their size (no bounds checks, loops the compiler can unroll): the same bits.
    ///
    /// Where the processor has AVX, its copy compiled for it runs ([`crate::numerics::vex`]: the
    /// same bits).
    pub(super) fn lu_solve(a: &mut [f64], b: &mut [f64], n: usize) -> bool => lu_solve_vex, lu_solve_body
}

/// [`lu_solve`]'s work.
#[inline(always)]
fn lu_solve_body(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    match n {
        1 => lu_fixed::<1>(a, b),
        2 => lu_fixed::<2>(a, b),
        3 => lu_fixed::<3>(a, b),
        4 => lu_fixed::<4>(a, b),
        5 => lu_fixed::<5>(a, b),
        6 => lu_fixed::<6>(a, b),
        7 => lu_fixed::<7>(a, b),
        8 => lu_fixed::<8>(a, b),
        9 => lu_fixed::<9>(a, b),
        10 => lu_fixed::<10>(a, b),
        11 => lu_fixed::<11>(a, b),
        12 => lu_fixed::<12>(a, b),
        _ => lu_any(a, b, n),
    }
}

/// [`lu_solve`] for N unknowns (`a` row-major N×N, `b` of N): the very arithmetic of
/// [`lu_any`] (pivot search, row exchange from the pivot's column on, the elimination that
/// skips a zero factor, the back substitution in the same order).
#[inline(always)]
fn lu_fixed<const N: usize>(a: &mut [f64], b: &mut [f64]) -> bool {
    let (rows, _) = a[..N * N].as_chunks_mut::<N>();
    let a: &mut [[f64; N]; N] = rows.try_into().expect("N rows");
    let b: &mut [f64; N] = (&mut b[..N]).try_into().expect("N values");
    for col in 0..N {
        let mut piv = col;
        let mut best = a[col][col].abs();
        for r in col + 1..N {
            let x = a[r][col].abs();
            if x > best {
                (piv, best) = (r, x);
            }
        }
        if best == 0.0 || !best.is_finite() {
            return false;
        }
        if piv != col {
            for c in col..N {
                let t = a[col][c];
                a[col][c] = a[piv][c];
                a[piv][c] = t;
            }
            b.swap(col, piv);
        }
        let inv = 1.0 / a[col][col];
        let prow = a[col];
        let bc = b[col];
        for r in col + 1..N {
            let f = a[r][col] * inv;
            if f != 0.0 {
                for c in col + 1..N {
                    a[r][c] -= f * prow[c];
                }
                b[r] -= f * bc;
            }
        }
    }
    for r in (0..N).rev() {
        let mut s = b[r];
        for c in r + 1..N {
            s -= a[r][c] * b[c];
        }
        b[r] = s / a[r][r];
    }
    true
}

/// [`lu_solve`] for any n.
pub(super) fn lu_any(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    for col in 0..n {
        let mut piv = col;
        let mut best = a[col * n + col].abs();
        for r in col + 1..n {
            let x = a[r * n + col].abs();
            if x > best {
                (piv, best) = (r, x);
            }
        }
        if best == 0.0 || !best.is_finite() {
            return false;
        }
        if piv != col {
            for c in col..n {
                a.swap(col * n + c, piv * n + c);
            }
            b.swap(col, piv);
        }
        let inv = 1.0 / a[col * n + col];
        let (top, rest) = a.split_at_mut((col + 1) * n);
        let prow = &top[col * n + col + 1..col * n + n];
        let bc = b[col];
        for (i, row) in rest.chunks_exact_mut(n).enumerate() {
            let f = row[col] * inv;
            if f != 0.0 {
                for (x, y) in row[col + 1..].iter_mut().zip(prow) {
                    *x -= f * y;
                }
                b[col + 1 + i] -= f * bc;
            }
        }
    }
    for r in (0..n).rev() {
        let mut s = b[r];
        for c in r + 1..n {
            s -= a[r * n + c] * b[c];
        }
        b[r] = s / a[r * n + r];
    }
    true
}

/// The law's force at the start of a step at every level: the state's own, or at a located
/// onset (δ within `event_tol` below 0, approaching) the law's right limit there (c·δ̇ for
/// Kelvin), not the 0 of δ ≤ 0.
pub(in crate::integrate) fn start_force(
    sys: &System,
    k: usize,
    st: &LevelState,
    onset: f64,
    tol: f64,
) -> f64 {
    if st.delta <= 0.0 && st.delta >= -tol && st.delta_dot > 0.0 {
        let v0 = if onset > 0.0 { onset } else { st.delta_dot };
        sys.levels[k]
            .force
            .force(f64::MIN_POSITIVE, st.delta_dot, v0)
    } else {
        st.force
    }
}
