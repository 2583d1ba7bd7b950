//! Flight events: what happened and when, located by root-finding on the dense output.

/// What happened.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EventKind {
    /// Thrust first beats weight along the rail: the rocket starts to move.
    Liftoff,
    /// The upper rail guide (or the aft end, without guides) leaves the rail.
    RailExit,
    /// The motor's last thrust point.
    Burnout,
    /// The center of mass's highest point.
    Apogee,
    /// Parachute `index` (in the order given) triggered; it opens after its lag.
    ParachuteTrigger(usize),
    /// Parachute `index` opened.
    ParachuteDeploy(usize),
    /// Mass shift `index` (in the order given) started.
    Shift(usize),
    /// Release `index` (in the order given) fired: its part left the rocket.
    Release(usize),
    /// The center of mass reached the ground.
    Landing,
    /// The flight reached its time limit.
    TimeLimit,
}

impl EventKind {
    /// Short snake-case name, for tables and files.
    pub fn name(&self) -> String {
        match self {
            EventKind::Liftoff => "liftoff".into(),
            EventKind::RailExit => "rail_exit".into(),
            EventKind::Burnout => "burnout".into(),
            EventKind::Apogee => "apogee".into(),
            EventKind::ParachuteTrigger(i) => format!("parachute_{i}_trigger"),
            EventKind::ParachuteDeploy(i) => format!("parachute_{i}_deploy"),
            EventKind::Shift(i) => format!("shift_{i}"),
            EventKind::Release(i) => format!("release_{i}"),
            EventKind::Landing => "landing".into(),
            EventKind::TimeLimit => "time_limit".into(),
        }
    }
}

/// One event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    pub kind: EventKind,
    pub time_s: f64,
    /// Height of the center of mass above ground, m.
    pub altitude_m: f64,
    /// Speed of the center of mass, m/s.
    pub speed_m_s: f64,
}
