//! The few numbers the report computes itself from the rows: the chance of passing a
//! ceiling with its one-sided bound, radii holding a share of the landings, histogram bins,
//! quantiles across flights at common times, and the calendar date of a file.

use crate::campaign::stats::quantile;

/// The one-sided upper confidence bound on a binomial probability after `k` successes in `n`
/// trials (Clopper and Pearson's exact bound): the p at which `P(X ≤ k) = 1 − confidence`.
/// For `k = 0` it is `1 − (1 − confidence)^(1/n)`, about `3/n` at 95 % (the rule of three).
/// Found by bisection to 1e-15 on the binomial distribution function summed in logarithms
/// (no underflow for large `n`).
pub fn binomial_upper(k: u64, n: u64, confidence: f64) -> f64 {
    if n == 0 {
        return 1.0;
    }
    if k >= n {
        return 1.0;
    }
    let alpha = 1.0 - confidence;
    let cdf = |p: f64| -> f64 {
        // P(X ≤ k) for X ~ B(n, p): terms P(X = j) from j = 0 by their ratio, in logs.
        let (nf, lp, lq) = (n as f64, p.ln(), (-p).ln_1p());
        let mut log_term = nf * lq;
        let mut best = log_term;
        let mut logs = Vec::with_capacity(k as usize + 1);
        logs.push(log_term);
        for j in 0..k {
            let jf = j as f64;
            log_term += ((nf - jf) / (jf + 1.0)).ln() + lp - lq;
            best = best.max(log_term);
            logs.push(log_term);
        }
        let sum: f64 = logs.iter().map(|l| (l - best).exp()).sum();
        (best + sum.ln()).exp().min(1.0)
    };
    let (mut lo, mut hi) = (k as f64 / n as f64, 1.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if cdf(mid) > alpha {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-15 {
            break;
        }
    }
    0.5 * (lo + hi)
}

/// The radii, about (cx, cy), of the circles holding the share `q` of the points (type-7
/// quantiles of the distances, as every percentile of the run).
pub fn radii(xs: &[f64], ys: &[f64], (cx, cy): (f64, f64), qs: &[f64]) -> Vec<f64> {
    let mut d: Vec<f64> = xs
        .iter()
        .zip(ys)
        .map(|(x, y)| (x - cx).hypot(y - cy))
        .filter(|d| d.is_finite())
        .collect();
    if d.is_empty() {
        return vec![f64::NAN; qs.len()];
    }
    d.sort_by(f64::total_cmp);
    qs.iter().map(|&q| quantile(&d, q)).collect()
}

/// Bins of a histogram of `values`: about `target` bins of a round width, each `(lo, hi,
/// count)`; every value falls in exactly one (the last bin holds its upper edge).
pub fn histogram(values: &[f64], target: usize) -> Vec<(f64, f64, u64)> {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let Some((lo, hi)) = crate::chart::extent(&finite, 0.0) else {
        return vec![];
    };
    let (_, step) = crate::chart::ticks(lo, hi, target.max(1));
    let first = (lo / step).floor() * step;
    let bins = (((hi - first) / step).floor() as usize + 1).max(1);
    let mut counts = vec![0u64; bins];
    for v in finite {
        let k = (((v - first) / step).floor() as usize).min(bins - 1);
        counts[k] += 1;
    }
    counts
        .into_iter()
        .enumerate()
        .map(|(k, c)| (first + k as f64 * step, first + (k + 1) as f64 * step, c))
        .collect()
}

/// A value of a series (sorted times `t`) at time `at`, linear between samples; NaN outside.
pub fn at_time(t: &[f64], v: &[f64], at: f64) -> f64 {
    if t.is_empty() || at < t[0] || at > t[t.len() - 1] {
        return f64::NAN;
    }
    let k = t.partition_point(|&x| x <= at);
    if k == 0 {
        return v[0];
    }
    if k >= t.len() {
        return v[t.len() - 1];
    }
    let (t0, t1) = (t[k - 1], t[k]);
    if t1 <= t0 {
        return v[k];
    }
    v[k - 1] + (at - t0) / (t1 - t0) * (v[k] - v[k - 1])
}

/// The 5, 50 and 95 % quantiles of the finite values (NaN where there are fewer than 2).
pub fn bands(values: &mut Vec<f64>) -> (f64, f64, f64) {
    values.retain(|v| v.is_finite());
    if values.len() < 2 {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    values.sort_by(f64::total_cmp);
    (
        quantile(values, 0.05),
        quantile(values, 0.5),
        quantile(values, 0.95),
    )
}

/// A UTC date and time, `YYYY-MM-DD HH:MM UTC`, of seconds since 1970: the output
/// directory's stamp ([`crate::campaign::outdir::utc_text`]) without its seconds.
pub fn utc(unix_s: u64) -> String {
    let text = crate::campaign::outdir::utc_text(unix_s);
    match text.rsplit_once(':') {
        Some((minutes, _)) => format!("{minutes} UTC"),
        None => text,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn none_of_n_passing_gives_the_rule_of_three_at_95_percent() {
        // Exactly 1 − 0.05^(1/n).
        for n in [10u64, 500, 160_000] {
            let u = binomial_upper(0, n, 0.95);
            let exact = 1.0 - 0.05f64.powf(1.0 / n as f64);
            assert!((u - exact).abs() < 1e-12, "n {n}: {u} against {exact}");
        }
        // Which is −ln(0.05)/n = 2.9957/n less a term in 1/n²: 3/n to within 0.5 % at
        // n = 500 and 0.2 % at 160,000.
        let u = binomial_upper(0, 500, 0.95);
        assert!((u * 500.0 / 3.0 - 1.0).abs() < 0.005, "{u}");
        let u = binomial_upper(0, 160_000, 0.95);
        assert!((u * 160_000.0 / 3.0 - 1.0).abs() < 0.002, "{u}");
    }

    #[test]
    fn the_upper_bound_leaves_five_percent_below_k() {
        // 3 of 100: P(X ≤ 3; 100, u) = 0.05, checked by summing the binomial terms directly.
        let u = binomial_upper(3, 100, 0.95);
        let p = |j: u64| {
            let c: f64 = (0..j).map(|i| (100 - i) as f64 / (i + 1) as f64).product();
            c * u.powi(j as i32) * (1.0 - u).powi((100 - j) as i32)
        };
        let cdf: f64 = (0..=3).map(p).sum();
        assert!((cdf - 0.05).abs() < 1e-10, "{cdf}");
        // Large n and k (no underflow): 2,000 of 160,000 sits just above 1.25 %.
        let u = binomial_upper(2000, 160_000, 0.95);
        assert!(u > 0.0125 && u < 0.0135, "{u}");
    }

    #[test]
    fn every_value_falls_in_one_histogram_bin() {
        let v: Vec<f64> = (0..1000)
            .map(|i| (i as f64 * 0.37).sin() * 50.0 + 100.0)
            .collect();
        let bins = histogram(&v, 30);
        assert_eq!(bins.iter().map(|b| b.2).sum::<u64>(), 1000);
        assert!(bins[0].0 <= 50.0 && bins.last().unwrap().1 >= 150.0);
    }

    #[test]
    fn dates_come_out_in_the_civil_calendar() {
        assert_eq!(utc(0), "1970-01-01 00:00 UTC");
        // 2026-12-04 10:30 UTC.
        assert_eq!(utc(1_796_380_200), "2026-12-04 10:30 UTC");
        assert_eq!(utc(951_782_400), "2000-02-29 00:00 UTC");
    }

    #[test]
    fn series_interpolate_between_samples_and_stop_at_their_ends() {
        let t = [0.0, 1.0, 3.0];
        let v = [0.0, 10.0, 30.0];
        assert_eq!(at_time(&t, &v, 2.0), 20.0);
        assert_eq!(at_time(&t, &v, 3.0), 30.0);
        assert!(at_time(&t, &v, 3.5).is_nan());
    }
}
