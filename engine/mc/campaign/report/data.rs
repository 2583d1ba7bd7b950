//! The files a run wrote, read back for the report: `variants.parquet` (its metadata, every
//! input and metric column, the statuses and warnings), `summary.parquet`,
//! `ellipses.parquet`, `sensitivity.parquet`, `requirements.parquet` and
//! `trajectories.parquet`. Columns are found by name and role (the order the run writes
//! them), never by a scenario: the report needs only the directory.

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

/// A variant's status, as its row says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Landed,
    TimeLimit,
    Refused,
    Failed,
}

impl Status {
    fn parse(s: &str) -> Status {
        match s {
            "landed" => Status::Landed,
            "time_limit" => Status::TimeLimit,
            "refused" => Status::Refused,
            _ => Status::Failed,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Status::Landed => "landed",
            Status::TimeLimit => "time_limit",
            Status::Refused => "refused",
            Status::Failed => "failed",
        }
    }
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
    pub inputs: Vec<Col>,
    pub metrics: Vec<Col>,
    pub id: Vec<u64>,
    pub point: Vec<usize>,
    pub status: Vec<Status>,
    /// Row → error text, for rows that have one.
    pub errors: HashMap<usize, String>,
    /// Row → warnings text, for rows that have some.
    pub warnings: HashMap<usize, String>,
    /// Per input, per row.
    pub input_values: Vec<Vec<f64>>,
    /// Per metric, per row (NaN where null).
    pub metric_values: Vec<Vec<f64>>,
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

impl Run {
    /// Read a run's files.
    pub fn read(dir: &Path, files: &Files) -> Result<Run> {
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
        let mut inputs = vec![];
        let mut metrics = vec![];
        for (k, f) in schema.fields().iter().enumerate() {
            let n = f.name();
            if k < status_at {
                if let Some(rest) = n.strip_prefix("sweep_") {
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
        let mut run = Run {
            dir: dir.to_path_buf(),
            meta,
            written_unix_s,
            sweep_values: vec![vec![]; points],
            input_values: vec![vec![]; inputs.len()],
            metric_values: vec![vec![]; metrics.len()],
            sweep,
            inputs,
            metrics,
            ..Run::default()
        };
        let reader = builder.with_batch_size(8192).build()?;
        for b in reader {
            let b = b.with_context(|| format!("reading {}", path.display()))?;
            let first = run.id.len();
            run.id.extend(u64s(&b, "variant_id", path)?);
            let pts = u32s(&b, "point", path)?;
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
                }
            }
            run.point.extend(pts);
            let status: &StringArray = col(&b, "status", path)?;
            run.status
                .extend((0..status.len()).map(|r| Status::parse(status.value(r))));
            for (r, e) in strings(&b, "error", path)?.into_iter().enumerate() {
                if let Some(e) = e {
                    run.errors.insert(first + r, e);
                }
            }
            for (r, w) in strings(&b, "warnings", path)?.into_iter().enumerate() {
                if let Some(w) = w {
                    run.warnings.insert(first + r, w);
                }
            }
            for (j, c) in run.inputs.iter().enumerate() {
                run.input_values[j].extend(f64s(&b, &c.name, path)?);
            }
            for (m, c) in run.metrics.iter().enumerate() {
                run.metric_values[m].extend(f64s(&b, &c.name, path)?);
            }
        }
        run.read_statistics(files)?;
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

    /// Number of sweep points.
    pub fn points(&self) -> usize {
        self.sweep_values.len()
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

    /// The requirement on `metric` at point `pt`.
    pub fn requirement(&self, pt: usize, metric: &str) -> Option<&Requirement> {
        self.requirements
            .iter()
            .find(|r| r.point == pt && r.metric == metric)
    }
}
