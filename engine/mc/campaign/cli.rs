//! `hpr-mc SCENARIO.toml` and `hpr-mc run SCENARIO.toml`: the arguments, the run, the
//! printed summary and the exit code.
//!
//! Exit codes: 0 every variant landed; 1 the run finished but some variants did not land
//! (their count is printed; their rows say why); 2 bad input or usage (a scenario that breaks
//! a rule, a missing file, bad arguments) or an error that stopped the run (a file that can't
//! be written). An interrupted run (Ctrl-C) leaves no half-written file; rerun it with
//! `--resume` to fly only what is missing.

use super::fly::Prepared;
use super::params::Param;
use super::run::{run_campaign, RunConfig, RunReport};
use super::stats::Summary;
use super::variants::Shard;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Options of a scenario run.
#[derive(clap::Args, Debug, Default, Clone)]
pub struct RunArgs {
    /// Variants per sweep point (replaces the scenario's variants_per_point; at most
    /// 1,000,000,000 variants in all, 10,000,000 in one process).
    #[arg(long, value_name = "N")]
    pub variants: Option<u64>,
    /// Seed of the random draws (replaces the scenario's seed).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Worker threads, 1 or more (default: one per core). The results do not depend on it.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = thread_count)]
    pub threads: Option<usize>,
    /// Output directory (default: results/ and the scenario's name).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Run only the variants with id % N == K, written to *-shard-K-of-N.parquet.
    #[arg(long, value_name = "K/N", value_parser = Shard::parse)]
    pub shard: Option<Shard>,
    /// Keep the complete parts of an interrupted run and fly only the missing ones.
    #[arg(long)]
    pub resume: bool,
    /// Print where the run's time went, phase by phase (scenario and tables, sampling,
    /// flights, Parquet, statistics, report).
    #[arg(long)]
    pub timings: bool,
    /// Rows per part file (the unit a run keeps on disk and --resume keeps); by default at
    /// least 16,384, at most 256 parts a run. For tests of --resume.
    #[arg(long, value_name = "ROWS", hide = true)]
    pub part_rows: Option<u64>,
    /// Write no report (report.html and the landing maps) at the end.
    #[arg(long)]
    pub no_report: bool,
    /// Print every metric's statistics per sweep point after the summary table.
    #[arg(long)]
    pub verbose: bool,
}

/// `--threads N`: a whole number, 1 or more (a negative one is named as such, not taken
/// for an option).
fn thread_count(text: &str) -> Result<usize, String> {
    match text.trim().parse::<i64>() {
        Ok(n) if n >= 1 => usize::try_from(n).map_err(|_| format!("{n} is too many")),
        Ok(n) => Err(format!("must be at least 1 (got {n})")),
        Err(_) => Err(format!(
            "must be a whole number, 1 or more (got \"{text}\")"
        )),
    }
}

/// Exit codes and limits, as `--help` shows them.
pub const EXIT_CODES: &str = "Exit codes: 0 every variant landed; 1 the run finished but some variants did not land (counted; their rows say why); 2 bad input or usage, or an error that stopped the run. Ctrl-C leaves no half-written file: rerun with --resume to fly only what is missing.

Output directory: one run at a time writes a scenario's files (or a shard's) in a directory: a second is refused at once, naming the first (its pid, host, start time, seed). Without --resume a run first removes the earlier results of its files (other shards' stay).

Limits (refused before anything is flown, with the rule): at most 100,000 sweep points; at most 1,000,000,000 variants (sweep points x variants per point), 10,000,000 in one process (split a larger run with --shard); a scenario file of 4 MiB, a design or .ork file of 64 MiB (its inflated document 64 MiB, nested 100 deep; 1,000 components), a motor file, sounding or drag/lift CSV of 16 MiB; RK4 at most 10,000,000 steps (max_time_s / step_s), and a parachute's or the air brakes' sampler at most 10,000,000 samples to the time limit (max_time_s x sampling_rate_hz). See docs/scenarios.md, \"Limits\".";

/// `hpr-mc run SCENARIO.toml [options]`.
#[derive(clap::Args, Debug)]
#[command(after_help = EXIT_CODES)]
pub struct RunCommand {
    /// The scenario file (TOML; see docs/scenarios.md).
    pub scenario: PathBuf,
    #[command(flatten)]
    pub args: RunArgs,
}

impl RunArgs {
    pub fn config(&self) -> RunConfig {
        RunConfig {
            seed: self.seed,
            variants_per_point: self.variants,
            threads: self.threads,
            out: self.out.clone(),
            quiet: self.quiet,
            shard: self.shard,
            resume: self.resume,
            max_parts: None,
            part_rows: self.part_rows,
            no_report: self.no_report,
        }
    }
}

/// Run a scenario, print its summary, and say by the exit code whether every variant landed.
pub fn run(scenario: &Path, args: &RunArgs) -> anyhow::Result<ExitCode> {
    let report = run_campaign(scenario, &args.config())?;
    crate::cli::emit(&summary_text(&report, args.verbose))?;
    if args.timings {
        crate::cli::emit(&timings_text(&report))?;
    }
    let failures = report.failures();
    if failures > 0 {
        eprintln!(
            "hpr-mc: {failures} of {} variants did not land ({} refused, {} failed, {} reached the time limit); their rows in {} say why",
            report.variants,
            report.refused,
            report.failed,
            report.time_limit,
            report.outputs.variants.display()
        );
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// Where the run's time went (`--timings`): each phase's wall time on the main thread, the
/// workers' thread-seconds for the phases they share, and the flights per second.
pub fn timings_text(r: &RunReport) -> String {
    use std::fmt::Write;
    let t = &r.timings;
    let s = |d: std::time::Duration| d.as_secs_f64();
    let total = s(t.total).max(1e-9);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\ntimings ({} worker threads; wall seconds and share of the run's {:.3} s):",
        t.threads, total
    );
    let mut line = |name: &str, d: f64, note: &str| {
        let _ = writeln!(
            out,
            "  {name:<28} {d:>8.3} s {:>5.1} %  {note}",
            100.0 * d / total
        );
    };
    line("scenario and tables", s(t.prepare), "");
    line(
        "flying the variants",
        s(t.flying_wall),
        "(wall: sampling, flights, rows, parts, statistics' gathering)",
    );
    let threads = t.threads.max(1) as f64;
    let busy = s(t.flying_wall) * threads;
    let mut worker = |name: &str, d: f64| {
        let _ = writeln!(
            out,
            "    {name:<26} {d:>8.3} thread-s {:>5.1} % of the workers' time",
            100.0 * d / busy.max(1e-9)
        );
    };
    worker("sampling", s(t.sampling));
    worker("flights", s(t.flights));
    worker("rows (Arrow)", s(t.rows));
    if t.shared > 0 {
        let _ = writeln!(
            out,
            "    {} flights began where the same replicate's flight at sweep point 0 left off",
            t.shared
        );
    }
    let mut main = |name: &str, d: f64| {
        let _ = writeln!(
            out,
            "    {name:<26} {d:>8.3} s (main thread, while the workers fly)",
        );
    };
    main("Parquet parts", s(t.parquet));
    main("statistics gathered", s(t.gather));
    main("waiting for flights", s(t.waiting));
    let mut line = |name: &str, d: f64| {
        let _ = writeln!(out, "  {name:<28} {d:>8.3} s {:>5.1} %", 100.0 * d / total);
    };
    line("variants file (parts copied)", s(t.merge));
    line(
        "statistics and trajectories",
        s(t.statistics_and_trajectories),
    );
    for (name, d, note) in [
        ("statistics and their files", s(t.statistics), ""),
        (
            "trajectories",
            s(t.trajectories),
            " (beside the statistics)",
        ),
    ] {
        let _ = writeln!(out, "    {name:<26} {d:>8.3} s{note}");
    }
    let mut line = |name: &str, d: f64| {
        let _ = writeln!(out, "  {name:<28} {d:>8.3} s {:>5.1} %", 100.0 * d / total);
    };
    line("report and maps", s(t.report));
    let rest = total
        - s(t.prepare)
        - s(t.flying_wall)
        - s(t.merge)
        - s(t.statistics_and_trajectories)
        - s(t.report);
    line("other", rest.max(0.0));
    let _ = writeln!(
        out,
        "  {} flights in {:.3} s: {:.0} flights/s end to end",
        r.variants,
        total,
        r.variants as f64 / total
    );
    out
}

/// A number in 9 characters with about 5 significant digits.
fn num(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 {
        "0".into()
    } else if !(1e-3..1e6).contains(&a) {
        format!("{x:.3e}")
    } else {
        let digits = a.log10().floor() as i32 + 1;
        format!("{x:.*}", (5 - digits).clamp(0, 6) as usize)
    }
}

/// The metrics whose sensitivity is printed (all are in sensitivity.parquet).
const SENSITIVITY_PRINTED: [&str; 4] = [
    "apogee_m",
    "static_margin_min_cal",
    "landing_x_m",
    "landing_y_m",
];

/// The printed summary: one table across the sweep points (a row a point: the swept values,
/// the share of the point's flights meeting each requirement, and the key metrics' medians
/// with their 5–95 % range), where the report and the files are, and with `verbose` every
/// metric's statistics per point.
pub fn summary_text(r: &RunReport, verbose: bool) -> String {
    use std::fmt::Write;
    let p: &Prepared = &r.prepared;
    let mut s = String::new();
    let shard = if r.shard.is_all() {
        String::new()
    } else {
        format!(" (shard {}/{})", r.shard.k, r.shard.n)
    };
    let secs = r.elapsed.as_secs_f64();
    let _ = writeln!(
        s,
        "{}{shard}: {} variants ({}), {} landed, {} did not · {:.1} s",
        p.scenario.name,
        r.variants,
        if p.plan.points() == 1 {
            "no sweep".to_string()
        } else {
            format!(
                "{} sweep points × {} per point",
                p.plan.points(),
                p.scenario.variants_per_point
            )
        },
        r.landed,
        r.failures(),
        secs
    );
    if !r.complete {
        let _ = writeln!(
            s,
            "stopped after {} parts; rerun with --resume to finish",
            r.parts_flown
        );
        return s;
    }
    if !r.warned.is_empty() {
        let counts: Vec<String> = r.warned.iter().map(|(k, n)| format!("{n} {k}")).collect();
        let _ = writeln!(
            s,
            "warnings: {} (the variants' warnings column says which and why)",
            counts.join(", ")
        );
    }
    s.push('\n');
    s.push_str(&sweep_table(r));
    s.push('\n');
    let dir = r.outputs.dir.display();
    match &r.report {
        Some(w) => {
            let _ = writeln!(
                s,
                "report: {} ({:.0} kB, drawn in {:.2} s)",
                w.report.display(),
                w.bytes as f64 / 1000.0,
                w.seconds
            );
            if let (Some(k), Some(g)) = (&w.kml, &w.geojson) {
                let _ = writeln!(
                    s,
                    "landing maps: {} (Google Earth), {} (QGIS, web maps)",
                    k.display(),
                    g.display()
                );
            }
        }
        None => {
            let _ = writeln!(
                s,
                "no report (--no-report); hpr-mc report {dir} draws it from the files"
            );
        }
    }
    let _ = writeln!(
        s,
        "files in {dir}: variants, summary, ellipses, sensitivity, requirements and trajectories ({} variants' time series) .parquet{}",
        r.trajectories,
        if verbose { "" } else { "; --verbose prints every metric per point" }
    );
    if verbose {
        s.push_str(&point_details(r));
    }
    s
}

/// The key metrics of the printed table and the report: the apogee, the static margin
/// after each shift (the least static margin without one) and the landing distance.
pub fn key_metrics(p: &Prepared) -> Vec<usize> {
    let find = |n: &str| p.metrics.iter().position(|m| m.name == n);
    let mut keys: Vec<usize> = find("apogee_m").into_iter().collect();
    keys.extend(
        p.metrics
            .iter()
            .enumerate()
            .filter(|(_, m)| m.name.starts_with("shift_") && m.name.ends_with("_margin_after_cal"))
            .map(|(k, _)| k),
    );
    if keys.len() == 1 {
        keys.extend(find("static_margin_min_cal"));
    }
    keys.extend(find("landing_distance_m"));
    keys
}

/// The table across the sweep points, its requirements lettered A, B, … above it.
pub fn sweep_table(r: &RunReport) -> String {
    use std::fmt::Write;
    let p = &r.prepared;
    let mut s = String::new();
    let letters = |k: usize| ((b'A' + (k % 26) as u8) as char).to_string();
    if !p.requirements.is_empty() {
        let list: Vec<String> = p
            .requirements
            .iter()
            .enumerate()
            .map(|(k, (m, req))| {
                format!(
                    "{} {} {}",
                    letters(k),
                    req.metric,
                    req.bounds_text(p.metrics[*m].unit)
                )
            })
            .collect();
        let _ = writeln!(
            s,
            "share of each point's flights meeting: {}",
            list.join(" · ")
        );
    }
    let _ = writeln!(
        s,
        "key metrics: median (5 % – 95 %) of each point's landed flights"
    );
    let keys = key_metrics(p);
    let swept: Vec<_> = p.scenario.swept().collect();
    let mut head: Vec<String> = vec!["point".into()];
    head.extend(swept.iter().map(|i| match i.unit {
        // A swept motor is named by its designation, not its number in the list.
        _ if i.param == Param::Motor => "motor".into(),
        "1" => i.column.clone(),
        u => format!("{} ({u})", i.column),
    }));
    head.extend((0..p.requirements.len()).map(letters));
    head.extend(keys.iter().map(|&m| p.metrics[m].name.clone()));
    let mut rows: Vec<Vec<String>> = vec![];
    for st in &r.stats {
        let mut row = vec![st.point.to_string()];
        row.extend(
            swept
                .iter()
                .zip(p.plan.sweep_values(st.point))
                .map(|(i, v)| match motor_at(p, i.param, st.point) {
                    Some(d) => d.to_string(),
                    None => short(v),
                }),
        );
        row.extend(
            st.requirements
                .iter()
                .map(|c| format!("{:.1} %", 100.0 * c.fraction)),
        );
        row.extend(keys.iter().map(|&m| match &st.summaries[m] {
            Some(x) => format!("{} ({}–{})", short(x.p50), short(x.p5), short(x.p95)),
            None => "-".into(),
        }));
        rows.push(row);
    }
    let widths: Vec<usize> = (0..head.len())
        .map(|k| {
            rows.iter()
                .map(|r| r[k].chars().count())
                .chain([head[k].chars().count()])
                .max()
                .unwrap_or(1)
        })
        .collect();
    let line = |cells: &[String]| -> String {
        let parts: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{}{c}", " ".repeat(w - c.chars().count())))
            .collect();
        parts.join("  ")
    };
    let _ = writeln!(s, "{}", line(&head));
    for row in &rows {
        let _ = writeln!(s, "{}", line(row));
    }
    s
}

/// The designation of the motor sweep point `point` flies, where `param` is the swept motor.
fn motor_at(p: &Prepared, param: Param, point: usize) -> Option<&str> {
    if param != Param::Motor {
        return None;
    }
    p.motor_of(&p.plan.centers(point))
}

/// A number with about four significant digits (the table's).
fn short(x: f64) -> String {
    crate::campaign::report::figures::short(x).replace('−', "-")
}

/// Per sweep point, each metric's mean, std, p5, p50 and p95, the requirements, the 1 σ
/// landing ellipse, and the largest shares of variance of a few metrics (`--verbose`).
fn point_details(r: &RunReport) -> String {
    use std::fmt::Write;
    let p: &Prepared = &r.prepared;
    let mut s = String::new();
    let width = p
        .metrics
        .iter()
        .map(|m| m.name.len())
        .max()
        .unwrap_or(6)
        .max(6);
    let swept: Vec<_> = p.scenario.swept().collect();
    for st in &r.stats {
        let _ = writeln!(s);
        let at: Vec<String> = swept
            .iter()
            .zip(p.plan.sweep_values(st.point))
            .map(|(i, v)| match (motor_at(p, i.param, st.point), i.unit) {
                (Some(d), _) => format!("{} = {d}", i.key),
                // A pure number (a scale) has no unit to print.
                (None, "1") => format!("{} = {v}", i.key),
                (None, unit) => format!("{} = {v} {unit}", i.key),
            })
            .collect();
        let at = if at.is_empty() {
            String::new()
        } else {
            format!(": {}", at.join(", "))
        };
        let _ = writeln!(
            s,
            "point {}{at}  ({} variants, {} did not land)",
            st.point, st.variants, st.failures
        );
        for ((m, req), c) in p.requirements.iter().zip(&st.requirements) {
            let _ = writeln!(
                s,
                "  requirement {} {}: met by {} of {} ({:.1} %; 95 % interval {:.1}–{:.1} %)",
                req.metric,
                req.bounds_text(p.metrics[*m].unit),
                c.met,
                c.variants,
                100.0 * c.fraction,
                100.0 * c.low,
                100.0 * c.high
            );
        }
        if st.variants == st.failures {
            continue;
        }
        let _ = writeln!(
            s,
            "  {:<width$} {:>10} {:>10} {:>10} {:>10} {:>10}",
            "metric", "mean", "std", "p5", "p50", "p95"
        );
        for (m, sum) in p.metrics.iter().zip(&st.summaries) {
            let row = |x: &Summary| {
                [
                    num(x.mean),
                    x.std.map_or("-".into(), num),
                    num(x.p5),
                    num(x.p50),
                    num(x.p95),
                ]
            };
            let cells = sum.as_ref().map_or_else(
                || {
                    [
                        "-".to_string(),
                        "-".into(),
                        "-".into(),
                        "-".into(),
                        "-".into(),
                    ]
                },
                row,
            );
            let _ = writeln!(
                s,
                "  {:<width$} {:>10} {:>10} {:>10} {:>10} {:>10}",
                m.name, cells[0], cells[1], cells[2], cells[3], cells[4]
            );
        }
        if let Some(e) = st.ellipse {
            let _ = writeln!(
                s,
                "  landing ellipse (1 sigma; 2 and 3 sigma scale it): center {} m east, {} m north; semi-axes {} × {} m, major axis {}° from east",
                num(e.center_x_m),
                num(e.center_y_m),
                num(e.semi_major_m),
                num(e.semi_minor_m),
                num(e.major_axis_deg)
            );
        }
        for (r, e) in p.scenario.releases.iter().zip(&st.release_ellipses) {
            if let Some(e) = e {
                let _ = writeln!(
                    s,
                    "  released {}'s landing ellipse (1 sigma): center {} m east, {} m north; semi-axes {} × {} m, major axis {}° from east",
                    r.name,
                    num(e.center_x_m),
                    num(e.center_y_m),
                    num(e.semi_major_m),
                    num(e.semi_minor_m),
                    num(e.major_axis_deg)
                );
            }
        }
        let dispersed: Vec<&str> = p
            .scenario
            .inputs
            .iter()
            .filter(|i| i.dispersion.is_some())
            .map(|i| i.column.as_str())
            .collect();
        for name in SENSITIVITY_PRINTED {
            let Some(m) = p.metrics.iter().position(|c| c.name == name) else {
                continue;
            };
            let Some(fit) = &st.sensitivity[m] else {
                continue;
            };
            let mut shares: Vec<(f64, &str)> = fit
                .shares
                .iter()
                .zip(&dispersed)
                .filter_map(|(x, n)| x.map(|x| (x, *n)))
                .collect();
            shares.sort_by(|a, b| b.0.total_cmp(&a.0));
            let top: Vec<String> = shares
                .iter()
                .take(4)
                .map(|(x, n)| format!("{n} {:.0}%", 100.0 * x))
                .collect();
            let _ = writeln!(
                s,
                "  variance of {name} (linear fit R² {:.2}): {}",
                fit.r2,
                top.join(", ")
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::num;

    #[test]
    fn numbers_print_with_about_five_significant_digits() {
        assert_eq!(num(1749.83), "1749.8");
        assert_eq!(num(0.012345), "0.012345");
        assert_eq!(num(-2.5), "-2.5000");
        assert_eq!(num(0.0), "0");
        assert_eq!(num(1.5e7), "1.500e7");
    }
}
