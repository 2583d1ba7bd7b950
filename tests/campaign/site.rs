//! The launch site's latitude and its gravity through a whole campaign: the rows are the flights
//! `Simulation` flies with the same site set up by hand.

use super::*;
use hpr_sim::gravity::Gravity;
use hpr_sim::wind::Wind;
use hpr_sim::{Environment, Parachute, Trigger};

const SITE: &str = "elevation_m = 1200.0\nlatitude_deg = 40.0\ngravity = \"somigliana\"\nwind_speed_m_s = 4.0\nwind_from_deg = 250.0";

/// Every row's drag scale, apogee and landing point.
fn rows(text: &str) -> Vec<[f64; 4]> {
    landed_rows(
        text,
        ["drag_scale", "apogee_m", "landing_x_m", "landing_y_m"],
    )
}

#[test]
fn a_scenario_s_latitude_and_ellipsoid_gravity_fly_as_the_simulator_set_up_by_hand() {
    let campaign = rows(&windy(SITE, "drag_scale = [1.0]"));
    let env = Environment {
        elevation_m: 1200.0,
        wind: Wind::constant(4.0, 250.0).unwrap(),
        gravity: Gravity::somigliana(40.0, 1200.0).unwrap(),
        latitude_deg: Some(40.0),
        vacuum: false,
    };
    for row in &campaign {
        let by_hand = flown_by_hand(
            env.clone(),
            Parachute::new("main", 0.9, Trigger::Apogee, 1.0),
            row[0],
        );
        for k in 1..4 {
            // The same flight: equal to rounding (the campaign's drag scale is read back from
            // its column exactly).
            assert!(
                (row[k] - by_hand[k]).abs() <= 1e-9 * by_hand[k].abs().max(1.0),
                "figure {k}: campaign {} against by hand {}",
                row[k],
                by_hand[k]
            );
        }
    }
    // Without the latitude the Earth stands still: the same rows land elsewhere (Coriolis
    // moves a 1 km flight by metres) and, with standard gravity, climb differently.
    let still = rows(&windy(
        &SITE.replace("latitude_deg = 40.0\ngravity = \"somigliana\"\n", ""),
        "drag_scale = [1.0]",
    ));
    let moved = (campaign[0][2] - still[0][2]).hypot(campaign[0][3] - still[0][3]);
    eprintln!(
        "latitude 40° and its gravity: apogee {:.3} m against {:.3} m, landing moved {moved:.3} m",
        campaign[0][1], still[0][1]
    );
    assert!(moved > 0.3, "{moved} m");
    assert!((campaign[0][1] - still[0][1]).abs() > 0.5);
}
