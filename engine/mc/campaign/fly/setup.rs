//! A flight's values ([`Setup`]: the nominals, or a variant's with its sampled inputs checked
//! against their ranges) and what turns them into flights ([`Fixed`]): the base simulation,
//! built once from scratch, and the batch engine's columns for the lanes.

use super::super::params::Param;
use super::super::scenario::{with_trigger_value, Scenario};
use hpr_design::design::model::Design;
use hpr_design::motor::{Motor, MotorOptions};
use hpr_sim::batch::Columns;
use hpr_sim::wind::Wind;
use hpr_sim::{
    Environment, MassShift, Parachute, PartChute, Rail, Release, SimError, SimOptions, Simulation,
};

/// Every flight's values, nominal or a variant's.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Setup {
    pub(super) structure_mass_kg: f64,
    pub(super) structure_cg_m: f64,
    pub(super) ballast_kg: f64,
    pub(super) impulse_ns: f64,
    pub(super) burn_time_s: f64,
    pub(super) drag_scale: f64,
    pub(super) elevation_m: f64,
    /// The site's air temperature, K, and pressure, Pa.
    pub(super) temperature_k: f64,
    pub(super) pressure_pa: f64,
    /// The launch time, hours after the weather file's `time`, and its ensemble member (NaN
    /// without a weather file).
    pub(super) launch_time_h: f64,
    pub(super) weather_member: f64,
    pub(super) wind_speed_m_s: f64,
    pub(super) wind_from_deg: f64,
    pub(super) wind_scale: f64,
    pub(super) wind_rotation_deg: f64,
    pub(super) wind_turbulence_intensity: f64,
    pub(super) rail: [f64; 3],
    /// The air brakes' target apogee, m (NaN without brakes).
    pub(super) brake_target_m: f64,
    /// Per parachute: CdS, lag, trigger number (NaN if none).
    pub(super) parachutes: Vec<[f64; 3]>,
    /// Per shift: travel, duration, trigger number (NaN if none).
    pub(super) shifts: Vec<[f64; 3]>,
    /// Per release: trigger number (NaN if none), the part's drag area, its parachute's CdS
    /// and lag (NaN without a parachute).
    pub(super) releases: Vec<[f64; 4]>,
    /// The seed of the parachutes' barometer noise (the variant's own; 0 for the nominal).
    pub(super) sensor_seed: u64,
}

impl Setup {
    pub(super) fn get(&self, p: Param) -> f64 {
        match p {
            Param::StructureMassKg => self.structure_mass_kg,
            Param::StructureCgM => self.structure_cg_m,
            Param::BallastKg => self.ballast_kg,
            Param::MotorImpulseNs => self.impulse_ns,
            Param::MotorBurnTimeS => self.burn_time_s,
            Param::DragScale => self.drag_scale,
            Param::ElevationM => self.elevation_m,
            Param::TemperatureK => self.temperature_k,
            Param::PressurePa => self.pressure_pa,
            Param::LaunchTimeH => self.launch_time_h,
            Param::WeatherMember => self.weather_member,
            Param::WindSpeedMS => self.wind_speed_m_s,
            Param::WindFromDeg => self.wind_from_deg,
            Param::WindScale => self.wind_scale,
            Param::WindRotationDeg => self.wind_rotation_deg,
            Param::WindTurbulenceIntensity => self.wind_turbulence_intensity,
            Param::RailLengthM => self.rail[0],
            Param::RailInclinationDeg => self.rail[1],
            Param::RailHeadingDeg => self.rail[2],
            Param::AirBrakesTargetM => self.brake_target_m,
            Param::ParachuteCdsM2(i) => self.parachutes[i][0],
            Param::ParachuteLagS(i) => self.parachutes[i][1],
            Param::ParachuteTrigger(i) => self.parachutes[i][2],
            Param::ShiftTravelM(i) => self.shifts[i][0],
            Param::ShiftDurationS(i) => self.shifts[i][1],
            Param::ShiftTrigger(i) => self.shifts[i][2],
            Param::ReleaseTrigger(i) => self.releases[i][0],
            Param::ReleaseCdaM2(i) => self.releases[i][1],
            Param::ReleaseChuteCdsM2(i) => self.releases[i][2],
            Param::ReleaseChuteLagS(i) => self.releases[i][3],
        }
    }

    pub(super) fn set(&mut self, p: Param, v: f64) {
        let slot = match p {
            Param::StructureMassKg => &mut self.structure_mass_kg,
            Param::StructureCgM => &mut self.structure_cg_m,
            Param::BallastKg => &mut self.ballast_kg,
            Param::MotorImpulseNs => &mut self.impulse_ns,
            Param::MotorBurnTimeS => &mut self.burn_time_s,
            Param::DragScale => &mut self.drag_scale,
            Param::ElevationM => &mut self.elevation_m,
            Param::TemperatureK => &mut self.temperature_k,
            Param::PressurePa => &mut self.pressure_pa,
            Param::LaunchTimeH => &mut self.launch_time_h,
            Param::WeatherMember => &mut self.weather_member,
            Param::WindSpeedMS => &mut self.wind_speed_m_s,
            Param::WindFromDeg => &mut self.wind_from_deg,
            Param::WindScale => &mut self.wind_scale,
            Param::WindRotationDeg => &mut self.wind_rotation_deg,
            Param::WindTurbulenceIntensity => &mut self.wind_turbulence_intensity,
            Param::RailLengthM => &mut self.rail[0],
            Param::RailInclinationDeg => &mut self.rail[1],
            Param::RailHeadingDeg => &mut self.rail[2],
            Param::AirBrakesTargetM => &mut self.brake_target_m,
            Param::ParachuteCdsM2(i) => &mut self.parachutes[i][0],
            Param::ParachuteLagS(i) => &mut self.parachutes[i][1],
            Param::ParachuteTrigger(i) => &mut self.parachutes[i][2],
            Param::ShiftTravelM(i) => &mut self.shifts[i][0],
            Param::ShiftDurationS(i) => &mut self.shifts[i][1],
            Param::ShiftTrigger(i) => &mut self.shifts[i][2],
            Param::ReleaseTrigger(i) => &mut self.releases[i][0],
            Param::ReleaseCdaM2(i) => &mut self.releases[i][1],
            Param::ReleaseChuteCdsM2(i) => &mut self.releases[i][2],
            Param::ReleaseChuteLagS(i) => &mut self.releases[i][3],
        };
        *slot = v;
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
        let err = |e: &dyn std::fmt::Display| SimError::Setup(e.to_string());
        let site = &self.scenario.environment;
        let gravity = site
            .gravity
            .at_site(site.latitude_deg, s.elevation_m, "environment.latitude_deg")
            .map_err(|e| err(&e))?;
        // A launch time or member of its own: the weather file's air and wind then.
        let drawn = self.drawn_weather(s).map_err(|e| err(&e))?;
        let base_air = match &drawn {
            Some(w) => w.air_model(),
            None => site.air.clone(),
        };
        let air = if (s.temperature_k, s.pressure_pa)
            == (self.nominal.temperature_k, self.nominal.pressure_pa)
        {
            base_air
        } else {
            // The air of the scenario's site, at this setup's temperature and pressure.
            base_air
                .with_site_values(site.elevation_m, Some(s.temperature_k), Some(s.pressure_pa))
                .map_err(|e| err(&e))?
        };
        let wind = match &drawn {
            Some(w) => w
                .wind()
                .and_then(|w| w.transformed(s.wind_scale, s.wind_rotation_deg))
                .and_then(|w| w.with_turbulence(s.wind_turbulence_intensity)),
            None => self.wind(s),
        }
        .map_err(|e| err(&e))?;
        let env = Environment {
            elevation_m: s.elevation_m,
            wind,
            gravity,
            vacuum: false,
            latitude_deg: self.scenario.environment.latitude_deg,
            air,
        };
        let rail = Rail {
            length_m: s.rail[0],
            inclination_deg: s.rail[1],
            heading_deg: s.rail[2],
        };
        let sim = Simulation::new(self.design.clone(), self.motor.clone(), env, rail)?;
        let (delta_mass, delta_cg) = self.structure_deltas(s);
        let ballast = self
            .scenario
            .ballast
            .as_deref()
            .filter(|_| s.ballast_kg != self.nominal.ballast_kg);
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
            if s.drag_scale != 1.0 {
                c.drag_scale(s.drag_scale)?;
            }
            if s.brake_target_m != self.nominal.brake_target_m && !s.brake_target_m.is_nan() {
                c.air_brakes_target(s.brake_target_m)?;
            }
            if let Some(id) = ballast {
                c.part_mass(id, s.ballast_kg)?;
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
            .map_or(f64::NAN, |w| w.time_s + s.launch_time_h * 3600.0)
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
        if (s.launch_time_h, s.weather_member)
            == (self.nominal.launch_time_h, self.nominal.weather_member)
        {
            return Ok(None);
        }
        let member = w.site.member_index(s.weather_member)?;
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
            Some(profile) => profile.transformed(s.wind_scale, s.wind_rotation_deg),
            None => Wind::constant(s.wind_speed_m_s, s.wind_from_deg)?
                .transformed(s.wind_scale, s.wind_rotation_deg),
        }?
        .with_turbulence(s.wind_turbulence_intensity)
    }

    /// The structure's change from its nominal (which is at the nominal ballast: a ballast
    /// change is the part's mass, the structure's dispersion comes on top of it).
    pub(super) fn structure_deltas(&self, s: &Setup) -> (f64, f64) {
        (
            s.structure_mass_kg - self.nominal.structure_mass_kg,
            s.structure_cg_m - self.nominal.structure_cg_m,
        )
    }

    /// The motor's impulse and time scales: the setup's impulse and burn time over the
    /// nominal thrust curve's.
    pub(super) fn motor_scales(&self, s: &Setup) -> MotorOptions {
        self.scenario
            .motor_options
            .with_impulse_scale(s.impulse_ns / self.nominal.impulse_ns)
            .with_time_scale(s.burn_time_s / self.nominal.burn_time_s)
    }

    /// The batch engine's columns of `rows`: one column per swept or dispersed input (the
    /// wind's speed and direction together, the rail's three numbers together, so that each
    /// is the setup's own value), empty for every other.
    pub(super) fn columns(&self, rows: &[&Setup]) -> Columns {
        let has = |p: Param| self.scenario.inputs.iter().any(|i| i.param == p);
        let any = |ps: &[Param]| ps.iter().any(|&p| has(p));
        let col = |on: bool, f: &dyn Fn(&Setup) -> f64| -> Vec<f64> {
            if on {
                rows.iter().map(|s| f(s)).collect()
            } else {
                vec![]
            }
        };
        use Param::*;
        let structure = any(&[StructureMassKg, StructureCgM]);
        let motor = any(&[MotorImpulseNs, MotorBurnTimeS]);
        let wind = any(&[WindSpeedMS, WindFromDeg, WindScale, WindRotationDeg]);
        // A profile's rows are the scenario's own: only its scale and turn vary.
        let constant_wind = wind && self.scenario.environment.wind_profile.is_none();
        let rail = any(&[RailLengthM, RailInclinationDeg, RailHeadingDeg]);
        let air = any(&[TemperatureK, PressurePa]);
        let drawn = any(&[LaunchTimeH, WeatherMember]);
        let per = |count: usize, p: fn(usize) -> Param, f: fn(&Setup, usize) -> f64| {
            (0..count)
                .map(|k| col(has(p(k)), &|s| f(s, k)))
                .collect::<Vec<_>>()
        };
        let (chutes, shifts) = (self.scenario.parachutes.len(), self.scenario.shifts.len());
        let releases = self.scenario.releases.len();
        let noisy = self.scenario.has_noise();
        Columns {
            sensor_seed: if noisy {
                rows.iter().map(|s| s.sensor_seed).collect()
            } else {
                vec![]
            },
            len: rows.len(),
            structure_delta_mass_kg: col(structure, &|s| self.structure_deltas(s).0),
            structure_delta_cg_m: col(structure, &|s| self.structure_deltas(s).1),
            part_mass_kg: col(has(BallastKg), &|s| s.ballast_kg),
            impulse_scale: col(motor, &|s| self.motor_scales(s).impulse_scale),
            time_scale: col(motor, &|s| self.motor_scales(s).time_scale),
            drag_scale: col(has(DragScale), &|s| s.drag_scale),
            elevation_m: col(has(ElevationM), &|s| s.elevation_m),
            temperature_k: col(air, &|s| s.temperature_k),
            pressure_pa: col(air, &|s| s.pressure_pa),
            launch_time_s: col(drawn, &|s| self.launch_time_s(s)),
            weather_member: col(drawn, &|s| s.weather_member),
            wind_speed_m_s: col(constant_wind, &|s| s.wind_speed_m_s),
            wind_from_deg: col(constant_wind, &|s| s.wind_from_deg),
            wind_scale: col(wind, &|s| s.wind_scale),
            wind_rotation_deg: col(wind, &|s| s.wind_rotation_deg),
            wind_turbulence_intensity: col(has(WindTurbulenceIntensity), &|s| {
                s.wind_turbulence_intensity
            }),
            rail_length_m: col(rail, &|s| s.rail[0]),
            rail_inclination_deg: col(rail, &|s| s.rail[1]),
            rail_heading_deg: col(rail, &|s| s.rail[2]),
            air_brakes_target_m: col(has(AirBrakesTargetM), &|s| s.brake_target_m),
            chute_cds_m2: per(chutes, ParachuteCdsM2, |s, k| s.parachutes[k][0]),
            chute_lag_s: per(chutes, ParachuteLagS, |s, k| s.parachutes[k][1]),
            chute_trigger: per(chutes, ParachuteTrigger, |s, k| s.parachutes[k][2]),
            shift_travel_m: per(shifts, ShiftTravelM, |s, k| s.shifts[k][0]),
            shift_duration_s: per(shifts, ShiftDurationS, |s, k| s.shifts[k][1]),
            shift_trigger: per(shifts, ShiftTrigger, |s, k| s.shifts[k][2]),
            release_trigger: per(releases, ReleaseTrigger, |s, k| s.releases[k][0]),
            release_cda_m2: per(releases, ReleaseCdaM2, |s, k| s.releases[k][1]),
            release_chute_cds_m2: per(releases, ReleaseChuteCdsM2, |s, k| s.releases[k][2]),
            release_chute_lag_s: per(releases, ReleaseChuteLagS, |s, k| s.releases[k][3]),
        }
    }
}
