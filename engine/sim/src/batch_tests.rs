//! The batch engine's contract: every lane is the single flight with the same inputs, and
//! results do not depend on threads or chunking.

use super::*;
use crate::flight::{Environment, Parachute, Rail, SimOptions, Simulation};
use crate::MassShift;
use hpr_design::motor::{self, MotorOptions};
use hpr_design::Design;

const REFERENCE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../validation/designs/synthetic-54mm-three-fin.json"
);

/// A small deterministic generator (SplitMix64) so the test needs no dependency.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn uniform(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

fn chutes() -> Vec<Parachute> {
    vec![
        Parachute::new("drogue", 0.1, Trigger::Apogee, 1.0),
        Parachute::new(
            "main",
            0.9,
            Trigger::HeightDescending { height_m: 300.0 },
            1.0,
        ),
    ]
}

fn base() -> Simulation {
    let d = Design::load(REFERENCE).unwrap();
    Simulation::new(
        d,
        motor::find("Cesaroni_I175").unwrap(),
        Environment::default(),
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
        Trigger::Time { time_s: 5.0 },
        "ballast",
        0.3,
        1.0,
    )])
    .unwrap()
}

/// `n` random variants; about one in twenty has a shift too long for its holder (refused) and
/// one in fifty a non-finite drag scale.
fn columns(n: usize, seed: u64) -> Columns {
    let mut r = Rng(seed);
    let mut c = Columns {
        len: n,
        ..Columns::default()
    };
    for i in 0..n {
        c.structure_delta_mass_kg.push(r.uniform(-0.02, 0.02));
        c.structure_delta_cg_m.push(r.uniform(-0.01, 0.01));
        c.part_mass_kg.push(r.uniform(0.15, 0.25));
        c.impulse_scale.push(r.uniform(0.95, 1.05));
        c.time_scale.push(r.uniform(0.97, 1.03));
        c.drag_scale.push(if i % 50 == 7 {
            f64::NAN
        } else {
            r.uniform(0.9, 1.1)
        });
        c.wind_speed_m_s.push(r.uniform(0.0, 8.0));
        c.wind_from_deg.push(r.uniform(0.0, 360.0));
        c.rail_inclination_deg.push(r.uniform(84.0, 90.0));
        c.rail_heading_deg.push(r.uniform(0.0, 360.0));
        c.elevation_m.push(r.uniform(0.0, 1500.0));
    }
    c.chute_cds_m2 = vec![
        (0..n).map(|_| r.uniform(0.08, 0.12)).collect(),
        (0..n).map(|_| r.uniform(0.8, 1.0)).collect(),
    ];
    c.chute_lag_s = vec![(0..n).map(|_| r.uniform(0.5, 1.5)).collect(), vec![]];
    c.shift_travel_m = vec![(0..n)
        .map(|i| {
            if i % 20 == 3 {
                0.9
            } else {
                r.uniform(0.0, 0.3)
            }
        })
        .collect()];
    c.shift_duration_s = vec![(0..n).map(|_| r.uniform(0.2, 1.5)).collect()];
    c.shift_trigger = vec![(0..n).map(|_| r.uniform(3.0, 8.0)).collect()];
    c
}

/// The single-flight simulator set up from scratch with row `i`'s inputs.
fn single(c: &Columns, i: usize) -> Result<Simulation, String> {
    let e = |e: crate::flight::SimError| e.to_string();
    let wind =
        Wind::constant(c.wind_speed_m_s[i], c.wind_from_deg[i]).map_err(|e| e.to_string())?;
    let env = Environment {
        elevation_m: c.elevation_m[i],
        wind,
        ..Environment::default()
    };
    let rail = Rail {
        length_m: 2.0,
        inclination_deg: c.rail_inclination_deg[i],
        heading_deg: c.rail_heading_deg[i],
    };
    let options = MotorOptions::default()
        .with_impulse_scale(c.impulse_scale[i])
        .with_time_scale(c.time_scale[i]);
    let mut ch = chutes();
    ch[0].cds_m2 = c.chute_cds_m2[0][i];
    ch[0].lag_s = c.chute_lag_s[0][i];
    ch[1].cds_m2 = c.chute_cds_m2[1][i];
    Simulation::with_motor_options(
        Design::load(REFERENCE).unwrap(),
        motor::find("Cesaroni_I175").unwrap(),
        options,
        env,
        rail,
    )
    .and_then(|s| s.with_drag_scale(c.drag_scale[i]))
    .and_then(|s| s.with_part_mass("ballast", c.part_mass_kg[i]))
    .and_then(|s| s.with_mass_adjustment(c.structure_delta_mass_kg[i], c.structure_delta_cg_m[i]))
    .and_then(|s| s.with_parachutes(ch))
    .and_then(|s| {
        s.with_shifts(vec![MassShift::new(
            Trigger::Time {
                time_s: c.shift_trigger[0][i],
            },
            "ballast",
            c.shift_travel_m[0][i],
            c.shift_duration_s[0][i],
        )])
    })
    .and_then(|s| {
        s.with_options(SimOptions {
            keep_samples: false,
            ..SimOptions::default()
        })
    })
    .map_err(e)
}

fn metric_list(m: &Metrics) -> Vec<Option<f64>> {
    let l = m.landing_position_m;
    vec![
        m.apogee_m,
        m.apogee_time_s,
        Some(m.max_speed_m_s),
        Some(m.max_mach),
        Some(m.max_accel_m_s2),
        m.liftoff_time_s,
        m.rail_exit_time_s,
        m.rail_exit_speed_m_s,
        m.burnout_time_s,
        m.static_margin_liftoff_cal,
        m.static_margin_rail_exit_cal,
        m.static_margin_burnout_cal,
        m.static_margin_min_cal,
        m.flight_margin_min_cal,
        m.landing_time_s,
        l.map(|p| p[0]),
        l.map(|p| p[1]),
        m.landing_speed_m_s,
    ]
}

#[test]
fn every_lane_equals_the_single_flight_with_the_same_inputs() {
    let n = 1000;
    let c = columns(n, 42);
    let batch = Batch::new(base(), Some("ballast"), c.clone()).unwrap();
    let (mut worst, mut landed, mut refused) = (0.0f64, 0, 0);
    let mut results = Vec::with_capacity(n);
    batch.run(16, 4, |r| results.push(r));
    assert_eq!(results.len(), n);
    for (i, lane) in results.iter().enumerate() {
        assert_eq!(lane.variant, i, "results come in variant order");
        match single(&c, i) {
            Err(e) => {
                assert_eq!(
                    lane.status,
                    Status::Refused,
                    "variant {i}: the single flight refused ({e}) but the lane {:?}",
                    lane.status
                );
                refused += 1;
            }
            Ok(sim) => {
                let f = sim.run(&mut ()).unwrap();
                assert_eq!(
                    lane.status,
                    if f.metrics.landing_time_s.is_some() {
                        Status::Landed
                    } else {
                        Status::TimeLimit
                    }
                );
                for (a, b) in metric_list(&lane.metrics)
                    .iter()
                    .zip(metric_list(&f.metrics))
                {
                    match (a, b) {
                        (Some(a), Some(b)) => {
                            worst = worst.max((a - b).abs() / b.abs().max(1e-300))
                        }
                        (None, None) => {}
                        _ => panic!("variant {i}: a metric exists in one and not the other"),
                    }
                }
                assert_eq!(lane.shifts[0].start_s, f.shift_starts_s[0]);
                landed += 1;
            }
        }
    }
    eprintln!("{n} variants: {landed} flown, {refused} refused; worst relative difference from the single flight {worst:.1e}");
    assert!(refused >= 40 && landed >= 900);
    assert!(worst <= 1e-9, "{worst:e} (bound 1e-9)");
}

#[test]
fn results_do_not_depend_on_threads_or_chunks() {
    let n = 96;
    let batch = Batch::new(base(), Some("ballast"), columns(n, 7)).unwrap();
    let run_with = |threads: usize, chunk: usize, window: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out = Vec::new();
        pool.install(|| batch.run(chunk, window, |r| out.push(r)));
        out
    };
    let a = run_with(1, 8, 2);
    let b = run_with(2, 8, 4);
    let c = run_with(2, 5, 3);
    assert_eq!(a.len(), n);
    // PartialEq on f64: bit-for-bit equal values (NaNs would differ, and there are none).
    assert!(
        a == b && a == c,
        "results differ with the thread count or chunk size"
    );
}
