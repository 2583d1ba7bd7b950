//! Which of a sweep's flights share their beginning, and up to when: the campaign's side of
//! [`hpr_sim::batch::Prefix`]. Points are grouped from the plan and the base flight alone;
//! each variant's place (what it takes, what it leaves, the time it may share until) is
//! drawn from its replicate's own random numbers, so it too depends only on (seed, id).

use super::super::params::Param;
use super::super::scenario::InputSpec;
use super::super::variants::{Plan, Variant};
use hpr_sim::batch::{Prefix, Share};
use hpr_sim::inputs::Part;
use hpr_sim::{Simulation, Trigger};
use std::sync::Arc;

/// Sweep points that differ only in the inputs of shifts started at fixed times after
/// launch, flown with common random numbers: replicate `r` of each such point is the same
/// flight until the earliest of those shifts' starts among the points, so the first point's
/// flight flies that stretch once and leaves it for the others ([`hpr_sim::batch::Prefix`]).
/// The points group by their other swept inputs (a sweep of fin spans and ballast travels
/// shares within each span); within a group, the points whose moves start later than the
/// group's earliest (the same swept start times) share on to their own start: the first of
/// them takes the group's beginning and leaves the longer one for the rest.
#[derive(Debug, Clone)]
pub(super) struct Sharing {
    /// Each swept shift's start: a fixed time, or the plan's input that gives it.
    starts: Vec<ShiftStart>,
    /// Every point's centers ([`Plan::centers`]).
    centers: Vec<Vec<f64>>,
    /// Every point's group: the points that differ from it only in the swept shifts'
    /// inputs, in order (the first is the group's owner).
    groups: Vec<Arc<Vec<usize>>>,
    /// Every point's subgroup: the points of its group whose swept shifts start when its
    /// own do (the same swept start times), in order.
    subgroups: Vec<Arc<Vec<usize>>>,
}

#[derive(Debug, Clone, Copy)]
enum ShiftStart {
    At(f64),
    Input(usize),
}

/// Shared beginnings are kept for at most this many at once (about 4.7 KB each: a full
/// store adds about 38 MiB to a run's peak memory, measured); flights whose owner found
/// the store full fly from the pad.
pub(super) const SHARED_BEGINNINGS: usize = 8192;

/// The points of `keys` with the same key as each point, in order, one list shared by them.
fn classes<K: PartialEq>(keys: &[K]) -> Vec<Arc<Vec<usize>>> {
    let mut classes: Vec<Arc<Vec<usize>>> = Vec::with_capacity(keys.len());
    for q in 0..keys.len() {
        match (0..q).find(|&o| keys[o] == keys[q]) {
            Some(o) => classes.push(classes[o].clone()),
            None => classes.push(Arc::new(
                (q..keys.len()).filter(|&m| keys[m] == keys[q]).collect(),
            )),
        }
    }
    classes
}

impl Sharing {
    /// The sharing of `plan`'s points flying `base` (the first point's flight), if some
    /// share: common random numbers, and two points or more differing only in swept inputs
    /// of shifts each started at a fixed time after launch.
    pub(super) fn of(plan: &Plan, inputs: &[InputSpec], base: &Simulation) -> Option<Sharing> {
        if !plan.common_random_numbers {
            return None;
        }
        let model = base.model();
        let timed = |k: usize| {
            model.shifts.get(k).and_then(|s| match s.trigger {
                Trigger::Time { time_s } => Some(time_s),
                _ => None,
            })
        };
        // The swept inputs that act only from a timed shift's start, and their shifts.
        let late: Vec<bool> = plan
            .inputs
            .iter()
            .zip(inputs)
            .map(|(p, i)| {
                p.sweep.is_some()
                    && matches!(i.param.part(), Some((Part::Shift, k)) if timed(k).is_some())
            })
            .collect();
        let mut shifts: Vec<usize> = Vec::new();
        for (_, input) in inputs.iter().enumerate().filter(|&(j, _)| late[j]) {
            if let Some((_, k)) = input.param.part() {
                if !shifts.contains(&k) {
                    shifts.push(k);
                }
            }
        }
        let starts = shifts
            .iter()
            .map(|&k| {
                match inputs
                    .iter()
                    .position(|i| i.param == Param::ShiftTrigger(k))
                {
                    Some(j) => ShiftStart::Input(j),
                    None => ShiftStart::At(timed(k).unwrap_or(f64::INFINITY)),
                }
            })
            .collect();
        // Points group by the sweep indices of their other inputs, and within a group by
        // those of their swept start times.
        let points = plan.points();
        let indices: Vec<Vec<Option<usize>>> = (0..points).map(|q| plan.point_indices(q)).collect();
        let group_keys: Vec<Vec<Option<usize>>> = indices
            .iter()
            .map(|idx| {
                idx.iter()
                    .zip(&late)
                    .map(|(i, l)| if *l { None } else { *i })
                    .collect()
            })
            .collect();
        let sub_keys: Vec<Vec<Option<usize>>> = indices
            .iter()
            .map(|idx| {
                idx.iter()
                    .zip(&late)
                    .zip(inputs)
                    .map(|((i, l), input)| {
                        let start = matches!(input.param, Param::ShiftTrigger(_));
                        if *l && !start {
                            None
                        } else {
                            *i
                        }
                    })
                    .collect()
            })
            .collect();
        let groups = classes(&group_keys);
        if groups.iter().all(|g| g.len() < 2) {
            return None;
        }
        Some(Sharing {
            starts,
            centers: (0..points).map(|q| plan.centers(q)).collect(),
            groups,
            subgroups: classes(&sub_keys),
        })
    }

    /// What variant `v` shares (`None`: nothing): the beginning it takes from its group's
    /// first point, to the earliest start of a swept shift in the group, or from its
    /// subgroup's first point, to their own start when that is later; and the beginning it
    /// leaves if it is the first of either.
    pub(super) fn prefix(&self, plan: &Plan, v: &Variant) -> Option<Prefix> {
        let group = &self.groups[v.point];
        if group.len() < 2 {
            return None;
        }
        let r = v.replicate;
        // Each point's earliest start of a swept shift in this replicate, drawn once.
        let starts: Vec<f64> = group
            .iter()
            .map(|&q| {
                self.starts
                    .iter()
                    .map(|s| match *s {
                        ShiftStart::At(t) => t,
                        ShiftStart::Input(j) => plan.common_value(&self.centers[q], r, j),
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        let start = |q: usize| match group.iter().position(|&m| m == q) {
            Some(i) => starts[i],
            None => f64::INFINITY,
        };
        let owner = group[0];
        let until_s = starts.iter().copied().fold(f64::INFINITY, f64::min);
        // A subgroup that starts later than the group shares on to its start.
        let later = |q: usize| {
            let sub = &self.subgroups[q];
            let first_start = start(sub[0]);
            (sub.len() >= 2 && !sub.contains(&owner) && first_start > until_s)
                .then(|| (sub.clone(), first_start))
        };
        let id = |q: usize| q as u64 * plan.variants_per_point + r;
        let second: usize = group
            .iter()
            .filter(|&&q| self.subgroups[q][0] == q)
            .filter_map(|&q| later(q).map(|(sub, _)| sub.len() - 1))
            .sum();
        let first = Share {
            key: id(owner),
            until_s,
            borrowers: (group.len() - 1 - second) as u32,
        };
        let q = v.point;
        if q == owner {
            return Some(Prefix {
                take: None,
                keep: Some(first),
            });
        }
        Some(match later(q) {
            Some((sub, sub_start)) => {
                let share = Share {
                    key: id(sub[0]),
                    until_s: sub_start,
                    borrowers: (sub.len() - 1) as u32,
                };
                if q == sub[0] {
                    Prefix {
                        take: Some(first),
                        keep: Some(share),
                    }
                } else {
                    Prefix {
                        take: Some(share),
                        keep: None,
                    }
                }
            }
            None => Prefix {
                take: Some(first),
                keep: None,
            },
        })
    }
}
