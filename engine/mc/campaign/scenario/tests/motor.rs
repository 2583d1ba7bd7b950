//! A motor's own data in a scenario (masses, centers, casing inertia, grains, nozzle,
//! propellant chamber): read, and refused by key against the motor.

use super::*;

#[test]
fn a_motor_s_masses_are_read_and_a_negative_or_non_finite_one_refused_by_key() {
    let with = |lines: &str| BASE.replace("[motor]\n", &format!("[motor]\n{lines}\n"));
    assert_ne!(with("x = 1"), BASE, "BASE has a [motor] table");
    let s = Scenario::parse(
        &with("propellant_mass_kg = 2.95591\ndry_mass_kg = 1.815"),
        &path(),
    )
    .unwrap();
    assert_eq!(
        (
            s.motor_options.propellant_mass_kg,
            s.motor_options.dry_mass_kg
        ),
        (Some(2.95591), Some(1.815))
    );
    let plain = Scenario::parse(BASE, &path()).unwrap();
    assert_eq!(
        plain.motor_options,
        hpr_design::motor::MotorOptions::default()
    );
    for (line, key) in [
        ("dry_mass_kg = -0.1", "motor.dry_mass_kg"),
        ("propellant_mass_kg = inf", "motor.propellant_mass_kg"),
    ] {
        let e = Scenario::parse(&with(line), &path()).unwrap_err();
        assert_eq!(e.key(), key);
        assert!(
            e.to_string().contains("must be finite and not negative"),
            "{e}"
        );
    }
}

#[test]
fn a_motor_s_centers_and_casing_inertia_are_read_and_refused_by_key_against_the_motor() {
    let with = |lines: &str| BASE.replace("[motor]\n", &format!("[motor]\n{lines}\n"));
    let s = Scenario::parse(
        &with(
            "dry_center_from_nozzle_m = 0.1\npropellant_center_from_nozzle_m = 0.15\n\
             dry_inertia_kg_m2 = [0.0001, 0.002]",
        ),
        &path(),
    )
    .unwrap();
    let o = s.motor_options;
    assert_eq!(
        (
            o.dry_center_from_nozzle_m,
            o.propellant_center_from_nozzle_m,
            o.dry_inertia_kg_m2
        ),
        (Some(0.1), Some(0.15), Some([0.0001, 0.002]))
    );
    Prepared::new(s).expect("within the I175's 245 mm");
    let e = Scenario::parse(&with("dry_center_from_nozzle_m = -0.1"), &path()).unwrap_err();
    assert_eq!(e.key(), "motor.dry_center_from_nozzle_m");
    // Against the motor once it is known: a center past its 245 mm, an axial inertia more
    // than twice the transverse.
    for (line, key, rule) in [
        (
            "propellant_center_from_nozzle_m = 0.3",
            "motor.propellant_center_from_nozzle_m",
            "must lie within the motor",
        ),
        (
            "dry_inertia_kg_m2 = [0.01, 0.002]",
            "motor.dry_inertia_kg_m2",
            "at most twice the transverse",
        ),
    ] {
        let e = Prepared::new(Scenario::parse(&with(line), &path()).unwrap()).unwrap_err();
        assert_eq!(e.key(), key, "{line}");
        assert!(e.to_string().contains(rule), "{line}: {e}");
    }
}

#[test]
fn a_motor_s_grains_and_nozzle_are_read_and_refused_by_key_against_the_motor() {
    let with = |lines: &str| BASE.replace("[motor]\n", &format!("[motor]\n{lines}\n"));
    const GRAINS: &str = "grains = { count = 2, outer_radius_m = 0.016, inner_radius_m = 0.006, \
                          height_m = 0.1, separation_m = 0.003, density_kg_m3 = 1700.0 }";
    let s = Scenario::parse(
        &with(&format!("{GRAINS}\nnozzle_radius_m = 0.012")),
        &path(),
    )
    .unwrap();
    let g = s.motor_options.grains.expect("grains");
    assert_eq!(
        (g.count, g.outer_radius_m, g.inner_radius_m, g.height_m),
        (2, 0.016, 0.006, 0.1)
    );
    assert_eq!(
        (
            g.separation_m,
            g.density_kg_m3,
            s.motor_options.nozzle_radius_m
        ),
        (0.003, 1700.0, Some(0.012))
    );
    // Two grains of 0.1 m and 3 mm between fit the I175's 245 × 38 mm.
    Prepared::new(s).expect("the grains fit");
    for (lines, key, rule) in [
        (
            GRAINS.replace("count = 2", "count = 0"),
            "motor.grains.count",
            "at least 1",
        ),
        (
            GRAINS.replace("count = 2", "count = 3"),
            "motor.grains.height_m",
            "must fit in the motor's length",
        ),
        (
            format!("{GRAINS}\npropellant_mass_kg = 0.2"),
            "motor.propellant_mass_kg",
            "give one or the other",
        ),
        (
            "nozzle_radius_m = 0.02".to_owned(),
            "motor.nozzle_radius_m",
            "at most the motor's radius",
        ),
    ] {
        let e = Prepared::new(Scenario::parse(&with(&lines), &path()).unwrap()).unwrap_err();
        assert_eq!(e.key(), key, "{lines}");
        assert!(e.to_string().contains(rule), "{lines}: {e}");
    }
    let e = Scenario::parse(&with("grains = { count = 2 }"), &path()).unwrap_err();
    assert!(e.to_string().contains("outer_radius_m"), "{e}");
}

#[test]
fn a_motor_s_propellant_chamber_is_read_and_refused_by_key_against_the_motor() {
    // RocketPy's GenericMotor: the propellant a solid cylinder of the chamber's size.
    let with = |lines: &str| BASE.replace("[motor]\n", &format!("[motor]\n{lines}\n"));
    let s = Scenario::parse(
        &with("chamber = { radius_m = 0.015, height_m = 0.2 }"),
        &path(),
    )
    .unwrap();
    assert_eq!(s.motor_options.chamber_m, Some([0.015, 0.2]));
    Prepared::new(s).expect("within the I175's 245 × 38 mm");
    for (lines, key) in [
        (
            "chamber = { radius_m = 0.02, height_m = 0.2 }",
            "motor.chamber.radius_m",
        ),
        (
            "chamber = { radius_m = 0.015, height_m = 0.3 }",
            "motor.chamber.height_m",
        ),
        (
            "chamber = { radius_m = 0.015, height_m = 0.2 }\ngrains = { count = 1, \
             outer_radius_m = 0.016, inner_radius_m = 0.006, height_m = 0.1, \
             separation_m = 0.0, density_kg_m3 = 1700.0 }",
            "motor.chamber",
        ),
    ] {
        let e = Prepared::new(Scenario::parse(&with(lines), &path()).unwrap()).unwrap_err();
        assert_eq!(e.key(), key, "{lines}");
    }
}

#[test]
fn a_motor_file_s_own_size_out_of_range_is_the_motor_s_key_not_an_option_s() {
    // The I175's file with its length 1e-323 mm: positive as read, 0 m once in metres
    // (the quotient underflows). The file's reader refuses it with the file, the line and
    // the header's field, and it is the file's fault: the key naming the motor,
    // `motor.name` or its place in a sweep of motors.
    let i175 =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("engine/design/motors/Cesaroni_I175.eng");
    let text = std::fs::read_to_string(i175).unwrap();
    assert!(
        text.contains(" 38 245 "),
        "the I175's header: 38 mm by 245 mm"
    );
    let dir = tempfile::tempdir().unwrap();
    let flat = dir.path().join("Flat_I175.eng");
    std::fs::write(&flat, text.replace(" 38 245 ", " 38 1e-323 ")).unwrap();
    let flat = flat.display().to_string();
    let rule = format!(
        "{flat}, line 2, length (header field 3, mm): 1e-323 mm is 0 m: a size must be a \
         positive, finite number of metres"
    );
    let e = Prepared::new(Scenario::parse(&BASE.replace("Cesaroni_I175", &flat), &path()).unwrap())
        .unwrap_err();
    assert_eq!(e.key(), "motor.name");
    assert!(e.to_string().contains(&rule), "{e}");
    let swept = format!("{BASE}[sweep]\nmotor = [\"Cesaroni_I175\", {flat:?}]\n");
    let e = Prepared::new(Scenario::parse(&swept, &path()).unwrap()).unwrap_err();
    assert_eq!(e.key(), "sweep.motor[1]");
    assert!(e.to_string().contains(&rule), "{e}");
    // An option's field keeps its own key beside it: grains wider than the motor.
    let wide = BASE.replace(
        "[motor]\n",
        "[motor]\ngrains = { count = 1, outer_radius_m = 0.02, inner_radius_m = 0.006, \
         height_m = 0.1, separation_m = 0.0, density_kg_m3 = 1700.0 }\n",
    );
    let e = Prepared::new(Scenario::parse(&wide, &path()).unwrap()).unwrap_err();
    assert_eq!(e.key(), "motor.grains.outer_radius_m");
    assert!(
        e.to_string()
            .contains("option grains.outer_radius_m = 0.02: must fit in the motor"),
        "{e}"
    );
}
