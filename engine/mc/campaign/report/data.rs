//! The files a run wrote, read back for the report: `variants.parquet` (its metadata, the
//! input and metric columns, the statuses and warnings), `summary.parquet`,
//! `ellipses.parquet`, `sensitivity.parquet`, `requirements.parquet` and
//! `trajectories.parquet`. Columns are found by name and role (the order the run writes
//! them), never by a scenario: the report needs only the directory.
//!
//! The variants file is streamed, a batch at a time and only the columns the report uses,
//! so the report's memory does not grow with the run. What it draws from rows (landings,
//! histograms, margins, convergence) comes from a bounded sample it holds: per sweep point the
//! first [`Run::held_per_point`] rows in variant order (the variants of a point are
//! independent draws, so the first N are a uniform sample), N chosen so that the values held
//! stay under [`HELD_BYTES`] whatever the number of points. What counts over every row (the
//! statuses, the flights that did not land or warned, each input's mean and spread, each
//! requirement's counts and worst flight) is gathered as the rows pass. A run whose points
//! all fit is held whole and gives the page it gave when every row was read.

use crate::campaign::parquet::read_batches;
use anyhow::{bail, Context, Result};
use arrow::array::{Array, Float64Array, StringArray, UInt32Array, UInt64Array, UInt8Array};
use arrow::record_batch::RecordBatch;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::collections::HashMap;
use std::fs::File;
use std::path::{Path, PathBuf};

/// A column's name and unit (`1` for a pure number).
#[derive(Debug, Clone, PartialEq)]
pub struct Col {
    pub name: String,
    pub unit: String,
}

/// A row of requirements.parquet.
#[derive(Debug, Clone, PartialEq)]
pub struct Requirement {
    pub point: usize,
    pub metric: String,
    pub unit: String,
    pub min: Option<f64>,
    pub max: Option<f64>,
    pub variants: u64,
    pub met: u64,
    pub fraction: f64,
    pub low: f64,
    pub high: f64,
}

/// A row of ellipses.parquet.
/// Whose landings an ellipse is of: the rocket's, or released part `k`'s (in the file's
/// order of bodies after the rocket).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Body {
    Rocket,
    Released(usize),
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipseRow {
    /// Whose landings: `rocket`, or `release_<name>` (a released part's).
    pub body: Body,
    pub point: usize,
    pub sigma: u8,
    pub count: u64,
    pub center_x_m: f64,
    pub center_y_m: f64,
    pub semi_major_m: f64,
    pub semi_minor_m: f64,
    pub major_axis_deg: f64,
}

/// A row of sensitivity.parquet.
#[derive(Debug, Clone, PartialEq)]
pub struct SensitivityRow {
    pub point: usize,
    pub metric: String,
    pub input: String,
    pub r2: f64,
    pub standardized: Option<f64>,
    pub share: Option<f64>,
}

/// A row of summary.parquet (the figures the report uses).
#[derive(Debug, Clone, PartialEq)]
pub struct SummaryRow {
    pub point: usize,
    pub metric: String,
    pub count: u64,
    pub std: Option<f64>,
    pub p5: Option<f64>,
    pub p50: Option<f64>,
    pub p95: Option<f64>,
}

/// One variant's time series from trajectories.parquet.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    pub id: u64,
    pub point: usize,
    pub time_s: Vec<f64>,
    pub x_m: Vec<f64>,
    pub y_m: Vec<f64>,
    pub altitude_m: Vec<f64>,
    pub static_margin_cal: Vec<f64>,
    pub flight_margin_cal: Vec<f64>,
}

/// A variant's status: the batch's, read back from its row's text.
pub use hpr_sim::batch::Status;

/// A row's status from its text (as [`Status::name`] wrote it); any other text is a failure.
fn parse_status(s: &str) -> Status {
    [Status::Landed, Status::TimeLimit, Status::Refused]
        .into_iter()
        .find(|st| st.name() == s)
        .unwrap_or(Status::Failed)
}

/// The most bytes of row values the report holds (8 bytes a value, a row's inputs and metrics
/// with its id, point and status): 16 MiB.
pub const HELD_BYTES: usize = 16 << 20;

/// The flights a point has and how many of them the report holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PointCount {
    /// Rows of the point in variants.parquet.
    pub variants: u64,
    /// Of them, landed.
    pub landed: u64,
    /// Rows of the point held (the first ones, in variant order).
    pub held: u64,
}

/// A flight that did not land or raised a warning.
#[derive(Debug, Clone, PartialEq)]
pub struct Look {
    pub id: u64,
    pub point: usize,
    pub status: Status,
    /// Its error, else its warnings.
    pub why: String,
}

/// An input's moments over every row.
pub use crate::campaign::gather::Moments;

/// A requirement's counts over every row of its point: the landed flights with a finite
/// value, those above its maximum and those below its minimum.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Tally {
    pub landed: u64,
    pub above: u64,
    pub below: u64,
}

/// The worst flight of a point by a requirement (point 0's bounds): its id and value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Worst {
    pub id: u64,
    pub value: f64,
    score: f64,
}

/// Everything the report draws from.
#[derive(Debug, Clone, Default)]
pub struct Run {
    pub dir: PathBuf,
    /// `hpr_mc.*` metadata of the variants file.
    pub meta: HashMap<String, String>,
    /// When variants.parquet was written (its modification time), seconds since 1970.
    pub written_unix_s: Option<u64>,
    /// Swept inputs (`sweep_<input>` without the prefix) and each point's values.
    pub sweep: Vec<Col>,
    pub sweep_values: Vec<Vec<f64>>,
    /// Per point, the designation of the motor it flies where the motor is swept (the `motor`
    /// column beside `sweep_motor_index`); empty without a sweep of motors.
    pub sweep_motors: Vec<Option<String>>,
    pub inputs: Vec<Col>,
    pub metrics: Vec<Col>,
    /// The rows held (the sample): their ids, points and statuses.
    pub id: Vec<u64>,
    pub point: Vec<usize>,
    pub status: Vec<Status>,
    /// Per input, per row held.
    pub input_values: Vec<Vec<f64>>,
    /// Per metric, per row held (NaN where null).
    pub metric_values: Vec<Vec<f64>>,
    /// The most rows held of a point, and the bound on the bytes held it follows from.
    pub held_per_point: u64,
    pub held_bytes: usize,
    /// Per point: its rows, landed, held.
    pub counts: Vec<PointCount>,
    /// Rows in variants.parquet, and of them landed.
    pub variants: u64,
    pub landed: u64,
    /// The first [`LOOKS_KEPT`] flights that did not land or warned, in variant order, and
    /// how many there are.
    pub looks: Vec<Look>,
    pub looks_total: u64,
    /// Per input, over every row.
    pub input_moments: Vec<Moments>,
    /// Per row of `requirements`, over every row of its point.
    pub tallies: Vec<Tally>,
    /// Per requirement of point 0 (its index in `requirements`), per point: the worst flight.
    pub worst: HashMap<(usize, usize), Worst>,
    pub summary: Vec<SummaryRow>,
    pub ellipses: Vec<EllipseRow>,
    /// The released parts' body names in ellipses.parquet (`release_<name>`), in order.
    pub released: Vec<String>,
    pub sensitivity: Vec<SensitivityRow>,
    pub requirements: Vec<Requirement>,
    pub series: Vec<Series>,
    /// Whether trajectories.parquet was there.
    pub has_trajectories: bool,
}

/// The files of a run in `dir` with the name suffix of a shard (`""` for a whole run).
#[derive(Debug, Clone)]
pub struct Files {
    pub variants: PathBuf,
    pub summary: PathBuf,
    pub ellipses: PathBuf,
    pub sensitivity: PathBuf,
    pub requirements: PathBuf,
    pub trajectories: PathBuf,
}

impl Files {
    pub fn in_dir(dir: &Path, suffix: &str) -> Files {
        let f = |stem: &str| dir.join(format!("{stem}{suffix}.parquet"));
        Files {
            variants: f("variants"),
            summary: f("summary"),
            ellipses: f("ellipses"),
            sensitivity: f("sensitivity"),
            requirements: f("requirements"),
            trajectories: f("trajectories"),
        }
    }
}

fn col<'a, T: 'static>(b: &'a RecordBatch, name: &str, path: &Path) -> Result<&'a T> {
    b.column_by_name(name)
        .and_then(|c| c.as_any().downcast_ref::<T>())
        .with_context(|| format!("{}: no column {name} of the expected type", path.display()))
}

fn f64s(b: &RecordBatch, name: &str, path: &Path) -> Result<Vec<f64>> {
    let c: &Float64Array = col(b, name, path)?;
    Ok((0..c.len())
        .map(|r| if c.is_null(r) { f64::NAN } else { c.value(r) })
        .collect())
}

fn opt_f64s(b: &RecordBatch, name: &str, path: &Path) -> Result<Vec<Option<f64>>> {
    let c: &Float64Array = col(b, name, path)?;
    Ok((0..c.len())
        .map(|r| (!c.is_null(r)).then(|| c.value(r)))
        .collect())
}

fn strings(b: &RecordBatch, name: &str, path: &Path) -> Result<Vec<Option<String>>> {
    let c: &StringArray = col(b, name, path)?;
    Ok((0..c.len())
        .map(|r| (!c.is_null(r)).then(|| c.value(r).to_string()))
        .collect())
}

fn u32s(b: &RecordBatch, name: &str, path: &Path) -> Result<Vec<usize>> {
    let c: &UInt32Array = col(b, name, path)?;
    Ok(c.values().iter().map(|&v| v as usize).collect())
}

fn u64s(b: &RecordBatch, name: &str, path: &Path) -> Result<Vec<u64>> {
    let c: &UInt64Array = col(b, name, path)?;
    Ok(c.values().to_vec())
}

/// All the batches of a file.
fn batches(path: &Path) -> Result<Vec<RecordBatch>> {
    read_batches(path)?
        .collect::<Result<Vec<_>>>()
        .with_context(|| format!("reading {}", path.display()))
}

/// How many flights that did not land or warned are kept by name.
pub const LOOKS_KEPT: usize = 40;

impl Run {
    /// Read a run's files, holding at most [`HELD_BYTES`] of rows.
    pub fn read(dir: &Path, files: &Files) -> Result<Run> {
        Run::read_holding(dir, files, HELD_BYTES)
    }

    /// Read a run's files, holding at most `held_bytes` of rows (at least one row a point).
    pub fn read_holding(dir: &Path, files: &Files, held_bytes: usize) -> Result<Run> {
        let path = &files.variants;
        if !path.is_file() {
            bail!(
                "{}: no variants file (a run writes variants.parquet there; a shard's run writes variants-shard-K-of-N.parquet and its own report)",
                path.display()
            );
        }
        let file = File::open(path).with_context(|| format!("can't open {}", path.display()))?;
        let builder = ParquetRecordBatchReaderBuilder::try_new(file)
            .with_context(|| format!("{} is not a readable Parquet file", path.display()))?;
        let meta: HashMap<String, String> = builder
            .metadata()
            .file_metadata()
            .key_value_metadata()
            .cloned()
            .unwrap_or_default()
            .into_iter()
            .filter_map(|kv| kv.value.map(|v| (kv.key, v)))
            .collect();
        if !meta.contains_key("hpr_mc.scenario") {
            bail!(
                "{}: not a file of an hpr-mc run (no hpr_mc.scenario metadata)",
                path.display()
            );
        }
        let schema = builder.schema().clone();
        let unit = |f: &arrow::datatypes::Field| {
            f.metadata()
                .get("unit")
                .cloned()
                .unwrap_or_else(|| "1".into())
        };
        let names: Vec<&str> = schema.fields().iter().map(|f| f.name().as_str()).collect();
        let status_at = names
            .iter()
            .position(|n| *n == "status")
            .with_context(|| format!("{}: no status column", path.display()))?;
        let mut sweep = vec![];
        let mut has_motor = false;
        let mut inputs = vec![];
        let mut metrics = vec![];
        for (k, f) in schema.fields().iter().enumerate() {
            let n = f.name();
            if k < status_at {
                if n == "motor" && f.data_type() == &arrow::datatypes::DataType::Utf8 {
                    has_motor = true;
                } else if let Some(rest) = n.strip_prefix("sweep_") {
                    sweep.push(Col {
                        name: rest.to_string(),
                        unit: unit(f),
                    });
                } else if !["variant_id", "point", "replicate", "sensor_seed"].contains(&n.as_str())
                    // An input's number (a swept motor's designation is text beside it).
                    && f.data_type() == &arrow::datatypes::DataType::Float64
                {
                    inputs.push(Col {
                        name: n.clone(),
                        unit: unit(f),
                    });
                }
            } else if n != "status" && n != "error" && n != "warnings" && !n.starts_with("warning_")
            {
                metrics.push(Col {
                    name: n.clone(),
                    unit: unit(f),
                });
            }
        }
        let written_unix_s = std::fs::metadata(path)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
            .map(|d| d.as_secs());
        let points: usize = meta
            .get("hpr_mc.points")
            .and_then(|p| p.parse().ok())
            .unwrap_or(1);
        let row_bytes = 8 * (inputs.len() + metrics.len()) + 8 + 8 + 1;
        let held_per_point = (held_bytes / (row_bytes * points.max(1))).max(1) as u64;
        let mut run = Run {
            dir: dir.to_path_buf(),
            meta,
            written_unix_s,
            sweep_values: vec![vec![]; points],
            sweep_motors: if has_motor {
                vec![None; points]
            } else {
                vec![]
            },
            input_values: vec![vec![]; inputs.len()],
            metric_values: vec![vec![]; metrics.len()],
            input_moments: vec![Moments::default(); inputs.len()],
            counts: vec![PointCount::default(); points],
            held_per_point,
            held_bytes,
            sweep,
            inputs,
            metrics,
            ..Run::default()
        };
        // The statistics first: the requirements say what to count as the rows pass.
        run.read_statistics(files)?;
        run.tallies = vec![Tally::default(); run.requirements.len()];
        let tallied: Vec<(usize, Option<usize>)> = run
            .requirements
            .iter()
            .enumerate()
            .map(|(q, r)| (q, run.metric(&r.metric)))
            .collect();
        let judged: Vec<(usize, usize)> = run
            .requirements
            .iter()
            .enumerate()
            .filter(|(_, r)| r.point == 0)
            .filter_map(|(q, r)| Some((q, run.metric(&r.metric)?)))
            .collect();
        let mut names: Vec<String> = vec!["variant_id".into(), "point".into()];
        names.extend(run.sweep.iter().map(|c| format!("sweep_{}", c.name)));
        if has_motor {
            names.push("motor".into());
        }
        names.extend(["status".into(), "error".into(), "warnings".into()]);
        names.extend(run.inputs.iter().map(|c| c.name.clone()));
        names.extend(run.metrics.iter().map(|c| c.name.clone()));
        let mask = parquet::arrow::ProjectionMask::columns(
            builder.parquet_schema(),
            names.iter().map(String::as_str),
        );
        let reader = builder
            .with_projection(mask)
            .with_batch_size(8192)
            .build()?;
        for b in reader {
            let b = b.with_context(|| format!("reading {}", path.display()))?;
            let ids = u64s(&b, "variant_id", path)?;
            let pts = u32s(&b, "point", path)?;
            let status: &StringArray = col(&b, "status", path)?;
            let status: Vec<Status> = (0..status.len())
                .map(|r| parse_status(status.value(r)))
                .collect();
            let errors: &StringArray = col(&b, "error", path)?;
            let warnings: &StringArray = col(&b, "warnings", path)?;
            let mut keep = vec![];
            for (r, &pt) in pts.iter().enumerate() {
                if pt < points && run.sweep_values[pt].is_empty() {
                    run.sweep_values[pt] = run
                        .sweep
                        .iter()
                        .map(|s| {
                            f64s(&b.slice(r, 1), &format!("sweep_{}", s.name), path)
                                .map(|v| v[0])
                                .unwrap_or(f64::NAN)
                        })
                        .collect();
                    if has_motor {
                        let m: &StringArray = col(&b, "motor", path)?;
                        run.sweep_motors[pt] = Some(m.value(r).to_string());
                    }
                }
                let landed = status[r] == Status::Landed;
                run.variants += 1;
                run.landed += u64::from(landed);
                if let Some(c) = run.counts.get_mut(pt) {
                    c.variants += 1;
                    c.landed += u64::from(landed);
                    if c.held < held_per_point {
                        c.held += 1;
                        keep.push(r);
                    }
                }
                if !landed || !warnings.is_null(r) {
                    run.looks_total += 1;
                    if run.looks.len() < LOOKS_KEPT {
                        let why = if !errors.is_null(r) {
                            errors.value(r)
                        } else if !warnings.is_null(r) {
                            warnings.value(r)
                        } else {
                            ""
                        };
                        run.looks.push(Look {
                            id: ids[r],
                            point: pt,
                            status: status[r],
                            why: why.to_string(),
                        });
                    }
                }
            }
            for &r in &keep {
                run.id.push(ids[r]);
                run.point.push(pts[r]);
                run.status.push(status[r]);
            }
            for (j, c) in run.inputs.iter().enumerate() {
                let v = f64s(&b, &c.name, path)?;
                let m = &mut run.input_moments[j];
                v.iter().for_each(|&x| m.add(x));
                run.input_values[j].extend(keep.iter().map(|&r| v[r]));
            }
            let mut values: Vec<Option<Vec<f64>>> = vec![None; run.metrics.len()];
            for (m, c) in run.metrics.iter().enumerate() {
                let v = f64s(&b, &c.name, path)?;
                run.metric_values[m].extend(keep.iter().map(|&r| v[r]));
                values[m] = Some(v);
            }
            for &(q, m) in &tallied {
                let (Some(m), req) = (m, &run.requirements[q]) else {
                    continue;
                };
                let v = values[m].as_ref().expect("read above");
                let t = &mut run.tallies[q];
                for r in 0..v.len() {
                    if pts[r] != req.point || status[r] != Status::Landed || !v[r].is_finite() {
                        continue;
                    }
                    t.landed += 1;
                    t.above += u64::from(req.max.is_some_and(|c| v[r] > c));
                    t.below += u64::from(req.min.is_some_and(|c| v[r] < c));
                }
            }
            for &(q, m) in &judged {
                let (min, max) = (run.requirements[q].min, run.requirements[q].max);
                // Below a minimum, the least; above a maximum, the greatest; within both,
                // the farthest out in half-widths of the interval.
                let score = |v: f64| match (min, max) {
                    (Some(a), Some(b)) => ((v - 0.5 * (a + b)) / (0.5 * (b - a))).abs(),
                    (Some(_), None) => -v,
                    (None, Some(_)) => v,
                    (None, None) => 0.0,
                };
                let v = values[m].as_ref().expect("read above");
                for r in 0..v.len() {
                    if !v[r].is_finite() {
                        continue;
                    }
                    let s = score(v[r]);
                    // The last of equals, as a maximum over the rows in order is.
                    let w = run.worst.entry((q, pts[r])).or_insert(Worst {
                        id: ids[r],
                        value: v[r],
                        score: s,
                    });
                    if s.total_cmp(&w.score) != std::cmp::Ordering::Less {
                        *w = Worst {
                            id: ids[r],
                            value: v[r],
                            score: s,
                        };
                    }
                }
            }
        }
        if files.trajectories.is_file() {
            run.read_series(&files.trajectories)?;
            run.has_trajectories = true;
        }
        Ok(run)
    }

    fn read_statistics(&mut self, files: &Files) -> Result<()> {
        let p = &files.summary;
        for b in batches(p)? {
            let (pt, metric) = (u32s(&b, "point", p)?, strings(&b, "metric", p)?);
            let count = u64s(&b, "count", p)?;
            let (std, p5, p50, p95) = (
                opt_f64s(&b, "std", p)?,
                opt_f64s(&b, "p5", p)?,
                opt_f64s(&b, "p50", p)?,
                opt_f64s(&b, "p95", p)?,
            );
            for r in 0..b.num_rows() {
                self.summary.push(SummaryRow {
                    point: pt[r],
                    metric: metric[r].clone().unwrap_or_default(),
                    count: count[r],
                    std: std[r],
                    p5: p5[r],
                    p50: p50[r],
                    p95: p95[r],
                });
            }
        }
        let p = &files.ellipses;
        for b in batches(p)? {
            // Files without a `body` column hold the rocket's ellipses only.
            let bodies = match b.column_by_name("body") {
                Some(_) => strings(&b, "body", p)?,
                None => vec![None; b.num_rows()],
            };
            let pt = u32s(&b, "point", p)?;
            let sigma: &UInt8Array = col(&b, "sigma", p)?;
            let count = u64s(&b, "count", p)?;
            let f = |n: &str| f64s(&b, n, p);
            let (cx, cy, a, bb, ang) = (
                f("center_x_m")?,
                f("center_y_m")?,
                f("semi_major_m")?,
                f("semi_minor_m")?,
                f("major_axis_deg")?,
            );
            for r in 0..b.num_rows() {
                let body = match bodies[r].as_deref() {
                    None | Some("rocket") => Body::Rocket,
                    Some(name) => {
                        let k = match self.released.iter().position(|n| n == name) {
                            Some(k) => k,
                            None => {
                                self.released.push(name.to_string());
                                self.released.len() - 1
                            }
                        };
                        Body::Released(k)
                    }
                };
                self.ellipses.push(EllipseRow {
                    body,
                    point: pt[r],
                    sigma: sigma.value(r),
                    count: count[r],
                    center_x_m: cx[r],
                    center_y_m: cy[r],
                    semi_major_m: a[r],
                    semi_minor_m: bb[r],
                    major_axis_deg: ang[r],
                });
            }
        }
        let p = &files.sensitivity;
        for b in batches(p)? {
            let pt = u32s(&b, "point", p)?;
            let (metric, input) = (strings(&b, "metric", p)?, strings(&b, "input", p)?);
            let r2 = f64s(&b, "r2", p)?;
            let (std, share) = (
                opt_f64s(&b, "standardized_coefficient", p)?,
                opt_f64s(&b, "share", p)?,
            );
            for r in 0..b.num_rows() {
                self.sensitivity.push(SensitivityRow {
                    point: pt[r],
                    metric: metric[r].clone().unwrap_or_default(),
                    input: input[r].clone().unwrap_or_default(),
                    r2: r2[r],
                    standardized: std[r],
                    share: share[r],
                });
            }
        }
        let p = &files.requirements;
        for b in batches(p)? {
            let pt = u32s(&b, "point", p)?;
            let (metric, unit) = (strings(&b, "metric", p)?, strings(&b, "unit", p)?);
            let (min, max) = (opt_f64s(&b, "min", p)?, opt_f64s(&b, "max", p)?);
            let (variants, met) = (u64s(&b, "variants", p)?, u64s(&b, "met", p)?);
            let (fr, lo, hi) = (
                f64s(&b, "fraction", p)?,
                f64s(&b, "fraction_low_95", p)?,
                f64s(&b, "fraction_high_95", p)?,
            );
            for r in 0..b.num_rows() {
                self.requirements.push(Requirement {
                    point: pt[r],
                    metric: metric[r].clone().unwrap_or_default(),
                    unit: unit[r].clone().unwrap_or_default(),
                    min: min[r],
                    max: max[r],
                    variants: variants[r],
                    met: met[r],
                    fraction: fr[r],
                    low: lo[r],
                    high: hi[r],
                });
            }
        }
        Ok(())
    }

    fn read_series(&mut self, p: &Path) -> Result<()> {
        // Only the columns drawn.
        let file = File::open(p).with_context(|| format!("can't open {}", p.display()))?;
        let builder = ParquetRecordBatchReaderBuilder::try_new(file)
            .with_context(|| format!("{} is not a readable Parquet file", p.display()))?;
        let mask = parquet::arrow::ProjectionMask::columns(
            builder.parquet_schema(),
            [
                "variant_id",
                "point",
                "time_s",
                "x_m",
                "y_m",
                "altitude_m",
                "static_margin_cal",
                "flight_margin_cal",
            ],
        );
        let reader = builder
            .with_projection(mask)
            .with_batch_size(8192)
            .build()?;
        for b in reader {
            let b = b.with_context(|| format!("reading {}", p.display()))?;
            let id = u64s(&b, "variant_id", p)?;
            let pt = u32s(&b, "point", p)?;
            let f = |n: &str| f64s(&b, n, p);
            let (t, x, y, alt, sm, fm) = (
                f("time_s")?,
                f("x_m")?,
                f("y_m")?,
                f("altitude_m")?,
                f("static_margin_cal")?,
                f("flight_margin_cal")?,
            );
            for r in 0..b.num_rows() {
                if self.series.last().is_none_or(|s| s.id != id[r]) {
                    self.series.push(Series {
                        id: id[r],
                        point: pt[r],
                        ..Series::default()
                    });
                }
                let s = self.series.last_mut().expect("pushed above");
                s.time_s.push(t[r]);
                s.x_m.push(x[r]);
                s.y_m.push(y[r]);
                s.altitude_m.push(alt[r]);
                s.static_margin_cal.push(sm[r]);
                s.flight_margin_cal.push(fm[r]);
            }
        }
        Ok(())
    }

    /// Whether every row is held (no point has more rows than the sample holds).
    pub fn whole(&self) -> bool {
        self.counts.iter().all(|c| c.held == c.variants)
    }

    /// Whether point `pt` is drawn from a sample of its rows.
    pub fn sampled(&self, pt: usize) -> bool {
        self.counts.get(pt).is_some_and(|c| c.held < c.variants)
    }

    /// Where a point is drawn from a sample: "the first N of its M flights" said in words
    /// (empty when every row of the point is held).
    pub fn sample_text(&self, pt: usize) -> String {
        match self.counts.get(pt) {
            Some(c) if c.held < c.variants => format!(
                "the first {} of the point's {} flights in variant order (a uniform sample: the variants of a point are independent draws; the report holds at most {} of rows)",
                c.held,
                c.variants,
                if self.held_bytes % (1 << 20) == 0 {
                    format!("{} MiB", self.held_bytes >> 20)
                } else {
                    format!("{} bytes", self.held_bytes)
                }
            ),
            _ => String::new(),
        }
    }

    /// Number of sweep points.
    pub fn points(&self) -> usize {
        self.sweep_values.len()
    }

    /// The designation of the motor point `pt` flies, where swept input `k` is the motor.
    pub fn sweep_motor(&self, pt: usize, k: usize) -> Option<&str> {
        if self.sweep.get(k)?.name != "motor_index" {
            return None;
        }
        self.sweep_motors.get(pt)?.as_deref()
    }

    /// The designations of a swept motor, each once, in the order of the points that fly
    /// them; `None` without a sweep of motors.
    pub fn swept_motor_names(&self) -> Option<Vec<&str>> {
        let k = self.sweep.iter().position(|c| c.name == "motor_index")?;
        let mut names: Vec<&str> = vec![];
        for pt in 0..self.points() {
            if let Some(d) = self.sweep_motor(pt, k).filter(|d| !names.contains(d)) {
                names.push(d);
            }
        }
        (!names.is_empty()).then_some(names)
    }

    /// A metric's index by name.
    pub fn metric(&self, name: &str) -> Option<usize> {
        self.metrics.iter().position(|m| m.name == name)
    }

    /// The rows of sweep point `pt`.
    pub fn rows_of(&self, pt: usize) -> Vec<usize> {
        (0..self.id.len())
            .filter(|&r| self.point[r] == pt)
            .collect()
    }

    /// The finite values of metric `m` among the landed rows of point `pt`, in row order.
    pub fn landed_values(&self, m: usize, pt: usize) -> Vec<f64> {
        (0..self.id.len())
            .filter(|&r| self.point[r] == pt && self.status[r] == Status::Landed)
            .map(|r| self.metric_values[m][r])
            .filter(|v| v.is_finite())
            .collect()
    }

    /// A metadata value.
    pub fn meta(&self, key: &str) -> &str {
        self.meta.get(key).map_or("", String::as_str)
    }

    /// A summary row.
    pub fn summary_of(&self, pt: usize, metric: &str) -> Option<&SummaryRow> {
        self.summary
            .iter()
            .find(|s| s.point == pt && s.metric == metric)
    }

    /// The counts over every row of the requirement on `metric` at point `pt`.
    pub fn tally(&self, pt: usize, metric: &str) -> Option<Tally> {
        let q = self
            .requirements
            .iter()
            .position(|r| r.point == pt && r.metric == metric)?;
        self.tallies.get(q).copied()
    }

    /// The requirement on `metric` at point `pt`.
    pub fn requirement(&self, pt: usize, metric: &str) -> Option<&Requirement> {
        self.requirements
            .iter()
            .find(|r| r.point == pt && r.metric == metric)
    }
}
