//! The rows a scenario gives do not change when the code that carries its inputs does: each
//! bundled scenario (a few variants per point) and two scenarios that sweep or disperse every
//! other input (`tests/rows_before/*.toml`) are run, and their `variants.parquet` is compared
//! column by column, bit for bit, with the file the same run wrote before the inputs became
//! one list (`tests/rows_before/<name>.parquet`, written by the build of 2026-12-05, commit
//! bef8a11, descents by RODAS4, with `hpr-mc SCENARIO --variants N --no-report --threads 2`;
//! the same files from the build of 2026-12-04, commit cf5616f, before the descents' method
//! changed, differ only in the columns the descent sets, by at most 0.35 m and 0.11 s where a
//! noisy barometer's main fires some samples apart, and 2 mm elsewhere).

use arrow::array::{Array, Float64Array};
use arrow::compute::concat_batches;
use arrow::record_batch::RecordBatch;
use hpr_mc::campaign::{run_campaign, RunConfig};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::fs::File;
use std::path::{Path, PathBuf};

fn read(path: &Path) -> RecordBatch {
    let builder = ParquetRecordBatchReaderBuilder::try_new(File::open(path).unwrap()).unwrap();
    let schema = builder.schema().clone();
    let batches: Vec<RecordBatch> = builder.build().unwrap().map(|b| b.unwrap()).collect();
    concat_batches(&schema, &batches).unwrap()
}

/// Every double column of the variants file is written without a dictionary, its bytes split
/// into streams (BYTE_STREAM_SPLIT): the encoding the stored files, written with dictionaries,
/// did not have, so the comparison below also shows the values survive it bit for bit.
fn doubles_are_split_into_byte_streams(path: &Path, name: &str) {
    use parquet::basic::{Encoding, Type};
    use parquet::file::reader::{FileReader, SerializedFileReader};
    let reader = SerializedFileReader::new(File::open(path).unwrap()).unwrap();
    let meta = reader.metadata();
    let mut doubles = 0;
    for rg in meta.row_groups() {
        for c in rg.columns() {
            if c.column_type() != Type::DOUBLE {
                continue;
            }
            doubles += 1;
            let encodings: Vec<Encoding> = c.encodings().collect();
            assert!(
                encodings.contains(&Encoding::BYTE_STREAM_SPLIT)
                    && !encodings.contains(&Encoding::RLE_DICTIONARY)
                    && c.dictionary_page_offset().is_none(),
                "{name}: column {} is encoded {encodings:?}",
                c.column_path()
            );
        }
    }
    assert!(doubles > 0, "{name}: no double column");
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Run `scenario` (with `variants` per point, if given) and compare its rows with the stored
/// file `tests/rows_before/<name>.parquet`: the same columns, in the same order, with the same
/// units, and every value the same (floats by their bits, nulls where they were).
fn same_rows_as_before(scenario: &Path, name: &str, variants: Option<u64>) {
    let dir = tempfile::tempdir().unwrap();
    let config = RunConfig {
        out: Some(dir.path().join(name)),
        quiet: true,
        no_report: true,
        variants_per_point: variants,
        threads: Some(2),
        ..RunConfig::default()
    };
    let report = run_campaign(scenario, &config).unwrap();
    doubles_are_split_into_byte_streams(&report.outputs.variants, name);
    let now = read(&report.outputs.variants);
    let before = read(&root().join(format!("tests/rows_before/{name}.parquet")));
    let names = |b: &RecordBatch| -> Vec<(String, Option<String>)> {
        b.schema()
            .fields()
            .iter()
            .map(|f| (f.name().clone(), f.metadata().get("unit").cloned()))
            .collect()
    };
    assert_eq!(
        names(&now),
        names(&before),
        "{name}: the columns and their units"
    );
    assert_eq!(now.num_rows(), before.num_rows(), "{name}: the rows");
    for (k, field) in before.schema().fields().iter().enumerate() {
        let (a, b) = (now.column(k), before.column(k));
        if let (Some(a), Some(b)) = (
            a.as_any().downcast_ref::<Float64Array>(),
            b.as_any().downcast_ref::<Float64Array>(),
        ) {
            for row in 0..a.len() {
                let value = |c: &Float64Array| (!c.is_null(row)).then(|| c.value(row).to_bits());
                assert_eq!(
                    value(a),
                    value(b),
                    "{name}: column {} row {row}: {:?} now, {:?} before",
                    field.name(),
                    (!a.is_null(row)).then(|| a.value(row)),
                    (!b.is_null(row)).then(|| b.value(row)),
                );
            }
        } else {
            assert_eq!(a.to_data(), b.to_data(), "{name}: column {}", field.name());
        }
    }
}

#[test]
fn the_bundled_scenarios_give_the_rows_they_gave_before() {
    for name in [
        "ballast_sweep",
        "bella_lui",
        "calisto",
        "payload_drop",
        "sounding",
        "wind_study",
    ] {
        let scenario = root().join(format!("scenarios/{name}.toml"));
        same_rows_as_before(&scenario, name, Some(3));
    }
}

#[test]
fn a_scenario_that_varies_every_input_gives_the_rows_it_gave_before() {
    for name in ["every_input", "wind_profile"] {
        let scenario = root().join(format!("tests/rows_before/{name}.toml"));
        same_rows_as_before(&scenario, name, None);
    }
}

#[test]
fn sweeps_whose_points_share_their_beginnings_give_the_rows_of_flights_flown_whole() {
    // 40 variants a point: each point's chunks come after its first point's, so most
    // flights begin where that point's flight of their replicate left off (on two threads;
    // which ones depends on the threads' timing, the rows never). Stored by the build
    // before the sharing.
    for scenario in ["ballast_sweep", "fin_sizing"] {
        let path = root().join(format!("scenarios/{scenario}.toml"));
        same_rows_as_before(&path, &format!("{scenario}_40"), Some(40));
    }
}
