//! Mass shifts: a part carried inside the airframe that slides along the axis during the
//! flight (`docs/moving-mass.md` states the rules for users).
//!
//! This module owns the [`MassShift`] description, every rule that refuses one (each refusal
//! names the rule it broke), and the grouping of shifts by part that the mass-property kernel
//! reads. The motion itself is the cycloid of [`crate::cycloid`]; the mass properties and
//! their exact rates are [`crate::massprops`]; the extra moment term `ω × h + h′` is in
//! [`crate::eom`]. The flight driver starts each shift when its trigger fires, records an
//! `EventKind::Shift` event, and cuts the move into 16 equal parts by stop times.

use crate::trigger::Trigger;
use hpr_design::design::model::{ComponentIdx, ComponentKind, Design};
use std::fmt;

/// Shortest move allowed, s: its peak acceleration is already 63 km/s² per metre of travel.
pub const MIN_DURATION_S: f64 = 0.01;
/// Each move is cut into this many equal parts by stop times, so a fixed-step integrator
/// takes at least this many steps across it.
pub const STOPS_PER_SHIFT: usize = 16;

/// A part that slides along the axis: what moves, how far, how long, and when it starts.
#[derive(Debug, Clone, PartialEq)]
pub struct MassShift {
    pub trigger: Trigger,
    /// Id of the internal component that moves; everything inside it moves too.
    pub component: String,
    /// How far along the axis, m: positive toward the tail, negative toward the nose.
    pub travel_m: f64,
    /// How long the move takes, s (at least [`MIN_DURATION_S`]).
    pub duration_s: f64,
}

impl MassShift {
    pub fn new(
        trigger: Trigger,
        component: impl Into<String>,
        travel_m: f64,
        duration_s: f64,
    ) -> MassShift {
        MassShift {
            trigger,
            component: component.into(),
            travel_m,
            duration_s,
        }
    }
}

/// Why a shift was refused. Each variant is one rule of `docs/moving-mass.md` ("What is refused,
/// and why").
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ShiftRefusal {
    #[error("shift {index} ({component}): duration_s must be at least 0.01 s, a shorter move is closer to an impact than a motion (got {duration_s} s)")]
    TooShort {
        index: usize,
        component: String,
        duration_s: f64,
    },
    #[error("shift {index} ({component}): travel_m and duration_s must be finite numbers (got travel {travel_m} m, duration {duration_s} s)")]
    NotFinite {
        index: usize,
        component: String,
        travel_m: f64,
        duration_s: f64,
    },
    #[error("shift {index}: the design has no component with id \"{component}\"")]
    UnknownComponent { index: usize, component: String },
    #[error("shift {index} ({component}): a body component (nose cone, body tube, transition) can't move; only internal parts can")]
    BodyComponent { index: usize, component: String },
    #[error("shift {index} ({component}): a part on the outside of the airframe ({kind}) can't move; only internal parts can")]
    ExternalPart {
        index: usize,
        component: String,
        kind: &'static str,
    },
    #[error("shift {index} ({component}): the part holds the motor (in \"{mount}\"), and the motor would not go with it")]
    HoldsMotor {
        index: usize,
        component: String,
        mount: String,
    },
    #[error("shift {index} ({component}): the part is inside \"{mover}\", which another shift moves; a part inside a part that moves can't move")]
    InsideMovingPart {
        index: usize,
        component: String,
        mover: String,
    },
    #[error("shift {index} ({component}): the part is one tube of a cluster of {tubes}, which can't move")]
    ClusterTube {
        index: usize,
        component: String,
        tubes: usize,
    },
    #[error("shift {index} ({component}): the part is covered by the mass override of its stage \"{stage}\", which doesn't say how much of that mass is the part's")]
    StageOverride {
        index: usize,
        component: String,
        stage: String,
    },
    #[error("shift {index} ({component}): the part is covered by the mass override of \"{holder}\", which covers what it holds and doesn't say how much of that mass is the part's")]
    ComponentOverride {
        index: usize,
        component: String,
        holder: String,
    },
    #[error("shifts of \"{component}\" add up to {total_m:.4} m toward the {direction}, which would take it out of \"{holder}\" (at most {limit_m:.4} m that way)")]
    OutOfHolder {
        component: String,
        direction: &'static str,
        total_m: f64,
        limit_m: f64,
        holder: String,
    },
    #[error("shift {index} ({component}): trigger {trigger}: {rule}")]
    Trigger {
        index: usize,
        component: String,
        trigger: String,
        rule: String,
    },
}

impl ShiftRefusal {
    /// The shift refused and the field of it at fault (`component`, `travel_m`, `duration_s`
    /// or `trigger`), so that an input file can name its own key; `None` for a refusal of
    /// several shifts together (their travels adding up past the holder).
    pub fn field(&self) -> Option<(usize, &'static str)> {
        use ShiftRefusal::*;
        match self {
            TooShort { index, .. } => Some((*index, "duration_s")),
            NotFinite {
                index, travel_m, ..
            } if travel_m.is_finite() => Some((*index, "duration_s")),
            NotFinite { index, .. } => Some((*index, "travel_m")),
            UnknownComponent { index, .. }
            | BodyComponent { index, .. }
            | ExternalPart { index, .. }
            | HoldsMotor { index, .. }
            | InsideMovingPart { index, .. }
            | ClusterTube { index, .. }
            | StageOverride { index, .. }
            | ComponentOverride { index, .. } => Some((*index, "component")),
            Trigger { index, .. } => Some((*index, "trigger")),
            OutOfHolder { .. } => None,
        }
    }
}

/// The parts that move, each with the shifts that move it, ready for the flight.
#[derive(Debug, Clone, PartialEq)]
pub struct ShiftPlan {
    /// Component index of each moving part, in order of first appearance.
    pub parts: Vec<ComponentIdx>,
    /// For each shift (in the order given), the index into `parts` it moves.
    pub part_of_shift: Vec<usize>,
}

pub(crate) fn ancestors(
    design: &Design,
    idx: ComponentIdx,
) -> impl Iterator<Item = ComponentIdx> + '_ {
    std::iter::successors(design.components[idx].parent, move |&p| {
        design.components[p].parent
    })
}

pub(crate) fn subtree_contains(design: &Design, root: ComponentIdx, target: ComponentIdx) -> bool {
    target == root || ancestors(design, target).any(|a| a == root)
}

/// Why a component can be neither moved by a shift nor dropped by a release: the rules on
/// the part itself that the two share (each names them in its own refusal).
pub(crate) enum PartProblem {
    /// No component has this id.
    Unknown,
    /// A body component (nose, tube, transition) is the airframe.
    Body,
    /// An external part (fins, lugs...), of this kind, is outside the airframe.
    External(&'static str),
    /// The part holds the motor mount, whose id this is.
    HoldsMotor(String),
    /// A clustered inner tube of this many tubes.
    Cluster(usize),
    /// The part's stage, whose id this is, overrides its mass or center.
    StageOverride(String),
    /// A component around the part, whose id this is, overrides its children's mass or center.
    ComponentOverride(String),
}

/// The index of the component `id` if it is an inner part that may move or leave the
/// rocket, else the rule it breaks.
pub(crate) fn inner_part(design: &Design, id: &str) -> Result<ComponentIdx, PartProblem> {
    let idx = design
        .components
        .iter()
        .position(|c| c.id == id)
        .ok_or(PartProblem::Unknown)?;
    let c = &design.components[idx];
    if c.is_body() {
        return Err(PartProblem::Body);
    }
    if c.is_external() {
        return Err(PartProblem::External(c.kind.type_name()));
    }
    if let Some(mount) = &design.motor_mount {
        if subtree_contains(design, idx, mount.component) {
            return Err(PartProblem::HoldsMotor(
                design.components[mount.component].id.clone(),
            ));
        }
    }
    if let ComponentKind::InnerTube(t) = &c.kind {
        if t.cluster_offsets_m.len() > 1 {
            return Err(PartProblem::Cluster(t.cluster_offsets_m.len()));
        }
    }
    let stage = &design.stages[c.stage];
    if stage.overrides.any() {
        return Err(PartProblem::StageOverride(stage.id.clone()));
    }
    if let Some(h) = ancestors(design, idx).find(|&a| {
        let o = &design.components[a].overrides;
        o.any() && o.covers_children
    }) {
        return Err(PartProblem::ComponentOverride(
            design.components[h].id.clone(),
        ));
    }
    Ok(idx)
}

/// Check every rule that can be checked before the flight and group the shifts by part.
/// `motor_delay_s` is the motor's first ejection delay (None for a plugged motor).
pub fn plan(
    design: &Design,
    shifts: &[MassShift],
    motor_delay_s: Option<f64>,
) -> Result<ShiftPlan, ShiftRefusal> {
    let mut parts: Vec<ComponentIdx> = Vec::new();
    let mut part_of_shift = Vec::with_capacity(shifts.len());
    for (index, s) in shifts.iter().enumerate() {
        let component = s.component.clone();
        if !s.travel_m.is_finite() || !s.duration_s.is_finite() {
            return Err(ShiftRefusal::NotFinite {
                index,
                component,
                travel_m: s.travel_m,
                duration_s: s.duration_s,
            });
        }
        if s.duration_s < MIN_DURATION_S {
            return Err(ShiftRefusal::TooShort {
                index,
                component,
                duration_s: s.duration_s,
            });
        }
        check_trigger(index, s, motor_delay_s)?;
        let idx = inner_part(design, &s.component).map_err(|p| {
            let component = component.clone();
            match p {
                PartProblem::Unknown => ShiftRefusal::UnknownComponent { index, component },
                PartProblem::Body => ShiftRefusal::BodyComponent { index, component },
                PartProblem::External(kind) => ShiftRefusal::ExternalPart {
                    index,
                    component,
                    kind,
                },
                PartProblem::HoldsMotor(mount) => ShiftRefusal::HoldsMotor {
                    index,
                    component,
                    mount,
                },
                PartProblem::Cluster(tubes) => ShiftRefusal::ClusterTube {
                    index,
                    component,
                    tubes,
                },
                PartProblem::StageOverride(stage) => ShiftRefusal::StageOverride {
                    index,
                    component,
                    stage,
                },
                PartProblem::ComponentOverride(holder) => ShiftRefusal::ComponentOverride {
                    index,
                    component,
                    holder,
                },
            }
        })?;
        let k = match parts.iter().position(|&p| p == idx) {
            Some(k) => k,
            None => {
                parts.push(idx);
                parts.len() - 1
            }
        };
        part_of_shift.push(k);
    }
    // A part inside another part that moves.
    for (index, s) in shifts.iter().enumerate() {
        let idx = parts[part_of_shift[index]];
        if let Some(&mover) = parts
            .iter()
            .find(|&&p| p != idx && subtree_contains(design, p, idx))
        {
            return Err(ShiftRefusal::InsideMovingPart {
                index,
                component: s.component.clone(),
                mover: design.components[mover].id.clone(),
            });
        }
    }
    // Totals toward the nose and toward the tail, each against the holder.
    for (k, &idx) in parts.iter().enumerate() {
        let (aft, fore): (f64, f64) = shifts
            .iter()
            .zip(&part_of_shift)
            .filter(|(_, &p)| p == k)
            .fold((0.0, 0.0), |(a, f), (s, _)| {
                if s.travel_m > 0.0 {
                    (a + s.travel_m, f)
                } else {
                    (a, f - s.travel_m)
                }
            });
        let c = &design.components[idx];
        let holder = c
            .parent
            .expect("internal parts always have a parent (validated design)");
        let (h_top, h_bottom) = design.components[holder].holder_extent_m();
        // A part already reaching outside its holder may go as far as it already reaches.
        let aft_limit = h_bottom.max(c.x_bottom_m()) - c.x_bottom_m();
        let fore_limit = c.x_top_m - h_top.min(c.x_top_m);
        let holder_id = design.components[holder].id.clone();
        // A relative tolerance of 1e-12 m forgives rounding in positions computed by sums.
        if aft > aft_limit + 1e-12 {
            return Err(ShiftRefusal::OutOfHolder {
                component: c.id.clone(),
                direction: "tail",
                total_m: aft,
                limit_m: aft_limit,
                holder: holder_id,
            });
        }
        if fore > fore_limit + 1e-12 {
            return Err(ShiftRefusal::OutOfHolder {
                component: c.id.clone(),
                direction: "nose",
                total_m: fore,
                limit_m: fore_limit,
                holder: holder_id,
            });
        }
    }
    Ok(ShiftPlan {
        parts,
        part_of_shift,
    })
}

fn check_trigger(
    index: usize,
    s: &MassShift,
    motor_delay_s: Option<f64>,
) -> Result<(), ShiftRefusal> {
    let refuse = |rule: &str| ShiftRefusal::Trigger {
        index,
        component: s.component.clone(),
        trigger: s.trigger.to_string(),
        rule: rule.to_string(),
    };
    if let Err(e) = s.trigger.validate() {
        return Err(refuse(&e.to_string()));
    }
    match s.trigger {
        Trigger::Time { time_s } if time_s <= 0.0 => {
            Err(refuse("a shift can't start before the rocket leaves the rail, and at launch it is still on the pad; time it from the burnout or the apogee instead"))
        }
        Trigger::HeightDescending { height_m } if height_m <= 0.0 => {
            Err(refuse("a height on the way down must be above the ground, or the shift would never start"))
        }
        Trigger::BurnoutPlusDelay { delay_s: None } if motor_delay_s.is_none() => {
            Err(refuse("the motor is plugged (it has no ejection delay), so burnout plus its delay never comes; give the delay in seconds"))
        }
        _ => Ok(()),
    }
}

impl fmt::Display for MassShift {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "\"{}\" {:+} m over {} s at {}",
            self.component, self.travel_m, self.duration_s, self.trigger
        )
    }
}

#[cfg(test)]
mod refusals;
#[cfg(test)]
mod tests;
