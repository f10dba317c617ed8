//! The skyway network as a graph: rooftop nodes joined by edges that can be flown both ways.
//!
//! [`SkywayGraph`] is built from a validated [`Network`] on a petgraph [`UnGraph`]. Node `i` of the
//! graph is `network.nodes[i]` and edge `e` is `network.edges[e]`, so indices are stable and match
//! the file order. Routes and shortest paths over it live in [`crate::network`].
//!
//! Conventions: `x_m` is easting and `y_m` northing; a heading is the direction flown, degrees
//! clockwise from north in `[0, 360)`; `wind_from_deg` is where the wind blows from (meteorological).

use super::validate::{euclidean_m, validate_network};
use super::Network;
use crate::error::{Error, Result};
use petgraph::graph::{NodeIndex, UnGraph};
use petgraph::unionfind::UnionFind;
use std::collections::HashMap;
use std::sync::OnceLock;

/// One edge of the graph, with its length resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct SkywayEdge {
    /// Index of the `from` node as written in the file.
    pub a: usize,
    /// Index of the `to` node as written in the file.
    pub b: usize,
    /// Length in metres: the file's `distance_m`, or the Euclidean distance when absent.
    pub distance_m: f64,
    /// Wind speed on the edge, m/s.
    pub wind_speed_mps: f64,
    /// Direction the wind blows from, degrees clockwise from north.
    pub wind_from_deg: f64,
}

#[derive(Debug, Clone)]
struct NodeData {
    id: String,
    x_m: f64,
    y_m: f64,
    pads: u32,
    pad_rate_mah_per_min: Option<f64>,
}

/// A validated skyway network on a petgraph undirected graph; edge weights are edge indices.
#[derive(Debug, Clone)]
pub struct SkywayGraph {
    pub(crate) graph: UnGraph<(), usize>,
    nodes: Vec<NodeData>,
    pub(crate) edges: Vec<SkywayEdge>,
    index: HashMap<String, usize>,
    component: Vec<usize>,
    /// `(neighbour, edge)` pairs of every node, sorted by neighbour index.
    adjacency: Vec<Vec<(usize, usize)>>,
    /// `headings_deg[i][j]`: direction flown from node `i` to its `j`-th neighbour (as in
    /// `adjacency`), degrees clockwise from north in `[0, 360)`.
    headings_deg: Vec<Vec<f64>>,
    /// Shortest-path distances from every node, each computed on first use; empty above
    /// [`MAX_CACHED_DISTANCE_NODES`] nodes.
    distance_rows: Vec<OnceLock<Vec<f64>>>,
}

/// Most nodes for which a graph keeps the shortest-path distances it computed (`n^2` numbers:
/// 32 MiB at this size).
pub const MAX_CACHED_DISTANCE_NODES: usize = 2048;

/// Direction from `a` to `b` in degrees clockwise from north, in `[0, 360)`; 0 when `a == b`.
pub fn heading_deg(a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    if dx == 0.0 && dy == 0.0 {
        return 0.0;
    }
    let h = dx.atan2(dy).to_degrees();
    let h = if h < 0.0 { h + 360.0 } else { h };
    if h >= 360.0 {
        0.0
    } else {
        h
    }
}

/// Reads a network JSON file, validates it and builds its graph.
///
/// # Arguments
/// * `path` - the network file.
///
/// # Returns
/// The network as read and its graph.
///
/// # Errors
/// [`Error::Invalid`] with E0008 or E0009 if the file cannot be read or is not UTF-8, with E0001 for malformed JSON or
/// with every E1xxx violation, each field prefixed by the file name (`net.json: edges[3].to`).
pub fn read_network(path: &std::path::Path) -> Result<(Network, SkywayGraph)> {
    let network: Network = crate::problem::io::read_json(path)?;
    let graph = SkywayGraph::new(&network).map_err(|e| prefix_fields(e, path))?;
    Ok((network, graph))
}

/// Prefixes every violation's field of an [`Error::Invalid`] with a file name.
pub(crate) fn prefix_fields(e: Error, path: &std::path::Path) -> Error {
    match e {
        Error::Invalid(v) => Error::Invalid(
            v.into_iter()
                .map(|mut x| {
                    x.field = format!("{}: {}", path.display(), x.field);
                    x
                })
                .collect(),
        ),
        other => other,
    }
}

impl SkywayGraph {
    /// Builds the graph of a network after checking every network rule.
    ///
    /// # Arguments
    /// * `network` - the network as read from its file.
    ///
    /// # Returns
    /// The graph; node and edge indices follow the file order.
    ///
    /// # Errors
    /// [`Error::Invalid`] with every violation of [`validate_network`] (codes E1xxx).
    ///
    /// # Complexity
    /// O(V + E) expected time.
    pub fn new(network: &Network) -> Result<SkywayGraph> {
        let violations = validate_network(network);
        if !violations.is_empty() {
            return Err(Error::Invalid(violations));
        }
        let nodes: Vec<NodeData> = network
            .nodes
            .iter()
            .map(|n| NodeData {
                id: n.id.clone(),
                x_m: n.x_m,
                y_m: n.y_m,
                pads: n.pads,
                pad_rate_mah_per_min: n.pad_charge_rate_mah_per_min,
            })
            .collect();
        let index: HashMap<String, usize> = nodes
            .iter()
            .enumerate()
            .map(|(i, n)| (n.id.clone(), i))
            .collect();
        let mut graph = UnGraph::with_capacity(nodes.len(), network.edges.len());
        for _ in &nodes {
            graph.add_node(());
        }
        let mut edges = Vec::with_capacity(network.edges.len());
        let mut components = UnionFind::new(nodes.len());
        for (e, s) in network.edges.iter().enumerate() {
            // Validation guarantees both ids exist.
            let (a, b) = (index[&s.from], index[&s.to]);
            let distance_m = s.distance_m.unwrap_or_else(|| {
                euclidean_m((nodes[a].x_m, nodes[a].y_m), (nodes[b].x_m, nodes[b].y_m))
            });
            graph.add_edge(NodeIndex::new(a), NodeIndex::new(b), e);
            components.union(a, b);
            edges.push(SkywayEdge {
                a,
                b,
                distance_m,
                wind_speed_mps: s.wind_speed_mps,
                wind_from_deg: s.wind_from_deg,
            });
        }
        let component = components.into_labeling();
        let mut adjacency = vec![Vec::new(); nodes.len()];
        for (e, s) in edges.iter().enumerate() {
            adjacency[s.a].push((s.b, e));
            adjacency[s.b].push((s.a, e));
        }
        for list in &mut adjacency {
            list.sort_unstable();
        }
        let position = |i: usize| (nodes[i].x_m, nodes[i].y_m);
        let headings_deg = adjacency
            .iter()
            .enumerate()
            .map(|(i, list)| {
                list.iter()
                    .map(|&(j, _)| heading_deg(position(i), position(j)))
                    .collect()
            })
            .collect();
        let distance_rows = if nodes.len() <= MAX_CACHED_DISTANCE_NODES {
            (0..nodes.len()).map(|_| OnceLock::new()).collect()
        } else {
            Vec::new()
        };
        Ok(SkywayGraph {
            graph,
            nodes,
            edges,
            index,
            component,
            distance_rows,
            adjacency,
            headings_deg,
        })
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// Index of the node with this id, `None` if there is none.
    pub fn index_of(&self, id: &str) -> Option<usize> {
        self.index.get(id).copied()
    }

    /// Id of node `i`. Panics if `i >= node_count()` (a programming error, not bad input).
    pub fn id_of(&self, i: usize) -> &str {
        &self.nodes[i].id
    }

    /// Number of recharging pads at node `i` (`k` in the node-time model).
    pub fn pads(&self, i: usize) -> u32 {
        self.nodes[i].pads
    }

    /// Pad charge rate at node `i`: the node's own rate if the file gives one, else `default`
    /// (the profile's rate).
    pub fn pad_rate_mah_per_min(&self, i: usize, default: f64) -> f64 {
        self.nodes[i].pad_rate_mah_per_min.unwrap_or(default)
    }

    /// Position of node `i`: (easting, northing) in metres.
    pub fn position_m(&self, i: usize) -> (f64, f64) {
        (self.nodes[i].x_m, self.nodes[i].y_m)
    }

    /// Edge `e` (file order). Panics if `e >= edge_count()`.
    pub fn edge(&self, e: usize) -> &SkywayEdge {
        &self.edges[e]
    }

    /// Every edge in file order.
    pub fn edges(&self) -> &[SkywayEdge] {
        &self.edges
    }

    /// Index of the edge joining `a` and `b` (either direction), `None` if they are not adjacent.
    ///
    /// # Complexity
    /// O(log d) for degree d.
    pub fn edge_between(&self, a: usize, b: usize) -> Option<usize> {
        self.neighbor_position(a, b).map(|j| self.adjacency[a][j].1)
    }

    /// Position of `b` in the neighbour list of `a`, `None` if either is out of range or they
    /// are not adjacent.
    fn neighbor_position(&self, a: usize, b: usize) -> Option<usize> {
        if a >= self.nodes.len() || b >= self.nodes.len() {
            return None;
        }
        self.adjacency[a]
            .binary_search_by(|&(other, _)| other.cmp(&b))
            .ok()
    }

    /// The edge joining `from` and `to` and the direction flown from `from` to `to` (degrees
    /// clockwise from north in `[0, 360)`, computed once when the graph is built), `None` if
    /// they are not adjacent.
    ///
    /// # Complexity
    /// O(log d) for degree d.
    pub fn edge_and_heading(&self, from: usize, to: usize) -> Option<(usize, f64)> {
        self.neighbor_position(from, to)
            .map(|j| (self.adjacency[from][j].1, self.headings_deg[from][j]))
    }

    /// Neighbours of node `i` with the joining edge, as `(neighbour, edge)` pairs sorted by
    /// neighbour index.
    ///
    /// # Complexity
    /// O(1): the lists are built once with the graph.
    pub fn neighbors(&self, i: usize) -> &[(usize, usize)] {
        &self.adjacency[i]
    }

    /// The slot that keeps the shortest-path distances from node `i` once computed; `None` for
    /// a graph too large to keep them.
    pub(crate) fn distance_row(&self, i: usize) -> Option<&OnceLock<Vec<f64>>> {
        self.distance_rows.get(i)
    }

    /// Number of edges at node `i`.
    pub fn degree(&self, i: usize) -> usize {
        self.adjacency[i].len()
    }

    /// Whether some chain of edges joins `a` and `b` (a node is connected to itself).
    ///
    /// # Complexity
    /// O(1): connected components are labelled once when the graph is built.
    pub fn is_connected(&self, a: usize, b: usize) -> bool {
        a < self.component.len()
            && b < self.component.len()
            && self.component[a] == self.component[b]
    }

    /// Whether every node can reach every other node.
    pub fn is_fully_connected(&self) -> bool {
        self.component.iter().all(|&c| c == self.component[0])
    }

    /// The underlying petgraph graph: node `i` is `NodeIndex::new(i)`, the edge weight is the edge
    /// index.
    pub fn graph(&self) -> &UnGraph<(), usize> {
        &self.graph
    }
}
