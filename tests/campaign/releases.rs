//! Releases through a whole campaign: the rows are the flights `Simulation` flies with the
//! same releases set up by hand, the release's numbers are swept and dispersed under their
//! keys, each released part has its landing ellipse, and every refusal names its key.

use super::*;
use hpr_sim::wind::Wind;
use hpr_sim::{Environment, Parachute, PartChute, PartTrigger, Release, Trigger};

/// [`windy`]'s scenario with `release` as its `[[releases]]` table.
fn with_release(release: &str, sweep: &str) -> String {
    windy("wind_speed_m_s = 4.0\nwind_from_deg = 250.0", sweep).replace(
        "[integrator]",
        &format!("[[releases]]\n{release}\n[integrator]"),
    )
}

/// The campaign `text`, run: its report and its variants file.
fn run(text: &str) -> (tempfile::TempDir, hpr_mc::campaign::RunReport, RecordBatch) {
    let (dir, file) = setup(text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    let v = read(&report.outputs.variants);
    (dir, report, v)
}

#[test]
fn a_scenario_s_release_flies_as_the_simulator_set_up_by_hand_and_has_its_own_ellipse() {
    let text = with_release(
        "name = \"payload\"\ncomponent = \"ballast\"\ntrigger = \"apogee\"\nparachute = { cds_m2 = 0.3, trigger = \"release\", lag_s = 2.0 }",
        "drag_scale = [1.0]",
    );
    let (_dir, report, v) = run(&text);
    assert_eq!(report.landed, 4);
    let design = hpr_design::Design::load(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("validation/designs/synthetic-54mm-three-fin.json"),
    )
    .unwrap();
    let env = Environment {
        wind: Wind::constant(4.0, 250.0).unwrap(),
        ..Environment::default()
    };
    let column = |n: &str| f64s(&v, n).values().to_vec();
    let (drag, fired, x, y, speed, open) = (
        column("drag_scale"),
        column("release_payload_fire_time_s"),
        column("release_payload_landing_x_m"),
        column("release_payload_landing_y_m"),
        column("release_payload_landing_speed_m_s"),
        column("release_payload_chute_open_time_s"),
    );
    let mut worst: f64 = 0.0;
    for r in 0..v.num_rows() {
        let f = hpr_sim::Simulation::new(
            design.clone(),
            hpr_design::motor::find("Cesaroni_I175").unwrap(),
            env.clone(),
            hpr_sim::Rail {
                inclination_deg: 85.0,
                ..hpr_sim::Rail::default()
            },
        )
        .and_then(|s| s.with_parachutes(vec![Parachute::new("main", 0.9, Trigger::Apogee, 1.0)]))
        .and_then(|s| {
            s.with_releases(vec![Release::new(Trigger::Apogee, "ballast")
                .with_parachute(PartChute::new(0.3, PartTrigger::Release, 2.0))])
        })
        .and_then(|s| s.with_drag_scale(drag[r]))
        .and_then(|s| {
            s.with_options(hpr_sim::SimOptions {
                max_time_s: 900.0,
                ..hpr_sim::SimOptions::default()
            })
        })
        .unwrap()
        .run(&mut ())
        .unwrap();
        let rec = &f.releases[0];
        let part = rec.part.as_ref().unwrap();
        let [px, py] = part.landing_position_m.unwrap();
        for (campaign, by_hand) in [
            (fired[r], rec.time_s.unwrap()),
            (x[r], px),
            (y[r], py),
            (speed[r], part.landing_speed_m_s.unwrap()),
            (open[r], part.chute_open_s.unwrap()),
        ] {
            worst = worst.max((campaign - by_hand).abs() / by_hand.abs().max(1.0));
        }
    }
    eprintln!("the payload's columns against the flights set up by hand: {worst:.1e}");
    assert!(worst <= 1e-9, "{worst:e}");
    // ellipses.parquet: the rocket's three and the payload's three, the payload's centered
    // on the mean of its landings.
    let e = read(&report.outputs.ellipses);
    let body = strings(&e, "body");
    let bodies: Vec<&str> = (0..e.num_rows()).map(|r| body.value(r)).collect();
    assert_eq!(
        bodies,
        [
            "rocket",
            "rocket",
            "rocket",
            "release_payload",
            "release_payload",
            "release_payload"
        ]
    );
    let mean_x = x.iter().sum::<f64>() / x.len() as f64;
    let center = f64s(&e, "center_x_m").value(3);
    assert!(
        (center - mean_x).abs() <= 1e-9 * mean_x.abs(),
        "{center} {mean_x}"
    );
    // The payload under its canopy drifts far past the rocket under its main.
    let rocket_x = f64s(&e, "center_x_m").value(0);
    eprintln!("ellipse centers: rocket {rocket_x:.1} m east, payload {center:.1} m east");
    assert!(center.abs() > rocket_x.abs());
}

#[test]
fn a_release_s_numbers_are_swept_and_dispersed_under_their_keys() {
    let text = with_release(
        "component = \"ballast\"\ntrigger = { time_s = 5.0 }\ncda_m2 = 0.002",
        "releases.ballast.time_s = [5.0, 6.0]",
    )
        + "releases.ballast.cda_m2 = { dist = \"uniform\", min = -0.0005, max = 0.0005 }\n";
    let (_dir, report, v) = run(&text);
    assert_eq!(report.landed, 8);
    let (swept, fired, cda) = (
        f64s(&v, "sweep_release_ballast_time_s"),
        f64s(&v, "release_ballast_fire_time_s"),
        f64s(&v, "release_ballast_cda_m2"),
    );
    let point = v
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt32Array>()
        .unwrap();
    for r in 0..v.num_rows() {
        let time = [5.0, 6.0][point.value(r) as usize];
        assert_eq!(swept.value(r), time);
        assert_eq!(fired.value(r), time, "the release fires at its swept time");
        assert!(
            (0.0015..=0.0025).contains(&cda.value(r)),
            "{}",
            cda.value(r)
        );
    }
    // The part's drag area moves its landing (the dispersion reaches the flight).
    let x = f64s(&v, "release_ballast_landing_x_m");
    assert_ne!(x.value(0), x.value(1));
    // The ballast's margin drops by the same jump at either time (the motor is out by then).
    let (before, after) = (
        f64s(&v, "release_ballast_margin_before_cal"),
        f64s(&v, "release_ballast_margin_after_cal"),
    );
    for r in 0..v.num_rows() {
        assert!((after.value(r) - before.value(r) - (-1.682739)).abs() < 1e-5);
    }
}

#[test]
fn every_refusal_of_a_release_names_its_key() {
    let cases = [
        (
            with_release("component = \"fins\"\ntrigger = \"apogee\"", "drag_scale = [1.0]"),
            "releases[0].component",
            "only internal parts can",
        ),
        (
            with_release(
                "component = \"ballast\"\ntrigger = { time_s = 0.0 }",
                "drag_scale = [1.0]",
            ),
            "releases[0].trigger",
            "still on the pad",
        ),
        (
            with_release(
                "component = \"ballast\"\ntrigger = \"apogee\"\ncda_m2 = -1.0",
                "drag_scale = [1.0]",
            ),
            "releases[0].cda_m2",
            "must be positive",
        ),
        (
            with_release(
                "component = \"ballast\"\ntrigger = \"apogee\"\nparachute = { cds_m2 = 0.3, trigger = \"landing\" }",
                "drag_scale = [1.0]",
            ),
            "releases[0].parachute.trigger",
            "\"release\"",
        ),
        (
            with_release(
                "component = \"ballast\"\ntrigger = \"apogee\"\nparachute = { cds_m2 = 0.3, trigger = { height_m = -5.0 } }",
                "drag_scale = [1.0]",
            ),
            "releases[0].parachute.trigger.height_m",
            "above the ground",
        ),
        (
            with_release(
                "component = \"ballast\"\ntrigger = \"apogee\"",
                "releases.ballast.parachute_cds_m2 = [0.1, 0.2]",
            ),
            "sweep.releases.ballast.parachute_cds_m2",
            "has no parachute",
        ),
        (
            with_release(
                "component = \"ballast\"\ntrigger = \"apogee\"",
                "releases.ballast.time_s = [5.0, 6.0]",
            ),
            "sweep.releases.ballast.time_s",
            "no number to sweep",
        ),
        (
            with_release(
                "component = \"ballast\"\ntrigger = \"apogee\"",
                "releases.payload.cda_m2 = [0.001]",
            ),
            "sweep.releases.payload",
            "no release is named \"payload\"",
        ),
    ];
    for (text, key, rule) in cases {
        let err = refusal(&text);
        eprintln!("{err}");
        assert!(err.contains(&format!(": {key}: ")), "{key}: {err}");
        assert!(err.contains(rule), "{rule}: {err}");
    }
}
