//! What OpenRocket weighs with a fin set beside its plates: the share of the plate a
//! cross-section fills, the fin tabs and the fillets (`FinSet.calculateCM`).

use super::super::parse_number;
use super::parts::density;
use super::{Component, Context, DesignError, El, Parent};
use serde_json::json;

impl Context {
    /// What OpenRocket weighs with a fin set beside its plates, as parts of the parent that
    /// sit where it puts them: the fin tabs (each the rectangle `tablength × tabheight` below
    /// the root, as thick as the fin, of the fins' material) and the fillets (each root's two
    /// concave fillets of radius `filletradius`, of the fillet material, by OpenRocket's
    /// cross-section and its centroid `r + r_f/5` off the axis). Each becomes one mass
    /// component for the whole set, spread round the axis (the fins' own spacing), with the
    /// inertia of that ring about its center. None where an override gives the set's mass
    /// (OpenRocket's override covers them). `fore` is the set's fore end from the parent's.
    pub(super) fn fin_attachments(
        &mut self,
        el: &El<'_, '_>,
        fins: &Component,
        fore: f64,
        root_m: f64,
        parent: &Parent,
    ) -> Result<Vec<Component>, DesignError> {
        let mut out = Vec::new();
        if el.text("overridemass").is_some() {
            return Ok(out);
        }
        let Some((r_fore, r_aft)) = parent.surface_r else {
            return Ok(out);
        };
        // The body's radius at `x` from the parent's fore end (linear between its ends).
        let body_r = |x: f64| {
            let t = if parent.length_m > 0.0 {
                (x / parent.length_m).clamp(0.0, 1.0)
            } else {
                0.0
            };
            r_fore + (r_aft - r_fore) * t
        };
        let count = fins["count"].as_f64().unwrap_or(1.0);
        let thickness = fins["thickness_m"].as_f64().unwrap_or(0.0);
        let name = el.name().to_owned();
        // A ring of mass `mass_kg` from radius `r_in` to `r_out` and `length` long, spread
        // round the axis: its inertia about its center, [axial, transverse].
        let ring = |mass_kg: f64, r_in: f64, r_out: f64, length: f64| {
            let mean_r2 = if r_out > r_in {
                (r_out.powi(3) - r_in.powi(3)) / (3.0 * (r_out - r_in))
            } else {
                r_out * r_out
            };
            [
                mass_kg * mean_r2,
                mass_kg * (mean_r2 / 2.0 + length * length / 12.0),
            ]
        };
        let mut attach = |cx: &mut Context,
                          what: &str,
                          mass_kg: f64,
                          at: f64,
                          length: f64,
                          inertia: [f64; 2]| {
            let mut m = Component::new();
            m.insert("id".into(), json!(cx.id(&format!("{name} {what}"))));
            m.insert("type".into(), json!("mass_component"));
            m.insert("name".into(), json!(format!("{name} ({what})")));
            m.insert("mass_kg".into(), json!(mass_kg));
            m.insert("length_m".into(), json!(length));
            // The packed cylinder only has to fit the parent; the ring's inertia is given.
            let fit = parent.ring_r.unwrap_or(r_fore.max(r_aft)) / 2.0;
            m.insert("radius_m".into(), json!(fit.max(1e-6)));
            m.insert("inertia_kg_m2".into(), json!(inertia));
            m.insert(
                "position".into(),
                json!({ "from": "top", "offset_m": fore + at }),
            );
            out.push(m);
        };

        let height = el.num("tabheight")?.unwrap_or(0.0);
        let tab_length = el.num("tablength")?.unwrap_or(0.0);
        let tab_density = material_density(el, "material")?;
        if let (true, Some(density)) = (
            height > 0.0 && tab_length > 0.0 && height * tab_length >= 1e-8,
            tab_density,
        ) {
            let (method, offset) = tab_position(el)?;
            // OpenRocket's AxialMethod against the root chord. As OpenRocket's mass model
            // does, the tab is taken as saved, even where it runs past the root.
            let front = match method {
                "top" => offset,
                "middle" => offset + (root_m - tab_length) / 2.0,
                _ => offset + root_m - tab_length,
            };
            let r = body_r(fore + front + tab_length / 2.0);
            let mass = count * tab_length * height * thickness * density;
            let inertia = ring(mass, (r - height).max(0.0), r, tab_length);
            attach(self, "fin tabs", mass, front, tab_length, inertia);
        }
        let fillet_r = el.num("filletradius")?.unwrap_or(0.0);
        if fillet_r > 0.0 && root_m > 0.0 {
            let Some(density) = material_density(el, "filletmaterial")? else {
                self.note(format!(
                    "{name}: its fillets have no material in the file; their mass is left out."
                ));
                return Ok(out);
            };
            let b = body_r(fore + root_m / 2.0);
            let area = fillet_cross_section_m2(fillet_r, b);
            let mass = count * area * root_m * density;
            let y = b + fillet_r / 5.0;
            let inertia = ring(mass, y, y, root_m);
            attach(self, "fillets", mass, 0.0, root_m, inertia);
        }
        Ok(out)
    }
}

/// One fin's planform area, m², from the fin set's JSON (`root_m` its root chord).
pub(super) fn fin_area_m2(m: &Component, root_m: f64) -> f64 {
    let num = |k: &str| m[k].as_f64().unwrap_or(0.0);
    match m["planform"].as_str() {
        Some("trapezoidal") => 0.5 * (root_m + num("tip_chord_m")) * num("span_m"),
        Some("elliptical") => std::f64::consts::FRAC_PI_4 * root_m * num("span_m"),
        _ => {
            // The outline closed by the root (shoelace).
            let pts: Vec<[f64; 2]> = m["points_m"]
                .as_array()
                .map(|a| {
                    a.iter()
                        .map(|p| [p[0].as_f64().unwrap_or(0.0), p[1].as_f64().unwrap_or(0.0)])
                        .collect()
                })
                .unwrap_or_default();
            let mut twice = 0.0;
            for (i, a) in pts.iter().enumerate() {
                let b = pts[(i + 1) % pts.len()];
                twice += a[0] * b[1] - b[0] * a[1];
            }
            (0.5 * twice).abs()
        }
    }
}

/// The area across the axis of one fin's two fillets, m², as OpenRocket's
/// `FinSet.calculateFilletCrossSection` computes it for fillet radius `r_f` on a body of
/// radius `b`: the triangle of the body's center, the fillet's center and its tangent point
/// on the fin, less the body's and the fillet's sectors inside it, twice.
pub(crate) fn fillet_cross_section_m2(r_f: f64, b: f64) -> f64 {
    let hypotenuse = r_f + b;
    let inner = (r_f / hypotenuse).asin();
    let outer = (r_f / hypotenuse).acos();
    let triangle = outer.tan() * r_f * r_f / 2.0;
    let one = triangle - outer * r_f * r_f / 2.0 - inner * b * b / 2.0;
    if one.is_finite() {
        2.0 * one
    } else {
        0.0
    }
}

/// A fin tab's position: OpenRocket's method against the root chord (`<tabposition
/// relativeto>`: `front`/`top`, `center`/`middle`, `end`/`bottom`) and its offset.
fn tab_position(el: &El<'_, '_>) -> Result<(&'static str, f64), DesignError> {
    let Some(p) = el.child("tabposition") else {
        return Ok(("middle", 0.0));
    };
    let method = match p.attribute("relativeto").unwrap_or("center") {
        "front" | "top" => "top",
        "center" | "middle" => "middle",
        "end" | "bottom" => "bottom",
        other => return Err(el.bad("tabposition", format!("unknown tab position \"{other}\""))),
    };
    let text = p.own_text();
    let value = if text.is_empty() {
        0.0
    } else {
        parse_number(text).ok_or_else(|| el.bad("tabposition", "is not a finite number"))?
    };
    Ok((method, value))
}

/// The density of a bulk material element `tag` (a fin's `material`, its `filletmaterial`),
/// kg/m³, if the element is there.
fn material_density(el: &El<'_, '_>, tag: &str) -> Result<Option<f64>, DesignError> {
    match el.child(tag) {
        Some(_) => density(el, tag, "bulk").map(Some),
        None => Ok(None),
    }
}
