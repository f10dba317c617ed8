//! The joint optimum of one request under `--sharing exact`: the least delivery time over stop
//! sequences, continuous-time sharing schedules and pad assignments, found by a lazy shortest
//! path on the stop graph whose arc costs are refined from cheap lower bounds to exact hop
//! solves only where the search needs them. See models/compose.md, "Joint optimum".

use super::optimal::{BestArc, Start};
use super::plan::{Plan, PlanOutcome, RouteOptimality};
use super::Planner;
use crate::eaas::exact::EndPads;
use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::fluid;
use crate::eaas::milp::{ExactStatus, Objective};
use crate::error::Result;
use crate::network::ShortestPathsTo;
use std::collections::HashMap;

/// Relative margin by which the fluid LP's bound is lowered: clarabel's answers are accurate to
/// about its tolerances (1e-8 relative when solved, looser when only almost solved), far below
/// this, and far below the gap between the bound and the arc's cost.
const FLUID_BOUND_MARGIN: f64 = 1e-5;

/// How far an arc's cost is known: each level is a lower bound on the next, the last is the
/// cost itself.
enum Known {
    /// The bound of [`Planner::hop_bound_min`] from the path's legs; the arc has not been
    /// flown.
    PathBound(f64),
    /// The larger of that bound and `tt` plus the fluid LP's node-time bound
    /// (`models/eaas_fluid.md`); not flown.
    FluidBound(f64),
    /// A bound proves that no schedule flies the arc.
    NoSchedule,
    /// Flown: `tt + nt` at the infimum of the hop's node time, or no schedule flies (`None`).
    Flown(Option<(f64, Box<BestArc>)>),
}

impl Known {
    fn cost_min(&self) -> f64 {
        match self {
            Known::PathBound(c) | Known::FluidBound(c) => *c,
            Known::Flown(Some((c, _))) => *c,
            Known::Flown(None) | Known::NoSchedule => f64::INFINITY,
        }
    }
}

/// The search's state: the stop graph's nodes, the shortest-path trees of the nodes expanded so
/// far, and the arcs bounded or flown.
struct Search<'g> {
    /// The stop graph's nodes: the source, every node with pads, the destination.
    stops: Vec<usize>,
    trees: HashMap<usize, ShortestPathsTo<'g>>,
    arcs: HashMap<(usize, usize), Known>,
}

impl Planner {
    /// `tt` plus the fluid LP's bound on the node time at `v` of flying `path` from full
    /// batteries, lowered by a relative [`FLUID_BOUND_MARGIN`]. An interior-point answer is
    /// trusted as a bound only: an infeasible (or nearly infeasible) LP, or a failed one, bounds
    /// nothing (`tt`), and the arc is then flown, whose exact solve proves what it proves.
    fn fluid_bound_min(&self, path: &crate::network::Route, v: usize) -> Result<f64> {
        let tt_min = path.distance_m / self.speed_m_per_min();
        let problem = self.hop_problem(path, &self.full_battery_mah())?;
        let objective = Objective::NodeTime(EndPads {
            pads: self.graph().pads(v) as usize,
            pad_rate_mah_per_min: self.pad_rate_mah_per_min(v),
        });
        let settings = self.exact_settings();
        let nt_min = match fluid::bound(
            &problem,
            &objective,
            settings.milp.reorder,
            settings.milp.time_limit_s,
        ) {
            Ok(o) if o.status == ExactStatus::Optimal => o.bound.unwrap_or(0.0).max(0.0),
            Ok(_) | Err(_) => 0.0,
        };
        Ok((tt_min + nt_min) * (1.0 - FLUID_BOUND_MARGIN))
    }

    /// [`Planner::compose_optimal`] under the exact policy: the least `dt` over stop sequences,
    /// hop schedules in continuous time and pad assignments, each hop along the hop-path rule.
    ///
    /// Lazy shortest path (models/compose.md, "Joint optimum"): every arc of the stop graph
    /// starts at a lower bound on its cost, `tt` plus the energy bound from the distance alone;
    /// Dijkstra on the current values gives a stop sequence; its arcs still at the distance
    /// bound get the bound from their path's legs, and when none is left the first arc not yet
    /// flown is flown (a configuration LP, the exact node time at its stop). The search ends
    /// when the sequence found has every arc flown: its cost is then no more than every other
    /// sequence's lower bound. An arc flown with its infimum only approached costs its infimum,
    /// and the route's `dt` lies within the summed distances (`epsilon_min`) of it.
    ///
    /// # Errors
    /// Those of [`Planner::fly`] and [`Planner::stop_at`].
    ///
    /// # Complexity
    /// Per round one Dijkstra on the stop graph, `O(K^2)` for `K` stops, and one shortest-path
    /// tree of the network per stop expanded (once); at most one hop solve per arc, and in
    /// practice a few per stop of the route.
    pub(crate) fn compose_joint(
        &self,
        source: usize,
        destination: usize,
        solves: &mut HopSolveCounts,
    ) -> Result<Plan> {
        let graph = self.graph();
        let speed = self.speed_m_per_min();
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
        let mut stops = vec![source];
        stops.extend(
            (0..graph.node_count())
                .filter(|&v| v != source && v != destination && graph.pads(v) > 0),
        );
        stops.push(destination);
        let mut search = Search {
            stops,
            trees: HashMap::new(),
            arcs: HashMap::new(),
        };
        // The direct arc is flown and does not fly.
        search
            .arcs
            .insert((source, destination), Known::Flown(None));
        let sequence = loop {
            optimality.rounds += 1;
            // Dijkstra on the current values, arcs from the lowest tail among equal labels.
            let n = graph.node_count();
            let mut label = vec![f64::INFINITY; n];
            let mut tail: Vec<Option<usize>> = vec![None; n];
            let mut settled = vec![false; n];
            label[source] = 0.0;
            while let Some(u) = super::optimal::least_unsettled(&label, &settled) {
                settled[u] = true;
                if u == destination {
                    break;
                }
                let tree = search
                    .trees
                    .entry(u)
                    .or_insert_with(|| graph.shortest_paths_to(u));
                for &v in &search.stops {
                    if settled[v] || v == source {
                        continue;
                    }
                    let cost = match search.arcs.get(&(u, v)) {
                        Some(known) => known.cost_min(),
                        None => {
                            let distance_m = tree.distance_m[v];
                            if !distance_m.is_finite() {
                                f64::INFINITY
                            } else if v == destination {
                                distance_m / speed
                            } else if distance_m / speed > endurance_min * (1.0 + 1e-9) {
                                f64::INFINITY
                            } else {
                                self.distance_bound_min(v, distance_m, 0.0, min_swarm_rate)
                            }
                        }
                    };
                    let through_u = label[u] + cost;
                    if through_u < label[v] {
                        label[v] = through_u;
                        tail[v] = Some(u);
                    }
                }
            }
            if !label[destination].is_finite() {
                optimality.stops_settled = search.trees.len() - 1;
                plan.route_optimality = Some(optimality);
                return Ok(plan.fail(PlanOutcome::NoStopSequence {
                    from: graph.id_of(source).to_string(),
                    to: graph.id_of(destination).to_string(),
                    stops_reached: search.trees.len() - 1,
                    direct: direct_failure.expect("an infeasible hop reports its first failure"),
                }));
            }
            // The sequence's arcs, from the source.
            let mut sequence = Vec::new();
            let mut at = destination;
            while at != source {
                let u = tail[at].expect("a labelled node other than the source has a tail");
                sequence.push((u, at));
                at = u;
            }
            sequence.reverse();
            // Arcs at the distance bound get their path's bound; else the first arc not flown
            // is flown.
            let unbounded: Vec<(usize, usize)> = sequence
                .iter()
                .copied()
                .filter(|arc| !search.arcs.contains_key(arc))
                .collect();
            if !unbounded.is_empty() {
                for (u, v) in unbounded {
                    let path = if v == destination {
                        graph.shortest_path(u, destination)
                    } else {
                        search.trees[&u].reversed_path_from(v)
                    }
                    .expect("a finite distance has a path");
                    let stop = (v != destination).then_some(v);
                    let known = match self.hop_bound_min(&path, stop)? {
                        Some(bound) => Known::PathBound(bound),
                        None => Known::NoSchedule,
                    };
                    search.arcs.insert((u, v), known);
                    optimality.arcs_bounded += 1;
                }
                continue;
            }
            // Arcs into a stop at the path's bound get the fluid bound.
            let path_bounded: Vec<(usize, usize)> = sequence
                .iter()
                .copied()
                .filter(|arc| matches!(search.arcs.get(arc), Some(Known::PathBound(_))))
                .filter(|&(_, v)| v != destination)
                .collect();
            if !path_bounded.is_empty() {
                for (u, v) in path_bounded {
                    let path = search.trees[&u]
                        .reversed_path_from(v)
                        .expect("a finite distance has a path");
                    let before = search.arcs[&(u, v)].cost_min();
                    let known = Known::FluidBound(self.fluid_bound_min(&path, v)?.max(before));
                    search.arcs.insert((u, v), known);
                    optimality.arcs_fluid_bounded += 1;
                }
                continue;
            }
            let next = sequence
                .iter()
                .copied()
                .find(|arc| !matches!(search.arcs.get(arc), Some(Known::Flown(_))));
            let Some((u, v)) = next else {
                break sequence;
            };
            let arc = if v == destination {
                let path = graph
                    .shortest_path(u, destination)
                    .expect("a finite distance has a path");
                let (flight, _) = self.fly_to_destination(&path, &full, &mut optimality, solves)?;
                flight.map(|flight| {
                    let cost = path.distance_m / speed;
                    let arc = BestArc {
                        from: u,
                        path,
                        flight,
                        stop: None,
                        epsilon_min: 0.0,
                    };
                    (cost, Box::new(arc))
                })
            } else {
                let path = search.trees[&u]
                    .reversed_path_from(v)
                    .expect("a finite distance has a path");
                self.arc_into_stop(u, v, path, &full, &mut optimality, solves)?
                    .map(|arc| {
                        let nt_min = arc.stop.as_ref().map_or(0.0, |s| s.nt_min);
                        (
                            arc.path.distance_m / speed + nt_min - arc.epsilon_min,
                            Box::new(arc),
                        )
                    })
            };
            optimality.arcs_flown += usize::from(v == destination);
            search.arcs.insert((u, v), Known::Flown(arc));
        };
        optimality.stops_settled = search.trees.len() - 1;
        // Arcs from the source to every other stop, and from each stop with pads to every
        // stop but the source and itself.
        let m = search.stops.len();
        optimality.arcs_total = (m - 1) + (m - 2) * (m - 2);
        // Every arc of the sequence is flown and flies.
        let mut best: Vec<Option<BestArc>> = (0..graph.node_count()).map(|_| None).collect();
        for (u, v) in sequence {
            let Some(Known::Flown(Some((_, arc)))) = search.arcs.remove(&(u, v)) else {
                unreachable!("the sequence's arcs are flown and fly");
            };
            best[v] = Some(*arc);
        }
        Ok(self.route_of(plan, best, source, destination, optimality))
    }
}
