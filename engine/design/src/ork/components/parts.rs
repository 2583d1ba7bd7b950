//! The parts on and in the body components (fins, lugs, rail buttons, inner tubes,
//! rings, bulkheads, packed parts): each mapped onto the design format's, placed along its
//! parent as OpenRocket places it, one component per instance.

use super::super::parse_number;
use super::cluster;
use super::fins::fin_area_m2;
use super::{Auto, Component, Context, DesignError, El, Parent, THIN_WALL_M};
use serde_json::{json, Value};

impl Context {
    /// The parts on and in component `el` (`parent`: what they read of it), in the order
    /// OpenRocket lists them.
    pub(super) fn parts(
        &mut self,
        el: &El<'_, '_>,
        parent: &Parent,
    ) -> Result<Vec<Value>, DesignError> {
        let mut out = Vec::new();
        // The fore end and length of the last part placed, for OpenRocket's "after".
        let mut previous: Option<(f64, f64)> = None;
        let Some(subs) = el.child("subcomponents") else {
            return Ok(out);
        };
        let children: Vec<El<'_, '_>> = subs.children().collect();
        for el in &children {
            if !parent.on_body
                && matches!(
                    el.tag(),
                    "trapezoidfinset"
                        | "ellipticalfinset"
                        | "freeformfinset"
                        | "launchlug"
                        | "railbutton"
                )
            {
                return Err(el.refuse("an outside part on an inner tube"));
            }
            let (method, value) = position(el)?;
            // The fore end of a part of this length, m aft of the parent's fore end.
            let fore_of = |length: f64| match method {
                "top" => value,
                "middle" => value + (parent.length_m - length) / 2.0,
                "bottom" => value + parent.length_m - length,
                "after" => previous.map_or(0.0, |(x, l)| x + l) + value,
                _ => value - parent.front_m, // absolute
            };
            let made = self.part(el, parent, &children, &fore_of)?;
            let Some((mut part, length)) = made else {
                continue;
            };
            let Some(length) = self.no_length(el, &mut part, length) else {
                continue;
            };
            self.no_wall_weighs_nothing(el, &mut part);
            let fore = fore_of(length);
            let count = el
                .num("instancecount")?
                .filter(|_| {
                    matches!(
                        el.tag(),
                        "launchlug" | "railbutton" | "centeringring" | "bulkhead"
                    )
                })
                .unwrap_or(1.0);
            let separation = el.num("instanceseparation")?.unwrap_or(0.0);
            previous = Some((fore, length));
            if matches!(el.tag(), "innertube" | "tubecoupler") {
                let inner = part["outer_diameter_m"].as_f64().unwrap_or(0.0) / 2.0
                    - part["wall_thickness_m"].as_f64().unwrap_or(0.0);
                let tube = Parent {
                    length_m: length,
                    front_m: parent.front_m + fore,
                    ring_r: Some(inner),
                    inner_at: None,
                    packed_r: Some(inner),
                    on_body: false,
                    surface_r: None,
                };
                let children = self.parts(el, &tube)?;
                if !children.is_empty() {
                    part.insert("children".into(), Value::Array(children));
                }
            }
            let (from, offset) = match method {
                // A rail button's fore end, half its diameter before the center OpenRocket
                // places.
                _ if el.tag() == "railbutton" => (
                    "top",
                    fore - part["outer_diameter_m"].as_f64().unwrap_or(0.0) / 2.0,
                ),
                "after" => ("top", fore),
                "absolute" => ("nose_tip", value),
                m => (m, value),
            };
            if !(count >= 1.0 && count.fract() == 0.0 && count <= 64.0) {
                return Err(el.bad(
                    "instancecount",
                    format!("must be a whole number from 1 to 64 (got {count})"),
                ));
            }
            let attached = if el.tag().ends_with("finset") {
                self.fin_attachments(el, &part, fore, length, parent)?
            } else {
                Vec::new()
            };
            let id = part["id"].as_str().unwrap_or("part").to_owned();
            for i in 0..count as usize {
                let mut p = part.clone();
                if i > 0 {
                    p.insert("id".into(), json!(self.id(&format!("{id} {}", i + 1))));
                }
                p.insert(
                    "position".into(),
                    json!({ "from": from, "offset_m": offset + i as f64 * separation }),
                );
                out.push(Value::Object(p));
            }
            out.extend(attached.into_iter().map(Value::Object));
        }
        Ok(out)
    }

    /// A tube with no wall, or a ring as wide inside as outside, which OpenRocket draws and
    /// weighs at nothing: here a wall of [`THIN_WALL_M`] and no mass (an override still
    /// weighs it), with a note; the design format's shapes need a wall.
    fn no_wall_weighs_nothing(&mut self, el: &El<'_, '_>, part: &mut Component) {
        let num = |p: &Component, k: &str| p.get(k).and_then(Value::as_f64);
        let fixed = match part.get("type").and_then(Value::as_str) {
            Some("inner_tube") if num(part, "wall_thickness_m").is_some_and(|t| t <= 0.0) => {
                part.insert("wall_thickness_m".into(), json!(THIN_WALL_M));
                true
            }
            Some("centering_ring") => {
                match (num(part, "outer_diameter_m"), num(part, "inner_diameter_m")) {
                    (Some(od), Some(id)) if id >= od && od > 0.0 => {
                        part.insert("inner_diameter_m".into(), json!(od - 2.0 * THIN_WALL_M));
                        true
                    }
                    _ => false,
                }
            }
            _ => false,
        };
        if fixed {
            part.remove("material");
            part.insert("mass_kg".into(), json!(0.0));
            self.note(format!(
                "{}: no wall, so it weighs nothing (as in OpenRocket); drawn with a wall of 0.1 µm.",
                el.name()
            ));
        }
    }

    /// A part OpenRocket draws with no length (a marker, or a point mass): left out, with a
    /// note, if it weighs nothing (no volume, a zero override or mass); otherwise
    /// [`THIN_WALL_M`] long, its mass where OpenRocket puts it. The length to place it by.
    fn no_length(&mut self, el: &El<'_, '_>, part: &mut Component, length: f64) -> Option<f64> {
        let holds = el
            .child("subcomponents")
            .is_some_and(|s| s.children().next().is_some());
        if length > 0.0 || holds || !part.contains_key("length_m") {
            return Some(length);
        }
        let given = part
            .get("override")
            .and_then(|o| o.get("mass_kg"))
            .or_else(|| part.get("mass_kg"))
            .and_then(Value::as_f64);
        if given.is_some_and(|m| m > 0.0) {
            part.insert("length_m".into(), json!(THIN_WALL_M));
            self.note(format!(
                "{}: no length; its mass is put in 0.1 µm of it, where OpenRocket has it.",
                el.name()
            ));
            Some(THIN_WALL_M)
        } else {
            self.note(format!(
                "{}: no length, so it weighs nothing; left out.",
                el.name()
            ));
            None
        }
    }

    /// A recovery device's deployment in the default flight configuration (its own
    /// `<deploymentconfiguration>` for it, else its default), as the design format's
    /// `deploy`: apogee and altitude events with OpenRocket's delay as the lag, launch as a
    /// time after launch, ejection as the default motor's delay after burnout. `None` (with
    /// a note) where it never deploys in hpr's flight: OpenRocket's "never", a stage
    /// separation (stages are not separated), a plugged motor's ejection.
    fn deployment(&mut self, el: &El<'_, '_>) -> Result<Option<Value>, DesignError> {
        let config = self.config.clone();
        let chosen = el
            .children()
            .find(|c| {
                c.tag() == "deploymentconfiguration"
                    && config.is_some()
                    && c.attribute("configid") == config.as_deref()
            })
            .unwrap_or_else(|| el.clone());
        let event = chosen.text("deployevent").unwrap_or("ejection").to_owned();
        let delay = chosen.num("deploydelay")?.unwrap_or(0.0).max(0.0);
        let altitude = chosen.num("deployaltitude")?.unwrap_or(0.0);
        let name = el.name().to_owned();
        let (trigger, lag, when) = match event.as_str() {
            "apogee" => (json!("apogee"), delay, "at apogee".to_owned()),
            "altitude" => (
                json!({ "height_m": altitude.max(0.0) }),
                delay,
                format!("at {altitude} m on the way down"),
            ),
            "launch" => (
                json!({ "time_s": delay }),
                0.0,
                format!("{delay} s after launch"),
            ),
            "ejection" => match (self.has_motor, self.motor_delay_s) {
                (true, Some(d)) => (
                    json!({ "delay_s": d }),
                    delay,
                    format!("at the motor's ejection, {d} s after burnout"),
                ),
                (true, None) => {
                    self.note(format!(
                        "{name}: OpenRocket deploys it at the motor's ejection, and the motor is \
                         plugged: it does not deploy."
                    ));
                    return Ok(None);
                }
                (false, _) => (
                    json!("motor_delay"),
                    delay,
                    "at the motor's ejection, its first listed delay after burnout".to_owned(),
                ),
            },
            other => {
                self.note(format!(
                    "{name}: OpenRocket deploys it on \"{other}\", which hpr's flight has not: it \
                     does not deploy."
                ));
                return Ok(None);
            }
        };
        let after = if lag > 0.0 {
            format!(", open {lag} s later")
        } else {
            String::new()
        };
        self.note(format!(
            "{name}: deploys {when}{after} (as `fly` flies it; a scenario lists its own \
             parachutes)."
        ));
        Ok(Some(json!({ "trigger": trigger, "lag_s": lag })))
    }

    /// One part and its length along the axis (what OpenRocket positions it by); `None` for
    /// an element that is not a component.
    fn part(
        &mut self,
        el: &El<'_, '_>,
        parent: &Parent,
        siblings: &[El<'_, '_>],
        fore_of: &dyn Fn(f64) -> f64,
    ) -> Result<Option<(Component, f64)>, DesignError> {
        let tag = el.tag();
        let mut m = self.common(el)?;
        let length;
        match tag {
            "trapezoidfinset" | "ellipticalfinset" | "freeformfinset" => {
                m.insert("type".into(), json!("fin_set"));
                m.insert("count".into(), json!(fin_count(el)?));
                m.insert("thickness_m".into(), json!(el.req("thickness")?));
                let cross = el.text("crosssection").unwrap_or("square");
                match cross {
                    "square" | "rounded" | "airfoil" => {
                        m.insert("cross_section".into(), json!(cross))
                    }
                    other => {
                        return Err(el.bad(
                            "crosssection",
                            format!("cross-section \"{other}\" cannot be imported"),
                        ))
                    }
                };
                m.insert("cant_deg".into(), json!(el.num("cant")?.unwrap_or(0.0)));
                let rotation = match el.num("angleoffset")? {
                    Some(a) => a,
                    None => el.num("rotation")?.unwrap_or(0.0),
                };
                m.insert("rotation_deg".into(), json!(rotation));
                match tag {
                    "trapezoidfinset" => {
                        length = el.req("rootchord")?;
                        m.insert("planform".into(), json!("trapezoidal"));
                        m.insert("root_chord_m".into(), json!(length));
                        m.insert("tip_chord_m".into(), json!(el.req("tipchord")?));
                        m.insert("span_m".into(), json!(el.req("height")?));
                        m.insert(
                            "sweep_m".into(),
                            json!(el.num("sweeplength")?.unwrap_or(0.0)),
                        );
                    }
                    "ellipticalfinset" => {
                        length = el.req("rootchord")?;
                        m.insert("planform".into(), json!("elliptical"));
                        m.insert("root_chord_m".into(), json!(length));
                        m.insert("span_m".into(), json!(el.req("height")?));
                    }
                    _ => {
                        let points = fin_points(el)?;
                        length = points.last().map_or(0.0, |p| p[0]);
                        m.insert("planform".into(), json!("free_form"));
                        m.insert("points_m".into(), json!(points));
                    }
                }
                // OpenRocket's volume of a fin of each cross-section, relative to the flat
                // plate (`FinSet.CrossSection`): a rounded fin 0.99 of it, an airfoil 0.85.
                let relative_volume = match cross {
                    "rounded" => 0.99,
                    "airfoil" => 0.85,
                    _ => 1.0,
                };
                if relative_volume != 1.0 {
                    if let Some(mat) = m.remove("material") {
                        let density = mat["density_kg_m3"].as_f64().unwrap_or(0.0);
                        let area = fin_area_m2(&m, length);
                        m.insert(
                            "mass_kg".into(),
                            json!(
                                relative_volume
                                    * m["count"].as_f64().unwrap_or(1.0)
                                    * area
                                    * m["thickness_m"].as_f64().unwrap_or(0.0)
                                    * density
                            ),
                        );
                    }
                }
            }
            "launchlug" => {
                length = el.req("length")?;
                let r = el.req("radius")?;
                m.insert("type".into(), json!("launch_lug"));
                m.insert("length_m".into(), json!(length));
                m.insert("outer_diameter_m".into(), json!(2.0 * r));
                m.insert("wall_thickness_m".into(), json!(el.req("thickness")?));
                m.insert("angle_deg".into(), json!(angle(el)?));
            }
            "railbutton" => {
                // OpenRocket places a rail button by its center (its length is 0); the parts
                // loop turns that into the fore end the design format places it by.
                length = 0.0;
                let d = el.req("outerdiameter")?;
                let height = el.req("height")?;
                m.insert("type".into(), json!("rail_button"));
                m.insert("outer_diameter_m".into(), json!(d));
                m.insert("height_m".into(), json!(height));
                m.insert("angle_deg".into(), json!(angle(el)?));
                if el.text("overridemass").is_none() {
                    if let Some(mat) = m.remove("material") {
                        let density = mat["density_kg_m3"].as_f64().unwrap_or(0.0);
                        m.insert(
                            "mass_kg".into(),
                            json!(density * rail_button_volume(el, d, height)?),
                        );
                    }
                }
            }
            "innertube" | "tubecoupler" => {
                length = el.req("length")?;
                let r = auto_size(el, "outerradius", parent.ring_r)?;
                let wall = el.req("thickness")?;
                if tag == "innertube" {
                    let cluster = cluster::offsets(el, r)?;
                    if cluster.len() > 1 {
                        m.insert("cluster".into(), json!(cluster));
                    }
                    radial(el, &mut m)?;
                }
                m.insert("type".into(), json!("inner_tube"));
                m.insert("length_m".into(), json!(length));
                m.insert("outer_diameter_m".into(), json!(2.0 * r));
                m.insert("wall_thickness_m".into(), json!(wall));
                if let Some(mount) = el.child("motormount") {
                    self.mount(el, &mount, &mut m)?;
                }
            }
            "centeringring" | "engineblock" => {
                length = el.req("length")?;
                let r = ring_radius(el, parent, fore_of(length), length)?;
                let inner = if tag == "engineblock" {
                    r - el.req("thickness")?
                } else {
                    match el.auto("innerradius")? {
                        Some(Auto::Value(v)) => v,
                        Some(Auto::Bare) => ring_inner_auto(siblings)?,
                        None => return Err(el.bad("innerradius", "is missing")),
                    }
                };
                m.insert("type".into(), json!("centering_ring"));
                m.insert("length_m".into(), json!(length));
                m.insert("outer_diameter_m".into(), json!(2.0 * r));
                m.insert("inner_diameter_m".into(), json!(2.0 * inner));
            }
            "bulkhead" => {
                length = el.req("length")?;
                let r = ring_radius(el, parent, fore_of(length), length)?;
                m.insert("type".into(), json!("bulkhead"));
                m.insert("length_m".into(), json!(length));
                m.insert("outer_diameter_m".into(), json!(2.0 * r));
            }
            "masscomponent" | "parachute" | "shockcord" | "streamer" => {
                length = el.req("packedlength")?;
                let radius = auto_size(el, "packedradius", parent.packed_r)?;
                m.insert("length_m".into(), json!(length));
                m.insert("radius_m".into(), json!(radius));
                radial(el, &mut m)?;
                let surface = |el: &El<'_, '_>| -> Result<f64, DesignError> {
                    density(el, "material", "surface")
                };
                match tag {
                    "masscomponent" => {
                        m.insert("type".into(), json!("mass_component"));
                        m.insert("mass_kg".into(), json!(el.req("mass")?));
                    }
                    "parachute" => {
                        let d = el.req("diameter")?;
                        let cd = match el.auto("cd")? {
                            Some(Auto::Value(v)) => v,
                            _ => 0.8,
                        };
                        let lines = el.num("linecount")?.unwrap_or(0.0)
                            * el.num("linelength")?.unwrap_or(1.5 * d)
                            * density(el, "linematerial", "line").unwrap_or(0.0);
                        let canopy = std::f64::consts::PI * (d / 2.0).powi(2) * surface(el)?;
                        m.insert("type".into(), json!("parachute"));
                        m.insert("canopy_diameter_m".into(), json!(d));
                        m.insert("cd".into(), json!(cd));
                        m.insert("mass_kg".into(), json!(canopy + lines));
                        if let Some(deploy) = self.deployment(el)? {
                            m.insert("deploy".into(), deploy);
                        }
                    }
                    "shockcord" => {
                        m.insert("type".into(), json!("shock_cord"));
                        m.insert(
                            "linear_density_kg_m".into(),
                            json!(density(el, "material", "line")?),
                        );
                        m.insert("cord_length_m".into(), json!(el.req("cordlength")?));
                    }
                    _ => {
                        // OpenRocket's streamer: drag cd × the strip's area, cd by default
                        // 0.034 (ρ + 0.025)/0.105 (L + 1)/L, at most 0.4 (`Streamer`).
                        let (l, w) = (el.req("striplength")?, el.req("stripwidth")?);
                        let rho = surface(el)?;
                        let cd = match el.auto("cd")? {
                            Some(Auto::Value(v)) => v,
                            _ if l > 0.0 => {
                                (0.034 * ((rho + 0.025) / 0.105) * (l + 1.0) / l).min(0.4)
                            }
                            _ => 0.0,
                        };
                        let area = l * w;
                        m.insert("type".into(), json!("parachute"));
                        m.insert(
                            "canopy_diameter_m".into(),
                            json!((4.0 * area / std::f64::consts::PI).sqrt()),
                        );
                        m.insert("cd".into(), json!(cd));
                        m.insert("mass_kg".into(), json!(area * rho));
                        if let Some(deploy) = self.deployment(el)? {
                            m.insert("deploy".into(), deploy);
                        }
                        self.note(format!(
                            "{}: a streamer, flown as a canopy of its drag, cd {} × the strip's \
                             {} m² (OpenRocket's).",
                            el.name(),
                            super::super::simulation::round(cd),
                            super::super::simulation::round(area)
                        ));
                    }
                }
                m.remove("material");
            }
            "tubefinset" => return Err(el.refuse("a tube fin set")),
            "podset" | "parallelstage" | "boosterset" => {
                return Err(el.refuse("a pod or a parallel stage"))
            }
            "nosecone" | "bodytube" | "transition" => {
                return Err(el.refuse("a body component inside another component"))
            }
            other => {
                self.note(format!("{}: a <{other}> is not imported.", el.name()));
                return Ok(None);
            }
        }
        Ok(Some((m, length)))
    }
}

/// The number of fins (`<fincount>`, or `<instancecount>`).
fn fin_count(el: &El<'_, '_>) -> Result<u32, DesignError> {
    let n = match el.num("fincount")? {
        Some(n) => n,
        None => el.req("instancecount")?,
    };
    if n >= 1.0 && n.fract() == 0.0 && n <= 64.0 {
        Ok(n as u32)
    } else {
        Err(el.bad(
            "fincount",
            format!("must be a whole number of fins (got {n})"),
        ))
    }
}

/// A free-form fin's outline from `<finpoints>`.
fn fin_points(el: &El<'_, '_>) -> Result<Vec<[f64; 2]>, DesignError> {
    let points = el
        .child("finpoints")
        .ok_or_else(|| el.bad("finpoints", "is missing"))?;
    let mut out = Vec::new();
    for p in points.children().filter(|p| p.tag() == "point") {
        let coord = |a: &str| {
            p.attribute_number(a)
                .ok_or_else(|| el.bad("finpoints", format!("a point without a finite {a}")))
        };
        out.push([coord("x")?, coord("y")?]);
    }
    if out.len() < 3 {
        return Err(el.bad("finpoints", "an outline needs at least three points"));
    }
    Ok(out)
}

/// A rail button's volume as OpenRocket computes it: the flange and the base (standoff) at
/// the outer diameter, the waist between them at the inner, and the screw's head.
fn rail_button_volume(el: &El<'_, '_>, d: f64, height: f64) -> Result<f64, DesignError> {
    let inner_d = el.num("innerdiameter")?.unwrap_or(d).min(d);
    let flange = el.num("flangeheight")?.unwrap_or(0.0);
    let base = el.num("baseheight")?.unwrap_or(0.0);
    let screw = el.num("screwheight")?.unwrap_or(0.0);
    let disc = |diameter: f64, h: f64| std::f64::consts::PI * (diameter / 2.0).powi(2) * h;
    let waist = (height - flange - base).max(0.0);
    Ok(disc(d, flange) + disc(inner_d, waist) + disc(d, base) + 2.0 / 3.0 * disc(d, screw))
}

/// A part's axis off its parent's: OpenRocket's radial position and direction.
fn radial(el: &El<'_, '_>, m: &mut Component) -> Result<(), DesignError> {
    let offset = el.num("radialposition")?.unwrap_or(0.0);
    m.insert("radial_offset_m".into(), json!(offset));
    m.insert(
        "radial_angle_deg".into(),
        json!(el.num("radialdirection")?.unwrap_or(0.0)),
    );
    Ok(())
}

/// A part's angle about the axis, degrees (`<angleoffset>`, or the older `<radialdirection>`).
fn angle(el: &El<'_, '_>) -> Result<f64, DesignError> {
    Ok(match el.num("angleoffset")? {
        Some(a) => a,
        None => el.num("radialdirection")?.unwrap_or(0.0),
    })
}

/// The density of material element `tag`, which must be of kind `kind` (surface, line).
pub(super) fn density(el: &El<'_, '_>, tag: &str, kind: &str) -> Result<f64, DesignError> {
    let mat = el.child(tag).ok_or_else(|| el.bad(tag, "is missing"))?;
    if mat.attribute("type").is_some_and(|t| t != kind) {
        return Err(el.bad(tag, format!("must be a {kind} material")));
    }
    mat.attribute_number("density")
        .ok_or_else(|| el.bad(tag, "has no finite density"))
}

/// A size OpenRocket may compute (`auto`): its value, or for a bare `auto` what the parent
/// gives (`fallback`: a ring's outer radius is the parent's inner radius, a packed part's
/// radius the parent's, by OpenRocket's rule for each kind of parent).
fn auto_size(el: &El<'_, '_>, tag: &str, fallback: Option<f64>) -> Result<f64, DesignError> {
    match el.auto(tag)? {
        Some(Auto::Value(v)) => Ok(v),
        Some(Auto::Bare) => fallback.ok_or_else(|| {
            el.bad(
                tag,
                "a bare auto inside a tapered part cannot be resolved; give the radius",
            )
        }),
        None => Err(el.bad(tag, "is missing")),
    }
}

/// A ring's or bulkhead's outer radius; a bare `auto` inside a nose cone or transition is
/// OpenRocket's: the smaller of the parent's inner radii at the part's two ends (each kept
/// within the parent), `fore_m` being the part's fore end aft of the parent's.
fn ring_radius(
    el: &El<'_, '_>,
    parent: &Parent,
    fore_m: f64,
    length_m: f64,
) -> Result<f64, DesignError> {
    if let (Some(Auto::Bare), None, Some(inner)) =
        (el.auto("outerradius")?, parent.ring_r, &parent.inner_at)
    {
        // (A parent of no or negative length, which the validation refuses, keeps its fore end.)
        let at = |x: f64| inner(x.clamp(0.0, parent.length_m.max(0.0)));
        return Ok(at(fore_m).min(at(fore_m + length_m)));
    }
    auto_size(el, "outerradius", parent.ring_r)
}

/// A centering ring's automatic inner radius: the largest outer radius of the inner tubes
/// beside it, 0 if none (OpenRocket takes those that overlap the ring along the axis; a
/// ring beside an inner tube it does not overlap takes that tube's radius here).
fn ring_inner_auto(siblings: &[El<'_, '_>]) -> Result<f64, DesignError> {
    let mut r: f64 = 0.0;
    for s in siblings.iter().filter(|s| s.tag() == "innertube") {
        if let Some(Auto::Value(v)) = s.auto("outerradius")? {
            r = r.max(v);
        }
    }
    Ok(r)
}

/// A part's position: OpenRocket's method (top, middle, bottom, after, absolute) and value.
fn position(el: &El<'_, '_>) -> Result<(&'static str, f64), DesignError> {
    let found = el
        .child("axialoffset")
        .map(|p| (p.attribute("method"), "axialoffset", p))
        .or_else(|| {
            el.child("position")
                .map(|p| (p.attribute("type"), "position", p))
        });
    let Some((method, tag, p)) = found else {
        let default = if el.tag().ends_with("finset") {
            "bottom"
        } else {
            "top"
        };
        return Ok((default, 0.0));
    };
    let method = match method.unwrap_or("top") {
        "top" => "top",
        "middle" => "middle",
        "bottom" => "bottom",
        "after" => "after",
        "absolute" => "absolute",
        other => return Err(el.bad(tag, format!("unknown position method \"{other}\""))),
    };
    let text = p.own_text();
    let value = if text.is_empty() {
        0.0
    } else {
        parse_number(text).ok_or_else(|| el.bad(tag, format!("not a finite number: \"{text}\"")))?
    };
    Ok((method, value))
}
