//! Fixed-route baselines: Dijkstra and Floyd–Warshall on edge cost `tt + nt`, then flown with
//! recharging only where the swarm must.

use super::plan::{Plan, PlanOutcome};
use super::{FixedRoute, HopEnd, Planner};
use crate::eaas::SharingPolicy;
use crate::error::Result;
use petgraph::graph::{DiGraph, NodeIndex};

impl Planner<'_> {
    /// Edge cost of the baselines, min, for every directed edge `(u, v)`: `tt(u, v) + nt(v)`, where
    /// `nt(v)` is the exact node time at `v` of a swarm that flew the edge from full batteries
    /// without sharing (0 where `v` has no pads). See models/compose.md for this reading of the
    /// paper's rule.
    pub fn baseline_edge_costs_min(&self) -> Result<Vec<(usize, usize, f64)>> {
        let graph = self.graph();
        let speed = self.speed_m_per_min();
        let full = self.full_battery_mah();
        let mut costs = Vec::new();
        for u in 0..graph.node_count() {
            for &(v, _) in graph.neighbors(u) {
                let Some(path) = graph.path_from_nodes(&[u, v]) else {
                    continue;
                };
                let flight = self.fly(&path, &full, SharingPolicy::None, HopEnd::Stop)?;
                let nt = match self.stop_at(v, &flight.outcome.final_battery_mah)? {
                    Some(stop) => stop.nt_min,
                    None => 0.0,
                };
                costs.push((u, v, path.distance_m / speed + nt));
            }
        }
        Ok(costs)
    }

    /// The baseline route from `source` to `destination`: node indices, or `None` if unreachable.
    pub fn baseline_route(
        &self,
        source: usize,
        destination: usize,
        algorithm: FixedRoute,
    ) -> Result<Option<Vec<usize>>> {
        let n = self.graph().node_count();
        let mut digraph: DiGraph<(), f64> = DiGraph::with_capacity(n, 0);
        for _ in 0..n {
            digraph.add_node(());
        }
        for (u, v, cost) in self.baseline_edge_costs_min()? {
            digraph.add_edge(NodeIndex::new(u), NodeIndex::new(v), cost);
        }
        let (s, t) = (NodeIndex::new(source), NodeIndex::new(destination));
        if algorithm == FixedRoute::Dijkstra {
            let found = petgraph::algo::astar(&digraph, s, |x| x == t, |e| *e.weight(), |_| 0.0);
            return Ok(found.map(|(_, nodes)| nodes.into_iter().map(|x| x.index()).collect()));
        }
        let (_, prev) =
            petgraph::algo::floyd_warshall::floyd_warshall_path(&digraph, |e| *e.weight())
                .expect("edge costs are non-negative, so there is no negative cycle");
        // prev[s][t] is the node before t on the shortest s-t path.
        let mut route = vec![destination];
        let mut at = destination;
        while at != source {
            match prev[source][at] {
                Some(p) if route.len() <= n => {
                    route.push(p);
                    at = p;
                }
                _ => return Ok(None),
            }
        }
        route.reverse();
        Ok(Some(route))
    }

    /// Dijkstra / Floyd–Warshall baseline: compute the route, then fly it, stopping at a pad node
    /// on it only when the next pad node (or the destination) cannot be reached without stopping;
    /// fail when even the next pad node cannot be reached.
    pub(crate) fn compose_fixed_route(
        &self,
        source: usize,
        destination: usize,
        algorithm: FixedRoute,
    ) -> Result<Plan> {
        let graph = self.graph();
        let mut plan = self.empty_plan(source, destination);
        if source == destination {
            return Ok(plan.finish());
        }
        let Some(route) = self.baseline_route(source, destination, algorithm)? else {
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
                let flight = self.fly(&path, &battery, self.sharing(), HopEnd::NoStop)?;
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
                let at_stop = self.fly(&path, &battery, self.sharing(), HopEnd::Stop)?;
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
