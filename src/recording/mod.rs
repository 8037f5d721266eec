//! What a run keeps.

pub mod floor_response;
pub mod history;
pub mod recorder;
pub mod run_record;
pub mod stations;
pub mod storey_record;
pub mod subgrid;
