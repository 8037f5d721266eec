//! What a run keeps.

pub mod floor_response;
pub mod recorder;
pub mod storey_record;
