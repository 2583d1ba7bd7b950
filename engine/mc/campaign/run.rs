//! The campaign loop: a shard's variants cut into parts (the unit of checkpoint) and each
//! part into chunks (the unit of work), the chunks flown by worker threads and their rows
//! handed on in variant order to this thread, which gathers the statistics as the rows pass
//! ([`super::gather`]) and appends them, a row group at a time, to the part's file. Once every
//! part is there, the parts' row groups are copied as they are into the variants file (nothing
//! decoded) and the statistics written.
//!
//! Determinism: a variant's values depend only on (seed, id) and each flight is sequential,
//! so the rows are the same whatever the thread count, the chunk size or the shards; the
//! parts and the variants file list them in id order, and the statistics see them in that
//! order.
//!
//! Parts: a part holds [`PART_ROWS`] rows or more, enough that a run keeps at most
//! [`MAX_PARTS`] of them whatever its size (a multiple of the row group, so the variants
//! file's row groups are the scenario's `row_group_rows` whether the run was cut or not).
//! Chunks stay small (the scenario's `chunk_size`: lanes of one phase stay in step) and never
//! straddle two parts.
//!
//! Interruption and `--resume`: a part (`parts/variants[-shard-K-of-N]/part-NNNNNN.parquet`)
//! is written under a temporary name and renamed when complete, as every file is. A rerun
//! with `resume` keeps the complete parts whose metadata shows the same run (scenario
//! fingerprint, seed, variants per point, shard, chunk size, part size), reads them back in
//! their turn for the statistics, flies only the missing parts, then writes the variants file.
//! The resumed run's files are the uninterrupted run's, byte for byte. Without `resume` a rerun
//! starts over. The parts are removed once copied.
//!
//! The output directory (its lock, the run's temporary names, the clean start) is
//! [`super::outdir`]'s; the copy here checks that every part it takes is the part this run
//! flew or kept: same run identity, part, writer and rows (a kept part's variant ids too).
//!
//! Size: one process flies at most [`MAX_VARIANTS_PER_RUN`] variants (the report reads every
//! row of the variants file back); more are refused before anything is written, with the rule
//! and the way round it (`--shard`).

use super::fly::{fly_chunk_sharing, Prepared};
use super::gather::{Gather, Percentiles};
pub use super::outdir::Outputs;
use super::outdir::{Holder, OutputDir};
use super::parquet::{self as pq, RunMeta};
use super::scenario::Scenario;
use super::stats::PointStats;
use super::variants::{chunks, Shard, Variant};
use anyhow::{bail, Context};
use arrow::record_batch::RecordBatch;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use parquet::arrow::ArrowWriter;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::IsTerminal;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex};
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
    /// Keep the complete parts of an interrupted run and fly only the missing ones.
    pub resume: bool,
    /// Write at most this many parts, then stop without writing the variants file, as an
    /// interruption would (for tests of `resume`).
    pub max_parts: Option<usize>,
    /// Rows per part in place of [`part_rows`]'s (for tests of `resume` on small runs).
    pub part_rows: Option<u64>,
    /// Skip the report (`report.html` and the landing maps) at the end (`--no-report`).
    pub no_report: bool,
}

/// Most variants one process flies (its shard's, or the whole run's): 10,000,000. Its
/// statistics are bounded ([`super::gather`]), but the report reads every row of the
/// variants file back (about 0.4 kB a row for the bundled scenarios); a larger run is split
/// with `--shard`.
pub const MAX_VARIANTS_PER_RUN: u64 = 10_000_000;

/// The fewest rows a part holds (but a run's last, or a run smaller than this): a few
/// seconds of flights on a small machine.
pub const PART_ROWS: u64 = 16_384;

/// The most parts a run keeps: past `PART_ROWS × MAX_PARTS` rows, parts grow.
pub const MAX_PARTS: u64 = 256;

/// Rows per part for a run of `count` variants written in row groups of `row_group_rows`:
/// at least [`PART_ROWS`], enough for at most [`MAX_PARTS`] parts, rounded up to whole row
/// groups.
pub fn part_rows(count: u64, row_group_rows: usize) -> u64 {
    let rg = row_group_rows.max(1) as u64;
    PART_ROWS.max(count.div_ceil(MAX_PARTS)).div_ceil(rg) * rg
}

/// Where a run's time went. The flights' phases (sampling, flights, rows) are summed over
/// the worker threads (thread-seconds); the others run on the main thread, while the
/// workers fly (parts, statistics of the rows) or after them.
#[derive(Debug, Clone, Default)]
pub struct Timings {
    /// Worker threads.
    pub threads: usize,
    /// Reading the scenario, the design and the motor; building the tables.
    pub prepare: Duration,
    /// Drawing the variants' inputs (thread-seconds).
    pub sampling: Duration,
    /// Flying them (thread-seconds).
    pub flights: Duration,
    /// Turning the results into Arrow rows (thread-seconds).
    pub rows: Duration,
    /// From the first flight to the last part written (wall).
    pub flying_wall: Duration,
    /// Encoding, compressing and writing the parts (main thread, while the workers fly).
    pub parquet: Duration,
    /// Gathering the statistics as the rows pass (main thread, while the workers fly) and
    /// reading back the parts a resumed run kept.
    pub gather: Duration,
    /// The main thread waiting for the next chunk's rows.
    pub waiting: Duration,
    /// Copying the parts into the variants file.
    pub merge: Duration,
    /// The statistics and the trajectories, side by side (wall).
    pub statistics_and_trajectories: Duration,
    /// Computing the statistics and writing their four files.
    pub statistics: Duration,
    /// Flying the few variants of trajectories.parquet again and writing it (beside the
    /// statistics).
    pub trajectories: Duration,
    /// The report and the landing maps.
    pub report: Duration,
    /// The whole run.
    pub total: Duration,
    /// Flights that took the beginning they share with another sweep point's flight
    /// rather than flying it again ([`Prepared::prefix_store`]).
    pub shared: u64,
}

/// What a run did.
#[derive(Debug)]
pub struct RunReport {
    pub prepared: Prepared,
    pub outputs: Outputs,
    pub shard: Shard,
    /// Variants in this shard.
    pub variants: u64,
    /// Rows per part, parts written by this run and parts kept from an earlier one.
    pub part_rows: u64,
    pub parts: usize,
    pub parts_flown: usize,
    pub parts_kept: usize,
    /// Whether every part is done and the files written (false only with `max_parts`).
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
    /// How the percentiles were found (exact, or from a digest past the size held).
    pub percentiles: Percentiles,
    /// Variants whose time series trajectories.parquet holds.
    pub trajectories: u64,
    /// What the report wrote (None with `no_report`, or before the run is complete).
    pub report: Option<crate::campaign::report::Written>,
    pub elapsed: Duration,
    pub timings: Timings,
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

/// Run a scenario: fly what is missing, write the parts and the variants file, and the
/// statistics gathered on the way.
pub fn run_campaign(scenario: &Path, cfg: &RunConfig) -> anyhow::Result<RunReport> {
    let started = Instant::now();
    let prepared = prepare(scenario, cfg)?;
    let mut timings = Timings {
        prepare: started.elapsed(),
        ..Timings::default()
    };
    if !cfg.quiet {
        crate::report::motor_notes(prepared.motor());
    }
    let shard = cfg.shard.unwrap_or(Shard::ALL);
    let dir = cfg
        .out
        .clone()
        .unwrap_or_else(|| Path::new("results").join(&prepared.scenario.name));
    let total = prepared.plan.total();
    let count = shard.count(total);
    if count > MAX_VARIANTS_PER_RUN {
        bail!(
            "{}: {count} variants in one run is more than {MAX_VARIANTS_PER_RUN}, the most one \
             process flies (its report reads every row back); split the run with \
             --shard K/N, N at least {}",
            prepared.scenario.file.display(),
            total.div_ceil(MAX_VARIANTS_PER_RUN)
        );
    }
    let row_group_rows = prepared.scenario.row_group_rows;
    let part_rows = cfg
        .part_rows
        .unwrap_or_else(|| part_rows(count, row_group_rows))
        .max(1);
    let meta = RunMeta::of(&prepared, shard);
    let schema = pq::variants_schema(&prepared, &meta);
    let part_list = chunks(count, part_rows as usize);
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
    let threads = cfg
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);
    timings.threads = threads;

    let mut report = RunReport {
        prepared,
        outputs,
        shard,
        variants: count,
        part_rows,
        parts: part_list.len(),
        parts_flown: 0,
        parts_kept: 0,
        complete: false,
        landed: 0,
        time_limit: 0,
        refused: 0,
        failed: 0,
        warned: Vec::new(),
        stats: vec![],
        percentiles: Percentiles::Exact,
        trajectories: 0,
        report: None,
        elapsed: Duration::ZERO,
        timings: Timings::default(),
    };
    let p = &report.prepared;
    let out = &report.outputs;
    let dispersed: Vec<bool> = p
        .scenario
        .inputs
        .iter()
        .map(|i| i.dispersion.is_some())
        .collect();
    let landings: Vec<(usize, usize)> = p.landings.iter().map(|&(_, x, y)| (x, y)).collect();
    let mut gather = Gather::new(
        p.plan.points(),
        &dispersed,
        p.metrics.len(),
        &landings,
        &p.requirements,
    );

    // A resumed run whose variants file is already there only recomputes the statistics.
    let finished = cfg.resume
        && out.variants.is_file()
        && pq::read_pairs(&out.variants)
            .map(|kv| meta.mismatch(&kv).is_none())
            .unwrap_or(false)
        && pq::row_count(&out.variants)? == count;
    if !finished {
        let id = PartId {
            meta: &meta,
            part_rows,
        };
        // Per part, the writer of its file: a kept part's, or this run's once written.
        let mut writers = scan_parts(out, &id, &part_list, cfg.resume)?;
        report.parts_kept = writers.iter().filter(|d| d.is_some()).count();
        let mut missing: Vec<usize> = (0..part_list.len())
            .filter(|&k| writers[k].is_none())
            .collect();
        if let Some(m) = cfg.max_parts {
            missing.truncate(m);
        }
        let flights_left: u64 = missing
            .iter()
            .map(|&k| part_list[k].end - part_list[k].start)
            .sum();
        let bar = progress(flights_left, cfg.quiet);
        let flying = Instant::now();
        let written = fly_parts(
            p,
            &Flow {
                shard,
                schema: &schema,
                parts: &part_list,
                missing: &missing,
                kept: &writers,
                id: &id,
                held: &held,
                threads,
                bar: &bar,
            },
            &mut gather,
            &mut timings,
        )?;
        timings.flying_wall = flying.elapsed();
        bar.finish_and_clear();
        report.parts_flown = written.len();
        for &k in &written {
            writers[k] = Some(Some(held.run_id.clone()));
        }
        if report.parts_kept + report.parts_flown < part_list.len() {
            report.elapsed = started.elapsed();
            timings.total = report.elapsed;
            report.timings = timings;
            return Ok(report);
        }
        // Every part is there: each must be the part this run wrote or kept; their row
        // groups, copied in order, are the variants file.
        let merging = Instant::now();
        let paths: Vec<PathBuf> = (0..part_list.len()).map(|k| out.part(k)).collect();
        for (k, range) in part_list.iter().enumerate() {
            let writer = writers[k].as_ref().and_then(|w| w.as_deref());
            check_part(&paths[k], k, &id, writer, range.end - range.start)?;
        }
        if paths.is_empty() {
            // A shard without variants (more shards than variants): an empty file.
            pq::write_atomic(
                &out.variants,
                &held.temporary(&out.variants),
                &schema,
                &meta.pairs(),
                row_group_rows,
                |_| Ok(()),
            )?;
        } else {
            pq::concat_atomic(
                &out.variants,
                &held.temporary(&out.variants),
                &paths,
                &meta.pairs(),
            )?;
        }
        timings.merge = merging.elapsed();
        // The variants file is whole: a run killed from here on is resumed from it.
        std::fs::remove_dir_all(&report.outputs.parts)
            .with_context(|| format!("can't remove {}", report.outputs.parts.display()))?;
        let _ = std::fs::remove_dir(report.outputs.dir.join("parts"));
    } else {
        let reading = Instant::now();
        pq::check_schema(&out.variants, &schema)?;
        for batch in pq::read_batches(&out.variants)? {
            pq::gather(p, &mut gather, &batch?)?;
        }
        timings.gather = reading.elapsed();
        let _ = std::fs::remove_dir_all(&out.parts);
        let _ = std::fs::remove_dir(out.dir.join("parts"));
    }
    finish_beside_trajectories(
        &mut report,
        &meta,
        &mut gather,
        &held,
        &mut timings,
        threads,
    )?;
    report.complete = true;
    if !cfg.no_report {
        let drawing = Instant::now();
        report.report = Some(super::report::write_files(&report.outputs)?);
        timings.report = drawing.elapsed();
    }
    report.elapsed = started.elapsed();
    timings.total = report.elapsed;
    report.timings = timings;
    Ok(report)
}

/// What the parts of a run are: the run's identity and the rows a part holds.
struct PartId<'a> {
    meta: &'a RunMeta,
    part_rows: u64,
}

impl PartId<'_> {
    /// The metadata of part `k`, written by run `run_id`.
    fn pairs(&self, k: usize, run_id: &str) -> Vec<(String, String)> {
        let mut pairs = self.meta.pairs();
        pairs.push((PART.into(), k.to_string()));
        pairs.push((PART_ROWS_KEY.into(), self.part_rows.to_string()));
        pairs.push((RUN_ID.into(), run_id.into()));
        pairs
    }

    /// Why a part's metadata shows another run or another cut (None if this run's).
    fn mismatch(&self, kv: &std::collections::HashMap<String, String>) -> Option<String> {
        self.meta.mismatch(kv).or_else(|| {
            let want = self.part_rows.to_string();
            match kv.get(PART_ROWS_KEY) {
                Some(w) if *w == want => None,
                Some(w) => Some(format!("its {PART_ROWS_KEY} is {w}, this run's is {want}")),
                None => Some(format!("it has no {PART_ROWS_KEY}")),
            }
        })
    }
}

/// What the flying of a run's missing parts needs.
struct Flow<'a> {
    shard: Shard,
    schema: &'a arrow::datatypes::SchemaRef,
    parts: &'a [Range<u64>],
    /// The parts to fly, in order.
    missing: &'a [usize],
    /// Per part, whether it is kept (`Some`).
    kept: &'a [Option<Option<String>>],
    id: &'a PartId<'a>,
    held: &'a OutputDir,
    threads: usize,
    bar: &'a ProgressBar,
}

/// Chunks a worker may fly ahead of the one the main thread waits for, per thread.
const WINDOW_PER_THREAD: usize = 8;

/// One chunk's rows, or why there are none, and the worker's time on it.
type Done = (usize, anyhow::Result<RecordBatch>, [Duration; 3]);

/// Fly the missing parts: `threads` workers fly their chunks (in order, at most a window
/// ahead), this thread takes the rows in variant order, kept parts' rows read back in their
/// turn, gathers the statistics and writes each missing part. Returns the parts written
/// (a prefix of `missing`: all of them unless an error stops the run).
fn fly_parts(
    p: &Prepared,
    f: &Flow,
    gather: &mut Gather,
    timings: &mut Timings,
) -> anyhow::Result<Vec<usize>> {
    // The chunks of the missing parts, in order: (part, variants of the shard).
    let work: Vec<(usize, Range<u64>)> = f
        .missing
        .iter()
        .flat_map(|&k| {
            let r = f.parts[k].clone();
            chunks(r.end - r.start, p.scenario.chunk_size)
                .into_iter()
                .map(move |c| (k, r.start + c.start..r.start + c.end))
        })
        .collect();
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    // The chunks the main thread has taken, and a bell for workers waiting on it.
    let taken = (Mutex::new(0usize), Condvar::new());
    let window = WINDOW_PER_THREAD * f.threads;
    let (tx, rx) = std::sync::mpsc::channel::<Done>();
    // The beginnings of flights the sweep's points share, left and taken by every worker.
    let store = p.prefix_store();
    let store = store.as_ref();
    std::thread::scope(|s| -> anyhow::Result<Vec<usize>> {
        for _ in 0..f.threads.min(work.len()) {
            let tx = tx.clone();
            let (work, next, stop, taken) = (&work, &next, &stop, &taken);
            s.spawn(move || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= work.len() || stop.load(Ordering::Relaxed) {
                    return;
                }
                {
                    let mut t = taken.0.lock().unwrap_or_else(|e| e.into_inner());
                    while i >= *t + window && !stop.load(Ordering::Relaxed) {
                        t = taken.1.wait(t).unwrap_or_else(|e| e.into_inner());
                    }
                }
                let t0 = Instant::now();
                let variants: Vec<Variant> = work[i]
                    .1
                    .clone()
                    .map(|q| p.plan.variant(f.shard.id(q)))
                    .collect();
                let t1 = Instant::now();
                let results = fly_chunk_sharing(p, &variants, store);
                let t2 = Instant::now();
                let batch = pq::variants_batch(p, f.schema, &variants, &results);
                let t3 = Instant::now();
                if tx.send((i, batch, [t1 - t0, t2 - t1, t3 - t2])).is_err() {
                    return;
                }
            });
        }
        drop(tx);
        let result = (|| -> anyhow::Result<Vec<usize>> {
            let mut pending: BTreeMap<usize, anyhow::Result<RecordBatch>> = BTreeMap::new();
            let mut i = 0;
            let mut written = Vec::new();
            for (k, range) in f.parts.iter().enumerate() {
                if let Some(writer) = &f.kept[k] {
                    // A kept part: its rows read back in their turn, for the statistics.
                    let t = Instant::now();
                    let path = f.held.outputs.part(k);
                    check_part(&path, k, f.id, writer.as_deref(), range.end - range.start)?;
                    let mut q = range.start;
                    for batch in pq::read_batches(&path)? {
                        let batch = batch?;
                        check_ids(&path, &batch, f.shard, &mut q)?;
                        pq::gather(p, gather, &batch)?;
                    }
                    timings.gather += t.elapsed();
                    continue;
                }
                if !f.missing.contains(&k) {
                    // Past the parts this run was to write (`max_parts`).
                    break;
                }
                let path = f.held.outputs.part(k);
                let mut part = PartWriter::create(
                    &path,
                    f.held.temporary(&path),
                    f.schema,
                    &f.id.pairs(k, &f.held.run_id),
                    p.scenario.row_group_rows,
                )?;
                while i < work.len() && work[i].0 == k {
                    let t = Instant::now();
                    let batch = loop {
                        if let Some(b) = pending.remove(&i) {
                            break b;
                        }
                        let (j, b, spent) = rx
                            .recv()
                            .context("a worker thread stopped before its chunk was flown")?;
                        timings.sampling += spent[0];
                        timings.flights += spent[1];
                        timings.rows += spent[2];
                        pending.insert(j, b);
                    }?;
                    timings.waiting += t.elapsed();
                    i += 1;
                    *taken.0.lock().unwrap_or_else(|e| e.into_inner()) = i;
                    taken.1.notify_all();
                    let t = Instant::now();
                    pq::gather(p, gather, &batch)?;
                    let t2 = Instant::now();
                    timings.gather += t2 - t;
                    part.push(batch)?;
                    timings.parquet += t2.elapsed();
                    f.bar.inc(work[i - 1].1.end - work[i - 1].1.start);
                }
                let t = Instant::now();
                part.finish()?;
                timings.parquet += t.elapsed();
                written.push(k);
            }
            Ok(written)
        })();
        if result.is_err() {
            stop.store(true, Ordering::Relaxed);
            taken.1.notify_all();
        }
        drop(rx);
        timings.shared += store.map_or(0, |s| s.borrowed());
        result
    })
}

/// A part being written: its rows appended a row group at a time (the same batches whatever
/// the chunk size, so the same bytes), under its temporary name until it is complete.
struct PartWriter {
    path: PathBuf,
    tmp: PathBuf,
    writer: Option<ArrowWriter<File>>,
    pending: Vec<RecordBatch>,
    rows: usize,
    row_group_rows: usize,
}

impl PartWriter {
    fn create(
        path: &Path,
        tmp: PathBuf,
        schema: &arrow::datatypes::SchemaRef,
        pairs: &[(String, String)],
        row_group_rows: usize,
    ) -> anyhow::Result<PartWriter> {
        let writer = pq::open_writer(&tmp, schema, pairs, row_group_rows)?;
        Ok(PartWriter {
            path: path.to_path_buf(),
            tmp,
            writer: Some(writer),
            pending: Vec::new(),
            rows: 0,
            row_group_rows: row_group_rows.max(1),
        })
    }

    fn push(&mut self, batch: RecordBatch) -> anyhow::Result<()> {
        self.rows += batch.num_rows();
        self.pending.push(batch);
        if self.rows >= self.row_group_rows {
            self.flush()?;
        }
        Ok(())
    }

    /// Write the pending rows' whole row groups (all of them when finishing).
    fn flush(&mut self) -> anyhow::Result<()> {
        let schema = self.pending[0].schema();
        let all = arrow::compute::concat_batches(&schema, &self.pending)?;
        self.pending.clear();
        let w = self.writer.as_mut().expect("open until finished");
        let whole = all.num_rows() / self.row_group_rows * self.row_group_rows;
        let mut at = 0;
        while at < whole {
            w.write(&all.slice(at, self.row_group_rows))?;
            at += self.row_group_rows;
        }
        self.rows = all.num_rows() - whole;
        if self.rows > 0 {
            self.pending.push(all.slice(whole, self.rows));
        }
        Ok(())
    }

    fn finish(mut self) -> anyhow::Result<()> {
        let result = (|| -> anyhow::Result<()> {
            if self.rows > 0 {
                let schema = self.pending[0].schema();
                let rest = arrow::compute::concat_batches(&schema, &self.pending)?;
                self.pending.clear();
                self.writer
                    .as_mut()
                    .expect("open until finished")
                    .write(&rest)?;
            }
            let file = self
                .writer
                .take()
                .expect("open until finished")
                .into_inner()?;
            file.sync_all()?;
            std::fs::rename(&self.tmp, &self.path).with_context(|| {
                format!(
                    "can't rename {} to {}",
                    self.tmp.display(),
                    self.path.display()
                )
            })
        })();
        if result.is_err() {
            let _ = std::fs::remove_file(&self.tmp);
        }
        result.with_context(|| format!("writing {}", self.path.display()))
    }
}

impl Drop for PartWriter {
    /// A part left unfinished (an error, or the run stopped) leaves no temporary file.
    fn drop(&mut self) {
        if self.writer.is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// The metadata keys of a part: the run that wrote it, its number and the rows a part holds.
const RUN_ID: &str = "hpr_mc.run_id";
const PART: &str = "hpr_mc.part";
const PART_ROWS_KEY: &str = "hpr_mc.part_rows";

/// Check that the part at `path` is part `k` of this run, written by `writer` (the run id
/// in its metadata), with `rows` rows: else the directory was changed under the run, and the
/// run stops rather than mix runs.
fn check_part(
    path: &Path,
    k: usize,
    id: &PartId,
    writer: Option<&str>,
    rows: u64,
) -> anyhow::Result<()> {
    let kv = pq::read_pairs(path)?;
    let why = if let Some(why) = id.mismatch(&kv) {
        Some(why)
    } else if kv.get(PART) != Some(&k.to_string()) {
        Some(format!(
            "its {PART} is {}",
            kv.get(PART).map_or("missing", |s| s.as_str())
        ))
    } else if kv.get(RUN_ID).map(String::as_str) != writer {
        Some(format!(
            "it was written by run {}, not by run {}",
            kv.get(RUN_ID).map_or("(none)", |s| s.as_str()),
            writer.unwrap_or("(none)")
        ))
    } else {
        let got = pq::row_count(path)?;
        (got != rows).then(|| format!("it holds {got} rows, the part {rows}"))
    };
    match why {
        None => Ok(()),
        Some(why) => bail!(
            "{} is not part {k} of this run ({why}): something else wrote into the output \
             directory during the run; the variants file was not written, run again",
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
                "{} holds variant {id} where this run's variant {} belongs; the variants file was not written, run again",
                path.display(),
                shard.id(*q)
            );
        }
        *q += 1;
    }
    Ok(())
}

/// [`finish`], the few variants of `trajectories.parquet` flown again alone and written on
/// another thread meanwhile (each on `threads` threads: the statistics are computed point by
/// point side by side, the trajectories flown side by side).
fn finish_beside_trajectories(
    report: &mut RunReport,
    meta: &RunMeta,
    gather: &mut Gather,
    held: &OutputDir,
    timings: &mut Timings,
    threads: usize,
) -> anyhow::Result<()> {
    let prepared = report.prepared.clone();
    let (shard, path) = (report.shard, report.outputs.trajectories.clone());
    let (tmp, pairs) = (held.temporary(&path), meta.pairs());
    let pool = |what: &str| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .with_context(|| format!("can't start the threads of the {what}"))
    };
    let (stats_pool, trajectories_pool) = (pool("statistics")?, pool("trajectories")?);
    let both = Instant::now();
    let (finished, trajectories) = std::thread::scope(|s| {
        let trajectories = s.spawn(|| {
            let t = Instant::now();
            let written = trajectories_pool
                .install(|| super::trajectories::write(&prepared, shard, &path, &tmp, &pairs));
            (written, t.elapsed())
        });
        let finished = stats_pool.install(|| finish(report, meta, gather, held, timings));
        (finished, trajectories.join())
    });
    timings.statistics_and_trajectories = both.elapsed();
    finished?;
    let (written, spent) = trajectories
        .map_err(|_| anyhow::anyhow!("the thread writing trajectories.parquet panicked"))?;
    report.trajectories = written?;
    timings.trajectories = spent;
    Ok(())
}

/// Take the statistics gathered from the rows and write their four files.
fn finish(
    report: &mut RunReport,
    meta: &RunMeta,
    gather: &mut Gather,
    held: &OutputDir,
    timings: &mut Timings,
) -> anyhow::Result<()> {
    let t = Instant::now();
    report.stats = gather.finish();
    report.percentiles = gather.percentiles();
    (
        report.landed,
        report.time_limit,
        report.refused,
        report.failed,
    ) = (
        gather.landed,
        gather.time_limit,
        gather.refused,
        gather.failed,
    );
    report.warned = hpr_sim::Warning::KEYS
        .iter()
        .zip(gather.warned)
        .filter(|(_, n)| *n > 0)
        .map(|(k, n)| (k.to_string(), n))
        .collect();
    let p = &report.prepared;
    let out = &report.outputs;
    let pairs = meta.pairs();
    let rg = p.scenario.row_group_rows;
    let mut summary_pairs = pairs.clone();
    summary_pairs.push((
        "hpr_mc.percentiles".into(),
        report.percentiles.describe(gather.exact_rows()),
    ));
    let summary = pq::summary_batch(p, meta, &report.stats)?;
    let tmp = |path: &Path| held.temporary(path);
    pq::write_atomic(
        &out.summary,
        &tmp(&out.summary),
        &summary.schema(),
        &summary_pairs,
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
    timings.statistics = t.elapsed();
    Ok(())
}

/// Per part, the writer of its complete file kept from an earlier run (`Some(run id)`, the
/// id `None` for a part that names none), or `None` to fly it. Only with `resume` are parts
/// kept; without it the output directory has removed them already ([`OutputDir::open`]).
/// Leftover temporary files, and files of another cut, are removed.
fn scan_parts(
    out: &Outputs,
    id: &PartId,
    part_list: &[Range<u64>],
    resume: bool,
) -> anyhow::Result<Vec<Option<Option<String>>>> {
    let mut done = vec![None; part_list.len()];
    for entry in std::fs::read_dir(&out.parts)
        .with_context(|| format!("can't read {}", out.parts.display()))?
    {
        let path = entry?.path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("")
            .to_string();
        let part = name
            .strip_prefix("part-")
            .and_then(|r| r.strip_suffix(".parquet"))
            .and_then(|n| n.parse::<usize>().ok());
        match part {
            Some(k) if resume => {
                let kv = pq::read_pairs(&path)?;
                if let Some(why) = id.mismatch(&kv) {
                    bail!("{} is a part of another run ({why}); to start over, run without --resume, or remove {}", path.display(), out.parts.display());
                }
                let expected = part_list.get(k).map(|r| r.end - r.start);
                if kv.get(PART) != Some(&k.to_string()) || expected != Some(pq::row_count(&path)?) {
                    bail!("{} does not hold part {k} of this run; to start over, run without --resume, or remove {}", path.display(), out.parts.display());
                }
                done[k] = Some(kv.get(RUN_ID).cloned());
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

    /// Part `c` of `ids` written as run `writer` of the run `meta`, parts of 2 rows.
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
        let pairs = PartId { meta, part_rows: 2 }.pairs(c, writer);
        let path = dir.join(format!("chunk-{c}-{}-{writer}-{ids:?}.parquet", meta.seed));
        pq::write_atomic(&path, &dir.join("tmp"), &schema, &pairs, 100, |w| {
            Ok(w.write(&batch)?)
        })
        .unwrap();
        path
    }

    #[test]
    fn parts_hold_at_least_16384_rows_in_whole_row_groups_and_a_run_has_at_most_256() {
        assert_eq!(part_rows(20_000, 8192), 16_384);
        // A million variants: 62 parts (the last of 576 rows), not 31,250 chunks.
        assert_eq!(part_rows(1_000_000, 8192), 16_384);
        assert_eq!(1_000_000u64.div_ceil(16_384), 62);
        // Ten million, the most one process flies: 40,960 rows a part, 245 parts.
        assert_eq!(part_rows(10_000_000, 8192), 40_960);
        assert_eq!(10_000_000u64.div_ceil(40_960), 245);
        for count in [1, 1000, 4_194_304, 4_194_305, 9_999_999, 10_000_000] {
            for rg in [1, 7, 8192, 100_000] {
                let rows = part_rows(count, rg);
                assert!(count.div_ceil(rows) <= MAX_PARTS, "{count} {rg}");
                assert!(rows >= PART_ROWS && rows % rg as u64 == 0, "{count} {rg}");
            }
        }
    }

    #[test]
    fn the_copy_takes_only_a_part_of_this_run_s_cut_number_writer_rows_and_ids() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let m = meta(5);
        let id = PartId {
            meta: &m,
            part_rows: 2,
        };
        // Shard 1 of 2, parts of 2: part 1 holds the shard's variants 2 and 3, ids 5 and 7.
        let good = part(d, &m, 1, "me", &[5, 7]);
        check_part(&good, 1, &id, Some("me"), 2).unwrap();
        let mut q = 2;
        for b in pq::read_batches(&good).unwrap() {
            check_ids(&good, &b.unwrap(), m.shard, &mut q).unwrap();
        }
        assert_eq!(q, 4);
        let refusal = |path: &Path, c: usize, writer: &str, rows: u64| {
            check_part(path, c, &id, Some(writer), rows)
                .unwrap_err()
                .to_string()
        };
        // Another seed's part under this part's name (what two runs into one directory made).
        let other = part(d, &meta(7), 1, "me", &[5, 7]);
        let e = refusal(&other, 1, "me", 2);
        assert!(
            e.contains("is not part 1 of this run (its hpr_mc.seed is 7, this run's is 5)")
                && e.contains("the variants file was not written"),
            "{e}"
        );
        let e = refusal(&good, 1, "another", 2);
        assert!(
            e.contains("(it was written by run me, not by run another)"),
            "{e}"
        );
        let e = refusal(&good, 0, "me", 2);
        assert!(e.contains("(its hpr_mc.part is 1)"), "{e}");
        let e = refusal(&good, 1, "me", 3);
        assert!(e.contains("(it holds 2 rows, the part 3)"), "{e}");
        // The same run cut into parts of another size.
        let cut = PartId {
            meta: &m,
            part_rows: 4,
        };
        let e = check_part(&good, 1, &cut, Some("me"), 2)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("(its hpr_mc.part_rows is 2, this run's is 4)"),
            "{e}"
        );
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
