//! The mass-property kernel: the rocket's mass, center of mass and inertia about O at one
//! instant, and their exact rates, from the burning propellant and the parts that move.
//!
//! The rocket is split, once before the flight, into what never moves relative to the
//! airframe (structure, casing, every part where the design puts it), the propellant (whose
//! mass falls while its shape scales with it, see `hpr_design::motor`), and the parts that
//! shifts move. Moving a part of mass `m` from `c₀` by `d` adds `m d` to the first moment and
//! `m [J(c₀ + d) − J(c₀)]` to the inertia about O (parallel-axis theorem: the
//! `I_new` of `hpr_design::mass::moved_part` written about O rather than about the new center;
//! the two are the same).
//! The rates follow exactly from the cycloid and the propellant's mass rates:
//!
//! ```text
//! r′  = (S′ − M′ r)/M,          S = Σ m p  (first moment about O)
//! r″  = (S″ − 2 M′ r′ − M″ r)/M
//! I′  = ṁ_p (k_p + J(c_p)) + Σ m (2 (c·d′) E − d′ cᵀ − c d′ᵀ),   c = c₀ + d
//! h   = Σ m c × d′,   h′ = Σ m c × d″
//! ```
//!
//! which are the rates of the center of mass and of the inertia (`docs/moving-mass.md`, "What
//! changes") expanded. A part a release has dropped is taken
//! out whole: its mass `m`, its first moment `m c` and its inertia about O, `I_own + m J(c)`
//! (`c` its center where it left, `I_own` its inertia about that center), are subtracted
//! from the rocket's: the two-body formula about O, exact; it changes none of the rates.
//! Pure, allocation-free, and written once
//! over [`Real`] ([`mass_state_lanes`]): the single flight evaluates it on one lane
//! (`FlightModel::instant_computed_into`), the batch engine on four lanes at once for the
//! lanes whose mass is changing (the motor burning or a part moving), lane by lane the same
//! IEEE operations.

use crate::eom::{MassLanes, MassState};
use crate::lanes::{any, pack_m3, pack_v3, F64x4, Real, M3, V3};
use hpr_design::mass::MassProps;
use hpr_design::motor::Grains;
use nalgebra::{Matrix3, Vector3};

use crate::frames;

/// Most parts that shifts may move in one flight. The kernel keeps their masses, centers and
/// motions in arrays of this size so that it allocates nothing; the flight's set-up refuses a
/// plan with more (`Simulation::with_changes`).
pub const MAX_MOVING_PARTS: usize = 8;

/// A part that one or more shifts move, as the flight sees it (body axes about O).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingPart {
    pub mass_kg: f64,
    /// Its center where the design puts it, body axes, m.
    pub c0_b: Vector3<f64>,
}

/// A part that a release drops, as the flight sees it (body axes about O).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReleasedMass {
    pub mass_kg: f64,
    /// Its center where the design puts it, body axes, m.
    pub c0_b: Vector3<f64>,
    /// Its inertia about its own center, body axes, kg·m².
    pub inertia_cg_b: Matrix3<f64>,
    /// Its index among [`MassModel::parts`] if shifts move it too (it leaves from where
    /// they left it).
    pub moving_part: Option<usize>,
}

impl ReleasedMass {
    /// Its center, body axes, m, once its shifts have moved it `delta_m` aft.
    #[inline]
    pub fn center_b(&self, delta_m: f64) -> Vector3<f64> {
        // Aft is −b3.
        self.c0_b + Vector3::new(0.0, 0.0, -delta_m)
    }
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
    /// The parts that releases drop, in the releases' order (each counted in the fixed mass
    /// above until it leaves).
    pub released: Vec<ReleasedMass>,
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
    /// properties where the design puts them, `released` the parts releases drop (their own
    /// properties where the design puts them, and their index among `parts` if shifts move
    /// them too).
    pub fn new(
        dry: &MassProps,
        casing: &MassProps,
        propellant_full: &MassProps,
        parts: &[MassProps],
        released: &[(MassProps, Option<usize>)],
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
            released: released
                .iter()
                .map(|(p, moving_part)| ReleasedMass {
                    mass_kg: p.mass_kg,
                    c0_b: frames::station_to_body(&p.cg_m),
                    inertia_cg_b: frames::tensor_station_to_body(&p.inertia_cg),
                    moving_part: *moving_part,
                })
                .collect(),
        }
    }
}

/// What the released parts take out of the rocket at one instant, on lanes: their mass,
/// first moment about O and inertia about O (body axes).
#[derive(Debug, Clone, Copy)]
pub struct Removed<S> {
    pub mass_kg: S,
    pub first_moment_b: V3<S>,
    pub inertia_o_b: M3<S>,
}

impl Removed<f64> {
    /// Nothing taken out.
    pub const NONE: Removed<f64> = Removed {
        mass_kg: 0.0,
        first_moment_b: V3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
        inertia_o_b: M3 { m: [[0.0; 3]; 3] },
    };

    /// `part` taken out as well, its center at `c_b` (body axes, m): the part's mass, `m c`
    /// and `I_own + m J(c)` added to what is taken out (in the releases' order, so that both
    /// drivers add the same numbers in the same order).
    #[inline]
    pub fn add(&mut self, part: &ReleasedMass, c_b: &Vector3<f64>) {
        let m = part.mass_kg;
        let c = V3::from_na(c_b);
        self.mass_kg += m;
        self.first_moment_b = self.first_moment_b + c.scale(m);
        self.inertia_o_b = self
            .inertia_o_b
            .add(&M3::from_na(&part.inertia_cg_b).add(&M3::point_inertia(&c).scale(m)));
    }
}

/// A mass model's numbers as [`mass_state_lanes`] reads them, on lanes (the single flight's
/// one lane, or four variants' models packed side by side by the batch engine).
#[derive(Debug, Clone, Copy)]
pub struct MassModelLanes<S> {
    pub fixed_mass_kg: S,
    pub fixed_first_moment_b: V3<S>,
    pub fixed_inertia_o_b: M3<S>,
    pub propellant_cg_b: V3<S>,
    pub propellant_inertia_o_per_kg: M3<S>,
    /// The moving parts' masses and centers where the design puts them (a part that one lane
    /// lacks has no mass there and never moves).
    pub part_mass_kg: [S; MAX_MOVING_PARTS],
    pub part_c0_b: [V3<S>; MAX_MOVING_PARTS],
    /// How many of the parts any lane has.
    pub parts: usize,
    /// Whether any lane's flight releases parts (read beside `parts`: a flight without
    /// releases asks nothing more of them).
    pub releases: bool,
}

impl MassModelLanes<f64> {
    /// One model's numbers (at most [`MAX_MOVING_PARTS`] parts: the set-up's rule).
    #[inline]
    pub fn of(model: &MassModel) -> MassModelLanes<f64> {
        let mut part_mass_kg = [0.0; MAX_MOVING_PARTS];
        let mut part_c0_b = [V3::zero(); MAX_MOVING_PARTS];
        for (k, p) in model.parts.iter().take(MAX_MOVING_PARTS).enumerate() {
            part_mass_kg[k] = p.mass_kg;
            part_c0_b[k] = V3::from_na(&p.c0_b);
        }
        MassModelLanes {
            fixed_mass_kg: model.fixed_mass_kg,
            fixed_first_moment_b: V3::from_na(&model.fixed_first_moment_b),
            fixed_inertia_o_b: M3::from_na(&model.fixed_inertia_o_b),
            propellant_cg_b: V3::from_na(&model.propellant_cg_b),
            propellant_inertia_o_per_kg: M3::from_na(&model.propellant_inertia_o_per_kg),
            part_mass_kg,
            part_c0_b,
            parts: model.parts.len().min(MAX_MOVING_PARTS),
            releases: !model.released.is_empty(),
        }
    }
}

impl MassModelLanes<F64x4> {
    /// Four models' numbers side by side.
    #[inline]
    pub fn pack(m: [&MassModelLanes<f64>; 4]) -> MassModelLanes<F64x4> {
        MassModelLanes {
            fixed_mass_kg: F64x4::from_fn(|i| m[i].fixed_mass_kg),
            fixed_first_moment_b: pack_v3(m.map(|m| &m.fixed_first_moment_b)),
            fixed_inertia_o_b: pack_m3(m.map(|m| &m.fixed_inertia_o_b)),
            propellant_cg_b: pack_v3(m.map(|m| &m.propellant_cg_b)),
            propellant_inertia_o_per_kg: pack_m3(m.map(|m| &m.propellant_inertia_o_per_kg)),
            part_mass_kg: std::array::from_fn(|k| F64x4::from_fn(|i| m[i].part_mass_kg[k])),
            part_c0_b: std::array::from_fn(|k| pack_v3(m.map(|m| &m.part_c0_b[k]))),
            parts: m.iter().map(|m| m.parts).max().unwrap_or(0),
            releases: m.iter().any(|m| m.releases),
        }
    }
}

/// A moving part's motion along the axis (positive aft), summed over its shifts, on lanes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Motion<S> {
    pub delta_m: S,
    pub rate_m_s: S,
    pub accel_m_s2: S,
}

/// What changes the mass at one instant, on lanes: the propellant, its grains' own inertia
/// and the moving parts' motions.
#[derive(Debug, Clone, Copy)]
pub struct MassInputs<S: Real> {
    pub prop_mass_kg: S,
    pub prop_rate_kg_s: S,
    pub prop_accel_kg_s2: S,
    /// The grains' inertia about their own centers, `[axial, transverse]`, and its rate per
    /// kilogram of propellant, on the lanes whose motor gives grains (the mask); `None` when no
    /// lane's does.
    pub grains: Option<(S::Mask, [S; 2], [S; 2])>,
    pub motions: [Motion<S>; MAX_MOVING_PARTS],
    /// What the released parts take out, on every lane; `None` when no lane has lost a part
    /// (a lane that has not, beside one that has, takes out zeros: the same numbers).
    pub removed: Option<Removed<S>>,
}

impl<S: Real> MassInputs<S> {
    /// No propellant, no grains, nothing moved.
    #[inline(always)]
    pub fn zero() -> MassInputs<S> {
        let zero = S::splat(0.0);
        let still = Motion {
            delta_m: zero,
            rate_m_s: zero,
            accel_m_s2: zero,
        };
        MassInputs {
            prop_mass_kg: zero,
            prop_rate_kg_s: zero,
            prop_accel_kg_s2: zero,
            grains: None,
            motions: [still; MAX_MOVING_PARTS],
            removed: None,
        }
    }

    /// Set lane `l`'s released parts: what they take out (`None`: no part has left that lane).
    #[inline(always)]
    pub fn set_removed(&mut self, l: usize, removed: Option<&Removed<f64>>) {
        let r = match (removed, &self.removed) {
            (Some(r), _) => r,
            (None, Some(_)) => &Removed::NONE,
            (None, None) => return,
        };
        let zero = S::splat(0.0);
        let out = self.removed.get_or_insert(Removed {
            mass_kg: zero,
            first_moment_b: V3::new(zero, zero, zero),
            inertia_o_b: M3::diag(zero, zero, zero),
        });
        *out.mass_kg.lane_mut(l) = r.mass_kg;
        *out.first_moment_b.x.lane_mut(l) = r.first_moment_b.x;
        *out.first_moment_b.y.lane_mut(l) = r.first_moment_b.y;
        *out.first_moment_b.z.lane_mut(l) = r.first_moment_b.z;
        for (row, src) in out.inertia_o_b.m.iter_mut().zip(&r.inertia_o_b.m) {
            for (e, v) in row.iter_mut().zip(src) {
                *e.lane_mut(l) = *v;
            }
        }
    }

    /// Set lane `l`'s propellant from `prop`, and its grains' inertia (`grains`, the
    /// grains and how many motors hold them; `None`: the lane's motor gives none).
    #[inline(always)]
    pub fn set_propellant(
        &mut self,
        l: usize,
        prop: &PropellantState,
        grains: Option<&(Grains, usize)>,
    ) {
        *self.prop_mass_kg.lane_mut(l) = prop.mass_kg;
        *self.prop_rate_kg_s.lane_mut(l) = prop.rate_kg_s;
        *self.prop_accel_kg_s2.lane_mut(l) = prop.accel_kg_s2;
        match grains {
            Some((grains, motors)) => {
                let g = grains.cluster_inertia(*motors, prop.mass_kg);
                let zero = S::splat(0.0);
                let (has, i, d) = self
                    .grains
                    .get_or_insert((zero.gt(zero), [zero; 2], [zero; 2]));
                S::set_mask_lane(has, l, true);
                for k in 0..2 {
                    *i[k].lane_mut(l) = g.inertia_kg_m2[k];
                    *d[k].lane_mut(l) = g.per_kg_m2[k];
                }
            }
            None => {
                if let Some((has, _, _)) = &mut self.grains {
                    S::set_mask_lane(has, l, false);
                }
            }
        }
    }
}

/// The mass-property kernel on lanes (the one copy of these equations; the single flight's
/// [`crate::flight::model::FlightModel::instant_computed_into`] is its one lane). A part whose
/// motion and its rate are both zero on a lane adds nothing there.
#[inline(always)]
pub fn mass_state_lanes<S: Real>(model: &MassModelLanes<S>, x: &MassInputs<S>) -> MassLanes<S> {
    let zero = S::splat(0.0);
    let mut m = model.fixed_mass_kg + x.prop_mass_kg;
    let cg = &model.propellant_cg_b;
    let mut s = model.fixed_first_moment_b + cg.scale(x.prop_mass_kg);
    let mut s_rate = cg.scale(x.prop_rate_kg_s);
    let mut s_accel = cg.scale(x.prop_accel_kg_s2);
    let per_kg = &model.propellant_inertia_o_per_kg;
    let mut i_o = model.fixed_inertia_o_b.add(&per_kg.scale(x.prop_mass_kg));
    let mut i_rate = per_kg.scale(x.prop_rate_kg_s);
    if let Some((has, [a, t], [da, dt])) = x.grains {
        // Body axes: the axis is b3.
        let with = i_o.add(&M3::diag(t, t, a));
        i_o = M3::select(has, &with, &i_o);
        let with = i_rate.add(&M3::diag(dt, dt, da).scale(x.prop_rate_kg_s));
        i_rate = M3::select(has, &with, &i_rate);
    }
    // The released parts, taken out whole (where their shifts left them: the moving parts'
    // terms below put them there, and these take them out).
    if let Some(gone) = &x.removed {
        m = m - gone.mass_kg;
        s = s - gone.first_moment_b;
        i_o = i_o.sub(&gone.inertia_o_b);
    }
    let mut h = V3::zero();
    let mut h_rate = V3::zero();
    for k in 0..model.parts {
        let mo = &x.motions[k];
        let moving = S::or(mo.delta_m.ne(zero), mo.rate_m_s.ne(zero));
        if !any::<S>(moving) {
            continue;
        }
        let pm = model.part_mass_kg[k];
        let c0 = &model.part_c0_b[k];
        // Aft is −b3.
        let d = V3::new(zero, zero, -mo.delta_m);
        let dv = V3::new(zero, zero, -mo.rate_m_s);
        let da = V3::new(zero, zero, -mo.accel_m_s2);
        let c = *c0 + d;
        let two_c_dv = S::splat(2.0) * c.dot(&dv);
        let di_rate = M3::diag(two_c_dv, two_c_dv, two_c_dv)
            .sub(&M3::outer(&dv, &c))
            .sub(&M3::outer(&c, &dv));
        s = V3::select(moving, &(s + d.scale(pm)), &s);
        s_rate = V3::select(moving, &(s_rate + dv.scale(pm)), &s_rate);
        s_accel = V3::select(moving, &(s_accel + da.scale(pm)), &s_accel);
        let with = i_o.add(&M3::point_inertia(&c).sub(&M3::point_inertia(c0)).scale(pm));
        i_o = M3::select(moving, &with, &i_o);
        i_rate = M3::select(moving, &i_rate.add(&di_rate.scale(pm)), &i_rate);
        h = V3::select(moving, &(h + c.cross(&dv).scale(pm)), &h);
        h_rate = V3::select(moving, &(h_rate + c.cross(&da).scale(pm)), &h_rate);
    }
    let r = s.div(m);
    let m_rate = x.prop_rate_kg_s;
    let m_accel = x.prop_accel_kg_s2;
    let r_rate = (s_rate - r.scale(m_rate)).div(m);
    let r_accel = (s_accel - r_rate.scale(S::splat(2.0) * m_rate) - r.scale(m_accel)).div(m);
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
