//! Algorithm 1 of the paper (sequential composition) and its A*-style variant.

use super::plan::Plan;
use super::Planner;
use crate::eaas::SharingPolicy;
use crate::error::Result;

impl Planner<'_> {
    /// Algorithm 1. From the current node: fly straight to the destination if every drone can
    /// without sharing; else straight with sharing if that makes it; else fly (with sharing) to the
    /// recharging node, not yet stopped at, reachable without stopping, with the least `tt + nt`
    /// (plus, with `astar`, the remaining shortest-path travel time to the destination), recharge
    /// there, and repeat. Stopped-at nodes are never candidates again, so the loop ends after at
    /// most one step per recharging node: a request with no candidate left fails (dead end).
    pub(crate) fn compose_sequential(
        &self,
        source: usize,
        destination: usize,
        astar: bool,
    ) -> Result<Plan> {
        let graph = self.graph();
        let speed = self.speed_m_per_min();
        let mut plan = self.empty_plan(source, destination);
        if source == destination {
            return Ok(plan.finish());
        }
        let to_destination_m = graph.distances_from_m(destination);
        let mut stopped = vec![false; graph.node_count()];
        stopped[source] = true;
        let mut min_rates: Option<Vec<f64>> = None;
        let mut current = source;
        let mut battery = self.full_battery_mah();
        loop {
            let Some(direct) = graph.shortest_path(current, destination) else {
                return Ok(plan.fail(format!(
                    "destination {} is not connected to {}",
                    graph.id_of(destination),
                    graph.id_of(current)
                )));
            };
            // Lines 5-7: every drone reaches the destination on its own battery.
            let outcome = self.fly(&direct, &battery, SharingPolicy::None)?;
            if outcome.feasible {
                plan.push(self.hop(&direct, &battery, outcome, None));
                return Ok(plan.finish());
            }
            // Lines 8-10: in-flight sharing makes the direct flight possible.
            if self.sharing().shares() {
                let outcome = self.fly(&direct, &battery, self.sharing())?;
                if outcome.feasible {
                    plan.push(self.hop(&direct, &battery, outcome, None));
                    return Ok(plan.finish());
                }
            }
            // Lines 12-16: the best recharging node reachable without stopping.
            let min_rates = min_rates.get_or_insert_with(|| self.min_rates_mah_per_min());
            let endurance_min = self.endurance_bound_min(&battery, min_rates);
            // Shortest paths v -> current, flown reversed: one Dijkstra for all candidates.
            let towards_current = graph.shortest_paths_to(current);
            let mut best = None;
            let mut best_cost = f64::INFINITY;
            for v in 0..graph.node_count() {
                if stopped[v] || graph.pads(v) == 0 || v == destination {
                    continue;
                }
                // A NaN or infinite distance (unreachable) is skipped too.
                if towards_current.distance_m[v] / speed > endurance_min
                    || !towards_current.distance_m[v].is_finite()
                {
                    continue;
                }
                let Some(path) = towards_current.path_from(v).and_then(|p| {
                    let reversed: Vec<usize> = p.nodes.into_iter().rev().collect();
                    graph.path_from_nodes(&reversed)
                }) else {
                    continue;
                };
                let outcome = self.fly(&path, &battery, self.sharing())?;
                if !outcome.feasible {
                    continue;
                }
                let stop = self
                    .stop_at(v, &outcome.final_battery_mah)?
                    .expect("candidates have pads");
                let mut cost = path.distance_m / speed + stop.nt_min;
                if astar {
                    cost += to_destination_m[v] / speed;
                }
                // Strict improvement keeps the lowest node index among equal costs.
                if cost < best_cost {
                    best_cost = cost;
                    best = Some((v, path, outcome, stop));
                }
            }
            let Some((v, path, outcome, stop)) = best else {
                return Ok(plan.fail(format!(
                    "dead end at {}: neither the destination nor any recharging node not yet \
                     stopped at is reachable without stopping",
                    graph.id_of(current)
                )));
            };
            plan.push(self.hop(&path, &battery, outcome, Some(stop)));
            stopped[v] = true;
            current = v;
            battery = self.full_battery_mah();
        }
    }
}
