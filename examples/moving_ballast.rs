//! The worked example of `docs/moving-mass.md`: the reference 54 mm design on the Cesaroni I175
//! (411I175-14A), with its 200 g ballast sliding 0.3 m toward the tail over one second from
//! 5 s after launch. Prints the rocket's mass properties before, during and after the move,
//! the static margin before and after, and the apogee with the ballast moving and held still.
//!
//! Run: `cargo run --release --example moving_ballast`

use hpr_design::{motor, Design};
use hpr_sim::flight::{Environment, Rail, Simulation};
use hpr_sim::{MassShift, Trigger};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/validation/designs/synthetic-54mm-three-fin.json"
    );
    let design = Design::load(path)?;
    let motor = motor::find("Cesaroni_I175")?;
    let simulation = Simulation::new(design, motor, Environment::default(), Rail::default())?;
    let still = simulation.run(&mut ())?;

    let simulation = simulation.with_shifts(vec![MassShift::new(
        Trigger::Time { time_s: 5.0 },
        "ballast",
        0.3,
        1.0,
    )])?;
    let flight = simulation.run(&mut ())?;

    println!("| time (s) | mass (kg) | center of mass (m aft of the nose tip) | transverse inertia (kg·m²) |");
    println!("|---|---|---|---|");
    for t in [4.0, 5.25, 5.5, 5.75, 7.0] {
        let p = simulation.mass_properties(&flight, t);
        println!(
            "| {t:.2} | {:.4} | {:.4} | {:.5} |",
            p.mass_kg,
            p.cg_m.x,
            p.transverse_inertia()
        );
    }
    let before = simulation.static_margin_for(simulation.mass_properties(&flight, 4.0).cg_m.x);
    let after = simulation.static_margin_for(simulation.mass_properties(&flight, 7.0).cg_m.x);
    println!();
    println!(
        "static margin: {before:.3} calibres before the move, {after:.3} after (change {:.3})",
        after - before
    );
    let (moving, held) = (
        flight.metrics.apogee_m.unwrap_or(f64::NAN),
        still.metrics.apogee_m.unwrap_or(f64::NAN),
    );
    println!("apogee: {moving:.1} m with the ballast moving, {held:.1} m with it held still");
    Ok(())
}
