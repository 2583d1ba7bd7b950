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
