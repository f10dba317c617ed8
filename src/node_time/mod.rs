//! Node time at a recharging node: the pad-to-drone assignment, identical parallel machines
//! P||Cmax. See `models/node_time.md`.
//! User guide: the command `node-time` (`docs/src/commands/node-time.md`) and "Node time"
//! (`docs/src/models/node_time.md`).
//!
//! Every drone `j` of the swarm (delivery and support) needs charging time `p_j` (minutes) to reach
//! a full battery; a node has `k` identical pads, each charging one drone at a time. The node time
//! `nt` is the makespan
//!
//! ```text
//! nt = min over assignments a: J -> {1..k} of  max_i  sum_{j : a(j) = i} p_j
//! ```
//!
//! Four methods:
//! - [`exact()`] (`exact/`): combinatorial branch and bound (`exact/assignment.rs`), LPT as
//!   first upper bound, then bin completion (`exact/completion.rs`) or, for real-valued times
//!   with many drones per pad, sequential partitioning (`exact/partition.rs`); proven optimal
//!   unless a limit stops it ([`exact_with`] picks the second search);
//! - [`milp()`] (`milp.rs`): the assignment MILP with symmetry breaking on every enabled
//!   [`MilpBackend`];
//! - [`lpt()`] (`heuristics/lpt.rs`): Graham's longest-processing-time list schedule, a
//!   `4/3 - 1/(3k)` approximation;
//! - [`brute()`] (`brute.rs`): the paper's brute force over every assignment, refused
//!   above [`brute::BRUTE_MAX_ASSIGNMENTS`] assignments.
//!
//! The files by role:
//! - `mod.rs`: the shared types ([`Limits`], [`NodeTimeSolution`], [`REL_TOL`]), validation and
//!   the public entry points;
//! - `bounds/`: lower bounds: the root bound, the cardinality bound, the Martello–Toth `L2`, the
//!   two-class count bound and their lift by bisection (`mod.rs`), the bin-packing LP bound
//!   (`lp.rs`);
//! - `heuristics/`: LPT (`lpt.rs`), largest differencing (`ldm.rs`), the move/swap local search
//!   (`local_search.rs`), the perfect-partition search (`perfect.rs`);
//! - `search/`: what the exact searches share: the node and time budget with its one limit check
//!   (`budget.rs`), the memo of failed states (`memo.rs`), the outcome of a decision query;
//! - `exact/`: the phase policy and its tuning constants (`mod.rs`), the assignment branch and
//!   bound (`assignment.rs`), bin completion (`completion.rs`), sequential partitioning
//!   (`partition.rs`), the repacking of pad groups by bin completion (`repack.rs`);
//! - `milp.rs`, `brute.rs`: the cross-check solvers, independent of the exact search.
//!
//! Floating-point tolerance: charge times are `f64` minutes. Two makespans are equal when they
//! differ by at most [`REL_TOL`] times the larger; "proven optimal" means no assignment has a makespan
//! below the returned one by more than that. When every time is a whole number of minutes the
//! search is exact (integer makespans, rounded-up bounds).
//!
//! Example, the paper's worked example (section 5): charge times 60, 50, 40, 30, 20 minutes give
//! 200 minutes on one pad, 70 on three pads and 60 on five.
//!
//! ```
//! use swarmplan::node_time::{exact, Limits};
//! let times = [60.0, 50.0, 40.0, 30.0, 20.0];
//! assert_eq!(exact(1, &times, &Limits::default()).unwrap().makespan_min, 200.0);
//! assert_eq!(exact(3, &times, &Limits::default()).unwrap().makespan_min, 70.0);
//! assert_eq!(exact(5, &times, &Limits::default()).unwrap().makespan_min, 60.0);
//! ```

use crate::error::{show, Error, Result, Violation};
use crate::solver::{MilpBackend, SolveStatus};
use serde::{Deserialize, Serialize};

mod bounds;
mod brute;
mod exact;
mod heuristics;
mod milp;
mod search;

pub(crate) use bounds::lower_bound_sorted;
pub use brute::{brute, BRUTE_MAX_ASSIGNMENTS};
pub use exact::{exact, exact_with, ExactSearch};
pub use heuristics::lpt;
pub use milp::{milp, model_text, solve_with, write_model};

/// Relative tolerance under which two makespans count as equal (`1e-9`).
pub const REL_TOL: f64 = 1e-9;

/// Node limit of the exact node time at every recharging stop the planner makes
/// ([`crate::compose::Planner`], `solve` and `batch`, `--node-limit`): search nodes counted over
/// every phase of [`exact()`], so a stopped search gives the same node time on any machine and
/// thread count. A stop it stops keeps the incumbent (LPT or better), status `Feasible`.
/// Exhausted in 0.24 to 0.36 s on one core, whichever phase runs; the stops of the README's main
/// job (paper-195, `paper` profile) each need under 1,000 nodes (see `models/node_time.md`, "Node
/// limit at a stop").
pub const DEFAULT_STOP_NODE_LIMIT: u64 = 20_000_000;

/// Largest charge time, in minutes, treated as a whole number for the exact integer search
/// (`2^50`, so every sum of up to 1000 such times is exact in `f64`).
const INTEGRAL_MAX_MIN: f64 = 1_125_899_906_842_624.0;

/// Method that computes a node time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum NodeTimeMethod {
    /// Combinatorial branch and bound, proven optimal unless a limit stops it.
    Exact,
    /// Assignment MILP on a [`MilpBackend`].
    Milp,
    /// Longest processing time first (Graham 1969), a heuristic.
    Lpt,
    /// The paper's brute force over every assignment.
    Brute,
}

display_as_value_name!(NodeTimeMethod);

/// Limits of a solve; the default has none.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Limits {
    /// Wall-clock limit in seconds; `None` for no limit.
    pub time_limit_s: Option<f64>,
    /// Limit on the search nodes of [`exact()`], counted over all its phases (placements,
    /// completion queries and their work; `models/node_time.md`, "Limits"); `None` for no limit.
    /// Other methods ignore it.
    pub node_limit: Option<u64>,
}

/// A node time and the pad assignment that achieves it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodeTimeSolution {
    /// Method that produced it.
    pub method: NodeTimeMethod,
    /// Node time `nt` (minutes): the largest pad load of `assignment`.
    pub makespan_min: f64,
    /// A proven lower bound on the optimal node time (minutes); equal to `makespan_min` when
    /// `status` is `Optimal`.
    pub lower_bound_min: f64,
    /// `Optimal` when proven optimal (within [`REL_TOL`]); `Feasible` when a limit stopped the
    /// proof or the method is a heuristic whose result is not proven.
    pub status: SolveStatus,
    /// Drone indices (into the input list, ascending) charged on each pad; one entry per pad,
    /// `min(pads, drones)` entries (further pads would stay empty).
    pub assignment: Vec<Vec<usize>>,
    /// Wall-clock time of the solve in milliseconds.
    pub solve_ms: f64,
}

/// The document `swarmplan node-time --json` prints and `swarmplan check --node-time` reads:
/// the instance solved, the solution and its gap.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodeTimeReport {
    /// Number of pads `k` of the instance.
    pub pads: usize,
    /// Charge time of every drone of the instance, minutes.
    pub charge_times_min: Vec<f64>,
    /// The solution.
    #[serde(flatten)]
    pub solution: NodeTimeSolution,
    /// `(makespan - reference) / reference`: 0 against the optimum when proven, else against
    /// the method's own lower bound; `None` without an assignment.
    pub gap: Option<crate::solver::Gap>,
}

impl NodeTimeSolution {
    /// The node time's gap: 0 against the optimum when proven, else against the method's own
    /// lower bound; `None` without an assignment.
    pub fn gap(&self) -> Option<crate::solver::Gap> {
        use crate::solver::{Gap, ReferenceKind, Sense};
        match self.status {
            SolveStatus::Optimal => Some(Gap::new(
                self.makespan_min,
                self.makespan_min,
                ReferenceKind::Optimal,
                Sense::Minimise,
            )),
            SolveStatus::Feasible => Some(Gap::new(
                self.makespan_min,
                self.lower_bound_min,
                ReferenceKind::Bound,
                Sense::Minimise,
            )),
            SolveStatus::Infeasible => None,
        }
    }
}

impl NodeTimeReport {
    /// The report of `solution` on the instance (`pads`, `charge_times_min`).
    pub fn new(pads: usize, charge_times_min: &[f64], solution: NodeTimeSolution) -> Self {
        NodeTimeReport {
            pads,
            charge_times_min: charge_times_min.to_vec(),
            gap: solution.gap(),
            solution,
        }
    }
}

/// Checks a node-time instance and reports every violation at once.
///
/// # Arguments
/// * `pads` - number of identical pads `k` at the node.
/// * `charge_times_min` - charge time `p_j` of every drone, minutes.
///
/// # Errors
/// [`Error::Invalid`] listing `E5001` (no pads), `E5002` (empty list), `E5003` (negative time),
/// `E5004` (NaN, infinite, or above [`MAX_CHARGE_TIME_MIN`]).
///
/// # Complexity
/// `O(n)`.
pub fn validate(pads: usize, charge_times_min: &[f64]) -> Result<()> {
    let mut violations = Vec::new();
    if pads == 0 {
        violations.push(Violation::new(
            "E5001",
            "pads",
            "the node has 0 pads, so no drone can charge",
            "give at least 1 pad",
        ));
    }
    if charge_times_min.is_empty() {
        violations.push(Violation::new(
            "E5002",
            "charge_times_min",
            "the list of charge times is empty",
            "give one charge time (minutes) per drone that lands at the node",
        ));
    }
    for (j, &p) in charge_times_min.iter().enumerate() {
        if !(p.is_finite() && p <= MAX_CHARGE_TIME_MIN) {
            violations.push(Violation::new(
                "E5004",
                format!("charge_times_min[{j}]"),
                format!(
                    "charge time {} is not a finite number of at most {} min",
                    show(p),
                    show(MAX_CHARGE_TIME_MIN)
                ),
                "give a finite charge time in minutes",
            ));
        } else if p < 0.0 {
            violations.push(Violation::new(
                "E5003",
                format!("charge_times_min[{j}]"),
                format!("charge time {} min is negative", show(p)),
                "give a charge time of 0 minutes or more",
            ));
        }
    }
    if violations.is_empty() {
        Ok(())
    } else {
        Err(Error::Invalid(violations))
    }
}

/// Longest time limit accepted, seconds (about 11.6 days): any solve that needs more is not one a
/// time limit should wait for, and every longer value would overflow a `Duration` somewhere.
pub const MAX_TIME_LIMIT_S: f64 = 1e6;

/// Longest charge time accepted, minutes (about 1,900 years): keeps every sum of charge times
/// finite and exact to well below a minute.
pub const MAX_CHARGE_TIME_MIN: f64 = 1e9;

/// Checks the limits: a time limit must be a number of seconds in `[0, MAX_TIME_LIMIT_S]`
/// (`E5006`).
pub(crate) fn validate_limits(limits: &Limits) -> Result<()> {
    match limits.time_limit_s {
        Some(t) if !(t.is_finite() && (0.0..=MAX_TIME_LIMIT_S).contains(&t)) => {
            Err(Error::invalid(
                "E5006",
                "time_limit_s",
                format!(
                    "time limit {} s is not a number of seconds in [0, {}]",
                    show(t),
                    show(MAX_TIME_LIMIT_S)
                ),
                "give a time limit such as 10",
            ))
        }
        _ => Ok(()),
    }
}

/// Computes the node time with the chosen method.
///
/// # Arguments
/// * `method` - which algorithm.
/// * `backend` - MILP backend, used by [`NodeTimeMethod::Milp`] only.
/// * `pads`, `charge_times_min` - the instance, as in [`validate`].
/// * `limits` - time and node limits.
///
/// # Returns
/// The [`NodeTimeSolution`] of that method.
///
/// # Errors
/// Those of [`validate`]; `E5005` when brute force is asked beyond its size limit;
/// [`Error::Backend`] when a MILP backend fails.
///
/// # Complexity
/// That of the method called.
pub fn solve(
    method: NodeTimeMethod,
    backend: MilpBackend,
    pads: usize,
    charge_times_min: &[f64],
    limits: &Limits,
) -> Result<NodeTimeSolution> {
    match method {
        NodeTimeMethod::Exact => exact(pads, charge_times_min, limits),
        NodeTimeMethod::Milp => milp(pads, charge_times_min, backend, limits),
        NodeTimeMethod::Lpt => lpt(pads, charge_times_min),
        NodeTimeMethod::Brute => brute(pads, charge_times_min, limits),
    }
}

/// Lower bound on the node time from the bin-packing LP (`models/node_time.md`, "LP bound"): the
/// root bound, lifted by bisection to the largest capacity `C` below LPT's makespan at which the
/// LP proves that the drones do not fit on the pads (then `nt >= C + 1` with whole minutes,
/// `nt > C` otherwise).
///
/// # Arguments
/// * `pads`, `charge_times_min` - the instance, as in [`validate`].
/// * `limits` - time and node limits (nodes as in [`exact()`]); a limit returns the bound so far.
///
/// # Returns
/// A proven lower bound (minutes) on the optimal node time, at least the root bound
/// `max(p_1, sum/k, ...)` (rounded up for whole minutes).
///
/// # Errors
/// Those of [`validate`] and `E5006`.
///
/// # Complexity
/// `O(log(UB - LB))` LPs (whole minutes; about 60 for real minutes), each a column generation of
/// at most 200 interior-point solves and exact knapsacks.
///
/// # Example
/// ```
/// use swarmplan::node_time::{lp_lower_bound, Limits};
/// // Three drones of 6 min on 2 pads: the LP needs 3 pads of capacity 11, so nt >= 12.
/// assert_eq!(lp_lower_bound(2, &[6.0, 6.0, 6.0], &Limits::default()).unwrap(), 12.0);
/// ```
pub fn lp_lower_bound(pads: usize, charge_times_min: &[f64], limits: &Limits) -> Result<f64> {
    validate(pads, charge_times_min)?;
    validate_limits(limits)?;
    let (_, sorted) = sort_desc(charge_times_min);
    let integral = all_integral(charge_times_min);
    let lb = lower_bound_sorted(pads, &sorted, integral);
    let positive = sorted.iter().take_while(|&&p| p > 0.0).count();
    if pads >= positive {
        return Ok(lb);
    }
    let p = &sorted[..positive];
    let mut pad_of = vec![0; positive];
    let ub = heuristics::lpt_sorted(pads, p, &mut pad_of);
    let mut budget = search::Budget::new(limits);
    Ok(
        match bounds::lp::LpBound::new(p, integral).lift(pads, lb, ub, &mut budget) {
            Some(c) if integral => lb.max(c + 1.0),
            Some(c) => lb.max(c),
            None => lb,
        },
    )
}

/// Largest pad load of an assignment (minutes), recomputed from the raw times.
///
/// # Complexity
/// `O(n)`.
pub fn makespan_of(charge_times_min: &[f64], assignment: &[Vec<usize>]) -> f64 {
    assignment
        .iter()
        .map(|pad| pad.iter().map(|&j| charge_times_min[j]).sum::<f64>())
        .fold(0.0, f64::max)
}

/// True when every time is a whole number of minutes small enough for exact `f64` sums.
pub(crate) fn all_integral(charge_times_min: &[f64]) -> bool {
    charge_times_min.len() <= 1000
        && charge_times_min
            .iter()
            .all(|&p| p.fract() == 0.0 && p <= INTEGRAL_MAX_MIN)
}

/// Drone indices sorted by decreasing charge time (ties by index), and the sorted times.
pub(crate) fn sort_desc(charge_times_min: &[f64]) -> (Vec<usize>, Vec<f64>) {
    let mut order: Vec<usize> = (0..charge_times_min.len()).collect();
    order.sort_by(|&a, &b| {
        charge_times_min[b]
            .total_cmp(&charge_times_min[a])
            .then(a.cmp(&b))
    });
    let sorted = order.iter().map(|&j| charge_times_min[j]).collect();
    (order, sorted)
}

/// True when `a` is at most `b` within [`REL_TOL`].
pub(crate) fn le_tol(a: f64, b: f64) -> bool {
    a <= b + REL_TOL * a.abs().max(b.abs())
}

/// Milliseconds elapsed since `start`.
pub(crate) fn elapsed_ms(start: std::time::Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1000.0
}

/// Assignment when there are at least as many pads as drones: one drone per pad.
pub(crate) fn one_per_pad(n: usize) -> Vec<Vec<usize>> {
    (0..n).map(|j| vec![j]).collect()
}

/// Builds the per-pad lists from `pad_of[j]` (pad of drone `j`), each sorted ascending.
pub(crate) fn lists_from_pad_of(pad_of: &[usize], pads: usize) -> Vec<Vec<usize>> {
    let mut lists = vec![Vec::new(); pads];
    for (j, &i) in pad_of.iter().enumerate() {
        lists[i].push(j);
    }
    lists
}
