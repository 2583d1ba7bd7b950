//! `hpr-mc fly --scenario`: a scenario's nominal flight at a sweep point, against the
//! campaign's own rows.

use super::*;

#[test]
fn fly_with_a_scenario_flies_the_nominal_flight_of_the_point_it_is_given() {
    // No dispersion: every variant of a sweep point is that point's nominal flight.
    let text = windy(
        "wind_speed_m_s = 4.0\nwind_from_deg = 270.0",
        "wind_scale = [0.5, 1.5]",
    )
    .replace(
        "drag_scale = { dist = \"normal\", sigma = 0.05, relative = true }\n",
        "",
    );
    let (dir, file) = setup(&text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    let b = read(&report.outputs.variants);
    let file = file.to_str().unwrap();
    for point in 0..2 {
        let (code, out, err) = hpr_mc(&[
            "fly",
            "--scenario",
            file,
            "--point",
            &point.to_string(),
            "--json",
        ]);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let row = point * 4; // the first variant of the point
        for (json, column) in [
            ("apogee_m", "apogee_m"),
            ("landing_x_m", "landing_x_m"),
            ("landing_time_s", "landing_time_s"),
        ] {
            let (a, b) = (
                v["metrics"][json].as_f64().unwrap(),
                f64s(&b, column).value(row),
            );
            assert!(
                (a - b).abs() <= 1e-9 * b.abs().max(1.0),
                "point {point} {json}: fly {a}, campaign {b}"
            );
        }
    }
    // The two points differ (the wind's scale does move the landing), and a point past the
    // sweep is an error naming the count.
    assert!((f64s(&b, "landing_x_m").value(0) - f64s(&b, "landing_x_m").value(4)).abs() > 10.0);
    let (code, _, err) = hpr_mc(&["fly", "--scenario", file, "--point", "2"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--point 2: the scenario has 2 sweep points (0 to 1)"),
        "{err}"
    );
    // The text says which flight it is; --point means nothing without a scenario.
    let (code, out, _) = hpr_mc(&["fly", "--scenario", file, "--point", "1"]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with(&format!(
            "the nominal flight of {file} at sweep point 1 (wind_scale = 1.5)\n"
        )),
        "{out}"
    );
    let design = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/validation/designs/synthetic-54mm-three-fin.json"
    );
    let (code, _, err) = hpr_mc(&["fly", "--point", "1", design]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--point") && err.contains("--scenario"),
        "{err}"
    );
}

#[test]
fn fly_with_a_scenario_takes_an_input_given_by_its_own_mean_at_that_mean() {
    let fly = |text: &str| {
        let (_dir, file) = setup(text);
        let (code, out, err) = hpr_mc(&["fly", "--scenario", file.to_str().unwrap(), "--json"]);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        v["metrics"]["landing_x_m"].as_f64().unwrap()
    };
    let about_mean = fly(&windy(
        "wind_speed_m_s = 2.0\nwind_from_deg = 270.0",
        "drag_scale = [1.0]",
    )
    .replace(
        "[dispersions]\n",
        "[dispersions]\nwind_speed_m_s = { dist = \"normal\", mean = 6.0, sigma = 1.0 }\n",
    ));
    let at_six = fly(&windy(
        "wind_speed_m_s = 6.0\nwind_from_deg = 270.0",
        "drag_scale = [1.0]",
    ));
    let at_two = fly(&windy(
        "wind_speed_m_s = 2.0\nwind_from_deg = 270.0",
        "drag_scale = [1.0]",
    ));
    assert_eq!(about_mean.to_bits(), at_six.to_bits());
    assert!((at_six - at_two).abs() > 10.0, "{at_six} {at_two}");
}

#[test]
fn fly_with_a_sounding_flies_the_scenario_that_names_it() {
    // `fly DESIGN --sounding FILE` and a scenario with `environment.sounding = FILE` (no
    // dispersion, its main at apogee on the same rail) fly the same flight: the site the
    // sounding's ground, its air and wind.
    let sounding = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/soundings/synthetic-wyoming.txt")
        .display()
        .to_string();
    let text = windy(&format!("sounding = {sounding:?}"), "drag_scale = [1.0]").replace(
        "drag_scale = { dist = \"normal\", sigma = 0.05, relative = true }\n",
        "",
    );
    let (dir, file) = setup(&text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    let b = read(&report.outputs.variants);
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json")
        .display()
        .to_string();
    let sounding_fly = [
        "fly",
        &design,
        "--motor",
        "Cesaroni_I175",
        "--sounding",
        &sounding,
    ];
    let (code, out, err) = hpr_mc(
        &[
            &sounding_fly[..],
            &[
                "--inclination-deg",
                "85",
                "--main-cds-m2",
                "0.9",
                "--drogue-cds-m2",
                "0.9",
                "--main-height-m",
                "0.001",
                "--json",
            ],
        ]
        .concat(),
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let a = v["metrics"]["apogee_m"].as_f64().unwrap();
    // To rounding, as the other `fly` checks (the campaign's air passes through its site's
    // values: 1 ulp here).
    let c = f64s(&b, "apogee_m").value(0);
    assert!(
        (a - c).abs() <= 1e-9 * c,
        "the same climb through the same air: {a} against {c}"
    );
    // A sounding beside the air or wind it gives is refused by clap, naming both flags.
    let (code, _, err) = hpr_mc(&[&sounding_fly[..], &["--wind-m-s", "3"]].concat());
    assert_ne!(code, 0);
    assert!(
        err.contains("--sounding") && err.contains("--wind-m-s"),
        "{err}"
    );
}

#[test]
fn fly_exits_1_saying_so_for_a_flight_that_never_leaves_the_rail_or_reaches_its_time_limit() {
    let design = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/validation/designs/synthetic-54mm-three-fin.json"
    );
    // A wind of 1e6 m/s holds the rocket on its rail until the time limit.
    let (code, out, err) = hpr_mc(&["fly", design, "--wind-m-s", "1e6"]);
    assert_eq!(code, 1, "{err}");
    assert!(out.contains("time_limit"), "{out}");
    assert_eq!(
        err.lines().last().unwrap(),
        "hpr-mc: the flight never left the rail: it was still on it at its time limit, 600 s \
         (its events above say how far it got)"
    );
    // Off the rail, but no parachute and a slow fall: still up at the time limit of a
    // scenario's short max_time_s.
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("short.toml");
    std::fs::write(
        &scenario,
        format!(
            "seed = 1\nvariants_per_point = 1\n[design]\nfile = \"{design}\"\n[motor]\nname = \"Cesaroni_I175\"\n[integrator]\nmax_time_s = 20.0\n"
        ),
    )
    .unwrap();
    let (code, _, err) = hpr_mc(&["fly", "--scenario", scenario.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains(
            "hpr-mc: the flight did not land: it was still flying at its time limit, 20 s"
        ),
        "{err}"
    );
    // A flight that lands is a success.
    let (code, _, err) = hpr_mc(&["fly", design]);
    assert_eq!(code, 0, "{err}");
}
