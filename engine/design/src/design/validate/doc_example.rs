//! The user documentation's example is the example design file, and it parses.

use super::tests::{example_path, example_value};
use crate::design::model::Design;
use serde_json::Value;
use std::path::Path;

#[test]
fn the_documented_example_is_the_example_file_and_it_parses() {
    let doc_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/design-format.md");
    let doc = std::fs::read_to_string(doc_path).expect("docs/design-format.md");
    let start = doc.find("```json\n").expect("a JSON block in the docs") + "```json\n".len();
    let len = doc[start..].find("```").expect("the JSON block ends");
    let shown: Value =
        serde_json::from_str(&doc[start..start + len]).expect("the docs' JSON parses");
    assert_eq!(shown, example_value());
    let d = Design::from_json_str(&doc[start..start + len], Some(&example_path())).expect("valid");
    // The figures the page quotes.
    assert!((d.length_m - 1.15).abs() < 1e-12);
    assert!((d.motor_mount.unwrap().motor_aft_m - 1.16).abs() < 1e-12);
    assert_eq!(d.reference_diameter_m, 0.0563);
}
