//! Bin-packing LP bound for the decision "do the drones fit on `k` pads of capacity `C`?"
//! (Gilmore–Gomory column generation, clarabel for the restricted LP, an exact bounded knapsack
//! for the pricing), rounded safely by Farley's bound in integer arithmetic. See
//! `models/node_time.md`, "LP bound".
//!
//! Drone lengths are grouped into types `t` with length `w_t` and count `d_t`. A pattern `a` is
//! a feasible pad content: `a_t` drones of type `t`, `0 <= a_t <= d_t`, `sum_t a_t w_t <= C`. The
//! dual of the bin-packing LP is
//!
//! ```text
//! maximise  sum_t d_t y_t   subject to  sum_t a_t y_t <= 1 for every pattern a,  y >= 0,
//! ```
//!
//! solved over a growing set of patterns. For any `y >= 0`, with `v_t = floor(y_t 2^30)` and
//! `V* = max_a sum_t a_t v_t` (the exact knapsack optimum, integers), every pad weighs at most
//! `V*` and all drones weigh `sum_t d_t v_t`, so at least `ceil(sum_t d_t v_t / V*)` pads are
//! needed (Farley 1990). That is the bound returned: whatever the LP solver's accuracy, it is a
//! proof.

use crate::node_time::search::{Budget, CAP_SLACK};
use crate::node_time::REL_TOL;
use crate::solver::conic::{self, ConicSettings, CscMatrix, NonnegativeConeT, SupportedConeT};
use crate::solver::BackendStatus;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::collections::{HashMap, HashSet};

/// Fixed-point scale of the dual values `v_t = floor(y_t SCALE)`.
const SCALE: f64 = (1u64 << 30) as f64;

/// Most column-generation iterations of one bound.
const MAX_ITERATIONS: usize = 200;

/// Largest `pieces x (C + 1)` table of the dynamic-programming pricing (whole minutes); larger
/// knapsacks go to branch and bound. `2^24` cells (a 2 MiB bit table for the pattern) admits 100
/// drones with times near 10,000 min (nu3 of the classical classes, `C` about 94,000), where the
/// branch and bound stops at its node limit and its fractional bound proves nothing.
const DP_MAX_CELLS: usize = 1 << 24;

/// Node limit of one branch-and-bound pricing; when it is reached, the fractional knapsack bound
/// stands in for the optimum (still a valid `V*`, only weaker).
const KNAPSACK_MAX_NODES: u64 = 200_000;

/// Nodes of the shared budget one restricted LP solve counts as (about its time, against a node
/// of bin completion: tens to hundreds of microseconds for tens of types and patterns).
const LP_SOLVE_NODES: u64 = 20_000;

/// Work units (table cells or knapsack nodes) that count as one node of the shared budget.
const WORK_PER_NODE: u64 = 16;

/// Tolerance of the dive on the LP's floating-point values (pattern values read as whole
/// pads, the residual LP against the pads left); the dive is a heuristic, its pads are checked.
const DIVE_LP_TOL: f64 = 1e-6;

/// Most patterns an [`LpBound`] keeps for later capacities.
const POOL_MAX_PATTERNS: usize = 4000;

/// Result of [`lp_bins`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LpBins {
    /// Proven lower bound on the number of pads of capacity `C` that hold every drone.
    pub bins: u64,
    /// The restricted LP's last value (floating point, for reports only).
    pub lp_value: f64,
    /// Column-generation iterations run.
    pub iterations: usize,
}

/// Drone types: distinct lengths (decreasing) and their counts.
fn types_of(p: &[f64]) -> (Vec<f64>, Vec<u64>) {
    let (mut w, mut d) = (Vec::new(), Vec::new());
    for &x in p {
        if w.last() == Some(&x) {
            *d.last_mut().expect("a type") += 1;
        } else {
            w.push(x);
            d.push(1);
        }
    }
    (w, d)
}

/// Binary pieces of the table pricing: `c` copies of type `t` as one 0/1 item (type, copies,
/// value), copies `1, 2, 4, ...` up to the count that fits `cap`.
fn pieces_of(w: &[f64], d: &[u64], v: &[u64], cap: f64) -> Vec<(usize, u64, u64)> {
    let mut pieces = Vec::new();
    for t in 0..w.len() {
        if v[t] == 0 {
            continue;
        }
        let mut left = d[t].min((cap / w[t]).floor() as u64);
        let mut c = 1;
        while left > 0 {
            let take = c.min(left);
            pieces.push((t, take, take * v[t]));
            left -= take;
            c *= 2;
        }
    }
    pieces
}

/// The knapsack optimum `V*(x)` of [`knapsack`] for every capacity `x` in `0..=cap` (whole
/// minutes) from one table; `None` when the table would exceed [`DP_MAX_CELLS`].
fn values_by_capacity(w: &[f64], d: &[u64], v: &[u64], cap: usize) -> Option<Vec<u64>> {
    let pieces = pieces_of(w, d, v, cap as f64);
    if pieces.len().saturating_mul(cap + 1) > DP_MAX_CELLS {
        return None;
    }
    let mut dp = vec![0u64; cap + 1];
    for &(t, c, val) in &pieces {
        let wt = (w[t] as usize) * c as usize;
        for x in (wt..=cap).rev() {
            dp[x] = dp[x].max(dp[x - wt] + val);
        }
    }
    Some(dp)
}

/// Exact bounded knapsack: `max sum_t a_t v_t` over `0 <= a_t <= d_t`, `sum_t a_t w_t <= cap`.
/// Returns (an upper bound on the optimum, which is the optimum unless the branch and bound hit
/// its node limit; the best pattern found; work done).
fn knapsack(w: &[f64], d: &[u64], v: &[u64], cap: f64, integral: bool) -> (u64, Vec<u64>, u64) {
    if integral && cap >= 0.0 {
        let cap_i = cap.floor() as usize;
        let pieces = pieces_of(w, d, v, cap);
        let cells = pieces.len().saturating_mul(cap_i + 1);
        if cells <= DP_MAX_CELLS {
            let words = (cap_i + 1).div_ceil(64);
            let mut keep = vec![0u64; pieces.len() * words];
            let mut dp = vec![0u64; cap_i + 1];
            for (q, &(t, c, val)) in pieces.iter().enumerate() {
                let wt = (w[t] as usize) * c as usize;
                for x in (wt..=cap_i).rev() {
                    let cand = dp[x - wt] + val;
                    if cand > dp[x] {
                        dp[x] = cand;
                        keep[q * words + x / 64] |= 1 << (x % 64);
                    }
                }
            }
            let mut a = vec![0u64; w.len()];
            let mut x = cap_i;
            for (q, &(t, c, _)) in pieces.iter().enumerate().rev() {
                if keep[q * words + x / 64] >> (x % 64) & 1 == 1 {
                    a[t] += c;
                    x -= (w[t] as usize) * c as usize;
                }
            }
            return (dp[cap_i], a, cells as u64);
        }
    }
    knapsack_bb(w, d, v, cap)
}

/// Branch and bound for [`knapsack`]: types by decreasing `v_t / w_t`, counts from the largest
/// down, pruned by the fractional (Dantzig) bound with a margin for rounding.
fn knapsack_bb(w: &[f64], d: &[u64], v: &[u64], cap: f64) -> (u64, Vec<u64>, u64) {
    let mut order: Vec<usize> = (0..w.len()).filter(|&t| v[t] > 0).collect();
    order.sort_by(|&a, &b| (v[b] as f64 / w[b]).total_cmp(&(v[a] as f64 / w[a])));
    let frac = |from: usize, room: f64| -> f64 {
        let mut room = room;
        let mut s = 0.0;
        for &t in &order[from..] {
            let all = d[t] as f64 * w[t];
            if all <= room {
                s += d[t] as f64 * v[t] as f64;
                room -= all;
            } else {
                s += v[t] as f64 * room / w[t];
                break;
            }
        }
        s
    };
    // Pruning is sound when the fractional bound, widened by its rounding, cannot reach best + 1.
    let prunes = |bound: f64, best: u64| bound * (1.0 + 1e-9) + 1e-6 < (best + 1) as f64;
    let root = frac(0, cap);
    struct St<'a> {
        order: &'a [usize],
        w: &'a [f64],
        d: &'a [u64],
        v: &'a [u64],
        a: Vec<u64>,
        best: u64,
        best_a: Vec<u64>,
        nodes: u64,
    }
    fn dfs(
        s: &mut St,
        i: usize,
        room: f64,
        val: u64,
        frac: &dyn Fn(usize, f64) -> f64,
        prunes: &dyn Fn(f64, u64) -> bool,
    ) {
        if val > s.best {
            s.best = val;
            s.best_a.copy_from_slice(&s.a);
        }
        if i == s.order.len() || s.nodes >= KNAPSACK_MAX_NODES {
            return;
        }
        s.nodes += 1;
        if prunes(val as f64 + frac(i, room), s.best) {
            return;
        }
        let t = s.order[i];
        let most = s.d[t].min((room / s.w[t]).floor().max(0.0) as u64);
        for c in (0..=most).rev() {
            let used = c as f64 * s.w[t];
            if used > room {
                continue;
            }
            s.a[t] = c;
            dfs(s, i + 1, room - used, val + c * s.v[t], frac, prunes);
            s.a[t] = 0;
            if s.nodes >= KNAPSACK_MAX_NODES {
                break;
            }
        }
    }
    let mut st = St {
        order: &order,
        w,
        d,
        v,
        a: vec![0; w.len()],
        best: 0,
        best_a: vec![0; w.len()],
        nodes: 0,
    };
    dfs(&mut st, 0, cap, 0, &frac, &prunes);
    let bound = if st.nodes >= KNAPSACK_MAX_NODES {
        // Not proven: the root's fractional bound, rounded up with margin, bounds the optimum.
        st.best.max((root * (1.0 + 1e-9)).ceil() as u64 + 1)
    } else {
        st.best
    };
    (bound, st.best_a, st.nodes)
}

/// Solves the restricted dual LP over `patterns`: `max d'y`, `A y <= 1`, `y >= 0`. Returns
/// `y`, the objective and the primal pattern values `x` (the multipliers of `A y <= 1`: `min
/// 1'x`, `A'x >= d`, `x >= 0`), or `None` when clarabel does not solve it.
fn restricted_dual(d: &[u64], patterns: &[Vec<u64>]) -> Option<(Vec<f64>, f64, Vec<f64>)> {
    let nt = d.len();
    let (mut ri, mut ci, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for (r, a) in patterns.iter().enumerate() {
        for (t, &c) in a.iter().enumerate() {
            if c > 0 {
                ri.push(r);
                ci.push(t);
                vals.push(c as f64);
            }
        }
    }
    let rows = patterns.len();
    for t in 0..nt {
        ri.push(rows + t);
        ci.push(t);
        vals.push(-1.0);
    }
    let a = CscMatrix::new_from_triplets(rows + nt, nt, ri, ci, vals);
    let mut b = vec![1.0; rows];
    b.extend(std::iter::repeat_n(0.0, nt));
    let q: Vec<f64> = d.iter().map(|&x| -(x as f64)).collect();
    let p = CscMatrix::new_from_triplets(nt, nt, Vec::new(), Vec::new(), Vec::new());
    let cones: Vec<SupportedConeT<f64>> = vec![NonnegativeConeT(rows + nt)];
    let settings = ConicSettings {
        tolerance: 1e-9,
        time_limit_s: None,
    };
    let out = conic::solve(&p, &q, &a, &b, &cones, settings).ok()?;
    match (out.status, out.values) {
        (BackendStatus::Optimal, Some(v)) => {
            let y: Vec<f64> = v.x.iter().map(|&x| x.max(0.0)).collect();
            let x: Vec<f64> = v.z[..rows].iter().map(|&z| z.max(0.0)).collect();
            Some((y, -v.primal, x))
        }
        _ => None,
    }
}

/// First-fit decreasing at capacity `cap`, as patterns over the types.
fn ffd_patterns(w: &[f64], d: &[u64], cap: f64) -> Vec<Vec<u64>> {
    let mut bins: Vec<(f64, Vec<u64>)> = Vec::new();
    for t in 0..w.len() {
        for _ in 0..d[t] {
            match bins.iter_mut().find(|(load, _)| *load + w[t] <= cap) {
                Some((load, a)) => {
                    *load += w[t];
                    a[t] += 1;
                }
                None => {
                    let mut a = vec![0; w.len()];
                    a[t] = 1;
                    bins.push((w[t], a));
                }
            }
        }
    }
    bins.into_iter().map(|(_, a)| a).collect()
}

/// Fixes one pad of pattern `a` cut to the drones `left` (a pattern of the covering LP may hold
/// more of a type than remain): pushes it to `fixed` and takes its drones from `left`. Returns
/// whether the pad holds any drone.
fn take(a: &[u64], left: &mut [u64], fixed: &mut Vec<Vec<u64>>) -> bool {
    let cut: Vec<u64> = a.iter().zip(left.iter()).map(|(&c, &l)| c.min(l)).collect();
    if cut.iter().all(|&c| c == 0) {
        return false;
    }
    for (l, &c) in left.iter_mut().zip(&cut) {
        *l -= c;
    }
    fixed.push(cut);
    true
}

/// The bin-packing LP of one set of drones, asked at several capacities (the bisection of
/// [`LpBound::lift`], the decisions of bin completion): every pattern priced is kept in a pool
/// and starts the restricted LP of any later capacity at least its weight.
pub(crate) struct LpBound {
    /// Type lengths, decreasing.
    w: Vec<f64>,
    /// Type counts.
    d: Vec<u64>,
    /// Whole minutes (the table pricing applies).
    integral: bool,
    /// Patterns priced so far, with their weights `sum_t a_t w_t`.
    pool: Vec<(Vec<u64>, f64)>,
    /// The dual `y` of the best Farley bound of the last [`LpBound::bins`].
    best_dual: Option<Vec<f64>>,
    /// The patterns and primal values `x` of the last restricted LP solved.
    primal: Option<(Vec<Vec<u64>>, Vec<f64>)>,
}

impl LpBound {
    /// The LP of the drones `p` (sorted decreasingly, all `> 0`); `integral` allows the exact
    /// table pricing.
    pub(crate) fn new(p: &[f64], integral: bool) -> Self {
        let (w, d) = types_of(p);
        LpBound {
            w,
            d,
            integral,
            pool: Vec::new(),
            best_dual: None,
            primal: None,
        }
    }

    fn weight(&self, a: &[u64]) -> f64 {
        a.iter().zip(&self.w).map(|(&c, &x)| c as f64 * x).sum()
    }

    /// Lower bound on the pads of capacity `cap` that hold the drones; with a `target`, stops
    /// as soon as the bound exceeds it or the LP cannot reach it (without, runs to the LP
    /// optimum); counts its work on `budget` (checked between iterations).
    ///
    /// `cap` is the capacity the patterns are checked against: the caller widens it for
    /// real-valued times (as bin completion does), so that every pattern within the true
    /// capacity is one here.
    ///
    /// Complexity: at most [`MAX_ITERATIONS`] LP solves (interior point, polynomial) and one
    /// knapsack each (`O(T C log n)` by table, or a branch and bound of at most
    /// [`KNAPSACK_MAX_NODES`] nodes).
    pub(crate) fn bins(&mut self, cap: f64, target: Option<u64>, budget: &mut Budget) -> LpBins {
        let mut best_dual = None;
        let out = self.column_generation(cap, target, budget, &mut best_dual);
        self.best_dual = best_dual.map(|(y, _)| y);
        out
    }

    /// [`LpBound::bins`], leaving the best Farley dual and its bound in `best_dual`.
    fn column_generation(
        &mut self,
        cap: f64,
        target: Option<u64>,
        budget: &mut Budget,
        best_dual: &mut Option<(Vec<f64>, f64)>,
    ) -> LpBins {
        let none = LpBins {
            bins: 0,
            lp_value: 0.0,
            iterations: 0,
        };
        let nt = self.w.len();
        if nt == 0 {
            return none;
        }
        if self.w[0] > cap {
            return LpBins {
                bins: u64::MAX,
                lp_value: f64::INFINITY,
                iterations: 0,
            };
        }
        let (w, d) = (self.w.clone(), self.d.clone());
        let mut patterns: Vec<Vec<u64>> = (0..nt)
            .map(|t| {
                let mut a = vec![0; nt];
                a[t] = d[t].min((cap / w[t]).floor() as u64).max(1);
                a
            })
            .collect();
        patterns.extend(ffd_patterns(&w, &d, cap));
        patterns.extend(
            self.pool
                .iter()
                .filter(|(_, weight)| *weight <= cap)
                .map(|(a, _)| a.clone()),
        );
        let mut seen: HashSet<Vec<u64>> = patterns.iter().cloned().collect();
        let mut best = 0u64;
        let mut lp_value = 0.0;
        let total_of =
            |v: &[u64]| -> u128 { d.iter().zip(v).map(|(&c, &x)| c as u128 * x as u128).sum() };
        for it in 1..=MAX_ITERATIONS {
            budget.nodes = budget.nodes.saturating_add(LP_SOLVE_NODES);
            let Some((y_lp, value, x_lp)) = restricted_dual(&d, &patterns) else {
                return LpBins {
                    bins: best,
                    lp_value,
                    iterations: it,
                };
            };
            lp_value = value;
            // The restricted LP (an upper bound on the full LP) cannot exceed the target.
            if target.is_some_and(|k| value <= k as f64 + 1e-7) {
                self.primal = Some((patterns, x_lp));
                return LpBins {
                    bins: best,
                    lp_value,
                    iterations: it,
                };
            }
            let v: Vec<u64> = y_lp.iter().map(|&x| (x * SCALE).floor() as u64).collect();
            let (vmax, a, work) = knapsack(&w, &d, &v, cap, self.integral);
            budget.nodes = budget.nodes.saturating_add(work / WORK_PER_NODE);
            if vmax > 0 {
                let total = total_of(&v);
                let bins = total.div_ceil(vmax as u128);
                best = best.max(u64::try_from(bins).unwrap_or(u64::MAX));
                let farley = total as f64 / vmax as f64;
                if best_dual.as_ref().is_none_or(|(_, f)| farley > *f) {
                    *best_dual = Some((y_lp, farley));
                }
            }
            // The pattern enters when it prices out (`V* > 1` in fixed point) and is new.
            let column = ((vmax as f64) > SCALE * (1.0 + 1e-7) && !seen.contains(&a)).then_some(a);
            let out = LpBins {
                bins: best,
                lp_value,
                iterations: it,
            };
            // Proven; or no pattern prices out (the LP is solved); or a limit.
            if target.is_some_and(|k| best > k) || budget.spent() {
                return out;
            }
            let Some(a) = column else { return out };
            seen.insert(a.clone());
            if self.pool.len() < POOL_MAX_PATTERNS {
                self.pool.push((a.clone(), self.weight(&a)));
            }
            patterns.push(a);
        }
        LpBins {
            bins: best,
            lp_value,
            iterations: MAX_ITERATIONS,
        }
    }

    /// Whether the LP proves that the drones do not fit on `k` pads of capacity `c`: `nt > c`.
    /// Real-valued times are checked against `c (1 + CAP_SLACK)`.
    pub(crate) fn refutes(&mut self, k: usize, c: f64, budget: &mut Budget) -> bool {
        let widened = if self.integral {
            c
        } else {
            c * (1.0 + CAP_SLACK)
        };
        self.bins(widened, Some(k as u64), budget).bins > k as u64
    }

    /// Largest `c` in `[lo, hi)` found by bisection with [`LpBound::refutes`], i.e. proven
    /// `nt > c`; `None` when the LP does not refute `lo`. Like `bound_lift`, any refuted `c` is
    /// a valid bound (feasibility is monotone in `c`). With whole minutes, each refutation's best
    /// dual is first tried at every larger capacity at once ([`LpBound::dual_reach`]), which
    /// replaces most LP solves of the bisection.
    pub(crate) fn lift(&mut self, k: usize, lo: f64, hi: f64, budget: &mut Budget) -> Option<f64> {
        if !self.refutes(k, lo, budget) {
            return None;
        }
        let (mut fail, mut ok) = (lo, hi);
        for _ in 0..60 {
            if let Some(c) = self.dual_reach(k, fail, ok) {
                fail = fail.max(c);
            }
            let width_left = if self.integral {
                ok - fail > 1.0
            } else {
                ok - fail > REL_TOL * ok
            };
            if !width_left || budget.spent() {
                break;
            }
            let mid = if self.integral {
                ((fail + ok) / 2.0).floor()
            } else {
                0.5 * (fail + ok)
            };
            if self.refutes(k, mid, budget) {
                fail = mid;
            } else {
                ok = mid;
            }
        }
        Some(fail)
    }

    /// LP diving towards an assignment on `k` pads of capacity `cap`: solve the LP of the
    /// drones not yet placed until its restricted LP needs at most the pads left, fix as pads
    /// the patterns it uses at least once (when none is, the one it uses most, or with `rng` one
    /// drawn with probability proportional to its value), and repeat on the rest. Returns the pads fixed, in
    /// order, as counts per type (each of weight `<= cap`, at most `k`), and whether they hold
    /// every drone; it stops early when a residual LP needs more pads than are left or on a
    /// limit. A heuristic: an incomplete dive proves nothing.
    ///
    /// Complexity: at most `k` rounds, each a column generation ([`LpBound::bins`]) warm-started
    /// from the pool.
    pub(crate) fn dive(
        &self,
        k: usize,
        cap: f64,
        rng: Option<&mut ChaCha8Rng>,
        budget: &mut Budget,
    ) -> (Vec<Vec<u64>>, bool) {
        let mut rng = rng;
        let mut fixed: Vec<Vec<u64>> = Vec::new();
        let mut left = self.d.clone();
        let mut residual = LpBound {
            w: self.w.clone(),
            d: left.clone(),
            integral: self.integral,
            pool: self
                .pool
                .iter()
                .filter(|(_, weight)| *weight <= cap)
                .cloned()
                .collect(),
            best_dual: None,
            primal: None,
        };
        while left.iter().any(|&c| c > 0) {
            let pads_left = (k - fixed.len()) as u64;
            if pads_left == 0 || budget.spent() {
                return (fixed, false);
            }
            residual.d.clone_from(&left);
            residual
                .pool
                .retain(|(a, _)| a.iter().zip(&left).all(|(&c, &l)| c <= l));
            // Column generation stops as soon as the restricted LP needs at most the pads left:
            // its solution, feasible for the full LP, guides the dive as well as an optimal
            // one and costs a fraction (one iteration per round against up to a hundred).
            let r = residual.bins(cap, Some(pads_left), budget);
            if r.bins > pads_left || r.lp_value > pads_left as f64 + DIVE_LP_TOL {
                return (fixed, false);
            }
            let Some((patterns, x)) = residual.primal.take() else {
                return (fixed, false);
            };
            // The restricted LP may hold a pattern more than once (a single type that is also a
            // first-fit pad, a pool pattern): its values are summed.
            let mut value_of: HashMap<&[u64], f64> = HashMap::new();
            for (a, &v) in patterns.iter().zip(&x) {
                *value_of.entry(a.as_slice()).or_default() += v;
            }
            let (patterns, x): (Vec<&[u64]>, Vec<f64>) = patterns
                .iter()
                .filter_map(|a| value_of.remove(a.as_slice()).map(|v| (a.as_slice(), v)))
                .unzip();
            let mut took = false;
            for (q, a) in patterns.iter().enumerate() {
                for _ in 0..(x[q] + DIVE_LP_TOL).floor() as u64 {
                    if !take(a, &mut left, &mut fixed) {
                        break;
                    }
                    took = true;
                }
            }
            if !took {
                let most = match rng.as_deref_mut() {
                    // A pattern drawn with probability proportional to its value.
                    Some(rng) => {
                        let total: f64 = x.iter().sum();
                        let mut at = rng.random::<f64>() * total;
                        (0..patterns.len()).find(|&q| {
                            at -= x[q];
                            at <= 0.0 && x[q] > 0.0
                        })
                    }
                    None => (0..patterns.len()).max_by(|&a, &b| x[a].total_cmp(&x[b])),
                };
                if !most.is_some_and(|q| take(patterns[q], &mut left, &mut fixed)) {
                    return (fixed, false);
                }
            }
            if fixed.len() > k {
                fixed.truncate(k);
                return (fixed, false);
            }
        }
        (fixed, true)
    }

    /// Type counts `d_t` of the drones (types by decreasing length: the drones of type `t` are
    /// the `d_t` consecutive ones after those of the earlier types).
    pub(crate) fn counts(&self) -> &[u64] {
        &self.d
    }

    /// Largest capacity `c` in `[from, below)` at which the last best Farley dual `v` still
    /// proves more than `k` pads: `ceil(sum_t d_t v_t / V*(c)) > k`, with `V*(c)` for every
    /// `c` from one knapsack table (whole minutes). `None` without a dual, for real-valued times,
    /// or when the table is too large.
    fn dual_reach(&self, k: usize, from: f64, below: f64) -> Option<f64> {
        let y = self.best_dual.as_ref()?;
        if !self.integral || below <= from + 1.0 {
            return None;
        }
        let v: Vec<u64> = y.iter().map(|&x| (x * SCALE).floor() as u64).collect();
        let total: u128 = self
            .d
            .iter()
            .zip(&v)
            .map(|(&c, &x)| c as u128 * x as u128)
            .sum();
        let top = (below - 1.0) as usize;
        let values = values_by_capacity(&self.w, &self.d, &v, top)?;
        let refuted = |x: usize| values[x] > 0 && total.div_ceil(values[x] as u128) > k as u128;
        // `V*` grows with the capacity, so the refuted capacities are a prefix.
        (from as usize..=top)
            .take_while(|&x| refuted(x))
            .last()
            .map(|x| x as f64)
    }
}

/// Lower bound on the pads of capacity `cap` that hold the drones `p` (sorted decreasingly, all
/// `> 0`) by the bin-packing LP, asked once ([`LpBound::bins`]).
#[cfg(test)]
fn lp_bins(
    p: &[f64],
    cap: f64,
    integral: bool,
    target: Option<u64>,
    budget: &mut Budget,
) -> LpBins {
    LpBound::new(p, integral).bins(cap, target, budget)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::node_time::Limits;

    /// Table pricing and branch and bound agree on the knapsack optimum.
    #[test]
    fn table_and_branch_and_bound_agree() {
        let w = [7.0, 5.0, 4.0, 3.0];
        let d = [2, 3, 1, 4];
        let v = [70, 52, 38, 31];
        for cap in 0..=40 {
            let (a, pa, _) = knapsack(&w, &d, &v, f64::from(cap), true);
            let (b, _, _) = knapsack_bb(&w, &d, &v, f64::from(cap));
            assert_eq!(a, b, "cap {cap}");
            let weight: f64 = pa.iter().zip(&w).map(|(&c, &x)| c as f64 * x).sum();
            let value: u64 = pa.iter().zip(&v).map(|(&c, &x)| c * x).sum();
            assert!(weight <= f64::from(cap));
            assert_eq!(value, a);
        }
    }

    /// Five drones of 7, 5, 5, 3, 2 min on 2 pads (sum 22): every combinatorial bound stops at
    /// 11 (root: `sum/2 = 11`; `L2(11) = 2`; the count bound and its lift do not exceed 2 pads),
    /// but no split meets 11 (7 needs 4 more, which 5, 3, 2 cannot make), so `nt = 12`.
    /// Hand-computed LP at `C = 11`: the maximal patterns are {7,3}, {7,2}, {5,5}, {5,3,2}; the
    /// duals `y = (3/4, 1/2, 1/4, 1/4)` for (7, 5, 3, 2) give every pattern weight `<= 1` and the
    /// drones weight `3/4 + 2/2 + 1/4 + 1/4 = 9/4`, and the primal `x{7,3} = x{7,2} = x{5,3,2} =
    /// 1/2`, `x{5,5} = 3/4` covers every drone with `9/4` pads: the LP value is `9/4 > 2`, so the
    /// LP proves `nt >= 12`.
    #[test]
    fn lp_bound_proves_an_optimum_above_every_combinatorial_bound() {
        let p = [7.0, 5.0, 5.0, 3.0, 2.0];
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        let lb = crate::node_time::lower_bound_sorted(2, &p, true);
        assert_eq!(lb, 11.0);
        assert_eq!(crate::node_time::bounds::l2_bins(&p, 11.0), 2);
        assert_eq!(
            crate::node_time::bounds::bound_lift(&p, 2, lb, 12.0, true),
            None
        );
        let r = lp_bins(&p, 11.0, true, None, &mut budget);
        assert!((r.lp_value - 2.25).abs() < 1e-6, "{r:?}");
        assert_eq!(r.bins, 3);
        assert_eq!(
            LpBound::new(&p, true).lift(2, lb, 12.0, &mut budget),
            Some(11.0)
        );
        assert_eq!(lp_bins(&p, 12.0, true, None, &mut budget).bins, 2);
    }

    /// One [`LpBound`] asked first at 12 then at 11 on the drones above: the pool holds patterns
    /// of weight 12 ({7, 5}, {7, 3, 2}, {5, 5, 2}), which must not enter the LP at 11, where
    /// the hand-computed value is still 9/4 (3 pads). The best dual at 11, `y = (3/4, 1/2, 1/4,
    /// 1/4)`, weighs every pattern of capacity 12 at most 5/4 (each of the three above), so at
    /// 12 it proves only `ceil((9/4) / (5/4)) = 2` pads: it reaches no capacity beyond 11.
    #[test]
    fn the_pool_keeps_heavier_patterns_out_and_the_dual_reaches_no_further() {
        let p = [7.0, 5.0, 5.0, 3.0, 2.0];
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        let mut lp = LpBound::new(&p, true);
        assert_eq!(lp.bins(12.0, None, &mut budget).bins, 2);
        assert!(lp.pool.iter().any(|(_, weight)| *weight == 12.0));
        let at_11 = lp.bins(11.0, None, &mut budget);
        assert!((at_11.lp_value - 2.25).abs() < 1e-6, "{at_11:?}");
        assert_eq!(at_11.bins, 3);
        assert_eq!(lp.dual_reach(2, 11.0, 13.0), Some(11.0));
    }

    /// Drones 6, 6, 5, 5, 4, 4 on 3 pads of 10 (types 6, 5, 4, two each). The drones weigh 30 =
    /// 3 x 10, so an LP solution of value 3 uses only full patterns, {6, 4} and {5, 5}, and
    /// covering the types needs `x{6,4} = 2`, `x{5,5} = 1`: the dive fixes exactly those pads.
    #[test]
    fn the_dive_fixes_the_whole_patterns_of_an_integral_lp() {
        let p = [6.0, 6.0, 5.0, 5.0, 4.0, 4.0];
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        let lp = LpBound::new(&p, true);
        let (mut pads, complete) = lp.dive(3, 10.0, None, &mut budget);
        assert!(complete);
        pads.sort();
        assert_eq!(pads, vec![vec![0, 2, 0], vec![1, 0, 1], vec![1, 0, 1]]);
    }

    /// On the hand-computed case above (LP value 9/4 at capacity 11), two pads are fewer than
    /// the LP needs: the dive fixes nothing and says it is incomplete.
    #[test]
    fn the_dive_stops_where_the_lp_needs_more_pads() {
        let p = [7.0, 5.0, 5.0, 3.0, 2.0];
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        let (pads, complete) = LpBound::new(&p, true).dive(2, 11.0, None, &mut budget);
        assert!(!complete);
        assert!(pads.is_empty(), "{pads:?}");
    }

    #[test]
    fn three_long_items_need_three_bins() {
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        let r = lp_bins(&[6.0, 6.0, 6.0], 10.0, true, Some(2), &mut budget);
        assert_eq!(r.bins, 3);
    }
}
