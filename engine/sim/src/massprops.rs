//! The mass-property kernel: the rocket's mass, center of mass and inertia about O at one
//! instant, and their exact rates, from the burning propellant and the parts that move.
//!
//! The rocket is split, once before the flight, into what never moves relative to the
//! airframe (structure, casing, every part where the design puts it), the propellant (whose
//! mass falls while its shape scales with it, see `hpr_design::motor`), and the parts that
//! shifts move. Moving a part of mass `m` from `c₀` by `d` adds `m d` to the first moment and
//! `m [J(c₀ + d) − J(c₀)]` to the inertia about O (parallel-axis theorem, the spec's
//! `I_new` formula written about O rather than about the new center; the two are the same).
//! The rates follow exactly from the cycloid and the propellant's mass rates:
//!
//! ```text
//! r′  = (S′ − M′ r)/M,          S = Σ m p  (first moment about O)
//! r″  = (S″ − 2 M′ r′ − M″ r)/M
//! I′  = ṁ_p (k_p + J(c_p)) + Σ m (2 (c·d′) E − d′ cᵀ − c d′ᵀ),   c = c₀ + d
//! h   = Σ m c × d′,   h′ = Σ m c × d″
//! ```
//!
//! which are the spec's `r′`, `r″` and `I′` expanded. Pure, allocation-free: the single
//! flight and every lane of the batch engine call [`mass_state`].

use crate::cycloid::CycloidState;
use crate::eom::MassState;
use hpr_design::mass::{point_inertia, MassProps};
use hpr_design::motor::Grains;
use nalgebra::{Matrix3, Vector3};

use crate::frames;

/// A part that one or more shifts move, as the flight sees it (body axes about O).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingPart {
    pub mass_kg: f64,
    /// Its center where the design puts it, body axes, m.
    pub c0_b: Vector3<f64>,
}

/// The split of the rocket's mass, built once before the flight.
#[derive(Debug, Clone, PartialEq)]
pub struct MassModel {
    /// Everything but the propellant, every part where the design puts it.
    pub fixed_mass_kg: f64,
    pub fixed_first_moment_b: Vector3<f64>,
    pub fixed_inertia_o_b: Matrix3<f64>,
    /// The propellant's center (fixed), body axes, m.
    pub propellant_cg_b: Vector3<f64>,
    /// The propellant's inertia about O per kilogram of propellant, body axes, m² (all of
    /// it but grains' own shape).
    pub propellant_inertia_o_per_kg: Matrix3<f64>,
    /// The propellant's grains and the motors that hold them, if the motor gives them: their
    /// inertia about their center, not in proportion to the mass left, is added to the above.
    pub grains: Option<(Grains, usize)>,
    /// The parts that shifts move.
    pub parts: Vec<MovingPart>,
}

/// The propellant's mass and its first two rates at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PropellantState {
    pub mass_kg: f64,
    pub rate_kg_s: f64,
    pub accel_kg_s2: f64,
}

impl MassModel {
    /// Build from the rocket without its motor (`dry`), the motor's casing and its full
    /// propellant load, all in the station frame; `parts` are the moving parts' own
    /// properties where the design puts them.
    pub fn new(
        dry: &MassProps,
        casing: &MassProps,
        propellant_full: &MassProps,
        parts: &[MassProps],
    ) -> MassModel {
        let fixed = dry.combine(casing);
        let prop_o = propellant_full.inertia_about_tip();
        let per_kg = if propellant_full.mass_kg > 0.0 {
            prop_o / propellant_full.mass_kg
        } else {
            Matrix3::zeros()
        };
        MassModel {
            fixed_mass_kg: fixed.mass_kg,
            fixed_first_moment_b: frames::station_to_body(&fixed.cg_m) * fixed.mass_kg,
            fixed_inertia_o_b: frames::tensor_station_to_body(&fixed.inertia_about_tip()),
            propellant_cg_b: frames::station_to_body(&propellant_full.cg_m),
            propellant_inertia_o_per_kg: frames::tensor_station_to_body(&per_kg),
            grains: None,
            parts: parts
                .iter()
                .map(|p| MovingPart {
                    mass_kg: p.mass_kg,
                    c0_b: frames::station_to_body(&p.cg_m),
                })
                .collect(),
        }
    }
}

/// Mass state at one instant. `motions[k]` is the total motion of `model.parts[k]` along the
/// axis (positive aft), summed over its shifts; missing entries mean "not moved".
#[inline]
pub fn mass_state(
    model: &MassModel,
    prop: &PropellantState,
    motions: &[CycloidState],
) -> MassState {
    let m = model.fixed_mass_kg + prop.mass_kg;
    let mut s = model.fixed_first_moment_b + model.propellant_cg_b * prop.mass_kg;
    let mut s_rate = model.propellant_cg_b * prop.rate_kg_s;
    let mut s_accel = model.propellant_cg_b * prop.accel_kg_s2;
    let prop_o_per_kg = model.propellant_inertia_o_per_kg;
    let mut i_o = model.fixed_inertia_o_b + prop_o_per_kg * prop.mass_kg;
    let mut i_rate = prop_o_per_kg * prop.rate_kg_s;
    if let Some((grains, motors)) = &model.grains {
        // Body axes: the axis is b3.
        let g = grains.cluster_inertia(*motors, prop.mass_kg);
        let [a, t] = g.inertia_kg_m2;
        let [da, dt] = g.per_kg_m2;
        i_o += Matrix3::from_diagonal(&Vector3::new(t, t, a));
        i_rate += Matrix3::from_diagonal(&Vector3::new(dt, dt, da)) * prop.rate_kg_s;
    }
    let mut h = Vector3::zeros();
    let mut h_rate = Vector3::zeros();
    for (part, motion) in model.parts.iter().zip(motions) {
        if motion.delta_m == 0.0 && motion.rate_m_s == 0.0 {
            continue;
        }
        let pm = part.mass_kg;
        // Aft is −b3.
        let d = Vector3::new(0.0, 0.0, -motion.delta_m);
        let dv = Vector3::new(0.0, 0.0, -motion.rate_m_s);
        let da = Vector3::new(0.0, 0.0, -motion.accel_m_s2);
        let c = part.c0_b + d;
        s += d * pm;
        s_rate += dv * pm;
        s_accel += da * pm;
        i_o += (point_inertia(&c) - point_inertia(&part.c0_b)) * pm;
        i_rate +=
            (Matrix3::identity() * (2.0 * c.dot(&dv)) - dv * c.transpose() - c * dv.transpose())
                * pm;
        h += c.cross(&dv) * pm;
        h_rate += c.cross(&da) * pm;
    }
    let r = s / m;
    let m_rate = prop.rate_kg_s;
    let m_accel = prop.accel_kg_s2;
    let r_rate = (s_rate - r * m_rate) / m;
    let r_accel = (s_accel - r_rate * (2.0 * m_rate) - r * m_accel) / m;
    MassState {
        mass_kg: m,
        mass_rate: m_rate,
        mass_accel: m_accel,
        r_cm: r,
        r_cm_rate: r_rate,
        r_cm_accel: r_accel,
        inertia_o: i_o,
        inertia_o_rate: i_rate,
        h_rel: h,
        h_rel_rate: h_rate,
    }
}

/// The mass state as station-frame [`MassProps`] (center aft of the tip, inertia about the
/// center), for reports.
pub fn to_station(ms: &MassState) -> MassProps {
    let r = frames::station_to_body_matrix();
    let i_cm_b = ms.inertia_cm();
    MassProps {
        mass_kg: ms.mass_kg,
        cg_m: frames::body_to_station(&ms.r_cm),
        inertia_cg: r.transpose() * i_cm_b * r,
    }
}
