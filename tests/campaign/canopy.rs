//! A parachute's canopy shape through a whole campaign: the rows are the flights `Simulation`
//! flies with the same canopy set up by hand, and the shape moves them.

use super::*;
use hpr_sim::wind::Wind;
use hpr_sim::{CanopyShape, Environment, Parachute, Trigger};

/// Every row's drag scale, apogee and landing point.
fn rows(text: &str) -> Vec<[f64; 4]> {
    landed_rows(
        text,
        ["drag_scale", "apogee_m", "landing_x_m", "landing_y_m"],
    )
}

#[test]
fn a_scenario_s_canopy_radius_height_and_porosity_fly_as_the_simulator_set_up_by_hand() {
    let wind = "wind_speed_m_s = 4.0\nwind_from_deg = 250.0";
    let plain = windy(wind, "drag_scale = [1.0]");
    let shaped = plain.replace(
        "trigger = \"apogee\"\n",
        "trigger = \"apogee\"\nradius_m = 1.1\nheight_m = 0.6\nporosity = 0.2\n",
    );
    assert_ne!(plain, shaped);
    let campaign = rows(&shaped);
    let env = Environment {
        wind: Wind::constant(4.0, 250.0).unwrap(),
        ..Environment::default()
    };
    let canopy = CanopyShape {
        radius_m: Some(1.1),
        height_m: Some(0.6),
        porosity: 0.2,
    };
    for row in &campaign {
        let chute = Parachute::new("main", 0.9, Trigger::Apogee, 1.0).with_canopy(canopy);
        let by_hand = flown_by_hand(env.clone(), chute, row[0]);
        for k in 1..4 {
            // The same flight: equal to rounding.
            assert!(
                (row[k] - by_hand[k]).abs() <= 1e-9 * by_hand[k].abs().max(1.0),
                "figure {k}: campaign {} against by hand {}",
                row[k],
                by_hand[k]
            );
        }
    }
    // The default canopy of 0.9 m² (R = 0.452 m) carries 0.194 m³ of air, this one 1.148 m³
    // (C_a = 0.7548): the heavier canopy opens more slowly and the landing moves.
    let default = rows(&plain);
    let moved = (campaign[0][2] - default[0][2]).hypot(campaign[0][3] - default[0][3]);
    eprintln!("canopy of 1.1 m × 0.6 m, porosity 0.2: landing moved {moved:.4} m");
    assert!(moved > 1e-3, "{moved} m");
    assert_eq!(
        campaign[0][1], default[0][1],
        "the apogee comes before any canopy"
    );
}
