//! Export a scenario as an OpenSeesPy model, and compare OpenSees' numbers with the program's
//! (issue 14).
//!
//! [`script`] writes a self-contained Python script: the model's data as one JSON literal
//! (`MODEL`, built by [`model`]) followed by a fixed driver (`driver.py`, embedded) that builds
//! the OpenSees model, runs it with and without contact and prints the headline numbers of
//! `summary.json` as JSON. [`compare`] runs such a script with a local `openseespy` and sets
//! its numbers beside the program's.
//!
//! How the scenario maps onto OpenSees (what is exact and what is not: [`law_mapping`],
//! [`damping_notes`]):
//!
//! - a cantilever: `elements` 2-D `elasticBeamColumn` elements with its EI and a consistent
//!   mass (`-mass m -cMass`), axial DOFs fixed, a node at every contact height ([`mesh`]);
//! - a shear building: a node per floor with its mass, rotations fixed (rigid floors), storey
//!   springs as `twoNodeLink` elements in shear — `Elastic`, or for yielding storeys OpenSees'
//!   `BoucWen` material with the program's law mapped onto it ([`bouc_wen_material`]); a
//!   building given by its modes cannot be exported (OpenSees needs stiffnesses);
//! - the ground motion as nodal loads `−M r a_g(t)` through a `Plain` pattern with a `Path`
//!   series (never `UniformExcitation`: in OpenSees 3.7.1 a 2-D `elasticBeamColumn` with element
//!   mass under `UniformExcitation` receives the ground inertia load twice);
//! - damping: modal (`modalDampingQ` on every FE mode, each with its structure's ratio for its
//!   mode number) or Rayleigh (`region … -rayleigh` with the *initial* stiffness, as the program's
//!   damping stays that of the initial stiffness; never on the contact elements), as the
//!   scenario has it;
//! - contact at every level: a `zeroLength` element between the two structures' nodes at that
//!   height, with the law's material ([`contact_material`]);
//! - Newmark average acceleration (γ = ½, β = ¼), Newton iterations, and on a failed step:
//!   sub-steps halved down to dt/64, then the same with ModifiedNewton, then KrylovNewton.

pub mod compare;
pub mod results;
pub mod row;
pub mod row_compare;
mod storeys;
mod yielding;

pub use yielding::{BOUC_WEN_MAPPING, BoucWenMaterial, bouc_wen_material};

use serde::Serialize;

use crate::input::scenario::Scenario;
use crate::model::contact::{ContactForce, ContactLaw};
use crate::model::ground_motion::GroundMotion;
use crate::model::structure::{Cantilever, Damping, FloorKind, Structure};

/// The driver appended to every exported script (Python, OpenSeesPy).
pub const DRIVER: &str = include_str!("driver.py");

/// The OpenSeesPy release the export was written and tested against (`pip install
/// openseespy==3.7.1.2`).
pub const TESTED_OPENSEESPY: &str = "3.7.1.2";

/// Default number of beam elements per cantilever.
pub const DEFAULT_ELEMENTS: usize = 20;

/// Default OpenSees analysis step, s: the step at which the agreement (≤ 2 % with
/// Hertz contact) was measured.
pub const DEFAULT_DT: f64 = 2.5e-4;

/// Newton's convergence tolerance on the norm of the displacement increment (m, rad).
pub const NEWTON_TOLERANCE: f64 = 1e-10;

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

/// Which runs the script does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Only {
    /// Only the run with contact.
    Contact,
    /// Only the run without contact.
    Free,
}

impl Only {
    /// Parse `contact` or `free`.
    pub fn from_name(name: &str) -> Option<Only> {
        match name {
            "contact" => Some(Only::Contact),
            "free" => Some(Only::Free),
            _ => None,
        }
    }
}

/// Options of the export.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExportOptions {
    /// Beam elements per cantilever (at least one per segment between contact heights).
    pub elements: usize,
    /// OpenSees analysis step, s.
    pub dt: f64,
    /// Simulated time, s (`None`: the scenario's).
    pub duration: Option<f64>,
    /// Run only one of the two cases.
    pub only: Option<Only>,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            elements: DEFAULT_ELEMENTS,
            dt: DEFAULT_DT,
            duration: None,
            only: None,
        }
    }
}

/// Why a scenario cannot be exported.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// The contact law has no OpenSees counterpart.
    #[error("contact law `{law}` cannot be exported to OpenSees: {reason}")]
    Law {
        /// The law's scenario name.
        law: &'static str,
        /// Why.
        reason: &'static str,
    },
    /// A structure of a kind OpenSees cannot be given.
    #[error("structure `{name}` cannot be exported to OpenSees: {reason}")]
    Structure {
        /// The structure's name.
        name: String,
        /// Why.
        reason: String,
    },
    /// An option out of range.
    #[error("{0}")]
    Option(String),
    /// A row's pair that cannot be exported (issue 29): which pair, and why.
    #[error("contact[{pair}] (between \"{left}\" and \"{right}\"): {source}")]
    Pair {
        /// The pair's place in the row, 1-based (`contact[P]`, as a sweep names it).
        pair: usize,
        /// Its left structure's name.
        left: String,
        /// Its right structure's name.
        right: String,
        /// Why.
        source: Box<ExportError>,
    },
}

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

/// The model's data, serialised as the script's `MODEL` literal.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExportModel {
    /// Scenario title.
    pub title: String,
    /// What wrote it.
    pub source: String,
    /// Analysis step, s.
    pub dt: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Newton tolerance.
    pub tolerance: f64,
    /// Runs (`None`: both).
    pub only: Option<Only>,
    /// Structure 1 and 2.
    pub structures: Vec<ExportStructure>,
    /// Contact levels.
    pub levels: Vec<ExportLevel>,
    /// Ground motion.
    pub ground: ExportGround,
}

/// One structure of the exported model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExportStructure {
    /// Name.
    pub name: String,
    /// `cantilever` or `shear-building`.
    pub kind: &'static str,
    /// Node heights, m, from the base (0) up.
    pub node_heights: Vec<f64>,
    /// EI, N·m² (cantilever).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bending_stiffness: Option<f64>,
    /// m, kg/m (cantilever).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass_per_length: Option<f64>,
    /// Beam elements (cantilever).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub elements: Option<usize>,
    /// Floor masses, kg (shear building).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub floor_masses: Option<Vec<f64>>,
    /// Storey stiffnesses, N/m (shear building).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub storey_stiffnesses: Option<Vec<f64>>,
    /// Yielding storeys (a shear building with `hysteresis`): each storey's `BoucWen` material,
    /// lowest first.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bouc_wen: Option<Vec<BoucWenMaterial>>,
    /// Air damping c_a, N·s/m² (its ground-velocity load).
    pub air_damping: f64,
    /// Damping.
    pub damping: ExportDamping,
    /// Heights whose peaks are reported, m: the contact heights (cantilever) or every floor.
    pub tracked_heights: Vec<f64>,
    /// Modes the program keeps (for the record).
    pub program_modes: usize,
}

/// Damping of an exported structure.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum ExportDamping {
    /// Modal ratios by mode number; modes beyond the list take its last ratio.
    Modal {
        /// ζ per mode.
        ratios: Vec<f64>,
    },
    /// `C = α_M M + β_K K`.
    Rayleigh {
        /// α_M, 1/s.
        alpha_m: f64,
        /// β_K, s.
        beta_k: f64,
    },
}

/// A contact level of the exported model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExportLevel {
    /// Height, m.
    pub height: f64,
    /// Gap, m.
    pub gap: f64,
    /// Its OpenSees material.
    pub material: ContactMaterial,
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

/// Ground motion of the exported model.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum ExportGround {
    /// No shaking.
    None,
    /// `a_g = −PGA sin ωt`, sampled by the script at its step into a `Path` series.
    Harmonic {
        /// m/s².
        pga: f64,
        /// rad/s.
        omega: f64,
    },
    /// The record's samples (m/s²) into a `Path` series (zero after the last).
    Record {
        /// s.
        dt: f64,
        /// m/s².
        accel: Vec<f64>,
        /// m/s², only when a structure has air damping.
        #[serde(skip_serializing_if = "Option::is_none")]
        velocity: Option<Vec<f64>>,
    },
}

/// Node heights of a cantilever of height `length` meshed with `elements` elements, with a node
/// at every height of `at` inside (0, length): each stretch between such heights gets elements
/// in proportion to its length (at least one), of equal length within the stretch. The count
/// may exceed `elements` when there are more stretches than elements.
pub fn mesh(length: f64, at: &[f64], elements: usize) -> Vec<f64> {
    let mut breaks: Vec<f64> = at
        .iter()
        .copied()
        .filter(|h| *h > 0.0 && *h < length)
        .collect();
    breaks.push(length);
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * length);
    let lens: Vec<f64> = std::iter::once(breaks[0])
        .chain(breaks.windows(2).map(|w| w[1] - w[0]))
        .collect();
    // largest remainder, at least one per stretch
    let total = elements.max(lens.len());
    let ideal: Vec<f64> = lens.iter().map(|l| l / length * total as f64).collect();
    let mut count: Vec<usize> = ideal.iter().map(|x| (x.floor() as usize).max(1)).collect();
    while count.iter().sum::<usize>() < total {
        let i = (0..count.len())
            .max_by(|&a, &b| (ideal[a] - count[a] as f64).total_cmp(&(ideal[b] - count[b] as f64)))
            .unwrap_or(0);
        count[i] += 1;
    }
    let mut nodes = vec![0.0];
    let mut base = 0.0;
    for (&top, &n) in breaks.iter().zip(&count) {
        for k in 1..=n {
            nodes.push(if k == n {
                top
            } else {
                base + (top - base) * k as f64 / n as f64
            });
        }
        base = top;
    }
    nodes
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

/// Damping of a cantilever: modal ratios, or the physical form as Rayleigh (exact: strain-rate
/// damping is stiffness-proportional with β_K = c_s/E, air damping mass-proportional with
/// α_M = c_a/m).
fn cantilever_damping(c: &Cantilever) -> (ExportDamping, f64) {
    match &c.damping {
        Damping::Modal(z) => (ExportDamping::Modal { ratios: z.clone() }, 0.0),
        Damping::Physical { strain_rate, air } => (
            ExportDamping::Rayleigh {
                alpha_m: air / c.mass_per_length(),
                beta_k: *strain_rate,
            },
            *air,
        ),
    }
}

/// Notes on the damping of `scenario`'s structures in OpenSees (what is exact, what is not).
pub fn damping_notes(scenario: &Scenario) -> Vec<String> {
    let mut notes = Vec::new();
    for s in &scenario.structures {
        let modal = match s {
            Structure::Cantilever(c) => matches!(c.damping, Damping::Modal(_)),
            Structure::Floors(f) => match &f.kind {
                FloorKind::ShearBuilding(b) => {
                    matches!(b.damping, crate::model::building::FloorDamping::Modal(_))
                }
                FloorKind::Modal(_) => true,
            },
        };
        notes.push(if modal {
            format!(
                "{}: modal damping on every mode of the OpenSees model (the program keeps {} \
                 modes; OpenSees' higher modes are damped too, at the ratio of the last mode \
                 given)",
                s.name(),
                s.modes()
            )
        } else {
            format!(
                "{}: Rayleigh damping, the same C = α_M M + β_K K₀ as the program's ratios (K₀ \
                 the initial stiffness, constant in time as in the program)",
                s.name()
            )
        });
    }
    notes
}

/// The exported model of `scenario` (see the module documentation).
pub fn model(scenario: &Scenario, opts: &ExportOptions) -> Result<ExportModel, ExportError> {
    let duration = checked_duration(scenario, opts)?;
    let heights: Vec<f64> = scenario.contact.levels.iter().map(|l| l.height).collect();
    let mut structures = Vec::with_capacity(2);
    for s in &scenario.structures {
        structures.push(export_structure(s, &heights, opts.elements)?);
    }
    let system = scenario.system();
    let mut levels = Vec::with_capacity(system.levels.len());
    for lv in &system.levels {
        let material =
            contact_material(&scenario.contact.law, &lv.force, lv.gap, lv.effective_mass)?;
        levels.push(ExportLevel {
            height: lv.height,
            gap: lv.gap,
            material,
        });
    }
    let ground = export_ground(scenario, &structures);
    Ok(ExportModel {
        title: scenario.title.clone(),
        source: format!("pounding {}", env!("CARGO_PKG_VERSION")),
        dt: opts.dt,
        duration,
        tolerance: NEWTON_TOLERANCE,
        only: opts.only,
        structures,
        levels,
        ground,
    })
}

/// The options checked (elements, step, duration, number of steps); the simulated time, s.
fn checked_duration(scenario: &Scenario, opts: &ExportOptions) -> Result<f64, ExportError> {
    if opts.elements == 0 || opts.elements > 10_000 {
        return Err(ExportError::Option(format!(
            "--elements must be a whole number from 1 to 10000, got {}",
            opts.elements
        )));
    }
    if !(opts.dt.is_finite() && opts.dt > 0.0) {
        return Err(ExportError::Option(format!(
            "--dt must be a finite number > 0 (s), got {}",
            opts.dt
        )));
    }
    let duration = opts.duration.unwrap_or(scenario.solver.duration);
    if !(duration.is_finite() && duration > 0.0) {
        return Err(ExportError::Option(format!(
            "the duration must be a finite number > 0 (s), got {duration}"
        )));
    }
    if duration / opts.dt > 1e8 {
        return Err(ExportError::Option(format!(
            "{duration} s at dt = {} s is more than 1e8 OpenSees steps",
            opts.dt
        )));
    }
    Ok(duration)
}

/// The scenario's ground motion for the script (the record's velocity only when a structure
/// has air damping).
fn export_ground(scenario: &Scenario, structures: &[ExportStructure]) -> ExportGround {
    let air = structures.iter().any(|s| s.air_damping > 0.0);
    match &scenario.ground_motion {
        GroundMotion::None => ExportGround::None,
        GroundMotion::Harmonic(h) => ExportGround::Harmonic {
            pga: h.pga,
            omega: h.omega,
        },
        GroundMotion::Record(r) => ExportGround::Record {
            dt: r.dt,
            accel: r.accel.clone(),
            velocity: air.then(|| r.velocity_samples().to_vec()),
        },
    }
}

fn export_structure(
    s: &Structure,
    heights: &[f64],
    elements: usize,
) -> Result<ExportStructure, ExportError> {
    match s {
        Structure::Cantilever(c) => {
            let (damping, air) = cantilever_damping(c);
            let nodes = mesh(c.length, heights, elements);
            Ok(ExportStructure {
                name: c.name.clone(),
                kind: "cantilever",
                elements: Some(nodes.len() - 1),
                node_heights: nodes,
                bending_stiffness: Some(c.bending_stiffness()),
                mass_per_length: Some(c.mass_per_length()),
                floor_masses: None,
                storey_stiffnesses: None,
                bouc_wen: None,
                air_damping: air,
                damping,
                tracked_heights: heights.to_vec(),
                program_modes: c.modes,
            })
        }
        Structure::Floors(f) => {
            let b = match &f.kind {
                FloorKind::ShearBuilding(b) => b,
                FloorKind::Modal(_) => {
                    return Err(ExportError::Structure {
                        name: f.name.clone(),
                        reason: "it is given by its periods and mode shapes (kind = \"modal\"): \
                                 OpenSees needs its storey stiffnesses (give it as a shear \
                                 building)"
                            .into(),
                    });
                }
            };
            for &h in heights {
                if b.floors.floor_at(h).is_none() {
                    return Err(ExportError::Structure {
                        name: f.name.clone(),
                        reason: format!(
                            "the contact at h = {h} m is not at one of its floors ({}): in \
                             OpenSees the contact element joins two floor nodes",
                            b.floors
                                .heights
                                .iter()
                                .map(|x| format!("{x} m"))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    });
                }
            }
            let damping = match &b.damping {
                crate::model::building::FloorDamping::Modal(z) => {
                    ExportDamping::Modal { ratios: z.clone() }
                }
                crate::model::building::FloorDamping::Rayleigh { ratio, modes } => {
                    let w = &f.all_modes.omega;
                    let (wi, wj) = (w[modes[0] - 1], w[modes[1] - 1]);
                    ExportDamping::Rayleigh {
                        alpha_m: 2.0 * ratio * wi * wj / (wi + wj),
                        beta_k: 2.0 * ratio / (wi + wj),
                    }
                }
            };
            let mut nodes = vec![0.0];
            nodes.extend_from_slice(&b.floors.heights);
            Ok(ExportStructure {
                name: f.name.clone(),
                kind: "shear-building",
                node_heights: nodes,
                bending_stiffness: None,
                mass_per_length: None,
                elements: None,
                floor_masses: Some(b.floors.masses.clone()),
                storey_stiffnesses: Some(b.storey_stiffnesses.clone()),
                bouc_wen: f.hysteresis.as_ref().map(|bw| {
                    b.storey_stiffnesses
                        .iter()
                        .zip(&bw.yield_drifts)
                        .map(|(&k, &dy)| bouc_wen_material(k, dy, bw))
                        .collect()
                }),
                air_damping: 0.0,
                damping,
                tracked_heights: b.floors.heights.clone(),
                program_modes: f.modes,
            })
        }
    }
}

/// The self-contained OpenSeesPy script of `scenario`: a header saying what it is and how the
/// scenario was mapped, the `MODEL` data, the driver. `source` names the scenario file.
pub fn script(
    scenario: &Scenario,
    opts: &ExportOptions,
    source: &str,
) -> Result<String, ExportError> {
    let m = model(scenario, opts)?;
    let json = serde_json::to_string(&m)
        .map_err(|e| ExportError::Option(format!("could not serialise the model: {e}")))?;
    let mut out = String::with_capacity(json.len() + DRIVER.len() + 4096);
    out.push_str("#!/usr/bin/env python3\n");
    out.push_str(&format!(
        "# OpenSeesPy model of the pounding scenario \"{}\" ({}),\n",
        one_line(&scenario.title),
        one_line(source)
    ));
    out.push_str(&format!(
        "# written by `pounding export opensees` ({}). Needs openseespy (tested with {}):\n",
        m.source, TESTED_OPENSEESPY
    ));
    out.push_str(&format!(
        "#   pip install openseespy=={TESTED_OPENSEESPY}\n#   python3 model.py [--json out.json] [--only contact|free] [--dt DT] [--duration T]\n"
    ));
    out.push_str(
        "# prints JSON with the headline numbers of pounding's summary.json (peaks at the contact\n\
         # heights and at every floor, every storey's peak drift and storey force, a yielding\n\
         # storey's residual drift and hysteretic energy, peak force, impacts, required separation).\n#\n",
    );
    out.push_str(&format!(
        "# OpenSees step dt = {} s over {} s; Newmark average acceleration, Newton.\n",
        m.dt, m.duration
    ));
    for (s, st) in m.structures.iter().enumerate() {
        out.push_str(&structure_line(s, st));
    }
    out.push_str(&format!(
        "# contact `{}`: {}\n",
        scenario.contact.law.name(),
        mapping_text(&scenario.contact.law)
    ));
    for n in damping_notes(scenario) {
        out.push_str(&format!("# damping: {}\n", one_line(&n)));
    }
    if m.structures.iter().any(|s| s.bouc_wen.is_some()) {
        out.push_str(&format!("# yielding {BOUC_WEN_MAPPING}\n"));
    }
    out.push_str("import json\n\nMODEL = json.loads(r'''");
    out.push_str(&json);
    out.push_str("''')\n\n");
    out.push_str(DRIVER);
    Ok(out)
}

/// How `law` maps onto OpenSees, as the script's header says it.
fn mapping_text(law: &ContactLaw) -> String {
    match law_mapping(law) {
        Mapping::Exact(t) => format!("exact — {t}"),
        Mapping::Approximate(t) => format!("approximate — {t}"),
        Mapping::Refused(t) => t.to_string(),
    }
}

/// The header line of structure `s` (0-based) of the script.
fn structure_line(s: usize, st: &ExportStructure) -> String {
    format!(
        "# structure {} ({}): {}\n",
        s + 1,
        one_line(&st.name),
        match st.kind {
            "cantilever" => format!(
                "{} elasticBeamColumn elements, EI = {:e} N·m², m = {:e} kg/m, consistent mass",
                st.node_heights.len() - 1,
                st.bending_stiffness.unwrap_or(0.0),
                st.mass_per_length.unwrap_or(0.0)
            ),
            _ => format!(
                "shear building, {} floors (nodal masses, twoNodeLink storey springs{})",
                st.node_heights.len() - 1,
                if st.bouc_wen.is_some() {
                    ", BoucWen: yielding"
                } else {
                    ""
                }
            ),
        }
    )
}

/// `text` on one line (for comments).
fn one_line(text: &str) -> String {
    text.replace(['\n', '\r'], " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mesh has a node at every contact height and the asked number of elements.
    #[test]
    fn mesh_puts_nodes_at_contact_heights() {
        let n = mesh(16.0, &[10.0, 6.0], 20);
        assert_eq!(n.len(), 21);
        assert!(n.contains(&10.0) && n.contains(&6.0));
        assert_eq!(*n.last().unwrap_or(&0.0), 16.0);
        assert!(n.windows(2).all(|w| w[1] > w[0]));
        let n = mesh(10.0, &[10.0], 20);
        assert_eq!(n.len(), 21);
        assert!((n[1] - 0.5).abs() < 1e-12);
        // more stretches than elements: one each
        assert_eq!(mesh(10.0, &[2.0, 5.0, 7.0], 2).len(), 5);
    }

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
