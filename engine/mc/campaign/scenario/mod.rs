//! Scenario files: the TOML a user writes (raw serde structs that refuse unknown keys) and
//! the validated [`Scenario`] the campaign runs.
//!
//! This module owns every rule a scenario file can break that can be checked without loading
//! the design or the motor; each error names the file, the key path (for instance
//! `dispersions.wind_speed_m_s.sigma`) and the rule. The rules that need the design or the
//! motor (the ballast component exists, a relative dispersion of a nominal that is zero...)
//! are checked by `fly::Prepared::new`, in the same words. The format is documented, with a
//! complete example, in `docs/scenarios.md`.

mod raw;
mod rules;
#[cfg(test)]
mod tests;

use super::params::{trigger_unit, Param};
use super::sample::{fingerprint, Dispersion};
use hpr_design::design::dimension::Dimension;
use hpr_design::motor::{Grains, MotorOptions};
use hpr_design::MAX_SAMPLING_RATE_HZ;
use hpr_sim::atmosphere::{AirModel, AirProfile, AirRow, AtmosphereError};
use hpr_sim::gravity::{is_latitude, Gravity, LATITUDE_RULE};
use hpr_sim::turbulence::{MAX_TURBULENCE_INTENSITY, MAX_TURBULENT_FLIGHT_S};
use hpr_sim::wind::{Wind, WindError, WindRow};
use hpr_sim::{CanopyShape, Integrator, PartChute, PartTrigger, SensorNoise, Trigger};
use raw::RawScenario;
use rules::{
    canopy_shape, check_name, check_param, design_parachute, finite, inputs, integrator, noise,
    one_line, requirements, sounding, weather, weather_inputs, ParachuteFromDesign,
};
use std::path::{Path, PathBuf};

/// Most sweep points a scenario may have: 100,000. Each point's nominal flight is set up and
/// checked before the run starts (some microseconds each: 100,000 points of the reference
/// design in 0.7 s, 2026-12-04), and the summary and statistics hold a row per point and
/// metric.
pub const MAX_SWEEP_POINTS: u64 = 100_000;

/// Most variants a scenario may have (sweep points × variants per point): 1,000,000,000,
/// some two days of flights on a 2-core machine; a run of one process holds fewer
/// ([`crate::campaign::run::MAX_VARIANTS_PER_RUN`]), a sharded one spreads them.
pub const MAX_VARIANTS: u64 = 1_000_000_000;

/// A scenario file that can't be read or breaks a rule.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    #[error("{file}: can't read it: {cause}")]
    Io {
        file: String,
        /// Not a `#[source]`: the message already says it, and error chains would say it twice.
        cause: std::io::Error,
    },
    #[error("{file}: {key}: {rule}")]
    Invalid {
        file: String,
        key: String,
        rule: String,
    },
}

impl ScenarioError {
    /// The key path the error names (empty for a file that can't be read).
    pub fn key(&self) -> &str {
        match self {
            ScenarioError::Io { .. } => "",
            ScenarioError::Invalid { key, .. } => key,
        }
    }
}

/// The launch site and the wind.
#[derive(Debug, Clone, PartialEq)]
pub struct EnvironmentSpec {
    pub elevation_m: f64,
    pub wind_speed_m_s: f64,
    pub wind_from_deg: f64,
    /// A wind that changes with height (`environment.wind_profile`, checked and built once),
    /// in place of the constant `wind_speed_m_s` from `wind_from_deg`.
    pub wind_profile: Option<Wind>,
    /// OpenRocket's turbulence intensity (the wind speed's standard deviation over its mean,
    /// 0 to 1; 0: a steady wind): each variant's gusts are drawn from its noise seed
    /// ([`hpr_sim::turbulence`]).
    pub wind_turbulence_intensity: f64,
    pub gravity: GravityModel,
    /// The site's latitude, degrees north: given, the flights feel the Earth's rotation
    /// (Coriolis), and `gravity = "somigliana"` needs it.
    pub latitude_deg: Option<f64>,
    /// The site's longitude, degrees east (WGS 84): with the latitude, the landing maps
    /// (KML, GeoJSON) place the launch frame on the Earth, and a weather file's grid is read
    /// there. The flights do not use it otherwise.
    pub longitude_deg: Option<f64>,
    /// The atmosphere: the standard one, or the site's measured air (`temperature_k`,
    /// `pressure_pa` at the nominal `elevation_m`, built once: every variant flies it).
    pub air: AirModel,
    /// The sounding the air and the wind were read from (`environment.sounding`), if any,
    /// and its text.
    pub sounding: Option<(PathBuf, String)>,
    /// The weather-model file the air and the wind were read from (`environment.weather`),
    /// if any.
    pub weather: Option<WeatherSpec>,
}

/// `environment.weather`: a weather-model file read over the site, and the launch time and
/// ensemble member whose air and wind the nominal flight flies.
#[derive(Debug, Clone)]
pub struct WeatherSpec {
    pub file: PathBuf,
    /// The file's weather over the site (every time and member).
    pub site: std::sync::Arc<hpr_sim::weather::SiteWeather>,
    /// The launch time, seconds since 1970 UTC.
    pub time_s: f64,
    /// The ensemble member, by the file's number.
    pub member: f64,
    /// The FNV-1a 64 fingerprint of the file's bytes (part of the scenario's).
    pub fingerprint: String,
}

impl PartialEq for WeatherSpec {
    fn eq(&self, other: &Self) -> bool {
        self.file == other.file
            && self.time_s == other.time_s
            && self.member == other.member
            && self.fingerprint == other.fingerprint
    }
}

/// `environment.gravity` (and `fly --gravity`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GravityModel {
    /// The constant standard gravity, 9.80665 m/s² (the default).
    Standard,
    /// Standard gravity at sea level falling off as the inverse square of the distance from
    /// the Earth's center.
    InverseSquare,
    /// The WGS 84 ellipsoid's normal gravity at the site's latitude, with height (RocketPy's
    /// default).
    Somigliana,
    /// A constant value, m/s², at every height (RocketPy's `gravity=9.81`).
    Constant(f64),
}

/// The rule `environment.gravity` and `fly --gravity` keep.
pub const GRAVITY_RULE: &str = "must be \"standard\", \"inverse_square\", \"somigliana\" or a constant value in m/s² from 0.1 to 100 (such as 9.81)";

impl GravityModel {
    /// A gravity model by its name, or a constant value in m/s².
    pub fn parse(text: &str) -> Result<GravityModel, String> {
        let t = text.trim();
        match t {
            "standard" => return Ok(GravityModel::Standard),
            "inverse_square" => return Ok(GravityModel::InverseSquare),
            "somigliana" => return Ok(GravityModel::Somigliana),
            _ => {}
        }
        match t.parse::<f64>() {
            Ok(g) => GravityModel::value(g),
            Err(_) => Err(format!("{GRAVITY_RULE} (got \"{t}\")")),
        }
    }

    /// A constant gravity of `g` m/s², from 0.1 to 100.
    pub fn value(g: f64) -> Result<GravityModel, String> {
        if g.is_finite() && (0.1..=100.0).contains(&g) {
            Ok(GravityModel::Constant(g))
        } else {
            Err(format!("{GRAVITY_RULE} (got {g})"))
        }
    }

    /// The gravity of a site `elevation_m` above sea level at `latitude_deg`, which
    /// [`GravityModel::Somigliana`] needs (`None` is an error for it; the error says which
    /// setting is at fault, `latitude_key` naming the latitude's).
    pub fn at_site(
        self,
        latitude_deg: Option<f64>,
        elevation_m: f64,
        latitude_key: &str,
    ) -> Result<Gravity, String> {
        match (self, latitude_deg) {
            (GravityModel::Standard, _) => Ok(Gravity::default()),
            (GravityModel::Constant(g), _) => Gravity::constant(g).map_err(|e| e.to_string()),
            (GravityModel::InverseSquare, _) => {
                Gravity::inverse_square(elevation_m).map_err(|e| e.to_string())
            }
            (GravityModel::Somigliana, Some(lat)) => {
                Gravity::somigliana(lat, elevation_m).map_err(|e| e.to_string())
            }
            (GravityModel::Somigliana, None) => Err(format!(
                "\"somigliana\" is the gravity at the site's latitude: give {latitude_key}"
            )),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct RailSpec {
    pub length_m: f64,
    pub inclination_deg: f64,
    pub heading_deg: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct ParachuteSpec {
    pub name: String,
    pub cds_m2: f64,
    pub lag_s: f64,
    pub trigger: Trigger,
    /// The open canopy's shape: the air it carries along.
    pub canopy: CanopyShape,
    /// The sampling rate of the flight computer that fires it, Hz (`None`: continuous).
    pub sampling_rate_hz: Option<f64>,
    /// The noise of its barometer (RocketPy's `noise`; see `hpr_sim::sensor`).
    pub noise: Option<SensorNoise>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct ShiftSpec {
    pub name: String,
    pub component: String,
    pub travel_m: f64,
    pub duration_s: f64,
    pub trigger: Trigger,
}

/// `[[releases]]`: a part that leaves the rocket, what releases it, and how it falls (its
/// own drag area, the tumbling estimate's if `None`, or its own parachute).
#[derive(Debug, Clone, PartialEq)]
pub struct ReleaseSpec {
    pub name: String,
    pub component: String,
    pub trigger: Trigger,
    pub cda_m2: Option<f64>,
    pub parachute: Option<PartChute>,
}

/// An input the scenario sweeps, disperses, or both.
#[derive(Debug, Clone, PartialEq)]
pub struct InputSpec {
    pub param: Param,
    /// Key path in the file (`parachutes.main.cds_m2`).
    pub key: String,
    /// Column name in the output (`parachute_main_cds_m2`).
    pub column: String,
    pub unit: &'static str,
    /// The sweep's values, if the input is swept.
    pub sweep: Option<Vec<f64>>,
    pub dispersion: Option<Dispersion>,
}

impl InputSpec {
    /// Where the file gives the input: `sweep.<key>` if it is swept, else
    /// `dispersions.<key>` (the key an error about it names).
    pub fn key_path(&self) -> String {
        let section = if self.sweep.is_some() {
            "sweep"
        } else {
            "dispersions"
        };
        format!("{section}.{}", self.key)
    }
}

/// A motor as a scenario names it: a file beside the scenario, `FILE#NAME` (one motor of a
/// file of several, the file beside the scenario), or a bundled motor's name.
fn resolve_motor(dir: &Path, name: &str) -> String {
    let path = dir.join(name);
    let in_file = name
        .rsplit_once('#')
        .filter(|(file, _)| dir.join(file).is_file());
    if path.is_file() {
        path.display().to_string()
    } else if let Some((file, name)) = in_file {
        format!("{}#{name}", dir.join(file).display())
    } else {
        name.to_string()
    }
}

/// A validated scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The file (for messages and metadata), its directory (relative paths start there).
    pub file: PathBuf,
    pub dir: PathBuf,
    /// The file's text and its FNV-1a 64 fingerprint (of the text and its sounding's, if
    /// it reads one).
    pub text: String,
    pub hash: String,
    pub name: String,
    pub description: Option<String>,
    pub seed: u64,
    pub variants_per_point: u64,
    /// Replicate r of every sweep point sees the same draws (common random numbers).
    pub common_random_numbers: bool,
    pub design_file: PathBuf,
    /// Id of the design's ballast component.
    pub ballast: Option<String>,
    /// A motor file (resolved against the scenario's directory) or a bundled motor's name.
    pub motor: String,
    /// The motors a sweep flies (`[sweep] motor`, by name or file, as `motor.name`), one per
    /// point along the motor's axis; empty without a sweep of motors.
    pub motors: Vec<String>,
    /// The design's dimensions the scenario sweeps or disperses (`design.<id>.<field>`), in
    /// order of component id and field: [`Param::Design`] numbers them.
    pub dimensions: Vec<Dimension>,
    /// The motor's own masses, their centers, the casing's inertia, the grains and the nozzle
    /// in place of the defaults (`motor.propellant_mass_kg`, `dry_mass_kg`,
    /// `dry_center_from_nozzle_m`, `propellant_center_from_nozzle_m`, `dry_inertia_kg_m2`,
    /// `grains`, `chamber`, `nozzle_radius_m`; a cluster's are each motor's);
    /// its scales are 1 (the dispersions set them flight by flight).
    pub motor_options: MotorOptions,
    /// The thrust curve cut at this time, s (`motor.burn_time_s`, RocketPy's `burn_time`).
    pub motor_burn_time_s: Option<f64>,
    /// The casing's outer diameter in place of the file's, m (`motor.diameter_m`).
    pub motor_diameter_m: Option<f64>,
    pub environment: EnvironmentSpec,
    pub rail: RailSpec,
    pub parachutes: Vec<ParachuteSpec>,
    pub shifts: Vec<ShiftSpec>,
    pub releases: Vec<ReleaseSpec>,
    pub integrator: Integrator,
    pub max_time_s: f64,
    /// Swept or dispersed inputs, in canonical order ([`Param`]'s: the globals, then every
    /// parachute's CdS, every parachute's lag, every parachute's trigger number, then every
    /// shift's travel, duration and trigger number, then every release's trigger number,
    /// drag area, parachute CdS and lag, parachutes, shifts and releases in file order).
    pub inputs: Vec<InputSpec>,
    /// Variants per chunk (the unit of work, of resumption and of the part files).
    pub chunk_size: usize,
    /// Rows per row group of the output files.
    pub row_group_rows: usize,
    /// What a flight must meet (`[requirements]`), by metric name in name order; each sweep
    /// point's share of the variants that meet each is reported.
    pub requirements: Vec<RequirementSpec>,
    /// Variants per sweep point (its first replicates) whose time series are written to
    /// `trajectories.parquet` (`[outputs] trajectories`).
    pub trajectories: u64,
}

/// Variants per sweep point whose time series a run writes unless `[outputs] trajectories`
/// says otherwise.
pub const DEFAULT_TRAJECTORIES: u64 = 10;
/// The most `[outputs] trajectories` may ask for.
pub const MAX_TRAJECTORIES: u64 = 10_000;

/// Bounds a metric must keep: `min ≤ value ≤ max` (either may be absent, not both). A
/// variant whose metric has no value (a flight that failed, or never reached what the metric
/// measures) does not meet it.
#[derive(Debug, Clone, PartialEq)]
pub struct RequirementSpec {
    pub metric: String,
    pub min: Option<f64>,
    pub max: Option<f64>,
}

impl RequirementSpec {
    /// Whether `value` (NaN: none) meets the bounds.
    pub fn met_by(&self, value: f64) -> bool {
        !value.is_nan()
            && self.min.is_none_or(|m| value >= m)
            && self.max.is_none_or(|m| value <= m)
    }

    /// The bounds as a reader writes them: `≥ 1.5`, `≤ 3048`, `in [2900, 3200]`.
    pub fn bounds_text(&self, unit: &str) -> String {
        let u = if unit == "1" {
            String::new()
        } else {
            format!(" {unit}")
        };
        match (self.min, self.max) {
            (Some(a), Some(b)) => format!("in [{a}, {b}]{u}"),
            (Some(a), None) => format!("≥ {a}{u}"),
            (None, Some(b)) => format!("≤ {b}{u}"),
            (None, None) => "anything".to_string(),
        }
    }
}

/// The field of a trigger's number (`time_s`, `height_m`, `delay_s`), if it has one.
pub fn trigger_field(t: &Trigger) -> Option<&'static str> {
    match t {
        Trigger::Time { .. } => Some("time_s"),
        Trigger::HeightDescending { .. } => Some("height_m"),
        Trigger::BurnoutPlusDelay { .. } => Some("delay_s"),
        Trigger::Apogee | Trigger::Burnout => None,
    }
}

/// The number of a trigger (`None` for apogee, burnout, and the motor's own delay).
pub fn trigger_value(t: &Trigger) -> Option<f64> {
    match *t {
        Trigger::Time { time_s } => Some(time_s),
        Trigger::HeightDescending { height_m } => Some(height_m),
        Trigger::BurnoutPlusDelay { delay_s } => delay_s,
        Trigger::Apogee | Trigger::Burnout => None,
    }
}

/// The trigger with its number replaced by `v`.
pub fn with_trigger_value(t: &Trigger, v: f64) -> Trigger {
    match t {
        Trigger::Time { .. } => Trigger::Time { time_s: v },
        Trigger::HeightDescending { .. } => Trigger::HeightDescending { height_m: v },
        Trigger::BurnoutPlusDelay { .. } => Trigger::BurnoutPlusDelay { delay_s: Some(v) },
        other => *other,
    }
}

impl Scenario {
    /// Whether a flight draws noise from its seed (a parachute's noisy barometer, the wind's
    /// turbulence): then each variant's seed is drawn, and written, so that it can be flown
    /// again alone.
    pub fn has_noise(&self) -> bool {
        self.parachutes.iter().any(|p| p.noise.is_some()) || self.turbulent()
    }

    /// Whether any flight's wind has turbulence (the scenario's, or a swept or dispersed
    /// intensity).
    pub fn turbulent(&self) -> bool {
        self.environment.wind_turbulence_intensity > 0.0
            || self
                .inputs
                .iter()
                .any(|i| i.param == Param::WindTurbulenceIntensity)
    }

    /// Read and validate the scenario file at `path`.
    pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
        let text = hpr_design::limits::read_text_limited(
            path,
            hpr_design::limits::MAX_SCENARIO_FILE_BYTES,
            "a scenario file",
        )
        .map_err(|cause| ScenarioError::Io {
            file: path.display().to_string(),
            cause,
        })?;
        Scenario::parse(&text, path)
    }

    /// Validate `text`, read from `path` (relative paths in it start at `path`'s directory).
    pub fn parse(text: &str, path: &Path) -> Result<Scenario, ScenarioError> {
        let file = path.display().to_string();
        let bad = |key: &str, rule: String| ScenarioError::Invalid {
            file: file.clone(),
            key: key.to_string(),
            rule,
        };
        let de = toml::Deserializer::parse(text).map_err(|e| {
            let hint = if text.trim_start().starts_with('{') {
                " (this looks like a JSON design: a scenario is a TOML file that names its design \
                 under [design] file = \"...\"; see docs/scenarios.md)"
            } else {
                ""
            };
            bad("(syntax)", format!("{}{hint}", one_line(&e.to_string())))
        })?;
        let mut raw: RawScenario = serde_path_to_error::deserialize(de).map_err(|e| {
            let key = e.path().to_string();
            let key = if key == "." {
                "(top level)".to_string()
            } else {
                key
            };
            bad(
                &key,
                hpr_design::design::json_errors::plain_types(&one_line(
                    &e.into_inner().to_string(),
                )),
            )
        })?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();

        let name = match raw.name.take() {
            Some(n) => n,
            // The file's stem, with what a directory name should not hold made '_'.
            None => path
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("scenario")
                .chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                        c
                    } else {
                        '_'
                    }
                })
                .collect(),
        };
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        {
            return Err(bad("name", format!("must be letters, digits, '_' or '-' (it names the output directory; got \"{name}\")")));
        }
        if raw.variants_per_point == 0 {
            return Err(bad("variants_per_point", "must be at least 1".into()));
        }

        let design_file = dir.join(&raw.design.file);
        if design_file.is_dir() {
            return Err(bad(
                "design.file",
                format!(
                    "{} is a directory, not a design file",
                    design_file.display()
                ),
            ));
        }
        if !design_file.exists() {
            return Err(bad(
                "design.file",
                format!("no such file: {}", design_file.display()),
            ));
        }
        if let Some(b) = &raw.design.ballast {
            if b.is_empty() {
                return Err(bad(
                    "design.ballast",
                    "must be the id of a component of the design".into(),
                ));
            }
        }
        let motor = if raw.motor.name.trim().is_empty() {
            return Err(bad(
                "motor.name",
                "must name a motor: a bundled motor (Cesaroni_I175, I175...) or an .eng/.rse file"
                    .into(),
            ));
        } else {
            resolve_motor(&dir, &raw.motor.name)
        };
        let inertia = raw.motor.dry_inertia_kg_m2.unwrap_or_default();
        for (key, v) in [
            ("motor.propellant_mass_kg", raw.motor.propellant_mass_kg),
            ("motor.dry_mass_kg", raw.motor.dry_mass_kg),
            (
                "motor.dry_center_from_nozzle_m",
                raw.motor.dry_center_from_nozzle_m,
            ),
            (
                "motor.propellant_center_from_nozzle_m",
                raw.motor.propellant_center_from_nozzle_m,
            ),
            ("motor.dry_inertia_kg_m2", Some(inertia[0])),
            ("motor.dry_inertia_kg_m2", Some(inertia[1])),
            ("motor.burn_time_s", raw.motor.burn_time_s),
            ("motor.diameter_m", raw.motor.diameter_m),
        ] {
            if let Some(v) = v {
                if !(v.is_finite() && v >= 0.0) {
                    return Err(bad(
                        key,
                        format!("must be finite and not negative (got {v})"),
                    ));
                }
            }
        }

        let mut env = raw.environment.take().unwrap_or_default();
        // A sounding gives the air and the wind: read here, it becomes the air profile and
        // the wind profile below, as if the scenario had written their rows.
        let sounding = sounding(&bad, &dir, &mut env)?;
        let weather = weather(&bad, &dir, &mut env)?;
        let wind_profile = match &env.wind_profile {
            None => None,
            Some(_) if env.wind_speed_m_s.is_some() || env.wind_from_deg.is_some() => {
                return Err(bad(
                    "environment.wind_profile",
                    "give either a wind profile or a constant wind_speed_m_s and wind_from_deg, not both".into(),
                ))
            }
            Some(rows) => {
                let rows: Vec<WindRow> = rows
                    .iter()
                    .map(|r| WindRow {
                        height_agl_m: r.height_m,
                        speed_m_s: r.speed_m_s,
                        from_deg: r.from_deg,
                    })
                    .collect();
                let table = Wind::table(&rows).map_err(|e| {
                    let key = match &e {
                        WindError::EmptyTable => "environment.wind_profile".to_string(),
                        WindError::Speed { row, .. } => {
                            format!("environment.wind_profile[{}].speed_m_s", row.unwrap_or(0))
                        }
                        WindError::Direction { row, .. } => {
                            format!("environment.wind_profile[{}].from_deg", row.unwrap_or(0))
                        }
                        WindError::Height { row, .. } => {
                            format!("environment.wind_profile[{row}].height_m")
                        }
                        WindError::Scale { .. } => "environment.wind_profile".to_string(),
                        WindError::Turbulence { .. } => {
                            "environment.wind_turbulence_intensity".to_string()
                        }
                    };
                    // The message in the scenario's words: height_m for the table's height.
                    bad(&key, e.to_string().replace("height_agl_m", "height_m"))
                })?;
                Some(table)
            }
        };
        let mut environment = EnvironmentSpec {
            elevation_m: finite(
                &bad,
                "environment.elevation_m",
                env.elevation_m.unwrap_or(0.0),
            )?,
            wind_speed_m_s: check_param(
                &bad,
                "environment.wind_speed_m_s",
                Param::WindSpeedMS,
                env.wind_speed_m_s.unwrap_or(0.0),
            )?,
            wind_from_deg: finite(
                &bad,
                "environment.wind_from_deg",
                env.wind_from_deg.unwrap_or(0.0),
            )?,
            wind_profile,
            wind_turbulence_intensity: match env.wind_turbulence_intensity {
                None => 0.0,
                Some(i) if (0.0..=MAX_TURBULENCE_INTENSITY).contains(&i) => i,
                Some(i) => {
                    return Err(bad(
                        "environment.wind_turbulence_intensity",
                        format!(
                            "must be between 0 and {MAX_TURBULENCE_INTENSITY}, the wind speed's standard deviation over its mean (OpenRocket's 10 % is 0.1; got {i})"
                        ),
                    ))
                }
            },
            gravity: match &env.gravity {
                None => GravityModel::Standard,
                Some(raw::RawGravity::Name(name)) => {
                    GravityModel::parse(name).map_err(|r| bad("environment.gravity", r))?
                }
                Some(raw::RawGravity::Value(g)) => {
                    GravityModel::value(*g).map_err(|r| bad("environment.gravity", r))?
                }
            },
            latitude_deg: match env.latitude_deg {
                Some(l) if !is_latitude(l) => {
                    return Err(bad(
                        "environment.latitude_deg",
                        format!("{LATITUDE_RULE} degrees north (got {l})"),
                    ))
                }
                l => l,
            },
            longitude_deg: match env.longitude_deg {
                Some(l) if !(l.is_finite() && l.abs() <= 180.0) => {
                    return Err(bad(
                        "environment.longitude_deg",
                        format!("must be finite and within [-180, 180] degrees east (got {l})"),
                    ))
                }
                Some(_) if env.latitude_deg.is_none() => {
                    return Err(bad(
                        "environment.longitude_deg",
                        "places the site on the Earth with environment.latitude_deg: give both"
                            .into(),
                    ))
                }
                l => l,
            },
            air: AirModel::Standard,
            sounding,
            weather,
        };
        let air_error = |e: AtmosphereError| {
            let key = match &e {
                AtmosphereError::SiteTemperature { .. } => "environment.temperature_k".into(),
                AtmosphereError::SitePressure { .. } => "environment.pressure_pa".into(),
                AtmosphereError::ProfileRows { .. } => "environment.air_profile".into(),
                AtmosphereError::ProfileHeight { row, .. } => {
                    format!("environment.air_profile[{row}].height_m")
                }
                AtmosphereError::ProfileTemperature { row, .. } => {
                    format!("environment.air_profile[{row}].temperature_k")
                }
                _ => "environment.elevation_m".into(),
            };
            bad(&key, e.to_string().replace("atmosphere: ", ""))
        };
        environment.air = match &env.air_profile {
            None => AirModel::site(environment.elevation_m, env.temperature_k, env.pressure_pa)
                .map_err(air_error)?,
            Some(_) if env.temperature_k.is_some() => {
                return Err(bad(
                    "environment.temperature_k",
                    "the site's temperature is environment.air_profile's first row: give one or the other".into(),
                ))
            }
            Some(rows) => {
                // The site's pressure: as given, or the standard's at the site.
                let (_, _, standard_pa) = AirModel::Standard.site_values(environment.elevation_m);
                let profile = AirProfile {
                    elevation_m: environment.elevation_m,
                    pressure_pa: env.pressure_pa.unwrap_or(standard_pa),
                    rows: rows
                        .iter()
                        .map(|r| AirRow {
                            height_m: r.height_m,
                            temperature_k: r.temperature_k,
                            pressure_pa: r.pressure_pa,
                        })
                        .collect(),
                };
                let air = AirModel::Profile(std::sync::Arc::new(profile));
                air.check().map_err(air_error)?;
                air
            }
        };
        // The site's gravity can be had (Somigliana's needs the latitude).
        environment
            .gravity
            .at_site(
                environment.latitude_deg,
                environment.elevation_m,
                "environment.latitude_deg",
            )
            .map_err(|rule| bad("environment.gravity", rule))?;
        let r = raw.rail.take().unwrap_or_default();
        let rail = RailSpec {
            length_m: check_param(
                &bad,
                "rail.length_m",
                Param::RailLengthM,
                r.length_m.unwrap_or(2.0),
            )?,
            inclination_deg: check_param(
                &bad,
                "rail.inclination_deg",
                Param::RailInclinationDeg,
                r.inclination_deg.unwrap_or(90.0),
            )?,
            heading_deg: finite(&bad, "rail.heading_deg", r.heading_deg.unwrap_or(0.0))?,
        };

        let mut parachutes = Vec::new();
        // The design, read only when a parachute takes its canopy from a component of it.
        let mut design: Option<hpr_design::Design> = None;
        for (i, p) in raw.parachutes.iter().enumerate() {
            let key = |f: &str| format!("parachutes[{i}].{f}");
            let from = match &p.component {
                Some(id) => {
                    let d = match design.take() {
                        Some(d) => d,
                        None => hpr_design::Design::load(&design_file)
                            .map_err(|e| bad("design.file", format!("{e}")))?,
                    };
                    let from = design_parachute(&bad, &key("component"), &d, id)?;
                    design = Some(d);
                    Some(from)
                }
                None => None,
            };
            let name = match (&p.name, &p.component) {
                (Some(n), _) => n.clone(),
                (None, Some(id)) => id.clone(),
                (None, None) => {
                    return Err(bad(&key("name"), "is missing (or give a component)".into()))
                }
            };
            check_name(&bad, &key("name"), &name)?;
            if parachutes.iter().any(|q: &ParachuteSpec| q.name == name) {
                return Err(bad(
                    &key("name"),
                    format!("two parachutes are named \"{name}\"; give each its own name"),
                ));
            }
            let cds_m2 = match (p.cds_m2, &from) {
                (Some(c), _) => c,
                (None, Some(d)) => d.cds_m2,
                (None, None) => {
                    return Err(bad(
                        &key("cds_m2"),
                        "is missing (or give a component)".into(),
                    ))
                }
            };
            let (trigger, lag_s) = match (&p.trigger, &from) {
                (Some(t), _) => (t.0, p.lag_s.unwrap_or(0.0)),
                (
                    None,
                    Some(ParachuteFromDesign {
                        deploy: Some((t, lag)),
                        ..
                    }),
                ) => (*t, p.lag_s.unwrap_or(*lag)),
                (None, Some(_)) => {
                    return Err(bad(
                        &key("trigger"),
                        "is missing, and the component says no \"deploy\"".into(),
                    ))
                }
                (None, None) => return Err(bad(&key("trigger"), "is missing".into())),
            };
            parachutes.push(ParachuteSpec {
                name,
                cds_m2: check_param(&bad, &key("cds_m2"), Param::ParachuteCdsM2(i), cds_m2)?,
                lag_s: check_param(&bad, &key("lag_s"), Param::ParachuteLagS(i), lag_s)?,
                trigger,
                canopy: canopy_shape(&bad, &key, p)?,
                sampling_rate_hz: match p.sampling_rate_hz {
                    Some(r) if !(r.is_finite() && r > 0.0 && r <= MAX_SAMPLING_RATE_HZ) => {
                        return Err(bad(
                            &key("sampling_rate_hz"),
                            format!(
                                "must be positive, at most {MAX_SAMPLING_RATE_HZ} Hz (got {r})"
                            ),
                        ))
                    }
                    r => r,
                },
                noise: noise(&bad, &key, p)?,
            });
        }
        let mut shifts = Vec::new();
        for (i, s) in raw.shifts.iter().enumerate() {
            let key = |f: &str| format!("shifts[{i}].{f}");
            let name = s.name.clone().unwrap_or_else(|| s.component.clone());
            check_name(&bad, &key("name"), &name)?;
            if shifts.iter().any(|q: &ShiftSpec| q.name == name) {
                return Err(bad(&key("name"), format!("two shifts are named \"{name}\" (a shift is named after its component unless it has a name); give each its own name")));
            }
            shifts.push(ShiftSpec {
                name,
                component: s.component.clone(),
                travel_m: check_param(&bad, &key("travel_m"), Param::ShiftTravelM(i), s.travel_m)?,
                duration_s: check_param(
                    &bad,
                    &key("duration_s"),
                    Param::ShiftDurationS(i),
                    s.duration_s,
                )?,
                trigger: s.trigger.0,
            });
        }
        let mut releases = Vec::new();
        for (i, r) in raw.releases.iter().enumerate() {
            let key = |f: &str| format!("releases[{i}].{f}");
            let name = r.name.clone().unwrap_or_else(|| r.component.clone());
            check_name(&bad, &key("name"), &name)?;
            if releases.iter().any(|q: &ReleaseSpec| q.name == name) {
                return Err(bad(&key("name"), format!("two releases are named \"{name}\" (a release is named after its component unless it has a name); give each its own name")));
            }
            let cda_m2 = match r.cda_m2 {
                Some(v) => Some(check_param(
                    &bad,
                    &key("cda_m2"),
                    Param::ReleaseCdaM2(i),
                    v,
                )?),
                None => None,
            };
            let parachute = match &r.parachute {
                None => None,
                Some(c) => {
                    let k = |f: &str| key(&format!("parachute.{f}"));
                    let trigger = c.trigger.as_ref().map_or(PartTrigger::Release, |t| t.0);
                    if let PartTrigger::HeightDescending { height_m } = trigger {
                        if !(height_m.is_finite() && height_m > 0.0) {
                            return Err(bad(&k("trigger.height_m"), format!("must be above the ground and finite, or the canopy never opens (got {height_m})")));
                        }
                    }
                    let shape = CanopyShape {
                        radius_m: c.radius_m,
                        height_m: c.height_m,
                        porosity: c.porosity.unwrap_or(CanopyShape::default().porosity),
                    };
                    shape
                        .check()
                        .map_err(|(field, rule)| bad(&k(field), rule.to_string()))?;
                    Some(PartChute {
                        cds_m2: check_param(
                            &bad,
                            &k("cds_m2"),
                            Param::ReleaseChuteCdsM2(i),
                            c.cds_m2,
                        )?,
                        trigger,
                        lag_s: check_param(
                            &bad,
                            &k("lag_s"),
                            Param::ReleaseChuteLagS(i),
                            c.lag_s.unwrap_or(0.0),
                        )?,
                        canopy: shape,
                    })
                }
            };
            releases.push(ReleaseSpec {
                name,
                component: r.component.clone(),
                trigger: r.trigger.0,
                cda_m2,
                parachute,
            });
        }

        let (integrator, max_time_s) = integrator(&bad, raw.integrator.take().unwrap_or_default())?;
        let run = raw.run.take().unwrap_or_default();
        let chunk_size = run.chunk_size.unwrap_or(32);
        if !(1..=1_000_000).contains(&chunk_size) {
            return Err(bad(
                "run.chunk_size",
                format!("must be from 1 to 1000000 variants (got {chunk_size})"),
            ));
        }
        let row_group_rows = run.row_group_rows.unwrap_or(8192);
        if !(1..=10_000_000).contains(&row_group_rows) {
            return Err(bad(
                "run.row_group_rows",
                format!("must be from 1 to 10000000 rows (got {row_group_rows})"),
            ));
        }

        let requirements = requirements(&bad, raw.requirements.take().unwrap_or_default())?;
        let trajectories = match raw.outputs.take().and_then(|o| o.trajectories) {
            None => DEFAULT_TRAJECTORIES,
            Some(n) if n <= MAX_TRAJECTORIES => n,
            Some(n) => {
                return Err(bad(
                    "outputs.trajectories",
                    format!(
                        "must be from 0 to {MAX_TRAJECTORIES} variants per sweep point (got {n})"
                    ),
                ))
            }
        };

        let mut scenario = Scenario {
            file: path.to_path_buf(),
            dir,
            text: text.to_string(),
            // A sounding or a weather file is part of the scenario: a run resumed with
            // another is refused.
            hash: match (&environment.sounding, &environment.weather) {
                (Some((_, sounding)), _) => fingerprint(format!("{text}\n{sounding}").as_bytes()),
                (None, Some(w)) => fingerprint(format!("{text}\n{}", w.fingerprint).as_bytes()),
                (None, None) => fingerprint(text.as_bytes()),
            },
            name,
            description: raw.description.take(),
            seed: raw.seed,
            variants_per_point: raw.variants_per_point,
            common_random_numbers: raw.common_random_numbers.unwrap_or(true),
            design_file,
            ballast: raw.design.ballast.take(),
            motor,
            motor_options: MotorOptions {
                propellant_mass_kg: raw.motor.propellant_mass_kg,
                dry_mass_kg: raw.motor.dry_mass_kg,
                dry_center_from_nozzle_m: raw.motor.dry_center_from_nozzle_m,
                propellant_center_from_nozzle_m: raw.motor.propellant_center_from_nozzle_m,
                dry_inertia_kg_m2: raw.motor.dry_inertia_kg_m2,
                grains: raw.motor.grains.map(|g| Grains {
                    count: g.count,
                    outer_radius_m: g.outer_radius_m,
                    inner_radius_m: g.inner_radius_m,
                    height_m: g.height_m,
                    separation_m: g.separation_m,
                    density_kg_m3: g.density_kg_m3,
                }),
                chamber_m: raw.motor.chamber.map(|c| [c.radius_m, c.height_m]),
                nozzle_radius_m: raw.motor.nozzle_radius_m,
                ..MotorOptions::default()
            },
            motor_burn_time_s: raw.motor.burn_time_s,
            motor_diameter_m: raw.motor.diameter_m,
            environment,
            rail,
            parachutes,
            shifts,
            releases,
            integrator,
            max_time_s,
            inputs: vec![],
            motors: vec![],
            dimensions: vec![],
            chunk_size: chunk_size as usize,
            row_group_rows: row_group_rows as usize,
            requirements,
            trajectories,
        };
        let (mut sweep, dispersions) = (raw.sweep.take(), raw.dispersions.take());
        if dispersions.as_ref().is_some_and(|d| d.motor.is_some()) {
            return Err(bad(
                "dispersions.motor",
                "a motor is not a number to disperse: sweep it over a list of motors ([sweep] motor = [\"Cesaroni_I175\", ...])".into(),
            ));
        }
        if let Some(motors) = sweep.as_mut().and_then(|s| s.motor.take()) {
            if motors.is_empty() {
                return Err(bad(
                    "sweep.motor",
                    "empty sweep: give at least one motor".into(),
                ));
            }
            for (j, m) in motors.iter().enumerate() {
                if motors[..j].contains(m) {
                    return Err(bad(
                        &format!("sweep.motor[{j}]"),
                        format!("the motor \"{m}\" appears twice in the sweep"),
                    ));
                }
            }
            // A motor file is found beside the scenario, as motor.name's.
            scenario.motors = motors
                .iter()
                .map(|m| resolve_motor(&scenario.dir, m))
                .collect();
        }
        // The design's dimensions, numbered before the inputs are collected.
        let mut dimensions: Vec<Dimension> = Vec::new();
        if let Some(s) = &sweep {
            dimensions.extend(rules::dimensions(&s.design));
        }
        if let Some(d) = &dispersions {
            dimensions.extend(rules::dimensions(&d.design));
        }
        dimensions.sort();
        dimensions.dedup();
        scenario.dimensions = dimensions;
        scenario.inputs = inputs(&scenario, &bad, sweep, dispersions)?;
        if scenario.turbulent() && scenario.max_time_s > MAX_TURBULENT_FLIGHT_S {
            return Err(bad(
                "integrator.max_time_s",
                format!("must be at most {MAX_TURBULENT_FLIGHT_S} s in a turbulent wind (environment.wind_turbulence_intensity), whose gusts each flight draws to its time limit (got {})", scenario.max_time_s),
            ));
        }
        weather_inputs(&scenario, &bad)?;
        if scenario.environment.wind_profile.is_some() {
            if let Some(i) = scenario
                .inputs
                .iter()
                .find(|i| matches!(i.param, Param::WindSpeedMS | Param::WindFromDeg))
            {
                return Err(bad(
                    &i.key_path(),
                    "the wind is environment.wind_profile, whose rows give its speeds and directions: vary it with wind_scale (a factor on every speed) and wind_rotation_deg (a clockwise turn of every direction)".into(),
                ));
            }
        }
        scenario.check_size("variants_per_point")?;
        Ok(scenario)
    }

    /// The scenario with the command line's seed and variants per point.
    pub fn with_overrides(
        mut self,
        seed: Option<u64>,
        variants_per_point: Option<u64>,
    ) -> Result<Scenario, ScenarioError> {
        if let Some(s) = seed {
            self.seed = s;
        }
        if let Some(n) = variants_per_point {
            if n == 0 {
                return Err(ScenarioError::Invalid {
                    file: self.file.display().to_string(),
                    key: "--variants".into(),
                    rule: "must be at least 1".into(),
                });
            }
            self.variants_per_point = n;
        }
        self.check_size("--variants")?;
        Ok(self)
    }

    /// The sweep's points and the variants within their limits ([`MAX_SWEEP_POINTS`],
    /// [`MAX_VARIANTS`]), judged before anything is built; `variants_key` names where the
    /// variants per point were given (the file's key or `--variants`).
    fn check_size(&self, variants_key: &str) -> Result<(), ScenarioError> {
        let bad = |key: &str, rule: String| ScenarioError::Invalid {
            file: self.file.display().to_string(),
            key: key.to_string(),
            rule,
        };
        let lengths: Vec<(&str, u64)> = self
            .swept()
            .map(|i| {
                (
                    i.key.as_str(),
                    i.sweep.as_ref().map_or(1, |s| s.len() as u64),
                )
            })
            .collect();
        let points = lengths
            .iter()
            .try_fold(1u64, |n, (_, len)| n.checked_mul(*len))
            .filter(|&n| n <= MAX_SWEEP_POINTS);
        let Some(points) = points else {
            let grid: Vec<String> = lengths.iter().map(|(k, n)| format!("{n} of {k}")).collect();
            return Err(bad(
                "sweep",
                format!(
                    "the grid of {} values has more than {MAX_SWEEP_POINTS} points, the most a \
                     scenario may sweep (every point's flight is set up and checked before the \
                     run); sweep fewer values, or split the sweep over several scenarios",
                    grid.join(" × ")
                ),
            ));
        };
        match points.checked_mul(self.variants_per_point) {
            Some(n) if n <= MAX_VARIANTS => Ok(()),
            _ => Err(bad(
                variants_key,
                format!(
                    "{points} sweep points × {} variants per point is more than {MAX_VARIANTS} \
                     variants, the most one scenario may fly (a larger study is several runs \
                     with other seeds)",
                    self.variants_per_point
                ),
            )),
        }
    }

    /// Number of sweep points (1 without a sweep).
    pub fn points(&self) -> usize {
        super::variants::sweep_points(self.inputs.iter().map(|i| i.sweep.as_ref()))
    }

    /// Sweep points × variants per point, if it fits in 64 bits.
    pub fn total_variants(&self) -> Option<u64> {
        (self.points() as u64).checked_mul(self.variants_per_point)
    }

    /// The swept inputs, in canonical order (the sweep's axes, the last one varying fastest).
    pub fn swept(&self) -> impl Iterator<Item = &InputSpec> {
        self.inputs.iter().filter(|i| i.sweep.is_some())
    }

    /// The key path of an input (`wind_speed_m_s`, `parachutes.main.cds_m2`).
    pub fn key(&self, p: Param) -> String {
        if let Some(k) = p.global_key() {
            return k.to_string();
        }
        match p {
            Param::Design(k) => format!(
                "design.{}.{}",
                self.dimensions[k].component, self.dimensions[k].field
            ),
            Param::ParachuteCdsM2(i) => format!("parachutes.{}.cds_m2", self.parachutes[i].name),
            Param::ParachuteLagS(i) => format!("parachutes.{}.lag_s", self.parachutes[i].name),
            Param::ParachuteTrigger(i) => format!(
                "parachutes.{}.{}",
                self.parachutes[i].name,
                trigger_field(&self.parachutes[i].trigger).unwrap_or("trigger")
            ),
            Param::ShiftTravelM(i) => format!("shifts.{}.travel_m", self.shifts[i].name),
            Param::ShiftDurationS(i) => format!("shifts.{}.duration_s", self.shifts[i].name),
            Param::ShiftTrigger(i) => format!(
                "shifts.{}.{}",
                self.shifts[i].name,
                trigger_field(&self.shifts[i].trigger).unwrap_or("trigger")
            ),
            Param::ReleaseTrigger(i) => format!(
                "releases.{}.{}",
                self.releases[i].name,
                trigger_field(&self.releases[i].trigger).unwrap_or("trigger")
            ),
            Param::ReleaseCdaM2(i) => format!("releases.{}.cda_m2", self.releases[i].name),
            Param::ReleaseChuteCdsM2(i) => {
                format!("releases.{}.parachute_cds_m2", self.releases[i].name)
            }
            Param::ReleaseChuteLagS(i) => {
                format!("releases.{}.parachute_lag_s", self.releases[i].name)
            }
            _ => unreachable!("global inputs have a global key"),
        }
    }

    /// The output column of an input (`wind_speed_m_s`, `parachute_main_cds_m2`).
    pub fn column(&self, p: Param) -> String {
        let key = self.key(p);
        if let Some(rest) = key.strip_prefix("parachutes.") {
            format!("parachute_{}", rest.replace('.', "_"))
        } else if let Some(rest) = key.strip_prefix("shifts.") {
            format!("shift_{}", rest.replace('.', "_"))
        } else if let Some(rest) = key.strip_prefix("releases.") {
            format!("release_{}", rest.replace('.', "_"))
        } else if key.starts_with("design.") {
            key.replace('.', "_")
        } else if p == Param::Motor {
            // The motor's number in the sweep's list (its designation is the `motor` column).
            "motor_index".into()
        } else {
            key
        }
    }

    /// The unit of an input.
    pub fn unit(&self, p: Param) -> &'static str {
        match p {
            Param::ParachuteTrigger(i) => {
                trigger_unit(trigger_field(&self.parachutes[i].trigger).unwrap_or(""))
            }
            Param::ShiftTrigger(i) => {
                trigger_unit(trigger_field(&self.shifts[i].trigger).unwrap_or(""))
            }
            Param::ReleaseTrigger(i) => {
                trigger_unit(trigger_field(&self.releases[i].trigger).unwrap_or(""))
            }
            Param::Design(k) => self.dimensions[k].unit(),
            _ => p.unit(),
        }
    }
}
