//! Tests of the recorder: its lane sums against the four-lane sums and closed forms,
//! penetration peaks between observations, impulses, and a bounded history.

use super::*;
use crate::integrate::Tally;
use crate::model::contact::ContactLaw;
use crate::model::ground_motion::GroundMotion;
use crate::model::structure::{Cantilever, Damping, Stiffness};
use crate::model::system::{ContactLevel, LevelState};

fn system(law: ContactLaw) -> System {
    let st = |period: f64| Cantilever {
        name: "s".into(),
        length: 10.0,
        mass: 2.0e6,
        stiffness: Stiffness::Period(period),
        modes: 2,
        damping: Damping::Modal(vec![0.02]),
    };
    System::new(
        [st(0.4).modal(), st(0.6).modal()],
        &law,
        &[ContactLevel {
            height: 10.0,
            gap: 0.01,
        }],
        GroundMotion::None,
    )
}

/// Observes δ at t = 0, 1e-3, 2e-3 s with the given impulse tallies; returns the impacts.
fn episodes(sys: &System, deltas: [(f64, f64); 3], impulses: [f64; 3]) -> Vec<Impact> {
    observed(sys, deltas, impulses).impacts
}

/// Observes δ at t = 0, 1e-3, 2e-3 s with the given impulse tallies; returns the record.
fn observed(sys: &System, deltas: [(f64, f64); 3], impulses: [f64; 3]) -> RunRecord {
    let mut rec = Recorder::new(sys, &[10.0], 0.01, 0.002);
    let (q, v) = (vec![0.0; 4], vec![0.0; 4]);
    for i in 0..3 {
        let (delta, delta_dot) = deltas[i];
        let levels = [LevelState {
            delta,
            delta_dot,
            force: 0.0,
        }];
        let tally = Tally {
            impulse: vec![impulses[i]],
            ..Tally::default()
        };
        let view = StepView {
            t: i as f64 * 1e-3,
            q: &q,
            v: &v,
            levels: &levels,
            z: &[],
            tally: &tally,
        };
        rec.observe(sys, &view);
    }
    rec.finish()
}

/// The projections (and the modal energy) in two SSE2 pairs of lanes are the four-lane
/// sums they replaced, bit for bit: lane l takes the products of modes l, l + 4, … (and the remainder's l-th),
/// added as (lane 0 + lane 1) + (lane 2 + lane 3); below 8 modes one chain. Every length
/// from 0 to 45, on values that round.
#[test]
fn projections_in_pairs_of_lanes_are_the_four_lane_sums() {
    fn four_lanes(phi: &[f64], x: &[f64]) -> f64 {
        let n = phi.len();
        if n < LANES_FROM {
            return (0..n).fold(0.0, |s, j| s + phi[j] * x[j]);
        }
        let mut w = [0.0; 4];
        for j in 0..n / 4 * 4 {
            w[j % 4] += phi[j] * x[j];
        }
        for j in n / 4 * 4..n {
            w[j % 4] += phi[j] * x[j];
        }
        (w[0] + w[1]) + (w[2] + w[3])
    }
    for n in 0..46 {
        let phi: Vec<f64> = (0..n).map(|j| ((j * 5 + 1) as f64).sqrt() - 3.1).collect();
        let q: Vec<f64> = (0..n).map(|j| 1.0 / (j as f64 + 0.7)).collect();
        let v: Vec<f64> = (0..n).map(|j| ((j as f64) * 1.3).cos() * 7e-2).collect();
        let (w, wd) = project(&phi, &q, &v);
        assert_eq!(w.to_bits(), four_lanes(&phi, &q).to_bits(), "n = {n}");
        assert_eq!(wd.to_bits(), four_lanes(&phi, &v).to_bits(), "n = {n}");
        // the modal energy likewise, term ½(η̇² + ω²η²) per mode
        let w2: Vec<f64> = (0..n).map(|j| (j as f64 * 3.7 + 0.4).powi(2)).collect();
        let terms: Vec<f64> = (0..n)
            .map(|j| 0.5 * (v[j] * v[j] + w2[j] * q[j] * q[j]))
            .collect();
        let ones = vec![1.0; n];
        assert_eq!(
            modal_energy(&w2, &q, &v).to_bits(),
            four_lanes(&ones, &terms).to_bits(),
            "n = {n}"
        );
    }
}

/// The largest penetration inside a step whose end slopes have one sign (δ̇ = +1 m/s at
/// both ends of two 1 ms steps, δ = 0.1 mm at every observation): the step's cubic
/// Hermite interpolant is δ(θ) = δ₀ + h·δ̇·θ(1 − θ)(1 − 2θ), whose maximum is at
/// θ = (3 − √3)/6 and worth δ₀ + h·δ̇·√3/18 (closed form). The episode's and the level's
/// largest penetration are that value, and the elastic peak force is Hertz's k·δ^1.5
/// there. (The old shortcut solved only where δ̇ changes sign from + to −, and reported
/// the end value 0.1 mm, 49 % low.)
#[test]
fn interior_penetration_maximum_without_a_slope_sign_change() {
    let k = 2.8e10;
    let sys = system(ContactLaw::Hertz { stiffness: k });
    let (d0, v) = (1e-4, 1.0);
    let r = observed(&sys, [(d0, v); 3], [0.0, 1.0, 2.0]);
    let expected = d0 + 1e-3 * v * 3f64.sqrt() / 18.0;
    // (the root of a quadratic and one evaluation of the cubic: a few ulps)
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b;
    assert_eq!(r.impacts.len(), 1, "{:?}", r.impacts);
    let i = &r.impacts[0];
    assert!(
        close(i.max_penetration, expected),
        "{} vs {expected}",
        i.max_penetration
    );
    assert!(close(r.levels[0].max_penetration, expected));
    let force = k * expected.powf(1.5);
    assert!(close(i.peak_force, force), "{} vs {force}", i.peak_force);
    assert!(close(r.levels[0].peak_force, force));
}

/// The projections and the modal energy, in one chain below [`LANES_FROM`] modes and in
/// four lanes from it on (every remainder length), against the closed forms of integer
/// sums, exact in floating point at these sizes: with φ_j = j, η_j = 1, η̇_j = j,
/// `φ·η = n(n+1)/2`, `φ·η̇ = n(n+1)(2n+1)/6`; with ω² = 1, `Σ ½(η̇² + ω²η²) = ½(Σ j² + n)`.
#[test]
fn lane_sums_against_closed_forms() {
    for n in 0..=23usize {
        let phi: Vec<f64> = (1..=n).map(|j| j as f64).collect();
        let ones = vec![1.0; n];
        let nf = n as f64;
        let squares = nf * (nf + 1.0) * (2.0 * nf + 1.0) / 6.0;
        assert_eq!(
            project(&phi, &ones, &phi),
            (nf * (nf + 1.0) / 2.0, squares),
            "{n} modes"
        );
        assert_eq!(modal_energy(&ones, &ones, &phi), 0.5 * (squares + nf));
    }
}

/// Memory does not grow with the duration: over a run of 2·10⁶ samples (2000 s at 1 ms)
/// the sink receives every sample, in order, while the recorder keeps at most
/// [`MAX_KEPT_SAMPLES`] rows; the envelope keeps the extremes of the sampled series (its
/// maximum and minimum of w₁ equal those of the streamed samples) and its time range.
#[test]
fn long_run_keeps_a_bounded_history() {
    struct Count {
        n: u64,
        last_t: f64,
        max_w1: f64,
        min_w1: f64,
    }
    impl HistorySink for Count {
        fn row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
            assert!(t > self.last_t || self.n == 0);
            assert_eq!(forces.len(), 1);
            self.n += 1;
            self.last_t = t;
            self.max_w1 = self.max_w1.max(w[0]);
            self.min_w1 = self.min_w1.min(w[0]);
        }
    }
    let base = system(ContactLaw::Hertz { stiffness: 2.8e10 });
    let sys = System::new(
        [base.structures[0].clone(), base.structures[1].clone()],
        &ContactLaw::Hertz { stiffness: 2.8e10 },
        &[ContactLevel {
            height: 10.0,
            gap: 0.01,
        }],
        GroundMotion::Harmonic(crate::model::ground_motion::Harmonic::from_pga_g(0.01, 0.5)),
    );
    let (interval, duration) = (1e-3, 2000.0);
    let mut sink = Count {
        n: 0,
        last_t: 0.0,
        max_w1: f64::NEG_INFINITY,
        min_w1: f64::INFINITY,
    };
    let settings =
        crate::integrate::SolverSettings::new(crate::integrate::Method::ExactModal, 0.01, duration);
    let mut rec = Recorder::new(&sys, &[10.0], interval, duration).with_sink(&mut sink);
    crate::integrate::integrate(
        &sys,
        &settings,
        &crate::integrate::InitialState::default(),
        &mut rec,
    )
    .unwrap();
    let run = rec.finish();
    assert_eq!(sink.n, sample_count(interval, duration));
    assert_eq!(sink.n, 2_000_001);
    let h = &run.history;
    assert!(h.stride > 1);
    assert!(h.t.len() <= MAX_KEPT_SAMPLES, "{} rows kept", h.t.len());
    assert_eq!(h.t.len(), h.w1.len());
    assert_eq!(h.force[0].len(), h.t.len());
    let max = h.w1.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let min = h.w1.iter().copied().fold(f64::INFINITY, f64::min);
    assert_eq!(max, sink.max_w1);
    assert_eq!(min, sink.min_w1);
    assert!(sink.max_w1 > 0.0, "the ground moved the structure");
    assert_eq!(h.t[0], 0.0);
    assert_eq!(*h.t.last().unwrap(), sink.last_t);
    // a run of at most MAX_KEPT_SAMPLES samples keeps every one
    let short = Recorder::new(&sys, &[10.0], 0.01, 20.0);
    assert_eq!(short.history.stride, 1);
}

/// A force law's round-off impulse over an interval where δ stays ≤ 0 (a step that ends on a
/// located onset) is no impact; a grazing contact between observations (δ > 0 inside the
/// interval) and a stereomechanical impulse at δ = 0 are.
#[test]
fn impulses_without_penetration() {
    let hertz = system(ContactLaw::Hertz { stiffness: 2.8e10 });
    // approaching, reaching δ = −1e-15 at the second observation: round-off impulse
    let onset = [(-2e-3, 1.0), (-1e-15, 1.0), (-1e-3, -1.0)];
    assert!(episodes(&hertz, onset, [0.0, 1e-12, 1e-12]).is_empty());
    // δ < 0 at both ends but the cubic through (δ, δ̇) rises above 0 in between
    let grazing = [(-2e-3, 1.0), (-2e-4, 1.0), (-1e-4, -1.0)];
    let found = episodes(&hertz, grazing, [0.0, 0.0, 5.0]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].max_penetration > 0.0 && found[0].impulse == 5.0);
    // an instantaneous impact: an impulse with δ ≤ 0 throughout
    let stereo = system(ContactLaw::Stereomechanical { restitution: 0.6 });
    let found = episodes(&stereo, onset, [0.0, 80.0, 80.0]);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].impulse, 80.0);
}

/// Every tracked height's projections formed structure by structure ([`Tracks`]) are
/// [`project`]'s, bit for bit, in AVX (where the processor has it) and in SSE2 pairs: every
/// mode count from 0 to 29 (one chain below [`LANES_FROM`], four lanes from it on, every
/// remainder), one to six entries per structure (blocks of four and what is left), two
/// structures of different mode counts, on values that round.
#[test]
fn tracks_are_the_single_projections_bit_for_bit() {
    let vals = |n: usize, a: f64, b: f64| -> Vec<f64> {
        (0..n)
            .map(|j| ((j as f64) * a + b).sin() / (j as f64 + b))
            .collect()
    };
    for n1 in 0..30 {
        for (n2, count) in [(n1, 1), (n1 / 2, 2), (n1 + 3, 3), (n1, 5), (n1 + 1, 6)] {
            let (q, v) = (vals(n1 + n2, 0.7, 1.9), vals(n1 + n2, 2.3, 0.8));
            let rows = |n: usize, k: usize| -> Vec<Vec<f64>> {
                (0..k)
                    .map(|e| vals(n, 1.1 + 0.3 * e as f64, 0.3 + e as f64))
                    .collect()
            };
            let (r1, r2) = (rows(n1, count), rows(n2, 4));
            // tracked heights pairing entries of both structures (the same entry twice too)
            let of: Vec<[usize; 2]> = (0..count + 1).map(|k| [k % count, count + k % 4]).collect();
            for wide in [false, true] {
                let mut t = Tracks::from_groups(
                    vec![(0, n1, r1.clone()), (n1, n2, r2.clone())],
                    of.clone(),
                    wide,
                );
                t.project(&q, &v);
                for (k, &[a, b]) in of.iter().enumerate() {
                    let (x, y) = t.at(k);
                    let one = project(&r1[a], &q[..n1], &v[..n1]);
                    let two = project(&r2[b - count], &q[n1..], &v[n1..]);
                    let bits = |p: (f64, f64)| (p.0.to_bits(), p.1.to_bits());
                    assert_eq!(bits(x), bits(one), "{n1} modes, entry {a}, wide {wide}");
                    assert_eq!(bits(y), bits(two), "{n2} modes, entry {b}, wide {wide}");
                }
            }
        }
    }
}

/// The recorder's AVX pass ([`Recorder::observe_part`] compiled for AVX, the projections
/// four modes to an operation) gives the SSE2 pass's record bit for bit: two 12-mode
/// cantilevers (groups of four) pounding at two heights under a harmonic motion, with
/// `exact-modal` and `rk4`, every field of the record (peaks, impacts, history, energy,
/// floors). (Without AVX both take the SSE2 pass.)
#[test]
fn the_avx_pass_is_the_sse2_pass_bit_for_bit() {
    use crate::integrate::{InitialState, Method, SolverSettings, integrate};
    use crate::model::ground_motion::Harmonic;
    struct Both<'a>(Recorder<'a>, Recorder<'a>);
    impl Observer for Both<'_> {
        fn observe(&mut self, system: &System, s: &StepView) {
            self.0.observe(system, s);
            self.1.observe(system, s);
        }
    }
    let st = |period: f64| {
        Cantilever {
            name: "s".into(),
            length: 10.0,
            mass: 2.0e6,
            stiffness: Stiffness::Period(period),
            modes: 12,
            damping: Damping::Modal(vec![0.03]),
        }
        .modal()
    };
    let level = |height: f64| ContactLevel { height, gap: 0.01 };
    let sys = System::new(
        [st(0.4), st(0.65)],
        &ContactLaw::Hertz { stiffness: 2.8e10 },
        &[level(10.0), level(7.0)],
        GroundMotion::Harmonic(Harmonic::from_pga_g(0.5, 0.5)),
    );
    // (rk4 at 0.2 ms: the 12th mode's ω ≈ 5 800 rad/s needs dt < 0.49 ms)
    for (method, dt) in [(Method::ExactModal, 0.01), (Method::Rk4, 2e-4)] {
        let heights = [10.0, 7.0];
        let mut both = Both(
            Recorder::new(&sys, &heights, 0.01, 5.0),
            Recorder::new(&sys, &heights, 0.01, 5.0),
        );
        both.1.tracks.narrow();
        let settings = SolverSettings::new(method, dt, 5.0);
        integrate(&sys, &settings, &InitialState::default(), &mut both).unwrap();
        let (wide, narrow) = (both.0.finish(), both.1.finish());
        assert!(!wide.impacts.is_empty(), "{method:?}: the structures pound");
        assert!(wide == narrow, "{method:?}");
    }
}
