//! Groups of four lanes stepped together. In free flight the four lanes' Dormand–Prince steps
//! are held side by side as structure of arrays ([`Steps`]): every stage is one stage
//! combination and one call of the 6-DOF kernel on [`F64x4`] lanes, compiled for AVX2 where
//! the processor has it. Each lane keeps its own time, step, stops and error control, judged
//! and ended by its own flight ([`OnLanes`]); the kernel does lane by lane the IEEE
//! operations of the single flight, so the lanes are bit for bit single flights. Under canopy
//! (the rocket's descent and released parts') each lane of a descent group takes its own
//! RODAS4 step, the single flight's code itself: a dozen steps a descent, each with its own
//! Jacobian and factored matrix, leave too little to share across lanes to pay for packing.

use super::guarded;
use super::memo::{FreeMemo, Held, SlotModels};
use crate::eom::{pack_mass, MassLanes, N3, N6};
use crate::flight::driver::{Descending, Paused, PausedPhase, PhaseEnd, StepEnd, Verdict};
use crate::flight::model::{
    derivative_6dof_lanes, end_point_lanes, CenterLanes, FlightModel, FourModels,
};
use crate::flight::{SimError, Simulation};
use crate::integrate::dopri54::{self, arithmetic};
use crate::integrate::{DenseStepper, StepOutcome};
use crate::lanes::{ln, F64x4, Real};
use crate::massprops::{mass_state_lanes, MassInputs, MassModelLanes};

/// Most lanes of one chunk in flight at once (four groups of four).
pub const LANES_IN_FLIGHT: usize = 16;

/// One lane: a row of the chunk in its free flight or under canopy.
pub(super) struct Lane<'a> {
    pub(super) row: usize,
    pub(super) sim: &'a Simulation,
    pub(super) flying: Flying<'a>,
    /// Set when the lane's phase is over.
    pub(super) end: Option<LaneEnd>,
    /// Whether the lane's last attempt was rejected: its next group step tries the same step
    /// again, smaller (its stepper holds the attempt), rather than beginning a new one.
    pub(super) retrying: bool,
    /// Whether the lane owns a beginning other lanes share, not yet left for them
    /// ([`super::prefix`]).
    pub(super) owns_prefix: bool,
}

/// The phase a lane is in.
pub(super) enum Flying<'a> {
    Free(Box<Paused<'a, ()>>),
    Descent(Box<Descending<'a, ()>>),
    /// Taken out to be ended.
    Gone,
}

pub(super) enum LaneEnd {
    /// The free flight ended.
    Free(StepEnd),
    /// The descent ended.
    Landed,
    Error(SimError),
    Panic(String),
}

/// A lane's flight in a phase the batch steps four lanes at a time ([`PausedPhase`]), and
/// where a lane holds it.
pub(super) trait OnLanes<'a, const N: usize>: PausedPhase<'a, N> {
    /// This phase's flight of `lane` (which is in this phase).
    fn of<'l>(lane: &'l mut Lane<'a>) -> &'l mut Self;
    fn lane_end(end: Self::End) -> LaneEnd;
}

impl<'a> OnLanes<'a, N6> for Paused<'a, ()> {
    #[inline(always)]
    fn of<'l>(lane: &'l mut Lane<'a>) -> &'l mut Self {
        match &mut lane.flying {
            Flying::Free(p) => p,
            _ => unreachable!("a free-flight group holds free flights"),
        }
    }
    fn lane_end(end: StepEnd) -> LaneEnd {
        LaneEnd::Free(end)
    }
}

impl<'a> OnLanes<'a, N3> for Descending<'a, ()> {
    #[inline(always)]
    fn of<'l>(lane: &'l mut Lane<'a>) -> &'l mut Self {
        match &mut lane.flying {
            Flying::Descent(d) => d,
            _ => unreachable!("a descent group holds descents"),
        }
    }
    fn lane_end(_: PhaseEnd) -> LaneEnd {
        LaneEnd::Landed
    }
}

/// One attempt of every lane of `group` (at most four, all in the same phase), the lanes'
/// stages evaluated together; each lane's accepted step then ends as a single flight's does,
/// and a rejected one is tried again, smaller, at the next. Lanes whose integrator steps
/// whole (RK4) take their step alone.
/// `index` is the group's place among its phase's groups this round (its memo's).
pub(super) fn step_group<'a>(group: &mut [Lane<'a>], scratch: &mut Scratch<'a>, index: usize) {
    let descent = matches!(group.first().map(|l| &l.flying), Some(Flying::Descent(_)));
    let stepped = guarded(|| {
        if descent {
            step_descents(group)
        } else {
            with_avx2(
                #[inline(always)]
                || step_free(group, &mut scratch.free, &mut scratch.free_memo[index]),
            )
        }
    });
    if let Err(message) = stepped {
        for lane in group.iter_mut() {
            lane.end = Some(LaneEnd::Panic(message.clone()));
        }
    }
}

/// Four lanes' Dormand–Prince steps in progress, as structure of arrays: lane `l` of every
/// number is slot `l`'s. The arithmetic is [`arithmetic`]'s, the single flight's. Kept by
/// the chunk from step to step (every field is written before it is read within a step).
pub(super) struct Steps<const N: usize> {
    /// Each attempt's start and end times, s.
    t: F64x4,
    t_end: F64x4,
    h: F64x4,
    /// Each stepper's controller: its β and the logarithm of its last accepted error.
    beta: F64x4,
    ln_err_prev: F64x4,
    atol: [F64x4; N],
    rtol: F64x4,
    y: [F64x4; N],
    k1: [F64x4; N],
    /// Stages k2..k7.
    k: [[F64x4; N]; 6],
    /// The state of the stage being evaluated; after the last stage, each slot's end state
    /// (with its derivative in `k[5]`, FSAL): an accepted step's, read by the step's end.
    ys: [F64x4; N],
    /// Dense-output coefficients of the steps just accepted.
    cont: [[F64x4; N]; 4],
}

impl<const N: usize> Steps<N> {
    fn new() -> Steps<N> {
        let zero = F64x4::splat(0.0);
        Steps {
            t: zero,
            t_end: zero,
            h: zero,
            beta: zero,
            ln_err_prev: zero,
            atol: [zero; N],
            rtol: zero,
            y: [zero; N],
            k1: [zero; N],
            k: [[zero; N]; 6],
            ys: [zero; N],
            cont: [[zero; N]; 4],
        }
    }
}

/// The chunk's scratch for both phases' groups, and what each group's step leaves for the
/// next step of the group at the same place.
pub(super) struct Scratch<'a> {
    free: Steps<N6>,
    free_memo: [Option<FreeMemo<'a>>; LANES_IN_FLIGHT / 4],
}

impl<'a> Scratch<'a> {
    pub(super) fn new() -> Box<Scratch<'a>> {
        Box::new(Scratch {
            free: Steps::new(),
            free_memo: std::array::from_fn(|_| None),
        })
    }
}

/// Lane `l` of a structure-of-arrays state.
#[inline(always)]
fn lane_of<const N: usize>(v: &[F64x4; N], l: usize) -> [f64; N] {
    // A plain loop: `array::from_fn` here was left as a call per element.
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(v) {
        *o = x.0[l];
    }
    out
}

/// Lanes of `dy` that are surely all finite: a lane with an infinity or a NaN has a sum that
/// is not finite (its sum times 0 is NaN). A lane flagged only because its finite values'
/// sum overflowed is looked at again, value by value, by [`PausedPhase::observe`].
#[inline(always)]
fn finite_lanes<const N: usize>(dy: &[F64x4; N]) -> [bool; 4] {
    let zero = F64x4::splat(0.0);
    let mut s = zero;
    for v in dy {
        s = s + *v;
    }
    (s * zero).eq(zero)
}

/// Where a group's four slots stand in a stage: which lane each slot holds (a slot without a
/// lane in step repeats the first one's, its results ignored), which slots are in step, and
/// each slot's stage time.
pub(super) struct Slots {
    pub(super) lane: [usize; 4],
    active: [bool; 4],
    t: [f64; 4],
}

impl Slots {
    /// Whether slot `l` needs its inputs at this stage: a lane in step, or a filler not yet
    /// filled (`filled`).
    #[inline(always)]
    fn wants(&self, l: usize, filled: bool) -> bool {
        if self.lane[l] == l {
            self.active[l]
        } else {
            !filled
        }
    }
}

/// One attempt of each lane of `group` (all in phase `P`) with their attempts held side by
/// side: a new step, or the smaller retry of a step its last attempt had rejected.
/// `eval(group, slots, ys, dy)` evaluates the phase's derivative of the four slots at their
/// stage states `ys` (the slots' times in `slots.t`). Returns how each slot's step ended, if
/// it was accepted (its end state in `st.ys`, its derivative there in `st.k[5]`; the other
/// slots' lanes there are not read); the caller ends those steps
/// ([`end_steps`]).
#[inline(always)]
fn step_on_lanes<'a, const N: usize, P: OnLanes<'a, N>>(
    group: &mut [Lane<'a>],
    st: &mut Steps<N>,
    mut eval: impl FnMut(&mut [Lane<'a>], &Slots, &[F64x4; N], &mut [F64x4; N]),
) -> [Option<StepOutcome>; 4] {
    let n = group.len();
    let mut active = [false; 4];
    let mut outcomes: [Option<StepOutcome>; 4] = [None; 4];
    for (l, lane) in group.iter_mut().enumerate() {
        let retrying = lane.retrying;
        let p = P::of(lane);
        match if retrying { Ok(true) } else { p.begin_step() } {
            Ok(true) => {
                active[l] = true;
                let d = p.dopri();
                st.h.0[l] = d.attempt_step();
                st.t.0[l] = d.t();
                st.t_end.0[l] = d.attempt_end();
                st.beta.0[l] = d.control().beta;
                st.ln_err_prev.0[l] = d.ln_err_prev();
                let tol = d.tolerances();
                st.rtol.0[l] = tol.rtol();
                for k in 0..N {
                    st.y[k].0[l] = d.y()[k];
                    st.k1[k].0[l] = d.dy()[k];
                    st.atol[k].0[l] = tol.atol()[k];
                }
            }
            Ok(false) => match p.step() {
                Ok(Some(end)) => lane.end = Some(P::lane_end(end)),
                Ok(None) => {}
                Err(e) => lane.end = Some(LaneEnd::Error(e)),
            },
            Err(e) => lane.end = Some(LaneEnd::Error(e)),
        }
    }
    let Some(first) = (0..n).find(|&l| active[l]) else {
        return outcomes;
    };
    let mut slots = Slots {
        lane: std::array::from_fn(|l| if l < n && active[l] { l } else { first }),
        active,
        t: [0.0; 4],
    };
    for l in 0..4 {
        let i = slots.lane[l];
        if l != i {
            st.h.0[l] = st.h.0[i];
            st.t.0[l] = st.t.0[i];
            st.t_end.0[l] = st.t_end.0[i];
            st.beta.0[l] = st.beta.0[i];
            st.ln_err_prev.0[l] = st.ln_err_prev.0[i];
            st.rtol.0[l] = st.rtol.0[i];
            for k in 0..N {
                st.atol[k].0[l] = st.atol[k].0[i];
                st.y[k].0[l] = st.y[k].0[i];
                st.k1[k].0[l] = st.k1[k].0[i];
            }
        }
    }
    for stage in 0..6 {
        arithmetic::stage_state(stage, st.h, &st.y, &st.k1, &st.k, &mut st.ys);
        slots.t = dopri54::stage_time(stage, st.t, st.h, st.t_end).0;
        let dy4 = &mut st.k[stage];
        eval(group, &slots, &st.ys, dy4);
        let finite = finite_lanes(dy4);
        if finite != [true; 4] {
            for l in 0..n {
                if slots.active[l] && !finite[l] {
                    P::of(&mut group[l]).observe(slots.t[l], &lane_of(&st.ys, l), &lane_of(dy4, l));
                }
            }
        }
    }
    // The attempts are complete: each lane's error norm decides. A rejected lane tries again
    // at the group's next step, beside the other lanes' next steps (its stepper holds the
    // smaller attempt), so no slot waits on another lane's retry.
    let sums = arithmetic::error_sum(st.h, &st.y, &st.ys, &st.k1, &st.k, &st.atol, st.rtol);
    let errs = (sums / F64x4::splat(N as f64)).sqrt();
    // The controller's logarithm and factors, four attempts at once (each lane then reads
    // the one its verdict needs).
    let ln_errs = ln(errs);
    let growths = dopri54::growth(st.beta, st.ln_err_prev, ln_errs);
    let shrinkages = dopri54::shrinkage(st.beta, ln_errs);
    let mut cont_done = false;
    for l in 0..n {
        if !slots.active[l] {
            continue;
        }
        let lane = &mut group[l];
        let p = P::of(lane);
        let verdict = Verdict {
            err: errs.0[l],
            ln_err: ln_errs.0[l],
            growth: growths.0[l],
            shrinkage: shrinkages.0[l],
        };
        let (retrying, error) = match p.judge(verdict) {
            Ok(Some(outcome)) => {
                if !cont_done {
                    arithmetic::dense_coefficients(
                        st.h,
                        &st.y,
                        &st.ys,
                        &st.k1,
                        &st.k,
                        &mut st.cont,
                    );
                    cont_done = true;
                }
                match p.commit(l, &st.ys, &st.k[5], &st.cont) {
                    Ok(()) => {
                        outcomes[l] = Some(outcome);
                        (false, None)
                    }
                    Err(e) => (false, Some(e)),
                }
            }
            Ok(None) => (true, None),
            Err(e) => (false, Some(e)),
        };
        lane.retrying = retrying;
        if let Some(e) = error {
            lane.end = Some(LaneEnd::Error(e));
        }
    }
    outcomes
}

/// End the steps `step_on_lanes` accepted: `end(phase, outcome, l)` is lane `l`'s
/// [`PausedPhase::end_step`].
#[inline(always)]
fn end_steps<'a, const N: usize, P: OnLanes<'a, N>>(
    group: &mut [Lane<'a>],
    outcomes: &[Option<StepOutcome>; 4],
    mut end: impl FnMut(&mut P, StepOutcome, usize) -> Result<Option<P::End>, SimError>,
) {
    for (l, lane) in group.iter_mut().enumerate() {
        if let Some(o) = outcomes[l] {
            match end(P::of(lane), o, l) {
                Ok(Some(e)) => lane.end = Some(P::lane_end(e)),
                Ok(None) => {}
                Err(e) => lane.end = Some(LaneEnd::Error(e)),
            }
        }
    }
}

/// The four slots' models (a slot repeats its lane's).
#[inline(always)]
pub(super) fn slot_models<'a, const N: usize, P: OnLanes<'a, N>>(
    group: &mut [Lane<'a>],
    slots: &Slots,
) -> [&'a FlightModel; 4] {
    slots.lane.map(|i| P::of(&mut group[i]).model())
}

/// One free-flight attempt of the lanes of `group`: the 6-DOF kernel on four lanes, each slot's
/// mass state refreshed only when it changes (kept from the group's last step in `memo` when
/// its slots hold the same lanes), the changing ones computed on four lanes.
#[inline(always)]
fn step_free<'a>(group: &mut [Lane<'a>], st: &mut Steps<N6>, memo: &mut Option<FreeMemo<'a>>) {
    // Each slot's air brakes, as they stand for the whole step.
    let mut brake = F64x4::splat(0.0);
    // Each slot's gust factor at its stage time (1 without turbulence, then never set).
    let mut gust = F64x4::splat(1.0);
    let gusty = group.iter().any(|l| match &l.flying {
        Flying::Free(p) => p.model().gusts.is_some(),
        _ => false,
    });
    // Whether `memo` is this step's (its slots checked against this step's lanes).
    let mut checked = false;
    let outcomes = step_on_lanes::<N6, Paused<'_, ()>>(
        group,
        st,
        #[inline(always)]
        |group, slots, ys, dy| {
            if !checked {
                let rows = SlotModels::rows(group, slots);
                if !matches!(memo, Some(m) if m.slots.rows == rows) {
                    *memo = Some(FreeMemo {
                        slots: SlotModels::of::<N6, Paused<'_, ()>>(group, slots),
                        ms: pack_mass([&MassLanes::ZERO; 4]),
                        thrust: F64x4::splat(0.0),
                        held: [Held::Nothing; 4],
                        mass_models: None,
                        inputs: None,
                    });
                }
                checked = true;
            }
            let Some(m) = memo.as_mut() else {
                return;
            };
            match &m.slots.four {
                Some(four) => {
                    let mut compute = [false; 4];
                    for l in 0..4 {
                        if !slots.wants(l, m.held[l] != Held::Nothing) {
                            continue;
                        }
                        let t = slots.t[l];
                        let p = Paused::of(&mut group[slots.lane[l]]);
                        brake.0[l] = p.brake_cd();
                        if gusty {
                            gust.0[l] = p.model().gust(t);
                        }
                        if let Some((ms, sn)) = p.settled_mass(t) {
                            if m.held[l] != Held::Settled(sn) {
                                m.ms.set_lane(l, ms);
                                m.held[l] = Held::Settled(sn);
                            }
                            m.thrust.0[l] = 0.0;
                        } else {
                            let key = Held::Computed(t.to_bits(), p.mass_key().1);
                            // The step's last two stages share a time: the second keeps the
                            // first's state (and thrust).
                            if m.held[l] != key {
                                let x = m.inputs.get_or_insert_with(MassInputs::zero);
                                m.thrust.0[l] = p.mass_inputs_into(t, x, l).thrust_n;
                                compute[l] = true;
                                m.held[l] = key;
                            }
                        }
                    }
                    if let (true, Some(x)) = (compute.contains(&true), &m.inputs) {
                        let models = m.mass_models.get_or_insert_with(|| {
                            MassModelLanes::pack(four.models.map(|m| &m.mass_lanes))
                        });
                        if compute == [true; 4] {
                            m.ms = mass_state_lanes(models, x);
                        } else {
                            let fresh = mass_state_lanes(models, x);
                            m.ms = MassLanes::select(compute, &fresh, &m.ms);
                        }
                    }
                    eval_four(four, gusty.then_some(gust), &m.ms, m.thrust, brake, ys, dy)
                }
                None => {
                    // Lanes that do not share their aerodynamic tables: one at a time.
                    for (l, lane) in group.iter_mut().enumerate() {
                        if !slots.active[l] {
                            continue;
                        }
                        let p = Paused::of(lane);
                        let model = p.model();
                        let brake_cd = p.brake_cd();
                        let g = model.gust_at(slots.t[l]);
                        let (ms, th, _) = p.mass_at(slots.t[l]);
                        let mut d = [0.0; N6];
                        derivative_6dof_lanes(model, g, ms, th, brake_cd, &lane_of(ys, l), &mut d);
                        for k in 0..N6 {
                            dy[k].0[l] = d[k];
                        }
                    }
                }
            }
        },
    );
    // The accepted steps' end figures on four lanes where the lanes share their tables: each
    // such slot's mass state is the last stage's, at the step's end.
    let ends = match memo.as_ref() {
        Some(FreeMemo {
            slots: SlotModels {
                four: Some(four), ..
            },
            ms,
            ..
        }) if checked && outcomes.iter().any(Option::is_some) => {
            let c = CenterLanes {
                r: ms.r,
                r_rate: ms.r_rate,
                r_accel: ms.r_accel,
            };
            let mut gust_end = F64x4::splat(1.0);
            let mut any_gust = false;
            for (l, lane) in group.iter_mut().enumerate() {
                if outcomes[l].is_some() {
                    if let Some(g) = Paused::of(lane).end_gust() {
                        gust_end.0[l] = g;
                        any_gust = true;
                    }
                }
            }
            Some((
                end_point_lanes(four, any_gust.then_some(gust_end), &c, &st.ys, &st.k[5]),
                ms.m,
                ms.r.z,
            ))
        }
        _ => None,
    };
    end_steps::<N6, Paused<'_, ()>>(group, &outcomes, |p, o, l| match &ends {
        Some((e, m, r_z)) => p.end_step_with(o, e.lane(l).figures(m.0[l], r_z.0[l])),
        None => p.end_step(o),
    });
}

/// One descent step of each lane of `group`, each lane alone: a descent is stepped by
/// RODAS4, whose steps (few, and each with a Jacobian and a factored matrix of its own
/// lane) are the single flight's own code, so each lane is its single flight bit for bit.
fn step_descents(group: &mut [Lane<'_>]) {
    for lane in group.iter_mut() {
        match Descending::of(lane).step() {
            Ok(Some(end)) => lane.end = Some(Descending::lane_end(end)),
            Ok(None) => {}
            Err(e) => lane.end = Some(LaneEnd::Error(e)),
        }
    }
}

/// `f` (a group's step, inlined into it) compiled for AVX2 where the processor has it: the
/// lanes' stepper arithmetic and the kernels then run four doubles to a register. The same
/// IEEE operations either way (no FMA), so the same bits.
#[inline(always)]
fn with_avx2(f: impl FnOnce()) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            unsafe { avx2(f) };
            return;
        }
    }
    f();
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn avx2(f: impl FnOnce()) {
    f();
}

/// The 6-DOF kernel on four lanes, in AVX2 registers where the processor has them (the same
/// IEEE operations lane by lane either way: AVX2 without FMA changes no result).
#[inline]
pub fn eval_four(
    four: &FourModels<'_>,
    gust: Option<F64x4>,
    ms: &MassLanes<F64x4>,
    thrust: F64x4,
    brake_cd: F64x4,
    y: &[F64x4; N6],
    dy: &mut [F64x4; N6],
) {
    with_avx2(
        #[inline(always)]
        || derivative_6dof_lanes(four, gust, ms, thrust, brake_cd, y, dy),
    );
}
