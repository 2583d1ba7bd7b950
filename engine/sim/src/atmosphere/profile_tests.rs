//! A measured temperature profile over a site: the hydrostatic law layer by layer, checked
//! by hand, against the standard atmosphere and against the site model.

use super::*;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn profile(elevation_m: f64, pressure_pa: f64, rows: &[(f64, f64)]) -> AirModel {
    AirModel::Profile(Arc::new(AirProfile {
        elevation_m,
        pressure_pa,
        rows: rows
            .iter()
            .map(|&(height_m, temperature_k)| AirRow {
                height_m,
                temperature_k,
                pressure_pa: None,
            })
            .collect(),
    }))
}

#[test]
fn a_profile_of_the_standard_s_own_temperatures_is_the_standard_atmosphere() {
    // Rows at the standard's layer bases (geopotential 0, 11, 20, 32, 47 km, given as heights
    // above a sea-level site) with its temperatures there, and its sea-level pressure: the
    // same layers, so the same air to rounding (1e-11; the lapses are computed from the rows
    // instead of given).
    let rows: Vec<(f64, f64)> = [
        (0.0, 288.15),
        (11_000.0, 216.65),
        (20_000.0, 216.65),
        (32_000.0, 228.65),
        (47_000.0, 270.65),
    ]
    .iter()
    .map(|&(h, t)| (geometric_altitude_m(h), t))
    .collect();
    let atm = Atmosphere::new(0.0, &profile(0.0, P0_PA, &rows)).unwrap();
    let std = Atmosphere::standard(0.0).unwrap();
    let mut z = -2_000.0;
    while z <= 47_000.0 {
        let (a, s) = (atm.at_msl(z), std.at_msl(z));
        assert!(rel(a.temperature_k, s.temperature_k) < 1e-11, "T at {z} m");
        assert!(rel(a.pressure_pa, s.pressure_pa) < 1e-11, "p at {z} m");
        assert!(
            rel(a.density_kg_m3, s.density_kg_m3) < 1e-11,
            "rho at {z} m"
        );
        z += 250.0;
    }
}

#[test]
fn an_isothermal_profile_thins_exponentially_with_geopotential_height() {
    // One row: 250 K at a site 500 m up at 95 kPa. By hand p = p_s exp(−g0 ΔH / (R T)),
    // ΔH the geopotential height above the site; ρ = p / (R T); a = √(γ R T).
    let atm = Atmosphere::new(500.0, &profile(500.0, 95_000.0, &[(0.0, 250.0)])).unwrap();
    let h_site = geopotential_altitude_m(500.0);
    for h in [0.0, 1_000.0, 5_000.0, 30_000.0] {
        let dh = geopotential_altitude_m(500.0 + h) - h_site;
        let p = 95_000.0 * (-G0_M_S2 * dh / (R_AIR_J_KG_K * 250.0)).exp();
        let a = atm.at(h);
        assert_eq!(a.temperature_k, 250.0);
        assert!(
            rel(a.pressure_pa, p) < 1e-13,
            "p at {h} m: {} vs {p}",
            a.pressure_pa
        );
        assert!(rel(a.density_kg_m3, p / (R_AIR_J_KG_K * 250.0)) < 1e-13);
        assert!(rel(a.speed_of_sound_m_s, (1.4 * R_AIR_J_KG_K * 250.0).sqrt()) < 1e-15);
    }
}

#[test]
fn between_two_rows_the_temperature_is_linear_and_the_pressure_hydrostatic() {
    // 300 K at a site 1000 m up at 90 kPa, 280 K 3000 m above it, nothing higher. By hand:
    // L = (280 − 300)/(H₁ − H₀) in geopotential metres, T = 300 + L (H − H₀) and
    // p = p_s (300/T)^(g0/(R L)) between the rows; above the last row isothermal at 280 K
    // from the pressure there.
    let atm = Atmosphere::new(
        1000.0,
        &profile(1000.0, 90_000.0, &[(0.0, 300.0), (3000.0, 280.0)]),
    )
    .unwrap();
    let (h0, h1) = (
        geopotential_altitude_m(1000.0),
        geopotential_altitude_m(4000.0),
    );
    let lapse = (280.0 - 300.0) / (h1 - h0);
    let at = |z: f64| {
        let t = 300.0 + lapse * (geopotential_altitude_m(z) - h0);
        (
            t,
            90_000.0 * (300.0 / t).powf(G0_M_S2 / (R_AIR_J_KG_K * lapse)),
        )
    };
    let (t, p) = at(2500.0);
    let a = atm.at(1500.0);
    assert!(
        (a.temperature_k - t).abs() < 1e-11,
        "{} vs {t}",
        a.temperature_k
    );
    assert!(rel(a.pressure_pa, p) < 1e-12, "{} vs {p}", a.pressure_pa);
    let (t_top, p_top) = at(4000.0);
    assert!((t_top - 280.0).abs() < 1e-11);
    let above = atm.at(5000.0);
    let p =
        p_top * (-G0_M_S2 * (geopotential_altitude_m(6000.0) - h1) / (R_AIR_J_KG_K * 280.0)).exp();
    assert_eq!(above.temperature_k, 280.0);
    assert!(
        rel(above.pressure_pa, p) < 1e-12,
        "{} vs {p}",
        above.pressure_pa
    );
}

#[test]
fn a_profile_through_the_site_model_s_temperatures_is_the_site_model_to_20_km() {
    // The site model (305 K, 86.5 kPa at 1200 m, linear to 216.65 K at 11 km, the standard's
    // isothermal layer to 20 km) as two rows: the same air below 20 km geopotential, and
    // the same tables the flight reads.
    let site = AirModel::site(1200.0, Some(305.0), Some(86_500.0)).unwrap();
    let top = geometric_altitude_m(11_000.0) - 1200.0;
    let prof = profile(1200.0, 86_500.0, &[(0.0, 305.0), (top, 216.65)]);
    let (a, b) = (
        Atmosphere::new(1200.0, &site).unwrap(),
        Atmosphere::new(1200.0, &prof).unwrap(),
    );
    let (ta, tb) = (AirTable::new(&site).unwrap(), AirTable::new(&prof).unwrap());
    let mut z = 0.0;
    while z < geometric_altitude_m(20_000.0) {
        let (x, y) = (a.at_msl(z), b.at_msl(z));
        assert!(
            rel(x.density_kg_m3, y.density_kg_m3) < 1e-12,
            "rho at {z} m"
        );
        assert!(rel(x.speed_of_sound_m_s, y.speed_of_sound_m_s) < 1e-12);
        let (x, y) = (ta.at_msl(z + 3.7), tb.at_msl(z + 3.7));
        assert!(
            rel(x.density_kg_m3, y.density_kg_m3) < 1e-12,
            "table at {z} m"
        );
        z += 100.0;
    }
}

#[test]
fn a_profile_s_bad_rows_are_refused_naming_the_row() {
    let err = |rows: &[(f64, f64)]| profile(0.0, P0_PA, rows).check().unwrap_err();
    assert_eq!(err(&[]), AtmosphereError::ProfileRows { count: 0 });
    assert!(matches!(
        err(&[(10.0, 280.0)]),
        AtmosphereError::ProfileHeight { row: 0, .. }
    ));
    assert!(matches!(
        err(&[(0.0, 280.0), (500.0, 275.0), (500.0, 270.0)]),
        AtmosphereError::ProfileHeight { row: 2, .. }
    ));
    assert!(matches!(
        err(&[(0.0, 280.0), (f64::NAN, 275.0)]),
        AtmosphereError::ProfileHeight { row: 1, .. }
    ));
    assert!(matches!(
        err(&[(0.0, 280.0), (1000.0, 120.0)]),
        AtmosphereError::ProfileTemperature { row: 1, .. }
    ));
    let e = err(&[(0.0, 280.0), (1000.0, 400.0)]).to_string();
    assert!(
        e.contains("air_profile[1].temperature_k") && e.contains("[150, 350] K"),
        "{e}"
    );
    assert!(matches!(
        profile(0.0, 5_000.0, &[(0.0, 280.0)]).check(),
        Err(AtmosphereError::SitePressure { .. })
    ));
}

#[test]
fn a_profile_s_site_temperature_shifts_every_row_and_its_pressure_is_the_site_s() {
    // A sweep's or a dispersion's site temperature moves the whole profile by its change
    // (a warmer day, the same shape); a site pressure replaces the site's; a row pushed out
    // of range is refused by its index.
    let p = profile(300.0, 97_000.0, &[(0.0, 300.0), (2000.0, 288.0)]);
    assert_eq!(p.with_site_values(300.0, None, None), Ok(p.clone()));
    assert_eq!(
        p.with_site_values(300.0, Some(305.5), Some(96_000.0)),
        Ok(profile(300.0, 96_000.0, &[(0.0, 305.5), (2000.0, 293.5)]))
    );
    assert_eq!(p.site_values(0.0), (300.0, 300.0, 97_000.0));
    assert!(matches!(
        p.with_site_values(300.0, Some(355.0), None),
        Err(AtmosphereError::ProfileTemperature { row: 0, .. })
    ));
}

/// A profile from a sea-level site whose rows carry the pressures `pressures` (None: none).
fn measured(rows: &[(f64, f64, Option<f64>)]) -> AirModel {
    AirModel::Profile(Arc::new(AirProfile {
        elevation_m: 0.0,
        pressure_pa: 101_325.0,
        rows: rows
            .iter()
            .map(|&(h, t, p)| AirRow {
                height_m: geometric_altitude_m(h),
                temperature_k: t,
                pressure_pa: p,
            })
            .collect(),
    }))
}

#[test]
fn a_row_s_measured_pressure_is_met_by_the_layer_below_with_the_gas_constant_it_implies() {
    // Rows at 0 and 2 km geopotential, 288.15 K to 275.15 K (the standard's lapse), and a
    // measured pressure at 2 km that the standard's dry air would reach with a gas constant
    // 1 % larger (humid air): p = p0 (T/T0)^(g0 / (1.01 R L)). The layer meets it, and at
    // 1 km has that same law's pressure; the density is p / (R T) there (dry air's gas law
    // at the layer's pressure and temperature).
    let lapse = -6.5e-3;
    let exponent = -G0_M_S2 / (1.01 * R_AIR_J_KG_K * lapse);
    let p = |h: f64| 101_325.0 * ((288.15 + lapse * h) / 288.15).powf(exponent);
    let air = Atmosphere::new(
        0.0,
        &measured(&[(0.0, 288.15, None), (2000.0, 275.15, Some(p(2000.0)))]),
    )
    .unwrap();
    for h in [500.0, 1000.0, 2000.0] {
        let a = air.at_msl(geometric_altitude_m(h));
        assert!(rel(a.pressure_pa, p(h)) < 1e-13, "{h}");
        let t = 288.15 + lapse * h;
        assert!(rel(a.density_kg_m3, p(h) / (R_AIR_J_KG_K * t)) < 1e-13);
    }
    // Above the last row: isothermal, carried up from the measured pressure as dry air.
    let above = air.at_msl(geometric_altitude_m(3000.0));
    let carried = p(2000.0) * (-G0_M_S2 * 1000.0 / (R_AIR_J_KG_K * 275.15)).exp();
    assert!(rel(above.pressure_pa, carried) < 1e-13);
    // A measured pressure that is the dry air's own is the profile without it.
    let dry = -G0_M_S2 / (R_AIR_J_KG_K * lapse);
    let p_dry = 101_325.0 * (275.15_f64 / 288.15).powf(dry);
    let (with, without) = (
        Atmosphere::new(
            0.0,
            &measured(&[(0.0, 288.15, None), (2000.0, 275.15, Some(p_dry))]),
        )
        .unwrap(),
        Atmosphere::new(
            0.0,
            &measured(&[(0.0, 288.15, None), (2000.0, 275.15, None)]),
        )
        .unwrap(),
    );
    let z = geometric_altitude_m(1234.0);
    assert!(rel(with.at_msl(z).pressure_pa, without.at_msl(z).pressure_pa) < 1e-14);
    // An isothermal layer meets its measured pressure too: ln p linear in height.
    let iso = Atmosphere::new(
        0.0,
        &measured(&[(0.0, 250.0, None), (1000.0, 250.0, Some(89_000.0))]),
    )
    .unwrap();
    let half = iso.at_msl(geometric_altitude_m(500.0)).pressure_pa;
    assert!(rel(half, (101_325.0_f64 * 89_000.0).sqrt()) < 1e-13);
}

#[test]
fn a_measured_pressure_that_asks_for_an_impossible_gas_constant_is_refused_naming_its_row() {
    // 2 km of air at about 280 K weighs 22 % of the site's pressure: a row 2 km up at 95 % of
    // it would need a gas constant four times dry air's; one at a higher pressure than the
    // row beneath, a negative one.
    for p in [96_000.0, 102_000.0, f64::NAN, -1.0] {
        let e = measured(&[(0.0, 288.15, None), (2000.0, 275.15, Some(p))])
            .check()
            .unwrap_err();
        assert!(
            matches!(e, AtmosphereError::ProfilePressure { row: 1, .. }),
            "{p}: {e}"
        );
        assert!(e.to_string().contains("air_profile[1].pressure_pa"), "{e}");
    }
    // The first row's pressure is the profile's own: a row 0 pressure is refused.
    let e = measured(&[(0.0, 288.15, Some(101_325.0)), (2000.0, 275.15, None)])
        .check()
        .unwrap_err();
    assert!(matches!(e, AtmosphereError::ProfilePressure { row: 0, .. }));
}
