//! A contact law as an OpenSees material: how exactly each law maps ([`law_mapping`]), the
//! sampled Hertz curve ([`hertz_curve`]) and the material of a resolved contact force
//! ([`contact_material`]).

use serde::Serialize;

use super::ExportError;
use crate::model::contact::{ContactForce, ContactLaw};

/// Ratio between consecutive penetrations of the sampled Hertz curve: the piecewise-linear
/// curve is then within `(3/32)(r − 1)² ≈ 2.3e-4` of `k δ^{3/2}` (relative) above
/// [`HERTZ_MIN_PENETRATION`].
pub const HERTZ_RATIO: f64 = 1.05;

/// Smallest sampled penetration of the Hertz curve, m (below it the curve is a straight line
/// from zero: forces under k·1e-12 N·m^{-3/2}).
pub const HERTZ_MIN_PENETRATION: f64 = 1e-8;

/// Largest sampled penetration of the Hertz curve, m (beyond it OpenSees extends the last
/// segment linearly; a penetration of a metre is far outside any meaningful contact).
pub const HERTZ_MAX_PENETRATION: f64 = 1.0;

/// Gap given to the OpenSees gap materials when the scenario's gap is zero, m: some releases
/// of `Hertzdamp`, `JankowskiImpact` and `ViscoelasticGap` refuse a zero gap.
pub const ZERO_GAP: f64 = 1e-12;

/// How exactly a contact law maps onto OpenSees.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mapping {
    /// The same force law (up to the sampling stated).
    Exact(&'static str),
    /// A close but different law; says what differs.
    Approximate(&'static str),
    /// No OpenSees material.
    Refused(&'static str),
}

/// How `law` maps onto the materials of OpenSees 3.7.1.
pub fn law_mapping(law: &ContactLaw) -> Mapping {
    match law {
        ContactLaw::Hertz { .. } => Mapping::Exact(
            "ElasticMultiLinear: zero up to the gap, then k_h δ^1.5 sampled at penetrations \
             growing by 5 % from 1e-8 m to 1 m (within 2.3e-4 of the curve)",
        ),
        ContactLaw::Linear { .. } => {
            Mapping::Exact("ElasticPPGap: k (δ) beyond the gap, a yield force never reached")
        }
        ContactLaw::Jankowski { .. } => Mapping::Exact(
            "JankowskiImpact: k_h δ^1.5 + 2ξ√(k_h √δ m*) δ̇ while approaching, with the \
             program's ξ(e) and effective mass m*",
        ),
        ContactLaw::Kelvin { .. } => Mapping::Approximate(
            "ViscoelasticGap: k δ + c δ̇ with the program's c, but not clamped at zero: near \
             the end of each contact the dashpot pulls, which the program's no-tension law \
             does not (the rebound is slower)",
        ),
        ContactLaw::HertzDamp { .. } => Mapping::Approximate(
            "Hertzdamp: k_h δ^1.5 (1 + χ δ̇/v₀) with the program's χ, but v₀ is δ̇ at the \
             first step end inside the contact (the program: at the located onset) and the \
             force is not clamped at zero",
        ),
        ContactLaw::Stereomechanical { .. } => Mapping::Refused(
            "an instantaneous impact (a jump of the velocities) has no OpenSees material; \
             use kelvin or jankowski with the same restitution",
        ),
    }
}

/// A contact material of OpenSees (compression = the structures approaching; strains and
/// gaps negative).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type")]
pub enum ContactMaterial {
    /// Piecewise-linear elastic curve.
    ElasticMultiLinear {
        /// Strains (m), ascending.
        strain: Vec<f64>,
        /// Stresses (N).
        stress: Vec<f64>,
    },
    /// Elastic–perfectly-plastic gap.
    ElasticPPGap {
        /// k, N/m.
        k: f64,
        /// Yield force (negative, never reached), N.
        fy: f64,
        /// Gap (negative), m.
        gap: f64,
    },
    /// Linear spring and dashpot in contact.
    ViscoelasticGap {
        /// k, N/m.
        k: f64,
        /// c, N·s/m.
        c: f64,
        /// Gap (negative), m.
        gap: f64,
    },
    /// Hertz with nonlinear damping.
    Hertzdamp {
        /// k_h, N/m^1.5.
        k: f64,
        /// χ.
        xi_norm: f64,
        /// Gap (negative), m.
        gap: f64,
    },
    /// Jankowski's nonlinear viscoelastic impact.
    JankowskiImpact {
        /// k_h, N/m^1.5.
        k: f64,
        /// ξ.
        xi: f64,
        /// m*, kg.
        m_eff: f64,
        /// Gap (negative), m.
        gap: f64,
    },
}

/// The Hertz law `F = k δ^{3/2}` beyond `gap` as an `ElasticMultiLinear` curve in OpenSees'
/// signs (strain = −gap − δ, stress = −F, ascending strain): penetrations 0,
/// [`HERTZ_MIN_PENETRATION`] · [`HERTZ_RATIO`]ⁿ up to [`HERTZ_MAX_PENETRATION`], zero force from
/// the gap to a tensile strain of 1 m.
pub fn hertz_curve(k: f64, gap: f64) -> (Vec<f64>, Vec<f64>) {
    let mut deltas = vec![0.0];
    let mut d = HERTZ_MIN_PENETRATION;
    while d < HERTZ_MAX_PENETRATION {
        deltas.push(d);
        d *= HERTZ_RATIO;
    }
    deltas.push(HERTZ_MAX_PENETRATION);
    let mut strain: Vec<f64> = deltas.iter().rev().map(|d| -gap - d).collect();
    let mut stress: Vec<f64> = deltas.iter().rev().map(|d| -k * d.powf(1.5)).collect();
    strain.push(1.0_f64.max(10.0 * gap));
    stress.push(0.0);
    (strain, stress)
}

/// The OpenSees material of contact law `law`, resolved as `force` for a level of gap `gap`
/// (m) and effective mass `m_star` (kg).
pub fn contact_material(
    law: &ContactLaw,
    force: &ContactForce,
    gap: f64,
    m_star: f64,
) -> Result<ContactMaterial, ExportError> {
    let neg_gap = -(if gap > 0.0 { gap } else { ZERO_GAP });
    Ok(match *force {
        ContactForce::Hertz { k } => {
            let (strain, stress) = hertz_curve(k, gap);
            ContactMaterial::ElasticMultiLinear { strain, stress }
        }
        ContactForce::Linear { k } => ContactMaterial::ElasticPPGap {
            k,
            fy: -k * 1e6,
            gap: -gap,
        },
        ContactForce::Kelvin { k, c } => ContactMaterial::ViscoelasticGap { k, c, gap: neg_gap },
        ContactForce::HertzDamp { k, chi } => ContactMaterial::Hertzdamp {
            k,
            xi_norm: chi,
            gap: neg_gap,
        },
        ContactForce::Jankowski { k, .. } => match *law {
            // c₀ = 2ξ√(m* k): the material takes ξ and m* separately
            ContactLaw::Jankowski { restitution, .. } => ContactMaterial::JankowskiImpact {
                k,
                xi: jankowski_xi(restitution),
                m_eff: m_star,
                gap: neg_gap,
            },
            _ => {
                return Err(ExportError::Law {
                    law: law.name(),
                    reason: "its resolved force does not match the law",
                });
            }
        },
        ContactForce::Impulsive { .. } => {
            let reason = match law_mapping(law) {
                Mapping::Refused(r) => r,
                _ => "no OpenSees material",
            };
            return Err(ExportError::Law {
                law: law.name(),
                reason,
            });
        }
    })
}

/// Jankowski's ξ for restitution e (the program's formula, [`ContactLaw::resolve`]).
fn jankowski_xi(e: f64) -> f64 {
    use std::f64::consts::PI;
    9.0 * 5f64.sqrt() * (1.0 - e * e) / (2.0 * e * (e * (9.0 * PI - 16.0) + 16.0))
}

/// How `law` maps onto OpenSees, as a script's header says it.
pub(super) fn mapping_text(law: &ContactLaw) -> String {
    match law_mapping(law) {
        Mapping::Exact(t) => format!("exact — {t}"),
        Mapping::Approximate(t) => format!("approximate — {t}"),
        Mapping::Refused(t) => t.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sampled Hertz curve is within 3e-4 of k δ^1.5 between its points (chord error of
    /// δ^1.5 over a ratio r: (3/32)(r − 1)² = 2.3e-4 at r = 1.05), zero up to the gap, and
    /// ascending in strain.
    #[test]
    fn hertz_curve_is_close_to_the_law() {
        let (k, gap) = (2.808e10, 0.0127);
        let (e, s) = hertz_curve(k, gap);
        assert!(e.windows(2).all(|w| w[1] > w[0]));
        let f = |x: f64| {
            let i = e.partition_point(|&v| v <= x).clamp(1, e.len() - 1);
            s[i - 1] + (s[i] - s[i - 1]) * (x - e[i - 1]) / (e[i] - e[i - 1])
        };
        assert_eq!(f(-gap + 1e-6), 0.0);
        assert_eq!(f(0.5), 0.0);
        let mut worst: f64 = 0.0;
        let mut d: f64 = 1e-6;
        while d < 0.9 {
            let exact = k * d.powf(1.5);
            worst = worst.max((-f(-gap - d) - exact).abs() / exact);
            d *= 1.0137;
        }
        assert!(worst < 3e-4, "{worst}");
    }
}
