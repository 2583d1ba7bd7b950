//! The output directory of a run: who may write there, under which names, and what an
//! earlier run left there.
//!
//! A run writes one *output set*: `variants.parquet`, `summary.parquet`, `ellipses.parquet`,
//! `sensitivity.parquet`, `requirements.parquet` and, until the variants file is written,
//! its parts under `parts/variants/` (a shard K of N: the same names with `-shard-K-of-N`, so that the shards
//! of a run share a directory). This module owns the rules that keep two runs from mixing
//! their files:
//!
//! - **One writer per output set.** The run holds an exclusive advisory lock
//!   (`flock`, through `std::fs::File::try_lock`) on the set's lock file
//!   (`.hpr-mc-lock`, `.hpr-mc-lock-shard-K-of-N`) from before it touches anything until it
//!   ends. A second run into the same set is refused at once, naming the holder written in
//!   the lock file (process id, host, start time, seed, scenario). The kernel releases the
//!   lock when its holder ends, killed or not, so a dead run never blocks the next; the file
//!   itself stays (removing it would let two runs lock two different files). On a file
//!   system that does not lock files (ENOLCK, EOPNOTSUPP: some network ones) the run goes on
//!   unguarded, with a warning.
//! - **Temporary names of the run's own.** Every file is written as
//!   `NAME.<run id>.tmp` and renamed into place when complete (the run id is the process id
//!   and the start time in nanoseconds), so no two runs ever write the same temporary file.
//! - **A clean start.** A run without `--resume` removes the earlier results of its set (the
//!   five files and the parts) before it flies anything, so no finished file of another run
//!   sits beside its own; other sets (other shards) are left alone. Leftover temporary files
//!   of the set are removed by every run.
//! - **Parts of this run only.** Each part carries the run's identity (scenario fingerprint,
//!   seed, variants per point, points, shard, chunk size, rows per part; `hpr_mc.*`
//!   metadata), its number (`hpr_mc.part`) and the id of the run that wrote it
//!   (`hpr_mc.run_id`); before the parts are copied into the variants file, every part's
//!   identity, number, writer and row count is checked against what this run wrote or kept,
//!   and a kept part's variant ids as it is read back (see `run`).

use super::variants::Shard;
use anyhow::{bail, Context};
use std::fs::File;
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

/// The files of a run.
#[derive(Debug, Clone)]
pub struct Outputs {
    pub dir: PathBuf,
    pub variants: PathBuf,
    pub summary: PathBuf,
    pub ellipses: PathBuf,
    pub sensitivity: PathBuf,
    pub requirements: PathBuf,
    pub trajectories: PathBuf,
    /// The report (`report.html`, or `report-shard-K-of-N.html`) and the landing maps
    /// (`landing.kml`, `landing.geojson`, with the same suffix).
    pub report: PathBuf,
    pub kml: PathBuf,
    pub geojson: PathBuf,
    pub parts: PathBuf,
    /// The set's lock file.
    pub lock: PathBuf,
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
            trajectories: f("trajectories"),
            report: dir.join(format!("report{suffix}.html")),
            kml: dir.join(format!("landing{suffix}.kml")),
            geojson: dir.join(format!("landing{suffix}.geojson")),
            parts: dir.join("parts").join(format!("variants{suffix}")),
            lock: dir.join(format!(".hpr-mc-lock{suffix}")),
        }
    }

    /// The file of part `k` (a checkpoint of the variants' rows, see `run`).
    pub fn part(&self, k: usize) -> PathBuf {
        self.parts.join(format!("part-{k:06}.parquet"))
    }

    /// The set's finished files (not the parts).
    pub fn finished(&self) -> [&PathBuf; 9] {
        [
            &self.variants,
            &self.summary,
            &self.ellipses,
            &self.sensitivity,
            &self.requirements,
            &self.trajectories,
            &self.report,
            &self.kml,
            &self.geojson,
        ]
    }
}

/// Who holds an output set: written into its lock file, read by a run that is refused.
#[derive(Debug, Clone)]
pub struct Holder {
    pub scenario: String,
    pub seed: u64,
}

/// An output directory held by this run: its files, its lock (released when this is
/// dropped, or by the kernel when the process ends) and the run's id.
#[derive(Debug)]
pub struct OutputDir {
    pub outputs: Outputs,
    /// Unique to this run: the process id and the start time (ns since 1970), in hex.
    pub run_id: String,
    /// Held open: the lock lives as long as the file is open.
    _lock: File,
}

impl OutputDir {
    /// Take `dir` for `shard`'s output set: create the directory, lock the set (refused at
    /// once if another run holds it), record the holder, remove the set's leftover temporary
    /// files and, without `resume`, the earlier run's results.
    pub fn open(dir: &Path, shard: Shard, resume: bool, holder: &Holder) -> anyhow::Result<Self> {
        if dir.exists() && !dir.is_dir() {
            bail!(
                "{}: the output directory is a file, not a directory (give another with --out)",
                dir.display()
            );
        }
        std::fs::create_dir_all(dir).with_context(|| format!("can't create {}", dir.display()))?;
        let outputs = Outputs::new(dir, shard);
        let mut lock = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&outputs.lock)
            .with_context(|| format!("can't open the lock file {}", outputs.lock.display()))?;
        match lock.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                let mut who = String::new();
                let _ = lock.read_to_string(&mut who);
                let who = who.trim();
                let who = if who.is_empty() {
                    "a run that has not yet said who it is".to_string()
                } else {
                    who.to_string()
                };
                bail!(
                    "{}: another hpr-mc run is writing {} there ({who}); wait for it to end, or give another --out",
                    dir.display(),
                    set_name(shard)
                );
            }
            // A file system without locks (some network ones): the run goes on unguarded,
            // and says so.
            Err(std::fs::TryLockError::Error(e))
                if e.kind() == std::io::ErrorKind::Unsupported
                    || matches!(e.raw_os_error(), Some(37 | 95)) =>
            {
                eprintln!(
                    "warning: {}: the file system does not lock files ({e}): nothing keeps another run from writing here at the same time",
                    dir.display()
                );
            }
            Err(std::fs::TryLockError::Error(e)) => {
                return Err(e).with_context(|| format!("can't lock {}", outputs.lock.display()));
            }
        }
        let started = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .unwrap_or_default();
        let pid = std::process::id();
        let run_id = format!("{pid:x}-{:x}", started.as_nanos());
        let record = format!(
            "pid {pid} on {}, started {}, seed {}, scenario {}\n",
            host_name(),
            utc_text(started.as_secs()),
            holder.seed,
            holder.scenario
        );
        lock.set_len(0)
            .and_then(|_| lock.rewind())
            .and_then(|_| lock.write_all(record.as_bytes()))
            .and_then(|_| lock.flush())
            .with_context(|| format!("can't write {}", outputs.lock.display()))?;
        let out = OutputDir {
            outputs,
            run_id,
            _lock: lock,
        };
        out.remove_temporaries()?;
        if !resume {
            out.start_clean()?;
        }
        std::fs::create_dir_all(&out.outputs.parts)
            .with_context(|| format!("can't create {}", out.outputs.parts.display()))?;
        Ok(out)
    }

    /// The name `path` is written under until it is complete: `NAME.<run id>.tmp`.
    pub fn temporary(&self, path: &Path) -> PathBuf {
        temporary(path, &self.run_id)
    }

    /// Remove the set's temporary files (of any run: none other can be writing, the set is
    /// locked).
    fn remove_temporaries(&self) -> anyhow::Result<()> {
        let o = &self.outputs;
        let prefixes: Vec<String> = o
            .finished()
            .iter()
            .filter_map(|p| p.file_name()?.to_str().map(|n| format!("{n}.")))
            .collect();
        for entry in
            std::fs::read_dir(&o.dir).with_context(|| format!("can't read {}", o.dir.display()))?
        {
            let entry = entry?;
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.ends_with(".tmp") && prefixes.iter().any(|p| name.starts_with(p)) {
                let path = entry.path();
                std::fs::remove_file(&path)
                    .with_context(|| format!("can't remove {}", path.display()))?;
            }
        }
        Ok(())
    }

    /// Remove the earlier run's results of this set: its finished files and its parts.
    fn start_clean(&self) -> anyhow::Result<()> {
        let o = &self.outputs;
        for path in o.finished() {
            if path.is_dir() {
                bail!(
                    "{} is a directory where this run writes a file; remove it or give another --out",
                    path.display()
                );
            }
            match std::fs::remove_file(path) {
                Ok(()) => {}
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                Err(e) => {
                    return Err(e).with_context(|| {
                        format!("can't remove the earlier run's {}", path.display())
                    })
                }
            }
        }
        match std::fs::remove_dir_all(&o.parts) {
            Ok(()) => Ok(()),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
            Err(e) => Err(e)
                .with_context(|| format!("can't remove the earlier run's {}", o.parts.display())),
        }
    }
}

/// `NAME.<run id>.tmp` beside `path`.
pub fn temporary(path: &Path, run_id: &str) -> PathBuf {
    let mut name = path
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_default();
    name.push(format!(".{run_id}.tmp"));
    path.with_file_name(name)
}

/// How a refusal names the set: `its files` or `shard K of N's files`.
fn set_name(shard: Shard) -> String {
    if shard.is_all() {
        "this scenario's files".to_string()
    } else {
        format!("shard {}/{}'s files", shard.k, shard.n)
    }
}

/// The machine's name (Linux's, else `this machine`): runs on a cluster share directories.
fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "this machine".to_string())
}

/// `secs` since 1970 as UTC, `2026-12-04 09:30:00 UTC` (Howard Hinnant's `civil_from_days`).
pub fn utc_text(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_dates_match_known_instants() {
        assert_eq!(utc_text(0), "1970-01-01 00:00:00 UTC");
        // 2000-02-29 12:34:56 UTC (a leap day) and 2026-12-04 00:00:00 UTC.
        assert_eq!(utc_text(951_827_696), "2000-02-29 12:34:56 UTC");
        assert_eq!(utc_text(1_796_342_400), "2026-12-04 00:00:00 UTC");
    }

    #[test]
    fn a_second_run_into_a_locked_set_is_refused_naming_the_holder_and_another_set_is_not() {
        let dir = tempfile::tempdir().unwrap();
        let holder = Holder {
            scenario: "tiny".into(),
            seed: 7,
        };
        let first = OutputDir::open(dir.path(), Shard::ALL, false, &holder).unwrap();
        let e = OutputDir::open(dir.path(), Shard::ALL, false, &holder)
            .unwrap_err()
            .to_string();
        let pid = std::process::id();
        assert!(
            e.contains("another hpr-mc run is writing this scenario's files there (pid ")
                && e.contains(&format!("pid {pid} on "))
                && e.contains(", seed 7, scenario tiny")
                && e.contains("started 20"),
            "{e}"
        );
        // A shard's set is another lock: shards of one run share the directory.
        let shard = Shard { k: 1, n: 2 };
        let other = OutputDir::open(dir.path(), shard, false, &holder).unwrap();
        assert_ne!(other.run_id, first.run_id);
        drop(first);
        // Released with its holder: the next run takes it.
        OutputDir::open(dir.path(), Shard::ALL, false, &holder).unwrap();
    }

    #[test]
    fn a_fresh_start_removes_the_sets_earlier_results_and_leaves_other_sets_alone() {
        let dir = tempfile::tempdir().unwrap();
        let holder = Holder {
            scenario: "tiny".into(),
            seed: 1,
        };
        let mine = Outputs::new(dir.path(), Shard::ALL);
        let theirs = Outputs::new(dir.path(), Shard { k: 0, n: 2 });
        for o in [&mine, &theirs] {
            std::fs::create_dir_all(&o.parts).unwrap();
            std::fs::write(o.part(0), b"part").unwrap();
            for f in o.finished() {
                std::fs::write(f, b"old").unwrap();
            }
            std::fs::write(temporary(&o.variants, "dead-run"), b"half").unwrap();
        }
        let resumed = OutputDir::open(dir.path(), Shard::ALL, true, &holder).unwrap();
        // Resumed: the results stay, the temporary file of a dead run goes.
        assert!(mine.variants.is_file() && mine.part(0).is_file());
        assert!(!temporary(&mine.variants, "dead-run").exists());
        drop(resumed);
        let _fresh = OutputDir::open(dir.path(), Shard::ALL, false, &holder).unwrap();
        assert!(mine.finished().iter().all(|f| !f.exists()));
        assert!(!mine.part(0).exists() && mine.parts.is_dir());
        // The other shard's set is untouched, its temporary file too.
        assert!(theirs.finished().iter().all(|f| f.is_file()));
        assert!(theirs.part(0).is_file());
        assert!(temporary(&theirs.variants, "dead-run").is_file());
    }
}
