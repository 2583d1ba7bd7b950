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

use super::{MassAdjustment, Parachute, Rail, SimError, SimOptions, Simulation};
use crate::atmosphere::AirTable;
use crate::flight::{model, Environment};
use crate::releases::Release;
use crate::shifts::{self, MassShift};
use crate::trigger::Trigger;
use hpr_design::motor::MotorOptions;
use hpr_design::{mass, MAX_SAMPLING_RATE_HZ};
use std::sync::Arc;

/// A flight being changed: every setter checks its input as the matching `with_*` builder
/// does and records it; [`Simulation::with_changes`] rebuilds the model once at the end.
#[derive(Debug)]
pub struct Changes<'a> {
    sim: &'a mut Simulation,
}

impl Simulation {
    /// Apply the changes `f` makes, then rebuild the flight's model once. The first refused
    /// change is the error (its message is the matching `with_*` builder's).
    pub fn with_changes(
        mut self,
        f: impl FnOnce(&mut Changes<'_>) -> Result<(), SimError>,
    ) -> Result<Simulation, SimError> {
        f(&mut Changes { sim: &mut self })?;
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
            let what = format!("parachute {i} (\"{}\")", p.name);
            if !(p.cds_m2.is_finite() && p.cds_m2 > 0.0) {
                return Err(SimError::Setup(format!(
                    "{what}: field \"cds_m2\" must be positive and finite (got {})",
                    p.cds_m2
                )));
            }
            if !(p.lag_s.is_finite() && p.lag_s >= 0.0) {
                return Err(SimError::Setup(format!(
                    "{what}: field \"lag_s\" must be finite and not negative (got {})",
                    p.lag_s
                )));
            }
            if let Some(rate) = p.sampling_rate_hz {
                if !(rate.is_finite() && rate > 0.0 && rate <= MAX_SAMPLING_RATE_HZ) {
                    return Err(SimError::Setup(format!(
                        "{what}: field \"sampling_rate_hz\" must be positive, at most {MAX_SAMPLING_RATE_HZ} Hz (got {rate})"
                    )));
                }
            }
            if let Some(noise) = &p.noise {
                noise.check().map_err(|(field, rule, got)| {
                    SimError::Setup(format!(
                        "{what}: noise field \"{field}\" {rule} (got {got})"
                    ))
                })?;
                if p.sampling_rate_hz.is_none() {
                    return Err(SimError::Setup(format!("{what}: a noisy pressure is read at samples: field \"sampling_rate_hz\" is needed with \"noise\" (RocketPy's default is 100 Hz)")));
                }
            }
            p.canopy.check().map_err(|(field, rule)| {
                SimError::Setup(format!("{what}: canopy field \"{field}\" {rule}"))
            })?;
            p.trigger
                .validate()
                .map_err(|e| SimError::Setup(format!("{what}: {e}")))?;
            match p.trigger {
                Trigger::HeightDescending { height_m } if height_m <= 0.0 => {
                    return Err(SimError::Setup(format!("{what}: trigger {}: the height must be above the ground, or the canopy never opens", p.trigger)));
                }
                Trigger::BurnoutPlusDelay { delay_s: None } if delay.is_none() => {
                    return Err(SimError::Setup(format!("{what}: trigger {}: the motor is plugged (no ejection delay), so this trigger never fires", p.trigger)));
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
            return Err(SimError::Setup(format!(
                "at most {} shifts in one flight (got {})",
                model::MAX_SHIFTS,
                shifts.len()
            )));
        }
        let plan = shifts::plan(
            &self.sim.design,
            &shifts,
            self.sim.motor.delays_s.first().copied(),
        )?;
        if plan.parts.len() > model::MAX_MOVING_PARTS {
            return Err(SimError::Setup(format!(
                "at most {} parts may move in one flight (got {})",
                model::MAX_MOVING_PARTS,
                plan.parts.len()
            )));
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
            return Err(SimError::Setup(format!(
                "at most {} releases in one flight (got {})",
                model::MAX_RELEASES,
                releases.len()
            )));
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
        options.validate().map_err(SimError::Setup)?;
        self.sim.options = options;
        Ok(())
    }

    /// See [`Simulation::with_part_mass`].
    pub fn part_mass(&mut self, component: &str, mass_kg: f64) -> Result<(), SimError> {
        let bad = |rule: String| SimError::Setup(format!("part mass of \"{component}\": {rule}"));
        let design = &self.sim.design;
        let idx = design
            .component_index(component)
            .ok_or_else(|| bad("the design has no such component".into()))?;
        if !(mass_kg.is_finite() && mass_kg > 0.0) {
            return Err(bad(format!(
                "mass_kg must be positive and finite (got {mass_kg})"
            )));
        }
        let c = &design.components[idx];
        if c.is_body() || c.is_external() {
            return Err(bad(
                "only an internal part's mass can change this way".into()
            ));
        }
        let hidden = c.overrides.mass_kg.is_some()
            || design.stages[c.stage].overrides.mass_kg.is_some()
            || std::iter::successors(c.parent, |&p| design.components[p].parent).any(|p| {
                let o = &design.components[p].overrides;
                o.mass_kg.is_some() && o.covers_children
            });
        if hidden {
            return Err(bad(
                "a mass override (its own, its stage's or a holder's) hides its mass".into(),
            ));
        }
        // The new mass scales the part's own (with what it holds): a part that weighs nothing
        // has no mass distribution to scale (0/0 would poison the flight with NaN).
        let own = mass::subtree(design, idx).mass_kg;
        if !(own.is_finite() && own > 0.0) {
            return Err(bad(format!(
                "it weighs {own} kg in the design, so it has no mass to scale; give it a mass in the design"
            )));
        }
        self.sim.part_masses.retain(|(i, _)| *i != idx);
        self.sim.part_masses.push((idx, mass_kg));
        Ok(())
    }

    /// See [`Simulation::with_drag_scale`].
    pub fn drag_scale(&mut self, scale: f64) -> Result<(), SimError> {
        if !(scale.is_finite() && scale > 0.0) {
            return Err(SimError::Setup(format!(
                "drag scale must be positive and finite (got {scale})"
            )));
        }
        self.sim.drag_scale = scale;
        Ok(())
    }

    /// See [`Simulation::with_air_brakes_target`].
    pub fn air_brakes_target(&mut self, target_apogee_m: f64) -> Result<(), SimError> {
        if self.sim.design.air_brakes.is_none() {
            return Err(SimError::Setup(format!(
                "design \"{}\" has no air brakes to aim",
                self.sim.design.name
            )));
        }
        if !(target_apogee_m.is_finite() && target_apogee_m > 0.0) {
            return Err(SimError::Setup(format!(
                "air brakes: the target apogee must be positive and finite (got {target_apogee_m})"
            )));
        }
        self.sim.brake_target_m = Some(target_apogee_m);
        Ok(())
    }

    /// See [`Simulation::with_mass_adjustment`].
    pub fn mass_adjustment(&mut self, delta_mass_kg: f64, delta_cg_m: f64) -> Result<(), SimError> {
        // The shared tables hold `mass::dry` of this very design (no change touches it).
        let dry = self.sim.tables.dry.mass_kg;
        if !(delta_mass_kg.is_finite() && delta_cg_m.is_finite()) || dry + delta_mass_kg <= 0.0 {
            return Err(SimError::Setup(format!("mass adjustment: delta_mass_kg {delta_mass_kg} and delta_cg_m {delta_cg_m} must be finite and leave a positive mass (structure {dry} kg)")));
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
