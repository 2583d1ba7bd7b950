//! The reference design against the moving-mass worked example, digit for digit as
//! `docs/moving-mass.md` ("The worked example") prints it, and `hpr-mc inspect` on it.

use hpr_sim::flight::{Environment, Rail, Simulation};
use hpr_sim::{reference, Trigger};

const REFERENCE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/validation/designs/synthetic-54mm-three-fin.json"
);

/// Run `hpr-mc` with `args`; it must succeed. Its standard output.
fn hpr_mc(args: &[&str]) -> String {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn the_moving_ballast_example_prints_the_specification_s_table_to_every_digit() {
    let still = reference::simulation();
    let sim = reference::worked_example();
    let flight = sim.run(&mut ()).unwrap();
    let table: Vec<String> = [4.0, 5.25, 5.5, 5.75, 7.0]
        .iter()
        .map(|&t| {
            let p = sim.mass_properties(&flight, t);
            format!(
                "{t:.2} {:.4} {:.4} {:.5}",
                p.mass_kg,
                p.cg_m.x,
                p.transverse_inertia()
            )
        })
        .collect();
    let spec = [
        "4.00 0.8188 0.6681 0.09556",
        "5.25 0.8188 0.6748 0.09248",
        "5.50 0.8188 0.7048 0.08138",
        "5.75 0.8188 0.7347 0.07483",
        "7.00 0.8188 0.7414 0.07399",
    ];
    assert_eq!(table, spec);
    let before = sim.static_margin_for(sim.mass_properties(&flight, 4.0).cg_m.x);
    let after = sim.static_margin_for(sim.mass_properties(&flight, 7.0).cg_m.x);
    assert_eq!(
        format!("{before:.3} {after:.3} {:.3}", after - before),
        "4.297 2.996 -1.302"
    );
    let moving = flight.metrics.apogee_m.unwrap();
    let held = still.run(&mut ()).unwrap().metrics.apogee_m.unwrap();
    eprintln!("apogee {moving:.3} m with the ballast moving, {held:.3} m held still");
    // The example's stated apogees (`docs/moving-mass.md`): 1749.8 m moving, 1749.9 m held.
    // Measured 1749.987 and 1750.084 m (0.01 % above; they were stated without the
    // atmosphere, rail and integrator settings behind them, so 0.5 m is allowed); the
    // ballast's worth, −0.097 m, is the stated −0.1 m.
    for (a, spec) in [(moving, 1749.8), (held, 1749.9)] {
        assert!(
            (a - spec).abs() <= 0.5,
            "apogee {a} m against {spec} m (bound 0.5 m)"
        );
    }
    assert!(
        (moving - held + 0.1).abs() <= 0.05,
        "the ballast moves the apogee by {} m (the specification: −0.1 m ± 0.05)",
        moving - held
    );
}

#[test]
fn inspect_prints_the_reference_design_s_mass_properties_and_margin() {
    let v: serde_json::Value =
        serde_json::from_str(&hpr_mc(&["inspect", REFERENCE, "--json"])).unwrap();
    let b = &v["after_burnout"];
    let f = |k: &str| b[k].as_f64().unwrap();
    assert_eq!(
        format!(
            "{:.4} {:.4} {:.5} {:.3}",
            f("mass_kg"),
            f("cg_m"),
            f("inertia_transverse_kg_m2"),
            f("static_margin_cal")
        ),
        "0.8188 0.6681 0.09556 4.297"
    );
    assert_eq!(v["motor"]["designation"], "411-I175-WH-14A");
    // Each lifting surface's slope and center of pressure: the nose's slender-body 2/rad, and
    // the rocket's CP their slope-weighted mean (to rounding).
    let surfaces = v["lifting_surfaces"].as_array().unwrap();
    let kinds: Vec<&str> = surfaces
        .iter()
        .map(|l| l["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["nose_cone", "fin_set"]);
    let slope = |l: &serde_json::Value| l["cn_alpha_mach0_per_rad"].as_f64().unwrap();
    assert!((slope(&surfaces[0]) - 2.0).abs() < 1e-12);
    let total: f64 = surfaces.iter().map(slope).sum();
    let moment: f64 = surfaces
        .iter()
        .map(|l| slope(l) * l["x_cp_m"].as_f64().unwrap())
        .sum();
    let cp = v["center_of_pressure_m"].as_f64().unwrap();
    assert!(
        (moment / total - cp).abs() < 1e-12,
        "{} vs {cp}",
        moment / total
    );
    // The text form says the same.
    let text = hpr_mc(&["inspect", REFERENCE]);
    let line = text
        .lines()
        .find(|l| l.starts_with("after burnout"))
        .unwrap();
    for figure in ["0.8188", "0.6681", "0.09556", "4.297"] {
        assert!(line.contains(figure), "{line}");
    }
}

#[test]
fn fly_takes_negative_numbers_after_a_space_as_values() {
    // `--heading-deg -30` is the value −30, not an unknown flag; it equals `--heading-deg=-30`.
    let fly =
        |more: &[&str]| hpr_mc(&[&["fly", REFERENCE, "--json", "--wind-m-s", "3"], more].concat());
    let spaced = fly(&["--heading-deg", "-30", "--inclination-deg", "85"]);
    let joined = fly(&["--heading-deg=-30", "--inclination-deg=85"]);
    assert_eq!(spaced, joined);
    assert_ne!(
        spaced,
        fly(&["--heading-deg", "30", "--inclination-deg", "85"])
    );
}

#[test]
fn fly_flies_on_the_turning_earth_of_its_latitude_with_the_ellipsoid_s_gravity() {
    let args = [
        "fly",
        REFERENCE,
        "--json",
        "--latitude-deg",
        "-33.9",
        "--gravity",
        "somigliana",
        "--elevation-m",
        "800",
        "--wind-m-s",
        "4",
    ];
    let v: serde_json::Value = serde_json::from_str(&hpr_mc(&args)).unwrap();
    let apogee = v.pointer("/metrics/apogee_m").unwrap().as_f64().unwrap();
    // The same site by hand (the apogee comes before any canopy).
    let env = Environment {
        elevation_m: 800.0,
        wind: hpr_sim::wind::Wind::constant(4.0, 0.0).unwrap(),
        gravity: hpr_sim::gravity::Gravity::somigliana(-33.9, 800.0).unwrap(),
        latitude_deg: Some(-33.9),
        ..Environment::default()
    };
    let by_hand = Simulation::new(
        reference::design(),
        reference::motor(),
        env,
        Rail::default(),
    )
    .unwrap()
    .run(&mut ())
    .unwrap()
    .metrics
    .apogee_m
    .unwrap();
    assert!(
        (apogee - by_hand).abs() < 1e-9,
        "{apogee} against {by_hand}"
    );
    // Somigliana without a latitude, or a latitude past a pole: refused, exit code 2.
    for (more, says) in [
        (&["--gravity", "somigliana"][..], "give --latitude-deg"),
        (&["--latitude-deg", "95"][..], "latitude_deg"),
    ] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
            .args([&["fly", REFERENCE][..], more].concat())
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{err}");
        assert!(out.stdout.is_empty());
    }
}

#[test]
fn fly_prints_a_ballistic_warning_for_a_rocket_without_parachutes() {
    let calisto = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/validation/designs/calisto.json"
    );
    let v: serde_json::Value = serde_json::from_str(&hpr_mc(&["fly", calisto, "--json"])).unwrap();
    let speed = v["metrics"]["landing_speed_m_s"].as_f64().unwrap();
    assert_eq!(
        v["warnings"],
        serde_json::json!([format!(
            "ballistic: landed at {speed:.1} m/s with no parachute open"
        )])
    );
    // The text form says the same on its own line.
    let text = hpr_mc(&["fly", calisto]);
    assert!(
        text.contains(&format!(
            "\nwarning             ballistic: landed at {speed:.1} m/s"
        )),
        "{text}"
    );
    // The reference design opens its drogue and main: nothing to warn of.
    let v: serde_json::Value =
        serde_json::from_str(&hpr_mc(&["fly", REFERENCE, "--json"])).unwrap();
    assert_eq!(v["warnings"], serde_json::json!([]));
}

#[test]
fn output_into_a_closed_pipe_ends_quietly_instead_of_panicking() {
    // `true` exits without reading, so hpr-mc's write finds the pipe closed (it flies first,
    // which takes far longer than `true` does to exit). Its exit status is kept by pipefail.
    let bin = env!("CARGO_BIN_EXE_hpr-mc");
    for args in [
        format!("fly '{REFERENCE}' --json"),
        format!("inspect '{REFERENCE}'"),
    ] {
        let out = std::process::Command::new("bash")
            .args(["-c", &format!("set -o pipefail; '{bin}' {args} | true")])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args}: {:?} {stderr}", out.status);
        assert!(!stderr.contains("panicked"), "{args}: {stderr}");
    }
}

#[test]
fn a_trajectory_file_of_another_kind_is_refused_before_the_flight_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("flight.txt");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
        .args(["fly", REFERENCE, "--trajectory", bad.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("flight.txt: a trajectory is written as .csv or .parquet"),
        "{err}"
    );
    // Refused before flying: no flight printed, no file left behind.
    assert!(out.stdout.is_empty());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    // A CSV trajectory is written, with a header and one row per sample.
    let csv = dir.path().join("flight.csv");
    hpr_mc(&["fly", REFERENCE, "--trajectory", csv.to_str().unwrap()]);
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(
        text.starts_with("phase,time_s,x_m,y_m,altitude_m,"),
        "{}",
        &text[..80]
    );
    // The flight takes about 300 steps, a sample each (302 lines with the header; some 490
    // when Dormand–Prince stepped the descent too, before RODAS4 took it over).
    assert!(text.lines().count() > 250, "{} lines", text.lines().count());
}

#[test]
fn a_flag_s_number_out_of_range_is_refused_naming_the_flag() {
    for (flag, value, rule) in [
        ("--rail-length-m", "-2", "must be positive and finite"),
        ("--lag-s", "-1", "must be 0 or more and finite"),
        ("--main-cds-m2", "0", "must be positive and finite"),
        ("--wind-m-s", "fast", "not a number"),
    ] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
            .args(["fly", REFERENCE, &format!("{flag}={value}")])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{flag}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(&format!("invalid value '{value}' for '{flag}")) && err.contains(rule),
            "{err}"
        );
        assert!(out.stdout.is_empty());
    }
}

#[test]
fn the_released_ballast_example_prints_the_page_s_table_to_every_digit() {
    // docs/released-mass.md's worked example: the ballast dropped at 5 s, tumbling.
    let kept = reference::simulation();
    let sim = kept
        .clone()
        .with_releases(vec![hpr_sim::Release::new(
            Trigger::Time { time_s: 5.0 },
            "ballast",
        )])
        .unwrap();
    let flight = sim.run(&mut ()).unwrap();
    let table: Vec<String> = [4.0, 5.0, 10.0]
        .iter()
        .map(|&t| {
            let p = sim.mass_properties(&flight, t);
            format!(
                "{t:.2} {:.4} {:.4} {:.5} {:.6} {:.3}",
                p.mass_kg,
                p.cg_m.x,
                p.transverse_inertia(),
                p.inertia_cg[(0, 0)],
                sim.static_margin_for(p.cg_m.x)
            )
        })
        .collect();
    assert_eq!(
        table,
        [
            "4.00 0.8188 0.6681 0.09556 0.000406 4.297",
            "5.00 0.6188 0.7629 0.07276 0.000366 2.615",
            "10.00 0.6188 0.7629 0.07276 0.000366 2.615",
        ]
    );
    let r = &flight.releases[0];
    let part = r.part.as_ref().unwrap();
    let [x, y] = part.landing_position_m.unwrap();
    let figures = format!(
        "{:.3} {:.1} {:.1} {:.5} {:.1} {:.1} {:.1} {:.1} {:.1}",
        r.margin_after_cal.unwrap() - r.margin_before_cal.unwrap(),
        flight.metrics.apogee_m.unwrap(),
        kept.run(&mut ()).unwrap().metrics.apogee_m.unwrap(),
        sim.release_plan().cda_m2[0],
        part.start_position_m[2],
        part.apogee_m,
        part.landing_time_s.unwrap(),
        x.hypot(y),
        part.landing_speed_m_s.unwrap()
    );
    assert_eq!(
        figures,
        "-1.683 1667.9 1750.1 0.00112 1028.8 1391.7 41.2 0.0 53.9"
    );
}
