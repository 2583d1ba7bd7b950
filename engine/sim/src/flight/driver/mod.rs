//! The single-flight driver: pad, rail, free flight, descent, landing. It steps the chosen
//! integrator one step at a time, never across a stop time (thrust-curve knots, burnout,
//! timed triggers, canopy openings, the 16 parts of every shift), locates events by
//! root-finding on the dense output, and records samples and metrics.

use super::config::Integrator;
use super::model::{
    EndFigures, FlightAux, FlightModel, InstantMemo, ModelLanes, ShiftStarts, MAX_SHIFTS,
};
use super::output::{
    Flight, Metrics, Observer, PartFlight, PartSample, Phase, ReleaseRecord, Sample,
};
use super::SimError;
use crate::eom::{self, Canopies, MassLanes, N3, N6};
use crate::events::{Event, EventKind};
use crate::frames;
use crate::integrate::{
    brent_root, brent_root_bracketed, locate_event, Crossing, DenseStepper, Dopri54,
    IntegratorError, Rk4, Rodas4, StepOutcome, Tolerances,
};
use crate::releases::{PartChute, PartTrigger};
use crate::sensor::NoiseProcess;
use crate::shifts::STOPS_PER_SHIFT;
use crate::trigger::Trigger;
use nalgebra::Vector3;

/// Time tolerance of every event, s.
const EVENT_TOL_S: f64 = 1e-12;

/// The integrator of a phase, by value (no trait object): Dormand–Prince for the rail and
/// the free flight, RODAS4 for the descents ([`Stepper::descent`]), or fixed-step RK4 for
/// every phase when the options ask for it.
#[derive(Clone)]
enum Stepper<const N: usize> {
    Adaptive(Box<Dopri54<N>>),
    Fixed(Box<Rk4<N>>),
    Stiff(Box<Rodas4<N>>),
}

macro_rules! each {
    ($s:expr, $x:ident => $e:expr) => {
        match $s {
            Stepper::Adaptive($x) => $e,
            Stepper::Fixed($x) => $e,
            Stepper::Stiff($x) => $e,
        }
    };
}

// The phases, after the macro they use.
mod descent;
mod paused;
mod six_dof;

use descent::Descent;
pub(crate) use paused::{
    fly_to_free, AfterFree, Descending, Paused, PausedPhase, Progress, StepEnd, Verdict,
};
use six_dof::{six_dof_phase, SixDof};

/// What a step watches for: the first derivative that is not finite (where it appeared), so
/// that a flight that goes non-finite stops with [`SimError::NonFinite`] at that place (a NaN
/// makes the adaptive stepper reject until its step underflows; RK4 would carry it into the
/// state), and any other failure is the integration's error in its phase.
#[derive(Clone)]
struct Watch<const N: usize> {
    t_now: f64,
    bad: Option<(f64, [f64; N])>,
}

impl<const N: usize> Watch<N> {
    fn new(t_now: f64) -> Watch<N> {
        Watch { t_now, bad: None }
    }

    #[inline]
    fn observe(&mut self, t: f64, y: &[f64; N], dy: &[f64; N]) {
        if self.bad.is_none() && !dy.iter().all(|v| v.is_finite()) {
            self.bad = Some((t, *y));
        }
    }

    fn error(&self, e: IntegratorError, y_now: &[f64; N], what: &str) -> SimError {
        match self.bad {
            Some((tb, yb)) => non_finite(tb, &yb),
            None => integ_at(self.t_now, y_now, e, what),
        }
    }

    /// The state at the end of an accepted step must be finite.
    #[inline]
    fn check_end(&self, t: f64, y: &[f64; N]) -> Result<(), SimError> {
        // Every element read (no early exit): a few vector comparisons.
        if y.iter().fold(true, |ok, v| ok & v.is_finite()) {
            return Ok(());
        }
        let (tb, yb) = self.bad.unwrap_or((t, *y));
        Err(non_finite(tb, &yb))
    }
}

impl<const N: usize> Stepper<N> {
    /// One step, never past `t_stop`, counting derivative evaluations in `evals`, watched
    /// by a [`Watch`].
    fn checked_step(
        &mut self,
        mut f: impl FnMut(f64, &[f64; N], &mut [f64; N]),
        t_stop: f64,
        what: &str,
        evals: &mut u64,
    ) -> Result<crate::integrate::StepOutcome, SimError> {
        let mut watch = Watch::new(each!(self, s => s.t()));
        let outcome = each!(self, s => s.step(|t, y, dy| {
            *evals += 1;
            f(t, y, dy);
            watch.observe(t, y, dy);
        }, t_stop))
        .map_err(|e| watch.error(e, each!(self, s => s.y()), what))?;
        watch.check_end(each!(self, s => s.t()), each!(self, s => s.y()))?;
        Ok(outcome)
    }

    /// [`Stepper::checked_step`] with the Jacobian RODAS4 factors given by `jacobian` (see
    /// [`Rodas4::step_with`]; its evaluations of the derivative counted in `evals` too); the
    /// other steppers step as `checked_step` does.
    fn checked_step_with(
        &mut self,
        mut f: impl FnMut(f64, &[f64; N], &mut [f64; N]),
        jacobian: impl FnMut(f64, &[f64; N], &[f64; N], f64, &mut [[f64; N]; N], &mut [f64; N]) -> u64,
        t_stop: f64,
        what: &str,
        evals: &mut u64,
    ) -> Result<crate::integrate::StepOutcome, SimError> {
        let Stepper::Stiff(r) = self else {
            return self.checked_step(f, t_stop, what, evals);
        };
        let mut watch = Watch::new(r.t());
        let before = r.n_eval();
        let outcome = r
            .step_with(
                |t, y, dy| {
                    f(t, y, dy);
                    watch.observe(t, y, dy);
                },
                jacobian,
                t_stop,
            )
            .map_err(|e| watch.error(e, r.y(), what))?;
        *evals += r.n_eval() - before;
        watch.check_end(r.t(), r.y())?;
        Ok(outcome)
    }

    fn new(integrator: &Integrator, atol: [f64; N], rtol: f64) -> Result<Self, IntegratorError> {
        Ok(match *integrator {
            Integrator::Adaptive { .. } => Stepper::Adaptive(Box::new(Dopri54::with_tolerances(
                Tolerances::new(rtol, atol)?,
            ))),
            Integrator::Rk4 { step_s } => Stepper::Fixed(Box::new(Rk4::new(step_s)?)),
        })
    }

    /// The descents' stepper: RODAS4 at the adaptive integrator's tolerances (a point under
    /// drag relaxes to its terminal velocity at a rate `2g/v` that would hold an explicit
    /// method's step at its stability limit; see `descent.rs`), or the fixed-step RK4 asked
    /// for.
    fn descent(
        integrator: &Integrator,
        atol: [f64; N],
        rtol: f64,
    ) -> Result<Self, IntegratorError> {
        Ok(match *integrator {
            Integrator::Adaptive { .. } => Stepper::Stiff(Box::new(Rodas4::with_tolerances(
                Tolerances::new(rtol, atol)?,
            ))),
            Integrator::Rk4 { step_s } => Stepper::Fixed(Box::new(Rk4::new(step_s)?)),
        })
    }
}

/// Absolute tolerances of the 6-DOF state and the descent state.
fn tolerances(integrator: &Integrator) -> (f64, [f64; N6], [f64; N3]) {
    match *integrator {
        Integrator::Adaptive {
            rtol,
            atol_position_m: p,
            atol_velocity_m_s: v,
            atol_quaternion: q,
            atol_rate_rad_s: w,
        } => (
            rtol,
            [p, p, p, v, v, v, q, q, q, q, w, w, w],
            [p, p, p, v, v, v],
        ),
        Integrator::Rk4 { .. } => (1e-6, [1.0; N6], [1.0; N3]),
    }
}

/// The angle of attack is watched from this long after rail exit, s (OpenRocket's 0.25 s).
const ALPHA_WATCH_AFTER_RAIL_S: f64 = 0.25;
/// ... and while the vertical speed is at least this fraction of its highest so far
/// (OpenRocket's 20 %).
const ALPHA_WATCH_CLIMB_FRACTION: f64 = 0.2;

/// Whether the angle of attack given by its `atan2` arguments (crossflow ≥ 0, axial) is larger
/// than `than`'s, without the `atan2`: both lie in [0, π], so `r₁r₂ sin(α₁ − α₂) > 0` says it,
/// but for 180° against 0°, where the sine is 0 too.
fn steeper((cross, axial): (f64, f64), (c, a): (f64, f64)) -> bool {
    let s = cross * a - axial * c;
    s > 0.0 || (s == 0.0 && axial < 0.0 && a > 0.0)
}

/// The flight in progress.
struct Run<'a, O: Observer> {
    model: &'a FlightModel,
    observer: &'a mut O,
    starts: ShiftStarts,
    /// How many times `starts` has changed (a cheap test of whether it did).
    starts_changed: u64,
    /// The last instant computed (see [`InstantMemo`]).
    memo: InstantMemo,
    /// Pending stop times, unsorted; the next one is their minimum above the current time.
    stops: Stops,
    samples: Vec<Sample>,
    events: Vec<Event>,
    metrics: Metrics,
    evaluations: u64,
    steps: u64,
    apogee_done: bool,
    /// Per parachute: where it is between armed and open.
    chutes: Vec<Chute>,
    /// Per parachute, its noisy barometer where one fires it (a sampled height trigger with
    /// [`super::Parachute::noise`]); empty when none does.
    noise: Vec<Option<Barometer>>,
    /// Per trigger owner: whether a height-on-the-way-down trigger has fired (chutes, then shifts).
    rail_exit_done: bool,
    burnout_done: bool,
    /// Highest vertical speed of the center of mass so far, m/s (for the angle-of-attack watch).
    max_climb_m_s: f64,
    /// The largest watched angle of attack so far, as the arguments of
    /// [`FlightAux::alpha_rad`]'s `atan2` (crossflow speed ≥ 0, axial air velocity): angles in
    /// [0, π] compare by a cross product, and the one `atan2` is taken when the flight ends.
    steepest: Option<(f64, f64)>,
    /// The air brakes' drag coefficient as they stand, on the reference area (0: closed),
    /// held from one controller sample to the next.
    brake_cd: f64,
    /// What each release did (its part's flight is filled in once the part has flown).
    releases: Vec<ReleaseRecord>,
    /// A part left at the step's end: the derivative jumps there, so the stepper restarts.
    released_now: bool,
    /// The controller's next sample, s (infinite without brakes; burnout, then every period).
    brake_next_s: f64,
}

/// A parachute's noisy barometer through one flight: its noise, the pressure at its trigger
/// height and its sampling rate, fixed for the flight and so found once.
#[derive(Clone)]
struct Barometer {
    noise: NoiseProcess,
    trigger_pa: f64,
    rate_hz: f64,
}

/// The barometer of each parachute a noisy one fires (a sampled height trigger with a
/// noise), its noise from the flight's sensor seed; empty when none does (nothing allocated).
fn barometers(model: &FlightModel) -> Vec<Option<Barometer>> {
    let noisy = |p: &super::Parachute| match (p.noise, p.trigger, p.sampling_rate_hz) {
        (Some(noise), Trigger::HeightDescending { height_m }, Some(rate_hz)) => {
            Some((noise, height_m, rate_hz))
        }
        _ => None,
    };
    if !model.parachutes.iter().any(|p| noisy(p).is_some()) {
        return Vec::new();
    }
    model
        .parachutes
        .iter()
        .enumerate()
        .map(|(i, p)| {
            noisy(p).map(|(noise, height_m, rate_hz)| Barometer {
                noise: NoiseProcess::new(noise, model.sensor_seed, i as u64),
                trigger_pa: model.air.pressure_msl_pa(height_m + model.env.elevation_m),
                rate_hz,
            })
        })
        .collect()
}

/// Where a parachute is between its trigger and its open canopy.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Chute {
    /// Its trigger's condition is not met yet.
    Armed,
    /// Met; the trigger fires at `fires_s` (a sampled trigger's next sample, a stop time).
    Pending {
        fires_s: f64,
    },
    /// The trigger fired at `fires_s`; the canopy opens `lag_s` later (a stop time).
    Fired {
        fires_s: f64,
    },
    Open,
}

/// Where the rocket is when a trigger fires: what a released part leaves from.
#[derive(Clone, Copy)]
pub(crate) enum Here<'y> {
    /// On the rail, where nothing may leave.
    Rail,
    /// In free flight, the 6-DOF state.
    Free(&'y [f64; N6]),
    /// Under canopy, the center of mass as a point (position, velocity).
    Point(Vector3<f64>, Vector3<f64>),
}

/// Pending stop times, latest first (the next one is at the end); NaN is never a stop.
#[derive(Clone)]
struct Stops(Vec<f64>);

impl Stops {
    /// Take one stop at `s` (its bits) away, if there is one.
    fn remove(&mut self, s: f64) {
        if let Some(i) = self.0.iter().position(|x| x.to_bits() == s.to_bits()) {
            self.0.remove(i);
        }
    }

    fn push(&mut self, s: f64) {
        if s.is_nan() {
            return;
        }
        let i = self.0.partition_point(|&x| x > s);
        self.0.insert(i, s);
    }
}

/// What ended a phase.
pub(crate) enum PhaseEnd {
    RailExit,
    Deploy,
    Landed,
    TimeLimit,
}

impl<'a, O: Observer> Run<'a, O> {
    /// This run's state as another flight's, of `model` with `observer`: everything the
    /// flight has done and holds pending, the memo of its last instant left behind (it is
    /// `model`'s to compute). The caller answers for `model` flying the same as this one's
    /// up to where the run stands ([`Paused::clone_onto`]).
    fn clone_onto<'b, P: Observer>(
        &self,
        model: &'b FlightModel,
        observer: &'b mut P,
    ) -> Run<'b, P> {
        Run {
            model,
            observer,
            starts: self.starts,
            starts_changed: self.starts_changed,
            memo: InstantMemo::default(),
            stops: self.stops.clone(),
            samples: self.samples.clone(),
            events: self.events.clone(),
            metrics: self.metrics,
            evaluations: self.evaluations,
            steps: self.steps,
            apogee_done: self.apogee_done,
            chutes: self.chutes.clone(),
            noise: self.noise.clone(),
            rail_exit_done: self.rail_exit_done,
            burnout_done: self.burnout_done,
            max_climb_m_s: self.max_climb_m_s,
            steepest: self.steepest,
            brake_cd: self.brake_cd,
            releases: self.releases.clone(),
            released_now: self.released_now,
            brake_next_s: self.brake_next_s,
        }
    }

    /// The first stop time after `t` (or the time limit). Time only moves forward, so the
    /// stops at or before `t` are dropped. With turbulence every sample of the gusts is a
    /// stop too (a step then lies within one straight piece of them).
    fn next_stop(&mut self, t: f64) -> f64 {
        let max = match &self.model.gusts {
            Some(g) => self.model.options.max_time_s.min(g.next_sample_s(t)),
            None => self.model.options.max_time_s,
        };
        while let Some(&s) = self.stops.0.last() {
            if s > t {
                return s.min(max);
            }
            self.stops.0.pop();
        }
        max
    }

    fn push_event(&mut self, kind: EventKind, t: f64, altitude_m: f64, speed_m_s: f64) {
        let e = Event {
            kind,
            time_s: t,
            altitude_m,
            speed_m_s,
        };
        self.observer.on_event(&e);
        self.events.push(e);
    }

    /// Start shift `k` at `t` (its stops are the 16 equal parts of the move).
    fn start_shift(
        &mut self,
        k: usize,
        t: f64,
        altitude_m: f64,
        speed_m_s: f64,
    ) -> Result<(), SimError> {
        if !self.rail_exit_done {
            return Err(SimError::ShiftBeforeRailExit {
                index: k,
                time_s: t,
            });
        }
        let model = self.model;
        let part = model.shifts[k].part;
        let n = model.shifts.len();
        for (j, r) in model.mass.released.iter().enumerate() {
            let released_s = self.starts[n + j];
            if r.moving_part == Some(part) && released_s <= t {
                return Err(SimError::ShiftAfterRelease {
                    index: k,
                    release: j,
                    time_s: t,
                    released_s,
                });
            }
        }
        self.starts[k] = t;
        self.starts_changed += 1;
        let d = self.model.shifts[k].duration_s;
        for i in 1..=STOPS_PER_SHIFT {
            self.stops.push(t + d * i as f64 / STOPS_PER_SHIFT as f64);
        }
        self.push_event(EventKind::Shift(k), t, altitude_m, speed_m_s);
        Ok(())
    }

    /// Release `j` fires at `t`, the rocket `here`: its part leaves with the velocity its
    /// material had (no impulse), the rocket flies on without it from `t` (its stepper
    /// restarts there), and the static margin just before and after is recorded.
    #[inline(never)]
    fn release(
        &mut self,
        j: usize,
        t: f64,
        altitude_m: f64,
        speed_m_s: f64,
        here: Here<'_>,
    ) -> Result<(), SimError> {
        let model = self.model;
        let y = match here {
            Here::Rail => {
                return Err(SimError::ReleaseBeforeRailExit {
                    index: j,
                    time_s: t,
                })
            }
            _ if !self.rail_exit_done => {
                return Err(SimError::ReleaseBeforeRailExit {
                    index: j,
                    time_s: t,
                })
            }
            here => here,
        };
        let part = model.mass.released[j];
        // A part leaves from rest in the airframe: not while a shift moves it.
        if let Some(p) = part.moving_part {
            for (k, sh) in model.shifts.iter().enumerate() {
                let start = self.starts[k];
                // Started (at `t` itself, too: it moves from now) and not yet ended, as the
                // mass model judges an end.
                if sh.part == p && start <= t && (t - start) / sh.duration_s < 1.0 {
                    return Err(SimError::ReleaseDuringShift {
                        index: j,
                        shift: k,
                        time_s: t,
                        start_s: start,
                        duration_s: sh.duration_s,
                    });
                }
            }
        }
        let n = model.shifts.len();
        let before = model.static_margin(&model.instant(&self.starts, t).mass);
        let (pos, vel) = match y {
            Here::Free(y) => {
                let c = part.center_b(model.part_delta_m(&self.starts, t, part.moving_part));
                let r = frames::body_to_inertial(&[y[6], y[7], y[8], y[9]]);
                let w = Vector3::new(y[10], y[11], y[12]);
                (
                    Vector3::new(y[0], y[1], y[2]) + r * c,
                    Vector3::new(y[3], y[4], y[5]) + r * w.cross(&c),
                )
            }
            Here::Point(pos, vel) => (pos, vel),
            Here::Rail => unreachable!("refused above"),
        };
        self.starts[n + j] = t;
        self.starts_changed += 1;
        self.released_now = true;
        let after = model.static_margin(&model.instant(&self.starts, t).mass);
        self.releases[j] = ReleaseRecord {
            time_s: Some(t),
            margin_before_cal: Some(before),
            margin_after_cal: Some(after),
            part: Some(PartFlight {
                mass_kg: part.mass_kg,
                start_position_m: [pos.x, pos.y, pos.z],
                start_velocity_m_s: [vel.x, vel.y, vel.z],
                apogee_m: pos.z,
                ..PartFlight::default()
            }),
        };
        self.push_event(EventKind::Release(j), t, altitude_m, speed_m_s);
        Ok(())
    }

    /// Parachute `i`'s trigger condition became true at `t`: it fires now, or, sampled, at
    /// its next sample (a stop time, where [`Run::at_stop`] fires it); it opens `lag_s` after.
    fn trigger_chute(&mut self, i: usize, t: f64, altitude_m: f64, speed_m_s: f64) {
        let chute = &self.model.parachutes[i];
        let (fires_s, lag) = (chute.fires_at(t), chute.lag_s);
        if fires_s == t {
            self.chutes[i] = Chute::Fired { fires_s };
            self.push_event(EventKind::ParachuteTrigger(i), t, altitude_m, speed_m_s);
        } else {
            self.chutes[i] = Chute::Pending { fires_s };
            self.stops.push(fires_s);
        }
        self.stops.push(fires_s + lag);
    }

    /// Fire every trigger of kind `matches` that has not fired yet, at `t`, the rocket `here`
    /// (parachutes, then shifts, then releases).
    fn fire(
        &mut self,
        t: f64,
        altitude_m: f64,
        speed_m_s: f64,
        here: Here<'_>,
        matches: impl Fn(&Trigger) -> bool,
    ) -> Result<(), SimError> {
        for i in 0..self.model.parachutes.len() {
            if self.chute_armed(i) && matches(&self.model.parachutes[i].trigger) {
                self.trigger_chute(i, t, altitude_m, speed_m_s);
            }
        }
        let n = self.model.shifts.len();
        for k in 0..n {
            if self.starts[k].is_infinite() && matches(&self.model.shifts[k].trigger) {
                self.start_shift(k, t, altitude_m, speed_m_s)?;
            }
        }
        for j in 0..self.model.releases.len() {
            if self.starts[n + j].is_infinite() && matches(&self.model.releases[j].trigger) {
                self.release(j, t, altitude_m, speed_m_s, here)?;
            }
        }
        Ok(())
    }

    /// Handle what happens exactly at a stop time `t`, the rocket `here`: burnout, timed
    /// triggers, canopies. Returns true when a canopy opened (the phase must end).
    fn at_stop(
        &mut self,
        t: f64,
        altitude_m: f64,
        speed_m_s: f64,
        here: Here<'_>,
    ) -> Result<bool, SimError> {
        let m = self.model;
        if !self.burnout_done && t >= m.burnout_s {
            self.burnout_done = true;
            self.metrics.burnout_time_s = Some(m.burnout_s);
            self.metrics.static_margin_burnout_cal =
                Some(m.static_margin(&m.instant(&self.starts, m.burnout_s).mass));
            self.push_event(EventKind::Burnout, m.burnout_s, altitude_m, speed_m_s);
        }
        let (burnout, delay) = (m.burnout_s, m.motor_delay_s);
        self.fire(t, altitude_m, speed_m_s, here, |tr| {
            tr.fixed_time(burnout, delay).is_some_and(|ft| ft <= t)
        })?;
        // Sampled triggers that fire here, then the canopies that open here.
        for i in 0..m.parachutes.len() {
            if let Chute::Pending { fires_s } = self.chutes[i] {
                if fires_s <= t {
                    self.chutes[i] = Chute::Fired { fires_s };
                    self.push_event(
                        EventKind::ParachuteTrigger(i),
                        fires_s,
                        altitude_m,
                        speed_m_s,
                    );
                }
            }
        }
        let mut opened = false;
        for i in 0..m.parachutes.len() {
            if let Chute::Fired { fires_s } = self.chutes[i] {
                if fires_s + m.parachutes[i].lag_s <= t {
                    self.chutes[i] = Chute::Open;
                    self.push_event(EventKind::ParachuteDeploy(i), t, altitude_m, speed_m_s);
                    opened = true;
                }
            }
        }
        Ok(opened)
    }

    /// The air brakes' controller at a step's end `t` in free flight, the center of mass at
    /// `pos` moving at `vel`: at or after its sample time (and before apogee) it reads the
    /// state, sets the brakes' opening ([`BrakeModel::opening`]) until its next sample (a stop
    /// time) and returns whether the drag changed (the stepper must start again there).
    fn control_brakes(
        &mut self,
        t: f64,
        pos: Vector3<f64>,
        vel: Vector3<f64>,
        aux: &FlightAux,
    ) -> bool {
        let m = self.model;
        let Some(b) = m.air_brakes else {
            return false;
        };
        if self.apogee_done || t < self.brake_next_s {
            return false;
        }
        let mach = aux.air_speed_m_s / aux.speed_of_sound_m_s;
        let u = b.opening(
            pos.z,
            vel.z,
            aux.mass_kg,
            aux.density_kg_m3,
            ModelLanes::<f64>::gravity(m, pos.z),
            m.aero.cd(mach, false) * m.drag_scale,
            m.aero.ref_area_m2,
        );
        while self.brake_next_s <= t {
            self.brake_next_s += b.period_s;
        }
        self.stops.push(self.brake_next_s);
        let mx = &mut self.metrics;
        mx.air_brakes_max_opening = Some(mx.air_brakes_max_opening.unwrap_or(0.0).max(u));
        if u > 0.0 && mx.air_brakes_open_time_s.is_none() {
            mx.air_brakes_open_time_s = Some(t);
        }
        let cd = u * b.cd_open;
        let changed = cd != self.brake_cd;
        self.brake_cd = cd;
        changed
    }

    /// Whether parachute `i`'s trigger still watches for its condition.
    fn chute_armed(&self, i: usize) -> bool {
        self.chutes[i] == Chute::Armed
    }

    /// Whether parachute `i` fires on a noisy barometer (judged at its samples by
    /// [`Run::noisy_trigger`], not located as an event).
    #[inline]
    fn reads_noise(&self, i: usize) -> bool {
        self.noise.get(i).is_some_and(Option::is_some)
    }

    /// Whether a noisy barometer's sample can fire now (after apogee, with noise).
    #[inline(always)]
    fn hears_noise(&self) -> bool {
        self.apogee_done && !self.noise.is_empty()
    }

    /// The sample in `(t0, t_end]` at which a noisy barometer fires a parachute
    /// ([`Run::noisy_trigger`]) if it comes before `found`, the step's other event: its time
    /// and the parachute. In line, so that a flight without a noisy barometer, or before
    /// apogee, pays one comparison a step end.
    #[inline(always)]
    fn noisy_before(
        &mut self,
        found: Option<(f64, EventKind)>,
        t0: f64,
        t_end: f64,
        z_end: f64,
        height_at: impl FnMut(f64) -> f64,
    ) -> Option<(f64, usize)> {
        if !self.hears_noise() {
            return None;
        }
        self.noisy_trigger(t0, t_end, z_end, height_at)
            .filter(|&(tk, _)| found.is_none_or(|(te, _)| tk < te))
    }

    /// The first sample in `(t0, t1]` at which an armed parachute's noisy barometer says the
    /// rocket is below its trigger height (see [`crate::sensor`]), and which parachute (past
    /// apogee: [`Run::noisy_before`] calls it). `z1` is the center's height at `t1` (the lowest of the interval: the rocket
    /// descends) and `height_at(t)` the center's height at a time of the interval. Draws each
    /// parachute's noise up to the samples it reads. (Where two noisy parachutes could fire in
    /// one step, the one scanned first may have read samples past the other's firing sample:
    /// those draws are kept, read once, on the trajectory as it was before the other fired,
    /// which a firing does not change until its canopy opens a lag later.)
    fn noisy_trigger(
        &mut self,
        t0: f64,
        t1: f64,
        z1: f64,
        mut height_at: impl FnMut(f64) -> f64,
    ) -> Option<(f64, usize)> {
        let model = self.model;
        let elevation = model.env.elevation_m;
        let p1 = model.air.pressure_msl_pa(z1 + elevation);
        let mut found: Option<(f64, usize)> = None;
        for i in 0..self.noise.len() {
            if self.chutes[i] != Chute::Armed {
                continue;
            }
            let Some(Barometer {
                noise: process,
                trigger_pa: p_trigger,
                rate_hz: rate,
            }) = self.noise[i].as_mut()
            else {
                continue;
            };
            let (p_trigger, rate) = (*p_trigger, *rate);
            if p1 + process.ceiling_pa() <= p_trigger {
                continue;
            }
            // The samples k / rate in (t0, t_last], none of them drawn before.
            let t_last = found.map_or(t1, |(t, _)| t);
            let mut k = ((t0 * rate).floor() as i64).max(process.last_sample() + 1);
            while (k as f64) / rate <= t0 {
                k += 1;
            }
            loop {
                let tk = k as f64 / rate;
                if tk > t_last {
                    break;
                }
                let p = model.air.pressure_msl_pa(height_at(tk) + elevation);
                if p + process.at(k) > p_trigger {
                    if found.is_none_or(|(t, _)| tk < t) {
                        found = Some((tk, i));
                    }
                    break;
                }
                k += 1;
            }
        }
        found
    }

    /// Parachute `i`'s noisy barometer read below its height at its sample `t`: it fires
    /// there (the canopy opens `lag_s` after, a stop time).
    fn fire_at_sample(&mut self, i: usize, t: f64, altitude_m: f64, speed_m_s: f64) {
        self.chutes[i] = Chute::Fired { fires_s: t };
        self.push_event(EventKind::ParachuteTrigger(i), t, altitude_m, speed_m_s);
        self.stops.push(t + self.model.parachutes[i].lag_s);
    }

    /// The open canopies: their CdS and the air they carry, summed.
    fn canopies(&self) -> Canopies<f64> {
        let mut sum = Canopies {
            cds_m2: 0.0,
            added_air_m3: 0.0,
        };
        for (c, _) in self
            .model
            .canopies
            .iter()
            .zip(&self.chutes)
            .filter(|(_, &c)| c == Chute::Open)
        {
            sum.cds_m2 += c.cds_m2;
            sum.added_air_m3 += c.added_air_m3;
        }
        sum
    }

    /// Take in a sample: the metrics' extremes and margins, the observer, the kept samples.
    /// Returns the speed `|vel|`, m/s (computed here once for the caller too).
    #[allow(clippy::too_many_arguments)]
    fn record(
        &mut self,
        phase: Phase,
        t: f64,
        pos: Vector3<f64>,
        vel: Vector3<f64>,
        q: [f64; 4],
        w: [f64; 3],
        aux: &FlightAux,
    ) -> f64 {
        let m = self.model;
        let mach = aux.air_speed_m_s / aux.speed_of_sound_m_s;
        let speed = vel.norm();
        let mt = &mut self.metrics;
        mt.max_speed_m_s = mt.max_speed_m_s.max(speed);
        if mach.is_finite() {
            mt.max_mach = mt.max_mach.max(mach);
        }
        if aux.accel_cm_m_s2.is_finite() {
            mt.max_accel_m_s2 = mt.max_accel_m_s2.max(aux.accel_cm_m_s2);
        }
        let dynamic_pressure_pa = 0.5 * aux.density_kg_m3 * aux.air_speed_m_s * aux.air_speed_m_s;
        if dynamic_pressure_pa.is_finite() {
            mt.max_dynamic_pressure_pa = mt.max_dynamic_pressure_pa.max(dynamic_pressure_pa);
        }
        // The margins count until apogee, outside the descent (the flight margin in free
        // flight only).
        let margins = phase != Phase::Descent && !self.apogee_done;
        let sampled = O::WANTS_SAMPLES || m.options.keep_samples;
        if !sampled && !margins {
            return speed;
        }
        let static_margin_cal = m.static_margin_of(aux.r_cm_z_m);
        let flight_margin_cal = if sampled || phase == Phase::Free {
            m.flight_margin_of(aux.r_cm_z_m, mach)
        } else {
            f64::NAN
        };
        if margins {
            let min = |a: Option<f64>, b: f64| Some(a.map_or(b, |a| a.min(b)));
            mt.static_margin_min_cal = min(mt.static_margin_min_cal, static_margin_cal);
            if phase == Phase::Free {
                mt.flight_margin_min_cal = min(mt.flight_margin_min_cal, flight_margin_cal);
                // Watched as OpenRocket watches its aerodynamic warnings: from 0.25 s after
                // rail exit, while the climb is at least 20 % of its fastest. Outside that,
                // a slow rocket's angle of attack is large without meaning a tumble (leaving
                // the rail in a crosswind, arcing over near apogee).
                self.max_climb_m_s = self.max_climb_m_s.max(vel.z);
                let watched = mt
                    .rail_exit_time_s
                    .is_some_and(|te| t >= te + ALPHA_WATCH_AFTER_RAIL_S)
                    && vel.z >= ALPHA_WATCH_CLIMB_FRACTION * self.max_climb_m_s;
                if watched {
                    let angle = aux.alpha_arguments();
                    let finite = angle.0.is_finite() && angle.1.is_finite();
                    if finite && self.steepest.is_none_or(|s| steeper(angle, s)) {
                        self.steepest = Some(angle);
                    }
                }
            }
        }
        if !sampled {
            return speed;
        }
        let s = Sample {
            t_s: t,
            phase,
            position_m: [pos.x, pos.y, pos.z],
            velocity_m_s: [vel.x, vel.y, vel.z],
            quaternion: q,
            omega_rad_s: w,
            altitude_m: pos.z,
            speed_m_s: speed,
            mach,
            dynamic_pressure_pa,
            alpha_deg: aux.alpha_rad().to_degrees(),
            accel_m_s2: aux.accel_cm_m_s2,
            thrust_n: m.motor.eval(t).thrust_n,
            mass_kg: aux.mass_kg,
            cg_m: -aux.r_cm_z_m,
            static_margin_cal,
            flight_margin_cal,
        };
        self.observer.on_sample(&s);
        if m.options.keep_samples {
            self.samples.push(s);
        }
        speed
    }
}

/// Center-of-mass position and velocity of a 6-DOF state at `t`.
fn cm_of(
    model: &FlightModel,
    starts: &ShiftStarts,
    t: f64,
    y: &[f64; N6],
) -> (Vector3<f64>, Vector3<f64>) {
    let ms = model.instant(starts, t).mass;
    let r = frames::body_to_inertial(&[y[6], y[7], y[8], y[9]]);
    (
        eom::center_of_mass_position(y, &ms, &r),
        eom::center_of_mass_velocity(y, &ms, &r),
    )
}

/// The error of a flight that went non-finite at `t`, in or from the state `y`.
fn non_finite<const N: usize>(t: f64, y: &[f64; N]) -> SimError {
    SimError::NonFinite {
        time_s: t,
        state: format!("{y:?}"),
    }
}

/// An integrator's error at `t` on the state `y`: a non-finite state or derivative is a
/// [`SimError::NonFinite`], anything else an integration failure of the phase `what`.
fn integ_at<const N: usize>(t: f64, y: &[f64; N], e: IntegratorError, what: &str) -> SimError {
    match e {
        IntegratorError::NonFinite { .. } => non_finite(t, y),
        e => integ(t, e, what),
    }
}

fn integ(t: f64, e: IntegratorError, what: &str) -> SimError {
    SimError::Integration {
        time_s: t,
        phase: what.to_string(),
        source: e,
    }
}

/// Fly the model from the pad.
pub fn run<O: Observer>(model: &FlightModel, observer: &mut O) -> Result<Flight, SimError> {
    fly(model, observer, None)
}

/// Fly the model in free flight from the 6-DOF state `y0` at `t0` (no pad, no rail): for
/// experiments and checks against exact answers.
pub fn run_from<O: Observer>(
    model: &FlightModel,
    observer: &mut O,
    t0: f64,
    y0: &[f64; N6],
) -> Result<Flight, SimError> {
    fly(model, observer, Some((t0, *y0)))
}

fn fly<O: Observer>(
    model: &FlightModel,
    observer: &mut O,
    from: Option<(f64, [f64; N6])>,
) -> Result<Flight, SimError> {
    match fly_to_free(model, observer, from)? {
        Progress::Done(flight) => Ok(flight),
        Progress::Free(mut paused) => loop {
            if let Some(end) = paused.step()? {
                return paused.finish(end);
            }
        },
    }
}

/// The pad: the rocket waits until thrust beats its weight along the rail. Returns the
/// liftoff time and the state there.
fn pad<O: Observer>(run: &mut Run<'_, O>) -> Result<(f64, [f64; N6]), SimError> {
    let model = run.model;
    // The pad: the rocket waits until thrust beats its weight along the rail.
    let g0 = model.env.gravity.at(0.0);
    let sin_inc = model.rail.direction_n.z;
    let excess = |t: f64| {
        let i = model.instant(&run.starts, t);
        i.motor.thrust_n - i.mass.mass_kg * g0 * sin_inc
    };
    // The curve's knots (interior ones only in `thrust_knots_s`) and its last sample, the
    // burnout: a curve that ends above zero (it burns out there) is judged at its last
    // sample by the instant just before it, where it still pushes.
    let mut knots: Vec<f64> = vec![0.0];
    knots.extend(
        model
            .thrust_knots_s
            .iter()
            .copied()
            .filter(|&k| k > 0.0 && k < model.burnout_s),
    );
    if model.burnout_s > 0.0 {
        knots.push(model.burnout_s);
    }
    let before_burnout = |k: f64| {
        if k == model.burnout_s {
            k.next_down()
        } else {
            k
        }
    };
    let mut t_lift = None;
    for w in knots.windows(2) {
        let end = before_burnout(w[1]);
        if excess(end) > 0.0 {
            t_lift = Some(if excess(w[0]) > 0.0 {
                w[0]
            } else {
                brent_root(excess, w[0], end, EVENT_TOL_S).map_err(SimError::Liftoff)?
            });
            break;
        }
    }
    let t_lift = t_lift.ok_or(SimError::NeverLeavesPad {
        max_thrust_n: knots
            .iter()
            .map(|&k| model.motor.eval(before_burnout(k)).thrust_n)
            .fold(0.0, f64::max),
        weight_n: model.instant(&run.starts, 0.0).mass.mass_kg * g0 * sin_inc,
    })?;
    let mut y = [0.0; N6];
    y[0..3].copy_from_slice(model.rail.o_start_n.as_slice());
    y[6..10].copy_from_slice(&model.rail.attitude);
    {
        let (pos, _) = cm_of(model, &run.starts, t_lift, &y);
        run.push_event(EventKind::Liftoff, t_lift, pos.z, 0.0);
        run.metrics.liftoff_time_s = Some(t_lift);
        run.metrics.static_margin_liftoff_cal =
            Some(model.static_margin(&model.instant(&run.starts, t_lift).mass));
    }

    Ok((t_lift, y))
}

fn land<O: Observer>(run: &mut Run<'_, O>, t: f64, pos: Vector3<f64>, vel: Vector3<f64>) {
    run.push_event(EventKind::Landing, t, pos.z, vel.norm());
    run.metrics.landing_time_s = Some(t);
    run.metrics.landing_position_m = Some([pos.x, pos.y]);
    run.metrics.landing_speed_m_s = Some(vel.norm());
}
