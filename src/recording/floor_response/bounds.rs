//! A station's peak between two observations from its values and rates at both ends: the
//! cubic Hermite's bound ([`reach`]) that decides whether an interval can change a peak at all,
//! the refinement on the Hermite ([`refine`]), one station's full update at an observation, the
//! bound where fast modes ring, and the refinement on the sub-grid's parts. Pure functions over
//! the values they are given.

use super::FloorPeaks;
use crate::numerics::hermite::hermite_abs_max;
use crate::recording::subgrid::SubGrid;

/// The largest of the cubic Hermite slope basis functions θ(1−θ)², θ²(1−θ) on [0, 1].
pub(super) const HERMITE_REACH: f64 = 4.0 / 27.0;

/// `peak = max(peak, x)` as a plain comparison (no NaN handling: a NaN state has already
/// stopped the run as diverged).
#[inline(always)]
pub(super) fn raise(peak: &mut f64, x: f64) {
    if x > *peak {
        *peak = x;
    }
}

/// An upper bound of |y(θ)| over the cubic Hermite interpolant y of (y0, d0), (y1, d1) over a
/// step `h` (module [`crate::numerics::hermite`]): its value weights h00, h01 are ≥ 0 and sum
/// to 1, so they give at most the larger |end value|; its slope weights θ(1−θ)² and θ²(1−θ)
/// are at most 4/27 (at θ = 1/3 and 2/3: the roots of their derivatives), so the slope terms
/// add at most (4/27)·h·(|d0| + |d1|). The same expression, evaluated in the same order, is
/// the test of [`refine`] and of the stations' skip in [`super::FloorRecorder::observe`]: a station
/// whose bounds do not exceed its peaks is one where `refine` and `raise` change nothing.
#[inline(always)]
pub(crate) fn reach(y0: f64, d0: f64, y1: f64, d1: f64, h: f64) -> f64 {
    // (a plain comparison, not f64::max: one instruction, and the values are finite)
    let ends = if y0.abs() > y1.abs() {
        y0.abs()
    } else {
        y1.abs()
    };
    ends + HERMITE_REACH * h * (d0.abs() + d1.abs())
}

/// Refine `peak` on the cubic Hermite interpolant of (y0, d0), (y1, d1) over a step `h`, only
/// where it could beat the peak ([`reach`]).
#[inline(always)]
pub(crate) fn refine(peak: &mut f64, y0: f64, d0: f64, y1: f64, d1: f64, h: f64) {
    if reach(y0, d0, y1, d1, h) > *peak {
        raise(peak, hermite_abs_max(y0, d0, y1, d1, h));
    }
}

/// The full update of one station's peaks at an observation at time `t` (`h` since the
/// previous one): displacement and drift (`ends`: (y, ẏ) at the previous observation and at
/// this one, of the displacement then of the drift) raised to this observation's values and
/// refined between the observations, the absolute acceleration `a`, and the storey force
/// `force` (V, V̇; `None`: formed at the end from the drift, storey springs) with its value at
/// the previous observation in `prev_force`, which becomes this one's.
#[inline(never)]
pub(super) fn update_station(
    p: &mut FloorPeaks,
    prev_force: &mut (f64, f64),
    (t, h): (f64, Option<f64>),
    [(up, udp), (u, ud), (dp, ddp), (d, dd)]: [(f64, f64); 4],
    a: f64,
    force: Option<(f64, f64)>,
) {
    raise(&mut p.displacement, u.abs());
    raise(&mut p.drift, d.abs());
    if let Some(h) = h {
        refine(&mut p.displacement, up, udp, u, ud, h);
        refine(&mut p.drift, dp, ddp, d, dd, h);
    }
    if a.abs() > p.acceleration {
        p.acceleration = a.abs();
        p.acceleration_time = t;
    }
    if let Some((v1, vd1)) = force {
        raise(&mut p.shear, v1.abs());
        if let Some(h) = h {
            let (v0, vd0) = *prev_force;
            refine(&mut p.shear, v0, vd0, v1, vd1, h);
        }
        *prev_force = (v1, vd1);
    }
}

/// A bound of |Q| over an interval of length `h` for a station quantity `Q = Σ c_n η_n` with
/// (Q, Q̇) at its ends `ends`, from the fast modes' sums `s` (`Σ c_n [η₀, η̇₀, η₁, η̇₁, α, β]`)
/// and their ringing `ring = Σ |c_n| ρ_n` ([`crate::recording::subgrid`]): the Hermite bound
/// of the slow modes' part ([`reach`]), the fast modes' linear part at its larger end, and
/// their ringing.
#[inline(always)]
pub(super) fn ring_bound(ends: (f64, f64, f64, f64), s: &[f64; 6], ring: f64, h: f64) -> f64 {
    let slow = reach(
        ends.0 - s[0],
        ends.1 - s[1],
        ends.2 - s[2],
        ends.3 - s[3],
        h,
    );
    // (a plain comparison for f64::max: the values are finite)
    let (l0, l1) = (s[4].abs(), (s[4] + s[5] * h).abs());
    let linear = if l0 > l1 { l0 } else { l1 };
    slow + linear + ring
}

/// The peaks of displacement, drift and (`rows`) storey force of the stations `flagged` (of
/// `ns`) refined on the sub-grid's parts (values and rates from the modes' closed forms).
pub(super) fn refine_on_subgrid(
    g: &SubGrid,
    flagged: &[usize],
    ns: usize,
    rows: bool,
    peaks: &mut [FloorPeaks],
) {
    let dl = g.delta;
    for &f in flagged {
        let p = &mut peaks[f];
        for k in 0..g.parts {
            let (i0, i1) = (k * ns + f, (k + 1) * ns + f);
            let (u0, ud0, u1, ud1) = (g.u[i0], g.ud[i0], g.u[i1], g.ud[i1]);
            refine(&mut p.displacement, u0, ud0, u1, ud1, dl);
            let (b0, bd0, b1, bd1) = if f > 0 {
                (g.u[i0 - 1], g.ud[i0 - 1], g.u[i1 - 1], g.ud[i1 - 1])
            } else {
                (0.0, 0.0, 0.0, 0.0)
            };
            refine(&mut p.drift, u0 - b0, ud0 - bd0, u1 - b1, ud1 - bd1, dl);
            if rows {
                refine(&mut p.shear, g.v[i0], g.vd[i0], g.v[i1], g.vd[i1], dl);
            }
        }
    }
}
