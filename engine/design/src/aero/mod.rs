//! Aerodynamics of a design: Barrowman's normal-force slopes and centers of pressure per
//! component, their Mach dependence as RocketPy computes it, fin-cant roll forcing and roll
//! damping, and the zero-lift drag coefficient (the design's curves, or OpenRocket's estimate).
//!
//! Everything is built once, by [`AeroModel::from_design`], into tables over Mach (0 to 5 in
//! steps of 0.01, linear interpolation, constant beyond): the flight reads them every step
//! without allocating. All coefficients are referenced to the area `A_ref = π d²/4` of the
//! design's reference diameter `d` (and to `d` for moments); positions are metres aft of the
//! nose tip (the station frame).
//!
//! Submodules: [`barrowman`] (Mach-0 slopes and CPs, sources there), [`mach`] (Mach
//! dependence and roll), [`profile`] (body profiles and their integrals), [`drag_formulas`],
//! [`nose_drag`] and [`drag_estimate`] (OpenRocket's drag method), [`table`] (look-ups).
//!
//! Body tubes carry no normal force (Barrowman; RocketPy likewise has no body lift).

pub mod barrowman;
pub mod drag_estimate;
pub mod drag_formulas;
pub mod fins;
pub mod mach;
pub mod nose_drag;
pub mod profile;
pub mod table;
#[cfg(test)]
mod tests;

pub use barrowman::Lift;
pub use fins::{FinGeometry, Fins};
pub use profile::Section;
pub use table::{Curve, MachTable, ReynoldsTables};

use crate::design::{ComponentIdx, ComponentKind, Design, DragSpec, FinPlanform};
use std::f64::consts::PI;

/// Static margin in calibres: `(x_cp − x_cg)/d`, positive when the CP is aft of the CG.
#[inline]
pub fn static_margin_cal(cp_m: f64, cg_m: f64, d_m: f64) -> f64 {
    (cp_m - cg_m) / d_m
}

/// Why a design's aerodynamics cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AeroError {
    #[error("{file}: reference_diameter_m is {value}; the reference diameter must be finite and positive")]
    BadReferenceDiameter { file: String, value: f64 },
    #[error("{file}: component '{component}' ({kind}): {field} is {value}; {rule}")]
    BadGeometry {
        file: String,
        component: String,
        kind: &'static str,
        field: &'static str,
        value: f64,
        rule: &'static str,
    },
    #[error(
        "{file}: the rocket's total normal-force slope is {cn_alpha} at Mach {mach}; it must be \
         positive for the center of pressure to exist (does the design have a nose cone and fins?)"
    )]
    NoNetLift {
        file: String,
        mach: f64,
        cn_alpha: f64,
    },
    #[error("{file}: drag.{which}: {rule}")]
    BadDragCurve {
        file: String,
        which: &'static str,
        rule: &'static str,
    },
}

/// What kind of component a lifting surface is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceKind {
    NoseCone,
    Transition,
    FinSet,
}

/// Roll data of a fin set (RocketPy's `Fins.roll_parameters`), on `A_ref` and `d`.
///
/// Roll moment of the set, as RocketPy writes it about its body axis pointing to the nose:
/// `M = q A_ref d (C_lf,δ(M) δ − C_ld,ω(M) ω d/(2V))`, `q = ρV²/2`, `δ` the cant in radians,
/// `ω` the roll rate about that axis. About the station `+x` axis (pointing aft) the moment is
/// `M_x = −q A_ref d (C_lf,δ δ + C_ld,ω ω_x d/(2V))` with `ω_x` the roll rate about `+x`.
#[derive(Debug, Clone, PartialEq)]
pub struct FinRoll {
    pub count: u32,
    /// Cant angle, rad (the design's `cant_deg`, RocketPy's `cant_angle`).
    pub cant_rad: f64,
    /// First fin's angle about the axis, rad.
    pub rotation_rad: f64,
    /// Roll forcing coefficient per radian of cant, `C_lf,δ`.
    pub forcing_per_rad: MachTable,
    /// Roll damping coefficient, `C_ld,ω`.
    pub damping: MachTable,
    /// The planform numbers behind them.
    pub geometry: FinGeometry,
}

/// One component that produces normal force.
#[derive(Debug, Clone, PartialEq)]
pub struct LiftingSurface {
    pub kind: SurfaceKind,
    /// Index in [`Design::components`].
    pub component: ComponentIdx,
    /// The component's id.
    pub id: String,
    /// Center of pressure, m aft of the nose tip (absolute; constant over Mach).
    pub x_cp_m: f64,
    /// `dCN/dα` over Mach, 1/rad, on `A_ref`.
    pub cn_alpha: MachTable,
    /// Fin sets only.
    pub roll: Option<FinRoll>,
}

impl LiftingSurface {
    /// `dCN/dα` at `mach`, 1/rad, on `A_ref`.
    #[inline]
    pub fn cn_alpha(&self, mach: f64) -> f64 {
        self.cn_alpha.at(mach)
    }
}

/// Where the drag coefficients come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DragSource {
    /// The design's curves.
    Curves,
    /// OpenRocket's estimate from the geometry ([`drag_estimate`]).
    Estimate,
}

/// Zero-lift drag coefficient over Mach, on `A_ref`.
#[derive(Debug, Clone, PartialEq)]
pub enum DragCurve {
    /// The design's points, interpolated linearly, constant beyond the ends (as RocketPy).
    Points(Curve),
    /// A table on the Mach grid.
    Table(MachTable),
}

impl DragCurve {
    #[inline]
    pub fn at(&self, mach: f64) -> f64 {
        match self {
            DragCurve::Points(c) => c.at(mach),
            DragCurve::Table(t) => t.at(mach),
        }
    }
}

/// Everything aerodynamic the flight needs, built once per design.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroModel {
    pub ref_diameter_m: f64,
    pub ref_area_m2: f64,
    /// Nose cones, transitions and fin sets, in the design's component order.
    pub surfaces: Vec<LiftingSurface>,
    pub drag_source: DragSource,
    pub drag_power_off: DragCurve,
    pub drag_power_on: DragCurve,
    /// For an estimated drag, `C_D` against Mach and the Reynolds number's scale (the
    /// curves above are its sea-level table); `None` for curves a design gives.
    pub drag_reynolds: Option<ReynoldsTables>,
    cn_alpha_total: MachTable,
    cp_total: MachTable,
    roll_forcing_total: MachTable,
    roll_damping_total: MachTable,
}

impl AeroModel {
    /// Builds the model of a validated design.
    pub fn from_design(design: &Design) -> Result<AeroModel, AeroError> {
        let file = design.source.as_ref().map_or_else(
            || format!("design '{}'", design.name),
            |p| p.display().to_string(),
        );
        let d = design.reference_diameter_m;
        if !(d.is_finite() && d > 0.0) {
            return Err(AeroError::BadReferenceDiameter { file, value: d });
        }
        let a_ref = PI * d * d / 4.0;
        let mut surfaces = Vec::new();
        for (idx, c) in design.components.iter().enumerate() {
            let bad =
                |field: &'static str, value: f64, rule: &'static str| AeroError::BadGeometry {
                    file: file.clone(),
                    component: c.id.clone(),
                    kind: c.kind.type_name(),
                    field,
                    value,
                    rule,
                };
            let positive = |field: &'static str, v: f64| {
                if v.is_finite() && v > 0.0 {
                    Ok(())
                } else {
                    Err(bad(field, v, "must be finite and positive"))
                }
            };
            match &c.kind {
                ComponentKind::NoseCone(n) => {
                    positive("length_m", c.length_m)?;
                    positive("base_diameter_m", n.base_diameter_m)?;
                    let lift = barrowman::nose_cone_lift(
                        n.shape,
                        c.length_m,
                        n.base_diameter_m / 2.0,
                        a_ref,
                    );
                    surfaces.push(body_surface(
                        SurfaceKind::NoseCone,
                        idx,
                        &c.id,
                        c.x_top_m,
                        lift,
                    ));
                }
                ComponentKind::Transition(t) => {
                    positive("length_m", c.length_m)?;
                    if !(t.fore_diameter_m.is_finite() && t.fore_diameter_m >= 0.0) {
                        return Err(bad(
                            "fore_diameter_m",
                            t.fore_diameter_m,
                            "must be finite and non-negative",
                        ));
                    }
                    if !(t.aft_diameter_m.is_finite() && t.aft_diameter_m >= 0.0) {
                        return Err(bad(
                            "aft_diameter_m",
                            t.aft_diameter_m,
                            "must be finite and non-negative",
                        ));
                    }
                    let section = Section::transition(c.length_m, t);
                    let lift = barrowman::body_section_lift(&section, a_ref);
                    // Equal end diameters: no lift (a tube), nothing for the flight to sum.
                    if lift.cn_alpha != 0.0 {
                        surfaces.push(body_surface(
                            SurfaceKind::Transition,
                            idx,
                            &c.id,
                            c.x_top_m,
                            lift,
                        ));
                    }
                }
                ComponentKind::FinSet(f) => {
                    positive("root_chord_m", f.root_chord_m)?;
                    positive("span_m", f.span_m)?;
                    positive("body_radius_m", f.body_radius_m)?;
                    if let FinPlanform::Trapezoidal {
                        tip_chord_m,
                        sweep_m,
                    } = f.planform
                    {
                        if !(tip_chord_m.is_finite() && tip_chord_m >= 0.0) {
                            return Err(bad(
                                "tip_chord_m",
                                tip_chord_m,
                                "must be finite and non-negative",
                            ));
                        }
                        if !sweep_m.is_finite() {
                            return Err(bad("sweep_m", sweep_m, "must be finite"));
                        }
                    }
                    if f.count == 0 {
                        return Err(bad("count", 0.0, "a fin set needs at least one fin"));
                    }
                    let fins = Fins::of(f);
                    let g = fins.geometry();
                    let cn_alpha =
                        MachTable::from_fn(|m| mach::fin_set_cn_alpha(&fins, &g, m, a_ref));
                    let roll = FinRoll {
                        count: f.count,
                        cant_rad: fins.cant_rad,
                        rotation_rad: f.rotation_deg.to_radians(),
                        forcing_per_rad: MachTable::from_fn(|m| {
                            mach::roll_forcing_per_cant(&fins, &g, m, a_ref, d)
                        }),
                        damping: MachTable::from_fn(|m| mach::roll_damping(&fins, &g, m, a_ref, d)),
                        geometry: g,
                    };
                    surfaces.push(LiftingSurface {
                        kind: SurfaceKind::FinSet,
                        component: idx,
                        id: c.id.clone(),
                        x_cp_m: c.x_top_m + fins.x_cp_m(),
                        cn_alpha,
                        roll: Some(roll),
                    });
                }
                _ => {}
            }
        }

        let cn_alpha_total =
            MachTable::from_fn(|m| surfaces.iter().map(|s| s.cn_alpha.at(m)).sum());
        if let Some((i, &cn)) = cn_alpha_total
            .values()
            .iter()
            .enumerate()
            .find(|(_, &v)| v.is_nan() || v <= 0.0)
        {
            return Err(AeroError::NoNetLift {
                file,
                mach: table::mach_node(i),
                cn_alpha: cn,
            });
        }
        let moment =
            MachTable::from_fn(|m| surfaces.iter().map(|s| s.cn_alpha.at(m) * s.x_cp_m).sum());
        let cp_total = moment.zip_with(&cn_alpha_total, |num, den| num / den);
        let roll_forcing_total = MachTable::from_fn(|m| {
            surfaces
                .iter()
                .filter_map(|s| s.roll.as_ref())
                .map(|r| r.forcing_per_rad.at(m) * r.cant_rad)
                .sum()
        });
        let roll_damping_total = MachTable::from_fn(|m| {
            surfaces
                .iter()
                .filter_map(|s| s.roll.as_ref())
                .map(|r| r.damping.at(m))
                .sum()
        });

        let (drag_source, drag_power_off, drag_power_on, drag_reynolds) = match &design.drag {
            DragSpec::Curves {
                power_off,
                power_on,
            } => {
                let curve = |pts: &[(f64, f64)], which: &'static str| {
                    Curve::new(pts).map(DragCurve::Points).ok_or_else(|| AeroError::BadDragCurve {
                        file: file.clone(),
                        which,
                        rule: "needs at least one (mach, cd) point, all finite, Mach strictly increasing",
                    })
                };
                (
                    DragSource::Curves,
                    curve(power_off, "power_off")?,
                    curve(power_on, "power_on")?,
                    None,
                )
            }
            DragSpec::Estimate { roughness_m } => {
                if !(roughness_m.is_finite() && *roughness_m >= 0.0) {
                    return Err(AeroError::BadDragCurve {
                        file,
                        which: "estimate.roughness_m",
                        rule: "must be finite and non-negative",
                    });
                }
                let est = drag_estimate::DragGeometry::from_design(design, *roughness_m).estimate();
                (
                    DragSource::Estimate,
                    DragCurve::Table(est.power_off),
                    DragCurve::Table(est.power_on),
                    Some(est.reynolds),
                )
            }
        };

        Ok(AeroModel {
            ref_diameter_m: d,
            ref_area_m2: a_ref,
            surfaces,
            drag_source,
            drag_power_off,
            drag_power_on,
            drag_reynolds,
            cn_alpha_total,
            cp_total,
            roll_forcing_total,
            roll_damping_total,
        })
    }

    /// Total `dCN/dα` at `mach`, 1/rad, on `A_ref`.
    #[inline]
    pub fn cn_alpha(&self, mach: f64) -> f64 {
        self.cn_alpha_total.at(mach)
    }

    /// Center of pressure of the whole rocket at `mach`, m aft of the nose tip: the
    /// `CNα`-weighted mean of the surfaces' CPs.
    #[inline]
    pub fn cp_m(&self, mach: f64) -> f64 {
        self.cp_total.at(mach)
    }

    /// Roll forcing coefficient of all fin sets at their cants, `Σ C_lf,δ δ` (see [`FinRoll`]).
    #[inline]
    pub fn roll_forcing_coefficient(&self, mach: f64) -> f64 {
        self.roll_forcing_total.at(mach)
    }

    /// Roll damping coefficient of all fin sets, `Σ C_ld,ω` (see [`FinRoll`]).
    #[inline]
    pub fn roll_damping_coefficient(&self, mach: f64) -> f64 {
        self.roll_damping_total.at(mach)
    }

    /// Zero-lift drag coefficient, motor off, on `A_ref`.
    #[inline]
    pub fn cd_power_off(&self, mach: f64) -> f64 {
        self.drag_power_off.at(mach)
    }

    /// Zero-lift drag coefficient, motor burning, on `A_ref`.
    #[inline]
    pub fn cd_power_on(&self, mach: f64) -> f64 {
        self.drag_power_on.at(mach)
    }

    /// Static margin in calibres for a center of mass at `cg_m`, at `mach`.
    #[inline]
    pub fn static_margin_cal(&self, cg_m: f64, mach: f64) -> f64 {
        static_margin_cal(self.cp_m(mach), cg_m, self.ref_diameter_m)
    }
}

fn body_surface(
    kind: SurfaceKind,
    idx: ComponentIdx,
    id: &str,
    x_top_m: f64,
    lift: Lift,
) -> LiftingSurface {
    LiftingSurface {
        kind,
        component: idx,
        id: id.to_string(),
        x_cp_m: x_top_m + lift.x_cp_m,
        cn_alpha: MachTable::constant(lift.cn_alpha),
        roll: None,
    }
}
