//! Exact node time for P||Cmax in two phases (see `models/node_time.md`, "Exact method").
//!
//! Phase 1, the assignment branch and bound (`assignment.rs`): jobs (drones) are taken in
//! decreasing charge time `p_1 >= ... >= p_n`; a node of the search tree fixes the pads of jobs
//! `1..j`. The search only looks for assignments strictly better than the incumbent `UB`, so
//! every pad load must stay within the capacity
//!
//! ```text
//! cap = UB - 1            when every p_j is a whole number of minutes,
//! cap = UB * (1 - 1e-9)   otherwise (REL_TOL),
//! ```
//!
//! and a node is pruned when the useful slack `sum_i (cap - L_i)` over pads whose slack can still
//! take the shortest job is below the remaining work `sum_{l >= j} p_l`. Symmetry: among pads with
//! equal load (in particular all empty pads) only one is tried. LPT gives the first `UB`; pads are
//! tried by increasing load, so the first dive follows LPT's rule. It stops as soon as `UB` meets
//! the root lower bound or the tree is exhausted (then `UB` is proven optimal), or after
//! `PHASE1_NODES` nodes.
//!
//! Phase 2, one of two searches:
//! - at most 7 pads and 40 drones, with real-valued times and more than 4 drones per pad, or
//!   whole minutes, at least 5 per pad and an optimum expected above `sum/k`: sequential
//!   partitioning (`partition.rs`), the fullest pad's set in increasing load, each set found by
//!   meet in the middle or read from the cache of sets near `sum/k`;
//! - otherwise: local search on the incumbent (`heuristics/local_search.rs`), the Martello–Toth
//!   `L2` and two-class count bounds (`bounds/`), and the decision version "do all jobs fit on
//!   `k` pads of capacity `C`?" by bin completion (`completion.rs`), first at `C = LB` (or, when the optimum is expected above `sum/k`,
//!   a little above it), then just below each new incumbent and at midpoints of the gap between
//!   `LB` and `UB` (whole minutes: of the whole makespans not yet excluded).

mod assignment;
mod completion;
mod cover;
mod dive;
mod partition;
mod repack;

use super::bounds::lp::LpBound;
use super::bounds::{bound_lift, cardinality_bound};
use super::heuristics::lpt_sorted;
use super::heuristics::{aim_at, ldm_sorted, local_search};
use super::search::{Budget, Decision, Memo, SearchOutcome, CAP_SLACK};
use super::{
    all_integral, elapsed_ms, le_tol, lists_from_pad_of, lower_bound_sorted, one_per_pad,
    sort_desc, validate, validate_limits, Limits, NodeTimeMethod, NodeTimeSolution, REL_TOL,
};
use crate::error::Result;
use crate::solver::SolveStatus;
use assignment::run_assignment_search;
use completion::BinCompletion;
use cover::cover_at;
use dive::lp_dive;
use partition::{partition, PARTITION_MAX_DRONES};
use repack::repack;
use std::time::Instant;

/// Nodes of the assignment search before the decision version takes over (phase 1).
const PHASE1_NODES: u64 = 2000;

/// Deepest recursion of the bin-completion search, `n + 2 k` frames (`completion.rs`), kept well
/// within a 2 MiB thread stack; larger instances continue with the assignment search.
const DECISION_MAX_DEPTH: usize = 3000;

/// Real-valued times go to sequential partitioning with more than this many drones per pad.
const PARTITION_REAL_DRONES_PER_PAD: usize = 4;

/// Whole minutes go to sequential partitioning with at least this many drones per pad (and an
/// optimum expected above `sum/k`).
const PARTITION_WHOLE_DRONES_PER_PAD: usize = 5;

/// Real-valued times on more than 2 pads of which at least one in this many repeats an earlier one
/// (identical drones carrying identical packages) go to bin completion, which proves most of them
/// in milliseconds where sequential partitioning lists the same subset sums over and over (on 2
/// pads partitioning stays far faster) (`models/experiments/
/// node_time.md`, "Repeated charge times").
const REPEATED_SHARE_DENOMINATOR: usize = 4;

/// Most pads for which phase 2 is sequential partitioning (with more, bin completion's median
/// and worst case are lower; measured at 4 drones per pad).
const PARTITION_MAX_PADS: usize = 7;

/// The first decision of bin completion is at `LB + FIRST_GUESS_EXCESS d` when the bound is
/// `sum/k` and the optimum is expected above it by `d` (`expected_excess`): just above the
/// optimum, most often, so the incumbents that follow start close to it.
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const FIRST_GUESS_EXCESS: f64 = 2.5;

/// Real-valued times with more than [`PARTITION_MAX_DRONES`] drones and at least this many per
/// pad: phase 2 starts from the better of the incumbent and largest differencing's assignment
/// (whole minutes with many drones per pad are proven at the bound at once; there it would only
/// cost time).
const LDM_DRONES_PER_PAD: usize = 5;

/// Node budget of the real-valued decision trial at the lower bound itself (phase 2).
const FIRST_TRIAL_NODES: u64 = 4000;

/// Sequential partitioning with at most this many drones per pad hands over to bin completion
/// after [`PARTITION_SWITCH_NODES`] nodes (with more per pad bin completion is far slower).
const PARTITION_SWITCH_DRONES_PER_PAD: usize = 6;

/// Nodes (completion queries and placements, and the queries' work: `partition.rs`,
/// `WORK_PER_NODE`) after which sequential partitioning hands over to bin completion, keeping its
/// lower bound.
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const PARTITION_SWITCH_NODES: u64 = 1_000_000;

/// Nodes one bin-completion decision runs before the LP bound (`bounds/lp.rs`) and the
/// perfect-partition search (`heuristics/perfect.rs`) are tried at its capacity (then in slices doubling
/// from this): the decisions of small swarms end long before, so they never pay for either.
const STALL_NODES: u64 = 100_000;

/// Largest knapsack table (`drones x (C + 1)` cells, whole minutes) for which the LP bound is
/// tried after the first slice; a larger one waits for slice [`LP_LATE_SLICE`].
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const LP_EARLY_MAX_CELLS: f64 = (1u64 << 20) as f64;

/// The slice (counted from 0) after which the LP bound is tried on a large knapsack table.
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const LP_LATE_SLICE: u64 = 5;

/// Expected excess of the optimum over `sum/k` (whole minutes, `expected_excess` at a resolution
/// of 1 min) below which a perfect assignment (every load at `ceil(sum/k)` or below) is expected:
/// sequential partitioning is not chosen, and the LP bound on a large knapsack table
/// ([`LP_EARLY_MAX_CELLS`]) is not tried at `ceil(sum/k)`.
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const PERFECT_EXCESS_MAX_MIN: f64 = 0.5;

/// Nodes of an LP dive (`dive.rs`) per node of the slice after which it runs (mostly restricted
/// LP solves, counted 20,000 each, `bounds/lp.rs`). The budget is checked between LP solves, so a
/// dive may pass it by one solve and its pricing.
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const DIVE_SLICE_FACTOR: u64 = 16;

/// Most drones per pad (on average) for which a stalled decision repacks pad groups
/// (`repack.rs`) after the perfect-partition search.
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const REPACK_MAX_DRONES_PER_PAD: usize = 4;

/// Most drones per pad (on average) for which a stalled decision tries the exact front and
/// covered tail (`cover.rs`) after the repacking, with the slice's nodes ([`COVER_SLICE_FACTOR`]
/// times as many where the LP bound is skipped at the volume bound).
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const COVER_MAX_DRONES_PER_PAD: usize = 4;

/// Nodes of the exact front and covered tail per slice, in slices, at a decision where the LP
/// bound is skipped (at the volume bound `ceil(sum/k)` with a perfect assignment expected,
/// [`PERFECT_EXCESS_MAX_MIN`], and a large knapsack table, [`LP_EARLY_MAX_CELLS`]): there the
/// cover is what finds the perfect assignment, and a larger share brings the first cover sooner.
/// Elsewhere one slice.
/// Measured: `models/experiments/node_time.md`, "Tuning constants of the exact method".
const COVER_SLICE_FACTOR: u64 = 8;

/// Largest load of the assignment `pad_of` of the sorted drones `p`.
fn makespan_sorted(m: usize, p: &[f64], pad_of: &[usize]) -> f64 {
    let mut loads = vec![0.0_f64; m];
    for (j, &i) in pad_of.iter().enumerate() {
        loads[i] += p[j];
    }
    loads.iter().copied().fold(0.0, f64::max)
}

/// Whether the incumbent `ub` meets the bound `lb`: exactly for whole minutes, within
/// [`REL_TOL`] otherwise.
fn proven(integral: bool, ub: f64, lb: f64) -> bool {
    if integral {
        ub <= lb
    } else {
        le_tol(ub, lb)
    }
}

/// A search's outcome: whether it proved the incumbent `ub`, and the bound `lb` it reached.
fn outcome(proven: bool, lb: f64, ub: f64) -> SearchOutcome {
    SearchOutcome {
        proven,
        lower_bound_min: lb,
        incumbent_min: ub,
    }
}

/// Phase 2: local search on the incumbent, the `L2` and count bounds, then the decision version
/// from the lower bound up (whole minutes) or by bisection (real minutes); `pad_of` holds the
/// incumbent.
fn phase2(
    m: usize,
    p: &[f64],
    integral: bool,
    mut lb: f64,
    mut ub: f64,
    pad_of: &mut [usize],
    budget: &mut Budget,
) -> SearchOutcome {
    let mut trial = pad_of.to_vec();
    let improved = local_search(m, p, &mut trial);
    if improved < ub {
        ub = improved;
        pad_of.copy_from_slice(&trial);
    }
    if let Some(fail) = bound_lift(p, m, lb, ub, integral) {
        lb = lb.max(if integral { fail + 1.0 } else { fail });
    }
    if proven(integral, ub, lb) {
        return outcome(true, lb, ub);
    }
    if p.len() + 2 * m > DECISION_MAX_DEPTH {
        let found = run_assignment_search(m, p, integral, lb, ub, pad_of, budget);
        return outcome(found.proven, lb, found.incumbent_min);
    }
    CapacitySearch::new(m, p, integral, lb, ub, pad_of).run(budget)
}

/// Phase 2's search over the capacity `C` (`models/node_time.md`, "Search over `C`"): the bound,
/// the incumbent, bin completion's memo and the LP bound, kept from one decision to the next.
struct CapacitySearch<'a> {
    m: usize,
    p: &'a [f64],
    integral: bool,
    lb: f64,
    ub: f64,
    /// The incumbent's pad of every drone.
    pad_of: &'a mut [usize],
    /// Bin completion's failed states, valid at capacities up to `memo_cap`.
    memo: Memo,
    memo_cap: f64,
    /// The LP, built at its first use (small swarms never stall, so never pay for it), and the
    /// smallest capacity at which it did not refute (it cannot refute any larger one).
    lp: Option<LpBound>,
    lp_failed_at: f64,
    /// The volume bound `sum/k` (whole minutes: rounded up).
    volume: f64,
    /// Whole minutes with a perfect assignment expected ([`PERFECT_EXCESS_MAX_MIN`]).
    perfect_expected: bool,
}

/// How one decision at a capacity `C` ended.
enum AtCapacity {
    /// The first real-valued trial at the bound stopped on its own budget: dropped.
    Dropped,
    /// An assignment with every load within `C`.
    Fits(Vec<usize>),
    /// No assignment within `refuted` (`C`, or the larger capacity the LP refuted).
    DoesNotFit { refuted: f64 },
    /// A limit stopped it.
    Stopped,
}

/// Where a stalled decision is in its slices (`models/node_time.md`, "Stalled decisions").
struct Slices {
    /// Nodes of the current slice.
    nodes: u64,
    /// The current slice, counted from 0.
    round: u64,
    /// The slice after which the LP bound is tried.
    lp_round: u64,
    /// The LP is skipped at the volume bound (a large table, a perfect assignment expected).
    lp_skipped_at_volume: bool,
    /// LP dives run to their end so far.
    dives: u64,
}

impl<'a> CapacitySearch<'a> {
    /// The search from the bound `lb` and the incumbent `ub` (`pad_of`).
    fn new(
        m: usize,
        p: &'a [f64],
        integral: bool,
        lb: f64,
        ub: f64,
        pad_of: &'a mut [usize],
    ) -> Self {
        let volume = p.iter().sum::<f64>() / m as f64;
        let volume = if integral {
            (volume - 1e-9).ceil()
        } else {
            volume
        };
        CapacitySearch {
            m,
            p,
            integral,
            lb,
            ub,
            pad_of,
            memo: Memo::default(),
            memo_cap: f64::INFINITY,
            lp: None,
            lp_failed_at: f64::INFINITY,
            volume,
            perfect_expected: integral && expected_excess(p, m, 1.0) < PERFECT_EXCESS_MAX_MIN,
        }
    }

    /// Decisions at capacities between the bound and the incumbent until they meet or a limit
    /// stops the search.
    fn run(mut self, budget: &mut Budget) -> SearchOutcome {
        let integral = self.integral;
        let mut first = true;
        let mut try_proof = false;
        let mut guess = first_guess(self.m, self.p, integral, self.lb, self.ub);
        for _ in 0..10_000 {
            if proven(integral, self.ub, self.lb) {
                return outcome(true, self.lb, self.ub);
            }
            // First the bound itself; after a new incumbent, just below it (the proof that ends
            // the search); else the midpoint of the gap (whole minutes: of the makespans not
            // excluded).
            let c = if let Some(g) = guess.take() {
                first = false;
                g
            } else if first {
                self.lb
            } else if try_proof {
                if integral {
                    self.ub - 1.0
                } else {
                    self.ub * (1.0 - 0.5 * REL_TOL)
                }
            } else if integral {
                (0.5 * (self.lb + self.ub - 1.0)).floor()
            } else {
                0.5 * (self.lb + self.ub)
            };
            let capped = !integral && first;
            first = false;
            try_proof = false;
            match self.decide_at(c, capped, budget) {
                AtCapacity::Dropped => {}
                AtCapacity::Fits(found_pads) => {
                    // The makespan is recomputed from the assignment, whichever search found it.
                    let found = makespan_sorted(self.m, self.p, &found_pads);
                    if found < self.ub {
                        self.ub = found;
                        self.pad_of.copy_from_slice(&found_pads);
                        try_proof = true;
                    }
                }
                AtCapacity::DoesNotFit { refuted } => {
                    self.lb = if integral {
                        self.lb.max(refuted + 1.0)
                    } else {
                        self.lb.max(refuted)
                    };
                }
                AtCapacity::Stopped => return outcome(false, self.lb, self.ub),
            }
        }
        outcome(proven(integral, self.ub, self.lb), self.lb, self.ub)
    }

    /// One decision at capacity `c`: with `capped`, the real-valued trial at the bound itself,
    /// else bin completion in slices. Bin completion keeps its memo for the next decision.
    fn decide_at(&mut self, c: f64, capped: bool, budget: &mut Budget) -> AtCapacity {
        let c_run = if self.integral {
            c
        } else {
            c * (1.0 + CAP_SLACK)
        };
        if c_run > self.memo_cap {
            self.memo.clear();
        }
        self.memo_cap = c_run;
        let memo = std::mem::take(&mut self.memo);
        let search = BinCompletion::new(self.p, self.m, c_run, self.integral, memo);
        let (at, memo) = if capped {
            first_trial(c, search, budget)
        } else {
            self.in_slices(c, c_run, search, budget)
        };
        self.memo = memo;
        at
    }

    /// Bin completion at `c` in slices, from [`STALL_NODES`] nodes, doubling; between two
    /// slices the bounds and searches of [`CapacitySearch::after_slice`]. Bin completion
    /// resumes with its memo, which it hands back.
    fn in_slices(
        &mut self,
        c: f64,
        c_run: f64,
        mut search: BinCompletion<'a>,
        budget: &mut Budget,
    ) -> (AtCapacity, Memo) {
        let lp_round = if self.integral && (c + 1.0) * self.p.len() as f64 > LP_EARLY_MAX_CELLS {
            LP_LATE_SLICE
        } else {
            0
        };
        let mut slices = Slices {
            nodes: STALL_NODES,
            round: 0,
            lp_round,
            lp_skipped_at_volume: self.perfect_expected
                && c <= self.volume
                && lp_round == LP_LATE_SLICE,
            dives: 0,
        };
        loop {
            let d = budget.within(slices.nodes, |slice| search.decide(slice));
            if d != Decision::Stopped || budget.spent() {
                return decided(d, c, search);
            }
            if let Some(at) = self.after_slice(c, c_run, &mut slices, budget) {
                return (at, search.into_memo());
            }
            if budget.spent() {
                return (AtCapacity::Stopped, search.into_memo());
            }
            slices.round += 1;
            slices.nodes = slices.nodes.saturating_mul(2);
            search = BinCompletion::new(self.p, self.m, c_run, self.integral, search.into_memo());
        }
    }

    /// Between two slices of a stalled decision at `c`: after slice `lp_round` the LP bound
    /// at `c` once (not above a capacity where it failed, nor where it is skipped at the volume
    /// bound); with whole minutes the upper bounds aimed at `c`
    /// ([`CapacitySearch::aim_at_capacity`]); once the LP has failed to refute `c`, an LP dive.
    /// The decision, when one of them settles it.
    fn after_slice(
        &mut self,
        c: f64,
        c_run: f64,
        slices: &mut Slices,
        budget: &mut Budget,
    ) -> Option<AtCapacity> {
        let (m, p, integral) = (self.m, self.p, self.integral);
        if slices.round == slices.lp_round
            && c_run < self.lp_failed_at
            && !slices.lp_skipped_at_volume
        {
            // Refuted at `c`: the bisection up to the incumbent lifts the bound at once (and
            // proves the incumbent when it refutes just below it).
            let lp = self.lp.get_or_insert_with(|| LpBound::new(p, integral));
            if let Some(fail) = lp.lift(m, c, self.ub, budget) {
                return Some(AtCapacity::DoesNotFit {
                    refuted: fail.max(c),
                });
            }
            if !budget.spent() {
                self.lp_failed_at = c_run;
            }
        }
        if integral {
            if let Some(trial) = self.aim_at_capacity(c, slices, budget) {
                return Some(AtCapacity::Fits(trial));
            }
        }
        // Not refuted at `c` by the LP: a dive guided by its patterns, with DIVE_SLICE_FACTOR
        // times the slice's nodes; one cut short by them is run again (same seed) in the next
        // slice.
        if let Some(lp) = self
            .lp
            .as_ref()
            .filter(|_| integral && c_run >= self.lp_failed_at)
        {
            let share = slices.nodes.saturating_mul(DIVE_SLICE_FACTOR);
            let (dived, ended) = budget.within(share, |sub| {
                let dived = lp_dive(m, p, c, slices.dives, lp, sub);
                (dived, !sub.spent())
            });
            if ended {
                slices.dives += 1;
            }
            if let Some(trial) = dived.filter(|t| makespan_sorted(m, p, t) <= c) {
                return Some(AtCapacity::Fits(trial));
            }
        }
        None
    }

    /// Whole minutes, after a slice: the perfect-partition search aimed at `c` from the
    /// incumbent with as many nodes as the slice, then the repacking of pad groups with as many
    /// again, then the exact front and covered tail (`cover.rs`) with as many again
    /// ([`COVER_SLICE_FACTOR`] times as many where the LP is skipped at the volume bound). An
    /// assignment within `c` when one of them finds it; a better one becomes the incumbent.
    fn aim_at_capacity(
        &mut self,
        c: f64,
        slices: &Slices,
        budget: &mut Budget,
    ) -> Option<Vec<usize>> {
        let (m, p) = (self.m, self.p);
        // It starts from the incumbent, so each slice goes on from the best assignment the
        // earlier ones met.
        let mut trial = self.pad_of.to_vec();
        let aimed_at = aim_at(m, p, c, &mut trial, slices.nodes, slices.round, budget);
        let repacked = aimed_at.is_none_or(|x| x > c)
            && p.len() <= REPACK_MAX_DRONES_PER_PAD * m
            && repack(m, p, c, &mut trial, slices.nodes, slices.round, budget).is_some();
        if aimed_at.is_some() || repacked {
            let found = makespan_sorted(m, p, &trial);
            if found <= c {
                return Some(trial);
            }
            if found < self.ub {
                self.ub = found;
                self.pad_of.copy_from_slice(&trial);
            }
        }
        if p.len() <= COVER_MAX_DRONES_PER_PAD * m {
            let factor = if slices.lp_skipped_at_volume {
                COVER_SLICE_FACTOR
            } else {
                1
            };
            let work = slices.nodes.saturating_mul(factor);
            let covered = cover_at(m, p, c, work, slices.round, budget);
            return covered.filter(|t| makespan_sorted(m, p, t) <= c);
        }
        None
    }
}

/// Real minutes: the trial at the bound `c` itself only pays off when the bound is the node
/// time (a perfect split, or the longest drone / pair bound); a failure there proves nothing
/// new, so that trial gets [`FIRST_TRIAL_NODES`] nodes and is dropped when it stops on them.
/// Bin completion hands back its memo.
fn first_trial(c: f64, mut search: BinCompletion<'_>, budget: &mut Budget) -> (AtCapacity, Memo) {
    let d = budget.within(FIRST_TRIAL_NODES, |trial| search.decide(trial));
    if d == Decision::Stopped && !budget.spent() {
        return (AtCapacity::Dropped, search.into_memo());
    }
    decided(d, c, search)
}

/// Bin completion's decision `d` at `c`, with its assignment when it fits, and its memo.
fn decided(d: Decision, c: f64, mut search: BinCompletion<'_>) -> (AtCapacity, Memo) {
    let at = match d {
        Decision::Fits => AtCapacity::Fits(std::mem::take(&mut search.pad_of)),
        Decision::DoesNotFit => AtCapacity::DoesNotFit { refuted: c },
        Decision::Stopped => AtCapacity::Stopped,
    };
    (at, search.into_memo())
}

/// The first capacity bin completion tries when the bound `lb` is `sum/k` itself (not lifted by
/// a long drone, a pair or `L2`): `lb + FIRST_GUESS_EXCESS d` (whole minutes: rounded down), `d`
/// the expected excess of the optimum; `None` when that is not strictly between `lb` and `ub`
/// (then the first trial is at `lb`).
fn first_guess(m: usize, p: &[f64], integral: bool, lb: f64, ub: f64) -> Option<f64> {
    let even = p.iter().sum::<f64>() / m as f64;
    let at_even = if integral {
        lb <= even.ceil()
    } else {
        le_tol(lb, even)
    };
    if !at_even {
        return None;
    }
    let delta = if integral { 1.0 } else { REL_TOL * lb };
    let c = lb + FIRST_GUESS_EXCESS * expected_excess(p, m, delta);
    let c = if integral { c.floor() } else { c };
    (c > lb && c < ub).then_some(c)
}

/// Whether phase 2 is sequential partitioning (`partition.rs`) rather than bin completion, for
/// the charge times `times` (`positive` of them above zero) on `m` pads: at most
/// [`PARTITION_MAX_PADS`] pads and at most [`PARTITION_MAX_DRONES`] drones, and with real-valued
/// times more than [`PARTITION_REAL_DRONES_PER_PAD`] drones per pad and, beyond 2 pads, fewer
/// than one in [`REPEATED_SHARE_DENOMINATOR`] repeated; with whole minutes at least
/// [`PARTITION_WHOLE_DRONES_PER_PAD`] per pad and no assignment expected to meet the bound (the
/// expected excess of the optimum over `sum/k` at least half a minute; below, bin completion
/// usually finds a perfect assignment at `C = LB` at once). Measured by
/// `examples/bench_node_time.rs`: elsewhere bin completion is faster.
fn use_partition(m: usize, times: &[f64], positive: usize, integral: bool) -> bool {
    if m > PARTITION_MAX_PADS || positive > PARTITION_MAX_DRONES {
        return false;
    }
    if !integral {
        return positive > PARTITION_REAL_DRONES_PER_PAD * m
            && (m == 2 || REPEATED_SHARE_DENOMINATOR * repeated_times(times) < positive);
    }
    if positive < PARTITION_WHOLE_DRONES_PER_PAD * m {
        return false;
    }
    let p: Vec<f64> = times.iter().copied().filter(|&t| t > 0.0).collect();
    expected_excess(&p, m, 1.0) >= PERFECT_EXCESS_MAX_MIN
}

/// How many of the positive `times` equal an earlier one.
fn repeated_times(times: &[f64]) -> usize {
    let mut p: Vec<f64> = times.iter().copied().filter(|&t| t > 0.0).collect();
    p.sort_by(f64::total_cmp);
    p.windows(2).filter(|w| w[0] == w[1]).count()
}

/// The expected excess of the node time over `sum/k` for `m` pads and drones with charge times
/// like `p` (random, independent), at resolution `delta` (see `models/node_time.md`, "Expected
/// excess of the optimum over `sum/k`"). The `m^n / m!` assignments give `choice = log2(m^n / m!)` bits;
/// each of the `m - 1` free pad loads, spread over about `sqrt(2π) σ`, takes
/// `log2(sqrt(2π) σ / delta)` bits to land within `delta` of its target; about one assignment
/// has every load within `d` of `sum/k` when `(m d / delta)^(m-1) / (m-1)! = 2^(constraint -
/// choice)`. Returns 0 when there are no more drones than pads.
pub(crate) fn expected_excess(p: &[f64], m: usize, delta: f64) -> f64 {
    let n = p.len();
    if n <= m || m < 2 {
        return 0.0;
    }
    let (nf, k) = (n as f64, m as f64);
    let mean = p.iter().sum::<f64>() / nf;
    let var = p.iter().map(|&x| (x - mean) * (x - mean)).sum::<f64>() / nf;
    let per_pad = nf / k;
    let spread = (per_pad * var + per_pad * (1.0 - 1.0 / k) * mean * mean) * (1.0 - 1.0 / k);
    let sigma = spread.sqrt();
    let log2_factorial = |x: usize| (2..=x).map(|i| (i as f64).log2()).sum::<f64>();
    let choice = nf * k.log2() - log2_factorial(m);
    let constraint = (k - 1.0) * ((2.0 * std::f64::consts::PI).sqrt() * sigma / delta).log2();
    let log2_d = (delta / k).log2() + (log2_factorial(m - 1) + constraint - choice) / (k - 1.0);
    log2_d.exp2()
}

/// Exact node time by combinatorial branch and bound.
///
/// # Arguments
/// * `pads` - number of identical pads `k`.
/// * `charge_times_min` - charge time `p_j` of each drone, minutes (zero is fine).
/// * `limits` - optional time limit (s) and node limit; with neither the result is proven.
///
/// # Returns
/// A [`NodeTimeSolution`] with method `exact`: `Optimal` with `lower_bound_min == makespan_min`
/// when the proof completed; `Feasible` with the incumbent and the best proven lower bound (the
/// root bound `max(p_max, sum/k, p_k + p_{k+1}, ...)`, lifted by `L2`, the count bound and failed
/// decisions)
/// when a limit stopped it. With `pads >= drones` the node time is the longest charge time, one
/// drone per pad.
///
/// # Errors
/// Those of [`validate`]; `E5006` for a negative or non-finite time limit.
///
/// # Complexity
/// Worst case exponential (P||Cmax is strongly NP-hard); `O(n k)` memory plus at most `2^21`
/// remembered failed states, or two lists of `2^(n/2)` subset sums (sequential partitioning,
/// `n <= 40`). Medians on seeded uniform instances (`examples/bench_node_time.rs`, 100 per row)
/// up to 30 drones and 10 pads: whole minutes in `U[1,100]` and `U[1,1000]` below 0.1 and 0.8 ms;
/// in `U[1,10000]` below 0.2 ms except 30 drones on 6 to 10 pads (0.8 to 2.3 ms); real-valued
/// times below 1 ms on 2 to 6 and on 10 pads, 1.6 to 2.0 ms for 30 drones on 7 to 9 pads; 100
/// whole-minute drones on 10 pads below 0.1 ms. 100 real-valued drones on 10 pads are not proven
/// within 10 s: a limit returns the incumbent, `Feasible`.
///
/// # Example
/// ```
/// use swarmplan::node_time::{exact, Limits};
/// use swarmplan::solver::SolveStatus;
/// let s = exact(3, &[60.0, 50.0, 40.0, 30.0, 20.0], &Limits::default()).unwrap();
/// assert_eq!(s.makespan_min, 70.0);
/// assert_eq!(s.status, SolveStatus::Optimal);
/// ```
pub fn exact(pads: usize, charge_times_min: &[f64], limits: &Limits) -> Result<NodeTimeSolution> {
    exact_with(pads, charge_times_min, limits, ExactSearch::Auto)
}

/// Which search [`exact_with`] runs after the first 2,000 nodes of the assignment branch and
/// bound (see `models/node_time.md`, "Exact method").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ExactSearch {
    /// Sequential partitioning with at most 7 pads and 40 drones, for real-valued times with more
    /// than 4 drones per pad and for whole minutes with at least 5 per pad and an optimum
    /// expected above `sum/k`, handing over to bin completion after 1,000,000 nodes with at most 6
    /// drones per pad; bin completion otherwise (what [`exact()`] does).
    #[default]
    Auto,
    /// Bin completion under bisection of the makespan (`completion.rs`).
    BinCompletion,
    /// Sequential partitioning (`partition.rs`); bin completion above 40 drones with positive
    /// charge time.
    Partition,
}

/// [`exact()`] with the search after the first phase chosen by the caller, to compare the two
/// searches; every choice returns the same proven node time.
///
/// # Arguments
/// As [`exact()`], and `search`, the phase-2 search.
///
/// # Returns
/// As [`exact()`].
///
/// # Errors
/// As [`exact()`].
///
/// # Example
/// ```
/// use swarmplan::node_time::{exact_with, ExactSearch, Limits};
/// let times = [60.0, 50.0, 40.0, 30.0, 20.0];
/// let s = exact_with(3, &times, &Limits::default(), ExactSearch::Partition).unwrap();
/// assert_eq!(s.makespan_min, 70.0);
/// ```
pub fn exact_with(
    pads: usize,
    charge_times_min: &[f64],
    limits: &Limits,
    search: ExactSearch,
) -> Result<NodeTimeSolution> {
    let positive = charge_times_min.iter().filter(|&&p| p > 0.0).count();
    let next = match search {
        ExactSearch::Auto => {
            if use_partition(
                pads,
                charge_times_min,
                positive,
                all_integral(charge_times_min),
            ) {
                Next::PartitionThenBinCompletion
            } else {
                Next::BinCompletion
            }
        }
        ExactSearch::BinCompletion => Next::BinCompletion,
        ExactSearch::Partition if positive <= PARTITION_MAX_DRONES => Next::Partition,
        ExactSearch::Partition => Next::BinCompletion,
    };
    let phase1_nodes = if pads == 2 && next == Next::BinCompletion {
        u64::MAX
    } else {
        PHASE1_NODES
    };
    exact_phased(pads, charge_times_min, limits, phase1_nodes, next)
}

/// The search of phase 2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Next {
    /// Bin completion under bisection of the makespan.
    BinCompletion,
    /// Sequential partitioning to the end (at most [`PARTITION_MAX_DRONES`] positive drones).
    Partition,
    /// Sequential partitioning, handing over to bin completion after [`PARTITION_SWITCH_NODES`]
    /// nodes with at most [`PARTITION_SWITCH_DRONES_PER_PAD`] drones per pad.
    PartitionThenBinCompletion,
}

/// [`exact`] with `phase1_nodes` nodes of the assignment search before phase 2 (0 skips phase
/// 1; the tests use it to check each phase-2 method alone), and phase 2 by `next`.
pub(crate) fn exact_phased(
    pads: usize,
    charge_times_min: &[f64],
    limits: &Limits,
    phase1_nodes: u64,
    next: Next,
) -> Result<NodeTimeSolution> {
    validate(pads, charge_times_min)?;
    validate_limits(limits)?;
    let start = Instant::now();
    let mut solution = if pads >= charge_times_min.len() {
        one_drone_per_pad(charge_times_min)
    } else {
        let budget = Budget {
            nodes: 0,
            start,
            limits,
        };
        solve_sorted(pads, charge_times_min, budget, phase1_nodes, next)
    };
    solution.solve_ms = elapsed_ms(start);
    Ok(solution)
}

/// At least as many pads as drones: one drone per pad, the longest charge time proven optimal
/// ([`exact_phased`] stamps the time).
fn one_drone_per_pad(charge_times_min: &[f64]) -> NodeTimeSolution {
    let makespan = charge_times_min.iter().copied().fold(0.0, f64::max);
    NodeTimeSolution {
        method: NodeTimeMethod::Exact,
        makespan_min: makespan,
        lower_bound_min: makespan,
        status: SolveStatus::Optimal,
        assignment: one_per_pad(charge_times_min.len()),
        solve_ms: 0.0,
    }
}

/// Fewer pads than drones: the drones sorted by decreasing charge time, the root bound and LPT's
/// incumbent, then the phases ([`Phases::run`]) unless LPT meets the bound ([`exact_phased`]
/// stamps the time).
fn solve_sorted(
    m: usize,
    charge_times_min: &[f64],
    mut budget: Budget,
    phase1_nodes: u64,
    next: Next,
) -> NodeTimeSolution {
    let n = charge_times_min.len();
    let (order, sorted) = sort_desc(charge_times_min);
    let integral = all_integral(charge_times_min);
    let lb = lower_bound_sorted(m, &sorted, integral);
    // Zero-time drones (at the end of `sorted`) change no load: they join pad 0 at the end.
    let positive = sorted.iter().take_while(|&&p| p > 0.0).count();
    let mut pad_sorted = vec![0; n];
    let ub = lpt_sorted(m, &sorted[..positive], &mut pad_sorted[..positive]);
    let (finished, lb) = if proven(integral, ub, lb) {
        (true, lb)
    } else {
        let mut phases = Phases {
            m,
            p: &sorted[..positive],
            integral,
            lb,
            ub,
            pad_of: &mut pad_sorted[..positive],
        };
        let finished = phases.run(phase1_nodes, next, &mut budget);
        (finished, phases.lb)
    };
    let mut pad_of = vec![0; n];
    for (pos, &j) in order.iter().enumerate() {
        pad_of[j] = pad_sorted[pos];
    }
    let assignment = lists_from_pad_of(&pad_of, m);
    let makespan = super::makespan_of(charge_times_min, &assignment);
    NodeTimeSolution {
        method: NodeTimeMethod::Exact,
        makespan_min: makespan,
        lower_bound_min: if finished { makespan } else { lb.min(makespan) },
        status: if finished {
            SolveStatus::Optimal
        } else {
            SolveStatus::Feasible
        },
        assignment,
        solve_ms: 0.0,
    }
}

/// The phases of one exact solve (`models/node_time.md`, "Exact method") on the drones of
/// positive charge time, sorted decreasingly: the bound and the incumbent they pass on.
struct Phases<'a> {
    m: usize,
    p: &'a [f64],
    integral: bool,
    lb: f64,
    ub: f64,
    /// The incumbent's pad of every drone.
    pad_of: &'a mut [usize],
}

impl Phases<'_> {
    /// Phase 1, the cardinality bound and largest differencing's start, then phase 2 by `next`,
    /// while the incumbent is not proven and the budget lasts: whether it is proven.
    fn run(&mut self, phase1_nodes: u64, next: Next, budget: &mut Budget) -> bool {
        // Phase 1: the assignment branch and bound, briefly (small swarms end here).
        if phase1_nodes > 0 && self.assignment_search(phase1_nodes, budget) {
            return true;
        }
        // The cardinality bound, `O(n k)`: after phase 1, so that the small swarms it proves
        // never pay for it.
        self.lb = self
            .lb
            .max(cardinality_bound(self.m, self.p, self.integral));
        if proven(self.integral, self.ub, self.lb) {
            return true;
        }
        let positive = self.p.len();
        if !self.integral
            && positive > PARTITION_MAX_DRONES
            && positive >= LDM_DRONES_PER_PAD * self.m
        {
            self.ldm_start();
        }
        if budget.spent() {
            return false;
        }
        match next {
            Next::BinCompletion => self.phase2(budget),
            Next::Partition | Next::PartitionThenBinCompletion => self.partition(next, budget),
        }
    }

    /// Phase 1 within `phase1_nodes` nodes: whether it proved its incumbent.
    fn assignment_search(&mut self, phase1_nodes: u64, budget: &mut Budget) -> bool {
        let (m, p, integral, lb, ub) = (self.m, self.p, self.integral, self.lb, self.ub);
        let pad_of = &mut *self.pad_of;
        let found = budget.within(phase1_nodes, |phase1| {
            run_assignment_search(m, p, integral, lb, ub, pad_of, phase1)
        });
        self.ub = found.incumbent_min;
        found.proven
    }

    /// Real-valued times beyond partitioning's reach with many drones per pad, where a limit
    /// may well stop the proof: largest differencing balances better than LPT.
    fn ldm_start(&mut self) {
        let mut alt = vec![0; self.p.len()];
        let found = ldm_sorted(self.m, self.p, &mut alt);
        if found < self.ub {
            self.ub = found;
            self.pad_of.copy_from_slice(&alt);
        }
    }

    /// Phase 2 by sequential partitioning; with few drones per pad and `next`
    /// [`Next::PartitionThenBinCompletion`], a search that runs long hands over to bin
    /// completion, which keeps the bound reached (the load of the set tried last). Whether the
    /// incumbent is proven.
    fn partition(&mut self, next: Next, budget: &mut Budget) -> bool {
        let (m, p, lb, ub) = (self.m, self.p, self.lb, self.ub);
        let switch = next == Next::PartitionThenBinCompletion
            && p.len() <= PARTITION_SWITCH_DRONES_PER_PAD * m;
        let share = if switch {
            PARTITION_SWITCH_NODES
        } else {
            u64::MAX
        };
        let pad_of = &mut *self.pad_of;
        let found = budget.within(share, |part| partition(m, p, lb, ub, pad_of, part));
        self.lb = found.lower_bound_min;
        if !found.proven && switch && !budget.spent() {
            return self.phase2(budget);
        }
        found.proven
    }

    /// Phase 2 by local search, bounds and bin completion ([`phase2`]): whether the incumbent
    /// is proven.
    fn phase2(&mut self, budget: &mut Budget) -> bool {
        let found = phase2(
            self.m,
            self.p,
            self.integral,
            self.lb,
            self.ub,
            self.pad_of,
            budget,
        );
        self.lb = found.lower_bound_min;
        found.proven
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::node_time::brute;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `n` charge times of one random kind: whole minutes with ties and zeros, reals, wide whole
    /// minutes (optimum many minutes above the bound), or few distinct values.
    fn small_times(rng: &mut ChaCha8Rng, n: usize) -> Vec<f64> {
        let kind = rng.random_range(0..4);
        (0..n)
            .map(|_| match kind {
                0 => f64::from(rng.random_range(0..=30u32)),
                1 => rng.random_range(0.0..100.0),
                2 => f64::from(rng.random_range(1..=10_000u32)),
                _ => f64::from(rng.random_range(1..=3u32)) * 2.5,
            })
            .collect()
    }

    /// Asserts that `e` is proven optimal, charges every drone exactly once, reports the largest
    /// recomputed pad load, and equals the reference node time `reference_min` (within 1e-9).
    fn assert_optimal(times: &[f64], e: &NodeTimeSolution, reference_min: f64, context: &str) {
        assert_eq!(e.status, SolveStatus::Optimal, "{context}");
        let mut count = vec![0; times.len()];
        e.assignment.iter().flatten().for_each(|&j| count[j] += 1);
        assert!(count.iter().all(|&c| c == 1), "{context}: {e:?}");
        let recomputed = crate::node_time::makespan_of(times, &e.assignment);
        assert_eq!(recomputed, e.makespan_min, "{context}");
        assert!(
            (e.makespan_min - reference_min).abs() <= 1e-9 * reference_min.max(1.0),
            "{context}: {} against reference {reference_min}",
            e.makespan_min
        );
    }

    /// Phase 2 alone (local search, `L2` and count bounds, bin completion) agrees with brute force.
    #[test]
    fn decision_version_alone_equals_brute_force() {
        let mut rng = ChaCha8Rng::seed_from_u64(40);
        for case in 0..3000 {
            let n = rng.random_range(1..=10);
            let k = rng.random_range(1..=4);
            let times = small_times(&mut rng, n);
            let b = brute(k, &times, &Limits::default()).unwrap();
            let e = exact_phased(k, &times, &Limits::default(), 0, Next::BinCompletion).unwrap();
            let full = exact(k, &times, &Limits::default()).unwrap();
            let context = format!("case {case}: k={k} times={times:?}");
            assert_optimal(&times, &e, b.makespan_min, &context);
            assert_optimal(&times, &full, b.makespan_min, &context);
        }
    }

    /// Sequential partitioning alone (phase 1 skipped) agrees with brute force, on real, whole
    /// and repeated times.
    #[test]
    fn sequential_partitioning_alone_equals_brute_force() {
        let mut rng = ChaCha8Rng::seed_from_u64(41);
        for case in 0..3000 {
            let n = rng.random_range(1..=10);
            let k = rng.random_range(2..=4);
            let times = small_times(&mut rng, n);
            let b = brute(k, &times, &Limits::default()).unwrap();
            let e = exact_phased(k, &times, &Limits::default(), 0, Next::Partition).unwrap();
            assert_optimal(
                &times,
                &e,
                b.makespan_min,
                &format!("case {case}: k={k} times={times:?}"),
            );
        }
    }

    /// Beyond brute force's reach, the two phase-2 methods (different searches over different
    /// spaces: sets per pad in increasing load, and bin completion under bisection) prove the
    /// same node time on real-valued swarms of 14 to 28 drones on 2 to 7 pads.
    #[test]
    fn sequential_partitioning_equals_bin_completion_on_larger_real_swarms() {
        let mut rng = ChaCha8Rng::seed_from_u64(42);
        for case in 0..200 {
            let n = rng.random_range(14..=28);
            let k = rng.random_range(2..=7);
            let times: Vec<f64> = (0..n).map(|_| rng.random_range(1.0..100.0)).collect();
            let none = Limits::default();
            let a = exact_phased(k, &times, &none, 0, Next::Partition).unwrap();
            let b = exact_phased(k, &times, &none, 0, Next::BinCompletion).unwrap();
            let context = format!("case {case}: k={k} times={times:?}");
            assert_eq!(b.status, SolveStatus::Optimal, "{context}");
            assert_optimal(&times, &a, b.makespan_min, &context);
        }
    }

    /// A swarm on which sequential partitioning runs long (about 400,000 nodes; the slowest of
    /// 300 random swarms of 30 real-valued drones on 7 pads) while bin completion proves it in a
    /// few thousand: `exact` hands over after `PARTITION_SWITCH_NODES` nodes, keeping the
    /// partitioning's bound, and proves the same node time as each search run alone.
    #[test]
    fn sequential_partitioning_hands_over_to_bin_completion_on_a_long_search() {
        let times = [
            71.55152673905367,
            10.625711027749215,
            3.2125818575359557,
            56.59950963230777,
            1.9484939325430979,
            99.94159946753571,
            9.290679299888925,
            77.12978576064714,
            22.224502724613643,
            46.17400954246027,
            1.8696473449772502,
            1.4269776127174019,
            2.792078748723851,
            96.87864963829848,
            85.5618540051607,
            84.65827921909013,
            36.609315960867,
            1.3026593795355585,
            19.657521764192957,
            55.95635866775829,
            4.436358382792687,
            68.18872318093447,
            15.564145217604263,
            1.8892750131298897,
            9.786473244851152,
            63.204885804916096,
            41.708772566474266,
            61.10793131333399,
            11.0608955870893,
            24.122779492061763,
        ];
        let none = Limits::default();
        let cut = Limits {
            time_limit_s: None,
            node_limit: Some(PHASE1_NODES + PARTITION_SWITCH_NODES),
        };
        // Partitioning alone does not finish within the nodes before the handover.
        let stopped = exact_phased(7, &times, &cut, PHASE1_NODES, Next::Partition).unwrap();
        assert_eq!(stopped.status, SolveStatus::Feasible);
        let partition_alone = exact_phased(7, &times, &none, 0, Next::Partition).unwrap();
        let bin_completion_alone = exact_phased(7, &times, &none, 0, Next::BinCompletion).unwrap();
        assert_eq!(bin_completion_alone.status, SolveStatus::Optimal);
        assert_optimal(
            &times,
            &partition_alone,
            bin_completion_alone.makespan_min,
            "partitioning alone",
        );
        let handed_over = exact(7, &times, &none).unwrap();
        assert_optimal(
            &times,
            &handed_over,
            bin_completion_alone.makespan_min,
            "exact",
        );
        assert!(stopped.lower_bound_min <= handed_over.makespan_min);
    }

    /// 100 real-valued drones on 10 pads under a node limit: the proof does not finish, and the
    /// incumbent returned is a valid assignment no worse than LPT's or largest differencing's
    /// (its starting points), with a lower bound below it.
    #[test]
    fn many_real_drones_under_a_limit_keep_the_better_start() {
        let mut rng = ChaCha8Rng::seed_from_u64(44);
        for case in 0..5 {
            let times: Vec<f64> = (0..100).map(|_| rng.random_range(1.0..100.0)).collect();
            let limits = Limits {
                time_limit_s: None,
                node_limit: Some(20_000),
            };
            let s = exact(10, &times, &limits).unwrap();
            assert_eq!(s.status, SolveStatus::Feasible, "case {case}");
            let mut count = vec![0; times.len()];
            s.assignment.iter().flatten().for_each(|&j| count[j] += 1);
            assert!(count.iter().all(|&c| c == 1), "case {case}");
            assert_eq!(
                crate::node_time::makespan_of(&times, &s.assignment),
                s.makespan_min
            );
            let (_, sorted) = crate::node_time::sort_desc(&times);
            let mut pad_of = vec![0; sorted.len()];
            let by_ldm = ldm_sorted(10, &sorted, &mut pad_of);
            let by_lpt = lpt_sorted(10, &sorted, &mut pad_of);
            assert!(by_ldm < by_lpt, "case {case}: {by_ldm} against {by_lpt}");
            assert!(s.makespan_min <= by_ldm * (1.0 + 1e-12), "case {case}");
            assert!(s.lower_bound_min <= s.makespan_min, "case {case}");
        }
    }

    /// Bin completion at its deepest allowed recursion (`n + 2k = DECISION_MAX_DEPTH`: 2,920
    /// drones of 1 min on 40 pads of capacity 73, every pad filled by 73 recursive takes) on a
    /// thread with a 2 MiB stack, the default of spawned threads: no overflow, and the packing
    /// found puts exactly 73 drones on each pad.
    #[test]
    fn bin_completion_at_the_deepest_recursion_fits_a_two_mib_stack() {
        let (k, n) = (40, DECISION_MAX_DEPTH - 80);
        let loads = std::thread::Builder::new()
            .stack_size(2 << 20)
            .spawn(move || {
                let p = vec![1.0; n];
                let limits = Limits::default();
                let mut budget = Budget::new(&limits);
                let mut search = BinCompletion::new(&p, k, 73.0, true, Memo::default());
                assert_eq!(search.decide(&mut budget), Decision::Fits);
                let mut loads = vec![0usize; k];
                search.pad_of.iter().for_each(|&i| loads[i] += 1);
                loads
            })
            .expect("thread")
            .join()
            .expect("no stack overflow");
        assert_eq!(loads, vec![73; 40]);
    }

    /// The expected excess on a case worked by hand: times 1, 2, 3, 4 on 2 pads at a resolution
    /// of 1 min. Mean 2.5, variance 1.25, 2 drones per pad: spread (2 * 1.25 + 2 * 0.5 * 6.25) *
    /// 0.5 = 4.375, sigma = 2.0917; choice = log2(2^4 / 2!) = 3 bits; constraint =
    /// log2(sqrt(2 pi) * 2.0917) = 2.3904 bits; log2 d = log2(1/2) + (0 + 2.3904 - 3) / 1 =
    /// -1.6096, d = 0.3277 min. Fewer drones than pads: 0.
    #[test]
    fn expected_excess_matches_a_hand_computed_case() {
        let d = expected_excess(&[1.0, 2.0, 3.0, 4.0], 2, 1.0);
        assert!((d - 0.3277).abs() < 1e-4, "{d}");
        assert_eq!(expected_excess(&[5.0, 6.0], 3, 1.0), 0.0);
    }

    /// The first guess on the hand-computed case above, real-valued: the bound is sum/2 = 5, the
    /// expected excess does not depend on the resolution with 2 pads (0.3277 min), so the first
    /// capacity is 5 + 2.5 * 0.3277 = 5.819. None when that is not below the incumbent, when the
    /// bound was lifted above sum/k, or with whole minutes (5.819 rounds down to the bound).
    #[test]
    fn first_guess_is_the_bound_plus_two_and_a_half_expected_excesses() {
        let p = [4.0, 3.0, 2.0, 1.0];
        let c = first_guess(2, &p, false, 5.0, 6.0).expect("between bound and incumbent");
        assert!((c - 5.8192).abs() < 1e-3, "{c}");
        assert_eq!(first_guess(2, &p, false, 5.0, 5.5), None);
        assert_eq!(first_guess(2, &p, false, 5.5, 6.0), None);
        assert_eq!(first_guess(2, &p, true, 5.0, 7.0), None);
    }

    /// A node limit stops sequential partitioning with a valid incumbent, labelled feasible, and
    /// a lower bound no larger than the optimum.
    #[test]
    fn sequential_partitioning_under_a_node_limit_is_feasible_with_a_valid_bound() {
        let mut rng = ChaCha8Rng::seed_from_u64(43);
        let mut stopped = [0, 0];
        for case in 0..60 {
            // 3 pads: list queries; 5 pads: cached queries.
            let k = if case % 2 == 0 { 3 } else { 5 };
            let times: Vec<f64> = (0..24).map(|_| rng.random_range(1.0..100.0)).collect();
            let opt = exact_phased(k, &times, &Limits::default(), 0, Next::BinCompletion)
                .unwrap()
                .makespan_min;
            let limits = Limits {
                time_limit_s: None,
                node_limit: Some(3),
            };
            let s = exact_phased(k, &times, &limits, 0, Next::Partition).unwrap();
            assert!(s.lower_bound_min <= opt * (1.0 + 1e-12));
            assert!(s.makespan_min >= opt * (1.0 - 1e-9));
            if s.status == SolveStatus::Feasible {
                stopped[case % 2] += 1;
                assert!(s.lower_bound_min <= s.makespan_min);
            } else {
                assert!((s.makespan_min - opt).abs() <= 1e-9 * opt);
            }
        }
        assert!(
            stopped.iter().all(|&s| s > 0),
            "three nodes never stopped the search: {stopped:?}"
        );
    }
}
