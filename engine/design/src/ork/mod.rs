//! OpenRocket designs (`.ork`) read into hpr's design format, so that a team can fly the
//! rocket it already drew in OpenRocket.
//!
//! An `.ork` is a ZIP whose first entry is the XML document (`rocket.ork`); very old files
//! are that XML gzipped or plain (OpenRocket's own loader tells them apart by their first
//! bytes, and so does [`is_ork`]). The document is a tree of components in SI units but for
//! angles (degrees), which [`import`] maps one to one onto the design format's components
//! (`docs/design-format.md`, whose positions, overrides and materials follow OpenRocket's):
//! the result is the JSON of a design, validated afterwards exactly as a hand-written one.
//!
//! What a design cannot hold is refused with the element and the reason (pods and parallel
//! stages, tube fins, clustered motors); what it leaves out is listed
//! in [`OrkImport::notes`] and the design's `notes` (drag overrides, a
//! parachute hpr's flight never deploys; each parachute's deployment is said too). The
//! drag is estimated from the geometry, each skin (nose cone, body tube, transition, fin set)
//! at its own finish's roughness, as OpenRocket estimates it (a `.ork` holds no drag curve).
//!
//! The element names and their meaning (units, `auto` values, position methods, override
//! flags, material kinds) are those of OpenRocket's own loader and savers (openrocket/
//! openrocket: `file/openrocket/importt/DocumentConfig.java` and its setters,
//! `file/openrocket/savers/*Saver.java`, `rocketcomponent/position/AxialMethod.java`), format
//! versions 1.0 to 1.10.
//!
//! Written by hand over `roxmltree` (the document is small and its mapping is the whole job);
//! the container is read with the `zip` and `flate2` crates.

mod components;
#[cfg(test)]
mod fuzz;
mod simulation;

pub use simulation::{OrkResults, OrkSimulation};
#[cfg(test)]
mod tests;

use crate::error::DesignError;
use crate::limits::{read_to_string_limited, MAX_ORK_DEPTH, MAX_ORK_DOCUMENT_BYTES, MAX_ORK_NODES};
use roxmltree::Node;
use serde_json::{json, Map, Value};

/// A design read from an `.ork`: its JSON (the design format) and what the import left out
/// or approximated, one sentence each.
#[derive(Debug, Clone)]
pub struct OrkImport {
    pub json: Value,
    pub notes: Vec<String>,
    /// OpenRocket's own simulation of the design, as `fly` can repeat it.
    pub simulation: Option<OrkSimulation>,
}

/// Whether `bytes` look like an OpenRocket file: a ZIP or a gzip stream (as OpenRocket writes
/// them), or XML that names `<openrocket` in its first 300 bytes (never a JSON object).
pub fn is_ork(bytes: &[u8]) -> bool {
    if looks_like_json(bytes) {
        return false;
    }
    bytes.starts_with(b"PK")
        || bytes.starts_with(&[0x1f, 0x8b])
        || bytes[..bytes.len().min(300)]
            .windows(b"<openrocket".len())
            .any(|w| w == b"<openrocket")
}

/// Whether the file at `path` holding `bytes` is to be read as an OpenRocket design: its
/// content says so ([`is_ork`]), or its name ends in `.ork` and it is not a JSON object (a
/// damaged `.ork` is then refused as one, not as a JSON design).
pub fn is_ork_file(path: &std::path::Path, bytes: &[u8]) -> bool {
    let named = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ork"));
    is_ork(bytes) || (named && !looks_like_json(bytes))
}

/// Whether `bytes` start (after a byte-order mark and white space) with `{`.
fn looks_like_json(bytes: &[u8]) -> bool {
    let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    text.trim_ascii_start().starts_with(b"{")
}

/// Read the `.ork` in `bytes` (`file` names it in errors) into a design.
pub fn import(bytes: &[u8], file: &str) -> Result<OrkImport, DesignError> {
    if looks_like_json(bytes) {
        return Err(err(
            file,
            "document",
            "this is JSON (a design already?), not an OpenRocket document",
        ));
    }
    let xml = document_text(bytes, file)?;
    let options = roxmltree::ParsingOptions {
        nodes_limit: MAX_ORK_NODES,
        ..roxmltree::ParsingOptions::default()
    };
    let doc = roxmltree::Document::parse_with_options(&xml, options).map_err(|e| {
        err(
            file,
            "document",
            format!(
                "not an OpenRocket document ({e}): a .ork is a ZIP, a gzip stream or XML \
                 whose root is <openrocket>"
            ),
        )
    })?;
    let root = doc.root_element();
    if depth(root) > MAX_ORK_DEPTH {
        return Err(err(
            file,
            "document",
            format!(
                "its elements nest more than {MAX_ORK_DEPTH} deep, deeper than any OpenRocket design \
                 (the most hpr-mc reads)"
            ),
        ));
    }
    if root.tag_name().name() != "openrocket" {
        return Err(err(
            file,
            "document",
            "the root element is not <openrocket>",
        ));
    }
    // Paths start at <rocket> (`rocket/stage "Sustainer"/bodytube "Body"`).
    let rocket = El::new(file, root, "")
        .child("rocket")
        .ok_or_else(|| err(file, "openrocket", "has no <rocket>"))?;
    let rocket_override =
        rocket.text("overridemass").is_some() || rocket.text("overridecg").is_some();
    let mut cx = components::Context::new();
    let motor = cx.default_motor(&rocket);
    let mut stages = Vec::new();
    let subs = rocket.child("subcomponents");
    for stage in subs.iter().flat_map(|s| s.children()) {
        match stage.tag() {
            "stage" => stages.push(cx.stage(&stage)?),
            other => return Err(stage.refuse(&format!("a <{other}> directly in the rocket"))),
        }
    }
    if stages.is_empty() {
        return Err(err(file, "rocket", "has no <stage>"));
    }
    if rocket_override {
        // The whole rocket's override is its one stage's (the design format overrides
        // stages); with several stages, or over a stage's own, it has nowhere to go.
        let covers = rocket.flag("overridesubcomponentsmass")
            || rocket.flag("overridesubcomponentscg")
            || rocket.flag("overridesubcomponents");
        match stages.as_mut_slice() {
            [only] if covers && only.get("override").is_none() => {
                let o =
                    components::overrides(rocket.num("overridemass")?, rocket.num("overridecg")?);
                only["override"] = Value::Object(o);
                cx.note("The whole rocket's mass override is its stage's.".to_owned());
            }
            _ => {
                return Err(rocket.refuse(
                    "an override of the whole rocket that does not cover its parts, or of \
                     several stages, or over a stage's own",
                ))
            }
        }
    }
    if stages.len() > 1 {
        cx.note(format!(
            "The {} stages fly together as one rocket (hpr does not separate stages).",
            stages.len()
        ));
    }
    let name = rocket
        .text("name")
        .unwrap_or("OpenRocket design")
        .to_owned();
    let creator = root.attribute("creator").unwrap_or("OpenRocket");
    let version = root.attribute("version").unwrap_or("?");
    let mut design = Map::new();
    design.insert("name".into(), json!(name));
    let motor_name = match motor {
        Some(m) => match m
            .candidates
            .iter()
            .find(|c| crate::motor::find(c).is_ok())
            .cloned()
            .or_else(|| {
                let common = m.by_common_name.clone()?;
                let found = crate::motor::find(&common).ok()?;
                cx.note(format!(
                    "the motor {} flies as the bundled {} ({}, the same maker, class and                      average thrust): check that it is the same motor, or give yours with                      --motor FILE",
                    m.label, common, found.designation
                ));
                Some(common)
            }) {
            Some(found) => Some(found),
            None => {
                cx.note(format!(
                    "the motor {} is not bundled with hpr-mc: give it with --motor FILE (a \
                     .eng or .rse) or the scenario's motor",
                    m.label
                ));
                None
            }
        },
        None => None,
    };
    let roughness = cx.roughness();
    let simulation = simulation::simulation(&El::new(file, root, ""), &rocket, cx.config());
    if let Some(sim) = &simulation {
        cx.note(sim.note());
    }
    let mut notes = vec![format!(
        "Imported from {} ({creator}, file format {version}).",
        short_name(file)
    )];
    notes.extend(cx.notes.iter().cloned());
    design.insert("notes".into(), json!(notes.join(" ")));
    if let Some(m) = motor_name {
        design.insert("motor".into(), json!(m));
    }
    design.insert(
        "drag".into(),
        json!({ "estimate": { "roughness_m": roughness } }),
    );
    // OpenRocket weighs a part where it is drawn, inside its parent or not.
    design.insert("geometry_checks".into(), json!("openrocket"));
    design.insert("stages".into(), Value::Array(stages));
    Ok(OrkImport {
        json: Value::Object(design),
        notes: cx.notes,
        simulation,
    })
}

/// `design` as indented JSON in the order a person reads a design: a component's id, type
/// and name first, its dimensions, then its material, override and position, its children
/// last (a JSON object's keys are otherwise alphabetical).
pub fn to_pretty_json(design: &Value) -> String {
    let mut out = String::new();
    write_value(design, 0, &mut out);
    out.push('\n');
    out
}

fn key_rank(key: &str) -> u8 {
    match key {
        "id" => 0,
        "type" => 1,
        "name" => 2,
        "notes" => 3,
        "motor" => 4,
        "drag" => 5,
        "material" => 7,
        "override" => 8,
        "position" => 9,
        "stages" | "components" | "children" => 10,
        _ => 6,
    }
}

fn write_value(v: &Value, depth: usize, out: &mut String) {
    let pad = |d: usize| "  ".repeat(d);
    match v {
        Value::Object(m) if !m.is_empty() => {
            let mut keys: Vec<&String> = m.keys().collect();
            keys.sort_by_key(|k| (key_rank(k), k.as_str()));
            out.push_str("{\n");
            for (i, k) in keys.iter().enumerate() {
                out.push_str(&pad(depth + 1));
                out.push_str(&Value::String((*k).clone()).to_string());
                out.push_str(": ");
                write_value(&m[k.as_str()], depth + 1, out);
                out.push_str(if i + 1 < keys.len() { ",\n" } else { "\n" });
            }
            out.push_str(&pad(depth));
            out.push('}');
        }
        // Rows of numbers (a free-form fin's corners) on one line each.
        Value::Array(a) if !a.is_empty() && !a.iter().all(|x| x.is_number()) => {
            out.push_str("[\n");
            for (i, x) in a.iter().enumerate() {
                out.push_str(&pad(depth + 1));
                write_value(x, depth + 1, out);
                out.push_str(if i + 1 < a.len() { ",\n" } else { "\n" });
            }
            out.push_str(&pad(depth));
            out.push(']');
        }
        other => out.push_str(&other.to_string()),
    }
}

/// The file's name without its directories.
fn short_name(file: &str) -> &str {
    file.rsplit(['/', '\\']).next().unwrap_or(file)
}

/// The XML text of the document: the first entry of a ZIP, a gunzipped stream, or the bytes;
/// an inflated document larger than [`MAX_ORK_DOCUMENT_BYTES`] is refused as soon as it
/// passes the limit (a ZIP bomb is never inflated whole).
fn document_text(bytes: &[u8], file: &str) -> Result<String, DesignError> {
    let limit = MAX_ORK_DOCUMENT_BYTES;
    let too_large = || {
        err(
            file,
            "container",
            format!(
                "its document inflates to more than {}, the most hpr-mc reads of an OpenRocket design",
                crate::limits::size_text(limit)
            ),
        )
    };
    if bytes.starts_with(b"PK") {
        let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes))
            .map_err(|e| err(file, "container", format!("not a readable ZIP: {e}")))?;
        if zip.is_empty() {
            return Err(err(file, "container", "the ZIP is empty"));
        }
        // OpenRocket reads the first entry; `rocket.ork` is its name when OpenRocket wrote it.
        let index = zip.index_for_name("rocket.ork").unwrap_or(0);
        let entry = zip
            .by_index(index)
            .map_err(|e| err(file, "container", format!("cannot open its document: {e}")))?;
        // The size the ZIP declares first (it may lie: the read below is bounded too).
        if entry.size() > limit {
            return Err(too_large());
        }
        read_to_string_limited(entry, limit).map_err(|e| match e {
            None => too_large(),
            Some(e) => err(file, "container", format!("cannot read its document: {e}")),
        })
    } else if bytes.starts_with(&[0x1f, 0x8b]) {
        read_to_string_limited(flate2::read::GzDecoder::new(bytes), limit).map_err(|e| match e {
            None => too_large(),
            Some(e) => err(
                file,
                "container",
                format!("not a readable gzip stream: {e}"),
            ),
        })
    } else {
        String::from_utf8(bytes.to_vec()).map_err(|_| err(file, "document", "not UTF-8 text"))
    }
}

/// How deeply the document's elements nest, counted without recursion (the import walks the
/// tree recursively, so a document nested thousands deep must be refused before it does).
fn depth(root: Node<'_, '_>) -> usize {
    let mut deepest = 0;
    let mut stack = vec![(root, 1usize)];
    while let Some((node, d)) = stack.pop() {
        deepest = deepest.max(d);
        if d > MAX_ORK_DEPTH {
            break;
        }
        stack.extend(node.children().filter(Node::is_element).map(|c| (c, d + 1)));
    }
    deepest
}

fn err(file: &str, element: &str, message: impl std::fmt::Display) -> DesignError {
    DesignError::Ork {
        file: file.to_owned(),
        element: element.to_owned(),
        message: message.to_string(),
    }
}

/// An element of the document with its path (for errors): `stage "Sustainer"/bodytube
/// "Body tube"`.
#[derive(Clone)]
pub(crate) struct El<'a, 'i> {
    file: &'a str,
    node: Node<'a, 'i>,
    path: String,
}

/// A number that may be OpenRocket's `auto` (its value resolved from the neighbours): `auto
/// 0.0325` carries the value, a bare `auto` (files before 1.8) does not.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Auto {
    Value(f64),
    Bare,
}

impl<'a, 'i> El<'a, 'i> {
    fn new(file: &'a str, node: Node<'a, 'i>, path: &str) -> El<'a, 'i> {
        El {
            file,
            node,
            path: path.to_owned(),
        }
    }

    pub(crate) fn tag(&self) -> &'a str {
        self.node.tag_name().name()
    }

    /// The element's `<name>`, or its tag.
    pub(crate) fn name(&self) -> &'a str {
        self.text("name").unwrap_or(self.tag())
    }

    /// The element children (components inside `<subcomponents>`), each with its path.
    pub(crate) fn children(&self) -> impl Iterator<Item = El<'a, 'i>> + '_ {
        self.node.children().filter(Node::is_element).map(|n| {
            let tag = n.tag_name().name();
            let name = n
                .children()
                .find(|c| c.has_tag_name("name"))
                .and_then(|c| c.text())
                .map(|s| format!(" \"{}\"", s.trim()))
                .unwrap_or_default();
            let path = if self.tag() == "subcomponents" {
                // A component's path skips the <subcomponents> between it and its parent.
                self.path
                    .trim_end_matches("/subcomponents")
                    .trim_end_matches("subcomponents")
                    .to_owned()
            } else {
                self.path.clone()
            };
            let sep = if path.is_empty() { "" } else { "/" };
            El::new(self.file, n, &format!("{path}{sep}{tag}{name}"))
        })
    }

    pub(crate) fn child(&self, tag: &str) -> Option<El<'a, 'i>> {
        self.node.children().find(|c| c.has_tag_name(tag)).map(|n| {
            let sep = if self.path.is_empty() { "" } else { "/" };
            El::new(self.file, n, &format!("{}{sep}{tag}", self.path))
        })
    }

    pub(crate) fn attribute(&self, name: &str) -> Option<&'a str> {
        self.node.attribute(name)
    }

    /// The trimmed text of child `<tag>`.
    pub(crate) fn text(&self, tag: &str) -> Option<&'a str> {
        self.node
            .children()
            .find(|c| c.has_tag_name(tag))
            .map(|c| c.text().unwrap_or("").trim())
    }

    /// This element's own trimmed text.
    pub(crate) fn own_text(&self) -> &'a str {
        self.node.text().unwrap_or("").trim()
    }

    /// An error at child `<field>` of this element.
    pub(crate) fn bad(&self, field: &str, message: impl std::fmt::Display) -> DesignError {
        err(self.file, &format!("{}/<{field}>", self.path), message)
    }

    /// An error at this element: what hpr cannot hold.
    pub(crate) fn refuse(&self, what: &str) -> DesignError {
        err(
            self.file,
            &self.path,
            format!("{what} cannot be imported (hpr's design format has no such part)"),
        )
    }

    /// Child `<tag>` as a finite number, if present.
    pub(crate) fn num(&self, tag: &str) -> Result<Option<f64>, DesignError> {
        match self.text(tag) {
            None => Ok(None),
            Some(t) => parse_number(t)
                .map(Some)
                .ok_or_else(|| self.bad(tag, format!("not a finite number: \"{t}\""))),
        }
    }

    /// Child `<tag>` as a finite number, required.
    pub(crate) fn req(&self, tag: &str) -> Result<f64, DesignError> {
        self.num(tag)?
            .ok_or_else(|| self.bad(tag, "is missing (the design needs it)"))
    }

    /// Child `<tag>`, a number or OpenRocket's `auto` (`auto 0.0325`, or a bare `auto`).
    pub(crate) fn auto(&self, tag: &str) -> Result<Option<Auto>, DesignError> {
        let Some(t) = self.text(tag) else {
            return Ok(None);
        };
        let value = t.strip_prefix("auto").map(str::trim).unwrap_or(t);
        if value.is_empty() {
            return Ok(Some(Auto::Bare));
        }
        parse_number(value)
            .map(|v| Some(Auto::Value(v)))
            .ok_or_else(|| self.bad(tag, format!("not a finite number or auto: \"{t}\"")))
    }

    /// Attribute `name` as a finite number, if present and one.
    pub(crate) fn attribute_number(&self, name: &str) -> Option<f64> {
        self.attribute(name).and_then(parse_number)
    }

    /// Child `<tag>` as `true`/`false` (absent: false).
    pub(crate) fn flag(&self, tag: &str) -> bool {
        self.text(tag)
            .is_some_and(|t| t.eq_ignore_ascii_case("true"))
    }
}

fn parse_number(t: &str) -> Option<f64> {
    t.trim().parse::<f64>().ok().filter(|v| v.is_finite())
}
