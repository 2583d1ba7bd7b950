//! Weather-model files: the air and the wind over a launch site at a launch time, as a
//! reanalysis (ECMWF's ERA5) or a forecast (NOAA's GFS, an ensemble) gives them on pressure
//! levels (RocketPy's `Environment.set_atmospheric_model(type="Reanalysis" | "Forecast" |
//! "Ensemble")`).
//!
//! **The file** is NetCDF, in either layout users meet: the classic one (NetCDF-3, as ERA5
//! was delivered until 2024: `time`, `level`, `latitude`, `longitude`, values packed as short
//! integers with `scale_factor` and `add_offset`) or NetCDF-4 (HDF5 inside, as the Copernicus
//! service has delivered since 2024: `valid_time`, `pressure_level`, unpacked floats). Each
//! quantity is found by its CF standard name, else by the names the services use
//! (`read.rs`): the geopotential (`z`, m²/s²) or the geopotential height (`gh`, `hgtprs`,
//! `Geopotential_height_isobaric`, geopotential metres), the temperature, and the wind's east
//! and north components, on (ensemble member,) time, pressure level, latitude and longitude.
//! A value marked missing (`_FillValue`, `missing_value`) drops its level at that time (as
//! RocketPy drops it); a value that is not finite and not so marked is an error.
//!
//! **Over the site** ([`SiteWeather::read`]): every quantity is interpolated bilinearly in
//! latitude and longitude between the four grid points around the site (a site outside the
//! grid is refused), the site's longitude taken in the grid's own convention (0 to 360 or
//! −180 to 180). Only that cell is read from the file.
//!
//! **At the launch time** ([`SiteWeather::levels`]): every level's geopotential, temperature
//! and wind are interpolated linearly in time between the file's two times around the launch
//! (at a file's time exactly, its own values; outside the file's times, refused with its
//! range). RocketPy takes the file's nearest time instead, which is the same at a file's own
//! time.
//!
//! **Heights** from the geopotential Φ: the geopotential height `H = Φ / g0` (g0 = 9.80665
//! m/s²), then the geometric height above sea level `Z = R H / (R − H)`, with `R` the WGS 84
//! ellipsoid's geocentric radius at the site's latitude ([`earth_radius_m`]): the conversion
//! RocketPy uses for these files (gravity falling off as the inverse square from g0 at a
//! sphere of that radius). 4 km of geopotential height is 2.5 m more of geometric height;
//! the radius's latitude moves that by millimetres (the U.S. Standard Atmosphere's fixed
//! 6,356,766 m, which `crate::sounding` uses for a sounding's heights, differs by 4 mm).
//!
//! **What the flight gets** ([`SiteWeather::over_site`]): the levels become a sounding
//! (`crate::sounding`) and are read as one: the site's temperature interpolated linearly in
//! height between the levels around it and its pressure with ln p linear in height; the air
//! above the site is an [`AirProfile`] through the levels'
//! temperatures, its pressure carried up hydrostatically from the site's (dry air; the
//! files hold no humidity); the wind is a table of the levels' east and north components,
//! interpolated linearly in height. Built once per scenario (or per launch time or member a
//! campaign draws), never in a flight: the flight reads the same air table and wind rows as
//! from any other source.
//!
//! **Edges.** Below the lowest level (a site on the ground below the file's highest
//! pressure, a high-pressure day at the sea's edge) a site may be up to
//! [`BELOW_LOWEST_LEVEL_M`] below it: its temperature and pressure continue the lowest two
//! levels' (lapse and ln p linear in height), its wind is the lowest level's. Above the top
//! level the temperature follows the U.S. Standard Atmosphere's lapse rates shifted to meet
//! the top level's temperature ([`continue_above_top`]), the pressure falls hydrostatically
//! through it, and the wind is the top level's.

mod read;
mod time;

#[cfg(test)]
mod tests;

pub use time::{format_utc, parse_utc, LAUNCH_TIME_RULE};

use crate::atmosphere::{
    geometric_altitude_m, geopotential_altitude_m, AirModel, AirProfile, AirRow, Atmosphere,
    LAYER_BASE_M, MAX_PROFILE_HEIGHT_M, SITE_TEMPERATURE_RANGE_K,
};
use crate::sounding::{Level, SiteAir, Sounding};
use std::path::Path;
use std::sync::Arc;
use thiserror::Error;

/// The largest weather file read, bytes (2 GiB): a day of ERA5 over a country is a few MB; a
/// file past this is refused before it is read.
pub const MAX_WEATHER_FILE_BYTES: u64 = 2 << 30;
/// Most times a file may hold.
pub const MAX_TIMES: usize = 100_000;
/// Most members an ensemble may hold.
pub const MAX_MEMBERS: usize = 1_000;
/// Most (time, member, level) values of one quantity over the site (2 million: a month of
/// hourly ERA5 on its 37 levels is 27,528; a 51-member ensemble's week of 3-hourly
/// forecasts, 105,672): what is read is four times this, the grid cell's corners.
pub const MAX_COLUMN_VALUES: usize = 2_000_000;
/// How far below the file's lowest level a site may be, m.
pub const BELOW_LOWEST_LEVEL_M: f64 = 500.0;
/// The largest wind component taken for a measurement, m/s (the strongest jet streams blow
/// about 120 m/s).
pub const MAX_WIND_M_S: f64 = 250.0;

/// What is wrong with a weather file, or with what is asked of it. The caller names the file.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WeatherError {
    #[error("can't read it: {0}")]
    Io(String),
    #[error("it is {bytes} bytes: a weather file may be at most {MAX_WEATHER_FILE_BYTES} bytes (2 GiB); cut it to the days and the area of the launch")]
    TooLarge { bytes: u64 },
    #[error("it is not a NetCDF file (classic or NetCDF-4) this reader can read: {0}")]
    Format(String),
    #[error("it has no {what} (looked for: {names})")]
    Missing { what: &'static str, names: String },
    #[error("variable \"{variable}\": {rule}")]
    Value { variable: String, rule: String },
    #[error("the site at {latitude_deg}° N, {longitude_deg}° E is outside the file's grid ({lat0} to {lat1}° N, {lon0} to {lon1}° E)")]
    Outside {
        latitude_deg: f64,
        longitude_deg: f64,
        lat0: f64,
        lat1: f64,
        lon0: f64,
        lon1: f64,
    },
    #[error("the launch time {time} is outside the file's times ({first} to {last})")]
    Time {
        time: String,
        first: String,
        last: String,
    },
    #[error("ensemble member {member} is not in the file (its members: {members})")]
    Member { member: f64, members: String },
    #[error("at {time}: {rule}")]
    Site { time: String, rule: String },
}

impl WeatherError {
    fn read(variable: &str, what: &str, e: impl std::fmt::Display) -> WeatherError {
        WeatherError::Value {
            variable: variable.to_string(),
            rule: format!("its {what} can't be read: {e}"),
        }
    }
}

/// A weather file's quantities over one site: every member, time and level, interpolated
/// bilinearly in latitude and longitude (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct SiteWeather {
    pub latitude_deg: f64,
    pub longitude_deg: f64,
    /// The file's times, seconds since 1970 UTC, increasing.
    times_s: Vec<f64>,
    /// The ensemble's member numbers (`[0]` for a file of one).
    members: Vec<f64>,
    /// The pressure levels, Pa, in the file's order.
    levels_pa: Vec<f64>,
    /// Per (member, time, level), `(m · times + t) · levels + l`: the geopotential height
    /// (m), the temperature (K), the wind's east and north components (m/s); `None` where
    /// the file marks a value missing.
    geopotential_height_m: Vec<Option<f64>>,
    temperature_k: Vec<Option<f64>>,
    wind_east_m_s: Vec<Option<f64>>,
    wind_north_m_s: Vec<Option<f64>>,
    /// The variables read: geopotential (or its height), temperature, east wind, north wind.
    variables: [String; 4],
}

impl SiteWeather {
    /// Read the weather file at `path` over the site at `latitude_deg` north,
    /// `longitude_deg` east. The file is read whole (at most [`MAX_WEATHER_FILE_BYTES`]).
    pub fn read(
        path: &Path,
        latitude_deg: f64,
        longitude_deg: f64,
    ) -> Result<SiteWeather, WeatherError> {
        let meta = std::fs::metadata(path).map_err(|e| WeatherError::Io(e.to_string()))?;
        if !meta.is_file() {
            return Err(WeatherError::Io("it is not a file".into()));
        }
        if meta.len() > MAX_WEATHER_FILE_BYTES {
            return Err(WeatherError::TooLarge { bytes: meta.len() });
        }
        let bytes = std::fs::read(path).map_err(|e| WeatherError::Io(e.to_string()))?;
        SiteWeather::from_bytes(&bytes, latitude_deg, longitude_deg)
    }

    /// [`SiteWeather::read`] of a file's bytes.
    pub fn from_bytes(
        bytes: &[u8],
        latitude_deg: f64,
        longitude_deg: f64,
    ) -> Result<SiteWeather, WeatherError> {
        if bytes.len() as u64 > MAX_WEATHER_FILE_BYTES {
            return Err(WeatherError::TooLarge {
                bytes: bytes.len() as u64,
            });
        }
        if !(latitude_deg.is_finite() && latitude_deg.abs() <= 90.0) {
            return Err(WeatherError::Value {
                variable: "latitude".into(),
                rule: format!(
                    "the site's latitude must be finite and within [-90, 90] (got {latitude_deg})"
                ),
            });
        }
        if !(longitude_deg.is_finite() && longitude_deg.abs() <= 360.0) {
            return Err(WeatherError::Value {
                variable: "longitude".into(),
                rule: format!(
                    "the site's longitude must be finite and within [-360, 360] (got {longitude_deg})"
                ),
            });
        }
        // The reader must not take the process down on a corrupt file: a panic in it is the
        // file's fault, reported as one.
        let opened = std::panic::catch_unwind(|| {
            let file = netcdf_reader::NcFile::from_bytes(bytes)
                .map_err(|e| WeatherError::Format(e.to_string()))?;
            read::site_weather(&file, latitude_deg, longitude_deg)
        });
        opened.unwrap_or_else(|_| {
            Err(WeatherError::Format(
                "its structure is corrupt (the NetCDF reader gave up on it)".into(),
            ))
        })
    }

    /// The file's times, seconds since 1970 UTC.
    pub fn times_s(&self) -> &[f64] {
        &self.times_s
    }

    /// The ensemble's member numbers (`[0]` for a file without members).
    pub fn members(&self) -> &[f64] {
        &self.members
    }

    /// The variables read: geopotential (or geopotential height), temperature, east and north
    /// wind.
    pub fn variables(&self) -> &[String; 4] {
        &self.variables
    }

    /// The index of ensemble member `number` (as the file numbers them).
    pub fn member_index(&self, number: f64) -> Result<usize, WeatherError> {
        self.members
            .iter()
            .position(|&m| m == number)
            .ok_or_else(|| WeatherError::Member {
                member: number,
                members: match self.members.as_slice() {
                    [one] => format!("{one} only"),
                    all => format!("{} to {}", all[0], all[all.len() - 1]),
                },
            })
    }

    /// Refuse `time_s` (seconds since 1970 UTC) outside the file's times.
    pub fn check_time(&self, time_s: f64) -> Result<(), WeatherError> {
        let (first, last) = (self.times_s[0], self.times_s[self.times_s.len() - 1]);
        if time_s.is_finite() && (first..=last).contains(&time_s) {
            Ok(())
        } else {
            Err(WeatherError::Time {
                time: format_utc(time_s),
                first: format_utc(first),
                last: format_utc(last),
            })
        }
    }

    /// The levels at `time_s` (seconds since 1970 UTC) of member index `member`, lowest
    /// first, at geometric heights above sea level; the levels missing a value at either of
    /// the two times around it are left out.
    pub fn levels(&self, time_s: f64, member: usize) -> Result<Vec<Level>, WeatherError> {
        self.check_time(time_s)?;
        let nt = self.times_s.len();
        let nl = self.levels_pa.len();
        let k = self
            .times_s
            .partition_point(|&t| t <= time_s)
            .saturating_sub(1)
            .min(nt.saturating_sub(2));
        let (k1, w) = if nt == 1 {
            (0, 0.0)
        } else {
            (
                k + 1,
                (time_s - self.times_s[k]) / (self.times_s[k + 1] - self.times_s[k]),
            )
        };
        let at = |field: &[Option<f64>], l: usize| -> Option<f64> {
            let a = field[(member * nt + k) * nl + l]?;
            let b = field[(member * nt + k1) * nl + l]?;
            Some(if w == 0.0 { a } else { a + w * (b - a) })
        };
        let radius = earth_radius_m(self.latitude_deg);
        let when = format_utc(time_s);
        let mut levels = Vec::with_capacity(nl);
        for l in 0..nl {
            let (Some(h), Some(t), Some(u), Some(v)) = (
                at(&self.geopotential_height_m, l),
                at(&self.temperature_k, l),
                at(&self.wind_east_m_s, l),
                at(&self.wind_north_m_s, l),
            ) else {
                continue;
            };
            let p_hpa = self.levels_pa[l] / 100.0;
            let (lo, hi) = SITE_TEMPERATURE_RANGE_K;
            if !(lo..=hi).contains(&t) {
                return Err(WeatherError::Value {
                    variable: self.variables[1].clone(),
                    rule: format!(
                        "at {when}, {p_hpa} hPa: {t} K is outside [{lo}, {hi}] K, no air a rocket flies in"
                    ),
                });
            }
            if !(u.abs() <= MAX_WIND_M_S && v.abs() <= MAX_WIND_M_S) {
                return Err(WeatherError::Value {
                    variable: self.variables[2..].join(" and "),
                    rule: format!(
                        "at {when}, {p_hpa} hPa: the wind ({u}, {v}) m/s is over {MAX_WIND_M_S} m/s"
                    ),
                });
            }
            if !(h.abs() < 0.5 * radius) {
                return Err(WeatherError::Value {
                    variable: self.variables[0].clone(),
                    rule: format!("at {when}, {p_hpa} hPa: a height of {h} m is no height"),
                });
            }
            levels.push((
                self.levels_pa[l],
                Level {
                    height_msl_m: radius * h / (radius - h),
                    pressure_pa: Some(self.levels_pa[l]),
                    temperature_k: Some(t),
                    wind: Some((
                        u.hypot(v),
                        (u.atan2(v).to_degrees() + 180.0).rem_euclid(360.0),
                    )),
                },
            ));
        }
        // Lowest first: the highest pressure first, and the heights must rise with it.
        levels.sort_by(|a, b| b.0.total_cmp(&a.0));
        if levels.len() < 2 {
            return Err(WeatherError::Site {
                time: when,
                rule: "fewer than two pressure levels have every value (the others are marked \
                       missing)"
                    .into(),
            });
        }
        for w in levels.windows(2) {
            if w[1].1.height_msl_m <= w[0].1.height_msl_m {
                return Err(WeatherError::Value {
                    variable: self.variables[0].clone(),
                    rule: format!(
                        "at {when}: the {} hPa level ({:.1} m) is not above the {} hPa level \
                         ({:.1} m): heights must rise as the pressure falls",
                        w[1].0 / 100.0,
                        w[1].1.height_msl_m,
                        w[0].0 / 100.0,
                        w[0].1.height_msl_m
                    ),
                });
            }
        }
        Ok(levels.into_iter().map(|(_, l)| l).collect())
    }

    /// The air and the wind over a site `elevation_m` above sea level at `time_s` (seconds
    /// since 1970 UTC), ensemble member index `member` (see the module docs).
    pub fn over_site(
        &self,
        time_s: f64,
        member: usize,
        elevation_m: f64,
    ) -> Result<SiteAir, WeatherError> {
        let sounding = Sounding {
            levels: self.levels(time_s, member)?,
        };
        let when = format_utc(time_s);
        let mut site = sounding
            .over_site_within(elevation_m, BELOW_LOWEST_LEVEL_M)
            .map_err(|e| WeatherError::Site {
                time: when.clone(),
                rule: e.to_string().replace("sounding's", "file's"),
            })?;
        // The profile's rows above the site are the levels above it, in order: each carries
        // its level's pressure, which the air then meets.
        let above = sounding
            .levels
            .iter()
            .filter(|l| l.height_msl_m > elevation_m);
        for (row, level) in site.air.rows[1..].iter_mut().zip(above) {
            row.pressure_pa = level.pressure_pa;
        }
        continue_above_top(&mut site.air);
        AirModel::Profile(Arc::new(site.air.clone()))
            .check()
            .map_err(|e| WeatherError::Site {
                time: when,
                rule: format!(
                    "the levels do not make an atmosphere ({} and {} disagree): {}",
                    self.variables[0],
                    self.variables[1],
                    e.to_string().replace("atmosphere: ", "")
                ),
            })?;
        Ok(site)
    }

    /// The height of the file's top level with every value at `time_s`, m above sea level.
    pub fn top_m(&self, time_s: f64, member: usize) -> Result<f64, WeatherError> {
        let levels = self.levels(time_s, member)?;
        Ok(levels[levels.len() - 1].height_msl_m)
    }
}

/// The WGS 84 ellipsoid's geocentric radius at geodetic latitude `latitude_deg`, m:
/// `√(((a² cos φ)² + (b² sin φ)²) / ((a cos φ)² + (b sin φ)²))` (RocketPy's
/// `Environment.calculate_earth_radius`): 6,378,137 m at the equator, 6,356,752 m at a pole.
pub fn earth_radius_m(latitude_deg: f64) -> f64 {
    const A: f64 = 6_378_137.0;
    const F: f64 = 1.0 / 298.257_223_563;
    let b = A * (1.0 - F);
    let (s, c) = latitude_deg.to_radians().sin_cos();
    (((A * A * c).powi(2) + (b * b * s).powi(2)) / ((A * c).powi(2) + (b * s).powi(2))).sqrt()
}

/// Give a profile rows above its last one so that its temperature follows the U.S. Standard
/// Atmosphere's lapse rates, shifted by the difference between the last row's temperature
/// and the standard's at its height: rows at the standard's layer bases above it (11, 20,
/// 32, 47, 51, 71 and 84.852 km geopotential), up to [`MAX_PROFILE_HEIGHT_M`] above the site,
/// each within [`SITE_TEMPERATURE_RANGE_K`]. Between the last row and the next base the
/// temperature is linear, as the standard's is inside a layer.
pub fn continue_above_top(air: &mut AirProfile) {
    let Some(&last) = air.rows.last() else {
        return;
    };
    let standard = Atmosphere::standard(0.0).expect("the standard atmosphere is valid");
    let top_msl = air.elevation_m + last.height_m;
    let shift = last.temperature_k - standard.at_msl(top_msl).temperature_k;
    let (lo, hi) = SITE_TEMPERATURE_RANGE_K;
    for &base in &LAYER_BASE_M[1..] {
        let z = geometric_altitude_m(base);
        let height_m = z - air.elevation_m;
        if base <= geopotential_altitude_m(top_msl) || height_m <= last.height_m {
            continue;
        }
        if height_m > MAX_PROFILE_HEIGHT_M {
            break;
        }
        air.rows.push(AirRow {
            height_m,
            temperature_k: (standard.at_msl(z).temperature_k + shift).clamp(lo, hi),
            pressure_pa: None,
        });
    }
}
