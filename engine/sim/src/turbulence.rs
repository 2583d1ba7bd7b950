//! Wind turbulence as OpenRocket models it (its `PinkNoiseWindModel`): the wind's speed
//! wanders about its mean as pink noise, its direction kept. OpenRocket's turbulence
//! intensity `I` is the speed's standard deviation over its mean (10 % by default there).
//!
//! The noise is OpenRocket's: Kasdin's two-pole approximation of `1/f^α` noise with `α = 5/3`
//! (Kolmogorov's spectrum), sampled every [`GUST_INTERVAL_S`] (0.05 s) and interpolated
//! linearly between the samples. Two poles make it the AR(2) process
//! `x_k = φ₁ x_{k−1} + φ₂ x_{k−2} + w_k`, `w_k` standard normal, `φ₁ = α/2 = 5/6`,
//! `φ₂ = (α/2)(1 − α/2)/2 = 5/72`, whose standard deviation [`pink_std`] (2.25255; OpenRocket
//! rounds it to 2.252) divides it to unit variance. hpr-mc starts the process from its
//! stationary distribution (OpenRocket runs ten values from zero, which leaves the first
//! seconds' variance about 15 % short).
//!
//! Here the noise multiplies the wind: the air's velocity at height `h` and time `t` is
//! `w(h) · (1 + I x(t))`. In a constant wind that is OpenRocket's `average + σ x(t)` with
//! `σ = I · average`; in a profile each height's wind gusts in proportion, along its own
//! direction. The noise does not depend on height (OpenRocket's neither), so it adds no shear.
//!
//! A flight's noise is a function of its seed (the flight's noise seed, which its barometers
//! share, on a stream of its own), and of nothing else: the single flight and a batch lane
//! draw the same gusts. The whole flight's samples, to its time limit, are drawn once when the
//! flight is set up ([`Gusts::new`]); the kernels read them. Every sample is a stop time of
//! the integrator, so a step lies within one straight piece of the gusts and the
//! Dormand–Prince error control sees a smooth wind.

use rand_distr::{Distribution, StandardNormal};

/// Time between the noise's samples, s (OpenRocket's `DELTA_T`).
pub const GUST_INTERVAL_S: f64 = 0.05;

/// The AR(2) coefficients of Kasdin's two-pole pink noise for `α = 5/3`.
pub const PINK_PHI: [f64; 2] = [5.0 / 6.0, 5.0 / 72.0];

/// The largest turbulence intensity accepted: a standard deviation as large as the mean.
pub const MAX_TURBULENCE_INTENSITY: f64 = 1.0;

/// The longest time limit of a flight in a turbulent wind, s (two hours): its gusts are drawn
/// to the time limit when the flight is set up (1.15 MB at this limit), so a limit without a
/// ceiling would draw without end.
pub const MAX_TURBULENT_FLIGHT_S: f64 = 7200.0;

/// The stream of the flight's seed the gusts draw from (the barometers take 0, 1, … by
/// their parachute's place in its list).
const GUST_STREAM: u64 = u64::MAX;

/// The stationary variance and lag-one correlation of the AR(2) process `φ`.
pub fn pink_variance_and_correlation() -> (f64, f64) {
    let [p1, p2] = PINK_PHI;
    let var = (1.0 - p2) / ((1.0 + p2) * ((1.0 - p2).powi(2) - p1 * p1));
    (var, p1 / (1.0 - p2))
}

/// The stationary standard deviation of the pink noise before it is scaled (2.25255).
pub fn pink_std() -> f64 {
    pink_variance_and_correlation().0.sqrt()
}

/// One flight's gusts: the wind's factor `1 + I x_k` at every sample `t_k = k ·`
/// [`GUST_INTERVAL_S`] from liftoff to past the time limit.
#[derive(Debug, Clone, PartialEq)]
pub struct Gusts {
    factors: Vec<f64>,
}

impl Gusts {
    /// The gusts of intensity `intensity` (`0 <` it `<=` [`MAX_TURBULENCE_INTENSITY`], checked
    /// by the wind) of the flight with noise seed `seed`, drawn to `duration_s`.
    pub fn new(intensity: f64, seed: u64, duration_s: f64) -> Gusts {
        let mut rng = crate::sensor::noise_rng(seed, GUST_STREAM);
        let mut normal = || -> f64 { StandardNormal.sample(&mut rng) };
        let (var, rho) = pink_variance_and_correlation();
        let std = var.sqrt();
        // (x_{k−2}, x_{k−1}) from the process's stationary law.
        let mut x2 = std * normal();
        let mut x1 = rho * x2 + std * (1.0 - rho * rho).sqrt() * normal();
        let n = (duration_s / GUST_INTERVAL_S).ceil().max(0.0) as usize + 2;
        let scale = intensity / std;
        let factors = (0..n)
            .map(|_| {
                let x = PINK_PHI[0] * x1 + PINK_PHI[1] * x2 + normal();
                (x2, x1) = (x1, x);
                1.0 + scale * x
            })
            .collect();
        Gusts { factors }
    }

    /// The samples' factors, `1 + I x_k`.
    pub fn factors(&self) -> &[f64] {
        &self.factors
    }

    /// The wind's factor at `t` (s after liftoff): linear between the samples, the last
    /// sample's after them (a flight ends at its time limit, inside the table).
    #[inline]
    pub fn factor(&self, t: f64) -> f64 {
        let last = self.factors.len() - 1;
        let u = (t / GUST_INTERVAL_S).max(0.0);
        let k = u.floor();
        if k >= last as f64 {
            return self.factors[last];
        }
        let k_us = k as usize;
        let a = (t - k * GUST_INTERVAL_S) / GUST_INTERVAL_S;
        let (f0, f1) = (self.factors[k_us], self.factors[k_us + 1]);
        f0 + (f1 - f0) * a
    }

    /// The first sample after `t`: a stop time of the integrator.
    #[inline]
    pub fn next_sample_s(&self, t: f64) -> f64 {
        let mut k = (t / GUST_INTERVAL_S).floor().max(0.0) + 1.0;
        while k * GUST_INTERVAL_S <= t {
            k += 1.0;
        }
        k * GUST_INTERVAL_S
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_two_pole_pink_noise_has_openrockets_standard_deviation() {
        // OpenRocket's STDDEV = 2.252 for α = 5/3 and two poles; the AR(2) law gives it
        // exactly: γ₀ = (1 − φ₂) / ((1 + φ₂)((1 − φ₂)² − φ₁²)).
        let s = pink_std();
        assert!((s - 2.252).abs() < 1e-3, "{s}");
        assert!((s - 2.25255).abs() < 5e-6, "{s}");
        // Kasdin's coefficients a_k = (k − 1 − α/2) a_{k−1} / k, a_0 = 1, negated.
        let alpha = 5.0 / 3.0;
        let a1 = -alpha / 2.0;
        let a2 = (1.0 - alpha / 2.0) * a1 / 2.0;
        // (to rounding: 5/3/2 and 5/6 are one ulp apart in binary).
        assert!((-a1 - PINK_PHI[0]).abs() < 1e-15 && (-a2 - PINK_PHI[1]).abs() < 1e-15);
    }

    #[test]
    fn gusts_have_the_intensity_asked_for_and_a_mean_factor_of_one() {
        // 2,000 s of 10 % turbulence: 40,000 samples. The pink noise's samples are
        // correlated (lag one 0.895), so the mean's standard error is about
        // 0.1 · sqrt((1 + ρ)/(1 − ρ)/n) ≈ 0.002 for a geometric decay of ρ ≈ 0.9 (a bound
        // for this spectrum's slower tail too); the tolerances are four of those.
        let g = Gusts::new(0.1, 7, 2000.0);
        let f = g.factors();
        let n = f.len() as f64;
        let mean = f.iter().sum::<f64>() / n;
        let var = f.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
        assert!((mean - 1.0).abs() < 0.008, "mean {mean}");
        assert!((var.sqrt() - 0.1).abs() < 0.01, "std {}", var.sqrt());
        // The lag-one correlation is the process's φ₁/(1 − φ₂).
        let rho = f
            .windows(2)
            .map(|w| (w[0] - mean) * (w[1] - mean))
            .sum::<f64>()
            / (n - 1.0)
            / var;
        let want = pink_variance_and_correlation().1;
        assert!((rho - want).abs() < 0.01, "{rho} against {want}");
    }

    #[test]
    fn gusts_are_a_function_of_the_seed_alone_and_linear_between_samples() {
        let a = Gusts::new(0.2, 42, 10.0);
        assert_eq!(a, Gusts::new(0.2, 42, 10.0));
        assert_ne!(a, Gusts::new(0.2, 43, 10.0));
        // A longer flight draws the same first samples.
        assert_eq!(
            a.factors(),
            &Gusts::new(0.2, 42, 30.0).factors()[..a.factors().len()]
        );
        assert_eq!(a.factors().len(), 202);
        let f = a.factors();
        assert_eq!(a.factor(0.0), f[0]);
        assert!((a.factor(0.1) - f[2]).abs() < 1e-15);
        let mid = a.factor(0.125);
        assert!((mid - 0.5 * (f[2] + f[3])).abs() < 1e-15, "{mid}");
        assert_eq!(a.factor(1e9), f[f.len() - 1]);
        // The stops: every sample after t, never t itself.
        assert_eq!(a.next_sample_s(0.0), 0.05);
        assert_eq!(a.next_sample_s(0.05), 0.1);
        assert_eq!(a.next_sample_s(0.07), 0.1);
        let t = 3.0 * GUST_INTERVAL_S;
        assert!(a.next_sample_s(t) > t + 0.04);
    }
}
