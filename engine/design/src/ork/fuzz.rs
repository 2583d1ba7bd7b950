//! Fuzzing the OpenRocket import: random bytes (plain, or behind a ZIP's or a gzip stream's
//! magic number) and random edits of a valid document must give `Ok` or `Err`, never a
//! panic; a design the import writes is then validated like any other, which must also
//! answer without panicking, and its mass is finite when its numbers are of a sensible size.

use super::import;
use crate::design::model::Design;
use crate::mass;
use proptest::prelude::*;
use proptest::sample::Index;

/// Cases per property (each an import, and for accepted designs a validation and a mass).
const CASES: u32 = 2000;

const EXAMPLE: &str = include_str!("../../../../validation/designs/example-minimal.ork");

/// The import of `bytes`, and of what it writes, answered without a panic.
fn exercise(bytes: &[u8]) -> Result<(), TestCaseError> {
    let Ok(imported) = import(bytes, "fuzz.ork") else {
        return Ok(());
    };
    let text = imported.json.to_string();
    if let Ok(d) = Design::from_json_str(&text, None) {
        let dry = mass::dry(&d);
        let sensible = numbers_within(&imported.json, 1e-9, 1e4);
        if sensible {
            prop_assert!(dry.mass_kg.is_finite(), "dry mass {}", dry.mass_kg);
            prop_assert!(dry.cg_m.iter().all(|x| x.is_finite()), "cg {:?}", dry.cg_m);
        }
    }
    Ok(())
}

/// Whether every number in `v` is zero or of magnitude within `[lo, hi]`.
fn numbers_within(v: &serde_json::Value, lo: f64, hi: f64) -> bool {
    match v {
        serde_json::Value::Number(n) => n
            .as_f64()
            .is_some_and(|x| x == 0.0 || (lo..=hi).contains(&x.abs())),
        serde_json::Value::Array(a) => a.iter().all(|x| numbers_within(x, lo, hi)),
        serde_json::Value::Object(m) => m.values().all(|x| numbers_within(x, lo, hi)),
        _ => true,
    }
}

/// The byte ranges of the text of every leaf element (`<tag>text</tag>`, no element inside).
fn leaf_texts(xml: &str) -> Vec<(usize, usize)> {
    let b = xml.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(open) = xml[i..].find('>').map(|k| i + k) {
        let start = open + 1;
        match xml[start..].find('<').map(|k| start + k) {
            Some(end) if b.get(end + 1) == Some(&b'/') && end > start => {
                out.push((start, end));
                i = end;
            }
            Some(end) => i = end,
            None => break,
        }
    }
    out
}

/// What to put in place of a number: numbers that break rules, words, nothing.
fn nasty_text() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("0".to_owned()),
        Just("-1".to_owned()),
        Just("1e308".to_owned()),
        Just("-1e308".to_owned()),
        Just("5e-324".to_owned()),
        Just("NaN".to_owned()),
        Just("inf".to_owned()),
        Just(String::new()),
        Just("auto".to_owned()),
        Just("auto -0.5".to_owned()),
        Just("ogive".to_owned()),
        Just("top".to_owned()),
        any::<f64>().prop_map(|x| x.to_string()),
        (-2.0f64..2.0).prop_map(|x| x.to_string()),
    ]
}

#[derive(Debug, Clone)]
enum Edit {
    /// A leaf element's text replaced.
    Text(Index, String),
    /// A leaf element's text scaled (mostly keeps the design valid).
    Scale(Index, f64),
    /// A span of the document removed.
    Cut(Index, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<Index>(), nasty_text()).prop_map(|(i, t)| Edit::Text(i, t)),
        (any::<Index>(), 0.5f64..2.0).prop_map(|(i, f)| Edit::Scale(i, f)),
        (any::<Index>(), 0usize..200).prop_map(|(i, n)| Edit::Cut(i, n)),
    ]
}

fn apply(xml: &str, e: &Edit) -> String {
    let leaves = leaf_texts(xml);
    match e {
        Edit::Text(i, t) if !leaves.is_empty() => {
            let (a, b) = leaves[i.index(leaves.len())];
            format!("{}{t}{}", &xml[..a], &xml[b..])
        }
        Edit::Scale(i, f) if !leaves.is_empty() => {
            let (a, b) = leaves[i.index(leaves.len())];
            match xml[a..b].trim().parse::<f64>() {
                Ok(x) => format!("{}{}{}", &xml[..a], x * f, &xml[b..]),
                Err(_) => xml.to_owned(),
            }
        }
        Edit::Cut(i, n) => {
            let a = i.index(xml.len());
            let mut b = (a + n).min(xml.len());
            while !xml.is_char_boundary(b) {
                b += 1;
            }
            let mut a = a;
            while !xml.is_char_boundary(a) {
                a -= 1;
            }
            format!("{}{}", &xml[..a], &xml[b..])
        }
        _ => xml.to_owned(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: CASES, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic_the_import(
        magic in prop_oneof![Just(&b""[..]), Just(&b"PK\x03\x04"[..]), Just(&[0x1f, 0x8b][..])],
        bytes in proptest::collection::vec(any::<u8>(), 0..600),
    ) {
        let mut all = magic.to_vec();
        all.extend_from_slice(&bytes);
        exercise(&all)?;
    }

    #[test]
    fn random_edits_of_a_valid_document_never_panic_the_import(
        edits in proptest::collection::vec(edit(), 1..4),
    ) {
        let mut xml = EXAMPLE.to_owned();
        for e in &edits {
            xml = apply(&xml, e);
        }
        exercise(xml.as_bytes())?;
    }
}

#[test]
fn the_example_s_leaf_elements_are_found_for_the_edits() {
    // The edits reach the numbers: the fin set's root chord is one of the leaves.
    let leaves = leaf_texts(EXAMPLE);
    assert!(leaves.len() > 100, "{}", leaves.len());
    assert!(leaves.iter().any(|&(a, b)| &EXAMPLE[a..b] == "0.12"));
}
