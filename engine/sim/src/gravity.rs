//! Gravitational acceleration as a function of height above the launch site.
//!
//! Default: the constant standard gravity g0 = 9.80665 m/s² (CGPM 1901), which is what most
//! hobby-rocketry simulators use and is accurate to 0.3 % up to 10 km. Optionally an
//! inverse-square law `g = g0 (R / (R + z))²` with `z` the altitude above mean sea level
//! (launch-site elevation + height above ground) and `R` the Earth's mean radius, by default
//! 6 371 008.8 m (IUGG mean radius R1). Or, for a site of known latitude, the normal gravity
//! of the WGS 84 ellipsoid (Somigliana's formula) with its second-order free-air correction in
//! the height above the ellipsoid, which is RocketPy's default (`Environment(gravity=None)`,
//! `somigliana_gravity`) and already holds the centrifugal part of the Earth's rotation. All
//! are pure and allocation-free.
//!
//! The launch frame is flat. The Earth's rotation enters the flight as the Coriolis
//! acceleration, which [`crate::flight::Environment::latitude_deg`] switches on
//! ([`earth_rate_n`]).

use thiserror::Error;

/// Standard gravity, m/s².
pub const STANDARD_GRAVITY_M_S2: f64 = 9.80665;
/// Earth mean radius (IUGG R1), m.
pub const EARTH_MEAN_RADIUS_M: f64 = 6_371_008.8;

/// The Earth's rotation rate, rad/s: one turn per sidereal day of 86 164.1 s (RocketPy's
/// value; the IERS's 7.292115e-5 rad/s differs by 2e-8 relative).
pub const EARTH_RATE_RAD_S: f64 = 2.0 * std::f64::consts::PI / 86_164.1;

/// The rule a site's latitude keeps (degrees north), for every place that checks one.
pub const LATITUDE_RULE: &str = "must be finite and within [-90, 90]";

/// Whether `latitude_deg` keeps [`LATITUDE_RULE`].
pub fn is_latitude(latitude_deg: f64) -> bool {
    latitude_deg.is_finite() && latitude_deg.abs() <= 90.0
}

/// The Earth's rotation vector at a site of latitude `latitude_deg` (north positive) in the
/// launch frame (x east, y north, z up), rad/s: `ω (0, cos φ, sin φ)`.
pub fn earth_rate_n(latitude_deg: f64) -> [f64; 3] {
    let (s, c) = latitude_deg.to_radians().sin_cos();
    [0.0, EARTH_RATE_RAD_S * c, EARTH_RATE_RAD_S * s]
}

// WGS 84 (NIMA TR8350.2, 3rd ed., tables 3.1 and 3.4), as RocketPy's `somigliana_gravity`.
const WGS84_A_M: f64 = 6_378_137.0;
const WGS84_F: f64 = 1.0 / 298.257_223_563;
/// ω²a²b/GM.
const WGS84_M: f64 = 3.449_786_506_841e-3;
/// Normal gravity at the equator, m/s².
const WGS84_G_E: f64 = 9.780_325_335_9;
/// Somigliana's constant k = (b γ_p)/(a γ_e) − 1.
const WGS84_K: f64 = 1.931_852_652_458e-3;
/// First eccentricity squared.
const WGS84_E2: f64 = 6.694_379_990_141e-3;

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
    /// `g0 (1 − c1 z + c2 z²)` in the height `z` above the ellipsoid (site elevation plus
    /// height above the site); `g0_m_s2` is the normal gravity on the ellipsoid.
    Ellipsoid {
        c1_per_m: f64,
        c2_per_m2: f64,
        latitude_deg: f64,
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

    /// The normal gravity of the WGS 84 ellipsoid at latitude `latitude_deg` (Somigliana's
    /// formula), `γ = g_e (1 + k sin²φ) / √(1 − e² sin²φ)`, with the free-air correction
    /// `γ(z) = γ (1 − 2z/a (1 + f + m − 2f sin²φ) + 3z²/a²)` in the height `z` above the
    /// ellipsoid, over a site `launch_elevation_m` above it: RocketPy's default gravity.
    pub fn somigliana(latitude_deg: f64, launch_elevation_m: f64) -> Result<Self, GravityError> {
        if !is_latitude(latitude_deg) {
            return Err(GravityError::Setting {
                field: "latitude_deg",
                value: latitude_deg,
                rule: LATITUDE_RULE,
            });
        }
        if !launch_elevation_m.is_finite() {
            return Err(GravityError::Setting {
                field: "launch_elevation_m",
                value: launch_elevation_m,
                rule: "must be finite",
            });
        }
        let s2 = latitude_deg.to_radians().sin().powi(2);
        Ok(Self {
            g0_m_s2: WGS84_G_E * (1.0 + WGS84_K * s2) / (1.0 - WGS84_E2 * s2).sqrt(),
            model: Model::Ellipsoid {
                c1_per_m: 2.0 / WGS84_A_M * (1.0 + WGS84_F + WGS84_M - 2.0 * WGS84_F * s2),
                c2_per_m2: 3.0 / (WGS84_A_M * WGS84_A_M),
                latitude_deg,
                launch_elevation_m,
            },
        })
    }

    /// The same gravity over a launch site `launch_elevation_m` above mean sea level: an
    /// inverse-square law or the ellipsoid's keeps its constants and moves its site; a
    /// constant one is the same everywhere. For a dispersion or sweep of the site's elevation.
    pub fn at_launch_elevation(&self, launch_elevation_m: f64) -> Result<Self, GravityError> {
        match self.model {
            Model::Constant => Ok(*self),
            Model::InverseSquare { radius_m, .. } => {
                Self::inverse_square_with(self.g0_m_s2, radius_m, launch_elevation_m)
            }
            Model::Ellipsoid { latitude_deg, .. } => {
                Self::somigliana(latitude_deg, launch_elevation_m)
            }
        }
    }

    /// The magnitude of a gravity that is the same at every height, m/s²; `None` when it
    /// changes with height.
    #[inline]
    pub fn constant_m_s2(&self) -> Option<f64> {
        matches!(self.model, Model::Constant).then_some(self.g0_m_s2)
    }

    /// Magnitude of gravity at `height_agl_m` above the launch site, m/s² (pointing down).
    #[inline]
    pub fn at(&self, height_agl_m: f64) -> f64 {
        // The constant model first and alone: the flights' usual case stays one test.
        if let Some(g) = self.constant_m_s2() {
            return g;
        }
        match self.model {
            Model::Constant => self.g0_m_s2,
            Model::InverseSquare {
                radius_m,
                launch_elevation_m,
            } => {
                let q = radius_m / (radius_m + launch_elevation_m + height_agl_m);
                self.g0_m_s2 * q * q
            }
            Model::Ellipsoid {
                c1_per_m,
                c2_per_m2,
                launch_elevation_m,
                ..
            } => {
                let z = launch_elevation_m + height_agl_m;
                self.g0_m_s2 * (1.0 - c1_per_m * z + c2_per_m2 * z * z)
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
    fn somigliana_gravity_is_wgs84_normal_gravity_at_the_equator_and_the_poles() {
        // WGS 84 (NIMA TR8350.2, table 3.4): γ_e = 9.7803253359, γ_p = 9.8321849378 m/s².
        let at = |lat: f64| Gravity::somigliana(lat, 0.0).unwrap().at(0.0);
        assert_eq!(at(0.0), 9.780_325_335_9);
        assert!((at(90.0) - 9.832_184_937_8).abs() < 1e-9, "{}", at(90.0));
        assert!((at(-90.0) - 9.832_184_937_8).abs() < 1e-9);
        assert!(at(45.0) > at(30.0) && at(45.0) < at(60.0));
    }

    #[test]
    fn somigliana_gravity_at_spaceport_america_is_rocketpy_s() {
        // RocketPy 1.13's Environment(latitude=32.990254, elevation=1400) gravity, as
        // validation/rocketpy/calisto_reference.json (facts) records it at 0, 1400, 4705 and
        // 10000 m above sea level. RocketPy samples its formula at 100 heights and splines
        // them, 6.6e-9 m/s² off the formula at 1400 m: 1e-8 m/s² covers that.
        let g = Gravity::somigliana(32.990254, 1400.0).unwrap();
        for (asl, rocketpy) in [
            (0.0, 9.795652669148597),
            (1400.0, 9.79133308624842),
            (4705.0, 9.78114704051094),
            (10000.0, 9.764860677799257),
        ] {
            let ours = g.at(asl - 1400.0);
            assert!(
                (ours - rocketpy).abs() < 1e-8,
                "{asl} m: {ours} vs {rocketpy}"
            );
        }
        // The free-air gradient near the ground: 2γ/a (1 + f + m − 2f sin²φ) = 3.08e-6 s⁻².
        let slope = (g.at(0.0) - g.at(100.0)) / 100.0;
        assert!((slope - 3.0835e-6).abs() < 1e-9, "{slope:e}");
        // Moving the site moves the ellipsoid's height, not the latitude.
        let moved = Gravity::somigliana(32.990254, 0.0)
            .unwrap()
            .at_launch_elevation(1400.0)
            .unwrap();
        assert_eq!(moved, g);
    }

    #[test]
    fn the_earth_turns_once_a_sidereal_day_about_the_local_north_and_up() {
        assert!((EARTH_RATE_RAD_S - 7.292_115e-5).abs() < 2e-12);
        let pole = earth_rate_n(90.0);
        assert_eq!(pole[0], 0.0);
        assert!(pole[1].abs() < 1e-20 && (pole[2] - EARTH_RATE_RAD_S).abs() < 1e-20);
        let eq = earth_rate_n(0.0);
        assert_eq!(eq, [0.0, EARTH_RATE_RAD_S, 0.0]);
        // RocketPy's earth_rotation_vector at 32.990254° (calisto_reference.json, facts).
        let site = earth_rate_n(32.990254);
        assert!(
            (site[1] - 6.116357748625292e-05).abs() < 1e-18,
            "{}",
            site[1]
        );
        assert!(
            (site[2] - 3.97053017247332e-05).abs() < 1e-18,
            "{}",
            site[2]
        );
        let south = earth_rate_n(-30.0);
        assert!((south[2] + 0.5 * EARTH_RATE_RAD_S).abs() < 1e-18);
        assert!((south[1] - EARTH_RATE_RAD_S * 0.75f64.sqrt()).abs() < 1e-18);
    }

    #[test]
    fn bad_gravity_settings_are_typed_errors() {
        for bad in [91.0, -90.5, f64::NAN] {
            let e = Gravity::somigliana(bad, 0.0).unwrap_err();
            assert!(e.to_string().contains("latitude_deg"), "{e}");
        }
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
