//! Files and text reports.

pub mod atomic;
pub mod budget;
pub mod csv;
pub mod floors_csv;
pub mod ground_section;
pub mod record_summary;
pub mod row;
pub mod row_spool;
pub mod run;
pub mod sa_scaling;
pub mod spectrum_report;
pub mod text;
pub mod writer;
