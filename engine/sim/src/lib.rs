//! `hpr_sim`: the flight. It owns the kernels (cycloid, mass properties at an instant,
//! atmosphere, wind, aerodynamic loads, the one rigid-body derivative), the integrators and
//! event location, triggers, parachutes, mass shifts, and the two drivers built on the same
//! kernels: the single-flight [`Simulation`] and the structure-of-arrays batch engine.

pub mod cycloid;
pub mod eom;
pub mod frames;
pub mod massprops;
pub mod events;
pub mod trigger;
pub mod shifts;
// pub mod aero_loads; (enabled once hpr_design::aero::table exists)
