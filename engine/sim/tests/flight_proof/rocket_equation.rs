//! A vertical, drag-free climb on a constant-thrust motor against Tsiolkovsky's rocket
//! equation with gravity loss, `Δv = v_e ln(m_a/m_b) − g (t_b − t_a)`, `v_e = I_total/m_prop`
//! (the propellant burns in proportion to the impulse delivered).
//!
//! What RocketPy's mass-flow terms do here. With ω = 0 the rigid-body equation gives O's
//! acceleration `a_O = (F + m g − m r″ − 2ṁ r′ + m̈ (r_noz − r))/m`. The propellant's center
//! `x_p` is fixed, so `m r = S_fixed + m_p x_p` gives `m r′ = ṁ (x_p − r)` and
//! `m r″ = m̈ (x_p − r) − 2ṁ r′`; the three terms add up to `m̈ (r_noz − x_p)`. Where the
//! thrust is constant (m̈ = 0) they cancel exactly and every point of the airframe follows
//! the rocket equation. Where the thrust changes, m̈ ≠ 0 and they leave an axial force
//! `m̈ (r_noz − x_p)` (the momentum of the gas between the grain and the nozzle, RocketPy's
//! model): it integrates to a velocity change `(r_noz − x_p)·∫ m̈/m dt` across a thrust
//! ramp, whatever the ramp's length. The rail phase (one degree of freedom) has no such
//! term. The test checks both: the pure rocket equation at the end of the constant-thrust
//! segment, and the rocket equation plus that closed-form term at burnout, after the ramp.

use crate::common::*;
use hpr_design::motor::Motor;
use hpr_design::Design;
use hpr_sim::events::EventKind;
use hpr_sim::flight::{Phase, Rail, Simulation};
use serde_json::Value;

/// Thrust, N, and the ramps' length, s, of the test motor; its flat top ends at `T_FLAT`.
const F: f64 = 200.0;
const RAMP: f64 = 0.01;
const T_FLAT: f64 = 1.0;
const T_BURNOUT: f64 = 1.01;
const PROPELLANT_KG: f64 = 0.2;

/// A plugged 38 × 250 mm motor: 200 N from 0.01 s to 1.0 s, 10 ms ramps, 0.2 kg of
/// propellant in 0.4 kg, written to a file and read back as any motor is.
fn constant_thrust_motor() -> Motor {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("constant_thrust.eng");
    let text = format!(
        "; constant-thrust test motor\nT200 38 250 P {PROPELLANT_KG} 0.4 Test\n{RAMP} {F}\n{T_FLAT} {F}\n{T_BURNOUT} 0\n"
    );
    std::fs::write(&path, text).expect("temp file");
    Motor::from_file(&path).expect("the test motor parses")
}

/// The example rocket without its rail buttons (their mass sits off the axis and would
/// tip the thrust line off the center of mass).
fn on_axis_rocket() -> Design {
    let path = repo("validation/designs/example-minimal.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let body = v.pointer_mut("/stages/0/components/1/children").unwrap();
    body.as_array_mut()
        .unwrap()
        .retain(|c| c["type"] != "rail_button");
    Design::from_json_str(&v.to_string(), Some(&path)).expect("valid")
}

#[test]
fn a_vertical_constant_thrust_climb_in_a_vacuum_follows_the_rocket_equation() {
    let motor = constant_thrust_motor();
    assert_eq!(motor.total_impulse_ns(), 200.0);
    let v_e = motor.total_impulse_ns() / PROPELLANT_KG;
    let rail = Rail {
        length_m: 2.0,
        inclination_deg: 90.0,
        heading_deg: 0.0,
    };
    let sim = Simulation::new(on_axis_rocket(), motor, vacuum(G0), rail)
        .and_then(|s| s.with_options(options(TIGHT, 3.0)))
        .expect("set up");
    let f = sim.run(&mut ()).expect("flies");
    let t_a = f.metrics.liftoff_time_s.expect("lifts off");
    let t_exit = f.metrics.rail_exit_time_s.expect("leaves the rail");
    let m_a = mass_at(&sim, t_a).mass_kg;
    assert!(
        t_a < RAMP && t_exit > RAMP,
        "liftoff {t_a} s and rail exit {t_exit} s must straddle the end of the first ramp"
    );

    // End of the flat top: the rail and the free flight with m̈ = 0 only.
    let at = |t: f64| {
        f.samples
            .iter()
            .find(|s| s.t_s == t && s.phase == Phase::Free)
            .unwrap_or_else(|| panic!("no sample at the stop time {t}"))
    };
    let s1 = at(T_FLAT);
    let ms1 = mass_at(&sim, T_FLAT);
    // O's velocity: the center's less the center's drift through the airframe (ω = 0).
    let v_o1 = s1.velocity_m_s[2] - (rotation(s1) * ms1.r_cm_rate).z;
    let expected1 = v_e * (m_a / ms1.mass_kg).ln() - G0 * (T_FLAT - t_a);
    let err1 = v_o1 - expected1;

    // The mass-flow terms mid-burn: −m r″ − 2ṁ r′ + m̈ (r_noz − r), axial.
    let noz = sim.model().nozzle.r_noz;
    let x_p = sim.model().mass.propellant_cg_b;
    let mid = mass_at(&sim, 0.5);
    let flow = -mid.r_cm_accel * mid.mass_kg - mid.r_cm_rate * (2.0 * mid.mass_rate)
        + (noz - mid.r_cm) * mid.mass_accel;

    // Burnout, after the second ramp: plus (r_noz − x_p)·∫ m̈/m dt, with m̈ constant over
    // the ramp and m = m_b + ½ m̈ (t_b − t)², ∫₀^ε m̈ ds/(m_b + ½ m̈ s²)
    // = √(2 m̈/m_b) atan(ε √(m̈/(2 m_b))).
    let sb = at(T_BURNOUT);
    let m_b = mass_at(&sim, T_BURNOUT).mass_kg;
    let m_dd = PROPELLANT_KG / 200.0 * F / RAMP;
    let ramp_integral = (2.0 * m_dd / m_b).sqrt() * (RAMP * (m_dd / (2.0 * m_b)).sqrt()).atan();
    let lever = (noz - x_p).z;
    let rocket_b = v_e * (m_a / m_b).ln() - G0 * (T_BURNOUT - t_a);
    let expected_b = rocket_b + lever * ramp_integral;
    let err_b = sb.velocity_m_s[2] - expected_b;
    let burnout = f.event(EventKind::Burnout).expect("burnout event");

    eprintln!(
        "rocket equation: v_e {v_e} m/s, liftoff {t_a:.6} s at {m_a:.6} kg, rail exit {t_exit:.4} s; \
         at {T_FLAT} s v_O = {v_o1:.9} m/s, expected {expected1:.9} (error {err1:.2e}); \
         mass-flow terms mid-burn (axial) {:.2e} N; at burnout v = {:.9} m/s, rocket equation \
         {rocket_b:.9}, the ramp's m̈ (r_noz − x_p) term {:.6} m/s (lever {lever:.4} m), \
         error {err_b:.2e}; lateral speed {:.2e} m/s",
        flow.z,
        sb.velocity_m_s[2],
        lever * ramp_integral,
        sb.velocity_m_s[0].hypot(sb.velocity_m_s[1]),
    );
    assert_eq!(burnout.time_s, T_BURNOUT);
    assert!(
        (lever + 0.125).abs() < 1e-12,
        "nozzle 125 mm aft of the grain's center"
    );
    // Rounding in the mass-flow terms (products of order 1e-1 N): 1e-12 N.
    assert!(flow.norm() <= 1e-12, "mass-flow terms with m̈ = 0: {flow}");
    // Δv ≈ 213 m/s integrated at rtol 1e-12.
    assert!(err1.abs() <= 1e-8, "flat top: {err1} m/s");
    assert!(err_b.abs() <= 1e-8, "burnout: {err_b} m/s");
    // A vertical climb stays vertical.
    assert!(sb.velocity_m_s[0].hypot(sb.velocity_m_s[1]) <= 1e-9);
}
