//! A noisy parachute barometer fires the main where RocketPy's fires it, in distribution.
//!
//! `validation/rocketpy/noise_crosscheck.py` flew the cross-checked reference design (54 mm,
//! I175, drogue at apogee, main at 200 m, both read at 105 Hz, still air, RocketPy's lever
//! arm and standard air corrected) 200 times in RocketPy 1.13 for each of two barometer
//! noises, RocketPy's example (0, 8.3 Pa, 0.5) and a poor one (6 Pa, 20 Pa, 0.8), and kept
//! the height of the center above the site at each main trigger. hpr-mc flies the same
//! rocket, mapped as `crosscheck.rs` maps it, over 400 of its own sensor seeds. The two
//! codes draw different random numbers, so the check is of the distributions: the mean
//! height within four standard errors of the difference, the deviations' ratio within four
//! of its standard errors. Without noise the two mains fire at the same sample.

use crate::crosscheck::{crosscheck_simulation, num};
use hpr_sim::events::EventKind;
use hpr_sim::sensor::SensorNoise;
use serde_json::Value;

/// hpr's flights per noise.
const SEEDS: u64 = 400;

fn reference() -> (Value, Value) {
    let read = |file: &str| -> Value {
        let path = crate::common::repo(&format!("validation/rocketpy/{file}"));
        serde_json::from_str(&std::fs::read_to_string(path).expect("reference")).expect("JSON")
    };
    let noise = read("noise_crosscheck_reference.json");
    let rocket = noise["rocket"].as_str().expect("rocket").to_string();
    let designs = read("design_crosscheck_reference.json");
    (designs["rockets"][rocket.as_str()].clone(), noise)
}

fn mean_sd(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

#[test]
fn a_noisy_barometer_fires_the_main_at_heights_distributed_as_rocketpys() {
    let (r, rp) = reference();
    let wind = rp["wind"].as_str().unwrap();
    let (sim, start_height, _) = crosscheck_simulation(&r, wind);
    // The main's trigger height as RocketPy's rocket sees it (hpr's center starts
    // `start_height` above RocketPy's; its site is as much lower: see crosscheck.rs).
    let main_height = |f: &hpr_sim::flight::Flight| {
        f.event(EventKind::ParachuteTrigger(1))
            .expect("main trigger")
            .altitude_m
            - start_height
    };
    let plain = sim.clone().run(&mut ()).expect("flies");
    let rate = num(&r, "/inputs/sampling_rate_hz");
    let (t_rp, h_rp) = (
        num(&rp, "/noiseless_main_trigger/time_s"),
        num(&rp, "/noiseless_main_trigger/height_m"),
    );
    let t_hpr = plain.event(EventKind::ParachuteTrigger(1)).unwrap().time_s;
    eprintln!(
        "noiseless main: hpr at {t_hpr:.6} s, {:.4} m; RocketPy at {t_rp:.6} s, {h_rp:.4} m",
        main_height(&plain)
    );
    assert!(
        ((t_hpr - t_rp) * rate).abs() < 0.5,
        "the same 105 Hz sample"
    );
    assert!((main_height(&plain) - h_rp).abs() < 0.02);
    for (name, run) in rp["runs"].as_object().unwrap() {
        let noise = SensorNoise {
            bias_pa: num(run, "/noise/bias_pa"),
            std_pa: num(run, "/noise/std_pa"),
            correlation: num(run, "/noise/correlation"),
        };
        let chutes = sim
            .parachutes()
            .iter()
            .map(|p| p.clone().with_noise(noise))
            .collect();
        let noisy = sim.clone().with_parachutes(chutes).expect("noise");
        let ours: Vec<f64> = (0..SEEDS)
            .map(|seed| main_height(&noisy.clone().with_sensor_seed(seed).run(&mut ()).unwrap()))
            .collect();
        let theirs: Vec<f64> = run["main_trigger_heights_m"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let ((m_h, s_h), (m_r, s_r)) = (mean_sd(&ours), mean_sd(&theirs));
        let (n_h, n_r) = (ours.len() as f64, theirs.len() as f64);
        let se_mean = (s_h * s_h / n_h + s_r * s_r / n_r).sqrt();
        // The relative standard error of a deviation over n samples is about 1/√(2(n − 1)).
        let se_ratio = (1.0 / (2.0 * (n_h - 1.0)) + 1.0 / (2.0 * (n_r - 1.0))).sqrt();
        eprintln!(
            "{name}: hpr {m_h:.4} ± {s_h:.4} m over {n_h} seeds, RocketPy {m_r:.4} ± {s_r:.4} m \
             over {n_r} flights: means {:.4} m apart (standard error {se_mean:.4} m), \
             deviations' ratio {:.4} (standard error {se_ratio:.4})",
            m_h - m_r,
            s_h / s_r
        );
        assert!((m_h - m_r).abs() < 4.0 * se_mean, "{name}: means");
        assert!(
            (s_h / s_r - 1.0).abs() < 4.0 * se_ratio,
            "{name}: deviations"
        );
    }
}
