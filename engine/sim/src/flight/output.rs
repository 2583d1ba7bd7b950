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
    /// Dynamic pressure, ½ ρ v² of the speed through the air, Pa.
    pub dynamic_pressure_pa: f64,
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
    /// Largest dynamic pressure the airframe met, ½ ρ v² of its speed through the air at the
    /// center of mass (what the drag reads), Pa: the load a fin's flutter and the airframe's
    /// strength are judged at ("max Q"), over every step's end and event.
    pub max_dynamic_pressure_pa: f64,
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
    /// Largest angle of attack of the center of mass in free flight before apogee (or the
    /// first canopy), degrees, watched as OpenRocket watches its aerodynamic warnings: from
    /// 0.25 s after rail exit and while the vertical speed is at least 20 % of its highest so
    /// far. Past 45° the aerodynamics are this crate's extrapolation of RocketPy's model (see
    /// [`crate::aero_loads`]), and the flight a tumble.
    pub max_alpha_deg: Option<f64>,
    pub landing_time_s: Option<f64>,
    /// Landing point of the center of mass, east and north of the rail's foot, m.
    pub landing_position_m: Option<[f64; 2]>,
    pub landing_speed_m_s: Option<f64>,
    /// The first controller sample that opened the air brakes, s (`None` without brakes or
    /// if they never opened).
    pub air_brakes_open_time_s: Option<f64>,
    /// The widest opening the controller asked for, 0 (closed) to 1 (fully open) (`None`
    /// without brakes or before their first sample).
    pub air_brakes_max_opening: Option<f64>,
}

/// A flown flight.
#[derive(Debug, Clone, PartialEq)]
pub struct Flight {
    pub samples: Vec<Sample>,
    pub events: Vec<Event>,
    pub metrics: Metrics,
    /// Start time of each shift, s (in the order given; `None` if its trigger never fired).
    pub shift_starts_s: Vec<Option<f64>>,
    /// What each release did (in the order given): when its part left, the static margin
    /// just before and after, and the part's own flight to the ground.
    pub releases: Vec<ReleaseRecord>,
    /// Derivative evaluations (a measure of cost).
    pub derivative_evaluations: u64,
    /// Accepted integration steps.
    pub steps: u64,
}

/// What one release did in a flight.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReleaseRecord {
    /// When the part left, s (`None`: its trigger never fired).
    pub time_s: Option<f64>,
    /// The rocket's static margin just before and just after the part left, calibres (the
    /// center of pressure at Mach 0 does not move; the center of mass jumps).
    pub margin_before_cal: Option<f64>,
    pub margin_after_cal: Option<f64>,
    /// The part's own flight from the release to the ground.
    pub part: Option<PartFlight>,
}

/// A released part's flight: a point of its own mass under its own drag or parachute.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PartFlight {
    pub mass_kg: f64,
    /// Its center where it left and the velocity its material had then (the airframe's at
    /// that point), launch frame, m and m/s.
    pub start_position_m: [f64; 3],
    pub start_velocity_m_s: [f64; 3],
    /// Its highest point above the ground, m (its start, for a part that leaves on the way
    /// down).
    pub apogee_m: f64,
    /// When its own parachute opened, s (`None`: it has none, or it never opened).
    pub chute_open_s: Option<f64>,
    /// Where, when and how fast it reached the ground (`None`: the flight's time limit came
    /// first).
    pub landing_time_s: Option<f64>,
    /// East and north of the rail's foot, m.
    pub landing_position_m: Option<[f64; 2]>,
    pub landing_speed_m_s: Option<f64>,
    /// Its path, one sample per step (when the flight keeps samples).
    pub samples: Vec<PartSample>,
}

/// One sample of a released part's flight, at the end of an accepted step or at an event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartSample {
    pub t_s: f64,
    /// Its center, launch frame (east, north, up from the rail's foot), m.
    pub position_m: [f64; 3],
    pub velocity_m_s: [f64; 3],
}

impl Flight {
    /// Each shift's start time, then each release's time (infinite where it never came), as
    /// the flight's model reads them ([`crate::flight::model::ShiftStarts`]).
    pub fn starts(&self) -> crate::flight::model::ShiftStarts {
        let mut starts = [f64::INFINITY; crate::flight::model::MAX_SHIFTS];
        let times = self
            .shift_starts_s
            .iter()
            .chain(self.releases.iter().map(|r| &r.time_s));
        for (s, t) in starts.iter_mut().zip(times) {
            if let Some(t) = t {
                *s = *t;
            }
        }
        starts
    }

    /// The first event of `kind`.
    pub fn event(&self, kind: EventKind) -> Option<&Event> {
        self.events.iter().find(|e| e.kind == kind)
    }

    /// Parachute `i`'s opening: its time, s, and the speed of the center of mass then, m/s
    /// (`None` if it never opened).
    pub fn deploy(&self, i: usize) -> Option<(f64, f64)> {
        self.event(EventKind::ParachuteDeploy(i))
            .map(|e| (e.time_s, e.speed_m_s))
    }

    /// What a flier should look at before trusting this flight's numbers.
    pub fn warnings(&self) -> Vec<Warning> {
        let opened = self
            .events
            .iter()
            .any(|e| matches!(e.kind, EventKind::ParachuteDeploy(_)));
        Warning::of(&self.metrics, opened)
    }
}

/// Angle of attack past which a flight is flagged, degrees: where the loads leave RocketPy's
/// model for this crate's turn-over (see [`crate::aero_loads`]).
pub const LARGE_ALPHA_DEG: f64 = 45.0;

/// Something in a flight that its figures alone hide, the way OpenRocket lists warnings
/// beside a simulation's results. The flight still counts; the warning says how to read it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Warning {
    /// The static margin fell below zero between liftoff and apogee: the rocket was unstable.
    NegativeStaticMargin { min_cal: f64 },
    /// The angle of attack passed [`LARGE_ALPHA_DEG`] in free flight while climbing
    /// ([`Metrics::max_alpha_deg`]): the rocket tumbled or turned far from its path, on
    /// extrapolated aerodynamics.
    LargeAngleOfAttack { max_deg: f64 },
    /// The rocket reached the ground with no canopy open (a ballistic landing).
    NoCanopyAtLanding { speed_m_s: f64 },
}

impl Warning {
    /// The warnings of a flight with these metrics, `opened` telling whether any canopy opened
    /// before its end.
    pub fn of(m: &Metrics, opened: bool) -> Vec<Warning> {
        let mut w = Vec::new();
        if let Some(min_cal) = m.static_margin_min_cal.filter(|&x| x < 0.0) {
            w.push(Warning::NegativeStaticMargin { min_cal });
        }
        if let Some(max_deg) = m.max_alpha_deg.filter(|&a| a > LARGE_ALPHA_DEG) {
            w.push(Warning::LargeAngleOfAttack { max_deg });
        }
        if let (false, Some(speed_m_s)) = (opened, m.landing_speed_m_s) {
            w.push(Warning::NoCanopyAtLanding { speed_m_s });
        }
        w
    }

    /// Every warning's key, in the order of [`Warning::index`].
    pub const KEYS: [&'static str; 3] = ["unstable", "large_alpha", "ballistic"];

    /// This warning's place in [`Warning::KEYS`].
    pub fn index(&self) -> usize {
        match self {
            Warning::NegativeStaticMargin { .. } => 0,
            Warning::LargeAngleOfAttack { .. } => 1,
            Warning::NoCanopyAtLanding { .. } => 2,
        }
    }

    /// A short name for counting and filtering (`unstable`, `large_alpha`, `ballistic`).
    pub fn key(&self) -> &'static str {
        Warning::KEYS[self.index()]
    }
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Warning::NegativeStaticMargin { min_cal } => write!(
                f,
                "unstable: the static margin fell to {min_cal:.3} cal (below 0) before apogee"
            ),
            Warning::LargeAngleOfAttack { max_deg } => write!(
                f,
                "large_alpha: the angle of attack reached {max_deg:.1}° in free flight (past {LARGE_ALPHA_DEG}°, the rocket tumbled or turned far from its path)"
            ),
            Warning::NoCanopyAtLanding { speed_m_s } => write!(
                f,
                "ballistic: landed at {speed_m_s:.1} m/s with no parachute open"
            ),
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(margin: f64, alpha: f64, landing: Option<f64>) -> Metrics {
        Metrics {
            static_margin_min_cal: Some(margin),
            max_alpha_deg: Some(alpha),
            landing_speed_m_s: landing,
            ..Metrics::default()
        }
    }

    #[test]
    fn a_warning_starts_just_past_its_threshold() {
        assert_eq!(Warning::of(&metrics(0.0, 45.0, Some(5.0)), true), vec![]);
        assert_eq!(
            Warning::of(&metrics(-1e-12, 45.0 + 1e-12, Some(5.0)), true),
            vec![
                Warning::NegativeStaticMargin { min_cal: -1e-12 },
                Warning::LargeAngleOfAttack {
                    max_deg: 45.0 + 1e-12
                },
            ]
        );
    }

    #[test]
    fn only_a_landing_without_a_canopy_is_ballistic() {
        assert_eq!(
            Warning::of(&metrics(1.0, 2.0, Some(80.0)), false),
            vec![Warning::NoCanopyAtLanding { speed_m_s: 80.0 }]
        );
        // No landing (a time limit): nothing to say about it.
        assert_eq!(Warning::of(&metrics(1.0, 2.0, None), false), vec![]);
        // A flight that never got that far has no margins and no angles to judge.
        assert_eq!(Warning::of(&Metrics::default(), false), vec![]);
    }

    #[test]
    fn each_warning_s_text_starts_with_its_key() {
        for w in [
            Warning::NegativeStaticMargin { min_cal: -0.5 },
            Warning::LargeAngleOfAttack { max_deg: 90.0 },
            Warning::NoCanopyAtLanding { speed_m_s: 50.0 },
        ] {
            let text = w.to_string();
            assert!(text.starts_with(&format!("{}: ", w.key())), "{text}");
            // The campaign joins a flight's warnings with "; " and splits them there.
            assert!(!text.contains("; "), "{text}");
        }
    }
}
