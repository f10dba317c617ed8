//! Algorithm 1 of the paper (sequential composition) and its A*-style variant.

use super::plan::{Plan, PlanOutcome};
use super::{Flight, LookAhead, Planner, Stop};
use crate::eaas::exact::EndPads;
use crate::eaas::exact::Objective;
use crate::eaas::exact::{fluid, ExactStatus};
use crate::eaas::exact_hop::HopGoal;
use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::{HopFailure, SharingPolicy};
use crate::error::Result;
use crate::network::{Route, ShortestPathsTo};
use crate::problem::Candidates;

/// Relative tolerance, on minutes, of pruning a candidate by its lower bound: a bound computed
/// in floating point may sit slightly above the true value, so a candidate is pruned only when
/// its bound exceeds the best cost by more than this fraction.
const PRUNE_TOL_MIN: f64 = 1e-6;

/// Relative margin by which the energy bound on a candidate's cost is lowered: far above the
/// rounding of the sums behind the bound and the cost (about 1e-15 relative each), far below
/// the gap between the bound and the cost it bounds.
const BOUND_MARGIN: f64 = 1e-9;

/// A candidate stop: node, hop path, A* look-ahead (min), lower bound on its cost (min).
type Candidate = (usize, Route, f64, f64);

/// A candidate stop whose hop path is built only when its turn comes under the simulated
/// policies: node, hop path (when built), A* look-ahead (min), lower bound on its cost (min).
type LazyCandidate = (usize, Option<Route>, f64, f64);

/// Algorithm 1's request: its destination, the look-ahead, every node's distance to the
/// destination, and the nodes stopped at so far (the source among them).
struct SequentialRequest {
    destination: usize,
    look_ahead: LookAhead,
    to_destination_m: Vec<f64>,
    stopped: Vec<bool>,
}

impl Planner {
    /// Exact and fair policies: every candidate with a lower bound on its cost `tt + nt + look-
    /// ahead`, `nt` bounded by the fluid LP of `models/eaas_fluid.md` (valid for every
    /// continuous-time schedule, so for every grid schedule and the fair layout), sorted by bound
    /// then node; candidates the LP proves unflyable are dropped.
    fn bounded_candidates(
        &self,
        candidates: Vec<Candidate>,
        battery: &[f64],
    ) -> Result<Vec<Candidate>> {
        let speed = self.speed_m_per_min();
        let settings = self.exact_settings();
        let mut out = Vec::with_capacity(candidates.len());
        for (v, path, look_ahead_min, _) in candidates {
            let problem = self.hop_problem(&path, battery)?;
            let objective = Objective::NodeTime(EndPads {
                pads: self.graph().pads(v) as usize,
                pad_rate_mah_per_min: self.pad_rate_mah_per_min(v),
            });
            let nt_bound = match fluid::bound(
                &problem,
                &objective,
                settings.milp.reorder,
                settings.milp.time_limit_s,
            ) {
                Ok(o) if o.status == ExactStatus::Infeasible => continue,
                Ok(o) => o.bound.unwrap_or(0.0).max(0.0),
                // A failed bound prunes nothing.
                Err(_) => 0.0,
            };
            let bound = path.distance_m / speed + nt_bound + look_ahead_min;
            out.push((v, path, look_ahead_min, bound));
        }
        out.sort_by(|a, b| a.3.total_cmp(&b.3).then(a.0.cmp(&b.0)));
        Ok(out)
    }

    /// Simulated policies: a lower bound on the cost `tt + nt + look-ahead` of stopping at `v`
    /// after flying `path`. Sharing moves energy between drones and creates none, so the swarm
    /// arrives short of full by at least the energy every drone consumes in its cheapest slot on
    /// every leg, `E`; the pads must put it back, so `nt >= E / (k r)` for `k` pads charging at
    /// `r` mAh/min. Lowered by a relative [`BOUND_MARGIN`] so that rounding never lifts it above
    /// the computed cost.
    ///
    /// # Errors
    /// Those of [`Planner::hop_problem`] (a rate matrix that is not finite).
    pub(super) fn energy_bound_min(
        &self,
        path: &Route,
        v: usize,
        look_ahead_min: f64,
    ) -> Result<f64> {
        let speed = self.speed_m_per_min();
        let mut energy_mah = 0.0;
        for leg in &path.legs {
            energy_mah += leg.distance_m / speed * self.cheapest_swarm_rate_mah_per_min(leg)?;
        }
        let pads = f64::from(self.graph().pads(v));
        let nt_bound = energy_mah / (pads * self.pad_rate_mah_per_min(v));
        Ok((path.distance_m / speed + nt_bound + look_ahead_min) * (1.0 - BOUND_MARGIN))
    }

    /// Simulated policies: [`Planner::energy_bound_min`] before the path is built, from the
    /// shortest distance `distance_m` to `v` alone: every path is at least that long, and on every
    /// leg the swarm consumes at least `min_swarm_rate_mah_per_min` (the sum over drones of each
    /// one's least rate over every edge and slot).
    pub(super) fn distance_bound_min(
        &self,
        v: usize,
        distance_m: f64,
        look_ahead_min: f64,
        min_swarm_rate_mah_per_min: f64,
    ) -> f64 {
        let tt_min = distance_m / self.speed_m_per_min();
        let pads = f64::from(self.graph().pads(v));
        let nt_bound = tt_min * min_swarm_rate_mah_per_min / (pads * self.pad_rate_mah_per_min(v));
        (tt_min + nt_bound + look_ahead_min) * (1.0 - BOUND_MARGIN)
    }

    /// Algorithm 1. From the current node: fly straight to the destination if every drone can
    /// without sharing; else straight with sharing if that makes it; else fly (with sharing) to the
    /// recharging node, not yet stopped at, reachable without stopping, with the least `tt + nt`
    /// (plus, with [`LookAhead::RemainingTravelTime`], the remaining shortest-path travel time to the destination), recharge
    /// there, and repeat. Stopped-at nodes are never candidates again, so the loop ends after at
    /// most one step per recharging node: a request with no candidate left fails (dead end).
    pub(crate) fn compose_sequential(
        &self,
        source: usize,
        destination: usize,
        look_ahead: LookAhead,
        solves: &mut HopSolveCounts,
    ) -> Result<Plan> {
        let graph = self.graph();
        let mut plan = self.empty_plan(source, destination);
        if source == destination {
            return Ok(plan.finish());
        }
        let mut request = SequentialRequest {
            destination,
            look_ahead,
            to_destination_m: graph.distances_from_m(destination),
            stopped: vec![false; graph.node_count()],
        };
        request.stopped[source] = true;
        let mut min_rates: Option<Vec<f64>> = None;
        let mut current = source;
        let mut battery = self.full_battery_mah();
        loop {
            let Some(direct) = graph.shortest_path(current, destination) else {
                return Ok(plan.fail(PlanOutcome::NoRoute {
                    from: graph.id_of(current).to_string(),
                    to: graph.id_of(destination).to_string(),
                }));
            };
            let (flight, direct_failure) = self.fly_straight(&direct, &battery, solves)?;
            if let Some(flight) = flight {
                plan.push(self.hop(&direct, &battery, flight, None));
                return Ok(plan.finish());
            }
            let min_rates = match &mut min_rates {
                Some(rates) => rates,
                None => min_rates.insert(self.min_rates_mah_per_min()?),
            };
            let best = self.best_recharging_node(&request, current, &battery, min_rates, solves)?;
            let Some((v, path, flight, stop)) = best else {
                return Ok(plan.fail(PlanOutcome::DeadEnd {
                    node: graph.id_of(current).to_string(),
                    candidates: Candidates::PadNodes,
                    direct: direct_failure.expect("an infeasible hop reports its first failure"),
                }));
            };
            plan.push(self.hop(&path, &battery, flight, Some(stop)));
            request.stopped[v] = true;
            current = v;
            battery = self.full_battery_mah();
        }
    }

    /// Lines 5-10: the direct hop from `battery`, flown without sharing when every drone reaches
    /// the destination on its own battery, else with the policy's sharing when it shares and
    /// that makes it. The flight, or `None` with the first failure (of the flight with sharing,
    /// when the policy shares).
    fn fly_straight(
        &self,
        direct: &Route,
        battery: &[f64],
        solves: &mut HopSolveCounts,
    ) -> Result<(Option<Flight>, Option<HopFailure>)> {
        let flight = self.fly_counted(
            direct,
            battery,
            SharingPolicy::None,
            HopGoal::Feasible,
            solves,
        )?;
        if flight.outcome.feasible {
            return Ok((Some(flight), None));
        }
        let mut direct_failure = flight.outcome.failure;
        if self.sharing().shares() {
            let flight =
                self.fly_counted(direct, battery, self.sharing(), HopGoal::Feasible, solves)?;
            if flight.outcome.feasible {
                return Ok((Some(flight), None));
            }
            direct_failure = flight.outcome.failure;
        }
        Ok((None, direct_failure))
    }

    /// Lines 12-16: the recharging node reachable from `current` without stopping (its shortest
    /// path, flown reversed, within the endurance bound of `battery`), not yet stopped at, of
    /// least `tt + nt` (plus the look-ahead), the lowest index among equals: the node, the hop,
    /// its flight and the stop there; `None` when none flies.
    fn best_recharging_node(
        &self,
        request: &SequentialRequest,
        current: usize,
        battery: &[f64],
        min_rates: &[f64],
        solves: &mut HopSolveCounts,
    ) -> Result<Option<(usize, Route, Flight, Stop)>> {
        let graph = self.graph();
        let speed = self.speed_m_per_min();
        let endurance_min = self.endurance_bound_min(battery, min_rates);
        // Shortest paths v -> current, flown reversed: one Dijkstra for all candidates.
        let towards_current = graph.shortest_paths_to(current);
        let mut reachable = Vec::new();
        for v in 0..graph.node_count() {
            if request.stopped[v] || graph.pads(v) == 0 || v == request.destination {
                continue;
            }
            // A NaN or infinite distance (unreachable) is skipped too.
            if towards_current.distance_m[v] / speed > endurance_min
                || !towards_current.distance_m[v].is_finite()
            {
                continue;
            }
            let look_ahead_min = if request.look_ahead == LookAhead::RemainingTravelTime {
                request.to_destination_m[v] / speed
            } else {
                0.0
            };
            reachable.push((v, look_ahead_min));
        }
        let candidates =
            self.ordered_candidates(reachable, &towards_current, battery, min_rates)?;
        self.least_candidate(candidates, &towards_current, battery, solves)
    }

    /// The candidates `reachable` (node, look-ahead) with a lower bound on their cost, the most
    /// promising first: under `exact` with their paths and, when candidates are pruned, the
    /// fluid LP's bound; else the energy bound from the distance alone, each path built, and its
    /// own bound checked, only when the candidate's turn comes.
    fn ordered_candidates(
        &self,
        reachable: Vec<(usize, f64)>,
        towards_current: &ShortestPathsTo<'_>,
        battery: &[f64],
        min_rates: &[f64],
    ) -> Result<Vec<LazyCandidate>> {
        if self.sharing().is_exact() {
            let mut with_paths = Vec::new();
            for (v, look_ahead_min) in reachable {
                if let Some(path) = towards_current.reversed_path_from(v) {
                    with_paths.push((v, path, look_ahead_min, 0.0));
                }
            }
            if self.exact_settings().prune_candidates {
                // The fluid LP bounds `nt`.
                with_paths = self.bounded_candidates(with_paths, battery)?;
            }
            return Ok(with_paths
                .into_iter()
                .map(|(v, path, look_ahead_min, bound)| (v, Some(path), look_ahead_min, bound))
                .collect());
        }
        let min_swarm_rate: f64 = min_rates.iter().sum();
        let mut bounded: Vec<_> = reachable
            .into_iter()
            .map(|(v, look_ahead_min)| {
                let d = towards_current.distance_m[v];
                let bound = self.distance_bound_min(v, d, look_ahead_min, min_swarm_rate);
                (v, None, look_ahead_min, bound)
            })
            .collect();
        bounded.sort_by(|a, b| a.3.total_cmp(&b.3).then(a.0.cmp(&b.0)));
        Ok(bounded)
    }

    /// The candidate of least cost `tt + nt + look-ahead`, each flown from `battery` in turn;
    /// one whose bound exceeds the best cost found is never flown. The choice (least cost, then
    /// least node index) does not depend on the order.
    fn least_candidate(
        &self,
        candidates: Vec<LazyCandidate>,
        towards_current: &ShortestPathsTo<'_>,
        battery: &[f64],
        solves: &mut HopSolveCounts,
    ) -> Result<Option<(usize, Route, Flight, Stop)>> {
        let speed = self.speed_m_per_min();
        let mut best: Option<(usize, Route, Flight, Stop)> = None;
        let mut best_cost = f64::INFINITY;
        let beyond =
            |bound: f64, best_cost: f64| bound > best_cost + PRUNE_TOL_MIN * (1.0 + best_cost);
        for (v, path, look_ahead_min, bound_min) in candidates {
            if beyond(bound_min, best_cost) {
                break;
            }
            let path = match path {
                Some(path) => path,
                None => {
                    let Some(path) = towards_current.reversed_path_from(v) else {
                        continue;
                    };
                    if beyond(self.energy_bound_min(&path, v, look_ahead_min)?, best_cost) {
                        continue;
                    }
                    path
                }
            };
            let flight =
                self.fly_counted(&path, battery, self.sharing(), HopGoal::NodeTimeMin, solves)?;
            if !flight.outcome.feasible {
                continue;
            }
            let stop = self
                .stop_at(v, &flight.outcome.final_battery_mah)?
                .expect("candidates have pads");
            let cost = path.distance_m / speed + stop.nt_min + look_ahead_min;
            // The lowest node index among equal costs.
            let better = match &best {
                None => true,
                Some((b, ..)) => cost < best_cost || (cost == best_cost && v < *b),
            };
            if better {
                best_cost = cost;
                best = Some((v, path, flight, stop));
            }
        }
        Ok(best)
    }
}
