//! `trajectories.parquet`: the time series of the first `[outputs] trajectories` replicates
//! of every sweep point, in long format (one row per variant and integrator step), for the
//! report's bands of margin and height against time and for analysts.
//!
//! The run's lanes keep no samples, so these variants are flown again after the run as
//! lanes of a batch that keeps them ([`fly_chunk_with_samples`]): the same lanes, so each
//! series ends at the apogee and the landing its row in `variants.parquet` gives (and is
//! what `hpr-mc fly --variant` flies). A variant that is refused or fails has no rows.
//! Flights are flown a window at a time on the run's threads and written in id order, so
//! memory stays that of one window.

use super::fly::{fly_chunk_with_samples, sampling_batch, Prepared};
use super::parquet::{field, write_atomic_with};
use super::variants::{Shard, Variant};
use arrow::array::{ArrayRef, Float64Array, StringArray, UInt32Array, UInt64Array};
use arrow::datatypes::{DataType, Schema, SchemaRef};
use arrow::record_batch::RecordBatch;
use hpr_sim::flight::Sample;
use rayon::prelude::*;
use std::path::Path;
use std::sync::Arc;

/// The float columns after the ids and the phase, with their units.
pub const SERIES: [(&str, &str); 11] = [
    ("time_s", "s"),
    ("x_m", "m"),
    ("y_m", "m"),
    ("altitude_m", "m"),
    ("speed_m_s", "m/s"),
    ("mach", "1"),
    ("alpha_deg", "deg"),
    ("accel_m_s2", "m/s²"),
    ("static_margin_cal", "cal"),
    ("flight_margin_cal", "cal"),
    ("thrust_n", "N"),
];

fn values(s: &Sample) -> [f64; 11] {
    [
        s.t_s,
        s.position_m[0],
        s.position_m[1],
        s.altitude_m,
        s.speed_m_s,
        s.mach,
        s.alpha_deg,
        s.accel_m_s2,
        s.static_margin_cal,
        s.flight_margin_cal,
        s.thrust_n,
    ]
}

/// The schema of trajectories.parquet, with the run's metadata.
pub fn schema(pairs: &[(String, String)]) -> SchemaRef {
    let mut fields = vec![
        field("variant_id", DataType::UInt64, false, None),
        field("point", DataType::UInt32, false, None),
        field("replicate", DataType::UInt64, false, None),
        field("phase", DataType::Utf8, false, None),
    ];
    fields.extend(
        SERIES
            .iter()
            .map(|(n, u)| field(n, DataType::Float64, true, Some(u))),
    );
    Arc::new(Schema::new_with_metadata(
        fields,
        pairs.iter().cloned().collect(),
    ))
}

/// The ids whose series are written: replicates `0..min(per_point, variants per point)` of
/// every point, those of `shard` only, in id order.
pub fn chosen(p: &Prepared, shard: Shard, per_point: u64) -> Vec<u64> {
    let vpp = p.plan.variants_per_point;
    (0..p.plan.points() as u64)
        .flat_map(|pt| (0..per_point.min(vpp)).map(move |r| pt * vpp + r))
        .filter(|id| id % shard.n == shard.k)
        .collect()
}

/// One flight's rows (none if it has no samples: a variant refused, or a flight that failed).
fn rows(
    schema: &SchemaRef,
    v: &Variant,
    samples: &[Sample],
) -> anyhow::Result<Option<RecordBatch>> {
    if samples.is_empty() {
        return Ok(None);
    }
    let n = samples.len();
    let mut cols: Vec<ArrayRef> = vec![
        Arc::new(UInt64Array::from_value(v.id, n)),
        Arc::new(UInt32Array::from_value(v.point as u32, n)),
        Arc::new(UInt64Array::from_value(v.replicate, n)),
        Arc::new(StringArray::from_iter_values(
            samples.iter().map(|s| s.phase.name()),
        )),
    ];
    let table: Vec<[f64; 11]> = samples.iter().map(values).collect();
    for j in 0..SERIES.len() {
        cols.push(Arc::new(Float64Array::from_iter(
            table.iter().map(|r| Some(r[j]).filter(|x| x.is_finite())),
        )));
    }
    Ok(Some(RecordBatch::try_new(schema.clone(), cols)?))
}

/// Fly the chosen variants and write their series to `path` (atomically). Returns the number
/// of variants written. Call it inside the run's thread pool.
pub fn write(
    p: &Prepared,
    shard: Shard,
    path: &Path,
    tmp: &Path,
    pairs: &[(String, String)],
) -> anyhow::Result<u64> {
    let ids = chosen(p, shard, p.scenario.trajectories);
    let schema = schema(pairs);
    let mut written = 0;
    let floats: Vec<&str> = SERIES.iter().map(|c| c.0).collect();
    write_atomic_with(
        path,
        tmp,
        &schema,
        pairs,
        p.scenario.row_group_rows,
        &floats,
        |w| {
            // Windows of 64, each cut into a chunk per thread flown as lanes.
            let batch = sampling_batch(p);
            for window in ids.chunks(64) {
                let size = 8;
                let chunks: Vec<Vec<Option<RecordBatch>>> = window
                    .par_chunks(size)
                    .map(|chunk| {
                        let variants: Vec<Variant> =
                            chunk.iter().map(|&id| p.plan.variant(id)).collect();
                        fly_chunk_with_samples(p, &batch, &variants)
                            .iter()
                            .zip(&variants)
                            .map(|((_, samples), v)| rows(&schema, v, samples))
                            .collect::<anyhow::Result<Vec<_>>>()
                    })
                    .collect::<anyhow::Result<_>>()?;
                for b in chunks.into_iter().flatten().flatten() {
                    w.write(&b)?;
                    written += 1;
                }
            }
            Ok(())
        },
    )?;
    Ok(written)
}
