//! A scenario's motor masses (`[motor] propellant_mass_kg`, `dry_mass_kg`, their centers and
//! the casing's inertia) through a whole campaign, with the motor's impulse scattered too:
//! each row is the flight `Simulation` flies with the same motor given by hand.

use super::*;
use hpr_design::motor::MotorOptions;
use hpr_sim::{Environment, Parachute, Rail, SimOptions, Simulation, Trigger};

#[test]
fn a_scenario_s_motor_masses_fly_as_the_simulator_given_them_by_hand() {
    let plain = windy("wind_speed_m_s = 0.0", "drag_scale = [1.0]").replace(
        "[dispersions]\n",
        "[dispersions]\nmotor_impulse_ns = { dist = \"normal\", sigma = 0.03, relative = true }\n",
    );
    let massed = plain.replace(
        "name = \"Cesaroni_I175\"\n",
        "name = \"Cesaroni_I175\"\npropellant_mass_kg = 0.25\ndry_mass_kg = 0.16\n\
         dry_center_from_nozzle_m = 0.09\npropellant_center_from_nozzle_m = 0.14\n\
         dry_inertia_kg_m2 = [0.00007, 0.0012]\n",
    );
    assert_ne!(plain, massed);
    let names = ["drag_scale", "motor_impulse_ns", "apogee_m"];
    let rows = landed_rows(&massed, names);
    let motor = hpr_design::motor::find("Cesaroni_I175").unwrap();
    let nominal_ns = motor.total_impulse_ns();
    let design = hpr_design::Design::load(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("validation/designs/synthetic-54mm-three-fin.json"),
    )
    .unwrap();
    for row in &rows {
        let options = MotorOptions {
            dry_center_from_nozzle_m: Some(0.09),
            propellant_center_from_nozzle_m: Some(0.14),
            dry_inertia_kg_m2: Some([0.00007, 0.0012]),
            ..MotorOptions::default()
        }
        .with_propellant_mass_kg(0.25)
        .with_dry_mass_kg(0.16)
        .with_impulse_scale(row[1] / nominal_ns);
        let by_hand = Simulation::with_motor_options(
            design.clone(),
            motor.clone(),
            options,
            Environment::default(),
            Rail {
                inclination_deg: 85.0,
                ..Rail::default()
            },
        )
        .and_then(|s| s.with_parachutes(vec![Parachute::new("main", 0.9, Trigger::Apogee, 1.0)]))
        .and_then(|s| s.with_drag_scale(row[0]))
        .and_then(|s| {
            s.with_options(SimOptions {
                max_time_s: 900.0,
                ..SimOptions::default()
            })
        })
        .unwrap();
        assert!((by_hand.model().motor.ignition_mass_kg() - 0.41).abs() < 1e-15);
        let apogee = by_hand.run(&mut ()).unwrap().metrics.apogee_m.unwrap();
        // Equal to rounding: the scale is read back from its column (1e-9 relative).
        assert!(
            (row[2] - apogee).abs() <= 1e-9 * apogee,
            "campaign {} against by hand {apogee}",
            row[2]
        );
    }
    // The file's masses (0.2289 kg of propellant, 0.2086 kg dry) fly otherwise: 27.5 g
    // lighter at ignition, 21.1 g more propellant burnt to the same impulse.
    let file_masses = landed_rows(&plain, names);
    for (a, b) in rows.iter().zip(&file_masses) {
        assert_eq!(a[..2], b[..2], "the same draws");
        assert!((a[2] - b[2]).abs() > 1.0, "{} against {}", a[2], b[2]);
    }
}

#[test]
fn inspect_and_fly_take_the_motor_s_masses_and_refuse_a_negative_one() {
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    let design = design.to_str().unwrap();
    let masses = [
        "--propellant-mass-kg",
        "0.25",
        "--motor-dry-mass-kg",
        "0.16",
    ];
    let (code, out, err) = hpr_mc(&[&["inspect", design, "--json"][..], &masses].concat());
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["motor"]["propellant_mass_kg"].as_f64(), Some(0.25));
    assert!((j["motor"]["loaded_mass_kg"].as_f64().unwrap() - 0.41).abs() < 1e-15);
    let (_, plain, _) = hpr_mc(&["inspect", design, "--json"]);
    let p: serde_json::Value = serde_json::from_str(&plain).unwrap();
    // The liftoff mass moves by the motor's: 0.41 kg against the file's 0.4375 kg.
    let liftoff = |v: &serde_json::Value| v["liftoff"]["mass_kg"].as_f64().unwrap();
    assert!((liftoff(&p) - liftoff(&j) - 0.0275).abs() < 1e-12);
    let (code, out, err) = hpr_mc(&[&["fly", design, "--json"][..], &masses].concat());
    assert_eq!(code, 0, "{err}");
    let f: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(f["metrics"]["apogee_m"].as_f64().unwrap() > 100.0);
    let (code, _, err) = hpr_mc(&["fly", design, "--propellant-mass-kg", "-0.1"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--propellant-mass-kg") && err.contains("must be 0 or more"),
        "{err}"
    );
}

#[test]
fn inspect_moves_the_center_of_mass_by_the_casing_s_moment_when_the_casing_moves() {
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    let design = design.to_str().unwrap();
    let inspect = |extra: &[&str]| {
        let (code, out, err) = hpr_mc(&[&["inspect", design, "--json"][..], extra].concat());
        assert_eq!(code, 0, "{err}");
        serde_json::from_str::<serde_json::Value>(&out).unwrap()
    };
    let liftoff = |extra: &[&str]| {
        let j = inspect(extra);
        let l = &j["liftoff"];
        (l["mass_kg"].as_f64().unwrap(), l["cg_m"].as_f64().unwrap())
    };
    let (mass, cg) = liftoff(&[]);
    // inspect says where the casing and the propellant are: the motor's middle, 0.1225 m
    // forward of its aft end, unless placed; the nozzle 0.88 of the 19 mm radius unless given.
    let plain = inspect(&[]);
    let placed = inspect(&[
        "--motor-dry-center-from-nozzle-m",
        "0.05",
        "--motor-propellant-center-from-nozzle-m",
        "0.2",
    ]);
    let at = |j: &serde_json::Value, k: &str| j["motor"][k].as_f64().unwrap();
    let aft = at(&plain, "casing_cg_m") + 0.1225;
    assert!((at(&plain, "propellant_cg_m") - (aft - 0.1225)).abs() < 1e-12);
    assert!((at(&placed, "casing_cg_m") - (aft - 0.05)).abs() < 1e-12);
    assert!((at(&placed, "propellant_cg_m") - (aft - 0.2)).abs() < 1e-12);
    assert!((at(&plain, "nozzle_radius_m") - 0.88 * 0.019).abs() < 1e-15);
    assert!(plain["motor"]["grains"].is_null());
    // The I175's 0.2086 kg casing from its middle (0.1225 m forward of the nozzle) to 0.05 m:
    // 0.0725 m aft, the rocket's center of mass 0.2086 × 0.0725 / m aft with it.
    let (moved_mass, moved_cg) = liftoff(&["--motor-dry-center-from-nozzle-m", "0.05"]);
    assert_eq!(mass, moved_mass);
    let want = 0.2086 * 0.0725 / mass;
    assert!(
        ((moved_cg - cg) - want).abs() < 1e-9,
        "{} against {want}",
        moved_cg - cg
    );
    let (code, _, err) = hpr_mc(&["inspect", design, "--motor-dry-inertia-kg-m2", "1,2,3"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("AXIAL,TRANSVERSE"), "{err}");
    let (code, _, err) = hpr_mc(&["inspect", design, "--motor-dry-center-from-nozzle-m", "0.3"]);
    assert_ne!(code, 0);
    assert!(err.contains("must lie within the motor"), "{err}");
}

#[test]
fn the_grains_chamber_and_nozzle_flags_give_inspect_rocketpy_s_propellant_shapes() {
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    let design = design.to_str().unwrap();
    let inspect = |extra: &[&str]| {
        let (code, out, err) = hpr_mc(&[&["inspect", design, "--json"][..], extra].concat());
        assert_eq!(code, 0, "{err}");
        serde_json::from_str::<serde_json::Value>(&out).unwrap()
    };
    let axial = |j: &serde_json::Value| j["liftoff"]["inertia_axial_kg_m2"].as_f64().unwrap();
    let mass = |j: &serde_json::Value| j["liftoff"]["mass_kg"].as_f64().unwrap();
    let plain = inspect(&[]);
    // The design's I175: 0.2289 kg of propellant, by default a solid cylinder of the motor's
    // 19 mm radius (axial inertia ½ m r²).
    let m_p = plain["motor"]["propellant_mass_kg"].as_f64().unwrap();
    assert!((m_p - 0.2289).abs() < 1e-12, "{m_p}");
    // Two BATES grains (RocketPy's SolidMotor order): their mass n ρ π (R² − r²) h replaces
    // the file's propellant, and their axial inertia is ½ m (R² + r²).
    let (n, rho, big_r, r, h) = (2.0, 1815.0, 0.0165, 0.008, 0.1);
    let grains = inspect(&["--motor-grains", "2,1815,0.0165,0.008,0.1,0.005"]);
    let m_g = n * rho * std::f64::consts::PI * (big_r * big_r - r * r) * h;
    let got = grains["motor"]["propellant_mass_kg"].as_f64().unwrap();
    assert!((got - m_g).abs() < 1e-12, "{got} against {m_g}");
    assert!(((mass(&grains) - mass(&plain)) - (m_g - m_p)).abs() < 1e-9);
    let want = 0.5 * m_g * (big_r * big_r + r * r) - 0.5 * m_p * 0.019_f64.powi(2);
    assert!(
        ((axial(&grains) - axial(&plain)) - want).abs() < 1e-12,
        "{} against {want}",
        axial(&grains) - axial(&plain)
    );
    assert_eq!(grains["motor"]["grains"]["count"].as_u64(), Some(2));
    // A GenericMotor's chamber 10 mm across the radius: the same mass, ½ m (0.01² − 0.019²)
    // less axial inertia; the nozzle radius as given.
    let chamber = inspect(&[
        "--motor-chamber-m",
        "0.01,0.1",
        "--motor-nozzle-radius-m",
        "0.012",
    ]);
    assert_eq!(mass(&chamber), mass(&plain));
    let want = 0.5 * m_p * (0.01_f64.powi(2) - 0.019_f64.powi(2));
    assert!(((axial(&chamber) - axial(&plain)) - want).abs() < 1e-12);
    assert_eq!(chamber["motor"]["nozzle_radius_m"].as_f64(), Some(0.012));
    // Refusals name the flag (clap's) or the motor option (the motor tables').
    let (code, _, err) = hpr_mc(&[
        "inspect",
        design,
        "--motor-grains",
        "2,1815,0.0165,0.008,0.1",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--motor-grains") && err.contains("give 6 numbers"),
        "{err}"
    );
    let (code, _, err) = hpr_mc(&[
        "inspect",
        design,
        "--motor-grains",
        "2.5,1815,0.0165,0.008,0.1,0",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("must be a whole number"), "{err}");
    let (code, _, err) = hpr_mc(&[
        "inspect",
        design,
        "--motor-grains",
        "2,1815,0.05,0.008,0.1,0",
    ]);
    assert_ne!(code, 0);
    assert!(
        err.contains("grains.outer_radius_m = 0.05: must fit in the motor"),
        "{err}"
    );
    let (code, _, err) = hpr_mc(&[
        "inspect",
        design,
        "--motor-grains",
        "2,1815,0.0165,0.008,0.1,0",
        "--propellant-mass-kg",
        "0.2",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("cannot be used with"), "{err}");
    // fly takes them too.
    let (code, out, err) = hpr_mc(&[
        "fly",
        design,
        "--json",
        "--motor-grains",
        "2,1815,0.0165,0.008,0.1,0.005",
    ]);
    assert_eq!(code, 0, "{err}");
    let f: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(f["metrics"]["apogee_m"].as_f64().unwrap() > 100.0);
}
