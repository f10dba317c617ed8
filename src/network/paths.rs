//! Legs, paths and shortest paths over a [`SkywayGraph`].
//!
//! Edge cost here is the edge length `distance_m`; travel time `tt` and node time `nt` are
//! priced by the composition code on top of these paths.

use crate::problem::SkywayGraph;
use petgraph::algo::{dijkstra, floyd_warshall};
use petgraph::graph::NodeIndex;

/// One edge flown in one direction.
#[derive(Debug, Clone, PartialEq)]
pub struct Leg {
    /// Node the leg starts at.
    pub from: usize,
    /// Node the leg ends at.
    pub to: usize,
    /// Index of the edge flown.
    pub edge: usize,
    /// Length in metres.
    pub distance_m: f64,
    /// Direction flown, degrees clockwise from north in `[0, 360)`, from the node coordinates
    /// (`atan2(dx, dy)` with x east and y north).
    pub heading_deg: f64,
    /// The edge's wind speed, m/s.
    pub wind_speed_mps: f64,
    /// The edge's wind direction (where it blows from), degrees clockwise from north.
    pub wind_from_deg: f64,
}

/// A route: the nodes visited in order and the legs between them.
#[derive(Debug, Clone, PartialEq)]
pub struct Route {
    /// Nodes in flight order, source first; `legs.len() + 1` of them.
    pub nodes: Vec<usize>,
    /// Legs in flight order.
    pub legs: Vec<Leg>,
    /// Total length in metres (sum of the legs).
    pub distance_m: f64,
}

impl SkywayGraph {
    /// The leg flying from node `from` to adjacent node `to`, `None` if no edge joins them.
    pub fn leg(&self, from: usize, to: usize) -> Option<Leg> {
        let (e, heading_deg) = self.edge_and_heading(from, to)?;
        let s = &self.edges[e];
        Some(Leg {
            from,
            to,
            edge: e,
            distance_m: s.distance_m,
            heading_deg,
            wind_speed_mps: s.wind_speed_mps,
            wind_from_deg: s.wind_from_deg,
        })
    }

    /// The path visiting `nodes` in order.
    ///
    /// # Returns
    /// `None` if `nodes` is empty, names an index out of range, or two consecutive nodes are not
    /// joined by an edge. A single node gives a path with no legs and length 0.
    ///
    /// # Complexity
    /// O(n d) for n nodes of degree at most d.
    pub fn path_from_nodes(&self, nodes: &[usize]) -> Option<Route> {
        if nodes.is_empty() || nodes.iter().any(|&i| i >= self.node_count()) {
            return None;
        }
        let legs = nodes
            .windows(2)
            .map(|w| self.leg(w[0], w[1]))
            .collect::<Option<Vec<Leg>>>()?;
        let distance_m = legs.iter().map(|l| l.distance_m).sum();
        Some(Route {
            nodes: nodes.to_vec(),
            legs,
            distance_m,
        })
    }

    /// Length of the shortest path from `from` to every node (Dijkstra, petgraph).
    ///
    /// # Returns
    /// One entry per node: metres, `f64::INFINITY` when unreachable, 0 at `from`.
    ///
    /// # Complexity
    /// O((V + E) log V) the first time for each `from`, then O(V): the graph keeps the distances
    /// (up to [`crate::problem::MAX_CACHED_DISTANCE_NODES`] nodes).
    pub fn distances_from_m(&self, from: usize) -> Vec<f64> {
        match self.distance_row(from) {
            Some(row) => row.get_or_init(|| self.dijkstra_m(from)).clone(),
            None => self.dijkstra_m(from),
        }
    }

    /// [`SkywayGraph::distances_from_m`] computed afresh.
    fn dijkstra_m(&self, from: usize) -> Vec<f64> {
        let mut out = vec![f64::INFINITY; self.node_count()];
        if from >= self.node_count() {
            return out;
        }
        let found = dijkstra(&self.graph, NodeIndex::new(from), None, |e| {
            self.edges[*e.weight()].distance_m
        });
        for (n, d) in found {
            out[n.index()] = d;
        }
        out
    }

    /// Shortest-path lengths between every pair of nodes (Floyd–Warshall, petgraph).
    ///
    /// # Returns
    /// `d[i][j]` in metres, `f64::INFINITY` when unreachable.
    ///
    /// # Complexity
    /// O(V^3) time, O(V^2) memory.
    pub fn all_pairs_distances_m(&self) -> Vec<Vec<f64>> {
        let n = self.node_count();
        let mut out = vec![vec![f64::INFINITY; n]; n];
        // Edge costs are positive (validated), so there is no negative cycle.
        if let Ok(map) = floyd_warshall(&self.graph, |e| self.edges[*e.weight()].distance_m) {
            for ((a, b), d) in map {
                if d < f64::MAX {
                    out[a.index()][b.index()] = d;
                }
            }
        }
        out
    }

    /// Shortest path by distance from `from` to `to` (Dijkstra, petgraph).
    ///
    /// Tie-breaking is deterministic: distances to `to` are computed first, then the path is walked
    /// from `from`, each time stepping to the lowest-index neighbour that lies on a shortest path
    /// (lengths equal within a relative 1e-9). Among equally short paths this returns the one whose
    /// node sequence is lexicographically smallest by node index (file order).
    ///
    /// # Arguments
    /// * `from`, `to` - node indices.
    ///
    /// # Returns
    /// The path, or `None` if either index is out of range or `to` is unreachable from `from`.
    /// `from == to` gives a path with no legs.
    ///
    /// # Complexity
    /// O((V + E) log V).
    ///
    /// # Example
    /// ```
    /// use swarmplan::problem::SkywayGraph;
    /// use swarmplan::problem::{io::parse_json, Network};
    /// // A (0,0) - B (300,400) - C (300,0): A-B 500 m, B-C 400 m, no A-C edge.
    /// let network: Network = parse_json(r#"{ "schema_version": 1,
    ///   "nodes": [ { "id": "A", "x_m": 0, "y_m": 0, "pads": 1 },
    ///              { "id": "B", "x_m": 300, "y_m": 400, "pads": 0 },
    ///              { "id": "C", "x_m": 300, "y_m": 0, "pads": 2 } ],
    ///   "edges": [ { "from": "A", "to": "B", "wind_speed_mps": 3, "wind_from_deg": 0 },
    ///                 { "from": "C", "to": "B", "wind_speed_mps": 3, "wind_from_deg": 0 } ] }"#,
    ///   "example").unwrap();
    /// let g = SkywayGraph::new(&network).unwrap();
    /// let p = g.shortest_path(0, 2).unwrap();
    /// assert_eq!(p.nodes, vec![0, 1, 2]);
    /// assert_eq!(p.distance_m, 900.0);
    /// assert_eq!(p.legs[1].heading_deg, 180.0); // B to C flies due south
    /// ```
    pub fn shortest_path(&self, from: usize, to: usize) -> Option<Route> {
        if to >= self.node_count() {
            return None;
        }
        self.shortest_paths_to(to).path_from(from)
    }

    /// Shortest paths from every node to `to`, sharing one Dijkstra run: [`ShortestPathsTo::path_from`]
    /// gives the same path as [`SkywayGraph::shortest_path`] with the same tie-breaking.
    ///
    /// # Complexity
    /// O((V + E) log V) once, then O(path length x degree) per path.
    pub fn shortest_paths_to(&self, to: usize) -> ShortestPathsTo<'_> {
        ShortestPathsTo {
            graph: self,
            to,
            // The graph is undirected, so distances to `to` equal distances from `to`.
            distance_m: self.distances_from_m(to),
        }
    }
}

/// Shortest paths towards one node; see [`SkywayGraph::shortest_paths_to`].
pub struct ShortestPathsTo<'a> {
    graph: &'a SkywayGraph,
    to: usize,
    /// Shortest distance from every node to the target, m (`f64::INFINITY` when unreachable).
    pub distance_m: Vec<f64>,
}

impl ShortestPathsTo<'_> {
    /// The shortest path from `from` to the target, `None` if unreachable or out of range.
    pub fn path_from(&self, from: usize) -> Option<Route> {
        self.graph.path_from_nodes(&self.nodes_from(from)?)
    }

    /// The path of [`ShortestPathsTo::path_from`] flown the other way: from the target to
    /// `from`, `None` if unreachable or out of range.
    pub fn reversed_path_from(&self, from: usize) -> Option<Route> {
        let mut nodes = self.nodes_from(from)?;
        nodes.reverse();
        self.graph.path_from_nodes(&nodes)
    }

    /// The nodes of the shortest path from `from` to the target.
    fn nodes_from(&self, from: usize) -> Option<Vec<usize>> {
        let g = self.graph;
        let n = g.node_count();
        let to = self.to;
        if from >= n || !self.distance_m[from].is_finite() {
            return None;
        }
        let d = &self.distance_m;
        let eps = 1e-9 * d[from].max(1.0);
        let mut nodes = vec![from];
        let mut u = from;
        while u != to {
            if nodes.len() > n {
                return None;
            }
            let mut next: Option<usize> = None;
            let mut fallback: Option<(f64, usize)> = None;
            for &(v, e) in g.neighbors(u) {
                if d[v] >= d[u] {
                    continue;
                }
                let via = d[v] + g.edges[e].distance_m;
                if via <= d[u] + eps {
                    next = Some(v);
                    break; // neighbours come sorted by index
                }
                if fallback.is_none_or(|(best, _)| via < best) {
                    fallback = Some((via, v));
                }
            }
            u = next.or(fallback.map(|(_, v)| v))?;
            nodes.push(u);
        }
        Some(nodes)
    }
}
