//! The design format: raw JSON (serde) in [`raw`], turned in one place ([`validate`]) into the
//! validated [`model`] that the rest of hpr reads. Only this module knows about serde.
//! [`shapes`] holds the nose-cone and transition profiles that mass and aerodynamics share.

pub mod dimension;
pub mod json_errors;
pub mod model;
pub mod raw;
pub mod shapes;
pub mod validate;

pub use model::*;
