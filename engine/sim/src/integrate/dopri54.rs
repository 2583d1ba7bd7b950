//! Dormand–Prince 5(4) with FSAL, per-component error control, a PI step-size controller,
//! Hairer's starting-step estimate and Shampine's 4th-order continuous extension.
//!
//! References: J. R. Dormand, P. J. Prince, "A family of embedded Runge–Kutta formulae",
//! J. Comput. Appl. Math. 6 (1980) 19–26 (tableau); L. F. Shampine, "Some practical
//! Runge–Kutta formulas", Math. Comp. 46 (1986) 135–150 (dense output); E. Hairer,
//! S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., Springer
//! 1993, §II.4 (error norm, starting step), §II.5 (dense output), §IV.2 (PI control, as in
//! their code DOPRI5).
//!
//! Error norm: `err = sqrt(mean_i (e_i / (atol_i + rtol·max(|y_i|, |y_new_i|)))²)`, with `e`
//! the difference of the 5th- and 4th-order solutions; a step is accepted when `err <= 1` and
//! the 5th-order solution is kept (local extrapolation).
//!
//! Step-size control (defaults in [`StepControl::default`], DOPRI5's): after an accepted step
//! `h_new = h · clamp(safety · err^{-α} · err_prev^{β}, min_factor, max_factor)` with
//! `α = 1/5 − 0.75 β`, `β = 0.04`, `safety = 0.9`, `min_factor = 0.2`, `max_factor = 10`,
//! `err_prev = max(err of the last accepted step, 1e-4)`; right after a rejection the step may
//! not grow. After a rejection `h_new = h · max(min_factor, safety · err^{-α})` (a NaN error
//! counts as a rejection with `min_factor`). A step clipped to land on a stop time does not
//! shrink the proposal for the next one. The factor is computed as
//! `safety · exp(β ln err_prev − α ln err)`, with `ln err_prev` kept from the last step: one
//! logarithm and one exponential a step where two powers cost 4 % of the batch's instructions
//! (`lanes::ln` and `lanes::exp`, written over lanes, so that the batch computes four
//! attempts' factors at once: [`growth`], [`shrinkage`]).

use super::{check_finite, clip_to_stop, DenseStepper, IntegratorError, StepOutcome, Tolerances};
use crate::lanes::{ln, F64x4};

pub mod arithmetic;
pub use arithmetic::{growth, shrinkage, stage_time};

// Butcher tableau (c_i, a_ij), 5th-order weights b = a7j (FSAL), error weights e = b − b̂.
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
/// `ln 1e-4`: the floor of the previous step's error norm in the PI controller.
pub(crate) const LN_ERR_FLOOR: f64 = -9.210_340_371_976_182;

// Shampine's dense-output coefficients.
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// Settings of the step-size controller. All validated by [`Dopri54::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepControl {
    /// Safety factor on the optimal step, in (0, 1). Default 0.9.
    pub safety: f64,
    /// PI exponent β on the previous error, in [0, 0.2]. Default 0.04 (0 = pure I control).
    pub beta: f64,
    /// Smallest ratio h_new / h, in (0, 1). Default 0.2.
    pub min_factor: f64,
    /// Largest ratio h_new / h, finite and > 1. Default 10.
    pub max_factor: f64,
    /// Absolute minimum step, s (≥ 0). Default 0: only the relative floor `10·ε·|t|` applies.
    /// A step forced below `max(h_min, 10·ε·|t|)` is [`IntegratorError::StepSizeUnderflow`]
    /// (steps shortened to land on a stop time are exempt).
    pub h_min: f64,
    /// Largest step, s (> `h_min`, may be ∞). Default ∞.
    pub h_max: f64,
    /// First step, s; 0 (default) = Hairer's estimate from the derivative.
    pub h_initial: f64,
    /// Most attempts (accepted and rejected steps) one stepper may make of its own choosing,
    /// ≥ 1: the accepted steps that end on a stop time are not counted, since the input
    /// set them (a thrust curve's samples, an air-brake controller's), so a stepper makes at
    /// most `max_steps` attempts plus one per stop time it is given. Default 100,000, some
    /// 300 times a whole flight's steps at the default tolerances: a flight whose steps
    /// collapse without quite underflowing (a chattering force) ends with
    /// [`IntegratorError::TooManySteps`] instead of running for hours.
    pub max_steps: u64,
}

impl Default for StepControl {
    fn default() -> Self {
        Self {
            safety: 0.9,
            beta: 0.04,
            min_factor: 0.2,
            max_factor: 10.0,
            h_min: 0.0,
            h_max: f64::INFINITY,
            h_initial: 0.0,
            max_steps: 100_000,
        }
    }
}

impl StepControl {
    /// Check every setting against its documented range.
    pub fn validate(&self) -> Result<(), IntegratorError> {
        let bad = |field, value, rule| Err(IntegratorError::Setting { field, value, rule });
        if !(self.safety > 0.0 && self.safety < 1.0) {
            return bad("safety", self.safety, "must lie in (0, 1)");
        }
        if !(0.0..=0.2).contains(&self.beta) {
            return bad("beta", self.beta, "must lie in [0, 0.2]");
        }
        if !(self.min_factor > 0.0 && self.min_factor < 1.0) {
            return bad("min_factor", self.min_factor, "must lie in (0, 1)");
        }
        if !(self.max_factor.is_finite() && self.max_factor > 1.0) {
            return bad("max_factor", self.max_factor, "must be finite and > 1");
        }
        if !(self.h_min.is_finite() && self.h_min >= 0.0) {
            return bad("h_min", self.h_min, "must be finite and >= 0");
        }
        if self.h_max.is_nan() || self.h_max <= self.h_min {
            return bad("h_max", self.h_max, "must be > h_min (infinity allowed)");
        }
        if !(self.h_initial.is_finite() && self.h_initial >= 0.0) {
            return bad(
                "h_initial",
                self.h_initial,
                "must be finite and >= 0 (0 = estimate)",
            );
        }
        if self.max_steps == 0 {
            return bad("max_steps", 0.0, "must be at least 1");
        }
        Ok(())
    }
}

/// Adaptive Dormand–Prince 5(4) stepper for one trajectory of `N` states.
#[derive(Debug, Clone)]
pub struct Dopri54<const N: usize> {
    tol: Tolerances<N>,
    control: StepControl,
    t: f64,
    t_prev: f64,
    y: [f64; N],
    y_prev: [f64; N],
    dy: [f64; N],
    /// Dense output: `y(θ) = y_prev + θ(c0 + (1−θ)(c1 + θ(c2 + (1−θ)c3)))`.
    cont: [[f64; N]; 4],
    /// Proposal for the next step; 0 = estimate it.
    h_next: f64,
    /// Logarithm of the error norm of the last accepted step (that norm ≥ 1e-4), for the PI
    /// controller.
    ln_err_prev: f64,
    n_eval: u64,
    n_accepted: u64,
    n_rejected: u64,
    /// Accepted steps that ended on their stop time (not counted against `max_steps`).
    n_on_stop: u64,
    /// The latest time any attempt so far was allowed to reach, s: its stop time where the
    /// attempt was clipped to it, else `t + 1.01 h`, the sum [`super::clip_to_stop`] compares
    /// with the stop time. Another trajectory of the same derivative up to this time whose
    /// stop times differ only at or after it took exactly the same attempts ([`Dopri54::reach`]).
    reach: f64,
    initialized: bool,
    /// The step in progress (see [`Dopri54::begin_step`]).
    cur: Attempt<N>,
}

/// A step in progress: its stages are evaluated one at a time, so that a driver may evaluate
/// the same stage of many trajectories together.
#[derive(Debug, Clone)]
struct Attempt<const N: usize> {
    t_stop: f64,
    /// Step size of this attempt, the proposal it was clipped from, and whether it ends on
    /// the stop time.
    h: f64,
    h_proposal: f64,
    last: bool,
    t_end: f64,
    /// Whether an attempt of this step was rejected already.
    rejected: bool,
    /// Stages k2..k7 (k1 is the derivative at the start).
    k: [[f64; N]; 6],
    /// Next stage to evaluate, 0..6 for k2..k7.
    stage: usize,
    /// Its time and state.
    t_stage: f64,
    y_stage: [f64; N],
}

impl<const N: usize> Dopri54<N> {
    /// A stepper with tolerances `tol` and controller settings `control` (validated).
    pub fn new(tol: Tolerances<N>, control: StepControl) -> Result<Self, IntegratorError> {
        control.validate()?;
        Ok(Self {
            tol,
            control,
            t: 0.0,
            t_prev: 0.0,
            y: [0.0; N],
            y_prev: [0.0; N],
            dy: [0.0; N],
            cont: [[0.0; N]; 4],
            h_next: 0.0,
            ln_err_prev: LN_ERR_FLOOR,
            n_eval: 0,
            n_accepted: 0,
            n_rejected: 0,
            n_on_stop: 0,
            reach: f64::NEG_INFINITY,
            initialized: false,
            cur: Attempt {
                t_stop: 0.0,
                h: 0.0,
                h_proposal: 0.0,
                last: false,
                t_end: 0.0,
                rejected: false,
                k: [[0.0; N]; 6],
                stage: 0,
                t_stage: 0.0,
                y_stage: [0.0; N],
            },
        })
    }

    /// A stepper with tolerances `tol` and the default controller.
    pub fn with_tolerances(tol: Tolerances<N>) -> Self {
        Self::new(tol, StepControl::default()).expect("the default step control is valid")
    }

    /// The tolerances in force.
    pub fn tolerances(&self) -> &Tolerances<N> {
        &self.tol
    }

    /// The controller settings in force.
    pub fn control(&self) -> &StepControl {
        &self.control
    }

    /// Step size the next `step` will try first (0 before the first step after `init`).
    pub fn h_next(&self) -> f64 {
        self.h_next
    }

    /// Accepted steps so far.
    pub fn n_accepted(&self) -> u64 {
        self.n_accepted
    }

    /// Rejected attempts so far.
    pub fn n_rejected(&self) -> u64 {
        self.n_rejected
    }

    /// The latest time any attempt so far was allowed to reach, s (`-inf` before the first):
    /// the attempt's stop time where it was clipped to it, else `t + 1.01 h`. Two
    /// trajectories with the same derivative before this time, the same state, the same
    /// stepper and the same stop times before it took the same attempts, bit for bit, however
    /// their stop times at or after it differ: no attempt of either reached a stop there.
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// How far the first attempt of the next step toward `t_stop` may reach (what it would
    /// add to [`Dopri54::reach`]), or `None` where its size is yet to be estimated (the
    /// estimate reads the stop).
    pub fn next_reach(&self, t_stop: f64) -> Option<f64> {
        (self.h_next > 0.0)
            .then(|| super::attempt_reach(self.t, self.h_next.min(self.control.h_max), t_stop))
    }

    fn set_state<F>(&mut self, f: &mut F, t: f64, y: &[f64; N]) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        check_finite("state", t, y)?;
        let mut dy = [0.0; N];
        f(t, y, &mut dy);
        self.n_eval += 1;
        check_finite("derivative", t, &dy)?;
        self.t = t;
        self.t_prev = t;
        self.y = *y;
        self.y_prev = *y;
        self.dy = dy;
        self.cont = [[0.0; N]; 4];
        self.initialized = true;
        Ok(())
    }

    /// Hairer's starting step ([`super::starting_step`]), unless the controller gives one.
    fn initial_step<F>(&mut self, f: &mut F, t_stop: f64) -> f64
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        if self.control.h_initial > 0.0 {
            return self.control.h_initial;
        }
        self.n_eval += 1;
        super::starting_step(
            f,
            self.t,
            &self.y,
            &self.dy,
            &self.tol,
            1.0 / 5.0,
            self.control.h_max,
            t_stop,
        )
    }
}

impl<const N: usize> Dopri54<N> {
    /// Start a step that will not pass `t_stop` (`f` is called only for the starting-step
    /// estimate of a first step). Then evaluate the derivative at [`Dopri54::stage_input`]
    /// and hand it to [`Dopri54::feed_stage`] until that reports the step done: this is
    /// [`DenseStepper::step`] one stage at a time, the same arithmetic in the same order.
    pub fn begin_step<F>(&mut self, f: &mut F, t_stop: f64) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        self.begin_step_outside(f, t_stop)?;
        self.prepare_stage();
        Ok(())
    }

    /// [`Dopri54::begin_step`] for a driver that does the stages' arithmetic itself, with
    /// the functions of [`arithmetic`] (the batch engine, on four lanes at once): the step
    /// is set up and clipped, and no stage state is computed here. The driver then reads
    /// [`Dopri54::attempt_step`] and [`Dopri54::stage_time`], and ends each attempt with
    /// [`Dopri54::judge`] (and [`Dopri54::commit`] when it is accepted).
    pub fn begin_step_outside<F>(&mut self, f: &mut F, t_stop: f64) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        if !self.initialized {
            return Err(IntegratorError::NotInitialized);
        }
        if t_stop.is_nan() || t_stop <= self.t {
            return Err(IntegratorError::StopTimeNotAhead { t: self.t, t_stop });
        }
        let h = if self.h_next > 0.0 {
            self.h_next
        } else {
            // The starting step's estimate reads the stop time (it is clipped to it), so
            // the stop counts as reached.
            self.reach = self.reach.max(t_stop);
            self.initial_step(f, t_stop)
        };
        self.cur.t_stop = t_stop;
        self.cur.h = h;
        self.cur.rejected = false;
        self.begin_attempt()
    }

    /// Clip the attempt's step to the stop time (its first stage is then stage 0).
    #[inline(always)]
    fn begin_attempt(&mut self) -> Result<(), IntegratorError> {
        let c = self.control;
        let t = self.t;
        let a = &mut self.cur;
        a.h_proposal = a.h.min(c.h_max);
        let (h, last) = clip_to_stop(t, a.h_proposal, a.t_stop);
        a.h = h;
        a.last = last;
        self.reach = self
            .reach
            .max(super::attempt_reach(t, a.h_proposal, a.t_stop));
        if self.n_accepted + self.n_rejected - self.n_on_stop >= c.max_steps {
            return Err(IntegratorError::TooManySteps {
                t,
                steps: c.max_steps,
            });
        }
        let h_floor = c.h_min.max(10.0 * f64::EPSILON * t.abs());
        if !last && (h.is_nan() || h < h_floor || h <= 0.0) {
            return Err(IntegratorError::StepSizeUnderflow {
                t,
                h,
                h_min: h_floor,
            });
        }
        a.t_end = if last { a.t_stop } else { t + h };
        a.stage = 0;
        Ok(())
    }

    /// Step size of the attempt in progress, s.
    #[inline(always)]
    pub fn attempt_step(&self) -> f64 {
        self.cur.h
    }

    /// The logarithm of the last accepted attempt's error norm (floored), which the
    /// controller's [`growth`] reads.
    #[inline(always)]
    pub fn ln_err_prev(&self) -> f64 {
        self.ln_err_prev
    }

    /// Where the attempt in progress ends, s.
    #[inline(always)]
    pub fn attempt_end(&self) -> f64 {
        self.cur.t_end
    }

    /// Time of stage `stage` (0..6 for k2..k7) of the attempt in progress.
    #[inline(always)]
    pub fn stage_time(&self, stage: usize) -> f64 {
        stage_time(stage, self.t, self.cur.h, self.cur.t_end)
    }

    /// The time and state of the stage `cur.stage` from the stages before it.
    #[inline(always)]
    fn prepare_stage(&mut self) {
        let t_stage = self.stage_time(self.cur.stage);
        let a = &mut self.cur;
        arithmetic::stage_state(a.stage, a.h, &self.y, &self.dy, &a.k, &mut a.y_stage);
        a.t_stage = t_stage;
    }

    /// Where the step in progress needs the derivative next.
    #[inline]
    pub fn stage_input(&self) -> (f64, &[f64; N]) {
        (self.cur.t_stage, &self.cur.y_stage)
    }

    /// Hand over the derivative at [`Dopri54::stage_input`]. Returns the step's outcome once
    /// its last stage is in and the step is accepted; `None` while it needs more stages
    /// (including a new attempt after a rejection).
    #[inline(always)]
    pub fn feed_stage(&mut self, dy: &[f64; N]) -> Result<Option<StepOutcome>, IntegratorError> {
        self.n_eval += 1;
        let st = self.cur.stage;
        self.cur.k[st] = *dy;
        if st < 5 {
            self.cur.stage = st + 1;
            self.prepare_stage();
            return Ok(None);
        }
        let a = &self.cur;
        let sum = arithmetic::error_sum(
            a.h,
            &self.y,
            &a.y_stage,
            &self.dy,
            &a.k,
            &self.tol.atol,
            self.tol.rtol,
        );
        let err = (sum / N as f64).sqrt();
        match self.judge(err, 0)? {
            Some(outcome) => {
                let a = &self.cur;
                let mut cont = [[0.0; N]; 4];
                arithmetic::dense_coefficients(a.h, &self.y, &a.y_stage, &self.dy, &a.k, &mut cont);
                let (y_new, k7) = (a.y_stage, a.k[5]);
                self.commit(&y_new, &k7, &cont);
                Ok(Some(outcome))
            }
            None => {
                self.prepare_stage();
                Ok(None)
            }
        }
    }

    /// The verdict on the attempt in progress once its last stage is in, from its error norm
    /// `err` (`stages` derivative evaluations done outside [`Dopri54::feed_stage`] are added
    /// to the count). Accepted: the controller's next step is set and the outcome returned;
    /// the caller then hands the new state to [`Dopri54::commit`]. Rejected: the next attempt
    /// is set up (smaller step, clipped) and `None` returned.
    #[inline(always)]
    pub fn judge(&mut self, err: f64, stages: u64) -> Result<Option<StepOutcome>, IntegratorError> {
        let ln_err = ln(err);
        let (beta, ln_err_prev) = (self.control.beta, self.ln_err_prev);
        self.judge_given(
            err,
            ln_err,
            || growth(beta, ln_err_prev, ln_err),
            || shrinkage(beta, ln_err),
            stages,
        )
    }

    /// [`Dopri54::judge`] given the error norm's logarithm and the controller's factors
    /// ([`growth`], called if the attempt is accepted, and [`shrinkage`], if not): the batch
    /// engine computes them for four attempts at once, by the same functions.
    #[inline(always)]
    pub fn judge_given(
        &mut self,
        err: f64,
        ln_err: f64,
        growth: impl FnOnce() -> f64,
        shrinkage: impl FnOnce() -> f64,
        stages: u64,
    ) -> Result<Option<StepOutcome>, IntegratorError> {
        self.n_eval += stages;
        let c = self.control;
        let a = &self.cur;
        let (h, h_proposal, last) = (a.h, a.h_proposal, a.last);
        if err <= 1.0 {
            let fac = (c.safety * growth()).clamp(c.min_factor, c.max_factor);
            let mut h_new = h * fac;
            if a.rejected {
                h_new = h_new.min(h);
            }
            if last && h < h_proposal {
                h_new = h_new.max(h_proposal);
            }
            self.ln_err_prev = ln_err.max(LN_ERR_FLOOR);
            self.h_next = h_new;
            self.n_accepted += 1;
            self.n_on_stop += u64::from(last);
            return Ok(Some(if last {
                StepOutcome::ReachedStop
            } else {
                StepOutcome::Internal
            }));
        }
        // Rejected (a NaN error lands here too, and `min` then picks 1/min_factor).
        self.n_rejected += 1;
        self.cur.rejected = true;
        let fac_err = shrinkage();
        self.cur.h = h / (1.0 / c.min_factor).min(fac_err / c.safety);
        self.begin_attempt()?;
        Ok(None)
    }

    /// Move to the end of the step [`Dopri54::judge`] accepted: its state `y_new`, the
    /// derivative there `k7` (FSAL) and the step's dense-output coefficients.
    #[inline(always)]
    pub fn commit(&mut self, y_new: &[f64; N], k7: &[f64; N], cont: &[[f64; N]; 4]) {
        self.commit_from(|i| y_new[i], |i| k7[i], |j, i| cont[j][i]);
    }

    /// [`Dopri54::commit`] from lane `l` of four attempts held side by side (the batch
    /// engine's), copied straight into place.
    #[inline(always)]
    pub fn commit_lane(
        &mut self,
        l: usize,
        y_new: &[F64x4; N],
        k7: &[F64x4; N],
        cont: &[[F64x4; N]; 4],
    ) {
        self.commit_from(|i| y_new[i].0[l], |i| k7[i].0[l], |j, i| cont[j][i].0[l]);
    }

    /// The commit itself, each number read where it stands.
    #[inline(always)]
    fn commit_from(
        &mut self,
        y_new: impl Fn(usize) -> f64,
        k7: impl Fn(usize) -> f64,
        cont: impl Fn(usize, usize) -> f64,
    ) {
        for (j, c) in self.cont.iter_mut().enumerate() {
            for (i, c) in c.iter_mut().enumerate() {
                *c = cont(j, i);
            }
        }
        for (i, d) in self.dy.iter_mut().enumerate() {
            *d = k7(i);
        }
        self.t_prev = self.t;
        self.y_prev = self.y;
        self.t = self.cur.t_end;
        for (i, y) in self.y.iter_mut().enumerate() {
            *y = y_new(i);
        }
    }
}

impl<const N: usize> DenseStepper<N> for Dopri54<N> {
    fn init<F>(&mut self, mut f: F, t0: f64, y0: &[f64; N]) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        self.initialized = false;
        self.h_next = 0.0;
        self.ln_err_prev = LN_ERR_FLOOR;
        self.set_state(&mut f, t0, y0)
    }

    fn restart<F>(&mut self, mut f: F, t: f64, y: &[f64; N]) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        self.set_state(&mut f, t, y)
    }

    fn step<F>(&mut self, mut f: F, t_stop: f64) -> Result<StepOutcome, IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        self.begin_step(&mut f, t_stop)?;
        let mut dy = [0.0; N];
        loop {
            let (t, y) = self.stage_input();
            f(t, y, &mut dy);
            if let Some(outcome) = self.feed_stage(&dy)? {
                return Ok(outcome);
            }
        }
    }

    fn t(&self) -> f64 {
        self.t
    }

    fn t_prev(&self) -> f64 {
        self.t_prev
    }

    fn y(&self) -> &[f64; N] {
        &self.y
    }

    fn y_prev(&self) -> &[f64; N] {
        &self.y_prev
    }

    fn dy(&self) -> &[f64; N] {
        &self.dy
    }

    fn dense(&self, t_between: f64) -> [f64; N] {
        if t_between == self.t {
            return self.y;
        }
        if t_between == self.t_prev {
            return self.y_prev;
        }
        let s = (t_between - self.t_prev) / (self.t - self.t_prev);
        let s1 = 1.0 - s;
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.y_prev[i]
                + s * (self.cont[0][i]
                    + s1 * (self.cont[1][i] + s * (self.cont[2][i] + s1 * self.cont[3][i])));
        }
        out
    }

    fn dense_component(&self, t_between: f64, i: usize) -> f64 {
        if t_between == self.t {
            return self.y[i];
        }
        if t_between == self.t_prev {
            return self.y_prev[i];
        }
        let s = (t_between - self.t_prev) / (self.t - self.t_prev);
        let s1 = 1.0 - s;
        self.y_prev[i]
            + s * (self.cont[0][i]
                + s1 * (self.cont[1][i] + s * (self.cont[2][i] + s1 * self.cont[3][i])))
    }

    fn n_eval(&self) -> u64 {
        self.n_eval
    }
}
