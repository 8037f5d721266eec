//! Two lanes of f64 (the same operation on two values), for the hot passes over modes: on
//! x86-64 one SSE2 register (the baseline of every x86-64 processor), so that each operation
//! is one vector instruction whatever the compiler's vectoriser would have paired; elsewhere
//! two plain values. Either way each lane is the IEEE operation on its own values: the same
//! bits as the scalar code. (The intrinsics are `unsafe` only as target-feature functions;
//! SSE2 is part of the x86-64 architecture's baseline, enabled on every x86-64 target.)

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::{
    __m128d, _mm_add_pd, _mm_andnot_pd, _mm_cvtsd_f64, _mm_mul_pd, _mm_set_pd, _mm_set1_pd,
    _mm_setzero_pd, _mm_sub_pd, _mm_unpackhi_pd,
};

/// Two f64 lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct F2(
    #[cfg(target_arch = "x86_64")] __m128d,
    #[cfg(not(target_arch = "x86_64"))] [f64; 2],
);

#[cfg(target_arch = "x86_64")]
impl F2 {
    /// Lanes (a, b).
    #[inline(always)]
    pub(crate) fn new(a: f64, b: f64) -> F2 {
        // SAFETY: SSE2 is in every x86-64 target's baseline (see the module)
        F2(unsafe { _mm_set_pd(b, a) })
    }

    /// Both lanes x.
    #[inline(always)]
    pub(crate) fn splat(x: f64) -> F2 {
        // SAFETY: as in `new`
        F2(unsafe { _mm_set1_pd(x) })
    }

    /// Both lanes 0.
    #[inline(always)]
    pub(crate) fn zero() -> F2 {
        // SAFETY: as in `new`
        F2(unsafe { _mm_setzero_pd() })
    }

    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn get(self) -> [f64; 2] {
        // SAFETY: as in `new`
        unsafe {
            [
                _mm_cvtsd_f64(self.0),
                _mm_cvtsd_f64(_mm_unpackhi_pd(self.0, self.0)),
            ]
        }
    }

    /// |x| in each lane (the sign bit cleared, as `f64::abs`).
    #[inline(always)]
    pub(crate) fn abs(self) -> F2 {
        // SAFETY: as in `new`
        F2(unsafe { _mm_andnot_pd(_mm_set1_pd(-0.0), self.0) })
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl F2 {
    /// Lanes (a, b).
    #[inline(always)]
    pub(crate) fn new(a: f64, b: f64) -> F2 {
        F2([a, b])
    }

    /// Both lanes x.
    #[inline(always)]
    pub(crate) fn splat(x: f64) -> F2 {
        F2([x; 2])
    }

    /// Both lanes 0.
    #[inline(always)]
    pub(crate) fn zero() -> F2 {
        F2([0.0; 2])
    }

    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn get(self) -> [f64; 2] {
        self.0
    }

    /// |x| in each lane.
    #[inline(always)]
    pub(crate) fn abs(self) -> F2 {
        F2([self.0[0].abs(), self.0[1].abs()])
    }
}

impl F2 {
    /// Lanes (x[0], x[1]).
    #[inline(always)]
    pub(crate) fn load(x: &[f64; 2]) -> F2 {
        F2::new(x[0], x[1])
    }
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $intr:ident, $op:tt) => {
        impl std::ops::$tr for F2 {
            type Output = F2;
            #[inline(always)]
            fn $f(self, o: F2) -> F2 {
                #[cfg(target_arch = "x86_64")]
                {
                    // SAFETY: as in `F2::new`
                    F2(unsafe { $intr(self.0, o.0) })
                }
                #[cfg(not(target_arch = "x86_64"))]
                {
                    F2([self.0[0] $op o.0[0], self.0[1] $op o.0[1]])
                }
            }
        }
    };
}

lane_op!(Add, add, _mm_add_pd, +);
lane_op!(Sub, sub, _mm_sub_pd, -);
lane_op!(Mul, mul, _mm_mul_pd, *);

#[cfg(test)]
mod tests {
    use super::F2;

    /// Every lane operation is the scalar IEEE operation on its lane, bit for bit, on values
    /// that round (thirds, sevenths), signed zeros, subnormals and infinities.
    #[test]
    fn lanes_are_the_scalar_operations() {
        let xs = [
            1.0 / 3.0,
            -2.0 / 7.0,
            0.0,
            -0.0,
            5e-324,
            -1e308,
            f64::INFINITY,
            123.456,
        ];
        for &a in &xs {
            for &b in &xs {
                let (x, y) = (F2::new(a, b), F2::new(b, a));
                let same = |v: F2, w: [f64; 2]| {
                    let g = v.get();
                    (0..2)
                        .all(|i| g[i].to_bits() == w[i].to_bits() || g[i].is_nan() && w[i].is_nan())
                };
                assert!(same(x + y, [a + b, b + a]));
                assert!(same(x - y, [a - b, b - a]));
                assert!(same(x * y, [a * b, b * a]));
                assert!(same(x.abs(), [a.abs(), b.abs()]));
                assert_eq!(F2::splat(a).get()[1].to_bits(), a.to_bits());
                assert_eq!(F2::load(&[a, b]).get()[0].to_bits(), a.to_bits());
            }
        }
        assert_eq!(F2::zero().get(), [0.0, 0.0]);
    }
}
