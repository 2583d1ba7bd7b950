//! Tests of the steppers against exact solutions. Each states its tolerance and prints what
//! it measured.

use super::*;
use std::f64::consts::PI;

mod lanes;
mod rodas4;

fn decay(_t: f64, y: &[f64; 1], dy: &mut [f64; 1]) {
    dy[0] = -y[0];
}

/// x'' = −x with x(0) = 1, x'(0) = 0: x = cos t, v = −sin t.
fn oscillator(_t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
    dy[0] = y[1];
    dy[1] = -y[0];
}

/// y' = y cos t, y(0) = 1: y = exp(sin t). Non-autonomous, so the stage times matter.
fn exp_sin(t: f64, y: &[f64; 1], dy: &mut [f64; 1]) {
    dy[0] = y[0] * t.cos();
}

fn dopri<const N: usize>(rtol: f64, atol: f64) -> Dopri54<N> {
    Dopri54::with_tolerances(Tolerances::uniform(rtol, atol).unwrap())
}

/// A DOPRI5 stepper that takes exactly steps of `h` (controller capped at `h`, tolerances
/// so loose that nothing is rejected).
fn dopri_fixed<const N: usize>(h: f64) -> Dopri54<N> {
    let control = StepControl {
        h_initial: h,
        h_max: h,
        ..StepControl::default()
    };
    Dopri54::new(Tolerances::uniform(1e-1, 1e3).unwrap(), control).unwrap()
}

/// Integrate to `t_end` and return the stepper.
fn run_to<S: DenseStepper<N>, const N: usize, F>(s: &mut S, mut f: F, t_end: f64)
where
    F: FnMut(f64, &[f64; N], &mut [f64; N]),
{
    while s.step(&mut f, t_end).unwrap() != StepOutcome::ReachedStop {}
    assert_eq!(s.t(), t_end);
}

#[test]
fn dopri5_solves_exponential_decay_to_a_billionth_at_rtol_1e_10() {
    // Absolute error below 1e-9 everywhere (y ≤ 1); the relative error grows linearly with
    // time (≈ 3e-10 per time constant), so below 1e-8 at ten time constants.
    let mut s = dopri::<1>(1e-10, 1e-12);
    s.init(decay, 0.0, &[1.0]).unwrap();
    let (mut worst_abs, mut worst_rel): (f64, f64) = (0.0, 0.0);
    loop {
        let out = s.step(decay, 10.0).unwrap();
        let exact = (-s.t()).exp();
        worst_abs = worst_abs.max((s.y()[0] - exact).abs());
        worst_rel = worst_rel.max((s.y()[0] / exact - 1.0).abs());
        if out == StepOutcome::ReachedStop {
            break;
        }
    }
    eprintln!(
        "decay: worst absolute error {worst_abs:.2e}, relative {worst_rel:.2e}, {} steps, {} evaluations",
        s.n_accepted(),
        s.n_eval()
    );
    assert!(worst_abs < 1e-9);
    assert!(worst_rel < 1e-8);
}

#[test]
fn dopri5_follows_a_harmonic_oscillator_for_three_periods_at_rtol_1e_10() {
    let tol = 1e-9;
    let mut s = dopri::<2>(1e-10, 1e-10);
    s.init(oscillator, 0.0, &[1.0, 0.0]).unwrap();
    let t_end = 6.0 * PI;
    let mut worst: f64 = 0.0;
    loop {
        let out = s.step(oscillator, t_end).unwrap();
        let t = s.t();
        worst = worst
            .max((s.y()[0] - t.cos()).abs())
            .max((s.y()[1] + t.sin()).abs());
        if out == StepOutcome::ReachedStop {
            break;
        }
    }
    eprintln!(
        "oscillator: worst error {worst:.2e}, {} accepted, {} rejected",
        s.n_accepted(),
        s.n_rejected()
    );
    assert!(worst < tol);
}

#[test]
fn dopri5_global_error_falls_32_fold_when_the_fixed_step_is_halved() {
    // Order 5: ratio 2^5 = 32, approached from above (38, 36 for h = 0.2 → 0.1 → 0.05), so
    // measured at h = 0.05 → 0.025 → 0.0125 and allowed ±10 %.
    let t_end = 2.0;
    let errors: Vec<f64> = [0.05, 0.025, 0.0125]
        .iter()
        .map(|&h| {
            let mut s = dopri_fixed::<1>(h);
            s.init(exp_sin, 0.0, &[1.0]).unwrap();
            run_to(&mut s, exp_sin, t_end);
            assert_eq!(s.n_accepted(), (t_end / h).round() as u64);
            assert_eq!(s.n_rejected(), 0);
            (s.y()[0] - t_end.sin().exp()).abs()
        })
        .collect();
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        eprintln!(
            "dopri5 fixed step: errors {:.3e} → {:.3e}, ratio {ratio:.2}",
            w[0], w[1]
        );
        assert!((ratio - 32.0).abs() < 3.2, "ratio {ratio}");
    }
}

#[test]
fn dopri5_adaptive_error_is_proportional_to_the_tolerance() {
    // Tolerance proportionality: error / tol stays within a fixed band across 4 decades and
    // each 100× tighter tolerance gains at least 50×.
    let mut previous = f64::NAN;
    for tol in [1e-5, 1e-7, 1e-9, 1e-11] {
        let mut s = dopri::<2>(tol, tol);
        s.init(oscillator, 0.0, &[1.0, 0.0]).unwrap();
        run_to(&mut s, oscillator, 10.0);
        let err = (s.y()[0] - 10.0_f64.cos())
            .abs()
            .max((s.y()[1] + 10.0_f64.sin()).abs());
        eprintln!(
            "tol {tol:.0e}: error {err:.3e} (error/tol {:.3}), {} steps",
            err / tol,
            s.n_accepted()
        );
        assert!(
            err / tol < 10.0 && err / tol > 1e-3,
            "error/tol {}",
            err / tol
        );
        if previous.is_finite() {
            assert!(previous / err > 50.0, "gain {}", previous / err);
        }
        previous = err;
    }
}

#[test]
fn rk4_global_error_falls_16_fold_when_the_step_is_halved() {
    let t_end = 2.0;
    let errors: Vec<f64> = [0.1, 0.05, 0.025]
        .iter()
        .map(|&h| {
            let mut s = Rk4::<1>::new(h).unwrap();
            s.init(exp_sin, 0.0, &[1.0]).unwrap();
            run_to(&mut s, exp_sin, t_end);
            // 4 evaluations per step plus the initial derivative.
            assert_eq!(s.n_eval(), 1 + 4 * (t_end / h).round() as u64);
            (s.y()[0] - t_end.sin().exp()).abs()
        })
        .collect();
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        eprintln!("rk4: errors {:.3e} → {:.3e}, ratio {ratio:.2}", w[0], w[1]);
        assert!((ratio - 16.0).abs() <= 2.0, "ratio {ratio}");
    }
}

/// Largest error of the dense output of one step of `s` from (0, [1, 0]) for the oscillator,
/// at several interior points, against the exact solution.
fn one_step_dense_error<S: DenseStepper<2>>(s: &mut S, h: f64) -> f64 {
    s.init(oscillator, 0.0, &[1.0, 0.0]).unwrap();
    s.step(oscillator, h).unwrap();
    assert_eq!(s.t(), h);
    let mut worst: f64 = 0.0;
    for theta in [0.2, 0.5, 0.7, 0.9] {
        let t = theta * h;
        let y = s.dense(t);
        worst = worst
            .max((y[0] - t.cos()).abs())
            .max((y[1] + t.sin()).abs());
    }
    worst
}

#[test]
fn dopri5_dense_output_has_local_error_of_order_five() {
    // 4th-order interpolant: local error O(h^5), ratio 32 on halving (±15 %: asymptotic).
    let errs: Vec<f64> = [0.4, 0.2, 0.1]
        .iter()
        .map(|&h| one_step_dense_error(&mut dopri_fixed::<2>(h), h))
        .collect();
    for w in errs.windows(2) {
        let ratio = w[0] / w[1];
        eprintln!(
            "dopri5 dense: {:.3e} → {:.3e}, ratio {ratio:.2}",
            w[0], w[1]
        );
        assert!((ratio - 32.0).abs() < 4.8, "ratio {ratio}");
    }
}

#[test]
fn dopri5_dense_output_between_adaptive_steps_is_as_accurate_as_the_steps() {
    // Within 10× the tolerance anywhere inside the steps over three periods.
    let tol = 1e-8;
    let mut s = dopri::<2>(tol, tol);
    s.init(oscillator, 0.0, &[1.0, 0.0]).unwrap();
    let mut worst: f64 = 0.0;
    while s.step(oscillator, 6.0 * PI).unwrap() == StepOutcome::Internal {
        let (a, b) = (s.t_prev(), s.t());
        for k in 1..10 {
            let t = a + (b - a) * k as f64 / 10.0;
            let y = s.dense(t);
            worst = worst
                .max((y[0] - t.cos()).abs())
                .max((y[1] + t.sin()).abs());
            assert_eq!(s.dense_component(t, 1), y[1]);
        }
        assert_eq!(s.dense(a), *s.y_prev());
        assert_eq!(s.dense(b), *s.y());
    }
    eprintln!("dopri5 dense, adaptive tol {tol:e}: worst error {worst:.3e}");
    assert!(worst < 10.0 * tol);
}

#[test]
fn rk4_hermite_dense_output_has_local_error_of_order_four() {
    // Cubic Hermite: O(h^4) inside the step, ratio 16 on halving (±2).
    let errs: Vec<f64> = [0.2, 0.1, 0.05]
        .iter()
        .map(|&h| one_step_dense_error(&mut Rk4::<2>::new(h).unwrap(), h))
        .collect();
    for w in errs.windows(2) {
        let ratio = w[0] / w[1];
        eprintln!("rk4 dense: {:.3e} → {:.3e}, ratio {ratio:.2}", w[0], w[1]);
        assert!((ratio - 16.0).abs() <= 2.0, "ratio {ratio}");
    }
}

/// Steps through `stops` and checks that no step passes the stop in force and each is hit
/// bit for bit. Returns the state at the end.
fn walk_stops<S: DenseStepper<2>>(s: &mut S, stops: &[f64]) -> [f64; 2] {
    s.init(oscillator, 0.0, &[1.0, 0.0]).unwrap();
    for &stop in stops {
        loop {
            let out = s.step(oscillator, stop).unwrap();
            assert!(s.t() <= stop, "t {} crossed stop {stop}", s.t());
            if out == StepOutcome::ReachedStop {
                assert_eq!(s.t(), stop);
                break;
            }
            assert!(s.t() < stop);
        }
    }
    *s.y()
}

#[test]
fn a_stop_time_is_never_crossed_and_is_hit_exactly() {
    let one_plus = f64::from_bits(1.0_f64.to_bits() + 2);
    let stops = [0.1, 0.1 + 1e-12, 0.37, 1.0, one_plus, 2.5, 7.0];
    let mut d = dopri::<2>(1e-9, 1e-9);
    let y = walk_stops(&mut d, &stops);
    let err = (y[0] - 7.0_f64.cos())
        .abs()
        .max((y[1] + 7.0_f64.sin()).abs());
    eprintln!(
        "dopri5 through stops: error at 7 s {err:.2e}, {} steps, next h {:.3}",
        d.n_accepted(),
        d.h_next()
    );
    assert!(err < 1e-8);
    let mut r = Rk4::<2>::new(0.01).unwrap();
    let y = walk_stops(&mut r, &stops);
    let err = (y[0] - 7.0_f64.cos())
        .abs()
        .max((y[1] + 7.0_f64.sin()).abs());
    eprintln!("rk4 through stops: error at 7 s {err:.2e}");
    assert!(err < 1e-8);
}

#[test]
fn a_sliver_stop_does_not_shrink_the_next_step() {
    let mut s = dopri::<2>(1e-9, 1e-9);
    s.init(oscillator, 0.0, &[1.0, 0.0]).unwrap();
    run_to(&mut s, oscillator, 1.0);
    let h_before = s.h_next();
    let sliver = f64::from_bits(1.0_f64.to_bits() + 2);
    assert_eq!(s.step(oscillator, sliver), Ok(StepOutcome::ReachedStop));
    eprintln!(
        "h_next before the sliver {h_before:.4}, after {:.4}",
        s.h_next()
    );
    assert!(s.t() == sliver && s.h_next() >= h_before);
}

#[test]
fn dopri5_counts_six_evaluations_per_attempt_and_retries_rejected_steps() {
    // A first step of 2 s at rtol 1e-10 is far too long: it must be rejected and retried.
    let control = StepControl {
        h_initial: 2.0,
        ..StepControl::default()
    };
    let mut s = Dopri54::new(Tolerances::uniform(1e-10, 1e-12).unwrap(), control).unwrap();
    s.init(decay, 0.0, &[1.0]).unwrap();
    run_to(&mut s, decay, 3.0);
    eprintln!(
        "decay from h0 = 2: {} accepted, {} rejected, {} evaluations, error {:.2e}",
        s.n_accepted(),
        s.n_rejected(),
        s.n_eval(),
        (s.y()[0] - (-3.0_f64).exp()).abs()
    );
    assert!(s.n_rejected() >= 1);
    assert_eq!(s.n_eval(), 1 + 6 * (s.n_accepted() + s.n_rejected()));
    assert!((s.y()[0] / (-3.0_f64).exp() - 1.0).abs() < 1e-9);
    // With the starting-step estimate: one more evaluation.
    let mut s = dopri::<1>(1e-10, 1e-12);
    s.init(decay, 0.0, &[1.0]).unwrap();
    run_to(&mut s, decay, 3.0);
    assert_eq!(s.n_eval(), 2 + 6 * (s.n_accepted() + s.n_rejected()));
}

#[test]
fn a_projectile_in_vacuum_reaches_the_closed_form_apogee_and_lands_on_time() {
    const G: f64 = 9.80665;
    let v0 = 100.0;
    let f = |_t: f64, y: &[f64; 2], dy: &mut [f64; 2]| {
        dy[0] = y[1];
        dy[1] = -G;
    };
    let (t_ap, z_ap) = (v0 / G, v0 * v0 / (2.0 * G));
    let mut s = dopri::<2>(1e-8, 1e-8);
    s.init(f, 0.0, &[0.0, v0]).unwrap();
    let apogee = loop {
        s.step(f, f64::INFINITY).unwrap();
        if let Some(found) = locate_maximum(&s, 0, 1, DEFAULT_TIME_TOL_S).unwrap() {
            break found;
        }
    };
    eprintln!(
        "apogee t {:.15} (exact {t_ap:.15}, error {:.2e}), z {:.12} (exact {z_ap:.12}, error {:.2e})",
        apogee.0,
        (apogee.0 - t_ap).abs(),
        apogee.1,
        (apogee.1 - z_ap).abs()
    );
    // DOPRI5 and its interpolant are exact on a quadratic: only rounding remains.
    assert!((apogee.0 - t_ap).abs() < 1e-11);
    assert!((apogee.1 - z_ap).abs() < 1e-9);
    // Continue from the apogee state (as a driver does after an event) down to the ground.
    let y_ap = s.dense(apogee.0);
    s.restart(f, apogee.0, &y_ap).unwrap();
    let landing = loop {
        s.step(f, f64::INFINITY).unwrap();
        if let Some(t) =
            locate_event(&s, |_t, y: &[f64; 2]| y[0], Crossing::Falling, 1e-12).unwrap()
        {
            break t;
        }
    };
    eprintln!("landing t {landing:.13}, exact {:.13}", 2.0 * t_ap);
    assert!((landing - 2.0 * t_ap).abs() < 1e-10);
    // RK4 with its Hermite interpolant is exact on a quadratic too.
    let mut r = Rk4::<2>::new(0.37).unwrap();
    r.init(f, 0.0, &[0.0, v0]).unwrap();
    let apogee = loop {
        r.step(f, f64::INFINITY).unwrap();
        if let Some(found) = locate_maximum(&r, 0, 1, DEFAULT_TIME_TOL_S).unwrap() {
            break found;
        }
    };
    eprintln!("rk4 apogee {apogee:?}");
    assert!((apogee.0 - t_ap).abs() < 1e-11 && (apogee.1 - z_ap).abs() < 1e-9);
}

#[test]
fn an_event_on_the_dense_output_is_located_to_the_accuracy_of_the_solution() {
    // x = cos t falls through 0 at π/2; the interpolant is good to ~tol, so is the root.
    let mut s = dopri::<2>(1e-10, 1e-10);
    s.init(oscillator, 0.0, &[1.0, 0.0]).unwrap();
    let t = loop {
        s.step(oscillator, 10.0).unwrap();
        assert!(
            locate_event(&s, |_t, y: &[f64; 2]| y[0], Crossing::Rising, 1e-12)
                .unwrap()
                .is_none()
        );
        if let Some(t) = locate_event(&s, |_t, y: &[f64; 2]| y[0], Crossing::Either, 1e-12).unwrap()
        {
            break t;
        }
    };
    eprintln!("cos root {t:.15}, error {:.2e}", (t - PI / 2.0).abs());
    assert!((t - PI / 2.0).abs() < 1e-9);
}

#[test]
fn a_derivative_that_turns_nan_ends_in_a_step_size_underflow_error() {
    let f = |t: f64, _y: &[f64; 1], dy: &mut [f64; 1]| {
        dy[0] = if t > 0.5 { f64::NAN } else { 1.0 };
    };
    let mut s = dopri::<1>(1e-8, 1e-8);
    s.init(f, 0.0, &[0.0]).unwrap();
    let err = loop {
        match s.step(f, 1.0) {
            Ok(_) => assert!(s.t() <= 0.5),
            Err(e) => break e,
        }
    };
    eprintln!("{err} after {} evaluations", s.n_eval());
    match err {
        IntegratorError::StepSizeUnderflow { t, .. } => assert!((t - 0.5).abs() < 1e-9),
        other => panic!("unexpected {other}"),
    }
}

#[test]
fn a_chattering_derivative_ends_at_the_step_limit_instead_of_running_on() {
    // y' = −1000·sign(y) from y = 1 reaches 0 at t = 1 ms and then chatters about it: each
    // step across zero is rejected down to about atol/1000, far above the underflow floor, so
    // only the count of attempts can stop it (2·10¹¹ steps to t = 1 s otherwise).
    let f = |_t: f64, y: &[f64; 1], dy: &mut [f64; 1]| {
        dy[0] = -1000.0 * y[0].signum();
    };
    let control = StepControl {
        max_steps: 1_000,
        ..StepControl::default()
    };
    let mut s = Dopri54::new(Tolerances::uniform(1e-8, 1e-8).unwrap(), control).unwrap();
    s.init(f, 0.0, &[1.0]).unwrap();
    let err = loop {
        if let Err(e) = s.step(f, 1.0) {
            break e;
        }
    };
    eprintln!("{err}");
    assert_eq!(s.n_accepted() + s.n_rejected(), 1_000);
    match err {
        IntegratorError::TooManySteps { t, steps } => {
            assert_eq!(steps, 1_000);
            // Stuck within a few step sizes of the zero at 1 ms.
            assert!((t - 1e-3).abs() < 1e-6, "t = {t}");
        }
        other => panic!("unexpected {other}"),
    }
    assert!(err.to_string().contains("max_steps"), "{err}");
    // The default allows a whole flight's steps hundreds of times over.
    assert_eq!(StepControl::default().max_steps, 100_000);
    let none = StepControl {
        max_steps: 0,
        ..StepControl::default()
    };
    assert!(none
        .validate()
        .unwrap_err()
        .to_string()
        .contains("max_steps"));
}

#[test]
fn steps_that_end_on_stop_times_do_not_count_against_the_step_limit() {
    // y' = 1 stepped to 5,000 stop times 1e-4 s apart, with a limit of 1,000 attempts: every
    // step ends on its stop (the input chose it), so all 5,000 are taken and y(0.5) = 0.5.
    let f = |_t: f64, _y: &[f64; 1], dy: &mut [f64; 1]| dy[0] = 1.0;
    let control = StepControl {
        max_steps: 1_000,
        ..StepControl::default()
    };
    let mut s = Dopri54::new(Tolerances::uniform(1e-8, 1e-8).unwrap(), control).unwrap();
    s.init(f, 0.0, &[0.0]).unwrap();
    for k in 1..=5_000 {
        let stop = k as f64 * 1e-4;
        while s.step(f, stop).expect("within the limit") != StepOutcome::ReachedStop {}
    }
    assert_eq!(s.n_accepted(), 5_000);
    assert!((s.y()[0] - 0.5).abs() < 1e-12, "{}", s.y()[0]);
    // Steps of its own choosing still count: one stop 1e9 s ahead of a stiff decay
    // (y' = −1e6 y, steps held near 3e-6 s by stability) stops at the limit.
    let stiff = |_t: f64, y: &[f64; 1], dy: &mut [f64; 1]| dy[0] = -1e6 * y[0];
    let mut s = Dopri54::new(Tolerances::uniform(1e-8, 1e-8).unwrap(), control).unwrap();
    s.init(stiff, 0.0, &[1.0]).unwrap();
    let err = loop {
        if let Err(e) = s.step(stiff, 1e9) {
            break e;
        }
    };
    assert!(
        matches!(err, IntegratorError::TooManySteps { steps: 1_000, .. }),
        "{err}"
    );
    assert_eq!(s.n_accepted() + s.n_rejected(), 1_000);
}

#[test]
fn bad_tolerances_and_settings_are_typed_errors() {
    for rtol in [0.0, 1e-15, 0.2, f64::NAN, f64::INFINITY] {
        let e = Tolerances::<2>::uniform(rtol, 1e-6).unwrap_err();
        assert!(
            matches!(e, IntegratorError::RelativeTolerance { .. }),
            "{e}"
        );
        assert!(e.to_string().contains("rtol"));
    }
    assert!(Tolerances::<2>::uniform(1e-14, 1e-6).is_ok());
    assert!(Tolerances::<2>::uniform(1e-1, 1e-6).is_ok());
    for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let e = Tolerances::new(1e-6, [1e-6, bad]).unwrap_err();
        assert!(
            matches!(e, IntegratorError::AbsoluteTolerance { index: 1, .. }),
            "{e}"
        );
        assert!(e.to_string().contains("atol[1]"));
    }
    let tol = Tolerances::<1>::uniform(1e-6, 1e-6).unwrap();
    let bad_controls = [
        (
            "safety",
            StepControl {
                safety: 1.0,
                ..StepControl::default()
            },
        ),
        (
            "beta",
            StepControl {
                beta: -0.1,
                ..StepControl::default()
            },
        ),
        (
            "min_factor",
            StepControl {
                min_factor: 0.0,
                ..StepControl::default()
            },
        ),
        (
            "max_factor",
            StepControl {
                max_factor: 1.0,
                ..StepControl::default()
            },
        ),
        (
            "h_min",
            StepControl {
                h_min: -1.0,
                ..StepControl::default()
            },
        ),
        (
            "h_max",
            StepControl {
                h_max: 0.0,
                ..StepControl::default()
            },
        ),
        (
            "h_initial",
            StepControl {
                h_initial: f64::NAN,
                ..StepControl::default()
            },
        ),
    ];
    for (field, control) in bad_controls {
        let e = Dopri54::new(tol, control).unwrap_err();
        assert!(
            matches!(e, IntegratorError::Setting { field: f, .. } if f == field),
            "{field}: {e}"
        );
    }
    for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            Rk4::<1>::new(h),
            Err(IntegratorError::Setting { field: "h", .. })
        ));
    }
}

#[test]
fn misuse_of_a_stepper_is_a_typed_error() {
    let mut s = dopri::<1>(1e-6, 1e-6);
    assert_eq!(s.step(decay, 1.0), Err(IntegratorError::NotInitialized));
    let e = s.init(decay, 0.0, &[f64::NAN]).unwrap_err();
    assert!(
        matches!(e, IntegratorError::NonFinite { what: "state", .. }),
        "{e}"
    );
    s.init(decay, 2.0, &[1.0]).unwrap();
    for stop in [2.0, 1.0, f64::NAN] {
        assert!(matches!(
            s.step(decay, stop),
            Err(IntegratorError::StopTimeNotAhead { .. })
        ));
    }
    let mut r = Rk4::<1>::new(0.1).unwrap();
    assert_eq!(r.step(decay, 1.0), Err(IntegratorError::NotInitialized));
    let bad = |_t: f64, _y: &[f64; 1], dy: &mut [f64; 1]| dy[0] = f64::INFINITY;
    let e = r.init(bad, 0.0, &[1.0]).unwrap_err();
    assert!(
        matches!(
            e,
            IntegratorError::NonFinite {
                what: "derivative",
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn restart_keeps_the_step_size_and_init_forgets_it() {
    let mut s = dopri::<1>(1e-8, 1e-8);
    s.init(decay, 0.0, &[1.0]).unwrap();
    run_to(&mut s, decay, 1.0);
    let h = s.h_next();
    assert!(h > 0.0);
    s.restart(decay, 1.0, &[0.5]).unwrap();
    assert_eq!(s.h_next(), h);
    assert_eq!(
        (s.t_prev(), s.t(), s.y()[0], s.dense(1.0)[0]),
        (1.0, 1.0, 0.5, 0.5)
    );
    s.init(decay, 1.0, &[0.5]).unwrap();
    assert_eq!(s.h_next(), 0.0);
}
