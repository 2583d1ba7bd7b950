//! The aerodynamic-loads kernel: normal force at each lifting surface's center of pressure
//! from its own local angle of attack (so the airframe's rotation gives pitch damping), axial
//! drag from the Cd-vs-Mach curve, and roll forcing and damping from canted fins.
//!
//! As RocketPy does (`Flight.u_dot_generalized`): the air's velocity relative to each surface
//! is `u = −(v_O + ω × p_i − wind)` in body axes; the surface's angle of attack is the angle
//! between `u` and `−b3`; its normal force is `½ ρ |u|² A_ref CNα(M) α` along the part of `u`
//! across the axis. Drag is `½ ρ V² A_ref Cd(M)` along `−b3`, with `V` the center of mass's
//! speed through the air. Tables are built once ([`AeroTables`]); a call allocates nothing.

use crate::eom::Loads;
use crate::lanes::{atan2_upper, Real, V3};
use hpr_design::aero::table::MachTable;
use nalgebra::Vector3;

/// One lifting surface on the axis.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceTable {
    /// Center of pressure, m aft of the nose tip.
    pub x_cp_m: f64,
    /// Normal-force slope against Mach, per radian, referenced to `ref_area_m2`.
    pub cn_alpha: MachTable,
}

/// Everything the loads need, built once before the flight.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroTables {
    pub ref_area_m2: f64,
    pub ref_diameter_m: f64,
    pub surfaces: Vec<SurfaceTable>,
    pub cd_power_off: MachTable,
    pub cd_power_on: MachTable,
    /// Roll forcing coefficient per radian of cant times the cant (so: the coefficient), against
    /// Mach; the roll moment is `½ρV² A_ref d · forcing`.
    pub roll_forcing: MachTable,
    /// Roll damping coefficient against Mach; the moment is `−½ρV A_ref d² · damping · ω3 / 2`.
    pub roll_damping: MachTable,
    /// Center of pressure of the whole rocket at Mach 0, m aft of the tip.
    pub cp_mach0_m: f64,
}

/// The air a load evaluation sees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirAt {
    pub density_kg_m3: f64,
    pub speed_of_sound_m_s: f64,
}

impl AeroTables {
    /// Whole-rocket center of pressure at `mach`, m aft of the tip (CNα-weighted).
    pub fn cp_m(&self, mach: f64) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        for s in &self.surfaces {
            let c = s.cn_alpha.at(mach);
            num += c * s.x_cp_m;
            den += c;
        }
        if den == 0.0 {
            f64::NAN
        } else {
            num / den
        }
    }

    /// Drag coefficient at `mach`, motor burning or not.
    #[inline]
    pub fn cd(&self, mach: f64, powered: bool) -> f64 {
        if powered {
            self.cd_power_on.at(mach)
        } else {
            self.cd_power_off.at(mach)
        }
    }
}

/// Aerodynamic loads about O in body axes. `v_o_air_b` is O's velocity relative to the air and
/// `v_cm_air_b` the center of mass's, both in body axes; `drag_scale` multiplies the drag
/// coefficient (a dispersion, 1 by default).
#[inline]
pub fn aero_loads(
    t: &AeroTables,
    v_o_air_b: &Vector3<f64>,
    v_cm_air_b: &Vector3<f64>,
    omega: &Vector3<f64>,
    air: &AirAt,
    powered: bool,
    drag_scale: f64,
) -> Loads {
    let (f, m) = loads(
        t,
        &V3::from_na(v_o_air_b),
        &V3::from_na(v_cm_air_b),
        &V3::from_na(omega),
        air.density_kg_m3,
        air.speed_of_sound_m_s,
        powered,
        drag_scale,
    );
    Loads {
        force_b: f.to_na(),
        moment_o_b: m.to_na(),
    }
}

/// [`aero_loads`] on lanes (the one copy of these equations): force and moment about O, body
/// axes. The tables are shared by every lane; look-ups and `atan2` run lane by lane.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn loads<S: Real>(
    t: &AeroTables,
    v_o_air_b: &V3<S>,
    v_cm_air_b: &V3<S>,
    omega: &V3<S>,
    rho: S,
    speed_of_sound: S,
    powered: S::Mask,
    drag_scale: S,
) -> (V3<S>, V3<S>) {
    let zero = S::splat(0.0);
    let one = S::splat(1.0);
    let half = S::splat(0.5);
    let area = S::splat(t.ref_area_m2);
    let mut force = V3::<S>::zero();
    let mut moment = V3::<S>::zero();
    for s in &t.surfaces {
        let p = V3::new(zero, zero, S::splat(-s.x_cp_m));
        let u = -(*v_o_air_b + omega.cross(&p));
        let speed2 = u.norm_squared();
        let cross2 = u.x * u.x + u.y * u.y;
        // No flow across the axis (or none at all): no normal force from this surface.
        let none = S::or(cross2.eq(zero), speed2.eq(zero));
        let speed = speed2.sqrt();
        let cross = S::select(none, one, cross2.sqrt());
        // The angle between u and −b3: atan2 is exact near zero, where acos(−u_z/|u|) loses
        // half its digits (and it is cheaper); this one runs in vector registers.
        let alpha = atan2_upper(cross, -u.z);
        let mach = speed / speed_of_sound;
        let cn = S::mach_table(&s.cn_alpha, mach);
        let n = S::select(none, zero, half * rho * speed2 * area * cn * alpha);
        let f = V3::new(n * u.x / cross, n * u.y / cross, zero);
        force = force + f;
        moment = moment + p.cross(&f);
    }
    let v2 = v_cm_air_b.norm_squared();
    let moving = v2.gt(zero);
    let v = v2.sqrt();
    let mach = v / speed_of_sound;
    let q = half * rho * v2;
    let cd = if S::LANES == 1 {
        // One lane: read only the table in use.
        mach.map(|i, m| t.cd(m, S::mask_lane(powered, i)))
    } else {
        S::select(
            powered,
            S::mach_table(&t.cd_power_on, mach),
            S::mach_table(&t.cd_power_off, mach),
        )
    };
    let d = S::splat(t.ref_diameter_m);
    let forcing = q * area * d * S::mach_table(&t.roll_forcing, mach);
    let damping = half * rho * v * area * d * d * S::mach_table(&t.roll_damping, mach) * omega.z
        / S::splat(2.0);
    force.z = S::select(moving, force.z - q * area * drag_scale * cd, force.z);
    moment.z = S::select(moving, moment.z + (forcing - damping), moment.z);
    (force, moment)
}
