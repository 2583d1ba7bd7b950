//! Released mass's worked example: the reference 54 mm design on the Cesaroni I175
//! (411I175-14A) drops its 200 g ballast 5 s after launch, in the coast (the burn ends at
//! 2.5 s). Prints the rocket's mass properties just before and after the drop, the static
//! margin's jump, the apogee with and without the drop, and where the ballast lands, tumbling
//! with the drag area estimated from its size (OpenRocket's tumbling body: 0.56 × its length
//! × its diameter), in still air and in a 5 m/s wind from the west off a rail leaning into it.
//!
//! Run: `cargo run --release --example released_ballast`

use hpr_design::{motor, Design};
use hpr_sim::flight::{Environment, Rail, Simulation};
use hpr_sim::releases::TUMBLE_CD;
use hpr_sim::wind::Wind;
use hpr_sim::{Release, Trigger};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/validation/designs/synthetic-54mm-three-fin.json"
    );
    let design = Design::load(path)?;
    let motor = motor::find("Cesaroni_I175")?;
    let kept = Simulation::new(design, motor, Environment::default(), Rail::default())?;
    let drop = vec![Release::new(Trigger::Time { time_s: 5.0 }, "ballast")];
    let dropped = kept.clone().with_releases(drop.clone())?;
    let flight = dropped.run(&mut ())?;

    println!("| time (s) | mass (kg) | center of mass (m aft of the nose tip) | transverse inertia (kg·m²) | axial inertia (kg·m²) | static margin (cal) |");
    println!("|---|---|---|---|---|---|");
    // Just before the drop, at it (what remains), and later (nothing changes after it).
    for (t, label) in [(4.0, "4.00"), (5.0, "5.00 (after)"), (10.0, "10.00")] {
        let p = dropped.mass_properties(&flight, t);
        println!(
            "| {label} | {:.4} | {:.4} | {:.5} | {:.6} | {:.3} |",
            p.mass_kg,
            p.cg_m.x,
            p.transverse_inertia(),
            p.inertia_cg[(0, 0)],
            dropped.static_margin_for(p.cg_m.x)
        );
    }
    let r = &flight.releases[0];
    let (before, after) = (r.margin_before_cal.unwrap(), r.margin_after_cal.unwrap());
    println!();
    println!(
        "static margin: {before:.3} calibres before the drop, {after:.3} after (change {:.3})",
        after - before
    );
    let with_ballast = kept.run(&mut ())?;
    println!(
        "apogee: {:.1} m dropping the ballast at 5 s, {:.1} m keeping it",
        flight.metrics.apogee_m.unwrap_or(f64::NAN),
        with_ballast.metrics.apogee_m.unwrap_or(f64::NAN)
    );

    let cda = dropped.release_plan().cda_m2[0];
    println!();
    println!(
        "the ballast tumbles with CdA = {TUMBLE_CD} × 0.05 m × 0.04 m = {:.5} m² (its terminal speed at sea level {:.1} m/s):",
        cda,
        (2.0 * 0.2 * 9.80665 / (1.225 * cda)).sqrt()
    );
    let windy_site = Environment {
        wind: Wind::constant(5.0, 270.0)?,
        ..Environment::default()
    };
    let windy_rail = Rail {
        inclination_deg: 85.0,
        heading_deg: 270.0,
        ..Rail::default()
    };
    let windy = kept
        .with_site(windy_site, windy_rail)?
        .with_releases(drop)?
        .run(&mut ())?;
    for (case, f) in [
        ("still air, vertical rail", &flight),
        ("5 m/s from the west, rail 85° into it", &windy),
    ] {
        let part = f.releases[0]
            .part
            .as_ref()
            .ok_or("the ballast never left")?;
        let [x, y] = part.landing_position_m.ok_or("the ballast never landed")?;
        let [rx, ry] = f
            .metrics
            .landing_position_m
            .ok_or("the rocket never landed")?;
        println!(
            "  {case}: left at {:.1} m climbing {:.1} m/s, topped out at {:.1} m, landed at {:.1} s, {:.1} m east and {:.1} m north of the pad ({:.1} m away), at {:.1} m/s; the rocket, falling free without a parachute, {:.1} m east and {:.1} m north",
            part.start_position_m[2],
            part.start_velocity_m_s[2],
            part.apogee_m,
            part.landing_time_s.unwrap_or(f64::NAN),
            x,
            y,
            x.hypot(y),
            part.landing_speed_m_s.unwrap_or(f64::NAN),
            rx,
            ry
        );
    }
    Ok(())
}
