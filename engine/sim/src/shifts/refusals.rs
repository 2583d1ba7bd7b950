//! Every refusal `docs/moving-mass.md` lists ("What is refused, and why") has a test that checks
//! which rule fired.

use super::{plan, ShiftRefusal};
use crate::flight::{Environment, SimError, SimOptions};
use crate::reference::testing::{component_mut, design, reference_json, simulation};
use crate::{MassShift, Trigger};
use serde_json::json;

fn t5() -> Trigger {
    Trigger::Time { time_s: 5.0 }
}

/// Refusal of `shifts` on design JSON `v`, with the message printed.
fn refuse(v: &serde_json::Value, shifts: Vec<MassShift>) -> ShiftRefusal {
    let r = plan(&design(v), &shifts, Some(6.0)).expect_err("the shifts must be refused");
    eprintln!("refused: {r}");
    r
}

fn body_children(v: &mut serde_json::Value) -> &mut Vec<serde_json::Value> {
    component_mut(v, "body")["children"].as_array_mut().unwrap()
}

#[test]
fn shifts_that_cannot_be_made_are_refused() {
    let v = reference_json();
    let one = |c: &str, travel: f64, dur: f64| vec![MassShift::new(t5(), c, travel, dur)];
    assert!(
        matches!(refuse(&v, one("ballast", 0.1, 0.009)), ShiftRefusal::TooShort { duration_s, .. } if duration_s == 0.009)
    );
    assert!(
        plan(&design(&v), &one("ballast", 0.1, 0.01), Some(6.0)).is_ok(),
        "exactly 10 ms is allowed"
    );
    // A value that is not a finite number is refused, and the refusal names the field at
    // fault, so that a scenario or design file can point at its own key.
    let travel = refuse(&v, one("ballast", f64::NAN, 1.0));
    assert!(matches!(travel, ShiftRefusal::NotFinite { .. }));
    assert_eq!(travel.field(), Some((0, "travel_m")));
    let duration = refuse(&v, one("ballast", 0.1, f64::INFINITY));
    assert!(matches!(duration, ShiftRefusal::NotFinite { .. }));
    assert_eq!(duration.field(), Some((0, "duration_s")));
    assert!(matches!(
        refuse(&v, one("no_such_part", 0.1, 1.0)),
        ShiftRefusal::UnknownComponent { .. }
    ));
    assert!(matches!(
        refuse(&v, one("nose", 0.1, 1.0)),
        ShiftRefusal::BodyComponent { .. }
    ));
    assert!(matches!(
        refuse(&v, one("body", 0.1, 1.0)),
        ShiftRefusal::BodyComponent { .. }
    ));
    assert!(matches!(
        refuse(&v, one("fins", 0.1, 1.0)),
        ShiftRefusal::ExternalPart {
            kind: "fin_set",
            ..
        }
    ));
    assert!(matches!(
        refuse(&v, one("button_fore", 0.1, 1.0)),
        ShiftRefusal::ExternalPart {
            kind: "rail_button",
            ..
        }
    ));
    let r = refuse(&v, one("mmt", 0.05, 1.0));
    assert!(matches!(&r, ShiftRefusal::HoldsMotor { mount, .. } if mount == "mmt"));
    assert!(r.to_string().contains("the motor would not go with it"));

    // Totals toward the tail and toward the nose, each against the holder (the body tube,
    // 0.25 m to 1.1502 m; the ballast spans 0.35 m to 0.40 m).
    let body_bottom = design(&v).component("body").unwrap().x_bottom_m();
    let aft_room = body_bottom - 0.40;
    let ok = vec![
        MassShift::new(t5(), "ballast", 0.5, 1.0),
        MassShift::new(Trigger::Apogee, "ballast", aft_room - 0.5 - 1e-9, 1.0),
        MassShift::new(t5(), "ballast", -0.0999, 1.0),
    ];
    assert!(
        plan(&design(&v), &ok, Some(6.0)).is_ok(),
        "moves that stay inside add up to less than the room"
    );
    let r = refuse(
        &v,
        vec![
            MassShift::new(t5(), "ballast", 0.5, 1.0),
            MassShift::new(Trigger::Apogee, "ballast", aft_room - 0.5 + 1e-6, 1.0),
        ],
    );
    assert!(
        matches!(&r, ShiftRefusal::OutOfHolder { direction: "tail", holder, .. } if holder == "body")
    );
    // Moves back toward the nose don't cancel moves toward the tail: hpr can't know which fire.
    let r = refuse(
        &v,
        vec![
            MassShift::new(t5(), "ballast", 0.6, 1.0),
            MassShift::new(Trigger::Apogee, "ballast", -0.3, 1.0),
            MassShift::new(t5(), "ballast", 0.2, 1.0),
        ],
    );
    assert!(matches!(
        r,
        ShiftRefusal::OutOfHolder {
            direction: "tail",
            ..
        }
    ));
    let r = refuse(
        &v,
        vec![
            MassShift::new(t5(), "ballast", -0.06, 1.0),
            MassShift::new(Trigger::Apogee, "ballast", -0.05, 1.0),
        ],
    );
    assert!(
        matches!(r, ShiftRefusal::OutOfHolder { direction: "nose", limit_m, .. } if (limit_m - 0.1).abs() < 1e-12)
    );

    // A part inside a part that moves.
    let mut v2 = v.clone();
    body_children(&mut v2).push(json!({
        "id": "sled", "type": "inner_tube", "length_m": 0.1, "outer_diameter_m": 0.05, "wall_thickness_m": 0.001,
        "material": { "density_kg_m3": 700.0 }, "position": { "from": "nose_tip", "offset_m": 0.45 },
        "children": [{ "id": "battery", "type": "mass_component", "mass_kg": 0.05, "length_m": 0.03, "radius_m": 0.015,
                       "position": { "from": "top", "offset_m": 0.02 } }]
    }));
    assert!(
        plan(
            &design(&v2),
            &[MassShift::new(t5(), "sled", 0.1, 1.0)],
            Some(6.0)
        )
        .is_ok(),
        "the sled may move, with the battery in it"
    );
    assert!(
        plan(
            &design(&v2),
            &[MassShift::new(t5(), "battery", 0.05, 1.0)],
            Some(6.0)
        )
        .is_ok(),
        "the battery may move inside the sled"
    );
    let r = refuse(
        &v2,
        vec![
            MassShift::new(t5(), "sled", 0.1, 1.0),
            MassShift::new(t5(), "battery", 0.05, 1.0),
        ],
    );
    assert!(
        matches!(&r, ShiftRefusal::InsideMovingPart { component, mover, .. } if component == "battery" && mover == "sled")
    );
}

#[test]
fn refusals_that_need_a_design_of_their_own() {
    // One tube of a cluster.
    let mut v = reference_json();
    body_children(&mut v).push(json!({
        "id": "pods", "type": "inner_tube", "length_m": 0.05, "outer_diameter_m": 0.012, "wall_thickness_m": 0.001,
        "cluster": [[0.0, 0.012], [0.0, -0.012]], "material": { "density_kg_m3": 700.0 },
        "position": { "from": "nose_tip", "offset_m": 0.5 }
    }));
    let r = refuse(&v, vec![MassShift::new(t5(), "pods", 0.05, 1.0)]);
    assert!(matches!(r, ShiftRefusal::ClusterTube { tubes: 2, .. }));

    // An override of mass on the stage.
    let mut v = reference_json();
    v["stages"][0]["override"] = json!({ "mass_kg": 0.9 });
    let r = refuse(&v, vec![MassShift::new(t5(), "ballast", 0.1, 1.0)]);
    assert!(matches!(&r, ShiftRefusal::StageOverride { stage, .. } if stage == "sustainer"));
    assert!(r
        .to_string()
        .contains("doesn't say how much of that mass is the part's"));

    // An override on a component around the part that covers what it holds; one that does
    // not cover its contents does not stop the part.
    let mut v = reference_json();
    component_mut(&mut v, "body")["override"] = json!({ "mass_kg": 0.5, "covers_children": true });
    let r = refuse(&v, vec![MassShift::new(t5(), "ballast", 0.1, 1.0)]);
    assert!(matches!(&r, ShiftRefusal::ComponentOverride { holder, .. } if holder == "body"));
    let mut v = reference_json();
    component_mut(&mut v, "body")["override"] = json!({ "mass_kg": 0.2 });
    assert!(plan(
        &design(&v),
        &[MassShift::new(t5(), "ballast", 0.1, 1.0)],
        Some(6.0)
    )
    .is_ok());

    // A part the design already places partly outside its holder (a weight reaching out of a
    // nose cone's shoulder) may go as far as it already reaches, and no farther.
    let mut v = reference_json();
    component_mut(&mut v, "nose")["children"].as_array_mut().unwrap().push(json!({
        "id": "shoulder_weight", "type": "mass_component", "mass_kg": 0.02, "length_m": 0.04, "radius_m": 0.015,
        "position": { "from": "nose_tip", "offset_m": 0.28 }
    }));
    // The nose and its shoulder span 0 to 0.30 m; the weight spans 0.28 to 0.32 m.
    let d = design(&v);
    assert!(plan(
        &d,
        &[MassShift::new(t5(), "shoulder_weight", -0.28, 1.0)],
        Some(6.0)
    )
    .is_ok());
    let r = refuse(
        &v,
        vec![MassShift::new(t5(), "shoulder_weight", -0.2801, 1.0)],
    );
    assert!(matches!(
        r,
        ShiftRefusal::OutOfHolder {
            direction: "nose",
            ..
        }
    ));
    let r = refuse(
        &v,
        vec![MassShift::new(t5(), "shoulder_weight", 0.001, 1.0)],
    );
    assert!(
        matches!(&r, ShiftRefusal::OutOfHolder { direction: "tail", holder, limit_m, .. } if holder == "nose" && *limit_m == 0.0)
    );
}

#[test]
fn triggers_a_shift_cannot_have_are_refused_in_its_own_words() {
    let v = reference_json();
    let r = refuse(
        &v,
        vec![MassShift::new(
            Trigger::Time { time_s: 0.0 },
            "ballast",
            0.1,
            1.0,
        )],
    );
    assert!(
        matches!(&r, ShiftRefusal::Trigger { rule, .. } if rule.contains("before the rocket leaves the rail"))
    );
    let r = refuse(
        &v,
        vec![MassShift::new(
            Trigger::Time { time_s: -1.0 },
            "ballast",
            0.1,
            1.0,
        )],
    );
    assert!(matches!(&r, ShiftRefusal::Trigger { rule, .. } if rule.contains("time_s")));
    let r = refuse(
        &v,
        vec![MassShift::new(
            Trigger::HeightDescending { height_m: 0.0 },
            "ballast",
            0.1,
            1.0,
        )],
    );
    assert!(matches!(&r, ShiftRefusal::Trigger { rule, .. } if rule.contains("never start")));
    let r = refuse(
        &v,
        vec![MassShift::new(
            Trigger::HeightDescending { height_m: f64::NAN },
            "ballast",
            0.1,
            1.0,
        )],
    );
    assert!(matches!(&r, ShiftRefusal::Trigger { rule, .. } if rule.contains("height_m")));
    // Burnout plus the motor's delay, on a plugged motor (no delay).
    let r = plan(
        &design(&v),
        &[MassShift::new(
            Trigger::BurnoutPlusDelay { delay_s: None },
            "ballast",
            0.1,
            1.0,
        )],
        None,
    )
    .unwrap_err();
    eprintln!("refused: {r}");
    assert!(matches!(&r, ShiftRefusal::Trigger { rule, .. } if rule.contains("plugged")));
    assert!(plan(
        &design(&v),
        &[MassShift::new(
            Trigger::BurnoutPlusDelay { delay_s: Some(2.0) },
            "ballast",
            0.1,
            1.0
        )],
        None
    )
    .is_ok());

    // A shift that would start on the rail stops the flight with an error that says so; the
    // same shift later flies.
    let sim = simulation(design(&v), Environment::default(), SimOptions::default());
    let exit = sim.run(&mut ()).unwrap().metrics.rail_exit_time_s.unwrap();
    let early = sim
        .clone()
        .with_shifts(vec![MassShift::new(
            Trigger::Time { time_s: 0.5 * exit },
            "ballast",
            0.1,
            1.0,
        )])
        .unwrap();
    let e = early.run(&mut ()).unwrap_err();
    eprintln!("flight stopped: {e}");
    assert!(matches!(e, SimError::ShiftBeforeRailExit { index: 0, .. }));
    assert!(e.to_string().contains("before the rocket leaves the rail"));
    let late = sim
        .with_shifts(vec![MassShift::new(
            Trigger::Time { time_s: 1.5 * exit },
            "ballast",
            0.1,
            1.0,
        )])
        .unwrap();
    assert!(late.run(&mut ()).is_ok());
}
