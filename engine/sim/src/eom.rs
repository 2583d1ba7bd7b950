//! The equations of motion: one rigid-body derivative for every powered and coasting phase,
//! the rail's one degree of freedom, and the point-mass descent under a canopy.
//!
//! The rigid body follows RocketPy's "Equations of Motion v1", written about O, the nose tip
//! (a point fixed in the airframe), in body axes (see [`crate::frames`]). With `m` the mass,
//! `r` the center of mass seen from O, primes for rates seen from the airframe, `h` the
//! moving parts' angular momentum about O relative to the airframe (moving mass, spec
//! "What the equations of motion add"), `F` the external forces but gravity and `M_O` their
//! moment about O:
//!
//! ```text
//! T20 = F + m g − m ω×(ω×r) − m r″ − 2m ω×r′ − 2ṁ r′ + 2 ω×ṁ(r_noz − r) + m̈ (r_noz − r)
//! T21 = M_O + r×m g − ω×(I_O ω) − I_O′ ω − (ω×h + h′) + ṁ S_noz ω
//! ω̇   = I_cm⁻¹ (T21 − r × T20),   I_cm = I_O − m J(r)
//! a_O = T20/m − ω̇ × r
//! ```
//!
//! `a_O` is O's inertial acceleration in body components. The terms in ṁ and m̈ are RocketPy's
//! mass-flow (thrust-damping) terms, with the nozzle at `r_noz` and its gyration tensor
//! `S_noz`. All of it is a pure function of plain data: no allocation, no tables built.

use crate::frames;
use hpr_design::mass::point_inertia;
use nalgebra::{Matrix3, Vector3};

/// Number of states of the 6-DOF phase: position of O (3, inertial, m), velocity of O
/// (3, inertial, m/s), attitude quaternion body→inertial (4), angular rate (3, body, rad/s).
pub const N6: usize = 13;
/// Number of states of the descent phase: center-of-mass position and velocity (inertial).
pub const N3: usize = 6;

/// Mass properties of the whole rocket at one instant and their rates, in body axes about O.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassState {
    pub mass_kg: f64,
    /// dm/dt, kg/s (negative while the motor burns).
    pub mass_rate: f64,
    /// d²m/dt², kg/s².
    pub mass_accel: f64,
    /// Center of mass from O, body axes, m.
    pub r_cm: Vector3<f64>,
    /// Its velocity through the airframe, m/s.
    pub r_cm_rate: Vector3<f64>,
    /// Its acceleration through the airframe, m/s².
    pub r_cm_accel: Vector3<f64>,
    /// Inertia about O, body axes, kg·m².
    pub inertia_o: Matrix3<f64>,
    /// Its rate seen from the airframe, kg·m²/s.
    pub inertia_o_rate: Matrix3<f64>,
    /// Angular momentum of the moving parts about O relative to the airframe, kg·m²/s.
    pub h_rel: Vector3<f64>,
    /// Its rate, kg·m²/s².
    pub h_rel_rate: Vector3<f64>,
}

impl MassState {
    /// Inertia about the center of mass, body axes.
    #[inline]
    pub fn inertia_cm(&self) -> Matrix3<f64> {
        self.inertia_o - point_inertia(&self.r_cm) * self.mass_kg
    }
}

/// The motor's nozzle, for RocketPy's mass-flow terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nozzle {
    /// Nozzle exit position from O, body axes, m.
    pub r_noz: Vector3<f64>,
    /// Nozzle gyration tensor, m².
    pub s_noz: Matrix3<f64>,
}

impl Nozzle {
    /// A nozzle of radius `radius_m` at `x_m` aft of the nose tip, with RocketPy's gyration
    /// tensor: `S33 = r²/2`, `S11 = S22 = S33/2 + d²/4`, `d` its distance from the center of
    /// dry mass along the axis (given by the caller; 0 is a fine default).
    pub fn at(x_m: f64, radius_m: f64, lever_m: f64) -> Nozzle {
        let s33 = 0.5 * radius_m * radius_m;
        let s11 = 0.5 * s33 + 0.25 * lever_m * lever_m;
        Nozzle {
            r_noz: frames::axial_point(x_m),
            s_noz: Matrix3::from_diagonal(&Vector3::new(s11, s11, s33)),
        }
    }
}

/// External loads but gravity: force (body axes, N) and its moment about O (N·m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Loads {
    pub force_b: Vector3<f64>,
    pub moment_o_b: Vector3<f64>,
}

/// Accelerations of the rigid body: O's inertial acceleration (body axes) and ω̇.
/// Returns `None` when the inertia about the center of mass cannot be inverted.
#[inline]
pub fn rigid_body_accelerations(
    ms: &MassState,
    loads: &Loads,
    gravity_b: &Vector3<f64>,
    omega: &Vector3<f64>,
    nozzle: &Nozzle,
) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let m = ms.mass_kg;
    let r = &ms.r_cm;
    let rp = &ms.r_cm_rate;
    let weight = gravity_b * m;
    let noz_arm = nozzle.r_noz - r;
    let t20 = loads.force_b + weight
        - omega.cross(&omega.cross(r)) * m
        - ms.r_cm_accel * m
        - omega.cross(rp) * (2.0 * m)
        - rp * (2.0 * ms.mass_rate)
        + omega.cross(&noz_arm) * (2.0 * ms.mass_rate)
        + noz_arm * ms.mass_accel;
    let t21 = loads.moment_o_b + r.cross(&weight)
        - omega.cross(&(ms.inertia_o * omega))
        - ms.inertia_o_rate * omega
        - (omega.cross(&ms.h_rel) + ms.h_rel_rate)
        + nozzle.s_noz * omega * ms.mass_rate;
    let i_cm = ms.inertia_cm();
    let omega_dot = i_cm.try_inverse()? * (t21 - r.cross(&t20));
    let a_o = t20 / m - omega_dot.cross(r);
    Some((a_o, omega_dot))
}

/// The 6-DOF state derivative from the accelerations.
#[inline]
pub fn rigid_body_derivative(
    y: &[f64; N6],
    a_o_b: &Vector3<f64>,
    omega_dot: &Vector3<f64>,
    body_to_inertial: &Matrix3<f64>,
    dy: &mut [f64; N6],
) {
    let a_n = body_to_inertial * a_o_b;
    let q = [y[6], y[7], y[8], y[9]];
    let w = Vector3::new(y[10], y[11], y[12]);
    let qd = frames::quaternion_rate(&q, &w);
    dy[0] = y[3];
    dy[1] = y[4];
    dy[2] = y[5];
    dy[3] = a_n.x;
    dy[4] = a_n.y;
    dy[5] = a_n.z;
    dy[6..10].copy_from_slice(&qd);
    dy[10] = omega_dot.x;
    dy[11] = omega_dot.y;
    dy[12] = omega_dot.z;
}

/// Inertial velocity of the center of mass from the 6-DOF state: `v_O + R (ω×r + r′)`.
#[inline]
pub fn center_of_mass_velocity(
    y: &[f64; N6],
    ms: &MassState,
    body_to_inertial: &Matrix3<f64>,
) -> Vector3<f64> {
    let w = Vector3::new(y[10], y[11], y[12]);
    Vector3::new(y[3], y[4], y[5]) + body_to_inertial * (w.cross(&ms.r_cm) + ms.r_cm_rate)
}

/// Inertial position of the center of mass from the 6-DOF state.
#[inline]
pub fn center_of_mass_position(
    y: &[f64; N6],
    ms: &MassState,
    body_to_inertial: &Matrix3<f64>,
) -> Vector3<f64> {
    Vector3::new(y[0], y[1], y[2]) + body_to_inertial * ms.r_cm
}

/// Angular momentum about the center of mass, inertial components: `R (I_cm ω + h_cm)`, with
/// `h_cm` the moving parts' relative angular momentum about the center of mass.
pub fn angular_momentum_about_cm(
    y: &[f64; N6],
    ms: &MassState,
    body_to_inertial: &Matrix3<f64>,
) -> Vector3<f64> {
    let w = Vector3::new(y[10], y[11], y[12]);
    // h about O = Σ m ρ × ρ′; about the center: h − r × (M r′) (the parts' momentum is M r′).
    let h_cm = ms.h_rel - ms.r_cm.cross(&(ms.r_cm_rate * ms.mass_kg));
    body_to_inertial * (ms.inertia_cm() * w + h_cm)
}

/// Descent under a canopy: the center of mass as a point with the canopy's drag.
/// `cds_m2` is the sum of the open canopies' CdS, `wind_n` the wind (inertial), `rho` the air
/// density, `g` gravity. State `[x, y, z, vx, vy, vz]` of the center of mass.
#[inline]
pub fn descent_derivative(
    y: &[f64; N3],
    mass_kg: f64,
    cds_m2: f64,
    rho: f64,
    g: f64,
    wind_n: &Vector3<f64>,
    dy: &mut [f64; N3],
) {
    let v = Vector3::new(y[3], y[4], y[5]);
    let rel = v - wind_n;
    let drag = rel * (-0.5 * rho * cds_m2 * rel.norm());
    dy[0] = y[3];
    dy[1] = y[4];
    dy[2] = y[5];
    dy[3] = drag.x / mass_kg;
    dy[4] = drag.y / mass_kg;
    dy[5] = drag.z / mass_kg - g;
}
