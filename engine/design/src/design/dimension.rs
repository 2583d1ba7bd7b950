//! A design's dimensions as numbers to change: a component's field, addressed by the
//! component's id and the field's name in the design format (`fins` and `span_m`,
//! `nose` and `length_m`, `ballast` and `mass_kg`, a part's `position_m`, a fin set's
//! `cant_deg`), read from and written into the design's JSON form, and the design built
//! again from it by the one validation every design goes through, so that a changed design
//! obeys every rule a design file does (a fin longer than its body is refused by the rule it
//! breaks).

use crate::error::DesignError;
use crate::Design;
use std::path::{Path, PathBuf};

/// One dimension of a design: a number of one of its components.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Dimension {
    /// The component's id.
    pub component: String,
    /// The field's name: a number of the component's JSON object, or `position_m`, the
    /// offset of its position (`position.offset_m`).
    pub field: String,
}

/// Fields a component may leave out, and their value when it does.
const DEFAULTS: [(&str, f64); 1] = [("cant_deg", 0.0)];

impl Dimension {
    /// The field's path in the component's JSON object.
    fn path(&self) -> Vec<&str> {
        match self.field.as_str() {
            "position_m" => vec!["position", "offset_m"],
            f => vec![f],
        }
    }

    /// The unit of the field, by its name's ending ("1" for a pure number).
    pub fn unit(&self) -> &'static str {
        let f = self.field.as_str();
        if f.ends_with("_m") {
            "m"
        } else if f.ends_with("_kg") {
            "kg"
        } else if f.ends_with("_deg") {
            "deg"
        } else if f.ends_with("_m2") {
            "m²"
        } else {
            "1"
        }
    }
}

/// A design in its JSON form, whose dimensions can be read and changed.
#[derive(Debug, Clone)]
pub struct DesignSource {
    json: serde_json::Value,
    /// The file it came from (errors name it; drag CSVs are found beside it).
    source: Option<PathBuf>,
}

impl DesignSource {
    /// The design file `path` (JSON, or an OpenRocket `.ork` in its imported form), checked
    /// as [`Design::load`] checks it.
    pub fn load(path: &Path) -> Result<(DesignSource, Design), DesignError> {
        let text = Design::read_json_text(path)?;
        let design = Design::from_json_str(&text, Some(path))?;
        // The text has just been read as a design, so it is JSON.
        let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
        let json = serde_json::from_str(text).map_err(|e| DesignError::Json {
            file: path.display().to_string(),
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        })?;
        Ok((
            DesignSource {
                json,
                source: Some(path.to_path_buf()),
            },
            design,
        ))
    }

    /// The component's JSON object with this id, searched through every stage and every
    /// component's children.
    fn component<'a>(
        json: &'a mut serde_json::Value,
        id: &str,
    ) -> Option<&'a mut serde_json::Map<String, serde_json::Value>> {
        // Without recursion (the design was loaded, so it has at most `MAX_COMPONENTS`).
        let mut stack: Vec<&mut serde_json::Value> = Vec::new();
        for stage in json.get_mut("stages")?.as_array_mut()? {
            if let Some(c) = stage.get_mut("components") {
                stack.push(c);
            }
        }
        while let Some(list) = stack.pop() {
            let Some(list) = list.as_array_mut() else {
                continue;
            };
            for c in list.iter_mut() {
                let Some(obj) = c.as_object_mut() else {
                    continue;
                };
                if obj.get("id").and_then(|v| v.as_str()) == Some(id) {
                    return Some(obj);
                }
                if let Some(children) = obj.get_mut("children") {
                    stack.push(children);
                }
            }
        }
        None
    }

    /// The value of `dim` in the design as written (a field left out that has a default,
    /// such as a fin set's `cant_deg`, has it). The error says what is missing.
    pub fn value(&self, dim: &Dimension) -> Result<f64, String> {
        let mut json = self.json.clone();
        let obj = Self::component(&mut json, &dim.component)
            .ok_or_else(|| format!("the design has no component with id \"{}\"", dim.component))?;
        let path = dim.path();
        let mut at: Option<&serde_json::Value> = obj.get(path[0]);
        for p in &path[1..] {
            at = at.and_then(|v| v.get(p));
        }
        match at {
            Some(v) => v.as_f64().ok_or_else(|| {
                format!(
                    "the component \"{}\"'s {} is not a number",
                    dim.component, dim.field
                )
            }),
            None => DEFAULTS
                .iter()
                .find(|d| d.0 == dim.field)
                .map(|d| d.1)
                .ok_or_else(|| {
                    format!(
                        "the component \"{}\" has no number {} to change",
                        dim.component, dim.field
                    )
                }),
        }
    }

    /// The design with each dimension of `changes` set to its value, validated as a design
    /// file is: the error is the rule the changed design breaks.
    pub fn design_with(&self, changes: &[(&Dimension, f64)]) -> Result<Design, DesignError> {
        let mut json = self.json.clone();
        for (dim, v) in changes {
            let file = self
                .source
                .as_ref()
                .map_or("<design>".to_owned(), |p| p.display().to_string());
            let missing = || DesignError::JsonAt {
                file: file.clone(),
                at: crate::error::Location::Component(dim.component.clone()),
                field: Some(dim.field.clone()),
                message: "no such component or field to change".into(),
            };
            let obj = Self::component(&mut json, &dim.component).ok_or_else(missing)?;
            let path = dim.path();
            let mut at = obj;
            for p in &path[..path.len() - 1] {
                at = at
                    .get_mut(*p)
                    .and_then(|v| v.as_object_mut())
                    .ok_or_else(missing)?;
            }
            // A value that is not finite has no JSON form: the validation refuses NaN as it
            // refuses a missing number.
            let number = serde_json::Number::from_f64(*v)
                .map(serde_json::Value::Number)
                .unwrap_or(serde_json::Value::Null);
            at.insert(path[path.len() - 1].to_owned(), number);
        }
        Design::from_json_str(&json.to_string(), self.source.as_deref())
    }
}
