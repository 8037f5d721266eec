//! Exponential Lobatto collocation of the contact forces over a step: the embedded pair that
//! `exact-modal` integrates contact with (docs/model.md §2.9; README, *Solver methods and speed*).
//!
//! Over a step of length h every level's contact force is the polynomial through its values at
//! the Lobatto nodes; each mode's response to a polynomial load is exact (the tables below,
//! per mode and step length), so the penetrations at the nodes are an affine function of the
//! nodal forces through small level×level tables, and the nodal forces solve the contact law at
//! the nodal states (Newton's method in those few unknowns, with the law's exact Jacobian).
//! Two such schemes on one step:
//!
//! - **the propagated one**: 5 Lobatto nodes θ = 0, ½ ∓ √(3/7)/2, ½, 1, the force a quartic —
//!   order 8 at the step's end (Lobatto IIIA, s = 5: 2s − 2; exact without contact);
//! - **its companion**: 4 nodes θ = 0, ½ ∓ 1/(2√5), 1, the force a cubic — order 6.
//!
//! The distance between the two ends is the companion's local error to within the propagated
//! one's (O(h⁹) against O(h⁷)), and it is what the step size is chosen by: an estimate that,
//! unlike a formula on one solution, solves the contact law itself, so it sees the contact's
//! stiffness, its onset and release and any kink of the law. The state kept is the eighth-order
//! one (local extrapolation, as in the Dormand–Prince pair): its error is the estimate's at
//! most and far below it on a smooth stretch — an upper bound, tested against the true local
//! error of both solutions (`exact_modal::elastic` tests).
//!
//! Everything that depends on the step length only is in [`Table`] (propagators to the nodes,
//! every mode's response to the Lagrange loads, the level tables); steps take lengths from a
//! quantised set so that the tables are computed once per length.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::linear::{Prop, propagator};
use crate::model::system::{LevelState, System, episode_v0};
use crate::numerics::linalg::power;

/// The two interior nodes of the 4-node companion, ½ ∓ 1/(2√5).
const A1: f64 = 0.276_393_202_250_021;
const A2: f64 = 0.723_606_797_749_978_9;
/// The interior nodes of the 5-node scheme, ½ ∓ √(3/7)/2 and ½.
const B1: f64 = 0.172_673_164_646_011_43;
const B3: f64 = 0.827_326_835_353_988_6;

/// Every node a table holds, as fractions of the step: the companion's interior nodes, the
/// propagated scheme's interior nodes, the end.
pub(super) const NODES: [f64; 6] = [A1, A2, B1, 0.5, B3, 1.0];
/// The end node's index in [`NODES`].
pub(super) const END: usize = 5;
/// The propagated scheme: its nodes after the start, as indices into [`NODES`].
pub(super) const NODES8: [usize; 4] = [2, 3, 4, END];
/// The companion: its nodes after the start, as indices into [`NODES`].
pub(super) const NODES6: [usize; 3] = [0, 1, END];
/// Lobatto weights of the 5-node scheme on [0, 1] (nodes 0, B1, ½, B3, 1): exact for
/// polynomials of degree 7.
pub(super) const WEIGHTS8: [f64; 5] = [
    1.0 / 20.0,
    49.0 / 180.0,
    16.0 / 45.0,
    49.0 / 180.0,
    1.0 / 20.0,
];
/// The 5-node scheme's nodes on [0, 1], start included.
pub(super) const THETA8: [f64; 5] = [0.0, B1, 0.5, B3, 1.0];
/// The 4-node scheme's nodes on [0, 1], start included.
const THETA6: [f64; 4] = [0.0, A1, A2, 1.0];

/// Coefficients of the Lagrange basis of `theta`: `ℓ_p(x) = Σ_m out[m][p] x^m` (the inverse
/// of the Vandermonde matrix, by Gauss–Jordan with partial pivoting; at most 5×5 and well
/// conditioned).
fn lagrange<const S: usize>(theta: &[f64; S]) -> [[f64; S]; S] {
    let mut a = [[0.0; 14]; 7];
    for i in 0..S {
        for m in 0..S {
            a[i][m] = power(theta[i], m as u32);
        }
        a[i][S + i] = 1.0;
    }
    for col in 0..S {
        let p = (col..S)
            .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
            .unwrap_or(col);
        a.swap(col, p);
        let d = a[col][col];
        for x in a[col].iter_mut() {
            *x /= d;
        }
        for r in 0..S {
            if r != col {
                let f = a[r][col];
                let row = a[col];
                for (x, y) in a[r].iter_mut().zip(row) {
                    *x -= f * y;
                }
            }
        }
    }
    let mut inv = [[0.0; S]; S];
    for i in 0..S {
        for j in 0..S {
            inv[i][j] = a[i][S + j];
        }
    }
    inv
}

/// The coefficients of both schemes' Lagrange bases (computed once), and the weights that give
/// the 5-node scheme's quartic at the companion's interior nodes.
pub(super) struct Bases {
    l8: [[f64; 5]; 5],
    l6: [[f64; 4]; 4],
    /// `at6[i][p] = ℓ8_p(A_i)`: the quartic through the 5-node values at A1, A2.
    pub at6: [[f64; 5]; 2],
    /// `1/Π_{q≠p}(θ_p − θ_q)` over the 5 nodes (Lagrange form at any point).
    den8: [f64; 5],
    /// `partial[i][p] = ∫₀^{θ_{i+1}} ℓ8_p(x) dx`: the quadrature of the 5 nodal values from the
    /// start to the interior node i (B1, ½, B3), exact for quartics (tallies at dense output).
    pub partial: [[f64; 5]; 3],
    /// `first[p] = ∫₀¹ x ℓ8_p(x) dx`: the first moment of a quartic from its nodal values.
    pub first: [f64; 5],
    /// The interpolatory quadrature on every point a step knows the state at,
    /// [`SEVEN`] (exact to degree 7: symmetric): the work of the contacts with the law along the
    /// motion, whose defect against the force quartic vanishes at the 5 nodes and, to leading
    /// order, integrates to 0 against any quadratic weight.
    pub seven: [f64; 7],
}

/// 0, B1, A1, ½, A2, B3, 1: the nodes of both schemes.
pub(super) const SEVEN: [f64; 7] = [0.0, B1, A1, 0.5, A2, B3, 1.0];

/// See [`Bases`].
pub(super) fn bases() -> &'static Bases {
    static B: std::sync::OnceLock<Bases> = std::sync::OnceLock::new();
    B.get_or_init(|| {
        let l8 = lagrange(&THETA8);
        let at6 = [A1, A2]
            .map(|x| std::array::from_fn(|p| (0..5).map(|m| l8[m][p] * power(x, m as u32)).sum()));
        let den8 = std::array::from_fn(|p| {
            1.0 / (0..5)
                .filter(|&q| q != p)
                .map(|q| THETA8[p] - THETA8[q])
                .product::<f64>()
        });
        let partial = std::array::from_fn(|i| {
            let x = THETA8[i + 1];
            std::array::from_fn(|p| {
                (0..5)
                    .map(|m| l8[m][p] * power(x, m as u32 + 1) / (m + 1) as f64)
                    .sum()
            })
        });
        let first = std::array::from_fn(|p| (0..5).map(|m| l8[m][p] / (m + 2) as f64).sum());
        let l7 = lagrange(&SEVEN);
        let seven = std::array::from_fn(|p| (0..7).map(|m| l7[m][p] / (m + 1) as f64).sum());
        Bases {
            l8,
            l6: lagrange(&THETA6),
            at6,
            den8,
            partial,
            first,
            seven,
        }
    })
}

impl Bases {
    /// The value at x of the quartic through `values` at the 5-node scheme's nodes.
    #[inline]
    pub(super) fn quartic_at(&self, values: &[f64; 5], x: f64) -> f64 {
        let d: [f64; 5] = std::array::from_fn(|q| x - THETA8[q]);
        let mut sum = 0.0;
        for p in 0..5 {
            let mut l = self.den8[p];
            for q in 0..5 {
                if q != p {
                    l *= d[q];
                }
            }
            sum += l * values[p];
        }
        sum
    }
}

/// 1/k for k < 70 (the series' factorials without divisions).
fn reciprocals() -> &'static [f64; 70] {
    static R: std::sync::OnceLock<[f64; 70]> = std::sync::OnceLock::new();
    R.get_or_init(|| std::array::from_fn(|k| if k == 0 { 0.0 } else { 1.0 / k as f64 }))
}

/// Exact response (η, η̇) at times `s_i = θ_i h` from rest of one mode (ω rad/s, damp = 2ζω
/// 1/s) to the loads (τ/h)^m, m = 0..4, with the propagators `props[i] = P(s_i)`: into
/// `out[i][m]`. A series in `sA` (shared by the five loads) where `s(ω + damp)` is small, the
/// polynomial particular solution otherwise (no cancellation either way).
fn monomial_responses(
    omega: f64,
    damp: f64,
    h: f64,
    props: &[Prop; 6],
    out: &mut [[(f64, f64); 5]; 6],
) {
    let w2 = omega * omega;
    for (i, &th) in NODES.iter().enumerate() {
        let s = th * h;
        let o = &mut out[i];
        if s * (omega + damp) < 1.0 {
            // Σ_r (m!/h^m) s^{r+m+1}/(r+m+1)! A^r e₂, A = [[0, 1], [−ω², −damp]]
            let inv = reciprocals();
            let mut coef = [0.0; 5];
            let mut fact = 1.0; // m!/h^m
            for (m, c) in coef.iter_mut().enumerate() {
                if m > 0 {
                    fact *= m as f64 / h;
                }
                let mut x = fact;
                for q in 1..=(m + 1) {
                    x *= s / q as f64;
                }
                *c = x;
            }
            let (mut x, mut y) = (0.0, 1.0);
            let mut acc = [(0.0, 0.0); 5];
            for r in 0..60 {
                for m in 0..5 {
                    acc[m].0 += coef[m] * x;
                    acc[m].1 += coef[m] * y;
                    coef[m] *= s * inv[r + m + 2];
                }
                let (nx, ny) = (y, -w2 * x - damp * y);
                x = nx;
                y = ny;
                // (the m = 0 series converges slowest)
                if coef[0] * (x.abs() + y.abs())
                    < 1e-17 * (acc[0].0.abs() * w2.max(1.0) + acc[0].1.abs())
                {
                    break;
                }
            }
            *o = acc;
        } else {
            for m in 0..5 {
                // particular polynomial Σ u_r τ^r of the load τ^m/h^m
                let mut u = [0.0; 7];
                let cm = 1.0 / h.powi(m as i32);
                for r in (0..=m).rev() {
                    let c = if r == m { cm } else { 0.0 };
                    u[r] = (c
                        - damp * (r + 1) as f64 * u[r + 1]
                        - ((r + 2) * (r + 1)) as f64 * u[r + 2])
                        / w2;
                }
                let (mut e, mut d) = (0.0, 0.0);
                for r in (0..=m).rev() {
                    e = e * s + u[r];
                }
                for r in (1..=m).rev() {
                    d = d * s + r as f64 * u[r];
                }
                let (a, b) = props[i].apply(u[0], u[1]);
                o[m] = (e - a, d - b);
            }
        }
    }
}

/// One mode's part of a [`Table`]: what an accepted step needs of it, in one place.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct ModeStep {
    /// `P(h)`.
    pub end: Prop,
    /// (η, η̇) at the step's end from rest under the 5-node scheme's Lagrange load ℓ_p.
    pub end8: [(f64, f64); 5],
    /// `P(θh)` at the 5-node scheme's interior nodes (B1, ½, B3), for dense output.
    pub mid: [Prop; 3],
    /// (η, η̇) there under ℓ_p.
    pub mid8: [[(f64, f64); 5]; 3],
}

/// One mode's Γ_j of the level tables `W_kl = Σ_j c_kj c_lj Γ_j` (see [`Table::w8`]), or
/// one slot's sum of them: the 5-node scheme's at its 4 nodes, the companion's at its 3, the
/// 5-node scheme's at the companion's 2 interior nodes.
#[derive(Debug, Clone, Copy)]
struct Gammas {
    g8: [(f64, f64); 20],
    g6: [(f64, f64); 12],
    g86: [(f64, f64); 10],
}

impl Default for Gammas {
    fn default() -> Gammas {
        Gammas {
            g8: [(0.0, 0.0); 20],
            g6: [(0.0, 0.0); 12],
            g86: [(0.0, 0.0); 10],
        }
    }
}

/// Everything of a step of length h that does not depend on the state.
pub(super) struct Table {
    /// Step length, s.
    pub h: f64,
    /// Modes.
    n: usize,
    /// `c_kj·(p11, p21, p12, p22)` of `P(θh)` at every node of [`NODES`] (the columns in
    /// pairs: (η, η̇) from η₀, then from η̇₀), level by level over the level's pair's modes
    /// only (`System::coupling_modes`; c_kj = 0 elsewhere): level k's block starts at
    /// `cstart[k]`, node i's row of it at `i·n_k` (see [`Table::cprop_at`]). The free
    /// flight's δ, δ̇ at the nodes are two dot products per node and level.
    cprop: Vec<[f64; 4]>,
    /// Where each level's block of `cprop` starts (L + 1 entries).
    cstart: Vec<usize>,
    /// Per mode, see [`ModeStep`].
    pub modes: Vec<ModeStep>,
    /// Per mode, its responses to the Lagrange loads in the level tables' layout (scratch of
    /// [`Table::fill`]).
    gammas: Vec<Gammas>,
    /// Level tables of the 5-node scheme: the response of `c_k·η` (and `c_k·η̇`) at its node i
    /// (B1, ½, B3, end) to a unit force at level l shaped as ℓ_p,
    /// `Σ_j c_kj c_lj Γ_j(i, p)`: `[(kl·4 + i)·5 + p]`, kl = `System::band_slot(k, l)`. Banded:
    /// only the levels l sharing a structure with k are stored (`System::sharing_levels`; the
    /// others' weights are sums of zeros); a pair's band is every level (kl = k·L + l).
    pub w8: Vec<(f64, f64)>,
    /// The same for the 4-node companion at its nodes (A1, A2, end): `[(kl·3 + i)·4 + p]`.
    pub w6: Vec<(f64, f64)>,
    /// The 5-node scheme's response at the companion's interior nodes (A1, A2), for the work
    /// of the contacts along the computed motion: `[(kl·2 + i)·5 + p]`.
    pub w86: Vec<(f64, f64)>,
    /// Harmonic motion: (sin Ωθh, cos Ωθh) at every node of [`NODES`].
    pub rot: [(f64, f64); 6],
    /// Harmonic motion: `(∫₀ʰ ℓ_p(τ/h) cos Ωτ dτ, ∫₀ʰ ℓ_p(τ/h) sin Ωτ dτ)` of the 5-node
    /// scheme's Lagrange loads (s), for the ground's exact work under a contact load.
    pub hmom: [(f64, f64); 5],
    /// Per structure, whether its modes' responses to the Lagrange loads are filled (a row's
    /// structures out of contact are not: see [`Table::fill_for`]), and which were filled by
    /// the last fill (scratch).
    done: Vec<bool>,
    fresh: Vec<bool>,
}

impl Table {
    /// The table of step length `h` for `sys` (Ω of a harmonic motion in `big`), every
    /// structure's modes filled.
    #[cfg(test)]
    pub(super) fn new(sys: &System, big: Option<f64>, h: f64) -> Table {
        Table::new_for(sys, big, h, &vec![true; sys.structures.len()])
    }

    /// The table of step length `h` with the responses to the Lagrange loads of the
    /// structures `active` marks only (see [`Table::fill_for`]).
    pub(super) fn new_for(sys: &System, big: Option<f64>, h: f64, active: &[bool]) -> Table {
        let mut t = Table {
            h: f64::NAN,
            n: 0,
            cprop: Vec::new(),
            cstart: Vec::new(),
            modes: Vec::new(),
            gammas: Vec::new(),
            w8: Vec::new(),
            w6: Vec::new(),
            w86: Vec::new(),
            rot: [(0.0, 1.0); 6],
            hmom: [(0.0, 0.0); 5],
            done: Vec::new(),
            fresh: Vec::new(),
        };
        t.fill_for(sys, big, h, active);
        t
    }

    /// Whether the structures `active` marks are all filled (see [`Table::ensure`]).
    #[inline]
    pub(super) fn covers(&self, active: &[bool]) -> bool {
        active.iter().zip(&self.done).all(|(&a, &d)| d || !a)
    }

    /// Fill the structures `active` marks that are not filled yet (their responses to the
    /// Lagrange loads, and the level-table slots that sum over them): a row's contact step
    /// that grows its set of active structures ([`Table::fill_for`]).
    pub(super) fn ensure(&mut self, sys: &System, active: &[bool]) {
        if self.covers(active) {
            return;
        }
        let (omega, damp) = (sys.omega(), sys.damping_coefficients());
        let h = self.h;
        self.fresh.clear();
        self.fresh
            .extend(active.iter().zip(&self.done).map(|(&a, &d)| a && !d));
        for s in 0..sys.structures.len() {
            if self.fresh[s] {
                for j in sys.modes_of(s) {
                    let props: [Prop; 6] = NODES.map(|x| propagator(omega[j], damp[j], x * h));
                    self.fill_mode(omega[j], damp[j], h, j, &props);
                }
                self.done[s] = true;
            }
        }
        self.fill_slots(sys);
    }

    /// Recompute for step length `h` (the buffers are reused): every mode's propagators to the
    /// nodes (the free flight to them, and the state of a mode no contact force acts on), and
    /// the responses to the Lagrange loads of the structures `active` marks only — of a row,
    /// the structures of the pairs in (or near) contact: a mode of any other structure carries
    /// no contact force over the step (its responses would multiply zeros), and a level-table
    /// slot is summed only when every structure it sums over is filled. A pair: both.
    pub(super) fn fill_for(&mut self, sys: &System, big: Option<f64>, h: f64, active: &[bool]) {
        let (omega, damp) = (sys.omega(), sys.damping_coefficients());
        let n = sys.len();
        let nl = sys.levels.len();
        self.h = h;
        self.n = n;
        let Bases { l8, .. } = bases();
        if let Some(big) = big {
            self.rot = NODES.map(|x| (big * x * h).sin_cos());
            let moments = trig_moments(big * h);
            self.hmom = std::array::from_fn(|p| {
                let (mut a, mut b) = (0.0, 0.0);
                for m in 0..5 {
                    a += l8[m][p] * moments[m].0;
                    b += l8[m][p] * moments[m].1;
                }
                (h * a, h * b)
            });
        }
        // (every entry of `cprop`, `modes`, `gammas` and the level tables is written below:
        // nothing is cleared)
        self.cstart.clear();
        self.cstart.push(0);
        for k in 0..nl {
            let w = sys.coupling_modes(k).len();
            self.cstart.push(self.cstart[k] + 6 * w);
        }
        self.cprop.resize(self.cstart[nl], [0.0; 4]);
        self.modes.resize(n, ModeStep::default());
        self.gammas.resize(n, Gammas::default());
        let slots = sys.band_slots();
        for (t, per) in [(&mut self.w8, 20), (&mut self.w6, 12), (&mut self.w86, 10)] {
            t.resize(slots * per, (0.0, 0.0));
        }
        self.done.clear();
        self.done.extend_from_slice(active);
        self.fresh.clear();
        self.fresh.extend_from_slice(active);
        for j in 0..n {
            let props: [Prop; 6] = NODES.map(|x| propagator(omega[j], damp[j], x * h));
            // (of a row, only the levels whose pair holds mode j: c_kj = 0 for the others)
            for k in sys.levels_of_mode(j) {
                let c = sys.coupling(k)[j];
                let modes = sys.coupling_modes(k);
                let (w, at) = (modes.len(), self.cstart[k] + j - modes.start);
                for (i, p) in props.iter().enumerate() {
                    self.cprop[at + i * w] = [c * p.p11, c * p.p21, c * p.p12, c * p.p22];
                }
            }
            if self.done[sys.structure_of_mode(j).0] {
                self.fill_mode(omega[j], damp[j], h, j, &props);
            } else {
                // (a passive mode: its free flight to the end and the interior nodes only)
                let ms = &mut self.modes[j];
                ms.end = props[END];
                ms.mid = [props[NODES8[0]], props[NODES8[1]], props[NODES8[2]]];
            }
        }
        self.fill_slots(sys);
    }

    /// Mode j's responses to the Lagrange loads (its [`ModeStep`] and Γ_j), from its
    /// propagators to the nodes.
    fn fill_mode(&mut self, omega: f64, damp: f64, h: f64, j: usize, props: &[Prop; 6]) {
        let Bases { l8, l6, .. } = bases();
        {
            let mut mono = [[(0.0, 0.0); 5]; 6];
            monomial_responses(omega, damp, h, props, &mut mono);
            // this mode's responses to the Lagrange loads: the 5-node scheme's at its 4 nodes
            // and at the companion's 2 interior ones, the companion's at its 3
            let lagrange8 = |node: usize| -> [(f64, f64); 5] {
                std::array::from_fn(|p| {
                    let (mut a, mut b) = (0.0, 0.0);
                    for m in 0..5 {
                        a += l8[m][p] * mono[node][m].0;
                        b += l8[m][p] * mono[node][m].1;
                    }
                    (a, b)
                })
            };
            let g8: [[(f64, f64); 5]; 4] = NODES8.map(lagrange8);
            let g86: [[(f64, f64); 5]; 2] = [lagrange8(0), lagrange8(1)];
            let g6: [[(f64, f64); 4]; 3] = NODES6.map(|node| {
                std::array::from_fn(|p| {
                    let (mut a, mut b) = (0.0, 0.0);
                    for m in 0..4 {
                        a += l6[m][p] * mono[node][m].0;
                        b += l6[m][p] * mono[node][m].1;
                    }
                    (a, b)
                })
            });
            self.modes[j] = ModeStep {
                end: props[END],
                end8: g8[3],
                mid: [props[NODES8[0]], props[NODES8[1]], props[NODES8[2]]],
                mid8: [g8[0], g8[1], g8[2]],
            };
            let g = &mut self.gammas[j];
            g.g8.copy_from_slice(g8.as_flattened());
            g.g6.copy_from_slice(g6.as_flattened());
            g.g86.copy_from_slice(g86.as_flattened());
        }
    }

    /// The level tables, slot by slot over each level's band: the sum over the modes both
    /// levels couple to (c_kj c_lj = 0 on every other mode), in mode order from 0 — the slots
    /// whose structures are all filled and one of them just now (`fresh`).
    fn fill_slots(&mut self, sys: &System) {
        let nl = sys.levels.len();
        for k in 0..nl {
            let (ck, mk) = (sys.coupling(k), sys.coupling_modes(k));
            let pk = sys.levels[k].pair;
            for l in sys.sharing_levels(k) {
                let (cl, ml) = (sys.coupling(l), sys.coupling_modes(l));
                // (the structures both pairs hold)
                let pl = sys.levels[l].pair;
                let shared = pk.max(pl)..(pk.min(pl) + 2);
                if !shared.clone().all(|s| self.done[s]) || !shared.clone().any(|s| self.fresh[s]) {
                    continue;
                }
                let mut sum = Gammas::default();
                for j in mk.start.max(ml.start)..mk.end.min(ml.end) {
                    let w = ck[j] * cl[j];
                    if w == 0.0 {
                        continue;
                    }
                    let g = &self.gammas[j];
                    let add = |t: &mut [(f64, f64)], g: &[(f64, f64)]| {
                        for (e, g) in t.iter_mut().zip(g) {
                            e.0 += w * g.0;
                            e.1 += w * g.1;
                        }
                    };
                    add(&mut sum.g8, &g.g8);
                    add(&mut sum.g6, &g.g6);
                    add(&mut sum.g86, &g.g86);
                }
                let kl = sys.band_slot(k, l);
                self.w8[kl * 20..(kl + 1) * 20].copy_from_slice(&sum.g8);
                self.w6[kl * 12..(kl + 1) * 12].copy_from_slice(&sum.g6);
                self.w86[kl * 10..(kl + 1) * 10].copy_from_slice(&sum.g86);
            }
        }
    }

    /// Modes the table was made for.
    pub(super) fn modes(&self) -> usize {
        self.n
    }

    /// Level k's coupled propagators at node i of [`NODES`], over `sys.coupling_modes(k)`
    /// (the same system the table was filled for; the steps take all six at once,
    /// [`Table::cprop_rows`]).
    #[cfg(test)]
    pub(super) fn cprop_at(&self, sys: &System, k: usize, i: usize) -> &[[f64; 4]] {
        let w = sys.coupling_modes(k).len();
        let at = self.cstart[k] + i * w;
        &self.cprop[at..at + w]
    }

    /// Level k's coupled propagators at the six nodes of [`NODES`] (see [`Table::cprop_at`]),
    /// in one call.
    #[inline]
    pub(super) fn cprop_rows(&self, sys: &System, k: usize) -> [&[[f64; 4]]; 6] {
        let w = sys.coupling_modes(k).len();
        let block = &self.cprop[self.cstart[k]..self.cstart[k] + 6 * w];
        std::array::from_fn(|i| &block[i * w..(i + 1) * w])
    }

    /// The coupled propagators of a pair's single contact level (`n` modes, all coupled):
    /// node i's row at `[i·n..(i + 1)·n]`, as [`Table::cprop_at`] gives them one by one.
    #[inline]
    pub(super) fn cprop_single(&self, n: usize) -> &[[f64; 4]] {
        &self.cprop[..6 * n]
    }
}

/// `(∫₀¹ x^m cos ax dx, ∫₀¹ x^m sin ax dx)` for m = 0..4: a series for |a| < 2, else the
/// recursion `I_m = (e^{ia} − m I_{m−1})/(ia)` (each step divides the error by |a|/m).
fn trig_moments(a: f64) -> [(f64, f64); 5] {
    let mut out = [(0.0, 0.0); 5];
    if a.abs() < 2.0 {
        // Σ_r (ia)^r/(r!·(m + r + 1)): real parts from even r, imaginary from odd
        for (m, o) in out.iter_mut().enumerate() {
            let (mut re, mut im) = (0.0, 0.0);
            let mut term = 1.0; // a^r/r!
            for r in 0..40 {
                let x = term / (m + r + 1) as f64;
                match r % 4 {
                    0 => re += x,
                    1 => im += x,
                    2 => re -= x,
                    _ => im -= x,
                }
                term *= a / (r + 1) as f64;
                if term.abs() < 1e-18 {
                    break;
                }
            }
            *o = (re, im);
        }
    } else {
        let (s, c) = a.sin_cos();
        // I_0 = (e^{ia} − 1)/(ia) = (sin a + i(1 − cos a))/a
        let mut prev = (s / a, (1.0 - c) / a);
        out[0] = prev;
        for (m, o) in out.iter_mut().enumerate().skip(1) {
            // (e^{ia} − m·I)/(ia) = (Im(e^{ia} − mI) − i Re(e^{ia} − mI))/a
            let (re, im) = (c - m as f64 * prev.0, s - m as f64 * prev.1);
            prev = (im / a, -re / a);
            *o = prev;
        }
    }
    out
}

/// Scratch of the Newton iterations on the nodal forces.
#[derive(Default)]
pub(super) struct Newton {
    rhs: Vec<f64>,
    /// Per unknown, the law's derivatives (∂φ/∂δ, ∂φ/∂δ̇) at its node: its Jacobian row is
    /// `e_r + kd·w.0 + kv·w.1`, assembled only for the unknowns in contact, over the levels
    /// sharing a structure with its own (the rest of the row is exactly zero).
    slopes: Vec<(f64, f64)>,
    /// Per unknown, whether its node is out of contact (the law's force and derivatives 0:
    /// its row of the Jacobian is the identity's).
    free: Vec<bool>,
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
    /// Of the level a pass is at, the levels of its band that carry force: where their
    /// weights' block starts in the level table, and where their forces start.
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
pub(super) struct NoConvergence;

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
pub(super) fn solve<const S: usize>(
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
        for &k in levels {
            let law = &sys.levels[k].force;
            let band = sys.sharing_levels(k);
            let first = sys.band_slot(k, band.start);
            // (the band's levels in order, those out of contact throughout skipped: the same
            // sums as over every level of the band, term for term)
            let Newton {
                rhs,
                slopes,
                free,
                quiet,
                loaded,
                ..
            } = &mut *scratch;
            loaded.clear();
            for l in band.clone() {
                if !quiet[l] {
                    loaded.push(((first + (l - band.start)) * m * S, l * S));
                }
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
            for p in 0..m {
                let (mut d, mut dd) = df[p];
                for &(at, fat) in loaded.iter() {
                    let row: &[(f64, f64); S] = w[at + p * S..at + (p + 1) * S]
                        .try_into()
                        .expect("S weights");
                    let fl: &[f64; S] = force[fat..fat + S].try_into().expect("S forces");
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
pub(super) fn nodal_states<const S: usize>(
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

/// [`solve`] for a single contact level (the common case): the same iterations on stack
/// arrays, the elimination unrolled by the compiler for the scheme's S − 1 unknowns.
fn solve_one<const S: usize>(
    sys: &System,
    w: &[(f64, f64)],
    dfree: &[(f64, f64)],
    onset: &[f64],
    force: &mut [f64],
    nodal: &mut [(f64, f64)],
    tol: f64,
) -> Result<usize, NoConvergence> {
    const MAX: usize = 4;
    let m = S - 1;
    let law = &sys.levels[0].force;
    let w = &w[..m * S];
    let (dfree, nodal, force) = (&dfree[..m], &mut nodal[..m], &mut force[..S]);
    let mut last = f64::INFINITY;
    for iter in 1..=30 {
        let mut rhs = [0.0; MAX];
        let mut slopes = [(0.0, 0.0); MAX];
        let mut scale: f64 = 0.0;
        for p in 0..m {
            let row = &w[p * S..(p + 1) * S];
            let (mut d, mut dd) = dfree[p];
            for q in 0..S {
                d -= row[q].0 * force[q];
                dd -= row[q].1 * force[q];
            }
            nodal[p] = (d, dd);
            let v0 = episode_v0(onset[0], dd);
            let (phi, kd, kv) = law.force_jacobian(d, dd, v0);
            let f = force[p + 1];
            rhs[p] = phi - f;
            slopes[p] = (kd, kv);
            scale = fmax(fmax(scale, phi.abs()), f.abs());
        }
        let residual = rhs[..m].iter().fold(0.0f64, |a, x| fmax(a, x.abs()));
        if !residual.is_finite() {
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
            let mut piv = col;
            for r in col + 1..m {
                if jac[r][col].abs() > jac[piv][col].abs() {
                    piv = r;
                }
            }
            if jac[piv][col] == 0.0 || !jac[piv][col].is_finite() {
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
pub(super) fn solve_single<const S: usize>(
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
fn solve_touching<const S: usize>(
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
            let at = (slot * m + p) * S;
            let ws = &w[at + 1..at + S];
            for (q, x) in ws.iter().enumerate() {
                let c = l * m + q;
                let e = kd * x.0 + kv * x.1;
                let e = if c == r { e + 1.0 } else { e };
                if free[c] {
                    b -= e * rhs[c];
                } else {
                    row[pos[c]] = e;
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

/// Solve `a·x = b` in place (b becomes x; `a` is destroyed) by Gaussian elimination with
/// partial pivoting; false if singular.
fn lu_solve(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
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
pub(super) fn start_force(sys: &System, k: usize, st: &LevelState, onset: f64, tol: f64) -> f64 {
    if st.delta <= 0.0 && st.delta >= -tol && st.delta_dot > 0.0 {
        let v0 = if onset > 0.0 { onset } else { st.delta_dot };
        sys.levels[k]
            .force
            .force(f64::MIN_POSITIVE, st.delta_dot, v0)
    } else {
        st.force
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::linear::monomial_influence;

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
                                assert_eq!(
                                    t.w8[(kl * 4 + i) * 5 + p],
                                    (a, b),
                                    "w8 {k} {l} {i} {p}"
                                );
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
}
