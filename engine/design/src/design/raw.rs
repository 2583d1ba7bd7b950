//! The design file as JSON says it: serde structs, nothing checked beyond types.
//!
//! Every struct denies unknown fields, so a misspelt field is an error with its line and
//! column rather than a silently ignored value. Components are internally tagged by `"type"`.
//! [`super::validate`] turns a [`RawDesign`] into the validated [`super::Design`]; nothing
//! else reads these types. The format is documented for users in `docs/design-format.md`.

use super::model::NoseShape;
use serde::Deserialize;

/// The whole file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDesign {
    pub name: String,
    /// Free text for people: where the design comes from, what was tuned.
    #[serde(default)]
    pub notes: Option<String>,
    /// Default motor: a path, a file stem or a designation.
    #[serde(default)]
    pub motor: Option<String>,
    /// Drag model; absent means `{"estimate": {}}`.
    #[serde(default)]
    pub drag: Option<RawDrag>,
    /// How strictly parts must sit in their parents: `strict` (the default) or `openrocket`.
    #[serde(default)]
    pub geometry_checks: RawGeometryChecks,
    /// Air brakes and the controller that opens them.
    #[serde(default)]
    pub air_brakes: Option<RawAirBrakes>,
    pub stages: Vec<RawStage>,
}

/// Air brakes: their drag coefficient fully open (on `reference_area_m2`, the rocket's by
/// default) and the controller's target apogee and sampling rate.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawAirBrakes {
    pub cd: f64,
    #[serde(default)]
    pub reference_area_m2: Option<f64>,
    pub target_apogee_m: f64,
    pub sampling_rate_hz: f64,
}

/// How strictly a design's parts must sit in their parents.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RawGeometryChecks {
    /// A part entirely outside its parent, or wider than it, is an error.
    #[default]
    Strict,
    /// As OpenRocket: such a part stays where it is, weighed there, with a warning.
    Openrocket,
}

/// A fin's `airfoil`: exactly one of its 2-D lift-curve slope per rad, or a CSV lift table
/// (`angle,cl` rows, RocketPy's airfoil file) with its angles' unit.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawAirfoil {
    #[serde(default)]
    pub lift_slope_per_rad: Option<f64>,
    #[serde(default)]
    pub csv: Option<String>,
    #[serde(default)]
    pub angles: Option<String>,
}

/// A parachute's `deploy`: its trigger (a scenario's trigger written in JSON: `"apogee"`,
/// `"burnout"`, `"motor_delay"`, or `{"time_s": t}`, `{"height_m": h}`, `{"delay_s": d}`)
/// and the time from the trigger to the open canopy.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDeploy {
    pub trigger: serde_json::Value,
    #[serde(default)]
    pub lag_s: Option<f64>,
}

/// `drag`: exactly one of `power_off`, `power_off_csv` and `estimate`; `power_on` or
/// `power_on_csv` optionally beside a power-off curve (default: the power-off curve).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDrag {
    /// Rows `[mach, cd]`.
    #[serde(default)]
    pub power_off: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    pub power_on: Option<Vec<[f64; 2]>>,
    /// CSV file with rows `mach,cd`, relative to the design file.
    #[serde(default)]
    pub power_off_csv: Option<String>,
    #[serde(default)]
    pub power_on_csv: Option<String>,
    #[serde(default)]
    pub estimate: Option<RawEstimate>,
}

/// `drag.estimate`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEstimate {
    /// Surface roughness, m (default 60 µm, OpenRocket's "regular paint").
    #[serde(default)]
    pub roughness_m: Option<f64>,
}

/// One stage: body components fore to aft.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStage {
    pub id: String,
    #[serde(default)]
    pub name: Option<String>,
    /// Mass override of the whole stage; `cg_m` is m aft of the stage's fore end.
    #[serde(default, rename = "override")]
    pub overrides: Option<RawStageOverride>,
    pub components: Vec<RawComponent>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStageOverride {
    #[serde(default)]
    pub mass_kg: Option<f64>,
    #[serde(default)]
    pub cg_m: Option<f64>,
}

/// A component's override; `cg_m` is m aft of the component's fore end.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOverride {
    #[serde(default)]
    pub mass_kg: Option<f64>,
    #[serde(default)]
    pub cg_m: Option<f64>,
    #[serde(default)]
    pub covers_children: bool,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    /// For the reader only.
    #[serde(default)]
    pub name: Option<String>,
    pub density_kg_m3: f64,
}

/// Where a child sits along its parent.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPosition {
    #[serde(default)]
    pub from: RawFrom,
    #[serde(default)]
    pub offset_m: f64,
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RawFrom {
    /// Fore ends aligned, plus the offset.
    #[default]
    Top,
    /// Centers aligned, plus the offset.
    Middle,
    /// Aft ends aligned, plus the offset.
    Bottom,
    /// Fore end at the offset aft of the nose tip.
    NoseTip,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RawNoseShape {
    Conical,
    Ogive,
    VonKarman,
    Haack,
    LvHaack,
    Elliptical,
    PowerSeries,
    Parabolic,
}

impl RawNoseShape {
    /// The profile this name and parameter give, the parameter defaulted as OpenRocket
    /// defaults it (ogive 1, the tangent ogive; Haack `c` 0, power series `k` 0.5,
    /// parabolic `K'` 1) and not checked
    /// (the validation checks it first); a parameter of a shape that takes none is ignored.
    pub fn with_parameter(self, param: Option<f64>) -> NoseShape {
        match self {
            RawNoseShape::Conical => NoseShape::Conical,
            RawNoseShape::Ogive => match param {
                Some(p) if p < 1.0 => NoseShape::SecantOgive { p },
                _ => NoseShape::Ogive,
            },
            RawNoseShape::VonKarman => NoseShape::Haack { c: 0.0 },
            RawNoseShape::LvHaack => NoseShape::Haack { c: 1.0 / 3.0 },
            RawNoseShape::Elliptical => NoseShape::Elliptical,
            RawNoseShape::Haack => NoseShape::Haack {
                c: param.unwrap_or(0.0),
            },
            RawNoseShape::PowerSeries => NoseShape::PowerSeries {
                k: param.unwrap_or(0.5),
            },
            RawNoseShape::Parabolic => NoseShape::Parabolic {
                k: param.unwrap_or(1.0),
            },
        }
    }
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RawFinPlanform {
    #[default]
    Trapezoidal,
    Elliptical,
    FreeForm,
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RawCrossSection {
    #[default]
    Square,
    Rounded,
    Airfoil,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawShoulder {
    pub length_m: f64,
    pub outer_diameter_m: f64,
    pub wall_thickness_m: f64,
    #[serde(default)]
    pub capped: bool,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMotorMount {
    #[serde(default)]
    pub overhang_m: f64,
}

/// Declares a component struct with the fields every component has (id, name, material,
/// mass_kg, override) followed by its own. Serde cannot `flatten` into a struct that denies
/// unknown fields, hence the macro.
macro_rules! component_struct {
    ($(#[$m:meta])* $name:ident { $($(#[$fm:meta])* $field:ident : $ty:ty),* $(,)? }) => {
        $(#[$m])*
        #[derive(Debug, Clone, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            pub id: String,
            #[serde(default)]
            pub name: Option<String>,
            #[serde(default)]
            pub material: Option<RawMaterial>,
            #[serde(default)]
            pub mass_kg: Option<f64>,
            #[serde(default, rename = "override")]
            pub overrides: Option<RawOverride>,
            $($(#[$fm])* pub $field: $ty,)*
        }
    };
}

component_struct!(RawNoseCone {
    /// Surface roughness of this part's skin for the drag estimate, m (OpenRocket's finish
    /// of the part); absent: the estimate's `roughness_m`.
    #[serde(default)]
    roughness_m: Option<f64>,
    shape: RawNoseShape,
    #[serde(default)]
    shape_parameter: Option<f64>,
    length_m: f64,
    base_diameter_m: f64,
    #[serde(default)]
    wall_thickness_m: Option<f64>,
    /// The wall measured along the surface's normal (OpenRocket's) instead of across the axis.
    #[serde(default)]
    wall_along_normal: bool,
    #[serde(default)]
    filled: bool,
    #[serde(default)]
    shoulder: Option<RawShoulder>,
    #[serde(default)]
    children: Vec<RawComponent>,
});

component_struct!(RawBodyTube {
    /// Surface roughness of this part's skin for the drag estimate, m (OpenRocket's finish
    /// of the part); absent: the estimate's `roughness_m`.
    #[serde(default)]
    roughness_m: Option<f64>,
    length_m: f64,
    outer_diameter_m: f64,
    wall_thickness_m: f64,
    #[serde(default)]
    children: Vec<RawComponent>,
});

component_struct!(RawTransition {
    /// Surface roughness of this part's skin for the drag estimate, m (OpenRocket's finish
    /// of the part); absent: the estimate's `roughness_m`.
    #[serde(default)]
    roughness_m: Option<f64>,
    shape: RawNoseShape,
    #[serde(default)]
    shape_parameter: Option<f64>,
    length_m: f64,
    fore_diameter_m: f64,
    aft_diameter_m: f64,
    #[serde(default)]
    wall_thickness_m: Option<f64>,
    /// The wall measured along the surface's normal (OpenRocket's) instead of across the axis.
    #[serde(default)]
    wall_along_normal: bool,
    #[serde(default)]
    filled: bool,
    /// OpenRocket's clipped profile (the rest of a nose of the larger radius).
    #[serde(default)]
    clipped: bool,
    #[serde(default)]
    fore_shoulder: Option<RawShoulder>,
    #[serde(default)]
    aft_shoulder: Option<RawShoulder>,
    #[serde(default)]
    children: Vec<RawComponent>,
});

component_struct!(RawFinSet {
    /// Surface roughness of this part's skin for the drag estimate, m (OpenRocket's finish
    /// of the part); absent: the estimate's `roughness_m`.
    #[serde(default)]
    roughness_m: Option<f64>,
    count: u32,
    #[serde(default)]
    planform: RawFinPlanform,
    #[serde(default)]
    root_chord_m: Option<f64>,
    #[serde(default)]
    tip_chord_m: Option<f64>,
    #[serde(default)]
    span_m: Option<f64>,
    #[serde(default)]
    sweep_m: Option<f64>,
    /// The leading edge's sweep angle, degrees (RocketPy's `sweep_angle`), in place of
    /// `sweep_m`.
    #[serde(default)]
    sweep_deg: Option<f64>,
    #[serde(default)]
    points_m: Option<Vec<[f64; 2]>>,
    thickness_m: f64,
    #[serde(default)]
    cant_deg: f64,
    #[serde(default)]
    cross_section: RawCrossSection,
    /// The section's lift: its 2-D slope, or a lift table (RocketPy's `airfoil`).
    #[serde(default)]
    airfoil: Option<RawAirfoil>,
    #[serde(default)]
    rotation_deg: f64,
    #[serde(default)]
    position: Option<RawPosition>,
});

component_struct!(RawLaunchLug {
    length_m: f64,
    outer_diameter_m: f64,
    wall_thickness_m: f64,
    #[serde(default)]
    angle_deg: f64,
    #[serde(default)]
    position: Option<RawPosition>,
});

component_struct!(RawRailButton {
    outer_diameter_m: f64,
    height_m: f64,
    #[serde(default)]
    angle_deg: f64,
    #[serde(default)]
    position: Option<RawPosition>,
});

component_struct!(RawInnerTube {
    /// Its drag area once released in flight, m² (a flight's release of it, falling free or
    /// before its own canopy opens); absent: the flight's tumbling estimate.
    #[serde(default)]
    released_cda_m2: Option<f64>,
    length_m: f64,
    outer_diameter_m: f64,
    wall_thickness_m: f64,
    #[serde(default)]
    motor_mount: Option<RawMotorMount>,
    /// Offsets `[y, z]` of the tubes of a cluster from the tube's own axis, m.
    #[serde(default)]
    cluster: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    radial_offset_m: f64,
    #[serde(default)]
    radial_angle_deg: f64,
    #[serde(default)]
    position: Option<RawPosition>,
    #[serde(default)]
    children: Vec<RawComponent>,
});

component_struct!(RawCenteringRing {
    /// Its drag area once released in flight, m² (a flight's release of it, falling free or
    /// before its own canopy opens); absent: the flight's tumbling estimate.
    #[serde(default)]
    released_cda_m2: Option<f64>,
    length_m: f64,
    outer_diameter_m: f64,
    inner_diameter_m: f64,
    #[serde(default)]
    position: Option<RawPosition>,
});

component_struct!(RawBulkhead {
    /// Its drag area once released in flight, m² (a flight's release of it, falling free or
    /// before its own canopy opens); absent: the flight's tumbling estimate.
    #[serde(default)]
    released_cda_m2: Option<f64>,
    length_m: f64,
    outer_diameter_m: f64,
    #[serde(default)]
    position: Option<RawPosition>,
});

component_struct!(RawMassComponent {
    /// Its drag area once released in flight, m² (a flight's release of it, falling free or
    /// before its own canopy opens); absent: the flight's tumbling estimate.
    #[serde(default)]
    released_cda_m2: Option<f64>,
    length_m: f64,
    radius_m: f64,
    #[serde(default)]
    radial_offset_m: f64,
    #[serde(default)]
    radial_angle_deg: f64,
    /// `[axial, transverse]` about the part's own center, kg·m².
    #[serde(default)]
    inertia_kg_m2: Option<[f64; 2]>,
    #[serde(default)]
    position: Option<RawPosition>,
});

component_struct!(RawParachute {
    /// Its drag area once released in flight, m² (a flight's release of it, falling free or
    /// before its own canopy opens); absent: the flight's tumbling estimate.
    #[serde(default)]
    released_cda_m2: Option<f64>,
    length_m: f64,
    radius_m: f64,
    canopy_diameter_m: f64,
    cd: f64,
    /// How the parachute deploys when a flight takes it from the design (`fly`).
    #[serde(default)]
    deploy: Option<RawDeploy>,
    #[serde(default)]
    radial_offset_m: f64,
    #[serde(default)]
    radial_angle_deg: f64,
    #[serde(default)]
    inertia_kg_m2: Option<[f64; 2]>,
    #[serde(default)]
    position: Option<RawPosition>,
});

component_struct!(RawShockCord {
    /// Its drag area once released in flight, m² (a flight's release of it, falling free or
    /// before its own canopy opens); absent: the flight's tumbling estimate.
    #[serde(default)]
    released_cda_m2: Option<f64>,
    length_m: f64,
    radius_m: f64,
    #[serde(default)]
    linear_density_kg_m: Option<f64>,
    #[serde(default)]
    cord_length_m: Option<f64>,
    #[serde(default)]
    radial_offset_m: f64,
    #[serde(default)]
    radial_angle_deg: f64,
    #[serde(default)]
    inertia_kg_m2: Option<[f64; 2]>,
    #[serde(default)]
    position: Option<RawPosition>,
});

/// Any component, tagged by `"type"`.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum RawComponent {
    NoseCone(RawNoseCone),
    BodyTube(RawBodyTube),
    Transition(RawTransition),
    FinSet(RawFinSet),
    LaunchLug(RawLaunchLug),
    RailButton(RawRailButton),
    InnerTube(RawInnerTube),
    CenteringRing(RawCenteringRing),
    Bulkhead(RawBulkhead),
    MassComponent(RawMassComponent),
    Parachute(RawParachute),
    ShockCord(RawShockCord),
}

/// Applies `$e` to the struct inside any variant of a [`RawComponent`].
macro_rules! with_variant {
    ($s:expr, $c:ident => $e:expr) => {
        match $s {
            RawComponent::NoseCone($c) => $e,
            RawComponent::BodyTube($c) => $e,
            RawComponent::Transition($c) => $e,
            RawComponent::FinSet($c) => $e,
            RawComponent::LaunchLug($c) => $e,
            RawComponent::RailButton($c) => $e,
            RawComponent::InnerTube($c) => $e,
            RawComponent::CenteringRing($c) => $e,
            RawComponent::Bulkhead($c) => $e,
            RawComponent::MassComponent($c) => $e,
            RawComponent::Parachute($c) => $e,
            RawComponent::ShockCord($c) => $e,
        }
    };
}

/// The fields every component has.
#[derive(Debug, Clone, Copy)]
pub struct RawCommon<'a> {
    pub id: &'a str,
    pub name: Option<&'a str>,
    pub material: Option<&'a RawMaterial>,
    pub mass_kg: Option<f64>,
    pub overrides: Option<&'a RawOverride>,
}

impl RawComponent {
    /// The component's id.
    pub fn id(&self) -> &str {
        with_variant!(self, c => &c.id)
    }

    /// The fields every component has.
    pub fn common(&self) -> RawCommon<'_> {
        with_variant!(self, c => RawCommon {
            id: &c.id,
            name: c.name.as_deref(),
            material: c.material.as_ref(),
            mass_kg: c.mass_kg,
            overrides: c.overrides.as_ref(),
        })
    }

    /// The part's own surface roughness, m, for the parts whose skin meets the air (nose
    /// cones, body tubes, transitions, fin sets); `None` for the others or when not given.
    pub fn roughness_m(&self) -> Option<f64> {
        match self {
            RawComponent::NoseCone(c) => c.roughness_m,
            RawComponent::BodyTube(c) => c.roughness_m,
            RawComponent::Transition(c) => c.roughness_m,
            RawComponent::FinSet(c) => c.roughness_m,
            _ => None,
        }
    }

    /// The drag area an internal part flies with once released, m², if the design gives it
    /// (`None` for body and external components, which have no such field).
    pub fn released_cda_m2(&self) -> Option<f64> {
        match self {
            RawComponent::InnerTube(c) => c.released_cda_m2,
            RawComponent::CenteringRing(c) => c.released_cda_m2,
            RawComponent::Bulkhead(c) => c.released_cda_m2,
            RawComponent::MassComponent(c) => c.released_cda_m2,
            RawComponent::Parachute(c) => c.released_cda_m2,
            RawComponent::ShockCord(c) => c.released_cda_m2,
            _ => None,
        }
    }

    /// The components inside this one (body components and inner tubes hold children).
    pub fn children(&self) -> &[RawComponent] {
        match self {
            RawComponent::NoseCone(c) => &c.children,
            RawComponent::BodyTube(c) => &c.children,
            RawComponent::Transition(c) => &c.children,
            RawComponent::InnerTube(c) => &c.children,
            _ => &[],
        }
    }

    /// The JSON `type` tag.
    pub fn type_name(&self) -> &'static str {
        match self {
            RawComponent::NoseCone(_) => "nose_cone",
            RawComponent::BodyTube(_) => "body_tube",
            RawComponent::Transition(_) => "transition",
            RawComponent::FinSet(_) => "fin_set",
            RawComponent::LaunchLug(_) => "launch_lug",
            RawComponent::RailButton(_) => "rail_button",
            RawComponent::InnerTube(_) => "inner_tube",
            RawComponent::CenteringRing(_) => "centering_ring",
            RawComponent::Bulkhead(_) => "bulkhead",
            RawComponent::MassComponent(_) => "mass_component",
            RawComponent::Parachute(_) => "parachute",
            RawComponent::ShockCord(_) => "shock_cord",
        }
    }

    /// True for nose cones, body tubes and transitions.
    pub fn is_body(&self) -> bool {
        matches!(
            self,
            RawComponent::NoseCone(_) | RawComponent::BodyTube(_) | RawComponent::Transition(_)
        )
    }

    /// True for fins, launch lugs and rail buttons.
    pub fn is_external(&self) -> bool {
        matches!(
            self,
            RawComponent::FinSet(_) | RawComponent::LaunchLug(_) | RawComponent::RailButton(_)
        )
    }
}
