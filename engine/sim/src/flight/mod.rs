//! The single-flight simulator: [`Simulation`] sets a flight up (design, motor, launch site,
//! rail, parachutes, shifts, options), checks every input, builds the [`FlightModel`]'s tables
//! once, and flies it with [`Simulation::run`]. Changes to a flight set up (the `with_*`
//! builders, or many at once with [`Simulation::with_changes`]) are checked in [`changes`]
//! and rebuild only the light per-flight model; the design's tables are shared by `Arc`.
//!
//! The flight's physics lives in the kernels ([`crate::eom`], [`crate::massprops`],
//! [`crate::aero_loads`], [`crate::cycloid`], the atmosphere); this module only assembles
//! them and drives the integrator (see [`driver`]). The batch engine drives the same model.

pub mod changes;
pub mod config;
pub mod driver;
pub mod model;
pub mod output;
pub mod setup_error;

pub use changes::Changes;
pub use config::{
    rk4_steps_rule, AirModel, CanopyShape, Environment, Integrator, Parachute, Rail, SimOptions,
    MAX_INPUT_STEPS,
};
pub use model::FlightModel;
pub use output::{
    Flight, Metrics, Observer, PartFlight, PartSample, Phase, ReleaseRecord, Sample, Warning,
    LARGE_ALPHA_DEG,
};
pub use setup_error::{
    Bound, OptionsRule, ParachuteRule, PartMassRule, SetupError, SiteFault, TriggerOwner,
};

use crate::aero_loads::{AeroTables, SurfaceTable};
use crate::atmosphere::{AirTable, Atmosphere};
use crate::eom::{self, Nozzle};
use crate::integrate::{IntegratorError, RootError};
use crate::massprops::MassModel;
use crate::releases::{Release, ReleasePlan, ReleaseRefusal};
use crate::shifts::{MassShift, ShiftPlan, ShiftRefusal};
use hpr_design::aero::{AeroModel, MachTable};
use hpr_design::design::model::Design;
use hpr_design::mass::{self, MassProps};
use hpr_design::motor::{Motor, MotorOptions, MotorTables};
use std::sync::Arc;

/// Why a flight could not be set up or flown.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// An input of the flight breaks a rule (which input, the value, the bound).
    #[error(transparent)]
    Setup(#[from] SetupError),
    #[error(transparent)]
    Shift(#[from] ShiftRefusal),
    #[error(transparent)]
    Release(#[from] ReleaseRefusal),
    #[error("motor: {0}")]
    Motor(#[from] hpr_design::motor::MotorError),
    /// The motor is wider than its mount or longer than the room it has (the design's words).
    #[error("{0}")]
    MotorDoesNotFit(String),
    #[error("aerodynamics: {0}")]
    Aero(#[from] hpr_design::aero::AeroError),
    #[error("the motor's thrust never beats the rocket's weight along the rail (peak thrust {max_thrust_n:.1} N, weight along the rail {weight_n:.1} N): the rocket never leaves the pad")]
    NeverLeavesPad { max_thrust_n: f64, weight_n: f64 },
    #[error("shift {index} would start at t = {time_s:.4} s, before the rocket leaves the rail; the rail has no stop at its foot, so a part thrown toward the tail on the pad could push the rocket up the rail and leave it hanging there; time the shift from the burnout or the apogee instead")]
    ShiftBeforeRailExit { index: usize, time_s: f64 },
    #[error("release {index} would fire at t = {time_s:.4} s, before the rocket leaves the rail; a part dropped on the rail would fall through the airframe's guides, which the flight does not model; time the release from the burnout or the apogee instead")]
    ReleaseBeforeRailExit { index: usize, time_s: f64 },
    #[error("release {index} fires at t = {time_s:.4} s while shift {shift} is still moving its part (from {start_s:.4} s for {duration_s} s); a part leaves from rest in the airframe: time the release after the move ends")]
    ReleaseDuringShift {
        index: usize,
        shift: usize,
        time_s: f64,
        start_s: f64,
        duration_s: f64,
    },
    #[error("shift {index} would start at t = {time_s:.4} s, after release {release} dropped its part at {released_s:.4} s; there is nothing left to move")]
    ShiftAfterRelease {
        index: usize,
        release: usize,
        time_s: f64,
        released_s: f64,
    },
    #[error("the flight went non-finite at t = {time_s} s; state {state}")]
    NonFinite { time_s: f64, state: String },
    /// An event (apogee, a height, the rail's end, a part's landing) could not be located
    /// within a step.
    #[error("event location failed: {0}")]
    EventLocation(#[source] RootError),
    /// The moment the thrust first beats the weight along the rail could not be located.
    #[error("liftoff: {0}")]
    Liftoff(#[source] RootError),
    /// A released part's descent was asked for before the part left.
    #[error("release {index} never left")]
    ReleaseNeverLeft { index: usize },
    /// A flight on a fixed step (RK4) was stepped by the batch's lanes, which step the
    /// adaptive integrators only.
    #[error("a fixed-step flight was stepped on lanes")]
    FixedStepOnLanes,
    #[error("integration failed in the {phase} phase at t = {time_s} s: {source}")]
    Integration {
        time_s: f64,
        phase: String,
        #[source]
        source: IntegratorError,
    },
}

/// A flight, set up and checked, ready to run.
#[derive(Debug, Clone)]
pub struct Simulation {
    /// The design and the motor, shared by the flights made from this one (a batch's lanes
    /// clone the base for each variant; a new design or motor replaces the whole).
    design: Arc<Design>,
    motor: Arc<Motor>,
    motor_options: MotorOptions,
    env: Environment,
    rail: Rail,
    parachutes: Vec<Parachute>,
    shifts: Vec<MassShift>,
    plan: ShiftPlan,
    releases: Vec<Release>,
    release_plan: ReleasePlan,
    options: SimOptions,
    drag_scale: f64,
    mass_adjustment: MassAdjustment,
    part_masses: Vec<(usize, f64)>,
    tables: Arc<DesignTables>,
    /// The seed of the flight computers' sensor noise ([`Simulation::with_sensor_seed`]).
    sensor_seed: u64,
    /// The air brakes' target apogee in place of the design's
    /// ([`Simulation::with_air_brakes_target`]).
    brake_target_m: Option<f64>,
    model: FlightModel,
}

/// A change to the rocket's structure (everything but the motor): its mass changes by
/// `delta_mass_kg` (inertia scaled in proportion) and its center of mass moves by
/// `delta_cg_m` (positive aft). Used for dispersions of mass and center of mass.
///
/// The parts that shifts move or releases drop stay where the design puts them (on their
/// holders, where the shifts' travel is measured from, and what a release takes out): the
/// change is made by the rest of the structure ([`MassAdjustment::apply_holding`]), so that
/// the flight's split of the mass into what is fixed, what moves and what leaves describes
/// one body whose inertia is never negative, before and after a part leaves.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MassAdjustment {
    pub delta_mass_kg: f64,
    pub delta_cg_m: f64,
}

impl MassAdjustment {
    /// Apply to the structure's mass properties.
    pub fn apply(&self, dry: &MassProps) -> MassProps {
        let m = dry.mass_kg + self.delta_mass_kg;
        MassProps {
            mass_kg: m,
            cg_m: dry.cg_m + nalgebra::Vector3::new(self.delta_cg_m, 0.0, 0.0),
            // A structure that weighs nothing (its parts' masses all zero) has no inertia to
            // scale, and 0/0 would poison the flight with NaN.
            inertia_cg: if dry.mass_kg > 0.0 {
                dry.inertia_cg * (m / dry.mass_kg)
            } else {
                dry.inertia_cg
            },
        }
    }

    /// Apply to the structure `dry` (station frame) that holds `held`, the parts that shifts
    /// move or releases drop, each where the design puts it. The result has [`MassAdjustment::apply`]'s mass
    /// and center of mass, bit for bit, but the change is made by the rest of the structure
    /// alone, which gains the mass (its inertia scaled in proportion) and moves rigidly as far
    /// as the whole's center must move; the held parts keep their places. Moving the whole
    /// structure instead would carry the held parts along in its inertia while the flight
    /// keeps them where the design puts them: the rest would be left with a negative moment
    /// of inertia once the center moved far enough, and the rocket's inertia about its center
    /// of mass could pass through zero as a part moves (a singular rigid body, whose angular
    /// acceleration has a pole there). Without held parts, or without a change, it is
    /// [`MassAdjustment::apply`] bit for bit. The error says why the rest cannot make the
    /// change (it would be left without mass).
    pub fn apply_holding(
        &self,
        dry: &MassProps,
        held: &[MassProps],
    ) -> Result<MassProps, SetupError> {
        if held.is_empty() || *self == MassAdjustment::default() {
            return Ok(self.apply(dry));
        }
        let held = held
            .iter()
            .fold(MassProps::ZERO, |sum, part| sum.combine(part));
        let rest = dry.combine(&held.scaled(-1.0));
        let whole = self.apply(dry);
        let m = rest.mass_kg + self.delta_mass_kg;
        if !(rest.mass_kg > 0.0 && m > 0.0) {
            return Err(SetupError::MassAdjustmentHeld {
                rest_kg: rest.mass_kg,
                after_kg: m,
                delta_mass_kg: self.delta_mass_kg,
            });
        }
        // The whole's first moment, less the held parts', placed on the rest.
        let moved = MassProps {
            mass_kg: m,
            cg_m: (whole.cg_m * whole.mass_kg - held.cg_m * held.mass_kg) / m,
            inertia_cg: rest.inertia_cg * (m / rest.mass_kg),
        };
        // The mass and center are the whole's as `apply` gives them, to the last bit; only
        // the inertia about that center is the two bodies'.
        Ok(MassProps {
            inertia_cg: moved.inertia_about(&whole.cg_m) + held.inertia_about(&whole.cg_m),
            ..whole
        })
    }
}

impl Simulation {
    /// Set up a flight of `design` on `motor` from `rail` at the site `env`.
    pub fn new(
        design: Design,
        motor: Motor,
        env: Environment,
        rail: Rail,
    ) -> Result<Simulation, SimError> {
        Self::with_motor_options(design, motor, MotorOptions::default(), env, rail)
    }

    /// As [`Simulation::new`], with the motor's propellant/dry mass overrides or scales.
    pub fn with_motor_options(
        design: Design,
        motor: Motor,
        motor_options: MotorOptions,
        env: Environment,
        rail: Rail,
    ) -> Result<Simulation, SimError> {
        let plan = ShiftPlan {
            parts: vec![],
            part_of_shift: vec![],
        };
        let tables = Arc::new(DesignTables::new(&design)?);
        let air = air_table(&env, None)?;
        let mut model = build_model(
            &design,
            &motor,
            &motor_options,
            &env,
            &rail,
            &[],
            &[],
            &plan,
            &[],
            &ReleasePlan::default(),
            &SimOptions::default(),
            1.0,
            &MassAdjustment::default(),
            &[],
            &tables,
            air,
        )?;
        model.set_noise_seed(0);
        Ok(Simulation {
            design: Arc::new(design),
            motor: Arc::new(motor),
            motor_options,
            env,
            rail,
            parachutes: vec![],
            shifts: vec![],
            plan,
            releases: vec![],
            release_plan: ReleasePlan::default(),
            options: SimOptions::default(),
            drag_scale: 1.0,
            mass_adjustment: MassAdjustment::default(),
            part_masses: vec![],
            tables,
            sensor_seed: 0,
            brake_target_m: None,
            model,
        })
    }

    fn rebuild(mut self) -> Result<Simulation, SimError> {
        // The releases' rules read the shifts' parts: checked here, after every change, so
        // that the order of the changes never changes a verdict.
        if self.releases.len() + self.shifts.len() > model::MAX_SHIFTS {
            return Err(SimError::Setup(SetupError::TooManyShiftsAndReleases {
                max: model::MAX_SHIFTS,
                shifts: self.shifts.len(),
                releases: self.releases.len(),
            }));
        }
        self.release_plan = if self.releases.is_empty() {
            ReleasePlan::default()
        } else {
            crate::releases::plan(
                &self.design,
                &self.releases,
                &self.plan,
                self.motor.delays_s.first().copied(),
            )?
        };
        let air = air_table(&self.env, Some(&self.model.air))?;
        self.model = build_model(
            &self.design,
            &self.motor,
            &self.motor_options,
            &self.env,
            &self.rail,
            &self.parachutes,
            &self.shifts,
            &self.plan,
            &self.releases,
            &self.release_plan,
            &self.options,
            self.drag_scale,
            &self.mass_adjustment,
            &self.part_masses,
            &self.tables,
            air,
        )?;
        self.model.set_noise_seed(self.sensor_seed);
        if let (Some(target), Some(b)) = (self.brake_target_m, self.model.air_brakes.as_mut()) {
            b.target_apogee_m = target;
        }
        Ok(self)
    }

    /// Parachutes, opened in the order their triggers fire. Canopies add up: once a second
    /// canopy opens, both drag (their CdS add), as a drogue left attached above a main does.
    pub fn with_parachutes(self, parachutes: Vec<Parachute>) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.parachutes(parachutes))
    }

    /// Mass shifts ([`MassShift`], rules in `docs/moving-mass.md`). Every rule that can be
    /// checked before the flight is checked here, and a refusal names the rule it broke.
    pub fn with_shifts(self, shifts: Vec<MassShift>) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.shifts(shifts))
    }

    /// Releases: parts that leave the rocket in flight and fall on their own. Every rule
    /// that can be checked before the flight is checked here (with the shifts already set:
    /// set the shifts first), and a refusal names the rule it broke.
    pub fn with_releases(self, releases: Vec<Release>) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.releases(releases))
    }

    /// The seed of the noise the parachutes' flight computers read (those given a
    /// [`Parachute::noise`]; 0 unless set) and of the wind's gusts (a wind with turbulence,
    /// [`crate::turbulence`]): flights that differ only by it see different noise, and the
    /// same seed gives the same noise (see [`crate::sensor`]). A campaign gives
    /// each variant its own from the scenario's seed.
    pub fn with_sensor_seed(mut self, seed: u64) -> Simulation {
        self.sensor_seed = seed;
        self.model.set_noise_seed(seed);
        self
    }

    /// Integrator and limits.
    pub fn with_options(self, options: SimOptions) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.options(options))
    }

    /// Give the part `component` (and what it holds, scaled alike) a mass of `mass_kg`, as a
    /// dispersion of a ballast or payload does, without rebuilding the design. Refused for a
    /// part whose mass an override hides, a body component or an external part.
    pub fn with_part_mass(self, component: &str, mass_kg: f64) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.part_mass(component, mass_kg))
    }

    /// Multiply the drag coefficient by `scale` (a dispersion).
    pub fn with_drag_scale(self, scale: f64) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.drag_scale(scale))
    }

    /// Aim the design's air brakes at another apogee, m above the site (a sweep of the
    /// controller's setting). Refused for a design without air brakes.
    pub fn with_air_brakes_target(self, target_apogee_m: f64) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.air_brakes_target(target_apogee_m))
    }

    /// Change the structure's mass and center of mass (a dispersion, see [`MassAdjustment`]).
    pub fn with_mass_adjustment(
        self,
        delta_mass_kg: f64,
        delta_cg_m: f64,
    ) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.mass_adjustment(delta_mass_kg, delta_cg_m))
    }

    /// Change the launch site and the rail (a dispersion of the wind, elevation or rail).
    pub fn with_site(self, env: Environment, rail: Rail) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.site(env, rail))
    }

    /// Change the motor's options (its impulse and time scales, its masses).
    pub fn with_motor_scales(self, options: MotorOptions) -> Result<Simulation, SimError> {
        self.with_changes(|c| c.motor_scales(options))
    }

    pub fn environment(&self) -> &Environment {
        &self.env
    }
    pub fn rail(&self) -> &Rail {
        &self.rail
    }
    pub fn parachutes(&self) -> &[Parachute] {
        &self.parachutes
    }
    pub fn motor_options(&self) -> &MotorOptions {
        &self.motor_options
    }

    pub fn options(&self) -> &SimOptions {
        &self.options
    }

    pub fn design(&self) -> &Design {
        &self.design
    }
    pub fn motor(&self) -> &Motor {
        &self.motor
    }
    pub fn model(&self) -> &FlightModel {
        &self.model
    }
    pub fn shifts(&self) -> &[MassShift] {
        &self.shifts
    }
    pub fn releases(&self) -> &[Release] {
        &self.releases
    }
    /// Each release's part (component index), and its drag area falling free, m².
    pub fn release_plan(&self) -> &ReleasePlan {
        &self.release_plan
    }

    /// Fly. The observer sees every sample and event as it happens (`&mut ()` sees nothing).
    pub fn run<O: Observer>(&self, observer: &mut O) -> Result<Flight, SimError> {
        driver::run(&self.model, observer)
    }

    /// Fly in free flight from the 6-DOF state `y0` at time `t0` (no pad, no rail; shifts may
    /// start at once). The state is O's position and velocity (inertial), the attitude
    /// quaternion and the body rates, as [`crate::eom`] lays them out.
    pub fn run_from<O: Observer>(
        &self,
        observer: &mut O,
        t0: f64,
        y0: &[f64; crate::eom::N6],
    ) -> Result<Flight, SimError> {
        driver::run_from(&self.model, observer, t0, y0)
    }

    /// Mass properties at `t_s` with every part where the design puts it (no shift), station frame.
    pub fn mass_properties_at(&self, t_s: f64) -> MassProps {
        crate::massprops::to_station(
            &self
                .model
                .instant(&[f64::INFINITY; model::MAX_SHIFTS], t_s)
                .mass,
        )
    }

    /// Static margin, calibres, for a center of mass `cg_m` aft of the tip.
    pub fn static_margin_for(&self, cg_m: f64) -> f64 {
        (self.model.cp_mach0_m - cg_m) / self.model.ref_diameter_m
    }

    /// The rocket's mass, center of mass (m aft of the tip) and inertia about that center at
    /// time `t_s` of `flight`, in the design's station frame. At a release's own instant the
    /// part has left (what remains).
    pub fn mass_properties(&self, flight: &Flight, t_s: f64) -> MassProps {
        crate::massprops::to_station(&self.model.instant(&flight.starts(), t_s).mass)
    }
}

/// What a flight needs from the design alone, built once per design and shared (by `Arc`) by
/// every flight of it: the structure's mass properties (shape integrals) and the aerodynamic
/// tables.
#[derive(Debug, Clone)]
pub struct DesignTables {
    /// Everything but the motor, every part where the design puts it (station frame).
    pub dry: MassProps,
    pub aero: Arc<AeroTables>,
}

impl DesignTables {
    pub fn new(design: &Design) -> Result<DesignTables, SimError> {
        let aero_model = AeroModel::from_design(design)?;
        let aero = AeroTables {
            ref_area_m2: aero_model.ref_area_m2,
            ref_diameter_m: aero_model.ref_diameter_m,
            surfaces: aero_model
                .surfaces
                .iter()
                .map(|s| SurfaceTable {
                    x_cp_m: s.x_cp_m,
                    cn_alpha: s.cn_alpha.clone(),
                })
                .collect(),
            cd_power_off: MachTable::from_fn(|m| aero_model.cd_power_off(m)),
            cd_power_on: MachTable::from_fn(|m| aero_model.cd_power_on(m)),
            cd_reynolds: aero_model.drag_reynolds.clone(),
            roll_forcing: MachTable::from_fn(|m| aero_model.roll_forcing_coefficient(m)),
            roll_damping: MachTable::from_fn(|m| aero_model.roll_damping_coefficient(m)),
            cp_mach0_m: aero_model.cp_m(0.0),
        };
        Ok(DesignTables {
            dry: mass::dry(design),
            aero: Arc::new(aero),
        })
    }
}

/// The air table of `env`'s atmosphere: `previous` again if it holds the same one (variants
/// made from one flight share it), else the standard's or a new one.
fn air_table(
    env: &Environment,
    previous: Option<&Arc<AirTable>>,
) -> Result<Arc<AirTable>, SimError> {
    match previous {
        Some(air) if *air.model() == env.air => Ok(air.clone()),
        _ => {
            AirTable::new(&env.air).map_err(|e| SimError::Setup(SetupError::Environment(e.into())))
        }
    }
}

/// Build every table of a flight once (`air`: the table of `env`'s atmosphere).
#[allow(clippy::too_many_arguments)]
pub fn build_model(
    design: &Design,
    motor: &Motor,
    motor_options: &MotorOptions,
    env: &Environment,
    rail: &Rail,
    parachutes: &[Parachute],
    shifts: &[MassShift],
    plan: &ShiftPlan,
    releases: &[Release],
    release_plan: &ReleasePlan,
    options: &SimOptions,
    drag_scale: f64,
    adjustment: &MassAdjustment,
    part_masses: &[(usize, f64)],
    tables: &DesignTables,
    air: Arc<AirTable>,
) -> Result<FlightModel, SimError> {
    use crate::turbulence::MAX_TURBULENT_FLIGHT_S;
    use config::MAX_INPUT_STEPS;
    if env.wind.turbulence_intensity() > 0.0 && options.max_time_s > MAX_TURBULENT_FLIGHT_S {
        return Err(SimError::Setup(SetupError::TurbulentTimeLimit {
            max_s: MAX_TURBULENT_FLIGHT_S,
            got_s: options.max_time_s,
        }));
    }
    // Each sample of a sampler (the air brakes' controller, a sampled parachute trigger)
    // ends a step: the fastest one's samples to the time limit are bounded.
    let fastest_hz = parachutes
        .iter()
        .filter_map(|p| p.sampling_rate_hz)
        .chain(design.air_brakes.map(|b| b.sampling_rate_hz))
        .fold(0.0, f64::max);
    if fastest_hz * options.max_time_s > MAX_INPUT_STEPS {
        return Err(SimError::Setup(SetupError::TooManySamples {
            rate_hz: fastest_hz,
            max_time_s: options.max_time_s,
            max_steps: MAX_INPUT_STEPS,
        }));
    }
    let mount = design.motor_mount.ok_or_else(|| {
        SimError::Setup(SetupError::NoMotorMount {
            design: design.name.clone(),
        })
    })?;
    design
        .motor_fits(motor.diameter_m, motor.length_m)
        .map_err(|e| SimError::MotorDoesNotFit(e.to_string()))?;
    let motor_tables = MotorTables::new(motor, motor_options)?.clustered(design.motor_offsets_m());
    let burnout = motor_tables.burn_time_s();
    let casing = motor_tables.casing_props(mount.motor_aft_m);
    let propellant = motor_tables.propellant_props_scaling(mount.motor_aft_m);
    // A part whose mass changes (a dispersion of the ballast, say) keeps its shape, so its
    // mass properties scale; the structure gains the difference. Mass properties are linear
    // in the mass distribution, so adding the scaled difference (negative for a lighter part)
    // is exact.
    let scale_of = |idx: usize| {
        part_masses
            .iter()
            .rev()
            .find(|(i, _)| *i == idx)
            .map(|&(_, m)| m / mass::subtree(design, idx).mass_kg)
    };
    let mut dry = tables.dry;
    for &(idx, _) in part_masses {
        let k = scale_of(idx).unwrap_or(1.0);
        dry = dry.combine(&mass::subtree(design, idx).scaled(k - 1.0));
    }
    let part_props = |idx: usize| mass::subtree(design, idx).scaled(scale_of(idx).unwrap_or(1.0));
    let parts: Vec<MassProps> = plan.parts.iter().map(|&idx| part_props(idx)).collect();
    let released: Vec<(MassProps, Option<usize>)> = release_plan
        .parts
        .iter()
        .zip(&release_plan.moving_part)
        .map(|(&idx, &moving)| (part_props(idx), moving))
        .collect();
    // The parts that move or leave keep their places when the structure's mass changes (a
    // part both moved and released once).
    let held: Vec<MassProps> = parts
        .iter()
        .copied()
        .chain(
            released
                .iter()
                .filter(|(_, moving)| moving.is_none())
                .map(|(p, _)| *p),
        )
        .collect();
    let dry = adjustment.apply_holding(&dry, &held)?;
    let mut mass_model = MassModel::new(&dry, &casing, &propellant, &parts, &released);
    mass_model.grains = motor_tables.grains().map(|g| (*g, motor_tables.motors()));
    let fixed_cg_m = dry.combine(&casing).cg_m.x;
    let nozzle = Nozzle::at(
        mount.motor_aft_m,
        motor_tables.nozzle_radius_m(),
        mount.motor_aft_m - fixed_cg_m,
    )
    .clustered(design.motor_offsets_m());

    // Checks the site elevation (the flight reads the shared table) and latitude.
    Atmosphere::standard(env.elevation_m)
        .map_err(|e| SimError::Setup(SetupError::Environment(e.into())))?;
    env.validate()?;
    let aft_m = design.length_m.max(mount.motor_aft_m);
    let rail_geo = model::rail_geometry(rail, aft_m, design.rail_guides_m.map(|(upper, _)| upper))?;
    let knots: Vec<f64> = motor_tables
        .times_s()
        .iter()
        .copied()
        .filter(|&t| t > 0.0 && t < burnout)
        .collect();
    Ok(FlightModel {
        mass_lanes: crate::massprops::MassModelLanes::of(&mass_model),
        mass: mass_model,
        nozzle,
        aero: tables.aero.clone(),
        drag_scale,
        air,
        env: env.clone(),
        earth_rate_n: env.earth_rate_n(),
        rail: rail_geo,
        parachutes: parachutes.to_vec(),
        canopies: parachutes
            .iter()
            .map(|p| eom::Canopies {
                cds_m2: p.cds_m2,
                added_air_m3: p.canopy.added_air_volume_m3(p.cds_m2),
            })
            .collect(),
        shifts: model::shift_specs(shifts, plan),
        releases: model::release_specs(releases, release_plan),
        options: *options,
        burnout_s: burnout,
        motor_delay_s: motor.delays_s.first().copied(),
        thrust_knots_s: knots,
        ref_diameter_m: tables.aero.ref_diameter_m,
        cp_mach0_m: tables.aero.cp_mach0_m,
        motor: motor_tables,
        settled: Vec::new(),
        sensor_seed: 0,
        // Drawn by `set_noise_seed`, once the flight's seed is known.
        gusts: None,
        air_brakes: design.air_brakes.map(|b| model::BrakeModel {
            cd_open: b.cd * b.reference_area_m2 / tables.aero.ref_area_m2,
            target_apogee_m: b.target_apogee_m,
            period_s: 1.0 / b.sampling_rate_hz,
        }),
    }
    .with_settled_states())
}
