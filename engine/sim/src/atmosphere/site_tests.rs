//! A launch site's measured air: its own numbers at the site, the standard above 11 km.

use super::*;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

const SITE: AirModel = AirModel::Site {
    elevation_m: 1400.0,
    temperature_k: 308.15,
    pressure_pa: 85_600.0,
};

#[test]
fn a_site_s_air_is_the_measured_air_there_and_the_standard_above_11_km() {
    let atm = Atmosphere::new(1400.0, &SITE).unwrap();
    let here = atm.at(0.0);
    assert!((here.temperature_k - 308.15).abs() < 1e-12);
    assert!(rel(here.pressure_pa, 85_600.0) < 1e-14);
    assert!(rel(here.density_kg_m3, 85_600.0 / (R_AIR_J_KG_K * 308.15)) < 1e-14);
    // By hand, 2000 geopotential m above the site: the temperature falls linearly to
    // 216.65 K at 11 km, L = (216.65 − 308.15)/(11000 − H_site), and the pressure follows
    // the hydrostatic law of a linear layer, p = p_s (T_s/T)^(g0/(R L)).
    let h_site = R0_GEOPOTENTIAL_M * 1400.0 / (R0_GEOPOTENTIAL_M + 1400.0);
    let lapse = (216.65 - 308.15) / (11_000.0 - h_site);
    let h = h_site + 2000.0;
    let z = R0_GEOPOTENTIAL_M * h / (R0_GEOPOTENTIAL_M - h);
    let t = 308.15 + lapse * 2000.0;
    let p = 85_600.0 * (308.15 / t).powf(9.80665 / (8314.32 / 28.9644 * lapse));
    let up = atm.at_msl(z);
    assert!(
        (up.temperature_k - t).abs() < 1e-9,
        "{} vs {t}",
        up.temperature_k
    );
    assert!(rel(up.pressure_pa, p) < 1e-9, "{} vs {p}", up.pressure_pa);
    // Above 11 km the standard temperatures, and the standard's pressure ratios.
    let std = Atmosphere::standard(0.0).unwrap();
    let z11 = geometric_altitude_m(11_000.0);
    for z in [15_000.0, 25_000.0, 40_000.0] {
        let (a, s) = (atm.at_msl(z), std.at_msl(z));
        assert!((a.temperature_k - s.temperature_k).abs() < 1e-9, "T at {z}");
        let ratio = a.pressure_pa / atm.at_msl(z11).pressure_pa;
        let standard_ratio = s.pressure_pa / std.at_msl(z11).pressure_pa;
        assert!(rel(ratio, standard_ratio) < 1e-12, "p ratio at {z}");
    }
    // The hot, low day is thinner over the site (its steeper lapse brings it back to the
    // standard temperature by 11 km).
    for z in [1400.0, 2000.0, 4000.0] {
        assert!(atm.at_msl(z).density_kg_m3 < std.at_msl(z).density_kg_m3);
    }
}

#[test]
fn a_site_at_the_standard_s_own_temperature_and_pressure_is_the_standard_atmosphere() {
    for elevation in [0.0, 1400.0, 4200.0] {
        let model = AirModel::site(elevation, None, None).unwrap();
        assert_eq!(model, AirModel::Standard);
        let standard = Atmosphere::standard(elevation).unwrap();
        let here = standard.at(0.0);
        let as_site = AirModel::Site {
            elevation_m: elevation,
            temperature_k: here.temperature_k,
            pressure_pa: here.pressure_pa,
        };
        let atm = Atmosphere::new(elevation, &as_site).unwrap();
        for h in [-300.0, 0.0, 500.0, 3000.0, 9000.0, 20_000.0, 60_000.0] {
            let (a, s) = (atm.at(h), standard.at(h));
            assert!(rel(a.temperature_k, s.temperature_k) < 1e-12, "T at {h}");
            assert!(rel(a.pressure_pa, s.pressure_pa) < 1e-12, "p at {h}");
        }
    }
    // One of the two given: the other is the standard's at the site.
    let hot = AirModel::site(1400.0, Some(308.15), None).unwrap();
    let standard = Atmosphere::standard(1400.0).unwrap().at(0.0);
    match hot {
        AirModel::Site { pressure_pa, .. } => assert_eq!(pressure_pa, standard.pressure_pa),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_site_s_table_reads_its_air_as_the_standard_s_reads_the_standard() {
    let table = AirTable::new(&SITE).unwrap();
    assert_eq!(*table.model(), SITE);
    let exact = Atmosphere::new(0.0, &SITE).unwrap();
    // Mid-cell, inside the first layer: linear interpolation holds 5e-7.
    for z in [1405.0, 2345.0, 5005.0, 9995.0] {
        let (a, e) = (table.at_msl(z), exact.at_msl(z));
        assert!(rel(a.density_kg_m3, e.density_kg_m3) < 5e-7, "ρ at {z}");
        assert!(
            rel(a.speed_of_sound_m_s, e.speed_of_sound_m_s) < 5e-7,
            "a at {z}"
        );
    }
    // Past the table's top the site's own model answers.
    let high = table.at_msl(90_000.0);
    assert_eq!(high.density_kg_m3, exact.at_msl(90_000.0).density_kg_m3);
    // The standard model's table is the one shared table.
    assert!(std::sync::Arc::ptr_eq(
        &AirTable::new(&AirModel::Standard).unwrap(),
        &AirTable::standard()
    ));
}

#[test]
fn a_site_s_air_outside_its_ranges_is_refused_by_field() {
    let site = |elevation_m, temperature_k, pressure_pa| {
        AirModel::site(elevation_m, Some(temperature_k), Some(pressure_pa))
    };
    for (bad, field) in [
        (site(0.0, 140.0, 101_325.0), "temperature_k"),
        (site(0.0, f64::NAN, 101_325.0), "temperature_k"),
        (site(0.0, 288.15, 5_000.0), "pressure_pa"),
        (site(0.0, 288.15, 130_000.0), "pressure_pa"),
    ] {
        let e = bad.unwrap_err().to_string();
        assert!(e.contains(field), "{e}");
    }
    let e = site(10_500.0, 220.0, 25_000.0).unwrap_err();
    assert!(matches!(e, AtmosphereError::SiteElevation { .. }), "{e}");
    assert!(e.to_string().contains("below the 11 km layer"));
}
