//! Variants: the sweep grid × the variants of each point, each variant a row of every input's
//! value, and how the rows are cut into shards and chunks.
//!
//! Variant `id` runs over `0 .. points × variants_per_point`: its sweep point is
//! `id / variants_per_point` and its replicate `id % variants_per_point`. Points are numbered
//! with the swept inputs in canonical order, the last one varying fastest. An input's value is
//! its sweep value at the point (or its nominal), scattered by its dispersion with draws from
//! stream `replicate` (common random numbers: replicate r of every point sees the same random
//! numbers, so differences between sweep points are not drowned in noise) or stream `id`
//! (independent points). Either way a variant's values depend only on (seed, id).
//!
//! A shard K of N takes the variants `id ≡ K (mod N)` (interleaved, so that every shard gets
//! its share of every sweep point and the shards take about as long); its variants are cut in
//! order into chunks of `chunk_size`, the unit of work and of resumption.

use super::sample::{input_rng, Dispersion};
use rand::RngExt;

/// One input as the variants need it: its nominal (the center when it is not swept), its
/// sweep and its dispersion.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanInput {
    pub key: String,
    pub nominal: f64,
    pub sweep: Option<Vec<f64>>,
    pub dispersion: Option<Dispersion>,
    /// Whether its scattered value stays on its center's side of zero (a shift's travel: a
    /// scatter shortens or lengthens the move, never reverses it or makes one from none).
    pub keeps_side: bool,
}

/// Everything that decides the variants' values.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    pub seed: u64,
    pub variants_per_point: u64,
    pub common_random_numbers: bool,
    pub inputs: Vec<PlanInput>,
}

/// One variant: its id, sweep point, replicate, and the value of every input of the plan (in
/// the plan's order).
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    pub id: u64,
    pub point: usize,
    pub replicate: u64,
    pub values: Vec<f64>,
    /// The seed of its parachutes' barometer noise: drawn from the same stream as its
    /// values (key `sensor_noise`), so it too depends only on (seed, id), and with common
    /// random numbers replicate r of every point reads the same noise.
    pub sensor_seed: u64,
}

/// Number of points of a sweep whose inputs' values are `sweeps` (`None` for an input not
/// swept): the product of the swept inputs' counts, 1 without a sweep.
pub fn sweep_points<'a>(sweeps: impl Iterator<Item = Option<&'a Vec<f64>>>) -> usize {
    sweeps.flatten().map(Vec::len).product()
}

impl Plan {
    /// Number of sweep points.
    pub fn points(&self) -> usize {
        sweep_points(self.inputs.iter().map(|i| i.sweep.as_ref()))
    }

    /// Number of variants.
    pub fn total(&self) -> u64 {
        self.points() as u64 * self.variants_per_point
    }

    /// For each input, the index of its value in its sweep at `point` (`None` if not swept).
    pub fn point_indices(&self, point: usize) -> Vec<Option<usize>> {
        let mut rest = point;
        let mut idx = vec![None; self.inputs.len()];
        for (j, input) in self.inputs.iter().enumerate().rev() {
            if let Some(s) = &input.sweep {
                idx[j] = Some(rest % s.len());
                rest /= s.len();
            }
        }
        idx
    }

    /// The center of every input at `point`: its sweep value there, or its nominal.
    pub fn centers(&self, point: usize) -> Vec<f64> {
        self.point_indices(point)
            .iter()
            .zip(&self.inputs)
            .map(|(k, input)| match (k, &input.sweep) {
                (Some(k), Some(s)) => s[*k],
                _ => input.nominal,
            })
            .collect()
    }

    /// The swept inputs' values at `point`, in order.
    pub fn sweep_values(&self, point: usize) -> Vec<f64> {
        self.centers(point)
            .into_iter()
            .zip(&self.inputs)
            .filter(|(_, i)| i.sweep.is_some())
            .map(|(c, _)| c)
            .collect()
    }

    /// The value of `input`, centered on `center`, drawn from the random numbers `stream`.
    fn draw(&self, input: &PlanInput, center: f64, stream: u64) -> f64 {
        match &input.dispersion {
            Some(d) => {
                let v = d.sample(center, &mut input_rng(self.seed, stream, &input.key));
                if input.keeps_side {
                    on_side_of(d.scatter_center(center), v)
                } else {
                    v
                }
            }
            None => center,
        }
    }

    /// The value of input `j` (in the plan's order) of replicate `replicate` at sweep point
    /// `point` with common random numbers: [`Plan::variant`]'s `values[j]` for that variant,
    /// without drawing the others. `centers` is [`Plan::centers`] at `point`.
    pub fn common_value(&self, centers: &[f64], replicate: u64, j: usize) -> f64 {
        self.draw(&self.inputs[j], centers[j], replicate)
    }

    /// Variant `id` (which must be below [`Plan::total`]).
    pub fn variant(&self, id: u64) -> Variant {
        let point = (id / self.variants_per_point) as usize;
        let replicate = id % self.variants_per_point;
        let stream = if self.common_random_numbers {
            replicate
        } else {
            id
        };
        let values = self
            .centers(point)
            .into_iter()
            .zip(&self.inputs)
            .map(|(c, input)| self.draw(input, c, stream))
            .collect();
        Variant {
            id,
            point,
            replicate,
            values,
            sensor_seed: input_rng(self.seed, stream, "sensor_noise").random(),
        }
    }
}

/// `v` held on `center`'s side of zero (the value its draws scatter around): 0 if it crossed,
/// 0 if the center is 0.
fn on_side_of(center: f64, v: f64) -> f64 {
    if center > 0.0 {
        v.max(0.0)
    } else if center < 0.0 {
        v.min(0.0)
    } else {
        0.0
    }
}

/// Shard K of N: the variants `id ≡ K (mod N)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub k: u64,
    pub n: u64,
}

impl Shard {
    /// The whole run.
    pub const ALL: Shard = Shard { k: 0, n: 1 };

    /// Parse `K/N` (0 ≤ K < N).
    pub fn parse(s: &str) -> Result<Shard, String> {
        let (k, n) = s
            .split_once('/')
            .ok_or_else(|| format!("--shard must be K/N, for instance 0/4 (got \"{s}\")"))?;
        let k: u64 = k
            .trim()
            .parse()
            .map_err(|_| format!("--shard K/N: K must be a whole number (got \"{k}\")"))?;
        let n: u64 = n
            .trim()
            .parse()
            .map_err(|_| format!("--shard K/N: N must be a whole number (got \"{n}\")"))?;
        if n == 0 || k >= n {
            return Err(format!("--shard K/N needs 0 <= K < N (got {k}/{n})"));
        }
        Ok(Shard { k, n })
    }

    /// How many of `total` variants the shard takes.
    pub fn count(&self, total: u64) -> u64 {
        if self.k >= total {
            0
        } else {
            (total - self.k).div_ceil(self.n)
        }
    }

    /// The id of the shard's `q`-th variant.
    pub fn id(&self, q: u64) -> u64 {
        self.k + q * self.n
    }

    /// Whether this is the whole run.
    pub fn is_all(&self) -> bool {
        self.n == 1
    }
}

/// The shard's chunks: for chunk c, the range of the shard's positions it holds.
pub fn chunks(shard_count: u64, chunk_size: usize) -> Vec<std::ops::Range<u64>> {
    let s = chunk_size as u64;
    (0..shard_count.div_ceil(s))
        .map(|c| c * s..((c + 1) * s).min(shard_count))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::campaign::sample::Shape;

    fn plan(crn: bool) -> Plan {
        let normal = Some(Dispersion {
            shape: Shape::Normal {
                bias: 0.0,
                sigma: 1.0,
            },
            relative: false,
        });
        Plan {
            seed: 5,
            variants_per_point: 4,
            common_random_numbers: crn,
            inputs: vec![
                PlanInput {
                    key: "a".into(),
                    nominal: 1.0,
                    sweep: Some(vec![10.0, 20.0, 30.0]),
                    dispersion: None,
                    keeps_side: false,
                },
                PlanInput {
                    key: "b".into(),
                    nominal: 2.0,
                    sweep: None,
                    dispersion: normal,
                    keeps_side: false,
                },
                PlanInput {
                    key: "c".into(),
                    nominal: 3.0,
                    sweep: Some(vec![0.5, 0.7]),
                    dispersion: normal,
                    keeps_side: false,
                },
            ],
        }
    }

    #[test]
    fn points_run_over_the_grid_with_the_last_swept_input_fastest() {
        let p = plan(true);
        assert_eq!(p.points(), 6);
        assert_eq!(p.total(), 24);
        let grid: Vec<Vec<f64>> = (0..6).map(|k| p.sweep_values(k)).collect();
        assert_eq!(
            grid,
            vec![
                vec![10.0, 0.5],
                vec![10.0, 0.7],
                vec![20.0, 0.5],
                vec![20.0, 0.7],
                vec![30.0, 0.5],
                vec![30.0, 0.7]
            ]
        );
        assert_eq!(p.centers(3), vec![20.0, 2.0, 0.7]);
    }

    #[test]
    fn a_variant_holds_its_point_s_values_and_its_draws_around_them() {
        let p = plan(true);
        let v = p.variant(13); // point 3, replicate 1
        assert_eq!((v.point, v.replicate), (3, 1));
        assert_eq!(v.values[0], 20.0);
        let d = p.inputs[1].dispersion.unwrap();
        assert_eq!(v.values[1], d.sample(2.0, &mut input_rng(5, 1, "b")));
        assert_eq!(v.values[2], d.sample(0.7, &mut input_rng(5, 1, "c")));
    }

    #[test]
    fn with_common_random_numbers_every_point_sees_the_same_draws() {
        let p = plan(true);
        let (a, b) = (p.variant(1), p.variant(1 + 4 * 5)); // replicate 1 of points 0 and 5
        assert_eq!(a.values[1], b.values[1]);
        assert!((a.values[2] - 0.5 - (b.values[2] - 0.7)).abs() < 1e-15);
        let q = plan(false);
        assert_ne!(q.variant(1).values[1], q.variant(21).values[1]);
    }

    #[test]
    fn a_value_that_keeps_its_side_is_held_at_zero_and_a_zero_center_stays_zero() {
        // A swept travel of 0, 0.001 and −0.001 m, scattered by σ = 1 m: most draws cross.
        let mut p = plan(true);
        p.inputs[2] = PlanInput {
            key: "travel".into(),
            nominal: 0.0,
            sweep: Some(vec![0.0, 0.001, -0.001]),
            dispersion: p.inputs[1].dispersion,
            keeps_side: true,
        };
        let (mut zero, mut crossed) = (0, 0);
        for id in 0..p.total() {
            let v = p.variant(id);
            let center = p.centers(v.point)[2];
            let free = p.inputs[2]
                .dispersion
                .unwrap()
                .sample(center, &mut input_rng(5, v.replicate, "travel"));
            let got = v.values[2];
            if center == 0.0 {
                assert_eq!(got, 0.0, "variant {id}");
                zero += 1;
            } else if free * center < 0.0 {
                assert_eq!(got, 0.0, "variant {id}: {free} crossed zero");
                crossed += 1;
            } else {
                assert_eq!(got, free, "variant {id}: on its side, untouched");
            }
        }
        assert!(zero == 12 && crossed >= 4, "{zero} {crossed}");
    }

    #[test]
    fn a_travel_given_by_its_own_mean_keeps_the_side_of_that_mean() {
        // Nominal travel 0.1 m, but the draws are N(−0.05, 0.01²): they keep the mean's side.
        let mut p = plan(true);
        p.inputs[1] = PlanInput {
            key: "travel".into(),
            nominal: 0.1,
            sweep: None,
            dispersion: Some(Dispersion {
                shape: Shape::NormalAbout {
                    mean: -0.05,
                    sigma: 0.01,
                },
                relative: false,
            }),
            keeps_side: true,
        };
        let travels: Vec<f64> = (0..p.total()).map(|id| p.variant(id).values[1]).collect();
        assert!(travels.iter().all(|&t| t < 0.0), "{travels:?}");
        let mean = travels.iter().sum::<f64>() / travels.len() as f64;
        assert!((mean + 0.05).abs() < 0.01, "{mean}");
    }

    #[test]
    fn shards_interleave_and_together_hold_every_variant_once() {
        let total = 23;
        let mut seen = vec![0; total as usize];
        for k in 0..4 {
            let s = Shard { k, n: 4 };
            for q in 0..s.count(total) {
                assert_eq!(s.id(q) % 4, k);
                seen[s.id(q) as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
        assert_eq!(Shard { k: 5, n: 8 }.count(3), 0);
    }

    #[test]
    fn shard_arguments_are_checked() {
        assert_eq!(Shard::parse("2/4"), Ok(Shard { k: 2, n: 4 }));
        assert!(Shard::parse("4/4").unwrap_err().contains("0 <= K < N"));
        assert!(Shard::parse("1").unwrap_err().contains("K/N"));
        assert!(Shard::parse("a/2").unwrap_err().contains("whole number"));
    }

    #[test]
    fn chunks_cut_a_shard_in_order_with_a_short_last_chunk() {
        assert_eq!(chunks(10, 4), vec![0..4, 4..8, 8..10]);
        assert_eq!(chunks(8, 4), vec![0..4, 4..8]);
        assert!(chunks(0, 4).is_empty());
    }
}
