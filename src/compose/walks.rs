//! The walks of one arc of the stop graph under `--sharing exact --hop-paths any`, built one at a
//! time in order of an admissible lower bound on their cost: a best-first search over partial
//! walks from the arc's tail. See models/compose.md, "Joint optimum", "Any hop path".

use super::Planner;
use crate::error::Result;
use crate::network::Route;
use crate::problem::Role;
use petgraph::algo::dijkstra;
use petgraph::graph::{DiGraph, NodeIndex};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Relative margin by which a walk's key is lowered, as the other bounds of the search.
const KEY_MARGIN: f64 = 1e-9;

/// What every key of a search toward one head uses: the bounds of the whole swarm, and the two
/// potentials of the head.
pub(super) struct WalkBounds {
    /// Each drone's least rate over every directed edge and slot, mAh/min.
    pub(super) min_rate_mah_per_min: Vec<f64>,
    /// The endurance bound of the search, min.
    pub(super) endurance_min: f64,
}

/// The potentials of one head `v` of the stop graph: the shortest distance from every node to
/// `v`, and (into a stop) the least `tt + W / (k q)` of a walk from every node to `v`.
pub(super) struct HeadPotentials {
    pub(super) distance_m: Vec<f64>,
    /// `None` into the destination.
    pub(super) time_energy_min: Option<Vec<f64>>,
}

/// A walk from the search's origin: where it ends, its travel time, every drone's least
/// consumption along it, and the walk it extends.
struct PartialWalk {
    node: usize,
    parent: Option<usize>,
    tt_min: f64,
    consumed_mah: Vec<f64>,
}

/// A partial walk waiting in the queue: the least key first, then the earliest created.
#[derive(PartialEq)]
struct Queued {
    key_min: f64,
    walk: usize,
}

impl Eq for Queued {}

impl Ord for Queued {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed: BinaryHeap pops the greatest.
        other
            .key_min
            .total_cmp(&self.key_min)
            .then(other.walk.cmp(&self.walk))
    }
}

impl PartialOrd for Queued {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// The best-first search of the walks from `from` to `to`: every partial walk not pruned, and
/// those not yet extended in order of their key.
pub(super) struct WalkSearch {
    to: usize,
    /// `Some(to)` when the head is a stop (its node time counts), `None` into the destination.
    stop: Option<usize>,
    walks: Vec<PartialWalk>,
    queue: BinaryHeap<Queued>,
    /// An extension was not created: the search reached [`super::MAX_HOP_PATH_LABELS`]
    /// partial walks, and its walks are no longer all enumerated.
    capped: bool,
}

impl Planner {
    /// The potentials of head `v`: distances to `v` and, when `stop`, the least `tt + W / (k q)`
    /// from every node, with `W` the swarm's least consumption (each drone's least rate over the
    /// slots, per directed edge) and `k q` the pads' total rate at `v`: a Dijkstra toward `v`
    /// over the network's directed edges (petgraph).
    ///
    /// # Errors
    /// Those of [`Planner::cheapest_swarm_rate_mah_per_min`].
    pub(super) fn head_potentials(&self, v: usize, stop: bool) -> Result<HeadPotentials> {
        let graph = self.graph();
        let distance_m = graph.distances_from_m(v);
        if !stop {
            return Ok(HeadPotentials {
                distance_m,
                time_energy_min: None,
            });
        }
        let speed = self.speed_m_per_min();
        let pads_rate = f64::from(graph.pads(v)) * self.pad_rate_mah_per_min(v);
        let n = graph.node_count();
        // Edges reversed: a shortest path from `v` in this graph is one toward `v` in the network.
        let mut reversed: DiGraph<(), f64> = DiGraph::with_capacity(n, 2 * graph.edge_count());
        for _ in 0..n {
            reversed.add_node(());
        }
        for x in 0..n {
            for &(y, _) in graph.neighbors(x) {
                let Some(leg) = graph.leg(x, y) else {
                    continue;
                };
                let tau_min = leg.distance_m / speed;
                let cost =
                    tau_min + tau_min * self.cheapest_swarm_rate_mah_per_min(&leg)? / pads_rate;
                reversed.add_edge(NodeIndex::new(y), NodeIndex::new(x), cost);
            }
        }
        let mut time_energy_min = vec![f64::INFINITY; n];
        for (x, c) in dijkstra(&reversed, NodeIndex::new(v), None, |e| *e.weight()) {
            time_energy_min[x.index()] = c;
        }
        Ok(HeadPotentials {
            distance_m,
            time_energy_min: Some(time_energy_min),
        })
    }

    /// A lower bound on the cost of every walk into `to` that extends a partial walk ending at
    /// `x` after `tt_min` with least consumptions `consumed_mah`; `None` when no extension can fly
    /// (the tests of [`Planner::hop_bound_min`] on the same bounds).
    ///
    /// With `t_r >= h(x) / v_g` the rest's time: a support drone's deficit is at least
    /// `w_d + t_r m_d` (`m_d` its least rate anywhere), a delivery drone's at least
    /// `w_d - rho tt + t_r (m_d - rho)` when `m_d >= rho` (else 0), the swarm's at least
    /// `W + t_r sum m`. Into a stop with `k` pads at rate `q`, the key is the larger of
    /// `tt + W / (k q) + H(x)` (`H` the time-energy potential) and `tt + h(x) / v_g` plus the
    /// P||Cmax bound of the deficit bounds; into the destination, `tt + h(x) / v_g`.
    fn walk_key_min(
        &self,
        x: usize,
        tt_min: f64,
        consumed_mah: &[f64],
        stop: Option<usize>,
        bounds: &WalkBounds,
        head: &HeadPotentials,
    ) -> Option<f64> {
        const MARGIN: f64 = 1e-9;
        let rest_min = head.distance_m[x] / self.speed_m_per_min();
        if !rest_min.is_finite() || tt_min + rest_min > bounds.endurance_min * (1.0 + MARGIN) {
            return None;
        }
        let swarm = &self.swarm().drones;
        let rho = self.inflow_rate_mah_per_min();
        let beyond = |deficit: f64, capacity: f64| deficit > capacity * (1.0 + MARGIN) + 1e-6;
        let mut deficits = Vec::with_capacity(swarm.len());
        let (mut total_mah, mut capacity_mah) = (0.0, 0.0);
        for ((d, &w), &m) in swarm
            .iter()
            .zip(consumed_mah)
            .zip(&bounds.min_rate_mah_per_min)
        {
            let deficit = match d.role {
                Role::Support => w + rest_min * m,
                Role::Delivery if m >= rho => (w - rho * tt_min + rest_min * (m - rho)).max(0.0),
                Role::Delivery => 0.0,
            };
            if beyond(deficit, d.capacity_mah) {
                return None;
            }
            deficits.push(deficit);
            total_mah += w + rest_min * m;
            capacity_mah += d.capacity_mah;
        }
        if beyond(total_mah, capacity_mah) {
            return None;
        }
        let Some(v) = stop else {
            return Some((tt_min + rest_min) * (1.0 - KEY_MARGIN));
        };
        let pads = self.graph().pads(v) as usize;
        let q = self.pad_rate_mah_per_min(v);
        deficits.sort_by(|a, b| b.total_cmp(a));
        let mut nt_min = deficits[0].max(total_mah / pads as f64) / q;
        if deficits.len() > pads {
            nt_min = nt_min.max((deficits[pads - 1] + deficits[pads]) / q);
        }
        let consumed: f64 = consumed_mah.iter().sum();
        let through_potential = head
            .time_energy_min
            .as_ref()
            .map_or(0.0, |h| tt_min + consumed / (pads as f64 * q) + h[x]);
        Some(through_potential.max(tt_min + rest_min + nt_min) * (1.0 - KEY_MARGIN))
    }

    /// The search of the walks from `from` to `to` (`stop`: `to` has pads and its node time
    /// counts), started with the empty walk at `from` (an empty queue when no walk from `from`
    /// can reach `to` within the bounds).
    pub(super) fn walk_search(
        &self,
        from: usize,
        to: usize,
        stop: bool,
        bounds: &WalkBounds,
        head: &HeadPotentials,
    ) -> WalkSearch {
        let stop = stop.then_some(to);
        let consumed_mah = vec![0.0; self.swarm().drones.len()];
        let mut search = WalkSearch {
            to,
            stop,
            walks: Vec::new(),
            queue: BinaryHeap::new(),
            capped: false,
        };
        if let Some(key_min) = self.walk_key_min(from, 0.0, &consumed_mah, stop, bounds, head) {
            search.walks.push(PartialWalk {
                node: from,
                parent: None,
                tt_min: 0.0,
                consumed_mah,
            });
            search.queue.push(Queued { key_min, walk: 0 });
        }
        search
    }

    /// Extends the search's least-key partial walk by every edge out of its end, and returns
    /// the walk it completes when it ends at the head (with at least one edge).
    ///
    /// At [`super::MAX_HOP_PATH_LABELS`] partial walks it creates no more and marks the
    /// search capped ([`WalkSearch::capped`]).
    ///
    /// # Errors
    /// Those of [`Planner::leg_rates`] for a rate that is not finite.
    pub(super) fn extend_walk(
        &self,
        search: &mut WalkSearch,
        bounds: &WalkBounds,
        head: &HeadPotentials,
    ) -> Result<Option<Route>> {
        let graph = self.graph();
        let speed = self.speed_m_per_min();
        let Some(Queued { walk, .. }) = search.queue.pop() else {
            return Ok(None);
        };
        let x = search.walks[walk].node;
        for &(y, _) in graph.neighbors(x) {
            let Some(leg) = graph.leg(x, y) else {
                continue;
            };
            let tau_min = leg.distance_m / speed;
            let tt_min = search.walks[walk].tt_min + tau_min;
            let consumed_mah: Vec<f64> = search.walks[walk]
                .consumed_mah
                .iter()
                .zip(self.least_rates(self.edge_key(&leg), &leg))
                .map(|(w, r)| w + tau_min * r)
                .collect();
            if consumed_mah.iter().any(|w| !w.is_finite()) {
                // The rate matrix names the culprit.
                self.leg_rates(&leg)?;
            }
            let Some(key_min) =
                self.walk_key_min(y, tt_min, &consumed_mah, search.stop, bounds, head)
            else {
                continue;
            };
            if search.walks.len() >= super::MAX_HOP_PATH_LABELS {
                search.capped = true;
                continue;
            }
            search.walks.push(PartialWalk {
                node: y,
                parent: Some(walk),
                tt_min,
                consumed_mah,
            });
            search.queue.push(Queued {
                key_min,
                walk: search.walks.len() - 1,
            });
        }
        if x != search.to || search.walks[walk].parent.is_none() {
            return Ok(None);
        }
        let mut nodes = vec![x];
        let mut at = walk;
        while let Some(p) = search.walks[at].parent {
            nodes.push(search.walks[p].node);
            at = p;
        }
        nodes.reverse();
        Ok(Some(
            graph
                .path_from_nodes(&nodes)
                .expect("walks follow network edges"),
        ))
    }
}

impl WalkSearch {
    /// The least key of the partial walks not yet extended: a lower bound on the cost of every
    /// walk not yet returned (infinite when none is left).
    pub(super) fn key_min(&self) -> f64 {
        self.queue.peek().map_or(f64::INFINITY, |q| q.key_min)
    }

    /// Whether the search reached [`super::MAX_HOP_PATH_LABELS`] partial walks and dropped an
    /// extension: its least key no longer bounds every walk.
    pub(super) fn capped(&self) -> bool {
        self.capped
    }

    /// Partial walks created so far.
    pub(super) fn len(&self) -> usize {
        self.walks.len()
    }
}
