//! Fins, motor mounts and launch lugs: their own rules.

use super::*;

#[test]
fn fins_with_a_tip_chord_need_a_root_chord() {
    let (rule, loc, field) = invalid(with(|v| {
        *at(v, &format!("{FINS}/root_chord_m")) = json!(0.0)
    }));
    assert_eq!(
        rule,
        Rule::FinRootChord {
            root_m: 0.0,
            tip_m: 0.05
        }
    );
    assert_eq!(
        (loc, field.as_deref()),
        (comp("fins"), Some("root_chord_m"))
    );
    let (rule, ..) = invalid(with(|v| *at(v, &format!("{FINS}/count")) = json!(0)));
    assert_eq!(
        rule,
        Rule::FinCount {
            got: 0,
            max: crate::design::validate::MAX_FINS
        }
    );
}

#[test]
fn a_design_has_one_motor_mount_whose_motors_are_centred_on_the_axis() {
    let (rule, loc, _) = invalid(with(|v| {
        let mut second = children(v)[1].clone();
        second["id"] = json!("mmt2");
        children(v).push(second);
    }));
    assert_eq!(
        rule,
        Rule::TwoMotorMounts {
            first: "mmt".into()
        }
    );
    assert_eq!(loc, comp("mmt2"));
    // Two tubes either side of the axis hold two motors.
    let d = with(|v| {
        children(v)[1]["cluster"] = json!([[0.0, 0.004], [0.0, -0.004]]);
    })
    .expect("a centred pair");
    assert_eq!(d.motor_mount.unwrap().motors, 2);
    assert_eq!(d.motor_offsets_m(), &[[0.0, 0.004], [0.0, -0.004]]);
    // Their centre 3 mm off the axis: refused, naming the cluster.
    let (rule, loc, field) = invalid(with(|v| {
        children(v)[1]["cluster"] = json!([[0.0, 0.0], [0.0, 0.006]]);
    }));
    assert!(
        matches!(rule, Rule::MotorMountOffAxis { offset_m, motors: 2 } if close(offset_m, 0.003)),
        "{rule:?}"
    );
    assert_eq!((loc, field.as_deref()), (comp("mmt"), Some("cluster")));
    assert!(
        rule.to_string().contains("centre of a cluster of 2 motors"),
        "{rule}"
    );
    // A single tube off the axis: refused, naming its offset.
    let (rule, _, field) = invalid(with(|v| children(v)[1]["radial_offset_m"] = json!(0.005)));
    assert!(
        matches!(rule, Rule::MotorMountOffAxis { offset_m, motors: 1 } if close(offset_m, 0.005)),
        "{rule:?}"
    );
    assert_eq!(field.as_deref(), Some("radial_offset_m"));
    let single = with(|_| {}).expect("the example");
    assert_eq!(single.motor_mount.unwrap().motors, 1);
    assert_eq!(single.motor_offsets_m(), &[[0.0, 0.0]]);
}

#[test]
fn a_cluster_s_offsets_are_resolved_about_the_rocket_s_axis() {
    let d = with(|v| {
        children(v).push(json!({"id": "pods", "type": "inner_tube", "length_m": 0.1, "outer_diameter_m": 0.01,
            "wall_thickness_m": 0.001, "mass_kg": 0.01, "radial_offset_m": 0.005, "radial_angle_deg": 90.0,
            "cluster": [[0.01, 0.0], [-0.01, 0.0]]}));
    })
    .expect("valid");
    let ComponentKind::InnerTube(t) = &d.component("pods").unwrap().kind else {
        panic!()
    };
    let o = &t.cluster_offsets_m;
    assert_eq!(o.len(), 2);
    assert!(
        close(o[0][0], 0.01)
            && close(o[0][1], 0.005)
            && close(o[1][0], -0.01)
            && close(o[1][1], 0.005),
        "{o:?}"
    );
}

#[test]
fn a_motor_must_fit_its_mount_and_the_error_says_which_is_too_big() {
    let d = Design::load(example_path()).unwrap();
    // The I175: 38 mm, 245 mm in a 38 mm × 0.3 m mount with 0.01 m overhang.
    d.motor_fits(0.038, 0.245).expect("the I175 fits");
    let e = d.motor_fits(0.054, 0.2).unwrap_err();
    assert!(
        matches!(e.rule(), Some(Rule::MotorTooWide { motor_diameter_m, .. }) if *motor_diameter_m == 0.054),
        "{e}"
    );
    assert!(e.to_string().contains("too wide"), "{e}");
    let e = d.motor_fits(0.038, 0.4).unwrap_err();
    assert!(
        matches!(e.rule(), Some(Rule::MotorTooLong { room_m, .. }) if close(*room_m, 0.31)),
        "{e}"
    );
    assert!(e.to_string().contains("too long"), "{e}");
    // As OpenRocket draws it, a longer motor sticks out past the mount's fore end; one too
    // wide is still refused.
    let openrocket = with(|v| v["geometry_checks"] = json!("openrocket")).unwrap();
    openrocket
        .motor_fits(0.038, 0.4)
        .expect("sticks out forward");
    assert!(matches!(
        openrocket.motor_fits(0.054, 0.2).unwrap_err().rule(),
        Some(Rule::MotorTooWide { .. })
    ));
    let no_mount = with(|v| {
        children(v)[1]
            .as_object_mut()
            .unwrap()
            .remove("motor_mount");
    })
    .unwrap();
    assert_eq!(
        no_mount.motor_fits(0.038, 0.245).unwrap_err().rule(),
        Some(&Rule::NoMotorMount)
    );
}

#[test]
fn a_single_launch_lug_gives_its_two_ends_as_the_rail_guides() {
    let d = with(|v| {
        let c = children(v);
        c.retain(|p| p["type"] != "rail_button");
        c.push(json!({"id": "lug", "type": "launch_lug", "length_m": 0.1, "outer_diameter_m": 0.01,
            "wall_thickness_m": 0.001, "mass_kg": 0.003, "position": {"from": "top", "offset_m": 0.5}}));
    })
    .unwrap();
    let (a, b) = d.rail_guides_m.unwrap();
    assert!(close(a, 0.75) && close(b, 0.85), "{a} {b}");
    let lug = d.component("lug").unwrap();
    assert!(close(lug.radial_offset_m[0], 0.0563 / 2.0 + 0.005));
}

#[test]
fn an_elliptical_fin_set_takes_no_tip_chord_or_sweep_and_a_trapezoidal_one_needs_its_tip() {
    // The example's fins made elliptical: root and span kept, tip and sweep removed.
    let elliptical = |v: &mut Value| {
        let fins = at(v, FINS).as_object_mut().expect("fins");
        fins.insert("planform".into(), json!("elliptical"));
        fins.remove("tip_chord_m");
        fins.remove("sweep_m");
    };
    let d = with(elliptical).expect("an elliptical fin set is valid");
    match &d.component("fins").expect("fins").kind {
        ComponentKind::FinSet(f) => {
            assert_eq!(f.planform, FinPlanform::Elliptical);
            assert_eq!(f.root_chord_m, 0.12);
        }
        other => panic!("{other:?}"),
    }
    for (field, value) in [("tip_chord_m", 0.05), ("sweep_m", 0.0)] {
        let (rule, loc, got) = invalid(with(|v| {
            elliptical(v);
            at(v, FINS)
                .as_object_mut()
                .unwrap()
                .insert(field.into(), json!(value));
        }));
        assert_eq!(
            rule,
            Rule::NotForPlanform {
                planform: "elliptical"
            }
        );
        assert_eq!((loc, got.as_deref()), (comp("fins"), Some(field)));
    }
    let (rule, loc, field) = invalid(with(|v| {
        at(v, FINS).as_object_mut().unwrap().remove("tip_chord_m");
    }));
    assert!(matches!(rule, Rule::Required { .. }), "{rule:?}");
    assert_eq!((loc, field.as_deref()), (comp("fins"), Some("tip_chord_m")));
    let e = with(|v| {
        elliptical(v);
        at(v, FINS)
            .as_object_mut()
            .unwrap()
            .insert("sweep_m".into(), json!(0.02));
    })
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("\"fins\"") && e.contains("sweep_m") && e.contains("\"elliptical\""),
        "{e}"
    );
    // An unknown planform is refused by name.
    let e = with(|v| {
        at(v, FINS)
            .as_object_mut()
            .unwrap()
            .insert("planform".into(), json!("freeform"));
    })
    .unwrap_err()
    .to_string();
    assert!(e.contains("freeform") && e.contains("elliptical"), "{e}");
}

#[test]
fn a_free_form_fin_set_is_its_outline_and_an_outline_that_is_not_one_is_refused_by_its_corner() {
    // The example's fins as a free-form outline: a clipped delta with a notch.
    let outline = |points: Value| {
        move |v: &mut Value| {
            let fins = at(v, FINS).as_object_mut().expect("fins");
            for field in ["root_chord_m", "tip_chord_m", "span_m", "sweep_m"] {
                fins.remove(field);
            }
            fins.insert("planform".into(), json!("free_form"));
            fins.insert("points_m".into(), points);
        }
    };
    let good = json!([
        [0.0, 0.0],
        [0.06, 0.07],
        [0.09, 0.07],
        [0.1, 0.04],
        [0.12, 0.0]
    ]);
    let d = with(outline(good.clone())).expect("a free-form fin set is valid");
    match &d.component("fins").expect("fins").kind {
        ComponentKind::FinSet(f) => {
            assert_eq!((f.root_chord_m, f.span_m), (0.12, 0.07));
            assert!(
                matches!(&f.planform, FinPlanform::FreeForm { points_m } if points_m.len() == 5)
            );
        }
        other => panic!("{other:?}"),
    }
    for (points, corner, why) in [
        (json!([[0.0, 0.0], [0.12, 0.0]]), 2, "at least three"),
        (
            json!([[0.01, 0.0], [0.06, 0.07], [0.12, 0.0]]),
            0,
            "leading edge",
        ),
        (
            json!([[0.0, 0.0], [0.06, 0.07], [0.12, 0.01]]),
            2,
            "trailing edge",
        ),
        (
            json!([[0.0, 0.0], [0.06, -0.01], [0.12, 0.0]]),
            1,
            "below the root",
        ),
        (
            json!([[0.0, 0.0], [0.06, 0.07], [0.06, 0.07], [0.12, 0.0]]),
            2,
            "repeats",
        ),
        (
            json!([[0.0, 0.0], [0.06, 0.0], [0.12, 0.0]]),
            1,
            "leave the root",
        ),
        // A bow tie: the third edge crosses the first.
        (
            json!([[0.0, 0.0], [0.1, 0.06], [0.02, 0.06], [0.12, 0.0]]),
            2,
            "crosses",
        ),
    ] {
        let (rule, loc, field) = invalid(with(outline(points.clone())));
        match rule {
            Rule::FinOutline { point, why: got } => {
                assert_eq!(point, corner, "{points}: {got}");
                assert!(got.contains(why), "{points}: {got}");
            }
            other => panic!("{points}: {other:?}"),
        }
        assert_eq!((loc, field.as_deref()), (comp("fins"), Some("points_m")));
    }
    // A free-form fin takes its sizes from its corners; a trapezoidal one takes no corners.
    let (rule, _, field) = invalid(with(|v| {
        outline(good.clone())(v);
        at(v, FINS)
            .as_object_mut()
            .unwrap()
            .insert("span_m".into(), json!(0.07));
    }));
    assert_eq!(
        rule,
        Rule::NotForPlanform {
            planform: "free_form"
        }
    );
    assert_eq!(field.as_deref(), Some("span_m"));
    let (rule, _, field) = invalid(with(|v| {
        at(v, FINS)
            .as_object_mut()
            .unwrap()
            .insert("points_m".into(), good.clone());
    }));
    assert_eq!(
        rule,
        Rule::NotForPlanform {
            planform: "trapezoidal"
        }
    );
    assert_eq!(field.as_deref(), Some("points_m"));
    let (rule, _, field) = invalid(with(|v| {
        outline(good.clone())(v);
        at(v, FINS).as_object_mut().unwrap().remove("points_m");
    }));
    assert!(matches!(rule, Rule::Required { .. }));
    assert_eq!(field.as_deref(), Some("points_m"));
}

#[test]
fn fins_that_reach_ahead_of_the_nose_tip_are_refused_in_either_geometry_check() {
    // A 2 m root chord on the 0.9 m body, bottom-aligned at 1.15 m: its leading edge would
    // be 0.85 m ahead of the tip (the center of pressure with it). Refused, not flown.
    for checks in ["strict", "openrocket"] {
        let r = with(|v| {
            v["geometry_checks"] = json!(checks);
            *at(v, &format!("{FINS}/root_chord_m")) = json!(2.0);
        });
        let (rule, loc, field) = invalid(r);
        let Rule::AheadOfNoseTip { top_m } = rule else {
            panic!("{checks}: {rule:?}")
        };
        assert!((top_m - (1.15 - 2.0)).abs() < 1e-12, "{checks}: {top_m}");
        assert_eq!((loc, field.as_deref()), (comp("fins"), Some("position")));
    }
    // The chord that just reaches the tip (1.15 m) is allowed.
    let d = with(|v| {
        *at(v, &format!("{FINS}/root_chord_m")) = json!(1.15);
        *at(v, &format!("{FINS}/tip_chord_m")) = json!(0.05);
    })
    .unwrap();
    assert!(d.component("fins").unwrap().x_top_m.abs() < 1e-12);
}

#[test]
fn an_internal_part_ahead_of_the_nose_tip_is_an_error_and_kept_with_a_warning_for_openrocket() {
    // The 5 cm ballast from 2 cm ahead of the tip to 3 cm aft of it: partly ahead.
    let ballast_ahead = |v: &mut Value| {
        *at(v, &format!("{BODY}/children/5/position")) =
            json!({"from": "nose_tip", "offset_m": -0.02});
    };
    let (rule, loc, _) = invalid(with(ballast_ahead));
    assert_eq!(rule, Rule::AheadOfNoseTip { top_m: -0.02 });
    assert_eq!(loc, comp("ballast"));
    let d = with(|v| {
        v["geometry_checks"] = json!("openrocket");
        ballast_ahead(v);
    })
    .unwrap();
    assert!(
        d.warnings
            .iter()
            .any(|w| w.contains("ahead of the nose tip")),
        "{:?}",
        d.warnings
    );
}
