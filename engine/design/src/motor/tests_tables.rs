//! Tests of the flight tables: thrust, impulse and propellant against hand calculations,
//! dispersion scales, and the motor's mass properties in closed form.

use super::*;
use nalgebra::{Matrix3, Vector3};

/// A triangle: 0 N at 0 s, 200 N at 1 s, 0 N at 2 s (200 N·s); 50 mm × 400 mm, 0.3 kg of
/// propellant in 0.5 kg.
fn triangle() -> Motor {
    let m = parse_eng("TRI 50 400 P 0.3 0.5 T\n1 200\n2 0\n", "triangle.eng").unwrap();
    m.into_iter().next().unwrap()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

#[test]
fn the_triangle_motor_has_the_hand_calculated_thrust_impulse_and_propellant() {
    let t = MotorTables::from_motor(&triangle()).unwrap();
    assert_eq!(t.total_impulse_ns(), 200.0);
    // Rising: F = 200 t, I = 100 t², m = 0.3 (1 − I/200), ṁ = −0.3 F/200, m̈ = −0.3·200/200.
    let s = t.eval(0.5);
    assert!(close(s.thrust_n, 100.0, 1e-15));
    assert_eq!(s.thrust_rate_n_per_s, 200.0);
    assert!(close(t.impulse_ns(0.5), 25.0, 1e-15));
    assert!(close(s.propellant_kg, 0.2625, 1e-15));
    assert!(close(s.propellant_rate_kg_s, -0.15, 1e-15));
    assert!(close(s.propellant_accel_kg_s2, -0.3, 1e-15));
    // Falling: I(1.5) = 100 + 200·0.5 − 100·0.25 = 175.
    let s = t.eval(1.5);
    assert!(close(s.thrust_n, 100.0, 1e-15));
    assert_eq!(s.thrust_rate_n_per_s, -200.0);
    assert!(close(t.impulse_ns(1.5), 175.0, 1e-15));
    assert!(close(s.propellant_kg, 0.0375, 1e-14));
    assert!(close(s.propellant_accel_kg_s2, 0.3, 1e-15));
    // Before ignition: full and silent; at and after burnout: empty and silent.
    assert_eq!(
        t.eval(-0.1),
        MotorState {
            propellant_kg: 0.3,
            ..MotorState::default()
        }
    );
    assert_eq!(t.eval(2.0), MotorState::default());
    assert_eq!(t.eval(50.0), MotorState::default());
    assert!(t.eval(f64::NAN).thrust_n.is_nan());
}

#[test]
fn the_impulse_at_each_sample_and_segment_midpoint_is_the_trapezoid_sum_for_every_bundled_motor() {
    for (stem, m) in bundled() {
        let tables = MotorTables::new(
            &m,
            &MotorOptions::default()
                .with_impulse_scale(1.1)
                .with_time_scale(0.9),
        )
        .unwrap();
        let (times, thrust) = (m.times_s(), m.thrust_n());
        let mut sum = 0.0;
        for i in 1..times.len() {
            let dt = times[i] - times[i - 1];
            let mid_thrust = 0.5 * (thrust[i - 1] + thrust[i]);
            // Half a segment of a linear ramp: trapezoid from F_{i-1} to the midpoint thrust.
            let at_mid = sum + 0.5 * (thrust[i - 1] + mid_thrust) * 0.5 * dt;
            let t_mid = 0.9 * 0.5 * (times[i - 1] + times[i]);
            assert!(
                close(tables.impulse_ns(t_mid), 1.1 * at_mid, 1e-12),
                "{stem} segment {i}"
            );
            sum += mid_thrust * dt;
            if i + 1 < times.len() {
                assert!(
                    close(tables.impulse_ns(0.9 * times[i]), 1.1 * sum, 1e-12),
                    "{stem} sample {i}"
                );
            }
        }
        // Delivered at the last point = total impulse.
        assert!(
            close(
                tables.impulse_ns(tables.burn_time_s()),
                1.1 * m.total_impulse_ns(),
                1e-12
            ),
            "{stem}"
        );
        let just_before = tables.burn_time_s() * (1.0 - 1e-15);
        assert!(
            close(
                tables.impulse_ns(just_before),
                1.1 * m.total_impulse_ns(),
                1e-12
            ),
            "{stem}"
        );
        assert_eq!(
            tables.eval(tables.burn_time_s()).propellant_kg,
            0.0,
            "{stem}"
        );
        assert!(
            tables.eval(just_before).propellant_kg < 1e-12 * m.propellant_mass_kg,
            "{stem}"
        );
    }
}

#[test]
fn the_propellant_rate_is_the_derivative_of_the_propellant_mass() {
    let m = find("Cesaroni_M1670").unwrap();
    let t = MotorTables::from_motor(&m).unwrap();
    let h = 1e-6;
    let times = t.times_s().to_vec();
    for w in times.windows(2) {
        let mid = 0.5 * (w[0] + w[1]);
        let s = t.eval(mid);
        // m_p is quadratic on a segment: the central difference is exact but for rounding
        // (~3.1 kg · 1e-16 / 1e-6 ≈ 3e-10 kg/s).
        let fd = (t.eval(mid + h).propellant_kg - t.eval(mid - h).propellant_kg) / (2.0 * h);
        assert!(
            (fd - s.propellant_rate_kg_s).abs() < 1e-8,
            "{mid}: {fd} vs {}",
            s.propellant_rate_kg_s
        );
        let fd2 = (t.eval(mid + h).propellant_rate_kg_s - t.eval(mid - h).propellant_rate_kg_s)
            / (2.0 * h);
        assert!(
            (fd2 - s.propellant_accel_kg_s2).abs() < 1e-6 * s.propellant_accel_kg_s2.abs().max(1.0),
            "{mid}"
        );
        let fdf = (t.eval(mid + h).thrust_n - t.eval(mid - h).thrust_n) / (2.0 * h);
        assert!(
            (fdf - s.thrust_rate_n_per_s).abs() < 1e-6 * s.thrust_rate_n_per_s.abs().max(1.0),
            "{mid}"
        );
    }
}

#[test]
fn dispersion_scales_multiply_the_impulse_and_the_burn_time() {
    let m = find("Cesaroni_I175").unwrap();
    let t = MotorTables::new(
        &m,
        &MotorOptions::default()
            .with_impulse_scale(1.2)
            .with_time_scale(0.8),
    )
    .unwrap();
    assert!(close(
        t.total_impulse_ns(),
        1.2 * m.total_impulse_ns(),
        1e-14
    ));
    assert!(close(t.burn_time_s(), 2.0, 1e-15));
    // The peak sample (0.877 s, 195.087 N) moves to 0.7016 s with 1.2/0.8 = 1.5 times the thrust.
    assert!(close(t.eval(0.8 * 0.877).thrust_n, 1.5 * 195.087, 1e-14));
    // Propellant rate still burns m_p0 over the (scaled) impulse.
    let s = t.eval(0.8 * 0.877);
    assert!(close(
        s.propellant_rate_kg_s,
        -m.propellant_mass_kg * 1.5 * 195.087 / (1.2 * m.total_impulse_ns()),
        1e-14
    ));
    assert_eq!(t.eval(2.0).thrust_n, 0.0);
    assert!(t.eval(1.99).thrust_n > 0.0);
    let err = MotorTables::new(&m, &MotorOptions::default().with_time_scale(0.0))
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "motor Cesaroni_I175, option time_scale = 0: must be finite and greater than zero"
    );
    let err = MotorTables::new(&m, &MotorOptions::default().with_propellant_mass_kg(-1.0))
        .unwrap_err()
        .to_string();
    assert_eq!(
        err,
        "motor Cesaroni_I175, option propellant_mass_kg = -1: must be finite and not negative"
    );
}

#[test]
fn the_motor_at_ignition_is_a_shell_casing_and_a_solid_propellant_cylinder_at_mid_length() {
    let m = find("Cesaroni_I175").unwrap();
    let t = MotorTables::from_motor(&m).unwrap();
    let p = t.mass_props(0.0, 1.5);
    // 38 mm × 245 mm: r² = 0.019², casing 0.4375 − 0.2289 = 0.2086 kg, propellant 0.2289 kg.
    let (r2, l2, dry, prop) = (0.019f64 * 0.019, 0.245f64 * 0.245, 0.2086, 0.2289);
    let axial = dry * r2 + prop * r2 / 2.0;
    let transverse = dry * (r2 / 2.0 + l2 / 12.0) + prop * (3.0 * r2 + l2) / 12.0;
    assert!(close(p.mass_kg, 0.4375, 1e-15));
    assert_eq!(p.cg_m, Vector3::new(1.5 - 0.1225, 0.0, 0.0));
    assert!(close(p.inertia_cg[(0, 0)], axial, 1e-12));
    assert!(close(p.inertia_cg[(1, 1)], transverse, 1e-12));
    assert!(close(p.inertia_cg[(2, 2)], transverse, 1e-12));
    assert_eq!(
        p.inertia_cg - Matrix3::from_diagonal(&p.inertia_cg.diagonal()),
        Matrix3::zeros()
    );
}

#[test]
fn a_cluster_of_three_is_three_times_the_thrust_and_mass_with_each_motor_s_inertia_carried_to_the_axis(
) {
    // Three I175s 30 mm off the axis at 90°, 210° and 330° (OpenRocket's 3-ring turned):
    // hand calculation of the parallel axes, Σ m J(d_i) with J(d) = |d|² 1 − d dᵀ.
    let m = find("Cesaroni_I175").unwrap();
    let one = MotorTables::from_motor(&m).unwrap();
    let d = 0.03;
    let at = |deg: f64| {
        let a = deg.to_radians();
        [d * a.cos(), d * a.sin()]
    };
    let offsets = [at(90.0), at(210.0), at(330.0)];
    let three = one.clone().clustered(&offsets);
    assert_eq!(three.motors(), 3);
    assert!(close(
        three.total_impulse_ns(),
        3.0 * one.total_impulse_ns(),
        1e-15
    ));
    assert_eq!(three.burn_time_s(), one.burn_time_s());
    for t in [0.05, 0.7, 1.9, 2.2] {
        let (a, b) = (three.eval(t), one.eval(t));
        assert!(close(a.thrust_n, 3.0 * b.thrust_n, 1e-15), "{t}");
        assert!(close(a.propellant_kg, 3.0 * b.propellant_kg, 1e-14), "{t}");
        assert!(close(
            a.propellant_rate_kg_s,
            3.0 * b.propellant_rate_kg_s,
            1e-14
        ));
        assert!(close(three.impulse_ns(t), 3.0 * one.impulse_ns(t), 1e-15));
    }
    // At ignition: Σ |d_i|² = 3 d² about the axis; across it Σ y_i² = Σ z_i² = 3 d²/2 (a
    // symmetric ring), and Σ y_i z_i = 0.
    let (a, b) = (three.mass_props(0.0, 1.5), one.mass_props(0.0, 1.5));
    let m0 = b.mass_kg;
    assert!(close(a.mass_kg, 3.0 * m0, 1e-15));
    assert_eq!(a.cg_m, b.cg_m);
    let i = |p: &crate::mass::MassProps, r: usize, c: usize| p.inertia_cg[(r, c)];
    assert!(close(
        i(&a, 0, 0),
        3.0 * i(&b, 0, 0) + m0 * 3.0 * d * d,
        1e-12
    ));
    assert!(close(
        i(&a, 1, 1),
        3.0 * i(&b, 1, 1) + m0 * 1.5 * d * d,
        1e-12
    ));
    assert!(close(
        i(&a, 2, 2),
        3.0 * i(&b, 2, 2) + m0 * 1.5 * d * d,
        1e-12
    ));
    assert!(i(&a, 1, 2).abs() < 1e-15 * i(&a, 1, 1), "{}", i(&a, 1, 2));
    // At burnout the casings alone, each carried to the axis too.
    let (a, b) = (three.mass_props(9.0, 1.5), one.mass_props(9.0, 1.5));
    assert!(close(
        a.axial_inertia(),
        3.0 * b.axial_inertia() + b.mass_kg * 3.0 * d * d,
        1e-12
    ));
    // The propellant's inertia stays proportional to its mass, so the rates follow it.
    let s = three.eval(0.7);
    let rates = three.mass_rates(&s);
    let prop_inertia =
        three.mass_props_of(&s, 1.5).inertia_cg - three.mass_props(9.0, 1.5).inertia_cg;
    assert!(
        (rates.inertia_rate_kg_m2_s - prop_inertia * (s.propellant_rate_kg_s / s.propellant_kg))
            .norm()
            < 1e-12 * rates.inertia_rate_kg_m2_s.norm()
    );
    // One motor on the axis is the motor itself, bit for bit.
    assert_eq!(one.clone().clustered(&[[0.0, 0.0]]), one);
    assert_eq!(one.clone().clustered(&[]), one);
}

#[test]
fn the_motor_at_burnout_is_its_casing_alone() {
    let m = find("Cesaroni_I175").unwrap();
    let t = MotorTables::from_motor(&m).unwrap();
    for time in [2.5, 3.0, 100.0] {
        let p = t.mass_props(time, 0.8);
        assert!(close(p.mass_kg, 0.2086, 1e-12));
        assert!(close(p.cg_m.x, 0.8 - 0.1225, 1e-15));
        assert!(close(p.axial_inertia(), 0.2086 * 0.019 * 0.019, 1e-12));
        assert!(close(
            p.transverse_inertia(),
            0.2086 * (0.019 * 0.019 / 2.0 + 0.245 * 0.245 / 12.0),
            1e-12
        ));
    }
}

#[test]
fn a_casing_and_propellant_placed_as_rocketpy_s_solid_motor_places_them_sum_by_parallel_axes() {
    // The triangle (400 mm, 50 mm) with its casing 0.3 m and its propellant 0.1 m forward of
    // the nozzle, the casing's inertia (0.001 axial, 0.02 transverse), aft end at 1.0 m.
    let t = MotorTables::new(
        &triangle(),
        &MotorOptions {
            dry_center_from_nozzle_m: Some(0.3),
            propellant_center_from_nozzle_m: Some(0.1),
            dry_inertia_kg_m2: Some([0.001, 0.02]),
            ..MotorOptions::default()
        },
    )
    .unwrap();
    // At 1 s half the impulse is out: 0.15 kg of propellant left (0.3 kg full, dry 0.2 kg).
    let p = t.mass_props(1.0, 1.0);
    let (dry, prop) = (0.2, 0.15);
    let (x_dry, x_prop) = (0.7, 0.9);
    let x = (dry * x_dry + prop * x_prop) / (dry + prop);
    assert!(close(p.mass_kg, dry + prop, 1e-15));
    assert!(close(p.cg_m.x, x, 1e-15), "{} against {x}", p.cg_m.x);
    // Propellant: a solid cylinder of the motor's size, m (3r² + L²)/12 across, m r²/2 along.
    let (r2, l2) = (0.025f64 * 0.025, 0.4f64 * 0.4);
    let transverse = 0.02
        + dry * (x_dry - x) * (x_dry - x)
        + prop * (3.0 * r2 + l2) / 12.0
        + prop * (x_prop - x) * (x_prop - x);
    assert!(close(p.transverse_inertia(), transverse, 1e-14));
    assert!(close(p.axial_inertia(), 0.001 + prop * r2 / 2.0, 1e-14));
    // Burnt out: the casing alone, where it was put, with its own inertia.
    let end = t.mass_props(2.0, 1.0);
    assert_eq!((end.mass_kg, end.cg_m.x), (0.2, 0.7));
    assert_eq!(
        (end.axial_inertia(), end.transverse_inertia()),
        (0.001, 0.02)
    );
    assert_eq!(t.casing_props(1.0).cg_m.x, 0.7);
    assert_eq!(t.propellant_props(1.0).cg_m.x, 0.9);
}

#[test]
fn a_center_outside_the_motor_or_an_impossible_casing_inertia_is_refused_naming_it() {
    let refused = |o: MotorOptions| match MotorTables::new(&triangle(), &o) {
        Err(MotorError::InvalidOption { field, rule, .. }) => (field.as_str(), rule),
        other => panic!("accepted: {other:?}"),
    };
    let (field, rule) = refused(MotorOptions {
        dry_center_from_nozzle_m: Some(0.41),
        ..MotorOptions::default()
    });
    assert_eq!(field, "dry_center_from_nozzle_m");
    assert!(rule.contains("within the motor"), "{rule}");
    let (field, _) = refused(MotorOptions {
        propellant_center_from_nozzle_m: Some(-0.01),
        ..MotorOptions::default()
    });
    assert_eq!(field, "propellant_center_from_nozzle_m");
    // Axial more than twice the transverse: no body round its axis (a thin ring has twice).
    let (field, rule) = refused(MotorOptions {
        dry_inertia_kg_m2: Some([0.05, 0.02]),
        ..MotorOptions::default()
    });
    assert_eq!(field, "dry_inertia_kg_m2 (axial)");
    assert!(rule.contains("at most twice"), "{rule}");
    let (field, _) = refused(MotorOptions {
        dry_inertia_kg_m2: Some([0.001, f64::NAN]),
        ..MotorOptions::default()
    });
    assert_eq!(field, "dry_inertia_kg_m2 (transverse)");
    // The ends of the motor and a ring's inertia are allowed.
    let ends = MotorOptions {
        dry_center_from_nozzle_m: Some(0.0),
        propellant_center_from_nozzle_m: Some(0.4),
        dry_inertia_kg_m2: Some([0.04, 0.02]),
        ..MotorOptions::default()
    };
    MotorTables::new(&triangle(), &ends).expect("allowed");
}

#[test]
fn mass_overrides_replace_the_file_masses() {
    let m = triangle();
    let t = MotorTables::new(
        &m,
        &MotorOptions::default()
            .with_propellant_mass_kg(0.25)
            .with_dry_mass_kg(0.4),
    )
    .unwrap();
    assert!(close(t.mass_props(0.0, 1.0).mass_kg, 0.65, 1e-15));
    assert!(close(t.mass_props(2.0, 1.0).mass_kg, 0.4, 1e-15));
    // Half the impulse (100 N·s at 1 s) has burned half the propellant.
    assert!(close(t.eval(1.0).propellant_kg, 0.125, 1e-15));
    assert!(close(
        t.eval(1.0).propellant_rate_kg_s,
        -0.25 * 200.0 / 200.0,
        1e-15
    ));
}

#[test]
fn the_mass_and_inertia_rates_are_the_derivatives_of_the_mass_properties() {
    let m = find("AeroTech_J570W").unwrap();
    let t = MotorTables::from_motor(&m).unwrap();
    let h = 1e-6;
    for time in [0.02, 0.5, 1.3, 1.95] {
        let rates = t.mass_rates(&t.eval(time));
        let (a, b) = (t.mass_props(time + h, 1.0), t.mass_props(time - h, 1.0));
        assert!(
            ((a.mass_kg - b.mass_kg) / (2.0 * h) - rates.mass_rate_kg_s).abs() < 1e-8,
            "{time}"
        );
        let d_inertia = (a.inertia_cg - b.inertia_cg) / (2.0 * h);
        assert!(
            (d_inertia - rates.inertia_rate_kg_m2_s).abs().max() < 1e-9,
            "{time}"
        );
        assert_eq!(a.cg_m, b.cg_m);
        let d2 = (t.mass_rates(&t.eval(time + h)).inertia_rate_kg_m2_s
            - t.mass_rates(&t.eval(time - h)).inertia_rate_kg_m2_s)
            / (2.0 * h);
        assert!(
            (d2 - rates.inertia_accel_kg_m2_s2).abs().max() < 1e-6,
            "{time}"
        );
    }
}

#[test]
fn a_chamber_makes_the_propellant_a_solid_cylinder_of_its_size_as_rocketpy_s_generic_motor() {
    // The triangle (400 × 50 mm, 0.3 kg of propellant) with a 20 × 300 mm chamber: RocketPy's
    // GenericMotor propellant_I_11 = m (3 r² + h²)/12, propellant_I_33 = m r²/2.
    let t = MotorTables::new(
        &triangle(),
        &MotorOptions {
            chamber_m: Some([0.02, 0.3]),
            ..MotorOptions::default()
        },
    )
    .unwrap();
    let p = t.propellant_props(1.0);
    let (m, r, h) = (0.3, 0.02f64, 0.3f64);
    assert!(close(
        p.transverse_inertia(),
        m * (3.0 * r * r + h * h) / 12.0,
        1e-14
    ));
    assert!(close(p.axial_inertia(), m * r * r / 2.0, 1e-14));
    // Half burnt, half the inertia: the shape stays, the mass halves.
    let half = t.mass_props(1.0, 1.0).inertia_cg - t.casing_props(1.0).inertia_cg;
    assert!(close(half[(1, 1)], 0.5 * p.transverse_inertia(), 1e-12));
    let refused = |c: [f64; 2]| match MotorTables::new(
        &triangle(),
        &MotorOptions {
            chamber_m: Some(c),
            ..MotorOptions::default()
        },
    ) {
        Err(MotorError::InvalidOption { field, .. }) => field.as_str(),
        other => panic!("accepted: {other:?}"),
    };
    assert_eq!(refused([0.03, 0.3]), "chamber_m (radius)");
    assert_eq!(refused([0.02, 0.41]), "chamber_m (height)");
    assert_eq!(refused([f64::NAN, 0.3]), "chamber_m (radius)");
}

#[test]
fn a_look_up_started_from_any_segment_gives_the_searched_state_bit_for_bit() {
    let m = find("Cesaroni_M1670").unwrap();
    let t = MotorTables::from_motor(&m).unwrap();
    let n = t.times_s().len();
    let bits = |s: MotorState| {
        [
            s.thrust_n,
            s.thrust_rate_n_per_s,
            s.propellant_kg,
            s.propellant_rate_kg_s,
            s.propellant_accel_kg_s2,
        ]
        .map(f64::to_bits)
    };
    // Every knot and points between, before ignition and past burnout, from every hint
    // (right, wrong, out of range).
    let mut times = vec![-1.0, 0.0, t.burn_time_s(), t.burn_time_s() + 1.0, f64::NAN];
    for w in t.times_s().windows(2) {
        times.extend([w[0], 0.25 * (3.0 * w[0] + w[1]), 0.5 * (w[0] + w[1]), w[1]]);
    }
    for &time in &times {
        for start in 0..n + 2 {
            let mut hint = start;
            assert_eq!(
                bits(t.eval_hinted(time, &mut hint)),
                bits(t.eval(time)),
                "{time} from {start}"
            );
        }
    }
    // Successive look-ups through the burn, the hint carried along.
    let mut hint = 0;
    for i in 0..=4000 {
        let time = t.burn_time_s() * f64::from(i) / 4000.0;
        assert_eq!(
            bits(t.eval_hinted(time, &mut hint)),
            bits(t.eval(time)),
            "{time}"
        );
    }
}
