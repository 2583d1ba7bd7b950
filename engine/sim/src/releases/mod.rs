//! Released mass: a part carried inside the airframe that leaves the rocket in flight (ballast
//! dropped to trim an apogee, a payload ejected at apogee or at a height) and then flies to
//! the ground on its own.
//!
//! This module owns the [`Release`] description (which part, what releases it, the part's own
//! drag or parachute), every rule that refuses one before the flight (each refusal names the
//! rule it broke, [`ReleaseRefusal`]), and the estimate of a tumbling part's drag area. What a
//! release does to the rocket is in [`crate::massprops`] (the part's mass, first moment and
//! inertia about the nose tip taken out of the rocket's at once: the parallel-axis theorem);
//! the flight driver fires each release when its trigger fires, records an
//! `EventKind::Release` event with the static margin just before and just after, and flies
//! the part's own descent, a point mass under its drag or its parachute, once the rocket's
//! flight is over (the two never meet again, so the order changes no number).
//!
//! **No impulse.** At the release every bit of material keeps the velocity it had: the
//! airframe's state (its nose tip's velocity, its attitude and its rate of turn) is unchanged,
//! and the part's center leaves with `v_O + R (ω × ρ)`, `ρ` its center in body axes. The sum of
//! the two bodies' linear and angular momenta is the whole's, exactly.

use crate::eom::CanopyShape;
use crate::shifts::{inner_part, subtree_contains, PartProblem, ShiftPlan};
use crate::trigger::Trigger;
use hpr_design::design::model::{ComponentIdx, ComponentKind, Design};
use hpr_design::mass;
use std::fmt;

/// The drag coefficient of a tumbling body on its planform area (length times diameter):
/// OpenRocket's figure for a tumbling body tube (its technical documentation, "drag of a
/// tumbling body", section 3.5, `BasicTumbleStepper`'s `cDBt`). A released part given no drag
/// area of its own tumbles with `0.56 × length × diameter` of its component.
pub const TUMBLE_CD: f64 = 0.56;

/// What opens a released part's own parachute.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PartTrigger {
    /// At the release itself (the canopy opens its lag after the part leaves).
    Release,
    /// At the part's own apogee: at once for a part released on the way down.
    Apogee,
    /// When the part descends through `height_m` above the ground.
    HeightDescending { height_m: f64 },
}

impl fmt::Display for PartTrigger {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PartTrigger::Release => write!(f, "the release"),
            PartTrigger::Apogee => write!(f, "the part's apogee"),
            PartTrigger::HeightDescending { height_m } => {
                write!(f, "{height_m} m on the part's way down")
            }
        }
    }
}

/// A released part's own parachute: its drag area, what opens it, how long it takes to open
/// and the shape of its open canopy (which sets the air it carries along, as a rocket's
/// canopy does).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartChute {
    /// Drag coefficient times reference area of the open canopy, m².
    pub cds_m2: f64,
    pub trigger: PartTrigger,
    /// Time from the trigger to the open canopy, s.
    pub lag_s: f64,
    pub canopy: CanopyShape,
}

impl PartChute {
    /// A canopy of RocketPy's default shape sized from its CdS.
    pub fn new(cds_m2: f64, trigger: PartTrigger, lag_s: f64) -> PartChute {
        PartChute {
            cds_m2,
            trigger,
            lag_s,
            canopy: CanopyShape::default(),
        }
    }
}

/// A part that leaves the rocket: which, when, and how it falls.
#[derive(Debug, Clone, PartialEq)]
pub struct Release {
    pub trigger: Trigger,
    /// Id of the internal component that leaves; everything inside it goes with it.
    pub component: String,
    /// The part's drag area falling free (and before its parachute opens), m²; `None`: its
    /// component's `released_cda_m2` in the design, or else the tumbling estimate
    /// [`TUMBLE_CD`] × the component's length × its diameter.
    pub cda_m2: Option<f64>,
    /// Its own parachute, if it has one.
    pub parachute: Option<PartChute>,
}

impl Release {
    /// `component` leaving at `trigger`, tumbling with the estimated drag area.
    pub fn new(trigger: Trigger, component: impl Into<String>) -> Release {
        Release {
            trigger,
            component: component.into(),
            cda_m2: None,
            parachute: None,
        }
    }

    /// The same release with the part's drag area `cda_m2`, m².
    pub fn with_cda(mut self, cda_m2: f64) -> Release {
        self.cda_m2 = Some(cda_m2);
        self
    }

    /// The same release with the part's own parachute.
    pub fn with_parachute(mut self, chute: PartChute) -> Release {
        self.parachute = Some(chute);
        self
    }
}

impl fmt::Display for Release {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{}\" released at {}", self.component, self.trigger)
    }
}

/// Why a release was refused. Each variant is one rule.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReleaseRefusal {
    #[error("release {index}: the design has no component with id \"{component}\"")]
    UnknownComponent { index: usize, component: String },
    #[error("release {index} ({component}): a body component (nose cone, body tube, transition) can't leave the rocket this way; only internal parts can")]
    BodyComponent { index: usize, component: String },
    #[error("release {index} ({component}): a part on the outside of the airframe ({kind}) can't be released; only internal parts can")]
    ExternalPart {
        index: usize,
        component: String,
        kind: &'static str,
    },
    #[error("release {index} ({component}): the part holds the motor (in \"{mount}\"), which would leave with it")]
    HoldsMotor {
        index: usize,
        component: String,
        mount: String,
    },
    #[error("release {index} ({component}): the part is one tube of a cluster of {tubes}, which can't come apart")]
    ClusterTube {
        index: usize,
        component: String,
        tubes: usize,
    },
    #[error("release {index} ({component}): the part is covered by the mass override of its stage \"{stage}\", which doesn't say how much of that mass is the part's")]
    StageOverride {
        index: usize,
        component: String,
        stage: String,
    },
    #[error("release {index} ({component}): the part is covered by the mass override of \"{holder}\", which covers what it holds and doesn't say how much of that mass is the part's")]
    ComponentOverride {
        index: usize,
        component: String,
        holder: String,
    },
    #[error("release {index} ({component}): the part is inside \"{mover}\", which a shift moves; a part inside a part that moves can't leave on its own")]
    InsideMovingPart {
        index: usize,
        component: String,
        mover: String,
    },
    #[error("release {index} ({component}): the part holds \"{moving}\", which a shift moves inside it; release the part that moves, or move the part that leaves")]
    HoldsMovingPart {
        index: usize,
        component: String,
        moving: String,
    },
    #[error("release {index} ({component}): the part is inside \"{holder}\", which release {other} drops; it leaves with its holder")]
    InsideReleasedPart {
        index: usize,
        component: String,
        holder: String,
        other: usize,
    },
    #[error("release {index} ({component}): release {other} already drops this part; a part leaves once")]
    ReleasedTwice {
        index: usize,
        component: String,
        other: usize,
    },
    #[error("release {index} ({component}): the part weighs {mass_kg} kg; a part that leaves must have a mass to fly")]
    Massless {
        index: usize,
        component: String,
        mass_kg: f64,
    },
    #[error("release {index} ({component}): field \"{field}\" {rule} (got {value})")]
    Number {
        index: usize,
        component: String,
        field: &'static str,
        rule: &'static str,
        value: f64,
    },
    #[error("release {index} ({component}): trigger {trigger}: {rule}")]
    Trigger {
        index: usize,
        component: String,
        trigger: String,
        rule: String,
    },
}

impl ReleaseRefusal {
    /// The release refused and the field of it at fault (`component`, `trigger`, `cda_m2`,
    /// `parachute.cds_m2`, `parachute.lag_s`, `parachute.height_m`), so that an input file can
    /// name its own key.
    pub fn field(&self) -> (usize, &'static str) {
        use ReleaseRefusal::*;
        match self {
            UnknownComponent { index, .. }
            | BodyComponent { index, .. }
            | ExternalPart { index, .. }
            | HoldsMotor { index, .. }
            | ClusterTube { index, .. }
            | StageOverride { index, .. }
            | ComponentOverride { index, .. }
            | InsideMovingPart { index, .. }
            | HoldsMovingPart { index, .. }
            | InsideReleasedPart { index, .. }
            | ReleasedTwice { index, .. }
            | Massless { index, .. } => (*index, "component"),
            Number { index, field, .. } => (*index, field),
            Trigger { index, .. } => (*index, "trigger"),
        }
    }
}

/// The parts that leave, ready for the flight.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReleasePlan {
    /// Component index of each release's part, in the order given.
    pub parts: Vec<ComponentIdx>,
    /// For each release, the index of its part among the parts shifts move
    /// ([`ShiftPlan::parts`]), if shifts move it too.
    pub moving_part: Vec<Option<usize>>,
    /// Each release's drag area falling free, m² (the release's, the design's, or the
    /// estimate: [`release_cda_m2`]).
    pub cda_m2: Vec<f64>,
}

/// The tumbling estimate of a component's drag area, m²: [`TUMBLE_CD`] × its length × its
/// outer diameter (for a part that holds others, its own envelope); NaN for a body component
/// or an external part, which no release may drop.
pub fn tumbling_cda_m2(design: &Design, idx: ComponentIdx) -> f64 {
    let c = &design.components[idx];
    let diameter = match &c.kind {
        ComponentKind::MassComponent(p) | ComponentKind::ShockCord(p) => 2.0 * p.radius_m,
        ComponentKind::Parachute(p) => 2.0 * p.packed.radius_m,
        ComponentKind::InnerTube(t) => t.outer_diameter_m,
        ComponentKind::CenteringRing(r) | ComponentKind::Bulkhead(r) => r.outer_diameter_m,
        // Body and external parts are refused before a flight asks; they have no estimate.
        _ => f64::NAN,
    };
    TUMBLE_CD * c.length_m * diameter
}

/// The drag area a release of component `idx` flies with, m²: `given` (the release's own),
/// else the design's `released_cda_m2` for the component, else the tumbling estimate.
pub fn release_cda_m2(design: &Design, idx: ComponentIdx, given: Option<f64>) -> f64 {
    given
        .or(design.components[idx].released_cda_m2)
        .unwrap_or_else(|| tumbling_cda_m2(design, idx))
}

/// Check every rule that can be checked before the flight. `shift_plan` holds the parts the
/// flight's shifts move (checked already); `motor_delay_s` is the motor's first ejection
/// delay (None for a plugged motor).
pub fn plan(
    design: &Design,
    releases: &[Release],
    shift_plan: &ShiftPlan,
    motor_delay_s: Option<f64>,
) -> Result<ReleasePlan, ReleaseRefusal> {
    let mut out = ReleasePlan::default();
    for (index, r) in releases.iter().enumerate() {
        let component = r.component.clone();
        let number = |field: &'static str, rule: &'static str, value: f64| {
            Err(ReleaseRefusal::Number {
                index,
                component: component.clone(),
                field,
                rule,
                value,
            })
        };
        if let Some(cda) = r.cda_m2 {
            if !(cda.is_finite() && cda > 0.0) {
                return number("cda_m2", "must be positive and finite", cda);
            }
        }
        if let Some(p) = &r.parachute {
            if !(p.cds_m2.is_finite() && p.cds_m2 > 0.0) {
                return number("parachute.cds_m2", "must be positive and finite", p.cds_m2);
            }
            if !(p.lag_s.is_finite() && p.lag_s >= 0.0) {
                return number(
                    "parachute.lag_s",
                    "must be finite and not negative",
                    p.lag_s,
                );
            }
            if let PartTrigger::HeightDescending { height_m } = p.trigger {
                if !(height_m.is_finite() && height_m > 0.0) {
                    return number(
                        "parachute.height_m",
                        "must be above the ground and finite, or the canopy never opens",
                        height_m,
                    );
                }
            }
            if let Err((field, rule)) = p.canopy.check() {
                return Err(ReleaseRefusal::Trigger {
                    index,
                    component,
                    trigger: "parachute".into(),
                    rule: format!("canopy field \"{field}\" {rule}"),
                });
            }
        }
        check_trigger(index, r, motor_delay_s)?;
        let idx = inner_part(design, &r.component).map_err(|p| {
            let component = component.clone();
            match p {
                PartProblem::Unknown => ReleaseRefusal::UnknownComponent { index, component },
                PartProblem::Body => ReleaseRefusal::BodyComponent { index, component },
                PartProblem::External(kind) => ReleaseRefusal::ExternalPart {
                    index,
                    component,
                    kind,
                },
                PartProblem::HoldsMotor(mount) => ReleaseRefusal::HoldsMotor {
                    index,
                    component,
                    mount,
                },
                PartProblem::Cluster(tubes) => ReleaseRefusal::ClusterTube {
                    index,
                    component,
                    tubes,
                },
                PartProblem::StageOverride(stage) => ReleaseRefusal::StageOverride {
                    index,
                    component,
                    stage,
                },
                PartProblem::ComponentOverride(holder) => ReleaseRefusal::ComponentOverride {
                    index,
                    component,
                    holder,
                },
            }
        })?;
        // Parts that shifts move: the part itself may be one (released once its move has
        // ended, checked in flight); one around it or inside it may not.
        for &moving in &shift_plan.parts {
            if moving != idx && subtree_contains(design, moving, idx) {
                return Err(ReleaseRefusal::InsideMovingPart {
                    index,
                    component,
                    mover: design.components[moving].id.clone(),
                });
            }
            if moving != idx && subtree_contains(design, idx, moving) {
                return Err(ReleaseRefusal::HoldsMovingPart {
                    index,
                    component,
                    moving: design.components[moving].id.clone(),
                });
            }
        }
        if let Some(other) = out.parts.iter().position(|&p| p == idx) {
            return Err(ReleaseRefusal::ReleasedTwice {
                index,
                component,
                other,
            });
        }
        let mass_kg = mass::subtree(design, idx).mass_kg;
        if !(mass_kg.is_finite() && mass_kg > 0.0) {
            return Err(ReleaseRefusal::Massless {
                index,
                component,
                mass_kg,
            });
        }
        out.parts.push(idx);
        out.moving_part
            .push(shift_plan.parts.iter().position(|&p| p == idx));
        out.cda_m2.push(release_cda_m2(design, idx, r.cda_m2));
    }
    // A part inside a part another release drops (either order).
    for (index, &idx) in out.parts.iter().enumerate() {
        if let Some(other) = out
            .parts
            .iter()
            .position(|&p| p != idx && subtree_contains(design, p, idx))
        {
            return Err(ReleaseRefusal::InsideReleasedPart {
                index,
                component: releases[index].component.clone(),
                holder: design.components[out.parts[other]].id.clone(),
                other,
            });
        }
    }
    Ok(out)
}

fn check_trigger(
    index: usize,
    r: &Release,
    motor_delay_s: Option<f64>,
) -> Result<(), ReleaseRefusal> {
    let refuse = |rule: &str| ReleaseRefusal::Trigger {
        index,
        component: r.component.clone(),
        trigger: r.trigger.to_string(),
        rule: rule.to_string(),
    };
    if let Err(e) = r.trigger.validate() {
        return Err(refuse(&e.to_string()));
    }
    match r.trigger {
        Trigger::Time { time_s } if time_s <= 0.0 => Err(refuse(
            "a part can't leave before the rocket leaves the rail, and at launch it is still on the pad; time it from the burnout or the apogee instead",
        )),
        Trigger::HeightDescending { height_m } if height_m <= 0.0 => Err(refuse(
            "a height on the way down must be above the ground, or the part would never leave",
        )),
        Trigger::BurnoutPlusDelay { delay_s: None } if motor_delay_s.is_none() => Err(refuse(
            "the motor is plugged (it has no ejection delay), so burnout plus its delay never comes; give the delay in seconds",
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod refusals;
#[cfg(test)]
mod tests;
