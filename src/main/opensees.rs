//! The commands that go through OpenSees: `pounding export opensees` (the script) and
//! `pounding crosscheck` (run it and compare).

use pounding::output::text;

use super::args;
use super::{load, quiet_or, refuse_suite};

pub fn export(a: args::OpenseesArgs, quiet: bool) -> anyhow::Result<()> {
    let (sc, name) = load(a.scenario)?;
    refuse_suite(&sc)?;
    let opts = pounding::opensees::ExportOptions {
        elements: a.elements,
        dt: a.dt,
        duration: a.duration,
        only: a
            .only
            .as_deref()
            .and_then(pounding::opensees::Only::from_name),
    };
    let script = pounding::opensees::row::any_script(&sc, &opts, &name)?;
    let Some(path) = a.out else {
        print!("{script}");
        return Ok(());
    };
    pounding::output::atomic::write_atomic(&path, script.as_bytes())?;
    let p = path.display();
    quiet_or(quiet, || {
        println!("wrote {p} (run it: python3 {p} [--json results.json])")
    })
}

pub fn crosscheck(a: args::CrosscheckArgs, quiet: bool) -> anyhow::Result<()> {
    use pounding::opensees::{ExportOptions, compare};
    let (sc, name) = load(a.scenario)?;
    refuse_suite(&sc)?;
    let export = ExportOptions {
        elements: a.elements,
        dt: a.dt,
        duration: a.duration,
        only: None,
    };
    let opts = compare::CrosscheckOptions {
        export,
        modes: a.modes,
        keep: a.keep,
    };
    let python = compare::python();
    if !quiet {
        eprintln!("  running OpenSees ({python}) and the program …");
    }
    let table = if sc.is_row() {
        pounding::opensees::row_compare::crosscheck_row(&sc, &name, &opts, &python)?.table()
    } else {
        compare::crosscheck(&sc, &name, &opts, &python)?.table()
    };
    print!("{}{}", text::heading(&sc.title, &name), table);
    Ok(())
}
