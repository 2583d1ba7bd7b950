//! Where a run's files go when the place for them is wrong: refused by name before anything
//! is flown, and never a temporary file left behind.

use super::*;

/// `hpr-mc FILE --out OUT --quiet`: its exit code and standard error.
fn run_into(file: &Path, out: &Path) -> (i32, String) {
    let (code, _, stderr) = hpr_mc(&[
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    (code, stderr)
}

#[test]
fn an_output_directory_that_is_a_file_is_refused_by_name_before_anything_is_flown() {
    let (dir, file) = setup(&calm_text(&tiny(2)));
    let not_a_dir = dir.path().join("a_file");
    std::fs::write(&not_a_dir, "x").unwrap();
    let (code, stderr) = run_into(&file, &not_a_dir);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("a_file: the output directory is a file, not a directory"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(&not_a_dir).unwrap(), "x");
}

#[test]
fn an_output_that_cannot_be_put_in_place_leaves_no_temporary_file_behind() {
    let (dir, file) = setup(&calm_text(&tiny(2)));
    let out = dir.path().join("out");
    // A directory where the summary should go: the rename of its temporary file fails.
    std::fs::create_dir_all(out.join("summary.parquet")).unwrap();
    let (code, stderr) = run_into(&file, &out);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("summary.parquet"), "{stderr}");
    let leftovers: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// The seed in a Parquet file's metadata.
fn seed_of(path: &Path) -> String {
    hpr_mc::campaign::parquet::read_pairs(path).unwrap()["hpr_mc.seed"].clone()
}

#[test]
fn a_run_into_a_directory_another_run_holds_is_refused_at_once_naming_the_holder() {
    let (dir, file) = setup(&calm_text(&tiny(2)));
    let out = dir.path().join("out");
    let holder = hpr_mc::campaign::outdir::Holder {
        scenario: "held.toml".into(),
        seed: 99,
    };
    let held = hpr_mc::campaign::outdir::OutputDir::open(&out, Shard::ALL, false, &holder).unwrap();
    let (code, stderr) = run_into(&file, &out);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("another hpr-mc run is writing this scenario's files there (pid ")
            && stderr.contains(&format!("pid {} on ", std::process::id()))
            && stderr.contains("seed 99, scenario held.toml")
            && stderr.contains("wait for it to end, or give another --out"),
        "{stderr}"
    );
    assert!(
        !held.outputs.variants.exists(),
        "the refused run wrote nothing"
    );
    // Another shard's files are another lock: that run goes ahead beside the holder.
    let (code, _, stderr) = hpr_mc(&[
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--shard",
        "0/2",
    ]);
    assert_eq!(code, 0, "{stderr}");
    drop(held);
    // Its holder gone (a killed run's lock goes with it), the directory is free.
    let (code, stderr) = run_into(&file, &out);
    assert_eq!(code, 0, "{stderr}");
}

#[test]
fn a_fresh_run_removes_the_earlier_run_s_results_before_its_own_appear() {
    let (dir, file) = setup(&tiny(5));
    let out = dir.path().join("out");
    let earlier = run_campaign(
        &file,
        &RunConfig {
            seed: Some(7),
            ..config(&out)
        },
    )
    .unwrap();
    assert_eq!(seed_of(&earlier.outputs.variants), "7");
    // A run with another seed stopped after its first part, as a kill leaves it: no file
    // of the seed-7 run may remain beside its parts.
    let stopped = run_campaign(
        &file,
        &RunConfig {
            max_parts: Some(1),
            part_rows: Some(4),
            ..config(&out)
        },
    )
    .unwrap();
    assert!(!stopped.complete);
    let left: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".parquet"))
        .collect();
    assert!(left.is_empty(), "the earlier run's files remain: {left:?}");
    // Resumed, it finishes with its own seed in every file.
    let done = run_campaign(
        &file,
        &RunConfig {
            resume: true,
            part_rows: Some(4),
            ..config(&out)
        },
    )
    .unwrap();
    // Every Parquet file carries the seed (the report and the maps are drawn from them).
    let parquet = |f: &&&PathBuf| f.extension().is_some_and(|e| e == "parquet");
    for f in done.outputs.finished().iter().filter(parquet) {
        assert_eq!(seed_of(f), "2", "{}", f.display());
    }
}

/// Runs `hpr-mc` on `file` into `out` with `extra` arguments, in the background.
fn spawn_run(file: &Path, out: &Path, extra: &[&str]) -> std::process::Child {
    std::process::Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
        .arg(file)
        .args(["--out", out.to_str().unwrap(), "--quiet", "--threads", "1"])
        .args(extra)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap()
}

#[test]
fn two_runs_started_together_on_one_directory_give_one_refusal_or_two_whole_runs_never_a_mix() {
    // 40 flights each, in 10 chunks; the runs start together, with the same seed or not.
    let (dir, file) = setup(&tiny(20));
    let reference = |seed: u64| {
        let r = run_campaign(
            &file,
            &RunConfig {
                seed: Some(seed),
                ..config(&dir.path().join(format!("reference-{seed}")))
            },
        )
        .unwrap();
        columns(&read(&r.outputs.variants))
    };
    let references = [(2u64, reference(2)), (7, reference(7))];
    let mut refusals = 0;
    // The second run starts at once, or up to 0.4 s later (during or after the first).
    let delays_ms = [0, 0, 0, 20, 50, 100, 200, 400];
    for (trial, delay) in delays_ms.iter().enumerate() {
        let out = dir.path().join(format!("together-{trial}"));
        let second_seed = if trial % 2 == 0 { "2" } else { "7" };
        let a = spawn_run(&file, &out, &["--seed", "2"]);
        std::thread::sleep(std::time::Duration::from_millis(*delay));
        let b = spawn_run(&file, &out, &["--seed", second_seed]);
        let mut ok = 0;
        for child in [a, b] {
            let done = child.wait_with_output().unwrap();
            let stderr = String::from_utf8_lossy(&done.stderr).into_owned();
            match done.status.code() {
                Some(0 | 1) => ok += 1,
                Some(2) => {
                    assert!(
                        stderr.contains("another hpr-mc run is writing"),
                        "trial {trial}: {stderr}"
                    );
                    refusals += 1;
                }
                other => panic!("trial {trial}: exit {other:?}: {stderr}"),
            }
        }
        assert!(ok >= 1, "trial {trial}: neither run finished");
        // Whatever happened, every file is one whole run's: the same seed in all five, and
        // the variants are that seed's reference rows.
        let o = hpr_mc::campaign::run::Outputs::new(&out, Shard::ALL);
        let seed = seed_of(&o.variants);
        let parquet = |f: &&&PathBuf| f.extension().is_some_and(|e| e == "parquet");
        for f in o.finished().iter().filter(parquet) {
            assert_eq!(seed_of(f), seed, "trial {trial}: {}", f.display());
        }
        let want = &references
            .iter()
            .find(|(s, _)| s.to_string() == seed)
            .unwrap()
            .1;
        assert_eq!(
            &columns(&read(&o.variants)),
            want,
            "trial {trial}: seed {seed}"
        );
        let leftovers: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp") || n == "parts")
            .collect();
        assert!(leftovers.is_empty(), "trial {trial}: {leftovers:?}");
    }
    eprintln!(
        "{refusals} of {} second runs refused (the others ran after the first ended)",
        delays_ms.len()
    );
}

#[test]
fn a_negative_thread_count_is_named_as_one() {
    let (_dir, file) = setup(&calm_text(&tiny(2)));
    let (code, _, stderr) = hpr_mc(&[file.to_str().unwrap(), "--threads", "-1"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("invalid value '-1' for '--threads <N>': must be at least 1 (got -1)"),
        "{stderr}"
    );
    let (code, _, stderr) = hpr_mc(&[file.to_str().unwrap(), "--threads", "0"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("must be at least 1 (got 0)"), "{stderr}");
}

#[test]
fn a_run_killed_with_sigkill_leaves_a_free_directory_and_resumes_to_the_same_bytes() {
    // 120 flights in 30 parts of 4, on one thread: killed once a few parts are written.
    let (dir, file) = setup(&tiny(60));
    let reference = run_campaign(
        &file,
        &RunConfig {
            part_rows: Some(4),
            ..config(&dir.path().join("reference"))
        },
    )
    .unwrap();
    let out = dir.path().join("out");
    let mut child = spawn_run(&file, &out, &["--part-rows", "4"]);
    let parts = out.join("parts/variants");
    let t0 = std::time::Instant::now();
    let mut written = 0;
    while t0.elapsed() < std::time::Duration::from_secs(60) {
        written = std::fs::read_dir(&parts)
            .map(|d| {
                d.flatten()
                    .filter(|e| e.file_name().to_string_lossy().ends_with(".parquet"))
                    .count()
            })
            .unwrap_or(0);
        if written >= 3 || child.try_wait().unwrap().is_some() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child.kill().unwrap(); // SIGKILL: no clean-up of any kind
    let _ = child.wait();
    assert!(
        (3..30).contains(&written) && !out.join("variants.parquet").exists(),
        "killed mid-run: {written} parts written"
    );
    // Only whole files are left: the parts, and the killed part's temporary file at most.
    let temporaries = std::fs::read_dir(&parts)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .count();
    assert!(temporaries <= 1, "{temporaries} temporary files");
    // The lock died with it: the resumed run is not refused, and writes the reference's files.
    let (code, _, stderr) = hpr_mc(&[
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--resume",
        "--part-rows",
        "4",
    ]);
    assert!(code <= 1, "{stderr}");
    for name in [
        "variants.parquet",
        "summary.parquet",
        "ellipses.parquet",
        "sensitivity.parquet",
        "requirements.parquet",
        "trajectories.parquet",
    ] {
        assert!(
            std::fs::read(out.join(name)).unwrap()
                == std::fs::read(reference.outputs.dir.join(name)).unwrap(),
            "{name} differs from the uninterrupted run's"
        );
    }
}

#[test]
fn a_run_of_more_variants_than_one_process_may_fly_is_refused_before_anything_is_written() {
    // 2 sweep points × 6,000,000 = 12,000,000 variants in one process (the limit is 10^7):
    // refused with the shard count that fits; nothing is created.
    let (dir, file) = setup(&tiny(6_000_000));
    let out = dir.path().join("out");
    let e = run_campaign(&file, &config(&out)).unwrap_err().to_string();
    assert!(
        e.ends_with(
            "tiny.toml: 12000000 variants in one run is more than 10000000, the most one \
             process flies (its report reads every row back); split the run with \
             --shard K/N, N at least 2"
        ),
        "{e}"
    );
    assert!(!out.exists());
    // One shard of two holds 6,000,000: within the limit (refused here only by its size in
    // flights, which this test does not fly: it stops after its first part).
    let r = run_campaign(
        &file,
        &RunConfig {
            shard: Some(Shard { k: 0, n: 2 }),
            max_parts: Some(1),
            ..config(&out)
        },
    )
    .unwrap();
    assert_eq!(r.variants, 6_000_000);
    assert!(!r.complete);
}
