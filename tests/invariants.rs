//! Issue 15: properties that hold for every valid scenario, checked on random ones (proptest):
//! two structures of random kind (cantilever or shear building, 1–4 storeys of 3.5 m, 1–3
//! modes), masses, periods or storey stiffnesses, damping, gap, contact law (hertz, linear,
//! kelvin, hertzdamp, jankowski, stereomechanical) and its parameters, a harmonic ground motion of random PGA and
//! period, 2–5 s.
//!
//! - **Action and reaction.** The equations (docs/model.md §2–3, ARCHITECTURE.md *coupling
//!   rows*): structure i obeys q̈ + 2ζωq̇ + ω²q = −Γ a_g + s_i φ_i(h) F with s₁ = −1, s₂ = +1 and
//!   penetration δ = w₁(h) − w₂(h) − d. Reflecting the x axis and swapping the structures
//!   (w₁' = −w₂, w₂' = −w₁) leaves δ and F unchanged and turns each equation into the other's
//!   with −a_g: so the mirrored scenario — structures swapped *and the ground motion negated*
//!   — has w₁'(t) = −w₂(t), w₂'(t) = −w₁(t), the same contact force history and the same
//!   impacts. (Swapping alone is not a symmetry: the ground pushes both the same way.)
//! - **Energy balance**: input − Δ(modal) − contact stored − damping − contact dissipated, over
//!   the largest energy in the run, is small.
//! - **A gap that never closes**: with the gap above the sum of the free-run peaks at the
//!   contact height, |w₁| + |w₂| < d at every instant, so δ < 0 and F = 0 throughout: no impact,
//!   no force, and the run with contact is the run without.
//! - **Peaks bound the history**: every history sample (|w₁|, |w₂|, the force, with and
//!   without contact) is at most the reported peak.

use proptest::prelude::*;
use std::path::Path;

use pounding::analysis::simulate::{Report, simulate};
use pounding::input::scenario::Scenario;
use pounding::model::ground_motion::{GroundMotion, Harmonic};

/// One structure as a `[[structure]]` table.
#[derive(Debug, Clone)]
struct Building {
    shear: bool,
    storeys: usize,
    floor_mass: f64,
    /// Cantilever: its first period, s; shear building: storey stiffness, N/m.
    stiffness: f64,
    modes: usize,
    damping: f64,
}

impl Building {
    fn toml(&self) -> String {
        let n = self.storeys;
        if self.shear {
            format!(
                "[[structure]]\nkind = \"shear-building\"\nstoreys = {n}\nstorey_height = 3.5\n\
                 floor_mass = {:e}\nstorey_stiffness = {:e}\nmodes = {}\ndamping_ratio = {}\n\n",
                self.floor_mass,
                self.stiffness,
                self.modes.min(n),
                self.damping
            )
        } else {
            format!(
                "[[structure]]\nlength = {:e}\nmass = {:e}\nperiod = {}\nmodes = {}\n\
                 damping_ratio = {}\n\n",
                3.5 * n as f64,
                self.floor_mass * n as f64,
                self.stiffness,
                self.modes,
                self.damping
            )
        }
    }
}

fn building() -> impl Strategy<Value = Building> {
    (
        any::<bool>(),
        1usize..=4,
        1e5..5e5f64,
        0.0..1.0f64,
        1usize..=3,
        0.01..0.1f64,
    )
        .prop_map(|(shear, storeys, floor_mass, s, modes, damping)| Building {
            shear,
            storeys,
            floor_mass,
            // periods 0.2–1.5 s; storey stiffnesses 5e7–1e9 N/m (log-uniform)
            stiffness: if shear {
                5e7 * (20.0f64).powf(s)
            } else {
                0.2 + 1.3 * s
            },
            modes,
            damping,
        })
}

/// The contact table without the gap.
fn law() -> impl Strategy<Value = String> {
    (0usize..6, 0.0..1.0f64, 0.5..0.9f64).prop_map(|(law, s, e)| {
        let hertz = 1e9 * (50.0f64).powf(s); // N/m^1.5
        let linear = 1e8 * (100.0f64).powf(s); // N/m
        match law {
            0 => format!("law = \"hertz\"\nstiffness = {hertz:e}\n"),
            1 => format!("law = \"linear\"\nstiffness = {linear:e}\n"),
            2 => format!("law = \"kelvin\"\nstiffness = {linear:e}\nrestitution = {e}\n"),
            3 => format!("law = \"hertzdamp\"\nstiffness = {hertz:e}\nrestitution = {e}\n"),
            4 => format!("law = \"jankowski\"\nstiffness = {hertz:e}\nrestitution = {e}\n"),
            _ => format!("law = \"stereomechanical\"\nrestitution = {e}\n"),
        }
    })
}

#[derive(Debug, Clone)]
struct Case {
    a: Building,
    b: Building,
    contact: String,
    gap: f64,
    pga: f64,
    ground_period: f64,
    duration: f64,
}

fn case() -> impl Strategy<Value = Case> {
    (
        building(),
        building(),
        law(),
        0.0..0.03f64,
        0.1..1.0f64,
        0.2..2.0f64,
        2.0..5.0f64,
    )
        .prop_map(|(a, b, contact, gap, pga, ground_period, duration)| Case {
            a,
            b,
            contact,
            gap,
            pga,
            ground_period,
            duration,
        })
}

impl Case {
    /// The scenario text, structures in the order given; `solver` lines added.
    fn toml(&self, a: &Building, b: &Building, gap: f64, solver: &str) -> String {
        format!(
            "{}{}[contact]\n{}gap = {gap:e}\n\n[ground_motion]\nkind = \"harmonic\"\npga = {}\n\
             period = {}\n\n[solver]\nduration = {}\n{solver}",
            a.toml(),
            b.toml(),
            self.contact,
            self.pga,
            self.ground_period,
            self.duration
        )
    }

    fn scenario(&self, mirrored: bool, gap: f64, solver: &str) -> Scenario {
        let (a, b) = if mirrored {
            (&self.b, &self.a)
        } else {
            (&self.a, &self.b)
        };
        let text = self.toml(a, b, gap, solver);
        let mut sc = Scenario::from_toml(&text, "p.toml", Path::new("."))
            .unwrap_or_else(|e| panic!("a generated scenario is refused: {e}\n{text}"));
        if mirrored {
            // the reflected ground motion: a_g → −a_g (y = A sin ωt → −A sin ωt)
            let GroundMotion::Harmonic(h) = sc.ground_motion.clone() else {
                unreachable!()
            };
            sc.ground_motion = GroundMotion::Harmonic(Harmonic {
                pga: -h.pga,
                omega: h.omega,
            });
        }
        sc
    }
}

/// Cases per property: about three of each pair of kinds × law (2 × 2 × 6), and the file still
/// runs in a few seconds in release.
fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 64,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Mirrored results agree to this relative tolerance. Both runs take the same fixed RK4 steps;
/// they differ only in the order of floating-point sums over the concatenated modes (structure
/// 1's modes first in one run, structure 2's in the other), a few ulps per step, which impacts
/// can amplify. Measured: at most 5.6e-11 of the peak in most of 384 cases (six seeds of 64), but
/// a rare case (about one run of the 64-case test in 30) reaches 1.5e-7: a sequence of impacts
/// in which a grazing contact decides the next one amplifies the round-off by 10⁴ (the proptest
/// draws new cases every run, so 1e-8 failed CI now and then). 1e-5 leaves a factor of 60 above
/// that; a broken mirror (the ground motion not negated, or the force's sign on one structure)
/// moves the peaks by O(1) and still fails by five orders of magnitude.
const MIRROR_TOL: f64 = 1e-5;

proptest! {
    #![proptest_config(config())]

    /// Action and reaction: the mirrored scenario gives the mirrored results.
    #[test]
    fn mirrored_scenario_gives_mirrored_results(c in case()) {
        let solver = "method = \"rk4\"\ndt = 2e-4\n";
        let r = simulate(&c.scenario(false, c.gap, solver));
        let m = simulate(&c.scenario(true, c.gap, solver));
        let (r, m) = match (r, m) {
            (Ok(r), Ok(m)) => (r, m),
            (Err(a), Err(b)) => {
                // (an RK4 step too coarse for a stiff contact stops both alike)
                prop_assert_eq!(a.to_string(), b.to_string());
                return Ok(());
            }
            (a, b) => panic!("one run failed: {:?} / {:?}", a.err(), b.err()),
        };
        let mut worst: f64 = 0.0;
        let mut close = |what: &str, a: f64, b: f64, scale: f64| {
            let d = (a - b).abs() / scale.max(f64::MIN_POSITIVE);
            worst = worst.max(d);
            assert!(d <= MIRROR_TOL, "{what}: {a} vs {b} (scale {scale})");
        };
        for i in 0..2 {
            let (s, t) = (&r.structures[i], &m.structures[1 - i]);
            close("peak", s.peak_displacement, t.peak_displacement, s.peak_displacement);
            close("peak no contact", s.peak_displacement_no_contact,
                  t.peak_displacement_no_contact, s.peak_displacement_no_contact);
        }
        prop_assert_eq!(r.contact.impacts, m.contact.impacts);
        close("peak force", r.contact.peak_force, m.contact.peak_force, r.contact.peak_force);
        close("max penetration", r.contact.max_penetration, m.contact.max_penetration,
              r.contact.max_penetration.max(c.gap).max(1e-6));
        let (h, g) = (&r.with_contact.history, &m.with_contact.history);
        prop_assert_eq!(h.t.len(), g.t.len());
        let scale = r.structures[0].peak_displacement.max(r.structures[1].peak_displacement);
        let fscale = r.contact.peak_force.max(1.0);
        for k in 0..h.t.len() {
            close("w1 = −w2'", h.w1[k], -g.w2[k], scale);
            close("w2 = −w1'", h.w2[k], -g.w1[k], scale);
            close("force", h.force[0][k], g.force[0][k], fscale);
        }
        eprintln!("mirror: largest relative difference {worst:.1e}, {} impacts", r.contact.impacts);
    }

    /// The energy balance closes, with and without contact, at the default method and
    /// tolerance (`exact-modal`, rtol 1e-8). With contact its error is the work of the contact
    /// law along the computed motion (a 7-point rule on every point of a contact step whose
    /// state is known) against the work the force quartic did on the modes: the collocation's
    /// own inconsistency. Measured over 384 cases (six seeds of 64): at most 2.2e-13 with
    /// contact and 8e-15 without (`adaptive` at its default rtol 1e-10, the former default:
    /// 9.3e-10); 1e-7 as before. (A 4-point rule at the companion's nodes alone read 6.6e-8:
    /// the defect's leading term, which integrates to nothing, dominated it.)
    #[test]
    fn energy_balance_closes(c in case()) {
        let r = simulate(&c.scenario(false, c.gap, "")).unwrap();
        for (what, e) in [("with contact", &r.energy), ("without", &r.energy_no_contact)] {
            prop_assert!(e.relative_error.is_finite() && e.relative_error < 1e-7,
                         "{}: {:?}", what, e);
        }
        eprintln!("energy: {:.1e} with contact, {:.1e} without",
                  r.energy.relative_error, r.energy_no_contact.relative_error);
    }

    /// A gap above the sum of the free-run peaks never closes: no impact, no force, and the run
    /// with contact equals the run without, sample by sample and bit for bit (the contact adds
    /// F = 0 to no load, and the method takes the same steps: `exact-modal`'s free flight is the
    /// same grid and the same arithmetic with contact levels as without).
    #[test]
    fn a_gap_that_never_closes_changes_nothing(c in case()) {
        let free = simulate(&c.scenario(false, c.gap, "")).unwrap();
        let p = [
            free.structures[0].peak_displacement_no_contact,
            free.structures[1].peak_displacement_no_contact,
        ];
        // (1 % and 1 µm above: the peaks are refined between steps, so |w₁| + |w₂| < d always)
        let gap = 1.01 * (p[0] + p[1]) + 1e-6;
        let r = simulate(&c.scenario(false, gap, "")).unwrap();
        prop_assert_eq!(r.contact.impacts, 0);
        prop_assert_eq!(r.contact.peak_force, 0.0);
        prop_assert_eq!(r.contact.contact_time, 0.0);
        prop_assert!(r.impact_log.is_empty());
        for (i, (s, free_peak)) in r.structures.iter().zip(p).enumerate() {
            prop_assert!(s.peak_displacement == s.peak_displacement_no_contact,
                         "structure {}: {} vs {}", i + 1, s.peak_displacement,
                         s.peak_displacement_no_contact);
            // and the free run does not depend on the gap at all
            prop_assert_eq!(s.peak_displacement_no_contact, free_peak);
        }
        let (h, g) = (&r.with_contact.history, &r.without_contact.history);
        prop_assert_eq!(h.t.len(), g.t.len());
        for k in 0..h.t.len() {
            prop_assert_eq!(h.force[0][k], 0.0);
            prop_assert!(h.w1[k] == g.w1[k], "t = {}", h.t[k]);
            prop_assert!(h.w2[k] == g.w2[k], "t = {}", h.t[k]);
        }
    }

    /// Every history sample is within the reported peaks. The samples are values of each step's
    /// cubic Hermite interpolant at the output times; the peaks are the largest values at every
    /// step and of the same interpolant between steps (its critical points, by formula), so the
    /// only slack needed is rounding: 1e-12 relative.
    #[test]
    fn peaks_bound_every_history_sample(c in case()) {
        let r = simulate(&c.scenario(false, c.gap, "")).unwrap();
        check_peaks(&r)?;
    }
}

fn check_peaks(r: &Report) -> Result<(), TestCaseError> {
    let slack = |peak: f64| peak * (1.0 + 1e-12) + 1e-300;
    let h = &r.with_contact.history;
    let g = &r.without_contact.history;
    prop_assert_eq!(h.stride, 1);
    let (p1, p2) = (
        r.structures[0].peak_displacement,
        r.structures[1].peak_displacement,
    );
    let (f1, f2) = (
        r.structures[0].peak_displacement_no_contact,
        r.structures[1].peak_displacement_no_contact,
    );
    for k in 0..h.t.len() {
        let t = h.t[k];
        prop_assert!(h.w1[k].abs() <= slack(p1), "w1({t}) = {} > {p1}", h.w1[k]);
        prop_assert!(h.w2[k].abs() <= slack(p2), "w2({t}) = {} > {p2}", h.w2[k]);
        let f = h.force[0][k];
        prop_assert!(
            f >= 0.0 && f <= slack(r.contact.peak_force),
            "force({t}) = {f} > {}",
            r.contact.peak_force
        );
    }
    for k in 0..g.t.len() {
        prop_assert!(
            g.w1[k].abs() <= slack(f1),
            "w1 free({}) = {} > {f1}",
            g.t[k],
            g.w1[k]
        );
        prop_assert!(
            g.w2[k].abs() <= slack(f2),
            "w2 free({}) = {} > {f2}",
            g.t[k],
            g.w2[k]
        );
    }
    Ok(())
}

/// A case proptest found in CI: a stereomechanical impact at gap 0 leaves end slopes that do not
/// fit the end values, so the step's interpolant overshoots with slopes of one sign at both ends.
/// The recorder's old shortcut (an interior extremum only where the slope changes sign) missed
/// it: a history sample of w2 exceeded the reported peak by 1.8e-5 relative.
#[test]
fn peaks_bound_the_samples_after_a_stereomechanical_impact() {
    let c = Case {
        a: Building {
            shear: true,
            storeys: 2,
            floor_mass: 432750.3473385328,
            stiffness: 73286312.12296759,
            modes: 1,
            damping: 0.06914047065943885,
        },
        b: Building {
            shear: false,
            storeys: 2,
            floor_mass: 261823.98252649553,
            stiffness: 0.2,
            modes: 2,
            damping: 0.014359955245198557,
        },
        contact: "law = \"stereomechanical\"\nrestitution = 0.8282447891803252\n".into(),
        gap: 0.0,
        pga: 0.1,
        ground_period: 1.8667131474375291,
        duration: 2.0,
    };
    let r = simulate(&c.scenario(false, c.gap, "")).unwrap();
    check_peaks(&r).unwrap();
}
