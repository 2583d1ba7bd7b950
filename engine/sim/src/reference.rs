//! The reference rocket: the synthetic 54 mm three-fin design
//! (`validation/designs/synthetic-54mm-three-fin.json`, built into the library) on its Cesaroni
//! I175, with its 200 g ballast that slides 0.3 m toward the tail over one second. It is the
//! rocket of the moving-mass worked example (`docs/moving-mass.md`), of the benchmarks and of
//! many tests; they all build it here, so that they fly the same rocket.

use crate::flight::{Environment, Rail, Simulation};
use crate::shifts::MassShift;
use crate::trigger::Trigger;
use hpr_design::motor::{self, Motor};
use hpr_design::Design;

/// The reference design's JSON, as `validation/designs/synthetic-54mm-three-fin.json` holds it.
pub const DESIGN_JSON: &str =
    include_str!("../../../validation/designs/synthetic-54mm-three-fin.json");

/// The reference design's motor, a bundled file's stem.
pub const MOTOR: &str = "Cesaroni_I175";

/// The id of the reference design's ballast (a mass component of 200 g in the body tube).
pub const BALLAST: &str = "ballast";

/// How far the ballast slides toward the tail, m, and in how long, s.
pub const BALLAST_TRAVEL_M: f64 = 0.3;
pub const BALLAST_DURATION_S: f64 = 1.0;

/// The reference design, validated.
///
/// Panics only if the JSON built into the library is not a valid design, which this module's
/// tests rule out.
pub fn design() -> Design {
    Design::from_json_str(DESIGN_JSON, None).expect("the built-in reference design is valid")
}

/// The reference design's motor, from the bundled library.
pub fn motor() -> Motor {
    motor::find(MOTOR).expect("the reference motor is bundled")
}

/// The reference design on its motor in still standard air at sea level, off a 2 m vertical
/// rail, with the default options and no parachutes: `hpr-mc inspect`'s and `hpr-mc fly`'s
/// set-up of the file, less the canopies.
pub fn simulation() -> Simulation {
    Simulation::new(design(), motor(), Environment::default(), Rail::default())
        .expect("the reference rocket flies")
}

/// The ballast's shift: [`BALLAST_TRAVEL_M`] toward the tail over [`BALLAST_DURATION_S`],
/// starting `start_s` after launch.
pub fn ballast_shift(start_s: f64) -> MassShift {
    MassShift::new(
        Trigger::Time { time_s: start_s },
        BALLAST,
        BALLAST_TRAVEL_M,
        BALLAST_DURATION_S,
    )
}

/// The moving-mass worked example: [`simulation`] with the ballast sliding from 5 s after
/// launch (the motor has burnt out at 2.5 s).
pub fn worked_example() -> Simulation {
    simulation()
        .with_shifts(vec![ballast_shift(5.0)])
        .expect("the ballast's shift fits its holder")
}

/// What this crate's tests share to change the reference rocket: its JSON to edit, a design
/// from edited JSON, and a simulation of a design on the reference motor.
#[cfg(test)]
pub(crate) mod testing {
    use crate::flight::{Environment, Rail, SimOptions, Simulation};
    use hpr_design::Design;

    /// The reference design's JSON, for tests that change it.
    pub(crate) fn reference_json() -> serde_json::Value {
        serde_json::from_str(super::DESIGN_JSON).unwrap()
    }

    /// Find a component by id anywhere in a design's JSON.
    pub(crate) fn component_mut<'a>(
        v: &'a mut serde_json::Value,
        id: &str,
    ) -> &'a mut serde_json::Value {
        fn walk<'a>(v: &'a mut serde_json::Value, id: &str) -> Option<&'a mut serde_json::Value> {
            if v.get("id").and_then(|i| i.as_str()) == Some(id) && v.get("type").is_some() {
                return Some(v);
            }
            match v {
                serde_json::Value::Object(m) => m.values_mut().find_map(|c| walk(c, id)),
                serde_json::Value::Array(a) => a.iter_mut().find_map(|c| walk(c, id)),
                _ => None,
            }
        }
        walk(v, id).unwrap_or_else(|| panic!("no component {id}"))
    }

    pub(crate) fn design(v: &serde_json::Value) -> Design {
        Design::from_json_str(&v.to_string(), None).unwrap()
    }

    /// `design` on the reference motor off the default rail.
    pub(crate) fn simulation(design: Design, env: Environment, options: SimOptions) -> Simulation {
        Simulation::new(design, super::motor(), env, Rail::default())
            .unwrap()
            .with_options(options)
            .unwrap()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_design_is_the_validation_file_and_its_ballast_weighs_200_g() {
        let file = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../validation/designs/synthetic-54mm-three-fin.json"
        );
        assert_eq!(DESIGN_JSON, std::fs::read_to_string(file).unwrap());
        let d = design();
        assert_eq!(d.default_motor.as_deref(), Some(MOTOR));
        let ballast = d.component_index(BALLAST).unwrap();
        let m = hpr_design::mass::subtree(&d, ballast).mass_kg;
        assert!((m - 0.200).abs() < 1e-12, "ballast {m} kg");
    }

    #[test]
    fn the_worked_example_moves_the_ballast_0_3_m_aft_between_5_and_6_s() {
        let sim = worked_example();
        let flight = sim.run(&mut ()).unwrap();
        let before = sim.mass_properties(&flight, 4.9).cg_m.x;
        let after = sim.mass_properties(&flight, 6.1).cg_m.x;
        let total = sim.mass_properties(&flight, 6.1).mass_kg;
        // The center of mass moves by the ballast's share of the travel (motor burnt out, so
        // the total mass is constant across the move).
        let expected = 0.200 * BALLAST_TRAVEL_M / total;
        assert!(
            ((after - before) - expected).abs() < 1e-12,
            "moved {} m, expected {expected} m",
            after - before
        );
    }
}
