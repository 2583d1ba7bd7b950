//! A flight's values ([`Setup`]: the nominals, or a variant's with its sampled inputs checked
//! against their ranges) and what turns them into flights ([`Fixed`]): the base simulation,
//! built once from scratch, and the batch engine's columns for the lanes.

use super::super::params::Param;
use super::super::scenario::{with_trigger_value, Scenario};
use hpr_design::design::model::Design;
use hpr_design::motor::{Motor, MotorOptions};
use hpr_sim::batch::Columns;
use hpr_sim::flight::{SetupError, SiteFault};
use hpr_sim::inputs::{Part, Slot, GLOBAL_COUNT};
use hpr_sim::wind::Wind;
use hpr_sim::{
    Environment, MassShift, Parachute, PartChute, Rail, Release, SimError, SimOptions, Simulation,
};

/// Every flight's values, nominal or a variant's: one per input of the flight
/// ([`hpr_sim::inputs`]), held where the input's [`Slot`] says.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Setup {
    /// The inputs of the flight as a whole, in [`hpr_sim::inputs::GLOBAL`] order (NaN for
    /// one the scenario's flight does not have: a ballast, air brakes or a weather file).
    pub(super) globals: [f64; GLOBAL_COUNT],
    /// Per parachute, shift and release: its inputs in [`Part::fields`] order (a trigger's
    /// number NaN if it has none; a release's parachute's NaN without a parachute).
    pub(super) parachutes: Vec<[f64; 3]>,
    pub(super) shifts: Vec<[f64; 3]>,
    pub(super) releases: Vec<[f64; 4]>,
    /// Per dimension of the design the scenario varies: its value.
    pub(super) design: Vec<f64>,
    /// The seed of the parachutes' barometer noise (the variant's own; 0 for the nominal).
    pub(super) sensor_seed: u64,
}

impl Setup {
    fn slot(&mut self, p: Param) -> &mut f64 {
        match p.slot() {
            Slot::Global(i) => &mut self.globals[i],
            Slot::Design(k) => &mut self.design[k],
            Slot::Part(Part::Parachute, k, f) => &mut self.parachutes[k][f],
            Slot::Part(Part::Shift, k, f) => &mut self.shifts[k][f],
            Slot::Part(Part::Release, k, f) => &mut self.releases[k][f],
        }
    }

    pub(super) fn get(&self, p: Param) -> f64 {
        match p.slot() {
            Slot::Global(i) => self.globals[i],
            Slot::Design(k) => self.design[k],
            Slot::Part(Part::Parachute, k, f) => self.parachutes[k][f],
            Slot::Part(Part::Shift, k, f) => self.shifts[k][f],
            Slot::Part(Part::Release, k, f) => self.releases[k][f],
        }
    }

    pub(super) fn set(&mut self, p: Param, v: f64) {
        *self.slot(p) = v;
    }
}

/// What a flight needs besides its setup: the scenario's fixed parts, the design, the motor
/// and the nominals.
pub(super) struct Fixed<'a> {
    pub(super) scenario: &'a Scenario,
    pub(super) design: &'a Design,
    pub(super) motor: &'a Motor,
    pub(super) nominal: &'a Setup,
}

impl Fixed<'_> {
    /// The nominal setup with the plan's inputs set to `values`, each checked against its
    /// range (the error names the input and the rule).
    pub(super) fn setup(&self, values: &[f64]) -> Result<Setup, String> {
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

    /// The simulation of a setup, built from scratch (the base of the lanes).
    pub(super) fn simulation(&self, s: &Setup) -> Result<Simulation, SimError> {
        let err = |e: SiteFault| SimError::Setup(SetupError::Site(e));
        let site = &self.scenario.environment;
        let gravity = site.gravity.at_site(
            site.latitude_deg,
            s.get(Param::ElevationM),
            "environment.latitude_deg",
        )?;
        // A launch time or member of its own: the weather file's air and wind then.
        let drawn = self.drawn_weather(s).map_err(|e| err(e.into()))?;
        let base_air = match &drawn {
            Some(w) => w.air_model(),
            None => site.air.clone(),
        };
        let air = if (s.get(Param::TemperatureK), s.get(Param::PressurePa))
            == (
                self.nominal.get(Param::TemperatureK),
                self.nominal.get(Param::PressurePa),
            ) {
            base_air
        } else {
            // The air of the scenario's site, at this setup's temperature and pressure.
            base_air
                .with_site_values(
                    site.elevation_m,
                    Some(s.get(Param::TemperatureK)),
                    Some(s.get(Param::PressurePa)),
                )
                .map_err(|e| err(e.into()))?
        };
        let wind = match &drawn {
            Some(w) => w
                .wind()
                .and_then(|w| w.transformed(s.get(Param::WindScale), s.get(Param::WindRotationDeg)))
                .and_then(|w| w.with_turbulence(s.get(Param::WindTurbulenceIntensity))),
            None => self.wind(s),
        }
        .map_err(|e| err(e.into()))?;
        let env = Environment {
            elevation_m: s.get(Param::ElevationM),
            wind,
            gravity,
            vacuum: false,
            latitude_deg: self.scenario.environment.latitude_deg,
            air,
        };
        let rail = Rail {
            length_m: s.get(Param::RailLengthM),
            inclination_deg: s.get(Param::RailInclinationDeg),
            heading_deg: s.get(Param::RailHeadingDeg),
        };
        let sim = Simulation::new(self.design.clone(), self.motor.clone(), env, rail)?;
        let (delta_mass, delta_cg) = self.structure_deltas(s);
        let ballast = self
            .scenario
            .ballast
            .as_deref()
            .filter(|_| s.get(Param::BallastKg) != self.nominal.get(Param::BallastKg));
        sim.with_changes(|c| {
            c.motor_scales(self.motor_scales(s))?;
            if !self.scenario.parachutes.is_empty() {
                let chutes = self
                    .scenario
                    .parachutes
                    .iter()
                    .zip(&s.parachutes)
                    .map(|(p, v)| Parachute {
                        sampling_rate_hz: p.sampling_rate_hz,
                        noise: p.noise,
                        ..Parachute::new(
                            p.name.clone(),
                            v[0],
                            with_trigger_value(&p.trigger, v[2]),
                            v[1],
                        )
                        .with_canopy(p.canopy)
                    })
                    .collect();
                c.parachutes(chutes)?;
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
                c.shifts(shifts)?;
            }
            if !self.scenario.releases.is_empty() {
                let releases = self
                    .scenario
                    .releases
                    .iter()
                    .zip(&s.releases)
                    .map(|(r, v)| Release {
                        trigger: with_trigger_value(&r.trigger, v[0]),
                        component: r.component.clone(),
                        // The scenario's, the design's or the tumbling estimate (the nominal
                        // is that; NaN for a component the simulator then refuses by name).
                        cda_m2: v[1].is_finite().then_some(v[1]),
                        parachute: r.parachute.map(|c| PartChute {
                            cds_m2: v[2],
                            lag_s: v[3],
                            ..c
                        }),
                    })
                    .collect();
                c.releases(releases)?;
            }
            c.options(SimOptions {
                integrator: self.scenario.integrator,
                max_time_s: self.scenario.max_time_s,
                keep_samples: false,
            })?;
            if s.get(Param::DragScale) != 1.0 {
                c.drag_scale(s.get(Param::DragScale))?;
            }
            if s.get(Param::AirBrakesTargetM) != self.nominal.get(Param::AirBrakesTargetM)
                && !s.get(Param::AirBrakesTargetM).is_nan()
            {
                c.air_brakes_target(s.get(Param::AirBrakesTargetM))?;
            }
            if let Some(id) = ballast {
                c.part_mass(id, s.get(Param::BallastKg))?;
            }
            if delta_mass != 0.0 || delta_cg != 0.0 {
                c.mass_adjustment(delta_mass, delta_cg)?;
            }
            Ok(())
        })
    }

    /// The launch time of a setup, seconds since 1970 UTC (NaN without a weather file).
    pub(super) fn launch_time_s(&self, s: &Setup) -> f64 {
        self.scenario
            .environment
            .weather
            .as_ref()
            .map_or(f64::NAN, |w| w.time_s + s.get(Param::LaunchTimeH) * 3600.0)
    }

    /// The weather file's air and wind over the site at a setup's launch time and member,
    /// when either is not the nominal's (whose are the scenario's own).
    pub(super) fn drawn_weather(
        &self,
        s: &Setup,
    ) -> Result<Option<hpr_sim::sounding::SiteAir>, hpr_sim::weather::WeatherError> {
        let Some(w) = &self.scenario.environment.weather else {
            return Ok(None);
        };
        if (s.get(Param::LaunchTimeH), s.get(Param::WeatherMember))
            == (
                self.nominal.get(Param::LaunchTimeH),
                self.nominal.get(Param::WeatherMember),
            )
        {
            return Ok(None);
        }
        let member = w.site.member_index(s.get(Param::WeatherMember))?;
        w.site
            .over_site(
                self.launch_time_s(s),
                member,
                self.scenario.environment.elevation_m,
            )
            .map(Some)
    }

    /// The wind of a setup: the scenario's profile, or its constant wind at the setup's speed
    /// and direction, scaled and turned by the setup's `wind_scale` and `wind_rotation_deg`.
    pub(super) fn wind(&self, s: &Setup) -> Result<Wind, hpr_sim::wind::WindError> {
        let env = &self.scenario.environment;
        match &env.wind_profile {
            Some(profile) => {
                profile.transformed(s.get(Param::WindScale), s.get(Param::WindRotationDeg))
            }
            None => Wind::constant(s.get(Param::WindSpeedMS), s.get(Param::WindFromDeg))?
                .transformed(s.get(Param::WindScale), s.get(Param::WindRotationDeg)),
        }?
        .with_turbulence(s.get(Param::WindTurbulenceIntensity))
    }

    /// The structure's change from its nominal (which is at the nominal ballast: a ballast
    /// change is the part's mass, the structure's dispersion comes on top of it).
    pub(super) fn structure_deltas(&self, s: &Setup) -> (f64, f64) {
        (
            s.get(Param::StructureMassKg) - self.nominal.get(Param::StructureMassKg),
            s.get(Param::StructureCgM) - self.nominal.get(Param::StructureCgM),
        )
    }

    /// The motor's impulse and time scales: the setup's impulse and burn time over the
    /// nominal thrust curve's.
    pub(super) fn motor_scales(&self, s: &Setup) -> MotorOptions {
        self.scenario
            .motor_options
            .with_impulse_scale(
                s.get(Param::MotorImpulseNs) / self.nominal.get(Param::MotorImpulseNs),
            )
            .with_time_scale(s.get(Param::MotorBurnTimeS) / self.nominal.get(Param::MotorBurnTimeS))
    }

    /// The batch engine's columns of `rows`: one per swept or dispersed input, each row's
    /// value as the scenario writes it, and the rows' noise seeds when the parachutes'
    /// barometers are noisy.
    pub(super) fn columns(&self, rows: &[&Setup]) -> Columns {
        Columns {
            len: rows.len(),
            inputs: self
                .scenario
                .inputs
                .iter()
                .map(|i| (i.param, rows.iter().map(|s| s.get(i.param)).collect()))
                .collect(),
            sensor_seed: if self.scenario.has_noise() {
                rows.iter().map(|s| s.sensor_seed).collect()
            } else {
                vec![]
            },
        }
    }
}
