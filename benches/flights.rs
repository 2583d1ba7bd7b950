//! Whole flights by the thousand under criterion: the batch engine on 2 threads for 1k, 10k
//! and 100k variants, on 1 thread for 1k and 10k, and `Simulation` set up from scratch in a
//! rayon loop on 2 threads for 1k and 10k, all over the same variants (`fleet`: the reference
//! design, ballast moving, drogue and main, wind, rail, motor and mass dispersions). Criterion
//! reports flights per second (its "elements"); the batch's targets (batch / loop, 2 threads /
//! 1) are ratios of those. `batch.rs` measures the same with interleaved rounds and peak memory.
//!
//! Ten samples each; the 100k runs take about 35 s a sample, so the whole takes about eight
//! minutes. One size: `cargo bench --bench flights -- '/10k$'`.

mod fleet;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use rayon::prelude::*;
use std::hint::black_box;
use std::time::Duration;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

fn whole_flights(c: &mut Criterion) {
    let design = fleet::design();
    let batch = fleet::batch();
    let (one, two) = (pool(1), pool(2));
    let mut g = c.benchmark_group("whole_flights");
    g.sample_size(10).warm_up_time(Duration::from_secs(1));
    for (n, label) in [(1_000, "1k"), (10_000, "10k"), (100_000, "100k")] {
        // Ten samples at the rate each way reaches on this machine, so that criterion need
        // not stretch its time: about 3,000 flights/s on 2 threads, 1,400 otherwise.
        g.throughput(Throughput::Elements(n as u64));
        g.measurement_time(Duration::from_secs_f64(n as f64 / 280.0));
        g.bench_function(format!("batch_2_threads/{label}"), |b| {
            b.iter(|| black_box(two.install(|| fleet::fly_batch(&batch, n))))
        });
        if n > 10_000 {
            continue;
        }
        g.measurement_time(Duration::from_secs_f64(n as f64 / 120.0));
        g.bench_function(format!("batch_1_thread/{label}"), |b| {
            b.iter(|| black_box(one.install(|| fleet::fly_batch(&batch, n))))
        });
        g.bench_function(format!("simulation_rayon_loop_2_threads/{label}"), |b| {
            b.iter(|| {
                black_box(two.install(|| {
                    (0..n)
                        .into_par_iter()
                        .map(|i| fleet::from_scratch(&design, i))
                        .sum::<f64>()
                }))
            })
        });
    }
    g.finish();
}

criterion_group!(benches, whole_flights);
criterion_main!(benches);
