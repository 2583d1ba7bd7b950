//! A design's mass: components against hand calculations, overrides, and a part moved by the
//! moving-mass formula against the design rebuilt with the part moved.

use super::*;
use crate::mass::{moved_part, solids};
use serde_json::{json, Value};
use std::f64::consts::PI;
use std::path::Path;

fn example() -> Value {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../validation/designs/example-minimal.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn design(v: &Value) -> Design {
    Design::from_json_str(&v.to_string(), None).unwrap_or_else(|e| panic!("{e}"))
}

/// One body tube 0.5 m long (od 0.06, wall 0.002) from the nose... preceded by a 0.1 m
/// conical nose, with the given children.
fn simple(tube_extra: Value, children: Value) -> Value {
    let mut tube = json!({"id": "tube", "type": "body_tube", "length_m": 0.5, "outer_diameter_m": 0.06,
        "wall_thickness_m": 0.002, "mass_kg": 0.3, "children": children});
    for (k, v) in tube_extra.as_object().unwrap() {
        tube[k] = v.clone();
    }
    json!({"name": "simple", "stages": [{"id": "s", "components": [
        {"id": "nose", "type": "nose_cone", "shape": "conical", "length_m": 0.1, "base_diameter_m": 0.06,
         "filled": true, "mass_kg": 0.1},
        tube
    ]}]})
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn a_tube_given_by_mass_spreads_it_over_its_shape() {
    let d = design(&simple(json!({}), json!([])));
    let own = component_own(&d, 1);
    let hand =
        solids::hollow_cylinder(0.3, 0.03, 0.028, 0.5).translated(&Vector3::new(0.1, 0.0, 0.0));
    assert_eq!(own.mass_kg, 0.3);
    assert!((own.cg_m.x - 0.35).abs() < 1e-15);
    assert!(rel(own.axial_inertia(), 0.3 * (0.0009 + 0.000784) / 2.0) < 1e-14);
    assert!((own.inertia_cg - hand.inertia_cg).amax() < 1e-17);
}

#[test]
fn a_filled_nose_with_a_capped_shoulder_weighs_its_three_pieces() {
    // Conical, filled, L 0.2, R 0.03, 1000 kg/m³; shoulder 0.04 long, od 0.056, wall 0.002,
    // capped by a disc of the inner radius 0.026, 0.002 thick, at its aft end.
    let v = json!({"name": "n", "stages": [{"id": "s", "components": [
        {"id": "nose", "type": "nose_cone", "shape": "conical", "length_m": 0.2, "base_diameter_m": 0.06,
         "filled": true, "material": {"density_kg_m3": 1000.0},
         "shoulder": {"length_m": 0.04, "outer_diameter_m": 0.056, "wall_thickness_m": 0.002, "capped": true}}
    ]}]});
    let own = component_own(&design(&v), 0);
    // Volumes / π: cone 0.03² 0.2/3 = 6e-5; tube (0.028² − 0.026²) 0.04 = 4.32e-6;
    // cap 0.026² 0.002 = 1.352e-6. Centers: 0.15, 0.22, 0.239.
    let (v1, v2, v3) = (6e-5, 4.32e-6, 1.352e-6);
    let mass = 1000.0 * PI * (v1 + v2 + v3);
    let cg = (v1 * 0.15 + v2 * 0.22 + v3 * 0.239) / (v1 + v2 + v3);
    assert!(rel(own.mass_kg, mass) < 1e-12, "{} vs {mass}", own.mass_kg);
    assert!(rel(own.cg_m.x, cg) < 1e-12, "{} vs {cg}", own.cg_m.x);
    // Axial: cone 3/10 m R², tube m (ro² + ri²)/2, disc m r²/2.
    let axial =
        1000.0 * PI * (v1 * 0.3 * 0.0009 + v2 * (0.000784 + 0.000676) / 2.0 + v3 * 0.000676 / 2.0);
    assert!(rel(own.axial_inertia(), axial) < 1e-12);
}

#[test]
fn an_override_of_mass_scales_the_inertia_and_one_of_the_center_keeps_it() {
    let plain = design(&simple(json!({}), json!([])));
    let base = component_own(&plain, 1);
    let d = design(&simple(json!({"override": {"mass_kg": 0.6}}), json!([])));
    let s = subtree(&d, 1);
    assert_eq!(s.mass_kg, 0.6);
    assert_eq!(s.cg_m, base.cg_m);
    assert!((s.inertia_cg - base.inertia_cg * 2.0).amax() < 1e-17);
    // The center 0.1 m aft of the tube's top: 0.2 m aft of the tip, inertia unchanged.
    let d = design(&simple(json!({"override": {"cg_m": 0.1}}), json!([])));
    let s = subtree(&d, 1);
    assert_eq!(s.mass_kg, 0.3);
    assert!((s.cg_m.x - 0.2).abs() < 1e-16);
    assert_eq!(s.inertia_cg, base.inertia_cg);
}

#[test]
fn an_override_covering_children_replaces_the_subtree_s_total() {
    let ballast = json!([{"id": "w", "type": "mass_component", "mass_kg": 0.2, "length_m": 0.04, "radius_m": 0.02,
        "position": {"from": "top", "offset_m": 0.0}}]);
    let d = design(&simple(json!({}), ballast.clone()));
    // Without override: tube 0.3 at 0.35 and weight 0.2 at 0.12: total 0.5 at 0.258.
    let total = subtree(&d, 1);
    assert!(rel(total.mass_kg, 0.5) < 1e-15);
    assert!(rel(total.cg_m.x, (0.3 * 0.35 + 0.2 * 0.12) / 0.5) < 1e-15);

    let over = design(&simple(
        json!({"override": {"mass_kg": 1.0, "cg_m": 0.3, "covers_children": true}}),
        ballast.clone(),
    ));
    let s = subtree(&over, 1);
    assert_eq!(s.mass_kg, 1.0);
    assert!((s.cg_m.x - 0.4).abs() < 1e-16);
    assert!((s.inertia_cg - total.inertia_cg * 2.0).amax() < 1e-16);
    // Not covering: the tube's own mass becomes 1.0, the weight is added on top.
    let own_only = design(&simple(json!({"override": {"mass_kg": 1.0}}), ballast));
    assert!(rel(subtree(&own_only, 1).mass_kg, 1.2) < 1e-15);
}

#[test]
fn an_override_of_zero_makes_the_component_or_its_subtree_weigh_nothing() {
    // OpenRocket's zero override (a part drawn for its looks): the tube alone, then the tube
    // and the weight it holds, weigh nothing; the nose (0.1 kg at 0.075 m, 3/4 of a cone
    // 0.1 long) is all that is left of the rocket in the second case.
    let ballast = json!([{"id": "w", "type": "mass_component", "mass_kg": 0.2, "length_m": 0.04, "radius_m": 0.02,
        "position": {"from": "top", "offset_m": 0.0}}]);
    let own_only = design(&simple(
        json!({"override": {"mass_kg": 0.0}}),
        ballast.clone(),
    ));
    let s = subtree(&own_only, 1);
    assert_eq!(s.mass_kg, 0.2);
    assert!((s.cg_m.x - 0.12).abs() < 1e-16);
    let all = design(&simple(
        json!({"override": {"mass_kg": 0.0, "covers_children": true}}),
        ballast,
    ));
    assert_eq!(subtree(&all, 1).mass_kg, 0.0);
    assert_eq!(subtree(&all, 1).inertia_cg, Matrix3::zeros());
    let rocket = dry(&all);
    assert_eq!(rocket.mass_kg, 0.1);
    assert!((rocket.cg_m.x - 0.075).abs() < 1e-15);
}

#[test]
fn an_override_of_what_weighs_nothing_spreads_its_mass_as_the_shape_does() {
    // A tube drawn weighing nothing, its mass given by an override (OpenRocket puts the
    // override at the component's center): the same tube as one of that mass (to rounding),
    // covering its (empty) children or not.
    let given = subtree(&design(&simple(json!({"mass_kg": 0.5}), json!([]))), 1);
    for covers in [false, true] {
        let over = design(&simple(
            json!({"mass_kg": 0.0, "override": {"mass_kg": 0.5, "covers_children": covers}}),
            json!([]),
        ));
        let got = subtree(&over, 1);
        assert!(rel(got.mass_kg, 0.5) < 1e-15, "covers_children {covers}");
        assert_eq!(got.cg_m, given.cg_m);
        assert!((got.inertia_cg - given.inertia_cg).amax() < 1e-17);
    }
}

#[test]
fn a_stage_override_applies_to_the_whole_stage() {
    let mut v = simple(json!({}), json!([]));
    v["stages"][0]["override"] = json!({"mass_kg": 2.0, "cg_m": 0.25});
    let d = design(&v);
    let plain = design(&simple(json!({}), json!([])));
    let before = stage(&plain, 0);
    let after = stage(&d, 0);
    assert_eq!(after.mass_kg, 2.0);
    assert_eq!(after.cg_m.x, 0.25);
    assert!((after.inertia_cg - before.inertia_cg * (2.0 / before.mass_kg)).amax() < 1e-16);
    assert_eq!(dry(&d), after);
}

#[test]
fn a_rail_button_stands_on_the_body_with_its_axis_radial_and_counts_spread_round_the_axis() {
    let d = design(&simple(
        json!({}),
        json!([{"id": "b", "type": "rail_button", "outer_diameter_m": 0.01, "height_m": 0.008, "mass_kg": 0.004,
                "angle_deg": 90.0, "position": {"from": "top", "offset_m": 0.2}}]),
    ));
    let b = component_own(&d, 2);
    // Its center at x = 0.1 + 0.2 + 0.005, at 90° (+z), R + h/2 = 0.034 off the axis, spread
    // round the axis: the center on the axis.
    assert_eq!(b.mass_kg, 0.004);
    assert!(
        (b.cg_m - Vector3::new(0.305, 0.0, 0.0)).amax() < 1e-16,
        "{}",
        b.cg_m
    );
    // The solid cylinder r 0.005, h 0.008 along z: about its center I_zz = m r²/2,
    // I_xx = I_yy = m (3 r² + h²)/12. About the axis point: + m 0.034² on I_xx and I_yy. Spread:
    // I_xx kept, I_yy = I_zz = their mean, no products.
    let (m, r, h, off) = (0.004, 0.005, 0.008, 0.034);
    let side = m * (3.0 * r * r + h * h) / 12.0;
    let mean = 0.5 * (side + m * off * off + m * r * r / 2.0);
    assert!(rel(b.inertia_cg[(0, 0)], side + m * off * off) < 1e-14);
    assert!(rel(b.inertia_cg[(1, 1)], mean) < 1e-14);
    assert!(rel(b.inertia_cg[(2, 2)], mean) < 1e-14);
    let products = [(0, 1), (0, 2), (1, 2), (1, 0), (2, 0), (2, 1)];
    assert!(products.iter().all(|&ij| b.inertia_cg[ij] == 0.0));
}

#[test]
fn a_launch_lug_and_rail_buttons_leave_the_center_of_mass_on_the_axis() {
    let d = design(&simple(
        json!({}),
        json!([{"id": "b1", "type": "rail_button", "outer_diameter_m": 0.01, "height_m": 0.008, "mass_kg": 0.004,
                "angle_deg": 30.0, "position": {"from": "top", "offset_m": 0.1}},
               {"id": "b2", "type": "rail_button", "outer_diameter_m": 0.01, "height_m": 0.008, "mass_kg": 0.004,
                "angle_deg": 30.0, "position": {"from": "top", "offset_m": 0.3}},
               {"id": "lug", "type": "launch_lug", "length_m": 0.05, "outer_diameter_m": 0.01,
                "wall_thickness_m": 0.001, "mass_kg": 0.01, "angle_deg": 200.0,
                "position": {"from": "top", "offset_m": 0.2}}]),
    ));
    let all = dry(&d);
    // Exactly on the axis: the body is axisymmetric and every guide is spread round it.
    assert_eq!((all.cg_m.y, all.cg_m.z), (0.0, 0.0));
    assert!((all.inertia_cg[(1, 1)] - all.inertia_cg[(2, 2)]).abs() < 1e-18);
}

#[test]
fn a_shock_cord_weighs_its_linear_density_times_its_length_and_a_given_inertia_is_kept() {
    let d = design(&simple(
        json!({}),
        json!([{"id": "cord", "type": "shock_cord", "length_m": 0.05, "radius_m": 0.015,
                "linear_density_kg_m": 0.01, "cord_length_m": 3.0, "inertia_kg_m2": [1e-5, 2e-5]}]),
    ));
    let c = component_own(&d, 2);
    assert!(rel(c.mass_kg, 0.03) < 1e-15);
    assert!((c.cg_m.x - 0.125).abs() < 1e-16);
    assert_eq!(
        c.inertia_cg,
        Matrix3::from_diagonal(&Vector3::new(1e-5, 2e-5, 2e-5))
    );
}

#[test]
fn the_dry_mass_is_the_sum_of_every_part_without_overrides() {
    let d = design(&example());
    let rows = mass_table(&d);
    assert_eq!(rows.len(), d.components.len());
    let sum: f64 = rows.iter().map(|r| r.own.mass_kg).sum();
    let whole = dry(&d);
    assert!(rel(whole.mass_kg, sum) < 1e-14);
    // Summed by the parallel-axis theorem about the tip, part by part.
    let about_tip: Matrix3<f64> = rows.iter().map(|r| r.own.inertia_about_tip()).sum();
    assert!((whole.inertia_about_tip() - about_tip).amax() < 1e-14 * about_tip.amax());
    let ballast = rows.iter().find(|r| r.id == "ballast").unwrap();
    assert_eq!((ballast.depth, ballast.own.mass_kg), (1, 0.2));
    assert!((ballast.own.cg_m.x - 0.375).abs() < 1e-15);
    assert_eq!(rows[1].subtree, subtree(&d, 1));
}

#[test]
fn a_part_moved_in_the_example_matches_the_design_rebuilt_with_it_moved() {
    // The worked example's move (`docs/moving-mass.md`): the ballast 0.3 m aft.
    let d = design(&example());
    let whole = dry(&d);
    let ballast = subtree(&d, d.component_index("ballast").unwrap());
    let moved = moved_part(&whole, &ballast, &Vector3::new(0.3, 0.0, 0.0));
    let mut v = example();
    v["stages"][0]["components"][1]["children"][5]["position"]["offset_m"] = json!(0.65);
    let rebuilt = dry(&design(&v));
    assert!(rel(moved.mass_kg, rebuilt.mass_kg) < 1e-15);
    // Two routes of summation: rounding of a few 1e-17 on values of order 0.1.
    assert!(
        (moved.cg_m - rebuilt.cg_m).amax() < 1e-15,
        "{}",
        moved.cg_m - rebuilt.cg_m
    );
    assert!(
        (moved.inertia_cg - rebuilt.inertia_cg).amax() < 1e-15,
        "{}",
        moved.inertia_cg - rebuilt.inertia_cg
    );
    // The center moved by m Δ / M.
    assert!((moved.cg_m.x - whole.cg_m.x - 0.2 * 0.3 / whole.mass_kg).abs() < 1e-15);
}
