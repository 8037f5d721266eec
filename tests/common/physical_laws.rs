//! An integration of N shear buildings in physical coordinates, `M ü + C u̇ + K u = −M 1 a_g +
//! F`, with every contact law of the README (Contact laws) written here from its formula, by
//! RK4 at a small fixed step whose contact onsets are located by bisection of the step (so that
//! no step straddles the onset of Kelvin's force, which jumps to `c δ̇₀` there, and the damped
//! Hertz law's `v₀` is the approach speed at the onset). The independent reference of the
//! audit (`tests/audit_round.rs`): it shares nothing with the program but the equations.

use super::{FloorPeaks, Physical};

/// A contact law as the README states it (Contact laws), with its constants already derived.
#[derive(Clone, Copy, Debug)]
pub enum Law {
    /// `F = k_h δ^{3/2}`.
    Hertz { kh: f64 },
    /// `F = k δ`.
    Linear { k: f64 },
    /// `F = max(0, k δ + c δ̇)`.
    Kelvin { k: f64, c: f64 },
    /// `F = max(0, k_h δ^{3/2} (1 + χ δ̇/v₀))`, v₀ = δ̇ at the onset.
    HertzDamp { kh: f64, chi: f64 },
    /// `F = k_h δ^{3/2} + c δ̇` approaching, `k_h δ^{3/2}` separating, `c = c₀ δ^{1/4}` with
    /// `c₀ = 2ξ√(m* k_h)`.
    Jankowski { kh: f64, c0: f64 },
}

impl Law {
    /// The force at penetration `d` > 0, rate `v`, onset speed `v0` (N).
    fn force(&self, d: f64, v: f64, v0: f64) -> f64 {
        match *self {
            Law::Hertz { kh } => kh * d * d.sqrt(),
            Law::Linear { k } => k * d,
            Law::Kelvin { k, c } => (k * d + c * v).max(0.0),
            Law::HertzDamp { kh, chi } => (kh * d * d.sqrt() * (1.0 + chi * v / v0)).max(0.0),
            Law::Jankowski { kh, c0 } => {
                kh * d * d.sqrt()
                    + if v > 0.0 {
                        c0 * d.sqrt().sqrt() * v
                    } else {
                        0.0
                    }
            }
        }
    }
}

/// Lankarani–Nikravesh's χ = 3(1 − e²)/4 (the `hertzdamp` default).
pub fn lankarani_chi(e: f64) -> f64 {
    0.75 * (1.0 - e * e)
}

/// Jankowski's ξ = 9√5(1 − e²)/(2e(e(9π − 16) + 16)).
pub fn jankowski_xi(e: f64) -> f64 {
    9.0 * 5f64.sqrt() * (1.0 - e * e) / (2.0 * e * (e * (9.0 * std::f64::consts::PI - 16.0) + 16.0))
}

/// ξ of Kelvin's dashpot for which the clamped impact (force max(0, kδ + cδ̇)) rebounds at e
/// (README, Contact laws): the unit oscillator ẍ = −(x + 2ξẋ) from x = 0, ẋ = 1 until
/// x + 2ξẋ = 0, by RK4 at 1e-5, bisected on ξ.
pub fn kelvin_xi(e: f64) -> f64 {
    let rebound = |xi: f64| {
        let (mut x, mut v) = (0.0f64, 1.0f64);
        let h = 1e-5;
        let f = |x: f64, v: f64| (v, -(x + 2.0 * xi * v));
        loop {
            let k1 = f(x, v);
            let k2 = f(x + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
            let k3 = f(x + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
            let k4 = f(x + h * k3.0, v + h * k3.1);
            let (xn, vn) = (
                x + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
                v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
            );
            let (g0, g1) = (x + 2.0 * xi * v, xn + 2.0 * xi * vn);
            if g1 <= 0.0 {
                let s = g0 / (g0 - g1);
                return -(v + s * (vn - v));
            }
            (x, v) = (xn, vn);
        }
    };
    let (mut a, mut b) = (1e-6, 0.9999);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if rebound(m) > e { a = m } else { b = m }
    }
    0.5 * (a + b)
}

/// A linear structure's second-order system `diag(mass) ẍ + C ẋ + K x = −load a_g + forces`:
/// floor displacements of a building (mass = floor masses, load = floor masses) or a
/// cantilever's modal coordinates (mass 1, K = diag ω², C = diag 2ζω, load = Γ). K and C are
/// sparse rows `(column, value)`.
#[derive(Clone, Debug)]
pub struct Dofs {
    pub mass: Vec<f64>,
    pub load: Vec<f64>,
    pub k: Vec<Vec<(usize, f64)>>,
    pub c: Vec<Vec<(usize, f64)>>,
    /// Yielding storeys of a shear building (then `k` is empty: the storeys' forces restore).
    pub bouc_wen: Option<BoucWen>,
}

/// Bouc–Wen storeys (README, Yielding storeys): `V_j = α k_j d_j + (1 − α) k_j d_y z_j`,
/// `ż_j = (ḋ_j/d_y)[1 − |z_j|ⁿ(β sign(ḋ_j z_j) + γ)]`, one d_y, α, n, β, γ for every storey.
#[derive(Clone, Debug)]
pub struct BoucWen {
    /// Initial storey stiffnesses k_j, N/m.
    pub k: Vec<f64>,
    /// m.
    pub dy: f64,
    pub alpha: f64,
    pub n: f64,
    pub beta: f64,
    pub gamma: f64,
}

impl BoucWen {
    /// The storey force (N) and ż at drift `d`, drift rate `dd`, state `z`.
    fn force(&self, j: usize, d: f64, dd: f64, z: f64) -> (f64, f64) {
        let s = if dd * z == 0.0 {
            0.0
        } else {
            (dd * z).signum()
        };
        let zd = dd / self.dy * (1.0 - z.abs().powf(self.n) * (self.beta * s + self.gamma));
        let k = self.k[j];
        (
            self.alpha * k * d + (1.0 - self.alpha) * k * self.dy * z,
            zd,
        )
    }
}

impl Dofs {
    /// A shear building's floors with yielding storeys `bw` (the damping of `p` kept).
    pub fn yielding(p: &Physical, bw: BoucWen) -> Dofs {
        let mut d = Dofs::of(p);
        d.k = vec![Vec::new(); p.m.len()];
        d.bouc_wen = Some(bw);
        d
    }

    /// A building's floors from its physical matrices.
    pub fn of(p: &Physical) -> Dofs {
        let sparse = |a: &Vec<Vec<f64>>| -> Vec<Vec<(usize, f64)>> {
            a.iter()
                .map(|r| {
                    r.iter()
                        .copied()
                        .enumerate()
                        .filter(|(_, v)| *v != 0.0)
                        .collect()
                })
                .collect()
        };
        Dofs {
            mass: p.m.clone(),
            load: p.m.clone(),
            k: sparse(&p.k),
            c: sparse(&p.c),
            bouc_wen: None,
        }
    }
}

/// One contact level: the point `left` (weights on the dofs of the whole system: a floor is one
/// dof with weight 1, a cantilever's height is φ_n(h) on its modes) meets the point `right`
/// when `δ = x_left − x_right − gap > 0`.
#[derive(Clone, Debug)]
pub struct Level {
    pub left: Vec<(usize, f64)>,
    pub right: Vec<(usize, f64)>,
    /// m.
    pub gap: f64,
    pub law: Law,
}

/// A floor `f` of building `b` of a row of buildings of `sizes` floors, as a contact point.
pub fn floor(sizes: &[usize], b: usize, f: usize) -> Vec<(usize, f64)> {
    vec![(sizes[..b].iter().sum::<usize>() + f, 1.0)]
}

/// What the reference gives: every building's floor peaks (empty for modal structures), each
/// level's peak force (N) and count of impacts (onsets), and the peak |x·w| of each `watch`
/// functional (e.g. a cantilever's top).
#[derive(Debug, Clone)]
pub struct Peaks {
    pub floors: Vec<FloorPeaks>,
    pub force: Vec<f64>,
    pub impacts: Vec<usize>,
    pub watched: Vec<f64>,
    /// The peak |ẍ·w + a_g| of each `watch_acc` functional (an absolute acceleration, m/s²).
    pub watched_acc: Vec<f64>,
    /// When each `watched_acc` peak occurred (s).
    pub watched_acc_time: Vec<f64>,
}

/// RK4 at step `dt` over `duration` of the `structures` (in row order) with the contact
/// `levels` under a_g = −`pga`·sin(`omega` t) (the program's harmonic motion, docs/model.md
/// §2.8); peaks sampled at every step and at every located onset. `buildings` (the physical
/// matrices of shear buildings, in the same order) gives the floor peaks; `watch` functionals
/// give further peaks.
#[allow(clippy::too_many_arguments)]
pub fn integrate_dofs(
    structures: &[Dofs],
    buildings: &[Physical],
    levels: &[Level],
    watch: &[Vec<(usize, f64)>],
    watch_acc: &[Vec<(usize, f64)>],
    pga: f64,
    omega: f64,
    duration: f64,
    dt: f64,
) -> Peaks {
    let mass: Vec<f64> = structures
        .iter()
        .flat_map(|s| s.mass.iter().copied())
        .collect();
    let load: Vec<f64> = structures
        .iter()
        .flat_map(|s| s.load.iter().copied())
        .collect();
    let mut kr: Vec<Vec<(usize, f64)>> = Vec::new();
    let mut cr: Vec<Vec<(usize, f64)>> = Vec::new();
    let mut o = 0;
    for s in structures {
        kr.extend(
            s.k.iter()
                .map(|r| r.iter().map(|&(c, v)| (c + o, v)).collect::<Vec<_>>()),
        );
        cr.extend(
            s.c.iter()
                .map(|r| r.iter().map(|&(c, v)| (c + o, v)).collect::<Vec<_>>()),
        );
        o += s.mass.len();
    }
    let n = mass.len();
    // the yielding storeys: (building's Bouc–Wen, offset, storey) per dof
    let mut yielding: Vec<Option<(&BoucWen, usize, usize)>> = Vec::new();
    let mut o = 0;
    for s in structures {
        for j in 0..s.mass.len() {
            yielding.push(s.bouc_wen.as_ref().map(|b| (b, o, j)));
        }
        o += s.mass.len();
    }
    let any_yielding = yielding.iter().any(|y| y.is_some());
    // y = [x (n), ẋ (n), z (n)]
    let m3 = 3 * n;
    let dot = |w: &[(usize, f64)], x: &[f64]| w.iter().map(|&(i, a)| a * x[i]).sum::<f64>();
    let deriv = |t: f64,
                 y: &[f64],
                 v0: &[f64],
                 out: &mut [f64],
                 fext: &mut [f64],
                 fl: &mut [f64],
                 vst: &mut [f64]| {
        let a_g = -pga * (omega * t).sin();
        let (u, v) = (&y[..n], &y[n..2 * n]);
        fext.iter_mut().for_each(|x| *x = 0.0);
        for (k, l) in levels.iter().enumerate() {
            let d = dot(&l.left, u) - dot(&l.right, u) - l.gap;
            fl[k] = if d > 0.0 {
                l.law.force(d, dot(&l.left, v) - dot(&l.right, v), v0[k])
            } else {
                0.0
            };
            for &(i, a) in &l.left {
                fext[i] -= a * fl[k];
            }
            for &(i, a) in &l.right {
                fext[i] += a * fl[k];
            }
        }
        if any_yielding {
            for r in 0..n {
                out[2 * n + r] = 0.0;
                if let Some((bw, o, j)) = yielding[r] {
                    let below = |x: &[f64]| if j == 0 { 0.0 } else { x[o + j - 1] };
                    let (vj, zd) = bw.force(j, u[r] - below(u), v[r] - below(v), y[2 * n + r]);
                    out[2 * n + r] = zd;
                    vst[r] = vj;
                }
            }
        }
        for r in 0..n {
            let mut s = fext[r] - load[r] * a_g;
            // a yielding storey pushes its floor back and the floor below forward (`fext`
            // keeps the contact forces alone: the equilibrium shear's external forces)
            if let Some((_, o, _)) = yielding[r] {
                s -= vst[r];
                if r + 1 < n && yielding[r + 1].is_some_and(|(_, o2, _)| o2 == o) {
                    s += vst[r + 1];
                }
            }
            for &(c, a) in &kr[r] {
                s -= a * u[c];
            }
            for &(c, a) in &cr[r] {
                s -= a * v[c];
            }
            out[r] = v[r];
            out[n + r] = s / mass[r];
        }
    };
    let mut k = vec![vec![0.0; m3]; 4];
    let mut tmp = vec![0.0; m3];
    let (mut fe, mut f, mut vs) = (vec![0.0; n], vec![0.0; levels.len()], vec![0.0; n]);
    // one RK4 step of size h from (t, y) into `out`
    let mut step = |t: f64, y: &[f64], v0: &[f64], h: f64, out: &mut [f64]| {
        deriv(t, y, v0, &mut k[0], &mut fe, &mut f, &mut vs);
        for i in 0..m3 {
            tmp[i] = y[i] + 0.5 * h * k[0][i];
        }
        let (k0, rest) = k.split_at_mut(1);
        deriv(
            t + 0.5 * h,
            &tmp,
            v0,
            &mut rest[0],
            &mut fe,
            &mut f,
            &mut vs,
        );
        for i in 0..m3 {
            tmp[i] = y[i] + 0.5 * h * rest[0][i];
        }
        deriv(
            t + 0.5 * h,
            &tmp,
            v0,
            &mut rest[1],
            &mut fe,
            &mut f,
            &mut vs,
        );
        for i in 0..m3 {
            tmp[i] = y[i] + h * rest[1][i];
        }
        deriv(t + h, &tmp, v0, &mut rest[2], &mut fe, &mut f, &mut vs);
        for i in 0..m3 {
            out[i] = y[i] + h / 6.0 * (k0[0][i] + 2.0 * rest[0][i] + 2.0 * rest[1][i] + rest[2][i]);
        }
    };
    let mut peaks = Peaks {
        floors: buildings
            .iter()
            .map(|p| {
                let nn = p.m.len();
                FloorPeaks {
                    disp: vec![0.0; nn],
                    acc: vec![0.0; nn],
                    drift: vec![0.0; nn],
                    force: vec![0.0; nn],
                    shear: vec![0.0; nn],
                }
            })
            .collect(),
        force: vec![0.0; levels.len()],
        impacts: vec![0; levels.len()],
        watched: vec![0.0; watch.len()],
        watched_acc: vec![0.0; watch_acc.len()],
        watched_acc_time: vec![0.0; watch_acc.len()],
    };
    let (mut acc, mut fext, mut fl) = (vec![0.0; m3], vec![0.0; n], vec![0.0; levels.len()]);
    let mut vst = vec![0.0; n];
    let mut observe = |t: f64, y: &[f64], v0: &[f64], peaks: &mut Peaks| {
        deriv(t, y, v0, &mut acc, &mut fext, &mut fl, &mut vst);
        let a_g = -pga * (omega * t).sin();
        for (k, f) in fl.iter().enumerate() {
            peaks.force[k] = peaks.force[k].max(*f);
        }
        for (w, p) in watch.iter().zip(peaks.watched.iter_mut()) {
            *p = p.max(dot(w, y).abs());
        }
        for (i, w) in watch_acc.iter().enumerate() {
            let a = (dot(w, &acc[n..2 * n]) + a_g).abs();
            if a > peaks.watched_acc[i] {
                peaks.watched_acc[i] = a;
                peaks.watched_acc_time[i] = t;
            }
        }
        let mut o = 0;
        for (b, p) in buildings.iter().enumerate() {
            let nn = p.m.len();
            let pk = &mut peaks.floors[b];
            let mut above = 0.0;
            for f in (0..nn).rev() {
                let a = acc[n + o + f] + a_g;
                above += fext[o + f] - p.m[f] * a;
                let below = if f == 0 { 0.0 } else { y[o + f - 1] };
                let springs = p.springs.as_ref().expect("shear buildings");
                let storey = match structures[b].bouc_wen {
                    Some(_) => vst[o + f],
                    None => springs[f] * (y[o + f] - below),
                };
                pk.disp[f] = pk.disp[f].max(y[o + f].abs());
                pk.acc[f] = pk.acc[f].max(a.abs());
                pk.drift[f] = pk.drift[f].max((y[o + f] - below).abs());
                pk.force[f] = pk.force[f].max(storey.abs());
                pk.shear[f] = pk.shear[f].max(above.abs());
            }
            o += nn;
        }
    };
    let delta = |y: &[f64], l: &Level| dot(&l.left, y) - dot(&l.right, y) - l.gap;
    let rate = |y: &[f64], l: &Level| dot(&l.left, &y[n..2 * n]) - dot(&l.right, &y[n..2 * n]);
    let mut y = vec![0.0; m3];
    let mut v0 = vec![1.0; levels.len()];
    let mut trial = vec![0.0; m3];
    let steps = (duration / dt).round() as usize;
    observe(0.0, &y, &v0, &mut peaks);
    for s in 0..steps {
        let (mut t, t_end) = (s as f64 * dt, (s + 1) as f64 * dt);
        while t < t_end {
            let h = t_end - t;
            step(t, &y, &v0, h, &mut trial);
            let opens = |z: &[f64]| {
                levels
                    .iter()
                    .any(|l| delta(&y, l) <= 0.0 && delta(z, l) > 0.0)
            };
            if !opens(&trial) {
                t = t_end;
                y.copy_from_slice(&trial);
            } else {
                // the first onset inside the step: bisect the step's length to it (the law's
                // force at the onset is that of δ → 0⁺), then restart the episode there
                let (mut a, mut b) = (0.0, h);
                for _ in 0..50 {
                    let m = 0.5 * (a + b);
                    step(t, &y, &v0, m, &mut trial);
                    if opens(&trial) { b = m } else { a = m }
                }
                step(t, &y, &v0, b, &mut trial);
                for (k, l) in levels.iter().enumerate() {
                    if delta(&y, l) <= 0.0 && delta(&trial, l) > 0.0 {
                        v0[k] = rate(&trial, l);
                        peaks.impacts[k] += 1;
                    }
                }
                t += b;
                y.copy_from_slice(&trial);
            }
            observe(t, &y, &v0, &mut peaks);
        }
    }
    peaks
}

/// [`integrate_dofs`] of shear buildings in a row (every floor's peaks).
pub fn integrate(
    buildings: &[Physical],
    levels: &[Level],
    pga: f64,
    omega: f64,
    duration: f64,
    dt: f64,
) -> Peaks {
    let dofs: Vec<Dofs> = buildings.iter().map(Dofs::of).collect();
    integrate_dofs(&dofs, buildings, levels, &[], &[], pga, omega, duration, dt)
}

/// Cantilever mode shape φ·√(mL) at ξ = x/L (docs/model.md §2.3, in decaying exponentials).
pub fn shape(lam: f64, xi: f64) -> f64 {
    let e = f64::exp;
    let d = 1.0 + e(-2.0 * lam) + 2.0 * lam.cos() * e(-lam);
    let s = (1.0 - e(-2.0 * lam) - 2.0 * lam.sin() * e(-lam)) / d;
    let ch_sh = (e(-lam * xi)
        + e(-lam * (2.0 - xi))
        + lam.cos() * (e(-lam * (1.0 - xi)) + e(-lam * (1.0 + xi)))
        + lam.sin() * (e(-lam * (1.0 - xi)) - e(-lam * (1.0 + xi))))
        / d;
    ch_sh - (lam * xi).cos() + s * (lam * xi).sin()
}

/// Roots of cos λ + 1/cosh λ = 0 near (2n−1)π/2, by bisection.
pub fn roots(n: usize) -> Vec<f64> {
    (1..=n)
        .map(|k| {
            let f = |x: f64| x.cos() + 1.0 / x.cosh();
            let c = (2 * k - 1) as f64 * std::f64::consts::FRAC_PI_2;
            let (mut a, mut b) = (c - 0.5, c + 0.5);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if (f(a) > 0.0) == (f(m) > 0.0) {
                    a = m
                } else {
                    b = m
                }
            }
            0.5 * (a + b)
        })
        .collect()
}

/// A uniform cantilever (total `mass` kg, `length` m, first period `period` s, `modes` modes,
/// ζ = `zeta` in every mode) in its modal coordinates (docs/model.md §2.3–2.4: ω_n = ω₁ (λ_n/λ₁)²,
/// mass-normalised shapes, Γ_n = m ∫φ_n by Simpson's rule), and its mode shapes at the top.
pub fn cantilever(
    mass: f64,
    length: f64,
    period: f64,
    modes: usize,
    zeta: f64,
) -> (Dofs, Vec<f64>) {
    let lam = roots(modes);
    let m = mass / length;
    let nrm = 1.0 / (m * length).sqrt();
    let w1 = 2.0 * std::f64::consts::PI / period;
    let simpson = |l: f64| {
        let n = 4000;
        let h = 1.0 / n as f64;
        let mut s = shape(l, 0.0) + shape(l, 1.0);
        for i in 1..n {
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * shape(l, i as f64 * h);
        }
        s * h / 3.0
    };
    let om: Vec<f64> = lam.iter().map(|l| w1 * (l / lam[0]).powi(2)).collect();
    let dofs = Dofs {
        mass: vec![1.0; modes],
        load: lam.iter().map(|&l| m * length * nrm * simpson(l)).collect(),
        k: (0..modes).map(|i| vec![(i, om[i] * om[i])]).collect(),
        c: (0..modes).map(|i| vec![(i, 2.0 * zeta * om[i])]).collect(),
        bouc_wen: None,
    };
    (dofs, lam.iter().map(|&l| shape(l, 1.0) * nrm).collect())
}

/// The section shear of the cantilever of [`cantilever`] at height `x` (m) as weights on its
/// modal coordinates: `V(x) = Σ_n m ω_n² η_n ∫_x^L φ_n` (docs/model.md §2.6c, the storey force
/// of a cantilever: `−EI w‴`), the integral by Simpson's rule.
pub fn cantilever_shear(mass: f64, length: f64, period: f64, modes: usize, x: f64) -> Vec<f64> {
    let lam = roots(modes);
    let m = mass / length;
    let nrm = 1.0 / (m * length).sqrt();
    let w1 = 2.0 * std::f64::consts::PI / period;
    let a = x / length;
    lam.iter()
        .map(|&l| {
            let n = 4000;
            let h = (1.0 - a) / n as f64;
            let mut s = shape(l, a) + shape(l, 1.0);
            for i in 1..n {
                s += if i % 2 == 1 { 4.0 } else { 2.0 } * shape(l, a + i as f64 * h);
            }
            let om = w1 * (l / lam[0]).powi(2);
            m * om * om * length * nrm * s * h / 3.0
        })
        .collect()
}
