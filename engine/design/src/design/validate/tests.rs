//! Validation: the example parses with every position resolved, and every refusal names the
//! component, the field and the rule.

use crate::design::model::*;
use crate::error::{DesignError, Location, Rule};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

mod aero;
mod parts;
mod rules;

pub(crate) fn example_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../validation/designs/example-minimal.json")
}

pub(crate) fn example_value() -> Value {
    serde_json::from_str(&std::fs::read_to_string(example_path()).expect("example design"))
        .expect("example JSON")
}

/// The example, changed by `f`, validated as if read from `design.json`.
fn with(f: impl FnOnce(&mut Value)) -> Result<Design, DesignError> {
    let mut v = example_value();
    f(&mut v);
    Design::from_json_str(&v.to_string(), Some(Path::new("design.json")))
}

fn at<'a>(v: &'a mut Value, pointer: &str) -> &'a mut Value {
    v.pointer_mut(pointer)
        .unwrap_or_else(|| panic!("no {pointer} in the example"))
}

const BODY: &str = "/stages/0/components/1";
const FINS: &str = "/stages/0/components/1/children/0";

fn children(v: &mut Value) -> &mut Vec<Value> {
    at(v, &format!("{BODY}/children"))
        .as_array_mut()
        .expect("children")
}

/// The rule, location and field of an `Invalid` error.
fn invalid(r: Result<Design, DesignError>) -> (Rule, Location, Option<String>) {
    match r {
        Err(DesignError::Invalid {
            rule, at, field, ..
        }) => (rule, at, field),
        Err(e) => panic!("expected a rule broken, got {e}"),
        Ok(_) => panic!("expected a rule broken, the design was accepted"),
    }
}

fn comp(id: &str) -> Location {
    Location::Component(id.to_owned())
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12
}

#[test]
fn the_example_design_loads_with_every_position_resolved() {
    let d = Design::load(example_path()).expect("the example is valid");
    let x = |id: &str| d.component(id).expect(id).x_top_m;
    assert_eq!(d.components.len(), 10);
    assert_eq!(d.stages.len(), 1);
    assert_eq!(d.stages[0].components, (0..10).collect::<Vec<_>>());
    assert_eq!(d.default_motor.as_deref(), Some("Cesaroni_I175"));
    assert_eq!(d.reference_diameter_m, 0.0563);
    // Nose 0.25 then body 0.9, end to end.
    assert_eq!(x("nose"), 0.0);
    assert_eq!(x("body"), 0.25);
    assert!(close(d.length_m, 1.15));
    // Fins bottom-aligned: 1.15 − 0.12; motor tube bottom-aligned: 1.15 − 0.3.
    assert!(close(x("fins"), 1.03));
    assert!(close(x("mmt"), 0.85));
    assert!(close(x("ring_fore"), 1.15 - 0.006 - 0.294));
    assert!(close(x("chute"), 0.30));
    assert_eq!(x("ballast"), 0.35);
    // Rail buttons: centers at 0.25 + 0.4 + 0.005 and 1.15 − 0.02 − 0.005.
    let (upper, lower) = d.rail_guides_m.expect("two rail buttons");
    assert!(
        close(upper, 0.655) && close(lower, 1.125),
        "{upper} {lower}"
    );
    let mount = d.motor_mount.expect("a motor mount");
    assert_eq!(d.components[mount.component].id, "mmt");
    assert!(close(mount.motor_aft_m, 1.16));
    assert!(close(mount.inner_diameter_m, 0.038));
    assert_eq!(mount.tube_length_m, 0.3);
    match &d.components[d.component_index("fins").unwrap()].kind {
        ComponentKind::FinSet(f) => assert_eq!(f.body_radius_m, 0.0563 / 2.0),
        k => panic!("{k:?}"),
    }
    // The button sits on the surface: its center is R + h/2 off the axis, at angle 0 (+y).
    let b = d.component("button_fore").unwrap();
    assert!(close(b.radial_offset_m[0], 0.0563 / 2.0 + 0.004) && b.radial_offset_m[1] == 0.0);
    assert_eq!(
        d.drag,
        DragSpec::Curves {
            power_off: vec![
                (0.0, 0.45),
                (0.3, 0.44),
                (0.6, 0.46),
                (0.9, 0.55),
                (1.2, 0.62)
            ],
            power_on: vec![
                (0.0, 0.45),
                (0.3, 0.44),
                (0.6, 0.46),
                (0.9, 0.55),
                (1.2, 0.62)
            ],
        }
    );
    assert_eq!(d.source.as_deref(), Some(example_path().as_path()));
}

#[test]
fn the_position_rules_follow_openrocket() {
    let d = with(|v| {
        let c = children(v);
        c.push(
            json!({"id": "m_mid", "type": "mass_component", "mass_kg": 0.1, "length_m": 0.1,
                      "radius_m": 0.01, "position": {"from": "middle", "offset_m": 0.05}}),
        );
        c.push(
            json!({"id": "m_bottom", "type": "mass_component", "mass_kg": 0.1, "length_m": 0.1,
                      "radius_m": 0.01, "position": {"from": "bottom", "offset_m": -0.2}}),
        );
        c.push(
            json!({"id": "m_default", "type": "mass_component", "mass_kg": 0.1, "length_m": 0.1,
                      "radius_m": 0.01}),
        );
    })
    .expect("valid");
    let x = |id: &str| d.component(id).unwrap().x_top_m;
    // Body 0.25..1.15: middle 0.25 + 0.4 + 0.05; bottom 1.15 − 0.1 − 0.2; default top.
    assert!(close(x("m_mid"), 0.7));
    assert!(close(x("m_bottom"), 0.85));
    assert_eq!(x("m_default"), 0.25);
}

#[test]
fn stages_follow_each_other_and_their_overrides_become_absolute() {
    let d = with(|v| {
        let booster = json!({"id": "booster", "override": {"mass_kg": 1.5, "cg_m": 0.2}, "components": [
            {"id": "b_tube", "type": "body_tube", "length_m": 0.5, "outer_diameter_m": 0.0563,
             "wall_thickness_m": 0.0015, "mass_kg": 0.3,
             "override": {"cg_m": 0.1},
             "children": [{"id": "b_mass", "type": "mass_component", "mass_kg": 0.1, "length_m": 0.05,
                           "radius_m": 0.01, "position": {"from": "top", "offset_m": 0.1}}]}
        ]});
        at(v, "/stages").as_array_mut().unwrap().push(booster);
    })
    .expect("valid");
    let t = d.component("b_tube").unwrap();
    assert!(close(t.x_top_m, 1.15));
    assert!(close(d.length_m, 1.65));
    assert!(close(t.overrides.cg_m.unwrap(), 1.25));
    assert_eq!(t.stage, 1);
    assert!(close(d.component("b_mass").unwrap().x_top_m, 1.25));
    assert_eq!(d.stages[1].overrides.mass_kg, Some(1.5));
    assert!(close(d.stages[1].overrides.cg_m.unwrap(), 1.35));
    assert_eq!(d.stages[1].components, vec![10, 11]);
}

#[test]
fn a_negative_span_is_refused_with_file_component_field_and_value() {
    let e = with(|v| *at(v, &format!("{FINS}/span_m")) = json!(-0.1)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "design.json: component \"fins\": field \"span_m\": must be positive and finite (got -0.1)"
    );
}

#[test]
fn zero_sizes_and_densities_are_refused() {
    let cases: [(&str, Value, &str, &str); 5] = [
        (
            "/stages/0/components/0/length_m",
            json!(0.0),
            "nose",
            "length_m",
        ),
        (
            "/stages/0/components/1/outer_diameter_m",
            json!(-0.05),
            "body",
            "outer_diameter_m",
        ),
        (
            "/stages/0/components/1/material/density_kg_m3",
            json!(0.0),
            "body",
            "material.density_kg_m3",
        ),
        (
            "/stages/0/components/0/shoulder/length_m",
            json!(-1.0),
            "nose",
            "shoulder.length_m",
        ),
        (
            "/stages/0/components/1/children/4/cd",
            json!(0.0),
            "chute",
            "cd",
        ),
    ];
    for (pointer, value, id, field) in cases {
        let (rule, loc, f) = invalid(with(|v| *at(v, pointer) = value.clone()));
        assert!(
            matches!(rule, Rule::NotPositive { .. }),
            "{pointer}: {rule:?}"
        );
        assert_eq!((loc, f.as_deref()), (comp(id), Some(field)), "{pointer}");
    }
}

#[test]
fn a_length_in_millimetres_is_refused_as_larger_than_any_rocket_part() {
    // Every length or diameter above MAX_PART_SIZE_M (30 m) is refused by its field, the
    // typo of a length in millimetres (a 54 mm tube written 54) the case it is there for.
    assert_eq!(MAX_PART_SIZE_M, 30.0);
    let cases: [(&str, f64, &str, &str); 11] = [
        ("/stages/0/components/0/length_m", 300.0, "nose", "length_m"),
        (
            "/stages/0/components/0/shoulder/length_m",
            1e150,
            "nose",
            "shoulder.length_m",
        ),
        (
            "/stages/0/components/1/length_m",
            1200.0,
            "body",
            "length_m",
        ),
        (
            &format!("{FINS}/root_chord_m"),
            120.0,
            "fins",
            "root_chord_m",
        ),
        (&format!("{FINS}/tip_chord_m"), 60.0, "fins", "tip_chord_m"),
        (&format!("{FINS}/span_m"), 100.0, "fins", "span_m"),
        (&format!("{FINS}/sweep_m"), -31.0, "fins", "sweep_m"),
        (
            &format!("{BODY}/children/2/inner_diameter_m"),
            31.0,
            "ring_fore",
            "inner_diameter_m",
        ),
        (
            &format!("{BODY}/children/4/canopy_diameter_m"),
            900.0,
            "chute",
            "canopy_diameter_m",
        ),
        (
            &format!("{BODY}/children/5/radius_m"),
            30.5,
            "ballast",
            "radius_m",
        ),
        (
            &format!("{BODY}/children/6/height_m"),
            30.000001,
            "button_fore",
            "height_m",
        ),
    ];
    for (pointer, value, id, field) in cases {
        let (rule, loc, f) = invalid(with(|v| *at(v, pointer) = json!(value)));
        let got = if field == "sweep_m" {
            value.abs()
        } else {
            value
        };
        assert_eq!(rule, Rule::TooLarge { got, max: 30.0 }, "{pointer}");
        assert_eq!((loc, f.as_deref()), (comp(id), Some(field)), "{pointer}");
    }
    // The error says what the number probably is.
    let e = with(|v| *at(v, "/stages/0/components/1/outer_diameter_m") = json!(54.0)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "design.json: component \"body\": field \"outer_diameter_m\": must be at most 30 m, \
         more than any part of a high-power rocket (got 54 m; a length in millimetres? the \
         design's lengths are in metres)"
    );
    // 30 m itself is a size, not a typo: a 30 m canopy loads.
    let d = with(|v| *at(v, &format!("{BODY}/children/4/canopy_diameter_m")) = json!(30.0));
    assert!(d.is_ok(), "{:?}", d.err());
}

#[test]
fn a_free_form_fin_corner_beyond_30_m_is_refused() {
    let r = with(|v| {
        let fins = at(v, FINS).as_object_mut().unwrap();
        for k in ["root_chord_m", "tip_chord_m", "span_m", "sweep_m"] {
            fins.remove(k);
        }
        fins.insert("planform".into(), json!("free_form"));
        fins.insert(
            "points_m".into(),
            json!([[0.0, 0.0], [40.0, 60.0], [80.0, 60.0], [100.0, 0.0]]),
        );
    });
    let (rule, loc, field) = invalid(r);
    assert_eq!(
        rule,
        Rule::FinOutline {
            point: 1,
            why: "must be within 30 m (MAX_PART_SIZE_M) of the root's leading edge: \
                  the outline is in metres"
        }
    );
    assert_eq!((loc, field.as_deref()), (comp("fins"), Some("points_m")));
}

#[test]
fn an_explicit_mass_may_be_zero_but_not_negative() {
    // Zero: the part keeps its shape (for the aerodynamics) and weighs nothing.
    let d = with(|v| *at(v, &format!("{BODY}/children/5/mass_kg")) = json!(0.0))
        .expect("a zero explicit mass is accepted");
    let ballast = d.component_index("ballast").unwrap();
    assert_eq!(crate::mass::component_own(&d, ballast).mass_kg, 0.0);
    let full = Design::load(example_path()).unwrap();
    let dry_drop = crate::mass::dry(&full).mass_kg - crate::mass::dry(&d).mass_kg;
    assert!((dry_drop - 0.2).abs() <= 1e-15, "{dry_drop}");
    let (rule, loc, f) = invalid(with(|v| {
        *at(v, &format!("{BODY}/children/5/mass_kg")) = json!(-0.1)
    }));
    assert!(matches!(rule, Rule::Negative { .. }), "{rule:?}");
    assert_eq!((loc, f.as_deref()), (comp("ballast"), Some("mass_kg")));
}

#[test]
fn syntax_errors_give_the_line_and_column_and_a_component_s_faults_its_id_and_field() {
    let e = Design::from_json_str(
        "{\n  \"name\": \"x\",\n  \"stages\": [,]\n}",
        Some(Path::new("d.json")),
    )
    .unwrap_err();
    match e {
        DesignError::Json {
            ref file,
            line,
            column,
            ..
        } => {
            assert_eq!((file.as_str(), line, column), ("d.json", 3, 14), "{e}");
        }
        e => panic!("{e}"),
    }
    // A component's unknown field, wrong type, missing or unknown type: serde alone would put
    // them at the end of the enclosing array, naming neither the component nor the field.
    let located = |e: DesignError| match e {
        DesignError::JsonAt {
            at: place,
            field,
            message,
            ..
        } => (place, field, message),
        e => panic!("not placed by component: {e}"),
    };
    let (place, field, message) = located(
        with(|v| {
            at(v, BODY)
                .as_object_mut()
                .unwrap()
                .insert("colour".into(), json!("red"));
        })
        .unwrap_err(),
    );
    assert_eq!((place, field.as_deref()), (comp("body"), Some("colour")));
    assert!(message.starts_with("unknown field `colour`"), "{message}");
    let (place, field, message) =
        located(with(|v| *at(v, &format!("{FINS}/count")) = json!(3.5)).unwrap_err());
    assert_eq!((place, field.as_deref()), (comp("fins"), Some("count")));
    assert_eq!(
        message,
        "invalid type: floating point `3.5`, expected a whole number, 0 or more"
    );
    let (place, field, message) =
        located(with(|v| *at(v, &format!("{BODY}/length_m")) = json!("0.9")).unwrap_err());
    assert_eq!((place, field.as_deref()), (comp("body"), Some("length_m")));
    assert_eq!(message, "invalid type: string \"0.9\", expected a number");
    let e = with(|v| *at(v, "/stages/0/components/1/type") = json!("bodytube")).unwrap_err();
    assert!(e.to_string().contains("unknown variant `bodytube`"), "{e}");
    let (place, field, _) = located(e);
    assert_eq!((place, field.as_deref()), (comp("body"), Some("type")));
    let (place, field, _) = located(
        with(|v| {
            at(v, FINS).as_object_mut().unwrap().remove("type");
        })
        .unwrap_err(),
    );
    assert_eq!((place, field.as_deref()), (comp("fins"), Some("type")));
    // Outside the components serde's own place stands: a top-level field by line and column.
    let e = with(|v| v["name"] = json!(5)).unwrap_err();
    assert!(matches!(e, DesignError::Json { .. }), "{e}");
}

#[test]
fn ids_must_be_unique_and_not_empty() {
    let (rule, loc, field) = invalid(with(|v| *at(v, &format!("{FINS}/id")) = json!("nose")));
    assert_eq!(
        rule,
        Rule::DuplicateId {
            first: "stages[0].components[0]".into()
        }
    );
    assert_eq!((loc, field.as_deref()), (comp("nose"), Some("id")));
    let (rule, loc, _) = invalid(with(|v| *at(v, &format!("{FINS}/id")) = json!("")));
    assert_eq!(rule, Rule::EmptyId);
    assert_eq!(
        loc,
        Location::Path("stages[0].components[1].children[0]".into())
    );
    // Stage and component ids share one namespace.
    let (rule, ..) = invalid(with(|v| *at(v, "/stages/0/id") = json!("body")));
    assert_eq!(
        rule,
        Rule::DuplicateId {
            first: "stages[0]".into()
        }
    );
}

#[test]
fn a_wall_thicker_than_the_radius_is_refused() {
    let (rule, loc, field) = invalid(with(|v| {
        *at(v, "/stages/0/components/1/wall_thickness_m") = json!(0.03)
    }));
    assert_eq!(
        rule,
        Rule::WallThickerThanRadius {
            wall_m: 0.03,
            radius_m: 0.0563 / 2.0
        }
    );
    assert_eq!(
        (loc, field.as_deref()),
        (comp("body"), Some("wall_thickness_m"))
    );
}

#[test]
fn a_body_component_inside_another_is_refused() {
    let (rule, loc, _) = invalid(with(|v| {
        children(v).push(
            json!({"id": "inner_body", "type": "body_tube", "length_m": 0.1,
            "outer_diameter_m": 0.03, "wall_thickness_m": 0.001, "mass_kg": 0.01}),
        );
    }));
    assert_eq!(rule, Rule::BodyInsideComponent { kind: "body_tube" });
    assert_eq!(loc, comp("inner_body"));
    // And a part that is not a body at a stage's top level.
    let (rule, ..) = invalid(with(|v| {
        let mut ballast = children(v)[5].clone();
        ballast["id"] = json!("loose_ballast");
        at(v, "/stages/0/components")
            .as_array_mut()
            .unwrap()
            .push(ballast);
    }));
    assert_eq!(
        rule,
        Rule::NotABody {
            kind: "mass_component"
        }
    );
}

#[test]
fn a_part_entirely_outside_its_parent_is_refused_but_one_partly_outside_is_not() {
    let ballast = "/stages/0/components/1/children/5/position/offset_m";
    // Body 0.25..1.15; the 0.05 m ballast at 1.15 lies entirely aft of it.
    let (rule, loc, field) = invalid(with(|v| *at(v, ballast) = json!(1.15)));
    assert!(matches!(rule, Rule::OutsideParent { .. }), "{rule:?}");
    assert_eq!((loc, field.as_deref()), (comp("ballast"), Some("position")));
    // At 1.12 it is partly outside: allowed (a moving part may go as far as it already reaches,
    // `docs/moving-mass.md`).
    let d = with(|v| *at(v, ballast) = json!(1.12)).expect("partly outside is allowed");
    assert_eq!(d.component("ballast").unwrap().x_top_m, 1.12);
}

#[test]
fn a_weight_may_sit_in_a_nose_cone_s_shoulder() {
    // The nose spans 0..0.25 and its shoulder 0.25..0.30: a weight at 0.26 is inside it.
    let d = with(|v| {
        at(v, "/stages/0/components/0").as_object_mut().unwrap().insert(
            "children".into(),
            json!([{"id": "nose_weight", "type": "mass_component", "mass_kg": 0.05, "length_m": 0.03,
                    "radius_m": 0.02, "position": {"from": "nose_tip", "offset_m": 0.26}}]),
        );
    })
    .expect("a weight in the shoulder is inside the nose cone");
    assert_eq!(d.component("nose_weight").unwrap().parent, Some(0));
    // Beyond the shoulder it is refused.
    let (rule, ..) = invalid(with(|v| {
        at(v, "/stages/0/components/0").as_object_mut().unwrap().insert(
            "children".into(),
            json!([{"id": "nose_weight", "type": "mass_component", "mass_kg": 0.05, "length_m": 0.03,
                    "radius_m": 0.02, "position": {"from": "nose_tip", "offset_m": 0.30}}]),
        );
    }));
    assert!(
        matches!(rule, Rule::OutsideParent { parent_bottom_m, .. } if close(parent_bottom_m, 0.30)),
        "{rule:?}"
    );
}

#[test]
fn a_part_wider_than_its_parent_is_refused() {
    // Body inner diameter 0.0563 − 0.003 = 0.0533.
    let (rule, loc, _) = invalid(with(|v| {
        *at(v, "/stages/0/components/1/children/5/radius_m") = json!(0.03)
    }));
    assert!(
        matches!(rule, Rule::WiderThanParent { width_m, inner_diameter_m } if close(width_m, 0.06) && close(inner_diameter_m, 0.0533)),
        "{rule:?}"
    );
    assert_eq!(loc, comp("ballast"));
    // An offset counts: radius 0.02 at 0.01 off the axis reaches 0.03 from it.
    let (rule, ..) = invalid(with(|v| children(v)[5]["radial_offset_m"] = json!(0.01)));
    assert!(matches!(rule, Rule::WiderThanParent { .. }), "{rule:?}");
    // The rings fit exactly (0.0533 in 0.0563 − 2 × 0.0015): accepted within the tolerance.
    assert!(with(|_| {}).is_ok());
}

#[test]
fn with_openrocket_geometry_checks_a_misplaced_part_stays_where_it_is_drawn_with_a_warning() {
    // The two parts the strict checks refuse: the ballast 0.06 m wide in a 0.0533 m bore,
    // and a nose weight beyond the nose's shoulder (0.30 m aft of the tip, the shoulder
    // ending at 0.30 m); OpenRocket weighs each where it is.
    let d = with(|v| {
        v["geometry_checks"] = json!("openrocket");
        *at(v, "/stages/0/components/1/children/5/radius_m") = json!(0.03);
        at(v, "/stages/0/components/0").as_object_mut().unwrap().insert(
            "children".into(),
            json!([{"id": "nose_weight", "type": "mass_component", "mass_kg": 0.05, "length_m": 0.03,
                    "radius_m": 0.02, "position": {"from": "nose_tip", "offset_m": 0.30}}]),
        );
    })
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(d.warnings.len(), 2, "{:?}", d.warnings);
    assert!(
        d.warnings[0].starts_with(
            "design.json: component \"nose_weight\": field \"position\": the part (0.3 m to 0.33 m"
        ) && d.warnings[0].ends_with("(kept there, as OpenRocket keeps it)"),
        "{}",
        d.warnings[0]
    );
    assert!(
        d.warnings[1].starts_with("design.json: component \"ballast\": the part (0.06 m across"),
        "{}",
        d.warnings[1]
    );
    let weight = d.component("nose_weight").unwrap();
    assert!(close(weight.x_top_m, 0.30));
    // The strict default still refuses them, and a position that is not a number is refused
    // whatever the checks.
    assert!(with(|v| *at(v, "/stages/0/components/1/children/5/radius_m") = json!(0.03)).is_err());
    let loose = with(|v| v["geometry_checks"] = json!("loose"))
        .unwrap_err()
        .to_string();
    assert!(
        loose.contains("`loose`, expected `strict` or `openrocket`"),
        "{loose}"
    );
}

#[test]
fn a_parachute_may_say_how_it_deploys_with_a_scenario_s_trigger() {
    let chute_with = |deploy: Value| {
        with(|v| {
            let chute = children(v)
                .iter_mut()
                .find(|c| c["id"] == "chute")
                .expect("the example's chute");
            chute["deploy"] = deploy;
        })
    };
    let deploy_of = |d: Design| {
        let i = d.component_index("chute").unwrap();
        match &d.components[i].kind {
            ComponentKind::Parachute(p) => p.deploy,
            _ => unreachable!(),
        }
    };
    let cases = [
        (
            json!({"trigger": "apogee", "lag_s": 1.5}),
            DeployTrigger::Apogee,
            1.5,
        ),
        (json!({"trigger": "burnout"}), DeployTrigger::Burnout, 0.0),
        (
            json!({"trigger": "motor_delay"}),
            DeployTrigger::MotorDelay,
            0.0,
        ),
        (
            json!({"trigger": {"time_s": 5.0}}),
            DeployTrigger::Time { time_s: 5.0 },
            0.0,
        ),
        (
            json!({"trigger": {"height_m": 150.0}, "lag_s": 0.5}),
            DeployTrigger::Height { height_m: 150.0 },
            0.5,
        ),
        (
            json!({"trigger": {"delay_s": 6.0}}),
            DeployTrigger::AfterBurnout { delay_s: 6.0 },
            0.0,
        ),
    ];
    for (json, trigger, lag_s) in cases {
        let d = chute_with(json.clone()).unwrap_or_else(|e| panic!("{json}: {e}"));
        assert_eq!(deploy_of(d), Some(Deploy { trigger, lag_s }), "{json}");
    }
    // Without `deploy` the design says nothing of it.
    assert_eq!(deploy_of(with(|_| {}).unwrap()), None);
    for bad in [
        json!({"trigger": "ejection"}),
        json!({"trigger": {"height_m": -1.0}}),
        json!({"trigger": {"height_m": 100.0, "time_s": 2.0}}),
        json!({"trigger": {"altitude_m": 100.0}}),
        json!({"trigger": 3}),
    ] {
        let (rule, _, field) = invalid(chute_with(bad.clone()));
        assert!(matches!(rule, Rule::DeployTrigger { .. }), "{bad}: {rule}");
        assert_eq!(field.as_deref(), Some("deploy.trigger"), "{bad}");
    }
    let (rule, _, field) = invalid(chute_with(json!({"trigger": "apogee", "lag_s": -1.0})));
    assert!(matches!(rule, Rule::Negative { .. }));
    assert_eq!(field.as_deref(), Some("deploy.lag_s"));
}

#[test]
fn a_design_file_with_a_byte_order_mark_loads_as_the_same_design() {
    let dir = std::env::temp_dir().join(format!("hpr-bom-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("design.json");
    let text = std::fs::read_to_string(example_path()).unwrap();
    std::fs::write(&path, format!("\u{feff}{text}")).unwrap();
    let with_mark = Design::load(&path).unwrap();
    let without = Design::load(example_path()).unwrap();
    assert_eq!(
        format!("{:?}", with_mark.components),
        format!("{:?}", without.components)
    );
    assert_eq!(with_mark.length_m, without.length_m);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_design_that_is_a_directory_or_never_ends_is_refused_saying_so() {
    let e = Design::load(std::env::temp_dir()).unwrap_err().to_string();
    assert!(
        e.ends_with("cannot read it: it is a directory, not a design file"),
        "{e}"
    );
    let e = Design::load("/dev/zero").unwrap_err().to_string();
    assert_eq!(
        e,
        "/dev/zero: cannot read it: it is larger than 64 MiB, the most hpr-mc reads for a design file"
    );
}
