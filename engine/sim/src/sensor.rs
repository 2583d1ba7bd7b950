//! Sensor noise on a parachute's flight computer (RocketPy's `Parachute(noise=(bias,
//! deviation, correlation))`): the barometer it fires on reads the air's static pressure plus
//! a noise, and a height trigger fires at the first sample at which the height that reading
//! means is below the trigger's height, on the way down.
//!
//! **The noise.** Sample `k` of the flight computer (at `k / rate` s from launch, as every
//! sampled trigger here) reads `p(z_k) + n_k`, with RocketPy's process:
//!
//! ```text
//! n₋₁ = b + σ Z₋₁,      n_k = α n_{k−1} + β (b + σ Z_k),      β = √(1 − α²),  Z ~ N(0, 1)
//! ```
//!
//! (`b` the bias, `σ` the deviation, `α` the correlation of successive samples). Every `n_k` is
//! normal with deviation σ; its mean moves from `b` towards `β b / (1 − α)`, which is `b` when
//! the samples are uncorrelated (as in RocketPy, a bias with a correlation is not the mean it
//! settles to; RocketPy's own example has no bias). The process is Markov, and `m` samples on
//! from `n_k` it is normal with mean `αᵐ n_k + β b (1 − αᵐ)/(1 − α)` and deviation
//! `σ √(1 − α²ᵐ)`: [`NoiseProcess::at`] draws a sample from the last one drawn in one draw,
//! whatever the gap, so a flight draws only the samples it reads, and its noise has exactly
//! RocketPy's law at each of them.
//!
//! **The reading.** `p + n` means a height below the trigger's `h` exactly when
//! `p + n > p(h)` (pressure falls with height), so the trigger is judged in pressure: the
//! barometric inversion RocketPy makes is not needed, and the pressures are the atmosphere's
//! own (its exact layers, not the flight's table of density and speed of sound). Before
//! apogee nothing fires (RocketPy also asks for a falling vertical speed); after it the
//! rocket descends, so the lowest point of a step is its end, and a step whose end is still
//! more than [`NoiseProcess::ceiling_pa`] of pressure above the trigger's cannot fire: its
//! samples are not drawn at all. The ceiling is 12 deviations above the largest mean the
//! noise can reach: the chance that a sample passed over this way would have fired is below
//! 2e-33.
//!
//! **Seeds.** A flight's noise depends on its sensor seed ([`crate::Simulation::with_sensor_seed`])
//! and the parachute's place in its list only: ChaCha8 keyed by the seed (its 8
//! little-endian bytes, the rest of the key zero), stream = the parachute's index. A batch
//! lane and the single flight of the same inputs draw the same numbers.

use rand::rngs::ChaCha8Rng;
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};

/// Deviations above the largest mean the noise can reach beyond which a sample is taken not to
/// fire (P(Z > 12) ≈ 1.8e-33).
const CEILING_DEVIATIONS: f64 = 12.0;

/// The noise of a flight computer's pressure reading, Pa (RocketPy's `noise` tuple).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorNoise {
    /// `b`, Pa: the mean of the first reading's noise (see the module docs for what it
    /// settles to when `correlation` is not 0).
    pub bias_pa: f64,
    /// `σ`, Pa: the deviation of every reading's noise.
    pub std_pa: f64,
    /// `α`: the correlation of successive readings' noise, from −1 to 1.
    pub correlation: f64,
}

impl SensorNoise {
    /// Check the numbers: the field broken, the rule and the value given, if any.
    pub fn check(&self) -> Result<(), (&'static str, &'static str, f64)> {
        if !self.bias_pa.is_finite() {
            return Err(("bias_pa", "must be finite", self.bias_pa));
        }
        if !(self.std_pa.is_finite() && self.std_pa >= 0.0) {
            return Err(("std_pa", "must be finite and not negative", self.std_pa));
        }
        if !(-1.0..=1.0).contains(&self.correlation) {
            return Err(("correlation", "must be from -1 to 1", self.correlation));
        }
        Ok(())
    }

    /// `β = √(1 − α²)`.
    fn beta(&self) -> f64 {
        (1.0 - self.correlation * self.correlation).max(0.0).sqrt()
    }

    /// The mean the noise settles to, Pa: `β b / (1 − α)` (`b` with uncorrelated samples; the
    /// first reading's mean `b` when `α = 1`, which never moves).
    pub fn settled_mean_pa(&self) -> f64 {
        let a = self.correlation;
        if a == 1.0 {
            self.bias_pa
        } else {
            self.beta() * self.bias_pa / (1.0 - a)
        }
    }
}

/// One parachute's noise through one flight: the last sample drawn and its noise.
#[derive(Debug)]
pub struct NoiseProcess {
    noise: SensorNoise,
    rng: ChaCha8Rng,
    /// The last sample drawn (−1: RocketPy's draw before the first sample).
    k: i64,
    n_pa: f64,
    /// `|β b| / (1 − |α|)`, or 0 when `|α| = 1` (β = 0): how far the mean can move from `n`'s.
    drift_pa: f64,
}

/// A copy that draws what this one would draw next (the generator is not `Clone`: rand
/// keeps a generator from being copied by accident; here the copy is the point, the same
/// key, stream and position).
impl Clone for NoiseProcess {
    fn clone(&self) -> NoiseProcess {
        let mut rng = ChaCha8Rng::from_seed(self.rng.get_seed());
        rng.set_stream(self.rng.get_stream());
        rng.set_word_pos(self.rng.get_word_pos());
        NoiseProcess {
            noise: self.noise,
            rng,
            k: self.k,
            n_pa: self.n_pa,
            drift_pa: self.drift_pa,
        }
    }
}

/// The generator of a flight's noise: ChaCha8 keyed by the flight's seed, on `stream` (a
/// parachute's place in its list; the wind's gusts take their own).
pub(crate) fn noise_rng(seed: u64, stream: u64) -> ChaCha8Rng {
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    let mut rng = ChaCha8Rng::from_seed(key);
    rng.set_stream(stream);
    rng
}

impl NoiseProcess {
    /// The noise of the flight with sensor seed `seed`, for the parachute at `index` in its
    /// list (see the module docs).
    pub fn new(noise: SensorNoise, seed: u64, index: u64) -> NoiseProcess {
        let mut rng = noise_rng(seed, index);
        let z: f64 = StandardNormal.sample(&mut rng);
        let a = noise.correlation.abs();
        let drift_pa = if a < 1.0 {
            (noise.beta() * noise.bias_pa).abs() / (1.0 - a)
        } else {
            0.0
        };
        NoiseProcess {
            noise,
            rng,
            k: -1,
            n_pa: noise.bias_pa + noise.std_pa * z,
            drift_pa,
        }
    }

    /// The last sample drawn.
    pub fn last_sample(&self) -> i64 {
        self.k
    }

    /// The noise at sample `k`, Pa: the last one drawn again if `k` is it, else one draw from
    /// its law given the last one drawn (`k` must not be before it).
    pub fn at(&mut self, k: i64) -> f64 {
        debug_assert!(k >= self.k, "samples are drawn in order");
        if k <= self.k {
            return self.n_pa;
        }
        let SensorNoise {
            bias_pa: b,
            std_pa: sigma,
            correlation: a,
        } = self.noise;
        let m = (k - self.k) as f64;
        let am = a.powf(m);
        let sum = if a == 1.0 { m } else { (1.0 - am) / (1.0 - a) };
        let mean = am * self.n_pa + self.noise.beta() * b * sum;
        let sd = sigma * (1.0 - am * am).max(0.0).sqrt();
        let z: f64 = StandardNormal.sample(&mut self.rng);
        self.n_pa = mean + sd * z;
        self.k = k;
        self.n_pa
    }

    /// A ceiling of the noise at every sample after the last drawn, Pa: the largest mean it
    /// can reach from there plus `CEILING_DEVIATIONS` (12) deviations.
    pub fn ceiling_pa(&self) -> f64 {
        self.n_pa.abs() + self.drift_pa + CEILING_DEVIATIONS * self.noise.std_pa
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn moments(noise: SensorNoise, step: i64, n: usize, seed: u64) -> (f64, f64, f64) {
        let mut p = NoiseProcess::new(noise, seed, 0);
        // Far enough on that the start is forgotten (α^k negligible).
        let k0 = 1000;
        let xs: Vec<f64> = (0..n).map(|i| p.at(k0 + i as i64 * step)).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        let cov = xs
            .windows(2)
            .map(|w| (w[0] - mean) * (w[1] - mean))
            .sum::<f64>()
            / (n - 1) as f64;
        (mean, var.sqrt(), cov / var)
    }

    #[test]
    fn the_noise_has_rocketpys_settled_mean_deviation_and_correlation() {
        // 200,000 samples of an AR(1): the standard error of the mean is σ/√n · √((1+α)/(1−α))
        // (0.032 Pa here), of the deviation σ/√(2n) · √((1+α²)/(1−α²)) (0.017 Pa), of the
        // lag-one correlation √((1−α²)/n) (0.0019); the tolerances are five of them.
        let noise = SensorNoise {
            bias_pa: 2.0,
            std_pa: 8.3,
            correlation: 0.5,
        };
        let (mean, sd, rho) = moments(noise, 1, 200_000, 11);
        let settled = (0.75f64).sqrt() * 2.0 / 0.5;
        assert!((noise.settled_mean_pa() - settled).abs() < 1e-15);
        assert!(
            (mean - settled).abs() < 5.0 * 0.032,
            "mean {mean} against {settled}"
        );
        assert!((sd - 8.3).abs() < 5.0 * 0.017, "deviation {sd}");
        assert!(
            (rho - 0.5).abs() < 5.0 * 0.0019,
            "lag-one correlation {rho}"
        );
    }

    #[test]
    fn a_jump_of_m_samples_has_the_law_of_m_single_samples() {
        // Samples 3 apart: correlation α³ = 0.125, the same deviation and settled mean
        // (standard errors as above: 0.0101 Pa, 0.0064 Pa, 0.0022; tolerances five of them).
        let noise = SensorNoise {
            bias_pa: -1.0,
            std_pa: 4.0,
            correlation: 0.5,
        };
        let (mean, sd, rho) = moments(noise, 3, 200_000, 12);
        assert!(
            (mean - noise.settled_mean_pa()).abs() < 5.0 * 0.0101,
            "mean {mean}"
        );
        assert!((sd - 4.0).abs() < 5.0 * 0.0064, "deviation {sd}");
        assert!((rho - 0.125).abs() < 5.0 * 0.0022, "correlation {rho}");
    }

    #[test]
    fn a_noise_without_deviation_follows_the_recurrence_exactly() {
        // σ = 0: n₋₁ = b, n_k = α n_{k−1} + β b, drawn one by one or in one jump.
        let noise = SensorNoise {
            bias_pa: 10.0,
            std_pa: 0.0,
            correlation: 0.6,
        };
        let beta = 0.8;
        let mut by_hand = 10.0;
        let mut one_by_one = NoiseProcess::new(noise, 1, 0);
        for k in 0..40 {
            by_hand = 0.6 * by_hand + beta * 10.0;
            assert!((one_by_one.at(k) - by_hand).abs() < 1e-12 * by_hand.abs());
        }
        let mut jumped = NoiseProcess::new(noise, 1, 0);
        assert!((jumped.at(39) - by_hand).abs() < 1e-12 * by_hand);
        // Settled: β b / (1 − α) = 20 Pa.
        assert!((by_hand - 20.0).abs() < 1e-7);
        assert!((noise.settled_mean_pa() - 20.0).abs() < 1e-14);
    }

    #[test]
    fn the_same_seed_and_parachute_draw_the_same_noise_and_others_do_not() {
        let noise = SensorNoise {
            bias_pa: 0.0,
            std_pa: 8.3,
            correlation: 0.5,
        };
        let draw = |seed, index| {
            let mut p = NoiseProcess::new(noise, seed, index);
            (p.at(5), p.at(900))
        };
        assert_eq!(draw(7, 1), draw(7, 1));
        assert_ne!(draw(7, 1), draw(8, 1));
        assert_ne!(draw(7, 1), draw(7, 0));
    }

    #[test]
    fn bad_noise_names_its_field() {
        let ok = SensorNoise {
            bias_pa: 0.0,
            std_pa: 1.0,
            correlation: 0.0,
        };
        assert_eq!(ok.check(), Ok(()));
        let bad = |n: SensorNoise| n.check().unwrap_err().0;
        assert_eq!(bad(SensorNoise { std_pa: -1.0, ..ok }), "std_pa");
        assert_eq!(
            bad(SensorNoise {
                bias_pa: f64::NAN,
                ..ok
            }),
            "bias_pa"
        );
        assert_eq!(
            bad(SensorNoise {
                correlation: 1.5,
                ..ok
            }),
            "correlation"
        );
    }
}
