//! The nodes of both Lobatto schemes, the 5-node scheme's weights and both schemes' Lagrange
//! bases ([`Bases`], computed once).

use crate::numerics::linalg::power;

/// The two interior nodes of the 4-node companion, ½ ∓ 1/(2√5).
pub(super) const A1: f64 = 0.276_393_202_250_021;
pub(super) const A2: f64 = 0.723_606_797_749_978_9;
/// The interior nodes of the 5-node scheme, ½ ∓ √(3/7)/2 and ½.
pub(super) const B1: f64 = 0.172_673_164_646_011_43;
const B3: f64 = 0.827_326_835_353_988_6;

/// Every node a table holds, as fractions of the step: the companion's interior nodes, the
/// propagated scheme's interior nodes, the end.
pub(in crate::integrate) const NODES: [f64; 6] = [A1, A2, B1, 0.5, B3, 1.0];
/// The end node's index in [`NODES`].
pub(in crate::integrate) const END: usize = 5;
/// The propagated scheme: its nodes after the start, as indices into [`NODES`].
pub(in crate::integrate) const NODES8: [usize; 4] = [2, 3, 4, END];
/// The companion: its nodes after the start, as indices into [`NODES`].
pub(in crate::integrate) const NODES6: [usize; 3] = [0, 1, END];
/// Lobatto weights of the 5-node scheme on [0, 1] (nodes 0, B1, ½, B3, 1): exact for
/// polynomials of degree 7.
pub(in crate::integrate) const WEIGHTS8: [f64; 5] = [
    1.0 / 20.0,
    49.0 / 180.0,
    16.0 / 45.0,
    49.0 / 180.0,
    1.0 / 20.0,
];
/// The 5-node scheme's nodes on [0, 1], start included.
pub(in crate::integrate) const THETA8: [f64; 5] = [0.0, B1, 0.5, B3, 1.0];
/// The 4-node scheme's nodes on [0, 1], start included.
const THETA6: [f64; 4] = [0.0, A1, A2, 1.0];

/// Coefficients of the Lagrange basis of `theta`: `ℓ_p(x) = Σ_m out[m][p] x^m` (the inverse
/// of the Vandermonde matrix, by Gauss–Jordan with partial pivoting; at most 5×5 and well
/// conditioned).
pub(super) fn lagrange<const S: usize>(theta: &[f64; S]) -> [[f64; S]; S] {
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
pub(in crate::integrate) struct Bases {
    pub(super) l8: [[f64; 5]; 5],
    pub(super) l6: [[f64; 4]; 4],
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
pub(in crate::integrate) const SEVEN: [f64; 7] = [0.0, B1, A1, 0.5, A2, B3, 1.0];

/// See [`Bases`].
pub(in crate::integrate) fn bases() -> &'static Bases {
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
    pub(in crate::integrate) fn quartic_at(&self, values: &[f64; 5], x: f64) -> f64 {
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
