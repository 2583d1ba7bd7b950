//! Triggers read by a flight computer that samples: a parachute fires at the first sample at
//! or after the moment its condition became true, and opens its lag after that.

use crate::common::*;
use hpr_sim::events::EventKind;
use hpr_sim::flight::{Environment, Flight, Parachute, Rail, Simulation};
use hpr_sim::trigger::Trigger;

/// The synthetic rocket on its I175 in a 4 m/s wind: drogue at apogee, main at 300 m on the
/// way down, each opening 1 s after its trigger, read continuously or at `rate_hz`.
fn fly(rate_hz: Option<f64>) -> Flight {
    let sampled = |p: Parachute| match rate_hz {
        Some(r) => p.with_sampling_rate(r),
        None => p,
    };
    let chutes = vec![
        sampled(Parachute::new("drogue", 0.1, Trigger::Apogee, 1.0)),
        sampled(Parachute::new(
            "main",
            0.9,
            Trigger::HeightDescending { height_m: 300.0 },
            1.0,
        )),
    ];
    reference_flight_in_wind(4.0, 250.0, chutes)
}

fn time(f: &Flight, kind: EventKind) -> f64 {
    f.event(kind)
        .unwrap_or_else(|| panic!("no {kind:?}"))
        .time_s
}

#[test]
fn a_sampled_trigger_fires_at_its_first_sample_after_the_condition_and_opens_its_lag_later() {
    let rate = 20.0; // an altimeter reading every 50 ms
    let (watched, sampled) = (fly(None), fly(Some(rate)));
    // Up to the apogee the two flights are the same flight, bit for bit.
    let apogee = time(&watched, EventKind::Apogee);
    assert_eq!(time(&sampled, EventKind::Apogee), apogee);
    // The continuous drogue fires at the apogee itself; the sampled one at the next
    // multiple of 50 ms (exactly: it is a stop time of the flight), and opens 1 s later.
    assert_eq!(time(&watched, EventKind::ParachuteTrigger(0)), apogee);
    let drogue = time(&sampled, EventKind::ParachuteTrigger(0));
    let sample = (apogee * rate).ceil() / rate;
    eprintln!("apogee at {apogee:.6} s; the sampled drogue fires at {drogue} s");
    assert_eq!(drogue, sample);
    assert!(drogue > apogee && drogue - apogee < 1.0 / rate);
    assert_eq!(time(&sampled, EventKind::ParachuteDeploy(0)), drogue + 1.0);
    // The main: on a sample, at most one sample's fall below its 300 m. At the drogue's
    // steady descent (12.3 m/s, steady to 1e-3 over 50 ms) the fall between two samples is
    // the speed times 50 ms.
    let main = sampled
        .event(EventKind::ParachuteTrigger(1))
        .expect("main trigger");
    let k = main.time_s * rate;
    assert_eq!(
        k,
        k.round(),
        "the main fires on a sample: {} s",
        main.time_s
    );
    let below = 300.0 - main.altitude_m;
    let one_sample = main.speed_m_s / rate;
    eprintln!(
        "the sampled main fires at {} s, {below:.4} m below its 300 m (one sample's fall \
         {one_sample:.4} m); the continuous one at {:.4} m",
        main.time_s,
        watched
            .event(EventKind::ParachuteTrigger(1))
            .unwrap()
            .altitude_m
    );
    assert!(below > 0.0 && below <= one_sample * (1.0 + 1e-3));
    assert_eq!(
        time(&sampled, EventKind::ParachuteDeploy(1)),
        main.time_s + 1.0
    );
    // Both triggers fired late, so the canopies opened lower and later: the flight is
    // another one, though not by much.
    let (t0, t1) = (
        watched.metrics.landing_time_s.unwrap(),
        sampled.metrics.landing_time_s.unwrap(),
    );
    assert!(t1 != t0 && (t1 - t0).abs() < 0.2, "{t0} s against {t1} s");
}

#[test]
fn a_trigger_whose_condition_is_met_on_a_sample_fires_then() {
    // A sampled parachute's `fires_at`: a condition met on a sample fires on it, between
    // samples at the next, k / rate in both cases (and never before the condition).
    let p = Parachute::new("p", 1.0, Trigger::Apogee, 0.0).with_sampling_rate(105.0);
    assert_eq!(p.fires_at(2.0 / 105.0), 2.0 / 105.0);
    assert_eq!(p.fires_at(0.0), 0.0);
    assert_eq!(p.fires_at(1.0 / 105.0 + 1e-9), 2.0 / 105.0);
    for k in 0..2000 {
        let t = k as f64 * 0.01234567;
        let f = p.fires_at(t);
        assert!(f >= t && f - t < 1.0 / 105.0 + 1e-15, "{t} -> {f}");
    }
    let watched = Parachute::new("p", 1.0, Trigger::Apogee, 0.0);
    assert_eq!(watched.fires_at(1.2345), 1.2345);
}

#[test]
fn a_sampling_rate_not_positive_or_past_10_khz_is_refused_by_field() {
    for bad in [0.0, -20.0, f64::NAN, f64::INFINITY, 10_000.5, 1e300] {
        let chute = Parachute::new("drogue", 0.1, Trigger::Apogee, 1.0).with_sampling_rate(bad);
        let err = Simulation::new(
            design("synthetic-54mm-three-fin.json"),
            motor("Cesaroni_I175"),
            Environment::default(),
            Rail::default(),
        )
        .and_then(|s| s.with_parachutes(vec![chute]))
        .expect_err("refused")
        .to_string();
        assert!(
            err.contains("parachute 0 (\"drogue\")")
                && err.contains("sampling_rate_hz")
                && err.contains("must be positive, at most 10000 Hz"),
            "{err}"
        );
    }
}
