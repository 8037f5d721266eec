//! Small dense linear algebra on slices, for the hot loops (no allocation).

/// `xⁿ`, correctly rounded (libm's `pow`), for tables built once from constants (collocation
/// nodes): `f64::powi` there is either folded by the compiler with a correctly rounded `pow`
/// or, where inlining leaves it to run time, computed by repeated squaring (one rounding per
/// multiplication), so the tables' last bits, and every result through them, would depend on
/// unrelated code changes. Not for hot loops.
pub(crate) fn power(x: f64, n: u32) -> f64 {
    x.powf(f64::from(n))
}

/// Dot product.
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    // four partial sums for long rows: the additions of one chain would wait on each other
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    if n < 8 {
        let mut s = 0.0;
        for i in 0..n {
            s += a[i] * b[i];
        }
        return s;
    }
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for i in 0..4 {
            acc[i] += x[i] * y[i];
        }
    }
    for (i, (x, y)) in ra.iter().zip(rb).enumerate() {
        acc[i] += x * y;
    }
    (acc[0] + acc[2]) + (acc[1] + acc[3])
}
