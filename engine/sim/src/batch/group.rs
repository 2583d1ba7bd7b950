//! Groups of four lanes stepped together: every Dormand–Prince stage of the four lanes' free
//! flights is one call of the 6-DOF kernel on [`F64x4`] lanes, and the lanes' stepper
//! arithmetic is compiled with it for AVX2 where the processor has it. Each lane keeps its
//! own time, step, stops and error control; the kernel does lane by lane the IEEE operations
//! of the single flight, so the lanes are bit for bit single flights.

use super::guarded;
use crate::eom::{pack_mass, MassLanes, N6};
use crate::flight::driver::{Paused, StepEnd};
use crate::flight::model::{derivative_6dof_lanes, FlightModel, FourModels};
use crate::flight::{SimError, Simulation};
use crate::integrate::dopri54::arithmetic;
use crate::integrate::{DenseStepper, StepOutcome};
use crate::lanes::{F64x4, Real};

/// Most lanes of one chunk in flight at once (four groups of four).
pub const LANES_IN_FLIGHT: usize = 16;

/// One lane: a row of the chunk in its free flight.
pub(super) struct Lane<'a> {
    pub(super) row: usize,
    pub(super) sim: &'a Simulation,
    pub(super) paused: Option<Box<Paused<'a, ()>>>,
    /// Set when the lane's free flight is over.
    pub(super) end: Option<LaneEnd>,
}

pub(super) enum LaneEnd {
    Phase(StepEnd),
    Error(SimError),
    Panic(String),
}

/// One free-flight step of every lane of `group` (at most four): the lanes' steppers held
/// side by side as structure of arrays, each Dormand–Prince stage one stage combination and
/// one 6-DOF kernel call for the four lanes; each lane's step then ends as a single flight's
/// does. Lanes whose integrator steps whole (RK4) take their step alone.
pub(super) fn step_group(group: &mut [Lane<'_>], steps: &mut Steps) {
    if let Err(message) = guarded(|| step_lanes_dispatch(group, steps)) {
        for lane in group.iter_mut() {
            lane.end = Some(LaneEnd::Panic(message.clone()));
        }
    }
}

/// Four lanes' Dormand–Prince steps in progress, as structure of arrays: lane `l` of every
/// number is slot `l`'s. The arithmetic is [`arithmetic`]'s, the single flight's. Kept by
/// the chunk from step to step (every field is written before it is read within a step).
pub(super) struct Steps {
    h: F64x4,
    atol: [F64x4; N6],
    rtol: F64x4,
    y: [F64x4; N6],
    k1: [F64x4; N6],
    /// Stages k2..k7.
    k: [[F64x4; N6]; 6],
    /// The state of the stage being evaluated.
    ys: [F64x4; N6],
    /// Dense-output coefficients of the steps just accepted.
    cont: [[F64x4; N6]; 4],
}

impl Steps {
    pub(super) fn new() -> Box<Steps> {
        let zero = F64x4::splat(0.0);
        Box::new(Steps {
            h: zero,
            atol: [zero; N6],
            rtol: zero,
            y: [zero; N6],
            k1: [zero; N6],
            k: [[zero; N6]; 6],
            ys: [zero; N6],
            cont: [[zero; N6]; 4],
        })
    }
}

/// Lane `l` of a structure-of-arrays state.
#[inline(always)]
fn lane_of(v: &[F64x4; N6], l: usize) -> [f64; N6] {
    std::array::from_fn(|k| v[k].0[l])
}

/// Which lanes of `dy` are all finite (a lane with an infinity or a NaN gives NaN times 0).
#[inline(always)]
fn finite_lanes(dy: &[F64x4; N6]) -> [bool; 4] {
    let zero = F64x4::splat(0.0);
    let mut s = zero;
    for v in dy {
        s = s + *v * zero;
    }
    s.eq(zero)
}

/// The body of [`step_group`].
#[inline(always)]
fn step_lanes(group: &mut [Lane<'_>], st: &mut Steps) {
    let n = group.len();
    // Which lanes step on lanes (and which are still in their step), and their outcomes.
    let mut active = [false; 4];
    let mut outcomes: [Option<StepOutcome>; 4] = [None; 4];
    let zero = F64x4::splat(0.0);
    for (l, lane) in group.iter_mut().enumerate() {
        let Some(p) = lane.paused.as_mut() else {
            continue;
        };
        match p.begin_step() {
            Ok(true) => {
                active[l] = true;
                let d = p.dopri();
                st.h.0[l] = d.attempt_step();
                let tol = d.tolerances();
                st.rtol.0[l] = tol.rtol();
                for k in 0..N6 {
                    st.y[k].0[l] = d.y()[k];
                    st.k1[k].0[l] = d.dy()[k];
                    st.atol[k].0[l] = tol.atol()[k];
                }
            }
            Ok(false) => match p.step() {
                Ok(Some(end)) => lane.end = Some(LaneEnd::Phase(end)),
                Ok(None) => {}
                Err(e) => lane.end = Some(LaneEnd::Error(e)),
            },
            Err(e) => lane.end = Some(LaneEnd::Error(e)),
        }
    }
    if let Some(first) = (0..n).find(|&l| active[l]) {
        // A slot without a lane in step repeats the first one's start (its results are
        // ignored); a lane done with its step idles in its slot.
        let slots: [usize; 4] = std::array::from_fn(|l| if l < n && active[l] { l } else { first });
        for (l, &i) in slots.iter().enumerate() {
            if l != i {
                st.h.0[l] = st.h.0[i];
                st.rtol.0[l] = st.rtol.0[i];
                for k in 0..N6 {
                    st.atol[k].0[l] = st.atol[k].0[i];
                    st.y[k].0[l] = st.y[k].0[i];
                    st.k1[k].0[l] = st.k1[k].0[i];
                }
            }
        }
        let models: [&FlightModel; 4] = slots.map(|i| {
            group[i]
                .paused
                .as_deref()
                .expect("a lane in step flies")
                .model()
        });
        let four = FourModels::new(models);
        let mut ms = pack_mass([&MassLanes::ZERO; 4]);
        let mut thrust = zero;
        // Serial of the mass state each slot holds (refreshed only when it changes).
        let mut serial = [u64::MAX; 4];
        let mut t_stage = [0.0; 4];
        let mut stage = 0;
        loop {
            arithmetic::stage_state(stage, st.h, &st.y, &st.k1, &st.k, &mut st.ys);
            for (l, &i) in slots.iter().enumerate() {
                let own = l == i;
                if (own && !active[l]) || (!own && serial[l] != u64::MAX) {
                    continue;
                }
                let p = group[i].paused.as_mut().expect("a lane in step flies");
                let t = p.dopri().stage_time(stage);
                t_stage[l] = t;
                let (m, th, sn) = p.mass_at(t);
                if sn != serial[l] {
                    ms.set_lane(l, m);
                    serial[l] = sn;
                }
                thrust.0[l] = th;
            }
            let dy4 = &mut st.k[stage];
            match &four {
                Some(four) => eval_four(four, &ms, thrust, &st.ys, dy4),
                None => {
                    // Lanes that do not share their aerodynamic and air tables: one at a time.
                    for l in 0..n {
                        if !active[l] {
                            continue;
                        }
                        let p = group[l].paused.as_mut().expect("a lane in step flies");
                        let (m, th, _) = p.mass_at(t_stage[l]);
                        let mut d = [0.0; N6];
                        derivative_6dof_lanes(models[l], m, th, &lane_of(&st.ys, l), &mut d);
                        for k in 0..N6 {
                            dy4[k].0[l] = d[k];
                        }
                    }
                }
            }
            let finite = finite_lanes(dy4);
            for l in 0..n {
                if active[l] && !finite[l] {
                    let p = group[l].paused.as_mut().expect("a lane in step flies");
                    p.observe(t_stage[l], &lane_of(&st.ys, l), &lane_of(dy4, l));
                }
            }
            if stage < 5 {
                stage += 1;
                continue;
            }
            // The attempts are complete: each lane's error norm decides.
            let sums = arithmetic::error_sum(st.h, &st.y, &st.ys, &st.k1, &st.k, &st.atol, st.rtol);
            let mut cont_done = false;
            for l in 0..n {
                if !active[l] {
                    continue;
                }
                let lane = &mut group[l];
                let p = lane.paused.as_mut().expect("a lane in step flies");
                let err = (sums.0[l] / N6 as f64).sqrt();
                match p.judge(err) {
                    Ok(Some(outcome)) => {
                        active[l] = false;
                        if !cont_done {
                            arithmetic::dense_coefficients(
                                st.h, &st.y, &st.ys, &st.k1, &st.k, &mut st.cont,
                            );
                            cont_done = true;
                        }
                        let c_l = [0, 1, 2, 3].map(|j| lane_of(&st.cont[j], l));
                        match p.commit(&lane_of(&st.ys, l), &lane_of(&st.k[5], l), &c_l) {
                            Ok(()) => outcomes[l] = Some(outcome),
                            Err(e) => lane.end = Some(LaneEnd::Error(e)),
                        }
                    }
                    Ok(None) => st.h.0[l] = p.dopri().attempt_step(),
                    Err(e) => {
                        active[l] = false;
                        lane.end = Some(LaneEnd::Error(e));
                    }
                }
            }
            if !active.iter().any(|&a| a) {
                break;
            }
            stage = 0;
        }
    }
    for (l, lane) in group.iter_mut().enumerate() {
        if let (Some(o), Some(p)) = (outcomes[l], lane.paused.as_mut()) {
            match p.end_step(o) {
                Ok(Some(end)) => lane.end = Some(LaneEnd::Phase(end)),
                Ok(None) => {}
                Err(e) => lane.end = Some(LaneEnd::Error(e)),
            }
        }
    }
}

/// [`step_lanes`] compiled for AVX2 where the processor has it: the lanes' stepper arithmetic
/// (13-state loops) and the kernel then run four doubles to a register. The same IEEE
/// operations either way (no FMA), so the same bits.
fn step_lanes_dispatch(group: &mut [Lane<'_>], steps: &mut Steps) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            unsafe { step_lanes_avx2(group, steps) };
            return;
        }
    }
    step_lanes(group, steps);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn step_lanes_avx2(group: &mut [Lane<'_>], steps: &mut Steps) {
    step_lanes(group, steps);
}

/// The 6-DOF kernel on four lanes, in AVX2 registers where the processor has them (the same
/// IEEE operations lane by lane either way: AVX2 without FMA changes no result).
#[inline]
pub fn eval_four(
    four: &FourModels<'_>,
    ms: &MassLanes<F64x4>,
    thrust: F64x4,
    y: &[F64x4; N6],
    dy: &mut [F64x4; N6],
) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            unsafe { eval_four_avx2(four, ms, thrust, y, dy) };
            return;
        }
    }
    derivative_6dof_lanes(four, ms, thrust, y, dy);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn eval_four_avx2(
    four: &FourModels<'_>,
    ms: &MassLanes<F64x4>,
    thrust: F64x4,
    y: &[F64x4; N6],
    dy: &mut [F64x4; N6],
) {
    derivative_6dof_lanes(four, ms, thrust, y, dy);
}
