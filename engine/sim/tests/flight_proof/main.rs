//! The proof of the 6-DOF flight simulator: flights checked against exact
//! answers (the vacuum parabola, conservation of momentum and angular momentum, the rocket
//! equation), the convergence order of RK4, events landing on their roots, RocketPy 1.13's
//! Calisto, and bad input. Each test states its tolerance and prints what it measured
//! (`cargo test --release -p hpr_sim --test flight_proof -- --nocapture`).
//!
//! An integration test (not a `#[cfg(test)]` module) because it needs nothing private: the
//! public `Simulation`, `FlightModel` and `eom` are enough, which is also what users get.

mod air_brakes;
mod batch_rockets;
mod calisto;
mod clusters;
mod common;
mod coriolis;
mod crosscheck;
mod descent;
mod drag;
mod events;
mod exact;
mod inputs;
mod jet_damping;
mod large_angles;
mod limits;
mod motor_model;
mod noise_crosscheck;
mod profile_crosscheck;
mod random_crosscheck;
mod rocket_equation;
mod sampling;
mod sensor_noise;
mod sounding_crosscheck;
mod warnings;
