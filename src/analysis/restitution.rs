//! Achieved coefficient of restitution of a contact law, measured on an isolated two-body
//! impact through the real solver: two one-mode cantilevers so soft (T = 1000 s) that their
//! springs do nothing during the contact, meeting at their tips with approach speed v.
//!
//! Several laws are derived for an idealised impact (Lankarani–Nikravesh for e near 1, the
//! Kelvin damping coefficient for a spring-dashpot that may pull), so the restitution they achieve
//! differs from the `restitution` they are given; this measures it.

use crate::integrate::{
    InitialState, Method, Observer, SolveError, SolverSettings, StepView, integrate,
};
use crate::model::contact::{ContactLaw, HertzDampModel};
use crate::model::ground_motion::GroundMotion;
use crate::model::structure::{Cantilever, Damping, Stiffness};
use crate::model::system::{ContactLevel, System};
use crate::recording::recorder::Recorder;

/// What an isolated impact gave.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactOutcome {
    /// Approach speed v, m/s.
    pub approach_speed: f64,
    /// Separation speed over approach speed.
    pub restitution: f64,
    /// Contact duration, s (0 for the stereomechanical law).
    pub duration: f64,
    /// Peak force, N (0 for the stereomechanical law).
    pub peak_force: f64,
    /// Drop of the structures' mechanical energy over the impact, J.
    pub energy_drop: f64,
    /// Energy the solver booked as dissipated in the contact, J.
    pub contact_dissipated: f64,
    /// Effective mass m* at the contact point, kg.
    pub effective_mass: f64,
}

/// Estimated contact duration, s, of an elastic impact with this law's stiffness.
fn duration_estimate(law: &ContactLaw, m_star: f64, v: f64) -> f64 {
    let hertz = |k: f64| 2.9432 * (5.0 * m_star * v * v / (4.0 * k)).powf(0.4) / v;
    match *law {
        ContactLaw::Linear { stiffness } | ContactLaw::Kelvin { stiffness, .. } => {
            std::f64::consts::PI * (m_star / stiffness).sqrt()
        }
        ContactLaw::Hertz { stiffness }
        | ContactLaw::HertzDamp { stiffness, .. }
        | ContactLaw::Jankowski { stiffness, .. } => hertz(stiffness),
        ContactLaw::Stereomechanical { .. } => 1e-3,
    }
}

struct Tip {
    phi: [f64; 2],
    relative_velocity: f64,
    energy: f64,
}

/// The recorder (impact events, energy balance) and the tip probe, fed by one integration.
struct Probe {
    recorder: Recorder<'static>,
    tip: Tip,
}

impl Observer for Probe {
    fn observe(&mut self, sys: &System, s: &StepView) {
        self.recorder.observe(sys, s);
        self.tip.relative_velocity = self.tip.phi[0] * s.v[0] - self.tip.phi[1] * s.v[1];
        self.tip.energy = sys.modal_energy(s.q, s.v);
    }
}

/// Impact of two bodies of tip masses `m1/4`, `m2/4` (cantilevers of total mass m1, m2, kg)
/// approaching at `v` m/s through `law`.
pub fn isolated_impact(
    law: &ContactLaw,
    m1: f64,
    m2: f64,
    v: f64,
) -> Result<ImpactOutcome, SolveError> {
    let beam = |mass: f64| Cantilever {
        name: "body".into(),
        length: 10.0,
        mass,
        stiffness: Stiffness::Period(1000.0),
        modes: 1,
        damping: Damping::Modal(vec![0.0]),
    };
    let sys = System::new(
        [beam(m1).modal(), beam(m2).modal()],
        law,
        &[ContactLevel {
            height: 10.0,
            gap: 0.0,
        }],
        GroundMotion::None,
    );
    let m_star = sys.levels[0].effective_mass;
    let t_c = duration_estimate(law, m_star, v);
    let settings = SolverSettings::new(Method::Rk4, t_c / 4000.0, 3.0 * t_c);
    let phi = [
        sys.structures[0].shape(0, 10.0),
        sys.structures[1].shape(0, 10.0),
    ];
    let init = InitialState {
        q: vec![0.0, 0.0],
        v: vec![v / phi[0], 0.0],
    };
    let mut probe = Probe {
        recorder: Recorder::new(&sys, &[10.0], settings.duration, settings.duration),
        tip: Tip {
            phi,
            relative_velocity: 0.0,
            energy: 0.0,
        },
    };
    integrate(&sys, &settings, &init, &mut probe)?;
    let (rec, tip) = (probe.recorder.finish(), probe.tip);
    let e0 = 0.5 * (v / phi[0]).powi(2);
    let (duration, peak_force) = rec
        .impacts
        .first()
        .map_or((0.0, 0.0), |i| (i.end - i.start, i.peak_force));
    Ok(ImpactOutcome {
        approach_speed: v,
        restitution: -tip.relative_velocity / v,
        duration,
        peak_force,
        energy_drop: e0 - tip.energy,
        contact_dissipated: rec.energy.contact_dissipated,
        effective_mass: m_star,
    })
}

/// The laws that take a target restitution e.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TargetLaw {
    /// Kelvin–Voigt.
    Kelvin,
    /// Damped Hertz with a hysteresis model.
    HertzDamp(HertzDampModel),
    /// Jankowski's nonlinear viscoelastic law.
    Jankowski,
    /// Instantaneous impact.
    Stereomechanical,
}

impl TargetLaw {
    /// Every such law.
    pub const ALL: [TargetLaw; 6] = [
        TargetLaw::Kelvin,
        TargetLaw::HertzDamp(HertzDampModel::LankaraniNikravesh),
        TargetLaw::HertzDamp(HertzDampModel::HuntCrossley),
        TargetLaw::HertzDamp(HertzDampModel::YeLiZhu),
        TargetLaw::Jankowski,
        TargetLaw::Stereomechanical,
    ];

    /// Label, as in scenario files.
    pub fn label(self) -> String {
        match self {
            TargetLaw::HertzDamp(m) => format!("hertzdamp ({})", m.name()),
            TargetLaw::Kelvin => "kelvin".into(),
            TargetLaw::Jankowski => "jankowski".into(),
            TargetLaw::Stereomechanical => "stereomechanical".into(),
        }
    }

    /// The law for target restitution `e`, with stiffness `k_hertz` (N/m^1.5) for the Hertz
    /// family and `k_linear` (N/m) for Kelvin.
    pub fn law(self, e: f64, k_hertz: f64, k_linear: f64) -> ContactLaw {
        match self {
            TargetLaw::Kelvin => ContactLaw::Kelvin {
                stiffness: k_linear,
                restitution: e,
            },
            TargetLaw::HertzDamp(model) => ContactLaw::HertzDamp {
                stiffness: k_hertz,
                restitution: e,
                model,
            },
            TargetLaw::Jankowski => ContactLaw::Jankowski {
                stiffness: k_hertz,
                restitution: e,
            },
            TargetLaw::Stereomechanical => ContactLaw::Stereomechanical { restitution: e },
        }
    }
}

/// The target restitutions of `pounding laws`' table (columns).
pub const TABLE_TARGETS: [f64; 8] = [0.3, 0.4, 0.5, 0.6, 0.65, 0.7, 0.8, 0.9];
/// The Hertz-family stiffness of the table, N/m^1.5: the seed paper's k_h. The laws are
/// scale-free, so the achieved e does not depend on it.
pub const TABLE_K_HERTZ: f64 = 2.808e10;
/// Kelvin's linear stiffness of the table, N/m.
pub const TABLE_K_LINEAR: f64 = 1.0e9;
/// The two cantilevers' masses of the table, kg (unequal, so that a law's dependence on the
/// mass ratio would show).
pub const TABLE_MASSES: [f64; 2] = [1.0e6, 3.0e6];

/// The achieved restitution of every [`TargetLaw`] at every target of [`TABLE_TARGETS`]
/// (what `pounding laws` prints).
#[derive(Debug, Clone, PartialEq)]
pub struct RestitutionTable {
    /// Approach speed, m/s.
    pub speed: f64,
    /// The target restitutions, the columns.
    pub targets: Vec<f64>,
    /// Per law (in the order of [`TargetLaw::ALL`]), the achieved e at each target.
    pub rows: Vec<(TargetLaw, Vec<f64>)>,
}

/// Measures [`RestitutionTable`] at approach speed `speed` (m/s, finite and > 0) through
/// [`isolated_impact`].
pub fn restitution_table(speed: f64) -> Result<RestitutionTable, SolveError> {
    let [m1, m2] = TABLE_MASSES;
    let rows = TargetLaw::ALL
        .iter()
        .map(|&law| {
            let achieved = TABLE_TARGETS
                .iter()
                .map(|&e| {
                    let l = law.law(e, TABLE_K_HERTZ, TABLE_K_LINEAR);
                    isolated_impact(&l, m1, m2, speed).map(|o| o.restitution)
                })
                .collect::<Result<Vec<f64>, SolveError>>()?;
            Ok((law, achieved))
        })
        .collect::<Result<Vec<_>, SolveError>>()?;
    Ok(RestitutionTable {
        speed,
        targets: TABLE_TARGETS.to_vec(),
        rows,
    })
}
