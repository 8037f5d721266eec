//! The physical model.

pub mod bouc_wen;
pub mod building;
pub mod cantilever;
pub mod contact;
pub mod ground_motion;
pub mod hysteresis;
pub mod modal;
pub mod structure;
pub mod system;
