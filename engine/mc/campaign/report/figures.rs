//! The report's figures, each an SVG chart of [`crate::chart`] drawn from a run's rows: the
//! landing map, histograms and empirical distributions, rows of distributions on a shared
//! axis, bands against time, lines against a swept input, tornadoes and convergence.

use super::data::{EllipseRow, Run};
use super::numbers::{at_time, bands, histogram, radii};
use crate::campaign::stats::quantile;
use crate::chart::{esc, extent, fmt_tick, ticks, Chart, Key, PALETTE};

pub const W: f64 = 560.0;
pub const H: f64 = 330.0;
/// Landings drawn one by one up to this many at a point; more are drawn as a density.
pub const MAX_DOTS: usize = 1500;

/// A unit for an axis label (`""` for a pure number).
pub fn unit_text(u: &str) -> String {
    if u == "1" || u.is_empty() {
        String::new()
    } else {
        format!(" ({u})")
    }
}

/// A histogram of `values` with vertical lines `(x, label, colour)`; each bar carries its
/// count (`data-count`), so the bars add up to the values drawn.
pub fn histogram_chart(
    id: &str,
    title: &str,
    x_label: &str,
    values: &[f64],
    lines: &[(f64, String, &str)],
) -> Option<String> {
    let bins = histogram(values, 28);
    if bins.is_empty() {
        return None;
    }
    let top = bins.iter().map(|b| b.2).max().unwrap_or(1) as f64;
    let mut xs: Vec<f64> = vec![bins[0].0, bins[bins.len() - 1].1];
    xs.extend(lines.iter().map(|l| l.0));
    let (x0, x1) = extent(&xs, 0.03)?;
    let mut ch = Chart::new(id, W, H, (x0, x1), (0.0, top * 1.12))
        .title(title)
        .labels(x_label, "flights");
    for (lo, hi, n) in &bins {
        ch.bar(*lo, *hi, *n as f64, PALETTE[0], *n);
    }
    for (x, label, color) in lines {
        ch.vline(*x, color, true, label);
    }
    Some(ch.svg())
}

/// The empirical distribution of `values` (the share of flights at or below x), with
/// vertical lines.
pub fn ecdf_chart(
    id: &str,
    title: &str,
    x_label: &str,
    values: &[f64],
    lines: &[(f64, String, &str)],
) -> Option<String> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let mut xs = vec![v[0], v[v.len() - 1]];
    xs.extend(lines.iter().map(|l| l.0));
    let (x0, x1) = extent(&xs, 0.03)?;
    let mut ch = Chart::new(id, W, H, (x0, x1), (0.0, 100.0))
        .title(title)
        .labels(x_label, "flights at or below (%)");
    let n = v.len() as f64;
    // Thin the steps to about 600 points: a step per flight is more than a screen shows.
    let stride = (v.len() / 600).max(1);
    let mut pts = vec![(x0, 0.0)];
    for (k, &x) in v.iter().enumerate() {
        if k % stride == 0 || k + 1 == v.len() {
            pts.push((x, 100.0 * k as f64 / n));
            pts.push((x, 100.0 * (k + 1) as f64 / n));
        }
    }
    pts.push((x1, 100.0));
    ch.line(&pts, PALETTE[0], 2.0, false);
    for q in [5.0, 50.0, 95.0] {
        ch.hline(q, "#999999", true, &format!("{q} %"));
    }
    for (x, label, color) in lines {
        ch.vline(*x, color, true, label);
    }
    Some(ch.svg())
}

/// One row of a [`rows_chart`]: its label, its values, and a bound to mark on it.
pub struct Row {
    pub label: String,
    pub values: Vec<f64>,
    pub bound: Option<(f64, String)>,
}

/// Distributions on one axis, one row each: whiskers from 5 to 95 %, a box from 25 to 75 %,
/// the median, and the least and greatest as dots; a row's bound as a red mark.
pub fn rows_chart(id: &str, title: &str, x_label: &str, rows: &[Row]) -> Option<String> {
    let rows: Vec<(&Row, Vec<f64>)> = rows
        .iter()
        .map(|r| {
            let mut v: Vec<f64> = r.values.iter().copied().filter(|x| x.is_finite()).collect();
            v.sort_by(f64::total_cmp);
            (r, v)
        })
        .filter(|(_, v)| !v.is_empty())
        .collect();
    if rows.is_empty() {
        return None;
    }
    let mut xs: Vec<f64> = rows
        .iter()
        .flat_map(|(_, v)| [v[0], v[v.len() - 1]])
        .collect();
    xs.extend(
        rows.iter()
            .filter_map(|(r, _)| r.bound.as_ref().map(|b| b.0)),
    );
    let (x0, x1) = extent(&xs, 0.04)?;
    let n = rows.len();
    // A row's bound is said in its name (the red mark on the row shows where it is).
    let named = |r: &Row| match &r.bound {
        Some((_, b)) => format!("{} (required {b})", r.label),
        None => r.label.clone(),
    };
    let longest = rows
        .iter()
        .map(|(r, _)| named(r).chars().count())
        .max()
        .unwrap_or(8);
    let left = (longest as f64 * 6.4 + 16.0).clamp(70.0, 300.0);
    let h = (74.0 + 30.0 * n as f64).max(140.0);
    let names = rows
        .iter()
        .enumerate()
        .map(|(k, (r, _))| ((n - 1 - k) as f64, named(r)))
        .collect();
    let mut ch = Chart::with_margins(id, W, h, (x0, x1), (-0.7, n as f64 - 0.3), left)
        .title(title)
        .labels(x_label, "")
        .y_names(names);
    for (k, (r, v)) in rows.iter().enumerate() {
        let y = (n - 1 - k) as f64;
        let q = |p: f64| quantile(v, p);
        ch.line(&[(q(0.05), y), (q(0.95), y)], "#444444", 1.5, false);
        ch.rect(q(0.25), q(0.75), y - 0.22, y + 0.22, PALETTE[0], 0.55);
        ch.line(
            &[(q(0.5), y - 0.3), (q(0.5), y + 0.3)],
            "#000000",
            2.5,
            false,
        );
        ch.dots(&[(v[0], y), (v[v.len() - 1], y)], 2.5, "#444444", 0.9);
        // The label beyond the row's outermost dot (the least or the greatest), so that
        // neither the whisker nor the dot crosses it.
        let (tx, anchor) = if (v[v.len() - 1] - x0) / (x1 - x0) > 0.75 {
            (v[0], "end")
        } else {
            (v[v.len() - 1], "start")
        };
        let dx = if anchor == "end" { -8.0 } else { 8.0 };
        ch.text(
            (tx, y),
            dx,
            4.0,
            &format!("median {}", short(q(0.5))),
            anchor,
            "#222222",
        );
        if let Some((b, _)) = &r.bound {
            ch.line(&[(*b, y - 0.42), (*b, y + 0.42)], "#C00000", 3.0, false);
        }
    }
    Some(ch.svg())
}

/// A number with about four significant digits.
pub fn short(x: f64) -> String {
    if !x.is_finite() {
        return "–".into();
    }
    let a = x.abs();
    if a == 0.0 {
        return "0".into();
    }
    if !(1e-3..1e6).contains(&a) {
        return format!("{x:.2e}");
    }
    let digits = a.log10().floor() as i32 + 1;
    let mut t = format!("{x:.*}", (4 - digits).clamp(0, 5) as usize);
    if t.contains('.') {
        t = t.trim_end_matches('0').trim_end_matches('.').to_string();
    }
    t.replacen('-', "−", 1)
}

/// A quantity band against time: `(label, colour, lo, mid, hi)` over the common times `t`.
pub type Band<'a> = (&'a str, &'a str, Vec<f64>, Vec<f64>, Vec<f64>);

pub fn bands_chart(
    id: &str,
    title: &str,
    y_label: &str,
    t: &[f64],
    series: &[Band],
    hlines: &[(f64, String, &str)],
) -> Option<String> {
    let mut ys: Vec<f64> = series
        .iter()
        .flat_map(|s| s.2.iter().chain(&s.4).copied())
        .collect();
    ys.extend(hlines.iter().map(|h| h.0));
    let (y0, y1) = extent(&ys, 0.06)?;
    let (x0, x1) = extent(t, 0.0)?;
    let mut ch = Chart::new(id, W, H, (x0, x1), (y0, y1))
        .title(title)
        .labels("time after ignition (s)", y_label);
    for (label, color, lo, mid, hi) in series {
        ch.band(t, lo, hi, color, 0.25);
        let pts: Vec<(f64, f64)> = t.iter().copied().zip(mid.iter().copied()).collect();
        ch.line(&pts, color, 2.0, false);
        ch.key(&format!("{label}: median"), color, Key::Line);
        ch.key(&format!("{label}: 5–95 %"), color, Key::Area);
    }
    for (y, label, color) in hlines {
        ch.hline(*y, color, true, label);
    }
    Some(ch.svg())
}

/// The common times and the 5/50/95 % bands of `value` over the flights `series`, from 0 to
/// each flight's own end (`until`), on 240 times.
pub fn series_bands(
    flights: &[(&[f64], &[f64], f64)],
    hold_after: Option<f64>,
) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let end = flights.iter().map(|f| f.2).fold(0.0f64, f64::max);
    let t: Vec<f64> = (0..=240).map(|k| end * k as f64 / 240.0).collect();
    let (mut lo, mut mid, mut hi) = (vec![], vec![], vec![]);
    for &at in &t {
        let mut v: Vec<f64> = flights
            .iter()
            .map(|(ts, vs, until)| {
                if at <= *until {
                    at_time(ts, vs, at)
                } else {
                    hold_after.unwrap_or(f64::NAN)
                }
            })
            .collect();
        let (a, b, c) = bands(&mut v);
        lo.push(a);
        mid.push(b);
        hi.push(c);
    }
    (t, lo, mid, hi)
}

/// Series of a metric against one swept input: `(label, x values, lo, mid, hi)`.
pub type SweepSeries = (String, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

/// Lines (medians, or shares) with their bands against the swept input `x_label`; `x_names`
/// names the x values in place of numeric ticks (a swept motor's designations).
pub fn sweep_chart(
    id: &str,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[SweepSeries],
    y_range: Option<(f64, f64)>,
    hline: Option<(f64, String)>,
    x_names: Option<Vec<(f64, String)>>,
) -> Option<String> {
    let xs: Vec<f64> = series.iter().flat_map(|s| s.1.iter().copied()).collect();
    let (x0, x1) = extent(&xs, 0.05)?;
    let y = match y_range {
        Some(r) => r,
        None => {
            let mut ys: Vec<f64> = series
                .iter()
                .flat_map(|s| s.2.iter().chain(&s.4).copied())
                .collect();
            ys.extend(hline.iter().map(|h| h.0));
            extent(&ys, 0.08)?
        }
    };
    let mut ch = Chart::new(id, W, H, (x0, x1), y)
        .title(title)
        .labels(x_label, y_label);
    if let Some(names) = x_names {
        ch = ch.x_names(names);
    }
    for (k, (label, x, lo, mid, hi)) in series.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        ch.band(x, lo, hi, color, 0.18);
        for (i, &xv) in x.iter().enumerate() {
            // Each point's interval as a bar too: a sweep of two values shows them.
            ch.line(&[(xv, lo[i]), (xv, hi[i])], color, 1.5, false);
        }
        let pts: Vec<(f64, f64)> = x.iter().copied().zip(mid.iter().copied()).collect();
        ch.line(&pts, color, 2.0, false);
        ch.dots(&pts, 3.5, color, 1.0);
        if !label.is_empty() {
            ch.key(label, color, Key::Line);
        }
    }
    if let Some((v, label)) = hline {
        ch.hline(v, "#C00000", true, &label);
    }
    Some(ch.svg())
}

/// What the landing map draws beside the landings.
pub struct MapMarks<'a> {
    pub ellipses: Vec<&'a EllipseRow>,
    /// The recovery area's radius about the launch point (the scenario's requirement on
    /// landing_distance_m), m.
    pub recovery_m: Option<f64>,
}

/// The landing map of one point: the landings (dots, or a density past [`MAX_DOTS`]), the
/// 1/2/3σ ellipses, R50/R90/R99 about the mean landing point, the launch point and the
/// recovery area, a north arrow and a scale bar. Returns the SVG, the radii and what the
/// cloud shows.
pub fn landing_map(
    id: &str,
    title: &str,
    xs: &[f64],
    ys: &[f64],
    marks: &MapMarks,
) -> Option<(String, [f64; 3], (f64, f64), String)> {
    if xs.is_empty() {
        return None;
    }
    let n = xs.len() as f64;
    let mean = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let r = radii(xs, ys, mean, &[0.5, 0.9, 0.99]);
    let mut ex: Vec<f64> = xs.to_vec();
    let mut ey: Vec<f64> = ys.to_vec();
    ex.push(0.0);
    ey.push(0.0);
    for e in &marks.ellipses {
        let a = e.semi_major_m;
        ex.extend([e.center_x_m - a, e.center_x_m + a]);
        ey.extend([e.center_y_m - a, e.center_y_m + a]);
    }
    ex.extend([mean.0 - r[2], mean.0 + r[2]]);
    ey.extend([mean.1 - r[2], mean.1 + r[2]]);
    if let Some(rr) = marks.recovery_m {
        ex.extend([-rr, rr]);
        ey.extend([-rr, rr]);
    }
    let (x0, x1) = extent(&ex, 0.06)?;
    let (y0, y1) = extent(&ey, 0.06)?;
    let mut ch = Chart::map(id, W, 500.0, (x0, x1), (y0, y1))
        .title(title)
        .labels("east of the rail (m)", "north of the rail (m)");
    let cloud;
    if xs.len() <= MAX_DOTS {
        let pts: Vec<(f64, f64)> = xs.iter().copied().zip(ys.iter().copied()).collect();
        ch.dots(&pts, 2.2, PALETTE[0], 0.45);
        cloud = format!("every one of the {} landings as a dot", xs.len());
    } else {
        // A density on square cells of a round size, about 70 across the map.
        let (_, cell) = ticks(ch.x.lo, ch.x.hi, 70);
        let (cx0, cy0) = ((ch.x.lo / cell).floor(), (ch.y.lo / cell).floor());
        let nx = ((ch.x.hi / cell).ceil() - cx0) as usize + 1;
        let ny = ((ch.y.hi / cell).ceil() - cy0) as usize + 1;
        let mut grid = vec![0u32; nx * ny];
        for (x, y) in xs.iter().zip(ys) {
            let i = ((x / cell).floor() - cx0) as usize;
            let j = ((y / cell).floor() - cy0) as usize;
            if i < nx && j < ny {
                grid[j * nx + i] += 1;
            }
        }
        let top = f64::from(*grid.iter().max().unwrap_or(&1));
        for j in 0..ny {
            for i in 0..nx {
                let c = grid[j * nx + i];
                if c > 0 {
                    let (gx, gy) = ((cx0 + i as f64) * cell, (cy0 + j as f64) * cell);
                    let o = 0.12 + 0.88 * (f64::from(c) / top).sqrt();
                    ch.rect(
                        gx,
                        gx + cell,
                        gy,
                        gy + cell,
                        PALETTE[0],
                        (o * 100.0).round() / 100.0,
                    );
                }
            }
        }
        cloud = format!(
            "the {} landings as a density on {} m cells (darker: more landings; the darkest holds {})",
            xs.len(),
            fmt_tick(cell, cell),
            top
        );
    }
    if let Some(rr) = marks.recovery_m {
        ch.circle(
            (0.0, 0.0),
            rr,
            "#009E73",
            2.0,
            false,
            Some(("#009E73", 0.06)),
            "recovery",
        );
        ch.key(
            &format!("recovery area: {} m about the rail", short(rr)),
            "#009E73",
            Key::Line,
        );
    }
    for (k, (name, &rad)) in ["R50", "R90", "R99"].iter().zip(&r).enumerate() {
        ch.circle(
            mean,
            rad,
            "#555555",
            1.2,
            true,
            None,
            &format!("radius {}", name.to_lowercase()),
        );
        let a = std::f64::consts::FRAC_PI_4 * (1.0 + k as f64 * 0.35);
        ch.text(
            (mean.0 + rad * a.cos(), mean.1 + rad * a.sin()),
            3.0,
            -3.0,
            name,
            "start",
            "#555555",
        );
    }
    ch.key("R50 / R90 / R99 about the mean", "#555555", Key::Dashed);
    for e in &marks.ellipses {
        let width = if e.sigma == 1 { 2.4 } else { 1.6 };
        ch.ellipse(
            (e.center_x_m, e.center_y_m),
            e.semi_major_m,
            e.semi_minor_m,
            e.major_axis_deg,
            "#D55E00",
            width,
            e.sigma > 1,
            &format!("ellipse sigma{}", e.sigma),
        );
        let t = e.major_axis_deg.to_radians();
        ch.text(
            (
                e.center_x_m + e.semi_major_m * t.cos(),
                e.center_y_m + e.semi_major_m * t.sin(),
            ),
            4.0,
            4.0,
            &format!("{}σ", e.sigma),
            "start",
            "#D55E00",
        );
    }
    if !marks.ellipses.is_empty() {
        ch.key("1σ, 2σ, 3σ ellipses", "#D55E00", Key::Line);
    }
    // The launch point: a triangle.
    let (px, py) = ch.px(0.0, 0.0);
    ch.overlay(&format!(
        "<path d=\"M{:.1} {:.1}l6 10h-12z\" fill=\"#000000\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"11\" paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\">launch</text>\n",
        px,
        py - 6.0,
        px + 8.0,
        py + 4.0
    ));
    ch.key("landing", PALETTE[0], Key::Dot);
    ch.key("launch point", "#000000", Key::Dot);
    // North arrow and scale bar.
    let (l, t, _, b) = ch.area();
    ch.occupy((l + 8.0, t + 18.0), (l + 32.0, t + 70.0));
    ch.overlay(&format!(
        "<g stroke=\"#000000\" fill=\"#000000\"><line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{0:.1}\" y2=\"{2:.1}\" stroke-width=\"2\"/><path d=\"M{0:.1} {2:.1}l-5 9h10z\"/></g><text x=\"{0:.1}\" y=\"{3:.1}\" text-anchor=\"middle\" font-weight=\"bold\">N</text>\n",
        l + 20.0,
        t + 52.0,
        t + 24.0,
        t + 66.0
    ));
    let (_, step) = ticks(0.0, (ch.x.hi - ch.x.lo) / 4.0, 1);
    let len_px = step * ch.x.per_unit();
    ch.occupy((l + 10.0, b - 36.0), (l + 18.0 + len_px, b - 10.0));
    ch.overlay(&format!(
        "<g stroke=\"#000000\" stroke-width=\"2\"><line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{2:.1}\" y2=\"{1:.1}\"/><line x1=\"{0:.1}\" y1=\"{3:.1}\" x2=\"{0:.1}\" y2=\"{1:.1}\"/><line x1=\"{2:.1}\" y1=\"{3:.1}\" x2=\"{2:.1}\" y2=\"{1:.1}\"/></g><text class=\"scale\" data-metres=\"{4}\" data-pixels=\"{5}\" x=\"{6:.1}\" y=\"{7:.1}\" text-anchor=\"middle\" paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\">{8} m</text>\n",
        l + 14.0,
        b - 14.0,
        l + 14.0 + len_px,
        b - 20.0,
        step,
        len_px,
        l + 14.0 + len_px / 2.0,
        b - 22.0,
        esc(&fmt_tick(step, step))
    ));
    Some((ch.svg(), [r[0], r[1], r[2]], mean, cloud))
}

/// A tornado: each dispersed input's effect on `metric` when it moves by one standard
/// deviation (β* σ of the metric, from the point's linear fit), the largest first, with its
/// share of the metric's variance.
pub fn tornado(id: &str, run: &Run, pt: usize, metric: &str, unit: &str) -> Option<String> {
    let sd = run.summary_of(pt, metric)?.std?;
    let mut rows: Vec<(&str, f64, f64)> = run
        .sensitivity
        .iter()
        .filter(|s| s.point == pt && s.metric == metric)
        .filter_map(|s| {
            Some((
                s.input.as_str(),
                s.standardized? * sd,
                s.share.unwrap_or(0.0),
            ))
        })
        .collect();
    if rows.is_empty() {
        return None;
    }
    let r2 = run
        .sensitivity
        .iter()
        .find(|s| s.point == pt && s.metric == metric)
        .map_or(f64::NAN, |s| s.r2);
    rows.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
    rows.truncate(8);
    let reach = rows
        .iter()
        .map(|r| r.1.abs())
        .fold(0.0f64, f64::max)
        .max(1e-12);
    let n = rows.len();
    let longest = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(8);
    let left = (longest as f64 * 6.4 + 16.0).clamp(70.0, 260.0);
    let names = rows
        .iter()
        .enumerate()
        .map(|(k, r)| ((n - 1 - k) as f64, r.0.to_string()))
        .collect();
    // The bars on the left part, their figures in a column on the right.
    let mut ch = Chart::with_margins(
        id,
        W,
        (84.0 + 28.0 * n as f64).max(150.0),
        (-1.08 * reach, 2.35 * reach),
        (-0.7, n as f64 - 0.3),
        left,
    )
    .title(&format!("What moves {metric} (linear fit R² {:.2})", r2))
    .labels(
        &format!("change for +1σ and −1σ of the input{}", unit_text(unit)),
        "",
    )
    .y_names(names)
    .x_names({
        let (t, step) = ticks(-reach, reach, 4);
        t.into_iter().map(|v| (v, fmt_tick(v, step))).collect()
    });
    for (k, (_, effect, share)) in rows.iter().enumerate() {
        let y = (n - 1 - k) as f64;
        ch.rect(0.0, *effect, y - 0.32, y + 0.32, PALETTE[0], 0.85);
        ch.rect(0.0, -*effect, y - 0.32, y + 0.32, PALETTE[1], 0.85);
        // Pratt's share can come out a hair below 0 for an input that does nothing.
        let share = (100.0 * share).max(0.0);
        ch.text(
            (1.14 * reach, y),
            0.0,
            4.0,
            &format!("±{} · {share:.0} % of variance", short(effect.abs())),
            "start",
            "#222222",
        );
    }
    ch.line(&[(0.0, -0.7), (0.0, n as f64 - 0.3)], "#000000", 1.0, false);
    ch.key("input +1σ", PALETTE[0], Key::Area);
    ch.key("input −1σ", PALETTE[1], Key::Area);
    Some(ch.svg())
}

/// The running mean and 5/95 % quantiles of `values` (in flight order) against the number
/// of flights, on a logarithmic axis, with the final values as thin lines.
pub fn convergence(id: &str, title: &str, y_label: &str, values: &[f64]) -> Option<String> {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.len() < 10 {
        return None;
    }
    let n = v.len();
    let steps = 48;
    let counts: Vec<usize> = {
        let mut c: Vec<usize> = (0..=steps)
            .map(|k| (10.0 * (n as f64 / 10.0).powf(k as f64 / steps as f64)).round() as usize)
            .map(|c| c.clamp(10, n))
            .collect();
        c.dedup();
        c
    };
    let mut prefix = vec![0.0];
    for x in &v {
        prefix.push(prefix[prefix.len() - 1] + x);
    }
    let (mut mean, mut p5, mut p95) = (vec![], vec![], vec![]);
    let mut buf = Vec::with_capacity(n);
    for &c in &counts {
        mean.push(prefix[c] / c as f64);
        buf.clear();
        buf.extend_from_slice(&v[..c]);
        buf.sort_by(f64::total_cmp);
        p5.push(quantile(&buf, 0.05));
        p95.push(quantile(&buf, 0.95));
    }
    let all: Vec<f64> = p5.iter().chain(&p95).chain(&mean).copied().collect();
    let (y0, y1) = extent(&all, 0.08)?;
    let x: Vec<f64> = counts.iter().map(|&c| c as f64).collect();
    let mut ch = Chart::new(id, W, H, (10.0, n as f64), (y0, y1))
        .log_x()
        .title(title)
        .labels("flights counted (the first n, in variant order)", y_label);
    for (series, color, label) in [
        (&p95, PALETTE[1], "95 %"),
        (&mean, PALETTE[0], "mean"),
        (&p5, PALETTE[2], "5 %"),
    ] {
        let last = series[series.len() - 1];
        ch.hline(last, color, true, "");
        let pts: Vec<(f64, f64)> = x.iter().copied().zip(series.iter().copied()).collect();
        ch.line(&pts, color, 2.0, false);
        ch.key(&format!("{label}: {}", short(last)), color, Key::Line);
    }
    Some(ch.svg())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` landings on a deterministic spiral about (200, −50) m.
    fn cloud(n: usize) -> (Vec<f64>, Vec<f64>) {
        (0..n)
            .map(|k| {
                let r = 300.0 * ((k as f64 + 0.5) / n as f64).sqrt();
                let a = k as f64 * 2.399_963;
                (200.0 + r * a.cos(), -50.0 + 0.6 * r * a.sin())
            })
            .unzip()
    }

    fn marks() -> MapMarks<'static> {
        MapMarks {
            ellipses: vec![],
            recovery_m: Some(600.0),
        }
    }

    #[test]
    fn a_dense_landing_cloud_is_drawn_as_a_density_whose_size_does_not_grow_with_it() {
        let (xs, ys) = cloud(1000);
        let (svg, ..) = landing_map("a", "t", &xs, &ys, &marks()).unwrap();
        // Every landing a dot, plus R50/R90/R99, the recovery area and the legend's dot.
        assert_eq!(svg.matches("<circle").count(), 1000 + 3 + 1 + 2);
        let mut sizes = vec![];
        for n in [20_000, 160_000] {
            let (xs, ys) = cloud(n);
            let (svg, _, _, cloud_text) = landing_map("b", "t", &xs, &ys, &marks()).unwrap();
            assert!(cloud_text.contains("density"), "{cloud_text}");
            assert_eq!(svg.matches("<circle").count(), 3 + 1 + 2);
            sizes.push(svg.len());
        }
        // The same cells filled: the size is the cells', not the flights'.
        assert!(sizes[0] < 400_000, "{sizes:?}");
        assert!((sizes[1] as f64) < 1.1 * sizes[0] as f64, "{sizes:?}");
    }

    #[test]
    fn r50_r90_r99_hold_their_shares_of_the_landings() {
        let (xs, ys) = cloud(2000);
        let (_, r, mean, _) = landing_map("c", "t", &xs, &ys, &marks()).unwrap();
        for (radius, share) in r.iter().zip([0.5, 0.9, 0.99]) {
            let inside = xs
                .iter()
                .zip(&ys)
                .filter(|(x, y)| (*x - mean.0).hypot(*y - mean.1) <= *radius)
                .count();
            // Type-7 quantiles of 2,000 distances: within one landing of the share.
            assert!(
                (inside as f64 - share * 2000.0).abs() <= 1.0,
                "{share}: {inside}"
            );
        }
    }
}
