//! The batch engine flies every cross-checked rocket as the single flight does, bit for bit.
//!
//! The batch's own test (`hpr_sim::batch::tests`) proves the equality over 1,000 variants of
//! one design, the reference design. Here the seventeen rockets RocketPy has flown (the five
//! hand-picked of `crosscheck.rs`, the twelve drawn at random of `random_crosscheck.rs`:
//! canted fins that spin, boattails, lugs, elliptical and free-form fins, H to M motors, Mach
//! 0.3 to 1.5) are each flown in their three winds through [`Batch`], a dozen variants apiece
//! (motor, drag, wind, rail and canopy lags scattered), and every lane is compared with
//! [`Batch::variant`]'s single flight: the same metrics, canopy openings and landing to the
//! last bit (tolerance 0), and the same count of derivative evaluations.

use crate::common::repo;
use crate::crosscheck::crosscheck_simulation;
use hpr_sim::batch::{Batch, Columns, Status};
use serde_json::Value;

/// Variants per rocket and wind.
const VARIANTS: usize = 12;

fn rockets(file: &str) -> Vec<(String, Value)> {
    let text = std::fs::read_to_string(repo(file)).expect("reference");
    let all: Value = serde_json::from_str(&text).expect("JSON");
    all["rockets"]
        .as_object()
        .expect("rockets")
        .iter()
        .map(|(name, r)| (name.clone(), r.clone()))
        .collect()
}

/// `VARIANTS` rows of scattered inputs, spread evenly between their bounds (a low-discrepancy
/// walk, not random draws: nothing here needs to be random, only different from row to row).
fn columns(sim: &hpr_sim::Simulation) -> Columns {
    use hpr_sim::inputs::Input;
    let chutes = sim.parachutes().len();
    let (impulse, burn) = (sim.motor().total_impulse_ns(), sim.motor().burn_time_s());
    let spread = |k: usize, lo: f64, hi: f64| -> Vec<f64> {
        (0..VARIANTS)
            .map(|i| {
                // Multipliers prime to 12: each column takes every value once.
                let m = [1, 5, 7, 11][k % 4];
                let u = ((i * m + k) % VARIANTS) as f64 / (VARIANTS - 1) as f64;
                lo + (hi - lo) * u
            })
            .collect()
    };
    let times = |c: f64, v: Vec<f64>| v.into_iter().map(|x| c * x).collect();
    let mut c = Columns::new(VARIANTS)
        .with(Input::MotorImpulseNs, times(impulse, spread(0, 0.95, 1.05)))
        .with(Input::MotorBurnTimeS, times(burn, spread(1, 0.97, 1.03)))
        .with(Input::DragScale, spread(2, 0.9, 1.1))
        .with(Input::WindScale, spread(3, 0.5, 1.5))
        .with(Input::WindRotationDeg, spread(4, -40.0, 40.0))
        .with(Input::RailInclinationDeg, spread(5, 82.0, 89.5))
        .with(Input::RailHeadingDeg, spread(6, 0.0, 330.0));
    for k in 0..chutes {
        c = c.with(Input::ParachuteLagS(k), spread(7 + k, 0.5, 2.0));
    }
    c
}

#[test]
fn every_cross_checked_rocket_flies_in_the_batch_bit_for_bit_as_its_single_flight() {
    let mut all = rockets("validation/rocketpy/design_crosscheck_reference.json");
    all.extend(rockets(
        "validation/rocketpy/random_crosscheck_reference.json",
    ));
    assert_eq!(
        all.len(),
        17,
        "five hand-picked rockets and twelve random ones"
    );
    let mut lanes = 0;
    for (name, r) in &all {
        for case in ["wind", "profile", "calm"] {
            let (sim, _, _) = crosscheck_simulation(r, case);
            let c = columns(&sim);
            let batch = Batch::new(sim, None).expect("batch");
            let mut results = Vec::new();
            // Chunks of 5 rows: lanes are refilled mid-chunk and groups mix lanes at
            // different times of their flights.
            batch
                .run(VARIANTS, 5, 2, |rows| c.slice(rows), |l| results.push(l))
                .expect("runs");
            for (i, lane) in results.iter().enumerate() {
                let single = batch.variant(&c, i).expect("variant").run(&mut ());
                let f = single.unwrap_or_else(|e| panic!("{name} {case} {i}: {e}"));
                assert_eq!(lane.status, Status::Landed, "{name} {case} variant {i}");
                // Every metric, compared whole (`Metrics`' own equality: bit for bit).
                assert_eq!(
                    lane.metrics, f.metrics,
                    "{name} {case} variant {i}: the lane's metrics are the single flight's"
                );
                for (k, chute) in lane.parachutes.iter().enumerate() {
                    let deploy = chute.deploy_time_s.zip(chute.deploy_speed_m_s);
                    assert_eq!(deploy, f.deploy(k), "{name} {case} {i}: canopy {k}");
                }
                assert_eq!(
                    lane.derivative_evaluations, f.derivative_evaluations,
                    "{name} {case} {i}"
                );
                lanes += 1;
            }
        }
    }
    assert_eq!(lanes, 17 * 3 * VARIANTS);
    println!("{lanes} lanes of 17 rockets equal their single flights bit for bit");
}
