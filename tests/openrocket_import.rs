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
    // How the parachute deploys (taken into the design, for `fly`) is said on standard error.
    let notes = String::from_utf8(out.stderr).unwrap();
    assert!(
        notes.contains("note: Parachute: deploys at 300 m on the way down"),
        "{notes}"
    );
    let json = json.to_str().unwrap();
    assert_eq!(stdout_of(&["inspect", ORK]), stdout_of(&["inspect", json]));
    // `inspect` says how the parachute deploys: CdS 1.5 × π 0.3² m², at 300 m, at once.
    assert!(stdout_of(&["inspect", ORK]).contains(
        "  parachute                  CdS  0.4241 m²  deploys at 300 m on the way down, open 0 s after"
    ));
    let inspected: serde_json::Value =
        serde_json::from_str(&stdout_of(&["inspect", ORK, "--json"])).unwrap();
    let chute = &inspected["parachutes"][0];
    assert!((chute["cds_m2"].as_f64().unwrap() - 1.5 * std::f64::consts::PI * 0.09).abs() < 1e-15);
    assert_eq!(chute["deploy"]["trigger"], "300 m on the way down");
    // A flight of the .ork says the same on standard error; of the JSON, nothing.
    let fly_ork = hpr_mc(&["fly", ORK]);
    assert!(String::from_utf8_lossy(&fly_ork.stderr).contains("note: Parachute: deploys at 300 m"));
    assert!(hpr_mc(&["fly", json]).stderr.is_empty());
    let fly = |design: &str| stdout_of(&["fly", design, "--json"]);
    let (from_ork, from_json) = (fly(ORK), fly(json));
    assert_eq!(from_ork, from_json);
    let v: serde_json::Value = serde_json::from_str(&from_ork).unwrap();
    assert!(v["metrics"]["apogee_m"].as_f64().unwrap() > 100.0, "{v}");
}

/// The events of a flight's JSON as (kind, time, height).
fn events(flight: &serde_json::Value) -> Vec<(String, f64, f64)> {
    flight["events"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| {
            (
                e["event"].as_str().unwrap_or("").to_owned(),
                e["time_s"].as_f64().unwrap(),
                e["altitude_m"].as_f64().unwrap_or(f64::NAN),
            )
        })
        .collect()
}

#[test]
fn fly_deploys_an_openrocket_parachute_as_openrocket_does_unless_the_flags_say_otherwise() {
    // The example's parachute: OpenRocket deploys it descending through 300 m, no delay.
    let own: serde_json::Value = serde_json::from_str(&stdout_of(&["fly", ORK, "--json"])).unwrap();
    let ev = events(&own);
    let deploy = ev
        .iter()
        .find(|e| e.0.contains("deploy"))
        .unwrap_or_else(|| panic!("{ev:?}"));
    let trigger = ev.iter().find(|e| e.0.contains("trigger")).unwrap();
    // Fired at 300 m and open at once (lag 0), after apogee.
    assert!((trigger.2 - 300.0).abs() < 1e-6, "{ev:?}");
    assert_eq!(deploy.1, trigger.1, "{ev:?}");
    let apogee = ev.iter().find(|e| e.0 == "apogee").unwrap();
    assert!(deploy.1 > apogee.1);
    // Any parachute flag flies fly's drogue and main instead: the lone canopy is then the
    // drogue, fired at apogee and open a second later.
    let flagged: serde_json::Value =
        serde_json::from_str(&stdout_of(&["fly", ORK, "--json", "--lag-s", "1"])).unwrap();
    let ev = events(&flagged);
    let trigger = ev.iter().find(|e| e.0.contains("trigger")).unwrap();
    let deploy = ev.iter().find(|e| e.0.contains("deploy")).unwrap();
    let apogee = ev.iter().find(|e| e.0 == "apogee").unwrap();
    assert_eq!(trigger.1, apogee.1, "{ev:?}");
    assert!((deploy.1 - trigger.1 - 1.0).abs() < 1e-9, "{ev:?}");
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
