//! A sweep's points sharing the beginning of their flights: the rows are those of flights
//! flown whole, bit for bit, and the sharing happens.

use super::*;
use hpr_mc::campaign::fly::{fly_chunk, fly_chunk_sharing};
use hpr_mc::campaign::run::prepare;

fn scenario(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("scenarios/{name}.toml"))
}

/// Fly every variant of `name` with `replicates` per point in chunks of 32 in variant order,
/// as a run takes them on one thread, sharing beginnings and not: the same results, bit
/// for bit. (With at least 32 replicates a point's chunks come after its owner's: every
/// flight that can share does.) `owner(q)` is the point whose flight point `q`'s flights begin from. Returns how
/// many flights took a shared beginning and how many could have (a flown flight whose
/// owner's flight flew too).
fn shared_and_whole(name: &str, replicates: u64, owner: impl Fn(usize) -> usize) -> (u64, u64) {
    let cfg = RunConfig {
        variants_per_point: Some(replicates),
        ..RunConfig::default()
    };
    let p = prepare(&scenario(name), &cfg).unwrap();
    let store = p
        .prefix_store()
        .expect("points that differ only in a timed move share their beginnings");
    let total = p.plan.total();
    let mut flown = vec![false; total as usize];
    let ids: Vec<u64> = (0..total).collect();
    for chunk in ids.chunks(32) {
        let variants: Vec<_> = chunk.iter().map(|&id| p.plan.variant(id)).collect();
        let shared = fly_chunk_sharing(&p, &variants, Some(&store));
        let whole = fly_chunk(&p, &variants);
        for (a, b) in shared.iter().zip(&whole) {
            // Every metric by its bits, the status, the error and the warnings.
            assert_eq!(a, b, "{name}: variant {}", a.id);
            flown[a.id as usize] = a.warned.is_some();
        }
    }
    let r = replicates as usize;
    let could = (0..total as usize)
        .filter(|&id| {
            let (q, k) = (id / r, id % r);
            owner(q) != q && flown[id] && flown[owner(q) * r + k]
        })
        .count() as u64;
    (store.borrowed(), could)
}

#[test]
fn the_ballast_sweep_s_points_share_their_beginnings_and_their_rows_are_the_whole_flights() {
    // 8 points (4 travels x 2 start times, the start fastest), all differing only in the
    // ballast's move: point 0's flight of each replicate is left to its start (5 s, give or
    // take the timer's jitter) for points 1, 2, 4 and 6; point 1 flies on from it to the
    // later start (6 s) and leaves that for points 3, 5 and 7.
    let owner = |q: usize| if q % 2 == 1 && q > 1 { 1 } else { 0 };
    let (shared, could) = shared_and_whole("ballast_sweep", 40, owner);
    assert_eq!(could, 7 * 40, "every variant of this scenario flies");
    assert_eq!(shared, could);
}

#[test]
fn a_sweep_of_fins_and_travels_shares_within_each_fin_span() {
    // 4 spans x 3 travels, the travel fastest: points 3s, 3s+1 and 3s+2 share span s's.
    let (shared, could) = shared_and_whole("fin_sizing", 40, |q| q - q % 3);
    assert_eq!(could, 4 * 2 * 40, "every variant of this scenario flies");
    assert_eq!(shared, could);
}

#[test]
fn points_that_differ_before_their_moves_share_nothing() {
    // The wind study sweeps the wind (it acts from the pad), the payload drop its payload's
    // canopy (not a shift), and the Calisto flies no sweep.
    for name in ["wind_study", "calisto", "payload_drop"] {
        let cfg = RunConfig {
            variants_per_point: Some(2),
            ..RunConfig::default()
        };
        let p = prepare(&scenario(name), &cfg).unwrap();
        assert!(p.prefix_store().is_none(), "{name}");
    }
}
