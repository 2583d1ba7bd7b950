//! The descent under canopy: the center of mass as a point with the canopies' drag, one step
//! at a time. The single flight steps it with its own derivative ([`Descent::step`]); the
//! batch engine steps four lanes' descents together and hands each lane's step to the same
//! [`Descent::after_step`].

use super::*;

/// A descent between its steps: the canopies in force.
pub(super) struct Descent {
    canopies: Canopies<f64>,
}

impl Descent {
    /// Start under canopy at `(t0, y0)`: the stepper's first derivative and the first sample.
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
        let mut evals = 0u64;
        each!(stepper, s => s.init(|t, y, dy| { evals += 1; model.descent_rates(&canopies, t, y, dy); }, t0, y0)).map_err(|e| integ_at(t0, y0, e, name))?;
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
        Ok(Descent { canopies })
    }

    /// The canopies in force.
    #[inline(always)]
    pub(super) fn canopies(&self) -> Canopies<f64> {
        self.canopies
    }

    /// The stop time of the next step (which starts where the stepper is).
    pub(super) fn next_stop<O: Observer>(run: &mut Run<'_, O>, stepper: &Stepper<N3>) -> f64 {
        run.next_stop(each!(stepper, s => s.t()))
    }

    /// One step with the descent's own derivative; the phase's end if it ended.
    pub(super) fn step<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
    ) -> Result<Option<PhaseEnd>, SimError> {
        let model = run.model;
        let t_stop = Descent::next_stop(run, stepper);
        let canopies = self.canopies;
        let mut evals = 0u64;
        let outcome = stepper.checked_step(
            |t, y, dy| {
                model.descent_rates(&canopies, t, y, dy);
            },
            t_stop,
            Phase::Descent.name(),
            &mut evals,
        )?;
        run.evaluations += evals;
        self.after_step(run, stepper, outcome)
    }

    /// After a step that ended with `outcome`: events in the step (located on the dense
    /// output), the sample, triggers, stops and a change of canopies. Returns the phase's
    /// end (landing or the time limit), if this was its last step.
    pub(super) fn after_step<O: Observer>(
        &mut self,
        run: &mut Run<'_, O>,
        stepper: &mut Stepper<N3>,
        outcome: StepOutcome,
    ) -> Result<Option<PhaseEnd>, SimError> {
        let model = run.model;
        let name = Phase::Descent.name();
        let starts = run.starts;
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
                    if let (Trigger::HeightDescending { height_m }, true) = (p.trigger, run.chute_armed(i) && !run.reads_noise(i)) {
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
        run.record(
            Phase::Descent,
            t_end,
            pos,
            vel,
            [f64::NAN; 4],
            [0.0; 3],
            &aux,
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
                    return Ok(Some(PhaseEnd::Landed));
                }
                EventKind::ParachuteTrigger(i) if noisy.is_some() => {
                    run.fire_at_sample(i, te, alt, speed)
                }
                EventKind::ParachuteTrigger(i) => run.trigger_chute(i, te, alt, speed),
                EventKind::Shift(k) => run.start_shift(k, te, alt, speed)?,
                _ => {}
            }
        }
        if found.is_some() || matches!(outcome, StepOutcome::ReachedStop) {
            run.at_stop(t_end, alt, speed)?;
        }
        if t_end >= model.options.max_time_s {
            run.push_event(EventKind::TimeLimit, t_end, alt, speed);
            return Ok(Some(PhaseEnd::TimeLimit));
        }
        let new_canopies = run.canopies();
        if found.is_some()
            || new_canopies != self.canopies
            || matches!(outcome, StepOutcome::ReachedStop)
        {
            self.canopies = new_canopies;
            let canopies = new_canopies;
            let mut evals = 0u64;
            each!(stepper, s => s.restart(|t, y, dy| { evals += 1; model.descent_rates(&canopies, t, y, dy); }, t_end, &y_end)).map_err(|e| integ_at(t_end, &y_end, e, name))?;
            run.evaluations += evals;
        }
        Ok(None)
    }
}
