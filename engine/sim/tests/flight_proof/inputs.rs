//! Bad input gives a clear error naming the field and the rule; a flight that goes
//! non-finite stops with an error naming the time and the state, never a panic.

use crate::common::*;
use hpr_design::aero::MachTable;
use hpr_design::motor::Motor;
use hpr_sim::flight::{
    driver, CanopyShape, Integrator, Parachute, Rail, SimError, SimOptions, Simulation,
};
use hpr_sim::frames;
use hpr_sim::trigger::Trigger;
use hpr_sim::wind::Wind;
use std::sync::Arc;

fn example() -> Simulation {
    Simulation::new(
        design("example-minimal.json"),
        motor("Cesaroni_I175"),
        hpr_sim::flight::Environment::default(),
        Rail::default(),
    )
    .expect("set up")
}

/// The message of a refusal, which must name every one of `words`.
#[track_caller]
fn refused(r: Result<Simulation, SimError>, words: &[&str]) -> String {
    let msg = match r {
        Err(e) => e.to_string(),
        Ok(_) => panic!("accepted; expected a refusal naming {words:?}"),
    };
    for w in words {
        assert!(msg.contains(w), "{msg:?} does not name {w:?}");
    }
    eprintln!("refused: {msg}");
    msg
}

#[test]
fn a_rail_shorter_than_the_rocket_below_its_upper_guide_is_refused() {
    // The example's upper button is about 0.5 m above its aft end.
    let sim = |length_m| {
        Simulation::new(
            design("example-minimal.json"),
            motor("Cesaroni_I175"),
            hpr_sim::flight::Environment::default(),
            Rail {
                length_m,
                ..Rail::default()
            },
        )
    };
    refused(
        sim(0.4),
        &["rail", "\"length_m\"", "upper rail guide", "0.4"],
    );
    refused(sim(0.0), &["rail", "\"length_m\"", "positive"]);
    refused(sim(f64::NAN), &["rail", "\"length_m\"", "finite"]);
    let steep = Simulation::new(
        design("example-minimal.json"),
        motor("Cesaroni_I175"),
        hpr_sim::flight::Environment::default(),
        Rail {
            inclination_deg: 95.0,
            ..Rail::default()
        },
    );
    refused(steep, &["\"inclination_deg\"", "at most 90"]);
}

#[test]
fn a_trigger_that_can_never_fire_is_refused() {
    let chute = |t: Trigger| vec![Parachute::new("main", 1.0, t, 0.5)];
    refused(
        example().with_parachutes(chute(Trigger::HeightDescending { height_m: 0.0 })),
        &["\"main\"", "above the ground", "never opens"],
    );
    refused(
        example().with_parachutes(chute(Trigger::HeightDescending { height_m: -5.0 })),
        &["\"main\"", "\"height_m\"", "not negative"],
    );
    refused(
        example().with_parachutes(chute(Trigger::Time { time_s: f64::NAN })),
        &["\"main\"", "\"time_s\"", "finite"],
    );
    // A plugged motor has no ejection charge: "burnout + the motor's delay" never comes.
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("plugged.eng");
    std::fs::write(
        &path,
        "P100 38 250 P 0.1 0.3 Test\n0.05 100\n1.0 100\n1.05 0\n",
    )
    .unwrap();
    let plugged = Motor::from_file(&path).unwrap();
    assert!(plugged.delays_s.is_empty());
    let sim = Simulation::new(
        design("example-minimal.json"),
        plugged,
        hpr_sim::flight::Environment::default(),
        Rail::default(),
    )
    .unwrap();
    refused(
        sim.with_parachutes(chute(Trigger::BurnoutPlusDelay { delay_s: None })),
        &["\"main\"", "plugged", "never fires"],
    );
}

#[test]
fn a_parachute_without_a_positive_drag_area_is_refused() {
    for cds in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        refused(
            example().with_parachutes(vec![Parachute::new("drogue", cds, Trigger::Apogee, 0.0)]),
            &[
                "parachute 0",
                "\"drogue\"",
                "\"cds_m2\"",
                "positive and finite",
            ],
        );
    }
    refused(
        example().with_parachutes(vec![Parachute::new("drogue", 1.0, Trigger::Apogee, -1.0)]),
        &["\"lag_s\"", "not negative"],
    );
}

#[test]
fn a_canopy_without_a_positive_size_or_with_a_porosity_outside_0_to_1_is_refused() {
    let chute = |canopy: CanopyShape| {
        vec![Parachute::new("main", 1.0, Trigger::Apogee, 0.0).with_canopy(canopy)]
    };
    for bad in [0.0, -0.5, f64::NAN, f64::INFINITY] {
        let radius = CanopyShape {
            radius_m: Some(bad),
            ..CanopyShape::default()
        };
        refused(
            example().with_parachutes(chute(radius)),
            &[
                "parachute 0",
                "\"main\"",
                "\"radius_m\"",
                "positive and finite",
            ],
        );
        let height = CanopyShape {
            height_m: Some(bad),
            ..CanopyShape::default()
        };
        refused(
            example().with_parachutes(chute(height)),
            &["\"height_m\"", "positive and finite"],
        );
    }
    for bad in [-0.01, 1.0, 1.5, f64::NAN] {
        let porous = CanopyShape {
            porosity: bad,
            ..CanopyShape::default()
        };
        refused(
            example().with_parachutes(chute(porous)),
            &["\"porosity\"", "at least 0 and below 1"],
        );
    }
    // The edges that are allowed: a closed canopy, and a given size.
    let fine = CanopyShape {
        radius_m: Some(0.4),
        height_m: Some(0.3),
        porosity: 0.0,
    };
    assert!(example().with_parachutes(chute(fine)).is_ok());
}

#[test]
fn tolerances_and_steps_out_of_range_are_refused_when_the_options_are_set() {
    let adaptive = |rtol, p, v, q, w| SimOptions {
        integrator: Integrator::Adaptive {
            rtol,
            atol_position_m: p,
            atol_velocity_m_s: v,
            atol_quaternion: q,
            atol_rate_rad_s: w,
        },
        ..SimOptions::default()
    };
    let cases: [(SimOptions, &[&str]); 9] = [
        (
            adaptive(0.0, 1e-5, 1e-5, 1e-9, 1e-6),
            &["\"rtol\"", "1e-14"],
        ),
        (adaptive(0.5, 1e-5, 1e-5, 1e-9, 1e-6), &["\"rtol\"", "0.1"]),
        (adaptive(f64::NAN, 1e-5, 1e-5, 1e-9, 1e-6), &["\"rtol\""]),
        (
            adaptive(1e-8, -1.0, 1e-5, 1e-9, 1e-6),
            &["\"atol_position_m\"", "positive"],
        ),
        (
            adaptive(1e-8, 1e-5, 0.0, 1e-9, 1e-6),
            &["\"atol_velocity_m_s\"", "positive"],
        ),
        (
            adaptive(1e-8, 1e-5, 1e-5, f64::INFINITY, 1e-6),
            &["\"atol_quaternion\"", "finite"],
        ),
        (
            adaptive(1e-8, 1e-5, 1e-5, 1e-9, f64::NAN),
            &["\"atol_rate_rad_s\""],
        ),
        (
            SimOptions {
                integrator: Integrator::Rk4 { step_s: 0.0 },
                ..SimOptions::default()
            },
            &["\"step_s\"", "positive"],
        ),
        (
            SimOptions {
                max_time_s: -1.0,
                ..SimOptions::default()
            },
            &["\"max_time_s\"", "positive"],
        ),
    ];
    for (o, words) in cases {
        refused(example().with_options(o), words);
    }
}

#[test]
fn a_nan_wind_cannot_be_built() {
    let e = Wind::constant(f64::NAN, 0.0).unwrap_err().to_string();
    eprintln!("refused: {e}");
    assert!(e.contains("speed_m_s") && e.contains("finite"), "{e}");
    let e = Wind::constant(5.0, f64::NAN).unwrap_err().to_string();
    assert!(e.contains("from_deg") && e.contains("finite"), "{e}");
}

/// A flight model whose drag curve has a hole (NaN) from Mach 0.3 up, behind the checks (as a
/// design whose numbers produce NaN somewhere in flight would): the flight is finite until
/// the rocket reaches Mach 0.3, a few tenths of a second after the rail.
fn poisoned(integrator: Integrator) -> hpr_sim::flight::FlightModel {
    let sim = example()
        .with_options(SimOptions {
            integrator,
            ..SimOptions::default()
        })
        .unwrap();
    let mut model = sim.model().clone();
    let mut aero = (*model.aero).clone();
    let hole = |m: f64| if m < 0.3 { 0.45 } else { f64::NAN };
    aero.cd_power_on = MachTable::from_fn(hole);
    aero.cd_power_off = MachTable::from_fn(hole);
    model.aero = Arc::new(aero);
    model
}

#[track_caller]
fn non_finite(r: Result<hpr_sim::flight::Flight, SimError>, near_s: (f64, f64)) -> f64 {
    match r {
        Err(SimError::NonFinite { time_s, ref state }) => {
            let msg = r.as_ref().unwrap_err().to_string();
            eprintln!("stopped: {msg}");
            assert!(
                time_s >= near_s.0 && time_s <= near_s.1,
                "time {time_s} outside {near_s:?}"
            );
            assert!(msg.contains("non-finite") && msg.contains(&format!("t = {time_s}")));
            assert!(
                msg.contains(state.as_str()) && state.starts_with('['),
                "{msg}"
            );
            time_s
        }
        Err(e) => panic!("expected a non-finite stop, got {e}"),
        Ok(f) => panic!(
            "the flight went on to {:?} with NaN in it",
            f.events.last().map(|e| e.kind)
        ),
    }
}

#[test]
fn a_flight_that_goes_non_finite_stops_with_the_time_and_the_state() {
    // When does the sound flight pass Mach 0.3? The poisoned one must stop there.
    let sound = example().run(&mut ()).unwrap();
    let t_mach = sound
        .samples
        .iter()
        .find(|s| s.mach >= 0.3)
        .expect("passes Mach 0.3")
        .t_s;
    let exit = sound.metrics.rail_exit_time_s.unwrap();
    eprintln!("the sound flight leaves the rail at {exit:.4} s, passes Mach 0.3 by {t_mach:.4} s");
    // The adaptive stepper rejects the NaN stages until its step underflows; RK4 would carry
    // the NaN into the state: both must stop where the NaN first appeared.
    let t = non_finite(
        driver::run(&poisoned(Integrator::DEFAULT), &mut ()),
        (exit, t_mach),
    );
    let t4 = non_finite(
        driver::run(&poisoned(Integrator::Rk4 { step_s: 0.01 }), &mut ()),
        (exit, t_mach),
    );
    eprintln!("non-finite at {t:.6} s (adaptive), {t4:.6} s (RK4)");
    // A NaN start state, or one whose rates overflow the first derivative.
    let sim = example();
    let t0 = sim.model().burnout_s + 1.0;
    let q = frames::rail_attitude(80.0, 0.0);
    let nan = state([0.0, 0.0, 100.0], [0.0, 0.0, f64::NAN], q, [0.0; 3]);
    non_finite(sim.run_from(&mut (), t0, &nan), (t0, t0));
    let wild = state([0.0, 0.0, 100.0], [0.0; 3], q, [1e160, 1e160, 0.0]);
    non_finite(sim.run_from(&mut (), t0, &wild), (t0, t0));
}

#[test]
fn a_rocket_whose_parts_all_weigh_nothing_flies_on_its_motor_alone() {
    // Explicit masses may be zero; with every one zero the structure has no mass and no
    // inertia, and the flight must still be finite (the motor carries all the mass).
    let path = repo("validation/designs/calisto.json");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("\"mass_kg\": 14.426", "\"mass_kg\": 0.0");
    let design = hpr_design::Design::from_json_str(&text, Some(&path)).unwrap();
    assert_eq!(hpr_design::mass::dry(&design).mass_kg, 0.0);
    let sim = Simulation::new(
        design,
        motor("Cesaroni_M1670"),
        hpr_sim::flight::Environment::default(),
        Rail {
            length_m: 5.2,
            ..Rail::default()
        },
    )
    .and_then(|s| {
        s.with_options(SimOptions {
            max_time_s: 20.0,
            ..SimOptions::default()
        })
    })
    .unwrap();
    let f = sim.run(&mut ()).expect("a finite flight");
    let m0 = sim.mass_properties_at(0.0).mass_kg;
    let motor_mass = sim.motor().total_mass_kg;
    eprintln!(
        "massless structure: {m0} kg at ignition (the motor's {motor_mass} kg), {:.1} m at \
         {:.1} s",
        f.samples.last().unwrap().altitude_m,
        f.samples.last().unwrap().t_s
    );
    assert_eq!(m0, motor_mass);
    assert!(f
        .samples
        .iter()
        .all(|s| s.position_m.iter().all(|x| x.is_finite())));
}
