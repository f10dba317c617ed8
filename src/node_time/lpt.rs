//! Longest processing time first (Graham 1969): sort drones by decreasing charge time, put each on
//! the pad that frees up first. Makespan at most `(4/3 - 1/(3k))` times the optimum. Also the
//! largest differencing heuristic, a starting point of the exact search with many drones per pad.

use super::{
    elapsed_ms, le_tol, lists_from_pad_of, lower_bound_sorted, one_per_pad, sort_desc, validate,
    NodeTimeMethod, NodeTimeSolution,
};
use crate::error::Result;
use crate::solver::SolveStatus;
use std::time::Instant;

/// LPT schedule on the first `m` pads for times sorted in decreasing order.
///
/// Returns the pad of each sorted job and the makespan. Ties go to the lowest pad index.
pub(crate) fn lpt_sorted(m: usize, sorted_desc: &[f64], pad_of_sorted: &mut [usize]) -> f64 {
    let mut loads = vec![0.0_f64; m];
    for (pos, &p) in sorted_desc.iter().enumerate() {
        let mut best = 0;
        for i in 1..m {
            if loads[i] < loads[best] {
                best = i;
            }
        }
        loads[best] += p;
        pad_of_sorted[pos] = best;
    }
    loads.iter().copied().fold(0.0, f64::max)
}

/// Node time by LPT (longest processing time first).
///
/// # Arguments
/// * `pads` - number of pads `k`.
/// * `charge_times_min` - charge time `p_j` of each drone, minutes.
///
/// # Returns
/// The LPT schedule. `status` is `Optimal` only when its makespan meets the root lower bound
/// `max(p_max, sum/k, p_k + p_{k+1}, ...)` (see `models/node_time.md`), `Feasible` otherwise;
/// `lower_bound_min` is that bound.
///
/// # Errors
/// Those of [`validate`].
///
/// # Complexity
/// `O(n log n + n k)`.
///
/// # Example
/// ```
/// use swarmplan::node_time::lpt;
/// // LPT: 60 | 50 | 40, then 30 on the 40 pad, 20 on the 50 pad: loads 60, 70, 70.
/// assert_eq!(lpt(3, &[60.0, 50.0, 40.0, 30.0, 20.0]).unwrap().makespan_min, 70.0);
/// ```
pub fn lpt(pads: usize, charge_times_min: &[f64]) -> Result<NodeTimeSolution> {
    validate(pads, charge_times_min)?;
    let start = Instant::now();
    let n = charge_times_min.len();
    let (order, sorted) = sort_desc(charge_times_min);
    let integral = super::all_integral(charge_times_min);
    let lb = lower_bound_sorted(pads, &sorted, integral);
    let m = pads.min(n);
    let (makespan, assignment) = if pads >= n {
        (sorted[0], one_per_pad(n))
    } else {
        let mut pad_sorted = vec![0; n];
        let makespan = lpt_sorted(m, &sorted, &mut pad_sorted);
        let mut pad_of = vec![0; n];
        for (pos, &j) in order.iter().enumerate() {
            pad_of[j] = pad_sorted[pos];
        }
        (makespan, lists_from_pad_of(&pad_of, m))
    };
    let proven = le_tol(makespan, lb);
    Ok(NodeTimeSolution {
        method: NodeTimeMethod::Lpt,
        makespan_min: makespan,
        lower_bound_min: if proven { makespan } else { lb },
        status: if proven {
            SolveStatus::Optimal
        } else {
            SolveStatus::Feasible
        },
        assignment,
        solve_ms: elapsed_ms(start),
    })
}

/// Largest differencing (Karmarkar & Karp 1982, "The differencing method of set partitioning",
/// for `m` pads as in Korf, "Multi-way number partitioning", IJCAI 2009) on the drones
/// `sorted_desc` (decreasing): every drone starts as a partial assignment with its time on one
/// pad; the two partial assignments with the largest spread (largest minus smallest load) are
/// merged, the heaviest pad of one with the lightest of the other, until one is left. Writes the
/// pad of each drone into `pad_of_sorted` and returns the makespan.
///
/// With many drones per pad it balances far better than LPT, which leaves the last, shortest
/// drones to even out the loads. Complexity `O(n^2 + n m log m)` (merging the drone lists).
pub(crate) fn ldm_sorted(m: usize, sorted_desc: &[f64], pad_of_sorted: &mut [usize]) -> f64 {
    // A partial assignment: pads as (load, drones), heaviest first.
    type Partial = Vec<(f64, Vec<usize>)>;
    let spread = |a: &Partial| a[0].0 - a[a.len() - 1].0;
    let mut parts: Vec<Partial> = sorted_desc
        .iter()
        .enumerate()
        .map(|(j, &v)| {
            let mut pads = vec![(0.0, Vec::new()); m];
            pads[0] = (v, vec![j]);
            pads
        })
        .collect();
    while parts.len() > 1 {
        // The two largest spreads (ties: the earlier, so the result is reproducible).
        let (mut first, mut second) = (0, 1);
        if spread(&parts[1]) > spread(&parts[0]) {
            (first, second) = (1, 0);
        }
        for q in 2..parts.len() {
            let s = spread(&parts[q]);
            if s > spread(&parts[first]) {
                second = first;
                first = q;
            } else if s > spread(&parts[second]) {
                second = q;
            }
        }
        let (hi, lo) = (first.max(second), first.min(second));
        let b = parts.swap_remove(hi);
        let a = parts.swap_remove(lo);
        // Heaviest of one with lightest of the other.
        let mut merged: Partial = a
            .into_iter()
            .zip(b.into_iter().rev())
            .map(|((la, mut da), (lb, db))| {
                da.extend(db);
                (la + lb, da)
            })
            .collect();
        merged.sort_by(|x, y| y.0.total_cmp(&x.0));
        parts.push(merged);
    }
    for (i, (_, drones)) in parts[0].iter().enumerate() {
        for &j in drones {
            pad_of_sorted[j] = i;
        }
    }
    // Recompute the loads from the assignment.
    let mut loads = vec![0.0_f64; m];
    for (j, &i) in pad_of_sorted.iter().enumerate() {
        loads[i] += sorted_desc[j];
    }
    loads.iter().copied().fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Karmarkar and Karp's example, worked by hand. Two pads: 8 and 7 leave 1; 6 and 5 leave 1;
    /// 4 and 1 leave 3; 3 and 1 leave 2, so the loads are (30 + 2) / 2 = 16 and 14 (the optimum
    /// is 15, {8, 7} and {6, 5, 4}). LPT gives 17: 8 | 7, then 6, 5 and 4 on the lighter pad:
    /// 13 | 13, then 17. Three pads: (8,0,0) and (7,0,0) give (8,7,0); with (6,0,0), heaviest
    /// against lightest, (8,7,6); (5,0,0) and (4,0,0) give (5,4,0); with (8,7,6) reversed,
    /// (11,11,8): makespan 11, the optimum ({8}, {7, 4}, {6, 5}).
    #[test]
    fn largest_differencing_matches_the_hand_computed_example() {
        let p = [8.0, 7.0, 6.0, 5.0, 4.0];
        for (m, expected, loads) in [
            (2, 16.0, vec![16.0, 14.0]),
            (3, 11.0, vec![11.0, 11.0, 8.0]),
        ] {
            let mut pad_of = vec![usize::MAX; p.len()];
            assert_eq!(ldm_sorted(m, &p, &mut pad_of), expected);
            let mut got = vec![0.0; m];
            for (j, &i) in pad_of.iter().enumerate() {
                got[i] += p[j];
            }
            got.sort_by(|a, b| b.total_cmp(a));
            assert_eq!(got, loads);
        }
        let mut pad_of = vec![0; p.len()];
        assert_eq!(lpt_sorted(2, &p, &mut pad_of), 17.0);
    }
}
