//! The steps of [`Scenario::parse`]: the file's text read into its raw form, then each part
//! of the file (the name, the design, the motor, the environment, the rail, the parachutes,
//! the shifts, the releases, the run's options and outputs, the sweep and the dispersions)
//! checked and turned into its validated form. The steps run in a fixed order and each stops
//! at the first rule broken, so a file that breaks several rules is always refused with the
//! same one.

use super::raw::{
    RawDesign, RawDist, RawEnvironment, RawMotor, RawOutputs, RawParachute, RawParams, RawRail,
    RawRelease, RawReleaseChute, RawRun, RawScenario, RawShift,
};
use super::rules::{
    self, canopy_shape, check_name, check_param, design_parachute, finite, inputs, noise, one_line,
    sounding, weather, weather_inputs, Bad, ParachuteFromDesign,
};
use super::{
    resolve_motor, EnvironmentSpec, GravityModel, ParachuteSpec, RailSpec, ReleaseSpec, Scenario,
    ScenarioError, ShiftSpec, DEFAULT_TRAJECTORIES, MAX_TRAJECTORIES,
};
use crate::campaign::params::Param;
use crate::campaign::sample::fingerprint;
use hpr_design::design::dimension::Dimension;
use hpr_design::motor::{Grains, MotorOptions};
use hpr_design::MAX_SAMPLING_RATE_HZ;
use hpr_sim::atmosphere::{AirModel, AirProfile, AirRow, AtmosphereError};
use hpr_sim::gravity::{is_latitude, LATITUDE_RULE};
use hpr_sim::turbulence::{MAX_TURBULENCE_INTENSITY, MAX_TURBULENT_FLIGHT_S};
use hpr_sim::wind::{Wind, WindError, WindRow};
use hpr_sim::{CanopyShape, PartChute, PartTrigger};
use std::path::{Path, PathBuf};

/// The file's text read as TOML into the raw scenario: a syntax error, an unknown key or a
/// value of the wrong type names where it is.
pub(super) fn deserialize(bad: &Bad, text: &str) -> Result<RawScenario, ScenarioError> {
    let de = toml::Deserializer::parse(text).map_err(|e| {
        let hint = if text.trim_start().starts_with('{') {
            " (this looks like a JSON design: a scenario is a TOML file that names its design \
             under [design] file = \"...\"; see docs/scenarios.md)"
        } else {
            ""
        };
        bad("(syntax)", format!("{}{hint}", one_line(&e.to_string())))
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let key = e.path().to_string();
        let key = if key == "." {
            "(top level)".to_string()
        } else {
            key
        };
        bad(
            &key,
            hpr_design::design::json_errors::plain_types(&one_line(&e.into_inner().to_string())),
        )
    })
}

/// `name`, which names the output directory: as given, or the file's stem with what a
/// directory name should not hold made '_'.
pub(super) fn name(bad: &Bad, name: Option<String>, path: &Path) -> Result<String, ScenarioError> {
    let name = match name {
        Some(n) => n,
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
    Ok(name)
}

/// `variants_per_point`: at least 1 (its upper bound, with the sweep's size, is judged last
/// by [`Scenario::check_size`]).
pub(super) fn variants_per_point(bad: &Bad, n: u64) -> Result<u64, ScenarioError> {
    if n == 0 {
        return Err(bad("variants_per_point", "must be at least 1".into()));
    }
    Ok(n)
}

/// `[design]`: the design file (beside the scenario) exists and is a file, and the ballast,
/// if named, is not empty. The design itself is read later, by the campaign.
pub(super) fn design_file(
    bad: &Bad,
    dir: &Path,
    design: &RawDesign,
) -> Result<PathBuf, ScenarioError> {
    let design_file = dir.join(&design.file);
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
    if let Some(b) = &design.ballast {
        if b.is_empty() {
            return Err(bad(
                "design.ballast",
                "must be the id of a component of the design".into(),
            ));
        }
    }
    Ok(design_file)
}

/// `[motor]`, validated: the motor as the campaign finds it and what the scenario gives in
/// place of its file's values.
pub(super) struct MotorSection {
    /// A motor file (resolved against the scenario's directory) or a bundled motor's name.
    pub(super) motor: String,
    pub(super) options: MotorOptions,
    pub(super) burn_time_s: Option<f64>,
    pub(super) diameter_m: Option<f64>,
}

/// `[motor]`: a name that is not blank, resolved against the scenario's directory, and its
/// numbers finite and not negative. The motor itself is read later, by the campaign.
pub(super) fn motor(bad: &Bad, dir: &Path, m: &RawMotor) -> Result<MotorSection, ScenarioError> {
    let motor = if m.name.trim().is_empty() {
        return Err(bad(
            "motor.name",
            "must name a motor: a bundled motor (Cesaroni_I175, I175...) or an .eng/.rse file"
                .into(),
        ));
    } else {
        resolve_motor(dir, &m.name)
    };
    let inertia = m.dry_inertia_kg_m2.unwrap_or_default();
    for (key, v) in [
        ("motor.propellant_mass_kg", m.propellant_mass_kg),
        ("motor.dry_mass_kg", m.dry_mass_kg),
        ("motor.dry_center_from_nozzle_m", m.dry_center_from_nozzle_m),
        (
            "motor.propellant_center_from_nozzle_m",
            m.propellant_center_from_nozzle_m,
        ),
        ("motor.dry_inertia_kg_m2", Some(inertia[0])),
        ("motor.dry_inertia_kg_m2", Some(inertia[1])),
        ("motor.burn_time_s", m.burn_time_s),
        ("motor.diameter_m", m.diameter_m),
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
    Ok(MotorSection {
        motor,
        options: MotorOptions {
            propellant_mass_kg: m.propellant_mass_kg,
            dry_mass_kg: m.dry_mass_kg,
            dry_center_from_nozzle_m: m.dry_center_from_nozzle_m,
            propellant_center_from_nozzle_m: m.propellant_center_from_nozzle_m,
            dry_inertia_kg_m2: m.dry_inertia_kg_m2,
            grains: m.grains.map(|g| Grains {
                count: g.count,
                outer_radius_m: g.outer_radius_m,
                inner_radius_m: g.inner_radius_m,
                height_m: g.height_m,
                separation_m: g.separation_m,
                density_kg_m3: g.density_kg_m3,
            }),
            chamber_m: m.chamber.map(|c| [c.radius_m, c.height_m]),
            nozzle_radius_m: m.nozzle_radius_m,
            ..MotorOptions::default()
        },
        burn_time_s: m.burn_time_s,
        diameter_m: m.diameter_m,
    })
}

/// `[environment]`: the site, the wind, gravity and the air. A sounding or a weather file is
/// read first: its air and wind become the profiles below, as if the scenario had written
/// their rows.
pub(super) fn environment(
    bad: &Bad,
    dir: &Path,
    mut env: RawEnvironment,
) -> Result<EnvironmentSpec, ScenarioError> {
    let sounding = sounding(bad, dir, &mut env)?;
    let weather = weather(bad, dir, &mut env)?;
    let wind_profile = wind_profile(bad, &env)?;
    let mut environment = EnvironmentSpec {
        elevation_m: finite(
            bad,
            "environment.elevation_m",
            env.elevation_m.unwrap_or(0.0),
        )?,
        wind_speed_m_s: check_param(
            bad,
            "environment.wind_speed_m_s",
            Param::WindSpeedMS,
            env.wind_speed_m_s.unwrap_or(0.0),
        )?,
        wind_from_deg: finite(
            bad,
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
            Some(super::raw::RawGravity::Name(name)) => {
                GravityModel::parse(name).map_err(|r| bad("environment.gravity", r))?
            }
            Some(super::raw::RawGravity::Value(g)) => {
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
    environment.air = air(bad, &env, environment.elevation_m)?;
    // The site's gravity can be had (Somigliana's needs the latitude).
    environment
        .gravity
        .at_site(
            environment.latitude_deg,
            environment.elevation_m,
            "environment.latitude_deg",
        )
        .map_err(|rule| bad("environment.gravity", rule.to_string()))?;
    Ok(environment)
}

/// `environment.wind_profile`, checked and built once (refused beside a constant wind); each
/// error names the row and the field in the scenario's words.
fn wind_profile(bad: &Bad, env: &RawEnvironment) -> Result<Option<Wind>, ScenarioError> {
    match &env.wind_profile {
        None => Ok(None),
        Some(_) if env.wind_speed_m_s.is_some() || env.wind_from_deg.is_some() => Err(bad(
            "environment.wind_profile",
            "give either a wind profile or a constant wind_speed_m_s and wind_from_deg, not both"
                .into(),
        )),
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
            Ok(Some(table))
        }
    }
}

/// The site's air: the standard atmosphere with the site's temperature and pressure if given,
/// or `environment.air_profile` (refused beside a site temperature, which is its first row).
fn air(bad: &Bad, env: &RawEnvironment, elevation_m: f64) -> Result<AirModel, ScenarioError> {
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
    match &env.air_profile {
        None => AirModel::site(elevation_m, env.temperature_k, env.pressure_pa).map_err(air_error),
        Some(_) if env.temperature_k.is_some() => Err(bad(
            "environment.temperature_k",
            "the site's temperature is environment.air_profile's first row: give one or the other"
                .into(),
        )),
        Some(rows) => {
            // The site's pressure: as given, or the standard's at the site.
            let (_, _, standard_pa) = AirModel::Standard.site_values(elevation_m);
            let profile = AirProfile {
                elevation_m,
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
            Ok(air)
        }
    }
}

/// `[rail]`: its length and inclination within their inputs' bounds (2 m and vertical by
/// default), its heading finite.
pub(super) fn rail(bad: &Bad, r: RawRail) -> Result<RailSpec, ScenarioError> {
    Ok(RailSpec {
        length_m: check_param(
            bad,
            "rail.length_m",
            Param::RailLengthM,
            r.length_m.unwrap_or(2.0),
        )?,
        inclination_deg: check_param(
            bad,
            "rail.inclination_deg",
            Param::RailInclinationDeg,
            r.inclination_deg.unwrap_or(90.0),
        )?,
        heading_deg: finite(bad, "rail.heading_deg", r.heading_deg.unwrap_or(0.0))?,
    })
}

/// `[[parachutes]]`, in file order. The design is read only when a parachute takes its
/// canopy from a component of it, and then once.
pub(super) fn parachutes(
    bad: &Bad,
    design_file: &Path,
    raw: &[RawParachute],
) -> Result<Vec<ParachuteSpec>, ScenarioError> {
    let mut parachutes = Vec::new();
    let mut design: Option<hpr_design::Design> = None;
    for (i, p) in raw.iter().enumerate() {
        let key = |f: &str| format!("parachutes[{i}].{f}");
        let from = match &p.component {
            Some(id) => {
                let d = match design.take() {
                    Some(d) => d,
                    None => hpr_design::Design::load(design_file)
                        .map_err(|e| bad("design.file", format!("{e}")))?,
                };
                let from = design_parachute(bad, &key("component"), &d, id)?;
                design = Some(d);
                Some(from)
            }
            None => None,
        };
        let spec = parachute(bad, i, p, from.as_ref(), &parachutes)?;
        parachutes.push(spec);
    }
    Ok(parachutes)
}

/// The `i`-th parachute: what its table gives, the rest from its design component `from`;
/// its name is not one of the `earlier` parachutes'.
fn parachute(
    bad: &Bad,
    i: usize,
    p: &RawParachute,
    from: Option<&ParachuteFromDesign>,
    earlier: &[ParachuteSpec],
) -> Result<ParachuteSpec, ScenarioError> {
    let key = |f: &str| format!("parachutes[{i}].{f}");
    let name = match (&p.name, &p.component) {
        (Some(n), _) => n.clone(),
        (None, Some(id)) => id.clone(),
        (None, None) => return Err(bad(&key("name"), "is missing (or give a component)".into())),
    };
    check_name(bad, &key("name"), &name)?;
    if earlier.iter().any(|q| q.name == name) {
        return Err(bad(
            &key("name"),
            format!("two parachutes are named \"{name}\"; give each its own name"),
        ));
    }
    let cds_m2 = match (p.cds_m2, from) {
        (Some(c), _) => c,
        (None, Some(d)) => d.cds_m2,
        (None, None) => {
            return Err(bad(
                &key("cds_m2"),
                "is missing (or give a component)".into(),
            ))
        }
    };
    let (trigger, lag_s) = match (&p.trigger, from) {
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
    Ok(ParachuteSpec {
        name,
        cds_m2: check_param(bad, &key("cds_m2"), Param::ParachuteCdsM2(i), cds_m2)?,
        lag_s: check_param(bad, &key("lag_s"), Param::ParachuteLagS(i), lag_s)?,
        trigger,
        canopy: canopy_shape(bad, &key, p)?,
        sampling_rate_hz: match p.sampling_rate_hz {
            Some(r) if !(r.is_finite() && r > 0.0 && r <= MAX_SAMPLING_RATE_HZ) => {
                return Err(bad(
                    &key("sampling_rate_hz"),
                    format!("must be positive, at most {MAX_SAMPLING_RATE_HZ} Hz (got {r})"),
                ))
            }
            r => r,
        },
        noise: noise(bad, &key, p)?,
    })
}

/// `[[shifts]]`, in file order: each named (after its component unless it has a name), the
/// names distinct, the travel and duration within their inputs' bounds.
pub(super) fn shifts(bad: &Bad, raw: &[RawShift]) -> Result<Vec<ShiftSpec>, ScenarioError> {
    let mut shifts = Vec::new();
    for (i, s) in raw.iter().enumerate() {
        let key = |f: &str| format!("shifts[{i}].{f}");
        let name = s.name.clone().unwrap_or_else(|| s.component.clone());
        check_name(bad, &key("name"), &name)?;
        if shifts.iter().any(|q: &ShiftSpec| q.name == name) {
            return Err(bad(&key("name"), format!("two shifts are named \"{name}\" (a shift is named after its component unless it has a name); give each its own name")));
        }
        shifts.push(ShiftSpec {
            name,
            component: s.component.clone(),
            travel_m: check_param(bad, &key("travel_m"), Param::ShiftTravelM(i), s.travel_m)?,
            duration_s: check_param(
                bad,
                &key("duration_s"),
                Param::ShiftDurationS(i),
                s.duration_s,
            )?,
            trigger: s.trigger.0,
        });
    }
    Ok(shifts)
}

/// `[[releases]]`, in file order: each named (after its component unless it has a name), the
/// names distinct, its drag area and its own parachute checked.
pub(super) fn releases(bad: &Bad, raw: &[RawRelease]) -> Result<Vec<ReleaseSpec>, ScenarioError> {
    let mut releases = Vec::new();
    for (i, r) in raw.iter().enumerate() {
        let key = |f: &str| format!("releases[{i}].{f}");
        let name = r.name.clone().unwrap_or_else(|| r.component.clone());
        check_name(bad, &key("name"), &name)?;
        if releases.iter().any(|q: &ReleaseSpec| q.name == name) {
            return Err(bad(&key("name"), format!("two releases are named \"{name}\" (a release is named after its component unless it has a name); give each its own name")));
        }
        let cda_m2 = match r.cda_m2 {
            Some(v) => Some(check_param(bad, &key("cda_m2"), Param::ReleaseCdaM2(i), v)?),
            None => None,
        };
        let parachute = match &r.parachute {
            None => None,
            Some(c) => Some(release_parachute(bad, i, c)?),
        };
        releases.push(ReleaseSpec {
            name,
            component: r.component.clone(),
            trigger: r.trigger.0,
            cda_m2,
            parachute,
        });
    }
    Ok(releases)
}

/// The `i`-th release's own parachute: what opens it (at the release by default; a height
/// above the ground), its canopy, its CdS and lag within their inputs' bounds.
fn release_parachute(bad: &Bad, i: usize, c: &RawReleaseChute) -> Result<PartChute, ScenarioError> {
    let k = |f: &str| format!("releases[{i}].parachute.{f}");
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
    Ok(PartChute {
        cds_m2: check_param(bad, &k("cds_m2"), Param::ReleaseChuteCdsM2(i), c.cds_m2)?,
        trigger,
        lag_s: check_param(
            bad,
            &k("lag_s"),
            Param::ReleaseChuteLagS(i),
            c.lag_s.unwrap_or(0.0),
        )?,
        canopy: shape,
    })
}

/// `[run]`: the variants per chunk (1 to 1,000,000; 32 by default) and the rows per row
/// group of the outputs (1 to 10,000,000; 8192 by default).
pub(super) fn run_options(bad: &Bad, run: RawRun) -> Result<(usize, usize), ScenarioError> {
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
    Ok((chunk_size as usize, row_group_rows as usize))
}

/// `[outputs] trajectories`: the variants per sweep point whose time series are written
/// (0 to [`MAX_TRAJECTORIES`]; [`DEFAULT_TRAJECTORIES`] by default).
pub(super) fn trajectories(bad: &Bad, outputs: Option<RawOutputs>) -> Result<u64, ScenarioError> {
    match outputs.and_then(|o| o.trajectories) {
        None => Ok(DEFAULT_TRAJECTORIES),
        Some(n) if n <= MAX_TRAJECTORIES => Ok(n),
        Some(n) => Err(bad(
            "outputs.trajectories",
            format!("must be from 0 to {MAX_TRAJECTORIES} variants per sweep point (got {n})"),
        )),
    }
}

/// The scenario's fingerprint: of its text, and of its sounding's text or its weather file's
/// fingerprint, which are part of the scenario (a run resumed with another is refused).
pub(super) fn hash(text: &str, environment: &EnvironmentSpec) -> String {
    match (&environment.sounding, &environment.weather) {
        (Some((_, sounding)), _) => fingerprint(format!("{text}\n{sounding}").as_bytes()),
        (None, Some(w)) => fingerprint(format!("{text}\n{}", w.fingerprint).as_bytes()),
        (None, None) => fingerprint(text.as_bytes()),
    }
}

/// `[sweep]` and `[dispersions]` into the scenario's motors, dimensions and inputs: a motor
/// is swept over a list, never dispersed; the design's dimensions either names are numbered
/// (in order of component id and field) before the inputs are collected.
pub(super) fn sweep_and_dispersions(
    scenario: &mut Scenario,
    bad: &Bad,
    mut sweep: Option<RawParams<Vec<f64>>>,
    dispersions: Option<RawParams<RawDist>>,
) -> Result<(), ScenarioError> {
    if dispersions.as_ref().is_some_and(|d| d.motor.is_some()) {
        return Err(bad(
            "dispersions.motor",
            "a motor is not a number to disperse: sweep it over a list of motors ([sweep] motor = [\"Cesaroni_I175\", ...])".into(),
        ));
    }
    if let Some(motors) = sweep.as_mut().and_then(|s| s.motor.take()) {
        scenario.motors = swept_motors(bad, &scenario.dir, motors)?;
    }
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
    scenario.inputs = inputs(scenario, bad, sweep, dispersions)?;
    Ok(())
}

/// `[sweep] motor`: at least one motor, none twice, each file found beside the scenario as
/// `motor.name`'s is.
fn swept_motors(bad: &Bad, dir: &Path, motors: Vec<String>) -> Result<Vec<String>, ScenarioError> {
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
    Ok(motors.iter().map(|m| resolve_motor(dir, m)).collect())
}

/// The rules across sections, judged once the inputs are known: a turbulent wind's time
/// limit, the inputs a weather file allows, and no constant wind varied beside a wind
/// profile.
pub(super) fn across_sections(scenario: &Scenario, bad: &Bad) -> Result<(), ScenarioError> {
    if scenario.turbulent() && scenario.max_time_s > MAX_TURBULENT_FLIGHT_S {
        return Err(bad(
            "integrator.max_time_s",
            format!("must be at most {MAX_TURBULENT_FLIGHT_S} s in a turbulent wind (environment.wind_turbulence_intensity), whose gusts each flight draws to its time limit (got {})", scenario.max_time_s),
        ));
    }
    weather_inputs(scenario, bad)?;
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
    Ok(())
}
