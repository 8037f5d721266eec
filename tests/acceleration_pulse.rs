//! The peak absolute floor acceleration with pounding and the impact it falls in
//! (`peak_acceleration_time`, `peak_acceleration_impact` of summary.json): checked on two
//! undamped one-storey buildings, whose floor obeys `m (ü + a_g) = −k u ± F` exactly, so that
//! the peak acceleration during an impact is the impact's force over the floor mass up to the
//! storey's spring force.

use std::path::Path;

use pounding::analysis::simulate::simulate;
use pounding::input::scenario::Scenario;

/// Two one-storey shear buildings (m₁ = 2e5 kg, k₁ = 8e7 N/m: ω₁ = 20 rad/s; m₂ = 3e5 kg,
/// k₂ = 3e7 N/m: ω₂ = 10 rad/s), undamped, Hertz contact at the floor (3.5 m), harmonic
/// ground motion near structure 2's period.
fn scenario(gap: f64) -> Scenario {
    let text = format!(
        r#"
[[structure]]
kind = "shear-building"
floor_heights = [3.5]
floor_masses = [2.0e5]
storey_stiffnesses = [8.0e7]
damping_ratio = 0.0

[[structure]]
kind = "shear-building"
floor_heights = [3.5]
floor_masses = [3.0e5]
storey_stiffnesses = [3.0e7]
damping_ratio = 0.0

[contact]
law = "hertz"
stiffness = 1.0e10
gap = {gap}

[ground_motion]
kind = "harmonic"
pga = 0.3
period = 0.6

[solver]
duration = 5.0
"#
    );
    Scenario::from_toml(&text, "pulse.toml", Path::new(".")).unwrap()
}

#[test]
fn the_peak_acceleration_during_an_impact_is_its_force_over_the_floor_mass() {
    let sc = scenario(0.01);
    let r = simulate(&sc).unwrap();
    assert!(r.contact.impacts >= 3, "{} impacts", r.contact.impacts);
    let (m, k) = ([2.0e5, 3.0e5], [8.0e7, 3.0e7]);
    for i in 0..2 {
        let f = &r.structures[i].floors[0];
        let pulse = f
            .peak_acceleration_impact
            .unwrap_or_else(|| panic!("structure {}: the peak is not during an impact", i + 1));
        // the time lies inside the impact named, which is one of the impact log
        let t = f.peak_acceleration_time;
        assert!(pulse.start <= t && t <= pulse.end, "{t} not in {pulse:?}");
        assert!((pulse.duration - (pulse.end - pulse.start)).abs() < 1e-15);
        assert_eq!(pulse.height, 3.5);
        assert!(r.impact_log.iter().any(|imp| imp.start == pulse.start
            && imp.end == pulse.end
            && imp.peak_force == pulse.peak_force));
        // m |a(t)| ≤ F(t) + k|u(t)| ≤ F_peak + k u_max at the peak's time, and at the time of
        // the impact's peak force m |a| ≥ F_peak − k u_max: so |m a_peak − F_peak| ≤ k u_max,
        // up to the sampling of the acceleration at the integration steps (the force's peak is
        // located between them; adaptive steps in contact are short: 1e-3 of F_peak allowed)
        let bound = k[i] * f.peak_displacement + 1e-3 * pulse.peak_force;
        let gap = (m[i] * f.peak_acceleration - pulse.peak_force).abs();
        assert!(
            gap <= bound,
            "structure {}: m a = {} N, F = {} N, k u_max = {} N",
            i + 1,
            m[i] * f.peak_acceleration,
            pulse.peak_force,
            k[i] * f.peak_displacement
        );
        // the impact's force dominates: the pulse is several times the acceleration without
        // pounding (what makes it look like an error when unexplained)
        assert!(pulse.peak_force > 3.0 * k[i] * f.peak_displacement);
        assert!(f.peak_acceleration > 2.0 * f.peak_acceleration_no_contact);
    }
}

/// A gap that never closes: no impact, so no floor's peak is an impact's pulse; its time is
/// within the run.
#[test]
fn without_impacts_no_peak_is_a_pulse() {
    let sc = scenario(1.0);
    let r = simulate(&sc).unwrap();
    assert_eq!(r.contact.impacts, 0);
    for s in &r.structures {
        for f in &s.floors {
            assert!(f.peak_acceleration_impact.is_none());
            assert!((0.0..=5.0).contains(&f.peak_acceleration_time));
            // the same motion with and without the contact that never acts
            assert_eq!(f.peak_acceleration, f.peak_acceleration_no_contact);
        }
    }
}

/// summary.json carries the two keys beside the acceleration peaks (the impact left out when
/// the peak is not in one), and keeps the existing ones.
#[test]
fn summary_json_has_the_pulse_beside_the_peaks() {
    let sc = scenario(0.01);
    let r = simulate(&sc).unwrap();
    let json: serde_json::Value = serde_json::to_value(&r).unwrap();
    let floor = &json["structures"][0]["floors"][0];
    for key in [
        "height",
        "peak_displacement",
        "peak_displacement_no_contact",
        "peak_acceleration",
        "peak_acceleration_no_contact",
        "peak_drift",
        "peak_drift_no_contact",
        "peak_shear",
        "peak_shear_no_contact",
        "peak_acceleration_time",
    ] {
        assert!(floor[key].is_number(), "{key}: {floor}");
    }
    let pulse = &floor["peak_acceleration_impact"];
    for key in ["level", "height", "start", "end", "duration", "peak_force"] {
        assert!(pulse[key].is_number(), "{key}: {pulse}");
    }
    // not during an impact: the key is left out (summary.json holds no nulls)
    let quiet = serde_json::to_value(simulate(&scenario(1.0)).unwrap()).unwrap();
    let floor = quiet["structures"][0]["floors"][0].as_object().unwrap();
    assert!(floor.contains_key("peak_acceleration_time"));
    assert!(!floor.contains_key("peak_acceleration_impact"));
}
