//! Flying variants: the base setup of a scenario ([`Prepared`]: design, motor, nominals,
//! checked once, and one base [`Simulation`] for the whole run), a chunk of variants turned
//! into the batch engine's columns, and flown as lanes of [`hpr_sim::batch`].
//!
//! [`fly_chunk`] is the one step that flies: it takes a chunk of variants and returns one
//! [`VariantResult`] per variant, in order. Every swept or dispersed input of a variant is a
//! column of the chunk (structure mass and center → the structure's deltas, ballast → the
//! part mass, motor impulse and burn time → scales of the nominal curve, drag scale, site,
//! wind, rail, and per parachute, shift or release its numbers), so one base flight, built once from
//! the first sweep point, serves every sweep point: a lane is that base with its row applied
//! in one rebuild of the light per-flight model, and the design's tables are never rebuilt.
//! A variant that can't fly is a result too, never an error of the run: `refused` (a sampled
//! value outside its range, or a setup the simulator refuses, such as a shift taking its part
//! out of its holder), `failed` (the flight stopped with an error, went non-finite, panicked
//! or ended without landing) or `time_limit` (cut by `integrator.max_time_s` before landing).
//! Only `landed` variants enter the statistics.

mod setup;
mod sharing;

use super::params::Param;
use super::scenario::{trigger_value, RequirementSpec, Scenario, ScenarioError};
use super::variants::{Plan, PlanInput, Variant};
use hpr_design::design::dimension::DesignSource;
use hpr_design::design::model::Design;
use hpr_design::mass;
use hpr_design::motor::{self, Motor, MotorError, MotorField, MotorTables};
use hpr_sim::batch::{
    Batch, BatchDesigns, BatchWeather, LaneResult, ParachuteOutcome, Prefix, PrefixStore,
    ReleaseOutcome, ShiftOutcome,
};
use hpr_sim::flight::Metrics;
use hpr_sim::{SimError, SimOptions, Simulation, Trigger};
use setup::{Fixed, Setup};
use sharing::{Sharing, SHARED_BEGINNINGS};

/// How many kinds of warning a flight can raise ([`hpr_sim::Warning::KEYS`]).
pub const WARNINGS: usize = hpr_sim::Warning::KEYS.len();

/// How a variant ended: the batch lane's status.
pub use hpr_sim::batch::Status;

/// A flown (or refused) variant: its status, the error text, and the value of every metric
/// (in [`Prepared::metrics`] order; `None` where a value does not exist).
#[derive(Debug, Clone, PartialEq)]
pub struct VariantResult {
    pub id: u64,
    pub status: Status,
    pub error: Option<String>,
    /// The flight's warnings ([`hpr_sim::Warning`]), `; `-separated; `None` if it has none.
    pub warnings: Option<String>,
    /// Whether the flight raised each warning of [`hpr_sim::Warning::KEYS`] (`None` if it
    /// was not flown).
    pub warned: Option<[bool; WARNINGS]>,
    pub metrics: Vec<Option<f64>>,
}

/// An output column: name (with its unit) and unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    pub name: String,
    pub unit: &'static str,
}

/// How a metric is read from a flight: its name, its unit and its value (`None` where it does
/// not exist).
pub type Metric<T> = (&'static str, &'static str, fn(&T) -> Option<f64>);

/// The landing point's distance from the rail's foot, m.
fn distance(p: Option<[f64; 2]>) -> Option<f64> {
    p.map(|p| p[0].hypot(p[1]))
}

/// The metrics every flight has, in output order.
pub const FIXED_METRICS: [Metric<Metrics>; 18] = [
    ("apogee_m", "m", |m| m.apogee_m),
    ("apogee_time_s", "s", |m| m.apogee_time_s),
    ("max_speed_m_s", "m/s", |m| Some(m.max_speed_m_s)),
    ("max_mach", "1", |m| Some(m.max_mach)),
    ("max_accel_m_s2", "m/s²", |m| Some(m.max_accel_m_s2)),
    ("max_dynamic_pressure_pa", "Pa", |m| {
        Some(m.max_dynamic_pressure_pa)
    }),
    ("rail_exit_speed_m_s", "m/s", |m| m.rail_exit_speed_m_s),
    ("static_margin_liftoff_cal", "cal", |m| {
        m.static_margin_liftoff_cal
    }),
    ("static_margin_rail_exit_cal", "cal", |m| {
        m.static_margin_rail_exit_cal
    }),
    ("static_margin_burnout_cal", "cal", |m| {
        m.static_margin_burnout_cal
    }),
    ("static_margin_min_cal", "cal", |m| m.static_margin_min_cal),
    ("flight_margin_min_cal", "cal", |m| m.flight_margin_min_cal),
    ("max_alpha_deg", "deg", |m| m.max_alpha_deg),
    ("landing_time_s", "s", |m| m.landing_time_s),
    ("landing_x_m", "m", |m| m.landing_position_m.map(|p| p[0])),
    ("landing_y_m", "m", |m| m.landing_position_m.map(|p| p[1])),
    ("landing_distance_m", "m", |m| {
        distance(m.landing_position_m)
    }),
    ("landing_speed_m_s", "m/s", |m| m.landing_speed_m_s),
];

/// The metrics of each shift (`shift_<name>_...`): its start time and the static margin just
/// before and just after its move.
const PER_SHIFT: [Metric<ShiftOutcome>; 3] = [
    ("start_time_s", "s", |s| s.start_s),
    ("margin_before_cal", "cal", |s| s.margin_before_cal),
    ("margin_after_cal", "cal", |s| s.margin_after_cal),
];

/// The metrics of each parachute (`parachute_<name>_...`): its opening time and speed.
const PER_PARACHUTE: [Metric<ParachuteOutcome>; 2] = [
    ("deploy_time_s", "s", |c| c.deploy_time_s),
    ("deploy_speed_m_s", "m/s", |c| c.deploy_speed_m_s),
];

/// The metrics of a design with air brakes: when they first opened and their widest opening.
const AIR_BRAKES: [Metric<Metrics>; 2] = [
    ("air_brakes_open_time_s", "s", |m| m.air_brakes_open_time_s),
    ("air_brakes_max_opening", "1", |m| m.air_brakes_max_opening),
];

/// The metrics of each release (`release_<name>_...`): when it fired, the static margin just
/// before and after, and the released part's landing; a part with a parachute has
/// `RELEASE_CHUTE` besides.
pub const PER_RELEASE: [Metric<ReleaseOutcome>; 8] = [
    ("fire_time_s", "s", |r| r.time_s),
    ("margin_before_cal", "cal", |r| r.margin_before_cal),
    ("margin_after_cal", "cal", |r| r.margin_after_cal),
    ("landing_time_s", "s", |r| r.landing_time_s),
    ("landing_x_m", "m", |r| r.landing_position_m.map(|p| p[0])),
    ("landing_y_m", "m", |r| r.landing_position_m.map(|p| p[1])),
    ("landing_distance_m", "m", |r| {
        distance(r.landing_position_m)
    }),
    ("landing_speed_m_s", "m/s", |r| r.landing_speed_m_s),
];

/// The metric of a released part with a parachute: when its canopy opened.
const RELEASE_CHUTE: Metric<ReleaseOutcome> = ("chute_open_time_s", "s", |r| r.chute_open_s);

/// A scenario ready to fly: the design and motor loaded, the nominals resolved, the plan of
/// the variants built, and every sweep point's nominal flight checked.
#[derive(Debug, Clone)]
pub struct Prepared {
    pub scenario: Scenario,
    pub plan: Plan,
    /// The output metrics: [`FIXED_METRICS`], then per shift its start time and the static
    /// margin just before and just after its move, then per parachute its opening time and
    /// speed, then, for a design with air brakes, when they first opened and their widest
    /// opening, then per release when it fired, the static margin just before and after, the
    /// part's landing (time, east, north, distance, speed) and, for a part with a parachute,
    /// when its canopy opened.
    pub metrics: Vec<Column>,
    /// Each landing the statistics draw an ellipse of: the rocket's (`"rocket"`), then each
    /// released part's (`"release_<name>"`), with the metrics' indices of its east and north.
    pub landings: Vec<(String, usize, usize)>,
    /// The scenario's requirements, each with its metric's index in [`Prepared::metrics`],
    /// in the metrics' order.
    pub requirements: Vec<(usize, RequirementSpec)>,
    design: Design,
    motor: Motor,
    /// The motors a sweep flies (empty without a sweep of motors).
    motors: Vec<Motor>,
    nominal: Setup,
    /// The flight at the first sweep point's centers; every lane is it with its row applied.
    batch: Batch,
    /// How a sweep's points share the beginning of their flights (`None`: they do not).
    sharing: Option<Sharing>,
}

/// The scenario's key of a motor option's field; `None` for the motor's own numbers (its
/// file's masses and sizes, and its curve under the scales, which the scenario leaves at 1),
/// which are the key naming the motor's.
fn option_key(field: MotorField) -> Option<&'static str> {
    use MotorField as F;
    Some(match field {
        F::ImpulseScale
        | F::TimeScale
        | F::Scales
        | F::MotorFilePropellantMass
        | F::MotorFileDryMass
        | F::MotorFileLength
        | F::MotorFileDiameter => return None,
        F::PropellantMass => "motor.propellant_mass_kg",
        F::DryMass => "motor.dry_mass_kg",
        F::Chamber => "motor.chamber",
        F::ChamberRadius => "motor.chamber.radius_m",
        F::ChamberHeight => "motor.chamber.height_m",
        F::GrainsCount => "motor.grains.count",
        F::GrainsOuterRadius => "motor.grains.outer_radius_m",
        F::GrainsInnerRadius => "motor.grains.inner_radius_m",
        F::GrainsHeight => "motor.grains.height_m",
        F::GrainsSeparation => "motor.grains.separation_m",
        F::GrainsDensity => "motor.grains.density_kg_m3",
        F::NozzleRadius => "motor.nozzle_radius_m",
        F::DryCenterFromNozzle => "motor.dry_center_from_nozzle_m",
        F::PropellantCenterFromNozzle => "motor.propellant_center_from_nozzle_m",
        F::DryInertiaAxial | F::DryInertiaTransverse => "motor.dry_inertia_kg_m2",
        F::BurnTime => "motor.burn_time_s",
        F::Diameter => "motor.diameter_m",
    })
}

impl Prepared {
    /// Load the design and the motor, resolve the nominals and check the scenario's rules that
    /// need them. Errors name the scenario's key.
    pub fn new(scenario: Scenario) -> Result<Prepared, ScenarioError> {
        let file = scenario.file.display().to_string();
        let bad = |key: &str, rule: String| ScenarioError::Invalid {
            file: file.clone(),
            key: key.to_string(),
            rule,
        };
        let design =
            Design::load(&scenario.design_file).map_err(|e| bad("design.file", e.to_string()))?;
        // A motor as the scenario names it (`name_key`: where), with its options.
        let load_motor = |name: &str, name_key: &str| -> Result<Motor, ScenarioError> {
            let mut motor = motor::find(name).map_err(|e| bad(name_key, e.to_string()))?;
            if let Some(t) = scenario.motor_burn_time_s {
                motor = motor
                    .cut_at(t)
                    .map_err(|e| bad("motor.burn_time_s", e.to_string()))?;
            }
            if let Some(d) = scenario.motor_diameter_m {
                motor = motor
                    .with_diameter(d)
                    .map_err(|e| bad("motor.diameter_m", e.to_string()))?;
            }
            // The motor's own numbers against the motor (a center within its length).
            if let Err(e) = MotorTables::new(&motor, &scenario.motor_options) {
                let key = match &e {
                    MotorError::InvalidOption { field, .. } => {
                        option_key(*field).map_or_else(|| name_key.to_owned(), str::to_owned)
                    }
                    _ => name_key.to_owned(),
                };
                return Err(bad(&key, e.to_string()));
            }
            Ok(motor)
        };
        let motor = load_motor(&scenario.motor, "motor.name")?;
        let motors = scenario
            .motors
            .iter()
            .enumerate()
            .map(|(j, m)| load_motor(m, &format!("sweep.motor[{j}]")))
            .collect::<Result<Vec<Motor>, _>>()?;
        if !motors.is_empty() {
            // The impulse and burn time are a motor's: scaled against which, with several?
            if let Some(i) = scenario
                .inputs
                .iter()
                .find(|i| matches!(i.param, Param::MotorImpulseNs | Param::MotorBurnTimeS))
            {
                return Err(bad(&i.key_path(), "the motor is swept: its impulse and burn time are each motor's own (vary them with a motor of its own, not with a sweep of motors)".into()));
            }
        }
        // The design's dimensions the scenario varies, each from the design as written.
        let source = if scenario.dimensions.is_empty() {
            None
        } else {
            let (source, _) = DesignSource::load(&scenario.design_file)
                .map_err(|e| bad("design.file", e.to_string()))?;
            Some(source)
        };
        let mut dimensions = Vec::new();
        for (k, dim) in scenario.dimensions.iter().enumerate() {
            let source = source.as_ref().expect("loaded for the dimensions");
            let value = source.value(dim).map_err(|r| {
                let key = scenario
                    .inputs
                    .iter()
                    .find(|i| i.param == Param::Design(k))
                    .map_or("design".into(), |i| i.key_path());
                bad(&key, r)
            })?;
            dimensions.push(value);
        }

        if let Some(i) = scenario
            .inputs
            .iter()
            .find(|i| i.param == Param::AirBrakesTargetM)
            .filter(|_| design.air_brakes.is_none())
        {
            return Err(bad(
                &i.key_path(),
                "the design has no air brakes to aim (its \"air_brakes\")".into(),
            ));
        }
        let uses_ballast = scenario.inputs.iter().find(|i| i.param == Param::BallastKg);
        let ballast = match &scenario.ballast {
            None => {
                if let Some(i) = uses_ballast {
                    return Err(bad(
                        &i.key_path(),
                        "needs design.ballast, the id of the design's ballast component".into(),
                    ));
                }
                None
            }
            Some(id) => {
                let idx = design.component_index(id).ok_or_else(|| {
                    bad(
                        "design.ballast",
                        format!(
                            "the design \"{}\" has no component with id \"{id}\"",
                            design.name
                        ),
                    )
                })?;
                check_ballast(&design, idx).map_err(|r| bad("design.ballast", r))?;
                // A variant's ballast is the part's mass, scaled from the design's with what
                // it holds (the simulator's part mass): only an internal part that holds
                // nothing keeps its meaning, its own mass.
                let c = &design.components[idx];
                if uses_ballast.is_some() && (c.is_body() || c.is_external()) {
                    return Err(bad(
                        "design.ballast",
                        format!("the component \"{id}\" is not an internal part (a body component or an external one); ballast_kg is the mass of an internal part"),
                    ));
                }
                if uses_ballast.is_some() && !c.children.is_empty() {
                    return Err(bad(
                        "design.ballast",
                        format!("the component \"{id}\" holds other parts; ballast_kg is the mass of a part that holds nothing"),
                    ));
                }
                Some(idx)
            }
        };
        let dry = mass::dry(&design);
        let motor_delay = motor.delays_s.first().copied();
        let trigger_nominal = |t: &Trigger, key: String| -> Result<f64, ScenarioError> {
            match (trigger_value(t), t) {
                (Some(v), _) => Ok(v),
                (None, Trigger::BurnoutPlusDelay { delay_s: None }) => match motor_delay {
                    Some(d) => Ok(d),
                    None => Err(bad(&key, format!("the trigger is burnout plus the motor's delay, but the motor {} is plugged (no delay)", motor.designation))),
                },
                _ => Ok(f64::NAN),
            }
        };
        let mut parachutes = Vec::new();
        for (i, p) in scenario.parachutes.iter().enumerate() {
            parachutes.push([
                p.cds_m2,
                p.lag_s,
                trigger_nominal(&p.trigger, format!("parachutes[{i}].trigger"))?,
            ]);
        }
        let mut shifts = Vec::new();
        for (i, s) in scenario.shifts.iter().enumerate() {
            shifts.push([
                s.travel_m,
                s.duration_s,
                trigger_nominal(&s.trigger, format!("shifts[{i}].trigger"))?,
            ]);
        }
        let mut releases = Vec::new();
        for (i, r) in scenario.releases.iter().enumerate() {
            // The part's drag area: the scenario's, the design's, or the tumbling estimate of
            // its component (NaN for a component the design lacks, or one no release may
            // drop, which the simulator refuses by name).
            let cda = match design.component_index(&r.component) {
                Some(idx) => hpr_sim::releases::release_cda_m2(&design, idx, r.cda_m2),
                None => r.cda_m2.unwrap_or(f64::NAN),
            };
            let (cds, lag) = r
                .parachute
                .map_or((f64::NAN, f64::NAN), |c| (c.cds_m2, c.lag_s));
            releases.push([
                trigger_nominal(&r.trigger, format!("releases[{i}].trigger"))?,
                cda,
                cds,
                lag,
            ]);
        }
        // The site's air as the scenario gives it (the standard's at the site if it does not).
        let (_, temperature_k, pressure_pa) = scenario
            .environment
            .air
            .site_values(scenario.environment.elevation_m);
        let weather = scenario.environment.weather.as_ref();
        let mut nominal = Setup {
            globals: [f64::NAN; hpr_sim::inputs::GLOBAL_COUNT],
            parachutes,
            shifts,
            releases,
            design: dimensions,
            sensor_seed: 0,
        };
        // Each input's nominal: the design's, the motor's or the scenario's (NaN for one the
        // flight does not have).
        for (p, v) in [
            (Param::StructureMassKg, dry.mass_kg),
            (Param::StructureCgM, dry.cg_m.x),
            (
                Param::BallastKg,
                ballast.map_or(f64::NAN, |idx| mass::component_own(&design, idx).mass_kg),
            ),
            (Param::MotorImpulseNs, motor.total_impulse_ns()),
            (Param::MotorBurnTimeS, motor.burn_time_s()),
            (Param::DragScale, 1.0),
            (Param::ElevationM, scenario.environment.elevation_m),
            (Param::TemperatureK, temperature_k),
            (Param::PressurePa, pressure_pa),
            (Param::WindSpeedMS, scenario.environment.wind_speed_m_s),
            (Param::WindFromDeg, scenario.environment.wind_from_deg),
            (Param::WindScale, 1.0),
            (Param::WindRotationDeg, 0.0),
            (
                Param::WindTurbulenceIntensity,
                scenario.environment.wind_turbulence_intensity,
            ),
            (Param::RailLengthM, scenario.rail.length_m),
            (Param::RailInclinationDeg, scenario.rail.inclination_deg),
            (Param::RailHeadingDeg, scenario.rail.heading_deg),
            (
                Param::AirBrakesTargetM,
                design.air_brakes.map_or(f64::NAN, |b| b.target_apogee_m),
            ),
            (Param::LaunchTimeH, weather.map_or(f64::NAN, |_| 0.0)),
            (Param::WeatherMember, weather.map_or(f64::NAN, |w| w.member)),
            (
                Param::MotorDryMassKg,
                (scenario.motor_options.dry_mass_kg).unwrap_or(motor.dry_mass_kg()),
            ),
        ] {
            nominal.set(p, v);
        }
        let plan = Plan {
            seed: scenario.seed,
            variants_per_point: scenario.variants_per_point,
            common_random_numbers: scenario.common_random_numbers,
            inputs: scenario
                .inputs
                .iter()
                .map(|i| PlanInput {
                    key: i.key.clone(),
                    nominal: nominal.get(i.param),
                    sweep: i.sweep.clone(),
                    dispersion: i.dispersion,
                    keeps_side: matches!(i.param, Param::ShiftTravelM(_)),
                })
                .collect(),
        };
        let column = |name: String, unit: &'static str| Column { name, unit };
        let metrics: Vec<Column> = FIXED_METRICS
            .iter()
            .map(|(n, u, _)| column(n.to_string(), u))
            .chain(scenario.shifts.iter().flat_map(|s| {
                PER_SHIFT.map(|(n, u, _)| column(format!("shift_{}_{n}", s.name), u))
            }))
            .chain(scenario.parachutes.iter().flat_map(|c| {
                PER_PARACHUTE.map(|(n, u, _)| column(format!("parachute_{}_{n}", c.name), u))
            }))
            .chain(
                design
                    .air_brakes
                    .iter()
                    .flat_map(|_| AIR_BRAKES.map(|(n, u, _)| column(n.into(), u))),
            )
            .chain(scenario.releases.iter().flat_map(|r| {
                let chute = r.parachute.is_some().then_some(RELEASE_CHUTE);
                PER_RELEASE
                    .into_iter()
                    .chain(chute)
                    .map(|(n, u, _)| column(format!("release_{}_{n}", r.name), u))
                    .collect::<Vec<_>>()
            }))
            .collect();
        // Each landing's east and north, by name.
        let at = |name: &str| {
            metrics
                .iter()
                .position(|c| c.name == name)
                .expect("a landing's columns")
        };
        let landings =
            std::iter::once(("rocket".to_string(), at("landing_x_m"), at("landing_y_m")))
                .chain(scenario.releases.iter().map(|r| {
                    (
                        format!("release_{}", r.name),
                        at(&format!("release_{}_landing_x_m", r.name)),
                        at(&format!("release_{}_landing_y_m", r.name)),
                    )
                }))
                .collect();
        let mut requirements = vec![];
        for r in &scenario.requirements {
            let Some(m) = metrics.iter().position(|c| c.name == r.metric) else {
                let names: Vec<&str> = metrics.iter().map(|c| c.name.as_str()).collect();
                return Err(bad(
                    &format!("requirements.{}", r.metric),
                    format!(
                        "is not a metric of this scenario; its metrics are {}",
                        names.join(", ")
                    ),
                ));
            };
            requirements.push((m, r.clone()));
        }
        requirements.sort_by_key(|(m, _)| *m);
        let fixed = Fixed {
            scenario: &scenario,
            design: &design,
            motor: &motor,
            nominal: &nominal,
        };
        let swept = scenario.swept().next().is_some();
        let point_key = if swept { "sweep" } else { "(nominal flight)" };
        // Every sweep point's nominal flight must set up, and a dispersion relative to its
        // center needs a center that is not zero. The first point's flight is the base of
        // every lane; the others are checked as lanes of it.
        // Every swept motor fits the design's mount (as written: a dimension that moves the
        // mount is judged flight by flight).
        for (j, m) in motors.iter().enumerate() {
            design
                .motor_fits(m.diameter_m, m.length_m)
                .map_err(|e| bad(&format!("sweep.motor[{j}]"), e.to_string()))?;
        }
        // The designs of the sweep points, built once each before the run (unless a dimension
        // is dispersed: then every variant's design is its own, built for its lane).
        let designs = source.map(|source| {
            let dims: Vec<usize> = (0..scenario.dimensions.len()).collect();
            let mut designs = BatchDesigns::new(source, scenario.dimensions.clone());
            let dispersed = scenario
                .inputs
                .iter()
                .any(|i| matches!(i.param, Param::Design(_)) && i.dispersion.is_some());
            if !dispersed {
                for point in 0..plan.points() {
                    let centers = plan.centers(point);
                    let values: Vec<(usize, f64)> = dims
                        .iter()
                        .map(|&k| {
                            let j = scenario
                                .inputs
                                .iter()
                                .position(|i| i.param == Param::Design(k))
                                .expect("every dimension is an input");
                            (k, centers[j])
                        })
                        .collect();
                    // A point whose design breaks a rule: its variants are refused, each
                    // naming the rule.
                    let _ = designs.keep(&values);
                }
            }
            designs
        });
        let designs = designs.map(std::sync::Arc::new);
        // Whether a sweep point's design breaks a rule (its variants are refused rows).
        let refused_design = |setup: &Setup| -> bool {
            designs.as_ref().is_some_and(|d| {
                let values: Vec<(usize, f64)> = setup.design.iter().copied().enumerate().collect();
                d.design(&values).is_err()
            })
        };
        let mut batch: Option<Batch> = None;
        for point in 0..plan.points() {
            let centers = plan.centers(point);
            let at = at_point(&scenario, &plan, point);
            for (input, c) in scenario.inputs.iter().zip(&centers) {
                if let Some(d) = &input.dispersion {
                    if d.needs_nonzero_center() && *c == 0.0 {
                        return Err(bad(&format!("dispersions.{}", input.key), format!("a relative or lognormal dispersion scales the nominal, which is 0{at}; give an absolute dispersion")));
                    }
                }
            }
            let setup = fixed.setup(&centers).map_err(|r| bad(point_key, r))?;
            let refused_at = |key: &str, r: &dyn std::fmt::Display| {
                bad(key, format!("the nominal flight{at} can't be set up: {r}"))
            };
            let refused = |r: String| refused_at(point_key, &r);
            match &batch {
                None => {
                    // A shift or a release the simulator refuses is named by its own key.
                    let base = fixed.simulation(&setup).map_err(|e| {
                        let own = match &e {
                            SimError::Shift(r) => r.field().map(|(i, f)| ("shifts", i, f)),
                            SimError::Release(r) => {
                                let (i, f) = r.field();
                                Some(("releases", i, f))
                            }
                            _ => None,
                        };
                        match (own, &e) {
                            (Some((table, i, field)), _) => {
                                refused_at(&format!("{table}[{i}].{field}"), &e)
                            }
                            // A motor that does not fit is the motor's fault, not the sweep's.
                            (None, SimError::MotorDoesNotFit(_)) => refused_at("motor.name", &e),
                            (None, _) => refused_at(point_key, &e),
                        }
                    })?;
                    let part = ballast.map(|i| design.components[i].id.as_str());
                    let mut b = Batch::new(base, part).map_err(refused)?;
                    if let Some(w) = &scenario.environment.weather {
                        b = b.with_weather(BatchWeather {
                            site: w.site.clone(),
                            time_s: w.time_s,
                            member: w.member,
                            elevation_m: scenario.environment.elevation_m,
                        });
                    }
                    b = b.with_motors(motors.clone());
                    if let Some(d) = &designs {
                        b = b.with_designs(d.clone());
                    }
                    batch = Some(b);
                }
                Some(_) => {}
            }
            // The base is the first point's flight with the design and the motor as written:
            // every point with a motor or a design of its own is checked as a lane of it.
            let changes_base = !motors.is_empty() || designs.is_some();
            if let Some(b) = batch.as_ref().filter(|_| point > 0 || changes_base) {
                if !refused_design(&setup) {
                    b.variant(&fixed.columns(&[&setup]), 0).map_err(refused)?;
                }
            }
        }
        let batch = batch.ok_or_else(|| bad("sweep", "the sweep has no points".into()))?;
        let sharing = Sharing::of(&plan, &scenario.inputs, batch.base());
        Ok(Prepared {
            scenario,
            plan,
            metrics,
            landings,
            requirements,
            design,
            motor,
            motors,
            nominal,
            batch,
            sharing,
        })
    }

    /// The store in which the chunks of a run leave and take the beginnings their flights
    /// share (`None` when the sweep's points share none); see [`fly_chunk_sharing`].
    pub fn prefix_store(&self) -> Option<PrefixStore<'_>> {
        self.sharing
            .as_ref()
            .map(|_| PrefixStore::new(self.batch.base().model(), SHARED_BEGINNINGS))
    }

    fn fixed(&self) -> Fixed<'_> {
        Fixed {
            scenario: &self.scenario,
            design: &self.design,
            motor: &self.motor,
            nominal: &self.nominal,
        }
    }

    /// The nominal value of an input (the center of its dispersion when it is not swept).
    pub fn nominal(&self, p: Param) -> f64 {
        self.nominal.get(p)
    }

    /// The design as loaded.
    pub fn design(&self) -> &Design {
        &self.design
    }

    /// The motor as found.
    pub fn motor(&self) -> &Motor {
        &self.motor
    }

    /// The motors a sweep flies, in the sweep's order (empty without a sweep of motors).
    pub fn swept_motors(&self) -> &[Motor] {
        &self.motors
    }

    /// The designation of the motor a variant's values fly (`None` without a sweep of
    /// motors).
    pub fn motor_of(&self, values: &[f64]) -> Option<&str> {
        let j = self
            .scenario
            .inputs
            .iter()
            .position(|i| i.param == Param::Motor)?;
        self.motors
            .get(values[j] as usize)
            .map(|m| m.designation.as_str())
    }

    /// The nominal flight of sweep point `point` (every input at its center, or at its mean
    /// where it is dispersed as a normal about its own mean), built from scratch and keeping
    /// its samples: what `hpr-mc fly --scenario` flies.
    pub fn nominal_flight(&self, point: usize) -> Result<Simulation, String> {
        let points = self.plan.points();
        if point >= points {
            return Err(format!(
                "--point {point}: the scenario has {points} sweep point{} (0 to {})",
                if points == 1 { "" } else { "s" },
                points - 1
            ));
        }
        let fixed = self.fixed();
        // An input given as a normal about its own mean scatters around that mean.
        let centers: Vec<f64> = self
            .plan
            .centers(point)
            .into_iter()
            .zip(&self.scenario.inputs)
            .map(|(c, input)| input.dispersion.map_or(c, |d| d.scatter_center(c)))
            .collect();
        let setup = fixed.setup(&centers)?;
        let sim = if self.motors.is_empty() && self.scenario.dimensions.is_empty() {
            fixed.simulation(&setup).map_err(|e| e.to_string())?
        } else {
            // A point's own motor or design: the base flight with the point's inputs, as its
            // lanes fly them.
            self.batch
                .variant(&fixed.columns(&[&setup]), 0)
                .map_err(|e| format!("the nominal flight{}: {e}", self.point_label(point)))?
        };
        let options = SimOptions {
            keep_samples: true,
            ..*sim.options()
        };
        sim.with_options(options).map_err(|e| e.to_string())
    }

    /// The single flight of variant `id` of the plan (every sampled input and its noise
    /// seed, as its lane flies it: [`Batch::variant`]), keeping its samples: what `hpr-mc fly
    /// --scenario FILE --variant ID` and the run's `trajectories.parquet` fly. Its
    /// [`Prepared::flight_result`] is the variant's row, bit for bit. Errs for an id past the
    /// plan or a variant the run records as `refused` (saying why).
    pub fn variant_flight(&self, id: u64) -> Result<Simulation, String> {
        let total = self.plan.total();
        if id >= total {
            return Err(format!(
                "--variant {id}: the run has {total} variants (0 to {})",
                total.saturating_sub(1)
            ));
        }
        let v = self.plan.variant(id);
        let fixed = self.fixed();
        let setup = fixed
            .setup(&v.values)
            .map(|mut s| {
                s.sensor_seed = v.sensor_seed;
                s
            })
            .map_err(|e| {
                hpr_design::error::tidy_numbers(&format!("variant {id} is refused: sampled {e}"))
            })?;
        let sim = self
            .batch
            .variant(&fixed.columns(&[&setup]), 0)
            .map_err(|e| format!("variant {id} is refused: {e}"))?;
        let options = SimOptions {
            keep_samples: true,
            ..*sim.options()
        };
        sim.with_options(options).map_err(|e| e.to_string())
    }

    /// Variant `id`'s result from its single flight ([`Prepared::variant_flight`]), judged
    /// by the code that judges its lane: the row `variants.parquet` holds for it.
    pub fn flight_result(
        &self,
        id: u64,
        sim: &Simulation,
        flight: Result<hpr_sim::Flight, SimError>,
    ) -> VariantResult {
        let lane = self.batch.lane_result(sim, flight, id as usize);
        self.result(id, lane)
    }

    /// " at sweep point k (key = v, ...)" for `point`, or "" without a sweep.
    pub fn point_label(&self, point: usize) -> String {
        at_point(&self.scenario, &self.plan, point)
    }

    /// The base flight of every lane (the first sweep point's nominal flight, no samples).
    pub fn base(&self) -> &Simulation {
        self.batch.base()
    }

    /// A variant's result from its lane.
    fn result(&self, id: u64, lane: LaneResult) -> VariantResult {
        let status = lane.status;
        let error = match status {
            Status::TimeLimit => Some(format!(
                "the flight reached its time limit (integrator.max_time_s = {} s) before landing",
                lane.end_s
            )),
            _ => lane.error,
        };
        if !lane.flown {
            return VariantResult {
                id,
                status,
                error,
                warnings: None,
                warned: None,
                metrics: vec![None; self.metrics.len()],
            };
        }
        let m = &lane.metrics;
        let mut out: Vec<Option<f64>> = FIXED_METRICS.iter().map(|(_, _, f)| f(m)).collect();
        for k in 0..self.scenario.shifts.len() {
            let shift = lane.shifts.get(k).copied().unwrap_or_default();
            out.extend(PER_SHIFT.iter().map(|(_, _, f)| f(&shift)));
        }
        for k in 0..self.scenario.parachutes.len() {
            let chute = lane.parachutes.get(k).copied().unwrap_or_default();
            out.extend(PER_PARACHUTE.iter().map(|(_, _, f)| f(&chute)));
        }
        if self.design.air_brakes.is_some() {
            out.extend(AIR_BRAKES.iter().map(|(_, _, f)| f(m)));
        }
        for (k, spec) in self.scenario.releases.iter().enumerate() {
            let r = lane.releases.get(k).copied().unwrap_or_default();
            out.extend(PER_RELEASE.iter().map(|(_, _, f)| f(&r)));
            if spec.parachute.is_some() {
                out.push((RELEASE_CHUTE.2)(&r));
            }
        }
        let warnings = (!lane.warnings.is_empty()).then(|| {
            let w: Vec<String> = lane.warnings.iter().map(|w| w.to_string()).collect();
            w.join("; ")
        });
        let mut warned = [false; WARNINGS];
        for w in &lane.warnings {
            warned[w.index()] = true;
        }
        VariantResult {
            id,
            status,
            error,
            warnings,
            warned: Some(warned),
            metrics: out
                .into_iter()
                .map(|x| x.filter(|v| v.is_finite()))
                .collect(),
        }
    }
}

/// " at sweep point k (key = v, ...)", or "" without a sweep.
fn at_point(scenario: &Scenario, plan: &Plan, point: usize) -> String {
    let swept: Vec<String> = scenario
        .swept()
        .zip(plan.sweep_values(point))
        .map(|(i, v)| format!("{} = {v}", i.key))
        .collect();
    if swept.is_empty() {
        String::new()
    } else {
        format!(" at sweep point {point} ({})", swept.join(", "))
    }
}

/// A ballast whose mass an override replaces can't have its mass changed.
fn check_ballast(design: &Design, idx: usize) -> Result<(), String> {
    let c = &design.components[idx];
    if c.overrides.mass_kg.is_some() {
        return Err(format!(
            "the component \"{}\" has a mass override, which would hide any change of its mass",
            c.id
        ));
    }
    if design.stages[c.stage].overrides.mass_kg.is_some() {
        return Err(format!("the component \"{}\" is in a stage whose mass is overridden, which would hide any change of its mass", c.id));
    }
    let mut p = c.parent;
    while let Some(i) = p {
        let a = &design.components[i];
        if a.overrides.mass_kg.is_some() && a.overrides.covers_children {
            return Err(format!("the component \"{}\" is inside \"{}\", whose mass override covers it and would hide any change of its mass", c.id, a.id));
        }
        p = a.parent;
    }
    Ok(())
}

/// Fly a chunk of variants, one result per variant in order: the variants whose sampled
/// values are in range become the rows of one set of columns, flown in order on this thread
/// as lanes of the prepared base flight (the run loop spreads the chunks over the threads).
pub fn fly_chunk(prepared: &Prepared, variants: &[Variant]) -> Vec<VariantResult> {
    fly_chunk_sharing(prepared, variants, None)
}

/// [`fly_chunk`], the variants' flights taking the beginnings they share from `store` or
/// leaving them there ([`Prepared::prefix_store`]): the same results, bit for bit, in less
/// time.
pub fn fly_chunk_sharing(
    prepared: &Prepared,
    variants: &[Variant],
    store: Option<&PrefixStore<'_>>,
) -> Vec<VariantResult> {
    fly_lanes(prepared, &prepared.batch, variants, store)
        .into_iter()
        .map(|r| r.0)
        .collect()
}

/// The run's batch with its lanes keeping their samples ([`fly_chunk_with_samples`]).
pub fn sampling_batch(prepared: &Prepared) -> Result<Batch, String> {
    prepared.batch.keeping_samples()
}

/// [`fly_chunk`] with each flight's samples (one per step; none for a variant not flown),
/// for the few variants whose time series a run writes: the same lanes, of `batch`
/// ([`sampling_batch`]), keeping samples.
pub fn fly_chunk_with_samples(
    prepared: &Prepared,
    batch: &Result<Batch, String>,
    variants: &[Variant],
) -> Vec<(VariantResult, Vec<hpr_sim::flight::Sample>)> {
    match batch {
        Ok(batch) => fly_lanes(prepared, batch, variants, None),
        Err(e) => variants
            .iter()
            .map(|v| {
                let r = VariantResult {
                    id: v.id,
                    status: Status::Failed,
                    error: Some(format!("internal error: {e}")),
                    warnings: None,
                    warned: None,
                    metrics: vec![None; prepared.metrics.len()],
                };
                (r, vec![])
            })
            .collect(),
    }
}

fn fly_lanes(
    prepared: &Prepared,
    batch: &Batch,
    variants: &[Variant],
    store: Option<&PrefixStore<'_>>,
) -> Vec<(VariantResult, Vec<hpr_sim::flight::Sample>)> {
    let fixed = prepared.fixed();
    let setups: Vec<Result<Setup, String>> = variants
        .iter()
        .map(|v| {
            fixed.setup(&v.values).map(|mut s| {
                s.sensor_seed = v.sensor_seed;
                s
            })
        })
        .collect();
    let rows: Vec<&Setup> = setups.iter().filter_map(|s| s.as_ref().ok()).collect();
    let columns = fixed.columns(&rows);
    let lanes = match (store, &prepared.sharing) {
        (Some(store), Some(sharing)) => {
            let prefixes: Vec<Option<Prefix>> = variants
                .iter()
                .zip(&setups)
                .filter(|(_, s)| s.is_ok())
                .map(|(v, _)| sharing.prefix(&prepared.plan, v))
                .collect();
            batch.fly_chunk_sharing(&columns, 0, Some((&prefixes, store)))
        }
        _ => batch.fly_chunk(&columns, 0),
    };
    let mut lanes = match lanes {
        Ok(l) => l.into_iter(),
        // The columns are built here from checked setups: a shape error is a bug of this
        // module, reported on every row rather than stopping the run.
        Err(e) => {
            let failed = |v: &Variant| {
                let r = VariantResult {
                    id: v.id,
                    status: Status::Failed,
                    error: Some(format!("internal error: {e}")),
                    warnings: None,
                    warned: None,
                    metrics: vec![None; prepared.metrics.len()],
                };
                (r, vec![])
            };
            return variants.iter().map(failed).collect();
        }
    };
    variants
        .iter()
        .zip(setups)
        .map(|(v, setup)| {
            let (status, error) = match setup.map(|_| lanes.next()) {
                Ok(Some(mut lane)) => {
                    let samples = std::mem::take(&mut lane.samples);
                    return (prepared.result(v.id, lane), samples);
                }
                Err(e) => (
                    Status::Refused,
                    hpr_design::error::tidy_numbers(&format!("sampled {e}")),
                ),
                Ok(None) => (Status::Failed, "internal error: a lane is missing".into()),
            };
            let r = VariantResult {
                id: v.id,
                status,
                error: Some(error),
                warnings: None,
                warned: None,
                metrics: vec![None; prepared.metrics.len()],
            };
            (r, vec![])
        })
        .collect()
}
