//! Free flight after burnout in a vacuum, against exact answers: the parabola of the center
//! of mass, the conservation of angular momentum about it, and RK4's fourth order.

use crate::common::*;
use hpr_sim::eom::{self, N6};
use hpr_sim::events::EventKind;
use hpr_sim::flight::{Flight, Integrator, Rail, Simulation};
use hpr_sim::frames;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// The example rocket on its I175, in a vacuum under gravity `g`, set up to fly from a state
/// after burnout.
fn coasting_in(g: f64, integrator: Integrator, max_time_s: f64) -> Simulation {
    Simulation::new(
        design("example-minimal.json"),
        motor("Cesaroni_I175"),
        vacuum(g),
        Rail::default(),
    )
    .and_then(|s| s.with_options(options(integrator, max_time_s)))
    .expect("set up")
}

fn coasting(integrator: Integrator, max_time_s: f64) -> Simulation {
    coasting_in(G0, integrator, max_time_s)
}

/// Center of mass position and velocity of a 6-DOF state at `t`.
fn cm(sim: &Simulation, t: f64, y: &[f64; N6]) -> (Vector3<f64>, Vector3<f64>) {
    let ms = mass_at(sim, t);
    let r = frames::body_to_inertial(&[y[6], y[7], y[8], y[9]]);
    (
        eom::center_of_mass_position(y, &ms, &r),
        eom::center_of_mass_velocity(y, &ms, &r),
    )
}

#[test]
fn in_a_vacuum_the_center_of_mass_flies_the_closed_form_parabola() {
    let sim = coasting(TIGHT, 200.0);
    let t0 = sim.model().burnout_s + 1.0;
    // Tilted 60° and turned 30°, not rotating; O 50 m up, thrown up and sideways.
    let q = frames::rail_attitude(60.0, 30.0);
    let y0 = state([5.0, -3.0, 50.0], [20.0, -10.0, 60.0], q, [0.0; 3]);
    let f = sim.run_from(&mut (), t0, &y0).expect("flies");
    let (p0, v0) = cm(&sim, t0, &y0);
    let g = Vector3::new(0.0, 0.0, -G0);
    let (mut err_p, mut err_v) = (0.0f64, 0.0f64);
    for s in &f.samples {
        let dt = s.t_s - t0;
        let p = p0 + v0 * dt + g * (0.5 * dt * dt);
        let v = v0 + g * dt;
        err_p = err_p.max((v3(s.position_m) - p).amax());
        err_v = err_v.max((v3(s.velocity_m_s) - v).amax());
    }
    // Apogee and landing in closed form.
    let t_apo = v0.z / G0;
    let h_apo = p0.z + v0.z * v0.z / (2.0 * G0);
    let t_land = (v0.z + (v0.z * v0.z + 2.0 * G0 * p0.z).sqrt()) / G0;
    let apo = f.event(EventKind::Apogee).expect("apogee");
    let land = f.event(EventKind::Landing).expect("landing");
    let e_apo_t = apo.time_s - t0 - t_apo;
    let e_apo_h = apo.altitude_m - h_apo;
    let e_land = land.time_s - t0 - t_land;
    eprintln!(
        "parabola, {} samples: max position error {err_p:.2e} m, velocity {err_v:.2e} m/s; \
         apogee time {e_apo_t:.2e} s, height {e_apo_h:.2e} m; landing time {e_land:.2e} s, \
         landing height {:.2e} m",
        f.samples.len(),
        land.altitude_m
    );
    // Dormand–Prince integrates a quadratic exactly: what is left is rounding.
    assert!(err_p <= 1e-9, "position error {err_p} m");
    assert!(err_v <= 1e-9, "velocity error {err_v} m/s");
    assert!(e_apo_t.abs() <= 1e-9 && e_apo_h.abs() <= 1e-9);
    assert!(e_land.abs() <= 1e-9 && land.altitude_m.abs() <= 1e-9);
}

#[test]
fn a_flight_started_on_its_way_down_lands_at_the_closed_form_time() {
    // Started descending, there is no apogee to wait for: the landing must still be found.
    let sim = coasting(TIGHT, 200.0);
    let t0 = sim.model().burnout_s + 0.5;
    let y0 = state(
        [0.0, 0.0, 80.0],
        [3.0, 4.0, -5.0],
        frames::rail_attitude(80.0, 0.0),
        [0.0; 3],
    );
    let f = sim.run_from(&mut (), t0, &y0).expect("flies");
    let (p0, v0) = cm(&sim, t0, &y0);
    let t_land = (v0.z + (v0.z * v0.z + 2.0 * G0 * p0.z).sqrt()) / G0;
    let land = f.event(EventKind::Landing);
    eprintln!(
        "descending start: landing {:?}, closed form {:.12} s after the start",
        land.map(|e| e.time_s - t0),
        t_land
    );
    let land = land.expect("a flight started on its way down lands");
    assert!((land.time_s - t0 - t_land).abs() <= 1e-9);
    assert!(f.event(EventKind::TimeLimit).is_none());
}

/// The tumbling start of the torque-free checks: rates about all three axes, thrown up and
/// sideways from 1000 m.
fn tumbling_start(t0_after_burnout: f64, sim: &Simulation) -> (f64, [f64; N6]) {
    let t0 = sim.model().burnout_s + t0_after_burnout;
    let y0 = state(
        [10.0, 20.0, 1000.0],
        [15.0, -7.0, 30.0],
        frames::rail_attitude(70.0, 120.0),
        [3.0, -2.0, 8.0],
    );
    (t0, y0)
}

/// The angular momentum about the center of mass of a sample (inertial components).
fn angular_momentum(sim: &Simulation, s: &hpr_sim::flight::Sample) -> Vector3<f64> {
    let ms = mass_at(sim, s.t_s);
    eom::angular_momentum_about_cm(&attitude_state(s), &ms, &rotation(s))
}

#[test]
fn a_torque_free_tumbling_body_keeps_its_angular_momentum_and_its_centers_velocity() {
    // No air, no gravity: no force and no moment at all.
    let probe = coasting_in(0.0, TIGHT, 1e9);
    let (t0, y0) = tumbling_start(1.0, &probe);
    let sim = coasting_in(0.0, TIGHT, t0 + 5.0);
    let f = sim.run_from(&mut (), t0, &y0).expect("flies");
    let first = &f.samples[0];
    let l0 = angular_momentum(&sim, first);
    let v0 = v3(first.velocity_m_s);
    let p0 = v3(first.position_m);
    let i_cm = mass_at(&sim, t0).inertia_cm();
    let energy = |s: &hpr_sim::flight::Sample| {
        let w = v3(s.omega_rad_s);
        0.5 * w.dot(&(i_cm * w))
    };
    let e0 = energy(first);
    let (mut err_l, mut err_v, mut err_p, mut err_e, mut turn) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for s in &f.samples {
        err_l = err_l.max((angular_momentum(&sim, s) - l0).norm() / l0.norm());
        err_v = err_v.max((v3(s.velocity_m_s) - v0).norm() / v0.norm());
        let p = p0 + v0 * (s.t_s - t0);
        err_p = err_p.max((v3(s.position_m) - p).norm());
        err_e = err_e.max((energy(s) - e0).abs() / e0);
        turn = turn.max((v3(s.omega_rad_s) - v3(first.omega_rad_s)).norm());
    }
    let last = f.samples.last().unwrap();
    eprintln!(
        "torque-free over {:.1} s, {} steps, {} evaluations: |L| = {:.6} kg m²/s, max relative \
         error of L {err_l:.2e}, of the center's velocity {err_v:.2e} (its position off the \
         straight line by {err_p:.2e} m), of the rotational energy {err_e:.2e}; body rates \
         moved by up to {turn:.3} rad/s (they precess)",
        last.t_s - t0,
        f.steps,
        f.derivative_evaluations,
        l0.norm()
    );
    assert!((last.t_s - t0 - 5.0).abs() < 1e-12, "flew the whole 5 s");
    assert!(turn > 1.0, "the body must really tumble");
    assert!(err_l <= 1e-10, "angular momentum drifted by {err_l}");
    assert!(err_v <= 1e-10, "center's velocity off by {err_v}");
    assert!(err_e <= 1e-10, "rotational energy drifted by {err_e}");
}

/// The end of a flight: center of mass position (m), attitude, body rates (rad/s), time.
fn end_of(f: &Flight) -> (Vector3<f64>, UnitQuaternion<f64>, Vector3<f64>, f64) {
    let s = f.samples.last().expect("samples");
    let [w, x, y, z] = s.quaternion;
    let q = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
    (v3(s.position_m), q, v3(s.omega_rad_s), s.t_s)
}

#[test]
fn rk4s_global_error_falls_sixteenfold_when_its_step_is_halved() {
    let probe = coasting(TIGHT, 1e9);
    let (t0, y0) = tumbling_start(1.0, &probe);
    let t_end = t0 + 2.0;
    let reference = coasting(TIGHT, t_end)
        .run_from(&mut (), t0, &y0)
        .expect("reference");
    let (p_ref, q_ref, w_ref, t_ref) = end_of(&reference);
    assert_eq!(t_ref, t_end);
    // ω h from 0.09 down to 0.02: the asymptotic range.
    let steps = [0.01, 0.005, 0.0025];
    let mut errors = Vec::new();
    for h in steps {
        let f = coasting(Integrator::Rk4 { step_s: h }, t_end)
            .run_from(&mut (), t0, &y0)
            .expect("rk4");
        let (p, q, w, t) = end_of(&f);
        assert_eq!(t, t_end);
        let e = [(w - w_ref).norm(), q.angle_to(&q_ref), (p - p_ref).norm()];
        eprintln!(
            "RK4 h = {h} s ({} steps): error of ω {:.4e} rad/s, of the attitude {:.4e} rad, of \
             the center {:.4e} m",
            f.steps, e[0], e[1], e[2]
        );
        errors.push(e);
    }
    for k in 1..errors.len() {
        let r: Vec<f64> = (0..3).map(|i| errors[k - 1][i] / errors[k][i]).collect();
        eprintln!(
            "h {} → {}: error ratios ω {:.3}, attitude {:.3}, center {:.3}",
            steps[k - 1],
            steps[k],
            r[0],
            r[1],
            r[2]
        );
        // Fourth order: 2⁴ = 16, within ±2.
        for (what, ratio) in ["ω", "attitude", "center"].iter().zip(&r) {
            assert!((ratio - 16.0).abs() <= 2.0, "{what}: ratio {ratio}");
        }
    }
    // The reference is far more accurate than the finest RK4 run (its error is ~1e-11).
    assert!(errors.last().unwrap()[0] > 1e-8);
}
