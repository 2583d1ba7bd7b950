//! A parachute's canopy shape through a whole campaign: the rows are the flights `Simulation`
//! flies with the same canopy set up by hand, and the shape moves them.

use super::*;
use hpr_sim::wind::Wind;
use hpr_sim::{CanopyShape, Environment, Parachute, Trigger};

#[test]
fn a_scenario_s_canopy_radius_height_and_porosity_fly_as_the_simulator_set_up_by_hand() {
    let wind = "wind_speed_m_s = 4.0\nwind_from_deg = 250.0";
    let plain = windy(wind, "drag_scale = [1.0]");
    let shaped = plain.replace(
        "trigger = \"apogee\"\n",
        "trigger = \"apogee\"\nradius_m = 1.1\nheight_m = 0.6\nporosity = 0.2\n",
    );
    assert_ne!(plain, shaped);
    let campaign = drag_apogee_landing(&shaped);
    let env = Environment {
        wind: Wind::constant(4.0, 250.0).unwrap(),
        ..Environment::default()
    };
    let canopy = CanopyShape {
        radius_m: Some(1.1),
        height_m: Some(0.6),
        porosity: 0.2,
    };
    let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0).with_canopy(canopy);
    assert_rows_flown_by_hand(&campaign, &env, &chute);
    // The default canopy of 0.9 m² (R = 0.452 m) carries 0.194 m³ of air, this one 1.148 m³
    // (C_a = 0.7548): the heavier canopy opens more slowly and the landing moves.
    let default = drag_apogee_landing(&plain);
    let moved = (campaign[0][2] - default[0][2]).hypot(campaign[0][3] - default[0][3]);
    eprintln!("canopy of 1.1 m × 0.6 m, porosity 0.2: landing moved {moved:.4} m");
    assert!(moved > 1e-3, "{moved} m");
    assert_eq!(
        campaign[0][1], default[0][1],
        "the apogee comes before any canopy"
    );
}

#[test]
fn a_scenario_s_sampling_rate_fires_its_parachute_as_the_simulator_set_up_by_hand() {
    let wind = "wind_speed_m_s = 4.0\nwind_from_deg = 250.0";
    let plain = windy(wind, "drag_scale = [1.0]");
    let sampled = plain.replace(
        "trigger = \"apogee\"\n",
        "trigger = \"apogee\"\nsampling_rate_hz = 20.0\n",
    );
    assert_ne!(plain, sampled);
    let campaign = drag_apogee_landing(&sampled);
    let env = Environment {
        wind: Wind::constant(4.0, 250.0).unwrap(),
        ..Environment::default()
    };
    let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0).with_sampling_rate(20.0);
    assert_rows_flown_by_hand(&campaign, &env, &chute);
    // The canopy opens up to 50 ms later than the continuous one's: the landing moves.
    let watched = drag_apogee_landing(&plain);
    let moved = (campaign[0][2] - watched[0][2]).hypot(campaign[0][3] - watched[0][3]);
    eprintln!("a 20 Hz altimeter: landing moved {moved:.4} m");
    assert!(moved > 1e-3, "{moved} m");
    assert_eq!(campaign[0][1], watched[0][1], "the same apogee");
}

#[test]
fn a_sampling_rate_that_is_not_positive_is_refused_naming_its_parachute_s_key() {
    let text = windy("wind_speed_m_s = 4.0", "drag_scale = [1.0]").replace(
        "trigger = \"apogee\"\n",
        "trigger = \"apogee\"\nsampling_rate_hz = 0.0\n",
    );
    let err = refusal(&text);
    assert!(err.contains("parachutes[0].sampling_rate_hz"), "{err}");
    assert!(err.contains("must be positive and finite"), "{err}");
}
