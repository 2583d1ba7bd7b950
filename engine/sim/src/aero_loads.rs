//! The aerodynamic-loads kernel: normal force at each lifting surface's center of pressure
//! from its own local angle of attack (so the airframe's rotation gives pitch damping), axial
//! drag from the Cd-vs-Mach curve, and roll forcing and damping from canted fins.
//!
//! As RocketPy does (`Flight.u_dot_generalized`): the air's velocity relative to each surface
//! is `u = −(v_O + ω × p_i − wind_i)` in body axes, with `wind_i` the wind at the surface's
//! own height (in a wind that changes with height the nose and the fins meet different air:
//! the shear turns the rocket as a rotation of the air would; the caller gives it, from the
//! wind and its shear at the center of mass); the surface's angle of attack
//! is the angle between `u` and `−b3`; its normal force is `½ ρ |u|² A_ref CNα(M) α` along the
//! part of `u` across the axis. Drag is `½ ρ V² A_ref Cd(M)` along `−b3`, with `V` the speed
//! through the air of the airframe's point at the center of mass (not of the center itself,
//! which drifts through the airframe while the motor burns). Tables are built once
//! ([`AeroTables`]); a call allocates nothing.
//!
//! Past what RocketPy models, for a rocket that tumbles or flies tail first (an unstable
//! design): beyond 90° a surface's normal force is that of the supplementary angle `π − α`,
//! so it vanishes when the air runs along the axis from either end, and the axial drag turns
//! over smoothly between 45° and 135° (the center of mass's angle of attack) to oppose a flow
//! from behind. Below 45° both are RocketPy's, bit for bit. RocketPy's linear `α` up to 180°
//! and always-aft drag would push a rocket flying tail first ever faster, with a normal force
//! that flips with the crossflow's sign: its steps collapse.

use crate::eom::Loads;
use crate::lanes::{atan2_upper, Real, V3};
use hpr_design::aero::table::{MachTable, ReynoldsTables};
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
    /// An estimated drag's `C_D` against Mach and the Reynolds number's scale, read at the
    /// air the rocket flies through (power on and off alike); `None`: the curves above.
    pub cd_reynolds: Option<ReynoldsTables>,
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

/// Aerodynamic loads about O in body axes, in air that moves the same at every surface.
/// `v_o_air_b` is O's velocity relative to the air and `v_cm_air_b` that of the airframe's
/// point at the center of mass, both in body axes; `drag_scale` multiplies the drag
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
        |_| V3::zero(),
        &V3::from_na(v_cm_air_b),
        &V3::from_na(omega),
        air.density_kg_m3,
        air.speed_of_sound_m_s,
        powered,
        drag_scale,
        0.0,
    );
    Loads {
        force_b: f.to_na(),
        moment_o_b: m.to_na(),
    }
}

/// [`aero_loads`] on lanes (the one copy of these equations): force and moment about O, body
/// axes. `v_o_b` is O's velocity over the ground and `wind_b_at(x)` the wind, both in body
/// axes, at the surface whose center of pressure is `x` m aft of the tip; `v_cm_air_b` is the
/// velocity through the air of the airframe's point at the center of mass. The tables are
/// shared by every lane; look-ups and `atan2` run lane by lane. `brake_cd` is the air brakes'
/// drag coefficient as they stand, on the rocket's reference area (0 when closed or absent:
/// the drag is then the rocket's alone, to the bit).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn loads<S: Real>(
    t: &AeroTables,
    v_o_b: &V3<S>,
    wind_b_at: impl Fn(S) -> V3<S>,
    v_cm_air_b: &V3<S>,
    omega: &V3<S>,
    rho: S,
    speed_of_sound: S,
    powered: S::Mask,
    drag_scale: S,
    brake_cd: S,
) -> (V3<S>, V3<S>) {
    let zero = S::splat(0.0);
    let one = S::splat(1.0);
    let half = S::splat(0.5);
    let area = S::splat(t.ref_area_m2);
    let mut force = V3::<S>::zero();
    let mut moment = V3::<S>::zero();
    for s in &t.surfaces {
        let x_cp = S::splat(s.x_cp_m);
        let p = V3::new(zero, zero, -x_cp);
        let u = -(*v_o_b + omega.cross(&p) - wind_b_at(x_cp));
        let speed2 = u.norm_squared();
        let cross2 = u.x * u.x + u.y * u.y;
        // No flow across the axis (or none at all): no normal force from this surface.
        let none = S::or(cross2.eq(zero), speed2.eq(zero));
        let speed = speed2.sqrt();
        let cross = S::select(none, one, cross2.sqrt());
        // The angle between u and −b3: atan2 is exact near zero, where acos(−u_z/|u|) loses
        // half its digits (and it is cheaper); this one runs in vector registers.
        let alpha = atan2_upper(cross, -u.z);
        // Past 90°, the supplementary angle (see the module doc); below, α itself.
        let back = S::splat(std::f64::consts::PI) - alpha;
        let alpha = S::select(alpha.gt(back), back, alpha);
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
    let cd = if let Some(re) = &t.cd_reynolds {
        // Lane by lane, the scalar look-up: the air's Reynolds scale, then the two tables.
        mach.map(|i, m| {
            re.at(
                m,
                crate::atmosphere::reynolds_ln_scale(rho.lane(i), speed_of_sound.lane(i)),
            )
        })
    } else if S::LANES == 1 {
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
    // The drag's share along −b3: 1 up to 45° off the nose, −1 from 135°, and in between
    // the cubic through 0 broadside that meets both ends with zero slope (x = √2·cos α).
    let x = v_cm_air_b.z / v * S::splat(std::f64::consts::SQRT_2);
    let turning = x * (S::splat(3.0) - x * x) * half;
    let axial = S::select(x.gt(one), one, S::select((-one).gt(x), -one, turning));
    force.z = S::select(
        moving,
        force.z - q * area * drag_scale * cd * axial - q * area * brake_cd * axial,
        force.z,
    );
    moment.z = S::select(moving, moment.z + (forcing - damping), moment.z);
    (force, moment)
}

#[cfg(test)]
mod tests {
    use super::*;

    const AREA_M2: f64 = 0.002;
    const CD: f64 = 0.5;
    const CN_ALPHA: f64 = 10.0;

    /// One surface 0.8 m aft of the tip, constant coefficients, no roll terms.
    fn tables() -> AeroTables {
        AeroTables {
            ref_area_m2: AREA_M2,
            ref_diameter_m: 0.05,
            surfaces: vec![SurfaceTable {
                x_cp_m: 0.8,
                cn_alpha: MachTable::constant(CN_ALPHA),
            }],
            cd_power_off: MachTable::constant(CD),
            cd_power_on: MachTable::constant(CD),
            cd_reynolds: None,
            roll_forcing: MachTable::constant(0.0),
            roll_damping: MachTable::constant(0.0),
            cp_mach0_m: 0.8,
        }
    }

    /// The rocket's velocity through the air at `alpha_deg` off the nose, 100 m/s: along
    /// (sin α, 0, cos α) in body axes, so the air comes at α off −b3.
    fn velocity(alpha_deg: f64) -> Vector3<f64> {
        let a = alpha_deg.to_radians();
        Vector3::new(100.0 * a.sin(), 0.0, 100.0 * a.cos())
    }

    /// Dynamic pressure at `alpha_deg`, rounded as the kernel rounds it.
    fn q_pa(alpha_deg: f64) -> f64 {
        let v = velocity(alpha_deg);
        0.5 * 1.225 * (v.x * v.x + v.y * v.y + v.z * v.z)
    }

    /// The loads of air met at `alpha_deg` off the nose, no rotation, sea-level air.
    fn at(alpha_deg: f64) -> Loads {
        let v = velocity(alpha_deg);
        let air = AirAt {
            density_kg_m3: 1.225,
            speed_of_sound_m_s: 340.0,
        };
        aero_loads(&tables(), &v, &v, &Vector3::zeros(), &air, false, 1.0)
    }

    #[test]
    fn an_estimated_drag_is_read_at_the_reynolds_number_of_the_air_around_the_rocket() {
        // A drag table of 0.5 + 0.02 ln k (linear in ln k, so its interpolation is exact):
        // in the published 5 km air (ρ 0.73643 kg/m³, a 320.55 m/s, k = 0.6223) the axial
        // force is q A (0.5 + 0.02 ln k); four lanes in four airs give each lane's own, bit
        // for bit.
        use crate::lanes::F64x4;
        let t = AeroTables {
            cd_reynolds: Some(ReynoldsTables::from_fn(|_, k| 0.5 + 0.02 * k.ln())),
            ..tables()
        };
        let none = V3::<f64>::zero();
        let v = V3::new(0.0, 0.0, 150.0);
        let axial = |rho: f64, a: f64| {
            loads(&t, &v, |_| none, &v, &none, rho, a, false, 1.0, 0.0)
                .0
                .z
        };
        let q_a = 0.5 * 0.73643 * 150.0 * 150.0 * AREA_M2;
        let ln_k = crate::atmosphere::reynolds_ln_scale(0.73643, 320.55);
        assert!((ln_k - -0.4743).abs() < 1e-3, "{ln_k}");
        let want = -q_a * (0.5 + 0.02 * ln_k);
        let got = axial(0.73643, 320.55);
        assert!((got - want).abs() < 1e-12 * want.abs(), "{got} vs {want}");
        let airs = [
            (1.225, 340.294),
            (0.73643, 320.55),
            (0.41351, 308.0),
            (1.1, 335.0),
        ];
        let lanes = |f: fn(&(f64, f64)) -> f64| F64x4(airs.map(|a| f(&a)));
        let v4 = V3::new(F64x4::splat(0.0), F64x4::splat(0.0), F64x4::splat(150.0));
        let z4 = V3::<F64x4>::zero();
        let (f4, _) = loads(
            &t,
            &v4,
            |_| z4,
            &v4,
            &z4,
            lanes(|a| a.0),
            lanes(|a| a.1),
            [false; 4],
            F64x4::splat(1.0),
            F64x4::splat(0.0),
        );
        for (l, &(rho, a)) in airs.iter().enumerate() {
            assert_eq!(f4.z.0[l].to_bits(), axial(rho, a).to_bits(), "lane {l}");
        }
    }

    #[test]
    fn each_surface_meets_the_wind_at_its_own_center_of_pressure() {
        // Two surfaces, at 0.2 m and 0.8 m, in a wind across the axis that grows aft (as in
        // a shear): each surface's normal force is the one it gets alone in its own wind.
        let mut two = tables();
        two.surfaces.insert(
            0,
            SurfaceTable {
                x_cp_m: 0.2,
                cn_alpha: MachTable::constant(CN_ALPHA),
            },
        );
        let one = |x: f64| AeroTables {
            surfaces: vec![SurfaceTable {
                x_cp_m: x,
                cn_alpha: MachTable::constant(CN_ALPHA),
            }],
            ..tables()
        };
        let wind_at = |x: f64| V3::new(0.0, 3.0 + 10.0 * x, 0.0);
        let v_o = V3::new(0.0, 0.0, 100.0);
        let none = V3::<f64>::zero();
        let alone = |x: f64| {
            let v_air = v_o - wind_at(x);
            loads(
                &one(x),
                &v_air,
                |_| none,
                &v_air,
                &none,
                1.225,
                340.0,
                false,
                1.0,
                0.0,
            )
        };
        let (f, m) = loads(
            &two, &v_o, wind_at, &v_o, &none, 1.225, 340.0, false, 1.0, 0.0,
        );
        let ((f1, m1), (f2, m2)) = (alone(0.2), alone(0.8));
        // Lateral force and moment: the sum of the two alone, to rounding (1e-12 relative).
        assert!(
            (f.y - (f1.y + f2.y)).abs() <= 1e-12 * f.y.abs(),
            "{} {}",
            f.y,
            f1.y + f2.y
        );
        assert!(
            (m.x - (m1.x + m2.x)).abs() <= 1e-12 * m.x.abs(),
            "{} {}",
            m.x,
            m1.x + m2.x
        );
        // The aft surface meets 9 m/s across against the fore one's 5: more force there.
        assert!(f2.y.abs() > 1.7 * f1.y.abs());
    }

    #[test]
    fn up_to_45_degrees_the_drag_is_the_whole_drag_along_the_axis_as_in_rocketpy() {
        for deg in [0.0, 3.0, 20.0, 44.9] {
            // Bit for bit RocketPy's −q A Cd: the turn-over factor is exactly 1 here.
            assert_eq!(
                at(deg).force_b.z,
                0.0 - q_pa(deg) * AREA_M2 * 1.0 * CD,
                "{deg}°"
            );
        }
    }

    #[test]
    fn flying_tail_first_the_drag_points_forward_and_broadside_there_is_none() {
        let drag = |deg: f64| q_pa(deg) * AREA_M2 * CD;
        for deg in [135.1, 150.0, 180.0] {
            let f = at(deg).force_b.z;
            assert!((f - drag(deg)).abs() <= 1e-12 * drag(deg), "{deg}°: {f} N");
        }
        assert!(
            at(90.0).force_b.z.abs() <= 1e-12 * drag(90.0),
            "broadside: {}",
            at(90.0).force_b.z
        );
        // In between it turns over smoothly and without a jump: 89.9° and 90.1° differ by
        // about the slope 1.5·√2 q A Cd per radian times 0.2°.
        let step = (at(90.1).force_b.z - at(89.9).force_b.z).abs();
        let slope = 1.5 * std::f64::consts::SQRT_2 * drag(90.0) * 0.2f64.to_radians();
        assert!(
            (step - slope).abs() < 1e-3 * slope,
            "{step} N against {slope} N"
        );
    }

    #[test]
    fn past_90_degrees_the_normal_force_is_that_of_the_supplementary_angle() {
        // Below 90°: q A CNα α along the crossflow, bit for bit.
        let a = 30f64.to_radians();
        let n30 = q_pa(30.0) * AREA_M2 * CN_ALPHA * a;
        assert!((at(30.0).force_b.x.abs() - n30).abs() <= 1e-12 * n30);
        for deg in [100.0, 150.0, 175.0] {
            let (n, mirror) = (at(deg).force_b.x, at(180.0 - deg).force_b.x);
            assert!(
                (n.abs() - mirror.abs()).abs() <= 1e-9 * mirror.abs(),
                "{deg}°: {n} N against {mirror} N"
            );
        }
        // Straight tail first: no crossflow, no normal force (RocketPy's linear α would give
        // q A CNα π here, its sign set by rounding).
        assert!(at(180.0).force_b.x.abs() < 1e-9, "{}", at(180.0).force_b.x);
        assert!(at(179.0).force_b.x.abs() < 0.02 * q_pa(179.0) * AREA_M2 * CN_ALPHA);
    }
}
