//! The campaign report: `report.html`, one self-contained page (inline SVG and CSS, no
//! script, nothing fetched) beside a run's Parquet files, and the landing maps
//! (`landing.kml`, `landing.geojson`) when the scenario places the site on the Earth.
//!
//! This module owns them and draws them only from the files the run wrote
//! (`variants.parquet`, `summary.parquet`, `ellipses.parquet`, `sensitivity.parquet`,
//! `requirements.parquet`, `trajectories.parquet`, and their metadata): the run calls
//! [`write_files`] at its end and `hpr-mc report RESULTS_DIR` calls [`write_dir`], and both
//! give the same page (its date is the variants file's). A dense landing cloud is drawn as a
//! density, not one element per flight, so the page's size does not grow with the number
//! of variants; and the variants file is streamed, the rows drawn being a bounded sample
//! (the first N of each point, said on the page) and the counts gathered over every row as
//! they pass, so the report's memory does not grow with it either ([`data`]).
//!
//! - [`data`]: the files read back: the statistics files whole, the variants streamed.
//! - [`numbers`]: the few figures computed from the rows (a ceiling's chance and bound,
//!   radii, histogram bins, bands across flights).
//! - [`figures`]: the charts.
//! - [`page`]: the page, section by section.
//! - [`maps`]: KML and GeoJSON.

pub mod data;
pub mod figures;
pub mod maps;
pub mod numbers;
pub mod page;

use super::run::Outputs;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What the report wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    pub report: PathBuf,
    /// The page's size, bytes.
    pub bytes: u64,
    /// The maps, when the scenario gives the site's latitude and longitude.
    pub kml: Option<PathBuf>,
    pub geojson: Option<PathBuf>,
    /// Time taken, s.
    pub seconds: f64,
}

/// Write `text` to `path` through a temporary file renamed into place.
fn write_atomic(path: &Path, text: &str) -> Result<()> {
    // A name of this process's own: a run writes its report under its lock; `hpr-mc report`
    // may run beside another, and never renames another's half-written file.
    let tmp = crate::campaign::outdir::temporary(path, &format!("report-{:x}", std::process::id()));
    std::fs::write(&tmp, text).with_context(|| format!("can't write {}", tmp.display()))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        anyhow::anyhow!("can't rename {} to {}: {e}", tmp.display(), path.display())
    })
}

/// The report and the maps of the run whose files `outputs` names.
pub fn write_files(outputs: &Outputs) -> Result<Written> {
    let suffix = outputs
        .variants
        .file_name()
        .and_then(|n| n.to_str())
        .and_then(|n| n.strip_prefix("variants"))
        .and_then(|n| n.strip_suffix(".parquet"))
        .unwrap_or("")
        .to_string();
    write(
        &outputs.dir,
        &suffix,
        &outputs.report,
        &outputs.kml,
        &outputs.geojson,
        data::HELD_BYTES,
    )
}

/// `hpr-mc report RESULTS_DIR`: the report and maps of the (whole) run in `dir`, again.
pub fn write_dir(dir: &Path) -> Result<Written> {
    write_dir_holding(dir, data::HELD_BYTES)
}

/// [`write_dir`] holding at most `held_bytes` of rows (see [`data`]).
pub fn write_dir_holding(dir: &Path, held_bytes: usize) -> Result<Written> {
    if !dir.is_dir() {
        anyhow::bail!(
            "{}: no such directory (give a run's output directory)",
            dir.display()
        );
    }
    write(
        dir,
        "",
        &dir.join("report.html"),
        &dir.join("landing.kml"),
        &dir.join("landing.geojson"),
        held_bytes,
    )
}

fn write(
    dir: &Path,
    suffix: &str,
    report: &Path,
    kml: &Path,
    geojson: &Path,
    held_bytes: usize,
) -> Result<Written> {
    let started = Instant::now();
    let files = data::Files::in_dir(dir, suffix);
    let run = data::Run::read_holding(dir, &files, held_bytes)?;
    let context = page::Context::of(&run);
    let html = page::html(&run, &context);
    write_atomic(report, &html)?;
    let (mut k, mut g) = (None, None);
    if let Some(site) = maps::site(&run, context.elevation_m) {
        let shapes = maps::shapes(&run, &context.point_labels);
        write_atomic(kml, &maps::kml(&site, &context.name, &shapes)?)?;
        write_atomic(geojson, &maps::geojson(&site, &shapes))?;
        (k, g) = (Some(kml.to_path_buf()), Some(geojson.to_path_buf()));
    }
    Ok(Written {
        report: report.to_path_buf(),
        bytes: html.len() as u64,
        kml: k,
        geojson: g,
        seconds: started.elapsed().as_secs_f64(),
    })
}
