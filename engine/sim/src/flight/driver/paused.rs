//! A flight paused between steps: the pad and the rail flown ([`fly_to_free`]), the free
//! flight ([`Paused`]) and the descent ([`Descending`]) stepped one step at a time by the
//! single flight, or with four lanes' stages evaluated together by the batch engine, and the
//! flight's record once it is over.

use super::*;
use crate::lanes::F64x4;
use crate::massprops::MassInputs;
use hpr_design::motor::MotorState;

/// A flight paused in its free flight, between two steps. The single flight steps it with
/// [`Paused::step`]; the batch engine steps four lanes' free flights together: it begins
/// each lane's step ([`Paused::begin_step`]), computes the stages of the four lanes side by
/// side, has each lane judge its attempt ([`Paused::judge`], [`Paused::commit`]), and hands
/// every finished step to the same [`Paused::end_step`].
pub(crate) struct Paused<'a, O: Observer> {
    run: Run<'a, O>,
    s6: LaneStepper<N6>,
    free: SixDof,
    rtol: f64,
    atol3: [f64; N3],
    /// The mass state while nothing changes the mass, and the count of shift-start changes
    /// it holds for (`Run::starts_changed`).
    settled: Option<(u64, MassLanes<f64>, u64)>,
    /// Serial number of the last mass state handed out by [`Paused::mass_at`].
    serial: u64,
    /// The mass state of the last stage that was not settled, its thrust, and the time
    /// and count of shift-start changes they hold for.
    moving: MassLanes<f64>,
    moving_thrust_n: f64,
    moving_key: Option<(u64, u64)>,
    /// A time from which on the mass stays settled, and the count of shift-start changes it
    /// holds for ([`FlightModel::settled_from_now_on`]).
    settled_from: Option<(f64, u64)>,
    /// The motor curve's segment at the last stage computed on lanes (where the next look-up
    /// starts).
    motor_segment: usize,
}

/// A phase's stepper as the batch engine steps it, four lanes' stages computed together
/// outside it: the stepper, the watch over its step in progress, and the phase it steps.
#[derive(Clone)]
pub(crate) struct LaneStepper<const N: usize> {
    stepper: Stepper<N>,
    watch: Watch<N>,
    phase: Phase,
}

impl<const N: usize> LaneStepper<N> {
    fn new(stepper: Stepper<N>, phase: Phase, t: f64) -> LaneStepper<N> {
        LaneStepper {
            stepper,
            watch: Watch::new(t),
            phase,
        }
    }

    /// Whether its steps can be taken on lanes (adaptive, not fixed-step RK4).
    fn on_lanes(&self) -> bool {
        matches!(self.stepper, Stepper::Adaptive(_))
    }

    /// Begin a step to `t_stop` whose stages are computed outside; `f` is the phase's
    /// derivative, for the estimate of a first step (its evaluations counted in `evals`).
    fn begin(
        &mut self,
        t_stop: f64,
        evals: &mut u64,
        mut f: impl FnMut(f64, &[f64; N], &mut [f64; N]),
    ) -> Result<(), SimError> {
        let Stepper::Adaptive(d) = &mut self.stepper else {
            return Err(not_on_lanes());
        };
        self.watch = Watch::new(d.t());
        let watch = &mut self.watch;
        let begun = d.begin_step_outside(
            &mut |t, y: &[f64; N], dy: &mut [f64; N]| {
                *evals += 1;
                f(t, y, dy);
                watch.observe(t, y, dy);
            },
            t_stop,
        );
        begun.map_err(|e| self.watch.error(e, d.y(), self.phase.name()))
    }

    /// The adaptive stepper of the step begun.
    #[inline(always)]
    pub(crate) fn dopri(&self) -> &Dopri54<N> {
        match &self.stepper {
            Stepper::Adaptive(d) => d,
            _ => unreachable!("only Dormand–Prince steps are taken on lanes"),
        }
    }

    /// A stage's derivative `dy` at `(t, y)` that may not be finite (looked at here value by
    /// value): the first one that is not is where a flight that goes non-finite is reported
    /// to have done so.
    #[cold]
    pub(crate) fn observe(&mut self, t: f64, y: &[f64; N], dy: &[f64; N]) {
        self.watch.observe(t, y, dy);
    }

    /// The verdict on the attempt whose six stages were evaluated outside, from its error
    /// norm `err`, the norm's logarithm and the controller's factors computed outside too
    /// ([`Dopri54::judge_given`]; the six evaluations are counted in `evals`): the
    /// outcome when accepted (then hand the new state to [`LaneStepper::commit`]), `None`
    /// when the step is tried again, smaller.
    #[inline(always)]
    pub(crate) fn judge(
        &mut self,
        verdict: Verdict,
        evals: &mut u64,
    ) -> Result<Option<StepOutcome>, SimError> {
        let Stepper::Adaptive(d) = &mut self.stepper else {
            return Err(not_on_lanes());
        };
        *evals += 6;
        let Verdict {
            err,
            ln_err,
            growth,
            shrinkage,
        } = verdict;
        d.judge_given(err, ln_err, || growth, || shrinkage, 6)
            .map_err(|e| self.watch.error(e, d.y(), self.phase.name()))
    }

    /// The end of the step [`LaneStepper::judge`] accepted, lane `l` of the four attempts
    /// held side by side ([`Dopri54::commit_lane`]); it must be finite.
    #[inline(always)]
    pub(crate) fn commit(
        &mut self,
        l: usize,
        y_new: &[F64x4; N],
        k7: &[F64x4; N],
        cont: &[[F64x4; N]; 4],
    ) -> Result<(), SimError> {
        let Stepper::Adaptive(d) = &mut self.stepper else {
            return Err(not_on_lanes());
        };
        d.commit_lane(l, y_new, k7, cont);
        self.watch.check_end(d.t(), d.y())
    }
}

/// An attempt's error norm, its logarithm and the step-size controller's factors from it
/// ([`crate::integrate::dopri54::growth`], [`crate::integrate::dopri54::shrinkage`]), as
/// the batch computes them for four attempts at once.
#[derive(Clone, Copy)]
pub(crate) struct Verdict {
    pub(crate) err: f64,
    pub(crate) ln_err: f64,
    pub(crate) growth: f64,
    pub(crate) shrinkage: f64,
}

fn not_on_lanes() -> SimError {
    SimError::FixedStepOnLanes
}

/// A flight paused in a phase that the batch engine steps four lanes at a time ([`Paused`]
/// in free flight, [`Descending`] under canopy). The single flight takes whole steps
/// ([`PausedPhase::step`]); the batch engine begins each lane's step
/// ([`PausedPhase::begin_step`]), computes the four lanes' stages side by side, has each lane
/// judge and commit its attempt through its [`LaneStepper`], and hands every finished step
/// to the same [`PausedPhase::end_step`] as the single flight.
pub(crate) trait PausedPhase<'a, const N: usize> {
    /// How the phase ends.
    type End;
    /// The flight's model.
    fn model(&self) -> &'a FlightModel;
    /// One step with the flight's own derivative; the phase's end if it ended.
    fn step(&mut self) -> Result<Option<Self::End>, SimError>;
    /// Start a step whose stages are computed on lanes. False when the integrator does not
    /// step that way (fixed-step RK4): then take the step with [`PausedPhase::step`].
    fn begin_step(&mut self) -> Result<bool, SimError>;
    /// After a step taken on lanes: the same as the end of [`PausedPhase::step`].
    fn end_step(&mut self, outcome: StepOutcome) -> Result<Option<Self::End>, SimError>;
    /// The phase's lane stepper.
    fn lanes(&self) -> &LaneStepper<N>;
    /// The phase's lane stepper and the flight's count of derivative evaluations.
    fn lanes_mut(&mut self) -> (&mut LaneStepper<N>, &mut u64);

    #[inline(always)]
    fn dopri(&self) -> &Dopri54<N> {
        self.lanes().dopri()
    }
    #[inline(always)]
    fn observe(&mut self, t: f64, y: &[f64; N], dy: &[f64; N]) {
        self.lanes_mut().0.observe(t, y, dy);
    }
    #[inline(always)]
    fn judge(&mut self, verdict: Verdict) -> Result<Option<StepOutcome>, SimError> {
        let (lanes, evals) = self.lanes_mut();
        lanes.judge(verdict, evals)
    }
    #[inline(always)]
    fn commit(
        &mut self,
        l: usize,
        y_new: &[F64x4; N],
        k7: &[F64x4; N],
        cont: &[[F64x4; N]; 4],
    ) -> Result<(), SimError> {
        self.lanes_mut().0.commit(l, y_new, k7, cont)
    }
}

/// Where a flight is after [`fly_to_free`].
#[allow(clippy::large_enum_variant)]
pub(crate) enum Progress<'a, O: Observer> {
    /// In free flight, between steps.
    Free(Box<Paused<'a, O>>),
    /// Over before any free flight (it ended on the rail).
    Done(Flight),
}

/// Set the flight up and fly it to the start of its free flight: the pad and the rail (or
/// straight into free flight from `from`).
pub(crate) fn fly_to_free<'a, O: Observer>(
    model: &'a FlightModel,
    observer: &'a mut O,
    from: Option<(f64, [f64; N6])>,
) -> Result<Progress<'a, O>, SimError> {
    let n_chutes = model.parachutes.len();
    let mut stops = Stops(Vec::with_capacity(
        64 + STOPS_PER_SHIFT * model.shifts.len() + 2 * n_chutes + model.releases.len(),
    ));
    for &k in &model.thrust_knots_s {
        stops.push(k);
    }
    stops.push(model.burnout_s);
    for tr in model
        .parachutes
        .iter()
        .map(|p| p.trigger)
        .chain(model.shifts.iter().map(|s| s.trigger))
        .chain(model.releases.iter().map(|r| r.trigger))
    {
        if let Some(t) = tr.fixed_time(model.burnout_s, model.motor_delay_s) {
            stops.push(t);
        }
    }
    let mut run = Run {
        model,
        observer,
        starts: [f64::INFINITY; MAX_SHIFTS],
        starts_changed: 0,
        memo: InstantMemo::default(),
        stops,
        samples: Vec::with_capacity(if model.options.keep_samples { 2048 } else { 0 }),
        events: Vec::with_capacity(16),
        metrics: Metrics::default(),
        evaluations: 0,
        steps: 0,
        apogee_done: false,
        chutes: vec![Chute::Armed; n_chutes],
        noise: barometers(model),
        rail_exit_done: false,
        burnout_done: false,
        max_climb_m_s: 0.0,
        steepest: None,
        brake_cd: 0.0,
        releases: vec![ReleaseRecord::default(); model.releases.len()],
        released_now: false,
        brake_next_s: if model.air_brakes.is_some() {
            model.burnout_s
        } else {
            f64::INFINITY
        },
    };

    let (rtol, atol6, atol3) = tolerances(&model.options.integrator);
    let (t, y, on_rail) = match from {
        Some((t0, y0)) => {
            run.rail_exit_done = true;
            run.burnout_done = t0 >= model.burnout_s;
            // Started on the way down (or at the top), the apogee is behind it: the landing
            // and the height triggers are armed at once.
            run.apogee_done = cm_of(model, &run.starts, t0, &y0).1.z <= 0.0;
            run.stops.0.retain(|&s| s > t0);
            (t0, y0, false)
        }
        None => {
            let (t, y) = pad(&mut run)?;
            (t, y, true)
        }
    };
    let mut s6: Stepper<N6> =
        Stepper::new(&model.options.integrator, atol6, rtol).map_err(|e| integ(t, e, "setup"))?;
    let (t, y) = if on_rail {
        match six_dof_phase(&mut run, &mut s6, Phase::Rail, t, &y)? {
            (t, y, PhaseEnd::RailExit) => (t, y),
            end => return finish(run, rtol, atol3, end).map(Progress::Done),
        }
    } else {
        (t, y)
    };
    let free = SixDof::start(&mut run, &mut s6, Phase::Free, t, &y)?;
    Ok(Progress::Free(Box::new(Paused {
        run,
        s6: LaneStepper::new(s6, Phase::Free, t),
        free,
        rtol,
        atol3,
        settled: None,
        serial: 0,
        moving: MassLanes::ZERO,
        moving_thrust_n: 0.0,
        moving_key: None,
        settled_from: None,
        motor_segment: 0,
    })))
}

/// The flight after its rail or free flight ended with `end`: the descent if a canopy
/// opened, then the flight's record.
fn finish<O: Observer>(
    run: Run<'_, O>,
    rtol: f64,
    atol3: [f64; N3],
    end: (f64, [f64; N6], PhaseEnd),
) -> Result<Flight, SimError> {
    match descend(run, rtol, atol3, end)? {
        AfterFree::Done(flight) => Ok(flight),
        AfterFree::Descending(mut d) => loop {
            if d.step()?.is_some() {
                return Ok(d.finish());
            }
        },
    }
}

/// Where a flight is once its free flight is over.
#[allow(clippy::large_enum_variant)]
pub(crate) enum AfterFree<'a, O: Observer> {
    /// Under canopy, between steps.
    Descending(Box<Descending<'a, O>>),
    /// Over (it landed or ran out of time without a canopy, or failed).
    Done(Flight),
}

/// The flight after its rail or free flight ended with `end`: under canopy if one opened,
/// else its record.
fn descend<'a, O: Observer>(
    mut run: Run<'a, O>,
    rtol: f64,
    atol3: [f64; N3],
    (t, y, end): (f64, [f64; N6], PhaseEnd),
) -> Result<AfterFree<'a, O>, SimError> {
    let model = run.model;
    // The free flight's restart is behind it.
    run.released_now = false;
    let mut s3: Stepper<N3> = Stepper::descent(&model.options.integrator, atol3, rtol)
        .map_err(|e| integ(t, e, "setup"))?;
    let descent = if let PhaseEnd::Deploy = end {
        // Descent: the center of mass as a point, with its velocity (including r′) kept.
        let (pos, vel) = cm_of(model, &run.starts, t, &y);
        let y3 = [pos.x, pos.y, pos.z, vel.x, vel.y, vel.z];
        Descent::start(&mut run, &mut s3, t, &y3)?
    } else {
        // Landed or out of time without a canopy: the parts that left fly next, if any.
        match Descent::next_part(&mut run, &mut s3, None)? {
            Some(d) => d,
            None => return Ok(AfterFree::Done(record(run))),
        }
    };
    let t0 = each!(&s3, s => s.t());
    Ok(AfterFree::Descending(Box::new(Descending {
        run,
        s3: LaneStepper::new(s3, Phase::Descent, t0),
        descent,
    })))
}

/// The flight's record.
fn record<O: Observer>(run: Run<'_, O>) -> Flight {
    let model = run.model;
    let mut metrics = run.metrics;
    metrics.max_alpha_deg = run
        .steepest
        .map(|(cross, axial)| FlightAux::alpha_of(cross, axial).to_degrees());
    Flight {
        samples: run.samples,
        events: run.events,
        metrics,
        shift_starts_s: run.starts[..model.shifts.len()]
            .iter()
            .map(|&s| s.is_finite().then_some(s))
            .collect(),
        releases: run.releases,
        derivative_evaluations: run.evaluations,
        steps: run.steps,
    }
}

/// A flight under canopy, between two steps of its descent. The single flight steps it with
/// [`Descending::step`]; the batch engine steps four lanes' descents together, as it does
/// their free flights.
pub(crate) struct Descending<'a, O: Observer> {
    run: Run<'a, O>,
    s3: LaneStepper<N3>,
    descent: Descent,
}

impl<O: Observer> Descending<'_, O> {
    /// The flight's record, once its descent has ended.
    pub(crate) fn finish(self) -> Flight {
        record(self.run)
    }
}

impl<'a, O: Observer> PausedPhase<'a, N3> for Descending<'a, O> {
    type End = PhaseEnd;

    fn model(&self) -> &'a FlightModel {
        self.run.model
    }

    fn step(&mut self) -> Result<Option<PhaseEnd>, SimError> {
        self.descent.step(&mut self.run, &mut self.s3.stepper)
    }

    fn begin_step(&mut self) -> Result<bool, SimError> {
        if !self.s3.on_lanes() {
            return Ok(false);
        }
        let t_stop = self.descent.next_stop(&mut self.run, &self.s3.stepper);
        let model = self.run.model;
        let canopies = self.descent.canopies();
        let descent = &self.descent;
        self.s3
            .begin(t_stop, &mut self.run.evaluations, |t, y, dy| {
                model.descent_rates_of(descent.mass(model, t), &canopies, t, y, dy);
            })?;
        Ok(true)
    }

    fn end_step(&mut self, outcome: StepOutcome) -> Result<Option<PhaseEnd>, SimError> {
        self.descent
            .after_step(&mut self.run, &mut self.s3.stepper, outcome)
    }

    #[inline(always)]
    fn lanes(&self) -> &LaneStepper<N3> {
        &self.s3
    }

    #[inline(always)]
    fn lanes_mut(&mut self) -> (&mut LaneStepper<N3>, &mut u64) {
        (&mut self.s3, &mut self.run.evaluations)
    }
}

/// A free-flight step's end: time, state and why the phase ended.
pub(crate) type StepEnd = (f64, [f64; N6], PhaseEnd);

/// Sharing a free flight's beginning with other flights: where it stands, whether its next
/// step could tell them apart, and a copy of it as another flight's.
impl<'a, O: Observer> Paused<'a, O> {
    /// Whether every attempt of the free flight's next step ends before `limit`, whatever
    /// stop times at or after `limit` the flight has (then a flight whose stops differ from
    /// this one's only there, with the same derivative before `limit`, takes the same step):
    /// its stop is before `limit`, or its first attempt's reach ([`Dopri54::next_reach`]) is.
    /// False for a step whose size is yet to be estimated toward a stop at or after `limit`
    /// and for fixed-step RK4.
    pub(crate) fn next_step_before(&mut self, limit: f64) -> bool {
        let Stepper::Adaptive(d) = &self.s6.stepper else {
            return false;
        };
        let t_stop = self.run.next_stop(d.t());
        t_stop < limit || d.next_reach(t_stop).is_some_and(|r| r < limit)
    }

    /// The latest time an attempt of this flight so far was allowed to reach, s
    /// ([`Dopri54::reach`]; infinite for fixed-step RK4, whose steps are not watched).
    pub(crate) fn reach(&self) -> f64 {
        match &self.s6.stepper {
            Stepper::Adaptive(d) => d.reach(),
            _ => f64::INFINITY,
        }
    }

    /// This paused flight as a flight of `model` (with `observer`) that stands where this
    /// one stands: its state, stepper, record and pending stops copied, its memos left
    /// behind (each is recomputed from `model` when asked, to the same bits). The caller
    /// answers for `model` flying exactly as this flight's model did up to here, and moves
    /// the stop times where the two models' fixed triggers differ ([`Paused::move_stops`]).
    pub(crate) fn clone_onto<'b, P: Observer>(
        &self,
        model: &'b FlightModel,
        observer: &'b mut P,
    ) -> Paused<'b, P> {
        Paused {
            run: self.run.clone_onto(model, observer),
            s6: self.s6.clone(),
            free: self.free.clone(),
            rtol: self.rtol,
            atol3: self.atol3,
            settled: None,
            serial: self.serial,
            moving: MassLanes::ZERO,
            moving_thrust_n: 0.0,
            moving_key: None,
            settled_from: None,
            motor_segment: 0,
        }
    }

    /// Replace the pending stops at the times `from` by stops at `to` (a fixed trigger of
    /// this flight's model at a time of `from`, of another model's at `to`): one stop taken
    /// away per time of `from` still ahead, one added per time of `to` ahead.
    pub(crate) fn move_stops(&mut self, from: &[f64], to: &[f64]) {
        let t = self.time_s();
        for &s in from.iter().filter(|&&s| s > t) {
            self.run.stops.remove(s);
        }
        for &s in to.iter().filter(|&&s| s > t) {
            self.run.stops.push(s);
        }
    }

    /// Time of the free flight where it stands, s.
    pub(crate) fn time_s(&self) -> f64 {
        each!(&self.s6.stepper, s => s.t())
    }
}

impl<'a, O: Observer> Paused<'a, O> {
    /// The flight from the end of its free flight (descent, record).
    pub(crate) fn finish(self, end: StepEnd) -> Result<Flight, SimError> {
        finish(self.run, self.rtol, self.atol3, end)
    }

    /// The flight once its free flight ended with `end`: under canopy, to be stepped, or
    /// over.
    pub(crate) fn after_free(self, end: StepEnd) -> Result<AfterFree<'a, O>, SimError> {
        descend(self.run, self.rtol, self.atol3, end)
    }

    /// Whether the mass is changing where the flight stands (the motor burns or a part
    /// moves): the batch engine groups such lanes together, whose mass states it computes
    /// four at a time.
    #[inline]
    pub(crate) fn mass_changing(&self) -> bool {
        let t = self.time_s();
        !self.run.model.mass_settled(&self.run.starts, t)
    }

    /// The gust factor at the end of the step just taken on lanes (`None`: steady wind).
    #[inline(always)]
    pub(crate) fn end_gust(&self) -> Option<f64> {
        self.run.model.gust_at(self.s6.dopri().t())
    }

    /// [`PausedPhase::end_step`] with the step end's figures computed on lanes (for the
    /// center [`Paused::end_center`] gave).
    #[inline(always)]
    pub(crate) fn end_step_with(
        &mut self,
        outcome: StepOutcome,
        ep1: EndFigures,
    ) -> Result<Option<StepEnd>, SimError> {
        self.free
            .after_step(&mut self.run, &mut self.s6.stepper, outcome, Some(ep1))
    }

    /// The air brakes' drag coefficient as they stand (0: closed), for the step in progress.
    #[inline]
    pub(crate) fn brake_cd(&self) -> f64 {
        self.run.brake_cd
    }

    /// The mass state at `t` and its serial number (see [`Paused::mass_at`]) if nothing
    /// changes the mass then (the thrust is then 0), else `None`: the batch engine then
    /// computes it on lanes from [`FlightModel::mass_inputs_into`] at [`Paused::mass_key`].
    #[inline(always)]
    pub(crate) fn settled_mass(&mut self, t: f64) -> Option<(&MassLanes<f64>, u64)> {
        if !self.settle(t) {
            return None;
        }
        self.settled.as_ref().map(|(_, ms, serial)| (ms, *serial))
    }

    /// Whether nothing changes the mass at `t`; if so, `self.settled` holds its state.
    #[inline(always)]
    fn settle(&mut self, t: f64) -> bool {
        let model = self.run.model;
        let starts = &self.run.starts;
        let changes = self.run.starts_changed;
        // At or after a time from which on it is known settled (stages and steps move on),
        // no need to ask again.
        if !matches!(self.settled_from, Some((from, c)) if c == changes && t >= from) {
            if !model.mass_settled(starts, t) {
                return false;
            }
            if model.settled_from_now_on(starts, t) {
                self.settled_from = Some((t, changes));
            }
        }
        if !matches!(&self.settled, Some((c, _, _)) if *c == changes) {
            let ms = MassLanes::of(&model.instant(starts, t).mass);
            self.serial += 1;
            self.settled = Some((changes, ms, self.serial));
        }
        true
    }

    /// [`FlightModel::mass_inputs_into`] at `t` into lane `l` of `x`, for the batch engine:
    /// the motor curve's segment looked for first where the last stage found it.
    #[inline(always)]
    pub(crate) fn mass_inputs_into(
        &mut self,
        t: f64,
        x: &mut MassInputs<F64x4>,
        l: usize,
    ) -> MotorState {
        let model = self.run.model;
        let motor = model.motor.eval_hinted(t, &mut self.motor_segment);
        model.mass_inputs_with(motor, &self.run.starts, t, x, l)
    }

    /// The shifts' start times and the count of their changes (the mass state at a time is
    /// the same for the same count).
    #[inline(always)]
    pub(crate) fn mass_key(&self) -> (&ShiftStarts, u64) {
        (&self.run.starts, self.run.starts_changed)
    }

    /// The mass state (as the equations read it) and the thrust at `t`, and a serial number
    /// that changes whenever the mass state handed out does (so that a caller holding a
    /// copy knows when to refresh it). While the motor is out and no part moves it is
    /// computed once and kept (the same numbers `instant` gives).
    #[inline(always)]
    pub(crate) fn mass_at(&mut self, t: f64) -> (&MassLanes<f64>, f64, u64) {
        if self.settle(t) {
            if let Some((_, ms, serial)) = &self.settled {
                return (ms, 0.0, *serial);
            }
        }
        let model = self.run.model;
        let starts = &self.run.starts;
        // The step's last two stages share a time: the second reads the first's mass state.
        let key = (t.to_bits(), self.run.starts_changed);
        if self.moving_key != Some(key) {
            let (ms, thrust_n) = self.run.memo.computed(model, starts, key.1, t);
            self.moving = MassLanes::of(ms);
            self.moving_thrust_n = thrust_n;
            self.moving_key = Some(key);
            self.serial += 1;
        }
        (&self.moving, self.moving_thrust_n, self.serial)
    }
}

impl<'a, O: Observer> PausedPhase<'a, N6> for Paused<'a, O> {
    type End = StepEnd;

    fn model(&self) -> &'a FlightModel {
        self.run.model
    }

    fn step(&mut self) -> Result<Option<StepEnd>, SimError> {
        self.free.step(&mut self.run, &mut self.s6.stepper)
    }

    fn begin_step(&mut self) -> Result<bool, SimError> {
        if !self.s6.on_lanes() {
            return Ok(false);
        }
        let t_stop = self.free.next_stop(&mut self.run, &self.s6.stepper);
        let model = self.run.model;
        let starts = &self.run.starts;
        self.s6
            .begin(t_stop, &mut self.run.evaluations, |t, y, dy| {
                model.derivative_6dof(starts, t, y, dy);
            })?;
        Ok(true)
    }

    fn end_step(&mut self, outcome: StepOutcome) -> Result<Option<StepEnd>, SimError> {
        self.free
            .after_step(&mut self.run, &mut self.s6.stepper, outcome, None)
    }

    #[inline(always)]
    fn lanes(&self) -> &LaneStepper<N6> {
        &self.s6
    }

    #[inline(always)]
    fn lanes_mut(&mut self) -> (&mut LaneStepper<N6>, &mut u64) {
        (&mut self.s6, &mut self.run.evaluations)
    }
}
