//! Scenario errors name the key and the rule; a good scenario reads into the expected inputs.

use super::*;
use crate::campaign::fly::Prepared;
use crate::campaign::sample::Shape;
use hpr_sim::wind::WindRow;
use std::path::{Path, PathBuf};

mod chutes;
mod motor;

/// A scenario file in the repository's `scenarios/` directory (so relative paths resolve);
/// it is only parsed, never written.
fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join("test.toml")
}

const BASE: &str = r#"
seed = 1
variants_per_point = 3
[design]
file = "../validation/designs/synthetic-54mm-three-fin.json"
ballast = "ballast"
[motor]
name = "Cesaroni_I175"
[environment]
wind_speed_m_s = 4.0
[[parachutes]]
name = "main"
cds_m2 = 0.9
lag_s = 1.0
trigger = "apogee"
[[shifts]]
component = "ballast"
travel_m = 0.2
duration_s = 1.0
trigger = { time_s = 5.0 }
"#;

fn parse(extra: &str) -> Result<Scenario, ScenarioError> {
    Scenario::parse(&format!("{BASE}{extra}"), &path())
}

/// The error's key and rule, for a scenario that must be refused.
fn refused(extra: &str) -> (String, String) {
    match parse(extra) {
        Ok(_) => panic!("the scenario was accepted:\n{extra}"),
        Err(ScenarioError::Invalid { key, rule, file }) => {
            assert!(
                file.ends_with("test.toml"),
                "the error names the file: {file}"
            );
            (key, rule)
        }
        Err(e) => panic!("unexpected error {e}"),
    }
}

#[test]
fn a_good_scenario_has_its_inputs_in_canonical_order_with_keys_columns_and_units() {
    let s = parse(
        r#"
[sweep]
shifts.ballast.travel_m = [0.0, 0.3]
wind_speed_m_s = [2.0, 4.0, 6.0]
[dispersions]
drag_scale = { dist = "normal", sigma = 0.05, relative = true }
parachutes.main.cds_m2 = { dist = "uniform", min = -0.1, max = 0.1 }
shifts.ballast.time_s = { dist = "triangular", min = -0.1, max = 0.2 }
"#,
    )
    .unwrap();
    let keys: Vec<(&str, &str, &str)> = s
        .inputs
        .iter()
        .map(|i| (i.key.as_str(), i.column.as_str(), i.unit))
        .collect();
    assert_eq!(
        keys,
        vec![
            ("drag_scale", "drag_scale", "1"),
            ("wind_speed_m_s", "wind_speed_m_s", "m/s"),
            ("parachutes.main.cds_m2", "parachute_main_cds_m2", "m²"),
            ("shifts.ballast.travel_m", "shift_ballast_travel_m", "m"),
            ("shifts.ballast.time_s", "shift_ballast_time_s", "s"),
        ]
    );
    assert_eq!(s.points(), 6);
    assert_eq!(s.total_variants(), Some(18));
    assert_eq!(s.name, "test");
    assert_eq!(s.shifts[0].name, "ballast");
    let d = s.inputs[4].dispersion.unwrap();
    assert_eq!(
        d.shape,
        Shape::Triangular {
            min: -0.1,
            mode: 0.0,
            max: 0.2
        }
    );
}

#[test]
fn an_unknown_key_is_refused_with_its_path() {
    let (key, rule) =
        refused("[dispersions]\nwind_sped_m_s = { dist = \"normal\", sigma = 1.0 }\n");
    assert_eq!(key, "dispersions.wind_sped_m_s");
    assert!(rule.contains("unknown field `wind_sped_m_s`"), "{rule}");
    assert!(
        rule.contains("wind_speed_m_s"),
        "the rule lists the known keys: {rule}"
    );
    let (key, rule) = refused("[rail]\nlenght_m = 2.0\n");
    assert_eq!(key, "rail.lenght_m");
    assert!(rule.contains("unknown field"), "{rule}");
    let (key, _) =
        refused("[dispersions]\nwind_speed_m_s = { dist = \"normal\", sigma = 1.0, sd = 2.0 }\n");
    assert_eq!(key, "dispersions.wind_speed_m_s.sd");
}

#[test]
fn bad_distribution_parameters_are_refused_with_the_rule() {
    let cases = [
        (
            "wind_speed_m_s = { dist = \"normal\", sigma = -1.0 }",
            "dispersions.wind_speed_m_s.sigma",
            "must be positive",
        ),
        (
            "wind_speed_m_s = { dist = \"normal\", sigma = nan }",
            "dispersions.wind_speed_m_s.sigma",
            "must be finite",
        ),
        (
            "wind_speed_m_s = { dist = \"normal\" }",
            "dispersions.wind_speed_m_s.sigma",
            "needs sigma",
        ),
        (
            "wind_speed_m_s = { dist = \"uniform\", min = 1.0, max = 1.0 }",
            "dispersions.wind_speed_m_s.max",
            "greater than min",
        ),
        (
            "wind_speed_m_s = { dist = \"uniform\", min = 1.0, max = 2.0, sigma = 1.0 }",
            "dispersions.wind_speed_m_s.sigma",
            "has no sigma",
        ),
        (
            "wind_speed_m_s = { dist = \"triangular\", min = 0.1, max = 2.0 }",
            "dispersions.wind_speed_m_s.mode",
            "from min to max",
        ),
        (
            "wind_speed_m_s = { dist = \"truncated_normal\", sigma = 1.0 }",
            "dispersions.wind_speed_m_s.min",
            "needs min, max or both",
        ),
        (
            // A bound a typo's distance into the tail: no normal draw could reach it.
            "wind_speed_m_s = { dist = \"truncated_normal\", sigma = 1.5, min = 1e300 }",
            "dispersions.wind_speed_m_s.min",
            "lies 6.667e299 sigma above the distribution's center",
        ),
        (
            "wind_speed_m_s = { dist = \"truncated_normal\", sigma = 0.5, bias = 1.0, max = -3.01 }",
            "dispersions.wind_speed_m_s.max",
            "lies 8.020e0 sigma below the distribution's center",
        ),
        (
            "wind_speed_m_s = { dist = \"lognormal\", sigma = 0.1, relative = true }",
            "dispersions.wind_speed_m_s.relative",
            "always relative",
        ),
        (
            "wind_speed_m_s = { dist = \"gauss\", sigma = 0.1 }",
            "dispersions.wind_speed_m_s.dist",
            "unknown distribution",
        ),
        (
            "wind_speed_m_s = { dist = \"normal\", sigma = 0.1, mean = 3.0, relative = true }",
            "dispersions.wind_speed_m_s.mean",
            "can't be relative",
        ),
    ];
    for (line, key, rule) in cases {
        let (k, r) = refused(&format!("[dispersions]\n{line}\n"));
        assert_eq!(k, key, "{line}");
        assert!(r.contains(rule), "{line}: {r}");
    }
}

#[test]
fn a_truncation_reaching_exactly_eight_sigma_from_the_center_is_kept_and_drawn_inside_it() {
    // min = bias + 8σ is the farthest a truncated normal may begin: accepted, and its
    // draws (Robert's exponential proposal) all lie at least 7 m/s over the center, and
    // their mean is the tail's exact one, φ(8)/Q(8) = 8.121368 σ over the bias.
    let s = parse(
        "[dispersions]\nwind_speed_m_s = { dist = \"truncated_normal\", sigma = 0.5, bias = 3.0, min = 7.0 }\n",
    )
    .unwrap();
    let d = s.inputs[0].dispersion.unwrap();
    let mut rng = <rand::rngs::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(7);
    let n = 20_000;
    let mut sum = 0.0;
    for _ in 0..n {
        let v = d.sample(4.0, &mut rng);
        assert!(v >= 4.0 + 7.0, "{v}");
        sum += v;
    }
    // Standard error of the mean: the tail's σ (0.1197 σ = 0.060 m/s) / √n = 4.2e-4 m/s.
    let mean = sum / n as f64;
    let want = 4.0 + 3.0 + 0.5 * 8.121_368;
    assert!((mean - want).abs() < 2e-3, "{mean} against {want}");
}

#[test]
fn an_empty_or_out_of_range_sweep_is_refused() {
    let (k, r) = refused("[sweep]\nwind_speed_m_s = []\n");
    assert_eq!(
        (k.as_str(), r.as_str()),
        (
            "sweep.wind_speed_m_s",
            "empty sweep: give at least one value"
        )
    );
    let (k, r) = refused("[sweep]\nrail_inclination_deg = [80.0, 95.0]\n");
    assert_eq!(k, "sweep.rail_inclination_deg[1]");
    assert!(r.contains("at most 90"), "{r}");
    let (k, r) = refused("[sweep]\nwind_speed_m_s = [1.0, 2.0, 1.0]\n");
    assert_eq!(k, "sweep.wind_speed_m_s[2]");
    assert!(r.contains("twice"), "{r}");
}

#[test]
fn a_missing_design_file_is_refused_naming_the_key() {
    let text = BASE.replace("synthetic-54mm-three-fin.json", "no-such-design.json");
    let e = Scenario::parse(&text, &path()).unwrap_err();
    assert_eq!(e.key(), "design.file");
    assert!(e.to_string().contains("no such file"), "{e}");
    assert!(e.to_string().contains("no-such-design.json"), "{e}");
}

#[test]
fn parts_and_triggers_must_exist_to_be_dispersed() {
    let (k, r) =
        refused("[dispersions.parachutes.drogue]\ncds_m2 = { dist = \"normal\", sigma = 0.1 }\n");
    assert_eq!(k, "dispersions.parachutes.drogue");
    assert!(
        r.contains("no parachute is named \"drogue\"") && r.contains("main"),
        "{r}"
    );
    let (k, r) =
        refused("[dispersions.parachutes.main]\nheight_m = { dist = \"normal\", sigma = 10.0 }\n");
    assert_eq!(k, "dispersions.parachutes.main.height_m");
    assert!(r.contains("apogee, which has no number"), "{r}");
    let (k, r) = refused("[sweep.shifts.ballast]\nheight_m = [100.0]\n");
    assert_eq!(k, "sweep.shifts.ballast.height_m");
    assert!(r.contains("its number is time_s"), "{r}");
}

#[test]
fn triggers_integrators_and_names_are_checked() {
    let text = BASE.replace("trigger = \"apogee\"", "trigger = \"apogée\"");
    let e = Scenario::parse(&text, &path()).unwrap_err();
    assert_eq!(e.key(), "parachutes[0].trigger");
    assert!(e.to_string().contains("unknown trigger"), "{e}");
    let (k, _) = refused("[integrator]\nmethod = \"rk4\"\n");
    assert_eq!(k, "integrator.step_s");
    let (k, _) = refused("[integrator]\nmethod = \"rk4\"\nstep_s = 0.01\nrtol = 1e-6\n");
    assert_eq!(k, "integrator.rtol");
    let (k, _) = refused("[run]\nchunk_size = 0\n");
    assert_eq!(k, "run.chunk_size");
    let e = Scenario::parse(&format!("name = \"my run\"\n{BASE}"), &path()).unwrap_err();
    let (k, r) = (e.key().to_string(), e.to_string());
    assert_eq!(k, "name");
    assert!(r.contains("output directory"), "{r}");
}

#[test]
fn a_toml_syntax_error_says_where() {
    let e = parse("[sweep\n").unwrap_err();
    assert_eq!(e.key(), "(syntax)");
    assert!(e.to_string().contains("line"), "{e}");
    assert!(!e.to_string().contains("JSON design"), "{e}");
    // A design file given where a scenario belongs is recognised as one.
    let e = Scenario::parse("{\n  \"name\": \"x\"\n}\n", &path()).unwrap_err();
    assert_eq!(e.key(), "(syntax)");
    assert!(
        e.to_string().contains("this looks like a JSON design"),
        "{e}"
    );
}

#[test]
fn a_value_of_the_wrong_kind_is_named_in_plain_words() {
    let e = Scenario::parse(&BASE.replace("seed = 1", "seed = -5"), &path()).unwrap_err();
    assert_eq!(e.key(), "seed");
    assert!(
        e.to_string().contains("expected a whole number, 0 or more"),
        "{e}"
    );
    let e = parse("[rail]\nlength_m = \"1.83\"\n").unwrap_err();
    assert_eq!(e.key(), "rail.length_m");
    assert!(e.to_string().contains("expected a number"), "{e}");
    assert!(!e.to_string().contains("f64"), "{e}");
}

#[test]
fn a_motor_named_in_a_file_after_a_hash_is_found_relative_to_the_scenario() {
    let named = "../engine/design/motors/Cesaroni_I175.eng#411-I175-WH-14A";
    let s = Scenario::parse(&BASE.replace("Cesaroni_I175", named), &path()).unwrap();
    let dir = path().parent().unwrap().to_path_buf();
    assert_eq!(
        s.motor,
        format!(
            "{}#411-I175-WH-14A",
            dir.join("../engine/design/motors/Cesaroni_I175.eng")
                .display()
        )
    );
    let prepared = Prepared::new(s).unwrap();
    assert_eq!(prepared.motor().designation, "411-I175-WH-14A");
    // A name the file does not hold is the motor's key's error, listing what it holds.
    let wrong = BASE.replace(
        "Cesaroni_I175",
        "../engine/design/motors/Cesaroni_I175.eng#K550",
    );
    let e = Prepared::new(Scenario::parse(&wrong, &path()).unwrap()).unwrap_err();
    assert_eq!(e.key(), "motor.name");
    assert!(
        e.to_string()
            .contains("no motor named `K550` (it holds 411-I175-WH-14A)"),
        "{e}"
    );
}

#[test]
fn rules_that_need_the_design_and_motor_name_their_key() {
    let prep = |extra: &str| Prepared::new(parse(extra).unwrap()).unwrap_err();
    let e = Prepared::new(
        Scenario::parse(&BASE.replace("Cesaroni_I175", "Nobody_Z9"), &path()).unwrap(),
    )
    .unwrap_err();
    assert_eq!(e.key(), "motor.name");
    // A motor too wide for the mount is the motor's fault too, not the sweep's.
    let e = Prepared::new(
        Scenario::parse(&BASE.replace("Cesaroni_I175", "Cesaroni_M1670"), &path()).unwrap(),
    )
    .unwrap_err();
    assert_eq!(e.key(), "motor.name");
    assert!(e.to_string().contains("the motor is too wide"), "{e}");
    let text = BASE.replace("ballast = \"ballast\"", "ballast = \"lead\"");
    let e = Prepared::new(Scenario::parse(&text, &path()).unwrap()).unwrap_err();
    assert_eq!(e.key(), "design.ballast");
    assert!(
        e.to_string().contains("no component with id \"lead\""),
        "{e}"
    );
    let e = prep("[sweep]\nwind_speed_m_s = [0.0, 3.0]\n[dispersions]\nwind_speed_m_s = { dist = \"normal\", sigma = 0.1, relative = true }\n");
    assert_eq!(e.key(), "dispersions.wind_speed_m_s");
    assert!(
        e.to_string().contains("which is 0") && e.to_string().contains("wind_speed_m_s = 0"),
        "{e}"
    );
    // A shift of a part the design does not have is the shift's component's fault, not the
    // sweep's.
    // So is a part the simulator will not move (fins are on the outside).
    for (part, rule) in [
        ("ballastt", "no component with id \"ballastt\""),
        ("fins", "outside of the airframe"),
    ] {
        let text = BASE.replace(
            "component = \"ballast\"",
            &format!("component = \"{part}\""),
        );
        let e = Prepared::new(Scenario::parse(&text, &path()).unwrap()).unwrap_err();
        assert_eq!(e.key(), "shifts[0].component", "{part}");
        assert!(e.to_string().contains(rule), "{e}");
    }
    // A file that is not there is said once.
    let e = Scenario::load(&path().with_file_name("no-such-scenario.toml")).unwrap_err();
    let chain = format!("{:#}", anyhow::Error::from(e));
    assert_eq!(chain.matches("os error").count(), 1, "{chain}");
    // A sweep point whose nominal flight the simulator refuses: 0.9 m of travel takes the
    // ballast out of the body tube.
    let e = prep("[sweep]\nshifts.ballast.travel_m = [0.1, 0.9]\n");
    assert_eq!(e.key(), "sweep");
    assert!(
        e.to_string().contains("shifts.ballast.travel_m = 0.9") && e.to_string().contains("out of"),
        "{e}"
    );
}

#[test]
fn a_swept_or_dispersed_ballast_must_be_an_internal_part_that_holds_nothing() {
    let dispersed = "[dispersions]\nballast_kg = { dist = \"normal\", sigma = 0.002 }\n";
    let with = |id: &str, extra: &str| {
        let text = format!("{BASE}{extra}")
            .replace("ballast = \"ballast\"", &format!("ballast = \"{id}\""));
        Prepared::new(Scenario::parse(&text, &path()).unwrap())
    };
    let e = with("fins", dispersed).unwrap_err();
    assert_eq!(e.key(), "design.ballast");
    assert!(
        e.to_string().contains("\"fins\" is not an internal part"),
        "{e}"
    );
    // An inner tube holding a slug: a holder, not a part that holds nothing.
    let dir = tempfile::tempdir().unwrap();
    let reference = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(reference).unwrap()).unwrap();
    let body = json["stages"][0]["components"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|c| c["id"] == "body")
        .unwrap();
    body["children"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({
            "id": "bay", "type": "inner_tube", "length_m": 0.1, "outer_diameter_m": 0.04,
            "wall_thickness_m": 0.001, "material": { "density_kg_m3": 700.0 },
            "position": { "from": "nose_tip", "offset_m": 0.45 },
            "children": [{
                "id": "slug", "type": "mass_component", "mass_kg": 0.05, "length_m": 0.02,
                "radius_m": 0.015, "position": { "from": "nose_tip", "offset_m": 0.47 }
            }]
        }));
    let design = dir.path().join("bay.json");
    std::fs::write(&design, json.to_string()).unwrap();
    let text = format!("{BASE}{dispersed}")
        .replace("ballast = \"ballast\"", "ballast = \"bay\"")
        .replace(
            "../validation/designs/synthetic-54mm-three-fin.json",
            design.to_str().unwrap(),
        );
    let bay = |text: &str| Prepared::new(Scenario::parse(text, &path()).unwrap());
    let e = bay(&text).unwrap_err();
    assert_eq!(e.key(), "design.ballast");
    assert!(e.to_string().contains("\"bay\" holds other parts"), "{e}");
    // Not swept or dispersed, the same ballast is only a name.
    assert!(bay(&text.replace(dispersed, "")).is_ok());
    // A ballast of 0 kg is no mass to scale: refused as a sampled value.
    assert_eq!(
        super::super::params::Param::BallastKg.domain().check(0.0),
        Err("must be positive and finite (got 0)".into())
    );
    let (k, r) = refused("[sweep]\nballast_kg = [0.0, 0.2]\n");
    assert_eq!(k, "sweep.ballast_kg[0]");
    assert_eq!(r, "must be positive and finite (got 0)");
}

/// The base scenario with its constant wind replaced by `environment` lines and `extra` after.
fn with_environment(environment: &str, extra: &str) -> Result<Scenario, ScenarioError> {
    let base = BASE.replace("wind_speed_m_s = 4.0\n", environment);
    Scenario::parse(&format!("{base}{extra}"), &path())
}

const PROFILE: &str = "wind_profile = [\n  { height_m = 0.0, speed_m_s = 2.0, from_deg = 270.0 },\n  { height_m = 1000.0, speed_m_s = 9.0, from_deg = 300.0 },\n]\n";

#[test]
fn a_wind_profile_is_read_in_its_rows_and_varied_by_scale_and_turn() {
    let s = with_environment(
        PROFILE,
        "[dispersions]\nwind_scale = { dist = \"normal\", sigma = 0.2, relative = true }\nwind_rotation_deg = { dist = \"uniform\", min = -20.0, max = 20.0 }\n",
    )
    .unwrap();
    let row = |height_agl_m, speed_m_s, from_deg| WindRow {
        height_agl_m,
        speed_m_s,
        from_deg,
    };
    let written = Wind::table(&[row(0.0, 2.0, 270.0), row(1000.0, 9.0, 300.0)]).unwrap();
    assert_eq!(s.environment.wind_profile.as_ref(), Some(&written));
    let keys: Vec<&str> = s.inputs.iter().map(|i| i.key.as_str()).collect();
    assert_eq!(keys, ["wind_scale", "wind_rotation_deg"]);
    let units: Vec<&str> = s.inputs.iter().map(|i| i.unit).collect();
    assert_eq!(units, ["1", "deg"]);
}

#[test]
fn a_wind_profile_refuses_a_constant_wind_beside_it_and_its_bad_rows() {
    let err = |env: &str, extra: &str| match with_environment(env, extra) {
        Err(ScenarioError::Invalid { key, rule, .. }) => (key, rule),
        other => panic!("accepted or another error: {other:?}"),
    };
    let (key, rule) = err(&format!("{PROFILE}wind_from_deg = 10.0\n"), "");
    assert_eq!(key, "environment.wind_profile");
    assert!(rule.contains("not both"), "{rule}");
    let (key, rule) = err(
        PROFILE,
        "[dispersions]\nwind_speed_m_s = { dist = \"normal\", sigma = 1.0 }\n",
    );
    assert_eq!(key, "dispersions.wind_speed_m_s");
    assert!(rule.contains("wind_scale"), "{rule}");
    let (key, _) = err(PROFILE, "[sweep]\nwind_from_deg = [0.0, 90.0]\n");
    assert_eq!(key, "sweep.wind_from_deg");
    let (key, rule) = err(
        "wind_profile = [{ height_m = 100.0, speed_m_s = 2.0, from_deg = 0.0 }, { height_m = 50.0, speed_m_s = 3.0, from_deg = 0.0 }]\n",
        "",
    );
    assert_eq!(key, "environment.wind_profile[1].height_m");
    assert!(rule.contains("height_m") && !rule.contains("agl"), "{rule}");
    let (key, _) = err(
        "wind_profile = [{ height_m = 0.0, speed_m_s = -2.0, from_deg = 0.0 }]\n",
        "",
    );
    assert_eq!(key, "environment.wind_profile[0].speed_m_s");
    let (key, rule) = err(
        "wind_profile = [{ height_m = nan, speed_m_s = 2.0, from_deg = 0.0 }]\n",
        "",
    );
    assert_eq!(key, "environment.wind_profile[0].height_m");
    assert!(rule.contains("must be finite"), "{rule}");
    let (key, rule) = err(
        "wind_profile = [{ height_m = -10.0, speed_m_s = 2.0, from_deg = 0.0 }]\n",
        "",
    );
    assert_eq!(key, "environment.wind_profile[0].height_m");
    assert!(rule.contains("not below the site"), "{rule}");
    let (key, _) = err(
        "wind_profile = [{ height_m = 0.0, speed_m_s = 2.0, from_deg = inf }]\n",
        "",
    );
    assert_eq!(key, "environment.wind_profile[0].from_deg");
    let (key, _) = err("wind_profile = []\n", "");
    assert_eq!(key, "environment.wind_profile");
    let (key, rule) = err("", "[sweep]\nwind_scale = [1.0, -0.5]\n");
    assert_eq!(key, "sweep.wind_scale[1]");
    assert!(rule.contains("not negative"), "{rule}");
}

#[test]
fn a_scenario_without_a_name_is_named_after_its_file_made_fit_for_a_directory() {
    let file = path().with_file_name("wind.v2 test.toml");
    let s = Scenario::parse(BASE, &file).unwrap();
    assert_eq!(s.name, "wind_v2_test");
}

#[test]
fn a_number_where_a_distribution_belongs_says_what_a_distribution_looks_like() {
    let (key, rule) = refused("[dispersions]\nwind_scale = 0.5\n");
    assert!(key.starts_with("dispersions"), "{key}");
    assert!(
        rule.contains("a distribution table such as { dist = \"normal\", sigma = 0.1 }")
            && !rule.contains("RawDist"),
        "{rule}"
    );
}

#[test]
fn a_site_s_latitude_and_its_ellipsoid_s_gravity_are_read_and_their_mistakes_refused() {
    let s = with_environment("latitude_deg = -33.9\ngravity = \"somigliana\"\n", "").unwrap();
    assert_eq!(s.environment.latitude_deg, Some(-33.9));
    assert_eq!(s.environment.gravity, GravityModel::Somigliana);
    let s = with_environment("latitude_deg = 50.0\n", "").unwrap();
    assert_eq!(s.environment.gravity, GravityModel::Standard);
    let s = with_environment("", "").unwrap();
    assert_eq!(s.environment.latitude_deg, None);
    let err = |env: &str| match with_environment(env, "") {
        Err(ScenarioError::Invalid { key, rule, .. }) => (key, rule),
        other => panic!("accepted or another error: {other:?}"),
    };
    for bad in ["90.5", "-91.0", "nan"] {
        let (key, rule) = err(&format!("latitude_deg = {bad}\n"));
        assert_eq!(key, "environment.latitude_deg");
        assert!(rule.contains("[-90, 90]"), "{rule}");
    }
    let (key, rule) = err("gravity = \"somigliana\"\n");
    assert_eq!(key, "environment.gravity");
    assert!(rule.contains("latitude_deg"), "{rule}");
    let (key, rule) = err("gravity = \"wgs84\"\n");
    assert_eq!(key, "environment.gravity");
    assert!(rule.contains("\"somigliana\""), "{rule}");
}

#[test]
fn an_rk4_step_that_would_run_for_days_is_refused_with_the_step_it_needs() {
    let (k, r) = refused("[integrator]\nmethod = \"rk4\"\nstep_s = 1e-9\n");
    assert_eq!(k, "integrator.step_s");
    assert_eq!(
        r,
        "max_time_s / step_s is 6.0000e11 steps, more than the 10000000 a flight may take: \
         give a step of at least 6e-5 s, or a shorter max_time_s (got 0.000000001)"
    );
    assert!(parse("[integrator]\nmethod = \"rk4\"\nstep_s = 6e-5\n").is_ok());
}

/// `n` values from 1 by 0.001.
fn values(n: usize) -> String {
    let v: Vec<String> = (0..n)
        .map(|i| format!("{}", 1.0 + i as f64 * 1e-3))
        .collect();
    format!("[{}]", v.join(", "))
}

/// BASE with `variants_per_point` and a sweep of `lists` (key, count of values).
fn swept(variants_per_point: u64, lists: &[(&str, usize)]) -> Result<Scenario, ScenarioError> {
    let mut text = BASE.replace(
        "variants_per_point = 3\n",
        &format!("variants_per_point = {variants_per_point}\n"),
    );
    text.push_str("[sweep]\n");
    for (key, n) in lists {
        text.push_str(&format!("{key} = {}\n", values(*n)));
    }
    Scenario::parse(&text, &path())
}

#[test]
fn a_sweep_of_more_points_than_the_limit_is_refused_before_anything_is_built() {
    // Four lists of 1,000 values: 10^12 points, once a silent spin through every point's
    // set-up. Refused by parse, with the grid.
    let four = [
        ("drag_scale", 1000),
        ("wind_speed_m_s", 1000),
        ("rail_length_m", 1000),
        ("wind_from_deg", 1000),
    ];
    let e = swept(1, &four).unwrap_err();
    assert_eq!(e.key(), "sweep");
    assert!(
        e.to_string().ends_with(
            "test.toml: sweep: the grid of 1000 of drag_scale × 1000 of wind_speed_m_s × \
             1000 of wind_from_deg × 1000 of rail_length_m values has more than 100000 points, \
             the most a scenario may sweep (every point's flight is set up and checked before \
             the run); sweep fewer values, or split the sweep over several scenarios"
        ),
        "{e}"
    );
    // Seven lists of 1,000 (10^21 points) overflow 64 bits: refused in the same words.
    let seven = [
        ("drag_scale", 1000),
        ("wind_speed_m_s", 1000),
        ("rail_length_m", 1000),
        ("wind_from_deg", 1000),
        ("elevation_m", 1000),
        ("rail_heading_deg", 1000),
        ("structure_mass_kg", 1000),
    ];
    let e = swept(1, &seven).unwrap_err();
    assert_eq!(e.key(), "sweep");
    assert!(e.to_string().contains("has more than 100000 points"), "{e}");
    // 100 × 1,000 points is the limit itself: accepted (nothing is set up by parse).
    let s = swept(1, &[("drag_scale", 100), ("wind_speed_m_s", 1000)]).unwrap();
    assert_eq!(s.points(), MAX_SWEEP_POINTS as usize);
    let e = swept(1, &[("drag_scale", 101), ("wind_speed_m_s", 1000)]).unwrap_err();
    assert_eq!(e.key(), "sweep");
}

#[test]
fn more_variants_than_the_limit_are_refused_naming_where_they_were_given() {
    // The limit itself is allowed; one more is not, in the file or from --variants.
    let s = swept(MAX_VARIANTS / 2, &[("drag_scale", 2)]).unwrap();
    assert_eq!(s.total_variants(), Some(MAX_VARIANTS));
    let e = swept(MAX_VARIANTS / 2 + 1, &[("drag_scale", 2)]).unwrap_err();
    assert_eq!(e.key(), "variants_per_point");
    assert!(
        e.to_string().ends_with(
            "variants_per_point: 2 sweep points × 500000001 variants per point is more than \
             1000000000 variants, the most one scenario may fly (a larger study is several \
             runs with other seeds)"
        ),
        "{e}"
    );
    // --variants 10000000000 once asked for 40 GB of chunk ranges and aborted.
    let e = s.with_overrides(None, Some(10_000_000_000)).unwrap_err();
    assert_eq!(e.key(), "--variants");
    assert!(
        e.to_string()
            .contains("× 10000000000 variants per point is more than"),
        "{e}"
    );
    let e = swept(1, &[])
        .unwrap()
        .with_overrides(None, Some(u64::MAX))
        .unwrap_err();
    assert_eq!(e.key(), "--variants");
}

#[test]
fn a_design_file_that_is_a_directory_is_named_as_one() {
    let text = BASE.replace(
        "file = \"../validation/designs/synthetic-54mm-three-fin.json\"",
        "file = \"../validation/designs\"",
    );
    let e = Scenario::parse(&text, &path()).unwrap_err();
    assert_eq!(e.key(), "design.file");
    assert!(
        e.to_string()
            .ends_with("validation/designs is a directory, not a design file"),
        "{e}"
    );
}

#[test]
fn a_scenario_or_sounding_that_never_ends_is_refused_at_its_limit() {
    let e = Scenario::load(Path::new("/dev/zero")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "/dev/zero: can't read it: it is larger than 4 MiB, the most hpr-mc reads for a scenario file"
    );
    let text = BASE.replace("wind_speed_m_s = 4.0", "sounding = \"/dev/zero\"");
    let e = Scenario::parse(&text, &path()).unwrap_err();
    assert_eq!(e.key(), "environment.sounding");
    assert!(
        e.to_string().ends_with(
            "environment.sounding: cannot read /dev/zero: it is larger than 16 MiB, the most \
             hpr-mc reads for a sounding"
        ),
        "{e}"
    );
}
