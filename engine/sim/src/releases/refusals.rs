//! Every refusal of a release has a test that checks which rule fired, before the flight and
//! in it.

use super::{plan, PartChute, PartTrigger, Release, ReleaseRefusal};
use crate::flight::SimError;
use crate::reference;
use crate::reference::testing::{component_mut, design, reference_json};
use crate::shifts::{self, ShiftPlan};
use crate::{MassShift, Trigger};
use serde_json::json;

fn t5() -> Trigger {
    Trigger::Time { time_s: 5.0 }
}

/// The refusal of `releases` with the shifts `moving` on design JSON `v`, printed.
fn refuse_with(
    v: &serde_json::Value,
    moving: &[MassShift],
    releases: Vec<Release>,
) -> ReleaseRefusal {
    let d = design(v);
    let shift_plan = shifts::plan(&d, moving, Some(6.0)).unwrap();
    let r = plan(&d, &releases, &shift_plan, Some(6.0)).expect_err("the releases must be refused");
    eprintln!("refused: {r}");
    r
}

fn refuse(v: &serde_json::Value, releases: Vec<Release>) -> ReleaseRefusal {
    refuse_with(v, &[], releases)
}

fn accepted(v: &serde_json::Value, moving: &[MassShift], releases: Vec<Release>) -> bool {
    let d = design(v);
    let shift_plan = shifts::plan(&d, moving, Some(6.0)).unwrap();
    plan(&d, &releases, &shift_plan, Some(6.0)).is_ok()
}

fn one(c: &str) -> Vec<Release> {
    vec![Release::new(t5(), c)]
}

fn body_children(v: &mut serde_json::Value) -> &mut Vec<serde_json::Value> {
    component_mut(v, "body")["children"].as_array_mut().unwrap()
}

#[test]
fn releases_that_cannot_be_made_are_refused() {
    let v = reference_json();
    assert!(accepted(&v, &[], one("ballast")));
    assert!(matches!(
        refuse(&v, one("no_such_part")),
        ReleaseRefusal::UnknownComponent { .. }
    ));
    for body in ["nose", "body"] {
        assert!(matches!(
            refuse(&v, one(body)),
            ReleaseRefusal::BodyComponent { .. }
        ));
    }
    assert!(matches!(
        refuse(&v, one("fins")),
        ReleaseRefusal::ExternalPart {
            kind: "fin_set",
            ..
        }
    ));
    assert!(matches!(
        refuse(&v, one("button_aft")),
        ReleaseRefusal::ExternalPart {
            kind: "rail_button",
            ..
        }
    ));
    let r = refuse(&v, one("mmt"));
    assert!(matches!(&r, ReleaseRefusal::HoldsMotor { mount, .. } if mount == "mmt"));
    assert!(r.to_string().contains("which would leave with it"));
    let r = refuse(
        &v,
        vec![
            Release::new(t5(), "ballast"),
            Release::new(Trigger::Apogee, "ballast"),
        ],
    );
    assert!(matches!(
        r,
        ReleaseRefusal::ReleasedTwice {
            index: 1,
            other: 0,
            ..
        }
    ));
    // The part's own numbers, each named by its field.
    let bad = [
        (Release::new(t5(), "ballast").with_cda(0.0), "cda_m2"),
        (Release::new(t5(), "ballast").with_cda(f64::NAN), "cda_m2"),
        (
            Release::new(t5(), "ballast").with_parachute(PartChute::new(
                -0.1,
                PartTrigger::Release,
                1.0,
            )),
            "parachute.cds_m2",
        ),
        (
            Release::new(t5(), "ballast").with_parachute(PartChute::new(
                0.1,
                PartTrigger::Release,
                -1.0,
            )),
            "parachute.lag_s",
        ),
        (
            Release::new(t5(), "ballast").with_parachute(PartChute::new(
                0.1,
                PartTrigger::HeightDescending { height_m: 0.0 },
                1.0,
            )),
            "parachute.height_m",
        ),
    ];
    for (release, field) in bad {
        let r = refuse(&v, vec![release]);
        assert!(matches!(r, ReleaseRefusal::Number { .. }), "{r}");
        assert_eq!(r.field(), (0, field));
    }
    // A part that weighs nothing has nothing to fly.
    let mut v2 = v.clone();
    body_children(&mut v2).push(json!({
        "id": "empty", "type": "mass_component", "mass_kg": 0.0, "length_m": 0.02, "radius_m": 0.01,
        "position": { "from": "nose_tip", "offset_m": 0.5 }
    }));
    let r = refuse(&v2, one("empty"));
    assert!(matches!(r, ReleaseRefusal::Massless { mass_kg, .. } if mass_kg == 0.0));
    assert_eq!(r.field(), (0, "component"));
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
    assert!(matches!(
        refuse(&v, one("pods")),
        ReleaseRefusal::ClusterTube { tubes: 2, .. }
    ));

    // A mass override of the stage, or of a component around the part that covers it.
    let mut v = reference_json();
    v["stages"][0]["override"] = json!({ "mass_kg": 0.9 });
    let r = refuse(&v, one("ballast"));
    assert!(matches!(&r, ReleaseRefusal::StageOverride { stage, .. } if stage == "sustainer"));
    let mut v = reference_json();
    component_mut(&mut v, "body")["override"] = json!({ "mass_kg": 0.5, "covers_children": true });
    let r = refuse(&v, one("ballast"));
    assert!(matches!(&r, ReleaseRefusal::ComponentOverride { holder, .. } if holder == "body"));
    let mut v = reference_json();
    component_mut(&mut v, "body")["override"] = json!({ "mass_kg": 0.2 });
    assert!(
        accepted(&v, &[], one("ballast")),
        "an override that does not cover the body's contents"
    );

    // A sled holding a battery: parts inside parts that move or leave.
    let mut v = reference_json();
    body_children(&mut v).push(json!({
        "id": "sled", "type": "inner_tube", "length_m": 0.1, "outer_diameter_m": 0.05, "wall_thickness_m": 0.001,
        "material": { "density_kg_m3": 700.0 }, "position": { "from": "nose_tip", "offset_m": 0.45 },
        "children": [{ "id": "battery", "type": "mass_component", "mass_kg": 0.05, "length_m": 0.03, "radius_m": 0.015,
                       "position": { "from": "top", "offset_m": 0.02 } }]
    }));
    let sled_moves = [MassShift::new(t5(), "sled", 0.1, 1.0)];
    let battery_moves = [MassShift::new(t5(), "battery", 0.05, 1.0)];
    assert!(
        accepted(&v, &[], one("sled")),
        "the sled leaves with its battery"
    );
    assert!(
        accepted(&v, &[], one("battery")),
        "the battery leaves the sled"
    );
    assert!(
        accepted(&v, &sled_moves, one("sled")),
        "the sled moves, then leaves"
    );
    let r = refuse_with(&v, &sled_moves, one("battery"));
    assert!(
        matches!(&r, ReleaseRefusal::InsideMovingPart { component, mover, .. } if component == "battery" && mover == "sled")
    );
    let r = refuse_with(&v, &battery_moves, one("sled"));
    assert!(
        matches!(&r, ReleaseRefusal::HoldsMovingPart { component, moving, .. } if component == "sled" && moving == "battery")
    );
    for order in [["sled", "battery"], ["battery", "sled"]] {
        let r = refuse(
            &v,
            vec![Release::new(t5(), order[0]), Release::new(t5(), order[1])],
        );
        assert!(
            matches!(&r, ReleaseRefusal::InsideReleasedPart { component, holder, .. } if component == "battery" && holder == "sled"),
            "{r}"
        );
    }
}

#[test]
fn triggers_a_release_cannot_have_are_refused_in_its_own_words() {
    let v = reference_json();
    let with = |t: Trigger| vec![Release::new(t, "ballast")];
    let rule = |r: ReleaseRefusal| match r {
        ReleaseRefusal::Trigger { rule, .. } => rule,
        other => panic!("not a trigger's refusal: {other}"),
    };
    assert!(rule(refuse(&v, with(Trigger::Time { time_s: 0.0 })))
        .contains("at launch it is still on the pad"));
    assert!(rule(refuse(&v, with(Trigger::Time { time_s: -1.0 }))).contains("time_s"));
    assert!(rule(refuse(
        &v,
        with(Trigger::HeightDescending { height_m: 0.0 })
    ))
    .contains("would never leave"));
    assert!(rule(refuse(
        &v,
        with(Trigger::HeightDescending { height_m: f64::NAN })
    ))
    .contains("height_m"));
    // Burnout plus the motor's delay, on a plugged motor (no delay).
    let d = design(&v);
    let none = ShiftPlan {
        parts: vec![],
        part_of_shift: vec![],
    };
    let motor_delay = |r: &[Release], delay| plan(&d, r, &none, delay);
    let plugged = with(Trigger::BurnoutPlusDelay { delay_s: None });
    let r = motor_delay(&plugged, None).unwrap_err();
    eprintln!("refused: {r}");
    assert!(rule(r).contains("plugged"));
    assert!(motor_delay(&plugged, Some(6.0)).is_ok());
    assert!(motor_delay(
        &with(Trigger::BurnoutPlusDelay { delay_s: Some(2.0) }),
        None
    )
    .is_ok());
    // Burnout itself cannot come on the pad (the motor burns to it).
    assert!(motor_delay(&with(Trigger::Burnout), None).is_ok());
}

#[test]
fn a_release_that_would_fire_on_the_rail_stops_the_flight_and_the_same_later_flies() {
    let sim = reference::simulation();
    let exit = sim.run(&mut ()).unwrap().metrics.rail_exit_time_s.unwrap();
    let early = sim
        .clone()
        .with_releases(vec![Release::new(
            Trigger::Time { time_s: 0.5 * exit },
            "ballast",
        )])
        .unwrap();
    let e = early.run(&mut ()).unwrap_err();
    eprintln!("flight stopped: {e}");
    assert!(matches!(
        e,
        SimError::ReleaseBeforeRailExit { index: 0, .. }
    ));
    assert!(e.to_string().contains("before the rocket leaves the rail"));
    let late = sim
        .with_releases(vec![Release::new(
            Trigger::Time { time_s: 1.5 * exit },
            "ballast",
        )])
        .unwrap();
    assert!(late.run(&mut ()).is_ok());
}

#[test]
fn a_part_is_not_released_while_its_shift_moves_it_nor_moved_once_released() {
    let sim = reference::simulation()
        .with_shifts(vec![MassShift::new(t5(), "ballast", 0.3, 1.0)])
        .unwrap();
    let with = |t: f64| {
        sim.clone()
            .with_releases(vec![Release::new(Trigger::Time { time_s: t }, "ballast")])
            .unwrap()
            .run(&mut ())
    };
    // During the move (its start, its middle, just before its end): the flight stops.
    for t in [5.0 + 1e-9, 5.5, 6.0 - 1e-9] {
        let e = with(t).unwrap_err();
        assert!(
            matches!(
                e,
                SimError::ReleaseDuringShift {
                    index: 0,
                    shift: 0,
                    ..
                }
            ),
            "{e}"
        );
    }
    eprintln!("flight stopped: {}", with(5.5).unwrap_err());
    // Released at the move's end or after it, the part leaves.
    assert!(with(6.0).is_ok());
    // Released first, then the shift's trigger comes: nothing is left to move.
    let e = with(4.0).unwrap_err();
    eprintln!("flight stopped: {e}");
    assert!(matches!(
        e,
        SimError::ShiftAfterRelease {
            index: 0,
            release: 0,
            ..
        }
    ));
    // A release and a shift of the part at the same instant: the shift starts first (the
    // triggers fire in that order), so the part would leave moving.
    assert!(matches!(
        with(5.0).unwrap_err(),
        SimError::ReleaseDuringShift {
            index: 0,
            shift: 0,
            ..
        }
    ));
}
