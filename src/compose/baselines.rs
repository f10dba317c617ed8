//! Fixed-route baselines: Dijkstra and Floyd–Warshall on edge cost `tt + nt`, then flown with
//! recharging only where the swarm must.
//!
//! The edge costs depend on the swarm (and the network, the profile and the node limit of the
//! planner), not on the sharing policy nor on the algorithm: [`BaselineCosts`] holds them for one
//! swarm, with the all-pairs result of Floyd–Warshall, so that the combinations of one request
//! that fly the same swarm compute them once ([`Planner::compose_with_baseline_costs`]).

use super::plan::{Plan, PlanOutcome};
use super::{FixedRoute, Planner};
use crate::eaas::exact_hop::HopGoal;
use crate::eaas::exact_hop::HopSolveCounts;
use crate::error::Result;
use crate::network::floyd_warshall::{floyd_warshall, AllPairs};
use crate::problem::Swarm;
use petgraph::graph::{DiGraph, NodeIndex};
use std::sync::OnceLock;

/// The baselines' edge costs `tt(u, v) + nt(v)` of one swarm, min, and the shortest paths on them.
#[derive(Debug, Clone)]
pub struct BaselineCosts {
    /// The swarm the costs were computed for.
    swarm: Swarm,
    /// Directed edges `(u, v, tt + nt)`, in the order of [`Planner::baseline_edge_costs_min`].
    edges_min: Vec<(usize, usize, f64)>,
    /// The same edges as a graph for Dijkstra.
    digraph: DiGraph<(), f64>,
    /// Floyd–Warshall's all-pairs shortest paths, computed on first use.
    all_pairs: OnceLock<AllPairs>,
}

impl BaselineCosts {
    /// The costs `edges_min` (directed edges `(u, v, tt + nt)`, finite and non-negative) of
    /// `swarm` on a network of `node_count` nodes.
    pub fn new(swarm: Swarm, node_count: usize, edges_min: Vec<(usize, usize, f64)>) -> Self {
        let mut digraph: DiGraph<(), f64> = DiGraph::with_capacity(node_count, edges_min.len());
        for _ in 0..node_count {
            digraph.add_node(());
        }
        for &(u, v, cost) in &edges_min {
            digraph.add_edge(NodeIndex::new(u), NodeIndex::new(v), cost);
        }
        BaselineCosts {
            swarm,
            edges_min,
            digraph,
            all_pairs: OnceLock::new(),
        }
    }

    /// The swarm the costs were computed for.
    pub fn swarm(&self) -> &Swarm {
        &self.swarm
    }

    /// Directed edges `(u, v, tt + nt)`, min.
    pub fn edges_min(&self) -> &[(usize, usize, f64)] {
        &self.edges_min
    }

    /// Floyd–Warshall's shortest paths between every pair of nodes on these costs, computed on the
    /// first call.
    ///
    /// # Complexity
    /// O(|V|^3) on the first call, O(1) after.
    pub fn all_pairs(&self) -> &AllPairs {
        self.all_pairs
            .get_or_init(|| floyd_warshall(self.digraph.node_count(), &self.edges_min))
    }

    /// The baseline route from `source` to `destination` on these costs: node indices, or `None`
    /// if unreachable.
    ///
    /// # Panics
    /// When a node index is outside the network.
    ///
    /// # Complexity
    /// Dijkstra: O(|E| log |V|). Floyd–Warshall: O(|V|^3) for the first route of this swarm
    /// (all pairs at once), O(|V|) for the others.
    pub fn route(
        &self,
        source: usize,
        destination: usize,
        algorithm: FixedRoute,
    ) -> Option<Vec<usize>> {
        match algorithm {
            FixedRoute::Dijkstra => {
                let (s, t) = (NodeIndex::new(source), NodeIndex::new(destination));
                let found =
                    petgraph::algo::astar(&self.digraph, s, |x| x == t, |e| *e.weight(), |_| 0.0);
                found.map(|(_, nodes)| nodes.into_iter().map(|x| x.index()).collect())
            }
            FixedRoute::FloydWarshall => self.all_pairs().path(source, destination),
        }
    }
}

impl Planner {
    /// Edge cost of the baselines, min, for every directed edge `(u, v)`: `tt(u, v) + nt(v)`, where
    /// `nt(v)` is the exact node time at `v` of a swarm that flew the edge from full batteries
    /// without sharing (0 where `v` has no pads). See models/compose.md for this reading of the
    /// paper's rule. The costs do not depend on the planner's sharing policy.
    ///
    /// The arrival batteries are those of [`Planner::fly`] with [`crate::eaas::SharingPolicy::None`] from full
    /// batteries, to the last digit, computed without building the hop problem (one leg, no
    /// transfer: `C_d - r_d τ`).
    ///
    /// # Errors
    /// Those of [`Planner::fly`] and [`Planner::stop_at`].
    ///
    /// # Complexity
    /// One exact node time per directed edge into a node with pads.
    pub fn baseline_edge_costs_min(&self) -> Result<Vec<(usize, usize, f64)>> {
        let graph = self.graph();
        let speed = self.speed_m_per_min();
        let mut costs = Vec::new();
        for u in 0..graph.node_count() {
            for &(v, _) in graph.neighbors(u) {
                let Some(leg) = graph.leg(u, v) else {
                    continue;
                };
                let nt = if graph.pads(v) == 0 {
                    0.0
                } else {
                    let arrival = self.arrival_without_sharing_mah(&leg)?;
                    match self.stop_at(v, &arrival)? {
                        Some(stop) => stop.nt_min,
                        None => 0.0,
                    }
                };
                // The path's length: the sum of its one leg.
                let distance_m: f64 = [leg.distance_m].iter().sum();
                costs.push((u, v, distance_m / speed + nt));
            }
        }
        Ok(costs)
    }

    /// [`Planner::baseline_edge_costs_min`] of this planner's swarm, ready for routing: pass them
    /// to [`Planner::compose_with_baseline_costs`] of every planner of the same graph, profile,
    /// swarm and node limit (whatever its sharing policy).
    ///
    /// # Errors
    /// Those of [`Planner::baseline_edge_costs_min`].
    ///
    /// # Complexity
    /// That of [`Planner::baseline_edge_costs_min`].
    pub fn baseline_costs(&self) -> Result<BaselineCosts> {
        Ok(BaselineCosts::new(
            self.swarm().clone(),
            self.graph().node_count(),
            self.baseline_edge_costs_min()?,
        ))
    }

    /// The baseline route from `source` to `destination`: node indices, or `None` if unreachable.
    ///
    /// # Errors
    /// Those of [`Planner::baseline_edge_costs_min`].
    ///
    /// # Complexity
    /// That of [`Planner::baseline_edge_costs_min`], then of [`BaselineCosts::route`].
    pub fn baseline_route(
        &self,
        source: usize,
        destination: usize,
        algorithm: FixedRoute,
    ) -> Result<Option<Vec<usize>>> {
        Ok(self.baseline_costs()?.route(source, destination, algorithm))
    }

    /// Dijkstra / Floyd–Warshall baseline: compute the route, then fly it, stopping at a pad node
    /// on it only when the next pad node (or the destination) cannot be reached without stopping;
    /// fail when even the next pad node cannot be reached. `costs`: the baseline costs of this
    /// planner's swarm, computed here when `None`.
    pub(crate) fn compose_fixed_route(
        &self,
        source: usize,
        destination: usize,
        algorithm: FixedRoute,
        costs: Option<&BaselineCosts>,
        solves: &mut HopSolveCounts,
    ) -> Result<Plan> {
        let graph = self.graph();
        let mut plan = self.empty_plan(source, destination);
        if source == destination {
            return Ok(plan.finish());
        }
        let route = match costs {
            Some(costs) => costs.route(source, destination, algorithm),
            None => self.baseline_route(source, destination, algorithm)?,
        };
        let Some(route) = route else {
            return Ok(plan.fail(PlanOutcome::NoRoute {
                from: graph.id_of(source).to_string(),
                to: graph.id_of(destination).to_string(),
            }));
        };
        let last = route.len() - 1;
        let mut at = 0;
        let mut battery = self.full_battery_mah();
        while at < last {
            // The farthest pad node (or the destination) on the route reachable without stopping.
            let mut reached = None;
            // The first failure of the first hop that does not fly.
            let mut failure = None;
            for j in at + 1..=last {
                if j != last && graph.pads(route[j]) == 0 {
                    continue;
                }
                let path = graph
                    .path_from_nodes(&route[at..=j])
                    .expect("the route follows network edges");
                // Reachability only: the hop's schedule is optimised once j is chosen.
                let flight =
                    self.fly_counted(&path, &battery, self.sharing(), HopGoal::Feasible, solves)?;
                if !flight.outcome.feasible {
                    failure = flight.outcome.failure;
                    break;
                }
                reached = Some((j, path, flight));
            }
            let Some((j, path, flight)) = reached else {
                let next = (at + 1..=last)
                    .find(|&j| j == last || graph.pads(route[j]) > 0)
                    .expect("the destination is on the route");
                return Ok(plan.fail(PlanOutcome::HopInfeasible {
                    from: graph.id_of(route[at]).to_string(),
                    to: graph.id_of(route[next]).to_string(),
                    failure: failure.expect("an infeasible hop reports its first failure"),
                }));
            };
            if j == last {
                plan.push(self.hop(&path, &battery, flight, None));
                return Ok(plan.finish());
            }
            let flight = if self.sharing().is_exact() {
                // The least node time at the chosen stop (the exact schedule) or the fair one.
                let at_stop = self.fly_counted(
                    &path,
                    &battery,
                    self.sharing(),
                    HopGoal::NodeTimeMin,
                    solves,
                )?;
                if at_stop.outcome.feasible {
                    at_stop
                } else {
                    flight
                }
            } else {
                flight
            };
            let stop = self.stop_at(route[j], &flight.outcome.final_battery_mah)?;
            plan.push(self.hop(&path, &battery, flight, stop));
            battery = self.full_battery_mah();
            at = j;
        }
        Ok(plan.finish())
    }
}
