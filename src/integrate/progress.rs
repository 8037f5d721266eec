//! The guard every error-controlled integrator's loop runs under: a step that cannot be made
//! ends the run with a [`SolveError::StepFailed`] that names the instant, the contact level and
//! the method, never with a loop that does not return.
//!
//! Each integrator bounds its own retries (a rejected step is retried shorter, down to a
//! shortest length, then [`SolveError::ToleranceUnreachable`]); this guard bounds what those
//! bounds cannot see: a retry that does not shrink (more than [`MAX_REJECTIONS`] rejections in
//! a row), an accepted step that does not move time forward, and a sequence of steps each
//! shorter than time's resolution ([`MAX_STALLS`] in a row), where a deterministic integrator
//! would repeat itself without end.

use super::{Method, SolveError};
use crate::model::system::{LevelState, System};

/// Rejected trials in a row at one instant before the run stops. Every integrator shortens a
/// rejected step by at least one of its quantised lengths and stops at its shortest (`adaptive`
/// 120 lengths, `exact-modal` 160): more rejections than that mean a retry that does not shrink.
pub(crate) const MAX_REJECTIONS: u32 = 256;

/// Loop iterations in a row that move time by less than [`time_floor`] before the run stops.
/// A step that short (≈1e-13 s at t ≈ 10 s) resolves a frequency of ~1e13 rad/s: no contact
/// law of the scenario format comes near it, so a thousand in a row is a stall, not physics.
pub(crate) const MAX_STALLS: u32 = 1000;

/// Why an error-controlled method could not make a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepFailure {
    /// An accepted step did not move time forward (its length is below the resolution of t).
    NoProgress,
    /// `MAX_STALLS` steps in a row each moved time by less than its resolution.
    Stalled,
    /// `MAX_REJECTIONS` trials in a row were rejected at one instant.
    Rejected,
}

impl std::fmt::Display for StepFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepFailure::NoProgress => write!(
                f,
                "its step fell below the resolution of time there and did not advance it"
            ),
            StepFailure::Stalled => write!(
                f,
                "{MAX_STALLS} steps in a row each advanced time by less than its resolution"
            ),
            StepFailure::Rejected => write!(
                f,
                "{MAX_REJECTIONS} trial steps in a row were rejected without the step shrinking"
            ),
        }
    }
}

/// The shortest advance of time that counts as progress at time `t` of a run with base step
/// `dt`, s: 64 units in the last place of t (and of dt, near t = 0). A step shorter than this
/// cannot be told from its start in the time it ends at.
pub(crate) fn time_floor(t: f64, dt: f64) -> f64 {
    64.0 * f64::EPSILON * (t.abs() + dt)
}

/// The contact level a failed step is named by (0-based): the deepest penetrating one — the
/// contact the step was resolving — or, with none in contact, the one closest to contact;
/// `None` without contact levels.
pub(crate) fn governing_level(states: &[LevelState]) -> Option<usize> {
    (0..states.len()).max_by(|&a, &b| states[a].delta.total_cmp(&states[b].delta))
}

/// Counts of the current run of rejections and of stalled steps (see the module's comment).
#[derive(Debug, Clone)]
pub(crate) struct Progress {
    method: Method,
    rejections: u32,
    stalls: u32,
}

impl Progress {
    /// A fresh guard for a run of `method`.
    pub(crate) fn new(method: Method) -> Progress {
        Progress {
            method,
            rejections: 0,
            stalls: 0,
        }
    }

    /// The error for a step (last length `h`, s) that could not be made at `t` (s).
    pub(crate) fn failure(
        &self,
        sys: &System,
        states: &[LevelState],
        t: f64,
        h: f64,
        reason: StepFailure,
    ) -> SolveError {
        let level = governing_level(states);
        SolveError::StepFailed {
            method: self.method.name(),
            t,
            level: level.map(|k| k + 1),
            height: level.map(|k| sys.levels[k].height),
            h,
            reason,
            alternative: match self.method {
                Method::ExactModal => Method::Adaptive.name(),
                _ => Method::ExactModal.name(),
            },
        }
    }

    /// A trial of length `h` rejected at `t`: an error after [`MAX_REJECTIONS`] in a row.
    #[inline]
    pub(crate) fn rejected(
        &mut self,
        sys: &System,
        states: &[LevelState],
        t: f64,
        h: f64,
    ) -> Result<(), SolveError> {
        self.rejections += 1;
        if self.rejections > MAX_REJECTIONS {
            return Err(self.failure(sys, states, t, h, StepFailure::Rejected));
        }
        Ok(())
    }

    /// A step of length `h` about to be accepted from `t0` to `t1` (s): an error if it does
    /// not move time forward (checked before the state is touched).
    #[inline]
    pub(crate) fn accepting(
        &mut self,
        sys: &System,
        states: &[LevelState],
        t0: f64,
        t1: f64,
        h: f64,
    ) -> Result<(), SolveError> {
        self.rejections = 0;
        if t1 <= t0 || t1.is_nan() {
            return Err(self.failure(sys, states, t0, h, StepFailure::NoProgress));
        }
        Ok(())
    }

    /// One pass of the integrator's main loop moved time from `t0` to `t1` (s; base step `dt`):
    /// an error after [`MAX_STALLS`] passes in a row shorter than [`time_floor`]. (A pass may
    /// legitimately not move time — a free flight that finds contact starting now — but not
    /// many in a row.)
    #[inline]
    pub(crate) fn passed(
        &mut self,
        sys: &System,
        states: &[LevelState],
        t0: f64,
        t1: f64,
        dt: f64,
    ) -> Result<(), SolveError> {
        if t1 - t0 >= time_floor(t0, dt) {
            self.stalls = 0;
            return Ok(());
        }
        self.stalls += 1;
        if self.stalls > MAX_STALLS {
            return Err(self.failure(sys, states, t1, t1 - t0, StepFailure::Stalled));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::scenario::Scenario;

    /// Two cantilevers with contact levels at 10 m and 6 m.
    fn system() -> System {
        let text = "[[structure]]\nlength = 10.0\nmass = 2.273e6\nperiod = 0.3\n\
             damping_ratio = 0.01\n[[structure]]\nlength = 10.0\nmass = 2.273e6\n\
             period = 0.6\ndamping_ratio = 0.01\n[contact]\nlaw = \"hertz\"\n\
             stiffness = 2.8e10\n[[contact.level]]\nheight = 10.0\ngap = 0.01\n\
             [[contact.level]]\nheight = 6.0\ngap = 0.01\n[ground_motion]\n\
             kind = \"harmonic\"\npga = 0.5\nperiod = 0.8\n";
        Scenario::from_toml(text, "case.toml", std::path::Path::new("."))
            .expect("valid scenario")
            .system()
    }

    /// The level at 6 m penetrating, the one at 10 m open.
    fn states() -> Vec<LevelState> {
        vec![
            LevelState {
                delta: -0.003,
                ..LevelState::default()
            },
            LevelState {
                delta: 0.002,
                delta_dot: 0.1,
                force: 1e6,
            },
        ]
    }

    /// Each bound fires exactly past its count, names the method, the time, the penetrating
    /// level and the other method, and an advancing step resets the counts.
    #[test]
    fn every_bound_stops_the_run_past_its_count() {
        let (sys, st) = (system(), states());
        let mut p = Progress::new(Method::Adaptive);
        for _ in 0..MAX_REJECTIONS {
            p.rejected(&sys, &st, 3.0, 1e-9).expect("within the bound");
        }
        let e = p
            .rejected(&sys, &st, 3.0, 1e-9)
            .expect_err("past the bound");
        assert_eq!(
            e,
            SolveError::StepFailed {
                method: "adaptive",
                t: 3.0,
                level: Some(2),
                height: Some(6.0),
                h: 1e-9,
                reason: StepFailure::Rejected,
                alternative: "exact-modal",
            }
        );
        let msg = e.to_string();
        for part in [
            "adaptive could not advance",
            "t = 3.000000000 s",
            "level 2 (h = 6 m)",
        ] {
            assert!(msg.contains(part), "{part} in {msg}");
        }
        // an accepted step resets the rejections
        p.accepting(&sys, &st, 3.0, 3.001, 1e-3).expect("advances");
        p.rejected(&sys, &st, 3.001, 1e-3).expect("counted from 0");
        // a step that does not move time, or moves it to NaN
        let mut p = Progress::new(Method::ExactModal);
        for t1 in [3.0, 3.0 + 1e-17, 2.0, f64::NAN] {
            let e = p
                .accepting(&sys, &st, 3.0, t1, 1e-17)
                .expect_err("no progress");
            assert!(
                matches!(
                    e,
                    SolveError::StepFailed {
                        reason: StepFailure::NoProgress,
                        alternative: "adaptive",
                        ..
                    }
                ),
                "{e}"
            );
        }
        // passes shorter than time's resolution: MAX_STALLS in a row pass, one more fails;
        // one pass of a normal length in between resets the count
        let floor = time_floor(3.0, 1e-3);
        assert!(floor > 3.0 * f64::EPSILON && floor < 1e-13, "{floor}");
        for i in 0..2 * MAX_STALLS {
            let t1 = if i == MAX_STALLS { 3.0 + 1e-3 } else { 3.0 };
            p.passed(&sys, &st, 3.0, t1, 1e-3)
                .expect("within the bound");
        }
        let mut p = Progress::new(Method::ExactModal);
        for _ in 0..MAX_STALLS {
            p.passed(&sys, &st, 3.0, 3.0 + 0.5 * floor, 1e-3)
                .expect("within the bound");
        }
        let e = p
            .passed(&sys, &st, 3.0, 3.0 + 0.5 * floor, 1e-3)
            .expect_err("stalled");
        assert!(
            matches!(
                e,
                SolveError::StepFailed {
                    reason: StepFailure::Stalled,
                    ..
                }
            ),
            "{e}"
        );
        // without contact levels: no level named
        assert_eq!(governing_level(&[]), None);
    }
}
