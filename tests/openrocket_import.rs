//! `hpr-mc import`, and `inspect` and `fly` reading an OpenRocket design directly: the bundled
//! `validation/designs/example-minimal.ork` (the design format's example drawn as OpenRocket
//! saves it) gives the same rocket whichever way it is read.

use std::process::{Command, Output};

const ORK: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/validation/designs/example-minimal.ork"
);

fn hpr_mc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hpr-mc"))
        .args(args)
        .output()
        .unwrap()
}

fn stdout_of(args: &[&str]) -> String {
    let out = hpr_mc(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("hpr-ork-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn an_imported_design_inspects_and_flies_as_the_ork_it_came_from() {
    let dir = scratch("same");
    let json = dir.join("example.json");
    let out = hpr_mc(&["import", ORK, "--output", json.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // What the import leaves to the scenario is said on standard error.
    let notes = String::from_utf8(out.stderr).unwrap();
    assert!(
        notes.contains("note: Parachute: OpenRocket deploys it at 300 m"),
        "{notes}"
    );
    let json = json.to_str().unwrap();
    assert_eq!(stdout_of(&["inspect", ORK]), stdout_of(&["inspect", json]));
    // A flight of the .ork says the same on standard error; of the JSON, nothing.
    let fly_ork = hpr_mc(&["fly", ORK]);
    assert!(
        String::from_utf8_lossy(&fly_ork.stderr).contains("note: Parachute: OpenRocket deploys it")
    );
    assert!(hpr_mc(&["fly", json]).stderr.is_empty());
    let fly = |design: &str| stdout_of(&["fly", design, "--json"]);
    let (from_ork, from_json) = (fly(ORK), fly(json));
    assert_eq!(from_ork, from_json);
    let v: serde_json::Value = serde_json::from_str(&from_ork).unwrap();
    assert!(v["metrics"]["apogee_m"].as_f64().unwrap() > 100.0, "{v}");
}

#[test]
fn a_design_the_import_cannot_make_is_refused_and_nothing_is_written() {
    let dir = scratch("refused");
    let ork = dir.join("tube-fins.ork");
    let text = std::fs::read_to_string(ORK).unwrap().replacen(
        "<parachute>",
        "<tubefinset><name>Tubes</name></tubefinset><parachute>",
        1,
    );
    std::fs::write(&ork, text).unwrap();
    let json = dir.join("out.json");
    let out = hpr_mc(&[
        "import",
        ork.to_str().unwrap(),
        "-o",
        json.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8(out.stderr).unwrap();
    assert!(
        e.contains("tube-fins.ork: rocket/stage \"Sustainer\"/bodytube \"Body tube\"/tubefinset \"Tubes\": a tube fin set cannot be imported"),
        "{e}"
    );
    assert!(!json.exists());
    // inspect reads it the same way, and says the same.
    let out = hpr_mc(&["inspect", ork.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("a tube fin set cannot be imported"));
}
