//! The pad assignment of the node-time objective by a branch and bound of its own, on the warm
//! re-solves of a dense dual simplex ([`crate::solver::dense`]; `models/eaas_config.md`, "The
//! pad search").
//!
//! The model's optimum is `V = min_A LP(A)` over the assignments `A` of drones to the `k`
//! identical pads, `LP(A)` the configuration LP with each pad's load row `sum_{d on p} ct_d <= M`.
//! The root is the LP with every `ct_d <= M` and `sum_d ct_d <= min(k, n) M` (valid for every
//! assignment). A node assigns the next drone, longest charge time first, to a pad already used
//! or to the first empty one (the pads are identical: any other empty pad gives the same
//! subtree); its LP is the parent's with the pad's new load row, added only when the parent's
//! point violates it (otherwise that point is the child's optimum too) and then re-solved by
//! the dual simplex from the parent's basis, until the point keeps every pad's row. A leaf
//! is `LP(A)` itself. Children are tried least-loaded pad first (at the parent's point), so the
//! first dive is LPT's assignment; a node whose LP value reaches the least upper bound known
//! (within [`PRUNE_REL`]) is pruned. When the search ends,
//! `V >= min(ub, p)` with `ub` the least of the leaves and the incumbent and `p` the least LP
//! value of a node pruned (within the tolerance band below `ub`, else `p >= ub`); stopped by the
//! node limit, `V >=` also the least value of a node left with children unexplored.

use super::ChargeTime;
use crate::solver::dense::{DenseFailure, Sense, Tableau};
use std::borrow::Cow;
use std::time::Instant;

/// A node whose LP value is within this relative distance of the least upper bound (`max(1, ub)`
/// times it) is pruned; the search's bound is the least value of a node pruned, when below `ub`.
pub(super) const PRUNE_REL: f64 = 1e-9;

/// A pad's load row counts as kept at a point when it exceeds `M` by at most this, relative to
/// `max(1, M)` (the simplex's own feasibility tolerance is of this order).
pub(super) const SETTLE_REL: f64 = 1e-9;

/// How a search ended.
pub(super) struct PadSearchEnd {
    /// The best leaf below the incumbent: the pad of every drone and the LP's optimum.
    pub leaf: Option<(Vec<usize>, Tableau)>,
    /// The least upper bound on `V`: the best leaf's value, or the incumbent's.
    pub value: f64,
    /// A proven lower bound on `V`.
    pub bound: f64,
    /// Whether the search ran to its end (else a node or time limit stopped it).
    pub complete: bool,
}

/// A drone's charge time in the LP's columns: `constant - per_min * battery`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Charge {
    pub battery: Option<usize>,
    pub per_min: f64,
    pub constant: f64,
}

impl Charge {
    /// In the columns of the dense LP, column `i` good_lp's variable `i`.
    pub fn of(c: &ChargeTime) -> Charge {
        Charge {
            battery: c.battery.map(crate::solver::variable_index),
            per_min: c.per_min,
            constant: c.constant,
        }
    }

    fn at(&self, node: &Tableau) -> f64 {
        self.constant - self.battery.map_or(0.0, |b| self.per_min * node.value(b))
    }
}

/// The load row of `drones` on one pad, `sum ct_d - M <= 0`, as terms over the columns and its
/// right-hand side; `makespan` the column of `M`.
pub(super) fn load_row(
    charges: &[Charge],
    makespan: usize,
    drones: &[usize],
) -> (Vec<(usize, f64)>, f64) {
    let mut terms = Vec::with_capacity(drones.len() + 1);
    let mut rhs = 0.0;
    for &d in drones {
        let c = &charges[d];
        rhs -= c.constant;
        if let Some(b) = c.battery {
            terms.push((b, -c.per_min));
        }
    }
    terms.push((makespan, -1.0));
    (terms, rhs)
}

/// The search's settings and state.
struct Search<'a> {
    charges: &'a [Charge],
    makespan: usize,
    order: &'a [usize],
    pads: usize,
    node_limit: Option<u64>,
    deadline: Option<Instant>,
    /// A pad's row is kept when it exceeds `M` by at most this, relative ([`SETTLE_REL`]).
    settle_rel: f64,
    nodes: u64,
    /// The least upper bound on `V`.
    ub: f64,
    leaf: Option<(Vec<usize>, Tableau)>,
    /// The least LP value of a node left with children unexplored by a limit, or pruned.
    open: f64,
    stopped: bool,
}

/// Runs the search from `root` (the LP of [`super::Pads::Aggregate`]) over the drones in
/// `order` (every drone once, longest charge time first), on `pads` pads, below the upper bound
/// `incumbent` (`f64::INFINITY`: none), with the node-time variable `makespan`.
///
/// # Errors
/// The simplex's failures, infeasibility among them: every node LP is feasible when the root is
/// (`M` has no upper bound), so an infeasible one is a numerical failure, and the caller then
/// solves the pad MILP.
///
/// # Complexity
/// At most `sum_{j < n} k^j` LPs, each a warm re-solve; in practice a few per drone.
#[allow(clippy::too_many_arguments)]
pub(super) fn search(
    root: Tableau,
    charges: &[Charge],
    makespan: usize,
    order: &[usize],
    pads: usize,
    incumbent: f64,
    node_limit: Option<u64>,
    deadline: Option<Instant>,
) -> Result<PadSearchEnd, DenseFailure> {
    let limits = (node_limit, deadline);
    search_settling_within(
        root, charges, makespan, order, pads, incumbent, limits, SETTLE_REL,
    )
}

/// [`search`], a pad's load row counted as kept when it exceeds `M` by at most `settle_rel`
/// times `max(1, |M|)`.
#[allow(clippy::too_many_arguments)]
fn search_settling_within(
    root: Tableau,
    charges: &[Charge],
    makespan: usize,
    order: &[usize],
    pads: usize,
    incumbent: f64,
    (node_limit, deadline): (Option<u64>, Option<Instant>),
    settle_rel: f64,
) -> Result<PadSearchEnd, DenseFailure> {
    let mut s = Search {
        settle_rel,
        charges,
        makespan,
        order,
        pads: pads.max(1),
        node_limit,
        deadline,
        nodes: 0,
        ub: incumbent,
        leaf: None,
        open: f64::INFINITY,
        stopped: false,
    };
    let mut on_pad: Vec<Vec<usize>> = vec![Vec::new(); s.pads];
    s.dive(&root, 0, &mut on_pad)?;
    Ok(PadSearchEnd {
        value: s.ub,
        bound: s.ub.min(s.open),
        complete: !s.stopped,
        leaf: s.leaf,
    })
}

impl Search<'_> {
    /// Whether a node of LP value `value` is pruned; the bound then remembers its value.
    fn prunes(&mut self, value: f64) -> bool {
        let pruned = value >= self.ub - PRUNE_REL * self.ub.abs().max(1.0);
        if pruned {
            self.open = self.open.min(value);
        }
        pruned
    }

    fn limit_reached(&self) -> bool {
        self.node_limit.is_some_and(|n| self.nodes >= n)
            || self.deadline.is_some_and(|d| Instant::now() >= d)
    }

    /// The pad's load at `node`'s point less `M`: positive when its row is violated.
    fn excess(&self, drones: &[usize], node: &Tableau) -> f64 {
        let load: f64 = drones.iter().map(|&d| self.charges[d].at(node)).sum();
        load - node.value(self.makespan)
    }

    /// The node LP of the assignment `on_pad`, from its parent's optimum `parent`: the pads' load
    /// rows are added lazily, each only while the point violates it (the parent's rows hold), so
    /// a child whose new row the parent's point already keeps is the parent's optimum itself, no
    /// re-solve. A pad's row is added at most once: once in the LP, the simplex keeps it within
    /// its own tolerance ([`crate::solver::dense::PRIMAL_TOL`], relative to the row's
    /// right-hand side), which can exceed [`SETTLE_REL`]; adding it again would change nothing
    /// and loop.
    fn settle<'n>(
        &self,
        parent: &'n Tableau,
        on_pad: &[Vec<usize>],
    ) -> Result<Cow<'n, Tableau>, DenseFailure> {
        let mut node = Cow::Borrowed(parent);
        let mut added = vec![false; on_pad.len()];
        loop {
            let tolerance = self.settle_rel * node.objective().abs().max(1.0);
            let worst = on_pad
                .iter()
                .enumerate()
                .filter(|&(p, drones)| !added[p] && !drones.is_empty())
                .map(|(p, drones)| (self.excess(drones, &node), p))
                .filter(|&(e, _)| e > tolerance)
                .max_by(|a, b| a.0.total_cmp(&b.0));
            let Some((_, p)) = worst else {
                return Ok(node);
            };
            added[p] = true;
            let (terms, rhs) = load_row(self.charges, self.makespan, &on_pad[p]);
            let mut child = node.into_owned();
            child.add_row(&terms, Sense::Le, rhs)?;
            node = Cow::Owned(child);
        }
    }

    fn dive(
        &mut self,
        node: &Tableau,
        depth: usize,
        on_pad: &mut Vec<Vec<usize>>,
    ) -> Result<(), DenseFailure> {
        let lp = node.objective();
        if depth == self.order.len() {
            if lp < self.ub {
                self.ub = lp;
                let mut pad_of = vec![0; self.charges.len()];
                for (p, drones) in on_pad.iter().enumerate() {
                    for &d in drones {
                        pad_of[d] = p;
                    }
                }
                self.leaf = Some((pad_of, node.clone()));
            }
            return Ok(());
        }
        let d = self.order[depth];
        // The pads used so far and the first empty one, least loaded first at this node's point.
        let used = on_pad.iter().filter(|p| !p.is_empty()).count();
        let mut children: Vec<(f64, usize)> = (0..(used + 1).min(self.pads))
            .map(|p| {
                let load: f64 = on_pad[p].iter().map(|&e| self.charges[e].at(node)).sum();
                (load, p)
            })
            .collect();
        children.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for (_, p) in children {
            if self.prunes(lp) {
                return Ok(());
            }
            if self.limit_reached() {
                self.stopped = true;
                self.open = self.open.min(lp);
                return Ok(());
            }
            self.nodes += 1;
            on_pad[p].push(d);
            let child = self.settle(node, on_pad)?;
            if !self.prunes(child.objective()) {
                self.dive(&child, depth + 1, on_pad)?;
            }
            on_pad[p].pop();
            if self.stopped {
                self.open = self.open.min(lp);
                return Ok(());
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::{configurations, Attempt, ContinuousOptions, Model, Pads, Solved};
    use crate::eaas::exact::{EndPads, Objective, Reorder};
    use crate::eaas::{DroneState, HopProblem, LegRates, Role};
    use nalgebra::Vector2;
    use rand::{Rng, SeedableRng};

    /// A random hop into a stop: 2-4 delivery and 1-2 support drones, every drone full at the
    /// start (as every hop of a plan leaves a stop), 1-3 legs of real rates, slots on a line
    /// 1 m apart (range 1.2 m).
    fn stop_hop(seed: u64) -> HopProblem {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let nd = rng.random_range(2..=4usize);
        let ns = rng.random_range(1..=2usize);
        let n = nd + ns;
        let legs = (0..rng.random_range(1..=3usize))
            .map(|_| LegRates {
                duration_min: rng.random_range(1.0..4.0),
                rate_mah_per_min: (0..n)
                    .map(|_| (0..n).map(|_| rng.random_range(4.0..12.0)).collect())
                    .collect::<Vec<_>>()
                    .into(),
            })
            .collect();
        let drones = (0..n)
            .map(|d| {
                let cap = if d < nd { 100.0 } else { 200.0 };
                DroneState {
                    role: if d < nd {
                        Role::Delivery
                    } else {
                        Role::Support
                    },
                    capacity_mah: cap,
                    battery_mah: cap,
                }
            })
            .collect();
        let mut initial_slot: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            initial_slot.swap(i, rng.random_range(0..=i));
        }
        HopProblem {
            legs,
            drones,
            slots_m: (0..n).map(|q| Vector2::new(q as f64, 0.0)).collect(),
            initial_slot,
            rho_mah_per_min: rng.random_range(2.0..10.0),
            range_m: 1.2,
            gamma_mah: 90.0,
            lambda_mah: 20.0,
            delta_mah: 0.0,
        }
    }

    /// The pad search from its root, no incumbent; `None` when the root does not solve.
    fn search_from_the_root(
        model: &Model<'_>,
        objective: &Objective,
        options: &ContinuousOptions,
        rank: &[usize],
    ) -> Option<super::super::Searched> {
        model.search_root(objective, options).map(|root| {
            root.search(options, rank, f64::INFINITY)
                .expect("the search runs")
        })
    }

    /// Every assignment of `n` drones to `k` pads, as the pad of each drone.
    fn assignments(n: usize, k: usize) -> Vec<Vec<usize>> {
        let mut all = vec![Vec::new()];
        for _ in 0..n {
            all = all
                .into_iter()
                .flat_map(|a| {
                    (0..k).map(move |p| {
                        let mut b = a.clone();
                        b.push(p);
                        b
                    })
                })
                .collect();
        }
        all
    }

    /// Brute force: the least value of the fixed-assignment LP over every assignment of `drones`
    /// drones to `pads` pads, each solved by the backend; infinite when none flies.
    fn brute_force(
        model: &Model<'_>,
        objective: &Objective,
        options: &ContinuousOptions,
        drones: usize,
        pads: usize,
    ) -> f64 {
        assignments(drones, pads)
            .iter()
            .filter_map(
                |a| match model.solve(objective, options, Attempt::exact(Pads::Fixed(a))) {
                    Ok(Solved::Values(v)) => Some(v.value),
                    _ => None,
                },
            )
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn the_pad_search_finds_the_least_lp_over_every_assignment() {
        let mut searched = 0;
        for seed in 0..60u64 {
            let p = stop_hop(seed);
            let pads = 2 + (seed % 2) as usize;
            let objective = Objective::NodeTime(EndPads {
                pads,
                pad_rate_mah_per_min: 7.0,
            });
            let configs = configurations(&p, Reorder::Paper, 20_000).unwrap();
            let model = Model::of(&p, &configs, Reorder::Paper);
            let options = ContinuousOptions::default();
            let brute = brute_force(&model, &objective, &options, p.drones.len(), pads);
            let rank: Vec<usize> = (0..p.drones.len()).collect();
            let s = search_from_the_root(&model, &objective, &options, &rank);
            if !brute.is_finite() {
                assert!(
                    s.is_none_or(|s| s.leaf.is_none()),
                    "seed {seed}: a leaf where no assignment flies"
                );
                continue;
            }
            let s = s.expect("the root of a hop that flies solves");
            assert!(s.complete, "seed {seed}");
            searched += 1;
            let tol = 1e-7 * (1.0 + brute.abs());
            assert!(
                (s.value - brute).abs() <= tol,
                "seed {seed}: search {} brute {brute}",
                s.value
            );
            assert!(
                s.bound <= brute + tol && s.bound >= brute - tol,
                "seed {seed}: bound {}",
                s.bound
            );
            let (pad_of, _) = s.leaf.expect("a leaf without an incumbent");
            let again =
                match model.solve(&objective, &options, Attempt::exact(Pads::Fixed(&pad_of))) {
                    Ok(Solved::Values(v)) => v.value,
                    _ => panic!("seed {seed}: the leaf's assignment does not solve"),
                };
            assert!(
                (again - brute).abs() <= tol,
                "seed {seed}: leaf {again} brute {brute}"
            );
        }
        assert!(searched >= 40, "only {searched} hops fly");
    }

    /// A pad's row the simplex keeps only within its own tolerance (relative to the row's
    /// right-hand side, which can exceed the search's) is not added again: the search once
    /// looped there, adding the same row forever (request r02859 of paper-195 on findings-195,
    /// a 3.8e-8 excess against a 2.9e-8 tolerance). A zero tolerance makes such rows common (a
    /// row at its bound evaluates a few ulps above it about half the time); the search still
    /// ends, adds at most one row per pad and node, and finds brute force's optimum.
    #[test]
    fn a_row_kept_only_within_the_simplexs_tolerance_is_added_once() {
        let mut searched = 0;
        for seed in 0..40u64 {
            let p = stop_hop(seed);
            let pads = 2 + (seed % 2) as usize;
            let objective = Objective::NodeTime(EndPads {
                pads,
                pad_rate_mah_per_min: 7.0,
            });
            let configs = configurations(&p, Reorder::Paper, 20_000).unwrap();
            let model = Model::of(&p, &configs, Reorder::Paper);
            let options = ContinuousOptions::default();
            let brute = brute_force(&model, &objective, &options, p.drones.len(), pads);
            let Some(root) = model.search_root(&objective, &options) else {
                continue;
            };
            if !brute.is_finite() {
                continue;
            }
            let order: Vec<usize> = (0..p.drones.len()).collect();
            let rows_at_root = root.tableau.rows();
            let end = super::search_settling_within(
                root.tableau.clone(),
                &root.charges,
                root.makespan,
                &order,
                root.pads,
                f64::INFINITY,
                (None, None),
                0.0,
            )
            .expect("the search runs");
            assert!(end.complete, "seed {seed}");
            let tol = 1e-7 * (1.0 + brute.abs());
            assert!(
                (end.value - brute).abs() <= tol,
                "seed {seed}: search {} brute {brute}",
                end.value
            );
            // A leaf holds the root's rows and at most one row per pad and drone placed.
            let (_, leaf) = end.leaf.expect("a leaf");
            assert!(
                leaf.rows() <= rows_at_root + pads * p.drones.len(),
                "seed {seed}: {} rows",
                leaf.rows()
            );
            searched += 1;
        }
        assert!(searched >= 25, "only {searched} hops fly");
    }

    #[test]
    fn a_search_stopped_by_its_node_limit_says_so_and_bounds_the_optimum() {
        let mut stopped = 0;
        for seed in 0..30u64 {
            let p = stop_hop(seed);
            let objective = Objective::NodeTime(EndPads {
                pads: 2,
                pad_rate_mah_per_min: 7.0,
            });
            let configs = configurations(&p, Reorder::Paper, 20_000).unwrap();
            let model = Model::of(&p, &configs, Reorder::Paper);
            let rank: Vec<usize> = (0..p.drones.len()).collect();
            let Some(full) =
                search_from_the_root(&model, &objective, &ContinuousOptions::default(), &rank)
            else {
                continue;
            };
            let limited = ContinuousOptions {
                node_limit: Some(2),
                ..ContinuousOptions::default()
            };
            let s = search_from_the_root(&model, &objective, &limited, &rank)
                .expect("the same root solves");
            if !full.value.is_finite() {
                continue;
            }
            // The stopped search's bound is a bound on the optimum the full search proves.
            assert!(
                s.bound <= full.value + 1e-7 * (1.0 + full.value),
                "seed {seed}"
            );
            assert!(
                s.value >= full.value - 1e-7 * (1.0 + full.value),
                "seed {seed}"
            );
            if !s.complete {
                stopped += 1;
                assert!(
                    s.bound < s.value,
                    "seed {seed}: a stopped search proved its value"
                );
            }
        }
        assert!(
            stopped >= 10,
            "only {stopped} searches needed more than 2 nodes"
        );
    }
}
