//! A structure in modal coordinates, whatever its kind (docs/model.md §2.4): frequencies,
//! damping ratios, participation factors, air loads and the mode shapes ([`Shapes`]: a
//! cantilever's closed-form modes, or values at floors). What the integrators see of a
//! structure; [`crate::model::structure`] reduces each kind to it.

use crate::model::cantilever::Mode;

/// How a structure's mass-normalised mode shapes φ_n(x) are evaluated (kg^(−1/2)).
#[derive(Debug, Clone, PartialEq)]
pub enum Shapes {
    /// A uniform continuous cantilever (docs/model.md §2.3): closed-form modes of the beam,
    /// scaled by `1/√M`.
    Cantilever(Vec<Mode>),
    /// Masses lumped at floors: each mode's value at every floor, `values[n][f]`, kg^(−1/2).
    /// Between floors (and from 0 at the base to the first floor) φ is linear in height; above
    /// the top floor it is the top floor's value.
    Floors {
        /// Floor heights above the base, m, strictly increasing.
        heights: Vec<f64>,
        /// Floor masses, kg.
        masses: Vec<f64>,
        /// `values[n][f]`: mode n at floor f, kg^(−1/2).
        values: Vec<Vec<f64>>,
    },
}

/// A structure in modal coordinates, whatever its kind:
/// `η̈_n + 2ζ_nω_n η̇_n + ω_n² η_n = −Γ_n a_g − a_n v_g + s φ_n(h) F` (docs/model.md §2.4),
/// with mass-normalised modes (modal mass 1 kg).
#[derive(Debug, Clone, PartialEq)]
pub struct ModalModel {
    /// Height of the top, L, m.
    pub length: f64,
    /// Total mass M, kg.
    pub mass: f64,
    /// Air damping coefficient c_a used in the forcing, N·s/m² (0 with modal damping, and for
    /// buildings with floors).
    pub air_damping: f64,
    /// Participation factors Γ_n, kg^(1/2): `∫ m φ_n dx` for a cantilever, `φ_nᵀ M 1` for
    /// floors; the modal load per unit ground acceleration is −Γ_n.
    pub participation: Vec<f64>,
    /// Modal load per unit ground velocity `a_n = c_a γ_n` (air damping of a cantilever), kg^(1/2)/s.
    pub air_load: Vec<f64>,
    /// The mode shapes.
    pub shapes: Shapes,
    /// Natural circular frequencies ω_n, rad/s.
    pub omega: Vec<f64>,
    /// Damping ratios ζ_n.
    pub zeta: Vec<f64>,
}

impl ModalModel {
    /// The first `n` modes (all if fewer).
    pub fn truncated(&self, n: usize) -> ModalModel {
        let n = n.min(self.len());
        let shapes = match &self.shapes {
            Shapes::Cantilever(m) => Shapes::Cantilever(m[..n].to_vec()),
            Shapes::Floors {
                heights,
                masses,
                values,
            } => Shapes::Floors {
                heights: heights.clone(),
                masses: masses.clone(),
                values: values[..n].to_vec(),
            },
        };
        ModalModel {
            participation: self.participation[..n].to_vec(),
            air_load: self.air_load[..n].to_vec(),
            omega: self.omega[..n].to_vec(),
            zeta: self.zeta[..n].to_vec(),
            shapes,
            ..self.clone()
        }
    }

    /// Number of modes kept.
    pub fn len(&self) -> usize {
        self.omega.len()
    }

    /// True if no mode is kept (never, for a checked scenario).
    pub fn is_empty(&self) -> bool {
        self.omega.is_empty()
    }

    /// Mass-normalised shape φ_n(x) of mode index `n` (0-based), kg^(−1/2); x in m, 0 ≤ x ≤ L.
    pub fn shape(&self, n: usize, x: f64) -> f64 {
        match &self.shapes {
            Shapes::Cantilever(modes) => modes[n].shape(x / self.length) / self.mass.sqrt(),
            Shapes::Floors {
                heights, values, ..
            } => floor_interpolate(heights, &values[n], x),
        }
    }

    /// All φ_n(x), kg^(−1/2).
    pub fn shapes_at(&self, x: f64) -> Vec<f64> {
        (0..self.len()).map(|n| self.shape(n, x)).collect()
    }

    /// Floor heights (m) of a structure with floors; `None` for a cantilever.
    pub fn floor_heights(&self) -> Option<&[f64]> {
        match &self.shapes {
            Shapes::Cantilever(_) => None,
            Shapes::Floors { heights, .. } => Some(heights),
        }
    }

    /// The largest |φ_n| at the top over the modes kept, kg^(−1/2) (`2/√M` for a cantilever):
    /// turns a displacement at the top into a modal amplitude.
    pub fn top_shape_scale(&self) -> f64 {
        (0..self.len())
            .map(|n| self.shape(n, self.length).abs())
            .fold(0.0, f64::max)
    }

    /// Periods T_n = 2π/ω_n, s.
    pub fn periods(&self) -> Vec<f64> {
        self.omega
            .iter()
            .map(|w| 2.0 * std::f64::consts::PI / w)
            .collect()
    }

    /// Participation factor Γ_n, kg^(1/2): the modal load per unit ground acceleration,
    /// `η̈_n + … = −Γ_n a_g`.
    pub fn participation_factor(&self, n: usize) -> f64 {
        self.participation[n]
    }

    /// Effective modal mass fraction Γ_n²/M: the share of the total mass mode n moves under
    /// ground shaking (sums to 1 over all modes; 0.613 for the first cantilever mode).
    pub fn effective_mass_fraction(&self, n: usize) -> f64 {
        self.participation_factor(n).powi(2) / self.mass
    }
}

/// φ at height x from its values at floors (linear between floors, 0 at the base, the top
/// floor's value above it).
fn floor_interpolate(heights: &[f64], values: &[f64], x: f64) -> f64 {
    let (mut h0, mut v0) = (0.0, 0.0);
    for (&h, &v) in heights.iter().zip(values) {
        if x <= h {
            return if h > h0 {
                v0 + (v - v0) * (x - h0).max(0.0) / (h - h0)
            } else {
                v
            };
        }
        (h0, v0) = (h, v);
    }
    v0
}
