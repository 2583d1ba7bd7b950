//! Fins from an OpenRocket file: tabs, fillets and rounded or airfoil sections weigh what
//! OpenRocket weighs.

use super::*;

#[test]
fn fin_tabs_and_fillets_weigh_what_openrocket_weighs_where_it_puts_them() {
    // The example's three fins (root 0.12 m at the body's aft end, 1.03 to 1.15 m; 3 mm
    // birch plywood, 630 kg/m³; body radius 0.02815 m) with a tab 0.05 × 0.01 m, 0.01 m
    // behind the root's leading edge, and 5 mm fillets of cardboard (680 kg/m³).
    let text = edited(
        "<filletradius>0.0</filletradius>",
        "<filletradius>0.005</filletradius><tabheight>0.01</tabheight><tablength>0.05</tablength>\
         <tabposition relativeto=\"front\">0.01</tabposition>\
         <tabposition relativeto=\"top\">0.01</tabposition>",
    )
    .replacen(
        "<length>0.9</length>",
        "<length>0.9</length><overridecd>0.5</overridecd>",
        1,
    );
    let (got, import) = imported(text.as_bytes());
    let parts = import.json["stages"][0]["components"][1]["children"]
        .as_array()
        .unwrap();
    let by_id = |id: &str| parts.iter().find(|p| p["id"] == id).unwrap().clone();
    // Tabs: 3 × 0.05 × 0.01 × 0.003 m × 630 kg/m³, from 1.04 to 1.09 m.
    let tabs = by_id("fins_fin_tabs");
    let tab_kg = 3.0 * 0.05 * 0.01 * 0.003 * 630.0;
    assert!(
        close(tabs["mass_kg"].as_f64().unwrap(), tab_kg, 1e-15),
        "{tabs}"
    );
    assert_eq!(
        tabs["position"],
        json!({ "from": "top", "offset_m": 0.78 + 0.01 })
    );
    assert_eq!(tabs["length_m"], 0.05);
    // Fillets: OpenRocket's cross-section (checked here against the corner integrated) times
    // the root, along the whole root.
    let area = fillets_by_integration_m2(0.005, 0.02815);
    let or_area = super::components::fins::fillet_cross_section_m2(0.005, 0.02815);
    assert!(close(or_area, area, 1e-10), "{or_area} {area}");
    let fillets = by_id("fins_fillets");
    let fillet_kg = 3.0 * area * 0.12 * 680.0;
    assert!(
        close(fillets["mass_kg"].as_f64().unwrap(), fillet_kg, 1e-9),
        "{fillets}"
    );
    assert_eq!(
        fillets["position"],
        json!({ "from": "top", "offset_m": 0.78 })
    );
    // The rocket: the example's mass and first moment plus theirs (tabs centered at
    // 1.065 m, fillets at 1.09 m).
    let (g, w) = (dry(&got), dry(&imported(EXAMPLE.as_bytes()).0));
    let mass = w.mass_kg + tab_kg + fillet_kg;
    assert!(close(g.mass_kg, mass, 1e-9), "{} {}", g.mass_kg, mass);
    let cg = (w.mass_kg * w.cg_m.x + tab_kg * 1.065 + fillet_kg * 1.09) / mass;
    assert!(close(g.cg_m.x, cg, 1e-9), "{} {cg}", g.cg_m.x);
    // Spread round the axis: the center of mass stays on it.
    assert!(g.cg_m.y.abs() < 1e-15 && g.cg_m.z.abs() < 1e-15);
    assert!(
        noted(&import, "Body tube: its drag override is not imported"),
        "{:?}",
        import.notes
    );

    // A fin set whose mass OpenRocket overrides carries its tabs and fillets in it.
    let overridden = text.replacen(
        "<thickness>0.003</thickness>",
        "<thickness>0.003</thickness><overridemass>0.1</overridemass>",
        1,
    );
    let (_, import) = imported(overridden.as_bytes());
    let parts = import.json["stages"][0]["components"][1]["children"]
        .as_array()
        .unwrap();
    assert!(parts
        .iter()
        .all(|p| p["type"] != "mass_component" || !p["id"].as_str().unwrap().starts_with("fins_")));
}

#[test]
fn a_rounded_or_airfoil_fin_weighs_openrocket_s_share_of_the_flat_plate() {
    // OpenRocket's FinSet.CrossSection volumes: rounded 0.99, airfoil 0.85 of the plate.
    // The example's fins: 3 × (0.12 + 0.05)/2 × 0.07 m² × 0.003 m × 630 kg/m³ as a plate.
    let plate_kg = 3.0 * 0.5 * (0.12 + 0.05) * 0.07 * 0.003 * 630.0;
    for (cross, share) in [("square", 1.0), ("rounded", 0.99), ("airfoil", 0.85)] {
        let text = edited(
            "<crosssection>square</crosssection>",
            &format!("<crosssection>{cross}</crosssection>"),
        );
        let (got, _) = imported(text.as_bytes());
        let fins = got.component_index("fins").unwrap();
        let m = crate::mass::components::component_own(&got, fins).mass_kg;
        assert!(close(m, share * plate_kg, 1e-13), "{cross}: {m}");
    }
}
