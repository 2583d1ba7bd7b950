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

/// Variant `i`'s draws: the structure's change of mass, kg, the ballast's mass, kg, the
/// motor's impulse scale, the drag scale, the wind's speed, m/s, and direction, degrees, the
/// rail's inclination, degrees, the drogue's and the main's CdS, m², the ballast's travel,
/// m, and the time it starts, s.
pub fn draws(i: usize) -> [f64; 11] {
    let mut r = Rng::of_variant(SEED, i);
    [
        r.uniform(-0.02, 0.02),
        r.uniform(0.18, 0.22),
        r.uniform(0.97, 1.03),
        r.uniform(0.95, 1.05),
        r.uniform(0.0, 6.0),
        r.uniform(0.0, 360.0),
        r.uniform(85.0, 89.0),
        r.uniform(0.09, 0.11),
        r.uniform(0.85, 0.95),
        r.uniform(0.0, 0.3),
        r.uniform(4.0, 7.0),
    ]
}

/// The columns of variants `rows`, drawn from (SEED, variant index): each input's value as
/// a scenario writes it (the structure's mass, the motor's impulse).
pub fn columns_of(rows: std::ops::Range<usize>) -> Columns {
    use hpr_sim::inputs::Input::*;
    // The design's structure and the motor's impulse, found once (not in the timed chunks).
    static NOMINALS: std::sync::OnceLock<(f64, f64)> = std::sync::OnceLock::new();
    let &(dry, impulse) = NOMINALS.get_or_init(|| {
        (
            hpr_design::mass::dry(&design()).mass_kg,
            motor::find("Cesaroni_I175").unwrap().total_impulse_ns(),
        )
    });
    let d: Vec<[f64; 11]> = rows.clone().map(draws).collect();
    let col = |k: usize, f: &dyn Fn(f64) -> f64| d.iter().map(|x| f(x[k])).collect::<Vec<_>>();
    Columns::new(rows.len())
        .with(StructureMassKg, col(0, &|v| dry + v))
        .with(BallastKg, col(1, &|v| v))
        .with(MotorImpulseNs, col(2, &|v| impulse * v))
        .with(DragScale, col(3, &|v| v))
        .with(WindSpeedMS, col(4, &|v| v))
        .with(WindFromDeg, col(5, &|v| v))
        .with(RailInclinationDeg, col(6, &|v| v))
        .with(ParachuteCdsM2(0), col(7, &|v| v))
        .with(ParachuteCdsM2(1), col(8, &|v| v))
        .with(ShiftTravelM(0), col(9, &|v| v))
        .with(ShiftTrigger(0), col(10, &|v| v))
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
    let d = draws(i);
    let wind = Wind::constant(d[4], d[5]).unwrap();
    let env = Environment {
        wind,
        ..Environment::default()
    };
    let rail = Rail {
        inclination_deg: d[6],
        ..Rail::default()
    };
    let mut ch = chutes();
    ch[0].cds_m2 = d[7];
    ch[1].cds_m2 = d[8];
    let sim = Simulation::with_motor_options(
        design.clone(),
        motor::find("Cesaroni_I175").unwrap(),
        MotorOptions::default().with_impulse_scale(d[2]),
        env,
        rail,
    )
    .and_then(|s| s.with_drag_scale(d[3]))
    .and_then(|s| s.with_part_mass("ballast", d[1]))
    .and_then(|s| s.with_mass_adjustment(d[0], 0.0))
    .and_then(|s| s.with_parachutes(ch))
    .and_then(|s| {
        s.with_shifts(vec![MassShift::new(
            Trigger::Time { time_s: d[10] },
            "ballast",
            d[9],
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
