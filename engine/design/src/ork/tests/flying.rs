//! How an OpenRocket file flies: its parachutes' deployment and its own simulation's
//! settings, said as `fly`'s flags.

use super::*;

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
