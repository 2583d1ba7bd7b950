//! Scenario files: the TOML a user writes (raw serde structs that refuse unknown keys) and
//! the validated [`Scenario`] the campaign runs.
//!
//! This module owns every rule a scenario file can break that can be checked without loading
//! the design or the motor; each error names the file, the key path (for instance
//! `dispersions.wind_speed_m_s.sigma`) and the rule. The rules that need the design or the
//! motor (the ballast component exists, a relative dispersion of a nominal that is zero...)
//! are checked by `fly::Prepared::new`, in the same words. The format is documented, with a
//! complete example, in `docs/scenarios.md`.

use super::params::{trigger_unit, Param, GLOBAL};
use super::sample::{fingerprint, Dispersion, Shape};
use hpr_sim::{Integrator, Trigger};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A scenario file that can't be read or breaks a rule.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    #[error("{file}: can't read it: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
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

// ------------------------------------------------------------------------------ raw TOML

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    name: Option<String>,
    description: Option<String>,
    seed: u64,
    variants_per_point: u64,
    common_random_numbers: Option<bool>,
    design: RawDesign,
    motor: RawMotor,
    environment: Option<RawEnvironment>,
    rail: Option<RawRail>,
    #[serde(default)]
    parachutes: Vec<RawParachute>,
    #[serde(default)]
    shifts: Vec<RawShift>,
    integrator: Option<RawIntegrator>,
    sweep: Option<RawParams<Vec<f64>>>,
    dispersions: Option<RawParams<RawDist>>,
    run: Option<RawRun>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDesign {
    file: PathBuf,
    ballast: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMotor {
    name: String,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawEnvironment {
    elevation_m: Option<f64>,
    wind_speed_m_s: Option<f64>,
    wind_from_deg: Option<f64>,
    gravity: Option<String>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawRail {
    length_m: Option<f64>,
    inclination_deg: Option<f64>,
    heading_deg: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawParachute {
    name: String,
    cds_m2: f64,
    #[serde(default)]
    lag_s: f64,
    trigger: RawTrigger,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawShift {
    name: Option<String>,
    component: String,
    travel_m: f64,
    duration_s: f64,
    trigger: RawTrigger,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawIntegrator {
    method: Option<String>,
    rtol: Option<f64>,
    atol_position_m: Option<f64>,
    atol_velocity_m_s: Option<f64>,
    atol_quaternion: Option<f64>,
    atol_rate_rad_s: Option<f64>,
    step_s: Option<f64>,
    max_time_s: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawRun {
    chunk_size: Option<u64>,
    row_group_rows: Option<u64>,
}

/// A trigger as the file writes it: `"apogee"`, `"burnout"`, `"motor_delay"`, or a table with
/// one number: `{ time_s = 5.0 }`, `{ height_m = 300.0 }` (on the way down), `{ delay_s = 2.0 }`
/// (after burnout).
#[derive(Deserialize)]
#[serde(try_from = "toml::Value")]
struct RawTrigger(Trigger);

impl TryFrom<toml::Value> for RawTrigger {
    type Error = String;
    fn try_from(v: toml::Value) -> Result<Self, String> {
        const FORMS: &str = "a trigger is \"apogee\", \"burnout\", \"motor_delay\" (burnout plus the motor's delay), or a table with one number: { time_s = .. } (after launch), { height_m = .. } (on the way down) or { delay_s = .. } (after burnout)";
        match v {
            toml::Value::String(s) => match s.as_str() {
                "apogee" => Ok(RawTrigger(Trigger::Apogee)),
                "burnout" => Ok(RawTrigger(Trigger::Burnout)),
                "motor_delay" => Ok(RawTrigger(Trigger::BurnoutPlusDelay { delay_s: None })),
                other => Err(format!("unknown trigger \"{other}\": {FORMS}")),
            },
            toml::Value::Table(t) if t.len() == 1 => {
                let (k, v) = t.into_iter().next().expect("one entry");
                let x = match v {
                    toml::Value::Float(x) => x,
                    toml::Value::Integer(i) => i as f64,
                    other => return Err(format!("trigger {k}: must be a number (got {other})")),
                };
                if !(x.is_finite() && x >= 0.0) {
                    return Err(format!(
                        "trigger {k}: must be finite and not negative (got {x})"
                    ));
                }
                match k.as_str() {
                    "time_s" => Ok(RawTrigger(Trigger::Time { time_s: x })),
                    "height_m" => Ok(RawTrigger(Trigger::HeightDescending { height_m: x })),
                    "delay_s" => Ok(RawTrigger(Trigger::BurnoutPlusDelay { delay_s: Some(x) })),
                    other => Err(format!("unknown trigger field \"{other}\": {FORMS}")),
                }
            }
            _ => Err(FORMS.to_string()),
        }
    }
}

/// The inputs under `[sweep]` (T = a list of values) or `[dispersions]` (T = a distribution).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawParams<T> {
    structure_mass_kg: Option<T>,
    structure_cg_m: Option<T>,
    ballast_kg: Option<T>,
    motor_impulse_ns: Option<T>,
    motor_burn_time_s: Option<T>,
    drag_scale: Option<T>,
    elevation_m: Option<T>,
    wind_speed_m_s: Option<T>,
    wind_from_deg: Option<T>,
    rail_length_m: Option<T>,
    rail_inclination_deg: Option<T>,
    rail_heading_deg: Option<T>,
    #[serde(default = "BTreeMap::new")]
    parachutes: BTreeMap<String, RawParachuteParams<T>>,
    #[serde(default = "BTreeMap::new")]
    shifts: BTreeMap<String, RawShiftParams<T>>,
}

impl<T> RawParams<T> {
    /// The global entries in [`GLOBAL`] order.
    fn globals(&mut self) -> [Option<T>; 12] {
        [
            self.structure_mass_kg.take(),
            self.structure_cg_m.take(),
            self.ballast_kg.take(),
            self.motor_impulse_ns.take(),
            self.motor_burn_time_s.take(),
            self.drag_scale.take(),
            self.elevation_m.take(),
            self.wind_speed_m_s.take(),
            self.wind_from_deg.take(),
            self.rail_length_m.take(),
            self.rail_inclination_deg.take(),
            self.rail_heading_deg.take(),
        ]
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawParachuteParams<T> {
    cds_m2: Option<T>,
    lag_s: Option<T>,
    time_s: Option<T>,
    height_m: Option<T>,
    delay_s: Option<T>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawShiftParams<T> {
    travel_m: Option<T>,
    duration_s: Option<T>,
    time_s: Option<T>,
    height_m: Option<T>,
    delay_s: Option<T>,
}

/// A distribution as the file writes it (see `docs/scenarios.md`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDist {
    dist: String,
    sigma: Option<f64>,
    bias: Option<f64>,
    mean: Option<f64>,
    min: Option<f64>,
    max: Option<f64>,
    mode: Option<f64>,
    mu: Option<f64>,
    relative: Option<bool>,
}

// ------------------------------------------------------------------------ validated model

/// The launch site and the wind.
#[derive(Debug, Clone, PartialEq)]
pub struct EnvironmentSpec {
    pub elevation_m: f64,
    pub wind_speed_m_s: f64,
    pub wind_from_deg: f64,
    /// Inverse-square gravity (true) or the constant standard gravity (false).
    pub inverse_square_gravity: bool,
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
}

#[derive(Debug, Clone, PartialEq)]
pub struct ShiftSpec {
    pub name: String,
    pub component: String,
    pub travel_m: f64,
    pub duration_s: f64,
    pub trigger: Trigger,
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

/// A validated scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The file (for messages and metadata), its directory (relative paths start there).
    pub file: PathBuf,
    pub dir: PathBuf,
    /// The file's text and its FNV-1a 64 fingerprint.
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
    pub environment: EnvironmentSpec,
    pub rail: RailSpec,
    pub parachutes: Vec<ParachuteSpec>,
    pub shifts: Vec<ShiftSpec>,
    pub integrator: Integrator,
    pub max_time_s: f64,
    /// Swept or dispersed inputs, in canonical order (globals, then each parachute's, then
    /// each shift's).
    pub inputs: Vec<InputSpec>,
    /// Variants per chunk (the unit of work, of resumption and of the part files).
    pub chunk_size: usize,
    /// Rows per row group of the output files.
    pub row_group_rows: usize,
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
    /// Read and validate the scenario file at `path`.
    pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Io {
            file: path.display().to_string(),
            source,
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
        let de = toml::Deserializer::parse(text)
            .map_err(|e| bad("(syntax)", one_line(&e.to_string())))?;
        let mut raw: RawScenario = serde_path_to_error::deserialize(de).map_err(|e| {
            let key = e.path().to_string();
            let key = if key == "." {
                "(top level)".to_string()
            } else {
                key
            };
            bad(&key, one_line(&e.into_inner().to_string()))
        })?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();

        let name = match raw.name.take() {
            Some(n) => n,
            None => path
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("scenario")
                .to_string(),
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
        if !design_file.is_file() {
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
        let motor_path = dir.join(&raw.motor.name);
        let motor = if raw.motor.name.trim().is_empty() {
            return Err(bad(
                "motor.name",
                "must name a motor: a bundled motor (Cesaroni_I175, I175...) or an .eng/.rse file"
                    .into(),
            ));
        } else if motor_path.is_file() {
            motor_path.display().to_string()
        } else {
            raw.motor.name.clone()
        };

        let env = raw.environment.take().unwrap_or_default();
        let environment = EnvironmentSpec {
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
            inverse_square_gravity: match env.gravity.as_deref() {
                None | Some("standard") => false,
                Some("inverse_square") => true,
                Some(other) => {
                    return Err(bad(
                        "environment.gravity",
                        format!("must be \"standard\" or \"inverse_square\" (got \"{other}\")"),
                    ))
                }
            },
        };
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
        for (i, p) in raw.parachutes.iter().enumerate() {
            let key = |f: &str| format!("parachutes[{i}].{f}");
            check_name(&bad, &key("name"), &p.name)?;
            if parachutes.iter().any(|q: &ParachuteSpec| q.name == p.name) {
                return Err(bad(
                    &key("name"),
                    format!(
                        "two parachutes are named \"{}\"; give each its own name",
                        p.name
                    ),
                ));
            }
            parachutes.push(ParachuteSpec {
                name: p.name.clone(),
                cds_m2: check_param(&bad, &key("cds_m2"), Param::ParachuteCdsM2(i), p.cds_m2)?,
                lag_s: check_param(&bad, &key("lag_s"), Param::ParachuteLagS(i), p.lag_s)?,
                trigger: p.trigger.0,
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

        let mut scenario = Scenario {
            file: path.to_path_buf(),
            dir,
            text: text.to_string(),
            hash: fingerprint(text.as_bytes()),
            name,
            description: raw.description.take(),
            seed: raw.seed,
            variants_per_point: raw.variants_per_point,
            common_random_numbers: raw.common_random_numbers.unwrap_or(true),
            design_file,
            ballast: raw.design.ballast.take(),
            motor,
            environment,
            rail,
            parachutes,
            shifts,
            integrator,
            max_time_s,
            inputs: vec![],
            chunk_size: chunk_size as usize,
            row_group_rows: row_group_rows as usize,
        };
        scenario.inputs = inputs(&scenario, &bad, raw.sweep.take(), raw.dispersions.take())?;
        if scenario.total_variants().is_none() {
            return Err(bad(
                "variants_per_point",
                "sweep points × variants per point is too many to count".into(),
            ));
        }
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
        if self.total_variants().is_none() {
            return Err(ScenarioError::Invalid {
                file: self.file.display().to_string(),
                key: "--variants".into(),
                rule: "sweep points × variants per point is too many to count".into(),
            });
        }
        Ok(self)
    }

    /// Number of sweep points (1 without a sweep).
    pub fn points(&self) -> usize {
        self.inputs
            .iter()
            .filter_map(|i| i.sweep.as_ref())
            .map(Vec::len)
            .product()
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
            _ => p.unit(),
        }
    }
}

/// A TOML error on one line (the crate's messages show the offending line in a box).
fn one_line(s: &str) -> String {
    s.lines()
        .map(str::trim)
        .filter(|l| {
            !l.is_empty() && !l.starts_with('|') && !l.chars().all(|c| c == '^' || c == ' ')
        })
        .collect::<Vec<_>>()
        .join("; ")
}

type Bad<'a> = dyn Fn(&str, String) -> ScenarioError + 'a;

fn finite(bad: &Bad, key: &str, v: f64) -> Result<f64, ScenarioError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad(key, format!("must be finite (got {v})")))
    }
}

fn check_param(bad: &Bad, key: &str, p: Param, v: f64) -> Result<f64, ScenarioError> {
    p.domain().check(v).map_err(|r| bad(key, r))?;
    Ok(v)
}

fn check_name(bad: &Bad, key: &str, name: &str) -> Result<(), ScenarioError> {
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(bad(
            key,
            format!("must be letters, digits and '_' (it names output columns; got \"{name}\")"),
        ));
    }
    Ok(())
}

fn integrator(bad: &Bad, r: RawIntegrator) -> Result<(Integrator, f64), ScenarioError> {
    let max_time_s = r.max_time_s.unwrap_or(600.0);
    if !(max_time_s.is_finite() && max_time_s > 0.0) {
        return Err(bad(
            "integrator.max_time_s",
            format!("must be positive and finite (got {max_time_s})"),
        ));
    }
    let pos = |key: &str, v: Option<f64>, default: f64| -> Result<f64, ScenarioError> {
        let v = v.unwrap_or(default);
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(bad(key, format!("must be positive and finite (got {v})")))
        }
    };
    match r.method.as_deref().unwrap_or("adaptive") {
        "adaptive" => {
            if r.step_s.is_some() {
                return Err(bad(
                    "integrator.step_s",
                    "only the \"rk4\" method has a fixed step; the adaptive one takes tolerances"
                        .into(),
                ));
            }
            let Integrator::Adaptive {
                rtol,
                atol_position_m,
                atol_velocity_m_s,
                atol_quaternion,
                atol_rate_rad_s,
            } = Integrator::DEFAULT
            else {
                unreachable!("the default integrator is adaptive")
            };
            Ok((
                Integrator::Adaptive {
                    rtol: pos("integrator.rtol", r.rtol, rtol)?,
                    atol_position_m: pos(
                        "integrator.atol_position_m",
                        r.atol_position_m,
                        atol_position_m,
                    )?,
                    atol_velocity_m_s: pos(
                        "integrator.atol_velocity_m_s",
                        r.atol_velocity_m_s,
                        atol_velocity_m_s,
                    )?,
                    atol_quaternion: pos(
                        "integrator.atol_quaternion",
                        r.atol_quaternion,
                        atol_quaternion,
                    )?,
                    atol_rate_rad_s: pos(
                        "integrator.atol_rate_rad_s",
                        r.atol_rate_rad_s,
                        atol_rate_rad_s,
                    )?,
                },
                max_time_s,
            ))
        }
        "rk4" => {
            for (k, v) in [
                ("rtol", r.rtol),
                ("atol_position_m", r.atol_position_m),
                ("atol_velocity_m_s", r.atol_velocity_m_s),
                ("atol_quaternion", r.atol_quaternion),
                ("atol_rate_rad_s", r.atol_rate_rad_s),
            ] {
                if v.is_some() {
                    return Err(bad(
                        &format!("integrator.{k}"),
                        "the \"rk4\" method takes a fixed step_s, not tolerances".into(),
                    ));
                }
            }
            let step = r.step_s.ok_or_else(|| {
                bad(
                    "integrator.step_s",
                    "the \"rk4\" method needs a step_s".into(),
                )
            })?;
            Ok((
                Integrator::Rk4 {
                    step_s: pos("integrator.step_s", Some(step), 0.0)?,
                },
                max_time_s,
            ))
        }
        other => Err(bad(
            "integrator.method",
            format!("must be \"adaptive\" or \"rk4\" (got \"{other}\")"),
        )),
    }
}

/// The entries of one parachute's or shift's table under `[sweep]` or `[dispersions]`:
/// (field, value), with the trigger fields separate.
struct PartEntries<T> {
    fixed: Vec<(&'static str, Param, Option<T>)>,
    trigger: Vec<(&'static str, Option<T>)>,
}

fn parachute_entries<T>(i: usize, p: RawParachuteParams<T>) -> PartEntries<T> {
    PartEntries {
        fixed: vec![
            ("cds_m2", Param::ParachuteCdsM2(i), p.cds_m2),
            ("lag_s", Param::ParachuteLagS(i), p.lag_s),
        ],
        trigger: vec![
            ("time_s", p.time_s),
            ("height_m", p.height_m),
            ("delay_s", p.delay_s),
        ],
    }
}

fn shift_entries<T>(i: usize, s: RawShiftParams<T>) -> PartEntries<T> {
    PartEntries {
        fixed: vec![
            ("travel_m", Param::ShiftTravelM(i), s.travel_m),
            ("duration_s", Param::ShiftDurationS(i), s.duration_s),
        ],
        trigger: vec![
            ("time_s", s.time_s),
            ("height_m", s.height_m),
            ("delay_s", s.delay_s),
        ],
    }
}

/// Collect the swept and dispersed inputs, keyed by input, checking names and triggers.
fn collect<T>(
    scenario: &Scenario,
    bad: &Bad,
    section: &str,
    raw: Option<RawParams<T>>,
) -> Result<BTreeMap<Param, T>, ScenarioError> {
    let mut out = BTreeMap::new();
    let Some(mut raw) = raw else { return Ok(out) };
    for ((p, _, _), v) in GLOBAL.iter().zip(raw.globals()) {
        if let Some(v) = v {
            out.insert(*p, v);
        }
    }
    let parts: [(&str, &str, Vec<(String, Trigger)>); 2] = [
        (
            "parachutes",
            "parachute",
            scenario
                .parachutes
                .iter()
                .map(|p| (p.name.clone(), p.trigger))
                .collect(),
        ),
        (
            "shifts",
            "shift",
            scenario
                .shifts
                .iter()
                .map(|s| (s.name.clone(), s.trigger))
                .collect(),
        ),
    ];
    let mut tables: [Vec<(String, PartEntries<T>)>; 2] = [vec![], vec![]];
    for (name, p) in std::mem::take(&mut raw.parachutes) {
        let i = index_of(bad, section, &parts[0], &name)?;
        tables[0].push((name, parachute_entries(i, p)));
    }
    for (name, s) in std::mem::take(&mut raw.shifts) {
        let i = index_of(bad, section, &parts[1], &name)?;
        tables[1].push((name, shift_entries(i, s)));
    }
    for (k, entries) in tables.into_iter().enumerate() {
        let (plural, singular, names) = &parts[k];
        for (name, e) in entries {
            let i = names
                .iter()
                .position(|n| n.0 == name)
                .expect("checked by index_of");
            for (_, p, v) in e.fixed {
                if let Some(v) = v {
                    out.insert(p, v);
                }
            }
            for (field, v) in e.trigger {
                let Some(v) = v else { continue };
                let trigger = names[i].1;
                let key = format!("{section}.{plural}.{name}.{field}");
                match trigger_field(&trigger) {
                    Some(f) if f == field => {}
                    Some(f) => return Err(bad(&key, format!("the {singular}'s trigger is {trigger}: its number is {f}, not {field}"))),
                    None => return Err(bad(&key, format!("the {singular}'s trigger is {trigger}, which has no number to sweep or disperse"))),
                }
                out.insert(
                    if k == 0 {
                        Param::ParachuteTrigger(i)
                    } else {
                        Param::ShiftTrigger(i)
                    },
                    v,
                );
            }
        }
    }
    Ok(out)
}

fn index_of(
    bad: &Bad,
    section: &str,
    part: &(&str, &str, Vec<(String, Trigger)>),
    name: &str,
) -> Result<usize, ScenarioError> {
    let (plural, _, names) = part;
    names.iter().position(|n| n.0 == name).ok_or_else(|| {
        let list: Vec<&str> = names.iter().map(|n| n.0.as_str()).collect();
        let known = if list.is_empty() {
            format!("the scenario has no {plural}")
        } else {
            format!("the scenario's {plural}: {}", list.join(", "))
        };
        bad(
            &format!("{section}.{plural}.{name}"),
            format!(
                "no {} is named \"{name}\" ({known})",
                &plural[..plural.len() - 1]
            ),
        )
    })
}

fn inputs(
    scenario: &Scenario,
    bad: &Bad,
    sweep: Option<RawParams<Vec<f64>>>,
    disp: Option<RawParams<RawDist>>,
) -> Result<Vec<InputSpec>, ScenarioError> {
    let sweep = collect(scenario, bad, "sweep", sweep)?;
    let disp = collect(scenario, bad, "dispersions", disp)?;
    let mut params: Vec<Param> = sweep.keys().chain(disp.keys()).copied().collect();
    params.sort();
    params.dedup();
    let mut out = Vec::new();
    for p in params {
        let key = scenario.key(p);
        let sweep_values = match sweep.get(&p) {
            None => None,
            Some(values) => {
                let k = format!("sweep.{key}");
                if values.is_empty() {
                    return Err(bad(&k, "empty sweep: give at least one value".into()));
                }
                for (j, &v) in values.iter().enumerate() {
                    p.domain()
                        .check(v)
                        .map_err(|r| bad(&format!("{k}[{j}]"), r))?;
                    if values[..j].contains(&v) {
                        return Err(bad(
                            &format!("{k}[{j}]"),
                            format!("the value {v} appears twice in the sweep"),
                        ));
                    }
                }
                Some(values.clone())
            }
        };
        let dispersion = match disp.get(&p) {
            None => None,
            Some(d) => Some(dispersion(
                bad,
                &format!("dispersions.{key}"),
                d,
                sweep_values.is_some(),
            )?),
        };
        out.push(InputSpec {
            param: p,
            column: scenario.column(p),
            unit: scenario.unit(p),
            key,
            sweep: sweep_values,
            dispersion,
        });
    }
    // Two keys landing on one block slot would share draws; FNV-1a 32 makes this very
    // unlikely, but it is checked.
    for (a, ia) in out.iter().enumerate() {
        for ib in &out[..a] {
            if ia.dispersion.is_some()
                && ib.dispersion.is_some()
                && super::sample::slot(&ia.key) == super::sample::slot(&ib.key)
            {
                return Err(bad(
                    &format!("dispersions.{}", ia.key),
                    format!(
                        "its random stream collides with that of {}; rename a parachute or a shift",
                        ib.key
                    ),
                ));
            }
        }
    }
    Ok(out)
}

fn dispersion(bad: &Bad, key: &str, d: &RawDist, swept: bool) -> Result<Dispersion, ScenarioError> {
    let fields = [
        ("sigma", d.sigma),
        ("bias", d.bias),
        ("mean", d.mean),
        ("min", d.min),
        ("max", d.max),
        ("mode", d.mode),
        ("mu", d.mu),
    ];
    for (f, v) in fields {
        if let Some(v) = v {
            if v.is_nan() || (v.is_infinite() && f != "min" && f != "max") {
                return Err(bad(
                    &format!("{key}.{f}"),
                    format!("must be finite (got {v})"),
                ));
            }
        }
    }
    let allowed: &[&str] = match d.dist.as_str() {
        "normal" => &["sigma", "bias", "mean"],
        "truncated_normal" => &["sigma", "bias", "min", "max"],
        "uniform" => &["min", "max"],
        "triangular" => &["min", "mode", "max"],
        "lognormal" => &["sigma", "mu"],
        other => {
            return Err(bad(&format!("{key}.dist"), format!("unknown distribution \"{other}\" (normal, truncated_normal, uniform, triangular or lognormal)")));
        }
    };
    for (f, v) in fields {
        if v.is_some() && !allowed.contains(&f) {
            return Err(bad(
                &format!("{key}.{f}"),
                format!(
                    "a {} distribution has no {f} (it takes {})",
                    d.dist,
                    allowed.join(", ")
                ),
            ));
        }
    }
    let relative = d.relative.unwrap_or(false);
    let need = |f: &str, v: Option<f64>| {
        v.ok_or_else(|| {
            bad(
                &format!("{key}.{f}"),
                format!("a {} distribution needs {f}", d.dist),
            )
        })
    };
    let sigma = |v: Option<f64>| -> Result<f64, ScenarioError> {
        let s = need("sigma", v)?;
        if s > 0.0 {
            Ok(s)
        } else {
            Err(bad(
                &format!("{key}.sigma"),
                format!("must be positive (got {s})"),
            ))
        }
    };
    let ordered = |min: f64, max: f64| -> Result<(), ScenarioError> {
        if min < max {
            Ok(())
        } else {
            Err(bad(
                &format!("{key}.max"),
                format!("must be greater than min (min {min}, max {max})"),
            ))
        }
    };
    let shape = match d.dist.as_str() {
        "normal" => {
            let s = sigma(d.sigma)?;
            match (d.mean, d.bias) {
                (Some(_), Some(_)) => return Err(bad(&format!("{key}.mean"), "give a mean (the value's) or a bias (the deviation's from the nominal), not both".into())),
                (Some(_), None) if relative => return Err(bad(&format!("{key}.mean"), "a mean is a value, so it can't be relative; give a bias instead".into())),
                (Some(_), None) if swept => return Err(bad(&format!("{key}.mean"), "the input is also swept, and a mean would ignore the sweep; give a bias (around each sweep value) instead".into())),
                (Some(mean), None) => Shape::NormalAbout { mean, sigma: s },
                (None, bias) => Shape::Normal { bias: bias.unwrap_or(0.0), sigma: s },
            }
        }
        "truncated_normal" => {
            let s = sigma(d.sigma)?;
            if d.min.is_none() && d.max.is_none() {
                return Err(bad(
                    &format!("{key}.min"),
                    "a truncated_normal distribution needs min, max or both (a normal has neither)"
                        .into(),
                ));
            }
            let (min, max) = (
                d.min.unwrap_or(f64::NEG_INFINITY),
                d.max.unwrap_or(f64::INFINITY),
            );
            ordered(min, max)?;
            Shape::TruncatedNormal {
                bias: d.bias.unwrap_or(0.0),
                sigma: s,
                min,
                max,
            }
        }
        "uniform" => {
            let (min, max) = (need("min", d.min)?, need("max", d.max)?);
            for (f, v) in [("min", min), ("max", max)] {
                if !v.is_finite() {
                    return Err(bad(
                        &format!("{key}.{f}"),
                        format!("must be finite (got {v})"),
                    ));
                }
            }
            ordered(min, max)?;
            Shape::Uniform { min, max }
        }
        "triangular" => {
            let (min, max) = (need("min", d.min)?, need("max", d.max)?);
            for (f, v) in [("min", min), ("max", max)] {
                if !v.is_finite() {
                    return Err(bad(
                        &format!("{key}.{f}"),
                        format!("must be finite (got {v})"),
                    ));
                }
            }
            ordered(min, max)?;
            let mode = d.mode.unwrap_or(0.0);
            if !(min <= mode && mode <= max) {
                return Err(bad(&format!("{key}.mode"), format!("must be from min to max ({min} to {max}; got {mode}, and it is 0 when not given)")));
            }
            Shape::Triangular { min, mode, max }
        }
        _ => {
            if d.relative.is_some() {
                return Err(bad(&format!("{key}.relative"), "a lognormal dispersion is always relative (value = nominal × exp(mu + sigma Z)); remove relative".into()));
            }
            Shape::LogNormal {
                mu: d.mu.unwrap_or(0.0),
                sigma: sigma(d.sigma)?,
            }
        }
    };
    Ok(Dispersion { shape, relative })
}

#[cfg(test)]
#[path = "scenario_tests.rs"]
mod tests;
