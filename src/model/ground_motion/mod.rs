//! Ground motion: the acceleration a_g(t) and velocity v_g(t) that both structures' bases share
//! (docs/model.md §2.8). Harmonic motion is given by its PGA and period; recorded motion by a file:
//! [`record`] (the signal model), [`formats`] (one reader per layout, a dispatcher that detects
//! the layout from the content), [`processing`] (baseline correction and band-pass of
//! uncorrected records), [`scale`] (`scale_to_pga`, `scale_to_sa` and what was applied), [`sdof`] (the exact oscillator under a record: spectral accelerations,
//! for `scale_to_sa` and the response spectra), [`error`] (diagnostics); what `pounding record` prints is
//! [`crate::output::record_summary`].

pub mod error;
pub mod formats;
pub mod processing;
pub mod record;
pub mod scale;
pub mod sdof;

pub use error::{Location, RecordError};
pub use processing::{Baseline, Processing};
pub use record::{
    AccelUnits, Component, Record, RecordFormat, RecordOptions, STANDARD_GRAVITY, StatedPeak,
};
pub use scale::{RecordScaling, SaTarget, ScaleTarget};

use std::f64::consts::PI;
use std::sync::Arc;

/// Harmonic ground displacement `y = A sin(ω_g t)` with `A = PGA/ω_g²` (docs/model.md §2.8, paper eq. 3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    /// Peak ground acceleration, m/s².
    pub pga: f64,
    /// Circular frequency ω_g = 2π/T_g, rad/s.
    pub omega: f64,
}

impl Harmonic {
    /// From PGA in g and period T_g in s.
    pub fn from_pga_g(pga_g: f64, period: f64) -> Harmonic {
        Harmonic {
            pga: pga_g * STANDARD_GRAVITY,
            omega: 2.0 * PI / period,
        }
    }

    /// Displacement amplitude A = PGA/ω_g², m.
    pub fn amplitude(&self) -> f64 {
        self.pga / (self.omega * self.omega)
    }

    /// Period T_g, s.
    pub fn period(&self) -> f64 {
        2.0 * PI / self.omega
    }
}

/// The ground motion shared by both structures. A closed set, matched in the solver's step.
#[derive(Debug, Clone, PartialEq)]
pub enum GroundMotion {
    /// No shaking (free vibration from the initial state).
    None,
    /// Sinusoidal motion.
    Harmonic(Harmonic),
    /// A recorded accelerogram, linear between samples, zero after its end. Shared, so that
    /// sweeps over thousands of cases do not copy it.
    Record(Arc<Record>),
}

impl GroundMotion {
    /// Ground acceleration a_g (m/s²) and velocity v_g (m/s) at time t (s).
    #[inline]
    pub fn accel_velocity(&self, t: f64) -> (f64, f64) {
        match self {
            GroundMotion::None => (0.0, 0.0),
            GroundMotion::Harmonic(h) => {
                // y = A sin ωt: ÿ = −PGA sin ωt, ẏ = (PGA/ω) cos ωt
                let (s, c) = (h.omega * t).sin_cos();
                (-h.pga * s, h.pga / h.omega * c)
            }
            GroundMotion::Record(r) => r.accel_and_velocity_at(t),
        }
    }

    /// Peak ground acceleration, m/s².
    pub fn pga(&self) -> f64 {
        match self {
            GroundMotion::None => 0.0,
            GroundMotion::Harmonic(h) => h.pga,
            GroundMotion::Record(r) => r.pga(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// a_g is the second derivative of y = A sin ωt and v_g the first (central differences).
    #[test]
    fn harmonic_derivatives_are_consistent() {
        let h = Harmonic::from_pga_g(0.6, 0.65);
        let g = GroundMotion::Harmonic(h);
        let a = h.amplitude();
        let y = |t: f64| a * (h.omega * t).sin();
        let e = 1e-4;
        for &t in &[0.0, 0.1, 0.37, 1.9] {
            let (acc, vel) = g.accel_velocity(t);
            let v_fd = (y(t + e) - y(t - e)) / (2.0 * e);
            let a_fd = (y(t + e) - 2.0 * y(t) + y(t - e)) / (e * e);
            assert!((vel - v_fd).abs() < 1e-6 * h.pga / h.omega);
            assert!((acc - a_fd).abs() < 1e-4 * h.pga);
        }
        assert!((g.pga() - 0.6 * 9.80665).abs() < 1e-12);
    }
}
