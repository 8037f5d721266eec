//! One structure's stations through a run ([`Stations`]): the per-observation update of their
//! displacements, drifts, storey forces, accelerations and equilibrium shear, refined between
//! observations on the Hermite interpolant or the sub-grid of the fast modes' closed forms (the
//! parent module's documentation says what each quantity is).

// Index loops over parallel per-mode slices read like the sums they form.
#![allow(clippy::needless_range_loop)]

use super::FloorPeaks;
#[cfg(target_arch = "x86_64")]
use super::between::between_on_hermite_avx;
use super::between::{Between, between_on_hermite, between_on_subgrid};
use super::bounds::{raise, reach, refine_on_subgrid, ring_bound, update_station};
use crate::model::modal::{ModalModel, Shapes};
use crate::model::system::{LevelState, System};
#[cfg(target_arch = "x86_64")]
use crate::recording::subgrid::modal_sums_avx;
use crate::recording::subgrid::{NEGLIGIBLE, SubGrid, modal_sums};

/// `dst` = `src` (resized: no allocation once grown).
pub(super) fn copy_into(dst: &mut Vec<f64>, src: &[f64]) {
    dst.clear();
    dst.extend_from_slice(src);
}

/// [`modal_sums`], four stations to an AVX operation ([`modal_sums_avx`]) where `WIDE` (called
/// from [`Stations::observe_avx`] only: the processor has AVX).
#[inline(always)]
fn sums<const WIDE: bool, const K: usize>(
    c: &[f64],
    ns: usize,
    x: [&[f64]; K],
    out: [&mut [f64]; K],
    start: Option<(f64, &[f64])>,
) {
    #[cfg(target_arch = "x86_64")]
    if WIDE {
        // SAFETY: `WIDE` only inside `Stations::observe_avx`, where the processor has AVX
        unsafe { modal_sums_avx(c, ns, x, out, start) };
        return;
    }
    modal_sums(c, ns, x, out, start);
}

/// [`SubGrid::jerks`], compiled for AVX where `WIDE` (as [`sums`]).
#[inline(always)]
fn jerks<'g, const WIDE: bool>(
    grid: &'g mut SubGrid,
    h: f64,
    va: (&[f64], &[f64]),
    (omega, damp): (&[f64], &[f64]),
) -> Option<(&'g [f64], &'g [f64])> {
    #[cfg(target_arch = "x86_64")]
    if WIDE {
        // SAFETY: as in `sums`
        return unsafe { grid.jerks_avx(h, va, omega, damp) };
    }
    grid.jerks(h, va, omega, damp)
}

/// [`between_on_hermite`], compiled for AVX where `WIDE` (as [`sums`]).
#[inline(always)]
fn hermite_between<const WIDE: bool>(
    peaks: (&mut [FloorPeaks], &mut [f64]),
    bt: &Between,
    now: (&[f64], &[f64]),
    jerks: (&[f64], &[f64], &[f64]),
    times: (f64, f64, f64),
) {
    #[cfg(target_arch = "x86_64")]
    if WIDE {
        // SAFETY: as in `sums`
        unsafe { between_on_hermite_avx(peaks, bt, now, jerks, times) };
        return;
    }
    between_on_hermite(peaks, bt, now, jerks, times);
}

/// How closely (relative to the row's largest term) a floor's storey-force row must be `k_j`
/// times its drift row for the floors to be taken as storey springs: far above the round-off
/// of an eigen-solution (~1e-13) and far below any real departure from a chain of springs.
const SPRING_MATCH: f64 = 1e-9;

/// How the equilibrium shear of one structure is formed.
#[derive(Debug, Clone)]
pub(super) enum Equilibrium {
    /// Lumped floor masses, kg.
    Lumped(Vec<f64>),
    /// A continuous cantilever: mass per length (kg/m) and, per station, `∫_x^L φ_n dx` of
    /// every mode (m·kg^−½) and `L − x` (m).
    Continuous {
        m: f64,
        /// `[n·stations + station]` (built `[station·modes + n]`, transposed).
        integral: Vec<f64>,
        above: Vec<f64>,
    },
}

/// How the storey force (restoring, without damping) of one structure is formed.
#[derive(Debug, Clone)]
pub(super) enum StoreyForce {
    /// Storey springs k_j, N/m: `V_j = k_j d_j`, so its peak is `k_j` times the (refined) peak
    /// drift, formed at the end.
    Springs(Vec<f64>),
    /// `V = r·η` per station, `r_n = ω_n² Σ_{g ≥ j} m_g φ_n(g)` (floors) or `ω_n² m ∫_x^L φ_n
    /// dx` (a cantilever), N·kg^−½, `[n·stations + station]` (built `[station·modes + n]`,
    /// transposed); refined between observations.
    Rows(Vec<f64>),
}

/// The storey stiffnesses k_j (N/m) when the storey-force rows `rows` are `k_j` times the
/// drift rows of the floor values `phi` (both `[floor·modes + n]`) to [`SPRING_MATCH`]: the
/// modes are those of a chain of storey springs. `None` otherwise.
fn springs(rows: &[f64], phi: &[f64], floors: usize, modes: usize) -> Option<Vec<f64>> {
    let mut ks = Vec::with_capacity(floors);
    let mut e = vec![0.0; modes];
    for f in 0..floors {
        let r = &rows[f * modes..(f + 1) * modes];
        for n in 0..modes {
            let below = if f == 0 {
                0.0
            } else {
                phi[(f - 1) * modes + n]
            };
            e[n] = phi[f * modes + n] - below;
        }
        let (mut re, mut ee, mut big) = (0.0, 0.0, 0.0f64);
        for n in 0..modes {
            re += r[n] * e[n];
            ee += e[n] * e[n];
            big = big.max(r[n].abs());
        }
        let k = re / ee;
        if !(k.is_finite() && k > 0.0)
            || (0..modes).any(|n| (r[n] - k * e[n]).abs() > SPRING_MATCH * big)
        {
            return None;
        }
        ks.push(k);
    }
    Some(ks)
}

/// The stations of one structure.
#[derive(Debug, Clone)]
pub(super) struct Stations {
    pub(super) heights: Vec<f64>,
    /// Modes of the structure.
    pub(super) modes: usize,
    /// φ_n at every station: `[n·stations + station]`.
    pub(super) phi: Vec<f64>,
    pub(super) equilibrium: Equilibrium,
    pub(super) force: StoreyForce,
    /// Stations whose storey yields (Bouc–Wen), with the storey's index in the system's
    /// hysteresis: its force comes from the law.
    pub(super) yields: Vec<Option<usize>>,
    /// Which contact levels load the part above each station: `[station·levels + k]` (for
    /// floors: the level acts at that very floor).
    pub(super) above: Vec<bool>,
    pub(super) levels: usize,
    /// Offset of this structure's modes in the system.
    pub(super) offset: usize,
    /// The sign of each contact level's force on this structure: −1 where it is the left one
    /// of the level's pair, +1 the right one, 0 a level of another pair (a row).
    pub(super) signs: Vec<f64>,
    /// (u, u̇) at every station at the previous observation, and at the one before (for
    /// the samples between them).
    pub(super) prev: Vec<(f64, f64)>,
    pub(super) before: Vec<(f64, f64)>,
    /// (V, V̇) of the storey force (`StoreyForce::Rows`, or a yielding storey's) at the
    /// previous observation.
    pub(super) prev_force: Vec<(f64, f64)>,
    /// Per station u, u̇, ü + … (modal part), V, V̇ and the inertia integral (scratch).
    pub(super) work: Vec<f64>,
    /// Absolute acceleration at the current observation, and the one of largest size since
    /// the last sample (signed).
    pub(super) abs_now: Vec<f64>,
    pub(super) hold: Vec<f64>,
    pub(super) peaks: Vec<FloorPeaks>,
    /// The time of this structure's last observation and the interval before it, s (a row's
    /// passive structure is observed on the grid only: see [`FloorRecorder::observe_part`]).
    pub(super) last_t: Option<f64>,
    pub(super) h: Option<f64>,
    /// Whether the current observation saw this structure.
    pub(super) fresh: bool,
    /// The modes' closed forms between observations ([`crate::recording::subgrid`]), the
    /// largest ω (1/s), |φ|, |φ(j) − φ(j−1)| and |storey-force rows| (`[n·stations +
    /// station]`), and the stations that take the sub-grid at this observation (scratch).
    pub(super) grid: SubGrid,
    pub(super) omega_max: f64,
    pub(super) abs_phi: Vec<f64>,
    pub(super) abs_drift: Vec<f64>,
    pub(super) abs_rows: Vec<f64>,
    /// Per mode, the largest of |φ|, |φ(j) − φ(j−1)| and |storey-force row| over the stations.
    pub(super) cmax: [Vec<f64>; 3],
    pub(super) flagged: Vec<usize>,
    /// The absolute acceleration and the equilibrium shear between observations
    /// ([`Between`]).
    pub(super) between: Between,
    /// Scratch: the contact levels that carry force on this structure at an observation (or
    /// a pulse point of [`Stations::raise_at`]), with their `sign·F` (N), in the levels'
    /// order.
    pub(super) loaded: Vec<(usize, f64)>,
    /// Scratch of [`Stations::raise_at`]: per station the modal part of the acceleration
    /// (m/s²), then the equilibrium shear (N).
    pub(super) point: Vec<f64>,
    /// The stations each contact level loads (those whose `above` marks it), level k's at
    /// `level_stations[level_at[k]..level_at[k + 1]]`, lowest first.
    pub(super) level_stations: Vec<usize>,
    pub(super) level_at: Vec<usize>,
    /// Whether the processor has AVX ([`Stations::observe`] compiled for it).
    pub(super) wide: bool,
}

/// One observation's data as a structure's stations read it: the time (s), the modal state and
/// accelerations, the ground's acceleration (m/s²), the levels' states and the yielding
/// storeys' z.
pub(super) struct At<'v> {
    pub(super) t: f64,
    pub(super) q: &'v [f64],
    pub(super) v: &'v [f64],
    pub(super) accel: &'v [f64],
    pub(super) ag: f64,
    pub(super) levels: &'v [LevelState],
    pub(super) z: &'v [f64],
}

/// A copy of the last observation at which a row's structures were left unobserved (valid:
/// there was one, and it is the last observation): a structure skipped there that the next
/// step carries under contact forces is observed at it first, so that its interpolants never
/// span a step with forces and the free flight before it.
#[derive(Debug, Clone, Default)]
pub(super) struct Saved {
    pub(super) valid: bool,
    pub(super) t: f64,
    pub(super) ag: f64,
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) accel: Vec<f64>,
    pub(super) levels: Vec<LevelState>,
    pub(super) z: Vec<f64>,
}

impl Stations {
    pub(super) fn new(
        m: &ModalModel,
        contact_heights: &[f64],
        signs: &[f64],
        offset: usize,
    ) -> Stations {
        let nm = m.len();
        let (heights, equilibrium) = match &m.shapes {
            Shapes::Floors {
                heights, masses, ..
            } => (heights.clone(), Equilibrium::Lumped(masses.clone())),
            Shapes::Cantilever(modes) => {
                let l = m.length;
                let mut h: Vec<f64> = (1..=10).map(|k| l * k as f64 / 10.0).collect();
                h.extend(
                    contact_heights
                        .iter()
                        .zip(signs)
                        .filter(|&(&x, &s)| s != 0.0 && x > 0.0 && x <= l)
                        .map(|(&x, _)| x),
                );
                h.sort_by(f64::total_cmp);
                h.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * l);
                let scale = l / m.mass.sqrt(); // ∫ φ dx = L ∫ y dξ / √(mL)
                let integral = h
                    .iter()
                    .flat_map(|&x| modes.iter().map(move |md| scale * md.integral_above(x / l)))
                    .collect();
                let above = h.iter().map(|&x| l - x).collect();
                (
                    h,
                    Equilibrium::Continuous {
                        m: m.mass / l,
                        integral,
                        above,
                    },
                )
            }
        };
        let phi: Vec<f64> = heights.iter().flat_map(|&x| m.shapes_at(x)).collect();
        let ns = heights.len();
        // the storey force per unit modal coordinate: the equivalent static forces
        // K φ_n = ω_n² M φ_n of what is above (docs/model.md §2.6c)
        let mut rows = vec![0.0; ns * nm];
        match &equilibrium {
            Equilibrium::Lumped(masses) => {
                for f in (0..ns).rev() {
                    for n in 0..nm {
                        let above = if f + 1 < ns {
                            rows[(f + 1) * nm + n]
                        } else {
                            0.0
                        };
                        rows[f * nm + n] =
                            above + masses[f] * m.omega[n] * m.omega[n] * phi[f * nm + n];
                    }
                }
            }
            Equilibrium::Continuous {
                m: mpl, integral, ..
            } => {
                for f in 0..ns {
                    for n in 0..nm {
                        rows[f * nm + n] = mpl * m.omega[n] * m.omega[n] * integral[f * nm + n];
                    }
                }
            }
        }
        let force = match &equilibrium {
            Equilibrium::Lumped(_) => match springs(&rows, &phi, ns, nm) {
                Some(k) => StoreyForce::Springs(k),
                None => StoreyForce::Rows(rows),
            },
            Equilibrium::Continuous { .. } => StoreyForce::Rows(rows),
        };
        // the time loop runs over the stations mode by mode: `[mode·stations + station]`
        let transpose = |x: &[f64]| -> Vec<f64> {
            (0..nm)
                .flat_map(|n| (0..ns).map(move |f| x[f * nm + n]))
                .collect()
        };
        let force = match force {
            StoreyForce::Rows(r) => StoreyForce::Rows(transpose(&r)),
            springs => springs,
        };
        let equilibrium = match equilibrium {
            Equilibrium::Continuous { m, integral, above } => Equilibrium::Continuous {
                m,
                integral: transpose(&integral),
                above,
            },
            lumped => lumped,
        };
        let phi = transpose(&phi);
        let lumped = matches!(equilibrium, Equilibrium::Lumped(_));
        let above: Vec<bool> = heights
            .iter()
            .flat_map(|&x| {
                contact_heights.iter().zip(signs).map(move |(&hk, &sign)| {
                    if sign == 0.0 {
                        // a level of a pair this structure is not in
                        false
                    } else if lumped {
                        crate::model::building::same_height(hk, x)
                    } else {
                        hk >= x || crate::model::building::same_height(hk, x)
                    }
                })
            })
            .collect();
        let abs_phi: Vec<f64> = phi.iter().map(|x| x.abs()).collect();
        let abs_drift: Vec<f64> = (0..nm)
            .flat_map(|n| {
                let phi = &phi;
                (0..ns).map(move |f| {
                    let below = if f == 0 { 0.0 } else { phi[n * ns + f - 1] };
                    (phi[n * ns + f] - below).abs()
                })
            })
            .collect();
        let abs_rows: Vec<f64> = match &force {
            StoreyForce::Rows(r) => r.iter().map(|x| x.abs()).collect(),
            StoreyForce::Springs(_) => Vec::new(),
        };
        let largest = |x: &[f64]| -> Vec<f64> {
            (0..nm)
                .map(|n| {
                    x.get(n * ns..(n + 1) * ns)
                        .map_or(0.0, |c| c.iter().fold(0.0, |a: f64, &b| a.max(b)))
                })
                .collect()
        };
        let cmax = [largest(&abs_phi), largest(&abs_drift), largest(&abs_rows)];
        // the equilibrium's modal rows E_n and the mass above each station
        let (eq_rows, mass_above): (Vec<f64>, Vec<f64>) = match &equilibrium {
            Equilibrium::Lumped(masses) => {
                let mut e = vec![0.0; nm * ns];
                let mut mass = vec![0.0; ns];
                for f in (0..ns).rev() {
                    mass[f] = masses[f] + if f + 1 < ns { mass[f + 1] } else { 0.0 };
                    for n in 0..nm {
                        let up = if f + 1 < ns { e[n * ns + f + 1] } else { 0.0 };
                        e[n * ns + f] = up + masses[f] * phi[n * ns + f];
                    }
                }
                (e, mass)
            }
            Equilibrium::Continuous { m, integral, above } => (
                integral.iter().map(|x| m * x).collect(),
                above.iter().map(|x| m * x).collect(),
            ),
        };
        let between = Between::new(&phi, (eq_rows, mass_above), &m.omega, (ns, nm));
        let nl = contact_heights.len();
        let mut level_at = vec![0];
        let mut level_stations = Vec::new();
        for k in 0..nl {
            level_stations.extend((0..ns).filter(|&f| above[f * nl + k]));
            level_at.push(level_stations.len());
        }
        Stations {
            cmax,
            grid: SubGrid::new(nm),
            omega_max: m.omega.iter().fold(0.0, |a, &w| a.max(w)),
            abs_phi,
            abs_drift,
            abs_rows,
            flagged: Vec::with_capacity(ns),
            between,
            peaks: heights
                .iter()
                .map(|&height| FloorPeaks {
                    height,
                    ..FloorPeaks::default()
                })
                .collect(),
            heights,
            modes: nm,
            phi,
            equilibrium,
            force,
            yields: vec![None; ns],
            above,
            levels: contact_heights.len(),
            offset,
            signs: signs.to_vec(),
            prev: vec![(0.0, 0.0); ns],
            before: vec![(0.0, 0.0); ns],
            prev_force: vec![(0.0, 0.0); ns],
            work: vec![0.0; 6 * ns],
            abs_now: vec![0.0; ns],
            hold: vec![0.0; ns],
            last_t: None,
            h: None,
            fresh: false,
            loaded: Vec::with_capacity(contact_heights.len()),
            point: vec![0.0; 2 * ns],
            level_stations,
            level_at,
            wide: crate::numerics::vex::available(),
        }
    }

    /// Observe this structure at `at` (its interval: since its last observation); `full`:
    /// every station takes the full update (tests).
    #[inline]
    pub(super) fn observe(
        &mut self,
        system: &System,
        at: &At,
        full: bool,
        resolution: Option<f64>,
    ) {
        #[cfg(target_arch = "x86_64")]
        if self.wide {
            // SAFETY: `wide` only where the processor has AVX
            unsafe { self.observe_avx(system, at, full, resolution) };
            return;
        }
        self.observe_body::<false>(system, at, full, resolution);
    }

    /// [`Stations::observe`] compiled for AVX: the same IEEE operations in the same order
    /// (three-operand encoding, and the stations' sums over the modes four stations to an
    /// operation, [`modal_sums_avx`]). Safety: the processor has AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn observe_avx(
        &mut self,
        system: &System,
        at: &At,
        full: bool,
        resolution: Option<f64>,
    ) {
        self.observe_body::<true>(system, at, full, resolution);
    }

    /// [`Stations::observe`]; `WIDE`: compiled for AVX (called from [`Stations::observe_avx`]
    /// only).
    #[inline(always)]
    fn observe_body<const WIDE: bool>(
        &mut self,
        system: &System,
        at: &At,
        full: bool,
        resolution: Option<f64>,
    ) {
        let h = self.last_t.map(|t0| at.t - t0).filter(|h| *h > 0.0);
        self.last_t = Some(at.t);
        self.h = h;
        let st = self;
        let ag = at.ag;
        let nm = st.modes;
        let ns = st.heights.len();
        let (q, v, a) = (
            &at.q[st.offset..st.offset + nm],
            &at.v[st.offset..st.offset + nm],
            &at.accel[st.offset..st.offset + nm],
        );
        let (omega, damp) = (
            &system.omega()[st.offset..st.offset + nm],
            &system.damping_coefficients()[st.offset..st.offset + nm],
        );
        // modes too fast for the Hermite that ring: the sub-grid may be needed
        let ringing = match resolution {
            Some(theta) => st
                .grid
                .prepare(h, theta, (q, v, a), omega, damp, st.omega_max),
            None => false,
        };
        st.flagged.clear();
        // every station's sums over the modes, in the modes' order (`c_0 x_0 + c_1 x_1 + …`),
        // two stations per pass ([`modal_sums`])
        let (u, rest) = st.work[..6 * ns].split_at_mut(ns);
        let (ud, rest) = rest.split_at_mut(ns);
        let (ua, rest) = rest.split_at_mut(ns);
        let (vf, rest) = rest.split_at_mut(ns);
        let (vfd, inertia) = rest.split_at_mut(ns);
        let phi = &st.phi[..ns * nm];
        sums::<WIDE, 3>(phi, ns, [q, v, a], [u, ud, ua], None);
        // the storey force from the modes' equivalent static forces (springs: at the end)
        let rows = match &st.force {
            StoreyForce::Rows(rows) => Some(&rows[..ns * nm]),
            StoreyForce::Springs(_) => None,
        };
        if ringing {
            st.grid.station_sums(
                (phi, &st.abs_phi, &st.abs_drift),
                rows.map(|r| (r, &st.abs_rows[..])),
                ns,
            );
        }
        if let Some(rows) = rows {
            sums::<WIDE, 2>(rows, ns, [q, v], [vf, vfd], None);
        }
        // the previous observation's (u, u̇) become the one before: swap, then overwrite
        std::mem::swap(&mut st.prev, &mut st.before);
        let abs = &mut st.abs_now[..ns];
        let (mut below, mut below_rate, mut below_prev, mut below_prev_rate) = (0.0, 0.0, 0.0, 0.0);
        // (every per-station slice cut to the stations once: no bounds check per station)
        let (u, ud, ua) = (&u[..ns], &ud[..ns], &ua[..ns]);
        let (vf, vfd, yields) = (&vf[..ns], &vfd[..ns], &st.yields[..ns]);
        let (before, prev) = (&st.before[..ns], &mut st.prev[..ns]);
        let (peaks, prev_force) = (&mut st.peaks[..ns], &mut st.prev_force[..ns]);
        // Most observations change no station's peak: a first, lean pass tests each
        // station's bounds ([`reach`]: the very test `refine` makes, and ≥ the end values
        // `raise` compares) and the acceleration against its peaks, and only a station
        // that can change a peak (or yields: its force needs its law) takes the full
        // update, out of line. The peaks are exactly those of the full update at every
        // station (the skipped updates are no-ops).
        let has_rows = rows.is_some();
        for f in 0..ns {
            let (u, ud) = (u[f], ud[f]);
            let (up, udp) = before[f];
            let (d, dd, dp, ddp) = (
                u - below,
                ud - below_rate,
                up - below_prev,
                udp - below_prev_rate,
            );
            let a = ua[f] + ag;
            abs[f] = a;
            let p = &peaks[f];
            // (`|` not `||`: every test is cheap, and branch-free is cheaper)
            let need = full
                | yields[f].is_some()
                | (a.abs() > p.acceleration)
                | match h {
                    Some(h) => {
                        (reach(up, udp, u, ud, h) > p.displacement)
                            | (reach(dp, ddp, d, dd, h) > p.drift)
                            | (has_rows && {
                                let (v0, vd0) = prev_force[f];
                                reach(v0, vd0, vf[f], vfd[f], h) > p.shear
                            })
                    }
                    None => {
                        (u.abs() > p.displacement)
                            | (d.abs() > p.drift)
                            | (has_rows && vf[f].abs() > p.shear)
                    }
                };
            // where the fast modes ring more than negligibly the Hermite of the ends
            // neither follows nor bounds the station's quantities: their bound over the
            // interval ([`ring_bound`]) decides between the ends only and the sub-grid
            let (mut sub, mut ringing_here) = (false, false);
            if ringing && yields[f].is_none() {
                let hh = h.unwrap_or(0.0);
                let g = &st.grid;
                let six = |x: &[f64], f: usize| -> [f64; 6] {
                    x[6 * f..6 * f + 6].try_into().expect("six sums")
                };
                let su = six(&g.sums_u, f);
                let sb = if f > 0 {
                    six(&g.sums_u, f - 1)
                } else {
                    [0.0; 6]
                };
                let sd: [f64; 6] = std::array::from_fn(|j| su[j] - sb[j]);
                let ring: [f64; 3] = g.rings[3 * f..3 * f + 3].try_into().expect("three");
                let mut judge = |ends: (f64, f64, f64, f64), s: &[f64; 6], ring, peak| {
                    if ring * g.hermite_factor > NEGLIGIBLE * peak {
                        ringing_here = true;
                        sub |= ring_bound(ends, s, ring, hh) > peak;
                    } else {
                        sub |= reach(ends.0, ends.1, ends.2, ends.3, hh) > peak;
                    }
                };
                judge((up, udp, u, ud), &su, ring[0], p.displacement);
                judge((dp, ddp, d, dd), &sd, ring[1], p.drift);
                if has_rows {
                    let (v0, vd0) = prev_force[f];
                    judge(
                        (v0, vd0, vf[f], vfd[f]),
                        &six(&g.sums_v, f),
                        ring[2],
                        p.shear,
                    );
                }
                sub &= ringing_here;
            }
            if sub || (ringing_here && need) {
                update_station(
                    &mut peaks[f],
                    &mut prev_force[f],
                    (at.t, None),
                    [(up, udp), (u, ud), (dp, ddp), (d, dd)],
                    a,
                    rows.map(|_| (vf[f], vfd[f])),
                );
                if sub {
                    st.flagged.push(f);
                }
            } else if need {
                // the storey force: a yielding storey's Bouc–Wen V (C¹ in time) from
                // this drift and its z, or the modal rows' V
                let force = match yields[f] {
                    Some(k) => {
                        let law = &system.hysteresis.storeys()[k];
                        let z = at.z.get(k).copied().unwrap_or(0.0);
                        Some((law.force(d, z), law.force_rate(dd, z)))
                    }
                    None => rows.map(|_| (vf[f], vfd[f])),
                };
                update_station(
                    &mut peaks[f],
                    &mut prev_force[f],
                    (at.t, h),
                    [(up, udp), (u, ud), (dp, ddp), (d, dd)],
                    a,
                    force,
                );
            } else if has_rows {
                prev_force[f] = (vf[f], vfd[f]);
            }
            prev[f] = (u, ud);
            (below, below_rate, below_prev, below_prev_rate) = (u, ud, up, udp);
        }
        // the equilibrium of what is above (storey force and damping forces)
        let nl = st.levels.min(at.levels.len());
        // the levels that carry force on this structure, `sign_k F_k ≠ 0`, once per observation
        // (the others add an exact zero: leaving them out changes no sum but, at most, the sign
        // of a sum that is exactly zero, which no |V| compared with a peak sees)
        st.loaded.clear();
        for (k, (&sign, level)) in st.signs[..nl].iter().zip(&at.levels[..nl]).enumerate() {
            let sf = sign * level.force;
            if sf != 0.0 {
                st.loaded.push((k, sf));
            }
        }
        // `v += Σ_k sign_k F_k` over the levels that load the part above station f, in order
        let (loaded, stride) = (&st.loaded[..], st.levels);
        let above_of = &st.above;
        let contact = |v: &mut f64, f: usize| {
            let row = &above_of[f * stride..f * stride + nl];
            for &(k, sf) in loaded {
                if row[k] {
                    *v += sf;
                }
            }
        };
        let bt = &mut st.between;
        match &st.equilibrium {
            Equilibrium::Lumped(masses) => {
                let (mut v_above, mut c_above) = (0.0, 0.0);
                for f in (0..ns).rev() {
                    v_above -= masses[f] * abs[f];
                    // contact forces acting at this floor
                    contact(&mut v_above, f);
                    contact(&mut c_above, f);
                    bt.eq_now[f] = v_above;
                    bt.contact_now[f] = c_above;
                    raise(&mut st.peaks[f].shear_with_damping, v_above.abs());
                }
            }
            Equilibrium::Continuous { m, integral, above } => {
                // ag (L − x) + Σ_n (∫_x^L φ_n) η̈_n, in that order
                let above = &above[..ns];
                sums::<WIDE, 1>(&integral[..ns * nm], ns, [a], [inertia], Some((ag, above)));
                for (f, (p, &x)) in st.peaks[..ns].iter_mut().zip(&inertia[..ns]).enumerate() {
                    let mut v_sec = -m * x;
                    contact(&mut v_sec, f);
                    let mut c = 0.0;
                    contact(&mut c, f);
                    bt.eq_now[f] = v_sec;
                    bt.contact_now[f] = c;
                    raise(&mut p.shear_with_damping, v_sec.abs());
                }
            }
        }
        // the accelerations and the equilibrium shear where fast modes ring: the stations whose
        // bound over the interval (both ends, the fast modes' part twice: at the ends and
        // between) can beat a peak, and whose ringing is not negligible
        bt.flagged.clear();
        if ringing && h.is_some() {
            let g = &st.grid;
            // 1/cos(Θ/2): a sinusoid followed over `ω h ≤ Θ` exceeds the larger of its end
            // values by at most this factor (its crest midway, the ends Θ/2 from it)
            let slow_reach = 1.0 / (0.5 * resolution.unwrap_or(0.0)).cos();
            let (ra, rest) = bt.rings.split_at_mut(ns);
            let (re, rest) = rest.split_at_mut(ns);
            let (fa, fe) = rest.split_at_mut(2 * ns);
            g.fast_parts((phi, &bt.abs_acc), (omega, damp), ns, ra, fa);
            g.fast_parts((&bt.eq_rows, &bt.abs_eq), (omega, damp), ns, re, fe);
            for f in 0..ns {
                let p = &st.peaks[f];
                // the slow part (slow modes and the linear parts) at its larger end, widened by
                // `slow_reach`, and the fast modes' ringing; a ringing whose swing stays below
                // NEGLIGIBLE of the peak is left out
                let judge = |y0: f64, y1: f64, fast0: f64, fast1: f64, ring: f64, peak: f64| {
                    let slow = (y0 - fast0).abs().max((y1 - fast1).abs());
                    2.0 * ring > NEGLIGIBLE * peak && slow_reach * slow + ring > peak
                };
                // (with the sign the equilibrium gives the modes' part: V = C − Σ E η̈ − M a_g)
                if judge(
                    bt.prev_acc[f],
                    abs[f],
                    fa[f],
                    fa[ns + f],
                    ra[f],
                    p.acceleration,
                ) || judge(
                    bt.prev_eq[f],
                    bt.eq_now[f],
                    -fe[f],
                    -fe[ns + f],
                    re[f],
                    p.shear_with_damping,
                ) {
                    bt.flagged.push(f);
                }
            }
        }
        if let (false, Some(theta), Some(h)) = (st.flagged.is_empty(), resolution, h) {
            let largest =
                |x: fn(&FloorPeaks) -> f64| -> f64 { st.peaks.iter().map(x).fold(0.0, f64::max) };
            let peak = [
                largest(|p| p.displacement),
                largest(|p| p.drift),
                largest(|p| p.shear),
            ];
            let cmax = [&st.cmax[0][..], &st.cmax[1][..], &st.cmax[2][..]];
            let resolve = st.grid.resolved_omega(omega, cmax, peak);
            st.grid
                .evaluate(h, theta, (q, v), omega, damp, resolve, phi, rows, ns);
            refine_on_subgrid(&st.grid, &st.flagged, ns, rows.is_some(), &mut st.peaks);
        }
        if let (false, Some(theta), Some(h)) = (st.between.flagged.is_empty(), resolution, h) {
            let prev_ag = st.between.prev_ag;
            between_on_subgrid(
                (&mut st.grid, &mut st.between),
                (
                    &mut st.peaks[..],
                    &mut st.hold[..],
                    &st.abs_now[..],
                    &st.phi[..],
                ),
                (at.t, h, theta),
                (q, v),
                (omega, damp),
                (prev_ag, ag),
            );
        }
        // the accelerations and the equilibrium shear between the observations of a free flight
        // where no mode rings too fast for the cubic Hermite ([`between_on_hermite`]; inside an
        // impact pulse the forcing is not linear: `pulse`)
        let loaded = !st.loaded.is_empty();
        if let (Some(h), Some(_), false) = (h, resolution, ringing)
            && !loaded
            && !st.between.prev_loaded
            && let Some((j0, j1)) = jerks::<WIDE>(&mut st.grid, h, (v, a), (omega, damp))
        {
            let la = &system.ground_load()[st.offset..st.offset + nm];
            let bt = &mut st.between;
            bt.fill_ground_gain(&st.phi, la, (ns, nm));
            hermite_between::<WIDE>(
                (&mut st.peaks[..ns], &mut st.hold[..ns]),
                &st.between,
                (&st.abs_now[..ns], &st.phi[..ns * nm]),
                (j0, j1, la),
                (at.t, h, ag),
            );
        }
        st.between.prev_loaded = loaded;
        if resolution.is_some() {
            st.grid.advance(q, v);
        }
        let bt = &mut st.between;
        // (abs_now: this observation's values, not the interval's largest)
        bt.prev_acc[..ns].copy_from_slice(&st.abs_now[..ns]);
        bt.prev_eq[..ns].copy_from_slice(&bt.eq_now[..ns]);
        bt.prev_contact[..ns].copy_from_slice(&bt.contact_now[..ns]);
        bt.prev_ag = ag;
    }

    /// The accelerations of its last observation count towards the next history sample.
    pub(super) fn hold_now(&mut self) {
        for f in 0..self.heights.len() {
            if self.abs_now[f].abs() > self.hold[f].abs() {
                self.hold[f] = self.abs_now[f];
            }
        }
    }

    /// The peaks, with the springs' storey forces formed from the peak drifts.
    pub(super) fn finish(mut self) -> Vec<FloorPeaks> {
        if let StoreyForce::Springs(k) = &self.force {
            for ((p, k), y) in self.peaks.iter_mut().zip(k).zip(&self.yields) {
                if y.is_none() {
                    p.shear = k * p.drift;
                }
            }
        }
        self.peaks
    }
}
