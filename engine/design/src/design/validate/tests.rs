//! Validation: the example parses with every position resolved, and every refusal names the
//! component, the field and the rule.

use crate::design::model::*;
use crate::error::{DesignError, Location, Rule};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

mod parts;

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
    // At 1.12 it is partly outside: allowed (the moving-mass spec relies on it).
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
fn drag_tables_must_have_mach_strictly_increasing() {
    let (rule, loc, field) = invalid(with(|v| *at(v, "/drag/power_off/2/0") = json!(0.3)));
    assert_eq!(
        rule,
        Rule::MachNotIncreasing {
            row: 2,
            previous: 0.3,
            got: 0.3
        }
    );
    assert_eq!((loc, field.as_deref()), (Location::Drag, Some("power_off")));
    let (rule, ..) = invalid(with(|v| *at(v, "/drag/power_off") = json!([])));
    assert_eq!(rule, Rule::EmptyTable);
    let (rule, ..) = invalid(with(|v| {
        at(v, "/drag")
            .as_object_mut()
            .unwrap()
            .insert("estimate".into(), json!({}));
    }));
    assert_eq!(rule, Rule::DragModelNotExactlyOne { given: 2 });
    let d = with(|v| *at(v, "/drag") = json!({"estimate": {"roughness_m": 20e-6}})).unwrap();
    assert_eq!(d.drag, DragSpec::Estimate { roughness_m: 20e-6 });
    let d = with(|v| {
        v.as_object_mut().unwrap().remove("drag");
    })
    .unwrap();
    assert_eq!(
        d.drag,
        DragSpec::Estimate {
            roughness_m: super::DEFAULT_ROUGHNESS_M
        }
    );
}

#[test]
fn drag_csvs_are_read_relative_to_the_design_file() {
    let dir = std::env::temp_dir().join(format!("hpr-design-csv-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("data")).unwrap();
    std::fs::write(
        dir.join("data/off.csv"),
        "mach,cd\n0.0,0.5\n# a comment\n0.5, 0.52\n\n1.0,0.7\n",
    )
    .unwrap();
    std::fs::write(dir.join("data/bad.csv"), "0.0,0.5\n0.5,0.52\n0.4,0.7\n").unwrap();
    let mut v = example_value();
    v["drag"] = json!({"power_off_csv": "data/off.csv", "power_on": [[0.0, 0.4], [2.0, 0.5]]});
    let design_path = dir.join("rocket.json");
    let d = Design::from_json_str(&v.to_string(), Some(&design_path)).expect("valid");
    assert_eq!(
        d.drag,
        DragSpec::Curves {
            power_off: vec![(0.0, 0.5), (0.5, 0.52), (1.0, 0.7)],
            power_on: vec![(0.0, 0.4), (2.0, 0.5)]
        }
    );
    v["drag"] = json!({"power_off_csv": "data/bad.csv"});
    let e = Design::from_json_str(&v.to_string(), Some(&design_path)).unwrap_err();
    let DesignError::Csv {
        file,
        line,
        message,
    } = &e
    else {
        panic!("{e}")
    };
    assert!(file.ends_with("bad.csv") && *line == 3, "{e}");
    assert!(message.contains("strictly increasing"), "{e}");
    v["drag"] = json!({"power_off_csv": "data/missing.csv"});
    let e = Design::from_json_str(&v.to_string(), Some(&design_path)).unwrap_err();
    assert!(
        matches!(e, DesignError::Io { ref file, .. } if file.ends_with("missing.csv")),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_rasaero_export_gives_its_power_off_and_power_on_curves_at_zero_angle_of_attack() {
    // RASAero II's aerodynamic export: a row per Mach number and angle of attack, the drag
    // with the motor off and burning in their own columns.
    let dir = std::env::temp_dir().join(format!("hpr-design-rasaero-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let header = "Mach,Alpha,CD,CD Power-Off,CD Power-On,CA Power-Off,CA Power-On,CL,CN,\
                  CN Potential,CN Viscous,Cn alpha (0-4 deg) (per rad),CP,CP 0-4 deg,\
                  Reynolds Number";
    let row = |mach: f64, alpha: f64, off: f64, on: f64| {
        format!("{mach},{alpha},{off},{off},{on},{off},{on},0,0,0,0,10.5,30.1,30.2,1e6\n")
    };
    let mut text = format!("{header}\n");
    for (mach, off, on) in [(0.01, 0.61, 0.52), (0.5, 0.55, 0.47), (1.2, 0.83, 0.71)] {
        for alpha in [0.0, 2.0, 4.0] {
            // At 2 and 4 degrees the drag grows: those rows must not be read.
            text += &row(mach, alpha, off + alpha * 0.01, on + alpha * 0.01);
        }
    }
    std::fs::write(dir.join("ras.csv"), &text).unwrap();
    let design_path = dir.join("rocket.json");
    let mut v = example_value();
    v["drag"] = json!({"power_off_csv": "ras.csv"});
    let d = Design::from_json_str(&v.to_string(), Some(&design_path)).expect("valid");
    assert_eq!(
        d.drag,
        DragSpec::Curves {
            power_off: vec![(0.01, 0.61), (0.5, 0.55), (1.2, 0.83)],
            power_on: vec![(0.01, 0.52), (0.5, 0.47), (1.2, 0.71)]
        }
    );
    // A power-on curve given beside it wins; the file can also give just the power-on one.
    v["drag"] = json!({"power_off_csv": "ras.csv", "power_on": [[0.0, 0.4]]});
    let d = Design::from_json_str(&v.to_string(), Some(&design_path)).expect("valid");
    assert!(matches!(&d.drag, DragSpec::Curves { power_on, .. } if power_on == &vec![(0.0, 0.4)]));
    v["drag"] = json!({"power_off": [[0.0, 0.5]], "power_on_csv": "ras.csv"});
    let d = Design::from_json_str(&v.to_string(), Some(&design_path)).expect("valid");
    assert!(matches!(&d.drag, DragSpec::Curves { power_on, .. }
        if power_on == &vec![(0.01, 0.52), (0.5, 0.47), (1.2, 0.71)]));
    // A broken row names its line; a file with no row at zero angle of attack is refused.
    std::fs::write(
        dir.join("bad.csv"),
        format!(
            "{header}\n{}0.5,0,0.5,x,0.4,0,0,0,0,0,0,0,0,0,0\n",
            row(0.01, 0.0, 0.6, 0.5)
        ),
    )
    .unwrap();
    v["drag"] = json!({"power_off_csv": "bad.csv"});
    let e = Design::from_json_str(&v.to_string(), Some(&design_path)).unwrap_err();
    assert!(matches!(&e, DesignError::Csv { line: 3, .. }), "{e}");
    std::fs::write(
        dir.join("tilted.csv"),
        format!("{header}\n{}", row(0.01, 2.0, 0.6, 0.5)),
    )
    .unwrap();
    v["drag"] = json!({"power_off_csv": "tilted.csv"});
    let e = Design::from_json_str(&v.to_string(), Some(&design_path)).unwrap_err();
    assert!(e.to_string().contains("without rows at Alpha 0"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
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
fn a_fin_s_airfoil_lift_table_gives_rocketpy_s_slope() {
    // RocketPy's NACA 0012 table (validation/rocketpy/data), read as RocketPy reads it: the
    // slope of the linear table at 0.001 rad, 6.302535573086407 /rad in RocketPy 1.13
    // (barrowman_reference.json), against a flat plate's 2π.
    let naca = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../validation/rocketpy/data/NACA0012-radians.txt"
    );
    let rocketpy = 6.302535573086407;
    let fins_with = |airfoil: Value| {
        with(|v| {
            at(v, FINS)["airfoil"] = airfoil;
        })
    };
    let slope = |d: Design| {
        let i = d.component_index("fins").unwrap();
        match &d.components[i].kind {
            ComponentKind::FinSet(f) => f.lift_slope_2d_per_rad,
            _ => unreachable!(),
        }
    };
    assert_eq!(slope(with(|_| {}).unwrap()), 2.0 * std::f64::consts::PI);
    let got = slope(fins_with(json!({"csv": naca, "angles": "radians"})).unwrap());
    assert!((got / rocketpy - 1.0).abs() < 1e-15, "{got}");
    // The same table in degrees gives the same slope per radian.
    let dir = std::env::temp_dir().join(format!("hpr-airfoil-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let degrees: String = std::fs::read_to_string(naca)
        .unwrap()
        .lines()
        .map(|l| {
            let (a, cl) = l.split_once(',').unwrap();
            format!("{},{cl}\n", a.trim().parse::<f64>().unwrap().to_degrees())
        })
        .collect();
    let deg_file = dir.join("naca-deg.csv");
    std::fs::write(&deg_file, format!("alpha_deg,cl\n{degrees}")).unwrap();
    let got = slope(fins_with(json!({"csv": deg_file, "angles": "degrees"})).unwrap());
    assert!((got / rocketpy - 1.0).abs() < 1e-12, "{got}");
    let given = slope(fins_with(json!({"lift_slope_per_rad": 6.1})).unwrap());
    assert_eq!(given, 6.1);
    // Refusals: both, neither, no unit, a non-increasing table.
    for bad in [
        json!({"lift_slope_per_rad": 6.1, "csv": naca}),
        json!({}),
        json!({"csv": naca}),
        json!({"lift_slope_per_rad": 6.1, "angles": "radians"}),
    ] {
        let (rule, _, field) = invalid(fins_with(bad.clone()));
        assert!(matches!(rule, Rule::Airfoil { .. }), "{bad}: {rule}");
        assert!(field.unwrap().starts_with("airfoil"), "{bad}");
    }
    let (rule, _, field) = invalid(fins_with(json!({"lift_slope_per_rad": -1.0})));
    assert!(matches!(rule, Rule::NotPositive { .. }));
    assert_eq!(field.as_deref(), Some("airfoil.lift_slope_per_rad"));
    let back = dir.join("back.csv");
    std::fs::write(&back, "0.0,0.0\n0.1,0.6\n0.05,0.7\n").unwrap();
    let e = fins_with(json!({"csv": back, "angles": "radians"})).unwrap_err();
    assert!(matches!(&e, DesignError::Csv { line: 3, .. }), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_trapezoidal_fin_s_sweep_may_be_its_leading_edge_angle_as_rocketpy_gives_it() {
    // The example's fins: span 0.07 m, the tip's leading edge 0.06 m behind the root's, so
    // Γ = atan(0.06/0.07); RocketPy's x_t = s tan Γ gives the 0.06 m back.
    let deg = (0.06f64 / 0.07).atan().to_degrees();
    let d = with(|v| {
        let fins = at(v, FINS).as_object_mut().unwrap();
        fins.remove("sweep_m");
        fins.insert("sweep_deg".into(), json!(deg));
    })
    .unwrap();
    let i = d.component_index("fins").unwrap();
    let ComponentKind::FinSet(f) = &d.components[i].kind else {
        unreachable!()
    };
    let FinPlanform::Trapezoidal { sweep_m, .. } = f.planform else {
        unreachable!()
    };
    assert!((sweep_m - 0.06).abs() < 1e-15, "{sweep_m}");
    let (rule, _, field) = invalid(with(|v| {
        at(v, FINS)["sweep_deg"] = json!(deg);
    }));
    assert!(matches!(rule, Rule::AtMostOneOf { .. }), "{rule}");
    assert_eq!(field.as_deref(), Some("sweep_deg"));
    let (rule, _, field) = invalid(with(|v| {
        let fins = at(v, FINS).as_object_mut().unwrap();
        fins.remove("sweep_m");
        fins.insert("sweep_deg".into(), json!(90.0));
    }));
    assert!(matches!(rule, Rule::OutOfRange { .. }), "{rule}");
    assert_eq!(field.as_deref(), Some("sweep_deg"));
}

#[test]
fn a_component_s_override_may_weigh_nothing_but_not_less_and_a_stage_s_must_weigh_something() {
    let zero = with(|v| {
        at(v, BODY)
            .as_object_mut()
            .unwrap()
            .insert("override".into(), json!({"mass_kg": 0.0}));
    });
    let zero = zero.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(zero.components[1].overrides.mass_kg, Some(0.0));
    let (rule, loc, field) = invalid(with(|v| {
        at(v, BODY)
            .as_object_mut()
            .unwrap()
            .insert("override".into(), json!({"mass_kg": -0.5}));
    }));
    assert_eq!(rule, Rule::Negative { got: -0.5 });
    assert_eq!(
        (loc, field.as_deref()),
        (comp("body"), Some("override.mass_kg"))
    );
    let (rule, loc, _) = invalid(with(|v| {
        at(v, "/stages/0")
            .as_object_mut()
            .unwrap()
            .insert("override".into(), json!({"mass_kg": 0.0}));
    }));
    assert_eq!(rule, Rule::NotPositive { got: 0.0 });
    assert_eq!(loc, Location::Stage("sustainer".into()));
    let (rule, loc, _) = invalid(with(|v| {
        at(v, "/stages/0")
            .as_object_mut()
            .unwrap()
            .insert("override".into(), json!({"mass_kg": -1.0}));
    }));
    assert_eq!(rule, Rule::NotPositive { got: -1.0 });
    assert_eq!(loc, Location::Stage("sustainer".into()));
}

#[test]
fn a_design_without_a_body_component_is_refused() {
    let (rule, loc, _) = invalid(with(|v| *at(v, "/stages") = json!([])));
    assert_eq!((rule, loc), (Rule::NoBodyComponent, Location::Design));
    let (rule, loc, _) = invalid(with(|v| *at(v, "/stages/0/components") = json!([])));
    assert_eq!(
        (rule, loc),
        (Rule::NoBodyComponent, Location::Stage("sustainer".into()))
    );
}

#[test]
fn a_mass_is_given_exactly_one_way() {
    let (rule, loc, _) = invalid(with(|v| at(v, BODY)["mass_kg"] = json!(0.1)));
    assert_eq!(
        rule,
        Rule::MassSpecNotExactlyOne {
            options: "\"material.density_kg_m3\" and \"mass_kg\"",
            given: 2
        }
    );
    assert_eq!(loc, comp("body"));
    let (rule, ..) = invalid(with(|v| {
        at(v, BODY).as_object_mut().unwrap().remove("material");
    }));
    assert!(
        matches!(rule, Rule::MassSpecNotExactlyOne { given: 0, .. }),
        "{rule:?}"
    );
    // A shock cord by its linear density needs the cord's length.
    let (rule, ..) = invalid(with(|v| {
        children(v).push(
            json!({"id": "cord", "type": "shock_cord", "length_m": 0.05, "radius_m": 0.015,
            "linear_density_kg_m": 0.01}),
        );
    }));
    assert_eq!(
        rule,
        Rule::NeedsField {
            other: "cord_length_m"
        }
    );
    let d = with(|v| {
        children(v).push(
            json!({"id": "cord", "type": "shock_cord", "length_m": 0.05, "radius_m": 0.015,
            "linear_density_kg_m": 0.01, "cord_length_m": 3.0}),
        );
    })
    .unwrap();
    assert_eq!(
        d.component("cord").unwrap().mass_spec,
        MassSpec::LinearDensity {
            kg_per_m: 0.01,
            cord_length_m: 3.0
        }
    );
}

#[test]
fn shapes_take_only_their_own_parameter() {
    // The nose of the example with `shape` and `shape_parameter`.
    let nose = |shape: &str, p: f64| {
        with(|v| {
            let nose = at(v, "/stages/0/components/0");
            nose["shape"] = json!(shape);
            nose["shape_parameter"] = json!(p);
        })
    };
    let shape_of = |d: Design| match &d.components[0].kind {
        ComponentKind::NoseCone(n) => n.shape,
        _ => panic!("the first component is the nose cone"),
    };
    let (rule, ..) = invalid(nose("elliptical", 0.5));
    assert_eq!(
        rule,
        Rule::ShapeTakesNoParameter {
            shape: "elliptical"
        }
    );
    // An ogive's parameter is OpenRocket's: 1 (the default) the tangent ogive, below it a
    // secant ogive, above it refused.
    assert_eq!(shape_of(nose("ogive", 1.0).unwrap()), NoseShape::Ogive);
    assert_eq!(
        shape_of(nose("ogive", 0.4).unwrap()),
        NoseShape::SecantOgive { p: 0.4 }
    );
    let (rule, _, field) = invalid(nose("ogive", 1.2));
    assert_eq!(
        rule,
        Rule::OutOfRange {
            got: 1.2,
            min: 0.0,
            max: 1.0
        }
    );
    assert_eq!(field.as_deref(), Some("shape_parameter"));
    assert_eq!(
        shape_of(nose("power_series", 0.75).unwrap()),
        NoseShape::PowerSeries { k: 0.75 }
    );
    let (rule, ..) = invalid(nose("haack", 1.5));
    assert_eq!(
        rule,
        Rule::OutOfRange {
            got: 1.5,
            min: 0.0,
            max: 1.0
        }
    );
}

#[test]
fn a_skin_s_own_roughness_must_not_be_negative_and_only_skins_may_give_one() {
    let d = with(|v| at(v, FINS)["roughness_m"] = json!(2e-6))
        .expect("a fin set's own roughness is accepted");
    let fins = d.component_index("fins").unwrap();
    assert_eq!(d.components[fins].roughness_m, Some(2e-6));
    let (rule, loc, f) = invalid(with(|v| at(v, BODY)["roughness_m"] = json!(-1e-6)));
    assert_eq!(rule, Rule::Negative { got: -1e-6 });
    assert_eq!((loc, f.as_deref()), (comp("body"), Some("roughness_m")));
    // A part inside has no skin in the air: the field is unknown there.
    let e = with(|v| at(v, &format!("{BODY}/children/5"))["roughness_m"] = json!(2e-6))
        .expect_err("a mass component gives no roughness");
    assert!(e.to_string().contains("roughness_m"), "{e}");
}

#[test]
fn air_brakes_take_their_area_from_the_rocket_unless_given_and_refuse_bad_numbers_by_field() {
    let d = with(|v| {
        v["air_brakes"] = json!({"cd": 1.1, "target_apogee_m": 1500.0, "sampling_rate_hz": 20.0});
    })
    .expect("brakes");
    let b = d.air_brakes.expect("the design's brakes");
    let area = std::f64::consts::PI * 0.25 * d.reference_diameter_m * d.reference_diameter_m;
    assert_eq!(
        (
            b.cd,
            b.reference_area_m2,
            b.target_apogee_m,
            b.sampling_rate_hz
        ),
        (1.1, area, 1500.0, 20.0)
    );
    assert!(with(|_| {}).unwrap().air_brakes.is_none());
    for (field, value) in [
        ("cd", json!(-0.1)),
        ("reference_area_m2", json!(0.0)),
        ("target_apogee_m", json!(-5.0)),
        ("sampling_rate_hz", json!(0.0)),
        ("sampling_rate_hz", json!(1e300)),
    ] {
        let (_, loc, got) = invalid(with(|v| {
            v["air_brakes"] =
                json!({"cd": 1.1, "target_apogee_m": 1500.0, "sampling_rate_hz": 20.0});
            v["air_brakes"][field] = value.clone();
        }));
        assert_eq!(loc, Location::Design);
        assert_eq!(got.as_deref(), Some(format!("air_brakes.{field}").as_str()));
    }
    // A controller sampling faster than any flight computer would end a step at every
    // sample: 10 kHz is the most, and it is allowed.
    let brakes_at = |rate: f64| {
        with(|v| {
            v["air_brakes"] =
                json!({"cd": 1.1, "target_apogee_m": 1500.0, "sampling_rate_hz": rate});
        })
    };
    assert_eq!(
        brakes_at(10_000.0)
            .unwrap()
            .air_brakes
            .unwrap()
            .sampling_rate_hz,
        10_000.0
    );
    let (rule, _, _) = invalid(brakes_at(10_001.0));
    assert_eq!(
        rule,
        Rule::OutOfRange {
            got: 10_001.0,
            min: 0.0,
            max: 10_000.0
        }
    );
    let e = with(|v| {
        v["air_brakes"] = json!({"cd": 1.1, "target_apogee_m": 1500.0, "sampling_rate": 20.0});
    })
    .unwrap_err();
    assert!(
        e.to_string().contains("unknown field `sampling_rate`"),
        "{e}"
    );
}
