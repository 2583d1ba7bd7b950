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

/// The example with one of each part teams' files brought that it lacks: a cluster of inner
/// tubes, a coupler with no wall and a mass override, a ring of no length, a streamer, a
/// bare `auto` bulkhead in the nose cone, a clipped Haack tail, a zero mass override.
fn rich() -> String {
    EXAMPLE
        .replacen(
            "<parachute>",
            "<innertube><name>Pins</name><position type=\"top\">0.05</position>\
             <material type=\"bulk\" density=\"1000.0\">Pins</material><length>0.01</length>\
             <outerradius>0.002</outerradius><thickness>0.001</thickness>\
             <clusterconfiguration>4-ring</clusterconfiguration><clusterscale>2.0</clusterscale>\
             <clusterrotation>45.0</clusterrotation></innertube>\
             <tubecoupler><name>Coupler</name><position type=\"top\">0.3</position>\
             <overridemass>0.2</overridemass><material type=\"bulk\" density=\"1850.0\">G</material>\
             <length>0.1</length><outerradius>0.0266</outerradius><thickness>0.0</thickness>\
             </tubecoupler>\
             <centeringring><name>Marker</name><position type=\"absolute\">0.6</position>\
             <overridemass>0.0</overridemass><material type=\"bulk\" density=\"680.0\">C</material>\
             <length>0.0</length><outerradius>auto</outerradius><innerradius>auto</innerradius>\
             </centeringring>\
             <streamer><name>Streamer</name><position type=\"top\">0.2</position>\
             <packedlength>0.05</packedlength><packedradius>0.015</packedradius><cd>auto</cd>\
             <material type=\"surface\" density=\"0.1\">Mylar</material>\
             <deployevent>apogee</deployevent><deploydelay>0.5</deploydelay>\
             <striplength>1.0</striplength><stripwidth>0.1</stripwidth></streamer><parachute>",
            1,
        )
        .replacen(
            "<isflipped>false</isflipped>\n          </nosecone>",
            "<isflipped>false</isflipped><subcomponents><bulkhead><name>Fore</name>\
             <position type=\"top\">0.2</position><material type=\"bulk\" density=\"630.0\">P</material>\
             <length>0.01</length><outerradius>auto</outerradius></bulkhead></subcomponents>\
             </nosecone>",
            1,
        )
        .replacen(
            "</bodytube>",
            "</bodytube><transition><name>Tail</name><length>0.05</length>\
             <material type=\"bulk\" density=\"680.0\">Cardboard</material>\
             <thickness>0.002</thickness><shape>haack</shape><shapeparameter>0.0</shapeparameter>\
             <shapeclipped>true</shapeclipped><foreradius>auto 0.02815</foreradius>\
             <aftradius>0.02</aftradius></transition>",
            1,
        )
}

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
        seed in prop_oneof![Just(false), Just(true)],
        edits in proptest::collection::vec(edit(), 1..4),
    ) {
        let mut xml = if seed { rich() } else { EXAMPLE.to_owned() };
        for e in &edits {
            xml = apply(&xml, e);
        }
        exercise(xml.as_bytes())?;
    }
}

#[test]
fn the_rich_seed_imports_with_every_part_it_adds() {
    let imported = import(rich().as_bytes(), "rich.ork").unwrap_or_else(|e| panic!("{e}"));
    let d =
        Design::from_json_str(&imported.json.to_string(), None).unwrap_or_else(|e| panic!("{e}"));
    for name in ["Pins", "Coupler", "Streamer", "Fore", "Tail"] {
        assert!(d.components.iter().any(|c| c.name == name), "{name}");
    }
    assert!(d.components.iter().all(|c| c.name != "Marker"));
}

#[test]
fn the_example_s_leaf_elements_are_found_for_the_edits() {
    // The edits reach the numbers: the fin set's root chord is one of the leaves.
    let leaves = leaf_texts(EXAMPLE);
    assert!(leaves.len() > 100, "{}", leaves.len());
    assert!(leaves.iter().any(|&(a, b)| &EXAMPLE[a..b] == "0.12"));
}
