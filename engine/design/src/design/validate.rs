//! From raw JSON to the validated [`Design`]: the one place where a design is checked.
//!
//! It resolves every position to metres aft of the nose tip (body components end to end in a
//! stage, stages end to end, children by their `position`), computes what the rest of hpr
//! reads (reference diameter, length, rail guides, motor mount, cluster offsets) and refuses
//! anything that would make the mass or aerodynamics meaningless, with a [`DesignError`]
//! naming the file, the component, the field and the rule. The body components are in
//! `bodies`, the parts inside and outside them in `parts` (a fin set's own fields in
//! `fins`), the drag curves in `drag`.

mod airfoil;
mod bodies;
mod drag;
mod files;
mod fins;
mod parts;

#[cfg(test)]
mod doc_example;
#[cfg(test)]
mod fuzz;
#[cfg(test)]
mod tests;

use super::model::*;
use super::raw::*;
use crate::error::{DesignError, Location, Rule};
use std::collections::HashMap;
use std::path::Path;

/// How much a diameter may exceed the room it must fit in (a part in its parent, a motor in
/// its mount), m: 1 µm, well below any manufacturing tolerance, so that a part that fits
/// exactly on paper is not refused because of rounding (0.0563 − 2 × 0.0015 ≠ 0.0533 in
/// binary).
pub const FIT_TOLERANCE_M: f64 = 1e-6;

/// How far a motor mount's centre (a cluster's mean tube position) may sit off the rocket's
/// axis, m: a nanometre, far below any build's accuracy and far above the rounding of an
/// OpenRocket pattern's sines and cosines (about 1e-18 m).
pub const CLUSTER_CENTRE_TOLERANCE_M: f64 = 1e-9;

/// Where a part reaches along the axis, m aft of the nose tip: its length from its fore
/// end, and for a fin set its whole outline (a swept tip may reach past the root's trailing
/// edge, or ahead of its leading edge).
fn axial_reach(c: &Component) -> (f64, f64) {
    let (top, bottom) = (c.x_top_m, c.x_bottom_m());
    let ComponentKind::FinSet(f) = &c.kind else {
        return (top, bottom);
    };
    let (fore, aft) = match &f.planform {
        FinPlanform::Trapezoidal {
            tip_chord_m,
            sweep_m,
        } => (
            sweep_m.min(0.0),
            (sweep_m + tip_chord_m).max(f.root_chord_m),
        ),
        FinPlanform::Elliptical => (0.0, f.root_chord_m),
        FinPlanform::FreeForm { points_m } => {
            points_m.iter().fold((0.0, f.root_chord_m), |(a, b), p| {
                (p[0].min(a), p[0].max(b))
            })
        }
    };
    (top + fore, top + aft)
}

/// Largest fin count of a fin set.
pub const MAX_FINS: u32 = 32;

/// Most components (stages' body components and every part, at any depth) a design may
/// hold: 1,000, where OpenRocket's designs hold tens. Each is weighed and its aerodynamics
/// tabulated before a flight, and the flight reads every surface at every step, so a design
/// of thousands would take minutes to set up and fly; it is refused before any of that.
pub const MAX_COMPONENTS: usize = 1000;

/// Largest cant angle of a fin set, degrees (OpenRocket's limit).
pub const MAX_CANT_DEG: f64 = 15.0;

/// Roughness of the drag estimate when the design gives none, m: OpenRocket's "regular
/// paint".
pub const DEFAULT_ROUGHNESS_M: f64 = 60e-6;

impl Design {
    /// Reads and validates a design file. Drag CSVs are found relative to it.
    pub fn load(path: impl AsRef<Path>) -> Result<Design, DesignError> {
        let path = path.as_ref();
        Design::from_json_str(&Design::read_json_text(path)?, Some(path))
    }

    /// A design file's JSON text: the file's own, or an OpenRocket `.ork` imported into the
    /// design format.
    pub fn read_json_text(path: &Path) -> Result<String, DesignError> {
        let bytes = crate::limits::read_limited(
            path,
            crate::limits::MAX_DESIGN_FILE_BYTES,
            "a design file",
        )
        .map_err(|source| DesignError::Io {
            file: path.display().to_string(),
            source,
        })?;
        if crate::ork::is_ork_file(path, &bytes) {
            let import = crate::ork::import(&bytes, &path.display().to_string())?;
            return Ok(import.json.to_string());
        }
        String::from_utf8(bytes).map_err(|e| DesignError::Io {
            file: path.display().to_string(),
            source: std::io::Error::new(std::io::ErrorKind::InvalidData, e),
        })
    }

    /// Validates a design given as JSON text. `source` is the file it came from: errors name
    /// it and drag CSVs are found relative to its directory (relative to the working
    /// directory when `None`).
    pub fn from_json_str(text: &str, source: Option<&Path>) -> Result<Design, DesignError> {
        // A byte-order mark (some Windows editors write one) is not part of the JSON.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let file = match source {
            Some(p) => p.display().to_string(),
            None => "<design>".to_owned(),
        };
        let raw: RawDesign = serde_json::from_str(text).map_err(|e| {
            // A component's fault is placed by its id and field; anything else keeps serde's
            // line and column.
            let located = match e.classify() {
                serde_json::error::Category::Data => super::json_errors::locate(&file, text),
                _ => None,
            };
            located.unwrap_or_else(|| json_error(&file, &e))
        })?;
        // Counted before anything is built (without recursion: nesting is not bounded yet).
        let mut count = 0usize;
        let mut stack: Vec<&RawComponent> = raw.stages.iter().flat_map(|s| &s.components).collect();
        while let Some(c) = stack.pop() {
            count += 1;
            if count > MAX_COMPONENTS {
                return Err(DesignError::Invalid {
                    file,
                    at: Location::Design,
                    field: Some("stages".into()),
                    rule: Rule::TooManyComponents {
                        max: MAX_COMPONENTS,
                    },
                });
            }
            stack.extend(c.children());
        }
        let design = Builder {
            file: file.clone(),
            source,
            components: Vec::new(),
            ids: HashMap::new(),
            motor_mount: None,
            openrocket_geometry: false,
            warnings: Vec::new(),
        }
        .design(raw)?;
        // A part may lie outside its parent (drawn so in OpenRocket, a weight past the tail),
        // but no part of it further outside the rocket than the rocket is long: there it is
        // attached to nothing, and its mass (at a fuzzed 4e9 m, or a 6 m tube in a 1.15 m
        // rocket) makes nonsense of the rocket's.
        let (lo, hi) = design
            .components
            .iter()
            .filter(|c| c.is_body())
            .map(Component::holder_extent_m)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (t, u)| {
                (a.min(t), b.max(u))
            });
        let reach = hi - lo;
        for c in design.components.iter().filter(|c| !c.is_body()) {
            let (top, bottom) = axial_reach(c);
            if bottom > hi + reach + FIT_TOLERANCE_M || top < lo - reach - FIT_TOLERANCE_M {
                return Err(DesignError::Invalid {
                    file,
                    at: Location::Component(c.id.clone()),
                    field: Some("position".into()),
                    rule: Rule::OutsideRocket {
                        top_m: top,
                        bottom_m: bottom,
                        length_m: design.length_m,
                    },
                });
            }
        }
        Ok(design)
    }

    /// Checks that a motor of this diameter and length fits the motor mount: its diameter
    /// must not exceed the mount's inner diameter, its length the mount's length plus the
    /// overhang (both within [`FIT_TOLERANCE_M`]). The error says which is too big.
    pub fn motor_fits(&self, diameter_m: f64, length_m: f64) -> Result<(), DesignError> {
        let file = match &self.source {
            Some(p) => p.display().to_string(),
            None => "<design>".to_owned(),
        };
        let invalid = |at: Location, field: Option<&str>, rule: Rule| DesignError::Invalid {
            file: file.clone(),
            at,
            field: field.map(str::to_owned),
            rule,
        };
        let Some(mount) = self.motor_mount else {
            return Err(invalid(Location::Design, None, Rule::NoMotorMount));
        };
        let at = Location::Component(self.components[mount.component].id.clone());
        if !(diameter_m > 0.0 && diameter_m.is_finite()) {
            return Err(invalid(
                at,
                Some("motor diameter_m"),
                Rule::NotPositive { got: diameter_m },
            ));
        }
        if !(length_m > 0.0 && length_m.is_finite()) {
            return Err(invalid(
                at,
                Some("motor length_m"),
                Rule::NotPositive { got: length_m },
            ));
        }
        if diameter_m > mount.inner_diameter_m + FIT_TOLERANCE_M {
            return Err(invalid(
                at,
                None,
                Rule::MotorTooWide {
                    motor_diameter_m: diameter_m,
                    mount_inner_diameter_m: mount.inner_diameter_m,
                },
            ));
        }
        let tube_bottom = self.components[mount.component].x_bottom_m();
        let room = mount.tube_length_m + (mount.motor_aft_m - tube_bottom);
        // OpenRocket lets a longer motor stick out past the mount's fore end.
        if length_m > room + FIT_TOLERANCE_M && !self.openrocket_geometry {
            return Err(invalid(
                at,
                None,
                Rule::MotorTooLong {
                    motor_length_m: length_m,
                    room_m: room,
                },
            ));
        }
        Ok(())
    }
}

/// serde_json's message without its " at line L column C" suffix, with the position apart.
fn json_error(file: &str, e: &serde_json::Error) -> DesignError {
    let (line, column) = (e.line(), e.column());
    let text = e.to_string();
    let suffix = format!(" at line {line} column {column}");
    let message = super::json_errors::plain_types(text.strip_suffix(&suffix).unwrap_or(&text));
    DesignError::Json {
        file: file.to_owned(),
        line,
        column,
        message,
    }
}

/// Builds the arena while it checks. Child modules add the per-kind work.
struct Builder<'a> {
    file: String,
    source: Option<&'a Path>,
    components: Vec<Component>,
    /// id -> where it was first used (JSON path), for duplicate errors.
    ids: HashMap<String, String>,
    motor_mount: Option<MotorMount>,
    /// `geometry_checks: "openrocket"`: a part outside or wider than its parent is a warning.
    openrocket_geometry: bool,
    warnings: Vec<String>,
}

impl Builder<'_> {
    fn invalid(&self, at: &Location, field: Option<&str>, rule: Rule) -> DesignError {
        DesignError::Invalid {
            file: self.file.clone(),
            at: at.clone(),
            field: field.map(str::to_owned),
            rule,
        }
    }

    /// A part that does not sit in its parent: an error, or under `geometry_checks:
    /// "openrocket"` (and where `tolerable`: its position is a number) a warning, the part
    /// kept where it is, as OpenRocket keeps it.
    fn misfit(
        &mut self,
        at: &Location,
        field: Option<&str>,
        rule: Rule,
        tolerable: bool,
    ) -> Result<(), DesignError> {
        if self.openrocket_geometry && tolerable {
            let what = self.invalid(at, field, rule);
            self.warnings
                .push(format!("{what} (kept there, as OpenRocket keeps it)"));
            Ok(())
        } else {
            Err(self.invalid(at, field, rule))
        }
    }

    /// `> 0` and finite.
    fn positive(&self, at: &Location, field: &str, v: f64) -> Result<f64, DesignError> {
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(self.invalid(at, Some(field), Rule::NotPositive { got: v }))
        }
    }

    /// A length or diameter: `> 0`, finite and at most [`MAX_PART_SIZE_M`].
    fn size(&self, at: &Location, field: &str, v: f64) -> Result<f64, DesignError> {
        self.positive(at, field, v)?;
        self.at_most_part_size(at, field, v)
    }

    /// A length or diameter that may be zero: `>= 0`, finite and at most [`MAX_PART_SIZE_M`].
    fn size_or_zero(&self, at: &Location, field: &str, v: f64) -> Result<f64, DesignError> {
        self.non_negative(at, field, v)?;
        self.at_most_part_size(at, field, v)
    }

    fn at_most_part_size(&self, at: &Location, field: &str, v: f64) -> Result<f64, DesignError> {
        if v <= MAX_PART_SIZE_M {
            Ok(v)
        } else {
            Err(self.invalid(
                at,
                Some(field),
                Rule::TooLarge {
                    got: v,
                    max: MAX_PART_SIZE_M,
                },
            ))
        }
    }

    /// A flight computer's sampling rate: `> 0` and at most [`MAX_SAMPLING_RATE_HZ`].
    fn sampling_rate(&self, at: &Location, field: &str, v: f64) -> Result<f64, DesignError> {
        let v = self.positive(at, field, v)?;
        if v <= MAX_SAMPLING_RATE_HZ {
            Ok(v)
        } else {
            Err(self.invalid(
                at,
                Some(field),
                Rule::OutOfRange {
                    got: v,
                    min: 0.0,
                    max: MAX_SAMPLING_RATE_HZ,
                },
            ))
        }
    }

    /// `>= 0` and finite.
    fn non_negative(&self, at: &Location, field: &str, v: f64) -> Result<f64, DesignError> {
        if v >= 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(self.invalid(at, Some(field), Rule::Negative { got: v }))
        }
    }

    fn finite(&self, at: &Location, field: &str, v: f64) -> Result<f64, DesignError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.invalid(at, Some(field), Rule::NotFinite { got: v }))
        }
    }

    /// `min <= v <= max`.
    fn within(
        &self,
        at: &Location,
        field: &str,
        v: f64,
        min: f64,
        max: f64,
    ) -> Result<f64, DesignError> {
        if v >= min && v <= max {
            Ok(v)
        } else {
            Err(self.invalid(at, Some(field), Rule::OutOfRange { got: v, min, max }))
        }
    }

    /// A wall: positive, finite and no thicker than the radius.
    fn wall(&self, at: &Location, field: &str, wall: f64, radius: f64) -> Result<f64, DesignError> {
        self.positive(at, field, wall)?;
        if wall > radius {
            return Err(self.invalid(
                at,
                Some(field),
                Rule::WallThickerThanRadius {
                    wall_m: wall,
                    radius_m: radius,
                },
            ));
        }
        Ok(wall)
    }

    /// A resolved position or extent that must be finite.
    fn resolved(&self, at: &Location, field: &str, v: f64) -> Result<f64, DesignError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.invalid(at, Some(field), Rule::PositionNotFinite { got: v }))
        }
    }

    /// Registers an id (stages and components share one namespace) and returns its location.
    fn claim_id(&mut self, id: &str, path: &str, stage: bool) -> Result<Location, DesignError> {
        if id.is_empty() {
            return Err(self.invalid(&Location::Path(path.to_owned()), Some("id"), Rule::EmptyId));
        }
        let at = if stage {
            Location::Stage(id.to_owned())
        } else {
            Location::Component(id.to_owned())
        };
        if let Some(first) = self.ids.get(id) {
            return Err(self.invalid(
                &at,
                Some("id"),
                Rule::DuplicateId {
                    first: first.clone(),
                },
            ));
        }
        self.ids.insert(id.to_owned(), path.to_owned());
        Ok(at)
    }

    /// Exactly one way to give the mass. `cord` is a shock cord's
    /// (`linear_density_kg_m`, `cord_length_m`).
    fn mass_spec(
        &self,
        at: &Location,
        common: &RawCommon<'_>,
        cord: Option<(Option<f64>, Option<f64>)>,
    ) -> Result<MassSpec, DesignError> {
        let (linear, cord_length) = cord.unwrap_or((None, None));
        if cord_length.is_some() && linear.is_none() {
            return Err(self.invalid(
                at,
                Some("cord_length_m"),
                Rule::NeedsField {
                    other: "linear_density_kg_m",
                },
            ));
        }
        let given = usize::from(common.material.is_some())
            + usize::from(common.mass_kg.is_some())
            + usize::from(linear.is_some());
        if given != 1 {
            let options = if cord.is_some() {
                "\"material.density_kg_m3\", \"mass_kg\" and \"linear_density_kg_m\""
            } else {
                "\"material.density_kg_m3\" and \"mass_kg\""
            };
            return Err(self.invalid(at, None, Rule::MassSpecNotExactlyOne { options, given }));
        }
        if let Some(m) = common.material {
            return Ok(MassSpec::Density(self.positive(
                at,
                "material.density_kg_m3",
                m.density_kg_m3,
            )?));
        }
        if let Some(m) = common.mass_kg {
            // Zero is allowed: a part whose mass is lumped into another component (as
            // RocketPy's rockets give one mass for the whole structure) still has a shape
            // for the aerodynamics.
            return Ok(MassSpec::Mass(self.non_negative(at, "mass_kg", m)?));
        }
        let kg_per_m = self.positive(at, "linear_density_kg_m", linear.unwrap_or(f64::NAN))?;
        let Some(cord_length) = cord_length else {
            return Err(self.invalid(
                at,
                Some("linear_density_kg_m"),
                Rule::NeedsField {
                    other: "cord_length_m",
                },
            ));
        };
        let cord_length_m = self.size(at, "cord_length_m", cord_length)?;
        Ok(MassSpec::LinearDensity {
            kg_per_m,
            cord_length_m,
        })
    }

    /// A component's override; its `cg_m` is relative to the component's fore end.
    fn overrides(
        &self,
        at: &Location,
        raw: Option<&RawOverride>,
        x_top: f64,
    ) -> Result<Overrides, DesignError> {
        let Some(o) = raw else {
            return Ok(Overrides::default());
        };
        // Zero is allowed, as in OpenRocket: the component (or its subtree) weighs nothing.
        self.override_of(at, o.mass_kg, o.cg_m, x_top, false, o.covers_children)
    }

    /// An override's mass (`stage`: above 0, a stage that weighs nothing being a mistake;
    /// else 0 or more) and center (`cg_m` aft of `x_top`, made absolute).
    fn override_of(
        &self,
        at: &Location,
        mass_kg: Option<f64>,
        cg_m: Option<f64>,
        x_top: f64,
        stage: bool,
        covers_children: bool,
    ) -> Result<Overrides, DesignError> {
        let mass_kg = match mass_kg {
            Some(m) if stage => Some(self.positive(at, "override.mass_kg", m)?),
            Some(m) => Some(self.non_negative(at, "override.mass_kg", m)?),
            None => None,
        };
        let cg_m = match cg_m {
            Some(c) => {
                let c = self.finite(at, "override.cg_m", c)?;
                Some(self.resolved(at, "override.cg_m", x_top + c)?)
            }
            None => None,
        };
        Ok(Overrides {
            mass_kg,
            cg_m,
            covers_children,
        })
    }

    /// Adds a checked component to the arena (and to its parent's children).
    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        at: &Location,
        raw: &RawComponent,
        parent: Option<ComponentIdx>,
        stage: usize,
        x_top_m: f64,
        length_m: f64,
        radial_offset_m: [f64; 2],
        kind: ComponentKind,
        cord: Option<(Option<f64>, Option<f64>)>,
    ) -> Result<ComponentIdx, DesignError> {
        let x_top_m = self.resolved(at, "position", x_top_m)?;
        self.resolved(at, "position", x_top_m + length_m)?;
        let common = raw.common();
        let mass_spec = self.mass_spec(at, &common, cord)?;
        let overrides = self.overrides(at, common.overrides, x_top_m)?;
        let roughness_m = match raw.roughness_m() {
            Some(r) => Some(self.non_negative(at, "roughness_m", r)?),
            None => None,
        };
        let released_cda_m2 = match raw.released_cda_m2() {
            Some(a) => Some(self.positive(at, "released_cda_m2", a)?),
            None => None,
        };
        let idx = self.components.len();
        self.components.push(Component {
            id: common.id.to_owned(),
            name: common.name.unwrap_or(common.id).to_owned(),
            parent,
            children: Vec::new(),
            stage,
            x_top_m,
            length_m,
            radial_offset_m,
            kind,
            mass_spec,
            overrides,
            roughness_m,
            released_cda_m2,
        });
        if let Some(p) = parent {
            self.components[p].children.push(idx);
        }
        Ok(idx)
    }

    fn design(mut self, raw: RawDesign) -> Result<Design, DesignError> {
        self.openrocket_geometry = raw.geometry_checks == RawGeometryChecks::Openrocket;
        let drag = self.drag(raw.drag.as_ref())?;
        if raw.stages.is_empty() {
            return Err(self.invalid(&Location::Design, Some("stages"), Rule::NoBodyComponent));
        }
        let mut stages = Vec::with_capacity(raw.stages.len());
        let mut cursor = 0.0;
        for (s, rs) in raw.stages.iter().enumerate() {
            let path = format!("stages[{s}]");
            let at = self.claim_id(&rs.id, &path, true)?;
            if rs.components.is_empty() {
                return Err(self.invalid(&at, Some("components"), Rule::NoBodyComponent));
            }
            let stage_top = cursor;
            let first = self.components.len();
            for (i, rc) in rs.components.iter().enumerate() {
                let cpath = format!("{path}.components[{i}]");
                let idx = self.body(rc, s, cursor, &cpath)?;
                cursor = self.components[idx].x_bottom_m();
                for (j, child) in rc.children().iter().enumerate() {
                    self.child(child, idx, s, &format!("{cpath}.children[{j}]"))?;
                }
            }
            let overrides = match &rs.overrides {
                None => Overrides::default(),
                // A stage's override always covers the whole stage.
                Some(o) => self.override_of(&at, o.mass_kg, o.cg_m, stage_top, true, true)?,
            };
            stages.push(Stage {
                id: rs.id.clone(),
                name: rs.name.clone().unwrap_or_else(|| rs.id.clone()),
                components: (first..self.components.len()).collect(),
                overrides,
            });
        }

        let reference_diameter_m = self
            .components
            .iter()
            .filter_map(|c| match &c.kind {
                ComponentKind::NoseCone(n) => Some(n.base_diameter_m),
                ComponentKind::BodyTube(b) => Some(b.outer_diameter_m),
                ComponentKind::Transition(t) => Some(t.fore_diameter_m.max(t.aft_diameter_m)),
                _ => None,
            })
            .fold(0.0, f64::max);

        let air_brakes = match &raw.air_brakes {
            None => None,
            Some(b) => {
                let at = Location::Design;
                let area = match b.reference_area_m2 {
                    Some(a) => self.positive(&at, "air_brakes.reference_area_m2", a)?,
                    None => {
                        std::f64::consts::PI * 0.25 * reference_diameter_m * reference_diameter_m
                    }
                };
                Some(AirBrakes {
                    cd: self.non_negative(&at, "air_brakes.cd", b.cd)?,
                    reference_area_m2: area,
                    target_apogee_m: self.positive(
                        &at,
                        "air_brakes.target_apogee_m",
                        b.target_apogee_m,
                    )?,
                    sampling_rate_hz: self.sampling_rate(
                        &at,
                        "air_brakes.sampling_rate_hz",
                        b.sampling_rate_hz,
                    )?,
                })
            }
        };
        let file = self.source.map(|p| p.display().to_string());
        let design = Design {
            name: raw.name,
            source: self.source.map(Path::to_path_buf),
            default_motor: raw.motor,
            reference_diameter_m,
            length_m: cursor,
            rail_guides_m: rail_guides(&self.components),
            motor_mount: self.motor_mount,
            stages,
            components: self.components,
            drag,
            openrocket_geometry: self.openrocket_geometry,
            warnings: self.warnings,
            air_brakes,
        };
        // Every part's mass, center and inertia, its overrides applied, must be numbers:
        // dimensions that pass each rule alone can still be too small or too large together
        // for arithmetic (a button 1e-157 m across weighs 1e-312 kg, and an override of its
        // mass scales that by 1e309).
        // The parts after the parts that hold them: the innermost at fault is named.
        for (idx, c) in design.components.iter().enumerate().rev() {
            let m = crate::mass::subtree(&design, idx);
            let finite = m.mass_kg.is_finite()
                && m.cg_m.iter().all(|x| x.is_finite())
                && m.inertia_cg.iter().all(|x| x.is_finite());
            if !finite {
                return Err(DesignError::Invalid {
                    file: file.unwrap_or_else(|| "<design>".to_owned()),
                    at: Location::Component(c.id.clone()),
                    field: None,
                    rule: Rule::MassNotFinite { mass_kg: m.mass_kg },
                });
            }
        }
        Ok(design)
    }
}

/// The first two rail guides (rail buttons or launch lugs, in document order), each spanning
/// its center (a button) or its two ends (a lug): (fore-most point, aft-most point). A single
/// lug gives its own two ends; a single button gives nothing.
fn rail_guides(components: &[Component]) -> Option<(f64, f64)> {
    let mut spans = components.iter().filter_map(|c| match c.kind {
        ComponentKind::RailButton(_) => {
            let mid = c.x_top_m + c.length_m / 2.0;
            Some((mid, mid))
        }
        ComponentKind::LaunchLug(_) => Some((c.x_top_m, c.x_bottom_m())),
        _ => None,
    });
    let (a_top, a_bottom) = spans.next()?;
    let (top, bottom) = match spans.next() {
        Some((b_top, b_bottom)) => (a_top.min(b_top), a_bottom.max(b_bottom)),
        None => (a_top, a_bottom),
    };
    (bottom > top).then_some((top, bottom))
}
