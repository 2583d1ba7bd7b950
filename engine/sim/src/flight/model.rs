//! The flight model: every table a flight reads, built once before it starts, and the pure
//! per-instant evaluations (mass state, derivative, step end) that the single flight and the
//! batch engine's lanes both call; the kernels written over lanes are in `model/kernels.rs`.

use super::config::{Environment, Parachute, Rail, SimOptions};
use super::setup_error::{Bound, SetupError};
use super::SimError;
use crate::aero_loads::{self, aero_loads, AeroTables, AirAt};
use crate::atmosphere::{Air, AirTable};
use crate::cycloid;
use crate::eom::{self, MassLanes, MassState, Nozzle, NozzleLanes, N3, N6};
use crate::frames;
use crate::integrate::roots::brent_root_bracketed;
use crate::lanes::{F64x4, Real, V3};
use crate::massprops::{
    mass_state_lanes, MassInputs, MassModel, MassModelLanes, PropellantState, Removed,
};
use crate::releases::{PartChute, Release, ReleasePlan};
use crate::shifts::{MassShift, ShiftPlan};
use crate::trigger::Trigger;
use crate::turbulence::Gusts;
use hpr_design::motor::{MotorState, MotorTables};
use nalgebra::Vector3;

mod kernels;
pub use kernels::{
    derivative_6dof_lanes, end_point_lanes, CenterLanes, EndLanes, FourModels, ModelLanes,
};

/// Most parts that shifts may move in one flight: the mass kernel's fixed arrays, whose size
/// the flight's set-up checks against.
pub use crate::massprops::MAX_MOVING_PARTS;

/// A shift as the flight runs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftSpec {
    pub part: usize,
    pub trigger: Trigger,
    pub travel_m: f64,
    pub duration_s: f64,
}

/// Most releases in one flight.
pub const MAX_RELEASES: usize = 8;

/// A release as the flight runs it (the part's mass properties are the mass model's
/// [`crate::massprops::ReleasedMass`] of the same index).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReleaseSpec {
    pub trigger: Trigger,
    /// The part's drag area falling free, m².
    pub cda_m2: f64,
    /// Its own parachute, and the air its open canopy carries, m³.
    pub parachute: Option<(PartChute, f64)>,
}

/// The rail as the flight needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailGeometry {
    /// Unit vector along the rail, inertial.
    pub direction_n: Vector3<f64>,
    /// Attitude on the rail.
    pub attitude: [f64; 4],
    /// Distance O travels along the rail until the upper guide (or the aft end) leaves it, m.
    pub travel_to_exit_m: f64,
    /// O's position at rest on the pad, inertial, m.
    pub o_start_n: Vector3<f64>,
}

/// Everything a flight reads, built once.
#[derive(Debug, Clone)]
pub struct FlightModel {
    pub mass: MassModel,
    /// `mass` as the mass-property kernel reads it, built with the model (crate-private, so
    /// that it cannot be set apart from `mass`: nothing changes `mass` once the model is
    /// built).
    pub(crate) mass_lanes: MassModelLanes<f64>,
    pub motor: MotorTables,
    pub nozzle: Nozzle,
    pub aero: std::sync::Arc<AeroTables>,
    /// Multiplies the drag coefficient (a dispersion; 1 by default).
    pub drag_scale: f64,
    /// The atmosphere, tabulated (see [`AirTable`]): the standard one shared by every flight,
    /// a site's by every variant made from one flight.
    pub air: std::sync::Arc<AirTable>,
    pub env: Environment,
    /// The Earth's rotation in the launch frame, rad/s ([`Environment::earth_rate_n`]: `None`
    /// without a latitude), computed once.
    pub earth_rate_n: Option<[f64; 3]>,
    pub rail: RailGeometry,
    pub parachutes: Vec<Parachute>,
    /// Each parachute's drag area and the air its open canopy carries, in `parachutes`'
    /// order, computed once ([`eom::CanopyShape::added_air_volume_m3`]).
    pub canopies: Vec<eom::Canopies<f64>>,
    pub shifts: Vec<ShiftSpec>,
    /// The releases, in the order given; release `j`'s time is `starts[shifts.len() + j]`
    /// ([`ShiftStarts`]).
    pub releases: Vec<ReleaseSpec>,
    pub options: SimOptions,
    /// Motor's burnout time (last thrust point), s.
    pub burnout_s: f64,
    /// Motor's first ejection delay, s (None if plugged).
    pub motor_delay_s: Option<f64>,
    /// Times at which the thrust curve bends (stop times of the powered flight), s.
    pub thrust_knots_s: Vec<f64>,
    /// Reference diameter, m, and the whole rocket's Mach-0 center of pressure, m aft of the tip.
    pub ref_diameter_m: f64,
    pub cp_mach0_m: f64,
    /// The mass state while nothing changes the mass (motor out, no part moving), one per
    /// set of started shifts and fired releases (bit `k` of the index: shift `k` has started,
    /// and so has ended; bit `shifts.len() + j`: release `j` has fired), for flights with at
    /// most [`SETTLED_MAX_SHIFTS`] shifts and releases together; built once by
    /// [`FlightModel::with_settled_states`]. Empty: always compute.
    pub settled: Vec<MassState>,
    /// The seed of the flight's noise: its parachutes' sensor noise ([`crate::sensor`]) and
    /// its wind's gusts. Set by [`FlightModel::set_noise_seed`], which draws the gusts.
    pub sensor_seed: u64,
    /// Air brakes and their controller, if the rocket has them.
    pub air_brakes: Option<BrakeModel>,
    /// The wind's gusts ([`crate::turbulence`]), drawn once from the seed; `None` without
    /// turbulence.
    pub gusts: Option<Gusts>,
}

impl FlightModel {
    /// Set the flight's noise seed and draw its gusts from it (a wind with turbulence).
    pub fn set_noise_seed(&mut self, seed: u64) {
        let intensity = self.env.wind.turbulence_intensity();
        if self.sensor_seed == seed && (self.gusts.is_some() || intensity == 0.0) {
            return;
        }
        self.sensor_seed = seed;
        self.gusts =
            (intensity > 0.0).then(|| Gusts::new(intensity, seed, self.options.max_time_s));
    }

    /// The wind's factor at `t` (s): `1 + I x(t)` with turbulence, exactly 1 without.
    #[inline(always)]
    pub fn gust(&self, t: f64) -> f64 {
        self.gust_at(t).unwrap_or(1.0)
    }

    /// The wind's factor at `t` with turbulence, `None` without (as the kernels take it).
    #[inline(always)]
    pub fn gust_at(&self, t: f64) -> Option<f64> {
        self.gusts.as_ref().map(|g| g.factor(t))
    }
}

/// Air brakes as the flight reads them ([`hpr_design::AirBrakes`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BrakeModel {
    /// The brakes' drag coefficient fully open, on the rocket's reference area.
    pub cd_open: f64,
    /// The apogee the controller aims at, m above the launch site.
    pub target_apogee_m: f64,
    /// Time between the controller's samples, s.
    pub period_s: f64,
}

/// How closely the brakes' controller solves for their opening (a fraction of their travel).
const OPENING_TOL: f64 = 1e-12;

impl BrakeModel {
    /// The opening (0 closed, 1 fully open) the controller asks for, from the state it reads
    /// at a sample: the center of mass `height_m` above the site climbing at `climb_m_s`,
    /// the rocket's `mass_kg`, the air's `density_kg_m3` and `g_m_s2`, and the rocket's own
    /// drag coefficient `cd_rocket` (on `area_m2`). It predicts the apogee of a vertical coast
    /// against gravity and a drag `k v²` per unit mass, `k = ρ A (cd_rocket + u cd_open)/2m`,
    /// in air of the density it reads: `h + ln(1 + k v²/g)/(2k)`, and takes the opening `u`
    /// that makes it the target (Brent's method, the events' root finder, to 1e-12), 0 when
    /// even closed the rocket falls short of it or no longer climbs, 1 when even fully open
    /// it overshoots.
    #[allow(clippy::too_many_arguments)]
    pub fn opening(
        &self,
        height_m: f64,
        climb_m_s: f64,
        mass_kg: f64,
        density_kg_m3: f64,
        g_m_s2: f64,
        cd_rocket: f64,
        area_m2: f64,
    ) -> f64 {
        let climbing = climb_m_s > 0.0 && mass_kg > 0.0;
        if !climbing {
            return 0.0;
        }
        let apogee = |u: f64| {
            let k = 0.5 * density_kg_m3 * area_m2 * (cd_rocket + u * self.cd_open) / mass_kg;
            let v2 = climb_m_s * climb_m_s;
            if k > 0.0 {
                height_m + (k * v2 / g_m_s2).ln_1p() / (2.0 * k)
            } else {
                height_m + v2 / (2.0 * g_m_s2)
            }
        };
        let miss = |u: f64| apogee(u) - self.target_apogee_m;
        let (closed, open) = (miss(0.0), miss(1.0));
        let overshoots = closed > 0.0;
        if !overshoots {
            return 0.0;
        }
        if open >= 0.0 {
            return 1.0;
        }
        // Bracketed (closed > 0 > open) and finite: Brent's method cannot fail here.
        brent_root_bracketed(miss, 0.0, closed, 1.0, open, OPENING_TOL).unwrap_or(1.0)
    }
}

/// Most shifts and releases together for which [`FlightModel::settled`] is tabulated
/// (2⁴ = 16 states).
pub const SETTLED_MAX_SHIFTS: usize = 4;

/// Start times of each shift, then fire times of each release (infinite until its trigger
/// fires): a shift moves its part for `t > start`, a release has taken its part out for
/// `t ≥ its time`, so that the step that restarts at a release flies without the part.
pub type ShiftStarts = [f64; MAX_SHIFTS];
/// Most shifts and releases together in one flight.
pub const MAX_SHIFTS: usize = 16;

/// Everything at one instant that depends on time alone (and on which shifts have started).
#[derive(Debug, Clone, Copy, Default)]
pub struct Instant {
    pub motor: MotorState,
    pub mass: MassState,
}

/// The last [`Instant`] a flight computed while the mass was changing, and what it holds
/// for: its time and the count of shift-start changes (`starts` changes only with that
/// count). A Dormand–Prince step's last two stages and the step's end share a time, so a
/// flight keeps its last computed instant and computes each one once: the same numbers,
/// since an instant depends on nothing else. Settled instants are read from
/// [`FlightModel::settled`] in place.
#[derive(Debug, Clone, Copy, Default)]
pub struct InstantMemo {
    key: Option<(u64, u64)>,
    inst: Instant,
}

impl InstantMemo {
    /// The mass state and the thrust at `t` for `starts` (whose changes `starts_changed`
    /// counts).
    #[inline]
    pub fn get<'m>(
        &'m mut self,
        model: &'m FlightModel,
        starts: &ShiftStarts,
        starts_changed: u64,
        t: f64,
    ) -> (&'m MassState, f64) {
        if let Some(ms) = model.settled_state(starts, t) {
            return (ms, 0.0);
        }
        self.computed(model, starts, starts_changed, t)
    }

    /// [`InstantMemo::get`] where the caller has found the mass not settled at `t`
    /// ([`FlightModel::mass_settled`] false, so [`FlightModel::settled_state`] is `None`).
    #[inline]
    pub fn computed<'m>(
        &'m mut self,
        model: &'m FlightModel,
        starts: &ShiftStarts,
        starts_changed: u64,
        t: f64,
    ) -> (&'m MassState, f64) {
        let key = Some((t.to_bits(), starts_changed));
        if self.key != key {
            model.instant_computed_into(starts, t, &mut self.inst);
            self.key = key;
        }
        (&self.inst.mass, self.inst.motor.thrust_n)
    }
}

impl FlightModel {
    /// The air the loads see (none in a vacuum).
    #[inline]
    fn air_at(&self, air: &Air) -> AirAt {
        AirAt {
            density_kg_m3: if self.env.vacuum {
                0.0
            } else {
                air.density_kg_m3
            },
            speed_of_sound_m_s: air.speed_of_sound_m_s,
        }
    }

    /// Motor and mass state at `t`. While nothing changes the mass it is read from
    /// [`FlightModel::settled`] (the same numbers, computed once).
    #[inline]
    pub fn instant(&self, starts: &ShiftStarts, t: f64) -> Instant {
        match self.settled_state(starts, t) {
            Some(ms) => Instant {
                motor: MotorState::default(),
                mass: *ms,
            },
            None => self.instant_computed(starts, t),
        }
    }

    /// The tabulated mass state at `t` if nothing changes the mass then (the motor's state
    /// is then all zeros), `None` otherwise.
    #[inline]
    pub fn settled_state(&self, starts: &ShiftStarts, t: f64) -> Option<&MassState> {
        if !self.settled.is_empty() && self.mass_settled(starts, t) {
            let mut set = 0;
            let n = self.shifts.len();
            for (k, &start) in starts.iter().enumerate().take(n) {
                if t > start {
                    set |= 1 << k;
                }
            }
            for j in 0..self.releases.len() {
                if t >= starts[n + j] {
                    set |= 1 << (n + j);
                }
            }
            return Some(&self.settled[set]);
        }
        None
    }

    /// [`FlightModel::instant`] computed from the motor and the shifts' motions.
    #[inline]
    pub fn instant_computed(&self, starts: &ShiftStarts, t: f64) -> Instant {
        let mut inst = Instant::default();
        self.instant_computed_into(starts, t, &mut inst);
        inst
    }

    /// [`FlightModel::instant_computed`] written in place (a flight's memo is refreshed
    /// without copying the instant through the stack).
    #[inline(never)]
    pub fn instant_computed_into(&self, starts: &ShiftStarts, t: f64, out: &mut Instant) {
        let mut x = MassInputs::zero();
        out.motor = self.mass_inputs_into(starts, t, &mut x, 0);
        out.mass = mass_state_lanes(&self.mass_lanes, &x).to_state();
    }

    /// The motor's state at `t`, and lane `l` of `x` set to what the mass-property kernel
    /// ([`crate::massprops::mass_state_lanes`]) reads of it and of the shifts' motions then.
    #[inline(always)]
    pub fn mass_inputs_into<S: Real>(
        &self,
        starts: &ShiftStarts,
        t: f64,
        x: &mut MassInputs<S>,
        l: usize,
    ) -> MotorState {
        self.mass_inputs_with(self.motor.eval(t), starts, t, x, l)
    }

    /// [`FlightModel::mass_inputs_into`] for the motor's state `motor` at `t`, evaluated by
    /// the caller.
    #[inline(always)]
    pub fn mass_inputs_with<S: Real>(
        &self,
        motor: MotorState,
        starts: &ShiftStarts,
        t: f64,
        x: &mut MassInputs<S>,
        l: usize,
    ) -> MotorState {
        let prop = PropellantState {
            mass_kg: motor.propellant_kg,
            rate_kg_s: motor.propellant_rate_kg_s,
            accel_kg_s2: motor.propellant_accel_kg_s2,
        };
        x.set_propellant(l, &prop, self.mass.grains.as_ref());
        for m in x.motions.iter_mut().take(self.mass_lanes.parts) {
            *m.delta_m.lane_mut(l) = 0.0;
            *m.rate_m_s.lane_mut(l) = 0.0;
            *m.accel_m_s2.lane_mut(l) = 0.0;
        }
        for (k, s) in self.shifts.iter().enumerate() {
            let start = starts[k];
            if t > start {
                let c = cycloid::evaluate(t, start, s.duration_s, s.travel_m);
                let acc = &mut x.motions[s.part];
                *acc.delta_m.lane_mut(l) += c.delta_m;
                *acc.rate_m_s.lane_mut(l) += c.rate_m_s;
                *acc.accel_m_s2.lane_mut(l) += c.accel_m_s2;
            }
        }
        if self.mass_lanes.releases {
            let gone = self.removed(starts, t, |k| x.motions[k].delta_m.lane(l));
            x.set_removed(l, gone.as_ref());
        }
        motor
    }

    /// How far its shifts have moved moving part `part` by `t`, m (0 for `None`): the sum
    /// [`FlightModel::mass_inputs_into`] makes, in the same order.
    pub fn part_delta_m(&self, starts: &ShiftStarts, t: f64, part: Option<usize>) -> f64 {
        let Some(p) = part else {
            return 0.0;
        };
        let mut delta = 0.0;
        for (k, s) in self.shifts.iter().enumerate() {
            if s.part == p && t > starts[k] {
                delta += cycloid::evaluate(t, starts[k], s.duration_s, s.travel_m).delta_m;
            }
        }
        delta
    }

    /// What the parts released by `t` take out of the rocket (`None`: none has left), given
    /// how far its shifts have moved moving part `k`, `delta_m(k)`.
    #[inline]
    pub fn removed(
        &self,
        starts: &ShiftStarts,
        t: f64,
        delta_m: impl Fn(usize) -> f64,
    ) -> Option<Removed<f64>> {
        let n = self.shifts.len();
        let mut out: Option<Removed<f64>> = None;
        for (j, part) in self.mass.released.iter().enumerate() {
            if t >= starts[n + j] {
                let c = part.center_b(part.moving_part.map_or(0.0, &delta_m));
                out.get_or_insert(Removed::NONE).add(part, &c);
            }
        }
        out
    }

    /// Tabulate [`FlightModel::settled`]: for every set of started shifts, the mass state
    /// once the motor is out and those shifts have ended (the same at every such instant:
    /// the motor's state is then all zeros and each part rests at the end of its travel).
    pub fn with_settled_states(mut self) -> FlightModel {
        let n = self.shifts.len() + self.releases.len();
        self.settled = Vec::new();
        if n > SETTLED_MAX_SHIFTS {
            return self;
        }
        let longest = self.shifts.iter().map(|s| s.duration_s).fold(0.0, f64::max);
        let t = self.motor.burn_time_s().max(0.0) + longest + 1.0;
        let table: Vec<MassState> = (0..1usize << n)
            .map(|set| {
                let mut starts = [f64::INFINITY; MAX_SHIFTS];
                for (k, s) in starts.iter_mut().enumerate().take(n) {
                    if set & (1 << k) != 0 {
                        *s = 0.0;
                    }
                }
                debug_assert!(self.mass_settled(&starts, t));
                self.instant_computed(&starts, t).mass
            })
            .collect();
        if table.iter().all(|m| m.mass_kg.is_finite()) {
            self.settled = table;
        }
        self
    }

    /// Whether nothing changes the mass at `t`: the motor is out and every shift that has
    /// started has ended, judged exactly as [`FlightModel::instant`] evaluates them (so the
    /// mass state is the same at every such instant, given the same starts).
    #[inline(always)]
    pub fn mass_settled(&self, starts: &ShiftStarts, t: f64) -> bool {
        t >= self.motor.burn_time_s()
            && self.shifts.iter().enumerate().all(|(k, s)| {
                let start = starts[k];
                t <= start || (t - start) / s.duration_s >= 1.0
            })
    }

    /// Whether the mass, settled at `t` ([`FlightModel::mass_settled`]), stays settled at
    /// every later time for these starts: every shift that has started did so before `t`
    /// (its `(t − start) / duration ≥ 1` then holds later too, the subtraction and the
    /// division being monotone), the others never start (an infinite start).
    #[inline(always)]
    pub fn settled_from_now_on(&self, starts: &ShiftStarts, t: f64) -> bool {
        (0..self.shifts.len()).all(|k| starts[k] == f64::INFINITY || t > starts[k])
    }

    /// Static margin (center of pressure at Mach 0 minus center of mass, in calibres).
    #[inline]
    pub fn static_margin(&self, ms: &MassState) -> f64 {
        self.static_margin_of(ms.r_cm.z)
    }

    /// [`FlightModel::static_margin`] given the center of mass's body z, m (negative: aft).
    #[inline]
    pub fn static_margin_of(&self, r_cm_z_m: f64) -> f64 {
        (self.cp_mach0_m - (-r_cm_z_m)) / self.ref_diameter_m
    }

    /// Flight margin at `mach`, given the center of mass's body z, m.
    #[inline]
    pub fn flight_margin_of(&self, r_cm_z_m: f64, mach: f64) -> f64 {
        (self.aero.cp_m(mach) - (-r_cm_z_m)) / self.ref_diameter_m
    }

    #[inline]
    fn wind_n(&self, h: f64, t: f64) -> Vector3<f64> {
        kernels::gusted(ModelLanes::<f64>::wind(self, h), self.gust_at(t)).to_na()
    }

    /// The 6-DOF derivative (free flight) at `(t, y)`, air brakes closed.
    #[inline]
    pub fn derivative_6dof(&self, starts: &ShiftStarts, t: f64, y: &[f64; N6], dy: &mut [f64; N6]) {
        let inst = self.instant(starts, t);
        self.derivative_6dof_at(&inst.mass, inst.motor.thrust_n, 0.0, t, y, dy);
    }

    /// [`FlightModel::derivative_6dof`] given the mass state, the thrust and the air brakes'
    /// drag coefficient on the reference area (0: closed) at `t`.
    #[inline]
    pub fn derivative_6dof_at(
        &self,
        ms: &MassState,
        thrust_n: f64,
        brake_cd: f64,
        t: f64,
        y: &[f64; N6],
        dy: &mut [f64; N6],
    ) {
        let gust = self.gust_at(t);
        derivative_6dof_lanes(self, gust, &MassLanes::of(ms), thrust_n, brake_cd, y, dy);
    }

    /// The rail's derivative: O slides along the rail; attitude fixed, no rotation.
    #[inline]
    pub fn derivative_rail(&self, starts: &ShiftStarts, t: f64, y: &[f64; N6], dy: &mut [f64; N6]) {
        let inst = self.instant(starts, t);
        self.derivative_rail_at(&inst.mass, inst.motor.thrust_n, t, y, dy);
    }

    /// [`FlightModel::derivative_rail`] given the mass state and the thrust at `t`.
    #[inline]
    pub fn derivative_rail_at(
        &self,
        ms: &MassState,
        thrust_n: f64,
        t: f64,
        y: &[f64; N6],
        dy: &mut [f64; N6],
    ) {
        let u = self.rail.direction_n;
        let v = Vector3::new(y[3], y[4], y[5]);
        let speed = v.dot(&u);
        let h = (Vector3::new(y[0], y[1], y[2])
            + frames::body_to_inertial(&self.rail.attitude) * ms.r_cm)
            .z;
        let air = self.air.at_msl(h + self.env.elevation_m);
        let r = frames::body_to_inertial(&self.rail.attitude);
        let wind_b = r.transpose() * self.wind_n(h, t);
        let v_air_b = r.transpose() * v - wind_b;
        let air_at = self.air_at(&air);
        let powered = thrust_n > 0.0;
        let loads = aero_loads(
            &self.aero,
            &v_air_b,
            &(v_air_b + ms.r_cm_rate),
            &Vector3::zeros(),
            &air_at,
            powered,
            self.drag_scale,
        );
        let g_along = -self.env.gravity.at(h) * u.z;
        let mut a = (thrust_n + loads.force_b.z) / ms.mass_kg + g_along;
        if a < 0.0 && speed <= 0.0 {
            a = 0.0;
        }
        dy[0] = y[3];
        dy[1] = y[4];
        dy[2] = y[5];
        dy[3] = a * u.x;
        dy[4] = a * u.y;
        dy[5] = a * u.z;
        dy[6..].iter_mut().for_each(|d| *d = 0.0);
    }

    /// Descent under the open `canopies`: the center of mass as a point (its mass the mass
    /// state's at `starts`).
    #[inline]
    pub fn derivative_descent(
        &self,
        starts: &ShiftStarts,
        canopies: &eom::Canopies<f64>,
        t: f64,
        y: &[f64; N3],
        dy: &mut [f64; N3],
    ) -> FlightAux {
        let (mass_kg, r_cm_z_m) = match self.settled_state(starts, t) {
            Some(ms) => (ms.mass_kg, ms.r_cm.z),
            None => {
                let ms = self.instant_computed(starts, t).mass;
                (ms.mass_kg, ms.r_cm.z)
            }
        };
        let (at, speed_of_sound_m_s) = self.descent_rates_of(mass_kg, canopies, t, y, dy);
        let rel = Vector3::new(y[3], y[4], y[5]) - at.wind_n.to_na();
        let a = Vector3::new(dy[3], dy[4], dy[5] + at.g);
        FlightAux {
            mass_kg,
            r_cm_z_m,
            air_speed_m_s: rel.norm(),
            speed_of_sound_m_s,
            density_kg_m3: at.rho,
            accel_cm_m_s2: a.norm(),
            air_velocity_b: Vector3::repeat(f64::NAN),
        }
    }
}

impl FlightModel {
    /// The descent's derivative alone, as the integrator calls it, for the rocket with every
    /// part on board: the mass is the structure's plus the propellant left (exactly the mass
    /// state's mass; its center and inertia do not enter the point-mass descent). Returns the
    /// surroundings it used and the speed of sound there.
    #[inline]
    pub fn descent_rates(
        &self,
        canopies: &eom::Canopies<f64>,
        t: f64,
        y: &[f64; N3],
        dy: &mut [f64; N3],
    ) -> (eom::Surroundings<f64>, f64) {
        self.descent_rates_of(self.descent_mass(t), canopies, t, y, dy)
    }

    /// [`FlightModel::descent_rates`] of a point of mass `mass_kg` (the rocket's
    /// [`FlightModel::descent_mass_less`] the parts that left, or a released part's own).
    #[inline]
    pub fn descent_rates_of(
        &self,
        mass_kg: f64,
        canopies: &eom::Canopies<f64>,
        t: f64,
        y: &[f64; N3],
        dy: &mut [f64; N3],
    ) -> (eom::Surroundings<f64>, f64) {
        let (at, speed_of_sound_m_s) = kernels::descent_surroundings(self, y[2], self.gust_at(t));
        eom::descent_derivative(y, mass_kg, canopies, &at, dy);
        (at, speed_of_sound_m_s)
    }

    /// The descent's `∂v̇/∂v` at `(t, y)` for a point of mass `mass_kg` under `canopies`, in
    /// the surroundings [`FlightModel::descent_rates_of`] reads
    /// ([`eom::descent_velocity_jacobian`]).
    #[inline]
    pub fn descent_velocity_jacobian(
        &self,
        mass_kg: f64,
        canopies: &eom::Canopies<f64>,
        t: f64,
        y: &[f64; N3],
    ) -> [[f64; 3]; 3] {
        let (at, _) = kernels::descent_surroundings(self, y[2], self.gust_at(t));
        eom::descent_velocity_jacobian(y, mass_kg, canopies, &at)
    }

    /// The mass a descent carries at `t` with every part on board: the structure's plus the
    /// propellant left (exactly the mass state's mass).
    #[inline]
    pub fn descent_mass(&self, t: f64) -> f64 {
        // After burnout (nearly every descent) the motor's state is known without a call:
        // empty, exactly as `eval` gives it.
        let propellant_kg = if t >= self.motor.burn_time_s() {
            0.0
        } else {
            self.motor.eval(t).propellant_kg
        };
        self.mass.fixed_mass_kg + propellant_kg
    }

    /// The mass the parts released by `t` took away, kg (`None`: none has left), summed as
    /// the mass state sums it ([`FlightModel::removed`]).
    #[inline]
    pub fn removed_mass_kg(&self, starts: &ShiftStarts, t: f64) -> Option<f64> {
        let n = self.shifts.len();
        let mut gone: Option<f64> = None;
        for (j, part) in self.mass.released.iter().enumerate() {
            if t >= starts[n + j] {
                *gone.get_or_insert(0.0) += part.mass_kg;
            }
        }
        gone
    }

    /// The mass a descent carries at `t` once parts of `removed_kg` ([`FlightModel::removed_mass_kg`])
    /// have left: exactly the mass state's mass (the same numbers in the same order).
    #[inline(always)]
    pub fn descent_mass_less(&self, t: f64, removed_kg: Option<f64>) -> f64 {
        let m = self.descent_mass(t);
        match removed_kg {
            None => m,
            Some(gone) => m - gone,
        }
    }

    /// The center of mass's position and velocity (inertial) and a sample's figures at the end
    /// of a step whose derivative `dy` is known (the integrator's FSAL stage), given the mass
    /// state there `ms`: no aerodynamics. Agrees with [`FlightModel::derivative_6dof`]'s
    /// figures.
    pub fn end_point(
        &self,
        ms: &MassState,
        t: f64,
        y: &[f64; N6],
        dy: &[f64; N6],
        rail: bool,
    ) -> EndFigures {
        if !rail {
            return end_point_lanes(self, self.gust_at(t), &CenterLanes::of(ms), y, dy)
                .figures(ms.mass_kg, ms.r_cm.z);
        }
        let r = frames::body_to_inertial(&self.rail.attitude);
        let pos = eom::center_of_mass_position(y, ms, &r);
        let vel = eom::center_of_mass_velocity(y, ms, &r);
        let air = self.air_at(&self.air.at_msl(pos.z + self.env.elevation_m));
        let v_air_n = vel - self.wind_n(pos.z, t);
        let aux = FlightAux {
            mass_kg: ms.mass_kg,
            r_cm_z_m: ms.r_cm.z,
            air_speed_m_s: v_air_n.norm(),
            speed_of_sound_m_s: air.speed_of_sound_m_s,
            density_kg_m3: air.density_kg_m3,
            accel_cm_m_s2: Vector3::new(dy[3], dy[4], dy[5]).norm(),
            air_velocity_b: Vector3::zeros(),
        };
        (pos, vel, aux)
    }
}

/// A step end's figures: the center of mass's position and velocity (inertial) and what a
/// sample reads besides ([`FlightModel::end_point`]).
pub type EndFigures = (Vector3<f64>, Vector3<f64>, FlightAux);

/// What a derivative evaluation knows besides the derivative.
#[derive(Debug, Clone, Copy)]
pub struct FlightAux {
    pub mass_kg: f64,
    /// The center of mass's body z, m (negative: aft of the tip).
    pub r_cm_z_m: f64,
    pub air_speed_m_s: f64,
    pub speed_of_sound_m_s: f64,
    /// The air's density there, kg/m³.
    pub density_kg_m3: f64,
    /// Magnitude of the center of mass's inertial acceleration, m/s².
    pub accel_cm_m_s2: f64,
    /// The air's velocity relative to the rocket in body axes, m/s (zero on the rail, where
    /// the angle of attack is held at zero; NaN in the descent, where there is none). Kept
    /// rather than the angle, which only a sample reads ([`FlightAux::alpha_rad`]).
    pub air_velocity_b: Vector3<f64>,
}

impl FlightAux {
    /// The angle of attack, rad (0 on the rail, NaN in the descent).
    #[inline]
    pub fn alpha_rad(&self) -> f64 {
        let (cross, axial) = self.alpha_arguments();
        Self::alpha_of(cross, axial)
    }

    /// The angle of attack's `atan2` arguments: the crossflow speed (≥ 0) and the axial air
    /// velocity, m/s; (0, 1) in still air, where the angle is taken as 0.
    #[inline]
    pub fn alpha_arguments(&self) -> (f64, f64) {
        let v = &self.air_velocity_b;
        if v.norm() == 0.0 {
            (0.0, 1.0)
        } else {
            ((v.x * v.x + v.y * v.y).sqrt(), v.z)
        }
    }

    /// The angle of attack from [`FlightAux::alpha_arguments`], rad.
    #[inline]
    pub fn alpha_of(cross: f64, axial: f64) -> f64 {
        crate::lanes::atan2_upper(cross, axial)
    }
}

/// Build the rail geometry: the aft end at the foot, O up the rail.
pub fn rail_geometry(
    rail: &Rail,
    aft_m: f64,
    upper_guide_m: Option<f64>,
) -> Result<RailGeometry, SimError> {
    let bad = |field: &'static str, bound: Bound, got: f64| {
        SimError::Setup(SetupError::Rail { field, bound, got })
    };
    if !(rail.length_m.is_finite() && rail.length_m > 0.0) {
        return Err(bad("length_m", Bound::PositiveFinite, rail.length_m));
    }
    if !(rail.inclination_deg.is_finite()
        && rail.inclination_deg > 0.0
        && rail.inclination_deg <= 90.0)
    {
        return Err(bad(
            "inclination_deg",
            Bound::AboveZeroAtMost90Deg,
            rail.inclination_deg,
        ));
    }
    if !rail.heading_deg.is_finite() {
        return Err(bad("heading_deg", Bound::Finite, rail.heading_deg));
    }
    let guide_height = upper_guide_m.map_or(0.0, |g| aft_m - g);
    let travel = rail.length_m - guide_height;
    if travel <= 0.0 {
        return Err(SimError::Setup(SetupError::RailTooShort {
            guide_height_m: guide_height,
            length_m: rail.length_m,
        }));
    }
    let attitude = frames::rail_attitude(rail.inclination_deg, rail.heading_deg);
    let direction_n = frames::body_to_inertial(&attitude) * Vector3::z();
    Ok(RailGeometry {
        direction_n,
        attitude,
        travel_to_exit_m: travel,
        o_start_n: direction_n * aft_m,
    })
}

/// The releases as the model runs them.
pub fn release_specs(releases: &[Release], plan: &ReleasePlan) -> Vec<ReleaseSpec> {
    releases
        .iter()
        .zip(&plan.cda_m2)
        .map(|(r, &cda_m2)| ReleaseSpec {
            trigger: r.trigger,
            cda_m2,
            parachute: r
                .parachute
                .map(|p| (p, p.canopy.added_air_volume_m3(p.cds_m2))),
        })
        .collect()
}

/// Group shifts for the model.
pub fn shift_specs(shifts: &[MassShift], plan: &ShiftPlan) -> Vec<ShiftSpec> {
    shifts
        .iter()
        .zip(&plan.part_of_shift)
        .map(|(s, &part)| ShiftSpec {
            part,
            trigger: s.trigger,
            travel_m: s.travel_m,
            duration_s: s.duration_s,
        })
        .collect()
}
