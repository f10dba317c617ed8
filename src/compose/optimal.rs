//! The optimal route of one request over stop sequences: Dijkstra on the stop graph, with its
//! arcs evaluated lazily. See models/compose.md, "Optimal route".

use super::plan::{Plan, PlanOutcome, RouteOptimality};
use super::{Flight, Planner, Stop};
use crate::eaas::exact::ExactStatus;
use crate::eaas::exact_hop::HopGoal;
use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::SharingPolicy;
use crate::error::{Error, Result};
use crate::network::Route;
use crate::solver::SolveStatus;

/// The best arc found so far into a node of the stop graph: its tail, the hop path, the flight
/// and the stop at its head (`None` at the destination).
pub(super) struct BestArc {
    pub(super) from: usize,
    pub(super) path: Route,
    pub(super) flight: Flight,
    pub(super) stop: Option<Stop>,
    /// `--sharing exact`: how far the stop's node time may lie above the infimum of the hop's
    /// node time over continuous-time schedules, min (0 when the optimum is attained).
    pub(super) epsilon_min: f64,
}

/// How a search over stop sequences starts ([`Planner::start_search`]).
pub(super) enum Start {
    /// The plan is decided: the source is the destination, no path joins them, or the direct
    /// hop flies.
    Done(Plan),
    /// The search goes on from the empty plan.
    Search {
        plan: Plan,
        /// The shortest path from the source to the destination.
        direct: Route,
        /// The direct hop's first failure, when it was flown.
        direct_failure: Option<crate::eaas::HopFailure>,
        /// The bounds every arc is screened with.
        bounds: SearchBounds,
    },
}

/// Bounds of a search from full batteries: the swarm's least total consumption rate over every
/// edge and slot, and the endurance bound (no hop longer flies).
#[derive(Debug, Clone, Copy)]
pub(super) struct SearchBounds {
    pub(super) min_swarm_rate_mah_per_min: f64,
    pub(super) endurance_min: f64,
}

/// The coded error of `--route optimal` with `--sharing fair`.
pub(crate) fn optimal_with_solved_sharing(sharing: SharingPolicy) -> Error {
    Error::invalid(
        "E0015",
        "--route optimal",
        format!(
            "--route optimal supports the simulated sharing policies (none, idle-support, pb, \
             fb) and exact, not {sharing}: the fair QP's layout is not an optimum of any hop"
        ),
        "use --sharing exact (the joint optimum) or a simulated policy with --route optimal, \
         or another --route with --sharing fair",
    )
}

impl Planner {
    /// The least delivery time over every sequence of stops from `source` to `destination`,
    /// each hop along the shortest path by distance between its two stops and flown under the
    /// planner's sharing policy from full batteries.
    ///
    /// Stop graph: the source, the destination and every node with pads; arc `u -> v` when the
    /// hop flies, of cost `tt(u, v) + nt(v)` (`tt` alone into the destination, whose hop flies
    /// without sharing or with the policy, as in Algorithm 1's lines 5–10). Every stop leaves
    /// every battery full, so an arc's cost does not depend on how `u` was reached, and Dijkstra
    /// on these non-negative costs gives the optimum. When the direct hop from the source flies
    /// it is the route (no route with stops is shorter: its paths are at least as long).
    ///
    /// Nodes are settled in order of (cost, node index); a node's out-arcs are flown when it is
    /// settled, and the search ends when the destination is. Among arcs giving a node the same
    /// cost, the one from the lowest node index is kept. An arc is skipped only when a lower
    /// bound proves it improves neither its head nor the destination: the endurance bound (it
    /// cannot fly) and the energy bound of Algorithm 1's candidate pruning (its cost exceeds the
    /// head's or the destination's cost found so far).
    ///
    /// # Returns
    /// The plan, with [`RouteOptimality`]: the route is proven optimal when every stop solved
    /// while searching (the arcs' node times) ended `optimal`; a stop the node limit stopped
    /// makes the route optimal only for the node times found. [`PlanOutcome::NoStopSequence`]
    /// when no sequence of stops reaches the destination, [`PlanOutcome::NoRoute`] when no path
    /// does.
    ///
    /// # Errors
    /// E0015 for the fair policy; else those of [`Planner::fly`] and
    /// [`Planner::stop_at`].
    ///
    /// # Complexity
    /// At most one Dijkstra tree of the network and, per node with pads, one hop simulation
    /// and one exact node time for each settled node: O(K^2) hops for K nodes with pads, fewer
    /// when bounds prune; plus O(K^2) to pick the nodes to settle.
    pub(crate) fn compose_optimal(
        &self,
        source: usize,
        destination: usize,
        solves: &mut HopSolveCounts,
    ) -> Result<Plan> {
        if self.sharing() == SharingPolicy::Fair {
            return Err(optimal_with_solved_sharing(self.sharing()));
        }
        let graph = self.graph();
        let speed = self.speed_m_per_min();
        let n = graph.node_count();
        let mut optimality = RouteOptimality::default();
        let (mut plan, direct_failure, bounds) =
            match self.start_search(source, destination, &mut optimality, true, solves)? {
                Start::Done(plan) => return Ok(plan),
                Start::Search {
                    plan,
                    direct_failure,
                    bounds,
                    ..
                } => (plan, direct_failure, bounds),
            };
        let full = self.full_battery_mah();
        let (min_swarm_rate, endurance_min) =
            (bounds.min_swarm_rate_mah_per_min, bounds.endurance_min);
        let mut cost_min = vec![f64::INFINITY; n];
        let mut best: Vec<Option<BestArc>> = (0..n).map(|_| None).collect();
        let mut settled = vec![false; n];
        cost_min[source] = 0.0;
        loop {
            // Only the source, the destination and nodes with pads ever get a finite cost.
            let Some(u) = least_unsettled(&cost_min, &settled) else {
                plan.route_optimality = Some(optimality);
                return Ok(plan.fail(PlanOutcome::NoStopSequence {
                    from: graph.id_of(source).to_string(),
                    to: graph.id_of(destination).to_string(),
                    stops_reached: settled.iter().filter(|&&s| s).count() - 1,
                    direct: direct_failure.expect("an infeasible hop reports its first failure"),
                }));
            };
            settled[u] = true;
            if u == destination {
                break;
            }
            optimality.stops_settled += usize::from(u != source);
            // Into the destination (from the source, flown above).
            if u != source {
                if let Some(path) = graph.shortest_path(u, destination) {
                    let cost = cost_min[u] + path.distance_m / speed;
                    if improves(cost, u, cost_min[destination], &best[destination]) {
                        let (flight, _) =
                            self.fly_to_destination(&path, &full, &mut optimality, solves)?;
                        optimality.arcs_flown += 1;
                        if let Some(flight) = flight {
                            cost_min[destination] = cost;
                            best[destination] = Some(BestArc {
                                from: u,
                                path,
                                flight,
                                stop: None,
                                epsilon_min: 0.0,
                            });
                        }
                    }
                }
            }
            // Into every unsettled node with pads.
            let towards_u = graph.shortest_paths_to(u);
            for v in 0..n {
                if settled[v] || v == destination || graph.pads(v) == 0 {
                    continue;
                }
                let distance_m = towards_u.distance_m[v];
                if !distance_m.is_finite() || distance_m / speed > endurance_min {
                    continue;
                }
                let limit = cost_min[v].min(cost_min[destination]);
                let bound =
                    cost_min[u] + self.distance_bound_min(v, distance_m, 0.0, min_swarm_rate);
                if beyond(bound, limit) {
                    continue;
                }
                let Some(path) = towards_u.reversed_path_from(v) else {
                    continue;
                };
                if beyond(cost_min[u] + self.energy_bound_min(&path, v, 0.0)?, limit) {
                    continue;
                }
                let arc = self.arc_into_stop(u, v, path, &full, &mut optimality, solves)?;
                let tail_cost_min = cost_min[u];
                relax(&mut cost_min, &mut best, v, tail_cost_min, speed, arc);
            }
        }
        Ok(self.route_of(plan, best, source, destination, optimality))
    }

    /// The start of a search over stop sequences: done when the source is the destination, no
    /// path joins them, or (with `fly_direct`) the direct hop flies, which no route with stops
    /// beats; else the empty plan, the direct path and, when flown, its first failure. Counts
    /// the direct hop in `optimality` and puts `optimality` on a plan it returns done; the
    /// search's bounds.
    ///
    /// # Errors
    /// Those of [`Planner::fly`].
    pub(super) fn start_search(
        &self,
        source: usize,
        destination: usize,
        optimality: &mut RouteOptimality,
        fly_direct: bool,
        solves: &mut HopSolveCounts,
    ) -> Result<Start> {
        let graph = self.graph();
        let mut plan = self.empty_plan(source, destination);
        if source == destination {
            plan.route_optimality = Some(*optimality);
            return Ok(Start::Done(plan.finish()));
        }
        let Some(direct) = graph.shortest_path(source, destination) else {
            plan.route_optimality = Some(*optimality);
            return Ok(Start::Done(plan.fail(PlanOutcome::NoRoute {
                from: graph.id_of(source).to_string(),
                to: graph.id_of(destination).to_string(),
            })));
        };
        let full = self.full_battery_mah();
        let min_rates = self.min_rates_mah_per_min()?;
        let bounds = SearchBounds {
            min_swarm_rate_mah_per_min: min_rates.iter().sum(),
            endurance_min: self.endurance_bound_min(&full, &min_rates),
        };
        if !fly_direct {
            return Ok(Start::Search {
                plan,
                direct,
                direct_failure: None,
                bounds,
            });
        }
        let (flight, direct_failure) =
            self.fly_to_destination(&direct, &full, optimality, solves)?;
        optimality.arcs_flown += 1;
        if let Some(flight) = flight {
            plan.push(self.hop(&direct, &full, flight, None));
            plan.route_optimality = Some(*optimality);
            return Ok(Start::Done(plan.finish()));
        }
        Ok(Start::Search {
            plan,
            direct,
            direct_failure,
            bounds,
        })
    }

    /// The arc `u -> v` into a node with pads along `path`, flown from full batteries `full`
    /// under the planner's policy, with the stop at `v`; `None` when the hop does not fly.
    /// Counts the hop and the stop in `optimality`.
    pub(super) fn arc_into_stop(
        &self,
        u: usize,
        v: usize,
        path: Route,
        full: &[f64],
        optimality: &mut RouteOptimality,
        solves: &mut HopSolveCounts,
    ) -> Result<Option<BestArc>> {
        let flight = self.fly_counted(&path, full, self.sharing(), HopGoal::NodeTimeMin, solves)?;
        optimality.arcs_flown += 1;
        count_unproven(&flight, optimality);
        if !flight.outcome.feasible {
            return Ok(None);
        }
        let stop = self
            .stop_at(v, &flight.outcome.final_battery_mah)?
            .expect("the node has pads");
        optimality.stops_solved += 1;
        if stop.status != SolveStatus::Optimal {
            optimality.stops_unproven += 1;
        }
        // An infimum approached: the arc's cost is its infimum, the stop's node time lies
        // within the solve's certified distance of it.
        let epsilon_min = match &flight.solve {
            Some(solve) if solve.status == Some(ExactStatus::OptimalWithin) => solve
                .bound
                .map_or(0.0, |bound| (stop.nt_min - bound).max(0.0)),
            _ => 0.0,
        };
        Ok(Some(BestArc {
            from: u,
            path,
            flight,
            stop: Some(stop),
            epsilon_min,
        }))
    }

    /// The plan of the route the best arcs `best` give, from the source to the destination,
    /// pushed on `plan` (empty so far), with `optimality`.
    pub(super) fn route_of(
        &self,
        mut plan: Plan,
        mut best: Vec<Option<BestArc>>,
        source: usize,
        destination: usize,
        optimality: RouteOptimality,
    ) -> Plan {
        let full = self.full_battery_mah();
        // The arcs of the route, from the destination back to the source.
        let mut arcs = Vec::new();
        let mut at = destination;
        while at != source {
            let arc = best[at]
                .take()
                .expect("a settled node other than the source has an arc");
            at = arc.from;
            arcs.push(arc);
        }
        let mut optimality = optimality;
        for arc in arcs.into_iter().rev() {
            optimality.epsilon_min += arc.epsilon_min;
            plan.push(self.hop(&arc.path, &full, arc.flight, arc.stop));
        }
        plan.route_optimality = Some(optimality);
        plan.finish()
    }

    /// The hop `path` into the destination from full batteries `full`: flown without sharing if
    /// that flies, else under the policy when it shares (Algorithm 1's lines 5–10). The flight,
    /// or `None` with the first failure (of the flight with sharing, when the policy shares).
    pub(super) fn fly_to_destination(
        &self,
        path: &Route,
        full: &[f64],
        optimality: &mut RouteOptimality,
        solves: &mut HopSolveCounts,
    ) -> Result<(Option<Flight>, Option<crate::eaas::HopFailure>)> {
        let flight =
            self.fly_counted(path, full, SharingPolicy::None, HopGoal::Feasible, solves)?;
        if flight.outcome.feasible {
            return Ok((Some(flight), None));
        }
        let mut failure = flight.outcome.failure;
        if self.sharing().shares() {
            let flight = self.fly_counted(path, full, self.sharing(), HopGoal::Feasible, solves)?;
            count_unproven(&flight, optimality);
            if flight.outcome.feasible {
                return Ok((Some(flight), None));
            }
            failure = flight.outcome.failure;
        }
        Ok((None, failure))
    }
}

/// Counts `flight`'s exact solve in `optimality` when it ended unproven.
fn count_unproven(flight: &Flight, optimality: &mut RouteOptimality) {
    if flight.solve.as_ref().is_some_and(|s| !s.proven()) {
        optimality.hop_solves_unproven += 1;
    }
}

/// Whether a bound, already lowered by a relative margin (Algorithm 1's candidate bounds), exceeds the cost `limit`: the arc's
/// cost is then above `limit`, never equal to it, so arcs of equal cost are always flown.
fn beyond(bound_min: f64, limit_min: f64) -> bool {
    bound_min > limit_min
}

/// The unsettled node of least finite cost, the lowest index among equals; `None` when every
/// node of finite cost is settled. O(n).
pub(super) fn least_unsettled(cost_min: &[f64], settled: &[bool]) -> Option<usize> {
    let mut next: Option<usize> = None;
    for v in 0..cost_min.len() {
        if settled[v] || !cost_min[v].is_finite() {
            continue;
        }
        if next.is_none_or(|u| cost_min[v] < cost_min[u]) {
            next = Some(v);
        }
    }
    next
}

/// Keeps `arc` into `v` (if the hop flew) as the best arc into `v` when its cost, the tail's
/// `tail_cost_min` plus the hop's travel time at `speed_m_per_min` and the stop's node time,
/// improves `v`'s ([`improves`]).
pub(super) fn relax(
    cost_min: &mut [f64],
    best: &mut [Option<BestArc>],
    v: usize,
    tail_cost_min: f64,
    speed_m_per_min: f64,
    arc: Option<BestArc>,
) {
    let Some(arc) = arc else { return };
    let nt_min = arc.stop.as_ref().map_or(0.0, |s| s.nt_min) - arc.epsilon_min;
    let cost = tail_cost_min + arc.path.distance_m / speed_m_per_min + nt_min;
    if improves(cost, arc.from, cost_min[v], &best[v]) {
        cost_min[v] = cost;
        best[v] = Some(arc);
    }
}

/// Whether an arc from `from` giving cost `cost_min` replaces the best arc `best` of cost
/// `best_min`: a lower cost, or the same cost from a lower node index.
pub(super) fn improves(cost_min: f64, from: usize, best_min: f64, best: &Option<BestArc>) -> bool {
    match best {
        None => cost_min < best_min,
        Some(arc) => cost_min < best_min || cost_min == best_min && from < arc.from,
    }
}
