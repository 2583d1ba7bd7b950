//! Campaigns end to end on a tiny scenario (10 flights with loose tolerances): the Parquet
//! files read back with the parquet crate's Arrow reader, determinism whatever the threads and
//! shards, resumption of an interrupted run, and the exit codes of `hpr-mc`; winds scaled and
//! turned (`wind`), the site (`site`), canopy shapes (`canopy`), releases (`releases`) and
//! `fly --scenario` (`fly`) on a small windy scenario.

mod brakes;
mod canopy;
mod fly;
mod motor;
mod outputs;
mod releases;
mod report;
mod share;
mod site;
mod weather;
mod wind;

use arrow::array::{Array, BooleanArray, Float64Array, StringArray, UInt32Array, UInt64Array};
use arrow::compute::{concat_batches, sort_to_indices, take_record_batch};
use arrow::record_batch::RecordBatch;
use hpr_mc::campaign::sample::fingerprint;
use hpr_mc::campaign::{run_campaign, RunConfig, Shard};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::fs::File;
use std::path::{Path, PathBuf};

/// Two sweep points (ballast travel 0 and 0.25 m) × 5 variants, chunks of 4, row groups of
/// 7 rows, seed 2 (which gives 4 refused variants of 10). The main chute's lag is 1 s + U(−2.5, 0.5) s, negative (refused) 60 % of the time.
fn tiny(variants_per_point: u64) -> String {
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    format!(
        r#"
name = "tiny"
seed = 2
variants_per_point = {variants_per_point}
[design]
file = "{}"
ballast = "ballast"
[motor]
name = "Cesaroni_I175"
[environment]
wind_speed_m_s = 3.0
[[parachutes]]
name = "main"
cds_m2 = 0.9
lag_s = 1.0
trigger = "apogee"
[[shifts]]
component = "ballast"
travel_m = 0.2
duration_s = 1.0
trigger = {{ time_s = 5.0 }}
[integrator]
rtol = 1e-5
atol_position_m = 1e-2
atol_velocity_m_s = 1e-2
atol_quaternion = 1e-6
atol_rate_rad_s = 1e-3
max_time_s = 900.0
[run]
chunk_size = 4
row_group_rows = 7
[sweep]
shifts.ballast.travel_m = [0.0, 0.25]
[dispersions]
wind_speed_m_s = {{ dist = "truncated_normal", sigma = 1.0, min = -3.0 }}
drag_scale = {{ dist = "normal", sigma = 0.05, relative = true }}
parachutes.main.lag_s = {{ dist = "uniform", min = -2.5, max = 0.5 }}
"#,
        design.display()
    )
}

/// The error a run of the scenario `text` stops with (it must stop with one).
fn refusal(text: &str) -> String {
    let (dir, file) = setup(text);
    run_campaign(&file, &config(&dir.path().join("out")))
        .unwrap_err()
        .to_string()
}

/// A temporary directory holding `tiny.toml`.
fn setup(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("tiny.toml");
    std::fs::write(&file, text).unwrap();
    (dir, file)
}

fn config(out: &Path) -> RunConfig {
    RunConfig {
        out: Some(out.to_path_buf()),
        quiet: true,
        threads: Some(1),
        ..RunConfig::default()
    }
}

fn read(path: &Path) -> RecordBatch {
    let builder = ParquetRecordBatchReaderBuilder::try_new(File::open(path).unwrap()).unwrap();
    let schema = builder.schema().clone();
    let batches: Vec<RecordBatch> = builder.build().unwrap().map(|b| b.unwrap()).collect();
    concat_batches(&schema, &batches).unwrap()
}

fn f64s<'a>(b: &'a RecordBatch, name: &str) -> &'a Float64Array {
    b.column_by_name(name)
        .unwrap()
        .as_any()
        .downcast_ref::<Float64Array>()
        .unwrap()
}

fn u64s<'a>(b: &'a RecordBatch, name: &str) -> &'a UInt64Array {
    b.column_by_name(name)
        .unwrap_or_else(|| panic!("no column {name}"))
        .as_any()
        .downcast_ref::<UInt64Array>()
        .unwrap()
}

fn strings<'a>(b: &'a RecordBatch, name: &str) -> &'a StringArray {
    b.column_by_name(name)
        .unwrap()
        .as_any()
        .downcast_ref::<StringArray>()
        .unwrap()
}

#[test]
fn the_variants_file_reads_back_with_its_schema_units_nulls_metadata_and_values() {
    let text = tiny(5);
    let (dir, file) = setup(&text);
    let out = dir.path().join("out");
    let report = run_campaign(&file, &config(&out)).unwrap();
    assert!(report.complete);
    assert_eq!(report.variants, 10);
    assert!(
        report.refused > 0 && report.landed > 0,
        "the tiny scenario has refused and landed rows ({} refused)",
        report.refused
    );
    assert_eq!(report.landed + report.failures(), 10);

    let builder =
        ParquetRecordBatchReaderBuilder::try_new(File::open(&report.outputs.variants).unwrap())
            .unwrap();
    let meta = builder.metadata().clone();
    assert_eq!(meta.file_metadata().num_rows(), 10);
    assert_eq!(meta.num_row_groups(), 2, "row groups of 7 rows: 7 + 3");
    let kv: std::collections::HashMap<String, String> = meta
        .file_metadata()
        .key_value_metadata()
        .unwrap()
        .iter()
        .map(|k| (k.key.clone(), k.value.clone().unwrap_or_default()))
        .collect();
    assert_eq!(kv["hpr_mc.seed"], "2");
    assert_eq!(kv["hpr_mc.scenario"], text);
    assert_eq!(kv["hpr_mc.scenario_hash"], fingerprint(text.as_bytes()));
    assert_eq!(kv["hpr_mc.version"], env!("CARGO_PKG_VERSION"));

    let schema = builder.schema().clone();
    let names: Vec<&str> = schema.fields().iter().map(|f| f.name().as_str()).collect();
    let mut expected = vec![
        "variant_id",
        "point",
        "replicate",
        "sweep_shift_ballast_travel_m",
        "drag_scale",
        "wind_speed_m_s",
        "parachute_main_lag_s",
        "shift_ballast_travel_m",
        "status",
        "error",
        "warnings",
        "warning_unstable",
        "warning_large_alpha",
        "warning_ballistic",
    ];
    expected.extend(hpr_mc::campaign::fly::FIXED_METRICS.iter().map(|m| m.0));
    expected.extend([
        "shift_ballast_start_time_s",
        "shift_ballast_margin_before_cal",
        "shift_ballast_margin_after_cal",
        "parachute_main_deploy_time_s",
        "parachute_main_deploy_speed_m_s",
    ]);
    assert_eq!(names, expected);
    let unit = |n: &str| {
        schema
            .field_with_name(n)
            .unwrap()
            .metadata()
            .get("unit")
            .cloned()
    };
    assert_eq!(unit("apogee_m").as_deref(), Some("m"));
    assert_eq!(unit("wind_speed_m_s").as_deref(), Some("m/s"));
    assert_eq!(unit("sweep_shift_ballast_travel_m").as_deref(), Some("m"));
    assert_eq!(unit("max_mach").as_deref(), Some("1"));
    assert_eq!(unit("static_margin_min_cal").as_deref(), Some("cal"));
    assert_eq!(unit("status"), None);
    assert_eq!(unit("max_alpha_deg").as_deref(), Some("deg"));
    assert_eq!(
        unit("parachute_main_deploy_speed_m_s").as_deref(),
        Some("m/s")
    );

    let b = read(&report.outputs.variants);
    let ids = u64s(&b, "variant_id");
    assert_eq!(ids.values().to_vec(), (0..10).collect::<Vec<u64>>());
    let status = strings(&b, "status");
    let error = strings(&b, "error");
    let warnings = strings(&b, "warnings");
    let apogee = f64s(&b, "apogee_m");
    let lag = f64s(&b, "parachute_main_lag_s");
    for r in 0..10 {
        let landed = status.value(r) == "landed";
        assert_eq!(
            landed,
            lag.value(r) >= 0.0,
            "row {r}: refused exactly when the lag is negative"
        );
        assert_eq!(error.is_null(r), landed);
        for key in ["unstable", "large_alpha", "ballistic"] {
            // Flown: true or false; refused: null.
            let flag = bools(&b, &format!("warning_{key}"));
            assert_eq!(flag.is_null(r), !landed, "row {r} warning_{key}");
            assert!(!landed || !flag.value(r), "row {r} warning_{key}");
        }
        for m in hpr_mc::campaign::fly::FIXED_METRICS {
            assert_eq!(f64s(&b, m.0).is_null(r), !landed, "row {r} column {}", m.0);
        }
        if !landed {
            assert!(
                error.value(r).contains("parachutes.main.lag_s"),
                "{}",
                error.value(r)
            );
        } else {
            assert!(apogee.value(r) > 1000.0);
            // A stable rocket under its main: nothing to warn of. The main opens one lag
            // after the apogee, at the speed of a short fall.
            assert!(warnings.is_null(r), "row {r}: {}", warnings.value(r));
            let opened = f64s(&b, "parachute_main_deploy_time_s").value(r);
            let apogee_time = f64s(&b, "apogee_time_s").value(r);
            assert!(
                (opened - (apogee_time + lag.value(r))).abs() < 1e-9,
                "row {r}: opened at {opened} s, apogee at {apogee_time} s, lag {} s",
                lag.value(r)
            );
            let speed = f64s(&b, "parachute_main_deploy_speed_m_s").value(r);
            assert!(
                speed > 0.0 && speed < 9.81 * lag.value(r) + 5.0,
                "row {r}: {speed}"
            );
        }
        // Every input's value is the plan's draw for this variant.
        let v = report.prepared.plan.variant(r as u64);
        for (j, input) in report.prepared.scenario.inputs.iter().enumerate() {
            assert_eq!(f64s(&b, &input.column).value(r), v.values[j]);
        }
        assert_eq!(
            f64s(&b, "sweep_shift_ballast_travel_m").value(r),
            if r < 5 { 0.0 } else { 0.25 }
        );
    }
    // The shift's margin falls by m Δ / (M d) when the ballast moves 0.25 m: at least 1 cal
    // for 200 g in a 0.8 kg, 56.3 mm rocket (`docs/moving-mass.md`'s worked example: 1.302 cal
    // for 0.3 m).
    let (before, after) = (
        f64s(&b, "shift_ballast_margin_before_cal"),
        f64s(&b, "shift_ballast_margin_after_cal"),
    );
    for r in 5..10 {
        if status.value(r) == "landed" {
            assert!(
                before.value(r) - after.value(r) > 1.0,
                "row {r}: {} → {}",
                before.value(r),
                after.value(r)
            );
        }
    }
}

#[test]
fn the_summary_s_means_are_the_means_of_the_landed_rows() {
    let (dir, file) = setup(&tiny(5));
    let out = dir.path().join("out");
    let report = run_campaign(&file, &config(&out)).unwrap();
    let v = read(&report.outputs.variants);
    let s = read(&report.outputs.summary);
    let point = v
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt32Array>()
        .unwrap();
    let status = strings(&v, "status");
    let apogee = f64s(&v, "apogee_m");
    let spoint = s
        .column_by_name("point")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt32Array>()
        .unwrap();
    let metric = strings(&s, "metric");
    let mean = f64s(&s, "mean");
    for p in 0..2u32 {
        let landed: Vec<f64> = (0..v.num_rows())
            .filter(|&r| point.value(r) == p && status.value(r) == "landed")
            .map(|r| apogee.value(r))
            .collect();
        let expected = landed.iter().sum::<f64>() / landed.len() as f64;
        let row = (0..s.num_rows())
            .find(|&r| spoint.value(r) == p && metric.value(r) == "apogee_m")
            .unwrap();
        assert!(
            (mean.value(row) - expected).abs() <= 1e-12 * expected.abs(),
            "point {p}: {} vs {expected}",
            mean.value(row)
        );
    }
    // Requirements: none in this scenario, so the file holds no rows.
    assert_eq!(read(&report.outputs.requirements).num_rows(), 0);
    // Ellipses at 1, 2 and 3 sigma for each point.
    let e = read(&report.outputs.ellipses);
    assert_eq!(e.num_rows(), 6);
    let major = f64s(&e, "semi_major_m");
    assert!((major.value(1) - 2.0 * major.value(0)).abs() < 1e-9 * major.value(0));
}

/// The rows of a variants file (all columns), whatever the schema's metadata.
fn bools<'a>(b: &'a RecordBatch, name: &str) -> &'a BooleanArray {
    b.column_by_name(name)
        .unwrap_or_else(|| panic!("no column {name}"))
        .as_any()
        .downcast_ref::<BooleanArray>()
        .unwrap_or_else(|| panic!("{name} is not true/false"))
}

fn columns(b: &RecordBatch) -> Vec<std::sync::Arc<dyn Array>> {
    b.columns().to_vec()
}

#[test]
fn a_shard_without_variants_writes_an_empty_variants_file() {
    // 10 variants in 16 shards: shard 12 has none.
    let (dir, file) = setup(&tiny(5));
    let r = run_campaign(
        &file,
        &RunConfig {
            shard: Some(Shard { k: 12, n: 16 }),
            no_report: true,
            ..config(&dir.path().join("out"))
        },
    )
    .unwrap();
    assert!(r.complete);
    assert_eq!((r.variants, r.parts, r.landed), (0, 0, 0));
    assert_eq!(read(&r.outputs.variants).num_rows(), 0);
}

#[test]
fn the_thread_count_changes_no_byte_of_the_files_and_the_chunk_size_no_number() {
    // 10 variants in parts of 4, chunks of 4 (tiny's) or of 1, on 1, 2 or 3 threads.
    let (dir, file) = setup(&tiny(5));
    let run = |file: &Path, threads: usize, name: &str| {
        run_campaign(
            file,
            &RunConfig {
                threads: Some(threads),
                part_rows: Some(4),
                ..config(&dir.path().join(name))
            },
        )
        .unwrap()
    };
    let one = run(&file, 1, "one");
    let three = run(&file, 3, "three");
    for (a, b) in one
        .outputs
        .finished()
        .iter()
        .zip(three.outputs.finished())
        .filter(|(a, _)| a.extension().is_some_and(|e| e == "parquet"))
    {
        assert!(
            std::fs::read(a).unwrap() == std::fs::read(b).unwrap(),
            "{} differs between 1 and 3 threads",
            a.file_name().unwrap().to_string_lossy()
        );
    }
    // Chunks of 1 (another scenario text: its metadata differs, not its numbers).
    let ones = dir.path().join("chunks-of-1.toml");
    std::fs::write(&ones, tiny(5).replace("chunk_size = 4", "chunk_size = 1")).unwrap();
    let small = run(&ones, 2, "small");
    for (a, b) in [
        (&one.outputs.variants, &small.outputs.variants),
        (&one.outputs.summary, &small.outputs.summary),
        (&one.outputs.sensitivity, &small.outputs.sensitivity),
    ] {
        assert_eq!(columns(&read(a)), columns(&read(b)), "{}", a.display());
    }
}

#[test]
fn one_thread_or_two_give_the_same_rows_and_the_shards_together_are_the_whole_run() {
    let (dir, file) = setup(&tiny(5));
    let whole = run_campaign(&file, &config(&dir.path().join("one"))).unwrap();
    let two = run_campaign(
        &file,
        &RunConfig {
            threads: Some(2),
            ..config(&dir.path().join("two"))
        },
    )
    .unwrap();
    let a = read(&whole.outputs.variants);
    assert_eq!(columns(&a), columns(&read(&two.outputs.variants)));

    let shards: Vec<RecordBatch> = (0..3)
        .map(|k| {
            let r = run_campaign(
                &file,
                &RunConfig {
                    shard: Some(Shard { k, n: 3 }),
                    ..config(&dir.path().join("sharded"))
                },
            )
            .unwrap();
            assert!(r
                .outputs
                .variants
                .ends_with(format!("variants-shard-{k}-of-3.parquet")));
            read(&r.outputs.variants)
        })
        .collect();
    assert_eq!(
        shards.iter().map(|b| b.num_rows()).collect::<Vec<_>>(),
        vec![4, 3, 3]
    );
    let union = concat_batches(&shards[0].schema(), &shards).unwrap();
    let order = sort_to_indices(union.column_by_name("variant_id").unwrap(), None, None).unwrap();
    let union = take_record_batch(&union, &order).unwrap();
    assert_eq!(columns(&union), columns(&a));
}

#[test]
fn an_interrupted_run_resumes_flying_only_the_missing_parts_to_the_same_bytes() {
    let (dir, file) = setup(&tiny(5));
    // Parts of 4 rows: 10 variants in 3 parts.
    let parts_of_4 = |out: &Path| RunConfig {
        part_rows: Some(4),
        ..config(out)
    };
    let reference = run_campaign(&file, &parts_of_4(&dir.path().join("reference"))).unwrap();
    assert_eq!((reference.parts, reference.parts_flown), (3, 3));
    let out = dir.path().join("out");
    // Write one part of three, then stop as Ctrl-C would; leave a half-written part too.
    let first = run_campaign(
        &file,
        &RunConfig {
            max_parts: Some(1),
            ..parts_of_4(&out)
        },
    )
    .unwrap();
    assert!(!first.complete);
    assert_eq!(first.parts_flown, 1);
    assert!(
        !first.outputs.variants.exists(),
        "no variants file before every part is done"
    );
    let parts = out.join("parts/variants");
    std::fs::write(parts.join("part-000002.parquet.tmp"), b"half a file").unwrap();
    let done: Vec<String> = std::fs::read_dir(&parts)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert!(
        done.contains(&"part-000000.parquet".to_string()),
        "{done:?}"
    );

    // A resume with another seed refuses the parts, and so does one cut into other parts.
    let e = run_campaign(
        &file,
        &RunConfig {
            resume: true,
            seed: Some(3),
            ..parts_of_4(&out)
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("hpr_mc.seed"), "{e}");
    let e = run_campaign(
        &file,
        &RunConfig {
            resume: true,
            part_rows: Some(5),
            ..config(&out)
        },
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("(its hpr_mc.part_rows is 4, this run's is 5)"),
        "{e}"
    );

    let second = run_campaign(
        &file,
        &RunConfig {
            resume: true,
            ..parts_of_4(&out)
        },
    )
    .unwrap();
    assert!(second.complete);
    assert_eq!((second.parts_kept, second.parts_flown), (1, 2));
    // Every file the uninterrupted run wrote, byte for byte (the report too, but for the
    // time it names).
    for (a, b) in second
        .outputs
        .finished()
        .iter()
        .zip(reference.outputs.finished())
        .filter(|(a, _)| a.extension().is_some_and(|e| e == "parquet"))
    {
        assert!(
            std::fs::read(a).unwrap() == std::fs::read(b).unwrap(),
            "{} differs from the uninterrupted run's",
            a.display()
        );
    }
    assert!(
        !out.join("parts").exists(),
        "the parts are removed once copied"
    );

    // Resuming a finished run flies nothing and writes the same summary.
    let third = run_campaign(
        &file,
        &RunConfig {
            resume: true,
            ..parts_of_4(&out)
        },
    )
    .unwrap();
    assert_eq!((third.parts_kept, third.parts_flown), (0, 0));
    assert_eq!(
        std::fs::read(&third.outputs.summary).unwrap(),
        std::fs::read(&reference.outputs.summary).unwrap()
    );
}

fn hpr_mc(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

#[test]
fn the_exit_code_says_whether_every_variant_landed_or_the_input_was_bad() {
    let text = tiny(5);
    let (dir, file) = setup(&text);
    let out = dir.path().join("out");
    let (code, stdout, stderr) = hpr_mc(&[
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("did not land"), "{stderr}");
    // The table's row of point 1 gives its travel.
    assert!(
        stdout
            .lines()
            .any(|l| l.split_whitespace().take(2).eq(["1", "0.25"])),
        "{stdout}"
    );

    std::fs::write(&file, calm_text(&text)).unwrap();
    let (code, _, stderr) = hpr_mc(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--variants",
        "2",
        "--threads",
        "2",
    ]);
    assert_eq!(code, 0, "{stderr}");

    std::fs::write(&file, text.replace("sigma = 1.0, min", "sigma = -1.0, min")).unwrap();
    let (code, _, stderr) = hpr_mc(&[file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("dispersions.wind_speed_m_s.sigma: must be positive"),
        "{stderr}"
    );
    let (code, _, stderr) = hpr_mc(&[file.to_str().unwrap(), "--shard", "3/3"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("0 <= K < N"), "{stderr}");
}

/// [`tiny`]'s scenario without the lag dispersion that leaves some mains unopened: every
/// variant lands.
fn calm_text(text: &str) -> String {
    text.replace(
        "parachutes.main.lag_s = { dist = \"uniform\", min = -2.5, max = 0.5 }",
        "",
    )
}

#[test]
fn every_bundled_scenario_reads_and_sets_up_at_every_sweep_point() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let mut names = vec![];
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) == Some("toml") {
            let p = hpr_mc::campaign::run::prepare(&path, &RunConfig::default())
                .unwrap_or_else(|e| panic!("{}: {e:#}", path.display()));
            names.push(p.scenario.name.clone());
        }
    }
    names.sort();
    assert_eq!(
        names,
        vec![
            "ballast_sweep",
            "bella_lui",
            "calisto",
            "fin_sizing",
            "payload_drop",
            "sounding",
            "wind_study"
        ]
    );
}

#[test]
fn a_campaign_without_parachutes_marks_every_landing_ballistic_and_counts_it() {
    // The tiny scenario with its parachute (and the lag's dispersion) taken out.
    let text = tiny(3)
        .replace(
            "[[parachutes]]\nname = \"main\"\ncds_m2 = 0.9\nlag_s = 1.0\ntrigger = \"apogee\"\n",
            "",
        )
        .replace(
            "parachutes.main.lag_s = { dist = \"uniform\", min = -2.5, max = 0.5 }\n",
            "",
        );
    assert!(!text.contains("parachute"), "{text}");
    let (dir, file) = setup(&text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    assert_eq!(report.landed, 6, "no lag to refuse: every variant lands");
    assert_eq!(report.warned, vec![("ballistic".to_string(), 6)]);
    let b = read(&report.outputs.variants);
    let (warnings, speed) = (strings(&b, "warnings"), f64s(&b, "landing_speed_m_s"));
    for r in 0..6 {
        // The text carries the row's own landing speed, as printed to 0.1 m/s.
        assert_eq!(
            warnings.value(r),
            format!(
                "ballistic: landed at {:.1} m/s with no parachute open",
                speed.value(r)
            )
        );
        assert!(speed.value(r) > 50.0, "row {r}: {}", speed.value(r));
        // ... and its flag, beside the two it did not raise.
        assert!(bools(&b, "warning_ballistic").value(r));
        assert!(!bools(&b, "warning_unstable").value(r));
        assert!(!bools(&b, "warning_large_alpha").value(r));
    }
}

/// Runs the campaign `text` (every variant must land) and gives each row's values of the
/// Float64 columns `names`, in that order.
fn landed_rows<const N: usize>(text: &str, names: [&str; N]) -> Vec<[f64; N]> {
    let (dir, file) = setup(text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    assert_eq!(report.landed, report.variants, "every variant lands");
    let b = read(&report.outputs.variants);
    let cols = names.map(|n| f64s(&b, n).values().to_vec());
    (0..b.num_rows())
        .map(|r| std::array::from_fn(|k| cols[k][r]))
        .collect()
}

/// The reference design under its main, 4 variants scattered only in drag, with the given
/// `[environment]` wind lines and `[sweep]` lines.
fn windy(environment: &str, sweep: &str) -> String {
    let design = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    format!(
        r#"
name = "windy"
seed = 3
variants_per_point = 4
[design]
file = "{}"
[motor]
name = "Cesaroni_I175"
[environment]
{environment}
[rail]
inclination_deg = 85.0
[[parachutes]]
name = "main"
cds_m2 = 0.9
lag_s = 1.0
trigger = "apogee"
[integrator]
max_time_s = 900.0
[sweep]
{sweep}
[dispersions]
drag_scale = {{ dist = "normal", sigma = 0.05, relative = true }}
"#,
        design.display()
    )
}

/// Every row's drag scale, apogee and landing point, of a [`windy`] campaign.
fn drag_apogee_landing(text: &str) -> Vec<[f64; 4]> {
    landed_rows(
        text,
        ["drag_scale", "apogee_m", "landing_x_m", "landing_y_m"],
    )
}

/// Each row of a [`windy`] campaign ([`drag_apogee_landing`]) is the flight set up by hand as
/// `Simulation` (its rail, its integrator's time limit) with `env`, `chute` and the row's
/// drag scale: equal to rounding (the drag scale is read back from its column exactly).
fn assert_rows_flown_by_hand(
    campaign: &[[f64; 4]],
    env: &hpr_sim::Environment,
    chute: &hpr_sim::Parachute,
) {
    let envs = vec![env.clone(); campaign.len()];
    assert_rows_flown_by_hand_in(campaign, &envs, chute);
}

/// [`assert_rows_flown_by_hand`], each row in its own environment.
fn assert_rows_flown_by_hand_in(
    campaign: &[[f64; 4]],
    envs: &[hpr_sim::Environment],
    chute: &hpr_sim::Parachute,
) {
    let design = hpr_design::Design::load(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("validation/designs/synthetic-54mm-three-fin.json"),
    )
    .unwrap();
    let rail = hpr_sim::Rail {
        inclination_deg: 85.0,
        ..hpr_sim::Rail::default()
    };
    for (row, env) in campaign.iter().zip(envs) {
        let f = hpr_sim::Simulation::new(
            design.clone(),
            hpr_design::motor::find("Cesaroni_I175").unwrap(),
            env.clone(),
            rail,
        )
        .and_then(|s| s.with_parachutes(vec![chute.clone()]))
        .and_then(|s| s.with_drag_scale(row[0]))
        .and_then(|s| {
            s.with_options(hpr_sim::SimOptions {
                max_time_s: 900.0,
                ..hpr_sim::SimOptions::default()
            })
        })
        .unwrap()
        .run(&mut ())
        .unwrap();
        let [x, y] = f.metrics.landing_position_m.unwrap();
        let by_hand = [row[0], f.metrics.apogee_m.unwrap(), x, y];
        for k in 1..4 {
            assert!(
                (row[k] - by_hand[k]).abs() <= 1e-9 * by_hand[k].abs().max(1.0),
                "figure {k}: campaign {} against by hand {}",
                row[k],
                by_hand[k]
            );
        }
    }
}

#[test]
fn each_requirement_s_count_is_the_rows_that_meet_it_whatever_their_status() {
    // tiny(5) refuses some variants (a negative lag): they have no apogee and do not meet
    // the apogee requirement; the margin's requirement sits between the two points' values.
    let text = format!(
        "{}[requirements]\napogee_m = {{ min = 100.0 }}\nshift_ballast_margin_after_cal = {{ min = 1.0, max = 50.0 }}\n",
        tiny(5)
    );
    let (dir, file) = setup(&text);
    let report = run_campaign(&file, &config(&dir.path().join("out"))).unwrap();
    let v = read(&report.outputs.variants);
    let r = read(&report.outputs.requirements);
    assert_eq!(r.num_rows(), 4, "two points × two requirements");
    let point = |b: &RecordBatch| {
        b.column_by_name("point")
            .unwrap()
            .as_any()
            .downcast_ref::<UInt32Array>()
            .unwrap()
            .clone()
    };
    let (vp, rp) = (point(&v), point(&r));
    let (met, variants) = (u64s(&r, "met").clone(), u64s(&r, "variants").clone());
    let (metric, fraction) = (strings(&r, "metric"), f64s(&r, "fraction"));
    let (min, max) = (f64s(&r, "min"), f64s(&r, "max"));
    let mut refused_seen = false;
    for k in 0..r.num_rows() {
        let col = f64s(&v, metric.value(k));
        let rows: Vec<usize> = (0..v.num_rows())
            .filter(|&i| vp.value(i) == rp.value(k))
            .collect();
        let meets = |i: usize| {
            col.is_valid(i)
                && (min.is_null(k) || col.value(i) >= min.value(k))
                && (max.is_null(k) || col.value(i) <= max.value(k))
        };
        let want = rows.iter().filter(|&&i| meets(i)).count() as u64;
        assert_eq!(
            (met.value(k), variants.value(k)),
            (want, rows.len() as u64),
            "row {k}"
        );
        assert_eq!(fraction.value(k), want as f64 / rows.len() as f64);
        refused_seen |= rows.iter().any(|&i| !col.is_valid(i));
    }
    assert!(
        refused_seen,
        "some variant without a value, counted as not meeting"
    );
    assert!(!min.is_null(0) && max.is_null(0), "apogee_m has a min only");
}

#[test]
fn timings_name_every_phase_and_their_seconds_add_up_to_the_run() {
    let (dir, file) = setup(&tiny(5));
    let out = dir.path().join("out");
    let (code, stdout, stderr) = hpr_mc(&[
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--timings",
    ]);
    assert!(code <= 1, "{stderr}");
    let seconds = |name: &str| -> f64 {
        let line = stdout
            .lines()
            .find(|l| l.trim_start().starts_with(name))
            .unwrap_or_else(|| panic!("no line {name}: {stdout}"));
        line[name.len() + line.find(name).unwrap()..]
            .split_whitespace()
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    let total: f64 = stdout
        .lines()
        .find_map(|l| l.split("share of the run's ").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    let top = [
        "scenario and tables",
        "flying the variants",
        "variants file (parts copied)",
        "statistics and trajectories",
        "report and maps",
        "other",
    ];
    let sum: f64 = top.iter().map(|n| seconds(n)).sum();
    // Each printed to the millisecond: six roundings of at most 0.5 ms.
    assert!(
        (sum - total).abs() <= 0.0031,
        "{sum} against {total}: {stdout}"
    );
    for name in [
        "sampling",
        "flights",
        "rows (Arrow)",
        "Parquet parts",
        "statistics gathered",
        "waiting for flights",
    ] {
        assert!(seconds(name) >= 0.0, "{name}");
    }
    assert!(seconds("flights") > 0.0, "{stdout}");
    // The statistics and the trajectories go side by side: each within their phase's wall.
    for name in ["statistics and their files", "trajectories"] {
        assert!(
            seconds(name) <= seconds("statistics and trajectories") + 0.001,
            "{name}: {stdout}"
        );
    }
    assert!(stdout.contains("10 flights in "), "{stdout}");
}
