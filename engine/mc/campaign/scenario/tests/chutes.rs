//! Parachutes (their canopy and deployment, from the scenario or the design) and requirements:
//! read, and refused by key.

use super::*;

#[test]
fn a_parachute_takes_rocketpy_s_canopy_radius_height_and_porosity_or_its_defaults() {
    let s = parse(
        r#"
[[parachutes]]
name = "drogue"
cds_m2 = 0.1
trigger = "apogee"
radius_m = 0.35
height_m = 0.2
porosity = 0.1
"#,
    )
    .expect("parses");
    assert_eq!(s.parachutes[0].canopy, hpr_sim::CanopyShape::default());
    assert_eq!(
        s.parachutes[1].canopy,
        hpr_sim::CanopyShape {
            radius_m: Some(0.35),
            height_m: Some(0.2),
            porosity: 0.1,
        }
    );
    let chute = |line: &str| {
        refused(&format!(
            "[[parachutes]]\nname = \"drogue\"\ncds_m2 = 0.1\ntrigger = \"apogee\"\n{line}\n"
        ))
    };
    for (line, key, rule) in [
        (
            "radius_m = 0.0",
            "parachutes[1].radius_m",
            "positive and finite",
        ),
        (
            "height_m = -0.2",
            "parachutes[1].height_m",
            "positive and finite",
        ),
        (
            "porosity = 1.0",
            "parachutes[1].porosity",
            "at least 0 and below 1",
        ),
        (
            "porosity = -0.1",
            "parachutes[1].porosity",
            "at least 0 and below 1",
        ),
    ] {
        let (k, r) = chute(line);
        assert_eq!(k, key, "{line}");
        assert!(r.contains(rule), "{line}: {r}");
    }
}

/// A scenario flying OpenRocket's example design with the parachutes `chutes` (TOML).
fn with_ork_chutes(chutes: &str) -> Result<Scenario, ScenarioError> {
    let text = format!(
        "seed = 1\nvariants_per_point = 2\n[design]\nfile = \"../validation/designs/example-minimal.ork\"\n\
         [motor]\nname = \"Cesaroni_I175\"\n{chutes}"
    );
    Scenario::parse(&text, &path())
}

#[test]
fn a_parachute_may_take_its_canopy_and_deployment_from_a_component_of_the_design() {
    // The example's parachute: cd 1.5 on a 0.6 m canopy, deployed (as OpenRocket says)
    // descending through 300 m, at once.
    let cds = 1.5 * std::f64::consts::PI * 0.3 * 0.3;
    let s = with_ork_chutes("[[parachutes]]\ncomponent = \"parachute\"\n").unwrap();
    let p = &s.parachutes[0];
    assert_eq!(p.name, "parachute");
    assert!((p.cds_m2 - cds).abs() < 1e-15, "{}", p.cds_m2);
    assert_eq!(p.trigger, Trigger::HeightDescending { height_m: 300.0 });
    assert_eq!(p.lag_s, 0.0);
    // What the table gives wins: its name, CdS, lag, trigger.
    let s = with_ork_chutes(
        "[[parachutes]]\ncomponent = \"parachute\"\nname = \"main\"\ncds_m2 = 0.5\nlag_s = 1.5\n",
    )
    .unwrap();
    let p = &s.parachutes[0];
    assert_eq!((p.name.as_str(), p.cds_m2, p.lag_s), ("main", 0.5, 1.5));
    assert_eq!(p.trigger, Trigger::HeightDescending { height_m: 300.0 });
    let s = with_ork_chutes("[[parachutes]]\ncomponent = \"parachute\"\ntrigger = \"apogee\"\n")
        .unwrap();
    assert_eq!(
        (s.parachutes[0].trigger, s.parachutes[0].lag_s),
        (Trigger::Apogee, 0.0)
    );
    // Its CdS can be dispersed under its name, as any parachute's.
    let s = with_ork_chutes(
        "[[parachutes]]\ncomponent = \"parachute\"\n[dispersions.parachutes.parachute]\ncds_m2 = { dist = \"normal\", sigma = 0.01 }\n",
    );
    assert!(s.is_ok(), "{s:?}");
    // Refused, naming the key: no such component, not a parachute, no name or CdS without a
    // component, no trigger where the component says no deployment.
    let cases = [
        (
            "[[parachutes]]\ncomponent = \"nothing\"\n",
            "parachutes[0].component",
            "no component \"nothing\"",
        ),
        (
            "[[parachutes]]\ncomponent = \"nose_cone\"\n",
            "parachutes[0].component",
            "is not a parachute",
        ),
        (
            "[[parachutes]]\ncds_m2 = 0.5\ntrigger = \"apogee\"\n",
            "parachutes[0].name",
            "is missing",
        ),
        (
            "[[parachutes]]\nname = \"a\"\ntrigger = \"apogee\"\n",
            "parachutes[0].cds_m2",
            "is missing",
        ),
    ];
    for (chutes, key, says) in cases {
        let e = with_ork_chutes(chutes).unwrap_err();
        assert_eq!(e.key(), key, "{e}");
        assert!(e.to_string().contains(says), "{e}");
    }
    let text = concat!(
        "seed = 1\nvariants_per_point = 2\n[design]\nfile = \"../validation/designs/crosscheck-54mm-canted-boattail.json\"\n",
        "[motor]\nname = \"Cesaroni_I175\"\n[[parachutes]]\ncomponent = \"chute\"\n"
    );
    let e = Scenario::parse(text, &path()).unwrap_err();
    assert_eq!(e.key(), "parachutes[0].trigger", "{e}");
    assert!(e.to_string().contains("says no \"deploy\""), "{e}");
}

#[test]
fn a_requirement_needs_a_bound_finite_bounds_and_min_at_most_max() {
    let s = parse("[requirements]\napogee_m = { max = 3048.0 }\nrail_exit_speed_m_s = { min = 15.0, max = 15.0 }\n")
        .expect("two requirements");
    assert_eq!(
        s.requirements,
        vec![
            RequirementSpec {
                metric: "apogee_m".into(),
                min: None,
                max: Some(3048.0)
            },
            RequirementSpec {
                metric: "rail_exit_speed_m_s".into(),
                min: Some(15.0),
                max: Some(15.0)
            },
        ]
    );
    let r = &s.requirements[0];
    assert!(r.met_by(3048.0) && !r.met_by(3048.0001) && !r.met_by(f64::NAN));
    assert_eq!(r.bounds_text("m"), "≤ 3048 m");
    assert_eq!(s.requirements[1].bounds_text("1"), "in [15, 15]");
    let (k, r) = refused("[requirements]\napogee_m = {}\n");
    assert_eq!(
        (k.as_str(), r.as_str()),
        ("requirements.apogee_m", "needs min, max or both")
    );
    let (k, r) = refused("[requirements]\napogee_m = { min = 2.0, max = 1.0 }\n");
    assert_eq!(k, "requirements.apogee_m");
    assert!(r.contains("min (2) is above max (1)"), "{r}");
    let (k, _) = refused("[requirements]\napogee_m = { min = nan }\n");
    assert_eq!(k, "requirements.apogee_m.min");
    let (k, r) = refused("[requirements]\napogee_m = { below = 3.0 }\n");
    assert_eq!(k, "requirements.apogee_m.below");
    assert!(r.contains("unknown field"), "{r}");
}

#[test]
fn a_requirement_on_a_metric_the_scenario_does_not_have_is_refused_listing_its_metrics() {
    // BASE has a parachute named main and a shift named ballast: their metrics exist.
    let ok = Prepared::new(
        parse("[requirements]\nparachute_main_deploy_speed_m_s = { max = 30.0 }\nshift_ballast_margin_after_cal = { min = 1.5 }\napogee_m = { min = 1.0 }\n")
            .unwrap(),
    )
    .expect("metrics of this scenario");
    // In the metrics' order, each with its column.
    let order: Vec<&str> = ok
        .requirements
        .iter()
        .map(|(_, r)| r.metric.as_str())
        .collect();
    assert_eq!(
        order,
        [
            "apogee_m",
            "shift_ballast_margin_after_cal",
            "parachute_main_deploy_speed_m_s"
        ]
    );
    for (m, r) in &ok.requirements {
        assert_eq!(ok.metrics[*m].name, r.metric);
    }
    let e = Prepared::new(
        parse("[requirements]\nparachute_drogue_deploy_speed_m_s = { max = 30.0 }\n").unwrap(),
    )
    .unwrap_err();
    assert_eq!(e.key(), "requirements.parachute_drogue_deploy_speed_m_s");
    assert!(
        e.to_string().contains("is not a metric of this scenario")
            && e.to_string().contains("parachute_main_deploy_speed_m_s"),
        "{e}"
    );
}
