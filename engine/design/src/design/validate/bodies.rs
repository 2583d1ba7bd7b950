//! Body components (nose cones, body tubes, transitions): the airframe's outer shell, placed
//! end to end in their stage.

use super::Builder;
use crate::design::model::*;
use crate::design::raw::*;
use crate::design::shapes;
use crate::error::{DesignError, Location, Rule};

impl Builder<'_> {
    /// Checks a top-level component of a stage and adds it with its fore end at `x_top`.
    pub(super) fn body(
        &mut self,
        rc: &RawComponent,
        stage: usize,
        x_top: f64,
        path: &str,
    ) -> Result<ComponentIdx, DesignError> {
        let at = self.claim_id(rc.id(), path, false)?;
        let (length, kind) = match rc {
            RawComponent::NoseCone(n) => {
                let length = self.size(&at, "length_m", n.length_m)?;
                let base = self.size(&at, "base_diameter_m", n.base_diameter_m)?;
                let shape = self.nose_shape(&at, n.shape, n.shape_parameter)?;
                let wall = self.shell_wall(&at, n.wall_thickness_m, n.filled, base / 2.0)?;
                let shoulder = match &n.shoulder {
                    Some(s) => Some(self.shoulder(&at, "shoulder", s, base)?),
                    None => None,
                };
                let nose = NoseCone {
                    shape,
                    base_diameter_m: base,
                    wall_thickness_m: wall,
                    wall_along_normal: n.wall_along_normal,
                    filled: n.filled,
                    shoulder,
                };
                (length, ComponentKind::NoseCone(nose))
            }
            RawComponent::BodyTube(b) => {
                let length = self.size(&at, "length_m", b.length_m)?;
                let od = self.size(&at, "outer_diameter_m", b.outer_diameter_m)?;
                let wall = self.wall(&at, "wall_thickness_m", b.wall_thickness_m, od / 2.0)?;
                let tube = BodyTube {
                    outer_diameter_m: od,
                    wall_thickness_m: wall,
                };
                (length, ComponentKind::BodyTube(tube))
            }
            RawComponent::Transition(t) => {
                let length = self.size(&at, "length_m", t.length_m)?;
                let fore = self.size_or_zero(&at, "fore_diameter_m", t.fore_diameter_m)?;
                let aft = self.size_or_zero(&at, "aft_diameter_m", t.aft_diameter_m)?;
                if fore.max(aft) <= 0.0 {
                    return Err(self.invalid(
                        &at,
                        Some("aft_diameter_m"),
                        Rule::NotPositive { got: aft },
                    ));
                }
                let shape = transition_shape(self.nose_shape(&at, t.shape, t.shape_parameter)?);
                let wall =
                    self.shell_wall(&at, t.wall_thickness_m, t.filled, fore.max(aft) / 2.0)?;
                let fore_shoulder = match &t.fore_shoulder {
                    Some(s) => Some(self.shoulder(&at, "fore_shoulder", s, fore)?),
                    None => None,
                };
                let aft_shoulder = match &t.aft_shoulder {
                    Some(s) => Some(self.shoulder(&at, "aft_shoulder", s, aft)?),
                    None => None,
                };
                // Clipping changes only the shapes OpenRocket clips; others ignore it, as there.
                let nose = shapes::transition_nose_shape(shape);
                let clip_m = if t.clipped && shapes::clippable(nose) {
                    shapes::clip_length(nose, length, fore / 2.0, aft / 2.0)
                } else {
                    0.0
                };
                let transition = Transition {
                    shape,
                    fore_diameter_m: fore,
                    aft_diameter_m: aft,
                    clip_m,
                    wall_thickness_m: wall,
                    wall_along_normal: t.wall_along_normal,
                    filled: t.filled,
                    fore_shoulder,
                    aft_shoulder,
                };
                (length, ComponentKind::Transition(transition))
            }
            other => {
                return Err(self.invalid(
                    &at,
                    Some("type"),
                    Rule::NotABody {
                        kind: other.type_name(),
                    },
                ));
            }
        };
        self.push(&at, rc, None, stage, x_top, length, [0.0, 0.0], kind, None)
    }

    /// The shape with its parameter checked and defaulted (ogive 1, Haack `c` 0, power
    /// series `k` 0.5, parabolic `K'` 1, as OpenRocket defaults them).
    fn nose_shape(
        &self,
        at: &Location,
        shape: RawNoseShape,
        param: Option<f64>,
    ) -> Result<NoseShape, DesignError> {
        let none = |name: &'static str| match param {
            Some(_) => Err(self.invalid(
                at,
                Some("shape_parameter"),
                Rule::ShapeTakesNoParameter { shape: name },
            )),
            None => Ok(()),
        };
        match shape {
            RawNoseShape::Conical => none("conical")?,
            RawNoseShape::Ogive => {
                self.within(at, "shape_parameter", param.unwrap_or(1.0), 0.0, 1.0)?;
            }
            RawNoseShape::VonKarman => none("von_karman")?,
            RawNoseShape::LvHaack => none("lv_haack")?,
            RawNoseShape::Elliptical => none("elliptical")?,
            RawNoseShape::Haack => {
                self.within(at, "shape_parameter", param.unwrap_or(0.0), 0.0, 1.0)?;
            }
            RawNoseShape::PowerSeries => {
                let k = param.unwrap_or(0.5);
                if !(k > 0.0 && k <= 1.0) {
                    return Err(self.invalid(
                        at,
                        Some("shape_parameter"),
                        Rule::OutOfRange {
                            got: k,
                            min: 0.0,
                            max: 1.0,
                        },
                    ));
                }
            }
            RawNoseShape::Parabolic => {
                self.within(at, "shape_parameter", param.unwrap_or(1.0), 0.0, 1.0)?;
            }
        }
        Ok(shape.with_parameter(param))
    }

    /// The wall of a nose cone or transition: required unless filled (then it is the radius:
    /// solid all through).
    fn shell_wall(
        &self,
        at: &Location,
        wall: Option<f64>,
        filled: bool,
        radius: f64,
    ) -> Result<f64, DesignError> {
        match (wall, filled) {
            (Some(w), _) => self.wall(at, "wall_thickness_m", w, radius),
            (None, true) => Ok(radius),
            (None, false) => Err(self.invalid(
                at,
                Some("wall_thickness_m"),
                Rule::Required {
                    when: "unless \"filled\" is true",
                },
            )),
        }
    }

    /// A shoulder, no wider than the end it belongs to.
    fn shoulder(
        &self,
        at: &Location,
        name: &str,
        s: &RawShoulder,
        end_diameter: f64,
    ) -> Result<Shoulder, DesignError> {
        let length = self.size(at, &format!("{name}.length_m"), s.length_m)?;
        let od = self.size(at, &format!("{name}.outer_diameter_m"), s.outer_diameter_m)?;
        if od > end_diameter + super::FIT_TOLERANCE_M {
            return Err(self.invalid(
                at,
                Some(&format!("{name}.outer_diameter_m")),
                Rule::OutOfRange {
                    got: od,
                    min: 0.0,
                    max: end_diameter,
                },
            ));
        }
        let wall = self.wall(
            at,
            &format!("{name}.wall_thickness_m"),
            s.wall_thickness_m,
            od / 2.0,
        )?;
        Ok(Shoulder {
            length_m: length,
            outer_diameter_m: od,
            wall_thickness_m: wall,
            capped: s.capped,
        })
    }
}

fn transition_shape(shape: NoseShape) -> TransitionShape {
    match shape {
        NoseShape::Conical => TransitionShape::Conical,
        NoseShape::Ogive => TransitionShape::Ogive,
        NoseShape::SecantOgive { p } => TransitionShape::SecantOgive { p },
        NoseShape::Haack { c } => TransitionShape::Haack { c },
        NoseShape::Elliptical => TransitionShape::Elliptical,
        NoseShape::PowerSeries { k } => TransitionShape::PowerSeries { k },
        NoseShape::Parabolic { k } => TransitionShape::Parabolic { k },
    }
}
