//! The text reports the command line prints, one file per report, each a function returning
//! the text (`String`), so that the Python package gives the same text: `run_summary` (what
//! `pounding run` prints after a run), `modes_table`, `convergence_table`,
//! `separation_report`, `laws_table`. The reports of the layers above this one live with their
//! drivers: a suite's in `study::suite::report`, a sweep's in `study::sweep::report`, the rule
//! study's in `study::rule_study`.

pub mod convergence_table;
pub mod laws_table;
pub mod modes_table;
pub mod row_separation_report;
pub mod row_summary;
pub mod run_summary;
pub mod separation_report;

pub use convergence_table::convergence_table;
pub use laws_table::laws_table;
pub use modes_table::modes_table;
pub use row_separation_report::row_separation_report;
pub use row_summary::row_summary;
pub use run_summary::{run_summary, self_check_line, time_history_verdict};
pub use separation_report::separation_report;

/// "1 impact", "15 impacts".
pub(crate) fn impacts(n: usize) -> String {
    if n == 1 {
        "1 impact".into()
    } else {
        format!("{n} impacts")
    }
}

/// The two lines that head a report of a scenario: its title, and its name (the file, or the
/// bundled default) indented.
pub fn heading(title: &str, name: &str) -> String {
    format!("{title}\n  scenario: {name}\n")
}
