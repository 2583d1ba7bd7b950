//! Root finding for events: Brent's bracketing method on a scalar function of time, and
//! helpers that locate a sign change of an event function over the last step of a
//! [`DenseStepper`] using its dense output (no extra derivative evaluations).
//!
//! Brent's method (R. P. Brent, *Algorithms for Minimization without Derivatives*, 1973,
//! ch. 4) mixes inverse quadratic interpolation, the secant rule and bisection; the bracket
//! always contains a sign change and shrinks at least as fast as bisection every few
//! iterations, so it always converges, superlinearly on smooth functions. It stops when the
//! bracket around the returned time is narrower than `tol + 4·ε·|t|`. Hand-written (about 60
//! lines) because the root crates on crates.io either allocate, lack an absolute time
//! tolerance or are unmaintained.
//!
//! An apogee is a maximum of altitude; [`locate_maximum`] finds it as the falling zero of the
//! vertical velocity component, which is also a state component, so a root finder suffices.

use super::DenseStepper;
use thiserror::Error;

/// Default absolute time tolerance of event location, s. Brent's method reaches it in a few
/// more iterations than 1e-9 would take.
pub const DEFAULT_TIME_TOL_S: f64 = 1e-12;

/// Safety cap on Brent iterations (convergence is guaranteed well before; from a 1 s
/// bracket to 1e-12 s bisection alone needs 40).
const MAX_ITERATIONS: u32 = 500;

/// Errors of the root finders.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RootError {
    /// The tolerance must be finite and > 0.
    #[error("root finder: `tol` = {value}: must be finite and > 0")]
    Tolerance {
        /// The rejected value.
        value: f64,
    },
    /// The function has the same sign at both ends of the interval.
    #[error("root finder: no sign change on [{t0}, {t1}]: g = {g0} and {g1}")]
    NoSignChange {
        /// Interval start.
        t0: f64,
        /// Value there.
        g0: f64,
        /// Interval end.
        t1: f64,
        /// Value there.
        g1: f64,
    },
    /// An end of the interval, or a function value, is NaN or infinite.
    #[error("root finder: non-finite value {value} at t = {t}")]
    NonFinite {
        /// Where.
        t: f64,
        /// The value.
        value: f64,
    },
    /// The iteration cap was reached (should not happen with a finite function).
    #[error("root finder: no convergence after {iterations} iterations, bracket [{a}, {b}]")]
    NotConverged {
        /// Iterations done.
        iterations: u32,
        /// Bracket end.
        a: f64,
        /// Bracket end.
        b: f64,
    },
}

/// Which sign changes count as an event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Crossing {
    /// From `g < 0` to `g >= 0`.
    Rising,
    /// From `g > 0` to `g <= 0`.
    Falling,
    /// Either of the above.
    Either,
}

impl Crossing {
    /// Does going from `g0` (start of step) to `g1` (end) count?
    #[inline]
    pub fn matches(self, g0: f64, g1: f64) -> bool {
        let rising = g0 < 0.0 && g1 >= 0.0;
        let falling = g0 > 0.0 && g1 <= 0.0;
        match self {
            Crossing::Rising => rising,
            Crossing::Falling => falling,
            Crossing::Either => rising || falling,
        }
    }
}

/// A root of `g` in `[t0, t1]` (either order) where `g(t0)` and `g(t1)` differ in sign (or
/// one is zero), to an absolute tolerance `tol` (plus 4·ε·|t|).
pub fn brent_root<G>(mut g: G, t0: f64, t1: f64, tol: f64) -> Result<f64, RootError>
where
    G: FnMut(f64) -> f64,
{
    let g0 = g(t0);
    let g1 = g(t1);
    brent_root_bracketed(g, t0, g0, t1, g1, tol)
}

/// As [`brent_root`], with the end values `g0 = g(t0)`, `g1 = g(t1)` already known.
pub fn brent_root_bracketed<G>(
    mut g: G,
    t0: f64,
    g0: f64,
    t1: f64,
    g1: f64,
    tol: f64,
) -> Result<f64, RootError>
where
    G: FnMut(f64) -> f64,
{
    if !(tol.is_finite() && tol > 0.0) {
        return Err(RootError::Tolerance { value: tol });
    }
    for (t, v) in [(t0, t0), (t1, t1), (t0, g0), (t1, g1)] {
        if !v.is_finite() {
            return Err(RootError::NonFinite { t, value: v });
        }
    }
    if g0 == 0.0 {
        return Ok(t0);
    }
    if g1 == 0.0 {
        return Ok(t1);
    }
    if (g0 > 0.0) == (g1 > 0.0) {
        return Err(RootError::NoSignChange { t0, g0, t1, g1 });
    }
    // b: best estimate; c: the other end of the bracket; a: previous b.
    let (mut a, mut fa) = (t0, g0);
    let (mut b, mut fb) = (t1, g1);
    let (mut c, mut fc) = (b, fb);
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    for _ in 0..MAX_ITERATIONS {
        if (fb > 0.0) == (fc > 0.0) {
            // Keep the sign change between b and c.
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol1 || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q) = if a == c {
                // Secant.
                (2.0 * m * s, 1.0 - s)
            } else {
                // Inverse quadratic interpolation through a, b, c.
                let q = fa / fc;
                let r = fb / fc;
                (
                    s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0)),
                    (q - 1.0) * (r - 1.0) * (s - 1.0),
                )
            };
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            // Accept the interpolation only if it falls well inside the bracket and the
            // steps keep shrinking; otherwise bisect.
            if 2.0 * p < (3.0 * m * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(m) };
        fb = g(b);
        if !fb.is_finite() {
            return Err(RootError::NonFinite { t: b, value: fb });
        }
    }
    Err(RootError::NotConverged {
        iterations: MAX_ITERATIONS,
        a: b,
        b: c,
    })
}

/// If the event function `g(t, y)` changes sign over the stepper's last step in the
/// direction `crossing`, the time of the crossing on the dense output (to `tol`), else
/// `None`. The ends use the stepper's exact `y_prev` and `y`.
pub fn locate_event<S, G, const N: usize>(
    stepper: &S,
    mut g: G,
    crossing: Crossing,
    tol: f64,
) -> Result<Option<f64>, RootError>
where
    S: DenseStepper<N>,
    G: FnMut(f64, &[f64; N]) -> f64,
{
    let (t0, t1) = (stepper.t_prev(), stepper.t());
    let g0 = g(t0, stepper.y_prev());
    let g1 = g(t1, stepper.y());
    if t1 == t0 || !crossing.matches(g0, g1) {
        return Ok(None);
    }
    let t = brent_root_bracketed(|t| g(t, &stepper.dense(t)), t0, g0, t1, g1, tol)?;
    Ok(Some(t))
}

/// The maximum of state component `value_index` over the last step, found as the falling
/// zero of component `rate_index`, which must be its time derivative (e.g. altitude and
/// vertical velocity for an apogee). Returns `(t, value at t)` or `None` if the rate does not
/// go from positive to non-positive during the step.
pub fn locate_maximum<S, const N: usize>(
    stepper: &S,
    value_index: usize,
    rate_index: usize,
    tol: f64,
) -> Result<Option<(f64, f64)>, RootError>
where
    S: DenseStepper<N>,
{
    let (t0, t1) = (stepper.t_prev(), stepper.t());
    let g0 = stepper.y_prev()[rate_index];
    let g1 = stepper.y()[rate_index];
    if t1 == t0 || !Crossing::Falling.matches(g0, g1) {
        return Ok(None);
    }
    let t = brent_root_bracketed(
        |t| stepper.dense_component(t, rate_index),
        t0,
        g0,
        t1,
        g1,
        tol,
    )?;
    Ok(Some((t, stepper.dense_component(t, value_index))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_root_of_sine_near_pi_is_found_to_a_picosecond() {
        let tol = 1e-12;
        let mut evals = 0;
        let t = brent_root(
            |t: f64| {
                evals += 1;
                t.sin()
            },
            3.0,
            3.3,
            tol,
        )
        .unwrap();
        let err = (t - std::f64::consts::PI).abs();
        eprintln!("sin root: {t:.17}, error {err:.2e}, {evals} evaluations");
        assert!(err <= tol);
        // Superlinear: bisection alone would need 39 halvings of 0.3 s.
        assert!(evals < 15, "{evals} evaluations");
    }

    #[test]
    fn a_flat_triple_root_and_a_jump_still_converge_by_bracketing() {
        let tol = 1e-12;
        let t = brent_root(|t: f64| t * t * t, -1.0, 2.0, tol).unwrap();
        eprintln!("t³ root: {t:e}");
        assert!(t.abs() <= tol);
        let mut evals = 0;
        let t = brent_root(
            |t: f64| {
                evals += 1;
                if t < 0.3 {
                    -1.0
                } else {
                    2.0
                }
            },
            0.0,
            1.0,
            tol,
        )
        .unwrap();
        eprintln!("step root: {t:.15} after {evals} evaluations");
        assert!((t - 0.3).abs() <= tol + 4.0 * f64::EPSILON);
        assert!(evals < 100);
    }

    #[test]
    fn the_order_of_the_interval_ends_does_not_matter() {
        let t = brent_root(|t: f64| t * t - 2.0, 2.0, 0.0, 1e-13).unwrap();
        assert!((t - std::f64::consts::SQRT_2).abs() <= 1e-13);
    }

    #[test]
    fn a_zero_at_an_end_is_returned_as_is() {
        assert_eq!(brent_root(|t: f64| t - 1.0, 1.0, 2.0, 1e-12), Ok(1.0));
        assert_eq!(brent_root(|t: f64| t - 2.0, 1.0, 2.0, 1e-12), Ok(2.0));
    }

    #[test]
    fn no_sign_change_bad_tolerance_and_nan_are_typed_errors() {
        assert!(matches!(
            brent_root(|t: f64| t * t + 1.0, -1.0, 1.0, 1e-12),
            Err(RootError::NoSignChange { .. })
        ));
        for tol in [0.0, -1e-9, f64::NAN, f64::INFINITY] {
            let err = brent_root(|t: f64| t, -1.0, 1.0, tol).unwrap_err();
            assert!(matches!(err, RootError::Tolerance { .. }), "{err}");
            assert!(err.to_string().contains("`tol`"));
        }
        assert!(matches!(
            brent_root(
                |t: f64| if t > 0.5 { f64::NAN } else { t - 0.75 },
                0.0,
                1.0,
                1e-12
            ),
            Err(RootError::NonFinite { .. })
        ));
    }

    #[test]
    fn crossings_count_only_in_their_direction() {
        assert!(Crossing::Rising.matches(-1.0, 0.0));
        assert!(!Crossing::Rising.matches(0.0, 1.0));
        assert!(!Crossing::Rising.matches(1.0, -1.0));
        assert!(Crossing::Falling.matches(1.0, -1.0));
        assert!(!Crossing::Falling.matches(-1.0, 1.0));
        assert!(Crossing::Either.matches(1.0, -1.0) && Crossing::Either.matches(-1.0, 1.0));
        assert!(!Crossing::Either.matches(1.0, 2.0));
    }
}
