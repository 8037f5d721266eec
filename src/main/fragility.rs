//! `pounding fragility`: the study run, its files and figures written (fit.json last), its
//! report printed (`study::fragility::report`).

use std::io::IsTerminal as _;
use std::path::Path;

use pounding::study::fragility;

use super::args;
use super::list_paths;

pub fn fragility(a: args::FragilityArgs, quiet: bool) -> anyhow::Result<()> {
    let path = a.study.as_path();
    let study = pounding::input::fragility::FragilityStudy::from_file(path)?;
    let out = a.out.unwrap_or_else(|| {
        let stem = path.file_stem().unwrap_or_default();
        Path::new("out").join(stem)
    });
    if !quiet && std::io::stderr().is_terminal() {
        eprintln!(
            "  running {} runs (with and without contact) …",
            study.runs()
        );
    }
    let run =
        fragility::run(&study, a.jobs).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let mut failed = None;
    let written = fragility::write::write(&run, &out, || {
        if a.no_plot {
            return Vec::new();
        }
        pounding::figures::fragility::pictures(&run, &out).unwrap_or_else(|e| {
            failed = Some(e);
            Vec::new()
        })
    })?;
    if !quiet {
        print!("{}", fragility::report::report(&run));
        println!();
        println!("wrote {}", list_paths(&written));
    }
    for w in fragility::report::warnings(&run) {
        eprintln!("warning: {w}");
    }
    if let Some(e) = failed {
        anyhow::bail!("the figures could not be drawn: {e}");
    }
    Ok(())
}
