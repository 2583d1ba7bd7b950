//! The steppers on four lanes against four alone, and the step-size controller's floor.

use super::*;

#[test]
fn four_steppers_whose_stages_are_computed_side_by_side_step_exactly_as_four_alone() {
    use crate::lanes::{F64x4, Real};
    // The batch engine's way: each stepper begins and judges its own steps, the stage
    // arithmetic of all four runs on F64x4 lanes (`arithmetic`), the derivative lane by lane.
    // It must give the bits of four steppers stepping alone, rejections and stops included.
    let starts = [[1.0, 0.0], [0.3, -2.0], [-5.0, 0.7], [0.0, 1e-3]];
    let tols = [(1e-6, 1e-9), (1e-9, 1e-12), (1e-4, 1e-6), (1e-11, 1e-14)];
    let make = |k: usize| {
        let mut s: Dopri54<2> =
            Dopri54::with_tolerances(Tolerances::uniform(tols[k].0, tols[k].1).unwrap());
        s.init(oscillator, 0.0, &starts[k]).unwrap();
        s
    };
    let mut alone: [Dopri54<2>; 4] = std::array::from_fn(make);
    let mut lanes: [Dopri54<2>; 4] = std::array::from_fn(make);
    // Stops that cut some steps short, at different times for each lane: the next multiple
    // of the lane's period after t.
    let stop = |k: usize, t: f64| {
        let period = 0.37 + 0.11 * k as f64;
        let n = (t / period).floor() + 1.0;
        if n * period > t {
            n * period
        } else {
            (n + 1.0) * period
        }
    };
    let z = F64x4::splat(0.0);
    for _ in 0..200 {
        for (k, s) in alone.iter_mut().enumerate() {
            let t_stop = stop(k, s.t());
            s.step(oscillator, t_stop).unwrap();
        }
        let (mut h, mut y, mut k1) = (z, [z; 2], [z; 2]);
        let (mut atol, mut rtol) = ([z; 2], z);
        for (l, s) in lanes.iter_mut().enumerate() {
            let t_stop = stop(l, s.t());
            s.begin_step_outside(&mut oscillator, t_stop).unwrap();
            h.0[l] = s.attempt_step();
            rtol.0[l] = s.tolerances().rtol();
            for i in 0..2 {
                y[i].0[l] = s.y()[i];
                k1[i].0[l] = s.dy()[i];
                atol[i].0[l] = s.tolerances().atol()[i];
            }
        }
        let mut k = [[z; 2]; 6];
        let mut ys = [z; 2];
        let mut active = [true; 4];
        let mut stage = 0;
        while active.iter().any(|&a| a) {
            dopri54::arithmetic::stage_state(stage, h, &y, &k1, &k, &mut ys);
            for (l, s) in lanes.iter().enumerate() {
                let mut d = [0.0; 2];
                oscillator(s.stage_time(stage), &[ys[0].0[l], ys[1].0[l]], &mut d);
                k[stage][0].0[l] = d[0];
                k[stage][1].0[l] = d[1];
            }
            if stage < 5 {
                stage += 1;
                continue;
            }
            let sums = dopri54::arithmetic::error_sum(h, &y, &ys, &k1, &k, &atol, rtol);
            let mut cont = [[z; 2]; 4];
            dopri54::arithmetic::dense_coefficients(h, &y, &ys, &k1, &k, &mut cont);
            for l in 0..4 {
                if !active[l] {
                    continue;
                }
                let s = &mut lanes[l];
                match s.judge((sums.lane(l) / 2.0).sqrt(), 6).unwrap() {
                    Some(_) => {
                        active[l] = false;
                        let lane = |v: &[F64x4; 2]| [v[0].0[l], v[1].0[l]];
                        let c = [0, 1, 2, 3].map(|j| lane(&cont[j]));
                        s.commit(&lane(&ys), &lane(&k[5]), &c);
                    }
                    None => h.0[l] = s.attempt_step(),
                }
            }
            stage = 0;
        }
        for l in 0..4 {
            let (a, b) = (&alone[l], &lanes[l]);
            assert_eq!(a.t().to_bits(), b.t().to_bits(), "lane {l}: t");
            assert_eq!(
                a.h_next().to_bits(),
                b.h_next().to_bits(),
                "lane {l}: next step"
            );
            for i in 0..2 {
                assert_eq!(a.y()[i].to_bits(), b.y()[i].to_bits(), "lane {l}: y[{i}]");
                let tm = 0.5 * (a.t_prev() + a.t());
                assert_eq!(
                    a.dense(tm)[i].to_bits(),
                    b.dense(tm)[i].to_bits(),
                    "lane {l}: dense"
                );
            }
            assert_eq!(a.n_rejected(), b.n_rejected(), "lane {l}: rejections");
            assert_eq!(a.n_eval(), b.n_eval(), "lane {l}: evaluations");
        }
    }
    let rejected: u64 = alone.iter().map(|s| s.n_rejected()).sum();
    println!("4 × 200 steps equal bit for bit, {rejected} rejections among them");
    assert!(
        rejected > 0,
        "the comparison should include rejected attempts"
    );
}

#[test]
fn the_controller_s_error_floor_is_the_logarithm_of_1e_4() {
    // The PI controller keeps ln(max(err_prev, 1e-4)); its floor must be that of 1e-4.
    assert_eq!(dopri54::LN_ERR_FLOOR, 1e-4f64.ln());
}
