//! Mass properties of a design: each component alone, each subtree and stage with the
//! design's overrides, the dry rocket (everything but the motor), and a table for reports.
//!
//! A component's own properties come from its shape ([`super::solids`]) at unit density,
//! then scaled by its density, or to its given mass (the mass spread uniformly over the
//! shape), or by a shock cord's linear density times its cord length. Overrides follow
//! OpenRocket: an override of mass replaces the mass and scales the inertia by the same
//! ratio; an override of the center moves the center along the axis and keeps the inertia
//! about it; `covers_children` applies the override to the component's subtree instead of to
//! the component alone; a stage's override applies to the whole stage.

use super::solids;
use super::MassProps;
use crate::design::model::*;
use crate::design::shapes;
use nalgebra::{Matrix3, Vector3};

/// One line of a mass report.
#[derive(Debug, Clone, PartialEq)]
pub struct MassRow {
    pub idx: ComponentIdx,
    pub id: String,
    /// The JSON type of the component.
    pub kind: &'static str,
    /// Depth in the tree (0 for body components).
    pub depth: usize,
    /// The component alone, from its shape and material (no override).
    pub own: MassProps,
    /// The component and everything it holds, overrides applied.
    pub subtree: MassProps,
}

/// `props` with an override applied: mass replaced (inertia scaled by the ratio), center
/// moved along the axis to `cg_m` (inertia about the center kept).
pub fn apply_override(props: &MassProps, o: &Overrides) -> MassProps {
    let mut p = *props;
    if let Some(m) = o.mass_kg {
        p = p.with_mass(m);
    }
    if let Some(x) = o.cg_m {
        p.cg_m.x = x;
    }
    p
}

/// The component alone (not what it holds), from its shape and mass spec, with no
/// override, in the station frame.
pub fn component_own(design: &Design, idx: ComponentIdx) -> MassProps {
    let c = &design.components[idx];
    own_of(c, c.mass_spec)
}

/// Component `c` alone with mass spec `spec`, in the station frame.
fn own_of(c: &Component, spec: MassSpec) -> MassProps {
    let at = Vector3::new(c.x_top_m, c.radial_offset_m[0], c.radial_offset_m[1]);
    // A packed cylinder with a measured inertia keeps it whatever its mass spec.
    if let ComponentKind::MassComponent(p)
    | ComponentKind::ShockCord(p)
    | ComponentKind::Parachute(Parachute { packed: p, .. }) = &c.kind
    {
        let volume = solids::hollow_cylinder_volume(p.radius_m, 0.0, c.length_m);
        let mass = spec_mass(&spec, volume);
        let shape = solids::solid_cylinder(mass, p.radius_m, c.length_m).translated(&at);
        return match p.inertia_kg_m2 {
            Some((axial, transverse)) => MassProps {
                inertia_cg: Matrix3::from_diagonal(&Vector3::new(axial, transverse, transverse)),
                ..shape
            },
            None => shape,
        };
    }
    let unit = unit_shape(c, &at);
    let own = match spec {
        MassSpec::Density(rho) => unit.scaled(rho),
        spec => unit.with_mass(spec_mass(&spec, unit.mass_kg)),
    };
    // A rail guide's few grams stand off the axis, where they would put the center of mass
    // a fraction of a millimetre off it, and the thrust's line with it: a hard-burning
    // rocket would turn a fraction of a degree as it leaves the rail. That asymmetry is
    // smaller than any motor's thrust misalignment, which no one models, and OpenRocket and
    // RocketPy keep the center on the axis; so the guides count spread round the axis. A
    // part put off the axis on purpose (`radial_offset_m`) stays where it is.
    match c.kind {
        ComponentKind::RailButton(_) | ComponentKind::LaunchLug(_) => own.spread_about_axis(),
        _ => own,
    }
}

/// The mass a spec gives a shape of this volume.
fn spec_mass(spec: &MassSpec, volume_m3: f64) -> f64 {
    match *spec {
        MassSpec::Density(rho) => rho * volume_m3,
        MassSpec::Mass(m) => m,
        MassSpec::LinearDensity {
            kg_per_m,
            cord_length_m,
        } => kg_per_m * cord_length_m,
    }
}

/// A shoulder as unit-density tube plus its cap: the tube from `x0` to `x0 + length`, the cap
/// (a disc of the tube's inner radius, as thick as the wall) at the end `cap_at_aft` says.
fn shoulder(s: &Shoulder, x0: f64, cap_at_aft: bool, at: &Vector3<f64>) -> MassProps {
    let ro = s.outer_diameter_m / 2.0;
    let ri = (ro - s.wall_thickness_m).max(0.0);
    let tube = solids::hollow_cylinder(
        solids::hollow_cylinder_volume(ro, ri, s.length_m),
        ro,
        ri,
        s.length_m,
    )
    .translated(&(at + Vector3::new(x0, 0.0, 0.0)));
    if !s.capped || ri <= 0.0 {
        return tube;
    }
    let t = s.wall_thickness_m.min(s.length_m);
    let x_cap = if cap_at_aft { x0 + s.length_m - t } else { x0 };
    let cap = solids::solid_cylinder(solids::hollow_cylinder_volume(ri, 0.0, t), ri, t)
        .translated(&(at + Vector3::new(x_cap, 0.0, 0.0)));
    tube.combine(&cap)
}

/// The component's shape at unit density (mass = volume, m³), placed: `at` is its fore end
/// on its own axis.
fn unit_shape(c: &Component, at: &Vector3<f64>) -> MassProps {
    let l = c.length_m;
    let tube = |ro: f64, ri: f64, len: f64| {
        solids::hollow_cylinder(solids::hollow_cylinder_volume(ro, ri, len), ro, ri, len)
    };
    match &c.kind {
        ComponentKind::NoseCone(n) => {
            let r = n.base_diameter_m / 2.0;
            let wall =
                (!n.filled).then_some(solids::Wall::of(n.wall_thickness_m, n.wall_along_normal));
            let shape = n.shape;
            let body = solids::revolution(|x| shapes::profile_radius(shape, l, r, x), l, wall)
                .translated(at);
            match &n.shoulder {
                Some(s) => body.combine(&shoulder(s, l, true, at)),
                None => body,
            }
        }
        ComponentKind::Transition(t) => {
            let (r1, r2) = (t.fore_diameter_m / 2.0, t.aft_diameter_m / 2.0);
            let wall =
                (!t.filled).then_some(solids::Wall::of(t.wall_thickness_m, t.wall_along_normal));
            let (shape, clip) = (t.shape, t.clip_m);
            let radius = |x| shapes::transition_radius(shape, l, r1, r2, clip, x);
            let mut body = solids::revolution(radius, l, wall).translated(at);
            if let Some(s) = &t.fore_shoulder {
                body = body.combine(&shoulder(s, -s.length_m, false, at));
            }
            if let Some(s) = &t.aft_shoulder {
                body = body.combine(&shoulder(s, l, true, at));
            }
            body
        }
        ComponentKind::BodyTube(b) => {
            let ro = b.outer_diameter_m / 2.0;
            tube(ro, ro - b.wall_thickness_m, l).translated(at)
        }
        ComponentKind::FinSet(f) => {
            let volume = f.count as f64 * solids::fin_area(f) * f.thickness_m;
            solids::fin_set(volume, f).translated(at)
        }
        ComponentKind::LaunchLug(g) => {
            let ro = g.outer_diameter_m / 2.0;
            tube(ro, ro - g.wall_thickness_m, l).translated(at)
        }
        ComponentKind::RailButton(b) => {
            // A small solid cylinder whose axis points out of the body: build it along x,
            // turn x onto the radial direction, and put its center at the button's place.
            let r = b.outer_diameter_m / 2.0;
            let h = b.height_m;
            let button = solids::solid_cylinder(solids::hollow_cylinder_volume(r, 0.0, h), r, h)
                .translated(&Vector3::new(-h / 2.0, 0.0, 0.0));
            let (s, co) = b.angle_deg.to_radians().sin_cos();
            // Columns: x -> radial (0, cos, sin), y -> −x, z -> tangential (0, −sin, cos).
            let q = Matrix3::new(0.0, -1.0, 0.0, co, 0.0, -s, s, 0.0, co);
            button
                .rotated(&q)
                .translated(&(at + Vector3::new(l / 2.0, 0.0, 0.0)))
        }
        ComponentKind::InnerTube(t) => {
            let ro = t.outer_diameter_m / 2.0;
            let one = tube(ro, ro - t.wall_thickness_m, l);
            let mut all = MassProps::ZERO;
            for o in &t.cluster_offsets_m {
                all = all.combine(&one.translated(&Vector3::new(at.x, o[0], o[1])));
            }
            all
        }
        ComponentKind::CenteringRing(r) | ComponentKind::Bulkhead(r) => {
            tube(r.outer_diameter_m / 2.0, r.inner_diameter_m / 2.0, l).translated(at)
        }
        ComponentKind::MassComponent(p)
        | ComponentKind::ShockCord(p)
        | ComponentKind::Parachute(Parachute { packed: p, .. }) => {
            tube(p.radius_m, 0.0, l).translated(at)
        }
    }
}

/// The component and everything it holds, with every override on the way applied.
pub fn subtree(design: &Design, idx: ComponentIdx) -> MassProps {
    let c = &design.components[idx];
    let own = component_own(design, idx);
    // An override's mass on what weighs nothing has no distribution to scale: it is spread
    // as the component's shape spreads it, as OpenRocket puts it at the component's center.
    let nothing_overridden = |props: &MassProps| match c.overrides.mass_kg {
        Some(m) if props.mass_kg == 0.0 && m > 0.0 => Some(own_of(c, MassSpec::Mass(m))),
        _ => None,
    };
    if c.overrides.covers_children {
        let all = c
            .children
            .iter()
            .fold(own, |acc, &ch| acc.combine(&subtree(design, ch)));
        let all = nothing_overridden(&all).unwrap_or(all);
        apply_override(&all, &c.overrides)
    } else {
        let own = nothing_overridden(&own).unwrap_or(own);
        let own = apply_override(&own, &c.overrides);
        c.children
            .iter()
            .fold(own, |acc, &ch| acc.combine(&subtree(design, ch)))
    }
}

/// A stage, its override applied.
pub fn stage(design: &Design, s: usize) -> MassProps {
    let st = &design.stages[s];
    let all = st
        .components
        .iter()
        .filter(|&&i| design.components[i].parent.is_none())
        .fold(MassProps::ZERO, |acc, &i| acc.combine(&subtree(design, i)));
    apply_override(&all, &st.overrides)
}

/// The whole rocket without its motor.
pub fn dry(design: &Design) -> MassProps {
    (0..design.stages.len()).fold(MassProps::ZERO, |acc, s| acc.combine(&stage(design, s)))
}

/// Every component, in the design's order, alone and with what it holds.
pub fn mass_table(design: &Design) -> Vec<MassRow> {
    (0..design.components.len())
        .map(|i| {
            let c = &design.components[i];
            let mut depth = 0;
            let mut p = c.parent;
            while let Some(q) = p {
                depth += 1;
                p = design.components[q].parent;
            }
            MassRow {
                idx: i,
                id: c.id.clone(),
                kind: c.kind.type_name(),
                depth,
                own: component_own(design, i),
                subtree: subtree(design, i),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
