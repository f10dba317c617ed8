//! The paper's brute force (section 5, "we use a brute force approach to compute the node time"):
//! enumerate every assignment of drones to pads and keep the smallest makespan. No bounds, no
//! symmetry rules; it is the baseline the exact branch and bound is measured against.

use super::{
    elapsed_ms, one_per_pad, validate, validate_limits, Limits, NodeTimeMethod, NodeTimeSolution,
};
use crate::error::{Error, Result};
use crate::solver::SolveStatus;
use std::time::Instant;

/// Largest number of assignments `min(k, n)^n` brute force accepts (`10^8`, about a second in a
/// release build).
pub const BRUTE_MAX_ASSIGNMENTS: u128 = 100_000_000;

struct Enumeration<'a> {
    times: &'a [f64],
    loads: Vec<f64>,
    pad_of: Vec<usize>,
    best: f64,
    best_pad_of: Vec<usize>,
    leaves: u64,
    start: Instant,
    time_limit_s: Option<f64>,
    stopped: bool,
}

impl Enumeration<'_> {
    fn visit(&mut self, j: usize) {
        if self.stopped {
            return;
        }
        if j == self.times.len() {
            self.leaves += 1;
            let makespan = self.loads.iter().copied().fold(0.0, f64::max);
            if makespan < self.best {
                self.best = makespan;
                self.best_pad_of.copy_from_slice(&self.pad_of);
            }
            if self.leaves.is_multiple_of(65_536) {
                if let Some(t) = self.time_limit_s {
                    if self.start.elapsed().as_secs_f64() >= t {
                        self.stopped = true;
                    }
                }
            }
            return;
        }
        let p = self.times[j];
        for i in 0..self.loads.len() {
            let previous = self.loads[i];
            self.loads[i] = previous + p;
            self.pad_of[j] = i;
            self.visit(j + 1);
            self.loads[i] = previous;
        }
    }
}

/// Node time by brute force over all `min(k, n)^n` assignments (pads beyond the number of drones
/// are never needed).
///
/// # Arguments
/// * `pads` - number of pads `k`.
/// * `charge_times_min` - charge time `p_j` of each drone, minutes.
/// * `limits` - a time limit stops the enumeration with its best assignment so far (`Feasible`).
///
/// # Returns
/// The best assignment found; `Optimal` when the enumeration completed, otherwise `Feasible`
/// with the root lower bound `max(p_max, sum/k, p_k + p_{k+1}, ...)`.
///
/// # Errors
/// Those of [`validate`]; `E5005` when `min(k, n)^n` exceeds [`BRUTE_MAX_ASSIGNMENTS`];
/// `E5006` for a bad time limit.
///
/// # Complexity
/// `O(k^n * k)` time, `O(n + k)` memory.
///
/// # Example
/// ```
/// use swarmplan::node_time::{brute, Limits};
/// let s = brute(3, &[60.0, 50.0, 40.0, 30.0, 20.0], &Limits::default()).unwrap();
/// assert_eq!(s.makespan_min, 70.0);
/// ```
pub fn brute(pads: usize, charge_times_min: &[f64], limits: &Limits) -> Result<NodeTimeSolution> {
    validate(pads, charge_times_min)?;
    validate_limits(limits)?;
    let start = Instant::now();
    let n = charge_times_min.len();
    let m = pads.min(n);
    if m == n {
        let makespan = charge_times_min.iter().copied().fold(0.0, f64::max);
        return Ok(finish(makespan, one_per_pad(n), true, start));
    }
    if m == 1 {
        let makespan: f64 = charge_times_min.iter().sum();
        return Ok(finish(makespan, vec![(0..n).collect()], true, start));
    }
    let count = (m as u128)
        .checked_pow(n as u32)
        .filter(|&c| c <= BRUTE_MAX_ASSIGNMENTS);
    if count.is_none() {
        return Err(Error::invalid(
            "E5005",
            "charge_times_min",
            format!(
                "brute force would enumerate {m}^{n} assignments, more than its limit of {BRUTE_MAX_ASSIGNMENTS}"
            ),
            "use --method exact (proven optimal and fast), or fewer drones/pads",
        ));
    }
    let mut e = Enumeration {
        times: charge_times_min,
        loads: vec![0.0; m],
        pad_of: vec![0; n],
        best: f64::INFINITY,
        best_pad_of: vec![0; n],
        leaves: 0,
        start,
        time_limit_s: limits.time_limit_s,
        stopped: false,
    };
    e.visit(0);
    let assignment = super::lists_from_pad_of(&e.best_pad_of, m);
    // The makespan is recomputed from the raw times so it matches every other method's sums.
    let makespan = super::makespan_of(charge_times_min, &assignment);
    let mut solution = finish(makespan, assignment, !e.stopped, start);
    if e.stopped {
        let (_, sorted) = super::sort_desc(charge_times_min);
        let lb = super::lower_bound_sorted(m, &sorted, super::all_integral(charge_times_min));
        solution.lower_bound_min = lb.min(makespan);
    }
    Ok(solution)
}

fn finish(
    makespan: f64,
    assignment: Vec<Vec<usize>>,
    complete: bool,
    start: Instant,
) -> NodeTimeSolution {
    NodeTimeSolution {
        method: NodeTimeMethod::Brute,
        makespan_min: makespan,
        // An incomplete enumeration gets the root bound from the caller.
        lower_bound_min: if complete { makespan } else { 0.0 },
        status: if complete {
            SolveStatus::Optimal
        } else {
            SolveStatus::Feasible
        },
        assignment,
        solve_ms: elapsed_ms(start),
    }
}
