//! The optimal route over stop sequences and hop paths, without in-flight sharing
//! (`--route optimal --hop-paths any`): Dijkstra on the stop graph, each arc `u -> v` the best
//! of every path from `u` to `v` the swarm can fly from full batteries, found by a
//! resource-constrained shortest-path search from `u`. See models/compose.md, "Optimal route",
//! "Any hop path".

use super::optimal::{improves, least_unsettled, relax, BestArc, Start};
use super::plan::{Plan, PlanOutcome, RouteOptimality};
use super::{HopPaths, Planner};
use crate::eaas::exact_hop::HopGoal;
use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::{SharingPolicy, ENERGY_TOL_MAH};
use crate::error::{Error, Result};
use crate::solver::SolveStatus;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Most labels one search of hop paths (from one stop) may create; above it `--hop-paths any`
/// is refused with E0017. About 40 bytes plus 8 per drone each: 200,000 labels of a 10-drone
/// swarm take about 24 MB.
pub const MAX_HOP_PATH_LABELS: usize = 200_000;

/// Relative margin by which a lower bound is lowered before it prunes (as Algorithm 1's
/// candidate bounds): far above the rounding of the sums behind it.
const BOUND_MARGIN: f64 = 1e-9;

/// A path from the search's origin: where it ends, when, every drone's battery there, and the
/// label it extends.
struct Label {
    node: usize,
    time_min: f64,
    battery_mah: Vec<f64>,
    parent: Option<usize>,
    /// Whether no later label dominates it.
    alive: bool,
}

impl Label {
    /// Whether this label dominates a path reaching the same node at `time_min` with
    /// `battery_mah`: no slower, and no drone with less energy.
    fn dominates(&self, time_min: f64, battery_mah: &[f64]) -> bool {
        self.time_min <= time_min
            && self
                .battery_mah
                .iter()
                .zip(battery_mah)
                .all(|(a, b)| a >= b)
    }
}

/// The Pareto fronts of one search: every label created, and the alive ones at each node.
struct HopPathSearch {
    labels: Vec<Label>,
    front: Vec<Vec<usize>>,
}

impl HopPathSearch {
    /// The nodes of label `l`'s path, from the origin.
    fn nodes(&self, mut l: usize) -> Vec<usize> {
        let mut nodes = vec![self.labels[l].node];
        while let Some(p) = self.labels[l].parent {
            nodes.push(self.labels[p].node);
            l = p;
        }
        nodes.reverse();
        nodes
    }
}

/// Dijkstra on the stop graph from `source` to `destination`: each node's least cost found, the
/// best arc into it, and whether it is settled.
struct StopDijkstra {
    source: usize,
    destination: usize,
    cost_min: Vec<f64>,
    best: Vec<Option<BestArc>>,
    settled: Vec<bool>,
}

impl StopDijkstra {
    /// Nothing settled on `n` nodes, the source at cost 0.
    fn new(n: usize, source: usize, destination: usize) -> Self {
        let mut cost_min = vec![f64::INFINITY; n];
        cost_min[source] = 0.0;
        StopDijkstra {
            source,
            destination,
            cost_min,
            best: (0..n).map(|_| None).collect(),
            settled: vec![false; n],
        }
    }
}

/// A label waiting in the search's queue, the earliest first, then the lowest index.
#[derive(PartialEq)]
struct Queued {
    time_min: f64,
    label: usize,
}

impl Eq for Queued {}

impl Ord for Queued {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed: BinaryHeap pops the greatest.
        other
            .time_min
            .total_cmp(&self.time_min)
            .then(other.label.cmp(&self.label))
    }
}

impl PartialOrd for Queued {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// The coded error of `--hop-paths any` with a policy that shares energy in flight.
pub(crate) fn any_path_with_sharing(sharing: SharingPolicy) -> Error {
    Error::invalid(
        "E0016",
        "--hop-paths any",
        format!(
            "--hop-paths any searches hop paths without in-flight sharing (policies none and \
             idle-support) or with the exact schedules (exact), not under {sharing}'s \
             simulated sharing"
        ),
        format!(
            "use --hop-paths any with --sharing none, idle-support or exact, or --hop-paths \
             rule with --sharing {sharing}"
        ),
    )
}

/// The coded error of a search of hop paths above [`MAX_HOP_PATH_LABELS`].
fn too_many_labels(from: &str) -> Error {
    Error::invalid(
        "E0017",
        "--hop-paths any",
        format!(
            "the search of hop paths from {from} needs more than {MAX_HOP_PATH_LABELS} labels \
             (paths not dominated in time and in every drone's battery)"
        ),
        "use --hop-paths rule on this network, or a network with fewer nodes or a swarm with \
         fewer drones",
    )
}

impl Planner {
    /// The least delivery time over every sequence of stops and every path of each hop, without
    /// in-flight sharing: [`Planner::compose_optimal`] with the arcs of the stop graph taken over
    /// all flyable paths instead of the shortest one.
    ///
    /// When a stop `u` is settled, one search from `u` with full batteries builds, at every
    /// node, the Pareto front of the flyable paths from `u`: labels `(node, time, battery of
    /// each drone)`, extended one edge at a time in order of time, a label dropped when a drone's
    /// battery falls below zero (the hop evaluation's rule) or another label at its node is no
    /// slower with no drone holding less energy. The arc into the destination is the fastest
    /// label there; the arc into a node `v` with pads is the label of least `tt + nt(v)` (node
    /// time of its arrival batteries): the node time falls as any battery rises, so a dominated
    /// label never gives a smaller cost. The arc chosen is flown again by [`Planner::fly`], whose
    /// flight and stop make the plan.
    ///
    /// # Returns
    /// As [`Planner::compose_optimal`], with `route_optimality.hop_paths` = `any`.
    ///
    /// # Errors
    /// E0016 for a policy that shares in flight (the exact one goes to the joint optimum,
    /// [`Planner::compose_joint`]); E0017 when a
    /// search creates more than [`MAX_HOP_PATH_LABELS`] labels; else those of
    /// [`Planner::fly`] and [`Planner::stop_at`].
    ///
    /// # Complexity
    /// One search per settled stop, each O(L (deg + F n)) for L labels, F the largest front at
    /// a node and n drones (plus O(L log L) for the queue); L is at most
    /// [`MAX_HOP_PATH_LABELS`]. One exact node time per front label not pruned by the energy
    /// bound, and one hop simulation per improving arc.
    pub(crate) fn compose_optimal_any_path(
        &self,
        source: usize,
        destination: usize,
        solves: &mut HopSolveCounts,
    ) -> Result<Plan> {
        if self.sharing().shares() || self.sharing().is_exact() {
            return Err(any_path_with_sharing(self.sharing()));
        }
        let graph = self.graph();
        let mut optimality = RouteOptimality {
            hop_paths: HopPaths::Any,
            ..RouteOptimality::default()
        };
        let (mut plan, direct) =
            match self.start_search(source, destination, &mut optimality, false, solves)? {
                Start::Done(plan) => return Ok(plan),
                Start::Search { plan, direct, .. } => (plan, direct),
            };
        let full = self.full_battery_mah();
        let mut dijkstra = StopDijkstra::new(graph.node_count(), source, destination);
        let Some(best) = self.settle_any_path(&mut dijkstra, &full, &mut optimality, solves)?
        else {
            // The shortest path does not fly (else the search would have reached the
            // destination): its first failure.
            let flight = self.fly_counted(
                &direct,
                &full,
                SharingPolicy::None,
                HopGoal::Feasible,
                solves,
            )?;
            plan.route_optimality = Some(optimality);
            return Ok(plan.fail(PlanOutcome::NoStopSequence {
                from: graph.id_of(source).to_string(),
                to: graph.id_of(destination).to_string(),
                stops_reached: dijkstra.settled.iter().filter(|&&s| s).count() - 1,
                direct: flight
                    .outcome
                    .failure
                    .expect("the shortest path to the destination does not fly"),
            }));
        };
        Ok(self.route_of(plan, best, source, destination, optimality))
    }

    /// Dijkstra on the stop graph, the arcs out of each stop settled given by one search of hop
    /// paths from it: the best arc into every node when the destination is settled; `None` when
    /// it is out of reach.
    fn settle_any_path(
        &self,
        dijkstra: &mut StopDijkstra,
        full: &[f64],
        optimality: &mut RouteOptimality,
        solves: &mut HopSolveCounts,
    ) -> Result<Option<Vec<Option<BestArc>>>> {
        let graph = self.graph();
        let (source, destination) = (dijkstra.source, dijkstra.destination);
        let mut uses: Vec<Option<Vec<f64>>> = vec![None; 2 * graph.edge_count()];
        loop {
            let Some(u) = least_unsettled(&dijkstra.cost_min, &dijkstra.settled) else {
                return Ok(None);
            };
            dijkstra.settled[u] = true;
            if u == destination {
                return Ok(Some(std::mem::take(&mut dijkstra.best)));
            }
            optimality.stops_settled += usize::from(u != source);
            // No label slower than the destination's cost improves anything (nt >= 0).
            let horizon_min =
                (dijkstra.cost_min[destination] - dijkstra.cost_min[u]) * (1.0 + BOUND_MARGIN);
            let search = self.search_hop_paths(u, full, horizon_min, &mut uses)?;
            optimality.hop_path_labels += search.labels.len();
            self.fastest_into_destination(dijkstra, &search, u, full, optimality, solves)?;
            for v in 0..graph.node_count() {
                if dijkstra.settled[v] || v == destination || graph.pads(v) == 0 {
                    continue;
                }
                self.least_label_into_stop(dijkstra, &search, (u, v), full, optimality, solves)?;
            }
        }
    }

    /// The arc from the settled stop `u` into the destination: the fastest label of `search`
    /// there, flown without sharing, kept when it flies and improves the destination's cost.
    fn fastest_into_destination(
        &self,
        dijkstra: &mut StopDijkstra,
        search: &HopPathSearch,
        u: usize,
        full: &[f64],
        optimality: &mut RouteOptimality,
        solves: &mut HopSolveCounts,
    ) -> Result<()> {
        let destination = dijkstra.destination;
        let fastest = search.front[destination].iter().copied().min_by(|&a, &b| {
            let (la, lb) = (&search.labels[a], &search.labels[b]);
            la.time_min.total_cmp(&lb.time_min).then(a.cmp(&b))
        });
        let Some(l) = fastest else {
            return Ok(());
        };
        let path = self
            .graph()
            .path_from_nodes(&search.nodes(l))
            .expect("labels follow network edges");
        let cost = dijkstra.cost_min[u] + path.distance_m / self.speed_m_per_min();
        if improves(
            cost,
            u,
            dijkstra.cost_min[destination],
            &dijkstra.best[destination],
        ) {
            let flight =
                self.fly_counted(&path, full, SharingPolicy::None, HopGoal::Feasible, solves)?;
            optimality.arcs_flown += 1;
            if flight.outcome.feasible {
                dijkstra.cost_min[destination] = cost;
                dijkstra.best[destination] = Some(BestArc {
                    from: u,
                    path,
                    flight,
                    stop: None,
                    epsilon_min: 0.0,
                });
            }
        }
        Ok(())
    }

    /// The arc from the settled stop `u` into the unsettled node `v` with pads: the label of
    /// `search` at `v` of least `tt + nt` (each label in order of time, skipped when its energy
    /// bound cannot improve `v`, the destination or the labels before it), flown and relaxed.
    fn least_label_into_stop(
        &self,
        dijkstra: &mut StopDijkstra,
        search: &HopPathSearch,
        (u, v): (usize, usize),
        full: &[f64],
        optimality: &mut RouteOptimality,
        solves: &mut HopSolveCounts,
    ) -> Result<()> {
        let cost_min = &dijkstra.cost_min;
        let destination = dijkstra.destination;
        let mut front = search.front[v].clone();
        front.sort_by(|&a, &b| {
            let (la, lb) = (&search.labels[a], &search.labels[b]);
            la.time_min.total_cmp(&lb.time_min).then(a.cmp(&b))
        });
        let mut chosen: Option<(f64, usize)> = None;
        for l in front {
            let label = &search.labels[l];
            let limit = cost_min[v]
                .min(cost_min[destination])
                .min(chosen.map_or(f64::INFINITY, |c| c.0));
            let bound = cost_min[u] + label.time_min + self.nt_bound_min(v, &label.battery_mah);
            if bound * (1.0 - BOUND_MARGIN) > limit {
                continue;
            }
            let stop = self
                .stop_at(v, &label.battery_mah)?
                .expect("the node has pads");
            optimality.stops_solved += 1;
            if stop.status != SolveStatus::Optimal {
                optimality.stops_unproven += 1;
            }
            let cost = cost_min[u] + label.time_min + stop.nt_min;
            if chosen.is_none_or(|c| cost < c.0) {
                chosen = Some((cost, l));
            }
        }
        let Some((_, l)) = chosen else {
            return Ok(());
        };
        let path = self
            .graph()
            .path_from_nodes(&search.nodes(l))
            .expect("labels follow network edges");
        let arc = self.arc_into_stop(u, v, path, full, optimality, solves)?;
        let tail_cost_min = dijkstra.cost_min[u];
        let speed = self.speed_m_per_min();
        relax(
            &mut dijkstra.cost_min,
            &mut dijkstra.best,
            v,
            tail_cost_min,
            speed,
            arc,
        );
        Ok(())
    }

    /// A lower bound on the node time at `v` (with pads) of a swarm arriving with
    /// `battery_mah`: the longest charge time, and the total charge time over the pads.
    fn nt_bound_min(&self, v: usize, battery_mah: &[f64]) -> f64 {
        let rate = self.pad_rate_mah_per_min(v);
        let pads = f64::from(self.graph().pads(v));
        let (mut total, mut longest) = (0.0_f64, 0.0_f64);
        for (d, &b) in self.swarm().drones.iter().zip(battery_mah) {
            let ct = (d.capacity_mah - b).max(0.0) / rate;
            total += ct;
            longest = longest.max(ct);
        }
        longest.max(total / pads)
    }

    /// The Pareto fronts of the paths from `origin` flyable without sharing from batteries
    /// `full`, no longer than `horizon_min`; `uses` caches each directed edge's consumption.
    ///
    /// # Errors
    /// E0017 above [`MAX_HOP_PATH_LABELS`] labels; those of
    /// [`Planner::leg_use_without_sharing_mah`].
    fn search_hop_paths(
        &self,
        origin: usize,
        full: &[f64],
        horizon_min: f64,
        uses: &mut [Option<Vec<f64>>],
    ) -> Result<HopPathSearch> {
        let graph = self.graph();
        let speed = self.speed_m_per_min();
        let mut search = HopPathSearch {
            labels: vec![Label {
                node: origin,
                time_min: 0.0,
                battery_mah: full.to_vec(),
                parent: None,
                alive: true,
            }],
            front: vec![Vec::new(); graph.node_count()],
        };
        search.front[origin].push(0);
        let mut queue = BinaryHeap::new();
        queue.push(Queued {
            time_min: 0.0,
            label: 0,
        });
        while let Some(Queued { label, .. }) = queue.pop() {
            if !search.labels[label].alive {
                continue;
            }
            let x = search.labels[label].node;
            for &(y, _) in graph.neighbors(x) {
                let Some(leg) = graph.leg(x, y) else {
                    continue;
                };
                let time_min = search.labels[label].time_min + leg.distance_m / speed;
                if time_min > horizon_min {
                    continue;
                }
                let key = 2 * leg.edge + usize::from(leg.from < leg.to);
                if uses[key].is_none() {
                    uses[key] = Some(self.leg_use_without_sharing_mah(&leg)?);
                }
                let use_mah = uses[key].as_ref().expect("filled above");
                let battery_mah: Vec<f64> = search.labels[label]
                    .battery_mah
                    .iter()
                    .zip(use_mah)
                    .map(|(b, u)| b - u)
                    .collect();
                if battery_mah.iter().any(|&b| b < -ENERGY_TOL_MAH) {
                    continue;
                }
                let labels = &mut search.labels;
                if search.front[y]
                    .iter()
                    .any(|&m| labels[m].dominates(time_min, &battery_mah))
                {
                    continue;
                }
                search.front[y].retain(|&m| {
                    let other = &mut labels[m];
                    let dominated = time_min <= other.time_min
                        && battery_mah
                            .iter()
                            .zip(&other.battery_mah)
                            .all(|(a, b)| a >= b);
                    if dominated {
                        other.alive = false;
                    }
                    !dominated
                });
                if labels.len() >= MAX_HOP_PATH_LABELS {
                    return Err(too_many_labels(graph.id_of(origin)));
                }
                labels.push(Label {
                    node: y,
                    time_min,
                    battery_mah,
                    parent: Some(label),
                    alive: true,
                });
                search.front[y].push(labels.len() - 1);
                queue.push(Queued {
                    time_min,
                    label: labels.len() - 1,
                });
            }
        }
        Ok(search)
    }
}
