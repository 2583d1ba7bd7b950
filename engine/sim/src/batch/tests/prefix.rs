//! Flights that share their beginning ([`super::super::prefix`]): a sweep's points flown with
//! the same draws, one point's flight left for the others just before their moves could
//! tell them apart, give the results of flights flown whole, bit for bit.

use super::*;

/// Five sweep points of the ballast's move: (travel, m; start after the replicate's own
/// drawn start, s; duration, s). Points 2 and 4 start a second later than the first: point 2
/// takes the beginning all share and leaves a longer one for point 4.
const POINTS: [(f64, f64, f64); 5] = [
    (0.0, 0.0, 1.0),
    (0.1, 0.0, 0.5),
    (0.3, 1.0, 1.0),
    (0.2, 0.5, 0.8),
    (0.25, 1.0, 0.7),
];

/// Row `r` of point `p`'s place among the rows sharing their beginnings: point 0 leaves the
/// beginning to the replicate's start for points 1, 2 and 3, and point 2 the one to a second
/// later for point 4.
fn place(p: usize, r: usize, replicates: usize, start: f64) -> Prefix {
    let first = Share {
        key: r as u64,
        until_s: start,
        borrowers: 3,
    };
    let later = Share {
        key: (2 * replicates + r) as u64,
        until_s: start + 1.0,
        borrowers: 1,
    };
    match p {
        0 => Prefix {
            take: None,
            keep: Some(first),
        },
        2 => Prefix {
            take: Some(first),
            keep: Some(later),
        },
        4 => Prefix {
            take: Some(later),
            keep: None,
        },
        _ => Prefix {
            take: Some(first),
            keep: None,
        },
    }
}

/// The sweep's rows, point-major (row `p * replicates + r`): replicate `r` of every point has
/// the draws of row `r` of [`columns_of`], its move's travel, start and duration the point's;
/// in a few rows of point 2 the wind differs by a hair (those may not share), and in a few
/// of point 3 the ballast would leave its holder (refused).
fn sweep(replicates: usize, seed: u64) -> (Columns, Vec<Option<Prefix>>) {
    let draws = columns_of(0..replicates, seed);
    let mut c = Columns::new(POINTS.len() * replicates);
    let mut prefixes = Vec::new();
    for (p, &(travel, later_s, duration_s)) in POINTS.iter().enumerate() {
        for r in 0..replicates {
            for (input, values) in &draws.inputs {
                let v = values[r];
                let v = match *input {
                    Input::ShiftTravelM(0) if p == 3 && r % 7 == 2 => 0.9,
                    Input::ShiftTravelM(0) => travel,
                    Input::ShiftDurationS(0) => duration_s,
                    Input::ShiftTrigger(0) => v + later_s,
                    Input::WindSpeedMS if p == 2 && r % 5 == 1 => v * (1.0 + 1e-12),
                    _ => v,
                };
                c.column_mut(*input).push(v);
            }
            let start = draws.get(Input::ShiftTrigger(0)).unwrap()[r];
            prefixes.push(Some(place(p, r, replicates, start)));
        }
    }
    (c, prefixes)
}

#[test]
fn flights_that_share_their_beginning_equal_flights_flown_whole_bit_for_bit() {
    let replicates = 48;
    let (c, prefixes) = sweep(replicates, 11);
    let n = c.len;
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let store = PrefixStore::new(batch.base().model(), 1000);
    // Chunks of 16 rows in order, as a run takes them: every owner's chunk is done before
    // its borrowers' start.
    let (mut shared, mut whole) = (Vec::new(), Vec::new());
    for first in (0..n).step_by(16) {
        let rows = first..(first + 16).min(n);
        let chunk = c.slice(rows.clone());
        shared.extend(
            batch
                .fly_chunk_sharing(&chunk, first, Some((&prefixes[rows], &store)))
                .unwrap(),
        );
        whole.extend(batch.fly_chunk(&chunk, first).unwrap());
    }
    assert_eq!(shared.len(), n);
    for (a, b) in shared.iter().zip(&whole) {
        // PartialEq on f64: every metric, outcome and count bit for bit.
        assert_eq!(a, b, "variant {}", a.variant);
    }
    // Every borrower whose owner and itself flew took the owner's beginning, but where
    // point 2's wind differs (from point 0's, and from point 4's).
    let flown = |p: usize, r: usize| whole[p * replicates + r].flown;
    let expected = (0..replicates)
        .map(|r| {
            let wind = r % 5 == 1;
            let first = (1..4)
                .filter(|&p| flown(0, r) && flown(p, r) && !(p == 2 && wind))
                .count();
            let later = usize::from(flown(2, r) && flown(4, r) && !wind);
            (first + later) as u64
        })
        .sum::<u64>();
    eprintln!(
        "{n} flights, {} flown; {} began from their owner's flight",
        whole.iter().filter(|l| l.flown).count(),
        store.borrowed()
    );
    assert!(
        expected >= 100,
        "the sweep flies too few to show sharing ({expected})"
    );
    assert_eq!(store.borrowed(), expected);
    // Each owner's beginning was dropped after its last borrower (a refused one included).
    assert!(!whole[3 * replicates + 2].flown, "a refused borrower");
    assert!(store.is_empty(), "{} beginnings left", store.len());
}
