//! What a group of four lanes keeps from one step to its next while its slots hold the same
//! lanes (the chunk sorts its lanes stably, so most do): the slots' four-lane view of their
//! models, their mass states and thrusts as the slots hold them.

use super::group::{slot_models, Lane, OnLanes, Slots};
use crate::eom::MassLanes;
use crate::flight::model::FourModels;
use crate::lanes::F64x4;
use crate::massprops::{MassInputs, MassModelLanes};

/// The lanes a group's slots hold (the chunk's rows) and, if they share their tables, the
/// four-lane view of their models: kept while the slots hold the same lanes.
pub(super) struct SlotModels<'a> {
    pub(super) rows: [usize; 4],
    pub(super) four: Option<FourModels<'a>>,
}

impl<'a> SlotModels<'a> {
    /// The chunk's rows in the slots of `group` this stage.
    #[inline(always)]
    pub(super) fn rows(group: &[Lane<'a>], slots: &Slots) -> [usize; 4] {
        slots.lane.map(|i| group[i].row)
    }

    /// Those of the lanes the slots hold.
    #[inline(always)]
    pub(super) fn of<const N: usize, P: OnLanes<'a, N>>(
        group: &mut [Lane<'a>],
        slots: &Slots,
    ) -> Self {
        let models = slot_models::<N, P>(group, slots);
        SlotModels {
            rows: Self::rows(group, slots),
            four: FourModels::new(models),
        }
    }
}

/// What a free-flight group step leaves for the next step of the group at the same place
/// when its slots hold the same lanes (`slots`): their models and four-lane view, their
/// mass states and thrusts as the slots hold them, and their packed mass models. Everything
/// here is a function of the rows and of what `held` records, so a group of the same lanes
/// takes it up where it was left (lanes keep their groups from round to round but for the
/// few that change phase, start, land or change whether their mass changes).
pub(super) struct FreeMemo<'a> {
    pub(super) slots: SlotModels<'a>,
    pub(super) ms: MassLanes<F64x4>,
    pub(super) thrust: F64x4,
    pub(super) held: [Held; 4],
    pub(super) mass_models: Option<MassModelLanes<F64x4>>,
    pub(super) inputs: Option<MassInputs<F64x4>>,
}

/// What a slot's lane of the four-lane mass state holds.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Held {
    Nothing,
    /// A settled state, by its serial number ([`Paused::settled_mass`]).
    Settled(u64),
    /// A computed one, for the time (bits) and count of shift-start changes.
    Computed(u64, u64),
}
