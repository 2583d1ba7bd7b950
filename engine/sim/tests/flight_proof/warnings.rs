//! The warnings a flight carries beside its figures (`Flight::warnings`), and the figures they
//! read: the least static margin, the largest angle of attack while climbing (watched as
//! OpenRocket watches its aerodynamic warnings), and whether a canopy opened.

use crate::common::*;
use crate::large_angles::unstable;
use hpr_sim::events::EventKind;
use hpr_sim::flight::{Environment, Flight, Parachute, Phase, Rail, SimOptions, Simulation};
use hpr_sim::flight::{Warning, LARGE_ALPHA_DEG};
use hpr_sim::trigger::Trigger;

/// The reference design on its I175 from a vertical 2 m rail in still air, with the given
/// parachutes.
fn vertical(parachutes: Vec<Parachute>) -> Flight {
    Simulation::new(
        design("synthetic-54mm-three-fin.json"),
        motor("Cesaroni_I175"),
        Environment::default(),
        Rail {
            length_m: 2.0,
            inclination_deg: 90.0,
            heading_deg: 0.0,
        },
    )
    .unwrap()
    .with_parachutes(parachutes)
    .unwrap()
    .with_options(SimOptions::default())
    .unwrap()
    .run(&mut ())
    .unwrap()
}

/// The largest angle of attack among the samples the watch covers, recomputed from the
/// samples: free flight up to apogee, from 0.25 s after rail exit, while the climb is at least
/// 20 % of its fastest so far.
fn watched_alpha_deg(f: &Flight) -> f64 {
    let exit = f.event(EventKind::RailExit).unwrap().time_s;
    let apogee = f.event(EventKind::Apogee).unwrap().time_s;
    let mut fastest = 0.0_f64;
    let mut max = f64::NEG_INFINITY;
    for s in f
        .samples
        .iter()
        .filter(|s| s.phase == Phase::Free && s.t_s <= apogee)
    {
        fastest = fastest.max(s.velocity_m_s[2]);
        if s.t_s >= exit + 0.25 && s.velocity_m_s[2] >= 0.2 * fastest {
            max = max.max(s.alpha_deg);
        }
    }
    max
}

#[test]
fn a_rocket_that_turns_unstable_and_tumbles_is_flagged_with_its_least_margin_and_largest_angle() {
    let f = unstable(true).run(&mut ()).unwrap();
    let m = &f.metrics;
    let (margin, alpha) = (m.static_margin_min_cal.unwrap(), m.max_alpha_deg.unwrap());
    println!("least margin {margin:.3} cal, largest angle of attack {alpha:.2}°");
    // The move takes the margin below −0.9 cal and the rocket turns tail first (large_angles).
    assert!(margin < -0.9, "{margin}");
    let apogee = f.event(EventKind::Apogee).unwrap().time_s;
    let least = f
        .samples
        .iter()
        .filter(|s| s.phase != Phase::Descent && s.t_s <= apogee)
        .map(|s| s.static_margin_cal)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(margin.to_bits(), least.to_bits());
    assert!(alpha > 170.0, "{alpha}");
    // The metric is the samples' largest angle in the watched window, to the last bit.
    assert_eq!(alpha.to_bits(), watched_alpha_deg(&f).to_bits());
    assert_eq!(
        f.warnings(),
        vec![
            Warning::NegativeStaticMargin { min_cal: margin },
            Warning::LargeAngleOfAttack { max_deg: alpha },
        ]
    );
    let text: Vec<String> = f.warnings().iter().map(|w| w.to_string()).collect();
    assert!(text[0].starts_with("unstable: "), "{}", text[0]);
    assert!(text[1].starts_with("large_alpha: "), "{}", text[1]);
}

#[test]
fn a_vertical_flight_arcing_over_at_apogee_is_not_flagged_though_its_angle_of_attack_grows_there() {
    let f = vertical(vec![Parachute::new("main", 0.9, Trigger::Apogee, 1.0)]);
    let apogee = f.event(EventKind::Apogee).unwrap().time_s;
    // In still air the rocket stays nearly vertical; as the climb stops, the little sideways
    // speed it has is all its speed, and the angle of attack grows large without any tumble.
    let near_apogee = f
        .samples
        .iter()
        .filter(|s| s.phase == Phase::Free && s.t_s <= apogee)
        .map(|s| s.alpha_deg)
        .fold(0.0, f64::max);
    let alpha = f.metrics.max_alpha_deg.unwrap();
    println!("largest angle before apogee {near_apogee:.1}°, watched {alpha:.3}°");
    assert!(near_apogee > LARGE_ALPHA_DEG, "{near_apogee}");
    // While climbing fast it flies straight: well under a degree (no wind, no thrust
    // misalignment; only the rail's tip-off turns it).
    assert!(alpha < 1.0, "{alpha}");
    assert_eq!(alpha.to_bits(), watched_alpha_deg(&f).to_bits());
    assert_eq!(f.warnings(), vec![]);
}

#[test]
fn a_flight_without_an_open_canopy_is_flagged_ballistic_at_its_landing_speed() {
    let f = vertical(vec![]);
    let landing = f.event(EventKind::Landing).unwrap();
    println!("ballistic landing at {:.1} m/s", landing.speed_m_s);
    assert_eq!(
        f.warnings(),
        vec![Warning::NoCanopyAtLanding {
            speed_m_s: f.metrics.landing_speed_m_s.unwrap()
        }]
    );
    assert!(f.warnings()[0].to_string().starts_with("ballistic: "));
    assert_eq!(f.deploy(0), None);
}

#[test]
fn a_parachute_s_opening_is_its_deploy_event_one_lag_after_its_trigger() {
    let lag_s = 1.5;
    let f = vertical(vec![Parachute::new("main", 0.9, Trigger::Apogee, lag_s)]);
    let (t, speed) = f.deploy(0).unwrap();
    let trigger = f.event(EventKind::ParachuteTrigger(0)).unwrap();
    let deploy = f.event(EventKind::ParachuteDeploy(0)).unwrap();
    assert_eq!((t, speed), (deploy.time_s, deploy.speed_m_s));
    // Opened at the stop time trigger + lag, to rounding.
    assert!((t - (trigger.time_s + lag_s)).abs() < 1e-12, "{t}");
    // 1.5 s of fall from rest at the top of a vertical flight: at most g·t = 14.7 m/s, the
    // drag only slowing it, and more than 10 m/s (the drag of the bare rocket is small).
    assert!(speed > 10.0 && speed < 9.81 * lag_s + 0.1, "{speed}");
}
