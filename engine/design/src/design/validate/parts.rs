//! Parts inside or on a body component: fins, lugs, rail buttons (outside), inner tubes,
//! rings, bulkheads, masses, parachutes and shock cords (inside). Each is placed along its
//! parent by its `position` and must overlap its parent's axial extent and fit inside it.

use super::{Builder, CLUSTER_CENTRE_TOLERANCE_M, FIT_TOLERANCE_M, MAX_CANT_DEG, MAX_FINS};
use crate::design::model::*;
use crate::design::raw::*;
use crate::design::shapes;
use crate::error::{DesignError, Location, Rule};

/// A free-form fin's outline checked: at least three corners, every one finite and none below
/// the root (`y >= 0`), the first the root's leading edge `(0, 0)`, the last its trailing edge
/// `(root chord > 0, 0)`, some corner off the root, no corner twice in a row, and no two edges
/// crossing (the root, from the last corner back to the first, is an edge too). The error is
/// the corner and the rule.
fn fin_outline(points: &[[f64; 2]]) -> Result<(), (usize, &'static str)> {
    let n = points.len();
    if n < 3 {
        return Err((n, "an outline needs at least three corners"));
    }
    for (i, p) in points.iter().enumerate() {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return Err((i, "must be finite"));
        }
        if p[1] < 0.0 {
            return Err((i, "must not be below the root (y >= 0)"));
        }
        if p[0].abs() > MAX_PART_SIZE_M || p[1] > MAX_PART_SIZE_M {
            return Err((
                i,
                "must be within 30 m (MAX_PART_SIZE_M) of the root's leading edge: \
                 the outline is in metres",
            ));
        }
        if i > 0 && *p == points[i - 1] {
            return Err((i, "repeats the corner before it"));
        }
    }
    if points[0] != [0.0, 0.0] {
        return Err((0, "must be the root's leading edge, [0, 0]"));
    }
    let last = points[n - 1];
    if !(last[1] == 0.0 && last[0] > 0.0) {
        return Err((
            n - 1,
            "must be the root's trailing edge, [root chord > 0, 0]",
        ));
    }
    if points.iter().all(|p| p[1] == 0.0) {
        return Err((1, "the outline must leave the root (some y > 0)"));
    }
    // Edges i: points[i] → points[i + 1 mod n]; adjacent edges share a corner.
    let edge = |i: usize| (points[i], points[(i + 1) % n]);
    let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    for i in 0..n {
        for j in i + 1..n {
            if j == i + 1 || (i == 0 && j == n - 1) {
                continue;
            }
            let ((a, b), (c, d)) = (edge(i), edge(j));
            let (d1, d2) = (orient(a, b, c), orient(a, b, d));
            let (d3, d4) = (orient(c, d, a), orient(c, d, b));
            let straddle = d1 * d2 <= 0.0 && d3 * d4 <= 0.0;
            // Four zeros: the edges lie on one line and meet only if their extents overlap.
            let collinear = d1 == 0.0 && d2 == 0.0 && d3 == 0.0 && d4 == 0.0;
            let overlap =
                |k: usize| a[k].min(b[k]).max(c[k].min(d[k])) <= a[k].max(b[k]).min(c[k].max(d[k]));
            if straddle && (!collinear || (overlap(0) && overlap(1))) {
                return Err((j, "its edge crosses another edge of the outline"));
            }
        }
    }
    Ok(())
}

/// A radial offset `(y, z)` from a distance and an angle from +y toward +z, degrees.
fn polar(distance_m: f64, angle_deg: f64) -> [f64; 2] {
    let a = angle_deg.to_radians();
    [distance_m * a.cos(), distance_m * a.sin()]
}

fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// The largest inner radius of a component that holds parts (a filled nose or transition
/// counts as its outer radius: a weight may be set into it).
fn inner_radius(c: &Component) -> f64 {
    let shoulder_in =
        |s: Option<Shoulder>| s.map_or(0.0, |s| s.outer_diameter_m / 2.0 - s.wall_thickness_m);
    match &c.kind {
        ComponentKind::BodyTube(b) => b.outer_diameter_m / 2.0 - b.wall_thickness_m,
        ComponentKind::InnerTube(t) => t.outer_diameter_m / 2.0 - t.wall_thickness_m,
        ComponentKind::NoseCone(n) => {
            let r = n.base_diameter_m / 2.0;
            if n.filled {
                r
            } else {
                (r - n.wall_thickness_m).max(shoulder_in(n.shoulder))
            }
        }
        ComponentKind::Transition(t) => {
            let r = t.fore_diameter_m.max(t.aft_diameter_m) / 2.0;
            if t.filled {
                r
            } else {
                (r - t.wall_thickness_m)
                    .max(shoulder_in(t.fore_shoulder))
                    .max(shoulder_in(t.aft_shoulder))
            }
        }
        _ => 0.0,
    }
}

impl Builder<'_> {
    /// Checks a child of `parent` and adds it, then its own children.
    pub(super) fn child(
        &mut self,
        rc: &RawComponent,
        parent: ComponentIdx,
        stage: usize,
        path: &str,
    ) -> Result<(), DesignError> {
        let at = self.claim_id(rc.id(), path, false)?;
        let p = self.components[parent].clone();
        if rc.is_external() && !p.is_body() {
            return Err(self.invalid(
                &at,
                Some("type"),
                Rule::ExternalPartOffBody {
                    kind: rc.type_name(),
                },
            ));
        }
        let mut cord = None;
        // (length, kind, radial offset relative to the parent, radial half-width about the
        // parent's axis for internal parts, position)
        let (length, kind, offset, half_width, position) = match rc {
            RawComponent::FinSet(f) => {
                if f.count < 1 || f.count > MAX_FINS {
                    return Err(self.invalid(
                        &at,
                        Some("count"),
                        Rule::FinCount {
                            got: f.count,
                            max: MAX_FINS,
                        },
                    ));
                }
                let not_for = |planform: &'static str, given: &[(&'static str, bool)]| match given
                    .iter()
                    .find(|(_, g)| *g)
                {
                    Some((field, _)) => {
                        Err(self.invalid(&at, Some(field), Rule::NotForPlanform { planform }))
                    }
                    None => Ok(()),
                };
                let (planform, root, span) = match f.planform {
                    RawFinPlanform::FreeForm => {
                        not_for(
                            "free_form",
                            &[
                                ("root_chord_m", f.root_chord_m.is_some()),
                                ("tip_chord_m", f.tip_chord_m.is_some()),
                                ("span_m", f.span_m.is_some()),
                                ("sweep_m", f.sweep_m.is_some()),
                                ("sweep_deg", f.sweep_deg.is_some()),
                            ],
                        )?;
                        let points = f.points_m.clone().ok_or_else(|| {
                            self.invalid(
                                &at,
                                Some("points_m"),
                                Rule::Required {
                                    when: "for a free_form fin",
                                },
                            )
                        })?;
                        fin_outline(&points).map_err(|(point, why)| {
                            self.invalid(&at, Some("points_m"), Rule::FinOutline { point, why })
                        })?;
                        let root = points[points.len() - 1][0];
                        let span = points.iter().map(|p| p[1]).fold(0.0, f64::max);
                        (FinPlanform::FreeForm { points_m: points }, root, span)
                    }
                    planform => {
                        not_for(
                            if planform == RawFinPlanform::Elliptical {
                                "elliptical"
                            } else {
                                "trapezoidal"
                            },
                            &[("points_m", f.points_m.is_some())],
                        )?;
                        let shape = if planform == RawFinPlanform::Elliptical {
                            not_for(
                                "elliptical",
                                &[
                                    ("tip_chord_m", f.tip_chord_m.is_some()),
                                    ("sweep_m", f.sweep_m.is_some()),
                                    ("sweep_deg", f.sweep_deg.is_some()),
                                ],
                            )?;
                            FinPlanform::Elliptical
                        } else {
                            let tip = match f.tip_chord_m {
                                Some(t) => self.size_or_zero(&at, "tip_chord_m", t)?,
                                None => {
                                    return Err(self.invalid(
                                        &at,
                                        Some("tip_chord_m"),
                                        Rule::Required {
                                            when: "for a trapezoidal fin (the default planform)",
                                        },
                                    ))
                                }
                            };
                            let sweep = match (f.sweep_m, f.sweep_deg) {
                                (Some(_), Some(_)) => {
                                    return Err(self.invalid(
                                        &at,
                                        Some("sweep_deg"),
                                        Rule::AtMostOneOf {
                                            fields: "\"sweep_m\" and \"sweep_deg\"",
                                        },
                                    ))
                                }
                                // RocketPy: the tip's leading edge s tan Γ behind the root's.
                                (None, Some(deg)) => {
                                    let deg = self.within(&at, "sweep_deg", deg, -89.0, 89.0)?;
                                    f.span_m.unwrap_or(0.0) * deg.to_radians().tan()
                                }
                                (m, None) => {
                                    let sweep = self.finite(&at, "sweep_m", m.unwrap_or(0.0))?;
                                    self.at_most_part_size(&at, "sweep_m", sweep.abs())?;
                                    sweep
                                }
                            };
                            FinPlanform::Trapezoidal {
                                tip_chord_m: tip,
                                sweep_m: sweep,
                            }
                        };
                        let required = |field: &'static str, v: Option<f64>| {
                            v.ok_or_else(|| {
                                self.invalid(
                                    &at,
                                    Some(field),
                                    Rule::Required {
                                        when: "unless the planform is free_form",
                                    },
                                )
                            })
                        };
                        let root = required("root_chord_m", f.root_chord_m)?;
                        if !(root > 0.0 && root.is_finite()) {
                            let rule = match shape {
                                FinPlanform::Trapezoidal { tip_chord_m, .. }
                                    if tip_chord_m > 0.0 =>
                                {
                                    Rule::FinRootChord {
                                        root_m: root,
                                        tip_m: tip_chord_m,
                                    }
                                }
                                _ => Rule::NotPositive { got: root },
                            };
                            return Err(self.invalid(&at, Some("root_chord_m"), rule));
                        }
                        self.at_most_part_size(&at, "root_chord_m", root)?;
                        let span = self.size(&at, "span_m", required("span_m", f.span_m)?)?;
                        (shape, root, span)
                    }
                };
                let thickness = self.size(&at, "thickness_m", f.thickness_m)?;
                let cant = self.within(&at, "cant_deg", f.cant_deg, -MAX_CANT_DEG, MAX_CANT_DEG)?;
                let rotation = self.finite(&at, "rotation_deg", f.rotation_deg)?;
                let fins = FinSet {
                    count: f.count,
                    root_chord_m: root,
                    span_m: span,
                    planform,
                    thickness_m: thickness,
                    cant_deg: cant,
                    body_radius_m: 0.0, // set once placed
                    rotation_deg: rotation,
                    cross_section: match f.cross_section {
                        RawCrossSection::Square => FinCrossSection::Square,
                        RawCrossSection::Rounded => FinCrossSection::Rounded,
                        RawCrossSection::Airfoil => FinCrossSection::Airfoil,
                    },
                    lift_slope_2d_per_rad: match &f.airfoil {
                        Some(a) => self.airfoil_lift_slope(&at, a)?,
                        None => 2.0 * std::f64::consts::PI,
                    },
                };
                (
                    root,
                    ComponentKind::FinSet(fins),
                    [0.0, 0.0],
                    None,
                    f.position,
                )
            }
            RawComponent::LaunchLug(l) => {
                let length = self.size(&at, "length_m", l.length_m)?;
                let od = self.size(&at, "outer_diameter_m", l.outer_diameter_m)?;
                let wall = self.wall(&at, "wall_thickness_m", l.wall_thickness_m, od / 2.0)?;
                let angle = self.finite(&at, "angle_deg", l.angle_deg)?;
                let lug = LaunchLug {
                    outer_diameter_m: od,
                    wall_thickness_m: wall,
                    angle_deg: angle,
                };
                (
                    length,
                    ComponentKind::LaunchLug(lug),
                    [0.0, 0.0],
                    None,
                    l.position,
                )
            }
            RawComponent::RailButton(b) => {
                let od = self.size(&at, "outer_diameter_m", b.outer_diameter_m)?;
                let height = self.size(&at, "height_m", b.height_m)?;
                let angle = self.finite(&at, "angle_deg", b.angle_deg)?;
                let button = RailButton {
                    outer_diameter_m: od,
                    height_m: height,
                    angle_deg: angle,
                };
                (
                    od,
                    ComponentKind::RailButton(button),
                    [0.0, 0.0],
                    None,
                    b.position,
                )
            }
            RawComponent::InnerTube(t) => {
                let length = self.size(&at, "length_m", t.length_m)?;
                let od = self.size(&at, "outer_diameter_m", t.outer_diameter_m)?;
                let wall = self.wall(&at, "wall_thickness_m", t.wall_thickness_m, od / 2.0)?;
                let dist = self.size_or_zero(&at, "radial_offset_m", t.radial_offset_m)?;
                let angle = self.finite(&at, "radial_angle_deg", t.radial_angle_deg)?;
                let own = polar(dist, angle);
                let cluster = match &t.cluster {
                    None => vec![[0.0, 0.0]],
                    Some(v) if v.is_empty() => {
                        return Err(self.invalid(&at, Some("cluster"), Rule::EmptyCluster));
                    }
                    Some(v) => {
                        for (i, o) in v.iter().enumerate() {
                            self.finite(&at, &format!("cluster[{i}][0]"), o[0])?;
                            self.finite(&at, &format!("cluster[{i}][1]"), o[1])?;
                        }
                        v.clone()
                    }
                };
                let half = cluster
                    .iter()
                    .map(|c| norm(add(own, *c)))
                    .fold(0.0, f64::max)
                    + od / 2.0;
                let absolute = add(p.radial_offset_m, own);
                let motor_mount = match &t.motor_mount {
                    Some(m) => {
                        let overhang = self.finite(&at, "motor_mount.overhang_m", m.overhang_m)?;
                        // Each tube of a cluster holds one motor; their thrusts, all
                        // alike and parallel to the axis, turn the rocket unless their
                        // centre is on the axis (within the rounding of a pattern's
                        // trigonometry).
                        let n = cluster.len() as f64;
                        let centre = cluster.iter().fold([0.0, 0.0], |s, c| {
                            let o = add(absolute, *c);
                            [s[0] + o[0] / n, s[1] + o[1] / n]
                        });
                        let off = norm(centre);
                        if off > CLUSTER_CENTRE_TOLERANCE_M {
                            let field = if cluster.len() > 1 {
                                "cluster"
                            } else {
                                "radial_offset_m"
                            };
                            return Err(self.invalid(
                                &at,
                                Some(field),
                                Rule::MotorMountOffAxis {
                                    offset_m: off,
                                    motors: cluster.len(),
                                },
                            ));
                        }
                        if let Some(first) = self.motor_mount {
                            let first = self.components[first.component].id.clone();
                            return Err(self.invalid(
                                &at,
                                Some("motor_mount"),
                                Rule::TwoMotorMounts { first },
                            ));
                        }
                        Some(MotorMountSpec {
                            overhang_m: overhang,
                        })
                    }
                    None => None,
                };
                let tube = InnerTube {
                    outer_diameter_m: od,
                    wall_thickness_m: wall,
                    motor_mount,
                    cluster_offsets_m: cluster.iter().map(|c| add(absolute, *c)).collect(),
                };
                (
                    length,
                    ComponentKind::InnerTube(tube),
                    own,
                    Some(half),
                    t.position,
                )
            }
            RawComponent::CenteringRing(r) => {
                let length = self.size(&at, "length_m", r.length_m)?;
                let od = self.size(&at, "outer_diameter_m", r.outer_diameter_m)?;
                let id = self.size_or_zero(&at, "inner_diameter_m", r.inner_diameter_m)?;
                if id >= od {
                    return Err(self.invalid(
                        &at,
                        Some("inner_diameter_m"),
                        Rule::OutOfRange {
                            got: id,
                            min: 0.0,
                            max: od,
                        },
                    ));
                }
                let ring = Ring {
                    outer_diameter_m: od,
                    inner_diameter_m: id,
                };
                (
                    length,
                    ComponentKind::CenteringRing(ring),
                    [0.0, 0.0],
                    Some(od / 2.0),
                    r.position,
                )
            }
            RawComponent::Bulkhead(b) => {
                let length = self.size(&at, "length_m", b.length_m)?;
                let od = self.size(&at, "outer_diameter_m", b.outer_diameter_m)?;
                let ring = Ring {
                    outer_diameter_m: od,
                    inner_diameter_m: 0.0,
                };
                (
                    length,
                    ComponentKind::Bulkhead(ring),
                    [0.0, 0.0],
                    Some(od / 2.0),
                    b.position,
                )
            }
            RawComponent::MassComponent(m) => {
                let (packed, length, own) = self.packed(
                    &at,
                    m.length_m,
                    m.radius_m,
                    m.radial_offset_m,
                    m.radial_angle_deg,
                    m.inertia_kg_m2,
                )?;
                let half = norm(own) + packed.radius_m;
                (
                    length,
                    ComponentKind::MassComponent(packed),
                    own,
                    Some(half),
                    m.position,
                )
            }
            RawComponent::Parachute(c) => {
                let (packed, length, own) = self.packed(
                    &at,
                    c.length_m,
                    c.radius_m,
                    c.radial_offset_m,
                    c.radial_angle_deg,
                    c.inertia_kg_m2,
                )?;
                let chute = Parachute {
                    packed,
                    canopy_diameter_m: self.size(&at, "canopy_diameter_m", c.canopy_diameter_m)?,
                    cd: self.positive(&at, "cd", c.cd)?,
                    deploy: match &c.deploy {
                        Some(d) => Some(self.deploy(&at, d)?),
                        None => None,
                    },
                };
                let half = norm(own) + packed.radius_m;
                (
                    length,
                    ComponentKind::Parachute(chute),
                    own,
                    Some(half),
                    c.position,
                )
            }
            RawComponent::ShockCord(c) => {
                let (packed, length, own) = self.packed(
                    &at,
                    c.length_m,
                    c.radius_m,
                    c.radial_offset_m,
                    c.radial_angle_deg,
                    c.inertia_kg_m2,
                )?;
                cord = Some((c.linear_density_kg_m, c.cord_length_m));
                let half = norm(own) + packed.radius_m;
                (
                    length,
                    ComponentKind::ShockCord(packed),
                    own,
                    Some(half),
                    c.position,
                )
            }
            RawComponent::NoseCone(_) | RawComponent::BodyTube(_) | RawComponent::Transition(_) => {
                return Err(self.invalid(
                    &at,
                    Some("type"),
                    Rule::BodyInsideComponent {
                        kind: rc.type_name(),
                    },
                ));
            }
        };

        let x_top = self.place(&at, &p, length, position)?;
        // Nothing of a rocket lies ahead of its nose tip: fins, lugs and buttons there would
        // put the center of pressure ahead of the rocket. OpenRocket keeps an internal part
        // placed there (a mass it weighs), so its designs keep one too, with a warning.
        if x_top < -FIT_TOLERANCE_M {
            self.misfit(
                &at,
                Some("position"),
                Rule::AheadOfNoseTip { top_m: x_top },
                !rc.is_external(),
            )?;
        }
        let (parent_top, parent_bottom) = p.holder_extent_m();
        let overlap = (x_top + length).min(parent_bottom) - x_top.max(parent_top);
        if overlap <= 0.0 || overlap.is_nan() {
            self.misfit(
                &at,
                Some("position"),
                Rule::OutsideParent {
                    top_m: x_top,
                    bottom_m: x_top + length,
                    parent_top_m: parent_top,
                    parent_bottom_m: parent_bottom,
                },
                x_top.is_finite(),
            )?;
        }
        if let Some(half) = half_width {
            let inner = inner_radius(&p);
            if half > inner + FIT_TOLERANCE_M / 2.0 {
                self.misfit(
                    &at,
                    None,
                    Rule::WiderThanParent {
                        width_m: 2.0 * half,
                        inner_diameter_m: 2.0 * inner,
                    },
                    true,
                )?;
            }
        }

        // Parts on the outside sit on the parent's surface where they are.
        let mid = x_top + length / 2.0 - p.x_top_m;
        let surface = shapes::body_radius(&p.kind, p.length_m, mid).unwrap_or(0.0);
        let (kind, offset) = match kind {
            ComponentKind::FinSet(mut f) => {
                f.body_radius_m = surface;
                (ComponentKind::FinSet(f), offset)
            }
            ComponentKind::LaunchLug(l) => {
                let o = polar(surface + l.outer_diameter_m / 2.0, l.angle_deg);
                (ComponentKind::LaunchLug(l), o)
            }
            ComponentKind::RailButton(b) => {
                let o = polar(surface + b.height_m / 2.0, b.angle_deg);
                (ComponentKind::RailButton(b), o)
            }
            k => (k, offset),
        };
        let absolute = add(p.radial_offset_m, offset);
        let idx = self.push(
            &at,
            rc,
            Some(parent),
            stage,
            x_top,
            length,
            absolute,
            kind,
            cord,
        )?;

        if let ComponentKind::InnerTube(InnerTube {
            motor_mount: Some(m),
            outer_diameter_m,
            wall_thickness_m,
            cluster_offsets_m,
        }) = &self.components[idx].kind
        {
            let c = &self.components[idx];
            let motor_aft_m =
                self.resolved(&at, "motor_mount.overhang_m", c.x_bottom_m() + m.overhang_m)?;
            self.motor_mount = Some(MotorMount {
                component: idx,
                motors: cluster_offsets_m.len(),
                motor_aft_m,
                inner_diameter_m: outer_diameter_m - 2.0 * wall_thickness_m,
                tube_length_m: c.length_m,
            });
        }

        for (j, child) in rc.children().iter().enumerate() {
            self.child(child, idx, stage, &format!("{path}.children[{j}]"))?;
        }
        Ok(())
    }

    /// A parachute's `deploy`: its trigger (the scenario's, in JSON) and lag.
    fn deploy(&self, at: &Location, d: &RawDeploy) -> Result<Deploy, DesignError> {
        let bad = || {
            self.invalid(
                at,
                Some("deploy.trigger"),
                Rule::DeployTrigger {
                    got: d.trigger.to_string(),
                },
            )
        };
        let trigger = match &d.trigger {
            serde_json::Value::String(s) => DeployTrigger::named(s),
            serde_json::Value::Object(o) if o.len() == 1 => {
                let (key, value) = o.iter().next().ok_or_else(bad)?;
                let x = value.as_f64().ok_or_else(bad)?;
                DeployTrigger::with_number(key, x)
            }
            _ => return Err(bad()),
        }
        .map_err(|_| bad())?;
        let lag_s = match d.lag_s {
            Some(l) => self.non_negative(at, "deploy.lag_s", l)?,
            None => 0.0,
        };
        Ok(Deploy { trigger, lag_s })
    }

    /// A packed cylinder's shape: (shape, length, radial offset relative to the parent).
    fn packed(
        &self,
        at: &Location,
        length_m: f64,
        radius_m: f64,
        offset_m: f64,
        angle_deg: f64,
        inertia: Option<[f64; 2]>,
    ) -> Result<(PackedCylinder, f64, [f64; 2]), DesignError> {
        let length = self.size(at, "length_m", length_m)?;
        let radius = self.size(at, "radius_m", radius_m)?;
        let dist = self.size_or_zero(at, "radial_offset_m", offset_m)?;
        let angle = self.finite(at, "radial_angle_deg", angle_deg)?;
        let inertia_kg_m2 = match inertia {
            None => None,
            Some([axial, transverse]) => {
                let transverse = self.positive(at, "inertia_kg_m2[1]", transverse)?;
                let axial = self.positive(at, "inertia_kg_m2[0]", axial)?;
                // A body of revolution has I_axial <= 2 I_transverse (triangle inequality).
                self.within(at, "inertia_kg_m2[0]", axial, 0.0, 2.0 * transverse)?;
                Some((axial, transverse))
            }
        };
        Ok((
            PackedCylinder {
                radius_m: radius,
                inertia_kg_m2,
            },
            length,
            polar(dist, angle),
        ))
    }

    /// Fore end of a child of `parent`, m aft of the nose tip, from its `position`
    /// (default: fore ends aligned).
    fn place(
        &self,
        at: &Location,
        parent: &Component,
        length: f64,
        position: Option<RawPosition>,
    ) -> Result<f64, DesignError> {
        let pos = position.unwrap_or(RawPosition {
            from: RawFrom::Top,
            offset_m: 0.0,
        });
        let offset = self.finite(at, "position.offset_m", pos.offset_m)?;
        let x = match pos.from {
            RawFrom::Top => parent.x_top_m + offset,
            RawFrom::Middle => parent.x_top_m + (parent.length_m - length) / 2.0 + offset,
            RawFrom::Bottom => parent.x_bottom_m() - length + offset,
            RawFrom::NoseTip => offset,
        };
        self.resolved(at, "position", x)
    }
}
