//! The free flight to a contact step's six nodes projected on a level: the sums over the
//! modes of each node's coupled propagators times the modes' start (Σ_j c_kj P(θh)(x₀, y₀)),
//! two nodes at a time in AVX registers where the processor has AVX, else one node in the two
//! lanes of [`F2`] — the same operations in the same order, so the same bits.

use crate::numerics::lanes::F2;

/// The six nodes' sums `Σ_j (a x_j + b y_j, c x_j + e y_j)` of a level's coupled propagators
/// `rows[i][j] = [a, c, b, e]` ([`Table::cprop_rows`](super::super::super::collocation::Table::cprop_rows)) over the modes in order, each node's
/// (δ, δ̇) sums in the two lanes of one register: lane 0 adds a·x + b·y, lane 1 c·x + e·y,
/// the very operations of the scalar sums.
#[inline(always)]
pub(super) fn node_sums(rows: [&[[f64; 4]]; 6], xs: &[f64], ys: &[f64]) -> [(f64, f64); 6] {
    let w = xs.len().min(ys.len());
    let rows: [&[[f64; 4]]; 6] = rows.map(|row| &row[..w]);
    let mut acc = [F2::zero(); 6];
    for jj in 0..w {
        let (x, y) = (F2::splat(xs[jj]), F2::splat(ys[jj]));
        for (s, row) in acc.iter_mut().zip(&rows) {
            let [a, c, b, e] = row[jj];
            *s = *s + (F2::new(a, c) * x + F2::new(b, e) * y);
        }
    }
    acc.map(|s| {
        let [s0, s1] = s.get();
        (s0, s1)
    })
}

/// [`node_sums`] with two nodes in the four lanes of one AVX register
/// ([`Table::cprop_pairs`](super::super::super::collocation::Table::cprop_pairs)): each lane does its node's operations of [`node_sums`], in the
/// same order (s + (a·x + b·y), no fused multiply–add), so the sums are the same bits in half
/// the vector operations. Safety: the processor has AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
pub(super) unsafe fn node_sums_avx(
    pairs: [&[[[f64; 4]; 2]]; 3],
    xs: &[f64],
    ys: &[f64],
) -> [(f64, f64); 6] {
    use std::arch::x86_64::{
        _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_setzero_pd,
        _mm256_storeu_pd,
    };
    let w = xs.len().min(ys.len());
    let pairs: [&[[[f64; 4]; 2]]; 3] = pairs.map(|p| &p[..w]);
    let mut acc = [_mm256_setzero_pd(); 3];
    for jj in 0..w {
        let (x, y) = (_mm256_set1_pd(xs[jj]), _mm256_set1_pd(ys[jj]));
        for (s, p) in acc.iter_mut().zip(&pairs) {
            let [ac, be] = &p[jj];
            // SAFETY: AVX (the caller); each array holds four values
            let (ac, be) = unsafe { (_mm256_loadu_pd(ac.as_ptr()), _mm256_loadu_pd(be.as_ptr())) };
            *s = _mm256_add_pd(
                *s,
                _mm256_add_pd(_mm256_mul_pd(ac, x), _mm256_mul_pd(be, y)),
            );
        }
    }
    let mut out = [(0.0, 0.0); 6];
    for (i, s) in acc.iter().enumerate() {
        let mut v = [0.0; 4];
        // SAFETY: AVX (the caller); `v` holds four values
        unsafe { _mm256_storeu_pd(v.as_mut_ptr(), *s) };
        out[2 * i] = (v[0], v[1]);
        out[2 * i + 1] = (v[2], v[3]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The four-lane sums are the two-lane sums bit for bit, for every mode count from 0 to
    /// 13, on values of mixed signs and magnitudes (whose sums round differently in any
    /// other order: a reordering would show). Without AVX there is nothing to compare.
    #[test]
    fn two_nodes_in_four_lanes_are_the_two_lane_sums_bit_for_bit() {
        #[cfg(target_arch = "x86_64")]
        {
            if !crate::numerics::vex::available() {
                eprintln!("no AVX on this processor: the four-lane path is not compared");
                return;
            }
            // a reproducible spread of values over 1e-8 .. 1e8 of both signs
            let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
            let mut next = move || {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
                let sign = if seed & 1 == 0 { 1.0 } else { -1.0 };
                sign * (1.0 + u) * 10f64.powi(((seed >> 3) % 17) as i32 - 8)
            };
            for w in 0..=13 {
                let rows: Vec<Vec<[f64; 4]>> = (0..6)
                    .map(|_| (0..w).map(|_| [next(), next(), next(), next()]).collect())
                    .collect();
                let xs: Vec<f64> = (0..w).map(|_| next()).collect();
                let ys: Vec<f64> = (0..w).map(|_| next()).collect();
                let pairs: Vec<Vec<[[f64; 4]; 2]>> = (0..3)
                    .map(|p| {
                        (0..w)
                            .map(|j| {
                                let ([a0, c0, b0, e0], [a1, c1, b1, e1]) =
                                    (rows[2 * p][j], rows[2 * p + 1][j]);
                                [[a0, c0, a1, c1], [b0, e0, b1, e1]]
                            })
                            .collect()
                    })
                    .collect();
                let two = node_sums(std::array::from_fn(|i| rows[i].as_slice()), &xs, &ys);
                // SAFETY: the processor has AVX (tested above)
                let four = unsafe {
                    node_sums_avx(std::array::from_fn(|p| pairs[p].as_slice()), &xs, &ys)
                };
                for (a, b) in two.iter().zip(&four) {
                    assert_eq!(a.0.to_bits(), b.0.to_bits(), "w = {w}");
                    assert_eq!(a.1.to_bits(), b.1.to_bits(), "w = {w}");
                }
                // and the sums are the scalar ones, in mode order
                for (i, row) in rows.iter().enumerate() {
                    let (mut d, mut dd) = (0.0, 0.0);
                    for j in 0..w {
                        let [a, c, b, e] = row[j];
                        d += a * xs[j] + b * ys[j];
                        dd += c * xs[j] + e * ys[j];
                    }
                    assert_eq!(
                        (d.to_bits(), dd.to_bits()),
                        (two[i].0.to_bits(), two[i].1.to_bits())
                    );
                }
            }
        }
    }
}
