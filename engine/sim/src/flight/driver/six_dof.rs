//! The rail and free-flight phases: one step at a time, with the event functions found from
//! one mass-state evaluation per step end and located by Brent's method on the dense output.

use super::*;

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

/// The center of mass's position and velocity at a step's end: what the event functions
/// read there.
#[derive(Debug, Clone, Copy)]
struct Ends {
    pos: Vector3<f64>,
    vel: Vector3<f64>,
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
    fn at_end(self, model: &FlightModel, y: &[f64; N6], ep: &Ends) -> f64 {
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

/// The derivative of the rail or the free flight, its instant read through the flight's
/// memo (`changes` counts the changes of `starts`), the air brakes' drag coefficient
/// `brake_cd` (0: closed; never on the rail).
#[inline]
#[allow(clippy::too_many_arguments)]
pub(super) fn derivative(
    model: &FlightModel,
    rail: bool,
    memo: &mut InstantMemo,
    starts: &ShiftStarts,
    changes: u64,
    brake_cd: f64,
    t: f64,
    y: &[f64; N6],
    dy: &mut [f64; N6],
) {
    let (ms, thrust_n) = memo.get(model, starts, changes, t);
    if rail {
        model.derivative_rail_at(ms, thrust_n, t, y, dy)
    } else {
        model.derivative_6dof_at(ms, thrust_n, brake_cd, t, y, dy)
    }
}

/// A rail or free-flight phase between its steps: what the step that comes next needs, and
/// what the driver does after it ([`SixDof::after_step`]). The single flight steps it with
/// its own derivative ([`six_dof_phase`]); the batch engine steps the free flight of four
/// lanes at a time and hands each lane's step to the same `after_step`.
#[derive(Clone)]
pub(super) struct SixDof {
    pub(super) phase: Phase,
    prev_y: [f64; N6],
    /// The center's position and velocity at the end of the last step.
    prev: Ends,
    events: Vec<(EventKind, G)>,
    /// Time at the start of the step in progress.
    t_now: f64,
}

impl SixDof {
    /// Start the phase at `(t0, y0)`: the stepper's first derivative and the first sample.
    pub(super) fn start<O: Observer>(
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N6>,
        phase: Phase,
        t0: f64,
        y0: &[f64; N6],
    ) -> Result<SixDof, SimError> {
        let model = run.model;
        let rail = phase == Phase::Rail;
        let (starts, changes, brake) = (run.starts, run.starts_changed, run.brake_cd);
        let memo = &mut run.memo;
        let mut evals = 0u64;
        each!(stepper, s => s.init(|t, y, dy| { evals += 1; derivative(model, rail, memo, &starts, changes, brake, t, y, dy); }, t0, y0))
            .map_err(|e| integ_at(t0, y0, e, phase.name()))?;
        run.evaluations += evals;
        let ms = run.memo.get(model, &starts, changes, t0).0;
        let (pos, vel, aux) = model.end_point(ms, t0, y0, each!(stepper, s => s.dy()), rail);
        let ep = EndPoint { pos, vel, aux };
        run.record(
            phase,
            t0,
            ep.pos,
            ep.vel,
            [y0[6], y0[7], y0[8], y0[9]],
            [y0[10], y0[11], y0[12]],
            &ep.aux,
        );
        Ok(SixDof {
            phase,
            prev_y: *y0,
            prev: Ends {
                pos: ep.pos,
                vel: ep.vel,
            },
            events: Vec::with_capacity(2 + model.parachutes.len() + model.shifts.len()),
            t_now: t0,
        })
    }

    /// The stop time of the next step (which starts where the stepper is).
    pub(super) fn next_stop<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &Stepper<N6>,
    ) -> f64 {
        self.t_now = each!(stepper, s => s.t());
        run.next_stop(self.t_now)
    }

    /// After a step that ended with `outcome`: events in the step (located on the dense
    /// output), the sample, triggers and stops. Returns the phase's end, if this was its last
    /// step. `ep1` is the step end's figures if the caller has computed them
    /// ([`FlightModel::end_point`], or the batch's [`crate::flight::model::end_point_lanes`]
    /// on four lanes); otherwise they are computed here.
    pub(super) fn after_step<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N6>,
        outcome: crate::integrate::StepOutcome,
        ep1: Option<EndFigures>,
    ) -> Result<Option<(f64, [f64; N6], PhaseEnd)>, SimError> {
        let model = run.model;
        let phase = self.phase;
        let rail = phase == Phase::Rail;
        let name = phase.name();
        let t_now = self.t_now;
        run.steps += 1;
        let (t1, y1) = (each!(stepper, s => s.t()), *each!(stepper, s => s.y()));
        let (pos1, vel1, aux1) = match ep1 {
            Some(ep) => ep,
            None => {
                let ms1 = run.memo.get(model, &run.starts, run.starts_changed, t1).0;
                model.end_point(ms1, t1, &y1, each!(stepper, s => s.dy()), rail)
            }
        };
        let ep1 = EndPoint {
            pos: pos1,
            vel: vel1,
            aux: aux1,
        };
        // The event functions that can fire now.
        let events = &mut self.events;
        events.clear();
        if rail {
            events.push((EventKind::RailExit, G::RailTravel));
        } else if !run.apogee_done {
            events.push((EventKind::Apogee, G::VerticalSpeed));
        } else {
            events.push((EventKind::Landing, G::Height(0.0)));
            for (i, p) in model.parachutes.iter().enumerate() {
                if let (Trigger::HeightDescending { height_m }, true) =
                    (p.trigger, run.chute_armed(i) && !run.reads_noise(i))
                {
                    events.push((EventKind::ParachuteTrigger(i), G::Height(height_m)));
                }
            }
            for (k, sh) in model.shifts.iter().enumerate() {
                if let (Trigger::HeightDescending { height_m }, true) =
                    (sh.trigger, run.starts[k].is_infinite())
                {
                    events.push((EventKind::Shift(k), G::Height(height_m)));
                }
            }
            let n = model.shifts.len();
            for (j, r) in model.releases.iter().enumerate() {
                if let (Trigger::HeightDescending { height_m }, true) =
                    (r.trigger, run.starts[n + j].is_infinite())
                {
                    events.push((EventKind::Release(j), G::Height(height_m)));
                }
            }
        }
        // Earliest crossing in the step: rail travel rises through zero, the rest fall.
        let mut found: Option<(f64, EventKind)> = None;
        let starts = &run.starts;
        for &(kind, g) in events.iter() {
            let (g0, g1) = (
                g.at_end(model, &self.prev_y, &self.prev),
                g.at_end(
                    model,
                    &y1,
                    &Ends {
                        pos: ep1.pos,
                        vel: ep1.vel,
                    },
                ),
            );
            let crossing = if rail {
                Crossing::Rising
            } else {
                Crossing::Falling
            };
            if t1 > t_now && crossing.matches(g0, g1) {
                let te = each!(stepper, s => brent_root_bracketed(|t| g.at(model, starts, t, &s.dense(t)), t_now, g0, t1, g1, EVENT_TOL_S))
                    .map_err(SimError::EventLocation)?;
                if found.is_none_or(|(tf, _)| te < tf) {
                    found = Some((te, kind));
                }
            }
        }
        let (mut t_end, mut y_end, mut ep) = match found {
            Some((te, _)) => {
                let (ye, ep) = end_point_at(run, stepper, rail, te);
                (te, ye, ep)
            }
            None => (t1, y1, ep1),
        };
        // A noisy barometer's sample that fires before the step's end or its event.
        let noisy = if run.hears_noise() {
            let starts = run.starts;
            run.noisy_before(
                found,
                t_now,
                t_end,
                ep.pos.z,
                |t| each!(stepper, s => G::Height(0.0).at(model, &starts, t, &s.dense(t))),
            )
        } else {
            None
        };
        if let Some((tk, i)) = noisy {
            if tk < t_end {
                (y_end, ep) = end_point_at(run, stepper, rail, tk);
                t_end = tk;
            }
            found = Some((tk, EventKind::ParachuteTrigger(i)));
        }
        let speed = run.record(
            phase,
            t_end,
            ep.pos,
            ep.vel,
            [y_end[6], y_end[7], y_end[8], y_end[9]],
            [y_end[10], y_end[11], y_end[12]],
            &ep.aux,
        );
        let (pos, vel) = (ep.pos, ep.vel);
        let alt = pos.z;
        self.prev_y = y_end;
        self.prev = Ends { pos, vel };
        if let Some((te, kind)) = found {
            match kind {
                EventKind::RailExit => {
                    run.rail_exit_done = true;
                    run.push_event(EventKind::RailExit, te, alt, speed);
                    run.metrics.rail_exit_time_s = Some(te);
                    run.metrics.rail_exit_speed_m_s = Some(speed);
                    run.metrics.static_margin_rail_exit_cal =
                        Some(model.static_margin_of(ep.aux.r_cm_z_m));
                    return Ok(Some((te, y_end, PhaseEnd::RailExit)));
                }
                EventKind::Apogee => {
                    run.apogee_done = true;
                    // The brakes close at the top (the stepper restarts below, as after
                    // every event).
                    run.brake_cd = 0.0;
                    run.metrics.apogee_m = Some(alt);
                    run.metrics.apogee_time_s = Some(te);
                    run.push_event(EventKind::Apogee, te, alt, speed);
                    run.fire(te, alt, speed, Here::Free(&y_end), |tr| {
                        matches!(tr, Trigger::Apogee)
                    })?;
                }
                EventKind::Landing => {
                    land(run, te, pos, vel);
                    return Ok(Some((te, y_end, PhaseEnd::Landed)));
                }
                EventKind::ParachuteTrigger(i) if noisy.is_some() => {
                    run.fire_at_sample(i, te, alt, speed)
                }
                EventKind::ParachuteTrigger(i) => run.trigger_chute(i, te, alt, speed),
                EventKind::Shift(k) => run.start_shift(k, te, alt, speed)?,
                EventKind::Release(j) => run.release(j, te, alt, speed, Here::Free(&y_end))?,
                _ => {}
            }
        }
        if (found.is_some() || matches!(outcome, crate::integrate::StepOutcome::ReachedStop))
            && run.at_stop(
                t_end,
                alt,
                speed,
                if rail { Here::Rail } else { Here::Free(&y_end) },
            )?
        {
            return Ok(Some((t_end, y_end, PhaseEnd::Deploy)));
        }
        if t_end >= model.options.max_time_s {
            run.push_event(EventKind::TimeLimit, t_end, alt, speed);
            return Ok(Some((t_end, y_end, PhaseEnd::TimeLimit)));
        }
        let braked = phase == Phase::Free && run.control_brakes(t_end, pos, vel, &ep.aux);
        // A part that left changes the derivative at once: the stepper starts again there.
        if found.is_some() || braked || run.released_now {
            run.released_now = false;
            let (starts, changes, brake) = (run.starts, run.starts_changed, run.brake_cd);
            let memo = &mut run.memo;
            let mut evals = 0u64;
            each!(stepper, s => s.restart(|t, y, dy| { evals += 1; derivative(model, rail, memo, &starts, changes, brake, t, y, dy); }, t_end, &y_end)).map_err(|e| integ_at(t_end, &y_end, e, name))?;
            run.evaluations += evals;
        }
        Ok(None)
    }

    /// One step with the phase's own derivative.
    pub(super) fn step<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N6>,
    ) -> Result<Option<(f64, [f64; N6], PhaseEnd)>, SimError> {
        let model = run.model;
        let rail = self.phase == Phase::Rail;
        let t_stop = self.next_stop(run, stepper);
        let (starts, changes, brake) = (run.starts, run.starts_changed, run.brake_cd);
        let memo = &mut run.memo;
        let mut evals = 0u64;
        let outcome = stepper.checked_step(
            |t, y, dy| derivative(model, rail, memo, &starts, changes, brake, t, y, dy),
            t_stop,
            self.phase.name(),
            &mut evals,
        )?;
        run.evaluations += evals;
        self.after_step(run, stepper, outcome, None)
    }
}

/// The state at `te` inside the step just taken (its dense output) and the end figures there.
fn end_point_at<O: Observer>(
    run: &mut Run<'_, O>,
    stepper: &Stepper<N6>,
    rail: bool,
    te: f64,
) -> ([f64; N6], EndPoint) {
    let model = run.model;
    let (starts, changes, brake) = (run.starts, run.starts_changed, run.brake_cd);
    let ye = each!(stepper, s => s.dense(te));
    let mut dy = [0.0; N6];
    derivative(
        model,
        rail,
        &mut run.memo,
        &starts,
        changes,
        brake,
        te,
        &ye,
        &mut dy,
    );
    let ms = run.memo.get(model, &starts, changes, te).0;
    let (pos, vel, aux) = model.end_point(ms, te, &ye, &dy, rail);
    (ye, EndPoint { pos, vel, aux })
}

/// Rail or free flight until the rail exit (rail), a canopy opens, landing or the time limit.
pub(super) fn six_dof_phase<O: Observer>(
    run: &mut Run<'_, O>,
    stepper: &mut Stepper<N6>,
    phase: Phase,
    t0: f64,
    y0: &[f64; N6],
) -> Result<(f64, [f64; N6], PhaseEnd), SimError> {
    let mut sd = SixDof::start(run, stepper, phase, t0, y0)?;
    loop {
        if let Some(end) = sd.step(run, stepper)? {
            return Ok(end);
        }
    }
}
