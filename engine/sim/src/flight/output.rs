//! What a flight returns: samples, events and the metrics a flier asks for.

use crate::events::{Event, EventKind};

/// Which equations fly the rocket.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Sliding along the rail (one degree of freedom).
    Rail,
    /// Free flight, 6 degrees of freedom.
    Free,
    /// Under canopy: the center of mass as a point (3 degrees of freedom).
    Descent,
}

impl Phase {
    pub fn name(&self) -> &'static str {
        match self {
            Phase::Rail => "rail",
            Phase::Free => "free",
            Phase::Descent => "descent",
        }
    }
}

/// One sample of the flight, at the end of an accepted step or at an event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub t_s: f64,
    pub phase: Phase,
    /// Center of mass, inertial (east, north, up from the rail's foot), m.
    pub position_m: [f64; 3],
    /// Center of mass velocity, inertial, m/s.
    pub velocity_m_s: [f64; 3],
    /// Attitude quaternion body → inertial `[w, x, y, z]` (fixed in the descent phase).
    pub quaternion: [f64; 4],
    /// Angular rate, body axes, rad/s (zero in the descent phase).
    pub omega_rad_s: [f64; 3],
    /// Height of the center of mass above ground, m.
    pub altitude_m: f64,
    /// Speed of the center of mass, m/s.
    pub speed_m_s: f64,
    /// Speed through the air over the speed of sound.
    pub mach: f64,
    /// Angle of attack of the center of mass, degrees (NaN in the descent phase).
    pub alpha_deg: f64,
    /// Inertial acceleration of the center of mass, m/s².
    pub accel_m_s2: f64,
    pub thrust_n: f64,
    pub mass_kg: f64,
    /// Center of mass, m aft of the nose tip.
    pub cg_m: f64,
    /// Static margin (center of pressure at Mach 0), calibres.
    pub static_margin_cal: f64,
    /// Flight margin (center of pressure at this sample's Mach), calibres.
    pub flight_margin_cal: f64,
}

/// The figures a flier asks for. `None` where a value does not exist (no landing in a flight
/// cut by its time limit, no burnout sample for a flight that never left the rail...).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Metrics {
    pub apogee_m: Option<f64>,
    pub apogee_time_s: Option<f64>,
    pub max_speed_m_s: f64,
    pub max_mach: f64,
    pub max_accel_m_s2: f64,
    pub liftoff_time_s: Option<f64>,
    pub rail_exit_time_s: Option<f64>,
    pub rail_exit_speed_m_s: Option<f64>,
    pub burnout_time_s: Option<f64>,
    pub static_margin_liftoff_cal: Option<f64>,
    pub static_margin_rail_exit_cal: Option<f64>,
    pub static_margin_burnout_cal: Option<f64>,
    /// Smallest static margin from liftoff to apogee (or the first canopy), calibres.
    pub static_margin_min_cal: Option<f64>,
    /// Smallest flight margin from rail exit to apogee (or the first canopy), calibres.
    pub flight_margin_min_cal: Option<f64>,
    pub landing_time_s: Option<f64>,
    /// Landing point of the center of mass, east and north of the rail's foot, m.
    pub landing_position_m: Option<[f64; 2]>,
    pub landing_speed_m_s: Option<f64>,
}

/// A flown flight.
#[derive(Debug, Clone, PartialEq)]
pub struct Flight {
    pub samples: Vec<Sample>,
    pub events: Vec<Event>,
    pub metrics: Metrics,
    /// Start time of each shift, s (in the order given; `None` if its trigger never fired).
    pub shift_starts_s: Vec<Option<f64>>,
    /// Derivative evaluations (a measure of cost).
    pub derivative_evaluations: u64,
    /// Accepted integration steps.
    pub steps: u64,
}

impl Flight {
    /// The first event of `kind`.
    pub fn event(&self, kind: EventKind) -> Option<&Event> {
        self.events.iter().find(|e| e.kind == kind)
    }
}

/// Watches a flight as it goes. `()` watches nothing.
pub trait Observer {
    /// Whether it reads the samples (an observer that does not is spared their figures).
    const WANTS_SAMPLES: bool = true;
    fn on_sample(&mut self, _sample: &Sample) {}
    fn on_event(&mut self, _event: &Event) {}
}

impl Observer for () {
    const WANTS_SAMPLES: bool = false;
}
