//! Why a flight could not be set up: [`SetupError`], one variant per rule a flight's inputs
//! can break (a parachute's number out of its range, too many shifts, a rail that leans
//! below the horizon, a part mass that cannot change), each carrying what it names: the input,
//! its index, the value given and the bound broken. A caller matches on the variant and reads
//! its fields; the message (`Display`) is the words a user reads, the same whatever the path
//! (a `with_*` builder, [`super::Changes`], a batch's lane).

use crate::atmosphere::AtmosphereError;
use crate::gravity::{GravityError, LATITUDE_RULE};
use crate::trigger::{Trigger, TriggerError};
use crate::weather::WeatherError;
use crate::wind::WindError;
use hpr_design::DesignError;
use std::fmt;

/// A rule a single number of a flight's input breaks (shown as "must be ...").
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// `> 0` and finite.
    PositiveFinite,
    /// `>= 0` and finite.
    FiniteNotNegative,
    /// Finite.
    Finite,
    /// `> 0` and at most `max` (in `unit`).
    PositiveAtMost { max: f64, unit: &'static str },
    /// Above 0 and at most 90 degrees (an inclination above the horizon).
    AboveZeroAtMost90Deg,
}

impl fmt::Display for Bound {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Bound::PositiveFinite => f.write_str("must be positive and finite"),
            Bound::FiniteNotNegative => f.write_str("must be finite and not negative"),
            Bound::Finite => f.write_str("must be finite"),
            Bound::PositiveAtMost { max, unit } => {
                write!(f, "must be positive, at most {max} {unit}")
            }
            Bound::AboveZeroAtMost90Deg => f.write_str("must be above 0 and at most 90 degrees"),
        }
    }
}

/// Which rule a parachute's input breaks ([`SetupError::Parachute`]).
#[derive(Debug, Clone, PartialEq)]
pub enum ParachuteRule {
    /// A number of the parachute's own (`cds_m2`, `lag_s`, `sampling_rate_hz`) out of bounds.
    Field {
        field: &'static str,
        bound: Bound,
        got: f64,
    },
    /// A number of its pressure sensor's noise out of bounds.
    Noise {
        field: &'static str,
        rule: &'static str,
        got: f64,
    },
    /// A noisy sensor with no sampling rate.
    NoiseWithoutSampling,
    /// A number of its canopy's shape (the canopy's own words for the rule).
    Canopy { field: &'static str, rule: String },
    /// Its trigger's own number out of bounds.
    Trigger(TriggerError),
    /// A height trigger at or below the ground.
    NeverOpens { trigger: Trigger },
    /// A trigger on the motor's ejection delay, with a plugged motor.
    PluggedMotor { trigger: Trigger },
}

impl fmt::Display for ParachuteRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParachuteRule::Field { field, bound, got } => {
                write!(f, "field \"{field}\" {bound} (got {got})")
            }
            ParachuteRule::Noise { field, rule, got } => {
                write!(f, "noise field \"{field}\" {rule} (got {got})")
            }
            ParachuteRule::NoiseWithoutSampling => f.write_str("a noisy pressure is read at samples: field \"sampling_rate_hz\" is needed with \"noise\" (RocketPy's default is 100 Hz)"),
            ParachuteRule::Canopy { field, rule } => write!(f, "canopy field \"{field}\" {rule}"),
            ParachuteRule::Trigger(e) => write!(f, "{e}"),
            ParachuteRule::NeverOpens { trigger } => write!(
                f,
                "trigger {trigger}: the height must be above the ground, or the canopy never opens"
            ),
            ParachuteRule::PluggedMotor { trigger } => write!(
                f,
                "trigger {trigger}: the motor is plugged (no ejection delay), so this trigger never fires"
            ),
        }
    }
}

/// Which rule a new mass of a part breaks ([`SetupError::PartMass`]).
#[derive(Debug, Clone, PartialEq)]
pub enum PartMassRule {
    NoSuchComponent,
    /// The mass given is not positive and finite.
    Mass {
        got_kg: f64,
    },
    /// A body tube, nose or fin set: only an internal part's mass changes this way.
    NotInternal,
    /// A mass override hides the part's own mass.
    HiddenByOverride,
    /// The part weighs nothing (or not a finite mass) in the design: nothing to scale.
    NothingToScale {
        own_kg: f64,
    },
}

impl fmt::Display for PartMassRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PartMassRule::NoSuchComponent => f.write_str("the design has no such component"),
            PartMassRule::Mass { got_kg } => {
                write!(f, "mass_kg must be positive and finite (got {got_kg})")
            }
            PartMassRule::NotInternal => f.write_str("only an internal part's mass can change this way"),
            PartMassRule::HiddenByOverride => {
                f.write_str("a mass override (its own, its stage's or a holder's) hides its mass")
            }
            PartMassRule::NothingToScale { own_kg } => write!(
                f,
                "it weighs {own_kg} kg in the design, so it has no mass to scale; give it a mass in the design"
            ),
        }
    }
}

/// Which rule a numeric option of the integrator breaks ([`SetupError::Options`]).
#[derive(Debug, Clone, PartialEq)]
pub enum OptionsRule {
    /// Not positive and finite.
    NotPositive { got: f64 },
    /// RK4's step takes more steps to the time limit than a flight may (the rule's words,
    /// with the numbers).
    TooManySteps { rule: String },
    /// The relative tolerance outside `[min, max]`.
    Rtol { got: f64, min: f64, max: f64 },
}

/// The owner of a trigger whose number an input sets ([`SetupError::TriggerHasNoNumber`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TriggerOwner {
    Parachute,
    Shift,
    Release,
}

impl fmt::Display for TriggerOwner {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            TriggerOwner::Parachute => "parachute",
            TriggerOwner::Shift => "shift",
            TriggerOwner::Release => "release",
        })
    }
}

/// What a launch site's part refused (its air, gravity, wind or weather), with its own error.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SiteFault {
    #[error(transparent)]
    Atmosphere(#[from] AtmosphereError),
    #[error(transparent)]
    Gravity(#[from] GravityError),
    #[error(transparent)]
    Wind(#[from] WindError),
    #[error(transparent)]
    Weather(#[from] WeatherError),
}

/// Why a flight's inputs could not be set up: the rule broken, with the input, its index, the
/// value and the bound (see the module's doc).
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// Parachute `index` (named `name`) breaks `rule`.
    #[error("parachute {index} (\"{name}\"): {rule}")]
    Parachute {
        index: usize,
        name: String,
        rule: ParachuteRule,
    },
    #[error("at most {max} shifts in one flight (got {got})")]
    TooManyShifts { max: usize, got: usize },
    #[error("at most {max} parts may move in one flight (got {got})")]
    TooManyMovingParts { max: usize, got: usize },
    #[error("at most {max} releases in one flight (got {got})")]
    TooManyReleases { max: usize, got: usize },
    #[error("at most {max} shifts and releases together in one flight (got {shifts} shifts and {releases} releases)")]
    TooManyShiftsAndReleases {
        max: usize,
        shifts: usize,
        releases: usize,
    },
    /// An option of the integrator (`max_time_s`, `step_s`, `rtol`, `atol_*`).
    #[error("options: field \"{field}\"{}", options_rule(.rule))]
    Options {
        field: &'static str,
        rule: OptionsRule,
    },
    /// A part's new mass ([`super::Simulation::with_part_mass`]) refused.
    #[error("part mass of \"{component}\": {rule}")]
    PartMass {
        component: String,
        rule: PartMassRule,
    },
    #[error("drag scale must be positive and finite (got {got})")]
    DragScale { got: f64 },
    #[error("design \"{design}\" has no air brakes to aim")]
    NoAirBrakes { design: String },
    #[error("air brakes: the target apogee must be positive and finite (got {got_m})")]
    AirBrakesTarget { got_m: f64 },
    /// The structure's change of mass and center is not finite or leaves no mass.
    #[error("mass adjustment: delta_mass_kg {delta_mass_kg} and delta_cg_m {delta_cg_m} must be finite and leave a positive mass (structure {structure_kg} kg)")]
    MassAdjustment {
        delta_mass_kg: f64,
        delta_cg_m: f64,
        structure_kg: f64,
    },
    /// The structure less the parts its shifts move or releases drop would be left without
    /// mass by the change.
    #[error("mass adjustment: the structure without the parts its shifts move weighs {rest_kg} kg, and {after_kg} kg after the change of {delta_mass_kg} kg: nothing is left to make the change")]
    MassAdjustmentHeld {
        rest_kg: f64,
        after_kg: f64,
        delta_mass_kg: f64,
    },
    /// A number of the rail out of bounds.
    #[error("rail: field \"{field}\" {bound} (got {got})")]
    Rail {
        field: &'static str,
        bound: Bound,
        got: f64,
    },
    /// The rail is no longer than the rocket's aft end to its upper guide.
    #[error("rail: field \"length_m\" must be longer than the distance from the rocket's aft end to its upper rail guide ({guide_height_m:.3} m), or the rocket never rides it (got {length_m} m)")]
    RailTooShort { guide_height_m: f64, length_m: f64 },
    /// The site's latitude out of its range.
    #[error("environment: field \"latitude_deg\" {LATITUDE_RULE} (got {got})")]
    Latitude { got: f64 },
    /// The gravity model at the site's latitude with no latitude (`key` names the setting).
    #[error("\"somigliana\" is the gravity at the site's latitude: give {key}")]
    NoLatitude { key: String },
    /// The site's air or gravity refused.
    #[error("environment: {0}")]
    Environment(SiteFault),
    /// The weather file's air or wind at the site refused.
    #[error("weather: {0}")]
    Weather(SiteFault),
    /// A constant wind's speed or direction refused.
    #[error("wind: {0}")]
    Wind(WindError),
    /// The site's air, gravity, wind or weather refused, in its own words.
    #[error("{0}")]
    Site(SiteFault),
    /// A turbulent wind's gusts are drawn to the time limit, which is too far.
    #[error("a flight in a turbulent wind needs a time limit (max_time_s) of at most {max_s} s, its gusts drawn to it before it starts (got {got_s} s)")]
    TurbulentTimeLimit { max_s: f64, got_s: f64 },
    /// A sampler (air brakes, a sampled trigger) would take more samples than a flight's steps.
    #[error("a sampler read {rate_hz} times a second to the time limit (max_time_s = {max_time_s} s) takes {:.4e} samples, each ending a step, more than the {max_steps:.0} a flight may take: give a time limit of at most {} s, or a lower sampling rate", rate_hz * max_time_s, max_steps / rate_hz)]
    TooManySamples {
        rate_hz: f64,
        max_time_s: f64,
        max_steps: f64,
    },
    #[error("design \"{design}\": it has no motor mount (an inner tube with \"motor_mount\")")]
    NoMotorMount { design: String },
    /// A changed design dimension breaks a rule of the design.
    #[error("{0}")]
    Design(DesignError),
    /// A design dimension's number not among the batch's.
    #[error("design dimension {index}: the batch has {count}")]
    NoSuchDimension { index: usize, count: usize },
    /// Design dimensions set with no designs to build them from.
    #[error("the design's dimensions need the batch's designs")]
    NoDesigns,
    /// A motor's number not among the batch's motors (`index` as the column holds it).
    #[error("motor {index}: the batch has {count} motors")]
    NoSuchMotor { index: f64, count: usize },
    /// A launch time or weather member set with no weather file.
    #[error("the launch time and weather member columns need the batch's weather file")]
    NoWeather,
    /// A wind speed or direction set on a wind given as a table.
    #[error("the base wind is a table, whose speed and direction the wind columns can't set (scale and turn it with wind_scale and wind_rotation_deg)")]
    WindIsATable,
    /// A number set on a trigger that has none (apogee, burnout).
    #[error("{owner} {index}: trigger {trigger} has no number to vary")]
    TriggerHasNoNumber {
        owner: TriggerOwner,
        index: usize,
        trigger: Trigger,
    },
    /// A release's parachute numbers set on a release without one.
    #[error("release {index}: its part has no parachute to vary")]
    ReleaseWithoutChute { index: usize },
}

fn options_rule(rule: &OptionsRule) -> String {
    match rule {
        OptionsRule::NotPositive { got } => format!(" must be positive and finite (got {got})"),
        OptionsRule::TooManySteps { rule } => format!(": {rule}"),
        OptionsRule::Rtol { got, min, max } => {
            format!(" must be finite and within [{min:e}, {max}] (got {got})")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flight::{Parachute, SimError, Simulation};
    use crate::inputs::Input;
    use crate::reference;

    /// The refusal of the changes `f` makes to the reference rocket.
    fn refused(
        f: impl FnOnce(&mut crate::flight::Changes<'_>) -> Result<(), SimError>,
    ) -> SetupError {
        match reference::simulation().with_changes(f) {
            Err(SimError::Setup(e)) => e,
            Err(e) => panic!("refused, but not as a set-up: {e}"),
            Ok(_) => panic!("the changes were accepted"),
        }
    }

    #[test]
    fn a_parachute_s_negative_lag_is_refused_naming_its_index_name_field_bound_and_value() {
        let chute = Parachute::new("main", 1.2, Trigger::Apogee, -0.5);
        let e = refused(|c| {
            c.parachutes(vec![
                Parachute::new("drogue", 0.3, Trigger::Apogee, 0.0),
                chute,
            ])
        });
        match &e {
            SetupError::Parachute {
                index: 1,
                name,
                rule:
                    ParachuteRule::Field {
                        field: "lag_s",
                        bound: Bound::FiniteNotNegative,
                        got,
                    },
            } => {
                assert_eq!(name, "main");
                assert_eq!(*got, -0.5);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            e.to_string(),
            "parachute 1 (\"main\"): field \"lag_s\" must be finite and not negative (got -0.5)"
        );
    }

    #[test]
    fn an_input_out_of_range_set_through_the_inputs_is_the_same_typed_refusal_as_its_builder_s() {
        // The drag scale set as an input (a batch's lane, a sweep's point) and by its builder.
        let by_input = refused(|c| {
            c.set(Input::DragScale, -2.0);
            Ok(())
        });
        let by_builder = refused(|c| c.drag_scale(-2.0));
        for e in [&by_input, &by_builder] {
            assert!(
                matches!(e, SetupError::DragScale { got } if *got == -2.0),
                "{e:?}"
            );
            assert_eq!(
                e.to_string(),
                "drag scale must be positive and finite (got -2)"
            );
        }
        // The rail's inclination, through the rebuild's check of the rail.
        let e = refused(|c| {
            c.set(Input::RailInclinationDeg, 95.0);
            Ok(())
        });
        assert!(
            matches!(
                e,
                SetupError::Rail {
                    field: "inclination_deg",
                    bound: Bound::AboveZeroAtMost90Deg,
                    got
                } if got == 95.0
            ),
            "{e:?}"
        );
        assert_eq!(
            e.to_string(),
            "rail: field \"inclination_deg\" must be above 0 and at most 90 degrees (got 95)"
        );
    }

    #[test]
    fn a_part_mass_and_a_structure_change_are_refused_with_their_numbers() {
        let e = refused(|c| c.part_mass(reference::BALLAST, f64::NAN));
        assert!(
            matches!(&e, SetupError::PartMass { component, rule: PartMassRule::Mass { got_kg } }
                if component == reference::BALLAST && got_kg.is_nan()),
            "{e:?}"
        );
        assert_eq!(
            e.to_string(),
            "part mass of \"ballast\": mass_kg must be positive and finite (got NaN)"
        );
        let e = refused(|c| c.part_mass("no_such_part", 0.1));
        assert!(
            matches!(
                &e,
                SetupError::PartMass {
                    rule: PartMassRule::NoSuchComponent,
                    ..
                }
            ),
            "{e:?}"
        );
        assert_eq!(
            e.to_string(),
            "part mass of \"no_such_part\": the design has no such component"
        );
        // Taking 1000 kg from the structure leaves no mass: the structure's own mass is in
        // the error, as the design's dry mass (`mass::dry`) gives it.
        let dry_kg = hpr_design::mass::dry(&reference::design()).mass_kg;
        let e = refused(|c| c.mass_adjustment(-1000.0, 0.0));
        match e {
            SetupError::MassAdjustment {
                delta_mass_kg,
                delta_cg_m,
                structure_kg,
            } => {
                assert_eq!((delta_mass_kg, delta_cg_m), (-1000.0, 0.0));
                assert_eq!(structure_kg, dry_kg);
            }
            ref other => panic!("{other:?}"),
        }
        assert_eq!(
            e.to_string(),
            format!("mass adjustment: delta_mass_kg -1000 and delta_cg_m 0 must be finite and leave a positive mass (structure {dry_kg} kg)")
        );
    }

    #[test]
    fn a_number_set_on_an_apogee_trigger_names_the_owner_its_index_and_the_trigger() {
        let sim = reference::simulation()
            .with_parachutes(vec![Parachute::new("main", 1.2, Trigger::Apogee, 0.0)])
            .unwrap();
        let e = match sim.with_changes(|c| {
            c.set(Input::ParachuteTrigger(0), 300.0);
            Ok(())
        }) {
            Err(SimError::Setup(e)) => e,
            other => panic!("{other:?}"),
        };
        assert!(
            matches!(
                e,
                SetupError::TriggerHasNoNumber {
                    owner: TriggerOwner::Parachute,
                    index: 0,
                    trigger: Trigger::Apogee
                }
            ),
            "{e:?}"
        );
        assert_eq!(
            e.to_string(),
            "parachute 0: trigger apogee has no number to vary"
        );
        // A builder's too-short rail: the rail's length and the guide's height above the
        // aft end (the reference rocket's upper guide), to the millimetre.
        let e = match Simulation::new(
            reference::design(),
            reference::motor(),
            Default::default(),
            crate::flight::Rail {
                length_m: 0.01,
                ..Default::default()
            },
        ) {
            Err(SimError::Setup(e)) => e,
            other => panic!("{other:?}"),
        };
        let SetupError::RailTooShort {
            guide_height_m,
            length_m,
        } = e
        else {
            panic!("{e:?}")
        };
        assert_eq!(length_m, 0.01);
        // The aft end (the airframe's or the motor's, the further) less the upper guide's
        // station, as the design places them.
        let d = reference::design();
        let aft_m = d.length_m.max(d.motor_mount.unwrap().motor_aft_m);
        assert_eq!(guide_height_m, aft_m - d.rail_guides_m.unwrap().0);
        assert!(guide_height_m > 0.01, "{guide_height_m}");
        assert_eq!(
            e.to_string(),
            format!("rail: field \"length_m\" must be longer than the distance from the rocket's aft end to its upper rail guide ({guide_height_m:.3} m), or the rocket never rides it (got 0.01 m)")
        );
    }
}
