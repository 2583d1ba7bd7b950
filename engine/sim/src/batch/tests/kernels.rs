//! The four-lane kernels and steppers against the single lane's, bit for bit.

use super::*;

/// The first four flyable variants of the random stream `seed` (their own masses, ballast,
/// motor, wind and site).
fn four_variants(seed: u64) -> Vec<Simulation> {
    let c = columns(8, seed);
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let sims: Vec<Simulation> = (0..8)
        .filter_map(|r| batch.variant(&c, r).ok())
        .take(4)
        .collect();
    assert_eq!(sims.len(), 4);
    sims
}

#[test]
fn the_four_lane_kernel_is_bit_for_bit_four_single_lane_kernels() {
    // Four different variants' models, states and instants, evaluated together and alone.
    let sims = four_variants(7);
    let models: [&FlightModel; 4] = std::array::from_fn(|l| sims[l].model());
    let four = FourModels::new(models).expect("variants share the design's aerodynamic tables");
    let mut rng = Rng(99);
    let mut ms = pack_mass([&MassLanes::ZERO; 4]);
    let mut thrust = F64x4::splat(0.0);
    let mut brake = F64x4::splat(0.0);
    let mut gust = F64x4::splat(1.0);
    let mut y = [F64x4::splat(0.0); N6];
    let mut singles = Vec::new();
    for (l, model) in models.iter().enumerate() {
        // Burning (t < 2 s) or coasting with the ballast on its way (t in 5..6 s).
        let t = [0.7, 1.9, 5.3, 5.8][l];
        let mut starts = [f64::INFINITY; crate::flight::model::MAX_SHIFTS];
        starts[0] = 5.0;
        let inst = model.instant(&starts, t);
        let m = MassLanes::of(&inst.mass);
        let q: [f64; 4] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
        let yi: [f64; N6] = [
            rng.uniform(-50.0, 50.0),
            rng.uniform(-50.0, 50.0),
            rng.uniform(0.0, 1500.0),
            rng.uniform(-30.0, 30.0),
            rng.uniform(-30.0, 30.0),
            rng.uniform(-50.0, 300.0),
            q[0],
            q[1],
            q[2],
            q[3],
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
            rng.uniform(-20.0, 20.0),
        ];
        ms.set_lane(l, &m);
        thrust.0[l] = inst.motor.thrust_n;
        for k in 0..N6 {
            y[k].0[l] = yi[k];
        }
        // Lane 0's air brakes closed, the others open to a drag coefficient of their own.
        brake.0[l] = 0.35 * l as f64;
        gust.0[l] = model.gust(t);
        let mut d = [0.0; N6];
        if l == 0 {
            model.derivative_6dof(&starts, t, &yi, &mut d);
        } else {
            let (thrust_n, cd) = (inst.motor.thrust_n, brake.0[l]);
            model.derivative_6dof_at(&inst.mass, thrust_n, cd, t, &yi, &mut d);
        }
        singles.push(d);
    }
    let mut dy = [F64x4::splat(0.0); N6];
    eval_four(&four, Some(gust), &ms, thrust, brake, &y, &mut dy);
    let mut generic = [F64x4::splat(0.0); N6];
    derivative_6dof_lanes(&four, Some(gust), &ms, thrust, brake, &y, &mut generic);
    for (l, single) in singles.iter().enumerate() {
        for k in 0..N6 {
            assert!(single[k].is_finite());
            assert_eq!(
                dy[k].0[l].to_bits(),
                single[k].to_bits(),
                "lane {l}, state {k}"
            );
            assert_eq!(
                generic[k].0[l].to_bits(),
                single[k].to_bits(),
                "lane {l}, state {k}"
            );
        }
    }
}

#[test]
fn fixed_step_lanes_equal_their_single_flights_too() {
    // RK4 steps whole, so its lanes take their free-flight steps alone, inside the same loop.
    let rk4 = SimOptions {
        keep_samples: false,
        integrator: crate::flight::Integrator::Rk4 { step_s: 0.01 },
        ..SimOptions::default()
    };
    let batch = Batch::new(base().with_options(rk4).unwrap(), Some(reference::BALLAST)).unwrap();
    let n = 10;
    let c = columns(n, 5);
    let mut results = Vec::new();
    batch.run_columns(&c, 8, 2, |r| results.push(r)).unwrap();
    let mut flown = 0;
    for (i, lane) in results.iter().enumerate() {
        let Ok(sim) = batch.variant(&c, i) else {
            assert_eq!(lane.status, Status::Refused);
            continue;
        };
        let f = sim.run(&mut ()).unwrap();
        let bits = |m: &Metrics| -> Vec<Option<u64>> {
            metric_list(m).iter().map(|v| v.map(f64::to_bits)).collect()
        };
        assert_eq!(bits(&lane.metrics), bits(&f.metrics), "variant {i}");
        assert_eq!(lane.derivative_evaluations, f.derivative_evaluations);
        assert_eq!(lane.warnings, f.warnings(), "variant {i}");
        for (k, chute) in lane.parachutes.iter().enumerate() {
            let d = f.deploy(k);
            assert_eq!(chute.deploy_time_s, d.map(|d| d.0), "variant {i}");
            assert_eq!(chute.deploy_speed_m_s, d.map(|d| d.1), "variant {i}");
        }
        flown += 1;
    }
    assert!(flown >= 8, "{flown}");
}

#[test]
fn the_kept_mass_state_is_the_one_instant_gives_wherever_the_mass_is_settled() {
    let sim = base();
    let model = sim.model();
    let mut starts = [f64::INFINITY; crate::flight::model::MAX_SHIFTS];
    // Before its shift: settled from burnout on.
    let burn = model.motor.burn_time_s();
    assert!(!model.mass_settled(&starts, burn - 1e-9));
    let at =
        |s: &crate::flight::model::ShiftStarts, t: f64| MassLanes::of(&model.instant(s, t).mass);
    let still = at(&starts, burn);
    for t in [burn, burn + 0.1, 4.0, 9.0] {
        assert!(model.mass_settled(&starts, t));
        assert_eq!(at(&starts, t), still, "t = {t}");
    }
    // The ballast moves from 5 s for 1 s: not settled while it moves, settled (elsewhere)
    // after.
    starts[0] = 5.0;
    assert!(model.mass_settled(&starts, 5.0));
    for t in [5.0 + 1e-9, 5.5, 6.0 - 1e-9] {
        assert!(!model.mass_settled(&starts, t), "t = {t}");
    }
    let moved = at(&starts, 6.0);
    assert_ne!(moved, still);
    for t in [6.0, 6.5, 20.0] {
        assert!(model.mass_settled(&starts, t));
        assert_eq!(at(&starts, t), moved, "t = {t}");
    }
}

#[test]
fn a_mass_settled_for_good_stays_settled_at_every_later_time_and_the_edge_cases_are_refused() {
    let sim = base();
    let model = sim.model();
    let mut starts = [f64::INFINITY; crate::flight::model::MAX_SHIFTS];
    let burn = model.motor.burn_time_s();
    // The ballast's shift not started: settled for good from burnout on.
    assert!(model.settled_from_now_on(&starts, burn));
    // Started at 5 s, moving for 1 s: at its start the mass is settled (t <= start), but
    // not for good (it moves right after); once the move is over it is.
    starts[0] = 5.0;
    assert!(model.mass_settled(&starts, 5.0));
    assert!(!model.settled_from_now_on(&starts, 5.0));
    assert!(!model.mass_settled(&starts, 5.0 + 1e-9));
    assert!(model.mass_settled(&starts, 6.0) && model.settled_from_now_on(&starts, 6.0));
    // Every later time, down to the next double after the end of the move.
    let mut t = 6.0f64;
    for _ in 0..1000 {
        t = f64::from_bits(t.to_bits() + 1);
        assert!(model.mass_settled(&starts, t), "t = {t}");
    }
    for t in [6.5, 7.0, 20.0, 1e6, f64::INFINITY] {
        assert!(model.mass_settled(&starts, t), "t = {t}");
    }
}

#[test]
fn four_lanes_mass_states_are_bit_for_bit_four_single_instants() {
    // Four variants (their own masses and ballast), each at its own instant: burning with the
    // ballast at rest, burning with it moving, coasting with it moving, and burning just
    // before its shift starts.
    let sims = four_variants(11);
    let models: [&FlightModel; 4] = std::array::from_fn(|l| sims[l].model());
    let times = [0.7, 1.3, 5.4, 0.99];
    let shift_starts = [10.0, 1.0, 5.0, 1.0];
    let mut x = crate::massprops::MassInputs::<F64x4>::zero();
    let mut thrust = [0.0; 4];
    let mut singles = Vec::new();
    for (l, model) in models.iter().enumerate() {
        let mut starts = [f64::INFINITY; crate::flight::model::MAX_SHIFTS];
        starts[0] = shift_starts[l];
        thrust[l] = model
            .mass_inputs_into(&starts, times[l], &mut x, l)
            .thrust_n;
        singles.push(model.instant_computed(&starts, times[l]));
    }
    let m = models.map(|m| &m.mass_lanes);
    let four = crate::massprops::mass_state_lanes(&crate::massprops::MassModelLanes::pack(m), &x);
    for (l, single) in singles.iter().enumerate() {
        assert_eq!(
            thrust[l].to_bits(),
            single.motor.thrust_n.to_bits(),
            "lane {l}"
        );
        assert!(single.motor.thrust_n > 0.0 || l == 2, "lane {l} burns");
        let lane = MassLanes::of(&single.mass);
        let bits = |m: &MassLanes<f64>| {
            let mut v = vec![m.m, m.m_rate, m.m_accel];
            for w in [&m.r, &m.r_rate, &m.r_accel, &m.h, &m.h_rate] {
                v.extend([w.x, w.y, w.z]);
            }
            for a in [&m.i_o, &m.i_o_rate] {
                v.extend(a.m.iter().flatten().copied());
            }
            v.into_iter().map(f64::to_bits).collect::<Vec<_>>()
        };
        let mut mine = MassLanes::<f64>::ZERO;
        mine.m = four.m.0[l];
        mine.m_rate = four.m_rate.0[l];
        mine.m_accel = four.m_accel.0[l];
        for (d, s) in [
            (&mut mine.r, &four.r),
            (&mut mine.r_rate, &four.r_rate),
            (&mut mine.r_accel, &four.r_accel),
            (&mut mine.h, &four.h),
            (&mut mine.h_rate, &four.h_rate),
        ] {
            *d = crate::lanes::V3::new(s.x.0[l], s.y.0[l], s.z.0[l]);
        }
        for (d, s) in [
            (&mut mine.i_o, &four.i_o),
            (&mut mine.i_o_rate, &four.i_o_rate),
        ] {
            for r in 0..3 {
                for k in 0..3 {
                    d.m[r][k] = s.m[r][k].0[l];
                }
            }
        }
        assert_eq!(bits(&mine), bits(&lane), "lane {l}");
    }
    // Lanes 1 and 2 had the ballast on its way, lanes 0 and 3 at rest (3 just before its
    // shift starts), so the four lanes took both ways through the moving parts' terms.
    let rate = x.motions[0].rate_m_s.0;
    assert!(rate[1] != 0.0 && rate[2] != 0.0, "{rate:?}");
    assert!(rate[0] == 0.0 && rate[3] == 0.0, "{rate:?}");
}

#[test]
fn lanes_whose_ballast_moves_while_the_motor_burns_equal_their_single_flights_bit_for_bit() {
    // Shifts that start from 0.2 s to 3 s: lanes burning with the ballast moving, burning with
    // it at rest, and coasting with it moving share groups, whose mass states are computed on
    // four lanes at once.
    let n = 48;
    let early = |rows: std::ops::Range<usize>| {
        let mut c = columns_of(rows.clone(), 17);
        for (k, i) in rows.enumerate() {
            c.column_mut(Input::ShiftTrigger(0))[k] = 0.2 + 2.8 * (i % 8) as f64 / 7.0;
        }
        c
    };
    let c = early(0..n);
    let batch = Batch::new(base(), Some(reference::BALLAST)).unwrap();
    let mut results = Vec::new();
    batch.run(n, 24, 2, early, |r| results.push(r)).unwrap();
    let mut flown = 0;
    for (i, lane) in results.iter().enumerate() {
        let Ok(sim) = single(&c, i) else {
            assert_eq!(lane.status, Status::Refused, "variant {i}");
            continue;
        };
        let f = sim.run(&mut ()).unwrap();
        let bits = |m: &Metrics| -> Vec<Option<u64>> {
            metric_list(m).iter().map(|v| v.map(f64::to_bits)).collect()
        };
        assert_eq!(bits(&lane.metrics), bits(&f.metrics), "variant {i}");
        assert_eq!(
            lane.derivative_evaluations, f.derivative_evaluations,
            "variant {i}"
        );
        assert_eq!(lane.shifts[0].start_s, f.shift_starts_s[0], "variant {i}");
        flown += 1;
    }
    assert!(flown >= 40, "{flown}");
    // Some shifts started while the motor burned.
    let burning = results
        .iter()
        .filter(|l| match (l.shifts[0].start_s, l.metrics.burnout_time_s) {
            (Some(s), Some(b)) => s < b,
            _ => false,
        })
        .count();
    assert!(burning >= 10, "{burning}");
}
