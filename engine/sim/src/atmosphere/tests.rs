//! The standard atmosphere against the published tables.

use super::*;

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

fn sea_level() -> Atmosphere {
    Atmosphere::standard(0.0).unwrap()
}

#[test]
fn sea_level_matches_the_published_standard_values() {
    let a = sea_level().at(0.0);
    eprintln!("sea level: {a:?}");
    // Published to 5–6 digits: compare to half a unit of the last digit.
    assert!((a.temperature_k - 288.15).abs() < 1e-12);
    assert!((a.pressure_pa - 101_325.0).abs() < 1e-9);
    assert!((a.density_kg_m3 - 1.2250).abs() < 5e-5);
    assert!((a.speed_of_sound_m_s - 340.294).abs() < 5e-4);
    // Table value 1.7894e-5 Pa·s.
    assert!((a.dynamic_viscosity_pa_s - 1.7894e-5).abs() < 5e-10);
}

#[test]
fn layer_bases_reproduce_the_published_base_pressures_and_temperatures() {
    // (geopotential m', T K, P Pa) of the 1976 document's layer bases (pressures to 7
    // significant digits: tolerance 1e-6 relative), and the density where a published
    // value is at hand, with its absolute tolerance (half a unit of its last digit).
    let table = [
        (11_000.0, 216.65, 22_632.06, Some((0.363_918, 5e-7))),
        (20_000.0, 216.65, 5_474.889, Some((0.088_035, 5e-7))),
        (32_000.0, 228.65, 868.018_7, Some((0.013_225, 5e-7))),
        (47_000.0, 270.65, 110.906_3, None),
        (51_000.0, 270.65, 66.938_87, None),
        (71_000.0, 214.65, 3.956_420, None),
        (84_852.0, 186.946, 0.373_383_6, Some((6.958e-6, 5e-10))),
    ];
    let atm = sea_level();
    for (h, t, p, rho) in table {
        let s = atm.at_msl(geometric_altitude_m(h));
        eprintln!(
            "H = {h} m': T {} K ({:.2e}), P {} Pa ({:.2e}), rho {}",
            s.temperature_k,
            rel(s.temperature_k, t),
            s.pressure_pa,
            rel(s.pressure_pa, p),
            s.density_kg_m3,
        );
        assert!(rel(s.temperature_k, t) < 1e-9, "T at {h}");
        assert!(rel(s.pressure_pa, p) < 1e-6, "P at {h}");
        if let Some((rho, tol)) = rho {
            assert!((s.density_kg_m3 - rho).abs() < tol, "rho at {h}");
        }
        // Ideal gas, independently of the implementation's formula.
        assert!(
            rel(s.density_kg_m3, p / (287.05287 * t)) < 2e-6,
            "ideal gas at {h}"
        );
    }
}

#[test]
fn geometric_altitudes_match_the_published_table() {
    // (geometric m, T K, P Pa, ρ kg/m³), U.S. Standard Atmosphere 1976 geometric table to
    // 5 significant digits: tolerance 1e-4 relative (one unit in the 5th digit).
    let table = [
        (5_000.0, 255.676, 54_048.0, 0.736_43),
        (10_000.0, 223.252, 26_500.0, 0.413_51),
        (20_000.0, 216.65, 5_529.3, 0.088_910),
        (30_000.0, 226.509, 1_197.0, 0.018_410),
        (40_000.0, 250.350, 287.14, 0.003_995_7),
        (50_000.0, 270.65, 79.779, 0.001_026_9),
        (60_000.0, 247.021, 21.958, 3.096_8e-4),
        (70_000.0, 219.585, 5.220_9, 8.282_9e-5),
        (80_000.0, 198.639, 1.052_4, 1.845_8e-5),
    ];
    let atm = sea_level();
    for (z, t, p, rho) in table {
        let s = atm.at_msl(z);
        let worst = rel(s.temperature_k, t)
            .max(rel(s.pressure_pa, p))
            .max(rel(s.density_kg_m3, rho));
        eprintln!("Z = {z} m: {s:?}, worst relative error {worst:.2e}");
        assert!(worst < 1e-4, "at {z} m: {s:?}");
    }
}

#[test]
fn the_height_argument_is_above_the_launch_site() {
    let site = Atmosphere::standard(1_400.0).unwrap();
    let a = site.at(600.0);
    let b = sea_level().at_msl(2_000.0);
    assert_eq!(a, b);
    assert_eq!(site.launch_elevation_m(), 1_400.0);
}

#[test]
fn below_minus_five_kilometres_the_air_is_clamped() {
    let atm = sea_level();
    let edge = atm.at_msl(-5_000.0);
    assert_eq!(atm.at_msl(-9_000.0), edge);
    // −5 km: T = 288.15 + 6.5·H(−5 km)/1000, H = −5003.94 m'.
    let h = geopotential_altitude_m(-5_000.0);
    assert!((edge.temperature_k - (288.15 - 6.5e-3 * h)).abs() < 1e-12);
    assert!(edge.pressure_pa > 101_325.0);
}

#[test]
fn above_eighty_six_kilometres_the_air_thins_isothermally() {
    let atm = sea_level();
    let top = atm.at_msl(86_000.0);
    let s90 = atm.at_msl(90_000.0);
    let s100 = atm.at_msl(100_000.0);
    assert!((s90.temperature_k - top.temperature_k).abs() < 1e-12);
    assert!(s100.density_kg_m3 < s90.density_kg_m3 && s90.density_kg_m3 < top.density_kg_m3);
    // Isothermal: P(100)/P(86) = exp(−g0 ΔH / (R T)), computed by hand here.
    let dh = geopotential_altitude_m(100_000.0) - geopotential_altitude_m(86_000.0);
    let expected = (-G0_M_S2 * dh / (R_AIR_J_KG_K * 186.946)).exp();
    let ratio = s100.pressure_pa / top.pressure_pa;
    eprintln!(
        "P(100 km)/P(86 km) = {ratio}, expected {expected}, P(100 km) = {}",
        s100.pressure_pa
    );
    assert!(rel(ratio, expected) < 1e-6);
    // Real US76 at 100 km: 3.2011e-2 Pa; the extrapolation stays within 10 %.
    assert!(rel(s100.pressure_pa, 3.2011e-2) < 0.10);
    let far = atm.at_msl(1.0e7);
    assert!(far.density_kg_m3 >= 0.0 && far.density_kg_m3.is_finite());
}

#[test]
fn the_atmosphere_is_continuous_across_layer_boundaries() {
    let atm = sea_level();
    for &h in &LAYER_BASE_M[1..] {
        let z = geometric_altitude_m(h);
        let below = atm.at_msl(z - 1e-6);
        let above = atm.at_msl(z + 1e-6);
        assert!(rel(below.pressure_pa, above.pressure_pa) < 1e-9, "P at {h}");
        assert!(
            (below.temperature_k - above.temperature_k).abs() < 1e-8,
            "T at {h}"
        );
    }
}

#[test]
fn an_unusable_launch_elevation_is_a_typed_error() {
    for bad in [f64::NAN, f64::INFINITY, -6_000.0, 90_000.0] {
        let err = Atmosphere::standard(bad).unwrap_err();
        assert!(matches!(err, AtmosphereError::LaunchElevation { .. }));
        assert!(err.to_string().contains("launch_elevation_m"));
    }
}

#[test]
fn the_reynolds_scale_is_one_at_sea_level_and_that_of_the_published_air_at_five_kilometres() {
    // Sea level: Sutherland's 1.78938e-5 Pa·s at 288.15 K against the estimate's 1.7894e-5.
    assert!(reynolds_ln_scale(1.225, 340.294).abs() < 2e-5);
    // 5 km (US Standard Atmosphere 1976, as published to five digits): a = 320.55 m/s,
    // ρ = 0.73643 kg/m³, μ = 1.6283e-5 Pa·s, so ν = 2.2111e-5 m²/s and the Reynolds number at
    // a Mach number is (a/a₀)(ν₀/ν) = 0.6223 of sea level's.
    let want = (320.55f64 / 340.294 * (1.7894e-5 / 1.225) / (1.6283e-5 / 0.73643)).ln();
    let got = reynolds_ln_scale(0.73643, 320.55);
    assert!((got - want).abs() < 2e-4, "{got} vs {want}");
    assert!((got - -0.4743).abs() < 1e-3, "{got}");
    // From the model's own air at 5 km, the same to the published table's digits.
    let air = Atmosphere::standard(0.0).unwrap().at_msl(5_000.0);
    let model = reynolds_ln_scale(air.density_kg_m3, air.speed_of_sound_m_s);
    assert!((model - want).abs() < 3e-4, "{model} vs {want}");
    // A vacuum has no Reynolds number: the drag's first table then (q is 0 anyway).
    assert_eq!(reynolds_ln_scale(0.0, 300.0), f64::NEG_INFINITY);
}
