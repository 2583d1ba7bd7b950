//! The inputs of a flight that a campaign sweeps or disperses and a batch varies lane by lane,
//! described once: each [`Input`]'s key (as a scenario file writes it), unit, the values a
//! flight accepts ([`Domain`]), and how a value is applied to a flight
//! ([`Changes::set`](crate::flight::changes::Changes::set), which the single flight's changes
//! and the batch's lanes both use).
//!
//! A value is what the scenario writes (a structure's mass in kg, a motor's impulse in N·s, a
//! launch time in hours after the weather file's time); what the flight makes of it (a change
//! of the structure's mass from the design's, a scale of the thrust curve, a time since 1970)
//! is worked out where it is applied, against the flight's own design, motor and weather.
//!
//! Adding an input is one entry: its variant of [`Input`], its row of [`GLOBAL`] (key, unit,
//! rule), and its line where [`Changes::apply_inputs`](crate::flight::changes::Changes) reads
//! it.
//!
//! Two inputs change more than the flight's light model: the motor (a number in a list of
//! motors, for a sweep over motors) and a design's dimension (whose design is validated
//! again and whose tables are built again, or taken from those built for a sweep point).

use crate::atmosphere::{SITE_PRESSURE_RANGE_PA, SITE_TEMPERATURE_RANGE_K};
use crate::turbulence::MAX_TURBULENCE_INTENSITY;

/// One input of a flight. Parachutes, shifts and releases are numbered in the order the flight
/// holds them. The order of the variants is the canonical order of a campaign's inputs (its
/// output columns and its sweep's axes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Input {
    /// Mass of the rocket without its motor, kg (nominal: the design's, ballast included).
    StructureMassKg,
    /// Center of mass of the rocket without its motor, m aft of the nose tip.
    StructureCgM,
    /// Mass of the batch's named part (a campaign's ballast), kg.
    BallastKg,
    /// Total impulse of the motor, N·s (nominal: its thrust curve's).
    MotorImpulseNs,
    /// Burn time of the motor, s (nominal: its thrust curve's).
    MotorBurnTimeS,
    /// Multiplier of the drag coefficient (nominal 1).
    DragScale,
    /// Launch site elevation above sea level, m.
    ElevationM,
    /// The site's air temperature, K.
    TemperatureK,
    /// The site's air pressure, Pa.
    PressurePa,
    /// A constant wind's speed, m/s.
    WindSpeedMS,
    /// Direction a constant wind blows from, degrees clockwise from north.
    WindFromDeg,
    /// Multiplier of every speed of the wind (nominal 1).
    WindScale,
    /// Clockwise turn of every direction of the wind, degrees (nominal 0).
    WindRotationDeg,
    /// The wind's turbulence intensity.
    WindTurbulenceIntensity,
    RailLengthM,
    RailInclinationDeg,
    RailHeadingDeg,
    /// The air brakes' target apogee, m above the site.
    AirBrakesTargetM,
    /// The launch time, hours after the weather file's time (nominal 0): the air and the wind
    /// are the weather file's then.
    LaunchTimeH,
    /// The weather file's ensemble member, by the file's number.
    WeatherMember,
    /// The motor, by its number in the batch's list of motors ([`InputContext::motors`](crate::flight::changes::InputContext::motors)).
    Motor,
    /// The motor's casing (dry) mass, kg (each motor's, for a cluster).
    MotorDryMassKg,
    /// A dimension of the design, by its number in the batch's list
    /// ([`BatchDesigns::dimensions`](crate::batch::BatchDesigns)): a component's field
    /// (`design.fins.span_m`), whose change rebuilds the design's tables.
    Design(usize),
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

/// What describes an input: its key as a scenario writes it (for an input of a parachute,
/// a shift or a release, the field within that part's table), its unit ("1" for a pure
/// number, "" for a trigger's number, whose unit is its trigger's) and its rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct About {
    pub key: &'static str,
    pub unit: &'static str,
    pub domain: Domain,
}

const fn about(key: &'static str, unit: &'static str, domain: Domain) -> About {
    About { key, unit, domain }
}

/// Number of inputs of the flight as a whole (not of a parachute, shift or release).
pub const GLOBAL_COUNT: usize = 22;

/// The inputs of the flight as a whole, in canonical order, each with its description.
pub const GLOBAL: [(Input, About); GLOBAL_COUNT] = {
    use Domain::*;
    use Input::*;
    [
        (StructureMassKg, about("structure_mass_kg", "kg", Positive)),
        (StructureCgM, about("structure_cg_m", "m", Finite)),
        // A ballast's mass scales its mass distribution, which needs a mass to scale.
        (BallastKg, about("ballast_kg", "kg", Positive)),
        (MotorImpulseNs, about("motor_impulse_ns", "N·s", Positive)),
        (MotorBurnTimeS, about("motor_burn_time_s", "s", Positive)),
        (DragScale, about("drag_scale", "1", Positive)),
        (ElevationM, about("elevation_m", "m", Finite)),
        // The site's air, as a scenario's `environment.temperature_k` and `pressure_pa`.
        (
            TemperatureK,
            about(
                "temperature_k",
                "K",
                Between(SITE_TEMPERATURE_RANGE_K.0, SITE_TEMPERATURE_RANGE_K.1),
            ),
        ),
        (
            PressurePa,
            about(
                "pressure_pa",
                "Pa",
                Between(SITE_PRESSURE_RANGE_PA.0, SITE_PRESSURE_RANGE_PA.1),
            ),
        ),
        (WindSpeedMS, about("wind_speed_m_s", "m/s", NonNegative)),
        (WindFromDeg, about("wind_from_deg", "deg", Finite)),
        (WindScale, about("wind_scale", "1", NonNegative)),
        (WindRotationDeg, about("wind_rotation_deg", "deg", Finite)),
        (
            WindTurbulenceIntensity,
            about(
                "wind_turbulence_intensity",
                "1",
                Between(0.0, MAX_TURBULENCE_INTENSITY),
            ),
        ),
        (RailLengthM, about("rail_length_m", "m", Positive)),
        (
            RailInclinationDeg,
            about("rail_inclination_deg", "deg", Within(0.0, 90.0)),
        ),
        (RailHeadingDeg, about("rail_heading_deg", "deg", Finite)),
        (
            AirBrakesTargetM,
            about("air_brakes_target_apogee_m", "m", Positive),
        ),
        (LaunchTimeH, about("launch_time_h", "h", Finite)),
        (WeatherMember, about("weather_member", "1", NonNegative)),
        (Motor, about("motor", "1", NonNegative)),
        (MotorDryMassKg, about("motor_dry_mass_kg", "kg", Positive)),
    ]
};

/// The kinds of part whose inputs are numbered: a parachute, a shift, a release.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Part {
    Parachute,
    Shift,
    Release,
}

impl Part {
    /// The inputs of one part of this kind, in canonical order: (field, description,
    /// the input of part `k`). A trigger's field is `trigger` (its number's own name is its
    /// trigger's: `time_s`, `height_m`, `delay_s`).
    pub fn fields(&self) -> &'static [(About, fn(usize) -> Input)] {
        match self {
            Part::Parachute => &PARACHUTE_FIELDS,
            Part::Shift => &SHIFT_FIELDS,
            Part::Release => &RELEASE_FIELDS,
        }
    }
}

static PARACHUTE_FIELDS: [(About, fn(usize) -> Input); 3] = [
    (
        about("cds_m2", "m²", Domain::Positive),
        Input::ParachuteCdsM2,
    ),
    (
        about("lag_s", "s", Domain::NonNegative),
        Input::ParachuteLagS,
    ),
    (
        about("trigger", "", Domain::NonNegative),
        Input::ParachuteTrigger,
    ),
];

static SHIFT_FIELDS: [(About, fn(usize) -> Input); 3] = [
    (about("travel_m", "m", Domain::Finite), Input::ShiftTravelM),
    (
        about("duration_s", "s", Domain::AtLeast(0.01)),
        Input::ShiftDurationS,
    ),
    (
        about("trigger", "", Domain::NonNegative),
        Input::ShiftTrigger,
    ),
];

static RELEASE_FIELDS: [(About, fn(usize) -> Input); 4] = [
    (
        about("trigger", "", Domain::NonNegative),
        Input::ReleaseTrigger,
    ),
    (about("cda_m2", "m²", Domain::Positive), Input::ReleaseCdaM2),
    (
        about("parachute_cds_m2", "m²", Domain::Positive),
        Input::ReleaseChuteCdsM2,
    ),
    (
        about("parachute_lag_s", "s", Domain::NonNegative),
        Input::ReleaseChuteLagS,
    ),
];

/// Where an input's value is held: `Global(i)` the `i`-th of [`GLOBAL`], or `Part(kind, k,
/// f)` field `f` of [`Part::fields`] of the kind's `k`-th part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    Global(usize),
    Design(usize),
    Part(Part, usize, usize),
}

impl Input {
    /// Where the input's value is held.
    pub fn slot(&self) -> Slot {
        use Input::*;
        let part = |kind: Part, k: usize, f: usize| Slot::Part(kind, k, f);
        match *self {
            ParachuteCdsM2(k) => part(Part::Parachute, k, 0),
            ParachuteLagS(k) => part(Part::Parachute, k, 1),
            ParachuteTrigger(k) => part(Part::Parachute, k, 2),
            ShiftTravelM(k) => part(Part::Shift, k, 0),
            ShiftDurationS(k) => part(Part::Shift, k, 1),
            ShiftTrigger(k) => part(Part::Shift, k, 2),
            ReleaseTrigger(k) => part(Part::Release, k, 0),
            ReleaseCdaM2(k) => part(Part::Release, k, 1),
            ReleaseChuteCdsM2(k) => part(Part::Release, k, 2),
            ReleaseChuteLagS(k) => part(Part::Release, k, 3),
            Design(k) => Slot::Design(k),
            global => Slot::Global(
                GLOBAL
                    .iter()
                    .position(|g| g.0 == global)
                    .expect("every input of the flight as a whole is in GLOBAL"),
            ),
        }
    }

    /// The input's description.
    pub fn about(&self) -> About {
        match self.slot() {
            Slot::Global(i) => GLOBAL[i].1,
            // The design's own rules judge a dimension's value.
            Slot::Design(_) => about("design", "", Domain::Finite),
            Slot::Part(kind, _, f) => kind.fields()[f].0,
        }
    }

    /// The values a flight accepts (a trigger's number is checked by its trigger too).
    pub fn domain(&self) -> Domain {
        self.about().domain
    }

    /// Unit of the input's values ("1" for a pure number, "" for a trigger's number).
    pub fn unit(&self) -> &'static str {
        self.about().unit
    }

    /// The input of the flight as a whole with this key, if any.
    pub fn global(key: &str) -> Option<Input> {
        GLOBAL.iter().find(|g| g.1.key == key).map(|g| g.0)
    }

    /// The key of an input of the flight as a whole (`None` for a parachute's, a shift's or
    /// a release's, whose key needs the part's name).
    pub fn global_key(&self) -> Option<&'static str> {
        match self.slot() {
            Slot::Global(i) => Some(GLOBAL[i].1.key),
            Slot::Design(_) | Slot::Part(..) => None,
        }
    }

    /// The input's name in messages: its key for an input of the flight as a whole
    /// (`drag_scale`), else its part's list, number and field (`parachutes[1].lag_s`).
    pub fn name(&self) -> String {
        match self.slot() {
            Slot::Global(i) => GLOBAL[i].1.key.to_string(),
            Slot::Design(k) => format!("design dimension {k}"),
            Slot::Part(kind, k, f) => {
                let list = match kind {
                    Part::Parachute => "parachutes",
                    Part::Shift => "shifts",
                    Part::Release => "releases",
                };
                format!("{list}[{k}].{}", kind.fields()[f].0.key)
            }
        }
    }

    /// The part the input belongs to and its number, for a parachute's, shift's or
    /// release's.
    pub fn part(&self) -> Option<(Part, usize)> {
        match self.slot() {
            Slot::Global(_) | Slot::Design(_) => None,
            Slot::Part(kind, k, _) => Some((kind, k)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_global_input_has_a_unit_and_a_key_that_ends_in_it() {
        for (p, about) in GLOBAL {
            assert_eq!(p.unit(), about.unit);
            assert_eq!(Input::global(about.key), Some(p));
            let suffix = match about.unit {
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
            assert!(
                about.key.ends_with(suffix),
                "{} should end in {suffix}",
                about.key
            );
        }
    }

    #[test]
    fn the_global_inputs_are_listed_in_their_canonical_order() {
        assert!(GLOBAL.windows(2).all(|w| w[0].0 < w[1].0));
        assert!(GLOBAL[GLOBAL_COUNT - 1].0 < Input::ParachuteCdsM2(0));
    }

    #[test]
    fn every_part_input_is_held_in_its_own_field() {
        for kind in [Part::Parachute, Part::Shift, Part::Release] {
            for (f, (_, input)) in kind.fields().iter().enumerate() {
                assert_eq!(input(3).slot(), Slot::Part(kind, 3, f));
            }
        }
    }

    #[test]
    fn domains_say_the_rule_a_value_breaks() {
        assert_eq!(
            Input::ParachuteCdsM2(0).domain().check(-1.0),
            Err("must be positive and finite (got -1)".into())
        );
        assert!(Input::RailInclinationDeg.domain().check(90.0).is_ok());
        assert!(Input::RailInclinationDeg.domain().check(0.0).is_err());
        assert_eq!(
            Input::ShiftDurationS(0).domain().check(0.005),
            Err("must be at least 0.01 (got 0.005)".into())
        );
        assert!(Input::WindSpeedMS.domain().check(f64::NAN).is_err());
        assert_eq!(
            Input::BallastKg.domain().check(0.0),
            Err("must be positive and finite (got 0)".into())
        );
        assert!(Input::TemperatureK.domain().check(150.0).is_ok());
        assert!(Input::TemperatureK.domain().check(350.0).is_ok());
        assert_eq!(
            Input::TemperatureK.domain().check(400.0),
            Err("must be from 150 to 350 (got 400)".into())
        );
        assert!(Input::PressurePa.domain().check(9_999.0).is_err());
    }
}
