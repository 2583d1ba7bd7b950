//! The weather reader against an independent reading of the same files, against RocketPy's,
//! across the layouts a file comes in, and against corrupt files.

use super::*;
use crate::atmosphere::{AirModel, Atmosphere};
use crate::wind::Wind;
use serde_json::Value;
use std::sync::Arc;

const LAT: f64 = 47.213476;
const LON: f64 = 9.003336;
const ELEVATION_M: f64 = 407.0;

fn repo(path: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

const CLASSIC: &str = "validation/real-flights/bella-lui/bella_lui_weather_data_ERA5.nc";
const NETCDF4: &str = "validation/weather/bella_lui_era5_netcdf4.nc";
const GFS_LIKE: &str = "validation/weather/bella_lui_gfs_like.nc";
const ENSEMBLE: &str = "validation/weather/bella_lui_ensemble.nc";

fn site(path: &str) -> SiteWeather {
    SiteWeather::read(&repo(path), LAT, LON).unwrap()
}

fn reference() -> Value {
    let text = std::fs::read_to_string(repo("validation/rocketpy/era5_crosscheck_reference.json"))
        .unwrap();
    serde_json::from_str(&text).unwrap()
}

fn num(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap()
}

fn at(text: &str) -> f64 {
    parse_utc(text).unwrap()
}

fn east_north(l: &Level) -> [f64; 2] {
    let (speed, from) = l.wind.unwrap();
    let (s, c) = from.to_radians().sin_cos();
    [-speed * s, -speed * c]
}

#[test]
fn the_classic_era5_file_reads_its_grid_times_and_packed_values() {
    let w = site(CLASSIC);
    // 00, 06, 12, 13 and 18 UTC on 2020-02-22 ("hours since 1900-01-01": 1053144 ...).
    let day = at("2020-02-22T00:00Z");
    let hours: Vec<f64> = w.times_s().iter().map(|t| (t - day) / 3600.0).collect();
    assert_eq!(hours, [0.0, 6.0, 12.0, 13.0, 18.0]);
    assert_eq!(w.members(), [0.0]);
    assert_eq!(w.variables(), &["z", "t", "u", "v"].map(String::from));
    let levels = w.levels(at("2020-02-22T13:00Z"), 0).unwrap();
    assert_eq!(levels.len(), 14);
    assert_eq!(levels[0].pressure_pa, Some(100_000.0));
    assert_eq!(levels[13].pressure_pa, Some(60_000.0));
}

#[test]
fn the_levels_over_the_site_are_an_independent_reader_s_at_a_file_time_and_between_times() {
    // validation/rocketpy/era5_crosscheck.py: netCDF4's unpacked values, bilinear in numpy,
    // linear in time, heights with the same radius. The two do the same arithmetic in a
    // different order: they agree to the last few digits.
    let r = reference();
    let w = site(CLASSIC);
    let mut worst = [0.0f64; 4];
    for (when, levels) in r["independent"].as_object().unwrap() {
        let ours = w.levels(at(when), 0).unwrap();
        let theirs = levels.as_array().unwrap();
        assert_eq!(ours.len(), theirs.len(), "{when}");
        for (o, t) in ours.iter().zip(theirs) {
            assert_eq!(o.pressure_pa, Some(num(t, "pressure_pa")));
            let [e, n] = east_north(o);
            let d = [
                (o.height_msl_m - num(t, "height_msl_m")).abs(),
                (o.temperature_k.unwrap() - num(t, "temperature_k")).abs(),
                (e - num(t, "wind_east_m_s")).abs(),
                (n - num(t, "wind_north_m_s")).abs(),
            ];
            for (w, d) in worst.iter_mut().zip(d) {
                *w = w.max(d);
            }
        }
    }
    eprintln!("against the independent reader: heights {:.1e} m, temperatures {:.1e} K, winds {:.1e} / {:.1e} m/s", worst[0], worst[1], worst[2], worst[3]);
    // Heights to 1e-10 m (4.4 km: 2e-14 of themselves), temperatures 1e-12 K, winds
    // 1e-13 m/s.
    assert!(worst[0] < 1e-10 && worst[1] < 1e-12 && worst[2] < 1e-13 && worst[3] < 1e-13);
}

#[test]
fn the_air_and_the_wind_over_bella_lui_s_site_are_rocketpy_s_reading_of_the_same_file() {
    // RocketPy 1.13's Environment over the same site at the same time (a file time, where
    // taking the nearest time, as RocketPy does, and interpolating are the same). Both
    // interpolate the temperature and the wind's components linearly in geometric height
    // between the same levels. Both meet the file's pressures at its levels; between them
    // RocketPy interpolates the pressure linearly in height, hpr-mc follows the hydrostatic
    // law through the temperatures with each layer's gas constant (the humid air's the
    // file's heights imply); linear interpolation of a pressure falling exponentially is
    // high between levels by up to (Δz/H)²/8 of itself (levels 250 to 630 m apart, H ≈
    // 8.4 km: 7e-4), and the density follows.
    let r = reference();
    let rp = &r["rocketpy_classic"];
    let w = site(CLASSIC);
    let air = w
        .over_site(at("2020-02-22T13:00Z"), 0, ELEVATION_M)
        .unwrap();
    let atmosphere = Atmosphere::new(ELEVATION_M, &AirModel::Profile(Arc::new(air.air))).unwrap();
    let wind = Wind::table(&air.wind).unwrap();
    // The same radius for the heights (RocketPy's SIRGAS2000 ellipsoid is WGS 84's to 1e-9).
    assert!((earth_radius_m(LAT) / num(rp, "earth_radius_m") - 1.0).abs() < 1e-10);
    let mut worst = [0.0f64; 6];
    let mut speed_direction = [0.0f64; 2];
    let rows = rp["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 40); // 0 to 3.9 km above the site, every 100 m
    for row in rows {
        let h = num(row, "height_m");
        let ours = atmosphere.at(h);
        let [e, n] = wind.velocity_en(h);
        let d = [
            (ours.temperature_k / num(row, "temperature_k") - 1.0).abs(),
            (e - num(row, "wind_east_m_s")).abs(),
            (n - num(row, "wind_north_m_s")).abs(),
            (ours.pressure_pa / num(row, "pressure_pa") - 1.0).abs(),
            (ours.density_kg_m3 / num(row, "density_kg_m3") - 1.0).abs(),
            (ours.speed_of_sound_m_s / num(row, "speed_of_sound_m_s") - 1.0).abs(),
        ];
        for (w, d) in worst.iter_mut().zip(d) {
            *w = w.max(d);
        }
        let (speed, turn) = speed_and_turn(row, [e, n]);
        speed_direction[0] = speed_direction[0].max(speed);
        speed_direction[1] = speed_direction[1].max(turn);
    }
    // RocketPy reports the wind's speed and direction interpolated as themselves between
    // levels (it flies the components, which agree above): at the levels the two agree to
    // rounding; between them its speed is the levels' mean, not the mean wind's.
    let mut at_levels = [0.0f64; 2];
    for level in rp["levels"].as_array().unwrap() {
        let h = num(level, "height_msl_m") - ELEVATION_M;
        if h < 0.0 {
            continue;
        }
        let (speed, turn) = speed_and_turn(level, wind.velocity_en(h));
        at_levels = [at_levels[0].max(speed), at_levels[1].max(turn)];
    }
    eprintln!(
        "wind speed and direction: at the levels within {:.1e} m/s and {:.1e} degrees; between \
         them within {:.2} m/s and {:.2} degrees (RocketPy's interpolation of speed and angle)",
        at_levels[0], at_levels[1], speed_direction[0], speed_direction[1]
    );
    assert!(at_levels[0] < 1e-9 && at_levels[1] < 1e-6);
    let [t, e, n, p, rho, a] = worst;
    eprintln!(
        "0 to 3.9 km over Bella Lui's site against RocketPy: temperature {t:.1e} (relative), \
         wind east {e:.1e} m/s, north {n:.1e} m/s, pressure {p:.1e}, density {rho:.1e}, \
         speed of sound {a:.1e}"
    );
    // Between levels hpr-mc's temperature is linear in geopotential altitude (a profile's
    // layers are), RocketPy's in geometric height: apart by the curvature of one in the
    // other, Δz²/(8 r0) of height (7 mm for levels 630 m apart) times the lapse rate.
    // RocketPy's speed of sound is the chord of √T between levels (up to (ΔT/T)²/8 low).
    assert!(t < 1e-6, "temperature {t:e}");
    assert!(e < 1e-9 && n < 1e-9, "wind {e:e} {n:e}");
    assert!(p < 1e-3 && rho < 1e-3, "pressure {p:e} density {rho:e}");
    assert!(a < 3e-5, "speed of sound {a:e}");
    // At the levels themselves, the file's pressures and temperatures exactly.
    let mut at_levels = [0.0f64; 2];
    for l in w.levels(at("2020-02-22T13:00Z"), 0).unwrap() {
        if l.height_msl_m <= ELEVATION_M {
            continue;
        }
        let ours = atmosphere.at_msl(l.height_msl_m);
        at_levels[0] = at_levels[0].max((ours.pressure_pa / l.pressure_pa.unwrap() - 1.0).abs());
        at_levels[1] = at_levels[1].max((ours.temperature_k - l.temperature_k.unwrap()).abs());
    }
    eprintln!(
        "at the 12 levels above the site: pressure {:.1e} (relative), temperature {:.1e} K",
        at_levels[0], at_levels[1]
    );
    assert!(at_levels[0] < 1e-12 && at_levels[1] < 1e-9);
}

/// How far a wind `en` (east, north) is from RocketPy's `row` in speed (m/s) and in the
/// direction it blows from (degrees).
fn speed_and_turn(row: &Value, [e, n]: [f64; 2]) -> (f64, f64) {
    let from = (e.atan2(n).to_degrees() + 180.0).rem_euclid(360.0);
    let turn = (from - num(row, "wind_from_deg") + 540.0).rem_euclid(360.0) - 180.0;
    ((e.hypot(n) - num(row, "wind_speed_m_s")).abs(), turn.abs())
}

/// The worst differences between two readings' levels at `when`: height (m), temperature
/// (K), wind (m/s).
fn apart(a: &SiteWeather, b: &SiteWeather, when: f64, member: usize) -> [f64; 3] {
    let (la, lb) = (a.levels(when, 0).unwrap(), b.levels(when, member).unwrap());
    assert_eq!(la.len(), lb.len());
    let mut worst = [0.0f64; 3];
    for (x, y) in la.iter().zip(&lb) {
        assert_eq!(x.pressure_pa, y.pressure_pa);
        let ([e0, n0], [e1, n1]) = (east_north(x), east_north(y));
        worst[0] = worst[0].max((x.height_msl_m - y.height_msl_m).abs());
        worst[1] = worst[1].max((x.temperature_k.unwrap() - y.temperature_k.unwrap()).abs());
        worst[2] = worst[2].max((e0 - e1).abs().max((n0 - n1).abs()));
    }
    worst
}

#[test]
fn the_copernicus_netcdf4_layout_reads_as_the_classic_file_it_was_made_from() {
    // validation/weather/make_weather_files.py wrote the classic file's values as float32
    // (half an ulp: 2e-3 m²/s² of geopotential at 43,000 = 2e-4 m, 1.5e-5 K at 290 K, 1e-6
    // m/s), on valid_time, pressure levels stored 1000 down to 600, NaN fill values.
    let (classic, nc4) = (site(CLASSIC), site(NETCDF4));
    assert_eq!(classic.times_s(), nc4.times_s());
    for when in [
        "2020-02-22T13:00Z",
        "2020-02-22T15:24Z",
        "2020-02-22T00:00Z",
    ] {
        let [h, t, w] = apart(&classic, &nc4, at(when), 0);
        assert!(
            h < 3e-4 && t < 2e-5 && w < 2e-6,
            "{when}: {h} m, {t} K, {w} m/s"
        );
    }
}

#[test]
fn a_gfs_forecast_in_noaa_s_names_reads_through_the_same_reader() {
    // Geopotential height in gpm on isobaric levels in Pa, "Hour since ...": the same
    // weather, at 12, 13 and 18 UTC only, as float32.
    let (classic, gfs) = (site(CLASSIC), site(GFS_LIKE));
    assert_eq!(gfs.times_s(), &classic.times_s()[2..]);
    assert_eq!(
        gfs.variables(),
        &[
            "Geopotential_height_isobaric",
            "Temperature_isobaric",
            "u-component_of_wind_isobaric",
            "v-component_of_wind_isobaric"
        ]
        .map(String::from)
    );
    for when in [
        "2020-02-22T13:00Z",
        "2020-02-22T15:24Z",
        "2020-02-22T12:10Z",
    ] {
        let [h, t, w] = apart(&classic, &gfs, at(when), 0);
        assert!(
            h < 3e-4 && t < 2e-5 && w < 2e-6,
            "{when}: {h} m, {t} K, {w} m/s"
        );
    }
    // 06 UTC is in the classic file, not in the forecast's.
    let e = gfs.levels(at("2020-02-22T06:00Z"), 0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "the launch time 2020-02-22T06:00:00Z is outside the file's times \
         (2020-02-22T12:00:00Z to 2020-02-22T18:00:00Z)"
    );
}

#[test]
fn an_ensemble_s_members_read_by_number_and_a_longitude_wraps_to_the_grid_s_convention() {
    // Member k: the temperature plus 0.5 k K, the wind times 1 + 0.1 k; its longitudes are
    // every ERA5 longitude plus 340 degrees, in the 0-360 convention, so the site is asked
    // for at its longitude minus 20 (-10.996664), which wraps to 349.003336.
    let nc4 = site(NETCDF4);
    let ens = SiteWeather::read(&repo(ENSEMBLE), LAT, LON - 20.0).unwrap();
    assert_eq!(ens.members(), [0.0, 1.0, 2.0]);
    let when = at("2020-02-22T13:00Z");
    for number in [0.0, 1.0, 2.0] {
        let k = ens.member_index(number).unwrap();
        let (a, b) = (nc4.levels(when, 0).unwrap(), ens.levels(when, k).unwrap());
        for (x, y) in a.iter().zip(&b) {
            assert!((x.height_msl_m - y.height_msl_m).abs() < 1e-9);
            let t = x.temperature_k.unwrap() + 0.5 * number;
            assert!((y.temperature_k.unwrap() - t).abs() < 3e-5);
            let ([e0, n0], [e1, n1]) = (east_north(x), east_north(y));
            let s = 1.0 + 0.1 * number;
            assert!((e1 - s * e0).abs() < 3e-6 && (n1 - s * n0).abs() < 3e-6);
        }
    }
    assert_eq!(
        ens.member_index(3.0).unwrap_err().to_string(),
        "ensemble member 3 is not in the file (its members: 0 to 2)"
    );
}

#[test]
fn between_two_times_every_level_is_their_linear_mix() {
    let w = site(CLASSIC);
    let (a, b, mid) = (
        w.levels(at("2020-02-22T13:00Z"), 0).unwrap(),
        w.levels(at("2020-02-22T18:00Z"), 0).unwrap(),
        w.levels(at("2020-02-22T14:15Z"), 0).unwrap(),
    );
    let f = 0.25; // 1 h 15 of 5 h
    for ((x, y), m) in a.iter().zip(&b).zip(&mid) {
        let mix = |p: f64, q: f64| p + f * (q - p);
        let (tx, ty) = (x.temperature_k.unwrap(), y.temperature_k.unwrap());
        assert!((m.temperature_k.unwrap() - mix(tx, ty)).abs() < 1e-12);
        // Heights: the mix of the geopotentials, then made geometric (nearly linear).
        assert!((m.height_msl_m - mix(x.height_msl_m, y.height_msl_m)).abs() < 1e-3);
        let ([e0, n0], [e1, n1], [e, n]) = (east_north(x), east_north(y), east_north(m));
        assert!((e - mix(e0, e1)).abs() < 1e-12 && (n - mix(n0, n1)).abs() < 1e-12);
    }
}

#[test]
fn above_the_top_level_the_temperature_follows_the_standard_lapse_shifted_to_meet_it() {
    let w = site(CLASSIC);
    let when = at("2020-02-22T13:00Z");
    let air = w.over_site(when, 0, ELEVATION_M).unwrap().air;
    let top = w.top_m(when, 0).unwrap();
    let levels = w.levels(when, 0).unwrap();
    let t_top = levels.last().unwrap().temperature_k.unwrap();
    let standard = Atmosphere::standard(0.0).unwrap();
    let shift = t_top - standard.at_msl(top).temperature_k;
    let atmosphere = Atmosphere::new(ELEVATION_M, &AirModel::Profile(Arc::new(air))).unwrap();
    // At the top: the level's temperature; at 8 km and at 15 km: the standard's plus the shift.
    assert!((atmosphere.at_msl(top).temperature_k - t_top).abs() < 1e-9);
    for z in [8_000.0, 15_000.0, 25_000.0] {
        let expected = standard.at_msl(z).temperature_k + shift;
        let got = atmosphere.at_msl(z).temperature_k;
        assert!(
            (got - expected).abs() < 1e-9,
            "{z} m: {got} K, {expected} K"
        );
    }
    // The wind above the top is the top level's.
    let wind = Wind::table(&w.over_site(when, 0, ELEVATION_M).unwrap().wind).unwrap();
    let top_wind = east_north(levels.last().unwrap());
    let high = wind.velocity_en(9_000.0);
    assert!((high[0] - top_wind[0]).abs() < 1e-12 && (high[1] - top_wind[1]).abs() < 1e-12);
}

#[test]
fn a_site_up_to_500_m_below_the_lowest_level_continues_the_lowest_two_and_no_further() {
    let w = site(CLASSIC);
    let when = at("2020-02-22T13:00Z");
    let levels = w.levels(when, 0).unwrap();
    let (a, b) = (levels[0], levels[1]);
    let low = a.height_msl_m - 400.0;
    let air = w.over_site(when, 0, low).unwrap().air;
    let f = (low - a.height_msl_m) / (b.height_msl_m - a.height_msl_m);
    let (ta, tb) = (a.temperature_k.unwrap(), b.temperature_k.unwrap());
    assert!((air.rows[0].temperature_k - (ta + f * (tb - ta))).abs() < 1e-9);
    let e = w.over_site(when, 0, a.height_msl_m - 600.0).unwrap_err();
    assert!(
        e.to_string().contains("is outside the file's temperatures")
            && e.to_string()
                .contains("may be up to 500 m below the lowest"),
        "{e}"
    );
}

#[test]
fn what_the_file_does_not_hold_is_refused_naming_the_rule() {
    let w = site(CLASSIC);
    let e = w.levels(at("2020-02-23T00:00Z"), 0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "the launch time 2020-02-23T00:00:00Z is outside the file's times \
         (2020-02-22T00:00:00Z to 2020-02-22T18:00:00Z)"
    );
    let e = SiteWeather::read(&repo(CLASSIC), 45.0, LON).unwrap_err();
    assert_eq!(
        e.to_string(),
        "the site at 45° N, 9.003336° E is outside the file's grid (46 to 48° N, 8 to 10° E)"
    );
    let e = SiteWeather::read(&repo(CLASSIC), 91.0, LON).unwrap_err();
    assert!(e.to_string().contains("latitude must be finite"), "{e}");
    let e = w.member_index(1.0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "ensemble member 1 is not in the file (its members: 0 only)"
    );
    let e = SiteWeather::read(&repo("validation/weather"), LAT, LON).unwrap_err();
    assert_eq!(e.to_string(), "can't read it: it is not a file");
    let e = SiteWeather::read(&repo("scenarios/ballast_sweep.toml"), LAT, LON).unwrap_err();
    assert!(matches!(e, WeatherError::Format(_)), "{e}");
}

/// Copies of `bytes` broken as a damaged download or disk breaks them: cut short at many
/// lengths, a byte changed, a run of bytes overwritten; a deterministic stream of them.
fn broken_copies(bytes: &[u8], count: usize, seed: u64) -> Vec<Vec<u8>> {
    let mut state = seed | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let n = bytes.len();
    (0..count)
        .map(|k| {
            let mut b = bytes.to_vec();
            match k % 4 {
                0 => b.truncate((next() as usize) % n),
                1 => {
                    let i = (next() as usize) % n;
                    b[i] ^= 1 << (next() % 8);
                }
                2 => {
                    // Early bytes (the header and its sizes) are where damage bites.
                    let i = (next() as usize) % n.min(4096);
                    b[i] = next() as u8;
                }
                _ => {
                    let i = (next() as usize) % n;
                    let len = 1 + (next() as usize) % 64;
                    for x in b.iter_mut().skip(i).take(len) {
                        *x = next() as u8;
                    }
                }
            }
            b
        })
        .collect()
}

#[test]
fn damaged_copies_of_the_real_files_give_errors_or_finite_air_never_a_panic() {
    // 400 broken copies of each layout. Every one either is refused with an error, or reads
    // into levels and air that are all finite (a changed digit of a temperature reads as a
    // different temperature: that is the file's word, and any value outside a range a rocket
    // flies in is refused).
    let when = at("2020-02-22T13:00Z");
    let mut outcomes = [0usize; 2];
    for (k, file) in [CLASSIC, NETCDF4, GFS_LIKE, ENSEMBLE].iter().enumerate() {
        let bytes = std::fs::read(repo(file)).unwrap();
        let lon = if *file == ENSEMBLE { LON - 20.0 } else { LON };
        for copy in broken_copies(&bytes, 400, 0x9E37_79B9 + k as u64) {
            let read = SiteWeather::from_bytes(&copy, LAT, lon);
            let Ok(w) = read else {
                outcomes[0] += 1;
                continue;
            };
            match w.over_site(when, 0, ELEVATION_M) {
                Ok(site) => {
                    outcomes[1] += 1;
                    assert!(site.air.pressure_pa.is_finite());
                    assert!(site.air.rows.iter().all(|r| r.temperature_k.is_finite()));
                    assert!(site.wind.iter().all(|r| r.speed_m_s.is_finite()));
                    AirModel::Profile(Arc::new(site.air)).check().unwrap();
                }
                Err(_) => outcomes[0] += 1,
            }
        }
    }
    eprintln!(
        "1,600 damaged files: {} refused, {} read into finite air",
        outcomes[0], outcomes[1]
    );
    assert_eq!(outcomes[0] + outcomes[1], 1600);
}

#[test]
fn a_file_without_a_quantity_or_with_a_value_that_is_no_number_is_refused_naming_the_variable() {
    // validation/weather/make_weather_files.py: a cut of the ERA5 file without `v`, and one
    // with a NaN in `t` at 13:00, 875 hPa, where its fill value (-9999) marks the missing.
    let e = SiteWeather::read(
        &repo("validation/weather/broken_no_north_wind.nc"),
        LAT,
        LON,
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "it has no wind's north component (looked for: v, vgrdprs, \
         v-component_of_wind_isobaric, va, VGRD, vwnd)"
    );
    let e = SiteWeather::read(
        &repo("validation/weather/broken_nan_temperature.nc"),
        LAT,
        LON,
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "variable \"t\": holds NaN, which is neither a number nor its fill value: every value \
         must be finite"
    );
}
