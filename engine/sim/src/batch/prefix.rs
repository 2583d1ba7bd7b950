//! Flights that are the same flight for a while, flown that while once. The points of a
//! sweep over a moving mass's travel or start time, each flown with the same random draws
//! (common random numbers), are one flight until the first of their moves starts: every
//! step before it is the same step, bit for bit. One of them (the *owner*) flies that
//! stretch and leaves a copy of its paused free flight here just before its first step that
//! could tell them apart; the others (the *borrowers*) take the copy as their own and fly on
//! from there. A borrower's flight is the flight it would have flown from the pad, bit for
//! bit, because
//!
//! - the owner leaves its copy only when no attempt of any step so far was allowed to reach
//!   the first time at which the flights may differ (its stepper's
//!   [`reach`](crate::integrate::Dopri54::reach)), and before its next step would;
//! - a borrower takes it only if its inputs are the owner's bit for bit but for its shifts',
//!   and each shift whose inputs differ starts at a fixed time no earlier than that first
//!   time, in both flights (before its start a shift's inputs change nothing the flight
//!   computes: its part sits where it was); the owner's fixed stops of those shifts are
//!   then exchanged for the borrower's ([`Paused::move_stops`]), and every memo is left
//!   behind to be recomputed from the borrower's own model.
//!
//! A flight that finds no copy (its owner was refused, not yet there, or the store full)
//! flies from the pad: sharing changes when a result is computed, never what it is.

use super::Columns;
use crate::flight::driver::{Paused, PausedPhase};
use crate::flight::model::FlightModel;
use crate::inputs::{Input, Part};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// What a row shares with rows of other chunks: the beginning it takes from another row's
/// flight, and the one it leaves for others (a row may do both: it takes a beginning shared
/// by many and flies on to leave a longer one for fewer).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Prefix {
    pub take: Option<Share>,
    pub keep: Option<Share>,
}

/// A beginning that rows share.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Share {
    /// The rows sharing a beginning share this key (its owner's variant number).
    pub key: u64,
    /// The first time at which their flights may differ, s: the earliest start of a shift
    /// whose inputs differ among them (the same for every row of the key).
    pub until_s: f64,
    /// How many rows will take the owner's beginning (its copy is dropped after them).
    pub borrowers: u32,
}

/// The shared beginnings of a run's flights, by key, for the chunks of one batch on any
/// thread. Holds at most `capacity` of them (about 4.7 KB each: the paused flight, 2.1 KB,
/// its stepper, 1.8 KB, and the owner's inputs); an owner finding it full leaves nothing
/// and its borrowers fly from the pad.
pub struct PrefixStore<'m> {
    /// The model each kept flight points to while it waits (never flown from).
    placeholder: &'m FlightModel,
    capacity: usize,
    entries: Mutex<HashMap<u64, Entry<'m>>>,
    borrowed: AtomicU64,
}

/// One owner's paused flight and what a borrower checks against.
struct Entry<'m> {
    until_s: f64,
    /// The owner's inputs (the bits of its row of the columns) and noise seed.
    inputs: Vec<(Input, u64)>,
    seed: Option<u64>,
    /// The fixed start time of each of the owner's shifts (`None`: started by an event).
    starts_s: Vec<Option<f64>>,
    paused: Box<Paused<'m, ()>>,
    left: u32,
}

impl<'m> PrefixStore<'m> {
    /// An empty store for flights of models like `placeholder`'s, keeping at most
    /// `capacity` beginnings at once.
    pub fn new(placeholder: &'m FlightModel, capacity: usize) -> PrefixStore<'m> {
        PrefixStore {
            placeholder,
            capacity,
            entries: Mutex::new(HashMap::new()),
            borrowed: AtomicU64::new(0),
        }
    }

    /// How many flights so far took a beginning from the store.
    pub fn borrowed(&self) -> u64 {
        self.borrowed.load(Ordering::Relaxed)
    }

    /// How many beginnings the store holds now.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// Whether the store holds none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<u64, Entry<'m>>> {
        self.entries.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Keep the owner's flight `paused` (row `row` of `columns`) for the borrowers of
    /// `share`, unless the store is full or holds that key already.
    pub(super) fn keep(
        &self,
        share: &Share,
        paused: &Paused<'_, ()>,
        columns: &Columns,
        row: usize,
    ) {
        // No attempt so far may have reached the first time the flights may differ.
        if share.borrowers == 0 || !(paused.reach() < share.until_s) {
            return;
        }
        let model = paused.model();
        let mut entries = self.lock();
        if entries.len() >= self.capacity || entries.contains_key(&share.key) {
            return;
        }
        let observer: &'m mut () = Box::leak(Box::new(()));
        entries.insert(
            share.key,
            Entry {
                until_s: share.until_s,
                inputs: row_bits(columns, row),
                seed: columns.sensor_seed.get(row).copied(),
                starts_s: fixed_starts(model),
                paused: Box::new(paused.clone_onto(self.placeholder, observer)),
                left: share.borrowers,
            },
        );
    }

    /// The shared beginning `share` as the flight of `model` (row `row` of `columns`),
    /// if the store holds it and this flight may take it (see the module's text); `None`
    /// otherwise (the flight then flies from the pad).
    pub(super) fn take<'a>(
        &self,
        share: &Share,
        model: &'a FlightModel,
        columns: &Columns,
        row: usize,
    ) -> Option<Box<Paused<'a, ()>>> {
        let mut entries = self.lock();
        let entry = entries.get_mut(&share.key)?;
        if entry.until_s.to_bits() != share.until_s.to_bits() {
            return None;
        }
        entry.left = entry.left.saturating_sub(1);
        let taken = Self::fits(entry, model, columns, row).map(|(from, to)| {
            let observer: &'a mut () = Box::leak(Box::new(()));
            let mut paused = entry.paused.clone_onto(model, observer);
            paused.move_stops(&from, &to);
            Box::new(paused)
        });
        if entry.left == 0 {
            entries.remove(&share.key);
        }
        if taken.is_some() {
            self.borrowed.fetch_add(1, Ordering::Relaxed);
        }
        taken
    }

    /// A borrower of `share` that will not take its beginning (its inputs were refused):
    /// the owner's flight is kept for one borrower fewer.
    pub(super) fn pass(&self, share: &Share) {
        let mut entries = self.lock();
        let Some(entry) = entries.get_mut(&share.key) else {
            return;
        };
        if entry.until_s.to_bits() == share.until_s.to_bits() {
            entry.left = entry.left.saturating_sub(1);
            if entry.left == 0 {
                entries.remove(&share.key);
            }
        }
    }

    /// Whether the flight of `model` (row `row` of `columns`) may take `entry`'s beginning:
    /// if so, the owner's stop times of the shifts that differ and the borrower's.
    fn fits(
        entry: &Entry<'_>,
        model: &FlightModel,
        columns: &Columns,
        row: usize,
    ) -> Option<(Vec<f64>, Vec<f64>)> {
        let until = entry.until_s;
        // The copy was left before any attempt could reach `until`.
        if !(entry.paused.time_s() < until) {
            return None;
        }
        if columns.sensor_seed.get(row).copied() != entry.seed
            || columns.inputs.len() != entry.inputs.len()
            || model.shifts.len() != entry.starts_s.len()
        {
            return None;
        }
        let mut differs = vec![false; model.shifts.len()];
        for ((input, values), &(owner_input, owner_bits)) in
            columns.inputs.iter().zip(&entry.inputs)
        {
            let bits = values.get(row)?.to_bits();
            if *input != owner_input {
                return None;
            }
            if bits != owner_bits {
                match input.part() {
                    Some((Part::Shift, k)) if k < differs.len() => differs[k] = true,
                    _ => return None,
                }
            }
        }
        let own = fixed_starts(model);
        let (mut from, mut to) = (Vec::new(), Vec::new());
        for k in (0..differs.len()).filter(|&k| differs[k]) {
            match (entry.starts_s[k], own[k]) {
                (Some(a), Some(b)) if a >= until && b >= until => {
                    from.push(a);
                    to.push(b);
                }
                _ => return None,
            }
        }
        Some((from, to))
    }
}

/// The bits of row `row` of every column.
fn row_bits(columns: &Columns, row: usize) -> Vec<(Input, u64)> {
    columns
        .inputs
        .iter()
        .map(|(input, c)| (*input, c.get(row).map_or(u64::MAX, |v| v.to_bits())))
        .collect()
}

/// Each shift's fixed start time in `model` (`None`: started by an event).
fn fixed_starts(model: &FlightModel) -> Vec<Option<f64>> {
    model
        .shifts
        .iter()
        .map(|s| s.trigger.fixed_time(model.burnout_s, model.motor_delay_s))
        .collect()
}
