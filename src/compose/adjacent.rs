//! Algorithm 1 with the literal candidates of lines 12-14: "find nearest neighbor nodes ... select
//! best neighboring node, min(tt + ct) ... S travels to neighboring node" (`[readings] candidates =
//! "adjacent"`, see models/compose.md).

use super::plan::{Plan, PlanOutcome};
use super::{LookAhead, Planner};
use crate::eaas::exact_hop::HopGoal;
use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::SharingPolicy;
use crate::error::Result;
use crate::problem::Candidates;

impl Planner {
    /// Algorithm 1 over adjacent nodes. From the current node: fly to the destination along the
    /// shortest path if the swarm can without stopping (without, then with sharing, lines 5-10);
    /// else move to the best neighbour `v` in the skyway network not yet visited, least
    /// `tt(u, v) + nt(v)` (plus the remaining shortest-path travel time with [`LookAhead::RemainingTravelTime`]). A
    /// neighbour with pads is a stop: the swarm recharges there (`nt(v)` the exact node time) and
    /// the next hop starts full. A neighbour without pads is passed without charging (`nt = 0`):
    /// the hop goes on, and every flight test re-flies the hop from its last stop so the sharing
    /// window is the whole hop, as for every other method. Visited nodes are never candidates
    /// again, so the walk ends: a request with no reachable unvisited neighbour fails.
    pub(crate) fn compose_adjacent(
        &self,
        source: usize,
        destination: usize,
        look_ahead: LookAhead,
        solves: &mut HopSolveCounts,
    ) -> Result<Plan> {
        let graph = self.graph();
        let speed = self.speed_m_per_min();
        let mut plan = self.empty_plan(source, destination);
        if source == destination {
            return Ok(plan.finish());
        }
        let to_destination_m = graph.distances_from_m(destination);
        let full = self.full_battery_mah();
        let mut visited = vec![false; graph.node_count()];
        visited[source] = true;
        // Nodes of the hop flown so far, from its last stop (or the source) to the current node.
        let mut hop_nodes = vec![source];
        loop {
            let current = *hop_nodes.last().expect("a hop has a start");
            let Some(direct) = graph.shortest_path(current, destination) else {
                return Ok(plan.fail(PlanOutcome::NoRoute {
                    from: graph.id_of(current).to_string(),
                    to: graph.id_of(destination).to_string(),
                }));
            };
            let extended: Vec<usize> = hop_nodes
                .iter()
                .copied()
                .chain(direct.nodes.iter().skip(1).copied())
                .collect();
            let path = graph
                .path_from_nodes(&extended)
                .expect("the hop and the shortest path follow network edges");
            // Lines 5-10: the destination without stopping, without then with sharing.
            let mut policies = vec![SharingPolicy::None];
            if self.sharing().shares() {
                policies.push(self.sharing());
            }
            let mut direct_failure = None;
            for policy in policies {
                let flight = self.fly_counted(&path, &full, policy, HopGoal::Feasible, solves)?;
                if flight.outcome.feasible {
                    plan.push(self.hop(&path, &full, flight, None));
                    return Ok(plan.finish());
                }
                direct_failure = flight.outcome.failure;
            }
            // Lines 12-16: the best neighbour not yet visited.
            let mut best = None;
            let mut best_cost = f64::INFINITY;
            for &(v, _) in graph.neighbors(current) {
                if visited[v] {
                    continue;
                }
                let mut nodes = hop_nodes.clone();
                nodes.push(v);
                let Some(path) = graph.path_from_nodes(&nodes) else {
                    continue;
                };
                let goal = if v != destination && graph.pads(v) > 0 {
                    HopGoal::NodeTimeMin
                } else {
                    HopGoal::Feasible
                };
                let flight = self.fly_counted(&path, &full, self.sharing(), goal, solves)?;
                if !flight.outcome.feasible {
                    continue;
                }
                let stop = if v == destination {
                    None
                } else {
                    self.stop_at(v, &flight.outcome.final_battery_mah)?
                };
                let tt_min = graph.leg(current, v).map_or(0.0, |l| l.distance_m) / speed;
                let mut cost = tt_min + stop.as_ref().map_or(0.0, |s| s.nt_min);
                if look_ahead == LookAhead::RemainingTravelTime {
                    cost += to_destination_m[v] / speed;
                }
                // Strict improvement keeps the lowest node index among equal costs.
                if cost < best_cost {
                    best_cost = cost;
                    best = Some((v, nodes, path, flight, stop));
                }
            }
            let Some((v, nodes, path, flight, stop)) = best else {
                return Ok(plan.fail(PlanOutcome::DeadEnd {
                    node: graph.id_of(current).to_string(),
                    candidates: Candidates::Adjacent,
                    direct: direct_failure.expect("an infeasible hop reports its first failure"),
                }));
            };
            visited[v] = true;
            if v == destination {
                plan.push(self.hop(&path, &full, flight, None));
                return Ok(plan.finish());
            }
            if stop.is_some() {
                plan.push(self.hop(&path, &full, flight, stop));
                hop_nodes = vec![v];
            } else {
                hop_nodes = nodes;
            }
        }
    }
}
