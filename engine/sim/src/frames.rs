//! Frames and the one conversion between the design's station frame and the flight's body frame.
//!
//! * **Station frame** (`hpr_design`): origin at the nose tip, `x` along the axis pointing aft,
//!   `y`, `z` across it. Positions on the airframe are metres aft of the nose tip.
//! * **Body frame** (`hpr_sim`, as RocketPy's Equations of Motion v1): origin O at the nose tip,
//!   `b3` along the axis pointing forward (out of the nose), `b1`, `b2` across it, right-handed.
//!   Thrust acts along `+b3`. A point `x` m aft of the tip on the axis is at `(0, 0, −x)`.
//!   The map is `b1 = y_s`, `b2 = −z_s`, `b3 = −x_s` (a proper rotation, determinant +1).
//! * **Inertial frame**: origin at the launch point on the ground, `x` east, `y` north, `z` up.
//!   The attitude quaternion `q = (w, x, y, z)` takes body components to inertial ones.

use crate::lanes::{Real, M3, V3};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// The rotation taking station components to body components.
#[inline]
pub fn station_to_body_matrix() -> Matrix3<f64> {
    Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, -1.0, -1.0, 0.0, 0.0)
}

/// A station-frame vector in body components.
#[inline]
pub fn station_to_body(v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(v.y, -v.z, -v.x)
}

/// A body-frame vector in station components.
#[inline]
pub fn body_to_station(v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(-v.z, v.x, -v.y)
}

/// A station-frame tensor (inertia) in body axes: `R I Rᵀ`.
#[inline]
pub fn tensor_station_to_body(i: &Matrix3<f64>) -> Matrix3<f64> {
    let r = station_to_body_matrix();
    r * i * r.transpose()
}

/// A point `x_m` aft of the nose tip on the axis, in body coordinates.
#[inline]
pub fn axial_point(x_m: f64) -> Vector3<f64> {
    Vector3::new(0.0, 0.0, -x_m)
}

/// Rotation matrix body → inertial of a (not necessarily unit) quaternion `[w, x, y, z]`,
/// normalised first.
#[inline]
pub fn body_to_inertial(q: &[f64; 4]) -> Matrix3<f64> {
    rotation(*q).to_na()
}

/// [`body_to_inertial`] on lanes: the one formula both drivers use.
#[inline(always)]
pub fn rotation<S: Real>(q: [S; 4]) -> M3<S> {
    let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    let (w, i, j, k) = (q[0] / n, q[1] / n, q[2] / n, q[3] / n);
    let (ww, ii, jj, kk) = (w * w, i * i, j * j, k * k);
    let two = S::splat(2.0);
    M3 {
        m: [
            [
                ww + ii - jj - kk,
                two * (i * j - w * k),
                two * (w * j + i * k),
            ],
            [
                two * (w * k + i * j),
                ww - ii + jj - kk,
                two * (j * k - w * i),
            ],
            [
                two * (i * k - w * j),
                two * (w * i + j * k),
                ww - ii - jj + kk,
            ],
        ],
    }
}

/// Quaternion rate on lanes, `q̇ = ½ q ⊗ (0, ω)` (see [`quaternion_rate`]).
#[inline(always)]
pub fn quaternion_rate_lanes<S: Real>(q: [S; 4], w: &V3<S>) -> [S; 4] {
    let [q0, q1, q2, q3] = q;
    let h = S::splat(0.5);
    [
        h * (-q1 * w.x - q2 * w.y - q3 * w.z),
        h * (q0 * w.x + q2 * w.z - q3 * w.y),
        h * (q0 * w.y - q1 * w.z + q3 * w.x),
        h * (q0 * w.z + q1 * w.y - q2 * w.x),
    ]
}

/// Attitude of a rocket pointing along a rail with inclination `inclination_deg` above the
/// horizon and heading `heading_deg` clockwise from north, rolled so that body `b1` is
/// horizontal. Returns `[w, x, y, z]`.
pub fn rail_attitude(inclination_deg: f64, heading_deg: f64) -> [f64; 4] {
    let (inc, hdg) = (inclination_deg.to_radians(), heading_deg.to_radians());
    // Axis direction in ENU.
    let b3 = Vector3::new(inc.cos() * hdg.sin(), inc.cos() * hdg.cos(), inc.sin());
    // b1 horizontal, perpendicular to the heading (to the right of the heading when level).
    let b1 = Vector3::new(hdg.cos(), -hdg.sin(), 0.0);
    let b2 = b3.cross(&b1);
    let m = Matrix3::from_columns(&[b1, b2, b3]);
    let uq = UnitQuaternion::from_matrix(&m);
    let q = uq.quaternion();
    [q.w, q.i, q.j, q.k]
}

/// Quaternion rate `q̇ = ½ q ⊗ (0, ω)` with ω in body components.
#[inline]
pub fn quaternion_rate(q: &[f64; 4], w: &Vector3<f64>) -> [f64; 4] {
    quaternion_rate_lanes(*q, &V3::from_na(w))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_station_to_body_map_is_a_proper_rotation_and_its_own_inverse_pair() {
        let r = station_to_body_matrix();
        assert!((r.determinant() - 1.0).abs() < 1e-15);
        let v = Vector3::new(0.3, -0.2, 0.7);
        assert_eq!(body_to_station(&station_to_body(&v)), v);
        assert_eq!(station_to_body(&v), r * v);
    }

    #[test]
    fn a_vertical_rail_points_the_nose_up() {
        let q = rail_attitude(90.0, 0.0);
        let b3 = body_to_inertial(&q) * Vector3::z();
        assert!((b3 - Vector3::z()).norm() < 1e-15);
        let q = rail_attitude(85.0, 90.0);
        let b3 = body_to_inertial(&q) * Vector3::z();
        let inc = 85f64.to_radians();
        assert!((b3 - Vector3::new(inc.cos(), 0.0, inc.sin())).norm() < 1e-15);
    }

    #[test]
    fn the_quaternion_rate_turns_the_body_at_omega() {
        // A body spinning about b3 at 1 rad/s from the identity: q̇ = (0, 0, 0, ½).
        let d = quaternion_rate(&[1.0, 0.0, 0.0, 0.0], &Vector3::new(0.0, 0.0, 1.0));
        assert_eq!(d, [0.0, 0.0, 0.0, 0.5]);
    }
}
