//! Code separation rules against hand computations (issue 13, docs/codes.md; EN 1998-1 and
//! IS 1893's coinciding floors: issue 24).

use pounding::codes::rules::{
    Asce7Boundary, Asce7Params, CodeError, CodeRule, Ec8Boundary, Ec8Params, Gb50011Params,
    GbSystem, Is1893Params, NbccParams, NtcMethod, NtcParams, NtcZone, PairInput, PartialStep,
    gb50011_width,
};

fn input(d1: f64, d2: f64) -> PairInput {
    PairInput {
        displacement: [d1, d2],
        height: [20.0, 20.0],
        level: [12.0, 12.0],
        floors_coincide: false,
    }
}

/// [`input`] at a level that is a floor of both structures.
fn at_floors(d1: f64, d2: f64) -> PairInput {
    PairInput {
        floors_coincide: true,
        ..input(d1, d2)
    }
}

fn is1893(r: f64) -> CodeRule {
    CodeRule::Is1893(Is1893Params {
        r,
        floor_reduction: true,
    })
}

fn asce(boundary: Asce7Boundary) -> CodeRule {
    CodeRule::Asce7(Asce7Params {
        cd: [5.5, 4.0],
        ie: [1.25, 1.0],
        boundary,
    })
}

/// ASCE 7-16 §12.12.3: δ_M1 = 5.5·0.04/1.25 = 0.176 m, δ_M2 = 4·0.03/1 = 0.12 m;
/// same property δ_MT = √(0.176² + 0.12²) = √(0.030976 + 0.0144) = √0.045376 = 0.2130164 m;
/// property line: each set back by its δ_M, gap 0.176 + 0.12 = 0.296 m.
#[test]
fn asce7_by_hand() {
    let s = asce(Asce7Boundary::SameProperty)
        .required_separation(&input(0.04, 0.03))
        .unwrap();
    assert!((s.terms[0] - 0.176).abs() < 1e-15);
    assert!((s.terms[1] - 0.12).abs() < 1e-15);
    assert!((s.required - 0.045376f64.sqrt()).abs() < 1e-15);
    assert!((s.required - 0.2130164).abs() < 1e-7);
    assert_eq!((s.key, s.name), ("asce7", "ASCE 7-16"));
    assert!(s.clause.contains("12.12.3"));
    let p = asce(Asce7Boundary::PropertyLine)
        .required_separation(&input(0.04, 0.03))
        .unwrap();
    assert!((p.required - 0.296).abs() < 1e-15);
}

/// IS 1893 (Part 1):2016 §7.11.3: R(Δ₁ + Δ₂) = 5·(0.02 + 0.03) = 0.25 m; where the floor
/// levels coincide R/2: 2.5·0.05 = 0.125 m — unless the reduction is turned off.
#[test]
fn is1893_by_hand() {
    let rule = is1893(5.0);
    let s = rule.required_separation(&input(0.02, 0.03)).unwrap();
    assert!((s.required - 0.25).abs() < 1e-15);
    assert!((s.terms[0] - 0.10).abs() < 1e-15 && (s.terms[1] - 0.15).abs() < 1e-15);
    assert_eq!(s.reduction, None);
    assert_eq!(rule.clause(), "§7.11.3");
    let f = rule.required_separation(&at_floors(0.02, 0.03)).unwrap();
    assert!((f.required - 0.125).abs() < 1e-15);
    // the terms stay R Δ (before the reduction), and the report says what was applied
    assert!((f.terms[0] - 0.10).abs() < 1e-15 && (f.terms[1] - 0.15).abs() < 1e-15);
    assert!(f.reduction.unwrap().starts_with("R/2"));
    let off = CodeRule::Is1893(Is1893Params {
        r: 5.0,
        floor_reduction: false,
    })
    .required_separation(&at_floors(0.02, 0.03))
    .unwrap();
    assert!((off.required - 0.25).abs() < 1e-15);
    assert_eq!(off.reduction, None);
}

/// EN 1998-1:2004 §4.4.2.7 with d_s = q_d d_e (4.23). d_e = 0.012 and 0.009 m, q_d = 4 and
/// 3: d_s = 0.048 and 0.027 m. Same property: √(0.048² + 0.027²) = √(0.002304 + 0.000729) =
/// √0.003033 = 0.0550727 m; × 0.7 where the floor elevations coincide: 0.0385509 m.
/// Property line: each its own d_s, 0.048 + 0.027 = 0.075 m; × 0.7: 0.0525 m.
#[test]
fn ec8_by_hand() {
    let rule = |boundary, floor_reduction| {
        CodeRule::Ec8(Ec8Params {
            qd: [4.0, 3.0],
            boundary,
            floor_reduction,
        })
    };
    let same = rule(Ec8Boundary::SameProperty, true);
    let s = same.required_separation(&input(0.012, 0.009)).unwrap();
    assert!((s.terms[0] - 0.048).abs() < 1e-15 && (s.terms[1] - 0.027).abs() < 1e-15);
    assert!((s.required - 0.003033f64.sqrt()).abs() < 1e-15);
    assert!((s.required - 0.0550727).abs() < 1e-7);
    assert_eq!(s.reduction, None);
    assert_eq!((s.key, s.name), ("ec8", "EN 1998-1:2004"));
    assert!(s.clause.contains("4.4.2.7(2)b"));
    let f = same.required_separation(&at_floors(0.012, 0.009)).unwrap();
    assert!((f.required - 0.7 * 0.003033f64.sqrt()).abs() < 1e-15);
    assert!((f.required - 0.0385509).abs() < 1e-7);
    assert!(f.reduction.unwrap().contains("0.7"));
    let line = rule(Ec8Boundary::PropertyLine, true);
    let p = line.required_separation(&input(0.012, 0.009)).unwrap();
    assert!((p.required - 0.075).abs() < 1e-15);
    assert!(p.clause.contains("4.4.2.7(2)a"));
    let pf = line.required_separation(&at_floors(0.012, 0.009)).unwrap();
    assert!((pf.required - 0.0525).abs() < 1e-15);
    // the reduction may be turned off
    let off = rule(Ec8Boundary::SameProperty, false)
        .required_separation(&at_floors(0.012, 0.009))
        .unwrap();
    assert_eq!(off.required, s.required);
    // bad q_d names itself
    let bad = CodeRule::Ec8(Ec8Params {
        qd: [4.0, 0.0],
        boundary: Ec8Boundary::SameProperty,
        floor_reduction: true,
    })
    .required_separation(&input(0.01, 0.01))
    .unwrap_err();
    assert!(matches!(
        bad,
        CodeError::BadFactor {
            name: "q_d",
            structure: 2,
            ..
        }
    ));
}

/// The other codes do not depend on the floors: the same value at a coinciding floor.
#[test]
fn only_ec8_and_is1893_reward_coinciding_floors() {
    let rules = [
        asce(Asce7Boundary::SameProperty),
        CodeRule::Nbcc(NbccParams {
            rd: [4.0, 2.0],
            ro: [1.7, 1.3],
            ie: [1.0, 1.3],
        }),
        CodeRule::NtcSismo(NtcParams {
            zone: NtcZone::II,
            method: NtcMethod::Analysis,
            same_height_and_levels: false,
        }),
        CodeRule::Gb50011(Gb50011Params {
            intensity: 8,
            system: [GbSystem::Frame, GbSystem::Frame],
            partial_step: PartialStep::RoundUp,
        }),
    ];
    for r in rules {
        let a = r.required_separation(&input(0.04, 0.03)).unwrap();
        let b = r.required_separation(&at_floors(0.04, 0.03)).unwrap();
        assert_eq!(a, b, "{}", r.key());
    }
}

/// NBCC 4.1.8.14 with 4.1.8.13.(2): Δ₁ = 0.01·4·1.7/1.0 = 0.068 m,
/// Δ₂ = 0.02·2·1.3/1.3 = 0.04 m; √(0.068² + 0.04²) = √(0.004624 + 0.0016) = √0.006224
/// = 0.0788923 m.
#[test]
fn nbcc_by_hand() {
    let rule = CodeRule::Nbcc(NbccParams {
        rd: [4.0, 2.0],
        ro: [1.7, 1.3],
        ie: [1.0, 1.3],
    });
    let s = rule.required_separation(&input(0.01, 0.02)).unwrap();
    assert!((s.terms[0] - 0.068).abs() < 1e-15);
    assert!((s.terms[1] - 0.04).abs() < 1e-15);
    assert!((s.required - 0.006224f64.sqrt()).abs() < 1e-15);
    assert!((s.required - 0.0788923).abs() < 1e-7);
}

/// GB 50011-2010 §6.1.4 widths by hand (mm → m):
/// intensity 6, frame, 15 m: 100; intensity 8, frame, 24 m: (24 − 15)/3 = 3 steps → 160;
/// intensity 8, shear wall, 24 m: 0.5·160 = 80 → not below 100; intensity 7,
/// frame–shear-wall, 31 m: (31 − 15)/4 = 4 steps → 180, ·0.7 = 126; intensity 9, frame,
/// 20 m: 2.5 steps → rounded up 3 → 160, linear 150.
#[test]
fn gb50011_widths_by_hand() {
    let w = |i, s, h, p| gb50011_width(i, s, h, p).unwrap();
    use GbSystem::*;
    use PartialStep::*;
    assert!((w(6, Frame, 15.0, RoundUp) - 0.100).abs() < 1e-15);
    assert!((w(6, Frame, 10.0, RoundUp) - 0.100).abs() < 1e-15);
    assert!((w(8, Frame, 24.0, RoundUp) - 0.160).abs() < 1e-15);
    assert!((w(8, ShearWall, 24.0, RoundUp) - 0.100).abs() < 1e-15);
    assert!((w(7, FrameShearWall, 31.0, RoundUp) - 0.126).abs() < 1e-15);
    assert!((w(9, Frame, 20.0, RoundUp) - 0.160).abs() < 1e-15);
    assert!((w(9, Frame, 20.0, Linear) - 0.150).abs() < 1e-15);
    assert!(matches!(
        gb50011_width(10, Frame, 20.0, RoundUp),
        Err(CodeError::BadIntensity(10))
    ));
}

/// Two sides differ (§6.1.4 item 1(3)): the system needing the wider joint (frame) and the
/// lower height (20 m) at intensity 8: (20 − 15)/3 = 1.67 → 2 steps → 140 mm. Own widths: the
/// 30 m frame 5 steps → 200 mm; the 20 m shear wall 0.5·140 = 70 → 100 mm.
#[test]
fn gb50011_pair_by_hand() {
    let rule = CodeRule::Gb50011(Gb50011Params {
        intensity: 8,
        system: [GbSystem::Frame, GbSystem::ShearWall],
        partial_step: PartialStep::RoundUp,
    });
    let s = rule
        .required_separation(&PairInput {
            displacement: [f64::NAN, f64::NAN], // not used by GB 50011
            height: [30.0, 20.0],
            level: [0.0, 0.0],
            floors_coincide: false,
        })
        .unwrap();
    assert!((s.required - 0.140).abs() < 1e-15);
    assert!((s.terms[0] - 0.200).abs() < 1e-15);
    assert!((s.terms[1] - 0.100).abs() < 1e-15);
    let bad = rule.required_separation(&PairInput {
        displacement: [0.0, 0.0],
        height: [30.0, -1.0],
        level: [0.0, 0.0],
        floors_coincide: false,
    });
    assert!(matches!(
        bad,
        Err(CodeError::BadHeight { structure: 2, .. })
    ));
}

/// NTC-Sismo 2004 §1.10 at a 12 m level. Zone II, analysis, d = 0.04 and 0.03 m:
/// s₁ = 0.04 + 0.003·12 = 0.076 m, s₂ = 0.03 + 0.036 = 0.066 m; sum 0.142 m, half 0.071 m.
/// Zone I: s₂ = 0.03 + 0.001·12 = 0.042 → the 50 mm minimum. Simplified, zone III:
/// 0.012·12 = 0.144 m each, sum 0.288 m.
#[test]
fn ntc_by_hand() {
    let rule = |zone, method, same| {
        CodeRule::NtcSismo(NtcParams {
            zone,
            method,
            same_height_and_levels: same,
        })
    };
    let s = rule(NtcZone::II, NtcMethod::Analysis, false)
        .required_separation(&input(0.04, 0.03))
        .unwrap();
    assert!((s.terms[0] - 0.076).abs() < 1e-12 && (s.terms[1] - 0.066).abs() < 1e-12);
    assert!((s.required - 0.142).abs() < 1e-12);
    let half = rule(NtcZone::II, NtcMethod::Analysis, true)
        .required_separation(&input(0.04, 0.03))
        .unwrap();
    assert!((half.required - 0.071).abs() < 1e-12);
    let z1 = rule(NtcZone::I, NtcMethod::Analysis, false)
        .required_separation(&input(0.04, 0.03))
        .unwrap();
    assert!((z1.terms[0] - 0.052).abs() < 1e-12);
    assert_eq!(z1.terms[1], 0.050);
    let simp = rule(NtcZone::III, NtcMethod::Simplified, false)
        .required_separation(&input(f64::NAN, f64::NAN))
        .unwrap();
    assert!((simp.required - 0.288).abs() < 1e-12);
    assert_eq!((simp.key, simp.clause), ("ntc", "§1.10"));
}

/// No panic on bad input: errors name the factor and the structure.
#[test]
fn bad_inputs_are_errors() {
    let e = asce(Asce7Boundary::SameProperty)
        .required_separation(&input(-0.01, 0.03))
        .unwrap_err();
    assert!(matches!(e, CodeError::BadDisplacement { structure: 1, .. }));
    let rule = CodeRule::Asce7(Asce7Params {
        cd: [5.5, 0.0],
        ie: [1.0, 1.0],
        boundary: Asce7Boundary::SameProperty,
    });
    let e = rule.required_separation(&input(0.01, 0.03)).unwrap_err();
    assert!(matches!(
        e,
        CodeError::BadFactor {
            name: "C_d",
            structure: 2,
            ..
        }
    ));
    assert!(e.to_string().contains("C_d of structure 2"), "{e}");
    let rule = is1893(f64::INFINITY);
    assert!(rule.required_separation(&input(0.01, 0.03)).is_err());
    let rule = CodeRule::Nbcc(NbccParams {
        rd: [4.0, 2.0],
        ro: [1.7, 1.3],
        ie: [1.0, f64::NAN],
    });
    assert!(matches!(
        rule.required_separation(&input(0.01, 0.02)),
        Err(CodeError::BadFactor {
            name: "I_E",
            structure: 2,
            ..
        })
    ));
    assert!(
        is1893(5.0)
            .required_separation(&input(f64::NAN, 0.02))
            .is_err()
    );
}
