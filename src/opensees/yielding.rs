//! Yielding storeys in OpenSees (issue 24): the program's Bouc–Wen law (docs/model.md §2.6b) as
//! OpenSees' `BoucWen` uniaxial material in a storey link.

use serde::Serialize;

use crate::model::bouc_wen::BoucWen;

/// OpenSees' `uniaxialMaterial BoucWen tag alpha ko n gamma beta Ao deltaA deltaNu deltaEta tol
/// maxIter` for one yielding storey (OpenSees 3.7.1, `BoucWenMaterial`, Haukaas; Baber & Noori
/// 1985 with degradation): stress `α k₀ ε + (1 − α) k₀ Z` and `dZ/dε = A − |Z|ⁿ ν (γ + β sign(ε̇
/// Z))` over η, with `A = A₀ − δ_A e`, `ν = 1 + δ_ν e`, `η = 1 + δ_η e` (e the hysteretic
/// energy). Its Z is in units of ε (m here), the program's z is dimensionless: see
/// [`bouc_wen_material`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoucWenMaterial {
    /// α, post-yield stiffness ratio (the program's α).
    pub alpha: f64,
    /// k₀, initial stiffness, N/m (the storey's k).
    pub ko: f64,
    /// n (the program's n).
    pub n: f64,
    /// OpenSees' γ, m^−n: the program's γ / d_yⁿ.
    pub gamma: f64,
    /// OpenSees' β, m^−n: the program's β / d_yⁿ.
    pub beta: f64,
    /// A₀ = 1.
    pub a0: f64,
    /// δ_A = 0 (no stiffness degradation).
    pub delta_a: f64,
    /// δ_ν = 0 (no strength degradation).
    pub delta_nu: f64,
    /// δ_η = 0 (no degradation).
    pub delta_eta: f64,
    /// Tolerance of OpenSees' Newton iteration on Z, m (1e-10 d_y).
    pub tolerance: f64,
    /// Its iterations at most.
    pub max_iterations: u32,
    /// The program's yield drift d_y, m (for the record: Z = d_y z).
    pub yield_drift: f64,
}

/// What the program's Bouc–Wen parameters are in OpenSees' `BoucWen` material (stated in every
/// exported script and in the crosscheck's notes).
pub const BOUC_WEN_MAPPING: &str = "storeys as OpenSees' BoucWen material: the same law, \
     V = α k d + (1 − α) k Z with OpenSees' Z = d_y z in metres (the program's z is \
     dimensionless), so A₀ = 1, n and α as given, β and γ divided by d_yⁿ (OpenSees' β, γ are in \
     m^−n), no degradation (δ_A = δ_ν = δ_η = 0); OpenSees integrates Z over each step by \
     backward Euler (first order in the drift increment), the program to its tolerance";

/// The `BoucWen` material of a storey of initial stiffness `k` (N/m) and yield drift `dy` (m)
/// with the law `bw` (docs/model.md §2.6b): the same ODE. With the program's
/// `ż = (ḋ/d_y)[1 − |z|ⁿ(β sign(ḋz) + γ)]` and OpenSees' `Ż = ḋ[A₀ − |Z|ⁿ(γ' + β' sign(ḋZ))]`,
/// Z = d_y z gives `A₀ = 1`, `β' = β/d_yⁿ`, `γ' = γ/d_yⁿ`, and the force `α k d + (1 − α) k d_y
/// z = α k d + (1 − α) k Z` is OpenSees' stress with `k₀ = k`.
pub fn bouc_wen_material(k: f64, dy: f64, bw: &BoucWen) -> BoucWenMaterial {
    let scale = dy.powf(bw.exponent);
    BoucWenMaterial {
        alpha: bw.post_yield_ratio,
        ko: k,
        n: bw.exponent,
        gamma: bw.gamma / scale,
        beta: bw.beta / scale,
        a0: 1.0,
        delta_a: 0.0,
        delta_nu: 0.0,
        delta_eta: 0.0,
        tolerance: 1e-10 * dy,
        max_iterations: 50,
        yield_drift: dy,
    }
}
