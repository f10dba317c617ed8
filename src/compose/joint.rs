//! The joint optimum of one request under `--sharing exact`: the least delivery time over stop
//! sequences, continuous-time sharing schedules and pad assignments, found by a lazy shortest
//! path on the stop graph whose arc costs are refined from cheap lower bounds to exact hop
//! solves only where the search needs them. See models/compose.md, "Joint optimum".

use super::optimal::{BestArc, SearchBounds, Start};
use super::plan::{Plan, PlanOutcome, RouteOptimality};
use super::walks::{HeadPotentials, WalkBounds, WalkSearch};
use super::{HopPaths, Planner};
#[cfg(feature = "microlp")]
use crate::eaas::exact::continuous::{self, RelaxedNodeTime};
use crate::eaas::exact::fluid;
use crate::eaas::exact::EndPads;
use crate::eaas::exact::{ExactStatus, Objective};
use crate::eaas::exact_hop::HopSolveCounts;
use crate::error::Result;
use crate::network::{Route, ShortestPathsTo};
use std::collections::HashMap;

/// Relative margin by which the `l2` bound is lowered: clarabel's answers (the fluid LP) are
/// accurate to about its tolerances (1e-8 relative when solved, looser when only almost solved),
/// the simplex's (the relaxed configuration LP) to its `1e-9`, both far below this, and far below
/// the gap between the bound and the arc's cost.
const FLUID_BOUND_MARGIN: f64 = 1e-5;

/// A walk of an arc, built and bounded, not yet flown.
struct BoundedWalk {
    /// `l1` (the path's legs) or, once `fluid`, `l2` (an LP's bound too).
    bound_min: f64,
    fluid: bool,
    path: Route,
}

/// The walks of an arc not yet built (before an arc is first built its value is `l0`, from the
/// distance alone, and it has no [`ArcValue`]).
enum Unbuilt {
    /// `--hop-paths any`: the best-first search of the walks.
    Walks(Box<WalkSearch>),
    /// Every walk is built.
    Done,
}

/// How far an arc's cost is known: lower bounds on the walks not yet built and on those built
/// and not flown, and the best walk flown. Its value is the least of the three, a lower bound on
/// its cost, the cost itself when the best flown walk holds it.
struct ArcValue {
    unbuilt: Unbuilt,
    candidates: Vec<BoundedWalk>,
    /// `tt + nt` at the infimum of the hop's node time, and the arc, of the best walk flown that
    /// flies.
    flown: Option<(f64, Box<BestArc>)>,
}

/// What raises an arc's value next.
enum Step {
    /// The best flown walk holds the least value (or no walk flies): the value is the cost.
    Exact,
    /// Build the next walk (`l0` to `l1`).
    Build,
    /// Bound candidate `i` with the fluid LP (`l1` to `l2`).
    Fluid(usize),
    /// Fly candidate `i`.
    Fly(usize),
}

impl ArcValue {
    fn unbuilt_min(&self) -> f64 {
        match &self.unbuilt {
            Unbuilt::Walks(search) => search.key_min(),
            Unbuilt::Done => f64::INFINITY,
        }
    }

    /// The candidate of least bound, the first built among equals.
    fn least_candidate(&self) -> Option<usize> {
        let mut least: Option<usize> = None;
        for (i, c) in self.candidates.iter().enumerate() {
            if least.is_none_or(|l| c.bound_min < self.candidates[l].bound_min) {
                least = Some(i);
            }
        }
        least
    }

    fn cost_min(&self) -> f64 {
        let candidate = self
            .least_candidate()
            .map_or(f64::INFINITY, |i| self.candidates[i].bound_min);
        let flown = self.flown.as_ref().map_or(f64::INFINITY, |(c, _)| *c);
        self.unbuilt_min().min(candidate).min(flown)
    }

    /// The step on the least value; `into_stop`: the head has pads (the fluid LP bounds it).
    fn step(&self, into_stop: bool) -> Step {
        let unbuilt = self.unbuilt_min();
        let least = self.least_candidate();
        let candidate = least.map_or(f64::INFINITY, |i| self.candidates[i].bound_min);
        let flown = self.flown.as_ref().map_or(f64::INFINITY, |(c, _)| *c);
        if flown <= unbuilt && flown <= candidate {
            return Step::Exact;
        }
        match least {
            Some(i) if candidate < unbuilt => {
                if into_stop && !self.candidates[i].fluid {
                    Step::Fluid(i)
                } else {
                    Step::Fly(i)
                }
            }
            _ => Step::Build,
        }
    }
}

/// The request of a joint search: its ends, full batteries, the bounds of a search from them
/// and, under `any`, the walks' bounds.
struct JointRequest {
    source: usize,
    destination: usize,
    full: Vec<f64>,
    bounds: SearchBounds,
    walk_bounds: Option<WalkBounds>,
}

/// The search's state: the stop graph's nodes, the shortest-path trees of the nodes expanded so
/// far, the heads' potentials (`any`), and the arcs bounded or flown.
struct Search<'g> {
    /// The stop graph's nodes: the source, every node with pads, the destination.
    stops: Vec<usize>,
    trees: HashMap<usize, ShortestPathsTo<'g>>,
    heads: HashMap<usize, HeadPotentials>,
    arcs: HashMap<(usize, usize), ArcValue>,
    /// The rounds' Dijkstra over the stops, its arc values kept between rounds.
    values: ArcValues,
}

/// Every arc's current value (`l0` until the arc is known, then [`ArcValue::cost_min`]) in a
/// matrix over the stops, for the Dijkstra of every round: a row is filled when its tail is
/// first settled, an entry refreshed when its arc changes.
struct ArcValues {
    /// The stop graph's node of every network node, `usize::MAX` for a node without one.
    index_of: Vec<usize>,
    /// The stop graph's nodes in increasing network index (the order ties are settled in).
    by_node: Vec<usize>,
    /// `m x m`, row-major by tail; `None` for a row not filled yet.
    rows: Vec<Option<Vec<f64>>>,
}

impl ArcValues {
    fn new(stops: &[usize], n: usize) -> ArcValues {
        let mut index_of = vec![usize::MAX; n];
        for (i, &v) in stops.iter().enumerate() {
            index_of[v] = i;
        }
        let mut by_node: Vec<usize> = (0..stops.len()).collect();
        by_node.sort_by_key(|&i| stops[i]);
        ArcValues {
            index_of,
            by_node,
            rows: vec![None; stops.len()],
        }
    }
}

impl Planner {
    /// `tt` plus a lower bound on the node time at `v` of flying `path` from full batteries
    /// (`l2`): the configuration LP with the pads relaxed to their aggregate (the pad search's
    /// root, [`continuous::relaxed_node_time`]); infinite when that LP is infeasible (no schedule
    /// flies the arc, as its exact solve would find); where it tells nothing (too large, a
    /// simplex failure) the fluid LP's bound; lowered by a relative [`FLUID_BOUND_MARGIN`]. An
    /// infeasible or failed fluid LP bounds nothing (`tt`), and the arc is then flown, whose
    /// exact solve proves what it proves.
    fn l2_bound_min(&self, path: &crate::network::Route, v: usize) -> Result<f64> {
        let tt_min = path.distance_m / self.speed_m_per_min();
        let problem = self.hop_problem(path, &self.full_battery_mah())?;
        let objective = Objective::NodeTime(EndPads {
            pads: self.graph().pads(v) as usize,
            pad_rate_mah_per_min: self.pad_rate_mah_per_min(v),
        });
        let settings = self.exact_settings();
        #[cfg(feature = "microlp")]
        {
            let readings = crate::eaas::PolicyOptions::from(self.readings());
            let options = continuous::ContinuousOptions::like(&settings.milp, readings);
            match continuous::relaxed_node_time(&problem, &objective, &options) {
                RelaxedNodeTime::Bound(nt_min) => {
                    return Ok((tt_min + nt_min.max(0.0)) * (1.0 - FLUID_BOUND_MARGIN));
                }
                RelaxedNodeTime::Infeasible => return Ok(f64::INFINITY),
                RelaxedNodeTime::Unknown => {}
            }
        }
        // The configuration LP past its size or failed: the fluid LP (clarabel).
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
    /// hop schedules in continuous time and pad assignments, each hop along the hop-path rule
    /// (`hop_paths` = `rule`) or along any walk (`any`).
    ///
    /// Lazy shortest path (models/compose.md, "Joint optimum"): every arc of the stop graph
    /// starts at a lower bound on its cost, `tt` plus the energy bound from the distance alone;
    /// Dijkstra on the current values gives a stop sequence; its arcs whose least value is a
    /// walk not yet built get that walk built and bounded from its legs, then those whose least
    /// value is a walk bounded from its legs get the relaxed configuration LP's bound, and when none is left the
    /// first arc whose least value is a walk not yet flown flies it (a configuration LP, the exact
    /// node time at its stop). The search ends when the sequence found has every arc exact (its
    /// best flown walk no dearer than any bound of its other walks): its cost is then no more
    /// than every other sequence's lower bound. Under `rule` an arc has one walk; under `any`
    /// its walks come from a best-first search on admissible keys ([`WalkSearch`]). An arc flown
    /// with its infimum only approached costs its infimum, and the route's `dt` lies within the
    /// summed distances (`epsilon_min`) of it.
    ///
    /// # Errors
    /// Those of [`Planner::fly`] and [`Planner::stop_at`].
    ///
    /// # Complexity
    /// Per round one Dijkstra on the stop graph, `O(K^2)` for `K` stops, and one shortest-path
    /// tree of the network per stop expanded (once); at most one hop solve per walk built, and
    /// in practice a few per stop of the route.
    pub(crate) fn compose_joint(
        &self,
        source: usize,
        destination: usize,
        hop_paths: HopPaths,
        solves: &mut HopSolveCounts,
    ) -> Result<Plan> {
        let graph = self.graph();
        let mut optimality = RouteOptimality {
            hop_paths,
            ..RouteOptimality::default()
        };
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
        let walk_bounds = match hop_paths {
            HopPaths::Rule => None,
            HopPaths::Any => Some(WalkBounds {
                min_rate_mah_per_min: self.min_rates_mah_per_min()?,
                endurance_min: bounds.endurance_min,
            }),
        };
        let request = JointRequest {
            source,
            destination,
            full,
            bounds,
            walk_bounds,
        };
        let mut search = self.joint_search(&request, hop_paths);
        let sequence = self.lazy_search(&mut search, &request, &mut optimality, solves)?;
        optimality.stops_settled = search.trees.len() - 1;
        let Some(sequence) = sequence else {
            plan.route_optimality = Some(optimality);
            return Ok(plan.fail(PlanOutcome::NoStopSequence {
                from: graph.id_of(source).to_string(),
                to: graph.id_of(destination).to_string(),
                stops_reached: search.trees.len() - 1,
                direct: direct_failure.expect("an infeasible hop reports its first failure"),
            }));
        };
        // Arcs from the source to every other stop, and from each stop with pads to every
        // stop but the source and itself.
        let m = search.stops.len();
        optimality.arcs_total = (m - 1) + (m - 2) * (m - 2);
        let best = best_flown(&mut search, sequence, graph.node_count());
        Ok(self.route_of(plan, best, source, destination, optimality))
    }

    /// The joint search's start: the stop graph's nodes (the source, every node with pads, the
    /// destination), no arc known yet but, under `rule`, the direct one, flown already.
    fn joint_search(&self, request: &JointRequest, hop_paths: HopPaths) -> Search<'_> {
        let graph = self.graph();
        let (source, destination) = (request.source, request.destination);
        let mut stops = vec![source];
        stops.extend(
            (0..graph.node_count())
                .filter(|&v| v != source && v != destination && graph.pads(v) > 0),
        );
        stops.push(destination);
        let values = ArcValues::new(&stops, graph.node_count());
        let mut search = Search {
            stops,
            trees: HashMap::new(),
            heads: HashMap::new(),
            arcs: HashMap::new(),
            values,
        };
        if hop_paths == HopPaths::Rule {
            // The direct arc's one walk is flown and does not fly. Under `any` its other walks
            // are searched (the direct one again, from the planner's cache).
            search.arcs.insert(
                (source, destination),
                ArcValue {
                    unbuilt: Unbuilt::Done,
                    candidates: Vec::new(),
                    flown: None,
                },
            );
        }
        search
    }

    /// The rounds of the lazy search ("Lazy search"): each one takes the least sequence on the
    /// current values and raises its arcs, all still at `l0` to `l1`, else all into a stop at
    /// `l1` to `l2`, else flies the first not yet flown. The sequence whose arcs are all exact;
    /// `None` when no sequence reaches the destination.
    fn lazy_search<'g>(
        &'g self,
        search: &mut Search<'g>,
        request: &JointRequest,
        optimality: &mut RouteOptimality,
        solves: &mut HopSolveCounts,
    ) -> Result<Option<Vec<(usize, usize)>>> {
        let destination = request.destination;
        loop {
            optimality.rounds += 1;
            let Some(sequence) = self.least_sequence(search, request) else {
                return Ok(None);
            };
            let steps: Vec<((usize, usize), Step)> = sequence
                .iter()
                .map(|&(u, v)| {
                    let step = search
                        .arcs
                        .get(&(u, v))
                        .map_or(Step::Build, |a| a.step(v != destination));
                    ((u, v), step)
                })
                .collect();
            // Walks not yet built hold some arcs' least values: build them.
            if self.build_steps(search, &steps, request, optimality)? {
                refresh(search, &steps);
                continue;
            }
            // Walks into a stop bounded from their legs: the fluid bound.
            if self.fluid_steps(search, &steps, optimality)? {
                refresh(search, &steps);
                continue;
            }
            let next = steps.iter().find_map(|&(arc, ref step)| match *step {
                Step::Fly(i) => Some((arc, i)),
                _ => None,
            });
            let Some((arc, i)) = next else {
                return Ok(Some(sequence));
            };
            self.fly_walk(search, arc, i, request, optimality, solves)?;
            refresh(search, &steps);
        }
    }

    /// Dijkstra on the current values, arcs from the lowest tail among equal labels (an arc not
    /// yet known at `l0`, from its tail's shortest-path tree): the least sequence's arcs, from
    /// the source; `None` when the destination is out of reach.
    fn least_sequence<'g>(
        &'g self,
        search: &mut Search<'g>,
        request: &JointRequest,
    ) -> Option<Vec<(usize, usize)>> {
        let graph = self.graph();
        let (source, destination) = (request.source, request.destination);
        let m = search.stops.len();
        let at = |v: usize| search.values.index_of[v];
        let (s, t) = (at(source), at(destination));
        let mut label = vec![f64::INFINITY; m];
        let mut tail: Vec<Option<usize>> = vec![None; m];
        let mut settled = vec![false; m];
        label[s] = 0.0;
        // The least label, the lowest network index among equals (as over the network's nodes).
        while let Some(i) = search
            .values
            .by_node
            .iter()
            .copied()
            .filter(|&i| !settled[i] && label[i].is_finite())
            .reduce(|a, b| if label[b] < label[a] { b } else { a })
        {
            settled[i] = true;
            if i == t {
                break;
            }
            if search.values.rows[i].is_none() {
                let u = search.stops[i];
                let tree = search
                    .trees
                    .entry(u)
                    .or_insert_with(|| graph.shortest_paths_to(u));
                let row = search
                    .stops
                    .iter()
                    .map(|&v| match search.arcs.get(&(u, v)) {
                        Some(known) => known.cost_min(),
                        None => self.distance_value_min(tree.distance_m[v], v, request),
                    })
                    .collect();
                search.values.rows[i] = Some(row);
            }
            let row = search.values.rows[i].as_ref().expect("filled above");
            for j in 0..m {
                if settled[j] || j == s {
                    continue;
                }
                let through_u = label[i] + row[j];
                if through_u < label[j] {
                    label[j] = through_u;
                    tail[j] = Some(i);
                }
            }
        }
        if !label[t].is_finite() {
            return None;
        }
        let tail: Vec<Option<usize>> = tail.iter().map(|u| u.map(|u| search.stops[u])).collect();
        let mut by_network = vec![None; graph.node_count()];
        for (i, &v) in search.stops.iter().enumerate() {
            by_network[v] = tail[i];
        }
        Some(sequence_to(&by_network, source, destination))
    }

    /// The value `l0` of an arc into `v` not yet built, from the shortest distance `distance_m`
    /// alone: `tt` into the destination, the energy bound into a stop; infinite out of reach or
    /// beyond the endurance bound.
    fn distance_value_min(&self, distance_m: f64, v: usize, request: &JointRequest) -> f64 {
        let speed = self.speed_m_per_min();
        let bounds = &request.bounds;
        if !distance_m.is_finite() {
            f64::INFINITY
        } else if v == request.destination {
            distance_m / speed
        } else if distance_m / speed > bounds.endurance_min * (1.0 + 1e-9) {
            f64::INFINITY
        } else {
            self.distance_bound_min(v, distance_m, 0.0, bounds.min_swarm_rate_mah_per_min)
        }
    }

    /// Raises every arc of `steps` still at `l0` to `l1`: its walks built and bounded
    /// ([`Planner::build_walks`]). Whether any was.
    fn build_steps(
        &self,
        search: &mut Search<'_>,
        steps: &[((usize, usize), Step)],
        request: &JointRequest,
        optimality: &mut RouteOptimality,
    ) -> Result<bool> {
        let mut raised = false;
        for &((u, v), ref step) in steps {
            if matches!(step, Step::Build) {
                self.build_walks(
                    search,
                    (u, v),
                    request.destination,
                    request.walk_bounds.as_ref(),
                    optimality,
                )?;
                raised = true;
            }
        }
        Ok(raised)
    }

    /// Raises every arc into a stop of `steps` at `l1` to `l2`: its candidate bounded by the
    /// fluid LP too. Whether any was.
    fn fluid_steps(
        &self,
        search: &mut Search<'_>,
        steps: &[((usize, usize), Step)],
        optimality: &mut RouteOptimality,
    ) -> Result<bool> {
        let mut raised = false;
        for &((u, v), ref step) in steps {
            if let Step::Fluid(i) = *step {
                let arc = search
                    .arcs
                    .get_mut(&(u, v))
                    .expect("a stepped arc is known");
                let candidate = &mut arc.candidates[i];
                candidate.bound_min = self
                    .l2_bound_min(&candidate.path, v)?
                    .max(candidate.bound_min);
                candidate.fluid = true;
                optimality.arcs_fluid_bounded += 1;
                raised = true;
            }
        }
        Ok(raised)
    }

    /// Flies candidate `i` of arc `(u, v)` from full batteries (into the destination as
    /// Algorithm 1's lines 5–10, into a stop with its node time); the arc's best flown walk when
    /// it flies cheaper than the one kept.
    fn fly_walk(
        &self,
        search: &mut Search<'_>,
        (u, v): (usize, usize),
        i: usize,
        request: &JointRequest,
        optimality: &mut RouteOptimality,
        solves: &mut HopSolveCounts,
    ) -> Result<()> {
        let speed = self.speed_m_per_min();
        let (destination, full) = (request.destination, &request.full);
        let value = search
            .arcs
            .get_mut(&(u, v))
            .expect("a stepped arc is known");
        let path = value.candidates.remove(i).path;
        let arc = if v == destination {
            let (flight, _) = self.fly_to_destination(&path, full, optimality, solves)?;
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
            self.arc_into_stop(u, v, path, full, optimality, solves)?
                .map(|arc| {
                    let nt_min = arc.stop.as_ref().map_or(0.0, |s| s.nt_min);
                    (
                        arc.path.distance_m / speed + nt_min - arc.epsilon_min,
                        Box::new(arc),
                    )
                })
        };
        optimality.arcs_flown += usize::from(v == destination);
        if let Some((cost, arc)) = arc {
            if value.flown.as_ref().is_none_or(|(best, _)| cost < *best) {
                value.flown = Some((cost, arc));
            }
        }
        Ok(())
    }

    /// Builds the walks of arc `(u, v)` that hold its least value: under `rule` (`walk_bounds`
    /// `None`) its one path, under `any` walks from its search until a built walk, a flown one
    /// or no walk holds the least value. Each walk built is bounded from its legs
    /// ([`Planner::hop_bound_min`]) and kept unless that proves no schedule flies it.
    ///
    /// Under `any`, a search that reaches [`super::MAX_HOP_PATH_LABELS`] partial walks stops:
    /// the arc keeps the walks built, and `optimality.arcs_capped` counts it.
    ///
    /// # Errors
    /// Those of [`Planner::hop_bound_min`] and [`Planner::head_potentials`].
    fn build_walks(
        &self,
        search: &mut Search<'_>,
        (u, v): (usize, usize),
        destination: usize,
        walk_bounds: Option<&WalkBounds>,
        optimality: &mut RouteOptimality,
    ) -> Result<()> {
        let graph = self.graph();
        let into_stop = v != destination;
        let stop = into_stop.then_some(v);
        let Some(walk_bounds) = walk_bounds else {
            let path = if into_stop {
                search.trees[&u].reversed_path_from(v)
            } else {
                graph.shortest_path(u, destination)
            }
            .expect("a finite distance has a path");
            let candidates = match self.hop_bound_min(&path, stop)? {
                Some(bound_min) => vec![BoundedWalk {
                    bound_min,
                    fluid: false,
                    path,
                }],
                None => Vec::new(),
            };
            search.arcs.insert(
                (u, v),
                ArcValue {
                    unbuilt: Unbuilt::Done,
                    candidates,
                    flown: None,
                },
            );
            optimality.arcs_bounded += 1;
            return Ok(());
        };
        if let std::collections::hash_map::Entry::Vacant(e) = search.heads.entry(v) {
            e.insert(self.head_potentials(v, into_stop)?);
        }
        let head = &search.heads[&v];
        let value = search.arcs.entry((u, v)).or_insert_with(|| ArcValue {
            unbuilt: Unbuilt::Walks(Box::new(self.walk_search(
                u,
                v,
                into_stop,
                walk_bounds,
                head,
            ))),
            candidates: Vec::new(),
            flown: None,
        });
        let before = match &value.unbuilt {
            Unbuilt::Walks(walks) => walks.len(),
            _ => 0,
        };
        while matches!(value.step(into_stop), Step::Build) {
            let Unbuilt::Walks(walks) = &mut value.unbuilt else {
                unreachable!("only a search of walks builds under any");
            };
            if walks.capped() {
                // The walks left are no longer all enumerated: the arc keeps the walks built,
                // and the route is proven only over them.
                optimality.hop_path_labels += walks.len() - before;
                optimality.arcs_capped += 1;
                value.unbuilt = Unbuilt::Done;
                return Ok(());
            }
            let Some(path) = self.extend_walk(walks, walk_bounds, head)? else {
                continue;
            };
            if let Some(bound_min) = self.hop_bound_min(&path, stop)? {
                value.candidates.push(BoundedWalk {
                    bound_min,
                    fluid: false,
                    path,
                });
            }
            optimality.arcs_bounded += 1;
        }
        if let Unbuilt::Walks(walks) = &value.unbuilt {
            optimality.hop_path_labels += walks.len() - before;
        }
        Ok(())
    }
}

/// The values of the arcs of `steps` again, after a round raised them (rows not filled yet are
/// filled when their tail is settled).
fn refresh(search: &mut Search<'_>, steps: &[((usize, usize), Step)]) {
    for &((u, v), _) in steps {
        let (i, j) = (search.values.index_of[u], search.values.index_of[v]);
        if let (Some(row), Some(known)) = (search.values.rows[i].as_mut(), search.arcs.get(&(u, v)))
        {
            row[j] = known.cost_min();
        }
    }
}

/// The arcs of the sequence the Dijkstra tails `tail` give from `source` to `destination`, from
/// the source.
fn sequence_to(tail: &[Option<usize>], source: usize, destination: usize) -> Vec<(usize, usize)> {
    let mut sequence = Vec::new();
    let mut at = destination;
    while at != source {
        let u = tail[at].expect("a labelled node other than the source has a tail");
        sequence.push((u, at));
        at = u;
    }
    sequence.reverse();
    sequence
}

/// The best arc into each of the `n` nodes, taken out of `search`: the flown walk of each arc of
/// `sequence`, every one exact and flying.
fn best_flown(
    search: &mut Search<'_>,
    sequence: Vec<(usize, usize)>,
    n: usize,
) -> Vec<Option<BestArc>> {
    let mut best: Vec<Option<BestArc>> = (0..n).map(|_| None).collect();
    for (u, v) in sequence {
        let Some(ArcValue {
            flown: Some((_, arc)),
            ..
        }) = search.arcs.remove(&(u, v))
        else {
            unreachable!("the sequence's arcs are exact and fly");
        };
        best[v] = Some(*arc);
    }
    best
}
