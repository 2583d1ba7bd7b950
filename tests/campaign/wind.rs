//! Wind profiles and constant winds scaled and turned (`wind_scale`, `wind_rotation_deg`),
//! flown through whole campaigns against the same winds written out.

use super::*;
use hpr_sim::wind::Wind;
use hpr_sim::{Environment, Parachute, Trigger};

/// Every row's landing point, apogee and landing time.
fn flights(text: &str) -> Vec<[f64; 4]> {
    landed_rows(
        text,
        ["landing_x_m", "landing_y_m", "apogee_m", "landing_time_s"],
    )
}

/// Row by row, the same figures to 2e-6 (relative, or absolute below 1): the same flights up
/// to the rounding of their inputs. Not closer: when an input changes in its last bits, the
/// adaptive integrator may accept one step more or fewer somewhere, which moves the flight by
/// the order of its tolerance (rtol 1e-7). Measured on the reference design in the profile
/// below: 613 steps against 614, the apogee 1.2e-4 m apart on 1705 m; the landing point in
/// the campaign 2e-3 m apart on 3.7 km (5e-7); a hundredth of the tolerance brings the apogees
/// to 9e-6 m apart.
fn assert_same_flights(a: &[[f64; 4]], b: &[[f64; 4]]) {
    assert_eq!(a.len(), b.len());
    for (r, (a, b)) in a.iter().zip(b).enumerate() {
        for k in 0..4 {
            assert!(
                (a[k] - b[k]).abs() <= 2e-6 * b[k].abs().max(1.0),
                "row {r} figure {k}: {} against {}",
                a[k],
                b[k]
            );
        }
    }
}

#[test]
fn a_wind_profile_scaled_and_turned_flies_as_the_profile_written_scaled_and_turned() {
    // Rows 2 m/s from 270° at the ground and 9 m/s from 300° at 1 km; scaled 1.5 and turned
    // 40° clockwise, against the same rows written at 3 and 13.5 m/s from 310° and 340°.
    let rows = |k: f64, turn: f64| {
        format!(
            "wind_profile = [{{ height_m = 0.0, speed_m_s = {}, from_deg = {} }}, {{ height_m = 1000.0, speed_m_s = {}, from_deg = {} }}]",
            2.0 * k,
            270.0 + turn,
            9.0 * k,
            300.0 + turn
        )
    };
    let scaled = flights(&windy(
        &rows(1.0, 0.0),
        "wind_scale = [1.5]\nwind_rotation_deg = [40.0]",
    ));
    let written = flights(&windy(&rows(1.5, 40.0), "drag_scale = [1.0]"));
    // The two ways differ only in the rounding of the wind's components (1e-15 of them).
    assert_same_flights(&scaled, &written);
    // And the turn matters: unturned, the rocket lands elsewhere (more than 10 m away).
    let unturned = flights(&windy(&rows(1.5, 0.0), "drag_scale = [1.0]"));
    let apart = (unturned[0][0] - written[0][0]).hypot(unturned[0][1] - written[0][1]);
    assert!(apart > 10.0, "{apart} m");
}

#[test]
fn a_constant_wind_scaled_by_a_half_is_the_constant_wind_of_half_its_speed() {
    let scaled = flights(&windy(
        "wind_speed_m_s = 6.0\nwind_from_deg = 250.0",
        "wind_scale = [0.5]",
    ));
    let half = flights(&windy(
        "wind_speed_m_s = 3.0\nwind_from_deg = 250.0",
        "drag_scale = [1.0]",
    ));
    assert_same_flights(&scaled, &half);
}

#[test]
fn a_turbulent_wind_gusts_each_variant_by_its_own_seed_and_fly_repeats_a_row() {
    // OpenRocket's default turbulence, 10 %, on a 6 m/s wind: each variant draws its gusts
    // from its own seed (a sensor_seed column), the same scenario repeats its rows, and the
    // row is `fly` of the same flight with that seed.
    let env = "wind_speed_m_s = 6.0\nwind_from_deg = 250.0\nwind_turbulence_intensity = 0.1";
    let text = windy(env, "drag_scale = [1.0]");
    let steady = windy(
        "wind_speed_m_s = 6.0\nwind_from_deg = 250.0",
        "drag_scale = [1.0]",
    );
    let names = ["drag_scale", "apogee_m", "landing_x_m", "landing_y_m"];
    let (gusty, again, calm) = (
        landed_rows(&text, names),
        landed_rows(&text, names),
        landed_rows(&steady, names),
    );
    assert_eq!(gusty, again, "the same scenario and seed, the same rows");
    let (dir, file) = setup(&text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    let b = read(&report.outputs.variants);
    // A sensor_seed column with turbulence.
    let seeds = u64s(&b, "sensor_seed").values().to_vec();
    for (r, (g, c)) in gusty.iter().zip(&calm).enumerate() {
        assert_eq!(g[0], c[0], "the same drag scales");
        // The gusts move the landing point: 10 % of 6 m/s over a few minutes' drift does not
        // average out to a centimetre.
        let apart = (g[2] - c[2]).hypot(g[3] - c[3]);
        assert!(apart > 0.01, "row {r}: {apart} m");
        // Under the main the rocket drifts with the air: the gusty landing stays within a
        // few tens of percent of the steady one's distance.
        let (dg, dc) = (g[2].hypot(g[3]), c[2].hypot(c[3]));
        assert!(
            (dg / dc - 1.0).abs() < 0.3,
            "row {r}: {dg} m against {dc} m"
        );
    }
    // Row 0 flown alone: its design, motor, site, rail, drag scale, parachute and seed.
    let f = turbulent_by_hand(gusty[0][0], 0.1, seeds[0]);
    assert_eq!(
        Some([gusty[0][2], gusty[0][3]]),
        f.metrics.landing_position_m
    );
    assert_eq!(f.metrics.apogee_m, Some(gusty[0][1]));
}

#[test]
fn a_turbulence_intensity_outside_0_to_1_is_refused_by_key() {
    for bad in ["-0.1", "1.5", "nan"] {
        let text = windy(
            &format!("wind_speed_m_s = 6.0\nwind_turbulence_intensity = {bad}"),
            "drag_scale = [1.0]",
        );
        let err = refusal(&text);
        assert!(
            err.contains("environment.wind_turbulence_intensity")
                && err.contains("must be between 0 and 1"),
            "{err}"
        );
    }
    // The gusts are drawn to the time limit before a flight starts: at most two hours of them.
    let long = windy(
        "wind_speed_m_s = 6.0\nwind_turbulence_intensity = 0.1",
        "drag_scale = [1.0]",
    )
    .replace("max_time_s = 900.0", "max_time_s = 7200.5");
    let err = refusal(&long);
    assert!(
        err.contains("integrator.max_time_s") && err.contains("at most 7200 s in a turbulent wind"),
        "{err}"
    );
    assert!(refusal_free(&long.replace("7200.5", "7200.0")));
    // A swept intensity counts too, though the scenario's own wind is steady.
    let swept = windy(
        "wind_speed_m_s = 6.0",
        "wind_turbulence_intensity = [0.0, 0.1]",
    )
    .replace("max_time_s = 900.0", "max_time_s = 7200.5");
    assert!(refusal(&swept).contains("integrator.max_time_s"));
    let err = refusal(&windy(
        "wind_speed_m_s = 6.0",
        "wind_turbulence_intensity = [0.0, 1.2]",
    ));
    assert!(err.contains("sweep.wind_turbulence_intensity"), "{err}");
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    let (code, _, err) = hpr_mc(&[
        "fly",
        design.to_str().unwrap(),
        "--wind-turbulence-intensity",
        "2",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--wind-turbulence-intensity"), "{err}");
}

/// Whether the scenario `text` loads (its flights not flown).
fn refusal_free(text: &str) -> bool {
    let (_dir, file) = setup(text);
    hpr_mc::campaign::scenario::Scenario::load(&file).is_ok()
}

/// [`windy`]'s flight in a 6 m/s wind from 250° of turbulence `intensity`, set up by hand with
/// drag scale `drag` and noise seed `seed`.
fn turbulent_by_hand(drag: f64, intensity: f64, seed: u64) -> hpr_sim::Flight {
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    let wind = Wind::constant(6.0, 250.0)
        .and_then(|w| w.with_turbulence(intensity))
        .unwrap();
    hpr_sim::Simulation::new(
        hpr_design::Design::load(&design).unwrap(),
        hpr_design::motor::find("Cesaroni_I175").unwrap(),
        Environment {
            wind,
            ..Environment::default()
        },
        hpr_sim::Rail {
            inclination_deg: 85.0,
            ..hpr_sim::Rail::default()
        },
    )
    .and_then(|s| s.with_parachutes(vec![Parachute::new("main", 0.9, Trigger::Apogee, 1.0)]))
    .and_then(|s| s.with_drag_scale(drag))
    .and_then(|s| {
        s.with_options(hpr_sim::SimOptions {
            max_time_s: 900.0,
            ..hpr_sim::SimOptions::default()
        })
    })
    .unwrap()
    .with_sensor_seed(seed)
    .run(&mut ())
    .unwrap()
}

#[test]
fn a_swept_turbulence_intensity_is_a_column_and_each_row_its_flight_by_hand() {
    // Swept from a steady wind: 0 (no gusts) and 0.2; each row is the flight set up by hand
    // with its intensity, drag scale and seed.
    let text = windy(
        "wind_speed_m_s = 6.0\nwind_from_deg = 250.0",
        "wind_turbulence_intensity = [0.0, 0.2]",
    );
    let (dir, file) = setup(&text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    assert_eq!(report.landed, report.variants);
    let b = read(&report.outputs.variants);
    // A sensor_seed column when the turbulence is swept.
    let seeds = u64s(&b, "sensor_seed").values().to_vec();
    let intensity = f64s(&b, "wind_turbulence_intensity").values().to_vec();
    let (drag, x, y) = (
        f64s(&b, "drag_scale").values().to_vec(),
        f64s(&b, "landing_x_m").values().to_vec(),
        f64s(&b, "landing_y_m").values().to_vec(),
    );
    assert_eq!(intensity.iter().filter(|&&i| i == 0.0).count(), 4);
    assert_eq!(intensity.iter().filter(|&&i| i == 0.2).count(), 4);
    for r in 0..intensity.len() {
        let f = turbulent_by_hand(drag[r], intensity[r], seeds[r]);
        assert_eq!(f.metrics.landing_position_m, Some([x[r], y[r]]), "row {r}");
    }
}
