//! The single-flight driver: pad, rail, free flight, descent, landing. It steps the chosen
//! integrator one step at a time, never across a stop time (thrust-curve knots, burnout,
//! timed triggers, canopy openings, the 16 parts of every shift), locates events by
//! root-finding on the dense output, and records samples and metrics.

use super::config::Integrator;
use super::model::{FlightAux, FlightModel, ShiftStarts, MAX_SHIFTS};
use super::output::{Flight, Metrics, Observer, Phase, Sample};
use super::SimError;
use crate::eom::{self, N3, N6};
use crate::events::{Event, EventKind};
use crate::frames;
use crate::integrate::{
    brent_root, brent_root_bracketed, locate_event, Crossing, DenseStepper, Dopri54,
    IntegratorError, Rk4, Tolerances,
};
use crate::shifts::STOPS_PER_SHIFT;
use crate::trigger::Trigger;
use nalgebra::Vector3;

/// Time tolerance of every event, s.
const EVENT_TOL_S: f64 = 1e-12;

/// Either integrator, by value (no trait object).
enum Stepper<const N: usize> {
    Adaptive(Box<Dopri54<N>>),
    Fixed(Box<Rk4<N>>),
}

macro_rules! each {
    ($s:expr, $x:ident => $e:expr) => {
        match $s {
            Stepper::Adaptive($x) => $e,
            Stepper::Fixed($x) => $e,
        }
    };
}

impl<const N: usize> Stepper<N> {
    fn new(integrator: &Integrator, atol: [f64; N], rtol: f64) -> Result<Self, IntegratorError> {
        Ok(match *integrator {
            Integrator::Adaptive { .. } => Stepper::Adaptive(Box::new(Dopri54::with_tolerances(
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

/// The flight in progress.
struct Run<'a, O: Observer> {
    model: &'a FlightModel,
    observer: &'a mut O,
    starts: ShiftStarts,
    /// Pending stop times, unsorted; the next one is their minimum above the current time.
    stops: Vec<f64>,
    samples: Vec<Sample>,
    events: Vec<Event>,
    metrics: Metrics,
    evaluations: u64,
    steps: u64,
    apogee_done: bool,
    /// Per parachute: trigger time once it has fired.
    chute_triggered: Vec<Option<f64>>,
    chute_open: Vec<bool>,
    /// Per trigger owner: whether a height-on-the-way-down trigger has fired (chutes, then shifts).
    rail_exit_done: bool,
    burnout_done: bool,
}

/// What ended a phase.
enum PhaseEnd {
    RailExit,
    Deploy,
    Landed,
    TimeLimit,
}

impl<'a, O: Observer> Run<'a, O> {
    fn next_stop(&self, t: f64) -> f64 {
        let mut next = self.model.options.max_time_s;
        for &s in &self.stops {
            if s > t && s < next {
                next = s;
            }
        }
        next
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
        self.starts[k] = t;
        let d = self.model.shifts[k].duration_s;
        for i in 1..=STOPS_PER_SHIFT {
            self.stops.push(t + d * i as f64 / STOPS_PER_SHIFT as f64);
        }
        self.push_event(EventKind::Shift(k), t, altitude_m, speed_m_s);
        Ok(())
    }

    fn trigger_chute(&mut self, i: usize, t: f64, altitude_m: f64, speed_m_s: f64) {
        self.chute_triggered[i] = Some(t);
        self.push_event(EventKind::ParachuteTrigger(i), t, altitude_m, speed_m_s);
        self.stops.push(t + self.model.parachutes[i].lag_s);
    }

    /// Fire every trigger of kind `matches` that has not fired yet, at `t`.
    fn fire(
        &mut self,
        t: f64,
        altitude_m: f64,
        speed_m_s: f64,
        matches: impl Fn(&Trigger) -> bool,
    ) -> Result<(), SimError> {
        for i in 0..self.model.parachutes.len() {
            if self.chute_triggered[i].is_none() && matches(&self.model.parachutes[i].trigger) {
                self.trigger_chute(i, t, altitude_m, speed_m_s);
            }
        }
        for k in 0..self.model.shifts.len() {
            if self.starts[k].is_infinite() && matches(&self.model.shifts[k].trigger) {
                self.start_shift(k, t, altitude_m, speed_m_s)?;
            }
        }
        Ok(())
    }

    /// Handle what happens exactly at a stop time `t`: burnout, timed triggers, canopies.
    /// Returns true when a canopy opened (the phase must end).
    fn at_stop(&mut self, t: f64, altitude_m: f64, speed_m_s: f64) -> Result<bool, SimError> {
        let m = self.model;
        if !self.burnout_done && t >= m.burnout_s {
            self.burnout_done = true;
            self.metrics.burnout_time_s = Some(m.burnout_s);
            self.metrics.static_margin_burnout_cal =
                Some(m.static_margin(&m.instant(&self.starts, m.burnout_s).mass));
            self.push_event(EventKind::Burnout, m.burnout_s, altitude_m, speed_m_s);
        }
        let (burnout, delay) = (m.burnout_s, m.motor_delay_s);
        self.fire(t, altitude_m, speed_m_s, |tr| {
            tr.fixed_time(burnout, delay).is_some_and(|ft| ft <= t)
        })?;
        let mut opened = false;
        for i in 0..m.parachutes.len() {
            if let Some(tt) = self.chute_triggered[i] {
                if !self.chute_open[i] && tt + m.parachutes[i].lag_s <= t {
                    self.chute_open[i] = true;
                    self.push_event(EventKind::ParachuteDeploy(i), t, altitude_m, speed_m_s);
                    opened = true;
                }
            }
        }
        Ok(opened)
    }

    fn cds(&self) -> f64 {
        self.model
            .parachutes
            .iter()
            .zip(&self.chute_open)
            .filter(|(_, &o)| o)
            .map(|(p, _)| p.cds_m2)
            .sum()
    }

    fn record(
        &mut self,
        phase: Phase,
        t: f64,
        pos: Vector3<f64>,
        vel: Vector3<f64>,
        q: [f64; 4],
        w: [f64; 3],
        aux: &FlightAux,
        thrust_n: f64,
    ) {
        let m = self.model;
        let mach = aux.air_speed_m_s / aux.speed_of_sound_m_s;
        let speed = vel.norm();
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
            alpha_deg: aux.alpha_rad.to_degrees(),
            accel_m_s2: aux.accel_cm_m_s2,
            thrust_n,
            mass_kg: aux.mass.mass_kg,
            cg_m: -aux.mass.r_cm.z,
            static_margin_cal: m.static_margin(&aux.mass),
            flight_margin_cal: m.flight_margin(&aux.mass, mach),
        };
        let mt = &mut self.metrics;
        mt.max_speed_m_s = mt.max_speed_m_s.max(speed);
        if mach.is_finite() {
            mt.max_mach = mt.max_mach.max(mach);
        }
        if aux.accel_cm_m_s2.is_finite() {
            mt.max_accel_m_s2 = mt.max_accel_m_s2.max(aux.accel_cm_m_s2);
        }
        if phase != Phase::Descent && !self.apogee_done {
            let min = |a: Option<f64>, b: f64| Some(a.map_or(b, |a| a.min(b)));
            mt.static_margin_min_cal = min(mt.static_margin_min_cal, s.static_margin_cal);
            if phase == Phase::Free {
                mt.flight_margin_min_cal = min(mt.flight_margin_min_cal, s.flight_margin_cal);
            }
        }
        self.observer.on_sample(&s);
        if m.options.keep_samples {
            self.samples.push(s);
        }
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
    let n_chutes = model.parachutes.len();
    let mut stops = Vec::with_capacity(64 + STOPS_PER_SHIFT * model.shifts.len() + 2 * n_chutes);
    stops.extend(model.thrust_knots_s.iter().copied());
    stops.push(model.burnout_s);
    for tr in model
        .parachutes
        .iter()
        .map(|p| p.trigger)
        .chain(model.shifts.iter().map(|s| s.trigger))
    {
        if let Some(t) = tr.fixed_time(model.burnout_s, model.motor_delay_s) {
            stops.push(t);
        }
    }
    let mut run = Run {
        model,
        observer,
        starts: [f64::INFINITY; MAX_SHIFTS],
        stops,
        samples: Vec::with_capacity(if model.options.keep_samples { 2048 } else { 0 }),
        events: Vec::with_capacity(16),
        metrics: Metrics::default(),
        evaluations: 0,
        steps: 0,
        apogee_done: false,
        chute_triggered: vec![None; n_chutes],
        chute_open: vec![false; n_chutes],
        rail_exit_done: false,
        burnout_done: false,
    };

    let (rtol, atol6, atol3) = tolerances(&model.options.integrator);
    let (mut t, mut y, mut phase) = match from {
        Some((t0, y0)) => {
            run.rail_exit_done = true;
            run.burnout_done = t0 >= model.burnout_s;
            // Started on the way down (or at the top), the apogee is behind it: the landing
            // and the height triggers are armed at once.
            run.apogee_done = cm_of(model, &run.starts, t0, &y0).1.z <= 0.0;
            run.stops.retain(|&s| s > t0);
            (t0, y0, Phase::Free)
        }
        None => {
            let (t, y) = pad(&mut run)?;
            (t, y, Phase::Rail)
        }
    };
    let mut s6: Stepper<N6> =
        Stepper::new(&model.options.integrator, atol6, rtol).map_err(|e| integ(t, e, "setup"))?;
    // Rail, then free flight, in the same 13 states.
    let end = loop {
        let res = six_dof_phase(&mut run, &mut s6, phase, t, &y)?;
        t = res.0;
        y = res.1;
        match res.2 {
            PhaseEnd::RailExit => {
                phase = Phase::Free;
                continue;
            }
            other => break other,
        }
    };
    if let PhaseEnd::Deploy = end {
        // Descent: the center of mass as a point, with its velocity (including r′) kept.
        let (pos, vel) = cm_of(model, &run.starts, t, &y);
        let y3 = [pos.x, pos.y, pos.z, vel.x, vel.y, vel.z];
        let mut s3: Stepper<N3> = Stepper::new(&model.options.integrator, atol3, rtol)
            .map_err(|e| integ(t, e, "setup"))?;
        descent_phase(&mut run, &mut s3, t, &y3)?;
    }
    Ok(Flight {
        samples: run.samples,
        events: run.events,
        metrics: run.metrics,
        shift_starts_s: run.starts[..model.shifts.len()]
            .iter()
            .map(|&s| s.is_finite().then_some(s))
            .collect(),
        derivative_evaluations: run.evaluations,
        steps: run.steps,
    })
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
    let mut knots: Vec<f64> = vec![0.0];
    knots.extend(
        model
            .thrust_knots_s
            .iter()
            .copied()
            .filter(|&k| k > 0.0 && k <= model.burnout_s),
    );
    let mut t_lift = None;
    for w in knots.windows(2) {
        if excess(w[1]) > 0.0 {
            t_lift = Some(if excess(w[0]) > 0.0 {
                w[0]
            } else {
                brent_root(excess, w[0], w[1], EVENT_TOL_S)
                    .map_err(|e| SimError::Setup(format!("liftoff: {e}")))?
            });
            break;
        }
    }
    let t_lift = t_lift.ok_or(SimError::NeverLeavesPad {
        max_thrust_n: model
            .thrust_knots_s
            .iter()
            .map(|&k| model.motor.eval(k).thrust_n)
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

/// An event function of the rail and free-flight phases.
#[derive(Debug, Clone, Copy)]
enum G {
    /// O's travel along the rail minus the travel to the exit.
    RailTravel,
    /// The center of mass's vertical speed.
    VerticalSpeed,
    /// The center of mass's height minus this, m.
    Height(f64),
}

/// What the driver knows at the end of a step: the center's position and velocity and the
/// figures a sample needs, from one mass-state evaluation.
#[derive(Debug, Clone, Copy)]
struct EndPoint {
    pos: Vector3<f64>,
    vel: Vector3<f64>,
    aux: FlightAux,
}

impl G {
    /// The function's value from an end point (no further evaluation).
    #[inline]
    fn at_end(self, model: &FlightModel, y: &[f64; N6], ep: &EndPoint) -> f64 {
        match self {
            G::RailTravel => {
                (Vector3::new(y[0], y[1], y[2]) - model.rail.o_start_n).dot(&model.rail.direction_n)
                    - model.rail.travel_to_exit_m
            }
            G::VerticalSpeed => ep.vel.z,
            G::Height(h) => ep.pos.z - h,
        }
    }

    /// The function's value at any `(t, y)` (for root-finding on the dense output).
    #[inline]
    fn at(self, model: &FlightModel, starts: &ShiftStarts, t: f64, y: &[f64; N6]) -> f64 {
        match self {
            G::RailTravel => {
                (Vector3::new(y[0], y[1], y[2]) - model.rail.o_start_n).dot(&model.rail.direction_n)
                    - model.rail.travel_to_exit_m
            }
            G::VerticalSpeed => cm_of(model, starts, t, y).1.z,
            G::Height(h) => cm_of(model, starts, t, y).0.z - h,
        }
    }
}

/// Rail or free flight until the rail exit (rail), a canopy opens, landing or the time limit.
fn six_dof_phase<O: Observer>(
    run: &mut Run<'_, O>,
    stepper: &mut Stepper<N6>,
    phase: Phase,
    t0: f64,
    y0: &[f64; N6],
) -> Result<(f64, [f64; N6], PhaseEnd), SimError> {
    let model = run.model;
    let rail = phase == Phase::Rail;
    let deriv = |starts: &ShiftStarts, t: f64, y: &[f64; N6], dy: &mut [f64; N6]| -> FlightAux {
        if rail {
            model.derivative_rail(starts, t, y, dy)
        } else {
            model.derivative_6dof(starts, t, y, dy)
        }
    };
    // The end point of `(t, y)` whose derivative `dy` is known.
    let end_point = |starts: &ShiftStarts, t: f64, y: &[f64; N6], dy: &[f64; N6]| -> EndPoint {
        let (pos, vel, aux) = model.end_point(starts, t, y, dy, rail);
        EndPoint { pos, vel, aux }
    };
    let name = phase.name();
    let mut events: Vec<(EventKind, G)> =
        Vec::with_capacity(2 + model.parachutes.len() + model.shifts.len());
    let (mut prev_y, mut prev) = {
        let starts = run.starts;
        let mut evals = 0u64;
        each!(stepper, s => s.init(|t, y, dy| { evals += 1; deriv(&starts, t, y, dy); }, t0, y0))
            .map_err(|e| integ_at(t0, y0, e, name))?;
        run.evaluations += evals;
        let ep = end_point(&starts, t0, y0, each!(stepper, s => s.dy()));
        run.record(
            phase,
            t0,
            ep.pos,
            ep.vel,
            [y0[6], y0[7], y0[8], y0[9]],
            [y0[10], y0[11], y0[12]],
            &ep.aux,
            model.motor.eval(t0).thrust_n,
        );
        (*y0, ep)
    };
    loop {
        let t_now = each!(stepper, s => s.t());
        let t_stop = run.next_stop(t_now);
        let starts = run.starts;
        let mut evals = 0u64;
        // The first evaluation whose derivative was not finite (a NaN makes the adaptive
        // stepper reject until its step underflows; RK4 would carry it into the state).
        let mut bad: Option<(f64, [f64; N6])> = None;
        let outcome = each!(stepper, s => s.step(|t, y, dy| {
            evals += 1;
            deriv(&starts, t, y, dy);
            if bad.is_none() && !dy.iter().all(|v| v.is_finite()) {
                bad = Some((t, *y));
            }
        }, t_stop))
        .map_err(|e| match bad {
            Some((tb, yb)) => non_finite(tb, &yb),
            None => integ_at(t_now, each!(stepper, s => s.y()), e, name),
        })?;
        if !each!(stepper, s => s.y()).iter().all(|v| v.is_finite()) {
            let (tb, yb) = bad.unwrap_or((each!(stepper, s => s.t()), *each!(stepper, s => s.y())));
            return Err(non_finite(tb, &yb));
        }
        run.evaluations += evals;
        run.steps += 1;
        let (t1, y1) = (each!(stepper, s => s.t()), *each!(stepper, s => s.y()));
        let ep1 = end_point(&starts, t1, &y1, each!(stepper, s => s.dy()));
        // The event functions that can fire now.
        events.clear();
        if rail {
            events.push((EventKind::RailExit, G::RailTravel));
        } else if !run.apogee_done {
            events.push((EventKind::Apogee, G::VerticalSpeed));
        } else {
            events.push((EventKind::Landing, G::Height(0.0)));
            for (i, p) in model.parachutes.iter().enumerate() {
                if let (Trigger::HeightDescending { height_m }, None) =
                    (p.trigger, run.chute_triggered[i])
                {
                    events.push((EventKind::ParachuteTrigger(i), G::Height(height_m)));
                }
            }
            for (k, sh) in model.shifts.iter().enumerate() {
                if let (Trigger::HeightDescending { height_m }, true) =
                    (sh.trigger, starts[k].is_infinite())
                {
                    events.push((EventKind::Shift(k), G::Height(height_m)));
                }
            }
        }
        // Earliest crossing in the step: rail travel rises through zero, the rest fall.
        let mut found: Option<(f64, EventKind)> = None;
        for &(kind, g) in &events {
            let (g0, g1) = (g.at_end(model, &prev_y, &prev), g.at_end(model, &y1, &ep1));
            let crossing = if rail {
                Crossing::Rising
            } else {
                Crossing::Falling
            };
            if t1 > t_now && crossing.matches(g0, g1) {
                let te = each!(stepper, s => brent_root_bracketed(|t| g.at(model, &starts, t, &s.dense(t)), t_now, g0, t1, g1, EVENT_TOL_S))
                    .map_err(|e| SimError::Setup(format!("event location failed: {e}")))?;
                if found.is_none_or(|(tf, _)| te < tf) {
                    found = Some((te, kind));
                }
            }
        }
        let (t_end, y_end, ep) = match found {
            Some((te, _)) => {
                let ye = each!(stepper, s => s.dense(te));
                let mut dy = [0.0; N6];
                deriv(&run.starts, te, &ye, &mut dy);
                (te, ye, end_point(&run.starts, te, &ye, &dy))
            }
            None => (t1, y1, ep1),
        };
        run.record(
            phase,
            t_end,
            ep.pos,
            ep.vel,
            [y_end[6], y_end[7], y_end[8], y_end[9]],
            [y_end[10], y_end[11], y_end[12]],
            &ep.aux,
            model.motor.eval(t_end).thrust_n,
        );
        let (pos, vel) = (ep.pos, ep.vel);
        let (alt, speed) = (pos.z, vel.norm());
        prev_y = y_end;
        prev = ep;
        if let Some((te, kind)) = found {
            match kind {
                EventKind::RailExit => {
                    run.rail_exit_done = true;
                    run.push_event(EventKind::RailExit, te, alt, speed);
                    run.metrics.rail_exit_time_s = Some(te);
                    run.metrics.rail_exit_speed_m_s = Some(speed);
                    run.metrics.static_margin_rail_exit_cal =
                        Some(model.static_margin(&ep.aux.mass));
                    return Ok((te, y_end, PhaseEnd::RailExit));
                }
                EventKind::Apogee => {
                    run.apogee_done = true;
                    run.metrics.apogee_m = Some(alt);
                    run.metrics.apogee_time_s = Some(te);
                    run.push_event(EventKind::Apogee, te, alt, speed);
                    run.fire(te, alt, speed, |tr| matches!(tr, Trigger::Apogee))?;
                }
                EventKind::Landing => {
                    land(run, te, pos, vel);
                    return Ok((te, y_end, PhaseEnd::Landed));
                }
                EventKind::ParachuteTrigger(i) => run.trigger_chute(i, te, alt, speed),
                EventKind::Shift(k) => run.start_shift(k, te, alt, speed)?,
                _ => {}
            }
        }
        if (found.is_some() || matches!(outcome, crate::integrate::StepOutcome::ReachedStop))
            && run.at_stop(t_end, alt, speed)?
        {
            return Ok((t_end, y_end, PhaseEnd::Deploy));
        }
        if t_end >= model.options.max_time_s {
            run.push_event(EventKind::TimeLimit, t_end, alt, speed);
            return Ok((t_end, y_end, PhaseEnd::TimeLimit));
        }
        if found.is_some() {
            let starts = run.starts;
            let mut evals = 0u64;
            each!(stepper, s => s.restart(|t, y, dy| { evals += 1; deriv(&starts, t, y, dy); }, t_end, &y_end)).map_err(|e| integ_at(t_end, &y_end, e, name))?;
            run.evaluations += evals;
        }
    }
}

fn land<O: Observer>(run: &mut Run<'_, O>, t: f64, pos: Vector3<f64>, vel: Vector3<f64>) {
    run.push_event(EventKind::Landing, t, pos.z, vel.norm());
    run.metrics.landing_time_s = Some(t);
    run.metrics.landing_position_m = Some([pos.x, pos.y]);
    run.metrics.landing_speed_m_s = Some(vel.norm());
}

/// Under canopy until landing or the time limit.
fn descent_phase<O: Observer>(
    run: &mut Run<'_, O>,
    stepper: &mut Stepper<N3>,
    t0: f64,
    y0: &[f64; N3],
) -> Result<PhaseEnd, SimError> {
    let model = run.model;
    let name = Phase::Descent.name();
    let mut cds = run.cds();
    {
        let starts = run.starts;
        let mut evals = 0u64;
        each!(stepper, s => s.init(|t, y, dy| { evals += 1; model.derivative_descent(&starts, cds, t, y, dy); }, t0, y0)).map_err(|e| integ_at(t0, y0, e, name))?;
        run.evaluations += evals;
        let mut dy = [0.0; N3];
        let aux = model.derivative_descent(&starts, cds, t0, y0, &mut dy);
        run.record(
            Phase::Descent,
            t0,
            Vector3::new(y0[0], y0[1], y0[2]),
            Vector3::new(y0[3], y0[4], y0[5]),
            [f64::NAN; 4],
            [0.0; 3],
            &aux,
            model.motor.eval(t0).thrust_n,
        );
    }
    loop {
        let t_now = each!(stepper, s => s.t());
        let t_stop = run.next_stop(t_now);
        let starts = run.starts;
        let mut evals = 0u64;
        let mut bad: Option<(f64, [f64; N3])> = None;
        let outcome = each!(stepper, s => s.step(|t, y, dy| {
            evals += 1;
            model.derivative_descent(&starts, cds, t, y, dy);
            if bad.is_none() && !dy.iter().all(|v| v.is_finite()) {
                bad = Some((t, *y));
            }
        }, t_stop))
        .map_err(|e| match bad {
            Some((tb, yb)) => non_finite(tb, &yb),
            None => integ_at(t_now, each!(stepper, s => s.y()), e, name),
        })?;
        if !each!(stepper, s => s.y()).iter().all(|v| v.is_finite()) {
            let (tb, yb) = bad.unwrap_or((each!(stepper, s => s.t()), *each!(stepper, s => s.y())));
            return Err(non_finite(tb, &yb));
        }
        run.evaluations += evals;
        run.steps += 1;
        let mut found: Option<(f64, EventKind)> = None;
        let mut consider = |t: Option<f64>, k: EventKind| {
            if let Some(t) = t {
                if found.is_none_or(|(tf, _)| t < tf) {
                    found = Some((t, k));
                }
            }
        };
        let root_err = |e| SimError::Setup(format!("event location failed: {e}"));
        each!(stepper, s => {
            if !run.apogee_done {
                consider(locate_event(&**s, |_t, y: &[f64; N3]| y[5], Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::Apogee);
            }
            consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2], Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::Landing);
            if run.apogee_done {
                for (i, p) in model.parachutes.iter().enumerate() {
                    if let (Trigger::HeightDescending { height_m }, None) = (p.trigger, run.chute_triggered[i]) {
                        consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2] - height_m, Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::ParachuteTrigger(i));
                    }
                }
                for (k, sh) in model.shifts.iter().enumerate() {
                    if let (Trigger::HeightDescending { height_m }, true) = (sh.trigger, starts[k].is_infinite()) {
                        consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2] - height_m, Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::Shift(k));
                    }
                }
            }
        });
        let (t_end, y_end) = match found {
            Some((te, _)) => (te, each!(stepper, s => s.dense(te))),
            None => (each!(stepper, s => s.t()), *each!(stepper, s => s.y())),
        };
        let mut dy = [0.0; N3];
        let aux = model.derivative_descent(&run.starts, cds, t_end, &y_end, &mut dy);
        let pos = Vector3::new(y_end[0], y_end[1], y_end[2]);
        let vel = Vector3::new(y_end[3], y_end[4], y_end[5]);
        run.record(
            Phase::Descent,
            t_end,
            pos,
            vel,
            [f64::NAN; 4],
            [0.0; 3],
            &aux,
            model.motor.eval(t_end).thrust_n,
        );
        let (alt, speed) = (pos.z, vel.norm());
        if let Some((te, kind)) = found {
            match kind {
                EventKind::Apogee => {
                    run.apogee_done = true;
                    run.metrics.apogee_m = Some(alt);
                    run.metrics.apogee_time_s = Some(te);
                    run.push_event(EventKind::Apogee, te, alt, speed);
                    run.fire(te, alt, speed, |tr| matches!(tr, Trigger::Apogee))?;
                }
                EventKind::Landing => {
                    land(run, te, pos, vel);
                    return Ok(PhaseEnd::Landed);
                }
                EventKind::ParachuteTrigger(i) => run.trigger_chute(i, te, alt, speed),
                EventKind::Shift(k) => run.start_shift(k, te, alt, speed)?,
                _ => {}
            }
        }
        if found.is_some() || matches!(outcome, crate::integrate::StepOutcome::ReachedStop) {
            run.at_stop(t_end, alt, speed)?;
        }
        if t_end >= model.options.max_time_s {
            run.push_event(EventKind::TimeLimit, t_end, alt, speed);
            return Ok(PhaseEnd::TimeLimit);
        }
        let new_cds = run.cds();
        if found.is_some()
            || new_cds != cds
            || matches!(outcome, crate::integrate::StepOutcome::ReachedStop)
        {
            cds = new_cds;
            let starts = run.starts;
            let mut evals = 0u64;
            each!(stepper, s => s.restart(|t, y, dy| { evals += 1; model.derivative_descent(&starts, cds, t, y, dy); }, t_end, &y_end)).map_err(|e| integ_at(t_end, &y_end, e, name))?;
            run.evaluations += evals;
        }
    }
}
