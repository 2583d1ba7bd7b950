//! Fuzzing the parser: random bytes and random mutations of a valid design must give `Ok` or
//! `Err`, never a panic, and whatever is accepted must have finite mass properties.

use super::tests::example_value;
use crate::design::model::Design;
use crate::mass;
use proptest::prelude::*;
use proptest::sample::Index;
use serde_json::{json, Value};

/// Cases per property (each a full parse, and for accepted designs the mass of every part).
const CASES: u32 = 3000;

/// Values that break rules: zero, negative, tiny, huge, denormal, integers out of range.
fn nasty_number() -> impl Strategy<Value = Value> {
    prop_oneof![
        Just(json!(0.0)),
        Just(json!(-0.0)),
        Just(json!(-1.0)),
        Just(json!(1e308)),
        Just(json!(-1e308)),
        Just(json!(5e-324)),
        Just(json!(1e-300)),
        Just(json!(4294967296u64)),
        Just(json!(-1)),
        any::<f64>().prop_map(|x| json!(x)),
        (-2.0f64..2.0).prop_map(|x| json!(x)),
    ]
}

/// Every JSON pointer in `v`, the root excluded.
fn pointers(v: &Value, here: String, out: &mut Vec<String>) {
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                let p = format!("{here}/{k}");
                out.push(p.clone());
                pointers(child, p, out);
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                let p = format!("{here}/{i}");
                out.push(p.clone());
                pointers(child, p, out);
            }
        }
        _ => {}
    }
}

#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the value with another (a nasty number, or a value of another type).
    Replace(Index, Value),
    /// Multiply a number by a factor near 1 (mostly keeps the design valid, to exercise the
    /// mass code on many accepted shapes).
    Scale(Index, f64),
    /// Remove a key or an array element.
    Remove(Index),
    /// Duplicate an array element, or copy a value under another key of its object.
    Duplicate(Index),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let other = prop_oneof![
        nasty_number(),
        Just(Value::Null),
        Just(json!(true)),
        Just(json!("")),
        Just(json!("x")),
        Just(json!([])),
        Just(json!({})),
        Just(json!([0.0, 0.1])),
    ];
    prop_oneof![
        (any::<Index>(), other).prop_map(|(i, v)| Mutation::Replace(i, v)),
        (any::<Index>(), 0.5f64..2.0).prop_map(|(i, f)| Mutation::Scale(i, f)),
        (any::<Index>(), 0.5f64..2.0).prop_map(|(i, f)| Mutation::Scale(i, f)),
        any::<Index>().prop_map(Mutation::Remove),
        any::<Index>().prop_map(Mutation::Duplicate),
    ]
}

fn apply(v: &mut Value, m: &Mutation) {
    let mut all = Vec::new();
    pointers(v, String::new(), &mut all);
    if all.is_empty() {
        return;
    }
    let pick = |i: &Index| all[i.index(all.len())].clone();
    match m {
        Mutation::Replace(i, new) => {
            if let Some(slot) = v.pointer_mut(&pick(i)) {
                *slot = new.clone();
            }
        }
        Mutation::Scale(i, f) => {
            if let Some(slot) = v.pointer_mut(&pick(i)) {
                if let Some(x) = slot.as_f64() {
                    *slot = json!(x * f);
                }
            }
        }
        Mutation::Remove(i) | Mutation::Duplicate(i) => {
            let p = pick(i);
            let (parent, key) = p.rsplit_once('/').unwrap_or(("", &p));
            let Some(container) = v.pointer_mut(parent) else {
                return;
            };
            match (container, m) {
                (Value::Object(map), Mutation::Remove(_)) => {
                    map.remove(key);
                }
                (Value::Object(map), _) => {
                    if let Some(val) = map.get(key).cloned() {
                        map.insert(format!("{key}_copy"), val);
                    }
                }
                (Value::Array(items), Mutation::Remove(_)) => {
                    if let Ok(k) = key.parse::<usize>() {
                        if k < items.len() {
                            items.remove(k);
                        }
                    }
                }
                (Value::Array(items), _) => {
                    if let Some(val) = key
                        .parse::<usize>()
                        .ok()
                        .and_then(|k| items.get(k).cloned())
                    {
                        items.push(val);
                    }
                }
                _ => {}
            }
        }
    }
}

/// Every number in `v` is zero or has a magnitude in `[lo, hi]`.
fn numbers_within(v: &Value, lo: f64, hi: f64) -> bool {
    match v {
        Value::Number(n) => n
            .as_f64()
            .is_some_and(|x| x == 0.0 || (x.abs() >= lo && x.abs() <= hi)),
        Value::Array(items) => items.iter().all(|i| numbers_within(i, lo, hi)),
        Value::Object(map) => map.values().all(|i| numbers_within(i, lo, hi)),
        _ => true,
    }
}

/// Parse, and for an accepted design compute everything the mass code offers.
fn exercise(text: &str) -> Result<(), TestCaseError> {
    if let Ok(d) = Design::from_json_str(text, None) {
        let dry = mass::dry(&d);
        let rows = mass::mass_table(&d);
        prop_assert_eq!(rows.len(), d.components.len());
        let _ = d.motor_fits(0.038, 0.245);
        // Accepted numbers are positive and finite but may be absurd (a density of 1e308
        // overflows the mass): the mass is checked finite and positive when every number in
        // the file is of a sensible size.
        let v: Value = serde_json::from_str(text).expect("accepted text is JSON");
        if numbers_within(&v, 1e-30, 1e6) {
            prop_assert!(
                dry.mass_kg.is_finite() && dry.mass_kg > 0.0,
                "dry mass {}",
                dry.mass_kg
            );
            prop_assert!(dry.cg_m.iter().all(|x| x.is_finite()), "cg {:?}", dry.cg_m);
            prop_assert!(
                dry.inertia_cg.iter().all(|x| x.is_finite()),
                "inertia {}",
                dry.inertia_cg
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: CASES, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic_the_parser(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        exercise(&String::from_utf8_lossy(&bytes))?;
    }

    #[test]
    fn random_mutations_of_a_valid_design_never_panic(mutations in proptest::collection::vec(mutation(), 1..5)) {
        let mut v = example_value();
        for m in &mutations {
            apply(&mut v, m);
        }
        exercise(&v.to_string())?;
    }

    #[test]
    fn random_edits_of_the_design_text_never_panic(
        cut in any::<Index>(),
        len in 0usize..8,
        insert in proptest::collection::vec(any::<u8>(), 0..8),
    ) {
        let text = example_value().to_string();
        let at = cut.index(text.len());
        let end = (at + len).min(text.len());
        let mut bytes = text.as_bytes()[..at].to_vec();
        bytes.extend_from_slice(&insert);
        bytes.extend_from_slice(&text.as_bytes()[end..]);
        exercise(&String::from_utf8_lossy(&bytes))?;
    }
}
