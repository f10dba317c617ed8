//! Search for an assignment with every load within a target (whole minutes) by repacking a few
//! pads at a time: one pad above the target and up to `REPACK_PADS - 1` pads within it are emptied, and
//! their drones are packed again into as many pads of capacity `target` by bin completion
//! (`completion.rs`) under a small node budget. See `models/node_time.md`, "Perfect-partition
//! search".
//!
//! Where the pairwise re-partitioning of `heuristics/perfect.rs` stalls (four drones per pad and
//! a total slack `k C - sum` of a few minutes: a pair of pads has 256 splits, and the two loads
//! must land in windows a few minutes wide), a group of pads has many more ways to share its
//! slack.

use super::completion::BinCompletion;
use crate::node_time::search::{Budget, Decision, Memo};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Pads emptied and packed again by one move.
const REPACK_PADS: usize = 6;

/// Bin-completion nodes of one move.
const REPACK_NODES: u64 = 2_000;

/// Looks for an assignment of the drones `p` (whole minutes, sorted decreasingly, positive) on
/// `m` pads with every load `<= target`, starting from `pad_of`; `seed` varies the choice of
/// pads between calls. Stops when it reaches the target or when the `work` budget (nodes of
/// `budget`, also bounded by the caller's limits) runs out. A move only ever replaces a pad above
/// the target by pads within it, so the largest load never grows. Returns the largest load when
/// some move succeeded (`pad_of` updated), `None` otherwise.
///
/// Complexity: at most `work / REPACK_NODES` moves (more when moves are refused without a
/// search), each a bin completion of about `REPACK_PADS n / m` drones.
pub(crate) fn repack(
    m: usize,
    p: &[f64],
    target: f64,
    pad_of: &mut [usize],
    work: u64,
    seed: u64,
    budget: &mut Budget,
) -> Option<f64> {
    let q = REPACK_PADS.min(m);
    if q < 2 {
        return None;
    }
    let mut loads = vec![0.0_f64; m];
    for (j, &i) in pad_of.iter().enumerate() {
        loads[i] += p[j];
    }
    let mut rng = ChaCha8Rng::seed_from_u64(0x7e9a_c000 ^ seed);
    let stop_at = budget.nodes.saturating_add(work);
    let mut moved = false;
    let mut group: Vec<usize> = Vec::with_capacity(q);
    let mut items: Vec<usize> = Vec::new();
    let mut sub_p: Vec<f64> = Vec::new();
    loop {
        if budget.nodes >= stop_at || budget.spent() {
            break;
        }
        let over: Vec<usize> = (0..m).filter(|&i| loads[i] > target).collect();
        if over.is_empty() {
            break;
        }
        // One pad above the target, and q - 1 below it, each the roomier of two drawn at random.
        let mut under: Vec<usize> = (0..m).filter(|&i| loads[i] <= target).collect();
        let size = q.min(under.len() + 1);
        if size < 2 {
            break;
        }
        under.shuffle(&mut rng);
        group.clear();
        group.push(over[rng.random_range(0..over.len())]);
        for _ in 1..size {
            let a = rng.random_range(0..under.len());
            let b = rng.random_range(0..under.len());
            let pick = if loads[under[b]] < loads[under[a]] {
                b
            } else {
                a
            };
            group.push(under.swap_remove(pick));
        }
        budget.nodes += 1;
        let total: f64 = group.iter().map(|&i| loads[i]).sum();
        if total > size as f64 * target {
            continue;
        }
        // The group's drones, decreasing (`p` is sorted, so by index).
        items.clear();
        items.extend((0..p.len()).filter(|&j| group.contains(&pad_of[j])));
        sub_p.clear();
        sub_p.extend(items.iter().map(|&j| p[j]));
        let mut search = BinCompletion::new(&sub_p, size, target, true, Memo::default());
        let decision = budget.within(REPACK_NODES, |sub| search.decide(sub));
        if decision == Decision::Fits {
            for &i in &group {
                loads[i] = 0.0;
            }
            for (a, &j) in items.iter().enumerate() {
                let i = group[search.pad_of[a]];
                pad_of[j] = i;
                loads[i] += p[j];
            }
            moved = true;
        }
    }
    moved.then(|| loads.iter().copied().fold(0.0, f64::max))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::node_time::heuristics::cases::{loads_of, poor_start};
    use crate::node_time::Limits;

    /// With three pads one move repacks them all: the perfect split is found, every drone
    /// placed once.
    #[test]
    fn repacks_a_poor_start_into_a_perfect_split() {
        let (p, mut pad_of) = poor_start();
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        let found = repack(3, &p, 30.0, &mut pad_of, 100_000, 1, &mut budget);
        assert_eq!(found, Some(30.0));
        assert_eq!(loads_of(&p, &pad_of), [30.0; 3]);
    }

    /// Below `sum/k` (29) no move can succeed: bin completion refutes every group, the budget
    /// runs out, and the assignment is left as it was.
    #[test]
    fn an_unreachable_target_leaves_the_assignment_alone() {
        let (p, mut pad_of) = poor_start();
        let start = pad_of.clone();
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        assert_eq!(
            repack(3, &p, 29.0, &mut pad_of, 50_000, 1, &mut budget),
            None
        );
        assert_eq!(pad_of, start);
        assert!(budget.nodes >= 50_000);
    }

    /// 24 drones on 6 pads, dealt round robin: a move takes one pad above the target and pads
    /// within it, so the largest load drops, and the loads stay a partition of the drones.
    #[test]
    fn the_largest_load_never_grows() {
        let p: Vec<f64> = {
            let mut v: Vec<f64> = (0..24).map(|j| f64::from(5 + (j * 7) % 21)).collect();
            v.sort_by(|a, b| b.total_cmp(a));
            v
        };
        let total: f64 = p.iter().sum();
        let mut pad_of: Vec<usize> = (0..24).map(|j| j % 6).collect();
        let start_max = {
            let mut l = [0.0; 6];
            for (j, &i) in pad_of.iter().enumerate() {
                l[i] += p[j];
            }
            l.iter().copied().fold(0.0, f64::max)
        };
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        let target = (total / 6.0).ceil();
        let found = repack(6, &p, target, &mut pad_of, 200_000, 3, &mut budget).expect("a move");
        assert!(found < start_max, "{found} against {start_max}");
        let mut l = [0.0; 6];
        for (j, &i) in pad_of.iter().enumerate() {
            l[i] += p[j];
        }
        assert_eq!(l.iter().sum::<f64>(), total);
        assert_eq!(l.iter().copied().fold(0.0, f64::max), found);
    }
}
