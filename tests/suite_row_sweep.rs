//! Sweeps over a suite of records on a row of buildings (issue 29: "every door takes a row",
//! with issue 27's suites): a case is the whole suite on the whole row, its results row the
//! suite's answer per pair and level. Checked against other code paths and formulas, never
//! against numbers the program printed before:
//!
//! - a row whose second gap never closes gives, case by case, the pair suite sweep's columns
//!   of its first two buildings (the same arithmetic: to the last digit);
//! - the design values of a case are those of `pounding run` on the case's scenario (the
//!   scenario `pounding sweep --case N` prints, run by the binary; its summary.json read
//!   without rounding), bit for bit;
//! - along one pair's gap the design value does not move and the pair's verdict flips exactly
//!   at it (gap ≥ design value), with margin gap − design value;
//! - resuming a journal, shards and merge give the uninterrupted table; the pictures are drawn;
//! - refusals: a key of one ground motion, a pair beyond the row, a journal of another kind.
//!
//! The records are the bundled ones (examples/records), cut to a few seconds.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use common::pounding_here as pounding;
use common::{ok, s};

use pounding::study::sweep::Sweep;
use pounding::study::sweep::results::{header, parse_csv_line};
use pounding::study::sweep::run::compute_case;

fn records_dir() -> String {
    format!("{}/examples/records/", env!("CARGO_MANIFEST_DIR"))
}

/// A shear building of `n` storeys of 3.5 m.
fn building(name: &str, n: usize, k: f64) -> String {
    format!(
        "[[structure]]\nname = \"{name}\"\nkind = \"shear-building\"\nstoreys = {n}\n\
         storey_height = 3.5\nfloor_mass = 2.0e5\nstorey_stiffness = {k:e}\ndamping_ratio = 0.05\n"
    )
}

/// The contact keys (law) and levels (height, gap), m: one level as `height` and `gap` (its
/// gap swept as `contact[P].gap`), several as `level = [...]` (`contact[P].level[K].gap`).
fn contact_body(levels: &[(f64, f64)]) -> String {
    let law = "law = \"jankowski\"\nstiffness = 2.75e9\nrestitution = 0.65\n";
    if let [(h, g)] = levels {
        return format!("{law}height = {h:?}\ngap = {g:?}\n");
    }
    let l: Vec<String> = levels
        .iter()
        .map(|(h, g)| format!("{{ height = {h:?}, gap = {g:?} }}"))
        .collect();
    format!("{law}level = [{}]\n", l.join(", "))
}

/// The three Loma Prieta records of examples/suite-row.toml scaled by EN 1998-1 (with three
/// records the design value is the largest, §4.3.3.4.3), and a 6 s exact-modal solver.
fn ground_and_solver() -> String {
    let r = records_dir();
    format!(
        "[ground_motion]\nkind = \"suite\"\nrecords = [\n  \
         {{ file = \"{r}RSN753_LOMAP_CLS000.AT2\" }},\n  \
         {{ file = \"{r}RSN786_LOMAP_PAE055.AT2\" }},\n  \
         {{ file = \"{r}RSN808_LOMAP_TRI000.AT2\" }},\n]\n\
         scaling = {{ rule = \"ec8\", target = {{ spectrum = \"ec8\", ag = 2.0, ground_type = \"C\", type = 1 }} }}\n\
         [solver]\nmethod = \"exact-modal\"\ndt = 0.005\nduration = 6.0\n"
    )
}

/// A row A (4 storeys) – B (5) – C (4, a copy of A): A–B at `ab` levels, B–C at `bc`.
fn row(ab: &[(f64, f64)], bc: &[(f64, f64)]) -> String {
    format!(
        "{}{}{}[[contact]]\nbetween = [\"A\", \"B\"]\n{}[[contact]]\nbetween = [\"B\", \"C\"]\n{}{}",
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        building("C", 4, 3.0e8),
        contact_body(ab),
        contact_body(bc),
        ground_and_solver()
    )
}

/// The pair A–B of [`row`] with the levels `ab`.
fn pair(ab: &[(f64, f64)]) -> String {
    format!(
        "{}{}[contact]\n{}{}",
        building("A", 4, 3.0e8),
        building("B", 5, 1.6e8),
        contact_body(ab),
        ground_and_solver()
    )
}

fn write(path: &Path, text: &str) -> PathBuf {
    std::fs::write(path, text).unwrap();
    path.to_path_buf()
}

fn sweep_file(dir: &Path, name: &str, base: &str, axes: &str) -> PathBuf {
    write(&dir.join(name), &format!("scenario = \"{base}\"\n{axes}"))
}

/// Case `case` of `sweep` computed (self-checked with `check`) as a map column → field.
fn case_row(sweep: &Sweep, case: usize, check: bool) -> BTreeMap<String, String> {
    let head = parse_csv_line(&header(sweep)).unwrap();
    let f = parse_csv_line(&compute_case(sweep, case, check).line).unwrap();
    assert_eq!(f.len(), head.len());
    head.into_iter().zip(f).collect()
}

fn num(row: &BTreeMap<String, String>, k: &str) -> f64 {
    row.get(k)
        .unwrap_or_else(|| panic!("no column {k}"))
        .parse()
        .unwrap_or_else(|_| panic!("{k} = {:?}", row[k]))
}

/// A row whose second gap never closes (10 m at 10.5 m; C a copy of A, so that the row's
/// first-mode periods — which set the suite's scaling — are the pair's) gives, case by case,
/// the pair suite sweep's columns of A–B over the same axes (B's stiffness, A–B's top gap):
/// pair 1's design value at each level is the pair's `levelK_required_separation`, its
/// governing level's height, design value and margin the pair's governing level's, its verdict
/// the pair's; its design peak force is the largest of the pair's levels' (EC8 with 3 records
/// takes the largest record, so the largest over levels and records in either order); the
/// row's verdict is pair 1's (pair 2's margin is ~10 m). Every number compared is the same
/// arithmetic on the same bits (the runs without contact, and the forces: see
/// tests/suite_row.rs), so the comparison is exact, with one level A–B and with two.
#[test]
fn a_row_suite_sweep_whose_second_gap_never_closes_is_the_pair_suite_sweep() {
    let d = tempfile::tempdir().unwrap();
    let mut pounded = 0;
    for ab in [&[(14.0, 0.01)][..], &[(14.0, 0.01), (10.5, 0.01)][..]] {
        write(&d.path().join("row.toml"), &row(ab, &[(10.5, 10.0)]));
        write(&d.path().join("pair.toml"), &pair(ab));
        let gaps = "values = [0.004, 0.02]\n";
        let (row_gap, pair_gap) = if ab.len() == 1 {
            ("contact[1].gap", "contact.gap")
        } else {
            ("contact[1].level[1].gap", "contact.level.1.gap")
        };
        let rs = Sweep::from_file(&sweep_file(
            d.path(),
            "r.toml",
            "row.toml",
            &format!(
                "[[axis]]\nkey = \"structure[2].stiffness_scale\"\nvalues = [0.8, 1.0]\n\
                 [[axis]]\nkey = \"{row_gap}\"\n{gaps}"
            ),
        ))
        .unwrap();
        let ps = Sweep::from_file(&sweep_file(
            d.path(),
            "p.toml",
            "pair.toml",
            &format!(
                "[[axis]]\nkey = \"structure.2.stiffness_scale\"\nvalues = [0.8, 1.0]\n\
                 [[axis]]\nkey = \"{pair_gap}\"\n{gaps}"
            ),
        ))
        .unwrap();
        assert_eq!(rs.len(), 4);
        for case in 0..rs.len() {
            let r = case_row(&rs, case, false);
            let p = case_row(&ps, case, false);
            assert_eq!((r["status"].as_str(), p["status"].as_str()), ("ok", "ok"));
            let same = |rk: &str, pk: &str| assert_eq!(r[rk], p[pk], "case {case}: {rk} / {pk}");
            same("records", "records");
            same("statistic", "statistic");
            same("min_mean_to_target_ratio", "min_mean_to_target_ratio");
            same("pair1_sufficient", "sufficient");
            same("pair1_margin", "governing_margin");
            same("sufficient", "sufficient");
            same("governing_margin", "governing_margin");
            same("converged", "converged");
            assert_eq!(r["structures"], "3");
            assert_eq!(r["governing_pair"], "1", "case {case}");
            let g = num(&p, "governing_level") as usize;
            same("pair1_required", &format!("level{g}_required_separation"));
            assert_eq!(num(&r, "pair1_governing_height"), ab[g - 1].0);
            assert_eq!(num(&r, "governing_height"), ab[g - 1].0);
            let mut force = 0.0_f64;
            for k in 1..=ab.len() {
                same(
                    &format!("pair1_level{k}_required_separation"),
                    &format!("level{k}_required_separation"),
                );
                force = force.max(num(&p, &format!("level{k}_peak_force")));
            }
            assert_eq!(num(&r, "pair1_peak_force"), force, "case {case}");
            pounded += (force > 0.0) as usize;
            // the second gap never closes: no force, and a margin of nearly its 10 m
            assert_eq!(r["pair2_peak_force"], "0.0");
            assert_eq!(r["pair2_sufficient"], "true");
            assert!(num(&r, "pair2_margin") > 9.0);
        }
    }
    assert!(pounded >= 2, "the test needs pounding cases");
}

// ---------------------------------------------------------------------------------------------
// summary.json read without rounding: serde_json's default float parser may be an ulp off, so
// the design values are compared as the text summary.json holds, parsed by Rust's own parser.

/// A JSON value, numbers kept as their text.
#[derive(Debug)]
enum J {
    Num(String),
    Text(String),
    Other,
    Arr(Vec<J>),
    Obj(Vec<(String, J)>),
}

impl J {
    fn get(&self, key: &str) -> &J {
        match self {
            J::Obj(m) => &m.iter().find(|(k, _)| k == key).unwrap().1,
            _ => panic!("not an object at {key}"),
        }
    }
    fn at(&self, i: usize) -> &J {
        match self {
            J::Arr(v) => &v[i],
            _ => panic!("not an array"),
        }
    }
    fn len(&self) -> usize {
        match self {
            J::Arr(v) => v.len(),
            _ => panic!("not an array"),
        }
    }
    fn f64(&self) -> f64 {
        match self {
            J::Num(t) => t.parse().unwrap(),
            _ => panic!("not a number"),
        }
    }
}

fn json(text: &str) -> J {
    fn ws(b: &[u8], i: &mut usize) {
        while *i < b.len() && b[*i].is_ascii_whitespace() {
            *i += 1;
        }
    }
    fn string(b: &[u8], i: &mut usize) -> String {
        // (the keys and values read here have no escapes but quotes and backslashes)
        *i += 1;
        let mut out = Vec::new();
        while b[*i] != b'"' {
            if b[*i] == b'\\' {
                *i += 1;
            }
            out.push(b[*i]);
            *i += 1;
        }
        *i += 1;
        String::from_utf8(out).unwrap()
    }
    fn value(b: &[u8], i: &mut usize) -> J {
        ws(b, i);
        match b[*i] {
            b'{' => {
                *i += 1;
                let mut m = Vec::new();
                loop {
                    ws(b, i);
                    if b[*i] == b'}' {
                        *i += 1;
                        return J::Obj(m);
                    }
                    let k = string(b, i);
                    ws(b, i);
                    *i += 1; // ':'
                    m.push((k, value(b, i)));
                    ws(b, i);
                    if b[*i] == b',' {
                        *i += 1;
                    }
                }
            }
            b'[' => {
                *i += 1;
                let mut v = Vec::new();
                loop {
                    ws(b, i);
                    if b[*i] == b']' {
                        *i += 1;
                        return J::Arr(v);
                    }
                    v.push(value(b, i));
                    ws(b, i);
                    if b[*i] == b',' {
                        *i += 1;
                    }
                }
            }
            b'"' => J::Text(string(b, i)),
            b't' | b'f' | b'n' => {
                while *i < b.len() && b[*i].is_ascii_alphabetic() {
                    *i += 1;
                }
                J::Other
            }
            _ => {
                let start = *i;
                while *i < b.len()
                    && matches!(b[*i], b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E')
                {
                    *i += 1;
                }
                J::Num(String::from_utf8(b[start..*i].to_vec()).unwrap())
            }
        }
    }
    value(text.as_bytes(), &mut 0)
}

/// The design values of two cases of a row suite sweep (each pair's design value at each of
/// its levels, its governing level's height, design value and margin, its verdict, its design
/// peak force; the row's verdict, governing pair, height and margin; the statistic, the
/// number of records and the lowest mean-to-target ratio) are those of `pounding run` on the
/// case's scenario as `pounding sweep --case N` prints it, bit for bit (summary.json's
/// `suite.design.pairs` and `suite.statistics.pair{p}_peak_force.design`, read as text). The
/// sweep's rows go through the binary too (results.csv).
#[test]
fn design_values_equal_pounding_run_on_the_case() {
    let d = tempfile::tempdir().unwrap();
    write(
        &d.path().join("row.toml"),
        &row(&[(14.0, 0.01), (10.5, 0.01)], &[(14.0, 0.006)]),
    );
    let sw = sweep_file(
        d.path(),
        "s.toml",
        "row.toml",
        "[[axis]]\nkey = \"structure[3].stiffness_scale\"\nvalues = [0.7, 1.3]\n\
         [[axis]]\nkey = \"contact[2].gap\"\nvalues = [0.006]\n",
    );
    ok(&pounding(&[
        "sweep",
        s(&sw),
        "--out",
        s(&d.path().join("sw")),
        "-q",
        "--no-plot",
        "--no-check",
    ]));
    let csv = std::fs::read_to_string(d.path().join("sw/results.csv")).unwrap();
    let mut lines = csv.lines();
    let head = parse_csv_line(lines.next().unwrap()).unwrap();
    let rows: Vec<BTreeMap<String, String>> = lines
        .map(|l| {
            head.iter()
                .cloned()
                .zip(parse_csv_line(l).unwrap())
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), 2);
    let mut pounded = 0;
    for (case, r) in rows.iter().enumerate() {
        assert_eq!(r["status"], "ok");
        let toml = ok(&pounding(&["sweep", s(&sw), "--case", &case.to_string()]));
        let file = write(&d.path().join(format!("case{case}.toml")), &toml);
        let out = d.path().join(format!("run{case}"));
        ok(&pounding(&[
            "run",
            s(&file),
            "--out",
            s(&out),
            "--no-plot",
            "--no-check",
            "-q",
        ]));
        let summary = json(&std::fs::read_to_string(out.join("summary.json")).unwrap());
        let suite = summary.get("suite");
        let design = suite.get("design");
        let pairs = design.get("pairs");
        assert_eq!(pairs.len(), 2);
        let same = |col: &str, v: &J| {
            assert_eq!(
                num(r, col).to_bits(),
                v.f64().to_bits(),
                "case {case}: {col}"
            );
        };
        same("records", design.get("records"));
        same("governing_pair", design.get("governing_pair"));
        let J::Text(stat) = design.get("statistic") else {
            panic!()
        };
        assert_eq!(&r["statistic"], stat);
        same(
            "min_mean_to_target_ratio",
            suite.get("scaling").get("min_mean_to_target_ratio"),
        );
        let gp = num(r, "governing_pair") as usize;
        for p in 1..=2 {
            let dp = pairs.at(p - 1);
            let levels = dp.get("levels");
            let g = dp.get("governing_level").f64() as usize;
            for k in 1..=levels.len() {
                same(
                    &format!("pair{p}_level{k}_required_separation"),
                    levels.at(k - 1).get("required"),
                );
            }
            let gl = levels.at(g - 1);
            same(&format!("pair{p}_governing_height"), gl.get("height"));
            same(&format!("pair{p}_required"), gl.get("required"));
            same(&format!("pair{p}_margin"), gl.get("margin"));
            // the verdict: the gap is at least the design value at every level of the pair
            let sufficient = (0..levels.len()).all(|k| {
                let l = levels.at(k);
                l.get("gap").f64() >= l.get("required").f64()
            });
            assert_eq!(r[&format!("pair{p}_sufficient")], sufficient.to_string());
            same(
                &format!("pair{p}_peak_force"),
                suite
                    .get("statistics")
                    .get(&format!("pair{p}_peak_force"))
                    .get("design"),
            );
            pounded += (num(r, &format!("pair{p}_peak_force")) > 0.0) as usize;
            if p == gp {
                same("governing_height", gl.get("height"));
                same("governing_margin", gl.get("margin"));
            }
        }
        let all = (1..=2).all(|p| r[&format!("pair{p}_sufficient")] == "true");
        assert_eq!(r["sufficient"], all.to_string());
        // the governing pair is the one of least margin (the first of equal margins)
        let m = |p: usize| num(r, &format!("pair{p}_margin"));
        assert_eq!(gp, if m(2) < m(1) { 2 } else { 1 });
    }
    assert!(
        pounded >= 2,
        "the test needs pounding at both pairs or cases"
    );
}

/// Along the gap of one pair (B–C, one level) the design value of that pair does not move (the
/// runs without contact give it; the scaling depends on the periods only), and its verdict
/// flips exactly at it: gaps one part in 10⁹ below, at and above the design value D give too
/// small / suffices / suffices (the rule is gap ≥ D), with margin gap − D; pair 1's numbers do
/// not move either (its gap is not swept, and in the runs without contact the pairs are
/// uncoupled).
#[test]
fn the_verdict_of_a_pair_flips_at_its_design_value() {
    let d = tempfile::tempdir().unwrap();
    write(
        &d.path().join("row.toml"),
        &row(&[(14.0, 0.3)], &[(14.0, 0.01)]),
    );
    let coarse = Sweep::from_file(&sweep_file(
        d.path(),
        "a.toml",
        "row.toml",
        "[[axis]]\nkey = \"contact[2].gap\"\nvalues = [0.0005, 0.5]\n",
    ))
    .unwrap();
    let rows: Vec<_> = (0..2).map(|c| case_row(&coarse, c, false)).collect();
    let design = num(&rows[0], "pair2_required");
    assert!(design > 0.0005 && design < 0.5, "{design}");
    assert_eq!(num(&rows[1], "pair2_required"), design);
    assert_eq!(rows[0]["pair1_required"], rows[1]["pair1_required"]);
    assert!(
        num(&rows[0], "pair2_peak_force") > 0.0,
        "the narrow gap pounds"
    );
    assert_eq!(rows[0]["converged"], "unchecked");
    let (below, above) = (design * (1.0 - 1e-9), design * (1.0 + 1e-9));
    let fine = Sweep::from_file(&sweep_file(
        d.path(),
        "b.toml",
        "row.toml",
        &format!(
            "[[axis]]\nkey = \"contact[2].gap\"\nvalues = [{below:?}, {design:?}, {above:?}]\n"
        ),
    ))
    .unwrap();
    let mut lines = Vec::new();
    for (case, (gap, expected)) in [(below, false), (design, true), (above, true)]
        .into_iter()
        .enumerate()
    {
        lines.push(compute_case(&fine, case, false).line);
        let r = case_row(&fine, case, false);
        assert_eq!(num(&r, "contact.2.gap"), gap);
        assert_eq!(num(&r, "pair2_required"), design, "case {case}");
        assert_eq!(
            num(&r, "pair2_level1_required_separation"),
            design,
            "case {case}"
        );
        assert_eq!(r["pair2_sufficient"], expected.to_string(), "case {case}");
        assert_eq!(num(&r, "pair2_margin"), gap - design, "case {case}");
        assert_eq!(r["pair1_required"], rows[0]["pair1_required"]);
    }
    // the typed columns of the Python package's `pounding.sweep` (`results::columns`): the
    // verdicts, the statistic and `converged` as text, every other result a number
    use pounding::output::run::Column;
    let cols = pounding::study::sweep::results::columns(&fine, &lines).unwrap();
    for (name, col) in &cols {
        let text = matches!(name.as_str(), "status" | "statistic" | "converged")
            || name.ends_with("sufficient");
        match col {
            Column::Text(v) => assert!(text, "{name}: {v:?}"),
            Column::Float(v) => assert!(!text && v.len() == 3, "{name}"),
            Column::Int(_) => assert_eq!(name, "case"),
        }
    }
    let get = |n: &str| &cols.iter().find(|(k, _)| k == n).unwrap().1;
    let Column::Text(v) = get("pair2_sufficient") else {
        panic!()
    };
    assert_eq!(v, &["false", "true", "true"]);
    let Column::Float(v) = get("pair2_required") else {
        panic!()
    };
    assert_eq!(v, &[design; 3]);
}

/// A row suite sweep's journal cut after some rows (with a torn last line) resumes to the
/// table of an uninterrupted run, byte for byte; two shards merge into it; the default
/// pictures (the row's margin and verdict) are drawn and `pounding plot --field pair2_margin`
/// draws another; a journal of another kind in the directory (a row sweep's, a pair suite
/// sweep's) is refused, naming both kinds.
#[test]
fn row_suite_sweeps_resume_shard_merge_and_refuse_other_journals() {
    let d = tempfile::tempdir().unwrap();
    write(
        &d.path().join("row.toml"),
        &row(&[(14.0, 0.02)], &[(14.0, 0.01)]),
    );
    let sw = sweep_file(
        d.path(),
        "s.toml",
        "row.toml",
        "[[axis]]\nkey = \"structure[2].stiffness_scale\"\nvalues = [0.8, 1.0, 1.25]\n\
         [[axis]]\nkey = \"contact[2].gap\"\nvalues = [0.005, 0.05]\n",
    );
    let full = d.path().join("full");
    ok(&pounding(&["sweep", s(&sw), "--out", s(&full), "-q"]));
    let reference = std::fs::read_to_string(full.join("results.csv")).unwrap();
    assert_eq!(reference.lines().count(), 7);
    let journal = std::fs::read_to_string(full.join("journal.csv")).unwrap();
    assert!(
        journal.starts_with("# pounding sweep journal v6;"),
        "{journal}"
    );
    // every case self-checked
    assert!(
        reference.lines().skip(1).all(|l| l.ends_with(",true")),
        "{reference}"
    );

    // a journal with two rows and a torn third: resumed, the rest computed
    let cut = d.path().join("cut");
    std::fs::create_dir(&cut).unwrap();
    let mut j: String = journal.lines().take(4).map(|l| format!("{l}\n")).collect();
    j.push_str(&journal.lines().nth(4).unwrap()[..20]);
    std::fs::write(cut.join("journal.csv"), j).unwrap();
    let out = ok(&pounding(&["sweep", s(&sw), "--out", s(&cut), "--no-plot"]));
    assert!(out.contains("2 resumed"), "{out}");
    assert_eq!(
        std::fs::read_to_string(cut.join("results.csv")).unwrap(),
        reference
    );

    // shards
    let merged = common::sharded_and_merged(&sw, d.path(), 2, &["--no-plot"]);
    assert_eq!(merged, reference);

    // the pictures
    let plots = full.join("plots");
    for f in [
        "heatmap_governing_margin_structure.2.stiffness_scale-contact.2.gap.png",
        "heatmap_sufficient_structure.2.stiffness_scale-contact.2.gap.png",
    ] {
        assert!(plots.join(f).is_file(), "{f} missing");
    }
    let one = d.path().join("one");
    ok(&pounding(&[
        "plot",
        s(&full.join("results.csv")),
        "--field",
        "pair2_margin",
        "--out",
        s(&one),
        "-q",
    ]));
    assert!(
        one.join("heatmap_pair2_margin_structure.2.stiffness_scale-contact.2.gap.png")
            .is_file()
    );

    // a row sweep (one record) and a pair suite sweep into this directory: refused
    let record = format!(
        "[ground_motion]\nkind = \"record\"\nfile = \"{}RSN753_LOMAP_CLS000.AT2\"\n",
        records_dir()
    );
    let one_record = row(&[(14.0, 0.02)], &[(14.0, 0.01)]);
    let one_record = format!(
        "{}{record}[solver]\nmethod = \"exact-modal\"\nduration = 6.0\n",
        &one_record[..one_record.find("[ground_motion]").unwrap()]
    );
    write(&d.path().join("row1.toml"), &one_record);
    write(&d.path().join("pair.toml"), &pair(&[(14.0, 0.02)]));
    for (base, key, what) in [
        ("row1.toml", "contact[2].gap", "a row of buildings per case"),
        ("pair.toml", "contact.gap", "a suite of records per case"),
    ] {
        let other = sweep_file(
            d.path(),
            "t.toml",
            base,
            &format!("[[axis]]\nkey = \"{key}\"\nvalues = [0.01]\n"),
        );
        let out = pounding(&["sweep", s(&other), "--out", s(&cut), "--no-plot"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success()
                && err.contains("a suite of records on a row of buildings per case")
                && err.contains(&format!("this sweep has {what}"))
                && err.contains("never mixed"),
            "{base}: {err}"
        );
    }
    // and the other way round: the row suite sweep into the row sweep's directory
    let rowdir = d.path().join("rowdir");
    let row_sweep = sweep_file(
        d.path(),
        "u.toml",
        "row1.toml",
        "[[axis]]\nkey = \"contact[2].gap\"\nvalues = [0.01]\n",
    );
    ok(&pounding(&[
        "sweep",
        s(&row_sweep),
        "--out",
        s(&rowdir),
        "-q",
        "--no-plot",
        "--no-check",
    ]));
    let out = pounding(&["sweep", s(&sw), "--out", s(&rowdir), "--no-plot"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success()
            && err.contains("(a row of buildings per case; this sweep has a suite of records on a row of buildings per case)"),
        "{err}"
    );
}

/// The keys of one ground motion cannot be axes of a sweep over a suite on a row (named with
/// the axis and its line), nor a pair or structure beyond the row; a sweep whose case cannot
/// meet its rule fails that case with the rule's reason.
#[test]
fn bad_row_suite_sweeps_are_refused_naming_the_axis() {
    let d = tempfile::tempdir().unwrap();
    write(
        &d.path().join("row.toml"),
        &row(&[(14.0, 0.02)], &[(14.0, 0.01)]),
    );
    for key in [
        "ground_motion.scale_to_pga",
        "ground_motion.pga",
        "ground_motion.file",
    ] {
        let value = if key.ends_with("file") {
            "\"r1.txt\""
        } else {
            "0.3"
        };
        let p = sweep_file(
            d.path(),
            "bad.toml",
            "row.toml",
            &format!(
                "[[axis]]\nkey = \"contact[1].gap\"\nvalues = [0.1]\n\
                 [[axis]]\nkey = \"{key}\"\nvalues = [{value}]\n"
            ),
        );
        let e = Sweep::from_file(&p).unwrap_err().to_string();
        assert!(
            e.contains("bad.toml:5:1")
                && e.contains("`axis[2].key`")
                && e.contains(&format!("`{key}`"))
                && e.contains("suite of records"),
            "{key}: {e}"
        );
    }
    for (key, what) in [
        ("contact[3].gap", "pair"),
        ("structure[4].stiffness_scale", "structure"),
    ] {
        let p = sweep_file(
            d.path(),
            "bad.toml",
            "row.toml",
            &format!("[[axis]]\nkey = \"{key}\"\nvalues = [0.5]\n"),
        );
        let e = Sweep::from_file(&p).unwrap_err().to_string();
        assert!(
            e.contains("bad.toml:2:1")
                && e.contains(key.split('[').next().unwrap())
                && e.contains(what),
            "{key}: {e}"
        );
    }
    // a contact table of levels takes its gap by level
    let p = sweep_file(
        d.path(),
        "bad.toml",
        "row.toml",
        "[[axis]]\nkey = \"contact[1].level[2].gap\"\nvalues = [0.5]\n",
    );
    let e = Sweep::from_file(&p).unwrap_err().to_string();
    assert!(e.contains("level"), "{e}");

    // EC8 needs three records: a two-record suite on a row fails every case with that reason
    let text = row(&[(14.0, 0.02)], &[(14.0, 0.01)]);
    let cut = text.replacen(
        &format!(
            "  {{ file = \"{}RSN808_LOMAP_TRI000.AT2\" }},\n",
            records_dir()
        ),
        "",
        1,
    );
    assert_ne!(cut, text);
    write(&d.path().join("two.toml"), &cut);
    let sw = Sweep::from_file(&sweep_file(
        d.path(),
        "two-sweep.toml",
        "two.toml",
        "[[axis]]\nkey = \"contact[2].gap\"\nvalues = [0.1]\n",
    ))
    .unwrap();
    let row = compute_case(&sw, 0, false);
    assert!(row.failed);
    assert!(
        row.line.contains("failed: ground_motion.scaling:") && row.line.contains("at least 3"),
        "{}",
        row.line
    );
}
