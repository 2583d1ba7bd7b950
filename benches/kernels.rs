//! The kernels every flight and every batch lane calls, timed alone: the cycloid, the
//! mass-property kernel and the 6-DOF derivative (one lane at a time, as a single flight calls
//! it, and four at a time, as the batch engine does), over 1,024 lanes of different instants
//! (reported by criterion as elements per second: lanes or evaluations per second); and the
//! one set-up a variant can pay on its own, a site's air table.
//!
//! `cargo bench --bench kernels`

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use hpr_sim::atmosphere::{AirModel, AirTable};
use hpr_sim::batch::eval_four;
use hpr_sim::cycloid;
use hpr_sim::eom::{pack_mass, MassLanes};
use hpr_sim::flight::model::FourModels;
use hpr_sim::flight::model::MAX_SHIFTS;
use hpr_sim::flight::Simulation;
use hpr_sim::lanes::{F64x4, Real};
use hpr_sim::reference;
use std::hint::black_box;

const LANES: usize = 1024;

/// The reference rocket with its ballast moving from 1 s, during the burn: the mass kernel
/// evaluates the motor and the moving part together.
fn simulation() -> Simulation {
    reference::simulation()
        .with_shifts(vec![reference::ballast_shift(1.0)])
        .unwrap()
}

fn kernels(c: &mut Criterion) {
    let sim = simulation();
    let model = sim.model();
    let times: Vec<f64> = (0..LANES)
        .map(|i| 0.5 + 3.0 * i as f64 / LANES as f64)
        .collect();
    let mut starts = [f64::INFINITY; MAX_SHIFTS];
    starts[0] = 1.0;

    let mut g = c.benchmark_group("kernels");
    g.throughput(Throughput::Elements(LANES as u64));
    g.bench_function("cycloid (lanes)", |b| {
        b.iter(|| {
            times
                .iter()
                .map(|&t| cycloid::evaluate(black_box(t), 1.0, 1.0, 0.3).accel_m_s2)
                .sum::<f64>()
        })
    });
    g.bench_function("mass properties at an instant (lanes)", |b| {
        b.iter(|| {
            times
                .iter()
                .map(|&t| model.instant(&starts, black_box(t)).mass.r_cm_accel.z)
                .sum::<f64>()
        })
    });
    // A climbing, slightly tilted, slowly turning state at each lane's instant.
    let q = nalgebra::UnitQuaternion::from_euler_angles(0.02, -0.01, 0.0);
    let q = q.quaternion();
    let states: Vec<[f64; 13]> = (0..LANES)
        .map(|i| {
            let v = 50.0 + 250.0 * i as f64 / LANES as f64;
            [
                3.0, 1.0, 300.0, 2.0, 1.0, v, q.w, q.i, q.j, q.k, 0.01, -0.02, 0.5,
            ]
        })
        .collect();
    g.bench_function("6-DOF derivative (evaluations)", |b| {
        b.iter_batched_ref(
            || [0.0; 13],
            |dy| {
                let mut s = 0.0;
                for (t, y) in times.iter().zip(&states) {
                    model.derivative_6dof(&starts, *t, y, dy);
                    s += dy[5];
                }
                s
            },
            BatchSize::SmallInput,
        )
    });
    // The same evaluations four lanes at a time, as the batch engine makes them: each
    // lane's mass state packed beside three others', one four-lane kernel call.
    let four = FourModels::new([model; 4]).unwrap();
    let packs: Vec<(MassLanes<F64x4>, F64x4, [F64x4; 13])> = (0..LANES / 4)
        .map(|p| {
            let lanes: [usize; 4] = std::array::from_fn(|l| 4 * p + l);
            let inst = lanes.map(|i| model.instant(&starts, times[i]));
            let ms = inst.map(|i| MassLanes::of(&i.mass));
            let thrust = F64x4::from_fn(|l| inst[l].motor.thrust_n);
            let y = std::array::from_fn(|k| F64x4::from_fn(|l| states[lanes[l]][k]));
            (pack_mass([&ms[0], &ms[1], &ms[2], &ms[3]]), thrust, y)
        })
        .collect();
    g.bench_function(
        "6-DOF derivative, four lanes at a time (evaluations)",
        |b| {
            b.iter_batched_ref(
                || [F64x4::splat(0.0); 13],
                |dy| {
                    let mut s = 0.0;
                    for (ms, thrust, y) in &packs {
                        eval_four(&four, None, ms, *thrust, F64x4::splat(0.0), y, dy);
                        s += dy[5].0[0];
                    }
                    s
                },
                BatchSize::SmallInput,
            )
        },
    );
    g.finish();

    // What a variant whose site air is swept or dispersed pays before it flies: its own air
    // table (a hot, low site's; the standard's is built once per process).
    let mut g = c.benchmark_group("set-up");
    g.throughput(Throughput::Elements(1));
    let site = AirModel::Site {
        elevation_m: 1400.0,
        temperature_k: 308.15,
        pressure_pa: 85_600.0,
    };
    g.bench_function("a site's air table (tables)", |b| {
        b.iter(|| AirTable::new(black_box(&site)).unwrap())
    });
    g.finish();
}

criterion_group!(benches, kernels);
criterion_main!(benches);
