//! Time integrators for fixed-size ODE states, shared by the single-flight simulator and the
//! structure-of-arrays batch engine.
//!
//! The state is a plain `[f64; N]` (const generic). The derivative is any closure
//! `FnMut(t, &y, &mut dydt)`, monomorphised (no trait objects). A *stepper* owns everything
//! one trajectory needs between steps (time, state, FSAL derivative, step-size memory and the
//! dense-output coefficients of the last step) so a batch engine keeps one stepper per lane,
//! each with its own time and step size. Nothing allocates after construction.
//!
//! - [`Dopri54`]: Dormand–Prince 5(4), adaptive, FSAL, with the 4th-order continuous extension.
//! - [`Rk4`]: classic fixed-step Runge–Kutta 4, cubic-Hermite dense output.
//! - [`Rodas4`]: RODAS4, a Rosenbrock method of order 4(3), L-stable, with its dense output:
//!   for a stiff phase (the descent under canopy), whose steps an explicit method would keep
//!   at its stability limit.
//! - [`roots`]: Brent's bracketing root finder, event location on the dense output.
//!
//! Every stepper implements [`DenseStepper`]. A step never crosses the `t_stop` given to
//! [`DenseStepper::step`]: the step that would cross it is shortened to land on it exactly
//! (`t == t_stop` bit for bit) and reports [`StepOutcome::ReachedStop`]. Drivers put motor
//! ignition/burnout, table breakpoints and output times there so no step straddles a
//! discontinuity. Integration runs forward in time only.
//!
//! Why hand-written rather than a crate: the available Rust ODE crates drive a whole
//! interval and collect results into vectors (allocation per run/step, no per-step control,
//! no stop times, dynamic state types); lanes of the batch engine need a small `Copy`-able
//! per-trajectory stepper over `[f64; N]` that steps one at a time.

pub mod dopri54;
pub mod rk4;
pub mod rodas4;
pub mod roots;

#[cfg(test)]
mod tests;

pub use dopri54::{Dopri54, StepControl};
pub use rk4::Rk4;
pub use rodas4::Rodas4;
pub use roots::{
    brent_root, brent_root_bracketed, locate_event, locate_maximum, Crossing, RootError,
    DEFAULT_TIME_TOL_S,
};

use thiserror::Error;

/// Smallest accepted relative tolerance.
pub const RTOL_MIN: f64 = 1e-14;
/// Largest accepted relative tolerance.
pub const RTOL_MAX: f64 = 1e-1;

/// What a successful [`DenseStepper::step`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepOutcome {
    /// An ordinary accepted step; `t < t_stop`.
    Internal,
    /// The step landed exactly on `t_stop`.
    ReachedStop,
}

/// Errors of the integrators.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum IntegratorError {
    /// Relative tolerance out of range.
    #[error(
        "integrator tolerance `rtol` = {value}: must be finite and within [{RTOL_MIN}, {RTOL_MAX}]"
    )]
    RelativeTolerance {
        /// The rejected value.
        value: f64,
    },
    /// Absolute tolerance of one component not finite and positive.
    #[error("integrator tolerance `atol[{index}]` = {value}: must be finite and > 0")]
    AbsoluteTolerance {
        /// State component.
        index: usize,
        /// The rejected value.
        value: f64,
    },
    /// A step-control or step-size setting out of range.
    #[error("integrator setting `{field}` = {value}: {rule}")]
    Setting {
        /// Name of the setting.
        field: &'static str,
        /// The rejected value.
        value: f64,
        /// The rule broken.
        rule: &'static str,
    },
    /// The adaptive step fell below the minimum: a discontinuity not marked by a stop time,
    /// a stiff problem, or a derivative returning NaN/∞.
    #[error(
        "step size underflow at t = {t} s: step {h} s is below the minimum {h_min} s \
         (discontinuity without a stop time, stiffness, or a non-finite derivative)"
    )]
    StepSizeUnderflow {
        /// Time of the step start, s.
        t: f64,
        /// The step that was too small, s.
        h: f64,
        /// The minimum in force there, s.
        h_min: f64,
    },
    /// The stepper made its most attempts ([`StepControl::max_steps`]) before its stop.
    #[error(
        "{steps} steps by t = {t} s without reaching the phase's end (the limit `max_steps`): \
         the steps collapsed (a force that chatters, or stiffness at these tolerances)"
    )]
    TooManySteps {
        /// Time of the step start, s.
        t: f64,
        /// The limit reached.
        steps: u64,
    },
    /// `t_stop` must be strictly after the current time (and not NaN).
    #[error("stop time {t_stop} s is not after the current time {t} s")]
    StopTimeNotAhead {
        /// Current time, s.
        t: f64,
        /// Requested stop, s.
        t_stop: f64,
    },
    /// The start time, a state component or its derivative is NaN or infinite.
    #[error("non-finite {what} at t = {t} s, component {index}: {value}")]
    NonFinite {
        /// "time", "state" or "derivative".
        what: &'static str,
        /// Time, s.
        t: f64,
        /// State component.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// `step` was called before `init`.
    #[error("the stepper was stepped before `init` gave it a state")]
    NotInitialized,
}

/// Error tolerances of an adaptive integrator: a relative tolerance and one absolute
/// tolerance per state component (in that component's units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances<const N: usize> {
    rtol: f64,
    atol: [f64; N],
}

impl<const N: usize> Tolerances<N> {
    /// `rtol` in [1e-14, 1e-1]; every `atol[i]` finite and > 0.
    pub fn new(rtol: f64, atol: [f64; N]) -> Result<Self, IntegratorError> {
        if !(RTOL_MIN..=RTOL_MAX).contains(&rtol) {
            return Err(IntegratorError::RelativeTolerance { value: rtol });
        }
        for (index, &value) in atol.iter().enumerate() {
            if !(value.is_finite() && value > 0.0) {
                return Err(IntegratorError::AbsoluteTolerance { index, value });
            }
        }
        Ok(Self { rtol, atol })
    }

    /// The same absolute tolerance for every component.
    pub fn uniform(rtol: f64, atol: f64) -> Result<Self, IntegratorError> {
        Self::new(rtol, [atol; N])
    }

    /// Relative tolerance.
    pub fn rtol(&self) -> f64 {
        self.rtol
    }

    /// Absolute tolerances.
    pub fn atol(&self) -> &[f64; N] {
        &self.atol
    }
}

/// The interface a driver uses: one trajectory, stepped one accepted step at a time, with
/// dense output over the last step. Statically dispatched (the methods are generic over the
/// derivative closure, so the trait is not object-safe by design).
pub trait DenseStepper<const N: usize> {
    /// Start (or start afresh) at `(t0, y0)`: evaluates the derivative once and forgets any
    /// step-size history. Before the first step `t_prev == t` and `dense` returns `y`.
    fn init<F>(&mut self, f: F, t0: f64, y0: &[f64; N]) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]);

    /// Continue from a new state `(t, y)` (after an event changed the state or the
    /// derivative) keeping the step-size memory. Evaluates the derivative once.
    fn restart<F>(&mut self, f: F, t: f64, y: &[f64; N]) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]);

    /// Take one accepted step, never past `t_stop` (> `t`; may be `f64::INFINITY`).
    /// Rejected attempts are retried inside.
    fn step<F>(&mut self, f: F, t_stop: f64) -> Result<StepOutcome, IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]);

    /// Time at the end of the last accepted step, s.
    fn t(&self) -> f64;
    /// Time at the start of the last accepted step, s.
    fn t_prev(&self) -> f64;
    /// State at `t`.
    fn y(&self) -> &[f64; N];
    /// State at `t_prev`.
    fn y_prev(&self) -> &[f64; N];
    /// Derivative at `(t, y)` (first stage of the next step).
    fn dy(&self) -> &[f64; N];
    /// Dense output at `t_between` ∈ [`t_prev`, `t`] (outside it the polynomial is
    /// extrapolated, with no accuracy guarantee). Exact at both ends. By default each
    /// component's [`DenseStepper::dense_component`].
    fn dense(&self, t_between: f64) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.dense_component(t_between, i);
        }
        out
    }
    /// One component of the dense output. Panics if `index >= N`.
    fn dense_component(&self, t_between: f64, index: usize) -> f64;
    /// Derivative evaluations so far (since construction).
    fn n_eval(&self) -> u64;
}

/// First non-finite entry of `v`, if any.
pub(crate) fn check_finite<const N: usize>(
    what: &'static str,
    t: f64,
    v: &[f64; N],
) -> Result<(), IntegratorError> {
    if !t.is_finite() {
        return Err(IntegratorError::NonFinite {
            what: "time",
            t,
            index: 0,
            value: t,
        });
    }
    match v.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(IntegratorError::NonFinite {
            what,
            t,
            index,
            value: v[index],
        }),
        None => Ok(()),
    }
}

/// Step of a stepper at `t` toward `t_stop` with proposal `h`: returns `(h, last)` where
/// `last` means the step lands on `t_stop`. A step within 1 % of `t_stop` is stretched to it
/// rather than leaving a sliver step (Hairer's rule).
#[inline]
pub(crate) fn clip_to_stop(t: f64, h: f64, t_stop: f64) -> (f64, bool) {
    if t + 1.01 * h >= t_stop {
        (t_stop - t, true)
    } else {
        (h, false)
    }
}

/// How far an attempt from `t` with proposal `h` toward `t_stop` may reach: `t_stop` where
/// [`clip_to_stop`] clips it there, else `t + 1.01 h`, the sum that test compares with the
/// stop (a trajectory whose stop is later than this takes the same attempt).
#[inline]
pub(crate) fn attempt_reach(t: f64, h: f64, t_stop: f64) -> f64 {
    if clip_to_stop(t, h, t_stop).1 {
        t_stop
    } else {
        t + 1.01 * h
    }
}

/// Hairer's starting step (HNW I, §II.4) from `(t, y)` with derivative `dy`: a step such that
/// an explicit Euler step would make an error of about 1 % of the tolerance, refined by a
/// second-derivative estimate from one more evaluation of `f` (the caller counts it), never
/// past `t_stop` nor `h_max`. `exponent` is 1/(q+1), q the order of the method's error
/// estimate (1/5 for Dormand–Prince 5(4), 1/4 for RODAS4's order-3 estimate).
#[allow(clippy::too_many_arguments)]
pub(crate) fn starting_step<const N: usize, F>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    dy: &[f64; N],
    tol: &Tolerances<N>,
    exponent: f64,
    h_max: f64,
    t_stop: f64,
) -> f64
where
    F: FnMut(f64, &[f64; N], &mut [f64; N]),
{
    let rms = |v: &[f64; N]| {
        let mut sum = 0.0;
        for i in 0..N {
            let q = v[i] / (tol.atol[i] + tol.rtol * y[i].abs());
            sum += q * q;
        }
        (sum / N as f64).sqrt()
    };
    let (d0, d1) = (rms(y), rms(dy));
    let mut h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    h0 = h0.min(h_max).min(t_stop - t);
    let mut y1 = [0.0; N];
    for (i, v) in y1.iter_mut().enumerate() {
        *v = y[i] + h0 * dy[i];
    }
    let mut f1 = [0.0; N];
    f(t + h0, &y1, &mut f1);
    let mut diff = [0.0; N];
    for i in 0..N {
        diff[i] = f1[i] - dy[i];
    }
    let d2 = rms(&diff) / h0;
    let d12 = d1.max(d2);
    let h1 = if d12.is_nan() || d12 <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d12).powf(exponent)
    };
    (100.0 * h0).min(h1).min(h_max)
}
