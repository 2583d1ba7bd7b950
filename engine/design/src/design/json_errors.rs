//! Where in a design file serde's complaint belongs, in the words of the format.
//!
//! Components are tagged by `"type"`, and serde reads a tagged object whole before it looks
//! at its fields: a wrong field inside a component is reported at the end of the enclosing
//! array, with no field and no component named. When a design's JSON is well formed but
//! does not fit the format, this module reads it again as plain JSON, finds the innermost
//! component that does not fit (children first), and reads that component alone into its
//! own type through `serde_path_to_error`, which names the field. The message it returns
//! says which component (by id, or by path when it has none), which field, and the rule, with
//! serde's Rust type names put in plain words ([`plain_types`]).

use super::raw::*;
use crate::error::{DesignError, Location};
use serde::de::DeserializeOwned;
use serde_json::Value;

/// serde's type names in a rocketeer's words: `f64` is a number, `u32` a whole number.
pub fn plain_types(message: &str) -> String {
    [
        ("expected f64", "expected a number"),
        ("expected f32", "expected a number"),
        ("expected u64", "expected a whole number, 0 or more"),
        ("expected u32", "expected a whole number, 0 or more"),
        ("expected usize", "expected a whole number, 0 or more"),
        ("expected i64", "expected a whole number"),
        ("expected a boolean", "expected true or false"),
    ]
    .iter()
    .fold(message.to_owned(), |m, (rust, plain)| {
        m.replace(rust, plain)
    })
}

/// The component of `text` (a design that is valid JSON) that does not fit the format, as a
/// [`DesignError::JsonAt`] with its place; `None` when every component reads on its own (the
/// fault is elsewhere: serde's line and column stand).
pub fn locate(file: &str, text: &str) -> Option<DesignError> {
    let v: Value = serde_json::from_str(text).ok()?;
    for (i, stage) in v.get("stages")?.as_array()?.iter().enumerate() {
        let Some(components) = stage.get("components").and_then(Value::as_array) else {
            continue;
        };
        for (j, c) in components.iter().enumerate() {
            if let Some(e) = component(file, c, &format!("stages[{i}].components[{j}]")) {
                return Some(e);
            }
        }
    }
    None
}

fn component(file: &str, c: &Value, path: &str) -> Option<DesignError> {
    if let Some(children) = c.get("children").and_then(Value::as_array) {
        for (k, child) in children.iter().enumerate() {
            if let Some(e) = component(file, child, &format!("{path}.children[{k}]")) {
                return Some(e);
            }
        }
    }
    let at = match c.get("id").and_then(Value::as_str) {
        Some(id) if !id.is_empty() => Location::Component(id.to_owned()),
        _ => Location::Path(path.to_owned()),
    };
    let fault = |field: Option<String>, message: String| DesignError::JsonAt {
        file: file.to_owned(),
        at: at.clone(),
        field,
        message: plain_types(&message),
    };
    let Some(object) = c.as_object() else {
        return Some(fault(None, "a component must be a JSON object".to_owned()));
    };
    let Some(kind) = object.get("type") else {
        return Some(fault(
            Some("type".to_owned()),
            "missing: every component says its type (`nose_cone`, `body_tube`, ...)".to_owned(),
        ));
    };
    // The component alone: its children have been read above.
    let mut alone = object.clone();
    if alone.contains_key("children") {
        alone.insert("children".to_owned(), Value::Array(Vec::new()));
    }
    let alone = Value::Object(alone);
    let result = match kind.as_str().unwrap_or("") {
        "nose_cone" => read::<RawNoseCone>(alone),
        "body_tube" => read::<RawBodyTube>(alone),
        "transition" => read::<RawTransition>(alone),
        "fin_set" => read::<RawFinSet>(alone),
        "launch_lug" => read::<RawLaunchLug>(alone),
        "rail_button" => read::<RawRailButton>(alone),
        "inner_tube" => read::<RawInnerTube>(alone),
        "centering_ring" => read::<RawCenteringRing>(alone),
        "bulkhead" => read::<RawBulkhead>(alone),
        "mass_component" => read::<RawMassComponent>(alone),
        "parachute" => read::<RawParachute>(alone),
        "shock_cord" => read::<RawShockCord>(alone),
        _ => match serde_json::from_value::<RawComponent>(alone) {
            Ok(_) => Ok(()),
            Err(e) => Err((Some("type".to_owned()), e.to_string())),
        },
    };
    result.err().map(|(field, message)| fault(field, message))
}

/// Read one component's object (without `type`) into its own type; on failure the field
/// serde was reading and its message.
fn read<T: DeserializeOwned>(mut v: Value) -> Result<(), (Option<String>, String)> {
    if let Some(o) = v.as_object_mut() {
        o.remove("type");
    }
    match serde_path_to_error::deserialize::<_, T>(v) {
        Ok(_) => Ok(()),
        Err(e) => {
            let path = e.path().to_string();
            let field = (path != ".").then_some(path);
            Err((field, e.into_inner().to_string()))
        }
    }
}
