//! What `pounding sweep` and `pounding merge` print: a case as a scenario file, the summary of
//! a run of the grid (cases computed, resumed, failed, the self-check's counts), the warnings
//! about its cases (not converged, with warnings, failed) with the command that shows the
//! first such case, and what to do next.

use std::fmt::Write as _;
use std::path::Path;

use super::Sweep;
use super::merge::MergeSummary;
use super::run::RunOutcome;
use super::shard::Shard;
use crate::analysis::simulate::accuracy::{CHECK_THRESHOLD, percent};

/// Case `case` of `sweep` (read from `path`) as a scenario file, headed by a comment naming
/// the case and its values (`pounding sweep FILE --case N`); the error says why not (a case
/// out of range, or a case that is not a scenario).
pub fn case_file(sweep: &Sweep, path: &Path, case: usize) -> Result<String, String> {
    if case >= sweep.len() {
        return Err(format!(
            "--case {case}: the sweep has {} cases, numbered 0 to {}",
            sweep.len(),
            sweep.len().saturating_sub(1)
        ));
    }
    let text = sweep
        .case_toml(case)
        .map_err(|e| format!("case {case}: {e}"))?;
    Ok(format!(
        "# case {case} of {}: {}\n{text}",
        path.display(),
        sweep.label(case)
    ))
}

/// The summary of a run of `sweep` (read from `path`) on `jobs` threads over `shard`: the
/// counts and speed, the table written, the self-check of the cases (lines, each ending in a
/// newline).
pub fn summary(sweep: &Sweep, path: &Path, o: &RunOutcome, jobs: usize, shard: Shard) -> String {
    let mut s = String::new();
    let part = if shard.is_all() {
        String::new()
    } else {
        format!(" (part {shard} of the grid's {} cases)", sweep.len())
    };
    let speed = if o.computed > 0 {
        format!(
            " ({:.2} ms per case per thread)",
            o.seconds * 1e3 * jobs as f64 / o.computed as f64
        )
    } else {
        String::new()
    };
    let _ = writeln!(
        s,
        "{}: {} cases{part}: {} computed in {:.1} s with {jobs} thread(s){speed}, {} resumed, {} failed",
        path.display(),
        o.cases,
        o.computed,
        o.seconds,
        o.resumed,
        o.failed
    );
    let _ = writeln!(s, "wrote {}", o.results.display());
    if !sweep.code_columns().is_empty() {
        let _ = writeln!(
            s,
            "how often each rule is below the exact separation: pounding rules {}",
            o.results.display()
        );
    }
    let c = &o.check;
    let ok = o.cases - o.failed;
    if ok == 0 {
        // nothing ran to the end: nothing to check
    } else if c.unchecked == ok {
        s.push_str(
            "self-check: not done (--no-check): the cases were NOT self-checked (column converged = unchecked)\n",
        );
    } else if c.converged == ok {
        s.push_str(
            "self-check: every case converged within 1 % against a 100× tighter run (column check_max_change)\n",
        );
    } else {
        let _ = writeln!(
            s,
            "self-check: {} case(s) converged within 1 %, {} NOT converged, {} not checked (columns converged, check_max_change)",
            c.converged, c.not_converged, c.unchecked
        );
    }
    s
}

/// The warning about journal lines dropped as damaged, if any.
pub fn journal_warning(o: &RunOutcome) -> Option<String> {
    (o.dropped > 0).then(|| {
        format!(
            "{} damaged line(s) in the journal were dropped (a kill during a write); their cases were recomputed",
            o.dropped
        )
    })
}

/// The warnings about the cases of a run of `sweep` (read from `path`): cases NOT converged,
/// cases that ran with warnings, failed cases — each naming the first such case (and, for the
/// first two, the commands that rerun it).
pub fn warnings(sweep: &Sweep, path: &Path, o: &RunOutcome) -> Vec<String> {
    let mut w = Vec::new();
    let rerun = |c: usize| {
        format!(
            "(see it with: pounding sweep {} --case {c} > case.toml && pounding run case.toml)",
            path.display()
        )
    };
    if let Some((c, change)) = &o.check.first_not_converged {
        let change = match change.parse::<f64>() {
            Ok(x) if x > CHECK_THRESHOLD => format!("largest change {}", percent(x)),
            _ => "not verified: the check run failed or changed nothing".into(),
        };
        w.push(format!(
            "self-check: {} of {} cases are NOT converged within 1 % (column converged = false); the first, case {c} ({}): {change}\n{}",
            o.check.not_converged,
            o.cases - o.failed,
            sweep.label(*c),
            rerun(*c)
        ));
    }
    if let Some((c, first)) = &o.first_warning {
        w.push(format!(
            "{} of the {} cases computed now ran with warnings; the first, case {c} ({}): {first}\n{}",
            o.warned,
            o.computed,
            sweep.label(*c),
            rerun(*c)
        ));
    }
    if let Some((c, status)) = &o.first_failure {
        w.push(format!(
            "{} of {} cases failed; the first, case {c} ({}): {status}",
            o.failed,
            o.cases,
            sweep.label(*c)
        ));
    }
    w
}

/// The error of a run in which every case failed (nothing to plot or study), if so.
pub fn every_case_failed(o: &RunOutcome) -> Option<String> {
    (o.failed == o.cases && o.cases > 0).then(|| {
        format!(
            "every case failed (see the status column of {})",
            o.results.display()
        )
    })
}

/// What to do after running one part of a sharded grid into `out`.
pub fn merge_hint(out: &Path) -> String {
    format!(
        "when every part is done: pounding merge {}/results.csv {} (then pounding plot)\n",
        out.display(),
        out.display()
    )
}

/// What `pounding merge` did, written to `out`.
pub fn merge_summary(m: &MergeSummary, out: &Path) -> String {
    format!(
        "merged {} part(s): {} cases ({} failed) into {}\n",
        m.parts.len(),
        m.cases,
        m.failed,
        out.display()
    )
}
