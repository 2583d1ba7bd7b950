use hpr_design::Design;
use hpr_sim::flight::{Environment, Parachute, Rail, SimOptions, Simulation};
use hpr_sim::wind::Wind;
use hpr_sim::{MassShift, Trigger};
fn main() {
    let design = Design::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../validation/designs/synthetic-54mm-three-fin.json"
    ))
    .unwrap();
    let env = Environment {
        wind: Wind::constant(3.0, 30.0).unwrap(),
        ..Environment::default()
    };
    let sim = Simulation::new(
        design,
        hpr_design::motor::find("Cesaroni_I175").unwrap(),
        env,
        Rail {
            inclination_deg: 87.0,
            ..Rail::default()
        },
    )
    .unwrap()
    .with_parachutes(vec![
        Parachute::new("drogue", 0.1, Trigger::Apogee, 1.0),
        Parachute::new(
            "main",
            0.9,
            Trigger::HeightDescending { height_m: 300.0 },
            1.0,
        ),
    ])
    .unwrap()
    .with_shifts(vec![MassShift::new(
        Trigger::Time { time_s: 5.0 },
        "ballast",
        0.2,
        1.0,
    )])
    .unwrap()
    .with_options(SimOptions {
        keep_samples: false,
        ..SimOptions::default()
    })
    .unwrap();
    eprintln!("surfaces {}", sim.model().aero.surfaces.len());
    let n: usize = std::env::var("N").map(|s| s.parse().unwrap()).unwrap_or(20);
    for _ in 0..n {
        std::hint::black_box(sim.run(&mut ()).unwrap());
    }
}
