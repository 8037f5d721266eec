//! The exported model's data (the script's `MODEL` literal, [`ExportModel`]) built from a
//! scenario: each structure's nodes, masses, stiffnesses and damping, the contact levels with
//! their materials, the ground motion.

use serde::Serialize;

use super::{
    BoucWenMaterial, ContactMaterial, ExportError, ExportOptions, NEWTON_TOLERANCE, Only,
    bouc_wen_material, contact_material,
};
use crate::input::scenario::Scenario;
use crate::model::ground_motion::GroundMotion;
use crate::model::structure::{Cantilever, Damping, FloorKind, Structure};

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
    let levels = export_levels(scenario)
        .map_err(|(_, e)| e)?
        .into_iter()
        .map(|(_, level)| level)
        .collect();
    let ground = export_ground(scenario, &structures);
    Ok(ExportModel {
        title: scenario.title.clone(),
        source: exported_by(),
        dt: opts.dt,
        duration,
        tolerance: NEWTON_TOLERANCE,
        only: opts.only,
        structures,
        levels,
        ground,
    })
}

/// What wrote an exported model: `pounding` and its version.
pub(super) fn exported_by() -> String {
    format!("pounding {}", env!("CARGO_PKG_VERSION"))
}

/// Every contact level of `scenario` (a pair's, or a row's pair by pair) with its pair's law as
/// an OpenSees material, each with its pair (its left structure's index, 0-based); a refusal
/// with the pair whose law it concerns.
pub(super) fn export_levels(
    scenario: &Scenario,
) -> Result<Vec<(usize, ExportLevel)>, (usize, ExportError)> {
    let contacts: Vec<_> = scenario.contacts().collect();
    let system = scenario.system();
    system
        .levels
        .iter()
        .map(|lv| {
            let material =
                contact_material(&contacts[lv.pair].law, &lv.force, lv.gap, lv.effective_mass)
                    .map_err(|e| (lv.pair, e))?;
            let level = ExportLevel {
                height: lv.height,
                gap: lv.gap,
                material,
            };
            Ok((lv.pair, level))
        })
        .collect()
}

/// The options checked (elements, step, duration, number of steps); the simulated time, s.
pub(super) fn checked_duration(
    scenario: &Scenario,
    opts: &ExportOptions,
) -> Result<f64, ExportError> {
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
pub(super) fn export_ground(scenario: &Scenario, structures: &[ExportStructure]) -> ExportGround {
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

/// Structure `s` as OpenSees gets it, with a node at every height of `heights` (m) and a
/// cantilever meshed with `elements` elements; a kind OpenSees cannot be given, or a floor
/// structure whose contact is not at a floor, refused.
pub(super) fn export_structure(
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
}
