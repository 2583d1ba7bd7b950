//! The descents: the rocket under canopy (the center of mass as a point with the canopies'
//! drag) and, once the rocket's flight is over, each released part's own flight to the
//! ground (a point of the part's mass under its own drag or parachute), one step at a time.
//! Both drivers step them with this code: the single flight, and each lane of the batch
//! engine's descent groups, which calls [`Descent::step`] lane by lane (bit for bit the
//! single flight, since it is the single flight's step).
//!
//! # The method: RODAS4, a Rosenbrock method
//!
//! Under a canopy the velocity relaxes to the wind-relative terminal velocity at the rate
//! of the drag's Jacobian: `λ = 2g/v_t / (1 + m_a/m)` along the relative velocity and half
//! that across it (about 3/s under a main, 0.5 to 1/s under a drogue). An explicit method's
//! step cannot pass `|hλ| ≈ 3.3` (Dormand–Prince's stability limit on the real axis) however
//! smooth the descent, and that is where its steps used to settle: a third of a flight's
//! steps. The trajectory itself is smooth: once the canopy has opened, the velocity follows
//! the terminal velocity of the air and wind at the height, which change over hundreds of
//! metres. So the descent is stepped by RODAS4 ([`crate::integrate::Rodas4`]): L-stable (the
//! relaxation is damped whatever `hλ`), order 4 (the opening's transient is followed at the
//! tolerances' accuracy in few steps), stiffly accurate, with an error estimate and a dense
//! output of order 3 on which the events are found by Brent's method to 1e-12 s as before.
//! Its Jacobian is cheap and mostly closed-form: `ẋ = v`, the acceleration's `∂v̇/∂v`
//! ([`crate::eom::descent_velocity_jacobian`]: the drag's and Coriolis's), and by differences
//! only `∂v̇/∂z` (the air, the wind and gravity change with height) and, with gusts or while
//! the motor still burns, `∂f/∂t`: one or two more evaluations a step.
//!
//! Not chosen: an exponential step (the relaxation's rate is a 3×3 matrix that changes with
//! the relative velocity, and the weight and the wind's shear are not linear in the state),
//! and a closed form between the wind table's rows (quadratic drag with a wind at an angle
//! to gravity has none in three dimensions, and the air's density changes within a row).
//! Fixed-step RK4, when the options ask for it, steps the descent too.

use super::*;
use crate::integrate::rodas4;

/// Whose descent it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Body {
    /// The rocket, under its open canopies, and the mass of the parts that have left it
    /// ([`FlightModel::removed_mass_kg`], kept here: it changes only at a release).
    Rocket { removed_kg: Option<f64> },
    /// Release `j`'s part: its own parachute where it stands (`None`: it has none), and
    /// whether it still climbs (its apogee ahead).
    Part {
        j: usize,
        chute: Option<Chute>,
        climbing: bool,
    },
}

impl Body {
    /// The mass that descends at `t`.
    #[inline(always)]
    fn mass(self, model: &FlightModel, t: f64) -> f64 {
        match self {
            Body::Rocket { removed_kg } => model.descent_mass_less(t, removed_kg),
            Body::Part { j, .. } => model.mass.released[j].mass_kg,
        }
    }
}

/// A descent between its steps: whose, the drag in force, and its mass once it no longer
/// changes (the motor out: `body.mass` at any later time, the same bits).
pub(super) struct Descent {
    canopies: Canopies<f64>,
    body: Body,
    mass_kg: Option<f64>,
}

/// What ends a part's step besides its stops.
#[derive(Debug, Clone, Copy, PartialEq)]
enum PartEvent {
    Landing,
    Apogee,
    ChuteHeight,
}

impl Descent {
    /// Start the rocket under canopy at `(t0, y0)`: the stepper's first derivative and the
    /// first sample.
    pub(super) fn start<O: Observer>(
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
        t0: f64,
        y0: &[f64; N3],
    ) -> Result<Descent, SimError> {
        let model = run.model;
        let name = Phase::Descent.name();
        let canopies = run.canopies();
        let starts = run.starts;
        let body = Body::Rocket {
            removed_kg: model.removed_mass_kg(&starts, t0),
        };
        let mut evals = 0u64;
        each!(stepper, s => s.init(|t, y, dy| { evals += 1; model.descent_rates_of(body.mass(model, t), &canopies, t, y, dy); }, t0, y0)).map_err(|e| integ_at(t0, y0, e, name))?;
        run.evaluations += evals;
        let mut dy = [0.0; N3];
        let aux = model.derivative_descent(&starts, &canopies, t0, y0, &mut dy);
        run.record(
            Phase::Descent,
            t0,
            Vector3::new(y0[0], y0[1], y0[2]),
            Vector3::new(y0[3], y0[4], y0[5]),
            [f64::NAN; 4],
            [0.0; 3],
            &aux,
        );
        let mut d = Descent {
            canopies,
            body,
            mass_kg: None,
        };
        d.settle_mass(model, t0);
        Ok(d)
    }

    /// The descent of the first released part after release `after` (from the first if
    /// `None`) that left the rocket, started where it left; `None` when none is left to fly.
    pub(super) fn next_part<O: Observer>(
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
        after: Option<usize>,
    ) -> Result<Option<Descent>, SimError> {
        let first = after.map_or(0, |j| j + 1);
        let Some(j) = (first..run.releases.len()).find(|&j| run.releases[j].part.is_some()) else {
            return Ok(None);
        };
        Descent::start_part(run, stepper, j).map(Some)
    }

    /// Start release `j`'s part where and when it left: its parachute armed, or fired at
    /// once if its trigger is the release or its condition already holds (on its way down,
    /// at or below its height), and open at once without a lag.
    fn start_part<O: Observer>(
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
        j: usize,
    ) -> Result<Descent, SimError> {
        let model = run.model;
        let name = Phase::Descent.name();
        let record = &run.releases[j];
        let (t0, part) = match (record.time_s, &record.part) {
            (Some(t), Some(p)) => (t, p),
            _ => return Err(SimError::ReleaseNeverLeft { index: j }),
        };
        let (p, v) = (part.start_position_m, part.start_velocity_m_s);
        let y0 = [p[0], p[1], p[2], v[0], v[1], v[2]];
        let climbing = y0[5] > 0.0;
        let chute = model.releases[j].parachute.map(|(c, _)| {
            let fires = match c.trigger {
                PartTrigger::Release => true,
                PartTrigger::Apogee => !climbing,
                PartTrigger::HeightDescending { height_m } => !climbing && y0[2] <= height_m,
            };
            match (fires, c.lag_s == 0.0) {
                (false, _) => Chute::Armed,
                (true, false) => Chute::Fired { fires_s: t0 },
                (true, true) => Chute::Open,
            }
        });
        let mut d = Descent {
            canopies: Canopies {
                cds_m2: 0.0,
                added_air_m3: 0.0,
            },
            body: Body::Part { j, chute, climbing },
            mass_kg: Some(model.mass.released[j].mass_kg),
        };
        d.canopies = d.part_canopies(model);
        if chute == Some(Chute::Open) {
            if let Some(f) = run.releases[j].part.as_mut() {
                f.chute_open_s = Some(t0);
            }
        }
        let (canopies, mass) = (d.canopies, model.mass.released[j].mass_kg);
        let mut evals = 0u64;
        each!(stepper, s => s.init(|t, y, dy| { evals += 1; model.descent_rates_of(mass, &canopies, t, y, dy); }, t0, &y0)).map_err(|e| integ_at(t0, &y0, e, name))?;
        run.evaluations += evals;
        d.record_part(run, t0, &y0);
        Ok(d)
    }

    /// A part's drag in force: its canopy open, or its own drag area.
    fn part_canopies(&self, model: &FlightModel) -> Canopies<f64> {
        let Body::Part { j, chute, .. } = self.body else {
            return self.canopies;
        };
        let spec = &model.releases[j];
        match (chute, spec.parachute) {
            (Some(Chute::Open), Some((c, added_air_m3))) => Canopies {
                cds_m2: c.cds_m2,
                added_air_m3,
            },
            _ => Canopies {
                cds_m2: spec.cda_m2,
                added_air_m3: 0.0,
            },
        }
    }

    /// The drag in force.
    #[inline(always)]
    pub(super) fn canopies(&self) -> Canopies<f64> {
        self.canopies
    }

    /// The mass that descends at `t`: the rocket's, without the parts that have left, or the
    /// part's own.
    #[inline(always)]
    pub(super) fn mass(&self, model: &FlightModel, t: f64) -> f64 {
        match self.mass_kg {
            Some(m) => m,
            None => self.changing_mass(model, t),
        }
    }

    /// [`Descent::mass`] while it changes (the motor still burning), out of line.
    #[inline(never)]
    fn changing_mass(&self, model: &FlightModel, t: f64) -> f64 {
        self.body.mass(model, t)
    }

    /// Keep the mass from `t` on if it no longer changes (the motor is out; a part's never
    /// does), or forget it.
    fn settle_mass(&mut self, model: &FlightModel, t: f64) {
        self.mass_kg = (t >= model.motor.burn_time_s()).then(|| self.body.mass(model, t));
    }

    /// The stop time of the next step (which starts where the stepper is).
    #[inline]
    pub(super) fn next_stop<O: Observer>(
        &self,
        run: &mut Run<'_, O>,
        stepper: &Stepper<N3>,
    ) -> f64 {
        let t = each!(stepper, s => s.t());
        let Body::Part { j, chute, .. } = self.body else {
            return run.next_stop(t);
        };
        // A part's own stops: its canopy's opening, the gusts' samples and the time limit.
        let model = run.model;
        let mut stop = match &model.gusts {
            Some(g) => model.options.max_time_s.min(g.next_sample_s(t)),
            None => model.options.max_time_s,
        };
        if let (Some(Chute::Fired { fires_s }), Some((c, _))) = (chute, model.releases[j].parachute)
        {
            let open = fires_s + c.lag_s;
            if open > t {
                stop = stop.min(open);
            }
        }
        stop
    }

    /// One step with the descent's own derivative; the end of every descent if this was the
    /// last step of the last one.
    pub(super) fn step<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
    ) -> Result<Option<PhaseEnd>, SimError> {
        let model = run.model;
        let t_stop = self.next_stop(run, stepper);
        let canopies = self.canopies;
        let this = &*self;
        let rates = |t: f64, y: &[f64; N3], dy: &mut [f64; N3]| {
            model.descent_rates_of(this.mass(model, t), &canopies, t, y, dy);
        };
        // What changes with time but for the state: the gusts' factor, the mass while the
        // motor burns.
        let timed = model.gusts.is_some() || self.mass_kg.is_none();
        let mut evals = 0u64;
        let outcome = stepper.checked_step_with(
            rates,
            |t, y, f0, t_stop, jac, ft| {
                this.jacobian(model, &rates, timed, t, y, f0, t_stop, jac, ft)
            },
            t_stop,
            Phase::Descent.name(),
            &mut evals,
        )?;
        run.evaluations += evals;
        self.after_step(run, stepper, outcome)
    }

    /// The Jacobian of the descent's derivative `rates` at `(t, y)` (where it is `f0`) and
    /// its rate of change with time, for RODAS4: `ẋ = v` and the acceleration's `∂v̇/∂v` in
    /// closed form ([`FlightModel::descent_velocity_jacobian`]), its `∂v̇/∂z` (the air, the
    /// wind and gravity change with height) and, if anything but the state changes it
    /// (`timed`), `∂f/∂t` by differences. Returns the derivative's evaluations.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn jacobian(
        &self,
        model: &FlightModel,
        rates: &impl Fn(f64, &[f64; N3], &mut [f64; N3]),
        timed: bool,
        t: f64,
        y: &[f64; N3],
        f0: &[f64; N3],
        t_stop: f64,
        jac: &mut [[f64; N3]; N3],
        ft: &mut [f64; N3],
    ) -> u64 {
        let mut f = |t: f64, y: &[f64; N3], dy: &mut [f64; N3]| rates(t, y, dy);
        *jac = [[0.0; N3]; N3];
        for i in 0..3 {
            jac[i][3 + i] = 1.0;
        }
        let jv = model.descent_velocity_jacobian(self.mass(model, t), &self.canopies, t, y);
        for i in 0..3 {
            jac[3 + i][3..].copy_from_slice(&jv[i]);
        }
        let dz = rodas4::difference_column(&mut f, t, y, f0, 2);
        for i in 3..N3 {
            jac[i][2] = dz[i];
        }
        if timed {
            *ft = rodas4::time_difference(&mut f, t, y, f0, t_stop);
            2
        } else {
            *ft = [0.0; N3];
            1
        }
    }

    /// After a step that ended with `outcome`: events in the step (located on the dense
    /// output), the sample, triggers, stops and a change of canopies. Returns the end of
    /// every descent (the rocket's and then each released part's, which start when the one
    /// before ends), if this was the last step of the last one.
    pub(super) fn after_step<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
        outcome: StepOutcome,
    ) -> Result<Option<PhaseEnd>, SimError> {
        if let Body::Part { .. } = self.body {
            return self.after_part_step(run, stepper, outcome);
        }
        let model = run.model;
        let name = Phase::Descent.name();
        let starts = run.starts;
        run.steps += 1;
        let n = model.shifts.len();
        let mut found: Option<(f64, EventKind)> = None;
        let mut consider = |t: Option<f64>, k: EventKind| {
            if let Some(t) = t {
                if found.is_none_or(|(tf, _)| t < tf) {
                    found = Some((t, k));
                }
            }
        };
        let root_err = SimError::EventLocation;
        each!(stepper, s => {
            if !run.apogee_done {
                consider(locate_event(&**s, |_t, y: &[f64; N3]| y[5], Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::Apogee);
            }
            consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2], Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::Landing);
            if run.apogee_done {
                for (i, p) in model.parachutes.iter().enumerate() {
                    if let (Trigger::HeightDescending { height_m }, true) = (p.trigger, run.chute_armed(i) && !run.reads_noise(i)) {
                        consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2] - height_m, Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::ParachuteTrigger(i));
                    }
                }
                for (k, sh) in model.shifts.iter().enumerate() {
                    if let (Trigger::HeightDescending { height_m }, true) = (sh.trigger, starts[k].is_infinite()) {
                        consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2] - height_m, Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::Shift(k));
                    }
                }
                for (j, r) in model.releases.iter().enumerate() {
                    if let (Trigger::HeightDescending { height_m }, true) = (r.trigger, starts[n + j].is_infinite()) {
                        consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2] - height_m, Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, EventKind::Release(j));
                    }
                }
            }
        });
        let (mut t_end, mut y_end) = match found {
            Some((te, _)) => (te, each!(stepper, s => s.dense(te))),
            None => (each!(stepper, s => s.t()), *each!(stepper, s => s.y())),
        };
        // A noisy barometer's sample that fires before the step's end or its event.
        let t0 = each!(stepper, s => s.t_prev());
        let noisy = run.noisy_before(
            found,
            t0,
            t_end,
            y_end[2],
            |t| each!(stepper, s => s.dense_component(t, 2)),
        );
        if let Some((tk, i)) = noisy {
            if tk < t_end {
                (t_end, y_end) = (tk, each!(stepper, s => s.dense(tk)));
            }
            found = Some((tk, EventKind::ParachuteTrigger(i)));
        }
        let mut dy = [0.0; N3];
        let aux = model.derivative_descent(&run.starts, &self.canopies, t_end, &y_end, &mut dy);
        let pos = Vector3::new(y_end[0], y_end[1], y_end[2]);
        let vel = Vector3::new(y_end[3], y_end[4], y_end[5]);
        let speed = run.record(
            Phase::Descent,
            t_end,
            pos,
            vel,
            [f64::NAN; 4],
            [0.0; 3],
            &aux,
        );
        let alt = pos.z;
        if let Some((te, kind)) = found {
            match kind {
                EventKind::Apogee => {
                    run.apogee_done = true;
                    run.metrics.apogee_m = Some(alt);
                    run.metrics.apogee_time_s = Some(te);
                    run.push_event(EventKind::Apogee, te, alt, speed);
                    let here = Here::Point(pos, vel);
                    run.fire(te, alt, speed, here, |tr| matches!(tr, Trigger::Apogee))?;
                }
                EventKind::Landing => {
                    land(run, te, pos, vel);
                    return self.after_body(run, stepper);
                }
                EventKind::ParachuteTrigger(i) if noisy.is_some() => {
                    run.fire_at_sample(i, te, alt, speed)
                }
                EventKind::ParachuteTrigger(i) => run.trigger_chute(i, te, alt, speed),
                EventKind::Shift(k) => run.start_shift(k, te, alt, speed)?,
                EventKind::Release(j) => run.release(j, te, alt, speed, Here::Point(pos, vel))?,
                _ => {}
            }
        }
        if found.is_some() || matches!(outcome, StepOutcome::ReachedStop) {
            run.at_stop(t_end, alt, speed, Here::Point(pos, vel))?;
        }
        if t_end >= model.options.max_time_s {
            run.push_event(EventKind::TimeLimit, t_end, alt, speed);
            return self.after_body(run, stepper);
        }
        let new_canopies = run.canopies();
        let released = run.released_now;
        if released {
            run.released_now = false;
            self.body = Body::Rocket {
                removed_kg: model.removed_mass_kg(&run.starts, t_end),
            };
        }
        if found.is_some()
            || released
            || new_canopies != self.canopies
            || matches!(outcome, StepOutcome::ReachedStop)
        {
            self.canopies = new_canopies;
            self.settle_mass(model, t_end);
            let canopies = new_canopies;
            let this = &*self;
            let mut evals = 0u64;
            each!(stepper, s => s.restart(|t, y, dy| { evals += 1; model.descent_rates_of(this.mass(model, t), &canopies, t, y, dy); }, t_end, &y_end)).map_err(|e| integ_at(t_end, &y_end, e, name))?;
            run.evaluations += evals;
        }
        Ok(None)
    }

    /// The descent that ended is over: on to the next released part's, or the end of them
    /// all.
    #[inline(never)]
    fn after_body<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
    ) -> Result<Option<PhaseEnd>, SimError> {
        let after = match self.body {
            Body::Rocket { .. } => None,
            Body::Part { j, .. } => Some(j),
        };
        match Descent::next_part(run, stepper, after)? {
            Some(next) => {
                *self = next;
                Ok(None)
            }
            None => Ok(Some(PhaseEnd::Landed)),
        }
    }

    /// A released part's sample at `(t, y)`, and its highest point so far.
    fn record_part<O: Observer>(&self, run: &mut Run<'_, O>, t: f64, y: &[f64; N3]) {
        let Body::Part { j, .. } = self.body else {
            return;
        };
        let keep = run.model.options.keep_samples;
        if let Some(f) = run.releases[j].part.as_mut() {
            f.apogee_m = f.apogee_m.max(y[2]);
            if keep {
                f.samples.push(PartSample {
                    t_s: t,
                    position_m: [y[0], y[1], y[2]],
                    velocity_m_s: [y[3], y[4], y[5]],
                });
            }
        }
    }

    /// [`Descent::after_step`] of a released part: its landing, its apogee and its
    /// parachute's trigger located on the dense output, its canopy opened at its stop. Out of
    /// line: the rocket's descent, which most lanes fly, stays small.
    #[inline(never)]
    fn after_part_step<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
        outcome: StepOutcome,
    ) -> Result<Option<PhaseEnd>, SimError> {
        let Body::Part {
            j,
            mut chute,
            mut climbing,
        } = self.body
        else {
            unreachable!("a part's step");
        };
        let model = run.model;
        let name = Phase::Descent.name();
        run.steps += 1;
        let spec = model.releases[j];
        let mut found: Option<(f64, PartEvent)> = None;
        let mut consider = |t: Option<f64>, k: PartEvent| {
            if let Some(t) = t {
                if found.is_none_or(|(tf, _)| t < tf) {
                    found = Some((t, k));
                }
            }
        };
        let root_err = SimError::EventLocation;
        each!(stepper, s => {
            consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2], Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, PartEvent::Landing);
            if climbing {
                consider(locate_event(&**s, |_t, y: &[f64; N3]| y[5], Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, PartEvent::Apogee);
            }
            if let (Some(Chute::Armed), Some((PartChute { trigger: PartTrigger::HeightDescending { height_m }, .. }, _))) = (chute, spec.parachute) {
                consider(locate_event(&**s, |_t, y: &[f64; N3]| y[2] - height_m, Crossing::Falling, EVENT_TOL_S).map_err(root_err)?, PartEvent::ChuteHeight);
            }
        });
        let (t_end, y_end) = match found {
            Some((te, _)) => (te, each!(stepper, s => s.dense(te))),
            None => (each!(stepper, s => s.t()), *each!(stepper, s => s.y())),
        };
        self.record_part(run, t_end, &y_end);
        let speed = Vector3::new(y_end[3], y_end[4], y_end[5]).norm();
        let fire = |chute: &mut Option<Chute>| {
            if *chute == Some(Chute::Armed) {
                *chute = Some(Chute::Fired { fires_s: t_end });
            }
        };
        match found {
            Some((_, PartEvent::Landing)) => {
                if let Some(f) = run.releases[j].part.as_mut() {
                    f.landing_time_s = Some(t_end);
                    f.landing_position_m = Some([y_end[0], y_end[1]]);
                    f.landing_speed_m_s = Some(speed);
                }
                return self.after_body(run, stepper);
            }
            Some((_, PartEvent::Apogee)) => {
                climbing = false;
                if let Some((c, _)) = spec.parachute {
                    let on_the_way_down = match c.trigger {
                        PartTrigger::Apogee => true,
                        PartTrigger::HeightDescending { height_m } => y_end[2] <= height_m,
                        PartTrigger::Release => false,
                    };
                    if on_the_way_down {
                        fire(&mut chute);
                    }
                }
            }
            Some((_, PartEvent::ChuteHeight)) => fire(&mut chute),
            None => {}
        }
        // The canopy opens its lag after its trigger (at once without a lag).
        if let (Some(Chute::Fired { fires_s }), Some((c, _))) = (chute, spec.parachute) {
            if fires_s + c.lag_s <= t_end {
                chute = Some(Chute::Open);
                if let Some(f) = run.releases[j].part.as_mut() {
                    f.chute_open_s = Some(t_end);
                }
            }
        }
        self.body = Body::Part { j, chute, climbing };
        if t_end >= model.options.max_time_s {
            return self.after_body(run, stepper);
        }
        let new_canopies = self.part_canopies(model);
        if found.is_some()
            || new_canopies != self.canopies
            || matches!(outcome, StepOutcome::ReachedStop)
        {
            self.canopies = new_canopies;
            let (canopies, mass) = (new_canopies, model.mass.released[j].mass_kg);
            let mut evals = 0u64;
            each!(stepper, s => s.restart(|t, y, dy| { evals += 1; model.descent_rates_of(mass, &canopies, t, y, dy); }, t_end, &y_end)).map_err(|e| integ_at(t_end, &y_end, e, name))?;
            run.evaluations += evals;
        }
        Ok(None)
    }
}
