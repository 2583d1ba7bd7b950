//! BATES grains against RocketPy 1.13's `SolidMotor` (the Calisto's M1670, whose samples
//! `validation/rocketpy/calisto.py` recorded in `calisto_reference.json`), and the inertia's
//! derivatives against finite differences.

use super::*;
use serde_json::Value;

/// RocketPy's Calisto M1670: five grains 120 mm long, 33 mm outer and 15 mm bore radius,
/// 5 mm apart, 1815 kg/m³.
fn m1670_grains() -> Grains {
    Grains {
        count: 5,
        outer_radius_m: 0.033,
        inner_radius_m: 0.015,
        height_m: 0.12,
        separation_m: 0.005,
        density_kg_m3: 1815.0,
    }
}

fn reference() -> Value {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../validation/rocketpy/calisto_reference.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn the_grains_hold_rocketpy_s_propellant_and_burn_to_its_bore_height_and_inertia() {
    let r = reference();
    let g = m1670_grains();
    let full = r["outputs"]["motor_propellant_initial_mass_kg"]
        .as_f64()
        .unwrap();
    assert!(
        (g.mass_kg() - full).abs() <= 1e-14 * full,
        "{} against {full}",
        g.mass_kg()
    );
    // RocketPy integrates the bore and height from the mass flow (LSODA); the closed form
    // meets its samples within 6e-12 m but near burnout, where its integration is 3.6e-9 m
    // off (t = 3.5 s, 28 g left).
    for s in r["facts"]["motor_samples"].as_array().unwrap() {
        let f = |k: &str| s[k].as_f64().unwrap();
        let m = f("propellant_mass_kg");
        let bore = g.bore_m(m);
        let height = 0.12 - 2.0 * (bore - 0.015);
        let i = g.inertia(m);
        for (what, got, want, tol) in [
            ("bore", bore, f("grain_inner_radius_m"), 5e-9),
            ("height", height, f("grain_height_m"), 1e-8),
            (
                "I_11",
                i.inertia_kg_m2[1],
                f("propellant_I_11_about_propellant_com_kg_m2"),
                1e-9,
            ),
            ("I_33", i.inertia_kg_m2[0], f("propellant_I_33_kg_m2"), 3e-9),
        ] {
            assert!(
                (got - want).abs() <= tol,
                "t = {} s: {what} {got} against RocketPy's {want}",
                f("time_s")
            );
        }
    }
    // Full, the bore is the grains' own; empty, the wall has burnt through (R = 33 mm comes
    // before the ends meet at (h₀ + 2 r₀)/2 = 75 mm).
    assert_eq!(g.bore_m(g.mass_kg()), 0.015);
    assert_eq!(g.bore_m(0.0), 0.033);
}

#[test]
fn the_grains_inertia_rates_are_the_derivatives_of_their_inertia_in_the_mass() {
    let g = m1670_grains();
    for m in [2.9, 2.0, 1.0, 0.3, 0.05] {
        let dm = 1e-4;
        let (lo, mid, hi) = (g.inertia(m - dm), g.inertia(m), g.inertia(m + dm));
        for k in 0..2 {
            let d1 = (hi.inertia_kg_m2[k] - lo.inertia_kg_m2[k]) / (2.0 * dm);
            let d2 = (hi.inertia_kg_m2[k] - 2.0 * mid.inertia_kg_m2[k] + lo.inertia_kg_m2[k])
                / (dm * dm);
            // Central differences: error O(dm²) for the first (1e-8 relative here), and
            // rounding 1e-16 I / dm² ≈ 1e-10 for the second.
            assert!(
                (d1 - mid.per_kg_m2[k]).abs() <= 1e-7 * mid.per_kg_m2[k].abs(),
                "m {m}, {k}: {d1} against {}",
                mid.per_kg_m2[k]
            );
            assert!(
                (d2 - mid.per_kg2_m2[k]).abs() <= 1e-4 * mid.per_kg2_m2[k].abs() + 1e-8,
                "m {m}, {k}: {d2} against {}",
                mid.per_kg2_m2[k]
            );
        }
    }
    // Three motors sharing 6 kg: three times one motor's inertia with 2 kg, its slope, a
    // third of its curvature.
    let (three, one) = (g.cluster_inertia(3, 6.0), g.inertia(2.0));
    for k in 0..2 {
        assert_eq!(three.inertia_kg_m2[k], 3.0 * one.inertia_kg_m2[k]);
        assert_eq!(three.per_kg_m2[k], one.per_kg_m2[k]);
        assert_eq!(three.per_kg2_m2[k], one.per_kg2_m2[k] / 3.0);
    }
}

#[test]
fn grains_that_break_a_rule_or_do_not_fit_the_motor_are_refused_naming_the_field() {
    let m = find("Cesaroni_M1670").unwrap();
    let refused = |g: Grains, extra: MotorOptions| match MotorTables::new(
        &m,
        &MotorOptions {
            grains: Some(g),
            ..extra
        },
    ) {
        Err(MotorError::InvalidOption { field, rule, .. }) => (field.as_str(), rule),
        other => panic!("accepted: {other:?}"),
    };
    let ok = m1670_grains();
    let cases = [
        (Grains { count: 0, ..ok }, "grains.count"),
        (
            Grains {
                inner_radius_m: 0.033,
                ..ok
            },
            "grains.inner_radius_m",
        ),
        (
            Grains {
                height_m: -0.1,
                ..ok
            },
            "grains.height_m",
        ),
        (
            Grains {
                separation_m: f64::NAN,
                ..ok
            },
            "grains.separation_m",
        ),
        (
            Grains {
                density_kg_m3: 0.0,
                ..ok
            },
            "grains.density_kg_m3",
        ),
        // 80 mm across in a 75 mm motor; seven grains (0.87 m) in its 0.757 m.
        (
            Grains {
                outer_radius_m: 0.04,
                ..ok
            },
            "grains.outer_radius_m",
        ),
        (Grains { count: 7, ..ok }, "grains.height_m"),
    ];
    for (g, field) in cases {
        assert_eq!(refused(g, MotorOptions::default()).0, field, "{g:?}");
    }
    let (field, rule) = refused(ok, MotorOptions::default().with_propellant_mass_kg(3.0));
    assert_eq!(field, "propellant_mass_kg");
    assert!(rule.contains("give one or the other"), "{rule}");
    // Accepted, the grains are the propellant: their mass, and their inertia at ignition.
    let t = MotorTables::new(
        &m,
        &MotorOptions {
            grains: Some(ok),
            ..MotorOptions::default()
        },
    )
    .unwrap();
    assert_eq!(t.propellant_mass_kg(), ok.mass_kg());
    let p = t.propellant_props(2.0);
    assert_eq!(p.axial_inertia(), ok.inertia(ok.mass_kg()).inertia_kg_m2[0]);
    assert_eq!(
        p.transverse_inertia(),
        ok.inertia(ok.mass_kg()).inertia_kg_m2[1]
    );
}

#[test]
fn a_grain_motor_s_inertia_rates_are_the_derivatives_of_its_mass_properties_in_time() {
    let m = find("Cesaroni_M1670").unwrap();
    let t = MotorTables::new(
        &m,
        &MotorOptions {
            grains: Some(m1670_grains()),
            ..MotorOptions::default()
        },
    )
    .unwrap();
    let h = 1e-6;
    // Inside segments of the thrust curve (knots at 0.5, 1, 1.5, 2, 2.5, 2.9, 3, 3.3, 3.4 s).
    for time in [0.7, 1.7, 2.7, 3.6] {
        let rates = t.mass_rates(&t.eval(time));
        let i = |s: f64| t.mass_props(s, 2.0).inertia_cg;
        let d1 = (i(time + h) - i(time - h)) / (2.0 * h);
        let want = rates.inertia_rate_kg_m2_s;
        assert!(
            (d1 - want).norm() <= 1e-6 * want.norm(),
            "t {time}: {d1} against {want}"
        );
        let ir = |s: f64| t.mass_rates(&t.eval(s)).inertia_rate_kg_m2_s;
        let d2 = (ir(time + h) - ir(time - h)) / (2.0 * h);
        let want2 = rates.inertia_accel_kg_m2_s2;
        assert!(
            (d2 - want2).norm() <= 1e-5 * want2.norm() + 1e-9,
            "t {time}: {d2} against {want2}"
        );
    }
}
