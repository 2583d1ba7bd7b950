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
mod sections;
#[cfg(test)]
mod tests;

use super::params::{trigger_unit, Param};
use super::sample::Dispersion;
use hpr_design::design::dimension::Dimension;
use hpr_design::motor::MotorOptions;
use hpr_sim::atmosphere::AirModel;
use hpr_sim::flight::SetupError;
use hpr_sim::gravity::{Gravity, GravityError};
use hpr_sim::wind::Wind;
use hpr_sim::{CanopyShape, Integrator, PartChute, SensorNoise, Trigger};
use rules::{integrator, requirements};
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
    ) -> Result<Gravity, SetupError> {
        let site = |e: GravityError| SetupError::Site(e.into());
        match (self, latitude_deg) {
            (GravityModel::Standard, _) => Ok(Gravity::default()),
            (GravityModel::Constant(g), _) => Gravity::constant(g).map_err(site),
            (GravityModel::InverseSquare, _) => Gravity::inverse_square(elevation_m).map_err(site),
            (GravityModel::Somigliana, Some(lat)) => {
                Gravity::somigliana(lat, elevation_m).map_err(site)
            }
            (GravityModel::Somigliana, None) => Err(SetupError::NoLatitude {
                key: latitude_key.to_string(),
            }),
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

    /// Validate `text`, read from `path` (relative paths in it start at `path`'s directory):
    /// the file's parts in turn, each refused at its first broken rule, then the rules across
    /// them and the run's size.
    pub fn parse(text: &str, path: &Path) -> Result<Scenario, ScenarioError> {
        let file = path.display().to_string();
        let bad = |key: &str, rule: String| ScenarioError::Invalid {
            file: file.clone(),
            key: key.to_string(),
            rule,
        };
        let mut raw = sections::deserialize(&bad, text)?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let name = sections::name(&bad, raw.name.take(), path)?;
        let variants_per_point = sections::variants_per_point(&bad, raw.variants_per_point)?;
        let design_file = sections::design_file(&bad, &dir, &raw.design)?;
        let motor = sections::motor(&bad, &dir, &raw.motor)?;
        let environment =
            sections::environment(&bad, &dir, raw.environment.take().unwrap_or_default())?;
        let rail = sections::rail(&bad, raw.rail.take().unwrap_or_default())?;
        let parachutes = sections::parachutes(&bad, &design_file, &raw.parachutes)?;
        let shifts = sections::shifts(&bad, &raw.shifts)?;
        let releases = sections::releases(&bad, &raw.releases)?;
        let (integrator, max_time_s) = integrator(&bad, raw.integrator.take().unwrap_or_default())?;
        let (chunk_size, row_group_rows) =
            sections::run_options(&bad, raw.run.take().unwrap_or_default())?;
        let requirements = requirements(&bad, raw.requirements.take().unwrap_or_default())?;
        let trajectories = sections::trajectories(&bad, raw.outputs.take())?;
        let mut scenario = Scenario {
            file: path.to_path_buf(),
            dir,
            text: text.to_string(),
            hash: sections::hash(text, &environment),
            name,
            description: raw.description.take(),
            seed: raw.seed,
            variants_per_point,
            common_random_numbers: raw.common_random_numbers.unwrap_or(true),
            design_file,
            ballast: raw.design.ballast.take(),
            motor: motor.motor,
            motor_options: motor.options,
            motor_burn_time_s: motor.burn_time_s,
            motor_diameter_m: motor.diameter_m,
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
            chunk_size,
            row_group_rows,
            requirements,
            trajectories,
        };
        sections::sweep_and_dispersions(
            &mut scenario,
            &bad,
            raw.sweep.take(),
            raw.dispersions.take(),
        )?;
        sections::across_sections(&scenario, &bad)?;
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
