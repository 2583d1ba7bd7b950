//! The documented limits of the inputs fly: a thrust curve that ends above zero lifts off on
//! its last segment, a thrust curve of 120,000 samples flies as its two-sample equal, and a
//! fixed RK4 step that would take longer than the stated bound is refused before the flight.

use crate::common::*;
use hpr_design::motor::Motor;
use hpr_sim::flight::{Integrator, SimError, SimOptions, MAX_INPUT_STEPS};
use hpr_sim::EventKind;

/// A motor of the I175's size and masses with the RASP samples `rows` (time s, thrust N).
fn motor_of(rows: &[(f64, f64)]) -> Motor {
    let mut text = String::from("TEST 38 245 0 0.2289 0.4375 Test\n");
    for (t, f) in rows {
        text.push_str(&format!("{t} {f}\n"));
    }
    text.push_str(";\n");
    Motor::parse(text.as_bytes(), "test.eng").unwrap()
}

#[test]
fn a_curve_that_ends_above_zero_lifts_off_on_its_last_segment() {
    // Samples 0.1 s 1 N and 0.5 s 100 N (the thrust then stops): the reference rocket, some
    // 9 N on the pad, can only lift off between them, where the thrust passes its weight.
    // The pad check once judged the last sample by the thrust after it (none): refused.
    let motor = motor_of(&[(0.1, 1.0), (0.5, 100.0)]);
    let sim = still_air(design("synthetic-54mm-three-fin.json"), motor);
    let flight = sim.run(&mut ()).expect("it lifts off");
    let t = flight.event(EventKind::Liftoff).unwrap().time_s;
    assert!(t > 0.1 && t < 0.5, "liftoff at {t} s");
    // There the thrust equals the weight along the vertical rail, to the root's tolerance:
    // thrust(t) = 1 + 99 (t − 0.1)/0.4 N.
    let thrust = 1.0 + 99.0 * (t - 0.1) / 0.4;
    let weight = mass_at(&sim, t).mass_kg * G0;
    eprintln!("liftoff at {t:.9} s: thrust {thrust:.9} N, weight {weight:.9} N");
    assert!((thrust - weight).abs() < 1e-6, "{thrust} against {weight}");
    // A curve that never beats the weight is refused, naming its true peak, its last sample.
    let weak = motor_of(&[(0.1, 1.0), (0.5, 2.0)]);
    match still_air(design("synthetic-54mm-three-fin.json"), weak).run(&mut ()) {
        Err(SimError::NeverLeavesPad { max_thrust_n, .. }) => {
            assert!((max_thrust_n - 2.0).abs() < 1e-9, "{max_thrust_n}")
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_thrust_curve_of_120000_samples_flies_as_the_same_line_in_two_samples() {
    // F = 200 − 16 t N from 0.01 s to 2.5 s (burning out there), given by its two ends or by
    // 120,000 samples on the same line: the same motor. Each sample is a stop time, so the
    // long curve's flight takes over 120,000 steps (once refused at the limit of 100,000).
    let line = |t: f64| 200.0 - 16.0 * t;
    let n = 120_000;
    let rows: Vec<(f64, f64)> = (0..=n)
        .map(|i| {
            let t = 0.01 + (2.5 - 0.01) * i as f64 / n as f64;
            (t, line(t))
        })
        .collect();
    let short = motor_of(&[(0.01, line(0.01)), (2.5, line(2.5))]);
    let long = motor_of(&rows);
    assert_eq!(
        long.times_s().len(),
        n + 2,
        "the implicit start and every sample"
    );
    let fly = |m: Motor| {
        still_air(design("synthetic-54mm-three-fin.json"), m)
            .with_options(options(TIGHT, 600.0))
            .unwrap()
            .run(&mut ())
            .expect("flies")
    };
    let (a, b) = (fly(short), fly(long));
    assert!(b.steps > n as u64, "{} steps", b.steps);
    let (ha, hb) = (a.metrics.apogee_m.unwrap(), b.metrics.apogee_m.unwrap());
    eprintln!(
        "apogee {ha:.6} m in {} steps, {hb:.6} m in {} steps",
        a.steps, b.steps
    );
    // The same flight, its steps cut where the samples are: equal to the tight
    // integrator's tolerance (1e-12 relative a step), here within 1e-9 relative.
    assert!((ha - hb).abs() < 1e-9 * ha, "{ha} against {hb}");
    assert!(b.event(EventKind::Landing).is_some());
}

#[test]
fn an_rk4_step_that_would_take_more_than_the_stated_steps_is_refused_before_the_flight() {
    let sim = still_air(
        design("synthetic-54mm-three-fin.json"),
        motor("Cesaroni_I175"),
    );
    let with = |step_s: f64, max_time_s: f64| {
        sim.clone().with_options(SimOptions {
            integrator: Integrator::Rk4 { step_s },
            max_time_s,
            keep_samples: false,
        })
    };
    // 1e-9 s over 600 s is 6e11 steps (it once ran for days): refused, with the rule.
    let e = with(1e-9, 600.0).unwrap_err().to_string();
    assert!(
        e.contains(
            "field \"step_s\": max_time_s / step_s is 6.0000e11 steps, more than the 10000000"
        ) && e.contains("give a step of at least 6e-5 s"),
        "{e}"
    );
    // At the bound exactly it is allowed.
    assert!(with(600.0 / MAX_INPUT_STEPS, 600.0).is_ok());
    assert!(with(600.0 / MAX_INPUT_STEPS * 0.999, 600.0).is_err());
}

#[test]
fn a_sampler_whose_samples_to_the_time_limit_pass_the_stated_steps_is_refused() {
    // A main read 10,000 times a second: to 1000 s that is the 10,000,000 steps allowed;
    // to 1001 s one second's samples more.
    let chute = hpr_sim::Parachute {
        sampling_rate_hz: Some(10_000.0),
        ..hpr_sim::Parachute::new(
            "main",
            0.9,
            hpr_sim::Trigger::HeightDescending { height_m: 150.0 },
            1.0,
        )
    };
    let with = |max_time_s: f64| {
        still_air(
            design("synthetic-54mm-three-fin.json"),
            motor("Cesaroni_I175"),
        )
        .with_parachutes(vec![chute.clone()])
        .and_then(|s| s.with_options(options(Integrator::DEFAULT, max_time_s)))
    };
    assert!(with(1000.0).is_ok());
    let e = with(1001.0).unwrap_err().to_string();
    assert!(
        e.contains("a sampler read 10000 times a second to the time limit (max_time_s = 1001 s) takes 1.0010e7 samples")
            && e.contains("give a time limit of at most 1000 s"),
        "{e}"
    );
}
