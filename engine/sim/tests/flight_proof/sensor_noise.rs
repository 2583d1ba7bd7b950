//! A parachute fired by a noisy barometer (RocketPy's `noise`): at each of its samples after
//! apogee it fires when the air's pressure plus the noise is above the pressure at its
//! trigger height. Checked exactly where the noise has no deviation (a bias moves the
//! trigger to the height whose pressure is that much lower), and in distribution against an
//! independent model of first passage where it has one.

use crate::common::*;
use hpr_sim::atmosphere::Atmosphere;
use hpr_sim::events::EventKind;
use hpr_sim::flight::{Environment, Flight, Parachute, Rail, Simulation};
use hpr_sim::sensor::SensorNoise;
use hpr_sim::trigger::Trigger;

const RATE_HZ: f64 = 100.0;
const MAIN_M: f64 = 300.0;

/// The synthetic rocket on its I175 in still air (standard atmosphere, sea-level site):
/// drogue at apogee, main at `main_m` on the way down, both read at 100 Hz and opening 1 s
/// after their triggers; `noise` on both barometers (the drogue's apogee trigger reads no
/// pressure), with sensor seed `seed`.
fn fly(main_m: f64, noise: Option<SensorNoise>, seed: u64) -> Flight {
    let chute = |p: Parachute| {
        let p = p.with_sampling_rate(RATE_HZ);
        match noise {
            Some(n) => p.with_noise(n),
            None => p,
        }
    };
    let chutes = vec![
        chute(Parachute::new("drogue", 0.1, Trigger::Apogee, 1.0)),
        chute(Parachute::new(
            "main",
            0.9,
            Trigger::HeightDescending { height_m: main_m },
            1.0,
        )),
    ];
    Simulation::new(
        design("synthetic-54mm-three-fin.json"),
        motor("Cesaroni_I175"),
        Environment::default(),
        Rail::default(),
    )
    .and_then(|s| s.with_parachutes(chutes))
    .expect("set up")
    .with_sensor_seed(seed)
    .run(&mut ())
    .expect("flies")
}

fn event(f: &Flight, kind: EventKind) -> &hpr_sim::events::Event {
    f.event(kind).unwrap_or_else(|| panic!("no {kind:?}"))
}

fn pressure(h_m: f64) -> f64 {
    Atmosphere::standard(0.0).unwrap().at(h_m).pressure_pa
}

/// The height above the site whose pressure is `p_pa` (bisection to 1e-9 m).
fn height_of_pressure(p_pa: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 2000.0);
    while hi - lo > 1e-9 {
        let mid = 0.5 * (lo + hi);
        if pressure(mid) > p_pa {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn a_barometer_with_only_a_bias_fires_where_the_biased_pressure_says_the_trigger_height_is() {
    // Without deviation the noise is a number: b = 60 Pa uncorrelated, and b = 10 Pa with
    // correlation 0.6, which settles (long before apogee) at β b / (1 − α) = 0.8·10/0.4 =
    // 20 Pa. Reading p + n, the barometer is at 300 m when the air's pressure is p(300) − n:
    // a height h' a few metres higher, so the main fires exactly as a noiseless main at h'.
    for (bias, corr, settled) in [(60.0, 0.0, 60.0), (10.0, 0.6, 20.0)] {
        let noise = SensorNoise {
            bias_pa: bias,
            std_pa: 0.0,
            correlation: corr,
        };
        let h = height_of_pressure(pressure(MAIN_M) - settled);
        let (noisy, plain) = (fly(MAIN_M, Some(noise), 0), fly(h, None, 0));
        let (a, b) = (
            event(&noisy, EventKind::ParachuteTrigger(1)),
            event(&plain, EventKind::ParachuteTrigger(1)),
        );
        let one_sample = b.speed_m_s / RATE_HZ;
        eprintln!(
            "bias {bias} Pa, correlation {corr}: reads {settled} Pa high, fires as at {h:.4} m \
             ({:.4} m above {MAIN_M} m); noisy main at {} s, {:.4} m; noiseless at {h:.4} m: \
             {} s, {:.4} m; landings {} s and {} s",
            h - MAIN_M,
            a.time_s,
            a.altitude_m,
            b.time_s,
            b.altitude_m,
            noisy.metrics.landing_time_s.unwrap(),
            plain.metrics.landing_time_s.unwrap(),
        );
        // The same sample (the flights differ only by where their steps were cut, 1e-9 s
        // and below, far from a sample's 10 ms), just below h'.
        assert_eq!(a.time_s, b.time_s);
        assert!(h - a.altitude_m > 0.0 && h - a.altitude_m <= one_sample * 1.001);
        assert_eq!(
            event(&noisy, EventKind::ParachuteDeploy(1)).time_s,
            a.time_s + 1.0
        );
        // The drogue's apogee trigger reads no pressure: the same sample in both.
        assert_eq!(
            event(&noisy, EventKind::ParachuteTrigger(0)).time_s,
            event(&plain, EventKind::ParachuteTrigger(0)).time_s
        );
        // The same flight after that but for where the steps were cut (the noisy one at the
        // sample, the other at the crossing and then the sample): landings 80 s later within
        // what the integrator's tolerance allows over them (rtol 1e-7 of 80 s = 8e-6 s; seen:
        // 4e-8 s and 7e-6 s).
        let (ta, tb) = (
            noisy.metrics.landing_time_s.unwrap(),
            plain.metrics.landing_time_s.unwrap(),
        );
        assert!((ta - tb).abs() < 2e-5, "{ta} s against {tb} s");
    }
}

/// An independent model of the noisy main: the center falls at `v` m/s through the trigger
/// height, the barometer's samples fall at a uniformly random phase, its noise is the
/// recurrence n_k = α n_{k−1} + β (b + σ Z_k) started settled, and a sample fires when
/// `h_k − n_k / (ρ g) < 300` (the pressure linear in height over these few metres). Returns
/// the mean and deviation of the height (above the trigger) at which it fires.
fn first_passage_model(v: f64, rho_g: f64, noise: SensorNoise, runs: usize) -> (f64, f64) {
    // SplitMix64 and Box–Muller: none of the engine's generators.
    struct SplitMix(u64);
    impl SplitMix {
        fn uniform(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            (((z ^ (z >> 31)) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        }
        fn normal(&mut self) -> f64 {
            let (u1, u2) = (self.uniform(), self.uniform());
            (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
        }
    }
    let mut rng = SplitMix(0x1234_5678_9ABC_DEF0);
    let (a, s, b) = (noise.correlation, noise.std_pa, noise.bias_pa);
    let beta = (1.0 - a * a).sqrt();
    let dz = v / RATE_HZ;
    let mut fired = Vec::with_capacity(runs);
    for _ in 0..runs {
        // Start 30 m above (40 deviations of height for these numbers), settled.
        let mut n = noise.settled_mean_pa() + s * rng.normal();
        let mut h = 30.0 + dz * rng.uniform();
        loop {
            if h - n / rho_g < 0.0 {
                fired.push(h);
                break;
            }
            h -= dz;
            n = a * n + beta * (b + s * rng.normal());
        }
    }
    let mean = fired.iter().sum::<f64>() / runs as f64;
    let var = fired.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (runs - 1) as f64;
    (mean, var.sqrt())
}

#[test]
fn a_noisy_barometer_scatters_the_main_as_a_first_passage_of_its_noise_and_repeats_by_seed() {
    // RocketPy's example noise: no bias, 8.3 Pa, correlation 0.5.
    let noise = SensorNoise {
        bias_pa: 0.0,
        std_pa: 8.3,
        correlation: 0.5,
    };
    let plain = fly(MAIN_M, None, 0);
    let v = event(&plain, EventKind::ParachuteTrigger(1)).speed_m_s; // still air: vertical
    let air = Atmosphere::standard(0.0).unwrap().at(MAIN_M);
    let rho_g = air.density_kg_m3 * 9.80665;
    let seeds = 300;
    let heights: Vec<f64> = (0..seeds)
        .map(|seed| {
            let f = fly(MAIN_M, Some(noise), seed);
            let main = event(&f, EventKind::ParachuteTrigger(1));
            let k = (main.time_s * RATE_HZ).round();
            assert_eq!(main.time_s, k / RATE_HZ, "fires on a sample");
            main.altitude_m - MAIN_M
        })
        .collect();
    let mean = heights.iter().sum::<f64>() / seeds as f64;
    let sd = (heights.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (seeds - 1) as f64).sqrt();
    let (model_mean, model_sd) = first_passage_model(v, rho_g, noise, 200_000);
    let se = sd / (seeds as f64).sqrt();
    eprintln!(
        "main at {v:.3} m/s, one sample {:.4} m, σ/(ρg) = {:.4} m: fires {mean:.4} ± {sd:.4} m \
         above {MAIN_M} m over {seeds} seeds (standard error {se:.4} m); the first-passage \
         model {model_mean:.4} ± {model_sd:.4} m",
        v / RATE_HZ,
        8.3 / rho_g
    );
    // Early, as a first passage is: above the trigger height on average, by more than the
    // noiseless sampled main (which fires up to one sample below).
    assert!(mean > 0.0);
    // The mean within four standard errors of the model's (whose own is 40× smaller), and
    // the deviation within 15 % (its relative standard error over 300 flights is about 4 %).
    assert!(
        (mean - model_mean).abs() < 4.0 * se,
        "{mean} m against the model's {model_mean} m"
    );
    assert!(
        (sd / model_sd - 1.0).abs() < 0.15,
        "{sd} m against {model_sd} m"
    );
    // The same seed, the same flight; another seed, another.
    let (a, b) = (fly(MAIN_M, Some(noise), 7), fly(MAIN_M, Some(noise), 7));
    assert_eq!(a.metrics.landing_time_s, b.metrics.landing_time_s);
    assert_eq!(
        event(&a, EventKind::ParachuteTrigger(1)).time_s,
        event(&b, EventKind::ParachuteTrigger(1)).time_s
    );
    // The seeds fire at many samples (0.12 m apart: a deviation of 0.5 m spans about 20).
    let distinct: std::collections::BTreeSet<u64> = heights.iter().map(|h| h.to_bits()).collect();
    assert!(distinct.len() >= 10, "{} distinct", distinct.len());
}

#[test]
fn a_noisy_barometer_needs_a_sampling_rate_and_numbers_in_range() {
    let noise = SensorNoise {
        bias_pa: 0.0,
        std_pa: 8.3,
        correlation: 0.5,
    };
    let refused = |p: Parachute| {
        Simulation::new(
            design("synthetic-54mm-three-fin.json"),
            motor("Cesaroni_I175"),
            Environment::default(),
            Rail::default(),
        )
        .and_then(|s| s.with_parachutes(vec![p]))
        .expect_err("refused")
        .to_string()
    };
    let main = || {
        Parachute::new(
            "main",
            0.9,
            Trigger::HeightDescending { height_m: 300.0 },
            1.0,
        )
    };
    let e = refused(main().with_noise(noise));
    assert!(
        e.contains("parachute 0 (\"main\")") && e.contains("sampling_rate_hz"),
        "{e}"
    );
    let e = refused(main().with_sampling_rate(100.0).with_noise(SensorNoise {
        std_pa: -1.0,
        ..noise
    }));
    assert!(
        e.contains("noise field \"std_pa\"") && e.contains("-1"),
        "{e}"
    );
    let e = refused(main().with_sampling_rate(100.0).with_noise(SensorNoise {
        correlation: 2.0,
        ..noise
    }));
    assert!(e.contains("noise field \"correlation\""), "{e}");
}
