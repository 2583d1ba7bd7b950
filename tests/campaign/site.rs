//! The launch site's latitude, its gravity and its air through a whole campaign: the rows are
//! the flights `Simulation` flies with the same site set up by hand.

use super::*;
use hpr_sim::gravity::Gravity;
use hpr_sim::wind::Wind;
use hpr_sim::{AirModel, Environment, Parachute, Trigger};

const SITE: &str = "elevation_m = 1200.0\nlatitude_deg = 40.0\ngravity = \"somigliana\"\nwind_speed_m_s = 4.0\nwind_from_deg = 250.0\ntemperature_k = 305.0\npressure_pa = 86500.0";

#[test]
fn a_scenario_s_latitude_ellipsoid_gravity_and_measured_air_fly_as_the_simulator_set_up_by_hand() {
    let campaign = drag_apogee_landing(&windy(SITE, "drag_scale = [1.0]"));
    let env = Environment {
        elevation_m: 1200.0,
        wind: Wind::constant(4.0, 250.0).unwrap(),
        gravity: Gravity::somigliana(40.0, 1200.0).unwrap(),
        latitude_deg: Some(40.0),
        vacuum: false,
        air: AirModel::site(1200.0, Some(305.0), Some(86_500.0)).unwrap(),
    };
    let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0);
    assert_rows_flown_by_hand(&campaign, &env, &chute);
    // Without the latitude the Earth stands still: the same rows land elsewhere (Coriolis
    // moves a 1 km flight by metres) and, with standard gravity, climb differently.
    let still = drag_apogee_landing(&windy(
        &SITE.replace("latitude_deg = 40.0\ngravity = \"somigliana\"\n", ""),
        "drag_scale = [1.0]",
    ));
    let moved = (campaign[0][2] - still[0][2]).hypot(campaign[0][3] - still[0][3]);
    eprintln!(
        "latitude 40° and its gravity: apogee {:.3} m against {:.3} m, landing moved {moved:.3} m",
        campaign[0][1], still[0][1]
    );
    assert!(moved > 0.3, "{moved} m");
    assert!((campaign[0][1] - still[0][1]).abs() > 0.5);
    // The site's air, 305 K at 86.5 kPa (0.988 kg/m³) against the standard's 280.35 K at
    // 87.7 kPa (1.090 kg/m³) at 1200 m: the thinner air drags less, the rocket climbs higher.
    let standard_air = drag_apogee_landing(&windy(
        &SITE.replace("\ntemperature_k = 305.0\npressure_pa = 86500.0", ""),
        "drag_scale = [1.0]",
    ));
    eprintln!(
        "the site's air: apogee {:.3} m against {:.3} m in the standard atmosphere",
        campaign[0][1], standard_air[0][1]
    );
    assert!(campaign[0][1] > standard_air[0][1] + 10.0);
}

#[test]
fn a_swept_site_temperature_and_a_dispersed_site_pressure_fly_each_row_in_its_own_air() {
    // The standard atmosphere at 1200 m (280.35 K, 87.7 kPa), its temperature swept over a
    // cold and a hot day and its pressure dispersed: each row is the simulator set up by hand
    // in the air of that site at the row's temperature and pressure, to rounding, and the
    // hot day's thinner air lets the rocket climb higher.
    let text = windy(
        "elevation_m = 1200.0\nwind_speed_m_s = 4.0\nwind_from_deg = 250.0",
        "temperature_k = [263.15, 308.15]",
    )
    .replace(
        "[dispersions]\n",
        "[dispersions]\npressure_pa = { dist = \"normal\", sigma = 800.0 }\n",
    );
    let rows = landed_rows(
        &text,
        [
            "temperature_k",
            "pressure_pa",
            "drag_scale",
            "apogee_m",
            "landing_x_m",
            "landing_y_m",
        ],
    );
    assert_eq!(rows.len(), 8, "two temperatures, four variants each");
    let envs: Vec<Environment> = rows
        .iter()
        .map(|r| Environment {
            elevation_m: 1200.0,
            wind: Wind::constant(4.0, 250.0).unwrap(),
            air: AirModel::site(1200.0, Some(r[0]), Some(r[1])).unwrap(),
            ..Environment::default()
        })
        .collect();
    let flown: Vec<[f64; 4]> = rows.iter().map(|r| [r[2], r[3], r[4], r[5]]).collect();
    let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0);
    assert_rows_flown_by_hand_in(&flown, &envs, &chute);
    let pressures: Vec<f64> = rows.iter().map(|r| r[1]).collect();
    assert!(
        pressures.windows(2).any(|w| w[0] != w[1]),
        "the pressure is dispersed: {pressures:?}"
    );
    let mean = |t: f64| {
        let a: Vec<f64> = rows.iter().filter(|r| r[0] == t).map(|r| r[3]).collect();
        assert_eq!(a.len(), 4);
        a.iter().sum::<f64>() / 4.0
    };
    let (cold, hot) = (mean(263.15), mean(308.15));
    eprintln!("apogee at 263.15 K: {cold:.2} m, at 308.15 K: {hot:.2} m");
    // Density falls as 1/T at one pressure: 15 % thinner on the hot day.
    assert!(hot > cold + 20.0, "{hot} against {cold}");
}

#[test]
fn a_site_temperature_outside_the_air_s_range_is_refused_naming_the_sweep() {
    let text = windy(
        "elevation_m = 1200.0\nwind_speed_m_s = 4.0\nwind_from_deg = 250.0",
        "temperature_k = [288.15, 400.0]",
    );
    let err = refusal(&text);
    assert!(err.contains("sweep.temperature_k"), "{err}");
    assert!(err.contains("must be from 150 to 350"), "{err}");
}

/// The site model's air above (1200 m, 305 K, 86.5 kPa, linear to 216.65 K at 11 km
/// geopotential) written as an air profile of two rows.
fn site_as_profile() -> String {
    let top = hpr_sim::atmosphere::geometric_altitude_m(11_000.0) - 1200.0;
    SITE.replace(
        "temperature_k = 305.0\n",
        &format!(
            "air_profile = [\n  {{ height_m = 0.0, temperature_k = 305.0 }},\n  {{ height_m = {top:?}, temperature_k = 216.65 }},\n]\n"
        ),
    )
}

#[test]
fn an_air_profile_through_the_site_model_s_temperatures_flies_as_the_site_model() {
    // The same air to 1e-12 below 20 km (the atmosphere's own test), so the same flights to
    // what that moves: 1e-9 of the apogee and of the landing's offsets (measured: 0, the two
    // build the same first layer bit for bit).
    let site = drag_apogee_landing(&windy(SITE, "drag_scale = [1.0]"));
    let profile = drag_apogee_landing(&windy(&site_as_profile(), "drag_scale = [1.0]"));
    assert_eq!(site.len(), profile.len());
    let mut worst = 0.0f64;
    for (a, b) in site.iter().zip(&profile) {
        for k in 1..4 {
            worst = worst.max((a[k] - b[k]).abs() / a[1].abs());
        }
    }
    eprintln!("air profile against the site model: worst {worst:.1e} of the apogee");
    assert!(worst < 1e-9, "{worst:e}");
    // A profile of a cold layer aloft (the same site, 10 K colder from 500 m up) is denser
    // there: the rocket climbs less.
    let cold = SITE.replace(
        "temperature_k = 305.0\n",
        "air_profile = [\n  { height_m = 0.0, temperature_k = 305.0 },\n  { height_m = 500.0, temperature_k = 291.0 },\n  { height_m = 3000.0, temperature_k = 275.0 },\n]\n",
    );
    let cold = drag_apogee_landing(&windy(&cold, "drag_scale = [1.0]"));
    eprintln!(
        "a cold layer aloft: apogee {:.2} m against {:.2} m",
        cold[0][1], site[0][1]
    );
    assert!(cold[0][1] < site[0][1] - 1.0);
}

#[test]
fn an_air_profile_refuses_a_site_temperature_beside_it_and_its_bad_rows_by_index() {
    let profile = site_as_profile();
    let beside = profile.replace("pressure_pa", "temperature_k = 290.0\npressure_pa");
    let err = refusal(&windy(&beside, "drag_scale = [1.0]"));
    assert!(err.contains("environment.temperature_k"), "{err}");
    assert!(err.contains("air_profile's first row"), "{err}");
    let bad = profile.replace("temperature_k = 216.65", "temperature_k = 420.0");
    let err = refusal(&windy(&bad, "drag_scale = [1.0]"));
    assert!(
        err.contains("environment.air_profile[1].temperature_k") && err.contains("350"),
        "{err}"
    );
    let first = profile.replace("height_m = 0.0,", "height_m = 5.0,");
    let err = refusal(&windy(&first, "drag_scale = [1.0]"));
    assert!(err.contains("environment.air_profile[0].height_m"), "{err}");
}

#[test]
fn a_swept_site_temperature_moves_an_air_profile_whole_and_each_row_flies_in_its_own_air() {
    // A profile of an inversion (warmer 400 m up) over a 1200 m site at 87 kPa, its site
    // temperature swept over 285 and 305 K: each row is the simulator set up by hand with
    // every row of the profile moved by the sweep's change, and the warmer day climbs higher.
    let text = windy(
        "elevation_m = 1200.0\nwind_speed_m_s = 4.0\nwind_from_deg = 250.0\npressure_pa = 87000.0\nair_profile = [\n  { height_m = 0.0, temperature_k = 290.0 },\n  { height_m = 400.0, temperature_k = 293.0 },\n  { height_m = 2500.0, temperature_k = 278.0 },\n]",
        "temperature_k = [285.0, 305.0]",
    );
    let rows = landed_rows(
        &text,
        [
            "temperature_k",
            "drag_scale",
            "apogee_m",
            "landing_x_m",
            "landing_y_m",
        ],
    );
    assert_eq!(rows.len(), 8, "two temperatures, four variants each");
    let envs: Vec<Environment> = rows
        .iter()
        .map(|r| {
            let shift = r[0] - 290.0;
            let row = |height_m: f64, t: f64| hpr_sim::atmosphere::AirRow {
                height_m,
                temperature_k: t + shift,
                pressure_pa: None,
            };
            Environment {
                elevation_m: 1200.0,
                wind: Wind::constant(4.0, 250.0).unwrap(),
                air: AirModel::Profile(std::sync::Arc::new(hpr_sim::atmosphere::AirProfile {
                    elevation_m: 1200.0,
                    pressure_pa: 87_000.0,
                    rows: vec![row(0.0, 290.0), row(400.0, 293.0), row(2500.0, 278.0)],
                })),
                ..Environment::default()
            }
        })
        .collect();
    let flown: Vec<[f64; 4]> = rows.iter().map(|r| [r[1], r[2], r[3], r[4]]).collect();
    let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0);
    assert_rows_flown_by_hand_in(&flown, &envs, &chute);
    let mean = |t: f64| {
        let a: Vec<f64> = rows.iter().filter(|r| r[0] == t).map(|r| r[2]).collect();
        assert_eq!(a.len(), 4);
        a.iter().sum::<f64>() / 4.0
    };
    let (cold, warm) = (mean(285.0), mean(305.0));
    eprintln!("profile moved to 285 K: apogee {cold:.2} m, to 305 K: {warm:.2} m");
    assert!(warm > cold + 10.0, "{warm} against {cold}");
}

/// The synthetic Wyoming listing (`validation/soundings/synthetic-wyoming.txt`), by its
/// absolute path.
fn sounding_path() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/soundings/synthetic-wyoming.txt")
        .display()
        .to_string()
}

#[test]
fn a_scenario_s_sounding_flies_as_its_air_and_wind_rows_written_out_by_hand() {
    // `sounding = "..."` with no elevation: the site is the sounding's ground (its lowest
    // level with a temperature and a pressure, 1400 m geopotential), the air its temperature
    // rows above the site with its pressure there, the wind its rows. The same scenario with
    // those rows written into `air_profile`, `pressure_pa` and `wind_profile` flies the same
    // rows bit for bit, and so does a swept temperature (which shifts every row of both).
    let path = sounding_path();
    let sounding =
        hpr_sim::sounding::Sounding::parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let site = sounding.surface_m().unwrap();
    let air = sounding.air_profile(site).unwrap();
    let wind = sounding.wind_rows(site).unwrap();
    let air_rows: Vec<String> = air
        .rows
        .iter()
        .map(|r| {
            format!(
                "{{ height_m = {:?}, temperature_k = {:?} }}",
                r.height_m, r.temperature_k
            )
        })
        .collect();
    let wind_rows: Vec<String> = wind
        .iter()
        .map(|r| {
            format!(
                "{{ height_m = {:?}, speed_m_s = {:?}, from_deg = {:?} }}",
                r.height_agl_m, r.speed_m_s, r.from_deg
            )
        })
        .collect();
    let by_hand = format!(
        "elevation_m = {site:?}\npressure_pa = {:?}\nair_profile = [{}]\nwind_profile = [{}]",
        air.pressure_pa,
        air_rows.join(", "),
        wind_rows.join(", ")
    );
    let names = ["drag_scale", "apogee_m", "landing_x_m", "landing_y_m"];
    for sweep in ["drag_scale = [1.0]", "temperature_k = [300.0, 310.0]"] {
        let read = landed_rows(&windy(&format!("sounding = {path:?}"), sweep), names);
        let written = landed_rows(&windy(&by_hand, sweep), names);
        assert_eq!(read, written, "{sweep}");
        eprintln!(
            "{sweep}: through the sounding, apogee {:.2} m, landing ({:.1}, {:.1}) m",
            read[0][1], read[0][2], read[0][3]
        );
    }
    // Given an elevation between levels, the site moves up into the sounding: a higher,
    // cooler site with less air above it.
    let higher = landed_rows(
        &windy(
            &format!("sounding = {path:?}\nelevation_m = 1600.0"),
            "drag_scale = [1.0]",
        ),
        names,
    );
    let ground = landed_rows(
        &windy(&format!("sounding = {path:?}"), "drag_scale = [1.0]"),
        names,
    );
    assert!(higher[0][1] != ground[0][1]);
}

#[test]
fn a_sounding_is_refused_beside_the_air_or_wind_it_gives_and_when_it_cannot_be_read() {
    let path = sounding_path();
    for other in [
        "temperature_k = 300.0",
        "pressure_pa = 86000.0",
        "wind_speed_m_s = 4.0",
        "wind_profile = [{ height_m = 0.0, speed_m_s = 3.0, from_deg = 90.0 }]",
    ] {
        let err = refusal(&windy(
            &format!("sounding = {path:?}\n{other}"),
            "drag_scale = [1.0]",
        ));
        let field = other.split(' ').next().unwrap();
        assert!(
            err.contains("environment.sounding") && err.contains(&format!("environment.{field}")),
            "{err}"
        );
    }
    let err = refusal(&windy(
        "sounding = \"no-such-sounding.txt\"",
        "drag_scale = [1.0]",
    ));
    assert!(
        err.contains("environment.sounding") && err.contains("cannot read"),
        "{err}"
    );
    // A site below the sounding's ground.
    let err = refusal(&windy(
        &format!("sounding = {path:?}\nelevation_m = 500.0"),
        "drag_scale = [1.0]",
    ));
    assert!(
        err.contains("environment.sounding") && err.contains("outside the sounding's temperatures"),
        "{err}"
    );
    // A file that is not a listing.
    let dir = tempfile::tempdir().unwrap();
    let junk = dir.path().join("junk.txt");
    std::fs::write(&junk, "not a sounding\n").unwrap();
    let err = refusal(&windy(
        &format!("sounding = {:?}", junk.display().to_string()),
        "drag_scale = [1.0]",
    ));
    assert!(err.contains("no table of levels"), "{err}");
}
