//! Longest processing time first (Graham 1969): sort drones by decreasing charge time, put each on
//! the pad that frees up first. Makespan at most `(4/3 - 1/(3k))` times the optimum.

use crate::error::Result;
use crate::node_time::{
    elapsed_ms, le_tol, lists_from_pad_of, lower_bound_sorted, one_per_pad, sort_desc, validate,
    NodeTimeMethod, NodeTimeSolution,
};
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
    let integral = crate::node_time::all_integral(charge_times_min);
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
