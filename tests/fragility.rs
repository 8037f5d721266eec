//! Issue 28: fragility studies. The maximum-likelihood fit against a grid search of the
//! likelihood written here from its formula (Baker 2015, eq. 11); synthetic capacities drawn
//! from a known lognormal recovered within the bootstrap intervals (and the intervals'
//! coverage over many data sets); complete separation; P(pounding) from the runs without
//! contact against the runs with contact at a grid of gaps, record by record; the records
//! scaled to the stripes (PGA and Sa(T1), which scale linearly); the critical gap of the
//! `scaled` mode and the target gap by hand; the files; bad inputs naming their key.
//! Records are synthetic (written here), the structures 2-storey shear buildings.

use std::path::Path;

use pounding::analysis::record_spectrum::spectral_point;
use pounding::analysis::simulate::simulate;
use pounding::input::fragility::{FragilityStudy, GapMode};
use pounding::input::scenario::Scenario;
use pounding::model::ground_motion::GroundMotion;
use pounding::study::fragility::{self, fit, pounding as pp};

// ---------------------------------------------------------------------------------------------
// the fit

/// Φ from erfc (A&S 7.1.2 / 26.2.29), written here.
fn phi(x: f64) -> f64 {
    0.5 * libm::erfc(-x / 2f64.sqrt())
}

/// −ln L from Baker (2015) eq. 11, with the binomial counts.
fn nll(theta: f64, beta: f64, im: &[f64], n: &[usize], z: &[usize]) -> f64 {
    im.iter()
        .zip(n.iter().zip(z))
        .map(|(x, (n, z))| {
            let p = phi((x / theta).ln() / beta).clamp(1e-300, 1.0 - 1e-16);
            -(*z as f64) * p.ln() - (*n - *z) as f64 * (1.0 - p).ln()
        })
        .sum()
}

/// The minimum of `nll` by a grid over (ln θ, ln β), refined around the best cell five
/// times (each a 61 × 61 grid over ± two cells of the previous one).
fn grid_search(im: &[f64], n: &[usize], z: &[usize]) -> (f64, f64) {
    let (mut lt, mut lb) = (im[0].ln() - 1.0, (0.02f64).ln());
    let (mut ht, mut hb) = (im[im.len() - 1].ln() + 1.0, (3.0f64).ln());
    let mut best = (0.0, 0.0);
    for _ in 0..6 {
        let mut bv = f64::INFINITY;
        for i in 0..=60 {
            for j in 0..=60 {
                let t = lt + (ht - lt) * i as f64 / 60.0;
                let b = lb + (hb - lb) * j as f64 / 60.0;
                let v = nll(t.exp(), b.exp(), im, n, z);
                if v < bv {
                    bv = v;
                    best = (t, b);
                }
            }
        }
        let (dt, db) = ((ht - lt) / 30.0, (hb - lb) / 30.0);
        (lt, ht, lb, hb) = (best.0 - dt, best.0 + dt, best.1 - db, best.1 + db);
    }
    (best.0.exp(), best.1.exp())
}

#[test]
fn mle_equals_a_grid_search_of_the_likelihood() {
    let im = [0.1, 0.2, 0.3, 0.4, 0.6, 0.8];
    for (n, z) in [
        ([11; 6], [0, 1, 3, 5, 9, 10]),
        ([20; 6], [1, 2, 8, 8, 15, 20]),
        ([7, 7, 7, 7, 6, 5], [0, 0, 1, 4, 5, 5]),
    ] {
        let f = fit::fit_lognormal(&im, &n, &z).unwrap();
        let (t, b) = grid_search(&im, &n, &z);
        // the grid's last cell is (range / 30⁶): far below these tolerances, which allow for
        // the flat likelihood near its maximum (a 1e-4 change in θ changes ln L by ~1e-8)
        assert!(
            (f.theta / t - 1.0).abs() < 1e-4,
            "θ {} vs grid {t}",
            f.theta
        );
        assert!((f.beta / b - 1.0).abs() < 1e-4, "β {} vs grid {b}", f.beta);
        // and the fit's ln L is the formula's at its θ, β (not lower than the grid's minimum)
        assert!(-f.log_likelihood <= nll(t, b, &im, &n, &z) + 1e-9);
        assert!((f.log_likelihood + nll(f.theta, f.beta, &im, &n, &z)).abs() < 1e-9);
    }
}

#[test]
fn counts_that_jump_from_none_to_all_give_beta_at_its_bound() {
    let im = [0.1, 0.2, 0.4, 0.8];
    let f = fit::fit_lognormal(&im, &[5; 4], &[0, 0, 5, 5]).unwrap();
    assert!(f.at_bound);
    assert_eq!(f.beta, fit::BETA_MIN);
    // θ: the geometric mean of the two stripes around the jump
    assert!((f.theta - (0.2f64 * 0.4).sqrt()).abs() < 1e-12);
    assert_eq!(
        fit::fit_lognormal(&im, &[5; 4], &[0; 4]),
        Err(fit::FitError::NoExceedance)
    );
    assert_eq!(
        fit::fit_lognormal(&im, &[5; 4], &[5; 4]),
        Err(fit::FitError::AllExceed)
    );
    assert_eq!(
        fit::fit_lognormal(&im, &[5; 4], &[0, 6, 5, 5]),
        Err(fit::FitError::BadInput)
    );
}

/// A small generator written here (SplitMix64) and standard normals by Box–Muller.
struct Normals(u64);
impl Normals {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

/// Record r exceeds at stripe x when x ≥ its capacity θ·exp(β·ε).
fn synthetic(
    g: &mut Normals,
    records: usize,
    theta: f64,
    beta: f64,
    im: &[f64],
) -> Vec<Vec<Option<bool>>> {
    (0..records)
        .map(|_| {
            let cap = theta * (beta * g.normal()).exp();
            im.iter().map(|&x| Some(x >= cap)).collect()
        })
        .collect()
}

#[test]
fn synthetic_lognormal_capacities_are_recovered_within_their_intervals() {
    let (theta, beta) = (0.35, 0.4);
    let im: Vec<f64> = (1..=12).map(|k| 0.06 * k as f64).collect();
    let mut g = Normals(7);
    // one large data set: the truth inside the 90 % intervals and the estimate close to it
    let table = synthetic(&mut g, 200, theta, beta, &im);
    let all: Vec<usize> = (0..table.len()).collect();
    let (n, z) = fit::counts(&table, im.len(), &all);
    let f = fit::fit_lognormal(&im, &n, &z).unwrap();
    let b = fit::bootstrap(&table, &im, 300, 1, 0.9, &[]).unwrap();
    assert!(b.theta.lo < theta && theta < b.theta.hi, "{b:?}");
    assert!(b.beta.lo < beta && beta < b.beta.hi, "{b:?}");
    // (200 capacities: the standard error of θ is ≈ θβ/√200 ≈ 3 %)
    assert!((f.theta / theta - 1.0).abs() < 0.1 && (f.beta / beta - 1.0).abs() < 0.25);
    // the same seed, the same intervals
    assert_eq!(fit::bootstrap(&table, &im, 300, 1, 0.9, &[]).unwrap(), b);
    // coverage over 60 data sets of 30 records: a 90 % interval holds θ in about 90 % of
    // them; with 60 sets the binomial standard deviation is ≈ 4 %, so below 75 % would be
    // a defect (percentile intervals of a small sample under-cover a little)
    let mut hit = [0; 2];
    let sets = 60;
    for _ in 0..sets {
        let t = synthetic(&mut g, 30, theta, beta, &im);
        if let Some(b) = fit::bootstrap(&t, &im, 150, 3, 0.9, &[]) {
            hit[0] += usize::from(b.theta.lo <= theta && theta <= b.theta.hi);
            hit[1] += usize::from(b.beta.lo <= beta && beta <= b.beta.hi);
        }
    }
    assert!(
        hit[0] as f64 >= 0.75 * sets as f64,
        "θ covered in {} of {sets}",
        hit[0]
    );
    assert!(
        hit[1] as f64 >= 0.70 * sets as f64,
        "β covered in {} of {sets}",
        hit[1]
    );
}

// ---------------------------------------------------------------------------------------------
// P(pounding) and the target gap by hand

#[test]
fn critical_gap_and_target_gap_by_hand() {
    // uniform: the largest required separation
    assert_eq!(
        pp::critical_gap(&[0.03, 0.05], &[0.1, 0.2], 0.1, GapMode::Uniform),
        0.05
    );
    // scaled, gaps 0.10 (top) and 0.05: level 2 pounds when g·0.5 < 0.03, g < 0.06; level 1
    // when g < 0.04
    let c = pp::critical_gap(&[0.04, 0.03], &[0.10, 0.05], 0.10, GapMode::Scaled);
    assert!((c - 0.06).abs() < 1e-15);
    // a level with no gap pounds at any scale once it closes
    assert_eq!(
        pp::critical_gap(&[0.04, 0.01], &[0.10, 0.0], 0.10, GapMode::Scaled),
        f64::INFINITY
    );
    // ten records; P ≤ 20 %: two may pound, the gap is the third largest
    let crit = [0.05, 0.12, 0.08, 0.30, 0.07, 0.11, 0.09, 0.20, 0.06, 0.10];
    let t = pp::gap_for_target(&crit, 0.2, 1.0);
    assert_eq!(t.empirical, 0.12);
    assert_eq!(t.pounding_records, 2);
    let l: Vec<f64> = crit.iter().map(|x: &f64| x.ln()).collect();
    let mu = l.iter().sum::<f64>() / 10.0;
    let sd = (l.iter().map(|x| (x - mu).powi(2)).sum::<f64>() / 9.0).sqrt();
    // Φ⁻¹(0.8) = 0.841621233572914 (tables)
    let expect = (mu + sd * 0.841_621_233_572_914).exp();
    assert!((t.lognormal.unwrap() / expect - 1.0).abs() < 1e-9);
    // the table: the fraction of critical gaps above each gap
    let tab = pp::PoundingTable::new(&[1.0], &[0.0, 0.1, 0.25, 0.3], &[crit.to_vec()]);
    assert_eq!(tab.p[0], vec![1.0, 0.4, 0.1, 0.0]);
}

// ---------------------------------------------------------------------------------------------
// studies on small buildings

/// A record in g (one value a line, dt 0.01 s): a sine of period `t` under a half-sine
/// envelope plus a second harmonic.
fn record_text(a: f64, t: f64, n: usize) -> String {
    (0..n)
        .map(|k| {
            let x = k as f64 * 0.01;
            let env = (std::f64::consts::PI * k as f64 / (n - 1) as f64).sin();
            let w = 2.0 * std::f64::consts::PI / t;
            format!(
                "{}\n",
                a * env * ((w * x).sin() + 0.3 * (2.7 * w * x).sin())
            )
        })
        .collect()
}

const RECORDS: [(f64, f64); 4] = [(0.30, 0.50), (0.25, 0.80), (0.35, 0.35), (0.20, 1.10)];

/// Two 2-storey shear buildings (B yielding when `yielding`), contact at 6 m (`gap_top`) and
/// 3 m (`gap_low`), under record r1 of `dir`.
fn base_text(gap_top: f64, gap_low: f64, yielding: bool) -> String {
    let hyst = if yielding {
        "hysteresis = { model = \"bouc-wen\", yield_drifts = 0.01, post_yield_ratio = 0.05, exponent = 2.0, beta = 0.5, gamma = 0.5 }"
    } else {
        ""
    };
    format!(
        r#"title = "fragility test"
[[structure]]
name = "A"
kind = "shear-building"
floor_heights = [3.0, 6.0]
floor_masses = [2.0e5, 2.0e5]
storey_stiffnesses = [3.0e8, 3.0e8]
damping_ratio = 0.05
[[structure]]
name = "B"
kind = "shear-building"
floor_heights = [3.0, 6.0]
floor_masses = [2.0e5, 2.0e5]
storey_stiffnesses = [1.0e8, 1.0e8]
damping_ratio = 0.05
{hyst}
[contact]
law = "linear"
stiffness = 1.0e9
[[contact.level]]
height = 6.0
gap = {gap_top}
[[contact.level]]
height = 3.0
gap = {gap_low}
[ground_motion]
kind = "record"
file = "r1.txt"
units = "g"
dt = 0.01
"#
    )
}

fn setup(gap_top: f64, gap_low: f64, yielding: bool) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (i, (a, t)) in RECORDS.iter().enumerate() {
        std::fs::write(
            dir.path().join(format!("r{}.txt", i + 1)),
            record_text(*a, *t, 500),
        )
        .unwrap();
    }
    std::fs::write(
        dir.path().join("base.toml"),
        base_text(gap_top, gap_low, yielding),
    )
    .unwrap();
    dir
}

fn study_text(measure: &str, stripes: &str, limits: &str, extra: &str) -> String {
    let recs: Vec<String> = (1..=RECORDS.len())
        .map(|i| format!("  {{ file = \"r{i}.txt\", units = \"g\", dt = 0.01 }},"))
        .collect();
    format!(
        "scenario = \"base.toml\"\n[ground_motion]\nrecords = [\n{}\n]\n[intensity]\n{measure}\n\
         {limits}\n[fragility]\nstripes = {stripes}\nbootstrap = 50\n{extra}\n",
        recs.join("\n")
    )
}

fn study(dir: &Path, text: &str) -> FragilityStudy {
    FragilityStudy::from_toml(text, "study.toml", dir).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn study_error(dir: &Path, text: &str) -> String {
    match FragilityStudy::from_toml(text, "study.toml", dir) {
        Ok(_) => panic!("must be refused:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const POUNDING: &str = "[[limit_state]]\nkind = \"pounding\"";

#[test]
fn records_are_scaled_to_each_stripe() {
    let d = setup(0.02, 0.02, false);
    for (measure, units) in [
        ("measure = \"pga\"", 9.80665),
        ("measure = \"sa\"\nstructure = 1", 9.80665),
        ("measure = \"sa\"\nstructure = 2\nunits = \"m/s2\"", 1.0),
    ] {
        let s = study(d.path(), &study_text(measure, "[0.1, 0.3]", POUNDING, ""));
        let suite = s.scenario.suite.as_ref().unwrap();
        for (j, level) in [0.1, 0.3].iter().enumerate() {
            assert_eq!(s.stripes[j], level * units);
            for (r, m) in suite.records.iter().enumerate() {
                let own = fragility::im::intensity(&s.measure, &m.record);
                let sc = suite
                    .member_scenario(&s.scenario, r, s.stripes[j] / own)
                    .unwrap();
                let GroundMotion::Record(rec) = &sc.ground_motion else {
                    panic!()
                };
                // the scaled record's IM, computed here from its samples: PGA, or the PSA at T1
                // of the 5 %-damped oscillator, is the stripe (both linear in the record;
                // round-off of the scaled samples only)
                let got = match &s.measure {
                    pounding::input::fragility::IntensityMeasure::Pga => {
                        rec.accel.iter().fold(0.0f64, |a, x| a.max(x.abs()))
                    }
                    pounding::input::fragility::IntensityMeasure::Sa { structure, .. } => {
                        let t1 = s.scenario.structures[*structure].modal().periods()[0];
                        spectral_point(&rec.accel, rec.dt, t1, 0.05).psa
                    }
                    _ => unreachable!(),
                };
                assert!(
                    (got / s.stripes[j] - 1.0).abs() < 1e-12,
                    "{got} vs {}",
                    s.stripes[j]
                );
            }
        }
    }
}

#[test]
fn pounding_from_runs_without_contact_equals_the_contact_runs_at_a_grid_of_gaps() {
    let d = setup(0.02, 0.02, false);
    let s = study(
        d.path(),
        &study_text("measure = \"pga\"", "[0.15, 0.4]", POUNDING, ""),
    );
    let suite = s.scenario.suite.as_ref().unwrap();
    let mut checked = [0usize; 2];
    for r in 0..RECORDS.len() {
        let own = fragility::im::intensity(&s.measure, &suite.records[r].record);
        for &level in &s.stripes {
            let base = suite.member_scenario(&s.scenario, r, level / own).unwrap();
            let free = simulate(&base).unwrap();
            // the critical gap, from the formula: the largest required separation over levels
            let crit = free
                .levels
                .iter()
                .map(|l| l.required_gap)
                .fold(0.0, f64::max);
            assert!(crit > 0.0);
            for k in 0..12 {
                let g = crit * (0.3 + 0.12 * k as f64);
                // (within 1 % of the critical gap the answer depends on where within a step
                // the closing peaks: the band is left out)
                if (g / crit - 1.0).abs() < 0.01 {
                    continue;
                }
                let mut sc: Scenario = base.clone();
                for l in &mut sc.contact.levels {
                    l.gap = g;
                }
                let with = simulate(&sc).unwrap();
                let pounds = with.contact.impacts > 0;
                assert_eq!(
                    pounds,
                    g < crit,
                    "record {r}, level {level}, gap {g} vs {crit}"
                );
                checked[usize::from(pounds)] += 1;
            }
        }
    }
    // both outcomes were met many times
    assert!(checked[0] > 20 && checked[1] > 20, "{checked:?}");
}

#[test]
fn a_study_runs_and_writes_its_files() {
    let d = setup(0.02, 0.015, true);
    let limits = format!(
        "{POUNDING}\n[[limit_state]]\nkind = \"contact_force\"\nvalue = 1e5\n\
         [[limit_state]]\nkind = \"ductility\"\nvalue = 1.5\nstructure = 2\n\
         [[limit_state]]\nkind = \"floor_acceleration\"\nvalue = 0.5\nunits = \"g\""
    );
    let text = study_text(
        "measure = \"pga\"",
        "[0.05, 0.1, 0.2, 0.4]",
        &limits,
        "gaps = [0.0, 0.01, 0.02, 0.05, 0.1]\ntarget = { im = 0.2, probability = 0.25 }",
    );
    let s = study(d.path(), &text);
    assert_eq!(s.limit_states[3].value, 0.5 * 9.80665);
    assert_eq!(s.limit_states[3].name, "floor_acceleration>0.5g");
    let run = fragility::run(&s, Some(2)).unwrap();
    assert_eq!(run.outcomes.len(), RECORDS.len() * 4);
    // pounding: the run with contact has an impact exactly when a level's relative
    // displacement without contact passes its gap (record by record)
    let gaps = [vec![0.02, 0.015]];
    for o in &run.outcomes {
        let ls = &s.limit_states[0];
        assert_eq!(o.exceeds(ls, 0, &gaps), o.exceeds(ls, 1, &gaps), "{o:?}");
        // the contact force has no model without contact
        assert_eq!(o.exceeds(&s.limit_states[1], 1, &gaps), None);
    }
    // one curve per limit state and model where it applies: 2 + 1 + 2 + 2
    assert_eq!(run.curves.len(), 7);
    // P(pounding) at gap 0.02 (the top level's gap) ≥ the fraction pounding at the scenario's
    // gaps with a smaller gap below (any level may pound), ≤ it at 0.015 everywhere
    let pound = run
        .curves
        .iter()
        .find(|c| c.limit_state == 0 && c.model == 1)
        .unwrap();
    for (j, p) in run.pounding[0].p.iter().enumerate() {
        let frac = pound.exceedances[j] as f64 / pound.runs[j] as f64;
        assert!(p[2] <= frac + 1e-12 && frac <= p[1] + 1e-12, "{p:?} {frac}");
        // a probability, non-increasing in the gap
        assert!(p.windows(2).all(|w| w[1] <= w[0]));
    }
    let t = run.target_gap.first().unwrap();
    assert_eq!(t.records, RECORDS.len());
    let out = d.path().join("out");
    let written = fragility::write::write(&run, &out, || {
        pounding::figures::fragility::pictures(&run, &out).unwrap()
    })
    .unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.last().unwrap(), "fit.json");
    for f in [
        "fragility.csv",
        "p_pounding.csv",
        "runs.csv",
        "fragility.png",
        "p-pounding.svg",
    ] {
        assert!(names.iter().any(|n| n == f), "{f} in {names:?}");
    }
    let csv = std::fs::read_to_string(out.join("fragility.csv")).unwrap();
    assert!(csv.starts_with("limit_state,model,im,runs,exceedances,fraction\n"));
    assert_eq!(csv.lines().count(), 1 + 7 * 4);
    let p = std::fs::read_to_string(out.join("p_pounding.csv")).unwrap();
    assert_eq!(p.lines().count(), 1 + 4 * 5);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    assert_eq!(json["fits"].as_array().unwrap().len(), 7);
    assert_eq!(json["im_units"], "g");
    for f in json["fits"].as_array().unwrap() {
        assert!(f.get("theta").is_some() && f.get("beta").is_some(), "{f}");
    }
    // the report names every limit state
    let text = fragility::report::report(&run);
    for ls in &s.limit_states {
        assert!(text.contains(&ls.name), "{text}");
    }
}

#[test]
fn bad_inputs_name_their_key() {
    let d = setup(0.02, 0.02, false);
    let ok = study_text("measure = \"pga\"", "[0.1, 0.2]", POUNDING, "");
    for (from, to, key) in [
        ("scenario = \"base.toml\"", "", "`scenario`"),
        (
            "scenario = \"base.toml\"",
            "scenario = \"nothere.toml\"",
            "`scenario`",
        ),
        (
            "measure = \"pga\"",
            "measure = \"pgv\"",
            "`intensity.measure`",
        ),
        (
            "measure = \"pga\"",
            "measure = \"sa\"",
            "`intensity.structure`",
        ),
        (
            "measure = \"pga\"",
            "measure = \"sa\"\nstructure = 3",
            "`intensity.structure`",
        ),
        (
            "measure = \"pga\"",
            "measure = \"sa_avg\"\nperiods = [2.0, 0.5]",
            "`intensity.periods`",
        ),
        (
            "stripes = [0.1, 0.2]",
            "stripes = [0.2, 0.1]",
            "`fragility.stripes`",
        ),
        (
            "stripes = [0.1, 0.2]",
            "stripes = [0.1, 0.2]\ntarget = { im = 0.15, probability = 0.1 }",
            "`fragility.target.im`",
        ),
        (
            "stripes = [0.1, 0.2]",
            "stripes = [0.1, 0.2]\ntarget = { im = 0.1, probability = 1.5 }",
            "`fragility.target.probability`",
        ),
        (
            "stripes = [0.1, 0.2]",
            "stripes = [0.1, 0.2]\ngaps = [0.1, 0.05]",
            "`fragility.gaps`",
        ),
        (
            "stripes = [0.1, 0.2]",
            "stripes = [0.1, 0.2]\ngap_mode = \"linear\"",
            "`fragility.gap_mode`",
        ),
        (
            "kind = \"pounding\"",
            "kind = \"ductility\"\nvalue = 2.0",
            "`limit_state[1].kind`",
        ),
        (
            "kind = \"pounding\"",
            "kind = \"drift_ratio\"",
            "`limit_state[1].value`",
        ),
        (
            "kind = \"pounding\"",
            "kind = \"drift_ratio\"\nvalue = 2.0",
            "`limit_state[1].value`",
        ),
        (
            "kind = \"pounding\"",
            "kind = \"pounding\"\nvalue = 1.0",
            "`limit_state[1].value`",
        ),
        (
            "units = \"g\", dt = 0.01 },\n  { file = \"r2.txt\"",
            "units = \"g\", dt = 0.01, factor = 2.0 },\n  { file = \"r2.txt\"",
            "`ground_motion.records[1].factor`",
        ),
        (
            "records = [",
            "scaling = { rule = \"none\" }\nrecords = [",
            "`ground_motion.scaling`",
        ),
        (
            "\"r3.txt\"",
            "\"missing.txt\"",
            "ground_motion.records[3].file",
        ),
    ] {
        assert!(ok.contains(from), "{from}");
        let text = ok.replacen(from, to, 1);
        let e = study_error(d.path(), &text);
        assert!(e.contains(key), "{key} not in: {e}");
        assert!(e.contains("study.toml") || e.contains("base.toml"), "{e}");
    }
    // an unknown key: the TOML reader names it
    let e = study_error(
        d.path(),
        &ok.replace("[fragility]", "[fragility]\nstripe = 1"),
    );
    assert!(e.contains("stripe") && e.contains("study.toml:"), "{e}");
    // a scenario without a suite and no [ground_motion] in the study
    let bare = ok[ok.find("[intensity]").unwrap()..].to_string();
    let e = study_error(d.path(), &format!("scenario = \"base.toml\"\n{bare}"));
    assert!(e.contains("`ground_motion`"), "{e}");
}
