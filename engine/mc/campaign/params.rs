//! The inputs a scenario can sweep or disperse: their key paths (as the TOML file writes
//! them under `[sweep]` and `[dispersions]`), their column names in the output, their units
//! and the range of values a flight accepts.

use hpr_sim::atmosphere::{SITE_PRESSURE_RANGE_PA, SITE_TEMPERATURE_RANGE_K};

/// One input of a flight that a scenario may sweep or disperse. Parachutes, shifts and
/// releases are numbered in the order the scenario lists them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Param {
    /// Mass of the rocket without its motor, kg (nominal: the design's, ballast included).
    StructureMassKg,
    /// Center of mass of the rocket without its motor, m aft of the nose tip.
    StructureCgM,
    /// Mass of the design's ballast component, kg.
    BallastKg,
    /// Total impulse of the motor, N·s (nominal: its thrust curve's).
    MotorImpulseNs,
    /// Burn time of the motor, s (nominal: its thrust curve's).
    MotorBurnTimeS,
    /// Multiplier of the drag coefficient (nominal 1).
    DragScale,
    /// Launch site elevation above sea level, m.
    ElevationM,
    /// The site's air temperature, K (nominal: `environment.temperature_k`, or the standard
    /// atmosphere's at the site).
    TemperatureK,
    /// The site's air pressure, Pa (nominal: `environment.pressure_pa`, or the standard's).
    PressurePa,
    WindSpeedMS,
    /// Direction the wind blows from, degrees clockwise from north.
    WindFromDeg,
    /// Multiplier of every speed of the wind (nominal 1).
    WindScale,
    /// Clockwise turn of every direction of the wind, degrees (nominal 0).
    WindRotationDeg,
    /// The wind's turbulence intensity (nominal: `environment.wind_turbulence_intensity`).
    WindTurbulenceIntensity,
    RailLengthM,
    RailInclinationDeg,
    RailHeadingDeg,
    /// The air brakes' target apogee, m above the site (nominal: the design's).
    AirBrakesTargetM,
    /// The launch time, hours after `environment.weather.time` (nominal 0): the air and the
    /// wind are the weather file's then.
    LaunchTimeH,
    /// The weather file's ensemble member, by the file's number (nominal:
    /// `environment.weather.member`).
    WeatherMember,
    ParachuteCdsM2(usize),
    ParachuteLagS(usize),
    /// The number in the parachute's trigger (its time, height or delay).
    ParachuteTrigger(usize),
    ShiftTravelM(usize),
    ShiftDurationS(usize),
    /// The number in the shift's trigger (its time, height or delay).
    ShiftTrigger(usize),
    /// The number in the release's trigger (its time, height or delay).
    ReleaseTrigger(usize),
    /// The released part's drag area falling free, m².
    ReleaseCdaM2(usize),
    /// The released part's own parachute: its CdS, m², and its lag, s.
    ReleaseChuteCdsM2(usize),
    ReleaseChuteLagS(usize),
}

/// The global inputs, in their canonical order (the order of the output's columns and of the
/// sweep's axes), with their key and unit.
pub const GLOBAL: [(Param, &str, &str); 20] = [
    (Param::StructureMassKg, "structure_mass_kg", "kg"),
    (Param::StructureCgM, "structure_cg_m", "m"),
    (Param::BallastKg, "ballast_kg", "kg"),
    (Param::MotorImpulseNs, "motor_impulse_ns", "N·s"),
    (Param::MotorBurnTimeS, "motor_burn_time_s", "s"),
    (Param::DragScale, "drag_scale", "1"),
    (Param::ElevationM, "elevation_m", "m"),
    (Param::TemperatureK, "temperature_k", "K"),
    (Param::PressurePa, "pressure_pa", "Pa"),
    (Param::WindSpeedMS, "wind_speed_m_s", "m/s"),
    (Param::WindFromDeg, "wind_from_deg", "deg"),
    (Param::WindScale, "wind_scale", "1"),
    (Param::WindRotationDeg, "wind_rotation_deg", "deg"),
    (
        Param::WindTurbulenceIntensity,
        "wind_turbulence_intensity",
        "1",
    ),
    (Param::RailLengthM, "rail_length_m", "m"),
    (Param::RailInclinationDeg, "rail_inclination_deg", "deg"),
    (Param::RailHeadingDeg, "rail_heading_deg", "deg"),
    (Param::AirBrakesTargetM, "air_brakes_target_apogee_m", "m"),
    (Param::LaunchTimeH, "launch_time_h", "h"),
    (Param::WeatherMember, "weather_member", "1"),
];

/// The rule a value of an input must obey.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Domain {
    Finite,
    Positive,
    NonNegative,
    /// At least this much.
    AtLeast(f64),
    /// Above `lo` and at most `hi`.
    Within(f64, f64),
    /// From `lo` to `hi`, both included.
    Between(f64, f64),
}

impl Domain {
    /// `Ok` if `v` obeys the rule, else the rule in words.
    pub fn check(&self, v: f64) -> Result<(), String> {
        let ok = v.is_finite()
            && match *self {
                Domain::Finite => true,
                Domain::Positive => v > 0.0,
                Domain::NonNegative => v >= 0.0,
                Domain::AtLeast(lo) => v >= lo,
                Domain::Within(lo, hi) => v > lo && v <= hi,
                Domain::Between(lo, hi) => (lo..=hi).contains(&v),
            };
        if ok {
            Ok(())
        } else {
            Err(match *self {
                Domain::Finite => format!("must be finite (got {v})"),
                Domain::Positive => format!("must be positive and finite (got {v})"),
                Domain::NonNegative => format!("must be finite and not negative (got {v})"),
                Domain::AtLeast(lo) => format!("must be at least {lo} (got {v})"),
                Domain::Within(lo, hi) => format!("must be above {lo} and at most {hi} (got {v})"),
                Domain::Between(lo, hi) => format!("must be from {lo} to {hi} (got {v})"),
            })
        }
    }
}

impl Param {
    /// Unit of the input's values ("1" for a pure number).
    pub fn unit(&self) -> &'static str {
        match self {
            Param::ParachuteCdsM2(_) | Param::ReleaseCdaM2(_) | Param::ReleaseChuteCdsM2(_) => "m²",
            Param::ParachuteLagS(_) | Param::ShiftDurationS(_) | Param::ReleaseChuteLagS(_) => "s",
            Param::ShiftTravelM(_) => "m",
            Param::ParachuteTrigger(_) | Param::ShiftTrigger(_) | Param::ReleaseTrigger(_) => "",
            p => GLOBAL.iter().find(|g| g.0 == *p).map_or("", |g| g.2),
        }
    }

    /// The values a flight accepts. The trigger numbers are checked by their trigger.
    pub fn domain(&self) -> Domain {
        match self {
            Param::StructureMassKg
            | Param::MotorImpulseNs
            | Param::MotorBurnTimeS
            | Param::DragScale
            | Param::RailLengthM
            | Param::AirBrakesTargetM => Domain::Positive,
            // A ballast's mass scales its mass distribution, which needs a mass to scale.
            Param::BallastKg => Domain::Positive,
            Param::WindSpeedMS | Param::WindScale | Param::ParachuteLagS(_) => Domain::NonNegative,
            Param::ParachuteCdsM2(_) => Domain::Positive,
            Param::StructureCgM
            | Param::ElevationM
            | Param::WindFromDeg
            | Param::WindRotationDeg
            | Param::RailHeadingDeg
            | Param::LaunchTimeH
            | Param::ShiftTravelM(_) => Domain::Finite,
            Param::WeatherMember => Domain::NonNegative,
            Param::RailInclinationDeg => Domain::Within(0.0, 90.0),
            Param::WindTurbulenceIntensity => {
                Domain::Between(0.0, hpr_sim::turbulence::MAX_TURBULENCE_INTENSITY)
            }
            // The site's air, as `environment.temperature_k` and `pressure_pa` take it.
            Param::TemperatureK => {
                Domain::Between(SITE_TEMPERATURE_RANGE_K.0, SITE_TEMPERATURE_RANGE_K.1)
            }
            Param::PressurePa => {
                Domain::Between(SITE_PRESSURE_RANGE_PA.0, SITE_PRESSURE_RANGE_PA.1)
            }
            Param::ShiftDurationS(_) => Domain::AtLeast(0.01),
            Param::ParachuteTrigger(_) => Domain::NonNegative,
            Param::ShiftTrigger(_) => Domain::NonNegative,
            Param::ReleaseTrigger(_) | Param::ReleaseChuteLagS(_) => Domain::NonNegative,
            Param::ReleaseCdaM2(_) | Param::ReleaseChuteCdsM2(_) => Domain::Positive,
        }
    }

    /// The global input with this key, if any.
    pub fn global(key: &str) -> Option<Param> {
        GLOBAL.iter().find(|g| g.1 == key).map(|g| g.0)
    }

    /// The key of a global input (`None` for parachute, shift and release inputs, whose key
    /// needs their names: see `Scenario::key`).
    pub fn global_key(&self) -> Option<&'static str> {
        GLOBAL.iter().find(|g| g.0 == *self).map(|g| g.1)
    }
}

/// Unit of a trigger's number by its field name.
pub fn trigger_unit(field: &str) -> &'static str {
    match field {
        "height_m" => "m",
        _ => "s",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_global_input_has_a_unit_and_a_key_that_ends_in_it() {
        for (p, key, unit) in GLOBAL {
            assert_eq!(p.unit(), unit);
            assert_eq!(Param::global(key), Some(p));
            let suffix = match unit {
                "kg" => "_kg",
                "m" => "_m",
                "N·s" => "_ns",
                "s" => "_s",
                "m/s" => "_m_s",
                "deg" => "_deg",
                "K" => "_k",
                "Pa" => "_pa",
                "h" => "_h",
                _ => "",
            };
            assert!(key.ends_with(suffix), "{key} should end in {suffix}");
        }
    }

    #[test]
    fn domains_say_the_rule_a_value_breaks() {
        assert_eq!(
            Param::ParachuteCdsM2(0).domain().check(-1.0),
            Err("must be positive and finite (got -1)".into())
        );
        assert!(Param::RailInclinationDeg.domain().check(90.0).is_ok());
        assert!(Param::RailInclinationDeg.domain().check(0.0).is_err());
        assert_eq!(
            Param::ShiftDurationS(0).domain().check(0.005),
            Err("must be at least 0.01 (got 0.005)".into())
        );
        assert!(Param::WindSpeedMS.domain().check(f64::NAN).is_err());
        assert_eq!(
            Param::BallastKg.domain().check(0.0),
            Err("must be positive and finite (got 0)".into())
        );
        assert!(Param::TemperatureK.domain().check(150.0).is_ok());
        assert!(Param::TemperatureK.domain().check(350.0).is_ok());
        assert_eq!(
            Param::TemperatureK.domain().check(400.0),
            Err("must be from 150 to 350 (got 400)".into())
        );
        assert!(Param::PressurePa.domain().check(9_999.0).is_err());
    }
}
