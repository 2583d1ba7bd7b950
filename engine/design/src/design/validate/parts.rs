//! Parts inside or on a body component: fins, lugs, rail buttons (outside), inner tubes,
//! rings, bulkheads, masses, parachutes and shock cords (inside). A child is built in four
//! steps (`Builder::child`): its own fields checked by kind (`shaped`; a fin set's in
//! `fins.rs`), placed along its parent by its `position` (`place`), checked against its
//! parent's axial extent and inner radius (`check_fit`), set on the parent's surface if it is
//! outside (`on_surface`); then a motor mount is noted and its own children follow.

use super::{Builder, CLUSTER_CENTRE_TOLERANCE_M, FIT_TOLERANCE_M};
use crate::design::model::*;
use crate::design::raw::*;
use crate::design::shapes;
use crate::error::{DesignError, Location, Rule};

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

/// A child's own fields checked, before it is placed along its parent.
struct Shaped {
    /// Its length along the axis, m (a fin set's root chord, a rail button's diameter).
    length_m: f64,
    kind: ComponentKind,
    /// Its axis's radial offset from its parent's, (y, z) m (an outside part's is set once
    /// it is placed, on the parent's surface).
    offset_m: [f64; 2],
    /// For a part inside its parent, the radius about the parent's axis it needs, m.
    half_width_m: Option<f64>,
    position: Option<RawPosition>,
    /// A shock cord's linear density and cord length, for its mass.
    cord: Option<(Option<f64>, Option<f64>)>,
}

impl Shaped {
    /// A part on the outside of its parent.
    fn outside(length_m: f64, kind: ComponentKind, position: Option<RawPosition>) -> Shaped {
        Shaped {
            length_m,
            kind,
            offset_m: [0.0, 0.0],
            half_width_m: None,
            position,
            cord: None,
        }
    }

    /// A part inside its parent, `offset_m` off its axis, `half_width_m` wide about it.
    fn inside(
        length_m: f64,
        kind: ComponentKind,
        offset_m: [f64; 2],
        half_width_m: f64,
        position: Option<RawPosition>,
    ) -> Shaped {
        Shaped {
            length_m,
            kind,
            offset_m,
            half_width_m: Some(half_width_m),
            position,
            cord: None,
        }
    }
}

/// Where a part on the outside of `p` sits once placed at `x_top`: on the parent's surface
/// at its middle (a fin set's root there, a lug's or a rail button's axis off it by half its
/// diameter or height). Other parts keep their kind and offset. (kind, offset from the
/// parent's axis.)
fn on_surface(
    kind: ComponentKind,
    offset: [f64; 2],
    p: &Component,
    x_top: f64,
    length: f64,
) -> (ComponentKind, [f64; 2]) {
    let mid = x_top + length / 2.0 - p.x_top_m;
    let surface = shapes::body_radius(&p.kind, p.length_m, mid).unwrap_or(0.0);
    match kind {
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
        let Shaped {
            length_m: length,
            kind,
            offset_m,
            half_width_m,
            position,
            cord,
        } = self.shaped(&at, rc, &p)?;
        let x_top = self.place(&at, &p, length, position)?;
        self.check_fit(&at, rc, &p, x_top, length, half_width_m)?;
        let (kind, offset) = on_surface(kind, offset_m, &p, x_top, length);
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
        self.note_motor_mount(&at, idx)?;
        for (j, child) in rc.children().iter().enumerate() {
            self.child(child, idx, stage, &format!("{path}.children[{j}]"))?;
        }
        Ok(())
    }

    /// A child's own fields checked, by its kind (`p` its parent); a body component is not a
    /// child.
    fn shaped(
        &self,
        at: &Location,
        rc: &RawComponent,
        p: &Component,
    ) -> Result<Shaped, DesignError> {
        Ok(match rc {
            RawComponent::FinSet(f) => {
                let fins = self.fin_set(at, f)?;
                Shaped::outside(fins.root_chord_m, ComponentKind::FinSet(fins), f.position)
            }
            RawComponent::LaunchLug(l) => {
                let length = self.size(at, "length_m", l.length_m)?;
                let od = self.size(at, "outer_diameter_m", l.outer_diameter_m)?;
                let wall = self.wall(at, "wall_thickness_m", l.wall_thickness_m, od / 2.0)?;
                let angle = self.finite(at, "angle_deg", l.angle_deg)?;
                let lug = LaunchLug {
                    outer_diameter_m: od,
                    wall_thickness_m: wall,
                    angle_deg: angle,
                };
                Shaped::outside(length, ComponentKind::LaunchLug(lug), l.position)
            }
            RawComponent::RailButton(b) => {
                let od = self.size(at, "outer_diameter_m", b.outer_diameter_m)?;
                let height = self.size(at, "height_m", b.height_m)?;
                let angle = self.finite(at, "angle_deg", b.angle_deg)?;
                let button = RailButton {
                    outer_diameter_m: od,
                    height_m: height,
                    angle_deg: angle,
                };
                Shaped::outside(od, ComponentKind::RailButton(button), b.position)
            }
            RawComponent::InnerTube(t) => self.inner_tube(at, t, p)?,
            RawComponent::CenteringRing(r) => {
                let length = self.size(at, "length_m", r.length_m)?;
                let od = self.size(at, "outer_diameter_m", r.outer_diameter_m)?;
                let id = self.size_or_zero(at, "inner_diameter_m", r.inner_diameter_m)?;
                if id >= od {
                    return Err(self.invalid(
                        at,
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
                let kind = ComponentKind::CenteringRing(ring);
                Shaped::inside(length, kind, [0.0, 0.0], od / 2.0, r.position)
            }
            RawComponent::Bulkhead(b) => {
                let length = self.size(at, "length_m", b.length_m)?;
                let od = self.size(at, "outer_diameter_m", b.outer_diameter_m)?;
                let ring = Ring {
                    outer_diameter_m: od,
                    inner_diameter_m: 0.0,
                };
                let kind = ComponentKind::Bulkhead(ring);
                Shaped::inside(length, kind, [0.0, 0.0], od / 2.0, b.position)
            }
            RawComponent::MassComponent(m) => {
                let (packed, length, own) = self.packed(
                    at,
                    m.length_m,
                    m.radius_m,
                    m.radial_offset_m,
                    m.radial_angle_deg,
                    m.inertia_kg_m2,
                )?;
                let half = norm(own) + packed.radius_m;
                let kind = ComponentKind::MassComponent(packed);
                Shaped::inside(length, kind, own, half, m.position)
            }
            RawComponent::Parachute(c) => {
                let (packed, length, own) = self.packed(
                    at,
                    c.length_m,
                    c.radius_m,
                    c.radial_offset_m,
                    c.radial_angle_deg,
                    c.inertia_kg_m2,
                )?;
                let chute = Parachute {
                    packed,
                    canopy_diameter_m: self.size(at, "canopy_diameter_m", c.canopy_diameter_m)?,
                    cd: self.positive(at, "cd", c.cd)?,
                    deploy: match &c.deploy {
                        Some(d) => Some(self.deploy(at, d)?),
                        None => None,
                    },
                };
                let half = norm(own) + packed.radius_m;
                let kind = ComponentKind::Parachute(chute);
                Shaped::inside(length, kind, own, half, c.position)
            }
            RawComponent::ShockCord(c) => {
                let (packed, length, own) = self.packed(
                    at,
                    c.length_m,
                    c.radius_m,
                    c.radial_offset_m,
                    c.radial_angle_deg,
                    c.inertia_kg_m2,
                )?;
                let half = norm(own) + packed.radius_m;
                let kind = ComponentKind::ShockCord(packed);
                Shaped {
                    cord: Some((c.linear_density_kg_m, c.cord_length_m)),
                    ..Shaped::inside(length, kind, own, half, c.position)
                }
            }
            RawComponent::NoseCone(_) | RawComponent::BodyTube(_) | RawComponent::Transition(_) => {
                return Err(self.invalid(
                    at,
                    Some("type"),
                    Rule::BodyInsideComponent {
                        kind: rc.type_name(),
                    },
                ));
            }
        })
    }

    /// An inner tube: its walls, its own offset and a cluster's, and, as a motor mount, its
    /// motors' centre on the axis and no second mount in the design (`p` its parent).
    fn inner_tube(
        &self,
        at: &Location,
        t: &RawInnerTube,
        p: &Component,
    ) -> Result<Shaped, DesignError> {
        let length = self.size(at, "length_m", t.length_m)?;
        let od = self.size(at, "outer_diameter_m", t.outer_diameter_m)?;
        let wall = self.wall(at, "wall_thickness_m", t.wall_thickness_m, od / 2.0)?;
        let dist = self.size_or_zero(at, "radial_offset_m", t.radial_offset_m)?;
        let angle = self.finite(at, "radial_angle_deg", t.radial_angle_deg)?;
        let own = polar(dist, angle);
        let cluster = match &t.cluster {
            None => vec![[0.0, 0.0]],
            Some(v) if v.is_empty() => {
                return Err(self.invalid(at, Some("cluster"), Rule::EmptyCluster));
            }
            Some(v) => {
                for (i, o) in v.iter().enumerate() {
                    self.finite(at, &format!("cluster[{i}][0]"), o[0])?;
                    self.finite(at, &format!("cluster[{i}][1]"), o[1])?;
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
            Some(m) => Some(self.motor_mount_spec(at, m, &cluster, absolute)?),
            None => None,
        };
        let tube = InnerTube {
            outer_diameter_m: od,
            wall_thickness_m: wall,
            motor_mount,
            cluster_offsets_m: cluster.iter().map(|c| add(absolute, *c)).collect(),
        };
        Ok(Shaped::inside(
            length,
            ComponentKind::InnerTube(tube),
            own,
            half,
            t.position,
        ))
    }

    /// An inner tube's `motor_mount`: its overhang, its tubes' centre on the rocket's axis
    /// (`absolute` the tube's own offset from the axis, `cluster` each tube's from it), and
    /// no mount before it in the design.
    fn motor_mount_spec(
        &self,
        at: &Location,
        m: &RawMotorMount,
        cluster: &[[f64; 2]],
        absolute: [f64; 2],
    ) -> Result<MotorMountSpec, DesignError> {
        let overhang = self.finite(at, "motor_mount.overhang_m", m.overhang_m)?;
        // Each tube of a cluster holds one motor; their thrusts, all alike and parallel to
        // the axis, turn the rocket unless their centre is on the axis (within the rounding of
        // a pattern's trigonometry).
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
                at,
                Some(field),
                Rule::MotorMountOffAxis {
                    offset_m: off,
                    motors: cluster.len(),
                },
            ));
        }
        if let Some(first) = self.motor_mount {
            let first = self.components[first.component].id.clone();
            return Err(self.invalid(at, Some("motor_mount"), Rule::TwoMotorMounts { first }));
        }
        Ok(MotorMountSpec {
            overhang_m: overhang,
        })
    }

    /// Where a child placed at `x_top` sits against its parent `p`: not ahead of the nose
    /// tip, overlapping the parent's extent, and (`half_width`, inside parts) within its
    /// inner radius. Each is an error, or under OpenRocket's geometry checks a warning.
    fn check_fit(
        &mut self,
        at: &Location,
        rc: &RawComponent,
        p: &Component,
        x_top: f64,
        length: f64,
        half_width: Option<f64>,
    ) -> Result<(), DesignError> {
        // Nothing of a rocket lies ahead of its nose tip: fins, lugs and buttons there would
        // put the center of pressure ahead of the rocket. OpenRocket keeps an internal part
        // placed there (a mass it weighs), so its designs keep one too, with a warning.
        if x_top < -FIT_TOLERANCE_M {
            self.misfit(
                at,
                Some("position"),
                Rule::AheadOfNoseTip { top_m: x_top },
                !rc.is_external(),
            )?;
        }
        let (parent_top, parent_bottom) = p.holder_extent_m();
        let overlap = (x_top + length).min(parent_bottom) - x_top.max(parent_top);
        if overlap <= 0.0 || overlap.is_nan() {
            self.misfit(
                at,
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
            let inner = inner_radius(p);
            if half > inner + FIT_TOLERANCE_M / 2.0 {
                self.misfit(
                    at,
                    None,
                    Rule::WiderThanParent {
                        width_m: 2.0 * half,
                        inner_diameter_m: 2.0 * inner,
                    },
                    true,
                )?;
            }
        }
        Ok(())
    }

    /// Records the design's motor mount if component `idx`, just added, is one: where its
    /// motors' aft ends are and what it holds.
    fn note_motor_mount(&mut self, at: &Location, idx: ComponentIdx) -> Result<(), DesignError> {
        if let ComponentKind::InnerTube(InnerTube {
            motor_mount: Some(m),
            outer_diameter_m,
            wall_thickness_m,
            cluster_offsets_m,
        }) = &self.components[idx].kind
        {
            let c = &self.components[idx];
            let motor_aft_m =
                self.resolved(at, "motor_mount.overhang_m", c.x_bottom_m() + m.overhang_m)?;
            self.motor_mount = Some(MotorMount {
                component: idx,
                motors: cluster_offsets_m.len(),
                motor_aft_m,
                inner_diameter_m: outer_diameter_m - 2.0 * wall_thickness_m,
                tube_length_m: c.length_m,
            });
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
