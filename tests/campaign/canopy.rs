//! A parachute's canopy shape through a whole campaign: the rows are the flights `Simulation`
//! flies with the same canopy set up by hand, and the shape moves them.

use super::*;
use hpr_sim::wind::Wind;
use hpr_sim::{CanopyShape, Environment, Parachute, Trigger};

#[test]
fn a_scenario_s_canopy_radius_height_and_porosity_fly_as_the_simulator_set_up_by_hand() {
    let wind = "wind_speed_m_s = 4.0\nwind_from_deg = 250.0";
    let plain = windy(wind, "drag_scale = [1.0]");
    let shaped = plain.replace(
        "trigger = \"apogee\"\n",
        "trigger = \"apogee\"\nradius_m = 1.1\nheight_m = 0.6\nporosity = 0.2\n",
    );
    assert_ne!(plain, shaped);
    let campaign = drag_apogee_landing(&shaped);
    let env = Environment {
        wind: Wind::constant(4.0, 250.0).unwrap(),
        ..Environment::default()
    };
    let canopy = CanopyShape {
        radius_m: Some(1.1),
        height_m: Some(0.6),
        porosity: 0.2,
    };
    let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0).with_canopy(canopy);
    assert_rows_flown_by_hand(&campaign, &env, &chute);
    // The default canopy of 0.9 m² (R = 0.452 m) carries 0.194 m³ of air, this one 1.148 m³
    // (C_a = 0.7548): the heavier canopy opens more slowly and the landing moves.
    let default = drag_apogee_landing(&plain);
    let moved = (campaign[0][2] - default[0][2]).hypot(campaign[0][3] - default[0][3]);
    eprintln!("canopy of 1.1 m × 0.6 m, porosity 0.2: landing moved {moved:.4} m");
    assert!(moved > 1e-3, "{moved} m");
    assert_eq!(
        campaign[0][1], default[0][1],
        "the apogee comes before any canopy"
    );
}

#[test]
fn a_scenario_s_sampling_rate_fires_its_parachute_as_the_simulator_set_up_by_hand() {
    let wind = "wind_speed_m_s = 4.0\nwind_from_deg = 250.0";
    let plain = windy(wind, "drag_scale = [1.0]");
    let sampled = plain.replace(
        "trigger = \"apogee\"\n",
        "trigger = \"apogee\"\nsampling_rate_hz = 20.0\n",
    );
    assert_ne!(plain, sampled);
    let campaign = drag_apogee_landing(&sampled);
    let env = Environment {
        wind: Wind::constant(4.0, 250.0).unwrap(),
        ..Environment::default()
    };
    let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0).with_sampling_rate(20.0);
    assert_rows_flown_by_hand(&campaign, &env, &chute);
    // The canopy opens up to 50 ms later than the continuous one's: the landing moves.
    let watched = drag_apogee_landing(&plain);
    let moved = (campaign[0][2] - watched[0][2]).hypot(campaign[0][3] - watched[0][3]);
    eprintln!("a 20 Hz altimeter: landing moved {moved:.4} m");
    assert!(moved > 1e-3, "{moved} m");
    assert_eq!(campaign[0][1], watched[0][1], "the same apogee");
}

#[test]
fn a_sampling_rate_not_positive_or_past_10_khz_is_refused_naming_its_parachute_s_key() {
    // 1e300 Hz (a typo) would read a noisy barometer 1e300 times a second: refused, as a
    // rate of 0 is.
    for rate in ["0.0", "10000.5", "1e300"] {
        let text = windy("wind_speed_m_s = 4.0", "drag_scale = [1.0]").replace(
            "trigger = \"apogee\"\n",
            &format!("trigger = \"apogee\"\nsampling_rate_hz = {rate}\n"),
        );
        let err = refusal(&text);
        assert!(err.contains("parachutes[0].sampling_rate_hz"), "{err}");
        assert!(err.contains("must be positive, at most 10000 Hz"), "{err}");
    }
}

#[test]
fn fly_refuses_a_sampling_rate_past_10_khz_naming_its_flag() {
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    let design = design.to_str().unwrap();
    let (code, _, err) = hpr_mc(&["fly", design, "--sampling-rate-hz", "2e4"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--sampling-rate-hz") && err.contains("must be at most 10000 Hz"),
        "{err}"
    );
    let (code, _, err) = hpr_mc(&["fly", design, "--sampling-rate-hz", "10000"]);
    assert_eq!(code, 0, "{err}");
}

/// [`windy`]'s main fired at 300 m on the way down by a 100 Hz altimeter, with `noise` (a
/// TOML inline table) on its barometer, if any.
fn main_at_300(noise: Option<&str>) -> String {
    let noise = noise.map_or(String::new(), |n| format!("noise = {n}\n"));
    windy(
        "wind_speed_m_s = 4.0\nwind_from_deg = 250.0",
        "drag_scale = [1.0]",
    )
    .replace(
        "trigger = \"apogee\"\n",
        &format!("trigger = {{ height_m = 300.0 }}\nsampling_rate_hz = 100.0\n{noise}"),
    )
}

#[test]
fn a_scenario_s_noisy_barometer_fires_each_variant_s_main_through_its_own_seed() {
    // A poor barometer (60 Pa, about 5 m of height: a dozen samples of the ballistic fall)
    // with a bias and correlated samples. Each variant reads its own noise: its sensor seed is
    // drawn from the scenario's seed and its stream (key "sensor_noise"), so the same scenario
    // repeats its rows, and each row is the simulator set up by hand with that seed.
    let noisy_text = main_at_300(Some("{ bias_pa = 5.0, std_pa = 60.0, correlation = 0.3 }"));
    let names = [
        "drag_scale",
        "parachute_main_deploy_time_s",
        "apogee_m",
        "landing_x_m",
    ];
    let (noisy, again, plain) = (
        landed_rows(&noisy_text, names),
        landed_rows(&noisy_text, names),
        landed_rows(&main_at_300(None), names),
    );
    assert_eq!(noisy, again, "the same scenario and seed, the same rows");
    let seeds: Vec<u64> = {
        let (dir, file) = setup(&noisy_text);
        let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
        let b = read(&report.outputs.variants);
        u64s(&b, "sensor_seed").values().to_vec()
    };
    // Without noise, no such column.
    {
        let (dir, file) = setup(&main_at_300(None));
        let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
        assert!(read(&report.outputs.variants)
            .column_by_name("sensor_seed")
            .is_none());
    }
    let design = hpr_design::Design::load(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("validation/designs/synthetic-54mm-three-fin.json"),
    )
    .unwrap();
    let noise = hpr_sim::SensorNoise {
        bias_pa: 5.0,
        std_pa: 60.0,
        correlation: 0.3,
    };
    let chute = Parachute::new(
        "main",
        0.9,
        Trigger::HeightDescending { height_m: 300.0 },
        1.0,
    )
    .with_sampling_rate(100.0)
    .with_noise(noise);
    let mut moved = 0;
    for (r, (n, p)) in noisy.iter().zip(&plain).enumerate() {
        assert_eq!(n[0], p[0], "the same drag scales");
        assert_eq!(
            n[2], p[2],
            "the same apogee: nothing reads the noise before it"
        );
        // The row's own sensor seed (a column where a barometer is noisy): one point, common
        // random numbers, so variant r's is drawn from stream r of the scenario's seed 3.
        let seed = seeds[r];
        let derived: u64 = rand::RngExt::random(&mut hpr_mc::campaign::sample::input_rng(
            3,
            r as u64,
            "sensor_noise",
        ));
        assert_eq!(seed, derived);
        let f = hpr_sim::Simulation::new(
            design.clone(),
            hpr_design::motor::find("Cesaroni_I175").unwrap(),
            Environment {
                wind: Wind::constant(4.0, 250.0).unwrap(),
                ..Environment::default()
            },
            hpr_sim::Rail {
                inclination_deg: 85.0,
                ..hpr_sim::Rail::default()
            },
        )
        .and_then(|s| s.with_parachutes(vec![chute.clone()]))
        .and_then(|s| s.with_drag_scale(n[0]))
        .and_then(|s| {
            s.with_options(hpr_sim::SimOptions {
                max_time_s: 900.0,
                ..hpr_sim::SimOptions::default()
            })
        })
        .unwrap()
        .with_sensor_seed(seed)
        .run(&mut ())
        .unwrap();
        assert_eq!(Some(n[1]), f.deploy(0).map(|d| d.0), "row {r}");
        assert_eq!(
            Some(n[3]),
            f.metrics.landing_position_m.map(|p| p[0]),
            "row {r}"
        );
        moved += usize::from(n[1] != p[1]);
        eprintln!(
            "drag {:.4}: main opens at {:.2} s noiseless, {:.2} s through the noisy barometer",
            p[0], p[1], n[1]
        );
    }
    assert!(moved >= 3, "{moved} of {} moved", noisy.len());
}

#[test]
fn a_noisy_barometer_without_a_sampling_rate_or_with_a_bad_number_is_refused_by_key() {
    let no_rate = main_at_300(Some("{ std_pa = 8.3 }")).replace("sampling_rate_hz = 100.0\n", "");
    let err = refusal(&no_rate);
    assert!(
        err.contains("parachutes[0].noise") && err.contains("sampling_rate_hz"),
        "{err}"
    );
    let err = refusal(&main_at_300(Some("{ std_pa = -2.0 }")));
    assert!(
        err.contains("parachutes[0].noise.std_pa") && err.contains("-2"),
        "{err}"
    );
    let err = refusal(&main_at_300(Some("{ std_pa = 1.0, correlation = 1.5 }")));
    assert!(err.contains("parachutes[0].noise.correlation"), "{err}");
    let err = refusal(&main_at_300(Some("{ std_pa = 1.0, sigma = 2.0 }")));
    assert!(err.contains("sigma"), "{err}");
}
