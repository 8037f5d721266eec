//! One structure reduced to its modes: frequencies, damping ratios, participation factors and
//! mode shapes (docs/model.md §2.3–§2.6). [`Structure`] is the paper's uniform cantilever;
//! buildings with floors are in [`crate::model::building`]. Whatever the kind, the result is a
//! [`ModalModel`]: the integrators see only modes, couplings at contact heights and ground loads.

use crate::model::cantilever::Mode;
use crate::model::modal::{ModalModel, Shapes};

/// How the structure's stiffness is given (docs/model.md §2.6). All are converted to EI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stiffness {
    /// Bending stiffness EI, N·m².
    Bending(f64),
    /// First-mode period T₁, s: EI = m L⁴ (ω₁/λ₁²)².
    Period(f64),
    /// Lumped tip stiffness k = 3EI/L³, N/m.
    Tip(f64),
}

/// Damping of a structure (docs/model.md §2.5): exactly one of the two forms.
#[derive(Debug, Clone, PartialEq)]
pub enum Damping {
    /// Modal damping ratios: one value for every mode, or one per mode. No air term in the forcing.
    Modal(Vec<f64>),
    /// Physical (paper eq. 1): strain-rate coefficient `c_s/E` in s and air coefficient `c_a`
    /// in N·s/m². ζ_n = (c_s ω_n²/E + c_a/m)/(2ω_n); the air term also loads the structure with
    /// −γ_n c_a v_g.
    Physical {
        /// c_s/E, s.
        strain_rate: f64,
        /// c_a, N·s/m².
        air: f64,
    },
}

/// A checked structure of any kind (`[[structure]] kind = …` in a scenario): a closed set.
#[derive(Debug, Clone, PartialEq)]
pub enum Structure {
    /// The paper's uniform continuous cantilever (`kind = "cantilever"`, the default).
    Cantilever(Cantilever),
    /// A building with floors: a shear building or the engineer's own modes (boxed: it
    /// carries its whole modal model).
    Floors(Box<FloorStructure>),
}

/// A building with floors, checked: its input and every one of its modes.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorStructure {
    /// Name used in reports.
    pub name: String,
    /// What the scenario gave.
    pub kind: FloorKind,
    /// Every mode of the building (one per floor for a shear building, every mode given for
    /// the engineer's), checked.
    pub all_modes: ModalModel,
    /// Modes kept (1 … `all_modes.len()`).
    pub modes: usize,
    /// Yielding storeys (issue 16; a shear building only): `None` for an elastic building.
    pub hysteresis: Option<crate::model::bouc_wen::BoucWen>,
}

/// The kinds of building with floors.
#[derive(Debug, Clone, PartialEq)]
pub enum FloorKind {
    /// `kind = "shear-building"`: storey springs between lumped floor masses.
    ShearBuilding(crate::model::building::ShearBuilding),
    /// `kind = "modal"`: the engineer's periods and mode shapes.
    Modal(crate::model::building::EngineerModes),
}

impl FloorStructure {
    /// Check a building and compute its modes.
    pub fn new(
        name: String,
        kind: FloorKind,
    ) -> Result<FloorStructure, crate::model::building::BuildingError> {
        let (all_modes, modes) = match &kind {
            FloorKind::ShearBuilding(b) => {
                let n = b.floors.heights.len();
                let all = crate::model::building::ShearBuilding {
                    modes: n,
                    damping: every_mode(&b.damping, n),
                    ..b.clone()
                };
                (all.modal()?, b.modes)
            }
            FloorKind::Modal(e) => {
                let n = e.periods.len();
                let all = crate::model::building::EngineerModes {
                    modes: n,
                    damping: every_mode(&e.damping, n),
                    ..e.clone()
                };
                (all.modal()?, e.modes)
            }
        };
        if modes == 0 || modes > all_modes.len() {
            return Err(crate::model::building::BuildingError::Invalid(format!(
                "{modes} modes asked for; this building has modes 1 to {}",
                all_modes.len()
            )));
        }
        Ok(FloorStructure {
            name,
            kind,
            all_modes,
            modes,
            hysteresis: None,
        })
    }
}

/// Damping ratios given per mode kept, extended to every mode of the building (the modes not
/// kept take the last ratio; they are truncated away).
fn every_mode(
    d: &crate::model::building::FloorDamping,
    n: usize,
) -> crate::model::building::FloorDamping {
    match d {
        crate::model::building::FloorDamping::Modal(z) if z.len() > 1 && z.len() < n => {
            let mut z = z.clone();
            z.resize(n, z[z.len() - 1]);
            crate::model::building::FloorDamping::Modal(z)
        }
        other => other.clone(),
    }
}

impl Structure {
    /// Name used in reports.
    pub fn name(&self) -> &str {
        match self {
            Structure::Cantilever(c) => &c.name,
            Structure::Floors(f) => &f.name,
        }
    }

    /// Height of the top, m.
    pub fn length(&self) -> f64 {
        match self {
            Structure::Cantilever(c) => c.length,
            Structure::Floors(f) => f.all_modes.length,
        }
    }

    /// Total mass, kg.
    pub fn mass(&self) -> f64 {
        match self {
            Structure::Cantilever(c) => c.mass,
            Structure::Floors(f) => f.all_modes.mass,
        }
    }

    /// Modes kept.
    pub fn modes(&self) -> usize {
        match self {
            Structure::Cantilever(c) => c.modes,
            Structure::Floors(f) => f.modes,
        }
    }

    /// Keep `n` modes (a building keeps at most the modes it has).
    pub fn set_modes(&mut self, n: usize) {
        match self {
            Structure::Cantilever(c) => c.modes = n,
            Structure::Floors(f) => f.modes = n.clamp(1, f.all_modes.len()),
        }
    }

    /// Floor heights of a building, m (`None` for a cantilever).
    pub fn floor_heights(&self) -> Option<&[f64]> {
        match self {
            Structure::Cantilever(_) => None,
            Structure::Floors(f) => f.all_modes.floor_heights(),
        }
    }

    /// The cantilever, if this is one.
    pub fn as_cantilever(&self) -> Option<&Cantilever> {
        match self {
            Structure::Cantilever(c) => Some(c),
            Structure::Floors(_) => None,
        }
    }

    /// The Bouc–Wen storeys of a yielding shear building (`None`: elastic).
    pub fn hysteresis(&self) -> Option<&crate::model::bouc_wen::BoucWen> {
        match self {
            Structure::Cantilever(_) => None,
            Structure::Floors(f) => f.hysteresis.as_ref(),
        }
    }

    /// The initial storey stiffnesses of a shear building, N/m (lowest first).
    pub fn storey_stiffnesses(&self) -> Option<&[f64]> {
        match self {
            Structure::Floors(f) => match &f.kind {
                FloorKind::ShearBuilding(b) => Some(&b.storey_stiffnesses),
                FloorKind::Modal(_) => None,
            },
            Structure::Cantilever(_) => None,
        }
    }

    /// Reduce to the modal model (the modes kept).
    pub fn modal(&self) -> ModalModel {
        match self {
            Structure::Cantilever(c) => c.modal(),
            Structure::Floors(f) => f.all_modes.truncated(f.modes),
        }
    }
}

/// The paper's structure: a uniform cantilever of given height, mass and stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct Cantilever {
    /// Name used in reports.
    pub name: String,
    /// Height L, m (> 0).
    pub length: f64,
    /// Total mass M = m L, kg (> 0).
    pub mass: f64,
    /// Stiffness, in one of the accepted forms.
    pub stiffness: Stiffness,
    /// Number of modes kept (≥ 1).
    pub modes: usize,
    /// Damping.
    pub damping: Damping,
}

impl Cantilever {
    /// Mass per unit length m, kg/m.
    pub fn mass_per_length(&self) -> f64 {
        self.mass / self.length
    }

    /// Bending stiffness EI, N·m², whatever form the stiffness was given in (docs/model.md §2.6).
    pub fn bending_stiffness(&self) -> f64 {
        let m = self.mass_per_length();
        let l = self.length;
        match self.stiffness {
            Stiffness::Bending(ei) => ei,
            Stiffness::Period(t) => {
                let omega1 = 2.0 * std::f64::consts::PI / t;
                let l1 = Mode::new(1).lambda_squared();
                m * l.powi(4) * (omega1 / l1).powi(2)
            }
            Stiffness::Tip(k) => k * l.powi(3) / 3.0,
        }
    }

    /// Reduce to the modal model.
    pub fn modal(&self) -> ModalModel {
        let m = self.mass_per_length();
        let ei = self.bending_stiffness();
        let base = (ei / (m * self.length.powi(4))).sqrt();
        let modes = Mode::first(self.modes);
        let omega: Vec<f64> = modes.iter().map(|md| md.lambda_squared() * base).collect();
        let (zeta, air) = match &self.damping {
            Damping::Modal(z) => {
                let zeta = (0..self.modes)
                    .map(|i| if z.len() == 1 { z[0] } else { z[i] })
                    .collect();
                (zeta, 0.0)
            }
            Damping::Physical { strain_rate, air } => {
                let zeta = omega
                    .iter()
                    .map(|w| (strain_rate * w * w + air / m) / (2.0 * w))
                    .collect();
                (zeta, *air)
            }
        };
        let root_mass = self.mass.sqrt();
        // γ_n = ∫φ_n dx (m·kg^−½); Γ_n = m γ_n, the air load per unit v_g is c_a γ_n
        let gamma: Vec<f64> = modes
            .iter()
            .map(|md| md.participation() * self.length / root_mass)
            .collect();
        ModalModel {
            length: self.length,
            mass: self.mass,
            air_damping: air,
            participation: gamma.iter().map(|g| m * g).collect(),
            air_load: gamma.iter().map(|g| air * g).collect(),
            shapes: Shapes::Cantilever(modes),
            omega,
            zeta,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn beam(stiffness: Stiffness) -> Cantilever {
        Cantilever {
            name: "b".into(),
            length: 12.0,
            mass: 3.0e6,
            stiffness,
            modes: 5,
            damping: Damping::Modal(vec![0.02]),
        }
    }

    /// ω_n = λ_n² √(EI/(m L⁴)) with the tabulated λ₁ (paper eq. 12).
    #[test]
    fn frequencies_follow_beam_formula() {
        let ei = 4.0e11;
        let s = beam(Stiffness::Bending(ei));
        let mm = s.modal();
        let m = 3.0e6 / 12.0;
        let w1 = 1.875104068711961f64.powi(2) * (ei / (m * 12.0f64.powi(4))).sqrt();
        assert!((mm.omega[0] - w1).abs() < 1e-12 * w1);
        let w2 = 4.694091132974175f64.powi(2) * (ei / (m * 12.0f64.powi(4))).sqrt();
        assert!((mm.omega[1] - w2).abs() < 1e-12 * w2);
    }

    /// Given by period, the first period comes back; by tip stiffness, EI = kL³/3.
    #[test]
    fn alternative_stiffness_forms() {
        let mm = beam(Stiffness::Period(0.42)).modal();
        assert!((mm.periods()[0] - 0.42).abs() < 1e-12);
        let k = 5.0e7;
        let s = beam(Stiffness::Tip(k));
        assert!((s.bending_stiffness() - k * 12.0f64.powi(3) / 3.0).abs() < 1e-3);
    }

    /// Physical damping: ζ_n = (c_s ω²/E + c_a/m)/(2ω) (paper eq. 14).
    #[test]
    fn physical_damping_ratio() {
        let mut s = beam(Stiffness::Period(0.5));
        s.damping = Damping::Physical {
            strain_rate: 1e-3,
            air: 500.0,
        };
        let mm = s.modal();
        let m = 3.0e6 / 12.0;
        for n in 0..5 {
            let w = mm.omega[n];
            let z = (1e-3 * w * w + 500.0 / m) / (2.0 * w);
            assert!((mm.zeta[n] - z).abs() < 1e-15);
        }
        assert_eq!(mm.air_damping, 500.0);
        assert!((2.0 * PI / mm.omega[0] - 0.5).abs() < 1e-12);
    }

    /// Effective modal masses of a cantilever: 61.3 % in the first mode (textbook value, e.g.
    /// Chopra), and the fractions sum to 1 over all modes (completeness). The tail beyond mode N
    /// is ≈ Σ_{n>N} 4/λ_n² ≈ 4/(π²N) = 8.1e-4 for N = 500, itself good to O(1/N²) ≈ 1e-5.
    #[test]
    fn effective_masses_sum_to_total() {
        let mut s = beam(Stiffness::Period(0.5));
        s.modes = 500;
        let mm = s.modal();
        assert!((mm.effective_mass_fraction(0) - 0.6131).abs() < 1e-4);
        let total: f64 = (0..500).map(|n| mm.effective_mass_fraction(n)).sum();
        let tail = 4.0 / (PI * PI * 500.0);
        assert!((total - (1.0 - tail)).abs() < 1e-5, "{total}");
        assert!(total < 1.0);
    }

    /// Static check of the modal sum: a uniform load m·a on a cantilever gives the tip deflection
    /// a m L⁴/(8 EI). In modal terms w(L) = a m Σ γ_n φ_n(L)/ω_n² (converges fast).
    #[test]
    fn static_modal_sum_gives_uniform_load_deflection() {
        let mut s = beam(Stiffness::Bending(2.0e11));
        s.modes = 60;
        let mm = s.modal();
        let m = 3.0e6 / 12.0;
        let sum: f64 = (0..60)
            .map(|n| mm.participation[n] * mm.shape(n, 12.0) / mm.omega[n].powi(2))
            .sum();
        let exact = m * 12.0f64.powi(4) / (8.0 * 2.0e11);
        // Truncation error of the modal sum ~ Σ_{n>60} 1/λ_n^5 — far below 1e-9 relative.
        assert!((sum - exact).abs() < 1e-9 * exact, "{sum} vs {exact}");
    }
}
