//! Scenario campaigns: a scenario file (TOML) names a design, a motor, the launch site, the
//! rail, parachutes, shifts and integrator options, sweeps some inputs over a grid and
//! disperses some with distributions; the campaign flies every variant and writes the rows and
//! their statistics to Parquet.
//!
//! - [`scenario`]: the TOML format and its rules ([`params`]: the inputs it can sweep or
//!   disperse).
//! - [`sample`]: the distributions and the counter-based random streams (a variant's draws
//!   depend only on the seed and its id).
//! - [`variants`]: the sweep grid × variants per point, shards and chunks.
//! - [`fly`]: a chunk of variants turned into the batch engine's columns and flown as lanes
//!   of one base flight ([`fly::fly_chunk`]).
//! - [`stats`]: percentiles, landing ellipses, sensitivity (faer), the share of variants meeting
//!   each requirement (Wilson interval).
//! - [`gather`]: the statistics gathered as the rows pass, exact up to a stated size, then
//!   streamed ([`digest`]: the t-digest of streamed percentiles).
//! - [`parquet`]: the output files, written atomically and streamed by row groups; parts
//!   copied into one file undecoded.
//! - [`trajectories`]: the time series of a few variants per point, flown again alone.
//! - [`report`]: `report.html` and the landing maps, drawn from the files a run wrote.
//! - [`outdir`]: the output directory: one run per output set (a lock), temporary names of
//!   the run's own, a clean start without `--resume`.
//! - [`run`]: the loop (worker threads, parts, shards, resume, progress, timings) and [`cli`]:
//!   arguments, printed summary, `--timings`, exit codes.

pub mod cli;
pub mod digest;
pub mod fly;
pub mod gather;
pub mod outdir;
pub mod params;
pub mod parquet;
pub mod report;
pub mod run;
pub mod sample;
pub mod scenario;
pub mod stats;
pub mod trajectories;
pub mod variants;

pub use fly::{fly_chunk, Prepared, Status, VariantResult};
pub use run::{run_campaign, RunConfig, RunReport};
pub use scenario::{Scenario, ScenarioError};
pub use variants::{Plan, Shard, Variant};
