//! Lanes whose parts leave: each lane's releases, margins and released parts' landings are
//! its single flight's, bit for bit, the parts' descents stepped in the batch's descent
//! groups beside the rockets'.

use super::*;
use crate::releases::{PartChute, PartTrigger, Release};

/// The reference design with a 30 g payload of its own, under drogue and main; its ballast
/// slides aft and then leaves, its avionics leave at apogee under their own canopy, the
/// payload at a height under the rocket's canopy.
fn released_base() -> Simulation {
    let mut v = reference::testing::reference_json();
    v["stages"][0]["components"][1]["children"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({
            "id": "payload", "type": "mass_component", "mass_kg": 0.03, "length_m": 0.03, "radius_m": 0.015,
            "position": { "from": "nose_tip", "offset_m": 0.45 }
        }));
    let d = reference::testing::design(&v);
    Simulation::new(
        d,
        reference::motor(),
        site(0.0),
        Rail {
            length_m: 2.0,
            inclination_deg: 87.0,
            heading_deg: 30.0,
        },
    )
    .unwrap()
    .with_parachutes(chutes())
    .unwrap()
    .with_shifts(vec![MassShift::new(
        Trigger::Time { time_s: 3.0 },
        reference::BALLAST,
        0.2,
        1.0,
    )])
    .unwrap()
    .with_releases(vec![
        Release::new(Trigger::Time { time_s: 6.0 }, reference::BALLAST),
        Release::new(Trigger::Apogee, "avionics").with_parachute(PartChute::new(
            0.03,
            PartTrigger::Release,
            1.0,
        )),
        Release::new(Trigger::HeightDescending { height_m: 250.0 }, "payload").with_cda(0.001),
    ])
    .unwrap()
}

/// Random rows: the site, wind and drag as the other batch tests vary them, the ballast's
/// release time (about one in sixteen inside its move, which stops the flight), the avionics'
/// canopy and lag, the payload's height and drag area.
fn release_columns(rows: std::ops::Range<usize>, seed: u64) -> Columns {
    use Input::*;
    let impulse = nominals().0;
    let mut c = Columns::new(rows.len());
    for i in rows {
        let mut r = Rng::of_variant(seed, i);
        let mut push = |input: Input, v: f64| c.column_mut(input).push(v);
        push(DragScale, r.uniform(0.9, 1.1));
        push(WindSpeedMS, r.uniform(0.0, 8.0));
        push(WindFromDeg, r.uniform(0.0, 360.0));
        push(ElevationM, r.uniform(0.0, 1500.0));
        push(MotorImpulseNs, impulse * r.uniform(0.95, 1.05));
        push(ShiftTrigger(0), r.uniform(3.0, 3.6));
        push(ReleaseTrigger(0), r.uniform(4.0, 9.0));
        push(ReleaseCdaM2(0), r.uniform(0.0005, 0.002));
        push(ReleaseChuteCdsM2(1), r.uniform(0.02, 0.05));
        push(ReleaseChuteLagS(1), r.uniform(0.0, 2.0));
        push(ReleaseTrigger(2), r.uniform(150.0, 400.0));
        push(ReleaseCdaM2(2), r.uniform(0.0005, 0.002));
    }
    c
}

#[test]
fn lanes_whose_parts_leave_equal_their_single_flights_bit_for_bit() {
    let n = 240;
    let batch = Batch::new(released_base(), None).unwrap();
    let cols = |rows| release_columns(rows, 77);
    let results = run_on(&batch, n, 1, 40, 4, cols);
    assert_eq!(
        results,
        run_on(&batch, n, 2, 7, 2, cols),
        "threads or chunks"
    );
    let c = release_columns(0..n, 77);
    let (mut flown, mut stopped, mut part_landings) = (0, 0, 0);
    for lane in &results {
        let i = lane.variant;
        let sim = batch.variant(&c, i).unwrap();
        match sim.run(&mut ()) {
            Err(e) => {
                // A ballast released inside its move stops both.
                assert!(matches!(e, SimError::ReleaseDuringShift { .. }), "{e}");
                assert_eq!(lane.status, Status::Failed, "variant {i}");
                assert_eq!(lane.error.as_deref(), Some(e.to_string().as_str()));
                stopped += 1;
            }
            Ok(f) => {
                assert!(lane.flown, "variant {i}");
                assert_eq!(lane.metrics, f.metrics, "variant {i}");
                assert_eq!(
                    lane.derivative_evaluations, f.derivative_evaluations,
                    "variant {i}"
                );
                let single: Vec<ReleaseOutcome> =
                    f.releases.iter().map(ReleaseOutcome::of).collect();
                assert_eq!(lane.releases, single, "variant {i}");
                part_landings += lane
                    .releases
                    .iter()
                    .filter(|r| r.landing_time_s.is_some())
                    .count();
                flown += 1;
            }
        }
    }
    eprintln!("{n} variants: {flown} flown ({part_landings} released parts landed), {stopped} stopped by a release inside its part's move");
    assert!(flown >= 200 && stopped >= 5);
    assert_eq!(
        part_landings,
        3 * flown,
        "every part of every flight landed"
    );
}
