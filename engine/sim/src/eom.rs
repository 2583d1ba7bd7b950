//! The equations of motion: one rigid-body derivative for every powered and coasting phase,
//! the rail's one degree of freedom, and the point-mass descent under a canopy.
//!
//! The rigid body follows RocketPy's "Equations of Motion v1", written about O, the nose tip
//! (a point fixed in the airframe), in body axes (see [`crate::frames`]). With `m` the mass,
//! `r` the center of mass seen from O, primes for rates seen from the airframe, `h` the
//! moving parts' angular momentum about O relative to the airframe (moving mass,
//! `docs/moving-mass.md`, "What changes"), `F` the external forces but gravity and `M_O` their
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
//! `S_noz`. On a turning Earth (a site's latitude given) `g` also holds the Coriolis
//! acceleration of the center of mass, `−2 Ω × v_cm`: like gravity it acts on the whole mass
//! at its center, so it moves the center and leaves `ω̇` alone, as RocketPy's `−2 w_earth × v`
//! does (both leave out the moment from the airframe's own rotation, terms in Ω·ω, about
//! 1e-4 of the rest). All of it is a pure function of plain data: no allocation, no tables
//! built.

use crate::frames;
use crate::lanes::{pack_m3, pack_v3, F64x4, Real, M3, V3};
use hpr_design::mass::{offsets_inertia, point_inertia};
use nalgebra::{Matrix3, Vector3};

/// Number of states of the 6-DOF phase: position of O (3, inertial, m), velocity of O
/// (3, inertial, m/s), attitude quaternion body→inertial (4), angular rate (3, body, rad/s).
pub const N6: usize = 13;
/// Number of states of the descent phase: center-of-mass position and velocity (inertial).
pub const N3: usize = 6;

/// Mass properties of the whole rocket at one instant and their rates, in body axes about O.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
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
    /// tensor carried to O. RocketPy writes its equations about the center of dry mass and
    /// takes there `S33 = r²/2`, `S11 = S22 = S33/2 + d²/4`, `d` the nozzle's distance from
    /// the center of dry mass along the axis (`lever_m`, given by the caller).
    ///
    /// The equations here are about O, and the gyration tensor must be about the same point
    /// as the inertia whose rate `I_O′` it meets in `T21`: written about a point P, the
    /// mass-flow terms give the moment `(−I_cm′ + ṁ (S11 − p² + (p − r)²)) ω` about the center
    /// of mass (transverse ω; `p` the nozzle's and `r` the center's axial position from P), so
    /// only `S11 − p²` depends on the choice of P. Keeping RocketPy's `S11 − d²` (the parallel
    /// axis theorem) gives `S11 = S33/2 + d²/4 − d² + x²` about O and RocketPy's jet damping
    /// exactly. (RocketPy's `d²/4` is a quarter of the exit plane's integral, which gives
    /// `d²`: RocketPy pull request #1188, after 1.13; this keeps 1.13's.)
    pub fn at(x_m: f64, radius_m: f64, lever_m: f64) -> Nozzle {
        let s33 = 0.5 * radius_m * radius_m;
        let s11 = 0.5 * s33 + 0.25 * lever_m * lever_m - lever_m * lever_m + x_m * x_m;
        Nozzle {
            r_noz: frames::axial_point(x_m),
            s_noz: Matrix3::from_diagonal(&Vector3::new(s11, s11, s33)),
        }
    }

    /// The nozzles of a cluster, one at each offset `[y, z]` off the axis (station frame,
    /// m), each carrying an equal share of the mass flow: the gyration tensor is the mean of
    /// the nozzles', and a nozzle whose exit is centred `d` off the axis has its disc's
    /// tensor plus `J(d) = |d|² 1 − d dᵀ` (the terms linear in the disc's points vanish
    /// over the disc, those linear in `d` over the cluster, whose mean offset is on the
    /// axis). The nozzles stay at the axial station of `r_noz`. One offset `[0, 0]` changes
    /// nothing.
    pub fn clustered(mut self, offsets_m: &[[f64; 2]]) -> Nozzle {
        if offsets_m.is_empty() {
            return self;
        }
        let mean = offsets_inertia(offsets_m) / offsets_m.len() as f64;
        self.s_noz += frames::tensor_station_to_body(&mean);
        self
    }
}

/// External loads but gravity: force (body axes, N) and its moment about O (N·m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Loads {
    pub force_b: Vector3<f64>,
    pub moment_o_b: Vector3<f64>,
}

/// The fields of a [`MassState`] the equations read, on lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassLanes<S> {
    pub m: S,
    pub m_rate: S,
    pub m_accel: S,
    pub r: V3<S>,
    pub r_rate: V3<S>,
    pub r_accel: V3<S>,
    pub i_o: M3<S>,
    pub i_o_rate: M3<S>,
    pub h: V3<S>,
    pub h_rate: V3<S>,
}

impl MassLanes<f64> {
    #[inline(always)]
    pub fn of(ms: &MassState) -> MassLanes<f64> {
        MassLanes {
            m: ms.mass_kg,
            m_rate: ms.mass_rate,
            m_accel: ms.mass_accel,
            r: V3::from_na(&ms.r_cm),
            r_rate: V3::from_na(&ms.r_cm_rate),
            r_accel: V3::from_na(&ms.r_cm_accel),
            i_o: M3::from_na(&ms.inertia_o),
            i_o_rate: M3::from_na(&ms.inertia_o_rate),
            h: V3::from_na(&ms.h_rel),
            h_rate: V3::from_na(&ms.h_rel_rate),
        }
    }
}

impl<S: Real> MassLanes<S> {
    /// Lane-wise `if m { a } else { b }`.
    #[inline(always)]
    pub fn select(m: S::Mask, a: &MassLanes<S>, b: &MassLanes<S>) -> MassLanes<S> {
        MassLanes {
            m: S::select(m, a.m, b.m),
            m_rate: S::select(m, a.m_rate, b.m_rate),
            m_accel: S::select(m, a.m_accel, b.m_accel),
            r: V3::select(m, &a.r, &b.r),
            r_rate: V3::select(m, &a.r_rate, &b.r_rate),
            r_accel: V3::select(m, &a.r_accel, &b.r_accel),
            i_o: M3::select(m, &a.i_o, &b.i_o),
            i_o_rate: M3::select(m, &a.i_o_rate, &b.i_o_rate),
            h: V3::select(m, &a.h, &b.h),
            h_rate: V3::select(m, &a.h_rate, &b.h_rate),
        }
    }
}

impl MassLanes<f64> {
    /// The same numbers as a [`MassState`].
    #[inline(always)]
    pub fn to_state(&self) -> MassState {
        MassState {
            mass_kg: self.m,
            mass_rate: self.m_rate,
            mass_accel: self.m_accel,
            r_cm: self.r.to_na(),
            r_cm_rate: self.r_rate.to_na(),
            r_cm_accel: self.r_accel.to_na(),
            inertia_o: self.i_o.to_na(),
            inertia_o_rate: self.i_o_rate.to_na(),
            h_rel: self.h.to_na(),
            h_rel_rate: self.h_rate.to_na(),
        }
    }
}

impl MassLanes<f64> {
    /// All zeros (a place to pack lanes into).
    pub const ZERO: MassLanes<f64> = MassLanes {
        m: 0.0,
        m_rate: 0.0,
        m_accel: 0.0,
        r: V3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
        r_rate: V3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
        r_accel: V3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
        i_o: M3 { m: [[0.0; 3]; 3] },
        i_o_rate: M3 { m: [[0.0; 3]; 3] },
        h: V3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
        h_rate: V3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
    };
}

impl MassLanes<F64x4> {
    /// Write one lane's mass state into lane `l`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, m: &MassLanes<f64>) {
        let mat = |d: &mut M3<F64x4>, s: &M3<f64>| {
            for r in 0..3 {
                for c in 0..3 {
                    d.m[r][c].0[l] = s.m[r][c];
                }
            }
        };
        self.m.0[l] = m.m;
        self.m_rate.0[l] = m.m_rate;
        self.m_accel.0[l] = m.m_accel;
        self.r.set_lane(l, &m.r);
        self.r_rate.set_lane(l, &m.r_rate);
        self.r_accel.set_lane(l, &m.r_accel);
        mat(&mut self.i_o, &m.i_o);
        mat(&mut self.i_o_rate, &m.i_o_rate);
        self.h.set_lane(l, &m.h);
        self.h_rate.set_lane(l, &m.h_rate);
    }
}

/// Four lanes' mass states side by side.
#[inline(always)]
pub fn pack_mass(ms: [&MassLanes<f64>; 4]) -> MassLanes<F64x4> {
    MassLanes {
        m: F64x4::from_fn(|i| ms[i].m),
        m_rate: F64x4::from_fn(|i| ms[i].m_rate),
        m_accel: F64x4::from_fn(|i| ms[i].m_accel),
        r: pack_v3(ms.map(|m| &m.r)),
        r_rate: pack_v3(ms.map(|m| &m.r_rate)),
        r_accel: pack_v3(ms.map(|m| &m.r_accel)),
        i_o: pack_m3(ms.map(|m| &m.i_o)),
        i_o_rate: pack_m3(ms.map(|m| &m.i_o_rate)),
        h: pack_v3(ms.map(|m| &m.h)),
        h_rate: pack_v3(ms.map(|m| &m.h_rate)),
    }
}

/// The nozzle on lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NozzleLanes<S> {
    pub r_noz: V3<S>,
    pub s_noz: M3<S>,
}

impl Nozzle {
    #[inline(always)]
    pub fn lanes(&self) -> NozzleLanes<f64> {
        NozzleLanes {
            r_noz: V3::from_na(&self.r_noz),
            s_noz: M3::from_na(&self.s_noz),
        }
    }
}

/// Four lanes' nozzles side by side.
#[inline(always)]
pub fn pack_nozzle(n: [&NozzleLanes<f64>; 4]) -> NozzleLanes<F64x4> {
    NozzleLanes {
        r_noz: pack_v3(n.map(|n| &n.r_noz)),
        s_noz: pack_m3(n.map(|n| &n.s_noz)),
    }
}

/// Accelerations of the rigid body: O's inertial acceleration (body axes) and ω̇, the
/// equations of the module's header. `force_b` and `moment_o_b` are the external loads but
/// gravity. One copy for every driver: the single flight calls it on `f64`, the batch engine
/// on four lanes at once. A singular inertia gives non-finite results.
#[inline(always)]
pub fn accelerations<S: Real>(
    ms: &MassLanes<S>,
    force_b: &V3<S>,
    moment_o_b: &V3<S>,
    gravity_b: &V3<S>,
    omega: &V3<S>,
    nozzle: &NozzleLanes<S>,
) -> (V3<S>, V3<S>) {
    let m = ms.m;
    let r = &ms.r;
    let rp = &ms.r_rate;
    let two = S::splat(2.0);
    let weight = gravity_b.scale(m);
    let noz_arm = nozzle.r_noz - *r;
    let t20 = *force_b + weight
        - omega.cross(&omega.cross(r)).scale(m)
        - ms.r_accel.scale(m)
        - omega.cross(rp).scale(two * m)
        - rp.scale(two * ms.m_rate)
        + omega.cross(&noz_arm).scale(two * ms.m_rate)
        + noz_arm.scale(ms.m_accel);
    let t21 = *moment_o_b + r.cross(&weight)
        - omega.cross(&ms.i_o.mul_v(omega))
        - ms.i_o_rate.mul_v(omega)
        - (omega.cross(&ms.h) + ms.h_rate)
        + nozzle.s_noz.mul_v(omega).scale(ms.m_rate);
    // I_cm = I_O − m J(r), J(r) = |r|² E − r rᵀ.
    let rr = r.norm_squared();
    let rv = [r.x, r.y, r.z];
    let mut i_cm = ms.i_o;
    for (a, row) in i_cm.m.iter_mut().enumerate() {
        for (b, v) in row.iter_mut().enumerate() {
            let j = if a == b {
                rr - rv[a] * rv[b]
            } else {
                -(rv[a] * rv[b])
            };
            *v = *v - j * m;
        }
    }
    let omega_dot = i_cm.inverse().mul_v(&(t21 - r.cross(&t20)));
    let a_o = V3::new(t20.x / m, t20.y / m, t20.z / m) - omega_dot.cross(r);
    (a_o, omega_dot)
}

/// The 6-DOF state derivative from the accelerations, on lanes: `y` and `dy` hold the 13
/// states of [`N6`].
#[inline(always)]
pub fn rigid_body_derivative_lanes<S: Real>(
    y: &[S; N6],
    a_o_b: &V3<S>,
    omega_dot: &V3<S>,
    body_to_inertial: &M3<S>,
    dy: &mut [S; N6],
) {
    let a_n = body_to_inertial.mul_v(a_o_b);
    let w = V3::new(y[10], y[11], y[12]);
    let qd = frames::quaternion_rate_lanes([y[6], y[7], y[8], y[9]], &w);
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

/// What a descending point feels of its surroundings where it is, on lanes.
#[derive(Debug, Clone, Copy)]
pub struct Surroundings<S> {
    /// Air density, kg/m³.
    pub rho: S,
    /// Gravity's magnitude, m/s².
    pub g: S,
    /// The wind, launch frame, m/s.
    pub wind_n: V3<S>,
    /// The Earth's rotation in the launch frame, rad/s (`None` for an inertial frame).
    pub earth_rate_n: Option<V3<S>>,
}

/// The drag coefficient of an inflated canopy that sizes it from its CdS: a hemisphere's 1.4
/// (NASA SP-8066), RocketPy's `Parachute(drag_coefficient=1.4)` default.
pub const CANOPY_CD: f64 = 1.4;
/// A canopy's geometric porosity, RocketPy's default (its added-mass coefficient is then 1).
pub const CANOPY_POROSITY: f64 = 0.0432;

/// The added-mass coefficient of a canopy of porosity `p`, RocketPy's
/// `1.068 (1 − 1.465 p − 0.25975 p² + 1.2626 p³)`.
pub fn canopy_added_mass_coefficient(p: f64) -> f64 {
    1.068 * (1.0 - 1.465 * p - 0.25975 * p * p + 1.2626 * p * p * p)
}

/// An inflated canopy's shape, which sets the air it carries along: RocketPy's hemispheroid of
/// radius `R` and height `H` (its `Parachute(radius, height, porosity)`). What is not given
/// takes RocketPy's default: a hemisphere (`H = R`) sized from the canopy's CdS,
/// `R = √(CdS / (1.4 π))`, of porosity 0.0432.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CanopyShape {
    /// Radius of the inflated canopy, m (`None`: sized from its CdS).
    pub radius_m: Option<f64>,
    /// Height of the inflated canopy (its unique semi-axis), m (`None`: its radius).
    pub height_m: Option<f64>,
    /// Geometric porosity: the canopy's open area over its whole area, in [0, 1).
    pub porosity: f64,
}

impl Default for CanopyShape {
    fn default() -> CanopyShape {
        CanopyShape {
            radius_m: None,
            height_m: None,
            porosity: CANOPY_POROSITY,
        }
    }
}

impl CanopyShape {
    /// Check the numbers: a given radius and height positive and finite, the porosity at least
    /// 0 and below 1. The error is the field and the rule it breaks.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        for (field, v) in [("radius_m", self.radius_m), ("height_m", self.height_m)] {
            if let Some(v) = v.filter(|v| !(v.is_finite() && *v > 0.0)) {
                return Err((field, format!("must be positive and finite (got {v})")));
            }
        }
        if !(self.porosity.is_finite() && (0.0..1.0).contains(&self.porosity)) {
            return Err((
                "porosity",
                format!(
                    "must be at least 0 and below 1: the canopy's open area over its whole area (got {})",
                    self.porosity
                ),
            ));
        }
        Ok(())
    }

    /// The volume of air an open canopy of drag area `cds_m2` carries along, m³: its added mass
    /// per unit air density, `C_a (2/3) π R² H` (RocketPy 1.13's `u_dot_parachute`).
    pub fn added_air_volume_m3(&self, cds_m2: f64) -> f64 {
        let r = self
            .radius_m
            .unwrap_or_else(|| (cds_m2 / (CANOPY_CD * std::f64::consts::PI)).sqrt());
        let h = self.height_m.unwrap_or(r);
        canopy_added_mass_coefficient(self.porosity)
            * (2.0 / 3.0)
            * std::f64::consts::PI
            * r
            * r
            * h
    }
}

/// The open canopies as the descent sees them, on lanes: each canopy drags and carries its own
/// air, so both add up over the canopies open.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Canopies<S> {
    /// The sum of the open canopies' CdS, m².
    pub cds_m2: S,
    /// The sum of their added air volumes ([`CanopyShape::added_air_volume_m3`]), m³.
    pub added_air_m3: S,
}

/// Descent under the open canopies: the center of mass as a point with the canopies' drag,
/// gravity and the Coriolis acceleration `−2 Ω × v`, on lanes (one flight, or four side by
/// side). The air the canopies carry along, their added mass `m_a = ρ V_a`, is accelerated
/// with the rocket but has no weight: `(m + m_a) a = D − m g`. The steady descent is the
/// same; the opening is slower. State `[x, y, z, vx, vy, vz]` of the center of mass.
#[inline(always)]
pub fn descent_derivative<S: Real>(
    y: &[S; N3],
    mass_kg: S,
    canopies: &Canopies<S>,
    at: &Surroundings<S>,
    dy: &mut [S; N3],
) {
    let w = &at.wind_n;
    let rel = V3::new(y[3] - w.x, y[4] - w.y, y[5] - w.z);
    let k = S::splat(-0.5) * at.rho * canopies.cds_m2 * rel.norm_squared().sqrt();
    let inertia = mass_kg + at.rho * canopies.added_air_m3;
    dy[0] = y[3];
    dy[1] = y[4];
    dy[2] = y[5];
    dy[3] = rel.x * k / inertia;
    dy[4] = rel.y * k / inertia;
    dy[5] = (rel.z * k - mass_kg * at.g) / inertia;
    if let Some(earth) = &at.earth_rate_n {
        let coriolis = earth
            .cross(&V3::new(y[3], y[4], y[5]))
            .scale(S::splat(-2.0));
        dy[3] = dy[3] + coriolis.x;
        dy[4] = dy[4] + coriolis.y;
        dy[5] = dy[5] + coriolis.z;
    }
}

/// The Jacobian of [`descent_derivative`]'s acceleration with respect to the velocity,
/// `∂v̇/∂v`, the air, wind and gravity where they are: the drag's `−c (|u| I + u uᵀ / |u|)`
/// (`u = v − w`, `c = ½ ρ CdS / (m + m_a)`; the zero matrix in a point at rest in the air)
/// and the Coriolis term's `−2 [Ω]×`. What a stiff descent's integrator factors (RODAS4).
pub fn descent_velocity_jacobian(
    y: &[f64; N3],
    mass_kg: f64,
    canopies: &Canopies<f64>,
    at: &Surroundings<f64>,
) -> [[f64; 3]; 3] {
    let w = &at.wind_n;
    let u = [y[3] - w.x, y[4] - w.y, y[5] - w.z];
    let speed = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    let c = 0.5 * at.rho * canopies.cds_m2 / (mass_kg + at.rho * canopies.added_air_m3);
    let mut jac = [[0.0; 3]; 3];
    if speed > 0.0 {
        for i in 0..3 {
            for j in 0..3 {
                let along = u[i] * u[j] / speed;
                jac[i][j] = -c * (if i == j { speed + along } else { along });
            }
        }
    }
    if let Some(o) = &at.earth_rate_n {
        let skew = [[0.0, -o.z, o.y], [o.z, 0.0, -o.x], [-o.y, o.x, 0.0]];
        for i in 0..3 {
            for j in 0..3 {
                jac[i][j] -= 2.0 * skew[i][j];
            }
        }
    }
    jac
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_canopy_added_mass_is_rocketpy_s_default_hemisphere_of_air() {
        // RocketPy 1.13, Parachute(cd_s) with its defaults: R = √(cd_s / (1.4 π)), H = R,
        // porosity 0.0432, C_a = 1.068 (1 − 1.465 p − 0.25975 p² + 1.2626 p³) = 0.99999941.
        let c_a = canopy_added_mass_coefficient(CANOPY_POROSITY);
        assert!((c_a - 0.999_999_411_464_476_4).abs() < 1e-15, "{c_a}");
        // Calisto's main, CdS 10 m²: R = 1.50786 m, 7.18028 kg of air at ρ = 1 kg/m³
        // (RocketPy: C_a (2/3) π R² H = 7.180281906195443).
        let v = CanopyShape::default().added_air_volume_m3(10.0);
        assert!((v - 7.180_281_906_195_443).abs() < 1e-12, "{v}");
    }

    #[test]
    fn a_canopy_given_its_radius_height_and_porosity_carries_rocketpy_s_air() {
        // RocketPy 1.13: Parachute(cd_s=2, radius=1.2, height=0.9, porosity=0.1) has
        // added_mass_coefficient 0.9101123268 and C_a (2/3) π R² H = 2.4703507006413634;
        // its CdS no longer sizes it.
        let shape = CanopyShape {
            radius_m: Some(1.2),
            height_m: Some(0.9),
            porosity: 0.1,
        };
        assert!((canopy_added_mass_coefficient(0.1) - 0.910_112_326_8).abs() < 1e-12);
        for cds in [2.0, 5.0] {
            let v = shape.added_air_volume_m3(cds);
            assert!((v - 2.470_350_700_641_363_4).abs() < 1e-12, "{v}");
        }
        // A radius alone makes a hemisphere: H = R.
        let hemi = CanopyShape {
            radius_m: Some(1.2),
            ..CanopyShape::default()
        };
        let by_hand = canopy_added_mass_coefficient(CANOPY_POROSITY)
            * (2.0 / 3.0)
            * std::f64::consts::PI
            * 1.2f64.powi(3);
        assert!((hemi.added_air_volume_m3(2.0) - by_hand).abs() < 1e-13);
    }

    #[test]
    fn under_a_canopy_the_added_mass_slows_the_change_but_not_the_steady_descent() {
        // 16 kg under 10 m² at ρ = 1.1, still air, inertial frame, g = 9.8.
        let (m, cds, rho, g) = (16.0, 10.0, 1.1, 9.8);
        let at = Surroundings {
            rho,
            g,
            wind_n: V3::new(0.0, 0.0, 0.0),
            earth_rate_n: None,
        };
        let canopies = Canopies {
            cds_m2: cds,
            added_air_m3: CanopyShape::default().added_air_volume_m3(cds),
        };
        let m_a = canopies.added_air_m3 * rho;
        // At the terminal speed √(2 m g / (ρ CdS)) drag and weight balance: no acceleration.
        let v_t = (2.0 * m * g / (rho * cds)).sqrt();
        let mut dy = [0.0; N3];
        descent_derivative(
            &[0.0, 0.0, 500.0, 0.0, 0.0, -v_t],
            m,
            &canopies,
            &at,
            &mut dy,
        );
        assert!(dy[5].abs() < 1e-13, "{}", dy[5]);
        // Falling at 20 m/s and drifting 3 m/s east: (m + m_a) a = −½ ρ CdS |v| v − m g ẑ.
        let v = [3.0, 0.0, -20.0];
        let speed = (9.0f64 + 400.0).sqrt();
        descent_derivative(
            &[0.0, 0.0, 500.0, v[0], v[1], v[2]],
            m,
            &canopies,
            &at,
            &mut dy,
        );
        let drag = |c: f64| -0.5 * rho * cds * speed * c;
        assert_eq!(&dy[..3], &v);
        assert!((dy[3] - drag(v[0]) / (m + m_a)).abs() < 1e-13);
        assert_eq!(dy[4], 0.0);
        assert!((dy[5] - (drag(v[2]) - m * g) / (m + m_a)).abs() < 1e-12);
        // 7.18028 m³ × 1.1 kg/m³ = 7.8983 kg of air, half the rocket's mass.
        assert!((m_a - 7.898_310).abs() < 1e-6, "{m_a}");
    }

    #[test]
    fn the_descent_s_velocity_jacobian_is_the_derivative_s_by_central_differences() {
        // 16 kg under 10 m², a 4 m/s wind, at 45° north (the Coriolis term), drifting and
        // falling: each column against (f(v + δ) − f(v − δ)) / 2δ, δ = 1e-5 m/s, whose
        // truncation (δ² f‴ / 6, f‴ ≈ c / |u| ≈ 0.02) and rounding (ε |f| / δ ≈ 1e-11) stay
        // below 1e-9.
        let omega = crate::gravity::earth_rate_n(45.0);
        let at = Surroundings {
            rho: 1.1,
            g: 9.8,
            wind_n: V3::new(4.0, -1.0, 0.0),
            earth_rate_n: Some(V3::new(omega[0], omega[1], omega[2])),
        };
        let canopies = Canopies {
            cds_m2: 10.0,
            added_air_m3: CanopyShape::default().added_air_volume_m3(10.0),
        };
        let y = [3.0, 2.0, 400.0, 1.5, 0.5, -7.0];
        let jac = descent_velocity_jacobian(&y, 16.0, &canopies, &at);
        let d = 1e-5;
        for j in 0..3 {
            let (mut up, mut down) = (y, y);
            up[3 + j] += d;
            down[3 + j] -= d;
            let (mut fu, mut fd) = ([0.0; N3], [0.0; N3]);
            descent_derivative(&up, 16.0, &canopies, &at, &mut fu);
            descent_derivative(&down, 16.0, &canopies, &at, &mut fd);
            for i in 0..3 {
                let diff = (fu[3 + i] - fd[3 + i]) / (2.0 * d);
                let got = jac[i][j];
                assert!(
                    (got - diff).abs() < 1e-9,
                    "dv{i}/dv{j}: {got} against {diff}"
                );
            }
        }
        // At rest in the air the drag's part vanishes; Coriolis's stays.
        let still = [0.0, 0.0, 100.0, 4.0, -1.0, 0.0];
        let jac = descent_velocity_jacobian(&still, 16.0, &canopies, &at);
        assert_eq!(jac[0][0], 0.0);
        assert_eq!(jac[0][1], 2.0 * omega[2]);
    }
}
