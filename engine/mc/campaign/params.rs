//! The inputs a scenario can sweep or disperse are the flight's own ([`hpr_sim::inputs`]:
//! each input's key, unit, rule and how it is applied, described once); a scenario names
//! them by key under `[sweep]` and `[dispersions]` (a parachute's, shift's or release's
//! under its name: [`crate::campaign::scenario::Scenario::key`]).

pub use hpr_sim::inputs::{Domain, Input as Param, GLOBAL};

/// Unit of a trigger's number by its field name.
pub fn trigger_unit(field: &str) -> &'static str {
    match field {
        "height_m" => "m",
        _ => "s",
    }
}
