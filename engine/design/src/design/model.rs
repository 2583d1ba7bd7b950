//! The validated design: a flat arena of components with absolute positions.
//!
//! Everything here has been checked (finite, positive where it must be, inside its parent,
//! unique ids) and every position is resolved to metres aft of the nose tip, so the mass and
//! aerodynamics code never walks relative placements.

/// Index of a component in [`Design::components`].
pub type ComponentIdx = usize;

/// A validated rocket design.
#[derive(Debug, Clone)]
pub struct Design {
    /// Human-readable name.
    pub name: String,
    /// The file it came from (for error messages), if any.
    pub source: Option<std::path::PathBuf>,
    /// Motor the design flies by default: a path, a file stem or a designation.
    pub default_motor: Option<String>,
    /// Reference diameter (largest body diameter), m. Static margin is in calibres of this.
    pub reference_diameter_m: f64,
    /// Total length from the nose tip to the aft end of the last body component, m.
    pub length_m: f64,
    /// Stages, fore to aft. Every component belongs to exactly one.
    pub stages: Vec<Stage>,
    /// All components, parents before children, in document order.
    pub components: Vec<Component>,
    /// Drag model.
    pub drag: DragSpec,
    /// Rail buttons or lugs, if any: positions of the upper and lower guide, m aft of the tip.
    pub rail_guides_m: Option<(f64, f64)>,
    /// Motor placement, resolved from the motor-mount inner tube (`None` if no mount).
    pub motor_mount: Option<MotorMount>,
    /// `geometry_checks: "openrocket"`: parts may sit outside or be wider than their
    /// parents, and a motor longer than its mount sticks out past the mount's fore end.
    pub openrocket_geometry: bool,
    /// What the validation let pass under `geometry_checks: "openrocket"` (a part outside
    /// or wider than its parent, kept where it is), one sentence each.
    pub warnings: Vec<String>,
    /// Air brakes, if the rocket has them.
    pub air_brakes: Option<AirBrakes>,
}

/// The fastest a flight computer may sample, Hz (a parachute trigger's barometer, an air
/// brakes' controller): beyond any flight computer's barometer (1 kHz at most, RocketPy's
/// examples 10 to 105 Hz). Each of a controller's samples ends an integrator step, and a
/// noisy barometer is read at every sample, so a rate without a ceiling (1e300 Hz, a typo)
/// would never finish a flight.
pub const MAX_SAMPLING_RATE_HZ: f64 = 10_000.0;

/// The largest length or diameter a design may give a part, m (a body's length, a fin's span,
/// a canopy's diameter, a free-form fin's corner from the root's leading edge): beyond any
/// high-power or sounding rocket's part (a Saturn V stage is 42 m long, 10 m across; amateur
/// rockets' parts are a few metres at most). It catches a length written in millimetres in a
/// field in metres (a 54 mm tube as `54`), which would otherwise fly as a rocket the size of
/// a building, and it keeps the aerodynamics' quadratures finite.
pub const MAX_PART_SIZE_M: f64 = 30.0;

/// Air brakes and their controller (`air_brakes` in the design file). From burnout to
/// apogee, at each of the controller's samples, the brakes open to the fraction of their
/// travel that makes the predicted apogee the target, and hold it to the next sample; they
/// close at apogee.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirBrakes {
    /// Drag coefficient of the brakes fully open, on [`AirBrakes::reference_area_m2`].
    pub cd: f64,
    /// The area `cd` is referred to, m² (the rocket's reference area unless given).
    pub reference_area_m2: f64,
    /// The apogee the controller aims at, m above the launch site.
    pub target_apogee_m: f64,
    /// Samples per second of the controller (from burnout on).
    pub sampling_rate_hz: f64,
}

impl Design {
    /// Index of the component with this id, if any.
    pub fn component_index(&self, id: &str) -> Option<ComponentIdx> {
        self.components.iter().position(|c| c.id == id)
    }

    /// The component with this id, if any.
    pub fn component(&self, id: &str) -> Option<&Component> {
        self.components.iter().find(|c| c.id == id)
    }

    /// Where the motors sit across the airframe: each motor's axis as `[y, z]` off the
    /// rocket's, m (station frame), one per tube of the mount's cluster; `[[0, 0]]` for a
    /// single motor, empty with no motor mount. Their mean is on the axis (validation).
    pub fn motor_offsets_m(&self) -> &[[f64; 2]] {
        match self.motor_mount {
            Some(m) => match &self.components[m.component].kind {
                ComponentKind::InnerTube(t) => &t.cluster_offsets_m,
                _ => &[],
            },
            None => &[],
        }
    }
}

/// A stage: a group of top-level body components, with an optional mass override.
#[derive(Debug, Clone)]
pub struct Stage {
    pub id: String,
    pub name: String,
    /// Indices of the components in this stage (all of them, at every depth).
    pub components: Vec<ComponentIdx>,
    pub overrides: Overrides,
}

/// Where the motor sits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorMount {
    /// The inner tube that holds the motor.
    pub component: ComponentIdx,
    /// Motors it holds: one, or one in each tube of a cluster (their offsets:
    /// [`Design::motor_offsets_m`]).
    pub motors: usize,
    /// The motor's aft end, m aft of the nose tip (tube's aft end plus overhang).
    pub motor_aft_m: f64,
    /// Inner diameter of the mount, m (the motor's diameter must not exceed it).
    pub inner_diameter_m: f64,
    /// Length of the mount tube, m.
    pub tube_length_m: f64,
}

/// One component of the tree.
#[derive(Debug, Clone)]
pub struct Component {
    /// Unique id (the one `MassShift` names).
    pub id: String,
    pub name: String,
    pub parent: Option<ComponentIdx>,
    pub children: Vec<ComponentIdx>,
    pub stage: usize,
    /// Fore end, m aft of the nose tip.
    pub x_top_m: f64,
    /// Axial length, m.
    pub length_m: f64,
    /// Offset of the component's axis from the rocket's axis in the station frame (y, z), m.
    /// Zero for body components and most internal parts.
    pub radial_offset_m: [f64; 2],
    pub kind: ComponentKind,
    /// What the component is made of, or its explicit mass.
    pub mass_spec: MassSpec,
    pub overrides: Overrides,
    /// The skin's own surface roughness for the drag estimate, m (nose cones, body tubes,
    /// transitions and fin sets only); `None`: the estimate's.
    pub roughness_m: Option<f64>,
    /// An internal part's drag area once released in flight, m², if the design gives it
    /// (`released_cda_m2`); `None`: a flight estimates it.
    pub released_cda_m2: Option<f64>,
}

impl Component {
    /// Aft end, m aft of the nose tip.
    pub fn x_bottom_m(&self) -> f64 {
        self.x_top_m + self.length_m
    }
    /// The axial extent a child part may occupy, (fore, aft) m aft of the nose tip: the
    /// component's own length, plus its shoulders for a nose cone or a transition. The design's
    /// placement rules and a shift's travel limits both measure against it.
    pub fn holder_extent_m(&self) -> (f64, f64) {
        match &self.kind {
            ComponentKind::NoseCone(n) => (
                self.x_top_m,
                self.x_bottom_m() + n.shoulder.map_or(0.0, |s| s.length_m),
            ),
            ComponentKind::Transition(t) => (
                self.x_top_m - t.fore_shoulder.map_or(0.0, |s| s.length_m),
                self.x_bottom_m() + t.aft_shoulder.map_or(0.0, |s| s.length_m),
            ),
            _ => (self.x_top_m, self.x_bottom_m()),
        }
    }
    /// True for nose cones, body tubes and transitions (the airframe's outer shell).
    pub fn is_body(&self) -> bool {
        matches!(
            self.kind,
            ComponentKind::NoseCone(_) | ComponentKind::BodyTube(_) | ComponentKind::Transition(_)
        )
    }
    /// True for parts on the outside of the airframe (fins, lugs, rail buttons).
    pub fn is_external(&self) -> bool {
        matches!(
            self.kind,
            ComponentKind::FinSet(_) | ComponentKind::LaunchLug(_) | ComponentKind::RailButton(_)
        )
    }
}

/// How a component's mass is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MassSpec {
    /// Material density, kg/m³ (a shock cord's kg/m is given as `LinearDensity`).
    Density(f64),
    /// Explicit mass, kg, spread over the component's shape.
    Mass(f64),
    /// Linear density of a shock cord, kg/m, and the cord's full length, m: its mass is
    /// `kg_per_m * cord_length_m`, packed into the component's cylinder.
    LinearDensity { kg_per_m: f64, cord_length_m: f64 },
}

/// Overrides of mass and center of mass (as OpenRocket has them).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Overrides {
    /// Replace the mass, kg. The inertia is scaled by the same ratio.
    pub mass_kg: Option<f64>,
    /// Replace the center of mass, m aft of the nose tip (absolute).
    pub cg_m: Option<f64>,
    /// The override covers everything the component holds (its subtree), not just itself.
    pub covers_children: bool,
}

impl Overrides {
    pub fn any(&self) -> bool {
        self.mass_kg.is_some() || self.cg_m.is_some()
    }
}

/// Nose cone profiles. `r(x)` for `0 <= x <= L`, base radius `R`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoseShape {
    Conical,
    /// Tangent ogive.
    Ogive,
    /// Secant ogive: OpenRocket's ogive of shape parameter `p` in `[0, 1)`, the fore part
    /// `p` of the tangent ogive of length `L/p` through the same base radius (`p` → 1 the
    /// tangent ogive, `p` → 0 the cone); it meets the body at an angle.
    SecantOgive {
        p: f64,
    },
    /// Haack series with parameter `c` (0 = von Kármán / LD-Haack, 1/3 = LV-Haack).
    Haack {
        c: f64,
    },
    Elliptical,
    /// r = R (x/L)^k, 0 < k <= 1.
    PowerSeries {
        k: f64,
    },
    /// Parabolic series with parameter K' in [0, 1] (1 = full parabola).
    Parabolic {
        k: f64,
    },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoseCone {
    pub shape: NoseShape,
    pub base_diameter_m: f64,
    pub wall_thickness_m: f64,
    /// Whether the wall is measured along the surface's normal (OpenRocket's convention)
    /// rather than across the axis.
    pub wall_along_normal: bool,
    /// Solid (filled) nose, e.g. a turned wooden one.
    pub filled: bool,
    pub shoulder: Option<Shoulder>,
}

/// A shoulder: a tube that slides into the next body component, aft of the part's aft end
/// (for a nose cone) or fore of its fore end (a transition's fore shoulder).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shoulder {
    pub length_m: f64,
    pub outer_diameter_m: f64,
    pub wall_thickness_m: f64,
    /// Shoulder capped at its end by a disc of the same thickness.
    pub capped: bool,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyTube {
    pub outer_diameter_m: f64,
    pub wall_thickness_m: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TransitionShape {
    Conical,
    Ogive,
    SecantOgive { p: f64 },
    Elliptical,
    PowerSeries { k: f64 },
    Haack { c: f64 },
    Parabolic { k: f64 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transition {
    pub shape: TransitionShape,
    pub fore_diameter_m: f64,
    pub aft_diameter_m: f64,
    /// OpenRocket's clip length, m ([`crate::design::shapes::clip_length`]); 0 unclipped.
    pub clip_m: f64,
    pub wall_thickness_m: f64,
    /// As a nose cone's.
    pub wall_along_normal: bool,
    pub filled: bool,
    pub fore_shoulder: Option<Shoulder>,
    pub aft_shoulder: Option<Shoulder>,
}

/// The outline of one fin, in its plane: the root along the body from its leading edge
/// (`x = 0`, aft positive) to `root_chord_m`, the span outward from the body.
#[derive(Debug, Clone, PartialEq)]
pub enum FinPlanform {
    /// Straight edges: a tip chord parallel to the root, its leading edge `sweep_m` aft of
    /// the root's.
    Trapezoidal {
        tip_chord_m: f64,
        /// Axial distance from the root's leading edge to the tip's leading edge, m.
        sweep_m: f64,
    },
    /// Half an ellipse on the root: semi-axes half the root chord (along the body) and the
    /// span, its tip a point above the root's mid-chord (RocketPy's `EllipticalFins`,
    /// OpenRocket's elliptical fin set).
    Elliptical,
    /// Any outline of straight edges (RocketPy's `FreeFormFins`, OpenRocket's free-form fin
    /// set): its corners `(x, y)`, `x` aft of the root's leading edge and `y` out from the
    /// body, in order from the root's leading edge `(0, 0)` to its trailing edge
    /// `(root chord, 0)`; the root closes it.
    FreeForm { points_m: Vec<[f64; 2]> },
}

impl FinPlanform {
    /// Area of one fin of this planform on a root of `root_chord_m` and a span of `span_m`,
    /// m²: `(C_r + C_t) s / 2`, or `π C_r s / 4` for the half ellipse.
    pub fn area_m2(&self, root_chord_m: f64, span_m: f64) -> f64 {
        match self {
            FinPlanform::Trapezoidal { tip_chord_m, .. } => {
                (root_chord_m + tip_chord_m) * span_m / 2.0
            }
            FinPlanform::Elliptical => std::f64::consts::PI * root_chord_m * span_m / 4.0,
            FinPlanform::FreeForm { points_m } => polygon_area_m2(points_m),
        }
    }

    /// The name the design format gives it.
    pub fn name(&self) -> &'static str {
        match self {
            FinPlanform::Trapezoidal { .. } => "trapezoidal",
            FinPlanform::Elliptical => "elliptical",
            FinPlanform::FreeForm { .. } => "free_form",
        }
    }
}

/// The signed area of the polygon `points` closed back to its first point (the shoelace
/// formula: positive counter-clockwise), m².
pub fn polygon_signed_area_m2(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    0.5 * twice
}

/// The area of the polygon `points` closed back to its first point, m².
pub fn polygon_area_m2(points: &[[f64; 2]]) -> f64 {
    polygon_signed_area_m2(points).abs()
}

#[derive(Debug, Clone, PartialEq)]
pub struct FinSet {
    pub count: u32,
    pub root_chord_m: f64,
    /// Semi-span: from the body surface to the tip, m.
    pub span_m: f64,
    pub planform: FinPlanform,
    pub thickness_m: f64,
    pub cant_deg: f64,
    /// Radius of the body where the fins attach, m.
    pub body_radius_m: f64,
    /// Angle of the first fin about the axis, degrees (from +y toward +z).
    pub rotation_deg: f64,
    /// Fin cross-section for drag: square, rounded or airfoil.
    pub cross_section: FinCrossSection,
    /// The section's 2-D lift-curve slope, per rad (2π, a flat plate, unless an airfoil's
    /// lift table or slope is given).
    pub lift_slope_2d_per_rad: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FinCrossSection {
    Square,
    Rounded,
    Airfoil,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaunchLug {
    pub outer_diameter_m: f64,
    pub wall_thickness_m: f64,
    /// Angle about the axis, degrees.
    pub angle_deg: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailButton {
    pub outer_diameter_m: f64,
    pub height_m: f64,
    pub angle_deg: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct InnerTube {
    pub outer_diameter_m: f64,
    pub wall_thickness_m: f64,
    /// Present when this tube holds a motor.
    pub motor_mount: Option<MotorMountSpec>,
    /// Offsets (y, z) of each tube of a cluster from the rocket's axis (station frame), m:
    /// the tube's own radial offset (and its parent's) plus the cluster offset. A single tube
    /// has one entry, its own offset (`[0, 0]` on the axis).
    pub cluster_offsets_m: Vec<[f64; 2]>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorMountSpec {
    /// How far the motor sticks out of the tube's aft end, m.
    pub overhang_m: f64,
}

/// Centering ring or bulkhead (a bulkhead has inner diameter 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ring {
    pub outer_diameter_m: f64,
    pub inner_diameter_m: f64,
}

/// A solid cylinder (mass component, parachute or shock cord packed as a cylinder).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PackedCylinder {
    pub radius_m: f64,
    /// Optional measured inertia (axial, transverse) about the part's own center, kg·m²,
    /// replacing the solid-cylinder value.
    pub inertia_kg_m2: Option<(f64, f64)>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parachute {
    pub packed: PackedCylinder,
    /// Canopy diameter, m, and drag coefficient (used when the design names its recovery).
    pub canopy_diameter_m: f64,
    pub cd: f64,
    /// How it deploys when a flight takes its parachutes from the design, if the design says.
    pub deploy: Option<Deploy>,
}

impl Parachute {
    /// The canopy's drag area, m²: `cd` times the area of its diameter.
    pub fn cds_m2(&self) -> f64 {
        self.cd * std::f64::consts::PI * (0.5 * self.canopy_diameter_m).powi(2)
    }
}

/// A parachute's deployment as the design says it: its trigger and the time from the
/// trigger to the open canopy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deploy {
    pub trigger: DeployTrigger,
    pub lag_s: f64,
}

/// A trigger as a design's parachute or a scenario writes it (`hpr_sim::Trigger` flies it):
/// a word (`apogee`, `burnout`, `motor_delay`) or one named number (`time_s`, `height_m`,
/// `delay_s`). [`DeployTrigger::named`] and [`DeployTrigger::with_number`] are the one reader
/// of that grammar; each file format only finds the word or the number in its own values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DeployTrigger {
    Apogee,
    Burnout,
    /// Burnout plus the motor's first listed delay.
    MotorDelay,
    /// After launch, s.
    Time {
        time_s: f64,
    },
    /// On the way down, through this height above the ground, m.
    Height {
        height_m: f64,
    },
    /// After burnout, s.
    AfterBurnout {
        delay_s: f64,
    },
}

#[derive(Debug, Clone, PartialEq)]
pub enum ComponentKind {
    NoseCone(NoseCone),
    BodyTube(BodyTube),
    Transition(Transition),
    FinSet(FinSet),
    LaunchLug(LaunchLug),
    RailButton(RailButton),
    InnerTube(InnerTube),
    CenteringRing(Ring),
    Bulkhead(Ring),
    MassComponent(PackedCylinder),
    Parachute(Parachute),
    ShockCord(PackedCylinder),
}

impl DeployTrigger {
    /// What a trigger may be written as, for errors.
    pub const FORMS: &'static str = "a trigger is \"apogee\", \"burnout\", \"motor_delay\" (burnout plus the motor's delay), or one number: time_s (after launch), height_m (on the way down) or delay_s (after burnout)";

    /// The trigger the word `word` names.
    pub fn named(word: &str) -> Result<DeployTrigger, String> {
        match word {
            "apogee" => Ok(DeployTrigger::Apogee),
            "burnout" => Ok(DeployTrigger::Burnout),
            "motor_delay" => Ok(DeployTrigger::MotorDelay),
            other => Err(format!("unknown trigger \"{other}\": {}", Self::FORMS)),
        }
    }

    /// The trigger of number `x` under the name `key` (finite, not negative).
    pub fn with_number(key: &str, x: f64) -> Result<DeployTrigger, String> {
        if !(x.is_finite() && x >= 0.0) {
            return Err(format!(
                "trigger {key}: must be finite and not negative (got {x})"
            ));
        }
        match key {
            "time_s" => Ok(DeployTrigger::Time { time_s: x }),
            "height_m" => Ok(DeployTrigger::Height { height_m: x }),
            "delay_s" => Ok(DeployTrigger::AfterBurnout { delay_s: x }),
            other => Err(format!(
                "unknown trigger field \"{other}\": {}",
                Self::FORMS
            )),
        }
    }
}

impl ComponentKind {
    /// The JSON `type` tag of this kind.
    pub fn type_name(&self) -> &'static str {
        match self {
            ComponentKind::NoseCone(_) => "nose_cone",
            ComponentKind::BodyTube(_) => "body_tube",
            ComponentKind::Transition(_) => "transition",
            ComponentKind::FinSet(_) => "fin_set",
            ComponentKind::LaunchLug(_) => "launch_lug",
            ComponentKind::RailButton(_) => "rail_button",
            ComponentKind::InnerTube(_) => "inner_tube",
            ComponentKind::CenteringRing(_) => "centering_ring",
            ComponentKind::Bulkhead(_) => "bulkhead",
            ComponentKind::MassComponent(_) => "mass_component",
            ComponentKind::Parachute(_) => "parachute",
            ComponentKind::ShockCord(_) => "shock_cord",
        }
    }
}

/// Drag model of the design.
#[derive(Debug, Clone, PartialEq)]
pub enum DragSpec {
    /// Cd against Mach, referenced to the area of the reference diameter; power off and on
    /// (as RocketPy reads them). Mach strictly increasing.
    Curves {
        power_off: Vec<(f64, f64)>,
        power_on: Vec<(f64, f64)>,
    },
    /// Estimate from the geometry (skin friction, pressure and base drag, as OpenRocket does),
    /// with a surface roughness, m.
    Estimate { roughness_m: f64 },
}
