//! Gravitational acceleration as a function of height above the launch site.
//!
//! Default: the constant standard gravity g0 = 9.80665 m/s² (CGPM 1901), which is what most
//! hobby-rocketry simulators use and is accurate to 0.3 % up to 10 km. Optionally an
//! inverse-square law `g = g0 (R / (R + z))²` with `z` the altitude above mean sea level
//! (launch-site elevation + height above ground) and `R` the Earth's mean radius, by default
//! 6 371 008.8 m (IUGG mean radius R1). Both are pure and allocation-free.
//!
//! No latitude or centrifugal term: the launch frame is treated as inertial and flat.

use thiserror::Error;

/// Standard gravity, m/s².
pub const STANDARD_GRAVITY_M_S2: f64 = 9.80665;
/// Earth mean radius (IUGG R1), m.
pub const EARTH_MEAN_RADIUS_M: f64 = 6_371_008.8;

/// Invalid gravity settings.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GravityError {
    /// A setting is non-finite or out of its range.
    #[error("gravity: `{field}` = {value}: {rule}")]
    Setting {
        /// Name of the setting.
        field: &'static str,
        /// The rejected value.
        value: f64,
        /// The rule broken.
        rule: &'static str,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Model {
    Constant,
    InverseSquare {
        radius_m: f64,
        launch_elevation_m: f64,
    },
}

/// Gravity model. `Default` is the constant standard gravity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity {
    g0_m_s2: f64,
    model: Model,
}

impl Default for Gravity {
    fn default() -> Self {
        Self {
            g0_m_s2: STANDARD_GRAVITY_M_S2,
            model: Model::Constant,
        }
    }
}

impl Gravity {
    /// A constant `g_m_s2` (≥ 0, finite) at every height. Zero is allowed: checks in free
    /// space (no gravity, no air) against exact answers use it.
    pub fn constant(g_m_s2: f64) -> Result<Self, GravityError> {
        if !(g_m_s2.is_finite() && g_m_s2 >= 0.0) {
            return Err(GravityError::Setting {
                field: "g_m_s2",
                value: g_m_s2,
                rule: "must be finite and >= 0",
            });
        }
        Ok(Self {
            g0_m_s2: g_m_s2,
            model: Model::Constant,
        })
    }

    /// Inverse-square gravity with standard g0 and the mean Earth radius, over a launch site
    /// `launch_elevation_m` above mean sea level.
    pub fn inverse_square(launch_elevation_m: f64) -> Result<Self, GravityError> {
        Self::inverse_square_with(
            STANDARD_GRAVITY_M_S2,
            EARTH_MEAN_RADIUS_M,
            launch_elevation_m,
        )
    }

    /// Inverse-square gravity `g0 (R/(R+z))²` with `g0_m_s2` at mean sea level and radius
    /// `radius_m`.
    pub fn inverse_square_with(
        g0_m_s2: f64,
        radius_m: f64,
        launch_elevation_m: f64,
    ) -> Result<Self, GravityError> {
        check_positive("g0_m_s2", g0_m_s2)?;
        check_positive("radius_m", radius_m)?;
        if !launch_elevation_m.is_finite() || launch_elevation_m <= -radius_m {
            return Err(GravityError::Setting {
                field: "launch_elevation_m",
                value: launch_elevation_m,
                rule: "must be finite and above the centre of the Earth",
            });
        }
        Ok(Self {
            g0_m_s2,
            model: Model::InverseSquare {
                radius_m,
                launch_elevation_m,
            },
        })
    }

    /// The same gravity over a launch site `launch_elevation_m` above mean sea level: an
    /// inverse-square law keeps its g0 and radius and moves its site; a constant one is the
    /// same everywhere. For a dispersion or sweep of the site's elevation.
    pub fn at_launch_elevation(&self, launch_elevation_m: f64) -> Result<Self, GravityError> {
        match self.model {
            Model::Constant => Ok(*self),
            Model::InverseSquare { radius_m, .. } => {
                Self::inverse_square_with(self.g0_m_s2, radius_m, launch_elevation_m)
            }
        }
    }

    /// Magnitude of gravity at `height_agl_m` above the launch site, m/s² (pointing down).
    #[inline]
    pub fn at(&self, height_agl_m: f64) -> f64 {
        match self.model {
            Model::Constant => self.g0_m_s2,
            Model::InverseSquare {
                radius_m,
                launch_elevation_m,
            } => {
                let q = radius_m / (radius_m + launch_elevation_m + height_agl_m);
                self.g0_m_s2 * q * q
            }
        }
    }
}

fn check_positive(field: &'static str, value: f64) -> Result<(), GravityError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(GravityError::Setting {
            field,
            value,
            rule: "must be finite and > 0",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_standard_gravity_at_every_height() {
        let g = Gravity::default();
        for h in [-100.0, 0.0, 3_000.0, 1.0e5] {
            assert_eq!(g.at(h), 9.80665);
        }
        assert_eq!(Gravity::constant(9.81).unwrap().at(1e4), 9.81);
    }

    #[test]
    fn inverse_square_gravity_halves_at_sqrt_two_minus_one_earth_radii() {
        let g = Gravity::inverse_square(0.0).unwrap();
        assert_eq!(g.at(0.0), 9.80665);
        let h = EARTH_MEAN_RADIUS_M * (std::f64::consts::SQRT_2 - 1.0);
        let half = g.at(h);
        eprintln!("g at (√2−1)R = {half}");
        assert!((half - 9.80665 / 2.0).abs() < 1e-12);
    }

    #[test]
    fn inverse_square_gravity_at_one_hundred_kilometres_matches_a_hand_calculation() {
        // (6371.0088 / 6471.0088)² = 0.96933…, × 9.80665 = 9.50589 m/s² (by hand, 6 digits).
        let g = Gravity::inverse_square(0.0).unwrap().at(100_000.0);
        eprintln!("g(100 km) = {g}");
        assert!((g - 9.50589).abs() < 1e-5);
    }

    #[test]
    fn inverse_square_gravity_adds_the_launch_elevation() {
        let site = Gravity::inverse_square(1_500.0).unwrap();
        let msl = Gravity::inverse_square(0.0).unwrap();
        assert_eq!(site.at(500.0), msl.at(2_000.0));
        let custom = Gravity::inverse_square_with(10.0, 1000.0, 0.0).unwrap();
        assert!((custom.at(1000.0) - 2.5).abs() < 1e-15);
    }

    #[test]
    fn moving_the_launch_site_moves_inverse_square_gravity_and_leaves_constant_gravity_alone() {
        let moved = Gravity::inverse_square(0.0)
            .unwrap()
            .at_launch_elevation(1_500.0)
            .unwrap();
        assert_eq!(moved, Gravity::inverse_square(1_500.0).unwrap());
        let custom = Gravity::inverse_square_with(10.0, 1000.0, 0.0)
            .unwrap()
            .at_launch_elevation(1000.0)
            .unwrap();
        // 10 (1000 / 2000)² = 2.5 at the new site.
        assert!((custom.at(0.0) - 2.5).abs() < 1e-15);
        let g = Gravity::constant(9.81).unwrap();
        assert_eq!(g.at_launch_elevation(3_000.0).unwrap(), g);
        let e = Gravity::inverse_square(0.0)
            .unwrap()
            .at_launch_elevation(f64::NAN)
            .unwrap_err();
        assert!(e.to_string().contains("launch_elevation_m"));
    }

    #[test]
    fn bad_gravity_settings_are_typed_errors() {
        for bad in [-9.8, f64::NAN, f64::INFINITY] {
            let e = Gravity::constant(bad).unwrap_err();
            assert!(e.to_string().contains("g_m_s2"));
        }
        // Zero gravity is allowed (free-space checks).
        assert_eq!(Gravity::constant(0.0).unwrap().at(1000.0), 0.0);
        let e = Gravity::inverse_square_with(9.8, -1.0, 0.0).unwrap_err();
        assert!(e.to_string().contains("radius_m"));
        let e = Gravity::inverse_square(f64::NAN).unwrap_err();
        assert!(e.to_string().contains("launch_elevation_m"));
    }
}
