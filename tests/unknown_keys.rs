//! Every unknown-key message names its table and lists the table's valid keys
//! — including tables of one or two keys, whose serde message ("expected `a` or `b`") used to
//! be left unparsed ("unknown key `gapp` in this table (valid keys: )").
//!
//! The tables and their keys are written here from the scenario format of the README (Scenario
//! files, Buildings with floors, Yielding storeys, Code separation rules, Parameter sweeps), not
//! taken from the program.

use std::path::Path;

use pounding::input::scenario::Scenario;
use pounding::study::sweep::Sweep;

/// A scenario with every kind of table: structures with `rayleigh` and `hysteresis`, contact
/// levels, a record, a solver table and every code of `[separation]` as its own table.
const BASE: &str = r#"title = "every table"

[[structure]]
kind = "shear-building"
storeys = 4
storey_height = 3.5
floor_mass = 3.0e5
storey_stiffness = 4.85e8
rayleigh = { damping_ratio = 0.05, modes = [1, 3] }

[[structure]]
kind = "shear-building"
storeys = 8
storey_height = 3.5
floor_mass = 3.0e5
storey_stiffness = 3.48e8
damping_ratio = 0.05

[structure.hysteresis]
yield_drifts = 0.0175
post_yield_ratio = 0.05

[contact]
law = "jankowski"
stiffness = 2.75e9
restitution = 0.65

[[contact.level]]
height = 14.0
gap = 0.02

[ground_motion]
kind = "harmonic"
pga = 0.3
period = 0.8

[solver]
duration = 5.0

[separation.asce7]
cd = 5.5
ie = 1.0
r = 8

[separation.is1893]
r = 5
displacement_factor = 0.2

[separation.nbcc]
rd = 4
ro = 1.7
ie = 1.0
displacement_factor = 0.147

[separation.gb50011]
intensity = 8
systems = "frame"

[separation.ntc]
zone = "II"
method = "simplified"
"#;

/// The error of `BASE` with the line `after` followed by `line`.
fn error_with(after: &str, line: &str) -> String {
    assert!(BASE.contains(after), "test edit `{after}` does not apply");
    let text = BASE.replacen(after, &format!("{after}\n{line}"), 1);
    match Scenario::from_toml(&text, "k.toml", Path::new(".")) {
        Ok(_) => panic!("`{line}` after `{after}` must be refused"),
        Err(e) => e.to_string(),
    }
}

/// `message` names `key`, `table` and exactly these valid keys, in this order.
fn assert_names(message: &str, key: &str, table: &str, valid: &[&str]) {
    let expected = format!("unknown key `{key}` in {table}");
    assert!(message.contains(&expected), "{expected}\n{message}");
    let listed = format!("(valid keys: {})", valid.join(", "));
    assert!(message.contains(&listed), "{listed}\n{message}");
    assert!(!message.contains("this table"), "{message}");
}

#[test]
fn the_base_scenario_is_valid() {
    Scenario::from_toml(BASE, "k.toml", Path::new(".")).unwrap();
}

/// One unknown key in every table of a scenario.
#[test]
fn every_scenario_table_names_itself_and_its_keys() {
    let structure = [
        "kind",
        "name",
        "length",
        "mass",
        "period",
        "bending_stiffness",
        "tip_stiffness",
        "modes",
        "damping_ratio",
        "strain_rate_damping",
        "air_damping",
        "floor_heights",
        "floor_masses",
        "storey_stiffnesses",
        "storeys",
        "storey_height",
        "floor_mass",
        "storey_stiffness",
        "rayleigh",
        "periods",
        "mode_shapes",
        "modes_file",
        "hysteresis",
    ];
    let ground = [
        "kind",
        "pga",
        "period",
        "file",
        "units",
        "scale_to_pga",
        "scale_to_sa",
        "dt",
        "component",
        "processing",
        "spectrum",
        "sds",
        "sd1",
        "tl",
        "ag",
        "ground_type",
        "type",
        "records",
        "scaling",
    ];
    // (line after which the key goes, key, table, its valid keys)
    let cases: &[(&str, &str, &str, &[&str])] = &[
        (
            "title = \"every table\"",
            "titel",
            "the top level",
            &[
                "title",
                "structure",
                "contact",
                "ground_motion",
                "solver",
                "separation",
                "output",
            ],
        ),
        (
            "storey_height = 3.5",
            "storey_heigth",
            "[[structure]]",
            &structure,
        ),
        (
            "stiffness = 2.75e9",
            "gapp",
            "[contact]",
            &[
                "between",
                "law",
                "stiffness",
                "restitution",
                "damping_model",
                "gap",
                "height",
                "level",
            ],
        ),
        // two keys: serde says "expected `height` or `gap`"
        (
            "height = 14.0",
            "gapp",
            "[[contact.level]]",
            &["height", "gap"],
        ),
        ("pga = 0.3", "pgaa", "[ground_motion]", &ground),
        (
            "duration = 5.0",
            "steps",
            "[solver]",
            &[
                "method",
                "dt",
                "duration",
                "output_interval",
                "rtol",
                "atol",
            ],
        ),
        (
            "post_yield_ratio = 0.05",
            "alpha",
            "[structure.hysteresis]",
            &[
                "model",
                "yield_drifts",
                "yield_forces",
                "post_yield_ratio",
                "exponent",
                "beta",
                "gamma",
            ],
        ),
        (
            "cd = 5.5",
            "rr",
            "[separation.asce7]",
            &["cd", "ie", "r", "displacement_factor", "boundary"],
        ),
        (
            "r = 5",
            "ie",
            "[separation.is1893]",
            &["r", "displacement_factor", "floor_reduction"],
        ),
        (
            "rd = 4",
            "r",
            "[separation.nbcc]",
            &["rd", "ro", "ie", "displacement_factor"],
        ),
        (
            "intensity = 8",
            "system",
            "[separation.gb50011]",
            &["intensity", "systems", "partial_step"],
        ),
        (
            "zone = \"II\"",
            "zones",
            "[separation.ntc]",
            &[
                "zone",
                "method",
                "same_height_and_levels",
                "displacement_factor",
            ],
        ),
    ];
    for &(after, key, table, valid) in cases {
        let e = error_with(after, &format!("{key} = 1"));
        assert_names(&e, key, table, valid);
    }
    // the two-key inline table `rayleigh = { … }`
    let text = BASE.replace("modes = [1, 3] }", "mode = [1, 3] }");
    let e = Scenario::from_toml(&text, "k.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert_names(
        &e,
        "mode",
        "[structure.rayleigh]",
        &["damping_ratio", "modes"],
    );
    assert!(e.contains("did you mean `modes`?"), "{e}");
    // the suggestion of a two-key table
    let e = error_with("height = 14.0", "gapp = 0.02");
    let line = BASE.lines().position(|l| l == "height = 14.0").unwrap() + 2;
    let at = format!("k.toml:{line}:1:");
    assert!(
        e.contains("did you mean `gap`?") && e.starts_with(&at),
        "{at}\n{e}"
    );
}

/// A sweep file's two tables: the top level (two keys) and `[[axis]]`.
#[test]
fn sweep_tables_name_themselves_and_their_keys() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let sweep = |text: &str| {
        Sweep::from_toml(text, &dir.join("s.toml"))
            .err()
            .unwrap_or_else(|| panic!("must be refused:\n{text}"))
            .to_string()
    };
    let e = sweep("scenario = \"paper-c.toml\"\nscenaro = 1\n");
    assert_names(
        &e,
        "scenaro",
        "the top level of the sweep file",
        &["scenario", "axis"],
    );
    assert!(e.contains("did you mean `scenario`?"), "{e}");
    let e = sweep("scenario = \"paper-c.toml\"\n[[axis]]\nkey = \"contact.gap\"\nvalue = [0.1]\n");
    assert_names(
        &e,
        "value",
        "[[axis]]",
        &["key", "values", "from", "to", "steps", "scale"],
    );
    assert!(
        e.contains("did you mean `values`?") && e.contains("s.toml:4:1"),
        "{e}"
    );
}
