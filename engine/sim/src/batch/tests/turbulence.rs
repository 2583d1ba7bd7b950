//! Lanes in a turbulent wind: each lane draws the gusts its single flight draws (from its
//! seed, a column), whatever the threads and chunks, and the kernels meet the wind the gusts
//! make.

use super::*;
use crate::turbulence::{Gusts, GUST_INTERVAL_S};

/// The base flight in a 15 % turbulent wind (its speed and direction set per variant).
fn turbulent_base() -> Simulation {
    let sim = base();
    let mut env = sim.environment().clone();
    env.wind = Wind::constant(5.0, 270.0)
        .and_then(|w| w.with_turbulence(0.15))
        .unwrap();
    let rail = *sim.rail();
    sim.with_changes(|c| c.site(env, rail)).unwrap()
}

#[test]
fn lanes_in_a_turbulent_wind_equal_their_single_flights_whatever_the_chunks() {
    let batch = Batch::new(turbulent_base(), Some(reference::BALLAST)).unwrap();
    let n = 48;
    let cols = |rows: std::ops::Range<usize>| Columns {
        sensor_seed: rows.clone().map(|i| 7000 + i as u64).collect(),
        ..columns_of(rows, 11)
    };
    let run = |threads: usize, chunk: usize| run_on(&batch, n, threads, chunk, 3, cols);
    let (a, b) = (run(1, 16), run(2, 5));
    assert!(a == b, "the gusts depend on the threads or chunks");
    let c = cols(0..n);
    let mut flown = 0;
    for lane in a.iter().filter(|l| l.flown) {
        flown += 1;
        let sim = batch.variant(&c, lane.variant).unwrap();
        assert_eq!(
            sim.environment().wind.turbulence_intensity(),
            0.15,
            "variant {} keeps the base's turbulence under its own wind",
            lane.variant
        );
        let f = sim.clone().run(&mut ()).unwrap();
        assert_eq!(lane.metrics, f.metrics, "variant {}", lane.variant);
        // The same inputs set up from scratch, turbulence added: the same flight, bit for bit.
        if lane.variant < 6 {
            let scratch = single(&c, lane.variant).unwrap();
            let mut env = scratch.environment().clone();
            env.wind = env.wind.with_turbulence(0.15).unwrap();
            let rail = *scratch.rail();
            let scratch = scratch
                .with_changes(|ch| ch.site(env, rail))
                .unwrap()
                .with_sensor_seed(c.sensor_seed[lane.variant]);
            let g = scratch.run(&mut ()).unwrap();
            assert_eq!(
                lane.metrics, g.metrics,
                "variant {} from scratch",
                lane.variant
            );
        }
    }
    assert!(flown >= 40, "{flown} of {n} flown");
    // The gusts are there: another seed lands elsewhere.
    let sim = batch.variant(&c, 0).unwrap();
    let here = sim.clone().run(&mut ()).unwrap().metrics;
    let there = sim.with_sensor_seed(1).run(&mut ()).unwrap().metrics;
    assert_ne!(here.landing_position_m, there.landing_position_m);
}

#[test]
fn the_kernels_meet_the_steady_wind_times_the_gust_factor() {
    // A flight with 30 % turbulence against flights in steady winds of the speed its gusts
    // make at a few times: the 6-DOF, rail and descent derivatives agree to rounding (the
    // steady wind's components are speed × sin/cos, the gust's (speed·sin) × factor: 1e-15
    // relative apart).
    let steady = |speed: f64| {
        let sim = base();
        let mut env = sim.environment().clone();
        env.wind = Wind::constant(speed, 200.0).unwrap();
        let rail = *sim.rail();
        sim.with_changes(|c| c.site(env, rail)).unwrap()
    };
    let gusty = {
        let sim = steady(6.0);
        let mut env = sim.environment().clone();
        env.wind = env.wind.with_turbulence(0.3).unwrap();
        let rail = *sim.rail();
        sim.with_changes(|c| c.site(env, rail))
            .unwrap()
            .with_sensor_seed(5)
    };
    let gusts = Gusts::new(0.3, 5, SimOptions::default().max_time_s);
    let starts = [f64::INFINITY; crate::flight::model::MAX_SHIFTS];
    let y: [f64; N6] = [
        3.0, -2.0, 400.0, 4.0, 1.0, 80.0, 0.02, -0.01, 0.05, 0.998, 0.3, -0.2, 1.0,
    ];
    let y3 = [3.0, -2.0, 400.0, 1.0, -0.5, -20.0];
    let mut factors = Vec::new();
    for t in [0.3, 1.234, 7.05, 42.0] {
        let f = gusts.factor(t);
        assert_eq!(gusty.model().gust(t), f);
        factors.push(f);
        let calm_like = steady(6.0 * f);
        let close = |a: &[f64], b: &[f64], what: &str| {
            for (k, (x, y)) in a.iter().zip(b).enumerate() {
                let tol = 1e-12 * (1.0 + x.abs().max(y.abs()));
                assert!(
                    (x - y).abs() <= tol,
                    "{what} at t = {t}, state {k}: {x} against {y}"
                );
            }
        };
        let (mut d1, mut d2) = ([0.0; N6], [0.0; N6]);
        gusty.model().derivative_6dof(&starts, t, &y, &mut d1);
        calm_like.model().derivative_6dof(&starts, t, &y, &mut d2);
        close(&d1, &d2, "6-DOF");
        gusty.model().derivative_rail(&starts, t, &y, &mut d1);
        calm_like.model().derivative_rail(&starts, t, &y, &mut d2);
        close(&d1, &d2, "rail");
        let canopies = crate::eom::Canopies {
            cds_m2: 1.0,
            added_air_m3: 0.0,
        };
        let (mut e1, mut e2) = ([0.0; 6], [0.0; 6]);
        gusty.model().descent_rates(&canopies, t, &y3, &mut e1);
        calm_like.model().descent_rates(&canopies, t, &y3, &mut e2);
        close(&e1, &e2, "descent");
    }
    // The factors differ from 1 and from each other: the test met real gusts.
    assert!(
        factors.iter().all(|f| (f - 1.0).abs() > 1e-3),
        "{factors:?}"
    );
    // Between two samples the factor is the straight line through them.
    let k = 140;
    let (t0, t1) = (k as f64 * GUST_INTERVAL_S, (k + 1) as f64 * GUST_INTERVAL_S);
    let mid = gusty.model().gust(0.5 * (t0 + t1));
    let want = 0.5 * (gusts.factors()[k] + gusts.factors()[k + 1]);
    assert!((mid - want).abs() < 1e-14, "{mid} against {want}");
}

#[test]
fn a_turbulent_flight_with_a_time_limit_past_two_hours_is_refused() {
    let sim = turbulent_base();
    let err = sim
        .clone()
        .with_options(SimOptions {
            max_time_s: 7200.5,
            ..SimOptions::default()
        })
        .unwrap_err()
        .to_string();
    assert!(err.contains("at most 7200 s"), "{err}");
    // Two hours is allowed: 144,002 samples.
    let ok = sim
        .with_options(SimOptions {
            max_time_s: 7200.0,
            ..SimOptions::default()
        })
        .unwrap();
    assert_eq!(ok.model().gusts.as_ref().unwrap().factors().len(), 144_002);
}
