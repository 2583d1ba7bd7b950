//! Statistics of a campaign, per sweep point: the distribution of every metric, the landing
//! dispersion ellipses and the sensitivity of every metric to every dispersed input.
//!
//! - Percentiles interpolate linearly between order statistics (Hyndman & Fan's type 7, the
//!   default of NumPy and R, DuckDB's `quantile_cont`): the p-quantile of n sorted values is
//!   at position (n − 1) p. The standard deviation is the sample one (n − 1).
//! - The landing ellipses are the contours of the 2×2 covariance of the landing points at
//!   Mahalanobis distance k = 1, 2, 3: semi-axes k √λ along the covariance's eigenvectors. For a
//!   normal scatter they hold 39.3 %, 86.5 % and 98.9 % of the landings.
//! - Sensitivity: within a sweep point, each metric is fitted by least squares (faer's
//!   column-pivoted QR) as a linear function of the dispersed inputs, all standardized. The
//!   share of the metric's variance given to an input is Pratt's measure β*·r: its
//!   standardized coefficient β* = β σ_x / σ_y times its correlation r with the metric. The
//!   shares add up exactly to the fit's R²; 1 − R² is what a linear model does not explain
//!   (nonlinearity, interactions). For independent inputs, as the draws are, β*·r tends to
//!   β*², the square of the standardized coefficient, but in a finite sample the inputs are
//!   slightly correlated and the squares alone can add up to well over 1 (with 50 variants and
//!   16 inputs we saw 1.58), while Pratt's shares cannot. A share may come out slightly
//!   negative for an input that does nothing.
//!
//! - Requirements: the share of a point's variants, all of them whatever their status, whose
//!   metric has a value within the requirement's bounds (a variant without one does not meet
//!   it), with its 95 % Wilson score interval: for k of n, p̂ = k/n and z = 1.959964,
//!   `(p̂ + z²/2n ± z √(p̂(1 − p̂)/n + z²/4n²)) / (1 + z²/n)`. Unlike p̂ ± z √(p̂(1 − p̂)/n) it
//!   stays inside [0, 1] and is not of zero width when every variant (or none) meets it: 500
//!   of 500 gives [0.9924, 1].
//!
//! Only variants that landed enter the other statistics; `failures` counts the others.
//! Missing values are NaN here (a metric is never NaN otherwise: see `fly`).

use super::scenario::RequirementSpec;
use faer::linalg::solvers::SolveLstsq;
use faer::Mat;

/// The two-sided 95 % quantile of the standard normal distribution.
pub const Z95: f64 = 1.959963984540054;

/// How many of a point's variants meet one requirement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compliance {
    pub variants: u64,
    pub met: u64,
    /// met / variants (NaN for no variants).
    pub fraction: f64,
    /// The 95 % Wilson score interval of the fraction.
    pub low: f64,
    pub high: f64,
}

/// `met` of `variants`, with the 95 % Wilson score interval (see the module docs).
pub fn compliance(met: u64, variants: u64) -> Compliance {
    let n = variants as f64;
    let p = met as f64 / n;
    let z2 = Z95 * Z95;
    let denom = 1.0 + z2 / n;
    let centre = (p + z2 / (2.0 * n)) / denom;
    let half = Z95 * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt() / denom;
    Compliance {
        variants,
        met,
        fraction: p,
        low: (centre - half).max(0.0),
        high: (centre + half).min(1.0),
    }
}

/// The distribution of one metric's values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    pub count: u64,
    pub mean: f64,
    /// Sample standard deviation (None with fewer than two values).
    pub std: Option<f64>,
    pub min: f64,
    pub p1: f64,
    pub p5: f64,
    pub p50: f64,
    pub p95: f64,
    pub p99: f64,
    pub max: f64,
}

/// The q-quantile (0 ≤ q ≤ 1) of sorted values, type 7.
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    let pos = (sorted.len() - 1) as f64 * q;
    let lo = pos.floor() as usize;
    let hi = (lo + 1).min(sorted.len() - 1);
    sorted[lo] + (pos - lo as f64) * (sorted[hi] - sorted[lo])
}

/// Summary of the finite values among `values` (None if there are none).
pub fn summarize(values: impl IntoIterator<Item = f64>) -> Option<Summary> {
    let mut v: Vec<f64> = values.into_iter().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let std = (v.len() > 1)
        .then(|| (v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0)).sqrt());
    v.sort_by(f64::total_cmp);
    Some(Summary {
        count: v.len() as u64,
        mean,
        std,
        min: v[0],
        p1: quantile(&v, 0.01),
        p5: quantile(&v, 0.05),
        p50: quantile(&v, 0.5),
        p95: quantile(&v, 0.95),
        p99: quantile(&v, 0.99),
        max: v[v.len() - 1],
    })
}

/// A landing dispersion ellipse at 1 σ (multiply the semi-axes by k for k σ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    pub count: u64,
    pub center_x_m: f64,
    pub center_y_m: f64,
    pub var_x_m2: f64,
    pub var_y_m2: f64,
    pub cov_xy_m2: f64,
    pub semi_major_m: f64,
    pub semi_minor_m: f64,
    /// Direction of the major axis, degrees counterclockwise from +x (east) toward +y
    /// (north), in (−90, 90].
    pub major_axis_deg: f64,
}

/// Semi-axes (√ of the eigenvalues, major first) and the major axis's angle (degrees from
/// +x toward +y) of the 2×2 covariance `[[vxx, vxy], [vxy, vyy]]`.
pub fn covariance_axes(vxx: f64, vyy: f64, vxy: f64) -> (f64, f64, f64) {
    let mid = 0.5 * (vxx + vyy);
    let r = (0.25 * (vxx - vyy) * (vxx - vyy) + vxy * vxy).sqrt();
    let (l1, l2) = (mid + r, (mid - r).max(0.0));
    let mut angle = 0.5 * (2.0 * vxy).atan2(vxx - vyy).to_degrees();
    if angle <= -90.0 {
        angle += 180.0;
    }
    (l1.sqrt(), l2.sqrt(), angle)
}

/// The 1 σ ellipse of the points (x, y) that are both finite (None with fewer than 3).
pub fn ellipse(xs: &[f64], ys: &[f64]) -> Option<Ellipse> {
    let pts: Vec<(f64, f64)> = xs
        .iter()
        .zip(ys)
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .map(|(x, y)| (*x, *y))
        .collect();
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let cx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let cy = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let (mut vxx, mut vyy, mut vxy) = (0.0, 0.0, 0.0);
    for (x, y) in &pts {
        vxx += (x - cx) * (x - cx);
        vyy += (y - cy) * (y - cy);
        vxy += (x - cx) * (y - cy);
    }
    let (vxx, vyy, vxy) = (vxx / (n - 1.0), vyy / (n - 1.0), vxy / (n - 1.0));
    let (a, b, angle) = covariance_axes(vxx, vyy, vxy);
    Some(Ellipse {
        count: pts.len() as u64,
        center_x_m: cx,
        center_y_m: cy,
        var_x_m2: vxx,
        var_y_m2: vyy,
        cov_xy_m2: vxy,
        semi_major_m: a,
        semi_minor_m: b,
        major_axis_deg: angle,
    })
}

/// A linear fit of one metric on the dispersed inputs.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensitivity {
    pub count: u64,
    pub r2: f64,
    /// Per input: the metric's change per unit of the input (None for an input that did not
    /// vary).
    pub coefficients: Vec<Option<f64>>,
    /// Per input: the standardized coefficient β σ_x / σ_y.
    pub standardized: Vec<Option<f64>>,
    /// Per input: its correlation with the metric.
    pub correlations: Vec<Option<f64>>,
    /// Per input: the share of the metric's variance, Pratt's β*·r (they add up to R²).
    pub shares: Vec<Option<f64>>,
}

/// Fit `y` on the columns `xs` (rows where y and every x are finite). None when the metric
/// does not vary or there are not more rows than inputs + 1.
pub fn sensitivity(xs: &[&[f64]], y: &[f64]) -> Option<Sensitivity> {
    let rows: Vec<usize> = (0..y.len())
        .filter(|&r| y[r].is_finite() && xs.iter().all(|x| x[r].is_finite()))
        .collect();
    let n = rows.len();
    let mean_sd = |f: &dyn Fn(usize) -> f64| {
        let m = rows.iter().map(|&r| f(r)).sum::<f64>() / n as f64;
        let s =
            (rows.iter().map(|&r| (f(r) - m) * (f(r) - m)).sum::<f64>() / (n as f64 - 1.0)).sqrt();
        (m, s)
    };
    if n < 3 {
        return None;
    }
    let (my, sy) = mean_sd(&|r| y[r]);
    if sy.is_nan() || sy <= 0.0 {
        return None;
    }
    // Inputs that vary (relative to their size: a constant column carries rounding only).
    let stats: Vec<(f64, f64)> = xs.iter().map(|x| mean_sd(&|r| x[r])).collect();
    let used: Vec<usize> = (0..xs.len())
        .filter(|&j| stats[j].1 > 1e-12 * stats[j].0.abs().max(f64::MIN_POSITIVE))
        .collect();
    let p = used.len();
    let mut out = Sensitivity {
        count: n as u64,
        r2: 0.0,
        coefficients: vec![None; xs.len()],
        standardized: vec![None; xs.len()],
        correlations: vec![None; xs.len()],
        shares: vec![None; xs.len()],
    };
    if p == 0 {
        return Some(out);
    }
    if n <= p + 1 {
        return None;
    }
    let z = Mat::<f64>::from_fn(n, p, |i, k| {
        let j = used[k];
        (xs[j][rows[i]] - stats[j].0) / stats[j].1
    });
    let yc = Mat::<f64>::from_fn(n, 1, |i, _| y[rows[i]] - my);
    let b = z.col_piv_qr().solve_lstsq(&yc);
    let fitted = &z * &b;
    let ss_res: f64 = (0..n).map(|i| (yc[(i, 0)] - fitted[(i, 0)]).powi(2)).sum();
    let ss_tot = sy * sy * (n as f64 - 1.0);
    out.r2 = 1.0 - ss_res / ss_tot;
    for (k, &j) in used.iter().enumerate() {
        let bk = b[(k, 0)];
        let r = (0..n).map(|i| z[(i, k)] * yc[(i, 0)]).sum::<f64>() / ((n as f64 - 1.0) * sy);
        out.coefficients[j] = Some(bk / stats[j].1);
        out.standardized[j] = Some(bk / sy);
        out.correlations[j] = Some(r);
        out.shares[j] = Some(bk / sy * r);
    }
    Some(out)
}

/// The numbers of a campaign's rows the statistics read, column by column (NaN for a missing
/// value).
#[derive(Debug, Clone, Default)]
pub struct Table {
    pub point: Vec<u32>,
    pub landed: Vec<bool>,
    /// One column per input of the plan.
    pub inputs: Vec<Vec<f64>>,
    /// One column per metric.
    pub metrics: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table of `inputs` input columns and `metrics` metric columns.
    pub fn new(inputs: usize, metrics: usize) -> Table {
        Table {
            point: vec![],
            landed: vec![],
            inputs: vec![vec![]; inputs],
            metrics: vec![vec![]; metrics],
        }
    }

    /// [`Table::new`] with room for `rows` rows taken at once, or the error of an allocator
    /// that cannot give it (asked before the run flies anything, not after).
    pub fn with_room(
        inputs: usize,
        metrics: usize,
        rows: usize,
    ) -> Result<Table, std::collections::TryReserveError> {
        let mut t = Table::new(inputs, metrics);
        t.point.try_reserve_exact(rows)?;
        t.landed.try_reserve_exact(rows)?;
        for c in t.inputs.iter_mut().chain(t.metrics.iter_mut()) {
            c.try_reserve_exact(rows)?;
        }
        Ok(t)
    }

    /// Bytes a table of these columns holds per row.
    pub fn bytes_per_row(inputs: usize, metrics: usize) -> usize {
        std::mem::size_of::<u32>() + std::mem::size_of::<bool>() + 8 * (inputs + metrics)
    }
}

/// Statistics of one sweep point.
#[derive(Debug, Clone)]
pub struct PointStats {
    pub point: usize,
    pub variants: u64,
    pub failures: u64,
    /// Per metric.
    pub summaries: Vec<Option<Summary>>,
    /// The rocket's landing ellipse.
    pub ellipse: Option<Ellipse>,
    /// Each released part's landing ellipse, in the releases' order.
    pub release_ellipses: Vec<Option<Ellipse>>,
    /// Per metric (fits on the dispersed inputs).
    pub sensitivity: Vec<Option<Sensitivity>>,
    /// Per requirement, in the order given.
    pub requirements: Vec<Compliance>,
}

/// Statistics of every sweep point. `dispersed[j]` says whether input j is dispersed;
/// `landings` gives the metric indices of the landing x and y, the rocket's and then each
/// released part's; `requirements` the metric index of each requirement and its bounds.
pub fn compute(
    table: &Table,
    points: usize,
    dispersed: &[bool],
    landings: &[(usize, usize)],
    requirements: &[(usize, RequirementSpec)],
) -> Vec<PointStats> {
    let mut rows_of: Vec<Vec<usize>> = vec![vec![]; points];
    for (r, &p) in table.point.iter().enumerate() {
        rows_of[p as usize].push(r);
    }
    let inputs: Vec<usize> = (0..table.inputs.len()).filter(|&j| dispersed[j]).collect();
    // Each point's statistics are its own: computed side by side on the threads of the pool
    // this runs in, collected in point order.
    use rayon::prelude::*;
    rows_of
        .par_iter()
        .enumerate()
        .map(|(point, rows)| {
            let landed: Vec<usize> = rows.iter().copied().filter(|&r| table.landed[r]).collect();
            let col = |c: &Vec<f64>| -> Vec<f64> { landed.iter().map(|&r| c[r]).collect() };
            let xs: Vec<Vec<f64>> = inputs.iter().map(|&j| col(&table.inputs[j])).collect();
            let x_refs: Vec<&[f64]> = xs.iter().map(Vec::as_slice).collect();
            let metric_cols: Vec<Vec<f64>> = table.metrics.iter().map(col).collect();
            PointStats {
                point,
                variants: rows.len() as u64,
                failures: (rows.len() - landed.len()) as u64,
                summaries: metric_cols
                    .iter()
                    .map(|m| summarize(m.iter().copied()))
                    .collect(),
                ellipse: landings
                    .first()
                    .and_then(|&(x, y)| ellipse(&metric_cols[x], &metric_cols[y])),
                release_ellipses: landings
                    .iter()
                    .skip(1)
                    .map(|&(x, y)| ellipse(&metric_cols[x], &metric_cols[y]))
                    .collect(),
                sensitivity: metric_cols
                    .iter()
                    .map(|m| {
                        if x_refs.is_empty() {
                            None
                        } else {
                            sensitivity(&x_refs, m)
                        }
                    })
                    .collect(),
                requirements: requirements
                    .iter()
                    .map(|(m, r)| {
                        let met = rows
                            .iter()
                            .filter(|&&row| r.met_by(table.metrics[*m][row]))
                            .count();
                        compliance(met as u64, rows.len() as u64)
                    })
                    .collect(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_of_1_to_100_interpolate_between_order_statistics() {
        // Type 7: position (n − 1) q = 99 q, so p1 = 1 + 0.99, p5 = 1 + 4.95, p50 = 50.5...
        let s = summarize((1..=100).rev().map(f64::from)).unwrap();
        assert_eq!(s.count, 100);
        assert_eq!(s.min, 1.0);
        assert_eq!(s.max, 100.0);
        assert!((s.p1 - 1.99).abs() < 1e-12);
        assert!((s.p5 - 5.95).abs() < 1e-12);
        assert!((s.p50 - 50.5).abs() < 1e-12);
        assert!((s.p95 - 95.05).abs() < 1e-12);
        assert!((s.p99 - 99.01).abs() < 1e-12);
        assert!((s.mean - 50.5).abs() < 1e-12);
        // Sample variance of 1..n is n(n + 1)/12 = 841.666...
        assert!((s.std.unwrap() - (100.0 * 101.0 / 12.0f64).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn a_summary_skips_missing_values_and_one_value_has_no_spread() {
        let s = summarize([f64::NAN, 3.0, f64::NAN]).unwrap();
        assert_eq!(
            (s.count, s.mean, s.std, s.p5, s.p95),
            (1, 3.0, None, 3.0, 3.0)
        );
        assert!(summarize([f64::NAN]).is_none());
    }

    #[test]
    fn the_ellipse_of_a_known_covariance_has_its_eigen_axes() {
        // Diagonal: axes along x and y.
        assert_eq!(covariance_axes(4.0, 1.0, 0.0), (2.0, 1.0, 0.0));
        // [[2, 1], [1, 2]]: eigenvalues 3 and 1, major axis at 45°.
        let (a, b, t) = covariance_axes(2.0, 2.0, 1.0);
        assert!(
            (a - 3f64.sqrt()).abs() < 1e-15 && (b - 1.0).abs() < 1e-15 && (t - 45.0).abs() < 1e-12
        );
        // [[1, 0], [0, 9]]: major axis along y, 90°.
        let (a, b, t) = covariance_axes(1.0, 9.0, 0.0);
        assert_eq!((a, b, t), (3.0, 1.0, 90.0));
        // [[5, −2], [−2, 2]]: eigenvalues 6 and 1, major axis along (2, −1): −26.565°.
        let (a, b, t) = covariance_axes(5.0, 2.0, -2.0);
        assert!((a - 6f64.sqrt()).abs() < 1e-14 && (b - 1.0).abs() < 1e-14);
        assert!((t - (-0.5f64).atan().to_degrees()).abs() < 1e-12);
    }

    #[test]
    fn the_ellipse_of_four_points_has_their_sample_covariance() {
        // Points (±2, 0) and (0, ±1) about (10, 20): var x = 8/3, var y = 2/3, cov 0.
        let xs = [12.0, 8.0, 10.0, 10.0, f64::NAN];
        let ys = [20.0, 20.0, 21.0, 19.0, 5.0];
        let e = ellipse(&xs, &ys).unwrap();
        assert_eq!((e.count, e.center_x_m, e.center_y_m), (4, 10.0, 20.0));
        assert!((e.semi_major_m - (8.0f64 / 3.0).sqrt()).abs() < 1e-15);
        assert!((e.semi_minor_m - (2.0f64 / 3.0).sqrt()).abs() < 1e-15);
        assert_eq!(e.major_axis_deg, 0.0);
    }

    #[test]
    fn regression_recovers_known_linear_coefficients() {
        // y = 3 + 2 x1 − 0.5 x2 exactly, x from a fixed pseudo-random sequence.
        let n = 200;
        let x1: Vec<f64> = (0..n).map(|i| ((i * 37 % 101) as f64) / 10.0).collect();
        let x2: Vec<f64> = (0..n)
            .map(|i| ((i * 53 % 97) as f64) * 3.0 - 40.0)
            .collect();
        let x3: Vec<f64> = vec![7.0; n]; // an input that did not vary
        let y: Vec<f64> = (0..n).map(|i| 3.0 + 2.0 * x1[i] - 0.5 * x2[i]).collect();
        let s = sensitivity(&[&x1, &x2, &x3], &y).unwrap();
        assert!((s.coefficients[0].unwrap() - 2.0).abs() < 1e-10);
        assert!((s.coefficients[1].unwrap() + 0.5).abs() < 1e-10);
        assert_eq!(s.coefficients[2], None);
        assert!((s.r2 - 1.0).abs() < 1e-10);
        // The shares are β σ_x / σ_y × corr(x, y), computed here by hand from the columns,
        // and they add up to R² = 1.
        let m = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let cov = |a: &[f64], b: &[f64]| {
            let (ma, mb) = (m(a), m(b));
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - ma) * (y - mb))
                .sum::<f64>()
                / (a.len() - 1) as f64
        };
        let share = |x: &[f64], beta: f64| {
            beta * cov(x, x).sqrt() / cov(&y, &y).sqrt() * cov(x, &y)
                / (cov(x, x) * cov(&y, &y)).sqrt()
        };
        assert!((s.shares[0].unwrap() - share(&x1, 2.0)).abs() < 1e-10);
        assert!((s.shares[1].unwrap() - share(&x2, -0.5)).abs() < 1e-10);
        assert!((s.shares[0].unwrap() + s.shares[1].unwrap() - 1.0).abs() < 1e-10);
    }

    #[test]
    fn regression_needs_more_rows_than_inputs_and_a_metric_that_varies() {
        assert!(sensitivity(&[&[1.0, 2.0, 3.0]], &[5.0, 5.0, 5.0]).is_none());
        assert!(sensitivity(&[&[1.0, 2.0, 3.0], &[3.0, 1.0, 2.0]], &[1.0, 2.0, 4.0]).is_none());
    }

    #[test]
    fn statistics_group_by_point_and_count_failures() {
        let table = Table {
            point: vec![0, 0, 0, 1, 1],
            landed: vec![true, true, false, true, true],
            inputs: vec![vec![1.0, 2.0, 3.0, 4.0, 5.0]],
            metrics: vec![
                vec![10.0, 20.0, f64::NAN, 1.0, 3.0],
                vec![0.0; 5],
                vec![0.0; 5],
            ],
        };
        let st = compute(&table, 2, &[true], &[(1, 2)], &[]);
        assert_eq!((st[0].variants, st[0].failures), (3, 1));
        assert_eq!(st[0].summaries[0].unwrap().mean, 15.0);
        assert_eq!(st[1].summaries[0].unwrap().mean, 2.0);
    }

    #[test]
    fn a_requirement_counts_every_variant_of_its_point_and_a_missing_value_does_not_meet_it() {
        let table = Table {
            point: vec![0, 0, 0, 0, 1, 1],
            landed: vec![true, true, false, false, true, true],
            inputs: vec![],
            // Variant 2 failed (no value); variant 3 hit the time limit with a value.
            metrics: vec![vec![1.4, 1.5, f64::NAN, 2.0, 1.0, 9.0]],
        };
        let spec = |min, max| RequirementSpec {
            metric: "static_margin_min_cal".into(),
            min,
            max,
        };
        let reqs = [
            (0, spec(Some(1.5), None)),
            (0, spec(None, Some(1.5))),
            (0, spec(Some(1.0), Some(2.0))),
        ];
        let st = compute(&table, 2, &[], &[(0, 0)], &reqs);
        let met = |p: usize| -> Vec<(u64, u64)> {
            st[p]
                .requirements
                .iter()
                .map(|c| (c.met, c.variants))
                .collect()
        };
        // Bounds are inclusive: 1.5 meets both ≥ 1.5 and ≤ 1.5.
        assert_eq!(met(0), vec![(2, 4), (2, 4), (3, 4)]);
        assert_eq!(met(1), vec![(1, 2), (1, 2), (1, 2)]);
        assert_eq!(st[0].requirements[2].fraction, 0.75);
    }

    #[test]
    fn the_wilson_interval_matches_its_hand_calculation_and_stays_inside_zero_and_one() {
        // 487 of 500 by hand: p = 0.974, z² = 3.8414588, denominator 1.0076829,
        // centre (0.974 + 0.0038415)/1.0076829 = 0.9703861, half
        // z √(0.974·0.026/500 + 3.8414588/10⁶)/1.0076829 = 0.0143576.
        let c = compliance(487, 500);
        assert_eq!(c.fraction, 0.974);
        assert!((c.low - 0.9560285).abs() < 2e-7, "{}", c.low);
        assert!((c.high - 0.9847436).abs() < 2e-7, "{}", c.high);
        // All of n: [1/(1 + z²/n), 1] = [1/1.0076829, 1] = [0.9923757, 1]; none: [0, 1 − that].
        let all = compliance(500, 500);
        assert!((all.low - 0.9923757).abs() < 2e-7, "{}", all.low);
        assert_eq!(all.high, 1.0);
        let none = compliance(0, 500);
        assert!(none.low.abs() < 1e-15, "{}", none.low);
        assert!((none.high - 0.0076242).abs() < 2e-7, "{}", none.high);
        // The interval of one variant is wide, and still inside [0, 1].
        let one = compliance(1, 1);
        // 1 of 1: [1/(1 + z²), 1] = [0.2065493, 1].
        assert!(
            (one.low - 0.2065493).abs() < 2e-7 && one.high == 1.0,
            "{one:?}"
        );
    }
}
