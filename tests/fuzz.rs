//! The fuzzing harness's fast slice and its regression corpus (`examples/fuzz`, run for
//! long with `cargo run --release --example fuzz -- --cases N`): a few thousand mutated
//! inputs of every kind through the library, in this process, and every input that ever
//! failed (`tests/fuzz_corpus`), none of which may panic or be accepted while impossible.
//! (An abort or a hang would end or stall this test: a failure too.)

#[path = "../examples/fuzz/harness.rs"]
#[allow(dead_code)]
mod harness;

use harness::{Bases, Outcome, Target};
use std::collections::BTreeMap;
use std::path::Path;

/// Cases of the fast slice, and their seed (the long runs use others).
const SLICE_CASES: u64 = 3000;
const SLICE_SEED: u64 = 20261204;

#[test]
fn a_slice_of_fuzzed_inputs_of_every_kind_is_refused_or_accepted_sanely() {
    let bases = Bases::load();
    for (t, n) in bases.counts() {
        assert!(n > 0, "no bundled file of kind {}", t.name());
    }
    // Two threads, each with its own scratch directory, take every other case.
    let results: Vec<(u64, harness::Case, Outcome, f64)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..2u64)
            .map(|t| {
                let bases = &bases;
                scope.spawn(move || {
                    let scratch = tempfile::tempdir().unwrap();
                    harness::prepare_scratch(scratch.path()).unwrap();
                    (t..SLICE_CASES)
                        .step_by(2)
                        .map(|k| {
                            let case = harness::generate(bases, SLICE_SEED, k);
                            let t0 = std::time::Instant::now();
                            let outcome = harness::run(&case, scratch.path());
                            (k, case, outcome, t0.elapsed().as_secs_f64())
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    let mut seen: BTreeMap<(Target, &'static str), u64> = BTreeMap::new();
    let mut slowest = (0.0, 0);
    let mut failures = vec![];
    for (k, case, outcome, s) in &results {
        if *s > slowest.0 {
            slowest = (*s, *k);
        }
        *seen.entry((case.target, outcome.word())).or_default() += 1;
        if outcome.is_failure() {
            failures.push(format!(
                "case {k} ({} from {}: {}): {outcome:?}",
                case.target.name(),
                case.base,
                case.mutation
            ));
        }
    }
    eprintln!("outcomes: {seen:?}");
    eprintln!("slowest case: {} ({:.3} s)", slowest.1, slowest.0);
    assert!(failures.is_empty(), "{failures:#?}");
    // Every kind was made, and each was both refused and accepted somewhere in the slice:
    // the mutations reach past the first check.
    for t in Target::GENERATED {
        let refused = seen.get(&(t, "refused")).copied().unwrap_or(0);
        let accepted = ["accepted", "flown"]
            .iter()
            .map(|w| seen.get(&(t, *w)).copied().unwrap_or(0))
            .sum::<u64>();
        assert!(
            refused > 0 && accepted > 0,
            "{}: {refused} refused, {accepted} accepted",
            t.name()
        );
    }
    let flown: u64 = seen
        .iter()
        .filter(|((_, w), _)| *w == "flown")
        .map(|(_, n)| n)
        .sum();
    assert!(flown > SLICE_CASES / 10, "{flown} flown");
}

#[test]
fn every_input_that_ever_failed_is_now_refused_or_accepted_sanely() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_corpus");
    let scratch = tempfile::tempdir().unwrap();
    harness::prepare_scratch(scratch.path()).unwrap();
    let mut count = 0;
    let mut entries: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e != "md" && e != "report"))
        .collect();
    entries.sort();
    for path in entries {
        let case = harness::saved_case(&path)
            .unwrap_or_else(|| panic!("{}: its name does not start with its kind", path.display()));
        let outcome = harness::run(&case, scratch.path());
        eprintln!("{}: {}", path.display(), outcome.word());
        assert!(!outcome.is_failure(), "{}: {outcome:?}", path.display());
        if let Outcome::Refused(e) = &outcome {
            assert!(!e.contains("panicked"), "{e}");
        }
        count += 1;
    }
    assert!(count >= 5, "the corpus holds {count} inputs");
}
