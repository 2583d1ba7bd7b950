//! RODAS4: a Rosenbrock method of order 4 with an embedded method of order 3, L-stable and
//! stiffly accurate, with its order-3 dense output, for problems whose step an explicit method
//! would have to keep below its stability limit rather than where its accuracy puts it.
//!
//! References: E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, 2nd ed.,
//! Springer 1996, §IV.7 (the method, its coefficients as in their code RODAS, the
//! implementation form (7.25) below, the dense output); the same coefficients are in
//! OrdinaryDiffEq.jl's `Rodas4Tableau`.
//!
//! A step from `(t₀, y₀)` of size `h` solves six linear systems with the one matrix
//! `W = I/(γh) − J`, `J = ∂f/∂y` at `(t₀, y₀)`:
//!
//! `W kᵢ = f(t₀ + αᵢh, y₀ + Σⱼ aᵢⱼ kⱼ) + dᵢ h ∂f/∂t + Σⱼ (Cᵢⱼ / h) kⱼ`,
//!
//! `y₁ = y₀ + Σⱼ a₆ⱼ kⱼ + k₆` (stiffly accurate: the last two stages sit at `t₀ + h`), and the
//! embedded order-3 solution is `y₁ − k₆`, so `k₆` is the local error estimate. The dense
//! output over the step is `y(θ) = (1 − θ) y₀ + θ (y₁ + (1 − θ)(q₁ + θ q₂))` with `q₁`, `q₂`
//! fixed combinations of `k₁..k₅`, exact at both ends.
//!
//! The Jacobian and `∂f/∂t` are taken once a step (a rejected attempt reuses them): given by
//! the caller ([`Rodas4::step_with`], what it knows in closed form and differences of the
//! rest), or, through [`DenseStepper::step`], by forward differences of the derivative
//! alone ([`difference_jacobian`], `N + 1` more evaluations). The method's order needs `J`
//! itself; differences carry an error near `√ε` of it, which moves a step by far less than
//! its tolerance but does tie the result to that rounding (a caller that wants two inputs
//! equal to rounding to fly equal to rounding gives `J` in closed form). `W` is factored by
//! Gaussian elimination with partial pivoting.
//!
//! Error norm and control: the norm is [`super::dopri54`]'s (`atol_i + rtol·max(|y₀ᵢ|, |y₁ᵢ|)`
//! scales each component of `k₆`); the step grows or shrinks by
//! `clamp(safety · err^{-1/4}, min_factor, max_factor)`, not above 1 right after a
//! rejection, and a step clipped onto a stop time does not shrink the proposal for the next.
//! [`StepControl`]'s bounds (`h_min`, `h_max`, `h_initial`, `max_steps`) mean what they mean
//! for [`super::Dopri54`].

use super::dopri54::StepControl;
use super::{check_finite, clip_to_stop, DenseStepper, IntegratorError, StepOutcome, Tolerances};

const GAMMA: f64 = 0.25;
const A21: f64 = 1.544;
const A31: f64 = 0.946_678_528_081_582_6;
const A32: f64 = 0.255_701_169_898_328_4;
const A41: f64 = 3.314_825_187_068_521;
const A42: f64 = 2.896_124_015_972_201;
const A43: f64 = 0.998_641_913_997_781_7;
const A51: f64 = 1.221_224_509_226_641;
const A52: f64 = 6.019_134_481_288_629;
const A53: f64 = 12.537_083_329_320_87;
const A54: f64 = -0.687_886_036_105_895;
const C21: f64 = -5.6688;
const C31: f64 = -2.430_093_356_833_875;
const C32: f64 = -0.206_359_915_709_191_5;
const C41: f64 = -0.107_352_905_815_137_5;
const C42: f64 = -9.594_562_251_023_355;
const C43: f64 = -20.470_286_148_096_16;
const C51: f64 = 7.496_443_313_967_647;
const C52: f64 = -10.246_804_314_643_52;
const C53: f64 = -33.999_903_528_199_05;
const C54: f64 = 11.708_908_932_061_6;
const C61: f64 = 8.083_246_795_921_522;
const C62: f64 = -7.981_132_988_064_893;
const C63: f64 = -31.521_594_328_743_71;
const C64: f64 = 16.319_305_431_231_36;
const C65: f64 = -6.058_818_238_834_054;
/// Stage times `αᵢ` (stages 5 and 6 at the step's end).
const ALPHA2: f64 = 0.386;
const ALPHA3: f64 = 0.21;
const ALPHA4: f64 = 0.63;
/// `dᵢ = Σⱼ γᵢⱼ`, the weights of `∂f/∂t` (0 for stages 5 and 6).
const D1: f64 = 0.25;
const D2: f64 = -0.1043;
const D3: f64 = 0.1035;
const D4: f64 = -0.036_200_000_000_000_23;
/// Dense output: `q₁ = Σ H2ⱼ kⱼ`, `q₂ = Σ H3ⱼ kⱼ`.
const H21: f64 = 10.126_235_083_445_86;
const H22: f64 = -7.487_995_877_610_167;
const H23: f64 = -34.800_918_615_557_47;
const H24: f64 = -7.992_771_707_568_823;
const H25: f64 = 1.025_137_723_295_662;
const H31: f64 = -0.676_280_339_280_125_3;
const H32: f64 = 6.087_714_651_680_015;
const H33: f64 = 16.430_843_208_924_78;
const H34: f64 = 24.767_225_114_183_86;
const H35: f64 = -6.594_389_125_716_872;

/// Adaptive RODAS4 stepper for one trajectory of `N` states.
#[derive(Debug, Clone)]
pub struct Rodas4<const N: usize> {
    tol: Tolerances<N>,
    control: StepControl,
    t: f64,
    t_prev: f64,
    y: [f64; N],
    y_prev: [f64; N],
    dy: [f64; N],
    /// Dense output `q₁`, `q₂` of the last step.
    cont: [[f64; N]; 2],
    /// Proposal for the next step; 0 = estimate it.
    h_next: f64,
    n_eval: u64,
    n_accepted: u64,
    n_rejected: u64,
    /// Accepted steps that ended on their stop time (not counted against `max_steps`).
    n_on_stop: u64,
    initialized: bool,
}

/// One attempt's order-4 solution, error estimate `k₆` and dense output `q₁`, `q₂`.
struct Attempt<const N: usize> {
    y1: [f64; N],
    k6: [f64; N],
    cont: [[f64; N]; 2],
}

impl<const N: usize> Attempt<N> {
    fn zero() -> Attempt<N> {
        Attempt {
            y1: [0.0; N],
            k6: [0.0; N],
            cont: [[0.0; N]; 2],
        }
    }
}

/// `W = I/(γh) − J` factored as `P W = L U` (unit `L` below the diagonal, `U` on and above).
struct Factored<const N: usize> {
    lu: [[f64; N]; N],
    perm: [usize; N],
}

impl<const N: usize> Factored<N> {
    fn zero() -> Factored<N> {
        Factored {
            lu: [[0.0; N]; N],
            perm: [0; N],
        }
    }

    /// Factor `I/(γh) − J` into `self` (every entry rewritten, in place: no copy of the
    /// matrix); false if it is singular or not finite.
    #[inline]
    fn factor(&mut self, jac: &[[f64; N]; N], inv_gamma_h: f64) -> bool {
        let Factored { lu, perm } = self;
        for i in 0..N {
            for j in 0..N {
                lu[i][j] = -jac[i][j];
            }
            lu[i][i] += inv_gamma_h;
        }
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        for k in 0..N {
            let mut piv = k;
            for i in k + 1..N {
                if lu[i][k].abs() > lu[piv][k].abs() {
                    piv = i;
                }
            }
            let p = lu[piv][k];
            if !(p.is_finite() && p != 0.0) {
                return false;
            }
            if piv != k {
                // Element by element: swapping the rows whole calls memcpy (k < piv).
                let (upper, lower) = lu.split_at_mut(piv);
                for (a, b) in upper[k].iter_mut().zip(lower[0].iter_mut()) {
                    std::mem::swap(a, b);
                }
                perm.swap(piv, k);
            }
            for i in k + 1..N {
                let m = lu[i][k] / p;
                lu[i][k] = m;
                if m != 0.0 {
                    for j in k + 1..N {
                        lu[i][j] -= m * lu[k][j];
                    }
                }
            }
        }
        true
    }

    /// `W⁻¹ b`.
    #[inline(always)]
    fn solve(&self, b: &[f64; N]) -> [f64; N] {
        let mut x = [0.0; N];
        for i in 0..N {
            let mut s = b[self.perm[i]];
            for j in 0..i {
                s -= self.lu[i][j] * x[j];
            }
            x[i] = s;
        }
        for i in (0..N).rev() {
            let mut s = x[i];
            for j in i + 1..N {
                s -= self.lu[i][j] * x[j];
            }
            x[i] = s / self.lu[i][i];
        }
        x
    }
}

/// The forward-difference increment of a component (or the time) of size `v`:
/// `√ε · max(|v|, 1)`, so that the rounding of the difference (`ε |f| / d`) stays near `√ε`
/// of `f` whatever `v` is, 0 included; returned as the moved value and the difference it
/// makes exactly.
#[inline]
fn increment(v: f64) -> (f64, f64) {
    let d = f64::EPSILON.sqrt() * v.abs().max(1.0);
    let moved = v + d;
    (moved, moved - v)
}

impl<const N: usize> Rodas4<N> {
    /// A stepper with tolerances `tol` and controller settings `control` (validated; its
    /// `beta` is not used: the controller is an I controller).
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
            cont: [[0.0; N]; 2],
            h_next: 0.0,
            n_eval: 0,
            n_accepted: 0,
            n_rejected: 0,
            n_on_stop: 0,
            initialized: false,
        })
    }

    /// A stepper with tolerances `tol` and the default controller.
    pub fn with_tolerances(tol: Tolerances<N>) -> Self {
        Self::new(tol, StepControl::default()).expect("the default step control is valid")
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
        self.cont = [[0.0; N]; 2];
        self.initialized = true;
        Ok(())
    }

    /// The error norm's scale of component `i` between `y0` and `y1`.
    #[inline]
    fn scale(&self, i: usize, y0: f64, y1: f64) -> f64 {
        self.tol.atol()[i] + self.tol.rtol() * y0.abs().max(y1.abs())
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
            0.25,
            self.control.h_max,
            t_stop,
        )
    }
}

/// Column `j` of `J = ∂f/∂y` at `(t, y)`, where `f(t, y) = f0`, by a forward difference
/// (one evaluation of `f`).
pub fn difference_column<F, const N: usize>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    f0: &[f64; N],
    j: usize,
) -> [f64; N]
where
    F: FnMut(f64, &[f64; N], &mut [f64; N]),
{
    let mut moved = *y;
    let (yj, d) = increment(y[j]);
    moved[j] = yj;
    let mut fj = [0.0; N];
    f(t, &moved, &mut fj);
    let mut col = [0.0; N];
    for i in 0..N {
        col[i] = (fj[i] - f0[i]) / d;
    }
    col
}

/// `∂f/∂t` at `(t, y)`, where `f(t, y) = f0`, by a difference (one evaluation of `f`):
/// forward in time, inside a step toward `t_stop`, or backward when the step ends sooner (a
/// sliver step onto a stop time, whose `h dᵢ ∂f/∂t` terms are then negligible anyway).
pub fn time_difference<F, const N: usize>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    f0: &[f64; N],
    t_stop: f64,
) -> [f64; N]
where
    F: FnMut(f64, &[f64; N], &mut [f64; N]),
{
    let (mut tt, mut dt) = increment(t);
    if tt >= t_stop {
        tt = t - dt;
        dt = tt - t;
    }
    let mut ft = [0.0; N];
    f(tt, y, &mut ft);
    for i in 0..N {
        ft[i] = (ft[i] - f0[i]) / dt;
    }
    ft
}

/// `J` and `∂f/∂t` at `(t, y)` (where `f(t, y) = f0`) by differences alone: `N + 1`
/// evaluations of `f`, the count returned. What [`DenseStepper::step`] takes; a caller
/// that knows part of `J` in closed form gives [`Rodas4::step_with`] its own.
pub fn difference_jacobian<F, const N: usize>(
    f: &mut F,
    t: f64,
    y: &[f64; N],
    f0: &[f64; N],
    t_stop: f64,
    jac: &mut [[f64; N]; N],
    ft: &mut [f64; N],
) -> u64
where
    F: FnMut(f64, &[f64; N], &mut [f64; N]),
{
    for j in 0..N {
        let col = difference_column(f, t, y, f0, j);
        for i in 0..N {
            jac[i][j] = col[i];
        }
    }
    *ft = time_difference(f, t, y, f0, t_stop);
    N as u64 + 1
}

impl<const N: usize> DenseStepper<N> for Rodas4<N> {
    fn init<F>(&mut self, mut f: F, t0: f64, y0: &[f64; N]) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        self.initialized = false;
        self.h_next = 0.0;
        self.set_state(&mut f, t0, y0)
    }

    fn restart<F>(&mut self, mut f: F, t: f64, y: &[f64; N]) -> Result<(), IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        self.set_state(&mut f, t, y)
    }

    fn step<F>(&mut self, f: F, t_stop: f64) -> Result<StepOutcome, IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        let mut f = f;
        self.step_inner(&mut f, difference_jacobian, t_stop)
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
        let s = (t_between - self.t_prev) / (self.t - self.t_prev);
        let s1 = 1.0 - s;
        s1 * self.y_prev[i] + s * (self.y[i] + s1 * (self.cont[0][i] + s * self.cont[1][i]))
    }

    fn n_eval(&self) -> u64 {
        self.n_eval
    }
}

impl<const N: usize> Rodas4<N> {
    /// [`DenseStepper::step`] with the Jacobian and `∂f/∂t` given by `jacobian(t, y, f0,
    /// t_stop, jac, ft)` (at `(t, y)`, where `f(t, y) = f0`, once a step; it returns the
    /// evaluations of the derivative it made, added to [`DenseStepper::n_eval`]): what a
    /// caller knows in closed form, with differences ([`difference_column`],
    /// [`time_difference`]) for the rest.
    pub fn step_with<F, J>(
        &mut self,
        mut f: F,
        mut jacobian: J,
        t_stop: f64,
    ) -> Result<StepOutcome, IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
        J: FnMut(f64, &[f64; N], &[f64; N], f64, &mut [[f64; N]; N], &mut [f64; N]) -> u64,
    {
        self.step_inner(
            &mut f,
            |_: &mut F,
             t,
             y: &[f64; N],
             f0: &[f64; N],
             t_stop,
             jac: &mut [[f64; N]; N],
             ft: &mut [f64; N]| { jacobian(t, y, f0, t_stop, jac, ft) },
            t_stop,
        )
    }

    /// The step, the Jacobian's function handed the derivative.
    fn step_inner<F, J>(
        &mut self,
        f: &mut F,
        mut jacobian: J,
        t_stop: f64,
    ) -> Result<StepOutcome, IntegratorError>
    where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
        J: FnMut(&mut F, f64, &[f64; N], &[f64; N], f64, &mut [[f64; N]; N], &mut [f64; N]) -> u64,
    {
        if !self.initialized {
            return Err(IntegratorError::NotInitialized);
        }
        if t_stop.is_nan() || t_stop <= self.t {
            return Err(IntegratorError::StopTimeNotAhead { t: self.t, t_stop });
        }
        let c = self.control;
        let mut h = if self.h_next > 0.0 {
            self.h_next
        } else {
            self.initial_step(f, t_stop)
        };
        let (mut jac, mut ft) = ([[0.0; N]; N], [0.0; N]);
        self.n_eval += jacobian(f, self.t, &self.y, &self.dy, t_stop, &mut jac, &mut ft);
        let (t, y0, f0) = (self.t, self.y, self.dy);
        let mut rejected = false;
        // Each attempt's factored matrix, solution, error estimate and dense output, written
        // in place.
        let mut w = Factored::zero();
        let mut out = Attempt::zero();
        loop {
            let h_proposal = h.min(c.h_max);
            let (hs, last) = clip_to_stop(t, h_proposal, t_stop);
            h = hs;
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
            let t_end = if last { t_stop } else { t + h };
            let factored = w.factor(&jac, 1.0 / (GAMMA * h));
            let err = if factored {
                self.attempt(f, &w, t, t_end, h, &y0, &f0, &ft, &mut out);
                let (y1, k6) = (&out.y1, &out.k6);
                let mut sum = 0.0;
                for i in 0..N {
                    let q = k6[i] / self.scale(i, y0[i], y1[i]);
                    sum += q * q;
                }
                (sum / N as f64).sqrt()
            } else {
                f64::NAN
            };
            if factored && err <= 1.0 {
                let Attempt { y1, cont, .. } = out;
                let mut fac = (c.safety * err.powf(-0.25)).clamp(c.min_factor, c.max_factor);
                if rejected {
                    fac = fac.min(1.0);
                }
                let mut h_new = h * fac;
                if last && h < h_proposal {
                    h_new = h_new.max(h_proposal);
                }
                let mut dy1 = [0.0; N];
                f(t_end, &y1, &mut dy1);
                self.n_eval += 1;
                self.h_next = h_new;
                self.n_accepted += 1;
                self.n_on_stop += u64::from(last);
                self.t_prev = t;
                self.y_prev = y0;
                self.t = t_end;
                self.y = y1;
                self.dy = dy1;
                self.cont = cont;
                return Ok(if last {
                    StepOutcome::ReachedStop
                } else {
                    StepOutcome::Internal
                });
            }
            // Rejected (a NaN error, or a singular W, lands here too: the smallest factor).
            self.n_rejected += 1;
            rejected = true;
            let fac = c.safety * err.powf(-0.25);
            h *= if fac.is_nan() {
                c.min_factor
            } else {
                fac.clamp(c.min_factor, 1.0)
            };
        }
    }
}

impl<const N: usize> Rodas4<N> {
    /// One attempt of step `h` from `(t, y0)` (derivative `f0`, `∂f/∂t` `ft`) to `t_end`
    /// with the factored `w`: the order-4 solution, the error estimate `k₆` and the dense
    /// output's `q₁`, `q₂`, into `out`.
    #[allow(clippy::too_many_arguments)]
    fn attempt<F>(
        &mut self,
        f: &mut F,
        w: &Factored<N>,
        t: f64,
        t_end: f64,
        h: f64,
        y0: &[f64; N],
        f0: &[f64; N],
        ft: &[f64; N],
        out: &mut Attempt<N>,
    ) where
        F: FnMut(f64, &[f64; N], &mut [f64; N]),
    {
        let inv_h = 1.0 / h;
        let mut rhs = [0.0; N];
        let mut u = [0.0; N];
        let mut du = [0.0; N];
        for i in 0..N {
            rhs[i] = f0[i] + h * D1 * ft[i];
        }
        let k1 = w.solve(&rhs);
        for i in 0..N {
            u[i] = y0[i] + A21 * k1[i];
        }
        f(t + ALPHA2 * h, &u, &mut du);
        for i in 0..N {
            rhs[i] = du[i] + h * D2 * ft[i] + inv_h * (C21 * k1[i]);
        }
        let k2 = w.solve(&rhs);
        for i in 0..N {
            u[i] = y0[i] + A31 * k1[i] + A32 * k2[i];
        }
        f(t + ALPHA3 * h, &u, &mut du);
        for i in 0..N {
            rhs[i] = du[i] + h * D3 * ft[i] + inv_h * (C31 * k1[i] + C32 * k2[i]);
        }
        let k3 = w.solve(&rhs);
        for i in 0..N {
            u[i] = y0[i] + A41 * k1[i] + A42 * k2[i] + A43 * k3[i];
        }
        f(t + ALPHA4 * h, &u, &mut du);
        for i in 0..N {
            rhs[i] = du[i] + h * D4 * ft[i] + inv_h * (C41 * k1[i] + C42 * k2[i] + C43 * k3[i]);
        }
        let k4 = w.solve(&rhs);
        for i in 0..N {
            u[i] = y0[i] + A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i];
        }
        f(t_end, &u, &mut du);
        for i in 0..N {
            rhs[i] = du[i] + inv_h * (C51 * k1[i] + C52 * k2[i] + C53 * k3[i] + C54 * k4[i]);
        }
        let k5 = w.solve(&rhs);
        for i in 0..N {
            u[i] += k5[i];
        }
        f(t_end, &u, &mut du);
        for i in 0..N {
            rhs[i] = du[i]
                + inv_h * (C61 * k1[i] + C62 * k2[i] + C63 * k3[i] + C64 * k4[i] + C65 * k5[i]);
        }
        out.k6 = w.solve(&rhs);
        self.n_eval += 5;
        let Attempt { y1, k6, cont } = out;
        for i in 0..N {
            y1[i] = u[i] + k6[i];
            cont[0][i] = H21 * k1[i] + H22 * k2[i] + H23 * k3[i] + H24 * k4[i] + H25 * k5[i];
            cont[1][i] = H31 * k1[i] + H32 * k2[i] + H33 * k3[i] + H34 * k4[i] + H35 * k5[i];
        }
    }
}

#[cfg(test)]
mod factored_tests {
    use super::Factored;

    /// `W = I/(γh) − J` for `J = −w` and `1/(γh) = 0`: `w` itself.
    fn factored(w: [[f64; 3]; 3]) -> Factored<3> {
        let mut f = Factored::zero();
        assert!(f.factor(&w.map(|row| row.map(|v| -v)), 0.0));
        f
    }

    #[test]
    fn a_zero_first_pivot_is_swapped_and_the_solution_is_exact() {
        // Rows 0 and 1 swapped: x₁ = 1, x₀ = 2, 2 x₂ = 3.
        let f = factored([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 2.0]]);
        assert_eq!(f.perm, [1, 0, 2]);
        assert_eq!(f.solve(&[1.0, 2.0, 3.0]), [2.0, 1.0, 1.5]);
    }

    #[test]
    fn the_largest_pivot_is_taken_and_the_rows_move_whole() {
        // Pivot 4 (row 1); multiplier 1/4, then U = [[4, 1, 0], [0, 1.75, 0], [0, 0, 1]], all
        // exact in binary: W [1, −1, 2] = [−1, 3, 2] is solved exactly.
        let f = factored([[1.0, 2.0, 0.0], [4.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        assert_eq!(f.perm, [1, 0, 2]);
        assert_eq!(f.lu[0], [4.0, 1.0, 0.0]);
        assert_eq!(f.lu[1], [0.25, 1.75, 0.0]);
        assert_eq!(f.solve(&[-1.0, 3.0, 2.0]), [1.0, -1.0, 2.0]);
    }

    #[test]
    fn a_singular_matrix_is_refused() {
        let mut f = Factored::<2>::zero();
        assert!(!f.factor(&[[-1.0, -2.0], [-2.0, -4.0]], 0.0));
    }
}
