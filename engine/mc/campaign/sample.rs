//! Seeded sampling of dispersions: the distributions a scenario may give an input, and the
//! random stream each draw comes from.
//!
//! # Reproducibility
//!
//! Every draw comes from ChaCha8 (the `chacha20` crate through `rand`'s `chacha` feature), a
//! stream cipher whose output is fixed by its definition, so the numbers do not change with
//! the `rand` version. The generator is *counter based*: for one draw it is keyed by the
//! scenario's seed (its 8 little-endian bytes, the other 24 key bytes zero), its stream
//! (nonce) is the variant's stream number, and it starts at block `slot(key) × 2³²` where
//! `slot` is the FNV-1a 32-bit hash of the input's key path (`wind_speed_m_s`,
//! `parachutes.main.cds_m2`). So a draw depends only on (seed, stream, input): not on the
//! thread, the chunk, the shard, the order the variants are flown in, nor on which other
//! inputs the scenario disperses (adding a dispersion does not change the others' draws).
//! Each input has 2³² blocks (256 GiB) of stream to itself; no draw uses more than a few.
//!
//! The normal, exponential and triangular transforms are `rand_distr`'s (0.6), whose value
//! stability is part of that crate's versioning. The truncated normal is written here
//! (`rand_distr` has none), with Robert's (1995) exact rejection samplers.
//!
//! # What a dispersion means
//!
//! A dispersion scatters an input around its *center*: the scenario's nominal value, or the
//! sweep point's value when the input is also swept. Most shapes draw a deviation `d` that is
//! added to the center (`value = center + d`), or, with `relative = true`, taken as a fraction
//! of it (`value = center × (1 + d)`). A log-normal is always multiplicative:
//! `value = center × exp(mu + sigma Z)`. A normal may instead give its `mean` as a value, which
//! replaces the center.

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use rand_distr::{Distribution, Exp1, StandardNormal, Triangular};

/// The shape of a dispersion. For every shape but [`Shape::LogNormal`] the parameters
/// describe the deviation from the center (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// `d ~ N(bias, sigma²)`.
    Normal { bias: f64, sigma: f64 },
    /// `value ~ N(mean, sigma²)` whatever the center (a normal given by its mean).
    NormalAbout { mean: f64, sigma: f64 },
    /// `d ~ N(bias, sigma²)` restricted to `[min, max]` (either may be infinite).
    TruncatedNormal {
        bias: f64,
        sigma: f64,
        min: f64,
        max: f64,
    },
    /// `d ~ U(min, max)`.
    Uniform { min: f64, max: f64 },
    /// `d` triangular on `[min, max]` with its peak at `mode`.
    Triangular { min: f64, mode: f64, max: f64 },
    /// `value = center × exp(mu + sigma Z)`, Z standard normal.
    LogNormal { mu: f64, sigma: f64 },
    /// `value = first + k`, `k` uniform on `0 .. count` (a weather file's ensemble member,
    /// whatever the center).
    Members { first: f64, count: u32 },
}

/// A dispersion of one input: a shape and whether its deviation is a fraction of the center.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dispersion {
    pub shape: Shape,
    pub relative: bool,
}

impl Dispersion {
    /// The value the draws scatter around, for an input whose center is `center`: its own
    /// mean for a normal given by its mean, else the center.
    pub fn scatter_center(&self, center: f64) -> f64 {
        match self.shape {
            Shape::NormalAbout { mean, .. } => mean,
            _ => center,
        }
    }

    /// Draw the input's value around `center`.
    pub fn sample(&self, center: f64, rng: &mut ChaCha8Rng) -> f64 {
        let d = match self.shape {
            Shape::Normal { bias, sigma } => bias + sigma * standard_normal(rng),
            Shape::NormalAbout { mean, sigma } => return mean + sigma * standard_normal(rng),
            Shape::TruncatedNormal {
                bias,
                sigma,
                min,
                max,
            } => {
                bias + sigma
                    * truncated_standard_normal((min - bias) / sigma, (max - bias) / sigma, rng)
            }
            Shape::Uniform { min, max } => min + (max - min) * unit_open(rng),
            Shape::Triangular { min, mode, max } => match Triangular::new(min, max, mode) {
                Ok(t) => t.sample(rng),
                // Checked when the scenario is read; a degenerate triangle is its one point.
                Err(_) => mode,
            },
            Shape::LogNormal { mu, sigma } => {
                return center * (mu + sigma * standard_normal(rng)).exp()
            }
            Shape::Members { first, count } => {
                let k = (f64::from(count) * unit_open(rng))
                    .floor()
                    .min(f64::from(count) - 1.0);
                return first + k;
            }
        };
        if self.relative {
            center * (1.0 + d)
        } else {
            center + d
        }
    }

    /// Whether the value depends on the center (everything but a normal given by its mean).
    pub fn uses_center(&self) -> bool {
        !matches!(
            self.shape,
            Shape::NormalAbout { .. } | Shape::Members { .. }
        )
    }

    /// Whether a center of zero makes the dispersion meaningless (relative and log-normal).
    pub fn needs_nonzero_center(&self) -> bool {
        self.relative || matches!(self.shape, Shape::LogNormal { .. })
    }

    /// The value's theoretical mean and standard deviation around `center` (used by tests and
    /// by the documentation's tables).
    pub fn moments(&self, center: f64) -> (f64, f64) {
        let (m, s) = match self.shape {
            Shape::Normal { bias, sigma } => (bias, sigma),
            Shape::NormalAbout { mean, sigma } => return (mean, sigma),
            Shape::TruncatedNormal {
                bias,
                sigma,
                min,
                max,
            } => {
                let (m, s) = truncated_standard_moments((min - bias) / sigma, (max - bias) / sigma);
                (bias + sigma * m, sigma * s)
            }
            Shape::Uniform { min, max } => (0.5 * (min + max), (max - min) / 12f64.sqrt()),
            Shape::Triangular { min, mode, max } => {
                let var =
                    (min * min + mode * mode + max * max - min * mode - min * max - mode * max)
                        / 18.0;
                ((min + mode + max) / 3.0, var.sqrt())
            }
            Shape::Members { first, count } => {
                let n = f64::from(count);
                return (first + 0.5 * (n - 1.0), ((n * n - 1.0) / 12.0).sqrt());
            }
            Shape::LogNormal { mu, sigma } => {
                let m = (mu + 0.5 * sigma * sigma).exp();
                let v = ((sigma * sigma).exp() - 1.0) * (2.0 * mu + sigma * sigma).exp();
                return (center * m, center.abs() * v.sqrt());
            }
        };
        if self.relative {
            (center * (1.0 + m), center.abs() * s)
        } else {
            (center + m, s)
        }
    }
}

/// FNV-1a, 32 bits, of `key`: the block slot of an input's stream.
pub fn slot(key: &str) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for b in key.bytes() {
        h ^= u32::from(b);
        h = h.wrapping_mul(0x0100_0193);
    }
    h
}

/// FNV-1a, 64 bits, of `bytes`, as 16 hex digits: the scenario text's fingerprint in the
/// output files (an identifier, not a cryptographic hash).
pub fn fingerprint(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// The generator of one input's draws for one variant: ChaCha8 keyed by `seed`, stream
/// `stream`, starting at block `slot(key) × 2³²` (see the module docs).
pub fn input_rng(seed: u64, stream: u64, key: &str) -> ChaCha8Rng {
    let mut k = [0u8; 32];
    k[..8].copy_from_slice(&seed.to_le_bytes());
    let mut rng = ChaCha8Rng::from_seed(k);
    rng.set_stream(stream);
    rng.set_block_pos(u64::from(slot(key)) << 32);
    rng
}

fn standard_normal(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}

/// Uniform on (0, 1): 53 random bits, never 0 (so logarithms are finite).
fn unit_open(rng: &mut ChaCha8Rng) -> f64 {
    ((rng.random::<u64>() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
}

/// A standard normal restricted to `[a, b]` (a < b, either infinite), by exact rejection:
/// C. P. Robert, "Simulation of truncated normal variables", Statistics and Computing 5
/// (1995) 121–125. Every branch accepts a proposal with probability above 0.2, so the loops
/// end after a few tries.
pub fn truncated_standard_normal(a: f64, b: f64, rng: &mut ChaCha8Rng) -> f64 {
    if b <= 0.0 {
        // Mirror the lower tail onto the upper one.
        return -truncated_standard_normal(-b, -a, rng);
    }
    if a <= 0.0 {
        // The interval holds 0.
        if b - a >= 2.5066282746310002 {
            // Wide (at least √(2π)): plain rejection from the normal accepts at least 49 %.
            loop {
                let z = standard_normal(rng);
                if z >= a && z <= b {
                    return z;
                }
            }
        }
        // Narrow: uniform proposal, accept with exp(−z²/2).
        loop {
            let z = a + (b - a) * unit_open(rng);
            if unit_open(rng) <= (-0.5 * z * z).exp() {
                return z;
            }
        }
    }
    // 0 < a < b: the upper tail. Robert's translated exponential proposal with his optimal
    // rate α accepts at least 76 % of the whole tail; it only loses when b is within one
    // scale length 1/α of a, where a uniform proposal on [a, b] (accepted with
    // exp((a² − z²)/2) ≥ exp(−(b − a)(a + b)/2) ≥ e^(−3/2)) does better.
    let alpha = 0.5 * (a + (a * a + 4.0).sqrt());
    if b.is_finite() && b - a < 1.0 / alpha {
        loop {
            let z = a + (b - a) * unit_open(rng);
            if unit_open(rng) <= (0.5 * (a * a - z * z)).exp() {
                return z;
            }
        }
    }
    loop {
        let e: f64 = Exp1.sample(rng);
        let z = a + e / alpha;
        if z <= b && unit_open(rng) <= (-0.5 * (z - alpha) * (z - alpha)).exp() {
            return z;
        }
    }
}

/// Standard normal density.
pub fn normal_pdf(x: f64) -> f64 {
    if x.is_infinite() {
        return 0.0;
    }
    (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt()
}

/// Standard normal distribution function, from the complementary error function
/// (W. J. Cody's rational approximations as in Numerical Recipes' `erfc`, |error| < 1.2e-7),
/// enough for the test tolerances it serves.
pub fn normal_cdf(x: f64) -> f64 {
    if x == f64::INFINITY {
        return 1.0;
    }
    if x == f64::NEG_INFINITY {
        return 0.0;
    }
    0.5 * erfc(-x / std::f64::consts::SQRT_2)
}

fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let r = t
        * (-z * z - 1.265_512_23
            + t * (1.000_023_68
                + t * (0.374_091_96
                    + t * (0.096_784_18
                        + t * (-0.186_288_06
                            + t * (0.278_868_07
                                + t * (-1.135_203_98
                                    + t * (1.488_515_87
                                        + t * (-0.822_152_23 + t * 0.170_872_77)))))))))
            .exp();
    if x >= 0.0 {
        r
    } else {
        2.0 - r
    }
}

/// Mean and standard deviation of a standard normal restricted to `[a, b]`.
pub fn truncated_standard_moments(a: f64, b: f64) -> (f64, f64) {
    let z = normal_cdf(b) - normal_cdf(a);
    let (pa, pb) = (normal_pdf(a), normal_pdf(b));
    let mean = (pa - pb) / z;
    let apa = if a.is_finite() { a * pa } else { 0.0 };
    let bpb = if b.is_finite() { b * pb } else { 0.0 };
    let var = 1.0 + (apa - bpb) / z - mean * mean;
    (mean, var.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn draws(d: &Dispersion, center: f64, n: u64) -> Vec<f64> {
        (0..n)
            .map(|i| d.sample(center, &mut input_rng(7, i, "x")))
            .collect()
    }

    fn mean_std(v: &[f64]) -> (f64, f64) {
        let n = v.len() as f64;
        let m = v.iter().sum::<f64>() / n;
        let s = (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0)).sqrt();
        (m, s)
    }

    /// With n draws the sample mean's standard error is σ/√n; we allow 4.5 of them. The
    /// sample standard deviation's standard error is σ √((κ − 1)/(4n)) for kurtosis κ
    /// (σ/√(2n) for a normal); we allow 4.5 × 1.5 × σ/√(2n), which is at least 4.5 standard
    /// errors for every κ up to 5.5 (all shapes tested here). A correct sampler fails one of
    /// these checks with probability below 1e-5.
    fn check_moments(d: Dispersion, center: f64) {
        let n = 100_000;
        let v = draws(&d, center, n);
        let (m, s) = mean_std(&v);
        let (em, es) = d.moments(center);
        let tol_m = 4.5 * es / (n as f64).sqrt();
        let tol_s = 4.5 * es / (2.0 * n as f64).sqrt() * 1.5;
        assert!(
            (m - em).abs() < tol_m,
            "{d:?}: mean {m} expected {em} ± {tol_m}"
        );
        assert!(
            (s - es).abs() < tol_s,
            "{d:?}: std {s} expected {es} ± {tol_s}"
        );
    }

    #[test]
    fn the_same_seed_variant_and_input_give_the_same_draw_and_others_differ() {
        let d = Dispersion {
            shape: Shape::Normal {
                bias: 0.0,
                sigma: 1.0,
            },
            relative: false,
        };
        let a = d.sample(10.0, &mut input_rng(42, 17, "wind_speed_m_s"));
        let b = d.sample(10.0, &mut input_rng(42, 17, "wind_speed_m_s"));
        assert_eq!(a.to_bits(), b.to_bits());
        assert_ne!(a, d.sample(10.0, &mut input_rng(43, 17, "wind_speed_m_s")));
        assert_ne!(a, d.sample(10.0, &mut input_rng(42, 18, "wind_speed_m_s")));
        assert_ne!(a, d.sample(10.0, &mut input_rng(42, 17, "wind_from_deg")));
    }

    #[test]
    fn the_stream_is_chacha8_keyed_by_the_seed_so_its_first_word_is_fixed() {
        // The first 64-bit word of ChaCha8 with a zero key, stream 0, block 0. If this
        // changes, every scenario's numbers change: the generator is not the one documented.
        let mut rng = ChaCha8Rng::from_seed([0u8; 32]);
        let first: u64 = rng.random();
        let mut ours = input_rng(0, 0, "");
        // slot("") is the FNV offset basis, so ours starts elsewhere in the same stream:
        ours.set_block_pos(0);
        assert_eq!(first, ours.random::<u64>());
        // ChaCha8's keystream block 0 for the all-zero key and nonce starts 3e 00 ef 2f
        // 89 5f 40 d6 (the published ChaCha8 test vector, Bernstein's reference code).
        assert_eq!(
            first,
            u64::from_le_bytes([0x3e, 0x00, 0xef, 0x2f, 0x89, 0x5f, 0x40, 0xd6])
        );
    }

    #[test]
    fn a_normal_has_its_mean_and_sigma_in_100k_draws() {
        check_moments(
            Dispersion {
                shape: Shape::Normal {
                    bias: 0.5,
                    sigma: 2.0,
                },
                relative: false,
            },
            10.0,
        );
        check_moments(
            Dispersion {
                shape: Shape::NormalAbout {
                    mean: 6500.0,
                    sigma: 1000.0,
                },
                relative: false,
            },
            6026.0,
        );
    }

    #[test]
    fn a_relative_normal_scales_with_the_center() {
        let d = Dispersion {
            shape: Shape::Normal {
                bias: 0.0,
                sigma: 0.05,
            },
            relative: true,
        };
        check_moments(d, 200.0);
        assert_eq!(d.moments(200.0), (200.0, 10.0));
    }

    #[test]
    fn a_uniform_and_a_triangular_have_their_moments_in_100k_draws() {
        check_moments(
            Dispersion {
                shape: Shape::Uniform {
                    min: -1.0,
                    max: 3.0,
                },
                relative: false,
            },
            0.0,
        );
        check_moments(
            Dispersion {
                shape: Shape::Triangular {
                    min: -1.0,
                    mode: 0.0,
                    max: 2.0,
                },
                relative: false,
            },
            5.0,
        );
    }

    #[test]
    fn a_lognormal_has_its_moments_in_100k_draws() {
        check_moments(
            Dispersion {
                shape: Shape::LogNormal {
                    mu: 0.0,
                    sigma: 0.2,
                },
                relative: false,
            },
            3.0,
        );
    }

    #[test]
    fn a_truncated_normal_has_its_moments_and_stays_in_its_bounds() {
        let cases = [
            (0.0, 1.0, -1.0, 1.0),              // narrow, holding 0
            (0.0, 1.0, -3.0, 4.0),              // wide, holding 0
            (0.0, 1.0, 1.5, f64::INFINITY),     // upper tail
            (0.0, 1.0, 3.0, 3.2),               // short piece of the tail
            (0.2, 0.5, f64::NEG_INFINITY, 0.0), // lower tail, mirrored
            (0.0, 2.0, 0.5, 9.0),               // long piece of the tail
        ];
        for (bias, sigma, min, max) in cases {
            let d = Dispersion {
                shape: Shape::TruncatedNormal {
                    bias,
                    sigma,
                    min,
                    max,
                },
                relative: false,
            };
            let v = draws(&d, 1.0, 100_000);
            assert!(
                v.iter().all(|x| *x >= 1.0 + min && *x <= 1.0 + max),
                "{d:?} left its bounds"
            );
            check_moments(d, 1.0);
        }
    }

    #[test]
    fn the_normal_distribution_function_matches_tabulated_values() {
        // Abramowitz & Stegun table 26.1: Φ(1) = 0.8413447, Φ(1.96) = 0.9750021, Φ(−2.5) = 0.0062097.
        assert!((normal_cdf(1.0) - 0.841_344_7).abs() < 2e-7);
        assert!((normal_cdf(1.96) - 0.975_002_1).abs() < 2e-7);
        assert!((normal_cdf(-2.5) - 0.006_209_7).abs() < 2e-7);
    }

    #[test]
    fn the_fingerprint_is_fnv1a_64() {
        // FNV-1a 64 of "a" is af63dc4c8601ec8c (the published test vector).
        assert_eq!(fingerprint(b"a"), "af63dc4c8601ec8c");
        assert_eq!(fingerprint(b""), "cbf29ce484222325");
        // FNV-1a 32 of "a" is e40c292c.
        assert_eq!(slot("a"), 0xe40c_292c);
    }
}
