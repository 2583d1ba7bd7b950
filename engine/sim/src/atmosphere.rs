//! The standard atmosphere: temperature, pressure, density, speed of sound and viscosity of the
//! air as a function of height, for drag and Mach/Reynolds numbers.
//!
//! Model: U.S. Standard Atmosphere 1976 (identical to the ICAO/ISO International Standard
//! Atmosphere below 32 km), the seven lower layers of linear molecular-scale temperature in
//! *geopotential* altitude, from sea level to 86 km geometric. Source: COESA, *U.S. Standard
//! Atmosphere, 1976*, NOAA-S/T 76-1562, U.S. Government Printing Office, 1976 (equations 18,
//! 23, 33a/b, 50, 51 and table 4).
//!
//! Constants (all from that document):
//! - `g0` = 9.80665 m/s², sea-level gravity used to define geopotential altitude;
//! - `R` = R*/M0 = 8314.32 / 28.9644 ≈ 287.05287 J/(kg·K), specific gas constant of air;
//! - `r0` = 6 356 766 m, the Earth radius of the geometric → geopotential conversion
//!   `H = r0·Z / (r0 + Z)`;
//! - sea level: 288.15 K, 101 325 Pa; ratio of specific heats γ = 1.4;
//! - Sutherland's law μ = β T^{3/2} / (T + S), β = 1.458e-6 kg/(m·s·K^½), S = 110.4 K.
//!
//! Layer bases (geopotential m) and lapse rates (K/km): 0 / −6.5, 11 000 / 0, 20 000 / +1.0,
//! 32 000 / +2.8, 47 000 / 0, 51 000 / −2.8, 71 000 / −2.0, top 84 852 (= 86 km geometric).
//! Base temperatures and pressures are computed once, in [`Atmosphere::standard`], from the
//! layer chain (they reproduce the published 22 632.06 Pa, 5 474.889 Pa, … to 7 digits).
//!
//! Conventions and edges:
//! - [`Atmosphere::at`] takes the height **above the launch site (ground)**; the site's
//!   elevation above mean sea level, given once to [`Atmosphere::standard`], is added inside.
//!   [`Atmosphere::at_msl`] takes the geometric altitude above mean sea level directly.
//! - Below −5 km geometric the altitude is **clamped** to −5 km (the air there is returned).
//! - Above 86 km the atmosphere is **extrapolated isothermally** at the 86 km temperature
//!   (186.946 K): pressure and density keep falling exponentially (scale height ≈ 5.5 km),
//!   which stays close to the real upper atmosphere to ~100 km and never goes negative or NaN.
//! - The temperature returned is the molecular-scale temperature `T_M`. It equals the kinetic
//!   temperature below 80 km; between 80 and 86 km the kinetic one is lower by at most 0.04 %
//!   (186.87 vs 186.946 K at 86 km). Pressure and density are exact (ρ = P / (R·T_M)).
//!
//! [`Atmosphere::at`] is pure, allocation-free and branch-light: it is called per derivative
//! evaluation.

use thiserror::Error;

/// Standard gravity used by the geopotential definition, m/s².
pub const G0_M_S2: f64 = 9.80665;
/// Specific gas constant of air, R*/M0 = 8314.32 / 28.9644 ≈ 287.05287 J/(kg·K).
pub const R_AIR_J_KG_K: f64 = 8314.32 / 28.9644;
/// Earth radius of the geometric ↔ geopotential conversion, m.
pub const R0_GEOPOTENTIAL_M: f64 = 6_356_766.0;
/// Ratio of specific heats of air.
pub const GAMMA_AIR: f64 = 1.4;
/// Sea-level standard temperature, K.
pub const T0_K: f64 = 288.15;
/// Sea-level standard pressure, Pa.
pub const P0_PA: f64 = 101_325.0;
/// Sutherland's constant β, kg/(m·s·K^½).
pub const SUTHERLAND_BETA: f64 = 1.458e-6;
/// Sutherland's temperature S, K.
pub const SUTHERLAND_S_K: f64 = 110.4;
/// Lowest geometric altitude above mean sea level of the model (clamped below), m.
pub const MIN_ALTITUDE_MSL_M: f64 = -5_000.0;
/// Top of the tabulated model (isothermal extrapolation above), geometric m.
pub const MAX_ALTITUDE_MSL_M: f64 = 86_000.0;

/// Layer bases in geopotential metres; the last entry is the top of the table (86 km geometric).
const LAYER_BASE_M: [f64; 8] = [
    0.0, 11_000.0, 20_000.0, 32_000.0, 47_000.0, 51_000.0, 71_000.0, 84_852.0,
];
/// Lapse rates dT/dH of the layers starting at `LAYER_BASE_M[i]`, K/m. The last one (above
/// 86 km) is the isothermal extrapolation.
const LAPSE_K_M: [f64; 8] = [-6.5e-3, 0.0, 1.0e-3, 2.8e-3, 0.0, -2.8e-3, -2.0e-3, 0.0];

/// State of the air at one height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirState {
    /// Molecular-scale temperature (= kinetic below 80 km), K.
    pub temperature_k: f64,
    /// Static pressure, Pa.
    pub pressure_pa: f64,
    /// Density, kg/m³.
    pub density_kg_m3: f64,
    /// Speed of sound √(γ R T), m/s.
    pub speed_of_sound_m_s: f64,
    /// Dynamic viscosity from Sutherland's law, Pa·s.
    pub dynamic_viscosity_pa_s: f64,
}

/// Invalid atmosphere settings.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AtmosphereError {
    /// The launch-site elevation is not a finite number within the model's range.
    #[error(
        "atmosphere: `launch_elevation_m` = {value} m: must be finite and within \
         [{MIN_ALTITUDE_MSL_M}, {MAX_ALTITUDE_MSL_M}] m above mean sea level"
    )]
    LaunchElevation {
        /// The rejected value, m.
        value: f64,
    },
}

/// One layer of the model, precomputed.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Layer {
    base_m: f64,
    lapse_k_m: f64,
    t_base_k: f64,
    p_base_pa: f64,
    /// `g0 / (R L)` for a gradient layer, `g0 / (R T_b)` for an isothermal one.
    exponent: f64,
}

/// The standard atmosphere seen from one launch site.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere {
    launch_elevation_m: f64,
    layers: [Layer; 8],
}

impl Atmosphere {
    /// The US 1976 standard atmosphere over a site `launch_elevation_m` above mean sea level.
    pub fn standard(launch_elevation_m: f64) -> Result<Self, AtmosphereError> {
        if !launch_elevation_m.is_finite()
            || !(MIN_ALTITUDE_MSL_M..=MAX_ALTITUDE_MSL_M).contains(&launch_elevation_m)
        {
            return Err(AtmosphereError::LaunchElevation {
                value: launch_elevation_m,
            });
        }
        let mut layers = [Layer {
            base_m: 0.0,
            lapse_k_m: 0.0,
            t_base_k: T0_K,
            p_base_pa: P0_PA,
            exponent: 0.0,
        }; 8];
        let mut t_b = T0_K;
        let mut p_b = P0_PA;
        for i in 0..8 {
            let lapse = LAPSE_K_M[i];
            let exponent = if lapse == 0.0 {
                G0_M_S2 / (R_AIR_J_KG_K * t_b)
            } else {
                G0_M_S2 / (R_AIR_J_KG_K * lapse)
            };
            layers[i] = Layer {
                base_m: LAYER_BASE_M[i],
                lapse_k_m: lapse,
                t_base_k: t_b,
                p_base_pa: p_b,
                exponent,
            };
            if i + 1 < 8 {
                let dh = LAYER_BASE_M[i + 1] - LAYER_BASE_M[i];
                let (t_top, p_top) = layers[i].temperature_pressure(dh);
                t_b = t_top;
                p_b = p_top;
            }
        }
        Ok(Self {
            launch_elevation_m,
            layers,
        })
    }

    /// Elevation of the launch site above mean sea level, m.
    pub fn launch_elevation_m(&self) -> f64 {
        self.launch_elevation_m
    }

    /// The air at `altitude_above_ground_m` metres above the launch site (the site elevation
    /// is added here). See the module docs for the behaviour outside −5 km … 86 km MSL.
    #[inline]
    pub fn at(&self, altitude_above_ground_m: f64) -> AirState {
        self.at_msl(self.launch_elevation_m + altitude_above_ground_m)
    }

    /// The air at geometric altitude `altitude_msl_m` above mean sea level.
    #[inline]
    pub fn at_msl(&self, altitude_msl_m: f64) -> AirState {
        let z = altitude_msl_m.max(MIN_ALTITUDE_MSL_M);
        let h = geopotential_altitude_m(z);
        // Seven bases above 0: find the last layer whose base is below h (layer 0 below 0 m).
        let mut i = 7;
        while i > 0 && h < self.layers[i].base_m {
            i -= 1;
        }
        let layer = &self.layers[i];
        let (t, p) = layer.temperature_pressure(h - layer.base_m);
        air_state(t, p)
    }
}

impl Layer {
    /// Temperature and pressure `dh` geopotential metres above this layer's base.
    #[inline]
    fn temperature_pressure(&self, dh: f64) -> (f64, f64) {
        if self.lapse_k_m == 0.0 {
            (self.t_base_k, self.p_base_pa * (-self.exponent * dh).exp())
        } else {
            let t = self.t_base_k + self.lapse_k_m * dh;
            (t, self.p_base_pa * (self.t_base_k / t).powf(self.exponent))
        }
    }
}

/// Geopotential altitude (m') of geometric altitude `z_m` above mean sea level:
/// `H = r0 Z / (r0 + Z)`.
#[inline]
pub fn geopotential_altitude_m(z_m: f64) -> f64 {
    R0_GEOPOTENTIAL_M * z_m / (R0_GEOPOTENTIAL_M + z_m)
}

/// Geometric altitude of geopotential altitude `h_m`: `Z = r0 H / (r0 − H)`.
#[inline]
pub fn geometric_altitude_m(h_m: f64) -> f64 {
    R0_GEOPOTENTIAL_M * h_m / (R0_GEOPOTENTIAL_M - h_m)
}

/// Derived quantities of air at temperature `t` K and pressure `p` Pa.
#[inline]
fn air_state(t: f64, p: f64) -> AirState {
    AirState {
        temperature_k: t,
        pressure_pa: p,
        density_kg_m3: p / (R_AIR_J_KG_K * t),
        speed_of_sound_m_s: (GAMMA_AIR * R_AIR_J_KG_K * t).sqrt(),
        dynamic_viscosity_pa_s: SUTHERLAND_BETA * t * t.sqrt() / (t + SUTHERLAND_S_K),
    }
}

/// Spacing of [`AirTable`], m.
pub const AIR_TABLE_STEP_M: f64 = 10.0;

/// Density and speed of sound of the standard atmosphere tabulated every
/// [`AIR_TABLE_STEP_M`] of altitude above sea level, from −5 km to 86 km, built once per
/// process ([`AirTable::standard`]) and shared by every flight and every lane of a batch, so
/// that the derivative, called thousands of times, interpolates instead of evaluating powers
/// and exponentials. Linear interpolation at 10 m spacing holds the density and the speed of
/// sound to 5e-7 of themselves inside each layer (below 11 km, where rockets of this kind fly,
/// throughout), and to 1e-4 within 10 m of a layer boundary, where the lapse rate jumps;
/// outside the table the exact model answers.
#[derive(Debug, Clone, PartialEq)]
pub struct AirTable {
    /// (density kg/m³, speed of sound m/s) at altitudes −5000, −4990, ... m above sea level.
    nodes: Vec<(f64, f64)>,
}

/// Density and speed of sound, the part of [`AirState`] a flight reads every step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Air {
    pub density_kg_m3: f64,
    pub speed_of_sound_m_s: f64,
}

static STANDARD_TABLE: std::sync::OnceLock<AirTable> = std::sync::OnceLock::new();

impl AirTable {
    /// The standard atmosphere's table, built on first use.
    pub fn standard() -> &'static AirTable {
        STANDARD_TABLE.get_or_init(|| {
            let atm = Atmosphere::standard(0.0).expect("sea level is a valid site");
            let n = ((MAX_ALTITUDE_MSL_M - MIN_ALTITUDE_MSL_M) / AIR_TABLE_STEP_M) as usize + 1;
            let nodes = (0..n)
                .map(|i| {
                    let a = atm.at_msl(MIN_ALTITUDE_MSL_M + i as f64 * AIR_TABLE_STEP_M);
                    (a.density_kg_m3, a.speed_of_sound_m_s)
                })
                .collect();
            AirTable { nodes }
        })
    }

    /// Density and speed of sound at `altitude_msl_m` above sea level.
    #[inline]
    pub fn at_msl(&self, altitude_msl_m: f64) -> Air {
        let x = (altitude_msl_m - MIN_ALTITUDE_MSL_M) / AIR_TABLE_STEP_M;
        if x >= 0.0 && x < (self.nodes.len() - 1) as f64 {
            let i = x as usize;
            let f = x - i as f64;
            let (a, b) = (self.nodes[i], self.nodes[i + 1]);
            Air {
                density_kg_m3: a.0 + f * (b.0 - a.0),
                speed_of_sound_m_s: a.1 + f * (b.1 - a.1),
            }
        } else {
            let a = standard_msl(altitude_msl_m);
            Air {
                density_kg_m3: a.density_kg_m3,
                speed_of_sound_m_s: a.speed_of_sound_m_s,
            }
        }
    }

    /// [`AirTable::at_msl`] at four altitudes, lane by lane the same operations: the four
    /// cells are found side by side (in vector registers where the caller is compiled for
    /// them); if any altitude is outside the table, each lane takes `at_msl` itself.
    #[inline(always)]
    pub fn at_msl_four(&self, altitude_msl_m: [f64; 4]) -> ([f64; 4], [f64; 4]) {
        let cells = self.nodes.len() - 1;
        let x = altitude_msl_m.map(|z| (z - MIN_ALTITUDE_MSL_M) / AIR_TABLE_STEP_M);
        if x.iter().all(|&x| x >= 0.0 && x < cells as f64) {
            let (i, f) = crate::lanes::grid_cells(x, cells);
            let a: [(f64, f64); 4] = std::array::from_fn(|l| self.nodes[i[l]]);
            let b: [(f64, f64); 4] = std::array::from_fn(|l| self.nodes[i[l] + 1]);
            (
                std::array::from_fn(|l| a[l].0 + f[l] * (b[l].0 - a[l].0)),
                std::array::from_fn(|l| a[l].1 + f[l] * (b[l].1 - a[l].1)),
            )
        } else {
            let air = altitude_msl_m.map(|z| self.at_msl(z));
            (
                air.map(|a| a.density_kg_m3),
                air.map(|a| a.speed_of_sound_m_s),
            )
        }
    }
}

fn standard_msl(z: f64) -> AirState {
    Atmosphere::standard(0.0)
        .expect("sea level is a valid site")
        .at_msl(z)
}

#[cfg(test)]
mod table_tests {
    use super::*;

    #[test]
    fn four_altitudes_at_once_read_the_table_as_one_altitude_does_bit_for_bit() {
        let table = AirTable::standard();
        // Inside the table, on its nodes, at and past both ends (mixed in one call too).
        let mut z: Vec<f64> = (0..40_000).map(|k| -5_000.0 + 2.371 * k as f64).collect();
        z.extend([
            -5_000.0, -5_000.1, -9e9, 86_000.0, 85_999.99, 86_000.5, 1e12, 0.0, -0.0,
        ]);
        z.extend((0..200).map(|k| -5_000.0 + 10.0 * k as f64));
        for w in z.chunks(4) {
            let mut four = [1234.5; 4];
            four[..w.len()].copy_from_slice(w);
            let (rho, sound) = table.at_msl_four(four);
            for l in 0..4 {
                let one = table.at_msl(four[l]);
                assert_eq!(rho[l].to_bits(), one.density_kg_m3.to_bits(), "{}", four[l]);
                assert_eq!(
                    sound[l].to_bits(),
                    one.speed_of_sound_m_s.to_bits(),
                    "{}",
                    four[l]
                );
            }
        }
    }

    #[test]
    fn the_air_table_follows_the_standard_atmosphere_to_its_interpolation_error() {
        for elevation in [0.0, 1400.0] {
            let atm = Atmosphere::standard(elevation).unwrap();
            let table = AirTable::standard();
            // Inside a layer the error is the interpolation's, h²/8 · ρ''/ρ (h = 10 m, scale
            // height ≥ 6 km): ≤ 5e-7. Within one step of a layer boundary (the first at 11 km)
            // the lapse rate's jump adds up to ΔL/T · h/4 ≈ 1e-4.
            let (mut er, mut ea, mut er_trop): (f64, f64, f64) = (0.0, 0.0, 0.0);
            let mut h = -50.0;
            while h < 90_000.0 {
                let (t, x) = (table.at_msl(h + elevation), atm.at(h));
                let e = (t.density_kg_m3 - x.density_kg_m3).abs() / x.density_kg_m3;
                er = er.max(e);
                if h + elevation < 10_990.0 {
                    er_trop = er_trop.max(e).max(
                        (t.speed_of_sound_m_s - x.speed_of_sound_m_s).abs() / x.speed_of_sound_m_s,
                    );
                }
                ea = ea.max(
                    (t.speed_of_sound_m_s - x.speed_of_sound_m_s).abs() / x.speed_of_sound_m_s,
                );
                h += 3.7;
            }
            eprintln!("elevation {elevation} m: below 11 km within {er_trop:.1e}; everywhere density within {er:.1e}, speed of sound within {ea:.1e}");
            assert!(er_trop <= 5e-7, "{er_trop:e}");
            assert!(er <= 1e-4 && ea <= 1e-4, "{er:e} {ea:e}");
            // At the nodes the table is the model.
            assert_eq!(
                table.at_msl(1000.0 + elevation).density_kg_m3,
                atm.at(1000.0).density_kg_m3
            );
        }
    }
}

#[cfg(test)]
mod tests {
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
}
