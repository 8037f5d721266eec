//! Contact laws between the two structures (docs/model.md §2.7).
//!
//! Penetration at a contact level is `δ = w₁(h) − w₂(h) − d`; with δ ≤ 0 there is no force, and no
//! law ever pulls (the force is clamped at zero while the structures separate). The force `F ≥ 0`
//! pushes structure 1 to the left and structure 2 to the right (docs/model.md §2.4).

use std::f64::consts::PI;

/// How the damped Hertz law's hysteresis factor χ depends on the coefficient of restitution e.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HertzDampModel {
    /// Lankarani & Nikravesh (1990): χ = 3(1 − e²)/4. Derived for e near 1.
    LankaraniNikravesh,
    /// Hunt & Crossley (1975): χ = 3(1 − e)/2.
    HuntCrossley,
    /// Ye, Li & Zhu (2009): χ = 8(1 − e)/(5e).
    YeLiZhu,
}

impl HertzDampModel {
    /// χ for restitution e.
    pub fn chi(self, e: f64) -> f64 {
        match self {
            HertzDampModel::LankaraniNikravesh => 3.0 * (1.0 - e * e) / 4.0,
            HertzDampModel::HuntCrossley => 3.0 * (1.0 - e) / 2.0,
            HertzDampModel::YeLiZhu => 8.0 * (1.0 - e) / (5.0 * e),
        }
    }

    /// Name as written in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            HertzDampModel::LankaraniNikravesh => "lankarani-nikravesh",
            HertzDampModel::HuntCrossley => "hunt-crossley",
            HertzDampModel::YeLiZhu => "ye-li-zhu",
        }
    }
}

/// A contact law with its user-facing parameters. Damped laws are turned into forces for a
/// given effective mass m* by [`ContactLaw::resolve`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactLaw {
    /// Linear spring: `F = k δ`; k in N/m.
    Linear {
        /// k, N/m.
        stiffness: f64,
    },
    /// Kelvin–Voigt: `F = max(0, k δ + c δ̇)`, `c = 2ξ√(k m*)`. Anagnostopoulos (1988) takes
    /// `ξ = −ln e/√(π² + ln² e)`, which assumes the dashpot may pull at the end of the contact;
    /// with the no-tension clamp the bodies separate earlier (where F = 0) and rebound faster
    /// (target 0.3 gives 0.397). Here ξ is instead chosen so that the *clamped* impact rebounds at
    /// exactly e: see [`kelvin_damping_ratio`].
    Kelvin {
        /// k, N/m.
        stiffness: f64,
        /// Target coefficient of restitution e ∈ (0, 1].
        restitution: f64,
    },
    /// Hertz: `F = k_h δ^{3/2}` (paper eq. 5); k_h in N/m^{3/2}.
    Hertz {
        /// k_h, N/m^{3/2}.
        stiffness: f64,
    },
    /// Damped Hertz: `F = max(0, k_h δ^{3/2} (1 + χ δ̇/v₀))`, v₀ = δ̇ at the onset of the
    /// contact episode, χ from e by the chosen model.
    HertzDamp {
        /// k_h, N/m^{3/2}.
        stiffness: f64,
        /// Target coefficient of restitution e ∈ (0, 1].
        restitution: f64,
        /// How χ follows from e.
        model: HertzDampModel,
    },
    /// Jankowski (2005) nonlinear viscoelastic: `F = k_h δ^{3/2} + c δ̇` while approaching
    /// (δ̇ > 0), `F = k_h δ^{3/2}` while separating; `c = 2ξ√(m* k_h √δ)`,
    /// `ξ = 9√5 (1 − e²) / (2e (e(9π − 16) + 16))`.
    Jankowski {
        /// k_h, N/m^{3/2}.
        stiffness: f64,
        /// Target coefficient of restitution e ∈ (0, 1].
        restitution: f64,
    },
    /// Stereomechanical (instantaneous) impact: when the gap closes while approaching, the
    /// relative velocity at the contact point is reversed and scaled by e in one instant, by an
    /// impulse `P = (1 + e) m* δ̇` applied as jumps of the modal velocities `Δη̇ = c P`
    /// (c = s_i φ(h)); the kinetic energy `½(1 − e²) m* δ̇²` is lost. No contact force, stiffness
    /// or duration.
    Stereomechanical {
        /// Coefficient of restitution e ∈ [0, 1].
        restitution: f64,
    },
}

impl ContactLaw {
    /// Name as written in scenario files.
    pub fn name(&self) -> &'static str {
        match self {
            ContactLaw::Linear { .. } => "linear",
            ContactLaw::Kelvin { .. } => "kelvin",
            ContactLaw::Hertz { .. } => "hertz",
            ContactLaw::HertzDamp { .. } => "hertzdamp",
            ContactLaw::Jankowski { .. } => "jankowski",
            ContactLaw::Stereomechanical { .. } => "stereomechanical",
        }
    }

    /// The force law for a contact point whose two sides have effective mass `m_star` (kg):
    /// `1/m* = Σ_n φ₁ₙ(h)² + Σ_n φ₂ₙ(h)²` (see [`crate::model::system`]).
    pub fn resolve(&self, m_star: f64) -> ContactForce {
        match *self {
            ContactLaw::Linear { stiffness } => ContactForce::Linear { k: stiffness },
            ContactLaw::Kelvin {
                stiffness,
                restitution,
            } => ContactForce::Kelvin {
                k: stiffness,
                c: 2.0 * kelvin_damping_ratio(restitution) * (stiffness * m_star).sqrt(),
            },
            ContactLaw::Hertz { stiffness } => ContactForce::Hertz { k: stiffness },
            ContactLaw::HertzDamp {
                stiffness,
                restitution,
                model,
            } => ContactForce::HertzDamp {
                k: stiffness,
                chi: model.chi(restitution),
            },
            ContactLaw::Jankowski {
                stiffness,
                restitution,
            } => {
                let e = restitution;
                let xi =
                    9.0 * 5f64.sqrt() * (1.0 - e * e) / (2.0 * e * (e * (9.0 * PI - 16.0) + 16.0));
                ContactForce::Jankowski {
                    k: stiffness,
                    c0: 2.0 * xi * (m_star * stiffness).sqrt(),
                }
            }
            ContactLaw::Stereomechanical { restitution } => {
                ContactForce::Impulsive { e: restitution }
            }
        }
    }
}

/// Anagnostopoulos's Kelvin damping ratio `ξ = −ln e/√(π² + ln² e)` (exact when the dashpot
/// may pull).
pub fn anagnostopoulos_damping_ratio(e: f64) -> f64 {
    let ln_e = e.ln();
    -ln_e / (PI * PI + ln_e * ln_e).sqrt()
}

/// Restitution of a linear spring–dashpot impact with damping ratio ξ when the force may not
/// pull: δ(t) solves `δ̈ + 2ξωδ̇ + ω²δ = 0` from δ = 0, δ̇ = v; the bodies separate at the first
/// t* > 0 where `F ∝ −δ̈ = 0`, and `e = −δ̇(t*)/v`. With a = ξω, b = ω√(1−ξ²) (ω = 1 without
/// loss of generality): `b t* = atan2(2ab, a² − b²)` and `e = −e^{−at*}(cos bt* − (a/b) sin bt*)`;
/// overdamped, with r₁,₂ = −a ± s, s = √(ξ²−1): `t* = ln(r₂²/r₁²)/(2s)`,
/// `e = −(r₁e^{r₁t*} − r₂e^{r₂t*})/(2s)`. e(ξ) falls from 1 at ξ = 0 through e⁻² at ξ = 1.
pub fn clamped_kelvin_restitution(xi: f64) -> f64 {
    if xi <= 0.0 {
        return 1.0;
    }
    let xi = if (xi - 1.0).abs() < 1e-7 {
        1.0 - 1e-7
    } else {
        xi
    };
    if xi < 1.0 {
        let (a, b) = (xi, (1.0 - xi * xi).sqrt());
        let bt = (2.0 * a * b).atan2(a * a - b * b);
        let t = bt / b;
        -(-a * t).exp() * (bt.cos() - a / b * bt.sin())
    } else {
        let s = (xi * xi - 1.0).sqrt();
        let (r1, r2) = (-xi + s, -xi - s);
        let t = (r2 * r2 / (r1 * r1)).ln() / (2.0 * s);
        -(r1 * (r1 * t).exp() - r2 * (r2 * t).exp()) / (2.0 * s)
    }
}

/// The damping ratio ξ for which the clamped Kelvin impact rebounds at `e` ∈ (0, 1]: the
/// inverse of [`clamped_kelvin_restitution`] (monotone), by bisection to 1e-14.
pub fn kelvin_damping_ratio(e: f64) -> f64 {
    if e >= 1.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    while clamped_kelvin_restitution(hi) > e && hi < 1e6 {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if clamped_kelvin_restitution(mid) > e {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-14 * hi {
            break;
        }
    }
    0.5 * (lo + hi)
}

/// A contact law ready to evaluate: parameters that depend on the effective mass are resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactForce {
    /// `F = k δ`.
    Linear {
        /// N/m.
        k: f64,
    },
    /// `F = max(0, k δ + c δ̇)`.
    Kelvin {
        /// N/m.
        k: f64,
        /// N·s/m.
        c: f64,
    },
    /// `F = k δ^{3/2}`.
    Hertz {
        /// N/m^{3/2}.
        k: f64,
    },
    /// `F = max(0, k δ^{3/2}(1 + χ δ̇/v₀))`.
    HertzDamp {
        /// N/m^{3/2}.
        k: f64,
        /// Dimensionless hysteresis factor χ.
        chi: f64,
    },
    /// `F = k δ^{3/2} + c₀ δ^{1/4} δ̇` for δ̇ > 0, else `k δ^{3/2}`.
    Jankowski {
        /// N/m^{3/2}.
        k: f64,
        /// `2ξ√(m* k)`, N·s/m^{5/4}.
        c0: f64,
    },
    /// Instantaneous impact with restitution e: no force, a velocity jump (see
    /// [`ContactLaw::Stereomechanical`]).
    Impulsive {
        /// Coefficient of restitution.
        e: f64,
    },
}

impl ContactForce {
    /// The restitution of an impulsive law, `None` for force laws.
    #[inline]
    pub fn impulsive(&self) -> Option<f64> {
        match *self {
            ContactForce::Impulsive { e } => Some(e),
            _ => None,
        }
    }

    /// Whether the force depends on the episode's approach speed v₀ (the damped Hertz law), which
    /// a state taken on its own (δ, δ̇) does not carry.
    #[inline]
    pub fn needs_approach_speed(&self) -> bool {
        matches!(self, ContactForce::HertzDamp { .. })
    }

    /// Whether the force depends on the penetration rate δ̇ (the damped laws): its peak over an
    /// impact then comes before the largest penetration, not with it.
    #[inline]
    pub fn rate_dependent(&self) -> bool {
        matches!(
            self,
            ContactForce::Kelvin { .. }
                | ContactForce::HertzDamp { .. }
                | ContactForce::Jankowski { .. }
        )
    }

    /// Contact force (N, ≥ 0) at penetration δ (m), penetration rate δ̇ (m/s) and approach speed
    /// at the onset of the episode v₀ (m/s; only the damped Hertz law uses it).
    #[inline(always)]
    pub fn force(&self, delta: f64, delta_dot: f64, v0: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        match *self {
            ContactForce::Linear { k } => k * delta,
            ContactForce::Kelvin { k, c } => (k * delta + c * delta_dot).max(0.0),
            ContactForce::Hertz { k } => k * delta * delta.sqrt(),
            ContactForce::HertzDamp { k, chi } => {
                let damping = if v0 > 0.0 { chi * delta_dot / v0 } else { 0.0 };
                (k * delta * delta.sqrt() * (1.0 + damping)).max(0.0)
            }
            ContactForce::Jankowski { k, c0 } => {
                let elastic = k * delta * delta.sqrt();
                if delta_dot > 0.0 {
                    elastic + c0 * delta.sqrt().sqrt() * delta_dot
                } else {
                    elastic
                }
            }
            ContactForce::Impulsive { .. } => 0.0,
        }
    }

    /// Energy stored in the elastic part of the law at penetration δ, J:
    /// `½kδ²` (linear, Kelvin) or `(2/5)k δ^{5/2}` (Hertz family).
    #[inline]
    pub fn potential(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        match *self {
            ContactForce::Linear { k } | ContactForce::Kelvin { k, .. } => 0.5 * k * delta * delta,
            ContactForce::Hertz { k }
            | ContactForce::HertzDamp { k, .. }
            | ContactForce::Jankowski { k, .. } => 0.4 * k * delta * delta * delta.sqrt(),
            ContactForce::Impulsive { .. } => 0.0,
        }
    }

    /// Tangent stiffness dF/dδ of the elastic part at δ, N/m: used to warn when the contact
    /// makes an explicit step unstable.
    #[inline]
    pub fn tangent_stiffness(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        match *self {
            ContactForce::Linear { k } | ContactForce::Kelvin { k, .. } => k,
            ContactForce::Hertz { k }
            | ContactForce::HertzDamp { k, .. }
            | ContactForce::Jankowski { k, .. } => 1.5 * k * delta.sqrt(),
            ContactForce::Impulsive { .. } => 0.0,
        }
    }

    /// The force (N) and its exact partial derivatives ∂F/∂δ (N/m) and ∂F/∂δ̇ (N·s/m) at
    /// penetration δ (m), rate δ̇ (m/s) and onset speed v₀ (m/s), clamp included (where the
    /// no-tension clamp acts, or δ ≤ 0, all three are 0). For a Newton iteration on the law
    /// (`exact-modal`'s collocation).
    #[inline]
    pub fn force_jacobian(&self, delta: f64, delta_dot: f64, v0: f64) -> (f64, f64, f64) {
        if delta <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        match *self {
            ContactForce::Linear { k } => (k * delta, k, 0.0),
            ContactForce::Kelvin { k, c } => {
                let f = k * delta + c * delta_dot;
                if f > 0.0 { (f, k, c) } else { (0.0, 0.0, 0.0) }
            }
            ContactForce::Hertz { k } => {
                let r = delta.sqrt();
                (k * delta * r, 1.5 * k * r, 0.0)
            }
            ContactForce::HertzDamp { k, chi } => {
                let r = delta.sqrt();
                let rate = if v0 > 0.0 { chi / v0 } else { 0.0 };
                let factor = 1.0 + rate * delta_dot;
                if factor > 0.0 {
                    (
                        k * delta * r * factor,
                        1.5 * k * r * factor,
                        k * delta * r * rate,
                    )
                } else {
                    (0.0, 0.0, 0.0)
                }
            }
            ContactForce::Jankowski { k, c0 } => {
                let r = delta.sqrt();
                if delta_dot > 0.0 {
                    let q = r.sqrt();
                    (
                        k * delta * r + c0 * q * delta_dot,
                        1.5 * k * r + 0.25 * c0 * delta_dot / (q * q * q),
                        c0 * q,
                    )
                } else {
                    (k * delta * r, 1.5 * k * r, 0.0)
                }
            }
            ContactForce::Impulsive { .. } => (0.0, 0.0, 0.0),
        }
    }

    /// Where, inside contact (δ > 0), the law itself has a kink: a function of the state whose
    /// sign change marks it, or `None` for the laws that are smooth there (linear, Hertz). The
    /// no-tension clamp of Kelvin (`kδ + cδ̇`, N) and of the damped Hertz law (`1 + χδ̇/v₀`),
    /// and the switch of Jankowski's damping with the sign of δ̇ (m/s). An integrator that
    /// needs a smooth force over a step ends the step there.
    #[inline]
    pub fn kink(&self, delta: f64, delta_dot: f64, v0: f64) -> Option<f64> {
        match *self {
            ContactForce::Kelvin { k, c } => Some(k * delta + c * delta_dot),
            ContactForce::HertzDamp { chi, .. } if v0 > 0.0 => Some(1.0 + chi * delta_dot / v0),
            ContactForce::Jankowski { .. } => Some(delta_dot),
            _ => None,
        }
    }

    /// Tangent damping ∂F/∂δ̇ at penetration δ (m), rate δ̇ (m/s) and onset speed v₀ (m/s), N·s/m:
    /// `c` (Kelvin), `χ k δ^{3/2}/v₀` (damped Hertz), `c₀ δ^{1/4}` while approaching
    /// (Jankowski), 0 for the elastic and impulsive laws (and where the no-tension clamp acts,
    /// the clamp itself being ignored). With [`ContactForce::tangent_stiffness`] it linearises
    /// the law, e.g. to check an explicit step's stability in contact.
    #[inline]
    pub fn tangent_damping(&self, delta: f64, delta_dot: f64, v0: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        match *self {
            ContactForce::Kelvin { c, .. } => c,
            ContactForce::HertzDamp { k, chi } if v0 > 0.0 => chi * k * delta * delta.sqrt() / v0,
            ContactForce::Jankowski { c0, .. } if delta_dot > 0.0 => c0 * delta.sqrt().sqrt(),
            _ => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clamped Kelvin: e(0) = 1, e(1) = e⁻² (both branches meet), monotone, and Anagnostopoulos's
    /// ξ gives a higher rebound than its target once the clamp acts. The inverse round-trips.
    #[test]
    fn clamped_kelvin_restitution_curve() {
        assert_eq!(clamped_kelvin_restitution(0.0), 1.0);
        let e1 = (-2.0f64).exp();
        assert!((clamped_kelvin_restitution(1.0 - 1e-6) - e1).abs() < 1e-5);
        assert!((clamped_kelvin_restitution(1.0 + 1e-6) - e1).abs() < 1e-5);
        let mut prev = 1.0;
        for i in 1..400 {
            let e = clamped_kelvin_restitution(i as f64 * 0.01);
            assert!(e < prev, "monotone at ξ = {}", i as f64 * 0.01);
            prev = e;
        }
        for e in [0.05, 0.3, 0.5, 0.9, 0.99] {
            assert!((clamped_kelvin_restitution(kelvin_damping_ratio(e)) - e).abs() < 1e-12);
            assert!(clamped_kelvin_restitution(anagnostopoulos_damping_ratio(e)) > e);
        }
    }

    #[test]
    fn no_force_without_penetration_and_never_tension() {
        let laws = [
            ContactLaw::Linear { stiffness: 1e9 },
            ContactLaw::Kelvin {
                stiffness: 1e9,
                restitution: 0.5,
            },
            ContactLaw::Hertz { stiffness: 1e10 },
            ContactLaw::HertzDamp {
                stiffness: 1e10,
                restitution: 0.5,
                model: HertzDampModel::HuntCrossley,
            },
            ContactLaw::Jankowski {
                stiffness: 1e10,
                restitution: 0.5,
            },
        ];
        for law in laws {
            let f = law.resolve(1e5);
            assert_eq!(f.force(-1e-3, 1.0, 1.0), 0.0);
            assert_eq!(f.force(0.0, 1.0, 1.0), 0.0);
            // separating fast at a small penetration: damping would pull, the clamp forbids it
            assert!(f.force(1e-6, -100.0, 0.1) >= 0.0);
        }
    }

    #[test]
    fn hertz_force_and_potential() {
        let f = ContactLaw::Hertz {
            stiffness: 2.808e10,
        }
        .resolve(1.0);
        let d = 0.004;
        assert!((f.force(d, 0.0, 0.0) - 2.808e10 * d.powf(1.5)).abs() < 1e-3);
        // dU/dδ = F
        let e = 1e-9;
        let du = (f.potential(d + e) - f.potential(d - e)) / (2.0 * e);
        assert!((du - f.force(d, 0.0, 0.0)).abs() < 1e-6 * f.force(d, 0.0, 0.0));
    }

    /// The three χ formulas as printed in the literature.
    #[test]
    fn hysteresis_factors() {
        let e = 0.6;
        assert!((HertzDampModel::LankaraniNikravesh.chi(e) - 0.48).abs() < 1e-15);
        assert!((HertzDampModel::HuntCrossley.chi(e) - 0.6).abs() < 1e-15);
        assert!((HertzDampModel::YeLiZhu.chi(e) - 8.0 * 0.4 / 3.0).abs() < 1e-15);
    }

    /// Kelvin damping ratio: e = 1 gives no damping; ξ(e) from the closed form.
    #[test]
    fn kelvin_damping() {
        let f = ContactLaw::Kelvin {
            stiffness: 1e8,
            restitution: 1.0,
        }
        .resolve(2e5);
        assert_eq!(f, ContactForce::Kelvin { k: 1e8, c: 0.0 });
        let e: f64 = 0.5;
        let xi = kelvin_damping_ratio(e);
        if let ContactForce::Kelvin { c, .. } = (ContactLaw::Kelvin {
            stiffness: 1e8,
            restitution: e,
        })
        .resolve(2e5)
        {
            assert!((c - 2.0 * xi * (1e8f64 * 2e5).sqrt()).abs() < 1e-6 * c);
        } else {
            panic!("kelvin resolves to kelvin");
        }
    }

    /// `force_jacobian` is the law's force and its exact partial derivatives: against central
    /// differences (step 1e-7 of the value; the laws are smooth away from δ = 0, the clamp and
    /// Jankowski's δ̇ = 0, where no point is taken), every law, approaching and separating.
    #[test]
    fn force_jacobian_matches_finite_differences() {
        let laws = [
            ContactLaw::Linear { stiffness: 1e9 },
            ContactLaw::Kelvin {
                stiffness: 1e9,
                restitution: 0.5,
            },
            ContactLaw::Hertz { stiffness: 1e10 },
            ContactLaw::HertzDamp {
                stiffness: 1e10,
                restitution: 0.6,
                model: HertzDampModel::HuntCrossley,
            },
            ContactLaw::Jankowski {
                stiffness: 1e10,
                restitution: 0.6,
            },
        ];
        for law in laws {
            let f = law.resolve(1e5);
            for (d, dd) in [(2e-3, 0.4), (5e-4, -0.3), (1e-3, 0.0)] {
                let (force, kd, kv) = f.force_jacobian(d, dd, 0.8);
                // (the same formula, the products grouped otherwise: to an ulp or two)
                let direct = f.force(d, dd, 0.8);
                assert!((force - direct).abs() <= 1e-14 * direct.abs(), "{law:?}");
                let (ed, ev) = (1e-7 * d, 1e-7 * dd.abs().max(1e-3));
                let fd = (f.force(d + ed, dd, 0.8) - f.force(d - ed, dd, 0.8)) / (2.0 * ed);
                let fv = (f.force(d, dd + ev, 0.8) - f.force(d, dd - ev, 0.8)) / (2.0 * ev);
                // (central differences: error ~1e-12 of the force's scale here)
                let scale = force.abs().max(1.0);
                assert!(
                    (kd - fd).abs() <= 1e-6 * kd.abs().max(scale / d),
                    "{law:?} ∂δ {kd} {fd}"
                );
                if dd != 0.0 {
                    assert!(
                        (kv - fv).abs() <= 1e-6 * kv.abs().max(scale),
                        "{law:?} ∂δ̇ {kv} {fv}"
                    );
                }
            }
            assert_eq!(f.force_jacobian(-1e-3, 1.0, 1.0), (0.0, 0.0, 0.0));
            // clamped (separating fast at a small penetration): nothing pulls, nothing varies
            let (c, a, b) = f.force_jacobian(1e-6, -100.0, 0.1);
            if c == 0.0 {
                assert_eq!((a, b), (0.0, 0.0));
            }
        }
    }
}
