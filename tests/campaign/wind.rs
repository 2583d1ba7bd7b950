//! Wind profiles and constant winds scaled and turned (`wind_scale`, `wind_rotation_deg`),
//! flown through whole campaigns against the same winds written out.

use super::*;

/// Every row's landing point, apogee and landing time.
fn flights(text: &str) -> Vec<[f64; 4]> {
    landed_rows(
        text,
        ["landing_x_m", "landing_y_m", "apogee_m", "landing_time_s"],
    )
}

/// Row by row, the same figures to 2e-6 (relative, or absolute below 1): the same flights up
/// to the rounding of their inputs. Not closer: when an input changes in its last bits, the
/// adaptive integrator may accept one step more or fewer somewhere, which moves the flight by
/// the order of its tolerance (rtol 1e-7). Measured on the reference design in the profile
/// below: 613 steps against 614, the apogee 1.2e-4 m apart on 1705 m; the landing point in
/// the campaign 2e-3 m apart on 3.7 km (5e-7); a hundredth of the tolerance brings the apogees
/// to 9e-6 m apart.
fn assert_same_flights(a: &[[f64; 4]], b: &[[f64; 4]]) {
    assert_eq!(a.len(), b.len());
    for (r, (a, b)) in a.iter().zip(b).enumerate() {
        for k in 0..4 {
            assert!(
                (a[k] - b[k]).abs() <= 2e-6 * b[k].abs().max(1.0),
                "row {r} figure {k}: {} against {}",
                a[k],
                b[k]
            );
        }
    }
}

#[test]
fn a_wind_profile_scaled_and_turned_flies_as_the_profile_written_scaled_and_turned() {
    // Rows 2 m/s from 270° at the ground and 9 m/s from 300° at 1 km; scaled 1.5 and turned
    // 40° clockwise, against the same rows written at 3 and 13.5 m/s from 310° and 340°.
    let rows = |k: f64, turn: f64| {
        format!(
            "wind_profile = [{{ height_m = 0.0, speed_m_s = {}, from_deg = {} }}, {{ height_m = 1000.0, speed_m_s = {}, from_deg = {} }}]",
            2.0 * k,
            270.0 + turn,
            9.0 * k,
            300.0 + turn
        )
    };
    let scaled = flights(&windy(
        &rows(1.0, 0.0),
        "wind_scale = [1.5]\nwind_rotation_deg = [40.0]",
    ));
    let written = flights(&windy(&rows(1.5, 40.0), "drag_scale = [1.0]"));
    // The two ways differ only in the rounding of the wind's components (1e-15 of them).
    assert_same_flights(&scaled, &written);
    // And the turn matters: unturned, the rocket lands elsewhere (more than 10 m away).
    let unturned = flights(&windy(&rows(1.5, 0.0), "drag_scale = [1.0]"));
    let apart = (unturned[0][0] - written[0][0]).hypot(unturned[0][1] - written[0][1]);
    assert!(apart > 10.0, "{apart} m");
}

#[test]
fn a_constant_wind_scaled_by_a_half_is_the_constant_wind_of_half_its_speed() {
    let scaled = flights(&windy(
        "wind_speed_m_s = 6.0\nwind_from_deg = 250.0",
        "wind_scale = [0.5]",
    ));
    let half = flights(&windy(
        "wind_speed_m_s = 3.0\nwind_from_deg = 250.0",
        "drag_scale = [1.0]",
    ));
    assert_same_flights(&scaled, &half);
}
