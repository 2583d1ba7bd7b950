//! Flights past the small angles RocketPy's model is written for: a rocket whose ballast makes
//! it unstable turns over and flies tail first, and must still be slowed by its drag, come
//! down and land in an ordinary number of steps.

use crate::common::*;
use hpr_sim::events::EventKind;
use hpr_sim::flight::model::MAX_SHIFTS;
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

/// The reference design with its structure's center of mass 0.52 m further aft (1.06 m on
/// a 1.15 m rocket, as a variant of a ballast sweep under a 0.3 m dispersion of that center
/// drew it) and its 200 g ballast moved 0.3 m aft from 5 s over 1 s: the ballast moves toward
/// the center of mass, and the rocket's inertia about that center falls as it goes.
fn far_aft() -> Simulation {
    Simulation::new(
        design("synthetic-54mm-three-fin.json"),
        motor("Cesaroni_I175"),
        Environment {
            elevation_m: 300.0,
            wind: Wind::constant(4.0, 262.5).unwrap(),
            ..Environment::default()
        },
        Rail {
            length_m: 1.83,
            inclination_deg: 85.0,
            heading_deg: 270.0,
        },
    )
    .unwrap()
    .with_mass_adjustment(0.0, 0.52)
    .unwrap()
    .with_parachutes(vec![
        Parachute::new("drogue", 0.106, Trigger::Apogee, 1.0),
        Parachute::new(
            "main",
            0.954,
            Trigger::HeightDescending { height_m: 150.0 },
            1.0,
        ),
    ])
    .unwrap()
    .with_options(SimOptions::default())
    .unwrap()
    .with_shifts(vec![MassShift::new(
        Trigger::Time { time_s: 5.0 },
        "ballast",
        0.3,
        1.0,
    )])
    .unwrap()
}

#[test]
fn a_structure_moved_far_aft_keeps_a_positive_inertia_about_the_center_of_mass_while_its_ballast_moves(
) {
    let sim = far_aft();
    let model = sim.model();
    let mut starts = [f64::INFINITY; MAX_SHIFTS];
    starts[0] = 5.0;
    // The smallest transverse moment of inertia about the center of mass, through the move.
    let smallest = (0..=1000)
        .map(|i| {
            let t = 4.9 + 1.2 * i as f64 / 1000.0;
            let i_cm = model.instant(&starts, t).mass.inertia_cm();
            (t, i_cm[(0, 0)].min(i_cm[(1, 1)]))
        })
        .fold((0.0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
    // A body's inertia about its center of mass is at least what its parts have about
    // their own centers: here, the structure without its ballast (which the change carries
    // aft whole, its own inertia with it) and the ballast.
    let d = sim.design();
    let ballast = hpr_design::mass::subtree(d, d.component_index("ballast").unwrap());
    let rest = hpr_design::mass::dry(d).combine(&ballast.scaled(-1.0));
    let bound = rest.transverse_inertia() + ballast.transverse_inertia();
    println!(
        "smallest transverse inertia {:.5} kg·m² at {:.3} s, its parts' own {bound:.5} kg·m²",
        smallest.1, smallest.0
    );
    assert!(
        smallest.1 >= bound,
        "{} kg·m² at {} s, less than its parts' own {bound} kg·m²",
        smallest.1,
        smallest.0
    );
    // The structure's center of mass still moved by the whole 0.52 m: the rocket's first
    // moment changed by the structure's mass times 0.52 m, at every instant.
    let plain = Simulation::new(
        design("synthetic-54mm-three-fin.json"),
        motor("Cesaroni_I175"),
        Environment::default(),
        Rail::default(),
    )
    .unwrap();
    let structure_kg = hpr_design::mass::dry(sim.design()).mass_kg;
    for t in [0.0, 1.0, 3.0, 10.0] {
        let (a, b) = (mass_at(&sim, t), mass_at(&plain, t));
        let moved = (b.r_cm.z - a.r_cm.z) * a.mass_kg / structure_kg;
        assert!((moved - 0.52).abs() < 1e-12, "{t} s: {moved} m");
        assert_eq!(a.mass_kg, b.mass_kg);
    }
}

#[test]
fn a_rocket_whose_structure_sits_far_aft_flies_through_its_ballast_move_and_lands() {
    let f = far_aft().run(&mut ()).unwrap();
    let landing = f.event(EventKind::Landing).expect("a landing");
    println!(
        "steps {}, landing {:.2} m/s at {:.1} s",
        f.steps, landing.speed_m_s, landing.time_s
    );
    assert!(landing.speed_m_s.is_finite() && landing.speed_m_s < 10.0);
    assert!(f.steps < 1_100, "{} steps", f.steps);
}
