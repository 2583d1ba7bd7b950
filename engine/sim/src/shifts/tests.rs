//! The tests `docs/moving-mass.md` lists ("How it is checked"), each holding the bound given
//! there and printing what it measured.

use crate::cycloid;
use crate::eom::{self, N6};
use crate::events::EventKind;
use crate::flight::model::MAX_SHIFTS;
use crate::flight::{Environment, Flight, Integrator, Parachute, Phase, SimOptions, Simulation};
use crate::frames;
use crate::gravity::Gravity;
use crate::{MassShift, Trigger};
use hpr_design::mass::point_inertia;
use nalgebra::{Matrix3, Vector3};

use crate::reference::testing::{component_mut, design, reference_json, simulation};
use crate::reference::{self, ballast_shift, worked_example};

fn tight() -> SimOptions {
    SimOptions {
        integrator: Integrator::Adaptive {
            rtol: 1e-13,
            atol_position_m: 1e-13,
            atol_velocity_m_s: 1e-13,
            atol_quaternion: 1e-15,
            atol_rate_rad_s: 1e-13,
        },
        max_time_s: 600.0,
        keep_samples: true,
    }
}

fn free_space() -> Environment {
    Environment {
        gravity: Gravity::constant(0.0).unwrap(),
        vacuum: true,
        ..Environment::default()
    }
}

/// A state in free flight: O at 1 km, moving, tilted, turning about all three axes.
fn tumbling_state() -> [f64; N6] {
    let q = nalgebra::UnitQuaternion::from_euler_angles(0.3, -0.2, 0.5);
    let q = q.quaternion();
    [
        0.0, 0.0, 1000.0, 10.0, -5.0, 50.0, q.w, q.i, q.j, q.k, 0.7, -0.4, 2.0,
    ]
}

fn starts_of(flight: &Flight) -> [f64; MAX_SHIFTS] {
    let mut s = [f64::INFINITY; MAX_SHIFTS];
    for (k, v) in flight.shift_starts_s.iter().enumerate() {
        if let Some(v) = v {
            s[k] = *v;
        }
    }
    s
}

/// Angular momentum about the center of mass (inertial) and the center's velocity at a sample.
fn momenta(sim: &Simulation, flight: &Flight, i: usize) -> (Vector3<f64>, Vector3<f64>, f64) {
    let s = &flight.samples[i];
    let ms = sim.model().instant(&starts_of(flight), s.t_s).mass;
    let mut y = [0.0; N6];
    y[6..10].copy_from_slice(&s.quaternion);
    y[10..13].copy_from_slice(&s.omega_rad_s);
    let r = frames::body_to_inertial(&s.quaternion);
    let h_cm = ms.h_rel - ms.r_cm.cross(&(ms.r_cm_rate * ms.mass_kg));
    (
        eom::angular_momentum_about_cm(&y, &ms, &r),
        Vector3::from(s.velocity_m_s),
        h_cm.norm(),
    )
}

#[test]
fn mass_properties_before_during_and_after_a_shift_match_the_hand_calculation() {
    let sim = worked_example();
    let flight = sim.run(&mut ()).unwrap();
    assert_eq!(flight.shift_starts_s, vec![Some(5.0)]);
    // Two bodies: the ballast (m, at c(t), own inertia I_b) and the rest (M − m, fixed).
    let before = sim.mass_properties(&flight, 4.0);
    let ballast = hpr_design::mass::subtree(
        sim.design(),
        sim.design().component_index("ballast").unwrap(),
    );
    let (m, big_m) = (ballast.mass_kg, before.mass_kg);
    let mu = m * (big_m - m) / big_m;
    let rest_cg = (before.cg_m * big_m - ballast.cg_m * m) / (big_m - m);
    let rest_own =
        before.inertia_cg - ballast.inertia_cg - point_inertia(&(ballast.cg_m - rest_cg)) * mu;
    let mut worst: f64 = 0.0;
    for (t, tau) in [(4.0, 0.0), (5.5, 0.5), (7.0, 1.0)] {
        let p = sim.mass_properties(&flight, t);
        let delta = Vector3::new(0.3 * cycloid::fraction(tau), 0.0, 0.0);
        let c = ballast.cg_m + delta;
        let cg = (rest_cg * (big_m - m) + c * m) / big_m;
        let inertia = rest_own + ballast.inertia_cg + point_inertia(&(c - rest_cg)) * mu;
        let e_cg = (p.cg_m - cg).amax();
        let e_i = (p.inertia_cg - inertia).amax();
        eprintln!("t = {t}: center of mass error {e_cg:.1e} m, inertia error {e_i:.1e} kg·m², mass error {:.1e} kg", (p.mass_kg - big_m).abs());
        worst = worst.max(e_cg).max(e_i).max((p.mass_kg - big_m).abs());
        assert_eq!(p.mass_kg, big_m, "the mass does not change");
    }
    assert!(worst <= 1e-15, "worst error {worst:e} (bound 1e-15)");
    // The two-body figures by hand: arithmetic on the worked example's rounded table
    // figures (M 0.8188 kg, center 0.6681 m; ballast 0.2 kg at 0.375 m) gives μ = 0.1511 kg,
    // the rest's center 0.7628 m, the ballast 0.3878 m from it and then 0.0878 m, and the
    // inertia changed by μ (0.0878² − 0.3878²) = −0.0216 kg·m²; the simulator's unrounded
    // figures are the same within that rounding (the rest's center 0.76285 rounds up).
    let hand_mu: f64 = 0.2 * 0.6188 / 0.8188;
    let hand_rest: f64 = (0.8188 * 0.6681 - 0.2 * 0.375) / 0.6188;
    let (hand_d0, hand_d1) = (hand_rest - 0.375, hand_rest - 0.675);
    let hand_change = hand_mu * (hand_d1 * hand_d1 - hand_d0 * hand_d0);
    assert_eq!(
        format!(
            "{hand_mu:.4} {hand_rest:.4} {hand_d0:.4} {:.4} {hand_change:.4}",
            hand_d1.abs()
        ),
        "0.1511 0.7628 0.3878 0.0878 -0.0216"
    );
    let (d0, d1) = (
        (ballast.cg_m.x - rest_cg.x).abs(),
        (ballast.cg_m.x + 0.3 - rest_cg.x).abs(),
    );
    let change =
        sim.mass_properties(&flight, 7.0).transverse_inertia() - before.transverse_inertia();
    eprintln!(
        "unrounded: μ {mu:.6} kg, rest's center {:.6} m, {d0:.6} → {d1:.6} m, ΔI {change:.6} kg·m²",
        rest_cg.x
    );
    for (exact, hand) in [
        (mu, hand_mu),
        (rest_cg.x, hand_rest),
        (d0, hand_d0),
        (d1, hand_d1.abs()),
        (change, hand_change),
    ] {
        assert!(
            (exact - hand).abs() < 2e-4,
            "{exact} against the hand's {hand}"
        );
    }
    assert!((change - mu * (d1 * d1 - d0 * d0)).abs() < 1e-15);
    // The worked example's hand figures: the center moves m Δ / M and halfway at τ = ½.
    let (p0, p1) = (
        sim.mass_properties(&flight, 4.0),
        sim.mass_properties(&flight, 7.0),
    );
    assert!(((p1.cg_m.x - p0.cg_m.x) - 0.2 * 0.3 / 0.8188).abs() < 1e-4 * 0.0733);
    assert!(
        (sim.mass_properties(&flight, 5.5).cg_m.x - 0.5 * (p0.cg_m.x + p1.cg_m.x)).abs() < 1e-15
    );
}

#[test]
fn a_moving_mass_shifts_the_static_margin_by_the_hand_calculation() {
    let sim = worked_example();
    let flight = sim.run(&mut ()).unwrap();
    let burnout = sim.model().burnout_s;
    let d = sim.model().ref_diameter_m;
    let sm0 = sim.static_margin_for(sim.mass_properties(&flight, 4.0).cg_m.x);
    let big_m = sim.mass_properties(&flight, 4.0).mass_kg;
    let mut worst: f64 = 0.0;
    let mut n = 0;
    for s in flight
        .samples
        .iter()
        .filter(|s| s.t_s > burnout && s.phase == Phase::Free)
    {
        let tau = (s.t_s - 5.0).clamp(0.0, 1.0);
        let expected = sm0 - 0.2 * 0.3 * cycloid::fraction(tau) / (big_m * d);
        worst = worst.max((s.static_margin_cal - expected).abs());
        n += 1;
    }
    eprintln!("{n} coast samples, worst static-margin error {worst:.1e} calibres");
    assert!(n > 20);
    assert!(worst <= 1e-12, "worst {worst:e} (bound 1e-12)");
    // The worked example's figures (`docs/moving-mass.md`): 4.297 → 2.996, a change of
    // −1.302 = −0.0733/0.0563.
    let sm1 = sim.static_margin_for(sim.mass_properties(&flight, 7.0).cg_m.x);
    assert_eq!(
        format!("{sm0:.3} {sm1:.3} {:.3}", sm1 - sm0),
        "4.297 2.996 -1.302"
    );
}

#[test]
fn the_flight_margin_moves_by_the_same_amount_as_the_static_margin() {
    // Only the center of pressure differs between the two margins: at every instant of the
    // flight, moving ballast or not, flight − static = (x_cp(Mach) − x_cp(0)) / d.
    let sim = worked_example();
    let flight = sim.run(&mut ()).unwrap();
    let model = sim.model();
    let (mut worst, mut during): (f64, usize) = (0.0, 0);
    for s in flight.samples.iter().filter(|s| s.phase == Phase::Free) {
        let cp_shift = (model.aero.cp_m(s.mach) - model.cp_mach0_m) / model.ref_diameter_m;
        worst = worst.max((s.flight_margin_cal - s.static_margin_cal - cp_shift).abs());
        during += usize::from(s.t_s > 5.0 && s.t_s < 6.0);
    }
    eprintln!("{during} samples during the shift; worst error {worst:.1e} calibres");
    assert!(during >= 16, "the shift's 16 stop times are samples");
    assert!(worst <= 1e-12, "worst {worst:e} (bound 1e-12)");
}

/// The free-space case: the reference rocket after burnout with its ballast 1 cm off the axis,
/// moving 0.3 m aft over 1 s while the rocket turns about all three axes.
fn off_axis_free_space(options: SimOptions, duration_s: f64) -> (Simulation, Flight) {
    let mut v = reference_json();
    let b = component_mut(&mut v, "ballast");
    b["radial_offset_m"] = serde_json::json!(0.01);
    b["radius_m"] = serde_json::json!(0.015);
    let sim = simulation(
        design(&v),
        free_space(),
        SimOptions {
            max_time_s: 5.0 + duration_s + 0.5,
            ..options
        },
    )
    .with_shifts(vec![MassShift::new(
        Trigger::Time { time_s: 5.0 },
        "ballast",
        0.3,
        duration_s,
    )])
    .unwrap();
    let flight = sim.run_from(&mut (), 4.5, &tumbling_state()).unwrap();
    (sim, flight)
}

#[test]
fn a_part_moving_off_the_axis_keeps_both_momenta_in_free_space() {
    let (sim, flight) = off_axis_free_space(tight(), 1.0);
    let (h0, v0, _) = momenta(&sim, &flight, 0);
    let (mut eh, mut ev, mut h_rel_max): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for i in 0..flight.samples.len() {
        let (h, v, h_rel) = momenta(&sim, &flight, i);
        eh = eh.max((h - h0).norm() / h0.norm());
        ev = ev.max((v - v0).norm());
        h_rel_max = h_rel_max.max(h_rel / h0.norm());
    }
    eprintln!(
        "{} samples: angular momentum kept to {eh:.1e} of itself, center's velocity to {ev:.1e} m/s; the ballast's own relative angular momentum peaks at {:.2}% of the rocket's",
        flight.samples.len(),
        100.0 * h_rel_max
    );
    assert!(eh <= 1e-10, "angular momentum {eh:e} (bound 1e-10)");
    assert!(ev <= 1e-10, "center's velocity {ev:e} m/s (bound 1e-10)");
    // The term ω × h + h′ matters here: the ballast's own angular momentum is not negligible
    // (1.19 % of the rocket's at its peak with this test's turning rates; 1.8 % was given
    // for the worked example at rates not stated), far above the bounds above.
    assert!(h_rel_max > 5e-3, "{h_rel_max}");
}

#[test]
fn a_shift_s_rates_are_the_derivatives_of_its_mass_properties() {
    let mut v = reference_json();
    let b = component_mut(&mut v, "ballast");
    b["radial_offset_m"] = serde_json::json!(0.01);
    b["radius_m"] = serde_json::json!(0.015);
    let sim = simulation(design(&v), Environment::default(), SimOptions::default())
        .with_shifts(vec![
            MassShift::new(Trigger::Time { time_s: 1.0 }, "ballast", 0.3, 1.0),
            MassShift::new(Trigger::Time { time_s: 5.0 }, "ballast", -0.09, 0.5),
        ])
        .unwrap();
    let model = sim.model();
    let mut starts = [f64::INFINITY; MAX_SHIFTS];
    starts[0] = 1.0;
    starts[1] = 5.0;
    // During the burn (away from the thrust curve's knots) and after it.
    let knots = &model.thrust_knots_s;
    let (mut e1, mut e2, mut ei): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for t in [1.17, 1.43, 1.71, 5.13, 5.31] {
        let h = 1e-5;
        assert!(knots.iter().all(|k| (k - t).abs() > 2.0 * h));
        let at = |t: f64| model.instant(&starts, t).mass;
        let (m, p, q) = (at(t), at(t + h), at(t - h));
        let d1 = (p.r_cm - q.r_cm) / (2.0 * h);
        let d2 = (p.r_cm_rate - q.r_cm_rate) / (2.0 * h);
        let di: Matrix3<f64> = (p.inertia_o - q.inertia_o) / (2.0 * h);
        e1 = e1.max((d1 - m.r_cm_rate).norm());
        e2 = e2.max((d2 - m.r_cm_accel).norm() / m.r_cm_accel.norm());
        ei = ei.max((di - m.inertia_o_rate).norm() / m.inertia_o_rate.norm());
        // And h′ against h.
        let dh = (p.h_rel - q.h_rel) / (2.0 * h);
        assert!(
            (dh - m.h_rel_rate).norm() <= 1e-7 * m.h_rel_rate.norm().max(1e-12),
            "h′ at {t}"
        );
    }
    eprintln!("r′ error {e1:.1e} m/s, r″ error {e2:.1e} of itself, I′ error {ei:.1e} of itself");
    assert!(e1 <= 1e-9, "r′ {e1:e} (bound 1e-9)");
    assert!(e2 <= 1e-7, "r″ {e2:e} (bound 1e-7)");
    assert!(ei <= 1e-7, "I′ {ei:e} (bound 1e-7)");
}

#[test]
fn a_fixed_step_follows_a_short_shift_in_its_stops() {
    let options = SimOptions {
        integrator: Integrator::Rk4 { step_s: 0.01 },
        ..SimOptions::default()
    };
    let (sim, flight) = off_axis_free_space(options, 0.01);
    let (_, v0, _) = momenta(&sim, &flight, 0);
    let ev = (0..flight.samples.len())
        .map(|i| (momenta(&sim, &flight, i).1 - v0).norm())
        .fold(0.0, f64::max);
    let across = flight
        .samples
        .iter()
        .filter(|s| s.t_s > 5.0 && s.t_s <= 5.01 + 1e-12)
        .count();
    eprintln!(
        "RK4 at 10 ms across a 10 ms move: {across} steps, center's velocity kept to {ev:.1e} m/s"
    );
    assert!(across >= 16, "{across} steps across the move");
    assert!(ev <= 3e-4, "center's velocity {ev:e} m/s (bound 3e-4)");
}

#[test]
fn a_canopy_that_opens_while_the_ballast_moves_keeps_the_center_s_velocity() {
    let env = Environment {
        vacuum: true,
        ..Environment::default()
    };
    let g = env.gravity.at(0.0);
    let sim = simulation(
        design(&reference_json()),
        env,
        SimOptions {
            max_time_s: 8.0,
            ..tight()
        },
    )
    .with_shifts(vec![ballast_shift(5.0)])
    .unwrap()
    .with_parachutes(vec![Parachute::new(
        "drogue",
        0.3,
        Trigger::Time { time_s: 5.2 },
        0.3,
    )])
    .unwrap();
    let flight = sim.run_from(&mut (), 4.5, &tumbling_state()).unwrap();
    let open = flight
        .event(EventKind::ParachuteDeploy(0))
        .expect("the drogue opens")
        .time_s;
    assert_eq!(open, 5.5);
    let first = &flight.samples[0];
    let v0 = Vector3::from(first.velocity_m_s);
    let free_fall = |t: f64| v0 - Vector3::new(0.0, 0.0, g * (t - first.t_s));
    let last_free = flight
        .samples
        .iter()
        .rev()
        .find(|s| s.phase == Phase::Free)
        .unwrap();
    let first_descent = flight
        .samples
        .iter()
        .find(|s| s.phase == Phase::Descent)
        .unwrap();
    assert_eq!(last_free.t_s, open);
    assert_eq!(first_descent.t_s, open);
    let at_opening =
        (Vector3::from(first_descent.velocity_m_s) - Vector3::from(last_free.velocity_m_s)).norm();
    let before = (Vector3::from(last_free.velocity_m_s) - free_fall(open)).norm();
    let after = flight
        .samples
        .iter()
        .filter(|s| s.phase == Phase::Descent)
        .map(|s| (Vector3::from(s.velocity_m_s) - free_fall(s.t_s)).norm())
        .fold(0.0, f64::max);
    eprintln!("at the opening the center's velocity jumps by {at_opening:.1e} m/s (6-DOF vs free fall there {before:.1e}); afterwards it falls freely to {after:.1e} m/s");
    assert!(
        at_opening <= 1e-12 && before <= 1e-9,
        "opening {at_opening:e}, before {before:e}"
    );
    assert!(after <= 1e-9, "after {after:e} (bound 1e-9)");
    // The ballast finishes its move under the canopy.
    let p = sim.mass_properties(&flight, 6.5);
    assert!(
        (p.cg_m.x - sim.mass_properties(&flight, 4.0).cg_m.x - 0.2 * 0.3 / p.mass_kg).abs() < 1e-12
    );
}

#[test]
fn a_shift_the_flight_starts_gets_its_stops_too() {
    // RK4 with 20 ms steps: only the stop times put more than one step inside a 20 ms move.
    let options = SimOptions {
        integrator: Integrator::Rk4 { step_s: 0.02 },
        max_time_s: 40.0,
        ..SimOptions::default()
    };
    let sim = simulation(design(&reference_json()), Environment::default(), options)
        .with_shifts(vec![MassShift::new(Trigger::Apogee, "ballast", 0.3, 0.02)])
        .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let start = flight.shift_starts_s[0].expect("the shift starts");
    let across = flight
        .samples
        .iter()
        .filter(|s| s.t_s > start && s.t_s <= start + 0.02 + 1e-12)
        .count();
    eprintln!("a 20 ms move started at apogee ({start:.4} s) took {across} steps");
    assert_eq!(across, 16);
}

#[test]
fn a_shift_starts_at_apogee_or_at_its_height_on_the_way_down() {
    let sim = reference::simulation()
        .with_shifts(vec![
            MassShift::new(Trigger::Apogee, "ballast", 0.1, 0.5),
            MassShift::new(
                Trigger::HeightDescending { height_m: 200.0 },
                "ballast",
                0.1,
                0.5,
            ),
        ])
        .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let apogee = flight.event(EventKind::Apogee).unwrap();
    let s0 = flight.event(EventKind::Shift(0)).unwrap();
    let s1 = flight.event(EventKind::Shift(1)).unwrap();
    eprintln!(
        "apogee {:.6} m at {:.6} s; shift 0 at {:.6} s; shift 1 at {:.6} m ({:.4} s)",
        apogee.altitude_m, apogee.time_s, s0.time_s, s1.altitude_m, s1.time_s
    );
    assert_eq!(s0.time_s, apogee.time_s);
    assert!((s0.altitude_m - apogee.altitude_m).abs() <= 1e-6);
    assert!((s1.altitude_m - 200.0).abs() <= 1e-6, "{}", s1.altitude_m);
    assert!(s1.time_s > apogee.time_s);
}

#[test]
fn a_shift_starts_at_burnout_or_its_delay_after() {
    let sim = reference::simulation()
        .with_shifts(vec![
            MassShift::new(Trigger::Burnout, "ballast", 0.1, 0.5),
            MassShift::new(
                Trigger::BurnoutPlusDelay { delay_s: Some(2.0) },
                "ballast",
                0.1,
                0.5,
            ),
        ])
        .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let burnout = sim.model().burnout_s;
    let burnout_event = flight.event(EventKind::Burnout).unwrap().time_s;
    eprintln!("burnout {burnout} s; shifts at {:?}", flight.shift_starts_s);
    assert_eq!(burnout_event, burnout);
    assert_eq!(
        flight.shift_starts_s,
        vec![Some(burnout), Some(burnout + 2.0)]
    );
    // Both moved the ballast (the motor out at burnout, the first just starting): 0.2 m aft
    // in all once the second has ended.
    let before = sim.mass_properties(&flight, burnout).cg_m.x;
    let after = sim.mass_properties(&flight, burnout + 3.0).cg_m.x;
    let m = sim.mass_properties(&flight, burnout + 3.0).mass_kg;
    assert!(((after - before) - 0.2 * 0.2 / m).abs() < 1e-12);
}

#[test]
fn the_instant_memo_gives_the_model_s_instant_and_never_one_held_for_other_starts() {
    use crate::flight::model::InstantMemo;
    let sim = reference::simulation()
        .with_shifts(vec![ballast_shift(1.0)])
        .unwrap();
    let model = sim.model();
    let idle = [f64::INFINITY; MAX_SHIFTS];
    let mut moving = idle;
    moving[0] = 1.0;
    let mut memo = InstantMemo::default();
    // Repeated times (a step's last two stages), the burn, the shift, and after both; the
    // starts change (counted by the second argument) while the time stays the same.
    let calls = [
        (idle, 0, 0.4),
        (idle, 0, 0.4),
        (idle, 0, 1.2),
        (moving, 1, 1.2),
        (moving, 1, 1.2),
        (moving, 1, 1.6),
        (moving, 1, 9.0),
        (idle, 2, 1.6),
    ];
    for (starts, changes, t) in calls {
        let want = model.instant(&starts, t);
        let (ms, thrust_n) = memo.get(model, &starts, changes, t);
        // Bit for bit: the memo only saves recomputing the same function.
        assert_eq!(*ms, want.mass, "mass state at {t} s, changes {changes}");
        assert_eq!(
            thrust_n.to_bits(),
            want.motor.thrust_n.to_bits(),
            "thrust at {t} s"
        );
    }
    // The case the key exists for: same time, other starts, other mass state.
    let a = model.instant(&idle, 1.6).mass.r_cm.z;
    let b = model.instant(&moving, 1.6).mass.r_cm.z;
    assert!(
        (a - b).abs() > 1e-3,
        "the shift moves the center: {a} against {b}"
    );
}
