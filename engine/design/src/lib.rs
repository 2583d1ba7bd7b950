//! `hpr_design`: everything about a rocket that does not depend on the flight.
//!
//! It owns the design format (a JSON component tree in the spirit of OpenRocket), its
//! validation, the mass properties of any subtree (parallel-axis theorem, overrides), the
//! Barrowman aerodynamic coefficients, and motors (RASP `.eng`, RockSim `.rse`, the bundled
//! library). The flight crate `hpr_sim` reads these once, before a flight, into plain tables.
//!
//! # Frames and units
//! SI everywhere. Positions along the airframe are metres **aft of the nose tip**. The
//! *station frame* used throughout this crate has `x` along the rocket's axis pointing aft
//! (from the nose tip toward the tail), with `y` and `z` across it, right-handed, origin at
//! the nose tip. Inertia tensors are in kg·m² in station axes.

pub mod aero;
pub mod design;
pub mod error;
pub mod limits;
pub mod mass;
pub mod motor;
pub mod ork;

pub use design::{
    AirBrakes, Component, ComponentKind, Deploy, DeployTrigger, Design, MAX_PART_SIZE_M,
    MAX_SAMPLING_RATE_HZ,
};
pub use error::DesignError;
pub use mass::MassProps;
