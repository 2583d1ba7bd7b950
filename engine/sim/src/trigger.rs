//! Triggers: when a parachute opens, a mass shift starts or a part is released. All three use
//! this one type, so a shift or a release can start on anything that opens a parachute
//! (apogee, a height on the way down, a time after launch, burnout, burnout plus a delay), and
//! the flight driver judges them alike: a trigger with a time known before the flight
//! ([`Trigger::fixed_time`]) is a stop time, apogee and a height are events located on the
//! step's dense output, and one call fires every parachute, shift and release that a moment
//! triggers.

use std::fmt;

/// A trigger's own number (its height, time or delay) not finite or negative.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("trigger {trigger}: field \"{field}\" must be finite and not negative (got {got})")]
pub struct TriggerError {
    pub trigger: Trigger,
    pub field: &'static str,
    pub got: f64,
}

/// When something starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Trigger {
    /// At apogee (the center of mass's vertical speed crosses zero going down).
    Apogee,
    /// On the way down, when the center of mass descends through `height_m` above ground.
    HeightDescending { height_m: f64 },
    /// At `time_s` after launch (ignition, t = 0).
    Time { time_s: f64 },
    /// At the motor's burnout (the last point of its thrust curve).
    Burnout,
    /// At burnout plus a delay: `delay_s`, or the motor's own (first listed) delay if `None`.
    BurnoutPlusDelay { delay_s: Option<f64> },
}

impl Trigger {
    /// Check the trigger's own numbers: finite, non-negative. The message names the trigger and
    /// the field; the caller puts its owner in front of it (a parachute's name, a shift's index
    /// and part).
    pub fn validate(&self) -> Result<(), TriggerError> {
        let bad = |field: &'static str, v: f64| -> Result<(), TriggerError> {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(TriggerError {
                    trigger: *self,
                    field,
                    got: v,
                })
            }
        };
        match *self {
            Trigger::HeightDescending { height_m } => bad("height_m", height_m),
            Trigger::Time { time_s } => bad("time_s", time_s),
            Trigger::BurnoutPlusDelay { delay_s: Some(d) } => bad("delay_s", d),
            _ => Ok(()),
        }
    }

    /// Whether the trigger fires at a fixed time known before the flight, given the burnout
    /// time and the motor's delay: `Some(t)` for time, burnout and burnout-plus-delay.
    pub fn fixed_time(&self, burnout_s: f64, motor_delay_s: Option<f64>) -> Option<f64> {
        match *self {
            Trigger::Time { time_s } => Some(time_s),
            Trigger::Burnout => Some(burnout_s),
            Trigger::BurnoutPlusDelay { delay_s } => {
                delay_s.or(motor_delay_s).map(|d| burnout_s + d)
            }
            _ => None,
        }
    }
}

/// A design's deployment trigger (a parachute component's `deploy`) as the flight's.
impl From<hpr_design::DeployTrigger> for Trigger {
    fn from(t: hpr_design::DeployTrigger) -> Trigger {
        use hpr_design::DeployTrigger as D;
        match t {
            D::Apogee => Trigger::Apogee,
            D::Burnout => Trigger::Burnout,
            D::MotorDelay => Trigger::BurnoutPlusDelay { delay_s: None },
            D::Time { time_s } => Trigger::Time { time_s },
            D::Height { height_m } => Trigger::HeightDescending { height_m },
            D::AfterBurnout { delay_s } => Trigger::BurnoutPlusDelay {
                delay_s: Some(delay_s),
            },
        }
    }
}

impl fmt::Display for Trigger {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Trigger::Apogee => write!(f, "apogee"),
            Trigger::HeightDescending { height_m } => write!(f, "{height_m} m on the way down"),
            Trigger::Time { time_s } => write!(f, "{time_s} s after launch"),
            Trigger::Burnout => write!(f, "burnout"),
            Trigger::BurnoutPlusDelay { delay_s: Some(d) } => write!(f, "burnout + {d} s"),
            Trigger::BurnoutPlusDelay { delay_s: None } => write!(f, "burnout + the motor's delay"),
        }
    }
}
