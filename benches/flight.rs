//! One whole flight of the synthetic 54 mm reference design on the Cesaroni I175, to landing,
//! set up as `hpr-mc fly` sets it (2 m vertical rail, sea level, no wind, default integrator,
//! the design's two canopies: the smaller at apogee, the larger at 300 m, 1 s lag).
//!
//! Run: `cargo bench --bench flight -- --warm-up-time 1 --measurement-time 5`.

use criterion::{criterion_group, criterion_main, Criterion};
use hpr_mc::cli::parachutes_for;
use hpr_sim::flight::Simulation;
use hpr_sim::reference;
use std::hint::black_box;

fn setup() -> Simulation {
    let sim = reference::simulation();
    let chutes = parachutes_for(sim.design(), None, None, Some(300.0), Some(1.0));
    assert_eq!(chutes.len(), 2, "drogue and main");
    sim.with_parachutes(chutes).expect("set up")
}

fn flight(c: &mut Criterion) {
    let sim = setup();
    let f = sim.run(&mut ()).expect("flies");
    let m = &f.metrics;
    eprintln!(
        "flight: apogee {:.2} m at {:.3} s, landing at {:.2} s; {} derivative evaluations, \
         {} steps, {} samples",
        m.apogee_m.unwrap_or(f64::NAN),
        m.apogee_time_s.unwrap_or(f64::NAN),
        m.landing_time_s.unwrap_or(f64::NAN),
        f.derivative_evaluations,
        f.steps,
        f.samples.len()
    );
    c.bench_function("flight synthetic-54mm I175 to landing", |b| {
        b.iter(|| black_box(sim.run(&mut ()).expect("flies")))
    });
}

criterion_group!(benches, flight);
criterion_main!(benches);
