//! `pounding fragility`: the study run (journaled in DIR, resumed when rerun; a part of it with
//! --shard; its parts joined with --merge), its files and figures written (fit.json last), its
//! report printed (`study::fragility::report`).

use std::io::IsTerminal as _;
use std::path::Path;

use pounding::study::fragility;
use pounding::study::sweep::Shard;

use super::args;
use super::list_paths;

pub fn fragility(a: args::FragilityArgs, quiet: bool) -> anyhow::Result<()> {
    let path = a.study.as_path();
    let study = pounding::input::fragility::FragilityStudy::from_file(path)?;
    let out = a.out.clone().unwrap_or_else(|| {
        let stem = path.file_stem().unwrap_or_default();
        Path::new("out").join(stem)
    });
    let err = |e: fragility::FragilityError| anyhow::anyhow!("{}: {e}", path.display());
    let run = if !a.merge.is_empty() {
        fragility::journal::merge(&study, &a.merge).map_err(err)?
    } else {
        let shard = a.shard.unwrap_or(Shard::ALL);
        let store = fragility::journal::open(&study, &out, shard).map_err(err)?;
        let tasks = fragility::journal::part(&study, shard);
        if !quiet && std::io::stderr().is_terminal() {
            eprintln!(
                "  running {} tasks (at most {} runs, each with and without contact){} …",
                tasks.len(),
                study.runs(),
                match store.resumed() {
                    0 => String::new(),
                    n => format!("; {n} runs found in the journal (resuming)"),
                }
            );
        }
        let record_im = fragility::record_ims(&study).map_err(err)?;
        let outcomes =
            fragility::run_tasks(&study, &record_im, &tasks, a.jobs, &store).map_err(err)?;
        if !quiet && store.resumed() > 0 {
            println!(
                "resumed from {}: {} runs found, {} computed now{}",
                out.join(pounding::study::sweep::results::file_names(shard).1)
                    .display(),
                store.resumed(),
                store.computed(),
                match store.dropped {
                    0 => String::new(),
                    n => format!(" ({n} torn or damaged lines dropped)"),
                }
            );
        }
        if !shard.is_all() {
            if !quiet {
                println!(
                    "part {shard} of {}: {} tasks, {} runs ({} computed now); journal {}",
                    path.display(),
                    tasks.len(),
                    outcomes.len(),
                    store.computed(),
                    out.join(format!("journal-shard-{}-of-{}.csv", shard.k, shard.n))
                        .display()
                );
                println!(
                    "join the parts: pounding fragility {} --merge DIR… --out DIR",
                    path.display()
                );
            }
            return Ok(());
        }
        fragility::assemble(study.clone(), record_im, outcomes)
    };
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
