//! Lanes whose parachutes read a noisy barometer: each lane draws the noise its single flight
//! draws (its sensor seed is a column), whatever the threads and chunks.

use super::*;

#[test]
fn lanes_with_noisy_barometers_equal_their_single_flights_whatever_the_chunks() {
    // The main fired by a noisy barometer (RocketPy's example noise, read at 20 Hz), each
    // variant with its own sensor seed: a lane draws the noise its single flight draws.
    let noise = crate::SensorNoise {
        bias_pa: 0.0,
        std_pa: 8.3,
        correlation: 0.5,
    };
    let mut chutes = chutes();
    chutes[1] = chutes[1].clone().with_noise(noise);
    let batch = Batch::new(
        base().with_parachutes(chutes).unwrap(),
        Some(reference::BALLAST),
    )
    .unwrap();
    let n = 120;
    let cols = |rows: std::ops::Range<usize>| Columns {
        sensor_seed: rows.clone().map(|i| 1000 + i as u64).collect(),
        ..columns_of(rows, 5)
    };
    let run = |threads: usize, chunk: usize| run_on(&batch, n, threads, chunk, 3, cols);
    let (a, b) = (run(1, 40), run(2, 7));
    assert!(a == b, "the noise depends on the threads or chunks");
    let c = cols(0..n);
    let mut moved = 0;
    for lane in a.iter().filter(|l| l.flown) {
        let sim = batch.variant(&c, lane.variant).unwrap();
        let f = sim.clone().run(&mut ()).unwrap();
        assert_eq!(lane.metrics, f.metrics, "variant {}", lane.variant);
        for (k, chute) in lane.parachutes.iter().enumerate() {
            assert_eq!(
                chute.deploy_time_s,
                f.deploy(k).map(|d| d.0),
                "variant {}",
                lane.variant
            );
        }
        // The noise is there: another seed fires the main at another sample, mostly (the
        // noise's deviation, about 0.7 m of height, against one sample's fall of about 0.6 m
        // under the drogue at 20 Hz).
        if lane.variant < 20 {
            let other = sim.with_sensor_seed(1).run(&mut ()).unwrap();
            let main =
                |f: &crate::flight::Flight| f.event(EventKind::ParachuteTrigger(1)).unwrap().time_s;
            moved += usize::from(main(&other) != main(&f));
        }
    }
    eprintln!("{moved} of the first 20 variants' mains moved with another seed");
    assert!(moved >= 8);
}
