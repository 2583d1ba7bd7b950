//! Each OpenRocket component mapped onto the design format's (the element names, units and
//! rules are OpenRocket's savers' and loader's: lengths in metres, angles in degrees,
//! positions of a part's fore end along its parent): what the import carries from component
//! to component ([`Context`]: ids, finishes, the motor, notes), the fields every component
//! has, the stages and their body components; the parts on and in them are in [`parts`].

mod cluster;
pub(super) mod fins;
mod parts;

use super::{Auto, El};
use crate::design::raw::RawNoseShape;
use crate::design::shapes::{clip_length, clippable, tapered_radius};
use crate::error::DesignError;
use serde_json::{json, Map, Value};
use std::collections::HashMap;

/// The default flight configuration's motor: how to find it in hpr's library, and how to
/// name it to a reader.
pub(super) struct OrkMotor {
    /// Names to look up, in order: the maker's file of the designation, the designation.
    pub candidates: Vec<String>,
    /// Last, the maker's file of the designation's common name (`Cesaroni_K445` for
    /// `1635K445-17A`): the same class and average thrust, which the import says it took.
    pub by_common_name: Option<String>,
    pub label: String,
}

/// What the import carries from component to component: the ids used, the finishes seen,
/// the motor mount chosen, and the notes.
pub(super) struct Context {
    ids: HashMap<String, usize>,
    finishes: Vec<(String, f64)>,
    /// The configuration id of the default motor, whether the document has such a motor,
    /// and whether its mount has been placed.
    config: Option<String>,
    has_motor: bool,
    mount_placed: bool,
    /// The default motor's ejection delay, s (`None`: no motor, or plugged: "none").
    motor_delay_s: Option<f64>,
    /// The fore end of the next body component, m aft of the nose tip (stages follow each
    /// other).
    x_m: f64,
    /// The aft radius of the last stage's last body component (a bare `auto` of the next
    /// stage's first may take it).
    last_radius: Option<f64>,
    pub notes: Vec<String>,
}

/// A component's JSON object.
type Component = Map<String, Value>;

/// A body component read, its radii resolved later (a bare `auto` takes its neighbour's).
struct Body<'a, 'i> {
    el: El<'a, 'i>,
    json: Component,
    length_m: f64,
    fore: Option<Auto>,
    aft: Option<Auto>,
    kind: &'static str,
    /// The overhang of the motor this body tube holds itself (a minimum-diameter rocket).
    holds_motor: Option<f64>,
    /// A filled body tube: a solid rod, its wall its radius once that is resolved.
    solid: bool,
}

/// The wall of the massless tube that stands for a body tube's bore when the tube holds the
/// motor itself, m: thin enough that a motor as wide as the bore fits it (the fit's tolerance
/// is 1 µm across).
const BORE_WALL_M: f64 = 1e-7;

/// The wall given a tube, ring or shoulder OpenRocket draws with none (and weighs at
/// nothing), m: the design format's shapes need one.
const THIN_WALL_M: f64 = 1e-7;

/// What a part's position and automatic sizes read of its parent.
struct Parent {
    length_m: f64,
    /// The parent's fore end, m aft of the nose tip (for OpenRocket's absolute positions).
    front_m: f64,
    /// A ring's automatic outer radius (the parent's inner radius), where it is one number.
    ring_r: Option<f64>,
    /// A nose cone's or transition's inner radius `x` m aft of its fore end (OpenRocket's:
    /// the outer radius less the wall, across the axis), for a ring's automatic radius.
    inner_at: Option<Box<dyn Fn(f64) -> f64>>,
    /// A packed part's automatic radius (OpenRocket's rule for each kind of parent).
    packed_r: Option<f64>,
    /// Whether the parent is a body component (fins, lugs and buttons only go there).
    on_body: bool,
    /// A body component's outer radius at its fore and aft ends, m (a fin's root sits
    /// there; taken as linear between them).
    surface_r: Option<(f64, f64)>,
}

impl Context {
    pub fn new() -> Context {
        Context {
            ids: HashMap::new(),
            finishes: Vec::new(),
            config: None,
            has_motor: false,
            mount_placed: false,
            motor_delay_s: None,
            x_m: 0.0,
            last_radius: None,
            notes: Vec::new(),
        }
    }

    /// The default flight configuration's id, where the document names one.
    pub fn config(&self) -> Option<&str> {
        self.config.as_deref()
    }

    pub fn note(&mut self, text: String) {
        if !self.notes.contains(&text) {
            self.notes.push(text);
        }
    }

    /// The surface roughness of the finish most outer components have (OpenRocket's
    /// roughness of each finish), 60 µm ("normal") if none is given: the drag estimate's
    /// default, for the skins that give none and for launch lugs (each nose cone, body
    /// tube, transition and fin set carries its own finish's roughness).
    pub fn roughness(&self) -> f64 {
        let mut counts: Vec<(String, f64, usize)> = Vec::new();
        for (name, r) in &self.finishes {
            match counts.iter_mut().find(|c| &c.0 == name) {
                Some(c) => c.2 += 1,
                None => counts.push((name.clone(), *r, 1)),
            }
        }
        let Some(most) = counts.iter().max_by_key(|c| c.2) else {
            return 60e-6;
        };
        most.1
    }

    /// The default flight configuration's motor, if the document declares one.
    pub fn default_motor(&mut self, rocket: &El<'_, '_>) -> Option<OrkMotor> {
        let configs: Vec<El<'_, '_>> = rocket
            .children()
            .filter(|c| c.tag() == "motorconfiguration" || c.tag() == "flightconfiguration")
            .collect();
        let default = configs
            .iter()
            .find(|c| c.attribute("default") == Some("true"))
            .or(configs.first())
            .and_then(|c| c.attribute("configid"));
        self.config = default.map(str::to_owned);
        let Some(motor) = find_motor(rocket, default) else {
            self.note(
                "OpenRocket's default flight configuration has no motor: give one with --motor \
                 or the scenario's motor."
                    .to_owned(),
            );
            return None;
        };
        self.has_motor = true;
        self.motor_delay_s = motor.text("delay").and_then(super::parse_number);
        // Without configurations, the first motor's own.
        self.config = default.or(motor.attribute("configid")).map(str::to_owned);
        let designation = motor.text("designation").unwrap_or("").to_owned();
        let manufacturer = motor.text("manufacturer").unwrap_or("").to_owned();
        if designation.is_empty() {
            return None;
        }
        // "Cesaroni Technology" and "Loki Research" file as Cesaroni_… and Loki_….
        let maker = manufacturer.split_whitespace().next().unwrap_or("");
        let mut candidates = Vec::new();
        if !maker.is_empty() {
            candidates.push(format!("{maker}_{designation}"));
        }
        candidates.push(designation.clone());
        let common = crate::motor::curve::common_name(&designation, '?', 0.0);
        let by_common_name =
            (!maker.is_empty() && !common.starts_with('?') && common != designation)
                .then(|| format!("{maker}_{common}"));
        Some(OrkMotor {
            candidates,
            by_common_name,
            label: format!("{manufacturer} {designation}").trim().to_owned(),
        })
    }

    /// A unique id from a component's name (lower case, words joined by `_`).
    fn id(&mut self, name: &str) -> String {
        let mut slug = String::new();
        for c in name.trim().chars() {
            if c.is_ascii_alphanumeric() {
                slug.push(c.to_ascii_lowercase());
            } else if !slug.ends_with('_') && !slug.is_empty() {
                slug.push('_');
            }
        }
        let slug = slug.trim_end_matches('_');
        let slug = if slug.is_empty() { "part" } else { slug }.to_owned();
        let n = self.ids.entry(slug.clone()).or_insert(0);
        *n += 1;
        if *n == 1 {
            slug
        } else {
            format!("{slug}_{n}")
        }
    }

    /// The fields every component has: id, name, material and overrides.
    fn common(&mut self, el: &El<'_, '_>) -> Result<Component, DesignError> {
        let mut m = Map::new();
        m.insert("id".into(), json!(self.id(el.name())));
        m.insert("name".into(), json!(el.name()));
        if let Some(mat) = el.child("material") {
            let density = mat
                .attribute_number("density")
                .ok_or_else(|| el.bad("material", "has no finite density"))?;
            let kind = mat.attribute("type").unwrap_or("bulk");
            if kind == "bulk" {
                m.insert(
                    "material".into(),
                    json!({ "name": mat.own_text(), "density_kg_m3": density }),
                );
            }
        }
        if let Some(finish) = el.text("finish") {
            let roughness_m = match finish {
                "rough" => 500e-6,
                "roughunfinished" => 250e-6,
                "unfinished" => 150e-6,
                "normal" => 60e-6,
                "smooth" => 20e-6,
                "optimum" => 5e-6,
                "polished" => 2e-6,
                "finishpolished" => 0.5e-6,
                "mirror" => 0.0,
                other => return Err(el.bad("finish", format!("unknown finish \"{other}\""))),
            };
            self.finishes.push((finish.to_owned(), roughness_m));
            // The skins whose friction OpenRocket takes at their own finish.
            if matches!(
                el.tag(),
                "nosecone"
                    | "bodytube"
                    | "transition"
                    | "trapezoidfinset"
                    | "ellipticalfinset"
                    | "freeformfinset"
            ) {
                m.insert("roughness_m".into(), json!(roughness_m));
            }
        }
        let mass = el.num("overridemass")?;
        let cg = el.num("overridecg")?;
        if mass.is_some() || cg.is_some() {
            // Files before 1.8 have one flag for mass, CG and drag.
            let old = el.flag("overridesubcomponents");
            let mass_children = el.flag("overridesubcomponentsmass") || old;
            let cg_children = el.flag("overridesubcomponentscg") || old;
            let covers = if mass.is_some() {
                mass_children
            } else {
                cg_children
            };
            if mass.is_some() && cg.is_some() && mass_children != cg_children {
                self.note(format!(
                    "{}: its mass and CG overrides differ on whether they cover the parts \
                     inside; both are taken as {}.",
                    el.name(),
                    if covers { "covering them" } else { "its own" }
                ));
            }
            let mut o = overrides(mass, cg);
            o.insert("covers_children".into(), json!(covers));
            m.insert("override".into(), Value::Object(o));
        }
        if el.text("overridecd").is_some() {
            self.note(format!(
                "{}: its drag override is not imported (the drag is estimated from the \
                 geometry).",
                el.name()
            ));
        }
        Ok(m)
    }

    /// One stage: its body components fore to aft, their parts inside.
    pub fn stage(&mut self, el: &El<'_, '_>) -> Result<Value, DesignError> {
        let mut stage = Map::new();
        stage.insert("id".into(), json!(self.id(el.name())));
        stage.insert("name".into(), json!(el.name()));
        let (mass, cg) = (el.num("overridemass")?, el.num("overridecg")?);
        if mass.is_some() || cg.is_some() {
            // A stage's override is the whole stage's (its parts' masses replaced), as the
            // design format's stage override is.
            if !(el.flag("overridesubcomponentsmass")
                || el.flag("overridesubcomponentscg")
                || el.flag("overridesubcomponents"))
            {
                return Err(el.refuse("a stage's override that does not cover its parts"));
            }
            stage.insert("override".into(), Value::Object(overrides(mass, cg)));
        }
        let mut bodies = Vec::new();
        for c in el
            .child("subcomponents")
            .iter()
            .flat_map(|s| s.children().collect::<Vec<_>>())
        {
            // A body component of no length holding nothing, which OpenRocket draws and
            // weighs at nothing, is left out.
            let holds_nothing = c
                .child("subcomponents")
                .is_none_or(|s| s.children().next().is_none());
            if holds_nothing && c.num("length")? == Some(0.0) {
                self.note(format!(
                    "{}: no length and nothing in it, left out.",
                    c.name()
                ));
                continue;
            }
            bodies.push(self.body(&c)?);
        }
        if bodies.is_empty() {
            return Err(el.bad(
                "subcomponents",
                "a stage needs a nose cone, body tube or transition",
            ));
        }
        resolve_radii(el, &mut bodies, self.last_radius)?;
        self.last_radius = bodies.last().and_then(|b| match b.aft {
            Some(Auto::Value(r)) => Some(r),
            _ => None,
        });
        let mut components = Vec::new();
        for mut b in bodies {
            let radius = |k: &str| b.json[k].as_f64().map(|d| d / 2.0);
            let (ring_r, packed_r) = match b.kind {
                "body_tube" => {
                    let inner = radius("outer_diameter_m")
                        .zip(b.json["wall_thickness_m"].as_f64())
                        .map(|(r, t)| r - t);
                    (inner, inner)
                }
                "nose_cone" => (None, radius("base_diameter_m")),
                _ => (
                    None,
                    radius("fore_diameter_m")
                        .zip(radius("aft_diameter_m"))
                        .map(|(f, a)| f.max(a)),
                ),
            };
            let surface_r = match b.kind {
                "body_tube" => radius("outer_diameter_m").map(|r| (r, r)),
                "nose_cone" => radius("base_diameter_m").map(|r| (0.0, r)),
                _ => radius("fore_diameter_m").zip(radius("aft_diameter_m")),
            };
            let parent = Parent {
                length_m: b.length_m,
                front_m: self.x_m,
                ring_r,
                inner_at: shell_inner_radius(&b.json, b.kind, b.length_m),
                packed_r,
                on_body: true,
                surface_r,
            };
            let mut parts = self.parts(&b.el, &parent)?;
            if let (Some(overhang), Some(bore_r)) = (b.holds_motor, ring_r) {
                let id = self.id(&format!("{} motor mount", b.el.name()));
                parts.push(json!({
                    "id": id,
                    "type": "inner_tube",
                    "name": format!("{} (its bore, the motor mount)", b.el.name()),
                    "length_m": b.length_m,
                    "outer_diameter_m": 2.0 * bore_r,
                    "wall_thickness_m": BORE_WALL_M,
                    "mass_kg": 0.0,
                    "motor_mount": { "overhang_m": overhang },
                    "position": { "from": "top", "offset_m": 0.0 },
                }));
            }
            if !parts.is_empty() {
                b.json.insert("children".into(), Value::Array(parts));
            }
            self.x_m += b.length_m;
            components.push(Value::Object(b.json));
        }
        stage.insert("components".into(), Value::Array(components));
        Ok(Value::Object(stage))
    }

    /// A nose cone, body tube or transition (its parts are read once its radii are known).
    fn body<'a, 'i>(&mut self, el: &El<'a, 'i>) -> Result<Body<'a, 'i>, DesignError> {
        // A flipped nose cone (OpenRocket 23.09's tail cone) is OpenRocket's transition
        // from its base radius, fore, to a point, aft, its shoulder fore (`NoseCone.
        // setFlipped`); its file keeps the base and shoulder in the `aft` elements.
        let flipped = el.tag() == "nosecone" && el.flag("isflipped");
        let kind = match el.tag() {
            "nosecone" if flipped => "transition",
            "nosecone" => "nose_cone",
            "bodytube" => "body_tube",
            "transition" => "transition",
            other => return Err(el.refuse(&format!("a <{other}> among a stage's body components"))),
        };
        if flipped {
            self.note(format!(
                "{}: a flipped nose cone (a tail cone), imported as a transition to a point.",
                el.name()
            ));
        }
        let mut m = self.common(el)?;
        m.insert("type".into(), json!(kind));
        let length = el.req("length")?;
        m.insert("length_m".into(), json!(length));
        let mut fore = None;
        let mut solid = false;
        let aft;
        match kind {
            "body_tube" => {
                let r = el
                    .auto("radius")?
                    .ok_or_else(|| el.bad("radius", "is missing"))?;
                (fore, aft) = (Some(r), Some(r));
                match el.text("thickness") {
                    Some("filled") => {
                        solid = true;
                        self.note(format!(
                            "{}: a filled body tube, a solid rod (its wall its radius).",
                            el.name()
                        ));
                    }
                    _ => {
                        m.insert("wall_thickness_m".into(), json!(el.req("thickness")?));
                    }
                }
            }
            _ => {
                let (shape, param) = shape(el)?;
                m.insert("shape".into(), json!(shape));
                if let Some(p) = param {
                    m.insert("shape_parameter".into(), json!(p));
                }
                // OpenRocket writes `shapeclipped` for nose cones too, but clips only
                // transitions (of the shapes it can clip, which the design format checks).
                if kind == "transition" && !flipped && el.flag("shapeclipped") {
                    m.insert("clipped".into(), json!(true));
                }
                match el.text("thickness") {
                    Some("filled") => {
                        m.insert("filled".into(), json!(true));
                    }
                    _ => {
                        m.insert("wall_thickness_m".into(), json!(el.req("thickness")?));
                        // OpenRocket measures a shell's wall along the surface's normal.
                        m.insert("wall_along_normal".into(), json!(true));
                    }
                }
                let base = el
                    .auto("aftradius")?
                    .ok_or_else(|| el.bad("aftradius", "is missing"))?;
                if flipped {
                    (fore, aft) = (Some(base), Some(Auto::Value(0.0)));
                    if let Some(s) = shoulder(el, "aft")? {
                        m.insert("fore_shoulder".into(), s);
                    }
                } else if kind == "transition" {
                    aft = Some(base);
                    fore = Some(
                        el.auto("foreradius")?
                            .ok_or_else(|| el.bad("foreradius", "is missing"))?,
                    );
                    if let Some(s) = shoulder(el, "fore")? {
                        m.insert("fore_shoulder".into(), s);
                    }
                    if let Some(s) = shoulder(el, "aft")? {
                        m.insert("aft_shoulder".into(), s);
                    }
                } else {
                    aft = Some(base);
                    if let Some(s) = shoulder(el, "aft")? {
                        m.insert("shoulder".into(), s);
                    }
                }
            }
        }
        let holds_motor = match el.child("motormount") {
            Some(mount) => self.mount(el, &mount, &mut m)?,
            None => None,
        };
        Ok(Body {
            el: el.clone(),
            json: m,
            length_m: length,
            fore,
            aft,
            kind,
            holds_motor,
            solid,
        })
    }

    /// A tube's `<motormount>`: the mount of the default configuration's motor becomes the
    /// design's motor mount (a second motor is refused). Where the default configuration
    /// has no motor (a design not yet given one), the first tube OpenRocket marks as a
    /// mount is the design's, so that a motor given to the flight has its place. A body
    /// tube that holds the motor itself is not a mount in the design format: its overhang
    /// is returned, and the stage gives the tube a massless inner tube of its bore as the
    /// mount.
    fn mount(
        &mut self,
        tube: &El<'_, '_>,
        mount: &El<'_, '_>,
        m: &mut Component,
    ) -> Result<Option<f64>, DesignError> {
        if self.has_motor {
            let holds_default = mount
                .children()
                .any(|c| c.tag() == "motor" && c.attribute("configid") == self.config.as_deref());
            if !holds_default {
                return Ok(None);
            }
            if self.mount_placed {
                return Err(tube.refuse(
                    "a second motor in the default flight configuration (hpr flies one motor)",
                ));
            }
        } else if self.mount_placed {
            self.note(format!(
                "{}: also a motor mount in OpenRocket; hpr flies one motor, in the first.",
                tube.name()
            ));
            return Ok(None);
        }
        self.mount_placed = true;
        let overhang = mount.num("overhang")?.unwrap_or(0.0);
        if tube.tag() == "bodytube" {
            self.note(format!(
                "{}: it holds the motor itself; a massless inner tube of its bore is its motor \
                 mount.",
                tube.name()
            ));
            return Ok(Some(overhang));
        }
        m.insert("motor_mount".into(), json!({ "overhang_m": overhang }));
        Ok(None)
    }
}

/// An override's mass and CG, where given (the design format's `override` fields).
pub(super) fn overrides(mass: Option<f64>, cg: Option<f64>) -> Component {
    let mut o = Map::new();
    if let Some(v) = mass {
        o.insert("mass_kg".into(), json!(v));
    }
    if let Some(v) = cg {
        o.insert("cg_m".into(), json!(v));
    }
    o
}

/// The `<motor>` of configuration `config` (any, if `None`) anywhere under `el`.
pub(super) fn find_motor<'a, 'i>(el: &El<'a, 'i>, config: Option<&str>) -> Option<El<'a, 'i>> {
    for c in el.children() {
        if c.tag() == "motor" && (config.is_none() || c.attribute("configid") == config) {
            return Some(c);
        }
        if let Some(m) = find_motor(&c, config) {
            return Some(m);
        }
    }
    None
}

/// The design format's nose shape and shape parameter of an OpenRocket `<shape>`.
fn shape(el: &El<'_, '_>) -> Result<(&'static str, Option<f64>), DesignError> {
    let p = el.num("shapeparameter")?;
    Ok(match el.text("shape").unwrap_or("conical") {
        "conical" => ("conical", None),
        // OpenRocket's ogive parameter: 1 the tangent ogive (its default), below 1 a secant.
        "ogive" => ("ogive", p.filter(|&p| p != 1.0)),
        "ellipsoid" => ("elliptical", None),
        "power" => ("power_series", Some(p.unwrap_or(0.5))),
        "parabolic" => ("parabolic", Some(p.unwrap_or(1.0))),
        "haack" => ("haack", Some(p.unwrap_or(0.0))),
        other => return Err(el.bad("shape", format!("unknown shape \"{other}\""))),
    })
}

/// A transition's or nose cone's shoulder on `side` (fore or aft), if it has a length.
fn shoulder(el: &El<'_, '_>, side: &str) -> Result<Option<Value>, DesignError> {
    let length = el.num(&format!("{side}shoulderlength"))?.unwrap_or(0.0);
    if length <= 0.0 {
        return Ok(None);
    }
    let r = el.req(&format!("{side}shoulderradius"))?;
    // A shoulder drawn with no wall weighs nothing in OpenRocket; 0.1 µm of wall weighs
    // micrograms.
    let wall = el.num(&format!("{side}shoulderthickness"))?.unwrap_or(r);
    Ok(Some(json!({
        "length_m": length,
        "outer_diameter_m": 2.0 * r,
        "wall_thickness_m": if wall > 0.0 { wall } else { THIN_WALL_M },
        "capped": el.flag(&format!("{side}shouldercapped")),
    })))
}

/// Resolve the body components' radii: `auto` with its value as given; a bare `auto` (files
/// before 1.8) from the neighbours as OpenRocket does (a tube or a transition's fore end from
/// the component before it, the last stage's last for a stage's first, its aft end, and a
/// nose cone's base, from the one after).
fn resolve_radii(
    stage: &El<'_, '_>,
    bodies: &mut [Body],
    before_stage: Option<f64>,
) -> Result<(), DesignError> {
    let value = |a: Option<Auto>| match a {
        Some(Auto::Value(v)) => Some(v),
        _ => None,
    };
    for _ in 0..bodies.len() + 1 {
        for i in 0..bodies.len() {
            let before = if i > 0 {
                value(bodies[i - 1].aft)
            } else {
                before_stage
            };
            let after = bodies.get(i + 1).and_then(|b| value(b.fore));
            let b = &mut bodies[i];
            match b.kind {
                "body_tube" if b.fore == Some(Auto::Bare) => {
                    if let Some(r) = before.or(after) {
                        (b.fore, b.aft) = (Some(Auto::Value(r)), Some(Auto::Value(r)));
                    }
                }
                _ => {
                    if b.fore == Some(Auto::Bare) {
                        if let Some(r) = before {
                            b.fore = Some(Auto::Value(r));
                        }
                    }
                    if b.aft == Some(Auto::Bare) {
                        if let Some(r) = after {
                            b.aft = Some(Auto::Value(r));
                        }
                    }
                }
            }
        }
    }
    for b in bodies.iter_mut() {
        let (Some(aft), fore) = (value(b.aft), value(b.fore)) else {
            return Err(stage.bad(
                "subcomponents",
                format!(
                    "the radius of \"{}\" is automatic and no neighbour gives it",
                    b.json["name"].as_str().unwrap_or("?")
                ),
            ));
        };
        match b.kind {
            "body_tube" => {
                if b.solid {
                    b.json.insert("wall_thickness_m".into(), json!(aft));
                }
                b.json.insert("outer_diameter_m".into(), json!(2.0 * aft))
            }
            "nose_cone" => b.json.insert("base_diameter_m".into(), json!(2.0 * aft)),
            _ => {
                let fore = fore.ok_or_else(|| {
                    stage.bad(
                        "subcomponents",
                        "a transition's fore radius is automatic and no neighbour gives it",
                    )
                })?;
                b.json.insert("fore_diameter_m".into(), json!(2.0 * fore));
                b.json.insert("aft_diameter_m".into(), json!(2.0 * aft))
            }
        };
    }
    Ok(())
}

/// A nose cone's or transition's inner radius along it, as OpenRocket computes it for the
/// automatic radius of a ring inside (`max(r(x) − t, 0)`, 0 if filled), from its JSON.
fn shell_inner_radius(
    json: &Component,
    kind: &str,
    length_m: f64,
) -> Option<Box<dyn Fn(f64) -> f64>> {
    let shape: RawNoseShape = serde_json::from_value(json.get("shape")?.clone()).ok()?;
    let nose = shape.with_parameter(json.get("shape_parameter").and_then(Value::as_f64));
    let wall = if json.get("filled").and_then(Value::as_bool) == Some(true) {
        f64::INFINITY
    } else {
        json.get("wall_thickness_m")?.as_f64()?
    };
    let radius = |k: &str| json.get(k).and_then(Value::as_f64).map(|d| d / 2.0);
    let (fore, aft) = match kind {
        "nose_cone" => (0.0, radius("base_diameter_m")?),
        "transition" => (radius("fore_diameter_m")?, radius("aft_diameter_m")?),
        _ => return None,
    };
    let clip = if json.get("clipped").and_then(Value::as_bool) == Some(true) && clippable(nose) {
        clip_length(nose, length_m, fore, aft)
    } else {
        0.0
    };
    Some(Box::new(move |x| {
        (tapered_radius(nose, length_m, fore, aft, clip, x) - wall).max(0.0)
    }))
}
