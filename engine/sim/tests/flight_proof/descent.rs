//! The descent's integrator over the seventeen cross-checked rockets (the five hand-picked of
//! `crosscheck.rs`, the twelve drawn at random of `random_crosscheck.rs`), each in its three
//! winds: flown at the default tolerances, each lands within 2 ms and 2 cm of where the same
//! flight at tolerances a thousand times tighter lands. Under canopy RODAS4 takes steps its accuracy allows, not the
//! stability limit an explicit method would be held to, so these are the figures that say
//! its steps are not too long. Each line printed (`DESCENT ...`) gives the landing time and
//! point, the flight's steps and its steps under canopy: the bench log compares them with
//! the Dormand–Prince descent's.

use crate::common::repo;
use crate::crosscheck::crosscheck_simulation;
use hpr_sim::flight::{Integrator, Phase, SimOptions};
use serde_json::Value;

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

#[test]
fn every_cross_checked_rocket_lands_where_a_thousand_times_tighter_tolerances_land_it() {
    let mut all = rockets("validation/rocketpy/design_crosscheck_reference.json");
    all.extend(rockets(
        "validation/rocketpy/random_crosscheck_reference.json",
    ));
    assert_eq!(all.len(), 17);
    let tight = Integrator::Adaptive {
        rtol: 1e-10,
        atol_position_m: 1e-7,
        atol_velocity_m_s: 1e-7,
        atol_quaternion: 1e-11,
        atol_rate_rad_s: 1e-7,
    };
    let (mut worst_t, mut worst_xy): (f64, f64) = (0.0, 0.0);
    for (name, r) in &all {
        for case in ["wind", "profile", "calm"] {
            let (sim, _, _) = crosscheck_simulation(r, case);
            let options = SimOptions {
                integrator: tight,
                ..*sim.options()
            };
            let f = sim.run(&mut ()).expect("flies");
            let g = sim
                .with_options(options)
                .and_then(|s| s.run(&mut ()))
                .expect("flies");
            let (t, xy) = (
                f.metrics.landing_time_s.unwrap(),
                f.metrics.landing_position_m.unwrap(),
            );
            let (tg, xyg) = (
                g.metrics.landing_time_s.unwrap(),
                g.metrics.landing_position_m.unwrap(),
            );
            let under_canopy = f
                .samples
                .iter()
                .filter(|s| s.phase == Phase::Descent)
                .count();
            println!(
                "DESCENT {name} {case} {t:.9} {:.6} {:.6} {} {under_canopy} {}",
                xy[0], xy[1], f.steps, f.derivative_evaluations
            );
            worst_t = worst_t.max((t - tg).abs());
            worst_xy = worst_xy.max((xy[0] - xyg[0]).hypot(xy[1] - xyg[1]));
        }
    }
    println!(
        "worst against the tight tolerances: landing time {worst_t:.2e} s, point {worst_xy:.2e} m"
    );
    // Measured 1.20e-3 s and 9.5e-3 m (the Dormand–Prince descent: 1.18e-3 s and 1.3e-2 m);
    // the ascent's share is the same in both.
    assert!(worst_t < 2e-3, "{worst_t}");
    assert!(worst_xy < 2e-2, "{worst_xy}");
}
