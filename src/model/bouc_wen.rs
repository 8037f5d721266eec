//! The smooth Bouc–Wen law of a yielding storey (issue 16; docs/model.md §2.6b): the checked
//! parameters of a building's storeys ([`BoucWen`]), ż ([`z_rate`]) and one storey of the
//! assembled system ([`Storey`]: V, the pseudo-force ΔV, ż, the energy excess). The law, its
//! energy split and their sources are set out in [`crate::model::hysteresis`], which assembles
//! the storeys into the modal system.

/// The Bouc–Wen parameters of one building's storeys, checked (`hysteresis = { model =
/// "bouc-wen", … }` of a `shear-building`).
#[derive(Debug, Clone, PartialEq)]
pub struct BoucWen {
    /// Yield drift d_y of every storey, lowest first, m (> 0).
    pub yield_drifts: Vec<f64>,
    /// Post-yield stiffness ratio α, in [0, 1).
    pub post_yield_ratio: f64,
    /// Exponent n ≥ 1 (sharpness of the transition).
    pub exponent: f64,
    /// β (shape of unloading).
    pub beta: f64,
    /// γ.
    pub gamma: f64,
}

/// Default β (with γ = 0.5: β + γ = 1, so that the backbone's yield force is k d_y).
pub const DEFAULT_BETA: f64 = 0.5;
/// Default γ.
pub const DEFAULT_GAMMA: f64 = 0.5;
/// Default exponent n.
pub const DEFAULT_EXPONENT: f64 = 2.0;

/// `|z|ⁿ` with the common exponents without `powf`.
#[inline(always)]
fn abs_pow(z: f64, n: f64) -> f64 {
    let a = z.abs();
    if n == 2.0 {
        a * a
    } else if n == 1.0 {
        a
    } else {
        a.powf(n)
    }
}

/// ż of the Bouc–Wen law (A = 1) for drift rate `dd` (m/s), state `z`, yield drift `dy` (m).
#[inline(always)]
pub fn z_rate(dd: f64, z: f64, dy: f64, n: f64, beta: f64, gamma: f64) -> f64 {
    let s = if dd * z > 0.0 {
        1.0
    } else if dd * z < 0.0 {
        -1.0
    } else {
        0.0
    };
    dd / dy * (1.0 - abs_pow(z, n) * (beta * s + gamma))
}

/// One yielding storey of the assembled system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Storey {
    /// Structure (0 or 1).
    pub structure: usize,
    /// Storey index in its structure, 0 = the lowest (floor index of its top).
    pub storey: usize,
    /// Initial stiffness k, N/m.
    pub k: f64,
    /// α.
    pub alpha: f64,
    /// Yield drift, m.
    pub dy: f64,
    /// n.
    pub n: f64,
    /// β.
    pub beta: f64,
    /// γ.
    pub gamma: f64,
}

impl Storey {
    /// `(1 − α) k`, N/m.
    #[inline(always)]
    pub fn kh(&self) -> f64 {
        (1.0 - self.alpha) * self.k
    }

    /// The Bouc–Wen storey force `V = α k d + (1 − α) k d_y z`, N.
    #[inline(always)]
    pub fn force(&self, d: f64, z: f64) -> f64 {
        self.alpha * self.k * d + self.kh() * self.dy * z
    }

    /// The storey force's rate `dV/dt = α k ḋ + (1 − α) k d_y ż` for drift rate `dd` (m/s),
    /// N/s (continuous in time: ż is 0 from both sides where ḋ = 0, and |z|ⁿ is 0 where z = 0).
    #[inline(always)]
    pub fn force_rate(&self, dd: f64, z: f64) -> f64 {
        self.alpha * self.k * dd + self.kh() * self.dy * self.z_rate(dd, z)
    }

    /// The pseudo-force `ΔV = V − k d = (1 − α) k (d_y z − d)`, N.
    #[inline(always)]
    pub fn pseudo_force(&self, d: f64, z: f64) -> f64 {
        self.kh() * (self.dy * z - d)
    }

    /// ż for drift rate `dd`.
    #[inline(always)]
    pub fn z_rate(&self, dd: f64, z: f64) -> f64 {
        z_rate(dd, z, self.dy, self.n, self.beta, self.gamma)
    }

    /// `½ (1 − α) k (d² − d_y² z²)`, J: what turns the pseudo-force's work into the dissipated
    /// energy, `E_h = W + this − this at the start`.
    #[inline(always)]
    pub fn excess(&self, d: f64, z: f64) -> f64 {
        0.5 * self.kh() * (d * d - self.dy * self.dy * z * z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// dE_h/dt = (1 − α) k d_y z (ḋ − d_y ż) = (1 − α) k d_y |z|ⁿ (β|ḋz| + γ ḋz) ≥ 0 for β ≥ |γ|.
    #[test]
    fn dissipation_rate_is_non_negative_and_matches_the_closed_form() {
        let st = Storey {
            structure: 0,
            storey: 0,
            k: 2e7,
            alpha: 0.1,
            dy: 0.01,
            n: 1.5,
            beta: 0.6,
            gamma: -0.2,
        };
        for &z in &[-1.1, -0.7, -0.1, 0.0, 0.3, 0.99] {
            for &dd in &[-0.3, -0.01, 0.0, 0.02, 0.5] {
                let zd = st.z_rate(dd, z);
                let rate = st.kh() * st.dy * z * (dd - st.dy * zd);
                let closed = st.kh()
                    * st.dy
                    * z.abs().powf(st.n)
                    * (st.beta * (dd * z).abs() + st.gamma * dd * z);
                // (round-off of ḋ − d_y ż, each of size |ḋ|)
                let scale = st.kh() * st.dy * (z * dd).abs();
                assert!((rate - closed).abs() <= 1e-12 * scale.max(1.0));
                assert!(rate >= -1e-12, "z {z} ḋ {dd}: {rate}");
            }
        }
    }
}
