//! The rules of a scenario's values, sweeps and dispersions, each broken rule an error that
//! names the key path.

use super::raw::{
    RawAirRow, RawDist, RawEnvironment, RawIntegrator, RawParachute, RawParachuteParams, RawParams,
    RawReleaseParams, RawRequirement, RawShiftParams, RawWindRow,
};
use super::{trigger_field, InputSpec, RequirementSpec, Scenario, ScenarioError};
use crate::campaign::params::Param;
use crate::campaign::sample::{Dispersion, Shape};
use hpr_design::design::dimension::Dimension;
use hpr_sim::sounding::{SiteAir, Sounding};
use hpr_sim::{CanopyShape, Integrator, SensorNoise, Trigger};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What a parachute component of the design gives a scenario's parachute: its CdS (cd ×
/// the canopy's area) and, if it says, its trigger and lag.
pub(super) struct ParachuteFromDesign {
    pub(super) cds_m2: f64,
    pub(super) deploy: Option<(Trigger, f64)>,
}

/// The parachute component `id` of `design`.
pub(super) fn design_parachute(
    bad: &Bad,
    key: &str,
    design: &hpr_design::Design,
    id: &str,
) -> Result<ParachuteFromDesign, ScenarioError> {
    let Some(i) = design.component_index(id) else {
        return Err(bad(key, format!("the design has no component \"{id}\"")));
    };
    let hpr_design::ComponentKind::Parachute(p) = &design.components[i].kind else {
        return Err(bad(key, format!("component \"{id}\" is not a parachute")));
    };
    Ok(ParachuteFromDesign {
        cds_m2: p.cds_m2(),
        deploy: p.deploy.map(|d| (Trigger::from(d.trigger), d.lag_s)),
    })
}

/// A TOML error on one line (the crate's messages show the offending line in a box).
pub(super) fn one_line(s: &str) -> String {
    s.lines()
        .map(str::trim)
        .filter(|l| {
            // Drop the quoted source line ("8 | key = ...", "|") and its "^^^" marker.
            let quoted = l
                .trim_start_matches(|c: char| c.is_ascii_digit())
                .trim_start()
                .starts_with('|');
            !l.is_empty() && !quoted && !l.chars().all(|c| c == '^' || c == ' ')
        })
        .collect::<Vec<_>>()
        .join("; ")
}

pub(super) type Bad<'a> = dyn Fn(&str, String) -> ScenarioError + 'a;

pub(super) fn finite(bad: &Bad, key: &str, v: f64) -> Result<f64, ScenarioError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad(key, format!("must be finite (got {v})")))
    }
}

pub(super) fn check_param(bad: &Bad, key: &str, p: Param, v: f64) -> Result<f64, ScenarioError> {
    p.domain().check(v).map_err(|r| bad(key, r))?;
    Ok(v)
}

/// A parachute's canopy shape: what it gives of RocketPy's radius, height and porosity, the
/// rest RocketPy's defaults.
pub(super) fn canopy_shape(
    bad: &Bad,
    key: &dyn Fn(&str) -> String,
    p: &RawParachute,
) -> Result<CanopyShape, ScenarioError> {
    let shape = CanopyShape {
        radius_m: p.radius_m,
        height_m: p.height_m,
        porosity: p.porosity.unwrap_or(CanopyShape::default().porosity),
    };
    shape
        .check()
        .map_err(|(field, rule)| bad(&key(field), rule))?;
    Ok(shape)
}

/// A parachute's `noise`, checked: its numbers, and a sampling rate to read it at.
pub(super) fn noise(
    bad: &Bad,
    key: &dyn Fn(&str) -> String,
    p: &RawParachute,
) -> Result<Option<SensorNoise>, ScenarioError> {
    let Some(n) = &p.noise else {
        return Ok(None);
    };
    let noise = SensorNoise {
        bias_pa: n.bias_pa,
        std_pa: n.std_pa,
        correlation: n.correlation,
    };
    noise.check().map_err(|(field, rule, got)| {
        bad(
            &key(&format!("noise.{field}")),
            format!("{rule} (got {got})"),
        )
    })?;
    if p.sampling_rate_hz.is_none() {
        return Err(bad(&key("noise"), "a noisy barometer is read at samples: give the parachute a sampling_rate_hz too (RocketPy's default is 100 Hz)".into()));
    }
    Ok(Some(noise))
}

/// `environment.weather`, read: the file's weather over the site (`latitude_deg`,
/// `longitude_deg`, `elevation_m`, all required) at the launch time and member, its air
/// (with each level's pressure) and wind written into `env` as if the scenario had given
/// them, as a sounding's are. Refused beside the keys it replaces and beside a sounding.
pub(super) fn weather(
    bad: &Bad,
    dir: &Path,
    env: &mut RawEnvironment,
) -> Result<Option<super::WeatherSpec>, ScenarioError> {
    use hpr_sim::weather::{parse_utc, SiteWeather, MAX_WEATHER_FILE_BYTES};
    let Some(w) = &env.weather else {
        return Ok(None);
    };
    let key = "environment.weather";
    if env.sounding.is_some() {
        return Err(bad(
            key,
            "a weather file and a sounding each give the site's air and wind: give one of them"
                .into(),
        ));
    }
    let given = [
        ("temperature_k", env.temperature_k.is_some()),
        ("pressure_pa", env.pressure_pa.is_some()),
        ("air_profile", env.air_profile.is_some()),
        ("wind_speed_m_s", env.wind_speed_m_s.is_some()),
        ("wind_from_deg", env.wind_from_deg.is_some()),
        ("wind_profile", env.wind_profile.is_some()),
    ];
    if let Some((field, _)) = given.iter().find(|(_, g)| *g) {
        return Err(bad(key, format!("a weather file gives the site's air and wind: give either it or environment.{field}, not both")));
    }
    let needs = |field: &str, v: Option<f64>| {
        v.ok_or_else(|| {
            bad(
                &format!("environment.{field}"),
                format!("is needed with environment.weather: the file's grid is read at the site's latitude and longitude, and a pressure-level file does not say where the ground is (elevation_m, m above sea level)"),
            )
        })
    };
    let latitude = needs("latitude_deg", env.latitude_deg)?;
    let longitude = needs("longitude_deg", env.longitude_deg)?;
    let elevation = needs("elevation_m", env.elevation_m)?;
    let path = dir.join(&w.file);
    let file_key = "environment.weather.file";
    let size = std::fs::metadata(&path)
        .map_err(|e| bad(file_key, format!("cannot read {}: {e}", path.display())))?;
    if !size.is_file() {
        return Err(bad(file_key, format!("{} is not a file", path.display())));
    }
    if size.len() > MAX_WEATHER_FILE_BYTES {
        return Err(bad(file_key, format!("{}: it is {} bytes: a weather file may be at most {MAX_WEATHER_FILE_BYTES} bytes (2 GiB); cut it to the days and the area of the launch", path.display(), size.len())));
    }
    let bytes = std::fs::read(&path)
        .map_err(|e| bad(file_key, format!("cannot read {}: {e}", path.display())))?;
    let site = SiteWeather::from_bytes(&bytes, latitude, longitude)
        .map_err(|e| bad(file_key, format!("{}: {e}", path.display())))?;
    let time_s = parse_utc(&w.time).map_err(|r| bad("environment.weather.time", r))?;
    site.check_time(time_s).map_err(|e| {
        bad(
            "environment.weather.time",
            format!("{}: {e}", path.display()),
        )
    })?;
    let member = w.member.unwrap_or(site.members()[0]);
    let index = site.member_index(member).map_err(|e| {
        bad(
            "environment.weather.member",
            format!("{}: {e}", path.display()),
        )
    })?;
    let air = site.over_site(time_s, index, elevation).map_err(|e| {
        bad(
            file_key,
            format!(
                "{} (at environment.elevation_m = {elevation}): {e}",
                path.display()
            ),
        )
    })?;
    write_site_air(env, &air);
    Ok(Some(super::WeatherSpec {
        file: path,
        site: std::sync::Arc::new(site),
        time_s,
        member,
        fingerprint: crate::campaign::sample::fingerprint(&bytes),
    }))
}

/// The rules of the inputs a weather file gives: `launch_time_h` and `weather_member` need
/// one; a swept launch time, and a uniform or triangular one's ends, lie within its times;
/// a swept member is one of its members; neither goes with `temperature_k` or
/// `pressure_pa`, which set the same air.
pub(super) fn weather_inputs(scenario: &Scenario, bad: &Bad) -> Result<(), ScenarioError> {
    let drawn = |p: &Param| matches!(p, Param::LaunchTimeH | Param::WeatherMember);
    let Some(w) = &scenario.environment.weather else {
        if let Some(i) = scenario.inputs.iter().find(|i| drawn(&i.param)) {
            return Err(bad(
                &i.key_path(),
                "needs environment.weather, the weather file whose launch times and members it draws".into(),
            ));
        }
        return Ok(());
    };
    if let Some(i) = scenario.inputs.iter().find(|i| drawn(&i.param)) {
        if let Some(j) = scenario
            .inputs
            .iter()
            .find(|j| matches!(j.param, Param::TemperatureK | Param::PressurePa))
        {
            return Err(bad(
                &j.key_path(),
                format!("the site's air is the weather file's at each variant's {}: vary the one or the other", i.key),
            ));
        }
    }
    let times = w.site.times_s();
    let (first_h, last_h) = (
        (times[0] - w.time_s) / 3600.0,
        (times[times.len() - 1] - w.time_s) / 3600.0,
    );
    let window = format!(
        "the file's times are {first_h} to {last_h} h after environment.weather.time ({} to {})",
        hpr_sim::weather::format_utc(times[0]),
        hpr_sim::weather::format_utc(times[times.len() - 1])
    );
    for i in &scenario.inputs {
        match i.param {
            Param::LaunchTimeH => {
                let mut ends: Vec<(String, f64)> = i
                    .sweep
                    .iter()
                    .flatten()
                    .enumerate()
                    .map(|(k, &v)| (format!("sweep.{}[{k}]", i.key), v))
                    .collect();
                if let Some(d) = &i.dispersion {
                    let key = format!("dispersions.{}", i.key);
                    match d.shape {
                        Shape::Uniform { min, max } | Shape::Triangular { min, max, .. }
                            if !d.relative =>
                        {
                            for c in i.sweep.clone().unwrap_or(vec![0.0]) {
                                ends.push((format!("{key}.min"), c + min));
                                ends.push((format!("{key}.max"), c + max));
                            }
                        }
                        Shape::Uniform { .. } | Shape::Triangular { .. } => {
                            return Err(bad(
                                &key,
                                "a launch time's dispersion is in hours, not relative to the time"
                                    .into(),
                            ))
                        }
                        Shape::Members { .. } => {
                            return Err(bad(
                                &format!("{key}.dist"),
                                "\"members\" draws a weather_member, not a launch time".into(),
                            ))
                        }
                        // A normal's tail may leave the file: those variants are refused.
                        _ => {}
                    }
                }
                for (key, h) in ends {
                    if !(first_h..=last_h).contains(&h) {
                        return Err(bad(&key, format!("a launch {h} h after environment.weather.time is outside the weather file: {window}")));
                    }
                }
            }
            Param::WeatherMember => {
                for (k, &m) in i.sweep.iter().flatten().enumerate() {
                    w.site
                        .member_index(m)
                        .map_err(|e| bad(&format!("sweep.{}[{k}]", i.key), e.to_string()))?;
                }
                if let Some(d) = &i.dispersion {
                    if !matches!(d.shape, Shape::Members { .. }) {
                        return Err(bad(&format!("dispersions.{}.dist", i.key), "an ensemble member is dispersed with { dist = \"members\" }: each variant draws one of the file's members, each as likely".into()));
                    }
                    if i.sweep.is_some() {
                        return Err(bad(
                            &format!("dispersions.{}", i.key),
                            "the member is swept: a sweep point's member can't also be drawn"
                                .into(),
                        ));
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// A site's air and wind (from a weather file or a sounding) written into `env` as if the
/// scenario had given them: the ground pressure, the air rows and the wind rows.
fn write_site_air(env: &mut RawEnvironment, site: &SiteAir) {
    env.pressure_pa = Some(site.air.pressure_pa);
    env.air_profile = Some(
        site.air
            .rows
            .iter()
            .map(|r| RawAirRow {
                height_m: r.height_m,
                temperature_k: r.temperature_k,
                pressure_pa: r.pressure_pa,
            })
            .collect(),
    );
    env.wind_profile = Some(
        site.wind
            .iter()
            .map(|r| RawWindRow {
                height_m: r.height_agl_m,
                speed_m_s: r.speed_m_s,
                from_deg: r.from_deg,
            })
            .collect(),
    );
}

/// `environment.sounding`, read: the site's elevation (the sounding's ground unless given),
/// its pressure and the air and wind rows written into `env` as if the scenario had given
/// them; the file and its text, to fingerprint. Refused beside the keys it replaces.
pub(super) fn sounding(
    bad: &Bad,
    dir: &Path,
    env: &mut RawEnvironment,
) -> Result<Option<(PathBuf, String)>, ScenarioError> {
    let Some(file) = &env.sounding else {
        return Ok(None);
    };
    let key = "environment.sounding";
    let given = [
        ("temperature_k", env.temperature_k.is_some()),
        ("pressure_pa", env.pressure_pa.is_some()),
        ("air_profile", env.air_profile.is_some()),
        ("wind_speed_m_s", env.wind_speed_m_s.is_some()),
        ("wind_from_deg", env.wind_from_deg.is_some()),
        ("wind_profile", env.wind_profile.is_some()),
    ];
    if let Some((field, _)) = given.iter().find(|(_, g)| *g) {
        return Err(bad(key, format!("a sounding gives the site's air and wind: give either it or environment.{field}, not both")));
    }
    let path = dir.join(file);
    let text = hpr_design::limits::read_text_limited(
        &path,
        hpr_design::limits::MAX_SOUNDING_FILE_BYTES,
        "a sounding",
    )
    .map_err(|e| bad(key, format!("cannot read {}: {e}", path.display())))?;
    let site = Sounding::parse(&text)
        .map_err(|e| bad(key, format!("{}: {e}", path.display())))?
        .over_site(env.elevation_m)
        .map_err(|e| {
            bad(
                key,
                format!("{} (environment.elevation_m): {e}", path.display()),
            )
        })?;
    env.elevation_m = Some(site.elevation_m);
    write_site_air(env, &site);
    Ok(Some((path, text)))
}

pub(super) fn check_name(bad: &Bad, key: &str, name: &str) -> Result<(), ScenarioError> {
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(bad(
            key,
            format!("must be letters, digits and '_' (it names output columns; got \"{name}\")"),
        ));
    }
    Ok(())
}

/// `[requirements]`: each metric's bounds (at least one, finite, `min ≤ max`). Whether the
/// metric exists is judged with the design (`Prepared::new`).
pub(super) fn requirements(
    bad: &Bad,
    raw: BTreeMap<String, RawRequirement>,
) -> Result<Vec<RequirementSpec>, ScenarioError> {
    let mut out = Vec::with_capacity(raw.len());
    for (metric, r) in raw {
        let key = format!("requirements.{metric}");
        if r.min.is_none() && r.max.is_none() {
            return Err(bad(&key, "needs min, max or both".into()));
        }
        for (field, v) in [("min", r.min), ("max", r.max)] {
            if let Some(v) = v {
                finite(bad, &format!("{key}.{field}"), v)?;
            }
        }
        if let (Some(a), Some(b)) = (r.min, r.max) {
            if a > b {
                return Err(bad(&key, format!("min ({a}) is above max ({b})")));
            }
        }
        out.push(RequirementSpec {
            metric,
            min: r.min,
            max: r.max,
        });
    }
    Ok(out)
}

pub(super) fn integrator(bad: &Bad, r: RawIntegrator) -> Result<(Integrator, f64), ScenarioError> {
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
            let step_s = pos("integrator.step_s", Some(step), 0.0)?;
            if let Some(rule) = hpr_sim::flight::rk4_steps_rule(step_s, max_time_s) {
                return Err(bad("integrator.step_s", rule));
            }
            Ok((Integrator::Rk4 { step_s }, max_time_s))
        }
        other => Err(bad(
            "integrator.method",
            format!("must be \"adaptive\" or \"rk4\" (got \"{other}\")"),
        )),
    }
}

/// The entries of one parachute's, shift's or release's table under `[sweep]` or `[dispersions]`:
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

fn release_entries<T>(i: usize, r: RawReleaseParams<T>) -> PartEntries<T> {
    PartEntries {
        fixed: vec![
            ("cda_m2", Param::ReleaseCdaM2(i), r.cda_m2),
            (
                "parachute_cds_m2",
                Param::ReleaseChuteCdsM2(i),
                r.parachute_cds_m2,
            ),
            (
                "parachute_lag_s",
                Param::ReleaseChuteLagS(i),
                r.parachute_lag_s,
            ),
        ],
        trigger: vec![
            ("time_s", r.time_s),
            ("height_m", r.height_m),
            ("delay_s", r.delay_s),
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
    for (p, v) in std::mem::take(&mut raw.globals) {
        out.insert(p, v);
    }
    for (component, fields) in std::mem::take(&mut raw.design) {
        for (field, v) in fields {
            let k = scenario
                .dimensions
                .iter()
                .position(|d| d.component == component && d.field == field)
                .expect("the scenario's dimensions hold every one its tables name");
            out.insert(Param::Design(k), v);
        }
    }
    let parts: [PartNames; 3] = [
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
        (
            "releases",
            "release",
            scenario
                .releases
                .iter()
                .map(|r| (r.name.clone(), r.trigger))
                .collect(),
        ),
    ];
    let mut tables: [Vec<(String, PartEntries<T>)>; 3] = [vec![], vec![], vec![]];
    for (name, p) in std::mem::take(&mut raw.parachutes) {
        let i = index_of(bad, section, &parts[0], &name)?;
        tables[0].push((name, parachute_entries(i, p)));
    }
    for (name, s) in std::mem::take(&mut raw.shifts) {
        let i = index_of(bad, section, &parts[1], &name)?;
        tables[1].push((name, shift_entries(i, s)));
    }
    for (name, r) in std::mem::take(&mut raw.releases) {
        let i = index_of(bad, section, &parts[2], &name)?;
        tables[2].push((name, release_entries(i, r)));
    }
    for (k, entries) in tables.into_iter().enumerate() {
        let (plural, singular, names) = &parts[k];
        for (name, e) in entries {
            let i = names
                .iter()
                .position(|n| n.0 == name)
                .expect("checked by index_of");
            for (field, p, v) in e.fixed {
                let Some(v) = v else { continue };
                // A released part's parachute numbers need the parachute.
                if let Param::ReleaseChuteCdsM2(r) | Param::ReleaseChuteLagS(r) = p {
                    if scenario.releases[r].parachute.is_none() {
                        return Err(bad(
                            &format!("{section}.{plural}.{name}.{field}"),
                            "the release's part has no parachute (give its [[releases]] a parachute, or vary its cda_m2)".into(),
                        ));
                    }
                }
                out.insert(p, v);
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
                    match k {
                        0 => Param::ParachuteTrigger(i),
                        1 => Param::ShiftTrigger(i),
                        _ => Param::ReleaseTrigger(i),
                    },
                    v,
                );
            }
        }
    }
    Ok(out)
}

/// A kind of part (plural and singular) and the names and triggers of the scenario's parts.
type PartNames<'a> = (&'a str, &'a str, Vec<(String, Trigger)>);

fn index_of(
    bad: &Bad,
    section: &str,
    part: &PartNames,
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

/// The design's dimensions a `design` table of `[sweep]` or `[dispersions]` names.
pub(super) fn dimensions<T>(design: &BTreeMap<String, BTreeMap<String, T>>) -> Vec<Dimension> {
    design
        .iter()
        .flat_map(|(component, fields)| {
            fields.keys().map(|field| Dimension {
                component: component.clone(),
                field: field.clone(),
            })
        })
        .collect()
}

pub(super) fn inputs(
    scenario: &Scenario,
    bad: &Bad,
    sweep: Option<RawParams<Vec<f64>>>,
    disp: Option<RawParams<RawDist>>,
) -> Result<Vec<InputSpec>, ScenarioError> {
    let mut sweep = collect(scenario, bad, "sweep", sweep)?;
    // A sweep of motors is a sweep of their numbers in the list.
    if !scenario.motors.is_empty() {
        let numbers = (0..scenario.motors.len()).map(|j| j as f64).collect();
        sweep.insert(Param::Motor, numbers);
    }
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
        // "members": the weather file's, which must be numbered one after another.
        let dispersion = match dispersion {
            Some(Dispersion {
                shape: Shape::Members { .. },
                relative,
            }) => {
                let k = format!("dispersions.{key}.dist");
                if p != Param::WeatherMember {
                    return Err(bad(&k, "\"members\" draws a weather file's ensemble member: it is weather_member's".into()));
                }
                let Some(w) = &scenario.environment.weather else {
                    return Err(bad(
                        &k,
                        "needs environment.weather, the file whose members it draws".into(),
                    ));
                };
                let m = w.site.members();
                if m.windows(2).any(|p| p[1] != p[0] + 1.0) || m[0].fract() != 0.0 {
                    return Err(bad(&k, format!("the file's members ({}) are not whole numbers one after another, which a draw needs", m.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(", "))));
                }
                Some(Dispersion {
                    shape: Shape::Members {
                        first: m[0],
                        count: m.len() as u32,
                    },
                    relative,
                })
            }
            d => d,
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
                && crate::campaign::sample::slot(&ia.key) == crate::campaign::sample::slot(&ib.key)
            {
                return Err(bad(
                    &format!("dispersions.{}", ia.key),
                    format!(
                        "its random stream collides with that of {}; rename a parachute, a shift or a release",
                        ib.key
                    ),
                ));
            }
        }
    }
    Ok(out)
}

/// How far from its center (in sigmas) a truncated normal's interval may begin.
pub const TRUNCATION_REACH_SIGMA: f64 = 8.0;

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
        "members" => &[],
        other => {
            return Err(bad(&format!("{key}.dist"), format!("unknown distribution \"{other}\" (normal, truncated_normal, uniform, triangular, lognormal, or members for a weather_member)")));
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
            let bias = d.bias.unwrap_or(0.0);
            // A truncation far in a tail keeps almost nothing of the normal (beyond 8 σ,
            // less than 1e-15 of it): a mistake of units or of sign, and a draw no sampler
            // can make in finite time once the bound is past 1e154 σ.
            let (lo, hi) = ((min - bias) / s, (max - bias) / s);
            for (f, z, side) in [("min", lo, "above"), ("max", -hi, "below")] {
                if z > TRUNCATION_REACH_SIGMA {
                    return Err(bad(
                        &format!("{key}.{f}"),
                        format!(
                            "lies {z:.3e} sigma {side} the distribution's center (bias {bias}, sigma {s}): the interval must reach within {TRUNCATION_REACH_SIGMA} sigma of the center, or it holds almost none of the normal"
                        ),
                    ));
                }
            }
            Shape::TruncatedNormal {
                bias,
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
        "members" => {
            if d.relative.is_some() {
                return Err(bad(
                    &format!("{key}.relative"),
                    "a member is drawn, not scaled: remove relative".into(),
                ));
            }
            // The file's members are filled in by `inputs`, which knows them.
            Shape::Members {
                first: f64::NAN,
                count: 0,
            }
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
