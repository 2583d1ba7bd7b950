//! The atmosphere tabulated for the derivative: density and speed of sound every 10 m.

use crate::lanes::four;

use super::{
    geopotential_altitude_m, AirModel, Atmosphere, AtmosphereError, MAX_ALTITUDE_MSL_M,
    MIN_ALTITUDE_MSL_M,
};

/// Spacing of [`AirTable`], m.
pub const AIR_TABLE_STEP_M: f64 = 10.0;

/// Density and speed of sound of an atmosphere tabulated every [`AIR_TABLE_STEP_M`] of
/// altitude above sea level, from −5 km to 86 km: the standard's built once per process
/// ([`AirTable::standard`]) and shared by every flight and every lane of a batch, a site's
/// built once per flight set-up that names it ([`AirTable::new`]) and shared by the variants
/// made from it, so that the derivative, called thousands of times, interpolates instead of
/// evaluating powers and exponentials. Linear interpolation at 10 m spacing holds the density
/// and the speed of sound to 5e-7 of themselves inside each layer (below 11 km, where rockets
/// of this kind fly, throughout), and to 1e-4 within 10 m of a layer boundary, where the
/// lapse rate jumps; outside the table the exact model answers.
#[derive(Debug, Clone, PartialEq)]
pub struct AirTable {
    /// The atmosphere tabulated.
    model: AirModel,
    /// It, exact, for altitudes outside the table.
    exact: Atmosphere,
    /// (density kg/m³, speed of sound m/s) at altitudes −5000, −4990, ... m above sea level.
    nodes: Vec<(f64, f64)>,
}

/// Density and speed of sound, the part of [`AirState`](crate::atmosphere::AirState) a flight
/// reads every step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Air {
    pub density_kg_m3: f64,
    pub speed_of_sound_m_s: f64,
}

static STANDARD_TABLE: std::sync::OnceLock<std::sync::Arc<AirTable>> = std::sync::OnceLock::new();

impl AirTable {
    /// The standard atmosphere's table, built on first use.
    pub fn standard() -> std::sync::Arc<AirTable> {
        STANDARD_TABLE
            .get_or_init(|| {
                std::sync::Arc::new(
                    AirTable::build(AirModel::Standard).expect("the standard atmosphere is valid"),
                )
            })
            .clone()
    }

    /// The table of `model`: the shared standard one, or a new one of a site's air.
    pub fn new(model: &AirModel) -> Result<std::sync::Arc<AirTable>, AtmosphereError> {
        match model {
            AirModel::Standard => Ok(AirTable::standard()),
            other => AirTable::build(other.clone()).map(std::sync::Arc::new),
        }
    }

    fn build(model: AirModel) -> Result<AirTable, AtmosphereError> {
        let exact = Atmosphere::new(0.0, &model)?;
        let n = ((MAX_ALTITUDE_MSL_M - MIN_ALTITUDE_MSL_M) / AIR_TABLE_STEP_M) as usize + 1;
        let altitude = |i: usize| MIN_ALTITUDE_MSL_M + i as f64 * AIR_TABLE_STEP_M;
        let exact_node = |i: usize| {
            let a = exact.at_msl(altitude(i));
            (a.density_kg_m3, a.speed_of_sound_m_s)
        };
        let nodes = match model {
            AirModel::Standard | AirModel::Profile(_) => (0..n).map(exact_node).collect(),
            // A site's layers above 11 km are the standard's temperatures, so its pressure
            // and density there are the standard's times one ratio, that of the pressures at
            // 11 km: the standard's nodes scaled, not 7,500 powers and exponentials again
            // (a variant whose site air is swept or dispersed builds its table before it
            // flies). The scaled nodes are the exact model's to a few units in the last place.
            AirModel::Site { .. } => {
                let standard = AirTable::standard();
                let (site_11km, standard_11km) = (&exact.layers[1], &standard.exact.layers[1]);
                let ratio = site_11km.p_base_pa / standard_11km.p_base_pa;
                (0..n)
                    .map(|i| {
                        if geopotential_altitude_m(altitude(i)) >= site_11km.base_m {
                            let (rho, sound) = standard.nodes[i];
                            (rho * ratio, sound)
                        } else {
                            exact_node(i)
                        }
                    })
                    .collect()
            }
        };
        Ok(AirTable {
            model,
            exact,
            nodes,
        })
    }

    /// The static pressure at `altitude_msl_m` above sea level, Pa, from the exact layers
    /// (not tabulated: a flight reads it only where a noisy barometer is judged).
    pub fn pressure_msl_pa(&self, altitude_msl_m: f64) -> f64 {
        self.exact.at_msl(altitude_msl_m).pressure_pa
    }

    /// The atmosphere this table holds.
    pub fn model(&self) -> &AirModel {
        &self.model
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
            let a = self.exact.at_msl(altitude_msl_m);
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
        let z = altitude_msl_m;
        let x = four!(l => (z[l] - MIN_ALTITUDE_MSL_M) / AIR_TABLE_STEP_M);
        // Compared side by side, without short cuts, so the four tests run as one.
        let inside: [bool; 4] = std::array::from_fn(|l| (x[l] >= 0.0) & (x[l] < cells as f64));
        if inside == [true; 4] {
            let (i, f) = crate::lanes::grid_cells(x, cells);
            let a: [(f64, f64); 4] = four!(l => self.nodes[i[l]]);
            let b: [(f64, f64); 4] = four!(l => self.nodes[i[l] + 1]);
            (
                four!(l => a[l].0 + f[l] * (b[l].0 - a[l].0)),
                four!(l => a[l].1 + f[l] * (b[l].1 - a[l].1)),
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

#[cfg(test)]
mod tests {
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

    #[test]
    fn a_site_s_nodes_above_11_km_are_the_standard_s_scaled_and_equal_its_exact_model() {
        // Hot and low, cold and high, and the standard's own air given as a site's.
        for (elevation_m, temperature_k, pressure_pa) in [
            (1400.0, 308.15, 85_600.0),
            (4200.0, 250.0, 60_000.0),
            (0.0, 288.15, 101_325.0),
        ] {
            let model = AirModel::Site {
                elevation_m,
                temperature_k,
                pressure_pa,
            };
            let table = AirTable::new(&model).unwrap();
            let exact = Atmosphere::new(0.0, &model).unwrap();
            let (mut worst_rho, mut worst_sound, mut scaled) = (0.0f64, 0.0f64, 0);
            for (i, &(rho, sound)) in table.nodes.iter().enumerate() {
                let z = MIN_ALTITUDE_MSL_M + i as f64 * AIR_TABLE_STEP_M;
                let a = exact.at_msl(z);
                if geopotential_altitude_m(z) >= 11_000.0 {
                    scaled += 1;
                } else {
                    // Below 11 km every node is the site's exact air.
                    assert_eq!((rho, sound), (a.density_kg_m3, a.speed_of_sound_m_s));
                }
                worst_rho = worst_rho.max((rho - a.density_kg_m3).abs() / a.density_kg_m3);
                worst_sound =
                    worst_sound.max((sound - a.speed_of_sound_m_s).abs() / a.speed_of_sound_m_s);
            }
            eprintln!("{model:?}: {scaled} nodes scaled, density within {worst_rho:.1e}, sound within {worst_sound:.1e}");
            // 11 km geopotential is 11,019.07 m geometric: the nodes 11,020, 11,030, ... 86,000 m.
            assert_eq!(scaled, (86_000 - 11_020) / 10 + 1);
            // A few units in the last place (2.2e-16 each).
            assert!(worst_rho < 4e-15, "{worst_rho:e}");
            assert!(worst_sound < 1e-15, "{worst_sound:e}");
        }
    }
}
