//! The import against the design it describes: the design format's own example
//! (`docs/design-format.md`, "A complete example") drawn as OpenRocket 24.12 saves it.

use super::*;
use crate::aero::AeroModel;
use crate::mass::components::dry;
use crate::Design;
use std::io::Write as _;

mod teams;

/// The example rocket as an OpenRocket document (`validation/designs/example-minimal.ork`,
/// plain XML, which OpenRocket reads as it reads its ZIPs): the same parts, their positions
/// given as OpenRocket gives them (the rail buttons as one part of two instances, the
/// ballast's position absolute, radii `auto` with their values).
const EXAMPLE: &str = include_str!("../../../../validation/designs/example-minimal.ork");

/// The parachute's mass as OpenRocket computes it: canopy area × the cloth's surface
/// density, plus its lines (count × length × linear density).
fn chute_mass_kg() -> f64 {
    std::f64::consts::PI * 0.3 * 0.3 * 0.067 + 6.0 * 0.9 * 0.0018
}

/// `validation/designs/example-minimal.json` as the `.ork` says it: the drag estimated with
/// the normal finish, the nose cone's wall measured along its normal (OpenRocket's), the
/// parachute's mass from its cloth and lines and its deployment at 300 m, each rail button's
/// mass overriding its material's.
fn expected() -> Design {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../validation/designs/example-minimal.json"
    );
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    v["drag"] = json!({ "estimate": { "roughness_m": 60e-6 } });
    v["stages"][0]["components"][0]["wall_along_normal"] = json!(true);
    let parts = v["stages"][0]["components"][1]["children"]
        .as_array_mut()
        .unwrap();
    for p in parts.iter_mut() {
        if p["id"] == "chute" {
            p["mass_kg"] = json!(chute_mass_kg());
            p["deploy"] = json!({ "trigger": { "height_m": 300.0 }, "lag_s": 0.0 });
        }
    }
    Design::from_json_str(&v.to_string(), None).unwrap()
}

fn imported(bytes: &[u8]) -> (Design, OrkImport) {
    let import = super::import(bytes, "example.ork").unwrap();
    let design = Design::from_json_str(&import.json.to_string(), None).unwrap();
    (design, import)
}

fn zipped(entries: &[(&str, &str)]) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    let mut zip = zip::ZipWriter::new(&mut out);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, text) in entries {
        zip.start_file(*name, options).unwrap();
        zip.write_all(text.as_bytes()).unwrap();
    }
    zip.finish().unwrap();
    out.into_inner()
}

/// The error of an import that must fail, as a user reads it.
fn refusal(bytes: &[u8], file: &str) -> String {
    super::import(bytes, file).unwrap_err().to_string()
}

/// Whether one of the import's notes says `text`.
fn noted(import: &OrkImport, text: &str) -> bool {
    import.notes.iter().any(|n| n.contains(text))
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1e-300)
}

#[test]
fn an_openrocket_file_gives_the_mass_center_inertia_and_pressure_center_of_its_design() {
    let (got, import) = imported(EXAMPLE.as_bytes());
    let want = expected();
    let (g, w) = (dry(&got), dry(&want));
    // The same parts at the same places: equal to rounding (positions summed in another order).
    assert!(
        close(g.mass_kg, w.mass_kg, 1e-14),
        "{} {}",
        g.mass_kg,
        w.mass_kg
    );
    assert!(
        close(g.cg_m.x, w.cg_m.x, 1e-13),
        "{} {}",
        g.cg_m.x,
        w.cg_m.x
    );
    for (a, b) in g.inertia_cg.iter().zip(w.inertia_cg.iter()) {
        assert!((a - b).abs() <= 1e-13 * w.inertia_cg.norm(), "{a} {b}");
    }
    let (ga, wa) = (
        AeroModel::from_design(&got).unwrap(),
        AeroModel::from_design(&want).unwrap(),
    );
    for mach in [0.0, 0.3, 0.8, 1.5] {
        assert!(
            close(ga.cp_m(mach), wa.cp_m(mach), 1e-13),
            "CP at Mach {mach}"
        );
        assert!(
            close(ga.cn_alpha(mach), wa.cn_alpha(mach), 1e-13),
            "CNα at Mach {mach}"
        );
        assert!(
            close(ga.cd_power_off(mach), wa.cd_power_off(mach), 1e-13),
            "Cd at Mach {mach}"
        );
    }
    assert_eq!(import.json["motor"], "Cesaroni_I175");
    assert_eq!(got.reference_diameter_m, 0.0563);
    // The parachute's deployment is a note (hpr takes it from the scenario or fly's flags).
    assert!(
        noted(&import, "at 300 m on the way down"),
        "{:?}",
        import.notes
    );
}

#[test]
fn the_parachute_weighs_its_cloth_and_its_lines() {
    let (_, import) = imported(EXAMPLE.as_bytes());
    let chute = &import.json["stages"][0]["components"][1]["children"][4];
    assert_eq!(chute["type"], "parachute");
    // π (0.3 m)² × 0.067 kg/m² + 6 × 0.9 m × 0.0018 kg/m = 0.018943803 + 0.00972 kg.
    let want = 0.028663803_f64;
    assert!((chute["mass_kg"].as_f64().unwrap() - want).abs() < 1e-9);
    assert_eq!(chute["canopy_diameter_m"], 0.6);
    assert_eq!(chute["cd"], 1.5);
}

#[test]
fn a_zipped_a_gzipped_and_a_plain_document_give_the_same_design() {
    let plain = super::import(EXAMPLE.as_bytes(), "a.ork").unwrap().json;
    let zip = super::import(&zipped(&[("rocket.ork", EXAMPLE)]), "a.ork")
        .unwrap()
        .json;
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    gz.write_all(EXAMPLE.as_bytes()).unwrap();
    let gzip = super::import(&gz.finish().unwrap(), "a.ork").unwrap().json;
    assert_eq!(zip, plain);
    assert_eq!(gzip, plain);
    // OpenRocket reads the first entry of a ZIP (decal images follow it).
    let with_decal = zipped(&[("rocket.ork", EXAMPLE), ("decals/fin.png", "not xml")]);
    assert_eq!(super::import(&with_decal, "a.ork").unwrap().json, plain);
    assert!(is_ork(EXAMPLE.as_bytes()) && !is_ork(b"{\"name\": \"x\"}"));
    // A JSON design whose notes quote an OpenRocket document is still JSON.
    assert!(!is_ork(b"  {\"notes\": \"<openrocket version=1.10>\"}"));
}

#[test]
fn two_instances_of_a_rail_button_stand_their_separation_apart() {
    let (got, _) = imported(EXAMPLE.as_bytes());
    let tops: Vec<f64> = got
        .components
        .iter()
        .filter(|c| c.kind.type_name() == "rail_button")
        .map(|c| c.x_top_m)
        .collect();
    // The body starts 0.25 m aft of the tip: 0.25 + 0.4 and 0.25 + 0.4 + 0.47.
    assert_eq!(tops.len(), 2);
    assert!(
        (tops[0] - 0.65).abs() < 1e-12 && (tops[1] - 1.12).abs() < 1e-12,
        "{tops:?}"
    );
}

#[test]
fn a_rail_button_is_placed_by_its_center_and_weighs_its_flange_waist_and_base() {
    // Centred 0.405 m down the body tube (0.655 m from the tip), 0.01 m across: its fore end
    // at 0.65 m. Without its override it weighs OpenRocket's volume × 1400 kg/m³:
    // π (0.005² × 0.002 + 0.003² × 0.004 + 0.005² × 0.002) m³ = 4.27257e-7 m³ → 0.598159 g.
    let text = edited("<overridemass>0.002</overridemass>", "");
    let (got, import) = imported(text.as_bytes());
    let button = got.component("rail_button").unwrap();
    assert!((button.x_top_m + button.length_m / 2.0 - 0.655).abs() < 1e-12);
    let mass = import.json["stages"][0]["components"][1]["children"][6]["mass_kg"]
        .as_f64()
        .unwrap();
    let want =
        std::f64::consts::PI * (0.005_f64.powi(2) * 0.004 + 0.003_f64.powi(2) * 0.004) * 1400.0;
    assert!(
        (mass - want).abs() < 1e-15 && (mass - 5.98159e-4).abs() < 1e-9,
        "{mass}"
    );
}

/// The example with `from` replaced by `to` (once).
fn edited(from: &str, to: &str) -> String {
    assert!(EXAMPLE.contains(from), "{from}");
    EXAMPLE.replacen(from, to, 1)
}

#[test]
fn a_bare_auto_radius_of_an_older_file_is_taken_from_the_neighbouring_component() {
    // Files before format 1.8 write `auto` without its value: the body tube takes the nose
    // cone's base radius, as OpenRocket resolves it.
    // So do the rings' outer radii inside it (its inner radius) and the parachute's packed
    // radius: the design is the example's.
    let old = edited("<radius>auto 0.02815</radius>", "<radius>auto</radius>")
        .replace("<outerradius>auto 0.02665</outerradius>", "<outerradius>auto</outerradius>")
        .replace("<packedradius>0.02</packedradius>\n                <radialposition>0.0</radialposition>\n                <radialdirection>0.0</radialdirection>\n                <cd>", "<packedradius>auto</packedradius><cd>");
    assert_eq!(old.matches(">auto<").count(), 4, "{old}");
    let (got, import) = imported(old.as_bytes());
    match &got.component("body_tube").unwrap().kind {
        crate::ComponentKind::BodyTube(t) => assert_eq!(t.outer_diameter_m, 0.0563),
        other => panic!("{other:?}"),
    }
    let ring = &import.json["stages"][0]["components"][1]["children"][2];
    assert!(
        (ring["outer_diameter_m"].as_f64().unwrap() - 0.0533).abs() < 1e-15,
        "{ring}"
    );
    let chute = &import.json["stages"][0]["components"][1]["children"][4];
    assert!(
        (chute["radius_m"].as_f64().unwrap() - 0.02665).abs() < 1e-15,
        "{chute}"
    );
}

#[test]
fn a_part_after_another_starts_where_that_one_ends() {
    // An old `<position type="after">`: the ballast 0.02 m after the parachute's end (0.05 +
    // 0.08 m down the body tube), as OpenRocket's AxialMethod.AFTER adds the offset.
    let old = edited(
        r#"<axialoffset method="absolute">0.35</axialoffset>
                <position type="absolute">0.35</position>"#,
        r#"<position type="after">0.02</position>"#,
    );
    let (got, _) = imported(old.as_bytes());
    let ballast = got.component("ballast").unwrap();
    assert!(
        (ballast.x_top_m - (0.25 + 0.05 + 0.08 + 0.02)).abs() < 1e-12,
        "{}",
        ballast.x_top_m
    );
    // After a part placed from the nose tip, the same: the example's ballast spans 0.35 to
    // 0.40 m from the tip, so the rail buttons after it are centred at 0.40 m (OpenRocket
    // places a rail button by its center) and begin half their 0.01 m diameter before it.
    let after_absolute = edited(
        r#"<axialoffset method="top">0.405</axialoffset>
                <position type="top">0.405</position>"#,
        r#"<position type="after">0.0</position>"#,
    );
    let (got, _) = imported(after_absolute.as_bytes());
    let button = got.component("rail_button").unwrap();
    assert!((button.x_top_m - 0.395).abs() < 1e-12, "{}", button.x_top_m);
}

#[test]
fn a_secant_ogive_imports_with_its_shape_parameter_and_weighs_less_than_the_tangent_one() {
    let (tangent, _) = imported(EXAMPLE.as_bytes());
    let secant_file = edited(
        "<shapeparameter>1.0</shapeparameter>",
        "<shapeparameter>0.5</shapeparameter>",
    );
    let import = super::import(secant_file.as_bytes(), "example.ork").unwrap();
    let nose = &import.json["stages"][0]["components"][0];
    assert_eq!(nose["shape"], "ogive");
    assert_eq!(nose["shape_parameter"], 0.5);
    let (secant, _) = imported(secant_file.as_bytes());
    let shape = |d: &Design| {
        d.components
            .iter()
            .find_map(|c| match &c.kind {
                crate::design::ComponentKind::NoseCone(n) => Some(n.shape),
                _ => None,
            })
            .unwrap()
    };
    assert_eq!(shape(&tangent), crate::design::NoseShape::Ogive);
    assert_eq!(
        shape(&secant),
        crate::design::NoseShape::SecantOgive { p: 0.5 }
    );
    // Slimmer than the tangent ogive: a smaller shell (14 % lighter here), so a lighter
    // rocket; more of its volume aft, so its center of pressure moves aft; and it meets the
    // body at an angle, so it has the wave drag of that angle above Mach 1 (below, its
    // smaller skin's friction outweighs the angle's pressure drag).
    let (mt, ms) = (dry(&tangent).mass_kg, dry(&secant).mass_kg);
    assert!(ms < mt, "{ms} vs {mt}");
    let (at, as_) = (
        AeroModel::from_design(&tangent).unwrap(),
        AeroModel::from_design(&secant).unwrap(),
    );
    assert!(as_.cp_m(0.0) > at.cp_m(0.0));
    for m in [1.2, 2.0] {
        assert!(as_.cd_power_off(m) > at.cd_power_off(m), "Mach {m}");
    }
}

#[test]
fn a_flipped_nose_cone_is_a_tail_cone_from_its_base_to_a_point_with_its_shoulder_fore() {
    // The example's nose cone, copied aft of the body tube and flipped (OpenRocket 23.09's
    // tail cone): its file keeps the base and the shoulder in the `aft` elements.
    let start = EXAMPLE.find("<nosecone>").unwrap();
    let end = EXAMPLE.find("</nosecone>").unwrap() + "</nosecone>".len();
    let tail = EXAMPLE[start..end]
        .replace("<name>Nose cone</name>", "<name>Tail cone</name>")
        .replace(
            "<isflipped>false</isflipped>",
            "<isflipped>true</isflipped>",
        );
    let with_tail = edited("</bodytube>", &format!("</bodytube>{tail}"));
    let (plain, _) = imported(EXAMPLE.as_bytes());
    let (design, import) = imported(with_tail.as_bytes());
    let body = import.json["stages"][0]["components"].as_array().unwrap();
    let cone = body.last().unwrap();
    assert_eq!(cone["type"], "transition");
    assert_eq!(cone["shape"], "ogive");
    assert_eq!(cone["fore_diameter_m"], 0.0563);
    assert_eq!(cone["aft_diameter_m"], 0.0);
    assert_eq!(cone["fore_shoulder"]["length_m"], 0.05);
    assert!(cone.get("aft_shoulder").is_none() && cone.get("clipped").is_none());
    assert!(noted(&import, "flipped nose cone"), "{:?}", import.notes);
    // The same solid as the nose cone, mirrored: the same mass, its shoulder now fore.
    let mass_of = |d: &Design, name: &str| {
        let i = d.components.iter().position(|c| c.name == name).unwrap();
        crate::mass::components::component_own(d, i).mass_kg
    };
    let (nose, tail) = (mass_of(&design, "Nose cone"), mass_of(&design, "Tail cone"));
    assert!(close(tail, nose, 1e-9), "{tail} vs {nose}");
    // A body narrowing aft lifts the wrong way: the center of pressure moves forward.
    let (a0, a1) = (
        AeroModel::from_design(&plain).unwrap(),
        AeroModel::from_design(&design).unwrap(),
    );
    assert!(
        a1.cp_m(0.0) < a0.cp_m(0.0),
        "{} {}",
        a1.cp_m(0.0),
        a0.cp_m(0.0)
    );
    assert!(
        (dry(&design).mass_kg - dry(&plain).mass_kg - tail).abs() < 1e-12,
        "the tail cone adds its own mass"
    );
}

#[test]
fn a_filled_body_tube_is_a_solid_rod_of_its_radius() {
    // The example's body tube filled: its wall becomes its radius, 0.02815 m, and it weighs
    // a solid cylinder's mass, ρ π r² L, with the parts it holds unchanged.
    let start = EXAMPLE.find("<bodytube>").unwrap();
    let at = start + EXAMPLE[start..].find("<thickness>").unwrap();
    let end = at + EXAMPLE[at..].find("</thickness>").unwrap() + "</thickness>".len();
    let filled = format!(
        "{}<thickness>filled</thickness>{}",
        &EXAMPLE[..at],
        &EXAMPLE[end..]
    );
    let (design, import) = imported(filled.as_bytes());
    let tube = &import.json["stages"][0]["components"][1];
    assert_eq!(tube["type"], "body_tube");
    assert_eq!(tube["wall_thickness_m"], 0.02815);
    assert!(noted(&import, "solid rod"), "{:?}", import.notes);
    let i = design
        .components
        .iter()
        .position(|c| c.name == "Body tube")
        .unwrap();
    let got = crate::mass::components::component_own(&design, i).mass_kg;
    let density = tube["material"]["density_kg_m3"].as_f64().unwrap();
    let want = density * std::f64::consts::PI * 0.02815f64.powi(2) * 0.9;
    assert!(close(got, want, 1e-12), "{got} vs {want}");
}

#[test]
fn what_a_design_cannot_hold_is_refused_with_its_element_and_reason() {
    let cases = [
        (
            edited(
                "<parachute>",
                "<tubefinset><name>Tubes</name></tubefinset><parachute>",
            ),
            "tubefinset \"Tubes\"",
            "tube fin set",
        ),
        (
            edited("<length>0.9</length>", "<length>not a length</length>"),
            "bodytube \"Body tube\"/<length>",
            "not a finite number",
        ),
        (
            "<openrocket version=\"1.10\"><rocket><name>x</name></rocket></openrocket>".to_owned(),
            "rocket",
            "has no <stage>",
        ),
    ];
    for (text, element, why) in cases {
        let e = refusal(text.as_bytes(), "r.ork");
        assert!(e.starts_with("r.ork: "), "{e}");
        assert!(e.contains(element) && e.contains(why), "{e}");
    }
    let broken = refusal(b"PK\x03\x04 not really a zip", "z.ork");
    assert!(
        broken.starts_with("z.ork: container: not a readable ZIP"),
        "{broken}"
    );
}

#[test]
fn a_nose_cone_s_clipped_flag_and_a_second_stage_change_nothing_but_a_note() {
    let text = edited(
        "<shapeclipped>false</shapeclipped>",
        "<shapeclipped>true</shapeclipped>",
    )
    .replacen(
        "</stage>",
        "</stage><stage><name>Booster</name><subcomponents><bodytube><name>Booster tube</name>\
             <material type=\"bulk\" density=\"680.0\">Cardboard</material><length>0.3</length>\
             <thickness>0.0015</thickness><radius>auto</radius></bodytube></subcomponents></stage>",
        1,
    );
    let (got, import) = imported(text.as_bytes());
    assert_eq!(got.stages.len(), 2);
    assert!((got.length_m - 1.45).abs() < 1e-12, "{}", got.length_m);
    // The booster's tube takes the sustainer's radius (a bare auto, from the part before it).
    assert_eq!(
        import.json["stages"][1]["components"][0]["outer_diameter_m"],
        0.0563
    );
    assert!(
        noted(&import, "The 2 stages fly together"),
        "{:?}",
        import.notes
    );
}

#[test]
fn a_body_tube_that_holds_the_motor_gets_a_massless_mount_of_its_bore() {
    // A minimum-diameter rocket: the motor in the body tube itself (the example's mount moved
    // from its inner tube, which stays as a plain tube).
    let start = EXAMPLE.find("<motormount>").unwrap();
    let end = EXAMPLE.find("</motormount>").unwrap() + "</motormount>".len();
    let mount = &EXAMPLE[start..end];
    let text = EXAMPLE.replacen(mount, "", 1).replacen(
        "<radius>auto 0.02815</radius>",
        &format!("<radius>auto 0.02815</radius>{mount}"),
        1,
    );
    let (got, import) = imported(text.as_bytes());
    let mm = got.motor_mount.unwrap();
    // The body runs from 0.25 to 1.15 m; the motor's aft end overhangs it by 0.01 m.
    assert!((mm.motor_aft_m - 1.16).abs() < 1e-12, "{mm:?}");
    // The bore: 2 × (0.02815 − 0.0015) m, less the mount's 0.1 µm walls.
    assert!(
        (mm.inner_diameter_m - (0.0533 - 2e-7)).abs() < 1e-12,
        "{mm:?}"
    );
    // Massless: the rocket weighs what the example weighs.
    let (g, w) = (dry(&got), dry(&imported(EXAMPLE.as_bytes()).0));
    assert!(close(g.mass_kg, w.mass_kg, 1e-14) && close(g.cg_m.x, w.cg_m.x, 1e-13));
    assert!(
        noted(&import, "Body tube: it holds the motor itself"),
        "{:?}",
        import.notes
    );
    // A motor as wide as the bore fits it.
    assert!(got.motor_fits(0.0533, 0.5).is_ok());
}

#[test]
fn a_mount_without_a_motor_is_still_the_design_s_mount_when_the_default_configuration_has_none() {
    // A design not yet given a motor, as OpenRocket saves it: the inner tube is marked as a
    // mount, with its overhang, and no configuration puts a motor in it. The flight's motor
    // (--motor, a scenario's) then goes where the motor of the original example goes.
    let start = EXAMPLE.find("<motor configid").unwrap();
    let end = EXAMPLE.find("</motor>").unwrap() + "</motor>".len();
    let text = EXAMPLE.replacen(&EXAMPLE[start..end], "", 1);
    let (got, import) = imported(text.as_bytes());
    let (want, _) = imported(EXAMPLE.as_bytes());
    assert_eq!(got.default_motor, None);
    assert_eq!(want.default_motor.as_deref(), Some("Cesaroni_I175"));
    let (g, w) = (got.motor_mount.unwrap(), want.motor_mount.unwrap());
    assert_eq!(g.motor_aft_m, w.motor_aft_m);
    assert_eq!(g.inner_diameter_m, w.inner_diameter_m);
    assert!(
        noted(&import, "default flight configuration has no motor"),
        "{:?}",
        import.notes
    );
    // A second tube marked as a mount stays a plain tube, with a note (hpr flies one motor).
    let mount = &EXAMPLE[EXAMPLE.find("<motormount>").unwrap()
        ..EXAMPLE.find("</motormount>").unwrap() + "</motormount>".len()];
    let bare_mount = mount.replacen(&EXAMPLE[start..end], "", 1);
    let twice = text.replacen(
        "<radius>auto 0.02815</radius>",
        &format!("<radius>auto 0.02815</radius>{bare_mount}"),
        1,
    );
    let (got2, import2) = imported(twice.as_bytes());
    assert_eq!(got2.motor_mount.unwrap().motor_aft_m, 1.16);
    assert!(
        noted(&import2, "also a motor mount in OpenRocket"),
        "{:?}",
        import2.notes
    );
}

#[test]
fn a_stage_s_override_covering_its_parts_becomes_the_stage_s_override() {
    let text = edited(
        "<name>Sustainer</name>",
        "<name>Sustainer</name><overridemass>1.25</overridemass><overridecg>0.7</overridecg>\
         <overridesubcomponentsmass>true</overridesubcomponentsmass>\
         <overridesubcomponentscg>true</overridesubcomponentscg>",
    );
    let (got, import) = imported(text.as_bytes());
    assert_eq!(
        import.json["stages"][0]["override"],
        json!({ "mass_kg": 1.25, "cg_m": 0.7 })
    );
    let m = dry(&got);
    assert!(
        (m.mass_kg - 1.25).abs() < 1e-15 && (m.cg_m.x - 0.7).abs() < 1e-15,
        "{m:?}"
    );
    // One that leaves the parts' own masses has no counterpart in a design.
    let partial = edited(
        "<name>Sustainer</name>",
        "<name>Sustainer</name><overridemass>1.25</overridemass>",
    );
    let e = refusal(partial.as_bytes(), "s.ork");
    assert!(
        e.contains("stage \"Sustainer\": a stage's override that does not cover its parts"),
        "{e}"
    );
}

/// One fin's two fillets' area across the axis, by integrating the corner they fill: the
/// fin the line `x = 0` (its thickness left out), the body the circle of radius `b` about
/// the origin, the fillet the circle of radius `r` tangent to both, centered at
/// `(r, y_c)`, `y_c = √((b + r)² − r²)`. Between the fin and the fillet's tangent point on
/// the body (`x = b r/(b + r)`) the fillet runs from the body up to the circle's near arc.
fn fillets_by_integration_m2(r: f64, b: f64) -> f64 {
    let y_c = ((b + r).powi(2) - r * r).sqrt();
    let x_t = b * r / (b + r);
    let height = |x: f64| y_c - (r * r - (x - r).powi(2)).sqrt() - (b * b - x * x).sqrt();
    // The fillet's arc rises as √x from the fin: with x = u² the integrand 2u·height(u²) is
    // smooth, and composite Simpson's rule converges at its fourth order.
    let g = |u: f64| 2.0 * u * height(u * u);
    let (n, top) = (2_000, x_t.sqrt());
    let h = top / n as f64;
    let mut sum = g(0.0) + g(top);
    for i in 1..n {
        sum += g(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    2.0 * sum * h / 3.0
}

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

#[test]
fn a_parachute_deploys_as_the_default_configuration_deploys_it_in_openrocket() {
    let deploy = |event: &str, altitude: f64, delay: f64, extra: &str| {
        let text = edited(
            "<deployevent>altitude</deployevent>\n                <deployaltitude>300.0</deployaltitude>\n                <deploydelay>0.0</deploydelay>",
            &format!(
                "<deployevent>{event}</deployevent><deployaltitude>{altitude}</deployaltitude>\
                 <deploydelay>{delay}</deploydelay>{extra}"
            ),
        );
        let (got, import) = imported(text.as_bytes());
        let chute = got.component_index("parachute").unwrap();
        match &got.components[chute].kind {
            crate::ComponentKind::Parachute(p) => (p.deploy, import.notes),
            other => panic!("{other:?}"),
        }
    };
    use crate::{Deploy, DeployTrigger as T};
    let with = |trigger, lag_s| Some(Deploy { trigger, lag_s });
    assert_eq!(deploy("apogee", 0.0, 1.5, "").0, with(T::Apogee, 1.5));
    assert_eq!(
        deploy("altitude", 152.4, 0.0, "").0,
        with(T::Height { height_m: 152.4 }, 0.0)
    );
    assert_eq!(
        deploy("launch", 0.0, 4.0, "").0,
        with(T::Time { time_s: 4.0 }, 0.0)
    );
    // Ejection: the default motor's delay after burnout (the example's I175 is saved with
    // "none", plugged: it never deploys).
    let (plugged, notes) = deploy("ejection", 0.0, 0.0, "");
    assert_eq!(plugged, None);
    assert!(notes.iter().any(|n| n.contains("plugged")), "{notes:?}");
    let (never, notes) = deploy("never", 0.0, 0.0, "");
    assert_eq!(never, None);
    assert!(notes.iter().any(|n| n.contains("\"never\"")), "{notes:?}");
    // The default configuration's own deployment wins over the parachute's default.
    let (over, _) = deploy(
        "apogee",
        0.0,
        0.0,
        "<deploymentconfiguration configid=\"c1\"><deployevent>altitude</deployevent>\
         <deployaltitude>200.0</deployaltitude><deploydelay>0.5</deploydelay>\
         </deploymentconfiguration>",
    );
    assert_eq!(over, with(T::Height { height_m: 200.0 }, 0.5));
    let (other, _) = deploy(
        "apogee",
        0.0,
        0.0,
        "<deploymentconfiguration configid=\"c9\"><deployevent>never</deployevent>\
         </deploymentconfiguration>",
    );
    assert_eq!(other, with(T::Apogee, 0.0));
    // With a motor delay of 6 s, ejection is 6 s after burnout.
    let delayed = EXAMPLE
        .replacen("<delay>none</delay>", "<delay>6.0</delay>", 1)
        .replacen(
            "<deployevent>altitude</deployevent>",
            "<deployevent>ejection</deployevent>",
            1,
        );
    let (got, _) = imported(delayed.as_bytes());
    let chute = got.component_index("parachute").unwrap();
    let crate::ComponentKind::Parachute(p) = &got.components[chute].kind else {
        panic!()
    };
    assert_eq!(p.deploy, with(T::AfterBurnout { delay_s: 6.0 }, 0.0));
}

#[test]
fn openrocket_s_own_simulation_is_said_as_fly_s_flags_with_what_it_found() {
    let with_simulations = |sims: &str| {
        let text = EXAMPLE.replacen(
            "<simulations/>",
            &format!("<simulations>{sims}</simulations>"),
            1,
        );
        let (_, import) = imported(text.as_bytes());
        import
            .notes
            .into_iter()
            .find(|n| n.starts_with("OpenRocket's simulation"))
    };
    // OpenRocket 24's elements: the average wind (its direction in radians, from), the
    // extended ISA's base temperature and pressure; a simulation of another configuration
    // first, then the default configuration's, which is the one said.
    let note = with_simulations(
        r#"<simulation status="outdated"><name>Other</name><conditions><configid>c9</configid>
             <launchrodlength>3.0</launchrodlength></conditions></simulation>
           <simulation status="uptodate"><name>Field day</name><conditions>
             <configid>c1</configid><launchrodlength>1.5</launchrodlength>
             <launchrodangle>5.0</launchrodangle><launchroddirection>270.0</launchroddirection>
             <wind model="average"><speed>4.0</speed><direction>3.141592653589793</direction>
               <standarddeviation>0.4</standarddeviation></wind>
             <launchaltitude>1400.0</launchaltitude>
             <atmosphere model="extendedisa"><basetemperature>300.15</basetemperature>
               <basepressure>86000.0</basepressure></atmosphere></conditions>
             <flightdata maxaltitude="1234.5" timetoapogee="12.25" maxvelocity="250.0"
               launchrodvelocity="20.5" groundhitvelocity="6.1" flighttime="95.0"/>
           </simulation>"#,
    )
    .unwrap();
    assert_eq!(
        note,
        "OpenRocket's simulation \"Field day\" flew it on the Cesaroni Technology I175 with \
         --rail-length-m 1.5 --inclination-deg 85 --heading-deg 270 --wind-m-s 4 \
         --wind-from-deg 180 --wind-turbulence-intensity 0.1 --elevation-m 1400 \
         --temperature-k 300.15 --pressure-pa 86000; it found apogee 1234.5 m at 12.25 s, \
         max speed 250 m/s, off the rod at 20.5 m/s, landing at 6.1 m/s after 95 s."
    );
    // An older file's wind elements, OpenRocket's default direction (π/2, from the east), and
    // results OpenRocket marks outdated.
    let note = with_simulations(
        r#"<simulation status="outdated"><name>Old</name><conditions><configid>c1</configid>
             <launchrodlength>1.0</launchrodlength><windaverage>2.0</windaverage>
             <launchaltitude>0.0</launchaltitude><atmosphere model="isa"/></conditions>
             <flightdata maxaltitude="48.01"/></simulation>"#,
    )
    .unwrap();
    assert!(
        note.contains("--inclination-deg 90 --wind-m-s 2 --wind-from-deg 90 --elevation-m 0;"),
        "{note}"
    );
    assert!(
        note.ends_with("apogee 48.01 m (OpenRocket marks them outdated)."),
        "{note}"
    );
    // The rod's direction: before OpenRocket 22 (no wind direction saved) the rod's relative
    // to the wind, 90° across it; after, the wind's own when launched into the wind.
    let rod = |extra: &str| {
        with_simulations(&format!(
            r#"<simulation status="uptodate"><name>Rod</name><conditions><configid>c1</configid>
                 <launchrodlength>5.0</launchrodlength><launchrodangle>6.0</launchrodangle>
                 <launchroddirection>90.0</launchroddirection><windaverage>2.0</windaverage>
                 {extra}</conditions></simulation>"#
        ))
        .unwrap()
    };
    let old = rod("");
    assert!(
        old.contains("--inclination-deg 84 --heading-deg 180 --wind-m-s 2 --wind-from-deg 90"),
        "{old}"
    );
    let into = rod(
        "<winddirection>3.141592653589793</winddirection><launchintowind>true</launchintowind>",
    );
    assert!(
        into.contains("--heading-deg 180 --wind-m-s 2 --wind-from-deg 180"),
        "{into}"
    );
    let set = rod(
        "<winddirection>3.141592653589793</winddirection><launchintowind>false</launchintowind>",
    );
    // The site's latitude: the Earth's rotation and its gravity, unless OpenRocket's geodetic
    // method was flat (then only the gravity, which `fly` does not take without the other).
    let round =
        rod("<launchlatitude>32.99</launchlatitude><geodeticmethod>spherical</geodeticmethod>");
    assert!(
        round.contains("--latitude-deg 32.99 --gravity somigliana"),
        "{round}"
    );
    let flat = rod("<launchlatitude>32.99</launchlatitude><geodeticmethod>flat</geodeticmethod>");
    assert!(!flat.contains("--latitude-deg"), "{flat}");
    assert!(
        flat.contains("its gravity at latitude 32.99° without the Earth's rotation"),
        "{flat}"
    );
    assert!(
        set.contains("--heading-deg 90 --wind-m-s 2 --wind-from-deg 180"),
        "{set}"
    );
    // A flight OpenRocket aborted (it ends at its highest point, 2 s in) is passed over for
    // the next of the same configuration that flew on past its apogee.
    let note = with_simulations(
        r#"<simulation status="uptodate"><name>Aborted</name><conditions><configid>c1</configid>
             <launchrodlength>1.0</launchrodlength></conditions>
             <flightdata maxaltitude="88.3" timetoapogee="1.95" flighttime="1.95"/></simulation>
           <simulation status="uptodate"><name>Flown</name><conditions><configid>c1</configid>
             <launchrodlength>4.0</launchrodlength></conditions>
             <flightdata maxaltitude="773.2" timetoapogee="13.35" flighttime="93.6"/></simulation>"#,
    )
    .unwrap();
    assert!(
        note.starts_with("OpenRocket's simulation \"Flown\""),
        "{note}"
    );
    // No simulations, no note.
    assert_eq!(with_simulations(""), None);
}

#[test]
fn a_file_that_is_not_an_openrocket_document_is_refused_as_such() {
    let e = refusal(b"{ \"name\": \"a design already\" }", "rocket.ork");
    assert!(e.contains("this is JSON"), "{e}");
    let e = refusal(b"garbage", "rocket.ork");
    assert!(
        e.contains("rocket.ork: document: not an OpenRocket document"),
        "{e}"
    );
    // A damaged file named .ork is read as one (its error says what a .ork is), a JSON
    // design named .ork as JSON.
    let dir = std::env::temp_dir().join(format!("hpr-ork-named-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let damaged = dir.join("damaged.ORK");
    std::fs::write(&damaged, "garbage").unwrap();
    let e = Design::load(&damaged).unwrap_err().to_string();
    assert!(e.contains("not an OpenRocket document"), "{e}");
    let json = dir.join("design.ork");
    std::fs::write(&json, "{}").unwrap();
    let e = Design::load(&json).unwrap_err().to_string();
    assert!(e.contains("missing field"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_written_design_reads_back_as_the_same_json_with_ids_and_types_first() {
    let (_, import) = imported(EXAMPLE.as_bytes());
    let text = to_pretty_json(&import.json);
    let back: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(back, import.json);
    let nose = &text[text.find("\"components\"").unwrap()..];
    let (id, kind, length) = (
        nose.find("\"id\": \"nose_cone\"").unwrap(),
        nose.find("\"type\": \"nose_cone\"").unwrap(),
        nose.find("\"length_m\"").unwrap(),
    );
    assert!(id < kind && kind < length, "{nose}");
    assert!(
        text.starts_with("{\n  \"name\": \"Example: minimal 54 mm rocket\",\n  \"notes\""),
        "{text}"
    );
}
