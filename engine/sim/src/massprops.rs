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
use crate::eom::{MassLanes, MassState};
use crate::lanes::{pack_m3, pack_v3, F64x4, Real, M3, V3};
use hpr_design::mass::MassProps;
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
    /// The propellant's inertia about O per kilogram of propellant, body axes, m².
    pub propellant_inertia_o_per_kg: Matrix3<f64>,
    /// The parts that shifts move.
    pub parts: Vec<MovingPart>,
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

/// Most parts that shifts may move.
pub const MAX_PARTS: usize = 8;

/// The propellant's mass and its first two rates at one instant (of one flight, or of four
/// lanes side by side).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PropellantState<S = f64> {
    pub mass_kg: S,
    pub rate_kg_s: S,
    pub accel_kg_s2: S,
}

/// A [`MassModel`]'s numbers as [`mass_lanes`] reads them: one flight's (`f64`) or four
/// variants' side by side ([`F64x4`](crate::lanes::F64x4), packed by [`pack_mass_models`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassModelLanes<S> {
    pub fixed_mass_kg: S,
    pub fixed_first_moment_b: V3<S>,
    pub fixed_inertia_o_b: M3<S>,
    pub propellant_cg_b: V3<S>,
    pub propellant_inertia_o_per_kg: M3<S>,
    /// How many parts move (the same in every lane).
    pub n_parts: usize,
    pub part_mass_kg: [S; MAX_PARTS],
    pub part_c0_b: [V3<S>; MAX_PARTS],
}

impl MassModelLanes<f64> {
    /// One flight's model.
    #[inline(always)]
    pub fn of(model: &MassModel) -> MassModelLanes<f64> {
        let mut part_mass_kg = [0.0; MAX_PARTS];
        let mut part_c0_b = [V3::new(0.0, 0.0, 0.0); MAX_PARTS];
        for (k, p) in model.parts.iter().take(MAX_PARTS).enumerate() {
            part_mass_kg[k] = p.mass_kg;
            part_c0_b[k] = V3::from_na(&p.c0_b);
        }
        MassModelLanes {
            fixed_mass_kg: model.fixed_mass_kg,
            fixed_first_moment_b: V3::from_na(&model.fixed_first_moment_b),
            fixed_inertia_o_b: M3::from_na(&model.fixed_inertia_o_b),
            propellant_cg_b: V3::from_na(&model.propellant_cg_b),
            propellant_inertia_o_per_kg: M3::from_na(&model.propellant_inertia_o_per_kg),
            n_parts: model.parts.len().min(MAX_PARTS),
            part_mass_kg,
            part_c0_b,
        }
    }
}

/// Four flights' models side by side; `None` unless they move the same number of parts.
pub fn pack_mass_models(m: [&MassModelLanes<f64>; 4]) -> Option<MassModelLanes<F64x4>> {
    let n_parts = m[0].n_parts;
    if m.iter().any(|x| x.n_parts != n_parts) {
        return None;
    }
    let s = |f: fn(&MassModelLanes<f64>) -> f64| F64x4(m.map(f));
    Some(MassModelLanes {
        fixed_mass_kg: s(|x| x.fixed_mass_kg),
        fixed_first_moment_b: pack_v3(m.map(|x| &x.fixed_first_moment_b)),
        fixed_inertia_o_b: pack_m3(m.map(|x| &x.fixed_inertia_o_b)),
        propellant_cg_b: pack_v3(m.map(|x| &x.propellant_cg_b)),
        propellant_inertia_o_per_kg: pack_m3(m.map(|x| &x.propellant_inertia_o_per_kg)),
        n_parts,
        part_mass_kg: std::array::from_fn(|k| F64x4(m.map(|x| x.part_mass_kg[k]))),
        part_c0_b: std::array::from_fn(|k| pack_v3(m.map(|x| &x.part_c0_b[k]))),
    })
}

/// `a + b`, element by element.
#[inline(always)]
fn add_m<S: Real>(a: &M3<S>, b: &M3<S>) -> M3<S> {
    M3 {
        m: std::array::from_fn(|r| std::array::from_fn(|c| a.m[r][c] + b.m[r][c])),
    }
}

/// `a − b`, element by element.
#[inline(always)]
fn sub_m<S: Real>(a: &M3<S>, b: &M3<S>) -> M3<S> {
    M3 {
        m: std::array::from_fn(|r| std::array::from_fn(|c| a.m[r][c] - b.m[r][c])),
    }
}

/// `a k`, element by element.
#[inline(always)]
fn scale_m<S: Real>(a: &M3<S>, k: S) -> M3<S> {
    M3 {
        m: std::array::from_fn(|r| std::array::from_fn(|c| a.m[r][c] * k)),
    }
}

/// `k E` (the identity times `k`, as `E · k` element by element).
#[inline(always)]
fn identity_times<S: Real>(k: S) -> M3<S> {
    let (one, zero) = (S::splat(1.0), S::splat(0.0));
    M3 {
        m: std::array::from_fn(|r| {
            std::array::from_fn(|c| if r == c { one * k } else { zero * k })
        }),
    }
}

/// The outer product `a bᵀ`.
#[inline(always)]
fn outer<S: Real>(a: &V3<S>, b: &V3<S>) -> M3<S> {
    let (a, b) = ([a.x, a.y, a.z], [b.x, b.y, b.z]);
    M3 {
        m: std::array::from_fn(|r| std::array::from_fn(|c| a[r] * b[c])),
    }
}

/// `J(v) = |v|² E − v vᵀ`, the inertia about O of a unit mass at `v`.
#[inline(always)]
fn point_inertia_lanes<S: Real>(v: &V3<S>) -> M3<S> {
    sub_m(&identity_times(v.norm_squared()), &outer(v, v))
}

#[inline(always)]
fn select_v<S: Real>(m: S::Mask, a: &V3<S>, b: &V3<S>) -> V3<S> {
    V3::new(
        S::select(m, a.x, b.x),
        S::select(m, a.y, b.y),
        S::select(m, a.z, b.z),
    )
}

#[inline(always)]
fn select_m<S: Real>(m: S::Mask, a: &M3<S>, b: &M3<S>) -> M3<S> {
    M3 {
        m: std::array::from_fn(|r| std::array::from_fn(|c| S::select(m, a.m[r][c], b.m[r][c]))),
    }
}

/// The mass state at one instant, on lanes: the one copy of the mass-property equations.
/// `motions[k]` is the total motion of part `k` along the axis (positive aft), summed over
/// its shifts. A part at rest where the design puts it (no motion, no rate) adds nothing.
#[inline(always)]
pub fn mass_lanes<S: Real>(
    model: &MassModelLanes<S>,
    prop: &PropellantState<S>,
    motions: &[CycloidState<S>],
) -> MassLanes<S> {
    let zero = S::splat(0.0);
    let m = model.fixed_mass_kg + prop.mass_kg;
    let mut s = model.fixed_first_moment_b + model.propellant_cg_b.scale(prop.mass_kg);
    let mut s_rate = model.propellant_cg_b.scale(prop.rate_kg_s);
    let mut s_accel = model.propellant_cg_b.scale(prop.accel_kg_s2);
    let prop_o_per_kg = &model.propellant_inertia_o_per_kg;
    let mut i_o = add_m(
        &model.fixed_inertia_o_b,
        &scale_m(prop_o_per_kg, prop.mass_kg),
    );
    let mut i_rate = scale_m(prop_o_per_kg, prop.rate_kg_s);
    let mut h = V3::zero();
    let mut h_rate = V3::zero();
    for (k, motion) in motions.iter().enumerate().take(model.n_parts) {
        let still = S::and(motion.delta_m.eq(zero), motion.rate_m_s.eq(zero));
        if S::all(still) {
            continue;
        }
        let pm = model.part_mass_kg[k];
        let c0 = model.part_c0_b[k];
        // Aft is −b3.
        let d = V3::new(zero, zero, -motion.delta_m);
        let dv = V3::new(zero, zero, -motion.rate_m_s);
        let da = V3::new(zero, zero, -motion.accel_m_s2);
        let c = c0 + d;
        let i_part = scale_m(
            &sub_m(&point_inertia_lanes(&c), &point_inertia_lanes(&c0)),
            pm,
        );
        let two_c_dv = S::splat(2.0) * c.dot(&dv);
        let i_part_rate = scale_m(
            &sub_m(
                &sub_m(&identity_times(two_c_dv), &outer(&dv, &c)),
                &outer(&c, &dv),
            ),
            pm,
        );
        // Lanes whose part is still keep their sums.
        s = select_v(still, &s, &(s + d.scale(pm)));
        s_rate = select_v(still, &s_rate, &(s_rate + dv.scale(pm)));
        s_accel = select_v(still, &s_accel, &(s_accel + da.scale(pm)));
        i_o = select_m(still, &i_o, &add_m(&i_o, &i_part));
        i_rate = select_m(still, &i_rate, &add_m(&i_rate, &i_part_rate));
        h = select_v(still, &h, &(h + c.cross(&dv).scale(pm)));
        h_rate = select_v(still, &h_rate, &(h_rate + c.cross(&da).scale(pm)));
    }
    let per_m = |v: V3<S>| V3::new(v.x / m, v.y / m, v.z / m);
    let r = per_m(s);
    let m_rate = prop.rate_kg_s;
    let m_accel = prop.accel_kg_s2;
    let r_rate = per_m(s_rate - r.scale(m_rate));
    let r_accel = per_m(s_accel - r_rate.scale(S::splat(2.0) * m_rate) - r.scale(m_accel));
    MassLanes {
        m,
        m_rate,
        m_accel,
        r,
        r_rate,
        r_accel,
        i_o,
        i_o_rate: i_rate,
        h,
        h_rate,
    }
}

/// Lane by lane `if m { a } else { b }` of two mass states.
#[inline(always)]
pub fn select_mass<S: Real>(m: S::Mask, a: &MassLanes<S>, b: &MassLanes<S>) -> MassLanes<S> {
    MassLanes {
        m: S::select(m, a.m, b.m),
        m_rate: S::select(m, a.m_rate, b.m_rate),
        m_accel: S::select(m, a.m_accel, b.m_accel),
        r: select_v(m, &a.r, &b.r),
        r_rate: select_v(m, &a.r_rate, &b.r_rate),
        r_accel: select_v(m, &a.r_accel, &b.r_accel),
        i_o: select_m(m, &a.i_o, &b.i_o),
        i_o_rate: select_m(m, &a.i_o_rate, &b.i_o_rate),
        h: select_v(m, &a.h, &b.h),
        h_rate: select_v(m, &a.h_rate, &b.h_rate),
    }
}

/// Mass state at one instant ([`mass_lanes`] on one flight). `motions[k]` is the total
/// motion of `model.parts[k]` along the axis (positive aft), summed over its shifts; missing
/// entries mean "not moved".
#[inline]
pub fn mass_state(
    model: &MassModel,
    prop: &PropellantState,
    motions: &[CycloidState],
) -> MassState {
    MassState::of_lanes(&mass_lanes(&MassModelLanes::of(model), prop, motions))
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
