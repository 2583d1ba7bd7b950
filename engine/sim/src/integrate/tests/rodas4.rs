//! RODAS4 against exact solutions: its order (4) and its dense output's (3) with fixed
//! steps, a stiff problem an explicit method must crawl through, and the fall under a drag
//! quadratic in the speed (a canopy's) with its landing found on the dense output.

use super::*;

fn rodas<const N: usize>(rtol: f64, atol: f64) -> Rodas4<N> {
    Rodas4::with_tolerances(Tolerances::uniform(rtol, atol).unwrap())
}

/// A RODAS4 stepper that takes exactly steps of `h` (capped at `h`, tolerances so loose
/// that nothing is rejected).
fn rodas_fixed<const N: usize>(h: f64) -> Rodas4<N> {
    let control = StepControl {
        h_initial: h,
        h_max: h,
        ..StepControl::default()
    };
    Rodas4::new(Tolerances::uniform(1e-1, 1e3).unwrap(), control).unwrap()
}

#[test]
fn rodas4_global_error_falls_16_fold_when_the_fixed_step_is_halved() {
    // Order 4: ratio 2⁴ = 16, measured on y' = y cos t to t = 1 (non-autonomous: the stage
    // times and ∂f/∂t enter; 17.9, 16.8, 16.5 for h = 0.2 → 0.025) and on the oscillator to
    // t = 2, allowed ±15 %.
    let hs = [0.1, 0.05, 0.025];
    let exp_sin_errors: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let t_end = 1.0;
            let mut s = rodas_fixed::<1>(h);
            s.init(exp_sin, 0.0, &[1.0]).unwrap();
            run_to(&mut s, exp_sin, t_end);
            assert_eq!(s.n_accepted(), (t_end / h).round() as u64);
            assert_eq!(s.n_rejected(), 0);
            (s.y()[0] - t_end.sin().exp()).abs()
        })
        .collect();
    let oscillator_errors: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let t_end = 2.0;
            let mut s = rodas_fixed::<2>(h);
            s.init(oscillator, 0.0, &[1.0, 0.0]).unwrap();
            run_to(&mut s, oscillator, t_end);
            (s.y()[0] - t_end.cos())
                .abs()
                .max((s.y()[1] + t_end.sin()).abs())
        })
        .collect();
    for errors in [&exp_sin_errors, &oscillator_errors] {
        for w in errors.windows(2) {
            let ratio = w[0] / w[1];
            eprintln!(
                "rodas4 fixed step: errors {:.3e} → {:.3e}, ratio {ratio:.2}",
                w[0], w[1]
            );
            assert!((ratio - 16.0).abs() < 2.4, "ratio {ratio}");
        }
    }
}

#[test]
fn rodas4_dense_output_is_exact_at_the_ends_and_third_order_inside() {
    // Order 3 inside a step: the largest error at the steps' quarter and three-quarter
    // points falls at least 8 × 0.8 fold as the step halves; at both ends the state itself.
    let t_end = 2.0;
    let worst: Vec<f64> = [0.2, 0.1, 0.05]
        .iter()
        .map(|&h| {
            let mut s = rodas_fixed::<1>(h);
            s.init(exp_sin, 0.0, &[1.0]).unwrap();
            let mut worst: f64 = 0.0;
            loop {
                let out = s.step(exp_sin, t_end).unwrap();
                let (t0, t1) = (s.t_prev(), s.t());
                assert_eq!(s.dense(t0), *s.y_prev());
                assert_eq!(s.dense(t1), *s.y());
                for frac in [0.25, 0.75] {
                    let t = t0 + frac * (t1 - t0);
                    worst = worst.max((s.dense_component(t, 0) - t.sin().exp()).abs());
                }
                if out == StepOutcome::ReachedStop {
                    break;
                }
            }
            worst
        })
        .collect();
    for w in worst.windows(2) {
        let ratio = w[0] / w[1];
        eprintln!(
            "rodas4 dense output: worst {:.3e} → {:.3e}, ratio {ratio:.2}",
            w[0], w[1]
        );
        assert!(ratio > 6.4, "ratio {ratio}");
    }
}

/// Prothero and Robinson's stiff problem: y' = λ (y − cos t) − sin t, y(0) = 1, whose
/// solution is cos t whatever λ; with λ ≪ 0 every other solution falls onto it at once.
fn prothero_robinson(lambda: f64) -> impl FnMut(f64, &[f64; 1], &mut [f64; 1]) {
    move |t, y, dy| dy[0] = lambda * (y[0] - t.cos()) - t.sin()
}

#[test]
fn rodas4_crosses_a_stiff_relaxation_in_a_twentieth_of_dopri5_s_steps() {
    // λ = −1e4: DOPRI5's steps stay at its stability limit, |hλ| ≈ 3.3, some 3,000 a
    // second (29,851 steps); RODAS4 (L-stable) steps where the accuracy puts it (1,041).
    // Both within 1e-6 of cos t.
    let (rtol, atol, t_end) = (1e-7, 1e-9, 10.0);
    let mut r = rodas::<1>(rtol, atol);
    r.init(prothero_robinson(-1e4), 0.0, &[1.0]).unwrap();
    let mut worst_r: f64 = 0.0;
    while r.step(prothero_robinson(-1e4), t_end).unwrap() != StepOutcome::ReachedStop {
        worst_r = worst_r.max((r.y()[0] - r.t().cos()).abs());
    }
    let mut d = dopri::<1>(rtol, atol);
    d.init(prothero_robinson(-1e4), 0.0, &[1.0]).unwrap();
    run_to(&mut d, prothero_robinson(-1e4), t_end);
    eprintln!(
        "stiff: rodas4 {} steps ({} rejected), worst error {worst_r:.2e}; dopri5 {} steps",
        r.n_accepted(),
        r.n_rejected(),
        d.n_accepted()
    );
    assert!(worst_r < 1e-6, "{worst_r}");
    assert!((d.y()[0] - t_end.cos()).abs() < 1e-6);
    assert!(20 * r.n_accepted() < d.n_accepted());
    // At λ = −1e9 (DOPRI5 would need some 3e9 steps) RODAS4 takes no more steps.
    let mut r9 = rodas::<1>(rtol, atol);
    r9.init(prothero_robinson(-1e9), 0.0, &[1.0]).unwrap();
    run_to(&mut r9, prothero_robinson(-1e9), t_end);
    assert!((r9.y()[0] - t_end.cos()).abs() < 1e-6);
    assert!(r9.n_accepted() <= r.n_accepted() + 5, "{}", r9.n_accepted());
}

/// A fall under a drag quadratic in the speed, state [height, vertical velocity]:
/// z'' = −g + k z'² (falling), terminal speed √(g/k).
fn quadratic_fall(g: f64, k: f64) -> impl FnMut(f64, &[f64; 2], &mut [f64; 2]) {
    move |_t, y, dy| {
        dy[0] = y[1];
        dy[1] = -g - k * y[1] * y[1].abs();
    }
}

#[test]
fn a_canopy_s_fall_lands_where_the_closed_form_says_in_a_fraction_of_dopri5_s_steps() {
    // Opening at 40 m/s down from 1000 m under a canopy of 6 m/s terminal speed: with
    // u = −z' > v_t, u(t) = v_t coth(g t / v_t + φ), φ = atanh(v_t / u₀), and the height
    // falls by (v_t² / g) ln(sinh(g t / v_t + φ) / sinh φ): the landing at
    // t = (v_t / g)(asinh(sinh φ · exp(g z₀ / v_t²)) − φ). The flight's tolerances (rtol 1e-7,
    // atol 1e-4); the landing located by Brent's method on the dense output.
    let (g, v_t, z0, u0): (f64, f64, f64, f64) = (9.80665, 6.0, 1000.0, 40.0);
    let k = g / (v_t * v_t);
    let phi = (v_t / u0).atanh();
    let t_exact = (v_t / g) * ((phi.sinh() * (g * z0 / (v_t * v_t)).exp()).asinh() - phi);
    let tol = Tolerances::new(1e-7, [1e-4, 1e-4]).unwrap();
    let mut r = Rodas4::with_tolerances(tol);
    r.init(quadratic_fall(g, k), 0.0, &[z0, -u0]).unwrap();
    let t_r = land(&mut r, quadratic_fall(g, k));
    let steps_r = r.n_accepted();
    let mut d = Dopri54::with_tolerances(tol);
    d.init(quadratic_fall(g, k), 0.0, &[z0, -u0]).unwrap();
    let t_d = land(&mut d, quadratic_fall(g, k));
    eprintln!(
        "canopy fall: exact landing {t_exact:.9} s; rodas4 {t_r:.9} s in {steps_r} steps; \
         dopri5 {t_d:.9} s in {} steps",
        d.n_accepted()
    );
    assert!((t_r - t_exact).abs() < 1e-5, "{}", t_r - t_exact);
    assert!((t_d - t_exact).abs() < 1e-5, "{}", t_d - t_exact);
    assert!(4 * steps_r < d.n_accepted());
}

/// Step until the height crosses 0 and return when, located on the dense output.
fn land<S: DenseStepper<2>>(s: &mut S, mut f: impl FnMut(f64, &[f64; 2], &mut [f64; 2])) -> f64 {
    loop {
        let out = s.step(&mut f, 1000.0).unwrap();
        let hit = locate_event(&*s, |_t, y: &[f64; 2]| y[0], Crossing::Falling, 1e-12).unwrap();
        if let Some(t) = hit {
            return t;
        }
        assert_ne!(out, StepOutcome::ReachedStop, "never landed");
    }
}
