//! Network rules (E1xxx), one function per rule code; the table of codes is in [`super`].

use crate::error::{show, Violation};
use crate::problem::{Edge, Network, Node};
use std::collections::HashMap;

/// Safe-flight wind limit (m/s): an edge's wind speed must be strictly below it.
pub const MAX_WIND_SPEED_MPS: f64 = 13.8;
/// Largest coordinate magnitude, m (E1106): 10,000 km from the frame's origin, a quarter of the
/// Earth's circumference, holds any city's skyway network; differences stay finite.
pub const MAX_COORDINATE_M: f64 = 1e7;
/// Longest edge, m (E1208): 1,000 km, far beyond any drone's range (the paper's flies about 11.5
/// km on a battery), so that a travel time stays at most 6e4 min at the slowest 1 km/h.
pub const MAX_EDGE_M: f64 = 1e6;
/// Slowest pad charge rate, mAh/min (E1107, and `pads.charge_rate_mah_per_min` of a profile): a
/// full 4480 mAh charge in 31 days; slower is not a charger.
pub const MIN_PAD_RATE_MAH_PER_MIN: f64 = 0.1;
/// Fastest pad charge rate, mAh/min (E1107): a full charge of the largest battery allowed (1e6
/// mAh) in a minute.
pub const MAX_PAD_RATE_MAH_PER_MIN: f64 = 1e6;
/// Most pads at one node (E1108): more pads than drones change nothing (a swarm has at most 64
/// drones), and a rooftop holds far fewer than 1,000.
pub const MAX_PADS: u32 = 1_000;

/// Checks every network rule (E1xxx) and returns every violation found, in file order.
///
/// # Arguments
/// * `n` - the network as read from its file.
///
/// # Returns
/// All violations; empty when the network is valid.
///
/// # Complexity
/// O(V + E) expected time (hash maps of ids and node pairs).
pub fn validate_network(n: &Network) -> Vec<Violation> {
    let mut out = Vec::new();
    e1001_schema_version(n, &mut out);
    e1002_has_nodes(n, &mut out);
    let ids = NodeIds::of(n);
    for (i, node) in n.nodes.iter().enumerate() {
        e1101_node_id_not_empty(i, node, &mut out);
        e1102_node_id_unique(i, node, &ids, &mut out);
        for (name, v) in [("x_m", node.x_m), ("y_m", node.y_m)] {
            e1103_coordinate_finite(i, name, v, &mut out);
            e1106_coordinate_in_range(i, name, v, &mut out);
        }
        e1104_pad_rate_positive(i, node, &mut out);
        e1107_pad_rate_in_range(i, node, &mut out);
        e1108_pads_at_most_max(i, node, &mut out);
    }
    e1105_some_node_has_pads(n, &mut out);
    let pairs = first_edge_of_pairs(n);
    for (j, edge) in n.edges.iter().enumerate() {
        e1201_edge_ends_exist(j, edge, &ids, &mut out);
        e1202_no_self_loop(j, edge, &mut out);
        e1203_one_edge_per_pair(j, edge, &pairs, &mut out);
        let length = EdgeLength::of(edge, &ids);
        e1204_length_positive(j, edge, length, &mut out);
        e1208_length_at_most_max(j, edge, length, &mut out);
        e1205_wind_speed_not_negative(j, edge, &mut out);
        e1206_wind_speed_below_limit(j, edge, &mut out);
        e1207_wind_direction_in_range(j, edge, &mut out);
    }
    out
}

/// Every non-empty node id with the index and position of the first node that has it.
struct NodeIds<'a>(HashMap<&'a str, (usize, (f64, f64))>);

impl<'a> NodeIds<'a> {
    fn of(n: &'a Network) -> Self {
        let mut ids = HashMap::new();
        for (i, node) in n.nodes.iter().enumerate() {
            if !node.id.trim().is_empty() {
                ids.entry(node.id.as_str())
                    .or_insert((i, (node.x_m, node.y_m)));
            }
        }
        NodeIds(ids)
    }

    /// Position of the first node with this id.
    fn position(&self, id: &str) -> Option<(f64, f64)> {
        self.0.get(id).map(|&(_, position)| position)
    }
}

/// The pair of node ids an edge joins, in sorted order (edges are flown both ways).
fn pair(edge: &Edge) -> (&str, &str) {
    if edge.from <= edge.to {
        (edge.from.as_str(), edge.to.as_str())
    } else {
        (edge.to.as_str(), edge.from.as_str())
    }
}

/// The index of the first edge joining each pair of distinct node ids.
fn first_edge_of_pairs(n: &Network) -> HashMap<(&str, &str), usize> {
    let mut pairs = HashMap::new();
    for (j, edge) in n.edges.iter().enumerate() {
        if edge.from != edge.to {
            pairs.entry(pair(edge)).or_insert(j);
        }
    }
    pairs
}

/// The length an edge is flown at, and where it comes from.
#[derive(Debug, Clone, Copy)]
enum EdgeLength {
    /// `distance_m` as given.
    Given(f64),
    /// `distance_m` absent: the Euclidean distance between two known, different ends.
    Euclidean(f64),
    /// `distance_m` absent and an end unknown, or the edge a self-loop (reported elsewhere).
    Unknown,
}

impl EdgeLength {
    fn of(edge: &Edge, ids: &NodeIds) -> Self {
        match edge.distance_m {
            Some(d) => EdgeLength::Given(d),
            None => match (ids.position(&edge.from), ids.position(&edge.to)) {
                (Some(a), Some(b)) if edge.from != edge.to => {
                    EdgeLength::Euclidean(euclidean_m(a, b))
                }
                _ => EdgeLength::Unknown,
            },
        }
    }
}

/// A length the models can fly: finite and above 0.
fn positive_length(d: f64) -> bool {
    d.is_finite() && d > 0.0
}

/// E1001: the file's schema version is the one this build reads.
fn e1001_schema_version(n: &Network, out: &mut Vec<Violation>) {
    super::json_schema_version("E1001", n.schema_version, out);
}

/// E1002: the network has at least one node.
fn e1002_has_nodes(n: &Network, out: &mut Vec<Violation>) {
    if n.nodes.is_empty() {
        out.push(Violation::new(
            "E1002",
            "nodes",
            "the network has no nodes",
            "list at least two rooftop nodes",
        ));
    }
}

/// E1101: a node id is not empty.
fn e1101_node_id_not_empty(i: usize, node: &Node, out: &mut Vec<Violation>) {
    if node.id.trim().is_empty() {
        out.push(Violation::new(
            "E1101",
            format!("nodes[{i}].id"),
            "the node id is empty",
            "give every node a non-empty unique id",
        ));
    }
}

/// E1102: no earlier node has the same (non-empty) id.
fn e1102_node_id_unique(i: usize, node: &Node, ids: &NodeIds, out: &mut Vec<Violation>) {
    if matches!(ids.0.get(node.id.as_str()), Some(&(first, _)) if first != i) {
        out.push(Violation::new(
            "E1102",
            format!("nodes[{i}].id"),
            format!("node id '{}' is used by an earlier node", node.id),
            "rename one of the nodes so that ids are unique",
        ));
    }
}

/// E1103: a coordinate is finite.
fn e1103_coordinate_finite(i: usize, name: &str, v: f64, out: &mut Vec<Violation>) {
    if !v.is_finite() {
        out.push(Violation::new(
            "E1103",
            format!("nodes[{i}].{name}"),
            format!("coordinate is {}", show(v)),
            "give a finite coordinate in metres",
        ));
    }
}

/// E1106: a finite coordinate is within ±[`MAX_COORDINATE_M`].
fn e1106_coordinate_in_range(i: usize, name: &str, v: f64, out: &mut Vec<Violation>) {
    if v.is_finite() && v.abs() > MAX_COORDINATE_M {
        out.push(Violation::new(
            "E1106",
            format!("nodes[{i}].{name}"),
            format!(
                "coordinate {} m is outside the stated range [-1e7, 1e7] m",
                show(v)
            ),
            "move the frame's origin near the network (coordinates within ±1e7 m)",
        ));
    }
}

/// A pad charge rate the models can use: finite and above 0.
fn positive_rate(rate: f64) -> bool {
    rate.is_finite() && rate > 0.0
}

/// E1104: a node's own pad charge rate, when given, is finite and above 0.
fn e1104_pad_rate_positive(i: usize, node: &Node, out: &mut Vec<Violation>) {
    match node.pad_charge_rate_mah_per_min {
        Some(rate) if !positive_rate(rate) => out.push(Violation::new(
            "E1104",
            format!("nodes[{i}].pad_charge_rate_mah_per_min"),
            format!("pad charge rate is {}", show(rate)),
            "give a finite rate above 0 mAh/min, or omit it to use the profile's rate",
        )),
        _ => {}
    }
}

/// E1107: a positive pad charge rate is within [[`MIN_PAD_RATE_MAH_PER_MIN`],
/// [`MAX_PAD_RATE_MAH_PER_MIN`]].
fn e1107_pad_rate_in_range(i: usize, node: &Node, out: &mut Vec<Violation>) {
    match node.pad_charge_rate_mah_per_min {
        Some(rate)
            if positive_rate(rate)
                && !(MIN_PAD_RATE_MAH_PER_MIN..=MAX_PAD_RATE_MAH_PER_MIN).contains(&rate) =>
        {
            out.push(Violation::new(
                "E1107",
                format!("nodes[{i}].pad_charge_rate_mah_per_min"),
                format!(
                    "pad charge rate {} mAh/min is outside the stated range [0.1, 1e6] mAh/min",
                    show(rate)
                ),
                "give a rate within [0.1, 1e6] mAh/min, or omit it to use the profile's rate",
            ));
        }
        _ => {}
    }
}

/// E1108: a node has at most [`MAX_PADS`] pads.
fn e1108_pads_at_most_max(i: usize, node: &Node, out: &mut Vec<Violation>) {
    if node.pads > MAX_PADS {
        out.push(Violation::new(
            "E1108",
            format!("nodes[{i}].pads"),
            format!(
                "{} pads, more than the stated maximum {MAX_PADS}",
                node.pads
            ),
            "give at most 1000 pads (more pads than drones in a swarm change nothing)",
        ));
    }
}

/// E1105: at least one node has pads.
fn e1105_some_node_has_pads(n: &Network, out: &mut Vec<Violation>) {
    if !n.nodes.is_empty() && n.nodes.iter().all(|node| node.pads == 0) {
        out.push(Violation::new(
            "E1105",
            "nodes",
            "no node has recharging pads",
            "give at least one node pads >= 1 so that drones can recharge",
        ));
    }
}

/// E1201: both ends of an edge name a node.
fn e1201_edge_ends_exist(j: usize, edge: &Edge, ids: &NodeIds, out: &mut Vec<Violation>) {
    for (name, id) in [("from", &edge.from), ("to", &edge.to)] {
        if ids.position(id).is_none() {
            out.push(Violation::new(
                "E1201",
                format!("edges[{j}].{name}"),
                format!("node id '{id}' is not in nodes"),
                "use the id of a listed node, or add the node",
            ));
        }
    }
}

/// E1202: an edge joins two different nodes.
fn e1202_no_self_loop(j: usize, edge: &Edge, out: &mut Vec<Violation>) {
    if edge.from == edge.to {
        out.push(Violation::new(
            "E1202",
            format!("edges[{j}]"),
            format!("edge joins node '{}' to itself", edge.from),
            "remove the edge; an edge joins two different nodes",
        ));
    }
}

/// E1203: no earlier edge joins the same two nodes, in either direction.
fn e1203_one_edge_per_pair(
    j: usize,
    edge: &Edge,
    pairs: &HashMap<(&str, &str), usize>,
    out: &mut Vec<Violation>,
) {
    if edge.from == edge.to {
        return;
    }
    let key = pair(edge);
    if let Some(&first) = pairs.get(&key).filter(|&&first| first != j) {
        out.push(Violation::new(
            "E1203",
            format!("edges[{j}]"),
            format!(
                "edges[{first}] already joins '{}' and '{}' (edges are flown both ways)",
                key.0, key.1
            ),
            "keep one edge per pair of nodes",
        ));
    }
}

/// E1204: an edge's length, given or Euclidean, is finite and above 0.
fn e1204_length_positive(j: usize, edge: &Edge, length: EdgeLength, out: &mut Vec<Violation>) {
    match length {
        EdgeLength::Given(d) if !positive_length(d) => out.push(Violation::new(
            "E1204",
            format!("edges[{j}].distance_m"),
            format!("distance is {}", show(d)),
            "give a finite distance above 0 m, or omit it to use the Euclidean distance",
        )),
        EdgeLength::Euclidean(d) if !positive_length(d) => out.push(Violation::new(
            "E1204",
            format!("edges[{j}].distance_m"),
            format!(
                "distance_m is absent and the Euclidean distance between '{}' and '{}' is {}",
                edge.from,
                edge.to,
                show(d)
            ),
            "give distance_m, or distinct finite coordinates to the two nodes",
        )),
        _ => {}
    }
}

/// E1208: a positive edge length, given or Euclidean, is at most [`MAX_EDGE_M`].
fn e1208_length_at_most_max(j: usize, edge: &Edge, length: EdgeLength, out: &mut Vec<Violation>) {
    let (d, what) = match length {
        EdgeLength::Given(d) => (d, "distance_m is".to_string()),
        EdgeLength::Euclidean(d) => (
            d,
            format!(
                "distance_m is absent and the Euclidean distance between '{}' and '{}' is",
                edge.from, edge.to
            ),
        ),
        EdgeLength::Unknown => return,
    };
    if positive_length(d) && d > MAX_EDGE_M {
        out.push(Violation::new(
            "E1208",
            format!("edges[{j}].distance_m"),
            format!(
                "{what} {} m, outside the stated range (0, 1e6] m",
                show(d)
            ),
            "split the edge at intermediate nodes, or check its length and the nodes' coordinates (metres)",
        ));
    }
}

/// E1205: an edge's wind speed is finite and at least 0.
fn e1205_wind_speed_not_negative(j: usize, edge: &Edge, out: &mut Vec<Violation>) {
    let w = edge.wind_speed_mps;
    if !(w.is_finite() && w >= 0.0) {
        out.push(Violation::new(
            "E1205",
            format!("edges[{j}].wind_speed_mps"),
            format!("wind speed is {}", show(w)),
            "give a finite wind speed of 0 m/s or more",
        ));
    }
}

/// E1206: a finite wind speed is below [`MAX_WIND_SPEED_MPS`].
fn e1206_wind_speed_below_limit(j: usize, edge: &Edge, out: &mut Vec<Violation>) {
    let w = edge.wind_speed_mps;
    if w.is_finite() && w >= MAX_WIND_SPEED_MPS {
        out.push(Violation::new(
            "E1206",
            format!("edges[{j}].wind_speed_mps"),
            format!(
                "wind speed {} m/s is at or over the safe-flight limit {MAX_WIND_SPEED_MPS} m/s",
                show(w)
            ),
            "drones cannot fly this edge: lower the wind speed below 13.8 m/s or remove the edge",
        ));
    }
}

/// E1207: an edge's wind direction is finite and within [0, 360] degrees.
fn e1207_wind_direction_in_range(j: usize, edge: &Edge, out: &mut Vec<Violation>) {
    let dir = edge.wind_from_deg;
    if !(dir.is_finite() && (0.0..=360.0).contains(&dir)) {
        out.push(Violation::new(
            "E1207",
            format!("edges[{j}].wind_from_deg"),
            format!("wind direction is {}", show(dir)),
            "give the direction the wind blows from in degrees clockwise from north, within [0, 360]",
        ));
    }
}

/// Euclidean distance in metres between two positions.
pub(crate) fn euclidean_m(a: (f64, f64), b: (f64, f64)) -> f64 {
    (b.0 - a.0).hypot(b.1 - a.1)
}
