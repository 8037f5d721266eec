//! Building-code separation rules between two adjacent structures (issue 13).
//!
//! Each rule takes the two structures' displacements at the contact level *as the code defines
//! them* (see each variant) and, where a code needs them, their heights; it returns the
//! required separation in m with the per-structure terms, the code's name and the clause.
//! Sources, and what could not be verified against a retrievable text, are in `docs/codes.md`.
//!
//! Every rule is evaluated at one contact level; [`PairInput::floors_coincide`] says whether
//! that level is a floor of both structures, which EN 1998-1 §4.4.2.7(3) (× 0.7) and
//! IS 1893 §7.11.3 (R/2) reward.
//!
//! | rule | required separation |
//! |---|---|
//! | ASCE 7-16 §12.12.3, same property | `δ_MT = √(δ_M1² + δ_M2²)`, `δ_Mi = C_d,i δ_max,i / I_e,i` |
//! | ASCE 7-16 §12.12.3, property line | each set back by its own δ_Mi: gap `δ_M1 + δ_M2` |
//! | IS 1893 (Part 1):2016 §7.11.3 | `R (Δ₁ + Δ₂)`; R/2 where the floor levels coincide |
//! | EN 1998-1:2004 §4.4.2.7, same property | `√(d_s1² + d_s2²)`, `d_si = q_d,i d_e,i` (expression 4.23); × 0.7 where the floor elevations coincide |
//! | EN 1998-1:2004 §4.4.2.7, property line | each set back by its own d_si: gap `d_s1 + d_s2`; × 0.7 likewise |
//! | NBCC Art. 4.1.8.14 | `√(Δ₁² + Δ₂²)`, `Δ_i = δ_i R_d,i R_o,i / I_E,i` (Sentence 4.1.8.13.(2)) |
//! | GB 50011-2010 §6.1.4 | joint width by system, the lower height and the intensity |
//! | NTC-Sismo (Mexico City, 2004) §1.10 | `s₁ + s₂` (half if same height, system, slab levels), `s_i = max(50 mm, d_i + c h)` |

use serde::Serialize;

/// What is wrong with a code rule's parameters or input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CodeError {
    /// A factor that must be positive and finite is not.
    #[error("{code}: {name} of structure {structure} must be positive and finite, got {value}")]
    BadFactor {
        /// The code's short name.
        code: &'static str,
        /// The factor's name as the code writes it.
        name: &'static str,
        /// 1 or 2.
        structure: usize,
        /// The offending value.
        value: f64,
    },
    /// A displacement that is negative or not finite (peaks are magnitudes, m).
    #[error("{code}: displacement of structure {structure} must be finite and ≥ 0 m, got {value}")]
    BadDisplacement {
        /// The code's short name.
        code: &'static str,
        /// 1 or 2.
        structure: usize,
        /// The offending value, m.
        value: f64,
    },
    /// A height that is not positive and finite.
    #[error("{code}: height of structure {structure} must be positive and finite, got {value} m")]
    BadHeight {
        /// The code's short name.
        code: &'static str,
        /// 1 or 2.
        structure: usize,
        /// The offending value, m.
        value: f64,
    },
    /// A seismic intensity that GB 50011 §6.1.4 does not tabulate.
    #[error("GB 50011-2010 §6.1.4 gives joint widths for intensity 6, 7, 8 or 9, got {0}")]
    BadIntensity(u8),
}

/// The two structures' values at the contact level.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PairInput {
    /// Peak displacement of each structure at the contact level, m (≥ 0), in the sense the rule
    /// asks (see [`CodeRule`]: elastic displacement under the code's design forces).
    pub displacement: [f64; 2],
    /// Height of each structure (top above the base), m: used by GB 50011 only.
    pub height: [f64; 2],
    /// Height of the contact level above the ground on each structure, m: used by NTC-Sismo
    /// only.
    pub level: [f64; 2],
    /// The contact level is a floor of both structures (their floor elevations coincide
    /// there): EN 1998-1 §4.4.2.7(3) then allows × 0.7 and IS 1893 §7.11.3 R/2, each only when
    /// its `floor_reduction` is on. Never true where either structure has no floors.
    pub floors_coincide: bool,
}

/// Where the ASCE 7 separation is measured (§12.12.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Asce7Boundary {
    /// Adjacent structures on the same property: δ_MT = √(δ_M1² + δ_M2²) (Eq. 12.12-2).
    SameProperty,
    /// A property line between them (not common to a public way): each structure is set back
    /// from the line by its own δ_M, so the gap between them is δ_M1 + δ_M2.
    PropertyLine,
}

/// ASCE 7-16 §12.12.3 factors, per structure.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Asce7Params {
    /// Deflection amplification factor C_d of each structure (Table 12.2-1).
    pub cd: [f64; 2],
    /// Importance factor I_e of each structure (§11.5.1).
    pub ie: [f64; 2],
    /// Same property or property line.
    pub boundary: Asce7Boundary,
}

/// IS 1893 (Part 1):2016 §7.11.3 factor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Is1893Params {
    /// Response reduction factor R (Table 9) that multiplies the sum of the displacements. The
    /// clause names one R; for two systems with different R give the larger.
    pub r: f64,
    /// Replace R by R/2 where the floor levels coincide ([`PairInput::floors_coincide`]).
    pub floor_reduction: bool,
}

/// Where the EN 1998-1 separation is measured (§4.4.2.7(2)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Ec8Boundary {
    /// Buildings or units on the same property (§4.4.2.7(2)b): the SRSS of the two d_s.
    SameProperty,
    /// Not on the same property (§4.4.2.7(2)a): each building's own d_s to the property line,
    /// so the gap between the two is d_s1 + d_s2.
    PropertyLine,
}

/// EN 1998-1:2004 §4.4.2.7 factors, per structure.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ec8Params {
    /// Displacement behaviour factor q_d of each structure (§4.3.4: q unless otherwise
    /// specified): d_s = q_d d_e (expression 4.23).
    pub qd: [f64; 2],
    /// Same property or property line.
    pub boundary: Ec8Boundary,
    /// Reduce by 0.7 where the floor elevations coincide (§4.4.2.7(3),
    /// [`PairInput::floors_coincide`]).
    pub floor_reduction: bool,
}

/// NBCC Article 4.1.8.14 factors, per structure (Sentence 4.1.8.13.(2)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NbccParams {
    /// Ductility-related force modification factor R_d of each structure.
    pub rd: [f64; 2],
    /// Overstrength-related force modification factor R_o of each structure.
    pub ro: [f64; 2],
    /// Earthquake importance factor I_E of each structure.
    pub ie: [f64; 2],
}

/// Structural system of a reinforced-concrete building in GB 50011-2010 §6.1.4.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum GbSystem {
    /// Frame (including frames with a few seismic walls): the base width.
    Frame,
    /// Frame–seismic-wall (frame–shear-wall): 70 % of the frame width.
    FrameShearWall,
    /// Seismic-wall (shear-wall): 50 % of the frame width.
    ShearWall,
}

impl GbSystem {
    /// Fraction of the frame width: 1, 0.7, 0.5.
    pub fn fraction(self) -> f64 {
        match self {
            GbSystem::Frame => 1.0,
            GbSystem::FrameShearWall => 0.7,
            GbSystem::ShearWall => 0.5,
        }
    }
}

/// How a height above 15 m that is not a whole number of steps is counted (§6.1.4 says "for
/// every further 5/4/3/2 m, 20 mm wider" and does not say; see docs/codes.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum PartialStep {
    /// A started step counts as a whole step (conservative; the default).
    RoundUp,
    /// 20 mm per step in proportion (linear in the height).
    Linear,
}

/// GB 50011-2010 §6.1.4 parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Gb50011Params {
    /// Seismic fortification intensity: 6, 7, 8 or 9.
    pub intensity: u8,
    /// Structural system on each side of the joint.
    pub system: [GbSystem; 2],
    /// Counting of partial height steps.
    pub partial_step: PartialStep,
}

/// Mexico City seismic zone (NTC-Sismo 2004): I (firm ground), II (transition), III (lake bed).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum NtcZone {
    /// Zone I.
    I,
    /// Zone II.
    II,
    /// Zone III.
    III,
}

/// How the NTC-Sismo displacements were obtained (§1.10 gives a rule for each).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum NtcMethod {
    /// Static or dynamic analysis: `s = max(50 mm, d + c h)`, c = 0.001, 0.003, 0.006 in
    /// zones I, II, III.
    Analysis,
    /// The simplified method of seismic analysis: `s = max(50 mm, k h)`, k = 0.007, 0.009,
    /// 0.012 in zones I, II, III (no displacement used).
    Simplified,
}

/// NTC-Sismo (Normas Técnicas Complementarias para Diseño por Sismo, Mexico City, 2004) §1.10.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NtcParams {
    /// Seismic zone.
    pub zone: NtcZone,
    /// Analysis or simplified method.
    pub method: NtcMethod,
    /// Both bodies have the same height and structuring and their slabs coincide at every
    /// level: half the sum is allowed.
    pub same_height_and_levels: bool,
}

/// A code separation rule with its parameters: a closed set.
///
/// The displacements of [`PairInput`] are, per rule:
/// - `Asce7`: δ_max, the elastic displacement at the critical location under the design
///   forces (§12.8.6 / §12.9.1.2: the elastic demand × I_e/R), m;
/// - `Is1893`: Δ, the displacement under the design lateral force (§7.11.1), m;
/// - `Ec8`: d_e, the displacement from the linear analysis on the design spectrum of
///   §3.2.2.5 (§4.3.4), m;
/// - `Nbcc`: the elastic lateral deflection from the linear analysis under the design forces
///   (before × R_dR_o/I_E), m;
/// - `Gb50011`: not used (the joint width depends on system, height and intensity only);
/// - `NtcSismo`: the horizontal displacement calculated for the level (including the overall
///   flexure and base rotation when significant), m; not used by the simplified method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum CodeRule {
    /// ASCE 7-16 §12.12.3.
    Asce7(Asce7Params),
    /// IS 1893 (Part 1):2016 §7.11.3.
    Is1893(Is1893Params),
    /// NBCC Article 4.1.8.14.
    Nbcc(NbccParams),
    /// GB 50011-2010 §6.1.4 (reinforced-concrete buildings).
    Gb50011(Gb50011Params),
    /// NTC-Sismo 2004 (Mexico City) §1.10.
    NtcSismo(NtcParams),
    /// EN 1998-1:2004 §4.4.2.7 with §4.3.4.
    Ec8(Ec8Params),
}

/// The separation a code requires, with its terms.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CodeSeparation {
    /// Short key: "asce7", "is1893", "nbcc", "gb50011", "ntc" (CLI flags, sweep columns
    /// `sep_<key>`).
    pub key: &'static str,
    /// Code name, e.g. "ASCE 7-16".
    pub name: &'static str,
    /// Clause, e.g. "§12.12.3, Eqs. (12.12-1), (12.12-2)".
    pub clause: &'static str,
    /// Required separation, m.
    pub required: f64,
    /// Per-structure terms, m: δ_M (ASCE 7), R Δ (IS 1893), R_dR_oΔ/I_E (NBCC), the joint width
    /// each side's own system and height would need (GB 50011), each side's distance to the
    /// property line s_i (NTC-Sismo), d_s = q_d d_e (EN 1998-1) — before any reduction for
    /// coinciding floors.
    pub terms: [f64; 2],
    /// The reduction applied for coinciding floor levels, in words (`None`: none applied).
    pub reduction: Option<&'static str>,
}

impl CodeRule {
    /// Short key: "asce7", "is1893", "nbcc", "gb50011", "ntc".
    pub fn key(&self) -> &'static str {
        match self {
            CodeRule::Asce7(_) => "asce7",
            CodeRule::Is1893(_) => "is1893",
            CodeRule::Nbcc(_) => "nbcc",
            CodeRule::Gb50011(_) => "gb50011",
            CodeRule::NtcSismo(_) => "ntc",
            CodeRule::Ec8(_) => "ec8",
        }
    }

    /// The code's name for reports.
    pub fn name(&self) -> &'static str {
        match self {
            CodeRule::Asce7(_) => "ASCE 7-16",
            CodeRule::Is1893(_) => "IS 1893 (Part 1):2016",
            CodeRule::Nbcc(_) => "NBCC",
            CodeRule::Gb50011(_) => "GB 50011-2010",
            CodeRule::NtcSismo(_) => "NTC-Sismo 2004 (Mexico City)",
            CodeRule::Ec8(_) => "EN 1998-1:2004",
        }
    }

    /// The clause the rule comes from.
    pub fn clause(&self) -> &'static str {
        match self {
            CodeRule::Asce7(p) => match p.boundary {
                Asce7Boundary::SameProperty => "§12.12.3, Eqs. (12.12-1), (12.12-2)",
                Asce7Boundary::PropertyLine => "§12.12.3, Eq. (12.12-1), property line",
            },
            CodeRule::Is1893(_) => "§7.11.3",
            CodeRule::Nbcc(_) => "Art. 4.1.8.14 with Sentence 4.1.8.13.(2)",
            CodeRule::Gb50011(_) => "§6.1.4 item 1",
            CodeRule::NtcSismo(_) => "§1.10",
            CodeRule::Ec8(p) => match p.boundary {
                Ec8Boundary::SameProperty => "§4.4.2.7(2)b, expression (4.23)",
                Ec8Boundary::PropertyLine => "§4.4.2.7(2)a, expression (4.23), property line",
            },
        }
    }

    /// The required separation for `input`, m.
    pub fn required_separation(&self, input: &PairInput) -> Result<CodeSeparation, CodeError> {
        let key = self.key();
        let mut reduction = None;
        let (required, terms) = match self {
            CodeRule::Asce7(p) => {
                let d = displacements(key, input)?;
                let mut dm = [0.0; 2];
                for i in 0..2 {
                    factor(key, "C_d", i, p.cd[i])?;
                    factor(key, "I_e", i, p.ie[i])?;
                    dm[i] = p.cd[i] * d[i] / p.ie[i];
                }
                let required = match p.boundary {
                    Asce7Boundary::SameProperty => dm[0].hypot(dm[1]),
                    Asce7Boundary::PropertyLine => dm[0] + dm[1],
                };
                (required, dm)
            }
            CodeRule::Is1893(p) => {
                let d = displacements(key, input)?;
                factor(key, "R", 0, p.r)?;
                let t = [p.r * d[0], p.r * d[1]];
                // §7.11.3: R may be replaced by R/2 where the floor levels coincide
                let half = p.floor_reduction && input.floors_coincide;
                if half {
                    reduction = Some("R/2: the floor levels of both coincide here (§7.11.3)");
                }
                let sum = t[0] + t[1];
                (if half { 0.5 * sum } else { sum }, t)
            }
            CodeRule::Ec8(p) => {
                let d = displacements(key, input)?;
                let mut ds = [0.0; 2];
                for i in 0..2 {
                    factor(key, "q_d", i, p.qd[i])?;
                    ds[i] = p.qd[i] * d[i];
                }
                let distance = match p.boundary {
                    Ec8Boundary::SameProperty => ds[0].hypot(ds[1]),
                    Ec8Boundary::PropertyLine => ds[0] + ds[1],
                };
                // §4.4.2.7(3): × 0.7 where the floor elevations coincide
                let reduce = p.floor_reduction && input.floors_coincide;
                if reduce {
                    reduction =
                        Some("× 0.7: the floor elevations of both coincide here (§4.4.2.7(3))");
                }
                (if reduce { 0.7 * distance } else { distance }, ds)
            }
            CodeRule::Nbcc(p) => {
                let d = displacements(key, input)?;
                let mut t = [0.0; 2];
                for i in 0..2 {
                    factor(key, "R_d", i, p.rd[i])?;
                    factor(key, "R_o", i, p.ro[i])?;
                    factor(key, "I_E", i, p.ie[i])?;
                    t[i] = d[i] * p.rd[i] * p.ro[i] / p.ie[i];
                }
                (t[0].hypot(t[1]), t)
            }
            CodeRule::Gb50011(p) => {
                for i in 0..2 {
                    let h = input.height[i];
                    if !(h.is_finite() && h > 0.0) {
                        return Err(CodeError::BadHeight {
                            code: key,
                            structure: i + 1,
                            value: h,
                        });
                    }
                }
                let own = [
                    gb50011_width(p.intensity, p.system[0], input.height[0], p.partial_step)?,
                    gb50011_width(p.intensity, p.system[1], input.height[1], p.partial_step)?,
                ];
                // §6.1.4 item 1(3): different systems on the two sides — the system needing the
                // wider joint, and the lower building's height.
                let wider = if p.system[0].fraction() >= p.system[1].fraction() {
                    p.system[0]
                } else {
                    p.system[1]
                };
                let lower = input.height[0].min(input.height[1]);
                let required = gb50011_width(p.intensity, wider, lower, p.partial_step)?;
                (required, own)
            }
            CodeRule::NtcSismo(p) => {
                let d = match p.method {
                    NtcMethod::Analysis => displacements(key, input)?,
                    NtcMethod::Simplified => [0.0; 2],
                };
                // c for the analysis rule, k for the simplified method (zones I, II, III)
                let (c, k) = match p.zone {
                    NtcZone::I => (0.001, 0.007),
                    NtcZone::II => (0.003, 0.009),
                    NtcZone::III => (0.006, 0.012),
                };
                let mut s = [0.0; 2];
                for (i, si) in s.iter_mut().enumerate() {
                    let h = input.level[i];
                    if !(h.is_finite() && h >= 0.0) {
                        return Err(CodeError::BadHeight {
                            code: key,
                            structure: i + 1,
                            value: h,
                        });
                    }
                    let own = match p.method {
                        NtcMethod::Analysis => d[i] + c * h,
                        NtcMethod::Simplified => k * h,
                    };
                    *si = own.max(0.050);
                }
                let sum = s[0] + s[1];
                (
                    if p.same_height_and_levels {
                        0.5 * sum
                    } else {
                        sum
                    },
                    s,
                )
            }
        };
        Ok(CodeSeparation {
            key,
            name: self.name(),
            clause: self.clause(),
            required,
            terms,
            reduction,
        })
    }
}

/// GB 50011-2010 §6.1.4 item 1 joint width for one system and height, m:
/// frame `100 mm` up to 15 m, `+20 mm` for every further 5, 4, 3, 2 m at intensity 6, 7, 8, 9;
/// frame–shear-wall 70 % and shear-wall 50 % of that, and neither below 100 mm.
pub fn gb50011_width(
    intensity: u8,
    system: GbSystem,
    height: f64,
    partial: PartialStep,
) -> Result<f64, CodeError> {
    let step = match intensity {
        6 => 5.0,
        7 => 4.0,
        8 => 3.0,
        9 => 2.0,
        other => return Err(CodeError::BadIntensity(other)),
    };
    if !(height.is_finite() && height > 0.0) {
        return Err(CodeError::BadHeight {
            code: "gb50011",
            structure: 1,
            value: height,
        });
    }
    let steps = if height <= 15.0 {
        0.0
    } else {
        let s = (height - 15.0) / step;
        match partial {
            PartialStep::RoundUp => s.ceil(),
            PartialStep::Linear => s,
        }
    };
    let frame_mm = 100.0 + 20.0 * steps;
    Ok((system.fraction() * frame_mm).max(100.0) / 1000.0)
}

fn displacements(code: &'static str, input: &PairInput) -> Result<[f64; 2], CodeError> {
    for (i, &d) in input.displacement.iter().enumerate() {
        if !(d.is_finite() && d >= 0.0) {
            return Err(CodeError::BadDisplacement {
                code,
                structure: i + 1,
                value: d,
            });
        }
    }
    Ok(input.displacement)
}

fn factor(code: &'static str, name: &'static str, i: usize, v: f64) -> Result<(), CodeError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(CodeError::BadFactor {
            code,
            name,
            structure: i + 1,
            value: v,
        })
    }
}
