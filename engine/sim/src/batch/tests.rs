//! The batch engine's contract: every lane is the single flight with the same inputs, and
//! results do not depend on threads or chunking.

use super::*;
use crate::eom::{pack_mass, MassLanes, N6};
use crate::flight::model::{derivative_6dof_lanes, FlightModel, FourModels};
use crate::flight::{AirModel, Environment, Parachute, Rail, SimOptions, Simulation};
use crate::lanes::{F64x4, Real};
use crate::reference;
use crate::trigger::Trigger;
use crate::wind::Wind;
use crate::MassShift;
use hpr_design::motor::MotorOptions;

mod air;
mod kernels;
mod noise;
mod prefix;
mod releases;
mod turbulence;

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

/// A drogue watched continuously and a main fired by an altimeter sampling at 20 Hz (its
/// trigger fires at a stop time of its own, after the crossing).
fn chutes() -> Vec<Parachute> {
    vec![
        Parachute::new("drogue", 0.1, Trigger::Apogee, 1.0),
        Parachute::new(
            "main",
            0.9,
            Trigger::HeightDescending { height_m: 300.0 },
            1.0,
        )
        .with_sampling_rate(20.0),
    ]
}

/// The site of the random variants: a latitude (Coriolis on) and its ellipsoid's gravity, which
/// the elevation column moves.
const LATITUDE_DEG: f64 = 35.0;

fn site(elevation_m: f64) -> Environment {
    Environment {
        elevation_m,
        gravity: crate::gravity::Gravity::somigliana(LATITUDE_DEG, elevation_m).unwrap(),
        latitude_deg: Some(LATITUDE_DEG),
        ..Environment::default()
    }
}

fn base() -> Simulation {
    let d = reference::design();
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
    .with_shifts(vec![reference::ballast_shift(5.0)])
    .unwrap()
}

impl Rng {
    /// The generator of variant `i` of the stream `seed`: a variant's row depends only on
    /// (seed, i), never on the rows generated with it.
    fn of_variant(seed: u64, i: usize) -> Rng {
        let mut r = Rng(seed ^ (i as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
        r.next();
        r
    }
}

/// The motor's total impulse and burn time and the design's structure, which the random
/// scales and changes of the variants are of.
fn nominals() -> (f64, f64, hpr_design::mass::MassProps) {
    let m = reference::motor();
    let dry = hpr_design::mass::dry(&reference::design());
    (m.total_impulse_ns(), m.burn_time_s(), dry)
}

/// The rows `rows` of random variants from stream `seed`; about one in twenty has a shift too
/// long for its holder (refused) and one in fifty a non-finite drag scale.
fn columns_of(rows: std::ops::Range<usize>, seed: u64) -> Columns {
    use Input::*;
    let (impulse, burn, dry) = nominals();
    let mut c = Columns::new(rows.len());
    for i in rows {
        let mut r = Rng::of_variant(seed, i);
        let mut push = |input: Input, v: f64| c.column_mut(input).push(v);
        push(StructureMassKg, dry.mass_kg + r.uniform(-0.02, 0.02));
        push(StructureCgM, dry.cg_m.x + r.uniform(-0.01, 0.01));
        push(BallastKg, r.uniform(0.15, 0.25));
        push(MotorImpulseNs, impulse * r.uniform(0.95, 1.05));
        push(MotorBurnTimeS, burn * r.uniform(0.97, 1.03));
        let drag = r.uniform(0.9, 1.1);
        push(DragScale, if i % 50 == 7 { f64::NAN } else { drag });
        push(WindSpeedMS, r.uniform(0.0, 8.0));
        push(WindFromDeg, r.uniform(0.0, 360.0));
        push(RailInclinationDeg, r.uniform(84.0, 90.0));
        push(RailHeadingDeg, r.uniform(0.0, 360.0));
        push(ElevationM, r.uniform(0.0, 1500.0));
        push(ParachuteCdsM2(0), r.uniform(0.08, 0.12));
        push(ParachuteCdsM2(1), r.uniform(0.8, 1.0));
        push(ParachuteLagS(0), r.uniform(0.5, 1.5));
        let travel = r.uniform(0.0, 0.3);
        push(ShiftTravelM(0), if i % 20 == 3 { 0.9 } else { travel });
        push(ShiftDurationS(0), r.uniform(0.2, 1.5));
        push(ShiftTrigger(0), r.uniform(3.0, 8.0));
        push(WindScale, r.uniform(0.5, 1.5));
        push(WindRotationDeg, r.uniform(-30.0, 30.0));
        push(TemperatureK, r.uniform(263.0, 313.0));
        push(PressurePa, r.uniform(95_000.0, 104_000.0));
    }
    c
}

/// Every lane of `batch.run(n, chunk, window, cols)` on a pool of `threads`, in variant order.
fn run_on(
    batch: &Batch,
    n: usize,
    threads: usize,
    chunk: usize,
    window: usize,
    cols: impl Fn(std::ops::Range<usize>) -> Columns + Sync + Send,
) -> Vec<LaneResult> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let mut out = Vec::new();
    pool.install(|| batch.run(n, chunk, window, cols, |r| out.push(r)))
        .unwrap();
    out
}

fn columns(n: usize, seed: u64) -> Columns {
    columns_of(0..n, seed)
}

/// The single-flight simulator set up from scratch with row `i`'s inputs.
fn single(c: &Columns, i: usize) -> Result<Simulation, String> {
    use Input::*;
    let e = |e: crate::flight::SimError| e.to_string();
    let at = |input: Input| c.get(input).expect("the column")[i];
    let (impulse, burn, dry) = nominals();
    let wind = Wind::constant(at(WindSpeedMS), at(WindFromDeg))
        .and_then(|w| w.transformed(at(WindScale), at(WindRotationDeg)))
        .map_err(|e| e.to_string())?;
    // The base's site is at sea level in the standard atmosphere: a site's air there.
    let air = AirModel::site(0.0, Some(at(TemperatureK)), Some(at(PressurePa)))
        .map_err(|e| e.to_string())?;
    let env = Environment {
        wind,
        air,
        ..site(at(ElevationM))
    };
    let rail = Rail {
        length_m: 2.0,
        inclination_deg: at(RailInclinationDeg),
        heading_deg: at(RailHeadingDeg),
    };
    let options = MotorOptions::default()
        .with_impulse_scale(at(MotorImpulseNs) / impulse)
        .with_time_scale(at(MotorBurnTimeS) / burn);
    let mut ch = chutes();
    ch[0].cds_m2 = at(ParachuteCdsM2(0));
    ch[0].lag_s = at(ParachuteLagS(0));
    ch[1].cds_m2 = at(ParachuteCdsM2(1));
    Simulation::with_motor_options(reference::design(), reference::motor(), options, env, rail)
        .and_then(|s| s.with_drag_scale(at(DragScale)))
        .and_then(|s| s.with_part_mass(reference::BALLAST, at(BallastKg)))
        .and_then(|s| {
            s.with_mass_adjustment(
                at(StructureMassKg) - dry.mass_kg,
                at(StructureCgM) - dry.cg_m.x,
            )
        })
        .and_then(|s| s.with_parachutes(ch))
        .and_then(|s| {
            s.with_shifts(vec![MassShift::new(
                Trigger::Time {
                    time_s: at(ShiftTrigger(0)),
                },
                reference::BALLAST,
                at(ShiftTravelM(0)),
                at(ShiftDurationS(0)),
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
        Some(m.max_dynamic_pressure_pa),
        m.liftoff_time_s,
        m.rail_exit_time_s,
        m.rail_exit_speed_m_s,
        m.burnout_time_s,
        m.static_margin_liftoff_cal,
        m.static_margin_rail_exit_cal,
        m.static_margin_burnout_cal,
        m.static_margin_min_cal,
        m.flight_margin_min_cal,
        m.max_alpha_deg,
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
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let (mut worst, mut landed, mut refused) = (0.0f64, 0, 0);
    let mut results = Vec::with_capacity(n);
    batch
        // Chunks of 40 rows, 16 in flight: lanes that land are replaced mid-chunk, and
        // groups of four mix lanes at different times of their flights.
        .run(n, 40, 4, |rows| columns_of(rows, 42), |r| results.push(r))
        .unwrap();
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
                assert!(!lane.flown);
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
                assert_eq!(lane.end_s, f.events.last().unwrap().time_s);
                let keys =
                    |w: &[crate::flight::Warning]| w.iter().map(|w| w.key()).collect::<Vec<_>>();
                assert_eq!(keys(&lane.warnings), keys(&f.warnings()), "variant {i}");
                for (k, chute) in lane.parachutes.iter().enumerate() {
                    let lane_deploy = chute.deploy_time_s.zip(chute.deploy_speed_m_s);
                    match (lane_deploy, f.deploy(k)) {
                        (Some(a), Some(b)) => {
                            worst = worst.max((a.0 - b.0).abs() / b.0.abs());
                            worst = worst.max((a.1 - b.1).abs() / b.1.abs());
                        }
                        (None, None) => {}
                        _ => panic!("variant {i}: parachute {k} opened in one and not the other"),
                    }
                }
                // The same attempts, the rejected ones (tried again at the lane's next group
                // step) included.
                assert_eq!(
                    lane.derivative_evaluations, f.derivative_evaluations,
                    "variant {i}"
                );
                assert!(lane.flown);
                landed += 1;
            }
        }
    }
    eprintln!("{n} variants: {landed} flown, {refused} refused; worst relative difference from the single flight {worst:.1e}");
    assert!(refused >= 40 && landed >= 900);
    assert!(worst <= 1e-9, "{worst:e} (bound 1e-9)");
}

#[test]
fn results_do_not_depend_on_threads_chunks_or_window() {
    let n = 96;
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let run_with = |threads: usize, chunk: usize, window: usize| {
        run_on(&batch, n, threads, chunk, window, |rows| {
            columns_of(rows, 7)
        })
    };
    let a = run_with(1, 8, 2);
    let b = run_with(2, 8, 4);
    let c = run_with(2, 5, 3);
    let d = run_with(2, 96, 1);
    assert_eq!(a.len(), n);
    // PartialEq on f64: bit-for-bit equal values (NaNs would differ, and there are none).
    assert!(
        a == b && a == c && a == d,
        "results differ with the thread count, chunk size or window"
    );
    // Columns held whole give the same lanes.
    let mut whole = Vec::new();
    batch
        .run_columns(&columns(n, 7), 7, 2, |r| whole.push(r))
        .unwrap();
    assert!(
        a == whole,
        "held columns give other results than streamed ones"
    );
}

#[test]
fn each_chunk_s_columns_are_asked_for_once_in_chunk_sized_ranges_covering_every_variant() {
    let (n, chunk, window) = (23, 4, 2);
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let asked = std::sync::Mutex::new(Vec::new());
    let mut seen = 0;
    batch
        .run(
            n,
            chunk,
            window,
            |rows| {
                asked.lock().unwrap().push(rows.clone());
                // Cheap lanes: every one refused by its drag scale, flown no further.
                Columns::new(rows.len()).with(Input::DragScale, vec![-1.0; rows.len()])
            },
            |r| {
                assert_eq!(r.variant, seen);
                assert_eq!(r.status, Status::Refused);
                assert_eq!(
                    r.error.as_deref(),
                    Some("drag scale must be positive and finite (got -1)")
                );
                seen += 1;
            },
        )
        .unwrap();
    assert_eq!(seen, n);
    let mut asked = asked.into_inner().unwrap();
    asked.sort_by_key(|r| r.start);
    let expected: Vec<_> = (0..n)
        .step_by(chunk)
        .map(|s| s..(s + chunk).min(n))
        .collect();
    assert_eq!(asked, expected);
}

#[test]
fn no_chunk_starts_more_than_a_window_beyond_the_first_not_yet_handed_on() {
    // Memory stays bounded: with 2 threads, chunks of 3 and a window of 2, when a chunk's
    // columns are asked for, the chunks before the window's start have all been sunk.
    let (n, chunk, window) = (60, 3, 2);
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let sunk = std::sync::atomic::AtomicUsize::new(0);
    let worst_lead = std::sync::atomic::AtomicUsize::new(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    pool.install(|| {
        batch.run(
            n,
            chunk,
            window,
            |rows| {
                let first_unsunk = sunk.load(std::sync::atomic::Ordering::SeqCst) / chunk;
                let lead = rows.start / chunk - first_unsunk;
                worst_lead.fetch_max(lead, std::sync::atomic::Ordering::SeqCst);
                columns_of(rows, 3)
            },
            |_| {
                sunk.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
            },
        )
    })
    .unwrap();
    assert_eq!(sunk.into_inner(), n);
    let lead = worst_lead.into_inner();
    assert!(
        lead < window,
        "a chunk started {lead} chunks ahead of the sink"
    );
}

#[test]
fn a_panic_in_the_columns_closure_reaches_the_caller_instead_of_hanging_the_workers() {
    // Chunk 0 panics while another worker waits for it to be sunk (window 1).
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        pool.install(|| {
            batch.run(
                8,
                2,
                1,
                |rows| {
                    if rows.start == 0 {
                        std::thread::sleep(std::time::Duration::from_millis(50));
                        panic!("columns of the first chunk");
                    }
                    columns_of(rows, 1)
                },
                |_| {},
            )
        })
    }));
    assert!(caught.is_err(), "the panic was swallowed");
}

#[test]
fn columns_of_the_wrong_length_or_shape_are_an_error_naming_the_variants() {
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let short = batch
        .run(10, 4, 1, |rows| columns_of(0..rows.len() - 1, 1), |_| {})
        .unwrap_err();
    assert_eq!(short, "the columns of variants 0..4 have 3 rows, not 4");
    let mut flown = 0;
    let bad = batch
        .run(
            10,
            4,
            1,
            |rows| {
                let n = if rows.start == 8 { 1 } else { rows.len() };
                let mut c = columns_of(rows, 1);
                *c.column_mut(Input::DragScale) = vec![1.0; n];
                c
            },
            |_| flown += 1,
        )
        .unwrap_err();
    assert_eq!(
        bad,
        "variants 8..10: column drag_scale has 1 values for 2 variants"
    );
    assert_eq!(flown, 8, "the chunks before the bad one are handed on");
    let no_part = Batch::new(base(), None)
        .unwrap()
        .run_columns(&columns(3, 1), 4, 1, |_| {})
        .unwrap_err();
    assert_eq!(
        no_part,
        "column ballast_kg needs the part it gives the mass of"
    );
    // A held column too short for its variants: refused before any flight, and a slice of it
    // past its end is refused by the chunk's check rather than panicking.
    let mut short = columns(6, 1);
    short.column_mut(Input::WindSpeedMS).truncate(5);
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let e = batch.run_columns(&short, 4, 1, |_| {}).unwrap_err();
    assert_eq!(e, "column wind_speed_m_s has 5 values for 6 variants");
    let e = batch.fly_chunk(&short.slice(4..6), 4).unwrap_err();
    assert_eq!(
        e,
        ColumnsError::Length {
            input: Input::WindSpeedMS,
            values: 1,
            variants: 2
        }
    );
    assert_eq!(
        e.to_string(),
        "column wind_speed_m_s has 1 values for 2 variants"
    );
}

#[test]
fn many_changes_with_one_rebuild_fly_exactly_as_the_same_changes_made_one_by_one() {
    let env = Environment {
        elevation_m: 800.0,
        wind: Wind::constant(5.0, 200.0).unwrap(),
        ..Environment::default()
    };
    let rail = Rail {
        length_m: 3.0,
        inclination_deg: 86.0,
        heading_deg: 10.0,
    };
    let scales = MotorOptions::default()
        .with_impulse_scale(1.02)
        .with_time_scale(0.98);
    let mut ch = chutes();
    ch[1].cds_m2 = 0.85;
    let shift = vec![MassShift::new(
        Trigger::Time { time_s: 6.0 },
        reference::BALLAST,
        0.2,
        0.7,
    )];
    let one_by_one = base()
        .with_site(env.clone(), rail)
        .and_then(|s| s.with_motor_scales(scales))
        .and_then(|s| s.with_drag_scale(1.07))
        .and_then(|s| s.with_part_mass(reference::BALLAST, 0.23))
        .and_then(|s| s.with_mass_adjustment(0.01, -0.004))
        .and_then(|s| s.with_parachutes(ch.clone()))
        .and_then(|s| s.with_shifts(shift.clone()))
        .unwrap();
    let at_once = base()
        .with_changes(|c| {
            c.shifts(shift)?;
            c.parachutes(ch)?;
            c.mass_adjustment(0.01, -0.004)?;
            c.part_mass(reference::BALLAST, 0.23)?;
            c.drag_scale(1.07)?;
            c.motor_scales(scales)?;
            c.site(env, rail)
        })
        .unwrap();
    let (a, b) = (
        one_by_one.run(&mut ()).unwrap(),
        at_once.run(&mut ()).unwrap(),
    );
    assert_eq!(a.metrics, b.metrics, "bit-for-bit the same metrics");
    assert_eq!(a.events, b.events);
    assert!(a.metrics.apogee_m.unwrap() > 100.0);

    // A refused change gives the builder's words, whatever else changes with it.
    let alone = base().with_drag_scale(0.0).unwrap_err().to_string();
    let among = base()
        .with_changes(|c| {
            c.part_mass(reference::BALLAST, 0.3)?;
            c.drag_scale(0.0)?;
            c.mass_adjustment(0.0, 0.0)
        })
        .unwrap_err()
        .to_string();
    assert_eq!(alone, "drag scale must be positive and finite (got 0)");
    assert_eq!(among, alone);
}

#[test]
fn an_elevation_column_moves_an_inverse_square_gravity_with_the_site() {
    use crate::gravity::Gravity;
    let inverse_square_site = |elevation_m: f64| Environment {
        elevation_m,
        gravity: Gravity::inverse_square(elevation_m).unwrap(),
        ..Environment::default()
    };
    let batch = Batch::new(
        base()
            .with_site(inverse_square_site(0.0), *base().rail())
            .unwrap(),
        None,
    )
    .unwrap();
    let c = Columns::new(1).with(Input::ElevationM, vec![2500.0]);
    let lane = batch.variant(&c, 0).unwrap();
    assert_eq!(
        lane.environment().gravity,
        Gravity::inverse_square(2500.0).unwrap()
    );
    let single = batch
        .base()
        .clone()
        .with_site(inverse_square_site(2500.0), *base().rail())
        .unwrap();
    assert_eq!(
        lane.run(&mut ()).unwrap().metrics,
        single.run(&mut ()).unwrap().metrics
    );
}

#[test]
fn a_part_that_weighs_nothing_in_the_design_has_no_mass_to_scale() {
    let mut d = reference::design();
    let idx = d.component_index(reference::BALLAST).unwrap();
    d.components[idx].mass_spec = hpr_design::design::model::MassSpec::Mass(0.0);
    let sim = Simulation::new(
        d,
        reference::motor(),
        Environment::default(),
        Rail::default(),
    )
    .unwrap();
    let e = sim
        .with_part_mass(reference::BALLAST, 0.2)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "part mass of \"ballast\": it weighs 0 kg in the design, so it has no mass to scale; give it a mass in the design");
}

#[test]
fn a_wind_table_is_scaled_and_turned_lane_by_lane_as_a_single_flight_with_that_table() {
    let rows = [
        crate::wind::WindRow {
            height_agl_m: 0.0,
            speed_m_s: 3.0,
            from_deg: 250.0,
        },
        crate::wind::WindRow {
            height_agl_m: 1500.0,
            speed_m_s: 12.0,
            from_deg: 300.0,
        },
    ];
    let table = Wind::table(&rows).unwrap();
    let with_wind = |wind: Wind| {
        let sim = base();
        let env = Environment {
            wind,
            ..sim.environment().clone()
        };
        let rail = *sim.rail();
        sim.with_changes(|c| c.site(env, rail)).unwrap()
    };
    let batch = Batch::new(with_wind(table.clone()), Some(reference::BALLAST)).unwrap();
    let (scales, turns) = ([0.0, 0.5, 1.0, 1.7, 2.2], [0.0, -35.0, 0.0, 120.0, 15.0]);
    let c = Columns::new(5)
        .with(Input::WindScale, scales.to_vec())
        .with(Input::WindRotationDeg, turns.to_vec());
    let mut lanes = Vec::new();
    batch.run_columns(&c, 5, 1, |r| lanes.push(r)).unwrap();
    let bits = |m: &Metrics| -> Vec<Option<u64>> {
        metric_list(m).iter().map(|v| v.map(f64::to_bits)).collect()
    };
    let mut landings = Vec::new();
    for (i, lane) in lanes.iter().enumerate() {
        // From scratch: the table itself scaled and turned, as the site of a plain flight.
        let f = with_wind(table.transformed(scales[i], turns[i]).unwrap())
            .run(&mut ())
            .unwrap();
        assert_eq!(lane.status, Status::Landed, "variant {i}");
        assert_eq!(bits(&lane.metrics), bits(&f.metrics), "variant {i}");
        landings.push(f.metrics.landing_position_m.unwrap());
    }
    // Scaled to nothing, the table is calm air; scaled and turned, it moves the landing.
    let calm = base()
        .run(&mut ())
        .unwrap()
        .metrics
        .landing_position_m
        .unwrap();
    let apart = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    assert!(apart(landings[0], calm) < 1e-9, "{landings:?} {calm:?}");
    assert!(apart(landings[1], landings[2]) > 5.0, "{landings:?}");
    assert!(apart(landings[3], landings[2]) > 5.0, "{landings:?}");
    // A table has no single speed or direction for a column to set.
    let speed = Columns::new(1).with(Input::WindSpeedMS, vec![4.0]);
    let e = batch.variant(&speed, 0).unwrap_err();
    assert!(e.contains("wind_scale and wind_rotation_deg"), "{e}");
}

#[test]
fn a_motor_dry_mass_column_adds_its_change_to_the_rocket_at_liftoff() {
    let batch = Batch::new(base(), None).unwrap();
    let nominal = batch.base().motor().dry_mass_kg();
    let c = Columns::new(1).with(Input::MotorDryMassKg, vec![nominal + 0.1]);
    let lane = batch.variant(&c, 0).unwrap();
    let mass = |s: &Simulation| s.mass_properties_at(0.0).mass_kg;
    let added = mass(&lane) - mass(batch.base());
    assert!((added - 0.1).abs() < 1e-12, "{added} kg added");
}
