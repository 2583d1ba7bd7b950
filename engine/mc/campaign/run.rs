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
//!
//! The output directory (its lock, the run's temporary names, the clean start) is
//! [`super::outdir`]'s; the merge here checks that every part it reads is the chunk this run
//! flew or kept: same run identity, chunk, writer, rows and variant ids.
//!
//! Size: one process flies at most [`MAX_VARIANTS_PER_RUN`] variants (its statistics hold
//! every row's inputs and metrics in memory); more are refused before anything is written,
//! with the rule and the way round it (`--shard`).

use super::fly::{fly_chunk, Prepared, Status};
pub use super::outdir::Outputs;
use super::outdir::{Holder, OutputDir};
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
    /// Skip the report (`report.html` and the landing maps) at the end (`--no-report`).
    pub no_report: bool,
}

/// Most variants one process flies (its shard's, or the whole run's): 10,000,000. Its
/// statistics hold each row's inputs and metrics in memory (8 bytes each: about 0.4 kB a
/// row for the bundled scenarios, 4 GB at the limit); a larger run is split with `--shard`.
pub const MAX_VARIANTS_PER_RUN: u64 = 10_000_000;

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
    /// Variants whose time series trajectories.parquet holds.
    pub trajectories: u64,
    /// What the report wrote (None with `no_report`, or before the run is complete).
    pub report: Option<crate::campaign::report::Written>,
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
        crate::report::motor_notes(prepared.motor());
    }
    let shard = cfg.shard.unwrap_or(Shard::ALL);
    let dir = cfg
        .out
        .clone()
        .unwrap_or_else(|| Path::new("results").join(&prepared.scenario.name));
    let meta = RunMeta::of(&prepared, shard);
    let schema = pq::variants_schema(&prepared, &meta);
    let total = prepared.plan.total();
    let count = shard.count(total);
    if count > MAX_VARIANTS_PER_RUN {
        bail!(
            "{}: {count} variants in one run is more than {MAX_VARIANTS_PER_RUN}, the most one \
             process flies (its statistics hold every row in memory); split the run with \
             --shard K/N, N at least {}",
            prepared.scenario.file.display(),
            total.div_ceil(MAX_VARIANTS_PER_RUN)
        );
    }
    let (inputs_n, metrics_n) = (prepared.scenario.inputs.len(), prepared.metrics.len());
    // The statistics' room, asked before anything is flown or written.
    let mut table = Table::with_room(inputs_n, metrics_n, count as usize).map_err(|_| {
        anyhow::anyhow!(
            "{}: the statistics of {count} variants need {:.1} GB of memory, which this \
             machine does not give; split the run with --shard K/N",
            prepared.scenario.file.display(),
            count as f64 * Table::bytes_per_row(inputs_n, metrics_n) as f64 / 1e9
        )
    })?;
    let chunk_list = chunks(count, prepared.scenario.chunk_size);
    let held = OutputDir::open(
        &dir,
        shard,
        cfg.resume,
        &Holder {
            scenario: prepared.scenario.file.display().to_string(),
            seed: prepared.scenario.seed,
        },
    )?;
    let outputs = held.outputs.clone();

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
        trajectories: 0,
        report: None,
        elapsed: Duration::ZERO,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cfg.threads.unwrap_or(0))
        .build()
        .context("can't start the worker threads")?;
    let (p, out) = (&report.prepared, &report.outputs);

    // A resumed run whose merged file is already there only recomputes the statistics.
    let finished = cfg.resume
        && out.variants.is_file()
        && pq::read_pairs(&out.variants)
            .map(|kv| meta.mismatch(&kv).is_none())
            .unwrap_or(false)
        && pq::row_count(&out.variants)? == count;
    if !finished {
        // Per chunk, the writer of its part: a kept part's, or this run's once flown.
        let mut writers = scan_parts(out, &meta, &chunk_list, cfg.resume)?;
        report.chunks_kept = writers.iter().filter(|d| d.is_some()).count();
        let mut missing: Vec<usize> = (0..chunk_list.len())
            .filter(|&c| writers[c].is_none())
            .collect();
        if let Some(m) = cfg.max_chunks {
            missing.truncate(m);
        }
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
                pairs.push((RUN_ID.into(), held.run_id.clone()));
                let part = out.part(c);
                pq::write_atomic(
                    &part,
                    &held.temporary(&part),
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
        for &c in &missing {
            writers[c] = Some(Some(held.run_id.clone()));
        }
        if report.chunks_kept + report.chunks_flown < chunk_list.len() {
            report.elapsed = started.elapsed();
            return Ok(report);
        }
        // Merge the parts, in order, into the variants file, reading the statistics' table;
        // each part must be the chunk this run flew or kept, row for row.
        pq::write_atomic(
            &out.variants,
            &held.temporary(&out.variants),
            &schema,
            &meta.pairs(),
            p.scenario.row_group_rows,
            |w| {
                for (c, range) in chunk_list.iter().enumerate() {
                    let path = out.part(c);
                    let writer = writers[c].as_ref().and_then(|w| w.as_deref());
                    check_part(&path, c, &meta, writer, range.end - range.start)?;
                    let mut q = range.start;
                    for batch in pq::read_batches(&path)? {
                        let batch = batch?;
                        check_ids(&path, &batch, shard, &mut q)?;
                        pq::accumulate(p, &mut table, &batch)?;
                        w.write(&batch)?;
                    }
                }
                Ok(())
            },
        )?;
        finish(&mut report, &meta, &table, &held)?;
        std::fs::remove_dir_all(&report.outputs.parts)
            .with_context(|| format!("can't remove {}", report.outputs.parts.display()))?;
        let _ = std::fs::remove_dir(report.outputs.dir.join("parts"));
    } else {
        pq::check_schema(&out.variants, &schema)?;
        for batch in pq::read_batches(&out.variants)? {
            pq::accumulate(p, &mut table, &batch?)?;
        }
        let _ = std::fs::remove_dir_all(&out.parts);
        let _ = std::fs::remove_dir(out.dir.join("parts"));
        finish(&mut report, &meta, &table, &held)?;
    }
    report.trajectories = pool.install(|| {
        super::trajectories::write(
            &report.prepared,
            shard,
            &report.outputs.trajectories,
            &held.temporary(&report.outputs.trajectories),
            &meta.pairs(),
        )
    })?;
    report.complete = true;
    if !cfg.no_report {
        report.report = Some(super::report::write_files(&report.outputs)?);
    }
    report.elapsed = started.elapsed();
    Ok(report)
}

/// The metadata key of the run that wrote a part.
const RUN_ID: &str = "hpr_mc.run_id";

/// Check that the part at `path` is chunk `c` of this run, written by `writer` (the run id
/// in its metadata, `None` for a part of a version that wrote none), with `rows` rows: else
/// the directory was changed under the run, and the merge stops rather than mix runs.
fn check_part(
    path: &Path,
    c: usize,
    meta: &RunMeta,
    writer: Option<&str>,
    rows: u64,
) -> anyhow::Result<()> {
    let kv = pq::read_pairs(path)?;
    let why = if let Some(why) = meta.mismatch(&kv) {
        Some(why)
    } else if kv.get("hpr_mc.chunk") != Some(&c.to_string()) {
        Some(format!(
            "its hpr_mc.chunk is {}",
            kv.get("hpr_mc.chunk").map_or("missing", |s| s.as_str())
        ))
    } else if kv.get(RUN_ID).map(String::as_str) != writer {
        Some(format!(
            "it was written by run {}, not by run {}",
            kv.get(RUN_ID).map_or("(none)", |s| s.as_str()),
            writer.unwrap_or("(none)")
        ))
    } else {
        let got = pq::row_count(path)?;
        (got != rows).then(|| format!("it holds {got} rows, the chunk {rows}"))
    };
    match why {
        None => Ok(()),
        Some(why) => bail!(
            "{} is not chunk {c} of this run ({why}): something else wrote into the output \
             directory during the run; nothing was merged, run again",
            path.display()
        ),
    }
}

/// Check that a part's batch holds the shard's variants from its `q`-th on, in order, and
/// move `q` past them.
fn check_ids(
    path: &Path,
    batch: &arrow::record_batch::RecordBatch,
    shard: Shard,
    q: &mut u64,
) -> anyhow::Result<()> {
    let ids = batch
        .column_by_name("variant_id")
        .and_then(|c| c.as_any().downcast_ref::<arrow::array::UInt64Array>())
        .with_context(|| format!("{} has no variant_id column", path.display()))?;
    for id in ids.values().iter() {
        if *id != shard.id(*q) {
            bail!(
                "{} holds variant {id} where this run's variant {} belongs; nothing was merged, run again",
                path.display(),
                shard.id(*q)
            );
        }
        *q += 1;
    }
    Ok(())
}

/// Count the statuses, compute and write the statistics.
fn finish(
    report: &mut RunReport,
    meta: &RunMeta,
    table: &Table,
    held: &OutputDir,
) -> anyhow::Result<()> {
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
    let tmp = |path: &Path| held.temporary(path);
    pq::write_atomic(
        &out.summary,
        &tmp(&out.summary),
        &summary.schema(),
        &pairs,
        rg,
        |w| Ok(w.write(&summary)?),
    )?;
    let ellipses = pq::ellipses_batch(p, meta, &report.stats)?;
    pq::write_atomic(
        &out.ellipses,
        &tmp(&out.ellipses),
        &ellipses.schema(),
        &pairs,
        rg,
        |w| Ok(w.write(&ellipses)?),
    )?;
    let sens = pq::sensitivity_batch(p, meta, &report.stats)?;
    pq::write_atomic(
        &out.sensitivity,
        &tmp(&out.sensitivity),
        &sens.schema(),
        &pairs,
        rg,
        |w| Ok(w.write(&sens)?),
    )?;
    let reqs = pq::requirements_batch(p, meta, &report.stats)?;
    pq::write_atomic(
        &out.requirements,
        &tmp(&out.requirements),
        &reqs.schema(),
        &pairs,
        rg,
        |w| Ok(w.write(&reqs)?),
    )?;
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

/// Per chunk, the writer of its complete part kept from an earlier run (`Some(run id)`, the
/// id `None` for a part that names none), or `None` to fly it. Only with `resume` are parts
/// kept; without it the output directory has removed them already ([`OutputDir::open`]).
/// Leftover temporary files are removed.
fn scan_parts(
    out: &Outputs,
    meta: &RunMeta,
    chunk_list: &[std::ops::Range<u64>],
    resume: bool,
) -> anyhow::Result<Vec<Option<Option<String>>>> {
    let mut done = vec![None; chunk_list.len()];
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
                done[c] = Some(kv.get(RUN_ID).cloned());
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

#[cfg(test)]
mod tests {
    use super::*;
    use arrow::array::UInt64Array;
    use arrow::datatypes::{DataType, Field, Schema};
    use arrow::record_batch::RecordBatch;
    use std::sync::Arc;

    fn meta(seed: u64) -> RunMeta {
        RunMeta {
            scenario_file: "s.toml".into(),
            scenario_text: "text".into(),
            scenario_hash: "abc".into(),
            seed,
            variants_per_point: 8,
            points: 1,
            shard: Shard { k: 1, n: 2 },
            chunk_size: 2,
            latitude_deg: None,
            longitude_deg: None,
        }
    }

    /// A part of `ids` written as run `writer` of the run `meta`, chunk `c`.
    fn part(dir: &Path, meta: &RunMeta, c: usize, writer: &str, ids: &[u64]) -> PathBuf {
        let schema = Arc::new(Schema::new(vec![Field::new(
            "variant_id",
            DataType::UInt64,
            false,
        )]));
        let batch = RecordBatch::try_new(
            schema.clone(),
            vec![Arc::new(UInt64Array::from(ids.to_vec()))],
        )
        .unwrap();
        let mut pairs = meta.pairs();
        pairs.push(("hpr_mc.chunk".into(), c.to_string()));
        pairs.push((RUN_ID.into(), writer.into()));
        let path = dir.join(format!("chunk-{c}-{}-{writer}-{ids:?}.parquet", meta.seed));
        pq::write_atomic(&path, &dir.join("tmp"), &schema, &pairs, 100, |w| {
            Ok(w.write(&batch)?)
        })
        .unwrap();
        path
    }

    #[test]
    fn the_merge_takes_only_a_part_of_this_run_s_chunk_writer_rows_and_ids() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let m = meta(5);
        // Shard 1 of 2, chunks of 2: chunk 1 holds the shard's variants 2 and 3, ids 5 and 7.
        let good = part(d, &m, 1, "me", &[5, 7]);
        check_part(&good, 1, &m, Some("me"), 2).unwrap();
        let mut q = 2;
        for b in pq::read_batches(&good).unwrap() {
            check_ids(&good, &b.unwrap(), m.shard, &mut q).unwrap();
        }
        assert_eq!(q, 4);
        let refusal = |path: &Path, c: usize, writer: &str, rows: u64| {
            check_part(path, c, &m, Some(writer), rows)
                .unwrap_err()
                .to_string()
        };
        // Another seed's part under this chunk's name (what two runs into one directory made).
        let other = part(d, &meta(7), 1, "me", &[5, 7]);
        let e = refusal(&other, 1, "me", 2);
        assert!(
            e.contains("is not chunk 1 of this run (its hpr_mc.seed is 7, this run's is 5)")
                && e.contains("nothing was merged"),
            "{e}"
        );
        let e = refusal(&good, 1, "another", 2);
        assert!(
            e.contains("(it was written by run me, not by run another)"),
            "{e}"
        );
        let e = refusal(&good, 0, "me", 2);
        assert!(e.contains("(its hpr_mc.chunk is 1)"), "{e}");
        let e = refusal(&good, 1, "me", 3);
        assert!(e.contains("(it holds 2 rows, the chunk 3)"), "{e}");
        // The right metadata over other rows: the ids give it away.
        let wrong = part(d, &m, 1, "me", &[5, 9]);
        let mut q = 2;
        let e = pq::read_batches(&wrong)
            .unwrap()
            .map(|b| check_ids(&wrong, &b.unwrap(), m.shard, &mut q))
            .find_map(Result::err)
            .unwrap()
            .to_string();
        assert!(
            e.contains("holds variant 9 where this run's variant 7 belongs"),
            "{e}"
        );
    }
}
