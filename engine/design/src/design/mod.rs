//! The design format: raw JSON (serde) in [`raw`], turned in one place ([`validate`]) into the
//! validated [`model`] that the rest of hpr reads. Only this module knows about serde.

pub mod model;
pub mod raw;
pub mod validate;

pub use model::*;
