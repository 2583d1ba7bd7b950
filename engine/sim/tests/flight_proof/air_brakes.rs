//! Air brakes: the controller's prediction against its closed form, the brakes' drag against
//! the same drag written into the rocket's own curve, the target reached in flight, and the
//! batch flying braked rockets bit for bit as single flights.

use crate::common::*;
use hpr_design::Design;
use hpr_sim::flight::model::BrakeModel;
use hpr_sim::flight::Metrics;
use serde_json::{json, Value};

/// The closed form the controller predicts with: a vertical coast from `h` at `v` against
/// gravity `g` and a drag `k v²` per unit mass.
fn coast_apogee(h: f64, v: f64, k: f64, g: f64) -> f64 {
    h + (1.0 + k * v * v / g).ln() / (2.0 * k)
}

#[test]
fn the_controller_opens_the_brakes_to_make_its_predicted_apogee_the_target() {
    // 10 kg climbing at 100 m/s at 1000 m, ρ = 1 kg/m³, g = 9.81, Cd 0.5 on 0.01 m², brakes
    // of Cd 2 fully open. By hand: closed, k = ½·1·0.01·0.5/10 = 2.5e-4 /m and the apogee
    // 1000 + ln(1 + 2.5e-4·100²/9.81)/5e-4 = 1454.0193 m; fully open, k = 1.25e-3 /m and
    // 1328.6531 m.
    let brakes = |target: f64| BrakeModel {
        cd_open: 2.0,
        target_apogee_m: target,
        period_s: 0.05,
    };
    let k = |u: f64| 0.5 * 1.0 * 0.01 * (0.5 + 2.0 * u) / 10.0;
    assert!((coast_apogee(1000.0, 100.0, k(0.0), 9.81) - 1454.0193332).abs() < 1e-6);
    assert!((coast_apogee(1000.0, 100.0, k(1.0), 9.81) - 1328.6530939).abs() < 1e-6);
    let open =
        |target: f64, climb: f64| brakes(target).opening(1000.0, climb, 10.0, 1.0, 9.81, 0.5, 0.01);
    // 1400 m lies between: the opening whose apogee is 1400 m (0.33318 by bisection here).
    let u = open(1400.0, 100.0);
    assert!((u - 0.3331834).abs() < 1e-6, "{u}");
    assert!((coast_apogee(1000.0, 100.0, k(u), 9.81) - 1400.0).abs() < 1e-6);
    // Short of the target closed: closed. Over it fully open: fully open.
    assert_eq!(open(1500.0, 100.0), 0.0);
    assert_eq!(open(1300.0, 100.0), 1.0);
    // Falling or at the top: closed.
    assert_eq!(open(900.0, 0.0), 0.0);
    assert_eq!(open(900.0, -5.0), 0.0);
    // No drag of its own (Cd 0): the closed coast is v²/2g = 509.68 m, so a 1400 m target
    // asks for the opening whose drag takes 109.68 m off it.
    let bare = brakes(1400.0).opening(1000.0, 100.0, 10.0, 1.0, 9.81, 0.0, 0.01);
    let kb = 0.5 * 0.01 * 2.0 * bare / 10.0;
    assert!(
        (coast_apogee(1000.0, 100.0, kb, 9.81) - 1400.0).abs() < 1e-6,
        "{bare}"
    );
}

/// The example design (drag from its table) with `air_brakes`, if given.
fn example(brakes: Option<Value>, drag: Option<Value>) -> Design {
    let text = std::fs::read_to_string(repo("validation/designs/example-minimal.json")).unwrap();
    let mut v: Value = serde_json::from_str(&text).unwrap();
    if let Some(b) = brakes {
        v["air_brakes"] = b;
    }
    if let Some(d) = drag {
        v["drag"] = d;
    }
    Design::from_json_str(&v.to_string(), None).unwrap()
}

fn fly(design: Design) -> Metrics {
    still_air(design, motor("Cesaroni_I175"))
        .run(&mut ())
        .unwrap()
        .metrics
}

#[test]
fn brakes_open_from_burnout_to_apogee_drag_as_the_same_drag_in_the_rocket_s_power_off_curve() {
    // The example's drag table, Cd 0.45 to 0.62; brakes of Cd 0.3 on the reference area
    // with a target no flight reaches are open from the first sample, at burnout, to
    // apogee: the rocket's drag then is its power-off Cd + 0.3, as a design whose power-off
    // curve is the table + 0.3 and whose power-on curve is the table flies it.
    let table = [
        [0.0, 0.45],
        [0.3, 0.44],
        [0.6, 0.46],
        [0.9, 0.55],
        [1.2, 0.62],
    ];
    let raised: Vec<[f64; 2]> = table.iter().map(|r| [r[0], r[1] + 0.3]).collect();
    let braked = fly(example(
        Some(json!({"cd": 0.3, "target_apogee_m": 1.0, "sampling_rate_hz": 10.0})),
        None,
    ));
    let curve = fly(example(
        None,
        Some(json!({"power_off": raised, "power_on": table})),
    ));
    assert_eq!(braked.air_brakes_max_opening, Some(1.0));
    assert_eq!(braked.air_brakes_open_time_s, braked.burnout_time_s);
    // The brakes' samples cut the steps where the curve's flight does not: equal to the
    // integrator's tolerance (1e-6 relative).
    let (a, b) = (braked.apogee_m.unwrap(), curve.apogee_m.unwrap());
    eprintln!("apogee with brakes {a:.6} m, with the raised curve {b:.6} m");
    assert!((a - b).abs() < 1e-5 * b, "{a} against {b}");
    let (a, b) = (braked.apogee_time_s.unwrap(), curve.apogee_time_s.unwrap());
    assert!((a - b).abs() < 1e-5 * b, "{a} against {b}");
    // And they took a fifth off the plain rocket's climb (1476 m against 1829 m).
    let plain = fly(example(None, None));
    assert!(braked.apogee_m.unwrap() < 0.85 * plain.apogee_m.unwrap());
    assert_eq!(plain.air_brakes_open_time_s, None);
    // A coefficient on another area is scaled to the reference area: Cd 0.6 on half of it
    // is Cd 0.3 on it.
    let area = std::f64::consts::PI * 0.25 * 0.0563 * 0.0563;
    let half = fly(example(
        Some(json!({"cd": 0.6, "reference_area_m2": 0.5 * area,
                    "target_apogee_m": 1.0, "sampling_rate_hz": 10.0})),
        None,
    ));
    let (a, b) = (half.apogee_m.unwrap(), braked.apogee_m.unwrap());
    assert!((a - b).abs() < 1e-12 * b, "{a} against {b}");
}

#[test]
fn a_rocket_with_air_brakes_tops_out_at_its_target() {
    // The plain rocket tops out at 1829 m; fully open from burnout (Cd 1.2 on 30 cm²) these
    // brakes hold it to 1024 m: every target between is within their reach.
    let plain = fly(example(None, None)).apogee_m.unwrap();
    for target in [1100.0, 1300.0, 1500.0, 1750.0] {
        assert!(target < plain - 50.0);
        let m = fly(example(
            Some(json!({"cd": 1.2, "reference_area_m2": 0.003,
                        "target_apogee_m": target, "sampling_rate_hz": 20.0})),
            None,
        ));
        let apogee = m.apogee_m.unwrap();
        let opening = m.air_brakes_max_opening.unwrap();
        eprintln!("target {target} m: apogee {apogee:.6} m, widest opening {opening:.3}");
        // Straight up in still air (the default rail is vertical) the controller's vertical
        // coast is the flight's own; it reads the true state and acts at once, 20 times a
        // second to the end; its prediction errs less the less climb is left, and the last
        // sample comes with at most 0.05 s of climb (about 1 cm) to go: within a millimetre.
        assert!((apogee - target).abs() < 1e-3, "{apogee} against {target}");
        assert!(opening > 0.0 && opening < 1.0, "{opening}");
        assert!(m.air_brakes_open_time_s.unwrap() >= m.burnout_time_s.unwrap());
    }
    // Aiming above what the rocket reaches: the brakes never open, and the flight is the
    // plain one's to the integrator's tolerance (the samples still cut its steps).
    let high = fly(example(
        Some(json!({"cd": 1.2, "reference_area_m2": 0.003,
                    "target_apogee_m": plain + 100.0, "sampling_rate_hz": 20.0})),
        None,
    ));
    assert_eq!(high.air_brakes_open_time_s, None);
    assert_eq!(high.air_brakes_max_opening, Some(0.0));
    assert!((high.apogee_m.unwrap() - plain).abs() < 1e-5 * plain);
}

#[test]
fn braked_rockets_fly_in_the_batch_bit_for_bit_as_their_single_flights() {
    let sim = still_air(
        example(
            Some(json!({"cd": 1.2, "reference_area_m2": 0.003,
                        "target_apogee_m": 1000.0, "sampling_rate_hz": 20.0})),
            None,
        ),
        motor("Cesaroni_I175"),
    );
    let lanes = batch_flies_as_singles(sim);
    assert!(
        lanes
            .iter()
            .all(|l| l.metrics.air_brakes_open_time_s.is_some()),
        "every variant's brakes opened"
    );
}

#[test]
fn a_flight_aims_its_brakes_at_another_target_and_one_without_brakes_is_refused() {
    let braked = || {
        still_air(
            example(
                Some(json!({"cd": 1.2, "reference_area_m2": 0.003,
                            "target_apogee_m": 1500.0, "sampling_rate_hz": 20.0})),
                None,
            ),
            motor("Cesaroni_I175"),
        )
    };
    let aimed = braked().with_air_brakes_target(1300.0).unwrap();
    assert_eq!(aimed.model().air_brakes.unwrap().target_apogee_m, 1300.0);
    let apogee = aimed.run(&mut ()).unwrap().metrics.apogee_m.unwrap();
    assert!((apogee - 1300.0).abs() < 1e-3, "{apogee}");
    for bad in [0.0, -1.0, f64::NAN] {
        let e = braked()
            .with_air_brakes_target(bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains("target apogee must be positive"), "{e}");
    }
    let plain = still_air(example(None, None), motor("Cesaroni_I175"));
    let e = plain
        .with_air_brakes_target(1300.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("has no air brakes"), "{e}");
}

#[test]
fn air_brakes_at_the_highest_sampling_rate_fly_to_their_target() {
    // 10,000 samples a second (the most the design format allows), each a stop time: some
    // 150,000 steps from burnout to apogee, once refused at the step limit of 100,000.
    let m = fly(example(
        Some(json!({"cd": 1.2, "reference_area_m2": 0.003,
                    "target_apogee_m": 1500.0, "sampling_rate_hz": 10_000.0})),
        None,
    ));
    let apogee = m.apogee_m.unwrap();
    eprintln!("apogee {apogee:.6} m against the target 1500 m");
    assert!((apogee - 1500.0).abs() < 1e-3, "{apogee}");
    assert!(m.landing_time_s.is_some());
}
