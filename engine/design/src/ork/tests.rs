//! The import against the design it describes: the design format's own example
//! (`docs/design-format.md`, "A complete example") drawn as OpenRocket 24.12 saves it.

use super::*;
use crate::aero::AeroModel;
use crate::mass::components::dry;
use crate::Design;
use std::io::Write as _;

mod fins;
mod flying;
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

/// A document whose rocket holds stages nested `n` deep.
fn nested(n: usize) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?><openrocket version=\"1.9\" creator=\"x\">\
         <rocket><name>R</name><subcomponents>{}{}</subcomponents></rocket></openrocket>",
        "<stage><subcomponents>".repeat(n),
        "</subcomponents></stage>".repeat(n)
    )
}

#[test]
fn a_document_nested_deeper_than_the_limit_is_refused_before_the_import_walks_it() {
    // 20,000 stages deep overflowed the import's recursion (an abort), plain or zipped.
    for n in [20_000, 1_000_000] {
        let text = nested(n);
        for bytes in [text.clone().into_bytes(), zipped(&[("rocket.ork", &text)])] {
            let e = refusal(&bytes, "deep.ork");
            assert_eq!(
                e,
                format!(
                    "deep.ork: document: its elements nest more than {MAX_ORK_DEPTH} deep, \
                     deeper than any OpenRocket design (the most hpr-mc reads)"
                )
            );
        }
    }
    // At the limit the document is read and judged on its parts (a stage in a stage).
    let e = refusal(nested(MAX_ORK_DEPTH / 2 - 3).as_bytes(), "deep.ork");
    assert!(
        e.contains("a <stage> among a stage's body components"),
        "{e}"
    );
}

#[test]
fn a_document_that_inflates_past_the_limit_is_refused_as_it_passes_it() {
    // A ZIP bomb: 64 MiB and 1 KiB of spaces after the example inflate from about 65 KiB.
    let size = MAX_ORK_DOCUMENT_BYTES as usize + 1024;
    let mut text = String::with_capacity(size);
    text.push_str(EXAMPLE);
    text.push_str(&" ".repeat(size - EXAMPLE.len()));
    let zip = zipped(&[("rocket.ork", &text)]);
    assert!(zip.len() < 1 << 20, "{}", zip.len());
    let rule = "its document inflates to more than 64 MiB, the most hpr-mc reads of an \
                OpenRocket design";
    assert_eq!(
        refusal(&zip, "bomb.ork"),
        format!("bomb.ork: container: {rule}")
    );
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(text.as_bytes()).unwrap();
    assert_eq!(
        refusal(&gz.finish().unwrap(), "bomb.ork"),
        format!("bomb.ork: container: {rule}")
    );
    // The same document at the limit is read (and imported: white space after it).
    text.truncate(MAX_ORK_DOCUMENT_BYTES as usize);
    assert!(super::import(&zipped(&[("rocket.ork", &text)]), "big.ork").is_ok());
}
