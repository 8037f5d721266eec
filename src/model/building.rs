//! Buildings with floors (issue 11): masses lumped at floor heights, pounding floor against
//! floor — the standard models of the pounding literature (Anagnostopoulos 1988, Maison &
//! Kasai 1990, Jankowski 2005) and what engineers export from ETABS, SAP2000 or OpenSees.
//!
//! Two kinds reduce to a [`ModalModel`] with [`Shapes::Floors`]:
//!
//! - [`ShearBuilding`]: storey springs between the floors. Its modes solve the generalised
//!   eigenproblem `K φ = ω² M φ` with K tridiagonal (storey j joins floor j−1, the base for
//!   j = 1, to floor j) and M diagonal, solved as the symmetric problem
//!   `M^{−½} K M^{−½} v = ω² v`, `φ = M^{−½} v` (mass-normalised: `φᵀ M φ = 1`).
//! - [`EngineerModes`]: the engineer's own periods and mode shapes (any normalisation), which
//!   are mass-normalised with the floor masses and checked for mass-orthogonality.
//!
//! Both give the participation factors `Γ_n = φ_nᵀ M 1` (the modal load per unit ground
//! acceleration is −Γ_n) and the damping ratios of [`FloorDamping`].

use nalgebra::{DMatrix, SymmetricEigen};

use crate::model::modal::{ModalModel, Shapes};

/// Largest |φ_mᵀ M φ_n| (m ≠ n, shapes mass-normalised) accepted for the engineer's modes:
/// shapes exported with four significant digits are orthogonal to ~1e-4; 0.1 is a shape that
/// is not a mode of these floor masses (e.g. the wrong direction, or the wrong masses).
pub const MAX_ORTHOGONALITY_ERROR: f64 = 0.1;

/// Above this |φ_mᵀ M φ_n| the engineer's modes are accepted with a warning.
pub const WARN_ORTHOGONALITY_ERROR: f64 = 0.01;

/// Whether two heights (m) are the same level: equal to 1e-9 of the height (1e-9 m below 1 m),
/// the one rule for "a contact at this floor" everywhere.
pub fn same_height(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

/// The floors of a building: heights above the base and lumped masses.
#[derive(Debug, Clone, PartialEq)]
pub struct Floors {
    /// Floor heights above the base, m, strictly increasing, > 0.
    pub heights: Vec<f64>,
    /// Floor masses, kg, > 0, one per floor.
    pub masses: Vec<f64>,
}

impl Floors {
    /// Total mass, kg.
    pub fn total_mass(&self) -> f64 {
        self.masses.iter().sum()
    }

    /// Height of the top floor, m.
    pub fn top(&self) -> f64 {
        self.heights.last().copied().unwrap_or(0.0)
    }

    /// Index of the floor at height `h` ([`same_height`]), if any.
    pub fn floor_at(&self, h: f64) -> Option<usize> {
        self.heights.iter().position(|&x| same_height(x, h))
    }

    fn check(&self) -> Result<(), BuildingError> {
        let n = self.heights.len();
        if n == 0 {
            return Err(BuildingError::Invalid(
                "a building needs at least one floor".into(),
            ));
        }
        if self.masses.len() != n {
            return Err(BuildingError::Invalid(format!(
                "{} floor heights but {} floor masses (one per floor)",
                n,
                self.masses.len()
            )));
        }
        let mut last = 0.0;
        for (f, &h) in self.heights.iter().enumerate() {
            if !(h.is_finite() && h > last) {
                return Err(BuildingError::Invalid(format!(
                    "floor {} is at {h} m: heights must be finite, > 0 and strictly increasing",
                    f + 1
                )));
            }
            last = h;
        }
        if let Some(f) = self
            .masses
            .iter()
            .position(|m| !(m.is_finite() && *m > 0.0))
        {
            return Err(BuildingError::Invalid(format!(
                "floor {} has mass {}: every floor mass must be finite and > 0 (kg)",
                f + 1,
                self.masses[f]
            )));
        }
        Ok(())
    }
}

/// Damping of a building's modes.
#[derive(Debug, Clone, PartialEq)]
pub enum FloorDamping {
    /// Modal damping ratios: one value for every mode, or one per mode kept.
    Modal(Vec<f64>),
    /// Rayleigh damping `C = a₀M + a₁K` with ratio ζ at two modes i, j (1-based): `a₀ =
    /// 2ζω_iω_j/(ω_i + ω_j)`, `a₁ = 2ζ/(ω_i + ω_j)`, and for every mode
    /// `ζ_n = a₀/(2ω_n) + a₁ω_n/2` (Chopra, *Dynamics of Structures*, §11.4).
    Rayleigh {
        /// ζ at the two modes.
        ratio: f64,
        /// The two modes (1-based).
        modes: [usize; 2],
    },
}

impl FloorDamping {
    /// The damping ratio of every mode of frequencies `omega` (rad/s); `all_omega` holds every
    /// mode of the structure (Rayleigh may name a mode beyond those kept).
    fn ratios(&self, omega: &[f64], all_omega: &[f64]) -> Result<Vec<f64>, BuildingError> {
        match self {
            FloorDamping::Modal(z) => {
                if z.len() != 1 && z.len() != omega.len() {
                    return Err(BuildingError::Invalid(format!(
                        "{} damping ratios for {} modes (give one, or one per mode)",
                        z.len(),
                        omega.len()
                    )));
                }
                Ok((0..omega.len())
                    .map(|i| if z.len() == 1 { z[0] } else { z[i] })
                    .collect())
            }
            FloorDamping::Rayleigh { ratio, modes } => {
                let pick = |m: usize| {
                    all_omega.get(m.wrapping_sub(1)).copied().ok_or_else(|| {
                        BuildingError::Invalid(format!(
                            "Rayleigh damping names mode {m}; the building has modes 1 to {}",
                            all_omega.len()
                        ))
                    })
                };
                let (wi, wj) = (pick(modes[0])?, pick(modes[1])?);
                if modes[0] == modes[1] {
                    return Err(BuildingError::Invalid(
                        "Rayleigh damping needs two different modes".into(),
                    ));
                }
                let a0 = 2.0 * ratio * wi * wj / (wi + wj);
                let a1 = 2.0 * ratio / (wi + wj);
                Ok(omega
                    .iter()
                    .map(|w| a0 / (2.0 * w) + a1 * w / 2.0)
                    .collect())
            }
        }
    }
}

/// Why a building could not be reduced to its modes.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BuildingError {
    /// An input that is out of range or inconsistent (says which and why).
    #[error("{0}")]
    Invalid(String),
    /// The engineer's mode shapes are not mass-orthogonal with these floor masses.
    #[error(
        "modes {m} and {n} are not orthogonal with the floor masses: φ{m}ᵀ M φ{n} = {value:.3} \
         after mass-normalising (at most {MAX_ORTHOGONALITY_ERROR} is accepted); check that the \
         shapes and the masses are of the same direction and the same model"
    )]
    NotOrthogonal {
        /// First mode (1-based).
        m: usize,
        /// Second mode (1-based).
        n: usize,
        /// `φ_mᵀ M φ_n` of the mass-normalised shapes.
        value: f64,
    },
}

/// A shear building: floors joined by storey springs (lateral stiffness k_j of storey j, N/m).
#[derive(Debug, Clone, PartialEq)]
pub struct ShearBuilding {
    /// The floors.
    pub floors: Floors,
    /// Storey stiffnesses, N/m, one per floor: storey j joins floor j−1 (the base for j = 1)
    /// to floor j.
    pub storey_stiffnesses: Vec<f64>,
    /// Modes kept (1 … number of floors).
    pub modes: usize,
    /// Damping.
    pub damping: FloorDamping,
}

impl ShearBuilding {
    /// The stiffness matrix K, N/m (tridiagonal: `K_jj = k_j + k_{j+1}`, `K_{j,j+1} = −k_{j+1}`).
    pub fn stiffness_matrix(&self) -> DMatrix<f64> {
        let k = &self.storey_stiffnesses;
        let n = k.len();
        DMatrix::from_fn(n, n, |i, j| {
            if i == j {
                k[i] + k.get(i + 1).copied().unwrap_or(0.0)
            } else if j == i + 1 {
                -k[j]
            } else if i == j + 1 {
                -k[i]
            } else {
                0.0
            }
        })
    }

    /// Every mode of the building (ascending ω, rad/s), mass-normalised shapes `[mode][floor]`
    /// with the top floor's value positive.
    pub fn all_modes(&self) -> Result<(Vec<f64>, Vec<Vec<f64>>), BuildingError> {
        self.floors.check()?;
        let n = self.floors.heights.len();
        if self.storey_stiffnesses.len() != n {
            return Err(BuildingError::Invalid(format!(
                "{} floors but {} storey stiffnesses (one per storey)",
                n,
                self.storey_stiffnesses.len()
            )));
        }
        if let Some(j) = self
            .storey_stiffnesses
            .iter()
            .position(|k| !(k.is_finite() && *k > 0.0))
        {
            return Err(BuildingError::Invalid(format!(
                "storey {} has stiffness {}: every storey stiffness must be finite and > 0 (N/m)",
                j + 1,
                self.storey_stiffnesses[j]
            )));
        }
        let inv_sqrt_m: Vec<f64> = self.floors.masses.iter().map(|m| 1.0 / m.sqrt()).collect();
        let k = self.stiffness_matrix();
        let a = DMatrix::from_fn(n, n, |i, j| inv_sqrt_m[i] * k[(i, j)] * inv_sqrt_m[j]);
        let eig = SymmetricEigen::new(a);
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&x, &y| eig.eigenvalues[x].total_cmp(&eig.eigenvalues[y]));
        let mut omega = Vec::with_capacity(n);
        let mut shapes = Vec::with_capacity(n);
        for &c in &order {
            let lam = eig.eigenvalues[c];
            if !(lam.is_finite() && lam > 0.0) {
                return Err(BuildingError::Invalid(format!(
                    "the stiffness and mass matrices give a non-positive eigenvalue {lam:e}: \
                     the storey stiffnesses or floor masses are out of any usable range"
                )));
            }
            let mut phi: Vec<f64> = (0..n)
                .map(|f| eig.eigenvectors[(f, c)] * inv_sqrt_m[f])
                .collect();
            if phi[n - 1] < 0.0 {
                phi.iter_mut().for_each(|x| *x = -*x);
            }
            omega.push(lam.sqrt());
            shapes.push(phi);
        }
        Ok((omega, shapes))
    }

    /// Reduce to the modal model (the first `modes` modes).
    pub fn modal(&self) -> Result<ModalModel, BuildingError> {
        let (omega, shapes) = self.all_modes()?;
        floors_model(&self.floors, &omega, shapes, self.modes, &self.damping)
    }
}

/// The engineer's own modes (from ETABS, SAP2000, OpenSees `eigen` …): periods and shapes at
/// the floors, in any normalisation.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineerModes {
    /// The floors.
    pub floors: Floors,
    /// Periods T_n, s, > 0, one per mode given.
    pub periods: Vec<f64>,
    /// Mode shapes `[mode][floor]`, any normalisation (mass-normalised here).
    pub shapes: Vec<Vec<f64>>,
    /// Modes kept (1 … number of modes given).
    pub modes: usize,
    /// Damping.
    pub damping: FloorDamping,
}

impl EngineerModes {
    /// The shapes mass-normalised with the floor masses (`φᵀ M φ = 1`), and how far from
    /// mass-orthogonal they are.
    pub fn normalised(&self) -> Result<NormalisedModes, BuildingError> {
        self.floors.check()?;
        let nf = self.floors.heights.len();
        if self.periods.is_empty() {
            return Err(BuildingError::Invalid("no mode given".into()));
        }
        if self.shapes.len() != self.periods.len() {
            return Err(BuildingError::Invalid(format!(
                "{} periods but {} mode shapes",
                self.periods.len(),
                self.shapes.len()
            )));
        }
        if let Some(n) = self
            .periods
            .iter()
            .position(|t| !(t.is_finite() && *t > 0.0))
        {
            return Err(BuildingError::Invalid(format!(
                "mode {} has period {}: periods must be finite and > 0 (s)",
                n + 1,
                self.periods[n]
            )));
        }
        let m = &self.floors.masses;
        let mut out = Vec::with_capacity(self.shapes.len());
        for (n, s) in self.shapes.iter().enumerate() {
            if s.len() != nf {
                return Err(BuildingError::Invalid(format!(
                    "mode shape {} has {} values for {} floors",
                    n + 1,
                    s.len(),
                    nf
                )));
            }
            if s.iter().any(|x| !x.is_finite()) {
                return Err(BuildingError::Invalid(format!(
                    "mode shape {} has a value that is not a finite number",
                    n + 1
                )));
            }
            let norm: f64 = s
                .iter()
                .zip(m)
                .map(|(x, mf)| mf * x * x)
                .sum::<f64>()
                .sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                return Err(BuildingError::Invalid(format!(
                    "mode shape {} is zero at every floor",
                    n + 1
                )));
            }
            out.push(s.iter().map(|x| x / norm).collect::<Vec<f64>>());
        }
        let (mut worst, mut pair) = (0.0f64, (1, 1));
        for a in 0..out.len() {
            for b in a + 1..out.len() {
                let v: f64 = (0..nf).map(|f| out[a][f] * m[f] * out[b][f]).sum();
                if v.abs() > worst {
                    (worst, pair) = (v.abs(), (a + 1, b + 1));
                }
            }
        }
        Ok(NormalisedModes {
            shapes: out,
            orthogonality_error: worst,
            worst_pair: pair,
        })
    }

    /// Reduce to the modal model (the first `modes` modes), refusing shapes that are not
    /// mass-orthogonal within [`MAX_ORTHOGONALITY_ERROR`].
    pub fn modal(&self) -> Result<ModalModel, BuildingError> {
        let NormalisedModes {
            shapes,
            orthogonality_error: worst,
            worst_pair: (m, n),
        } = self.normalised()?;
        if worst > MAX_ORTHOGONALITY_ERROR {
            return Err(BuildingError::NotOrthogonal { m, n, value: worst });
        }
        let omega: Vec<f64> = self
            .periods
            .iter()
            .map(|t| 2.0 * std::f64::consts::PI / t)
            .collect();
        floors_model(&self.floors, &omega, shapes, self.modes, &self.damping)
    }
}

/// The engineer's shapes mass-normalised ([`EngineerModes::normalised`]).
#[derive(Debug, Clone, PartialEq)]
pub struct NormalisedModes {
    /// `[mode][floor]`, `φᵀ M φ = 1`, kg^(−1/2).
    pub shapes: Vec<Vec<f64>>,
    /// The largest `|φ_mᵀ M φ_n|`, m ≠ n (0 for one mode).
    pub orthogonality_error: f64,
    /// The pair (1-based) where it occurs.
    pub worst_pair: (usize, usize),
}

/// The modal model of floors from every mode's ω and mass-normalised shape, keeping `modes`.
fn floors_model(
    floors: &Floors,
    all_omega: &[f64],
    mut shapes: Vec<Vec<f64>>,
    modes: usize,
    damping: &FloorDamping,
) -> Result<ModalModel, BuildingError> {
    if modes == 0 || modes > all_omega.len() {
        return Err(BuildingError::Invalid(format!(
            "{modes} modes asked for; this building has modes 1 to {}",
            all_omega.len()
        )));
    }
    shapes.truncate(modes);
    let omega = all_omega[..modes].to_vec();
    let zeta = damping.ratios(&omega, all_omega)?;
    if let Some(n) = zeta
        .iter()
        .position(|z| !(z.is_finite() && (0.0..1.0).contains(z)))
    {
        return Err(BuildingError::Invalid(format!(
            "mode {} gets damping ratio {}: it must be in [0, 1)",
            n + 1,
            zeta[n]
        )));
    }
    let participation = shapes
        .iter()
        .map(|phi| phi.iter().zip(&floors.masses).map(|(p, m)| p * m).sum())
        .collect();
    Ok(ModalModel {
        length: floors.top(),
        mass: floors.total_mass(),
        air_damping: 0.0,
        participation,
        air_load: vec![0.0; modes],
        shapes: Shapes::Floors {
            heights: floors.heights.clone(),
            masses: floors.masses.clone(),
            values: shapes,
        },
        omega,
        zeta,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn uniform(n: usize, m: f64, k: f64, h: f64) -> ShearBuilding {
        ShearBuilding {
            floors: Floors {
                heights: (1..=n).map(|i| i as f64 * h).collect(),
                masses: vec![m; n],
            },
            storey_stiffnesses: vec![k; n],
            modes: n,
            damping: FloorDamping::Modal(vec![0.05]),
        }
    }

    /// A uniform shear building of N storeys (mass m, stiffness k each): ω_r = 2√(k/m)
    /// sin((2r−1)π/(2(2N+1))), φ_r(floor j) ∝ sin((2r−1)jπ/(2N+1)) (the fixed–free chain;
    /// e.g. Chopra, Example 10.x / the discrete string).
    #[test]
    fn uniform_building_has_the_chain_frequencies_and_shapes() {
        let (n, m, k) = (10, 2.0e5, 3.0e8);
        let b = uniform(n, m, k, 3.5);
        let mm = b.modal().unwrap();
        for r in 1..=n {
            let w =
                2.0 * (k / m).sqrt() * ((2 * r - 1) as f64 * PI / (2.0 * (2 * n + 1) as f64)).sin();
            assert!((mm.omega[r - 1] - w).abs() < 1e-10 * w, "mode {r}");
            // shape: mass-normalised sin((2r−1)jπ/(2N+1)), top positive
            let raw: Vec<f64> = (1..=n)
                .map(|j| ((2 * r - 1) as f64 * j as f64 * PI / (2 * n + 1) as f64).sin())
                .collect();
            let norm = (raw.iter().map(|x| m * x * x).sum::<f64>()).sqrt();
            let sign = raw[n - 1].signum();
            for (j, &h) in b.floors.heights.iter().enumerate() {
                let phi = mm.shape(r - 1, h);
                assert!(
                    (phi - sign * raw[j] / norm).abs() < 1e-10 / m.sqrt(),
                    "mode {r} floor {j}"
                );
            }
        }
        // participation: Σ Γ_n² = total mass (all modes kept)
        let total: f64 = mm.participation.iter().map(|g| g * g).sum();
        assert!((total - n as f64 * m).abs() < 1e-9 * total);
    }

    /// Two storeys by hand: m₁ = 2m, m₂ = m, k₁ = 2k, k₂ = k (Chopra Example 10.4):
    /// ω² = k/(2m) and 2k/m, φ₁ ∝ (1/2, 1), φ₂ ∝ (−1, 1).
    #[test]
    fn two_storeys_by_hand() {
        let (m, k) = (1.0e5, 4.0e7);
        let b = ShearBuilding {
            floors: Floors {
                heights: vec![3.0, 6.0],
                masses: vec![2.0 * m, m],
            },
            storey_stiffnesses: vec![2.0 * k, k],
            modes: 2,
            damping: FloorDamping::Modal(vec![0.02]),
        };
        let mm = b.modal().unwrap();
        assert!((mm.omega[0] - (k / (2.0 * m)).sqrt()).abs() < 1e-10 * mm.omega[0]);
        assert!((mm.omega[1] - (2.0 * k / m).sqrt()).abs() < 1e-10 * mm.omega[1]);
        // φ₁ = (1/2, 1)/√(2m/4 + m) = (1/2, 1)/√(1.5 m)
        let s = (1.5 * m).sqrt();
        assert!((mm.shape(0, 3.0) - 0.5 / s).abs() < 1e-12);
        assert!((mm.shape(0, 6.0) - 1.0 / s).abs() < 1e-12);
        // Γ₁ = φ₁ᵀ M 1 = (2m·½ + m·1)/√(1.5m) = 2m/√(1.5m)
        assert!((mm.participation[0] - 2.0 * m / s).abs() < 1e-9);
        // φ between floors is linear, 0 at the base
        assert!((mm.shape(0, 1.5) - 0.25 / s).abs() < 1e-12);
        assert!((mm.shape(0, 4.5) - 0.75 / s).abs() < 1e-12);
    }

    /// Rayleigh damping gives ζ exactly at its two modes and a₀/(2ω) + a₁ω/2 elsewhere.
    #[test]
    fn rayleigh_damping_hits_its_two_modes() {
        let mut b = uniform(6, 1.0e5, 2.0e8, 3.0);
        b.damping = FloorDamping::Rayleigh {
            ratio: 0.05,
            modes: [1, 3],
        };
        let mm = b.modal().unwrap();
        assert!((mm.zeta[0] - 0.05).abs() < 1e-14);
        assert!((mm.zeta[2] - 0.05).abs() < 1e-14);
        // between the two modes ζ < 0.05, beyond them ζ > 0.05
        assert!(mm.zeta[1] < 0.05 && mm.zeta[5] > 0.05);
        let (wi, wj) = (mm.omega[0], mm.omega[2]);
        let (a0, a1) = (0.1 * wi * wj / (wi + wj), 0.1 / (wi + wj));
        let w = mm.omega[4];
        assert!((mm.zeta[4] - (a0 / (2.0 * w) + a1 * w / 2.0)).abs() < 1e-14);
        b.damping = FloorDamping::Rayleigh {
            ratio: 0.05,
            modes: [1, 9],
        };
        assert!(b.modal().is_err());
    }

    /// The engineer's modes, given as the shear building's own shapes in another scaling
    /// (top = 1) with its periods, give the same modal model to round-off; shapes that are not
    /// orthogonal are refused, naming the modes.
    #[test]
    fn engineer_modes_equal_the_shear_buildings_own() {
        let b = uniform(5, 3.0e5, 4.0e8, 3.2);
        let mm = b.modal().unwrap();
        let shapes: Vec<Vec<f64>> = (0..5)
            .map(|n| {
                let top = mm.shape(n, 16.0);
                b.floors
                    .heights
                    .iter()
                    .map(|&h| 7.0 * mm.shape(n, h) / top)
                    .collect()
            })
            .collect();
        let e = EngineerModes {
            floors: b.floors.clone(),
            periods: mm.periods(),
            shapes,
            modes: 5,
            damping: FloorDamping::Modal(vec![0.05]),
        };
        let em = e.modal().unwrap();
        for n in 0..5 {
            assert!((em.omega[n] - mm.omega[n]).abs() < 1e-12 * mm.omega[n]);
            assert!(
                (em.participation[n] - mm.participation[n]).abs() < 1e-12 * mm.participation[0]
            );
            for &h in &b.floors.heights {
                assert!((em.shape(n, h) - mm.shape(n, h)).abs() < 1e-12 * mm.shape(0, 16.0));
            }
        }
        let mut bad = e.clone();
        bad.shapes[1] = bad.shapes[0]
            .iter()
            .zip(&e.shapes[1])
            .map(|(a, b)| a + 0.5 * b)
            .collect();
        match bad.modal() {
            Err(BuildingError::NotOrthogonal { m: 1, n: 2, value }) => assert!(value > 0.1),
            other => panic!("{other:?}"),
        }
    }

    /// Bad inputs are errors, never panics.
    #[test]
    fn bad_inputs_are_errors() {
        let mut b = uniform(3, 1.0e5, 1.0e8, 3.0);
        b.storey_stiffnesses.pop();
        assert!(b.modal().is_err());
        let mut b = uniform(3, 1.0e5, 1.0e8, 3.0);
        b.floors.heights[1] = 2.0;
        assert!(b.modal().is_err());
        let mut b = uniform(3, 1.0e5, 1.0e8, 3.0);
        b.modes = 4;
        assert!(b.modal().is_err());
        let mut b = uniform(3, 1.0e5, f64::NAN, 3.0);
        b.modes = 3;
        assert!(b.modal().is_err());
        let e = EngineerModes {
            floors: uniform(2, 1.0, 1.0, 1.0).floors,
            periods: vec![1.0, -1.0],
            shapes: vec![vec![1.0, 1.0], vec![1.0, -1.0]],
            modes: 2,
            damping: FloorDamping::Modal(vec![0.05]),
        };
        assert!(e.modal().is_err());
    }
}
