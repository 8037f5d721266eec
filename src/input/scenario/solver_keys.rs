//! `[solver]`: the method, steps, tolerances, duration and output interval, checked into
//! [`SolverSettings`].

use toml::Spanned;

use crate::integrate::{ATOL_PER_RTOL, MIN_ATOL, MIN_RTOL, Method, SolverSettings};
use crate::model::ground_motion::GroundMotion;

use super::RawSolver;
use super::diagnostics::{Check, ScenarioError, quoted};
use super::{DEFAULT_DT, DEFAULT_HARMONIC_DURATION};

pub(super) fn solver(
    c: &Check,
    raw: Option<&Spanned<RawSolver>>,
    ground: &GroundMotion,
    yielding: bool,
    defaults: &mut Vec<String>,
) -> Result<(SolverSettings, f64), ScenarioError> {
    let empty = RawSolver {
        method: None,
        dt: None,
        duration: None,
        output_interval: None,
        rtol: None,
        atol: None,
    };
    let s = raw.map_or(&empty, |r| r.get_ref());
    let method = match s.method.as_ref() {
        None => {
            let method = Method::default_for(yielding);
            defaults.push(format!("solver.method = \"{}\"", method.name()));
            method
        }
        Some(m) => match Method::from_name(m.get_ref()) {
            Some(method) => method,
            None => {
                let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
                return Err(c.invalid(
                    m,
                    "solver.method",
                    &format!("must be one of {}", quoted(&names)),
                ));
            }
        },
    };
    let rtol = match &s.rtol {
        None => {
            if method.has_tolerance() {
                defaults.push(format!("solver.rtol = {:e}", method.default_rtol()));
            }
            method.default_rtol()
        }
        Some(v) => {
            let x = *v.get_ref();
            if !(x.is_finite() && (MIN_RTOL..=0.1).contains(&x)) {
                return Err(c.invalid(
                    v,
                    "solver.rtol",
                    "must be in [1e-12, 0.1] (below 1e-12 double precision cannot resolve the \
                     error estimate)",
                ));
            }
            c.usual(x, "solver.rtol", "");
            x
        }
    };
    let atol = match &s.atol {
        None => rtol * ATOL_PER_RTOL,
        Some(v) => {
            let x = *v.get_ref();
            if !(x.is_finite() && (MIN_ATOL..=1.0).contains(&x)) {
                return Err(c.invalid(
                    v,
                    "solver.atol",
                    "must be in [1e-14, 1] m (an error in a structure's top displacement)",
                ));
            }
            c.usual(x, "solver.atol", "m");
            x
        }
    };
    let duration = match &s.duration {
        Some(v) => c.positive(v, "solver.duration", "s")?,
        None => {
            let (d, why) = match ground {
                GroundMotion::Record(r) => (r.duration(), "the record's duration"),
                _ => (DEFAULT_HARMONIC_DURATION, "harmonic motion"),
            };
            defaults.push(format!("solver.duration = {d} ({why})"));
            d
        }
    };
    let dt = match &s.dt {
        Some(dt_v) => {
            let dt = c.positive(dt_v, "solver.dt", "s")?;
            if dt >= duration {
                return Err(c.invalid(
                    dt_v,
                    "solver.dt",
                    &format!("must be smaller than solver.duration = {duration} s"),
                ));
            }
            if duration / dt > 1e9 {
                return Err(c.invalid(
                    dt_v,
                    "solver.dt",
                    &format!("more than 10⁹ steps over {duration} s: use a larger step"),
                ));
            }
            dt
        }
        None if method == Method::Rk4 => {
            return Err(c.missing(
                "solver.dt",
                "the fixed step of method \"rk4\" in s (within its stability limit for the highest mode); or omit `method` for the adaptive default",
                raw.map(|r| r.span().start),
            ));
        }
        None => {
            let record_dt = match ground {
                GroundMotion::Record(r) => r.dt,
                _ => f64::INFINITY,
            };
            let dt = DEFAULT_DT.min(record_dt).min(duration / 10.0);
            defaults.push(format!("solver.dt = {dt}"));
            dt
        }
    };
    let output_interval = match &s.output_interval {
        None => {
            let x = (0.01f64).max(dt).min(duration);
            defaults.push(format!("solver.output_interval = {x}"));
            x
        }
        Some(v) => {
            let x = c.positive(v, "solver.output_interval", "s")?;
            if x > duration {
                return Err(c.invalid(
                    v,
                    "solver.output_interval",
                    &format!("must be in (0, {duration}] s (at most solver.duration)"),
                ));
            }
            x
        }
    };
    Ok((
        SolverSettings {
            method,
            dt,
            duration,
            rtol,
            atol,
        },
        output_interval,
    ))
}
