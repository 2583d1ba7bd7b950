//! Cycloidal motion (cam design's "cycloidal displacement", Norton, *Design of Machinery*):
//! the shape of every mass shift.
//!
//! With τ the fraction of the move's time gone, the part is `s(τ) = τ − sin(2πτ)/2π` of the
//! way along. It starts and ends at rest with zero acceleration, so neither its speed nor its
//! acceleration jumps. Pure functions, no allocation: the single flight and the batch engine
//! both call them.

use std::f64::consts::TAU;

/// Position, velocity and acceleration of a shifted part along its move, at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CycloidState {
    /// Distance moved along the axis, m (signed like the travel).
    pub delta_m: f64,
    /// Rate of that distance, m/s.
    pub rate_m_s: f64,
    /// Its acceleration, m/s².
    pub accel_m_s2: f64,
}

/// The fraction of the way `s(τ) = τ − sin(2πτ)/2π`, for τ clamped to [0, 1].
#[inline]
pub fn fraction(tau: f64) -> f64 {
    let tau = tau.clamp(0.0, 1.0);
    tau - (TAU * tau).sin() / TAU
}

/// A move of `travel_m` over `duration_s` starting at `start_s`, evaluated at time `t_s`.
/// Before the start the part is where the design puts it; after the end it rests at the end.
#[inline]
pub fn evaluate(t_s: f64, start_s: f64, duration_s: f64, travel_m: f64) -> CycloidState {
    if t_s <= start_s {
        return CycloidState::default();
    }
    let tau = (t_s - start_s) / duration_s;
    if tau >= 1.0 {
        return CycloidState {
            delta_m: travel_m,
            rate_m_s: 0.0,
            accel_m_s2: 0.0,
        };
    }
    let (sin, cos) = (TAU * tau).sin_cos();
    CycloidState {
        delta_m: travel_m * (tau - sin / TAU),
        rate_m_s: travel_m / duration_s * (1.0 - cos),
        accel_m_s2: travel_m / (duration_s * duration_s) * TAU * sin,
    }
}

/// The peak acceleration of a move, `2π × travel / T²`, m/s².
pub fn peak_acceleration(travel_m: f64, duration_s: f64) -> f64 {
    TAU * travel_m.abs() / (duration_s * duration_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cycloid_is_exactly_halfway_at_half_time_and_moving_at_twice_the_mean_speed() {
        let s = evaluate(5.5, 5.0, 1.0, 0.3);
        assert!((s.delta_m - 0.15).abs() < 1e-15, "{}", s.delta_m);
        assert!((s.rate_m_s - 0.6).abs() < 1e-15, "{}", s.rate_m_s);
        assert!(s.accel_m_s2.abs() < 1e-15);
    }

    #[test]
    fn the_cycloid_starts_and_ends_at_rest_with_no_acceleration() {
        for t in [5.0, 6.0, 4.0, 7.0] {
            let s = evaluate(t, 5.0, 1.0, 0.3);
            assert_eq!(s.rate_m_s, 0.0);
            assert_eq!(s.accel_m_s2, 0.0);
        }
        // Just inside the move the rate and acceleration are small (continuity).
        let s = evaluate(5.0 + 1e-6, 5.0, 1.0, 0.3);
        assert!(s.rate_m_s < 1e-9 && s.accel_m_s2 < 1e-4 * 2.0 * TAU * 0.3);
        assert_eq!(evaluate(7.0, 5.0, 1.0, 0.3).delta_m, 0.3);
    }

    #[test]
    fn the_cycloid_rates_are_the_derivatives_of_its_position() {
        let (start, dur, travel) = (1.0, 0.37, -0.21);
        let h = 1e-6;
        for i in 1..20 {
            let t = start + dur * i as f64 / 20.0;
            let d = (evaluate(t + h, start, dur, travel).delta_m
                - evaluate(t - h, start, dur, travel).delta_m)
                / (2.0 * h);
            let a = (evaluate(t + h, start, dur, travel).rate_m_s
                - evaluate(t - h, start, dur, travel).rate_m_s)
                / (2.0 * h);
            let s = evaluate(t, start, dur, travel);
            assert!((d - s.rate_m_s).abs() < 1e-8, "rate {d} vs {}", s.rate_m_s);
            assert!(
                (a - s.accel_m_s2).abs() < 1e-6,
                "accel {a} vs {}",
                s.accel_m_s2
            );
        }
    }

    #[test]
    fn the_peak_acceleration_is_two_pi_travel_over_duration_squared() {
        // Peak at τ = 1/4: travel/T² · 2π · sin(π/2).
        let s = evaluate(0.25e-2, 0.0, 1e-2, 1.0);
        assert!((s.accel_m_s2 - peak_acceleration(1.0, 1e-2)).abs() < 1e-9 * s.accel_m_s2);
        // `docs/moving-mass.md`'s figure: 63 km/s² per metre for a 10 ms move.
        assert!((peak_acceleration(1.0, 0.01) / 1000.0 - 62.83).abs() < 0.01);
    }
}
