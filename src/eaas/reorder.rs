//! Fixed formation re-ordering (the paper's section "Formation Re-ordering").
//!
//! Support drones never move. When a transfer starts and the consumer is farther than `range_m`
//! from the support drone, the consumer swaps slots with the drone occupying the slot nearest the
//! support drone among the slots within `range_m` of it; ties go to the lower slot index. A slot is
//! a candidate only if its occupant is a delivery drone not involved (as consumer or swap partner)
//! in another transfer overlapping this one. Both swapped drones consume at the rate of their new
//! slot for the duration of the transfer, then return to their initial slots. Re-ordering costs no
//! time and no energy (paper).

use super::{HopProblem, Role, Transfer};

/// Distance between slots `a` and `b`, metres.
pub fn slot_distance_m(problem: &HopProblem, a: usize, b: usize) -> f64 {
    (problem.slots_m[a] - problem.slots_m[b]).norm()
}

/// The drone whose initial slot is `q`.
pub fn occupant(problem: &HopProblem, q: usize) -> usize {
    problem
        .initial_slot
        .iter()
        .position(|&x| x == q)
        .unwrap_or(q)
}

/// The drone swapped with the consumer during `t`, if any.
pub fn swap_partner(problem: &HopProblem, t: &Transfer) -> Option<usize> {
    if t.consumer_slot == problem.initial_slot[t.consumer] {
        None
    } else {
        Some(occupant(problem, t.consumer_slot))
    }
}

/// Slot for `consumer` while `support` shares with it.
///
/// # Arguments
/// * `busy[d]` - drone `d` is consumer or swap partner of a transfer overlapping this one.
///
/// # Returns
/// The consumer's own slot when within `range_m` of the support drone; else the nearest slot
/// within range whose occupant may swap (see the module doc); `None` when there is none (the
/// transfer cannot happen now).
///
/// # Complexity
/// `O(S log S)` for `S` slots.
pub fn choose_consumer_slot(
    problem: &HopProblem,
    support: usize,
    consumer: usize,
    busy: &[bool],
) -> Option<usize> {
    if busy[consumer] {
        return None;
    }
    let qs = problem.initial_slot[support];
    let own = problem.initial_slot[consumer];
    if slot_distance_m(problem, qs, own) <= problem.range_m {
        return Some(own);
    }
    let mut candidates: Vec<(f64, usize)> = (0..problem.slots_m.len())
        .filter(|&q| q != qs && q != own)
        .map(|q| (slot_distance_m(problem, qs, q), q))
        .filter(|&(dist, q)| {
            let occ = occupant(problem, q);
            dist <= problem.range_m && problem.drones[occ].role == Role::Delivery && !busy[occ]
        })
        .collect();
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    candidates.first().map(|&(_, q)| q)
}

/// Drones made busy by transfers in `plan` overlapping `[start, end)`: consumers and swap partners.
pub fn busy_drones(problem: &HopProblem, plan: &[Transfer], start: f64, end: f64) -> Vec<bool> {
    let mut busy = vec![false; problem.drones.len()];
    for t in plan {
        if t.start_min < end && start < t.end_min {
            busy[t.consumer] = true;
            if let Some(p) = swap_partner(problem, t) {
                busy[p] = true;
            }
        }
    }
    busy
}

/// Every drone's slot while the transfers `active` run (they must be drone-disjoint).
pub fn slot_assignment(problem: &HopProblem, active: &[Transfer]) -> Vec<usize> {
    let mut slot = problem.initial_slot.clone();
    slot_assignment_into(problem, active, &mut slot);
    slot
}

/// [`slot_assignment`] written into `slot` (as many entries as drones).
pub(crate) fn slot_assignment_into(problem: &HopProblem, active: &[Transfer], slot: &mut [usize]) {
    slot.copy_from_slice(&problem.initial_slot);
    for t in active {
        if let Some(p) = swap_partner(problem, t) {
            slot[p] = problem.initial_slot[t.consumer];
            slot[t.consumer] = t.consumer_slot;
        }
    }
}
