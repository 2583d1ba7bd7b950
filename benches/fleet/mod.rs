//! The fleet both whole-flight benchmarks fly (`batch.rs`, its own harness, and `flights.rs`,
//! criterion's): the batch tests' variants of the reference design with its ballast moving,
//! drogue and main, wind, rail, motor and mass dispersions, drawn from (seed, variant index)
//! chunk by chunk; and the same variants as `Simulation`s set up from scratch, what a user
//! without the batch engine writes.

#![allow(dead_code)] // each benchmark uses part of it

use hpr_design::motor::{self, MotorOptions};
use hpr_design::Design;
use hpr_sim::batch::{Batch, Columns};
use hpr_sim::flight::{Environment, Parachute, Rail, SimOptions, Simulation};
use hpr_sim::reference;
use hpr_sim::wind::Wind;
use hpr_sim::{MassShift, Trigger};

pub struct Rng(u64);
impl Rng {
    /// Variant `i`'s generator: its draws depend only on (seed, i).
    fn of_variant(seed: u64, i: usize) -> Rng {
        Rng(seed ^ (i as u64).wrapping_mul(0xD1B5_4A32_D192_ED03))
    }
    fn uniform(&mut self, a: f64, b: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        a + (b - a) * (((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64)
    }
}

pub const SEED: u64 = 2026;

pub fn chutes() -> Vec<Parachute> {
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

/// The columns of variants `rows`, drawn from (SEED, variant index).
pub fn columns_of(rows: std::ops::Range<usize>) -> Columns {
    let mut c = Columns {
        len: rows.len(),
        chute_cds_m2: vec![vec![], vec![]],
        shift_travel_m: vec![vec![]],
        shift_trigger: vec![vec![]],
        ..Columns::default()
    };
    for i in rows {
        let mut r = Rng::of_variant(SEED, i);
        c.structure_delta_mass_kg.push(r.uniform(-0.02, 0.02));
        c.part_mass_kg.push(r.uniform(0.18, 0.22));
        c.impulse_scale.push(r.uniform(0.97, 1.03));
        c.drag_scale.push(r.uniform(0.95, 1.05));
        c.wind_speed_m_s.push(r.uniform(0.0, 6.0));
        c.wind_from_deg.push(r.uniform(0.0, 360.0));
        c.rail_inclination_deg.push(r.uniform(85.0, 89.0));
        c.chute_cds_m2[0].push(r.uniform(0.09, 0.11));
        c.chute_cds_m2[1].push(r.uniform(0.85, 0.95));
        c.shift_travel_m[0].push(r.uniform(0.0, 0.3));
        c.shift_trigger[0].push(r.uniform(4.0, 7.0));
    }
    c
}

/// The fleet's base flight: the reference rocket with its ballast moving
/// ([`reference::worked_example`]) under the drogue and the main.
pub fn base() -> Simulation {
    reference::worked_example()
        .with_parachutes(chutes())
        .unwrap()
}

/// What a user without the batch engine writes: a Simulation per variant, flown in a rayon loop.
pub fn from_scratch(design: &Design, i: usize) -> f64 {
    let (c, i) = (&columns_of(i..i + 1), 0);
    let wind = Wind::constant(c.wind_speed_m_s[i], c.wind_from_deg[i]).unwrap();
    let env = Environment {
        wind,
        ..Environment::default()
    };
    let rail = Rail {
        inclination_deg: c.rail_inclination_deg[i],
        ..Rail::default()
    };
    let mut ch = chutes();
    ch[0].cds_m2 = c.chute_cds_m2[0][i];
    ch[1].cds_m2 = c.chute_cds_m2[1][i];
    let sim = Simulation::with_motor_options(
        design.clone(),
        motor::find("Cesaroni_I175").unwrap(),
        MotorOptions::default().with_impulse_scale(c.impulse_scale[i]),
        env,
        rail,
    )
    .and_then(|s| s.with_drag_scale(c.drag_scale[i]))
    .and_then(|s| s.with_part_mass("ballast", c.part_mass_kg[i]))
    .and_then(|s| s.with_mass_adjustment(c.structure_delta_mass_kg[i], 0.0))
    .and_then(|s| s.with_parachutes(ch))
    .and_then(|s| {
        s.with_shifts(vec![MassShift::new(
            Trigger::Time {
                time_s: c.shift_trigger[0][i],
            },
            "ballast",
            c.shift_travel_m[0][i],
            1.0,
        )])
    })
    .and_then(|s| {
        s.with_options(SimOptions {
            keep_samples: false,
            ..SimOptions::default()
        })
    });
    match sim.and_then(|s| s.run(&mut ())) {
        Ok(f) => f.metrics.apogee_m.unwrap_or(0.0),
        Err(_) => 0.0,
    }
}

/// The reference design, which each variant set up from scratch clones.
pub fn design() -> Design {
    reference::design()
}

/// The batch of the fleet's base flight, moving the ballast.
pub fn batch() -> Batch {
    Batch::new(base(), Some(reference::BALLAST)).unwrap()
}

/// Flies variants `0..n` through `batch` (chunks of 16 lanes, 64 variants per chunk of
/// columns) on the current rayon pool; the sum of their apogees.
pub fn fly_batch(batch: &Batch, n: usize) -> f64 {
    let mut sum = 0.0;
    batch
        .run(n, 16, 64, columns_of, |r| {
            sum += r.metrics.apogee_m.unwrap_or(0.0)
        })
        .unwrap();
    sum
}
