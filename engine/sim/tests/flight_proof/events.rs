//! Every event lands on its root: the apogee where the center's vertical speed is zero, the
//! rail exit at the exact travel, a height trigger at its height, the landing at zero.

use crate::common::*;
use hpr_sim::events::EventKind;
use hpr_sim::flight::{
    CanopyShape, Environment, Flight, Parachute, Rail, Sample, SimOptions, Simulation,
};
use hpr_sim::trigger::Trigger;
use hpr_sim::wind::Wind;

/// The sample recorded at an event (the driver records one at every event, from the dense
/// output at the located time).
fn sample_at(f: &Flight, kind: EventKind) -> (&Sample, f64) {
    let e = f.event(kind).unwrap_or_else(|| panic!("no {kind:?}"));
    let s = f
        .samples
        .iter()
        .find(|s| s.t_s == e.time_s)
        .unwrap_or_else(|| panic!("no sample at the {kind:?} time"));
    (s, e.time_s)
}

#[test]
fn every_event_lands_on_its_root() {
    // The synthetic rocket on its I175 as `hpr-mc fly` sets it up (drogue, the smaller of
    // the design's canopies, at apogee; main at 300 m), off an 85° rail in a 4 m/s wind.
    let design = design("synthetic-54mm-three-fin.json");
    let mut cds: Vec<f64> = design
        .components
        .iter()
        .filter_map(|c| match &c.kind {
            hpr_design::ComponentKind::Parachute(p) => {
                Some(p.cd * std::f64::consts::PI * (0.5 * p.canopy_diameter_m).powi(2))
            }
            _ => None,
        })
        .collect();
    cds.sort_by(f64::total_cmp);
    let main_height = 300.0;
    let chutes = vec![
        Parachute::new("drogue", cds[0], Trigger::Apogee, 1.0),
        Parachute::new(
            "main",
            cds[1],
            Trigger::HeightDescending {
                height_m: main_height,
            },
            1.0,
        ),
    ];
    let env = Environment {
        wind: Wind::constant(4.0, 250.0).unwrap(),
        ..Environment::default()
    };
    let rail = Rail {
        length_m: 2.0,
        inclination_deg: 85.0,
        heading_deg: 70.0,
    };
    let sim = Simulation::new(design, motor("Cesaroni_I175"), env, rail)
        .and_then(|s| s.with_parachutes(chutes))
        .and_then(|s| s.with_options(SimOptions::default()))
        .expect("set up");
    let f = sim.run(&mut ()).expect("flies");

    // Apogee: the center's vertical speed in the sample at the event.
    let (apo, _) = sample_at(&f, EventKind::Apogee);
    let vz = apo.velocity_m_s[2];
    let highest = f
        .samples
        .iter()
        .map(|s| s.altitude_m)
        .fold(f64::MIN, f64::max);

    // Rail exit: O's travel along the rail, from the center of mass in the sample.
    let (exit, t_exit) = sample_at(&f, EventKind::RailExit);
    let rail = &sim.model().rail;
    let ms = mass_at(&sim, t_exit);
    let o = v3(exit.position_m) - rotation(exit) * ms.r_cm;
    let travel = (o - rail.o_start_n).dot(&rail.direction_n);
    let e_travel = travel - rail.travel_to_exit_m;

    // The main's trigger and the landing.
    let trig = f
        .event(EventKind::ParachuteTrigger(1))
        .expect("main trigger");
    let land = f.event(EventKind::Landing).expect("landing");
    let (land_s, _) = sample_at(&f, EventKind::Landing);

    eprintln!(
        "events: apogee {:.3} m at {:.4} s, vertical speed there {vz:.2e} m/s (highest sample \
         {highest:.6} m); rail exit at {t_exit:.6} s, travel {travel:.12} m of {:.12} \
         (error {e_travel:.2e} m); main trigger at {:.4} s, height {:.12} m (error {:.2e}); \
         landing at {:.3} s, height {:.2e} m",
        apo.altitude_m,
        apo.t_s,
        rail.travel_to_exit_m,
        trig.time_s,
        trig.altitude_m,
        trig.altitude_m - main_height,
        land.time_s,
        land.altitude_m
    );
    // Time tolerance of the events 1e-12 s: at |dvz/dt| ≈ g the speed is off by ~1e-11,
    // the heights by the speed times 1e-12 s.
    assert!(vz.abs() <= 1e-9, "vertical speed at apogee {vz}");
    assert!(highest <= apo.altitude_m, "a sample above the apogee");
    assert!(e_travel.abs() <= 1e-9, "rail travel off by {e_travel} m");
    assert!((trig.altitude_m - main_height).abs() <= 1e-9);
    assert!(land.altitude_m.abs() <= 1e-9 && land_s.altitude_m.abs() <= 1e-9);
    // In order: rail exit, apogee, drogue trigger and opening, main, landing.
    let order: Vec<EventKind> = f.events.iter().map(|e| e.kind).collect();
    let pos = |k| order.iter().position(|&x| x == k).unwrap();
    assert!(pos(EventKind::RailExit) < pos(EventKind::Apogee));
    assert!(pos(EventKind::Apogee) <= pos(EventKind::ParachuteTrigger(0)));
    assert!(pos(EventKind::ParachuteDeploy(0)) < pos(EventKind::ParachuteTrigger(1)));
    assert!(pos(EventKind::ParachuteDeploy(1)) < pos(EventKind::Landing));
}

#[test]
fn two_open_canopies_drag_and_carry_air_as_one_canopy_of_their_summed_cds_and_air() {
    // The synthetic rocket on its I175 in a 6 m/s wind, two canopies opening together 1 s
    // after apogee: CdS 0.3 and 0.7 m², each a default hemisphere of radius
    // R_k = √(CdS_k / (1.4 π)). Each drags and carries its own air, so the pair flies as one
    // canopy of CdS 1.0 m² whose hemisphere holds both airs: R³ = R_1³ + R_2³. The two
    // flights differ only in the rounding of the sums, which may tip one of the descent's
    // few long steps (RODAS4's) to another size, so they agree to the integrator's
    // tolerance rather than to rounding: 1e-8 relative (measured 3.6e-9 in time, 3.8e-9 of
    // the drift in position).
    let fly = |chutes: Vec<Parachute>| reference_flight_in_wind(6.0, 200.0, chutes).metrics;
    let r = |cds: f64| (cds / (1.4 * std::f64::consts::PI)).sqrt();
    let pair = fly(vec![
        Parachute::new("a", 0.3, Trigger::Apogee, 1.0),
        Parachute::new("b", 0.7, Trigger::Apogee, 1.0),
    ]);
    let one_of = |radius_m: f64| {
        fly(vec![Parachute::new("ab", 1.0, Trigger::Apogee, 1.0)
            .with_canopy(CanopyShape {
                radius_m: Some(radius_m),
                ..CanopyShape::default()
            })])
    };
    let summed = one_of((r(0.3).powi(3) + r(0.7).powi(3)).cbrt());
    let (t, xy) = (
        pair.landing_time_s.unwrap(),
        pair.landing_position_m.unwrap(),
    );
    let (t1, xy1) = (
        summed.landing_time_s.unwrap(),
        summed.landing_position_m.unwrap(),
    );
    assert!((t - t1).abs() <= 1e-8 * t, "{t} s against {t1} s");
    let drift = xy[0].hypot(xy[1]);
    for k in 0..2 {
        assert!(
            (xy[k] - xy1[k]).abs() <= 1e-8 * drift,
            "{xy:?} against {xy1:?}"
        );
    }
    // One canopy of the summed CdS sized as a single hemisphere (R = √(1 / 1.4 π)) carries
    // more air (R³ = 0.0806 against 0.0691 m³): its opening is slower and the flight differs
    // far beyond that tolerance, so the test above tells the two apart.
    let single = one_of(r(1.0));
    let (t2, xy2) = (
        single.landing_time_s.unwrap(),
        single.landing_position_m.unwrap(),
    );
    eprintln!("pair {t} s {xy:?}; summed {t1} s {xy1:?}; one hemisphere {t2} s {xy2:?}");
    assert!((xy[0] - xy2[0]).abs().max((xy[1] - xy2[1]).abs()) > 1e-6 * drift);
}
