//! One step of `adaptive`: the Lobatto IIIA collocation tables of a step length (nodes,
//! Vandermonde inverse, propagators and influences), the work arrays, the exact free flight at
//! the nodes, and the Newton solve of the collocation equations with its tallies.

// Index loops over parallel per-mode arrays read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::*;

/// Gauss–Lobatto weights on [0, 1] for the nodes below.
pub(super) const WEIGHTS: [f64; 4] = [1.0 / 12.0, 5.0 / 12.0, 5.0 / 12.0, 1.0 / 12.0];

pub(super) fn nodes() -> [f64; 4] {
    let r = 1.0 / 5f64.sqrt();
    [0.0, 0.5 * (1.0 - r), 0.5 * (1.0 + r), 1.0]
}

/// Inverse of the Vandermonde matrix V_im = θ_i^m of the nodes: a = V⁻¹ F.
pub(super) fn vandermonde_inverse() -> [[f64; 4]; 4] {
    let th = nodes();
    let mut a = [[0.0; 8]; 4];
    for i in 0..4 {
        for m in 0..4 {
            a[i][m] = power(th[i], m as u32);
        }
        a[i][4 + i] = 1.0;
    }
    // Gauss–Jordan with partial pivoting (4×4, well conditioned)
    for col in 0..4 {
        let p = (col..4)
            .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
            .unwrap_or(col);
        a.swap(col, p);
        let d = a[col][col];
        for x in a[col].iter_mut() {
            *x /= d;
        }
        for r in 0..4 {
            if r != col {
                let f = a[r][col];
                let row = a[col];
                for (x, y) in a[r].iter_mut().zip(row) {
                    *x -= f * y;
                }
            }
        }
    }
    let mut inv = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            inv[i][j] = a[i][4 + j];
        }
    }
    inv
}

/// Everything that depends on the step length only.
pub(super) struct Table {
    pub(super) h: f64,
    /// P(θ_i h) for nodes 1..3: `[(i−1)·n + j]`.
    pub(super) props: Vec<Prop>,
    /// Influence of (τ/h)^m at node i = 1..3: `[((i−1)·4 + m)·n + j]`.
    pub(super) gam: Vec<(f64, f64)>,
    /// `Σ_j c_kj c_lj Γ_{j,i,m}`: `[((k·L + l)·3 + (i−1))·4 + m]`.
    pub(super) mm: Vec<(f64, f64)>,
    /// Harmonic motion: (sin Ωθ_i h, cos Ωθ_i h) for the 4 nodes and (sin Ωh/2, cos Ωh/2), so
    /// that a step needs one libm sin/cos (at its start) instead of seven.
    pub(super) rot: [(f64, f64); 4],
    pub(super) half: (f64, f64),
}

impl Table {
    /// sin, cos of the harmonic motion at the 4 nodes of a step from t, from those at t.
    pub(super) fn trigs(&self, tr0: Trig, t: f64) -> [Trig; 4] {
        let th = nodes();
        std::array::from_fn(|i| {
            let (sh, ch) = self.rot[i];
            Trig {
                t: t + th[i] * self.h,
                s: tr0.s * ch + tr0.c * sh,
                c: tr0.c * ch - tr0.s * sh,
            }
        })
    }

    pub(super) fn new() -> Table {
        Table {
            h: f64::NAN,
            props: Vec::new(),
            gam: Vec::new(),
            mm: Vec::new(),
            rot: [(0.0, 1.0); 4],
            half: (0.0, 1.0),
        }
    }

    pub(super) fn fill(&mut self, sys: &System, h: f64) {
        let (omega, damp) = (sys.omega(), sys.damping_coefficients());
        let n = sys.len();
        let nl = sys.levels.len();
        let th = nodes();
        self.h = h;
        if let GroundMotion::Harmonic(hm) = &sys.ground {
            self.rot = th.map(|x| (hm.omega * x * h).sin_cos());
            self.half = (0.5 * hm.omega * h).sin_cos();
        }
        self.props.clear();
        self.gam.clear();
        self.gam.resize(12 * n, (0.0, 0.0));
        for (i, &t) in th.iter().enumerate().skip(1) {
            for j in 0..n {
                let p = propagator(omega[j], damp[j], t * h);
                self.props.push(p);
                let g = monomial_influence(omega[j], damp[j], t * h, h, &p);
                for (m, gm) in g.iter().enumerate() {
                    self.gam[((i - 1) * 4 + m) * n + j] = *gm;
                }
            }
        }
        self.mm.clear();
        self.mm.resize(nl * nl * 12, (0.0, 0.0));
        for k in 0..nl {
            for l in 0..nl {
                let (ck, cl) = (sys.coupling(k), sys.coupling(l));
                for im in 0..12 {
                    let g = &self.gam[im * n..(im + 1) * n];
                    let mut s = (0.0, 0.0);
                    for j in 0..n {
                        let w = ck[j] * cl[j];
                        s.0 += w * g[j].0;
                        s.1 += w * g[j].1;
                    }
                    self.mm[(k * nl + l) * 12 + im] = s;
                }
            }
        }
    }
}

pub(super) struct Work {
    pub(super) n: usize,
    pub(super) nl: usize,
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) qn: Vec<f64>,
    pub(super) vn: Vec<f64>,
    /// Free-flight velocities at nodes 1 and 2.
    pub(super) vf: [Vec<f64>; 2],
    pub(super) cpoly: Vec<[f64; 3]>,
    /// Free-flight δ, δ̇ at nodes 1..3 per level: `[k·3 + i − 1]`.
    pub(super) dfree: Vec<(f64, f64)>,
    /// Nodal forces `[k·4 + i]`, their cubic's coefficients `[k·4 + m]`, and the nodal δ, δ̇.
    pub(super) fnode: Vec<f64>,
    pub(super) coef: Vec<f64>,
    pub(super) dnode: Vec<(f64, f64)>,
    pub(super) aq: Vec<f64>,
    pub(super) av: Vec<f64>,
    pub(super) vinv: [[f64; 4]; 4],
    /// Coupling rows transposed, mode-major: `[j·L + k]`.
    pub(super) cpl_t: Vec<f64>,
    /// Step doubling: the single step's end state, the saved start, the midpoint's level
    /// states and the halves' impulses.
    pub(super) q_full: Vec<f64>,
    pub(super) v_full: Vec<f64>,
    pub(super) q_save: Vec<f64>,
    pub(super) v_save: Vec<f64>,
    pub(super) mid_states: Vec<LevelState>,
    pub(super) imp_half: Vec<f64>,
}

impl Work {
    pub(super) fn new(sys: &System, q: Vec<f64>, v: Vec<f64>, aq: Vec<f64>, av: Vec<f64>) -> Work {
        let n = sys.len();
        let nl = sys.levels.len();
        Work {
            n,
            nl,
            q,
            v,
            qn: vec![0.0; n],
            vn: vec![0.0; n],
            vf: [vec![0.0; n], vec![0.0; n]],
            cpoly: vec![[0.0; 3]; n],
            dfree: vec![(0.0, 0.0); 3 * nl],
            fnode: vec![0.0; 4 * nl],
            coef: vec![0.0; 4 * nl],
            dnode: vec![(0.0, 0.0); 4 * nl],
            aq,
            av,
            vinv: vandermonde_inverse(),
            cpl_t: (0..n)
                .flat_map(|j| (0..nl).map(move |k| sys.coupling(k)[j]))
                .collect(),
            q_full: vec![0.0; n],
            v_full: vec![0.0; n],
            q_save: vec![0.0; n],
            v_save: vec![0.0; n],
            mid_states: vec![LevelState::default(); nl],
            imp_half: vec![0.0; nl],
        }
    }
}

/// Outcome of one trial step.
#[derive(Debug, Clone, Copy)]
pub(super) struct Trial {
    pub(super) err: f64,
    /// Contact forces were zero throughout: the step is exact.
    pub(super) free: bool,
    pub(super) input: f64,
    pub(super) damping: f64,
    pub(super) contact: f64,
}

/// Free flight (ground only) from the start state to the given nodes (1..=3): the state at the
/// end node into (qn, vn), velocities at nodes 1, 2 into `vf`, and δ, δ̇ at the nodes.
#[allow(clippy::too_many_arguments)]
pub(super) fn free_nodes(
    sys: &System,
    gm: &GroundModes,
    tab: &Table,
    w: &mut Work,
    piece: &Piece,
    poly: bool,
    t: f64,
    trs: &[Trig; 4],
    which: &[usize],
) {
    let (n, nl) = (w.n, w.nl);
    let h = tab.h;
    let th = nodes();
    let mut nodes_out = NodesOut {
        dfree: &mut w.dfree,
        qn: &mut w.qn,
        vn: &mut w.vn,
        vf: &mut w.vf,
    };
    let (q, v, cpl) = (&w.q[..n], &w.v[..n], &w.cpl_t[..n * nl]);
    match (piece, gm.harmonic_plain()) {
        (Piece::Harmonic, Some((big, g_re, g_im))) => {
            // harmonic motion: the particular solution is G_re sin Ωt + G_im cos Ωt
            let (g_re, g_im) = (&g_re[..n], &g_im[..n]);
            propagate(tab, q, v, cpl, which, &mut nodes_out, |j, i| {
                let (gr, gi, tr) = (g_re[j], g_im[j], &trs[i]);
                (gr * tr.s + gi * tr.c, big * (gr * tr.c - gi * tr.s))
            });
        }
        _ => {
            for (j, c) in w.cpoly.iter_mut().enumerate() {
                *c = if poly {
                    gm.poly_load(j, piece, t)
                } else {
                    [0.0; 3]
                };
            }
            let cpoly = &w.cpoly[..n];
            propagate(tab, q, v, cpl, which, &mut nodes_out, |j, i| {
                gm.particular(j, piece, &cpoly[j], th[i] * h, &trs[i])
            });
        }
    }
    // the sums hold −c·η; δ = −c·η − d through the one penetration (−(−s) is s exactly, so
    // this is the former `s − d` bit for bit)
    for (k, lv) in sys.levels.iter().enumerate() {
        for &i in which {
            let d = &mut w.dfree[k * 3 + i - 1].0;
            *d = lv.delta(-*d);
        }
    }
}

/// Where [`propagate`] writes: δ, δ̇ sums per level and node, the end state, node velocities.
pub(super) struct NodesOut<'a> {
    pub(super) dfree: &'a mut [(f64, f64)],
    pub(super) qn: &'a mut [f64],
    pub(super) vn: &'a mut [f64],
    pub(super) vf: &'a mut [Vec<f64>; 2],
}

/// The mode loop of [`free_nodes`], generic over the particular solution `part(j, node)` so that
/// harmonic and polynomial loads each get a loop without a branch per mode (slices cut to n
/// once: no bounds checks inside).
pub(super) fn propagate(
    tab: &Table,
    q: &[f64],
    v: &[f64],
    cpl: &[f64],
    which: &[usize],
    out: &mut NodesOut,
    part: impl Fn(usize, usize) -> (f64, f64),
) {
    let n = q.len();
    let nl = cpl.len() / n.max(1);
    let (v, props) = (&v[..n], &tab.props[..3 * n]);
    for j in 0..n {
        let (e0, d0) = part(j, 0);
        let (x0, y0) = (q[j] - e0, v[j] - d0);
        for &i in which {
            let (e, d) = part(j, i);
            let (x, y) = props[(i - 1) * n + j].apply(x0, y0);
            let (x, y) = (x + e, y + d);
            for k in 0..nl {
                let ck = cpl[j * nl + k];
                out.dfree[k * 3 + i - 1].0 -= ck * x;
                out.dfree[k * 3 + i - 1].1 -= ck * y;
            }
            if i == 3 {
                out.qn[j] = x;
                out.vn[j] = y;
            } else {
                out.vf[i - 1][j] = y;
            }
        }
    }
}

#[allow(clippy::too_many_arguments)]
pub(super) fn step(
    sys: &System,
    gm: &GroundModes,
    tab: &Table,
    w: &mut Work,
    onset: &[f64],
    start: &[LevelState],
    t: f64,
    piece: &Piece,
    imp: &mut [f64],
) -> Trial {
    let (n, nl) = (w.n, w.nl);
    let h = tab.h;
    let th = nodes();
    let trs = tab.trigs(gm.trig(t), t);
    let poly = matches!(piece, Piece::Poly { .. });
    w.dfree.iter_mut().for_each(|d| *d = (0.0, 0.0));
    let quiet = start.iter().all(|s| s.force == 0.0 && s.delta <= 0.0);
    // the end node first: if the free flight stays clear of contact from the start to the end
    // (cubic Hermite through both), it is the exact answer and the interior nodes are not needed
    free_nodes(sys, gm, tab, w, piece, poly, t, &trs, &[3]);
    let clear_to_end = |w: &Work| {
        (0..nl).all(|k| {
            let (d, dd) = w.dfree[k * 3 + 2];
            hermite_max(start[k].delta, start[k].delta_dot, d, dd, h).0 < 0.0
        })
    };
    let free = Trial {
        err: 0.0,
        free: true,
        input: 0.0,
        damping: 0.0,
        contact: 0.0,
    };
    if quiet && clear_to_end(w) {
        imp.iter_mut().for_each(|x| *x = 0.0);
        return free;
    }
    free_nodes(sys, gm, tab, w, piece, poly, t, &trs, &[1, 2]);
    // no contact force at the start, and the free flight stays clear (nodes, and the cubic
    // Hermite between consecutive nodes): the free flight is the exact answer
    let clear = quiet
        && (0..nl).all(|k| {
            let mut prev = (start[k].delta, start[k].delta_dot, 0.0);
            (0..3).all(|i| {
                let (d, dd) = w.dfree[k * 3 + i];
                let (m, _) = hermite_max(prev.0, prev.1, d, dd, (th[i + 1] - prev.2) * h);
                prev = (d, dd, th[i + 1]);
                m < 0.0
            })
        });
    if clear {
        imp.iter_mut().for_each(|x| *x = 0.0);
        return free;
    }
    // fixed point on the nodal forces
    for (k, lv) in sys.levels.iter().enumerate() {
        let f0 = if at_located_onset(&start[k]) {
            // the step starts on a located onset (δ = 0⁻ to 1e-12 m): the force at its start is
            // the law's right limit, c·δ̇ for Kelvin, not the 0 of δ ≤ 0
            let dd = start[k].delta_dot;
            let v0 = episode_v0(onset[k], dd);
            lv.force.force(f64::MIN_POSITIVE, dd, v0)
        } else {
            start[k].force
        };
        for i in 0..4 {
            w.fnode[k * 4 + i] = f0;
        }
        w.dnode[k * 4] = (start[k].delta, start[k].delta_dot);
    }
    let mut converged = false;
    for _ in 0..80 {
        for k in 0..nl {
            for m in 0..4 {
                w.coef[k * 4 + m] = (0..4).map(|i| w.vinv[m][i] * w.fnode[k * 4 + i]).sum();
            }
        }
        let mut change: f64 = 0.0;
        let mut scale: f64 = 0.0;
        for (k, lv) in sys.levels.iter().enumerate() {
            for i in 1..4 {
                let (mut d, mut dd) = w.dfree[k * 3 + i - 1];
                for l in 0..nl {
                    let base = (k * nl + l) * 12 + (i - 1) * 4;
                    for m in 0..4 {
                        let a = w.coef[l * 4 + m];
                        d -= a * tab.mm[base + m].0;
                        dd -= a * tab.mm[base + m].1;
                    }
                }
                w.dnode[k * 4 + i] = (d, dd);
                let v0 = episode_v0(onset[k], dd);
                let f = lv.force.force(d, dd, v0);
                let old = w.fnode[k * 4 + i];
                change = change.max((f - old).abs());
                scale = scale.max(f.abs()).max(old.abs());
                w.fnode[k * 4 + i] = f;
            }
        }
        if change <= 1e-14 * scale || !change.is_finite() {
            converged = change.is_finite();
            break;
        }
    }
    if !converged {
        return Trial {
            err: f64::INFINITY,
            free: false,
            input: 0.0,
            damping: 0.0,
            contact: 0.0,
        };
    }
    for k in 0..nl {
        for m in 0..4 {
            w.coef[k * 4 + m] = (0..4).map(|i| w.vinv[m][i] * w.fnode[k * 4 + i]).sum();
        }
    }
    // end state, nodal powers
    let damp = sys.damping_coefficients();
    let mut pw = [[0.0; 2]; 4];
    for j in 0..n {
        // contact load of mode j as a cubic in θ: Σ_l c_lj a_lm
        let mut g = [0.0; 4];
        for l in 0..nl {
            let c = w.cpl_t[j * nl + l];
            for (m, gm_) in g.iter_mut().enumerate() {
                *gm_ += c * w.coef[l * 4 + m];
            }
        }
        let (mut x, mut y) = (w.qn[j], w.vn[j]);
        for m in 0..4 {
            let gam = tab.gam[(8 + m) * n + j];
            x += g[m] * gam.0;
            y += g[m] * gam.1;
        }
        // velocities at the interior nodes for the quadrature
        for i in 1..3 {
            let mut vi = w.vf[i - 1][j];
            for m in 0..4 {
                vi += g[m] * tab.gam[((i - 1) * 4 + m) * n + j].1;
            }
            let tau = th[i] * h;
            pw[i][0] += gm.load(j, piece, &w.cpoly[j], tau, &trs[i]) * vi;
            pw[i][1] += damp[j] * vi * vi;
        }
        pw[0][0] += gm.load(j, piece, &w.cpoly[j], 0.0, &trs[0]) * w.v[j];
        pw[0][1] += damp[j] * w.v[j] * w.v[j];
        pw[3][0] += gm.load(j, piece, &w.cpoly[j], h, &trs[3]) * y;
        pw[3][1] += damp[j] * y * y;
        w.qn[j] = x;
        w.vn[j] = y;
    }
    let mut tr = Trial {
        err: 0.0,
        free: false,
        input: 0.0,
        damping: 0.0,
        contact: 0.0,
    };
    for i in 0..4 {
        tr.input += h * WEIGHTS[i] * pw[i][0];
        tr.damping += h * WEIGHTS[i] * pw[i][1];
        for k in 0..nl {
            tr.contact += h * WEIGHTS[i] * w.fnode[k * 4 + i] * w.dnode[k * 4 + i].1;
        }
    }
    for k in 0..nl {
        imp[k] = (0..4).map(|i| h * WEIGHTS[i] * w.fnode[k * 4 + i]).sum();
    }
    tr
}
