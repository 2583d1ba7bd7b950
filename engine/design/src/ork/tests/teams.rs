//! OpenRocket files as teams save them: what OpenRocket draws and weighs that a
//! hand-written design would be refused for (clusters, clipped transitions, parts that
//! weigh nothing, a bare `auto` inside a nose cone, a whole rocket's override), and the
//! motors and streamers such files fly.

use super::*;

#[test]
fn a_bare_auto_ring_in_a_nose_cone_takes_the_narrower_of_the_cone_s_inner_radii_at_its_ends() {
    // OpenRocket 15.03 writes a bulkhead in a nose cone with a bare `auto`: its radius is the
    // cone's inner radius (outer less the 2 mm wall, across the axis) at the bulkhead's
    // narrower end, here its fore end, each end kept within the cone (the second bulkhead
    // runs past the cone's base into the shoulder). Tangent ogive, L 0.25, R 0.02815.
    let text = edited(
        "<isflipped>false</isflipped>\n          </nosecone>",
        "<isflipped>false</isflipped><subcomponents>\
         <bulkhead><name>Fore</name><position type=\"top\">0.2</position>\
         <material type=\"bulk\" density=\"630.0\">Plywood</material><length>0.01</length>\
         <radialposition>0.0</radialposition><radialdirection>0.0</radialdirection>\
         <outerradius>auto</outerradius></bulkhead>\
         <bulkhead><name>Aft</name><position type=\"bottom\">0.005</position>\
         <material type=\"bulk\" density=\"630.0\">Plywood</material><length>0.01</length>\
         <radialposition>0.0</radialposition><radialdirection>0.0</radialdirection>\
         <outerradius>auto</outerradius></bulkhead></subcomponents></nosecone>",
    );
    let (_, import) = imported(text.as_bytes());
    let (l, r): (f64, f64) = (0.25, 0.02815);
    let rho = (r * r + l * l) / (2.0 * r);
    let ogive = |x: f64| (rho * rho - (l - x).powi(2)).sqrt() + r - rho;
    let nose = &import.json["stages"][0]["components"][0]["children"];
    for (i, fore) in [(0, 0.2), (1, 0.245)] {
        let d = nose[i]["outer_diameter_m"].as_f64().unwrap();
        let want = 2.0 * (ogive(fore) - 0.002);
        assert!((d - want).abs() < 1e-15, "{}: {d} vs {want}", nose[i]);
    }
}

#[test]
fn a_tube_a_ring_or_a_shoulder_drawn_with_no_wall_weighs_nothing_as_in_openrocket() {
    // A coupler of no wall and an engine block of no thickness (a ring as wide inside as
    // out), which OpenRocket weighs at nothing, and the nose's shoulder with no wall: the
    // rocket weighs what the example weighs less the shoulder's tube (0.002 m of polypropylene,
    // od 0.0533, 0.05 long) but for the 0.1 µm wall it keeps (under a milligram).
    let text = edited(
        "<aftshoulderthickness>0.002</aftshoulderthickness>",
        "<aftshoulderthickness>0.0</aftshoulderthickness>",
    )
    .replacen(
        "<parachute>",
        "<tubecoupler><name>Coupler</name><position type=\"top\">0.3</position>\
         <material type=\"bulk\" density=\"1850.0\">Fiberglass</material><length>0.1</length>\
         <outerradius>0.0266</outerradius><thickness>0.0</thickness></tubecoupler>\
         <engineblock><name>Block</name><position type=\"top\">0.5</position>\
         <material type=\"bulk\" density=\"1850.0\">Fiberglass</material><length>0.01</length>\
         <outerradius>0.0266</outerradius><thickness>0.0</thickness></engineblock><parachute>",
        1,
    );
    let (design, import) = imported(text.as_bytes());
    let (plain, _) = imported(EXAMPLE.as_bytes());
    for name in ["Coupler", "Block"] {
        let c = design
            .components
            .iter()
            .find(|c| c.name == name)
            .expect(name);
        assert_eq!(c.mass_spec, crate::design::MassSpec::Mass(0.0), "{name}");
        assert!(noted(
            &import,
            &format!("{name}: no wall, so it weighs nothing")
        ));
    }
    let tube = |wall: f64| {
        900.0 * std::f64::consts::PI * (0.02665f64.powi(2) - (0.02665 - wall).powi(2)) * 0.05
    };
    let lost = dry(&plain).mass_kg - dry(&design).mass_kg;
    let want = tube(0.002) - tube(1e-7);
    assert!((lost - want).abs() < 1e-15, "{lost} vs {want}");
    assert!(tube(1e-7) < 1e-6);
}

#[test]
fn a_body_tube_of_no_length_holding_nothing_is_left_out() {
    let text = edited(
        "</bodytube>",
        "</bodytube><bodytube><name>Cut</name><finish>normal</finish>\
         <material type=\"bulk\" density=\"680.0\">Cardboard</material><length>0.0</length>\
         <thickness>0.0015</thickness><radius>auto 0.02815</radius></bodytube>",
    );
    let (design, import) = imported(text.as_bytes());
    let (plain, _) = imported(EXAMPLE.as_bytes());
    assert_eq!(design.components.len(), plain.components.len());
    assert_eq!(dry(&design), dry(&plain));
    assert!(noted(
        &import,
        "Cut: no length and nothing in it, left out."
    ));
}

#[test]
fn a_motor_named_as_its_maker_sells_it_flies_as_the_bundled_file_of_its_common_name_with_a_note() {
    // Cesaroni's full name (impulse, class and average thrust, delay) of the bundled K445.
    let text = edited(
        "<designation>I175</designation>",
        "<designation>1635K445-17A</designation>",
    );
    let import = super::import(text.as_bytes(), "r.ork").unwrap();
    assert_eq!(import.json["motor"], "Cesaroni_K445");
    assert!(noted(
        &import,
        "the motor Cesaroni Technology 1635K445-17A flies as the bundled Cesaroni_K445 (K445"
    ));
    // A name with no class and thrust in it, or of another maker's, is still not found.
    for (from, to) in [
        (
            "<designation>I175</designation>",
            "<designation>Mystery</designation>",
        ),
        (
            "<manufacturer>Cesaroni Technology</manufacturer>",
            "<manufacturer>AeroTech</manufacturer>",
        ),
    ] {
        let import = super::import(
            edited(from, to).replace("I175<", "K445-14A<").as_bytes(),
            "r.ork",
        )
        .unwrap();
        assert!(
            import.json.get("motor").is_none(),
            "{}",
            import.json["motor"]
        );
        assert!(noted(&import, "is not bundled with hpr-mc"));
    }
}

#[test]
fn a_clipped_transition_is_imported_clipped_and_weighed_so() {
    // A Haack boattail OpenRocket clips (its default for the shapes it can clip).
    let tail = |clipped: bool| {
        edited(
            "</bodytube>",
            &format!(
                "</bodytube><transition><name>Tail</name><length>0.05</length>\
                 <material type=\"bulk\" density=\"680.0\">Cardboard</material>\
                 <thickness>0.002</thickness><shape>haack</shape><shapeparameter>0.0</shapeparameter>\
                 <shapeclipped>{clipped}</shapeclipped>\
                 <foreradius>auto 0.02815</foreradius><aftradius>0.02</aftradius></transition>"
            ),
        )
    };
    let (clipped, import) = imported(tail(true).as_bytes());
    let (plain, _) = imported(tail(false).as_bytes());
    let json = &import.json["stages"][0]["components"][2];
    assert_eq!(json["clipped"], true, "{json}");
    let t = |d: &Design| match &d.component("tail").unwrap().kind {
        crate::ComponentKind::Transition(t) => *t,
        other => panic!("{other:?}"),
    };
    let nose = crate::design::NoseShape::Haack { c: 0.0 };
    let want = crate::design::shapes::clip_length(nose, 0.05, 0.02, 0.02815);
    assert!(want > 0.0);
    assert_eq!(t(&clipped).clip_m, want);
    assert_eq!(t(&plain).clip_m, 0.0);
    // The unclipped Haack rises vertically from its small end, the clipped one (the base of
    // a long Haack nose) at a finite slope: the clipped shell is the slimmer, the lighter.
    let idx = |d: &Design| d.component_index("tail").unwrap();
    let (mc, mp) = (
        crate::mass::component_own(&clipped, idx(&clipped)).mass_kg,
        crate::mass::component_own(&plain, idx(&plain)).mass_kg,
    );
    assert!(mc < mp, "{mc} vs {mp}");
    let r = |d: &Design, x: f64| {
        crate::design::shapes::body_radius(&d.components[idx(d)].kind, 0.05, x)
    };
    assert!(r(&clipped, 0.045) < r(&plain, 0.045));
}

#[test]
fn the_whole_rocket_s_override_becomes_its_one_stage_s() {
    let with = |extra: &str| {
        edited(
            "<name>Example: minimal 54 mm rocket</name>",
            &format!("<name>Example: minimal 54 mm rocket</name>{extra}"),
        )
    };
    let text = with(
        "<overridemass>1.5</overridemass><overridecg>0.5</overridecg>\
         <overridesubcomponents>true</overridesubcomponents>",
    );
    let (design, import) = imported(text.as_bytes());
    assert_eq!(design.stages[0].overrides.mass_kg, Some(1.5));
    assert_eq!(design.stages[0].overrides.cg_m, Some(0.5));
    let dry = dry(&design);
    assert_eq!(dry.mass_kg, 1.5);
    assert!((dry.cg_m.x - 0.5).abs() < 1e-15);
    assert!(noted(
        &import,
        "The whole rocket's mass override is its stage's."
    ));
    // Not covering its parts (OpenRocket would add the mass on top), it is refused.
    let e = refusal(with("<overridemass>1.5</overridemass>").as_bytes(), "r.ork");
    assert!(e.contains("an override of the whole rocket"), "{e}");
}

#[test]
fn a_part_of_no_length_is_left_out_if_it_weighs_nothing_and_kept_as_a_point_mass_if_not() {
    let text = edited(
        "<parachute>",
        "<centeringring><name>Marker</name><position type=\"absolute\">0.6</position>\
         <material type=\"bulk\" density=\"680.0\">Cardboard</material><length>0.0</length>\
         <outerradius>auto 0.02665</outerradius><innerradius>auto 0.02</innerradius></centeringring>\
         <masscomponent><name>Point</name><position type=\"absolute\">0.7</position>\
         <packedlength>0.0</packedlength><packedradius>0.01</packedradius><mass>0.1</mass>\
         </masscomponent><parachute>",
    );
    let (design, import) = imported(text.as_bytes());
    let (plain, _) = imported(EXAMPLE.as_bytes());
    assert!(design.components.iter().all(|c| c.name != "Marker"));
    assert!(noted(
        &import,
        "Marker: no length, so it weighs nothing; left out."
    ));
    assert!(noted(
        &import,
        "Point: no length; its mass is put in 0.1 µm of it"
    ));
    let (with, without) = (dry(&design), dry(&plain));
    assert!((with.mass_kg - without.mass_kg - 0.1).abs() < 1e-15);
    // The point's center: 0.7 m aft of the tip, to the 0.05 µm of its length.
    let point_x = (with.cg_m.x * with.mass_kg - without.cg_m.x * without.mass_kg) / 0.1;
    assert!((point_x - 0.7).abs() < 1e-7, "{point_x}");
}

#[test]
fn a_streamer_flies_as_a_canopy_of_openrocket_s_streamer_drag() {
    // A 1 m × 0.1 m strip of 0.1 kg/m²: OpenRocket's automatic cd is
    // 0.034 (0.1 + 0.025)/0.105 (1 + 1)/1 = 0.080952..., on the strip's 0.1 m².
    let text = edited(
        "<parachute>",
        "<streamer><name>Streamer</name><position type=\"top\">0.2</position>\
         <packedlength>0.05</packedlength><packedradius>0.015</packedradius><cd>auto</cd>\
         <material type=\"surface\" density=\"0.1\">Mylar</material>\
         <deployevent>apogee</deployevent><deployaltitude>200.0</deployaltitude>\
         <deploydelay>0.5</deploydelay><striplength>1.0</striplength><stripwidth>0.1</stripwidth>\
         </streamer><parachute>",
    );
    let (design, import) = imported(text.as_bytes());
    let c = design.component("streamer").expect("the streamer");
    let crate::ComponentKind::Parachute(p) = &c.kind else {
        panic!("{:?}", c.kind)
    };
    let cd = 0.034 * (0.125 / 0.105) * 2.0;
    assert!((p.cd - cd).abs() < 1e-15, "{}", p.cd);
    assert!((p.cds_m2() - cd * 0.1).abs() < 1e-15, "{}", p.cds_m2());
    assert_eq!(c.mass_spec, crate::design::MassSpec::Mass(0.1 * 0.1));
    let deploy = p.deploy.expect("deploys");
    assert_eq!(deploy.lag_s, 0.5);
    assert!(noted(
        &import,
        "Streamer: a streamer, flown as a canopy of its drag, cd 0.081 × the strip's 0.1 m²"
    ));
    // A given cd is taken as it is; the automatic one is at most 0.4.
    let given = imported(text.replace("<cd>auto</cd>", "<cd>0.6</cd>").as_bytes()).0;
    let short = imported(
        text.replace("<striplength>1.0<", "<striplength>0.05<")
            .as_bytes(),
    )
    .0;
    for (d, want) in [(given, 0.6), (short, 0.4)] {
        match &d.component("streamer").unwrap().kind {
            crate::ComponentKind::Parachute(p) => assert_eq!(p.cd, want),
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn a_part_with_no_wall_weighs_its_mass_override() {
    // OpenRocket weighs a coupler drawn with no wall at its override, 0.2 kg at its center.
    let text = edited(
        "<parachute>",
        "<tubecoupler><name>Coupler</name><position type=\"top\">0.3</position>\
         <overridemass>0.2</overridemass><overridesubcomponentsmass>false</overridesubcomponentsmass>\
         <material type=\"bulk\" density=\"1850.0\">Fiberglass</material><length>0.1</length>\
         <outerradius>0.0266</outerradius><thickness>0.0</thickness></tubecoupler><parachute>",
    );
    let (design, _) = imported(text.as_bytes());
    let (plain, _) = imported(EXAMPLE.as_bytes());
    let idx = design
        .components
        .iter()
        .position(|c| c.name == "Coupler")
        .unwrap();
    let coupler = crate::mass::subtree(&design, idx);
    assert!((coupler.mass_kg - 0.2).abs() < 1e-15);
    // Its center: the tube's, 0.35 m below the body's top (0.3 + 0.05).
    let body_top = design.components[design.components[idx].parent.unwrap()].x_top_m;
    assert!(
        (coupler.cg_m.x - (body_top + 0.35)).abs() < 1e-12,
        "{}",
        coupler.cg_m.x
    );
    assert!((dry(&design).mass_kg - dry(&plain).mass_kg - 0.2).abs() < 1e-12);
}

#[test]
fn a_cluster_of_inner_tubes_is_placed_and_weighed_as_openrocket_places_and_weighs_it() {
    // Four shear-pin tubes (od 4 mm, wall 1 mm, 10 mm long, 1000 kg/m³) in OpenRocket's
    // 4-ring at scale 2 (separation 2 × 4 mm = 8 mm) turned 45°: the square's corners
    // (±½, ±½) land on the axes, √½ × 8 mm from the body's.
    let pins = "<innertube><name>Shear pins</name><position type=\"top\">0.05</position>\
        <material type=\"bulk\" density=\"1000.0\">Pins</material><length>0.01</length>\
        <radialposition>0.0</radialposition><radialdirection>0.0</radialdirection>\
        <outerradius>0.002</outerradius><thickness>0.001</thickness>\
        <clusterconfiguration>4-ring</clusterconfiguration><clusterscale>2.0</clusterscale>\
        <clusterrotation>45.0</clusterrotation></innertube><innertube>";
    let (design, _) = imported(edited("<innertube>", pins).as_bytes());
    let (plain, _) = imported(EXAMPLE.as_bytes());
    let idx = design
        .components
        .iter()
        .position(|c| c.name == "Shear pins")
        .expect("the pins");
    let crate::ComponentKind::InnerTube(t) = &design.components[idx].kind else {
        panic!("not an inner tube")
    };
    let r = 0.008 * 0.5f64.sqrt();
    let want = [[0.0, r], [r, 0.0], [0.0, -r], [-r, 0.0]];
    assert_eq!(t.cluster_offsets_m.len(), 4);
    for (got, want) in t.cluster_offsets_m.iter().zip(want) {
        assert!(
            (got[0] - want[0]).abs() < 1e-17 && (got[1] - want[1]).abs() < 1e-17,
            "{got:?} vs {want:?}"
        );
    }
    // Four tubes' mass, one tube's axial inertia each plus its offset's.
    let one = 1000.0 * std::f64::consts::PI * (0.002f64.powi(2) - 0.001f64.powi(2)) * 0.01;
    let own = crate::mass::component_own(&design, idx);
    assert!(close(own.mass_kg, 4.0 * one, 1e-14), "{}", own.mass_kg);
    assert!(own.cg_m.y.abs() < 1e-18 && own.cg_m.z.abs() < 1e-18);
    let axial = 4.0 * one * ((0.002f64.powi(2) + 0.001f64.powi(2)) / 2.0 + r * r);
    assert!(close(own.axial_inertia(), axial, 1e-12));
    assert!(close(
        dry(&design).mass_kg,
        dry(&plain).mass_kg + 4.0 * one,
        1e-14
    ));
    // The motor mount as a cluster: OpenRocket's "double" (points ∓½ across, times the
    // 40 mm tube's diameter) holds two motors either side of the axis; a pattern OpenRocket
    // does not have is refused.
    let mount_as = |pattern: &str| {
        edited(
            "<clusterconfiguration>single",
            &format!("<clusterconfiguration>{pattern}"),
        )
    };
    let (pair, _) = imported(mount_as("double").as_bytes());
    let mount = pair.motor_mount.expect("a mount");
    assert_eq!(mount.motors, 2);
    assert_eq!(pair.motor_offsets_m(), &[[-0.02, 0.0], [0.02, 0.0]]);
    let unknown = refusal(mount_as("7-ring").as_bytes(), "r.ork");
    assert!(
        unknown.contains("<clusterconfiguration>") && unknown.contains("\"7-ring\" is not one of"),
        "{unknown}"
    );
}

#[test]
fn each_skin_keeps_its_own_finish_for_the_drag_estimate_as_openrocket_takes_it() {
    // A polished nose cone on the example's normal body and fins: the nose's skin is taken at
    // 2 µm, the others at 60 µm (the estimate's own, the finish most skins have), and the
    // drag is the example's with only the nose's friction changed: the same design written
    // by hand with the nose's `roughness_m` gives the same table, bit for bit.
    let text = edited(
        "<name>Nose cone</name>\n            <finish>normal</finish>",
        "<name>Nose cone</name>\n            <finish>polished</finish>",
    );
    let (design, import) = imported(text.as_bytes());
    let parts = &import.json["stages"][0]["components"];
    assert_eq!(parts[0]["roughness_m"], json!(2e-6));
    assert_eq!(parts[1]["roughness_m"], json!(60e-6));
    assert_eq!(parts[1]["children"][0]["roughness_m"], json!(60e-6));
    assert_eq!(import.json["drag"]["estimate"]["roughness_m"], json!(60e-6));
    let (plain, plain_import) = imported(EXAMPLE.as_bytes());
    let mut by_hand = plain_import.json.clone();
    by_hand["stages"][0]["components"][0]["roughness_m"] = json!(2e-6);
    let by_hand = Design::from_json_str(&by_hand.to_string(), None).unwrap();
    let (got, want, normal) = (
        AeroModel::from_design(&design).unwrap(),
        AeroModel::from_design(&by_hand).unwrap(),
        AeroModel::from_design(&plain).unwrap(),
    );
    for mach in [0.0, 0.3, 0.8, 1.5] {
        let g = got.drag_power_off.at(mach);
        assert_eq!(
            g.to_bits(),
            want.drag_power_off.at(mach).to_bits(),
            "Mach {mach}"
        );
        // The nose's friction is roughness-limited at 60 µm (0.032 (60e-6/L)^0.2, about
        // 0.0047) and at 2 µm smooth-turbulent (about 0.0029 here): the polished rocket
        // has less drag at every speed but rest.
        if mach > 0.0 {
            assert!(g < normal.drag_power_off.at(mach), "Mach {mach}");
        }
    }
}
