//! How the reference flight's metrics and cost move with the integrator's tolerance:
//! the evidence behind the default (`Integrator::DEFAULT`). Run:
//! `cargo run --release --example tolerance_study`
use hpr_design::{motor, Design};
use hpr_sim::flight::{Environment, Integrator, Parachute, Rail, SimOptions, Simulation};
use hpr_sim::{MassShift, Trigger};
use std::time::Instant;
fn main() {
    let d = Design::load("validation/designs/synthetic-54mm-three-fin.json").unwrap();
    let m = motor::find("Cesaroni_I175").unwrap();
    let chutes = vec![
        Parachute::new("d", 0.1, Trigger::Apogee, 1.0),
        Parachute::new("m", 0.9, Trigger::HeightDescending { height_m: 300.0 }, 1.0),
    ];
    let wind = hpr_sim::wind::Wind::constant(5.0, 270.0).unwrap();
    for rtol in [1e-6, 1e-7, 1e-8, 1e-10, 1e-12] {
        let a = rtol * 1e3;
        let s = Simulation::new(
            d.clone(),
            m.clone(),
            Environment {
                wind: wind.clone(),
                ..Environment::default()
            },
            Rail::default(),
        )
        .unwrap()
        .with_parachutes(chutes.clone())
        .unwrap()
        .with_shifts(vec![MassShift::new(
            Trigger::Time { time_s: 5.0 },
            "ballast",
            0.3,
            1.0,
        )])
        .unwrap()
        .with_options(SimOptions {
            integrator: Integrator::Adaptive {
                rtol,
                atol_position_m: a,
                atol_velocity_m_s: a,
                atol_quaternion: rtol * 0.1,
                atol_rate_rad_s: a,
            },
            keep_samples: false,
            ..SimOptions::default()
        })
        .unwrap();
        let n = 100;
        let t = Instant::now();
        let mut f = None;
        for _ in 0..n {
            f = Some(s.run(&mut ()).unwrap());
        }
        let dt = t.elapsed().as_secs_f64() / n as f64;
        let f = f.unwrap();
        let mt = f.metrics;
        println!("rtol {rtol:e}: apogee {:.6} at {:.6}, maxv {:.6}, land {:.3} {:?}, steps {} evals {} time {:.0} us", mt.apogee_m.unwrap(), mt.apogee_time_s.unwrap(), mt.max_speed_m_s, mt.landing_time_s.unwrap(), mt.landing_position_m.unwrap(), f.steps, f.derivative_evaluations, dt*1e6);
    }
}
