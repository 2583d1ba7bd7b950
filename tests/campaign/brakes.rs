//! A design with air brakes through a campaign: its rows carry when the brakes opened and
//! how wide, and the drag's scatter no longer scatters the apogee.

use super::*;

/// The reference design with air brakes aiming at 1500 m, written into a temporary
/// directory (kept alive by the first value), its path the third; the second is the plain
/// design's path, which [`windy`] scenarios name.
fn braked_design() -> (tempfile::TempDir, PathBuf, PathBuf) {
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("validation/designs/synthetic-54mm-three-fin.json");
    let mut design: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&source).unwrap()).unwrap();
    design["air_brakes"] = serde_json::json!({
        "cd": 1.2, "reference_area_m2": 0.003, "target_apogee_m": 1500.0, "sampling_rate_hz": 20.0
    });
    let dir = tempfile::tempdir().unwrap();
    let braked = dir.path().join("braked.json");
    std::fs::write(&braked, design.to_string()).unwrap();
    (dir, source, braked)
}

#[test]
fn a_campaign_of_a_braked_rocket_writes_its_brakes_columns_and_holds_its_apogee_to_the_target() {
    let (_dir, source, braked) = braked_design();
    // `inspect` lists them, with the area given.
    let (code, out, err) = hpr_mc(&["inspect", braked.to_str().unwrap(), "--json"]);
    assert_eq!(code, 0, "{err}");
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["air_brakes"]["reference_area_m2"].as_f64(), Some(0.003));
    assert_eq!(j["air_brakes"]["target_apogee_m"].as_f64(), Some(1500.0));
    let text = windy("wind_speed_m_s = 0.0", "drag_scale = [1.0]")
        .replace(&source.display().to_string(), &braked.display().to_string());
    let rows = landed_rows(
        &text,
        [
            "drag_scale",
            "apogee_m",
            "air_brakes_open_time_s",
            "air_brakes_max_opening",
        ],
    );
    assert_eq!(rows.len(), 4);
    // The drag is scattered by 5 %; the brakes take up the difference.
    let scales: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    assert!(scales.iter().any(|&s| (s - 1.0).abs() > 0.01), "{scales:?}");
    // Off a rail 5° from vertical the rocket tops out moving sideways, which the
    // controller's vertical coast leaves out of the drag: a few centimetres (2.6 cm seen).
    for r in &rows {
        assert!((r[1] - 1500.0).abs() < 0.1, "apogee {}", r[1]);
        assert_eq!(r[2], 2.5, "opened at the first sample, at burnout");
        assert!(r[3] > 0.0 && r[3] <= 1.0, "{}", r[3]);
    }
}

#[test]
fn a_sweep_of_the_brakes_target_moves_each_point_s_apogee_to_it() {
    let (_dir, source, braked) = braked_design();
    let text = windy(
        "wind_speed_m_s = 0.0",
        "air_brakes_target_apogee_m = [1300.0, 1600.0]",
    )
    .replace(&source.display().to_string(), &braked.display().to_string());
    let rows = landed_rows(&text, ["air_brakes_target_apogee_m", "apogee_m"]);
    assert_eq!(rows.len(), 8, "two points of four");
    for r in &rows {
        assert!([1300.0, 1600.0].contains(&r[0]), "{}", r[0]);
        // Off the 85° rail: within a few centimetres, as above.
        assert!(
            (r[1] - r[0]).abs() < 0.1,
            "apogee {} for target {}",
            r[1],
            r[0]
        );
    }
    // Without brakes in the design there is nothing to aim: refused by key.
    let plain = windy(
        "wind_speed_m_s = 0.0",
        "air_brakes_target_apogee_m = [1300.0]",
    );
    let e = refusal(&plain);
    assert!(
        e.contains("sweep.air_brakes_target_apogee_m") && e.contains("no air brakes"),
        "{e}"
    );
}
