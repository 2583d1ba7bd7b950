//! Changes to a flight already set up, checked one by one and applied with a single rebuild of
//! the light per-flight model ([`Simulation::with_changes`]).
//!
//! Each `with_*` builder of [`Simulation`] is one change followed by a rebuild; the batch
//! engine applies a whole row of inputs (site, motor scales, drag, masses, parachutes,
//! shifts) and would otherwise rebuild the model once per input. The checks live here, once,
//! so that a change made either way is refused for the same reason with the same words.
//! None of the checks reads a field another change sets (they read the design and the motor,
//! which no change touches), so the order of the changes never changes a verdict; the
//! releases' rules, which read the shifts, are checked by the rebuild, after every change.

use super::setup_error::{Bound, ParachuteRule, PartMassRule, SetupError, SiteFault, TriggerOwner};
use super::{MassAdjustment, Parachute, Rail, SimError, SimOptions, Simulation};
use crate::atmosphere::{AirModel, AirTable};
use crate::batch::BatchWeather;
use crate::flight::DesignTables;
use crate::flight::{model, Environment};
use crate::inputs::Input;
use crate::releases::Release;
use crate::shifts::{self, MassShift};
use crate::trigger::Trigger;
use crate::wind::Wind;
use hpr_design::motor::Motor;
use hpr_design::motor::MotorOptions;
use hpr_design::Design;
use hpr_design::{mass, MAX_SAMPLING_RATE_HZ};
use std::sync::Arc;

/// A flight being changed: every setter checks its input as the matching `with_*` builder
/// does and records it; [`Simulation::with_changes`] rebuilds the model once at the end.
#[derive(Debug)]
pub struct Changes<'a> {
    sim: &'a mut Simulation,
    /// The inputs set so far ([`Changes::set`]), applied together by
    /// [`Changes::apply_inputs`].
    inputs: Vec<(Input, f64)>,
}

/// What applying inputs needs besides the flight: the part whose mass
/// [`Input::BallastKg`] gives, the weather file a launch time or an ensemble member is
/// drawn from, air tables already built (one of which may be the new air's), the motors
/// [`Input::Motor`] numbers, and the design of a row of [`Input::Design`] values (by
/// dimension number) with its tables, or the rule it breaks.
#[derive(Default)]
pub struct InputContext<'a> {
    pub part: Option<&'a str>,
    pub weather: Option<&'a BatchWeather>,
    pub air_table: Option<&'a dyn Fn(&AirModel) -> Option<Arc<AirTable>>>,
    pub motors: &'a [Motor],
    pub design: Option<&'a DesignOf<'a>>,
}

/// The design of a row of dimension values, with its tables (see [`InputContext::design`]).
pub type DesignOf<'a> =
    dyn Fn(&[(usize, f64)]) -> Result<(Design, Arc<DesignTables>), SimError> + 'a;

impl Simulation {
    /// Apply the changes `f` makes, then rebuild the flight's model once. The first refused
    /// change is the error (its message is the matching `with_*` builder's).
    pub fn with_changes(
        mut self,
        f: impl FnOnce(&mut Changes<'_>) -> Result<(), SimError>,
    ) -> Result<Simulation, SimError> {
        let mut changes = Changes {
            sim: &mut self,
            inputs: Vec::new(),
        };
        f(&mut changes)?;
        if !changes.inputs.is_empty() {
            changes.apply_inputs(&InputContext::default())?;
        }
        self.rebuild()
    }
}

impl Changes<'_> {
    /// The flight as changed so far (its model is not rebuilt yet).
    pub fn current(&self) -> &Simulation {
        self.sim
    }

    /// See [`Simulation::with_parachutes`].
    pub fn parachutes(&mut self, parachutes: Vec<Parachute>) -> Result<(), SimError> {
        let delay = self.sim.motor.delays_s.first().copied();
        for (i, p) in parachutes.iter().enumerate() {
            let bad = |rule: ParachuteRule| {
                SimError::Setup(SetupError::Parachute {
                    index: i,
                    name: p.name.clone(),
                    rule,
                })
            };
            let field = |field: &'static str, bound: Bound, got: f64| {
                bad(ParachuteRule::Field { field, bound, got })
            };
            if !(p.cds_m2.is_finite() && p.cds_m2 > 0.0) {
                return Err(field("cds_m2", Bound::PositiveFinite, p.cds_m2));
            }
            if !(p.lag_s.is_finite() && p.lag_s >= 0.0) {
                return Err(field("lag_s", Bound::FiniteNotNegative, p.lag_s));
            }
            if let Some(rate) = p.sampling_rate_hz {
                if !(rate.is_finite() && rate > 0.0 && rate <= MAX_SAMPLING_RATE_HZ) {
                    let bound = Bound::PositiveAtMost {
                        max: MAX_SAMPLING_RATE_HZ,
                        unit: "Hz",
                    };
                    return Err(field("sampling_rate_hz", bound, rate));
                }
            }
            if let Some(noise) = &p.noise {
                noise
                    .check()
                    .map_err(|(field, rule, got)| bad(ParachuteRule::Noise { field, rule, got }))?;
                if p.sampling_rate_hz.is_none() {
                    return Err(bad(ParachuteRule::NoiseWithoutSampling));
                }
            }
            p.canopy
                .check()
                .map_err(|(field, rule)| bad(ParachuteRule::Canopy { field, rule }))?;
            p.trigger
                .validate()
                .map_err(|e| bad(ParachuteRule::Trigger(e)))?;
            match p.trigger {
                Trigger::HeightDescending { height_m } if height_m <= 0.0 => {
                    return Err(bad(ParachuteRule::NeverOpens { trigger: p.trigger }));
                }
                Trigger::BurnoutPlusDelay { delay_s: None } if delay.is_none() => {
                    return Err(bad(ParachuteRule::PluggedMotor { trigger: p.trigger }));
                }
                _ => {}
            }
        }
        self.sim.parachutes = parachutes;
        Ok(())
    }

    /// See [`Simulation::with_shifts`].
    pub fn shifts(&mut self, shifts: Vec<MassShift>) -> Result<(), SimError> {
        if shifts.len() > model::MAX_SHIFTS {
            return Err(SimError::Setup(SetupError::TooManyShifts {
                max: model::MAX_SHIFTS,
                got: shifts.len(),
            }));
        }
        let plan = shifts::plan(
            &self.sim.design,
            &shifts,
            self.sim.motor.delays_s.first().copied(),
        )?;
        if plan.parts.len() > model::MAX_MOVING_PARTS {
            return Err(SimError::Setup(SetupError::TooManyMovingParts {
                max: model::MAX_MOVING_PARTS,
                got: plan.parts.len(),
            }));
        }
        self.sim.shifts = shifts;
        self.sim.plan = plan;
        Ok(())
    }

    /// See [`Simulation::with_releases`]. The releases' rules, which read the shifts, are
    /// checked when the flight is rebuilt, after every change (so that the order of the
    /// changes still never changes a verdict).
    pub fn releases(&mut self, releases: Vec<Release>) -> Result<(), SimError> {
        if releases.len() > model::MAX_RELEASES {
            return Err(SimError::Setup(SetupError::TooManyReleases {
                max: model::MAX_RELEASES,
                got: releases.len(),
            }));
        }
        self.sim.releases = releases;
        Ok(())
    }

    /// See [`Simulation::with_sensor_seed`].
    pub fn sensor_seed(&mut self, seed: u64) {
        self.sim.sensor_seed = seed;
    }

    /// See [`Simulation::with_options`].
    pub fn options(&mut self, options: SimOptions) -> Result<(), SimError> {
        options.validate()?;
        self.sim.options = options;
        Ok(())
    }

    /// See [`Simulation::with_part_mass`].
    pub fn part_mass(&mut self, component: &str, mass_kg: f64) -> Result<(), SimError> {
        let bad = |rule: PartMassRule| {
            SimError::Setup(SetupError::PartMass {
                component: component.to_string(),
                rule,
            })
        };
        let design = &self.sim.design;
        let idx = design
            .component_index(component)
            .ok_or_else(|| bad(PartMassRule::NoSuchComponent))?;
        if !(mass_kg.is_finite() && mass_kg > 0.0) {
            return Err(bad(PartMassRule::Mass { got_kg: mass_kg }));
        }
        let c = &design.components[idx];
        if c.is_body() || c.is_external() {
            return Err(bad(PartMassRule::NotInternal));
        }
        let hidden = c.overrides.mass_kg.is_some()
            || design.stages[c.stage].overrides.mass_kg.is_some()
            || std::iter::successors(c.parent, |&p| design.components[p].parent).any(|p| {
                let o = &design.components[p].overrides;
                o.mass_kg.is_some() && o.covers_children
            });
        if hidden {
            return Err(bad(PartMassRule::HiddenByOverride));
        }
        // The new mass scales the part's own (with what it holds): a part that weighs nothing
        // has no mass distribution to scale (0/0 would poison the flight with NaN).
        let own = mass::subtree(design, idx).mass_kg;
        if !(own.is_finite() && own > 0.0) {
            return Err(bad(PartMassRule::NothingToScale { own_kg: own }));
        }
        self.sim.part_masses.retain(|(i, _)| *i != idx);
        self.sim.part_masses.push((idx, mass_kg));
        Ok(())
    }

    /// See [`Simulation::with_drag_scale`].
    pub fn drag_scale(&mut self, scale: f64) -> Result<(), SimError> {
        if !(scale.is_finite() && scale > 0.0) {
            return Err(SimError::Setup(SetupError::DragScale { got: scale }));
        }
        self.sim.drag_scale = scale;
        Ok(())
    }

    /// See [`Simulation::with_air_brakes_target`].
    pub fn air_brakes_target(&mut self, target_apogee_m: f64) -> Result<(), SimError> {
        if self.sim.design.air_brakes.is_none() {
            return Err(SimError::Setup(SetupError::NoAirBrakes {
                design: self.sim.design.name.clone(),
            }));
        }
        if !(target_apogee_m.is_finite() && target_apogee_m > 0.0) {
            return Err(SimError::Setup(SetupError::AirBrakesTarget {
                got_m: target_apogee_m,
            }));
        }
        self.sim.brake_target_m = Some(target_apogee_m);
        Ok(())
    }

    /// See [`Simulation::with_mass_adjustment`].
    pub fn mass_adjustment(&mut self, delta_mass_kg: f64, delta_cg_m: f64) -> Result<(), SimError> {
        // The shared tables hold `mass::dry` of this very design (no change touches it).
        let dry = self.sim.tables.dry.mass_kg;
        if !(delta_mass_kg.is_finite() && delta_cg_m.is_finite()) || dry + delta_mass_kg <= 0.0 {
            return Err(SimError::Setup(SetupError::MassAdjustment {
                delta_mass_kg,
                delta_cg_m,
                structure_kg: dry,
            }));
        }
        self.sim.mass_adjustment = MassAdjustment {
            delta_mass_kg,
            delta_cg_m,
        };
        Ok(())
    }

    /// Offer `table` as the flight's air table: the rebuild keeps it if it is the table of the
    /// air the flight then names (the same numbers, built once for many flights), and builds
    /// the right one otherwise.
    pub fn air_table_candidate(&mut self, table: Arc<AirTable>) {
        self.sim.model.air = table;
    }

    /// See [`Simulation::with_site`]. The site and rail are checked by the rebuild.
    pub fn site(&mut self, env: Environment, rail: Rail) -> Result<(), SimError> {
        self.sim.env = env;
        self.sim.rail = rail;
        Ok(())
    }

    /// See [`Simulation::with_motor_scales`]. The scales are checked by the rebuild (the
    /// motor's tables).
    pub fn motor_scales(&mut self, options: MotorOptions) -> Result<(), SimError> {
        self.sim.motor_options = options;
        Ok(())
    }
}

/// A trigger with its number (its time, height or delay) set to `v` (the error is `owner
/// index`'s: its trigger has no number).
fn with_number(t: Trigger, v: f64, owner: TriggerOwner, index: usize) -> Result<Trigger, SimError> {
    Ok(match t {
        Trigger::Time { .. } => Trigger::Time { time_s: v },
        Trigger::HeightDescending { .. } => Trigger::HeightDescending { height_m: v },
        Trigger::BurnoutPlusDelay { .. } => Trigger::BurnoutPlusDelay { delay_s: Some(v) },
        Trigger::Apogee | Trigger::Burnout => {
            return Err(SimError::Setup(SetupError::TriggerHasNoNumber {
                owner,
                index,
                trigger: t,
            }))
        }
    })
}

impl Changes<'_> {
    /// Set `input` to `value` (as a scenario writes it). The inputs set are applied together
    /// by [`Changes::apply_inputs`], or at the end of [`Simulation::with_changes`]; a later
    /// value of the same input replaces an earlier one.
    pub fn set(&mut self, input: Input, value: f64) {
        match self.inputs.iter_mut().find(|(i, _)| *i == input) {
            Some(slot) => slot.1 = value,
            None => self.inputs.push((input, value)),
        }
    }

    /// Apply the inputs set so far, in one order whatever the order they were set in: the
    /// site (a drawn weather's air and wind, then the site's temperature and pressure, the
    /// elevation, the wind, the rail), the motor's scales, the drag, the air brakes, the
    /// ballast, the structure, then each parachute's, shift's and release's numbers. An input
    /// not set keeps the flight's value. The first refused value is the error.
    pub fn apply_inputs(&mut self, ctx: &InputContext<'_>) -> Result<(), SimError> {
        use Input::*;
        let inputs = std::mem::take(&mut self.inputs);
        let get = |input: Input| inputs.iter().find(|(i, _)| *i == input).map(|p| p.1);
        let setup = SimError::Setup;
        let site = |e: SiteFault| setup(SetupError::Site(e));
        let environment = |e: SiteFault| setup(SetupError::Environment(e));
        let weather = |e: SiteFault| setup(SetupError::Weather(e));
        // The design and the motor first: the checks of the parts below read them.
        let dimensions: Vec<(usize, f64)> = inputs
            .iter()
            .filter_map(|&(i, v)| match i {
                Input::Design(k) => Some((k, v)),
                _ => None,
            })
            .collect();
        let rebuilt = !dimensions.is_empty();
        if rebuilt {
            let of = ctx.design.ok_or_else(|| setup(SetupError::NoDesigns))?;
            let (design, tables) = of(&dimensions)?;
            self.sim.design = std::sync::Arc::new(design);
            self.sim.tables = tables;
        }
        let new_motor = get(Input::Motor).is_some();
        if let Some(k) = get(Input::Motor) {
            let m = ctx
                .motors
                .get(k as usize)
                .filter(|_| k.fract() == 0.0)
                .ok_or_else(|| {
                    setup(SetupError::NoSuchMotor {
                        index: k,
                        count: ctx.motors.len(),
                    })
                })?;
            self.sim.motor = std::sync::Arc::new(m.clone());
        }
        // A new design or motor: the parachutes, shifts and releases are judged again.
        let judge_again = rebuilt || new_motor;
        let (temperature, pressure) = (get(TemperatureK), get(PressurePa));
        let member = get(WeatherMember);
        let time = match (get(LaunchTimeH), ctx.weather) {
            (Some(h), Some(w)) => Some(w.time_s + h * 3600.0),
            (Some(_), None) => Some(f64::NAN),
            (None, _) => None,
        };
        let drawn = time.is_some() || member.is_some();
        let site_inputs = [
            ElevationM,
            WindSpeedMS,
            WindFromDeg,
            WindScale,
            WindRotationDeg,
            WindTurbulenceIntensity,
            RailLengthM,
            RailInclinationDeg,
            RailHeadingDeg,
        ];
        if temperature.is_some()
            || pressure.is_some()
            || drawn
            || site_inputs.iter().any(|&i| get(i).is_some())
        {
            let mut env = self.sim.env.clone();
            // The base wind's transformation and turbulence, before a drawn weather
            // replaces the wind as given.
            let (scale, rotation) = env.wind.transformation();
            let base_turbulence = env.wind.turbulence_intensity();
            if drawn {
                let w = ctx.weather.ok_or_else(|| setup(SetupError::NoWeather))?;
                let index = w
                    .site
                    .member_index(member.unwrap_or(w.member))
                    .map_err(|e| weather(e.into()))?;
                let at_site = w
                    .site
                    .over_site(time.unwrap_or(w.time_s), index, w.elevation_m)
                    .map_err(|e| weather(e.into()))?;
                env.air = at_site.air_model();
                env.wind = at_site.wind().map_err(|e| weather(e.into()))?;
            }
            if temperature.is_some() || pressure.is_some() {
                env.air = env
                    .air
                    .with_site_values(env.elevation_m, temperature, pressure)
                    .map_err(|e| environment(e.into()))?;
            }
            if drawn || temperature.is_some() || pressure.is_some() {
                if let Some(table) = ctx.air_table.and_then(|find| find(&env.air)) {
                    self.air_table_candidate(table);
                }
            }
            if let Some(v) = get(ElevationM) {
                env.elevation_m = v;
                env.gravity = env
                    .gravity
                    .at_launch_elevation(v)
                    .map_err(|e| environment(e.into()))?;
            }
            let turbulence = get(WindTurbulenceIntensity).unwrap_or(base_turbulence);
            if get(WindSpeedMS).is_some() || get(WindFromDeg).is_some() {
                let (speed, from) = env
                    .wind
                    .constant_parts()
                    .ok_or_else(|| setup(SetupError::WindIsATable))?;
                env.wind = Wind::constant(
                    get(WindSpeedMS).unwrap_or(speed),
                    get(WindFromDeg).unwrap_or(from),
                )
                .map_err(|e| setup(SetupError::Wind(e)))?;
            }
            env.wind = env
                .wind
                .transformed(
                    get(WindScale).unwrap_or(scale),
                    get(WindRotationDeg).unwrap_or(rotation),
                )
                .and_then(|w| w.with_turbulence(turbulence))
                .map_err(|e| site(e.into()))?;
            let mut rail = self.sim.rail;
            rail.length_m = get(RailLengthM).unwrap_or(rail.length_m);
            rail.inclination_deg = get(RailInclinationDeg).unwrap_or(rail.inclination_deg);
            rail.heading_deg = get(RailHeadingDeg).unwrap_or(rail.heading_deg);
            self.site(env, rail)?;
        }
        // The motor's impulse and burn time as scales of its own thrust curve's.
        if let Some(v) = get(MotorDryMassKg) {
            let o = self.sim.motor_options;
            self.motor_scales(MotorOptions {
                dry_mass_kg: Some(v),
                ..o
            })?;
        }
        let impulse = get(MotorImpulseNs).map(|v| v / self.sim.motor.total_impulse_ns());
        let burn = get(MotorBurnTimeS).map(|v| v / self.sim.motor.burn_time_s());
        if impulse.is_some() || burn.is_some() {
            let o = self.sim.motor_options;
            self.motor_scales(
                o.with_impulse_scale(impulse.unwrap_or(o.impulse_scale))
                    .with_time_scale(burn.unwrap_or(o.time_scale)),
            )?;
        }
        if let Some(v) = get(DragScale) {
            self.drag_scale(v)?;
        }
        if let Some(v) = get(AirBrakesTargetM) {
            self.air_brakes_target(v)?;
        }
        if let Some(m) = get(BallastKg) {
            self.part_mass(ctx.part.unwrap_or_default(), m)?;
        }
        // The structure's mass and center as changes from the design's.
        let dry = self.sim.tables.dry;
        let delta_mass = get(StructureMassKg).map(|m| m - dry.mass_kg);
        let delta_cg = get(StructureCgM).map(|x| x - dry.cg_m.x);
        if delta_mass.is_some() || delta_cg.is_some() {
            self.mass_adjustment(delta_mass.unwrap_or(0.0), delta_cg.unwrap_or(0.0))?;
        }
        let mut chutes = self.sim.parachutes.clone();
        let mut changed = judge_again && !chutes.is_empty();
        for (k, p) in chutes.iter_mut().enumerate() {
            if let Some(v) = get(ParachuteCdsM2(k)) {
                p.cds_m2 = v;
                changed = true;
            }
            if let Some(v) = get(ParachuteLagS(k)) {
                p.lag_s = v;
                changed = true;
            }
            if let Some(v) = get(ParachuteTrigger(k)) {
                p.trigger = with_number(p.trigger, v, TriggerOwner::Parachute, k)?;
                changed = true;
            }
        }
        if changed {
            self.parachutes(chutes)?;
        }
        let mut shifts = self.sim.shifts.clone();
        let mut changed = judge_again && !shifts.is_empty();
        for (k, s) in shifts.iter_mut().enumerate() {
            if let Some(v) = get(ShiftTravelM(k)) {
                s.travel_m = v;
                changed = true;
            }
            if let Some(v) = get(ShiftDurationS(k)) {
                s.duration_s = v;
                changed = true;
            }
            if let Some(v) = get(ShiftTrigger(k)) {
                s.trigger = with_number(s.trigger, v, TriggerOwner::Shift, k)?;
                changed = true;
            }
        }
        if changed {
            self.shifts(shifts)?;
        }
        let mut releases = self.sim.releases.clone();
        let mut changed = false;
        for (k, r) in releases.iter_mut().enumerate() {
            if let Some(v) = get(ReleaseTrigger(k)) {
                r.trigger = with_number(r.trigger, v, TriggerOwner::Release, k)?;
                changed = true;
            }
            if let Some(v) = get(ReleaseCdaM2(k)) {
                r.cda_m2 = Some(v);
                changed = true;
            }
            let cds = get(ReleaseChuteCdsM2(k));
            let lag = get(ReleaseChuteLagS(k));
            if cds.is_some() || lag.is_some() {
                let chute = r
                    .parachute
                    .as_mut()
                    .ok_or_else(|| setup(SetupError::ReleaseWithoutChute { index: k }))?;
                chute.cds_m2 = cds.unwrap_or(chute.cds_m2);
                chute.lag_s = lag.unwrap_or(chute.lag_s);
                changed = true;
            }
        }
        if changed {
            self.releases(releases)?;
        }
        Ok(())
    }
}
