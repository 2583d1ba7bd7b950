//! The campaign loop: a shard's variants cut into chunks, the chunks flown on a local rayon
//! pool, each chunk written to its own part file, and, once every chunk is there, the parts
//! merged into the variants file and the statistics computed and written.
//!
//! Determinism: a variant's values depend only on (seed, id) and each flight is sequential,
//! so the rows are the same whatever the thread count, the chunk size or the shards; the
//! merged file lists them in id order.
//!
//! Interruption and `--resume`: a chunk's part (`parts/variants[-shard-K-of-N]/chunk-NNNNNNNN.parquet`)
//! is written under a temporary name and renamed when complete, as every file is. A rerun
//! with `resume` keeps the complete parts whose metadata shows the same run (scenario
//! fingerprint, seed, variants per point, shard, chunk size), flies only the missing chunks,
//! then merges. Without `resume` a rerun starts over. The parts are removed once merged.

use super::fly::{fly_chunk, Prepared, Status};
use super::parquet::{self as pq, RunMeta};
use super::scenario::Scenario;
use super::stats::{self, PointStats, Table};
use super::variants::{chunks, Shard, Variant};
use anyhow::{bail, Context};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How to run a scenario.
#[derive(Debug, Clone, Default)]
pub struct RunConfig {
    /// Replaces the scenario's seed.
    pub seed: Option<u64>,
    /// Replaces the scenario's variants per sweep point.
    pub variants_per_point: Option<u64>,
    /// Worker threads (default: one per core).
    pub threads: Option<usize>,
    /// Output directory (default `results/<scenario name>`).
    pub out: Option<PathBuf>,
    /// No progress bar.
    pub quiet: bool,
    /// Which shard to run (default: all).
    pub shard: Option<Shard>,
    /// Keep the complete chunks of an interrupted run and fly only the missing ones.
    pub resume: bool,
    /// Fly at most this many chunks, then stop without merging, as an interruption would
    /// (for tests of `resume`).
    pub max_chunks: Option<usize>,
}

/// The files of a run.
#[derive(Debug, Clone)]
pub struct Outputs {
    pub dir: PathBuf,
    pub variants: PathBuf,
    pub summary: PathBuf,
    pub ellipses: PathBuf,
    pub sensitivity: PathBuf,
    pub requirements: PathBuf,
    pub parts: PathBuf,
}

impl Outputs {
    /// File names for `shard` in `dir`: `variants.parquet`..., or
    /// `variants-shard-K-of-N.parquet`... for one shard of several.
    pub fn new(dir: &Path, shard: Shard) -> Outputs {
        let suffix = if shard.is_all() {
            String::new()
        } else {
            format!("-shard-{}-of-{}", shard.k, shard.n)
        };
        let f = |stem: &str| dir.join(format!("{stem}{suffix}.parquet"));
        Outputs {
            dir: dir.to_path_buf(),
            variants: f("variants"),
            summary: f("summary"),
            ellipses: f("ellipses"),
            sensitivity: f("sensitivity"),
            requirements: f("requirements"),
            parts: dir.join("parts").join(format!("variants{suffix}")),
        }
    }

    fn part(&self, chunk: usize) -> PathBuf {
        self.parts.join(format!("chunk-{chunk:08}.parquet"))
    }
}

/// What a run did.
#[derive(Debug)]
pub struct RunReport {
    pub prepared: Prepared,
    pub outputs: Outputs,
    pub shard: Shard,
    /// Variants in this shard.
    pub variants: u64,
    /// Chunks flown by this run, and chunks kept from an earlier one.
    pub chunks_flown: usize,
    pub chunks_kept: usize,
    /// Whether every chunk is done and the files merged (false only with `max_chunks`).
    pub complete: bool,
    /// Variants per status: landed, time limit, refused, failed.
    pub landed: u64,
    pub time_limit: u64,
    pub refused: u64,
    pub failed: u64,
    /// Flown variants with warnings, per warning kind ([`hpr_sim::Warning::key`]) that
    /// occurred, in the order of [`hpr_sim::Warning::KEYS`].
    pub warned: Vec<(String, u64)>,
    pub stats: Vec<PointStats>,
    pub elapsed: Duration,
}

impl RunReport {
    /// Variants that did not land.
    pub fn failures(&self) -> u64 {
        self.time_limit + self.refused + self.failed
    }
}

/// Read, check and prepare a scenario with the configuration's overrides.
pub fn prepare(scenario: &Path, cfg: &RunConfig) -> anyhow::Result<Prepared> {
    let s = Scenario::load(scenario)?.with_overrides(cfg.seed, cfg.variants_per_point)?;
    Ok(Prepared::new(s)?)
}

/// Run a scenario: fly what is missing, merge, compute and write the statistics.
pub fn run_campaign(scenario: &Path, cfg: &RunConfig) -> anyhow::Result<RunReport> {
    let started = Instant::now();
    let prepared = prepare(scenario, cfg)?;
    if !cfg.quiet {
        crate::cli::motor_notes(prepared.motor());
    }
    let shard = cfg.shard.unwrap_or(Shard::ALL);
    let dir = cfg
        .out
        .clone()
        .unwrap_or_else(|| Path::new("results").join(&prepared.scenario.name));
    let outputs = Outputs::new(&dir, shard);
    let meta = RunMeta::of(&prepared, shard);
    let schema = pq::variants_schema(&prepared, &meta);
    let total = prepared.plan.total();
    let count = shard.count(total);
    let chunk_list = chunks(count, prepared.scenario.chunk_size);
    if dir.exists() && !dir.is_dir() {
        bail!(
            "{}: the output directory is a file, not a directory (give another with --out)",
            dir.display()
        );
    }
    std::fs::create_dir_all(&outputs.parts)
        .with_context(|| format!("can't create {}", outputs.parts.display()))?;

    let mut report = RunReport {
        prepared,
        outputs,
        shard,
        variants: count,
        chunks_flown: 0,
        chunks_kept: 0,
        complete: false,
        landed: 0,
        time_limit: 0,
        refused: 0,
        failed: 0,
        warned: Vec::new(),
        stats: vec![],
        elapsed: Duration::ZERO,
    };
    let (p, out) = (&report.prepared, &report.outputs);

    // A resumed run whose merged file is already there only recomputes the statistics.
    let finished = cfg.resume
        && out.variants.is_file()
        && pq::read_pairs(&out.variants)
            .map(|kv| meta.mismatch(&kv).is_none())
            .unwrap_or(false)
        && pq::row_count(&out.variants)? == count;
    if !finished {
        let done = scan_parts(out, &meta, &chunk_list, cfg.resume)?;
        report.chunks_kept = done.iter().filter(|d| **d).count();
        let mut missing: Vec<usize> = (0..chunk_list.len()).filter(|&c| !done[c]).collect();
        if let Some(m) = cfg.max_chunks {
            missing.truncate(m);
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(cfg.threads.unwrap_or(0))
            .build()
            .context("can't start the worker threads")?;
        let flights_left: u64 = missing
            .iter()
            .map(|&c| chunk_list[c].end - chunk_list[c].start)
            .sum();
        let bar = progress(flights_left, cfg.quiet);
        pool.install(|| {
            missing.par_iter().try_for_each(|&c| -> anyhow::Result<()> {
                let variants: Vec<Variant> = chunk_list[c]
                    .clone()
                    .map(|q| p.plan.variant(shard.id(q)))
                    .collect();
                let results = fly_chunk(p, &variants);
                let batch = pq::variants_batch(p, &schema, &variants, &results)?;
                let mut pairs = meta.pairs();
                pairs.push(("hpr_mc.chunk".into(), c.to_string()));
                pq::write_atomic(
                    &out.part(c),
                    &schema,
                    &pairs,
                    p.scenario.row_group_rows,
                    |w| Ok(w.write(&batch)?),
                )?;
                bar.inc(variants.len() as u64);
                Ok(())
            })
        })?;
        bar.finish_and_clear();
        report.chunks_flown = missing.len();
        if report.chunks_kept + report.chunks_flown < chunk_list.len() {
            report.elapsed = started.elapsed();
            return Ok(report);
        }
        // Merge the parts, in order, into the variants file, reading the statistics' table.
        let mut table = Table::new(p.scenario.inputs.len(), p.metrics.len());
        pq::write_atomic(
            &out.variants,
            &schema,
            &meta.pairs(),
            p.scenario.row_group_rows,
            |w| {
                for c in 0..chunk_list.len() {
                    for batch in pq::read_batches(&out.part(c))? {
                        let batch = batch?;
                        pq::accumulate(p, &mut table, &batch)?;
                        w.write(&batch)?;
                    }
                }
                Ok(())
            },
        )?;
        finish(&mut report, &meta, &table)?;
        std::fs::remove_dir_all(&report.outputs.parts)
            .with_context(|| format!("can't remove {}", report.outputs.parts.display()))?;
        let _ = std::fs::remove_dir(report.outputs.dir.join("parts"));
    } else {
        pq::check_schema(&out.variants, &schema)?;
        let mut table = Table::new(p.scenario.inputs.len(), p.metrics.len());
        for batch in pq::read_batches(&out.variants)? {
            pq::accumulate(p, &mut table, &batch?)?;
        }
        let _ = std::fs::remove_dir_all(&out.parts);
        let _ = std::fs::remove_dir(out.dir.join("parts"));
        finish(&mut report, &meta, &table)?;
    }
    report.complete = true;
    report.elapsed = started.elapsed();
    Ok(report)
}

/// Count the statuses, compute and write the statistics.
fn finish(report: &mut RunReport, meta: &RunMeta, table: &Table) -> anyhow::Result<()> {
    count_outcomes(report)?;
    let p = &report.prepared;
    let dispersed: Vec<bool> = p
        .scenario
        .inputs
        .iter()
        .map(|i| i.dispersion.is_some())
        .collect();
    let landings: Vec<(usize, usize)> = p.landings.iter().map(|&(_, x, y)| (x, y)).collect();
    report.stats = stats::compute(
        table,
        p.plan.points(),
        &dispersed,
        &landings,
        &p.requirements,
    );
    // Statuses other than landed were counted from the variants file above.
    report.landed = table.landed.iter().filter(|l| **l).count() as u64;
    let out = &report.outputs;
    let pairs = meta.pairs();
    let rg = p.scenario.row_group_rows;
    let summary = pq::summary_batch(p, meta, &report.stats)?;
    pq::write_atomic(&out.summary, &summary.schema(), &pairs, rg, |w| {
        Ok(w.write(&summary)?)
    })?;
    let ellipses = pq::ellipses_batch(p, meta, &report.stats)?;
    pq::write_atomic(&out.ellipses, &ellipses.schema(), &pairs, rg, |w| {
        Ok(w.write(&ellipses)?)
    })?;
    let sens = pq::sensitivity_batch(p, meta, &report.stats)?;
    pq::write_atomic(&out.sensitivity, &sens.schema(), &pairs, rg, |w| {
        Ok(w.write(&sens)?)
    })?;
    let reqs = pq::requirements_batch(p, meta, &report.stats)?;
    pq::write_atomic(&out.requirements, &reqs.schema(), &pairs, rg, |w| {
        Ok(w.write(&reqs)?)
    })?;
    Ok(())
}

/// Count, from the run's variants file, the variants that reached the time limit, were
/// refused or failed, and those with each kind of warning.
fn count_outcomes(report: &mut RunReport) -> anyhow::Result<()> {
    let path = report.outputs.variants.clone();
    let (mut t, mut r, mut f) = (0, 0, 0);
    let mut warned = [0u64; hpr_sim::Warning::KEYS.len()];
    let column = |batch: &arrow::record_batch::RecordBatch, name: &str| {
        batch
            .column_by_name(name)
            .cloned()
            .with_context(|| format!("{} has no column {name}", path.display()))
    };
    let strings = |batch: &arrow::record_batch::RecordBatch, name: &str| {
        column(batch, name)?
            .as_any()
            .downcast_ref::<arrow::array::StringArray>()
            .cloned()
            .with_context(|| format!("{}: column {name} is not text", path.display()))
    };
    for batch in pq::read_batches(&path)? {
        let batch = batch?;
        let status = strings(&batch, "status")?;
        for (k, key) in hpr_sim::Warning::KEYS.iter().enumerate() {
            let name = format!("warning_{key}");
            let flags = column(&batch, &name)?;
            let flags = flags
                .as_any()
                .downcast_ref::<arrow::array::BooleanArray>()
                .with_context(|| format!("{}: column {name} is not true/false", path.display()))?;
            warned[k] += flags.true_count() as u64;
        }
        for s in status.iter().flatten() {
            if s == Status::TimeLimit.name() {
                t += 1;
            } else if s == Status::Refused.name() {
                r += 1;
            } else if s == Status::Failed.name() {
                f += 1;
            }
        }
    }
    (report.time_limit, report.refused, report.failed) = (t, r, f);
    report.warned = hpr_sim::Warning::KEYS
        .iter()
        .zip(warned)
        .filter(|(_, n)| *n > 0)
        .map(|(k, n)| (k.to_string(), n))
        .collect();
    Ok(())
}

/// Which chunks have a complete part from this run. Without `resume`, every part of this
/// shard is removed first (a fresh start). Leftover temporary files are always removed.
fn scan_parts(
    out: &Outputs,
    meta: &RunMeta,
    chunk_list: &[std::ops::Range<u64>],
    resume: bool,
) -> anyhow::Result<Vec<bool>> {
    let mut done = vec![false; chunk_list.len()];
    for entry in std::fs::read_dir(&out.parts)
        .with_context(|| format!("can't read {}", out.parts.display()))?
    {
        let path = entry?.path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("")
            .to_string();
        let chunk = name
            .strip_prefix("chunk-")
            .and_then(|r| r.strip_suffix(".parquet"))
            .and_then(|n| n.parse::<usize>().ok());
        match chunk {
            Some(c) if resume => {
                let kv = pq::read_pairs(&path)?;
                if let Some(why) = meta.mismatch(&kv) {
                    bail!("{} is a part of another run ({why}); to start over, run without --resume, or remove {}", path.display(), out.parts.display());
                }
                let expected = chunk_list.get(c).map(|r| r.end - r.start);
                if kv.get("hpr_mc.chunk") != Some(&c.to_string())
                    || expected != Some(pq::row_count(&path)?)
                {
                    bail!("{} does not hold chunk {c} of this run; to start over, run without --resume, or remove {}", path.display(), out.parts.display());
                }
                done[c] = true;
            }
            _ => std::fs::remove_file(&path)
                .with_context(|| format!("can't remove {}", path.display()))?,
        }
    }
    Ok(done)
}

/// A progress bar on stderr with flights per second and the time left, hidden when quiet
/// or when stderr is not a terminal.
fn progress(len: u64, quiet: bool) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    let style = ProgressStyle::with_template(
        "{elapsed_precise} [{wide_bar}] {pos}/{len} flights, {per_sec}, {eta} left",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style.progress_chars("=> "));
    bar
}
