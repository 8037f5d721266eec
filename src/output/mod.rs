//! Files and text reports.

pub mod budget;
pub mod floors_csv;
pub mod record_summary;
pub mod row_spool;
pub mod run;
pub mod spectrum_report;
