//! `hpr_sim`: the flight. It owns the kernels (cycloid, mass properties at an instant,
//! atmosphere, wind, aerodynamic loads, the one rigid-body derivative), the integrators and
//! event location, triggers, parachutes, mass shifts, released masses, and the two drivers built on the same
//! kernels: the single-flight [`Simulation`] and the structure-of-arrays batch engine; and the
//! reference rocket the worked examples, benchmarks and tests fly ([`reference`](mod@reference)).

pub mod aero_loads;
pub mod atmosphere;
pub mod batch;
pub mod cycloid;
pub mod eom;
pub mod events;
pub mod flight;
pub mod frames;
pub mod gravity;
pub mod inputs;
pub mod integrate;
pub mod lanes;
pub mod massprops;
pub mod reference;
pub mod releases;
pub mod sensor;
pub mod shifts;
pub mod sounding;
pub mod trigger;
pub mod turbulence;
pub mod weather;
pub mod wind;

pub use events::EventKind;
pub use flight::{
    AirModel, CanopyShape, Environment, Flight, Integrator, Parachute, Rail, SimError, SimOptions,
    Simulation, Warning,
};
pub use releases::{PartChute, PartTrigger, Release};
pub use sensor::SensorNoise;
pub use shifts::MassShift;
pub use trigger::Trigger;
