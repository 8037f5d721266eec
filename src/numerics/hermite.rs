//! The cubic Hermite interpolant on one interval: the one copy of its basis, used by the
//! integrators (onset speeds, crossings, contact bounds) and by the recorder (history samples,
//! peaks between observations).
//!
//! On `[0, h]` with values `y0`, `y1` and derivatives `d0`, `d1` (per unit of τ = θh) at its
//! ends, the interpolant is (de Boor, *A Practical Guide to Splines*, 2001, ch. IV, eq. (6)–(7);
//! Burden & Faires, *Numerical Analysis*, §3.4)
//!
//! ```text
//! y(θ) = h00(θ) y0 + h10(θ) h d0 + h01(θ) y1 + h11(θ) h d1,   θ = τ/h ∈ [0, 1]
//! h00 = 2θ³ − 3θ² + 1,  h10 = θ³ − 2θ² + θ,  h01 = 3θ² − 2θ³,  h11 = θ³ − θ²
//! ```
//!
//! and its error for a smooth f is `f⁗(ξ) τ²(h − τ)²/24` (Hermite's remainder). The sums are
//! formed in one fixed order (basis × h × derivative): every caller gets the same bits.

/// The four cubic Hermite basis functions at one θ ∈ [0, 1] (see the module).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Basis {
    /// Weight of the start value, `2θ³ − 3θ² + 1`.
    pub h00: f64,
    /// Weight of the start slope × h, `θ³ − 2θ² + θ`.
    pub h10: f64,
    /// Weight of the end value, `3θ² − 2θ³`.
    pub h01: f64,
    /// Weight of the end slope × h, `θ³ − θ²`.
    pub h11: f64,
}

impl Basis {
    /// The basis at θ.
    #[inline(always)]
    pub fn at(th: f64) -> Basis {
        let (t2, t3) = (th * th, th * th * th);
        Basis {
            h00: 2.0 * t3 - 3.0 * t2 + 1.0,
            h10: t3 - 2.0 * t2 + th,
            h01: 3.0 * t2 - 2.0 * t3,
            h11: t3 - t2,
        }
    }

    /// The derivatives dh/dθ of the basis at θ: `6θ² − 6θ`, `3θ² − 4θ + 1`, `6θ − 6θ²`,
    /// `3θ² − 2θ` (in the fields of the same names; 6θ² formed as (6θ)·θ, the order in which
    /// the contact onset speeds have always been computed).
    #[inline(always)]
    pub fn slope_at(th: f64) -> Basis {
        Basis {
            h00: 6.0 * th * th - 6.0 * th,
            h10: 3.0 * th * th - 4.0 * th + 1.0,
            h01: 6.0 * th - 6.0 * th * th,
            h11: 3.0 * th * th - 2.0 * th,
        }
    }

    /// The interpolant of (y0, d0) at τ = 0 and (y1, d1) at τ = h with these weights
    /// (derivatives per unit of τ).
    #[inline(always)]
    pub fn combine(&self, y0: f64, d0: f64, y1: f64, d1: f64, h: f64) -> f64 {
        self.h00 * y0 + self.h10 * h * d0 + self.h01 * y1 + self.h11 * h * d1
    }
}

/// Cubic Hermite interpolant on [0, h] of values y0, y1 with derivatives d0, d1, at θ = τ/h.
#[inline]
pub fn hermite(y0: f64, d0: f64, y1: f64, d1: f64, h: f64, th: f64) -> f64 {
    Basis::at(th).combine(y0, d0, y1, d1, h)
}

/// The interpolant's derivative dy/dτ at θ = τ/h (h > 0).
#[inline]
pub fn hermite_slope(y0: f64, d0: f64, y1: f64, d1: f64, h: f64, th: f64) -> f64 {
    Basis::slope_at(th).combine(y0, d0, y1, d1, h) / h
}

/// Where the interpolant changes sign between its ends (y0 and y1 of opposite signs, or
/// y1 = 0): θ ∈ [0, 1] by `iterations` bisections of the bracket whose lower end keeps the
/// sign of y0 (positive or not), to 2^−iterations.
#[inline]
pub fn hermite_crossing(y0: f64, d0: f64, y1: f64, d1: f64, h: f64, iterations: u32) -> f64 {
    let start_up = y0 > 0.0;
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..iterations {
        let mid = 0.5 * (lo + hi);
        if (hermite(y0, d0, y1, d1, h, mid) > 0.0) == start_up {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Largest value over [0, h] of the cubic Hermite interpolant of (y0, d0), (y1, d1), and where
/// (θ = τ/h ∈ [0, 1]).
#[inline]
pub fn hermite_max(y0: f64, d0: f64, y1: f64, d1: f64, h: f64) -> (f64, f64) {
    let mut best = if y1 > y0 { (y1, 1.0) } else { (y0, 0.0) };
    hermite_critical_points(y0, d0, y1, d1, h, |th| {
        let y = hermite(y0, d0, y1, d1, h, th);
        if y > best.0 {
            best = (y, th);
        }
    });
    best
}

/// The largest of the cubic Hermite slope basis functions θ(1−θ)² and θ²(1−θ) on [0, 1].
pub const HERMITE_REACH: f64 = 4.0 / 27.0;

/// An upper bound of the cubic Hermite interpolant of (y0, d0), (y1, d1) over a step `h`,
/// without its root solve: its value basis functions are ≥ 0 and sum to 1 (at most the larger
/// end value), its slope terms θ(1−θ)²·h·d0 ≥ 0 ≥ −θ²(1−θ)·h·d1 add at most
/// (4/27)·h·(d0⁺ + d1⁻). A step whose bound does not beat a running maximum cannot raise it.
/// (Rounding: [`hermite_max`]'s evaluation may exceed it by a few ulps of
/// |y0| + |y1| + h(|d0| + |d1|); a caller that must decide as [`hermite_max`] would adds a
/// slack of that size.)
#[inline(always)]
pub fn hermite_bound(y0: f64, d0: f64, y1: f64, d1: f64, h: f64) -> f64 {
    big(y0, y1) + HERMITE_REACH * h * (big(d0, 0.0) - small(d1, 0.0))
}

/// `a.max(b)` as a plain comparison for finite values (`f64::max`'s NaN handling costs
/// instructions; a bound is only compared, so a zero's sign does not matter).
#[inline(always)]
pub(crate) fn big(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// `a.min(b)` as [`big`] is `max`.
#[inline(always)]
pub(crate) fn small(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// Largest absolute value over [0, h] of the cubic Hermite interpolant of (y0, d0), (y1, d1).
/// An interior extremum does not need the end slopes to differ in sign: a cubic whose end
/// slopes do not fit its end values (after a velocity jump, or over a step long against the
/// motion) overshoots between them with slopes of one sign at both ends.
#[inline]
pub fn hermite_abs_max(y0: f64, d0: f64, y1: f64, d1: f64, h: f64) -> f64 {
    let mut best = y0.abs().max(y1.abs());
    hermite_critical_points(y0, d0, y1, d1, h, |th| {
        best = best.max(hermite(y0, d0, y1, d1, h, th).abs());
    });
    best
}

/// Calls `consider(θ)` at the interior critical points θ ∈ (0, 1) of the cubic Hermite
/// interpolant of (y0, d0), (y1, d1) over a step h (the roots of its derivative, a quadratic,
/// by the cancellation-free form `q = −(b + sign(b)√disc)/2`, roots q/a and c/q: Press et al.,
/// *Numerical Recipes*, 3rd ed., §5.6).
#[inline]
fn hermite_critical_points(
    y0: f64,
    d0: f64,
    y1: f64,
    d1: f64,
    h: f64,
    mut consider: impl FnMut(f64),
) {
    let (m0, m1) = (h * d0, h * d1);
    let a = 6.0 * y0 + 3.0 * m0 - 6.0 * y1 + 3.0 * m1;
    let b = -6.0 * y0 - 4.0 * m0 + 6.0 * y1 - 2.0 * m1;
    let c = m0;
    let mut consider = |th: f64| {
        if th > 0.0 && th < 1.0 {
            consider(th);
        }
    };
    if a.abs() <= 1e-14 * (b.abs() + c.abs()) {
        if b != 0.0 {
            consider(-c / b);
        }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let r = disc.sqrt();
            let q = -0.5 * (b + b.signum() * r);
            if q != 0.0 {
                consider(q / a);
                consider(c / q);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic is its own Hermite interpolant: values and slopes of p(τ) = 2 − τ + 3τ² − 0.5τ³
    /// on [0, h] with h = 1.7, at 11 points (to round-off: the basis sums are exact for cubics).
    #[test]
    fn reproduces_a_cubic_and_its_slope() {
        let p = |t: f64| 2.0 - t + 3.0 * t * t - 0.5 * t * t * t;
        let dp = |t: f64| -1.0 + 6.0 * t - 1.5 * t * t;
        let h = 1.7;
        for i in 0..=10 {
            let th = i as f64 / 10.0;
            let t = th * h;
            let y = hermite(p(0.0), dp(0.0), p(h), dp(h), h, th);
            let d = hermite_slope(p(0.0), dp(0.0), p(h), dp(h), h, th);
            assert!((y - p(t)).abs() < 1e-12 * (1.0 + p(t).abs()), "{th}: {y}");
            assert!((d - dp(t)).abs() < 1e-12 * (1.0 + dp(t).abs()), "{th}: {d}");
        }
    }

    /// The value weights sum to 1 and the ends are interpolated (h00(0) = h01(1) = 1).
    #[test]
    fn basis_is_a_partition_of_unity() {
        for i in 0..=20 {
            let b = Basis::at(i as f64 / 20.0);
            assert!((b.h00 + b.h01 - 1.0).abs() < 1e-15);
        }
        assert_eq!(
            Basis::at(0.0),
            Basis {
                h00: 1.0,
                h10: 0.0,
                h01: 0.0,
                h11: 0.0
            }
        );
        assert_eq!(
            Basis::at(1.0),
            Basis {
                h00: 0.0,
                h10: 0.0,
                h01: 1.0,
                h11: 0.0
            }
        );
    }

    /// The crossing of p(τ) = τ² − 0.3 (a quadratic: interpolated exactly) on [0, 1] is √0.3,
    /// from below and, for −p, from above; 60 bisections resolve it to 1e-15.
    #[test]
    fn crossing_of_a_quadratic() {
        let r = 0.3f64.sqrt();
        let th = hermite_crossing(-0.3, 0.0, 0.7, 2.0, 1.0, 60);
        assert!((th - r).abs() < 1e-14, "{th}");
        let th = hermite_crossing(0.3, 0.0, -0.7, -2.0, 1.0, 60);
        assert!((th - r).abs() < 1e-14, "{th}");
    }

    /// [`hermite_bound`] is at least [`hermite_max`] (its value as evaluated, rounding
    /// included) up to the slack of 1e-12 (|y0| + |y1| + h(|d0| + |d1|)) that free flight's
    /// skip adds, for random data over many orders of magnitude — and the bound itself is at
    /// least the largest of 2001 samples of the cubic.
    #[test]
    fn the_bound_is_at_least_the_maximum() {
        use proptest::prelude::*;
        let mag = || (-6.0f64..2.0, -1.0f64..1.0).prop_map(|(e, s)| s * 10f64.powf(e));
        let data = (mag(), mag(), mag(), mag(), -4.0f64..0.0)
            .prop_map(|(y0, d0, y1, d1, e)| (y0, d0 * 1e2, y1, d1 * 1e2, 10f64.powf(e)));
        proptest!(ProptestConfig::with_cases(4000), |((y0, d0, y1, d1, h) in data)| {
            let b = hermite_bound(y0, d0, y1, d1, h);
            let slack = 1e-12 * (y0.abs() + y1.abs() + h * (d0.abs() + d1.abs()));
            let (m, _) = hermite_max(y0, d0, y1, d1, h);
            prop_assert!(m <= b + slack, "max {m:e} above the bound {b:e}");
            let mut top = f64::NEG_INFINITY;
            for i in 0..=2000 {
                top = top.max(hermite(y0, d0, y1, d1, h, i as f64 / 2000.0));
            }
            prop_assert!(top <= b + slack, "sample {top:e} above the bound {b:e}");
        });
    }

    /// Values 0 at both ends of [0, π] with slopes 1 and −1 (as sin): the interpolant is
    /// π(h10 − h11) = πθ(1 − θ), largest at θ = ½ with value π/4; the negated data's largest
    /// |value| is the same.
    #[test]
    fn maxima_of_the_interpolant() {
        let h = std::f64::consts::PI;
        let (m, th) = hermite_max(0.0, 1.0, 0.0, -1.0, h);
        assert!(
            (m - h / 4.0).abs() < 1e-15 && (th - 0.5).abs() < 1e-15,
            "{m} {th}"
        );
        assert!((hermite_abs_max(0.0, -1.0, 0.0, 1.0, h) - h / 4.0).abs() < 1e-15);
        // monotone data: the larger end
        assert_eq!(hermite_max(0.0, 1.0, 1.0, 1.0, 1.0), (1.0, 1.0));
    }
}
