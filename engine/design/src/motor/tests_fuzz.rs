//! Property tests: no input makes the parsers (or the tables built from what they accept)
//! panic. Random bytes, and random mutations of the real bundled files (which reach deep
//! into the parsers because most of each file stays valid).

use super::*;
use proptest::prelude::*;

/// Bytes that matter to one format or the other.
const INTERESTING: &[u8] = b"0123456789.-+eE;\n\r\t <>/\"=P,&x\xff";

#[derive(Debug, Clone)]
enum Mutation {
    Replace(usize, u8),
    Insert(usize, u8),
    Delete(usize, usize),
    Duplicate(usize, usize),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let byte = prop_oneof![prop::sample::select(INTERESTING), any::<u8>()];
    prop_oneof![
        (any::<usize>(), byte.clone()).prop_map(|(p, b)| Mutation::Replace(p, b)),
        (any::<usize>(), byte).prop_map(|(p, b)| Mutation::Insert(p, b)),
        (any::<usize>(), 1usize..24).prop_map(|(p, n)| Mutation::Delete(p, n)),
        (any::<usize>(), 1usize..64).prop_map(|(p, n)| Mutation::Duplicate(p, n)),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let len = bytes.len();
    let at = |p: usize| if len == 0 { 0 } else { p % len };
    match *m {
        Mutation::Replace(p, b) if len > 0 => bytes[at(p)] = b,
        Mutation::Replace(..) => {}
        Mutation::Insert(p, b) => bytes.insert(if len == 0 { 0 } else { p % (len + 1) }, b),
        Mutation::Delete(p, n) => {
            let start = at(p);
            bytes.drain(start..(start + n).min(len));
        }
        Mutation::Duplicate(p, n) => {
            let start = at(p);
            let chunk = bytes[start..(start + n).min(len)].to_vec();
            bytes.splice(start..start, chunk);
        }
        Mutation::Truncate(p) => bytes.truncate(at(p)),
    }
}

/// Whatever parses gives sane tables: finite, non-negative thrust and propellant within
/// [0, m_p0], at times across and beyond the burn.
fn check_tables(motor: &Motor) {
    let Ok(tables) = MotorTables::from_motor(motor) else {
        return;
    };
    let burn = tables.burn_time_s();
    for k in -2..=42 {
        let t = burn * k as f64 / 40.0;
        let s = tables.eval(t);
        assert!(s.thrust_n.is_finite() && s.thrust_n >= 0.0, "{t}: {s:?}");
        assert!(
            s.propellant_kg >= 0.0 && s.propellant_kg <= tables.propellant_mass_kg(),
            "{t}: {s:?}"
        );
        let p = tables.mass_props_of(&s, 1.0);
        assert!(
            p.mass_kg.is_finite() && p.inertia_cg.iter().all(|v| v.is_finite()),
            "{t}: {p:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn random_bytes_never_make_either_parser_panic(bytes in prop::collection::vec(any::<u8>(), 0..1024)) {
        for name in ["fuzz.eng", "fuzz.rse", "fuzz.txt"] {
            if let Ok(m) = Motor::parse(&bytes, name) {
                check_tables(&m);
            }
        }
        let text = String::from_utf8_lossy(&bytes);
        let _ = parse_eng(&text, "fuzz.eng");
        let _ = parse_rse(&text, "fuzz.rse");
    }

    #[test]
    fn mutated_real_files_never_make_the_parsers_or_tables_panic(
        file in 0..BUNDLED_FILES.len(),
        mutations in prop::collection::vec(mutation(), 1..5),
    ) {
        let original = BUNDLED_FILES[file];
        let mut bytes = original.text.as_bytes().to_vec();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        // Each file read by its own parser and by the other one.
        for name in [original.file_name, "swapped.eng", "swapped.rse"] {
            if let Ok(m) = Motor::parse(&bytes, name) {
                check_tables(&m);
            }
        }
    }
}
