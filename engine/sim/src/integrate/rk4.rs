//! Classic fixed-step Runge–Kutta 4 with the same stepper interface as [`super::Dopri54`].
//!
//! Every step has the configured size `h` except the one that would cross `t_stop`, which is
//! shortened to land on it exactly; a step that would end within 1 % of `t_stop` is stretched
//! onto it instead of leaving a sliver step. The derivative at the end of each step is
//! evaluated (it is the first stage of the next step, so a step costs 4 evaluations) and the
//! dense output is the cubic Hermite interpolant of the end values and derivatives
//! (local error O(h⁴) inside the step, exact at both ends).

use super::{check_finite, clip_to_stop, DenseStepper, IntegratorError, StepOutcome};

/// Fixed-step RK4 stepper for one trajectory of `N` states.
#[derive(Debug, Clone)]
pub struct Rk4<const N: usize> {
    h: f64,
    t: f64,
    t_prev: f64,
    y: [f64; N],
    y_prev: [f64; N],
    dy: [f64; N],
    dy_prev: [f64; N],
    n_eval: u64,
    initialized: bool,
}

impl<const N: usize> Rk4<N> {
    /// A stepper of step `h_s` seconds (finite, > 0).
    pub fn new(h_s: f64) -> Result<Self, IntegratorError> {
        if !(h_s.is_finite() && h_s > 0.0) {
            return Err(IntegratorError::Setting {
                field: "h",
                value: h_s,
                rule: "the RK4 step must be finite and > 0",
            });
        }
        Ok(Self {
            h: h_s,
            t: 0.0,
            t_prev: 0.0,
            y: [0.0; N],
            y_prev: [0.0; N],
            dy: [0.0; N],
            dy_prev: [0.0; N],
            n_eval: 0,
            initialized: false,
        })
    }

    /// The configured step, s.
    pub fn h(&self) -> f64 {
        self.h
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
        self.dy_prev = dy;
        self.initialized = true;
        Ok(())
    }
}

impl<const N: usize> DenseStepper<N> for Rk4<N> {
    fn init<F>(&mut self, mut f: F, t0: f64, y0: &[f64; N]) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        self.initialized = false;
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
        if !self.initialized {
            return Err(IntegratorError::NotInitialized);
        }
        if t_stop.is_nan() || t_stop <= self.t {
            return Err(IntegratorError::StopTimeNotAhead { t: self.t, t_stop });
        }
        let (h, last) = clip_to_stop(self.t, self.h, t_stop);
        let t = self.t;
        let t_end = if last { t_stop } else { t + h };
        let y = self.y;
        let k1 = self.dy;
        let (mut k2, mut k3, mut k4) = ([0.0; N], [0.0; N], [0.0; N]);
        let mut ys = [0.0; N];
        for i in 0..N {
            ys[i] = y[i] + 0.5 * h * k1[i];
        }
        f(t + 0.5 * h, &ys, &mut k2);
        for i in 0..N {
            ys[i] = y[i] + 0.5 * h * k2[i];
        }
        f(t + 0.5 * h, &ys, &mut k3);
        for i in 0..N {
            ys[i] = y[i] + h * k3[i];
        }
        f(t_end, &ys, &mut k4);
        let mut y_new = [0.0; N];
        for i in 0..N {
            y_new[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
        }
        let mut dy_new = [0.0; N];
        f(t_end, &y_new, &mut dy_new);
        self.n_eval += 4;
        self.t_prev = t;
        self.y_prev = y;
        self.dy_prev = k1;
        self.t = t_end;
        self.y = y_new;
        self.dy = dy_new;
        Ok(if last {
            StepOutcome::ReachedStop
        } else {
            StepOutcome::Internal
        })
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

    fn dense_component(&self, t_between: f64, i: usize) -> f64 {
        if t_between == self.t {
            return self.y[i];
        }
        if t_between == self.t_prev {
            return self.y_prev[i];
        }
        let h = self.t - self.t_prev;
        let s = (t_between - self.t_prev) / h;
        let s2 = s * s;
        let s3 = s2 * s;
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h10 = s3 - 2.0 * s2 + s;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h11 = s3 - s2;
        h00 * self.y_prev[i] + h * (h10 * self.dy_prev[i] + h11 * self.dy[i]) + h01 * self.y[i]
    }

    fn n_eval(&self) -> u64 {
        self.n_eval
    }
}
