//! Flights past the small angles RocketPy's model is written for: a rocket whose ballast makes
//! it unstable turns over and flies tail first, and must still be slowed by its drag, come
//! down and land in an ordinary number of steps.

use crate::common::*;
use hpr_sim::events::EventKind;
use hpr_sim::flight::{Environment, Parachute, Rail, SimOptions, Simulation};
use hpr_sim::trigger::Trigger;
use hpr_sim::wind::Wind;
use hpr_sim::MassShift;

/// The reference design with its structure's center of mass 0.3 m further aft (static margin
/// −0.36 cal on the pad, +0.18 cal after burnout) and its ballast thrown 0.29 m aft at 5 s
/// (margin −1.1 cal): it turns over in the coast. The inputs of a variant of the bundled ballast
/// sweep under a wide dispersion of the structure's center of mass, which before the large-angle
/// aerodynamics took more than three million steps in its first 10 s.
pub fn unstable(shift: bool) -> Simulation {
    let env = Environment {
        elevation_m: 300.0,
        wind: Wind::constant(5.69, 298.7).unwrap(),
        ..Environment::default()
    };
    let rail = Rail {
        length_m: 1.83,
        inclination_deg: 84.45,
        heading_deg: 271.7,
    };
    let sim = Simulation::new(
        design("synthetic-54mm-three-fin.json"),
        motor("Cesaroni_I175"),
        env,
        rail,
    )
    .unwrap()
    .with_mass_adjustment(0.0, 0.3)
    .unwrap()
    .with_parachutes(vec![
        Parachute::new("drogue", 0.112, Trigger::Apogee, 0.86),
        Parachute::new(
            "main",
            0.975,
            Trigger::HeightDescending { height_m: 155.8 },
            1.36,
        ),
    ])
    .unwrap()
    .with_options(SimOptions::default())
    .unwrap();
    if shift {
        sim.with_shifts(vec![MassShift::new(
            Trigger::Time { time_s: 4.96 },
            "ballast",
            0.29,
            1.02,
        )])
        .unwrap()
    } else {
        sim
    }
}

#[test]
fn a_rocket_that_turns_tail_first_is_slowed_by_its_drag_and_lands_in_an_ordinary_number_of_steps() {
    let f = unstable(true).run(&mut ()).unwrap();
    let shift_t = f.shift_starts_s[0].unwrap();
    let apogee = f.event(EventKind::Apogee).expect("an apogee");
    let landing = f.event(EventKind::Landing).expect("a landing");
    // It did turn over: some sample after the move flies more than 170° off the nose.
    let tail_first: Vec<_> = f
        .samples
        .iter()
        .filter(|s| s.t_s > shift_t && s.t_s < apogee.time_s && s.alpha_deg > 170.0)
        .collect();
    println!(
        "steps {}, apogee {:.1} m at {:.2} s, landing {:.2} m/s at {:.1} s, {} samples tail first",
        f.steps,
        apogee.altitude_m,
        apogee.time_s,
        landing.speed_m_s,
        landing.time_s,
        tail_first.len()
    );
    assert!(tail_first.len() >= 10, "it never flew tail first");
    // Flying tail first it slows down, sample by sample (drag and gravity both oppose the
    // climb; a drag that pointed aft regardless would push it ever faster).
    for w in tail_first.windows(2) {
        assert!(
            w[1].speed_m_s < w[0].speed_m_s,
            "sped up tail first: {:.3} → {:.3} m/s at {:.3} s",
            w[0].speed_m_s,
            w[1].speed_m_s,
            w[1].t_s
        );
    }
    // Nothing faster than the motor made it: after burnout, gravity and the air only take
    // speed away (1 m/s for the wind's share of the airspeed).
    let burnout = f.event(EventKind::Burnout).expect("a burnout");
    let max_speed = f
        .samples
        .iter()
        .filter(|s| s.t_s > burnout.time_s)
        .map(|s| s.speed_m_s)
        .fold(0.0, f64::max);
    assert!(
        max_speed < burnout.speed_m_s + 1.0,
        "max speed after burnout {max_speed} m/s, {} m/s at burnout",
        burnout.speed_m_s
    );
    // It lands under its main at an ordinary speed (the main's terminal speed is about
    // 6.7 m/s at this mass; 2 % covers the air's density at the field).
    assert!(
        (landing.speed_m_s - 6.7).abs() < 0.15,
        "{}",
        landing.speed_m_s
    );
    // An ordinary flight's count of steps is about 540: allow twice that for the tumble.
    assert!(f.steps < 1_100, "{} steps", f.steps);
}

#[test]
fn a_rocket_unstable_on_the_pad_turns_over_without_its_steps_collapsing() {
    // The same rocket without the move: margin −0.36 cal at liftoff. It weathercocks away
    // during the burn; whatever attitude it takes, it must reach the ground.
    let f = unstable(false).run(&mut ()).unwrap();
    let landing = f.event(EventKind::Landing).expect("a landing");
    let max_alpha = f.samples.iter().map(|s| s.alpha_deg).fold(0.0, f64::max);
    println!(
        "steps {}, max angle of attack {max_alpha:.1}°, landing {:.2} m/s at {:.1} s",
        f.steps, landing.speed_m_s, landing.time_s
    );
    assert!(landing.speed_m_s.is_finite() && landing.speed_m_s < 10.0);
    assert!(f.steps < 1_100, "{} steps", f.steps);
}
