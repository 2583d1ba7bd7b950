//! Clusters of motors: `n` motors in the tubes of a clustered mount, their centre on the axis.
//! Two motors in one place are exactly one motor of twice the thrust and mass (checked
//! against such a motor written out as a file); a ring of them adds each motor's inertia
//! about the rocket's axis and spreads the nozzles' mass flow.

use crate::common::*;
use hpr_design::mass::point_inertia;
use hpr_design::motor::Motor;
use hpr_design::Design;
use nalgebra::{Matrix3, Vector3};
use serde_json::{json, Value};

/// The example design with its motor mount's `cluster` (and the mount weighing 40 g, as
/// a cluster's `mass_kg` is the whole set's), tubes allowed to overlap as OpenRocket allows.
fn example_with_cluster(cluster: Option<Value>) -> Design {
    let text = std::fs::read_to_string(repo("validation/designs/example-minimal.json")).unwrap();
    let mut v: Value = serde_json::from_str(&text).unwrap();
    v["geometry_checks"] = json!("openrocket");
    let mount = v["stages"][0]["components"][1]["children"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|c| c["id"] == "mmt")
        .unwrap();
    mount.as_object_mut().unwrap().remove("material");
    mount["mass_kg"] = json!(0.04);
    if let Some(c) = cluster {
        mount["cluster"] = c;
    }
    Design::from_json_str(&v.to_string(), None).unwrap()
}

/// The I175 written out again with every thrust sample and both masses doubled (exact in
/// binary, and the shortest decimal of a double reads back as that double).
fn doubled_i175() -> Motor {
    let text = std::fs::read_to_string(repo("engine/design/motors/Cesaroni_I175.eng")).unwrap();
    let twice = |s: &str| format!("{}", 2.0 * s.parse::<f64>().unwrap());
    let mut out = String::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let line = if line.starts_with(';') || words.is_empty() {
            line.to_owned()
        } else if words.len() == 7 {
            let mut w: Vec<String> = words.iter().map(|w| w.to_string()).collect();
            w[4] = twice(words[4]);
            w[5] = twice(words[5]);
            w.join(" ")
        } else {
            format!("{} {}", words[0], twice(words[1]))
        };
        out.push_str(&line);
        out.push('\n');
    }
    Motor::parse(out.as_bytes(), "Doubled_I175.eng").unwrap()
}

#[test]
fn two_motors_in_one_place_fly_exactly_as_one_motor_of_twice_the_thrust_and_mass() {
    let pair = still_air(
        example_with_cluster(Some(json!([[0.0, 0.0], [0.0, 0.0]]))),
        motor("Cesaroni_I175"),
    );
    let one = still_air(example_with_cluster(None), doubled_i175());
    assert_eq!(pair.model().motor.motors(), 2);
    assert_eq!(
        pair.model().motor.total_impulse_ns(),
        one.model().motor.total_impulse_ns()
    );
    let (a, b) = (pair.run(&mut ()).unwrap(), one.run(&mut ()).unwrap());
    let (a, b) = (a.metrics, b.metrics);
    // The two set-ups differ only in rounding (the mount's two coincident tubes are scaled
    // to its 40 g, the one tube too), so the flights agree to rounding: 1e-9 relative.
    let pairs = [
        (a.apogee_m.unwrap(), b.apogee_m.unwrap()),
        (a.apogee_time_s.unwrap(), b.apogee_time_s.unwrap()),
        (a.max_speed_m_s, b.max_speed_m_s),
        (a.max_accel_m_s2, b.max_accel_m_s2),
        (
            a.rail_exit_speed_m_s.unwrap(),
            b.rail_exit_speed_m_s.unwrap(),
        ),
        (
            a.static_margin_liftoff_cal.unwrap(),
            b.static_margin_liftoff_cal.unwrap(),
        ),
        (a.landing_time_s.unwrap(), b.landing_time_s.unwrap()),
    ];
    for (i, (x, y)) in pairs.into_iter().enumerate() {
        assert!(
            (x - y).abs() <= 1e-9 * y.abs(),
            "metric {i}: {x} against {y}"
        );
    }
    // And the pair really is twice one I175: higher and faster than the single motor.
    let single = still_air(example_with_cluster(None), motor("Cesaroni_I175"))
        .run(&mut ())
        .unwrap()
        .metrics;
    assert!(a.max_speed_m_s > 1.3 * single.max_speed_m_s);
}

#[test]
fn a_ring_of_motors_adds_each_motor_s_inertia_about_the_axis_and_spreads_the_nozzles() {
    // Three I175s 25 mm off the axis at 90°, 210° and 330°, against the same three on it.
    let d = 0.025;
    let at = |deg: f64| {
        let a = deg.to_radians();
        json!([d * a.cos(), d * a.sin()])
    };
    let ring = still_air(
        example_with_cluster(Some(json!([at(90.0), at(210.0), at(330.0)]))),
        motor("Cesaroni_I175"),
    );
    let stack = still_air(
        example_with_cluster(Some(json!([[0.0, 0.0], [0.0, 0.0], [0.0, 0.0]]))),
        motor("Cesaroni_I175"),
    );
    // The motors' mass at t: Σ m J(d_i) = m (3d² about the axis, 3d²/2 across it), body
    // axes (b3 the axis). The mount's three tubes moved too: they add their own share,
    // 40 g × the same mean.
    let spread = Matrix3::from_diagonal(&Vector3::new(1.5 * d * d, 1.5 * d * d, 3.0 * d * d));
    for t in [0.0, 0.5, 1.2, 5.0] {
        let motors_kg = ring.model().motor.mass_props(t, 1.0).mass_kg;
        let (a, b) = (mass_at(&ring, t), mass_at(&stack, t));
        assert!((a.mass_kg - b.mass_kg).abs() <= 1e-15 * b.mass_kg);
        let want = spread * ((motors_kg + 0.04) / 3.0);
        let got = a.inertia_o - b.inertia_o;
        assert!(
            (got - want).norm() <= 1e-12 * want.norm(),
            "t {t}: {got} against {want}"
        );
        // The inertia's rate: the burning propellant's share of the spread.
        let rate = a.inertia_o_rate - b.inertia_o_rate;
        let want_rate = spread * (b.mass_rate / 3.0);
        assert!(
            (rate - want_rate).norm() <= 1e-12 * want_rate.norm().max(1e-30),
            "t {t}: {rate} against {want_rate}"
        );
    }
    // The nozzles' gyration tensor gains the mean of J(d_i): d² about the axis, d²/2 across.
    let s = ring.model().nozzle.s_noz - stack.model().nozzle.s_noz;
    let mean = Matrix3::from_diagonal(&Vector3::new(0.5 * d * d, 0.5 * d * d, d * d));
    assert!((s - mean).norm() <= 1e-15, "{s}");
    assert_eq!(
        point_inertia(&Vector3::new(0.0, 0.0, d))[(0, 0)],
        d * d,
        "J(d) is |d|² − d dᵀ"
    );
    // The ring flies as the stack does in still air, a little slower to pitch: same apogee
    // to 0.1 %.
    let (a, b) = (ring.run(&mut ()).unwrap(), stack.run(&mut ()).unwrap());
    let (a, b) = (a.metrics.apogee_m.unwrap(), b.metrics.apogee_m.unwrap());
    assert!((a - b).abs() <= 1e-3 * b, "{a} against {b}");
}

#[test]
fn a_ring_of_motors_flies_in_the_batch_bit_for_bit_as_its_single_flight() {
    let d = 0.025;
    let at = |deg: f64| {
        let a = deg.to_radians();
        json!([d * a.cos(), d * a.sin()])
    };
    let sim = still_air(
        example_with_cluster(Some(json!([at(90.0), at(210.0), at(330.0)]))),
        motor("Cesaroni_I175"),
    );
    batch_flies_as_singles(sim);
}
