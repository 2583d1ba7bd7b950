//! A radiosonde sounding reaches the flight as RocketPy reads the same file.
//!
//! `validation/rocketpy/sounding_crosscheck.py` handed RocketPy 1.13 the bundled synthetic
//! Wyoming listing (`validation/soundings/synthetic-wyoming.txt`) through its own
//! `wyoming_sounding` reader, recorded its air and wind every 50 m to 8 km over the site, and
//! flew `crosscheck.rs`'s elliptical-finned rocket (102 mm, L1115, to 4 km) through it with
//! its lever arm corrected. hpr-mc reads the file with `hpr_sim::sounding` at the same site
//! (RocketPy's: the station's listed 1400.0 m) and flies the same rocket, mapped as
//! `crosscheck.rs` maps it.
//!
//! Where they differ by design (`hpr_sim::sounding`'s docs): RocketPy interpolates the
//! listing's pressures linearly in height between levels, hpr-mc carries the site's up
//! hydrostatically through the temperatures, which meets the listed pressures at the levels
//! (to their 0.1 hPa rounding) and bends between them as the true pressure does; RocketPy's
//! is high between levels by up to (Δz/H)²/8 of itself, 3e-4 for levels 400 m apart. The
//! tolerances below say which figure allows what.

use crate::crosscheck::{
    check, crosscheck_simulation, fly_simulation, hand_picked, num, Tolerances,
    APOGEE_POSITION_TOL_M,
};
use hpr_sim::atmosphere::{geometric_altitude_m, AirModel, Atmosphere};
use hpr_sim::sounding::Sounding;
use hpr_sim::wind::Wind;
use serde_json::Value;
use std::sync::Arc;

fn read(file: &str) -> Value {
    let path = crate::common::repo(file);
    serde_json::from_str(&std::fs::read_to_string(path).expect("reference")).expect("JSON")
}

fn sounding(rp: &Value) -> Sounding {
    let path = crate::common::repo(rp["sounding"].as_str().unwrap());
    Sounding::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn a_sounding_s_air_and_wind_over_the_site_are_rocketpys_reading_of_the_same_file() {
    // RocketPy 1.13 reads the listing's temperatures and pressures at its geopotential
    // heights taken as geometric (it converts the heights only for the wind): its air at
    // geometric height z is the sounding's at geopotential height z, which hpr-mc (reading
    // the heights as the listing means them) has at geometric height Z(z) = r0 z / (r0 − z).
    // Compared there, the two readings are the same numbers; the wind, which RocketPy reads
    // at geometric heights, is compared where it is.
    let rp = read("validation/rocketpy/sounding_crosscheck_reference.json");
    let site = num(&rp, "/site_elevation_m");
    let s = sounding(&rp);
    let air = Atmosphere::new(
        site,
        &AirModel::Profile(Arc::new(s.air_profile(site).unwrap())),
    )
    .unwrap();
    let wind = Wind::table(&s.wind_rows(site).unwrap()).unwrap();
    let mut worst = [0.0f64; 5];
    let mut shifted_t: f64 = 0.0;
    for row in rp["air"].as_array().unwrap() {
        let h = num(row, "/height_m");
        let ours = air.at_msl(geometric_altitude_m(site + h));
        let [e, n] = wind.velocity_en(h);
        let diffs = [
            (ours.temperature_k - num(row, "/temperature_k")).abs(),
            (ours.pressure_pa / num(row, "/pressure_pa") - 1.0).abs(),
            (ours.density_kg_m3 / num(row, "/density_kg_m3") - 1.0).abs(),
            (ours.speed_of_sound_m_s - num(row, "/speed_of_sound_m_s")).abs(),
            (e - num(row, "/wind_east_m_s"))
                .abs()
                .max((n - num(row, "/wind_north_m_s")).abs()),
        ];
        for (w, d) in worst.iter_mut().zip(diffs) {
            *w = w.max(d);
        }
        shifted_t = shifted_t.max((air.at(h).temperature_k - num(row, "/temperature_k")).abs());
    }
    let [t, p, rho, a, w] = worst;
    eprintln!(
        "0 to 8 km over the site, RocketPy's heights read as it reads them: temperature within \
         {t:.1e} K, pressure {p:.1e}, density {rho:.1e}, speed of sound {a:.1e} m/s, wind \
         {w:.1e} m/s (compared at the same geometric heights instead, the temperatures are \
         {shifted_t:.3} K apart at 8 km)"
    );
    // Temperatures: both linear in geopotential height between levels.
    assert!(t < 1e-9, "temperature {t} K");
    // RocketPy's speed of sound is √(γRT) at the levels and linear between them, below the
    // square root's curve by up to (ΔT/T)²/16 of itself, 2.4e-3 m/s where a level's 3.6 K
    // change meets 400 m spacing (checked in RocketPy: exact at 1550 m, 5.7e-4 m/s low
    // midway to 1400 m).
    assert!(a < 3e-3, "speed of sound {a} m/s");
    // Pressures: RocketPy's linear between levels against hpr's hydrostatic, (Δz/H)²/8 =
    // 3.1e-4 apart at most between levels 400 m apart, plus the listing's 0.05 hPa rounding
    // (1e-4 at 500 hPa): 4e-4. Density is pressure over temperature in both.
    assert!(p < 4e-4, "pressure {p}");
    assert!(rho < 4e-4, "density {rho}");
    // The wind: both interpolate the components linearly in geometric height, converted
    // from geopotential with RocketPy's Earth radius at the site's latitude (6,371.8 km) and
    // the standard's r0 (6,356.8 km): 2 cm apart at 8 km, 1.3e-4 m/s of the jet's shear.
    assert!(w < 2e-4, "wind {w} m/s");
    // And RocketPy's reading is not the listing's meaning, by what the heights say: at 8 km
    // the geopotential and geometric heights are 14 m apart, 0.13 K of this lapse rate.
    assert!(shifted_t > 0.05);
}

#[test]
fn the_elliptical_finned_rocket_flies_through_a_sounding_as_rocketpy_flies_it() {
    let rp = read("validation/rocketpy/sounding_crosscheck_reference.json");
    let designs = read("validation/rocketpy/design_crosscheck_reference.json");
    let r = &designs["rockets"][rp["rocket"].as_str().unwrap()];
    let (sim, start_height, start_en) = crosscheck_simulation(r, "calm");
    // The air and the wind read `start_height` lower than the rocket is (crosscheck.rs).
    let s = sounding(&rp);
    let site = num(&rp, "/site_elevation_m") - start_height;
    let env = hpr_sim::Environment {
        elevation_m: site,
        air: AirModel::Profile(Arc::new(s.air_profile(site).unwrap())),
        wind: Wind::table(&s.wind_rows(site).unwrap()).unwrap(),
        ..sim.environment().clone()
    };
    let rail = *sim.rail();
    let sim = sim.with_site(env, rail).unwrap();
    let c = fly_simulation(&sim, start_height, start_en);
    let rate = num(r, "/inputs/sampling_rate_hz");
    // RocketPy's flight through its own reading, its heights made geometric: the air differs
    // only by RocketPy's pressure interpolated linearly between levels (up to 3e-4 high,
    // above), which makes its air a little denser: the apogee is allowed 0.15 m for it beside
    // the hand-picked 0.2 m.
    let out = &rp["heights_geometric"];
    let tol = Tolerances {
        apogee_m: 0.35,
        ..hand_picked(out, APOGEE_POSITION_TOL_M)
    };
    let bad = check("sounding", &c, out, rate, &tol);
    assert!(bad.is_empty(), "outside tolerance: {bad:?}");
    // As RocketPy reads it, its air aloft is the sounding's a few metres higher up: thinner.
    let as_read = num(&rp, "/as_rocketpy_reads_it/apogee_agl_m");
    let ours = c.flight.metrics.apogee_m.unwrap() - start_height;
    eprintln!("apogee: hpr {ours:.3} m; RocketPy {as_read:.3} m as it reads the sounding");
}
