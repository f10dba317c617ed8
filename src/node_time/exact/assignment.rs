//! Phase 1 of the exact search: the assignment branch and bound (`models/node_time.md`, "Exact
//! method"). Jobs are taken in decreasing charge time; a node fixes the pads of jobs `1..j`,
//! pads within the capacity below the incumbent, pruned by the useful slack, one pad per load.

use crate::node_time::search::{Budget, SearchOutcome, CLOCK_EVERY_NODES};
use crate::node_time::{le_tol, Limits, REL_TOL};
use std::time::Instant;

/// Depth-first branch and bound over the positive jobs, sorted decreasingly.
struct Search<'a> {
    /// `p[j]`, decreasing, all > 0.
    p: &'a [f64],
    /// `rem[j] = p[j] + ... + p[n-1]`.
    rem: Vec<f64>,
    /// Number of pads `m` in use.
    m: usize,
    integral: bool,
    /// Root lower bound.
    lb: f64,
    /// Incumbent makespan.
    ub: f64,
    /// Pad of each sorted job in the incumbent.
    best: Vec<usize>,
    /// Largest load an improving assignment may have.
    cap: f64,
    loads: Vec<f64>,
    pad_of: Vec<usize>,
    /// Load of the pad of job `j` before job `j` was put on it (exact restore on backtrack).
    prev: Vec<f64>,
    /// Candidate pads of job `j`: `cands[j*m .. j*m + ncand[j]]`, increasing load.
    cands: Vec<usize>,
    ncand: Vec<usize>,
    /// Whether job `j`'s pad was fixed by dominance (one candidate, no branching).
    forced: Vec<bool>,
    /// Next candidate of job `j` to try.
    next: Vec<usize>,
    nodes: u64,
}

impl Search<'_> {
    fn cap_for(&self, ub: f64) -> f64 {
        if self.integral {
            ub - 1.0
        } else {
            ub - REL_TOL * ub
        }
    }

    fn proven(&self) -> bool {
        if self.integral {
            self.ub <= self.lb
        } else {
            le_tol(self.ub, self.lb)
        }
    }

    /// Fills the candidate list of job `j` under the current capacity.
    fn expand(&mut self, j: usize) {
        let m = self.m;
        let pj = self.p[j];
        let p_min = self.p[self.p.len() - 1];
        let cap = self.cap;
        self.ncand[j] = 0;
        self.next[j] = 0;
        self.forced[j] = false;
        // Useful slack bound.
        let mut useful = 0.0;
        for &l in &self.loads {
            let s = cap - l;
            if s >= p_min {
                useful += s;
            }
        }
        if useful < self.rem[j] {
            return;
        }
        let n = self.p.len();
        // Two shortest jobs after j: a pad whose slack is below their sum takes at most one more.
        let two_shortest = if n >= j + 3 {
            self.p[n - 1] + self.p[n - 2]
        } else {
            f64::INFINITY
        };
        // Identical consecutive jobs: job j goes to a pad at least as loaded as the one job j-1
        // went to (before it), unless job j-1 was placed by dominance.
        let floor = if j > 0 && pj == self.p[j - 1] && !self.forced[j - 1] {
            self.prev[j - 1]
        } else {
            f64::NEG_INFINITY
        };
        let base = j * m;
        let mut count = 0;
        for i in 0..m {
            let l = self.loads[i];
            if l + pj > cap || l < floor {
                continue;
            }
            // Dominance: pad i fits job j and can take at most one later job (<= p_j): put j
            // there and branch no further.
            if cap - l < two_shortest {
                self.cands[base] = i;
                self.ncand[j] = 1;
                self.forced[j] = true;
                return;
            }
            // Symmetry: pads with equal load lead to the same subtrees.
            if self.cands[base..base + count]
                .iter()
                .any(|&c| self.loads[c] == l)
            {
                continue;
            }
            // Insert keeping increasing load.
            let mut pos = count;
            while pos > 0 && self.loads[self.cands[base + pos - 1]] > l {
                self.cands[base + pos] = self.cands[base + pos - 1];
                pos -= 1;
            }
            self.cands[base + pos] = i;
            count += 1;
        }
        self.ncand[j] = count;
    }

    /// Runs the search; returns `true` when it finished (proof complete), `false` when a limit
    /// stopped it.
    fn run(&mut self, start: Instant, limits: &Limits) -> bool {
        let n = self.p.len();
        let mut j = 0;
        self.expand(0);
        loop {
            // Take the next candidate of job j that still fits under the (possibly lowered) cap.
            let mut placed = false;
            while self.next[j] < self.ncand[j] {
                let i = self.cands[j * self.m + self.next[j]];
                self.next[j] += 1;
                if self.loads[i] + self.p[j] > self.cap {
                    continue;
                }
                self.prev[j] = self.loads[i];
                self.loads[i] += self.p[j];
                self.pad_of[j] = i;
                placed = true;
                break;
            }
            if placed {
                self.nodes += 1;
                if j + 1 == n {
                    // Leaf: every load is within cap < UB, a strictly better incumbent.
                    self.ub = self.loads.iter().copied().fold(0.0, f64::max);
                    self.best.copy_from_slice(&self.pad_of);
                    if self.proven() {
                        return true;
                    }
                    self.cap = self.cap_for(self.ub);
                    self.loads[self.pad_of[j]] = self.prev[j];
                    if self.limit_hit(start, limits) {
                        return false;
                    }
                    continue;
                }
                if self.limit_hit(start, limits) {
                    return false;
                }
                j += 1;
                self.expand(j);
                continue;
            }
            // A dominance decision holds only while the forced pad still fits job j: once a
            // better incumbent lowered the capacity below that, branch over the other pads.
            if self.forced[j] {
                let i = self.cands[j * self.m];
                if self.loads[i] + self.p[j] > self.cap {
                    self.expand(j);
                    continue;
                }
            }
            // Job j exhausted: backtrack.
            if j == 0 {
                return true;
            }
            j -= 1;
            self.loads[self.pad_of[j]] = self.prev[j];
        }
    }

    fn limit_hit(&self, start: Instant, limits: &Limits) -> bool {
        if let Some(max_nodes) = limits.node_limit {
            if self.nodes >= max_nodes {
                return true;
            }
        }
        if let Some(t) = limits.time_limit_s {
            if self.nodes.is_multiple_of(CLOCK_EVERY_NODES) && start.elapsed().as_secs_f64() >= t {
                return true;
            }
        }
        false
    }
}

/// Runs the assignment branch and bound from incumbent `ub` (pads in `best`, updated in place),
/// counting its nodes on `budget`; the outcome's lower bound is `lb` (or the incumbent, proven).
pub(super) fn run_assignment_search(
    m: usize,
    p: &[f64],
    integral: bool,
    lb: f64,
    ub: f64,
    best: &mut [usize],
    budget: &mut Budget,
) -> SearchOutcome {
    let n = p.len();
    let mut rem = vec![0.0; n + 1];
    for j in (0..n).rev() {
        rem[j] = rem[j + 1] + p[j];
    }
    let mut search = Search {
        p,
        rem,
        m,
        integral,
        lb,
        ub,
        best: best.to_vec(),
        cap: 0.0,
        loads: vec![0.0; m],
        pad_of: vec![0; n],
        prev: vec![0.0; n],
        cands: vec![0; n * m],
        ncand: vec![0; n],
        forced: vec![false; n],
        next: vec![0; n],
        nodes: budget.nodes,
    };
    search.cap = search.cap_for(ub);
    let done = search.run(budget.start, budget.limits);
    best.copy_from_slice(&search.best);
    budget.nodes = search.nodes;
    SearchOutcome {
        proven: done,
        lower_bound_min: if done { search.ub } else { lb },
        incumbent_min: search.ub,
    }
}
