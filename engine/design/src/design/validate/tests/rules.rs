//! Masses and overrides, the body a design needs, shapes' parameters, skins' roughness and
//! air brakes: their rules.

use super::*;

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

#[test]
fn a_part_further_outside_the_rocket_than_its_length_is_refused_even_where_openrocket_keeps_it() {
    // The ballast 4294967296 m aft of the tip (a fuzzed OpenRocket offset): kept with a
    // warning as outside its parent, it flew to an apogee of −1.2e9 m. Now refused.
    // (Strict checks refuse it first as outside its parent.)
    let (rule, loc, field) = invalid(with(|v| {
        v["geometry_checks"] = json!("openrocket");
        *at(v, "/stages/0/components/1/children/5/position") =
            json!({"from": "nose_tip", "offset_m": 4294967296.0});
    }));
    assert_eq!(loc, Location::Component("ballast".into()));
    assert_eq!(field.as_deref(), Some("position"));
    assert!(
        matches!(rule, Rule::OutsideRocket { top_m, length_m, .. }
            if top_m == 4294967296.0 && (length_m - 1.15).abs() < 1e-12),
        "{rule:?}"
    );
    // Past the tail, a rocket's length past it at most: kept where OpenRocket keeps it (a
    // weight drawn past the tail), with its warning; a little further, refused.
    let past = |offset_m: f64| {
        with(|v| {
            v["geometry_checks"] = json!("openrocket");
            *at(v, "/stages/0/components/1/children/5/position") =
                json!({"from": "nose_tip", "offset_m": offset_m});
        })
    };
    // (The 5 cm ballast ends a rocket's length past the tail at 2.25 m.)
    let kept = past(2.0 * 1.15 - 0.05).unwrap();
    assert!(
        kept.warnings[0].contains("lies entirely outside its parent"),
        "{:?}",
        kept.warnings
    );
    let (rule, ..) = invalid(past(2.0 * 1.15 - 0.05 + 1e-3));
    assert!(matches!(rule, Rule::OutsideRocket { .. }), "{rule:?}");
    // A part longer than the rocket by more than the rocket (a fuzzed 6 m inner tube in
    // this 1.15 m rocket, its fore end at the tail's fore end): refused too, in either check.
    for checks in ["strict", "openrocket"] {
        let (rule, loc, _) = invalid(with(|v| {
            v["geometry_checks"] = json!(checks);
            *at(v, "/stages/0/components/1/children/1/length_m") = json!(6.0);
            *at(v, "/stages/0/components/1/children/1/position") =
                json!({"from": "top", "offset_m": 0.0});
        }));
        assert_eq!(loc, Location::Component("mmt".into()), "{checks}");
        assert!(
            matches!(rule, Rule::OutsideRocket { .. }),
            "{checks}: {rule:?}"
        );
    }
    // A fin swept 19.8 m (a fuzzed sweep, within the size limit): its tip reaches 19.8 m
    // past the root, far past the tail: refused, the outline's reach named.
    let (rule, loc, _) = invalid(with(|v| {
        *at(v, "/stages/0/components/1/children/0/sweep_m") = json!(19.8);
    }));
    assert_eq!(loc, Location::Component("fins".into()));
    assert!(
        matches!(rule, Rule::OutsideRocket { top_m, bottom_m, .. }
            if (top_m - 1.03).abs() < 1e-9 && (bottom_m - (1.03 + 19.8 + 0.05)).abs() < 1e-9),
        "{rule:?}"
    );
}

#[test]
fn a_design_of_more_components_than_the_limit_is_refused_before_it_is_built() {
    // 1,001 body tubes (a fuzzed .ork of 11,881 nose cones took a minute to weigh).
    let r = with(|v| {
        let tube = v["stages"][0]["components"][1].clone();
        let comps = v["stages"][0]["components"].as_array_mut().unwrap();
        comps.truncate(1);
        for i in 0..1000 {
            let mut t = tube.clone();
            t["id"] = json!(format!("tube{i}"));
            t["children"] = json!([]);
            comps.push(t);
        }
    });
    let (rule, loc, field) = invalid(r);
    assert_eq!(rule, Rule::TooManyComponents { max: 1000 });
    assert_eq!((loc, field.as_deref()), (Location::Design, Some("stages")));
}
