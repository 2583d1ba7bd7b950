//! What a flight is set up with besides the design and the motor: the launch site, the rail,
//! the parachutes and the integrator options. Each has a `validate` that says which field
//! broke which rule.

use super::setup_error::{OptionsRule, SetupError};
pub use crate::atmosphere::AirModel;
pub use crate::eom::CanopyShape;
use crate::gravity::Gravity;
use crate::sensor::SensorNoise;
use crate::trigger::Trigger;
use crate::wind::Wind;

/// The launch site and the air.
#[derive(Debug, Clone, PartialEq)]
pub struct Environment {
    /// Elevation of the launch site above mean sea level, m (the standard atmosphere is
    /// evaluated at elevation + height above ground).
    pub elevation_m: f64,
    pub wind: Wind,
    pub gravity: Gravity,
    /// No air at all (density zero): for checks against exact answers.
    pub vacuum: bool,
    /// The site's latitude, degrees north (−90 to 90). Given, the launch frame turns with the
    /// Earth and the flight feels the Coriolis acceleration `−2 Ω × v` (Ω from
    /// [`crate::gravity::earth_rate_n`]), as RocketPy's and OpenRocket's do; `None` (the
    /// default) keeps the launch frame inertial. It does not choose the gravity: see
    /// [`Gravity::somigliana`].
    pub latitude_deg: Option<f64>,
    /// The atmosphere: the standard one (the default), or one from the site's measured
    /// temperature and pressure ([`AirModel::site`]).
    pub air: AirModel,
}

impl Default for Environment {
    fn default() -> Self {
        Environment {
            elevation_m: 0.0,
            wind: Wind::calm(),
            gravity: Gravity::default(),
            vacuum: false,
            latitude_deg: None,
            air: AirModel::Standard,
        }
    }
}

impl Environment {
    /// The Earth's rotation in the launch frame (x east, y north, z up), rad/s; `None`
    /// without a latitude (an inertial launch frame).
    pub fn earth_rate_n(&self) -> Option<[f64; 3]> {
        self.latitude_deg.map(crate::gravity::earth_rate_n)
    }

    /// Checks the latitude.
    pub fn validate(&self) -> Result<(), SetupError> {
        use crate::gravity::is_latitude;
        self.air
            .check()
            .map_err(|e| SetupError::Environment(e.into()))?;
        match self.latitude_deg {
            Some(l) if !is_latitude(l) => Err(SetupError::Latitude { got: l }),
            _ => Ok(()),
        }
    }
}

/// The launch rail. The rocket's aft end sits at the rail's foot, on the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rail {
    pub length_m: f64,
    /// Angle above the horizon, degrees (90 = vertical).
    pub inclination_deg: f64,
    /// Direction the rail leans toward, degrees clockwise from north.
    pub heading_deg: f64,
}

impl Default for Rail {
    fn default() -> Self {
        Rail {
            length_m: 2.0,
            inclination_deg: 90.0,
            heading_deg: 0.0,
        }
    }
}

/// A parachute: its drag area, what opens it, how long it takes to open and the shape of its
/// open canopy (which sets the air it carries along).
#[derive(Debug, Clone, PartialEq)]
pub struct Parachute {
    pub name: String,
    /// Drag coefficient times reference area, m².
    pub cds_m2: f64,
    pub trigger: Trigger,
    /// Time from the trigger to the open canopy, s.
    pub lag_s: f64,
    /// The open canopy's shape (RocketPy's default hemisphere sized from the CdS unless given).
    pub canopy: CanopyShape,
    /// How often the flight computer that fires it reads its sensors, Hz, from launch (its
    /// samples are at k / rate s); `None` (the default) watches continuously. A sampled
    /// trigger fires at the first sample at or after the moment its condition became true
    /// (RocketPy's `sampling_rate`; an altimeter reading at 20 Hz sees an apogee up to 50 ms
    /// late).
    pub sampling_rate_hz: Option<f64>,
    /// The noise of the pressure its flight computer reads (RocketPy's `noise`); `None` (the
    /// default) reads the air's pressure exactly. Only a height trigger reads the pressure,
    /// and a noisy one must be sampled ([`Parachute::sampling_rate_hz`]): see
    /// [`crate::sensor`].
    pub noise: Option<SensorNoise>,
}

impl Parachute {
    /// A parachute whose open canopy has RocketPy's default shape.
    pub fn new(name: impl Into<String>, cds_m2: f64, trigger: Trigger, lag_s: f64) -> Parachute {
        Parachute {
            name: name.into(),
            cds_m2,
            trigger,
            lag_s,
            canopy: CanopyShape::default(),
            sampling_rate_hz: None,
            noise: None,
        }
    }

    /// This parachute fired by a flight computer sampling at `rate_hz` (see
    /// [`Parachute::sampling_rate_hz`]).
    pub fn with_sampling_rate(self, rate_hz: f64) -> Parachute {
        Parachute {
            sampling_rate_hz: Some(rate_hz),
            ..self
        }
    }

    /// The moment a trigger whose condition became true at `t` fires: `t` itself when the
    /// parachute watches continuously, else its first sample at or after `t`.
    pub fn fires_at(&self, t: f64) -> f64 {
        match self.sampling_rate_hz {
            None => t,
            // k / rate rounds to the nearest double; a sample that rounds below `t` is `t`.
            Some(rate) => ((t * rate).ceil() / rate).max(t),
        }
    }

    /// This parachute fired on a pressure read with `noise` (see [`Parachute::noise`]).
    pub fn with_noise(self, noise: SensorNoise) -> Parachute {
        Parachute {
            noise: Some(noise),
            ..self
        }
    }

    /// This parachute with an open canopy of the given shape.
    pub fn with_canopy(self, canopy: CanopyShape) -> Parachute {
        Parachute { canopy, ..self }
    }
}

/// Which integrator flies the 6-DOF and descent phases.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// Dormand–Prince 5(4) with error control on every state.
    Adaptive {
        rtol: f64,
        /// Absolute tolerance of positions, m.
        atol_position_m: f64,
        /// Absolute tolerance of velocities, m/s.
        atol_velocity_m_s: f64,
        /// Absolute tolerance of the quaternion's components.
        atol_quaternion: f64,
        /// Absolute tolerance of the angular rates, rad/s.
        atol_rate_rad_s: f64,
    },
    /// Classic fixed-step Runge–Kutta 4.
    Rk4 { step_s: f64 },
}

impl Integrator {
    /// The default: rtol 1e-7, atol 1e-4 m, 1e-4 m/s, 1e-8, 1e-4 rad/s. On the reference design
    /// it puts the apogee within 0.3 mm and the landing point within 2 cm of the answer at
    /// rtol 1e-12 (see `examples/tolerance_study.rs`).
    pub const DEFAULT: Integrator = Integrator::Adaptive {
        rtol: 1e-7,
        atol_position_m: 1e-4,
        atol_velocity_m_s: 1e-4,
        atol_quaternion: 1e-8,
        atol_rate_rad_s: 1e-4,
    };
}

/// Options of a flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimOptions {
    pub integrator: Integrator,
    /// The flight stops with `EventKind::TimeLimit` at this time, s.
    pub max_time_s: f64,
    /// Keep a sample at every accepted step (true) or none but the events (false, faster).
    pub keep_samples: bool,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            integrator: Integrator::DEFAULT,
            max_time_s: 600.0,
            keep_samples: true,
        }
    }
}

/// Most steps the input itself sets over a flight's time limit, 10,000,000 (some tens of
/// seconds of one flight): RK4's `max_time_s / step_s`, and a sampler's
/// `max_time_s × sampling_rate_hz` (each sample of the air brakes' controller or of a
/// sampled parachute trigger ends a step). More would run for hours (`step_s = 1e-9` over
/// 600 s: 6·10¹¹ steps), and is refused before the flight.
pub const MAX_INPUT_STEPS: f64 = 1e7;

/// The rule RK4's fixed step breaks, if it does: `max_time_s / step_s` steps above
/// [`MAX_INPUT_STEPS`] (both positive and finite, checked apart).
pub fn rk4_steps_rule(step_s: f64, max_time_s: f64) -> Option<String> {
    let steps = max_time_s / step_s;
    (steps > MAX_INPUT_STEPS).then(|| {
        format!(
            "max_time_s / step_s is {steps:.4e} steps, more than the {MAX_INPUT_STEPS:.0} a flight \
             may take: give a step of at least {:e} s, or a shorter max_time_s (got {step_s})",
            max_time_s / MAX_INPUT_STEPS
        )
    })
}

impl SimOptions {
    /// Check every number: the time limit, RK4's step, the adaptive tolerances (the same
    /// ranges as the integrators enforce, named by the fields a user sets).
    pub fn validate(&self) -> Result<(), SetupError> {
        let positive = |field: &'static str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(SetupError::Options {
                    field,
                    rule: OptionsRule::NotPositive { got: v },
                })
            }
        };
        positive("max_time_s", self.max_time_s)?;
        match self.integrator {
            Integrator::Rk4 { step_s } => {
                positive("step_s", step_s)?;
                match rk4_steps_rule(step_s, self.max_time_s) {
                    Some(rule) => Err(SetupError::Options {
                        field: "step_s",
                        rule: OptionsRule::TooManySteps { rule },
                    }),
                    None => Ok(()),
                }
            }
            Integrator::Adaptive {
                rtol,
                atol_position_m,
                atol_velocity_m_s,
                atol_quaternion,
                atol_rate_rad_s,
            } => {
                use crate::integrate::{RTOL_MAX, RTOL_MIN};
                if !(RTOL_MIN..=RTOL_MAX).contains(&rtol) {
                    return Err(SetupError::Options {
                        field: "rtol",
                        rule: OptionsRule::Rtol {
                            got: rtol,
                            min: RTOL_MIN,
                            max: RTOL_MAX,
                        },
                    });
                }
                positive("atol_position_m", atol_position_m)?;
                positive("atol_velocity_m_s", atol_velocity_m_s)?;
                positive("atol_quaternion", atol_quaternion)?;
                positive("atol_rate_rad_s", atol_rate_rad_s)
            }
        }
    }
}
