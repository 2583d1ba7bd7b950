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
use crate::integrate::StepOutcome;
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

/// One free-flight step of every lane of `group` (at most four): a stage at a time, the
/// 6-DOF kernel evaluated on the four lanes together; each lane's step then ends as a single
/// flight's does. Lanes whose integrator steps whole (RK4) take their step alone.
pub(super) fn step_group(group: &mut [Lane<'_>]) {
    if let Err(message) = guarded(|| step_lanes_dispatch(group)) {
        for lane in group.iter_mut() {
            lane.end = Some(LaneEnd::Panic(message.clone()));
        }
    }
}

/// The body of [`step_group`].
#[inline(always)]
fn step_lanes(group: &mut [Lane<'_>]) {
    // Which lanes step a stage at a time (and which are done with this step).
    let mut staged = [false; 4];
    let mut outcomes: [Option<StepOutcome>; 4] = [None; 4];
    for (i, lane) in group.iter_mut().enumerate() {
        let Some(p) = lane.paused.as_mut() else {
            continue;
        };
        match p.begin_step() {
            Ok(true) => staged[i] = true,
            Ok(false) => match p.step() {
                Ok(Some(end)) => lane.end = Some(LaneEnd::Phase(end)),
                Ok(None) => {}
                Err(e) => lane.end = Some(LaneEnd::Error(e)),
            },
            Err(e) => lane.end = Some(LaneEnd::Error(e)),
        }
    }
    let n = group.len();
    if let Some(first) = (0..n).find(|&i| staged[i]) {
        // Slot l holds lane l; a slot without a staged lane repeats the first one's input
        // (filled once, its results ignored). A lane done with its step idles in its slot.
        let slots: [usize; 4] = std::array::from_fn(|l| if l < n && staged[l] { l } else { first });
        let models: [&FlightModel; 4] = slots.map(|i| {
            group[i]
                .paused
                .as_deref()
                .expect("a staged lane flies")
                .model()
        });
        let four = FourModels::new(models);
        let mut y = [F64x4::splat(0.0); N6];
        let mut ms = pack_mass([&MassLanes::ZERO; 4]);
        let mut thrust = F64x4::splat(0.0);
        // Serial of the mass state each slot holds (refreshed only when it changes).
        let mut serial = [u64::MAX; 4];
        let mut dy = [0.0; N6];
        let mut dy4 = [F64x4::splat(0.0); N6];
        loop {
            let active: [bool; 4] =
                std::array::from_fn(|l| l < n && staged[l] && outcomes[l].is_none());
            if !active.iter().any(|&a| a) {
                break;
            }
            for (l, &i) in slots.iter().enumerate() {
                let own = l == i;
                if (own && !active[l]) || (!own && serial[l] != u64::MAX) {
                    continue;
                }
                let p = group[i].paused.as_mut().expect("a staged lane flies");
                let (t, yi) = p.stage_input();
                for k in 0..N6 {
                    y[k].0[l] = yi[k];
                }
                let (m, th, sn) = p.mass_at(t);
                if sn != serial[l] {
                    ms.set_lane(l, m);
                    serial[l] = sn;
                }
                thrust.0[l] = th;
            }
            match &four {
                Some(four) => eval_four(four, &ms, thrust, &y, &mut dy4),
                None => {
                    // Lanes that do not share their aerodynamic and air tables: one at a time.
                    for (l, &i) in slots.iter().enumerate() {
                        if l != i || !active[l] {
                            continue;
                        }
                        let p = group[i].paused.as_mut().expect("a staged lane flies");
                        let (t, yi) = p.stage_input();
                        let yi = *yi;
                        let (m, th, _) = p.mass_at(t);
                        let mut d = [0.0; N6];
                        derivative_6dof_lanes(models[l], m, th, &yi, &mut d);
                        for k in 0..N6 {
                            dy4[k].0[l] = d[k];
                        }
                    }
                }
            }
            for l in 0..n {
                if !active[l] {
                    continue;
                }
                for k in 0..N6 {
                    dy[k] = dy4[k].0[l];
                }
                let lane = &mut group[l];
                let p = lane.paused.as_mut().expect("a staged lane flies");
                match p.feed_stage(&dy) {
                    Ok(None) => {}
                    Ok(Some(o)) => outcomes[l] = Some(o),
                    Err(e) => {
                        lane.end = Some(LaneEnd::Error(e));
                        staged[l] = false;
                    }
                }
            }
        }
    }
    for (i, lane) in group.iter_mut().enumerate() {
        if let (Some(o), Some(p)) = (outcomes[i], lane.paused.as_mut()) {
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
fn step_lanes_dispatch(group: &mut [Lane<'_>]) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            unsafe { step_lanes_avx2(group) };
            return;
        }
    }
    step_lanes(group);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn step_lanes_avx2(group: &mut [Lane<'_>]) {
    step_lanes(group);
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
