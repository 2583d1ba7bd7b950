//! The statistics of a run gathered as its rows stream past, in variant order, so that the
//! run never reads its rows back and holds a bounded amount of memory whatever its size.
//!
//! - **Exact up to a stated size.** While the rows' numbers fit in [`EXACT_BYTES`] (the
//!   inputs and metrics at 8 bytes each: 24,000 rows of the bundled ballast sweep), they are
//!   held as columns and [`stats::compute`] gives every statistic exactly as it is defined
//!   there (type-7 percentiles of the sorted values, two-pass moments, the least-squares fit
//!   by QR).
//! - **Streamed beyond it.** At the first row past that size the held rows are replayed, in
//!   order, into per-point accumulators and dropped, and every later row goes to them: a
//!   metric's count, sum (its mean is the sum over the count, as exactly), least and
//!   greatest, its variance by Welford's update, its percentiles from a t-digest
//!   ([`super::digest`]: the one approximate figure, within [`digest::RANK_ERROR`] of the
//!   count in rank on the distributions tested); the landing ellipses' means and covariances
//!   by Welford's bivariate update; the sensitivity fits from their sufficient statistics
//!   (the sums and cross-products of the dispersed inputs and each metric, taken about the
//!   point's first landed row, then centred and solved as the normal equations of the
//!   standardized inputs); the requirements and statuses are counts either way. Memory is
//!   then per sweep point and metric, not per row: at most about 40 kB per point and metric
//!   (the digest's 2,000 centroids and its buffer).
//!
//! The rows arrive in variant order whatever the threads, and a resumed run replays its kept
//! parts in the same order, so every figure is the same bits whether the run was flown in
//! one go or resumed. `summary.parquet` says which way its percentiles were found
//! (`hpr_mc.percentiles`).

use super::digest::{self, Digest};
use super::fly::{Status, WARNINGS};
use super::scenario::RequirementSpec;
use super::stats::{self, compliance, Ellipse, PointStats, Sensitivity, Summary, Table};
use faer::linalg::solvers::SolveLstsq;
use faer::Mat;

/// The most memory the exact statistics hold in rows (8 MiB): past it they stream.
pub const EXACT_BYTES: usize = 8 << 20;

/// How the percentiles of `summary.parquet` were found (its `hpr_mc.percentiles`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Percentiles {
    /// From the sorted values (type 7).
    Exact,
    /// From a t-digest of each point's values.
    Digest,
}

impl Percentiles {
    /// The text of `hpr_mc.percentiles`.
    pub fn describe(self, exact_rows: usize) -> String {
        match self {
            Percentiles::Exact => format!(
                "exact: type 7 over the sorted values (a run of up to {exact_rows} rows)"
            ),
            Percentiles::Digest => format!(
                "approximate: t-digest (merging, k1 scale, compression {}) of each point's values, its rank error within {} of the count on the distributions tested; the run had more than {exact_rows} rows, the most held exactly",
                digest::COMPRESSION,
                digest::RANK_ERROR
            ),
        }
    }
}

/// One row as the statistics read it.
#[derive(Debug, Clone, Copy)]
pub struct Row<'a> {
    pub point: usize,
    pub status: Status,
    /// Whether the flight raised each warning (None if not flown).
    pub warned: Option<&'a [bool; WARNINGS]>,
    /// Every input's value, in the plan's order.
    pub inputs: &'a [f64],
    /// Every metric's value, NaN where there is none.
    pub metrics: &'a [f64],
}

/// The statistics of a run, row by row.
#[derive(Debug)]
pub struct Gather {
    points: usize,
    inputs: usize,
    metrics: usize,
    dispersed: Vec<usize>,
    landings: Vec<(usize, usize)>,
    requirements: Vec<(usize, RequirementSpec)>,
    exact_rows: usize,
    /// The rows while they fit.
    table: Option<Table>,
    /// Per point, once they do not.
    streams: Vec<PointStream>,
    /// The dispersed inputs of the row being streamed (kept to allocate nothing per row).
    scratch: Vec<f64>,
    /// Rows seen.
    pub rows: u64,
    /// Rows per status: landed, time limit, refused, failed.
    pub landed: u64,
    pub time_limit: u64,
    pub refused: u64,
    pub failed: u64,
    /// Flown rows raising each warning of [`hpr_sim::Warning::KEYS`].
    pub warned: [u64; WARNINGS],
}

impl Gather {
    /// The statistics of `points` sweep points of rows of `inputs` inputs and `metrics`
    /// metrics; `dispersed[j]` says whether input j is dispersed, `landings` the metric
    /// indices of each landing's east and north, `requirements` each requirement's metric
    /// index and bounds.
    pub fn new(
        points: usize,
        dispersed: &[bool],
        metrics: usize,
        landings: &[(usize, usize)],
        requirements: &[(usize, RequirementSpec)],
    ) -> Gather {
        let rows = EXACT_BYTES / Table::bytes_per_row(dispersed.len(), metrics);
        Gather::with_exact_rows(points, dispersed, metrics, landings, requirements, rows)
    }

    /// [`Gather::new`] holding at most `exact_rows` rows exactly.
    pub fn with_exact_rows(
        points: usize,
        dispersed: &[bool],
        metrics: usize,
        landings: &[(usize, usize)],
        requirements: &[(usize, RequirementSpec)],
        exact_rows: usize,
    ) -> Gather {
        Gather {
            points,
            inputs: dispersed.len(),
            metrics,
            dispersed: (0..dispersed.len()).filter(|&j| dispersed[j]).collect(),
            landings: landings.to_vec(),
            requirements: requirements.to_vec(),
            exact_rows: exact_rows.max(1),
            table: Some(Table::new(dispersed.len(), metrics)),
            streams: Vec::new(),
            scratch: Vec::new(),
            rows: 0,
            landed: 0,
            time_limit: 0,
            refused: 0,
            failed: 0,
            warned: [0; WARNINGS],
        }
    }

    /// The most rows held exactly.
    pub fn exact_rows(&self) -> usize {
        self.exact_rows
    }

    /// Add the next row (rows come in variant order).
    pub fn push(&mut self, row: Row) {
        debug_assert_eq!(row.inputs.len(), self.inputs);
        debug_assert_eq!(row.metrics.len(), self.metrics);
        self.rows += 1;
        match row.status {
            Status::Landed => self.landed += 1,
            Status::TimeLimit => self.time_limit += 1,
            Status::Refused => self.refused += 1,
            Status::Failed => self.failed += 1,
        }
        if let Some(w) = row.warned {
            for (n, &b) in self.warned.iter_mut().zip(w) {
                *n += u64::from(b);
            }
        }
        let landed = row.status == Status::Landed;
        if let Some(t) = &mut self.table {
            if t.point.len() < self.exact_rows {
                t.point.push(row.point as u32);
                t.landed.push(landed);
                for (c, &v) in t.inputs.iter_mut().zip(row.inputs) {
                    c.push(v);
                }
                for (c, &v) in t.metrics.iter_mut().zip(row.metrics) {
                    c.push(v);
                }
                return;
            }
            // Past the size held exactly: the rows so far go to the streams, in order.
            let t = self.table.take().expect("checked above");
            self.streams = (0..self.points)
                .map(|_| PointStream::new(self.metrics, self.landings.len(), &self.requirements))
                .collect();
            let mut ins = vec![0.0; self.inputs];
            let mut ms = vec![0.0; self.metrics];
            for r in 0..t.point.len() {
                for (x, c) in ins.iter_mut().zip(&t.inputs) {
                    *x = c[r];
                }
                for (x, c) in ms.iter_mut().zip(&t.metrics) {
                    *x = c[r];
                }
                self.stream(t.point[r] as usize, t.landed[r], &ins, &ms);
            }
        }
        self.stream(row.point, landed, row.inputs, row.metrics);
    }

    fn stream(&mut self, point: usize, landed: bool, inputs: &[f64], metrics: &[f64]) {
        let Some(s) = self.streams.get_mut(point) else {
            return;
        };
        s.variants += 1;
        for (k, (m, r)) in self.requirements.iter().enumerate() {
            s.met[k] += u64::from(r.met_by(metrics[*m]));
        }
        if !landed {
            return;
        }
        s.landed += 1;
        for (acc, &v) in s.moments.iter_mut().zip(metrics) {
            if v.is_finite() {
                acc.add(v);
            }
        }
        for (e, &(x, y)) in s.ellipses.iter_mut().zip(&self.landings) {
            let (x, y) = (metrics[x], metrics[y]);
            if x.is_finite() && y.is_finite() {
                e.add(x, y);
            }
        }
        if !self.dispersed.is_empty() {
            let xs = &mut self.scratch;
            xs.clear();
            xs.extend(self.dispersed.iter().map(|&j| inputs[j]));
            if xs.iter().all(|x| x.is_finite()) {
                s.fit
                    .get_or_insert_with(|| Fit::new(xs, self.metrics))
                    .add(xs, metrics);
            }
        }
    }

    /// How the percentiles are found.
    pub fn percentiles(&self) -> Percentiles {
        if self.table.is_some() {
            Percentiles::Exact
        } else {
            Percentiles::Digest
        }
    }

    /// The statistics of every sweep point.
    pub fn finish(&mut self) -> Vec<PointStats> {
        if let Some(t) = &self.table {
            let dispersed: Vec<bool> = (0..self.inputs)
                .map(|j| self.dispersed.contains(&j))
                .collect();
            return stats::compute(
                t,
                self.points,
                &dispersed,
                &self.landings,
                &self.requirements,
            );
        }
        let p = self.dispersed.len();
        // Each point's accumulators are its own: summed up side by side.
        use rayon::prelude::*;
        let metrics = self.metrics;
        self.streams
            .par_iter_mut()
            .enumerate()
            .map(|(point, s)| PointStats {
                point,
                variants: s.variants,
                failures: s.variants - s.landed,
                summaries: s.moments.iter_mut().map(MetricStream::summary).collect(),
                ellipse: s.ellipses.first().and_then(Bivariate::ellipse),
                release_ellipses: s.ellipses.iter().skip(1).map(Bivariate::ellipse).collect(),
                sensitivity: (0..metrics)
                    .map(|m| {
                        if p == 0 {
                            None
                        } else {
                            s.fit.as_ref().and_then(|f| f.sensitivity(m))
                        }
                    })
                    .collect(),
                requirements: s
                    .met
                    .iter()
                    .map(|&met| compliance(met, s.variants))
                    .collect(),
            })
            .collect()
    }
}

/// One sweep point's accumulators.
#[derive(Debug)]
struct PointStream {
    variants: u64,
    landed: u64,
    met: Vec<u64>,
    moments: Vec<MetricStream>,
    ellipses: Vec<Bivariate>,
    fit: Option<Fit>,
}

impl PointStream {
    fn new(metrics: usize, landings: usize, requirements: &[(usize, RequirementSpec)]) -> Self {
        PointStream {
            variants: 0,
            landed: 0,
            met: vec![0; requirements.len()],
            moments: (0..metrics).map(|_| MetricStream::default()).collect(),
            ellipses: vec![Bivariate::default(); landings],
            fit: None,
        }
    }
}

/// A column's count, sum (in row order), Welford's mean and sum of squared deviations, least
/// and greatest, as the rows pass: the metrics' here, the inputs' in the report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Moments {
    pub n: u64,
    pub sum: f64,
    pub mean: f64,
    pub m2: f64,
    pub min: f64,
    pub max: f64,
}

impl Default for Moments {
    fn default() -> Self {
        Moments {
            n: 0,
            sum: 0.0,
            mean: 0.0,
            m2: 0.0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
        }
    }
}

impl Moments {
    pub fn add(&mut self, x: f64) {
        self.n += 1;
        self.sum += x;
        let d = x - self.mean;
        self.mean += d / self.n as f64;
        self.m2 += d * (x - self.mean);
        self.min = self.min.min(x);
        self.max = self.max.max(x);
    }
}

/// A metric's moments and its digest (its finite values only).
#[derive(Debug, Default)]
struct MetricStream {
    moments: Moments,
    digest: Digest,
}

impl MetricStream {
    fn add(&mut self, x: f64) {
        self.moments.add(x);
        self.digest.add(x);
    }

    fn summary(&mut self) -> Option<Summary> {
        let m = self.moments;
        if m.n == 0 {
            return None;
        }
        let n = m.n as f64;
        let mut q = |p: f64| self.digest.quantile(p).clamp(m.min, m.max);
        Some(Summary {
            count: m.n,
            mean: m.sum / n,
            std: (m.n > 1).then(|| (m.m2 / (n - 1.0)).sqrt()),
            min: m.min,
            p1: q(0.01),
            p5: q(0.05),
            p50: q(0.5),
            p95: q(0.95),
            p99: q(0.99),
            max: m.max,
        })
    }
}

/// Welford's bivariate update: the landing points' means and co-moments.
#[derive(Debug, Clone, Default)]
struct Bivariate {
    n: u64,
    mx: f64,
    my: f64,
    cxx: f64,
    cyy: f64,
    cxy: f64,
}

impl Bivariate {
    fn add(&mut self, x: f64, y: f64) {
        self.n += 1;
        let n = self.n as f64;
        let (dx, dy) = (x - self.mx, y - self.my);
        self.mx += dx / n;
        self.my += dy / n;
        self.cxx += dx * (x - self.mx);
        self.cyy += dy * (y - self.my);
        self.cxy += dx * (y - self.my);
    }

    fn ellipse(&self) -> Option<Ellipse> {
        if self.n < 3 {
            return None;
        }
        let d = self.n as f64 - 1.0;
        let (vxx, vyy, vxy) = (self.cxx / d, self.cyy / d, self.cxy / d);
        let (a, b, angle) = stats::covariance_axes(vxx, vyy, vxy);
        Some(Ellipse {
            count: self.n,
            center_x_m: self.mx,
            center_y_m: self.my,
            var_x_m2: vxx,
            var_y_m2: vyy,
            cov_xy_m2: vxy,
            semi_major_m: a,
            semi_minor_m: b,
            major_axis_deg: angle,
        })
    }
}

/// Index of (j, k), j ≤ k, in a packed upper triangle of side `p`.
fn tri(p: usize, j: usize, k: usize) -> usize {
    j * p - j * (j + 1) / 2 + k
}

/// The sufficient statistics of one point's sensitivity fits: over its landed rows, the
/// dispersed inputs' sums and cross-products about the point's first landed row, and per
/// metric the same over the rows where the metric has no value (taken off), the metric's
/// own sums and its cross-products with the inputs.
#[derive(Debug)]
struct Fit {
    p: usize,
    x0: Vec<f64>,
    n: u64,
    sx: Vec<f64>,
    sxx: Vec<f64>,
    /// Per metric.
    ys: Vec<YSums>,
    dx: Vec<f64>,
}

#[derive(Debug, Default, Clone)]
struct YSums {
    /// The metric's first value, the origin of its sums.
    y0: Option<f64>,
    sy: f64,
    syy: f64,
    sxy: Vec<f64>,
    /// The rows without a value: their count and input sums, taken off the point's.
    missing: Option<Box<(u64, Vec<f64>, Vec<f64>)>>,
}

impl Fit {
    fn new(x0: &[f64], metrics: usize) -> Fit {
        let p = x0.len();
        Fit {
            p,
            x0: x0.to_vec(),
            n: 0,
            sx: vec![0.0; p],
            sxx: vec![0.0; p * (p + 1) / 2],
            ys: vec![
                YSums {
                    sxy: vec![0.0; p],
                    ..YSums::default()
                };
                metrics
            ],
            dx: vec![0.0; p],
        }
    }

    fn add(&mut self, xs: &[f64], metrics: &[f64]) {
        let p = self.p;
        for j in 0..p {
            self.dx[j] = xs[j] - self.x0[j];
        }
        self.n += 1;
        add_products(&mut self.sx, &mut self.sxx, &self.dx);
        for (ys, &y) in self.ys.iter_mut().zip(metrics) {
            if !y.is_finite() {
                let miss = ys
                    .missing
                    .get_or_insert_with(|| Box::new((0, vec![0.0; p], vec![0.0; p * (p + 1) / 2])));
                miss.0 += 1;
                add_products(&mut miss.1, &mut miss.2, &self.dx);
                continue;
            }
            let dy = y - *ys.y0.get_or_insert(y);
            ys.sy += dy;
            ys.syy += dy * dy;
            for (s, d) in ys.sxy.iter_mut().zip(&self.dx) {
                *s += d * dy;
            }
        }
    }

    /// The fit of metric `m` on the dispersed inputs, as [`stats::sensitivity`] defines it.
    fn sensitivity(&self, m: usize) -> Option<Sensitivity> {
        let p = self.p;
        let ys = &self.ys[m];
        let (mut n, mut sx, mut sxx) = (self.n, self.sx.clone(), self.sxx.clone());
        if let Some(miss) = &ys.missing {
            n -= miss.0;
            for (a, b) in sx.iter_mut().zip(&miss.1) {
                *a -= b;
            }
            for (a, b) in sxx.iter_mut().zip(&miss.2) {
                *a -= b;
            }
        }
        if n < 3 {
            return None;
        }
        let nf = n as f64;
        // Centred co-moments.
        let cxx = |j: usize, k: usize| {
            let (a, b) = (j.min(k), j.max(k));
            sxx[tri(p, a, b)] - sx[a] * sx[b] / nf
        };
        let cyy = ys.syy - ys.sy * ys.sy / nf;
        let cxy: Vec<f64> = (0..p).map(|j| ys.sxy[j] - sx[j] * ys.sy / nf).collect();
        let sy = (cyy / (nf - 1.0)).sqrt();
        if sy.is_nan() || sy <= 0.0 {
            return None;
        }
        let stats: Vec<(f64, f64)> = (0..p)
            .map(|j| {
                (
                    self.x0[j] + sx[j] / nf,
                    (cxx(j, j).max(0.0) / (nf - 1.0)).sqrt(),
                )
            })
            .collect();
        let used: Vec<usize> = (0..p)
            .filter(|&j| stats[j].1 > 1e-12 * stats[j].0.abs().max(f64::MIN_POSITIVE))
            .collect();
        let q = used.len();
        let mut out = Sensitivity {
            count: n,
            r2: 0.0,
            coefficients: vec![None; p],
            standardized: vec![None; p],
            correlations: vec![None; p],
            shares: vec![None; p],
        };
        if q == 0 {
            return Some(out);
        }
        if n <= q as u64 + 1 {
            return None;
        }
        // The normal equations of the standardized inputs: (ZᵀZ) b = Zᵀ(y − ȳ).
        let zz = Mat::<f64>::from_fn(q, q, |a, b| {
            let (j, k) = (used[a], used[b]);
            cxx(j, k) / (stats[j].1 * stats[k].1)
        });
        let zy = Mat::<f64>::from_fn(q, 1, |a, _| cxy[used[a]] / stats[used[a]].1);
        let b = zz.col_piv_qr().solve_lstsq(&zy);
        let bzy: f64 = (0..q).map(|a| b[(a, 0)] * zy[(a, 0)]).sum();
        let bzzb: f64 = (0..q)
            .map(|a| {
                (0..q)
                    .map(|c| b[(a, 0)] * zz[(a, c)] * b[(c, 0)])
                    .sum::<f64>()
            })
            .sum();
        let ss_res = (cyy - 2.0 * bzy + bzzb).max(0.0);
        out.r2 = 1.0 - ss_res / cyy;
        for (a, &j) in used.iter().enumerate() {
            let bk = b[(a, 0)];
            let r = zy[(a, 0)] / ((nf - 1.0) * sy);
            out.coefficients[j] = Some(bk / stats[j].1);
            out.standardized[j] = Some(bk / sy);
            out.correlations[j] = Some(r);
            out.shares[j] = Some(bk / sy * r);
        }
        Some(out)
    }
}

/// Add `d` to the sums `s` and its products to the packed triangle `ss`.
fn add_products(s: &mut [f64], ss: &mut [f64], d: &[f64]) {
    let p = d.len();
    let mut at = 0;
    for j in 0..p {
        s[j] += d[j];
        let dj = d[j];
        for dk in &d[j..p] {
            ss[at] += dj * dk;
            at += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows of 2 points: 3 inputs (the second not dispersed), 4 metrics (the last missing
    /// on some landed rows), landings at metrics 1 and 2, a few rows not landed.
    fn rows(n: usize) -> Vec<(usize, Status, Vec<f64>, Vec<f64>)> {
        let mut s = 11u64;
        let mut u = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64) / (1u64 << 53) as f64 - 0.5
        };
        (0..n)
            .map(|i| {
                let point = i * 2 / n;
                let x = [1.0 + 0.1 * u(), 7.0, 300.0 + 20.0 * u()];
                let noise = u();
                let y0 = 1500.0 + 200.0 * x[0] - 0.5 * x[2] + 3.0 * noise + point as f64;
                let status = if i % 17 == 5 {
                    Status::Failed
                } else {
                    Status::Landed
                };
                let lx = 100.0 + 30.0 * u() + 10.0 * x[0];
                let ly = -50.0 + 10.0 * u() + 0.1 * lx;
                let last = if i % 13 == 2 {
                    f64::NAN
                } else {
                    2.0 * x[0] + u()
                };
                (point, status, x.to_vec(), vec![y0, lx, ly, last])
            })
            .collect()
    }

    fn gather(exact_rows: usize, data: &[(usize, Status, Vec<f64>, Vec<f64>)]) -> Gather {
        let req = [(
            0usize,
            RequirementSpec {
                metric: "m0".into(),
                min: Some(1490.0),
                max: None,
            },
        )];
        let mut g =
            Gather::with_exact_rows(2, &[true, false, true], 4, &[(1, 2)], &req, exact_rows);
        for (point, status, x, m) in data {
            g.push(Row {
                point: *point,
                status: *status,
                warned: None,
                inputs: x,
                metrics: m,
            });
        }
        g
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * a.abs().max(b.abs()).max(1e-300)
    }

    #[test]
    fn streamed_statistics_agree_with_the_exact_ones_and_counts_are_equal() {
        let data = rows(4000);
        let mut exact = gather(1_000_000, &data);
        let mut streamed = gather(100, &data);
        assert_eq!(exact.percentiles(), Percentiles::Exact);
        assert_eq!(streamed.percentiles(), Percentiles::Digest);
        let (a, b) = (exact.finish(), streamed.finish());
        for (a, b) in a.iter().zip(&b) {
            assert_eq!((a.variants, a.failures), (b.variants, b.failures));
            assert_eq!(a.requirements, b.requirements);
            for (sa, sb) in a.summaries.iter().zip(&b.summaries) {
                let (sa, sb) = (sa.unwrap(), sb.unwrap());
                assert_eq!((sa.count, sa.min, sa.max), (sb.count, sb.min, sb.max));
                // The mean is the same sum over the same count.
                assert_eq!(sa.mean, sb.mean);
                assert!(close(sa.std.unwrap(), sb.std.unwrap(), 1e-12));
                // Fewer than 2,000 values a point: the digest holds them nearly one by one.
                for (qa, qb) in [(sa.p5, sb.p5), (sa.p50, sb.p50), (sa.p95, sb.p95)] {
                    assert!((qa - qb).abs() <= 1e-3 * (sa.max - sa.min), "{qa} {qb}");
                }
            }
            let (ea, eb) = (a.ellipse.unwrap(), b.ellipse.unwrap());
            assert_eq!(ea.count, eb.count);
            for (x, y) in [
                (ea.center_x_m, eb.center_x_m),
                (ea.center_y_m, eb.center_y_m),
                (ea.var_x_m2, eb.var_x_m2),
                (ea.var_y_m2, eb.var_y_m2),
                (ea.cov_xy_m2, eb.cov_xy_m2),
                (ea.semi_major_m, eb.semi_major_m),
                (ea.major_axis_deg, eb.major_axis_deg),
            ] {
                assert!(close(x, y, 1e-11), "{x} {y}");
            }
            for (fa, fb) in a.sensitivity.iter().zip(&b.sensitivity) {
                let (fa, fb) = (fa.as_ref().unwrap(), fb.as_ref().unwrap());
                assert_eq!(fa.count, fb.count);
                assert!(close(fa.r2, fb.r2, 1e-9), "{} {}", fa.r2, fb.r2);
                // One coefficient per dispersed input (the first and the third).
                assert_eq!((fa.coefficients.len(), fb.coefficients.len()), (2, 2));
                for k in 0..2 {
                    match (fa.coefficients[k], fb.coefficients[k]) {
                        (None, None) => {}
                        (Some(x), Some(y)) => assert!(close(x, y, 1e-9), "{x} {y}"),
                        other => panic!("{other:?}"),
                    }
                    if let (Some(x), Some(y)) = (fa.shares[k], fb.shares[k]) {
                        assert!((x - y).abs() < 1e-9, "{x} {y}");
                    }
                }
            }
        }
        // The fit found the law the rows were made with: 200 per unit of the first input,
        // −0.5 per unit of the third (the noise, 3 × uniform(−½, ½), moves them by about 1 %).
        let fit = b[0].sensitivity[0].as_ref().unwrap();
        assert!(
            (fit.coefficients[0].unwrap() - 200.0).abs() < 2.0,
            "{fit:?}"
        );
        assert!((fit.coefficients[1].unwrap() + 0.5).abs() < 0.01, "{fit:?}");
        assert_eq!(
            (exact.rows, exact.landed, exact.failed),
            (streamed.rows, streamed.landed, streamed.failed)
        );
        assert_eq!(
            exact.failed,
            (0..4000).filter(|i| i % 17 == 5).count() as u64
        );
    }

    #[test]
    fn streamed_statistics_are_the_same_bits_however_the_rows_were_cut() {
        // The crossing happens at a fixed row: the same rows give the same figures.
        let data = rows(3000);
        let a = gather(500, &data).finish();
        let b = gather(500, &data).finish();
        assert_eq!(format!("{a:?}"), format!("{b:?}"));
    }
}
