//! The page: its header (the scenario, its fingerprint, seed, variants, version, date, the
//! inputs and their distributions), the sweep's answer (each requirement's share against the
//! swept values, the key metrics' medians and 5–95 % bands), one section per sweep point
//! (landings, apogee, the flight's figures, margins and height against time, sensitivity,
//! convergence) and the flights to look at, each with the command that flies it again.

use super::data::{Body, Run, Status};
use super::figures::series_bands;
use super::figures::{self, short, unit_text, MapMarks, Row};
use super::numbers::{binomial_upper, utc};
use crate::campaign::stats::quantile;
use crate::chart::{esc, PALETTE};
use std::fmt::Write as _;

/// What the page takes from the scenario's text (kept in the files' metadata) and the
/// columns: names, labels and the inputs' distributions.
pub struct Context {
    pub name: String,
    pub description: Option<String>,
    pub scenario_file: String,
    pub elevation_m: f64,
    /// `" (key = v, …)"` of each point (empty without a sweep).
    pub point_labels: Vec<String>,
    /// Input column → (swept values, the dispersion as the file writes it).
    pub inputs: Vec<(Option<String>, Option<String>)>,
    /// Extra arguments a `fly --variant` needs for this run's ids: the run's seed and
    /// variants per point where the command line replaced the file's.
    pub fly_overrides: String,
    /// The key metrics: apogee, the margin after each shift, the landing distance.
    pub key_metrics: Vec<usize>,
}

/// An input's column from its key path, as the run names it.
fn column_of(key: &str) -> String {
    if let Some(rest) = key.strip_prefix("parachutes.") {
        format!("parachute_{}", rest.replace('.', "_"))
    } else if let Some(rest) = key.strip_prefix("shifts.") {
        format!("shift_{}", rest.replace('.', "_"))
    } else {
        key.to_string()
    }
}

/// A TOML value as a reader writes it.
fn toml_text(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Float(f) => short(*f),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::Array(a) => {
            let items: Vec<String> = a.iter().map(toml_text).collect();
            items.join(", ")
        }
        toml::Value::Table(t) => {
            let items: Vec<String> = t
                .iter()
                .filter(|(k, _)| *k != "dist")
                .map(|(k, v)| format!("{k} {}", toml_text(v)))
                .collect();
            match t.get("dist") {
                Some(d) => format!("{}: {}", toml_text(d), items.join(", ")),
                None => items.join(", "),
            }
        }
        toml::Value::Datetime(d) => d.to_string(),
    }
}

/// Leaves of a nested TOML table by key path: a leaf is a table with `dist` (a dispersion)
/// or anything that is not a table (a sweep's list).
fn leaves(prefix: &str, t: &toml::Table, out: &mut Vec<(String, toml::Value)>) {
    for (k, v) in t {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            toml::Value::Table(inner) if !inner.contains_key("dist") => leaves(&key, inner, out),
            v => out.push((key, v.clone())),
        }
    }
}

impl Context {
    pub fn of(run: &Run) -> Context {
        let text = run.meta("hpr_mc.scenario");
        let scenario_file = run.meta("hpr_mc.scenario_file").to_string();
        let doc: toml::Table = text.parse().unwrap_or_default();
        let name = doc
            .get("name")
            .and_then(|v| v.as_str())
            .map(str::to_string)
            .unwrap_or_else(|| {
                std::path::Path::new(&scenario_file)
                    .file_stem()
                    .map_or("run".into(), |s| s.to_string_lossy().into_owned())
            });
        let elevation_m = doc
            .get("environment")
            .and_then(|e| e.get("elevation_m"))
            .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
            .unwrap_or(0.0);
        let mut sweep = vec![];
        if let Some(t) = doc.get("sweep").and_then(|v| v.as_table()) {
            leaves("", t, &mut sweep);
        }
        let mut disp = vec![];
        if let Some(t) = doc.get("dispersions").and_then(|v| v.as_table()) {
            leaves("", t, &mut disp);
        }
        let find = |list: &[(String, toml::Value)], col: &str| {
            list.iter()
                .find(|(k, _)| column_of(k) == col)
                .map(|(_, v)| toml_text(v))
        };
        let inputs = run
            .inputs
            .iter()
            .map(|c| (find(&sweep, &c.name), find(&disp, &c.name)))
            .collect();
        let mut fly_overrides = String::new();
        let file_seed = doc
            .get("seed")
            .and_then(|v| v.as_integer())
            .map(|s| s.to_string());
        if file_seed.as_deref() != Some(run.meta("hpr_mc.seed")) {
            let _ = write!(fly_overrides, " --run-seed {}", run.meta("hpr_mc.seed"));
        }
        let file_vpp = doc
            .get("variants_per_point")
            .and_then(|v| v.as_integer())
            .map(|s| s.to_string());
        if file_vpp.as_deref() != Some(run.meta("hpr_mc.variants_per_point")) {
            let _ = write!(
                fly_overrides,
                " --variants {}",
                run.meta("hpr_mc.variants_per_point")
            );
        }
        let point_labels = (0..run.points())
            .map(|pt| {
                let parts: Vec<String> = (0..run.sweep.len())
                    .map(|k| format!("{} = {}", sweep_name(run, k), sweep_value(run, pt, k)))
                    .collect();
                if parts.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", parts.join(", "))
                }
            })
            .collect();
        let mut key_metrics: Vec<usize> = run.metric("apogee_m").into_iter().collect();
        key_metrics.extend(
            run.metrics
                .iter()
                .enumerate()
                .filter(|(_, m)| {
                    m.name.starts_with("shift_") && m.name.ends_with("_margin_after_cal")
                })
                .map(|(k, _)| k),
        );
        if key_metrics.len() == 1 {
            key_metrics.extend(run.metric("static_margin_min_cal"));
        }
        key_metrics.extend(run.metric("landing_distance_m"));
        Context {
            name,
            description: doc
                .get("description")
                .and_then(|v| v.as_str())
                .map(str::to_string),
            scenario_file,
            elevation_m,
            point_labels,
            inputs,
            fly_overrides,
            key_metrics,
        }
    }

    /// The command that flies variant `id` again, with a flight plot.
    pub fn fly_command(&self, id: u64) -> String {
        format!(
            "hpr-mc fly --scenario {} --variant {id}{} --plot variant-{id}.html",
            shell_word(&self.scenario_file),
            self.fly_overrides
        )
    }
}

/// A path as one shell word.
fn shell_word(s: &str) -> String {
    if s.chars()
        .all(|c| c.is_ascii_alphanumeric() || "/._-+:,@".contains(c))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// The name of swept input `k`: `motor` for a swept motor (its values are designations).
fn sweep_name(run: &Run, k: usize) -> &str {
    match run.sweep_motor(0, k) {
        Some(_) => "motor",
        None => &run.sweep[k].name,
    }
}

/// Swept input `k`'s value at point `pt` with its unit, or the designation of a swept motor.
fn sweep_value(run: &Run, pt: usize, k: usize) -> String {
    match run.sweep_motor(pt, k) {
        Some(d) => d.to_string(),
        None => format!(
            "{}{}",
            short(run.sweep_values[pt][k]),
            unit_suffix(&run.sweep[k].unit)
        ),
    }
}

fn unit_suffix(u: &str) -> String {
    if u == "1" || u.is_empty() {
        String::new()
    } else {
        format!(" {u}")
    }
}

const CSS: &str = "
body{font-family:Helvetica,Arial,sans-serif;color:#222;margin:0;background:#f4f4f2}
main{max-width:1180px;margin:0 auto;padding:18px 22px 40px;background:#fff}
h1{font-size:24px;margin:4px 0 2px}h2{font-size:19px;margin:28px 0 8px;border-bottom:2px solid #0072B2;padding-bottom:3px}
h3{font-size:15px;margin:18px 0 6px}
p,li{font-size:14px;line-height:1.45}.sub{color:#555;margin-top:0}
table{border-collapse:collapse;font-size:13px;margin:6px 0 10px}
th,td{border:1px solid #ddd;padding:3px 6px;overflow-wrap:break-word;text-align:left;vertical-align:top}
th{background:#f0f4f8}td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.grid{display:flex;flex-wrap:wrap;gap:10px}
figure{margin:0;border:1px solid #e4e4e4;padding:4px;background:#fff;max-width:100%}
figure svg{max-width:100%;height:auto;display:block}
figcaption{font-size:12.5px;color:#444;max-width:560px;padding:2px 4px 4px;line-height:1.4}
code{font-size:12px;background:#f3f3f3;padding:1px 3px;border-radius:2px}
.bad{color:#B00000;font-weight:bold}.ok{color:#006400}
details>summary{cursor:pointer;font-size:19px;font-weight:bold;margin:24px 0 6px}
.small{font-size:12px;color:#555}
.wide{overflow-x:auto;max-width:100%}
";

fn figure(svg: Option<String>, caption: &str) -> String {
    match svg {
        Some(svg) => format!("<figure>{svg}<figcaption>{caption}</figcaption></figure>\n"),
        None => String::new(),
    }
}

fn pct(x: f64) -> String {
    if !x.is_finite() {
        return "–".into();
    }
    let v = 100.0 * x;
    if v != 0.0 && v.abs() < 0.1 {
        format!("{v:.3} %")
    } else {
        format!("{v:.1} %")
    }
}

/// A requirement's bounds as text.
fn bounds(min: Option<f64>, max: Option<f64>, unit: &str) -> String {
    let u = unit_suffix(unit);
    match (min, max) {
        (Some(a), Some(b)) => format!("in [{}, {}]{u}", short(a), short(b)),
        (Some(a), None) => format!("≥ {}{u}", short(a)),
        (None, Some(b)) => format!("≤ {}{u}", short(b)),
        (None, None) => "anything".into(),
    }
}

/// The whole page.
pub fn html(run: &Run, ctx: &Context) -> String {
    let mut s = String::with_capacity(1 << 20);
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{} · hpr-mc report</title><style>{CSS}</style></head><body><main>\n",
        esc(&ctx.name)
    );
    header(&mut s, run, ctx);
    // Contents: the page is long with many sweep points.
    s.push_str("<p class=\"small\">Contents: <a href=\"#answer\">the answer</a>");
    for pt in 0..run.points() {
        let _ = write!(s, " · <a href=\"#point-{pt}\">point {pt}</a>");
    }
    s.push_str(" · <a href=\"#flights\">flights to look at</a></p>\n");
    answer(&mut s, run, ctx);
    for pt in 0..run.points() {
        point_section(&mut s, run, ctx, pt);
    }
    flights_to_look_at(&mut s, run, ctx);
    let _ = write!(
        s,
        "<h2>How this page was made</h2><p class=\"small\">Drawn by hpr-mc {} from the run's files in this directory (variants, summary, ellipses, sensitivity, requirements and trajectories Parquet files); <code>hpr-mc report DIR</code> draws it again from them. Percentiles are type 7 (linear between order statistics) over the landed flights; shares of requirements count every variant of a point, with Wilson's 95 % interval. A landing cloud of more than {} flights is drawn as a density.{} Nothing on this page is fetched from the network.</p>\n</main></body></html>\n",
        env!("CARGO_PKG_VERSION"),
        figures::MAX_DOTS,
        if run.whole() {
            String::new()
        } else {
            format!(
                " The report holds at most {} rows of a point (the first, in variant order) to draw from rows, so that its memory does not grow with the run; a point with more flights says so in its section, and its counts, shares, percentiles, ellipses and sensitivities are still over all of them.",
                run.held_per_point
            )
        }
    );
    s
}

fn header(s: &mut String, run: &Run, ctx: &Context) {
    let landed = run.landed;
    let _ = write!(s, "<h1>{}</h1>\n", esc(&ctx.name));
    if let Some(d) = &ctx.description {
        let _ = write!(s, "<p class=\"sub\">{}</p>\n", esc(d));
    }
    let points = run.points();
    let vpp = run.meta("hpr_mc.variants_per_point");
    let shard = run.meta("hpr_mc.shard");
    let shard_text = if shard.is_empty() || shard == "0/1" {
        String::new()
    } else {
        format!(" (shard {shard}: the variants with id % N = K)")
    };
    let site = match (
        run.meta.get("hpr_mc.latitude_deg"),
        run.meta.get("hpr_mc.longitude_deg"),
    ) {
        (Some(a), Some(b)) => format!(
            "{a}° N, {b}° E, {} m above sea level",
            short(ctx.elevation_m)
        ),
        (Some(a), None) => format!("{a}° N, {} m above sea level", short(ctx.elevation_m)),
        _ => format!("{} m above sea level", short(ctx.elevation_m)),
    };
    let _ = write!(
        s,
        "<table><tr><th>scenario</th><td><code>{}</code></td></tr><tr><th>scenario text's fingerprint (FNV-1a 64)</th><td><code>{}</code></td></tr><tr><th>seed</th><td>{}</td></tr><tr><th>variants</th><td>{}{} · {} sweep point{} × {} per point · {} landed, {} did not</td></tr><tr><th>site</th><td>{}</td></tr><tr><th>written by</th><td>hpr-mc {} · files of {}</td></tr></table>\n",
        esc(&ctx.scenario_file),
        esc(run.meta("hpr_mc.scenario_hash")),
        esc(run.meta("hpr_mc.seed")),
        run.variants,
        shard_text,
        points,
        if points == 1 { "" } else { "s" },
        esc(vpp),
        landed,
        run.variants - landed,
        esc(&site),
        esc(run.meta("hpr_mc.version")),
        run.written_unix_s.map_or("an unknown date".into(), utc),
    );
    let _ = write!(
        s,
        "<h3>Inputs</h3><table><tr><th>input</th><th>unit</th><th>swept over</th><th>dispersion (as the scenario writes it)</th><th>mean</th><th>standard deviation</th><th>least</th><th>greatest</th></tr>\n"
    );
    for (j, c) in run.inputs.iter().enumerate() {
        if let Some(names) = run.swept_motor_names().filter(|_| c.name == "motor_index") {
            // A swept motor is named by its designations (its number is only a position in
            // the sweep's list: its mean and extremes mean nothing to a reader).
            let dash = "<td class=\"n\">–</td>".repeat(4);
            let _ = write!(
                s,
                "<tr><td><code>motor</code></td><td></td><td>{}</td><td>–</td>{dash}</tr>\n",
                esc(&names.join(", "))
            );
            continue;
        }
        // Over every row: the sum in row order and the extremes as the rows passed; the
        // spread from the rows when all are held (two passes), else Welford's as they passed.
        let mo = &run.input_moments[j];
        let n = mo.n as f64;
        let mean = mo.sum / n;
        let sd = if run.whole() {
            let v = &run.input_values[j];
            (v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0).max(1.0)).sqrt()
        } else {
            (mo.m2 / (n - 1.0).max(1.0)).sqrt()
        };
        let (lo, hi) = (mo.min, mo.max);
        let (sweep, disp) = &ctx.inputs[j];
        let _ = write!(
            s,
            "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
            esc(&c.name),
            esc(&c.unit),
            esc(sweep.as_deref().unwrap_or("–")),
            esc(disp.as_deref().unwrap_or("–")),
            short(mean),
            short(sd),
            short(lo),
            short(hi)
        );
    }
    s.push_str("</table>\n");
}

/// The swept input to put on the x axis (the one with the most values; the first of those
/// tied), and the other swept inputs' combinations as series: (label, points in x order).
fn sweep_layout(run: &Run) -> Option<(usize, Vec<(String, Vec<usize>)>)> {
    if run.sweep.is_empty() || run.points() < 2 {
        return None;
    }
    let distinct = |k: usize| {
        let mut v: Vec<f64> = run.sweep_values.iter().map(|p| p[k]).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v.len()
    };
    let axis = (0..run.sweep.len()).max_by_key(|&k| (distinct(k), usize::MAX - k))?;
    let mut series: Vec<(String, Vec<usize>)> = vec![];
    for pt in 0..run.points() {
        let label: Vec<String> = run
            .sweep
            .iter()
            .enumerate()
            .filter(|(k, _)| *k != axis)
            .map(|(k, _)| format!("{} = {}", sweep_name(run, k), sweep_value(run, pt, k)))
            .collect();
        let label = label.join(", ");
        match series.iter_mut().find(|(l, _)| *l == label) {
            Some((_, pts)) => pts.push(pt),
            None => series.push((label, vec![pt])),
        }
    }
    for (_, pts) in &mut series {
        pts.sort_by(|a, b| run.sweep_values[*a][axis].total_cmp(&run.sweep_values[*b][axis]));
    }
    Some((axis, series))
}

fn answer(s: &mut String, run: &Run, ctx: &Context) {
    let swept = run.points() > 1;
    let _ = write!(
        s,
        "<h2 id=\"answer\">{}</h2>\n<p>One row per sweep point: the share of its flights meeting each requirement (95 % interval), and each key metric's median with its 5–95 % range over the landed flights.</p>\n",
        if swept { "The sweep's answer" } else { "The answer" }
    );
    let reqs: Vec<&super::data::Requirement> =
        run.requirements.iter().filter(|r| r.point == 0).collect();
    s.push_str("<div class=\"wide\"><table><tr><th>point</th>");
    for (k, c) in run.sweep.iter().enumerate() {
        match run.sweep_motor(0, k) {
            Some(_) => s.push_str("<th>motor</th>"),
            None => {
                let _ = write!(s, "<th>{}{}</th>", esc(&c.name), esc(&unit_text(&c.unit)));
            }
        }
    }
    for r in &reqs {
        let _ = write!(
            s,
            "<th>{}<br><span class=\"small\">{}, 95 % interval</span></th>",
            esc(&r.metric),
            esc(&bounds(r.min, r.max, &r.unit))
        );
    }
    for &m in &ctx.key_metrics {
        let c = &run.metrics[m];
        let _ = write!(
            s,
            "<th>{}{}<br><span class=\"small\">median, 5–95 %</span></th>",
            esc(&c.name),
            esc(&unit_text(&c.unit))
        );
    }
    s.push_str("</tr>\n");
    for pt in 0..run.points() {
        let _ = write!(s, "<tr><td class=\"n\">{pt}</td>");
        for (k, v) in run.sweep_values[pt].iter().enumerate() {
            match run.sweep_motor(pt, k) {
                Some(d) => {
                    let _ = write!(s, "<td>{}</td>", esc(d));
                }
                None => {
                    let _ = write!(s, "<td class=\"n\">{}</td>", short(*v));
                }
            }
        }
        for r0 in &reqs {
            if let Some(r) = run.requirement(pt, &r0.metric) {
                let class = if r.fraction >= 0.99 {
                    "ok"
                } else if r.fraction < 0.9 {
                    "bad"
                } else {
                    ""
                };
                let _ = write!(
                    s,
                    "<td class=\"n {class}\">{}<br><span class=\"small\">{}–{}</span></td>",
                    pct(r.fraction),
                    pct(r.low),
                    pct(r.high)
                );
            }
        }
        for &m in &ctx.key_metrics {
            let name = &run.metrics[m].name;
            match run.summary_of(pt, name) {
                Some(sm) => {
                    let _ = write!(
                        s,
                        "<td class=\"n\">{}<br><span class=\"small\">{} – {}</span></td>",
                        sm.p50.map_or("–".into(), short),
                        sm.p5.map_or("–".into(), short),
                        sm.p95.map_or("–".into(), short)
                    );
                }
                None => s.push_str("<td>–</td>"),
            }
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</table></div>\n");
    let Some((axis, series)) = sweep_layout(run) else {
        return;
    };
    let x_col = &run.sweep[axis];
    let x_label = format!("{}{}", sweep_name(run, axis), unit_text(&x_col.unit));
    // A swept motor's axis is named by designation at each motor's number.
    let x_names: Option<Vec<(f64, String)>> = run.sweep_motor(0, axis).map(|_| {
        let mut names: Vec<(f64, String)> = (0..run.points())
            .filter_map(|p| Some((run.sweep_values[p][axis], run.sweep_motor(p, axis)?.into())))
            .collect();
        names.sort_by(|a, b| a.0.total_cmp(&b.0));
        names.dedup_by(|a, b| a.0 == b.0);
        names
    });
    s.push_str("<div class=\"grid\">\n");
    for (k, r0) in reqs.iter().enumerate() {
        let lines: Vec<figures::SweepSeries> = series
            .iter()
            .map(|(label, pts)| {
                let row = |pt: usize| run.requirement(pt, &r0.metric);
                (
                    label.clone(),
                    pts.iter().map(|&p| run.sweep_values[p][axis]).collect(),
                    pts.iter()
                        .map(|&p| row(p).map_or(f64::NAN, |r| 100.0 * r.low))
                        .collect(),
                    pts.iter()
                        .map(|&p| row(p).map_or(f64::NAN, |r| 100.0 * r.fraction))
                        .collect(),
                    pts.iter()
                        .map(|&p| row(p).map_or(f64::NAN, |r| 100.0 * r.high))
                        .collect(),
                )
            })
            .collect();
        let svg = figures::sweep_chart(
            &format!("req{k}"),
            &format!("{} {}", r0.metric, bounds(r0.min, r0.max, &r0.unit)),
            &x_label,
            "flights meeting it (%)",
            &lines,
            Some((0.0, 104.0)),
            None,
            x_names.clone(),
        );
        s.push_str(&figure(
            svg,
            &format!(
                "The share of each point's flights meeting <code>{}</code> {}: dots and line the share, bars and band its 95 % Wilson interval.",
                esc(&r0.metric),
                esc(&bounds(r0.min, r0.max, &r0.unit))
            ),
        ));
    }
    for &m in &ctx.key_metrics {
        let c = &run.metrics[m];
        let lines: Vec<figures::SweepSeries> = series
            .iter()
            .map(|(label, pts)| {
                let get = |p: usize, f: fn(&super::data::SummaryRow) -> Option<f64>| {
                    run.summary_of(p, &c.name).and_then(f).unwrap_or(f64::NAN)
                };
                (
                    label.clone(),
                    pts.iter().map(|&p| run.sweep_values[p][axis]).collect(),
                    pts.iter().map(|&p| get(p, |r| r.p5)).collect(),
                    pts.iter().map(|&p| get(p, |r| r.p50)).collect(),
                    pts.iter().map(|&p| get(p, |r| r.p95)).collect(),
                )
            })
            .collect();
        let bound = reqs.iter().find(|r| r.metric == c.name).and_then(|r| {
            r.min
                .map(|v| (v, format!("required ≥ {}", short(v))))
                .or(r.max.map(|v| (v, format!("required ≤ {}", short(v)))))
        });
        let svg = figures::sweep_chart(
            &format!("key{m}"),
            &c.name,
            &x_label,
            &format!("{}{}", c.name, unit_text(&c.unit)),
            &lines,
            None,
            bound,
            x_names.clone(),
        );
        s.push_str(&figure(
            svg,
            &format!(
                "<code>{}</code> against the sweep: median (line), 5–95 % of the landed flights (band and bars).",
                esc(&c.name)
            ),
        ));
    }
    s.push_str("</div>\n");
}

fn point_section(s: &mut String, run: &Run, ctx: &Context, pt: usize) {
    let rows = run.rows_of(pt);
    let count = run.counts[pt];
    let sample = run.sample_text(pt);
    // Said in each caption drawn from the rows when they are a sample.
    let of_sample = if sample.is_empty() {
        String::new()
    } else {
        format!(
            " Drawn from the first {} of the point's {} flights.",
            count.held, count.variants
        )
    };
    let title = if run.points() > 1 {
        format!("Point {pt}{}", ctx.point_labels[pt])
    } else {
        "The flights".to_string()
    };
    let _ = write!(
        s,
        "<details open id=\"point-{pt}\"><summary>{}</summary>\n<p>{} variants, {} landed.{}</p>\n<div class=\"grid\">\n",
        esc(&title),
        count.variants,
        count.landed,
        if sample.is_empty() {
            String::new()
        } else {
            format!(
                "</p><p class=\"sample\"><b>Sample.</b> The landing map, histograms, distributions, margins, descent speeds and convergence of this point draw {sample}. The counts, shares, percentiles, ellipses, sensitivities and the flights to look at count all {} flights.",
                count.variants
            )
        }
    );
    let id = |what: &str| format!("p{pt}-{what}");
    // Landing.
    if let (Some(mx), Some(my)) = (run.metric("landing_x_m"), run.metric("landing_y_m")) {
        let (mut xs, mut ys) = (vec![], vec![]);
        for &r in &rows {
            let (x, y) = (run.metric_values[mx][r], run.metric_values[my][r]);
            if run.status[r] == Status::Landed && x.is_finite() && y.is_finite() {
                xs.push(x);
                ys.push(y);
            }
        }
        let ellipses: Vec<_> = run
            .ellipses
            .iter()
            .filter(|e| e.point == pt && e.body == Body::Rocket)
            .collect();
        let recovery = run
            .requirement(pt, "landing_distance_m")
            .and_then(|r| r.max);
        let marks = MapMarks {
            ellipses,
            recovery_m: recovery,
        };
        if let Some((svg, r, mean, cloud)) =
            figures::landing_map(&id("map"), "Where the flights land", &xs, &ys, &marks)
        {
            let e1 = marks.ellipses.iter().find(|e| e.sigma == 1);
            let ell = e1.map_or(String::new(), |e| {
                format!(
                    " The 1σ ellipse (39.3 % of a normal scatter; 2σ 86.5 %, 3σ 98.9 %) has semi-axes {} × {} m, its major axis {}° from east, centre {} m east, {} m north.",
                    short(e.semi_major_m),
                    short(e.semi_minor_m),
                    short(e.major_axis_deg),
                    short(e.center_x_m),
                    short(e.center_y_m)
                )
            });
            let rec = run.requirement(pt, "landing_distance_m").map_or(String::new(), |q| {
                format!(
                    " The green circle is the recovery area the scenario requires (<code>landing_distance_m</code> {}): {} of the point's flights land in it.",
                    esc(&bounds(q.min, q.max, "m")),
                    pct(q.fraction)
                )
            });
            // The released parts land on their own: their 1σ ellipses, said in words.
            let parts: String = run
                .released
                .iter()
                .enumerate()
                .filter_map(|(k, name)| {
                    let e = run.ellipses.iter().find(|e| {
                        e.point == pt && e.sigma == 1 && e.body == Body::Released(k)
                    })?;
                    Some(format!(
                        " The released part <code>{}</code> lands on its own: its 1σ ellipse is centred {} m east, {} m north, semi-axes {} × {} m ({} landings; <code>ellipses.parquet</code>, body <code>{}</code>).",
                        esc(name.strip_prefix("release_").unwrap_or(name)),
                        short(e.center_x_m),
                        short(e.center_y_m),
                        short(e.semi_major_m),
                        short(e.semi_minor_m),
                        e.count,
                        esc(name)
                    ))
                })
                .collect();
            s.push_str(&figure(
                Some(svg),
                &format!(
                    "Shown: {cloud}, the rocket's.{of_sample} Dashed grey circles about the mean landing point ({} m east, {} m north) hold 50, 90 and 99 % of the landings: R50 {} m, R90 {} m, R99 {} m.{ell}{rec}{parts}",
                    short(mean.0),
                    short(mean.1),
                    short(r[0]),
                    short(r[1]),
                    short(r[2])
                ),
            ));
        }
    }
    // Apogee.
    if let Some(ma) = run.metric("apogee_m") {
        let v = run.landed_values(ma, pt);
        let ceiling = run.requirement(pt, "apogee_m").and_then(|r| r.max);
        let lines: Vec<(f64, String, &str)> = ceiling
            .map(|c| vec![(c, format!("ceiling {} m", short(c)), "#C00000")])
            .unwrap_or_default();
        // Over every landed flight of the point, counted as the rows passed.
        let exceed = ceiling.zip(run.tally(pt, "apogee_m")).map(|(c, t)| {
            let (k, n) = (t.above, t.landed);
            (c, k, n, binomial_upper(k, n, 0.95))
        });
        let p_text = exceed.map_or(
            " The scenario sets no ceiling (a requirement <code>apogee_m = { max = … }</code> is one, a waiver's for instance).".to_string(),
            |(c, k, n, u)| {
                format!(
                    " <span class=\"p-exceed\" data-k=\"{k}\" data-n=\"{n}\" data-upper=\"{u}\">P(apogee &gt; {} m) = {} ({k} of {n} landed flights); at most {} with 95 % confidence</span> (Clopper–Pearson's one-sided bound: for 0 of N it is 1 − 0.05<sup>1/N</sup> ≈ 3/N).",
                    short(c),
                    pct(k as f64 / n.max(1) as f64),
                    pct(u)
                )
            },
        );
        s.push_str(&figure(
            figures::histogram_chart(
                &id("apogee-hist"),
                "Apogee",
                "apogee above the ground (m)",
                &v,
                &lines,
            ),
            &format!(
                "How high the {} landed flights go.{of_sample}{p_text}",
                v.len()
            ),
        ));
        s.push_str(&figure(
            figures::ecdf_chart(
                &id("apogee-cdf"),
                "Apogee: empirical distribution",
                "apogee above the ground (m)",
                &v,
                &lines,
            ),
            &format!("The share of flights whose apogee is at or below each height.{of_sample}"),
        ));
    }
    // Rail exit speed.
    if let Some(m) = run.metric("rail_exit_speed_m_s") {
        let v = run.landed_values(m, pt);
        let min = run
            .requirement(pt, "rail_exit_speed_m_s")
            .and_then(|r| r.min);
        let lines: Vec<(f64, String, &str)> = min
            .map(|c| vec![(c, format!("required ≥ {} m/s", short(c)), "#C00000")])
            .unwrap_or_default();
        let below =
            min.zip(run.tally(pt, "rail_exit_speed_m_s"))
                .map_or(String::new(), |(c, t)| {
                    format!(
                        " {} of {} leave the rail slower than the {} m/s required.",
                        t.below,
                        t.landed,
                        short(c)
                    )
                });
        s.push_str(&figure(
            figures::histogram_chart(
                &id("rail"),
                "Speed off the rail",
                "rail exit speed (m/s)",
                &v,
                &lines,
            ),
            &format!("The speed as the rocket leaves the rail.{of_sample}{below}"),
        ));
    }
    // Margins at the flight's moments.
    let mut margin_rows = vec![];
    let bound_of = |metric: &str| {
        run.requirement(pt, metric).and_then(|r| {
            r.min
                .map(|v| (v, format!("≥ {}", short(v))))
                .or(r.max.map(|v| (v, format!("≤ {}", short(v)))))
        })
    };
    for (name, label) in [
        ("static_margin_liftoff_cal", "static, at liftoff"),
        ("static_margin_rail_exit_cal", "static, at rail exit"),
        ("static_margin_burnout_cal", "static, at burnout"),
    ] {
        if let Some(m) = run.metric(name) {
            margin_rows.push(Row {
                label: label.into(),
                values: run.landed_values(m, pt),
                bound: bound_of(name),
            });
        }
    }
    for (k, c) in run.metrics.iter().enumerate() {
        if let Some(shift) = c
            .name
            .strip_prefix("shift_")
            .and_then(|n| n.strip_suffix("_margin_after_cal"))
        {
            margin_rows.push(Row {
                label: format!("static, after {shift} moves"),
                values: run.landed_values(k, pt),
                bound: bound_of(&c.name),
            });
        }
    }
    for (name, label) in [
        ("static_margin_min_cal", "static, least"),
        ("flight_margin_min_cal", "flight (at Mach), least"),
    ] {
        if let Some(m) = run.metric(name) {
            margin_rows.push(Row {
                label: label.into(),
                values: run.landed_values(m, pt),
                bound: bound_of(name),
            });
        }
    }
    s.push_str(&figure(
        figures::rows_chart(&id("margins"), "Stability margin", "margin (calibres)", &margin_rows),
        &format!("The static margin (centre of pressure at Mach 0) at the flight's moments and its least from liftoff to apogee, and the flight margin's least (centre of pressure at the flight's Mach). Box 25–75 %, whiskers 5–95 %, dots the least and the greatest; a red mark is a requirement.{of_sample}"),
    ));
    // Loads.
    for (name, title, label, scale) in [
        (
            "max_dynamic_pressure_pa",
            "Largest dynamic pressure",
            "max q (kPa)",
            1e-3,
        ),
        ("max_mach", "Largest Mach number", "max Mach", 1.0),
        (
            "max_accel_m_s2",
            "Largest acceleration",
            "max acceleration (m/s²)",
            1.0,
        ),
    ] {
        if let Some(m) = run.metric(name) {
            let v: Vec<f64> = run.landed_values(m, pt).iter().map(|x| x * scale).collect();
            let extra = if name == "max_accel_m_s2" {
                // The median of every landed flight (summary.parquet) when the rows are a
                // sample.
                let whole = run
                    .summary_of(pt, name)
                    .and_then(|r| r.p50)
                    .filter(|_| !of_sample.is_empty());
                let med = if let Some(p50) = whole {
                    p50
                } else {
                    let mut w = v.clone();
                    w.sort_by(f64::total_cmp);
                    if w.is_empty() {
                        f64::NAN
                    } else {
                        quantile(&w, 0.5)
                    }
                };
                format!(" (median {} g)", short(med / 9.80665))
            } else {
                String::new()
            };
            s.push_str(&figure(
                figures::histogram_chart(&id(name), title, label, &v, &[]),
                &format!("{title} over each landed flight{extra}.{of_sample}"),
            ));
        }
    }
    // Descent speed under each canopy.
    let chutes: Vec<(String, usize, usize)> = run
        .metrics
        .iter()
        .enumerate()
        .filter_map(|(k, c)| {
            let name = c
                .name
                .strip_prefix("parachute_")?
                .strip_suffix("_deploy_time_s")?;
            let speed = run.metric(&format!("parachute_{name}_deploy_speed_m_s"))?;
            Some((name.to_string(), k, speed))
        })
        .collect();
    if let (false, Some(land)) = (chutes.is_empty(), run.metric("landing_speed_m_s")) {
        let mut speeds: Vec<Vec<f64>> = vec![vec![]; chutes.len()];
        for &r in &rows {
            if run.status[r] != Status::Landed {
                continue;
            }
            // The canopies in the order they opened; under each, the speed when the next
            // opened, or at landing for the last.
            let mut open: Vec<(f64, usize)> = chutes
                .iter()
                .enumerate()
                .map(|(i, c)| (run.metric_values[c.1][r], i))
                .filter(|(t, _)| t.is_finite())
                .collect();
            open.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (k, &(_, i)) in open.iter().enumerate() {
                let v = match open.get(k + 1) {
                    Some(&(_, next)) => run.metric_values[chutes[next].2][r],
                    None => run.metric_values[land][r],
                };
                speeds[i].push(v);
            }
        }
        let rows_: Vec<Row> = chutes
            .iter()
            .zip(speeds)
            .map(|(c, v)| Row {
                label: format!("under {} (and any open before)", c.0),
                values: v,
                bound: None,
            })
            .collect();
        s.push_str(&figure(
            figures::rows_chart(&id("descent"), "Speed under canopy", "speed (m/s)", &rows_),
            &format!("The rocket's speed once each canopy has opened and the descent has settled: under a canopy, the speed as the next one opens, or at landing under the last (the centre of mass's speed, the wind's drift included). Box 25–75 %, whiskers 5–95 %.{of_sample}"),
        ));
    }
    // Against time, from trajectories.parquet.
    let series: Vec<&super::data::Series> = run.series.iter().filter(|x| x.point == pt).collect();
    if series.len() >= 2 {
        let apogee_t = |x: &super::data::Series| {
            let k = x
                .altitude_m
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(b.1))
                .map_or(0, |(k, _)| k);
            x.time_s[k]
        };
        let sm: Vec<(&[f64], &[f64], f64)> = series
            .iter()
            .map(|x| {
                (
                    x.time_s.as_slice(),
                    x.static_margin_cal.as_slice(),
                    apogee_t(x),
                )
            })
            .collect();
        let fm: Vec<(&[f64], &[f64], f64)> = series
            .iter()
            .map(|x| {
                (
                    x.time_s.as_slice(),
                    x.flight_margin_cal.as_slice(),
                    apogee_t(x),
                )
            })
            .collect();
        let (t, lo, mid, hi) = series_bands(&sm, None);
        let (_, flo, fmid, fhi) = series_bands(&fm, None);
        s.push_str(&figure(
            figures::bands_chart(
                &id("margin-t"),
                "Stability margin against time",
                "margin (calibres)",
                &t,
                &[
                    ("static", PALETTE[0], lo, mid, hi),
                    ("flight", PALETTE[1], flo, fmid, fhi),
                ],
                &[],
            ),
            &format!(
                "From ignition to apogee, over the {} flights of this point in <code>trajectories.parquet</code>: the median and the 5–95 % band at each time.",
                series.len()
            ),
        ));
        let hs: Vec<(&[f64], &[f64], f64)> = series
            .iter()
            .map(|x| {
                (
                    x.time_s.as_slice(),
                    x.altitude_m.as_slice(),
                    *x.time_s.last().unwrap_or(&0.0),
                )
            })
            .collect();
        let (t, lo, mid, hi) = series_bands(&hs, Some(0.0));
        s.push_str(&figure(
            figures::bands_chart(
                &id("height-t"),
                "Height against time",
                "height above the ground (m)",
                &t,
                &[("height", PALETTE[2], lo, mid, hi)],
                &[],
            ),
            &format!(
                "Over the same {} flights (a flight that has landed counts at 0 m).",
                series.len()
            ),
        ));
    } else if !run.has_trajectories || series.is_empty() {
        s.push_str("<p class=\"small\">No time series for this point: the run wrote none (<code>[outputs] trajectories = N</code> flies N variants per point again with their samples).</p>\n");
    }
    // Sensitivity and convergence of the key metrics.
    for &m in &ctx.key_metrics {
        let c = &run.metrics[m];
        s.push_str(&figure(
            figures::tornado(&id(&format!("tornado{m}")), run, pt, &c.name, &c.unit),
            &format!(
                "Each dispersed input's effect on <code>{}</code>: the change when the input moves one standard deviation, from a linear fit over the point's landed flights, with its share of the variance (Pratt's measure; the shares add up to R²).",
                esc(&c.name)
            ),
        ));
    }
    for &m in &ctx.key_metrics {
        let c = &run.metrics[m];
        let v = run.landed_values(m, pt);
        s.push_str(&figure(
            figures::convergence(
                &id(&format!("conv{m}")),
                &format!("{}: convergence", c.name),
                &format!("{}{}", c.name, unit_text(&c.unit)),
                &v,
            ),
            &format!(
                "The mean and the 5 and 95 % quantiles of <code>{}</code> over the first n landed flights: where the lines have flattened, more variants would not move them.{of_sample}",
                esc(&c.name)
            ),
        ));
    }
    s.push_str("</div></details>\n");
}

fn flights_to_look_at(s: &mut String, run: &Run, ctx: &Context) {
    s.push_str("<h2 id=\"flights\">Flights to look at</h2>\n");
    let total = run.looks_total as usize;
    const SHOWN: usize = super::data::LOOKS_KEPT;
    if total == 0 {
        s.push_str("<p>Every flight landed, and none raised a warning.</p>\n");
    } else {
        let _ = write!(
            s,
            "<p>{} flight{} did not land or raised a warning{}.</p><table><tr><th>variant</th><th>point</th><th>status</th><th>why</th><th>fly it again</th></tr>\n",
            total,
            if total == 1 { "" } else { "s" },
            if total > SHOWN {
                format!(" (the first {SHOWN} below; filter variants.parquet on status and the warning_ columns for all)")
            } else {
                String::new()
            }
        );
        for f in run.looks.iter().take(SHOWN) {
            // A refused variant has nothing to fly: the why says which input is out of range.
            let again = if f.status == Status::Refused {
                "–".to_string()
            } else {
                format!("<code>{}</code>", esc(&ctx.fly_command(f.id)))
            };
            let _ = write!(
                s,
                "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td><td>{}</td><td>{again}</td></tr>\n",
                f.id,
                f.point,
                f.status.name(),
                esc(&f.why)
            );
        }
        s.push_str("</table>\n");
    }
    let reqs: Vec<(usize, &super::data::Requirement)> = run
        .requirements
        .iter()
        .enumerate()
        .filter(|(_, r)| r.point == 0)
        .collect();
    if reqs.is_empty() {
        return;
    }
    s.push_str("<h3>The worst flight of each point by each requirement</h3><table><tr><th>requirement</th><th>point</th><th>variant</th><th>value</th><th>fly it again</th></tr>\n");
    for (q, r0) in reqs {
        if run.metric(&r0.metric).is_none() {
            continue;
        }
        for pt in 0..run.points() {
            // Over every row of the point, gathered as the rows passed (data.rs).
            if let Some(w) = run.worst.get(&(q, pt)) {
                let v = w.value;
                let met = r0.min.is_none_or(|a| v >= a) && r0.max.is_none_or(|b| v <= b);
                let _ = write!(
                    s,
                    "<tr><td><code>{}</code> {}</td><td class=\"n\">{pt}</td><td class=\"n\">{}</td><td class=\"n {}\">{}{}</td><td><code>{}</code></td></tr>\n",
                    esc(&r0.metric),
                    esc(&bounds(r0.min, r0.max, &r0.unit)),
                    w.id,
                    if met { "ok" } else { "bad" },
                    short(v),
                    esc(&unit_suffix(&r0.unit)),
                    esc(&ctx.fly_command(w.id))
                );
            }
        }
    }
    s.push_str("</table>\n");
}
