//! The scenario file as TOML says it: serde structs that refuse unknown keys. Only
//! [`super`] reads them, turning them into the validated [`super::Scenario`].

use crate::campaign::params::{Param, GLOBAL};
use hpr_design::DeployTrigger;
use hpr_sim::{PartTrigger, Trigger};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScenario {
    pub(super) name: Option<String>,
    pub(super) description: Option<String>,
    pub(super) seed: u64,
    pub(super) variants_per_point: u64,
    pub(super) common_random_numbers: Option<bool>,
    pub(super) design: RawDesign,
    pub(super) motor: RawMotor,
    pub(super) environment: Option<RawEnvironment>,
    pub(super) rail: Option<RawRail>,
    #[serde(default)]
    pub(super) parachutes: Vec<RawParachute>,
    #[serde(default)]
    pub(super) shifts: Vec<RawShift>,
    #[serde(default)]
    pub(super) releases: Vec<RawRelease>,
    pub(super) integrator: Option<RawIntegrator>,
    pub(super) sweep: Option<RawParams<Vec<f64>>>,
    pub(super) dispersions: Option<RawParams<RawDist>>,
    pub(super) run: Option<RawRun>,
    pub(super) outputs: Option<RawOutputs>,
    /// Metric name → bounds.
    pub(super) requirements: Option<std::collections::BTreeMap<String, RawRequirement>>,
}

/// A requirement on a metric: `{ min = 1.5 }`, `{ max = 3048.0 }` or both.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRequirement {
    pub(super) min: Option<f64>,
    pub(super) max: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDesign {
    pub(super) file: PathBuf,
    pub(super) ballast: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMotor {
    pub(super) name: String,
    pub(super) propellant_mass_kg: Option<f64>,
    pub(super) dry_mass_kg: Option<f64>,
    pub(super) dry_center_from_nozzle_m: Option<f64>,
    pub(super) propellant_center_from_nozzle_m: Option<f64>,
    pub(super) dry_inertia_kg_m2: Option<[f64; 2]>,
    pub(super) grains: Option<RawGrains>,
    pub(super) chamber: Option<RawChamber>,
    pub(super) nozzle_radius_m: Option<f64>,
    /// The thrust curve cut at this time (RocketPy's `burn_time`).
    pub(super) burn_time_s: Option<f64>,
    /// The casing's outer diameter in place of the file's.
    pub(super) diameter_m: Option<f64>,
}

#[derive(Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub(super) struct RawChamber {
    pub(super) radius_m: f64,
    pub(super) height_m: f64,
}

#[derive(Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub(super) struct RawGrains {
    pub(super) count: u32,
    pub(super) outer_radius_m: f64,
    pub(super) inner_radius_m: f64,
    pub(super) height_m: f64,
    pub(super) separation_m: f64,
    pub(super) density_kg_m3: f64,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawEnvironment {
    pub(super) elevation_m: Option<f64>,
    pub(super) wind_speed_m_s: Option<f64>,
    pub(super) wind_from_deg: Option<f64>,
    pub(super) wind_profile: Option<Vec<RawWindRow>>,
    pub(super) wind_turbulence_intensity: Option<f64>,
    pub(super) gravity: Option<RawGravity>,
    pub(super) latitude_deg: Option<f64>,
    pub(super) longitude_deg: Option<f64>,
    pub(super) weather: Option<RawWeather>,
    pub(super) temperature_k: Option<f64>,
    pub(super) pressure_pa: Option<f64>,
    pub(super) air_profile: Option<Vec<RawAirRow>>,
    pub(super) sounding: Option<String>,
}

/// `environment.gravity`: a model's name or a constant value, m/s².
#[derive(Deserialize)]
#[serde(
    untagged,
    expecting = "a gravity model's name (\"standard\", \"inverse_square\", \"somigliana\") or a constant value in m/s² (such as 9.81)"
)]
pub(super) enum RawGravity {
    Name(String),
    Value(f64),
}

/// `environment.weather`: a weather-model file and the launch time in it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawWeather {
    pub(super) file: PathBuf,
    pub(super) time: String,
    /// The ensemble member, by the file's number (default: its first).
    pub(super) member: Option<f64>,
}

/// A row of `environment.air_profile`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAirRow {
    pub(super) height_m: f64,
    pub(super) temperature_k: f64,
    /// The pressure measured there, Pa (optional; never on the first row).
    pub(super) pressure_pa: Option<f64>,
}

/// A row of `environment.wind_profile`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawWindRow {
    pub(super) height_m: f64,
    pub(super) speed_m_s: f64,
    pub(super) from_deg: f64,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRail {
    pub(super) length_m: Option<f64>,
    pub(super) inclination_deg: Option<f64>,
    pub(super) heading_deg: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawParachute {
    /// Default: the design component's id, with `component`.
    pub(super) name: Option<String>,
    /// A parachute component of the design whose canopy (cd × area) and deployment
    /// (`deploy`) give what this table does not.
    pub(super) component: Option<String>,
    pub(super) cds_m2: Option<f64>,
    pub(super) lag_s: Option<f64>,
    pub(super) trigger: Option<RawTrigger>,
    pub(super) radius_m: Option<f64>,
    pub(super) height_m: Option<f64>,
    pub(super) porosity: Option<f64>,
    pub(super) sampling_rate_hz: Option<f64>,
    pub(super) noise: Option<RawNoise>,
}

/// A flight computer's barometer noise: `{ bias_pa = 0, std_pa = 8.3, correlation = 0.5 }`
/// (RocketPy's `noise` tuple; bias and correlation default to 0).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawNoise {
    #[serde(default)]
    pub(super) bias_pa: f64,
    pub(super) std_pa: f64,
    #[serde(default)]
    pub(super) correlation: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawShift {
    pub(super) name: Option<String>,
    pub(super) component: String,
    pub(super) travel_m: f64,
    pub(super) duration_s: f64,
    pub(super) trigger: RawTrigger,
}

/// `[[releases]]`: a part that leaves the rocket, and how it falls.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRelease {
    /// Default: the component's id.
    pub(super) name: Option<String>,
    pub(super) component: String,
    pub(super) trigger: RawTrigger,
    /// The part's drag area falling free, m² (default: the tumbling estimate).
    pub(super) cda_m2: Option<f64>,
    pub(super) parachute: Option<RawReleaseChute>,
}

/// A released part's own parachute: `{ cds_m2 = 0.3, trigger = "release", lag_s = 2.0 }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawReleaseChute {
    pub(super) cds_m2: f64,
    /// `"release"` (the default), `"apogee"` (the part's own) or `{ height_m = 150.0 }`.
    pub(super) trigger: Option<RawPartTrigger>,
    pub(super) lag_s: Option<f64>,
    pub(super) radius_m: Option<f64>,
    pub(super) height_m: Option<f64>,
    pub(super) porosity: Option<f64>,
}

/// What opens a released part's parachute, as the file writes it.
#[derive(Deserialize)]
#[serde(try_from = "toml::Value")]
pub(super) struct RawPartTrigger(pub(super) PartTrigger);

impl TryFrom<toml::Value> for RawPartTrigger {
    type Error = String;
    fn try_from(v: toml::Value) -> Result<Self, String> {
        const FORMS: &str = "a released part's parachute opens at \"release\", at the part's own \"apogee\", or at { height_m = ... } on its way down";
        match v {
            toml::Value::String(s) if s == "release" => Ok(RawPartTrigger(PartTrigger::Release)),
            toml::Value::String(s) if s == "apogee" => Ok(RawPartTrigger(PartTrigger::Apogee)),
            toml::Value::Table(t) if t.len() == 1 && t.contains_key("height_m") => {
                let height_m = match &t["height_m"] {
                    toml::Value::Float(x) => *x,
                    toml::Value::Integer(i) => *i as f64,
                    other => {
                        return Err(format!("trigger height_m: must be a number (got {other})"))
                    }
                };
                Ok(RawPartTrigger(PartTrigger::HeightDescending { height_m }))
            }
            other => Err(format!("{FORMS} (got {other})")),
        }
    }
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawIntegrator {
    pub(super) method: Option<String>,
    pub(super) rtol: Option<f64>,
    pub(super) atol_position_m: Option<f64>,
    pub(super) atol_velocity_m_s: Option<f64>,
    pub(super) atol_quaternion: Option<f64>,
    pub(super) atol_rate_rad_s: Option<f64>,
    pub(super) step_s: Option<f64>,
    pub(super) max_time_s: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOutputs {
    pub(super) trajectories: Option<u64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRun {
    pub(super) chunk_size: Option<u64>,
    pub(super) row_group_rows: Option<u64>,
}

/// A trigger as the file writes it: `"apogee"`, `"burnout"`, `"motor_delay"`, or a table with
/// one number: `{ time_s = 5.0 }`, `{ height_m = 300.0 }` (on the way down), `{ delay_s = 2.0 }`
/// (after burnout).
#[derive(Deserialize)]
#[serde(try_from = "toml::Value")]
pub(super) struct RawTrigger(pub(super) Trigger);

impl TryFrom<toml::Value> for RawTrigger {
    type Error = String;
    fn try_from(v: toml::Value) -> Result<Self, String> {
        // The grammar is the design format's (`hpr_design::DeployTrigger`); TOML only holds
        // the word or the table.
        let trigger = match v {
            toml::Value::String(s) => DeployTrigger::named(&s)?,
            toml::Value::Table(t) if t.len() == 1 => {
                let (k, v) = t.into_iter().next().expect("one entry");
                let x = match v {
                    toml::Value::Float(x) => x,
                    toml::Value::Integer(i) => i as f64,
                    other => return Err(format!("trigger {k}: must be a number (got {other})")),
                };
                DeployTrigger::with_number(&k, x)?
            }
            _ => return Err(DeployTrigger::FORMS.to_string()),
        };
        Ok(RawTrigger(Trigger::from(trigger)))
    }
}

/// The inputs under `[sweep]` (T = a list of values) or `[dispersions]` (T = a distribution):
/// each input of the flight as a whole by its key ([`hpr_sim::inputs::GLOBAL`]), in the
/// file's order, and each parachute's, shift's and release's under its name.
pub(super) struct RawParams<T> {
    pub(super) globals: Vec<(Param, T)>,
    /// `motor = ["Cesaroni_I175", ...]`: the motors a sweep flies, by name or file.
    pub(super) motor: Option<Vec<String>>,
    /// `design.<component id>.<field>`: a dimension of the design.
    pub(super) design: BTreeMap<String, BTreeMap<String, T>>,
    pub(super) parachutes: BTreeMap<String, RawParachuteParams<T>>,
    pub(super) shifts: BTreeMap<String, RawShiftParams<T>>,
    pub(super) releases: BTreeMap<String, RawReleaseParams<T>>,
}

/// A value refused, whatever it is, with this rule.
struct Refuse(String);

impl<'de> serde::de::DeserializeSeed<'de> for Refuse {
    type Value = ();
    fn deserialize<D: serde::Deserializer<'de>>(self, _: D) -> Result<(), D::Error> {
        Err(serde::de::Error::custom(self.0))
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for RawParams<T> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor<T>(std::marker::PhantomData<T>);
        impl<'de, T: Deserialize<'de>> serde::de::Visitor<'de> for Visitor<T> {
            type Value = RawParams<T>;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a table of inputs")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> Result<RawParams<T>, A::Error> {
                use serde::de::Error;
                let mut out = RawParams {
                    globals: Vec::new(),
                    motor: None,
                    design: BTreeMap::new(),
                    parachutes: BTreeMap::new(),
                    shifts: BTreeMap::new(),
                    releases: BTreeMap::new(),
                };
                while let Some(key) = map.next_key::<String>()? {
                    match key.as_str() {
                        "motor" => out.motor = Some(map.next_value()?),
                        "design" => out.design = map.next_value()?,
                        "parachutes" => out.parachutes = map.next_value()?,
                        "shifts" => out.shifts = map.next_value()?,
                        "releases" => out.releases = map.next_value()?,
                        k => match Param::global(k) {
                            Some(p) => out.globals.push((p, map.next_value()?)),
                            None => {
                                let known: Vec<String> = GLOBAL
                                    .iter()
                                    .map(|g| g.1.key)
                                    .chain(["design", "parachutes", "shifts", "releases"])
                                    .map(|k| format!("`{k}`"))
                                    .collect();
                                // Refused while its value is read, so that the error's path
                                // ends in the key.
                                let rule = format!(
                                    "unknown field `{k}`, expected one of {}",
                                    known.join(", ")
                                );
                                map.next_value_seed(Refuse(rule.clone()))?;
                                return Err(A::Error::custom(rule));
                            }
                        },
                    }
                }
                Ok(out)
            }
        }
        d.deserialize_map(Visitor(std::marker::PhantomData))
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawParachuteParams<T> {
    pub(super) cds_m2: Option<T>,
    pub(super) lag_s: Option<T>,
    pub(super) time_s: Option<T>,
    pub(super) height_m: Option<T>,
    pub(super) delay_s: Option<T>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawShiftParams<T> {
    pub(super) travel_m: Option<T>,
    pub(super) duration_s: Option<T>,
    pub(super) time_s: Option<T>,
    pub(super) height_m: Option<T>,
    pub(super) delay_s: Option<T>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawReleaseParams<T> {
    pub(super) time_s: Option<T>,
    pub(super) height_m: Option<T>,
    pub(super) delay_s: Option<T>,
    pub(super) cda_m2: Option<T>,
    pub(super) parachute_cds_m2: Option<T>,
    pub(super) parachute_lag_s: Option<T>,
}

/// A distribution as the file writes it (see `docs/scenarios.md`).
#[derive(Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a distribution table such as { dist = \"normal\", sigma = 0.1 }"
)]
pub(super) struct RawDist {
    pub(super) dist: String,
    pub(super) sigma: Option<f64>,
    pub(super) bias: Option<f64>,
    pub(super) mean: Option<f64>,
    pub(super) min: Option<f64>,
    pub(super) max: Option<f64>,
    pub(super) mode: Option<f64>,
    pub(super) mu: Option<f64>,
    pub(super) relative: Option<bool>,
}
