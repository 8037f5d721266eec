//! The library functions the Python package calls (issue 12): each gives what the command line's
//! path gives — a table validates as its file, a captured run writes the bytes a streamed run
//! writes, the in-memory sweep rows are results.csv's, key paths set as a sweep sets them.

use std::path::Path;

use pounding::analysis::simulate::{RunCapture, simulate_streaming};
use pounding::input::scenario::Scenario;
use pounding::output::run::Column;
use pounding::output::writer::{RunWriter, write_run};
use pounding::study::sweep::Sweep;

fn example(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

#[test]
fn a_table_validates_as_its_file() {
    let path = example("paper-c.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let table: toml::Table = toml::from_str(&text).unwrap();
    let dir = path.parent().unwrap();
    let name = path.display().to_string();
    assert_eq!(
        Scenario::from_table(&table, &name, dir).unwrap(),
        Scenario::from_file(&path).unwrap()
    );
    // the same refusal, with the same key and reason (positions are in the table's text)
    let bad = text.replace("gap = 0.0127", "gap = -1.0");
    let mut table: toml::Table = toml::from_str(&bad).unwrap();
    let from_table = Scenario::from_table(&table, "<dict>", dir)
        .unwrap_err()
        .to_string();
    let from_text = Scenario::from_toml(&bad, "<dict>", dir)
        .unwrap_err()
        .to_string();
    let tail = |s: &str| s.split_once(": ").unwrap().1.to_string();
    assert_eq!(tail(&from_table), tail(&from_text));
    assert!(from_table.contains("`contact.gap` = -1"), "{from_table}");
    // anything in a table is an error, not a panic
    table.insert("structure".into(), toml::Value::Integer(3));
    assert!(Scenario::from_table(&table, "<dict>", dir).is_err());
    assert!(Scenario::from_table(&toml::Table::new(), "<dict>", dir).is_err());
}

#[test]
fn a_captured_run_writes_the_bytes_of_a_streamed_run() {
    let sc = Scenario::from_file(&example("two-levels.toml")).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let streamed = tmp.path().join("streamed");
    let mut writer = RunWriter::for_scenario(&streamed, &sc).unwrap();
    let report = simulate_streaming(&sc, false, &mut writer).unwrap();
    writer.finish(&sc, &report, None).unwrap();

    let mut capture = RunCapture::new();
    let again = simulate_streaming(&sc, false, &mut capture).unwrap();
    let replayed = tmp.path().join("replayed");
    let files = write_run(&replayed, &sc, &again, &capture, None).unwrap();
    assert_eq!(files.last().unwrap().file_name().unwrap(), "summary.json");
    for f in ["history.csv", "impacts.csv", "floors.csv", "summary.json"] {
        assert_eq!(
            std::fs::read(streamed.join(f)).unwrap(),
            std::fs::read(replayed.join(f)).unwrap(),
            "{f}"
        );
    }
    // the columns are the file's numbers
    let csv = std::fs::read_to_string(streamed.join("history.csv")).unwrap();
    let cols = capture.history_columns();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(
        cols.iter().map(|(k, _)| k.as_str()).collect::<Vec<_>>(),
        header
    );
    for (i, line) in csv.lines().skip(1).enumerate() {
        for (j, x) in line.split(',').enumerate() {
            let v: f64 = x.parse().unwrap();
            assert_eq!(v.to_bits(), cols[j].1[i].to_bits(), "row {i} column {j}");
        }
    }
}

#[test]
fn in_memory_rows_are_the_results_rows() {
    let sweep = Sweep::from_file(&example("quick-sweep.toml")).unwrap();
    let rows = pounding::study::sweep::run::compute_all(&sweep, 2, false).unwrap();
    assert_eq!(rows.len(), sweep.len());
    for (c, r) in rows.iter().enumerate() {
        assert_eq!(
            r.line,
            pounding::study::sweep::run::compute_case(&sweep, c, false).line
        );
        assert!(r.line.starts_with(&format!("{c},")));
    }
    let lines: Vec<&str> = rows.iter().map(|r| r.line.as_str()).collect();
    let cols = pounding::study::sweep::results::columns(&sweep, &lines).unwrap();
    let header = pounding::study::sweep::results::header(&sweep);
    assert_eq!(
        cols.iter()
            .map(|(k, _)| k.as_str())
            .collect::<Vec<_>>()
            .join(","),
        header
    );
    assert!(matches!(&cols[0].1, Column::Int(v) if v.len() == sweep.len()));
    // the same sweep rebuilt from its sources (another process) has the same cases
    let (text, path, base, base_path) = sweep.sources();
    let again = Sweep::from_toml_with_base(text, path, Some((base, base_path))).unwrap();
    assert_eq!(again.identity(), sweep.identity());
    assert_eq!(again.case_toml(7).unwrap(), sweep.case_toml(7).unwrap());
}

#[test]
fn set_keys_sets_as_a_sweep_sets() {
    let path = example("paper-c.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let out = pounding::study::sweep::set_keys(
        &text,
        &path,
        vec![
            ("period_ratio".into(), toml::Value::Float(0.5)),
            ("ground_motion.pga".into(), toml::Value::Float(0.4)),
        ],
    )
    .unwrap();
    let t: toml::Table = toml::from_str(&out).unwrap();
    let s = t["structure"].as_array().unwrap();
    assert_eq!(s[1]["period"].as_float(), Some(0.4203 / 0.5));
    assert_eq!(t["ground_motion"]["pga"].as_float(), Some(0.4));
    let err = pounding::study::sweep::set_keys(
        &text,
        &path,
        vec![("contact.gapp".into(), toml::Value::Float(0.1))],
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("`contact.gapp`: unknown axis key; did you mean `contact.gap`?"),
        "{err}"
    );
}
