//! What the drag reads: the air meets the airframe. While the motor burns the center of mass
//! drifts forward through the airframe (`r′`, a few cm/s); the drag and the Mach number are
//! those of the airframe's point at the center of mass, as RocketPy's are of its center of
//! dry mass, a point of the airframe (with the drift in them every cross-checked apogee came
//! out 0.08 to 0.16 m below RocketPy's; see `crosscheck.rs`).

use crate::common::*;
use hpr_sim::eom::N6;
use hpr_sim::flight::model::MAX_SHIFTS;
use hpr_sim::flight::{Environment, Rail, Simulation};
use hpr_sim::frames;

/// The reference design on its I175 in still air, its drag scaled by `scale`.
fn sim(scale: f64) -> Simulation {
    Simulation::new(
        design("synthetic-54mm-three-fin.json"),
        motor("Cesaroni_I175"),
        Environment::default(),
        Rail::default(),
    )
    .and_then(|s| s.with_drag_scale(scale))
    .expect("set up")
}

#[test]
fn an_airframe_at_rest_in_still_air_feels_no_drag_while_its_center_of_mass_drifts() {
    // O at rest, no rotation, still air: whatever the drag scale, the derivative is the same
    // bit for bit, though the center of mass moves through the airframe. Given O the
    // center's drift instead, the airframe moves through the air and the drag scale shows:
    // the check can see a drag of that speed (about 1e-5 N).
    let (one, two) = (sim(1.0), sim(2.0));
    let starts = [f64::INFINITY; MAX_SHIFTS];
    let q = frames::rail_attitude(90.0, 0.0);
    let to_inertial = frames::body_to_inertial(&q);
    for t in [0.3, 1.0, 2.0] {
        let drift_b = mass_at(&one, t).r_cm_rate;
        assert!(
            drift_b.norm() > 1e-3,
            "the center drifts at {t} s: {drift_b}"
        );
        let at_rest = state([0.0, 0.0, 100.0], [0.0; 3], q, [0.0; 3]);
        let (mut a, mut b) = ([0.0; N6], [0.0; N6]);
        one.model().derivative_6dof(&starts, t, &at_rest, &mut a);
        two.model().derivative_6dof(&starts, t, &at_rest, &mut b);
        assert_eq!(
            a, b,
            "at {t} s the drag scale changed the derivative at rest"
        );

        let v = to_inertial * drift_b;
        let moving = state([0.0, 0.0, 100.0], [v.x, v.y, v.z], q, [0.0; 3]);
        one.model().derivative_6dof(&starts, t, &moving, &mut a);
        two.model().derivative_6dof(&starts, t, &moving, &mut b);
        let dv = (a[5] - b[5]).abs();
        println!(
            "at {t} s: drift {:.4} m/s, drag's deceleration {dv:.3e} m/s²",
            drift_b.norm()
        );
        assert!(
            dv > 1e-7,
            "at {t} s the airframe at the drift's speed felt no drag: {dv}"
        );
    }
}

#[test]
fn the_largest_dynamic_pressure_is_half_gamma_p_mach_squared_at_its_sample() {
    // ½ ρ v² = ½ ρ a² M² = (γ/2) p M², with ρ a² = γ p: the metric, from the flight's air
    // table's density and its airspeed, against the exact standard atmosphere's pressure at
    // each sample's height and the sample's Mach number (a sample is recorded wherever the
    // metric is taken: every step's end and every event). The table's interpolation holds
    // ρ and a to 5e-7 each: 2e-6 of q.
    let f = reference_flight_in_wind(
        5.0,
        300.0,
        vec![hpr_sim::Parachute::new(
            "main",
            0.9,
            hpr_sim::Trigger::Apogee,
            1.0,
        )],
    );
    let atm = hpr_sim::atmosphere::Atmosphere::standard(0.0).unwrap();
    let (mut q_max, mut at) = (0.0f64, 0.0);
    let mut worst_sample = 0.0f64;
    for s in &f.samples {
        let q = 0.5
            * hpr_sim::atmosphere::GAMMA_AIR
            * atm.at(s.altitude_m).pressure_pa
            * s.mach
            * s.mach;
        if q > q_max {
            (q_max, at) = (q, s.t_s);
        }
        // Each sample's own dynamic pressure is the same (in the air, where q ≥ 1 Pa).
        if q >= 1.0 {
            worst_sample = worst_sample.max((s.dynamic_pressure_pa - q).abs() / q);
        }
    }
    assert!(
        worst_sample <= 2e-6,
        "a sample's dynamic pressure {worst_sample:e} off"
    );
    let m = &f.metrics;
    let rel = (m.max_dynamic_pressure_pa - q_max).abs() / q_max;
    eprintln!(
        "max Q {:.1} Pa, (γ/2) p M² {q_max:.1} Pa at {at:.4} s (relative {rel:.1e}); max speed {:.2} m/s",
        m.max_dynamic_pressure_pa, m.max_speed_m_s
    );
    assert!(rel <= 2e-6, "{rel:e}");
    // By hand: about ½ · 1.18 kg/m³ · (321 m/s)² ≈ 61 kPa, low down and fast, as the thrust
    // tails off before burnout at 2.5 s.
    assert!((2.0..3.0).contains(&at), "max Q at {at} s");
    assert!((55e3..65e3).contains(&m.max_dynamic_pressure_pa));
}
