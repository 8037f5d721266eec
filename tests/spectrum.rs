//! Design spectra and response-spectrum analysis against hand computations (issue 13).

use pounding::codes::spectrum::{
    Asce7Spectrum, DesignSpectrum, Ec8Spectrum, Ec8Type, GroundType, SpectrumError, SpectrumTable,
    modal_correlation, peak_displacement, peak_displacements, relative_peak,
};
use pounding::model::modal::ModalModel;
use pounding::model::structure::{Cantilever, Damping, Stiffness};
use std::f64::consts::PI;

const G: f64 = 9.80665;

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

/// ASCE 7-16 §11.4.6 with S_DS = 1.0 g, S_D1 = 0.6 g, T_L = 8 s:
/// T_0 = 0.2·0.6/1.0 = 0.12 s, T_S = 0.6 s.
/// T = 0: 0.4 g; T = 0.06: 1.0(0.4 + 0.6·0.06/0.12) = 0.7 g; T = 0.3: 1.0 g;
/// T = 1.2: 0.6/1.2 = 0.5 g; T = 10: 0.6·8/10² = 0.048 g.
#[test]
fn asce7_branches_by_hand() {
    let s = Asce7Spectrum::new(1.0, 0.6, 8.0).unwrap();
    assert!(close(s.t0(), 0.12, 1e-15) && close(s.ts(), 0.6, 1e-15));
    let d = DesignSpectrum::Asce7(s);
    for (t, g) in [
        (0.0, 0.4),
        (0.06, 0.7),
        (0.3, 1.0),
        (1.2, 0.5),
        (10.0, 0.048),
    ] {
        let sa = d.acceleration(t, 0.05).unwrap();
        assert!(close(sa, g * G, 1e-14), "T = {t}: {sa} vs {}", g * G);
    }
    // continuity at T_0, T_S, T_L
    for t in [0.12, 0.6, 8.0] {
        let a = d.acceleration(t * (1.0 - 1e-12), 0.05).unwrap();
        let b = d.acceleration(t * (1.0 + 1e-12), 0.05).unwrap();
        assert!(close(a, b, 1e-9), "jump at {t}");
    }
    // S_d = S_a (T/2π)²: 0.5·9.80665·(1.2/2π)² = 0.1788518 m
    let sd = d.displacement(1.2, 0.05).unwrap();
    assert!(close(sd, 0.5 * G * (1.2 / (2.0 * PI)).powi(2), 1e-14));
    assert!((sd - 0.1788518).abs() < 1e-7);
    // a 5 % spectrum used as given: ζ does not change it
    assert_eq!(d.acceleration(1.2, 0.02), d.acceleration(1.2, 0.05));
    assert!(!d.damping_corrected());
}

#[test]
fn asce7_rejects_bad_parameters() {
    assert!(matches!(
        Asce7Spectrum::new(0.0, 0.6, 8.0),
        Err(SpectrumError::NotPositive { name: "S_DS", .. })
    ));
    assert!(matches!(
        Asce7Spectrum::new(1.0, f64::NAN, 8.0),
        Err(SpectrumError::NotPositive { name: "S_D1", .. })
    ));
    // T_L = 0.5 s < T_S = 0.6 s
    assert!(matches!(
        Asce7Spectrum::new(1.0, 0.6, 0.5),
        Err(SpectrumError::LongPeriodBeforeTs { .. })
    ));
    let d = DesignSpectrum::Asce7(Asce7Spectrum::new(1.0, 0.6, 8.0).unwrap());
    assert!(matches!(
        d.acceleration(-1.0, 0.05),
        Err(SpectrumError::BadPeriod(_))
    ));
    assert!(matches!(
        d.acceleration(1.0, 1.0),
        Err(SpectrumError::BadDamping(_))
    ));
}

/// EN 1998-1 Type 1, ground C (S = 1.15, T_B = 0.2, T_C = 0.6, T_D = 2.0 s), a_g = 2 m/s².
/// ζ = 5 % (η = 1): T = 0: 2·1.15 = 2.3; T = 0.1: 2.3·(1 + 0.5·(2.5 − 1)) = 4.025;
/// T = 0.4: 2.5·2·1.15 = 5.75; T = 1.2: 5.75·0.6/1.2 = 2.875; T = 3: 5.75·0.6·2/9 = 0.7666…
/// ζ = 10 %: η = √(10/15) = 0.8164966, plateau 4.694855; ζ = 30 %: √(10/35) = 0.5345 → 0.55,
/// plateau 5.75·0.55 = 3.1625.
#[test]
fn ec8_branches_and_eta_by_hand() {
    let s = Ec8Spectrum::new(2.0, GroundType::C, Ec8Type::Type1).unwrap();
    let sh = s.shape();
    assert_eq!((sh.s, sh.tb, sh.tc, sh.td), (1.15, 0.20, 0.6, 2.0));
    let d = DesignSpectrum::Ec8(s);
    for (t, sa) in [
        (0.0, 2.3),
        (0.1, 4.025),
        (0.4, 5.75),
        (1.2, 2.875),
        (3.0, 5.75 * 0.6 * 2.0 / 9.0),
    ] {
        assert!(
            close(d.acceleration(t, 0.05).unwrap(), sa, 1e-14),
            "T = {t}"
        );
    }
    assert!(close(d.acceleration(0.4, 0.10).unwrap(), 4.694855340, 1e-9));
    assert!(close(d.acceleration(0.4, 0.30).unwrap(), 3.1625, 1e-14));
    // at T = 0 the spectrum is a_g S whatever the damping
    assert!(close(d.acceleration(0.0, 0.02).unwrap(), 2.3, 1e-14));
    assert!(d.damping_corrected());
    // Type 2, ground D (S = 1.8, T_B = 0.1, T_C = 0.3, T_D = 1.2): plateau 2.5·2·1.8 = 9.0
    let d2 = DesignSpectrum::Ec8(Ec8Spectrum::new(2.0, GroundType::D, Ec8Type::Type2).unwrap());
    assert!(close(d2.acceleration(0.2, 0.05).unwrap(), 9.0, 1e-14));
    // 1/T² branch beyond T_D = 1.2: 9·0.3·1.2/2² = 0.81
    assert!(close(d2.acceleration(2.0, 0.05).unwrap(), 0.81, 1e-14));
    assert!(Ec8Spectrum::new(-1.0, GroundType::A, Ec8Type::Type1).is_err());
}

/// User table: interpolation by hand and every validation error naming the pair.
#[test]
fn table_interpolation_and_validation() {
    let t = SpectrumTable::new(&[(0.1, 4.0), (0.5, 8.0), (2.0, 2.0)]).unwrap();
    let d = DesignSpectrum::Table(t);
    // T = 0.3: 4 + (0.2/0.4)·4 = 6; T = 1.0: 8 − (0.5/1.5)·6 = 6
    assert!(close(d.acceleration(0.3, 0.05).unwrap(), 6.0, 1e-14));
    assert!(close(d.acceleration(1.0, 0.05).unwrap(), 6.0, 1e-14));
    assert!(matches!(
        d.acceleration(0.05, 0.05),
        Err(SpectrumError::OutsideTable { .. })
    ));
    assert!(matches!(
        SpectrumTable::new(&[(0.1, 1.0)]),
        Err(SpectrumError::TooFewPoints(1))
    ));
    let e = SpectrumTable::new(&[(0.1, 1.0), (0.5, 2.0), (0.5, 3.0)]).unwrap_err();
    assert!(matches!(
        e,
        SpectrumError::PeriodsNotIncreasing { row: 3, .. }
    ));
    assert!(e.to_string().contains("pair 3"), "{e}");
    let e = SpectrumTable::new(&[(0.1, 1.0), (0.5, -2.0)]).unwrap_err();
    assert!(matches!(
        e,
        SpectrumError::BadTableAcceleration { row: 2, .. }
    ));
    let e = SpectrumTable::new(&[(f64::NAN, 1.0), (0.5, 2.0)]).unwrap_err();
    assert!(matches!(e, SpectrumError::BadTablePeriod { row: 1, .. }));
}

fn cantilever(period: f64, modes: usize, zeta: f64) -> ModalModel {
    Cantilever {
        name: "s".into(),
        length: 12.0,
        mass: 3.0e6,
        stiffness: Stiffness::Period(period),
        modes,
        damping: Damping::Modal(vec![zeta]),
    }
    .modal()
}

fn ec8_c() -> DesignSpectrum {
    DesignSpectrum::Ec8(Ec8Spectrum::new(2.0, GroundType::C, Ec8Type::Type1).unwrap())
}

/// One mode: u(h) = S_d Γ φ(h) exactly. T₁ = 0.5 s (plateau, S_a = 5.75 m/s²):
/// S_d = 5.75·(0.5/2π)² = 0.0364123 m. At the tip the uniform cantilever's Γ₁φ₁(L) = 4σ₁/λ₁
/// (∫φ = 2σ/λ, ∫φ² = 1, φ(1) = 2) = 4·0.7340955/1.8751041 = 1.565984, so u(L) = 0.0570209 m.
#[test]
fn single_mode_is_sd_gamma_phi() {
    let m = cantilever(0.5, 1, 0.05);
    let d = ec8_c();
    let sd = 5.75 * (0.5 / (2.0 * PI)).powi(2);
    for h in [12.0, 6.0, 3.0] {
        let r = peak_displacement(&m, &d, h).unwrap();
        let expected = sd * m.participation_factor(0) * m.shape(0, h);
        assert!(close(r.srss, expected.abs(), 1e-12), "h = {h}");
        assert!(close(r.cqc, expected.abs(), 1e-12), "h = {h}");
        assert!(close(r.modes[0].sd, sd, 1e-12));
    }
    let tip = peak_displacement(&m, &d, 12.0).unwrap();
    let gamma_phi = m.participation_factor(0) * m.shape(0, 12.0);
    assert!((gamma_phi - 4.0 * 0.734_095_514 / 1.875_104_069).abs() < 1e-6);
    assert!((tip.srss - 0.0570209).abs() < 1e-6);
    // at the base nothing moves
    assert_eq!(peak_displacement(&m, &d, 0.0).unwrap().srss, 0.0);
}

/// Several modes: SRSS √Σu², CQC with Der Kiureghian's ρ written out here.
#[test]
fn several_modes_srss_and_cqc() {
    let m = cantilever(0.8, 3, 0.05);
    let d = ec8_c();
    let rs = peak_displacements(&m, &d, &[12.0, 8.0]).unwrap();
    for r in &rs {
        let u: Vec<f64> = (0..3)
            .map(|n| {
                let w = m.omega[n];
                let t = 2.0 * PI / w;
                let sa = d.acceleration(t, 0.05).unwrap();
                m.participation_factor(n) * m.shape(n, r.height) * sa / (w * w)
            })
            .collect();
        let srss = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
        assert!(close(r.srss, srss, 1e-12));
        let rho = |i: usize, j: usize| {
            let (z, b) = (0.05f64, m.omega[j] / m.omega[i]);
            8.0 * z * z * (1.0 + b) * b.powf(1.5)
                / ((1.0 - b * b).powi(2) + 4.0 * z * z * b * (1.0 + b * b) + 8.0 * z * z * b * b)
        };
        let mut s = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                s += rho(i, j) * u[i] * u[j];
            }
        }
        assert!(close(r.cqc, s.sqrt(), 1e-12));
        // well-separated modes: CQC close to SRSS
        assert!((r.cqc - r.srss).abs() < 0.02 * r.srss);
    }
}

/// ρ for different damping: ζᵢ = 0.02, ζⱼ = 0.05, r = ωⱼ/ωᵢ = 0.8:
/// num = 8√0.001·(0.02 + 0.8·0.05)·0.8^1.5 = 0.0108612
/// den = 0.36² + 4·0.001·0.8·1.64 + 4·0.0029·0.64 = 0.1296 + 0.005248 + 0.007424 = 0.142272
/// ρ = 0.0763408, and ρ is symmetric.
#[test]
fn correlation_with_different_damping() {
    let rho = modal_correlation(10.0, 0.02, 8.0, 0.05);
    assert!((rho - 0.0763408).abs() < 1e-7, "{rho}");
    assert!(close(modal_correlation(8.0, 0.05, 10.0, 0.02), rho, 1e-12));
    assert_eq!(modal_correlation(5.0, 0.05, 5.0, 0.05), 1.0);
    assert_eq!(modal_correlation(5.0, 0.0, 5.0, 0.0), 1.0);
}

/// Relative peak of two single-mode structures, T₁ = 0.5 s and T₂ = 1.0 s, ζ = 5 %:
/// u₁ = S_d(0.5)·Γφ₁(L) with S_d = 0.0364123 m; u₂ = S_d(1.0)·Γφ₂(L) with
/// S_a(1.0) = 5.75·0.6/1 = 3.45, S_d = 3.45/(2π)² = 0.0873895 m; r = ω₂/ω₁ = 0.5 gives
/// ρ = 0.0184864 (separation.rs hand value); CQC = √(u₁² + u₂² − 2ρu₁u₂).
/// Identical structures at the same height move together: CQC = 0, SRSS = √2 u.
#[test]
fn relative_peak_by_hand() {
    let (m1, m2) = (cantilever(0.5, 1, 0.05), cantilever(1.0, 1, 0.05));
    let d = ec8_c();
    let r = relative_peak(&m1, 12.0, &m2, 12.0, &d).unwrap();
    let gp: f64 = 4.0 * 0.734_095_514 / 1.875_104_069;
    let u1: f64 = 0.036_412_300 * gp;
    let u2: f64 = 0.087_389_521 * gp;
    let rho = 0.0184864;
    assert!((r.srss - (u1 * u1 + u2 * u2).sqrt()).abs() < 1e-7);
    assert!((r.cqc - (u1 * u1 + u2 * u2 - 2.0 * rho * u1 * u2).sqrt()).abs() < 1e-7);
    let same = relative_peak(&m1, 12.0, &m1, 12.0, &d).unwrap();
    assert!(same.cqc.abs() < 1e-12);
    assert!(close(same.srss, 2f64.sqrt() * same.structure1.srss, 1e-14));
}

#[test]
fn analysis_errors_are_reported() {
    let m = cantilever(0.5, 2, 0.05);
    let d = ec8_c();
    assert!(matches!(
        peak_displacement(&m, &d, 12.5),
        Err(SpectrumError::HeightOutside { .. })
    ));
    assert!(matches!(
        peak_displacement(&m, &d, f64::NAN),
        Err(SpectrumError::HeightOutside { .. })
    ));
    // a table that does not reach the second mode's period (0.5/6.27 = 0.08 s)
    let t = DesignSpectrum::Table(SpectrumTable::new(&[(0.2, 5.0), (2.0, 1.0)]).unwrap());
    assert!(matches!(
        peak_displacement(&m, &t, 12.0),
        Err(SpectrumError::OutsideTable { .. })
    ));
    let mut bad = m.clone();
    bad.zeta.pop();
    assert!(matches!(
        peak_displacement(&bad, &d, 12.0),
        Err(SpectrumError::BadModel(_))
    ));
    let mut bad = m.clone();
    bad.omega[1] = 0.0;
    assert!(matches!(
        peak_displacement(&bad, &d, 12.0),
        Err(SpectrumError::BadModel(_))
    ));
}
