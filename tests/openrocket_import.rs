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

#[test]
fn fly_with_openrocket_conditions_flies_the_saved_simulation_s_launch_and_sets_its_results_beside()
{
    // The example with a simulation as OpenRocket 24 saves it: a 3 m rod 5° off vertical
    // towards 45°, a 3 m/s wind from the south, a site 1000 m up at 40° N; what it found.
    let text = std::fs::read_to_string(ORK).unwrap().replacen(
        "<simulations/>",
        r#"<simulations><simulation status="uptodate"><name>Field day</name><conditions>
             <configid>c1</configid><launchrodlength>3.0</launchrodlength>
             <launchrodangle>5.0</launchrodangle><launchroddirection>45.0</launchroddirection>
             <launchintowind>false</launchintowind>
             <wind model="average"><speed>3.0</speed><direction>3.141592653589793</direction>
               <standarddeviation>0.3</standarddeviation></wind>
             <launchaltitude>1000.0</launchaltitude><launchlatitude>40.0</launchlatitude>
             <geodeticmethod>spherical</geodeticmethod><atmosphere model="isa"/></conditions>
             <flightdata maxaltitude="600.0" timetoapogee="10.5" maxvelocity="150.0"
               launchrodvelocity="20.0" groundhitvelocity="6.0" flighttime="90.0"/>
           </simulation></simulations>"#,
        1,
    );
    let dir = scratch("conditions");
    let ork = dir.join("field.ork");
    std::fs::write(&ork, text).unwrap();
    let ork = ork.to_str().unwrap();
    let json =
        |args: &[&str]| -> serde_json::Value { serde_json::from_str(&stdout_of(args)).unwrap() };
    let as_saved = json(&["fly", ork, "--openrocket-conditions", "--json"]);
    let by_hand = json(&[
        "fly",
        ork,
        "--json",
        "--rail-length-m",
        "3",
        "--inclination-deg",
        "85",
        "--heading-deg",
        "45",
        "--wind-m-s",
        "3",
        "--wind-from-deg",
        "180",
        "--wind-turbulence-intensity",
        // OpenRocket's intensity: its standard deviation over its speed, 0.3 / 3 (one ulp
        // under 0.1, which the note rounds away).
        &(0.3f64 / 3.0).to_string(),
        "--elevation-m",
        "1000",
        "--latitude-deg",
        "40",
        "--gravity",
        "somigliana",
    ]);
    assert_eq!(as_saved["metrics"], by_hand["metrics"]);
    let or = &as_saved["openrocket"];
    assert_eq!(or["simulation"], "Field day");
    assert_eq!(or["apogee_m"], 600.0);
    assert_eq!(or["landing_time_s"], 90.0);
    // Its 10 % turbulence is flown (the gusts of seed 0, both times).
    assert!(
        or["not_repeated"].as_array().is_none_or(|a| a.is_empty()),
        "{}",
        or["not_repeated"]
    );
    // The text sets each saved result beside the flight's, with the difference.
    let text = stdout_of(&["fly", ork, "--openrocket-conditions"]);
    let apogee = by_hand["metrics"]["apogee_m"].as_f64().unwrap();
    let beside = text
        .split("\nOpenRocket's simulation \"Field day\"")
        .nth(1)
        .expect("the section");
    let row = beside
        .lines()
        .find(|l| l.trim_start().starts_with("apogee  "))
        .unwrap();
    assert!(
        row.contains("600.00 m") && row.contains(&format!("{apogee:.2} m")),
        "{row}"
    );
    assert!(
        row.trim_end()
            .ends_with(&format!("{:+.2} %", 100.0 * (apogee / 600.0 - 1.0))),
        "{row}"
    );
    // It needs a .ork with a simulation, and no launch flag beside it.
    let plain = hpr_mc(&["fly", ORK, "--openrocket-conditions"]);
    assert!(String::from_utf8_lossy(&plain.stderr).contains("the file holds no simulation"));
    let both = hpr_mc(&["fly", ork, "--openrocket-conditions", "--wind-m-s", "1"]);
    assert!(!both.status.success());
}

#[test]
fn a_part_openrocket_draws_outside_its_parent_is_kept_there_with_a_warning_inspect_reports() {
    // A weight OpenRocket lets sit 20 cm past the body tube's aft end.
    let text = std::fs::read_to_string(ORK).unwrap().replacen(
        "<parachute>",
        "<masscomponent><name>Stray</name><position type=\"bottom\">0.25</position>\
         <packedlength>0.05</packedlength><packedradius>0.02</packedradius><mass>0.1</mass>\
         </masscomponent><parachute>",
        1,
    );
    let dir = scratch("stray");
    let ork = dir.join("stray.ork");
    std::fs::write(&ork, text).unwrap();
    let ork = ork.to_str().unwrap();
    let out = hpr_mc(&["inspect", ork, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("warning: ") && stderr.contains("component \"stray\""),
        "{stderr}"
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let warning = json["warnings"][0].as_str().unwrap();
    assert!(
        warning.contains("component \"stray\": field \"position\"")
            && warning.contains("lies entirely outside its parent")
            && warning.ends_with("(kept there, as OpenRocket keeps it)"),
        "{warning}"
    );
    // The plain example has none.
    let plain: serde_json::Value =
        serde_json::from_str(&stdout_of(&["inspect", ORK, "--json"])).unwrap();
    assert_eq!(plain["warnings"], serde_json::json!([]));
}
