//! Flying variants: the base setup of a scenario ([`Prepared`]: design, motor, nominals,
//! checked once), a variant's values applied to it, and the flight with `hpr_sim`'s
//! single-flight [`Simulation`].
//!
//! [`fly_chunk`] is the one step that flies: it takes a chunk of variants and returns one
//! [`VariantResult`] per variant, in order. The batch engine replaces it without touching the
//! rest of the run. A variant that can't fly is a result too, never an error of the run:
//! `refused` (a sampled value outside its range, or a setup the simulator refuses, such as a
//! shift taking its part out of its holder), `failed` (the flight stopped with an error, went
//! non-finite, or ended without landing) or `time_limit` (cut by `integrator.max_time_s`
//! before landing). Only `landed` variants enter the statistics.

use super::params::Param;
use super::scenario::{trigger_value, with_trigger_value, Scenario, ScenarioError};
use super::variants::{Plan, PlanInput, Variant};
use hpr_design::design::model::{Design, MassSpec};
use hpr_design::mass;
use hpr_design::motor::{self, Motor, MotorOptions};
use hpr_sim::gravity::Gravity;
use hpr_sim::wind::Wind;
use hpr_sim::{Environment, EventKind, Flight, Parachute, Rail, SimOptions, Simulation};
use hpr_sim::{MassShift, Trigger};

/// How a variant ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Landed,
    TimeLimit,
    Refused,
    Failed,
}

impl Status {
    pub fn name(&self) -> &'static str {
        match self {
            Status::Landed => "landed",
            Status::TimeLimit => "time_limit",
            Status::Refused => "refused",
            Status::Failed => "failed",
        }
    }
}

/// A flown (or refused) variant: its status, the error text, and the value of every metric
/// (in [`Prepared::metrics`] order; `None` where a value does not exist).
#[derive(Debug, Clone, PartialEq)]
pub struct VariantResult {
    pub id: u64,
    pub status: Status,
    pub error: Option<String>,
    pub metrics: Vec<Option<f64>>,
}

/// An output column: name (with its unit) and unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    pub name: String,
    pub unit: &'static str,
}

/// The metrics every flight has, in output order.
pub const FIXED_METRICS: [(&str, &str); 16] = [
    ("apogee_m", "m"),
    ("apogee_time_s", "s"),
    ("max_speed_m_s", "m/s"),
    ("max_mach", "1"),
    ("max_accel_m_s2", "m/s²"),
    ("rail_exit_speed_m_s", "m/s"),
    ("static_margin_liftoff_cal", "cal"),
    ("static_margin_rail_exit_cal", "cal"),
    ("static_margin_burnout_cal", "cal"),
    ("static_margin_min_cal", "cal"),
    ("flight_margin_min_cal", "cal"),
    ("landing_time_s", "s"),
    ("landing_x_m", "m"),
    ("landing_y_m", "m"),
    ("landing_distance_m", "m"),
    ("landing_speed_m_s", "m/s"),
];

/// Indices of the landing point's east (x) and north (y) in the metrics.
pub const LANDING_XY: (usize, usize) = (12, 13);

/// Every flight's values, nominal or a variant's.
#[derive(Debug, Clone, PartialEq)]
struct Setup {
    structure_mass_kg: f64,
    structure_cg_m: f64,
    ballast_kg: f64,
    impulse_ns: f64,
    burn_time_s: f64,
    drag_scale: f64,
    elevation_m: f64,
    wind_speed_m_s: f64,
    wind_from_deg: f64,
    rail: [f64; 3],
    /// Per parachute: CdS, lag, trigger number (NaN if none).
    parachutes: Vec<[f64; 3]>,
    /// Per shift: travel, duration, trigger number (NaN if none).
    shifts: Vec<[f64; 3]>,
}

impl Setup {
    fn get(&self, p: Param) -> f64 {
        match p {
            Param::StructureMassKg => self.structure_mass_kg,
            Param::StructureCgM => self.structure_cg_m,
            Param::BallastKg => self.ballast_kg,
            Param::MotorImpulseNs => self.impulse_ns,
            Param::MotorBurnTimeS => self.burn_time_s,
            Param::DragScale => self.drag_scale,
            Param::ElevationM => self.elevation_m,
            Param::WindSpeedMS => self.wind_speed_m_s,
            Param::WindFromDeg => self.wind_from_deg,
            Param::RailLengthM => self.rail[0],
            Param::RailInclinationDeg => self.rail[1],
            Param::RailHeadingDeg => self.rail[2],
            Param::ParachuteCdsM2(i) => self.parachutes[i][0],
            Param::ParachuteLagS(i) => self.parachutes[i][1],
            Param::ParachuteTrigger(i) => self.parachutes[i][2],
            Param::ShiftTravelM(i) => self.shifts[i][0],
            Param::ShiftDurationS(i) => self.shifts[i][1],
            Param::ShiftTrigger(i) => self.shifts[i][2],
        }
    }

    fn set(&mut self, p: Param, v: f64) {
        let slot = match p {
            Param::StructureMassKg => &mut self.structure_mass_kg,
            Param::StructureCgM => &mut self.structure_cg_m,
            Param::BallastKg => &mut self.ballast_kg,
            Param::MotorImpulseNs => &mut self.impulse_ns,
            Param::MotorBurnTimeS => &mut self.burn_time_s,
            Param::DragScale => &mut self.drag_scale,
            Param::ElevationM => &mut self.elevation_m,
            Param::WindSpeedMS => &mut self.wind_speed_m_s,
            Param::WindFromDeg => &mut self.wind_from_deg,
            Param::RailLengthM => &mut self.rail[0],
            Param::RailInclinationDeg => &mut self.rail[1],
            Param::RailHeadingDeg => &mut self.rail[2],
            Param::ParachuteCdsM2(i) => &mut self.parachutes[i][0],
            Param::ParachuteLagS(i) => &mut self.parachutes[i][1],
            Param::ParachuteTrigger(i) => &mut self.parachutes[i][2],
            Param::ShiftTravelM(i) => &mut self.shifts[i][0],
            Param::ShiftDurationS(i) => &mut self.shifts[i][1],
            Param::ShiftTrigger(i) => &mut self.shifts[i][2],
        };
        *slot = v;
    }
}

/// A scenario ready to fly: the design and motor loaded, the nominals resolved, the plan of
/// the variants built, and every sweep point's nominal flight checked.
#[derive(Debug, Clone)]
pub struct Prepared {
    pub scenario: Scenario,
    pub plan: Plan,
    /// The output metrics: [`FIXED_METRICS`], then per shift its start time and the static
    /// margin just before and just after its move.
    pub metrics: Vec<Column>,
    design: Design,
    motor: Motor,
    ballast: Option<usize>,
    nominal: Setup,
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
        let motor = motor::find(&scenario.motor).map_err(|e| bad("motor.name", e.to_string()))?;

        let uses_ballast = scenario.inputs.iter().find(|i| i.param == Param::BallastKg);
        let ballast = match &scenario.ballast {
            None => {
                if let Some(i) = uses_ballast {
                    let section = if i.sweep.is_some() {
                        "sweep"
                    } else {
                        "dispersions"
                    };
                    return Err(bad(
                        &format!("{section}.ballast_kg"),
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
        let nominal = Setup {
            structure_mass_kg: dry.mass_kg,
            structure_cg_m: dry.cg_m.x,
            ballast_kg: ballast.map_or(f64::NAN, |idx| mass::component_own(&design, idx).mass_kg),
            impulse_ns: motor.total_impulse_ns(),
            burn_time_s: motor.burn_time_s(),
            drag_scale: 1.0,
            elevation_m: scenario.environment.elevation_m,
            wind_speed_m_s: scenario.environment.wind_speed_m_s,
            wind_from_deg: scenario.environment.wind_from_deg,
            rail: [
                scenario.rail.length_m,
                scenario.rail.inclination_deg,
                scenario.rail.heading_deg,
            ],
            parachutes,
            shifts,
        };
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
                })
                .collect(),
        };
        let mut metrics: Vec<Column> = FIXED_METRICS
            .iter()
            .map(|(n, u)| Column {
                name: n.to_string(),
                unit: u,
            })
            .collect();
        for s in &scenario.shifts {
            metrics.push(Column {
                name: format!("shift_{}_start_time_s", s.name),
                unit: "s",
            });
            metrics.push(Column {
                name: format!("shift_{}_margin_before_cal", s.name),
                unit: "cal",
            });
            metrics.push(Column {
                name: format!("shift_{}_margin_after_cal", s.name),
                unit: "cal",
            });
        }
        let prepared = Prepared {
            scenario,
            plan,
            metrics,
            design,
            motor,
            ballast,
            nominal,
        };

        // Every sweep point's nominal flight must set up, and a dispersion relative to its
        // center needs a center that is not zero.
        for point in 0..prepared.plan.points() {
            let centers = prepared.plan.centers(point);
            for (input, c) in prepared.scenario.inputs.iter().zip(&centers) {
                if let Some(d) = &input.dispersion {
                    if d.needs_nonzero_center() && *c == 0.0 {
                        return Err(bad(&format!("dispersions.{}", input.key), format!("a relative or lognormal dispersion scales the nominal, which is 0{}; give an absolute dispersion", prepared.at_point(point))));
                    }
                }
            }
            let setup = prepared
                .setup(&centers)
                .map_err(|r| bad(&prepared.point_key(point), r))?;
            prepared.simulation(&setup).map_err(|r| {
                bad(
                    &prepared.point_key(point),
                    format!(
                        "the nominal flight{} can't be set up: {r}",
                        prepared.at_point(point)
                    ),
                )
            })?;
        }
        Ok(prepared)
    }

    /// " at sweep point k (key = v, ...)", or "" without a sweep.
    fn at_point(&self, point: usize) -> String {
        let swept: Vec<String> = self
            .scenario
            .swept()
            .zip(self.plan.sweep_values(point))
            .map(|(i, v)| format!("{} = {v}", i.key))
            .collect();
        if swept.is_empty() {
            String::new()
        } else {
            format!(" at sweep point {point} ({})", swept.join(", "))
        }
    }

    fn point_key(&self, _point: usize) -> String {
        if self.scenario.swept().next().is_some() {
            "sweep".into()
        } else {
            "(nominal flight)".into()
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

    /// The nominal setup with the plan's inputs set to `values`, each checked against its
    /// range (the error names the input and the rule).
    fn setup(&self, values: &[f64]) -> Result<Setup, String> {
        let mut s = self.nominal.clone();
        for (input, &v) in self.scenario.inputs.iter().zip(values) {
            input
                .param
                .domain()
                .check(v)
                .map_err(|r| format!("{} = {v}: {r}", input.key))?;
            s.set(input.param, v);
        }
        Ok(s)
    }

    /// The simulation of a setup.
    fn simulation(&self, s: &Setup) -> Result<Simulation, String> {
        let err = |e: &dyn std::fmt::Display| e.to_string();
        let mut design = self.design.clone();
        if let Some(idx) = self.ballast {
            if s.ballast_kg != self.nominal.ballast_kg {
                design.components[idx].mass_spec = MassSpec::Mass(s.ballast_kg);
            }
        }
        let options = MotorOptions::default()
            .with_impulse_scale(s.impulse_ns / self.nominal.impulse_ns)
            .with_time_scale(s.burn_time_s / self.nominal.burn_time_s);
        let gravity = if self.scenario.environment.inverse_square_gravity {
            Gravity::inverse_square(s.elevation_m).map_err(|e| err(&e))?
        } else {
            Gravity::default()
        };
        let env = Environment {
            elevation_m: s.elevation_m,
            wind: Wind::constant(s.wind_speed_m_s, s.wind_from_deg).map_err(|e| err(&e))?,
            gravity,
            vacuum: false,
        };
        let rail = Rail {
            length_m: s.rail[0],
            inclination_deg: s.rail[1],
            heading_deg: s.rail[2],
        };
        // A change of ballast is in the design; the structure's own dispersion comes on top
        // of it (structure_mass_kg and structure_cg_m are at the nominal ballast).
        let delta_mass = s.structure_mass_kg - self.nominal.structure_mass_kg;
        let delta_cg = s.structure_cg_m - self.nominal.structure_cg_m;
        let mut sim =
            Simulation::with_motor_options(design, self.motor.clone(), options, env, rail)
                .map_err(|e| err(&e))?;
        if !self.scenario.parachutes.is_empty() {
            let chutes = self
                .scenario
                .parachutes
                .iter()
                .zip(&s.parachutes)
                .map(|(p, v)| {
                    Parachute::new(
                        p.name.clone(),
                        v[0],
                        with_trigger_value(&p.trigger, v[2]),
                        v[1],
                    )
                })
                .collect();
            sim = sim.with_parachutes(chutes).map_err(|e| err(&e))?;
        }
        if !self.scenario.shifts.is_empty() {
            let shifts = self
                .scenario
                .shifts
                .iter()
                .zip(&s.shifts)
                .map(|(sh, v)| {
                    MassShift::new(
                        with_trigger_value(&sh.trigger, v[2]),
                        sh.component.clone(),
                        v[0],
                        v[1],
                    )
                })
                .collect();
            sim = sim.with_shifts(shifts).map_err(|e| err(&e))?;
        }
        sim = sim
            .with_options(SimOptions {
                integrator: self.scenario.integrator,
                max_time_s: self.scenario.max_time_s,
                keep_samples: false,
            })
            .map_err(|e| err(&e))?;
        if s.drag_scale != 1.0 {
            sim = sim.with_drag_scale(s.drag_scale).map_err(|e| err(&e))?;
        }
        if delta_mass != 0.0 || delta_cg != 0.0 {
            sim = sim
                .with_mass_adjustment(delta_mass, delta_cg)
                .map_err(|e| err(&e))?;
        }
        Ok(sim)
    }

    /// Fly one variant.
    pub fn fly(&self, v: &Variant) -> VariantResult {
        let none = vec![None; self.metrics.len()];
        let refused = |e: String| VariantResult {
            id: v.id,
            status: Status::Refused,
            error: Some(e),
            metrics: none.clone(),
        };
        let setup = match self.setup(&v.values) {
            Ok(s) => s,
            Err(e) => return refused(format!("sampled {e}")),
        };
        let sim = match self.simulation(&setup) {
            Ok(s) => s,
            Err(e) => return refused(e),
        };
        let flown = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| sim.run(&mut ())));
        let flight = match flown {
            Ok(Ok(f)) => f,
            Ok(Err(e)) => {
                return VariantResult {
                    id: v.id,
                    status: Status::Failed,
                    error: Some(e.to_string()),
                    metrics: none,
                }
            }
            Err(panic) => {
                let msg = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                return VariantResult {
                    id: v.id,
                    status: Status::Failed,
                    error: Some(format!("the simulator panicked: {msg}")),
                    metrics: none,
                };
            }
        };
        let metrics = self.metrics_of(&sim, &flight, &setup);
        let (status, error) = if flight.metrics.landing_time_s.is_some() {
            (Status::Landed, None)
        } else if let Some(e) = flight.event(EventKind::TimeLimit) {
            (Status::TimeLimit, Some(format!("the flight reached its time limit (integrator.max_time_s = {} s) before landing", e.time_s)))
        } else {
            (
                Status::Failed,
                Some("the flight ended without landing".to_string()),
            )
        };
        VariantResult {
            id: v.id,
            status,
            error,
            metrics,
        }
    }

    fn metrics_of(&self, sim: &Simulation, f: &Flight, setup: &Setup) -> Vec<Option<f64>> {
        let m = &f.metrics;
        let landing = m.landing_position_m;
        let mut out = vec![
            m.apogee_m,
            m.apogee_time_s,
            Some(m.max_speed_m_s),
            Some(m.max_mach),
            Some(m.max_accel_m_s2),
            m.rail_exit_speed_m_s,
            m.static_margin_liftoff_cal,
            m.static_margin_rail_exit_cal,
            m.static_margin_burnout_cal,
            m.static_margin_min_cal,
            m.flight_margin_min_cal,
            m.landing_time_s,
            landing.map(|p| p[0]),
            landing.map(|p| p[1]),
            landing.map(|p| p[0].hypot(p[1])),
            m.landing_speed_m_s,
        ];
        let model = sim.model();
        let end_s = f
            .events
            .iter()
            .map(|e| e.time_s)
            .fold(f64::NEG_INFINITY, f64::max);
        let margin = |t: f64| {
            (t <= end_s).then(|| {
                (model.cp_mach0_m - sim.mass_properties(f, t).cg_m.x) / model.ref_diameter_m
            })
        };
        for (k, _) in self.scenario.shifts.iter().enumerate() {
            let start = f.shift_starts_s.get(k).copied().flatten();
            out.push(start);
            out.push(start.and_then(margin));
            out.push(start.and_then(|t| margin(t + setup.shifts[k][1])));
        }
        out.into_iter()
            .map(|x| x.filter(|v| v.is_finite()))
            .collect()
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

/// Fly a chunk of variants, one result per variant in order. This is the step the batch
/// engine replaces.
pub fn fly_chunk(prepared: &Prepared, variants: &[Variant]) -> Vec<VariantResult> {
    variants.iter().map(|v| prepared.fly(v)).collect()
}
