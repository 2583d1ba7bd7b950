//! A weather-model file in a campaign: each variant's launch time and ensemble member flown in
//! the file's air and wind at them, and the rules of what a scenario may ask of the file.

use super::*;
use hpr_sim::weather::{parse_utc, SiteWeather};
use hpr_sim::{AirModel, Environment, Parachute, Trigger};

/// The three-member ensemble made from Bella Lui's ERA5 file
/// (`validation/weather/make_weather_files.py`), by its absolute path; its longitudes are
/// relabelled 340 degrees east, so the site is asked for at 9.003336 − 20 degrees.
fn ensemble() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/weather/bella_lui_ensemble.nc")
        .display()
        .to_string()
}

const SITE: &str = "elevation_m = 407.0\nlatitude_deg = 47.213476\nlongitude_deg = -10.996664";

fn weather_lines(extra: &str) -> String {
    format!(
        "{SITE}\nweather = {{ file = {:?}, time = \"2020-02-22T13:00Z\"{extra} }}",
        ensemble()
    )
}

#[test]
fn each_variant_flies_the_weather_file_s_air_and_wind_at_its_own_launch_time_and_member() {
    // Launch times swept over 13:00 and 15:30 UTC, members drawn uniformly from the
    // ensemble's three: every row is the simulator set up by hand in the air and wind the
    // file gives over the site at that row's time and member, to rounding.
    let text = windy(&weather_lines(""), "launch_time_h = [0.0, 2.5]").replace(
        "[dispersions]\n",
        "[dispersions]\nweather_member = { dist = \"members\" }\n",
    );
    let rows = landed_rows(
        &text,
        [
            "launch_time_h",
            "weather_member",
            "drag_scale",
            "apogee_m",
            "landing_x_m",
            "landing_y_m",
        ],
    );
    assert_eq!(rows.len(), 8, "two launch times, four variants each");
    let members: std::collections::BTreeSet<u64> = rows.iter().map(|r| r[1] as u64).collect();
    assert!(
        members.len() >= 2,
        "the draws span the members: {members:?}"
    );
    assert!(rows.iter().all(|r| [0.0, 1.0, 2.0].contains(&r[1])));
    let site = SiteWeather::read(Path::new(&ensemble()), 47.213476, -10.996664).unwrap();
    let noon = parse_utc("2020-02-22T13:00Z").unwrap();
    let envs: Vec<Environment> = rows
        .iter()
        .map(|r| {
            let member = site.member_index(r[1]).unwrap();
            let air = site.over_site(noon + r[0] * 3600.0, member, 407.0).unwrap();
            Environment {
                elevation_m: 407.0,
                wind: air.wind().unwrap(),
                air: air.air_model(),
                latitude_deg: Some(47.213476),
                ..Environment::default()
            }
        })
        .collect();
    let flown: Vec<[f64; 4]> = rows.iter().map(|r| [r[2], r[3], r[4], r[5]]).collect();
    let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0);
    assert_rows_flown_by_hand_in(&flown, &envs, &chute);
    // Member 2's wind is 1.2 times member 0's: its rows drift further.
    let drift = |m: f64| {
        let d: Vec<f64> = rows
            .iter()
            .filter(|r| r[1] == m && r[0] == 0.0)
            .map(|r| r[4].hypot(r[5]))
            .collect();
        (!d.is_empty()).then(|| d.iter().sum::<f64>() / d.len() as f64)
    };
    eprintln!(
        "drift at 13:00 by member: {:?} {:?} {:?}",
        drift(0.0),
        drift(1.0),
        drift(2.0)
    );
    if let (Some(calm), Some(windy)) = (drift(0.0), drift(2.0)) {
        assert!(windy > calm * 1.1, "{windy} against {calm}");
    }
}

#[test]
fn fly_with_a_weather_file_flies_what_the_bella_lui_scenario_flies_and_refuses_what_it_lacks() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let at = |p: &str| root.join(p).display().to_string();
    let (code, scenario, err) = hpr_mc(&[
        "fly",
        "--scenario",
        &at("scenarios/bella_lui.toml"),
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let era5 = at("validation/real-flights/bella-lui/bella_lui_weather_data_ERA5.nc");
    let eng = at("validation/real-flights/bella-lui/AeroTech_K828FJ.eng");
    let design = at("validation/designs/bella-lui.json");
    let mut args = vec![
        "fly",
        &design,
        "--json",
        "--motor",
        &eng,
        "--motor-burn-time-s",
        "2.43",
        "--motor-diameter-m",
        "0.098",
        "--motor-dry-mass-kg",
        "0.001",
        "--motor-dry-inertia-kg-m2",
        "0,0",
        "--motor-propellant-center-from-nozzle-m",
        "0.3",
        "--motor-nozzle-radius-m",
        "0.04445",
        "--motor-grains",
        "3,782.4,0.042799,0.033147,0.1524,0.003",
        "--weather",
        &era5,
        "--latitude-deg",
        "47.213476",
        "--longitude-deg",
        "9.003336",
        "--elevation-m",
        "407",
        "--launch-time",
        "2020-02-22T14:00+01:00",
        "--gravity",
        "9.81",
        "--rail-length-m",
        "4.2",
        "--inclination-deg",
        "89",
        "--heading-deg",
        "45",
        "--drogue-cds-m2",
        "0.7853981633974483",
        "--lag-s",
        "1",
        "--sampling-rate-hz",
        "105",
    ];
    let (code, flags, err) = hpr_mc(&args);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("the air and wind of 2020-02-22T13:00:00Z"),
        "{err}"
    );
    let apogee = |out: &str| {
        let v: serde_json::Value = serde_json::from_str(out).unwrap();
        v["metrics"]["apogee_m"].as_f64().unwrap()
    };
    assert_eq!(apogee(&scenario), apogee(&flags));
    // A launch after the file's last time, and one without its zone.
    let late = args
        .iter()
        .position(|a| *a == "2020-02-22T14:00+01:00")
        .unwrap();
    args[late] = "2020-02-22T19:00Z";
    let (code, _, err) = hpr_mc(&args);
    assert_eq!(code, 2);
    assert!(
        err.contains("--weather") && err.contains("the launch time 2020-02-22T19:00:00Z is outside the file's times (2020-02-22T00:00:00Z to 2020-02-22T18:00:00Z)"),
        "{err}"
    );
    args[late] = "2020-02-22T13:00";
    let (code, _, err) = hpr_mc(&args);
    assert_eq!(code, 2);
    assert!(
        err.contains("--launch-time") && err.contains("no time zone"),
        "{err}"
    );
    // --weather without the site's longitude: clap names what is missing.
    let (code, _, err) = hpr_mc(&[
        "fly",
        &design,
        "--weather",
        &era5,
        "--latitude-deg",
        "47.2",
        "--elevation-m",
        "407",
        "--launch-time",
        "2020-02-22T13:00Z",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--longitude-deg"), "{err}");
}

#[test]
fn a_weather_file_s_nominal_flight_is_its_air_and_wind_rows_written_out_by_hand() {
    // `weather = {...}`: the same rows as a scenario whose air_profile (with each level's
    // pressure), pressure_pa and wind_profile are the file's over the site, written out.
    let site = SiteWeather::read(Path::new(&ensemble()), 47.213476, -10.996664).unwrap();
    let noon = parse_utc("2020-02-22T13:00Z").unwrap();
    let air = site.over_site(noon, 1, 407.0).unwrap();
    let rows: Vec<String> = air
        .air
        .rows
        .iter()
        .map(|r| match r.pressure_pa {
            Some(p) => format!(
                "{{ height_m = {:?}, temperature_k = {:?}, pressure_pa = {p:?} }}",
                r.height_m, r.temperature_k
            ),
            None => format!(
                "{{ height_m = {:?}, temperature_k = {:?} }}",
                r.height_m, r.temperature_k
            ),
        })
        .collect();
    let wind: Vec<String> = air
        .wind
        .iter()
        .map(|r| {
            format!(
                "{{ height_m = {:?}, speed_m_s = {:?}, from_deg = {:?} }}",
                r.height_agl_m, r.speed_m_s, r.from_deg
            )
        })
        .collect();
    let by_hand = format!(
        "{SITE}\npressure_pa = {:?}\nair_profile = [{}]\nwind_profile = [{}]",
        air.air.pressure_pa,
        rows.join(", "),
        wind.join(", ")
    );
    let names = ["drag_scale", "apogee_m", "landing_x_m", "landing_y_m"];
    let read = landed_rows(
        &windy(&weather_lines(", member = 1"), "drag_scale = [1.0]"),
        names,
    );
    let written = landed_rows(&windy(&by_hand, "drag_scale = [1.0]"), names);
    assert_eq!(read, written);
    assert!(matches!(air.air_model(), AirModel::Profile(_)));
}

#[test]
fn what_a_scenario_asks_of_a_weather_file_that_it_cannot_give_is_refused_naming_the_key() {
    let cases: Vec<(String, &str, &str)> = vec![
        (
            windy(
                &format!(
                    "elevation_m = 407.0\nlatitude_deg = 47.2\nweather = {{ file = {:?}, time = \"2020-02-22T13:00Z\" }}",
                    ensemble()
                ),
                "drag_scale = [1.0]",
            ),
            "environment.longitude_deg",
            "is needed with environment.weather",
        ),
        (
            windy(
                &format!(
                    "{SITE}\nweather = {{ file = {:?}, time = \"2020-02-23T13:00Z\" }}",
                    ensemble()
                ),
                "drag_scale = [1.0]",
            ),
            "environment.weather.time",
            "outside the file's times (2020-02-22T00:00:00Z to 2020-02-22T18:00:00Z)",
        ),
        (
            windy(
                &format!(
                    "{SITE}\nweather = {{ file = {:?}, time = \"2020-02-22T13:00\" }}",
                    ensemble()
                ),
                "drag_scale = [1.0]",
            ),
            "environment.weather.time",
            "no time zone",
        ),
        (
            windy(&weather_lines(", member = 7"), "drag_scale = [1.0]"),
            "environment.weather.member",
            "ensemble member 7 is not in the file (its members: 0 to 2)",
        ),
        (
            windy(
                &format!("{}\nwind_speed_m_s = 3.0", weather_lines("")),
                "drag_scale = [1.0]",
            ),
            "environment.weather",
            "give either it or environment.wind_speed_m_s",
        ),
        (
            windy(&weather_lines(""), "launch_time_h = [0.0, 6.0]"),
            "sweep.launch_time_h[1]",
            "outside the weather file: the file's times are -13 to 5 h after",
        ),
        (
            windy(&weather_lines(""), "drag_scale = [1.0]").replace(
                "[dispersions]\n",
                "[dispersions]\nlaunch_time_h = { dist = \"uniform\", min = -1.0, max = 8.0 }\n",
            ),
            "dispersions.launch_time_h.max",
            "outside the weather file",
        ),
        (
            windy(&weather_lines(""), "drag_scale = [1.0]").replace(
                "[dispersions]\n",
                "[dispersions]\nweather_member = { dist = \"normal\", sigma = 1.0 }\n",
            ),
            "dispersions.weather_member.dist",
            "dist = \"members\"",
        ),
        (
            windy("wind_speed_m_s = 3.0", "launch_time_h = [0.0, 1.0]"),
            "sweep.launch_time_h",
            "needs environment.weather",
        ),
        (
            windy(&weather_lines(""), "launch_time_h = [0.0, 1.0]").replace(
                "[dispersions]\n",
                "[dispersions]\ntemperature_k = { dist = \"normal\", sigma = 2.0 }\n",
            ),
            "dispersions.temperature_k",
            "the site's air is the weather file's at each variant's launch_time_h",
        ),
        (
            windy(&weather_lines(""), "drag_scale = [1.0]").replace(
                "[dispersions]\n",
                "[dispersions]\nwind_scale = { dist = \"members\" }\n",
            ),
            "dispersions.wind_scale.dist",
            "\"members\" draws a weather file's ensemble member",
        ),
    ];
    for (text, key, rule) in cases {
        let e = refusal(&text);
        assert!(
            e.contains(&format!(": {key}: ")) && e.contains(rule),
            "{key}: {e}"
        );
    }
}

#[test]
fn a_constant_gravity_and_a_cut_thrust_curve_are_taken_and_their_bad_values_refused() {
    // gravity = 9.81 flies lower than the standard 9.80665 only by the difference: the
    // scenario reads; gravity = 0 and a name that is no model are refused with the rule; a
    // burn time past the curve's burnout is refused naming motor.burn_time_s.
    let ok = windy("gravity = 9.81", "drag_scale = [1.0]");
    let (dir, file) = setup(&ok);
    run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    for (gravity, got) in [("0.0", "got 0"), ("\"earth\"", "got \"earth\"")] {
        let e = refusal(&windy(
            &format!("gravity = {gravity}"),
            "drag_scale = [1.0]",
        ));
        assert!(
            e.contains("environment.gravity: must be \"standard\", \"inverse_square\", \"somigliana\" or a constant value in m/s²")
                && e.contains(got),
            "{e}"
        );
    }
    let e = refusal(
        &windy("wind_speed_m_s = 3.0", "drag_scale = [1.0]").replace(
            "name = \"Cesaroni_I175\"",
            "name = \"Cesaroni_I175\"\nburn_time_s = 9.0",
        ),
    );
    assert!(
        e.contains(": motor.burn_time_s: ")
            && e.contains("no later than the thrust curve's burnout"),
        "{e}"
    );
}
