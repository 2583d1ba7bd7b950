//! Whole flights by the thousand: the batch engine against `Simulation` set up from scratch
//! and flown in a rayon loop over the same variants, on 1 and 2 threads, and the peak memory.
//!
//! `cargo bench --bench batch` runs 1k and 10k variants; `cargo bench --bench batch -- 1000
//! 100000` runs those sizes (each size in its own process, so that its peak resident memory,
//! read from /proc/self/status, is its own). Up to 10k variants it times five interleaved
//! rounds of (batch on 2 threads, batch on 1, rayon loop on 2) and prints the medians and the
//! median of the rounds' ratios; above 10k, one batch run on 2 threads. The targets: ≥ 2,000
//! flights/s on 2 threads, ≥ 3× the rayon loop per flight, 2 threads ≥ 1.8× 1.
//! The variants are the batch tests': the reference design with its ballast moving, drogue and
//! main, wind, rail, motor and mass dispersions. Their inputs are never held whole: each
//! chunk's columns are drawn from (seed, variant index) when the chunk is flown, so the peak
//! memory must not grow with the number of variants.
//!
//! `batch --once batch|loop N` flies N variants once on one thread, one way or the other, for
//! instruction counts under callgrind (the dated logs under `results/bench-*` give the
//! commands and the counts).

mod fleet;

use fleet::{design, fly_batch, from_scratch};
use rayon::prelude::*;
use std::time::Instant;

/// Interleaved rounds per size up to 10k variants.
const ROUNDS: usize = 5;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn peak_rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        })
        .unwrap_or(0)
}

fn measure(n: usize, compare: bool) {
    let design = design();
    let batch = fleet::batch();
    let pool = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    };
    let (one_thread, two_threads) = (pool(1), pool(2));
    let time_batch = |pool: &rayon::ThreadPool| {
        let t = Instant::now();
        std::hint::black_box(pool.install(|| fly_batch(&batch, n)));
        t.elapsed().as_secs_f64()
    };
    let time_loop = |pool: &rayon::ThreadPool| {
        let t = Instant::now();
        let s: f64 = pool.install(|| {
            (0..n)
                .into_par_iter()
                .map(|i| from_scratch(&design, i))
                .sum()
        });
        std::hint::black_box(s);
        t.elapsed().as_secs_f64()
    };
    if !compare {
        let b2 = time_batch(&two_threads);
        println!(
            "{n:>7} variants  batch: 2 threads {:>8.0} flights/s (one run)",
            n as f64 / b2
        );
    } else {
        // Rounds of (batch on 2 threads, batch on 1, loop on 2), so that a slow spell of the
        // shared machine falls on all three alike rather than on one of them; each ratio is
        // the median of the rounds' own ratios.
        let (mut b1, mut b2, mut l2) = (Vec::new(), Vec::new(), Vec::new());
        let mut batch_peak_kib = 0;
        for round in 0..ROUNDS {
            b2.push(time_batch(&two_threads));
            b1.push(time_batch(&one_thread));
            if round == 0 {
                batch_peak_kib = peak_rss_kib();
            }
            l2.push(time_loop(&two_threads));
        }
        let scaling = median(b1.iter().zip(&b2).map(|(a, b)| a / b).collect());
        let per_flight = median(l2.iter().zip(&b2).map(|(l, b)| l / b).collect());
        let (b1, b2, l2) = (median(b1), median(b2), median(l2));
        println!("{n:>7} variants  batch: 1 thread {:>8.0} flights/s, 2 threads {:>8.0} flights/s (2 threads / 1 = {scaling:.2}x)", n as f64 / b1, n as f64 / b2);
        println!("{n:>7} variants  Simulation in a rayon loop, 2 threads: {:>8.0} flights/s; batch / loop = {per_flight:.2}x per flight", n as f64 / l2);
        println!(
            "{n:>7} variants  peak resident memory {:.1} MiB after the batch's first runs, {:.1} MiB in all",
            batch_peak_kib as f64 / 1024.0,
            peak_rss_kib() as f64 / 1024.0
        );
        return;
    }
    println!(
        "{n:>7} variants  peak resident memory {:.1} MiB",
        peak_rss_kib() as f64 / 1024.0
    );
}

/// `batch --once batch|loop N`: fly N variants once on one thread, the batch engine's way or
/// the rayon loop's, and print nothing else: for instruction counts under
/// `valgrind --tool=callgrind`, which the noisy timings of a shared 2-core machine cannot
/// replace.
fn once(how: &str, n: usize) {
    let design = design();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let sum: f64 = pool.install(|| match how {
        "batch" => fly_batch(&fleet::batch(), n),
        _ => (0..n).map(|i| from_scratch(&design, i)).sum(),
    });
    println!("{how}: {n} variants, apogees sum to {sum:.6} m");
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() == 4 && args[1] == "--once" {
        once(&args[2], args[3].parse().unwrap());
        return;
    }
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    if sizes.len() == 1 {
        measure(sizes[0], sizes[0] <= 10_000);
        return;
    }
    // Each size in its own process so that its peak memory is its own.
    let me = std::env::current_exe().unwrap();
    for n in if sizes.is_empty() {
        vec![1_000, 10_000]
    } else {
        sizes
    } {
        let out = std::process::Command::new(&me)
            .arg(n.to_string())
            .output()
            .unwrap();
        print!("{}", String::from_utf8_lossy(&out.stdout));
    }
}
